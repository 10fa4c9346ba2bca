"""Barla 2006 on drawings this project did not make: openclipart line art read from SVG, analysed,
synthesized, written back and read again (issue 19, item 5).

The fixtures are excerpts of two public-domain drawings from Debian's openclipart-svg package
(tests/fixtures/svg/README.md): 24 hand-drawn feathers (cubic Béziers in a translated group, Inkscape) and 40
window marks (straight polylines, Adobe Illustrator).
"""

import importlib.util
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import shapely

from paperlib.geometry import read_svg, svg_string, write_svg
from paperlib.geometry.svg import DEFAULT_TOLERANCE
from paperlib.strokepattern import analyze, synthesize, target_count

FIXTURES = Path(__file__).resolve().parent / "fixtures" / "svg"
WING = FIXTURES / "openclipart_wing_feathers.svg"
WINDOWS = FIXTURES / "openclipart_skyscraper_windows.svg"
SVG = "{http://www.w3.org/2000/svg}"


def strokes_of(elements):
    return [stroke for element in elements for stroke in element.strokes]


def assert_same_drawing(written, read):
    assert len(read) == len(written)
    for a, b in zip(written, read):
        assert a.name == b.name and len(a.strokes) == len(b.strokes)
        for s, t in zip(a.strokes, b.strokes):
            assert np.array_equal(s.points, t.points)  # bit for bit
            assert (s.width, s.color) == (t.width, t.color)


@pytest.fixture(scope="module")
def wing():
    return read_svg(WING)


@pytest.fixture(scope="module")
def windows():
    return read_svg(WINDOWS)


# ----------------------------------------------------------------------------- the fixtures and their provenance


@pytest.mark.parametrize("path", [WING, WINDOWS], ids=["wing", "windows"])
def test_fixture_is_small_and_carries_its_public_domain_licence(path):
    text = path.read_text(encoding="utf-8")
    assert path.stat().st_size < 16_000
    assert 'cc:license rdf:resource="http://web.resource.org/cc/PublicDomain"' in text
    assert path.name in (FIXTURES / "README.md").read_text(encoding="utf-8")


def test_excerpt_script_keeps_the_listed_shapes_byte_for_byte(tmp_path):
    spec = importlib.util.spec_from_file_location("openclipart_excerpt", FIXTURES / "openclipart_excerpt.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    keep = ["path13201", "path14219"]
    module.excerpt(WING, tmp_path / "two.svg", keep)
    source_lines = WING.read_text(encoding="utf-8").splitlines()
    kept = [line for line in (tmp_path / "two.svg").read_text(encoding="utf-8").splitlines() if "<path" in line]
    assert len(kept) == 2 and all(line in source_lines for line in kept)
    assert len(strokes_of(read_svg(tmp_path / "two.svg"))) == 2
    with pytest.raises(SystemExit, match="not found"):
        module.excerpt(WING, tmp_path / "bad.svg", ["no-such-id"])


# ----------------------------------------------------------------------------- reading, against the files' numbers


def test_wing_reads_as_24_feathers_within_the_flattening_tolerance(wing):
    strokes = strokes_of(wing)
    assert len(wing) == 1 and len(strokes) == 24  # one <g>: one element of 24 strokes
    assert {(s.width, s.color) for s in strokes} == {(1.0, "#000000")}
    group = next(g for g in ET.parse(WING).getroot().iter(SVG + "g") if g.get("transform"))
    shift = np.array(re.fullmatch(r"translate\(([-\d.]+),([-\d.]+)\)", group.get("transform")).groups(), float)
    t = np.linspace(0.0, 1.0, 4001)[:, None]
    bernstein = np.hstack([(1 - t) ** 3, 3 * (1 - t) ** 2 * t, 3 * (1 - t) * t ** 2, t ** 3])
    for node, stroke in zip(group.iter(SVG + "path"), strokes, strict=True):
        numbers = re.fullmatch(r"M (\S+),(\S+) C (\S+),(\S+) (\S+),(\S+) (\S+),(\S+) L (\S+),(\S+)",
                               node.get("d").strip())
        control = (np.array(numbers.groups(), float).reshape(5, 2) + shift) * [1.0, -1.0]
        truth = np.vstack([bernstein @ control[:4], control[4]])
        line = shapely.linestrings(stroke.points)
        assert shapely.distance(shapely.points(truth), line).max() <= DEFAULT_TOLERANCE
        assert shapely.distance(shapely.points(stroke.points), shapely.linestrings(truth)).max() <= 1e-6
        np.testing.assert_allclose(stroke.points[[0, -1]], control[[0, 4]], rtol=0, atol=1e-9)


def test_windows_read_as_the_files_numbers_exactly(windows):
    nodes = list(ET.parse(WINDOWS).getroot().iter(SVG + "polyline"))
    assert len(windows) == len(nodes) == 40
    for node, element in zip(nodes, windows):
        expected = np.array(re.findall(r"-?[\d.]+", node.get("points")), float).reshape(-1, 2) * [1.0, -1.0]
        (stroke,) = element.strokes
        assert element.name == node.get("id")
        assert np.array_equal(stroke.points, expected)
        assert (stroke.width, stroke.color) == (0.6, "#000000")


# ----------------------------------------------------------------------------- the pipeline and the round trip


@pytest.mark.parametrize("name", ["wing", "windows"])
def test_inputs_survive_write_and_read(name, tmp_path, request):
    drawing = request.getfixturevalue(name)
    assert_same_drawing(drawing, read_svg(write_svg(drawing, tmp_path / f"{name}.svg")))


def test_feathers_and_windows_are_one_element_each(wing, windows):
    assert len(analyze(wing, 3.0, dimension=1)) == 24
    assert len(analyze(windows, 4.0, dimension=2)) == 40


def test_wing_synthesis_round_trip(wing, tmp_path):
    analysis = analyze(wing, 3.0, dimension=1)
    target = np.array([(0.0, 0.0), (120.0, 20.0), (240.0, 0.0)])
    synthesis = synthesize(analysis, target, rings=2, rng=0)
    assert len(synthesis) == target_count(analysis, target)
    back = read_svg(write_svg(synthesis.elements, tmp_path / "wing.svg"))
    assert_same_drawing(synthesis.elements, back)
    rounded = read_svg(svg_string(synthesis.elements, decimals=2))
    error = max(np.abs(s.points - t.points).max() for s, t in zip(strokes_of(synthesis.elements), strokes_of(rounded)))
    assert error <= 0.005 + 1e-12
    # the round trip is stable: what was read back writes the same text again
    assert svg_string(back) == svg_string(synthesis.elements)


def test_windows_synthesis_round_trip(windows, tmp_path):
    analysis = analyze(windows, 4.0, dimension=2)
    synthesis = synthesize(analysis, (0.0, 150.0, 0.0, 150.0), rings=1, rng=1)
    assert len(synthesis) == target_count(analysis, (0.0, 150.0, 0.0, 150.0))
    path = write_svg(synthesis.elements, tmp_path / "windows.svg", background="white")
    back = read_svg(path)
    assert_same_drawing(synthesis.elements, back)
    assert {(s.width, s.color) for s in strokes_of(back)} == {(0.6, "#000000")}
    # read back, the synthesis analyses like the reference: every mark is one element
    assert len(analyze(back, 4.0, dimension=2)) == len(synthesis)
