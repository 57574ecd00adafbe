#!/usr/bin/env bash
# Synthesis size of the Verilog reference units (the rasterizer's datapath and
# the array processor's CU): yosys maps each
# unit to its generic gate library (synth -top <unit>; stat) and this prints
# one line per unit with the cell count, beside the paper's figure where
# Crisu et al. give one (Table IV: Method 3 reciprocal, 1615 standard cells in
# UMC 0.18 um). Generic yosys cells are 2-input gates, muxes and flip-flops,
# not a standard-cell library, so that count compares in order of magnitude
# only. With --cmos4 a second count re-maps the same netlist with
# `abc -g cmos4` (NAND, NOR, NOT, AOI3/4, OAI3/4: complex gates closer to a
# real library's); it is off by default because ABC can take many minutes on
# the units with wide multipliers.
#
#   scripts/synth_report.sh                     # every unit of rtl_models/units.def
#   scripts/synth_report.sh reciprocal          # only the named units
#   scripts/synth_report.sh --cmos4 reciprocal  # also the cmos4 count
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
RTL_DIR="$ROOT/rtl_models"
YOSYS="${YOSYS:-yosys}"

if ! command -v "$YOSYS" >/dev/null 2>&1; then
  echo "synth_report: $YOSYS not found (scripts/setup.sh installs yosys)" >&2
  exit 1
fi

CMOS4=0
if [[ "${1:-}" == "--cmos4" ]]; then
  CMOS4=1
  shift
fi

LOG_DIR="$(mktemp -d)"
trap 'rm -rf "$LOG_DIR"' EXIT

# The units, one line each of rtl_models/units.def, the one table of them:
# name, folder, the generated packages it reads, the paper's cell count.
UNITS=()
while IFS= read -r line; do
  if [[ ! "$line" =~ ^TESSERA_RTL_UNIT\(([a-z][a-z0-9_]*),\ ([a-z]+),\ \"[^\"]+\",\ [a-z_]+,\ ([a-z_ ]+),\ ([0-9]+),\ \".*\"\)$ ]]; then
    echo "synth_report: rtl_models/units.def: cannot read '$line'" >&2
    exit 1
  fi
  UNITS+=("${BASH_REMATCH[1]}|${BASH_REMATCH[2]}|${BASH_REMATCH[3]}|${BASH_REMATCH[4]}")
done < <(grep '^TESSERA_RTL_UNIT(' "$RTL_DIR/units.def")

# Each package a unit reads, written by cmake/<package>.cmake from the
# tables the C++ model uses, as the build does for Verilator
# (tessera_add_sv_package, cmake/RtlUnits.cmake).
package_file() {
  local package="$1" file="$LOG_DIR/$1.sv"
  if [[ ! -f "$file" ]] && ! cmake -DROOT="$ROOT" -DOUT="$file" -P "$ROOT/cmake/$package.cmake" >&2; then
    echo "synth_report: cannot generate $package.sv" >&2
    exit 1
  fi
  echo "$file"
}

status=0
printf '%-24s %8s %8s %6s  %s\n' "unit" "cells" "cmos4" "flops" "paper (Table IV)"
cmos4_cmds=""
if [[ $CMOS4 -eq 1 ]]; then
  cmos4_cmds="; abc -g cmos4; stat"
fi
for entry in "${UNITS[@]}"; do
  IFS='|' read -r top folder packages paper <<<"$entry"
  if [[ $# -gt 0 && ! " $* " =~ " $top " ]]; then
    continue
  fi
  read_cmds=""
  for package in $packages; do
    if [[ "$package" != none ]]; then
      read_cmds+="read_verilog -sv $(package_file "$package"); "
    fi
  done
  read_cmds+="read_verilog -sv $RTL_DIR/$folder/$top.sv; "
  log="$LOG_DIR/$top.log"
  if ! "$YOSYS" -q -l "$log" -p "${read_cmds}synth -top $top; stat${cmos4_cmds}" >/dev/null 2>&1; then
    printf '%-24s %8s %8s %6s  %s\n' "$top" "FAILED" "-" "-" "see: $YOSYS -p '${read_cmds}synth -top $top'"
    status=1
    continue
  fi
  # Statistics blocks in the log: synth's own, ours after synth and, with
  # --cmos4, ours after abc -g cmos4 (one block each: synth -top flattens).
  if [[ $CMOS4 -eq 1 ]]; then
    cells=$(grep -E '^ +Number of cells:' "$log" | tail -n 2 | head -n 1 | awk '{print $4}')
    cmos_cells=$(grep -E '^ +Number of cells:' "$log" | tail -n 1 | awk '{print $4}')
  else
    cells=$(grep -E '^ +Number of cells:' "$log" | tail -n 1 | awk '{print $4}')
    cmos_cells="-"
  fi
  flops=$(awk '/^ +Number of cells:/ {n = 0} /^ +\$_(S?DFF|DLATCH)/ {n += $2} END {print n + 0}' "$log")
  if [[ "$paper" == 0 ]]; then
    paper_text="-"
  else
    paper_text="$paper standard cells"
  fi
  printf '%-24s %8s %8s %6s  %s\n' "$top" "$cells" "$cmos_cells" "$flops" "$paper_text"
done
exit $status
