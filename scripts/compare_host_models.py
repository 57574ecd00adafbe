#!/usr/bin/python3
"""Compares the two host models on every built-in GL scene.

For each scene and back end, runs soc_sim twice, host-compiled
(host.model=native: the cost model) and on the ISS (host.model=iss: the
driver cross-compiled for the ARM922T), with the same configuration, and
prints one Markdown table of the simulated time per frame, by phase of the
driver (the frame records' host_<phase>_ns figures: geometry,
rasterization, presenting, the application's own code), for the frames
after the first (the first holds the start-up: the ISS program parses its
boot information, the scenes build their meshes). The ISS is the reference:
the last columns are the host-compiled model's error against it. For the
array back ends (ap-tile, ap-pixel, ap-object) a second table gives their split of
the host's time (the frame records' host_compute_ns, host_write_ns,
host_read_ns, host_wait_ns, host_frame_out_ns), checked with --check like
the phases.

    scripts/compare_host_models.py                     # every scene, every back end, 3 frames
    scripts/compare_host_models.py --backend arm --scene teapot --frames 5
    scripts/compare_host_models.py --soc-sim build/default/bin/soc_sim --out out/host_models

Simulated times are exact and repeatable; this script times nothing on the
wall clock. docs/calibration.md ("The two host models") has the last table
and how to read it. Exit status: 0, 1 when a run fails, 2 for a bad command
line.
"""

import argparse
import json
import os
import pathlib
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

from run_outputs import SCENE_ARGUMENTS

ROOT = pathlib.Path(__file__).resolve().parent.parent
PHASES = ["geometry", "rasterization", "presenting", "application"]
# The array back ends' split of the host's time (renderers/common/host_time.h).
SPLIT = ["compute", "write", "read", "wait", "frame_out"]
ARRAY_BACKENDS = ("ap-tile", "ap-pixel", "ap-object")


def scenes(soc_sim):
    out = subprocess.run([soc_sim, "--list-apps"], capture_output=True, text=True, check=True).stdout
    return [line.split()[0] for line in out.splitlines() if "GL ES 1.1 scene" in line]


def recorded_frames(folder):
    """The frame records of an earlier run in `folder`, or None."""
    path = folder / "stats.json"
    if not path.is_file():
        return None
    return json.loads(path.read_text())["stats"]["frames"]


def run(soc_sim, out, scene, backend, model, frames, iss_from=None):
    folder = out / f"{scene}_{backend}_{model}"
    recorded = recorded_frames(iss_from / folder.name) if iss_from is not None and model == "iss" else None
    if recorded is not None:
        frames = len(recorded)
    else:
        command = [
            soc_sim,
            "--app",
            scene,
            "--backend",
            backend,
            "--frames",
            str(frames),
            "--no-frames",
            "--quiet",
            "--force",
            "--out",
            str(folder.resolve()),
            "--set",
            f"host.model={model}",
        ]
        if scene in SCENE_ARGUMENTS:
            command += ["--", *SCENE_ARGUMENTS[scene]]
        result = subprocess.run(command, capture_output=True, text=True, cwd=ROOT)
        if result.returncode != 0:
            raise RuntimeError(f"{' '.join(command)} exited with {result.returncode}: {result.stderr.strip()}")
        recorded = recorded_frames(folder)
    later = recorded[1:]
    if not later:
        raise RuntimeError(f"{scene} on {backend} ({model}): fewer than 2 frames shown")
    per_frame = {"render": sum(f["render_ns"] for f in later) / len(later) / 1e6}
    for phase in PHASES + SPLIT:
        per_frame[phase] = sum(f.get("driver", {}).get(f"host_{phase}_ns", 0.0) for f in later) / len(later) / 1e6
    return per_frame


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--soc-sim", default=str(ROOT / "build" / "default" / "bin" / "soc_sim"))
    parser.add_argument(
        "--backend", action="append", help="back end (repeatable; default arm, raster, ap-tile and ap-pixel)"
    )
    parser.add_argument("--scene", action="append", help="scene (repeatable; default every built-in GL scene)")
    parser.add_argument("--frames", type=int, default=3, help="frames per run (>= 2; frames 1.. are averaged)")
    parser.add_argument("--out", default="out/host_models", help="folder for the runs' statistics")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument(
        "--check",
        type=float,
        metavar="PERCENT",
        help="exit 1 unless every frame, and every phase that holds at least --floor of its frame, "
        "is within PERCENT of the ISS's",
    )
    parser.add_argument(
        "--floor",
        type=float,
        default=1.0,
        metavar="PERCENT",
        help="the share of the frame below which --check leaves a phase out (default 1)",
    )
    parser.add_argument(
        "--iss-from",
        metavar="DIR",
        help="take the ISS's runs from DIR where it has them (<scene>_<back end>_iss/stats.json, "
        "as scripts/measure_host_costs.py leaves them: the ISS's times do not depend on the "
        "table) and run the host-compiled model for as many frames",
    )
    parser.add_argument(
        "--doc",
        metavar="FILE",
        help="also exit 1 when FILE's table (between <!-- host-models:begin --> and "
        "<!-- host-models:end -->) is not the one printed",
    )
    parser.add_argument("--write-doc", action="store_true", help="write the printed tables into --doc's FILE")
    args = parser.parse_args()
    # The runs start in the repository (SCENE_ARGUMENTS' OBJ file): a relative path given here is the caller's.
    args.soc_sim = str(pathlib.Path(args.soc_sim).resolve())
    if args.frames < 2:
        parser.error("--frames must be at least 2")
    if args.write_doc and not args.doc:
        parser.error("--write-doc needs --doc FILE")
    if not os.access(args.soc_sim, os.X_OK):
        parser.error(f"no soc_sim at {args.soc_sim}")
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    backends = args.backend or ["arm", "raster", *ARRAY_BACKENDS]
    chosen = args.scene or scenes(args.soc_sim)
    cases = [(scene, backend) for backend in backends for scene in chosen]
    iss_from = pathlib.Path(args.iss_from) if args.iss_from else None
    frames = {}
    for scene, backend in cases:
        recorded = recorded_frames(iss_from / f"{scene}_{backend}_iss") if iss_from is not None else None
        frames[(scene, backend)] = len(recorded) if recorded is not None else args.frames
    with ThreadPoolExecutor(args.jobs) as pool:
        futures = {
            (scene, backend, model): pool.submit(
                run, args.soc_sim, out, scene, backend, model, frames[(scene, backend)], iss_from
            )
            for scene, backend in cases
            for model in ("native", "iss")
        }
        try:
            results = {key: future.result() for key, future in futures.items()}
        except RuntimeError as error:
            print(f"compare_host_models: {error}", file=sys.stderr)
            return 1

    table = []

    def emit(text):
        table.extend(text.split("\n"))

    emit(
        "Simulated ms per frame (the frames after the first), host-compiled (native) / ISS, and the "
        "host-compiled model's error against the ISS:\n"
    )
    header = ["scene", "back end", "frame: native / ISS"] + [f"{p}: native / ISS" for p in PHASES]
    header += ["frame error", "host-phases error"]
    emit("| " + " | ".join(header) + " |")
    emit("|" + "|".join(["---"] * 2 + ["--:"] * (len(header) - 2)) + "|")
    outside = []
    for scene, backend in cases:
        n, i = results[(scene, backend, "native")], results[(scene, backend, "iss")]
        if args.check is not None:
            checked = [("frame", n["render"], i["render"])]
            parts = PHASES + (SPLIT if backend in ARRAY_BACKENDS else [])
            checked += [(p, n[p], i[p]) for p in parts if i[p] >= args.floor / 100 * i["render"]]
            for what, native, iss in checked:
                error = (native / iss - 1) * 100 if iss > 0 else float("inf")
                if abs(error) > args.check:
                    outside.append(f"{scene} on {backend}, {what}: {native:.2f} / {iss:.2f} ms ({error:+.1f}%)")
        cells = [scene, backend, f"{n['render']:.2f} / {i['render']:.2f}"]
        cells += [f"{n[p]:.2f} / {i[p]:.2f}" for p in PHASES]
        host_n = sum(n[p] for p in PHASES if p != "application")
        host_i = sum(i[p] for p in PHASES if p != "application")
        cells.append(f"{(n['render'] / i['render'] - 1) * 100:+.0f}%")
        cells.append(f"{(host_n / host_i - 1) * 100:+.0f}%" if host_i > 0 else "-")
        emit("| " + " | ".join(cells) + " |")
    array_cases = [(scene, backend) for scene, backend in cases if backend in ARRAY_BACKENDS]
    if array_cases:
        emit("\nThe array back ends' host time by part (ms per frame, native / ISS, and the error):\n")
        header = ["scene", "back end"] + [f"{p}: native / ISS" for p in SPLIT]
        emit("| " + " | ".join(header) + " |")
        emit("|" + "|".join(["---"] * 2 + ["--:"] * (len(header) - 2)) + "|")
        for scene, backend in array_cases:
            n, i = results[(scene, backend, "native")], results[(scene, backend, "iss")]
            cells = [scene, backend]
            for p in SPLIT:
                error = f" ({(n[p] / i[p] - 1) * 100:+.0f}%)" if i[p] > 0 else ""
                cells.append(f"{n[p]:.2f} / {i[p]:.2f}{error}")
            emit("| " + " | ".join(cells) + " |")
    print("\n".join(table))
    stale = False
    if args.doc:
        doc = pathlib.Path(args.doc)
        text = doc.read_text()
        begin, end = "<!-- host-models:begin -->\n", "<!-- host-models:end -->"
        if begin not in text or end not in text:
            parser.error(f"{doc} has no {begin.strip()} ... {end} block")
        head, rest = text.split(begin, 1)
        tail = rest.split(end, 1)[1]
        block = "\n".join(table) + "\n"
        if args.write_doc:
            doc.write_text(head + begin + block + end + tail)
            print(f"\nwrote the tables into {doc}")
        elif rest.split(end, 1)[0] != block:
            print(f"\n{doc}'s table is not this one: run scripts/compare_host_models.py --doc {doc} --write-doc")
            stale = True
    if args.check is not None:
        if outside:
            print(f"\n{len(outside)} outside +-{args.check:g}%:\n  " + "\n  ".join(outside))
            return 1
        print(f"\nevery frame, and every phase of at least {args.floor:g}% of its frame, within +-{args.check:g}%")
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
