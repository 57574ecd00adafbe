"""Tests of scripts/experiment.py (docs/experiments.md).

    test_experiment.py run NAME --soc-sim SOC_SIM --work DIR
        runs the experiment NAME with one frame per run and checks what it
        writes: the table printed with the experiment's headers, the CSV with
        its column keys and one row per run, every figure a positive number
        (empty only where the column names back ends that exclude the run's or
        does not require its statistics; 0 only where it may be zero),
        the Markdown table and a PNG. It never checks a figure's value: none
        is known in advance.

    test_experiment.py hosts --soc-sim SOC_SIM --work DIR
        fullscreen_rect and tile_pass with --host both --program both: a row
        per host and program in both tables, the host and program columns,
        and the study's quantities against the whole frame's (the study's
        time and energy strictly less than the frame's; the ARM's clear time
        within its rasterization phase; the ISS and native rows of the
        array's passes agree, the array being the same).

    test_experiment.py errors --soc-sim SOC_SIM --work DIR
        the script's messages and exit statuses for --list, an unknown
        experiment, a missing soc_sim, a malformed experiment file and a
        soc_sim run that fails.

    test_experiment.py cluster --soc-sim SOC_SIM --work DIR
        the cluster's experiments cluster_soc and cluster_depth on a small
        scene: their tables printed and written, a row per machine, depth
        and node count, every time and energy a positive number.

    test_experiment.py matrix --work DIR
        the experiment file's "matrix" (runs x back ends x combinations of
        switches): the runs it expands to, their labels, settings and groups,
        and the loader's message for each mistake; the figures the what-if
        columns compute (host_time_ms, values_written_per_triangle, ...) and
        "required" and "per frame" on statistics written here. No soc_sim.

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
EXPERIMENTS = ROOT / "experiments"

# The script's loader and figures (python/tessera_sweep/experiment.py, which the script is an alias of;
# matplotlib is imported when it plots).
sys.path.insert(0, str(SCRIPT.parent))
import experiment  # noqa: E402

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


def non_negative_number(text):
    try:
        value = float(text.replace(",", ""))
    except ValueError:
        return False
    return not math.isnan(value) and value >= 0


def test_run(name, soc_sim, work, host="native"):
    # Loaded as the script loads it: a matrix's runs listed, the columns' defaults filled in, the runs on `host`
    # with each program the experiment lists.
    spec = experiment.load_experiment(EXPERIMENTS / f"{name}.yaml")
    runs = experiment.expand_runs(spec, [host])
    out = work / name
    shutil.rmtree(out, ignore_errors=True)
    status, stdout, stderr = run_script(
        name, "--frames", "1", "--soc-sim", soc_sim, "--out", out, "--quiet", "--host", host
    )
    if not check(status == 0, f"{name}: the experiment failed\n" + describe(status, stdout, stderr)):
        return
    check(f"[{name}] wall time: " in stderr, f"{name}: no wall time on standard error\n{stderr}")
    check_table(name, spec["label_header"], spec["columns"], runs, stdout, out / f"{name}.csv")
    check(
        "study" not in spec
        or check_table(name, spec["label_header"], spec["study"]["columns"], runs, stdout, out / f"{name}_study.csv"),
        f"{name}: the study's table",
    )
    markdown = out / f"{name}.md"
    check(
        markdown.is_file()
        and (spec["title"] in markdown.read_text())
        and ("study" not in spec or spec["study"]["title"] in markdown.read_text()),
        f"{name}: {markdown} lacks a table's title",
    )
    png = out / f"{name}.png"
    check(png.is_file() and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", f"{name}: {png} is not a PNG file")


def check_table(name, label_header, columns, runs, stdout, csv_path):
    """One table as printed and as its CSV: the headers (label, host, program, the columns), one row per run, every
    figure a positive number or empty where the column allows it. True when every check passed."""
    failures = len(FAILURES)
    columns = experiment.RUN_COLUMNS + columns
    headers = [label_header] + [column.get("header", column["key"]) for column in columns]
    header_line = "| " + " | ".join(headers) + " |"
    check(header_line in stdout.splitlines(), f"{name}: the printed table lacks the line {header_line}\n{stdout}")
    if not check(csv_path.is_file(), f"{name}: {csv_path} is missing"):
        return False
    with csv_path.open(newline="") as file:
        rows = list(csv.reader(file))
    keys = ["run"] + [column["key"] for column in columns]
    check(rows and rows[0] == keys, f"{name}: CSV header {rows[0] if rows else None}, expected {keys}")
    check(
        [row[0] for row in rows[1:]] == [run["label"] for run in runs],
        f"{name}: CSV rows {[row[0] for row in rows[1:]]}, expected the runs {[run['label'] for run in runs]}",
    )
    for row, run in zip(rows[1:], runs):
        check(
            row[1] == run["set"]["host.model"],
            f"{name}: run '{run['label']}': host '{row[1]}', expected {run['set']['host.model']}",
        )
        key = experiment.PROGRAM_KEYS.get(run["backend"]) if run.get("backend_program", True) else None
        check(
            row[2] == (run["set"].get(key, "tuned") if key else "-"),
            f"{name}: run '{run['label']}': program '{row[2]}'",
        )
        for column, cell in zip(columns[2:], row[3:]):
            applies = run["backend"] in column.get("backends", [run["backend"]])
            where = f"{name}: run '{run['label']}', column '{column['key']}'"
            if not applies:
                check(cell == "", f"{where}: '{cell}' where the column does not apply to {run['backend']}")
            elif cell == "":
                check(not column.get("required", True), f"{where}: empty, and the column requires its statistics")
            elif column.get("may_be_zero"):
                check(non_negative_number(cell), f"{where}: '{cell}' is not a number of 0 or more")
            else:
                check(positive_number(cell), f"{where}: '{cell}' is not a positive number")
    # The table shows the same runs, each figure or '-' where the CSV is empty.
    lines = stdout.splitlines()
    start = lines.index(header_line) if header_line in lines else 0
    for row in rows[1:]:
        table_rows = [line for line in lines[start : start + len(rows) + 2] if line.startswith(f"| {row[0]} |")]
        if check(len(table_rows) == 1, f"{name}: the printed table has no single row for '{row[0]}'"):
            cells = [cell.strip() for cell in table_rows[0].strip("|").split("|")][1:]
            check(
                cells[:2] == row[1:3] and [cell == "-" for cell in cells[2:]] == [value == "" for value in row[3:]],
                f"{name}: row '{row[0]}': the table's '-' cells differ from the CSV's empty ones",
            )
    return len(FAILURES) == failures


def read_csv(path):
    with path.open(newline="") as file:
        return {row["run"]: row for row in csv.DictReader(file)}


def test_hosts(soc_sim, work):
    """--host both --program both: every host and program in both tables, and the study's quantities set beside the
    whole frame's."""
    out = work / "hosts"
    shutil.rmtree(out, ignore_errors=True)
    status, stdout, stderr = run_script(
        "fullscreen_rect",
        "tile_pass",
        "--frames",
        "1",
        "--soc-sim",
        soc_sim,
        "--out",
        out,
        "--quiet",
        "--host",
        "both",
        "--program",
        "both",
    )
    if not check(status == 0, "hosts: the experiments failed\n" + describe(status, stdout, stderr)):
        return
    check(
        all(
            f"[{name}] wall time: " in stderr and "iss " in stderr and "native " in stderr
            for name in ("fullscreen_rect", "tile_pass")
        ),
        f"hosts: no wall time per host\n{stderr}",
    )
    whole = read_csv(out / "fullscreen_rect" / "fullscreen_rect.csv")
    study = read_csv(out / "fullscreen_rect" / "fullscreen_rect_study.csv")
    expected = [f"{label} {host}" for label in ("arm", "ap-tile study", "ap-tile tuned") for host in ("native", "iss")]
    for rows, what in ((whole, "whole-frame"), (study, "study's")):
        check(sorted(rows) == sorted(expected), f"hosts: the {what} table's rows {sorted(rows)}, expected {expected}")
    for label in expected:
        if label not in whole or label not in study:
            continue
        frame_ms, study_ms = float(whole[label]["frame_ms"]), float(study[label]["study_ms"])
        check(
            0 < study_ms < frame_ms,
            f"hosts: '{label}': the study's time {study_ms} ms is not within the frame's {frame_ms} ms",
        )
        energy_mj, study_mj = float(whole[label]["energy_mj"]), float(study[label]["study_energy_mj"])
        check(
            0 < study_mj < energy_mj,
            f"hosts: '{label}': the study's energy {study_mj} mJ is not within the frame's {energy_mj} mJ",
        )
    # The ARM's clears are timed on both hosts, inside the rasterization phase.
    for host in ("native", "iss"):
        stats_path = out / "fullscreen_rect" / "runs" / f"arm_{host}" / "stats.json"
        frames = json.loads(stats_path.read_text())["stats"]["frames"] if stats_path.is_file() else []
        check(
            frames
            and all(0 < f["driver"].get("host_clear_ns", 0) < f["driver"]["host_rasterization_ns"] for f in frames),
            f"hosts: {stats_path}: host_clear_ns not within the rasterization",
        )
    # The array's passes are the same on both hosts: the ISS changes the host, not the array's programs.
    for program in ("study", "tuned"):
        native, iss = study.get(f"ap-tile {program} native"), study.get(f"ap-tile {program} iss")
        if native and iss:
            check(
                native["study_ms"] == iss["study_ms"] and native["study_energy_mj"] == iss["study_energy_mj"],
                f"hosts: ap-tile {program}: the array's passes differ between the hosts: {native} {iss}",
            )
    # The study's program takes longer per pass than the tuned one (it keeps every variable in CMEM).
    passes = read_csv(out / "tile_pass" / "tile_pass_study.csv")
    if "ap-tile study native" in passes and "ap-tile tuned native" in passes:
        check(
            float(passes["ap-tile study native"]["total"]) > float(passes["ap-tile tuned native"]["total"]),
            f"hosts: tile_pass: the study's pass is not longer than the tuned one: {passes}",
        )


def test_errors(soc_sim, work):
    names = sorted(path.stem for path in EXPERIMENTS.glob("*.yaml"))
    check(names, f"no experiment in {EXPERIMENTS}")

    status, out, err = run_script("--list")
    check(status == 0, "--list failed\n" + describe(status, out, err))
    listed = [line.split()[0] for line in out.splitlines() if line.strip()]
    expected = names + ["cluster_depth", "cluster_speedup", "cluster_soc"]
    check(listed == expected, f"--list lists {listed}, the folder holds {names} and the cluster's are three")

    status, out, err = run_script("cluster_soc", "--frames", "1", "--soc-sim", soc_sim, "--out", work / "frames1")
    check(
        status == 2 and "--frames: at least 2" in err,
        "a cluster experiment with one frame must be status 2 naming --frames\n" + describe(status, out, err),
    )

    status, out, err = run_script("no_such_experiment", "--soc-sim", soc_sim, "--out", work / "unknown")
    check(
        status == 2 and "unknown experiment 'no_such_experiment'" in err and all(n in err for n in names),
        "an unknown experiment must be status 2 naming it and the known ones\n" + describe(status, out, err),
    )

    missing = work / "no_such_soc_sim"
    status, out, err = run_script(names[0], "--soc-sim", missing, "--out", work / "missing")
    check(
        status == 2 and "soc_sim not found" in err and str(missing) in err,
        "a missing soc_sim must be status 2 naming the path\n" + describe(status, out, err),
    )

    status, out, err = run_script()
    check(status == 2 and "name an experiment" in err, "no experiment must be status 2\n" + describe(status, out, err))

    work.mkdir(parents=True, exist_ok=True)
    malformed = work / "malformed.json"
    malformed.write_text(
        json.dumps(
            {
                "title": "t",
                "runs": [{"label": "a", "backend": "arm", "app": "triangle", "frame": 1}],
                "columns": [{"key": "frame_ms", "value": "frame_time_ms"}],
            }
        )
    )
    status, out, err = run_script(malformed, "--soc-sim", soc_sim, "--out", work / "malformed")
    check(
        status == 2 and str(malformed) in err and "frame" in err and "runs[0]" in err,
        "a misspelt key must be status 2 naming the file, the run and the key\n" + describe(status, out, err),
    )

    failing = work / "failing.json"
    failing.write_text(
        json.dumps(
            {
                "title": "t",
                "runs": [{"label": "doomed", "backend": "arm", "app": "no_such_app"}],
                "columns": [{"key": "frame_ms", "value": "frame_time_ms"}],
            }
        )
    )
    status, out, err = run_script(failing, "--soc-sim", soc_sim, "--out", work / "failing")
    check(
        status == 1 and "run 'doomed' failed" in err and "exit status 2" in err and "no_such_app" in err,
        "a failing soc_sim run must be status 1 naming the run, soc_sim's status and its message\n"
        + describe(status, out, err),
    )

    absent = work / "absent.json"
    absent.write_text(
        json.dumps(
            {
                "title": "t",
                "runs": [{"label": "a", "backend": "arm", "app": "triangle"}],
                "columns": [{"key": "passes", "stat": "driver.ap_tile.passes"}],
            }
        )
    )
    status, out, err = run_script(absent, "--soc-sim", soc_sim, "--out", work / "absent")
    check(
        status == 1 and "run 'a' has no statistic 'driver.ap_tile.passes'" in err,
        "a statistic a run lacks must be status 1 naming the run and the statistic\n" + describe(status, out, err),
    )

    # --host and --set reach every run, and the table says which host model the runs used (from their own
    # stats.json): the triangle's frame on the ISS, with a CIU latency the experiment does not set.
    small = work / "small.json"
    small.write_text(
        json.dumps(
            {
                "title": "t",
                "runs": [{"label": "a", "backend": "arm", "app": "triangle"}],
                "columns": [{"key": "ciu", "config": "ciu.read_cycles"}],
            }
        )
    )
    status, out, err = run_script(
        small, "--soc-sim", soc_sim, "--out", work / "small", "--quiet", "--host", "iss", "--set", "ciu.read_cycles=41"
    )
    check(
        status == 0 and "Host model: iss (`host.model`)." in out and "| a | iss | - | 41 |" in out,
        "--host iss --set ciu.read_cycles=41 must run on the ISS with that setting and say so\n"
        + describe(status, out, err),
    )
    status, out, err = run_script(small, "--soc-sim", soc_sim, "--out", work / "small", "--quiet")
    check(
        status == 0 and "Host model: native (`host.model`)." in out,
        "without --host the runs use the default host model, native, and the table says so\n"
        + describe(status, out, err),
    )
    status, out, err = run_script(small, "--soc-sim", soc_sim, "--out", work / "small", "--set", "ciu.read_cycles")
    check(
        status == 2 and "--set 'ciu.read_cycles': expected KEY=VALUE" in err,
        "a --set without '=' must be status 2 naming it\n" + describe(status, out, err),
    )
    status, out, err = run_script(small, "--soc-sim", soc_sim, "--out", work / "small", "--host", "qemu")
    check(
        status == 2 and "--host 'qemu': unknown (choose native, iss or both)" in err,
        "an unknown --host must be status 2 naming it\n" + describe(status, out, err),
    )
    status, out, err = run_script(small, "--soc-sim", soc_sim, "--out", work / "small", "--program", "fast")
    check(
        status == 2 and "--program 'fast': unknown (choose study, tuned or both)" in err,
        "an unknown --program must be status 2 naming it\n" + describe(status, out, err),
    )
    status, out, err = run_script(small, "--soc-sim", soc_sim, "--out", work / "small", "--set", "host.model=iss")
    check(
        status == 2 and "choose the host model with --host" in err,
        "--set host.model must be status 2 pointing to --host\n" + describe(status, out, err),
    )
    status, out, err = run_script(
        small, "--soc-sim", soc_sim, "--out", work / "small", "--set", "ap.pixel.program=study"
    )
    check(
        status == 2 and "choose the array programs with --program" in err,
        "--set ap.pixel.program must be status 2 pointing to --program\n" + describe(status, out, err),
    )
    for what, change, message in [
        (
            "an unknown host",
            {"hosts": ["native", "qemu"]},
            '\'hosts\' must be a non-empty list of distinct values of native, iss, got ["native", "qemu"]',
        ),
        (
            "an unknown program",
            {"programs": ["fast"]},
            "'programs' must be a non-empty list of distinct values of study, tuned",
        ),
        ("a host listed twice", {"hosts": ["iss", "iss"]}, "'hosts' must be a non-empty list of distinct values"),
    ]:
        bad = work / "bad_dimension.json"
        bad.write_text(
            json.dumps(
                {
                    "title": "t",
                    "runs": [{"label": "a", "backend": "arm", "app": "triangle"}],
                    "columns": [{"key": "ciu", "config": "ciu.read_cycles"}],
                    **change,
                }
            )
        )
        status, out, err = run_script(bad, "--soc-sim", soc_sim, "--out", work / "bad")
        check(
            status == 2 and message in err and str(bad) in err,
            f"{what} in an experiment file must be status 2 naming the file and it\n" + describe(status, out, err),
        )


MATRIX_SPEC = {
    "title": "matrix",
    "set": {"display.width": 192},
    "runs": [{"label": "listed", "backend": "arm", "app": "triangle"}],
    "matrix": {
        "switches": [
            {"key": "dma.enabled", "name": "dma", "backends": ["ap-tile"]},
            {"key": "dma.broadcast", "name": "bc", "backends": ["ap-tile"]},
            {"key": "display.dma", "name": "ddma"},
            {"key": "ap.pixel.block", "name": "block", "values": [1, 3], "backends": ["ap-pixel"]},
        ],
        "skip": [{"dma.enabled": False, "dma.broadcast": True}],
        "runs": [
            {
                "label": "tea",
                "app": "teapot",
                "args": ["x"],
                "frames": 2,
                "set": {"ap.tile.texcoords": "always"},
                "backends": ["arm", "ap-tile"],
            },
            {"label": "px", "app": "study_shading", "shows_frames": False, "backends": ["ap-pixel"]},
        ],
    },
    "columns": [{"key": "frame_ms", "value": "frame_time_ms"}],
    "plot": {"columns": ["frame_ms"], "groups": True},
}


def load_spec(work, name, spec):
    """experiment.load_experiment of `spec` written to work/name.json: (the spec, None) or (None, the message)."""
    path = work / f"{name}.json"
    path.write_text(json.dumps(spec))
    try:
        return experiment.load_experiment(path), None
    except experiment.UsageError as error:
        return None, str(error)


def mutated(change):
    """A deep copy of MATRIX_SPEC with `change` applied to it."""
    spec = json.loads(json.dumps(MATRIX_SPEC))
    change(spec)
    return spec


def test_matrix_expansion(work):
    spec, error = load_spec(work, "expansion", MATRIX_SPEC)
    if not check(error is None, f"matrix: the example does not load: {error}"):
        return
    labels = [run["label"] for run in spec["runs"]]
    expected = [
        "listed",
        "tea arm",
        "tea arm ddma",
        "tea ap-tile",
        "tea ap-tile ddma",
        "tea ap-tile dma",
        "tea ap-tile dma ddma",
        "tea ap-tile dma bc",
        "tea ap-tile dma bc ddma",
        "px ap-pixel block=1",
        "px ap-pixel block=3",
        "px ap-pixel ddma block=1",
        "px ap-pixel ddma block=3",
    ]
    check(labels == expected, f"matrix: runs {labels}, expected {expected}")
    runs = {run["label"]: run for run in spec["runs"]}
    run = runs.get("tea ap-tile dma bc", {})
    check(
        run.get("backend") == "ap-tile"
        and run.get("app") == "teapot"
        and run.get("args") == ["x"]
        and run.get("frames") == 2,
        f"matrix: 'tea ap-tile dma bc' lost its template's fields: {run}",
    )
    settings = {"ap.tile.texcoords": "always", "dma.enabled": True, "dma.broadcast": True, "display.dma": False}
    check(run.get("set") == settings, f"matrix: 'tea ap-tile dma bc' sets {run.get('set')}, expected {settings}")
    check(
        runs.get("tea arm ddma", {}).get("set") == {"ap.tile.texcoords": "always", "display.dma": True},
        f"matrix: a switch for other back ends must not be set on arm: {runs.get('tea arm ddma')}",
    )
    check(
        runs.get("px ap-pixel ddma block=3", {}).get("set") == {"display.dma": True, "ap.pixel.block": 3}
        and runs["px ap-pixel ddma block=3"].get("shows_frames") is False,
        f"matrix: 'px ap-pixel ddma block=3' is {runs.get('px ap-pixel ddma block=3')}",
    )
    groups = spec["run_groups"]
    check(
        groups.get("listed") == ("listed", "")
        and groups.get("tea ap-tile dma bc") == ("tea ap-tile", "dma bc")
        and groups.get("tea arm") == ("tea arm", ""),
        f"matrix: groups {groups}",
    )
    command = experiment.soc_sim_command("soc_sim", spec, runs["tea ap-tile dma bc"], 2, pathlib.Path("out"))
    for setting in (
        "display.width=192",
        "ap.tile.texcoords=always",
        "dma.enabled=true",
        "dma.broadcast=true",
        "display.dma=false",
    ):
        check(setting in command, f"matrix: the soc_sim command {command} lacks --set {setting}")
    check(command[-2:] == ["--", "x"], f"matrix: the soc_sim command {command} lacks the application's arguments")

    # No switches: one run per back end; no listed runs: the matrix's alone; false and 0 are different values.
    spec, error = load_spec(
        work,
        "plain",
        {
            "title": "t",
            "matrix": {"runs": [{"label": "a", "app": "triangle", "backends": ["arm", "raster"]}]},
            "columns": [{"key": "frame_ms", "value": "frame_time_ms"}],
        },
    )
    check(
        error is None and [run["label"] for run in spec["runs"]] == ["a arm", "a raster"],
        f"matrix: without switches, one run per back end: {error or spec['runs']}",
    )
    spec, error = load_spec(work, "values", mutated(lambda s: s["matrix"]["switches"][3].update(values=[0, False])))
    check(
        error is None and "px ap-pixel block=0" in [run["label"] for run in spec["runs"]],
        f"matrix: 0 and false are two values: {error}",
    )


MATRIX_ERRORS = [
    (
        "neither runs nor matrix",
        lambda s: (s.pop("runs"), s.pop("matrix"), s.pop("plot")),
        "'runs' is missing (or give a 'matrix')",
    ),
    ("a misspelt matrix key", lambda s: s["matrix"].update(switch=[]), "matrix: unknown key(s) switch"),
    (
        "a switch without a key",
        lambda s: s["matrix"]["switches"][0].pop("key"),
        "matrix: switches[0]: 'key' must be a configuration key",
    ),
    (
        "a key switched twice",
        lambda s: s["matrix"]["switches"][1].update(key="dma.enabled"),
        "switches[1]: 'dma.enabled' is switched twice",
    ),
    (
        "a name used twice",
        lambda s: s["matrix"]["switches"][1].update(name="dma"),
        "switches[1]: name 'dma' is used twice",
    ),
    (
        "a name that is not a word",
        lambda s: s["matrix"]["switches"][1].update(name="two words"),
        "switches[1]: 'name' (the run labels' word for it) must be a word",
    ),
    (
        "no values",
        lambda s: s["matrix"]["switches"][2].update(values=[]),
        "switches[2] ('display.dma'): 'values' must be a non-empty list",
    ),
    (
        "a value twice",
        lambda s: s["matrix"]["switches"][2].update(values=[True, True]),
        "switches[2] ('display.dma'): a value is listed twice",
    ),
    (
        "a skip naming no switch",
        lambda s: s["matrix"]["skip"].append({"dma.enable": True}),
        "matrix: skip[1]: 'dma.enable' is not a switch of the matrix",
    ),
    (
        "a skip of a value never switched",
        lambda s: s["matrix"]["skip"].append({"ap.pixel.block": 2}),
        "matrix: skip[1]: 2 is not one of the values of 'ap.pixel.block' (1, 3), so it skips nothing",
    ),
    (
        "a skip of everything",
        lambda s: s["matrix"]["skip"].extend([{"display.dma": False}, {"display.dma": True}]),
        "matrix: runs[0]: 'skip' leaves no combination of the switches for back end 'arm'",
    ),
    (
        "a run without back ends",
        lambda s: s["matrix"]["runs"][0].pop("backends"),
        "matrix: runs[0]: 'backends' must be a non-empty list of distinct back-end names",
    ),
    (
        "a back end twice",
        lambda s: s["matrix"]["runs"][0].update(backends=["arm", "arm"]),
        "matrix: runs[0]: 'backends' must be a non-empty list of distinct back-end names",
    ),
    (
        "'backend' for 'backends'",
        lambda s: s["matrix"]["runs"][1].update(backend="arm"),
        "matrix: runs[1]: unknown key(s) backend",
    ),
    (
        "a run setting a switch",
        lambda s: s["matrix"]["runs"][1].update(set={"display.dma": True}),
        "matrix: runs[1]: 'set' sets 'display.dma', which the matrix switches",
    ),
    (
        "the experiment setting a switch",
        lambda s: s["set"].update({"dma.broadcast": True}),
        "matrix: the experiment's 'set' sets 'dma.broadcast', which the matrix switches",
    ),
    (
        "a listed run's label made by the matrix",
        lambda s: s["runs"][0].update(label="tea arm"),
        "label 'tea arm' is used twice",
    ),
    (
        "a bad frames in a template",
        lambda s: s["matrix"]["runs"][0].update(frames=0),
        "matrix: runs[0] ('tea arm'): 'frames' must be a positive integer",
    ),
    ("groups without a matrix", lambda s: s.pop("matrix"), "plot: 'groups' draws a matrix's runs grouped"),
    (
        "groups of two columns",
        lambda s: (
            s["columns"].append({"key": "fps", "value": "frames_per_second"}),
            s["plot"].update(columns=["frame_ms", "fps"]),
        ),
        "plot: 'groups' plots one column",
    ),
    (
        "host_time_ms without part",
        lambda s: s["columns"].append({"key": "w", "value": "host_time_ms"}),
        "columns[1] ('w'): 'part' goes with the value host_time_ms",
    ),
    (
        "a part that is not one",
        lambda s: s["columns"].append({"key": "w", "value": "host_time_ms", "part": "idle"}),
        "columns[1] ('w'): 'part' must be one of compute, write, read, wait, frame_out",
    ),
    (
        "required not a boolean",
        lambda s: s["columns"][0].update(required="no"),
        "columns[0] ('frame_ms'): 'required' must be true or false",
    ),
]


def test_matrix_errors(work):
    for index, (what, change, message) in enumerate(MATRIX_ERRORS):
        spec, error = load_spec(work, f"error_{index}", mutated(change))
        if check(error is not None, f"matrix: {what}: loaded without an error"):
            check(
                message in error and str(work / f"error_{index}.json") in error,
                f'matrix: {what}: the message must name the file and say "{message}", it says: {error}',
            )
    # From the command line: status 2 and the message, before any soc_sim runs.
    path = work / "error_cli.json"
    path.write_text(json.dumps(mutated(lambda s: s["matrix"]["switches"][2].update(values=[]))))
    status, out, err = run_script(path, "--soc-sim", work / "no_soc_sim_needed", "--out", work / "cli")
    check(
        status == 2 and str(path) in err and "'values' must be a non-empty list" in err,
        "matrix: a malformed matrix must be status 2 naming the file\n" + describe(status, out, err),
    )


def test_what_if_figures():
    """The figures of the what-if columns on statistics written here, as a soc_sim run's stats.json holds them."""

    def result(backend, stats, shows_frames=True):
        run = {"label": f"{backend} run", "backend": backend, "shows_frames": shows_frames}
        return experiment.RunResult(run, pathlib.Path("stats.json"), {"stats": stats, "config": {}})

    scene = result(
        "ap-tile",
        {
            "frames": [{"render_ns": 2e6}, {"render_ns": 4e6}],
            "bus": {"initiators": {"host": {"bytes": 1000}}},
            "driver": {
                "ap_tile": {"values_written": 300, "triangles": 3, "host_write_ns": 4e6, "host_frame_out_ns": 1e6}
            },
        },
    )
    study = result(
        "ap-pixel", {"frames": [], "driver": {"study": {"total_ns": 7e6, "write_ns": 5e6}}}, shows_frames=False
    )
    bare = result("ap-pixel", {"frames": [{"render_ns": 1e6}], "driver": {"ap_pixel": {"triangles": 2}}})

    def value(column, run):
        try:
            return experiment.cell_value(column, run, [run])
        except experiment.RunError as error:
            return f"RunError: {error}"

    cases = [
        ("time per frame", {"value": "frame_or_run_time_ms"}, scene, 3.0),
        ("a study's time per run", {"value": "frame_or_run_time_ms"}, study, 7.0),
        ("host write per frame", {"value": "host_time_ms", "part": "write"}, scene, 2.0),
        ("frame out per frame", {"value": "host_time_ms", "part": "frame_out"}, scene, 0.5),
        ("a study's host write per run", {"value": "host_time_ms", "part": "write"}, study, 5.0),
        (
            "a study's frame out, not required",
            {"value": "host_time_ms", "part": "frame_out", "required": False},
            study,
            None,
        ),
        ("values per triangle", {"value": "values_written_per_triangle"}, scene, 100.0),
        (
            "values per triangle unpublished, not required",
            {"value": "values_written_per_triangle", "required": False},
            bare,
            None,
        ),
        ("bytes per frame", {"stat": "bus.initiators.host.bytes", "per": "frame"}, scene, 500.0),
        (
            "an absent initiator, not required",
            {"stat": "bus.initiators.dma.bytes", "per": "frame", "required": False},
            scene,
            None,
        ),
        ("a study's bytes per frame: per run", {"stat": "driver.study.write_ns", "per": "frame"}, study, 5e6),
    ]
    for what, column, run, expected in cases:
        got = value(column, run)
        check(got == expected, f"what-if figures: {what}: {got}, expected {expected}")
    for what, column, run, message in [
        (
            "an absent initiator, required",
            {"stat": "bus.initiators.dma.bytes"},
            scene,
            "run 'ap-tile run' has no statistic 'bus.initiators.dma.bytes'",
        ),
        (
            "values per triangle unpublished, required",
            {"value": "values_written_per_triangle"},
            bare,
            "run 'ap-pixel run' has no statistic 'driver.ap_pixel.values_written'",
        ),
        ("a study's time per frame", {"value": "frame_time_ms"}, study, "shows no frame"),
    ]:
        got = value(column, run)
        check(isinstance(got, str) and message in got, f'what-if figures: {what}: {got}, expected "{message}"')
    check(experiment.format_cell({}, None) == "-", "what-if figures: a missing figure must show as '-'")

    # Energy: the frame records' own energy (start-up excluded), a study's whole run, and the ratio to a baseline.
    def labelled(label, run):
        run.label = run.base_label = label
        return run

    arm = labelled(
        "arm",
        result(
            "arm",
            {
                "frames": [
                    {"render_ns": 1e6, "energy": {"total_j": 0.002}},
                    {"render_ns": 1e6, "energy": {"total_j": 0.004}},
                ],
                "energy": {"total_j": 1.0},
            },
        ),
    )
    array = labelled(
        "array",
        result("ap-tile", {"frames": [{"render_ns": 1e6, "energy": {"total_j": 0.012}}], "energy": {"total_j": 1.0}}),
    )
    shading = labelled("shading", result("ap-pixel", {"frames": [], "energy": {"total_j": 0.25}}, shows_frames=False))
    no_energy = labelled("old", result("arm", {"frames": [{"render_ns": 1e6}]}))
    per_frame = {"value": "energy_per_frame_mj"}
    ratio = {"value": "energy_ratio", "baseline": "arm"}
    for what, got, expected in [
        ("energy per frame: the frames' mean", experiment.cell_value(per_frame, arm, [arm]), 3.0),
        ("a study's energy: the whole run", experiment.cell_value(per_frame, shading, [shading]), 250.0),
        ("energy ratio over arm", experiment.cell_value(ratio, array, [arm, array]), 0.25),
        ("arm's own energy ratio", experiment.cell_value(ratio, arm, [arm, array]), 1.0),
    ]:
        check(abs(got - expected) < 1e-9, f"what-if figures: {what}: {got}, expected {expected}")
    got = value(per_frame, no_energy)
    check(
        isinstance(got, str) and "has no energy.total_j" in got,
        f"what-if figures: frames without energy: {got}, expected a RunError",
    )


def test_cluster(soc_sim, work):
    """cluster_soc and cluster_depth on a small scene: the tables printed and written, a row per machine and per
    depth and node count, every time and energy a positive number, the SoC's arm its own baseline."""
    triangles = "600"
    status, out, err = run_script(
        "cluster_soc", "--triangles", triangles, "--frames", "2", "--soc-sim", soc_sim, "--out", work / "soc"
    )
    if not check(status == 0, "cluster_soc failed\n" + describe(status, out, err)):
        return
    with open(work / "soc" / "cluster_soc.csv", newline="") as table:
        rows = list(csv.DictReader(table))
    machines = [row["machine"] for row in rows]
    expected = ["SoC, arm", "SoC, ap-tile"] + [f"cluster, p = {p}" for p in (1, 2, 4, 8, 16, 32, 64, 128)]
    check(machines == expected, f"cluster_soc: rows {machines}, expected {expected}")
    check("| SoC, arm |" in out, "cluster_soc: the table is not printed\n" + out)
    for row in rows:
        for key in ("time per frame (ms)", "energy per frame (mJ)", "speed-up over arm"):
            check(positive_number(row[key]), f"cluster_soc: {row['machine']}: {key} is {row[key]!r}")
    check(rows[0]["speed-up over arm"] == "1.00", f"cluster_soc: arm over itself is {rows[0]['speed-up over arm']}")
    check(
        all(positive_number(row["of it the network's (mJ)"]) for row in rows[3:]),
        f"cluster_soc: a cluster of several nodes has no network energy: {rows}",
    )

    status, out, err = run_script(
        "cluster_depth", "--triangles", "2000", "--frames", "2", "--soc-sim", soc_sim, "--out", work / "depth"
    )
    if not check(status == 0, "cluster_depth failed\n" + describe(status, out, err)):
        return
    with open(work / "depth" / "cluster_depth.csv", newline="") as table:
        rows = list(csv.DictReader(table))
    check([row["d"] for row in rows] == ["1", "2", "4", "8", "16", "32", "64"], f"cluster_depth: rows {rows}")
    check(
        all(positive_number(value) for row in rows for key, value in row.items() if key != "d"),
        f"cluster_depth: a time is not a positive number: {rows}",
    )
    with open(work / "depth" / "cluster_depth_fit.csv", newline="") as table:
        fits = list(csv.DictReader(table))
    check([row["p"] for row in fits] == ["8", "16", "32", "64"], f"cluster_depth: fit rows {fits}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", choices=("run", "hosts", "errors", "matrix", "cluster"))
    parser.add_argument("name", nargs="?")
    parser.add_argument("--soc-sim", help="the soc_sim to run (run and errors)")
    parser.add_argument("--work", required=True, type=pathlib.Path)
    args = parser.parse_args()
    if args.what != "matrix" and not args.soc_sim:
        parser.error(f"{args.what} needs --soc-sim")
    if args.what == "run":
        if not args.name:
            parser.error("run needs an experiment's name")
        test_run(args.name, args.soc_sim, args.work)
    elif args.what == "hosts":
        test_hosts(args.soc_sim, args.work)
    elif args.what == "errors":
        test_errors(args.soc_sim, args.work)
    elif args.what == "cluster":
        test_cluster(args.soc_sim, args.work)
    else:
        args.work.mkdir(parents=True, exist_ok=True)
        test_matrix_expansion(args.work)
        test_matrix_errors(args.work)
        test_what_if_figures()
    for failure in FAILURES:
        print(f"FAIL: {failure}\n")
    print("FAILED" if FAILURES else "PASSED")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
