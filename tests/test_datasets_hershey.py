"""Hershey glyph loader: known stroke counts, frame, immutability, errors."""

import numpy as np
import pytest

from paperlib.datasets.hershey import (
    DEFAULT_STROKE_WIDTH,
    hershey_fonts,
    hershey_glyph,
    hershey_glyphs,
)
from paperlib.geometry import Element, Stroke

UNIT = 1.0 / 21.0  # one Hershey grid unit in cap heights


def test_font_list_is_sorted_and_complete():
    fonts = hershey_fonts()
    assert fonts == sorted(fonts)
    assert len(fonts) == 32
    assert {"futural", "futuram", "timesr", "scripts", "gothiceng"} <= set(fonts)


def test_font_list_is_a_fresh_copy():
    hershey_fonts().clear()
    assert "futural" in hershey_fonts()


@pytest.mark.parametrize(
    "char, n_strokes",
    [("o", 1), ("x", 2), ("+", 2), ("-", 1), ("i", 2), ("j", 2), (".", 1), ("A", 3), ("B", 3), ("8", 1), ("%", 3)],
)
def test_futural_stroke_counts(char, n_strokes):
    assert len(hershey_glyph(char)) == n_strokes


def test_closed_and_open_strokes():
    (ring,) = hershey_glyph("o").strokes
    assert np.array_equal(ring.points[0], ring.points[-1])
    assert len(ring) == 17
    for stroke in hershey_glyph("x"):
        assert len(stroke) == 2  # two straight diagonals
    dot, stem = hershey_glyph("i").strokes
    assert np.array_equal(dot.points[0], dot.points[-1])  # the dot is a small closed diamond
    assert len(stem) == 2


def test_frame_is_y_up_in_cap_height_units():
    xmin, ymin, xmax, ymax = hershey_glyph("A").bounds()
    assert ymin == pytest.approx(0.0) and ymax == pytest.approx(1.0)  # base line .. cap line
    dot, stem = hershey_glyph("i").strokes
    assert dot.points[:, 1].min() > stem.points[:, 1].max()  # the dot is above the stem
    assert hershey_glyph("j").bounds()[1] < 0  # descender below the base line
    assert hershey_glyph("x").bounds()[3] == pytest.approx(14 * UNIT)  # x-height
    (bar,) = hershey_glyph("-").strokes
    assert np.allclose(bar.points, [[4 * UNIT, 9 * UNIT], [22 * UNIT, 9 * UNIT]])


def test_origin_is_left_margin():
    # 'o' has left margin -9 and spans x = -6 .. 7 in Hershey units.
    xmin, _, xmax, _ = hershey_glyph("o").bounds()
    assert xmin == pytest.approx(3 * UNIT) and xmax == pytest.approx(16 * UNIT)


def test_element_metadata_and_defaults():
    glyph = hershey_glyph("x", "timesr")
    assert isinstance(glyph, Element) and glyph.name == "timesr:x"
    assert all(isinstance(s, Stroke) for s in glyph)
    assert all(s.width == pytest.approx(DEFAULT_STROKE_WIDTH) for s in glyph)
    assert all(s.color == "#000000" for s in glyph)
    styled = hershey_glyph("x", width=0.1, color="red")
    assert {s.width for s in styled} == {0.1} and {s.color for s in styled} == {"red"}


def test_points_are_read_only_and_calls_deterministic():
    first, second = hershey_glyph("g"), hershey_glyph("g")
    assert first == second
    with pytest.raises(ValueError):
        first.strokes[0].points[0, 0] = 5.0
    assert hershey_glyph("g") == second


def test_every_printable_ascii_glyph_loads():
    for code in range(33, 127):
        glyph = hershey_glyph(chr(code))
        assert all(len(stroke) >= 2 for stroke in glyph), chr(code)


def test_glyphs_convenience():
    glyphs = hershey_glyphs("oxo")
    assert [g.name for g in glyphs] == ["futural:o", "futural:x", "futural:o"]
    assert glyphs[0] == glyphs[2]
    assert [len(g) for g in hershey_glyphs(["+", "-"], font="rowmans")] == [2, 1]
    assert [g.name for g in hershey_glyphs("a b", skip_blank=True)] == ["futural:a", "futural:b"]


@pytest.mark.parametrize("bad", [" ", "\u00e9", "ab", "", 5])
def test_bad_characters_raise(bad):
    with pytest.raises(ValueError, match=repr(bad) if isinstance(bad, str) and bad else "single"):
        hershey_glyph(bad)


def test_space_is_rejected_by_glyphs_unless_skipped():
    with pytest.raises(ValueError, match="no strokes"):
        hershey_glyphs("a b")
    with pytest.raises(ValueError, match="no glyph"):
        hershey_glyphs("a\u00e9", skip_blank=True)
    with pytest.raises(ValueError, match="iterable of characters"):
        hershey_glyphs(5)
    with pytest.raises(ValueError, match="single character"):
        hershey_glyphs(["ab"])


def test_unknown_font_lists_available_fonts():
    with pytest.raises(ValueError, match="unknown Hershey font 'nope'.*futural"):
        hershey_glyph("x", "nope")
    with pytest.raises(ValueError, match="timesr"):
        hershey_glyphs("x", font="Futural")
