#!/usr/bin/env bash
# Regenerates the ISA table in tlm/array/README.md from the .def tables
# (ap_asm --isa-table), between the two marker lines.
set -euo pipefail
cd "$(dirname "$0")/.."
asm=${1:-build/default/bin/ap_asm}
table=$("$asm" --isa-table)
python3 - "$table" <<'PY'
import sys
path = "tlm/array/README.md"
begin, end = "<!-- isa-table begin -->", "<!-- isa-table end -->"
text = open(path).read()
head, rest = text.split(begin, 1)
_, tail = rest.split(end, 1)
open(path, "w").write(head + begin + "\n" + sys.argv[1] + "\n" + end + tail)
PY
echo "tlm/array/README.md ISA table updated"
