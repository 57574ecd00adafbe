#!/usr/bin/env bash
# Second quick-start command (and CI): installs what is missing, builds, and
# runs the whole test suite. Extra arguments go to the default build's ctest
# (e.g. -L unit). Then the fuzz preset (clang, libFuzzer, ASan + UBSan):
# its own build of the fuzz targets, each run on its corpus and 1e5 new
# inputs (docs/fuzzing.md); TESSERA_SKIP_FUZZ=1 leaves it out.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset default
cmake --build --preset default
ctest --preset default "$@"

if [[ "${TESSERA_SKIP_FUZZ:-0}" == "1" ]]; then
  echo "test: TESSERA_SKIP_FUZZ=1, not running the fuzz targets"
  exit 0
fi
if ! command -v clang++-14 >/dev/null 2>&1; then
  echo "test: clang++-14 is missing: the fuzz targets need it (scripts/setup.sh installs clang-14 and libclang-rt-14-dev)" >&2
  exit 1
fi
cmake --preset fuzz
cmake --build --preset fuzz
ctest --preset fuzz
