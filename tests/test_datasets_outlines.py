"""DejaVu dingbat outlines: closed, CCW, simple, normalised, uniformly resampled."""

import numpy as np
import pytest
from matplotlib.ft2font import FT2Font
from shapely.geometry import LinearRing, Point, Polygon

from paperlib.datasets.outlines import (
    OUTLINE_CODEPOINTS,
    character_outline,
    font_path,
    glyph_outline,
    glyph_outlines,
    outline_names,
)
from paperlib.geometry import resample_closed_curve

NAMES = sorted(OUTLINE_CODEPOINTS)


def shoelace(points):
    x, y = points[:, 0], points[:, 1]
    return 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)


def edge_lengths(points):
    return np.hypot(*np.diff(np.vstack([points, points[:1]]), axis=0).T)


def test_names():
    assert outline_names() == NAMES
    assert len(NAMES) == 11
    assert {"shamrock", "floral_heart", "flower", "club", "spade", "heart"} <= set(NAMES)


def test_every_codepoint_is_in_the_bundled_font():
    charmap = FT2Font(font_path()).get_charmap()
    assert all(code in charmap for code in OUTLINE_CODEPOINTS.values())


@pytest.mark.parametrize("name", NAMES)
def test_outline_is_a_simple_ccw_ring(name):
    outline = glyph_outline(name)
    assert outline.ndim == 2 and outline.shape[1] == 2 and outline.dtype == np.float64
    assert outline.shape[0] > 100  # flattened Beziers, not a coarse polygon
    assert not np.array_equal(outline[0], outline[-1])  # no repeated end point
    assert np.all(edge_lengths(outline) > 0)
    assert shoelace(outline) > 0
    assert Polygon(outline).is_valid


@pytest.mark.parametrize("name", NAMES)
def test_outline_is_centred_and_scaled(name):
    outline = glyph_outline(name)
    centroid = Polygon(outline).centroid
    assert centroid.x == pytest.approx(0, abs=1e-9) and centroid.y == pytest.approx(0, abs=1e-9)
    assert np.ptp(outline, axis=0).max() == pytest.approx(1.0)
    assert np.abs(outline).max() <= 1.0


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("n_points", [32, 100, 257])
def test_resampled_outline(name, n_points):
    raw = glyph_outline(name)
    outline = glyph_outline(name, n_points)
    assert outline.shape == (n_points, 2) and not outline.flags.writeable
    assert shoelace(outline) > 0 and Polygon(outline).is_valid
    # The points lie on the original outline, at equal arc-length steps along it
    # from its first vertex.
    ring = LinearRing(raw)
    step = ring.length / n_points
    assert max(ring.distance(Point(p)) for p in outline) < 1e-9
    positions = np.array([ring.project(Point(p)) for p in outline])
    np.testing.assert_allclose(np.diff(positions), step, rtol=1e-6)
    # Chords never exceed the arc step; they are shorter where they cut a bend,
    # which at a fine step is rare.
    chords = edge_lengths(outline)
    assert chords.max() <= step * (1 + 1e-9)
    if n_points >= 100:
        assert chords.mean() > 0.95 * step


def test_resampling_known_answer_square():
    square = [(0, 0), (2, 0), (2, 2), (0, 2)]
    expected = [(0, 0), (1, 0), (2, 0), (2, 1), (2, 2), (1, 2), (0, 2), (0, 1)]
    np.testing.assert_allclose(resample_closed_curve(square, 8), expected, atol=1e-12)
    np.testing.assert_allclose(resample_closed_curve(square, 4), square, atol=1e-12)


def test_known_shapes():
    heart = glyph_outline("heart")
    assert heart[:, 0].min() == pytest.approx(-heart[:, 0].max(), abs=0.01)  # mirror symmetric
    assert heart[np.argmin(heart[:, 1]), 0] == pytest.approx(0, abs=0.01)  # tip on the axis
    # The florette's inner disc is a hole, not part of the outline: the region is
    # simply connected and its area is the whole flower's.
    assert Polygon(glyph_outline("florette")).area > 0.6


def test_all_outlines_and_determinism():
    outlines = glyph_outlines(n_points=64)
    assert list(outlines) == NAMES
    again = glyph_outlines(n_points=64)
    assert all(np.array_equal(outlines[k], again[k]) for k in NAMES)
    assert all(v.shape == (64, 2) for v in outlines.values())
    assert all(glyph_outlines()[k].shape == glyph_outline(k).shape for k in NAMES)


def test_outline_is_read_only():
    with pytest.raises(ValueError):
        glyph_outline("shamrock")[0, 0] = 3.0
    assert glyph_outline("shamrock")[0, 0] != 3.0


def test_unknown_name_lists_valid_names():
    with pytest.raises(ValueError, match="unknown outline 'maple'.*club.*shamrock"):
        glyph_outline("maple")


@pytest.mark.parametrize("bad", [0, 2, -5, 3.5, True, "10"])
def test_bad_n_points(bad):
    with pytest.raises(ValueError, match="n_points"):
        glyph_outline("heart", bad)


def test_zero_length_curve_cannot_be_resampled():
    with pytest.raises(ValueError, match="zero length"):
        resample_closed_curve([(1, 1), (1, 1), (1, 1)], 5)


@pytest.mark.parametrize("char", ["♔", "★", "✈", "A"])
def test_any_character_has_its_outer_outline(char):
    ring = character_outline(char)
    assert ring.ndim == 2 and ring.shape[1] == 2 and len(ring) >= 4 and not ring.flags.writeable
    assert shoelace(ring) > 0  # counter-clockwise
    assert np.ptp(ring, axis=0).max() == pytest.approx(1.0)
    assert LinearRing(ring).is_simple
    assert np.all(edge_lengths(ring) > 0)  # no repeated vertex


def test_named_outlines_are_their_characters_outlines():
    for name, codepoint in OUTLINE_CODEPOINTS.items():
        np.testing.assert_array_equal(character_outline(chr(codepoint)), glyph_outline(name))


@pytest.mark.parametrize("char", [" ", "\u200b", "ab", "", 5, "\U0010ffff"])
def test_characters_without_an_outline_are_refused(char):
    with pytest.raises(ValueError, match="char"):
        character_outline(char)
