#!/usr/bin/env bash
# Second quick-start command (and CI): installs what is missing, builds, and
# runs the whole test suite: the default test preset (everything but the
# labels slow and iss_slow, which the presets lint-full, iss-slow and slow
# run: tests/README.md). Extra arguments go to the default build's ctest
# (e.g. -L unit). Then the sanitize preset (GCC, ASan + UBSan with the
# float-cast check, leak checking): its own Debug build of what the unit
# and tlm tests run, and those tests; TESSERA_SKIP_SANITIZE=1 leaves it out.
# Then the fuzz preset (clang, libFuzzer, ASan + UBSan): its own build of the
# fuzz targets, each run on its corpus and 1e5 new inputs (docs/fuzzing.md);
# TESSERA_SKIP_FUZZ=1 leaves it out. Each step prints its wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
step_start=$SECONDS
step_done() {
  echo "test: $1 took $((SECONDS - step_start)) s ($((SECONDS / 60)) min since the start)"
  step_start=$SECONDS
}
scripts/setup.sh
step_done "set-up"
cmake --preset default
cmake --build --preset default
step_done "the default build"
ctest --preset default "$@"
step_done "the default test preset"

if [[ "${TESSERA_SKIP_SANITIZE:-0}" == "1" ]]; then
  echo "test: TESSERA_SKIP_SANITIZE=1, not running the sanitize preset"
else
  cmake --preset sanitize
  # Only the programs the unit and tlm tests run (the preset's labels), not
  # the benchmarks and tools no test of theirs needs.
  sanitize_list=$(python3 scripts/test_targets.py build/sanitize -L "unit|tlm")
  mapfile -t sanitize_targets <<<"$sanitize_list"
  cmake --build --preset sanitize --target "${sanitize_targets[@]}"
  step_done "the sanitize build"
  ctest --preset sanitize
  step_done "the sanitize test preset"
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
step_done "the fuzz build"
ctest --preset fuzz
step_done "the fuzz test preset"
