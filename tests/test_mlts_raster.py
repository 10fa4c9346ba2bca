"""Tests of the anti-aliased MLTS painter (Alvarez et al. 2015, section 5)."""

import time

import numpy as np
import pytest
import shapely

from paperlib.mlts.raster import coverage, paint, render_polygons


def full_mask(vertices, shape, samples=4, clip=None):
    """The coverage of ``vertices`` placed into a full (H, W) image."""
    row0, col0, mask = coverage(vertices, shape, samples=samples, clip=clip)
    out = np.zeros(shape)
    out[row0:row0 + mask.shape[0], col0:col0 + mask.shape[1]] = mask
    return out


def rectangle(x0, y0, x1, y1):
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float)


def random_convex(rng, centre_range=(-5, 45), radius_range=(3, 15), points=7):
    """Convex hull of random points around a random centre (a triangle when points == 3)."""
    centre = rng.uniform(*centre_range, 2)
    pts = centre + rng.uniform(-1, 1, (points, 2)) * rng.uniform(*radius_range)
    hull = shapely.convex_hull(shapely.MultiPoint(pts))
    return np.asarray(shapely.get_coordinates(hull))[:-1]


def random_star(rng, centre=(20, 20), points=11):
    """A simple, generally non-convex polygon: random radii at sorted random angles."""
    angles = np.sort(rng.uniform(0, 2 * np.pi, points))
    radii = rng.uniform(3, 18, points)
    return np.asarray(centre) + np.c_[radii * np.cos(angles), radii * np.sin(angles)]


def sample_count_oracle(vertices, shape, samples, clip=None):
    """Fraction of each pixel's sample points that shapely says are inside (and inside clip)."""
    height, width = shape
    offsets = (np.arange(samples) + 0.5) / samples
    xs = (np.arange(width)[:, None] + offsets[None, :]).ravel()
    ys = (np.arange(height)[:, None] + offsets[None, :]).ravel()
    gx, gy = np.meshgrid(xs, ys)
    inside = shapely.contains_xy(shapely.Polygon(vertices), gx, gy)
    if clip is not None:
        inside &= shapely.contains_xy(shapely.Polygon(clip), gx, gy)
    return inside.reshape(height, samples, width, samples).mean(axis=(1, 3))


def pixel_area_oracle(vertices, shape):
    """Exact area of the polygon inside each pixel square (shapely)."""
    height, width = shape
    rows, cols = np.mgrid[0:height, 0:width]
    boxes = shapely.box(cols.ravel(), rows.ravel(), cols.ravel() + 1, rows.ravel() + 1)
    return shapely.area(shapely.intersection(boxes, shapely.Polygon(vertices))).reshape(shape)


# (1) known answers -------------------------------------------------------------------------------


@pytest.mark.parametrize("samples", [1, 2, 3, 4, 5, 8])
def test_integer_rectangle_is_exactly_one_inside_zero_outside(samples):
    mask = full_mask(rectangle(3, 2, 9, 7), (10, 12), samples)
    expected = np.zeros((10, 12))
    expected[2:7, 3:9] = 1.0
    np.testing.assert_array_equal(mask, expected)


def test_integer_rectangle_returns_its_bounding_box():
    row0, col0, mask = coverage(rectangle(3, 2, 9, 7), (10, 12))
    assert (row0, col0, mask.shape, mask.dtype) == (2, 3, (5, 6), np.float64)


@pytest.mark.parametrize("samples", [2, 4, 6, 8])
def test_half_pixel_edges_give_exactly_one_half(samples):
    mask = full_mask(rectangle(2.5, 1.5, 6.5, 5.5), (8, 9), samples)
    expected = np.zeros((8, 9))
    expected[1:6, 2:7] = 0.5  # edge pixels
    expected[2:5, 3:6] = 1.0  # interior
    expected[[1, 1, 5, 5], [2, 6, 2, 6]] = 0.25  # corners: half of a half
    np.testing.assert_array_equal(mask, expected)


def test_edges_on_sample_lines_partition_the_samples():
    # Edges through sample points: the half-open rule counts each sample in exactly one of two
    # polygons sharing an edge, so adjacent objects neither overlap nor leave gaps.
    top = rectangle(0.125, 0.125, 5.375, 2.375)
    bottom = rectangle(0.125, 2.375, 5.375, 4.875)
    union = rectangle(0.125, 0.125, 5.375, 4.875)
    shape = (6, 6)
    np.testing.assert_array_equal(full_mask(top, shape) + full_mask(bottom, shape), full_mask(union, shape))
    np.testing.assert_array_equal(full_mask(union, shape), sample_count_oracle(rectangle(0, 0, 5.25, 4.75), shape, 4))


def test_polygon_outside_image_is_empty_and_huge_polygon_covers_everything():
    assert coverage(rectangle(20, 20, 30, 30), (10, 10))[2].shape == (0, 0)
    assert coverage(rectangle(-30, 2, -1, 5), (10, 10))[2].shape == (0, 0)
    row0, col0, mask = coverage(rectangle(-1e200, -1e200, 1e200, 1e200), (7, 5))
    assert (row0, col0) == (0, 0)
    np.testing.assert_array_equal(mask, np.ones((7, 5)))


def test_orientation_does_not_matter():
    rng = np.random.default_rng(4)
    star = random_star(rng)
    np.testing.assert_array_equal(full_mask(star, (40, 40)), full_mask(star[::-1], (40, 40)))


# (2) oracles ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("points", [3, 7])
@pytest.mark.parametrize("samples", [4, 8])
def test_coverage_matches_exact_pixel_areas_within_sampling_error(points, samples):
    # Per sub-row of a pixel the sample count misses the exact strip area by less than one sample
    # per edge crossing; a convex polygon crosses each line at most twice, so per pixel
    # |coverage - exact area| <= 2 / samples. The errors have both signs, so totals agree to 1 %.
    rng = np.random.default_rng(100 + points + samples)
    shape = (40, 40)
    image = shapely.box(0, 0, shape[1], shape[0])
    for _ in range(8):
        polygon = random_convex(rng, points=points)
        exact = pixel_area_oracle(polygon, shape)
        mask = full_mask(polygon, shape, samples)
        assert np.max(np.abs(mask - exact)) <= 2.0 / samples
        area = shapely.intersection(shapely.Polygon(polygon), image).area
        if area > 20:
            assert abs(mask.sum() - area) <= 0.01 * area


def test_coverage_counts_exactly_the_samples_shapely_finds_inside():
    rng = np.random.default_rng(7)
    for samples in (1, 3, 4):
        for _ in range(5):
            star = random_star(rng)
            np.testing.assert_array_equal(full_mask(star, (40, 40), samples),
                                          sample_count_oracle(star, (40, 40), samples))


# (3) compositing ------------------------------------------------------------------------------------


def test_opaque_black_square_on_white():
    square = rectangle(2.3, 3.6, 11.2, 9.9)
    canvas = render_polygons([square], [[0, 0, 0]], (14, 15))
    mask = full_mask(square, (14, 15))
    for ch in range(3):
        np.testing.assert_allclose(canvas[..., ch], 1.0 - mask, atol=1e-15)
    np.testing.assert_array_equal(canvas[5:9, 4:10], 0.0)
    np.testing.assert_array_equal(canvas[:3], 1.0)


def test_half_transparent_red_over_blue_is_purple():
    square = rectangle(1, 1, 8, 8)
    canvas = render_polygons([square, square], [[0, 0, 1], [1, 0, 0]], (10, 10), background=(0, 1, 0),
                             alphas=[0.0, 0.5])
    np.testing.assert_allclose(canvas[1:8, 1:8], np.broadcast_to([0.5, 0.0, 0.5], (7, 7, 3)), atol=1e-15)
    np.testing.assert_array_equal(canvas[0], np.broadcast_to([0.0, 1.0, 0.0], (10, 3)))


def test_fully_transparent_object_leaves_canvas_unchanged():
    canvas = render_polygons([rectangle(1, 1, 8, 8)], [[0, 0, 0]], (10, 10), alphas=1.0)
    np.testing.assert_array_equal(canvas, 1.0)


def test_paint_matches_a_numpy_reference_compositor():
    rng = np.random.default_rng(11)
    shape = (30, 35)
    polygons = [random_convex(rng, centre_range=(0, 30)) for _ in range(6)] + [random_star(rng, (15, 15))]
    n = len(polygons)
    colors = rng.uniform(0, 1, (n, 3))
    alphas = rng.uniform(0, 1, n)
    lights = np.array([p.mean(axis=0) for p in polygons])
    heights = rng.uniform(2, 10, n)
    canvas = render_polygons(polygons, colors, shape, background=(0.2, 0.3, 0.4), alphas=alphas, lights=lights,
                             light_height=heights, samples=3)
    reference = np.empty(shape + (3,))
    reference[:] = (0.2, 0.3, 0.4)
    rows, cols = np.mgrid[0:shape[0], 0:shape[1]]
    for i in range(n):
        a = full_mask(polygons[i], shape, 3)[..., None] * (1 - alphas[i])
        d2 = (cols + 0.5 - lights[i, 0]) ** 2 + (rows + 0.5 - lights[i, 1]) ** 2
        colour = colors[i] * (heights[i] ** 2 / (heights[i] ** 2 + d2))[..., None]
        reference = reference * (1 - a) + colour * a
    np.testing.assert_allclose(canvas, reference, rtol=0, atol=1e-12)


# (4) order = occlusion -------------------------------------------------------------------------------


def test_later_polygons_are_in_front():
    back = rectangle(0, 0, 6, 6)
    front = rectangle(3, 3, 9, 9)
    red, green = [1.0, 0, 0], [0, 1.0, 0]
    canvas = render_polygons([back, front], [red, green], (10, 10))
    np.testing.assert_array_equal(canvas[4, 4], green)  # overlap: the later one
    np.testing.assert_array_equal(canvas[1, 1], red)
    swapped = render_polygons([front, back], [green, red], (10, 10))
    np.testing.assert_array_equal(swapped[4, 4], red)
    np.testing.assert_array_equal(swapped[8, 8], green)


# (5) light spot -------------------------------------------------------------------------------------------


def test_light_spot_is_the_colour_at_the_light_and_half_at_distance_h():
    colour = np.array([0.8, 0.6, 0.4])
    h = 8.0
    canvas = render_polygons([rectangle(0, 0, 40, 30)], [colour], (30, 40), lights=[[10.5, 12.5]], light_height=h)
    np.testing.assert_allclose(canvas[12, 10], colour, rtol=1e-15)  # pixel centre = light point
    np.testing.assert_allclose(canvas[12, 18], colour / 2, rtol=1e-15)  # |p - light| = h
    np.testing.assert_allclose(canvas[12 + 8, 10], colour / 2, rtol=1e-15)
    # intensity falls off monotonically away from the light
    assert np.all(np.diff(canvas[12, 10:, 0]) < 0) and np.all(np.diff(canvas[12, :11, 0]) > 0)


def test_per_object_light_heights():
    squares = [rectangle(0, 0, 10, 10), rectangle(10, 0, 20, 10)]
    canvas = render_polygons(squares, [[1, 1, 1], [1, 1, 1]], (10, 20), background=(0, 0, 0),
                             lights=[[0.5, 0.5], [10.5, 0.5]], light_height=[2.0, 4.0])
    np.testing.assert_allclose(canvas[0, 2, 0], 0.5)  # distance 2 = h of the first
    np.testing.assert_allclose(canvas[0, 14, 0], 0.5)  # distance 4 = h of the second


# (6) clip ("keep father inclusion") ----------------------------------------------------------------------


def test_clip_draws_the_object_only_inside_its_father():
    child = rectangle(0, 0, 20, 20)
    father = rectangle(10, 10, 30, 30)
    canvas = render_polygons([child], [[0, 0, 0]], (32, 32), clip=[father])
    expected = np.ones((32, 32))
    expected[10:20, 10:20] = 0.0
    for ch in range(3):
        np.testing.assert_array_equal(canvas[..., ch], expected)


def test_clip_counts_samples_inside_both_polygons():
    rng = np.random.default_rng(21)
    shape = (40, 40)
    for _ in range(5):
        child, father = random_star(rng), random_star(rng)
        mask = full_mask(child, shape, 4, clip=father)
        np.testing.assert_array_equal(mask, sample_count_oracle(child, shape, 4, clip=father))
        canvas = render_polygons([child], [[0, 0, 0]], shape, clip=[father])
        np.testing.assert_allclose(canvas[..., 0], 1.0 - mask, atol=1e-15)


def test_clip_entries_may_be_none():
    squares = [rectangle(0, 0, 4, 4), rectangle(5, 0, 9, 4)]
    canvas = render_polygons(squares, [[0, 0, 0]] * 2, (5, 10), clip=[None, rectangle(5, 0, 7, 4)])
    np.testing.assert_array_equal(canvas[0:4, 0:4, 0], 0.0)
    np.testing.assert_array_equal(canvas[0:4, 5:7, 0], 0.0)
    np.testing.assert_array_equal(canvas[0:4, 7:9, 0], 1.0)


def test_disjoint_clip_draws_nothing():
    canvas = render_polygons([rectangle(0, 0, 4, 4)], [[0, 0, 0]], (10, 10), clip=[rectangle(6, 6, 9, 9)])
    np.testing.assert_array_equal(canvas, 1.0)


# (7) bad input -----------------------------------------------------------------------------------------------

SQUARE = rectangle(1, 1, 4, 4)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"vertices": [[0, 0], [1, 1]]}, "k >= 3"),
        ({"vertices": [[0, 0], [1, np.nan], [2, 0]]}, "NaN"),
        ({"vertices": [[0, 0, 0], [1, 1, 1], [2, 0, 1]]}, r"\(k, 2\)"),
        ({"vertices": "abc"}, "vertices"),
        ({"shape": (0, 5)}, "shape"),
        ({"shape": (5,)}, "shape"),
        ({"shape": (5.5, 5)}, "shape"),
        ({"samples": 0}, "samples"),
        ({"samples": 2.0}, "samples"),
        ({"samples": True}, "samples"),
        ({"samples": 1000}, "samples"),
        ({"clip": [[0, 0], [1, 1]]}, "clip"),
    ],
)
def test_coverage_rejects_bad_input(kwargs, message):
    args = {"vertices": SQUARE, "shape": (5, 5)} | kwargs
    with pytest.raises(ValueError, match=message):
        coverage(args.pop("vertices"), args.pop("shape"), **args)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"colors": [[0, 0, 0], [1, 1, 1]]}, "colors"),
        ({"colors": [[0, 0, 1.5]]}, "colors"),
        ({"colors": [[0, np.nan, 0]]}, "colors"),
        ({"alphas": [0.5, 0.5]}, "alphas"),
        ({"alphas": -0.1}, "alphas"),
        ({"alphas": [np.inf]}, "alphas"),
        ({"lights": [[2, 2]]}, "together"),
        ({"light_height": 3.0}, "together"),
        ({"lights": [[2, 2]], "light_height": 0.0}, "light_height"),
        ({"lights": [[2, 2]], "light_height": [-1.0]}, "light_height"),
        ({"lights": [[2, 2]], "light_height": [1.0, 2.0]}, "light_height"),
        ({"lights": [[2, np.nan]], "light_height": 1.0}, "lights"),
        ({"lights": [[2, 2, 2]], "light_height": 1.0}, "lights"),
        ({"clip": [None, None]}, "clip"),
        ({"clip": [[[0, 0], [1, 1]]]}, "clip"),
        ({"polygons": [[[0, 0], [1, 1]]]}, "polygons"),
        ({"samples": -1}, "samples"),
        ({"background": (1, 1)}, "background"),
        ({"background": (1, 1, 2)}, "background"),
    ],
)
def test_render_rejects_bad_input(kwargs, message):
    args = {"polygons": [SQUARE], "colors": [[0, 0, 0]]} | kwargs
    with pytest.raises(ValueError, match=message):
        render_polygons(args.pop("polygons"), args.pop("colors"), (6, 6), **args)


@pytest.mark.parametrize(
    "canvas",
    [np.ones((5, 5)), np.ones((5, 5, 4)), np.ones((5, 5, 3), dtype=np.float32), np.full((5, 5, 3), np.nan),
     np.ones((0, 5, 3)), [[[1.0, 1.0, 1.0]]]],
)
def test_paint_rejects_bad_canvas(canvas):
    with pytest.raises(ValueError, match="canvas"):
        paint(canvas, [SQUARE], [[0, 0, 0]])


def test_paint_rejects_read_only_canvas():
    canvas = np.ones((5, 5, 3))
    canvas.flags.writeable = False
    with pytest.raises(ValueError, match="writeable"):
        paint(canvas, [SQUARE], [[0, 0, 0]])


def test_no_polygons_is_a_no_op():
    canvas = np.full((4, 4, 3), 0.3)
    assert paint(canvas, [], np.zeros((0, 3))) is canvas
    np.testing.assert_array_equal(canvas, 0.3)


# (8) speed smoke and determinism --------------------------------------------------------------------------------


def random_triangles(rng, n, size):
    centres = rng.uniform(0, size, (n, 2))
    radii = rng.uniform(5, 60, n) / 2
    angles = rng.uniform(0, 2 * np.pi, (n, 3))
    return [centres[i] + radii[i] * np.c_[np.cos(angles[i]), np.sin(angles[i])] for i in range(n)]


def test_3000_triangles_at_1024_speed_smoke_and_determinism():
    rng = np.random.default_rng(2015)
    n = 3000
    triangles = random_triangles(rng, n, 1024)
    colors = rng.uniform(0, 1, (n, 3))
    alphas = rng.uniform(0, 1, n)
    lights = np.array([t.mean(axis=0) for t in triangles])
    options = {"alphas": alphas, "lights": lights, "light_height": 20.0}
    render_polygons(triangles[:2], colors[:2], (8, 8), alphas=alphas[:2], lights=lights[:2], light_height=20.0)
    start = time.perf_counter()
    first = render_polygons(triangles, colors, (1024, 1024), **options)
    elapsed = time.perf_counter() - start
    print(f"\nrender_polygons: {n} triangles (diameter 5-60 px), 1024x1024, samples=4: {elapsed:.3f} s")
    second = render_polygons(triangles, colors, (1024, 1024), **options)
    np.testing.assert_array_equal(first, second)
    assert np.all((first >= 0) & (first <= 1))
    assert np.mean(np.any(first != 1.0, axis=2)) > 0.3  # the triangles really were drawn
