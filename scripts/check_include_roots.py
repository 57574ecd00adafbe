#!/usr/bin/env python3
"""check_include_roots.py: the driver is compiled without tlm/ on its include path.

The software on the host (sw_driver/, native and for the ARM) may include
the software-visible contract (contract/) and its own folders, never a
model's header: contract/README.md, "What the driver takes from outside the
contract". A library that puts tlm/ (or a folder under it) on the include
path of what links it would let a driver source include a model's header
by accident; this check reads the compile commands CMake wrote and fails
naming each driver source compiled with such a root.

Usage: check_include_roots.py COMPILE_COMMANDS.json [...]
(the native build's, and the ARM sub-build's under arm922t/build/).
Exits 1 naming the sources and roots, 2 if a file cannot be read or holds
no driver source (the check would prove nothing).
"""

import json
import pathlib
import shlex
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
DRIVER = ROOT / "sw_driver"
FORBIDDEN = ROOT / "tlm"
INCLUDE_FLAGS = ("-I", "-isystem", "-iquote", "-idirafter")


def include_roots(entry: dict) -> list:
    """The include directories of one compile command, as absolute paths."""
    args = entry["arguments"] if "arguments" in entry else shlex.split(entry["command"])
    directory = pathlib.Path(entry.get("directory", "."))
    roots = []
    i = 0
    while i < len(args):
        arg = args[i]
        for flag in INCLUDE_FLAGS:
            if arg == flag and i + 1 < len(args):
                roots.append(args[i + 1])
                i += 1
                break
            if arg.startswith(flag) and len(arg) > len(flag) and flag == "-I":
                roots.append(arg[len(flag) :])
                break
        i += 1
    return [(directory / root).resolve() for root in roots]


def under(path: pathlib.Path, folder: pathlib.Path) -> bool:
    return path == folder or folder in path.parents


def check(path: pathlib.Path) -> list:
    """Problems of one compile_commands.json: (source, root) pairs."""
    try:
        entries = json.loads(path.read_text())
    except (OSError, ValueError) as error:
        print(f"check_include_roots: cannot read {path}: {error}", file=sys.stderr)
        sys.exit(2)
    driver_sources = 0
    problems = []
    for entry in entries:
        source = (pathlib.Path(entry.get("directory", ".")) / entry["file"]).resolve()
        if not under(source, DRIVER):
            continue
        driver_sources += 1
        for root in include_roots(entry):
            if under(root, FORBIDDEN):
                problems.append((source.relative_to(ROOT), root.relative_to(ROOT)))
    if driver_sources == 0:
        print(f"check_include_roots: {path} compiles no source of sw_driver/", file=sys.stderr)
        sys.exit(2)
    print(f"check_include_roots: {path.name} ({path.parent.name}): {driver_sources} driver sources")
    return problems


def main(argv: list) -> int:
    if not argv:
        print(__doc__, file=sys.stderr)
        return 2
    problems = []
    for name in argv:
        problems += check(pathlib.Path(name))
    for source, root in sorted(set(problems)):
        print(f"check_include_roots: {source} is compiled with the model's folder {root}/ on its include path")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
