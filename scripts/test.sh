#!/usr/bin/env bash
# Second quick-start command (and CI): installs what is missing, builds, and
# runs the whole test suite. Extra arguments go to the default build's ctest
# (e.g. -L unit). Then the sanitize preset (GCC, ASan + UBSan with the
# float-cast check, tests/README.md): its own Debug build of what the unit
# and tlm tests run, and those tests; TESSERA_SKIP_SANITIZE=1 leaves it out.
# Then the fuzz preset (clang, libFuzzer, ASan + UBSan): its own build of the
# fuzz targets, each run on its corpus and 1e5 new inputs (docs/fuzzing.md);
# TESSERA_SKIP_FUZZ=1 leaves it out.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset default
cmake --build --preset default
ctest --preset default "$@"

if [[ "${TESSERA_SKIP_SANITIZE:-0}" == "1" ]]; then
  echo "test: TESSERA_SKIP_SANITIZE=1, not running the sanitize preset"
else
  cmake --preset sanitize
  # Only the programs the unit and tlm tests run (the preset's labels), not
  # the benchmarks and tools no test of theirs needs.
  sanitize_list=$(python3 scripts/test_targets.py build/sanitize -L "unit|tlm")
  mapfile -t sanitize_targets <<<"$sanitize_list"
  cmake --build --preset sanitize --target "${sanitize_targets[@]}"
  ctest --preset sanitize
fi

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
