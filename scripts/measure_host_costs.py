#!/usr/bin/env python3
"""Measures the host-compiled model's costs on the ISS and writes them to sw_driver/costs/host_costs.def.

The host-compiled model (host.model=native) charges the driver's work by
rows of one table (sw_driver/costs/host_costs.def, README.md there): each
place in the driver names a row and counts its unit (a vertex, a polygon
vertex mapped to the screen, a GL call). This script measures each row's
cycles per unit on the ISS (host.model=iss: the same driver compiled for
the ARM922T, the reference host):

1. every training run (the built-in GL scenes on the arm, raster, ap-tile
   ap-pixel and ap-object back ends, TRAINING below, and a few on ap-tile with the
   study's array program, VARIANTS; the study's GL-free
   applications study_shading and study_patches on the host and on the
   array, and calib_ciu's loops, APP_TRAINING) runs natively and on the
   ISS with the same configuration;
2. the native frame records give, per frame and phase of the driver
   (application, geometry, rasterization, presenting), the units charged
   of each row (units_<phase>_<row>) and the phase's time; the ISS's give
   the phase's time. The array back ends also split their host time
   (compute, write, read, wait, frame_out: renderers/common/host_time.h),
   and the meter counts the units charged in each part again
   (units_<part>_<row> beside host_<part>_ns): each part of each frame is
   an equation too. The GL-free applications publish the same figures for
   their timed parts in their driver statistics (study.*, calib_ciu.*):
   one record each;
3. what the native model spends in a phase besides the table's rows
   (memory and bus, waiting, work not yet in the table) is its phase time
   less the rows' cycles at the table's current values; the rows' cycles
   must make up the rest of the ISS's time: one equation per frame and
   phase, in cycles, weighted by the ISS's phase time (relative error);
4. the cycles per unit are the non-negative least-squares solution over
   the phases whose every charge is a row of the table (FITTED_PHASES):
   a phase whose native time still holds hand-counted charges is left out.
   Of the first frame only the application phase counts: it holds the
   scenes' set-up (their meshes, the textures they upload), which later
   frames do not; its other phases hold the ISS program's own start-up
   (parsing its boot information, constructing the back end's
   configuration), which is no driver work the table models.

The cluster platform's node program (sw_driver/cluster_node) is trained
the same way on cluster runs (CLUSTER_TRAINING): each node's frame figures
give its phases' cycles (compute, split) and the units of each phase's
rows (sort_middle_*), one equation per node, frame and phase.

Every row the runs exercise is measured; a row no run charges keeps its
value and is listed. `--only-rows PREFIX` measures only the rows whose
names start with PREFIX, from the runs that charge them (the cluster's
for sort_middle_), and keeps every other row as it is: for a change to
the driver's sources that cannot move the other rows (the node program,
which no SoC run executes). The table's sources file (SOURCES, beside it)
holds the hash of the driver's sources (sw_driver, but the table itself):
`--check` recomputes it and fails when the sources changed since the table
was measured (the test host_costs_fresh). The hash has a file of its own,
and the table is rewritten only when a figure changes, so that a change to
the driver that moves no cost does not rebuild everything that includes
the table. Run it again after changing the driver. The table keeps its
figures when they predict every fitted phase within KEEP_WITHIN (0.5 % of
the ISS's time) of what the new fit predicts, and every directly measured
row is within 0.5 % of its figure: the fit is not exactly repeatable (the
native model's own time in a phase, step 3, depends on the table, and rows
that always appear together, a back end's start and a scene's set-up,
trade cycles between fits), and without the band every re-measurement of
unchanged code would rewrite the table and all that is derived from it.

    scripts/measure_host_costs.py                 # measure and rewrite the table (a few minutes)
    scripts/measure_host_costs.py --dry-run       # print the fit, leave the table
    scripts/measure_host_costs.py --only-rows sort_middle_   # the cluster's rows alone (a minute)
    scripts/measure_host_costs.py --check         # is the table current? (no runs)

Needs numpy and scipy (build/venv has them). Exit status: 0, 1 when a
run fails or the table is stale (--check), 2 for a bad command line.
"""

import argparse
import hashlib
import json
import os
import pathlib
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

from run_outputs import SCENE_ARGUMENTS

ROOT = pathlib.Path(__file__).resolve().parent.parent
TABLE = ROOT / "sw_driver" / "costs" / "host_costs.def"
SOURCES = TABLE.with_name("host_costs.sources")  # the hash of the sources the table was measured for
PHASES = ["application", "geometry", "rasterization", "presenting"]
# The training runs: (scene, back end). The GL front end's rows (the
# geometry phase) are the same code on every back end.
TRAINING_SCENES = [
    "aapoly",
    "clip_offset",
    "cubes",
    "dense_teapot",
    "fixed_point",
    "fog_row",
    "fullscreen_rect",
    "lights_two_side",
    "mipmap_floor",
    "multitexture",
    "obj_viewer",
    "points_lines",
    "random_triangles",
    "teapot",
    "texture_formats",
    "textured_quad",
    "tile_grid",
    "triangle",
]
ARRAY_BACKENDS = ("ap-tile", "ap-pixel", "ap-object")
# Back ends run with settings of their own, under a name of their own: a
# back end's second array program charges rows no default run charges.
VARIANTS = {
    "ap-tile:study": ("ap-tile", ["ap.tile.program=study"]),
    # Textures warped on the array (ap.tile.texture_warp): one band, bands at levels, alpha textures left to the
    # look-ups; and through the DMA.
    "ap-tile:warp": ("ap-tile", ["ap.tile.texture_warp=array"]),
    "ap-tile:warp_dma": ("ap-tile", ["ap.tile.texture_warp=array", "dma.enabled=true"]),
    # ap-object's records and pixels through the DMA.
    "ap-object:dma": ("ap-object", ["dma.enabled=true"]),
    # ap-object's pixels to the z-buffer unit (the frame kept, the unit's window and clear, the colour window
    # copied by the host; textured_quad falls back to the host path).
    "ap-object:zunit": ("ap-object", ["zbuf.enabled=true", "array.features.zsend=true", "ap.object.zpath=unit"]),
}
VARIANT_SCENES = {
    "ap-tile:study": ["cubes", "teapot", "textured_quad"],
    "ap-tile:warp": ["textured_quad", "mipmap_floor", "texture_formats"],
    "ap-tile:warp_dma": ["textured_quad"],
    "ap-object:dma": ["cubes", "teapot", "textured_quad"],
    "ap-object:zunit": ["cubes", "teapot", "textured_quad"],
}
TRAINING = [(scene, backend) for backend in ("arm", "raster") + ARRAY_BACKENDS for scene in TRAINING_SCENES]
TRAINING += [(scene, variant) for variant, scenes in VARIANT_SCENES.items() for scene in scenes]
# The array back ends' split of their host time within the phases.
SPLIT = ["compute", "write", "read", "wait", "frame_out"]
# The phases whose every native charge is a row of the table, per back end.
FITTED_PHASES = {
    "arm": PHASES,
    "raster": PHASES,
    "ap-tile": PHASES + SPLIT,
    "ap-pixel": PHASES + SPLIT,
    "ap-object": PHASES + SPLIT,
    "ap-tile:study": PHASES + SPLIT,
    "ap-tile:warp": PHASES + SPLIT,
    "ap-tile:warp_dma": PHASES + SPLIT,
    "ap-object:dma": PHASES + SPLIT,
    "ap-object:zunit": PHASES + SPLIT,
}
# What van Sinten's chain mapping needs of the array (the Image Blender preset's switches, by key).
CHAIN_SETTINGS = [
    "--set", "array.issue_skew=lane", "--set", "array.row_ring=true", "--set", "array.features.neighbour_add=true",
    "--set", "array.features.lut=true", "--set", "array.lut.entries=1024",
]  # fmt: skip
# The GL-free applications: (name, app, back end, arguments, driver statistics' prefix). Their
# records are their timed parts (the split).
APP_TRAINING = [
    ("study_shading_arm", "study_shading", "arm", ["--", "--shades", "9600"], "study"),
    ("study_shading_ap-pixel", "study_shading", "ap-pixel", ["--", "--shades", "9600"], "study"),
    # Six attributes (the study's shading test) beside the default seven: the host's loop's
    # cost per attribute apart from its cost per pixel; and the study's array program.
    ("study_shading_arm_6", "study_shading", "arm", ["--", "--shades", "9600", "--attributes", "6"], "study"),
    (
        "study_shading_ap-pixel_study",
        "study_shading",
        "ap-pixel",
        ["--set", "ap.pixel.program=study", "--", "--shades", "9600"],
        "study",
    ),
    ("study_patches_arm", "study_patches", "arm", [], "study"),
    ("study_patches_ap-pixel", "study_patches", "ap-pixel", [], "study"),
    ("calib_ciu", "calib_ciu", "arm", [], "calib_ciu"),
    # The forward texture warp at four texture sizes and four filter widths: lines, both passes' borders,
    # factors and pixels in independent proportions.
    ("study_forward_texture_128_2", "study_forward_texture", "arm", [], "study"),
    ("study_forward_texture_128_4", "study_forward_texture", "arm", ["--", "--filter-width", "4"], "study"),
    (
        "study_forward_texture_64_1",
        "study_forward_texture",
        "arm",
        ["--", "--texture-size", "64", "--filter-width", "1"],
        "study",
    ),
    (
        "study_forward_texture_32_3",
        "study_forward_texture",
        "arm",
        ["--", "--texture-size", "32", "--filter-width", "3"],
        "study",
    ),
    (
        "study_forward_texture_256_2",
        "study_forward_texture",
        "arm",
        ["--", "--texture-size", "256", "--filter-width", "2"],
        "study",
    ),
    (
        "study_forward_texture_256_1",
        "study_forward_texture",
        "arm",
        ["--", "--texture-size", "256", "--filter-width", "1", "--filter", "tent"],
        "study",
    ),
    # A smaller display: fewer second-pass lines for the same texture.
    (
        "study_forward_texture_128_2_small",
        "study_forward_texture",
        "arm",
        ["--set", "display.width=192", "--set", "display.height=144", "--", "--filter-width", "2"],
        "study",
    ),
    # The same warp on the array (resample_lines.s): through the CIU (ap-pixel) and the DMA (ap-tile), at
    # four texture sizes and four filter widths: lines, texels, rows and borders in independent proportions.
    ("study_forward_texture_array_ciu_128_2", "study_forward_texture", "ap-pixel", [], "study"),
    (
        "study_forward_texture_array_ciu_80_4",
        "study_forward_texture",
        "ap-pixel",
        ["--", "--texture-size", "80", "--filter-width", "4"],
        "study",
    ),
    (
        "study_forward_texture_array_dma_128_2",
        "study_forward_texture",
        "ap-tile",
        ["--set", "dma.enabled=true"],
        "study",
    ),
    (
        "study_forward_texture_array_dma_48_1",
        "study_forward_texture",
        "ap-tile",
        ["--set", "dma.enabled=true", "--", "--texture-size", "48", "--filter-width", "1"],
        "study",
    ),
    (
        "study_forward_texture_array_dma_200_3",
        "study_forward_texture",
        "ap-tile",
        ["--set", "dma.enabled=true", "--", "--texture-size", "200", "--filter-width", "3"],
        "study",
    ),
    # Van Sinten's own mapping (resample_chain.s, four lines a run) with the switches it needs, through the DMA and the
    # CIU: the same rows, in the chain's proportions.
    (
        "study_forward_texture_chain_dma_96_2",
        "study_forward_texture",
        "ap-tile",
        ["--set", "dma.enabled=true", *CHAIN_SETTINGS, "--", "--texture-size", "96", "--array-mapping", "chain"],
        "study",
    ),
    (
        "study_forward_texture_chain_ciu_64_3",
        "study_forward_texture",
        "ap-pixel",
        [*CHAIN_SETTINGS, "--", "--texture-size", "64", "--filter-width", "3", "--array-mapping", "chain"],
        "study",
    ),
]
# The cluster platform's node program (sw_driver/cluster_node): two nodes,
# so that trapezoids are both drawn at home and sent. Per node and frame,
# each phase's units are the node's own counts (stats.json's
# nodes[i].frames), the rows below each phase charges.
CLUSTER_TRAINING = {
    "cluster_random": [
        "--set", "cluster.nodes=2", "--set", "cluster.triangles=1500", "--set", "cluster.triangle_pixels=12",
        "--set", "cluster.width=160", "--set", "cluster.height=120",
    ],
    "cluster_teapot": [
        "--scene", "teapot", "--set", "cluster.nodes=2", "--set", "cluster.width=160", "--set", "cluster.height=120",
    ],
    "cluster_big_triangles": [
        "--set", "cluster.nodes=2", "--set", "cluster.triangles=200", "--set", "cluster.triangle_pixels=40",
        "--set", "cluster.width=160", "--set", "cluster.height=120",
    ],
}  # fmt: skip
CLUSTER_PHASE_ROWS = {
    "compute": {
        "sort_middle_triangle": "triangles",
        "sort_middle_trapezoid": "trapezoids_drawn",
        "sort_middle_row": "rows",
        "sort_middle_pixel": "pixels",
    },
    "split": {"sort_middle_split": "triangles_split", "sort_middle_piece": "trapezoids_made"},
}
FRAMES = 3
# ISS runs of the array back ends are slow (about 1 s of simulated host time a
# frame on the teapot): the start-up frame and one more.
ARRAY_FRAMES = 2
# The host's calibration loops (calibration.md's 13.9 million/s): one row
# each, the ISS's core cycles an iteration in the loop's function (its
# profile) less the issue cycles of its two loads and its store, which the
# native model charges with the accesses (host.cycles.load, .store: 1). The
# loops are bound by the memory, so their time says little of the core's:
# the row is measured per iteration, not fitted to the rate.
CALIBRATION_LOOPS = {
    "calib_add": ("calib_add_iteration", "tessera_calibration_add16"),
    "calib_mul": ("calib_mul_iteration", "tessera_calibration_mul16x8"),
}
LOOP_ACCESS_CYCLES = 3
# Rows whose code is functions of their own, run once per unit, measured
# from the ISS's profile of a training run instead of fitted: the
# functions' core cycles per unit, plus a correction. These are the rows
# whose time hides behind a device's (the CIU's, the display port's), which
# phase times cannot identify. Per row: the run's folder and results key,
# the functions (demangled-name prefixes), and the correction in cycles.
# - The CIU driver's WriteMem32 and ReadMem32 in calib_ciu's loops: plus
#   the caller's BL (3 cycles), less the issue cycle of the one access the
#   native model charges itself.
# - The display port's copy of a block in fullscreen_rect's arm frames (no
#   texture, so the copy is the only caller of write_words): the copy loop
#   and its LDM/STM, less the issue cycles of the 8 loads and the STM (8
#   stores and one) the native model charges with the accesses. The copy is
#   bound by the port, so the phase's time cannot tell its cycles.
CALL_ROWS = {
    "array_write32": ("calib_ciu", ("calib_ciu", "app"), ["tessera::ArrayDriver::write32("], 3 - 1),
    "array_read32": ("calib_ciu", ("calib_ciu", "app"), ["tessera::ArrayDriver::read32("], 3 - 1),
    "display_copy_block": (
        "fullscreen_rect_arm",
        ("fullscreen_rect", "arm"),
        ["tessera::DisplayDriver::present(", "tessera::HostApi::write_words("],
        -(8 + 9),
    ),
}
LOOP_ITERATIONS = re.compile(r"loop of ([0-9]+) iterations")
ROW = re.compile(r'^HOST_COST\((\w+), ([0-9.eE+-]+), (".*")\)$')
SOURCE_SUFFIXES = {".c", ".cpp", ".h", ".hpp", ".S", ".s", ".def", ".inc", ".txt"}


def sources_hash():
    """The hash of the driver's sources: every source file under sw_driver but the table."""
    digest = hashlib.sha256()
    folder = ROOT / "sw_driver"
    for path in sorted(p for p in folder.rglob("*") if p.is_file() and p.suffix in SOURCE_SUFFIXES):
        if path == TABLE:
            continue
        digest.update(path.relative_to(ROOT).as_posix().encode() + b"\0")
        digest.update(path.read_bytes() + b"\0")
    return digest.hexdigest()[:16]


def read_table():
    lines = TABLE.read_text().splitlines()
    rows = {}
    for line in lines:
        match = ROW.match(line)
        if match:
            rows[match.group(1)] = float(match.group(2))
    recorded = SOURCES.read_text().strip() if SOURCES.is_file() else None
    return lines, rows, recorded


# The table keeps its recorded figures when they predict every fitted phase within KEEP_WITHIN (of the ISS's
# time) of what the new figures predict, and every row measured directly (not fitted) is within KEEP_WITHIN of
# its recorded figure. The fit is not exactly repeatable: the native model's own time in a phase (its waiting for
# the array, the bus) depends on the table itself, and rows that always appear together in a phase (a back end's
# start and a scene's set-up, in a run's first frame) trade cycles from one fit to the next, only their sum being
# measured. Judging by the phases' predictions, not row by row, keeps a re-measurement that moves no cost from
# rewriting the table and every figure derived from it, and never mixes old and new rows.
KEEP_WITHIN = 0.005


def keeps_recorded(np, a, used, solution, table, names, direct, fitted):
    """Whether the recorded table predicts every phase as the new fit does (KEEP_WITHIN), direct rows alike."""
    recorded = np.array([table[names[column]] for column in used])
    phases_moved = float(np.max(np.abs(a[:, used] @ (recorded - solution)))) if len(used) else 0.0
    rows_moved = [row for row in direct if abs(fitted[row] - table[row]) > KEEP_WITHIN * abs(table[row])]
    print(
        f"the recorded figures predict the fitted phases within {phases_moved * 100:.2f}% of the new ones; "
        f"directly measured rows moved beyond {KEEP_WITHIN * 100:g}%: {', '.join(rows_moved) or 'none'}"
    )
    return phases_moved <= KEEP_WITHIN and not rows_moved


def write_table(lines, cycles, digest, keep):
    if keep:
        print(f"the table keeps its figures (within {KEEP_WITHIN * 100:g}%); its sources' hash is updated")
        cycles = {}
    out = []
    for line in lines:
        match = ROW.match(line)
        if match and match.group(1) in cycles:
            line = f"HOST_COST({match.group(1)}, {cycles[match.group(1)]:.6g}, {match.group(3)})"
        out.append(line)
    text = "\n".join(out) + "\n"
    if TABLE.read_text() != text:
        TABLE.write_text(text)
    SOURCES.write_text(digest + "\n")


def profiled(model):
    """soc_sim's flag for the ISS's per-function profile, which CALL_ROWS and the loops read (off by default)."""
    return ["--iss-profile"] if model == "iss" else []


def run(soc_sim, out, scene, name, model):
    backend, settings = VARIANTS.get(name, (name, []))
    folder = out / f"{scene}_{name.replace(':', '_')}_{model}"
    frames = ARRAY_FRAMES if backend in ARRAY_BACKENDS else FRAMES
    arguments = ["--app", scene, "--backend", backend, "--frames", str(frames)] + profiled(model)
    for setting in settings:
        arguments += ["--set", setting]
    if scene in SCENE_ARGUMENTS:
        arguments += ["--", *SCENE_ARGUMENTS[scene]]
    # The runs start in the repository (SCENE_ARGUMENTS' OBJ file is relative to it).
    stats = run_soc_sim(soc_sim, folder.resolve(), model, arguments, cwd=ROOT)
    return [frame.get("driver", {}) for frame in stats["frames"]]


def run_soc_sim(soc_sim, folder, model, arguments, cwd=None):
    """soc_sim with the training runs' common options into `folder` on host model `model`; its stats.json's stats."""
    command = [soc_sim, "--no-frames", "--quiet", "--force", "--out", str(folder), "--set", f"host.model={model}"]
    command += arguments
    result = subprocess.run(command, capture_output=True, text=True, cwd=cwd)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} exited with {result.returncode}: {result.stderr.strip()}")
    return json.loads((folder / "stats.json").read_text())["stats"]


def run_app(soc_sim, out, name, app, backend, arguments, prefix, model):
    """A GL-free application's one record: its timed parts' host_<part>_ns and units_<part>_<row>."""
    stats = run_soc_sim(
        soc_sim, out / f"{name}_{model}", model, ["--app", app, "--backend", backend] + profiled(model) + arguments
    )
    figures = stats["driver"].get(prefix, {})
    record = {}
    for key, value in figures.items():
        if key.startswith("units_"):
            record[key] = value
        elif key.endswith("_ns") and key[:-3] in SPLIT:
            record[f"host_{key}"] = value
    # As a frame after the start-up (frame 1).
    return [{}, record]


def run_cluster(soc_sim, out, name, arguments, model):
    """A cluster run's node frames: each node's figures of each frame (stats.json's nodes[i].frames)."""
    stats = run_soc_sim(soc_sim, out / f"{name}_{model}", model, ["--platform", "cluster", "--frames", "2"] + arguments)
    return [frame for node in stats["nodes"] for frame in node["frames"]]


def cluster_equations(table, index, native, iss):
    """The fit's equations of one cluster run: per node frame and phase, as the driver's phases'."""
    equations, targets, labels = [], [], []
    for k, (n, i) in enumerate(zip(native, iss)):
        for phase, rows in CLUSTER_PHASE_ROWS.items():
            iss_cycles = i.get(f"cycles_{phase}", 0.0)
            native_cycles = n.get(f"cycles_{phase}", 0.0)
            units = [0.0] * len(index)
            for row, figure in rows.items():
                units[index[row]] = n.get(figure, 0.0)
            if iss_cycles <= 0 or not any(units):
                continue
            charged = sum(n.get(figure, 0.0) * table[row] for row, figure in rows.items())
            other = native_cycles - charged
            equations.append([u / iss_cycles for u in units])
            targets.append((iss_cycles - other) / iss_cycles)
            labels.append(f"node frame {k} {phase}")
    return equations, targets, labels


def measure_cluster_rows(args, out, lines, table, np, nnls):
    """--only-rows: the rows named PREFIX... fitted to the cluster runs alone; the other rows kept."""
    rows = [name for name in table if name.startswith(args.only_rows)]
    cluster_rows = {row for phase in CLUSTER_PHASE_ROWS.values() for row in phase}
    if not rows or not set(rows) <= cluster_rows:
        print(
            f"measure_host_costs: --only-rows {args.only_rows}: the cluster's runs measure "
            f"{', '.join(sorted(cluster_rows))}",
            file=sys.stderr,
        )
        return 2
    with ThreadPoolExecutor(args.jobs) as pool:
        clusters = {
            (name, model): pool.submit(run_cluster, args.soc_sim, out, name, arguments, model)
            for name, arguments in CLUSTER_TRAINING.items()
            for model in ("native", "iss")
        }
        try:
            results = {key: future.result() for key, future in clusters.items()}
        except RuntimeError as error:
            print(f"measure_host_costs: {error}", file=sys.stderr)
            return 1
    names = list(table)
    index = {name: i for i, name in enumerate(names)}
    equations, targets, labels = [], [], []
    for name in CLUSTER_TRAINING:
        more, more_targets, more_labels = cluster_equations(
            table, index, results[(name, "native")], results[(name, "iss")]
        )
        equations += more
        targets += more_targets
        labels += [f"{name} {label}" for label in more_labels]
    a = np.array(equations)
    b = np.array(targets)
    used = [index[row] for row in rows if a[:, index[row]].any()]
    solution, _ = nnls(a[:, used], b)
    residual = a[:, used] @ solution - b
    fitted = {names[column]: float(value) for column, value in zip(used, solution)}
    print(
        f"{len(equations)} node-frame phases, {len(fitted)} rows measured; relative error: "
        f"largest {np.max(np.abs(residual)) * 100:.1f}%, rms {np.sqrt(np.mean(residual**2)) * 100:.1f}%"
    )
    for k in np.argsort(-np.abs(residual))[:5]:
        print(f"  {labels[k]}: {residual[k] * 100:+.1f}%")
    for row in rows:
        mark = "" if row in fitted else "   (no run charges it: kept)"
        print(f"  {row:28} {table[row]:10.4g} -> {fitted.get(row, table[row]):10.4g}{mark}")
    if not args.dry_run:
        keep = keeps_recorded(np, a, used, solution, table, names, [], fitted)
        write_table(lines, fitted, sources_hash(), keep)
        print(f"wrote {TABLE.relative_to(ROOT)}")
    return 0


def loop_cycles(soc_sim, out, app, function):
    """The ISS's core cycles an iteration of a calibration loop, from its function's profile."""
    folder = out / f"{app}_iss"
    command = [
        soc_sim,
        "--app",
        app,
        "--quiet",
        "--force",
        "--out",
        str(folder),
        "--set",
        "host.model=iss",
        "--iss-profile",
    ]
    result = subprocess.run(command, capture_output=True, text=True)
    match = LOOP_ITERATIONS.search(result.stdout)
    if result.returncode != 0 or not match:
        raise RuntimeError(
            f"{' '.join(command)} exited with {result.returncode} and printed no loop: {result.stderr.strip()}"
        )
    profile = json.loads((folder / "stats.json").read_text())["stats"]["host"]["iss"]["profile"]
    rows = [row for row in profile if row["function"] == function]
    if not rows:
        raise RuntimeError(f"{app}: no {function} in the ISS's profile")
    return rows[0]["core_cycles"] / int(match.group(1))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--soc-sim", default=str(ROOT / "build" / "default" / "bin" / "soc_sim"))
    parser.add_argument("--out", default="out/host_costs", help="folder for the runs' statistics")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--clock-hz", type=float, default=192e6, help="the host's clock (host.clock_hz)")
    parser.add_argument("--dry-run", action="store_true", help="print the fit, leave the table as it is")
    parser.add_argument("--check", action="store_true", help="fail when the table is stale (no runs)")
    parser.add_argument(
        "--only-rows", metavar="PREFIX", help="measure only the rows named PREFIX...; keep the others (sort_middle_)"
    )
    args = parser.parse_args()
    # The runs start in the repository (SCENE_ARGUMENTS' OBJ file): a relative path given here is the caller's.
    args.soc_sim = str(pathlib.Path(args.soc_sim).resolve())

    lines, table, recorded = read_table()
    if args.check:
        digest = sources_hash()
        if recorded != digest:
            print(
                f"measure_host_costs: {TABLE.relative_to(ROOT)} was measured for sources {recorded}, the driver's "
                f"sources are now {digest}: run scripts/measure_host_costs.py to measure it again",
                file=sys.stderr,
            )
            return 1
        print(f"measure_host_costs: the table is current (sources {digest})")
        return 0
    if not os.access(args.soc_sim, os.X_OK):
        parser.error(f"no soc_sim at {args.soc_sim}")
    try:
        import numpy as np
        from scipy.optimize import nnls
    except ImportError:
        parser.error("numpy and scipy are needed: run it with build/venv/bin/python")

    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.only_rows:
        return measure_cluster_rows(args, out, lines, table, np, nnls)
    with ThreadPoolExecutor(args.jobs) as pool:
        futures = {
            (scene, backend, model): pool.submit(run, args.soc_sim, out, scene, backend, model)
            for scene, backend in TRAINING
            for model in ("native", "iss")
        }
        for name, app, backend, arguments, prefix in APP_TRAINING:
            for model in ("native", "iss"):
                futures[(name, "app", model)] = pool.submit(
                    run_app, args.soc_sim, out, name, app, backend, arguments, prefix, model
                )
        clusters = {
            (name, model): pool.submit(run_cluster, args.soc_sim, out, name, arguments, model)
            for name, arguments in CLUSTER_TRAINING.items()
            for model in ("native", "iss")
        }
        loops = {
            app: pool.submit(loop_cycles, args.soc_sim, out, app, function)
            for app, (_, function) in CALIBRATION_LOOPS.items()
        }
        try:
            results = {key: future.result() for key, future in futures.items()}
            loop_results = {key: future.result() for key, future in loops.items()}
            cluster_results = {key: future.result() for key, future in clusters.items()}
        except RuntimeError as error:
            print(f"measure_host_costs: {error}", file=sys.stderr)
            return 1

    names = list(table)
    index = {name: i for i, name in enumerate(names)}
    known = {}
    for row, (folder, key, functions, correction) in CALL_ROWS.items():
        profile = json.loads((out / f"{folder}_iss" / "stats.json").read_text())["stats"]["host"]["iss"]["profile"]
        core = sum(r["core_cycles"] for r in profile if any(r["function"].startswith(f) for f in functions))
        per_bucket = {}
        for frame in results[key + ("native",)]:
            for name, value in frame.items():
                if name.startswith("units_") and name.endswith("_" + row):
                    bucket = name[len("units_") : -len(row) - 1]
                    per_bucket[bucket] = per_bucket.get(bucket, 0) + value
        # The phases' buckets hold every unit once (the split's again).
        units = sum(v for b, v in per_bucket.items() if b in PHASES) or sum(per_bucket.values())
        if core <= 0 or units <= 0:
            print(f"measure_host_costs: {folder} shows no {', '.join(functions)} to measure {row} by", file=sys.stderr)
            return 1
        known[row] = max(0.0, core / units + correction)
        print(
            f"{row}: {core / units:.3f} core cycles a unit in {', '.join(functions)} of {folder} on the ISS: "
            f"{known[row]:.4g}"
        )
    equations, targets, labels = [], [], []
    runs = TRAINING + [(name, "app") for name, *_ in APP_TRAINING]
    for scene, backend in runs:
        native, iss = results[(scene, backend, "native")], results[(scene, backend, "iss")]
        for frame, (n, i) in enumerate(zip(native, iss)):
            for phase in FITTED_PHASES.get(backend, SPLIT):
                if frame == 0 and phase != "application":
                    continue  # the start-up (STARTUP_PHASES)
                iss_cycles = i.get(f"host_{phase}_ns", 0.0) * 1e-9 * args.clock_hz
                native_cycles = n.get(f"host_{phase}_ns", 0.0) * 1e-9 * args.clock_hz
                units = [0.0] * len(names)
                for key, value in n.items():
                    prefix = f"units_{phase}_"
                    if key.startswith(prefix) and key[len(prefix) :] in index:
                        units[index[key[len(prefix) :]]] = value
                if iss_cycles <= 0 or not any(units):
                    continue
                charged = sum(u * table[name] for u, name in zip(units, names))
                other = native_cycles - charged + sum(units[index[row]] * value for row, value in known.items())
                for row in known:
                    units[index[row]] = 0.0
                equations.append([u / iss_cycles for u in units])
                targets.append((iss_cycles - other) / iss_cycles)
                labels.append(f"{scene}/{backend} frame {frame} {phase}")
    for name in CLUSTER_TRAINING:
        more, more_targets, more_labels = cluster_equations(
            table, index, cluster_results[(name, "native")], cluster_results[(name, "iss")]
        )
        equations += more
        targets += more_targets
        labels += [f"{name}/cluster {label}" for label in more_labels]
    if not equations:
        print("measure_host_costs: no run charged a row in a fitted phase", file=sys.stderr)
        return 1
    a = np.array(equations)
    b = np.array(targets)
    used = np.flatnonzero(a.any(axis=0))
    solution, _ = nnls(a[:, used], b)
    fitted = dict(table)
    for column, value in zip(used, solution):
        fitted[names[column]] = float(value)
    residual = a[:, used] @ solution - b
    measured = [names[column] for column in used]
    for row, value in known.items():
        fitted[row] = value
        measured.append(row)
    for app, (row, function) in CALIBRATION_LOOPS.items():
        core = loop_results[app]
        fitted[row] = max(0.0, core - LOOP_ACCESS_CYCLES)
        measured.append(row)
        print(f"{app}: {core:.3f} core cycles an iteration in {function} on the ISS: {row} {fitted[row]:.4g}")
    print(
        f"{len(equations)} phase-frames, {len(measured)} rows measured; relative error of the fitted phases: "
        f"largest {np.max(np.abs(residual)) * 100:.1f}%, rms {np.sqrt(np.mean(residual**2)) * 100:.1f}%"
    )
    for k in np.argsort(-np.abs(residual))[:5]:
        print(f"  {labels[k]}: {residual[k] * 100:+.1f}%")
    # Leaving a scene out: the rows fitted without any run of the scene,
    # then the scene's phases predicted by them. The application phase is
    # left out of this (the scene's own rows, scene_<name>_*, are that
    # scene's alone), and so are the GL-free applications (their rows are
    # theirs).
    print("leaving one scene out (fitted without it, its driver's phases predicted): largest error, its phase")
    scenes_of = [label.split("/")[0] for label in labels]
    for scene in TRAINING_SCENES:
        keep = np.array([s != scene for s in scenes_of])
        judged = np.array([s == scene and not label.endswith(" application") for s, label in zip(scenes_of, labels)])
        if not judged.any():
            continue
        columns = np.flatnonzero(a[keep].any(axis=0))
        partial, _ = nnls(a[keep][:, columns], b[keep])
        predicted = a[judged][:, columns] @ partial - b[judged]
        worst = np.argmax(np.abs(predicted))
        print(f"  {scene:16} {predicted[worst] * 100:+7.1f}%  ({np.array(labels)[judged][worst]})")
    for name in names:
        mark = "" if name in measured else "   (no run charges it: kept)"
        print(f"  {name:28} {table[name]:10.4g} -> {fitted[name]:10.4g}{mark}")
    if not args.dry_run:
        direct = list(known) + [row for row, _ in CALIBRATION_LOOPS.values()]
        keep = keeps_recorded(np, a, used, solution, table, names, direct, fitted)
        write_table(lines, {name: fitted[name] for name in measured}, sources_hash(), keep)
        print(f"wrote {TABLE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
