"""An experiment's table (the "columns" of its spec: a statistic, a
configuration value or a figure of figures.py per column, each run a row,
formatted in readable units) as Markdown and CSV, and its plot (matplotlib)."""

import csv
import math
import sys

from .figures import (
    COMPUTED,
    SAVING_PERCENT,
    RunError,
    baseline_result,
    config,
    frames_drawn,
    saving_percent,
    stat,
    stats_required,
)


class UsageError(Exception):
    """Bad input: the command line, an experiment file, a missing tool (status 2)."""


def cell_value(column, result, results):
    """The column's number for one run, or None where the column does not apply to its back end."""
    if "backends" in column and result.backend not in column["backends"]:
        return None
    if "stat" in column:
        value = stat(result, column["stat"], stats_required(column))
        per = column.get("per")
        if value is None:
            pass
        elif per == "frame":
            value = value / frames_drawn(result)
        elif per is not None:
            divisor = stat(result, per, stats_required(column))
            if divisor == 0:
                raise RunError(f"run '{result.label}': '{per}' is 0, so '{column['stat']}' per it is undefined")
            value = None if divisor is None else value / divisor
    elif "config" in column:
        value = config(result, column["config"])
    else:
        value = COMPUTED[column["value"]](result, column, results)
    if "scale" in column and isinstance(value, (int, float)) and not isinstance(value, bool):
        value = value * column["scale"]
    return value


def format_cell(column, value):
    if value is None:
        return "-"
    if isinstance(value, str):
        return value
    if "format" in column:
        return format(value, column["format"])
    if isinstance(value, bool):
        return str(value).lower()
    return format(value, ",") if isinstance(value, int) else format(value, ",.2f")


# The columns every table starts with, after the run's label: the host model and the array program it ran.
RUN_COLUMNS = [{"key": "host", "header": "host"}, {"key": "program", "header": "program"}]


def build_table(columns, results):
    """Rows of (label, [host, program, value per column]) in the runs' order. A saving_percent column comes from
    another column's values in the same table, so it is filled in once the run's own figures are."""
    rows = [
        [None if column.get("value") == SAVING_PERCENT else cell_value(column, result, results) for column in columns]
        for result in results
    ]
    position = {column["key"]: index for index, column in enumerate(columns)}
    for index, column in enumerate(columns):
        if column.get("value") != SAVING_PERCENT:
            continue
        of = position[column["of"]]
        for result, values in zip(results, rows):
            if "backends" in column and result.backend not in column["backends"]:
                continue
            baseline = rows[results.index(baseline_result(result, column, results))]
            values[index] = saving_percent(baseline[of], values[of], result, column)
    return [(result.label, [result.host, result.program] + values) for result, values in zip(results, rows)]


def markdown(label_header, columns, rows):
    columns = RUN_COLUMNS + columns
    headers = [label_header] + [column["header"] for column in columns]
    lines = [
        "| " + " | ".join(headers) + " |",
        "|" + "---|" + "".join(":--|" if column in RUN_COLUMNS else "--:|" for column in columns),
    ]
    for label, values in rows:
        cells = [format_cell(column, value) for column, value in zip(columns, values)]
        lines.append("| " + " | ".join([label] + cells) + " |")
    return "\n".join(lines) + "\n"


def csv_text(value):
    if value is None:
        return ""
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, float):
        return format(value, ".10g")
    return str(value)


def write_csv(columns, rows, path):
    with path.open("w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(["run"] + [column["key"] for column in RUN_COLUMNS + columns])
        for label, values in rows:
            writer.writerow([label] + [csv_text(value) for value in values])


# ---------------------------------------------------------------------------
# The plot.


def import_pyplot():
    try:
        import matplotlib
    except ImportError as error:
        raise UsageError(
            f"matplotlib is missing for {sys.executable}: install python3-matplotlib "
            "(scripts/setup.sh) or run the script with Debian's python3"
        ) from error
    matplotlib.use("Agg")  # files only, no display needed
    import matplotlib.pyplot as plt

    return plt


def plot_groups(spec, rows, index, groups, axes):
    """The column at `index` as bars grouped by the matrix's run and back end, one bar per switch combination, in
    the same colour in every group; a group without a combination has a gap there."""
    variants = list(dict.fromkeys(spec["run_groups"][label][1] for label, _ in rows))
    values = {spec["run_groups"][label]: row[index] for label, row in rows}
    width = 0.8 / len(variants)
    for number, variant in enumerate(variants):
        offset = (number - (len(variants) - 1) / 2) * width
        bars = [
            (position + offset, float(values[(group, variant)]))
            for position, group in enumerate(groups)
            if values.get((group, variant)) is not None
        ]
        axes.bar([x for x, _ in bars], [y for _, y in bars], width, label=variant or "none")
    axes.set_xticks(list(range(len(groups))))
    axes.set_xticklabels(groups, rotation=30, ha="right", fontsize=8)


def plot(spec, rows, path, plt):
    rows = [(label, values[len(RUN_COLUMNS) :]) for label, values in rows]
    settings = spec["plot"]
    columns = {column["key"]: (index, column) for index, column in enumerate(spec["columns"])}
    labels = [label for label, _ in rows]

    def series(key):
        index, _ = columns[key]
        return [values[index] for _, values in rows]

    keys = settings["columns"]
    if settings.get("groups"):
        groups = list(dict.fromkeys(spec["run_groups"][label][0] for label in labels))
        figure, axes = plt.subplots(figsize=(max(6.0, 1.2 * len(groups) + 2.5), 5.0))
        plot_groups(spec, rows, columns[keys[0]][0], groups, axes)
    elif "x" in settings:
        figure, axes = plt.subplots(figsize=(max(6.0, 1.6 * len(labels) + 2.5), 4.5))
        x = series(settings["x"])
        for key in keys:
            y = [math.nan if v is None else v for v in series(key)]
            axes.plot(x, y, marker="o", label=columns[key][1]["header"])
        axes.set_xlabel(columns[settings["x"]][1]["header"])
    else:
        figure, axes = plt.subplots(figsize=(max(6.0, 1.6 * len(labels) + 2.5), 4.5))
        positions = list(range(len(labels)))
        stacked = settings.get("stacked", False)
        width = 0.6 if stacked else 0.8 / len(keys)
        bottom = [0.0] * len(labels)
        for number, key in enumerate(keys):
            values = [0.0 if v is None else float(v) for v in series(key)]
            offset = 0.0 if stacked else (number - (len(keys) - 1) / 2) * width
            bars = axes.bar(
                [p + offset for p in positions],
                values,
                width,
                bottom=bottom if stacked else None,
                label=columns[key][1]["header"],
            )
            column = columns[key][1]
            axes.bar_label(
                bars,
                labels=[format_cell(column, v) if v else "" for v in values],
                fontsize=8,
                label_type="center" if stacked else "edge",
            )
            if stacked:
                bottom = [b + v for b, v in zip(bottom, values)]
        # Room above the tallest bar for its label and the legend.
        tallest = max(bottom) if stacked else max(max(0.0 if v is None else float(v) for v in series(k)) for k in keys)
        if tallest > 0 and not settings.get("log"):
            axes.set_ylim(0, tallest * 1.25)
        axes.set_xticks(positions)
        axes.set_xticklabels(labels)
        axes.set_xlabel(spec["label_header"])
    if settings.get("log"):
        axes.set_yscale("log")
    axes.set_ylabel(settings.get("ylabel", columns[keys[0]][1]["header"] if len(keys) == 1 else ""))
    axes.set_title(spec["title"], fontsize=10)
    axes.grid(True, axis="y", linewidth=0.3)
    if settings.get("groups"):
        axes.legend(fontsize=8, title="switches on", title_fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    elif len(keys) > 1:
        axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
