#!/usr/bin/env python3
"""Soak benchmark (a command, not a test): one long soc_sim run with the
display DMA and a VCD trace on, its resident memory sampled from /proc while
it runs; prints RSS at intervals and the slope of RSS against frames.

    scripts/soak.py [--frames 10000] [--backend arm] [--app teapot] [--interval 1] [--no-vcd]

A flat model has a slope near zero once warmed up. soc_sim runs with
--wall-clock, so stats.json gives each frame's wall time from the start of
the simulation; a sample's frame is the number of frames shown by its time
(the process's start-up before the simulation, well under a second, is not
subtracted). The slope is a least-squares fit over the samples from 10% of
the frames (warm-up: the scene's set-up, first allocations, the VCD
writer's buffers) to the last frame. Samples after the last frame, while
soc_sim builds and writes stats.json, are reported apart: that peak grows
with the number of frames, as the file does. The VCD is
written into a temporary folder and removed afterwards unless --keep
(about 0.46 MB per teapot frame at 320 x 240); --no-vcd leaves it out, for
runs of 100,000 frames and more (soc_sim streams the frames' statistics to
side files and merges them into stats.json at the end, so its memory stays
flat however many frames: the cheapest run, the pattern application on the
arm back end, is `--app pattern --frames 100000 --no-vcd`: 250 s on the
loaded 2-core machine, RSS 28.8 MiB from frame 10,274 to frame 99,981,
slope +0.0 KiB per 1000 frames, 29.0 MiB while stats.json was merged; it
kept about 1.7 KiB per frame before the streaming).
"""

from __future__ import annotations

import argparse
import bisect
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

DEFAULT_SOC_SIM = Path(__file__).resolve().parents[1] / "build" / "default" / "bin" / "soc_sim"


def rss_kib(pid: int) -> int | None:
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    except (OSError, ValueError):
        return None
    return None


def slope(points: list[tuple[float, float]]) -> float:
    """Least-squares slope of y against x."""
    n = len(points)
    mean_x = sum(x for x, _ in points) / n
    mean_y = sum(y for _, y in points) / n
    sxx = sum((x - mean_x) ** 2 for x, _ in points)
    sxy = sum((x - mean_x) * (y - mean_y) for x, y in points)
    return sxy / sxx if sxx else 0.0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=10000)
    parser.add_argument("--backend", default="arm")
    parser.add_argument("--app", default="teapot")
    parser.add_argument("--interval", type=float, default=1.0, help="seconds between RSS samples")
    parser.add_argument("--soc-sim", default=os.environ.get("TESSERA_SOC_SIM", DEFAULT_SOC_SIM))
    parser.add_argument("--keep", type=Path, help="keep the run's folder (stats.json, trace.vcd) here")
    parser.add_argument("--no-vcd", action="store_true", help="no VCD trace (it grows with the frames)")
    options = parser.parse_args()
    if options.frames < 10 or options.interval <= 0:
        parser.error("--frames must be at least 10 and --interval positive")
    if not Path(options.soc_sim).is_file():
        parser.error(f"soc_sim not found at {options.soc_sim} (build it, or pass --soc-sim)")

    scratch = Path(tempfile.mkdtemp(prefix="soak_"))
    out = options.keep or scratch / "run"
    command = [
        str(options.soc_sim),
        "--app",
        options.app,
        "--backend",
        options.backend,
        "--frames",
        str(options.frames),
        "--no-frames",
        "--set",
        "display.dma=true",
        "--out",
        str(out),
        "--force",
        "-q",
        "--wall-clock",
    ]
    if not options.no_vcd:
        command += ["--vcd", str(out / "trace.vcd")]
    out.mkdir(parents=True, exist_ok=True)
    samples: list[tuple[float, int]] = []  # (wall seconds, RSS KiB)
    start = time.monotonic()
    try:
        process = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
        while process.poll() is None:
            value = rss_kib(process.pid)
            if value:  # 0 before the process has mapped anything
                samples.append((time.monotonic() - start, value))
            time.sleep(options.interval)
        wall = time.monotonic() - start
        error = process.stderr.read()
        if process.returncode != 0:
            print(f"soak: soc_sim exited with status {process.returncode}: {error.strip()}", file=sys.stderr)
            return 1
        vcd_bytes = 0 if options.no_vcd else (out / "trace.vcd").stat().st_size
        frames = json.loads((out / "stats.json").read_text())["stats"]["frames"]
        frame_seconds = [frame["wall_ns"] / 1e9 for frame in frames]
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    if len(samples) < 5:
        print(
            f"soak: only {len(samples)} RSS samples in {wall:.1f} s: use more --frames or a smaller --interval",
            file=sys.stderr,
        )
        return 1

    frames_per_second = len(frame_seconds) / frame_seconds[-1]
    points = [(bisect.bisect_right(frame_seconds, t), rss) for t, rss in samples]
    running = [p for p, (t, _) in zip(points, samples) if t <= frame_seconds[-1]]
    after = [rss for t, rss in samples if t > frame_seconds[-1]]
    warm = [p for p in running if p[0] >= 0.1 * len(frame_seconds)] or running or points
    kib_per_1000_frames = slope(warm) * 1000
    print(
        f"soc_sim {options.app} on {options.backend}, {len(frame_seconds)} frames, display DMA "
        f"{'on, no VCD' if options.no_vcd else f'and VCD on (VCD {vcd_bytes / 1e9:.2f} GB)'}: "
        f"{wall:.1f} s wall, {frames_per_second:.1f} frames/s while simulating\n"
    )
    print("| frames shown | RSS (MiB) |")
    print("|---|---|")
    step = max(1, len(running) // 10)
    for index in sorted(set(range(0, len(running), step)) | {len(running) - 1}):
        frame, rss = running[index]
        print(f"| {frame} | {rss / 1024:.1f} |")
    print(
        f"\nRSS from frame {warm[0][0]} to the last: {warm[0][1] / 1024:.1f} MiB -> {warm[-1][1] / 1024:.1f} MiB; "
        f"slope {kib_per_1000_frames:+.1f} KiB per 1000 frames (least squares over {len(warm)} samples)"
    )
    if after:
        print(
            f"After the last frame (statistics built and written): peak {max(after) / 1024:.1f} MiB "
            f"({len(after)} samples)"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
