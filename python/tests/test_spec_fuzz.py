"""The sweep spec fuzzed with Hypothesis (docs/fuzzing.md, "sweep_spec"):
any text as a spec file, and any shape of the spec's fields, is either a
spec or a SpecError naming what is wrong -- never another exception, a
traceback or unbounded memory -- and a spec that loads expands to the
product of its axes, every point carrying the base settings and its own
axis values.

The number of examples: HYPOTHESIS_EXAMPLES (default 300 per test, a few
seconds; the fuzz label's nightly-style run sets 100000)."""

import itertools
import math
import os
import tempfile

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.configuration import set_hypothesis_home_dir

# Hypothesis's caches go to a temporary folder, not python/.hypothesis.
set_hypothesis_home_dir(tempfile.mkdtemp(prefix="hypothesis_"))

from tessera_sweep.spec import ALIASES, FIELDS, SpecError, expand, load_spec, parse_spec  # noqa: E402 (after the cache folder is set)

EXAMPLES = int(os.environ.get("HYPOTHESIS_EXAMPLES", "300"))
FUZZ = settings(
    max_examples=EXAMPLES,
    deadline=None,
    derandomize=True,
    database=None,  # no .hypothesis in the tree
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)

scalars = st.one_of(
    st.none(), st.booleans(), st.integers(-(2**70), 2**70), st.floats(allow_nan=True), st.text(max_size=12)
)
keys = st.one_of(
    st.sampled_from(sorted(FIELDS) + ["display.width", "sim.frames", "a.b", ""]),
    st.text(max_size=8),
    st.integers(-3, 3),
    st.booleans(),
    st.none(),
)
values = st.recursive(
    scalars,
    lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(keys, inner, max_size=4)),
    max_leaves=20,
)


def check_spec(spec):
    points = expand(spec)
    sizes = [len(values) for values in spec.axes.values()] + [
        len(next(iter(group.values()))) for group in spec.zips if group
    ]
    assert len(points) == math.prod(sizes)
    for point in points:
        for key, value in spec.base.items():
            if key not in point.axes:
                assert point.settings[key] == value or (value != value)  # NaN is never equal
        for key in point.axes:
            assert key in spec.axis_keys


@FUZZ
@given(st.dictionaries(keys, values, max_size=8))
def test_any_shape_of_the_fields_is_a_spec_or_a_spec_error(data):
    try:
        spec = parse_spec(data)
    except SpecError as error:
        assert str(error)
        return
    check_spec(spec)


@FUZZ
@given(
    st.fixed_dictionaries(
        {},
        optional={
            "app": st.sampled_from(["triangle", "cubes"]),
            "frames": st.integers(1, 3),
            "config": st.dictionaries(
                st.sampled_from(["display.width", "display.height", "dma.enabled"]), st.integers(1, 512), max_size=3
            ),
            "axes": st.dictionaries(
                st.sampled_from(["driver.backend", "raster.width", "app", "frames"]),
                st.lists(st.integers(0, 9), min_size=1, max_size=4),
                max_size=3,
            ),
            "zip": st.lists(
                st.dictionaries(
                    st.sampled_from(["array.columns", "array.rows", "sim.frames"]),
                    st.lists(st.integers(0, 9), min_size=2, max_size=2),
                    max_size=2,
                ),
                max_size=2,
            ),
        },
    )
)
def test_well_formed_specs_expand_to_the_product_of_their_axes(data):
    try:
        spec = parse_spec(data)
    except SpecError as error:
        # The only mistakes these can make: an axis in two places, an empty zip group.
        assert "given twice" in str(error) or "zip group needs" in str(error), error
        return
    check_spec(spec)
    # The product written out here: the axes, then each zip group's rows in
    # step, the last varying fastest.
    parts = [[{ALIASES.get(key, key): value} for value in values] for key, values in data.get("axes", {}).items()]
    for group in data.get("zip", []):
        parts.append([dict(zip(group, row)) for row in zip(*group.values())])
    expected = [{k: v for part in combination for k, v in part.items()} for combination in itertools.product(*parts)]
    assert [point.axes for point in expand(spec)] == expected


@FUZZ
@given(st.text(max_size=400))
def test_any_text_is_a_spec_or_a_spec_error(tmp_path_factory, text):
    path = tmp_path_factory.mktemp("spec") / "spec.yaml"
    path.write_text(text)
    try:
        spec = load_spec(path)
    except SpecError as error:
        assert str(error)
        return
    check_spec(spec)


# YAML with anchors and aliases nested at random: loads within the bound
# (MAX_SPEC_VALUES) or is refused, never grows without bound.
@st.composite
def aliased_yaml(draw):
    levels = draw(st.integers(1, 9))
    width = draw(st.integers(1, 12))
    lines = ["app: triangle", "config:", f"  a0: &a0 [{', '.join(['1'] * width)}]"]
    for level in range(1, levels):
        refs = draw(st.lists(st.integers(0, level - 1), min_size=1, max_size=width))
        lines.append(f"  a{level}: &a{level} [" + ", ".join(f"*a{r}" for r in refs) + "]")
    lines += ["axes:", f"  display.width: *a{levels - 1}"]
    return "\n".join(lines) + "\n"


@FUZZ
@given(aliased_yaml())
def test_nested_aliases_load_within_the_bound_or_are_refused(tmp_path_factory, text):
    path = tmp_path_factory.mktemp("spec") / "spec.yaml"
    path.write_text(text)
    try:
        spec = load_spec(path)
    except SpecError as error:
        assert "values with its aliases" in str(error) or "unknown" in str(error) or "axis" in str(error), error
        return
    check_spec(spec)
