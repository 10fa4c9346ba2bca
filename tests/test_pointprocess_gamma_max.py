"""ppm(..., gamma_max=...): pseudolikelihood under Hurtut's constraint gamma <= 1 (section 3.1).

The spatstat answers come from tests/oracle/project.json, written by
tests/oracle/spatstat_project.R: fits whose unconstrained gamma exceeds 1 and their projection
onto gamma <= 1 (spatstat's ``ppm(..., project = TRUE)``, or the best valid submodel by brute
force where spatstat accepts gamma > 1 because of a hard core). The data are in the fixture.
"""

import json
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import minimize

from paperlib.pointprocess import PointPattern, Window, fit_strauss_hardcore, ppm
from paperlib.pointprocess.fit import ROUNDING_RESOLUTION, _log_pl, _maximise_bounded

ORACLE = json.loads((Path(__file__).parent / "oracle" / "project.json").read_text())
FITS = {fit["name"]: fit for fit in ORACLE["fits"]}
UNCONSTRAINED_TOLERANCE = 1e-6  # measured: 7e-8 (R's IRLS stops at a relative deviance change of 1e-8)
PROJECTED_TOLERANCE = 1e-6  # measured: 3e-8
BOUND = "boundary (gamma = gamma_max)"


def dataset(name: str) -> PointPattern:
    data = ORACLE["data"][name]
    window = Window.rectangle([float(v) for v in data["window"]["xrange"]],
                              [float(v) for v in data["window"]["yrange"]])
    points = np.column_stack([[float(v) for v in data["x"]], [float(v) for v in data["y"]]])
    if "marks" not in data:
        return PointPattern(points, window)
    categories = data["categories"]
    return PointPattern(points, window, [categories.index(mark) for mark in data["marks"]], categories)


def fit_like_spatstat(fit: dict, gamma_max=None):
    """Strauss/StraussHard count d <= r and forbid d <= hc (closed); MultiStraussHard d < r, d < h."""
    if fit["model"] in ("Strauss", "StraussHard"):
        r, hc, closed = fit["r"], fit["hc"], True
    else:
        r, hc, closed = np.array(fit["iradii"]), np.array(fit["hradii"]), False
    return ppm(dataset(fit["data"]), r, hc, closed=closed, quadrature="spatstat", gamma_max=gamma_max)


def square(values, k):
    return np.reshape(np.array(values, dtype=np.float64), (k, k))


# ============================================================================ against spatstat


@pytest.mark.parametrize("name", sorted(FITS))
def test_unconstrained_fit_is_spatstats_and_has_gamma_above_one(name):
    expected = FITS[name]["unconstrained"]
    fit = fit_like_spatstat(FITS[name])
    table = fit.coefficients
    assert list(table.index) == expected["coef_names"]
    np.testing.assert_allclose(table["estimate"], expected["coef"], rtol=UNCONSTRAINED_TOLERANCE)
    assert fit.log_pl == pytest.approx(expected["logLik"], rel=1e-10)
    assert (fit.model.gamma > 1).any()


@pytest.mark.parametrize("name", sorted(FITS))
def test_gamma_max_one_is_spatstats_projection(name):
    expected = FITS[name]["projected"]
    fit = fit_like_spatstat(FITS[name], gamma_max=1.0)
    table = fit.coefficients
    names = expected["coef_names"]
    # the coefficients spatstat keeps are estimated; the terms it dropped are ours at the bound
    assert (table.loc[names, "status"] == "estimated").all()
    np.testing.assert_allclose(table.loc[names, "estimate"], expected["coef"], rtol=PROJECTED_TOLERANCE,
                               atol=PROJECTED_TOLERANCE)
    dropped = table.drop(index=names)
    assert len(dropped) and (dropped["status"] == BOUND).all()
    assert (dropped["estimate"] == 0).all() and dropped["se"].isna().all() and dropped["se_hessian"].isna().all()
    assert fit.log_pl == pytest.approx(expected["logLik"], rel=1e-10)
    assert fit.n_fitted == expected["n_fitted"]
    assert list(fit.vcov.index) == names
    if expected["vcov"] is not None:
        k = len(names)
        np.testing.assert_allclose(fit.vcov, square(expected["vcov"], k), rtol=PROJECTED_TOLERANCE)
        np.testing.assert_allclose(fit.vcov_hessian, square(expected["vcov_hessian"], k), rtol=PROJECTED_TOLERANCE)
    assert (fit.model.gamma <= 1).all()
    assert fit.gamma_max == 1.0


def test_gamma_at_the_bound_is_exactly_gamma_max_in_the_model():
    fit = fit_like_spatstat(FITS["mixed_multistrausshard"], gamma_max=1.0)
    gamma = fit.gamma
    assert gamma.loc["clustered", "clustered"] == 1.0 and gamma.loc["regular", "regular"] == 1.0
    assert 0 < gamma.loc["clustered", "regular"] < 1  # estimated inside the box once the others are fixed
    natural = fit.natural
    assert np.isnan(natural.loc[("gamma", "clustered-clustered"), "se"])
    assert np.isfinite(natural.loc[("gamma", "clustered-regular"), "se"])


# ============================================================================ unchanged without the bound


def test_gamma_max_none_or_inactive_changes_nothing_bit_for_bit():
    clustered = FITS["mixed_multistrauss"]
    free = fit_like_spatstat(clustered)
    loose = fit_like_spatstat(clustered, gamma_max=100.0)  # the bound does not bind
    for a, b in ((free, loose),):
        assert a.coefficients.equals(b.coefficients)
        assert a.vcov.equals(b.vcov) and a.vcov_hessian.equals(b.vcov_hessian)
        assert a.log_pl == b.log_pl and a.iterations == b.iterations
        np.testing.assert_array_equal(a.model.gamma, b.model.gamma)
    assert free.gamma_max is None


def test_regular_pattern_is_not_affected_by_gamma_max_one():
    mixed = dataset("mixed")
    pattern = PointPattern(mixed.of_type("regular"), mixed.window)  # simple sequential inhibition
    free = ppm(pattern, 0.0925, quadrature="spatstat")
    bounded = ppm(pattern, 0.0925, quadrature="spatstat", gamma_max=1.0)
    assert free.model.gamma[0, 0] < 1
    assert free.coefficients.equals(bounded.coefficients) and free.log_pl == bounded.log_pl


# ============================================================================ other bounds: the KKT point


def _problem(seed, n_columns=4):
    """A random Poisson-GLM log PL (design with intercept, weights, data flags) with a maximum."""
    rng = np.random.default_rng(seed)
    k = 400
    design = np.column_stack([np.ones(k), rng.poisson(1.5, size=(k, n_columns - 1))]).astype(np.float64)
    weights = rng.uniform(0.5, 1.5, k) / k
    is_data = rng.random(k) < 0.3
    return design, weights, is_data


def _scipy_bounded(design, weights, is_data, upper):
    data_statistic = design[is_data].sum(axis=0)

    def negative(theta):
        value, intensity = _log_pl(theta, design, weights, data_statistic)
        return -value, -(data_statistic - design.T @ intensity)

    bounds = [(None, None if np.isinf(u) else u) for u in upper]
    result = minimize(negative, np.minimum(0.0, upper), jac=True, method="L-BFGS-B", bounds=bounds,
                      options=dict(ftol=1e-15, gtol=1e-12, maxiter=10_000))
    return result.x, -result.fun


# seeds 96 and 151 (with log_bound 0) release a coefficient fixed on the way to the bound
@pytest.mark.parametrize("seed", [*range(12), 96, 151])
@pytest.mark.parametrize("log_bound", [-0.2, 0.0, 0.3])
def test_bounded_maximum_is_the_constrained_optimum(seed, log_bound):
    design, weights, is_data = _problem(seed)
    upper = np.array([np.inf, log_bound, log_bound, log_bound])
    start = np.array([np.log(is_data.sum()), 0.0, 0.0, 0.0])
    ours = _maximise_bounded(design, weights, is_data, start, upper)
    theirs, value = _scipy_bounded(design, weights, is_data, upper)
    assert (ours.theta <= upper).all()
    np.testing.assert_array_equal(ours.theta[ours.at_bound], upper[ours.at_bound])
    assert ours.log_pl >= value - 1e-9
    np.testing.assert_allclose(ours.theta, theirs, atol=1e-5)
    # KKT: zero derivative for the free coefficients, non-negative at the upper bound, in units
    # of each coefficient's standard error 1 / sqrt(information), to what Newton's stopping rule
    # resolves (a gain in log PL of ROUNDING_RESOLUTION relative)
    data_statistic = design[is_data].sum(axis=0)
    _, intensity = _log_pl(ours.theta, design, weights, data_statistic)
    scaled = (data_statistic - design.T @ intensity) / np.sqrt((design**2 * intensity[:, None]).sum(axis=0))
    resolution = 10 * np.sqrt(ROUNDING_RESOLUTION * (1 + abs(ours.log_pl)))
    np.testing.assert_allclose(scaled[~ours.at_bound], 0, atol=resolution)
    assert (scaled[ours.at_bound] > -resolution).all()


def test_a_bound_other_than_one_on_redwood():
    fit = FITS["redwood_strauss"]
    free, at_1 = fit_like_spatstat(fit), fit_like_spatstat(fit, gamma_max=1.0)
    between = fit_like_spatstat(fit, gamma_max=1.2)
    below = fit_like_spatstat(fit, gamma_max=0.5)
    assert free.model.gamma[0, 0] > 1.2
    assert between.model.gamma[0, 0] == 1.2 and below.model.gamma[0, 0] == 0.5
    assert free.log_pl > between.log_pl > at_1.log_pl > below.log_pl  # a tighter bound costs log PL
    assert between.coefficients.loc["Interaction", "estimate"] == pytest.approx(np.log(1.2), abs=1e-15)


def test_fit_strauss_hardcore_passes_gamma_max():
    pattern = dataset("redwood")
    free = fit_strauss_hardcore(pattern, r=0.0805)
    bounded = fit_strauss_hardcore(pattern, r=0.0805, gamma_max=1.0)
    assert free.model.gamma[0, 0] > 1
    assert bounded.model.gamma[0, 0] == 1.0
    assert bounded.coefficients.loc["Interaction", "status"] == BOUND
    assert bounded.fit.gamma_max == 1.0


# ============================================================================ input validation


@pytest.mark.parametrize("value", [0.0, -1.0, float("nan"), float("inf"), "1", True, [1.0]])
def test_gamma_max_must_be_a_positive_finite_float(value):
    pattern = dataset("redwood")
    with pytest.raises(ValueError, match=r"gamma_max must be a positive finite float or None.*got"):
        ppm(pattern, 0.0805, gamma_max=value)
    with pytest.raises(ValueError, match="gamma_max"):
        fit_strauss_hardcore(pattern, r=0.0805, gamma_max=value)


def test_an_unidentifiable_gamma_is_capped_by_a_bound_below_one():
    pattern = dataset("redwood")
    with pytest.warns(UserWarning, match="not identifiable"):
        fit = ppm(pattern, 0.01, 0.01, quadrature="spatstat", gamma_max=0.5)  # r = h: an empty shell
    assert fit.coefficients.loc["Interaction", "status"] == "not identifiable (gamma = gamma_max)"
    assert fit.model.gamma[0, 0] == 0.5
    with pytest.warns(UserWarning, match="not identifiable"):
        assert ppm(pattern, 0.01, 0.01, quadrature="spatstat", gamma_max=1.0).model.gamma[0, 0] == 1.0
