#!/usr/bin/env python3
"""plot_timeline.py: a Gantt chart of a soc_sim --timeline file, one row per track.

The Perfetto UI draws these files interactively; this draws the same
slices as a picture (docs/images/timeline.png) where no browser can reach
it: one row per track (block and thread, as the file names them), each
slice a bar coloured by its name, and below them the power counter's total
and the bus utilisation. --from-ms and --to-ms cut a window of simulated
time.

  plot_timeline.py TIMELINE.json OUT.png [--from-ms A] [--to-ms B] [--title T]

Needs matplotlib (Debian's python3-matplotlib, scripts/setup.sh).
"""

import argparse
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    try:
        with open(path) as f:
            events = json.load(f)["traceEvents"]
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"plot_timeline: cannot read {path} as a trace-event file: {e}")
    processes = {e["pid"]: e["args"]["name"] for e in events if e["ph"] == "M" and e["name"] == "process_name"}
    threads = {(e["pid"], e["tid"]): e["args"]["name"] for e in events if e["ph"] == "M" and e["name"] == "thread_name"}
    names = {key: f"{processes[key[0]]} {name}" for key, name in threads.items()}
    return events, names


def plot(events, names, out, start_ms, end_ms, title):
    lo = start_ms * 1e3 if start_ms is not None else -float("inf")
    hi = end_ms * 1e3 if end_ms is not None else float("inf")
    rows = {}
    power, bus = [], []
    for e in events:
        if e["ph"] == "X" and e["ts"] < hi and e["ts"] + e["dur"] > lo:
            rows.setdefault((e["pid"], e["tid"]), []).append(e)
        elif e["ph"] == "C" and lo <= e["ts"] <= hi:
            if "total" in e["args"]:
                power.append((e["ts"] / 1e3, e["args"]["total"]))
            elif "busy" in e["args"]:
                bus.append((e["ts"] / 1e3, e["args"]["busy"]))
    tracks = [key for key in names if key in rows]
    if not tracks:
        sys.exit("plot_timeline: no slice in the window")
    colours = {}
    palette = plt.get_cmap("tab20").colors
    fig, (gantt, counters) = plt.subplots(
        2, 1, figsize=(11, 1.2 + 0.42 * len(tracks) + 1.6), sharex=True, height_ratios=[len(tracks), 3]
    )
    for row, key in enumerate(tracks):
        by_name = {}
        for e in rows[key]:
            by_name.setdefault(e["name"].split(" ")[0], []).append((e["ts"] / 1e3, max(e["dur"] / 1e3, 1e-4)))
        for name, bars in by_name.items():
            colour = colours.setdefault(name, palette[len(colours) % len(palette)])
            gantt.broken_barh(bars, (row - 0.4, 0.8), facecolors=colour, label=name)
    gantt.set_yticks(range(len(tracks)), [names[key] for key in tracks], fontsize=8)
    gantt.invert_yaxis()
    handles, labels = gantt.get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    gantt.legend(unique.values(), unique.keys(), fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    if title:
        gantt.set_title(title, fontsize=10)
    if power:
        x, y = zip(*power)
        counters.step(x, y, where="post", label="power, total (mW)")
    if bus:
        x, y = zip(*bus)
        counters.step(x, y, where="post", label="bus utilisation (%)")
    counters.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    counters.set_xlabel("simulated time (ms)")
    if start_ms is not None or end_ms is not None:
        counters.set_xlim(start_ms, end_ms)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("timeline", help="a soc_sim --timeline file")
    parser.add_argument("out", help="the PNG to write")
    parser.add_argument("--from-ms", type=float, help="start of the window, ms of simulated time")
    parser.add_argument("--to-ms", type=float, help="end of the window, ms of simulated time")
    parser.add_argument("--title", default="", help="the chart's title")
    args = parser.parse_args()
    events, names = read(args.timeline)
    plot(events, names, args.out, args.from_ms, args.to_ms, args.title)
    return 0


if __name__ == "__main__":
    sys.exit(main())
