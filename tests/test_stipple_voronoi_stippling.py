"""paperlib.stipple.voronoi_stippling: Secord 2002 weighted Voronoi stippling, the baseline of Kim 2009."""

import numpy as np
import pytest
from scipy.spatial import cKDTree

from paperlib.stipple.voronoi_stippling import (
    VoronoiStipples,
    render_stipples,
    stipple_density,
    weighted_centroids,
    weighted_voronoi_stipples,
)


def nearest_neighbour_cv(points):
    """Coefficient of variation of nearest-neighbour distances: ~0.5 for Poisson, small for even spacing."""
    distances, _ = cKDTree(points).query(points, k=2)
    nearest = distances[:, 1]
    return nearest.std() / nearest.mean()


def gradient_image(width=200, height=100):
    """Intensity 0 (black) at the left to 0.8 at the right: density 1 -> 0.2."""
    return np.tile(np.linspace(0.0, 0.8, width), (height, 1))


# ============================================================================ density


def test_density_is_one_minus_intensity_for_every_dtype():
    floats = np.array([[0.0, 0.25], [1.0, 0.5]])
    assert np.array_equal(stipple_density(floats), 1.0 - floats)
    assert np.allclose(stipple_density(np.array([[0, 255], [51, 255]], dtype=np.uint8)), [[1.0, 0.0], [0.8, 0.0]])
    assert np.array_equal(stipple_density(np.array([[True, False]])), [[1.0, 0.0]])


# ============================================================================ weighted centroids (known answers)


def test_single_cell_weighted_centroid_by_hand():
    # One generator owns every pixel; density 1 at pixel (row 0, col 1), 3 at (row 1, col 2):
    # x = (1 * 1 + 3 * 2) / 4 = 1.75, y = (1 * 0 + 3 * 1) / 4 = 0.75.
    density = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 3.0]])
    centroids, mass = weighted_centroids([[0.0, 0.0]], density)
    assert np.allclose(centroids, [[1.75, 0.75]])
    assert np.allclose(mass, [4.0])


def test_two_cells_split_by_nearest_generator():
    # Pixels x = 0, 1 are nearer (0, 0); x = 2, 3 nearer (3, 0).
    density = np.array([[1.0, 1.0, 2.0, 2.0]])
    centroids, mass = weighted_centroids([[0.0, 0.0], [3.0, 0.0]], density)
    assert np.allclose(centroids, [[0.5, 0.0], [2.5, 0.0]])
    assert np.allclose(mass, [2.0, 4.0])


def test_cell_without_density_keeps_its_point():
    centroids, mass = weighted_centroids([[0.0, 0.0], [3.0, 0.0]], np.array([[1.0, 0.0, 0.0, 0.0]]))
    assert np.allclose(centroids, [[0.0, 0.0], [3.0, 0.0]])
    assert np.allclose(mass, [1.0, 0.0])


def test_weighted_centroids_match_brute_force_assignment():
    rng = np.random.default_rng(3)
    density = rng.random((30, 40))
    points = rng.uniform(0, 29, (12, 2))
    centroids, mass = weighted_centroids(points, density)
    rows, cols = np.mgrid[:30, :40]
    squared = (cols[..., None] - points[:, 0]) ** 2 + (rows[..., None] - points[:, 1]) ** 2
    owner = squared.argmin(axis=-1)
    for k in range(len(points)):
        cell = owner == k
        assert mass[k] == pytest.approx(density[cell].sum())
        assert centroids[k, 0] == pytest.approx((density * cols)[cell].sum() / density[cell].sum())
        assert centroids[k, 1] == pytest.approx((density * rows)[cell].sum() / density[cell].sum())


# ============================================================================ stippling


def test_constant_density_relaxes_to_an_even_arrangement():
    image = np.full((128, 128), 0.5)
    start = weighted_voronoi_stipples(image, 300, iterations=0, rng=1)
    relaxed = weighted_voronoi_stipples(image, 300, iterations=100, tol=0.0, rng=1)
    assert nearest_neighbour_cv(start.points) > 0.4  # Poisson-like rejection sample
    assert nearest_neighbour_cv(relaxed.points) < 0.15  # near-regular after Lloyd


def test_points_concentrate_where_the_image_is_dark():
    image = gradient_image()
    width = image.shape[1]
    x = np.arange(width)
    density_mean_x = np.sum(x * (1 - image[0])) / np.sum(1 - image[0])  # 0.388 of the width
    start = weighted_voronoi_stipples(image, 800, iterations=0, rng=0)
    relaxed = weighted_voronoi_stipples(image, 800, iterations=200, tol=1e-3, rng=0)
    # The standard error of the sample mean is about 0.27 * width / sqrt(800) ~ 0.01 width; allow 3 of them.
    assert abs(start.points[:, 0].mean() - density_mean_x) < 0.03 * width
    assert abs(relaxed.points[:, 0].mean() - density_mean_x) < 0.03 * width
    # Relaxation evens out the spacing but keeps the large-scale distribution of the start.
    assert abs(relaxed.points[:, 0].mean() - start.points[:, 0].mean()) < 0.01 * width
    left = np.count_nonzero(relaxed.points[:, 0] < (width - 1) / 2)
    # Dark-half to light-half density mass is 0.4 / 0.2 = 2; sqrt(rho), the asymptotic CVT optimum, would give ~1.35.
    assert left > 1.6 * (800 - left)


def test_points_stay_in_the_image_and_avoid_white_pixels():
    image = np.ones((60, 80))
    image[10:30, 20:50] = 0.3  # a gray rectangle on white
    result = weighted_voronoi_stipples(image, 150, iterations=30, rng=5)
    x, y = result.points.T
    assert np.all((x >= 19.5) & (x <= 49.5) & (y >= 9.5) & (y <= 29.5))


def test_displacement_decreases_and_stops_at_tolerance():
    image = gradient_image(96, 64)
    result = weighted_voronoi_stipples(image, 200, iterations=300, tol=1e-3, rng=2)
    steps = result.displacements
    assert isinstance(result, VoronoiStipples)
    assert result.converged and steps[-1] < 1e-3 and len(steps) < 300
    assert steps[-1] < steps[0] / 100
    assert np.all(np.diff(steps[:5]) < 0)  # the early steps shrink monotonically
    # A loose tolerance stops after the first step.
    loose = weighted_voronoi_stipples(image, 200, iterations=300, tol=100.0, rng=2)
    assert len(loose.displacements) == 1 and loose.converged
    # Without a tolerance all steps run.
    full = weighted_voronoi_stipples(image, 200, iterations=7, tol=0.0, rng=2)
    assert len(full.displacements) == 7 and not full.converged


def test_same_seed_same_points_bit_for_bit():
    image = gradient_image(64, 48)
    first = weighted_voronoi_stipples(image, 100, iterations=20, rng=11)
    second = weighted_voronoi_stipples(image, 100, iterations=20, rng=np.random.default_rng(11))
    assert np.array_equal(first.points, second.points)
    assert np.array_equal(first.displacements, second.displacements)
    other = weighted_voronoi_stipples(image, 100, iterations=20, rng=12)
    assert not np.array_equal(first.points, other.points)


def test_uint8_image_gives_the_same_stipples_as_its_float_version():
    image = (np.tile(np.linspace(0, 200, 50), (40, 1))).astype(np.uint8)
    as_uint8 = weighted_voronoi_stipples(image, 80, iterations=10, rng=4)
    as_float = weighted_voronoi_stipples(image / 255.0, 80, iterations=10, rng=4)
    assert np.array_equal(as_uint8.points, as_float.points)


def test_one_dark_pixel_collects_every_point_quickly():
    image = np.ones((256, 256))
    image[3, 7] = 0.0  # acceptance rate 1 / 65536 for the rejection sampler
    result = weighted_voronoi_stipples(image, 50, iterations=3, rng=0)
    assert np.all(np.abs(result.points - [7, 3]) <= 0.5)


@pytest.mark.parametrize(
    ("image", "kwargs", "message"),
    [
        (np.zeros((0, 5)), {}, "empty"),
        (np.zeros(5), {}, "2-D"),
        (np.zeros((4, 4, 3)), {}, "2-D"),
        (np.array([[0.5, np.nan]]), {}, "NaN"),
        (np.array([[0.5, 1.5]]), {}, r"\[0, 1\]"),
        (np.zeros((4, 4), dtype=np.int16), {}, "dtype"),
        (np.ones((8, 8)), {}, "all white"),
        (np.full((255, 255), 255, dtype=np.uint8), {}, "all white"),
        (np.zeros((8, 8)), {"n_points": 0}, "n_points"),
        (np.zeros((8, 8)), {"n_points": 2.5}, "n_points"),
        (np.zeros((8, 8)), {"n_points": 65}, "at most"),
        (np.zeros((8, 8)), {"iterations": -1}, "iterations"),
        (np.zeros((8, 8)), {"tol": -0.1}, "tol"),
        (np.zeros((8, 8)), {"tol": np.nan}, "tol"),
    ],
)
def test_bad_input_is_refused(image, kwargs, message):
    arguments = {"n_points": 5, **kwargs}
    n_points = arguments.pop("n_points")
    with pytest.raises(ValueError, match=message):
        weighted_voronoi_stipples(image, n_points, **arguments)


@pytest.mark.parametrize(
    ("points", "density", "message"),
    [
        (np.zeros((0, 2)), np.ones((3, 3)), "empty"),
        ([[0.0, 0.0, 0.0]], np.ones((3, 3)), r"\(n, 2\)"),
        ([[np.nan, 0.0]], np.ones((3, 3)), "NaN"),
        ([[5.0, 0.0]], np.ones((3, 3)), "extent"),
        ([[0.0, 0.0]], -np.ones((3, 3)), "non-negative"),
        ([[0.0, 0.0]], np.ones(3), "2-D"),
    ],
)
def test_weighted_centroids_refuse_bad_input(points, density, message):
    with pytest.raises(ValueError, match=message):
        weighted_centroids(points, density)


# ============================================================================ rendering


def test_disc_matches_the_distance_definition():
    ink = render_stipples([[10.3, 7.6]], (20, 25), radius=3.2)
    rows, cols = np.mgrid[:20, :25]
    expected = (cols - 10.3) ** 2 + (rows - 7.6) ** 2 < 3.2**2
    assert np.array_equal(ink, expected)


def test_tiny_stipples_still_ink_their_pixel_and_empty_input_is_blank():
    ink = render_stipples([[2.5, 1.5], [0.0, 0.0]], (4, 5), radius=0.1)
    assert ink.sum() == 2 and ink[0, 0] and ink[2, 3]  # x = 2.5 rounds to column 3, y = 1.5 to row 2
    assert not render_stipples(np.zeros((0, 2)), (4, 5)).any()


def test_discs_grow_with_density():
    density = np.zeros((40, 80))
    density[:, :40] = 1.0  # dark left half
    ink = render_stipples([[20.0, 20.0], [60.0, 20.0]], (40, 80), radius=4.0, density=density, min_radius=1.0)
    assert ink[:, :40].sum() > 5 * ink[:, 40:].sum()
    assert np.array_equal(ink[:, :40], render_stipples([[20.0, 20.0]], (40, 40), radius=4.0))


def test_rendered_stipples_of_an_image_follow_its_tone():
    image = gradient_image(128, 64)
    points = weighted_voronoi_stipples(image, 400, iterations=30, rng=9).points
    ink = render_stipples(points, image.shape, radius=1.5)
    assert ink.dtype == np.bool_ and ink.shape == image.shape
    assert ink[:, :64].mean() > ink[:, 64:].mean()


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"shape": (0, 5)}, "positive"),
        ({"shape": "ab"}, "shape"),
        ({"points": [[9.0, 0.0]]}, "extent"),
        ({"points": [[1.0, 1.0, 1.0]]}, r"\(n, 2\)"),
        ({"radius": 0.0}, "radius"),
        ({"density": np.ones((4, 4))}, "shape"),
        ({"density": np.full((4, 5), 2.0)}, r"\[0, 1\]"),
        ({"density": np.ones((4, 5)), "min_radius": 3.0}, "exceed"),
        ({"density": np.ones((4, 5)), "min_radius": -1.0}, "min_radius"),
    ],
)
def test_render_refuses_bad_input(kwargs, message):
    arguments = {"points": [[1.0, 1.0]], "shape": (4, 5), "radius": 1.0, **kwargs}
    with pytest.raises(ValueError, match=message):
        render_stipples(arguments.pop("points"), arguments.pop("shape"), **arguments)
