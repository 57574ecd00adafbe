"""tessera_sweep.sort_middle_model: Crockett and Orloff's performance model (ICASE 91-3) against hand
computations, a brute-force minimisation, known coefficients and the numbers the paper prints."""

import math
import re
from dataclasses import replace

import numpy as np
import pytest

from tessera_sweep import sort_middle_model as model

from conftest import tessera_sweep_command

# Table 2 of the paper (d_opt from Eq. 11 with Table 1's mean constants), the entries legible in the scan,
# as (n, p): d_opt. The scan reads the table column by column: "47 25 13", "94 50 27 15 9", "71 38 21 12";
# the columns are n = 25000 (p = 8, 16, 32), n = 100000 (p = 8 to 128) and n = 200000 (p = 16 to 128)
# (docs/sort_middle_model.md says why).
PAPER_TABLE2 = {
    (25_000, 8): 47,
    (25_000, 16): 25,
    (25_000, 32): 13,
    (100_000, 8): 94,
    (100_000, 16): 50,
    (100_000, 32): 27,
    (100_000, 64): 15,
    (100_000, 128): 9,
    (200_000, 16): 71,
    (200_000, 32): 38,
    (200_000, 64): 21,
    (200_000, 128): 12,
}

# Eq. 2 by hand for the standard scene: nh/2y = 100000 * 8.3 / 1024 = 810.546875, plus n/p.
STANDARD_R = {8: 13_310.546875, 16: 7_060.546875, 32: 3_935.546875, 64: 2_373.046875, 128: 1_591.796875}


@pytest.mark.parametrize("p", sorted(STANDARD_R))
def test_eq2_trapezoids_per_processor_of_the_standard_scene(p):
    assert model.trapezoids_per_processor(100_000, p, 8.3, 512) == pytest.approx(STANDARD_R[p], abs=1e-9)
    assert model.trapezoids_per_destination(100_000, p, 8.3, 512) == pytest.approx(STANDARD_R[p] / p)


def test_eq4_and_eq5_messages_and_send_time():
    # p = 8, v = 100, d = 30: ceil(100/30) = 4 messages to each of 7 others; 64-byte trapezoids at 1 us/byte.
    assert model.messages_per_processor(8, 100, 30) == 28
    assert model.messages_per_processor(8, 100, 30, ceiling=False) == pytest.approx(7 * 100 / 30)
    assert model.send_time(8, 100, 30, 64, 400e-6, 1e-6) == pytest.approx(28 * 400e-6 + 7 * 100 * 64 * 1e-6)


def test_eq8_termination_on_a_hypercube():
    # p = 16: 2 * (15 + 4) messages of 75 us.
    assert model.quit_time(16, 75e-6) == pytest.approx(38 * 75e-6)


CASES = [(100_000, p) for p in (8, 16, 32, 64, 128)] + [(25_000, 8), (200_000, 16), (6250, 2)]


@pytest.mark.parametrize(("n", "p"), CASES)
def test_eq11_is_the_minimum_of_eq10(n, p):
    """Eq. 10 without the ceiling (as Eq. 11 takes it), every term included, minimised over a grid of d."""
    constants = model.Constants(
        t_l=431e-6, alpha=143e-6, t_split=2.5e-6, t_B=13.375e-6, t_l0=75e-6, t_b=0.357e-6, s=64, C=213e-6
    )
    d_opt = model.scene_optimal_depth(n, p, 8.3, 512, constants)

    def best(grid):
        return grid[int(np.argmin([model.total_time(n, p, 8.3, 512, d, constants, ceiling=False) for d in grid]))]

    coarse = best(np.arange(0.1, 1000, 0.1))  # d = 0.1 to 1000, then 0.001 steps around the best
    fine = best(np.arange(coarse - 0.2, coarse + 0.2, 0.001))
    assert fine == pytest.approx(d_opt, abs=0.001)


def test_eq11_in_closed_form():
    # p = 8, v = 1000, t_l = 400 us, alpha = 100 us: sqrt(2 * 7 * 1000 * 4 / 8) = sqrt(7000).
    assert model.optimal_depth(8, 1000, 400e-6, 100e-6) == pytest.approx(math.sqrt(7000))


def test_recast_coefficients_are_eq10_without_the_ceiling_and_transfer():
    constants = model.Constants(t_l=431e-6, alpha=143e-6, t_split=2.5e-6, t_B=13.375e-6, t_l0=75e-6, t_b=0.0, s=64)
    constants = replace(constants, C=213e-6)
    c0, c1, c2 = model.recast_coefficients(100_000, 16, 8.3, 512, constants)
    for d in (2.0, 17.0, 250.0):
        assert c0 + c1 / d + c2 * d == pytest.approx(model.total_time(100_000, 16, 8.3, 512, d, constants, False))
    assert c2 == pytest.approx(143e-6 * 16 / 2)


def test_fit_recovers_known_coefficients():
    d = np.array([2, 3, 5, 8, 13, 21, 34, 55, 89, 144, 233, 377], dtype=float)
    c0, c1, c2 = 2.7, 12.3, 5.0e-4
    assert model.fit_depth_curve(d, c0 + c1 / d + c2 * d) == pytest.approx((c0, c1, c2), rel=1e-9)
    noise = np.random.default_rng(91).normal(0, 1e-4, d.size)
    assert model.fit_depth_curve(d, c0 + c1 / d + c2 * d + noise) == pytest.approx((c0, c1, c2), rel=1e-2)


def test_fit_gives_back_table1_constants():
    """Points made from Table 1's p = 8 constants (t_l = 452 us, alpha = 113 us) fitted as section 6.2 does."""
    p, v = 8, STANDARD_R[8] / 8
    d = np.arange(2, int(v / 2) + 1, 7, dtype=float)
    t = 2.9 + (p - 1) * v * 452e-6 / d + 113e-6 * p / 2 * d
    c0, c1, c2 = model.fit_depth_curve(d, t)
    t_l, alpha = model.latency_and_wait(c1, c2, p, v)
    assert (t_l, alpha) == pytest.approx((452e-6, 113e-6), rel=1e-9)


def test_fit_refuses_too_few_points():
    with pytest.raises(ValueError, match="at least 3"):
        model.fit_depth_curve([2, 4], [1.0, 2.0])


def test_paper_constants_give_table2():
    for (n, p), printed in PAPER_TABLE2.items():
        assert model.scene_optimal_depth(n, p, 8.3, 512) == pytest.approx(printed, abs=0.5), (n, p)


def printed_table(output: str) -> dict:
    """(n, p): value of the Markdown table `sort-middle table` prints."""
    lines = [line for line in output.splitlines() if line.startswith("|")]
    ns = [int(cell) for cell in re.findall(r"n = (\d+)", lines[0])]
    table = {}
    for line in lines[2:]:
        cells = [cell.strip() for cell in line.strip("|").split("|")]
        for n, cell in zip(ns, cells[1:]):
            if cell != "-":
                table[n, int(cells[0])] = float(cell)
    return table


def test_calculator_prints_the_papers_table2():
    done = tessera_sweep_command("sort-middle", "table")
    assert done.returncode == 0, done.stderr
    table = printed_table(done.stdout)
    for key, printed in PAPER_TABLE2.items():
        assert table[key] == printed, key
    unrounded = printed_table(tessera_sweep_command("sort-middle", "table", "--decimals", "3").stdout)
    for key, printed in PAPER_TABLE2.items():
        assert abs(unrounded[key] - printed) <= 0.5, key
    # No cell where n/p exceeds a node's 12500 triangles: 100000 needs p >= 8.
    assert (100_000, 4) not in table and (100_000, 8) in table


def test_calculator_time_of_the_standard_scene():
    done = tessera_sweep_command("sort-middle", "time", "--p", "16", "--d", "50", "--C-us", "200")
    assert done.returncode == 0, done.stderr
    # By hand: C n/p = 200 us * 6250 = 1250 ms; r = 7060.546875, v = 441.28..., ceil(v/50) = 9 messages to
    # each of 15 others at 431 us: 58.185 ms; wait 143 us * 16 * 50 / 2 = 57.2 ms; quit 2 * (15 + 4) * 75 us.
    r = 7060.546875
    expected = 1250 + r * 2.5e-3 + 15 * 9 * 0.431 + r * 13.375e-3 + 57.2 + 2.85
    assert f"{expected:.3f} ms" in done.stdout
    assert "m = 135 messages" in done.stdout


def test_calculator_fits_points_from_a_file(tmp_path):
    v = STANDARD_R[16] / 16
    rows = ["p,d,t"] + [f"16,{d},{1.6 + 15 * v * 443e-6 / d + 120e-6 * 8 * d!r}" for d in range(2, 200, 11)]
    (tmp_path / "points.csv").write_text("\n".join(rows) + "\n")
    done = tessera_sweep_command("sort-middle", "fit", str(tmp_path / "points.csv"))
    assert done.returncode == 0, done.stderr
    assert re.search(r"\| 16 \| 18 \| 1\.6000 \| [\d.]+ \| [\d.e-]+ \| 443 \| 120 \|", done.stdout), done.stdout


def test_calculator_names_a_bad_input(tmp_path):
    (tmp_path / "points.csv").write_text("p,depth,t\n8,2,1.0\n")
    done = tessera_sweep_command("sort-middle", "fit", str(tmp_path / "points.csv"))
    assert done.returncode == 2 and "missing column(s) d" in done.stderr
    done = tessera_sweep_command("sort-middle", "table", "--alpha-us", "-1")
    assert done.returncode == 2 and "--alpha-us" in done.stderr
    done = tessera_sweep_command("sort-middle", "table", "--p", "0")
    assert done.returncode == 2 and "--p 0" in done.stderr
    done = tessera_sweep_command("sort-middle", "time", "--p", "8", "--d", "0")
    assert done.returncode == 2 and "d positive" in done.stderr
