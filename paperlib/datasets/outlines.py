"""Closed leaf, flower and card-suit outlines from the DejaVu Sans font.

Source
------
Glyph outlines of ``DejaVuSans.ttf``, the font bundled with matplotlib (found
through :func:`matplotlib.get_data_path`; nothing is downloaded). Licence: the
Bitstream Vera Fonts licence (fonts (c) 2003 Bitstream, Inc.; DejaVu changes in the
public domain), see ``fonts/ttf/LICENSE_DEJAVU`` in matplotlib's data directory. It
permits reproducing and modifying the glyph designs.

Eleven outlines (the "leaves" class of shapes with large-scale structure):

=========================  ======  ==========================================
name                       code    Unicode name
=========================  ======  ==========================================
club                       U+2663  BLACK CLUB SUIT
eight_petalled_florette    U+2741  EIGHT PETALLED OUTLINED BLACK FLORETTE
floral_heart               U+2766  FLORAL HEART
florette                   U+273F  BLACK FLORETTE
flower                     U+2698  FLOWER
heart                      U+2665  BLACK HEART SUIT
rotated_floral_heart       U+2767  ROTATED FLORAL HEART BULLET
shamrock                   U+2618  SHAMROCK
six_petalled_florette      U+273E  SIX PETALLED BLACK AND WHITE FLORETTE
spade                      U+2660  BLACK SPADE SUIT
teardrop_asterisk          U+273D  HEAVY TEARDROP-SPOKED ASTERISK
=========================  ======  ==========================================

Only the outer boundary is kept: holes and inner details (the centre of the
florettes, the ring of the flower) are dropped. Left out: U+269C FLEUR-DE-LIS
(drawn as overlapping contours, so no single contour is its outline), U+2740
WHITE FLORETTE (same outer boundary as U+273F), U+2619 (a mirror image of U+2767)
and U+2764 HEAVY BLACK HEART (a second heart).

Construction
------------
The glyph is converted to polygons with :class:`matplotlib.textpath.TextPath`
(Bezier curves flattened by matplotlib at a text size of 1000, a few hundred
vertices per outline) and :meth:`~matplotlib.path.Path.to_polygons`. The outer
boundary is the polygon of largest area. It is returned as a closed curve without
a repeated end point, oriented counter-clockwise (positive shoelace area), with
the centroid of the enclosed region at the origin and scaled so that the longer
side of its bounding box is 1 (so every coordinate lies in [-1, 1]). Resampling
(``n_points``) happens after this normalisation and puts the points at equal arc
length along the flattened outline, starting at its first vertex; the resampled
points therefore lie on the same curve, inside the same bounding box.
"""

from __future__ import annotations

import os
from functools import lru_cache

import numpy as np

from paperlib.geometry.curves import MAX_RESAMPLE_POINTS
from paperlib.geometry import (
    drop_repeated_vertices,
    oriented_ccw,
    resample_closed_curve,
    ring_centroid,
    signed_area,
)

__all__ = ["outline_names", "glyph_outline", "glyph_outlines", "character_outline"]

OUTLINE_CODEPOINTS = {
    "club": 0x2663,
    "eight_petalled_florette": 0x2741,
    "floral_heart": 0x2766,
    "florette": 0x273F,
    "flower": 0x2698,
    "heart": 0x2665,
    "rotated_floral_heart": 0x2767,
    "shamrock": 0x2618,
    "six_petalled_florette": 0x273E,
    "spade": 0x2660,
    "teardrop_asterisk": 0x273D,
}

# Text size handed to TextPath: sets how finely matplotlib flattens the Beziers.
_FLATTEN_SIZE = 1000.0


def outline_names() -> list[str]:
    """Names of the available outlines, sorted (see the module docstring).

    Returns
    -------
    list of str
        The outline names, sorted.
    """
    return sorted(OUTLINE_CODEPOINTS)


def font_path() -> str:
    """Path of the ``DejaVuSans.ttf`` file bundled with matplotlib."""
    import matplotlib

    return os.path.join(matplotlib.get_data_path(), "fonts", "ttf", "DejaVuSans.ttf")


def _glyph_polygons(codepoint: int) -> list[np.ndarray]:
    from matplotlib.font_manager import FontProperties
    from matplotlib.ft2font import FT2Font
    from matplotlib.textpath import TextPath

    path = font_path()
    if codepoint not in FT2Font(path).get_charmap():
        raise RuntimeError(f"U+{codepoint:04X} is missing from {path}")
    if not chr(codepoint).isprintable() or chr(codepoint).isspace():
        return []  # nothing drawn (and matplotlib's TextPath fails on an empty path)
    text = TextPath((0, 0), chr(codepoint), size=_FLATTEN_SIZE, prop=FontProperties(fname=path))
    return text.to_polygons()


def _normalised(points: np.ndarray) -> np.ndarray:
    """Centroid at the origin, longer bounding-box side 1."""
    centred = points - ring_centroid(points)
    return centred / np.ptp(centred, axis=0).max()


def _outer_outline(name: str) -> np.ndarray:
    return _outer_boundary(OUTLINE_CODEPOINTS[name])


@lru_cache(maxsize=256)
def _outer_boundary(codepoint: int) -> np.ndarray:
    # Each polygon without its repeated end point and zero-length edges, counter-clockwise
    # (a zero-area polygon is left unreversed, which cannot matter: it never wins the max).
    polygons = _glyph_polygons(codepoint)
    rings = [oriented_ccw(drop_repeated_vertices(p)) for p in polygons if len(p) >= 4]
    if not rings:
        raise ValueError(f"U+{codepoint:04X} ({chr(codepoint)!r}) draws nothing in DejaVu Sans: it has no outline")
    outer = _normalised(max(rings, key=signed_area))
    outer.setflags(write=False)
    return outer


def character_outline(char: str) -> np.ndarray:
    """The outer boundary of any character of DejaVu Sans, as :func:`glyph_outline` gives the named ones.

    Parameters
    ----------
    char : str
        A single character that DejaVu Sans draws (letters, symbols, dingbats, chess pieces:
        ``"♔"``, ``"★"``, ``"✈"``...).

    Returns
    -------
    ndarray, shape (n, 2), float64, read-only
        matplotlib's flattening of the largest contour: counter-clockwise, no repeated end point,
        centroid of the enclosed region at the origin, longer bounding-box side 1. Holes and every
        other contour are dropped (an ``"i"``'s dot, an ``"o"``'s counter).

    Raises
    ------
    ValueError
        If ``char`` is not a single character, or DejaVu Sans has no glyph for it or draws nothing.
    """
    if not isinstance(char, str) or len(char) != 1:
        raise ValueError(f"char must be a single character, got {char!r}")
    try:
        return _outer_boundary(ord(char))
    except (RuntimeError, ValueError) as error:  # not in the font's character map, or drawn as nothing
        raise ValueError(f"char={char!r} has no outline: {error}") from None


def glyph_outline(name: str, n_points: int | None = None, *, max_points: int = MAX_RESAMPLE_POINTS) -> np.ndarray:
    """The outer boundary of one glyph as a closed counter-clockwise curve.

    Parameters
    ----------
    name : str
        One of :func:`outline_names`.
    n_points : int, optional
        If given (>= 3), resample to exactly this many points equally spaced in arc
        length along the outline (see :func:`paperlib.geometry.resample_closed_curve`).
        By default the vertices of matplotlib's flattening are returned (unevenly
        spaced: dense on curves, sparse on straight parts). Every outline stays a
        simple polygon for ``n_points >= 32`` (tested up to 1000); coarser
        resamplings may cut across thin parts (``floral_heart`` self-intersects at
        12 points).
    max_points : int, optional
        Budget: the largest ``n_points`` allowed (default
        :data:`paperlib.geometry.curves.MAX_RESAMPLE_POINTS`, 10**7).

    Returns
    -------
    ndarray, shape (n, 2), float64, read-only
        Counter-clockwise, no repeated end point, centroid of the enclosed region at
        the origin, longer bounding-box side 1 (see the module docstring).

    Raises
    ------
    ValueError
        If ``name`` is unknown or ``n_points`` is invalid.
    """
    if not isinstance(name, str) or name not in OUTLINE_CODEPOINTS:
        raise ValueError(f"unknown outline {name!r}: name must be one of {', '.join(outline_names())}")
    outline = _outer_outline(name)
    if n_points is None:
        return outline
    resampled = resample_closed_curve(outline, n_points, max_points=max_points)
    resampled.setflags(write=False)
    return resampled


def glyph_outlines(n_points: int | None = None, *, max_points: int = MAX_RESAMPLE_POINTS) -> dict[str, np.ndarray]:
    """All outlines, keyed by name in sorted order; see :func:`glyph_outline`.

    Parameters
    ----------
    n_points : int, optional
        If given (>= 3), resample every outline to exactly this many points equally spaced in
        arc length; by default the vertices of matplotlib's flattening (see :func:`glyph_outline`).
    max_points : int, optional
        Budget: the largest ``n_points`` allowed (default
        :data:`paperlib.geometry.curves.MAX_RESAMPLE_POINTS`, 10**7).

    Returns
    -------
    dict of str to ndarray
        ``{name: outline}`` for every name of :func:`outline_names`, in sorted order; each
        outline a read-only float64 array of shape (n, 2), as :func:`glyph_outline` returns.
    """
    return {name: glyph_outline(name, n_points, max_points=max_points) for name in outline_names()}
