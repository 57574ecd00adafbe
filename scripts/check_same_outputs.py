#!/usr/bin/env python3
"""check_same_outputs.py: a change of shape changes no output.

Records, for a fixed set of runs, every output soc_sim writes (each frame
file, the VCD, stats.json) into a manifest, and compares a later build's
runs with it byte for byte. The runs: every built-in GL scene on every back
end on the host-compiled model, the calibration and study applications on
the back ends they run on, and a set of scenes on the ISS (host.model=iss)
on every back end; each with the VCD on, at 192 x 144 (the study's size),
two frames; and the native runs again without the VCD (tracing takes
the paths that observe every transaction). From stats.json only the command line, the commit and the
version are taken out (they name the build, not the run); everything else,
every figure of every block, must be equal.

  check_same_outputs.py --soc-sim build/default/bin/soc_sim --record before.json
  check_same_outputs.py --soc-sim build/default/bin/soc_sim --compare before.json

Options: --iss-frames-only (a change that moves the ARM program's code
changes the ISS's timing, its function table in the VCD's trace.functions.txt
and so the ISS runs' statistics: compares only their frames, and counts the
runs whose other outputs moved), --removed-keys K1,K2 (configuration keys a change removed, such as
raster.width: dropped from the manifest's configuration when the new build
has no such key), --added-keys K1,K2 (configuration keys a change added, such as
array.features.divide, a switch whose default keeps the old behaviour: dropped
from the new run's configuration when the manifest has no such key), --jobs J
(default 2), --quick (only the native GL scenes on arm and ap-tile, for a fast
look), --work-dir DIR (kept, with the runs that differ).
--compare exits 1 naming each run that differs and the first difference in
it; a run missing on either side is a difference too.
"""

import argparse
import concurrent.futures
import hashlib
import json
import pathlib
import shutil
import subprocess
import sys
import tempfile

from json_difference import first_difference
from run_outputs import gl_scenes

SIZE = ["--set", "display.width=192", "--set", "display.height=144"]
BACKENDS = ["arm", "raster", "ap-tile", "ap-pixel"]
ISS_SCENES = ["triangle", "textured_quad", "tile_grid", "fog_row"]
BUILD_IDENTITY = ("command_line", "commit", "version")
# Applications that are not GL scenes, and the back ends each runs on.
OTHER_APPS = {
    "pattern": ["arm"],
    "calib_add": ["arm"],
    "calib_mul": ["arm"],
    "calib_ciu": ["ap-tile"],
    "calib_display_port": ["arm"],
    "calib_array_add": ["ap-tile"],
    "calib_array_mul": ["ap-tile"],
    "calib_array_add_cmem": ["ap-tile"],
    "calib_array_mul_cmem": ["ap-tile"],
    "study_shading": ["arm", "ap-pixel"],
    "study_patches": ["arm", "ap-pixel"],
}
# The two study applications at a size that keeps the check quick.
APP_ARGUMENTS = {"study_shading": ["--", "--shades", "2000"], "study_patches": ["--", "--max-pixels", "12"]}


def cases(soc_sim: str, quick: bool) -> list:
    scenes = gl_scenes(soc_sim)
    if quick:
        return [("native", backend, app) for backend in ("arm", "ap-tile") for app in scenes]
    found = [("native", backend, app) for backend in BACKENDS for app in scenes]
    found += [("native", backend, app) for app, backends in OTHER_APPS.items() for backend in backends]
    found += [("iss", backend, app) for backend in BACKENDS for app in ISS_SCENES]
    # The same native runs without the VCD: tracing takes the paths that
    # observe each transaction (a store train goes out word by word while
    # the bus or the CIU traces), so the untraced paths are compared too.
    native = [case for case in found if case[0] == "native"]
    found += [case + (NO_VCD,) for case in native]
    return found


def case_name(case: tuple) -> str:
    return "/".join(case)


def raster_size_keys(soc_sim: str) -> list:
    """A build that still has raster.width and raster.height needs them set to the display's size."""
    config = json.loads(subprocess.run([soc_sim, "--print-config"], check=True, capture_output=True, text=True).stdout)
    if "width" not in config.get("raster", {}):
        return []
    return ["--set", "raster.width=192", "--set", "raster.height=144"]


NO_VCD = "no-vcd"


def run(soc_sim: str, case: tuple, out: pathlib.Path) -> str:
    host, backend, app = case[:3]
    vcd = [] if case[3:] == (NO_VCD,) else ["--vcd", str(out / "trace.vcd")]
    command = [
        soc_sim,
        "--backend",
        backend,
        "--app",
        app,
        "--frames",
        "2",
        "--out",
        str(out),
        *vcd,
        "--force",
        "--quiet",
        "--set",
        f"host.model={host}",
    ]
    command += SIZE + (RASTER_SIZE if backend == "raster" else []) + APP_ARGUMENTS.get(app, [])
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        return f"soc_sim exited {result.returncode}: {' '.join(command)}\n{result.stderr[-2000:]}"
    return ""


RASTER_SIZE: list = []


def config_parent(config: dict, key: str):
    """The dictionary holding a dotted key's last part (array.cycles.div: config["array"]["cycles"]), or None."""
    *path, _ = key.split(".")
    for part in path:
        config = config.get(part)
        if not isinstance(config, dict):
            return None
    return config


def has_config_key(config: dict, key: str) -> bool:
    parent = config_parent(config, key)
    return parent is not None and key.split(".")[-1] in parent


def drop_config_key(config: dict, key: str) -> None:
    """Drops the key, then each group it leaves empty (array.features once its switches are gone)."""
    parts = key.split(".")
    for depth in range(len(parts), 0, -1):
        parent = config_parent(config, ".".join(parts[:depth]))
        if parent is None or (depth < len(parts) and parent.get(parts[depth - 1])):
            return
        parent.pop(parts[depth - 1], None)


def outputs(out: pathlib.Path) -> dict:
    """The run's outputs: a digest per file, and stats.json without the build's identity."""
    record = {"files": {}, "stats": None}
    for path in sorted(out.iterdir()):
        if path.name == "stats.json":
            stats = json.loads(path.read_text())
            for key in BUILD_IDENTITY:
                stats.pop(key, None)
            record["stats"] = stats
        else:
            record["files"][path.name] = hashlib.sha256(path.read_bytes()).hexdigest()
    return record


def measure(soc_sim: str, case: tuple, work: pathlib.Path):
    out = work / case_name(case).replace("/", "_")
    failure = run(soc_sim, case, out)
    if failure:
        return None, failure
    record = outputs(out)
    if not any(name.startswith("frame_") for name in record["files"]) and case[2] not in OTHER_APPS:
        return None, f"no frame written: {sorted(record['files'])}"
    return record, ""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--soc-sim", required=True)
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--record", help="write the manifest to FILE")
    mode.add_argument("--compare", help="compare with the manifest in FILE")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument(
        "--iss-frames-only",
        action="store_true",
        help="on the ISS compare the frames only (for a change that moves the ARM program's code)",
    )
    parser.add_argument("--work-dir", default="")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument(
        "--removed-keys", default="", help="comma-separated configuration keys (raster.width) that may be gone after"
    )
    parser.add_argument(
        "--added-keys", default="", help="comma-separated configuration keys (array.features.divide) new in this build"
    )
    args = parser.parse_args()
    RASTER_SIZE[:] = raster_size_keys(args.soc_sim)

    before = json.loads(pathlib.Path(args.compare).read_text()) if args.compare else None
    work = pathlib.Path(args.work_dir or tempfile.mkdtemp(prefix="check_same_outputs_"))
    work.mkdir(parents=True, exist_ok=True)
    todo = cases(args.soc_sim, args.quick)
    if before is not None and not args.quick:
        names = {case_name(case) for case in todo}
        todo += [tuple(name.split("/")) for name in before["runs"] if name not in names]
    failures, iss_timing_moved, manifest = 0, 0, {"runs": {}}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        results = pool.map(lambda case: measure(args.soc_sim, case, work), todo)
        for case, (record, failure) in zip(todo, results):
            name = case_name(case)
            if failure:
                failures += 1
                print(f"check_same_outputs: {name}: {failure}", file=sys.stderr)
                continue
            manifest["runs"][name] = record
            if before is None:
                continue
            if name not in before["runs"]:
                failures += 1
                print(f"check_same_outputs: {name}: not in the manifest {args.compare}", file=sys.stderr)
                continue
            old = json.loads(json.dumps(before["runs"][name]))
            if args.iss_frames_only and case[0] == "iss":
                frames = {k: v for k, v in record["files"].items() if k.startswith("frame_")}
                old_frames = {k: v for k, v in old["files"].items() if k.startswith("frame_")}
                difference = first_difference(old_frames, frames, "files")
                if difference:
                    failures += 1
                    print(f"check_same_outputs: {name}: {difference}", file=sys.stderr)
                elif first_difference(old["files"], record["files"]) or first_difference(old["stats"], record["stats"]):
                    iss_timing_moved += 1
                continue
            for key in filter(None, args.removed_keys.split(",")):
                group, field = key.split(".", 1)
                if field not in record["stats"]["config"].get(group, {}):
                    old["stats"]["config"].get(group, {}).pop(field, None)
            new = json.loads(json.dumps(record))
            for key in filter(None, args.added_keys.split(",")):
                if not has_config_key(old["stats"]["config"], key):
                    drop_config_key(new["stats"]["config"], key)
            difference = first_difference(old["files"], new["files"], "files")
            difference = difference or first_difference(old["stats"], new["stats"], "stats.json")
            if difference:
                failures += 1
                print(f"check_same_outputs: {name}: {difference}", file=sys.stderr)
    if args.record:
        pathlib.Path(args.record).write_text(json.dumps(manifest, sort_keys=True) + "\n")
    if failures == 0 and not args.work_dir:
        shutil.rmtree(work)
    verb = "recorded" if args.record else "identical to the manifest"
    if args.iss_frames_only:
        verb += f" (ISS runs: frames only; {iss_timing_moved} of them with other outputs changed)"
    print(
        f"check_same_outputs: {len(todo) - failures} of {len(todo)} runs {verb} "
        f"(frames, VCD, stats.json; {sum(len(r['files']) for r in manifest['runs'].values())} files)"
    )
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
