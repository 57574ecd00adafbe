"""Crockett and Orloff's performance model of their sort-middle parallel renderer.

T. W. Crockett and T. Orloff, "A Parallel Rendering Algorithm for MIMD
Architectures", ICASE Report 91-3 (NASA CR-187571), June 1991: section 4
(Eq. 1-10), section 6 (Eq. 11-15, Table 1, Table 2). The functions keep the
paper's symbols:

    n        triangles in the scene (before back-face culling, which removes half)
    p        processors (frame-buffer stripes, one per processor)
    h        mean projected triangle height, pixels
    y        screen height, scanlines
    d        buffer depth, trapezoids per message
    r        trapezoids per processor (Eq. 2)
    v = r/p  trapezoids per processor per destination
    s        trapezoid bytes
    C        linear cost per triangle (Eq. 1)
    t_split  cost of one split; t_B the Bresenham set-up of one trapezoid
    t_l      latency of one trapezoid message; t_l0 of a termination message
    t_b      per-byte transfer cost
    alpha    wait constant (Eq. 7)

Times are in seconds. docs/sort_middle_model.md reconstructs each equation
from the scanned report and says where the scan was ambiguous.
`tessera-sweep sort-middle` is the calculator (main() below).
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
from dataclasses import dataclass, fields, replace
from pathlib import Path

MICROSECOND = 1e-6


@dataclass(frozen=True)
class Constants:
    """The machine's constants of the model, in seconds (s in bytes)."""

    t_l: float
    alpha: float
    t_split: float
    t_B: float
    t_l0: float
    t_b: float
    s: int
    C: float | None = None


# The paper's own constants (iPSC/860, its standard scene):
#   t_l, alpha  Table 1, the mean over p = 8, 16, 32, 64 of the values fitted to Fig. 7 (431 and 143 us);
#   t_split, t_B  section 6.3, from operation counts and the i860's timings (2.500 and 13.375 us);
#   t_l0        section 6.3, published short-message latency of its reference [1] (75 us);
#   s           section 5: a trapezoid is 64 bytes;
#   t_b         0: section 6.2 drops the transfer term (p-1)vs t_b, overlapped with computing;
#   C           not printed (section 6.3 solves Eq. 10 for it from Table 3's diagonal).
PAPER = Constants(
    t_l=431 * MICROSECOND,
    alpha=143 * MICROSECOND,
    t_split=2.5 * MICROSECOND,
    t_B=13.375 * MICROSECOND,
    t_l0=75 * MICROSECOND,
    t_b=0.0,
    s=64,
)

# Table 1: (t_l, alpha) fitted per p to the standard scene's Fig. 7.
PAPER_TABLE1 = {
    8: (452 * MICROSECOND, 113 * MICROSECOND),
    16: (443 * MICROSECOND, 120 * MICROSECOND),
    32: (419 * MICROSECOND, 152 * MICROSECOND),
    64: (411 * MICROSECOND, 185 * MICROSECOND),
}

# The standard scene (section 6): 100000 triangles of 10 x 10 pixels at 512 x 512, h measured as 8.3.
STANDARD_SCENE = {"n": 100_000, "h": 8.3, "y": 512}
# Section 6.3 normalises Table 3 to this single-processor rate: 4366 triangles/s with n = 12500.
SINGLE_PROCESSOR_RATE = (4366.0, 12_500)
# Sections 6.1 and 6.3: memory allows at most 12500 triangles per processor (100000 needs p >= 8).
MAX_TRIANGLES_PER_PROCESSOR = 12_500
# The per-byte cost of the iPSC/860's link, 2.8 MB/s each way (configs/presets/README.md); not the paper's.
IPSC860_LINK_T_B = 1 / 2.8e6


def trapezoids_per_processor(n: float, p: int, h: float, y: float) -> float:
    """Eq. 2: r = (n/2)(2/p)(hp/2y + 1) = nh/2y + n/p. Culling leaves n/2 triangles, each split at its
    middle vertex into two pieces of height h/2, each crossing hp/2y stripe boundaries on average."""
    return n * h / (2 * y) + n / p


def trapezoids_per_destination(n: float, p: int, h: float, y: float) -> float:
    """v = r/p: a processor's trapezoids for each of the p destinations, itself included."""
    return trapezoids_per_processor(n, p, h, y) / p


def transfer_time(p: int, v: float, s: float, t_b: float) -> float:
    """Eq. 3: t_t = (p-1) v s t_b, the bytes a processor sends to the p-1 others."""
    return (p - 1) * v * s * t_b


def messages_per_processor(p: int, v: float, d: float, ceiling: bool = True) -> float:
    """Eq. 4: m = (p-1) ceil(v/d); without the ceiling, as Eq. 11 and 12 take it, (p-1) v/d."""
    return (p - 1) * (math.ceil(v / d) if ceiling else v / d)


def send_time(p: int, v: float, d: float, s: float, t_l: float, t_b: float, ceiling: bool = True) -> float:
    """Eq. 5: t_send = m t_l + t_t = (p-1)(ceil(v/d) t_l + v s t_b)."""
    return messages_per_processor(p, v, d, ceiling) * t_l + transfer_time(p, v, s, t_b)


def bandwidth_deficit(p: int, d: float) -> float:
    """Eq. 6: p(p-1) last messages of d/2 trapezoids, each over k/2 of the pk/2 edges of a hypercube of
    p = 2^k nodes: p(p-1)(d/2)(k/2) / (pk/2) = (p-1)d/2, about pd/2."""
    return (p - 1) * d / 2


def wait_time(p: int, d: float, alpha: float) -> float:
    """Eq. 7: t_wait = alpha pd/2, proportional to the deficit of Eq. 6."""
    return alpha * p * d / 2


def quit_time(p: int, t_l: float) -> float:
    """Eq. 8: t_quit = 2[(p-1) + log2 p] t_l: LT and LTC with every neighbour, then the NC merge and the GC
    broadcast on a hypercube."""
    return 2 * ((p - 1) + math.log2(p)) * t_l


def linear_time(n: float, p: int, C: float) -> float:
    """Eq. 1: C n/p, the part that parallelises perfectly (shading, transforming, culling, clipping, the
    scan conversion and z-buffer of every pixel)."""
    return C * n / p


@dataclass(frozen=True)
class TimeComponents:
    """Eq. 9: t = C n/p + r t_split + t_send + r t_B + t_wait + t_quit, each term in seconds."""

    linear: float
    split: float
    send: float
    raster_setup: float
    wait: float
    quit: float

    @property
    def total(self) -> float:
        return sum(getattr(self, field.name) for field in fields(self))


def time_components(
    n: float, p: int, h: float, y: float, d: float, constants: Constants = PAPER, ceiling: bool = True
) -> TimeComponents:
    """Eq. 9 and 10 for one scene, p and d. The termination messages take t_l0, as section 6 takes them
    (they are short and synchronous); Eq. 10 as printed writes t_l. C must be given (Constants.C)."""
    if constants.C is None:
        raise ValueError("the linear constant C is not set: the paper does not print it (give --C-us)")
    if p < 1 or d <= 0:
        raise ValueError(f"p must be at least 1 and d positive (p={p}, d={d})")
    r = trapezoids_per_processor(n, p, h, y)
    v = r / p
    return TimeComponents(
        linear=linear_time(n, p, constants.C),
        split=r * constants.t_split,
        send=send_time(p, v, d, constants.s, constants.t_l, constants.t_b, ceiling),
        raster_setup=r * constants.t_B,
        wait=wait_time(p, d, constants.alpha) if p > 1 else 0.0,  # Eq. 7 stands (p-1) for p; one sends nothing
        quit=quit_time(p, constants.t_l0),
    )


def total_time(
    n: float, p: int, h: float, y: float, d: float, constants: Constants = PAPER, ceiling: bool = True
) -> float:
    """Eq. 10: t(d), the sum of time_components."""
    return time_components(n, p, h, y, d, constants, ceiling).total


def optimal_depth(p: int, v: float, t_l: float, alpha: float) -> float:
    """Eq. 11: dt/dd = -(p-1) v t_l / d^2 + alpha p/2 = 0, so d_opt = sqrt(2(p-1) v t_l / (alpha p))."""
    return math.sqrt(2 * (p - 1) * v * t_l / (alpha * p))


def scene_optimal_depth(n: float, p: int, h: float, y: float, constants: Constants = PAPER) -> float:
    """Eq. 11 for a scene: v from Eq. 2."""
    return optimal_depth(p, trapezoids_per_destination(n, p, h, y), constants.t_l, constants.alpha)


def recast_coefficients(
    n: float, p: int, h: float, y: float, constants: Constants = PAPER
) -> tuple[float, float, float]:
    """Eq. 12-15: t(d) = C0 + C1/d + C2 d with
    C0 = C n/p + r(t_split + t_B) + 2[(p-1) + log2 p] t_l0   (Eq. 13; the transfer term dropped),
    C1 = (p-1) v t_l                                          (Eq. 14),
    C2 = alpha p/2                                            (Eq. 15)."""
    if constants.C is None:
        raise ValueError("the linear constant C is not set: C0 needs it")
    r = trapezoids_per_processor(n, p, h, y)
    v = r / p
    c0 = linear_time(n, p, constants.C) + r * (constants.t_split + constants.t_B) + quit_time(p, constants.t_l0)
    return c0, (p - 1) * v * constants.t_l, constants.alpha * p / 2


def fit_depth_curve(d, t) -> tuple[float, float, float]:
    """Least squares of Eq. 12 to measured (d, t) points of one p: (C0, C1, C2)."""
    import numpy as np  # here, not at the top: the package's other commands run under Debian's python3 without it

    d = np.asarray(d, dtype=float)
    t = np.asarray(t, dtype=float)
    if d.ndim != 1 or d.shape != t.shape or len(d) < 3:
        raise ValueError(f"need at least 3 (d, t) points of one p, got {len(d)}")
    if np.any(d <= 0):
        raise ValueError("every buffer depth d must be positive")
    design = np.column_stack([np.ones_like(d), 1 / d, d])
    (c0, c1, c2), *_ = np.linalg.lstsq(design, t, rcond=None)
    return float(c0), float(c1), float(c2)


def latency_and_wait(c1: float, c2: float, p: int, v: float) -> tuple[float, float]:
    """Table 1's way: t_l = C1 / ((p-1) v) from Eq. 14 and alpha = 2 C2 / p from Eq. 15."""
    if p < 2:
        raise ValueError("t_l and alpha need p >= 2 (no messages with one processor)")
    return c1 / ((p - 1) * v), 2 * c2 / p


def linear_constant_from_rate(
    rate: float, n: float, h: float, y: float, constants: Constants = PAPER, p: int = 1
) -> float:
    """C from a measured rate (triangles/s) on p processors, by Eq. 10 solved for C with the other terms
    from `constants`. With p = 1 and the paper's single-processor rate this gives a C the paper does not
    print (it solved for C from other points): an estimate of ours, marked as such wherever used."""
    if p == 1:  # one processor: no messages and no network (Eq. 6 is 0)
        rest = trapezoids_per_processor(n, p, h, y) * (constants.t_split + constants.t_B)
    else:
        d = scene_optimal_depth(n, p, h, y, constants)
        rest = total_time(n, p, h, y, d, replace(constants, C=0.0), ceiling=False)
    return (n / rate - rest) * p / n


def paper_linear_constant(constants: Constants = PAPER) -> float:
    """C from the paper's single-processor rate (4366 triangles/s, n = 12500, the standard scene's h and y)."""
    rate, n = SINGLE_PROCESSOR_RATE
    return linear_constant_from_rate(rate, n, STANDARD_SCENE["h"], STANDARD_SCENE["y"], constants)


# The scenes and processor counts of the paper's Tables 2 and 3.
TABLE_TRIANGLES = (6250, 12_500, 25_000, 50_000, 100_000, 200_000)
TABLE_PROCESSORS = (2, 4, 8, 16, 32, 64, 128)


def optimal_depth_table(
    ns=TABLE_TRIANGLES,
    ps=TABLE_PROCESSORS,
    h: float = STANDARD_SCENE["h"],
    y: float = STANDARD_SCENE["y"],
    constants: Constants = PAPER,
    fits_only: bool = True,
) -> dict[tuple[int, int], float]:
    """Table 2: d_opt (Eq. 11) per (n, p); with fits_only, only where n/p fits a node's memory."""
    return {
        (n, p): scene_optimal_depth(n, p, h, y, constants)
        for n in ns
        for p in ps
        if not fits_only or n / p <= MAX_TRIANGLES_PER_PROCESSOR
    }


def format_optimal_depth_table(table: dict, decimals: int = 0) -> str:
    """Markdown, a row per p and a column per n as the paper's Table 3 is laid out; '-' where n/p does not fit."""
    ns = sorted({n for n, _ in table})
    ps = sorted({p for _, p in table})
    lines = ["| p | " + " | ".join(f"n = {n}" for n in ns) + " |", "|---:|" + "---:|" * len(ns)]
    for p in ps:
        cells = [f"{table[n, p]:.{decimals}f}" if (n, p) in table else "-" for n in ns]
        lines.append(f"| {p} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def constants_from_options(options: argparse.Namespace) -> Constants:
    constants = PAPER
    given = {
        "t_l": options.latency_us,
        "alpha": options.alpha_us,
        "t_split": options.t_split_us,
        "t_B": options.t_B_us,
        "t_l0": options.t_l0_us,
        "t_b": options.t_b_us,
        "C": getattr(options, "C_us", None),
    }
    for name, value in given.items():
        if value is not None:
            if value < 0:
                raise ValueError(f"--{name.replace('_', '-')}-us must not be negative ({value})")
            constants = replace(constants, **{name: value * MICROSECOND})
    if options.s is not None:
        if options.s < 0:
            raise ValueError(f"--s must not be negative ({options.s})")
        constants = replace(constants, s=options.s)
    if options.h < 0 or options.y <= 0:
        raise ValueError(f"need --h >= 0 and --y > 0 (h={options.h}, y={options.y})")
    return constants


def add_constant_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("constants in microseconds (default: the paper's, docs/sort_middle_model.md)")
    group.add_argument("--latency-us", type=float, metavar="US", help="t_l, trapezoid message latency (431, Table 1)")
    group.add_argument("--alpha-us", type=float, metavar="US", help="alpha, wait constant (143, Table 1)")
    group.add_argument("--t-split-us", type=float, metavar="US", help="t_split (2.5, section 6.3)")
    group.add_argument(
        "--t-B-us", type=float, metavar="US", help="t_B, Bresenham set-up per trapezoid (13.375, section 6.3)"
    )
    group.add_argument(
        "--t-l0-us", type=float, metavar="US", help="t_l0, termination message latency (75, section 6.3)"
    )
    group.add_argument(
        "--t-b-us",
        type=float,
        metavar="US",
        help="t_b, per-byte cost (0: the paper drops it; the iPSC/860 link is 0.357)",
    )
    group.add_argument("--s", type=int, help="s, trapezoid bytes (64, section 5)")
    parser.add_argument("--h", type=float, default=STANDARD_SCENE["h"], help="mean triangle height (8.3)")
    parser.add_argument("--y", type=float, default=STANDARD_SCENE["y"], help="screen height (512)")


def table_command(options: argparse.Namespace) -> int:
    constants = constants_from_options(options)
    bad = [f"--n {n}" for n in options.n or () if n <= 0] + [f"--p {p}" for p in options.p or () if p < 1]
    if bad or options.decimals < 0:
        raise ValueError(f"need n > 0, p >= 1 and --decimals >= 0 ({', '.join(bad) or options.decimals})")
    table = optimal_depth_table(
        options.n or TABLE_TRIANGLES, options.p or TABLE_PROCESSORS, options.h, options.y, constants, not options.all
    )
    print(
        f"d_opt (Eq. 11), t_l = {constants.t_l / MICROSECOND:g} us, alpha = {constants.alpha / MICROSECOND:g} us, "
        f"h = {options.h:g}, y = {options.y:g}"
    )
    print(format_optimal_depth_table(table, options.decimals))
    return 0


def time_command(options: argparse.Namespace) -> int:
    constants = constants_from_options(options)
    note = ""
    if constants.C is None:
        constants = replace(constants, C=paper_linear_constant(constants))
        note = " (ours: from the paper's 4366 triangles/s on one processor, n = 12500; the paper prints none)"
    n, p, h, y = options.n, options.p, options.h, options.y
    if p < 1 or n <= 0:
        raise ValueError(f"need n > 0 and p >= 1 (n={n}, p={p})")
    r = trapezoids_per_processor(n, p, h, y)
    v = r / p
    d_opt = optimal_depth(p, v, constants.t_l, constants.alpha) if p > 1 else None
    d = options.d if options.d is not None else max(1, round(d_opt)) if d_opt else 1
    parts = time_components(n, p, h, y, d, constants, ceiling=not options.no_ceiling)
    print(f"n = {n:g}, p = {p}, h = {h:g}, y = {y:g}, d = {d:g}")
    print(f"C = {constants.C / MICROSECOND:.3f} us per triangle{note}")
    print(f"r = {r:.3f} trapezoids per processor (Eq. 2), v = r/p = {v:.3f}")
    print(f"m = {messages_per_processor(p, v, d, not options.no_ceiling):g} messages per processor (Eq. 4)")
    if d_opt is not None:
        print(f"d_opt = {d_opt:.2f} (Eq. 11)")
    rows = [
        ("C n/p (Eq. 1)", parts.linear),
        ("r t_split", parts.split),
        ("t_send (Eq. 5)", parts.send),
        ("r t_B", parts.raster_setup),
        ("t_wait (Eq. 7)", parts.wait),
        ("t_quit (Eq. 8)", parts.quit),
        ("t (Eq. 10)", parts.total),
    ]
    for name, seconds in rows:
        print(f"{name:<16}{seconds * 1e3:12.3f} ms")
    print(f"rate            {n / parts.total:12.0f} triangles/s")
    return 0


def read_points(path: Path) -> dict[int, list[tuple[float, float]]]:
    """(d, t) points per p from a CSV file with columns p, d, t (t in seconds)."""
    points: dict[int, list[tuple[float, float]]] = {}
    with open(path, newline="") as file:
        reader = csv.DictReader(file)
        missing = {"p", "d", "t"} - set(reader.fieldnames or [])
        if missing:
            raise ValueError(f"{path}: missing column(s) {', '.join(sorted(missing))} (need p, d, t)")
        for line, row in enumerate(reader, 2):
            try:
                points.setdefault(int(row["p"]), []).append((float(row["d"]), float(row["t"])))
            except (TypeError, ValueError) as error:
                raise ValueError(f"{path}:{line}: {error}") from None
    return points


def fit_command(options: argparse.Namespace) -> int:
    constants_from_options(options)  # checks --h and --y
    if options.n <= 0:
        raise ValueError(f"need n > 0 (n={options.n})")
    import numpy as np  # here, as in fit_depth_curve

    points = read_points(options.points)
    print(f"Eq. 12 fitted per p (n = {options.n:g}, h = {options.h:g}, y = {options.y:g}); t_l and alpha as Table 1")
    print("| p | points | C0 (s) | C1 (s) | C2 (s) | t_l (us) | alpha (us) | rms residual (ms) |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for p in sorted(points):
        d, t = (np.array(column) for column in zip(*points[p]))
        c0, c1, c2 = fit_depth_curve(d, t)
        t_l, alpha = latency_and_wait(c1, c2, p, trapezoids_per_destination(options.n, p, options.h, options.y))
        residual = math.sqrt(float(np.mean((c0 + c1 / d + c2 * d - t) ** 2)))
        print(
            f"| {p} | {len(d)} | {c0:.4f} | {c1:.4f} | {c2:.3e} | {t_l / MICROSECOND:.0f} | "
            f"{alpha / MICROSECOND:.0f} | {residual * 1e3:.2f} |"
        )
    return 0


def main(argv: list[str] | None = None, prog: str = "tessera-sweep sort-middle") -> int:
    parser = argparse.ArgumentParser(
        prog=prog,
        description="Crockett and Orloff's sort-middle performance model (ICASE 91-3): d_opt table, t(d), fit",
    )
    commands = parser.add_subparsers(dest="command", required=True)
    table = commands.add_parser("table", help="d_opt (Eq. 11) per n and p, the paper's Table 2")
    table.add_argument("--n", type=int, action="append", help="triangles (repeatable; default the paper's six)")
    table.add_argument("--p", type=int, action="append", help="processors (repeatable; default 2 to 128)")
    table.add_argument("--all", action="store_true", help="every (n, p), also where n/p > 12500 does not fit")
    table.add_argument("--decimals", type=int, default=0, help="decimals of d_opt (default 0, as the paper)")
    add_constant_options(table)
    table.set_defaults(run=table_command)
    time = commands.add_parser("time", help="t(d) (Eq. 10) and its components for one n, p, d")
    time.add_argument("--n", type=float, default=STANDARD_SCENE["n"], help="triangles (100000)")
    time.add_argument("--p", type=int, required=True, help="processors")
    time.add_argument("--d", type=float, help="buffer depth (default: d_opt rounded)")
    time.add_argument(
        "--C-us", type=float, metavar="US", help="C, linear cost per triangle (default: estimated, see output)"
    )
    time.add_argument("--no-ceiling", action="store_true", help="v/d instead of ceil(v/d) in Eq. 4 and 5")
    add_constant_options(time)
    time.set_defaults(run=time_command)
    fit = commands.add_parser("fit", help="Eq. 12 fitted to measured (p, d, t) points; t_l and alpha as Table 1")
    fit.add_argument("points", type=Path, help="CSV with columns p, d, t (t in seconds)")
    fit.add_argument("--n", type=float, default=STANDARD_SCENE["n"], help="triangles (100000)")
    add_constant_options(fit)
    fit.set_defaults(run=fit_command)
    options = parser.parse_args(argv)
    try:
        return options.run(options)
    except (ValueError, OSError) as error:
        print(f"{prog}: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
