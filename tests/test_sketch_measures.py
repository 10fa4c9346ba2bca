"""The measures of paperlib.sketch.measures on curves with known answers."""

import numpy as np
import pytest

from paperlib.sketch import box_counting_dimension, curve_hausdorff, densify, turning_ks, turning_per_sample


def circle(n=200, radius=1.0):
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return radius * np.column_stack([np.cos(t), np.sin(t)])


def koch(level):
    """The Koch curve from (0, 0) to (1, 0): box-counting dimension log 4 / log 3."""
    points = np.array([[0.0, 0.0], [1.0, 0.0]])
    rotate = np.array([[0.5, -np.sqrt(3) / 2], [np.sqrt(3) / 2, 0.5]])
    for _ in range(level):
        a, b = points[:-1], points[1:]
        third = (b - a) / 3
        peak = a + third + third @ rotate.T
        points = np.vstack([np.stack([a, a + third, peak, a + 2 * third], axis=1).reshape(-1, 2), points[-1:]])
    return points


def test_densify_keeps_vertices_and_bounds_spacing():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    dense = densify(square, closed=True, spacing=0.3)
    assert len(dense) == 16 and np.all(np.hypot(*np.diff(np.vstack([dense, dense[:1]]), axis=0).T) <= 0.3)
    assert all(any(np.allclose(v, d) for d in dense) for v in square)
    open_dense = densify(square, closed=False, spacing=0.5)
    np.testing.assert_array_equal(open_dense[[0, -1]], square[[0, -1]])


def test_hausdorff_between_concentric_circles_and_between_segments():
    assert curve_hausdorff(circle(), circle(radius=1.25), closed=True) == pytest.approx(0.25, abs=1e-3)
    # the vertices of a square are 0.5 from the midpoints of a rotated copy, its sides much closer
    a = np.array([[0.0, 0.0], [2.0, 0.0]])
    b = np.array([[0.0, 1.0], [1.0, 0.0], [2.0, 1.0]])
    assert curve_hausdorff(a, b, closed=False) == pytest.approx(1.0, abs=0.02)


def test_turning_sums_to_the_total_turning():
    assert turning_per_sample(circle(), closed=True).sum() == pytest.approx(2 * np.pi)
    assert turning_per_sample(circle()[::-1], closed=True).sum() == pytest.approx(-2 * np.pi)
    np.testing.assert_allclose(turning_per_sample(circle(100), closed=True), 2 * np.pi / 100)
    assert turning_per_sample(circle()[:50], closed=False).shape == (48,)


def test_ks_distance():
    rng = np.random.default_rng(0)
    x = rng.normal(size=500)
    assert turning_ks(x, x) == 0.0
    assert turning_ks(x, x + 100.0) == 1.0
    with pytest.raises(ValueError):
        turning_ks([], x)


def test_box_counting_dimension_of_smooth_and_fractal_curves():
    assert box_counting_dimension(circle(400), closed=True) == pytest.approx(1.0, abs=0.08)
    fractions = 3.0 ** -np.arange(1, 5)
    assert box_counting_dimension(koch(6), closed=False, fractions=fractions) == pytest.approx(
        np.log(4) / np.log(3), abs=0.06)
    with pytest.raises(ValueError, match="fractions"):
        box_counting_dimension(circle(), closed=True, fractions=[0.5])
    with pytest.raises(ValueError, match="single point"):
        box_counting_dimension(np.zeros((5, 2)), closed=True)


def test_densifying_beyond_the_budget_is_refused_before_allocating():
    """A random fuzz run: curve_hausdorff's default resolution (a hundredth of the smaller curve's mean
    segment) on a curve 1e-10 wide against a unit one asked for 7e11 points (5 TiB)."""
    tiny = np.array([[0.0, 0.0], [1e-10, 0.0], [1e-10, 1e-10]])
    unit = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    with pytest.raises(ValueError, match="max_samples"):
        curve_hausdorff(tiny, unit, closed=False)
    with pytest.raises(ValueError, match="max_samples"):
        densify(unit, closed=False, spacing=1e-300)  # 2e300 points: counted as floats, no int64 overflow
    with pytest.raises(ValueError, match="max_samples"):
        box_counting_dimension(unit, closed=False, fractions=(1e-9, 0.5))
    assert len(densify(unit, closed=False, spacing=0.5, max_samples=5)) == 5
    with pytest.raises(ValueError, match="max_samples"):
        densify(unit, closed=False, spacing=0.5, max_samples=4)
