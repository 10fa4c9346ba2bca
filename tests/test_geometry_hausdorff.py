"""paperlib.geometry.hausdorff: between point sets and between filled convex polygons."""

import numpy as np
import pytest
import shapely
from scipy.spatial.distance import cdist
from scipy.spatial.distance import directed_hausdorff as scipy_directed_hausdorff

from paperlib.geometry.hausdorff import directed_hausdorff, directed_hausdorff_boxes, hausdorff, hausdorff_boxes

SQUARE = np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)], dtype=float)  # counter-clockwise


def box(center, half_sizes, angle) -> np.ndarray:
    """Corners ``(4, 2)`` of an oriented box, counter-clockwise."""
    c, s = np.cos(angle), np.sin(angle)
    return np.asarray(center) + (SQUARE * half_sizes) @ np.array([[c, s], [-s, c]])


def random_boxes(rng, count) -> np.ndarray:
    return np.stack(
        [
            box(rng.uniform(-3, 3, 2), rng.uniform(0.1, 2, 2) * [1, rng.choice([0, 1])], rng.uniform(0, np.pi))
            for _ in range(count)
        ]
    )


def sample_region(corners, spacing) -> np.ndarray:
    """Brute force: a grid of the filled polygon's interior plus its densified boundary."""
    polygon = shapely.convex_hull(shapely.multipoints(corners))
    (xmin, ymin), (xmax, ymax) = corners.min(axis=0), corners.max(axis=0)
    x, y = np.meshgrid(np.arange(xmin, xmax + spacing, spacing), np.arange(ymin, ymax + spacing, spacing))
    grid = np.column_stack([x.ravel(), y.ravel()])
    inside = grid[shapely.contains_xy(polygon, grid[:, 0], grid[:, 1])]
    boundary = shapely.get_coordinates(shapely.segmentize(polygon.boundary, spacing))
    return np.vstack([inside, boundary])


def brute_force_directed(corners_a, corners_b, spacing=0.05) -> float:
    region_b = shapely.convex_hull(shapely.multipoints(corners_b))
    return float(shapely.distance(shapely.points(sample_region(corners_a, spacing)), region_b).max())


# --------------------------------------------------------------------------- point sets


def test_point_sets_known_answers():
    grid = np.stack(np.meshgrid(np.arange(5.0), np.arange(4.0)), axis=-1).reshape(-1, 2)
    # Shifted by less than half the spacing, each point's nearest neighbour is its copy.
    assert hausdorff(grid, grid + [0.3, 0.4]) == pytest.approx(0.5)
    assert hausdorff(SQUARE, 2 * SQUARE) == pytest.approx(np.sqrt(2))  # corners of nested squares
    assert hausdorff(grid, grid[::-1]) == 0.0
    assert directed_hausdorff(grid[:3], grid) == 0.0  # a subset strays nowhere
    assert directed_hausdorff(grid, grid[:1]) == pytest.approx(5.0)  # (4, 3) from (0, 0)
    assert directed_hausdorff([(0, 0)], [(3, 4), (30, 40)]) == 5.0


def test_point_sets_agree_with_scipy_and_brute_force():
    rng = np.random.default_rng(3)
    a, b = rng.normal(size=(300, 2)), rng.normal(loc=0.5, size=(200, 2))
    brute = cdist(a, b).min(axis=1).max()
    assert directed_hausdorff(a, b) == pytest.approx(brute, rel=1e-12)
    assert directed_hausdorff(a, b) == pytest.approx(scipy_directed_hausdorff(a, b)[0], rel=1e-12)
    assert hausdorff(a, b) == hausdorff(b, a) == pytest.approx(max(brute, cdist(b, a).min(axis=1).max()), rel=1e-12)


@pytest.mark.parametrize("bad", [np.zeros((0, 2)), np.zeros((3, 3)), [(0, 0), (np.nan, 1)], [(0, 0), (np.inf, 1)]])
def test_point_sets_bad_input(bad):
    with pytest.raises(ValueError, match=r"\b(a|b)\b"):
        hausdorff(bad, SQUARE)
    with pytest.raises(ValueError, match=r"\bb\b"):
        directed_hausdorff(SQUARE, bad)


# --------------------------------------------------------------------------- convex polygons


def test_boxes_known_answers():
    assert hausdorff_boxes(SQUARE, SQUARE) == 0.0
    # Nested squares: the inner one is inside (0), the outer one's corners stray sqrt(2).
    assert directed_hausdorff_boxes(SQUARE, 2 * SQUARE) == 0.0
    assert directed_hausdorff_boxes(2 * SQUARE, SQUARE) == pytest.approx(np.sqrt(2))
    assert hausdorff_boxes(SQUARE, 2 * SQUARE) == pytest.approx(np.sqrt(2))
    # A box inside another, off centre: the outer corner farthest from it decides.
    inner = 0.25 * SQUARE + [0.5, 0.5]
    assert directed_hausdorff_boxes(inner, SQUARE) == 0.0
    assert hausdorff_boxes(SQUARE, inner) == pytest.approx(np.hypot(1.25, 1.25))  # (-1, -1) to (0.25, 0.25)
    # Regions, not corners: corner to corner a square and its copy turned by 45 degrees are
    # 2 sqrt(2) sin(pi / 8) ~ 1.08 apart, as regions only sqrt(2) - 1.
    diamond = box((0, 0), (1, 1), np.pi / 4)
    assert hausdorff_boxes(SQUARE, diamond) == pytest.approx(np.sqrt(2) - 1)
    assert hausdorff(SQUARE, diamond) == pytest.approx(2 * np.sin(np.pi / 8) * np.sqrt(2))


def test_shifted_convex_regions_are_the_shift_apart():
    # For convex sets H(A, A + s) = |s| (the support functions differ by <s, u>).
    rng = np.random.default_rng(4)
    boxes = random_boxes(rng, 50)
    shifts = rng.normal(scale=2.0, size=(50, 1, 2))
    expected = np.hypot(*shifts[:, 0].T)
    assert hausdorff_boxes(boxes, boxes + shifts) == pytest.approx(expected, rel=1e-12)


def test_degenerate_boxes_are_segments_and_points():
    segment = np.array([(0, 0), (2, 0), (2, 0), (0, 0)], dtype=float)  # a box of zero width
    assert directed_hausdorff_boxes(segment, SQUARE) == pytest.approx(1.0)  # (2, 0) to the edge x = 1
    assert directed_hausdorff_boxes(SQUARE, segment) == pytest.approx(np.sqrt(2))
    point = np.zeros((4, 2)) + [3, 4]
    assert hausdorff_boxes(point, np.zeros((1, 2))) == 5.0
    assert directed_hausdorff_boxes(segment, segment[:2] * 2) == 0.0  # a sub-segment


def test_orientation_and_starting_corner_do_not_matter():
    rng = np.random.default_rng(5)
    a, b = random_boxes(rng, 2)
    expected = hausdorff_boxes(a, b)
    for variant in (a[::-1], np.roll(a, 1, axis=0), np.roll(a[::-1], 3, axis=0)):
        assert hausdorff_boxes(variant, b[::-1]) == pytest.approx(expected, rel=1e-12, abs=1e-15)


def test_boxes_agree_with_brute_force_sampling_of_the_regions():
    # Exact value >= every sampled point's distance (no interior point beats the
    # vertices), and the samples include the vertices, so they reach it.
    rng = np.random.default_rng(6)
    for a, b in zip(random_boxes(rng, 12), random_boxes(rng, 12)):
        for first, second in ((a, b), (b, a)):
            brute = brute_force_directed(first, second)
            assert directed_hausdorff_boxes(first, second) == pytest.approx(brute, rel=1e-9, abs=1e-9)


def test_batches_broadcast_and_equal_pair_by_pair_results():
    rng = np.random.default_rng(7)
    a, b = random_boxes(rng, 40), random_boxes(rng, 40)
    batched = directed_hausdorff_boxes(a, b)
    assert batched.shape == (40,)
    assert np.array_equal(batched, [directed_hausdorff_boxes(x, y) for x, y in zip(a, b)])
    one_to_many = hausdorff_boxes(a[0], b)
    assert np.array_equal(one_to_many, hausdorff_boxes(np.broadcast_to(a[0], b.shape), b))
    grid = hausdorff_boxes(a[:, None], b[None, :10])  # (40, 10): every a against ten b
    assert grid.shape == (40, 10) and grid[3, 7] == hausdorff_boxes(a[3], b[7])
    assert hausdorff_boxes(np.zeros((0, 4, 2)), SQUARE).shape == (0,)


def test_many_pairs_go_through_in_chunks_with_the_same_results():
    rng = np.random.default_rng(8)
    count = 40_000  # more than one chunk
    a, b = random_boxes(rng, 8)[rng.integers(0, 8, count)], random_boxes(rng, 8)[rng.integers(0, 8, count)]
    distances = hausdorff_boxes(a, b)
    for i in (0, 32_767, 32_768, count - 1):
        assert distances[i] == hausdorff_boxes(a[i], b[i])


@pytest.mark.parametrize(
    ("corners", "message"),
    [
        (np.zeros((4, 3)), r"shape \(\.\.\., p, 2\)"),
        (np.zeros((0, 2)), r"p >= 1"),
        ([(0, 0), (1, np.nan), (1, 1)], "NaN or infinite"),
        ([(0, 0), (1, 1), (1, 0), (0, 1)], "not a convex polygon"),  # a bow tie, zero area
        ([(0, 0), (2, 0), (1, 0.2), (2, 2), (0, 2)], "not a convex polygon"),  # a dent
        (np.stack([SQUARE, SQUARE[[0, 2, 1, 3]]]), r"corners_a\[1\] is not a convex polygon"),
        ("abcd", "numeric"),
    ],
)
def test_boxes_bad_input(corners, message):
    with pytest.raises(ValueError, match=message):
        hausdorff_boxes(corners, SQUARE)


def test_boxes_whose_pair_dimensions_do_not_broadcast():
    with pytest.raises(ValueError, match="do not broadcast"):
        hausdorff_boxes(np.stack([SQUARE] * 3), np.stack([SQUARE] * 2))
