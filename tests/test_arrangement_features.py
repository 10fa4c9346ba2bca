"""paperlib.arrangement.features: the five appearance features of Hurtut 2009, section 2.1."""

import warnings

import numpy as np
import pandas as pd
import pytest

from paperlib.arrangement.features import (
    crossing_points,
    element_features,
    extremity_points,
    minimum_box_areas,
    normalized_area,
    normalized_count,
    normalized_elongation,
    normalized_orientation,
)
from paperlib.datasets.hershey import hershey_glyph, hershey_glyphs
from paperlib.geometry import Element, Stroke

UNIT = 1.0 / 21.0  # one Hershey grid unit in cap heights; the default pen is one unit wide


def counts(element, **parameters):
    return len(extremity_points(element, **parameters)), len(crossing_points(element))


def as_set(points, unit=UNIT):
    """Points in grid units, rounded, as a set of tuples."""
    return {tuple(p) for p in np.round(np.asarray(points) / unit, 6).tolist()}


def similarity(element, scale, angle, offset):
    rotation = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    return element.transformed(scale * rotation, offset)


def polygon(n_sides, angle=0.0, width=0.01):
    """A regular polygon of circumradius 1 as one closed stroke."""
    turns = angle + 2 * np.pi * np.arange(n_sides + 1) / n_sides
    return Element([Stroke(np.column_stack([np.cos(turns), np.sin(turns)]), width=width)])


def subdivided(element, pieces):
    """The element with every segment cut into ``pieces`` equal segments."""
    strokes = []
    for stroke in element:
        p = stroke.points
        t = np.arange(pieces)[:, None, None] / pieces
        inner = (p[:-1] * (1 - t) + p[1:] * t).transpose(1, 0, 2).reshape(-1, 2)
        strokes.append(Stroke(np.vstack([inner, p[-1:]]), stroke.width))
    return Element(strokes)


# --------------------------------------------------------------------------- known answers on glyphs


@pytest.mark.parametrize(
    "char, n_extremities, n_crossings",
    [
        ("x", 4, 1),  # four free ends, one crossing
        ("+", 4, 1),
        ("o", 0, 0),  # closed and smooth
        ("0", 0, 0),
        ("-", 2, 0),
        ("L", 3, 0),  # two ends and the corner where its two strokes join
        ("V", 3, 0),
        ("T", 3, 0),  # the stem ends on the bar: attached, not an extremity
        ("A", 3, 0),  # the bar stops 0.3 units short of the legs, inside the 1-unit pen: attached
        ("E", 5, 0),  # three free ends, two corners
        ("H", 4, 0),
        ("Z", 4, 0),
        ("M", 5, 0),
        ("D", 2, 0),  # a closed curve of two strokes with two corners
        ("8", 0, 1),  # one closed stroke crossing itself
        ("4", 4, 1),
        ("Q", 2, 1),
        ("6", 1, 0),  # its tail ends on its own bowl
        ("e", 2, 0),  # the start of the bar lies on the curve; the bar's end turns 90 degrees
        ("S", 2, 0),
        ("i", 3, 0),  # the dot, a diamond smaller than two pen widths, is one blob
        (".", 1, 0),
        ("#", 8, 4),
        ("*", 6, 1),  # three strokes through one point: one crossing
    ],
)
def test_futural_glyph_counts(char, n_extremities, n_crossings):
    assert counts(hershey_glyph(char, "futural")) == (n_extremities, n_crossings)


def test_extremity_and_crossing_locations():
    assert as_set(extremity_points(hershey_glyph("L"))) == {(4, 21), (16, 0), (4, 0)}
    assert as_set(extremity_points(hershey_glyph("T"))) == {(1, 21), (15, 21), (8, 0)}
    assert as_set(extremity_points(hershey_glyph("V"))) == {(1, 21), (17, 21), (9, 0)}
    assert as_set(crossing_points(hershey_glyph("x"))) == {(8.5, 7)}
    assert as_set(crossing_points(hershey_glyph("+"))) == {(13, 9)}
    assert as_set(crossing_points(hershey_glyph("4"))) == {(13, 7)}


def test_julesz_textons():
    """L and T, which Julesz found indiscriminable, get the same counts; + differs from both."""
    features = element_features(hershey_glyphs("LT+"), reference_area=100.0)
    raw = features[["extremities_raw", "crossings_raw"]].to_numpy()
    assert np.array_equal(raw[0], raw[1])
    assert not np.array_equal(raw[0], raw[2])


# --------------------------------------------------------------------------- definitions on synthetic shapes


@pytest.mark.parametrize("n_sides, n_corners", [(3, 3), (4, 4), (5, 5), (6, 0), (8, 0), (40, 0)])
def test_regular_polygons(n_sides, n_corners):
    """Corners turn by 360/n degrees: above 60 they are points of strong curvature."""
    for angle in np.linspace(0.0, 1.0, 5):  # a hexagon's exact 60 degrees is decided alike at any pose
        assert counts(polygon(n_sides, angle)) == (n_corners, 0)


def test_corner_angle_parameter():
    assert counts(polygon(6), corner_angle=np.radians(50)) == (6, 0)
    assert counts(polygon(4), corner_angle=np.radians(100)) == (0, 0)


def test_square_drawn_as_four_strokes_has_four_corners():
    square = np.array([(0, 0), (1, 0), (1, 1), (0, 1), (0, 0)], dtype=float)
    sides = Element([Stroke(square[i : i + 2], width=0.01) for i in range(4)])
    assert counts(sides) == (4, 0)
    assert as_set(extremity_points(sides), unit=1.0) == {(0, 0), (1, 0), (1, 1), (0, 1)}


def test_a_small_loop_is_a_bend_and_a_large_one_a_crossing():
    def stroke_with_loop(radius):
        theta = np.linspace(-np.pi / 2, 3 * np.pi / 2, 60)
        loop = np.column_stack([radius * np.cos(theta) * 1.2, radius + radius * np.sin(theta)])
        loop[:, 0] += np.linspace(-radius, radius, 60)  # the pen goes on, so the loop crosses itself
        return Element([Stroke(np.vstack([[(-10.0, 0.0)], loop, [(10.0, 0.0)]]), width=0.01)])

    small, large = stroke_with_loop(0.2), stroke_with_loop(3.0)
    assert counts(large) == (2, 1)
    assert counts(small) == (3, 0)  # two ends, and the small loop seen as one bend
    assert len(crossing_points(small, curvature_scale=0.001)) == 1  # it does cross itself


def test_crossing_through_a_vertex_counts_once():
    plus = Element([Stroke([(-1, 0), (0, 0), (1, 0)], width=0.01), Stroke([(0, -1), (0, 1)], width=0.01)])
    assert counts(plus) == (4, 1)
    both_at_vertices = Element(
        [Stroke([(-1, 0), (0, 0), (1, 0)], width=0.01), Stroke([(0, -1), (0, 0), (0, 1)], width=0.01)]
    )
    assert counts(both_at_vertices) == (4, 1)


def test_touches_and_overlaps_are_not_crossings():
    touching_tips = Element(
        [Stroke([(-1, 1), (0, 0), (-1, -1)], width=0.01), Stroke([(1, 1), (0, 0), (1, -1)], width=0.01)]
    )
    assert len(crossing_points(touching_tips)) == 0
    overlapping = Element([Stroke([(0, 0), (2, 0)], width=0.01), Stroke([(1, 0), (3, 0)], width=0.01)])
    assert counts(overlapping) == (2, 0)  # seen as one line from 0 to 3


def test_end_near_a_stroke_is_attached_within_the_pen_width():
    def tee(gap):
        return Element([Stroke([(-1, 0), (1, 0)], width=0.05), Stroke([(0, -2), (0, -gap)], width=0.05)])

    assert counts(tee(0.0)) == (3, 0)
    assert counts(tee(0.04)) == (3, 0)  # the inks touch
    assert counts(tee(0.2)) == (4, 0)  # a visible gap: a free end


def test_hook_at_a_stroke_end_is_part_of_that_end():
    hooked = Element([Stroke([(0, 0), (10, 0), (10, 0.3)], width=0.01)])  # a 90 degree hook, 3% long
    assert counts(hooked) == (2, 0)
    bent = Element([Stroke([(0, 0), (10, 0), (10, 3)], width=0.01)])  # the same turn, far from the end
    assert counts(bent) == (3, 0)


def test_s_bend_is_not_a_corner():
    # Two turns of 50 degrees in opposite directions within one window cancel.
    d1, d2 = np.radians(50), 0.0
    path = np.array([(0, 0), (10, 0), (10 + 0.2 * np.cos(d1), 0.2 * np.sin(d1))])
    path = np.vstack([path, path[-1] + (10 * np.cos(d2), 10 * np.sin(d2))])
    assert counts(Element([Stroke(path, width=0.01)])) == (2, 0)


# --------------------------------------------------------------------------- invariances


GLYPHS = "xo-LVTAE8Q6e#*iS"


@pytest.mark.parametrize("seed", [0, 1])
def test_counts_are_invariant_to_similarities(seed):
    rng = np.random.default_rng(seed)
    glyphs = hershey_glyphs(GLYPHS)
    poses = [(rng.uniform(0.01, 100), rng.uniform(0, 2 * np.pi), rng.uniform(-1e3, 1e3, 2)) for _ in glyphs]
    moved = [similarity(glyph, *pose) for glyph, pose in zip(glyphs, poses)]
    before, after = element_features(glyphs, 1.0), element_features(moved, 1.0)
    for column in ("extremities_raw", "crossings_raw"):
        assert np.array_equal(before[column], after[column])


def test_counts_do_not_depend_on_vertex_density():
    glyphs = hershey_glyphs(GLYPHS)
    before = element_features(glyphs, 1.0)
    after = element_features([subdivided(g, 3) for g in glyphs], 1.0)
    for column in ("extremities_raw", "crossings_raw"):
        assert np.array_equal(before[column], after[column])


def test_box_features_under_similarity():
    glyphs = hershey_glyphs("xLV")  # boxes with a defined direction (no isotropic '+' or 'o')
    scale, angle = 3.0, 0.4
    before = element_features(glyphs, 1.0)
    after = element_features([similarity(g, scale, angle, (5.0, -7.0)) for g in glyphs], 1.0)
    assert np.allclose(after.area_raw, scale**2 * before.area_raw)
    assert np.allclose(after.elongation_raw, before.elongation_raw)
    rotated = np.mod(before.orientation_raw + angle, np.pi)
    assert np.allclose(after.orientation_raw, rotated)


# --------------------------------------------------------------------------- normalisations and table


def test_normalisations_follow_the_paper():
    assert np.allclose(normalized_area([0.0, 2.5, 5.0, 50.0], reference_area=100.0), [0.0, 0.5, 1.0, 1.0])
    assert np.allclose(normalized_orientation([0.0, np.pi / 2, np.pi - 1e-9]), [0.0, 0.25, 0.5 - 1e-9 / (2 * np.pi)])
    assert np.allclose(normalized_elongation([1.0, 1.5, 3.0, 7.0, np.inf]), [1 / 3, 0.5, 1.0, 1.0, 1.0])
    assert np.allclose(normalized_count([0, 4, 12]), [0.0, 0.4, 1.2])  # counts are not capped


def test_feature_table():
    glyphs = hershey_glyphs("x-#L")
    table = element_features(glyphs, reference_area=10.0)
    assert list(table.columns) == [
        "area",
        "orientation",
        "elongation",
        "extremities",
        "crossings",
        "large",
        "very_elongated",
        "area_raw",
        "orientation_raw",
        "elongation_raw",
        "extremities_raw",
        "crossings_raw",
        "length_raw",
    ]
    assert isinstance(table.index, pd.RangeIndex) and len(table) == 4
    assert table.extremities_raw.tolist() == [4, 2, 8, 3]
    assert table.crossings_raw.tolist() == [1, 0, 4, 0]
    # Skeleton lengths: the two diagonals of 'x' (11 x 14 units), '-' (18 units), 'L' (21 + 12 units).
    assert table.length_raw[[0, 1, 3]].tolist() == pytest.approx([2 * np.hypot(11, 14) * UNIT, 18 * UNIT, 33 * UNIT])
    assert np.allclose(table.extremities, table.extremities_raw / 10)
    assert np.allclose(table.crossings, table.crossings_raw / 10)
    # 'x' with its pen: (11 + 1) x (14 + 1) grid units, taller than wide.
    assert table.area_raw[0] == pytest.approx(12 * 15 * UNIT**2)
    assert table.area[0] == pytest.approx(12 * 15 * UNIT**2 / 0.5)
    assert table.orientation[0] == pytest.approx(0.25)
    # '-' with its pen: 19 x 1 units, very elongated; on the skeleton, infinitely.
    assert table.elongation_raw[1] == pytest.approx(19.0)
    assert table.very_elongated[1] and table.elongation[1] == 1.0
    assert not table.very_elongated[0] and table.elongation[0] == pytest.approx(15 / 12 / 3)
    assert element_features(glyphs, 10.0, include_width=False).elongation_raw[1] == np.inf
    assert table.attrs["reference_area"] == 10.0


def test_large_elements_are_capped():
    table = element_features(hershey_glyphs("xx"), reference_area=2.0)
    area = table.area_raw[0]
    assert table.large.all() == (area > 0.1)
    small = element_features(hershey_glyphs("x"), reference_area=100 * area)
    assert small.area[0] == pytest.approx(0.2) and not small.large[0]
    large = element_features(hershey_glyphs("x"), reference_area=area)
    assert large.area[0] == 1.0 and large.large[0]


def test_many_elements_give_the_same_features_as_few():
    rng = np.random.default_rng(0)
    base = hershey_glyphs("abcdefghijklmnopqrstuvwxyz0123456789")
    elements = [similarity(base[i % len(base)], 1.0, rng.uniform(0, 6), rng.uniform(0, 100, 2)) for i in range(3000)]
    table = element_features(elements, reference_area=1e4)
    assert np.array_equal(table.extremities_raw[:36], element_features(base, 1e4).extremities_raw)


# --------------------------------------------------------------------------- degenerate and bad input


def test_zero_length_strokes_are_dots_with_a_warning():
    with pytest.warns(UserWarning, match="2 stroke\\(s\\) of zero length"):
        table = element_features(
            [Element([Stroke([(1.0, 2.0)], width=0.5)]), Element([Stroke([(0, 0), (4, 0)]), Stroke([(2, 1), (2, 1)])])],
            reference_area=100.0,
        )
    assert table.extremities_raw.tolist() == [1, 3]
    assert table.crossings_raw.tolist() == [0, 0]
    assert table.area_raw[0] == pytest.approx(0.25)  # the pen's square
    assert table.elongation_raw[0] == 1.0


def test_elements_of_one_point():
    with pytest.warns(UserWarning, match="zero length"):
        table = element_features([Element([Stroke([(1.0, 2.0)])]), Element([Stroke([(3.0, 3.0)])])], 1.0)
    assert table.extremities_raw.tolist() == [1, 1] and table.crossings_raw.tolist() == [0, 0]
    with pytest.warns(UserWarning, match="zero length"):
        assert as_set(extremity_points(Element([Stroke([(1.0, 2.0)])])), unit=1.0) == {(1, 2)}


def test_glyphs_without_dots_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        element_features(hershey_glyphs("xo"), 1.0)


@pytest.mark.parametrize("reference_area", [0.0, -1.0, np.nan, np.inf, "big", None])
def test_bad_reference_area(reference_area):
    with pytest.raises(ValueError, match="reference_area"):
        element_features(hershey_glyphs("x"), reference_area)


@pytest.mark.parametrize(
    "parameters, name",
    [
        (dict(curvature_scale=0.0), "curvature_scale"),
        (dict(curvature_scale=0.5), "curvature_scale"),
        (dict(curvature_scale=np.nan), "curvature_scale"),
        (dict(corner_angle=0.0), "corner_angle"),
        (dict(corner_angle=4.0), "corner_angle"),
        (dict(corner_angle=True), "corner_angle"),
        (dict(join_tolerance=-0.1), "join_tolerance"),
        (dict(join_tolerance="1%"), "join_tolerance"),
    ],
)
def test_bad_parameters(parameters, name):
    with pytest.raises(ValueError, match=name):
        element_features(hershey_glyphs("x"), 1.0, **parameters)


def test_bad_elements():
    with pytest.raises(ValueError, match="at least 1 element"):
        element_features([], 1.0)
    with pytest.raises(TypeError, match=r"elements\[0\]"):
        element_features([np.zeros((3, 2))], 1.0)
    with pytest.raises(TypeError, match="Element"):
        extremity_points([hershey_glyph("x")])
    with pytest.raises(TypeError, match="Element"):
        crossing_points(np.zeros((3, 2)))


# --------------------------------------------------------------------------- ink-filled loops


def hairpin(turn_x):
    """A stroke up and back down that crosses itself once; ``turn_x`` sets how wide its loop is."""
    return Element([Stroke([(-0.01, 0.0), (0.01, 1.0), (turn_x, 0.6), (-0.2, 0.1)], width=0.05)])


def test_a_retraced_hairpin_is_not_a_crossing_a_loop_with_a_hole_is():
    # Both cross themselves once. The narrow loop (mean width ~0.01) is covered by the 0.05 pen: a
    # cusp drawn up and back down by a hand, as the stem of a cursive 'a'; the wide one has a hole.
    assert len(crossing_points(hairpin(0.02))) == 0
    assert len(crossing_points(hairpin(0.4))) == 1


def test_hand_drawn_cursive_a_has_no_crossing():
    from paperlib.datasets.drawn_glyphs import drawn_glyph

    rng = np.random.default_rng(1)
    glyphs = [drawn_glyph("a", 0.05, angle=rng.uniform(0, 360), font="cursive", rng=rng) for _ in range(20)]
    assert element_features(glyphs, 1.0)["crossings_raw"].tolist() == [0] * 20


# --------------------------------------------------------------------------- crossings at the pen's scale


PEN = 0.05


def stem_poking_through_serif(overshoot, corner_gap=0.02):
    """A serif bar and a 'V' of two strokes whose tops join within the pen, one poking through the bar."""
    serif = Stroke([(-1.0, 0.0), (1.0, 0.0)], width=PEN)
    left = Stroke([(0.3, -2.0), (0.0, overshoot)], width=PEN)
    right = Stroke([(corner_gap, -0.01), (0.5, -2.0)], width=PEN)
    return Element([serif, left, right])


def test_a_joined_corner_poking_through_a_stroke_is_a_junction():
    # The corner's two arms both stay below the bar: the raw curves cross twice, the eye sees a T.
    assert len(crossing_points(stem_poking_through_serif(0.03))) == 0
    # The same corner pushed well through the bar (arms on both sides at twice the pen): crossings.
    assert len(crossing_points(stem_poking_through_serif(0.6, corner_gap=0.6))) >= 1


def branch(lean):
    """A stroke leaving a long bar at its middle at a shallow angle and crossing it after 0.3."""
    bar = Stroke([(-2.0, 0.0), (2.0, 0.0)], width=PEN)
    offshoot = Stroke([(0.0, 0.0), (0.15, lean), (0.3, -0.001), (1.5, -1.5)], width=PEN)
    return Element([bar, offshoot])


def test_a_branch_running_inside_the_ink_before_it_crosses_is_a_junction():
    assert len(crossing_points(branch(0.01))) == 0  # within half a pen of the bar until it crosses
    assert len(crossing_points(branch(0.2))) == 1  # a visible loop before it crosses: a crossing


def bar_across_parallel_lines(spacing):
    """A bar across a stem drawn as two parallel lines ``spacing`` apart (a complex face's thick stroke)."""
    lines = [Stroke([(x, -1.0), (x, 1.0)], width=PEN) for x in (0.0, spacing)]
    return Element([Stroke([(-1.0, 0.1), (1.0, 0.0)], width=PEN), *lines])


def test_a_stroke_crossing_a_doubled_stem_crosses_once():
    assert len(crossing_points(bar_across_parallel_lines(0.06))) == 1  # the inks of the two lines touch
    assert len(crossing_points(bar_across_parallel_lines(0.6))) == 2  # two stems, two crossings


@pytest.mark.parametrize(("char", "font"), [("w", "timesr"), ("n", "timesr"), ("t", "scriptc"), ("x", "timesr")])
def test_hand_drawn_complex_faces_keep_their_crossings(char, font):
    from paperlib.datasets.drawn_glyphs import drawn_glyph

    rng = np.random.default_rng(2)
    glyphs = [drawn_glyph(char, 0.05, angle=rng.uniform(0, 360), font=font, rng=rng) for _ in range(20)]
    crossings = element_features(glyphs, 1.0)["crossings_raw"]
    expected = {"w": 0, "n": 0, "t": 1, "x": 1}[char]
    assert crossings.tolist() == [expected] * 20


# --------------------------------------------------------------------------- the area's box


def rotated(points, angle):
    rotation = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    return np.asarray(points, dtype=float) @ rotation.T


@pytest.mark.parametrize("angle", [0.0, 0.3, np.pi / 4, 2.0])
def test_minimum_box_of_a_rotated_rectangle_is_the_rectangle(angle):
    outline = rotated([(0, 0), (2, 0), (2, 1), (0, 1), (0, 0)], angle)
    element = Element([Stroke(outline, width=0.1)])
    assert minimum_box_areas([element], include_width=False)[0] == pytest.approx(2.0, rel=1e-12)
    assert minimum_box_areas([element])[0] == pytest.approx(2.1 * 1.1, rel=1e-12)


def test_minimum_box_matches_shapely_on_random_strokes():
    shapely = pytest.importorskip("shapely")
    rng = np.random.default_rng(0)
    elements = [Element([Stroke(rng.normal(size=(int(rng.integers(3, 30)), 2)) * rng.uniform(0.1, 3, 2), width=0.01)])
                for _ in range(50)]
    ours = minimum_box_areas(elements, include_width=False)
    theirs = [shapely.MultiPoint(e.strokes[0].points).minimum_rotated_rectangle.area for e in elements]
    np.testing.assert_allclose(ours, theirs, rtol=1e-9)


def test_minimum_box_of_degenerate_elements():
    segment = Element([Stroke([(0, 0), (3, 4), (1.5, 2)], width=0.2)])
    dot = Element([Stroke([(1, 1), (1, 1)], width=0.2)])
    np.testing.assert_allclose(minimum_box_areas([segment, dot]), [5.2 * 0.2, 0.2 * 0.2], rtol=1e-12)
    np.testing.assert_allclose(minimum_box_areas([segment, dot], include_width=False), [0.0, 0.0], atol=1e-12)


def test_minimum_box_is_rotation_invariant_and_no_larger_than_the_pca_box():
    from paperlib.geometry import oriented_bounding_boxes

    glyphs = hershey_glyphs("nxS&", font="rowmans")
    turned = [glyph.transformed(rotated(np.eye(2), 0.7), (3.0, -1.0)) for glyph in glyphs]
    np.testing.assert_allclose(minimum_box_areas(turned), minimum_box_areas(glyphs), rtol=1e-9)
    assert np.all(minimum_box_areas(glyphs) <= oriented_bounding_boxes(glyphs, include_width=True).areas * (1 + 1e-12))
