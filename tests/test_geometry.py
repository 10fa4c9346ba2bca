"""paperlib.geometry: strokes, elements and closed curves (rings)."""

import dataclasses

import numpy as np
import pytest
from shapely.geometry import LinearRing, Point

from paperlib.geometry import (
    Element,
    Stroke,
    as_points,
    drop_repeated_vertices,
    oriented_ccw,
    resample_closed_curve,
    ring_centroid,
    signed_area,
)

UNIT_SQUARE = np.array([(0, 0), (1, 0), (1, 1), (0, 1)], dtype=float)  # counter-clockwise
TRIANGLE = np.array([(0, 0), (4, 0), (0, 3)], dtype=float)  # counter-clockwise, area 6
# L-shaped hexagon: area 3, centroid (5/6, 5/6) while the vertex mean is (1, 1).
L_SHAPE = np.array([(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)], dtype=float)


# --------------------------------------------------------------------------- Stroke


@pytest.mark.parametrize(
    "points",
    [
        [1.0, 2.0],  # 1-D
        [[0, 0, 0], [1, 1, 1]],  # 3 columns
        [[[0, 0]], [[1, 1]]],  # 3-D
        np.zeros((0, 2)),  # no point
        [["a", "b"]],  # not numeric
        [[0, 0], [1]],  # ragged
    ],
)
def test_stroke_rejects_bad_shapes(points):
    with pytest.raises(ValueError, match="stroke points"):
        Stroke(points)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_stroke_rejects_non_finite_points(bad):
    with pytest.raises(ValueError, match="NaN or infinite"):
        Stroke([(0, 0), (1, bad)])


@pytest.mark.parametrize("width", [0, -1.0, np.nan, np.inf])
def test_stroke_rejects_non_positive_or_non_finite_width(width):
    with pytest.raises(ValueError, match="width"):
        Stroke([(0, 0), (1, 1)], width=width)


@pytest.mark.parametrize("color", ["", None, 0])
def test_stroke_rejects_bad_color(color):
    with pytest.raises(ValueError, match="color"):
        Stroke([(0, 0)], color=color)


def test_stroke_stores_a_read_only_float_copy():
    source = np.array([[0, 0], [3, 4]])  # integers, writeable
    stroke = Stroke(source, width=2)
    assert stroke.points.dtype == np.float64 and stroke.points.shape == (2, 2)
    assert isinstance(stroke.width, float) and stroke.width == 2.0
    assert not stroke.points.flags.writeable
    with pytest.raises(ValueError):
        stroke.points[0, 0] = 9.0
    source[0, 0] = 9  # the stroke does not share memory with its input
    assert stroke.points[0, 0] == 0.0
    floats = np.array([[0.0, 0.0], [3.0, 4.0]])  # already float64: must still be copied
    copied = Stroke(floats)
    floats[1, 1] = 7.0
    assert copied.points[1, 1] == 4.0 and floats.flags.writeable
    with pytest.raises(dataclasses.FrozenInstanceError):
        stroke.width = 3.0


def test_as_points_honours_min_points_and_name():
    assert as_points([(1, 2)]).shape == (1, 2)
    with pytest.raises(ValueError, match="ring needs at least 2"):
        as_points([(1, 2)], name="ring", min_points=2)


def test_stroke_equality():
    a = Stroke([(0, 0), (1, 2)], width=1.5, color="red")
    assert a == Stroke(np.array([[0.0, 0.0], [1.0, 2.0]]), width=1.5, color="red")
    assert a != Stroke([(0, 0), (1, 3)], width=1.5, color="red")
    assert a != Stroke([(0, 0), (1, 2), (1, 2)], width=1.5, color="red")  # other length
    assert a != Stroke([(0, 0), (1, 2)], width=2.5, color="red")
    assert a != Stroke([(0, 0), (1, 2)], width=1.5, color="blue")
    assert a != "not a stroke"
    with pytest.raises(TypeError):  # mutable-looking array content: not hashable
        hash(a)


def test_stroke_len_and_length():
    stroke = Stroke([(0, 0), (3, 4), (3, 10)])
    assert len(stroke) == 3
    assert stroke.length() == pytest.approx(11.0)
    assert Stroke([(5, 5)]).length() == 0.0  # a dot


def test_stroke_transformed_maps_points_and_scales_width():
    stroke = Stroke([(1, 0), (0, 1)], width=2.0, color="green")
    moved = stroke.transformed([[2, 0], [0, 8]], offset=(10, 20))
    np.testing.assert_allclose(moved.points, [(12, 20), (10, 28)])
    assert moved.width == pytest.approx(2.0 * 4.0)  # sqrt(|det|) = sqrt(16)
    assert moved.color == "green"
    assert not moved.points.flags.writeable
    np.testing.assert_array_equal(stroke.points, [(1, 0), (0, 1)])  # original unchanged


def test_stroke_transformed_rotation_and_reflection_keep_width():
    stroke = Stroke([(1, 0), (2, 0)], width=3.0)
    rotated = stroke.transformed([[0, -1], [1, 0]])
    np.testing.assert_allclose(rotated.points, [(0, 1), (0, 2)], atol=1e-15)
    assert rotated.width == pytest.approx(3.0)
    assert stroke.transformed([[-1, 0], [0, 1]]).width == pytest.approx(3.0)  # det -1


@pytest.mark.parametrize("matrix", [[[1, 2], [2, 4]], [[0, 0], [0, 0]]])
def test_stroke_transformed_rejects_singular_matrix(matrix):
    with pytest.raises(ValueError, match="singular"):
        Stroke([(0, 0), (1, 1)]).transformed(matrix)


@pytest.mark.parametrize("matrix", [np.eye(3), [1, 0, 0, 1], [[1, 0], [0, np.nan]]])
def test_stroke_transformed_rejects_bad_matrix(matrix):
    with pytest.raises(ValueError, match="matrix"):
        Stroke([(0, 0)]).transformed(matrix)


def test_stroke_transformed_rejects_bad_offset():
    with pytest.raises(ValueError, match="offset"):
        Stroke([(0, 0)]).transformed(np.eye(2), offset=(0, np.nan))


# --------------------------------------------------------------------------- Element


def test_element_rejects_no_stroke():
    with pytest.raises(ValueError, match="at least one stroke"):
        Element(())
    with pytest.raises(ValueError, match="at least one stroke"):
        Element()


@pytest.mark.parametrize("item", [[(0, 0), (1, 1)], np.zeros((2, 2)), "stroke", None])
def test_element_rejects_non_stroke_items(item):
    with pytest.raises(TypeError, match="element stroke 1"):
        Element([Stroke([(0, 0)]), item])


def test_element_container_behaviour_and_equality():
    a, b = Stroke([(0, 0), (1, 0)]), Stroke([(2, 2), (3, 5), (4, 4)], color="red")
    element = Element([a, b], name="glyph")  # a list is stored as a tuple
    assert element.strokes == (a, b) and isinstance(element.strokes, tuple)
    assert len(element) == 2 and list(element) == [a, b]
    np.testing.assert_array_equal(element.points, [(0, 0), (1, 0), (2, 2), (3, 5), (4, 4)])
    assert element == Element((Stroke([(0, 0), (1, 0)]), b), name="glyph")
    assert element != Element((a, b), name="other")
    assert element != Element((b, a), name="glyph")
    with pytest.raises(dataclasses.FrozenInstanceError):
        element.name = "x"


def test_element_bounds():
    element = Element([Stroke([(0, -1), (2, 3)]), Stroke([(-4, 0.5)])])
    bounds = element.bounds()
    assert bounds == (-4.0, -1.0, 2.0, 3.0)
    assert all(type(v) is float for v in bounds)


def test_element_transformed_maps_every_stroke_and_keeps_name():
    element = Element([Stroke([(1, 1)], width=1.0), Stroke([(0, 2), (2, 0)], width=0.5)], name="x")
    moved = element.transformed(3 * np.eye(2), offset=(1, -1))
    assert moved.name == "x" and len(moved) == 2
    first, second = moved.strokes
    np.testing.assert_allclose(first.points, [(4, 2)])
    np.testing.assert_allclose(second.points, [(1, 5), (7, -1)])
    assert (first.width, second.width) == pytest.approx((3.0, 1.5))  # np.linalg.det rounds
    assert moved.bounds() == (1.0, -1.0, 7.0, 5.0)
    with pytest.raises(ValueError, match="singular"):
        element.transformed(np.zeros((2, 2)))


# --------------------------------------------------------------------------- curves: area


@pytest.mark.parametrize(
    "ring, area",
    [(UNIT_SQUARE, 1.0), (TRIANGLE, 6.0), (L_SHAPE, 3.0), (2 * UNIT_SQUARE + 7, 4.0)],
)
def test_signed_area_of_known_polygons(ring, area):
    assert signed_area(ring) == pytest.approx(area)
    assert signed_area(ring[::-1]) == pytest.approx(-area)  # clockwise: negative
    assert signed_area(np.roll(ring, 2, axis=0)) == pytest.approx(area)  # any start vertex
    assert isinstance(signed_area(ring), float)


def test_signed_area_accepts_lists_and_ignores_a_closing_repeat():
    assert signed_area([(0, 0), (1, 0), (1, 1), (0, 1)]) == pytest.approx(1.0)
    assert signed_area(np.vstack([TRIANGLE, TRIANGLE[:1]])) == pytest.approx(6.0)
    assert signed_area([(0, 0), (1, 1), (2, 2)]) == 0.0  # collinear


# --------------------------------------------------------------------------- curves: centroid


@pytest.mark.parametrize(
    "ring, centroid",
    [
        (UNIT_SQUARE, (0.5, 0.5)),
        (TRIANGLE, (4 / 3, 1.0)),
        (L_SHAPE, (5 / 6, 5 / 6)),  # region centroid, not the vertex mean (1, 1)
        (UNIT_SQUARE * [3, 2] + [-10, 5], (-8.5, 6.0)),
    ],
)
def test_ring_centroid_of_known_polygons(ring, centroid):
    np.testing.assert_allclose(ring_centroid(ring), centroid, atol=1e-12)
    np.testing.assert_allclose(ring_centroid(ring[::-1]), centroid, atol=1e-12)  # clockwise


def test_ring_centroid_ignores_extra_vertices_on_an_edge():
    # Many vertices along the bottom edge pull the vertex mean down, not the centroid.
    bottom = np.column_stack([np.linspace(0, 1, 50, endpoint=False), np.zeros(50)])
    dense = np.vstack([bottom, [(1, 0), (1, 1), (0, 1)]])
    np.testing.assert_allclose(ring_centroid(dense), (0.5, 0.5), atol=1e-12)
    assert dense[:, 1].mean() < 0.1


@pytest.mark.parametrize(
    "ring", [[(0, 0), (1, 1), (2, 2)], [(0, 0), (1, 0), (0, 0)], [(3, 3), (3, 3), (3, 3)]]
)
def test_ring_centroid_of_zero_area_raises(ring):
    with pytest.raises(ValueError, match="no area"):
        ring_centroid(ring)


# --------------------------------------------------------------------------- curves: repeats


def test_drop_repeated_vertices_removes_consecutive_repeats():
    ring = [(0, 0), (0, 0), (1, 0), (1, 1), (1, 1), (1, 1), (0, 1)]
    result = drop_repeated_vertices(ring)
    np.testing.assert_array_equal(result, UNIT_SQUARE)
    assert result.dtype == np.float64


def test_drop_repeated_vertices_removes_the_closing_repeat_and_keeps_the_start():
    closed = np.vstack([UNIT_SQUARE, UNIT_SQUARE[:1]])
    np.testing.assert_array_equal(drop_repeated_vertices(closed), UNIT_SQUARE)
    wrapped = np.vstack([UNIT_SQUARE, UNIT_SQUARE[:1], UNIT_SQUARE[:1]])
    np.testing.assert_array_equal(drop_repeated_vertices(wrapped), UNIT_SQUARE)
    np.testing.assert_array_equal(drop_repeated_vertices(UNIT_SQUARE), UNIT_SQUARE)


def test_drop_repeated_vertices_keeps_non_consecutive_duplicates_and_clean_rings():
    # A figure eight passes through (1, 1) twice, not in a row: both stay.
    eight = np.array([(0, 0), (1, 1), (2, 0), (2, 2), (1, 1), (0, 2)], dtype=float)
    np.testing.assert_array_equal(drop_repeated_vertices(eight), eight)
    # Only exact equality counts: both coordinates must match.
    near = np.array([(0, 0), (0, 1e-12), (1e-12, 1e-12)])
    np.testing.assert_array_equal(drop_repeated_vertices(near), near)


def test_drop_repeated_vertices_of_a_single_repeated_point_is_empty():
    assert drop_repeated_vertices([(2, 3), (2, 3), (2, 3)]).shape == (0, 2)


# --------------------------------------------------------------------------- curves: orientation


def test_oriented_ccw():
    np.testing.assert_array_equal(oriented_ccw(UNIT_SQUARE), UNIT_SQUARE)  # already CCW
    clockwise = TRIANGLE[::-1]
    assert signed_area(clockwise) < 0
    result = oriented_ccw(clockwise)
    np.testing.assert_array_equal(result[0], clockwise[0])  # the start vertex stays first
    np.testing.assert_array_equal(result[1:], clockwise[:0:-1])
    assert signed_area(result) > 0
    assert oriented_ccw([(0, 0), (1, 0), (1, 1)]).dtype == np.float64


# --------------------------------------------------------------------------- curves: resampling


def test_resample_square_known_answer():
    square = 2 * UNIT_SQUARE
    expected = [(0, 0), (1, 0), (2, 0), (2, 1), (2, 2), (1, 2), (0, 2), (0, 1)]
    np.testing.assert_allclose(resample_closed_curve(square, 8), expected, atol=1e-12)
    np.testing.assert_allclose(resample_closed_curve(square, 4), square, atol=1e-12)
    # The closing edge (0, 2) -> (0, 0) is part of the curve: perimeter 8, step 8 / 3.
    np.testing.assert_allclose(
        resample_closed_curve(square, 3), [(0, 0), (2, 2 / 3), (2 / 3, 2)], atol=1e-12
    )


@pytest.mark.parametrize("n_points", [3, 7, 10, 64, np.int64(101)])
def test_resample_count_points_on_curve_and_equal_arc_spacing(n_points):
    ring = LinearRing(UNIT_SQUARE)
    result = resample_closed_curve(UNIT_SQUARE, n_points)
    assert result.shape == (n_points, 2) and result.dtype == np.float64
    np.testing.assert_array_equal(result[0], UNIT_SQUARE[0])  # starts at the first vertex
    assert max(ring.distance(Point(p)) for p in result) < 1e-12  # on the curve
    positions = np.array([ring.project(Point(p)) for p in result])  # arc length from (0, 0)
    np.testing.assert_allclose(positions, np.arange(n_points) * 4.0 / n_points, atol=1e-12)


def test_resample_does_not_depend_on_input_vertex_spacing():
    # The same square with many extra vertices on two of its edges.
    bottom = np.column_stack([np.linspace(0, 1, 37, endpoint=False), np.zeros(37)])
    right = np.column_stack([np.ones(5), np.linspace(0, 1, 5, endpoint=False)])
    dense = np.vstack([bottom, right, [(1, 1), (0, 1)]])
    np.testing.assert_allclose(
        resample_closed_curve(dense, 12), resample_closed_curve(UNIT_SQUARE, 12), atol=1e-12
    )


def test_resample_triangle_spacing():
    perimeter = 3 + 4 + 5
    result = resample_closed_curve(TRIANGLE, 24)
    ring = LinearRing(TRIANGLE)
    positions = np.array([ring.project(Point(p)) for p in result])
    np.testing.assert_allclose(np.diff(positions), perimeter / 24, atol=1e-12)


@pytest.mark.parametrize("bad", [0, 2, -5, 3.5, True, "10", None])
def test_resample_rejects_bad_n_points(bad):
    with pytest.raises(ValueError, match="n_points"):
        resample_closed_curve(UNIT_SQUARE, bad)


@pytest.mark.parametrize("ring", [[(1, 1), (1, 1), (1, 1)], [(0, 0), (0, 0)]])
def test_resample_rejects_zero_length(ring):
    with pytest.raises(ValueError, match="zero length"):
        resample_closed_curve(ring, 5)


@pytest.mark.parametrize("ring", [[(0, 0)], [(0, 0), (1, np.nan)], [(0, 0, 0), (1, 1, 1)]])
def test_resample_rejects_bad_rings(ring):
    with pytest.raises(ValueError, match="ring"):
        resample_closed_curve(ring, 5)


def test_as_elements_accepts_sequences_and_names_the_bad_item():
    from paperlib.geometry import as_elements

    element = Element([Stroke([[0, 0], [1, 0]])])
    assert as_elements((element, element)) == [element, element]
    assert as_elements(iter([element])) == [element]
    with pytest.raises(TypeError, match="wrap it in a list"):
        as_elements(element)
    with pytest.raises(TypeError, match=r"drawing\[1\] is a str"):
        as_elements([element, "x"], name="drawing")
    with pytest.raises(TypeError, match="got int"):
        as_elements(3)
    with pytest.raises(ValueError, match="at least 2 elements, got 1"):
        as_elements([element], min_count=2)
