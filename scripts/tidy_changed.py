#!/usr/bin/env python3
"""clang-tidy on the translation units a change touches (the test
lint_tidy_changed; the whole tree is the test lint_tidy, in the preset
lint-full: tests/README.md).

    scripts/tidy_changed.py BUILD_DIR [BASE]

A change is every file that differs from BASE (a commit; default: the one
written in tests/lint/tidy_clean_at, where the whole tree was last clean)
in the work tree, committed or not, plus untracked files. A translation unit
of the project's folders is checked when its source changed or when its
dependency file (the compiler's .o.d beside its object) names a changed
header. A unit not built yet has no dependency file: it is checked when it
or a header beside it changed. A change to .clang-tidy checks every unit.

Exits 0 when clang-tidy finds nothing (or nothing changed), 1 when it finds
something, 2 on bad arguments. Needs run-clang-tidy and clang-tidy (Debian's
clang 14, scripts/setup.sh).
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parent.parent
CHECKED_FOLDERS = ("tlm", "sw_driver", "tools", "bench", "tests", "testbench", "rtl_models", "fuzz")
BASE_FILE = SOURCE / "tests" / "lint" / "tidy_clean_at"


def git(*args: str) -> str:
    return subprocess.run(["git", "-C", str(SOURCE), *args], capture_output=True, text=True, check=True).stdout


def changed_files(base: str) -> set[Path]:
    names = git("diff", "--name-only", base).splitlines()
    names += git("ls-files", "--others", "--exclude-standard").splitlines()
    return {(SOURCE / name).resolve() for name in names if name}


def dependencies(directory: Path, output: str) -> set[Path] | None:
    depfile = directory / (output + ".d")
    if not depfile.is_file():
        return None
    text = depfile.read_text(errors="replace").replace("\\\n", " ")
    _, _, deps = text.partition(": ")
    return {(directory / name).resolve() for name in deps.split() if not name.endswith(":")}


def output_of(entry: dict) -> str | None:
    if "output" in entry:
        return entry["output"]
    match = re.search(r"\s-o\s+(\S+)", entry.get("command", ""))
    return match.group(1) if match else None


def main() -> int:
    if len(sys.argv) not in (2, 3):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    build = Path(sys.argv[1]).resolve()
    database = build / "compile_commands.json"
    if not database.is_file():
        print(f"tidy_changed: {build} has no compile_commands.json (configure it first)", file=sys.stderr)
        return 2
    base = sys.argv[2] if len(sys.argv) == 3 else BASE_FILE.read_text().split()[0]
    try:
        git("cat-file", "-e", base + "^{commit}")
    except subprocess.CalledProcessError:
        print(
            f"tidy_changed: {base} is not a commit of this repository (a shallow clone? fetch its history)",
            file=sys.stderr,
        )
        return 2
    changed = changed_files(base)
    everything = (SOURCE / ".clang-tidy").resolve() in changed
    roots = tuple(str(SOURCE / folder) + "/" for folder in CHECKED_FOLDERS)
    units: list[str] = []
    for entry in json.loads(database.read_text()):
        unit = Path(entry["directory"], entry["file"]).resolve()
        if not str(unit).startswith(roots):
            continue
        if everything or unit in changed:
            units.append(str(unit))
            continue
        output = output_of(entry)
        deps = dependencies(Path(entry["directory"]), output) if output else None
        if deps is None:
            deps = {path for path in changed if path.parent == unit.parent}
        if deps & changed:
            units.append(str(unit))
    units = sorted(set(units))
    print(f"tidy_changed: {len(changed)} file(s) changed since {base[:12]}; {len(units)} translation unit(s) to check")
    if not units:
        return 0
    run = shutil.which("run-clang-tidy-14") or shutil.which("run-clang-tidy")
    tidy = shutil.which("clang-tidy-14") or shutil.which("clang-tidy")
    if not run or not tidy:
        print(
            "tidy_changed: run-clang-tidy or clang-tidy is missing (scripts/setup.sh installs clang-tidy)",
            file=sys.stderr,
        )
        return 2
    pattern = "^(" + "|".join(re.escape(unit) for unit in units) + ")$"
    result = subprocess.run([run, "-clang-tidy-binary", tidy, "-p", str(build), "-quiet", "-j", "2", pattern])
    return 0 if result.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
