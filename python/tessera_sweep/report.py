"""The sweep's plots and HTML report, from the results table.

For each metric of the spec and each axis: the metric against that axis (a
line plot for a numeric axis, grouped bars for a categorical one), one series
per combination of the other axes' values, as OUTPUT/plots/NAME.png and .svg.
A zip group of several keys is one axis of the plots: grouped bars, one per
tuple of values in the zip's order, since its keys move in step and none of
them alone orders the points.
Failed points are left out of the plots. OUTPUT/report.html stands alone: the
spec as given, the table, every plot as inline SVG and the failed points."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from .spec import Spec

PLOTS = "plots"
REPORT = "report.html"


@dataclass
class Plot:
    metric: str
    axis: str
    name: str  # file stem under plots/
    points: int
    svg: str  # the SVG's own markup, for inlining


def plot_name(metric: str, axis: str | tuple[str, ...]) -> str:
    """The file stem: METRIC-by-KEY, or METRIC-by-KEY1+KEY2 for a zip group."""
    keys = (axis,) if isinstance(axis, str) else axis
    return re.sub(r"[^A-Za-z0-9._+-]", "_", f"{metric}-by-{'+'.join(keys)}")


def plot_axes(spec: Spec) -> list[tuple[tuple[str, ...], dict]]:
    """What the plots are drawn against, with their values: each product
    axis, and each zip group as one (a group of one key is a plain axis)."""
    return [((key,), {key: values}) for key, values in spec.axes.items()] + [
        (tuple(group), group) for group in spec.zips
    ]


def is_numeric_axis(column: pd.Series) -> bool:
    return pd.api.types.is_numeric_dtype(column) and not pd.api.types.is_bool_dtype(column)


def series_axes(spec: Spec, axis: str, table: pd.DataFrame) -> list[str]:
    """The axes that split the series of a plot against axis: all others but
    axis's zip partners."""
    partners = next((set(group) for group in spec.zips if axis in group), {axis})
    return [key for key in spec.axis_keys if key not in partners and key in table.columns]


def _series(rows: pd.DataFrame, others: list[str]):
    if not others:
        yield "", rows
        return
    by = others if len(others) > 1 else others[0]  # pandas 1.5 and 2 agree on a scalar's keys
    for values, group in rows.groupby(by, sort=False, dropna=False):
        values = values if isinstance(values, tuple) else (values,)
        yield ", ".join(f"{key}={value}" for key, value in zip(others, values)), group


ZIP_COLUMN = "__zip__"  # a zip group's values as one label, for its plots


def zip_labels(rows: pd.DataFrame, group: dict) -> tuple[pd.Series, list[str]]:
    """Each row's values of a zip group's keys as one label ("24, 4"), and
    the labels in the zip's order."""
    order = list(zip(*group.values()))

    def position(values) -> int:
        return next((i for i, step in enumerate(order) if all(a == b for a, b in zip(step, values))), len(order))

    keys = list(group)
    labels = rows[keys].astype(str).agg(", ".join, axis=1)
    positions = [position(values) for values in rows[keys].itertuples(index=False)]
    ordered = list(dict.fromkeys(label for _, label in sorted(zip(positions, labels), key=lambda p: p[0])))
    return labels, ordered


def _draw(
    rows: pd.DataFrame,
    metric: str,
    axis: str,
    axis_label: str,
    others: list[str],
    numeric: bool,
    stem: Path,
    categories: list | None = None,
):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # Text as text, not glyph paths: smaller SVGs, and the report can be searched.
    with matplotlib.rc_context({"svg.fonttype": "none"}):
        figure, axes = plt.subplots(figsize=(6.4, 4.0), layout="constrained")
        series = list(_series(rows, others))
        if numeric:
            for label, group in series:
                group = group.sort_values(axis)
                axes.plot(group[axis], group[metric], marker="o", label=label or metric)
        else:
            categories = categories or list(dict.fromkeys(rows[axis]))
            width = 0.8 / len(series)
            for index, (label, group) in enumerate(series):
                heights = [group.loc[group[axis] == c, metric].mean() for c in categories]
                offsets = [i - 0.4 + width * (index + 0.5) for i in range(len(categories))]
                axes.bar(offsets, heights, width, label=label or metric)
            axes.set_xticks(range(len(categories)), [str(c) for c in categories])
        axes.set_xlabel(axis_label)
        axes.set_ylabel(metric)
        axes.set_title(f"{metric} by {axis_label}")
        if others:
            axes.legend(fontsize="small")
        figure.savefig(f"{stem}.png", dpi=100)  # not with_suffix: a dotted key is in the stem
        figure.savefig(f"{stem}.svg")
        plt.close(figure)


def make_plots(spec: Spec, table: pd.DataFrame, output: Path) -> tuple[list[Plot], list[str]]:
    """The plots, and a note for each metric or axis there is nothing to plot for."""
    folder = output / PLOTS
    folder.mkdir(parents=True, exist_ok=True)
    for old in folder.glob("*"):  # a metric or axis since dropped from the spec
        if old.suffix in (".png", ".svg"):
            old.unlink()
    ok = table[table["status"] == 0]
    plots, notes = [], []
    for metric in spec.metrics:
        if metric not in ok.columns or ok[metric].isna().all():
            notes.append(f"metric '{metric}': no value in the results table (not a column, or no point succeeded)")
            continue
        for keys, group in plot_axes(spec):
            missing = [key for key in keys if key not in table.columns]
            if missing:
                notes.extend(f"axis '{key}': not in the results table" for key in missing)
                continue
            rows = ok.dropna(subset=[metric])
            name, label = plot_name(metric, keys), ", ".join(keys)
            others = series_axes(spec, keys[0], table)
            if len(keys) == 1:
                _draw(rows, metric, keys[0], label, others, is_numeric_axis(table[keys[0]]), folder / name)
            else:
                labels, ordered = zip_labels(rows, group)
                _draw(
                    rows.assign(**{ZIP_COLUMN: labels}),
                    metric,
                    ZIP_COLUMN,
                    label,
                    others,
                    False,
                    folder / name,
                    ordered,
                )
            svg = (folder / f"{name}.svg").read_text()
            plots.append(Plot(metric, label, name, len(rows), svg[svg.index("<svg") :]))
    return plots, notes


def write_report(spec: Spec, table: pd.DataFrame, output: Path) -> Path:
    """Plots every metric against every axis and writes OUTPUT/report.html."""
    import jinja2

    plots, notes = make_plots(spec, table, output)
    metrics = [m for m in spec.metrics if m in table.columns]
    axes = [key for key in spec.axis_keys if key in table.columns]
    shown = table[axes + ["status"] + metrics]
    failed = table[table["status"] != 0]
    environment = jinja2.Environment(
        loader=jinja2.PackageLoader("tessera_sweep", "templates"), autoescape=jinja2.select_autoescape(["html", "j2"])
    )
    html = environment.get_template("report.html.j2").render(
        spec=spec,
        output=output,
        plots=plots,
        notes=notes,
        table=shown.to_html(index=False, na_rep="", classes="results", border=0),
        failed=[
            {
                "axes": {key: row[key] for key in axes},
                "status": int(row["status"]),
                "error": row["error"] if isinstance(row["error"], str) else "",
            }
            for _, row in failed.iterrows()
        ],
        points=len(table),
    )
    path = output / REPORT
    path.write_text(html)
    return path
