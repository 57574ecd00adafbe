"""The plots and report.html of conftest's first_run (two of its four points
fail), and --report-only."""

import shutil
from html.parser import HTMLParser

from tessera_sweep.report import plot_name, series_axes, write_report
from tessera_sweep.spec import parse_spec

from conftest import AXES, METRICS, TINY, tessera_sweep_command, write_spec


class Report(HTMLParser):
    """What the tests look for: each figure's id and whether it holds an
    <svg>, the headings, and the failed points' table cells."""

    def __init__(self, text):
        super().__init__()
        self.figures, self.failed_cells, self.headings = {}, [], []
        self._figure = self._table = self._cell = None
        self._in_heading = False
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "figure":
            self._figure = attrs["id"]
            self.figures[self._figure] = False
        elif tag == "svg" and self._figure:
            self.figures[self._figure] = True
        elif tag == "table":
            self._table = attrs.get("class", "")
        elif tag == "td" and self._table == "failed":
            self._cell = ""
        elif tag == "h2":
            self._in_heading = True

    def handle_endtag(self, tag):
        if tag == "figure":
            self._figure = None
        elif tag == "table":
            self._table = None
        elif tag == "h2":
            self._in_heading = False
        elif tag == "td" and self._cell is not None:
            self.failed_cells.append(self._cell.strip())
            self._cell = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data
        if self._in_heading:
            self.headings.append(data)


def expected_plots():
    return [plot_name(metric, axis) for metric in METRICS for axis in AXES]


def test_a_png_and_an_svg_per_metric_and_axis(first_run):
    out, _, _ = first_run
    for name in expected_plots():
        assert (out / "plots" / f"{name}.png").read_bytes().startswith(b"\x89PNG"), name
        assert "<svg" in (out / "plots" / f"{name}.svg").read_text(), name
    assert len(list((out / "plots").iterdir())) == 2 * len(METRICS) * len(AXES)


def test_the_report_parses_and_embeds_every_plot(first_run):
    out, _, _ = first_run
    report = Report((out / "report.html").read_text())
    assert report.figures == {f"plot-{name}": True for name in expected_plots()}
    assert report.headings == ["Spec", "Results", "Plots", "Failed points"]


def test_the_report_lists_the_failed_points_with_status_and_error(first_run):
    out, _, _ = first_run
    text = (out / "report.html").read_text()
    cells = Report(text).failed_cells
    rows = [cells[i : i + 3] for i in range(0, len(cells), 3)]
    assert [row[:2] for row in rows] == [
        ["driver.backend=arm, sim.time_limit_ms=1", "1"],
        ["driver.backend=raster, sim.time_limit_ms=1", "1"],
    ]
    assert all("simulated-time limit reached" in row[2] for row in rows)
    assert "The 2 failed points are left out of the plots." in text


def test_series_are_split_by_the_other_axes_but_not_by_zip_partners(first_run):
    _, table, _ = first_run
    spec = parse_spec(
        dict(TINY, axes={"driver.backend": ["arm"]}, zip={"sim.time_limit_ms": [0], "display.refresh_hz": [60]})
    )
    table = table.assign(**{"display.refresh_hz": 60})
    assert series_axes(spec, "driver.backend", table) == ["sim.time_limit_ms", "display.refresh_hz"]
    assert series_axes(spec, "sim.time_limit_ms", table) == ["driver.backend"]


def test_a_zip_group_is_one_axis_with_a_bar_per_tuple_in_zip_order(first_run, tmp_path):
    _, table, _ = first_run
    spec = parse_spec(
        dict(
            TINY,
            axes={"sim.time_limit_ms": [0, 1]},
            metrics=METRICS[:1],
            zip={"driver.backend": ["raster", "arm"], "display.refresh_hz": [50, 60]},
        )
    )
    table = table.assign(**{"display.refresh_hz": table["driver.backend"].map({"arm": 60, "raster": 50})})
    write_report(spec, table, tmp_path)
    zip_plot = plot_name(METRICS[0], ("driver.backend", "display.refresh_hz"))
    assert zip_plot == f"{METRICS[0]}-by-driver.backend+display.refresh_hz"
    names = {plot_name(METRICS[0], "sim.time_limit_ms"), zip_plot}
    assert set(Report((tmp_path / "report.html").read_text()).figures) == {f"plot-{n}" for n in names}
    svg = (tmp_path / "plots" / f"{zip_plot}.svg").read_text()
    # the tuples as tick labels, in the zip's order (raster first), not the table's
    assert 0 <= svg.index("raster, 50") < svg.index("arm, 60")
    assert "by driver.backend, display.refresh_hz" in svg


def test_report_only_rebuilds_from_the_table_and_runs_nothing(first_run, simulator, tmp_path):
    out, _, _ = first_run
    copy = tmp_path / "copy"
    shutil.copytree(out, copy)
    (copy / "report.html").unlink()
    shutil.rmtree(copy / "points")  # a run would recreate them
    # one metric fewer: its plots go too
    spec_file = write_spec(tmp_path, dict(TINY, axes=AXES, metrics=METRICS[:1]))
    done = tessera_sweep_command(str(spec_file), "--report-only", "--out", str(copy), "--soc-sim", str(simulator.path))
    assert done.returncode == 0, done.stderr
    assert not (copy / "points").exists()
    names = [plot_name(METRICS[0], axis) for axis in AXES]
    assert set(Report((copy / "report.html").read_text()).figures) == {f"plot-{n}" for n in names}
    assert sorted(p.name for p in (copy / "plots").iterdir()) == sorted(
        f"{name}.{suffix}" for name in names for suffix in ("png", "svg")
    )


def test_a_sweep_where_every_point_failed_has_a_report_without_plots(first_run, spec, tmp_path):
    _, table, _ = first_run
    failed = table[table["status"] != 0].dropna(axis="columns", how="all")
    write_report(spec, failed, tmp_path)
    text = (tmp_path / "report.html").read_text()
    report = Report(text)
    assert report.figures == {}
    assert len(report.failed_cells) == 3 * len(failed)
    assert all(f"metric &#39;{metric}&#39;: no value" in text for metric in METRICS)


def test_report_only_without_a_table_exits_2(simulator, tmp_path):
    spec_file = write_spec(tmp_path, dict(TINY, axes=AXES, metrics=METRICS))
    done = tessera_sweep_command(
        str(spec_file), "--report-only", "--out", str(tmp_path / "none"), "--soc-sim", str(simulator.path)
    )
    assert done.returncode == 2
    assert "results.parquet" in done.stderr
