"""Summary functions (Kest, Lest, Kcross, Lcross, pcf) against spatstat and known answers.

The spatstat values come from ``tests/oracle/summary.json``, written by
``tests/oracle/spatstat_summary.R`` (R is not needed here). Function values there carry 11
significant digits, so agreement to ``RTOL = 1e-8`` relative is a real test: the estimates
(tie rules included) are the same as spatstat's up to rounding.
"""

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import shapely

from paperlib.pointprocess import PointPattern, Window, _pairs, summary
from paperlib.pointprocess.summary import Kcross, Kest, Lcross, Lest, default_r, default_rmax, pcf

ORACLE = json.loads((Path(__file__).parent / "oracle" / "summary.json").read_text())
DATASETS = ORACLE["datasets"]
RTOL = 1e-8
CORRECTION_COLUMNS = ("un", "border", "trans", "iso")


# ---------------------------------------------------------------------------- fixtures as objects


def floats(values) -> np.ndarray:
    """Fixture numbers (exact ones are written as 17-digit strings; NA as null) as float64."""
    return np.array([np.nan if v is None else float(v) for v in values])


def window_from(spec) -> Window:
    if spec["type"] == "rectangle":
        return Window.rectangle(floats(spec["xrange"]), floats(spec["yrange"]))
    rings = [np.column_stack([floats(ring["x"]), floats(ring["y"])]) for ring in spec["rings"]]
    # spatstat: outer boundaries anticlockwise, holes clockwise
    shells = [ring for ring in rings if shapely.is_ccw(shapely.linearrings(ring))]
    holes = [ring for ring in rings if not shapely.is_ccw(shapely.linearrings(ring))]
    assert len(shells) == 1
    return Window.polygon(shapely.Polygon(shells[0], holes))


def pattern_from(spec) -> PointPattern:
    points = np.column_stack([floats(spec["x"]), floats(spec["y"])])
    window = window_from(spec["window"])
    if "marks" not in spec:
        return PointPattern(points, window)
    categories = spec["categories"]
    return PointPattern(points, window, marks=[categories.index(m) for m in spec["marks"]], categories=categories)


def fixture_rows(table: dict, n_rows: int) -> list:
    """Rows of our full table that the fixture kept (every ``every``-th, and the last)."""
    return sorted(set(range(0, n_rows, table["every"])) | {n_rows - 1})


def assert_matches(ours: pd.DataFrame, table: dict, columns, *, rtol=RTOL, atol=0.0):
    rows = fixture_rows(table, len(ours))
    np.testing.assert_array_equal(ours["r"].to_numpy()[rows], floats(table["r"]))
    for column in columns:
        expected = floats(table[column])
        np.testing.assert_allclose(ours[column].to_numpy()[rows], expected, rtol=rtol, atol=atol,
                                   equal_nan=True, err_msg=f"column {column}")


@pytest.fixture(scope="module")
def amacrine():
    return pattern_from(DATASETS["amacrine"]["pattern"])


@pytest.fixture(scope="module")
def polygon_case():
    case = ORACLE["polygon"]
    return case, pattern_from(case["pattern"])


# ---------------------------------------------------------------------------- K and L against spatstat


@pytest.mark.parametrize("name", ["cells", "redwood", "swedishpines"])
def test_kest_matches_spatstat_on_its_default_grid(name):
    data = DATASETS[name]
    ours = Kest(pattern_from(data["pattern"]), correction="all")
    assert list(ours.columns) == ["r", "theo", *CORRECTION_COLUMNS]
    assert len(ours) == 513
    assert_matches(ours, data["Kest"], CORRECTION_COLUMNS)


@pytest.mark.parametrize("name", ["cells", "redwood", "swedishpines"])
def test_lest_matches_spatstat_off_the_tie_values(name):
    table = DATASETS[name]["Lest_offgrid"]
    ours = Lest(pattern_from(DATASETS[name]["pattern"]), r=floats(table["r"]), correction="all")
    np.testing.assert_array_equal(ours["theo"], ours["r"])
    assert_matches(ours, table, CORRECTION_COLUMNS)


@pytest.mark.parametrize("name", ["cells", "redwood", "swedishpines"])
def test_kest_on_an_uneven_grid_follows_spatstats_histogram_code(name):
    # d < r counting, lagged border eligibility, trans undefined from the short side on
    table = DATASETS[name]["Kest_uneven"]
    ours = Kest(pattern_from(DATASETS[name]["pattern"]), r=floats(table["r"]), correction="all")
    assert_matches(ours, table, CORRECTION_COLUMNS)


@pytest.mark.parametrize("name", ["cells", "redwood", "swedishpines"])
def test_kest_border_alone_uses_spatstats_border_engine(name):
    table = DATASETS[name]["Kest_border_only"]
    ours = Kest(pattern_from(DATASETS[name]["pattern"]), correction="border")
    assert list(ours.columns) == ["r", "theo", "border"]
    assert_matches(ours, table, ["border"])


@pytest.mark.parametrize("i, j", [("on", "off"), ("off", "on"), ("on", "on")])
def test_kcross_matches_spatstat(amacrine, i, j):
    ours = Kcross(amacrine, i, j, correction="all")
    assert_matches(ours, DATASETS["amacrine"][f"Kcross_{i}_{j}"], CORRECTION_COLUMNS)


@pytest.mark.parametrize("i, j", [("on", "off"), ("off", "on"), ("on", "on")])
def test_lcross_matches_spatstat_off_the_tie_values(amacrine, i, j):
    table = DATASETS["amacrine"][f"Lcross_offgrid_{i}_{j}"]
    ours = Lcross(amacrine, amacrine.categories.index(i), j, r=floats(table["r"]), correction="all")
    assert_matches(ours, table, CORRECTION_COLUMNS)


def test_kest_in_a_window_away_from_the_origin_reproduces_spatstats_shift():
    # spatstat's Krect moves the window to the origin first; on this lattice that decides ties
    data = DATASETS["lattice"]
    assert_matches(Kest(pattern_from(data["pattern"]), correction="all"), data["Kest"], CORRECTION_COLUMNS)


@pytest.mark.parametrize("case, wrong_engine", [
    ("cells", summary._Engine(closed=False, shift=False, cross=False)),   # histogram rule for Krect's
    ("amacrine", summary._Engine(closed=True, shift=False, cross=True)),  # Krect's rule for Kmulti's
    ("lattice", summary._Engine(closed=True, shift=False, cross=False)),  # Krect without its shift
])
def test_the_fixtures_tell_spatstats_code_paths_apart(monkeypatch, case, wrong_engine):
    """With another path's tie rule the fixtures no longer match: these tests can fail."""
    monkeypatch.setattr(summary._Engine, "choose", classmethod(lambda cls, *args, **kwargs: wrong_engine))
    pattern = pattern_from(DATASETS[case]["pattern"])
    if case == "amacrine":
        ours, table = Kcross(pattern, "on", "off", correction="all"), DATASETS[case]["Kcross_on_off"]
    else:
        ours, table = Kest(pattern, correction="all"), DATASETS[case]["Kest"]
    rows = fixture_rows(table, len(ours))
    mismatched = sum(
        (~np.isclose(ours[c].to_numpy()[rows], floats(table[c]), rtol=RTOL, equal_nan=True)).sum()
        for c in CORRECTION_COLUMNS
    )
    assert mismatched >= (2 if case == "lattice" else 10)


def test_kcross_of_a_type_with_itself_is_kest_of_that_type(amacrine):
    on_points = PointPattern(amacrine.of_type("on"), amacrine.window)
    pd.testing.assert_frame_equal(Kcross(amacrine, "on", "on"), Kest(on_points), check_like=True)


# ---------------------------------------------------------------------------- polygon windows


def test_polygon_window_matches_spatstat(polygon_case):
    case, pattern = polygon_case
    ours = Kest(pattern.unmark(), correction="all")
    # border (exact boundary distance) and isotropic (exact circle arcs, as spatstat's
    # ripleypoly) to rounding; translation against the exact overlaps computed in R
    assert_matches(ours, case["Kest"], ["un", "border", "iso"])
    assert_matches(ours.rename(columns={"trans": "trans_exact"}), case["Kest"], ["trans_exact"])
    # spatstat's own trans rasterises letterR on 128 x 128 pixels (0.015 x 0.021; perimeter
    # 12.5, area 3.7): overlaps can be off by perimeter x half a pixel, ~3 % of |W|, and
    # errors largely cancel over pairs. Allow 2 % (observed: 0.6 %).
    assert_matches(ours, case["Kest"], ["trans"], rtol=0.02)
    assert_matches(Kest(pattern.unmark(), correction="border"), case["Kest_border_only"], ["border"])


def test_polygon_window_kcross_matches_spatstat(polygon_case):
    case, pattern = polygon_case
    ours = Kcross(pattern, "a", "b", correction="all")
    assert_matches(ours, case["Kcross_a_b"], ["un", "border", "iso"])
    assert_matches(ours.rename(columns={"trans": "trans_exact"}), case["Kcross_a_b"], ["trans_exact"])


def test_polygon_and_mask_weights_agree_with_the_rectangle_formulas():
    """The same unit square as a rectangle, a polygon and an all-true mask: same weights."""
    rng = np.random.default_rng(3)
    points = rng.random((300, 2))
    r = np.linspace(0, 0.3, 61)
    expected = Kest(PointPattern(points, Window.rectangle()), r=r, correction=("isotropic", "translate"))
    for window in (Window.polygon(shapely.box(0, 0, 1, 1)), Window.mask(np.ones((32, 48), bool))):
        ours = Kest(PointPattern(points, window), r=r, correction=("isotropic", "translate"))
        for column in ("iso", "trans"):
            defined = np.isfinite(ours[column]) & np.isfinite(expected[column])
            assert defined.sum() > 50
            np.testing.assert_allclose(ours[column][defined], expected[column][defined], rtol=1e-10)


def test_mask_isotropic_weights_agree_with_the_same_shape_as_a_polygon():
    # an L of 3 pixels: the mask and the polygon are the same set
    mask = np.array([[True, True], [True, False]])
    polygon = Window.polygon([(0, 0), (1, 0), (1, 0.5), (0.5, 0.5), (0.5, 1), (0, 1)])
    points = Window.mask(mask).uniform_points(200, rng=5)
    r = np.linspace(0, 0.5, 51)
    as_mask = Kest(PointPattern(points, Window.mask(mask)), r=r, correction="isotropic")
    as_polygon = Kest(PointPattern(points, polygon), r=r, correction="isotropic")
    defined = np.isfinite(as_mask["iso"]) & np.isfinite(as_polygon["iso"])
    assert defined.sum() > 40
    np.testing.assert_allclose(as_mask["iso"][defined], as_polygon["iso"][defined], rtol=1e-10)


def test_mask_window_translation_uses_the_exact_pixel_set_covariance():
    # an L-shaped mask: |W n (W + v)| by brute force on a fine supersampling of the pixels
    mask = np.ones((4, 4), bool)
    mask[2:, 2:] = False
    window = Window.mask(mask)
    weights = _pairs.MaskWeights(window, np.array([[0.1, 0.1]]))
    v = np.array([0.3, -0.17])
    fine = np.kron(mask, np.ones((100, 100), bool))
    shifted = np.zeros_like(fine)
    dx, dy = int(round(v[0] * 400)), int(round(v[1] * 400))
    shifted[max(dy, 0):400 + min(dy, 0), max(dx, 0):400 + min(dx, 0)] = fine[max(-dy, 0):400 - max(dy, 0),
                                                                            max(-dx, 0):400 - max(dx, 0)]
    brute = (fine & shifted).sum() / 400**2
    assert weights.overlap_area(v[:1], v[1:])[0] == pytest.approx(brute, rel=1e-12)


# ---------------------------------------------------------------------------- pair correlation


@pytest.mark.parametrize("name", ["cells", "redwood", "swedishpines"])
def test_pcf_matches_spatstat(name):
    case = ORACLE["pcf"][name]
    ours = pcf(pattern_from(DATASETS[name]["pattern"]), correction="all", divisor=case["divisor"])
    assert ours.attrs["bw"] == pytest.approx(case["bw"], rel=1e-12)
    table = dict(case["table"])
    if case["divisor"] == "r":  # spatstat's "un" is normalised to mass 1 (see pcf's notes)
        table["un"] = [None if v is None else v * case["un_pairs"] for v in table["un"]]
    # FFT round-off: |g| ~ 1e-14 where spatstat has ~1e-14 noise and we have 0 (cells' hard core)
    columns = ["un", "trans", "iso"]
    atol = 1e-12 * max(np.nanmax(floats(table[c])) for c in columns)
    finite = ours.copy()
    finite[columns] = finite[columns].where(np.isfinite(finite[columns]))  # r = 0: inf or NaN, as spatstat
    assert_matches(finite, table, columns, atol=atol)


def test_pcf_in_a_polygon_window_matches_spatstat(polygon_case):
    case, pattern = polygon_case
    ours = pcf(pattern.unmark())
    ours = ours.where(np.isfinite(ours))
    assert_matches(ours, case["pcf"], ["iso"], atol=1e-12)
    assert_matches(ours.rename(columns={"trans": "trans_exact"}), case["pcf"], ["trans_exact"], atol=1e-12)


def test_pcf_of_csr_is_near_one():
    pattern = PointPattern(np.random.default_rng(11).random((2000, 2)), Window.rectangle())
    g = pcf(pattern, r=np.linspace(0, 0.05, 26))
    middle = g[(g.r > 0.01)]
    assert np.abs(middle[["trans", "iso"]].to_numpy() - 1).max() < 0.15


# ---------------------------------------------------------------------------- numba kernel


@pytest.mark.parametrize("closed", [True, False])
@pytest.mark.parametrize("same", [True, False])
def test_grid_kernel_matches_the_reference_path(closed, same):
    # points on a 0.01 lattice: many pair and boundary distances fall exactly on r values
    rng = np.random.default_rng(7)
    lattice = rng.choice(101 * 81, size=1500, replace=False)
    points = np.column_stack([lattice % 101 * 0.01, lattice // 101 * 0.01])
    frame = (0.0, 1.0, 0.0, 0.8)
    first, second = (points, points) if same else (points[:500], points[500:])
    r = np.linspace(0, 0.12, 121)
    b = np.minimum(np.minimum(first[:, 0], 1 - first[:, 0]), np.minimum(first[:, 1], 0.8 - first[:, 1]))
    options = dict(same=same, r=r, closed=closed, border=(b, _pairs.border_last_bins(b, r, closed)),
                   isotropic=True, translate=True)
    grid = _pairs.pair_sums_grid(first, second, frame=frame, **options)
    reference = _pairs.pair_sums_reference(first, second, weights=_pairs.RectangleWeights(frame, first), **options)
    counts = [_pairs.UN, _pairs.BORDER_START, _pairs.BORDER_STOP]
    np.testing.assert_array_equal(grid[counts], reference[counts])
    np.testing.assert_allclose(grid[[_pairs.TRANS, _pairs.ISO]], reference[[_pairs.TRANS, _pairs.ISO]], rtol=1e-12)
    assert reference[_pairs.UN].sum() > 10_000


def test_kest_through_the_grid_kernel_matches_spatstat(monkeypatch):
    monkeypatch.setattr(summary, "_GRID_KERNEL_MIN_PAIRS", 0)
    data = DATASETS["redwood"]  # its window starts at y = -1: spatstat's shifted coordinates
    assert_matches(Kest(pattern_from(data["pattern"]), correction="all"), data["Kest"], CORRECTION_COLUMNS)


# ---------------------------------------------------------------------------- known answers and conventions


def test_kest_of_csr_is_pi_r_squared_within_monte_carlo_error():
    """Binomial process of n points in the unit square.

    For small r the estimates are dominated by the pair count, a U-statistic over n(n-1)/2
    pairs each within r with probability p = pi r^2 / |W|: ``Var(K) ~ (2 |W| / n^2)^2 n^2 p / 2
    = 2 pi |W| r^2 / n^2``. Edge terms add up to 25 %
    to that standard deviation at r <= 0.1 (checked on 300 simulations), and the border
    estimate uses only the ``(1 - 2r)^2`` of the points away from the edges. The uncorrected
    estimate has the known mean ``pi r^2 - 8 r^3 / 3 + r^4 / 2`` (set covariance of the square).
    """
    n = 1000
    r = np.linspace(0, 0.1, 11)[1:]
    k = Kest(PointPattern(np.random.default_rng(2024).random((n, 2)), Window.rectangle()), r=np.r_[0, r],
             correction="all").iloc[1:]
    sd = 1.25 * np.sqrt(2 * np.pi) * r / n
    for column in ("iso", "trans"):
        assert np.all(np.abs(k[column] - np.pi * r**2) < 4 * sd), column
    assert np.all(np.abs(k["border"] - np.pi * r**2) < 4 * sd / (1 - 2 * r) ** 2)
    assert np.all(np.abs(k["un"] - (np.pi * r**2 - 8 * r**3 / 3 + r**4 / 2)) < 4 * sd)


def test_centered_l_is_l_minus_r():
    pattern = pattern_from(DATASETS["swedishpines"]["pattern"])
    plain, centered = Lest(pattern), Lest(pattern, centered=True)
    assert not plain.attrs["centered"] and centered.attrs["centered"]
    np.testing.assert_array_equal(plain["theo"], plain["r"])
    np.testing.assert_array_equal(centered["theo"], 0.0)
    for column in ("border", "trans", "iso"):
        np.testing.assert_allclose(centered[column], plain[column] - plain["r"], rtol=0, atol=1e-15)
    np.testing.assert_allclose(plain["iso"], np.sqrt(Kest(pattern)["iso"] / np.pi))
    cross = Lcross(pattern_from(DATASETS["amacrine"]["pattern"]), "on", "off", centered=True)
    assert cross["theo"].eq(0).all()


def test_default_r_grid_follows_spatstats_rule(amacrine):
    window = Window.rectangle((0, 2), (0, 1))
    assert default_rmax(window, 1.0) == pytest.approx(0.25)  # short side / 4
    assert default_rmax(window, 1e4) == pytest.approx(np.sqrt(1000 / (np.pi * 1e4)))
    r = default_r(window, 1e4)
    assert len(r) == 513 and r[0] == 0 and r[-1] == default_rmax(window, 1e4)
    # Kcross: the intensity of type j
    n_off = amacrine.counts[amacrine.type_index("off")]
    assert Kcross(amacrine, "on", "off", rmax=None)["r"].iloc[-1] == default_rmax(amacrine.window, n_off / amacrine.window.area)
    # masks: steps of a quarter pixel
    mask_r = default_r(Window.mask(np.ones((100, 200), bool), (0, 2), (0, 1)), 1.0)
    assert np.allclose(np.diff(mask_r), 0.01 / 4) and mask_r[-1] >= 0.25


def test_rmax_sets_the_default_grid():
    pattern = pattern_from(DATASETS["cells"]["pattern"])
    k = Kest(pattern, rmax=0.1)
    assert len(k) == 513 and k["r"].iloc[-1] == 0.1


# ---------------------------------------------------------------------------- bad input


@pytest.fixture(scope="module")
def cells():
    return pattern_from(DATASETS["cells"]["pattern"])


@pytest.mark.parametrize("points", [np.empty((0, 2)), [[0.5, 0.5]]])
@pytest.mark.parametrize("function", [Kest, Lest, pcf])
def test_too_few_points_are_rejected(function, points):
    with pytest.raises(ValueError, match="at least 2 points"):
        function(PointPattern(points, Window.rectangle()))


@pytest.mark.parametrize("r, message", [
    ([0, 0.1, 0.1, 0.2], "strictly increasing"),
    ([0, 0.2, 0.1], "strictly increasing"),
    ([-0.1, 0, 0.1], "start at 0"),
    ([0.05, 0.1], "start at 0"),
    ([0], "at least 2"),
    ([[0, 0.1]], "1-D"),
    ([0, np.nan], "finite"),
    (["a", "b"], "numbers"),
])
def test_bad_r_grids_are_rejected(cells, r, message):
    with pytest.raises(ValueError, match=message):
        Kest(cells, r=r)


@pytest.mark.parametrize("kwargs, message", [
    (dict(correction="bogus"), "unknown correction"),
    (dict(correction=[]), "no correction"),
    (dict(correction=3), "string or a sequence"),
    (dict(rmax=-1), "positive"),
    (dict(rmax=0.1, r=[0, 0.1]), "not both"),
])
def test_bad_options_are_rejected(cells, kwargs, message):
    with pytest.raises(ValueError, match=message):
        Kest(cells, **kwargs)


def test_bad_arguments_of_the_other_functions_are_rejected(cells, amacrine):
    with pytest.raises(ValueError, match="unknown correction"):
        pcf(cells, correction="border")
    with pytest.raises(ValueError, match="divisor"):
        pcf(cells, divisor="x")
    with pytest.raises(ValueError, match="bw"):
        pcf(cells, bw=0)
    with pytest.raises(ValueError, match="centered"):
        Lest(cells, centered="yes")
    with pytest.raises(ValueError, match="unknown category"):
        Kcross(amacrine, "on", "sideways")
    with pytest.raises(ValueError, match="out of range"):
        Lcross(amacrine, 0, 5)
    with pytest.raises(TypeError, match="PointPattern"):
        Kest(np.random.default_rng(0).random((10, 2)))


def test_kcross_needs_points_of_both_types():
    pattern = PointPattern([[0.2, 0.2], [0.7, 0.4], [0.5, 0.9]], Window.rectangle(), marks=[0, 0, 0],
                           categories=("a", "b"))
    with pytest.raises(ValueError, match="type 'b' has no points"):
        Kcross(pattern, "a", "b")
    with pytest.raises(ValueError, match="at least 2 points"):
        Kcross(PointPattern(pattern.points, pattern.window, marks=[0, 1, 1], categories=("a", "b")), "a", "a")


def _exact_smooth(self, binned):
    """The density's circular correlation with its kernel summed exactly (math.fsum), in place of the FFT."""
    import math

    size = self.grid_size
    offsets = np.linspace(0.0, 2 * (self.high - self.low), 2 * size)
    offsets[size + 1 :] = -offsets[size - 1 : 0 : -1]
    halfwidth = self.bw * np.sqrt(5.0)
    kernel = np.where(np.abs(offsets) < halfwidth, 0.75 * (1 - (offsets / halfwidth) ** 2) / halfwidth, 0.0)
    support = np.flatnonzero(kernel)
    smoothed = np.array([math.fsum(binned[(i + support) % (2 * size)] * kernel[support]) for i in range(size)])
    return np.interp(self.r, np.linspace(self.low, self.high, size), np.maximum(smoothed, 0.0))


def test_pcf_is_within_rounding_of_the_exact_kernel_sum(monkeypatch):
    """The kernel sum, summed directly, is within 1e-14 of the exactly summed one (measured 5-7e-16 at 1e3
    and 1e4 CSR points). By FFT, as R does, it was 1.6-2.4e-14 away, spatstat's 3.6-4.0e-14: an FFT's
    rounding is relative to the grid's largest value and dividing by small r magnifies it. So ours and
    spatstat's now differ by spatstat's own rounding (3.6-4.0e-14 at 1e3, 0.6-1.2e-14 at 1e4)."""
    pattern = PointPattern(np.random.default_rng(5).random((1000, 2)), Window.rectangle())
    fast = pcf(pattern)
    monkeypatch.setattr(summary._EpanechnikovDensity, "smooth", _exact_smooth)
    exact = pcf(pattern)
    for column in ("trans", "iso"):
        a, e = fast[column].to_numpy()[1:], exact[column].to_numpy()[1:]
        assert np.max(np.abs(a - e) / np.abs(e)) < 1e-14


def _kernel_arguments(n=20000):
    rng = np.random.default_rng(3)
    points = rng.random((n, 2)) * [2.0, 1.0]
    r = np.linspace(0, 0.1, 201)
    b = np.minimum(np.minimum(points[:, 0], 2 - points[:, 0]), np.minimum(points[:, 1], 1 - points[:, 1]))
    return (points, b, _pairs.border_last_bins(b, r, True), r, True, np.array([0.0, 2.0, 0.0, 1.0]),
            True, True, True, True, _pairs.MAX_EDGE_WEIGHT)


def test_parallel_pair_kernel_equals_its_serial_twin_bit_for_bit():
    arguments = _kernel_arguments()
    np.testing.assert_array_equal(_pairs._self_pair_sums_parallel(*arguments), _pairs._self_pair_sums_serial(*arguments))


_THREADS_SCRIPT = """
import hashlib, numpy as np, sys
sys.path.insert(0, sys.argv[1])
from test_pointprocess_summary import _kernel_arguments
from paperlib.pointprocess import _pairs
print(hashlib.sha256(_pairs._self_pair_sums_parallel(*_kernel_arguments()).tobytes()).hexdigest())
"""


def test_pair_sums_do_not_depend_on_the_number_of_threads():
    import os
    import subprocess
    import sys

    digests = set()
    for threads in ("1", "2"):
        environment = {**os.environ, "NUMBA_NUM_THREADS": threads}
        done = subprocess.run([sys.executable, "-c", _THREADS_SCRIPT, str(Path(__file__).parent)], env=environment,
                              capture_output=True, text=True, check=True, timeout=600)
        digests.add(done.stdout.strip().splitlines()[-1])
    assert len(digests) == 1
