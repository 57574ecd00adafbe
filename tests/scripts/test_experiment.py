"""Tests of scripts/experiment.py (docs/experiments.md).

    test_experiment.py run NAME --soc-sim SOC_SIM --work DIR
        runs the experiment NAME with one frame per run and checks what it
        writes: the table printed with the experiment's headers, the CSV with
        its column keys and one row per run, every figure a positive number
        (empty only where the column names back ends that exclude the run's),
        the Markdown table and a PNG. It never checks a figure's value: none
        is known in advance.

    test_experiment.py errors --soc-sim SOC_SIM --work DIR
        the script's messages and exit statuses for --list, an unknown
        experiment, a missing soc_sim, a malformed experiment file and a
        soc_sim run that fails.

Exit status 0 when every check passes; 1, with each failure printed, when
one does not.
"""

import argparse
import csv
import json
import math
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
SCRIPT = ROOT / "scripts" / "experiment.py"
EXPERIMENTS = ROOT / "configs" / "experiments"

FAILURES = []


def check(condition, message):
    if not condition:
        FAILURES.append(message)
    return condition


def run_script(*args):
    done = subprocess.run([str(SCRIPT), *map(str, args)], capture_output=True, text=True, check=False)
    return done.returncode, done.stdout, done.stderr


def describe(status, out, err):
    return f"exit status {status}\n--- stdout ---\n{out}--- stderr ---\n{err}"


def positive_number(text):
    """A number above 0; "inf" counts (patch_break_even: no size at which the other run is slower), NaN does not."""
    try:
        value = float(text.replace(",", ""))
    except ValueError:
        return False
    return not math.isnan(value) and value > 0


def test_run(name, soc_sim, work):
    spec = json.loads((EXPERIMENTS / f"{name}.json").read_text())
    out = work / name
    shutil.rmtree(out, ignore_errors=True)
    status, stdout, stderr = run_script(name, "--frames", "1", "--soc-sim", soc_sim, "--out", out, "--quiet")
    if not check(status == 0, f"{name}: the experiment failed\n" + describe(status, stdout, stderr)):
        return

    columns = spec["columns"]
    runs = spec["runs"]
    headers = [spec.get("label_header", "run")] + [column.get("header", column["key"]) for column in columns]
    header_line = "| " + " | ".join(headers) + " |"
    check(header_line in stdout.splitlines(), f"{name}: the printed table lacks the line {header_line}\n{stdout}")
    markdown = out / f"{name}.md"
    check(markdown.is_file() and header_line in markdown.read_text(), f"{name}: {markdown} lacks the table")

    png = out / f"{name}.png"
    check(png.is_file() and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", f"{name}: {png} is not a PNG file")

    csv_path = out / f"{name}.csv"
    if not check(csv_path.is_file(), f"{name}: {csv_path} is missing"):
        return
    with csv_path.open(newline="") as file:
        rows = list(csv.reader(file))
    keys = ["run"] + [column["key"] for column in columns]
    check(rows and rows[0] == keys, f"{name}: CSV header {rows[0] if rows else None}, expected {keys}")
    check([row[0] for row in rows[1:]] == [run["label"] for run in runs],
          f"{name}: CSV rows {[row[0] for row in rows[1:]]}, expected the runs {[run['label'] for run in runs]}")
    for row, run in zip(rows[1:], runs):
        for column, cell in zip(columns, row[1:]):
            applies = run["backend"] in column.get("backends", [run["backend"]])
            where = f"{name}: run '{run['label']}', column '{column['key']}'"
            if applies:
                check(positive_number(cell), f"{where}: '{cell}' is not a positive number")
            else:
                check(cell == "", f"{where}: '{cell}' where the column does not apply to {run['backend']}")
    # The table shows the same runs, each figure or '-' where the CSV is empty.
    for row in rows[1:]:
        table_rows = [line for line in stdout.splitlines() if line.startswith(f"| {row[0]} |")]
        if check(len(table_rows) == 1, f"{name}: the printed table has no single row for '{row[0]}'"):
            cells = [cell.strip() for cell in table_rows[0].strip("|").split("|")][1:]
            check([cell == "-" for cell in cells] == [value == "" for value in row[1:]],
                  f"{name}: row '{row[0]}': the table's '-' cells differ from the CSV's empty ones")


def test_errors(soc_sim, work):
    names = sorted(path.stem for path in EXPERIMENTS.glob("*.json"))
    check(names, f"no experiment in {EXPERIMENTS}")

    status, out, err = run_script("--list")
    check(status == 0, "--list failed\n" + describe(status, out, err))
    listed = [line.split()[0] for line in out.splitlines() if line.strip()]
    check(listed == names, f"--list lists {listed}, the folder holds {names}")

    status, out, err = run_script("no_such_experiment", "--soc-sim", soc_sim, "--out", work / "unknown")
    check(status == 2 and "unknown experiment 'no_such_experiment'" in err and all(n in err for n in names),
          "an unknown experiment must be status 2 naming it and the known ones\n" + describe(status, out, err))

    missing = work / "no_such_soc_sim"
    status, out, err = run_script(names[0], "--soc-sim", missing, "--out", work / "missing")
    check(status == 2 and "soc_sim not found" in err and str(missing) in err,
          "a missing soc_sim must be status 2 naming the path\n" + describe(status, out, err))

    status, out, err = run_script()
    check(status == 2 and "name an experiment" in err, "no experiment must be status 2\n" + describe(status, out, err))

    work.mkdir(parents=True, exist_ok=True)
    malformed = work / "malformed.json"
    malformed.write_text(json.dumps({"title": "t", "runs": [{"label": "a", "backend": "arm", "app": "triangle",
                                                             "frame": 1}],
                                     "columns": [{"key": "frame_ms", "value": "frame_time_ms"}]}))
    status, out, err = run_script(malformed, "--soc-sim", soc_sim, "--out", work / "malformed")
    check(status == 2 and str(malformed) in err and "frame" in err and "runs[0]" in err,
          "a misspelt key must be status 2 naming the file, the run and the key\n" + describe(status, out, err))

    failing = work / "failing.json"
    failing.write_text(json.dumps({"title": "t", "runs": [{"label": "doomed", "backend": "arm",
                                                           "app": "no_such_app"}],
                                   "columns": [{"key": "frame_ms", "value": "frame_time_ms"}]}))
    status, out, err = run_script(failing, "--soc-sim", soc_sim, "--out", work / "failing")
    check(status == 1 and "run 'doomed' failed" in err and "exit status 2" in err and "no_such_app" in err,
          "a failing soc_sim run must be status 1 naming the run, soc_sim's status and its message\n"
          + describe(status, out, err))

    absent = work / "absent.json"
    absent.write_text(json.dumps({"title": "t", "runs": [{"label": "a", "backend": "arm", "app": "triangle"}],
                                  "columns": [{"key": "passes", "stat": "driver.ap_tile.passes"}]}))
    status, out, err = run_script(absent, "--soc-sim", soc_sim, "--out", work / "absent")
    check(status == 1 and "run 'a' has no statistic 'driver.ap_tile.passes'" in err,
          "a statistic a run lacks must be status 1 naming the run and the statistic\n" + describe(status, out, err))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", choices=("run", "errors"))
    parser.add_argument("name", nargs="?")
    parser.add_argument("--soc-sim", required=True)
    parser.add_argument("--work", required=True, type=pathlib.Path)
    args = parser.parse_args()
    if args.what == "run":
        if not args.name:
            parser.error("run needs an experiment's name")
        test_run(args.name, args.soc_sim, args.work)
    else:
        test_errors(args.soc_sim, args.work)
    for failure in FAILURES:
        print(f"FAIL: {failure}\n")
    print("FAILED" if FAILURES else "PASSED")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
