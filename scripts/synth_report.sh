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
#   scripts/synth_report.sh                     # every unit in UNITS
#   scripts/synth_report.sh recip_unit          # only the named units
#   scripts/synth_report.sh --cmos4 recip_unit  # also the cmos4 count
set -euo pipefail

# top module | sources under rtl_models/ (space separated) | paper's cell count or -
# Every unit also reads fixed_function_pkg.sv, ap_isa_pkg.sv and
# fog_table_pkg.sv, which this script generates from
# contract/common/fixed_function.def, tlm/array/isa/ and
# contract/common/fog_exp2_table.def with cmake/fixed_function_pkg.cmake,
# cmake/ap_isa_pkg.cmake and cmake/fog_table_pkg.cmake, as the build does for
# Verilator.
UNITS=(
  "recip_unit|raster/recip_unit.sv|1615"
  "edge_function|raster/edge_function.sv|-"
  "attr_interp|raster/attr_interp.sv|-"
  "fragment_tests|raster/fragment_tests.sv|-"
  "blend_logic_op|raster/blend_logic_op.sv|-"
  "texel_address|raster/texel_address.sv|-"
  "texture_env|raster/texture_env.sv|-"
  "fog_unit|raster/fog_unit.sv|-"
  "lod_unit|raster/lod_unit.sv|-"
  "texture_combiner|raster/texture_combiner.sv|-"
  "cu_datapath|array/cu_datapath.sv|-"
)

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

PKG="$LOG_DIR/fixed_function_pkg.sv"
if ! cmake -DDEF="$ROOT/contract/common/fixed_function.def" -DOUT="$PKG" -P "$ROOT/cmake/fixed_function_pkg.cmake"; then
  echo "synth_report: cannot generate fixed_function_pkg.sv" >&2
  exit 1
fi
AP_PKG="$LOG_DIR/ap_isa_pkg.sv"
if ! cmake -DISA_DIR="$ROOT/tlm/array/isa" -DOUT="$AP_PKG" -P "$ROOT/cmake/ap_isa_pkg.cmake"; then
  echo "synth_report: cannot generate ap_isa_pkg.sv" >&2
  exit 1
fi

FOG_PKG="$LOG_DIR/fog_table_pkg.sv"
if ! cmake -DDEF="$ROOT/contract/common/fog_exp2_table.def" -DOUT="$FOG_PKG" -P "$ROOT/cmake/fog_table_pkg.cmake"; then
  echo "synth_report: cannot generate fog_table_pkg.sv" >&2
  exit 1
fi

status=0
printf '%-20s %8s %8s %6s  %s\n' "unit" "cells" "cmos4" "flops" "paper (Table IV)"
cmos4_cmds=""
if [[ $CMOS4 -eq 1 ]]; then
  cmos4_cmds="; abc -g cmos4; stat"
fi
for entry in "${UNITS[@]}"; do
  IFS='|' read -r top sources paper <<<"$entry"
  if [[ $# -gt 0 && ! " $* " =~ " $top " ]]; then
    continue
  fi
  read_cmds="read_verilog -sv $PKG; read_verilog -sv $AP_PKG; read_verilog -sv $FOG_PKG; "
  for src in $sources; do
    read_cmds+="read_verilog -sv $RTL_DIR/$src; "
  done
  log="$LOG_DIR/$top.log"
  if ! "$YOSYS" -q -l "$log" -p "${read_cmds}synth -top $top; stat${cmos4_cmds}" >/dev/null 2>&1; then
    printf '%-20s %8s %8s %6s  %s\n' "$top" "FAILED" "-" "-" "see: $YOSYS -p '${read_cmds}synth -top $top'"
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
  if [[ "$paper" == "-" ]]; then
    paper_text="-"
  else
    paper_text="$paper standard cells"
  fi
  printf '%-20s %8s %8s %6s  %s\n' "$top" "$cells" "$cmos_cells" "$flops" "$paper_text"
done
exit $status
