#!/usr/bin/env bash
# Regenerates the configuration reference in docs/configuration.md from the
# parameter table (soc_sim --config-reference), between the two marker lines
# (scripts/update_docs.py regenerates it with the docs' other generated blocks).
set -euo pipefail
cd "$(dirname "$0")/.."
sim=${1:-build/default/bin/soc_sim}
table=$("$sim" --config-reference)
python3 - "$table" <<'PY'
import sys
begin, end = "<!-- config-reference:begin -->", "<!-- config-reference:end -->"
path = "docs/configuration.md"
text = open(path).read()
head, rest = text.split(begin, 1)
_, tail = rest.split(end, 1)
open(path, "w").write(head + begin + "\n" + sys.argv[1] + "\n" + end + tail)
PY
echo "docs/configuration.md configuration reference updated"
