#!/usr/bin/env python3
"""check_skip_idle_cus.py: skipping idle CUs changes nothing but wall time.

Runs every built-in GL scene (soc_sim --list-apps, the "GL ES 1.1 scene"
lines; obj_viewer, which needs a model, runs the teapot's OBJ if given one
with --obj) on each array back end with array.skip_idle_cus=true and
=false, and compares the two runs byte for byte: every frame file, the VCD,
and stats.json with the command line and the switch itself taken out (a
run without --wall-clock has no wall-time figures), which must hold the
array's energy per program stage (stats.energy.array_stages, from the lanes'
activity per stage; CMEM accesses are given an energy for this) in both
runs. Exits 1 naming the first scene that differs, and where.

  check_skip_idle_cus.py --soc-sim build/default/bin/soc_sim [--frames N]
      [--backends ap-tile,ap-pixel] [--apps a,b] [--work-dir DIR] [--jobs J]
      [--set KEY=VALUE ...]

--set passes a setting to every run (both sides), e.g. array.issue_skew=row
to check skipping under row-sequential issue.
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

SWITCH = "array.skip_idle_cus"
SIZE = ["--set", "display.width=192", "--set", "display.height=144"]
# The fitted energy model gives CMEM bytes no energy, which would hide the
# lanes' activity per stage from energy.array_stages: here reads and writes
# cost something, and differently.
CMEM_ENERGY = ["--set", "power.cu_array.cmem_bytes_read_pj=1", "--set", "power.cu_array.cmem_bytes_written_pj=3"]


def run(soc_sim: str, backend: str, app: str, frames: int, skip: bool, out: pathlib.Path, settings: list) -> str:
    command = [
        soc_sim,
        "--backend",
        backend,
        "--app",
        app,
        "--frames",
        str(frames),
        "--out",
        str(out),
        "--vcd",
        str(out / "trace.vcd"),
        "--force",
        "--quiet",
        "--set",
        f"{SWITCH}={str(skip).lower()}",
    ]
    command += SIZE + CMEM_ENERGY
    for setting in settings:
        command += ["--set", setting]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        return f"soc_sim exited {result.returncode}: {' '.join(command)}\n{result.stderr[-2000:]}"
    return ""


def stats_without_switch(path: pathlib.Path) -> dict:
    stats = json.loads(path.read_text())
    stats.pop("command_line", None)
    array = stats.get("config", {}).get("array", {})
    if SWITCH.split(".", 1)[1] not in array:
        raise RuntimeError(f"{path}: no config.{SWITCH}")
    array.pop(SWITCH.split(".", 1)[1])
    return stats


def compare(on: pathlib.Path, off: pathlib.Path) -> str:
    difference = different_files(on, off)
    if difference:
        return difference
    stats_on, stats_off = stats_without_switch(on / "stats.json"), stats_without_switch(off / "stats.json")
    for name, stats in (("on", stats_on), ("off", stats_off)):
        sim = stats.get("stats", {})
        stages = sim.get("energy", {}).get("array_stages")
        if stages is None:
            return f"stats.json ({name}) has no stats.energy.array_stages"
        cmem_joules = sum(stage["units"]["cu_array"]["dynamic_j"] for stage in stages.values())
        if sim.get("array", {}).get("programs", 0) > 0 and cmem_joules <= 0:
            return f"stats.json ({name}): the array ran programs, but no stage's CMEM accesses show in its energy"
    return first_difference(stats_on, stats_off, "stats.json", ("on", "off"))


def check(soc_sim: str, backend: str, app: str, frames: int, work: pathlib.Path, settings: list) -> str:
    on, off = work / f"{backend}_{app}_on", work / f"{backend}_{app}_off"
    for skip, out in ((True, on), (False, off)):
        failure = run(soc_sim, backend, app, frames, skip, out, settings)
        if failure:
            return failure
    difference = compare(on, off)
    if not difference:
        shutil.rmtree(on)
        shutil.rmtree(off)
    return difference


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--soc-sim", required=True)
    parser.add_argument("--frames", type=int, default=2)
    parser.add_argument("--backends", default="ap-tile,ap-pixel")
    parser.add_argument("--apps", default="", help="comma-separated scenes (default: every GL scene)")
    parser.add_argument("--work-dir", default="", help="kept, with the runs that differ (default: a temporary one)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="a setting for every run")
    args = parser.parse_args()
    apps = args.apps.split(",") if args.apps else gl_scenes(args.soc_sim)
    work = pathlib.Path(args.work_dir or tempfile.mkdtemp(prefix="check_skip_idle_cus_"))
    work.mkdir(parents=True, exist_ok=True)
    cases = [(backend, app) for backend in args.backends.split(",") for app in apps]
    failures = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        results = pool.map(lambda case: check(args.soc_sim, case[0], case[1], args.frames, work, args.set), cases)
        for (backend, app), difference in zip(cases, results):
            if difference:
                failures += 1
                print(f"check_skip_idle_cus: {backend} {app}: {difference} (runs kept in {work})", file=sys.stderr)
            else:
                print(f"check_skip_idle_cus: {backend} {app}: frames, VCD and stats.json identical")
    if failures == 0 and not args.work_dir:
        shutil.rmtree(work)
    print(f"check_skip_idle_cus: {len(cases) - failures} of {len(cases)} runs identical with {SWITCH} on and off")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
