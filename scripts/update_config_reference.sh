#!/usr/bin/env bash
# Regenerates the configuration reference in README.md from the parameter
# table (soc_sim --config-reference), between the two marker lines.
set -euo pipefail
cd "$(dirname "$0")/.."
sim=${1:-build/default/bin/soc_sim}
table=$("$sim" --config-reference)
python3 - "$table" <<'PY'
import sys
begin, end = "<!-- config-reference:begin -->", "<!-- config-reference:end -->"
text = open("README.md").read()
head, rest = text.split(begin, 1)
_, tail = rest.split(end, 1)
open("README.md", "w").write(head + begin + "\n" + sys.argv[1] + "\n" + end + tail)
PY
echo "README.md configuration reference updated"
