"""Windows, point patterns, models and reference processes of paperlib.pointprocess."""

import numpy as np
import pytest
import shapely.geometry as geom

from paperlib.pointprocess import MultiStraussHard, PointPattern, Poisson, Strauss, StraussHard, Window
from paperlib.pointprocess.models import interaction_counts
from paperlib.pointprocess.processes import rMatClust, rpoispp

UNIT = Window.rectangle()


# --------------------------------------------------------------------------- windows


def test_rectangle_area_contains_and_boundary_distance():
    window = Window.rectangle((0, 2), (1, 2))
    assert window.area == 2.0 and window.is_rectangle
    assert window.contains([[0, 1], [2, 2], [1, 1.5], [2.01, 1.5]]).tolist() == [True, True, True, False]
    np.testing.assert_allclose(window.boundary_distance([[1, 1.5], [0.25, 1.9]]), [0.5, 0.1])


def test_polygon_window_from_vertices_and_shapely():
    triangle = Window.polygon([[0, 0], [1, 0], [0, 1]])
    assert triangle.area == pytest.approx(0.5)
    assert triangle.contains([[0.2, 0.2], [0.6, 0.6], [0.5, 0.5]]).tolist() == [True, False, True]
    assert triangle.boundary_distance([[0.2, 0.2]])[0] == pytest.approx(0.2)
    ring = Window.polygon(geom.Point(0, 0).buffer(2).difference(geom.Point(0, 0).buffer(1)))
    assert not ring.contains([[0, 0]])[0] and ring.contains([[1.5, 0]])[0]


def test_mask_window_orientation_area_and_distance():
    mask = np.zeros((4, 8), dtype=bool)
    mask[0, :] = True  # bottom row: row 0 is at the bottom
    window = Window.mask(mask, (0, 8), (0, 4))
    assert window.area == 8.0 and window.pixel_size == (1.0, 1.0)
    assert window.contains([[3.5, 0.5], [3.5, 3.5]]).tolist() == [True, False]
    assert window.boundary_distance([[3.5, 0.5]])[0] == pytest.approx(0.5)


def test_uniform_points_are_inside_and_reproducible():
    window = Window.polygon(geom.Point(0.5, 0.5).buffer(0.5))
    a, b = window.uniform_points(500, rng=3), window.uniform_points(500, rng=3)
    assert a.shape == (500, 2) and window.contains(a).all()
    np.testing.assert_array_equal(a, b)
    assert window.uniform_points(0, rng=1).shape == (0, 2)


@pytest.mark.parametrize(
    "build, message",
    [
        (lambda: Window.rectangle((0, 0), (0, 1)), "positive area"),
        (lambda: Window.rectangle((0, np.nan), (0, 1)), "finite"),
        (lambda: Window.polygon([[0, 0], [1, 1], [2, 2]]), "zero area|invalid"),
        (lambda: Window.polygon([[0, 0], [1, 1], [1, 0], [0, 1]]), "invalid"),
        (lambda: Window.mask(np.zeros((3, 3), bool)), "no admissible pixel"),
        (lambda: Window.mask(np.full((3, 3), 2)), "boolean"),
        (lambda: Window.mask(np.ones(3, bool)), "2-D"),
        (lambda: UNIT.uniform_points(-1), "non-negative"),
    ],
)
def test_bad_windows(build, message):
    with pytest.raises(ValueError, match=message):
        build()


def test_window_equality():
    assert Window.rectangle() == Window.rectangle((0, 1), (0, 1))
    assert Window.rectangle() != Window.rectangle((0, 2), (0, 1))
    assert Window.mask(np.eye(3, dtype=bool)) == Window.mask(np.eye(3, dtype=bool))


# --------------------------------------------------------------------------- patterns


def test_pattern_counts_types_and_intensity():
    pattern = PointPattern([[0.1, 0.1], [0.2, 0.9], [0.5, 0.5]], Window.rectangle((0, 2), (0, 1)), [1, 0, 1],
                           ["on", "off"])
    assert pattern.n == 3 and pattern.n_types == 2 and pattern.counts.tolist() == [1, 2]
    assert pattern.intensity == 1.5
    np.testing.assert_array_equal(pattern.of_type("off"), [[0.1, 0.1], [0.5, 0.5]])
    assert pattern.type_index(0) == 0 and pattern.unmark().categories == ("points",)
    assert not pattern.points.flags.writeable and not pattern.marks.flags.writeable


def test_empty_pattern_is_allowed():
    empty = PointPattern(np.empty((0, 2)), UNIT)
    assert empty.n == 0 and empty.counts.tolist() == [0]


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(points=[[0.5, np.nan]]), "NaN"),
        (dict(points=[[1.5, 0.5]]), "outside the window"),
        (dict(points=[[0.5, 0.5]], marks=[0, 1]), "shape"),
        (dict(points=[[0.5, 0.5]], marks=[2], categories=["a", "b"]), "0..1"),
        (dict(points=[[0.5, 0.5]], marks=[0.5]), "integer"),
        (dict(points=[[0.5, 0.5]], categories=["a", "a"]), "distinct"),
        (dict(points=[0.5, 0.5, 0.5]), "shape"),
        (dict(points=[[0.5, 0.5]], window="unit"), "Window"),
    ],
)
def test_bad_patterns(kwargs, message):
    kwargs = {"window": UNIT, **kwargs}
    with pytest.raises(ValueError, match=message):
        PointPattern(**kwargs)


def test_unknown_category():
    pattern = PointPattern([[0.5, 0.5]], UNIT, categories=["a"])
    with pytest.raises(ValueError, match="unknown category"):
        pattern.of_type("b")
    with pytest.raises(ValueError, match="out of range"):
        pattern.of_type(3)


# --------------------------------------------------------------------------- models


def brute_force_log_lambda(model, u, t, points, marks, exclude):
    """Direct transcription of the Papangelou intensity of Hurtut 2009 eq. (2)."""
    value = np.log(model.beta[t])
    for j, (x, m) in enumerate(zip(points, marks)):
        if j == exclude:
            continue
        d = np.hypot(*(u - x))
        h, r = model.hc[t, m], model.r[t, m]
        if (d <= h and h > 0) if model.closed else d < h:
            return -np.inf
        if (h < d <= r) if model.closed else (h <= d < r):
            value += np.log(model.gamma[t, m]) if model.gamma[t, m] > 0 else -np.inf
    return value


@pytest.mark.parametrize("closed", [False, True])
def test_log_conditional_intensity_matches_brute_force(closed):
    rng = np.random.default_rng(7)
    model = MultiStraussHard([50, 80, 20], gamma=[[0.5, 0.2, 1], [0.2, 0.8, 0.3], [1, 0.3, 0.1]],
                             r=[[0.1, 0.08, 0.05], [0.08, 0.12, 0.07], [0.05, 0.07, 0.09]],
                             hc=[[0.01, 0.0, 0.02], [0.0, 0.03, 0.0], [0.02, 0.0, 0.01]], closed=closed)
    points, marks = rng.random((60, 2)), rng.integers(0, 3, 60)
    u = np.vstack([rng.random((200, 2)), points[:10]])
    t = np.concatenate([rng.integers(0, 3, 200), marks[:10]])
    exclude = np.concatenate([np.full(200, -1), np.arange(10)])
    got = model.log_conditional_intensity(u, t, points, marks, exclude)
    want = [brute_force_log_lambda(model, u[k], t[k], points, marks, exclude[k]) for k in range(len(u))]
    np.testing.assert_allclose(got, want, rtol=1e-12)
    assert np.isinf(got).any() and np.isfinite(got).any()


def test_distance_ties_follow_the_closed_flag():
    points, marks = np.array([[0.0, 0.0]]), np.array([0])
    at_r, at_h = np.array([[0.5, 0.0]]), np.array([[0.25, 0.0]])
    open_model = StraussHard(1.0, 0.5, r=0.5, hc=0.25, closed=False)
    closed_model = StraussHard(1.0, 0.5, r=0.5, hc=0.25, closed=True)
    assert interaction_counts(open_model, at_r, [0], points, marks)[0][0, 0] == 0  # d < r: not at r
    assert interaction_counts(closed_model, at_r, [0], points, marks)[0][0, 0] == 1  # d <= r
    assert not interaction_counts(open_model, at_h, [0], points, marks)[1][0]  # d < h: not at h
    assert interaction_counts(closed_model, at_h, [0], points, marks)[1][0]  # d <= h


def test_gamma_zero_forbids_only_with_a_neighbour():
    model = Strauss(10.0, 0.0, 0.1)
    values = model.log_conditional_intensity([[0.5, 0.5], [0.9, 0.9]], [0, 0], [[0.55, 0.5]], [0])
    assert np.isneginf(values[0]) and values[1] == pytest.approx(np.log(10))


def test_poisson_and_constructors():
    poisson = Poisson([10, 20], categories=["a", "b"])
    assert poisson.hard_core_only and poisson.n_types == 2
    np.testing.assert_allclose(poisson.log_conditional_intensity([[0.5, 0.5]], [1], [[0.5, 0.51]], [0]), np.log(20))
    assert StraussHard(100, 0.3, 0.1, 0.02).reach == 0.1


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(beta=[0]), "beta must be positive"),
        (dict(beta=[1], gamma=-0.1), "non-negative"),
        (dict(beta=[1], r=0), "positive"),
        (dict(beta=[1], r=0.1, hc=0.2), r"hc <= r"),
        (dict(beta=[1, 1], gamma=[[1, 0.5], [0.2, 1]]), "symmetric"),
        (dict(beta=[1, 1], gamma=[1, 1, 1]), "2x2"),
        (dict(beta=[1, 1], categories=["a"]), "2 distinct names"),
        (dict(beta=[1], gamma=np.nan), "finite"),
    ],
)
def test_bad_models(kwargs, message):
    with pytest.raises(ValueError, match=message):
        MultiStraussHard(**kwargs)


# --------------------------------------------------------------------------- reference processes


def test_rpoispp_counts_follow_the_intensity():
    counts = np.array([rpoispp([100, 50], UNIT, rng=seed).counts for seed in range(200)])
    mean, standard_error = counts.mean(axis=0), np.sqrt(np.array([100, 50]) / 200)
    assert np.all(np.abs(mean - [100, 50]) < 3 * standard_error)
    assert rpoispp([100, 50], UNIT, rng=1) == rpoispp([100, 50], UNIT, rng=1)


def test_rmatclust_intensity_and_clustering():
    patterns = [rMatClust(20, 0.05, 10, UNIT, rng=seed) for seed in range(100)]
    mean = np.mean([p.n for p in patterns])
    assert abs(mean - 200) < 3 * np.sqrt(200 * (1 + 10) / 100)  # cluster variance: mu (1 + mu) kappa
    assert all(p.window.contains(p.points).all() for p in patterns)


@pytest.mark.parametrize("bad", [dict(kappa=0), dict(scale=-1), dict(mu=np.inf)])
def test_rmatclust_bad_parameters(bad):
    with pytest.raises(ValueError):
        rMatClust(**{"kappa": 10, "scale": 0.1, "mu": 5, "window": UNIT, **bad})
