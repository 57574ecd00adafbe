#!/usr/bin/env python3
"""Plot the reciprocal unit's relative error against X, like Figures 4, 5 and 7
of Crisu et al., "Design Tradeoffs for an Embedded OpenGL-Compliant Hardware
Rasterizer".

Runs the recip_table command once per method and writes, into the output
folder, one PNG per method (fig4_method1.png, fig5_method2.png,
fig7_method3.png) and all three on one page (reciprocal_error_all.png).

    build/venv/bin/python3 scripts/plot_reciprocal_error.py build/default/bin/recip_table out/recip

Runs under the project's Python environment, build/venv (scripts/setup.sh
makes it; it sees Debian's matplotlib, python3-matplotlib), or any Python 3
with matplotlib. python/tests/test_plot_reciprocal_error.py runs it so.
"""

import argparse
import csv
import io
import pathlib
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)

METHODS = (
    # (method, file name, title) -- the figure numbers are the paper's.
    ("1", "fig4_method1.png", "Method 1: 16k-entry table, fixed point 5.10 (cf. Fig. 4)"),
    ("2", "fig5_method2.png", "Method 2: 16k-entry table, floating point 1.6 / 5-bit exponent (cf. Fig. 5)"),
    ("3", "fig7_method3.png", "Method 3: prescaler and 1k-entry table (cf. Fig. 7)"),
)


def run_recip_table(binary, method):
    """Returns (x, relative error in percent, summary lines) for one method."""
    done = subprocess.run([binary, "--method", method], capture_output=True, text=True, check=False)
    if done.returncode != 0:
        sys.exit(f"{binary} --method {method} failed ({done.returncode}): {done.stderr.strip()}")
    rows = list(csv.DictReader(io.StringIO(done.stdout)))
    if not rows:
        sys.exit(f"{binary} --method {method} printed no rows")
    x = [float(row["x"]) for row in rows]
    error_percent = [100.0 * float(row["relative_error"]) for row in rows]
    summary = [line.lstrip("# ") for line in done.stderr.splitlines() if line.startswith("#")]
    return x, error_percent, summary


def draw(axes, x, error_percent, title, summary, linear_x):
    axes.plot(x, error_percent, linewidth=0.4)
    if not linear_x:
        # Every octave of X gets the same width, so the small operands, where
        # the tables are exact, stay visible.
        axes.set_xscale("log", base=2)
    axes.set_xlim(x[0], x[-1])
    axes.set_xlabel("X (10.4 operand)")
    axes.set_ylabel("relative error of 1/X [%]")
    axes.set_title(title, fontsize=10)
    axes.grid(True, which="both", linewidth=0.3)
    axes.text(0.01, 0.02, "\n".join(summary[1:]), transform=axes.transAxes, fontsize=8, va="bottom")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("recip_table", help="path to the recip_table binary")
    parser.add_argument("output_dir", nargs="?", default="out/reciprocal", help="folder for the PNG files")
    parser.add_argument("--linear-x", action="store_true", help="linear X axis instead of log2")
    args = parser.parse_args()

    out = pathlib.Path(args.output_dir)
    out.mkdir(parents=True, exist_ok=True)
    results = {method: run_recip_table(args.recip_table, method) for method, _, _ in METHODS}

    for method, file_name, title in METHODS:
        x, error_percent, summary = results[method]
        figure, axes = plt.subplots(figsize=(8, 4.5))
        draw(axes, x, error_percent, title, summary, args.linear_x)
        figure.tight_layout()
        figure.savefig(out / file_name, dpi=120)
        plt.close(figure)
        print(f"{out / file_name}: {'; '.join(summary[1:])}")

    figure, all_axes = plt.subplots(3, 1, figsize=(8, 11))
    for axes, (method, _, title) in zip(all_axes, METHODS):
        x, error_percent, summary = results[method]
        draw(axes, x, error_percent, title, summary, args.linear_x)
    figure.tight_layout()
    figure.savefig(out / "reciprocal_error_all.png", dpi=100)
    plt.close(figure)
    print(out / "reciprocal_error_all.png")


if __name__ == "__main__":
    main()
