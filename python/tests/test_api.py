"""tessera_sweep.run() and load() (the Python API) and the README's example of them."""

import re
from pathlib import Path

import pytest

import tessera_sweep

from conftest import TINY

README = Path(__file__).resolve().parents[1] / "tessera_sweep" / "README.md"

EXPERIMENT = {
    "title": "t",
    "set": {"display.width": 192, "display.height": 144},
    "runs": [
        {"label": "a", "backend": "arm", "app": "triangle"},
        {"label": "b", "backend": "raster", "app": "triangle"},
    ],
    "columns": [
        {"key": "frame_ms", "value": "frame_time_ms"},
        {"key": "speedup", "value": "speedup", "baseline": "a"},
        {"key": "ciu", "config": "ciu.read_cycles"},
        {"key": "saved", "value": "saving_percent", "of": "frame_ms", "baseline": "a"},
    ],
}


def test_readme_example_runs(simulator, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("TESSERA_SOC_SIM", str(simulator.path))
    blocks = re.findall(r"^```python\n(.*?)^```", README.read_text(), re.M | re.S)
    example = next(block for block in blocks if "tessera_sweep.run(" in block)
    exec(compile(example, str(README), "exec"), {})
    printed = capsys.readouterr().out
    assert "| arm | native | - |" in printed and "speed-up over arm" in printed
    assert (tmp_path / "out" / "api_example" / "experiment.csv").is_file()


def test_an_experiment_as_data_with_overrides(simulator, tmp_path):
    table = tessera_sweep.run(EXPERIMENT, {"ciu.read_cycles": 41}, out=tmp_path, soc_sim=simulator.path)
    assert list(table.columns) == ["run", "host", "program", "frame_ms", "speedup", "ciu", "saved"]
    assert list(table["run"]) == ["a", "b"] and list(table["ciu"]) == [41, 41]
    assert table["speedup"][0] == 1.0 and table["frame_ms"].gt(0).all()
    # The saving against the baseline: 0 for the baseline itself, and the speed-up's figure seen the other way.
    assert table["saved"][0] == 0.0
    assert table["saved"][1] == pytest.approx((1 - 1 / table["speedup"][1]) * 100)
    assert table.attrs["study"] is None and "| a | native | - |" in table.attrs["markdown"]
    again = tessera_sweep.load(tmp_path)
    assert list(again["run"]) == ["a", "b"]
    assert again["frame_ms"].tolist() == pytest.approx(table["frame_ms"].tolist(), rel=1e-9)


def test_an_experiment_from_its_file_by_name(simulator, tmp_path):
    table = tessera_sweep.run("host_traffic", frames=1, out=tmp_path, soc_sim=simulator.path)
    assert len(table) > 0 and (tmp_path / "host_traffic.md").is_file()


def test_run_refuses_what_hosts_choose_and_bad_specs(simulator, tmp_path):
    with pytest.raises(tessera_sweep.UsageError, match="choose the host model"):
        tessera_sweep.run(EXPERIMENT, {"host.model": "iss"}, out=tmp_path, soc_sim=simulator.path)
    with pytest.raises(tessera_sweep.UsageError, match="unknown experiment 'no_such'"):
        tessera_sweep.run("no_such", out=tmp_path, soc_sim=simulator.path)
    with pytest.raises(tessera_sweep.UsageError, match="'hosts' must be"):
        tessera_sweep.run(EXPERIMENT, hosts=["qemu"], out=tmp_path, soc_sim=simulator.path)


def test_a_sweep_as_data_with_overrides_and_load(simulator, tmp_path):
    spec = dict(TINY, axes={"driver.backend": ["arm", "raster"]})
    table = tessera_sweep.run(spec, {"ciu.read_cycles": 41}, out=tmp_path, soc_sim=simulator.path, workers=1)
    assert list(table["driver.backend"]) == ["arm", "raster"] and (table["status"] == 0).all()
    assert list(table["config.ciu.read_cycles"]) == [41, 41]
    assert tessera_sweep.load(tmp_path).equals(table)
    with pytest.raises(tessera_sweep.SpecError, match="axis"):
        tessera_sweep.run(spec, {"driver.backend": "arm"}, out=tmp_path, soc_sim=simulator.path)


def test_load_without_a_table(tmp_path):
    with pytest.raises(FileNotFoundError):
        tessera_sweep.load(tmp_path)


def test_a_saving_needs_an_earlier_column_and_a_baseline(tmp_path):
    for change, message in [
        ({"of": "nothing"}, "'of' must be the key of a column before it"),
        ({"baseline": "z"}, "'baseline' must be the label of a run"),
        ({"of": None}, "'of' goes with the value saving_percent"),
    ]:
        spec = {**EXPERIMENT, "columns": EXPERIMENT["columns"][:3] + [{**EXPERIMENT["columns"][3], **change}]}
        spec["columns"] = [{k: v for k, v in column.items() if v is not None} for column in spec["columns"]]
        with pytest.raises(tessera_sweep.UsageError, match=message):
            tessera_sweep.run(spec, out=tmp_path)
