#!/usr/bin/env python3
"""pair_builds.py: two soc_sim builds timed against each other, in pairs.

Runs the same soc_sim command with an old and a new build, whole processes
one after the other, N pairs, the order rotating (old first in even pairs,
new first in odd ones), and prints each side's CPU time (user + system of
the process, from the kernel's accounting of the child) as min and median,
the ratio of the mins, the ratio of the medians and the median of the
ratios within each pair (new / old: below 1, the new build is faster).
This is how docs/performance.md's "whole processes of the two builds
alternating, N pairs" figures are taken; on a shared machine, where a
neighbour's load comes and goes, the median of the pairs is the figure to
trust, and pairs taken while something else runs (a CI, a build) are not.

  pair_builds.py --pairs 11 OLD_SOC_SIM NEW_SOC_SIM -- --app teapot --backend ap-tile \\
      --set display.width=192 --set display.height=144 --frames 40 --no-frames

Each run gets its own output folder (--out, removed after it), --force and
--quiet after the arguments given. --json prints the figures as one JSON
object instead. Exit status 0; 2 with a message on bad arguments or a run
that fails (naming the build, its exit status and the end of its stderr).
"""

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile


class RunFailed(Exception):
    pass


def cpu_seconds_of_child(command):
    """Runs `command`; its user + system CPU time in seconds."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    completed = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, check=False)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if completed.returncode != 0:
        tail = "\n".join(completed.stderr.strip().splitlines()[-5:])
        raise RunFailed(f"{command[0]} exited with status {completed.returncode}" + (f": {tail}" if tail else ""))
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def order_of_pair(index):
    """The sides of pair `index` in the order they run: old first in even pairs."""
    return ("old", "new") if index % 2 == 0 else ("new", "old")


def summary(old_seconds, new_seconds):
    """The figures of paired times (lists of equal, non-zero length; positive times)."""
    if len(old_seconds) != len(new_seconds) or not old_seconds:
        raise ValueError("summary: needs as many new times as old ones, at least one")
    if min(old_seconds) <= 0 or min(new_seconds) <= 0:
        raise ValueError("summary: a run took no CPU time (too short to time: give it more frames)")
    ratios = [new / old for old, new in zip(old_seconds, new_seconds)]
    return {
        "pairs": len(old_seconds),
        "old_min_s": min(old_seconds),
        "old_median_s": statistics.median(old_seconds),
        "new_min_s": min(new_seconds),
        "new_median_s": statistics.median(new_seconds),
        "ratio_of_mins": min(new_seconds) / min(old_seconds),
        "ratio_of_medians": statistics.median(new_seconds) / statistics.median(old_seconds),
        "median_of_pair_ratios": statistics.median(ratios),
    }


def text_of(figures):
    return (
        f"old {figures['old_min_s']:.3f} s / {figures['old_median_s']:.3f} s, "
        f"new {figures['new_min_s']:.3f} s / {figures['new_median_s']:.3f} s (min / median CPU time); "
        f"new / old: {figures['ratio_of_mins']:.3f} of the mins, {figures['ratio_of_medians']:.3f} of the medians, "
        f"{figures['median_of_pair_ratios']:.3f} the median of the pairs ({figures['pairs']} pairs)"
    )


def run_pairs(builds, arguments, pairs, run=cpu_seconds_of_child):
    """Times `pairs` pairs; builds: {"old": path, "new": path}. Returns (old times, new times)."""
    times = {"old": [], "new": []}
    for index in range(pairs):
        for side in order_of_pair(index):
            out = tempfile.mkdtemp(prefix="pair_builds_")
            try:
                command = [builds[side], *arguments, "--out", out, "--force", "--quiet"]
                try:
                    times[side].append(run(command))
                except RunFailed as failure:
                    raise RunFailed(f"the {side} build, pair {index + 1}: {failure}") from None
            finally:
                shutil.rmtree(out, ignore_errors=True)
    return times["old"], times["new"]


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old", help="the old build's soc_sim")
    parser.add_argument("new", help="the new build's soc_sim")
    parser.add_argument("arguments", nargs="*", help="soc_sim's arguments (after --)")
    parser.add_argument("--pairs", type=int, default=11, help="pairs of runs (default 11)")
    parser.add_argument("--json", action="store_true", help="print the figures as one JSON object")
    options = parser.parse_args(argv)
    if options.pairs < 1:
        parser.error(f"--pairs {options.pairs}: at least one pair")
    builds = {"old": options.old, "new": options.new}
    for side, path in builds.items():
        if not (os.path.isfile(path) and os.access(path, os.X_OK)):
            parser.error(f"the {side} build {path!r} is not an executable file")
    try:
        old_seconds, new_seconds = run_pairs(builds, options.arguments, options.pairs)
        figures = summary(old_seconds, new_seconds)
    except (RunFailed, ValueError) as error:
        print(f"pair_builds.py: {error}", file=sys.stderr)
        return 2
    print(json.dumps(figures) if options.json else text_of(figures))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
