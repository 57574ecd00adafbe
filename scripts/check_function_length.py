#!/usr/bin/env python3
"""check_function_length.py: no function over 150 lines without a reason beside it.

Measures every C and C++ function in the project's own code folders with
lizard (its length: from the line of the signature to the closing brace)
and fails for each one longer than LIMIT lines that carries no reason: a
comment holding "Longer than 150 lines:" on one of the REASON_WINDOW lines
above the function's first line, saying why the length is the clearer
shape (one decoding table, one switch over an instruction set). Exits 1
listing each such function with its file, line and length.

  check_function_length.py [--limit 150] [FOLDER ...]   (default: FOLDERS)

Needs lizard (build/venv has it: scripts/setup.sh).
"""

import argparse
import pathlib
import sys

import lizard

ROOT = pathlib.Path(__file__).resolve().parent.parent
FOLDERS = ["tools", "tlm", "sw_driver", "testbench", "bench", "fuzz"]
SUFFIXES = {".c", ".cc", ".cpp", ".h", ".hpp"}
LIMIT = 150
REASON = "Longer than 150 lines:"
REASON_WINDOW = 6


def long_functions(folders: list, limit: int) -> list:
    found = []
    for folder in folders:
        base = ROOT / folder
        if not base.is_dir():
            continue
        for path in sorted(p for p in base.rglob("*") if p.suffix in SUFFIXES and p.is_file()):
            analysis = lizard.analyze_file(str(path))
            lines = None
            for function in analysis.function_list:
                if function.length <= limit:
                    continue
                lines = lines or path.read_text(errors="replace").splitlines()
                above = lines[max(0, function.start_line - 1 - REASON_WINDOW) : function.start_line - 1]
                reasoned = any(REASON in line for line in above)
                found.append(
                    (path.relative_to(ROOT).as_posix(), function.start_line, function.name, function.length, reasoned)
                )
    return found


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--limit", type=int, default=LIMIT)
    parser.add_argument("folders", nargs="*", default=FOLDERS)
    args = parser.parse_args()
    found = long_functions(args.folders, args.limit)
    bad = [f for f in found if not f[4]]
    for path, line, name, length, reasoned in found:
        status = "reason given" if reasoned else f'no "{REASON}" comment above it'
        print(f"{path}:{line}: {name}: {length} lines ({status})", file=sys.stderr if not reasoned else sys.stdout)
    print(
        f"check_function_length: {len(found)} functions over {args.limit} lines in {', '.join(args.folders)}; "
        f"{len(bad)} without a reason"
    )
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
