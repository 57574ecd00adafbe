#!/usr/bin/python3
"""Alias of `tessera-sweep run` for the study's experiments (python/tessera_sweep/experiment.py):
the same arguments without "run", and --list for `tessera-sweep list`.

    scripts/experiment.py --list
    scripts/experiment.py teapot --frames 1 --out out/quick
    scripts/experiment.py dma_whatif --set ciu.read_cycles=40 --out out/whatif_ciu

Runs under Debian's python3 (its #! line), which has matplotlib, PyYAML and pandas (scripts/setup.sh).
"""

import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "python"))

from tessera_sweep import experiment  # noqa: E402

if __name__ == "__main__":
    sys.exit(experiment.main())
else:
    # `import experiment` (tests/scripts/test_experiment.py) gets the package's module itself.
    sys.modules[__name__] = experiment
