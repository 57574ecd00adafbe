"""The figures an experiment's table computes from a run's statistics ("value"
columns: frame_time_ms, speedup, energy_ratio, the study's quantities, ...)
and the run's result they read (RunResult: stats.json's statistics and
effective configuration). docs/experiments.md lists every figure."""

import math


class RunError(Exception):
    """A soc_sim run failed or gave statistics the table cannot use (status 1)."""


# The array back ends' program keys; the other back ends run no array program.
PROGRAM_KEYS = {"ap-tile": "ap.tile.program", "ap-pixel": "ap.pixel.program"}


class RunResult:
    """One run's statistics and effective configuration (its stats.json), as the figures read them."""

    def __init__(self, run, stats_path, document, wall_seconds=0.0):
        self.label = run["label"]
        self.base_label = run.get("base_label", run["label"])
        self.baseline = run.get("baseline")
        self.backend = run["backend"]
        self.shows_frames = run.get("shows_frames", True)
        self.stats_path = stats_path
        self.stats = document["stats"]
        self.config = document["config"]
        self.wall_seconds = wall_seconds
        # The host model and array program the run used, as its own configuration says ("-": no array program).
        self.host = str(self.config.get("host", {}).get("model", "native"))
        key = PROGRAM_KEYS.get(self.backend)
        self.program = "-"
        if key and run.get("backend_program", True):
            node = self.config
            for part in key.split("."):
                node = node.get(part, {}) if isinstance(node, dict) else {}
            self.program = node if isinstance(node, str) and node else "-"


# ---------------------------------------------------------------------------
# Figures computed from a run's statistics ("value" columns). Each takes the
# run's result, the column and every run's result (for figures relative to
# another run) and returns a number, or None where the run has no such
# figure. docs/experiments.md lists them.


def stat(result, path, required=True):
    """The statistic at the dotted `path` of stats.json's "stats"."""
    node = result.stats
    for part in path.split("."):
        if not isinstance(node, dict) or part not in node:
            if required:
                raise RunError(f"run '{result.label}' has no statistic '{path}' in {result.stats_path}")
            return None
        node = node[part]
    if isinstance(node, bool) or not isinstance(node, (int, float)):
        raise RunError(f"run '{result.label}': statistic '{path}' is not a number in {result.stats_path}")
    return node


def stats_required(column):
    """Whether the column's statistics must exist ("required", default true): false tolerates a run that lacks one
    (an empty cell), e.g. a block that only exists with a switch on."""
    return column.get("required", True)


def frames_drawn(result):
    """The divisor of "per frame": the frames shown; a run of an application that shows none (study_shading, ...)
    counts as one, so its figures "per frame" are per run."""
    return len(result.stats["frames"]) if result.shows_frames else 1


def frame_time_ms(result, column, results):
    """Mean simulated time per frame: the frames' render_ns (request to request), in ms."""
    frames = result.stats["frames"]
    if not frames:
        raise RunError(f"run '{result.label}' shows no frame, so it has no time per frame ({result.stats_path})")
    return sum(frame["render_ns"] for frame in frames) / len(frames) / 1e6


def frame_or_run_time_ms(result, column, results):
    """frame_time_ms for a scene; for a study application, which shows no frame, its whole host time
    (driver.study.total_ns), in ms."""
    if result.shows_frames:
        return frame_time_ms(result, column, results)
    return stat(result, "driver.study.total_ns") / 1e6


def renderer_section(result):
    """The path of the back end's statistics in stats.json: driver.ap_tile for ap-tile, ..."""
    return "driver." + result.backend.replace("-", "_")


HOST_PARTS = ("compute", "write", "read", "wait", "frame_out")


def host_time_ms(result, column, results):
    """One part (column "part": compute, write, read, wait or frame_out) of the host's time, in ms per frame: an
    array back end's host_<part>_ns (driver.ap_tile, driver.ap_pixel), or for a study application the whole run's
    driver.study.<part>_ns (frame_out: none, the study shows no frame)."""
    if result.shows_frames:
        path = f"{renderer_section(result)}.host_{column['part']}_ns"
    else:
        path = f"driver.study.{column['part']}_ns"
    value = stat(result, path, stats_required(column))
    return None if value is None else value / frames_drawn(result) / 1e6


def values_written_per_triangle(result, column, results):
    """Values the array's data lines carried into CMEM per triangle: the back end's values_written over its
    triangles (driver.ap_tile, driver.ap_pixel)."""
    section = renderer_section(result)
    written = stat(result, f"{section}.values_written", stats_required(column))
    triangles = stat(result, f"{section}.triangles", stats_required(column))
    if written is None or triangles is None:
        return None
    if triangles == 0:
        raise RunError(f"run '{result.label}': '{section}.triangles' is 0, so values per triangle is undefined")
    return written / triangles


def frames_per_second(result, column, results):
    """Frames per simulated second, from frame_time_ms."""
    return 1000.0 / frame_time_ms(result, column, results)


def energy_per_frame_mj(result, column, results):
    """Mean energy per frame of the energy model (tlm/power/README.md): the frames' own energy.total_j (request to
    request, start-up excluded), in mJ; for a study application, which shows no frame, the whole run's
    energy.total_j."""
    if result.shows_frames:
        frames = result.stats["frames"]
        if not frames:
            raise RunError(f"run '{result.label}' shows no frame, so it has no energy per frame ({result.stats_path})")
        if any(not isinstance(frame.get("energy", {}).get("total_j"), (int, float)) for frame in frames):
            raise RunError(f"run '{result.label}': a frame record has no energy.total_j in {result.stats_path}")
        return sum(frame["energy"]["total_j"] for frame in frames) / len(frames) * 1e3
    return stat(result, "energy.total_j") * 1e3


def baseline_result(result, column, results):
    """The run a relative figure compares `result` with: the run of the experiment's label column["baseline"]
    (before the host and the program are added to it), or the run's own "baseline" (a run doing other work than
    the column's baseline, e.g. more attributes), on the same host, with the same program if it has one."""
    name = result.baseline or column["baseline"]
    candidates = [r for r in results if r.base_label == name and r.host == result.host]
    if not candidates:
        raise RunError(f"run '{result.label}': no run '{name}' on host {result.host} to compare with")
    return next((r for r in candidates if r.program == result.program), candidates[0])


def energy_ratio(result, column, results):
    """The baseline run's energy_per_frame_mj over this run's (column "baseline": the run's label): how many times
    less energy this run spends on a frame (on the whole run for a study application)."""
    baseline = baseline_result(result, column, results)
    return energy_per_frame_mj(baseline, column, results) / energy_per_frame_mj(result, column, results)


def speedup(result, column, results):
    """The baseline run's frame_time_ms over this run's (column "baseline": the run's label)."""
    baseline = baseline_result(result, column, results)
    return frame_time_ms(baseline, column, results) / frame_time_ms(result, column, results)


AP_TILE_PASS_STAGES = ("fill", "depth", "colour", "texcoord")


def ap_tile_pass_cycles(result, column, results):
    """Array cycles of one ap-tile pass: the four pass stages' cycles over the passes (clears excluded)."""
    cycles = sum(stat(result, f"driver.ap_tile.cycles.{stage}") for stage in AP_TILE_PASS_STAGES)
    return cycles / stat(result, "driver.ap_tile.passes")


def ap_tile_pass_us(result, column, results):
    """ap_tile_pass_cycles at the array's clock (array.clock_mhz), in microseconds."""
    return ap_tile_pass_cycles(result, column, results) / config(result, "array.clock_mhz")


def ap_tile_passes_per_second(result, column, results):
    """The array's clock over ap_tile_pass_cycles: passes per second with the host never in the way."""
    return config(result, "array.clock_mhz") * 1e6 / ap_tile_pass_cycles(result, column, results)


def ap_tile_cus_per_pass(result, column, results):
    """CUs with a triangle, per pass: triangle records (driver.ap_tile.cu_triangles) over passes."""
    return stat(result, "driver.ap_tile.cu_triangles") / stat(result, "driver.ap_tile.passes")


def ap_tile_peak_triangles_per_second(result, column, results):
    """ap_tile_cus_per_pass x ap_tile_passes_per_second: one triangle per busy CU per pass."""
    return ap_tile_cus_per_pass(result, column, results) * ap_tile_passes_per_second(result, column, results)


def study_shades_per_second(result, column, results):
    """Shades per second of host time, per result: driver.study.shades over driver.study.total_ns (inputs loaded,
    shades computed or sent, run and read back)."""
    return stat(result, "driver.study.shades") / (stat(result, "driver.study.total_ns") * 1e-9)


def study_shades_per_second_per_pass(result, column, results):
    """Shades per second of array time alone: driver.study.shades over driver.study.array_cycles at the array's
    clock (array.clock_mhz), the host's traffic not counted."""
    seconds = stat(result, "driver.study.array_cycles") / (config(result, "array.clock_mhz") * 1e6)
    return stat(result, "driver.study.shades") / seconds


def patch_break_even(result, column, results):
    """The smallest patch of the column's "shape" (line or square) at which the baseline run (column "baseline",
    the host) takes longer than this run: driver.study.patch.<shape>.<pixels>_ns compared size by size; inf when
    the baseline is faster at every size measured."""
    baseline = baseline_result(result, column, results)
    sizes = sorted(int(key[: -len("_ns")]) for key in result.stats["driver"]["study"]["patch"][column["shape"]])
    for pixels in sizes:
        path = f"driver.study.patch.{column['shape']}.{pixels}_ns"
        if stat(baseline, path) > stat(result, path):
            return float(pixels)
    return math.inf


def forward_texture_steps(result):
    """The programs' texel steps (driver.study.array_steps): a step takes every CU one texel border on, whatever the
    CUs with a line; one line per CU, a run's texture_size + 1 borders; van Sinten's chain, a run's rounds (a border
    per CU each)."""
    return stat(result, "driver.study.array_steps")


def forward_texture_division_cycles(result, column, results):
    """Array cycles per texel step in the border's stage (texcoord: the numerator and denominator stepped, the
    border divided): a texel border of every CU's line at once."""
    return stat(result, "array.cycles.texcoord") / forward_texture_steps(result)


def forward_texture_contribution_cycles(result, column, results):
    """Array cycles per texel step in the contribution's stages (shade: the F factors and scalings; transfer: the
    window's sums and the pixel it leaves)."""
    return (stat(result, "array.cycles.shade") + stat(result, "array.cycles.transfer")) / forward_texture_steps(result)


def forward_texture_texels_per_second(result, column, results):
    """Texel borders per second of the array's own time: driver.study.array_borders over driver.study.array_cycles
    at the array's clock (array.clock_mhz), one line per CU, the host's transfers not counted."""
    seconds = stat(result, "driver.study.array_cycles") / (config(result, "array.clock_mhz") * 1e6)
    return stat(result, "driver.study.array_borders") / seconds


def forward_texture_scalings_per_texel(result, column, results):
    """The scalings per texel step of Eq. 6 as the array ran them (F a texel): its multiplications (array.mix.mul,
    one broadcast instruction for every CU) over two (each scaling is two 16 x 8 multiplications), per step."""
    return stat(result, "array.mix.mul") / 2 / forward_texture_steps(result)


def forward_texture_lookups_per_texel(result, column, results):
    """The table lookups per texel step (Eq. 6's F a texel when the factors are looked up): array.mix.lut (one
    broadcast lut for every CU) per step; None on an array without the table (array.features.lut off, no
    array.mix.lut) when the column's statistics are not required."""
    lookups = stat(result, "array.mix.lut", stats_required(column))
    return None if lookups is None else lookups / forward_texture_steps(result)


def forward_texture_lut_stall_cycles(result, column, results):
    """Array cycles per texel step the AC waited for the lookup table's ports (array.lut.stall_cycles: lockstep,
    ceil(CUs / ports) - 1 per lut; skewed, the waits of a lut issued while every port is held); None on an array
    without the table when the column's statistics are not required."""
    stalls = stat(result, "array.lut.stall_cycles", stats_required(column))
    return None if stalls is None else stalls / forward_texture_steps(result)


def forward_texture_polyphase_ms(result, column, results):
    """A dedicated polyphase unit resampling one texel a cycle at the array's clock (array.clock_mhz): the warp's
    texel borders (driver.study.array_borders) over that clock, in ms per warp (the frames' mean)."""
    return stat(result, "driver.study.array_borders") / frames_drawn(result) / (config(result, "array.clock_mhz") * 1e3)


def array_ms_per_frame(result, column, results):
    """The array's own time per frame: its cycles (array.cycles.total, every program, z-buffer port stalls and issue
    skew included) at its clock (array.clock_mhz), in ms per frame. What a renderer's frame rate would be if the array
    alone set it (the host's geometry and set-up hidden): the measure of Davila et al.'s frames per second."""
    return stat(result, "array.cycles.total") / frames_drawn(result) / (config(result, "array.clock_mhz") * 1e3)


def array_frames_per_second(result, column, results):
    """1000 over array_ms_per_frame: frames per second of the array's own time."""
    return 1000.0 / array_ms_per_frame(result, column, results)


def triangles_per_frame(result):
    """The triangles the application submitted per frame: the driver's vertex cache sees each triangle's three
    indices once (driver.vertex_cache hits + misses over 3), culled and clipped triangles included."""
    cache = stat(result, "driver.vertex_cache.hits") + stat(result, "driver.vertex_cache.misses")
    return cache / 3 / frames_drawn(result)


def array_triangles_per_second(result, column, results):
    """triangles_per_frame x array_frames_per_second: the submitted triangles a second of the array's own time (Davila
    et al.'s T/s)."""
    return triangles_per_frame(result) * array_frames_per_second(result, column, results)


def zbuf_port_busy_percent(result, column, results):
    """The z-buffer unit's ports' busy share of the array's time: cycles in which a port took a pixel
    (zbuf.port_cycles) over array.cycles.total, in percent; None without the unit when the column's statistics are
    not required."""
    port = stat(result, "zbuf.port_cycles", stats_required(column))
    return None if port is None else 100.0 * port / stat(result, "array.cycles.total")


# ---------------------------------------------------------------------------
# The study's quantities (docs/spec/study_programs.md, "The study's test cases"): what the study's own figure
# covered, for the "study" tables. A column names the test's quantity ("quantity"); each back end's part of it:
#
#   rasterization  arm: the rasterization phase without the clears (host_rasterization_ns - host_clear_ns of
#                  the frame records); ap-tile: the array's passes (the cycles of its pass stages), per frame
#   pass           ap-tile: the array's cycles of one pass, at its clock
#   processing     the frame without its frame out to the display: arm, render_ns - host_presenting_ns (the copy
#                  to the display port); an array back end, render_ns - host_frame_out_ns
#   shading        arm: the shading loop (driver.study.compute_ns); ap-pixel: the array's passes
#                  (driver.study.array_cycles), the host's CIU transfers apart
#
# The study's energy is the energy of the units the board measured (the ARM922T for arm; the array controller,
# the CIU and the CUs for an array back end) over that interval: for the array's passes exactly, from
# stats.energy.array_stages (each stage's own activity and time); otherwise from the frame records or the run.

QUANTITIES = ("rasterization", "pass", "processing", "shading")
ARRAY_UNITS = ("array_controller", "ciu", "cu_array")


def frames_mean(result, figure):
    """The mean over the frames of a frame record's figure: `figure` is a function of the record."""
    frames = result.stats["frames"]
    if not frames:
        raise RunError(f"run '{result.label}' shows no frame ({result.stats_path})")
    try:
        return sum(figure(frame) for frame in frames) / len(frames)
    except KeyError as error:
        raise RunError(f"run '{result.label}': a frame record lacks {error} in {result.stats_path}") from error


def array_pass_stages(result):
    """The stages of the array's passes: ap-tile's four (its clears are not passes); every stage ap-pixel ran."""
    if result.backend == "ap-tile":
        return AP_TILE_PASS_STAGES
    return tuple(result.stats.get("energy", {}).get("array_stages", {}))


def study_divisor(result, quantity):
    """What the study's figure is per: a pass (pass), a frame (rasterization, processing), the run (shading)."""
    if quantity == "pass":
        return stat(result, "driver.ap_tile.passes")
    if quantity == "shading":
        return 1
    return frames_drawn(result)


def unsupported(result, quantity):
    return RunError(
        f"run '{result.label}': the study's {quantity} figure is not defined for back end '{result.backend}'"
    )


def study_time_ms(result, column, results):
    """The study's time (column "quantity", above), in ms."""
    quantity = column["quantity"]
    backend = result.backend
    if quantity == "processing":
        if backend == "arm":
            return frames_mean(result, lambda f: f["render_ns"] - f["driver"]["host_presenting_ns"]) / 1e6
        return frames_mean(result, lambda f: f["render_ns"] - f["driver"]["host_frame_out_ns"]) / 1e6
    if backend == "arm" and quantity == "rasterization":
        return frames_mean(result, lambda f: f["driver"]["host_rasterization_ns"] - f["driver"]["host_clear_ns"]) / 1e6
    if backend == "arm" and quantity == "shading":
        return stat(result, "driver.study.compute_ns") / 1e6
    if backend == "ap-tile" and quantity in ("rasterization", "pass"):
        cycles = sum(stat(result, f"driver.ap_tile.cycles.{stage}") for stage in AP_TILE_PASS_STAGES)
    elif backend == "ap-pixel" and quantity == "shading":
        cycles = stat(result, "driver.study.array_cycles")
    else:
        raise unsupported(result, quantity)
    return cycles / (config(result, "array.clock_mhz") * 1e6) / study_divisor(result, quantity) * 1e3


def static_watts(result, units):
    """The static powers of `units` (power.<unit>.static_mw of the run's configuration), in W."""
    return sum(config(result, f"power.{unit}.static_mw") for unit in units) / 1e3


def host_executing_watts(result):
    """The ARM922T's average power while it executes (its busy and stalled cycles, idle ones left out) over the
    run, in W: the host's power over an interval in which it never idles, as the study's ARM loops."""
    events = result.stats.get("energy", {}).get("units", {}).get("host", {}).get("events", {})
    try:
        joules = events["busy_cycles"]["j"] + events["stalled_cycles"]["j"]
        cycles = events["busy_cycles"]["count"] + events["stalled_cycles"]["count"]
    except KeyError as error:
        raise RunError(
            f"run '{result.label}': stats.energy.units.host.events lacks {error} in {result.stats_path}"
        ) from error
    seconds = cycles / (stat(result, "host.clock_mhz") * 1e6)
    return joules / seconds + static_watts(result, ("host",))


def study_energy_mj(result, column, results):
    """The study's energy (column "quantity"): the energy of the units the board measured over the study's
    interval, in mJ. The array's passes: the array_stages energies of the pass stages (exact). An array back end's
    processing: the frames' array-unit energy less their static power over the frame out (the array idles then).
    arm: host_executing_watts x the study's time: exact while a busy and a stalled cycle cost the same (the
    fitted defaults), since the ARM does not idle in the study's intervals."""
    quantity = column["quantity"]
    if result.backend == "arm":
        return host_executing_watts(result) * study_time_ms(result, column, results)
    if quantity == "processing":
        watts = static_watts(result, ARRAY_UNITS)
        return (
            frames_mean(
                result,
                lambda f: (
                    sum(f["energy"]["units"][unit]["total_j"] for unit in ARRAY_UNITS)
                    - watts * f["driver"]["host_frame_out_ns"] * 1e-9
                ),
            )
            * 1e3
        )
    study_time_ms(result, column, results)  # the quantity applies to the back end
    stages = result.stats.get("energy", {}).get("array_stages", {})
    missing = [stage for stage in array_pass_stages(result) if stage not in stages]
    if missing or not stages:
        raise RunError(
            f"run '{result.label}' has no statistic 'energy.array_stages.{(missing or ['*'])[0]}' in "
            f"{result.stats_path}"
        )
    joules = sum(stages[stage]["total_j"] for stage in array_pass_stages(result))
    return joules / study_divisor(result, quantity) * 1e3


def study_power_mw(result, column, results):
    """study_energy_mj over study_time_ms: the measured units' average power over the study's interval, in mW."""
    return study_energy_mj(result, column, results) / study_time_ms(result, column, results) * 1e3


def study_speedup(result, column, results):
    """The baseline run's study_time_ms over this run's (column "baseline")."""
    return study_time_ms(baseline_result(result, column, results), column, results) / study_time_ms(
        result, column, results
    )


def study_energy_ratio(result, column, results):
    """The baseline run's study_energy_mj over this run's (column "baseline")."""
    return study_energy_mj(baseline_result(result, column, results), column, results) / study_energy_mj(
        result, column, results
    )


def study_shades_per_second_of_study_time(result, column, results):
    """Shades per second of the study's time ("quantity": shading): driver.study.shades over study_time_ms."""
    return stat(result, "driver.study.shades") / (study_time_ms(result, column, results) * 1e-3)


COMPUTED = {
    function.__name__: function
    for function in (
        frame_time_ms,
        frame_or_run_time_ms,
        frames_per_second,
        speedup,
        energy_per_frame_mj,
        energy_ratio,
        ap_tile_pass_cycles,
        ap_tile_pass_us,
        ap_tile_passes_per_second,
        ap_tile_cus_per_pass,
        ap_tile_peak_triangles_per_second,
        study_shades_per_second,
        study_shades_per_second_per_pass,
        patch_break_even,
        host_time_ms,
        values_written_per_triangle,
        study_time_ms,
        study_energy_mj,
        study_power_mw,
        study_speedup,
        study_energy_ratio,
        study_shades_per_second_of_study_time,
        forward_texture_division_cycles,
        forward_texture_contribution_cycles,
        forward_texture_texels_per_second,
        forward_texture_scalings_per_texel,
        forward_texture_lookups_per_texel,
        forward_texture_lut_stall_cycles,
        forward_texture_polyphase_ms,
        array_ms_per_frame,
        array_frames_per_second,
        array_triangles_per_second,
        zbuf_port_busy_percent,
    )
}
# A figure of the table rather than of one run: another column's value (column "of") of the baseline run (column
# "baseline") against this run's, as the percentage this run saves, (baseline - this) / baseline x 100: any
# column, a time, an energy or a byte count, gets its saving against a baseline without a figure of its own.
SAVING_PERCENT = "saving_percent"


def saving_percent(baseline_value, value, result, column):
    """What this run saves of the column "of" against the baseline run, in percent; None where either lacks it."""
    if baseline_value is None or value is None:
        return None
    if baseline_value == 0:
        raise RunError(f"run '{result.label}': the baseline's '{column['of']}' is 0, so a saving is undefined")
    return (baseline_value - value) / baseline_value * 100


BASELINE_VALUES = (
    "speedup",
    "energy_ratio",
    "patch_break_even",
    "study_speedup",
    "study_energy_ratio",
    SAVING_PERCENT,
)
QUANTITY_VALUES = (
    "study_time_ms",
    "study_energy_mj",
    "study_power_mw",
    "study_speedup",
    "study_energy_ratio",
    "study_shades_per_second_of_study_time",
)


def config(result, key):
    """The effective configuration's value of the dotted `key` (stats.json's "config")."""
    node = result.config
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            raise RunError(f"run '{result.label}' has no configuration key '{key}' in {result.stats_path}")
        node = node[part]
    return node
