"""paperlib.geometry.boxes: PCA oriented bounding boxes (Barla 2006 section 2.1, Hurtut 2009 section 2.1)."""

import numpy as np
import pytest

from paperlib.datasets.hershey import hershey_glyph
from paperlib.geometry import Element, Stroke
from paperlib.geometry import OrientedBox, OrientedBoxes, oriented_bounding_box, oriented_bounding_boxes, stack_strokes
from paperlib.geometry.curves import signed_area

UNIT = 1.0 / 21.0  # one Hershey grid unit in cap heights


def rotation(angle):
    return np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])


def rectangle(center, half_lengths, angle):
    """Corners of a rectangle, counter-clockwise."""
    local = np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)]) * half_lengths
    return local @ rotation(angle).T + center


def closed(points):
    return np.vstack([points, points[:1]])


def same_angle(a, b):
    """Equal as axis directions (modulo pi)."""
    difference = np.mod(a - b + np.pi / 2, np.pi) - np.pi / 2
    return abs(difference) < 1e-9


# --------------------------------------------------------------------------- recovering known boxes


@pytest.mark.parametrize("angle", [0.0, 0.3, np.pi / 2, 2.0, 3.0])
def test_rotated_rectangle_outline_recovers_its_box(angle):
    corners = rectangle((5.0, -2.0), (3.0, 1.0), angle)
    box = oriented_bounding_box(Element([Stroke(closed(corners))]))
    assert same_angle(box.angle, angle)
    assert 0 <= box.angle < np.pi
    assert np.allclose(box.half_lengths, (3.0, 1.0))
    assert np.allclose(box.center, (5.0, -2.0))
    assert box.area == pytest.approx(12.0)
    assert box.elongation == pytest.approx(3.0)
    assert box.diagonal == pytest.approx(2 * np.hypot(3.0, 1.0))
    # The same four corners, counter-clockwise, from the (-major, -minor) one.
    assert signed_area(box.corners()) > 0
    assert np.allclose(np.sort(box.corners(), axis=0), np.sort(corners, axis=0))


@pytest.mark.parametrize("angle", [0.1, 1.3, 2.9])
def test_point_set_recovers_rotated_rectangle(angle):
    box = oriented_bounding_box(rectangle((0.0, 0.0), (2.0, 0.5), angle))
    assert same_angle(box.angle, angle)
    assert np.allclose(box.half_lengths, (2.0, 0.5))


def test_axes_are_the_rotation_by_the_angle():
    box = oriented_bounding_box(rectangle((1.0, 1.0), (4.0, 1.0), 0.7))
    major, minor = box.axes.T
    assert np.allclose(major, (np.cos(0.7), np.sin(0.7)))
    assert np.allclose(minor, (-np.sin(0.7), np.cos(0.7)))  # major turned by +90 degrees


def test_far_from_the_origin_the_box_is_as_accurate():
    corners = rectangle((1e7, -3e7), (3.0, 1.0), 0.4)
    box = oriented_bounding_box(Element([Stroke(closed(corners))]))
    assert np.allclose(box.half_lengths, (3.0, 1.0), atol=1e-6)
    assert same_angle(box.angle, 0.4)


def test_hershey_glyphs():
    bar = oriented_bounding_box(hershey_glyph("-"))
    assert bar.angle == 0.0
    assert np.allclose(bar.half_lengths, (9 * UNIT, 0.0))
    assert bar.half_lengths[1] == 0.0 and bar.elongation == np.inf and bar.area == 0.0
    cross = oriented_bounding_box(hershey_glyph("x"))  # 11 units wide, 14 tall
    assert cross.angle == pytest.approx(np.pi / 2)
    assert np.allclose(cross.half_lengths, (7 * UNIT, 5.5 * UNIT))
    assert np.allclose(cross.center, (8.5 * UNIT, 7 * UNIT))


# --------------------------------------------------------------------------- what the PCA is fitted to


def test_arc_length_weighting_ignores_vertex_density():
    """An 'L' whose long arm carries many vertices keeps its box; a vertex PCA would tilt."""
    corner = np.array([[0.0, 3.0], [0.0, 0.0], [4.0, 0.0]])
    dense = np.vstack([np.column_stack([np.zeros(50), np.linspace(3.0, 0.0, 50)]), [[4.0, 0.0]]])
    plain_box = oriented_bounding_box(Element([Stroke(corner)]))
    dense_box = oriented_bounding_box(Element([Stroke(dense)]))
    assert dense_box.angle == pytest.approx(plain_box.angle)
    assert np.allclose(dense_box.half_lengths, plain_box.half_lengths)
    assert not same_angle(oriented_bounding_box(dense).angle, plain_box.angle)


def test_major_axis_is_the_longer_side_not_the_larger_variance():
    # Most of the weight is spread along y (variance 9) but the box is longer along x.
    points = [(-10.0, 0.0), (10.0, 0.0), (0.0, -3.0), (0.0, 3.0)]
    box = oriented_bounding_box(points, weights=[1.0, 1.0, 100.0, 100.0])
    assert box.angle == 0.0
    assert np.allclose(box.half_lengths, (10.0, 3.0))


def test_weights_tilt_the_axes_but_every_point_stays_inside():
    points = np.array([(0.0, 0.0), (4.0, 1.0), (8.0, 0.0), (4.0, -1.0), (7.0, 6.0)])
    unweighted = oriented_bounding_box(points)
    weighted = oriented_bounding_box(points, weights=[1, 1, 1, 1, 0])
    assert weighted.angle == pytest.approx(0.0, abs=1e-12)
    assert not same_angle(unweighted.angle, weighted.angle)
    local = (points - weighted.center) @ weighted.axes
    assert np.all(np.abs(local) <= weighted.half_lengths + 1e-12)


def test_include_width_dilates_by_half_the_pen():
    segment = Element([Stroke([(0.0, 0.0), (3.0, 4.0)], width=0.5)])
    skeleton = oriented_bounding_box(segment)
    ink = oriented_bounding_box(segment, include_width=True)
    assert np.allclose(skeleton.half_lengths, (2.5, 0.0))
    assert np.allclose(ink.half_lengths, (2.75, 0.25))
    assert ink.angle == pytest.approx(skeleton.angle) == pytest.approx(np.arctan2(4, 3))
    assert np.allclose(ink.center, skeleton.center)
    assert ink.elongation == pytest.approx(11.0)


def test_pen_width_of_each_stroke_counts():
    thin_and_thick = Element([Stroke([(0, 0), (10, 0)], width=0.2), Stroke([(0, 2), (10, 2)], width=2.0)])
    box = oriented_bounding_box(thin_and_thick, include_width=True)
    assert np.allclose(box.half_lengths, (6.0, (3.0 + 0.1) / 2))


# --------------------------------------------------------------------------- degenerate cases


def test_single_point_is_a_box_of_zero_size():
    box = oriented_bounding_box([(2.0, 3.0)])
    assert np.array_equal(box.half_lengths, [0.0, 0.0])
    assert box.angle == 0.0 and box.area == 0.0 and box.elongation == 1.0
    assert np.array_equal(box.corners(), np.tile([2.0, 3.0], (4, 1)))


def test_dot_element_gets_the_square_its_pen_draws():
    dot = Element([Stroke([(1.0, 1.0)], width=0.4)])
    assert np.array_equal(oriented_bounding_box(dot).half_lengths, [0.0, 0.0])
    box = oriented_bounding_box(dot, include_width=True)
    assert np.allclose(box.half_lengths, (0.2, 0.2)) and box.elongation == 1.0


def test_repeated_points_and_zero_length_strokes_do_not_bias_the_axes():
    strokes = [Stroke([(0, 0), (0, 0), (6, 0)]), Stroke([(3, 1), (3, 1)])]
    box = oriented_bounding_box(Element(strokes))
    assert box.angle == 0.0
    assert np.allclose(box.half_lengths, (3.0, 0.5))  # the dot is inside the box, not in the PCA


@pytest.mark.parametrize("angle", [0.0, 0.2, 0.9])
def test_straight_segment_has_zero_width_exactly(angle):
    points = np.array([(0.0, 0.0), (np.cos(angle), np.sin(angle))]) * 7.0
    box = oriented_bounding_box(Element([Stroke(points)]))
    assert box.half_lengths[1] == 0.0
    assert box.elongation == np.inf
    assert same_angle(box.angle, angle)


def test_isotropic_shapes_get_the_x_axis():
    square = rectangle((0.0, 0.0), (1.0, 1.0), 0.3)
    box = oriented_bounding_box(Element([Stroke(closed(square))]))
    assert box.angle == 0.0  # PCA has no direction: the documented axis-aligned box
    assert oriented_bounding_box(hershey_glyph("+")).angle == 0.0


# --------------------------------------------------------------------------- many boxes


def test_batch_matches_single_boxes():
    glyphs = [hershey_glyph(c) for c in "xo-LV8"]
    boxes = oriented_bounding_boxes(glyphs, include_width=True)
    assert isinstance(boxes, OrientedBoxes) and len(boxes) == 6
    assert boxes.corners().shape == (6, 4, 2)
    for glyph, box in zip(glyphs, boxes):
        single = oriented_bounding_box(glyph, include_width=True)
        assert np.allclose(box.center, single.center)
        assert np.allclose(box.half_lengths, single.half_lengths)
        assert box.angle == pytest.approx(single.angle)
    assert np.allclose(boxes.areas, [b.area for b in boxes])
    assert np.array_equal(boxes.elongations, [b.elongation for b in boxes])
    assert np.allclose(boxes.diagonals, [b.diagonal for b in boxes])


def test_stacked_strokes_are_accepted_and_drop_repeated_vertices():
    glyphs = [hershey_glyph(c) for c in "ox"]
    stack = stack_strokes(glyphs + [Element([Stroke([(0, 0), (0, 0), (1, 0), (1, 0)])])])
    assert stack.n_elements == 3
    assert np.array_equal(np.diff(stack.stroke_offsets), [17, 2, 2, 2])
    assert np.array_equal(stack.stroke_element, [0, 1, 1, 2])
    boxes = oriented_bounding_boxes(stack)
    assert np.allclose(boxes.half_lengths[:2], oriented_bounding_boxes(glyphs).half_lengths)


def test_arrays_are_read_only():
    box = oriented_bounding_box([(0, 0), (1, 2)])
    with pytest.raises(ValueError):
        box.center[0] = 1.0
    boxes = oriented_bounding_boxes([hershey_glyph("x")])
    with pytest.raises(ValueError):
        boxes.half_lengths[0, 0] = 1.0


# --------------------------------------------------------------------------- constructing boxes


def test_from_angle_reduces_the_angle_and_builds_the_axes():
    box = OrientedBox.from_angle((1.0, 2.0), (3.0, 1.0), np.pi + 0.5)
    assert box.angle == pytest.approx(0.5)
    assert np.allclose(box.axes[:, 0], (np.cos(0.5), np.sin(0.5)))


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(half_lengths=(1.0, 2.0)), "major >= minor"),
        (dict(half_lengths=(1.0, -0.5)), "major >= minor"),
        (dict(angle=np.pi), r"\[0, pi\)"),
        (dict(angle=-0.1), r"\[0, pi\)"),
        (dict(axes=np.eye(2)[:, ::-1]), "rotation"),
        (dict(center=(np.nan, 0.0)), "NaN"),
        (dict(center=(0.0, 0.0, 0.0)), "shape"),
    ],
)
def test_malformed_box_is_rejected(kwargs, message):
    fields = dict(center=(0.0, 0.0), axes=np.eye(2), half_lengths=(2.0, 1.0), angle=0.0)
    fields.update(kwargs)
    with pytest.raises(ValueError, match=message):
        OrientedBox(**fields)


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "points, kwargs, message",
    [
        (np.zeros((0, 2)), {}, "at least 1"),
        ([(0.0, np.inf)], {}, "infinite"),
        ([(0.0, 1.0, 2.0)], {}, "shape"),
        ([(0, 0), (1, 1)], dict(weights=[1.0]), "shape"),
        ([(0, 0), (1, 1)], dict(weights=[1.0, -1.0]), "non-negative"),
        ([(0, 0), (1, 1)], dict(weights=[0.0, 0.0]), "not all zero"),
        ([(0, 0), (1, 1)], dict(weights=[np.nan, 1.0]), "finite"),
        ([(0, 0), (1, 1)], dict(include_width=True), "no pen width"),
    ],
)
def test_bad_points_are_rejected(points, kwargs, message):
    with pytest.raises(ValueError, match=message):
        oriented_bounding_box(points, **kwargs)


def test_weights_with_an_element_are_rejected():
    with pytest.raises(ValueError, match="arc length"):
        oriented_bounding_box(hershey_glyph("x"), weights=[1.0, 1.0, 1.0, 1.0])


def test_bad_element_lists_are_rejected():
    with pytest.raises(ValueError, match="at least 1 element"):
        oriented_bounding_boxes([])
    with pytest.raises(TypeError, match=r"elements\[1\]"):
        oriented_bounding_boxes([hershey_glyph("x"), np.zeros((2, 2))])
    with pytest.raises(TypeError, match="wrap it in a list"):
        oriented_bounding_boxes(hershey_glyph("x"))


def test_square_box_of_a_symmetric_glyph_keeps_its_pca_axis_despite_rounding():
    from paperlib.datasets import hershey_glyph

    plus = hershey_glyph("+")
    offsets = np.random.default_rng(0).random((50, 2)) * 10  # rounding differs with the position
    boxes = oriented_bounding_boxes([plus.transformed(np.eye(2), offset) for offset in offsets])
    assert np.unique(boxes.angles).size == 1
