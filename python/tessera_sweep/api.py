"""The Python API: run a sweep spec or an experiment and get its table as a
pandas DataFrame (run), or read a finished one back (load).

    import tessera_sweep
    table = tessera_sweep.run("dma_whatif", {"ciu.read_cycles": 40}, frames=1)
    table = tessera_sweep.load("out/experiments/dma_whatif")

README.md beside this file has a worked example (a test runs it)."""

from __future__ import annotations

import copy
import os
import pathlib

import pandas as pd

from . import experiment, table
from .runner import run_sweep
from .simulator import Simulator
from .spec import SpecError, load_spec, parse_spec


def _default_soc_sim(soc_sim):
    return soc_sim or os.environ.get("TESSERA_SOC_SIM") or experiment.DEFAULT_SOC_SIM


def _read(spec_or_path):
    """(data, name, the sweep spec's file or None) of a spec given as data, a file or an experiment's name."""
    if isinstance(spec_or_path, dict):
        return copy.deepcopy(spec_or_path), "experiment", None
    path = pathlib.Path(spec_or_path)
    if not path.suffix and not path.exists():
        path = experiment.experiment_path(str(spec_or_path))
    return experiment.read_experiment(path), path.stem, path


def _frame(columns, rows):
    keys = ["run"] + [column["key"] for column in experiment.RUN_COLUMNS + columns]
    return pd.DataFrame([[label, *values] for label, values in rows], columns=keys)


def run(
    spec_or_path,
    overrides: dict | None = None,
    *,
    out=None,
    soc_sim=None,
    frames: int | None = None,
    hosts: list[str] | None = None,
    programs: list[str] | None = None,
    workers: int | None = None,
    quiet: bool = True,
) -> pd.DataFrame:
    """Runs a spec and returns its table.

    spec_or_path: an experiment's name ("dma_whatif": experiments/dma_whatif.yaml), the path of an experiment or
    sweep spec (YAML or JSON), or the spec itself as a dict. overrides: configuration settings for every run or
    point, over the spec's own ({"ciu.read_cycles": 40}). frames: the frames of each run instead of the spec's.

    An experiment returns its table (a row per run: run, host, program and its columns' keys, unrounded, as its
    CSV) with attrs["study"], the study's table (or None), attrs["markdown"], the tables as printed, and
    attrs["out"], the folder written (default out/experiments/NAME); hosts and programs choose its host models
    and array programs (["native", "iss"], ["study", "tuned"]). A sweep spec returns its results table (one row
    per point) and writes into out (default: the spec's 'output'), its points on `workers` local workers.
    Raises experiment.UsageError or SpecError for a bad spec, experiment.RunError for a failed run."""
    data, name, path = _read(spec_or_path)
    overrides = dict(overrides or {})
    soc_sim = _default_soc_sim(soc_sim)
    if experiment.is_experiment(data):
        spec = experiment.check_experiment(data, str(path or "the experiment given"))
        settings = experiment.check_overrides(overrides, lambda key: f"overrides[{key!r}]")
        if frames is not None:
            experiment.positive_int("frames", frames)
        for value, allowed, what in ((hosts, experiment.HOSTS, "hosts"), (programs, experiment.PROGRAMS, "programs")):
            if value is not None:
                experiment.choice_list("run()", what, value, allowed)
        folder = pathlib.Path(out) if out else experiment.ROOT / "out" / "experiments" / name
        outcome = experiment.run_spec(
            spec, name, experiment.soc_sim_path(soc_sim), folder, frames, quiet, settings, hosts, programs
        )
        result = _frame(spec["columns"], outcome.rows)
        result.attrs["study"] = _frame(spec["study"]["columns"], outcome.study_rows) if "study" in spec else None
        result.attrs["markdown"] = outcome.text
        result.attrs["out"] = folder
        return result
    sweep = load_spec(path) if path else parse_spec(data)
    if frames is not None:
        overrides["sim.frames"] = frames
    swept = sorted(set(overrides) & set(sweep.axis_keys))
    if swept:
        raise SpecError(f"overrides: {', '.join(swept)} is an axis of the sweep")
    sweep.base.update(overrides)
    output = pathlib.Path(out) if out else sweep.output
    if output is None:
        raise SpecError("no output folder: give 'output' in the spec or out=")
    results, _ = run_sweep(sweep, Simulator(soc_sim), output, workers=workers)
    return results


def load(results_dir, study: bool = False) -> pd.DataFrame:
    """The table a run left in results_dir: a sweep's results.parquet, or an experiment's NAME.csv (with
    study=True, its NAME_study.csv)."""
    folder = pathlib.Path(results_dir)
    if (folder / table.PARQUET).is_file() and not study:
        return table.load(folder)
    found = [
        path
        for path in sorted(folder.glob("*.csv"))
        if path.name != table.CSV and path.stem.endswith("_study") == study
    ]
    if len(found) != 1:
        what = "a study's table" if study else "a results table"
        raise FileNotFoundError(f"{folder}: no {what} (results.parquet or one experiment's NAME.csv)")
    return pd.read_csv(found[0])
