#!/usr/bin/env python3
"""Prints the build targets that the tests of a configured build need, one
per line: every program a test runs or names in its arguments that is one
of the build's targets. For building only what a ctest label set needs:

    scripts/test_targets.py BUILD_DIR [ctest options, e.g. -L "unit|tlm"]

The build must be configured (ctest -N reads its test list); nothing needs
to be built yet. Paths are matched by file name against the build's targets
(`cmake --build BUILD_DIR --target help`). ctest leaves out the command of a
test whose program is not built yet; such a test must be named after its
program's target (as tessera_add_test names them), or this fails naming it.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path


def main() -> int:
    if len(sys.argv) < 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    build = Path(sys.argv[1])
    if not (build / "CTestTestfile.cmake").is_file():
        print(f"test_targets: {build} is not a configured build (no CTestTestfile.cmake)", file=sys.stderr)
        return 2
    listing = subprocess.run(
        ["ctest", "--test-dir", str(build), "-N", "--show-only=json-v1", *sys.argv[2:]],
        capture_output=True,
        text=True,
        check=True,
    )
    helps = subprocess.run(
        ["cmake", "--build", str(build), "--target", "help"], capture_output=True, text=True, check=True
    )
    # "... name" lines of the Makefile generator's help
    targets = {line[4:].split()[0] for line in helps.stdout.splitlines() if line.startswith("... ")}
    needed: set[str] = set()
    for test in json.loads(listing.stdout)["tests"]:
        if "command" not in test:
            if test["name"] not in targets:
                print(
                    f"test_targets: test {test['name']} has no program yet and no target of its name", file=sys.stderr
                )
                return 1
            needed.add(test["name"])
            continue
        for word in test["command"]:
            for part in str(word).replace("=", " ").split():
                name = Path(part).name
                if name in targets:
                    needed.add(name)
    if not needed:
        print("test_targets: no test names a target of this build", file=sys.stderr)
        return 1
    print("\n".join(sorted(needed)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
