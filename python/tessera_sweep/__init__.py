"""Parameter sweeps of soc_sim: a spec, its points, their runs and one table."""

from .simulator import Simulator, SimulatorError
from .spec import Point, Spec, SpecError, load_spec
from .table import load

__all__ = ["Point", "Simulator", "SimulatorError", "Spec", "SpecError", "load", "load_spec"]
