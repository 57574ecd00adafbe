"""Spec loading, expansion and the up-front check of every point."""

import json
from pathlib import Path

import pytest
import yaml

from tessera_sweep.spec import SpecError, check, expand, load_spec, parse_spec, point_key


def test_yaml_and_json_specs_are_the_same(tmp_path, tiny):
    tiny["axes"] = {"driver.backend": ["arm", "raster"]}
    (tmp_path / "a.yaml").write_text(yaml.safe_dump(tiny))
    (tmp_path / "a.json").write_text(json.dumps(tiny))
    assert load_spec(tmp_path / "a.yaml") == load_spec(tmp_path / "a.json")


def test_shorthands_and_nested_config_become_dotted_keys():
    spec = parse_spec({"app": "cubes", "backend": "raster", "frames": 2, "config": {"display": {"width": 192}}})
    assert spec.base == {"sim.app": "cubes", "driver.backend": "raster", "sim.frames": 2, "display.width": 192}


def test_product_of_axes_last_varies_fastest(tiny):
    tiny["axes"] = {"driver.backend": ["arm", "raster"], "app": ["triangle", "cubes", "teapot"]}
    points = expand(parse_spec(tiny))
    assert [tuple(p.axes.values()) for p in points] == [
        ("arm", "triangle"),
        ("arm", "cubes"),
        ("arm", "teapot"),
        ("raster", "triangle"),
        ("raster", "cubes"),
        ("raster", "teapot"),
    ]
    assert all(p.settings["display.width"] == 192 and p.settings["sim.frames"] == 1 for p in points)
    assert points[4].settings["sim.app"] == "cubes"


def test_zip_axes_go_in_step_and_multiply_the_rest(tiny):
    tiny["axes"] = {"driver.backend": ["arm", "ap-tile"]}
    tiny["zip"] = {"display.width": [192, 320], "display.height": [144, 240]}
    points = expand(parse_spec(tiny))
    assert [p.axes for p in points] == [
        {"driver.backend": "arm", "display.width": 192, "display.height": 144},
        {"driver.backend": "arm", "display.width": 320, "display.height": 240},
        {"driver.backend": "ap-tile", "display.width": 192, "display.height": 144},
        {"driver.backend": "ap-tile", "display.width": 320, "display.height": 240},
    ]


@pytest.mark.parametrize(
    "data, message",
    [
        ({"axis": {"a.b": [1]}}, "unknown spec field 'axis'"),
        ({"axes": {"array.columns": []}}, "axis 'array.columns'"),
        ({"axes": {"array.columns": 12}}, "axis 'array.columns'"),
        ({"zip": {"display.width": [192, 320], "display.height": [144]}}, "differ in length"),
        ({"axes": {"driver.backend": ["arm"]}, "zip": {"backend": ["raster"]}}, "'driver.backend' given twice"),
        # Found by test_spec_fuzz.py: an empty zip group made a sweep of no
        # points; a non-string output and a non-string field name were a TypeError.
        ({"app": "triangle", "zip": [{}]}, "zip group needs at least one axis"),
        ({"output": True}, "'output' must be a folder's path"),
        ({1: "x", "axis": {}}, "unknown spec field '1'"),
    ],
)
def test_malformed_specs_are_refused(data, message):
    with pytest.raises(SpecError, match=message):
        parse_spec(data)


@pytest.mark.parametrize(
    "axes, message",
    [
        ({"array.colums": [12]}, "unknown configuration key 'array.colums'"),
        ({"array.columns": [12, 99]}, "'array.columns' expects an integer"),
        ({"driver.backend": ["arm", "vulkan"]}, "'driver.backend' expects one of"),
        ({"app": ["triangle", "no_such_app"]}, "'sim.app': unknown application 'no_such_app'"),
    ],
)
def test_check_names_the_bad_key_before_anything_runs(simulator, tiny, axes, message):
    tiny["axes"] = axes
    with pytest.raises(SpecError, match=message):
        check(expand(parse_spec(tiny)), simulator)


def test_check_refuses_an_impossible_combination(simulator, tiny):
    # ap-tile draws the array's frame: the display's size must be its size
    tiny["config"] = {"display.width": 256, "display.height": 144}
    tiny["axes"] = {"driver.backend": ["arm", "ap-tile"]}
    with pytest.raises(SpecError, match="driver.backend=ap-tile"):
        check(expand(parse_spec(tiny)), simulator)


def test_cache_key_covers_configuration_and_simulator_version(simulator, tiny):
    tiny["axes"] = {"array.columns": [12, 24]}
    spec = parse_spec(tiny)
    points = expand(spec)
    configs = check(points, simulator)
    keys = {point_key(c, p, spec, "v1") for c, p in zip(configs, points)}
    assert len(keys) == 2
    assert point_key(configs[0], points[0], spec, "v1") != point_key(configs[0], points[0], spec, "v2")
    assert point_key(configs[0], points[0], spec, "v1") == point_key(configs[0], points[0], spec, "v1")


EXAMPLES = sorted((Path(__file__).resolve().parents[2] / "configs" / "sweeps").glob("*.yaml"))


@pytest.mark.parametrize("path", EXAMPLES, ids=[path.stem for path in EXAMPLES])
def test_example_sweeps_are_valid_and_name_metrics(path, simulator):
    spec = load_spec(path)
    assert spec.metrics and spec.output
    check(expand(spec), simulator)


def _nested_aliases(levels: int) -> str:
    """A spec of a few hundred bytes whose aliases of aliases ("billion
    laughs") expand to 10 ** (levels + 1) values."""
    lines = ["app: triangle", "frames: 1", "config:", "  a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    for level in range(1, levels + 1):
        lines.append(f"  a{level}: &a{level} [" + ", ".join([f"*a{level - 1}"] * 10) + "]")
    lines += ["axes:", f"  display.width: *a{levels}"]
    return "\n".join(lines) + "\n"


def test_nested_aliases_are_refused_before_anything_is_built(tmp_path):
    import tracemalloc

    path = tmp_path / "laughs.yaml"
    path.write_text(_nested_aliases(8))
    assert len(path.read_text()) < 700
    tracemalloc.start()
    try:
        with pytest.raises(SpecError, match=r"laughs.yaml: line \d+: .*more than 100,000 values.*aliases"):
            load_spec(path)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 20 * 2**20


def test_nested_aliases_are_refused_by_the_command_line(tmp_path, capsys):
    from tessera_sweep.cli import main

    path = tmp_path / "laughs.yaml"
    path.write_text(_nested_aliases(8))
    assert main([str(path), "--check", "--soc-sim", "/nonexistent/soc_sim"]) == 2
    error = capsys.readouterr().err
    assert "tessera-sweep:" in error and "aliases" in error and "Traceback" not in error


def test_an_alias_that_contains_itself_is_refused(tmp_path):
    path = tmp_path / "loop.yaml"
    path.write_text("app: triangle\naxes:\n  display.width: &w [192, *w]\n")
    with pytest.raises(SpecError, match="contains it"):
        load_spec(path)


def test_a_few_aliases_are_still_fine(tmp_path, tiny):
    # Aliases within the bound load as before: the same as the values written out.
    path = tmp_path / "ok.yaml"
    path.write_text(
        "app: triangle\nframes: 1\nconfig:\n  display.width: &w 192\n  raster.width: *w\n"
        "axes:\n  display.height: &h [144, 96]\n  raster.height: *h\n"
    )
    spec = load_spec(path)
    assert spec.base["display.width"] == spec.base["raster.width"] == 192
    assert spec.axes == {"display.height": [144, 96], "raster.height": [144, 96]}
