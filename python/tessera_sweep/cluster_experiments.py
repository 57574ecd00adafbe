#!/usr/bin/env python3
"""The cluster platform's experiments (docs/experiments.md, "The sort-middle cluster"): Crockett and Orloff's
questions asked of p ARM922T nodes, one command each, each printing its Markdown table and writing it with a CSV
(and a plot where matplotlib is present) to out/experiments/cluster_<name>.

    scripts/cluster_experiments.py depth      time per frame against the buffer depth d, p = 8 .. 64 (the paper's
                                              Fig. 7), the paper's model t(d) = C0 + C1/d + C2 d fitted per p, the
                                              fitted latency and wait constants, Eq. 11's d_opt against the best d
    scripts/cluster_experiments.py speedup    rate, speed-up and efficiency over n and p (the paper's Table 3), and
                                              the frame's time split into the model's components against p
    scripts/cluster_experiments.py all

Options: --triangles N (the depth sweep's scene; default 100,000, the paper's standard scene), --config FILE (e.g.
configs/presets/ipsc860_like.json), --frames F (default 3; figures are the mean of frames 1 .. F-1, frame 0 holds
the start-up), --soc-sim, --out, --jobs. Every run is soc_sim --platform cluster at 512 x 512 on the host-compiled
model (host.model=native), the random scene of 10-pixel triangles, seed 1.
"""

import argparse
import csv
import json
import pathlib
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))
from tessera_sweep import sort_middle_model as model  # noqa: E402

CLOCK_HZ = 192e6
DEPTHS = [1, 2, 4, 8, 16, 32, 64]
DEPTH_NODES = [8, 16, 32, 64]
SPEEDUP_TRIANGLES = [6250, 25000, 100000]
SPEEDUP_NODES = [1, 2, 4, 8, 16, 32, 64, 128]
PHASES = ["compute", "split", "send", "wait", "termination"]


def run(args, name, settings):
    """One soc_sim run; its frames' mean time (s) after frame 0 and the nodes' mean phase cycles over those frames."""
    folder = pathlib.Path(args.out) / "runs" / name
    command = [
        args.soc_sim,
        "--platform",
        "cluster",
        "--frames",
        str(args.frames),
        "--no-frames",
        "--quiet",
        "--force",
        "--out",
        str(folder),
    ]
    for config in args.config:
        command += ["--config", config]
    for key, value in settings.items():
        command += ["--set", f"{key}={value}"]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: exit {result.returncode}: {result.stderr.strip()}")
    stats = json.loads((folder / "stats.json").read_text())["stats"]
    frames = stats["frames"][1:]
    seconds = sum(f["render_ns"] for f in frames) / len(frames) * 1e-9
    nodes = stats["nodes"]
    phases = {
        phase: sum(f[f"cycles_{phase}"] for n in nodes for f in n["frames"][1:]) / (len(nodes) * len(frames))
        for phase in PHASES
    }
    busiest = max(sum(f["cycles"] for f in n["frames"][1:]) / len(frames) for n in nodes)
    messages = sum(f["messages_sent"] for n in nodes for f in n["frames"][1:]) / len(frames)
    trapezoids = sum(f["trapezoids_made"] for n in nodes for f in n["frames"][1:]) / len(frames)
    energy = sum(f["energy"]["total_j"] for f in frames) / len(frames)
    return {
        "seconds": seconds,
        "phases": phases,
        "busiest_cycles": busiest,
        "messages": messages,
        "trapezoids": trapezoids,
        "energy_j": energy,
    }


def run_all(args, jobs, name_of):
    """Every run of `jobs` (key -> settings), --jobs at a time; key -> run()'s figures."""
    with ThreadPoolExecutor(args.jobs) as pool:
        futures = {key: pool.submit(run, args, name_of(key), settings) for key, settings in jobs.items()}
        return {key: future.result() for key, future in futures.items()}


def write(args, name, header, rows, caption):
    folder = pathlib.Path(args.out)
    folder.mkdir(parents=True, exist_ok=True)
    with open(folder / f"cluster_{name}.csv", "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(header)
        writer.writerows(rows)
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("--:" for _ in header) + "|"]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    text = "\n".join(lines) + "\n\n" + caption + "\n"
    (folder / f"cluster_{name}.md").write_text(text)
    print(text)


def plot(args, name, series, xlabel, ylabel, logx=True):
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    figure, axes = plt.subplots(figsize=(6, 4))
    for label, (xs, ys) in series.items():
        axes.plot(xs, ys, marker="o", label=label)
    if logx:
        axes.set_xscale("log", base=2)
    axes.set_xlabel(xlabel)
    axes.set_ylabel(ylabel)
    axes.legend()
    axes.grid(True, alpha=0.3)
    figure.tight_layout()
    figure.savefig(pathlib.Path(args.out) / f"cluster_{name}.png", dpi=100)


def depth(args):
    jobs = {
        (p, d): {"cluster.nodes": p, "cluster.triangles": args.triangles, "cluster.buffer_depth": d}
        for p in DEPTH_NODES
        for d in DEPTHS
    }
    results = run_all(args, jobs, lambda key: f"depth_p{key[0]}_d{key[1]}")
    rows = []
    for d in DEPTHS:
        rows.append([d] + [f"{results[(p, d)]['seconds'] * 1e3:,.2f}" for p in DEPTH_NODES])
    write(
        args,
        "depth",
        ["d"] + [f"p = {p} (ms)" for p in DEPTH_NODES],
        rows,
        f"Time per frame against the buffer depth d: {args.triangles:,} random 10-pixel triangles at 512 x 512, "
        f"host.model=native, mean of frames 1 .. {args.frames - 1}.",
    )
    plot(
        args,
        "depth",
        {f"p = {p}": (DEPTHS, [results[(p, d)]["seconds"] * 1e3 for d in DEPTHS]) for p in DEPTH_NODES},
        "buffer depth d (trapezoids per message)",
        "time per frame (ms)",
    )
    fits = []
    for p in DEPTH_NODES:
        ds = [float(d) for d in DEPTHS]
        ts = [results[(p, d)]["seconds"] for d in DEPTHS]
        c0, c1, c2 = model.fit_depth_curve(ds, ts)
        v = results[(p, 1)]["trapezoids"] / p / p  # trapezoids a node makes per destination
        t_l, alpha = model.latency_and_wait(c1, c2, p, v)
        d_opt = model.optimal_depth(p, v, t_l, alpha) if t_l > 0 and alpha > 0 else float("nan")
        best = min(DEPTHS, key=lambda d: results[(p, d)]["seconds"])
        fits.append(
            [
                p,
                f"{c0 * 1e3:,.3f}",
                f"{c1 * 1e6:,.1f}",
                f"{c2 * 1e6:,.3f}",
                f"{t_l * 1e6:,.2f}",
                f"{alpha * 1e6:,.3f}",
                f"{d_opt:,.1f}",
                best,
            ]
        )
    write(
        args,
        "depth_fit",
        ["p", "C0 (ms)", "C1 (us)", "C2 (us)", "fitted t_l (us)", "fitted alpha (us)", "d_opt, Eq. 11", "best d run"],
        fits,
        "The paper's t(d) = C0 + C1/d + C2 d fitted to each p's runs by least squares (Eq. 12), the latency t_l and "
        "wait constant alpha they give (the paper's Table 1 way), and Eq. 11's d_opt from them against the best d "
        "run. A negative C1 or C2 means the runs show no such term.",
    )


def speedup(args):
    jobs = {
        (n, p): {"cluster.nodes": p, "cluster.triangles": n, "cluster.buffer_depth": "auto"}
        for n in SPEEDUP_TRIANGLES
        for p in SPEEDUP_NODES
    }
    results = run_all(args, jobs, lambda key: f"speedup_n{key[0]}_p{key[1]}")
    rows = []
    for n in SPEEDUP_TRIANGLES:
        one = results[(n, 1)]["seconds"]
        for p in SPEEDUP_NODES:
            r = results[(n, p)]
            rows.append(
                [
                    f"{n:,}",
                    p,
                    f"{r['seconds'] * 1e3:,.2f}",
                    f"{n / r['seconds']:,.0f}",
                    f"{one / r['seconds']:.2f}",
                    f"{one / r['seconds'] / p * 100:.1f}",
                    f"{r['energy_j'] * 1e3:,.2f}",
                ]
            )
    write(
        args,
        "speedup",
        ["n", "p", "time per frame (ms)", "rate (triangles/s)", "speed-up", "efficiency (%)", "energy per frame (mJ)"],
        rows,
        "Rate, speed-up and efficiency against one node, the same scene (n random 10-pixel triangles at 512 x 512), "
        f"cluster.buffer_depth=auto, host.model=native, mean of frames 1 .. {args.frames - 1}. Energy: the nodes' "
        "(the SoC's host, bus and memory energy model), without the network's estimate.",
    )
    plot(
        args,
        "speedup",
        {
            f"n = {n:,}": (
                SPEEDUP_NODES,
                [results[(n, 1)]["seconds"] / results[(n, p)]["seconds"] for p in SPEEDUP_NODES],
            )
            for n in SPEEDUP_TRIANGLES
        },
        "nodes p",
        "speed-up over one node",
    )
    n = SPEEDUP_TRIANGLES[-1]
    rows = []
    for p in SPEEDUP_NODES:
        r = results[(n, p)]
        total = sum(r["phases"].values())
        rows.append(
            [p]
            + [f"{r['phases'][phase] / CLOCK_HZ * 1e3:,.2f}" for phase in PHASES]
            + [f"{total / CLOCK_HZ * 1e3:,.2f}", f"{r['messages']:,.0f}"]
        )
    write(
        args,
        "components",
        ["p"] + [f"{phase} (ms)" for phase in PHASES] + ["node's frame (ms)", "messages / frame"],
        rows,
        f"Where a node's frame goes, mean over the nodes, n = {n:,} (the speed-up runs): the paper's components as "
        "the node program times them (sw_driver/cluster_node/README.md, 'Where the time goes'); messages are all "
        "nodes' per frame.",
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("experiment", choices=["depth", "speedup", "all"])
    parser.add_argument("--soc-sim", default=str(ROOT / "build" / "default" / "bin" / "soc_sim"))
    parser.add_argument("--out", default="out/experiments/cluster")
    parser.add_argument("--triangles", type=int, default=100000)
    parser.add_argument("--frames", type=int, default=3)
    parser.add_argument("--config", action="append", default=[])
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    if args.frames < 2:
        parser.error("--frames: at least 2 (frame 0 holds the start-up)")
    args.soc_sim = str(pathlib.Path(args.soc_sim).resolve())
    try:
        if args.experiment in ("depth", "all"):
            depth(args)
        if args.experiment in ("speedup", "all"):
            speedup(args)
    except RuntimeError as error:
        print(f"cluster_experiments: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
