"""A sweep through a real, separately started Dask scheduler and worker
(two processes on localhost, as on a cluster) gives the local run's table."""

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from tessera_sweep.table import load

from conftest import AXES, TINY, tessera_sweep_command, write_spec

PACKAGE_ROOT = Path(__file__).resolve().parents[1]  # python/: what workers import

# Differ between any two runs of the same point: not results.
RUN_COLUMNS = ["wall_s"]


def start(module: str, *args: str, log: Path) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(PACKAGE_ROOT))
    with open(log, "w") as out:
        return subprocess.Popen(
            [sys.executable, "-m", module, *args], stdout=out, stderr=subprocess.STDOUT, env=env, start_new_session=True
        )


def wait_for(condition, what: str, processes, timeout_s: float = 60.0):
    deadline = time.monotonic() + timeout_s
    while not condition():
        for process in processes:
            if process.poll() is not None:
                pytest.fail(f"{what}: {process.args[2]} exited with status {process.returncode}")
        if time.monotonic() > deadline:
            pytest.fail(f"{what}: not after {timeout_s:.0f} s")
        time.sleep(0.2)


@pytest.fixture
def cluster(tmp_path):
    """A scheduler on a free localhost port and one single-threaded worker,
    each its own process; yields the scheduler's address."""
    scheduler_file = tmp_path / "scheduler.json"
    scheduler = start(
        "distributed.cli.dask_scheduler",
        "--host",
        "127.0.0.1",
        "--port",
        "0",
        "--no-dashboard",
        "--scheduler-file",
        str(scheduler_file),
        log=tmp_path / "scheduler.log",
    )
    processes = [scheduler]
    try:
        wait_for(scheduler_file.exists, "the scheduler's address file", processes)
        address = json.loads(scheduler_file.read_text())["address"]
        worker = start(
            "distributed.cli.dask_worker",
            address,
            "--nworkers",
            "1",
            "--nthreads",
            "1",
            "--no-dashboard",
            "--no-nanny",
            "--local-directory",
            str(tmp_path / "worker"),
            log=tmp_path / "worker.log",
        )
        processes.append(worker)
        from dask.distributed import Client

        with Client(address, timeout=30) as client:
            client.wait_for_workers(1, timeout=60)
        yield address
    finally:
        for process in reversed(processes):
            process.terminate()
        for process in reversed(processes):
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()


def test_a_sweep_through_a_separate_scheduler_equals_the_local_run(cluster, first_run, simulator, tmp_path):
    local_out, local, _ = first_run
    spec_file = write_spec(tmp_path, dict(TINY, axes=AXES))
    remote_out = tmp_path / "remote"
    done = tessera_sweep_command(
        str(spec_file), "--out", str(remote_out), "--soc-sim", str(simulator.path), "--scheduler", cluster
    )
    assert done.returncode == 1, done.stderr  # half of AXES's points fail on purpose
    assert "4 points, 0 cached, 4 to run" in done.stderr
    remote = load(remote_out)
    assert len(remote) == 4 and (remote["status"] == local["status"]).all()
    # Every point ran on the worker: its files are in the shared output folder.
    assert all((remote_out / "points" / key / "result.json").is_file() for key in remote["point"])
    pd.testing.assert_frame_equal(remote.drop(columns=RUN_COLUMNS), local.drop(columns=RUN_COLUMNS))
