#!/usr/bin/env python3
"""same_run.py DIR_A DIR_B: two soc_sim runs are the same run: every frame
file byte for byte, and stats.json equal in everything but the command line
that started it (the one thing two spellings of the same configuration
change). Exits 1, naming the first difference, otherwise."""

import json
import pathlib
import sys


def main() -> int:
    a, b = (pathlib.Path(p) for p in sys.argv[1:3])
    frames_a = sorted(p.name for p in a.glob("frame_*.png"))
    frames_b = sorted(p.name for p in b.glob("frame_*.png"))
    if not frames_a or frames_a != frames_b:
        print(f"same_run: frames differ: {frames_a} in {a}, {frames_b} in {b}", file=sys.stderr)
        return 1
    for name in frames_a:
        if (a / name).read_bytes() != (b / name).read_bytes():
            print(f"same_run: {name} differs", file=sys.stderr)
            return 1
    stats_a = json.loads((a / "stats.json").read_text())
    stats_b = json.loads((b / "stats.json").read_text())
    for stats in (stats_a, stats_b):
        stats.pop("command_line", None)
    if stats_a != stats_b:
        keys = sorted(k for k in set(stats_a) | set(stats_b) if stats_a.get(k) != stats_b.get(k))
        print(f"same_run: stats.json differs in {keys}", file=sys.stderr)
        return 1
    print(f"same_run: {len(frames_a)} frame(s) and stats.json equal")
    return 0


if __name__ == "__main__":
    sys.exit(main())
