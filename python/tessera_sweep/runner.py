"""Runs a sweep's points on a Dask cluster, each point one soc_sim process
in its own folder, skipping those whose result is already there."""

from __future__ import annotations

import contextlib
import json
import logging
import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from . import table
from .report import write_report
from .simulator import Simulator
from .spec import Point, Spec, check, expand, point_key

RESULT = "result.json"


def run_point(soc_sim: str, point_dir: str, settings: dict, args: list, write_frames: bool, record: dict) -> dict:
    """One point, on a worker: its record, also left in point_dir/result.json
    (written last and atomically, so a half-run point is not cached)."""
    point_dir = Path(point_dir)
    point_dir.mkdir(parents=True, exist_ok=True)
    result = Simulator(soc_sim).run(settings, args, point_dir, write_frames)
    record = dict(record, status=result.status, error=result.error, wall_s=result.wall_s)
    partial = point_dir / (RESULT + ".part")
    partial.write_text(json.dumps(record, indent=2))
    partial.replace(point_dir / RESULT)
    return record


def cached_record(point_dir: Path, retry_failed: bool) -> dict | None:
    try:
        record = json.loads((point_dir / RESULT).read_text())
    except (OSError, json.JSONDecodeError):
        return None
    if record.get("status") != 0 and retry_failed:
        return None
    return record


@contextlib.contextmanager
def connect(scheduler: str | None, workers: int | None):
    """A client of the given scheduler, or of a local cluster of one
    single-threaded worker process per core, closed client first."""
    from dask.distributed import Client, LocalCluster

    if scheduler:
        with Client(scheduler) as client:
            yield client
        return
    with LocalCluster(
        n_workers=workers or os.cpu_count(),
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        silence_logs=logging.ERROR,
    ) as cluster:
        with Client(cluster) as client:
            yield client


def progress(done: int, total: int, record: dict, out=None) -> None:
    out = out or sys.stderr  # looked up at the call: redirect_stderr applies
    outcome = "ok" if record["status"] == 0 else f"FAILED (exit status {record['status']})"
    print(f"[{done}/{total}] {record['axes']} {outcome} {record['wall_s']:.2f} s", file=out, flush=True)


def run_sweep(
    spec: Spec,
    simulator: Simulator,
    output: Path,
    scheduler: str | None = None,
    workers: int | None = None,
    retry_failed: bool = False,
    phases: dict | None = None,
):
    """Checks every point, runs the missing ones and writes the table, the
    plots and the report; returns
    (table, number of soc_sim runs). Points with the same effective
    configuration share one run. If given, phases receives the wall seconds
    of the check, the cluster's start (as far as the check did not hide
    it), the runs (first submission to last result) and the whole call."""
    phases = {} if phases is None else phases
    start = time.perf_counter()
    with contextlib.ExitStack() as cluster:
        # The first run into an output folder has points to run: its cluster
        # starts on a thread while the points are checked (both mostly wait
        # for other processes). A re-run may find every point cached, so it
        # starts the cluster only once it knows something is left to run.
        early = None
        if not (output / "points").is_dir():
            with ThreadPoolExecutor(max_workers=1) as pool:
                early = pool.submit(cluster.enter_context, connect(scheduler, workers))
                try:
                    points = expand(spec)
                    configs = check(points, simulator)
                finally:
                    # wait for the start either way, so that the stack closes what it started
                    done_starting = early.exception()
                if done_starting is not None:
                    raise done_starting
        else:
            points = expand(spec)
            configs = check(points, simulator)
        phases["check_s"] = time.perf_counter() - start
        output.mkdir(parents=True, exist_ok=True)
        keys = [point_key(config, point, spec, simulator.version) for point, config in zip(points, configs)]
        records: dict[str, dict | None] = {}
        todo: dict[str, Point] = {}
        for key, point in zip(keys, points):
            if key not in records:
                records[key] = cached_record(output / "points" / key, retry_failed)
                if records[key] is None:
                    todo[key] = point
        cached = sum(records[key] is not None for key in keys)
        print(f"tessera-sweep: {len(points)} points, {cached} cached, {len(todo)} to run", file=sys.stderr)
        if todo:
            cluster_start = time.perf_counter()
            client = early.result() if early else cluster.enter_context(connect(scheduler, workers))
            runs_start = time.perf_counter()
            phases["cluster_start_s"] = runs_start - cluster_start
            run_points(client, todo, records, spec, simulator, output)
            phases["runs_s"] = time.perf_counter() - runs_start
    rows = [table.row(point.axes, records[key], output / "points" / key) for key, point in zip(keys, points)]
    results = table.write(rows, output)
    write_report(spec, results, output)
    phases["total_s"] = time.perf_counter() - start
    return results, len(todo)


def run_points(client, todo: dict, records: dict, spec: Spec, simulator: Simulator, output: Path) -> None:
    """Runs the points of todo on the client's cluster, each record into
    records as it arrives, with a progress line."""
    from dask.distributed import as_completed

    futures = {}
    for key, point in todo.items():
        base = {"point": key, "axes": point.axes, "sim_version": simulator.version}
        future = client.submit(
            run_point,
            str(simulator.path),
            str((output / "points" / key).resolve()),
            point.settings,
            list(point.args),
            spec.write_frames,
            base,
            key=f"point-{key}",
            pure=False,
        )
        futures[future] = base
    for done, future in enumerate(as_completed(futures), 1):
        base = futures[future]
        try:
            record = future.result()
        except Exception as error:  # the worker, not soc_sim, failed: not cached
            record = dict(base, status=-1, error=f"{type(error).__name__}: {error}", wall_s=float("nan"))
        records[base["point"]] = record
        progress(done, len(todo), record)
