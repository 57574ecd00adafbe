"""Runs on a local Dask cluster with the real soc_sim: the table, the cache
and a failing point (conftest's first_run: half its points fail on purpose)."""

import shutil

import pandas as pd

import tessera_sweep
from tessera_sweep.runner import run_sweep
from tessera_sweep.spec import parse_spec

from conftest import AXES, METRICS, TINY, tessera_sweep_command, write_spec


def test_every_point_runs_and_has_a_row(first_run, simulator):
    out, table, ran = first_run
    assert ran == 4
    assert list(table["driver.backend"]) == ["arm", "arm", "raster", "raster"]
    assert list(table["sim.time_limit_ms"]) == [0, 1, 0, 1]
    assert (table["sim_version"] == simulator.version).all()
    assert table["point"].is_unique
    assert (table["wall_s"] > 0).all()


def test_a_failing_point_is_recorded_and_the_others_succeed(first_run):
    _, table, _ = first_run
    failed = table[table["sim.time_limit_ms"] == 1]
    assert list(failed["status"]) == [1, 1]
    assert failed["error"].str.contains("simulated-time limit reached").all()
    succeeded = table[table["sim.time_limit_ms"] == 0]
    assert list(succeeded["status"]) == [0, 0]
    assert succeeded["error"].isna().all()
    assert (succeeded["frames_shown"] == 1).all()


def test_statistics_are_numeric_dotted_columns(first_run):
    _, table, _ = first_run
    assert (table.loc[table["status"] == 0, "stats.host.busy_cycles"] > 0).all()
    assert "stats.frames.0.energy.total_j" in table.columns  # list items by index
    assert table["config.display.width"].dropna().eq(192).all()
    stats = [c for c in table.columns if c.startswith("stats.")]
    assert stats and all(pd.api.types.is_numeric_dtype(table[c]) for c in stats)
    assert "application" not in table.columns  # strings are not statistics


def test_parquet_csv_and_load_agree(first_run):
    out, table, _ = first_run
    loaded = tessera_sweep.load(out)
    pd.testing.assert_frame_equal(loaded, table)
    csv = pd.read_csv(out / "results.csv")
    assert list(csv.columns) == list(table.columns) and len(csv) == len(table)


def test_a_rerun_runs_nothing(first_run, spec, simulator):
    out, table, _ = first_run
    again, ran = run_sweep(spec, simulator, out, workers=2)
    assert ran == 0
    pd.testing.assert_frame_equal(again, table)


def test_a_rerun_runs_only_the_missing_point(first_run, spec, simulator, tmp_path):
    out, table, _ = first_run
    copy = tmp_path / "copy"
    shutil.copytree(out, copy)
    shutil.rmtree(copy / "points" / table["point"][0])
    again, ran = run_sweep(spec, simulator, copy, workers=2)
    assert ran == 1
    assert again.loc[0, "status"] == 0


def test_retry_failed_runs_the_failed_points_again(first_run, spec, simulator, tmp_path):
    out, _, _ = first_run
    copy = tmp_path / "copy"
    shutil.copytree(out, copy)
    _, ran = run_sweep(spec, simulator, copy, workers=2, retry_failed=True)
    assert ran == 2


def test_points_with_the_same_configuration_share_one_run(simulator, tmp_path):
    # 60 and 60.0 are the same display.refresh_hz once soc_sim has read them
    spec = parse_spec(dict(TINY, axes={"display.refresh_hz": [60, 60.0]}))
    table, ran = run_sweep(spec, simulator, tmp_path, workers=1)
    assert ran == 1
    assert list(table["status"]) == [0, 0]
    assert table["point"].nunique() == 1


def test_command_reports_failed_points_with_exit_status_1(first_run, simulator, tmp_path):
    out, _, _ = first_run
    spec_file = write_spec(tmp_path, dict(TINY, axes=AXES, metrics=METRICS))
    done = tessera_sweep_command(str(spec_file), "--out", str(out), "--soc-sim", str(simulator.path))
    assert done.returncode == 1, done.stderr
    assert "4 points, 4 cached, 0 to run" in done.stderr
    assert "2 failed" in done.stdout


def test_command_refuses_a_bad_spec_naming_the_key(simulator, tmp_path):
    spec_file = write_spec(tmp_path, dict(TINY, axes={"array.columns": [24, 1000]}))
    done = tessera_sweep_command(str(spec_file), "--out", str(tmp_path / "out"), "--soc-sim", str(simulator.path))
    assert done.returncode == 2
    assert "'array.columns'" in done.stderr
    assert not (tmp_path / "out").exists()


def test_command_check_runs_nothing(simulator, tmp_path):
    spec_file = write_spec(tmp_path, dict(TINY, axes=AXES))
    done = tessera_sweep_command(str(spec_file), "--check", "--soc-sim", str(simulator.path))
    assert done.returncode == 0, done.stderr
    assert "4 points, all valid" in done.stdout


def test_command_host_and_set_reach_every_point_and_the_table(simulator, tmp_path):
    # One triangle frame on each of two resolutions of the ISS, with a CIU latency the spec does not set.
    spec_file = write_spec(tmp_path, dict(TINY, axes={"display.width": [192, 160]}))
    out = tmp_path / "out"
    done = tessera_sweep_command(
        str(spec_file),
        "--out",
        str(out),
        "--soc-sim",
        str(simulator.path),
        "--workers",
        "1",
        "--host",
        "iss",
        "--set",
        "ciu.read_cycles=41",
    )
    assert done.returncode == 0, done.stderr
    table = tessera_sweep.load(out)
    assert list(table["host_model"]) == ["iss", "iss"]
    assert list(table["config.ciu.read_cycles"]) == [41, 41]
    assert (table["stats.host.iss.instructions"] > 0).all()


def test_command_refuses_a_set_of_a_swept_key_or_without_a_value(simulator, tmp_path):
    spec_file = write_spec(tmp_path, dict(TINY, axes=AXES))
    swept = next(iter(AXES))
    done = tessera_sweep_command(str(spec_file), "--check", "--soc-sim", str(simulator.path), "--set", f"{swept}=1")
    assert done.returncode == 2 and f"{swept} is an axis of the sweep" in done.stderr
    done = tessera_sweep_command(str(spec_file), "--check", "--soc-sim", str(simulator.path), "--set", "ciu")
    assert done.returncode == 2 and "--set 'ciu': expected KEY=VALUE" in done.stderr
