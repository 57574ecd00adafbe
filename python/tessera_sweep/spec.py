"""A sweep spec (YAML or JSON), its expansion into points and their check.

    app: triangle            # shorthands for sim.app, driver.backend, sim.frames
    backend: arm
    frames: 1
    args: []                 # after -- on soc_sim's command line
    config: {display.width: 192, display.height: 144}   # base --set values
    axes:                    # product of these ...
      driver.backend: [arm, raster]
    zip:                     # ... and of each zip group, whose lists go in step
      display.width: [192, 320]
      display.height: [144, 240]
    metrics: [stats.host.busy_cycles]   # results-table columns to plot, against each axis
    output: out/sweeps/NAME

Every key is a soc_sim configuration key (soc_sim --print-config), dotted.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from .simulator import Simulator, SimulatorError, flatten

ALIASES = {"app": "sim.app", "backend": "driver.backend", "frames": "sim.frames"}
# The values a YAML spec may hold with its aliases (*name) expanded, each
# reference counting as a copy. A real spec holds tens; the bound refuses a
# few hundred bytes of nested aliases that expand to billions of values
# (which took gigabytes and ended in a MemoryError) before anything is built.
MAX_SPEC_VALUES = 100_000
FIELDS = {"app", "backend", "frames", "args", "config", "axes", "zip", "metrics", "output", "write_frames"}


class SpecError(ValueError):
    pass


@dataclass(frozen=True)
class Point:
    axes: dict
    settings: dict
    args: tuple = ()


@dataclass
class Spec:
    base: dict
    axes: dict
    zips: list
    args: list = field(default_factory=list)
    metrics: list = field(default_factory=list)
    output: Path | None = None
    write_frames: bool = False
    source: str = field(default="", compare=False)  # the spec as given, for the report

    @property
    def axis_keys(self) -> list[str]:
        return list(self.axes) + [key for group in self.zips for key in group]


def _keys(mapping, where: str) -> dict:
    if mapping is None:
        return {}
    if not isinstance(mapping, dict):
        raise SpecError(f"'{where}' must be a mapping of configuration keys")
    return {ALIASES.get(key, key): value for key, value in flatten(mapping).items()}


def _axis(key: str, values, where: str) -> list:
    if not isinstance(values, list) or not values:
        raise SpecError(f"axis '{key}' (in {where}) needs a non-empty list of values")
    return values


def parse_spec(data: dict) -> Spec:
    if not isinstance(data, dict):
        raise SpecError("a sweep spec is a mapping")
    unknown = sorted(str(name) for name in set(data) - FIELDS)
    if unknown:
        raise SpecError(f"unknown spec field '{unknown[0]}' (known: {', '.join(sorted(FIELDS))})")
    base = {ALIASES[name]: data[name] for name in ("app", "backend", "frames") if name in data}
    base.update(_keys(data.get("config"), "config"))
    axes = {key: _axis(key, values, "axes") for key, values in _keys(data.get("axes"), "axes").items()}
    zip_groups = data.get("zip") or []
    if isinstance(zip_groups, dict):
        zip_groups = [zip_groups]
    zips = []
    for group in zip_groups:
        group = {key: _axis(key, values, "zip") for key, values in _keys(group, "zip").items()}
        if not group:  # it would make the product empty: a sweep of no points
            raise SpecError("a zip group needs at least one axis")
        lengths = {key: len(values) for key, values in group.items()}
        if len(set(lengths.values())) > 1:
            raise SpecError(f"zip axes differ in length: {lengths}")
        zips.append(group)
    seen = set()
    for key in list(axes) + [key for group in zips for key in group]:
        if key in seen:
            raise SpecError(f"axis '{key}' given twice")
        seen.add(key)
    args = data.get("args") or []
    if not isinstance(args, list):
        raise SpecError("'args' must be a list")
    metrics = data.get("metrics") or []
    if not isinstance(metrics, list) or not all(isinstance(m, str) for m in metrics):
        raise SpecError("'metrics' must be a list of results-table columns")
    output = data.get("output")
    if output is not None and not isinstance(output, str):
        raise SpecError("'output' must be a folder's path")
    return Spec(
        base=base,
        axes=axes,
        zips=zips,
        args=[str(a) for a in args],
        metrics=list(metrics),
        output=Path(output) if output else None,
        write_frames=bool(data.get("write_frames", False)),
        source=yaml.safe_dump(data, sort_keys=False),
    )


def _children(node: yaml.Node) -> list:
    if isinstance(node, yaml.MappingNode):
        return [part for pair in node.value for part in pair]
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    return []


def _check_expanded_size(root: yaml.Node, where: Path) -> None:
    """SpecError if the YAML document, its aliases expanded, holds more than
    MAX_SPEC_VALUES values or refers to itself. Counts on the composed
    graph, where an alias is the anchored node itself: each node once,
    without building anything."""
    sizes: dict[int, int] = {}
    open_nodes: set[int] = set()  # the nodes whose children are being counted
    stack = [(root, False)]
    while stack:
        node, counted = stack.pop()
        key = id(node)
        if counted:
            open_nodes.discard(key)
            sizes[key] = 1 + sum(sizes[id(child)] for child in _children(node))
            if sizes[key] > MAX_SPEC_VALUES:
                line = node.start_mark.line + 1
                raise SpecError(
                    f"{where}: line {line}: the spec holds more than {MAX_SPEC_VALUES:,} values with "
                    "its aliases (*name) expanded: a spec that repeats aliases of aliases grows "
                    "exponentially; write the values out, or use fewer levels of aliases"
                )
            continue
        if key in sizes:
            continue
        if key in open_nodes:
            line = node.start_mark.line + 1
            raise SpecError(f"{where}: line {line}: an alias refers to a value that contains it")
        open_nodes.add(key)
        stack.append((node, True))
        stack.extend((child, False) for child in _children(node) if id(child) not in sizes)


def load_yaml(text: str, where: Path):
    """yaml.safe_load with the size of the document checked first."""
    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        _check_expanded_size(node, where)
        return loader.construct_document(node)
    finally:
        loader.dispose()


def load_spec(path: str | Path) -> Spec:
    path = Path(path)
    text = path.read_text()
    try:
        data = json.loads(text) if path.suffix == ".json" else load_yaml(text, path)
    except (json.JSONDecodeError, yaml.YAMLError) as error:
        raise SpecError(f"{path}: {error}") from None
    spec = parse_spec(data)
    spec.source = text
    return spec


def expand(spec: Spec) -> list[Point]:
    """The product of the axes and zip groups, the last axis varying fastest."""
    groups = [[{key: value} for value in values] for key, values in spec.axes.items()]
    for group in spec.zips:
        groups.append([dict(zip(group, values)) for values in zip(*group.values())])
    points = []
    for combination in itertools.product(*groups):
        axes = {}
        for part in combination:
            axes.update(part)
        points.append(Point(axes=axes, settings={**spec.base, **axes}, args=tuple(spec.args)))
    return points


def check(points: list[Point], simulator: Simulator) -> list[dict]:
    """Each point's effective configuration; SpecError naming the key at the
    first unknown key, unknown application or value soc_sim refuses."""
    known = set(flatten(simulator.default_config))
    for point in points:
        for key in point.settings:
            if key not in known:
                raise SpecError(f"unknown configuration key '{key}' (soc_sim --print-config lists them)")
    for point in points:
        app = point.settings.get("sim.app")
        if app is not None and app not in simulator.apps and not Path(str(app)).is_file():
            raise SpecError(f"'sim.app': unknown application '{app}' (soc_sim --list-apps)")

    def config(point: Point) -> dict | SimulatorError:
        try:
            return simulator.config(point.settings)
        except SimulatorError as error:
            return error

    # One soc_sim --print-config per point, as many at once as there are
    # cores (each is a process start, about 10 ms); the first refused point
    # in the spec's order is the one reported.
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        configs = list(pool.map(config, points))
    for point, result in zip(points, configs):
        if isinstance(result, SimulatorError):
            raise SpecError(f"point {point.axes}: {result}")
    return configs


def point_key(config: dict, point: Point, spec: Spec, version: str) -> str:
    """The cache key: everything that decides a run's statistics."""
    payload = {"config": config, "args": list(point.args), "write_frames": spec.write_frames, "simulator": version}
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()[:16]
