#!/usr/bin/env python3
"""Checks that a program exports every entry point tessera's headers declare.

Applications run with `soc_sim --app` leave their GL ES and EGL calls
undefined and resolve them in soc_sim when it loads them, so each function
that sw_driver/include's GLES/gl.h, GLES/glext.h (the implemented
extensions' entry points) and EGL/egl.h declare must be a defined
dynamic symbol of soc_sim; one that is missing fails only when an
application that calls it is loaded.
"""

import argparse
import os
import shutil
import subprocess
import sys

from check_headers import parse


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ours", required=True, help="root of tessera's headers (sw_driver/include)")
    parser.add_argument("--program", required=True, help="the program that loads applications (soc_sim)")
    args = parser.parse_args()

    nm = shutil.which("nm")
    if not nm:
        print("SKIP: nm (binutils) is not installed")
        return 77
    if not os.path.isfile(args.program):
        print(f"FAIL: {args.program} does not exist: build it first")
        return 1
    listing = subprocess.run([nm, "-D", "--defined-only", args.program], capture_output=True, text=True)
    if listing.returncode != 0:
        print(f"FAIL: nm could not read {args.program}: {listing.stderr.strip()}")
        return 1
    exported = {line.split()[-1] for line in listing.stdout.splitlines() if line.strip()}

    missing = []
    declared = 0
    # GLES/glext.h includes GLES/gl.h, so its functions are both headers'.
    for header in ("GLES/glext.h", "EGL/egl.h"):
        functions = parse(os.path.join(args.ours, header), args.ours).functions
        declared += len(functions)
        missing += [f"{name} ({header})" for name in sorted(functions) if name not in exported]
    for name in missing:
        print(f"FAIL: {name} is declared but {os.path.basename(args.program)} does not export it")
    print(f"{declared} entry points declared, {declared - len(missing)} exported, {len(missing)} missing")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
