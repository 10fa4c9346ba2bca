"""paperlib.arrangement.ink: extremities and crossings read on the ink of overdrawn strokes (issue 27)."""

import numpy as np
import pytest

from paperlib.arrangement import (
    MAX_INK_PIXELS,
    element_features,
    extremity_points,
    crossing_points,
    ink_centrelines,
    overdrawn_fraction,
)
from paperlib.datasets.drawn_glyphs import drawn_glyph
from paperlib.geometry import Element, Stroke

PEN = 0.1


def parallel_lines(points, lines=3, spacing=0.3 * PEN, pen=PEN):
    """One thick stroke drawn as ``lines`` pen lines side by side, as bold faces draw it."""
    points = np.asarray(points, dtype=float)
    tangent = np.gradient(points, axis=0)
    normal = np.column_stack([-tangent[:, 1], tangent[:, 0]]) / np.hypot(*tangent.T)[:, None]
    offsets = (np.arange(lines) - (lines - 1) / 2.0) * spacing
    return [Stroke(points + offset * normal, pen) for offset in offsets]


def arc(start, stop, n=90, radius=1.0):
    angle = np.linspace(start, stop, n)
    return radius * np.column_stack([np.cos(angle), np.sin(angle)])


def segment(a, b, n=40):
    return np.linspace(a, b, n)


def bold(*paths, **kw):
    return Element(tuple(stroke for path in paths for stroke in parallel_lines(path, **kw)))


def ink_counts(element, **parameters):
    return (len(extremity_points(element, topology="ink", **parameters)),
            len(crossing_points(element, topology="ink")))


BOLD_C = bold(arc(np.pi / 4, 7 * np.pi / 4))
BOLD_X = bold(segment((-1, -1), (1, 1)), segment((-1, 1), (1, -1)))
BOLD_O = bold(arc(0, 2 * np.pi, 120))
BOLD_T = bold(segment((-1, 1), (1, 1)), segment((0, 1), (0, -1)))


@pytest.mark.parametrize(("element", "expected"), [(BOLD_C, (2, 0)), (BOLD_X, (4, 1)), (BOLD_O, (0, 0)),
                                                   (BOLD_T, (3, 0))])
def test_thick_strokes_drawn_as_parallel_lines_read_as_one_line(element, expected):
    assert ink_counts(element) == expected


@pytest.mark.parametrize("angle", [0.0, 0.3, np.pi / 4, 1.1])
@pytest.mark.parametrize("scale", [0.05, 1.0, 30.0])
def test_ink_reading_does_not_depend_on_pose_or_scale(angle, scale):
    rotation = scale * np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    for element, expected in ((BOLD_X, (4, 1)), (BOLD_C, (2, 0))):
        moved = Element(tuple(Stroke(s.points @ rotation.T + (3.0, -2.0), s.width * scale) for s in element.strokes))
        assert ink_counts(moved) == expected


@pytest.mark.parametrize("degrees", [20, 30, 45])
def test_a_shallow_crossing_is_found_where_the_pen_lines_cross(degrees):
    """Two bold strokes crossing at a small angle share their ink: the skeleton makes two forks of it.

    Read alone, the centrelines see no crossing; told where the pen's lines cross (as
    element_features tells them), the two forks are one crossing.
    """
    half = np.radians(degrees / 2)
    c, s = np.cos(half), np.sin(half)
    element = bold(segment((-c, -s), (c, s)), segment((-c, s), (c, -s)))
    assert ink_counts(element) == (4, 1)
    alone = ink_centrelines(element)
    assert len(crossing_points(alone, topology="strokes")) == 0
    told = ink_centrelines(element, crossings=crossing_points(element, topology="strokes"))
    assert len(crossing_points(told, topology="strokes")) == 1


def test_the_pen_lines_themselves_miscount_a_bold_x():
    """Read pen line by pen line, the bold 'x' is not the ink's 4 ends and a crossing (why the ink is read)."""
    strokes = (len(extremity_points(BOLD_X, topology="strokes")), len(crossing_points(BOLD_X, topology="strokes")))
    assert strokes != (4, 1)


def test_a_dot_of_ink_is_one_extremity():
    dot = Stroke(np.array([[3.0, 0.0], [3.0, 0.0]]), PEN)
    element = Element(BOLD_C.strokes + (dot,))
    assert ink_counts(element) == (3, 0)
    near_the_dot = [stroke.points for stroke in ink_centrelines(element).strokes
                    if np.hypot(*(stroke.points - (3.0, 0.0)).T).max() < PEN]
    assert len(near_the_dot) == 1  # a point, or a few pixels of skeleton: a blob, one extremity


@pytest.mark.parametrize("length", [0.0625, 0.125])
def test_a_stroke_shorter_than_its_pen_is_one_dot(length):
    """Its ink thins to a pixel or two, which skan builds no graph of (found by the property below)."""
    element = Element((Stroke(np.array([[0.0625, 0.0], [0.0625, length]]), 0.25),))
    strokes = ink_centrelines(element).strokes
    assert len(strokes) == 1 and len(strokes[0].points) <= 3
    assert np.hypot(*(strokes[0].points - (0.0625, length / 2)).T).max() < 0.25


def test_centrelines_keep_name_pen_and_run_inside_the_ink():
    element = Element(BOLD_C.strokes, name="c")
    centrelines = ink_centrelines(element)
    assert centrelines.name == "c"
    assert len(centrelines.strokes) == 1
    assert {stroke.width for stroke in centrelines.strokes} == {PEN}
    radius = np.hypot(*centrelines.strokes[0].points.T)
    assert np.all(np.abs(radius - 1.0) < PEN / 2)


def test_hand_drawn_bold_glyphs_read_alike_copy_after_copy():
    """Twenty copies of a Times-bold 'x' (stroke-wise 6 to 12 extremities): one reading on the ink."""
    readings = {ink_counts(drawn_glyph("x", 1.0, font="timesrb", rng=seed))[1] for seed in range(20)}
    assert readings == {1}
    copies = [drawn_glyph("c", 1.0, font="timesrb", rng=seed) for seed in range(20)]
    extremities = [ink_counts(copy)[0] for copy in copies]
    assert np.mean(np.array(extremities) == 2) >= 0.9


def test_overdrawn_fraction_separates_single_and_parallel_lines():
    single = Element((Stroke(arc(0.0, np.pi), PEN),))
    assert overdrawn_fraction(single) == 0.0
    assert overdrawn_fraction(BOLD_C) == 1.0
    assert 0.0 < overdrawn_fraction(Element((Stroke(segment((-1, 0), (1, 0)), PEN),
                                             Stroke(segment((0, -1), (0, 1)), PEN)))) < 0.2


def test_features_choose_one_reading_for_the_whole_arrangement():
    thin = [Element((Stroke(segment((-1, -1), (1, 1)), PEN), Stroke(segment((-1, 1), (1, -1)), PEN)))] * 3
    assert element_features(thin, 100.0).attrs["topology_read_on"] == "strokes"
    table = element_features([BOLD_X, BOLD_C, BOLD_X], 100.0)
    assert table.attrs["topology_read_on"] == "ink"
    assert table.extremities_raw.tolist() == [4, 2, 4] and table.crossings_raw.tolist() == [1, 0, 1]
    forced = element_features([BOLD_X, BOLD_C, BOLD_X], 100.0, topology="strokes")
    assert forced.attrs["topology_read_on"] == "strokes"


def test_a_hairline_pen_on_a_large_drawing_stays_within_the_raster_bound():
    element = Element((Stroke(arc(0.0, 3 * np.pi / 2, 400, radius=1000.0), 1e-6),))
    centrelines = ink_centrelines(element)
    assert len(centrelines.strokes) == 1
    assert ink_counts(element) == (2, 0)
    assert MAX_INK_PIXELS <= 4096


@pytest.mark.parametrize(("call", "error", "match"), [
    (lambda: ink_centrelines(BOLD_C, pixels_per_pen=2), ValueError, "pixels_per_pen"),
    (lambda: ink_centrelines(BOLD_C, pixels_per_pen=6.0), TypeError, "pixels_per_pen"),
    (lambda: ink_centrelines(BOLD_C, spur_length=-1.0), ValueError, "spur_length"),
    (lambda: ink_centrelines(BOLD_C, spur_length="1"), TypeError, "spur_length"),
    (lambda: ink_centrelines([BOLD_C]), TypeError, "element"),
    (lambda: ink_centrelines(BOLD_C, crossings=[[np.nan, 0.0]]), ValueError, "crossings"),
    (lambda: ink_centrelines(BOLD_C, crossings=[0.0, 1.0, 2.0]), ValueError, "crossings"),
    (lambda: overdrawn_fraction("c"), TypeError, "element"),
    (lambda: element_features([BOLD_C], 1.0, topology="skeleton"), ValueError, "topology"),
    (lambda: extremity_points(BOLD_C, topology=None), ValueError, "topology"),
])
def test_bad_arguments_name_the_parameter(call, error, match):
    with pytest.raises(error, match=match):
        call()


def _footprint_without_slits(polylines, pen):
    """The pen's footprint (shapely), its holes narrower than the pen filled as the ink reading fills them."""
    import shapely
    from shapely.geometry import LineString, Point, Polygon
    from shapely.ops import unary_union

    ink = unary_union([LineString(points).buffer(pen / 2) if len(set(points)) > 1 else Point(points[0]).buffer(pen / 2)
                       for points in polylines])
    slits = [Polygon(ring) for part in getattr(ink, "geoms", [ink]) for ring in part.interiors
             if shapely.maximum_inscribed_circle(Polygon(ring)).length <= pen / 2 + pen / 6]
    return unary_union([ink, *slits])


def test_centrelines_of_random_scribbles_stay_in_the_ink_and_repeat_bit_for_bit():
    """Property: for any scribble, every centreline point lies in the ink, and a rerun is identical."""
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st
    from shapely.geometry import Point

    coordinate = st.floats(-1.0, 1.0, allow_nan=False)
    polyline = st.lists(st.tuples(coordinate, coordinate), min_size=2, max_size=8)

    # derandomized, as the fuzz harness's CI profile: the same 40 scribbles on every run, so CI never fails on
    # an input no one can replay (1500 random scribbles passed once the one-pixel skeleton was handled)
    @settings(max_examples=40, database=None, deadline=None, derandomize=True,
              suppress_health_check=[HealthCheck.too_slow])
    @given(st.lists(polyline, min_size=1, max_size=4), st.floats(0.02, 0.3))
    def check(polylines, pen):
        element = Element(tuple(Stroke(np.array(points), pen) for points in polylines))
        first, second = ink_centrelines(element), ink_centrelines(element)
        assert [s.points.tobytes() for s in first.strokes] == [s.points.tobytes() for s in second.strokes]
        # slack: the Gaussian smoothing (a third of a pen) cuts the corner of a hairpin by up to half a pen
        ink = _footprint_without_slits(polylines, pen).buffer(0.6 * pen)
        for stroke in first.strokes:
            assert all(ink.covers(Point(p)) for p in stroke.points)

    check()
