#!/usr/bin/env python3
"""Checks stats.json's region of interest of a run whose application marked
frames FIRST to LAST - 1 (examples/mine --roi FIRST:LAST: begun before frame
FIRST's drawing, ended before frame LAST's), against the run's own frame
records, which the recorder takes by another path (at each frame's request).

    check_roi.py STATS_JSON FIRST LAST

Exits 0 and prints a line of figures when every check holds, 1 naming the
first that fails.
"""

from __future__ import annotations

import json
import math
import sys


def numbers(value, path=()):
    """Every number under a JSON object with its dotted path (lists left out)."""
    if isinstance(value, dict):
        for key, item in value.items():
            yield from numbers(item, (*path, key))
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        yield ".".join(path), value


def at(document, dotted):
    for part in dotted.split("."):
        document = document[part]
    return document


def check(stats, first, last):
    roi = stats.get("roi")
    if roi is None:
        return "stats.json has no roi"
    frames = stats["frames"]
    if roi["regions"] != 1:
        return f"roi.regions is {roi['regions']}, not 1"
    if roi["frames"] != list(range(first, last)):
        return f"roi.frames is {roi['frames']}, not {list(range(first, last))}"
    begin, end = roi["begin_ns"], roi["end_ns"]
    # The region begins after frame FIRST - 1's eglSwapBuffers and before
    # frame FIRST's; it ends after frame LAST - 1's and before frame LAST's.
    if not frames[first - 1]["requested_ns"] <= begin <= frames[first]["requested_ns"]:
        return f"roi.begin_ns {begin} is not between frames {first - 1} and {first}'s requests"
    if not frames[last - 1]["requested_ns"] <= end <= frames[last]["requested_ns"]:
        return f"roi.end_ns {end} is not between frames {last - 1} and {last}'s requests"
    if not math.isclose(roi["simulated_ns"], end - begin, rel_tol=1e-9):
        return f"roi.simulated_ns {roi['simulated_ns']} is not end_ns - begin_ns {end - begin}"
    # The host's busy time in the region is that of frames FIRST..LAST-1
    # (each from the request before to its own) but for the few cycles of
    # eglSwapBuffers after each edge's request.
    busy = sum(frames[k]["host_busy_ns"] for k in range(first, last))
    if not math.isclose(roi["host"]["busy_ns"], busy, rel_tol=0.02):
        return f"roi.host.busy_ns {roi['host']['busy_ns']} is not the frames' host_busy_ns {busy} (2 %)"
    # Every statistic of the region is a part of the run's: none negative,
    # none above its total (the region is a stretch of the run).
    grown = 0
    for key, value in numbers(roi):
        if key in ("regions", "begin_ns", "end_ns"):
            continue
        total = at(stats, key)
        # Each edge is read at the register's access, every block but the
        # host as the kernel has it then, at most a quantum behind (1 us by
        # default), and the host's idle time is the time its busy and stalled
        # time leave, never below 0: a statistic may be off by a quantum's
        # worth at each edge (1,000 ns or cycles at a clock up to 1 GHz; in
        # joules, a quantum at the run's average power, ten times over).
        if key.endswith("_j"):
            slack = 2e-5 * stats["energy"]["average_w"]
        else:
            slack = 2000.0
        if value < -slack or value > total + slack:
            return f"roi.{key} is {value}, outside 0 .. the run's {total}"
        grown += value > 0
    if grown < 10:
        return f"only {grown} statistics grew in the region"
    return (
        f"roi: {begin:.0f} .. {end:.0f} ns, frames {roi['frames']}, host busy {roi['host']['busy_ns']:.0f} ns "
        f"(frames' {busy:.0f}), energy {roi['energy']['total_j']:.3e} J of {stats['energy']['total_j']:.3e}, "
        f"{grown} statistics grew"
    )


def main() -> int:
    if len(sys.argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    with open(sys.argv[1], encoding="utf-8") as file:
        stats = json.load(file)["stats"]
    result = check(stats, int(sys.argv[2]), int(sys.argv[3]))
    print(result)
    return 0 if result.startswith("roi: ") else 1


if __name__ == "__main__":
    sys.exit(main())
