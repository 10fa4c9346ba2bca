"""Hershey vector-font glyphs as :class:`~paperlib.geometry.Element` objects.

Source
------
The 32 fonts bundled with the PyPI package ``Hershey-Fonts`` (module
``HersheyFonts``), which embeds the glyph tables in its source; nothing is read
from disk or downloaded. The glyphs were digitised by A. V. Hershey at the U.S.
National Bureau of Standards and are in the public domain (see the notice in the
``HersheyFonts`` module). Each font maps 96 consecutive character codes starting at
U+0020 (space) to glyphs; for the symbol fonts (``astrology``, ``markers``,
``music``, ``japanese``, ...) the mapping of characters to symbols is arbitrary
(e.g. ``japanese`` holds 193 glyphs and gives even the space a kanji).

Coordinate frame
----------------
Hershey data are integer coordinates with y pointing *down*, the cap line at
``y = -12`` and the base line at ``y = 9`` for every bundled font. The glyphs
returned here are flipped to a y-up frame and normalised to cap-height units:

    x' = (x - left_margin) / (base_line - cap_line)
    y' = (base_line - y) / (base_line - cap_line)

so the glyph's left margin (its left side bearing, the pen position before the
glyph is typeset) is at ``x = 0``, the base line at ``y = 0`` and the cap line at
``y = 1``; descenders go below 0. One Hershey grid unit is ``1/21`` cap heights.
"""

from __future__ import annotations

from functools import lru_cache
from types import MappingProxyType

from paperlib.geometry import Element, Stroke

__all__ = ["DEFAULT_STROKE_WIDTH", "hershey_fonts", "hershey_glyph", "hershey_glyphs"]

#: Default pen width in cap-height units: one Hershey grid unit (1/21 cap height).
DEFAULT_STROKE_WIDTH = 1.0 / 21.0


@lru_cache(maxsize=1)
def _font_names() -> tuple[str, ...]:
    from HersheyFonts import HersheyFonts

    return tuple(sorted(HersheyFonts().default_font_names))


def hershey_fonts() -> list[str]:
    """Names of the fonts bundled with ``Hershey-Fonts``, sorted.

    Returns
    -------
    list of str
        E.g. ``["astrology", "cursive", ..., "futural", ..., "timesrb"]`` (32 names).
    """
    return list(_font_names())


def _check_font(font: str) -> None:
    if not isinstance(font, str) or font not in _font_names():
        raise ValueError(
            f"unknown Hershey font {font!r}; available fonts: {', '.join(_font_names())}"
        )


@lru_cache(maxsize=None)
def _font_strokes(font: str) -> MappingProxyType:
    """Map each character of ``font`` to its strokes, normalised to the y-up frame.

    The value is a tuple of strokes, each a tuple of ``(x, y)`` float pairs, so the
    cached mapping cannot be altered by callers.
    """
    from HersheyFonts import HersheyFonts

    loader = HersheyFonts()
    loader.load_default_font(font)
    base, cap = float(loader.render_options["base_line"]), float(loader.render_options["cap_line"])
    height = base - cap
    table = {}
    for char, glyph in loader.all_glyphs.items():
        left = glyph.left_offset
        table[char] = tuple(
            tuple(((x - left) / height, (base - y) / height) for x, y in stroke)
            for stroke in glyph.strokes
        )
    return MappingProxyType(table)


def _check_char(char, name: str = "char") -> None:
    if not isinstance(char, str) or len(char) != 1:
        raise ValueError(f"{name} must be a single character, got {char!r}")


def hershey_glyph(
    char: str,
    font: str = "futural",
    *,
    width: float = DEFAULT_STROKE_WIDTH,
    color: str = "#000000",
) -> Element:
    """One Hershey glyph as an element whose strokes are the glyph's pen strokes.

    Parameters
    ----------
    char : str
        A single character.
    font : str, optional
        One of :func:`hershey_fonts`; default ``"futural"`` (Futura-like sans serif,
        single-stroke, the Hershey "Roman Simplex").
    width : float, optional
        Pen width of every stroke, in cap-height units; default
        :data:`DEFAULT_STROKE_WIDTH` (one Hershey grid unit, 1/21).
    color : str, optional
        SVG colour of every stroke; default black.

    Returns
    -------
    Element
        Strokes in drawing order, in the y-up cap-height frame described in the
        module docstring (left margin at x = 0, base line at y = 0, cap line at
        y = 1). Closed strokes (e.g. ``"o"``) repeat their first point at the end,
        as in the Hershey data. ``name`` is ``"<font>:<char>"``, e.g.
        ``"futural:x"``.

    Raises
    ------
    ValueError
        If ``font`` is unknown, ``char`` is not a single character, the font has no
        glyph for it, or the glyph has no strokes (a space: an element needs at
        least one stroke).
    """
    _check_font(font)
    _check_char(char)
    strokes = _font_strokes(font).get(char)
    if strokes is None:
        raise ValueError(f"Hershey font {font!r} has no glyph for {char!r}")
    if not strokes:
        raise ValueError(f"Hershey glyph {char!r} in font {font!r} has no strokes (blank)")
    return Element(tuple(Stroke(s, width, color) for s in strokes), name=f"{font}:{char}")


def hershey_glyphs(
    text_or_chars,
    font: str = "futural",
    *,
    width: float = DEFAULT_STROKE_WIDTH,
    color: str = "#000000",
    skip_blank: bool = False,
) -> list[Element]:
    """The glyphs of several characters, one element each, in order.

    Each glyph is in its own frame (see :func:`hershey_glyph`); they are not
    typeset next to each other.

    Parameters
    ----------
    text_or_chars : str or iterable of str
        A string (one glyph per character) or an iterable of single characters.
    font, width, color
        As for :func:`hershey_glyph`.
    skip_blank : bool, optional
        If true, characters whose glyph has no strokes (spaces) are left out
        instead of raising; characters the font lacks still raise.

    Returns
    -------
    list of Element

    Raises
    ------
    ValueError
        As for :func:`hershey_glyph`.
    """
    _check_font(font)
    try:
        chars = list(text_or_chars)
    except TypeError:
        raise ValueError(f"text_or_chars must be a string or an iterable of characters, got {text_or_chars!r}") from None
    for index, char in enumerate(chars):
        _check_char(char, f"text_or_chars[{index}]")
    table = _font_strokes(font)
    if skip_blank:
        chars = [c for c in chars if c not in table or table[c]]
    return [hershey_glyph(c, font, width=width, color=color) for c in chars]
