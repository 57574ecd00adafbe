"""run_outputs.py: what the scripts that compare two soc_sim runs share: the built-in GL scenes to run, and whether
two runs' output folders hold the same frames and VCD byte for byte (stats.json is each script's own to compare)."""

import pathlib
import subprocess

# Scenes run with arguments by the host-model scripts (measure_host_costs.py,
# compare_host_models.py): the OBJ viewer its file (a relative path: an
# absolute one would make the ISS's obj_viewer cycles depend on where the
# repository was checked out); the random scene and the dense teapot 2,000
# triangles (their defaults take the ISS's array back ends long).
SCENE_ARGUMENTS = {
    "obj_viewer": ["tests/sw_driver/scenes/data/cube.obj"],
    "random_triangles": ["--triangles", "2000"],
    "dense_teapot": ["--triangles", "2000"],
}


def gl_scenes(soc_sim: str) -> list:
    """The built-in GL ES 1.1 scenes soc_sim --list-apps names, obj_viewer left out (it needs a model file)."""
    listing = subprocess.run([soc_sim, "--list-apps"], check=True, capture_output=True, text=True).stdout
    names = []
    for line in listing.splitlines():
        fields = line.split()
        if fields and "(GL ES 1.1 scene)" in line and fields[0] != "obj_viewer":
            names.append(fields[0])
    return names


def different_files(first: pathlib.Path, second: pathlib.Path) -> str:
    """Where the two folders' files other than stats.json differ ("" if they hold the same names and bytes); each must
    hold a trace.vcd and a frame."""
    files = sorted(p.name for p in first.iterdir() if p.name != "stats.json")
    files_second = sorted(p.name for p in second.iterdir() if p.name != "stats.json")
    if files != files_second:
        return f"different files: {files} against {files_second}"
    if "trace.vcd" not in files or not any(name.startswith("frame_") for name in files):
        return f"a frame or the VCD is missing: {files}"
    for name in files:
        if (first / name).read_bytes() != (second / name).read_bytes():
            return f"{name} differs"
    return ""
