"""paperlib.geometry.svg: reading SVG into elements, writing elements as SVG."""

import gzip
import os
import re
from pathlib import Path

import numpy as np
import pytest
import shapely
import svgelements
from scipy.spatial import cKDTree

from paperlib.geometry import Element, Stroke
from paperlib.geometry.svg import read_svg, svg_string, write_svg

FIXTURES = Path(__file__).parent / "fixtures" / "svg"
SVG_OPEN = '<svg xmlns="http://www.w3.org/2000/svg">'
TAU = 2 * np.pi


def svg(body: str, root: str = SVG_OPEN) -> str:
    return f"{root}{body}</svg>"


def only_stroke(elements) -> Stroke:
    assert len(elements) == 1 and len(elements[0].strokes) == 1
    return elements[0].strokes[0]


def random_elements(rng, count=5):
    colors = ["#000000", "#ff8000", "#11223344"]
    return [
        Element(
            tuple(
                Stroke(rng.normal(scale=10.0, size=(rng.integers(2, 9), 2)), rng.uniform(0.01, 2.0), colors[j % 3])
                for j in range(rng.integers(1, 4))
            ),
            name=f"glyph {i}" if i % 2 else "",
        )
        for i in range(count)
    ]


def deviation(polyline: np.ndarray, curve: np.ndarray) -> float:
    """Hausdorff distance between a polyline and a curve given by dense samples."""
    line = shapely.LineString(polyline)
    along = np.linspace(0.0, line.length, 20_001)
    on_polyline = shapely.get_coordinates(shapely.line_interpolate_point(line, along))
    to_polyline = shapely.distance(shapely.points(curve), line).max()
    to_curve = cKDTree(curve).query(on_polyline)[0].max()  # sample spacing << tolerance
    return float(max(to_polyline, to_curve))


# --------------------------------------------------------------------------- round trips


@pytest.mark.parametrize("y_up", [True, False])
def test_write_then_read_gives_back_the_same_elements_exactly(y_up):
    elements = random_elements(np.random.default_rng(1))
    assert read_svg(svg_string(elements, y_up=y_up), y_up=y_up) == elements


def test_round_trip_keeps_hard_numbers_names_and_repeated_vertices():
    points = [(0.1 + 0.2, -0.0), (1e-300, 1e300 / 3), (1 / 3, 2 / 3), (1 / 3, 2 / 3), (-5e-7, 123456789.123456789)]
    names = ['a & <b> "c"', "tab\there\nnewline", "ünïcode ✓"]
    elements = [Element((Stroke(points, 1 / 21, "#0a0b0c"),), name) for name in names]
    assert read_svg(svg_string(elements)) == elements


def test_round_trip_through_a_file_with_background_viewbox_and_size(tmp_path):
    elements = random_elements(np.random.default_rng(2))
    target = write_svg(
        elements,
        tmp_path / "sub" / "out.svg",
        width="120mm",
        height=80,
        viewbox=(-50, -50, 100, 100),
        background="#fff",
    )
    assert target == tmp_path / "sub" / "out.svg"
    assert read_svg(target) == elements  # the background rect is not an element
    assert read_svg(str(target)) == elements
    assert [p.name for p in target.parent.iterdir()] == ["out.svg"]  # no temporary left


def test_written_coordinates_are_mirrored_to_y_down_and_the_viewbox_too():
    stroke = Stroke([(1.0, 2.0), (3.0, 5.0)], 1.0)
    text = svg_string([Element((stroke,))], viewbox=(0, 0, 10, 8))
    assert 'points="1.0,-2.0 3.0,-5.0"' in text
    assert 'viewBox="0.0 -8.0 10.0 8.0"' in text
    assert np.array_equal(only_stroke(read_svg(text, y_up=False)).points, [(1.0, -2.0), (3.0, -5.0)])


def test_default_viewbox_is_the_bounds_of_the_strokes_with_half_their_widths():
    elements = [Element((Stroke([(0, 0), (10, 0)], 2.0),)), Element((Stroke([(5, 5), (5, 6)], 0.5),))]
    text = svg_string(elements)
    viewbox = [float(v) for v in re.search(r'viewBox="([^"]+)"', text).group(1).split()]
    assert viewbox == [-1.0, -6.25, 12.0, 7.25]  # x from 0 - 1 to 10 + 1, y from 0 - 1 to 6 + 0.25, mirrored
    assert 'width="12.0" height="7.25"' in text


def test_decimals_round_the_coordinates_only():
    stroke = Stroke([(1 / 3, 2 / 3), (1.0, -1 / 7)], 1 / 3)
    back = only_stroke(read_svg(svg_string([Element((stroke,))], decimals=2)))
    assert np.array_equal(back.points, [(0.33, 0.67), (1.0, -0.14)])
    assert back.width == 1 / 3


def test_a_one_point_stroke_is_written_as_a_dot_and_skipped_with_a_warning_on_reading():
    elements = [Element((Stroke([(1, 1)]),), "dot"), Element((Stroke([(0, 0), (1, 0)]),), "line")]
    text = svg_string(elements)
    assert 'points="1.0,-1.0 1.0,-1.0"' in text
    with pytest.warns(UserWarning, match=r"skipped 1 degenerate subpath.*'dot'"):
        assert read_svg(text) == elements[1:]


# --------------------------------------------------------------------------- flattening


CURVES = {
    "quadratic": "M 0 0 Q 30 40 60 0",
    "cubic": "M 0 0 C 10 50 50 -50 60 0",
    "cubic_cusp": "M 0 0 C 60 30 0 30 60 0",
    "arc_rotated_large": "M 0 0 A 30 10 25 1 1 40 5",
    "arc_half_circle": "M 0 0 A 30 30 0 0 1 60 0",
}


@pytest.mark.parametrize("tolerance", [1.0, 0.1, 0.01])
@pytest.mark.parametrize("name", list(CURVES))
def test_curves_are_flattened_within_the_tolerance_of_svgelements_exact_points(name, tolerance):
    path_data = CURVES[name]
    polyline = only_stroke(read_svg(svg(f'<path d="{path_data}" stroke="black"/>'), tolerance=tolerance, y_up=False))
    curve = svgelements.Path(path_data)[-1]
    exact = np.asarray(curve.npoint(np.linspace(0.0, 1.0, 100_001)))
    error = deviation(polyline.points, exact)
    assert error <= tolerance
    # And not needlessly fine: the |B''| bound is tight for quadratics and arcs, looser
    # for cubics whose B'' varies (about 0.2 for the cusp): within 0.1 of it everywhere.
    assert error >= 0.1 * tolerance
    # The vertices lie on the curve, the ends exactly at its ends.
    vertices_off = shapely.distance(shapely.points(polyline.points), shapely.LineString(exact)).max()
    assert vertices_off < 1e-3 * tolerance
    assert np.array_equal(polyline.points[[0, -1]], [list(curve.start), list(curve.end)])


def test_circle_is_closed_exactly_and_within_tolerance():
    stroke = only_stroke(read_svg(svg('<circle cx="3" cy="4" r="10" stroke="black"/>'), tolerance=0.05, y_up=False))
    assert np.array_equal(stroke.points[0], stroke.points[-1])
    assert not np.any(np.all(np.diff(stroke.points, axis=0) == 0, axis=1))  # no doubled closing vertex
    t = np.linspace(0, TAU, 100_001)
    assert deviation(stroke.points, np.column_stack([3 + 10 * np.cos(t), 4 + 10 * np.sin(t)])) <= 0.05


def test_skewed_and_scaled_circle_follows_the_transform_within_tolerance():
    doc = svg(
        '<g transform="translate(10 20) skewX(30)"><circle cx="5" cy="5" r="3" stroke="red" '
        'stroke-width="0.5" transform="scale(2 1)"/></g>'
    )
    stroke = only_stroke(read_svg(doc, tolerance=0.01, y_up=False))
    t = np.linspace(0, TAU, 100_001)
    x, y = 2 * (5 + 3 * np.cos(t)), 5 + 3 * np.sin(t)
    exact = np.column_stack([x + np.tan(np.radians(30)) * y + 10, y + 20])
    assert deviation(stroke.points, exact) <= 0.01
    assert stroke.width == pytest.approx(0.5 * np.sqrt(2))  # sqrt(|det|) of skew (1) times scale (2)


def test_tolerance_holds_in_user_units_under_a_magnifying_transform():
    doc = svg('<g transform="scale(100)"><path d="M 0 0 Q 0.3 0.4 0.6 0" stroke="black"/></g>')
    polyline = only_stroke(read_svg(doc, tolerance=0.1, y_up=False)).points
    exact = 100 * np.asarray(svgelements.Path("M 0 0 Q 0.3 0.4 0.6 0")[-1].npoint(np.linspace(0, 1, 100_001)))
    assert 0.025 <= deviation(polyline, exact) <= 0.1


# --------------------------------------------------------------------------- shapes, units, styles


def test_closed_shapes_repeat_their_first_point_at_the_end():
    doc = svg(
        '<rect x="1" y="2" width="3" height="4" stroke="black"/>'
        '<polygon points="0,0 5,0 5,5" stroke="black"/>'
        '<polygon points="0,0 5,0 5,5 0,0" stroke="black"/>'
        '<path d="M 0 0 L 1 0 L 1 1 Z" stroke="black"/>'
        '<polyline points="0,0 1,0 1,1" stroke="black"/>'
    )
    rect, triangle, closed_triangle, path, polyline = (e.strokes[0].points for e in read_svg(doc, y_up=False))
    assert np.array_equal(rect, [(1, 2), (4, 2), (4, 6), (1, 6), (1, 2)])
    assert np.array_equal(triangle, [(0, 0), (5, 0), (5, 5), (0, 0)])
    assert np.array_equal(closed_triangle, triangle)  # an explicit last vertex is not doubled
    assert np.array_equal(path, [(0, 0), (1, 0), (1, 1), (0, 0)])
    assert np.array_equal(polyline, [(0, 0), (1, 0), (1, 1)])  # open stays open


def test_each_subpath_is_a_stroke_and_a_segment_after_close_starts_a_new_one():
    element = read_svg(svg('<path d="M 0 0 L 1 1 M 5 5 L 6 6 L 6 7 Z L 9 9" stroke="black"/>'), y_up=False)[0]
    assert [s.points.tolist() for s in element.strokes] == [
        [[0, 0], [1, 1]],
        [[5, 5], [6, 6], [6, 7], [5, 5]],
        [[5, 5], [9, 9]],
    ]


def test_coordinates_are_in_the_root_user_space_whatever_the_viewport():
    root = '<svg xmlns="http://www.w3.org/2000/svg" width="210mm" height="297mm" viewBox="-10 -20 105 148.5">'
    stroke = only_stroke(read_svg(svg('<line x1="1.5" y1="2.5" x2="3" y2="4" stroke="black"/>', root), y_up=False))
    assert np.array_equal(stroke.points, [(1.5, 2.5), (3, 4)])
    assert stroke.width == 1.0


def test_lengths_with_units_are_resolved_at_96_user_units_per_inch():
    stroke = only_stroke(
        read_svg(svg('<line x1="0" y1="0" x2="1in" y2="0" stroke="black" stroke-width="0.5in"/>'), y_up=False)
    )
    assert np.array_equal(stroke.points, [(0, 0), (96, 0)])
    assert stroke.width == pytest.approx(48)


def test_group_transforms_compose_and_scale_the_stroke_width():
    doc = svg(
        '<g transform="translate(100 0)"><g transform="scale(2)">'
        '<line x1="1" y1="1" x2="2" y2="1" stroke="black" stroke-width="3"/>'
        '<line x1="1" y1="1" x2="2" y2="1" stroke="black" stroke-width="3" vector-effect="non-scaling-stroke"/>'
        "</g></g>"
    )
    scaled, fixed = read_svg(doc, y_up=False)[0].strokes
    assert np.array_equal(scaled.points, [(102, 2), (104, 2)])
    assert (scaled.width, fixed.width) == (6.0, 3.0)


def test_colours_come_from_the_stroke_else_the_fill_and_invisible_shapes_are_skipped():
    doc = svg(
        '<line id="stroked" x1="0" y1="0" x2="1" y2="0" stroke="red" fill="blue"/>'
        '<rect id="filled" x="0" y="0" width="1" height="1"/>'
        '<rect id="zero-width" x="0" y="0" width="1" height="1" stroke="red" stroke-width="0" fill="#00ff00"/>'
        '<line id="translucent" x1="0" y1="0" x2="1" y2="0" stroke="#102030" stroke-opacity="0.5"/>'
        '<g id="current" color="#abcdef"><line x1="0" y1="0" x2="1" y2="0" stroke="currentColor"/></g>'
        '<rect id="invisible" x="0" y="0" width="1" height="1" fill="none"/>'
    )
    styles = {e.name: (e.strokes[0].color, e.strokes[0].width) for e in read_svg(doc)}
    assert styles == {
        "stroked": ("#ff0000", 1.0),
        "filled": ("#000000", 1.0),  # SVG's initial fill is black
        "zero-width": ("#00ff00", 1.0),
        "translucent": ("#10203080", 1.0),
        "current": ("#abcdef", 1.0),
    }


# --------------------------------------------------------------------------- grouping


def test_grouping_rule_on_an_inkscape_style_document():
    elements = read_svg(FIXTURES / "inkscape_layers.svg", y_up=False)
    assert [(e.name, len(e.strokes)) for e in elements] == [("flower", 2), ("wave", 1), ("", 1), ("hatch", 1)]
    flower, wave, tick, hatch = elements
    assert [s.color for s in flower.strokes] == ["#000000", "#000000"]  # circle stroke, stem fill
    assert np.array_equal(flower.strokes[1].points, [(20, 25), (20, 35)])  # nested group merged, moved
    assert np.array_equal(tick.strokes[0].points, [(90, 40), (90, 43)])  # <use> placed at x, y
    assert (tick.strokes[0].color, hatch.strokes[0].color, hatch.strokes[0].width) == ("#008000", "#808080", 2.0)
    assert wave.strokes[0].width == 0.5 and len(wave.strokes[0]) > 2


def test_without_groups_each_shape_is_an_element():
    doc = svg('<line id="a" x1="0" y1="0" x2="1" y2="0" stroke="black"/><circle id="b" r="1" stroke="black"/>')
    assert [e.name for e in read_svg(doc)] == ["a", "b"]


def test_a_lone_group_of_shapes_is_one_element_but_a_lone_wrapper_of_groups_is_a_layer():
    line = '<line x1="0" y1="0" x2="1" y2="0" stroke="black"/>'
    lone = read_svg(svg(f'<g id="only">{line}{line}</g>'))
    assert [(e.name, len(e)) for e in lone] == [("only", 2)]
    wrapped = read_svg(
        svg(f'<g id="wrap" transform="translate(5 0)"><g id="x">{line}</g>{line}<g id="y">{line}</g></g>')
    )
    assert [e.name for e in wrapped] == ["x", "", "y"]
    assert wrapped[0].strokes[0].points[0, 0] == 5.0  # the wrapper's transform applies


def test_nested_groups_merge_into_their_top_level_group():
    line = '<line x1="0" y1="0" x2="1" y2="0" stroke="black"/>'
    doc = svg(f'<g id="a">{line}<g id="inner"><g>{line}{line}</g></g></g><g id="b">{line}</g>')
    assert [(e.name, len(e)) for e in read_svg(doc)] == [("a", 3), ("b", 1)]


def test_reads_gzip_compressed_svgz_and_bytes(tmp_path):
    text = svg('<line x1="0" y1="0" x2="1" y2="0" stroke="black"/>')
    (tmp_path / "d.svgz").write_bytes(gzip.compress(text.encode()))
    assert read_svg(tmp_path / "d.svgz") == read_svg(text.encode()) == read_svg(text)


# --------------------------------------------------------------------------- bad input: reading


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("<svg><line></svg>", "not well-formed XML"),
        (b"", "not well-formed XML"),
        ("  ", "empty string"),
        ('<html><svg xmlns="http://www.w3.org/2000/svg"/></html>', r"root element is <html>"),
        (svg('<path id="p7" d="M 0 0 L x y" stroke="black"/>'), r"<path id='p7'> has invalid path data"),
        (svg("", '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 a b">'), "viewBox"),
        (svg(""), "no drawable element"),
        (svg('<rect width="1" height="1" fill="none"/><text>hi</text>'), "no drawable element"),
    ],
)
def test_malformed_or_empty_documents_raise_a_clear_value_error(text, message):
    with pytest.raises(ValueError, match=message):
        read_svg(text)


def test_a_document_of_degenerate_paths_warns_then_raises():
    with pytest.warns(UserWarning, match="skipped 2 degenerate"):
        with pytest.raises(ValueError, match=r"no drawable element.*2 degenerate"):
            read_svg(svg('<path d="M 5 5 Z M 3 3" stroke="black"/><path d="M 1 1 L 1 1 Z" stroke="black"/>'))


def test_a_bare_moveto_draws_nothing_and_is_dropped_silently(recwarn):
    element = read_svg(svg('<path d="M 9 9 M 0 0 L 1 1 M 5 5" stroke="black"/><polyline points="3,3"/>'))[0]
    assert [s.points.tolist() for s in element.strokes] == [[[0, 0], [1, -1]]]
    assert not recwarn.list


def test_missing_file_and_wrong_types():
    with pytest.raises(FileNotFoundError, match="no SVG file"):
        read_svg("/nonexistent/drawing.svg")
    with pytest.raises(TypeError, match="SVG file name or SVG text"):
        read_svg(42)


@pytest.mark.parametrize("tolerance", [0, -1, np.nan, np.inf, "fine", True])
def test_bad_tolerance(tolerance):
    with pytest.raises(ValueError, match="tolerance"):
        read_svg(svg('<line x1="0" y1="0" x2="1" y2="0" stroke="black"/>'), tolerance=tolerance)


def test_a_tolerance_far_too_small_for_the_curve_is_refused_rather_than_exhausting_memory():
    with pytest.raises(ValueError, match="larger tolerance"):
        read_svg(svg('<circle r="1e6" stroke="black"/>'), tolerance=1e-9)


# --------------------------------------------------------------------------- bad input: writing


LINE = Element((Stroke([(0, 0), (1, 1)]),))


@pytest.mark.parametrize(
    ("elements", "options", "error", "message"),
    [
        (LINE, {}, TypeError, "wrap it in a list"),
        ([LINE, LINE.strokes[0]], {}, TypeError, r"elements\[1\] is a Stroke"),
        (5, {}, TypeError, "sequence of Element"),
        ([], {}, ValueError, "no elements to draw"),
        ([LINE], {"viewbox": (0, 0, 0, 1)}, ValueError, "viewbox"),
        ([LINE], {"viewbox": (0, 0, 1)}, ValueError, "viewbox"),
        ([LINE], {"width": -3}, ValueError, "width must be a positive"),
        ([LINE], {"height": "12 furlongs"}, ValueError, "height must be a positive"),
        ([LINE], {"width": "0mm"}, ValueError, "width must be a positive"),
        ([LINE], {"decimals": -1}, ValueError, "decimals"),
        ([Element(LINE.strokes, "bad\x00name")], {}, ValueError, "character XML cannot represent"),
    ],
)
def test_bad_input_to_the_writer(tmp_path, elements, options, error, message):
    target = tmp_path / "out.svg"
    target.write_text("previous")
    with pytest.raises(error, match=message):
        write_svg(elements, target, **options)
    assert target.read_text() == "previous"
    assert os.listdir(tmp_path) == ["out.svg"]


def test_an_empty_drawing_needs_a_viewbox():
    text = svg_string([], viewbox=(0, 0, 10, 10))
    with pytest.raises(ValueError, match="no drawable element"):
        read_svg(text)


def test_a_failure_while_writing_leaves_the_previous_file_and_no_temporary(tmp_path, monkeypatch):
    target = tmp_path / "out.svg"
    target.write_text("previous")

    def failing_replace(source, destination):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", failing_replace)
    with pytest.raises(OSError, match="disk full"):
        write_svg([LINE], target)
    assert target.read_text() == "previous"
    assert os.listdir(tmp_path) == ["out.svg"]
