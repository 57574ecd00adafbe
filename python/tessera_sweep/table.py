"""The results table: one row per point, written as Parquet and CSV."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

PARQUET = "results.parquet"
CSV = "results.csv"


def numeric_leaves(tree, prefix: str = "") -> dict:
    """Every number in stats.json under its dotted path (list items by index);
    booleans and strings are left out."""
    leaves = {}
    if isinstance(tree, dict):
        for key, value in tree.items():
            leaves.update(numeric_leaves(value, f"{prefix}{key}."))
    elif isinstance(tree, list):
        for index, value in enumerate(tree):
            leaves.update(numeric_leaves(value, f"{prefix}{index}."))
    elif isinstance(tree, (int, float)) and not isinstance(tree, bool):
        leaves[prefix[:-1]] = tree
    return leaves


def row(axes: dict, record: dict, point_dir: Path) -> dict:
    """A point's axes, run record and statistics. Axes keep their dotted
    configuration keys; statistics sit under stats.json's own top-level
    names (config., stats., ...), so the two cannot collide."""
    values = dict(axes)
    values.update(
        point=record["point"],
        sim_version=record["sim_version"],
        status=record["status"],
        error=record["error"],
        wall_s=record["wall_s"],
    )
    stats_file = point_dir / "stats.json"
    if record["status"] == 0 and stats_file.is_file():
        document = json.loads(stats_file.read_text())
        values.update(numeric_leaves(document))
        # Which host model made the point's figures (a string: numeric_leaves leaves it out).
        values["host_model"] = document.get("config", {}).get("host", {}).get("model")
    return values


def write(rows: list[dict], folder: Path) -> pd.DataFrame:
    frame = pd.DataFrame(rows)
    frame.to_parquet(folder / PARQUET, index=False)
    frame.to_csv(folder / CSV, index=False)
    return frame


def load(folder: str | Path) -> pd.DataFrame:
    """A sweep's results table, from the output folder tessera-sweep wrote."""
    return pd.read_parquet(Path(folder) / PARQUET)
