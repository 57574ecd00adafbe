#!/usr/bin/env bash
# check_frames_equal.sh NATIVE_DIR ISS_DIR COMMAND...: runs COMMAND (the ISS
# twin of a Mesa comparison, which writes its frames to ISS_DIR), then checks
# that every frame it wrote is byte for byte the frame of the same name the
# host-compiled run wrote to NATIVE_DIR (docs/calibration.md, "The two host
# models"; sw_driver/runtime/README.md), except the frames that
# iss_libm_differences.txt lists for its output folder.
set -uo pipefail
native=$1 iss=$2
shift 2
"$@" || exit $?
compared=0 listed_differences=0
# Frames a libm difference may change, each listed with what differs.
listed=$(dirname "$0")/iss_libm_differences.txt
for frame in "$iss"/frame_*.png; do
  [ -e "$frame" ] || continue
  name=$(basename "$frame")
  if [ ! -e "$native/$name" ]; then
    echo "check_frames_equal: the host-compiled run wrote no $name ($native)" >&2
    exit 1
  fi
  if ! cmp -s "$native/$name" "$frame"; then
    if grep -q "^$(basename "$(dirname "$iss")") $name " "$listed"; then
      echo "check_frames_equal: $name differs, as listed in $(basename "$listed") (libm)"
      listed_differences=$((listed_differences + 1))
      continue
    fi
    echo "check_frames_equal: $name differs between the host-compiled run ($native) and the ISS ($iss)" >&2
    exit 1
  fi
  compared=$((compared + 1))
done
if [ "$compared" -eq 0 ]; then
  echo "check_frames_equal: the ISS run wrote no frame in $iss" >&2
  exit 1
fi
echo "check_frames_equal: $compared frame(s) equal to the host-compiled run's, $listed_differences listed as differing"
