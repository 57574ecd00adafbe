#!/usr/bin/env python3
"""The description of stats.json (docs/stats_schema.json): every number's
unit and one-line description, as the code gives them (soc_sim
--stats-schema, Block::describe_stats), for every back end.

Runs soc_sim once per case below (one frame each, a few seconds in all) with
--stats and --stats-schema, merges the runs' schemas (a key described
differently by two runs is an error) and checks that every number of every
run's stats.json (but its "config", which docs/configuration.md describes)
matches a key of the schema. A schema key is a dotted path; a part "*", or
a part with a "*" in it, matches any name there, and "[]" after a part
means every element of an array (tlm/common/stats_schema.h).

    scripts/stats_schema.py --soc-sim build/default/bin/soc_sim           check (the test)
    scripts/stats_schema.py --soc-sim build/default/bin/soc_sim --update  write docs/stats_schema.json

The check fails naming every undescribed number (and the run it was in),
and when docs/stats_schema.json differs from what the code gives.
docs/statistics.md's table is generated from docs/stats_schema.json by
scripts/update_docs.py (its block stats-schema). Standard library only.
"""

import argparse
import fnmatch
import json
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
SCHEMA = ROOT / "docs" / "stats_schema.json"

# Each back end, and the blocks a default run leaves out: the array's DMA,
# the display DMA, the z-buffer unit (the MorphoSys-like preset).
CASES = {
    "arm": ["--backend", "arm"],
    "raster": ["--backend", "raster"],
    "ap-tile": ["--backend", "ap-tile"],
    "ap-pixel": ["--backend", "ap-pixel"],
    "ap-object": ["--backend", "ap-object"],
    "ap-pixel-dma": ["--backend", "ap-pixel", "--set", "dma.enabled=true", "--set", "dma.broadcast=true"],
    "arm-display-dma": ["--backend", "arm", "--config", str(ROOT / "configs" / "dma_display.json")],
    "ap-object-morphosys": [
        "--backend",
        "ap-object",
        "--config",
        str(ROOT / "configs" / "presets" / "morphosys_like.json"),
    ],
}


def run_case(soc_sim, name, arguments, folder):
    out = folder / name
    command = [soc_sim, *arguments, "--frames", "1", "--no-frames", "--quiet", "--out", str(out)]
    command += ["--stats-schema", str(out / "schema.json")]
    env = dict(os.environ, SYSTEMC_DISABLE_COPYRIGHT_MESSAGE="1")
    try:
        result = subprocess.run(command, env=env, capture_output=True, text=True)
    except OSError as error:
        sys.exit(f"stats_schema: cannot run {soc_sim}: {error.strerror} (build soc_sim, or give --soc-sim)")
    if result.returncode != 0:
        sys.exit(f"stats_schema: {' '.join(command)} failed with status {result.returncode}:\n{result.stderr}")
    return json.loads((out / "stats.json").read_text()), json.loads((out / "schema.json").read_text())["statistics"]


def merge(schemas):
    """One schema of every run's; a key two runs describe differently is an error."""
    merged, where = {}, {}
    for name, schema in schemas.items():
        for key, entry in schema.items():
            if key in merged and merged[key] != entry:
                sys.exit(
                    f"stats_schema: {key} is described as {merged[key]} in run {where[key]} and as {entry} in {name}"
                )
            merged.setdefault(key, entry)
            where.setdefault(key, name)
    return dict(sorted(merged.items()))


def parts_of(key):
    """A schema key's parts: "frames[].render_ns" is frames, [], render_ns."""
    parts = []
    for part in key.split("."):
        elements = 0
        while part.endswith("[]"):
            part, elements = part[:-2], elements + 1
        parts += [part] + ["[]"] * elements
    return tuple(parts)


def numbers(value, path=()):
    """Every number of a JSON value with its path (a list element's part is "[]"; a key
    with dots, as the back ends' frame figures "cycles.fill", is its parts)."""
    if isinstance(value, dict):
        for key, item in value.items():
            yield from numbers(item, (*path, *key.split(".")))  # a dotted name is a path, as in to_json
    elif isinstance(value, list):
        for item in value:
            yield from numbers(item, (*path, "[]"))
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        yield path


def matches(pattern, path):
    return len(pattern) == len(path) and all(
        p == q if "[]" in (p, q) else fnmatch.fnmatchcase(q, p) for p, q in zip(pattern, path)
    )


def undescribed(stats, schema):
    """The paths of stats.json's numbers no key of `schema` describes, outside "config"."""
    patterns = [parts_of(key) for key in schema]
    missing = set()
    for path in numbers(stats):
        if path[0] != "config" and path not in missing and not any(matches(p, path) for p in patterns):
            missing.add(path)
    return sorted(".".join(path).replace(".[]", "[]") for path in missing)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--soc-sim", default=str(ROOT / "build" / "default" / "bin" / "soc_sim"))
    parser.add_argument("--update", action="store_true", help="write docs/stats_schema.json")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="tessera-stats-schema-") as folder:
        runs = {
            name: run_case(args.soc_sim, name, arguments, pathlib.Path(folder)) for name, arguments in CASES.items()
        }
    schema = merge({name: run[1] for name, run in runs.items()})
    text = json.dumps(schema, indent=2) + "\n"
    failures = []
    for name, (stats, _) in runs.items():
        failures += [f"{name}: {path} has no unit and description" for path in undescribed(stats, schema)]
    if args.update:
        SCHEMA.write_text(text)
        print(f"stats_schema: wrote {SCHEMA.relative_to(ROOT)} ({len(schema)} keys)")
    elif not SCHEMA.exists() or SCHEMA.read_text() != text:
        failures.append(
            f"{SCHEMA.relative_to(ROOT)} is not what the code describes: run scripts/stats_schema.py --update, "
            "then scripts/update_docs.py --only stats-schema"
        )
    for failure in failures:
        print(f"stats_schema: {failure}", file=sys.stderr)
    if not failures:
        print(f"stats_schema: every number of {len(runs)} runs described by {len(schema)} keys")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
