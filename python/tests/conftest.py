import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tessera_sweep import Simulator
from tessera_sweep.cli import DEFAULT_SOC_SIM
from tessera_sweep.runner import run_sweep
from tessera_sweep.spec import parse_spec


@pytest.fixture(scope="session")
def simulator():
    """The soc_sim ctest names in TESSERA_SOC_SIM, else the default build."""
    return Simulator(os.environ.get("TESSERA_SOC_SIM", DEFAULT_SOC_SIM))


# The smallest real run: one triangle frame at 192 x 144, a fraction of a second.
TINY = {
    "app": "triangle",
    "frames": 1,
    "config": {"display.width": 192, "display.height": 144},
}


@pytest.fixture
def tiny():
    return {key: (dict(value) if isinstance(value, dict) else value) for key, value in TINY.items()}


def write_spec(folder: Path, data: dict, name: str = "spec.json") -> Path:
    path = folder / name
    path.write_text(json.dumps(data))
    return path


# Half the points fail on purpose: a 1 ms simulated-time limit is a valid
# configuration that stops the run with exit status 1.
AXES = {"driver.backend": ["arm", "raster"], "sim.time_limit_ms": [0, 1]}
METRICS = ["stats.host.busy_cycles", "stats.frames.0.energy.total_j"]


@pytest.fixture(scope="session")
def spec():
    return parse_spec(dict(TINY, axes=AXES, metrics=METRICS))


@pytest.fixture(scope="session")
def first_run(spec, simulator, tmp_path_factory):
    """The four points of AXES, run once for the whole session."""
    out = tmp_path_factory.mktemp("sweep")
    table, ran = run_sweep(spec, simulator, out, workers=2)
    return out, table, ran


def tessera_sweep_command(*args):
    return subprocess.run([sys.executable, "-m", "tessera_sweep", *args], capture_output=True, text=True)
