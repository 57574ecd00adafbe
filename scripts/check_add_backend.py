#!/usr/bin/env python3
"""check_add_backend.py: a renderer back end is one table line and one folder.

Follows docs/how_to_add_a_backend.md for a toy back end in a copy of the
tree, since the real table must not gain a toy row:

1. copies the files git tracks (git ls-files, as they are in the working
   tree) into a temporary folder;
2. in the copy, does what the guide asks for a new back end and nothing
   else: appends the line
     TESSERA_BACKEND(toy, "toy", 16, 0, "a toy back end that only clears")
   to sw_driver/renderers/backends.def (checked first against the columns
   of the TESSERA_BACKEND macro and of the table's other lines), makes the
   folder sw_driver/renderers/toy/ from the templates in
   scripts/check_add_backend/ (CMakeLists.txt, README.md, a gl::Renderer
   that clears, draws nothing and presents, and the four entry points),
   and tells test_gl_api what the toy's buffers hold (section 6); the
   generated documents (section 8) are left stale;
3. configures the copy with the options of the "default" configure preset
   (CMakePresets.json), in the preset's build folder inside the copy, so
   that ccache, which sees paths relative to the source tree, serves every
   unchanged unit from the main build's compiles, and builds soc_sim,
   test_backends, test_gl_api, test_soc_sim_backends and the ARM sub-build
   (tessera_arm922t: the driver, every back end and the applications
   cross-compiled for the ISS);
4. checks that soc_sim --backend toy --app triangle --frames 1 exits 0,
   writes one frame of one colour (the toy draws no triangle) and records
   driver.backend = "toy" and one frame shown in stats.json (as
   test_soc_sim_backends does); that the same with --app fullscreen_rect,
   whose clear colour is magenta, gives a magenta frame (the triangle
   scene's black is also what an untouched frame buffer shows); that
   --help's --backend line and the configuration reference's
   driver.backend row name toy; that an unknown --backend is rejected with
   status 2 and a message listing toy; that the three tests pass in the
   copy (ctest); and that the magenta frame comes out the same on the ISS
   (--set host.model=iss).

  check_add_backend.py [--keep] [--jobs J] [--work-dir DIR] [--no-iss]

--keep leaves the temporary folder and prints where it is: the copy in
repo/ (its build in the preset's folder, the toy's frames in
repo/out_toy_<scene>*/) and the logs configure.log, build.log and
build_iss.log. --work-dir names the folder the temporary one is made in
(default: the system's). --no-iss leaves out the ARM sub-build and the ISS
run. It takes a few minutes on 2 cores when ccache holds the main build's
compiles, nearly all of it the builds (ctest: docs_how_to_add_a_backend,
label slow). Exits 0 when every check passes, 1 naming the first step or
check that failed (a failed configure or build shows the last 40 lines of
its log), 2 for a bad command line.
"""

import argparse
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

import def_table
import png_read

ROOT = pathlib.Path(__file__).resolve().parent.parent
TEMPLATES = ROOT / "scripts" / "check_add_backend"
TOY_FILES = ("CMakeLists.txt", "README.md", "toy_renderer.h", "toy_renderer.cpp", "toy_backend.cpp")
TOY_ID, TOY_NAME = "toy", "toy"
TOY_LINE = f'TESSERA_BACKEND({TOY_ID}, "{TOY_NAME}", 16, 0, "a toy back end that only clears")'
TABLE = "sw_driver/renderers/backends.def"
ENTRY_POINTS = "sw_driver/renderers/backend_entry_points.h"
GUIDE = "docs/how_to_add_a_backend.md"
PRESET = "default"
# The one test that lists what each back end's buffers hold by hand (the guide, section 6).
CAPABILITIES_TEST = "tests/sw_driver/gl/test_gl_api.cpp"
CAPABILITIES_MAP = "const std::map<std::string, gl::RendererCapabilities> stored = {"
TESTS = ("test_backends", "test_gl_api", "test_soc_sim_backends")
TARGETS = ("soc_sim", *TESTS)
# The ARM sub-build: the driver, every back end and the applications for the ISS (host.model=iss).
ISS_TARGET = "tessera_arm922t"
LOG_TAIL = 40
EXIT_USAGE = 2


class CheckFailed(Exception):
    """A step or a check that failed, with the message to print."""


def say(message: str) -> None:
    print(f"check_add_backend: {message}", flush=True)


def tail(path: pathlib.Path, lines: int = LOG_TAIL) -> str:
    text = path.read_text(errors="replace").splitlines() if path.is_file() else []
    return "\n".join(text[-lines:])


def macro_arguments(line: str) -> list:
    """The arguments of a TESSERA_BACKEND(...) line (scripts/def_table.py), [] for another line."""
    return def_table.row(line.strip(), "TESSERA_BACKEND") or []


def macro_parameters(entry_points: str) -> list:
    """The parameters of the TESSERA_BACKEND macro backend_entry_points.h defines."""
    match = re.search(r"#define TESSERA_BACKEND\(([^)]*)\)", entry_points)
    if not match:
        raise CheckFailed(f"{ENTRY_POINTS} defines no TESSERA_BACKEND macro")
    return [name.strip() for name in match.group(1).split(",")]


def tracked_files(root: pathlib.Path) -> list:
    try:
        listing = subprocess.run(["git", "ls-files", "-z"], cwd=root, check=True, capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError) as error:
        raise CheckFailed(f"git ls-files failed in the repository: {error}") from error
    return [name for name in listing.split("\0") if name]


def copy_tree(root: pathlib.Path, copy: pathlib.Path) -> None:
    """The tracked files as they are in the working tree (a deleted one is left out)."""
    names = tracked_files(root)
    copied = 0
    for name in names:
        source, target = root / name, copy / name
        if not source.exists() and not source.is_symlink():
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        if source.is_symlink():
            target.symlink_to(os.readlink(source))
        else:
            shutil.copy2(source, target)
        copied += 1
    if copied == 0:
        raise CheckFailed("git ls-files listed no file to copy")
    say(f"copied {copied} tracked files ({len(names) - copied} deleted in the working tree left out)")


def check_guide_lines(copy: pathlib.Path, table: str) -> None:
    """The table lines the guide shows are the table's own, column for column."""
    guide_lines = [line for line in (copy / GUIDE).read_text().splitlines() if line.startswith("TESSERA_BACKEND(")]
    if not guide_lines:
        raise CheckFailed(f"{GUIDE} shows no TESSERA_BACKEND(...) line of {TABLE}")
    table_lines = set(table.splitlines())
    for line in guide_lines:
        if line not in table_lines:
            raise CheckFailed(f"{GUIDE} shows a line that {TABLE} does not have (its columns differ?): {line}")


def add_table_line(copy: pathlib.Path) -> None:
    """Section 1 of the guide: the back end's line at the end of backends.def."""
    path = copy / TABLE
    table = path.read_text()
    parameters = macro_parameters((copy / ENTRY_POINTS).read_text())
    entries = [line for line in table.splitlines() if line.startswith("TESSERA_BACKEND(")]
    if not entries:
        raise CheckFailed(f"{TABLE} has no TESSERA_BACKEND(...) line")
    for line in entries + [TOY_LINE]:
        arguments = macro_arguments(line)
        if len(arguments) != len(parameters):
            raise CheckFailed(
                f"{len(arguments)} columns where TESSERA_BACKEND({', '.join(parameters)}) takes "
                f"{len(parameters)}: {line}"
            )
        if line != TOY_LINE and arguments[0] == TOY_ID:
            raise CheckFailed(f"{TABLE} already lists a back end with the id {TOY_ID}: {line}")
    check_guide_lines(copy, table)
    path.write_text(table + ("" if table.endswith("\n") else "\n") + TOY_LINE + "\n")
    say(f"{TABLE}: appended {TOY_LINE}")


def add_folder(copy: pathlib.Path) -> None:
    """Sections 2 to 4 of the guide: the back end's folder, its library, renderer and entry points."""
    folder = copy / "sw_driver" / "renderers" / TOY_ID
    if folder.exists():
        raise CheckFailed(f"sw_driver/renderers/{TOY_ID}/ exists already in the repository")
    folder.mkdir()
    for name in TOY_FILES:
        template = TEMPLATES / name
        if not template.is_file():
            raise CheckFailed(f"the template {template.relative_to(ROOT)} is missing")
        shutil.copy2(template, folder / name)
    say(f"sw_driver/renderers/{TOY_ID}/: {', '.join(TOY_FILES)} (from scripts/check_add_backend/)")


def add_capabilities_to_test(copy: pathlib.Path) -> None:
    """Section 6 of the guide: test_gl_api told what the back end's depth and stencil buffers hold."""
    path = copy / CAPABILITIES_TEST
    text = path.read_text()
    start = text.find(CAPABILITIES_MAP)
    end = text.find("};", start)
    if start < 0 or end < 0:
        raise CheckFailed(f"{CAPABILITIES_TEST} has no '{CAPABILITIES_MAP} ... }};' for the guide's section 6 to edit")
    depth_bits, stencil_bits = macro_arguments(TOY_LINE)[2:4]
    entry = f'{{"{TOY_NAME}", {{{depth_bits}, {stencil_bits}}}}}'
    path.write_text(text[:end] + f", {entry}" + text[end:])
    say(f"{CAPABILITIES_TEST}: added {entry} to its map of what each back end stores")


def preset(root: pathlib.Path) -> tuple:
    """The build folder (relative to the source tree) and the cmake options of the configure preset."""
    try:
        presets = json.loads((root / "CMakePresets.json").read_text())
        entry = next(p for p in presets["configurePresets"] if p["name"] == PRESET)
    except (OSError, ValueError, KeyError, StopIteration) as error:
        raise CheckFailed(f"CMakePresets.json: no readable configure preset '{PRESET}' ({error!r})") from error
    binary_dir = entry.get("binaryDir", f"${{sourceDir}}/build/{PRESET}")
    if not binary_dir.startswith("${sourceDir}/"):
        raise CheckFailed(f"CMakePresets.json: preset '{PRESET}' builds outside the source tree: {binary_dir}")
    options = ["-G", entry["generator"]] if "generator" in entry else []
    options += [f"-D{key}={value}" for key, value in entry.get("cacheVariables", {}).items()]
    return binary_dir.removeprefix("${sourceDir}/"), options


def build_environment() -> dict:
    """This environment without a calling make's job server, which the copy's make must not join."""
    return {key: value for key, value in os.environ.items() if key not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL")}


def run_logged(command: list, log: pathlib.Path, what: str) -> float:
    """Runs a configure or build step into its log; a failure shows the log's last lines."""
    start = time.monotonic()
    with log.open("w") as out:
        try:
            status = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, env=build_environment()).returncode
        except OSError as error:
            raise CheckFailed(f"{what}: cannot run {command[0]}: {error}") from error
    seconds = time.monotonic() - start
    if status != 0:
        raise CheckFailed(
            f"{what} failed (status {status}, {seconds:.0f} s): {' '.join(command)}\n"
            f"last {LOG_TAIL} lines of {log}:\n{tail(log)}"
        )
    say(f"{what}: done in {seconds:.0f} s (log {log.name})")
    return seconds


def png_pixels(path: pathlib.Path) -> list:
    """The pixels of a PNG soc_sim wrote, each as its bytes (RGB or RGBA)."""
    try:
        _, _, channels, rows = png_read.read_png(path)
    except (OSError, ValueError) as error:
        raise CheckFailed(str(error)) from error
    return [row[x : x + channels] for row in rows for x in range(0, len(row), channels)]


def run(command: list, cwd: pathlib.Path) -> subprocess.CompletedProcess:
    try:
        return subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=600)
    except (OSError, subprocess.TimeoutExpired) as error:
        raise CheckFailed(f"cannot run {' '.join(command)}: {error}") from error


def describe(result: subprocess.CompletedProcess) -> str:
    return f"status {result.returncode}\nstdout:\n{result.stdout[-2000:]}\nstderr:\n{result.stderr[-2000:]}"


def check_toy_run(soc_sim: pathlib.Path, work: pathlib.Path, app: str, colour: str = "", host: str = "") -> str:
    """soc_sim --backend toy draws one frame of one colour (`colour`, RGBA in hex, if given) and
    records the back end in stats.json; `host`: the host model (host.model), if not the default."""
    out = work / f"out_{TOY_ID}_{app}{'_' + host if host else ''}"
    command = [str(soc_sim), "--backend", TOY_NAME, "--app", app, "--frames", "1", "--out", str(out), "--force"]
    command += ["--set", f"host.model={host}"] if host else []
    result = run(command, work)
    if result.returncode != 0:
        raise CheckFailed(describe(result))
    try:
        stats = json.loads((out / "stats.json").read_text())
    except (OSError, ValueError) as error:
        raise CheckFailed(f"no readable stats.json ({error})") from error
    backend = stats.get("config", {}).get("driver", {}).get("backend")
    if backend != TOY_NAME:
        raise CheckFailed(f"stats.json's config.driver.backend is {backend!r}, not {TOY_NAME!r}")
    shown = stats.get("stats", {}).get("display", {}).get("frames_shown")
    if shown != 1:
        raise CheckFailed(f"stats.json's stats.display.frames_shown is {shown!r}, not 1")
    frame = out / "frame_0000.png"
    if not frame.is_file():
        raise CheckFailed(f"no {frame.name} in {out}")
    found = sorted({pixel.hex() for pixel in png_pixels(frame)})
    if len(found) != 1:
        raise CheckFailed(f"{frame.name} has {len(found)} colours: the toy only clears")
    if colour and found[0] != colour:
        raise CheckFailed(f"{frame.name} is all #{found[0]}, not the scene's clear colour #{colour}")
    return f"exit 0, config.driver.backend = {TOY_NAME}, 1 frame shown, {frame.name} all #{found[0]}"


def check_help(soc_sim: pathlib.Path, work: pathlib.Path) -> str:
    result = run([str(soc_sim), "--help"], work)
    line = next((line for line in result.stdout.splitlines() if "--backend" in line), "")
    if result.returncode != 0 or not re.search(rf"\b{TOY_NAME}\b", line):
        raise CheckFailed(f"soc_sim --help: no '{TOY_NAME}' on the --backend line: {line!r}; {describe(result)}")
    return f"--backend line: {line.strip()}"


def check_config_reference(soc_sim: pathlib.Path, work: pathlib.Path) -> str:
    result = run([str(soc_sim), "--config-reference"], work)
    row = next((line for line in result.stdout.splitlines() if "`driver.backend`" in line), "")
    if result.returncode != 0 or f"{TOY_NAME} (" not in row:
        raise CheckFailed(f"soc_sim --config-reference: driver.backend's row does not name '{TOY_NAME}': {row!r}")
    return "driver.backend's row names toy"


def check_unknown_backend(soc_sim: pathlib.Path, work: pathlib.Path) -> str:
    result = run([str(soc_sim), "--backend", "nosuch", "--out", str(work / "out_nosuch")], work)
    message = result.stderr.strip()
    if result.returncode != EXIT_USAGE or "nosuch" not in message or not re.search(rf"\b{TOY_NAME}\b", message):
        raise CheckFailed(
            f"soc_sim --backend nosuch: not rejected with status 2 naming '{TOY_NAME}': {describe(result)}"
        )
    return f"status 2: {message}"


def check_tests(build: pathlib.Path, work: pathlib.Path) -> str:
    pattern = f"^({'|'.join(TESTS)})$"
    result = run(["ctest", "--test-dir", str(build), "-R", pattern, "--output-on-failure"], work)
    if result.returncode != 0 or f"0 tests failed out of {len(TESTS)}" not in result.stdout:
        raise CheckFailed(f"ctest -R '{pattern}' in the copy: {describe(result)}")
    return f"{len(TESTS)} of {len(TESTS)} passed"


def check_runs(copy: pathlib.Path, build: pathlib.Path, iss: bool) -> None:
    soc_sim = build / "bin" / "soc_sim"
    checks = [
        ("soc_sim --backend toy --app triangle --frames 1", lambda: check_toy_run(soc_sim, copy, "triangle")),
        # The triangle scene clears to black, which an untouched frame buffer shows too: this scene's
        # clear colour, magenta, shows that the toy clears (and draws none of its rectangle).
        (
            "soc_sim --backend toy --app fullscreen_rect --frames 1",
            lambda: check_toy_run(soc_sim, copy, "fullscreen_rect", "ff00ffff"),
        ),
        ("soc_sim --help", lambda: check_help(soc_sim, copy)),
        ("soc_sim --config-reference", lambda: check_config_reference(soc_sim, copy)),
        ("soc_sim --backend nosuch", lambda: check_unknown_backend(soc_sim, copy)),
        (", ".join(TESTS), lambda: check_tests(build, copy)),
    ]
    if iss:
        checks.append(
            (
                "soc_sim --backend toy --app fullscreen_rect --frames 1 --set host.model=iss",
                lambda: check_toy_run(soc_sim, copy, "fullscreen_rect", "ff00ffff", "iss"),
            )
        )
    for name, run_check in checks:
        try:
            outcome = run_check()
        except CheckFailed as failure:
            raise CheckFailed(f"check '{name}' failed: {failure}") from failure
        say(f"check '{name}': ok ({outcome})")


def check(work: pathlib.Path, jobs: int, iss: bool) -> None:
    for program in ("git", "cmake", "ctest"):
        if shutil.which(program) is None:
            raise CheckFailed(f"{program} is not on PATH")
    copy = work / "repo"
    copy_tree(ROOT, copy)
    add_table_line(copy)
    add_folder(copy)
    add_capabilities_to_test(copy)
    build_dir, options = preset(copy)
    build = copy / build_dir
    run_logged(
        ["cmake", "-S", str(copy), "-B", str(build), *options],
        work / "configure.log",
        f"configure ({' '.join(options)})",
    )
    run_logged(
        ["cmake", "--build", str(build), "--target", *TARGETS, "-j", str(jobs)],
        work / "build.log",
        f"build {' '.join(TARGETS)} (-j {jobs})",
    )
    if iss:
        run_logged(
            ["cmake", "--build", str(build), "--target", ISS_TARGET, "-j", str(jobs)],
            work / "build_iss.log",
            f"build {ISS_TARGET}, the ARM sub-build (-j {jobs})",
        )
    check_runs(copy, build, iss)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--keep", action="store_true", help="keep the copy, its build, logs and frame")
    parser.add_argument("--jobs", type=int, default=2, help="build jobs (default 2)")
    parser.add_argument("--no-iss", action="store_true", help=f"leave out the ARM sub-build ({ISS_TARGET}) and its run")
    parser.add_argument("--work-dir", default=None, help="where the temporary folder is made (default: the system's)")
    args = parser.parse_args()
    if args.jobs < 1:
        parser.error("--jobs must be at least 1")
    if args.work_dir is not None and not pathlib.Path(args.work_dir).is_dir():
        parser.error(f"--work-dir {args.work_dir}: not a folder")
    start = time.monotonic()
    temporary = None
    if args.keep:
        work = pathlib.Path(tempfile.mkdtemp(prefix="check_add_backend_", dir=args.work_dir))
    else:
        temporary = tempfile.TemporaryDirectory(prefix="check_add_backend_", dir=args.work_dir)
        work = pathlib.Path(temporary.name)
    say(f"following {GUIDE} for a back end '{TOY_NAME}' in a copy of the tree in {work}")
    try:
        check(work, args.jobs, not args.no_iss)
        status = 0
    except CheckFailed as failure:
        print(f"check_add_backend: FAILED: {failure}", file=sys.stderr)
        if not args.keep:
            print(
                "check_add_backend: the copy and its logs are removed: run with --keep to look at them", file=sys.stderr
            )
        status = 1
    finally:
        if temporary is not None:
            temporary.cleanup()
    minutes, seconds = divmod(round(time.monotonic() - start), 60)
    kept = f"; kept in {work}" if args.keep else ""
    say(f"{'passed' if status == 0 else 'failed'} in {minutes} min {seconds:02d} s{kept}")
    return status


if __name__ == "__main__":
    sys.exit(main())
