"""soc_sim --vcd and --fst in one run write the same signals: the FST,
read back by GTKWave's fst2vcd, has every variable of the VCD (by its full
scope path) with the same value changes at the same times.

Usage: check_fst_matches_vcd.py SOC_SIM FST2VCD WORK_DIR"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path


def read_vcd(text: str) -> dict[str, list[tuple[int, str]]]:
    """Every variable's changes by its scope path ("SystemC.soc.array.busy",
    a vector's range left out): (time, value), a vector's bits without
    leading zeros, a real's value as a float's text."""
    tokens = text.split()
    names: dict[str, list[str]] = {}
    scope: list[str] = []
    changes: dict[str, list[tuple[int, str]]] = {}
    time = 0
    i = 0
    while tokens[i] != "$enddefinitions":
        if tokens[i] == "$scope":
            scope.append(tokens[i + 2])
        elif tokens[i] == "$upscope":
            scope.pop()
        elif tokens[i] == "$var":
            ident, name = tokens[i + 3], tokens[i + 4]
            names.setdefault(ident, []).append(".".join([*scope, name]))
        i += 1
    for name_list in names.values():
        for name in name_list:
            changes[name] = []

    def change(ident: str, value: str) -> None:
        for name in names[ident]:
            changes[name].append((time, value))

    i += 2  # $enddefinitions $end
    while i < len(tokens):
        token = tokens[i]
        if token[0] == "#":
            time = int(token[1:])
        elif token == "$comment":
            while tokens[i] != "$end":
                i += 1
        elif token[0] == "$":
            pass
        elif token[0] in "bB":
            change(tokens[i + 1], token[1:].lstrip("0") or "0")
            i += 1
        elif token[0] in "rR":
            change(tokens[i + 1], repr(float(token[1:])))
            i += 1
        else:
            change(token[1:], token[0])
        i += 1
    return changes


def main() -> int:
    soc_sim, fst2vcd, work = sys.argv[1], sys.argv[2], Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    run = [soc_sim, "--quiet", "--frames", "2", "--set", "display.dma=true", "--out", str(work)]
    subprocess.run([*run, "--vcd", str(work / "trace.vcd"), "--fst", str(work / "trace.fst")], check=True)
    back = subprocess.run([fst2vcd, str(work / "trace.fst")], check=True, capture_output=True, text=True).stdout
    vcd = read_vcd((work / "trace.vcd").read_text())
    fst = read_vcd(back)
    problems = []
    if sorted(vcd) != sorted(fst):
        problems.append(f"variables only in the VCD: {sorted(set(vcd) - set(fst))}")
        problems.append(f"variables only in the FST: {sorted(set(fst) - set(vcd))}")
    for name in sorted(set(vcd) & set(fst)):
        if vcd[name] != fst[name]:
            first = next(
                (k for k, (a, b) in enumerate(zip(vcd[name], fst[name])) if a != b), min(len(vcd[name]), len(fst[name]))
            )
            problems.append(
                f"{name}: {len(vcd[name])} changes in the VCD, {len(fst[name])} in the FST; "
                f"change {first} differs: VCD {vcd[name][first : first + 1]}, FST {fst[name][first : first + 1]}"
            )
    changes = sum(len(c) for c in vcd.values())
    if changes < 100:
        problems.append(f"the VCD holds only {changes} value changes: too short a run to compare")
    for problem in problems:
        print("FAIL:", problem)
    if problems:
        return 1
    print(
        f"{len(vcd)} variables, {changes} value changes, the same in both; "
        f"VCD {(work / 'trace.vcd').stat().st_size} bytes, FST {(work / 'trace.fst').stat().st_size} bytes"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
