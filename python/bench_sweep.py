"""Benchmark (a command, not a test): the same 16-point sweep on a local
Dask cluster of 1 and of 2 workers, paired and repeated; prints min and
median wall time of each and the speed-up of the medians.

    build/venv/bin/python3 python/bench_sweep.py [--repeat 3] [--frames 1000]

Each run starts from an empty output folder (nothing cached). Two times
of each run: the whole run_sweep call, as a user sees it (the points'
check, one soc_sim --print-config each; the cluster's start and stop; the
16 soc_sim processes; the table and the report), and its runs alone (first
point submitted to last result: what the workers share). The runs alternate
(1 then 2 workers, then 2 then 1, ...) so that a change of the machine's
load falls on both. Points: the teapot at 192 x 144 on arm and raster, four
bus clocks, the display DMA off and on, --frames frames each, no PNG.

A third pair of rows is the machine's own ceiling: the same 16 soc_sim
commands started directly, one or two at a time, without Dask (a thread
per slot waiting for its process). The sweep cannot scale better than two
soc_sim processes scale on the machine's two cores.
"""

from __future__ import annotations

import argparse
import os
import platform
import shutil
import statistics
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from contextlib import redirect_stderr
from io import StringIO
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from tessera_sweep import Simulator  # noqa: E402
from tessera_sweep.cli import DEFAULT_SOC_SIM  # noqa: E402
from tessera_sweep.runner import run_sweep  # noqa: E402
from tessera_sweep.spec import expand, parse_spec  # noqa: E402


def sweep_spec(frames: int):
    return parse_spec(
        {
            "app": "teapot",
            "frames": frames,
            "config": {"display.width": 192, "display.height": 144},
            "axes": {
                "driver.backend": ["arm", "raster"],
                "bus.clock_mhz": [48, 96, 144, 192],
                "display.dma": [False, True],
            },
        }
    )


def timed_sweep(spec, simulator, workers: int, scratch: Path) -> dict:
    out = scratch / f"w{workers}"
    shutil.rmtree(out, ignore_errors=True)
    phases = {}
    with redirect_stderr(StringIO()):  # progress lines
        table, ran = run_sweep(spec, simulator, out, workers=workers, phases=phases)
    failed = int((table["status"] != 0).sum())
    if ran != 16 or failed:
        raise SystemExit(f"bench_sweep: {ran} points ran, {failed} failed (expected 16 and 0): see {out}/results.csv")
    return phases


def direct_runs(spec, simulator, slots: int, scratch: Path) -> dict:
    """The 16 points' soc_sim runs without Dask, `slots` at a time."""
    points = expand(spec)
    out = scratch / f"direct{slots}"
    shutil.rmtree(out, ignore_errors=True)

    def run(index: int):
        return simulator.run(points[index].settings, list(points[index].args), out / str(index), spec.write_frames)

    start = time.perf_counter()
    with ThreadPoolExecutor(max_workers=slots) as pool:
        results = list(pool.map(run, range(len(points))))
    elapsed = time.perf_counter() - start
    failed = [result.error for result in results if result.status != 0]
    if failed:
        raise SystemExit(f"bench_sweep: {len(failed)} direct runs failed: {failed[0]}")
    return {"direct_s": elapsed}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=3, help="pairs of runs (default 3)")
    parser.add_argument("--frames", type=int, default=1000, help="frames per point (default 1000)")
    parser.add_argument("--soc-sim", default=os.environ.get("TESSERA_SOC_SIM", DEFAULT_SOC_SIM))
    options = parser.parse_args()
    if options.repeat < 1 or options.frames < 1:
        parser.error("--repeat and --frames must be at least 1")
    simulator = Simulator(options.soc_sim)
    spec = sweep_spec(options.frames)
    times = {1: [], 2: []}  # phases of each run
    with tempfile.TemporaryDirectory(prefix="bench_sweep_") as scratch:
        for repeat in range(options.repeat):
            for workers in (1, 2) if repeat % 2 == 0 else (2, 1):
                times[workers].append(timed_sweep(spec, simulator, workers, Path(scratch)))
                times[workers][-1].update(direct_runs(spec, simulator, workers, Path(scratch)))
                phases = times[workers][-1]
                print(
                    f"  pair {repeat + 1}/{options.repeat}, {workers} worker(s): {phases['total_s']:.2f} s, "
                    f"runs {phases['runs_s']:.2f} s, without Dask {phases['direct_s']:.2f} s",
                    file=sys.stderr,
                    flush=True,
                )
    print(
        f"Machine: {os.cpu_count()} cores, {platform.processor() or platform.machine()}, "
        f"Python {platform.python_version()}; soc_sim {simulator.version}"
    )
    print(f"16 points (teapot 192x144, {options.frames} frames each), {options.repeat} paired runs\n")
    print("| what | local workers (or runs at a time) | min (s) | median (s) | speed-up (medians) |")
    print("|---|---|---|---|---|")
    for phase, name in (
        ("total_s", "whole sweep"),
        ("runs_s", "runs alone"),
        ("direct_s", "soc_sim runs without Dask (ceiling)"),
    ):
        median = {workers: statistics.median(run[phase] for run in runs) for workers, runs in times.items()}
        for workers in (1, 2):
            print(
                f"| {name} | {workers} | {min(run[phase] for run in times[workers]):.2f} | "
                f"{median[workers]:.2f} | {median[1] / median[workers]:.2f}x |"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
