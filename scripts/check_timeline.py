#!/usr/bin/env python3
"""check_timeline.py: soc_sim --timeline writes valid trace-event JSON that agrees with stats.json.

Runs soc_sim a few times (two frames each, well under a second apiece):
the teapot on ap-tile with the DMA and the display DMA, at the default
detail (blocks) and at detail all, and the rasterizer back end at detail
all; and once
the first without --timeline. For each timeline it checks that:

- the file is Chrome trace-event JSON: {"traceEvents": [...]}, each event
  with a known phase, pid, tid and (but metadata) a time; every B has its
  E on its track; on each track the X slices follow each other or nest,
  never overlap in part; every flow start has its end;
- the tracks the documentation names exist (process and thread names);
- each block's slices add up to its figure in stats.json: the host's busy
  and stalled time, the array's busy time, each DMA channel's busy time,
  the CIU's access time, the rasterizer's busy time and tiles (each inside
  a run), the GL driver's phases (to the frames' host_<phase>_ns) and
  calls (the teapot's glClear and glDrawElements among them), the
  display's frames and refreshes; and the power counter's energy (each window's total mW
  times its length) to stats.json's total energy;
- the run with the timeline has the same frames and stats.json (but the
  command line) as the run without.

Exits 1 naming the first thing that is wrong.

  check_timeline.py --soc-sim build/default/bin/soc_sim [--work-dir DIR]
"""

import argparse
import json
import math
import pathlib
import shutil
import subprocess
import sys
import tempfile

TEAPOT = ["--backend", "ap-tile", "--set", "dma.enabled=true", "--set", "display.dma=true", "--frames", "2"]
RASTER = ["--backend", "raster", "--frames", "2"]
PHASES = set("XBEiICMsft")


class Failure(Exception):
    pass


def close(a, b, what):
    if not math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-3):
        raise Failure(f"{what}: the timeline says {a!r}, stats.json {b!r}")


def run(soc_sim, folder, args):
    command = [soc_sim, "--out", str(folder), "-q", *args]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise Failure(f"{' '.join(command)} failed ({result.returncode}): {result.stderr}")
    return json.loads((folder / "stats.json").read_text())


def tracks_of(events):
    """{(process, thread): (pid, tid)} from the metadata events."""
    processes, threads = {}, {}
    for e in events:
        if e["ph"] == "M" and e["name"] == "process_name":
            processes[e["pid"]] = e["args"]["name"]
        elif e["ph"] == "M" and e["name"] == "thread_name":
            threads[(e["pid"], e["tid"])] = e["args"]["name"]
    return {(processes[pid], name): (pid, tid) for (pid, tid), name in threads.items()}


def check_format(events):
    open_b = {}
    slices = {}
    flows = {}
    for e in events:
        if e.get("ph") not in PHASES or not isinstance(e.get("pid"), int) or not isinstance(e.get("tid"), int):
            raise Failure(f"not a trace event: {e}")
        key = (e["pid"], e["tid"])
        if e["ph"] != "M" and not isinstance(e.get("ts"), (int, float)):
            raise Failure(f"event without a time: {e}")
        if e["ph"] == "B":
            open_b.setdefault(key, []).append(e)
        elif e["ph"] == "E":
            if not open_b.get(key):
                raise Failure(f"E without its B: {e}")
            open_b[key].pop()
        elif e["ph"] == "X":
            if e["dur"] < 0:
                raise Failure(f"negative duration: {e}")
            # In picoseconds, as written: no rounding of sums.
            start = round(e["ts"] * 1e6)
            slices.setdefault(key, []).append((start, start + round(e["dur"] * 1e6), e["name"]))
        elif e["ph"] in "sf":
            flows.setdefault(e["id"], set()).add(e["ph"])
    for key, stack in open_b.items():
        if stack:
            raise Failure(f"B without its E on track {key}: {stack[0]}")
    for key, spans in slices.items():
        # Sorted by start, longest first: a slice must end before the next
        # starts or enclose it (a stack of the enclosing slices).
        spans.sort(key=lambda s: (s[0], -s[1]))
        stack = []
        for start, end, name in spans:
            while stack and stack[-1][1] <= start:
                stack.pop()
            if stack and end > stack[-1][1]:
                raise Failure(f"track {key}: '{name}' {start}-{end} overlaps '{stack[-1][2]}' {stack[-1][:2]}")
            stack.append((start, end, name))
    for flow_id, phases in flows.items():
        if phases != {"s", "f"}:
            raise Failure(f"flow {flow_id} has only {phases}")
    return len(flows)


def slices_on(events, track, name=None):
    pid, tid = track
    return [
        e
        for e in events
        if e["ph"] == "X" and e["pid"] == pid and e["tid"] == tid and (name is None or e["name"] == name)
    ]


def need(tracks, process, thread):
    if (process, thread) not in tracks:
        raise Failure(f"no track '{thread}' of '{process}' (tracks: {sorted(tracks)})")
    return tracks[(process, thread)]


def check_teapot(events, stats, detail):
    tracks = tracks_of(events)
    s = stats["stats"]
    host = need(tracks, "soc.host", "activity")
    if detail == "all":
        busy = sum(e["dur"] for e in slices_on(events, host, "busy")) * 1e3
        stalled = sum(e["dur"] for e in slices_on(events, host, "stalled")) * 1e3
    else:
        running = slices_on(events, host, "running")
        busy = sum(e["args"]["busy_ns"] for e in running)
        stalled = sum(e["args"]["stalled_ns"] for e in running)
        close(sum(e["dur"] for e in running) * 1e3, busy + stalled, "host running = busy + stalled")
    close(busy, s["host"]["busy_ns"], "host busy_ns")
    close(stalled, s["host"]["stalled_on_bus_ns"], "host stalled_on_bus_ns")
    waits = slices_on(events, host, "waiting for interrupt")
    close(sum(e["dur"] for e in waits) * 1e3, s["host"]["waiting_for_irq_ns"], "host waiting_for_irq_ns")
    programs = slices_on(events, need(tracks, "soc.array", "programs"))
    close(sum(e["dur"] for e in programs) * 1e3, s["array"]["busy_ns"], "array busy_ns")
    for c in range(s["dma"]["channels"]):
        chains = slices_on(events, need(tracks, "soc.dma", f"ch{c}"), "chain")
        close(sum(e["dur"] for e in chains) * 1e3, s["dma"][f"ch{c}"]["busy_ns"], f"dma ch{c} busy_ns")
        descriptors = [e for e in slices_on(events, tracks[("soc.dma", f"ch{c}")]) if e["name"] != "chain"]
        close(len(descriptors), s["dma"][f"ch{c}"]["descriptors"], f"dma ch{c} descriptors")
    ciu = slices_on(events, need(tracks, "soc.ciu", "accesses"))
    access_ns = sum(e["dur"] * 1e3 if detail == "all" else e["args"]["access_ns"] for e in ciu)
    close(access_ns, s["ciu"]["access_ns"], "ciu access_ns")
    accesses = len(ciu) if detail == "all" else sum(e["args"]["accesses"] for e in ciu)
    close(accesses, s["ciu"]["reads"] + s["ciu"]["writes"], "ciu accesses")
    frames = slices_on(events, need(tracks, "soc.display", "frames"))
    close(len(frames), s["display"]["frames_shown"], "display frames")
    vblanks = slices_on(events, need(tracks, "soc.display", "vblank"))
    if not s["display"]["refreshes"] <= len(vblanks) <= s["display"]["refreshes"] + 1:
        raise Failure(f"{len(vblanks)} vblanks for {s['display']['refreshes']} refreshes")
    if detail == "all" and not slices_on(events, need(tracks, "soc.array", "stages")):
        raise Failure("no array stage at detail all")
    check_counters(events, tracks, s)


def check_counters(events, tracks, s):
    power = need(tracks, "soc", "power")
    need(tracks, "soc", "bus")
    samples = sorted(
        (e["ts"], e["args"]["total"])
        for e in events
        if e["ph"] == "C" and e["pid"] == power[0] and e["name"] == "power (mW)"
    )
    ends = [t for t, _ in samples[1:]] + [s["simulated_ns"] / 1e3]
    millijoules = sum(mw * (end - start) * 1e-6 for (start, mw), end in zip(samples, ends))
    if not math.isclose(millijoules, s["energy"]["total_j"] * 1e3, rel_tol=1e-6):
        raise Failure(f"power counter: {millijoules} mJ, stats.json {s['energy']['total_j'] * 1e3} mJ")


def check_raster(events, stats):
    tracks = tracks_of(events)
    runs = slices_on(events, need(tracks, "soc.raster", "runs"))
    close(sum(e["dur"] for e in runs) * 1e3, stats["stats"]["raster"]["busy_ns"], "raster busy_ns")
    close(len(runs), stats["stats"]["raster"]["runs"], "raster runs")
    # Detail all: every tile the rasterizer drew, each inside a run.
    tiles = slices_on(events, need(tracks, "soc.raster", "tiles"))
    close(len(tiles), stats["stats"]["raster"]["tiles"], "raster tiles")
    for tile in tiles:
        if not any(r["ts"] <= tile["ts"] and tile["ts"] + tile["dur"] <= r["ts"] + r["dur"] + 1e-6 for r in runs):
            raise Failure(f"{tile['name']} at {tile['ts']} us is outside every run of the rasterizer")
    check_driver_phases(events, tracks, stats)
    # Detail all: the application's GL calls, each inside the host's run.
    calls = slices_on(events, need(tracks, "soc.host", "driver calls"))
    names = {e["name"] for e in calls}
    for wanted in ("glClear", "glDrawElements"):
        if wanted not in names:
            raise Failure(f"no {wanted} among the driver calls ({sorted(names)[:10]} ...)")
    if not all(e["name"].startswith("gl") for e in calls):
        raise Failure(f"a driver call that is not a GL entry point: {sorted(names)}")
    last = stats["stats"]["simulated_ns"] / 1e3
    if any(e["ts"] < 0 or e["ts"] + e["dur"] > last + 1e-6 for e in calls):
        raise Failure("a driver call outside the run")


def check_driver_phases(events, tracks, stats):
    """The driver's phases up to the last frame's hand-over (the end of its
    presenting) add up to the frames' host_<phase>_ns."""
    phases = slices_on(events, need(tracks, "soc.host", "driver phase"))
    handed_over = max(e["ts"] + e["dur"] for e in phases if e["name"] == "presenting")
    for phase in ("application", "geometry", "rasterization", "presenting"):
        timeline = sum(e["dur"] for e in phases if e["name"] == phase and e["ts"] + e["dur"] <= handed_over + 1e-6)
        frames = sum(f["driver"][f"host_{phase}_ns"] for f in stats["stats"]["frames"])
        if not math.isclose(timeline * 1e3, frames, rel_tol=1e-6, abs_tol=1.0):
            raise Failure(f"driver phase {phase}: the timeline says {timeline * 1e3} ns, the frames {frames} ns")


def without_command_line(stats):
    stats = dict(stats)
    stats.pop("command_line")
    return stats


def check(soc_sim, work):
    plain = run(soc_sim, work / "plain", TEAPOT)
    for detail in ("blocks", "all"):
        folder = work / detail
        stats = run(soc_sim, folder, [*TEAPOT, "--timeline", str(folder / "t.json"), "--timeline-detail", detail])
        events = json.loads((folder / "t.json").read_text())["traceEvents"]
        flows = check_format(events)
        if flows == 0:
            raise Failure(f"detail {detail}: no flow from a DMA descriptor to an array program")
        check_teapot(events, stats, detail)
        if without_command_line(stats) != without_command_line(plain):
            raise Failure(f"detail {detail}: stats.json differs from the run without --timeline")
        for frame in sorted((work / "plain").glob("frame_*.png")):
            if frame.read_bytes() != (folder / frame.name).read_bytes():
                raise Failure(f"detail {detail}: {frame.name} differs from the run without --timeline")
        print(f"detail {detail}: {len(events)} events, {flows} flows: agree with stats.json")
    folder = work / "raster"
    stats = run(soc_sim, folder, [*RASTER, "--timeline", str(folder / "t.json"), "--timeline-detail", "all"])
    events = json.loads((folder / "t.json").read_text())["traceEvents"]
    check_format(events)
    check_raster(events, stats)
    print(f"raster: {len(events)} events: agree with stats.json")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--soc-sim", required=True, help="the soc_sim binary")
    parser.add_argument("--work-dir", help="where the runs go (default: a temporary folder, removed)")
    args = parser.parse_args()
    work = pathlib.Path(args.work_dir) if args.work_dir else pathlib.Path(tempfile.mkdtemp(prefix="check_timeline"))
    try:
        check(args.soc_sim, work)
    except Failure as e:
        print(f"check_timeline: {e}", file=sys.stderr)
        return 1
    finally:
        if not args.work_dir:
            shutil.rmtree(work, ignore_errors=True)
    print("check_timeline: every check passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
