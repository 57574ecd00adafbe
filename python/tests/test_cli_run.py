"""tessera-sweep run and list: an experiment or a sweep spec, told apart by content, with --set and --frames,
and scripts/experiment.py, the alias, printing the same tables."""

import json
import subprocess
from pathlib import Path

import yaml

from tessera_sweep import cluster_experiments, experiment

from conftest import TINY, tessera_sweep_command, write_spec

ROOT = Path(__file__).resolve().parents[2]
SMALL = {
    "title": "t",
    "runs": [{"label": "a", "backend": "arm", "app": "triangle"}],
    "columns": [{"key": "ciu", "config": "ciu.read_cycles"}, {"key": "frame_ms", "value": "frame_time_ms"}],
}


def test_every_experiment_file_loads_and_equals_its_json(tmp_path):
    files = experiment.experiment_files()
    assert [path.stem for path in files] == sorted(path.stem for path in files) and len(files) >= 7
    for path in files:
        data = yaml.safe_load(path.read_text())
        as_json = tmp_path / f"{path.stem}.json"
        as_json.write_text(json.dumps(data))
        assert experiment.load_experiment(path) == experiment.load_experiment(as_json), path


def test_list_names_every_experiment():
    done = tessera_sweep_command("list")
    assert done.returncode == 0, done.stderr
    listed = [line.split()[0] for line in done.stdout.splitlines() if line.strip()]
    assert listed == [path.stem for path in experiment.experiment_files()] + list(cluster_experiments.TITLES)


def test_run_a_cluster_experiment_by_name(simulator, tmp_path):
    """tessera-sweep run cluster_soc: the cluster's experiment, with its own options, through the same command."""
    done = tessera_sweep_command(
        "run",
        "cluster_soc",
        "--triangles",
        "300",
        "--frames",
        "2",
        "--soc-sim",
        str(simulator.path),
        "--out",
        str(tmp_path),
    )
    assert done.returncode == 0, done.stderr
    assert "| SoC, arm |" in done.stdout and "| cluster, p = 128 |" in done.stdout
    assert (tmp_path / "cluster_soc.csv").is_file() and (tmp_path / "cluster_soc.md").is_file()


def test_run_an_experiment_file_with_set_and_frames(simulator, tmp_path):
    spec = tmp_path / "small.yaml"
    spec.write_text(yaml.safe_dump(SMALL))
    done = tessera_sweep_command(
        "run",
        str(spec),
        "--soc-sim",
        str(simulator.path),
        "--out",
        str(tmp_path / "out"),
        "--quiet",
        "--set",
        "ciu.read_cycles=41",
        "--frames",
        "2",
    )
    assert done.returncode == 0, done.stderr
    assert "| a | native | - | 41 |" in done.stdout
    stats = json.loads((tmp_path / "out" / "runs" / "a" / "stats.json").read_text())
    assert len(stats["stats"]["frames"]) == 2


def test_run_a_sweep_spec_with_set_and_frames(simulator, tmp_path):
    spec = write_spec(tmp_path, dict(TINY, axes={"driver.backend": ["arm", "raster"]}))
    done = tessera_sweep_command(
        "run", str(spec), "--check", "--soc-sim", str(simulator.path), "--frames", "2", "--set", "ciu.read_cycles=41"
    )
    assert done.returncode == 0 and "2 points, all valid" in done.stdout, done.stderr


def test_run_refuses_the_other_kinds_options(simulator, tmp_path):
    sweep = write_spec(tmp_path, dict(TINY, axes={"driver.backend": ["arm"]}))
    done = tessera_sweep_command("run", str(sweep), "--program", "study", "--soc-sim", str(simulator.path))
    assert done.returncode == 2 and "--program applies to an experiment" in done.stderr
    done = tessera_sweep_command("run", "teapot", "--workers", "2", "--soc-sim", str(simulator.path))
    assert done.returncode == 2 and "--workers applies to a sweep spec" in done.stderr
    done = tessera_sweep_command("run", "no_such_experiment", "--soc-sim", str(simulator.path))
    assert done.returncode == 2 and "unknown experiment 'no_such_experiment'" in done.stderr


def test_the_alias_prints_the_same_tables(simulator, tmp_path):
    common = ["host_traffic", "--frames", "1", "--quiet", "--soc-sim", str(simulator.path)]
    package = tessera_sweep_command("run", *common, "--out", str(tmp_path / "package"))
    alias = subprocess.run(
        [str(ROOT / "scripts" / "experiment.py"), *common, "--out", str(tmp_path / "alias")],
        capture_output=True,
        text=True,
        check=False,
    )
    assert package.returncode == 0 and alias.returncode == 0, package.stderr + alias.stderr
    tables = [done.stdout.split("\ntable ")[0] for done in (package, alias)]
    assert tables[0] == tables[1] and "| " in tables[0]
