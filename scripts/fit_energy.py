#!/usr/bin/env python3
"""Fits the energy model to every power and energy figure the board measured.

docs/spec/calibration.md gives ten figures: the average power of three units
(ARM922T; array controller + CIU; CUs + CMEM) while the board ran its two
test workloads (the full-screen rectangle: the ARM rendering it for the ARM
column, ap-tile for the array columns; the 192,000-shade loop: the ARM's
loop, ap-pixel), and four energies per operation (the host's addition and
multiplication loops, the array's CMEM addition and multiplication), plus
the ARM's idle power and its leakage, which are converted, not fitted
("table" lines of energy_params.def).

This script runs each figure's workload with soc_sim, takes the activity
within the interval the figure covers, and solves for the parameters the
figures identify (least squares of the relative residuals, every value
non-negative, the same values for every figure):

  host            one energy per cycle the ARM is not idle
  AC              one energy per broadcast (a CMEM multiply counts the
                  CMEM-operand additions it stands for: tlm/array)
  CUs static      the CUs' and CMEM's clocked power
  CMEM            one energy per CMEM byte read, written or passed to a
                  neighbour

It prints every figure, the model's value and the residual (a figure the
parameters cannot meet is printed with its residual, never dropped), and
with --write puts the fitted values and those derived from them into
tlm/power/energy_params.def (the one place they live); --check fails when
the table differs from the fit (the model's activity changed since).

The intervals, as the study timed its tests (docs/spec/study_programs.md):
the ARM's figures cover its work, during which it is never idle (checked
here), so its power is its average over the run and its energy per
operation that power over the loop's rate; the array's cover the array's
own runs (the array's busy time), in which the host waits and the CIU
moves nothing, so they take the AC's and the CUs' activity with the CUs'
static power over that time.

Usage: scripts/fit_energy.py [--soc-sim PATH] [--work DIR] [--write | --check]
"""

import argparse
import itertools
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEF = os.path.join(ROOT, "tlm", "power", "energy_params.def")

RECT = ["--app", "fullscreen_rect", "--frames", "1", "--set", "display.width=192", "--set", "display.height=144"]
ISS = ["--set", "host.model=iss"]
# The workloads (soc_sim arguments). The host's run on the ISS, the
# reference host; the array's natively (the array's activity does not depend
# on the host model). The ARM's shading run is a tenth of the study's
# 192,000 shades: its power is the same over any number.
RUNS = {
    "arm_rect": ["--backend", "arm", *RECT, *ISS, "--", "depth"],
    "arm_shading": ["--backend", "arm", "--app", "study_shading", *ISS, "--", "--shades", "19200", "--attributes", "6"],
    "add_loop": ["--app", "calib_add", *ISS],
    "mul_loop": ["--app", "calib_mul", *ISS],
    "tile_rect": [
        "--backend",
        "ap-tile",
        *RECT,
        "--set",
        "ap.tile.program=study",
        "--set",
        "ap.tile.texcoords=always",
        "--",
        "depth",
    ],
    "pixel_shading": [
        "--backend",
        "ap-pixel",
        "--app",
        "study_shading",
        "--set",
        "ap.pixel.program=study",
        "--",
        "--shades",
        "192000",
        "--attributes",
        "6",
    ],
    "array_add": ["--app", "calib_array_add_cmem"],
    "array_mul": ["--app", "calib_array_mul_cmem"],
}

HOST = ["host"]
AC_CIU = ["array_controller", "ciu"]
CUS = ["cu_array"]
# docs/spec/calibration.md: (figure, run, units, kind, measured). Kinds:
# host_power (mW), host_op (nJ per iteration of the loop), array_power (mW
# over the array's runs), array_op (nJ per operation of one CU).
# A calibration figure of the host (its loops' energy per operation) must
# come within HOST_OP_TOLERANCE on the ISS, as every host calibration figure
# does (--check fails otherwise); the others are reported with their
# residuals (docs/calibration.md, "Power", says which cannot be met).
HOST_OP_TOLERANCE = 0.03
FIGURES = [
    ("full-screen rectangle, ARM922T", "arm_rect", HOST, "host_power", 57.5),
    ("shading loop, ARM922T", "arm_shading", HOST, "host_power", 62.76),
    ("16-bit addition loop, ARM922T", "add_loop", HOST, "host_op", 4.30),
    ("16 x 8 multiplication loop, ARM922T", "mul_loop", HOST, "host_op", 4.37),
    ("full-screen rectangle, AC + CIU", "tile_rect", AC_CIU, "array_power", 37.92),
    ("full-screen rectangle, CUs + CMEM", "tile_rect", CUS, "array_power", 33.24),
    ("shading loop, AC + CIU", "pixel_shading", AC_CIU, "array_power", 12.96),
    ("shading loop, CUs + CMEM", "pixel_shading", CUS, "array_power", 29.28),
    ("CMEM addition, per addition", "array_add", AC_CIU + CUS, "array_op", 0.039),
    ("CMEM multiplication, per multiplication", "array_mul", AC_CIU + CUS, "array_op", 2.92),
]
UNITS = {"host_power": "mW", "host_op": "nJ", "array_power": "mW", "array_op": "nJ"}
# The operation an array_op figure counts: the instruction of the program
# that makes one (the addition's upper byte is its adc).
ARRAY_OPERATION = {"array_add": "add", "array_mul": "mulm"}

# The fitted unknowns, each the (unit, event) values it sets ((unit, None):
# the unit's static power in mW, else an energy per event in pJ).
PARAMETERS = [
    ("power.host.busy_cycles_pj = stalled_cycles_pj", [("host", "busy_cycles"), ("host", "stalled_cycles")]),
    ("power.array_controller.broadcasts_pj", [("array_controller", "broadcasts")]),
    ("power.cu_array.static_mw", [("cu_array", None)]),
    (
        "power.cu_array.cmem_bytes_read_pj = cmem_bytes_written_pj = neighbour_transfers_pj",
        [("cu_array", "cmem_bytes_read"), ("cu_array", "cmem_bytes_written"), ("cu_array", "neighbour_transfers")],
    ),
]

# Parameters with no figure, set from a fitted one by a stated rule
# (tlm/power/README.md, "Parameters"): (unit, event) <- factor x (unit,
# event). The rule: moving a byte across the chip costs what the AC's
# broadcast costs per byte of its 64-bit instruction word (the broadcast
# drives one word to every CU); the fitted CMEM byte energy is no anchor,
# since it fits to 0.
BROADCAST_BYTE = (1 / 8, ("array_controller", "broadcasts"))
DERIVED = {
    ("ciu", "words"): 4,  # the four bytes it moves into or out of CMEM
    ("bus", "beats"): 4,  # a 32-bit beat
    ("dma", "bytes"): 1,
    ("display_dma", "bytes"): 1,
    ("raster", "fragments"): 8,  # colour and depth read and written in the tile buffer
    ("raster", "texels"): 4,  # a 32-bit texel into the texture path
}

# The ARM's figures assume it never idles in their interval.
MAX_IDLE_SHARE = 1e-3
RATE = re.compile(r"model ([0-9.]+) million/s")
LINE = re.compile(r"^POWER_(EVENT|STATIC)\((\w+), (?:(\w+), )?([0-9.eE+-]+), (\w+),")


def read_table():
    """(unit, event or None) -> (value, source) from the .def file."""
    table = {}
    with open(DEF) as f:
        for line in f:
            m = LINE.match(line)
            if m:
                kind, unit, event, value, source = m.groups()
                table[(unit, event if kind == "EVENT" else None)] = (float(value), source)
    return table


def run(soc_sim, name, work):
    out = os.path.join(work, name)
    # Options after the application's "--" belong to the application.
    arguments = RUNS[name]
    split = arguments.index("--") if "--" in arguments else len(arguments)
    cmd = [soc_sim, *arguments[:split], "--quiet", "--no-frames", "--force", "--out", out, *arguments[split:]]
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"fit_energy: {name} failed (status {result.returncode}): {' '.join(cmd)}\n{result.stderr}")
    with open(os.path.join(out, "stats.json")) as f:
        stats = json.load(f)["stats"]
    rate = RATE.search(result.stdout)
    return {"stats": stats, "rate": float(rate.group(1)) * 1e6 if rate else None}


class Workload:
    """One run's activity within its figure's interval."""

    def __init__(self, name, result):
        stats = result["stats"]
        self.name = name
        self.counts = {}
        for unit, u in stats["energy"]["units"].items():
            for event, e in u.get("events", {}).items():
                self.counts[(unit, event)] = e["count"]
        self.run_seconds = stats["simulated_ns"] * 1e-9
        array = stats["array"]
        self.array_seconds = array["busy_ns"] * 1e-9
        self.lanes = array["columns"] * array["rows"]
        self.mix = array["mix"]
        self.rate = result["rate"]
        host = [self.counts.get(("host", e), 0.0) for e in ("busy_cycles", "stalled_cycles", "idle_cycles")]
        self.idle_share = host[2] / sum(host) if sum(host) else 0.0

    def energy(self, units, values, seconds, skip=()):
        """Joules of `units` over `seconds` with these parameter values."""
        joules = 0.0
        for unit in units:
            joules += values[(unit, None)] * 1e-3 * seconds
            for (u, e), n in self.counts.items():
                if u == unit and (u, e) not in skip:
                    joules += n * values[(u, e)] * 1e-12
        return joules


def model(figure, workload, values):
    _, _, units, kind, _ = figure
    if kind.startswith("host"):
        power_mw = workload.energy(units, values, workload.run_seconds) / workload.run_seconds * 1e3
        return power_mw if kind == "host_power" else power_mw * 1e-3 / workload.rate * 1e9
    # The array's runs: the CIU moves nothing while the array runs.
    joules = workload.energy(units, values, workload.array_seconds, skip={("ciu", "words")})
    if kind == "array_power":
        return joules / workload.array_seconds * 1e3
    operations = workload.mix[ARRAY_OPERATION[workload.name]] * workload.lanes
    return joules / operations * 1e9


def solve(rows, rhs):
    """Least squares of rows @ x = rhs with x >= 0: the best over every
    subset of free unknowns whose unconstrained solution is non-negative."""
    n = len(rows[0])

    def lstsq(free):
        a = [[sum(r[i] * r[j] for r in rows) for j in free] for i in free]
        b = [sum(r[i] * y for r, y in zip(rows, rhs)) for i in free]
        m = len(free)
        for col in range(m):  # Gauss-Jordan with partial pivoting
            pivot = max(range(col, m), key=lambda k: abs(a[k][col]))
            if abs(a[pivot][col]) < 1e-300:
                return None
            a[col], a[pivot] = a[pivot], a[col]
            b[col], b[pivot] = b[pivot], b[col]
            for k in range(m):
                if k != col:
                    f = a[k][col] / a[col][col]
                    a[k] = [x - f * y for x, y in zip(a[k], a[col])]
                    b[k] -= f * b[col]
        x = [0.0] * n
        for i, col in enumerate(free):
            x[col] = b[i] / a[i][i]
        return x if min(x) >= 0 else None

    def cost(x):
        return sum((sum(c * v for c, v in zip(r, x)) - y) ** 2 for r, y in zip(rows, rhs))

    candidates = [[0.0] * n]
    for size in range(1, n + 1):
        for free in itertools.combinations(range(n), size):
            x = lstsq(list(free))
            if x is not None:
                candidates.append(x)
    return min(candidates, key=cost)


def fit(workloads, table):
    """The fitted parameters: the figures' values are linear in them."""
    base = {key: value for key, (value, _) in table.items()}

    def values_with(x):
        values = dict(base)
        for (_, keys), v in zip(PARAMETERS, x):
            for key in keys:
                values[key] = v
        return values

    zero = [0.0] * len(PARAMETERS)
    rows, rhs = [], []
    for figure in FIGURES:
        workload, measured = workloads[figure[1]], figure[4]
        offset = model(figure, workload, values_with(zero))
        row = []
        for p in range(len(PARAMETERS)):
            unit = list(zero)
            unit[p] = 1.0
            row.append((model(figure, workload, values_with(unit)) - offset) / measured)
        rows.append(row)
        rhs.append(1.0 - offset / measured)
    x = solve(rows, rhs)
    values = values_with(x)
    for key, bytes_moved in DERIVED.items():
        values[key] = bytes_moved * BROADCAST_BYTE[0] * values[BROADCAST_BYTE[1]]
    return x, values


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--soc-sim", default=os.path.join(ROOT, "build", "default", "bin", "soc_sim"))
    parser.add_argument("--work", help="folder for the runs' outputs (default: a temporary one)")
    action = parser.add_mutually_exclusive_group()
    action.add_argument("--write", action="store_true", help="write the fitted defaults into energy_params.def")
    action.add_argument("--check", action="store_true", help="fail when energy_params.def differs from the fit")
    args = parser.parse_args()
    if not os.access(args.soc_sim, os.X_OK):
        print(f"fit_energy: no soc_sim at {args.soc_sim} (build it, or give --soc-sim)", file=sys.stderr)
        return 2

    table = read_table()
    with tempfile.TemporaryDirectory(prefix="fit_energy_") as scratch:
        work = args.work or scratch
        workloads = {name: Workload(name, run(args.soc_sim, name, work)) for name in RUNS}
    for name in ("arm_rect", "arm_shading", "add_loop", "mul_loop"):
        if workloads[name].idle_share > MAX_IDLE_SHARE:
            print(
                f"fit_energy: the ARM idles {100 * workloads[name].idle_share:.2f} % of {name}: its power is not "
                "its executing power",
                file=sys.stderr,
            )
            return 1

    x, values = fit(workloads, table)
    print("Fitted parameters:\n")
    for (name, _), value in zip(PARAMETERS, x):
        print(f"- `{name}` = {value:.4g}")
    print("\n| figure | model | measured | residual |\n| --- | --: | --: | --: |")
    outside = []
    for figure in FIGURES:
        name, run_name, _, kind, measured = figure
        value = model(figure, workloads[run_name], values)
        unit = UNITS[kind]
        residual = (value - measured) / measured
        print(f"| {name} | {value:.4g} {unit} | {measured:g} {unit} | {100 * residual:+.1f} % |")
        if kind == "host_op" and abs(residual) > HOST_OP_TOLERANCE:
            outside.append(f"{name}: {100 * residual:+.1f} %")
    idle_mw = table[("host", "idle_cycles")][0] * 1e-9 * 192e6 + table[("host", None)][0]
    print(
        f"| ARM922T idling on NOPs (converted) | {idle_mw:.4g} mW | {43.5 * 1.2:g} mW | "
        f"{100 * (idle_mw - 52.2) / 52.2:+.1f} % |"
    )
    print(
        f"| leakage, clocks stopped (converted) | {table[('host', None)][0]:.4g} mW | 3.6 mW | "
        f"{100 * (table[('host', None)][0] - 3.6) / 3.6:+.1f} % |"
    )

    stale = []
    fitted_or_derived = {key for _, keys in PARAMETERS for key in keys} | set(DERIVED)
    for key in sorted(fitted_or_derived, key=str):
        old = table[key][0]
        if abs(values[key] - old) > 1e-4 * max(abs(values[key]), 1e-9):
            stale.append(f"{key[0]}.{key[1] or 'static'}: table {old:.6g}, fit {values[key]:.6g}")
    if args.write:
        with open(DEF) as f:
            lines = f.readlines()
        with open(DEF, "w") as f:
            for line in lines:
                m = LINE.match(line)
                key = (m.group(2), m.group(3) if m.group(1) == "EVENT" else None) if m else None
                if m and key in fitted_or_derived and m.group(5) in ("fit", "derived"):
                    line = line[: m.start(4)] + f"{values[key]:.6g}" + line[m.end(4) :]
                f.write(line)
        print("wrote", os.path.relpath(DEF, ROOT))
    elif args.check and stale:
        print(
            "fit_energy: energy_params.def is stale (run scripts/fit_energy.py --write):\n  " + "\n  ".join(stale),
            file=sys.stderr,
        )
        return 1
    if args.check and outside:
        print(
            f"fit_energy: outside {100 * HOST_OP_TOLERANCE:g} % on the ISS:\n  " + "\n  ".join(outside), file=sys.stderr
        )
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
