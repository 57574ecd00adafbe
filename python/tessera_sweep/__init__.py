"""soc_sim over many configurations: parameter sweeps (a spec, its points,
their runs and one results table) and the study's experiments (a spec of
runs and a table template). run() and load() are the Python API (api.py);
tessera-sweep the command (cli.py)."""

from .experiment import RunError, UsageError
from .simulator import Simulator, SimulatorError
from .spec import Point, Spec, SpecError, load_spec

__all__ = [
    "Point",
    "RunError",
    "Simulator",
    "SimulatorError",
    "Spec",
    "SpecError",
    "UsageError",
    "load",
    "load_spec",
    "run",
]


def __getattr__(name):
    # run and load need pandas; the experiments alone (scripts/experiment.py, under any python3 with PyYAML) do
    # not, so the API is imported when first used.
    if name in ("run", "load"):
        from . import api

        return getattr(api, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
