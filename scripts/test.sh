#!/usr/bin/env bash
# Second quick-start command (and CI): installs what is missing, builds, and
# runs the whole test suite. Extra arguments go to ctest (e.g. -L unit).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset default
cmake --build --preset default
ctest --preset default "$@"
