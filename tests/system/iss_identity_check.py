#!/usr/bin/env python3
"""Checks that the ISS's speed-ups leave every simulated result as it was.

Runs soc_sim with host.model=iss on each case twice, with the ISS's
per-function profile (--iss-profile) and without it (its accounting off),
and requires the two runs' outputs to be the same byte for byte: every
frame, the console output, and stats.json but for the profile's own keys
(host.iss.profile, host.iss.functions_profiled) and the run's command line.
Where the profile lists every function (a small program), its rows must
add up to the program's instructions and core cycles exactly, and to its
stall cycles but for rounding.
With --reference SOC_SIM (a soc_sim built before a change, beside its own
arm922t/tessera_apps.elf) each case also runs there with the profile and
must give the profiled run's outputs exactly, the profile included: the
before-and-after check of a change to the ISS, its timing layer or its
launcher.

    tests/system/iss_identity_check.py --soc-sim build/default/bin/soc_sim --out /tmp/iss_identity
    tests/system/iss_identity_check.py --soc-sim build/default/bin/soc_sim --reference OLD/bin/soc_sim \\
        --out /tmp/iss_identity --case teapot:arm:1 --case teapot:ap-tile:1 --case study_shading:arm:1

A case is APP:BACKEND:FRAMES (APP a built-in application or an ARM
executable). Exit status: 0 when every output matches, 1 when one
differs or a run fails, 2 for a bad command line.
"""

import argparse
import json
import pathlib
import subprocess
import sys

DEFAULT_CASES = ["triangle:arm:1", "cubes:ap-tile:1"]
# Relative error allowed between the rows' stall cycles, each summed access
# by access, and the program's, summed in whole clock ticks.
STALL_ROUNDING = 1e-9
# Keys of stats.json that name the run rather than simulate it.
RUN_KEYS = ("command_line", "commit")
PROFILE_KEYS = ("profile", "functions_profiled")


def parse_case(text):
    parts = text.split(":")
    if len(parts) != 3 or not parts[0] or not parts[1] or not parts[2].isdigit() or int(parts[2]) < 1:
        raise argparse.ArgumentTypeError(f"'{text}': a case is APP:BACKEND:FRAMES, FRAMES a positive integer")
    return parts[0], parts[1], int(parts[2])


def run(soc_sim, case, out, flags):
    app, backend, frames = case
    command = [
        str(soc_sim),
        "--app",
        app,
        "--backend",
        backend,
        "--frames",
        str(frames),
        "--quiet",
        "--force",
        "--out",
        str(out),
        "--set",
        "host.model=iss",
    ] + flags
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} exited with {result.returncode}: {result.stderr.strip()}")
    stats = json.loads((out / "stats.json").read_text())
    for key in RUN_KEYS:
        stats.pop(key, None)
    files = {p.name: p.read_bytes() for p in sorted(out.iterdir()) if p.is_file() and p.name != "stats.json"}
    return {"stdout": result.stdout, "stderr": result.stderr, "stats": stats, "files": files}


def without_profile(outputs):
    stats = json.loads(json.dumps(outputs["stats"]))
    iss = stats.get("stats", {}).get("host", {}).get("iss")
    if iss is None:
        raise RuntimeError("stats.json has no stats.host.iss: the run did not use the ISS")
    for key in PROFILE_KEYS:
        iss.pop(key, None)
    return dict(outputs, stats=stats)


def profile_sums(outputs):
    """What is wrong with the profile's sums: they must be the program's."""
    iss = outputs["stats"]["stats"]["host"]["iss"]
    rows = iss.get("profile")
    if rows is None:
        return ["stats.json has no host.iss.profile with --iss-profile"]
    if iss["functions_profiled"] != len(rows):
        return []  # only the top rows are listed: their sums are not the program's
    found = []
    for key in ("instructions", "core_cycles"):
        total = sum(row[key] for row in rows)
        if total != iss[key]:
            found.append(f"the profile's {key} add up to {total}, the program's are {iss[key]}")
    stalls = sum(row["stall_cycles"] for row in rows)
    if abs(stalls - iss["stall_cycles"]) > STALL_ROUNDING * max(1.0, iss["stall_cycles"]):
        found.append(f"the profile's stall cycles add up to {stalls}, the program's are {iss['stall_cycles']}")
    return found


def differences(a, b, names):
    found = []
    for key in ("stdout", "stderr"):
        if a[key] != b[key]:
            found.append(f"{key} differs between {names[0]} and {names[1]}")
    if a["stats"] != b["stats"]:
        found.append(
            f"stats.json differs between {names[0]} and {names[1]}: {first_difference(a['stats'], b['stats'])}"
        )
    if sorted(a["files"]) != sorted(b["files"]):
        found.append(f"the outputs differ: {sorted(a['files'])} against {sorted(b['files'])}")
    for name in sorted(set(a["files"]) & set(b["files"])):
        if a["files"][name] != b["files"][name]:
            found.append(f"{name} differs between {names[0]} and {names[1]}")
    return found


def first_difference(a, b, path="stats.json"):
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                return f"{path}.{key} only in one"
            if a[key] != b[key]:
                return first_difference(a[key], b[key], f"{path}.{key}")
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            if x != y:
                return first_difference(x, y, f"{path}[{i}]")
    return f"{path}: {json.dumps(a)[:200]} against {json.dumps(b)[:200]}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--soc-sim", required=True, type=pathlib.Path)
    parser.add_argument("--reference", type=pathlib.Path, help="a soc_sim from before the change, to compare with")
    parser.add_argument(
        "--reference-flag",
        action="append",
        default=[],
        help="a flag for the reference's runs (default: --iss-profile; give '' for a soc_sim from "
        "before it, which always listed the profile)",
    )
    parser.add_argument("--out", required=True, type=pathlib.Path, help="folder for the runs' outputs")
    parser.add_argument("--case", action="append", type=parse_case, help="APP:BACKEND:FRAMES (repeatable)")
    args = parser.parse_args()
    for path in [args.soc_sim] + ([args.reference] if args.reference else []):
        if not path.is_file():
            parser.error(f"no soc_sim at {path}")
    cases = args.case or [parse_case(text) for text in DEFAULT_CASES]
    failures = []
    for case in cases:
        name = ":".join(str(part) for part in case)
        folder = args.out / f"{pathlib.Path(case[0]).name}_{case[1]}_{case[2]}"
        try:
            profiled = run(args.soc_sim, case, folder / "profiled", ["--iss-profile"])
            plain = run(args.soc_sim, case, folder / "plain", [])
            found = differences(without_profile(profiled), plain, ("--iss-profile", "without"))
            found += profile_sums(profiled)
            if args.reference:
                flags = [flag for flag in args.reference_flag if flag] if args.reference_flag else ["--iss-profile"]
                reference = run(args.reference, case, folder / "reference", flags)
                found += differences(profiled, reference, ("this soc_sim", "the reference"))
        except RuntimeError as error:
            found = [str(error)]
        iss = {} if found else plain["stats"]["stats"]["host"]["iss"]
        status = "same" if not found else "DIFFERENT"
        print(
            f"{name}: {status}"
            + (f" ({iss['instructions']} instructions, {iss['core_cycles']} core cycles)" if iss else "")
        )
        failures += [f"{name}: {text}" for text in found]
    for text in failures:
        print(f"iss_identity_check: {text}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
