"""tessera-sweep: soc_sim over many configurations, in two kinds of spec.

    tessera-sweep run SPEC [options]      a sweep spec or an experiment (by file or by name)
    tessera-sweep run cluster_NAME ...    a cluster experiment (cluster_experiments.py: depth, speedup, soc)
    tessera-sweep list                    the experiments (experiments/*.yaml and the cluster's)
    tessera-sweep sort-middle COMMAND     Crockett and Orloff's sort-middle model: table, time, fit
    tessera-sweep run-report STATS HTML   one run of soc_sim on one page (run_report.py; soc_sim --report)
    tessera-sweep SPEC [options]          a sweep spec, as before "run" existed

A sweep spec (axes, zip groups, metrics): checks every point, runs those not
yet run and writes OUTPUT/results.parquet and results.csv, the plots
(OUTPUT/plots/) and OUTPUT/report.html. An experiment (runs or a matrix of
them, and a table's columns: experiment.py): runs it and prints its tables.
--set KEY=VALUE overrides any configuration key in every point or run, and
--frames the frames of each."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from . import cluster_experiments, experiment, run_report, sort_middle_model, table
from .report import write_report
from .runner import run_sweep
from .simulator import Simulator, SimulatorError
from .spec import SpecError, check, expand, load_spec

# The repository's default build (build/default/bin/soc_sim).
DEFAULT_SOC_SIM = experiment.DEFAULT_SOC_SIM


def command_line_settings(options: argparse.Namespace, spec) -> dict:
    """The settings --set, --host and --frames give every point (the last two last); a key the spec sweeps is
    refused."""
    settings: dict = {}
    for item in options.set:
        key, equals, value = item.partition("=")
        if not equals or not key.strip():
            raise SpecError(f"--set {item!r}: expected KEY=VALUE")
        settings[key.strip()] = value
    if options.host:
        settings["host.model"] = options.host
    if options.frames is not None:
        settings["sim.frames"] = options.frames
    swept = sorted(set(settings) & set(spec.axis_keys))
    if swept:
        raise SpecError(
            f"--set/--host: {', '.join(swept)} is an axis of the sweep; drop it from the spec or the command line"
        )
    return settings


def add_sweep_arguments(parser: argparse.ArgumentParser) -> None:
    """The options only a sweep spec takes."""
    parser.add_argument(
        "--scheduler", help="address of a running Dask scheduler, tcp://HOST:PORT (default: a local cluster)"
    )
    parser.add_argument("--workers", type=int, help="local cluster's workers (default: one per core)")
    parser.add_argument("--retry-failed", action="store_true", help="run failed points again")
    parser.add_argument("--check", action="store_true", help="check the spec and every point, run nothing")
    parser.add_argument(
        "--report-only",
        action="store_true",
        help="rebuild the plots and report.html from the output's results table, run nothing",
    )


SWEEP_ONLY = ("scheduler", "workers", "retry_failed", "check", "report_only")
EXPERIMENT_ONLY = ("program", "quiet")


def is_experiment_spec(name: str) -> bool:
    """Whether `name` names an experiment (experiments/NAME.yaml, or a file with a table's columns) rather than
    a sweep spec; a file that cannot be read or parsed counts as a sweep spec, whose loader says why."""
    path = Path(name)
    if not path.suffix and not path.exists():
        return True  # a name: experiment.experiment_path finds it or lists the known ones
    try:
        return experiment.is_experiment(experiment.read_experiment(path))
    except experiment.UsageError:
        return False


def run_main(argv: list[str]) -> int:
    """tessera-sweep run SPEC...: an experiment (several may be named) or one sweep spec; or one of the cluster's
    experiments, with its own options (cluster_experiments.py)."""
    if argv[:1] and argv[0] in cluster_experiments.EXPERIMENTS:
        return cluster_experiments.main(argv, "tessera-sweep run")
    parser = argparse.ArgumentParser(
        prog="tessera-sweep run", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument(
        "specs",
        nargs="+",
        metavar="SPEC",
        help="an experiment's name (experiments/NAME.yaml) or file, or a sweep spec (YAML or JSON)",
    )
    experiment.add_arguments(parser)
    add_sweep_arguments(parser)
    options = parser.parse_args(argv)
    given = {name for name, value in vars(options).items() if value not in (None, False, [])}
    kinds = {is_experiment_spec(name) for name in options.specs}
    if kinds == {True}:
        wrong = sorted(given & set(SWEEP_ONLY))
        if wrong:
            parser.error(f"--{wrong[0].replace('_', '-')} applies to a sweep spec, not to an experiment")
        options.experiments, options.list = options.specs, False
        options.soc_sim = options.soc_sim or os.environ.get("TESSERA_SOC_SIM")
        return experiment.run_command(options, "tessera-sweep")
    if len(options.specs) != 1:
        parser.error("give one sweep spec (several names are for experiments only)")
    wrong = sorted(given & set(EXPERIMENT_ONLY))
    if wrong:
        parser.error(f"--{wrong[0]} applies to an experiment, not to a sweep spec")
    if options.host not in (None, "native", "iss"):
        parser.error(f"--host {options.host!r}: a sweep's points run on one host model, native or iss")
    options.spec = Path(options.specs[0])
    options.out = Path(options.out) if options.out else None
    options.soc_sim = options.soc_sim or os.environ.get("TESSERA_SOC_SIM", DEFAULT_SOC_SIM)
    return sweep(options)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["run"]:
        return run_main(argv[1:])
    if argv[:1] == ["list"]:
        return experiment.main(["--list", *argv[1:]], prog="tessera-sweep list")
    if argv[:1] == ["sort-middle"]:
        return sort_middle_model.main(argv[1:])
    if argv[:1] == ["run-report"]:
        return run_report.main(argv[1:], prog="tessera-sweep run-report")
    parser = argparse.ArgumentParser(
        prog="tessera-sweep", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("spec", type=Path, help="sweep spec, YAML or JSON")
    parser.add_argument("--out", type=Path, help="output folder (default: the spec's 'output')")
    parser.add_argument(
        "--soc-sim",
        default=os.environ.get("TESSERA_SOC_SIM", DEFAULT_SOC_SIM),
        help="soc_sim to run (default: $TESSERA_SOC_SIM, else build/default/bin/soc_sim)",
    )
    add_sweep_arguments(parser)
    parser.add_argument(
        "--host",
        choices=("native", "iss"),
        help="the host model of every point (host.model): native, the host-compiled model, or iss, "
        "the driver as ARM code on the ISS; recorded in the table's host_model column",
    )
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="a configuration setting for every point, over the spec's config (repeatable)",
    )
    options = parser.parse_args(argv)
    options.frames = None
    return sweep(options)


def sweep(options: argparse.Namespace) -> int:
    """Checks and runs the sweep spec options.spec as the options say; the exit status."""
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
        results, _ = run_sweep(
            spec, simulator, output, options.scheduler, options.workers, options.retry_failed, phases
        )
    except (SpecError, SimulatorError, OSError) as error:
        print(f"tessera-sweep: {error}", file=sys.stderr)
        return 2
    failed = int((results["status"] != 0).sum())
    timing = ", ".join(
        f"{name} {phases[key]:.1f} s"
        for key, name in (("check_s", "check"), ("runs_s", "runs"), ("total_s", "total"))
        if key in phases
    )
    print(f"tessera-sweep: {len(results)} points in {output}/results.parquet, {failed} failed ({timing})")
    return 1 if failed else 0
