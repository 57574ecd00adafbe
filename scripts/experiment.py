#!/usr/bin/python3
"""Runs one of the study's experiments and prints its table.

An experiment is a JSON file, configs/experiments/<name>.json, that lists
soc_sim runs (back end, application and its arguments, frames, configuration
settings), or a matrix of them (applications x back ends x every combination
of some switches), and the table's columns (statistics of stats.json,
configuration values, or figures computed from them). This script runs
soc_sim once per run, reads each run's stats.json, prints the table in
Markdown and writes, in the output folder (default out/experiments/<name>):

    <name>.md   the table (and the study's)
    <name>.csv  the same values, unrounded, one row per run
    <name>_study.csv  the study's table's values, if it has one
    <name>.png  the plot the experiment asks for (matplotlib)
    runs/<run>/ each run's frames and stats.json

    scripts/experiment.py --list
    scripts/experiment.py fullscreen_rect
    scripts/experiment.py teapot --frames 1 --out out/quick
    scripts/experiment.py my_experiment.json --soc-sim build/sanitize/bin/soc_sim
    scripts/experiment.py teapot --host iss --frames 1 --out out/teapot_iss
    scripts/experiment.py fullscreen_rect --host both --program study
    scripts/experiment.py dma_whatif --set ciu.read_cycles=40 --out out/whatif_ciu

An experiment's runs are made on each host model it lists ("hosts":
native, the host-compiled model, or iss, the driver as ARM code on the ISS)
and, for ap-tile and ap-pixel, with each array program it lists
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
and how to add an experiment. The script runs under Debian's python3, the
one scripts/setup.sh installs python3-matplotlib for.

Exit status: 0 on success; 2 for a bad command line, an unknown experiment,
a malformed experiment file, a missing soc_sim or a missing matplotlib; 1
when a soc_sim run fails or its statistics lack a figure the table needs.
"""

import argparse
import csv
import itertools
import json
import math
import os
import pathlib
import re
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
EXPERIMENTS = ROOT / "configs" / "experiments"
DEFAULT_SOC_SIM = ROOT / "build" / "default" / "bin" / "soc_sim"

EXIT_FAILED = 1
EXIT_USAGE = 2


class UsageError(Exception):
    """Bad input: the command line, an experiment file, a missing tool (status 2)."""


class RunError(Exception):
    """A soc_sim run failed or gave statistics the table cannot use (status 1)."""


# ---------------------------------------------------------------------------
# Figures computed from a run's statistics ("value" columns). Each takes the
# run's result, the column and every run's result (for figures relative to
# another run) and returns a number, or None where the run has no such
# figure. docs/experiments.md lists them.


def stat(result, path, required=True):
    """The statistic at the dotted `path` of stats.json's "stats"."""
    node = result.stats
    for part in path.split("."):
        if not isinstance(node, dict) or part not in node:
            if required:
                raise RunError(f"run '{result.label}' has no statistic '{path}' in {result.stats_path}")
            return None
        node = node[part]
    if isinstance(node, bool) or not isinstance(node, (int, float)):
        raise RunError(f"run '{result.label}': statistic '{path}' is not a number in {result.stats_path}")
    return node


def stats_required(column):
    """Whether the column's statistics must exist ("required", default true): false tolerates a run that lacks one
    (an empty cell), e.g. a block that only exists with a switch on."""
    return column.get("required", True)


def frames_drawn(result):
    """The divisor of "per frame": the frames shown; a run of an application that shows none (study_shading, ...)
    counts as one, so its figures "per frame" are per run."""
    return len(result.stats["frames"]) if result.shows_frames else 1


def frame_time_ms(result, column, results):
    """Mean simulated time per frame: the frames' render_ns (request to request), in ms."""
    frames = result.stats["frames"]
    if not frames:
        raise RunError(f"run '{result.label}' shows no frame, so it has no time per frame ({result.stats_path})")
    return sum(frame["render_ns"] for frame in frames) / len(frames) / 1e6


def frame_or_run_time_ms(result, column, results):
    """frame_time_ms for a scene; for a study application, which shows no frame, its whole host time
    (driver.study.total_ns), in ms."""
    if result.shows_frames:
        return frame_time_ms(result, column, results)
    return stat(result, "driver.study.total_ns") / 1e6


def renderer_section(result):
    """The path of the back end's statistics in stats.json: driver.ap_tile for ap-tile, ..."""
    return "driver." + result.backend.replace("-", "_")


HOST_PARTS = ("compute", "write", "read", "wait", "frame_out")


def host_time_ms(result, column, results):
    """One part (column "part": compute, write, read, wait or frame_out) of the host's time, in ms per frame: an
    array back end's host_<part>_ns (driver.ap_tile, driver.ap_pixel), or for a study application the whole run's
    driver.study.<part>_ns (frame_out: none, the study shows no frame)."""
    if result.shows_frames:
        path = f"{renderer_section(result)}.host_{column['part']}_ns"
    else:
        path = f"driver.study.{column['part']}_ns"
    value = stat(result, path, stats_required(column))
    return None if value is None else value / frames_drawn(result) / 1e6


def values_written_per_triangle(result, column, results):
    """Values the array's data lines carried into CMEM per triangle: the back end's values_written over its
    triangles (driver.ap_tile, driver.ap_pixel)."""
    section = renderer_section(result)
    written = stat(result, f"{section}.values_written", stats_required(column))
    triangles = stat(result, f"{section}.triangles", stats_required(column))
    if written is None or triangles is None:
        return None
    if triangles == 0:
        raise RunError(f"run '{result.label}': '{section}.triangles' is 0, so values per triangle is undefined")
    return written / triangles


def frames_per_second(result, column, results):
    """Frames per simulated second, from frame_time_ms."""
    return 1000.0 / frame_time_ms(result, column, results)


def energy_per_frame_mj(result, column, results):
    """Mean energy per frame of the energy model (tlm/power/README.md): the frames' own energy.total_j (request to
    request, start-up excluded), in mJ; for a study application, which shows no frame, the whole run's
    energy.total_j."""
    if result.shows_frames:
        frames = result.stats["frames"]
        if not frames:
            raise RunError(f"run '{result.label}' shows no frame, so it has no energy per frame ({result.stats_path})")
        if any(not isinstance(frame.get("energy", {}).get("total_j"), (int, float)) for frame in frames):
            raise RunError(f"run '{result.label}': a frame record has no energy.total_j in {result.stats_path}")
        return sum(frame["energy"]["total_j"] for frame in frames) / len(frames) * 1e3
    return stat(result, "energy.total_j") * 1e3


def baseline_result(result, column, results):
    """The run a relative figure compares `result` with: the run of the experiment's label column["baseline"]
    (before the host and the program are added to it), or the run's own "baseline" (a run doing other work than
    the column's baseline, e.g. more attributes), on the same host, with the same program if it has one."""
    name = result.baseline or column["baseline"]
    candidates = [r for r in results if r.base_label == name and r.host == result.host]
    if not candidates:
        raise RunError(f"run '{result.label}': no run '{name}' on host {result.host} to compare with")
    return next((r for r in candidates if r.program == result.program), candidates[0])


def energy_ratio(result, column, results):
    """The baseline run's energy_per_frame_mj over this run's (column "baseline": the run's label): how many times
    less energy this run spends on a frame (on the whole run for a study application)."""
    baseline = baseline_result(result, column, results)
    return energy_per_frame_mj(baseline, column, results) / energy_per_frame_mj(result, column, results)


def speedup(result, column, results):
    """The baseline run's frame_time_ms over this run's (column "baseline": the run's label)."""
    baseline = baseline_result(result, column, results)
    return frame_time_ms(baseline, column, results) / frame_time_ms(result, column, results)


AP_TILE_PASS_STAGES = ("fill", "depth", "colour", "texcoord")


def ap_tile_pass_cycles(result, column, results):
    """Array cycles of one ap-tile pass: the four pass stages' cycles over the passes (clears excluded)."""
    cycles = sum(stat(result, f"driver.ap_tile.cycles.{stage}") for stage in AP_TILE_PASS_STAGES)
    return cycles / stat(result, "driver.ap_tile.passes")


def ap_tile_pass_us(result, column, results):
    """ap_tile_pass_cycles at the array's clock (array.clock_mhz), in microseconds."""
    return ap_tile_pass_cycles(result, column, results) / config(result, "array.clock_mhz")


def ap_tile_passes_per_second(result, column, results):
    """The array's clock over ap_tile_pass_cycles: passes per second with the host never in the way."""
    return config(result, "array.clock_mhz") * 1e6 / ap_tile_pass_cycles(result, column, results)


def ap_tile_cus_per_pass(result, column, results):
    """CUs with a triangle, per pass: triangle records (driver.ap_tile.cu_triangles) over passes."""
    return stat(result, "driver.ap_tile.cu_triangles") / stat(result, "driver.ap_tile.passes")


def ap_tile_peak_triangles_per_second(result, column, results):
    """ap_tile_cus_per_pass x ap_tile_passes_per_second: one triangle per busy CU per pass."""
    return ap_tile_cus_per_pass(result, column, results) * ap_tile_passes_per_second(result, column, results)


def study_shades_per_second(result, column, results):
    """Shades per second of host time, per result: driver.study.shades over driver.study.total_ns (inputs loaded,
    shades computed or sent, run and read back)."""
    return stat(result, "driver.study.shades") / (stat(result, "driver.study.total_ns") * 1e-9)


def study_shades_per_second_per_pass(result, column, results):
    """Shades per second of array time alone: driver.study.shades over driver.study.array_cycles at the array's
    clock (array.clock_mhz), the host's traffic not counted."""
    seconds = stat(result, "driver.study.array_cycles") / (config(result, "array.clock_mhz") * 1e6)
    return stat(result, "driver.study.shades") / seconds


def patch_break_even(result, column, results):
    """The smallest patch of the column's "shape" (line or square) at which the baseline run (column "baseline",
    the host) takes longer than this run: driver.study.patch.<shape>.<pixels>_ns compared size by size; inf when
    the baseline is faster at every size measured."""
    baseline = baseline_result(result, column, results)
    sizes = sorted(int(key[: -len("_ns")]) for key in result.stats["driver"]["study"]["patch"][column["shape"]])
    for pixels in sizes:
        path = f"driver.study.patch.{column['shape']}.{pixels}_ns"
        if stat(baseline, path) > stat(result, path):
            return float(pixels)
    return math.inf


# ---------------------------------------------------------------------------
# The study's quantities (docs/spec/study_programs.md, "The study's test cases"): what the study's own figure
# covered, for the "study" tables. A column names the test's quantity ("quantity"); each back end's part of it:
#
#   rasterization  arm: the rasterization phase without the clears (host_rasterization_ns - host_clear_ns of
#                  the frame records); ap-tile: the array's passes (the cycles of its pass stages), per frame
#   pass           ap-tile: the array's cycles of one pass, at its clock
#   processing     the frame without its frame out to the display: arm, render_ns - host_presenting_ns (the copy
#                  to the display port); an array back end, render_ns - host_frame_out_ns
#   shading        arm: the shading loop (driver.study.compute_ns); ap-pixel: the array's passes
#                  (driver.study.array_cycles), the host's CIU transfers apart
#
# The study's energy is the energy of the units the board measured (the ARM922T for arm; the array controller,
# the CIU and the CUs for an array back end) over that interval: for the array's passes exactly, from
# stats.energy.array_stages (each stage's own activity and time); otherwise from the frame records or the run.

QUANTITIES = ("rasterization", "pass", "processing", "shading")
ARRAY_UNITS = ("array_controller", "ciu", "cu_array")


def frames_mean(result, figure):
    """The mean over the frames of a frame record's figure: `figure` is a function of the record."""
    frames = result.stats["frames"]
    if not frames:
        raise RunError(f"run '{result.label}' shows no frame ({result.stats_path})")
    try:
        return sum(figure(frame) for frame in frames) / len(frames)
    except KeyError as error:
        raise RunError(f"run '{result.label}': a frame record lacks {error} in {result.stats_path}") from error


def array_pass_stages(result):
    """The stages of the array's passes: ap-tile's four (its clears are not passes); every stage ap-pixel ran."""
    if result.backend == "ap-tile":
        return AP_TILE_PASS_STAGES
    return tuple(result.stats.get("energy", {}).get("array_stages", {}))


def study_divisor(result, quantity):
    """What the study's figure is per: a pass (pass), a frame (rasterization, processing), the run (shading)."""
    if quantity == "pass":
        return stat(result, "driver.ap_tile.passes")
    if quantity == "shading":
        return 1
    return frames_drawn(result)


def unsupported(result, quantity):
    return RunError(f"run '{result.label}': the study's {quantity} figure is not defined for back end "
                    f"'{result.backend}'")


def study_time_ms(result, column, results):
    """The study's time (column "quantity", above), in ms."""
    quantity = column["quantity"]
    backend = result.backend
    if quantity == "processing":
        if backend == "arm":
            return frames_mean(result, lambda f: f["render_ns"] - f["driver"]["host_presenting_ns"]) / 1e6
        return frames_mean(result, lambda f: f["render_ns"] - f["driver"]["host_frame_out_ns"]) / 1e6
    if backend == "arm" and quantity == "rasterization":
        return frames_mean(result, lambda f: f["driver"]["host_rasterization_ns"] - f["driver"]["host_clear_ns"]) / 1e6
    if backend == "arm" and quantity == "shading":
        return stat(result, "driver.study.compute_ns") / 1e6
    if backend == "ap-tile" and quantity in ("rasterization", "pass"):
        cycles = sum(stat(result, f"driver.ap_tile.cycles.{stage}") for stage in AP_TILE_PASS_STAGES)
    elif backend == "ap-pixel" and quantity == "shading":
        cycles = stat(result, "driver.study.array_cycles")
    else:
        raise unsupported(result, quantity)
    return cycles / (config(result, "array.clock_mhz") * 1e6) / study_divisor(result, quantity) * 1e3


def static_watts(result, units):
    """The static powers of `units` (power.<unit>.static_mw of the run's configuration), in W."""
    return sum(config(result, f"power.{unit}.static_mw") for unit in units) / 1e3


def host_executing_watts(result):
    """The ARM922T's average power while it executes (its busy and stalled cycles, idle ones left out) over the
    run, in W: the host's power over an interval in which it never idles, as the study's ARM loops."""
    events = result.stats.get("energy", {}).get("units", {}).get("host", {}).get("events", {})
    try:
        joules = events["busy_cycles"]["j"] + events["stalled_cycles"]["j"]
        cycles = events["busy_cycles"]["count"] + events["stalled_cycles"]["count"]
    except KeyError as error:
        raise RunError(f"run '{result.label}': stats.energy.units.host.events lacks {error} in "
                       f"{result.stats_path}") from error
    seconds = cycles / (stat(result, "host.clock_mhz") * 1e6)
    return joules / seconds + static_watts(result, ("host",))


def study_energy_mj(result, column, results):
    """The study's energy (column "quantity"): the energy of the units the board measured over the study's
    interval, in mJ. The array's passes: the array_stages energies of the pass stages (exact). An array back end's
    processing: the frames' array-unit energy less their static power over the frame out (the array idles then).
    arm: host_executing_watts x the study's time (the host's power over the run, not the interval alone)."""
    quantity = column["quantity"]
    if result.backend == "arm":
        return host_executing_watts(result) * study_time_ms(result, column, results)
    if quantity == "processing":
        watts = static_watts(result, ARRAY_UNITS)
        return frames_mean(result, lambda f: sum(f["energy"]["units"][unit]["total_j"] for unit in ARRAY_UNITS)
                           - watts * f["driver"]["host_frame_out_ns"] * 1e-9) * 1e3
    study_time_ms(result, column, results)  # the quantity applies to the back end
    stages = result.stats.get("energy", {}).get("array_stages", {})
    missing = [stage for stage in array_pass_stages(result) if stage not in stages]
    if missing or not stages:
        raise RunError(f"run '{result.label}' has no statistic 'energy.array_stages.{(missing or ['*'])[0]}' in "
                       f"{result.stats_path}")
    joules = sum(stages[stage]["total_j"] for stage in array_pass_stages(result))
    return joules / study_divisor(result, quantity) * 1e3


def study_power_mw(result, column, results):
    """study_energy_mj over study_time_ms: the measured units' average power over the study's interval, in mW."""
    return study_energy_mj(result, column, results) / study_time_ms(result, column, results) * 1e3


def study_speedup(result, column, results):
    """The baseline run's study_time_ms over this run's (column "baseline")."""
    return study_time_ms(baseline_result(result, column, results), column, results) / study_time_ms(
        result, column, results)


def study_energy_ratio(result, column, results):
    """The baseline run's study_energy_mj over this run's (column "baseline")."""
    return study_energy_mj(baseline_result(result, column, results), column, results) / study_energy_mj(
        result, column, results)


def study_shades_per_second_of_study_time(result, column, results):
    """Shades per second of the study's time ("quantity": shading): driver.study.shades over study_time_ms."""
    return stat(result, "driver.study.shades") / (study_time_ms(result, column, results) * 1e-3)


COMPUTED = {
    function.__name__: function
    for function in (
        frame_time_ms,
        frame_or_run_time_ms,
        frames_per_second,
        speedup,
        energy_per_frame_mj,
        energy_ratio,
        ap_tile_pass_cycles,
        ap_tile_pass_us,
        ap_tile_passes_per_second,
        ap_tile_cus_per_pass,
        ap_tile_peak_triangles_per_second,
        study_shades_per_second,
        study_shades_per_second_per_pass,
        patch_break_even,
        host_time_ms,
        values_written_per_triangle,
        study_time_ms,
        study_energy_mj,
        study_power_mw,
        study_speedup,
        study_energy_ratio,
        study_shades_per_second_of_study_time,
    )
}
BASELINE_VALUES = ("speedup", "energy_ratio", "patch_break_even", "study_speedup", "study_energy_ratio")
QUANTITY_VALUES = ("study_time_ms", "study_energy_mj", "study_power_mw", "study_speedup", "study_energy_ratio",
                   "study_shades_per_second_of_study_time")


def config(result, key):
    """The effective configuration's value of the dotted `key` (stats.json's "config")."""
    node = result.config
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            raise RunError(f"run '{result.label}' has no configuration key '{key}' in {result.stats_path}")
        node = node[part]
    return node


# ---------------------------------------------------------------------------
# The experiment file.

TOP_KEYS = {"title", "description", "frames", "set", "runs", "matrix", "label_header", "columns", "plot", "hosts",
            "programs", "study"}
STUDY_KEYS = {"title", "description", "columns"}
HOSTS = ("native", "iss")
PROGRAMS = ("study", "tuned")
# The array back ends' program keys; the other back ends run no array program.
PROGRAM_KEYS = {"ap-tile": "ap.tile.program", "ap-pixel": "ap.pixel.program"}
RUN_KEYS = {"label", "backend", "app", "args", "set", "frames", "shows_frames", "baseline"}
MATRIX_KEYS = {"switches", "skip", "runs"}
SWITCH_KEYS = {"key", "name", "values", "backends"}
MATRIX_RUN_KEYS = (RUN_KEYS - {"backend"}) | {"backends"}
COLUMN_KEYS = {"key", "header", "stat", "config", "value", "per", "scale", "format", "backends", "baseline", "shape",
               "part", "required", "may_be_zero", "quantity"}
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
            raise UsageError(f"{switch_where}: 'name' (the run labels' word for it) must be a word of letters, "
                             "digits, '.', '_' and '-'")
        if switch["name"] in names:
            raise UsageError(f"{switch_where}: name '{switch['name']}' is used twice (the labels would not tell "
                             "the switches apart)")
        names.add(switch["name"])
        values = switch.setdefault("values", [False, True])
        if not isinstance(values, list) or not values or not all(is_setting_value(v) for v in values):
            raise UsageError(f"{switch_where} ('{switch['key']}'): 'values' must be a non-empty list of strings, "
                             "numbers or booleans")
        if any(same_value(a, b) for i, a in enumerate(values) for b in values[i + 1:]):
            raise UsageError(f"{switch_where} ('{switch['key']}'): a value is listed twice")
        if "backends" in switch and not non_empty_strings(switch["backends"]):
            raise UsageError(f"{switch_where} ('{switch['key']}'): 'backends' must be a non-empty list of back-end "
                             "names")


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
                raise UsageError(f"{skip_where}: '{key}' is not a switch of the matrix "
                                 f"({', '.join(by_key) or 'it has none'})")
            if not any(same_value(value, v) for v in by_key[key]["values"]):
                raise UsageError(f"{skip_where}: {json.dumps(value)} is not one of the values of '{key}' "
                                 f"({', '.join(json.dumps(v) for v in by_key[key]['values'])}), so it skips nothing")


def skipped(settings, skips):
    """Whether a combination of switch settings matches every key of one of the "skip" objects."""
    return any(all(key in settings and same_value(settings[key], value) for key, value in skip.items())
               for skip in skips)


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
            combinations = [dict(zip((switch["key"] for switch in applying), values))
                            for values in itertools.product(*(switch["values"] for switch in applying))]
            kept = [settings for settings in combinations if not skipped(settings, skips)]
            if not kept:
                raise UsageError(f"{run_where}: 'skip' leaves no combination of the switches for back end "
                                 f"'{backend}'")
            for settings in kept:
                variant = " ".join(part for part in (switch_label(switch, settings[switch["key"]])
                                                     for switch in applying) if part)
                label = f"{group} {variant}" if variant else group
                run = {key: value for key, value in template.items() if key != "backends"}
                run.update(label=label, backend=backend, set={**template["set"], **settings})
                runs.append(run)
                wheres.append(f"{run_where} ('{label}')")
                cells[label] = (group, variant)
    return runs, wheres, cells


def load_experiment(path):
    """The experiment at `path`, checked; UsageError naming the file and what is wrong."""
    try:
        spec = json.loads(path.read_text())
    except OSError as error:
        raise UsageError(f"cannot read {path}: {error.strerror}") from error
    except json.JSONDecodeError as error:
        raise UsageError(f"{path} is not valid JSON: {error}") from error
    where = str(path)
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
    spec["run_groups"] = {run["label"]: (run["label"], "") for run in runs if isinstance(run, dict)
                      and isinstance(run.get("label"), str)}
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
            raise UsageError(f"{run_where}: label '{run['label']}' is used twice (or names the same folder as "
                             "another: runs/" + run_folder_name(run["label"]) + ")")
        labels.add(run["label"])
        folders.add(run_folder_name(run["label"]))
        run.setdefault("args", [])
        if not isinstance(run["args"], list) or not all(isinstance(a, str) for a in run["args"]):
            raise UsageError(f"{run_where}: 'args' must be a list of strings")
        check_settings(run_where, run.setdefault("set", {}))
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
            raise UsageError(f"{column_where}: key '{key}' is used twice (or is 'run', 'host' or 'program', the "
                             "columns every table starts with)")
        keys.add(key)
        column.setdefault("header", key)
        sources = [source for source in ("stat", "config", "value") if source in column]
        if len(sources) != 1:
            raise UsageError(f"{column_where} ('{key}') needs exactly one of 'stat', 'config' and 'value'")
        if "value" in column and column["value"] not in COMPUTED:
            raise UsageError(f"{column_where} ('{key}'): unknown value '{column['value']}' "
                             f"(known: {', '.join(COMPUTED)})")
        if column.get("value") in BASELINE_VALUES and column.get("baseline") not in labels:
            raise UsageError(f"{column_where} ('{key}'): 'baseline' must be the label of a run "
                             f"({', '.join(sorted(labels))})")
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
                raise UsageError(f"{column_where} ('{key}'): bad 'format' {json.dumps(column['format'])} "
                                 "(a Python format for a number, e.g. \",.2f\")") from error
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
            raise UsageError(f"{column_where} ('{key}'): 'quantity' goes with the values {', '.join(QUANTITY_VALUES)}, "
                             "which need it")
        if "quantity" in column and column["quantity"] not in QUANTITIES:
            raise UsageError(f"{column_where} ('{key}'): 'quantity' must be one of {', '.join(QUANTITIES)}")



def choice_list(where, key, value, allowed):
    if not isinstance(value, list) or not value or len(set(map(str, value))) != len(value) \
            or not all(v in allowed for v in value):
        raise UsageError(f"{where}: '{key}' must be a non-empty list of distinct values of {', '.join(allowed)}, "
                         f"got {json.dumps(value)}")
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
            for program in (programs if key and programs else [None]):
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


def experiment_path(name):
    """The file of the experiment called `name`, or `name` itself if it is a path to a JSON file."""
    if name.endswith(".json"):
        return pathlib.Path(name)
    path = EXPERIMENTS / f"{name}.json"
    if not path.is_file():
        known = ", ".join(p.stem for p in sorted(EXPERIMENTS.glob("*.json")))
        raise UsageError(f"unknown experiment '{name}' (known: {known}; or the path of a .json file)")
    return path


# ---------------------------------------------------------------------------
# Running soc_sim.


class RunResult:
    def __init__(self, run, stats_path, document, wall_seconds=0.0):
        self.label = run["label"]
        self.base_label = run.get("base_label", run["label"])
        self.baseline = run.get("baseline")
        self.backend = run["backend"]
        self.shows_frames = run.get("shows_frames", True)
        self.stats_path = stats_path
        self.stats = document["stats"]
        self.config = document["config"]
        self.wall_seconds = wall_seconds
        # The host model and array program the run used, as its own configuration says ("-": no array program).
        self.host = str(self.config.get("host", {}).get("model", "native"))
        key = PROGRAM_KEYS.get(self.backend)
        self.program = "-"
        if key:
            node = self.config
            for part in key.split("."):
                node = node.get(part, {}) if isinstance(node, dict) else {}
            self.program = node if isinstance(node, str) and node else "-"


def setting_text(value):
    """A JSON value as soc_sim's --set key=value reads it."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def run_folder_name(label):
    return re.sub(r"[^A-Za-z0-9.-]+", "_", label).strip("_") or "run"


def soc_sim_command(soc_sim, spec, run, frames, folder, overrides=None):
    command = [str(soc_sim), "--backend", run["backend"], "--app", run["app"], "--frames", str(frames),
               "--out", str(folder), "--force", "--quiet"]
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
            done = subprocess.run(command, capture_output=True, text=True, check=False,
                                  env={**os.environ, "SYSTEMC_DISABLE_COPYRIGHT_MESSAGE": "1"})
        except OSError as error:
            raise UsageError(f"cannot run {soc_sim}: {error.strerror}") from error
        if done.returncode != 0:
            message = (done.stderr.strip() or done.stdout.strip()).splitlines()[-5:]
            raise RunError(f"run '{run['label']}' failed (soc_sim exit status {done.returncode}): "
                           f"{' '.join(command)}\n  " + "\n  ".join(message))
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
    settings = {}
    for item in args.set:
        key, equals, value = item.partition("=")
        if not equals or not key.strip():
            raise UsageError(f"--set {item!r}: expected KEY=VALUE")
        key = key.strip()
        if key == "host.model":
            raise UsageError(f"--set {item!r}: choose the host model with --host native|iss|both")
        if key in PROGRAM_KEYS.values():
            raise UsageError(f"--set {item!r}: choose the array programs with --program study|tuned|both")
        settings[key] = value
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
# The table.


def cell_value(column, result, results):
    """The column's number for one run, or None where the column does not apply to its back end."""
    if "backends" in column and result.backend not in column["backends"]:
        return None
    if "stat" in column:
        value = stat(result, column["stat"], stats_required(column))
        per = column.get("per")
        if value is None:
            pass
        elif per == "frame":
            value = value / frames_drawn(result)
        elif per is not None:
            divisor = stat(result, per, stats_required(column))
            if divisor == 0:
                raise RunError(f"run '{result.label}': '{per}' is 0, so '{column['stat']}' per it is undefined")
            value = None if divisor is None else value / divisor
    elif "config" in column:
        value = config(result, column["config"])
    else:
        value = COMPUTED[column["value"]](result, column, results)
    if "scale" in column and isinstance(value, (int, float)) and not isinstance(value, bool):
        value = value * column["scale"]
    return value


def format_cell(column, value):
    if value is None:
        return "-"
    if isinstance(value, str):
        return value
    if "format" in column:
        return format(value, column["format"])
    if isinstance(value, bool):
        return str(value).lower()
    return format(value, ",") if isinstance(value, int) else format(value, ",.2f")


# The columns every table starts with, after the run's label: the host model and the array program it ran.
RUN_COLUMNS = [{"key": "host", "header": "host"}, {"key": "program", "header": "program"}]


def build_table(columns, results):
    """Rows of (label, [host, program, value per column]) in the runs' order."""
    return [(result.label, [result.host, result.program]
             + [cell_value(column, result, results) for column in columns]) for result in results]


def markdown(label_header, columns, rows):
    columns = RUN_COLUMNS + columns
    headers = [label_header] + [column["header"] for column in columns]
    lines = ["| " + " | ".join(headers) + " |",
             "|" + "---|" + "".join(":--|" if column in RUN_COLUMNS else "--:|" for column in columns)]
    for label, values in rows:
        cells = [format_cell(column, value) for column, value in zip(columns, values)]
        lines.append("| " + " | ".join([label] + cells) + " |")
    return "\n".join(lines) + "\n"


def csv_text(value):
    if value is None:
        return ""
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, float):
        return format(value, ".10g")
    return str(value)


def write_csv(columns, rows, path):
    with path.open("w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(["run"] + [column["key"] for column in RUN_COLUMNS + columns])
        for label, values in rows:
            writer.writerow([label] + [csv_text(value) for value in values])


# ---------------------------------------------------------------------------
# The plot.


def import_pyplot():
    try:
        import matplotlib
    except ImportError as error:
        raise UsageError(f"matplotlib is missing for {sys.executable}: install python3-matplotlib "
                         "(scripts/setup.sh) or run the script with Debian's python3") from error
    matplotlib.use("Agg")  # files only, no display needed
    import matplotlib.pyplot as plt

    return plt


def plot_groups(spec, rows, index, groups, axes):
    """The column at `index` as bars grouped by the matrix's run and back end, one bar per switch combination, in
    the same colour in every group; a group without a combination has a gap there."""
    variants = list(dict.fromkeys(spec["run_groups"][label][1] for label, _ in rows))
    values = {spec["run_groups"][label]: row[index] for label, row in rows}
    width = 0.8 / len(variants)
    for number, variant in enumerate(variants):
        offset = (number - (len(variants) - 1) / 2) * width
        bars = [(position + offset, float(values[(group, variant)])) for position, group in enumerate(groups)
                if values.get((group, variant)) is not None]
        axes.bar([x for x, _ in bars], [y for _, y in bars], width, label=variant or "none")
    axes.set_xticks(list(range(len(groups))))
    axes.set_xticklabels(groups, rotation=30, ha="right", fontsize=8)


def plot(spec, rows, path, plt):
    rows = [(label, values[len(RUN_COLUMNS):]) for label, values in rows]
    settings = spec["plot"]
    columns = {column["key"]: (index, column) for index, column in enumerate(spec["columns"])}
    labels = [label for label, _ in rows]

    def series(key):
        index, _ = columns[key]
        return [values[index] for _, values in rows]

    keys = settings["columns"]
    if settings.get("groups"):
        groups = list(dict.fromkeys(spec["run_groups"][label][0] for label in labels))
        figure, axes = plt.subplots(figsize=(max(6.0, 1.2 * len(groups) + 2.5), 5.0))
        plot_groups(spec, rows, columns[keys[0]][0], groups, axes)
    elif "x" in settings:
        figure, axes = plt.subplots(figsize=(max(6.0, 1.6 * len(labels) + 2.5), 4.5))
        x = series(settings["x"])
        for key in keys:
            y = [math.nan if v is None else v for v in series(key)]
            axes.plot(x, y, marker="o", label=columns[key][1]["header"])
        axes.set_xlabel(columns[settings["x"]][1]["header"])
    else:
        figure, axes = plt.subplots(figsize=(max(6.0, 1.6 * len(labels) + 2.5), 4.5))
        positions = list(range(len(labels)))
        stacked = settings.get("stacked", False)
        width = 0.6 if stacked else 0.8 / len(keys)
        bottom = [0.0] * len(labels)
        for number, key in enumerate(keys):
            values = [0.0 if v is None else float(v) for v in series(key)]
            offset = 0.0 if stacked else (number - (len(keys) - 1) / 2) * width
            bars = axes.bar([p + offset for p in positions], values, width, bottom=bottom if stacked else None,
                            label=columns[key][1]["header"])
            column = columns[key][1]
            axes.bar_label(bars, labels=[format_cell(column, v) if v else "" for v in values], fontsize=8,
                           label_type="center" if stacked else "edge")
            if stacked:
                bottom = [b + v for b, v in zip(bottom, values)]
        # Room above the tallest bar for its label and the legend.
        tallest = max(bottom) if stacked else max(max(0.0 if v is None else float(v) for v in series(k)) for k in keys)
        if tallest > 0 and not settings.get("log"):
            axes.set_ylim(0, tallest * 1.25)
        axes.set_xticks(positions)
        axes.set_xticklabels(labels)
        axes.set_xlabel(spec["label_header"])
    if settings.get("log"):
        axes.set_yscale("log")
    axes.set_ylabel(settings.get("ylabel", columns[keys[0]][1]["header"] if len(keys) == 1 else ""))
    axes.set_title(spec["title"], fontsize=10)
    axes.grid(True, axis="y", linewidth=0.3)
    if settings.get("groups"):
        axes.legend(fontsize=8, title="switches on", title_fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    elif len(keys) > 1:
        axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)


# ---------------------------------------------------------------------------


def list_experiments():
    for path in sorted(EXPERIMENTS.glob("*.json")):
        try:
            title = load_experiment(path)["title"]
        except UsageError as error:
            title = f"(malformed: {error})"
        print(f"{path.stem}  {title}")


def run_experiment(name, args):
    path = experiment_path(name)
    spec = load_experiment(path)
    name = path.stem
    soc_sim = pathlib.Path(args.soc_sim) if args.soc_sim else DEFAULT_SOC_SIM
    if not soc_sim.is_file():
        raise UsageError(f"soc_sim not found at {soc_sim}: build it (cmake --preset default && "
                         "cmake --build --preset default) or give its path with --soc-sim")
    plt = import_pyplot()
    out = pathlib.Path(args.out) if args.out else ROOT / "out" / "experiments" / name
    if len(args.experiments) > 1 and args.out:
        out = out / name
    out.mkdir(parents=True, exist_ok=True)

    overrides = command_line_settings(args)
    runs = expand_runs(spec, chosen(args.host, HOSTS, "--host"), chosen(args.program, PROGRAMS, "--program"))
    started = time.monotonic()
    try:
        results = run_all(spec, name, soc_sim, out, args.frames, args.quiet, overrides, runs)
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
        text += (f"\n## {study['title']}\n\n" + (f"{study['description']}\n\n" if study["description"] else "")
                 + markdown(spec["label_header"], study["columns"], study_rows) + footer)
        write_csv(study["columns"], study_rows, out / f"{name}_study.csv")
        files += f", study's CSV {out / (name + '_study.csv')}"
    (out / f"{name}.md").write_text(text)
    plot(spec, rows, out / f"{name}.png", plt)
    print(text)
    print(f"{files}, plot {out / (name + '.png')}\n")
    by_host = ", ".join(f"{host} {sum(r.wall_seconds for r in results if r.host == host):.1f} s" for host in hosts)
    print(f"[{name}] wall time: {time.monotonic() - started:.1f} s ({by_host})", file=sys.stderr, flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("experiments", nargs="*", metavar="EXPERIMENT",
                        help="an experiment's name (configs/experiments/<name>.json) or a .json file")
    parser.add_argument("--list", action="store_true", help="list the experiments and exit")
    parser.add_argument("--soc-sim", help=f"the soc_sim to run (default: {DEFAULT_SOC_SIM.relative_to(ROOT)})")
    parser.add_argument("--out", help="output folder (default: out/experiments/<name>; with several "
                                      "experiments, one folder per experiment inside it)")
    parser.add_argument("--frames", type=int, help="frames of every run instead of the experiment's own "
                                                   "(e.g. 1 for a quick check)")
    parser.add_argument("--quiet", "-q", action="store_true", help="print the tables only, not each soc_sim run")
    parser.add_argument("--host", metavar="native|iss|both",
                        help="the host models the runs are made on (host.model): native, the host-compiled model, "
                             "iss, the driver as ARM code on the ISS, or both; default: the experiment's 'hosts' "
                             "(native unless it lists others); the tables say which")
    parser.add_argument("--program", metavar="study|tuned|both",
                        help="the array programs of the ap-tile and ap-pixel runs (ap.tile.program, "
                             "ap.pixel.program): study, the study's program as its compiler wrote it, tuned, or "
                             "both; default: the experiment's 'programs' (none: the configured one); the tables say "
                             "which")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a configuration setting for every run, over the experiment's own (repeatable; "
                             "docs/configuration.md lists the keys)")
    args = parser.parse_args()
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
        print(f"experiment.py: {error}", file=sys.stderr)
        return EXIT_USAGE
    except RunError as error:
        print(f"experiment.py: {error}", file=sys.stderr)
        return EXIT_FAILED
    return 0


if __name__ == "__main__":
    sys.exit(main())
