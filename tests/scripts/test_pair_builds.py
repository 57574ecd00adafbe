"""Tests of scripts/pair_builds.py (docs/performance.md's paired builds).

    test_pair_builds.py --work DIR

The figures of paired times against values worked out by hand; the order of
the runs (old first in even pairs, new first in odd ones) and the arguments
each gets; and the script run on two stand-in builds (shell scripts that
spend a little CPU time and log their arguments): its output with --json,
the arguments passed on, and its messages and exit statuses for a build that
fails, a path that is not an executable and --pairs 0. No soc_sim, and no
figure that depends on how fast the machine is.

Exit status 0 when every check passes; 1, with each failure printed.
"""

import argparse
import json
import pathlib
import stat
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
SCRIPT = ROOT / "scripts" / "pair_builds.py"
sys.path.insert(0, str(SCRIPT.parent))
import pair_builds  # noqa: E402

FAILURES = []


def check(condition, message):
    if not condition:
        FAILURES.append(message)


def close(a, b):
    return abs(a - b) < 1e-12


def test_summary():
    # old 2, 4, 3 s; new 1, 4, 6 s: mins 2 and 1, medians 3 and 4, the
    # pairs' ratios 0.5, 1 and 2 (median 1, mean 7/6).
    figures = pair_builds.summary([2.0, 4.0, 3.0], [1.0, 4.0, 6.0])
    check(figures["pairs"] == 3, f"summary: pairs {figures['pairs']}, expected 3")
    check(close(figures["ratio_of_mins"], 0.5), f"summary: ratio of mins {figures['ratio_of_mins']}, expected 0.5")
    check(close(figures["ratio_of_medians"], 4 / 3), f"summary: ratio of medians {figures['ratio_of_medians']}")
    check(close(figures["median_of_pair_ratios"], 1.0), f"summary: median of pairs {figures['median_of_pair_ratios']}")
    check(close(figures["old_median_s"], 3.0) and close(figures["new_min_s"], 1.0), f"summary: {figures}")
    # An even count: the median of the ratios 2 and 0.5 is their mean, 1.25.
    figures = pair_builds.summary([1.0, 2.0], [2.0, 1.0])
    check(close(figures["median_of_pair_ratios"], 1.25), f"summary: median of two pairs {figures}")
    text = pair_builds.text_of(pair_builds.summary([2.0, 4.0, 3.0], [1.0, 4.0, 6.0]))
    check("0.500 of the mins" in text and "1.000 the median of the pairs (3 pairs)" in text, f"text_of: {text}")
    for old, new, what in (([1.0], [1.0, 2.0], "unequal lengths"), ([], [], "no pairs"), ([0.0], [1.0], "no time")):
        try:
            pair_builds.summary(old, new)
            FAILURES.append(f"summary accepted {what}")
        except ValueError:
            pass


def test_order_and_arguments():
    check(
        [pair_builds.order_of_pair(i) for i in range(3)] == [("old", "new"), ("new", "old"), ("old", "new")],
        "order_of_pair: expected old first in even pairs",
    )
    commands = []

    def fake_run(command):
        commands.append(command)
        return 1.0 if command[0] == "OLD" else 0.5

    old, new = pair_builds.run_pairs({"old": "OLD", "new": "NEW"}, ["--app", "teapot"], 3, run=fake_run)
    check([c[0] for c in commands] == ["OLD", "NEW", "NEW", "OLD", "OLD", "NEW"], f"run order {commands}")
    check(old == [1.0] * 3 and new == [0.5] * 3, f"run_pairs times {old} {new}")
    for command in commands:
        check(
            command[1:3] == ["--app", "teapot"] and command[3] == "--out" and command[5:] == ["--force", "--quiet"],
            f"run_pairs command {command}",
        )
        check(not pathlib.Path(command[4]).exists(), f"run_pairs left its output folder {command[4]}")
    check(len({c[4] for c in commands}) == 6, "run_pairs: each run its own output folder")


def stand_in(path, log, status=0):
    """A build that spends a little CPU time, logs its arguments and exits with `status`."""
    path.write_text(
        "#!/bin/sh\n"
        f'echo "$@" >> {log}\n'
        "i=0\nwhile [ $i -lt 30000 ]; do i=$((i+1)); done\n"
        + ('echo "the stand-in fails" >&2\n' if status else "")
        + f"exit {status}\n"
    )
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path


def script(*arguments):
    return subprocess.run([sys.executable, str(SCRIPT), *arguments], capture_output=True, text=True, check=False)


def test_script(work):
    log = work / "arguments.log"
    old = stand_in(work / "old_soc_sim", log)
    new = stand_in(work / "new_soc_sim", log)
    run = script("--pairs", "2", "--json", str(old), str(new), "--", "--app", "triangle", "--frames", "2")
    check(run.returncode == 0, f"script on two stand-ins: status {run.returncode}, {run.stderr}")
    if run.returncode == 0:
        figures = json.loads(run.stdout)
        check(figures["pairs"] == 2 and figures["old_min_s"] > 0 and figures["new_min_s"] > 0, f"script: {figures}")
    lines = log.read_text().splitlines() if log.exists() else []
    check(len(lines) == 4, f"script: {len(lines)} runs logged, expected 4")
    check(all(line.startswith("--app triangle --frames 2 --out ") for line in lines), f"script arguments: {lines}")
    check(all(line.endswith(" --force --quiet") for line in lines), f"script arguments: {lines}")

    failing = stand_in(work / "failing_soc_sim", work / "failing.log", status=3)
    run = script("--pairs", "1", str(failing), str(new))
    check(run.returncode == 2, f"a failing build: status {run.returncode}, expected 2")
    check(
        "the old build, pair 1" in run.stderr and "status 3" in run.stderr and "the stand-in fails" in run.stderr,
        f"a failing build's message: {run.stderr!r}",
    )

    run = script(str(work / "no_such_soc_sim"), str(new))
    check(run.returncode == 2 and "is not an executable file" in run.stderr, f"a missing build: {run.stderr!r}")
    run = script("--pairs", "0", str(old), str(new))
    check(run.returncode == 2 and "at least one pair" in run.stderr, f"--pairs 0: {run.stderr!r}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--work", required=True, type=pathlib.Path)
    options = parser.parse_args()
    options.work.mkdir(parents=True, exist_ok=True)
    for stale in options.work.glob("*"):
        stale.unlink()
    test_summary()
    test_order_and_arguments()
    test_script(options.work)
    for failure in FAILURES:
        print("FAIL:", failure)
    print(f"test_pair_builds: {len(FAILURES)} failures")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
