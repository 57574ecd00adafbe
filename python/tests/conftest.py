import json
import os
from pathlib import Path

import pytest

from tessera_sweep import Simulator
from tessera_sweep.cli import DEFAULT_SOC_SIM


@pytest.fixture(scope="session")
def simulator():
    """The soc_sim ctest names in TESSERA_SOC_SIM, else the default build."""
    return Simulator(os.environ.get("TESSERA_SOC_SIM", DEFAULT_SOC_SIM))


# The smallest real run: one triangle frame at 192 x 144, a fraction of a second.
TINY = {
    "app": "triangle",
    "frames": 1,
    "config": {"display.width": 192, "display.height": 144,
               "raster.width": 192, "raster.height": 144},
}


@pytest.fixture
def tiny():
    return {key: (dict(value) if isinstance(value, dict) else value) for key, value in TINY.items()}


def write_spec(folder: Path, data: dict, name: str = "spec.json") -> Path:
    path = folder / name
    path.write_text(json.dumps(data))
    return path
