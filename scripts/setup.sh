#!/usr/bin/env bash
# Installs the Debian packages tessera needs, skipping those already present.
# Idempotent; runs as root or through sudo. Set TESSERA_SKIP_INSTALL=1 to skip.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git
  ccache                  # rebuilds and other clones on this machine reuse compiled units (cmake/Ccache.cmake)
  libsystemc-dev          # SystemC 2.3 with TLM-2.0
  libglm-dev              # vector maths for the GL front end
  libpng-dev              # PNG output of the display (soc_sim)
  libopenimageio-dev      # reading images back: tests and comparison tools
  libgtest-dev            # unit and TLM tests
  libgles-dev libegl-dev  # Khronos GL ES / EGL headers: the conformance test compares ours with them
  verilator               # Verilog reference units; its copy of GTKWave's FST writer (fstapi) is soc_sim --fst's
  zlib1g-dev              # fstapi's compression
  libosmesa6-dev          # Mesa off-screen renderer for reference images
  nlohmann-json3-dev      # configuration and statistics files
  libcli11-dev            # command-line parsing
  libtinyobjloader-dev    # Wavefront OBJ loading
  libunicorn-dev          # an independent ARM emulator: the ISS lock-step test
  gcc-arm-none-eabi libnewlib-arm-none-eabi  # bare-metal ARM922T programs for the ISS (tests/host/iss_programs)
  libstdc++-arm-none-eabi-newlib  # C++ for the bare-metal ARM: the GL driver cross-compiled for the ISS (issue 15)
  gdb-multiarch           # GDB against the ISS (iss_run --gdb; tests/host/iss/gdb_session.sh)
  yosys                   # synthesis size report of the Verilog units
  clang-format clang-tidy # the lint tests: one code dialect (tests/lint)
  clang-14 libclang-rt-14-dev  # the fuzz preset: clang with libFuzzer, ASan and UBSan (docs/fuzzing.md)
  gtkwave                 # viewing VCD and FST traces; its vcd2fst and fst2vcd check them in the tests
  python3                 # helper scripts
  python3-matplotlib      # reciprocal error plots (scripts/plot_reciprocal_error.py)
  python3-dask python3-distributed  # tessera-sweep: runs a sweep's points on a Dask cluster
  python3-pandas          # tessera-sweep: the results table
  python3-jinja2          # tessera-sweep: the HTML report (and soc_sim --report's)
  chromium                # headless, the test run_report_chromium loads soc_sim --report's page
  python3-yaml            # tessera-sweep: YAML sweep specs
  python3-pytest          # tessera-sweep's tests (python/tests)
  python3-hypothesis      # tessera-sweep's tests: the sweep spec fuzzed (python/tests/test_spec_fuzz.py)
  python3-venv python3-pip  # the sweep venv below
)

# Debian 12 has no pyarrow (pandas' Parquet engine): it comes from PyPI, pinned,
# into a venv that sees Debian's packages. build/ is not in git, so the venv is
# per work tree; CMake looks for it there (TESSERA_SWEEP_PYTHON).
SWEEP_VENV="$(cd "$(dirname "$0")/.." && pwd)/build/venv"
PYARROW_VERSION=14.0.2  # the last with wheels built against numpy 1.x, Debian 12's numpy
# The Python linter and formatter (tests/python: python_ruff_check, python_ruff_format;
# ruff.toml). Pinned: another version formats some constructs differently.
RUFF_VERSION=0.17.5
# Function lengths for the lint test lint_function_length (scripts/check_function_length.py).
LIZARD_VERSION=1.24.3

setup_sweep_venv() {
  if [[ -x "$SWEEP_VENV/bin/tessera-sweep" ]] &&
     "$SWEEP_VENV/bin/python3" -c "import pyarrow, sys; sys.exit(pyarrow.__version__ != '$PYARROW_VERSION')" 2>/dev/null &&
     [[ "$("$SWEEP_VENV/bin/ruff" --version 2>/dev/null)" == "ruff $RUFF_VERSION" ]] &&
     "$SWEEP_VENV/bin/python3" -c "import importlib.metadata as m, sys; sys.exit(m.version('lizard') != '$LIZARD_VERSION')" 2>/dev/null; then
    return
  fi
  echo "setup: sweep venv in $SWEEP_VENV (pyarrow $PYARROW_VERSION, ruff $RUFF_VERSION, lizard $LIZARD_VERSION, tessera-sweep)"
  /usr/bin/python3 -m venv --system-site-packages "$SWEEP_VENV"
  local pip=("$SWEEP_VENV/bin/python3" -m pip install -q --disable-pip-version-check)
  "${pip[@]}" "pyarrow==$PYARROW_VERSION" "ruff==$RUFF_VERSION" "lizard==$LIZARD_VERSION"
  # Editable: build/venv/bin/tessera-sweep runs python/tessera_sweep as it is
  # in this work tree; its dependencies are the Debian packages above.
  "${pip[@]}" --no-deps --no-build-isolation -e "$(dirname "$SWEEP_VENV")/../python"
}

if [[ "${TESSERA_SKIP_INSTALL:-0}" == "1" ]]; then
  echo "setup: TESSERA_SKIP_INSTALL=1, not installing packages"
  exit 0
fi

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  setup_sweep_venv
  exit 0
fi

if [[ $(id -u) -eq 0 ]]; then
  SUDO=()
elif command -v sudo >/dev/null 2>&1; then
  SUDO=(sudo)
else
  echo "setup: missing packages (${missing[*]}) and neither root nor sudo is available" >&2
  exit 1
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -qq
"${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
setup_sweep_venv
