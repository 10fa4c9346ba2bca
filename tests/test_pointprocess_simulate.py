"""paperlib.pointprocess.simulate.rmh: Metropolis-Hastings of Strauss hard-core processes.

Four kinds of evidence:

* the numba kernel (cell grid) equals the pure-Python O(n) reference step for step, on
  every move type, window kind, the torus, an intensity map and array growth;
* its conditional intensity equals the model's own vectorised one (models.py);
* known answers: Poisson mean counts beta * integral of the map over W;
* spatstat's ``rmh`` (fixture tests/oracle/rmh.json, made by tests/oracle/spatstat_rmh.R):
  mean counts per type and mean border-corrected L on a fixed r grid agree within Monte
  Carlo error. The test: at each statistic, |mean_ours - mean_spatstat| < z * SE with
  SE = sqrt(sd_ours^2 / N_ours + sd_spatstat^2 / N_spatstat), z = 3 for the counts and
  z = 3.5 for each of the 15 (correlated) r values of an L curve (Bonferroni-style
  allowance for looking at 15 values at once).
"""

import dataclasses
import json
import warnings
from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import Polygon

from paperlib.pointprocess import MultiStraussHard, PointPattern, Poisson, StraussHard, Window
from paperlib.pointprocess import _kernels, simulate
from paperlib.pointprocess._reference import reference_steps
from paperlib.pointprocess.simulate import rmh
from paperlib.pointprocess.summary import Lcross, Lest

ORACLE = json.loads((Path(__file__).parent / "oracle" / "rmh.json").read_text())
R_FINE = np.linspace(0.0, 0.2, 513)  # the R script's grid; it keeps every 32nd value
R_KEPT = slice(32, None, 32)
UNIT = Window.rectangle()

THREE_TYPES = MultiStraussHard(
    [40, 30, 60], gamma=[[0.3, 0.5, 0.8], [0.5, 0.2, 0.6], [0.8, 0.6, 0.4]], r=0.09,
    hc=[[0.03, 0.015, 0.01], [0.015, 0.04, 0.015], [0.01, 0.015, 0.02]],
)


def strauss_from(par) -> MultiStraussHard:
    return StraussHard(par["beta"], par["gamma"], par["r"], par["hc"], closed=False)  # rmh: d < r, d < hc


def multi_from(par) -> MultiStraussHard:
    return MultiStraussHard(par["beta"], gamma=par["gamma"], r=par["r"], hc=par["hc"])


def seeds(n, seed):
    return [np.random.default_rng(child) for child in np.random.SeedSequence(seed).spawn(n)]


# ---------------------------------------------------------------------------- kernel == reference


def polygon_window():
    return Window.polygon(Polygon([(0, 0), (1, 0), (1, 0.4), (0.4, 0.4), (0.4, 1), (0, 1)]))  # an L shape


def mask_window():
    yy, xx = np.mgrid[0:40, 0:40]
    return Window.mask((xx - 19.5) ** 2 + (yy - 19.5) ** 2 < 18**2)  # a disc of pixels


def gradient_map():
    return np.tile(np.clip(np.linspace(-0.5, 1.0, 25), 0.0, None), (20, 1))  # 0 for x < 9/25, then up to 1


# Chains start empty, so every case scans all points while n * M <= DENSE_SCAN_MAX; these
# cases end far above it, so their grid scans (plane, torus, torus with wrap-around rows) run too.
GRID_CASES = ("shifts, 3 types, ptypes", "torus", "torus of 2 x 2 cells")
CASES = {
    "birth-death, closed ties": dict(model=StraussHard(120, 0.3, 0.08, 0.02)),
    "shifts, 3 types, ptypes": dict(model=THREE_TYPES, p=0.5, q=0.6, ptypes=[0.5, 0.2, 0.3]),
    "fixed count, fixed types": dict(model=THREE_TYPES, p=1.0, fixall=True, start=[10, 10, 10]),
    "torus": dict(model=THREE_TYPES, periodic=True, p=0.3),
    "torus of 2 x 2 cells": dict(model=MultiStraussHard([100, 10], gamma=[[1.0, 0.9], [0.9, 0.5]], r=0.4,
                                                        hc=[[0.01, 0.0], [0.0, 0.05]]), periodic=True, p=0.5),
    "polygon window, hard core only": dict(model=MultiStraussHard([150], gamma=0.0, r=0.06, hc=0.03),
                                           window=polygon_window()),
    "mask window and intensity map": dict(model=THREE_TYPES, window=mask_window(), intensity_map=gradient_map(),
                                          p=0.4),
}


def run_both(model, window=UNIT, T=10_000, seed=7, **options):
    fast, fast_trace = simulate._simulate(model, window, T, stepper=_kernels.mh_steps, trace=True, rng=seed, **options)
    slow, slow_trace = simulate._simulate(model, window, T, stepper=reference_steps, trace=True, rng=seed, **options)
    return fast, fast_trace, slow, slow_trace


@pytest.mark.parametrize("case", list(CASES))
def test_kernel_matches_reference_step_for_step(case):
    fast, fast_trace, slow, slow_trace = run_both(**CASES[case])
    first_difference = np.flatnonzero(fast_trace != slow_trace)[:1]
    assert first_difference.size == 0, f"outcomes differ from step {first_difference}"
    assert fast == slow  # same points, bit for bit, in the same order
    accepted = set(np.unique(fast_trace[fast_trace > 0]).tolist())
    p = CASES[case].get("p", 0.0)
    expected = {_kernels.SHIFT} if p == 1 else {_kernels.BIRTH, _kernels.DEATH} | ({_kernels.SHIFT} if p else set())
    assert accepted == expected, "every move type of the case was exercised"
    if case in GRID_CASES:
        assert fast.n * fast.n_types > 1.5 * _kernels.DENSE_SCAN_MAX


def test_kernel_matches_reference_through_array_growth(monkeypatch):
    monkeypatch.setattr(simulate, "_MIN_POINT_CAPACITY", 1)
    monkeypatch.setattr(simulate, "_MIN_CELL_CAPACITY", 1)
    monkeypatch.setattr(simulate, "_POINTS_PER_CELL", 30.0)  # crowded cells overflow often
    model = MultiStraussHard([150, 100], gamma=0.7, r=0.05, hc=0.005)
    fast, fast_trace, slow, slow_trace = run_both(model, T=3000, p=0.3)
    assert np.array_equal(fast_trace, slow_trace) and fast == slow
    assert fast.n > 100


def test_kernel_matches_reference_from_a_start_violating_the_hard_core():
    start = PointPattern([[0.5, 0.5], [0.51, 0.5], [0.2, 0.2]], UNIT)
    with pytest.warns(UserWarning, match="zero density: 2 of its 3 points"):
        fast, fast_trace, slow, slow_trace = run_both(StraussHard(50, 0.5, 0.1, 0.05), start=start, T=500)
    assert np.array_equal(fast_trace, slow_trace) and fast == slow


# From a few 1e4 points the cell records outgrow the caches and the kernel prefetches the
# cells of the coming steps (_kernels, "Data layout" and "Memory"). These cases check that
# path, at spatstat's moves, against slow paths without it: the pure-Python reference, and
# the same kernel on a single cell (an O(n) scan of one record row, too small to prefetch).


def strauss_family(n):
    r = 0.08 * np.sqrt(50 / n)  # the benchmark's family: about 0.93 n points at equilibrium
    return StraussHard(2 * n, 0.3, r, r / 4, closed=False)


LARGE_CASES = {
    "StraussHard, 5e4 points": dict(model=strauss_family(50_000), n=50_000),
    "StraussHard, 5e4 points, torus": dict(model=strauss_family(50_000), n=50_000, periodic=True),
    "MultiStraussHard, 3 types, 5e4 points": dict(
        model=MultiStraussHard([32_000, 24_000, 48_000], gamma=[[0.3, 0.5, 0.8], [0.5, 0.2, 0.6], [0.8, 0.6, 0.4]],
                               r=0.0032, hc=[[0.0013, 0.0006, 0.0005], [0.0006, 0.0016, 0.0006],
                                             [0.0005, 0.0006, 0.001]]),
        n=50_000),
}


def large_start(case):
    options = LARGE_CASES[case]
    return rmh(options["model"], UNIT, 30 * options["n"], periodic=options.get("periodic", False), rng=0)


def run_on_one_cell(model, start, T, seed, **options):
    setup = simulate._prepare(model, UNIT, T, ptypes=None, fixall=False, intensity_map=None, **options)
    grid = setup.grid._replace(ncx=1, ncy=1, x_scale=1.0 / setup.grid.width, y_scale=1.0 / setup.grid.height)
    chain = simulate._Chain(dataclasses.replace(setup, grid=grid), start.points, start.marks.astype(np.int64))
    trace = chain.run(T, np.random.default_rng(seed), _kernels.mh_steps, trace=True)
    return chain.pattern(), trace, chain.state


@pytest.mark.parametrize("case", list(LARGE_CASES))
def test_prefetching_kernel_matches_the_one_cell_scan_at_many_points(case):
    options = LARGE_CASES[case]
    model, periodic, start = options["model"], options.get("periodic", False), large_start(case)
    moves = dict(p=0.9, q=0.9, periodic=periodic)
    grid, grid_trace = simulate._simulate(model, UNIT, 20_000, stepper=_kernels.mh_steps, trace=True, start=start,
                                          rng=4, **moves)
    scan, scan_trace, scan_state = run_on_one_cell(model, start, 20_000, 4, **moves)
    assert np.array_equal(grid_trace, scan_trace) and grid == scan
    setup = simulate._prepare(model, UNIT, 1, ptypes=None, fixall=False, intensity_map=None, **moves)
    grid_state = simulate._Chain(setup, start.points, start.marks.astype(np.int64)).state
    assert grid_state.cell_points.nbytes >= _kernels.PREFETCH_MIN_BYTES > scan_state.cell_points.nbytes
    assert set(np.unique(grid_trace).tolist()) >= {-3, -2, -1, 1, 2, 3}


def test_prefetching_kernel_matches_the_reference_at_5e4_points():
    start = large_start("StraussHard, 5e4 points")
    fast, fast_trace, slow, slow_trace = run_both(strauss_family(50_000), T=400, seed=5, start=start, p=0.9, q=0.9)
    assert np.array_equal(fast_trace, slow_trace) and fast == slow
    assert (fast_trace == _kernels.SHIFT).sum() > 100


def test_cell_records_mirror_the_points_after_a_run():
    """Every point has exactly one record, in its cell, at the slot ``place`` names, with its values."""
    model = LARGE_CASES["MultiStraussHard, 3 types, 5e4 points"]["model"]
    setup = simulate._prepare(model, UNIT, 1, p=0.5, q=0.5, ptypes=None, fixall=False, periodic=False,
                              intensity_map=None)
    chain = simulate._Chain(setup, np.empty((0, 2)), np.empty(0, dtype=np.int64))
    chain.run(100_000, np.random.default_rng(6), _kernels.mh_steps)
    state, n = chain.state, chain.n
    assert n > 1000 and state.cell_count.sum() == n
    cells, slots = state.place[:n, 0], state.place[:n, 1]
    assert np.array_equal(cells, _kernels.cells_of(setup.grid, state.x[:n], state.y[:n]))
    assert np.all(slots < state.cell_count[cells])
    records = state.cell_points[cells, slots]
    assert np.array_equal(records, np.column_stack([state.x[:n], state.y[:n], state.mark[:n], np.arange(n)]))
    assert state.cell_points.ctypes.data % 64 == 0 and state.cell_points.shape[1] % 2 == 0  # aligned rows


@pytest.mark.parametrize("n_points", [20, 300], ids=["scan of all points", "grid scan"])
@pytest.mark.parametrize("closed", [False, True])
def test_conditional_intensity_matches_the_model(n_points, closed):
    rng = np.random.default_rng(3)
    model = MultiStraussHard(THREE_TYPES.beta, gamma=THREE_TYPES.gamma, r=THREE_TYPES.r, hc=THREE_TYPES.hc,
                             closed=closed)
    points, marks = rng.random((n_points, 2)) ** 2, rng.integers(0, 3, n_points)  # crowded near the origin
    setup = simulate._prepare(model, UNIT, 1, p=0.0, q=0.5, ptypes=None, fixall=False, periodic=False,
                              intensity_map=None)
    chain = simulate._Chain(setup, points, marks)
    locations = np.vstack([rng.random((500, 2)) ** 2, points])
    types = np.concatenate([rng.integers(0, 3, 500), marks])
    skips = np.concatenate([np.full(500, -1), np.arange(n_points)])  # at data points: lambda(x_i; x - x_i)
    ours = chain.conditional_intensities(locations, types, skips)
    expected = np.exp(model.log_conditional_intensity(locations, types, points, marks, exclude=skips))
    assert (expected == 0).any() and (expected > 0).any()
    np.testing.assert_allclose(ours, expected, rtol=1e-12, atol=0)


# ---------------------------------------------------------------------------- reproducibility


def test_same_seed_same_output_other_seed_differs():
    case = CASES["mask window and intensity map"]
    first, again, other = (rmh(case["model"], case["window"], 3000, intensity_map=case["intensity_map"], p=0.4, rng=seed)
                           for seed in (11, 11, 12))
    assert first == again and first != other
    assert first.categories == THREE_TYPES.categories and first.window == case["window"]


def test_progress_bar_and_generator_rng(capsys):
    rng = np.random.default_rng(5)
    pattern = rmh(StraussHard(50, 0.5, 0.1, 0.02), UNIT, 2000, rng=rng, progress=True)
    assert pattern.n > 0
    assert "rmh" in capsys.readouterr().err


# ---------------------------------------------------------------------------- known answers


def mean_within_three_standard_errors(counts, expected):
    """Poisson counts: variance = mean, so SE = sqrt(expected / N)."""
    counts = np.asarray(counts, dtype=float)
    standard_error = np.sqrt(np.asarray(expected) / len(counts))
    assert np.all(np.abs(counts.mean(axis=0) - expected) < 3 * standard_error), (counts.mean(axis=0), expected)


def test_poisson_mean_count_is_beta_times_area():
    counts = [rmh(Poisson(200), UNIT, 20_000, rng=rng).n for rng in seeds(100, 1)]
    mean_within_three_standard_errors(counts, 200.0)


def test_poisson_mean_counts_per_type_with_unequal_type_proposals():
    window = Window.rectangle((0, 2), (0, 1))
    model = Poisson([30, 90])
    counts = [rmh(model, window, 20_000, ptypes=[0.8, 0.2], rng=rng).counts for rng in seeds(100, 2)]
    mean_within_three_standard_errors(counts, [60.0, 180.0])


def test_poisson_with_intensity_map_on_a_mask_has_mean_beta_times_integral():
    window, image = mask_window(), gradient_map()
    # mask (40 x 40) and map (20 x 25) share the frame: integrate exactly on their common refinement
    fine = np.kron(window.mask_array, np.ones((1, 5))) * np.kron(image, np.ones((2, 8)))  # 40 x 200 cells
    expected = 250 * fine.sum() / fine.size
    patterns = [rmh(Poisson(250), window, 20_000, intensity_map=image, rng=rng) for rng in seeds(100, 3)]
    mean_within_three_standard_errors([pattern.n for pattern in patterns], expected)
    assert min(pattern.points[:, 0].min() for pattern in patterns) >= 9 / 25  # where the map is 0, no point


def test_poisson_on_a_polygon_has_mean_beta_times_polygon_area():
    window = polygon_window()
    counts = [rmh(Poisson(300), window, 20_000, rng=rng).n for rng in seeds(100, 4)]
    mean_within_three_standard_errors(counts, 300 * window.area)


def test_fixed_count_mode_keeps_the_counts():
    pattern = rmh(THREE_TYPES, UNIT, 5000, p=1.0, fixall=True, start=[7, 8, 9], rng=0)
    assert pattern.counts.tolist() == [7, 8, 9]
    assert rmh(THREE_TYPES, UNIT, 5000, p=1.0, start=24, rng=0).n == 24


def min_distances_by_type_pair(pattern, periodic):
    delta = np.abs(pattern.points[:, None, :] - pattern.points[None, :, :])
    if periodic:
        delta = np.minimum(delta, 1.0 - delta)  # unit square torus
    distance = np.hypot(delta[..., 0], delta[..., 1])
    np.fill_diagonal(distance, np.inf)
    m = pattern.n_types
    return np.array([[distance[np.ix_(pattern.marks == a, pattern.marks == b)].min(initial=np.inf)
                      for b in range(m)] for a in range(m)])


@pytest.mark.parametrize("periodic", [False, True])
def test_hard_cores_are_never_violated(periodic):
    for rng in seeds(5, 8):
        pattern = rmh(THREE_TYPES, UNIT, 20_000, p=0.5, periodic=periodic, rng=rng)
        assert np.all(min_distances_by_type_pair(pattern, periodic) >= THREE_TYPES.hc)


# ---------------------------------------------------------------------------- spatstat rmh


def assert_matches_spatstat(ours, oracle, n_oracle, z, what):
    ours = np.asarray(ours, dtype=float).reshape(len(ours), -1)
    mean, sd = ours.mean(axis=0), ours.std(axis=0, ddof=1)
    oracle_mean, oracle_sd = np.atleast_1d(oracle["mean"]), np.atleast_1d(oracle["sd"])
    standard_error = np.sqrt(sd**2 / len(ours) + oracle_sd**2 / n_oracle)
    difference = np.abs(mean - oracle_mean)
    assert np.all(difference <= z * standard_error + 1e-12), (
        f"{what}: ours {mean}, spatstat {oracle_mean}, |difference| / SE = {difference / standard_error}")


def border_L(pattern):
    return Lest(pattern.unmark(), r=R_FINE, correction="border")["border"].to_numpy()[R_KEPT]


def test_oracle_grid_is_the_one_we_use():
    np.testing.assert_allclose(ORACLE["r"], R_FINE[R_KEPT], rtol=0, atol=1e-15)


@pytest.mark.parametrize("moves", [dict(), dict(p=0.9, q=0.5, start=50)], ids=["birth-death", "spatstat moves"])
def test_strausshard_matches_spatstat_rmh(moves):
    oracle = ORACLE["StraussHard"]
    model = strauss_from(oracle["model"])
    patterns = [rmh(model, UNIT, 30_000, rng=rng, **moves) for rng in seeds(200, 20)]
    assert_matches_spatstat([p.n for p in patterns], oracle["counts"], oracle["nsim"], 3.0, "counts")
    assert_matches_spatstat([border_L(p) for p in patterns], oracle["L"], oracle["nsim"], 3.5, "L")


def test_multistrausshard_matches_spatstat_rmh():
    oracle = ORACLE["MultiStraussHard"]
    model = multi_from(oracle["model"])
    patterns = [rmh(model, UNIT, 30_000, rng=rng) for rng in seeds(200, 21)]
    assert_matches_spatstat([p.counts for p in patterns], oracle["counts"], oracle["nsim"], 3.0, "counts per type")
    assert_matches_spatstat([border_L(p) for p in patterns], oracle["L"], oracle["nsim"], 3.5, "L")
    cross = [Lcross(p, "0", "1", r=R_FINE, correction="border")["border"].to_numpy()[R_KEPT] for p in patterns]
    assert_matches_spatstat(cross, oracle["Lcross_0_1"], oracle["nsim"], 3.5, "Lcross(0, 1)")


# ---------------------------------------------------------------------------- bad input


MODEL = StraussHard(100, 0.5, 0.1, 0.02)


@pytest.mark.parametrize("T", [0, -5, 1.5, "100", True, float("nan")])
def test_bad_number_of_steps(T):
    with pytest.raises(ValueError, match="T"):
        rmh(MODEL, UNIT, T)


@pytest.mark.parametrize(
    "options, message",
    [
        (dict(p=1.5), "p"),
        (dict(q=0.0), "q"),
        (dict(q=1.0), "q"),
        (dict(ptypes=[0.5, 0.5]), "ptypes"),
        (dict(ptypes=[1.2]), "ptypes must sum to 1"),
        (dict(fixall=True), "fixall"),
        (dict(p=1.0), "fixed-count mode"),
        (dict(start=PointPattern([[1.5, 0.5]], Window.rectangle((0, 2)))), "outside the synthesis window"),
        (dict(start=PointPattern([[0.2, 0.5], [0.7, 0.5]], UNIT, marks=[0, 1])), "start marks"),
        (dict(start=2.5), "start must be"),
        (dict(start=[-1]), "start must be"),
        (dict(intensity_map=-np.ones((4, 4))), "intensity_map"),
        (dict(intensity_map=np.full((4, 4), np.nan)), "intensity_map"),
        (dict(intensity_map=np.ones(4)), "2-D"),
        (dict(intensity_map=np.zeros((4, 4))), "zero everywhere"),
        (dict(intensity_map="dark"), "intensity_map"),
    ],
)
def test_bad_options(options, message):
    with pytest.raises(ValueError, match=message):
        rmh(MODEL, UNIT, 10, **options)


def test_bad_windows_and_models():
    with pytest.raises(ValueError, match="rectangular"):
        rmh(MODEL, polygon_window(), 10, periodic=True)
    with pytest.raises(ValueError, match="half"):
        rmh(StraussHard(10, 0.5, 0.3, 0.1), Window.rectangle((0, 1), (0, 0.5)), 10, periodic=True)
    with pytest.raises(ValueError, match="not integrable"):
        rmh(StraussHard(10, 1.5, 0.1, 0.0), UNIT, 10)
    with pytest.raises(ValueError, match="admissible"):
        Window.mask(np.zeros((5, 5), dtype=bool))  # a mask without an admissible cell
    with pytest.raises(ValueError, match="gamma"):
        StraussHard(10, -0.5, 0.1, 0.02)
    with pytest.raises(ValueError, match="hc <= r"):
        StraussHard(10, 0.5, 0.1, 0.2)
    with pytest.raises(TypeError, match="MultiStraussHard"):
        rmh("strauss", UNIT, 10)
    with pytest.raises(TypeError, match="Window"):
        rmh(MODEL, (0, 1), 10)


def test_gamma_above_one_is_fine_with_hard_cores():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pattern = rmh(StraussHard(50, 1.5, 0.1, 0.03), UNIT, 5000, rng=0)
    assert min_distances_by_type_pair(pattern, False).min() >= 0.03
