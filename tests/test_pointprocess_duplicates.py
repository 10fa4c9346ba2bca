"""Duplicated points as spatstat treats them, and marks given as names.

The spatstat values come from tests/oracle/duplicates.json, written by
tests/oracle/spatstat_duplicates.R: lansing's hickories and maples in [0.5, 1]^2 (with
lansing's duplicated tree) plus repeated and coincident points, one pair on the boundary.
"""

import json
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from test_pointprocess_summary import assert_matches, floats, pattern_from

from paperlib.pointprocess import (
    Kcross,
    Kest,
    Lcross,
    Lest,
    PointPattern,
    StraussHard,
    Window,
    _pairs,
    envelope,
    fit_strauss_hardcore,
    hardcore_distances,
    pcf,
    ppm,
    rmh,
    summary,
)

ORACLE = json.loads((Path(__file__).parent / "oracle" / "duplicates.json").read_text())
CORRECTION_COLUMNS = ("un", "border", "trans", "iso")
SPATSTAT_TOLERANCE = 1e-5  # as tests/test_pointprocess_fit.py; measured: 1.1e-7
UNIT = Window.rectangle()
# the fixture's pattern and its derivatives (unmark) repeat locations: warned once, checked below
pytestmark = pytest.mark.filterwarnings("ignore:data contain duplicated points")


@pytest.fixture(scope="module")
def lansing():
    return pattern_from(ORACLE["pattern"])


# ============================================================================ the pattern


def test_duplicates_are_accepted_with_spatstats_warning():
    spec = ORACLE["pattern"]
    with pytest.warns(UserWarning, match=r"data contain duplicated points: 4 point\(s\) repeat the location of an "
                                         r"earlier point, the first is point 42 at \[0\.64, 0\.983\] \(a copy of "
                                         r"point 41\)"):
        pattern_from(spec)


def test_duplicated_is_spatstats(lansing):
    np.testing.assert_array_equal(np.flatnonzero(lansing.duplicated()) + 1, ORACLE["duplicated"])
    np.testing.assert_array_equal(np.flatnonzero(lansing.duplicated("unmark")) + 1, ORACLE["duplicated_unmark"])
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no repeated location left, no warning
        distinct = lansing.unique("unmark")
    assert distinct.n == lansing.n - 4 and not distinct.duplicated("unmark").any()
    with pytest.raises(ValueError, match="rule must be one of"):
        lansing.duplicated("deldir")


# ============================================================================ summary functions vs spatstat


def test_kest_counts_zero_distance_pairs_as_spatstat(lansing):
    ours = Kest(lansing.unmark(), correction="all")
    assert_matches(ours, ORACLE["Kest"], CORRECTION_COLUMNS)
    # spatstat's C engine counts the pairs at distance 0 from r = 0 on, with edge weight 1:
    # 4 repeated locations, 8 ordered pairs
    n, area = lansing.n, lansing.window.area
    assert ours["un"].iloc[0] == pytest.approx(8 * area / (n * (n - 1)), rel=1e-15)
    assert ours["iso"].iloc[0] == ours["trans"].iloc[0] == ours["un"].iloc[0]


def test_other_k_code_paths_count_them_as_spatstat(lansing):
    pattern = lansing.unmark()
    assert_matches(Kest(pattern, correction="border"), ORACLE["Kest_border_only"], ["border"])
    uneven = Kest(pattern, r=floats(ORACLE["Kest_uneven"]["r"]), correction="all")  # histogram code: d < r
    assert_matches(uneven, ORACLE["Kest_uneven"], CORRECTION_COLUMNS)
    assert uneven["un"].iloc[0] == 0
    offgrid = Lest(pattern, r=floats(ORACLE["Lest_offgrid"]["r"]), correction="all")
    assert_matches(offgrid, ORACLE["Lest_offgrid"], CORRECTION_COLUMNS)


@pytest.mark.parametrize("i, j", [("hickory", "maple"), ("maple", "hickory"), ("maple", "maple")])
def test_kcross_and_lcross_count_them_as_spatstat(lansing, i, j):
    key = f"{i}_{j}"
    assert_matches(Kcross(lansing, i, j, correction="all"), ORACLE["cross"][f"Kcross_{key}"], CORRECTION_COLUMNS)
    table = ORACLE["cross"][f"Lcross_offgrid_{key}"]
    assert_matches(Lcross(lansing, i, j, r=floats(table["r"]), correction="all"), table, CORRECTION_COLUMNS)


def test_pcf_counts_them_as_spatstat(lansing):
    ours = pcf(lansing.unmark())
    ours = ours.where(np.isfinite(ours))  # r = 0: inf, NA in spatstat
    assert_matches(ours, ORACLE["pcf"], ["trans", "iso"], atol=1e-12)


def test_grid_kernel_counts_coincident_points_like_the_reference_path(monkeypatch):
    rng = np.random.default_rng(3)
    points = np.round(rng.random((2100, 2)), 2)  # on a 0.01 lattice: hundreds of repeated locations
    with pytest.warns(UserWarning, match="duplicated points"):
        pattern = PointPattern(points, UNIT)
    r = np.linspace(0, 0.05, 51)
    kernel = Kest(pattern, r=r, correction="all")
    monkeypatch.setattr(summary, "_GRID_KERNEL_MIN_PAIRS", np.inf)
    reference = Kest(pattern, r=r, correction="all")
    pd.testing.assert_frame_equal(kernel, reference, rtol=1e-12)
    assert kernel["un"].iloc[0] > 0


def test_isotropic_weight_of_a_coincident_pair_is_one_in_every_window():
    yy, xx = np.mgrid[0:40, 0:50]
    inside = (xx - 24.5) ** 2 + (yy - 19.5) ** 2 < 15**2
    mask = Window.mask(inside, xrange=(0, 5), yrange=(0, 4))
    column = int(np.argmax(inside[20]))
    on_edge = np.array([[column * 0.1, 2.05]])  # on the left edge of the mask's leftmost pixel in row 20
    weights = _pairs.MaskWeights(mask, on_edge)
    assert weights.isotropic(np.array([0]), np.array([0.0]))[0] == 1.0
    assert weights.isotropic(np.array([0]), np.array([1e-9]))[0] == pytest.approx(2.0)  # half the circle
    corner = np.array([[1.0, 1.0], [0.5, 0.0]])
    assert (_pairs.RectangleWeights((0, 1, 0, 1), corner).isotropic(np.arange(2), np.zeros(2)) == 1).all()
    triangle = Window.polygon([[0, 0], [1, 0], [0, 1]])
    assert (_pairs.PolygonWeights(triangle.shape, corner[1:], np.zeros(1)).isotropic(np.arange(1), np.zeros(1)) == 1)


def test_envelope_of_a_pattern_with_duplicates(lansing):
    r = np.linspace(0, 0.05, 21)
    result = envelope(lansing.unmark(), Kest, nsim=3, r=r, fun_kwargs={"correction": "isotropic"}, rng=1, workers=1)
    np.testing.assert_array_equal(result.obs, Kest(lansing.unmark(), r=r, correction="isotropic")["iso"])
    assert result.obs.iloc[0] > 0  # the coincident pairs


# ============================================================================ fits without and with hard cores


@pytest.mark.parametrize("name", ["strauss", "multistrauss"])
def test_fits_without_hard_core_count_coincident_neighbours_as_spatstat(lansing, name):
    expected = ORACLE[name]
    if name == "strauss":  # spatstat's Strauss counts d <= r, d = 0 included
        fit = ppm(lansing.unmark(), expected["r"], 0.0, closed=True, quadrature="spatstat")
    else:  # MultiStraussHard with hradii 0: d < r
        fit = ppm(lansing, np.array(expected["iradii"]), 0.0, quadrature="spatstat")
    assert list(fit.coefficients.index) == expected["coef_names"]
    np.testing.assert_allclose(fit.coefficients["estimate"], expected["coef"], rtol=SPATSTAT_TOLERANCE)
    np.testing.assert_allclose(fit.vcov, expected["vcov"], rtol=SPATSTAT_TOLERANCE)
    assert fit.log_pl == pytest.approx(expected["logLik"], rel=1e-10)


def test_what_a_hard_core_forbids_refuses_duplicates(lansing):
    named = r"point 42 at \[0\.64, 0\.983\] repeats the location of point 41 \(4 repeated point\(s\) in all\)"
    with pytest.raises(ValueError, match=named + r": ppm with a hard core"):
        ppm(lansing, 0.02, 0.001)
    with pytest.raises(ValueError, match=named + r": estimating hard cores"):
        hardcore_distances(lansing)
    with pytest.raises(ValueError, match=named):
        fit_strauss_hardcore(lansing, r=0.02)
    with pytest.raises(ValueError, match=named + r": rmh's start pattern"):
        rmh(StraussHard(100.0, 0.5, 0.02, 0.0), lansing.window, T=10, start=lansing.unmark(), rng=0)
    ppm(lansing.unique("unmark"), 0.02, 0.001)  # fine without the repeats


# ============================================================================ marks as names


def test_marks_as_names_take_sorted_categories():
    points = [[0.1, 0.1], [0.2, 0.2], [0.3, 0.3]]
    pattern = PointPattern(points, UNIT, ["maple", "hickory", "maple"])
    assert pattern.categories == ("hickory", "maple") and pattern.marks.tolist() == [1, 0, 1]
    given = PointPattern(points, UNIT, np.array(["maple", "hickory", "maple"]), categories=["maple", "hickory", "oak"])
    assert given.marks.tolist() == [0, 1, 0] and given.counts.tolist() == [2, 1, 0]
    integers = PointPattern(points, UNIT, [1, 0, 1])  # integer marks unchanged
    assert integers.categories == ("0", "1") and integers.marks.tolist() == [1, 0, 1]


def test_marks_as_a_categorical_keep_its_categories_in_order():
    points = [[0.1, 0.1], [0.2, 0.2], [0.3, 0.3]]
    marks = pd.Categorical(["on", "off", "on"], categories=["on", "off", "unused"])
    pattern = PointPattern(points, UNIT, marks)
    assert pattern.categories == ("on", "off", "unused") and pattern.marks.tolist() == [0, 1, 0]
    series = PointPattern(points, UNIT, pd.Series(marks))
    assert series == pattern
    reordered = PointPattern(points, UNIT, marks, categories=["off", "on"])
    assert reordered.marks.tolist() == [1, 0, 1]


@pytest.mark.parametrize(
    "marks, categories, message",
    [
        (["a", "b", "c"], ["a", "b"], r"mark name\(s\) \['c'\] are not among the categories"),
        (pd.Categorical(["a", None, "a"]), None, "missing at point 1"),
        ([{"a": 1}, "b", "c"], None, "integer category indices or category names"),
    ],
)
def test_bad_mark_names(marks, categories, message):
    with pytest.raises(ValueError, match=message):
        PointPattern([[0.1, 0.1], [0.2, 0.2], [0.3, 0.3]], UNIT, marks, categories)
