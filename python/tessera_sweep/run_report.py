"""One run of soc_sim on one page: `soc_sim --report FILE.html` runs this
after the run, and so can anyone on a run's statistics:

    python -m tessera_sweep.run_report STATS_JSON OUTPUT.html [--frames DIR]
    tessera-sweep run-report STATS_JSON OUTPUT.html [--frames DIR]

The page stands alone: the frames (up to MAX_THUMBNAILS of the PNGs in DIR,
by default the statistics' folder, embedded), frame time and energy per
frame as plots, where the simulated time went per block and per host phase
of the driver, the energy per unit, the command line and the configuration.
It is drawn with the sweep report's templates (templates/base.html.j2,
macros.html.j2) and its plots' style (inline SVG, text as text).

Needs jinja2 and matplotlib only (not the sweep's pandas or Dask), so that
soc_sim's run does not wait for them; a missing one is reported by name with
exit status MISSING_PACKAGE."""

from __future__ import annotations

import argparse
import base64
import io
import json
import sys
from dataclasses import dataclass
from pathlib import Path

# The generator the page names in its head: soc_sim recognises its own
# report by it before overwriting a file (tools/soc_sim/run_outputs.h).
GENERATOR = "tessera soc_sim --report"
MAX_THUMBNAILS = 12
MISSING_PACKAGE = 3
BAD_INPUT = 2
# The driver's host phases in each frame's record: host_<phase>_ns.
PHASE_PREFIX, PHASE_SUFFIX = "host_", "_ns"


@dataclass
class Plot:
    name: str
    caption: str
    svg: str


def _svg(figure) -> str:
    import matplotlib.pyplot as plt

    buffer = io.StringIO()
    figure.savefig(buffer, format="svg")
    plt.close(figure)
    text = buffer.getvalue()
    return text[text.index("<svg") :]


def _figure():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    matplotlib.rcParams["svg.fonttype"] = "none"  # as the sweep's plots: text as text
    return plt.subplots(figsize=(5.0, 3.0), layout="constrained")


def bar_plot(name: str, caption: str, labels: list[str], values: list[float], unit: str) -> Plot:
    figure, axes = _figure()
    axes.barh(labels[::-1], values[::-1])
    axes.set_xlabel(unit)
    axes.set_title(caption)
    return Plot(name, caption, _svg(figure))


def frame_plots(frames: list[dict]) -> list[Plot]:
    """Each frame's render time (from the previous frame's request to its
    own) and energy."""
    if not frames:
        return []
    index = [frame["index"] for frame in frames]
    plots = []
    figure, axes = _figure()
    axes.plot(index, [frame["render_ns"] / 1e6 for frame in frames], marker="o")
    axes.set_xlabel("frame")
    axes.xaxis.get_major_locator().set_params(integer=True)
    axes.set_ylabel("ms")
    axes.set_ylim(bottom=0)
    axes.set_title("frame time (render_ns)")
    plots.append(Plot("frame-time", "Frame time per frame, ms (frames[].render_ns)", _svg(figure)))
    if all("energy" in frame for frame in frames):
        figure, axes = _figure()
        axes.bar(index, [frame["energy"]["total_j"] * 1e3 for frame in frames])
        axes.set_xlabel("frame")
        axes.xaxis.get_major_locator().set_params(integer=True)
        axes.set_ylabel("mJ")
        axes.set_title("energy per frame (energy.total_j)")
        plots.append(Plot("frame-energy", "Energy per frame, mJ (frames[].energy.total_j)", _svg(figure)))
    return plots


def _ms(ns: float) -> str:
    return f"{ns / 1e6:.3f}"


def time_sections(stats: dict) -> list[dict]:
    """Busy time per block (every block's busy_ns) and the host's time per
    driver phase (host_<phase>_ns summed over the frames)."""
    sections = []
    simulated = stats.get("simulated_ns") or 0
    blocks = {name: block["busy_ns"] for name, block in stats.items() if isinstance(block, dict) and "busy_ns" in block}
    if blocks:
        names = sorted(blocks, key=blocks.get, reverse=True)
        share = [f"{100 * blocks[n] / simulated:.1f}" if simulated else "" for n in names]
        sections.append(
            {
                "name": "blocks",
                "title": "Busy time per block",
                "header": ["block", "busy (ms)", "share of the simulated time (%)"],
                "rows": [[n, _ms(blocks[n]), s] for n, s in zip(names, share)],
                "plot": bar_plot(
                    "block-busy", "Busy time per block, ms (busy_ns)", names, [blocks[n] / 1e6 for n in names], "ms"
                ),
            }
        )
    phases: dict[str, float] = {}
    for frame in stats.get("frames", []):
        for key, value in frame.get("driver", {}).items():
            if key.startswith(PHASE_PREFIX) and key.endswith(PHASE_SUFFIX):
                phase = key[len(PHASE_PREFIX) : -len(PHASE_SUFFIX)]
                phases[phase] = phases.get(phase, 0.0) + value
    if phases:
        names = sorted(phases, key=phases.get, reverse=True)
        total = sum(phases.values())
        sections.append(
            {
                "name": "host-phases",
                "title": "Host time per driver phase",
                "header": ["phase", "host time (ms)", "share (%)"],
                "rows": [[n, _ms(phases[n]), f"{100 * phases[n] / total:.1f}"] for n in names],
                "plot": bar_plot(
                    "host-phases",
                    "Host time per driver phase, ms (frames[].driver.host_*_ns)",
                    names,
                    [phases[n] / 1e6 for n in names],
                    "ms",
                ),
            }
        )
    return sections


def energy_section(stats: dict) -> dict | None:
    units = stats.get("energy", {}).get("units", {})
    if not units:
        return None
    names = sorted(units, key=lambda n: units[n]["total_j"], reverse=True)
    return {
        "header": ["unit", "total (mJ)", "static (mJ)", "dynamic (mJ)", "average (mW)"],
        "rows": [
            [
                n,
                f"{units[n]['total_j'] * 1e3:.4f}",
                f"{units[n]['static_j'] * 1e3:.4f}",
                f"{units[n]['dynamic_j'] * 1e3:.4f}",
                f"{units[n]['average_w'] * 1e3:.3f}",
            ]
            for n in names
        ],
        "plot": bar_plot(
            "energy-units",
            "Energy per unit, mJ (energy.units)",
            names,
            [units[n]["total_j"] * 1e3 for n in names],
            "mJ",
        ),
    }


def thumbnails(frames_dir: Path) -> list[dict]:
    """Up to MAX_THUMBNAILS of the frames' PNGs, evenly spaced, first and last included."""
    files = sorted(frames_dir.glob("frame_*.png"))
    if len(files) > MAX_THUMBNAILS:
        step = (len(files) - 1) / (MAX_THUMBNAILS - 1)
        files = [files[round(i * step)] for i in range(MAX_THUMBNAILS)]
    return [{"name": f.name, "base64": base64.b64encode(f.read_bytes()).decode("ascii")} for f in files]


def render(document: dict, frames_dir: Path) -> str:
    import jinja2

    stats = document.get("stats", {})
    run = {
        key: document.get(key, "")
        for key in ("application", "version", "commit", "run_status", "exit_status", "frames_shown", "frames_written")
    }
    run["simulated_ms"] = _ms(stats.get("simulated_ns", 0))
    run["command_line"] = " ".join(document.get("command_line", []))
    run["configuration"] = json.dumps(document.get("config", {}), indent=2)
    environment = jinja2.Environment(
        loader=jinja2.PackageLoader("tessera_sweep", "templates"), autoescape=jinja2.select_autoescape(["html", "j2"])
    )
    return environment.get_template("run_report.html.j2").render(
        generator=GENERATOR,
        run=run,
        thumbnails=thumbnails(frames_dir),
        frame_plots=frame_plots(stats.get("frames", [])),
        time_sections=time_sections(stats),
        energy=energy_section(stats),
    )


def write_run_report(stats_path: Path, output: Path, frames_dir: Path | None = None) -> Path:
    """Reads soc_sim's stats.json and writes the page to output, whole or not at all."""
    document = json.loads(stats_path.read_text())
    if not isinstance(document, dict) or "stats" not in document or "config" not in document:
        raise ValueError(f"{stats_path} is not soc_sim's statistics (no 'stats' and 'config')")
    html = render(document, frames_dir if frames_dir is not None else stats_path.parent)
    temporary = output.with_name(f".{output.name}.tmp")
    temporary.write_text(html)
    temporary.replace(output)
    return output


def main(argv: list[str] | None = None, prog: str = "python -m tessera_sweep.run_report") -> int:
    parser = argparse.ArgumentParser(
        prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("stats", type=Path, help="the run's stats.json")
    parser.add_argument("output", type=Path, help="the HTML page to write")
    parser.add_argument("--frames", type=Path, help="folder of the run's frame_NNNN.png (default: the stats' folder)")
    parser.add_argument("--quiet", action="store_true", help="print nothing but errors")
    options = parser.parse_args(argv)
    try:
        path = write_run_report(options.stats, options.output, options.frames)
    except ModuleNotFoundError as error:
        print(
            f"{prog}: the Python package '{error.name}' is missing (scripts/setup.sh installs it)",
            file=sys.stderr,
        )
        return MISSING_PACKAGE
    except (OSError, ValueError, KeyError, TypeError) as error:
        print(f"{prog}: {error}", file=sys.stderr)
        return BAD_INPUT
    if not options.quiet:
        print(f"run report: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
