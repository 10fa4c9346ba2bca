"""Tests for paperlib.mlts.basic: the basic processes of Alvarez et al. 2015, Fig. 5."""

import math

import numpy as np
import pytest
import shapely
from scipy import integrate, stats
from shapely.geometry import LineString, box
from shapely.ops import split

from paperlib.mlts.basic import (
    _mean_lens_area,
    DEFAULT_PALETTE,
    _chaos_game,
    _line_cell_labels,
    barnsley_fern,
    box_counting_dimension,
    dead_leaves,
    dead_leaves_coverage,
    dead_leaves_coverage_std,
    dead_leaves_mean_area,
    dead_leaves_window_area,
    ifs_chaos_game,
    ifs_fractal,
    poisson_line_tessellation,
    sierpinski_triangle,
    voronoi_tessellation,
)

PALETTE = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])


def _radius_cdf(r, r_min, r_max, alpha):
    """CDF of the density proportional to r^(-alpha) on [r_min, r_max], by quadrature (independent oracle)."""
    total = integrate.quad(lambda s: s**-alpha, r_min, r_max)[0]
    return np.array([integrate.quad(lambda s: s**-alpha, r_min, x)[0] / total for x in np.atleast_1d(r)])


# ---------------------------------------------------------------------------------------------
# dead leaves
# ---------------------------------------------------------------------------------------------


def test_dead_leaves_first_leaf_on_top_matches_reverse_painting():
    image, labels, (discs, colour_index) = dead_leaves((40, 56), n_leaves=120, r_min=1.0, r_max=9.0, palette=PALETTE,
                                                        rng=3, return_labels=True, return_geometry=True)
    assert image.shape == (40, 56, 3) and labels.shape == (40, 56) and discs.shape == (120, 3)
    # Painter's algorithm in reverse drop order: the first leaf ends on top.
    ys, xs = np.mgrid[0:40, 0:56] + 0.5
    expected = np.full((40, 56), -1)
    for index in range(len(discs) - 1, -1, -1):
        x, y, r = discs[index]
        expected[(xs - x) ** 2 + (ys - y) ** 2 <= r * r] = index
    np.testing.assert_array_equal(labels, expected)
    covered = labels >= 0
    np.testing.assert_array_equal(image[covered], PALETTE[colour_index[labels[covered]]])
    np.testing.assert_array_equal(image[~covered], np.ones((int((~covered).sum()), 3)))


@pytest.mark.parametrize("alpha", [3.0, 1.0, 2.5, 4.5])
def test_mean_area_closed_form_matches_quadrature(alpha):
    r_min, r_max = 0.7, 25.0
    second_moment = (integrate.quad(lambda r: r ** (2 - alpha), r_min, r_max)[0]
                     / integrate.quad(lambda r: r**-alpha, r_min, r_max)[0])
    assert dead_leaves_mean_area(r_min, r_max, alpha) == pytest.approx(math.pi * second_moment, rel=1e-9)


@pytest.mark.parametrize("r_min, r_max, alpha, expected", [
    (1e-10, 1e10, 40.0, math.pi * 39 / 37 * 1e-20),  # both moments dominated by r_min: E[r^2] = (39/37) r_min^2
    (1e-100, 1.0, 3.5, math.pi * 5e-200),  # E[r^2] = 5 r_min^2, computed directly
    (1e-300, 1.0, 4.0, 0.0),  # r_min^-3 = 1e900 overflows; E[r^2] = 3 r_min^2 = 3e-600 underflows to 0
    (1.0, 1e150, 1.5, math.pi / 3 * 1e225),  # numerator from r_max, normaliser from r_min
])
def test_mean_area_at_extreme_bounds_goes_through_logarithms(r_min, r_max, alpha, expected):
    """A random fuzz run: r_min = 2e-313 with alpha = 77 overflowed r_min**(1 - alpha)."""
    assert dead_leaves_mean_area(r_min, r_max, alpha) == pytest.approx(expected, rel=1e-9, abs=0.0)
    assert dead_leaves_mean_area(2.2250738585e-313, 1.0, 76.9) >= 0.0  # underflows to 0, no error
    with pytest.raises(ValueError, match="exceeds the largest float"):
        dead_leaves_mean_area(1e-300, 1e300, 0.1)


@pytest.mark.parametrize("alpha", [3.0, 1.0, 2.2])
def test_dead_leaves_radii_follow_power_law_and_centres_fill_enlarged_window(alpha):
    _, (discs, _) = dead_leaves((32, 48), n_leaves=5000, r_min=1.5, r_max=12.0, alpha=alpha, rng=11,
                                return_geometry=True)
    result = stats.kstest(discs[:, 2], lambda r: _radius_cdf(r, 1.5, 12.0, alpha))
    assert result.pvalue > 1e-3
    assert discs[:, 2].min() >= 1.5 and discs[:, 2].max() <= 12.0
    # Centres uniform in [-r_max, W + r_max] x [-r_max, H + r_max].
    assert stats.kstest(discs[:, 0], stats.uniform(-12.0, 48 + 24.0).cdf).pvalue > 1e-3
    assert stats.kstest(discs[:, 1], stats.uniform(-12.0, 32 + 24.0).cdf).pvalue > 1e-3


@pytest.mark.parametrize(("shape", "n", "r_min", "r_max", "alpha"), [
    ((128, 128), 1500, 1.0, 16.0, 3.0),
    ((96, 128), 400, 2.0, 20.0, 2.0),
])
def test_dead_leaves_coverage_matches_boolean_model(shape, n, r_min, r_max, alpha):
    seeds = range(8)
    measured = np.mean([(dead_leaves(shape, n_leaves=n, r_min=r_min, r_max=r_max, alpha=alpha, rng=seed,
                                     return_labels=True)[1] >= 0).mean() for seed in seeds])
    mean_area = dead_leaves_mean_area(r_min, r_max, alpha)
    area = dead_leaves_window_area(shape, r_max)
    sigma = dead_leaves_coverage_std(n, shape, r_min, r_max, alpha) / math.sqrt(len(seeds))
    tolerance = 4.0 * sigma
    assert abs(measured - dead_leaves_coverage(n, mean_area, area)) < tolerance
    # The test has power: the coverage predicted by a wrong radius law lies outside the tolerance.
    wrong_alpha = alpha - 0.7
    wrong = dead_leaves_coverage(n, dead_leaves_mean_area(r_min, r_max, wrong_alpha), area)
    assert abs(measured - wrong) > tolerance


def _brute_force_coverage_std(n, shape, r_min, r_max, alpha):
    """Var of the covered fraction over every ordered pair of pixel centres, L(d) by adaptive quadrature."""
    height, width = shape
    a = dead_leaves_mean_area(r_min, r_max, alpha)
    area = dead_leaves_window_area(shape, r_max)
    norm = integrate.quad(lambda r: r**-alpha, r_min, r_max)[0]

    def lens(d):
        def integrand(r):
            if d >= 2 * r:
                return 0.0
            return (2 * r * r * math.acos(d / (2 * r)) - d / 2 * math.sqrt(4 * r * r - d * d)) * r**-alpha / norm
        return integrate.quad(integrand, max(r_min, d / 2), r_max, limit=200)[0] if d < 2 * r_max else 0.0

    rows, cols = np.divmod(np.arange(height * width), width)
    distances = np.hypot(rows[:, None] - rows[None, :], cols[:, None] - cols[None, :])
    unique, inverse = np.unique(np.round(distances, 12), return_inverse=True)
    lenses = np.array([lens(d) for d in unique])[inverse.reshape(distances.shape)]
    covariance = (1 - (2 * a - lenses) / area) ** n - (1 - a / area) ** (2 * n)
    return math.sqrt(covariance.sum()) / (height * width)


def test_mean_lens_area_at_zero_is_the_mean_leaf_area():
    for r_min, r_max, alpha in [(2.0, 200.0, 3.0), (1.0, 8.0, 1.0), (0.5, 30.0, 2.2)]:
        lens = _mean_lens_area(np.array([0.0]), r_min, r_max, alpha)[0]
        assert lens == pytest.approx(dead_leaves_mean_area(r_min, r_max, alpha), rel=1e-7)


@pytest.mark.parametrize(("shape", "n", "r_min", "r_max", "alpha"), [
    ((7, 9), 40, 0.6, 4.0, 3.0),  # discs reach across the image: the far pairs barely exist
    ((12, 10), 150, 0.3, 2.5, 2.0),  # many pairs beyond 2 r_max, where a fixed n makes Cov < 0
])
def test_coverage_std_equals_the_pairwise_sum(shape, n, r_min, r_max, alpha):
    expected = _brute_force_coverage_std(n, shape, r_min, r_max, alpha)
    assert dead_leaves_coverage_std(n, shape, r_min, r_max, alpha) == pytest.approx(expected, rel=1e-4)


def test_coverage_std_matches_seed_spread_and_binomial_limit():
    shape, n, r_min, r_max = (64, 64), 300, 2.0, 10.0
    covered = [(dead_leaves(shape, n_leaves=n, r_min=r_min, r_max=r_max, rng=seed, return_labels=True)[1] >= 0).mean()
               for seed in range(400)]
    # Sample std of 400 draws: relative standard error 1/sqrt(2 * 399) = 3.5 %, so 14 % is 4 sigma
    # (the formula without the far pairs was 10 % too high here, the CDF-grid quadrature 4 % too low).
    assert np.std(covered, ddof=1) == pytest.approx(dead_leaves_coverage_std(n, shape, r_min, r_max), rel=0.14)
    # Discs too small to cover two pixel centres: binomial variance plus, for every other pair, the
    # covariance of a fixed number of leaves (1 - 2a/A)^n - (1 - a/A)^(2n), in closed form.
    p = dead_leaves_mean_area(0.1, 0.45, 3.0) / dead_leaves_window_area(shape, 0.45)
    q, pixels = 1 - (1 - p) ** n, 64 * 64
    pair = (1 - 2 * p) ** n - (1 - p) ** (2 * n)
    closed_form = math.sqrt(q * (1 - q) / pixels + (pixels - 1) / pixels * pair)
    assert dead_leaves_coverage_std(n, shape, 0.1, 0.45) == pytest.approx(closed_form, rel=1e-6)  # cancellation in pair
    assert closed_form < 0.97 * math.sqrt(q * (1 - q) / pixels)  # the far pairs matter: 5 % here


def test_dead_leaves_coverage_target_and_prefix_property():
    kwargs = dict(r_min=1.0, r_max=10.0, palette=PALETTE, rng=5, return_labels=True, return_geometry=True)
    image, labels, (discs, _) = dead_leaves((48, 64), coverage_target=1.0, **kwargs)
    assert np.all(labels >= 0)
    used = len(discs)
    assert labels.max() == used - 1  # the last leaf dropped covered the last uncovered pixel
    same_image, same_labels, _ = dead_leaves((48, 64), n_leaves=used, **kwargs)
    np.testing.assert_array_equal(same_image, image)
    np.testing.assert_array_equal(same_labels, labels)
    # A half-covered image: the target is reached, and one leaf fewer would not reach it.
    _, half, (half_discs, _) = dead_leaves((48, 64), coverage_target=0.5, **kwargs)
    assert (half >= 0).mean() >= 0.5
    _, before, _ = dead_leaves((48, 64), n_leaves=len(half_discs) - 1, **kwargs)
    assert (before >= 0).mean() < 0.5
    # More leaves than needed for full coverage: still exactly n_leaves in the geometry, same image.
    _, more_labels, (more_discs, _) = dead_leaves((48, 64), n_leaves=used + 5000, **kwargs)
    assert len(more_discs) == used + 5000
    np.testing.assert_array_equal(more_labels, labels)
    np.testing.assert_array_equal(more_discs[:used], discs)


def test_dead_leaves_cap_warns_when_target_not_reached():
    with pytest.warns(RuntimeWarning, match="target"):
        _, labels = dead_leaves((64, 64), n_leaves=10, coverage_target=1.0, r_min=1.0, r_max=4.0, rng=0,
                                return_labels=True)
    assert labels.max() == 9


def test_dead_leaves_seeded():
    first = dead_leaves((256, 256), coverage_target=1.0, r_min=1.0, r_max=32.0, rng=42)
    second = dead_leaves((256, 256), coverage_target=1.0, r_min=1.0, r_max=32.0, rng=42)
    np.testing.assert_array_equal(first, second)
    assert not np.array_equal(first, dead_leaves((256, 256), coverage_target=1.0, r_min=1.0, r_max=32.0, rng=43))
    assert first.dtype == np.float64 and first.min() >= 0 and first.max() <= 1


@pytest.mark.parametrize("kwargs", [
    dict(shape=(0, 10)), dict(shape=(10,)), dict(shape=(10.5, 10)), dict(shape=(True, 10)), dict(shape="ab"),
    dict(r_min=5.0, r_max=5.0), dict(r_min=6.0), dict(r_min=-1.0), dict(alpha=0.0), dict(alpha=-2.0),
    dict(alpha=float("nan")), dict(n_leaves=-1), dict(n_leaves=2.5), dict(n_leaves=None, coverage_target=None),
    dict(coverage_target=0.0), dict(coverage_target=1.5), dict(palette=[[0.1, 0.2]]), dict(palette=[[0, 0, 2]]),
    dict(palette=np.empty((0, 3))), dict(background=(1, 1)),
])
def test_dead_leaves_rejects_bad_input(kwargs):
    arguments = dict(shape=(10, 10), n_leaves=10, r_min=1.0, r_max=5.0) | kwargs
    with pytest.raises(ValueError):
        dead_leaves(arguments.pop("shape"), **arguments)


def test_coverage_helpers_reject_bad_input():
    with pytest.raises(ValueError):
        dead_leaves_coverage(-1, 1.0, 1.0)
    with pytest.raises(ValueError):
        dead_leaves_coverage(1, 0.0, 1.0)
    with pytest.raises(ValueError):
        dead_leaves_window_area((10, 10), -1.0)
    with pytest.raises(ValueError):
        dead_leaves_mean_area(2.0, 1.0)
    assert dead_leaves_coverage(0, 1.0, 1.0) == 0.0


# ---------------------------------------------------------------------------------------------
# random tessellations
# ---------------------------------------------------------------------------------------------


def test_voronoi_labels_are_nearest_centres():
    image, labels, (centres, colour_index) = voronoi_tessellation((30, 45), 40, palette=PALETTE, rng=2,
                                                                  return_labels=True, return_geometry=True)
    ys, xs = np.mgrid[0:30, 0:45] + 0.5
    distances = (xs[..., None] - centres[:, 0]) ** 2 + (ys[..., None] - centres[:, 1]) ** 2
    np.testing.assert_array_equal(labels, distances.argmin(axis=-1))
    assert len(np.unique(labels)) <= 40
    assert np.all((centres >= 0) & (centres <= [45, 30]))
    np.testing.assert_array_equal(image, PALETTE[colour_index[labels]])


def test_voronoi_seeded_and_validated():
    np.testing.assert_array_equal(voronoi_tessellation((20, 20), 5, rng=1), voronoi_tessellation((20, 20), 5, rng=1))
    assert np.all(voronoi_tessellation((8, 8), 1, rng=0) == voronoi_tessellation((8, 8), 1, rng=0)[0, 0])
    for bad in (0, -3, 2.5):
        with pytest.raises(ValueError):
            voronoi_tessellation((20, 20), bad)
    with pytest.raises(ValueError):
        voronoi_tessellation((20, -1), 3)


def test_poisson_lines_count_follows_cauchy_crofton():
    height, width, intensity = 16, 24, 0.3
    counts = [len(poisson_line_tessellation((height, width), intensity, rng=seed, return_geometry=True)[1][0])
              for seed in range(400)]
    expected = 400 * intensity * 2 * (height + width) / math.pi  # Poisson total, variance = mean
    assert abs(sum(counts) - expected) < 4 * math.sqrt(expected)
    # Power: counting the lines hitting the circumscribed disc instead would fail this test.
    circumscribed = 400 * intensity * math.hypot(height, width)
    assert abs(circumscribed - expected) > 4 * math.sqrt(expected)


def test_poisson_lines_are_isotropic_and_hit_the_window():
    lines = np.vstack([poisson_line_tessellation((20, 20), 0.4, rng=seed, return_geometry=True)[1][0]
                       for seed in range(60)])
    np.testing.assert_allclose(np.hypot(lines[:, 0], lines[:, 1]), 1.0)
    orientation = np.mod(np.arctan2(lines[:, 1], lines[:, 0]), math.pi)
    assert stats.kstest(orientation, stats.uniform(0, math.pi).cdf).pvalue > 1e-3
    window = box(0, 0, 20, 20)
    for a, b, p in lines[:50]:
        point = np.array([a, b]) * p
        direction = np.array([-b, a]) * 100.0
        assert LineString([point - direction, point + direction]).intersects(window)


def _shapely_cells(height, width, lines):
    """Cells of the line arrangement in the window, by successive shapely splits (independent oracle)."""
    cells = [box(0, 0, width, height)]
    for a, b, p in lines:
        point = np.array([a, b]) * p
        direction = np.array([-b, a]) * 10.0 * (height + width)
        cutter = LineString([point - direction, point + direction])
        cells = [piece for cell in cells for piece in split(cell, cutter).geoms]
    return cells


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_poisson_line_cells_match_shapely_split(seed):
    height, width = 48, 64
    _, labels, (lines, colour_index) = poisson_line_tessellation((height, width), 0.06, rng=seed,
                                                                 return_labels=True, return_geometry=True)
    cells = _shapely_cells(height, width, lines)
    ys, xs = np.mgrid[0:height, 0:width] + 0.5
    oracle = np.full((height, width), -1)
    for index, cell in enumerate(cells):
        oracle[shapely.contains_xy(cell, xs, ys)] = index
    assert np.all(oracle >= 0)
    # Same partition of the pixels: a bijection between our labels and the oracle's cells.
    pairs = np.unique(np.column_stack([labels.ravel(), oracle.ravel()]), axis=0)
    assert len(pairs) == len(np.unique(labels)) == len(np.unique(oracle))
    assert len(colour_index) == labels.max() + 1
    # Euler: a window crossed by m lines with I crossings inside has 1 + m + I cells.
    crossings = sum(1 for i in range(len(lines)) for j in range(i)
                    if _crossing_inside(lines[i], lines[j], height, width))
    assert len(cells) == 1 + len(lines) + crossings
    assert len(np.unique(labels)) <= len(cells)


def _crossing_inside(first, second, height, width):
    matrix = np.array([first[:2], second[:2]])
    point = np.linalg.solve(matrix, [first[2], second[2]])
    return 0 < point[0] < width and 0 < point[1] < height


def test_line_cell_labels_known_configurations():
    labels = _line_cell_labels(10, 10, np.array([[1.0, 0.0, 5.0], [0.0, 1.0, 5.0]]))
    assert len(np.unique(labels)) == 4
    assert np.all(np.bincount(labels.ravel()) == 25)
    # More than 64 lines: the sign vectors span two words.
    vertical = np.array([[1.0, 0.0, k + 0.7] for k in range(70)])
    labels = _line_cell_labels(3, 80, vertical)
    assert len(np.unique(labels)) == 71
    assert np.all(labels == labels[0]) and len(np.unique(labels[0, :71])) == 71
    assert len(np.unique(_line_cell_labels(5, 5, np.empty((0, 3))))) == 1


def test_poisson_line_tessellation_seeded_and_validated():
    first = poisson_line_tessellation((32, 32), 0.1, rng=9)
    np.testing.assert_array_equal(first, poisson_line_tessellation((32, 32), 0.1, rng=9))
    assert np.all(poisson_line_tessellation((8, 8), 0.0, rng=0) == poisson_line_tessellation((8, 8), 0.0, rng=0)[0, 0])
    for bad in (-0.1, float("inf"), "x"):
        with pytest.raises(ValueError):
            poisson_line_tessellation((32, 32), bad)


# ---------------------------------------------------------------------------------------------
# IFS fractals
# ---------------------------------------------------------------------------------------------


def test_sierpinski_box_counting_dimension():
    target = math.log(3) / math.log(2)
    # Right-angled gasket in the frame (0, 0, 1): its level-j copies are dyadic boxes, N = 3^j exactly
    # (seed study, 20 seeds, 200,000 points, levels 2..7 and 2..8: error below 1e-15).
    points, _ = ifs_chaos_game(sierpinski_triangle(right_angled=True), n_points=200_000, rng=0)
    assert box_counting_dimension(points, frame=(0.0, 0.0, 1.0)) == pytest.approx(target, abs=1e-9)
    # Equilateral triangle, not aligned with the grid: seed study (20 seeds) mean 1.6165, std 0.0005 in
    # its bounding box; the bias comes from the few levels. Tolerance 0.05.
    points, _ = ifs_chaos_game(sierpinski_triangle(), n_points=200_000, rng=0)
    assert box_counting_dimension(points) == pytest.approx(target, abs=0.05)


def test_box_counting_on_known_sets():
    t = np.linspace(0, 1, 20_000)
    assert box_counting_dimension(np.column_stack([t, 0.3 * t])) == pytest.approx(1.0, abs=0.02)
    grid = np.stack(np.meshgrid(np.linspace(0, 1, 400), np.linspace(0, 1, 400)), axis=-1).reshape(-1, 2)
    assert box_counting_dimension(grid) == pytest.approx(2.0, abs=0.02)
    with pytest.raises(ValueError):
        box_counting_dimension(np.zeros((5, 2)))
    with pytest.raises(ValueError):
        box_counting_dimension(grid, levels=(5, 3))
    with pytest.raises(ValueError):
        box_counting_dimension(grid, frame=(0.5, 0.0, 1.0))  # points outside the frame
    with pytest.raises(ValueError):
        box_counting_dimension(grid, frame=(0.0, 0.0, 0.0))


def test_chaos_game_points_stay_on_the_attractor():
    points, map_index = ifs_chaos_game(sierpinski_triangle(), n_points=50_000, rng=1)
    height = math.sqrt(3) / 2
    eps = 1e-12
    assert np.all((points[:, 0] >= -eps) & (points[:, 0] <= 1 + eps))
    assert np.all((points[:, 1] >= -eps) & (points[:, 1] <= height + eps))
    # Inside the triangle, and in the sub-triangle of the map that produced it.
    assert np.all(points[:, 1] <= math.sqrt(3) * np.minimum(points[:, 0], 1 - points[:, 0]) + 1e-9)
    vertices = np.array([[0.0, 0.0], [1.0, 0.0], [0.5, height]])
    assert np.all(np.hypot(*(points - vertices[map_index]).T) <= 0.5 + 1e-9)
    assert np.bincount(map_index).min() > 15_000
    fern, _ = ifs_chaos_game(n_points=50_000, rng=1)
    assert np.all((fern[:, 0] > -2.19) & (fern[:, 0] < 2.66) & (fern[:, 1] >= 0) & (fern[:, 1] < 10.0))


def test_chaos_game_kernel_matches_python_loop():
    linear, offsets, _ = barnsley_fern()
    choices = np.random.default_rng(0).integers(4, size=200)
    start = np.array([0.3, 0.7])
    expected, x = [], start.copy()
    for i in choices:
        x = linear[i] @ x + offsets[i]
        expected.append(x)
    np.testing.assert_allclose(_chaos_game(linear, offsets, choices, start), expected, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("mode", ["binary", "density"])
def test_ifs_fractal_image(mode):
    image, labels, (pixels, map_index) = ifs_fractal((64, 48), sierpinski_triangle(), n_points=20_000, mode=mode,
                                                     margin=3.0, palette=PALETTE, rng=4, return_labels=True,
                                                     return_geometry=True)
    assert image.shape == (64, 48, 3) and image.min() >= 0 and image.max() <= 1
    assert np.all((pixels >= 3.0 - 1e-9) & (pixels <= np.array([48, 64]) - 3.0 + 1e-9))
    hit = labels >= 0
    assert set(np.unique(labels[hit])) == {0, 1, 2}
    np.testing.assert_array_equal(image[~hit], np.ones((int((~hit).sum()), 3)))
    if mode == "binary":
        np.testing.assert_array_equal(image[hit], PALETTE[labels[hit]])
    # The apex (vertex 2, map 2) is drawn at the top of the image: y up in the IFS, y down in pixels.
    top_rows = labels[: labels.shape[0] // 4]
    assert np.all(top_rows[top_rows >= 0] == 2)
    np.testing.assert_array_equal(image, ifs_fractal((64, 48), sierpinski_triangle(), n_points=20_000, mode=mode,
                                                     margin=3.0, palette=PALETTE, rng=4))


def test_ifs_default_is_the_fern_and_colours_cycle_through_a_short_palette():
    _, labels = ifs_fractal((40, 40), n_points=5000, palette=PALETTE[:2], rng=0, return_labels=True)
    assert labels.max() == 3
    image = ifs_fractal((40, 40), n_points=5000, palette=PALETTE[:2], rng=0)
    hit = labels >= 0
    np.testing.assert_array_equal(image[hit], PALETTE[labels[hit] % 2])
    assert DEFAULT_PALETTE.shape[1] == 3


@pytest.mark.parametrize("maps", [
    (np.array([[[1.0, 0.0], [0.0, 0.5]]]), np.zeros((1, 2)), np.ones(1)),  # not a strict contraction
    (np.array([[[0.6, 0.6], [0.6, 0.6]]]), np.zeros((1, 2)), np.ones(1)),  # entries < 1, norm 1.2
    (0.5 * np.stack([np.eye(2)] * 2), np.zeros((2, 2)), np.array([0.5, 0.4])),  # sum != 1
    (0.5 * np.stack([np.eye(2)] * 2), np.zeros((2, 2)), np.array([1.5, -0.5])),  # negative
    (0.5 * np.stack([np.eye(2)] * 2), np.zeros((3, 2)), np.array([0.5, 0.5])),  # shapes
    (0.5 * np.eye(2), np.zeros(2), np.ones(1)),
    (np.full((1, 2, 2), np.nan), np.zeros((1, 2)), np.ones(1)),
    "fern",
])
def test_ifs_rejects_bad_maps(maps):
    with pytest.raises(ValueError):
        ifs_chaos_game(maps, n_points=10)
    with pytest.raises(ValueError):
        ifs_fractal((10, 10), maps, n_points=10)


@pytest.mark.parametrize("kwargs", [dict(n_points=0), dict(mode="log"), dict(margin=-1.0), dict(margin=5.0),
                                    dict(shape=(10, 0)), dict(palette=[[2.0, 0, 0]])])
def test_ifs_fractal_rejects_bad_options(kwargs):
    arguments = dict(shape=(10, 10), n_points=100) | kwargs
    with pytest.raises(ValueError):
        ifs_fractal(arguments.pop("shape"), **arguments)
