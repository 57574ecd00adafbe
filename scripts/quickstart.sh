#!/usr/bin/env bash
# First quick-start command: installs what is missing, builds soc_sim and
# only what it needs (the tests, benchmarks and the ARM sub-build come with
# the second command, scripts/test.sh), and runs the default demo (the
# teapot) with a waveform: frames, statistics and the VCD trace in ./out
# (out/trace.vcd, opens in GTKWave); it ends by naming the picture, and
# opens it where a desktop is there to show it. Arguments go to soc_sim:
# --force replaces the outputs of an earlier run, --out DIR moves them all
# (the trace to DIR/trace.vcd), --vcd FILE puts the trace elsewhere.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset default
cmake --build --preset default --target soc_sim

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

# The last frame the demo wrote is the picture; soc_sim names each frame
# frame_NNNN.png in its output folder.
picture=$(ls "$out"/frame_*.png 2>/dev/null | tail -n 1 || true)
if [[ -n "$picture" ]]; then
  echo "quickstart: the picture: $picture"
  if [[ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]] && command -v xdg-open >/dev/null 2>&1; then
    xdg-open "$picture" >/dev/null 2>&1 &
  fi
fi
