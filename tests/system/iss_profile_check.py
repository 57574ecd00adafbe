#!/usr/bin/python3
"""Checks that a back end's code on the ARM922T needs no double precision and no 64-bit division.

Runs soc_sim with the driver cross-compiled for the ARM922T on the ISS
(host.model=iss) on one scene of one back end and reads stats.json's
`stats.host.iss.profile`: a flat profile, one row per function of the
program's symbol table, the functions with the most cycles first, at most
40 of them (tools/soc_sim/launch/iss_launcher.cpp, PROFILE_ROWS). The back end's hot
paths are 32-bit integer fixed point, as an ARM922T driver's are: neither
double-precision arithmetic (the soft-float __aeabi_d* / __*df* helpers,
libm's double functions) nor 64-bit division (__aeabi_uldivmod,
__udivmoddi4, ...).

A flat profile cannot say who called a helper (on the teapot the array
back ends once spent 20.8 % and 5.8 % of the ISS's cycles in
double-precision helpers outside their drawing functions: their timing
scopes read the clock as a double). So the check attributes through the program itself: from the ISS image (--elf,
disassembled with --objdump) it follows every direct branch (BL and tail
B) from the back end's drawing functions (BACKENDS[..]["roots"]: its
rasterizer, its renderer's draw and clear, its memory interface; not its
constructors) and fails when any forbidden helper is reachable. The
profile then shows that the run exercised those functions (each of
BACKENDS[..]["ran"] has cycles) and lists the forbidden helpers the rest of
the program still spends cycles in, with their shares, for the record.
When a back end's whole program is clean, its "max_share" bounds every
forbidden helper's share of the profile (an unlisted one holds at most the
last listed row's share, which must then be below the bound too); None
leaves the profile's helpers to the report.

Table-driven: another back end is an entry of BACKENDS and a ctest
(tests/system/CMakeLists.txt, iss_profile_<backend>).

    tests/system/iss_profile_check.py --soc-sim build/default/bin/soc_sim \
        --elf build/default/bin/arm922t/tessera_apps.elf --objdump arm-none-eabi-objdump --backend arm --out out/p

Exit status: 0 when the rules hold, 1 when one does not or a run fails,
2 for a bad command line.
"""

import argparse
import json
import pathlib
import re
import subprocess
import sys

# The bound for a back end whose whole program is free of forbidden helpers
# (arm and raster since the GL geometry and the scenes went to single
# precision: 0.000 % listed, the 40th row at 0.25 %): 1 % of the ISS's
# cycles, far below what double precision in the geometry held (32.7 % on
# the teapot on arm), and far enough above the last listed row that the
# profile can show it.
CLEAN_MAX_SHARE = 0.01

# Per back end: the scene it runs and its frames, extra soc_sim settings,
# the functions (demangled names, regular expressions) whose direct callees
# may reach no forbidden helper, the functions that must show cycles in the
# profile, and the largest share of the ISS's cycles one forbidden helper
# may hold anywhere in the program (None: reported only).
BACKENDS = {
    "arm": {
        "scene": "teapot",
        "frames": 1,
        "set": [],
        "roots": [
            r"^tessera::arm::ArmRasterizer::(draw|draw_triangle|shade_span|write_color_run|fetch_texel|clear|"
            r"read_pixels)\(",
            r"^tessera::arm::ArmRenderer::(draw|clear|read_pixels)\(",
            r"^tessera::arm::HostPixelMemory::(load|store|compute)\(",
            r"^tessera::arm::\(anonymous namespace\)::",
        ],
        "ran": [r"^tessera::arm::ArmRasterizer::shade_span\(", r"^tessera::arm::ArmRasterizer::draw_triangle\("],
        "max_share": CLEAN_MAX_SHARE,
    },
    # The array back ends: the triangle set-up, the per-CU records and their
    # packing, the host's spans, depth test and per-pixel writes, the
    # read-back's texturing. Not the renderers' draw and flush themselves:
    # once a frame they publish their figures (the host time in
    # nanoseconds, formatted counters), which may use double. Their
    # TimedScopes read the host's clock in integer cycles (HostApi::
    # now_cycles), so the whole program is bounded like arm's.
    "ap-tile": {
        "scene": "teapot",
        "frames": 1,
        "set": [],
        "roots": [
            r"^tessera::ap_tile::TriangleSetup::",
            r"^tessera::ap_tile::encode_record\(",
            r"^tessera::ap_tile::TileBins::",
            r"^tessera::ap_tile::ApTileRenderer::(write_group|shade_pixel)\(",
        ],
        "ran": [
            r"^tessera::ap_tile::TriangleSetup::TriangleSetup\(",
            r"^tessera::ap_tile::TriangleSetup::edge_at\(",
            r"^tessera::ap_tile::ApTileRenderer::write_group\(",
        ],
        "max_share": CLEAN_MAX_SHARE,
    },
    "ap-pixel": {
        "scene": "teapot",
        "frames": 1,
        "set": [],
        "roots": [
            r"^tessera::ap_pixel::PixelTriangle::",
            r"^tessera::ap_pixel::ApPixelRenderer::(write_pixel|write_shaded)\(",
        ],
        "ran": [
            r"^tessera::ap_pixel::PixelTriangle::PixelTriangle\(",
            r"^tessera::ap_pixel::PixelTriangle::depth16\(",
            r"^tessera::ap_pixel::PixelTriangle::span\(",
        ],
        "max_share": CLEAN_MAX_SHARE,
    },
    # The raster driver's per-triangle path: the vertex records, the fog
    # argument and the binning (not flush, once a frame: its arena comes
    # from the GL's allocator and its errors are formatted by snprintf).
    "raster": {
        "scene": "teapot",
        "frames": 1,
        "set": [],
        "roots": [
            r"^tessera::raster_backend::RasterRenderer::draw\(",
            r"^tessera::raster_backend::\(anonymous namespace\)::encode_",
        ],
        "ran": [r"^tessera::raster_backend::RasterRenderer::draw\("],
        "max_share": CLEAN_MAX_SHARE,
    },
}

# Double-precision soft float (libgcc's __*df* and the ARM EABI's
# __aeabi_d*, conversions to and from double), libm's double functions, and
# 64-bit division.
FORBIDDEN = [
    (re.compile(r"^__aeabi_(d\w+|cd\w+|[il]2d|ul2d|ui2d|f2d|l2d)$"), "double-precision soft float"),
    (re.compile(r"^__\w*df\d?$"), "double-precision soft float"),
    (
        re.compile(
            r"^(__ieee754_)?(floor|ceil|round|lround|llround|trunc|sqrt|exp|exp2|log|log2|pow|fabs|fmod|modf|"
            r"ldexp|frexp|sin|cos|tan|atan|atan2)$"
        ),
        "double-precision libm",
    ),
    (re.compile(r"^__aeabi_u?ldivmod$"), "64-bit division"),
    (re.compile(r"^__(u?divmoddi4|u?divdi3|u?moddi3)$"), "64-bit division"),
    (re.compile(r"^__gnu_u?ldivmod_helper$"), "64-bit division"),
]


def forbidden_kind(function):
    for pattern, kind in FORBIDDEN:
        if pattern.match(function):
            return kind
    return None


FUNCTION = re.compile(r"^([0-9a-f]+) <(.+)>:$")
BRANCH = re.compile(r"^\s+[0-9a-f]+:\s+b[a-z.]*\s+[0-9a-f]+ <(.+)>\s*$")
OFFSET = re.compile(r"\+0x[0-9a-f]+$")


def call_graph(objdump, elf):
    """The direct branches (BL, BLX to a label, tail B) between the ELF's functions."""
    result = subprocess.run([objdump, "-d", "-C", "--no-show-raw-insn", str(elf)], capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{objdump} -d {elf} exited with {result.returncode}: {result.stderr.strip()}")
    calls, current = {}, None
    for line in result.stdout.splitlines():
        match = FUNCTION.match(line)
        if match:
            current = match.group(2)
            calls.setdefault(current, set())
            continue
        match = BRANCH.match(line)
        if match and current is not None and not OFFSET.search(match.group(1)) and match.group(1) != current:
            calls[current].add(match.group(1))
    return calls


def reachable_helpers(calls, roots):
    """The forbidden helpers reachable from the functions matching `roots`, each with a chain of callers."""
    patterns = [re.compile(root) for root in roots]
    starts = [f for f in calls if any(p.match(f) for p in patterns)]
    parent = {f: None for f in starts}
    stack = list(starts)
    while stack:
        function = stack.pop()
        for callee in calls.get(function, ()):
            if callee not in parent:
                parent[callee] = function
                stack.append(callee)
    found = []
    for function in parent:
        kind = forbidden_kind(function)
        if kind is None:
            continue
        chain, caller = [function], parent[function]
        while caller is not None:
            chain.append(caller)
            caller = parent[caller]
        found.append((function, kind, chain))
    return starts, found


def run(soc_sim, backend, settings, out):
    command = [
        soc_sim,
        "--app",
        settings["scene"],
        "--backend",
        backend,
        "--frames",
        str(settings["frames"]),
        "--no-frames",
        "--quiet",
        "--force",
        "--out",
        str(out),
        "--set",
        "host.model=iss",
        "--iss-profile",
    ]
    for setting in settings["set"]:
        command += ["--set", setting]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} exited with {result.returncode}: {result.stderr.strip()}")
    return json.loads((out / "stats.json").read_text())["stats"]["host"]["iss"]


def check_profile(iss, settings):
    """Returns (failures, lines) of the profile's rules and report."""
    rows = iss["profile"]
    failures, lines = [], []
    if not rows:
        return ["the profile has no rows"], lines
    for ran in settings["ran"]:
        pattern = re.compile(ran)
        cycles = sum(row["cycles"] for row in rows if pattern.match(row["function"]))
        if cycles <= 0:
            failures.append(f"no function matching {ran} has cycles in the profile: the run did not draw")
        else:
            lines.append(f"{ran}: {cycles:.0f} cycles")
    max_share = settings["max_share"]
    total = 0.0
    for row in rows:
        kind = forbidden_kind(row["function"])
        if kind is None:
            continue
        total += row["share"]
        line = f"{row['function']} ({kind}): {100 * row['share']:.3f} % of the ISS's cycles"
        lines.append("elsewhere in the program: " + line)
        if max_share is not None and row["share"] > max_share:
            failures.append(line + f" > {100 * max_share:.3f} %")
    listed, last = len(rows), rows[-1]["share"]
    lines.append(
        f"forbidden helpers listed: {100 * total:.3f} % of the ISS's cycles; {listed} of "
        f"{iss.get('functions_profiled', listed)} functions listed, the last at {100 * last:.3f} %"
    )
    if max_share is not None and iss.get("functions_profiled", listed) > listed and last > max_share:
        failures.append(
            f"an unlisted helper may hold up to {100 * last:.3f} % (the last listed row) "
            f"> {100 * max_share:.3f} %: the profile cannot show the rule"
        )
    return failures, lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--soc-sim", required=True)
    parser.add_argument("--elf", required=True, help="the ISS image soc_sim runs (bin/arm922t/tessera_apps.elf)")
    parser.add_argument("--objdump", default="arm-none-eabi-objdump")
    parser.add_argument("--backend", required=True, choices=sorted(BACKENDS))
    parser.add_argument("--out", required=True, help="folder for soc_sim's statistics")
    args = parser.parse_args()
    settings = BACKENDS[args.backend]
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    try:
        calls = call_graph(args.objdump, args.elf)
        iss = run(args.soc_sim, args.backend, settings, out)
    except (RuntimeError, OSError, KeyError, json.JSONDecodeError) as error:
        print(f"iss_profile_check: {error}", file=sys.stderr)
        return 1
    failures = []
    starts, found = reachable_helpers(calls, settings["roots"])
    print(f"{args.backend} on {settings['scene']} ({settings['frames']} frame(s), host.model=iss):")
    print(f"  {len(starts)} drawing functions followed")
    if not starts:
        failures.append("no function of the image matches the back end's roots")
    for function, kind, chain in found:
        failures.append(f"{function} ({kind}) is reachable from the back end: " + " <- ".join(chain))
    profile_failures, lines = check_profile(iss, settings)
    failures += profile_failures
    for line in lines:
        print("  " + line)
    for failure in failures:
        print("FAIL: " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
