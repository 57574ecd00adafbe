"""The cluster platform's experiments (docs/experiments.md, "The sort-middle cluster"): Crockett and Orloff's
questions asked of p ARM922T nodes, one command each (tessera-sweep run NAME, or scripts/experiment.py NAME), each
printing its Markdown tables and writing them with a CSV (and a plot where matplotlib is present) to
OUT/cluster_<table>.

    cluster_depth    time per frame against the buffer depth d, p = 8 .. 64 (the paper's Fig. 7), the paper's model
                     t(d) = C0 + C1/d + C2 d fitted per p, the fitted latency and wait constants, Eq. 11's d_opt
                     against the best d
    cluster_speedup  rate, speed-up and efficiency over n = 6,250 .. 200,000 and p = 1 .. 128 where the nodes'
                     memory holds the scene (the paper's Table 3), and the frame's time split into the model's
                     components against p
    cluster_soc      the same scene on the SoC (one ARM922T: the arm back end, and ap-tile with the array) against
                     p cluster nodes, at the array's frame (192 x 144): time and energy per frame

Options: --triangles N (cluster_depth's scene, default 100,000, the paper's standard scene; cluster_soc's, default
10,000), --config FILE (e.g. configs/presets/ipsc860_like.json), --frames F (default 3; figures are the mean of
frames 1 .. F-1, frame 0 holds the start-up), --soc-sim, --out (default out/experiments/cluster), --jobs. Every run is
soc_sim on the host-compiled model (host.model=native), the random scene of 10-pixel triangles, seed 1, at 512 x 512
(--platform cluster), or for cluster_soc at the array's frame, 192 x 144, on the cluster and on the SoC (its
built-in scene random_triangles: the same triangles).
"""

import argparse
import csv
import json
import os
import pathlib
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

from . import sort_middle_model as model
from .experiment import DEFAULT_SOC_SIM, EXIT_FAILED

CLOCK_HZ = 192e6
SIZE = (512, 512)  # the paper's screen
# The SoC's comparison is at the array's frame (ap-tile draws 192 x 144: array.columns x array.rows tiles of
# 8 x 36), 10,000 triangles: about the density of the paper's 100,000 at 512 x 512.
SOC_SIZE = (192, 144)
SOC_TRIANGLES = 10000
DEPTHS = [1, 2, 4, 8, 16, 32, 64]
DEPTH_NODES = [8, 16, 32, 64]
SPEEDUP_TRIANGLES = [6250, 25000, 100000, 200000]
SPEEDUP_NODES = [1, 2, 4, 8, 16, 32, 64, 128]
SOC_BACKENDS = ["arm", "ap-tile"]
SOC_NODES = [1, 2, 4, 8, 16, 32, 64, 128]
PHASES = ["compute", "split", "send", "wait", "termination"]


class TooBig(Exception):
    """A run refused because the scene's share or the stripe does not fit a node's memory (cluster.node_memory_kib):
    the paper's "where memory allows"."""


def soc_sim(args, name, arguments):
    """Runs soc_sim with `arguments` into OUT/runs/NAME; its stats.json's "stats"."""
    folder = pathlib.Path(args.out) / "runs" / name
    command = [args.soc_sim, "--frames", str(args.frames), "--no-frames", "--quiet", "--force", "--out", str(folder)]
    for config in args.config:
        command += ["--config", config]
    command += arguments
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        message = result.stderr.strip()
        # soc_sim's two messages: the stripe (before the run) and the node's triangles (when a node starts).
        if "cluster.node_memory_kib" in message and ("is too small" in message or "do not fit" in message):
            raise TooBig(message)
        raise RuntimeError(f"{' '.join(command)}: exit {result.returncode}: {message}")
    return json.loads((folder / "stats.json").read_text())["stats"]


def run(args, name, settings, size=SIZE):
    """One cluster run (soc_sim --platform cluster, the settings on a screen of `size`); its frames' mean time (s) and
    energy (J) after frame 0, the nodes' mean phase cycles over those frames and their counts; None when the scene
    does not fit the nodes' memory."""
    arguments = ["--platform", "cluster", "--set", f"cluster.width={size[0]}", "--set", f"cluster.height={size[1]}"]
    for key, value in settings.items():
        arguments += ["--set", f"{key}={value}"]
    try:
        stats = soc_sim(args, name, arguments)
    except TooBig:
        return None
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
    network = sum(f["energy"]["units"]["network"]["total_j"] for f in frames) / len(frames)
    return {
        "seconds": seconds,
        "phases": phases,
        "busiest_cycles": busiest,
        "messages": messages,
        "trapezoids": trapezoids,
        "energy_j": energy,
        "network_j": network,
    }


def run_soc(args, name, backend, triangles):
    """One SoC run of the built-in scene random_triangles on `backend` at SOC_SIZE; its frames' mean time (s),
    energy (J) and the part of the time that shows the frame (the arm back end's copy to the display, ap-tile's
    frame out), after frame 0."""
    arguments = ["--backend", backend, "--app", "random_triangles"]
    arguments += ["--set", f"display.width={SOC_SIZE[0]}", "--set", f"display.height={SOC_SIZE[1]}"]
    arguments += ["--", "--triangles", str(triangles)]
    stats = soc_sim(args, name, arguments)
    frames = stats["frames"][1:]
    showing = "host_presenting_ns" if backend == "arm" else "host_frame_out_ns"
    return {
        "seconds": sum(f["render_ns"] for f in frames) / len(frames) * 1e-9,
        "showing_s": sum(f["driver"][showing] for f in frames) / len(frames) * 1e-9,
        "energy_j": sum(f["energy"]["total_j"] for f in frames) / len(frames),
        "network_j": 0.0,
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
    args.triangles = args.triangles or 100000
    jobs = {
        (p, d): {"cluster.nodes": p, "cluster.triangles": args.triangles, "cluster.buffer_depth": d}
        for p in DEPTH_NODES
        for d in DEPTHS
    }
    results = run_all(args, jobs, lambda key: f"depth_p{key[0]}_d{key[1]}")
    too_big = sorted({p for (p, d), r in results.items() if r is None})
    if too_big:
        raise RuntimeError(
            f"--triangles {args.triangles:,} does not fit the nodes' memory at p = {too_big[0]} "
            "(cluster.node_memory_kib): fewer triangles, or more memory through --config"
        )
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
    notes = []
    for n in SPEEDUP_TRIANGLES:
        ran = [p for p in SPEEDUP_NODES if results[(n, p)] is not None]
        if not ran:
            notes.append(f"n = {n:,} fits no node count's memory.")
            continue
        # The speed-up is over one node; where n does not fit one node's memory, over the fewest nodes that hold
        # it, counted as that many times one node (marked *).
        base = ran[0]
        one = results[(n, base)]["seconds"] * base
        mark = "" if base == 1 else "*"
        if base != 1:
            notes.append(
                f"n = {n:,} does not fit the memory of fewer than {base} nodes "
                f"(cluster.node_memory_kib): its speed-up* is {base} x the time on {base} nodes over the time on p."
            )
        for p in SPEEDUP_NODES:
            r = results[(n, p)]
            if r is None:
                rows.append([f"{n:,}", p, "does not fit", "", "", "", ""])
                continue
            rows.append(
                [
                    f"{n:,}",
                    p,
                    f"{r['seconds'] * 1e3:,.2f}",
                    f"{n / r['seconds']:,.0f}",
                    f"{one / r['seconds']:.2f}{mark}",
                    f"{one / r['seconds'] / p * 100:.1f}{mark}",
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
        "and the network's (the network's an estimate: docs/cluster.md). " + " ".join(notes),
    )
    plot(
        args,
        "speedup",
        {
            f"n = {n:,}": (
                [p for p in SPEEDUP_NODES if results[(n, p)] is not None],
                [
                    results[(n, 1)]["seconds"] / results[(n, p)]["seconds"]
                    for p in SPEEDUP_NODES
                    if results[(n, p)] is not None
                ],
            )
            for n in SPEEDUP_TRIANGLES
            if results[(n, 1)] is not None
        },
        "nodes p",
        "speed-up over one node",
    )
    n = 100000
    rows = []
    for p in SPEEDUP_NODES:
        r = results[(n, p)]
        if r is None:
            continue
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


def soc(args):
    """The same scene on the SoC's arm and ap-tile back ends and on p cluster nodes, at SOC_SIZE."""
    n = args.triangles or SOC_TRIANGLES
    with ThreadPoolExecutor(args.jobs) as pool:
        socs = {b: pool.submit(run_soc, args, f"soc_{b}_n{n}", b, n) for b in SOC_BACKENDS}
        nodes = {
            p: pool.submit(
                run,
                args,
                f"soc_cluster_n{n}_p{p}",
                {"cluster.nodes": p, "cluster.triangles": n, "cluster.buffer_depth": "auto"},
                SOC_SIZE,
            )
            for p in SOC_NODES
        }
        results = {f"SoC, {b}": future.result() for b, future in socs.items()}
        results.update({f"cluster, p = {p}": future.result() for p, future in nodes.items()})
    arm = results["SoC, arm"]
    rows = []
    for label, r in results.items():
        if r is None:
            rows.append([label, "does not fit", "", "", "", "", ""])
            continue
        rows.append(
            [
                label,
                f"{r['seconds'] * 1e3:,.2f}",
                f"{r['showing_s'] * 1e3:,.2f}" if "showing_s" in r else "-",
                f"{arm['seconds'] / r['seconds']:.2f}",
                f"{r['energy_j'] * 1e3:,.2f}",
                f"{r['network_j'] * 1e3:,.2f}" if label.startswith("cluster") else "-",
                f"{arm['energy_j'] / r['energy_j']:.2f}",
            ]
        )
    write(
        args,
        "soc",
        [
            "machine",
            "time per frame (ms)",
            "of it showing the frame (ms)",
            "speed-up over arm",
            "energy per frame (mJ)",
            "of it the network's (mJ)",
            "energy saving over arm (x)",
        ],
        rows,
        f"{n:,} random 10-pixel triangles at {SOC_SIZE[0]} x {SOC_SIZE[1]} (the array's frame; seed 1), "
        f"host.model=native, mean of frames "
        f"1 .. {args.frames - 1}: the SoC (one ARM922T; ap-tile with the 96-CU array) drawing the built-in scene "
        "random_triangles, against p ARM922T nodes (cluster.buffer_depth=auto) drawing the same triangles. The "
        "SoC's frame includes showing it (arm: the copy to the display port; ap-tile: its frame out), the cluster's "
        "leaves out the gathering of the stripes. Energy: the SoC's whole energy model; the nodes' and the "
        "network's (an estimate: docs/cluster.md).",
    )


EXPERIMENTS = {"cluster_depth": depth, "cluster_speedup": speedup, "cluster_soc": soc}
TITLES = {
    "cluster_depth": "The sort-middle cluster: time per frame against the buffer depth d, the paper's model fitted",
    "cluster_speedup": "The sort-middle cluster: rate, speed-up and efficiency over n and p, the frame's components",
    "cluster_soc": "The sort-middle cluster against the SoC's arm and ap-tile on the same scene: time and energy",
}


def main(argv=None, prog="tessera-sweep run"):
    """NAME [options]: one of EXPERIMENTS; the exit status."""
    parser = argparse.ArgumentParser(
        prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("experiment", choices=sorted(EXPERIMENTS))
    parser.add_argument(
        "--soc-sim",
        default=os.environ.get("TESSERA_SOC_SIM", str(DEFAULT_SOC_SIM)),
        help="soc_sim to run (default: $TESSERA_SOC_SIM, else build/default/bin/soc_sim)",
    )
    parser.add_argument("--out", default="out/experiments/cluster", help="output folder")
    parser.add_argument(
        "--triangles", type=int, help="the scene of cluster_depth (default 100,000) and cluster_soc (10,000)"
    )
    parser.add_argument("--frames", type=int, default=3, help="frames per run, at least 2")
    parser.add_argument("--config", action="append", default=[], help="a configuration file for every run")
    parser.add_argument("--jobs", type=int, default=2, help="runs at a time")
    args = parser.parse_args(argv)
    if args.frames < 2:
        parser.error("--frames: at least 2 (frame 0 holds the start-up)")
    if args.triangles is not None and args.triangles < 1:
        parser.error("--triangles: at least 1")
    if args.jobs < 1:
        parser.error("--jobs: at least 1")
    args.soc_sim = str(pathlib.Path(args.soc_sim).resolve())
    try:
        EXPERIMENTS[args.experiment](args)
    except (RuntimeError, TooBig, OSError) as error:
        print(f"{prog}: {error}", file=sys.stderr)
        return EXIT_FAILED
    return 0
