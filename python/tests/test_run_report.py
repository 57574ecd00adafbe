"""tessera_sweep.run_report, soc_sim --report's page, on a hand-made
statistics document: its sections come from the numbers given, a missing
package is named, and bad input is refused. (soc_sim --report itself, in a
browser: tests/tools/soc_sim/check_run_report_chromium.py.)"""

import json
import sys

from tessera_sweep import run_report
from tessera_sweep.run_report import GENERATOR, MISSING_PACKAGE, main

# Stands for a frame: the page embeds the bytes and never decodes them.
PIXEL_PNG = bytes.fromhex(
    "89504e470d0a1a0a0000000d4948445200000001000000010806000000"
    "1f15c4890000000d4944415478da63f8cfc0f01f0005000201a5f0a2d10000000049454e44ae426082"
)


def document(frames: int = 2) -> dict:
    unit = {"total_j": 0.002, "static_j": 0.0005, "dynamic_j": 0.0015, "average_w": 0.004}
    return {
        "application": "triangle",
        "command_line": ["soc_sim", "--frames", str(frames)],
        "config": {"sim": {"frames": frames}},
        "exit_status": 0,
        "run_status": "completed",
        "frames_shown": frames,
        "frames_written": frames,
        "stats": {
            "simulated_ns": 4e6,
            "host": {"busy_ns": 3e6},
            "raster": {"busy_ns": 1e6},
            "energy": {"units": {"host": unit, "raster": dict(unit, total_j=0.001)}},
            "frames": [
                {
                    "index": i,
                    "render_ns": 2e6,
                    "energy": {"total_j": 0.0015},
                    "driver": {"host_geometry_ns": 1e6, "host_clear_ns": 0.5e6, "units_x": 3.0},
                }
                for i in range(frames)
            ],
        },
    }


def write_run(folder, frames: int = 2):
    (folder / "stats.json").write_text(json.dumps(document(frames)))
    for i in range(frames):
        (folder / f"frame_{i:04d}.png").write_bytes(PIXEL_PNG)
    return folder / "stats.json"


def test_the_page_holds_the_runs_frames_tables_and_plots(tmp_path):
    stats = write_run(tmp_path)
    assert main([str(stats), str(tmp_path / "run.html"), "--quiet"]) == 0
    page = (tmp_path / "run.html").read_text()
    assert f'<meta name="generator" content="{GENERATOR}">' in page
    assert page.count("data:image/png;base64,") == 2
    for table in ('id="blocks"', 'id="host-phases"', 'id="energy-units"'):
        assert table in page
    # The driver's phases summed over the two frames: geometry 2 ms of 3 ms.
    assert "<td>geometry</td><td>2.000</td><td>66.7</td>" in page
    # host 3 ms of the 4 ms simulated.
    assert "<td>host</td><td>3.000</td><td>75.0</td>" in page
    assert page.count("<svg") == 5
    assert "soc_sim --frames 2" in page
    assert not list(tmp_path.glob(".*.tmp"))


def test_many_frames_give_evenly_spaced_thumbnails_first_and_last(tmp_path):
    write_run(tmp_path, frames=30)
    names = [t["name"] for t in run_report.thumbnails(tmp_path)]
    assert len(names) == run_report.MAX_THUMBNAILS
    assert names[0] == "frame_0000.png" and names[-1] == "frame_0029.png"


def test_a_missing_package_is_named(tmp_path, monkeypatch, capsys):
    stats = write_run(tmp_path)
    monkeypatch.setitem(sys.modules, "jinja2", None)  # import jinja2 now fails
    assert main([str(stats), str(tmp_path / "run.html")]) == MISSING_PACKAGE
    assert "the Python package 'jinja2' is missing" in capsys.readouterr().err
    assert not (tmp_path / "run.html").exists()


def test_what_is_not_socsims_statistics_is_refused(tmp_path, capsys):
    (tmp_path / "other.json").write_text('{"results": []}')
    assert main([str(tmp_path / "other.json"), str(tmp_path / "run.html")]) == 2
    assert "is not soc_sim's statistics" in capsys.readouterr().err
    assert main([str(tmp_path / "missing.json"), str(tmp_path / "run.html")]) == 2
