#!/usr/bin/env python3
"""Runs every command of the README, as typed, in a clean temporary folder
after the quick start's demo, and fails when one exits with a status other
than 0.

    run_readme_commands.py SOURCE_DIR BUILD_DIR

The folder stands for a fresh checkout after the quick start: every
top-level entry of SOURCE_DIR is linked into it except build/ and out/
(scripts/ is copied, so that a script finding the repository from its own
path finds this folder),
build/default is a link to BUILD_DIR (the build the test belongs to) and
build/venv to BUILD_DIR/../venv when that exists. The quick start's demo
runs first, as scripts/quickstart.sh runs it once the build is done
(`build/default/bin/soc_sim --vcd out/trace.vcd`), and the outputs the
README promises (out/frame_0000.png, out/stats.json, out/trace.vcd) must be
there. Then every ```sh block of README.md runs, in order, in that folder,
with bash -e (the first failing line fails the block), except a block
preceded by a line
    <!-- readme_commands: not run (REASON) -->
(the quick start's own two commands, which install packages and build).
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

DEMO = "build/default/bin/soc_sim --vcd out/trace.vcd"
DEMO_OUTPUTS = ["out/frame_0000.png", "out/stats.json", "out/trace.vcd"]
SKIP = re.compile(r"<!-- readme_commands: not run \((.+)\) -->")


def blocks(readme):
    """(first line number, text, reason to skip or None) of each sh block."""
    lines = readme.splitlines()
    result = []
    index = 0
    while index < len(lines):
        if re.match(r"^```(sh|bash|shell)\s*$", lines[index]):
            start = index
            skip = None
            for before in reversed(lines[:start]):
                if before.strip():
                    match = SKIP.search(before)
                    skip = match.group(1) if match else None
                    break
            index += 1
            body = []
            while index < len(lines) and not lines[index].startswith("```"):
                body.append(lines[index])
                index += 1
            result.append((start + 2, "\n".join(body), skip))
        index += 1
    return result


def run(script, folder, label):
    env = dict(os.environ, SYSTEMC_DISABLE_COPYRIGHT_MESSAGE="1")
    env.pop("TERM", None)
    started = time.monotonic()
    result = subprocess.run(
        ["bash", "-e", "-x", "-c", script],
        cwd=folder,
        env=env,
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=600,
    )
    print(f"--- {label}: status {result.returncode}, {time.monotonic() - started:.1f} s")
    if result.returncode != 0:
        print(result.stdout[-4000:])
        print(result.stderr[-4000:])
    return result.returncode == 0


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    source = pathlib.Path(sys.argv[1]).resolve()
    build = pathlib.Path(sys.argv[2]).resolve()
    readme = (source / "README.md").read_text()
    found = blocks(readme)
    to_run = [block for block in found if block[2] is None]
    if not to_run:
        print("README.md has no sh block to run")
        return 1
    failures = 0
    with tempfile.TemporaryDirectory(prefix="tessera-readme-") as name:
        folder = pathlib.Path(name)
        for entry in source.iterdir():
            if entry.name == "scripts":
                # Copied, not linked: a script that finds the repository from
                # its own path (experiment.py's build/default/bin/soc_sim)
                # then finds this folder and the build under test.
                shutil.copytree(entry, folder / entry.name, symlinks=True)
            elif entry.name not in ("build", "out", ".git"):
                (folder / entry.name).symlink_to(entry)
        (folder / "build").mkdir()
        (folder / "build" / "default").symlink_to(build)
        if (build.parent / "venv").is_dir():
            (folder / "build" / "venv").symlink_to(build.parent / "venv")

        if not run(DEMO, folder, f"the quick start's demo: {DEMO}"):
            return 1
        missing = [output for output in DEMO_OUTPUTS if not (folder / output).is_file()]
        if missing:
            print(f"the demo did not write {', '.join(missing)}")
            return 1
        for line, script, skip in found:
            if skip is not None:
                print(f"--- README.md:{line}: not run ({skip})")
                continue
            if not run(script, folder, f"README.md:{line}"):
                failures += 1
    print(f"{len(to_run)} README command blocks run after the demo, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
