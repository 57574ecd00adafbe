#!/usr/bin/env bash
# First quick-start command: installs what is missing, builds, and runs the
# default simulation (outputs in ./out).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset default
cmake --build --preset default
build/default/bin/soc_sim "$@"
