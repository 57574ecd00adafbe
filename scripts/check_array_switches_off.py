#!/usr/bin/env python3
"""check_array_switches_off.py: the Image Blender's parameters do nothing while their switches are off.

Delayed execution and the lookup table (tlm/array/README.md) come with
parameters of their own (INERT below: the skew's K, the table's size and
ports, the lut's cycles) that only count with their switch on
(array.issue_skew = lane or row, array.features.lut = true); so does the z-buffer
unit (tlm/zbuf/README.md: its size, ports, pairing rule and energies, and
zsend's cycles, with zbuf.enabled and array.features.zsend off), and so do
the cycles of MorphoSys's 16-bit operations and wired-OR loop (with
array.features.wide_ops and array.features.wired_or_loop off). Runs every built-in GL
scene (soc_sim --list-apps, the "GL ES 1.1 scene" lines but obj_viewer) on
each array back end twice, with every parameter at its default and with
INERT set to other values, the switches left off, and compares the two runs
byte for byte: every frame file, the VCD, and stats.json with the command
line and INERT's keys taken out. Exits 1 naming the first scene that
differs, and where.

With --preset FILE (configs/presets/image_blender_like.json), the second
run is with that preset instead, and only the frames must be the same: the
model's array programs read no neighbour and look nothing up, so on the
Image Blender's machine they draw the same pictures, in other times (its
statistics must show the chain's skew wherever a program ran).

That a J2210 run is the same as before the switches existed is a comparison
with an older build, which a test cannot hold: scripts/check_same_outputs.py
--record with that build, then --compare with this one and --added-keys
ADDED (printed by --print-added-keys).

  check_array_switches_off.py --soc-sim build/default/bin/soc_sim [--frames N]
      [--backends ap-tile,ap-pixel] [--apps a,b] [--work-dir DIR] [--jobs J]
  check_array_switches_off.py --soc-sim build/default/bin/soc_sim --preset configs/presets/image_blender_like.json
  check_array_switches_off.py --print-added-keys
"""

import argparse
import concurrent.futures
import json
import pathlib
import shutil
import subprocess
import sys
import tempfile

from json_difference import first_difference
from run_outputs import different_files, gl_scenes

# The parameters that only count with a switch on, and a value other than
# their default for each.
INERT = {
    "array.issue_skew_cycles": "7",
    "array.lut.entries": "17",
    "array.lut.ports": "3",
    "array.cycles.lut": "9",
    "array.cycles.nadds": "5",
    "array.cycles.nadcs": "6",
    "array.cycles.zsend": "5",
    "array.cycles.add16": "3",
    "array.cycles.sub16": "5",
    "array.cycles.cmp16": "6",
    "array.cycles.mov16": "7",
    "array.cycles.endloopany": "9",
    "zbuf.entries": "1000",
    "zbuf.ports": "3",
    "zbuf.pair_halves_only": "true",
    "power.zbuf.pixels_pj": "7",
    "power.zbuf.writes_pj": "7",
    "power.zbuf.cleared_entries_pj": "7",
    "power.zbuf.window_words_pj": "7",
    "power.zbuf.static_mw": "7",
}
# Every configuration key delayed execution, the lookup table, the 16-bit
# operations, the wired OR and the z-buffer unit added (ap.object.zpath:
# ap-object's pixels to the unit, which refuses to run with the unit off):
# check_same_outputs.py --added-keys.
ADDED = [
    "array.issue_skew",
    "array.features.lut",
    "array.row_ring",
    "array.features.zsend",
    "zbuf.enabled",
    "array.features.wide_ops",
    "array.features.wired_or_loop",
    "ap.object.zpath",
    *INERT,
]
SIZE = ["--set", "display.width=192", "--set", "display.height=144"]


def run(soc_sim: str, backend: str, app: str, frames: int, inert: bool, out: pathlib.Path, preset: str = "") -> str:
    command = [soc_sim, "--backend", backend, "--app", app, "--frames", str(frames), "--out", str(out)]
    command += ["--vcd", str(out / "trace.vcd"), "--force", "--quiet"] + SIZE
    if inert and preset:
        command += ["--config", preset]
    for key, value in INERT.items() if inert and not preset else ():
        command += ["--set", f"{key}={value}"]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        return f"soc_sim exited {result.returncode}: {' '.join(command)}\n{result.stderr[-2000:]}"
    return ""


def stats_without_inert(path: pathlib.Path) -> dict:
    stats = json.loads(path.read_text())
    stats.pop("command_line", None)
    config = stats.get("config", {})
    for key in INERT:
        group, *inner, field = key.split(".")
        table = config.get(group, {})
        for name in inner:
            table = table.get(name, {})
        if field not in table:
            raise RuntimeError(f"{path}: no config.{key}")
        table.pop(field)
    return stats


def compare(default: pathlib.Path, inert: pathlib.Path) -> str:
    difference = different_files(default, inert)
    if difference:
        return difference
    stats = stats_without_inert(default / "stats.json")
    array = stats.get("stats", {}).get("array", {})
    sections = ("issue_skew", "lut", "zbuf", "wired_or")
    if any(section in array for section in sections) or "zbuf" in stats.get("stats", {}):
        return "stats.json has a section of a switch that is off (array.issue_skew, array.lut, zbuf or array.wired_or)"
    return first_difference(stats, stats_without_inert(inert / "stats.json"), "stats.json", ("default", "inert"))


def compare_frames(default: pathlib.Path, preset: pathlib.Path) -> str:
    frames = sorted(p.name for p in default.iterdir() if p.name.startswith("frame_"))
    if not frames or frames != sorted(p.name for p in preset.iterdir() if p.name.startswith("frame_")):
        return f"no frames, or different frames: {frames}"
    for name in frames:
        if (default / name).read_bytes() != (preset / name).read_bytes():
            return f"{name} differs"
    array = json.loads((preset / "stats.json").read_text()).get("stats", {}).get("array", {})
    if array.get("programs", 0) > 0 and array.get("issue_skew", {}).get("cycles", 0) <= 0:
        return "the preset's run has programs but no issue_skew.cycles"
    return ""


def check(soc_sim: str, backend: str, app: str, frames: int, work: pathlib.Path, preset: str = "") -> str:
    default, inert = work / f"{backend}_{app}_default", work / f"{backend}_{app}_inert"
    for set_inert, out in ((False, default), (True, inert)):
        failure = run(soc_sim, backend, app, frames, set_inert, out, preset)
        if failure:
            return failure
    difference = compare_frames(default, inert) if preset else compare(default, inert)
    if not difference:
        shutil.rmtree(default)
        shutil.rmtree(inert)
    return difference


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--soc-sim")
    parser.add_argument("--frames", type=int, default=2)
    parser.add_argument("--backends", default="ap-tile,ap-pixel")
    parser.add_argument("--apps", default="", help="comma-separated scenes (default: every GL scene)")
    parser.add_argument("--work-dir", default="", help="kept, with the runs that differ (default: a temporary one)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--print-added-keys", action="store_true", help="print ADDED, comma-separated, and exit")
    parser.add_argument("--preset", default="", help="compare the frames with this --config file's instead")
    args = parser.parse_args()
    if args.print_added_keys:
        print(",".join(ADDED))
        return 0
    if not args.soc_sim:
        parser.error("--soc-sim is required")
    apps = args.apps.split(",") if args.apps else gl_scenes(args.soc_sim)
    work = pathlib.Path(args.work_dir or tempfile.mkdtemp(prefix="check_array_switches_off_"))
    work.mkdir(parents=True, exist_ok=True)
    cases = [(backend, app) for backend in args.backends.split(",") for app in apps]
    failures = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        results = pool.map(lambda case: check(args.soc_sim, case[0], case[1], args.frames, work, args.preset), cases)
        for (backend, app), difference in zip(cases, results):
            if difference:
                failures += 1
                print(f"check_array_switches_off: {backend} {app}: {difference} (runs kept in {work})", file=sys.stderr)
    if failures == 0 and not args.work_dir:
        shutil.rmtree(work)
    what = f"frames with {args.preset}" if args.preset else f"{', '.join(INERT)} changed and their switches off"
    print(f"check_array_switches_off: {len(cases) - failures} of {len(cases)} runs identical with {what}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
