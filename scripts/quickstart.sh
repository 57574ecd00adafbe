#!/usr/bin/env bash
# First quick-start command: installs what is missing, builds, and runs the
# default demo (the teapot) with a waveform: frames, statistics and the VCD
# trace in ./out (out/trace.vcd, opens in GTKWave). Arguments go to soc_sim:
# --force replaces the outputs of an earlier run, --out DIR moves them all
# (the trace to DIR/trace.vcd), --vcd FILE puts the trace elsewhere.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset default
cmake --build --preset default

out=out
trace=yes
previous=""
for arg in "$@"; do
  [[ "$previous" == "--out" ]] && out="$arg"
  case "$arg" in
    --out=*) out="${arg#--out=}" ;;
    --vcd | --vcd=*) trace=no ;;
    --) break ;;
  esac
  previous="$arg"
done
vcd=()
[[ "$trace" == yes ]] && vcd=(--vcd "$out/trace.vcd")
build/default/bin/soc_sim "${vcd[@]}" "$@"
