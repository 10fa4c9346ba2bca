"""Hand-drawn-like glyph arrangements of several types, with truth labels (Hurtut 2009, section 2).

Hurtut et al. categorize the elements of an artist's drawing: elements of one perceptual type are
never exact copies, they vary in size, in orientation and in the wobble of the pen. These seeded
generators build such inputs from Hershey glyphs (:mod:`.hershey`) so that a categorization can be
scored against the types that generated it (adjusted Rand index), on the class of drawing a user
brings rather than on translated copies of one glyph.

A *type* is a glyph (a character of a Hershey font) drawn at a mean size. Every element of a type is
a fresh drawing of that glyph:

*Size.* The longer side of the upright glyph's box is ``size * (1 + size_spread) ** u`` with ``u``
uniform in ``[-1, 1]`` (default ``size_spread = 0.15``: sizes within about +-15%, areas within +-30%),
and the pen width scales with it (Hershey's default pen, 1/21 of the cap height).

*Rotation.* The glyph is turned by an angle uniform in ``[-rotation, rotation]`` degrees (default
180: any orientation, as scattered marks are drawn).

*Hand.* The strokes are densified (vertices kept, segments no longer than 1% of the size) and
displaced by two smooth fields, both in units of the element's own size:

- a *warp* of the glyph's plane, ``d(p) = jitter * size * sum_j a_j sin(2 pi f_j k_j . p / size +
  phi_j)`` per coordinate, three terms of random unit direction ``k_j``, frequency ``f_j`` in
  ``[0.3, 0.8]`` cycles per glyph, phase and signs, scaled to RMS ``jitter`` (default 0.04): the
  whole glyph leans, swells and bends as a hand draws it, while strokes that meet or cross in the
  glyph still meet or cross (a smooth map of the plane keeps joins, T-junctions and crossings);
- a *tremor* of each stroke across its direction, harmonics 2-6 of its arc length with amplitudes
  ``1/h``, RMS ``tremor`` (default 0.008), faded to zero at the stroke's ends so that joins stay
  joined.

So the types differ by their topology (extremities and crossings, which the hand preserves), their
elongation and their area, and the within-type variation is in everything else: exactly the
situation of section 2.1, where "not all the descriptive features participate to the perceptual
categorization process". What the hand does *not* do here is change the topology itself (an
overshooting corner that makes a crossing, a ring left open): such slips make a different glyph,
and a categorization is right to see them.

*Placement.* Elements are placed one by one at uniform random positions in the window (random
sequential adsorption), each kept only if its ink disc (the largest distance of its ink from its box
centre, pen included) does not meet an earlier one and lies inside the window; positions are the
box centres. The order of the types is shuffled, so labels and positions carry no order.

:func:`categorization_cases` lays out the test matrix used to judge ``categorize``: 2 to 5 types
differing in area, topology or elongation, at several relative sizes and counts, with a
single-type control, in fifteen families of glyphs: ``"main"``, the glyphs the method was designed
on; ``"held_out"``, other glyphs, partly of another Hershey font, checked once the method was fixed
(it failed, which led to the revision described in ``paperlib.arrangement.categorize``);
``"held_out_2"``, yet other glyphs, fixed before that revision and checked once after it;
``"held_out_3"``, a serif and another handwriting face, fixed before the next revision (the area's
box and histogram, gaps between values, ink-filled loops) and checked after it; and
``"held_out_4"``, Hershey's complex faces, fixed once that revision was final and checked once (it
failed, which led to judging crossings at the pen's scale); and ``"held_out_5"``, Times italic and
two double-stroke faces, fixed before that revision and checked once after it (it failed on Times
italic 'a', which led to reading crossings in and out of another stroke's ink as a touch); and
``"held_out_6"``, triplex, bold and blackletter faces, fixed before that last revision and checked
once after it (it failed on bold and triplex faces, which led to reading extremities and crossings
on the ink's centrelines when the drawing is made of parallel pen lines); and ``"held_out_7"``,
complex Greek and Cyrillic, Times Greek and three more blackletters, fixed before that revision and
checked once after it (it failed on the shallow crossing of a Greek alpha, which led to reading two
forks of the ink as one crossing where the pen's lines cross); and ``"held_out_8"``, simplex and
duplex Greek, a second Cyrillic and two more blackletters, fixed before that revision and checked
once after it (it failed on Greek pi and lambda, one extremity apart, which led to splitting a group
where two features agree, :func:`paperlib.arrangement.categorize`); and ``"held_out_9"``, symbol and
kana faces never used before (markers, symbols, a sans, kana, an italic), fixed before that revision
was written into the package and checked once after it; and ``"held_out_10"``, outlined polygons and
pictograms one corner apart and letters one stroke end apart, fixed before a witness beyond the paper's
features (the ink's length) was written into the package and checked once after it (it failed on a
looped script 'f' whose crossing the hand makes or unmakes, and on outlined polygons); and
``"held_out_11"``, looped cursive letters, serif digits and dingbats, fixed before the revision that
followed and checked once after it; and ``"held_out_12"``, Greek and looped cursive letters, digits
and weather pictograms, fixed before a dip test of the ink's length was written and checked once after
it (it failed on futural '2' and '5', 3 and 4 extremities in every copy); and ``"held_out_13"``,
capitals, Times letters, digits and pictograms, fixed after that and checked once with the method
unchanged; and ``"outlines"``, outer outlines of DejaVu
Sans characters (another tool's font, ``font="dejavu_outlines"``), whose first three cases led to
cutting extremity modes into unimodal runs and whose chess pieces and shapes were checked once after.

Written by hand: no library draws glyphs with a hand's variation.

References
----------
Hurtut, T., Landes, P.-E., Thollot, J., Gousseau, Y., Drouilhet, R., Coeurjolly, J.-F. (2009).
Appearance-guided synthesis of element arrangements by example. NPAR, section 2 (features and
categorization), Figures 3 and 9.
Julesz, B. (1986). Texton gradients: the texton theory revisited. Biological Cybernetics 54
(terminators and crossings as the discriminating features).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from paperlib._checks import as_generator, check_choice, integer_at_least, positive_number
from paperlib.geometry import Element, Stroke
from paperlib.pointprocess import PointPattern, Window

from .exemplars import OUTLINE_FONT, Exemplar, _frame, _glyph

__all__ = ["GlyphType", "categorization_cases", "drawn_glyph", "drawn_glyph_exemplar"]

#: Densified segments are no longer than this fraction of the glyph size.
_STEP = 0.01
#: Frequencies of the warp, cycles per glyph size.
_WARP_FREQUENCIES = (0.3, 0.8)
_WARP_TERMS = 3
_TREMOR_HARMONICS = np.arange(2, 7)
#: Placement gives up after this many rejected positions per element.
_MAX_TRIES = 2000


@dataclass(frozen=True)
class GlyphType:
    """One type of an arrangement: a glyph, its mean size and how many elements are drawn.

    Parameters
    ----------
    char : str
        A single character of the Hershey font.
    size : float
        Mean longer side of the glyph's upright box, window units (> 0).
    count : int
        Number of elements of this type (>= 1).
    name : str
        Category name (default ``"<char>@<size>"``).
    """

    char: str
    size: float
    count: int
    name: str = ""

    def __post_init__(self):
        if not isinstance(self.char, str) or len(self.char) != 1:
            raise ValueError(f"GlyphType.char must be a single character, got {self.char!r}")
        object.__setattr__(self, "size", positive_number(self.size, "GlyphType.size"))
        object.__setattr__(self, "count", integer_at_least(self.count, "GlyphType.count", 1))
        if not isinstance(self.name, str):
            raise TypeError(f"GlyphType.name must be a str, got {type(self.name).__name__}")
        if not self.name:
            object.__setattr__(self, "name", f"{self.char}@{self.size:g}")


def _fraction(value, name: str, high: float) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number in [0, {high}], got {value!r}") from None
    if not math.isfinite(number) or not 0.0 <= number <= high:
        raise ValueError(f"{name} must be a number in [0, {high}], got {value!r}")
    return number


def _densified(points: np.ndarray, step: float) -> np.ndarray:
    """The polyline with points inserted so that no segment is longer than ``step`` (vertices kept)."""
    if len(points) < 2:
        return points
    lengths = np.hypot(*np.diff(points, axis=0).T)
    pieces = np.maximum(np.ceil(lengths / step).astype(int), 1)
    parts = [a + np.linspace(0.0, 1.0, m, endpoint=False)[:, None] * (b - a)
             for a, b, m in zip(points[:-1], points[1:], pieces)]
    return np.vstack(parts + [points[-1:]])


def _warp(points: np.ndarray, size: float, jitter: float, rng: np.random.Generator) -> np.ndarray:
    """Smooth random displacement of the plane, RMS ``jitter * size`` per coordinate (module docstring)."""
    angle = rng.uniform(0.0, 2.0 * np.pi, _WARP_TERMS)
    frequency = rng.uniform(*_WARP_FREQUENCIES, _WARP_TERMS)
    wave = 2.0 * np.pi * frequency[:, None] * np.array([np.cos(angle), np.sin(angle)]).T / size  # (terms, 2)
    phase = rng.uniform(0.0, 2.0 * np.pi, (2, _WARP_TERMS))
    weight = rng.choice([-1.0, 1.0], (2, _WARP_TERMS)) * jitter * size * np.sqrt(2.0 / _WARP_TERMS)
    argument = points @ wave.T  # (n, terms)
    displacement = np.column_stack([np.sin(argument + phase[c]) @ weight[c] for c in range(2)])
    return points + displacement


def _tremor(points: np.ndarray, size: float, tremor: float, rng: np.random.Generator) -> np.ndarray:
    """Sideways wobble of one stroke, RMS ``tremor * size``, zero at its ends (module docstring)."""
    if len(points) < 3 or tremor == 0.0:
        return points
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])
    if arc[-1] <= 0.0:
        return points
    s = arc / arc[-1]
    amplitude = rng.normal(size=_TREMOR_HARMONICS.size) / _TREMOR_HARMONICS
    amplitude *= tremor * size / np.sqrt(np.sum(amplitude**2) / 2.0)
    phase = rng.uniform(0.0, 2.0 * np.pi, _TREMOR_HARMONICS.size)
    offset = np.sin(np.pi * s) * (np.sin(np.pi * np.outer(s, _TREMOR_HARMONICS) + phase) @ amplitude)
    tangent = np.gradient(points, arc, axis=0)
    norm = np.hypot(*tangent.T)
    normal = np.column_stack([-tangent[:, 1], tangent[:, 0]]) / np.where(norm > 0, norm, 1.0)[:, None]
    return points + offset[:, None] * normal


def drawn_glyph(char: str, size: float, *, angle: float = 0.0, jitter: float = 0.04, tremor: float = 0.008,
                font: str = "futural", rng=None) -> Element:
    """One hand-drawn-like copy of a Hershey glyph, box centre at the origin.

    Parameters
    ----------
    char : str
        A single character of ``font``.
    size : float
        Longer side of the upright glyph's box before the hand's displacement (> 0).
    angle : float, optional
        Rotation in degrees, counter-clockwise.
    jitter : float, optional
        RMS of the smooth warp, as a fraction of ``size``, in ``[0, 0.1]`` (default 0.04).
    tremor : float, optional
        RMS of each stroke's sideways tremor, as a fraction of ``size``, in ``[0, 0.03]`` (default
        0.008).
    font : str, optional
        Hershey font (default ``"futural"``), or ``"dejavu_outlines"``
        (:data:`~paperlib.datasets.exemplars.OUTLINE_FONT`): ``char`` is then any character of DejaVu
        Sans (``"♣"``, ``"♔"``, ``"★"``...), drawn as its outer outline, one closed pen line.
    rng : None, int or numpy.random.Generator
        Seed of the hand.

    Returns
    -------
    Element
        The glyph's strokes (pen width Hershey's default scaled to ``size``), named ``char``,
        translated so that the centre of its axis-aligned bounding box is the origin.

    Raises
    ------
    ValueError
        If ``char`` is not a single character, ``size`` is not positive, ``jitter`` or ``tremor``
        is out of range, or the glyph is empty.
    """
    if not isinstance(char, str) or len(char) != 1:
        raise ValueError(f"char must be a single character, got {char!r}")
    size = positive_number(size, "size")
    jitter = _fraction(jitter, "jitter", 0.1)
    tremor = _fraction(tremor, "tremor", 0.03)
    try:
        angle = float(angle)
    except (TypeError, ValueError):
        raise TypeError(f"angle must be a number of degrees, got {angle!r}") from None
    rng = as_generator(rng)
    template = _glyph(char, font, size).element
    theta = math.radians(angle)
    rotation = np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])
    strokes = [_densified(stroke.points, _STEP * size) for stroke in template.strokes]
    warp_rng, tremor_rng = rng.spawn(2)
    warped = np.split(_warp(np.vstack(strokes), size, jitter, warp_rng), np.cumsum([len(s) for s in strokes])[:-1])
    drawn = [_tremor(points, size, tremor, tremor_rng) @ rotation.T for points in warped]
    low = np.min([points.min(axis=0) for points in drawn], axis=0)
    high = np.max([points.max(axis=0) for points in drawn], axis=0)
    centre = (low + high) / 2.0
    return Element(tuple(Stroke(points - centre, s.width, s.color) for points, s in zip(drawn, template.strokes)),
                   name=char)


def _ink_radius(element: Element) -> float:
    pen = max(stroke.width for stroke in element.strokes)
    return float(np.hypot(*element.points.T).max() + pen / 2.0)


def _placed(elements, frame: Window, rng: np.random.Generator) -> np.ndarray:
    """Random sequential adsorption of the elements' ink discs in the frame; box centres, in order.

    The largest discs are placed first (as one draws the big shapes first), so that small ones fill
    the gaps and dense drawings still fit.
    """
    radii = np.array([_ink_radius(element) for element in elements])
    (x0, x1), (y0, y1) = frame.xrange, frame.yrange
    centres = np.full((len(elements), 2), np.inf)
    for i in np.argsort(-radii, kind="stable"):
        radius = radii[i]
        if x1 - x0 <= 2 * radius or y1 - y0 <= 2 * radius:
            raise ValueError(f"window {frame} is too small for an element of ink radius {radius:.4g}")
        for _ in range(_MAX_TRIES):
            point = rng.uniform([x0 + radius, y0 + radius], [x1 - radius, y1 - radius])
            if np.all(np.hypot(*(centres - point).T) >= radii + radius):
                centres[i] = point
                break
        else:
            raise ValueError(f"could not place element {i} of {len(elements)} without overlap after {_MAX_TRIES} "
                             f"tries: use a larger window, fewer or smaller glyphs")
    return centres


def _types(types) -> tuple:
    if isinstance(types, GlyphType):
        types = (types,)
    expected = "a sequence of GlyphType or (char, size, count[, name]) tuples"
    if isinstance(types, (str, bytes)) or not hasattr(types, "__iter__"):
        raise TypeError(f"types must be {expected}, got {types!r:.80}")
    checked = []
    for index, item in enumerate(types):
        if isinstance(item, GlyphType):
            checked.append(item)
            continue
        try:
            checked.append(GlyphType(*item))
        except TypeError as err:  # not a tuple, the wrong number of fields, or a field of the wrong type
            raise TypeError(f"types must be {expected}; types[{index}] = {item!r:.60} is not ({err})") from None
        except ValueError as err:  # a field out of range
            raise ValueError(f"types[{index}]: {err}") from None
    types = tuple(checked)
    if not types:
        raise ValueError("types must hold at least one glyph type, got none")
    names = [t.name for t in types]
    if len(set(names)) != len(names):
        raise ValueError(f"type names must be distinct (they name the categories), got {names}")
    return types


def drawn_glyph_exemplar(types, window: Window | None = None, *, size_spread: float = 0.15,
                         rotation: float = 180.0, jitter: float = 0.04, tremor: float = 0.008,
                         font: str = "futural", rng=None) -> Exemplar:
    """An arrangement of hand-drawn-like glyphs of several types, with the types as truth labels.

    Parameters
    ----------
    types : sequence of GlyphType or of (char, size, count[, name])
        The types: glyph, mean size (window units) and number of elements.
    window : Window, optional
        Rectangular frame (default the unit square); all the ink lies inside it.
    size_spread : float, optional
        Each element's size is the type's times ``(1 + size_spread) ** u``, ``u`` uniform in
        ``[-1, 1]``; in ``[0, 1]``, default 0.15.
    rotation : float, optional
        Rotations are uniform in ``[-rotation, rotation]`` degrees; in ``[0, 180]``, default 180.
    jitter, tremor, font
        The hand, as for :func:`drawn_glyph`.
    rng : None, int or numpy.random.Generator
        Seed: same seed, same arrangement bit for bit.

    Returns
    -------
    Exemplar
        ``labels`` index the types (``categories`` are their names); ``pattern`` holds the box
        centres with the labels as marks, in ``window``; ``truth`` records every parameter, the
        drawn sizes and angles.

    Raises
    ------
    TypeError, ValueError
        Malformed types or parameters out of range, or a window too small to place the glyphs
        without overlap.

    References
    ----------
    Hurtut et al. (2009), section 2 (elements of an artist's drawing vary within a category).
    """
    types = _types(types)
    frame = _frame(window)
    size_spread = _fraction(size_spread, "size_spread", 1.0)
    rotation = _fraction(rotation, "rotation", 180.0)
    rng = as_generator(rng)
    labels = rng.permutation(np.repeat(np.arange(len(types)), [t.count for t in types]))
    sizes = np.array([types[k].size for k in labels]) * (1.0 + size_spread) ** rng.uniform(-1.0, 1.0, labels.size)
    angles = rng.uniform(-rotation, rotation, labels.size)
    hands = rng.spawn(labels.size)
    shapes = [drawn_glyph(types[k].char, s, angle=a, jitter=jitter, tremor=tremor, font=font, rng=hand)
              for k, s, a, hand in zip(labels, sizes, angles, hands)]
    centres = _placed(shapes, frame, rng)
    elements = [shape.transformed(np.eye(2), centre) for shape, centre in zip(shapes, centres)]
    categories = tuple(t.name for t in types)
    labels.setflags(write=False)
    pattern = PointPattern(centres, frame, labels, categories)
    truth = {
        "process": "random sequential adsorption of ink discs",
        "types": [{"char": t.char, "size": t.size, "count": t.count, "name": t.name} for t in types],
        "size_spread": size_spread, "rotation": rotation, "jitter": jitter, "tremor": tremor, "font": font,
        "sizes": sizes.tolist(), "angles": angles.tolist(), "position": "bounding-box centre",
    }
    described = ", ".join(f"{t.count} {t.char!r} of size {t.size:g}" for t in types)
    description = (f"hand-drawn-like Hershey {font} glyphs: {described}; sizes within +-{size_spread:.0%}, rotations "
                   f"within +-{rotation:g} degrees, warp {jitter:g} and tremor {tremor:g} of the size")
    return Exemplar(elements, labels, categories, frame, pattern, truth, description)


# ============================================================================ the test matrix

#: The cases of :func:`categorization_cases`: name -> (what the types differ in, ((char, size, count), ...)).
#: Sizes are window units in the unit square (a size of 0.05 is a box of about 0.25% of the window).
MAIN_CASES = {
    "topology_2": ("extremities and crossings", (("o", 0.05, 40), ("x", 0.05, 40))),
    "topology_3_unbalanced": ("extremities and crossings", (("o", 0.05, 50), ("x", 0.05, 25), ("#", 0.05, 15))),
    "extremities_3": ("extremities", (("o", 0.05, 30), ("v", 0.05, 30), ("*", 0.05, 30))),
    "crossings_top_row": ("crossings only (Fig. 3 top row)", (("0", 0.06, 35), ("8", 0.06, 35))),
    "elongation_2": ("elongation", (("l", 0.07, 35), ("c", 0.07, 35))),
    "area_2x": ("area (sizes x2.5)", (("o", 0.03, 40), ("o", 0.075, 30, "O"))),
    "area_topology_3": ("area, then topology (Fig. 3 bottom row)",
                        (("o", 0.1, 20, "O"), ("x", 0.035, 40), ("o", 0.035, 40))),
    "mixed_4_few": ("topology and elongation, 15 each", (("o", 0.05, 15), ("x", 0.05, 15), ("#", 0.05, 15),
                                                          ("l", 0.05, 15))),
    "mixed_5": ("area, topology and elongation", (("o", 0.04, 30), ("x", 0.04, 30), ("v", 0.04, 25),
                                                   ("l", 0.06, 25), ("#", 0.09, 15))),
    "many_small_2": ("extremities, 120 tiny glyphs", (("c", 0.025, 60), ("z", 0.025, 60))),
    "control_single": ("one type (control: must stay one category)", (("x", 0.05, 60),)),
}
#: Held-out family: other glyphs, of another Hershey font (``scripts``, a handwriting face) for the
#: lower-case ones and futural capitals and digits; checked once the default method was fixed.
HELD_OUT_CASES = {
    "held_topology_2": ("extremities and crossings", (("c", 0.05, 40, "c"), ("x", 0.05, 40, "x"))),
    "held_capitals_3": ("extremities and crossings", (("H", 0.06, 30), ("8", 0.06, 30), ("0", 0.06, 30))),
    "held_area_3": ("area (three sizes)", (("e", 0.03, 30), ("e", 0.07, 25, "E"), ("e", 0.14, 12, "EE"))),
    "held_mixed_4": ("topology and elongation", (("w", 0.05, 25), ("+", 0.05, 25), ("l", 0.06, 25),
                                                  ("s", 0.05, 25))),
    "held_control_single": ("one type (control)", (("k", 0.05, 50),)),
}
#: Second held-out family, fixed after the first held-out check had failed (see the fig03 notebook)
#: and before the method was revised; checked once the revision was done.
HELD_OUT_2_CASES = {
    "held2_digits_3": ("topology and elongation", (("1", 0.06, 30), ("4", 0.06, 30), ("6", 0.06, 30))),
    "held2_letters_2": ("extremities and crossings", (("T", 0.05, 35), ("X", 0.05, 35))),
    "held2_area_2": ("area (sizes x2.7)", (("s", 0.03, 40), ("s", 0.08, 25, "S-big"))),
    "held2_mixed_5": ("area, topology and elongation", (("y", 0.05, 20), ("m", 0.05, 20), ("+", 0.05, 20),
                                                          ("S", 0.08, 20), ("1", 0.06, 20))),
    "held2_control_y": ("one type (control)", (("y", 0.05, 60),)),
    "held2_control_script_e": ("one type, a cursive glyph (control)", (("e", 0.05, 50),)),
}
#: Third held-out family, fixed before the revision of issue 27 (the area's box and histogram, gaps
#: between values, ink-filled loops) and checked after it: a serif face (``rowmans``) and another
#: handwriting face (``cursive``).
HELD_OUT_3_CASES = {
    "held3_area_2": ("area (sizes x2)", (("n", 0.035, 35), ("n", 0.07, 25, "N-big"))),
    "held3_area_3": ("area (three sizes)", (("a", 0.03, 30), ("a", 0.06, 25, "A2"), ("a", 0.12, 15, "A3"))),
    "held3_topology_3": ("extremities and crossings", (("O", 0.06, 30), ("X", 0.06, 30), ("C", 0.06, 30))),
    "held3_elongation_2": ("elongation", (("I", 0.07, 30), ("O", 0.07, 30))),
    "held3_mixed_4": ("area, topology and elongation", (("v", 0.05, 25), ("t", 0.05, 25), ("o", 0.04, 25),
                                                          ("L", 0.08, 20))),
    "held3_control_g": ("one type, a cursive glyph (control)", (("g", 0.05, 50),)),
}
#: Fourth held-out family, fixed once the revision checked on the third was final and checked once:
#: a complex serif face (``timesr``) and a complex script (``scriptc``).
HELD_OUT_4_CASES = {
    "held4_area_2": ("area (sizes x2.2)", (("h", 0.035, 35), ("h", 0.077, 25, "H-big"))),
    "held4_topology_3": ("extremities and crossings", (("c", 0.05, 30), ("t", 0.05, 30), ("o", 0.05, 30))),
    "held4_elongation_2": ("elongation", (("i", 0.07, 30), ("n", 0.07, 30))),
    "held4_mixed_4": ("area, topology and elongation", (("z", 0.05, 25), ("x", 0.05, 25), ("l", 0.07, 20),
                                                          ("O", 0.1, 15))),
    "held4_control_w": ("one type (control)", (("w", 0.05, 50),)),
    "held4_control_script_d": ("one type, a cursive glyph (control)", (("d", 0.05, 50),)),
}
#: Fifth held-out family, fixed after the fourth had failed and before the crossings were judged at the
#: pen's scale (issue 27); checked once that revision was final: Times italic (``timesi``), a
#: double-stroke sans (``futuram``) and a double-stroke serif (``rowmand``).
HELD_OUT_5_CASES = {
    "held5_area_2": ("area (sizes x2.3)", (("e", 0.035, 35), ("e", 0.08, 25, "E-big"))),
    "held5_topology_3": ("extremities and crossings", (("u", 0.05, 30), ("x", 0.05, 30), ("o", 0.05, 30))),
    "held5_elongation_2": ("elongation and topology", (("1", 0.07, 30), ("0", 0.07, 30))),
    "held5_mixed_4": ("area, topology and elongation", (("a", 0.05, 25), ("f", 0.06, 25), ("4", 0.05, 20),
                                                          ("Q", 0.1, 15))),
    "held5_control_m": ("one type (control)", (("m", 0.05, 50),)),
    "held5_control_italic_k": ("one type, an italic glyph (control)", (("k", 0.05, 50),)),
}
#: Sixth held-out family, fixed after the fifth had failed (Times italic 'a', whose bowl runs along its
#: stem) and before crossings in and out of another stroke's ink were read as a touch; checked once
#: after: Roman triplex (``rowmant``), Times bold and bold italic (``timesrb``, ``timesib``) and a
#: blackletter (``gothiceng``).
HELD_OUT_6_CASES = {
    "held6_area_2": ("area (sizes x2.1)", (("b", 0.035, 35), ("b", 0.075, 25, "B-big"))),
    "held6_topology_3": ("extremities and crossings", (("c", 0.05, 30), ("x", 0.05, 30), ("o", 0.05, 30))),
    "held6_elongation_2": ("elongation and topology", (("j", 0.07, 30), ("e", 0.07, 30))),
    "held6_mixed_4": ("area, topology and elongation", (("a", 0.05, 25), ("k", 0.05, 25), ("8", 0.05, 20),
                                                          ("W", 0.1, 15))),
    "held6_control_s": ("one type (control)", (("s", 0.05, 50),)),
    "held6_control_gothic_o": ("one type, a blackletter glyph (control)", (("o", 0.05, 50),)),
}
#: Seventh held-out family, fixed after the sixth had failed (bold and triplex faces) and before extremities
#: and crossings were read on the ink of drawings made of parallel pen lines; checked once after: complex
#: Greek (``greekc``), Cyrillic (``cyrillic``), Times Greek (``timesg``) and the blackletters ``gothitt``,
#: ``gothicger`` and ``gothgbt``.
HELD_OUT_7_CASES = {
    "held7_area_2": ("area (sizes x2.2)", (("d", 0.035, 35), ("d", 0.077, 25, "D-big"))),
    "held7_topology_3": ("extremities and crossings", (("o", 0.05, 30), ("x", 0.05, 30), ("c", 0.05, 30))),
    "held7_elongation_2": ("elongation and topology", (("1", 0.07, 30), ("o", 0.07, 30))),
    "held7_mixed_4": ("area, topology and elongation", (("a", 0.05, 25), ("k", 0.05, 25), ("w", 0.05, 20),
                                                          ("o", 0.1, 15))),
    "held7_control_m": ("one type, a blackletter glyph (control)", (("m", 0.05, 50),)),
    "held7_control_h": ("one type, a blackletter glyph (control)", (("h", 0.05, 50),)),
}
#: Eighth held-out family, fixed after the seventh had failed (a Greek alpha's shallow crossing lost on the
#: ink) and before the pen's crossings were used to join two forks of the ink; checked once after: simplex
#: and duplex Greek (``greeks``, ``greek``), Cyrillic complex (``cyrilc_1``) and the blackletters
#: ``gothicita`` and ``gothgrt``.
HELD_OUT_8_CASES = {
    "held8_area_2": ("area (sizes x2.1)", (("b", 0.035, 35), ("b", 0.075, 25, "B-big"))),
    "held8_topology_3": ("extremities and crossings", (("o", 0.05, 30), ("x", 0.05, 30), ("c", 0.05, 30))),
    "held8_elongation_2": ("elongation and topology", (("l", 0.07, 30), ("o", 0.07, 30))),
    "held8_mixed_4": ("area, topology and elongation", (("p", 0.05, 25), ("l", 0.05, 25), ("f", 0.06, 20),
                                                          ("o", 0.1, 15))),
    "held8_control_e": ("one type, a blackletter glyph (control)", (("e", 0.05, 50),)),
    "held8_control_m": ("one type (control)", (("m", 0.05, 50),)),
}
#: Ninth held-out family, fixed after the joint split of two agreeing features had been tried on the first eight
#: families and before it was written into the package; checked once after: the faces no family had used,
#: Hershey's ``markers``, ``symbolic``, ``meteorology`` (a sans), ``japanese`` (kana) and ``astrology`` (an
#: italic drawn in parallel pen lines).
HELD_OUT_9_CASES = {
    "held9_area_2": ("area (sizes x2.2)", (("h", 0.035, 35), ("h", 0.077, 25, "H-big"))),
    "held9_topology_3": ("extremities and crossings", (("a", 0.05, 30), ("h", 0.05, 30), ("i", 0.05, 30))),
    "held9_elongation_2": ("elongation and topology", (("s", 0.07, 30), ("n", 0.07, 30))),
    "held9_mixed_4": ("area, topology and elongation", (("p", 0.05, 25), ("l", 0.05, 25), ("f", 0.06, 20),
                                                          ("o", 0.1, 15))),
    "held9_mixed_markers_4": ("extremities and crossings", (("c", 0.05, 25), ("d", 0.05, 25), ("f", 0.05, 20),
                                                                  ("e", 0.05, 20))),
    "held9_control_club": ("one type, a pictogram (control)", (("f", 0.05, 50),)),
    "held9_control_k": ("one type, an italic in parallel pen lines (control)", (("k", 0.05, 50),)),
}
#: Drawings from another tool's font: outer outlines of DejaVu Sans characters (matplotlib's font,
#: :data:`~paperlib.datasets.exemplars.OUTLINE_FONT`) redrawn by the same hand. The suits, florettes and mixed
#: dingbats showed that extremity counts of two types can all stand above the uniform background, one
#: MM-mode, with a dip between them (which led to cutting extremity modes into unimodal runs); the chess
#: pieces and shapes were fixed before that change and checked once after it.
OUTLINE_CASES = {
    "outline_suits_3": ("extremities and elongation", (("♥", 0.05, 25), ("♣", 0.05, 25), ("♠", 0.05, 25))),
    "outline_florettes_3": ("extremities", (("✿", 0.05, 25), ("✾", 0.05, 25), ("☘", 0.05, 25))),
    "outline_mixed_4": ("extremities", (("♥", 0.05, 20), ("✽", 0.05, 20), ("❦", 0.05, 20), ("⚘", 0.05, 20))),
    "outline_chess_3": ("extremities and elongation", (("♔", 0.05, 25), ("♖", 0.05, 25), ("♙", 0.05, 25))),
    "outline_knight_bishop_2": ("extremities and elongation", (("♘", 0.05, 30), ("♗", 0.05, 30))),
    "outline_shapes_4": ("extremities and elongation", (("★", 0.05, 20), ("✈", 0.05, 20), ("✂", 0.05, 20),
                                                         ("☂", 0.05, 20))),
    "outline_control_club": ("one type (control)", (("♣", 0.05, 50),)),
    "outline_control_knight": ("one type (control)", (("♘", 0.05, 50),)),
}
#: Tenth held-out family, fixed before a witness beyond the paper's five features (the ink's length) was
#: written into the package and checked once after it: shapes one corner apart drawn as outlines (polygons,
#: DejaVu pictograms), letters one stroke end apart (futural 'P' and 'R', serif 'n', 'h' and 'm'), an
#: italic's two sizes, and controls of a pictogram, a complex script and a capital.
HELD_OUT_10_CASES = {
    "held10_polygons_4": ("extremities (corners)", (("▲", 0.05, 25), ("■", 0.05, 25), ("⬟", 0.05, 25),
                                                    ("⬢", 0.05, 25))),
    "held10_outline_mixed_3": ("extremities and elongation", (("⚓", 0.05, 25), ("☎", 0.05, 25),
                                                              ("♦", 0.05, 25))),
    "held10_letters_2": ("extremities", (("P", 0.06, 35), ("R", 0.06, 35))),
    "held10_letters_3": ("extremities and elongation", (("n", 0.05, 30), ("h", 0.05, 30), ("m", 0.05, 30))),
    "held10_area_2": ("area (sizes x2.3)", (("g", 0.035, 35), ("g", 0.08, 25, "G-big"))),
    "held10_control_anchor": ("one type, a pictogram's outline (control)", (("⚓", 0.05, 50),)),
    "held10_control_script_f": ("one type, a cursive glyph (control)", (("f", 0.05, 50),)),
    "held10_control_r": ("one type (control)", (("R", 0.05, 50),)),
}
#: Eleventh held-out family, fixed after the tenth had failed and before the revision it led to; checked once
#: after it: looped cursive letters and serif digits (crossings the hand may make or unmake), outlined
#: dingbats, a futural letter's two sizes, and controls of looped letters, a digit and a heart's outline.
HELD_OUT_11_CASES = {
    "held11_cursive_3": ("crossings and extremities", (("b", 0.05, 30), ("x", 0.05, 30), ("o", 0.04, 30))),
    "held11_digits_3": ("crossings and extremities", (("3", 0.06, 30), ("7", 0.06, 30), ("8", 0.06, 30))),
    "held11_outline_3": ("extremities", (("✚", 0.05, 25), ("❤", 0.05, 25), ("✦", 0.05, 25))),
    "held11_area_2": ("area (sizes x2.3)", (("k", 0.035, 35), ("k", 0.08, 25, "K-big"))),
    "held11_control_script_l": ("one type, a looped cursive glyph (control)", (("l", 0.06, 50),)),
    "held11_control_cursive_b": ("one type, a looped cursive glyph (control)", (("b", 0.05, 50),)),
    "held11_control_8": ("one type (control)", (("8", 0.06, 50),)),
    "held11_control_heart": ("one type, a pictogram's outline (control)", (("❤", 0.05, 50),)),
}
#: Twelfth held-out family, fixed after the eleventh had been checked and before the dip test of the ink's
#: length was written; checked once after it: simplex Greek letters, looped cursive letters, futural
#: digits, a serif letter's three sizes, outlined weather pictograms, and controls.
HELD_OUT_12_CASES = {
    "held12_greek_3": ("extremities and crossings", (("a", 0.05, 30), ("b", 0.06, 30), ("g", 0.05, 30))),
    "held12_cursive_3": ("extremities and elongation", (("h", 0.06, 30), ("k", 0.06, 30), ("n", 0.05, 30))),
    "held12_digits_2": ("extremities", (("2", 0.06, 35), ("5", 0.06, 35))),
    "held12_area_3": ("area (three sizes)", (("u", 0.03, 30), ("u", 0.06, 25, "U2"), ("u", 0.12, 15, "U3"))),
    "held12_outline_3": ("extremities and elongation", (("☁", 0.05, 25), ("☀", 0.05, 25),
                                                         ("❄", 0.05, 25))),
    "held12_control_cloud": ("one type, a pictogram's outline (control)", (("☁", 0.05, 50),)),
    "held12_control_script_h": ("one type, a looped cursive glyph (control)", (("h", 0.06, 50),)),
    "held12_control_greek_b": ("one type (control)", (("b", 0.06, 50),)),
    "held12_control_5": ("one type (control)", (("5", 0.06, 50),)),
}
#: Thirteenth held-out family, fixed after the twelfth had failed (futural '2' and '5', one extremity apart in
#: every copy) and checked once with the method unchanged (the revision tried after the twelfth, a final
#: reassignment of every element to the nearest category, was not kept): futural capitals, Times lower-case
#: letters, serif digits, outlined pictograms, a complex script's two sizes, and controls.
HELD_OUT_13_CASES = {
    "held13_capitals_3": ("extremities", (("E", 0.06, 30), ("F", 0.06, 30), ("K", 0.06, 30))),
    "held13_times_3": ("extremities and elongation", (("r", 0.05, 30), ("v", 0.05, 30), ("y", 0.05, 30))),
    "held13_digits_3": ("extremities and crossings", (("2", 0.06, 30), ("4", 0.06, 30), ("6", 0.06, 30))),
    "held13_outline_3": ("extremities and elongation", (("♪", 0.05, 25), ("⚑", 0.05, 25), ("✎", 0.05, 25))),
    "held13_area_2": ("area (sizes x2.3)", (("e", 0.035, 35), ("e", 0.08, 25, "E-big"))),
    "held13_control_e_capital": ("one type (control)", (("E", 0.06, 50),)),
    "held13_control_note": ("one type, a pictogram's outline (control)", (("♪", 0.05, 50),)),
    "held13_control_times_y": ("one type, a serif glyph (control)", (("y", 0.05, 50),)),
    "held13_control_4": ("one type (control)", (("4", 0.06, 50),)),
}
#: Fourteenth held-out family, fixed after the thirteenth had been checked (types one count apart in every copy
#: and nothing else a resolution apart) and before free ends and bends were tried as two counts (not kept: the
#: fig03 notebook), then checked once with the method unchanged (26 of 180 case-seeds below 0.9, fig03 notebook):
#: faces and glyphs no family had used, medium futural capitals
#: (``futuram``), complex script digits, double-stroke lower-case letters (``rowmand``), complex Greek sizes,
#: outlined pictograms, and controls.
HELD_OUT_14_CASES = {
    "held14_capitals_3": ("extremities", (("A", 0.06, 30), ("H", 0.06, 30), ("Z", 0.06, 30))),
    "held14_digits_3": ("extremities and crossings", (("1", 0.06, 30), ("3", 0.06, 30), ("9", 0.06, 30))),
    "held14_letters_3": ("extremities and elongation", (("c", 0.05, 30), ("s", 0.05, 30), ("z", 0.05, 30))),
    "held14_outline_3": ("extremities and elongation", (("☺", 0.05, 25), ("♫", 0.05, 25), ("✔", 0.05, 25))),
    "held14_area_2": ("area (sizes x2.3)", (("d", 0.035, 35), ("d", 0.08, 25, "D-big"))),
    "held14_control_a_capital": ("one type (control)", (("A", 0.06, 50),)),
    "held14_control_script_9": ("one type, a script digit (control)", (("9", 0.06, 50),)),
    "held14_control_smiley": ("one type, a pictogram's outline (control)", (("☺", 0.05, 50),)),
    "held14_control_z": ("one type, a double-stroke glyph (control)", (("z", 0.05, 50),)),
}
_FAMILIES = {"main": MAIN_CASES, "held_out": HELD_OUT_CASES, "held_out_2": HELD_OUT_2_CASES,
             "held_out_3": HELD_OUT_3_CASES, "held_out_4": HELD_OUT_4_CASES, "held_out_5": HELD_OUT_5_CASES,
             "held_out_6": HELD_OUT_6_CASES, "held_out_7": HELD_OUT_7_CASES, "held_out_8": HELD_OUT_8_CASES,
             "held_out_9": HELD_OUT_9_CASES, "held_out_10": HELD_OUT_10_CASES,
             "held_out_11": HELD_OUT_11_CASES, "held_out_12": HELD_OUT_12_CASES,
             "held_out_13": HELD_OUT_13_CASES, "held_out_14": HELD_OUT_14_CASES, "outlines": OUTLINE_CASES}
_HELD_OUT_FONTS = {"held_topology_2": "scripts", "held_area_3": "scripts", "held_mixed_4": "scripts",
                   "held2_control_script_e": "scripts", "held3_area_2": "rowmans", "held3_area_3": "cursive",
                   "held3_topology_3": "rowmans", "held3_elongation_2": "rowmans", "held3_mixed_4": "rowmans",
                   "held3_control_g": "cursive", "held4_area_2": "timesr", "held4_topology_3": "scriptc",
                   "held4_elongation_2": "timesr", "held4_mixed_4": "timesr", "held4_control_w": "timesr",
                   "held4_control_script_d": "scriptc", "held5_area_2": "timesi", "held5_topology_3": "futuram",
                   "held5_elongation_2": "rowmand", "held5_mixed_4": "timesi", "held5_control_m": "rowmand",
                   "held5_control_italic_k": "timesi", "held6_area_2": "rowmant", "held6_topology_3": "timesrb",
                   "held6_elongation_2": "rowmant", "held6_mixed_4": "timesib", "held6_control_s": "timesrb",
                   "held6_control_gothic_o": "gothiceng", "held7_area_2": "greekc", "held7_topology_3": "cyrillic",
                   "held7_elongation_2": "gothitt", "held7_mixed_4": "timesg", "held7_control_m": "gothicger",
                   "held7_control_h": "gothgbt", "held8_area_2": "greeks", "held8_topology_3": "gothicita",
                   "held8_elongation_2": "gothgrt", "held8_mixed_4": "greek", "held8_control_e": "gothicita",
                   "held8_control_m": "cyrilc_1", "held9_area_2": "meteorology", "held9_topology_3": "markers",
                   "held9_elongation_2": "symbolic", "held9_mixed_4": "japanese", "held9_mixed_markers_4": "markers",
                   "held9_control_club": "symbolic", "held9_control_k": "astrology",
                   "held10_polygons_4": OUTLINE_FONT, "held10_outline_mixed_3": OUTLINE_FONT,
                   "held10_letters_3": "rowmans", "held10_area_2": "timesi", "held10_control_anchor": OUTLINE_FONT,
                   "held10_control_script_f": "scriptc", "held11_cursive_3": "cursive", "held11_digits_3": "rowmans",
                   "held11_outline_3": OUTLINE_FONT, "held11_control_script_l": "scripts",
                   "held11_control_cursive_b": "cursive", "held11_control_8": "rowmans",
                   "held11_control_heart": OUTLINE_FONT, "held12_greek_3": "greeks", "held12_cursive_3": "scripts",
                   "held12_area_3": "rowmans", "held12_outline_3": OUTLINE_FONT, "held12_control_cloud": OUTLINE_FONT,
                   "held12_control_script_h": "scripts", "held12_control_greek_b": "greeks",
                   "held13_times_3": "timesr", "held13_digits_3": "rowmans", "held13_outline_3": OUTLINE_FONT,
                   "held13_area_2": "scriptc", "held13_control_note": OUTLINE_FONT, "held13_control_times_y": "timesr",
                   "held13_control_4": "rowmans", "held14_capitals_3": "futuram", "held14_digits_3": "scriptc",
                   "held14_letters_3": "rowmand", "held14_outline_3": OUTLINE_FONT, "held14_area_2": "greekc",
                   "held14_control_a_capital": "futuram", "held14_control_script_9": "scriptc",
                   "held14_control_smiley": OUTLINE_FONT, "held14_control_z": "rowmand"}


def _font_of(case: str) -> str:
    if case.startswith("outline_"):
        return OUTLINE_FONT
    return _HELD_OUT_FONTS.get(case, "futural")


def categorization_cases(family: str = "main", rng=None) -> dict:
    """The test matrix of categorizations: arrangements of 1 to 5 hand-drawn glyph types with truth.

    Parameters
    ----------
    family : {"main", "held_out", "held_out_2", ..., "held_out_14", "outlines"}
        ``"main"``: :data:`MAIN_CASES` (futural glyphs: 2-5 types differing in area, topology or
        elongation, at several relative sizes and counts, and a one-type control).
        ``"held_out"``: :data:`HELD_OUT_CASES`, other glyphs and another font (``scripts``).
        ``"held_out_2"``: :data:`HELD_OUT_2_CASES`, yet other glyphs.
        ``"held_out_3"``: :data:`HELD_OUT_3_CASES`, a serif and another handwriting face.
        ``"held_out_4"``: :data:`HELD_OUT_4_CASES`, a complex serif and a complex script face.
        ``"held_out_5"``: :data:`HELD_OUT_5_CASES`, Times italic and two double-stroke faces.
        ``"held_out_6"``: :data:`HELD_OUT_6_CASES`, triplex, bold and blackletter faces.
        ``"held_out_7"``: :data:`HELD_OUT_7_CASES`, complex Greek and Cyrillic, Times Greek and
        blackletters.
        ``"held_out_8"``: :data:`HELD_OUT_8_CASES`, simplex and duplex Greek, Cyrillic, blackletters.
        ``"held_out_9"``: :data:`HELD_OUT_9_CASES`, markers, symbols, a sans, kana and an italic.
        ``"held_out_10"``: :data:`HELD_OUT_10_CASES`, outlined polygons and pictograms, letters one
        stroke end apart.
        ``"held_out_11"``: :data:`HELD_OUT_11_CASES`, looped cursive letters, serif digits, dingbats.
        ``"held_out_12"``: :data:`HELD_OUT_12_CASES`, Greek and looped cursive letters, digits,
        weather pictograms.
        ``"held_out_13"``: :data:`HELD_OUT_13_CASES`, capitals, Times letters, digits, pictograms.
        ``"held_out_14"``: :data:`HELD_OUT_14_CASES`, medium capitals, script digits, double-stroke
        letters, pictograms.
        ``"outlines"``: :data:`OUTLINE_CASES`, outer outlines of DejaVu Sans dingbats and chess pieces.
    rng : None, int or numpy.random.Generator
        Seed; each case gets its own generator spawned from it, so a case does not change when
        another is added after it.

    Returns
    -------
    dict
        Case name -> (what the types differ in, :class:`~paperlib.datasets.Exemplar` from
        :func:`drawn_glyph_exemplar` with the default hand), in the order of the table.

    Raises
    ------
    ValueError
        If ``family`` is unknown.
    """
    check_choice(family, tuple(_FAMILIES), "family")
    table = _FAMILIES[family]
    children = as_generator(rng).spawn(len(table))
    return {name: (differs, drawn_glyph_exemplar(types, font=_font_of(name), rng=child))
            for (name, (differs, types)), child in zip(table.items(), children)}
