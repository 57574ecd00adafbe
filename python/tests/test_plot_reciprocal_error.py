"""scripts/plot_reciprocal_error.py runs under the project's Python (this
test runs under build/venv, which scripts/setup.sh makes): one PNG per
method of the reciprocal unit and the three on one page, from the
recip_table beside the soc_sim under test."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tessera_sweep.cli import DEFAULT_SOC_SIM

ROOT = Path(__file__).resolve().parents[2]
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def recip_table() -> Path:
    """The recip_table beside the soc_sim under test, else the default build's."""
    for soc_sim in (os.environ.get("TESSERA_SOC_SIM"), DEFAULT_SOC_SIM):
        if soc_sim and (Path(soc_sim).parent / "recip_table").is_file():
            return Path(soc_sim).parent / "recip_table"
    pytest.skip("recip_table is not built (cmake --build --preset default --target recip_table)")


def test_plots_every_method_from_the_project_environment(tmp_path):
    out = tmp_path / "recip"
    done = subprocess.run(
        [sys.executable, str(ROOT / "scripts/plot_reciprocal_error.py"), str(recip_table()), str(out)],
        capture_output=True,
        text=True,
        timeout=240,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    for name in ("fig4_method1.png", "fig5_method2.png", "fig7_method3.png", "reciprocal_error_all.png"):
        data = (out / name).read_bytes()
        assert data.startswith(PNG_SIGNATURE) and len(data) > 10_000, name
    # One line per method with its error figures.
    assert done.stdout.count("max |relative error| = ") == 3, done.stdout
