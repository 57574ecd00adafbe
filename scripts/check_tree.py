#!/usr/bin/env python3
"""check_tree.py: the folders are what docs/architecture.md says, and tests/ mirrors the code.

Two checks, over the folders that hold files git tracks:

1. The mirror: every folder of tlm/ that holds sources has its test folder
   at the same path under tests/ (tlm/raster/core -> tests/raster/core),
   and every folder of rtl_models/ under tests/rtl_models/
   (rtl_models/raster -> tests/rtl_models/raster), so a block sits at the
   same path in the three trees (STYLE.md, "The folders show the
   architecture"). A folder may be left out only through NO_TESTS below,
   with the reason.
2. The listing: the source tree in docs/architecture.md (between the
   source-tree markers) names every folder down to LISTED_DEPTH levels,
   except those under UNLISTED (data, vendored headers, and tests/'s
   mirror folders, which rule 1 describes), and names no folder that does
   not exist.

Exits 1 naming each missing test folder, each folder the listing misses
and each listed folder that does not exist.
"""

import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
SOURCE_SUFFIXES = {".h", ".hpp", ".cpp", ".c", ".def", ".sv", ".inc"}
MIRRORS = {"tlm": "tests", "rtl_models": "tests/rtl_models"}
# Code folders without a test folder of their own, and why.
NO_TESTS = {
    "tlm/array/datapath": "the CU's ALU: tested through tests/array/core (test_cu_array) and bit for bit "
    "against its Verilog twin (tests/rtl_models/array)",
}
LISTED_DEPTH = 3
# Folders (and everything under them) the listing need not name, and why.
UNLISTED = {
    "tests/": "mirrors tlm/ and rtl_models/ (rule 1); the listing names tests/'s own folders at depth 2",
    "fuzz/corpus/": "seed inputs, one folder per fuzzer",
    "docs/images/": "pictures the docs show",
    "docs/spec/": "the specification, restated",
    "sw_driver/include/": "the Khronos headers and the SDK's own, as installed",
    "python/tessera_sweep/templates/": "the HTML report's template",
    "configs/": "configuration files; configs/README.md lists them",
    "examples/": "one folder per example application; examples/README.md lists them",
}
BEGIN, END = "<!-- source-tree:begin -->", "<!-- source-tree:end -->"


def tracked_folders() -> dict:
    """Every folder holding tracked files, with the files' suffixes."""
    listing = subprocess.run(["git", "ls-files"], cwd=ROOT, check=True, capture_output=True, text=True).stdout
    folders: dict = {}
    for name in listing.splitlines():
        path = pathlib.PurePosixPath(name)
        for parent in list(path.parents)[:-1]:
            folders.setdefault(parent.as_posix(), set())
        if len(path.parts) > 1:
            folders[path.parent.as_posix()].add(path.suffix)
    return folders


def mirror_problems(folders: dict) -> list:
    problems = []
    for folder, suffixes in sorted(folders.items()):
        top = folder.split("/", 1)[0]
        if top not in MIRRORS or not suffixes & SOURCE_SUFFIXES or folder in NO_TESTS:
            continue
        rest = folder.split("/", 1)[1] if "/" in folder else ""
        expected = f"{MIRRORS[top]}/{rest}".rstrip("/")
        if folder == top:
            continue
        if expected not in folders:
            problems.append(f"{folder}/ has no test folder {expected}/")
    return problems


def listed_folders(text: str) -> set:
    if BEGIN not in text or END not in text:
        raise SystemExit(f"check_tree: docs/architecture.md has no {BEGIN} ... {END} block")
    block = text[text.index(BEGIN) + len(BEGIN) : text.index(END)]
    return {match.group(1).rstrip("/") for match in re.finditer(r"^\s*([\w.+-]+(?:/[\w.+-]+)*/)\s", block, re.M)}


def needs_listing(folder: str, folders: dict) -> bool:
    """Down to LISTED_DEPTH, but not under UNLISTED; of tests/, its own folders
    at depth 2 that mirror nothing (tests/system, tests/lint, ...)."""
    depth = folder.count("/") + 1
    if folder == "." or folder.startswith(".") or depth > LISTED_DEPTH:
        return False
    if folder == "tests" or (folder.startswith("tests/") and depth == 2):
        return folder == "tests" or folder.split("/")[1] not in mirror_names(folders)
    return not any((folder + "/").startswith(prefix) for prefix in UNLISTED)


def mirror_names(folders: dict) -> set:
    """tests/'s folders that mirror a tlm/ folder, and rtl_models (rule 1 describes them)."""
    names = {folder.split("/")[1] for folder in folders if folder.startswith("tlm/") and folder.count("/") == 1}
    return names | {"rtl_models"}


def listing_problems(folders: dict, listed: set) -> list:
    problems = [
        f"{folder}/ is not in docs/architecture.md's source tree"
        for folder in sorted(folders)
        if needs_listing(folder, folders) and folder not in listed
    ]
    for folder in sorted(listed):
        if folder not in folders:
            problems.append(f"docs/architecture.md's source tree names {folder}/, which holds no tracked file")
    return problems


def main() -> int:
    folders = tracked_folders()
    problems = mirror_problems(folders)
    problems += listing_problems(folders, listed_folders((ROOT / "docs/architecture.md").read_text()))
    for problem in problems:
        print(f"check_tree: {problem}", file=sys.stderr)
    print(f"check_tree: {len(folders)} folders; {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
