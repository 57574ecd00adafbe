"""A sweep killed mid-way (the command, its cluster and its soc_sim runs, at
once) and run again runs only the points that had not finished."""

import os
import signal
import subprocess
import sys
import time

from tessera_sweep.table import load

from conftest import TINY, write_spec

# Eight points of one triangle frame, on one worker: one after the other.
AXES = {"driver.backend": ["arm", "raster"], "display.refresh_hz": [50, 60, 75, 90]}


def finished_points(out):
    return {path.parent.name: path.stat().st_mtime_ns for path in (out / "points").glob("*/result.json")}


def test_a_killed_sweep_resumes_with_only_the_unfinished_points(simulator, tmp_path):
    spec_file = write_spec(tmp_path, dict(TINY, axes=AXES))
    out = tmp_path / "out"
    command = [
        sys.executable,
        "-m",
        "tessera_sweep",
        str(spec_file),
        "--out",
        str(out),
        "--soc-sim",
        str(simulator.path),
        "--workers",
        "1",
    ]
    sweep = subprocess.Popen(
        command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True
    )  # its own process group: the cluster's too
    deadline = time.monotonic() + 120
    while not finished_points(out) and sweep.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    os.killpg(sweep.pid, signal.SIGKILL)
    sweep.wait()
    before = finished_points(out)
    assert 1 <= len(before) < 8, "the kill came after every point had finished: nothing to resume"
    assert not (out / "results.parquet").exists()

    again = subprocess.run(command, capture_output=True, text=True)
    assert again.returncode == 0, again.stderr
    assert f"8 points, {len(before)} cached, {8 - len(before)} to run" in again.stderr
    after = finished_points(out)
    assert len(after) == 8
    # what had finished was not run again: its record is the same file
    assert {key: after[key] for key in before} == before
    table = load(out)
    assert len(table) == 8 and (table["status"] == 0).all()
