"""tessera-sweep SPEC: checks every point of a sweep spec, runs those not yet
run and writes OUTPUT/results.parquet and results.csv, the plots (OUTPUT/plots/)
and OUTPUT/report.html."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from . import table
from .report import write_report
from .runner import run_sweep
from .simulator import Simulator, SimulatorError
from .spec import SpecError, check, expand, load_spec

# python/tessera_sweep/ -> the repository's default build
DEFAULT_SOC_SIM = Path(__file__).resolve().parents[2] / "build" / "default" / "bin" / "soc_sim"


def command_line_settings(options: argparse.Namespace, spec) -> dict:
    """The settings --set and --host give every point (--host last); a key the spec sweeps is refused."""
    settings: dict = {}
    for item in options.set:
        key, equals, value = item.partition("=")
        if not equals or not key.strip():
            raise SpecError(f"--set {item!r}: expected KEY=VALUE")
        settings[key.strip()] = value
    if options.host:
        settings["host.model"] = options.host
    swept = sorted(set(settings) & set(spec.axis_keys))
    if swept:
        raise SpecError(f"--set/--host: {', '.join(swept)} is an axis of the sweep; drop it from the spec or the "
                        "command line")
    return settings


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="tessera-sweep", description=__doc__)
    parser.add_argument("spec", type=Path, help="sweep spec, YAML or JSON")
    parser.add_argument("--out", type=Path, help="output folder (default: the spec's 'output')")
    parser.add_argument("--soc-sim", default=os.environ.get("TESSERA_SOC_SIM", DEFAULT_SOC_SIM),
                        help="soc_sim to run (default: $TESSERA_SOC_SIM, else build/default/bin/soc_sim)")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler, tcp://HOST:PORT "
                        "(default: a local cluster)")
    parser.add_argument("--workers", type=int, help="local cluster's workers (default: one per core)")
    parser.add_argument("--retry-failed", action="store_true", help="run failed points again")
    parser.add_argument("--check", action="store_true", help="check the spec and every point, run nothing")
    parser.add_argument("--report-only", action="store_true",
                        help="rebuild the plots and report.html from the output's results table, run nothing")
    parser.add_argument("--host", choices=("native", "iss"),
                        help="the host model of every point (host.model): native, the host-compiled model, or iss, "
                             "the driver as ARM code on the ISS; recorded in the table's host_model column")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a configuration setting for every point, over the spec's config (repeatable)")
    options = parser.parse_args(argv)
    try:
        spec = load_spec(options.spec)
        spec.base.update(command_line_settings(options, spec))
        simulator = Simulator(options.soc_sim)
        if options.check:
            points = expand(spec)
            check(points, simulator)
            print(f"tessera-sweep: {len(points)} points, all valid")
            return 0
        output = options.out or spec.output
        if output is None:
            raise SpecError("no output folder: give 'output' in the spec or --out")
        if options.report_only:
            report = write_report(spec, table.load(output), output)
            print(f"tessera-sweep: {report}")
            return 0
        phases = {}
        results, _ = run_sweep(spec, simulator, output, options.scheduler, options.workers,
                               options.retry_failed, phases)
    except (SpecError, SimulatorError, OSError) as error:
        print(f"tessera-sweep: {error}", file=sys.stderr)
        return 2
    failed = int((results["status"] != 0).sum())
    timing = ", ".join(f"{name} {phases[key]:.1f} s" for key, name in
                       (("check_s", "check"), ("runs_s", "runs"), ("total_s", "total")) if key in phases)
    print(f"tessera-sweep: {len(results)} points in {output}/results.parquet, {failed} failed ({timing})")
    return 1 if failed else 0
