#!/usr/bin/python3
"""The study's experiments: a spec of soc_sim runs plus a table template, run
and printed as Markdown tables.

An experiment is a YAML (or JSON) file, experiments/<name>.yaml, that lists
soc_sim runs (back end, application and its arguments, frames, configuration
settings), or a matrix of them (applications x back ends x every combination
of some switches), and the table's columns (statistics of stats.json,
configuration values, or figures computed from them, figures.py: among them
a baseline run's figure over each run's, the speed-up or the energy saving,
and every time and energy in ms and mJ). run_experiment runs soc_sim once per
run, reads each run's stats.json, prints the table in Markdown and writes, in
the output folder (default out/experiments/<name>):

    <name>.md   the table (and the study's)
    <name>.csv  the same values, unrounded, one row per run
    <name>_study.csv  the study's table's values, if it has one
    <name>.png  the plot the experiment asks for (matplotlib)
    runs/<run>/ each run's frames and stats.json

    tessera-sweep list
    tessera-sweep run fullscreen_rect
    tessera-sweep run experiments/teapot.yaml --frames 1 --out out/quick
    tessera-sweep run my_experiment.yaml --soc-sim build/sanitize/bin/soc_sim
    tessera-sweep run teapot --host iss --frames 1 --out out/teapot_iss
    tessera-sweep run fullscreen_rect --host both --program study
    tessera-sweep run experiments/dma_whatif.yaml --set ciu.read_cycles=40 --out out/whatif_ciu

(scripts/experiment.py, an alias, takes the same arguments without "run";
--list lists.) The cluster platform's experiments (cluster_depth,
cluster_speedup, cluster_soc) fit a model to their runs and so are programs,
not specs: cluster_experiments.py, run by the same commands with options of
their own. An experiment's runs are made on each host model it lists
("hosts": native, the host-compiled model, or iss, the driver as ARM code on
the ISS) and, for ap-tile and ap-pixel, with each array program it lists
("programs": study, the study's program as its compiler wrote it, or tuned);
--host native|iss|both and --program study|tuned|both choose instead. Every
table says which host and program each row ran. --set KEY=VALUE sets any
configuration key in every run, over the experiment's own.

An experiment may have two tables: its own (the whole frame as the model
runs it: transfers, the display, the whole SoC's energy) and "study", the
study's quantities as the study measured them (docs/spec/study_programs.md,
"The study's test cases"); no table mixes the two. The wall time of each
run and of the experiment is printed on standard error.

docs/experiments.md describes each experiment, its columns, the file format
and how to add an experiment. It runs under Debian's python3 (which has
matplotlib, PyYAML and pandas: scripts/setup.sh) or the sweep venv.

Exit status: 0 on success; 2 for a bad command line, an unknown experiment,
a malformed experiment file, a missing soc_sim or a missing matplotlib; 1
when a soc_sim run fails or its statistics lack a figure the table needs.
"""

import argparse
import itertools
import json
import os
import pathlib
import re
import subprocess
import sys
import time

import yaml

from .experiment_table import RUN_COLUMNS as RUN_COLUMNS
from .experiment_table import UsageError, build_table, import_pyplot, markdown, plot, write_csv
from .experiment_table import cell_value as cell_value
from .experiment_table import format_cell as format_cell
from .figures import (
    BASELINE_VALUES,
    COMPUTED,
    HOST_PARTS,
    PROGRAM_KEYS,
    QUANTITIES,
    QUANTITY_VALUES,
    SAVING_PERCENT,
    RunError,
    RunResult,
)
from .spec import SpecError, load_yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXPERIMENTS = ROOT / "experiments"
DEFAULT_SOC_SIM = ROOT / "build" / "default" / "bin" / "soc_sim"

EXIT_FAILED = 1
EXIT_USAGE = 2


# ---------------------------------------------------------------------------
# The experiment file.

TOP_KEYS = {
    "title",
    "description",
    "frames",
    "set",
    "runs",
    "matrix",
    "label_header",
    "columns",
    "plot",
    "hosts",
    "programs",
    "study",
}
STUDY_KEYS = {"title", "description", "columns"}
HOSTS = ("native", "iss")
PROGRAMS = ("study", "tuned")
# The array back ends' program keys; the other back ends run no array program.
RUN_KEYS = {"label", "backend", "app", "args", "set", "config", "frames", "shows_frames", "baseline", "backend_program"}
MATRIX_KEYS = {"switches", "skip", "runs"}
SWITCH_KEYS = {"key", "name", "values", "backends"}
MATRIX_RUN_KEYS = (RUN_KEYS - {"backend"}) | {"backends"}
COLUMN_KEYS = {
    "key",
    "header",
    "stat",
    "config",
    "value",
    "per",
    "scale",
    "format",
    "backends",
    "baseline",
    "shape",
    "part",
    "required",
    "may_be_zero",
    "quantity",
    "of",
}
PLOT_KEYS = {"columns", "stacked", "ylabel", "x", "log", "groups"}


def check_keys(where, given, allowed):
    unknown = sorted(set(given) - allowed)
    if unknown:
        raise UsageError(f"{where}: unknown key(s) {', '.join(unknown)} (allowed: {', '.join(sorted(allowed))})")


def check_settings(where, settings):
    if not isinstance(settings, dict):
        raise UsageError(f"{where}: 'set' must be an object of configuration keys and values")
    for key, value in settings.items():
        if isinstance(value, (dict, list)) or value is None:
            raise UsageError(f"{where}: 'set' value of '{key}' must be a string, a number or a boolean")


def positive_int(where, value):
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise UsageError(f"{where} must be a positive integer, got {json.dumps(value)}")
    return value


def is_setting_value(value):
    return isinstance(value, (str, int, float))


def same_value(a, b):
    """Equality that keeps false apart from 0 and true from 1 (JSON's booleans are Python ints)."""
    return type(a) is type(b) and a == b


def non_empty_strings(value):
    return isinstance(value, list) and bool(value) and all(isinstance(v, str) and v for v in value)


def switch_label(switch, value):
    """A switch's part of a run's label: a boolean switch's name when it is true, nothing when it is false; any
    other value as name=value."""
    if isinstance(value, bool):
        return switch["name"] if value else ""
    return f"{switch['name']}={setting_text(value)}"


def load_switches(where, switches):
    if not isinstance(switches, list):
        raise UsageError(f"{where}: 'switches' must be a list of switches")
    keys, names = set(), set()
    for index, switch in enumerate(switches):
        switch_where = f"{where}: switches[{index}]"
        if not isinstance(switch, dict):
            raise UsageError(f"{switch_where} must be an object")
        check_keys(switch_where, switch, SWITCH_KEYS)
        if not isinstance(switch.get("key"), str) or not switch["key"]:
            raise UsageError(f"{switch_where}: 'key' must be a configuration key (e.g. \"dma.enabled\")")
        if switch["key"] in keys:
            raise UsageError(f"{switch_where}: '{switch['key']}' is switched twice")
        keys.add(switch["key"])
        switch.setdefault("name", switch["key"])
        if not isinstance(switch["name"], str) or not re.fullmatch(r"[A-Za-z0-9._-]+", switch["name"]):
            raise UsageError(
                f"{switch_where}: 'name' (the run labels' word for it) must be a word of letters, "
                "digits, '.', '_' and '-'"
            )
        if switch["name"] in names:
            raise UsageError(
                f"{switch_where}: name '{switch['name']}' is used twice (the labels would not tell the switches apart)"
            )
        names.add(switch["name"])
        values = switch.setdefault("values", [False, True])
        if not isinstance(values, list) or not values or not all(is_setting_value(v) for v in values):
            raise UsageError(
                f"{switch_where} ('{switch['key']}'): 'values' must be a non-empty list of strings, numbers or booleans"
            )
        if any(same_value(a, b) for i, a in enumerate(values) for b in values[i + 1 :]):
            raise UsageError(f"{switch_where} ('{switch['key']}'): a value is listed twice")
        if "backends" in switch and not non_empty_strings(switch["backends"]):
            raise UsageError(
                f"{switch_where} ('{switch['key']}'): 'backends' must be a non-empty list of back-end names"
            )


def load_skips(where, skips, switches):
    by_key = {switch["key"]: switch for switch in switches}
    if not isinstance(skips, list):
        raise UsageError(f"{where}: 'skip' must be a list of objects of switch keys and values")
    for index, skip in enumerate(skips):
        skip_where = f"{where}: skip[{index}]"
        if not isinstance(skip, dict) or not skip:
            raise UsageError(f"{skip_where} must be a non-empty object of switch keys and values")
        for key, value in skip.items():
            if key not in by_key:
                raise UsageError(
                    f"{skip_where}: '{key}' is not a switch of the matrix ({', '.join(by_key) or 'it has none'})"
                )
            if not any(same_value(value, v) for v in by_key[key]["values"]):
                raise UsageError(
                    f"{skip_where}: {json.dumps(value)} is not one of the values of '{key}' "
                    f"({', '.join(json.dumps(v) for v in by_key[key]['values'])}), so it skips nothing"
                )


def skipped(settings, skips):
    """Whether a combination of switch settings matches every key of one of the "skip" objects."""
    return any(
        all(key in settings and same_value(settings[key], value) for key, value in skip.items()) for skip in skips
    )


def load_matrix(where, matrix, common_settings):
    """The runs a "matrix" stands for, checked: for each of its runs, each of the run's back ends and each
    combination of the switches that apply to that back end (in the order listed, the last switch changing
    fastest), less the combinations a "skip" object matches. Each run's label is "<label> <back end>" and the
    names of the switches that are on (name=value for a switch that is not boolean). Returns the runs, where each
    is (for messages), and per label its group ("<label> <back end>") and variant (the switches' part)."""
    where = f"{where}: matrix"
    if not isinstance(matrix, dict):
        raise UsageError(f"{where} must be an object with 'runs', 'switches' and 'skip'")
    check_keys(where, matrix, MATRIX_KEYS)
    switches = matrix.setdefault("switches", [])
    load_switches(where, switches)
    skips = matrix.setdefault("skip", [])
    load_skips(where, skips, switches)
    for switch in switches:
        if switch["key"] in common_settings:
            raise UsageError(f"{where}: the experiment's 'set' sets '{switch['key']}', which the matrix switches")
    if not isinstance(matrix.get("runs"), list) or not matrix["runs"]:
        raise UsageError(f"{where}: 'runs' must be a non-empty list (each with a label, an app and its backends)")

    runs, wheres, cells = [], [], {}
    for index, template in enumerate(matrix["runs"]):
        run_where = f"{where}: runs[{index}]"
        if not isinstance(template, dict):
            raise UsageError(f"{run_where} must be an object")
        check_keys(run_where, template, MATRIX_RUN_KEYS)
        for key in ("label", "app"):
            if not isinstance(template.get(key), str) or not template[key]:
                raise UsageError(f"{run_where}: '{key}' must be a non-empty string")
        backends = template.get("backends")
        if not non_empty_strings(backends) or len(set(backends)) != len(backends):
            raise UsageError(f"{run_where}: 'backends' must be a non-empty list of distinct back-end names")
        check_settings(run_where, template.setdefault("set", {}))
        for switch in switches:
            if switch["key"] in template["set"]:
                raise UsageError(f"{run_where}: 'set' sets '{switch['key']}', which the matrix switches")
        for backend in template["backends"]:
            applying = [switch for switch in switches if backend in switch.get("backends", [backend])]
            group = f"{template['label']} {backend}"
            combinations = [
                dict(zip((switch["key"] for switch in applying), values))
                for values in itertools.product(*(switch["values"] for switch in applying))
            ]
            kept = [settings for settings in combinations if not skipped(settings, skips)]
            if not kept:
                raise UsageError(f"{run_where}: 'skip' leaves no combination of the switches for back end '{backend}'")
            for settings in kept:
                variant = " ".join(
                    part for part in (switch_label(switch, settings[switch["key"]]) for switch in applying) if part
                )
                label = f"{group} {variant}" if variant else group
                run = {key: value for key, value in template.items() if key != "backends"}
                run.update(label=label, backend=backend, set={**template["set"], **settings})
                runs.append(run)
                wheres.append(f"{run_where} ('{label}')")
                cells[label] = (group, variant)
    return runs, wheres, cells


SUFFIXES = (".yaml", ".yml", ".json")


def read_experiment(path):
    """The experiment file at `path` as data, unchecked: JSON for .json, else YAML."""
    try:
        text = path.read_text()
    except OSError as error:
        raise UsageError(f"cannot read {path}: {error.strerror}") from error
    if path.suffix == ".json":
        try:
            return json.loads(text)
        except json.JSONDecodeError as error:
            raise UsageError(f"{path} is not valid JSON: {error}") from error
    try:
        return load_yaml(text, path)
    except yaml.YAMLError as error:
        raise UsageError(f"{path} is not valid YAML: {error}") from error
    except SpecError as error:
        raise UsageError(str(error)) from error


def is_experiment(data):
    """Whether spec data is an experiment (a table of runs) rather than a sweep spec: it has a table's columns."""
    return isinstance(data, dict) and "columns" in data


def load_experiment(path):
    """The experiment at `path`, checked; UsageError naming the file and what is wrong."""
    return check_experiment(read_experiment(pathlib.Path(path)), str(path))


def check_experiment(spec, where):
    """The experiment `spec` (data as read from its file; filled in with its defaults), checked; UsageError
    naming `where` and what is wrong."""
    if not isinstance(spec, dict):
        raise UsageError(f"{where}: the top level must be an object")
    check_keys(where, spec, TOP_KEYS)
    for key in ("title", "columns"):
        if key not in spec:
            raise UsageError(f"{where}: '{key}' is missing")
    if "runs" not in spec and "matrix" not in spec:
        raise UsageError(f"{where}: 'runs' is missing (or give a 'matrix')")
    positive_int(f"{where}: 'frames'", spec.setdefault("frames", 1))
    check_settings(where, spec.setdefault("set", {}))
    spec.setdefault("description", "")
    spec.setdefault("label_header", "run")

    runs = spec.setdefault("runs", [])
    if not isinstance(runs, list) or not (runs or "matrix" in spec):
        raise UsageError(f"{where}: 'runs' must be a non-empty list")
    run_wheres = [f"{where}: runs[{index}]" for index in range(len(runs))]
    # The matrix's runs follow the listed ones; each listed run is a group of its own in a grouped plot.
    spec["run_groups"] = {
        run["label"]: (run["label"], "") for run in runs if isinstance(run, dict) and isinstance(run.get("label"), str)
    }
    if "matrix" in spec:
        matrix_runs, matrix_wheres, groups = load_matrix(where, spec["matrix"], spec["set"])
        runs += matrix_runs
        run_wheres += matrix_wheres
        spec["run_groups"].update(groups)
    labels, folders = set(), set()
    for run, run_where in zip(runs, run_wheres):
        if not isinstance(run, dict):
            raise UsageError(f"{run_where} must be an object")
        check_keys(run_where, run, RUN_KEYS)
        for key in ("label", "backend", "app"):
            if not isinstance(run.get(key), str) or not run[key]:
                raise UsageError(f"{run_where}: '{key}' must be a non-empty string")
        if run["label"] in labels or run_folder_name(run["label"]) in folders:
            raise UsageError(
                f"{run_where}: label '{run['label']}' is used twice (or names the same folder as "
                "another: runs/" + run_folder_name(run["label"]) + ")"
            )
        labels.add(run["label"])
        folders.add(run_folder_name(run["label"]))
        run.setdefault("args", [])
        if not isinstance(run["args"], list) or not all(isinstance(a, str) for a in run["args"]):
            raise UsageError(f"{run_where}: 'args' must be a list of strings")
        check_settings(run_where, run.setdefault("set", {}))
        if "config" in run and (not isinstance(run["config"], str) or not (ROOT / run["config"]).is_file()):
            raise UsageError(
                f"{run_where}: 'config' must name a configuration file of the repository, not {run['config']!r}"
            )
        if "frames" in run:
            positive_int(f"{run_where}: 'frames'", run["frames"])
    for run, run_where in zip(runs, run_wheres):
        if "baseline" in run and run["baseline"] not in labels:
            raise UsageError(f"{run_where}: 'baseline' must be the label of a run ({', '.join(sorted(labels))})")

    check_columns(where, spec["columns"], labels)
    load_dimensions(where, spec, runs)
    if "study" in spec:
        study = spec["study"]
        if not isinstance(study, dict):
            raise UsageError(f"{where}: 'study' must be an object with 'title', 'description' and 'columns'")
        check_keys(f"{where}: study", study, STUDY_KEYS)
        if not isinstance(study.get("title"), str) or not study["title"]:
            raise UsageError(f"{where}: study: 'title' must be a non-empty string")
        study.setdefault("description", "")
        check_columns(f"{where}: study", study["columns"] if "columns" in study else None, labels)
        study_keys = {column["key"] for column in study["columns"]}
        shared = sorted(study_keys & {column["key"] for column in spec["columns"]})
        if shared:
            raise UsageError(f"{where}: study: column key(s) {', '.join(shared)} also in the experiment's own table")
    keys = {column["key"] for column in spec["columns"]}

    plot = spec.setdefault("plot", {})
    if not isinstance(plot, dict):
        raise UsageError(f"{where}: 'plot' must be an object")
    check_keys(f"{where}: plot", plot, PLOT_KEYS)
    plot.setdefault("columns", [spec["columns"][0]["key"]])
    for key in plot["columns"] + ([plot["x"]] if "x" in plot else []):
        if key not in keys:
            raise UsageError(f"{where}: plot: '{key}' is not a column key ({', '.join(sorted(keys))})")
    if plot.get("groups"):
        if "matrix" not in spec:
            raise UsageError(f"{where}: plot: 'groups' draws a matrix's runs grouped, and there is no 'matrix'")
        if len(plot["columns"]) != 1 or "x" in plot or plot.get("stacked"):
            raise UsageError(f"{where}: plot: 'groups' plots one column, without 'x' or 'stacked'")
    return spec


def check_columns(where, columns, labels):
    """A table's columns, checked, their defaults filled in; `labels`: the runs' labels (for baselines)."""
    if not isinstance(columns, list) or not columns:
        raise UsageError(f"{where}: 'columns' must be a non-empty list")
    keys = set()
    for index, column in enumerate(columns):
        column_where = f"{where}: columns[{index}]"
        if not isinstance(column, dict):
            raise UsageError(f"{column_where} must be an object")
        check_keys(column_where, column, COLUMN_KEYS)
        key = column.get("key")
        if not isinstance(key, str) or not re.fullmatch(r"[a-z][a-z0-9_]*", key):
            raise UsageError(f"{column_where}: 'key' must be a name of [a-z0-9_] (the CSV's column)")
        if key in keys or key in ("run", "host", "program"):
            raise UsageError(
                f"{column_where}: key '{key}' is used twice (or is 'run', 'host' or 'program', the "
                "columns every table starts with)"
            )
        keys.add(key)
        column.setdefault("header", key)
        sources = [source for source in ("stat", "config", "value") if source in column]
        if len(sources) != 1:
            raise UsageError(f"{column_where} ('{key}') needs exactly one of 'stat', 'config' and 'value'")
        if "value" in column and column["value"] not in COMPUTED and column["value"] != SAVING_PERCENT:
            raise UsageError(
                f"{column_where} ('{key}'): unknown value '{column['value']}' "
                f"(known: {', '.join(COMPUTED)}, {SAVING_PERCENT})"
            )
        if (column.get("value") == SAVING_PERCENT) != ("of" in column):
            raise UsageError(f"{column_where} ('{key}'): 'of' goes with the value {SAVING_PERCENT}, which needs it")
        earlier = {c["key"] for c in columns[:index] if c.get("value") != SAVING_PERCENT}
        if "of" in column and column["of"] not in earlier:
            raise UsageError(
                f"{column_where} ('{key}'): 'of' must be the key of a column before it in the same table, "
                f"not itself a saving ({', '.join(sorted(earlier)) or 'there is none'})"
            )
        if column.get("value") in BASELINE_VALUES and column.get("baseline") not in labels:
            raise UsageError(
                f"{column_where} ('{key}'): 'baseline' must be the label of a run ({', '.join(sorted(labels))})"
            )
        if column.get("value") == "patch_break_even" and column.get("shape") not in ("line", "square"):
            raise UsageError(f"{column_where} ('{key}'): 'shape' must be line or square")
        if "per" in column and "stat" not in column:
            raise UsageError(f"{column_where} ('{key}'): 'per' applies to a 'stat' column only")
        if "scale" in column and (isinstance(column["scale"], bool) or not isinstance(column["scale"], (int, float))):
            raise UsageError(f"{column_where} ('{key}'): 'scale' must be a number")
        if "format" in column:
            try:
                format(1.5, column["format"])
            except (TypeError, ValueError) as error:
                raise UsageError(
                    f"{column_where} ('{key}'): bad 'format' {json.dumps(column['format'])} "
                    '(a Python format for a number, e.g. ",.2f")'
                ) from error
        if "backends" in column and (not isinstance(column["backends"], list) or not column["backends"]):
            raise UsageError(f"{column_where} ('{key}'): 'backends' must be a non-empty list of back-end names")
        for flag in ("required", "may_be_zero"):
            if flag in column and not isinstance(column[flag], bool):
                raise UsageError(f"{column_where} ('{key}'): '{flag}' must be true or false")
        if (column.get("value") == "host_time_ms") != ("part" in column):
            raise UsageError(f"{column_where} ('{key}'): 'part' goes with the value host_time_ms, which needs it")
        if "part" in column and column["part"] not in HOST_PARTS:
            raise UsageError(f"{column_where} ('{key}'): 'part' must be one of {', '.join(HOST_PARTS)}")
        if (column.get("value") in QUANTITY_VALUES) != ("quantity" in column):
            raise UsageError(
                f"{column_where} ('{key}'): 'quantity' goes with the values {', '.join(QUANTITY_VALUES)}, which need it"
            )
        if "quantity" in column and column["quantity"] not in QUANTITIES:
            raise UsageError(f"{column_where} ('{key}'): 'quantity' must be one of {', '.join(QUANTITIES)}")


def choice_list(where, key, value, allowed):
    if (
        not isinstance(value, list)
        or not value
        or len(set(map(str, value))) != len(value)
        or not all(v in allowed for v in value)
    ):
        raise UsageError(
            f"{where}: '{key}' must be a non-empty list of distinct values of {', '.join(allowed)}, "
            f"got {json.dumps(value)}"
        )
    return value


def load_dimensions(where, spec, runs):
    """The host models ("hosts", default native) and array programs ("programs", default none: each back end's
    configured one) the runs are made with, checked; a run may not set what they choose."""
    choice_list(where, "hosts", spec.setdefault("hosts", ["native"]), HOSTS)
    if "programs" in spec:
        choice_list(where, "programs", spec["programs"], PROGRAMS)
    for run in runs:
        settings = {**spec["set"], **run["set"]}
        if "host.model" in settings:
            raise UsageError(f"{where}: run '{run['label']}' sets host.model: list the hosts in 'hosts' instead")
        key = PROGRAM_KEYS.get(run["backend"])
        if "programs" in spec and key in settings:
            raise UsageError(f"{where}: run '{run['label']}' sets {key}, which 'programs' chooses")


def expand_runs(spec, hosts=None, programs=None):
    """The runs on each host of `hosts` (default: the experiment's "hosts") and, for an array back end, with each
    program of `programs` (default: the experiment's "programs"; none: the back end's configured program). A run's
    label gains its program and, with more than one host, its host; base_label keeps the experiment's label (the
    one baselines name). The matrix's groups follow."""
    hosts = hosts or spec["hosts"]
    programs = programs or spec.get("programs")
    expanded = []
    for run in spec["runs"]:
        key = PROGRAM_KEYS.get(run["backend"])
        for host in hosts:
            for program in programs if key and programs else [None]:
                settings = {**run["set"], "host.model": host}
                parts = [run["label"]]
                if program:
                    settings[key] = program
                    parts.append(program)
                if len(hosts) > 1:
                    parts.append(host)
                label = " ".join(parts)
                expanded.append({**run, "label": label, "base_label": run["label"], "set": settings})
                group, variant = spec["run_groups"].get(run["label"], (run["label"], ""))
                spec["run_groups"][label] = (group, " ".join(part for part in [variant] + parts[1:] if part))
    return expanded


def experiment_files():
    """The study's experiments: experiments/*.yaml."""
    return sorted(EXPERIMENTS.glob("*.yaml"))


def experiment_path(name):
    """The file of the experiment called `name`, or `name` itself if it is a path to a YAML or JSON file."""
    if str(name).endswith(SUFFIXES):
        return pathlib.Path(name)
    path = EXPERIMENTS / f"{name}.yaml"
    if not path.is_file():
        from . import cluster_experiments

        known = ", ".join([p.stem for p in experiment_files()] + sorted(cluster_experiments.EXPERIMENTS))
        raise UsageError(f"unknown experiment '{name}' (known: {known}; or the path of a .yaml or .json file)")
    return path


def setting_text(value):
    """A JSON value as soc_sim's --set key=value reads it."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def run_folder_name(label):
    return re.sub(r"[^A-Za-z0-9.-]+", "_", label).strip("_") or "run"


def soc_sim_command(soc_sim, spec, run, frames, folder, overrides=None):
    command = [
        str(soc_sim),
        "--backend",
        run["backend"],
        "--app",
        run["app"],
        "--frames",
        str(frames),
        "--out",
        str(folder),
        "--force",
        "--quiet",
    ]
    if "config" in run:
        command += ["--config", str(ROOT / run["config"])]
    for key, value in {**spec["set"], **run["set"], **(overrides or {})}.items():
        command += ["--set", f"{key}={setting_text(value)}"]
    if run["args"]:
        command += ["--"] + run["args"]
    return command


def run_all(spec, name, soc_sim, out, frames_override, quiet, overrides, runs):
    results = []
    for run in runs:
        frames = frames_override or run.get("frames", spec["frames"])
        folder = out / "runs" / run_folder_name(run["label"])
        folder.mkdir(parents=True, exist_ok=True)
        command = soc_sim_command(soc_sim, spec, run, frames, folder, overrides)
        if not quiet:
            print(f"[{name}] {run['label']}: {' '.join(command)}", file=sys.stderr, flush=True)
        start = time.monotonic()
        try:
            done = subprocess.run(
                command,
                capture_output=True,
                text=True,
                check=False,
                env={**os.environ, "SYSTEMC_DISABLE_COPYRIGHT_MESSAGE": "1"},
            )
        except OSError as error:
            raise UsageError(f"cannot run {soc_sim}: {error.strerror}") from error
        if done.returncode != 0:
            message = (done.stderr.strip() or done.stdout.strip()).splitlines()[-5:]
            raise RunError(
                f"run '{run['label']}' failed (soc_sim exit status {done.returncode}): "
                f"{' '.join(command)}\n  " + "\n  ".join(message)
            )
        stats_path = folder / "stats.json"
        try:
            document = json.loads(stats_path.read_text())
        except (OSError, json.JSONDecodeError) as error:
            raise RunError(f"run '{run['label']}': cannot read {stats_path}: {error}") from error
        shown = len(document.get("stats", {}).get("frames", []))
        # An application that is not a scene (study_shading, ...) shows none.
        expected = frames if run.get("shows_frames", True) else 0
        if shown != expected:
            raise RunError(f"run '{run['label']}': {shown} frames shown, {expected} expected ({stats_path})")
        wall = time.monotonic() - start
        if not quiet:
            print(f"[{name}] {run['label']}: done in {wall:.1f} s", file=sys.stderr, flush=True)
        results.append(RunResult(run, stats_path, document, wall))
    return results


def command_line_settings(args):
    """The settings --set gives every run, over the experiment's own. The host model and the array programs are
    chosen by --host and --program (run dimensions), not by --set."""
    settings, items = {}, {}
    for item in args.set:
        key, equals, value = item.partition("=")
        if not equals or not key.strip():
            raise UsageError(f"--set {item!r}: expected KEY=VALUE")
        settings[key.strip()] = value
        items[key.strip()] = item
    return check_overrides(settings, lambda key: f"--set {items[key]!r}")


def check_overrides(settings, where):
    """`settings` (key: value), which override every run's, if none of them chooses what --host and --program
    choose (run dimensions); UsageError starting with where(key) otherwise."""
    for key in settings:
        if key == "host.model":
            raise UsageError(f"{where(key)}: choose the host model with --host native|iss|both")
        if key in PROGRAM_KEYS.values():
            raise UsageError(f"{where(key)}: choose the array programs with --program study|tuned|both")
    return settings


def chosen(value, allowed, option):
    """The values --host or --program name (one of `allowed`, or both), or None when not given."""
    if value is None:
        return None
    if value == "both":
        return list(allowed)
    if value not in allowed:
        raise UsageError(f"{option} {value!r}: unknown (choose {', '.join(allowed)} or both)")
    return [value]


# ---------------------------------------------------------------------------


def list_experiments():
    for path in experiment_files():
        try:
            title = load_experiment(path)["title"]
        except UsageError as error:
            title = f"(malformed: {error})"
        print(f"{path.stem}  {title}")
    from . import cluster_experiments  # the cluster platform's: programs, not specs (it imports this module)

    for name, title in cluster_experiments.TITLES.items():
        print(f"{name}  {title}")


class Outcome:
    """What an experiment's runs gave: the runs' results, the rows of its table and of the study's (None without
    one), the Markdown text of both and the files written."""

    def __init__(self, spec, results, rows, study_rows, text, files):
        self.spec = spec
        self.results = results
        self.rows = rows
        self.study_rows = study_rows
        self.text = text
        self.files = files


def soc_sim_path(soc_sim):
    soc_sim = pathlib.Path(soc_sim) if soc_sim else DEFAULT_SOC_SIM
    if not soc_sim.is_file():
        raise UsageError(
            f"soc_sim not found at {soc_sim}: build it (cmake --preset default && "
            "cmake --build --preset default) or give its path with --soc-sim"
        )
    return soc_sim


def run_spec(spec, name, soc_sim, out, frames=None, quiet=True, overrides=None, hosts=None, programs=None):
    """Runs the checked experiment `spec` (load_experiment) into the folder `out` and writes its tables, CSVs
    and plot there (as <name>.md, ...): frames, when given, instead of the experiment's; overrides, settings of
    every run over the experiment's; hosts and programs, lists instead of its own. Returns the Outcome."""
    plt = import_pyplot()
    out.mkdir(parents=True, exist_ok=True)
    runs = expand_runs(spec, hosts, programs)
    try:
        results = run_all(spec, name, soc_sim, out, frames, quiet, overrides or {}, runs)
        rows = build_table(spec["columns"], results)
        study_rows = build_table(spec["study"]["columns"], results) if "study" in spec else None
        hosts = sorted({result.host for result in results})
    except RunError as error:
        raise RunError(f"experiment '{name}': {error}") from error
    # Which host model made the figures, as the runs' own configurations say.
    footer = f"\nHost model: {', '.join(hosts)} (`host.model`).\n"
    table = markdown(spec["label_header"], spec["columns"], rows) + footer
    text = f"## {spec['title']}\n\n" + (f"{spec['description']}\n\n" if spec["description"] else "") + table
    write_csv(spec["columns"], rows, out / f"{name}.csv")
    files = f"table {out / (name + '.md')}, CSV {out / (name + '.csv')}"
    if study_rows is not None:
        study = spec["study"]
        text += (
            f"\n## {study['title']}\n\n"
            + (f"{study['description']}\n\n" if study["description"] else "")
            + markdown(spec["label_header"], study["columns"], study_rows)
            + footer
        )
        write_csv(study["columns"], study_rows, out / f"{name}_study.csv")
        files += f", study's CSV {out / (name + '_study.csv')}"
    (out / f"{name}.md").write_text(text)
    plot(spec, rows, out / f"{name}.png", plt)
    return Outcome(spec, results, rows, study_rows, text, f"{files}, plot {out / (name + '.png')}")


def run_experiment(name, args):
    path = experiment_path(name)
    spec = load_experiment(path)
    name = path.stem
    soc_sim = soc_sim_path(args.soc_sim)
    out = pathlib.Path(args.out) if args.out else ROOT / "out" / "experiments" / name
    if len(args.experiments) > 1 and args.out:
        out = out / name
    started = time.monotonic()
    outcome = run_spec(
        spec,
        name,
        soc_sim,
        out,
        args.frames,
        args.quiet,
        command_line_settings(args),
        chosen(args.host, HOSTS, "--host"),
        chosen(args.program, PROGRAMS, "--program"),
    )
    print(outcome.text)
    print(f"{outcome.files}\n")
    results = outcome.results
    hosts = sorted({result.host for result in results})
    by_host = ", ".join(f"{host} {sum(r.wall_seconds for r in results if r.host == host):.1f} s" for host in hosts)
    print(f"[{name}] wall time: {time.monotonic() - started:.1f} s ({by_host})", file=sys.stderr, flush=True)


def add_arguments(parser):
    """The options of an experiment's run (scripts/experiment.py's, tessera-sweep run's)."""
    parser.add_argument("--soc-sim", help=f"the soc_sim to run (default: {DEFAULT_SOC_SIM.relative_to(ROOT)})")
    parser.add_argument(
        "--out",
        help="output folder (default: out/experiments/<name>; with several "
        "experiments, one folder per experiment inside it)",
    )
    parser.add_argument(
        "--frames", type=int, help="frames of every run instead of the experiment's own (e.g. 1 for a quick check)"
    )
    parser.add_argument("--quiet", "-q", action="store_true", help="print the tables only, not each soc_sim run")
    parser.add_argument(
        "--host",
        metavar="native|iss|both",
        help="the host models the runs are made on (host.model): native, the host-compiled model, "
        "iss, the driver as ARM code on the ISS, or both; default: the experiment's 'hosts' "
        "(native unless it lists others); the tables say which",
    )
    parser.add_argument(
        "--program",
        metavar="study|tuned|both",
        help="the array programs of the ap-tile and ap-pixel runs (ap.tile.program, "
        "ap.pixel.program): study, the study's program as its compiler wrote it, tuned, or "
        "both; default: the experiment's 'programs' (none: the configured one); the tables say "
        "which",
    )
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="a configuration setting for every run, over the experiment's own (repeatable; "
        "docs/configuration.md lists the keys)",
    )


def run_command(args, prog):
    """Runs the experiments args.experiments names (or lists them with args.list); the exit status."""
    try:
        if args.list:
            list_experiments()
            return 0
        if not args.experiments:
            raise UsageError("name an experiment (--list lists them)")
        if args.frames is not None:
            positive_int("--frames", args.frames)
        chosen(args.host, HOSTS, "--host")
        chosen(args.program, PROGRAMS, "--program")
        command_line_settings(args)
        for name in args.experiments:
            run_experiment(name, args)
    except UsageError as error:
        print(f"{prog}: {error}", file=sys.stderr)
        return EXIT_USAGE
    except RunError as error:
        print(f"{prog}: {error}", file=sys.stderr)
        return EXIT_FAILED
    return 0


def main(argv=None, prog="experiment.py"):
    """scripts/experiment.py's command line: EXPERIMENT... [options], or --list; a cluster experiment
    (cluster_experiments.py) with its own options."""
    from . import cluster_experiments

    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] and argv[0] in cluster_experiments.EXPERIMENTS:
        return cluster_experiments.main(argv, prog)
    parser = argparse.ArgumentParser(
        prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument(
        "experiments",
        nargs="*",
        metavar="EXPERIMENT",
        help="an experiment's name (experiments/<name>.yaml) or a .yaml or .json file",
    )
    parser.add_argument("--list", action="store_true", help="list the experiments and exit")
    add_arguments(parser)
    return run_command(parser.parse_args(argv), prog)
