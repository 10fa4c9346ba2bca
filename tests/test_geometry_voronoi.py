"""paperlib.geometry.voronoi: Lloyd relaxation (Barla 2006 section 3.2, Hurtut 2009 Figure 6 right)."""

import numpy as np
import pytest
import shapely
from scipy.spatial import cKDTree
from shapely.geometry import MultiPolygon, Polygon, box

from paperlib.geometry import lloyd_relaxation

UNIT = (0.0, 1.0, 0.0, 1.0)


def random_points(n, seed=0, scale=(1.0, 1.0), offset=(0.0, 0.0)):
    return np.random.default_rng(seed).random((n, 2)) * scale + offset


# --------------------------------------------------------------------------- known answers


def test_four_points_in_a_square_converge_to_the_quadrant_centres():
    start = [(0.1, 0.1), (0.2, 0.9), (0.9, 0.2), (0.8, 0.8)]
    relaxed = lloyd_relaxation(start, UNIT, 300)
    # Each point keeps its quadrant (order preserved) and sits at its centre.
    assert np.allclose(relaxed, [(0.25, 0.25), (0.25, 0.75), (0.75, 0.25), (0.75, 0.75)], atol=1e-9)


def test_one_step_moves_each_point_to_its_clipped_cell_centroid():
    # Two points on a horizontal line in [0, 4] x [0, 1]: the bisector x = 1.5 splits the
    # rectangle into [0, 1.5] x [0, 1] and [1.5, 4] x [0, 1], with centroids 0.75 and 2.75.
    relaxed = lloyd_relaxation([(1.0, 0.5), (2.0, 0.5)], (0.0, 4.0, 0.0, 1.0), 1)
    assert np.allclose(relaxed, [(0.75, 0.5), (2.75, 0.5)], rtol=0, atol=1e-12)


def test_one_step_off_axis_matches_an_independent_clipped_cell():
    # Bisector of (0.1, 0.1) and (0.5, 0.3) is the line 0.4 x + 0.2 y = 0.16 (2x + y = 0.8):
    # the first cell is the triangle (0,0), (0.4,0), (0,0.8), centroid (0.4/3, 0.8/3).
    relaxed = lloyd_relaxation([(0.1, 0.1), (0.5, 0.3)], UNIT, 1)
    assert np.allclose(relaxed[0], (0.4 / 3, 0.8 / 3), rtol=0, atol=1e-12)
    # The second cell is the rest of the square: (area-weighted) complement of the triangle.
    triangle_area, triangle_centroid = 0.16, np.array([0.4 / 3, 0.8 / 3])
    rest = (np.array([0.5, 0.5]) - triangle_area * triangle_centroid) / (1 - triangle_area)
    assert np.allclose(relaxed[1], rest, rtol=0, atol=1e-12)


def test_single_point_goes_to_the_window_centroid():
    assert np.allclose(lloyd_relaxation([(0.1, 0.3)], (0.0, 2.0, 0.0, 4.0), 1), [(1.0, 2.0)])


def test_points_on_a_line_become_evenly_spaced_in_1d():
    # Collinear points in a thin strip: the cells are vertical bands and the 1-D Lloyd fixed
    # point is evenly spaced (in a square the collinear state is a saddle and the points spread).
    start = np.column_stack([[0.05, 0.1, 0.3, 0.35, 0.9], np.full(5, 0.025)])
    relaxed = lloyd_relaxation(start, (0.0, 1.0, 0.0, 0.05), 400)
    assert np.allclose(relaxed[:, 0], [0.1, 0.3, 0.5, 0.7, 0.9], atol=1e-6)
    assert np.allclose(relaxed[:, 1], 0.025)


def test_relaxation_makes_random_points_regular():
    start = random_points(200, seed=3)
    relaxed = lloyd_relaxation(start, UNIT, 60)
    nn_start = cKDTree(start).query(start, 2)[0][:, 1]
    nn_relaxed = cKDTree(relaxed).query(relaxed, 2)[0][:, 1]
    # Near a centroidal (hexagonal-like) tessellation the spacing is sqrt(2 / (sqrt(3) n)) ~ 0.076:
    # every nearest neighbour within a factor of the ideal, unlike Poisson points.
    ideal = np.sqrt(2 / (np.sqrt(3) * len(start)))
    assert nn_relaxed.min() > 0.6 * ideal > nn_start.min()
    assert nn_relaxed.std() / nn_relaxed.mean() < 0.5 * nn_start.std() / nn_start.mean()


def test_non_convex_centroid_outside_its_cell_is_projected_onto_the_cell():
    # A U shape: its centroid (0.5, ~0.33) lies inside the notch, outside the region.
    u_shape = Polygon([(0, 0), (1, 0), (1, 1), (0.7, 1), (0.7, 0.2), (0.3, 0.2), (0.3, 1), (0, 1)])
    assert not u_shape.contains(u_shape.centroid)
    relaxed = lloyd_relaxation([(0.1, 0.5)], u_shape, 1)
    expected = shapely.get_coordinates(shapely.shortest_line(u_shape, u_shape.centroid))[0]
    assert np.allclose(relaxed[0], expected)
    # The centroid (0.5, 0.308 / 0.68) is 0.2 from the notch's walls x = 0.3 and x = 0.7.
    assert np.isclose(relaxed[0, 1], (0.5 - 0.32 * 0.6) / 0.68)
    assert np.isclose(abs(relaxed[0, 0] - 0.5), 0.2)
    assert u_shape.covers(shapely.Point(relaxed[0]))


@pytest.mark.parametrize("window", [
    Polygon([(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]),  # L shape
    Polygon([(0, 0), (1, 0), (1, 1), (0, 1)], [[(0.3, 0.3), (0.7, 0.3), (0.7, 0.7), (0.3, 0.7)]]),  # ring
    MultiPolygon([box(0, 0, 1, 1), box(2, 0, 3, 1)]),
])
def test_points_stay_in_non_convex_windows(window):
    rng = np.random.default_rng(1)
    xmin, ymin, xmax, ymax = window.bounds
    start = rng.uniform((xmin, ymin), (xmax, ymax), size=(400, 2))
    start = start[shapely.contains_xy(window, start[:, 0], start[:, 1])][:60]
    relaxed = lloyd_relaxation(start, window, 30)
    assert relaxed.shape == start.shape
    assert shapely.covers(window, shapely.points(relaxed)).all()


# --------------------------------------------------------------------------- invariants


def test_invariants_count_window_determinism_and_input_untouched():
    start = random_points(80, seed=5, scale=(2.0, 1.0), offset=(-1.0, 3.0))
    before = start.copy()
    window = (-1.0, 1.0, 3.0, 4.0)
    a = lloyd_relaxation(start, window, 20)
    b = lloyd_relaxation(start, window, 20)
    assert a.shape == (80, 2)
    assert np.array_equal(a, b)
    assert np.array_equal(start, before)
    assert ((a[:, 0] >= -1) & (a[:, 0] <= 1) & (a[:, 1] >= 3) & (a[:, 1] <= 4)).all()


def test_rectangle_tuple_and_polygon_agree():
    start = random_points(30, seed=2)
    assert np.allclose(lloyd_relaxation(start, UNIT, 10), lloyd_relaxation(start, box(0, 0, 1, 1), 10))


def test_zero_iterations_returns_a_copy_and_steps_compose():
    start = random_points(25, seed=4)
    assert np.array_equal(lloyd_relaxation(start, UNIT, 0), start)
    assert np.allclose(lloyd_relaxation(lloyd_relaxation(start, UNIT, 3), UNIT, 4), lloyd_relaxation(start, UNIT, 7))


def test_energy_decreases():
    # Lloyd's method does not increase the quantization energy sum_i int_{V_i} |x - p_i|^2.
    grid = (np.stack(np.meshgrid(np.linspace(0, 1, 201), np.linspace(0, 1, 201)), -1).reshape(-1, 2))

    def energy(points):
        return float(np.mean(cKDTree(points).query(grid)[0] ** 2))

    points = random_points(40, seed=6)
    energies = [energy(points)]
    for _ in range(5):
        points = lloyd_relaxation(points, UNIT, 1)
        energies.append(energy(points))
    assert all(later <= earlier + 1e-6 for earlier, later in zip(energies, energies[1:]))
    assert energies[-1] < 0.8 * energies[0]


def test_tol_stops_early_at_the_fixed_point():
    relaxed = lloyd_relaxation([(0.25, 0.5), (0.75, 0.5)], UNIT, 1000, tol=1e-12)
    assert np.allclose(relaxed, [(0.25, 0.5), (0.75, 0.5)])


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize("points, match", [
    (np.empty((0, 2)), "at least 1"),
    ([(0.5, np.nan)], "NaN"),
    ([(0.5, np.inf)], "NaN or infinite"),
    ([(0.5, 0.5, 0.5)], "shape"),
    ([(0.5, 1.5)], "outside the window"),
    ([(0.2, 0.2), (0.2, 0.2)], "distinct"),
    ("points", "numeric"),
])
def test_bad_points(points, match):
    with pytest.raises(ValueError, match=match):
        lloyd_relaxation(points, UNIT, 3)


@pytest.mark.parametrize("window", [
    (0, 1, 1, 0), (0, 0, 0, 1), (0, np.nan, 0, 1), (0, 1, 0), "unit", ("a", 1, 0, 1),
    Polygon([(0, 0), (1, 1), (1, 0), (0, 1)]),  # self-intersecting bow tie
    Polygon(),
])
def test_bad_window(window):
    with pytest.raises(ValueError, match="window"):
        lloyd_relaxation([(0.5, 0.5)], window, 3)


@pytest.mark.parametrize("iterations", [-1, 2.5, "3", True, None])
def test_bad_iterations(iterations):
    with pytest.raises(ValueError, match="iterations"):
        lloyd_relaxation([(0.5, 0.5)], UNIT, iterations)


def test_cells_beyond_the_budget_are_refused_before_the_first_step():
    points = [(0.2, 0.2), (0.8, 0.7)]
    with pytest.raises(ValueError, match="max_cells"):
        lloyd_relaxation(points, UNIT, 10**9)
    with pytest.raises(ValueError, match="max_cells"):
        lloyd_relaxation(points, UNIT, 4, max_cells=7)
    np.testing.assert_array_equal(lloyd_relaxation(points, UNIT, 4, max_cells=8), lloyd_relaxation(points, UNIT, 4))


@pytest.mark.parametrize("tol", [-1.0, np.nan, "x"])
def test_bad_tol(tol):
    with pytest.raises(ValueError, match="tol"):
        lloyd_relaxation([(0.5, 0.5)], UNIT, 3, tol=tol)
