"""Fitting the multitype Strauss hard-core model (Hurtut 2009, section 3.2) against spatstat.

The spatstat answers come from tests/oracle/ppm.json, written by tests/oracle/spatstat_ppm.R
(the data sets are in the fixture, so these tests need no R).
"""

import json
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from paperlib.pointprocess import PointPattern, Window, interaction_counts
from paperlib.pointprocess.fit import (
    PPMFit,
    StraussHardcoreFit,
    _shell_pairs,
    fine_nd,
    fit_strauss_hardcore,
    hardcore_distances,
    interaction_radii,
    ppm,
    select_radius,
)
from paperlib.pointprocess.models import MultiStraussHard
from paperlib.pointprocess.quadrature import QuadratureScheme, default_nd, quadscheme

ORACLE = json.loads((Path(__file__).parent / "oracle" / "ppm.json").read_text())
FITS = {fit["name"]: fit for fit in ORACLE["fits"]}
SPATSTAT_TOLERANCE = 1e-5  # the issue asks for 1e-4; we agree to ~1e-7 (R's IRLS stops at 1e-8 deviance)


def dataset(name: str) -> PointPattern:
    data = ORACLE["data"][name]
    window = Window.rectangle(data["window"]["xrange"], data["window"]["yrange"])
    points = np.column_stack([data["x"], data["y"]])
    if "marks" not in data:
        return PointPattern(points, window)
    categories = data["categories"]
    return PointPattern(points, window, [categories.index(mark) for mark in data["marks"]], categories)


def spatstat_model(fit: dict):
    """(r, hc, closed) of a fixture fit: spatstat's StraussHard/Strauss count d <= r (closed)."""
    if fit["data"] == "amacrine":
        return np.array(fit["iradii"]), np.array(fit["hradii"]), False
    return fit["r"], fit["hc"] if fit["hc"] is not None else 0.0, True


def fit_like_spatstat(fit: dict) -> PPMFit:
    r, hc, closed = spatstat_model(fit)
    return ppm(dataset(fit["data"]), r, hc, closed=closed, quadrature=fit["nd_given"] or "spatstat")


def csr(n, seed, marks=None, categories=None, window=None) -> PointPattern:
    rng = np.random.default_rng(seed)
    window = window or Window.rectangle()
    return PointPattern(window.uniform_points(n, rng), window, marks, categories)


# ============================================================================ quadrature


@pytest.mark.parametrize("name", sorted(FITS))
def test_quadscheme_is_spatstats(name):
    fit = FITS[name]
    scheme = quadscheme(dataset(fit["data"]), fit["nd_given"])
    expected = fit["quadrature"]
    assert (scheme.nd, scheme.ntile) == (expected["nd"], expected["ntile"])
    assert (scheme.n_data, scheme.n_dummy) == (expected["n_data"], expected["n_dummy"])
    assert scheme.total_weight == pytest.approx(expected["total_weight"], rel=1e-13)
    if "weights" in expected:
        np.testing.assert_allclose(scheme.weights, expected["weights"], rtol=1e-15)


def test_default_nd_and_spatstats_tile_rule():
    assert [default_nd(n) for n in (42, 294, 1000, 10_000)] == [32, 40, 70, 200]
    cells = dataset("cells")
    assert quadscheme(cells, 256).ntile == 32  # smallest divisor of 256 that is >= 32
    assert quadscheme(cells, 100).ntile == 50
    assert quadscheme(cells, 20).ntile == 20  # no divisor >= 32: nd itself
    assert quadscheme(cells, 64, ntile=8).ntile == 8


def test_point_on_a_tile_edge_goes_to_the_lower_tile():
    # tiles of side 1/32; x = 16/32 lies on the edge between tiles 15 and 16 (0-based)
    pattern = PointPattern([[0.5, 0.3], [0.9, 0.9], [0.1, 0.1]], Window.rectangle())
    scheme = quadscheme(pattern, 32)
    tile_area = 1 / 32**2
    assert scheme.weights[0] == pytest.approx(tile_area / 2)  # shares tile 15 with its grid centre
    lower = np.flatnonzero(np.isclose(scheme.points[:, 0], 15.5 / 32) & np.isclose(scheme.points[:, 1], 9.5 / 32))
    upper = np.flatnonzero(np.isclose(scheme.points[:, 0], 16.5 / 32) & np.isclose(scheme.points[:, 1], 9.5 / 32))
    assert scheme.weights[lower] == pytest.approx(tile_area / 2)
    assert scheme.weights[upper] == pytest.approx(tile_area)


def test_multitype_scheme_replicates_dummies_and_data():
    amacrine = dataset("amacrine")
    scheme = quadscheme(amacrine)
    n, grid = amacrine.n, default_nd(amacrine.n) ** 2 + 4
    assert scheme.n_points == n + 2 * grid + n  # data, grid x 2 types, each data point as the other type
    assert scheme.total_weight == pytest.approx(2 * amacrine.window.area, rel=1e-14)
    copies = slice(n + 2 * grid, None)
    # every data point reappears once with the other type, with its data weight
    order = np.lexsort(scheme.points[copies].T[::-1])
    data_order = np.lexsort(amacrine.points.T[::-1])
    np.testing.assert_array_equal(scheme.points[copies][order], amacrine.points[data_order])
    np.testing.assert_array_equal(scheme.types[copies][order], 1 - amacrine.marks[data_order])
    np.testing.assert_array_equal(scheme.weights[copies][order], scheme.weights[:n][data_order])


def test_polygon_and_mask_schemes_keep_dummies_inside_and_weights_exact():
    triangle = Window.polygon([[0, 0], [1, 0], [0, 1]])
    yy, xx = np.mgrid[0:40, 0:50]
    disc = Window.mask((xx - 24.5) ** 2 + (yy - 19.5) ** 2 < 15**2, xrange=(0, 5), yrange=(0, 4))
    for window in (triangle, disc):
        pattern = csr(30, seed=1, window=window)
        scheme = quadscheme(pattern, 37)
        assert window.contains(scheme.points).all()
        assert scheme.total_weight == pytest.approx(window.area, rel=1e-12)
        assert (scheme.weights > 0).all()


# ============================================================================ pseudolikelihood vs spatstat


@pytest.mark.parametrize("name", sorted(FITS))
def test_ppm_reproduces_spatstat(name):
    expected = FITS[name]
    fit = fit_like_spatstat(expected)
    table = fit.coefficients
    assert list(table.index) == expected["coef_names"]
    assert (table["status"] == "estimated").all()
    np.testing.assert_allclose(table["estimate"], expected["coef"], rtol=SPATSTAT_TOLERANCE)
    np.testing.assert_allclose(fit.vcov, expected["vcov"], rtol=SPATSTAT_TOLERANCE)
    np.testing.assert_allclose(fit.vcov_hessian, expected["vcov_hessian"], rtol=SPATSTAT_TOLERANCE)
    np.testing.assert_allclose(table["se"], np.sqrt(np.diag(expected["vcov"])), rtol=SPATSTAT_TOLERANCE)
    assert fit.log_pl == pytest.approx(expected["logLik"], rel=1e-10)
    assert fit.rbord == expected["rbord"]
    assert fit.n_fitted == expected["quadrature"]["n_fitted"]


def test_spatstats_hardcore_estimates():
    assert hardcore_distances(dataset("cells"), "spatstat")[0, 0] == pytest.approx(
        FITS["cells_strausshard_hc_estimated"]["hc"], rel=1e-14)
    np.testing.assert_allclose(hardcore_distances(dataset("amacrine"), "spatstat"),
                               FITS["amacrine_multistrausshard_nddefault"]["hradii"], rtol=1e-14)


def test_natural_parameters_and_delta_method():
    fit = fit_like_spatstat(FITS["amacrine_multistrausshard_nddefault"])
    theta = fit.coefficients["estimate"]
    assert fit.beta["on"] == pytest.approx(np.exp(theta["(Intercept)"] + theta["markson"]))
    assert fit.gamma.loc["on", "off"] == fit.gamma.loc["off", "on"] == pytest.approx(np.exp(theta["markoffxon"]))
    natural = fit.natural
    assert natural.loc[("gamma", "off-on"), "se"] == pytest.approx(
        fit.gamma.loc["off", "on"] * fit.coefficients.loc["markoffxon", "se"])
    v = fit.vcov.loc[["(Intercept)", "markson"], ["(Intercept)", "markson"]].to_numpy()
    assert natural.loc[("beta", "on"), "se"] == pytest.approx(fit.beta["on"] * np.sqrt(v.sum()))
    assert isinstance(fit.model, MultiStraussHard) and fit.model.categories == ("off", "on")


# ============================================================================ our default quadrature


# spatstat's nd = 512 fits are within ~0.01 of their nd -> infinity limits (from nd = 512, 1024,
# 1536 in the study behind fine_nd); our default nd (256 to 512 here) adds at most ~0.02 more.
# Quadrature error is thus below a tenth of the sampling error: hold every coefficient within
# 0.1 standard errors of spatstat's nd = 512 fit. spatstat's default scheme fails that for cells.
@pytest.mark.parametrize("name", ["cells_strausshard_nd512", "swedishpines_strauss_nd512",
                                  "amacrine_multistrausshard_nd512"])
def test_default_quadrature_is_close_to_the_converged_fit(name):
    reference = FITS[name]
    r, hc, closed = spatstat_model(reference)
    fit = ppm(dataset(reference["data"]), r, hc, closed=closed)
    assert fit.quadrature.nd == fine_nd(dataset(reference["data"]), np.broadcast_to(r, (fit.model.n_types,) * 2),
                                        np.broadcast_to(hc, (fit.model.n_types,) * 2))
    se = np.sqrt(np.diag(reference["vcov"]))
    assert np.abs(fit.coefficients["estimate"] - reference["coef"]).max() <= 0.1 * se.min()


def test_spatstats_default_quadrature_is_far_from_converged_for_cells():
    coarse, converged = FITS["cells_strausshard_nddefault"], FITS["cells_strausshard_nd512"]
    se = np.sqrt(np.diag(converged["vcov"]))
    assert np.abs(np.subtract(coarse["coef"], converged["coef"])).max() > 0.5 * se.min()


def test_fine_nd_rule():
    cells = dataset("cells")
    assert fine_nd(cells, np.full((1, 1), 0.1), np.full((1, 1), 0.05)) == 320  # 0.05 / 16 spacing, multiple of 32
    assert fine_nd(cells, np.full((1, 1), 0.5), np.zeros((1, 1))) == 32  # coarse features: spatstat's default
    assert fine_nd(cells, np.full((1, 1), 0.001), np.zeros((1, 1))) == 512  # capped


# ============================================================================ hard cores and radii


def test_hardcore_distances_known_answer():
    points = [[0, 0], [0.3, 0], [0.3, 0.4], [1, 1], [0.9, 1], [0.5, 0.5]]
    pattern = PointPattern(points, Window.rectangle((0, 1), (0, 1)), [0, 0, 0, 1, 1, 1])
    minimum = hardcore_distances(pattern)
    np.testing.assert_allclose(minimum, [[0.3, np.hypot(0.2, 0.1)], [np.hypot(0.2, 0.1), 0.1]], rtol=1e-15)
    np.testing.assert_allclose(hardcore_distances(pattern, "spatstat"), minimum * 3 / 4, rtol=1e-15)
    unmarked = hardcore_distances(pattern.unmark(), "spatstat")
    assert unmarked[0, 0] == pytest.approx(0.1 * 6 / 7)


def staircase(r):
    """A centered L curve with a dip of depth 0.01 at r = 0.2 and the real minimum at r = 0.5."""
    return (r - 0.5) ** 2 - 0.25 - 0.01 * np.exp(-(((r - 0.2) / 0.01) ** 2))


def test_select_radius_known_answers():
    r = np.linspace(0, 1, 1001)
    assert select_radius(r, staircase(r), 0.0, 0.05) == (0.5, "first local minimum")
    literal, rule = select_radius(r, staircase(r), 0.0, 0.0)  # no rebound asked: the dip counts
    assert literal == pytest.approx(0.2, abs=0.01) and rule == "first local minimum"
    beyond, _ = select_radius(r, staircase(r), 0.6, 0.05)  # r must exceed the hard core
    assert beyond == pytest.approx(0.601)
    falling = -r  # regularity grows up to rmax: no rebound, global minimum at rmax
    assert select_radius(r, falling, 0.1, 0.05) == (1.0, "global minimum (no rebound)")
    with_nan = np.where(r > 0.9, np.nan, staircase(r))
    assert select_radius(r, with_nan, 0.0, 0.05)[0] == 0.5
    with pytest.raises(ValueError, match="larger rmax"):
        select_radius(r, staircase(r), 1.0, 0.05)


def test_interaction_radius_of_cells():
    cells = dataset("cells")
    h = hardcore_distances(cells)
    selection = interaction_radii(cells, h)
    assert selection.table.loc[0, "rule"] == "first local minimum"
    # cells' L dips from h = 0.084 to about 0.1, then rises: the classical Strauss radius of cells
    assert 0.09 < selection.r[0, 0] < 0.11
    curve = selection.curves[("points", "points")]
    below = curve["r"] < h[0, 0]  # no pair yet: K = 0, and Hurtut's centered L is -r
    assert list(curve.columns) == ["r", "L"] and np.allclose(curve["L"][below], -curve["r"][below])


def test_interaction_radii_fallback_warns():
    with pytest.warns(UserWarning, match="global minimum"):
        selection = interaction_radii(dataset("cells"), hardcore_distances(dataset("cells")), rebound=1e6)
    assert selection.table.loc[0, "rule"] == "global minimum (no rebound)"


def test_fit_strauss_hardcore_on_amacrine():
    amacrine = dataset("amacrine")
    result = fit_strauss_hardcore(amacrine)
    assert isinstance(result, StraussHardcoreFit)
    table = result.distances
    assert list(zip(table["a"], table["b"])) == [("off", "off"), ("off", "on"), ("on", "on")]
    h = hardcore_distances(amacrine)
    np.testing.assert_array_equal(result.model.hc, h)
    assert (result.model.r > result.model.hc).all()
    assert set(result.L_curves) == {("off", "off"), ("off", "on"), ("on", "on")}
    # same-type regularity: strong inhibition; across types the mosaics are nearly independent
    assert result.gamma.loc["off", "off"] < 0.5 and result.gamma.loc["on", "on"] < 0.5
    assert result.coefficients.loc["markoffxon", "estimate"] == pytest.approx(0, abs=3 * result.coefficients.loc[
        "markoffxon", "se"])


def test_poisson_pattern_gives_gamma_one():
    fit = ppm(csr(500, seed=7), r=0.04)
    log_gamma = fit.coefficients.loc["Interaction"]
    assert abs(log_gamma["estimate"]) < 3 * log_gamma["se"]
    assert fit.beta["points"] == pytest.approx(500, rel=0.15)


def test_given_radii_are_used():
    result = fit_strauss_hardcore(dataset("cells"), r=0.1, quadrature="spatstat")
    assert result.model.r[0, 0] == 0.1 and result.distances.loc[0, "rule"] == "given"
    assert result.L_curves == {}


# ============================================================================ degenerate interactions


def test_no_pair_in_the_shell_gives_gamma_zero_like_a_hard_core():
    cells = dataset("cells")  # smallest distance 0.084: no pair within 0.06
    with pytest.warns(UserWarning, match="boundary"):
        shell = ppm(cells, r=0.06, hc=0.05, closed=True, quadrature="spatstat")
    assert shell.model.gamma[0, 0] == 0.0
    assert shell.coefficients.loc["Interaction", "estimate"] == -np.inf
    assert np.isnan(shell.coefficients.loc["Interaction", "se"])
    with pytest.warns(UserWarning, match="not identifiable"):
        hard = ppm(cells, r=0.06, hc=0.06, closed=True, quadrature="spatstat")
    assert hard.model.gamma[0, 0] == 1.0 and hard.coefficients.loc["Interaction", "status"].startswith("not")
    # gamma = 0 on (0.05, 0.06] and a hard core of 0.06 forbid the same places
    assert shell.log_pl == pytest.approx(hard.log_pl, rel=1e-12)
    assert shell.beta.iloc[0] == pytest.approx(hard.beta.iloc[0], rel=1e-10)


def test_shell_pairs_agree_with_interaction_counts():
    amacrine = dataset("amacrine")
    for closed in (False, True):
        model = MultiStraussHard([1, 1], 1.0, [[0.06, 0.03], [0.03, 0.07]], hardcore_distances(amacrine) / 2,
                                 amacrine.categories, closed)
        i, j = _shell_pairs(model, amacrine.points, amacrine.marks)
        counts = np.zeros((amacrine.n, 2), dtype=np.int64)
        np.add.at(counts, (i, amacrine.marks[j]), 1)
        expected, _ = interaction_counts(model, amacrine.points, amacrine.marks, amacrine.points, amacrine.marks,
                                         exclude=np.arange(amacrine.n))
        np.testing.assert_array_equal(counts, expected)


# ============================================================================ bad input


def test_too_few_points():
    for n in (0, 1):
        with pytest.raises(ValueError, match="at least 2"):
            ppm(PointPattern(np.full((n, 2), 0.5), Window.rectangle()), r=0.1)


def test_small_category_is_named():
    pattern = csr(12, seed=2, marks=[0] * 10 + [1] * 2, categories=["dots", "crosses"])
    for call in (lambda: ppm(pattern, r=0.1), lambda: fit_strauss_hardcore(pattern)):
        with pytest.raises(ValueError, match="'crosses' has 2"):
            call()


@pytest.mark.parametrize("kwargs, message", [
    ({"r": [[0.1, 0.1, 0.1]]}, "2x2"),
    ({"r": [[0.1, 0.2], [0.3, 0.1]]}, "symmetric"),
    ({"r": 0.1, "hc": 0.2}, "hc <= r"),
    ({"r": 0.1, "hc": [[0.01, 0.01]]}, "2x2"),
    ({"r": -0.1}, "positive"),
    ({"r": 0.1, "correction": "isotropic"}, "correction"),
    ({"r": 0.1, "quadrature": "fine"}, "quadrature"),
])
def test_inconsistent_parameters(kwargs, message):
    pattern = csr(20, seed=3, marks=[0] * 10 + [1] * 10)
    with pytest.raises(ValueError, match=message):
        ppm(pattern, **kwargs)


def test_hard_core_violated_by_the_data():
    cells = dataset("cells")
    with pytest.raises(ValueError, match="zero pseudolikelihood"):
        ppm(cells, r=0.12, hc=0.09)
    minimum = hardcore_distances(cells)
    ppm(cells, r=0.12, hc=minimum, quadrature="spatstat")  # open convention: the closest pair stays legal
    with pytest.raises(ValueError, match="zero pseudolikelihood"):
        ppm(cells, r=0.12, hc=minimum, closed=True)


def test_radius_below_hard_core_and_unknown_options():
    cells = dataset("cells")
    with pytest.raises(ValueError, match="below the hard core"):
        fit_strauss_hardcore(cells, r=0.05)
    with pytest.raises(ValueError, match="hardcore"):
        fit_strauss_hardcore(cells, hardcore="median")
    with pytest.raises(ValueError, match="must be one of"):
        hardcore_distances(cells, "median")


def test_zero_area_window_is_refused_upstream():
    with pytest.raises(ValueError, match="positive area"):
        Window.rectangle((0, 0), (0, 1))


def test_category_lost_to_the_border_correction():
    window = Window.rectangle()
    points = np.vstack([np.random.default_rng(4).uniform(0.2, 0.8, (20, 2)), [[0.01, 0.5], [0.5, 0.01], [0.99, 0.5]]])
    pattern = PointPattern(points, window, [0] * 20 + [1] * 3, ["inner", "edge"])
    with pytest.raises(ValueError, match="'edge' has no data point"):
        ppm(pattern, r=0.05)
    with pytest.warns(UserWarning, match="boundary"):  # the 3 edge points are far apart
        ppm(pattern, r=0.05, correction="none", quadrature="spatstat")


def test_foreign_quadrature_scheme_is_refused():
    scheme = quadscheme(csr(20, seed=5))
    assert isinstance(scheme, QuadratureScheme)
    with pytest.raises(ValueError, match="not built for this pattern"):
        ppm(csr(20, seed=6), r=0.1, quadrature=scheme)


def test_fit_results_are_tables():
    fit = fit_like_spatstat(FITS["swedishpines_strauss_nddefault"])
    assert isinstance(fit.coefficients, pd.DataFrame) and isinstance(fit.vcov, pd.DataFrame)
    assert list(fit.coefficients.columns) == ["estimate", "se", "se_hessian", "status"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        repr(fit)


def test_newton_stops_at_the_resolution_of_floating_point():
    # amacrine's 17-digit coordinates (summary fixture) leave one off-on pair in the shell:
    # Newton reaches the maximum in a few steps, then its decrement sits at rounding noise
    # (~1e-16) above the 1e-11-squared bound; the fit must stop there, not fail after 100 steps.
    entry = json.loads((Path(__file__).parent / "oracle" / "summary.json").read_text())["datasets"]["amacrine"]
    data = entry["pattern"]
    window = Window.rectangle(np.asarray(data["window"]["xrange"], float), np.asarray(data["window"]["yrange"], float))
    categories = data["categories"]
    amacrine = PointPattern(np.column_stack([data["x"], data["y"]]).astype(float), window,
                            [categories.index(mark) for mark in data["marks"]], categories)
    result = fit_strauss_hardcore(amacrine)
    assert result.fit.iterations < 20
    assert 0 < result.gamma.loc["off", "on"] < 1


def test_a_hard_core_beyond_rmax_gives_a_pure_hard_core_not_an_error():
    # five widely spaced points of category b: their hard core exceeds spatstat's default rmax
    rng = np.random.default_rng(0)
    a = rng.uniform(0, 1, (40, 2))
    b = np.array([[0.2, 0.2], [0.8, 0.2], [0.5, 0.5], [0.2, 0.8], [0.8, 0.8]])
    pattern = PointPattern(np.vstack([a, b]), Window.rectangle(), np.r_[np.zeros(40, int), np.ones(5, int)],
                           ("a", "b"))
    h = hardcore_distances(pattern)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        selection = interaction_radii(pattern, h)
    assert any("beyond the largest r examined" in str(w.message) for w in caught)  # the uniform 'a' warns too
    assert selection.r[1, 1] == h[1, 1]
    row = selection.table[(selection.table.a == "b") & (selection.table.b == "b")].iloc[0]
    assert row.rule == "hard core only (h beyond rmax)"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fitted = fit_strauss_hardcore(pattern, correction="none")
    assert fitted.model.hc[1, 1] == h[1, 1] and fitted.model.gamma[1, 1] == 1.0
