#!/usr/bin/env python3
"""Regenerates the generated blocks of the Markdown docs from their sources of
truth, or (--check) fails naming every block that is out of date.

A generated block sits between two marker lines in a Markdown file:

    <!-- NAME:begin -->
    ...generated text, never edited by hand...
    <!-- NAME:end -->

and one file may hold several blocks of the same NAME. The blocks and where
each comes from:

    backends          sw_driver/renderers/backends.def (the back-end table)
    memory-map        contract/soc/memory_map.def
    irq-map           contract/soc/irq_map.def
    registers         the register tables, contract/*/*_regs.def
    rtl-units         rtl_models/units.def (the Verilog reference units)
    apps              soc_sim --list-apps
    soc-sim-help      soc_sim --help
    config-reference  soc_sim --config-reference
    stats-schema      docs/stats_schema.json (scripts/stats_schema.py writes it)
    calibration-array   what the array's calibration applications print
    calibration-energy  what scripts/fit_energy.py prints (the energy fit)
    experiment-NAME   scripts/experiment.py NAME --host native, for every
                      experiment of experiments/ (experiment-dma-whatif
                      for dma_whatif): the tables it prints, simulated
                      figures, the same on every machine
    experiment-NAME-iss  the same with --host iss, for every experiment
                      whose "hosts" lists iss
    cluster-NAME      the cluster platform's experiment cluster_NAME
                      (cluster-depth-ipsc: with the iPSC/860 preset)

Besides, the pictures of PICTURES (the README's teapot: the demo's last
frame) are compared byte for byte with what their run writes today, and a
hand-written table that must list every item of a generated list is
checked for a row per item: sw_driver/scenes/README.md, a row for every
built-in scene of soc_sim --list-apps.

The experiment blocks run the simulator and are regenerated or checked only
with --experiments or --only-experiments (the native blocks, about a minute
together on two cores) and --iss-experiments or --only-iss-experiments (the
ISS blocks, slower: the default test suite leaves them out) and
--cluster-experiments or --only-cluster-experiments (the cluster's, a few
minutes: also left out).

Usage:
    scripts/update_docs.py [--soc-sim build/default/bin/soc_sim] [--experiments] [--iss-experiments]
    scripts/update_docs.py --only-experiments --only-iss-experiments   every experiment block
    scripts/update_docs.py --check [...]     exit 1 if a block is stale
    scripts/update_docs.py --only memory-map backends   only those blocks
Standard library and PyYAML (Debian's python3-yaml: the experiment files).
"""

import argparse
import json
import os
import pathlib
import re
import subprocess
import sys
import tempfile

import def_table
import yaml

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Every Markdown file that holds generated blocks; a block NAME found in a
# file not listed here is an error too (see blocks_in()).
FILES = [
    "README.md",
    "docs/backends.md",
    "docs/configuration.md",
    "docs/architecture.md",
    "docs/usage.md",
    "docs/experiments.md",
    "docs/calibration.md",
    "contract/README.md",
    "tlm/soc/README.md",
    "tools/soc_sim/README.md",
    "rtl_models/README.md",
    "docs/statistics.md",
]


def read_def(path, macro):
    """The argument lists of every `macro(...)` line of an X-macro file (scripts/def_table.py)."""
    rows = def_table.rows(ROOT / path, macro)
    if not rows:
        sys.exit(f"update_docs: no {macro} line in {path}")
    return rows


def backends_table(_args):
    lines = [
        "| `--backend` (`driver.backend`) | what renders | depth / stencil bits | its README |",
        "| --- | --- | --- | --- |",
    ]
    for backend_id, name, depth, stencil, description in read_def(
        "sw_driver/renderers/backends.def", "TESSERA_BACKEND"
    ):
        readme = f"sw_driver/renderers/{backend_id}/README.md"
        link = f"`{readme}`" if (ROOT / readme).exists() else "-"
        lines.append(f"| `{name}` | {description} | {depth} / {stencil} | {link} |")
    return "\n".join(lines)


def memory_map_table(_args):
    lines = ["| region | base | size | what answers |", "| --- | --- | --- | --- |"]
    for name, base, size, description in read_def("contract/soc/memory_map.def", "TESSERA_REGION"):
        base_value, size_value = int(base.rstrip("u"), 16), int(size.rstrip("u"), 16)
        if size_value % (1 << 20) == 0:
            human = f"{size_value >> 20} MiB"
        else:
            human = f"{size_value >> 10} KiB"
        lines.append(f"| `{name}` | `0x{base_value:08X}` | `0x{size_value:08X}` ({human}) | {description} |")
    return "\n".join(lines)


def irq_map_table(_args):
    lines = ["| source | host line |", "| --- | --- |"]
    for source, line in read_def("contract/soc/irq_map.def", "TESSERA_IRQ"):
        lines.append(f"| `{source}` | {line} |")
    return "\n".join(lines)


# The register tables, in the order of the memory map: (table, its region of
# memory_map.def).
REGISTER_TABLES = [
    ("contract/display/display_regs.def", "display_regs"),
    ("contract/array/array_regs.def", "array_regs"),
    ("contract/dma/dma_regs.def", "dma_regs"),
    ("contract/zbuf/zbuf_regs.def", "zbuf_regs"),
    ("contract/raster/raster_regs.def", "raster_regs"),
    ("contract/intc/intc_regs.def", "intc"),
    # A cluster node's block: not in the SoC's memory map (None); the
    # cluster platform maps it.
    ("contract/network/ni_regs.def", None),
]
REGISTER_ROW = re.compile(r"^(TESSERA_REG|TESSERA_CHANNEL_REG|TESSERA_BITS)\(([^)]*)\)\s*(?://\s*(.*))?$")


def registers_tables(_args):
    """Per register table: every register (offset, reset, access, what it
    holds) with its bit fields (common/register_table.h)."""
    bases = {
        name: base for name, base, _size, _description in read_def("contract/soc/memory_map.def", "TESSERA_REGION")
    }
    out = []
    for path, region in REGISTER_TABLES:
        rows, fields = [], {}
        for line in (ROOT / path).read_text().splitlines():
            match = REGISTER_ROW.match(line)
            if not match:
                continue
            macro, arguments = match.group(1), [argument.strip() for argument in match.group(2).split(",")]
            comment = (match.group(3) or "").replace("|", "\\|")
            if macro == "TESSERA_BITS":
                prefix, name, lsb, width = arguments
                bits = f"bit {lsb}" if width == "1" else f"bits {lsb}-{int(lsb) + int(width) - 1}"
                fields.setdefault(prefix, []).append(f"`{prefix}_{name}` ({bits}): {comment}".rstrip(": "))
            else:
                rows.append((macro == "TESSERA_CHANNEL_REG", arguments, comment))
        if region is None:
            out.append(f"**`{path}`** (a cluster node's; the cluster platform maps it, not the SoC's memory map):")
        else:
            out.append(f"**`{path}`** (region `{region}` at `{bases[region].rstrip('u')}`):")
        out.append("")
        out.append("| register | offset | reset | access | what it holds |")
        out.append("| --- | --- | --- | --- | --- |")
        for per_channel, (name, offset, reset, access), comment in rows:
            where = f"channel base + `{offset}`" if per_channel else f"`{offset}`"
            bits = fields.get("IRQ" if name == "IRQ_STATUS" else name, [])
            held = "; ".join(([comment] if comment else []) + bits)
            out.append(f"| `{name}` | {where} | `{reset}` | {access} | {held} |")
        out.append("")
    return "\n".join(out).strip()


def rtl_units_table(_args):
    lines = [
        "| unit | RTL (top module) | C++ twin | cosim test | packages | what it computes |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    for name, folder, twin, _library, packages, _paper, description in read_def(
        "rtl_models/units.def", "TESSERA_RTL_UNIT"
    ):
        read = ", ".join(f"`{package}`" for package in packages.split() if package != "none") or "-"
        lines.append(
            f"| `{name}` | `rtl_models/{folder}/{name}.sv` | `tlm/{twin.strip(chr(34))}` | "
            f"`test_{folder}_{name}_cosim` | {read} | {description} |"
        )
    return "\n".join(lines)


def run(command, cwd=None):
    env = dict(os.environ, SYSTEMC_DISABLE_COPYRIGHT_MESSAGE="1")
    try:
        result = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True)
    except OSError as error:
        sys.exit(f"update_docs: cannot run {command[0]}: {error.strerror} (build it, or give --soc-sim)")
    if result.returncode != 0:
        sys.exit(f"update_docs: {' '.join(map(str, command))} failed with status {result.returncode}:\n{result.stderr}")
    return result.stdout


def apps_table(args):
    lines = ["| `--app` | what it runs |", "| --- | --- |"]
    for line in run([args.soc_sim, "--list-apps"]).splitlines():
        name, _, description = line.strip().partition("  ")
        if name:
            lines.append(f"| `{name}` | {description.strip()} |")
    return "\n".join(lines)


def soc_sim_help(args):
    # The usage line names the binary by the path it was started from.
    text = run([args.soc_sim, "--help"]).rstrip()
    text = re.sub(r"^Usage: \S*soc_sim", "Usage: soc_sim", text, flags=re.M)
    return "```\n" + text + "\n```"


def stats_schema_table(_args):
    """Every statistic of docs/stats_schema.json: key, unit, description."""
    schema = json.loads((ROOT / "docs" / "stats_schema.json").read_text())
    lines = ["| key | unit | description |", "| --- | --- | --- |"]
    for key, entry in schema.items():
        description = entry["description"].replace("|", "\\|")
        lines.append(f"| `{key}` | {entry['unit']} | {description} |")
    return "\n".join(lines)


def config_reference(args):
    return run([args.soc_sim, "--config-reference"]).strip()


def experiment(name, host):
    def generate(args):
        with tempfile.TemporaryDirectory(prefix="tessera-docs-") as folder:
            # experiment.py runs under Debian's python3 (its #! line), which has matplotlib.
            table = run(
                [
                    ROOT / "scripts" / "experiment.py",
                    name,
                    "--quiet",
                    "--host",
                    host,
                    "--soc-sim",
                    args.soc_sim,
                    "--out",
                    folder,
                ]
            )
        lines = []
        for line in table.strip().splitlines():
            if line.startswith("table ") and folder in line:
                continue  # where it wrote its files: a temporary folder
            if line.startswith("#"):
                line = "**" + line.lstrip("# ").strip() + "**"  # a heading of its own would break the page's outline
            lines.append(line)
        return (
            f"From `scripts/experiment.py {name} --host {host}` (simulated times: the same on every machine):\n\n"
            + "\n".join(lines).strip()
        )

    return generate


def printed_by(*runs):
    """What soc_sim prints on stdout for each run (its arguments), in a
    fenced block: published figures, regenerated from the runs."""

    def generate(args):
        lines = []
        with tempfile.TemporaryDirectory(prefix="tessera-docs-") as folder:
            for number, arguments in enumerate(runs):
                output = run([args.soc_sim, *arguments, "--quiet", "--no-frames", "--out", f"run{number}"], cwd=folder)
                lines += output.strip().splitlines()
        return "```\n" + "\n".join(lines) + "\n```"

    return generate


def cluster_experiment(name, *options):
    """What the cluster's experiment `name` (python/tessera_sweep/cluster_experiments.py) prints with `options`."""

    def generate(args):
        command = ["scripts/experiment.py", name, *options]
        with tempfile.TemporaryDirectory(prefix="tessera-docs-") as folder:
            table = run([ROOT / command[0], *command[1:], "--soc-sim", args.soc_sim, "--out", folder], cwd=ROOT)
        return f"From `{' '.join(command)}` (simulated times: the same on every machine):\n\n" + table.strip()

    return generate


ARRAY_CALIBRATION = [
    ["--app", app]
    for app in ("calib_array_add", "calib_array_mul", "calib_array_add_cmem", "calib_array_mul_cmem", "calib_ciu")
]


def energy_fit(args):
    """What scripts/fit_energy.py prints: the fitted parameters and every
    figure beside the model's value (Markdown)."""
    return run([sys.executable, os.path.join(ROOT, "scripts", "fit_energy.py"), "--soc-sim", args.soc_sim]).strip()


GENERATORS = {
    "calibration-array": printed_by(*ARRAY_CALIBRATION),
    "calibration-energy": energy_fit,
    "backends": backends_table,
    "memory-map": memory_map_table,
    "irq-map": irq_map_table,
    "registers": registers_tables,
    "rtl-units": rtl_units_table,
    "apps": apps_table,
    "soc-sim-help": soc_sim_help,
    "config-reference": config_reference,
    "stats-schema": stats_schema_table,
}
# One block per experiment of experiments/: experiment-<name>, with the
# name's underscores as dashes.
# An experiment whose "hosts" lists iss has a second block, experiment-<name>-iss.
ISS = set()
for _file in sorted((ROOT / "experiments").glob("*.yaml")):
    _block = "experiment-" + _file.stem.replace("_", "-")
    GENERATORS[_block] = experiment(_file.stem, "native")
    if "iss" in yaml.safe_load(_file.read_text()).get("hosts", []):
        GENERATORS[_block + "-iss"] = experiment(_file.stem, "iss")
        ISS.add(_block + "-iss")
SLOW = {name for name in GENERATORS if name.startswith("experiment-")} - ISS
# The cluster platform's experiments: a few minutes together (about 130 runs).
CLUSTER = {
    "cluster-depth": cluster_experiment("cluster_depth"),
    "cluster-depth-ipsc": cluster_experiment("cluster_depth", "--config", "configs/presets/ipsc860_like.json"),
    "cluster-speedup": cluster_experiment("cluster_speedup"),
    "cluster-soc": cluster_experiment("cluster_soc"),
}
GENERATORS.update(CLUSTER)
# Blocks another script writes (scripts/compare_host_models.py --write-doc),
# or written by hand and checked by a script of their own
# (scripts/check_tree.py: the source tree), left as they are.
EXTERNAL = {"host-models", "source-tree"}


# Hand-written tables that must name every item of a generated list: the
# file, and a function giving the names a row must start with.
def builtin_scenes(args):
    return [
        line.split()[0]
        for line in run([args.soc_sim, "--list-apps"]).splitlines()
        if line.rstrip().endswith("(GL ES 1.1 scene)")
    ]


COMPLETE_TABLES = [("sw_driver/scenes/README.md", builtin_scenes)]

# Pictures the docs show, each the file a run writes: (the picture, soc_sim's
# arguments, the file of the run's output folder).
PICTURES = [("docs/images/teapot.png", ["--quiet"], "frame_0002.png")]  # the README's: the demo's last frame


def stale_pictures(args, write):
    """The pictures that differ from what their run writes today (and, with
    `write`, replaced by it)."""
    stale = []
    for relative, arguments, produced in PICTURES:
        with tempfile.TemporaryDirectory(prefix="tessera-docs-") as folder:
            run([args.soc_sim, *arguments, "--out", "out"], cwd=folder)
            fresh = (pathlib.Path(folder) / "out" / produced).read_bytes()
        if (ROOT / relative).read_bytes() != fresh:
            stale.append(f"{relative}: the picture")
            if write:
                (ROOT / relative).write_bytes(fresh)
    return stale


def missing_rows(args):
    """Items a hand-written table lacks: '<file>: no row for <name>'."""
    missing = []
    for relative, names in COMPLETE_TABLES:
        text = (ROOT / relative).read_text()
        missing += [f"{relative}: no row for `{name}`" for name in names(args) if f"| `{name}` |" not in text]
    return missing


MARKER = re.compile(r"<!-- ([a-z-]+):begin -->\n(.*?)\n?<!-- \1:end -->", re.S)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="change nothing; exit 1 if a block is stale")
    parser.add_argument(
        "--soc-sim",
        default=str(ROOT / "build" / "default" / "bin" / "soc_sim"),
        help="the soc_sim to ask (default: build/default/bin/soc_sim)",
    )
    parser.add_argument(
        "--experiments",
        action="store_true",
        help="also the blocks that run experiments (slow), and only those with --only-experiments",
    )
    parser.add_argument("--only-experiments", action="store_true", help="only the experiment blocks (native)")
    parser.add_argument(
        "--iss-experiments",
        action="store_true",
        help="also the experiment blocks run on the ISS (slower), and only those with --only-iss-experiments",
    )
    parser.add_argument("--only-iss-experiments", action="store_true", help="only the ISS's experiment blocks")
    parser.add_argument(
        "--cluster-experiments",
        action="store_true",
        help="also the cluster platform's experiment blocks (minutes), and only those with --only-cluster-experiments",
    )
    parser.add_argument("--only-cluster-experiments", action="store_true", help="only the cluster's blocks")
    parser.add_argument(
        "--only",
        nargs="+",
        choices=sorted(GENERATORS),
        metavar="BLOCK",
        help="only these blocks: " + ", ".join(sorted(GENERATORS)),
    )
    args = parser.parse_args()
    wanted = set(GENERATORS)
    only_experiments = args.only_experiments or args.only_iss_experiments or args.only_cluster_experiments
    if args.only:
        wanted = set(args.only)
    elif only_experiments:
        wanted = (
            (SLOW if args.only_experiments else set())
            | (ISS if args.only_iss_experiments else set())
            | (set(CLUSTER) if args.only_cluster_experiments else set())
        )
    else:
        if not args.experiments:
            wanted -= SLOW
        if not args.iss_experiments:
            wanted -= ISS
        if not args.cluster_experiments:
            wanted -= set(CLUSTER)

    cache = {}
    stale = []
    found = set()
    for relative in FILES:
        path = ROOT / relative
        text = path.read_text()

        # replace runs inside this iteration (MARKER.sub below), so the loop variables it reads are this file's.
        def replace(match):
            name, body = match.group(1), match.group(2)
            if name in EXTERNAL:
                return match.group(0)
            if name not in GENERATORS:
                sys.exit(f"update_docs: {relative}: unknown generated block '{name}'")  # noqa: B023
            found.add(name)
            if name not in wanted:
                return match.group(0)
            if name not in cache:
                cache[name] = GENERATORS[name](args)
            if body.strip() != cache[name]:
                stale.append(f"{relative}: block '{name}'")  # noqa: B023
            return f"<!-- {name}:begin -->\n{cache[name]}\n<!-- {name}:end -->"

        new_text = MARKER.sub(replace, text)
        if not args.check and new_text != text:
            path.write_text(new_text)
    if not only_experiments and not args.only:
        stale += stale_pictures(args, write=not args.check)
    missing = wanted - found
    if missing:
        sys.exit(f"update_docs: no block of {', '.join(sorted(missing))} in any of {', '.join(FILES)}")
    if not only_experiments and not args.only:
        missing = missing_rows(args)
        if missing:
            print("Incomplete (add the row by hand):\n  " + "\n  ".join(missing))
            if args.check:
                return 1
    if args.check:
        if stale:
            options = (" --only-experiments" if args.only_experiments else "") + (
                " --only-iss-experiments" if args.only_iss_experiments else ""
            )
            print(f"Out of date (run scripts/update_docs.py{options}):\n  " + "\n  ".join(stale))
            return 1
        print(f"generated blocks up to date: {', '.join(sorted(wanted))}")
        return 0
    print("updated: " + (", ".join(stale) if stale else "nothing was stale"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
