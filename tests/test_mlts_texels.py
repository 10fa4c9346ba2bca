"""Texels and affine objects of MLTS (Alvarez et al. 2015, section 3), checked against shapely and formulas."""

import math

import numpy as np
import pytest
from shapely.geometry import Polygon
from shapely.geometry.polygon import orient

from paperlib.mlts.texels import (
    TEXELS,
    _square_box_angle,
    _widths_minus_heights,
    affine_object,
    affine_objects,
    distance_to,
    distances_to,
    object_diameter,
    orientation_angle,
    orientation_angles,
    texel,
    texel_batch,
)

SEEDS = range(40)
UNIT_SQUARE = np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]])


def side_lengths(vertices):
    return np.linalg.norm(np.roll(vertices, -1, axis=0) - vertices, axis=1)


def interior_angles(triangle):
    angles = []
    for i in range(3):
        u, v = triangle[i - 1] - triangle[i], triangle[(i + 1) % 3] - triangle[i]
        angles.append(math.degrees(math.acos(np.dot(u, v) / (np.linalg.norm(u) * np.linalg.norm(v)))))
    return np.array(angles)


# ------------------------------------------------------------------------------------------ texels


def test_texel_kinds_are_the_papers():
    assert TEXELS == ("triangle", "rectangle", "ellipse", "regular_polygon", "convex_polygon", "random_shape")


@pytest.mark.parametrize("kind", TEXELS)
def test_bounding_box_is_exactly_the_centred_unit_square(kind):
    for seed in SEEDS:
        vertices = texel(kind, seed)
        assert vertices.dtype == np.float64 and vertices.ndim == 2 and vertices.shape[1] == 2
        assert vertices.shape[0] >= 3
        np.testing.assert_allclose(vertices.min(axis=0), [-0.5, -0.5], rtol=0, atol=1e-12)
        np.testing.assert_allclose(vertices.max(axis=0), [0.5, 0.5], rtol=0, atol=1e-12)


@pytest.mark.parametrize("kind", TEXELS)
def test_texels_are_valid_counter_clockwise_polygons(kind):
    for seed in SEEDS:
        vertices = texel(kind, seed)
        polygon = Polygon(vertices)
        assert polygon.is_valid and polygon.area > 0.05
        assert len(np.unique(vertices, axis=0)) == len(vertices)  # no repeated (or closing) vertex
        # shapely's orient(sign=1.0) leaves an already counter-clockwise ring untouched
        np.testing.assert_array_equal(np.asarray(orient(polygon, sign=1.0).exterior.coords)[:-1], vertices)


@pytest.mark.parametrize("kind", TEXELS)
def test_same_seed_same_texel_bit_for_bit(kind):
    for seed in (0, 7, 123):
        np.testing.assert_array_equal(texel(kind, seed), texel(kind, np.random.default_rng(seed)))
        np.testing.assert_array_equal(texel(kind, seed), texel(kind, seed))


@pytest.mark.parametrize("kind", ["triangle", "convex_polygon", "random_shape"])
def test_random_kinds_differ_between_seeds(kind):
    shapes = {texel(kind, seed).tobytes() for seed in SEEDS}
    assert len(shapes) == len(SEEDS)


@pytest.mark.parametrize("kind", ["rectangle", "ellipse"])
def test_rectangle_and_ellipse_draw_nothing(kind):
    rng = np.random.default_rng(5)
    first = texel(kind, rng)
    assert rng.random() == np.random.default_rng(5).random()
    np.testing.assert_array_equal(first, texel(kind, 99))
    first[0] = 7.0  # callers may modify their copy without changing the next texel
    assert texel(kind)[0, 0] != 7.0


def test_rectangle_is_the_unit_square():
    np.testing.assert_array_equal(texel("rectangle"), UNIT_SQUARE)


@pytest.mark.parametrize("n_vertices", [None, 5, 7, 12, 64, 100])
def test_ellipse_points_lie_on_a_circle(n_vertices):
    vertices = texel("ellipse", n_vertices=n_vertices)
    assert len(vertices) == (n_vertices or 64)
    radii = np.linalg.norm(vertices - vertices.mean(axis=0), axis=1)
    np.testing.assert_allclose(radii, radii[0], rtol=1e-12)
    if (n_vertices or 64) % 4 == 0:  # the circle is then inscribed in the box itself
        np.testing.assert_allclose(radii, 0.5, rtol=1e-12)
        np.testing.assert_allclose(vertices.mean(axis=0), 0.0, atol=1e-15)


def test_regular_polygons_have_equal_sides_and_angles():
    for n_sides in range(3, 13):
        for seed in range(10):
            vertices = texel("regular_polygon", seed, n_vertices=n_sides)
            assert len(vertices) == n_sides
            sides = side_lengths(vertices)
            np.testing.assert_allclose(sides, sides.mean(), rtol=1e-9)
            radii = np.linalg.norm(vertices - vertices.mean(axis=0), axis=1)
            np.testing.assert_allclose(radii, radii.mean(), rtol=1e-9)


def test_regular_polygon_side_count_is_drawn_in_3_to_8():
    counts = {len(texel("regular_polygon", seed)) for seed in range(200)}
    assert counts == set(range(3, 9))


def placements(n_sides, seeds):
    """Distinct vertex sets (whatever the start vertex) of regular polygons drawn with these seeds."""
    return {tuple(sorted(map(tuple, np.round(texel("regular_polygon", seed, n_vertices=n_sides), 9))))
            for seed in seeds}


def test_regular_polygon_rotation_is_random_among_square_box_rotations():
    # When 4 divides the side count every rotation has a square box: the rotation is continuous.
    for n_sides in (4, 8):
        assert len(placements(n_sides, range(30))) == 30
    # Otherwise only a few rotations (up to symmetry) have a square box, and all of them are drawn.
    for n_sides, expected in ((3, 4), (5, 4), (6, 2), (7, 4)):
        assert len(placements(n_sides, range(60))) == expected


def test_triangles_are_never_thin():
    smallest = []
    for seed in range(300):
        angles = interior_angles(texel("triangle", seed))
        np.testing.assert_allclose(angles.sum(), 180.0, atol=1e-9)
        smallest.append(angles.min())
    assert min(smallest) >= 15.0 - 1e-9
    assert min(smallest) < 20.0 and max(smallest) > 50.0  # the whole admissible range is drawn


def test_convex_polygons_equal_their_hull():
    sizes = set()
    for seed in range(100):
        vertices = texel("convex_polygon", seed)
        polygon = Polygon(vertices)
        assert polygon.equals(polygon.convex_hull)
        assert len(polygon.convex_hull.exterior.coords) - 1 == len(vertices)  # no collinear vertex
        assert 3 <= len(vertices) <= 12
        sizes.add(len(vertices))
    assert len(sizes) >= 4


def test_convex_polygon_points_count():
    hull = texel("convex_polygon", 3, n_vertices=3)
    assert len(hull) == 3


def test_random_shapes_are_simple_and_sometimes_concave():
    concave = 0
    for seed in range(60):
        vertices = texel("random_shape", seed)
        polygon = Polygon(vertices)
        assert polygon.is_valid and polygon.exterior.is_simple
        concave += not polygon.equals(polygon.convex_hull)
        assert len(vertices) == 64
    assert 0 < concave < 60


def test_random_shape_vertex_count():
    assert len(texel("random_shape", 1, n_vertices=200)) == 200
    assert Polygon(texel("random_shape", 1, n_vertices=8)).is_valid


def test_square_box_rotation_is_exact_before_the_final_rescaling():
    rng = np.random.default_rng(0)
    for _ in range(200):
        points = rng.normal(size=(int(rng.integers(3, 40)), 2)) * [1.0, rng.uniform(0.05, 1.0)]
        start = rng.uniform(0, 2 * np.pi)
        angle = _square_box_angle(points, start)
        assert start <= angle <= start + np.pi / 2
        width = np.ptp(points[:, 0] * np.cos(angle) - points[:, 1] * np.sin(angle))
        assert abs(_widths_minus_heights(np.array([angle]), points)[0]) <= 1e-13 * width


@pytest.mark.parametrize(
    ("kind", "n_vertices"),
    [("spiral", None), ("Triangle", None), ("triangle", 4), ("rectangle", 3), ("ellipse", 2),
     ("regular_polygon", 0), ("random_shape", 3.5), ("convex_polygon", True)],
)
def test_bad_texel_requests(kind, n_vertices):
    with pytest.raises(ValueError):
        texel(kind, 0, n_vertices=n_vertices)


def test_fixed_counts_accepted_for_triangle_and_rectangle():
    assert len(texel("triangle", 0, n_vertices=3)) == 3
    assert len(texel("rectangle", 0, n_vertices=4)) == 4


# ------------------------------------------------------------------------------------ affine objects


def test_affine_object_known_answer():
    obj = affine_object(UNIT_SQUARE, (5, 5), 10, 2, np.pi / 2)
    np.testing.assert_allclose(obj, [[7.5, 0], [7.5, 10], [2.5, 10], [2.5, 0]], atol=1e-12)
    flat = affine_object(UNIT_SQUARE, (5, 5), 10, 2, 0.0)
    np.testing.assert_allclose(flat, [[0, 2.5], [10, 2.5], [10, 7.5], [0, 7.5]], atol=1e-12)


def test_angle_turns_the_texel_x_axis_towards_plus_y():
    arrow = np.array([[0.5, 0.0], [-0.5, -0.25], [-0.5, 0.25]])  # tip on the texel's +x axis
    for angle in (0.3, 1.0, -2.0, np.pi):
        tip = affine_object(arrow, (20, 30), 8, 1, angle)[0]
        np.testing.assert_allclose(tip, [20 + 4 * np.cos(angle), 30 + 4 * np.sin(angle)], atol=1e-12)
    # +pi/2 sends the x axis to +y, i.e. downwards on screen (clockwise in the image)
    np.testing.assert_allclose(affine_object(arrow, (0, 0), 2, 1, np.pi / 2)[0], [0, 1], atol=1e-15)


@pytest.mark.parametrize("kind", TEXELS)
def test_area_scales_as_diameter_squared_over_aspect(kind):
    rng = np.random.default_rng(1)
    for seed in range(10):
        vertices = texel(kind, seed)
        diameter, aspect, angle = rng.uniform(1, 200), rng.uniform(1, 8), rng.uniform(-7, 7)
        obj = affine_object(vertices, rng.uniform(-50, 500, size=2), diameter, aspect, angle)
        polygon = Polygon(obj)
        assert polygon.is_valid
        np.testing.assert_allclose(polygon.area, Polygon(vertices).area * diameter**2 / aspect, rtol=1e-10)
        assert orient(polygon, sign=1.0).equals_exact(polygon, 0)  # still counter-clockwise


def test_aspect_one_keeps_proportions_and_diameter_sets_the_extent():
    obj = affine_object(texel("rectangle"), (0, 0), 12, 1, 0.0)
    np.testing.assert_allclose(np.ptp(obj, axis=0), [12, 12])
    obj = affine_object(texel("ellipse"), (0, 0), 12, 3, 0.0)
    np.testing.assert_allclose(np.ptp(obj, axis=0), [12, 4], rtol=1e-12)


def test_affine_objects_matches_affine_object():
    rng = np.random.default_rng(2)
    n = 25
    texels_ = [texel(TEXELS[i % len(TEXELS)], i) for i in range(n)]
    centers = rng.uniform(0, 100, size=(n, 2))
    diameters, aspects, angles = rng.uniform(1, 30, n), rng.uniform(1, 5, n), rng.uniform(-4, 4, n)
    batch = affine_objects(texels_, centers, diameters, aspects, angles)
    assert len(batch) == n
    for i in range(n):
        np.testing.assert_allclose(batch[i], affine_object(texels_[i], centers[i], diameters[i], aspects[i],
                                                           angles[i]), rtol=1e-13, atol=1e-12)
    shared = affine_objects(UNIT_SQUARE, centers, diameters, aspects, angles)
    for i in range(n):
        np.testing.assert_allclose(shared[i], affine_object(UNIT_SQUARE, centers[i], diameters[i], aspects[i],
                                                            angles[i]), rtol=1e-13, atol=1e-12)
    assert affine_objects([], np.empty((0, 2)), [], [], []) == []


@pytest.mark.parametrize(
    ("center", "diameter", "aspect", "angle"),
    [((0, 0), 10, 0.5, 0), ((0, 0), 0, 1, 0), ((0, 0), -3, 1, 0), ((0, 0), np.nan, 1, 0),
     ((0, 0), 10, np.nan, 0), ((0, 0), 10, 1, np.nan), ((0, 0), 10, 1, np.inf), ((np.nan, 0), 10, 1, 0),
     ((0, 0, 0), 10, 1, 0), ((0, 0), "big", 1, 0), ((0, 0), 10, np.inf, 0)],
)
def test_affine_object_bad_parameters(center, diameter, aspect, angle):
    with pytest.raises(ValueError):
        affine_object(UNIT_SQUARE, center, diameter, aspect, angle)


@pytest.mark.parametrize("vertices", [np.zeros((2, 2)), np.zeros((4, 3)), [[0, 0], [1, 0], [np.nan, 1]], "abc"])
def test_affine_object_bad_vertices(vertices):
    with pytest.raises(ValueError):
        affine_object(vertices, (0, 0), 1, 1, 0)


def test_affine_objects_bad_input():
    centers = np.zeros((2, 2))
    with pytest.raises(ValueError, match="2 centers"):
        affine_objects([UNIT_SQUARE], centers, [1, 1], [1, 1], [0, 0])
    with pytest.raises(ValueError, match="diameters"):
        affine_objects(UNIT_SQUARE, centers, [1, 0], [1, 1], [0, 0])
    with pytest.raises(ValueError, match="aspects"):
        affine_objects(UNIT_SQUARE, centers, [1, 1], [1, 0.9], [0, 0])
    with pytest.raises(ValueError, match="angles"):
        affine_objects(UNIT_SQUARE, centers, [1, 1], [1, 1], [0])
    with pytest.raises(ValueError, match="angles"):
        affine_objects(UNIT_SQUARE, centers, [1, 1], [1, 1], [0, np.nan])


# ------------------------------------------------------------------------- diameters and orientation


def test_object_diameter():
    assert object_diameter(UNIT_SQUARE) == pytest.approx(math.sqrt(2))
    assert object_diameter(texel("ellipse")) == pytest.approx(1.0)
    rectangle = affine_object(texel("rectangle"), (3, 4), 20, 4, 0.7)
    assert object_diameter(rectangle) == pytest.approx(20 * math.sqrt(1 + 1 / 16))
    points = np.random.default_rng(3).normal(size=(30, 2))
    brute = max(np.linalg.norm(p - q) for p in points for q in points)
    assert object_diameter(points) == pytest.approx(brute)
    with pytest.raises(ValueError):
        object_diameter([[0, 0], [1, 1]])


@pytest.mark.parametrize("center", [(0, 0), (100.5, -3), (1e4, 2e4)])
def test_points_at_infinity_give_parallel_orientations(center):
    assert orientation_angle(center, (1, 0, 0)) in (0.0, math.pi)
    assert orientation_angle(center, (-1, 0, 0)) == pytest.approx(math.pi)
    assert orientation_angle(center, (0, 1, 0)) == pytest.approx(math.pi / 2)
    assert orientation_angle(center, (0, 5, 0)) == pytest.approx(math.pi / 2)
    assert orientation_angle(center, (1, 1, 0)) == pytest.approx(math.pi / 4)
    assert distance_to(center, (1, 0, 0)) == math.inf


def test_finite_points():
    assert orientation_angle((0, 0), (3, 4, 1)) == pytest.approx(math.atan2(4, 3))
    # homogeneous coordinates: any nonzero multiple is the same point
    for scale in (2.0, -1.0, 0.25):
        assert orientation_angle((0, 0), (3 * scale, 4 * scale, scale)) == pytest.approx(math.atan2(4, 3))
        assert distance_to((0, 0), (3 * scale, 4 * scale, scale)) == pytest.approx(5.0)
    assert orientation_angle((10, 10), (10, 0, 1)) == pytest.approx(-math.pi / 2)  # straight up on screen
    assert orientation_angle((10, 10), (0, 10, 1)) == pytest.approx(math.pi)
    assert distance_to((10, 10), (10, 10, 1)) == 0.0


def test_objects_point_towards_their_vanishing_point():
    vanishing = np.array([400.0, -150.0, 1.0])
    rng = np.random.default_rng(4)
    for center in rng.uniform(0, 300, size=(20, 2)):
        obj = affine_object(texel("rectangle"), center, 30, 6, orientation_angle(center, vanishing))
        long_axis = obj[1] - obj[0]  # the square's first edge runs along the texel's +x axis
        towards = vanishing[:2] - center
        cosine = np.dot(long_axis, towards) / (np.linalg.norm(long_axis) * np.linalg.norm(towards))
        assert cosine == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize(
    ("center", "point"),
    [((0, 0), (0, 0, 0)), ((3, 4), (3, 4, 1)), ((3, 4), (6, 8, 2)), ((0, 0), (1, 0)), ((0, 0), (np.nan, 0, 1)),
     ((0, 0), (np.inf, 0, 1)), ((np.nan, 0), (1, 0, 0)), ((0,), (1, 0, 0))],
)
def test_orientation_bad_input(center, point):
    with pytest.raises(ValueError):
        orientation_angle(center, point)


@pytest.mark.parametrize(("center", "point"), [((0, 0), (0, 0, 0)), ((0, 0), (1, 0)), ((np.nan, 0), (1, 0, 1))])
def test_distance_bad_input(center, point):
    with pytest.raises(ValueError):
        distance_to(center, point)


def test_vectorised_orientation_and_distance_match_the_scalar_ones():
    centers = np.random.default_rng(6).uniform(-100, 400, size=(50, 2))
    for point in [(1, 0, 0), (0, 1, 0), (-2, 3, 0), (300, 20, 1), (-90, 600, 3), (5, 5, -0.01)]:
        np.testing.assert_allclose(orientation_angles(centers, point),
                                   [orientation_angle(c, point) for c in centers], rtol=0, atol=1e-15)
        np.testing.assert_allclose(distances_to(centers, point), [distance_to(c, point) for c in centers])
    assert orientation_angles(np.empty((0, 2)), (1, 2, 1)).shape == (0,)
    np.testing.assert_array_equal(distances_to([[3, 4], [0, 0]], (0, 0, 1)), [5, 0])


def test_vectorised_orientation_bad_input():
    with pytest.raises(ValueError, match="centre 1"):
        orientation_angles([[0, 0], [3, 4]], (6, 8, 2))
    for call in (orientation_angles, distances_to):
        with pytest.raises(ValueError):
            call([[0, 0]], (0, 0, 0))
        with pytest.raises(ValueError):
            call([0, 0], (1, 0, 0))
        with pytest.raises(ValueError):
            call([[np.nan, 0]], (1, 0, 0))


@pytest.mark.parametrize("kind", TEXELS)
def test_texel_batch_in_one_draw_are_valid_reproducible_and_independent(kind):
    batch = texel_batch(kind, 40, 5)
    assert len(batch) == 40
    for vertices in batch:
        np.testing.assert_array_equal(vertices.min(axis=0), [-0.5, -0.5])
        np.testing.assert_array_equal(vertices.max(axis=0), [0.5, 0.5])
        assert Polygon(vertices).is_valid and orient(Polygon(vertices), sign=1.0).equals_exact(Polygon(vertices), 0)
    np.testing.assert_array_equal(np.concatenate(batch), np.concatenate(texel_batch(kind, 40, 5)))
    distinct = {vertices.tobytes() for vertices in batch}
    if kind in ("rectangle", "ellipse"):
        assert len(distinct) == 1
    elif kind == "regular_polygon":  # 6 side counts, few square-box placements each (texel's Notes)
        assert 10 <= len(distinct) < 40
    else:
        assert len(distinct) == 40
    np.testing.assert_array_equal(texel(kind, 3), texel_batch(kind, 1, 3)[0])
    assert texel_batch(kind, 0, 1) == []


@pytest.mark.parametrize("count", [-1, 2.5, True])
def test_texel_batch_rejects_bad_counts(count):
    with pytest.raises(ValueError, match="count"):
        texel_batch("triangle", count, 0)
