"""Synthetic reference stroke patterns with known elements (Barla 2006's exemplars).

Barla et al. (2006) analyse and synthesize stroke patterns drawn by artists; we do not have those
drawings. These seeded generators draw SYNTHETIC stand-ins for them, stroke by stroke in the order a
user would draw, and return the ground truth that made them: which strokes form one element, the
element's designed parameters, and the clustering scale ``epsilon`` at which Barla's rules recover
exactly those elements.

=====================================  ======================================================================
generator                              what it draws (paper figure)
=====================================  ======================================================================
:func:`sketchy_hatching_exemplar`      curved near-vertical hatches, each drawn with 2-4 overlapping sketchy
                                       strokes or as two collinear dashes (Fig. 1, Fig. 2, Fig. 6 a)
:func:`jittered_hatching_exemplar`     straight vertical hatches, even spacing, random vertical offsets
                                       (Fig. 6 b)
:func:`gradient_hatching_exemplar`     single strokes whose orientation, length or pen width ramps
                                       linearly along the path (Fig. 6 c-e)
:func:`wave_hatching_exemplar`         single strokes whose orientation swings gradually back and forth
                                       (a stationary pattern of gradual changes, Fig. 6 c)
:func:`alternating_color_exemplar`     thick, slightly wavy brush strokes whose colours alternate along the
                                       path (Fig. 6 f)
:func:`bars_exemplar`                  straight bars in several directions in a region, parallel within
                                       patches (Fig. 7 a)
:func:`drops_exemplar`                 water drops (outline, sometimes a highlight inside), each ringed by six
                                       short hatches (Fig. 7 b)
:func:`flowers_exemplar`               flowers of five petal loops and a centre, one colour each, colours in
                                       horizontal bands (Fig. 7 c)
:func:`two_hatchings_exemplar`         two kinds of hatches in a checkerboard (Fig. 7 d)
:func:`irregular_exemplar`             small marks at clearly non-uniform (clustered) positions (Fig. 7 e)
=====================================  ======================================================================

Conventions shared by every generator
-------------------------------------
*Coordinates.* Plain ``(x, y)`` floats, y up. A 1D pattern is laid along the horizontal path from
``(0, 0)`` to ``(n_elements * spacing, 0)``; element ``i`` is designed at arc length
``(i + 0.5) * spacing`` (plus a small jitter where stated) and drawn left to right. A 2D pattern fills
the rectangle ``shapely.box(0, 0, width, height)``; its element centres come from a jittered hexagonal
(or, for the checkerboard, square) lattice, or from dart throwing for the irregular pattern, and keep
half a lattice spacing from the border, so every element lies inside the region. 2D elements are drawn
row by row, from the top row down, left to right in a row.

*Elements.* The strokes of one element are drawn one after the other; ``element_of_stroke`` numbers
the elements 0..n-1 in drawing order. ``params`` holds one entry per element: ``position`` the designed
centre (the centre of the element's PCA box for the symmetric shapes), ``arc`` its arc length along the
path (NaN in 2D), ``orientation`` its main direction in ``[0, pi)`` (a flower's: the direction of its
first petal; a drop's: its symmetry axis), ``length`` its extent along that direction (a flower's: its
diameter), ``thickness`` the pen width, ``color`` an SVG colour and ``kind`` a label
(``"hatch"``, ``"dashed-hatch"``, ``"brush"``, ``"bar"``, ``"drop"``, ``"flower"``, ``"A"``, ``"B"``,
``"mark"``). Stroke vertices never repeat consecutively (a closed loop ends on its first vertex).

*Epsilon.* Barla's clustering (section 2.2) fits each stroke with its PCA box and merges two elements
when their proximity (the smaller directed Hausdorff distance between the filled boxes) or their
continuation (the gap along an axis line of one box, when every corner of the other lies within
``epsilon / 2`` of that line) is below ``epsilon``. Each generator sets ``epsilon`` with a margin of two
on both sides: every link that binds an element's strokes measures at most ``epsilon / 2`` (sketchy
strokes hug each other, dashes are collinear with a short gap, petals overlap at the flower's heart,
a highlight nests inside its drop, an "A" hatch's strokes are close and parallel), while any two
strokes (and whole elements) of different elements measure at least ``2 epsilon`` on both measures.
Barla's greedy pass refits an element's box after each merge, so a flower's petals are joined through
the growing box rather than stroke to stroke; the wide, overlapping petal loops keep those links within
0.54 petal length, about half of epsilon. The spacings, sizes and jitters below were chosen for that
margin and checked over a hundred seeds: the greedy clustering recovers the truth at every scale from
0.6 to 1.5 epsilon. The distances are measured with the collinearity band of ``epsilon``; the band widens
with the scale, so at ``2 epsilon`` petals of neighbouring flowers that point at each other can link
(measured in the notebook ``barla2006_fig02_clustering``); the other generators keep the truth there.

*Randomness.* ``rng`` is ``None``, an ``int`` seed or a :class:`numpy.random.Generator`; a seed fixes
the exemplar bit for bit.

Written by hand: no library draws stroke patterns; geometry types come from :mod:`paperlib.geometry`.

References
----------
.. [1] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern Analysis and
   Synthesis", Computer Graphics Forum (Eurographics) 25(3), 2006: section 2.2 (clustering scale
   epsilon, proximity and continuation), Figures 1, 2, 6 and 7 (the reference patterns imitated here).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np
import shapely
from matplotlib.colors import to_hex

from paperlib._checks import as_generator, budget, check_budget, check_choice, positive_number
from paperlib.geometry import Stroke

__all__ = [
    "StrokePatternExemplar",
    "alternating_color_exemplar",
    "bars_exemplar",
    "drops_exemplar",
    "flowers_exemplar",
    "gradient_hatching_exemplar",
    "irregular_exemplar",
    "jittered_hatching_exemplar",
    "sketchy_hatching_exemplar",
    "two_hatchings_exemplar",
    "wave_hatching_exemplar",
]

#: Pen width of the thin (pen-and-ink) strokes.
PEN_WIDTH = 0.08
#: Default budget of every generator here (``max_elements``): the most elements of an exemplar, checked
#: before drawing (a region's count is estimated from its area; the 2D generators compare all pairs).
MAX_ELEMENTS = 5_000
#: 1D patterns: epsilon as a fraction of the spacing (neighbouring hatches are a spacing apart).
_EPSILON_1D = 0.2
#: Jitter of 1D element positions along the path, as a fraction of the spacing.
_ARC_JITTER = 0.05
#: 2D lattices: jitter radius as a fraction of the lattice spacing.
_LATTICE_JITTER = 0.05
#: Petal loops: half the angle a lobe spans at the heart, and how far (in petal lengths) it starts behind
#: the heart. Wide lobes that overlap at the heart keep Barla's greedy clustering within 0.54 petal length.
_PETAL_HALF_ANGLE = math.radians(80.0)
_PETAL_BACK = 0.4
#: Gradient ramps (first and last value) and the constants of the other parameters. Each ramp spans at least
#: 5 of the paper's thresholds for the measure that sees it (section 3.1): orientation 80 degrees = 8.9 sigma_par
#: (pi / 20); length ratio 8 = 5.1 steps of sigma_ov (1.5^5.1); thickness 0.70 = 5.7 sigma_sup (0.1 L, L = 1.22 the
#: mean contour length); colour RGB distance 1.06 = 7.1 sigma_col (0.15).
_GRADIENT_RANGES = {"orientation": (50.0, 130.0), "length": (0.5, 4.0), "thickness": (0.05, 0.75),
                    "color": (0.0, 1.0)}
_GRADIENT_CONSTANTS = {"orientation": 90.0, "length": 2.5, "thickness": PEN_WIDTH}
#: Length of the strokes of the thickness ramp: short, so that 0.1 L (sigma_sup) is small beside the ramp.
_THICKNESS_RAMP_LENGTH = 0.8
#: Pen width of the colour ramp's strokes (brush strokes, so the colour is visible).
_COLOR_RAMP_WIDTH = 0.25
_COLOR_RAMP_ENDS = ((0.85, 0.2, 0.1), (0.1, 0.2, 0.85))


@dataclass(frozen=True, eq=False)
class StrokePatternExemplar:
    """A synthetic reference stroke pattern with its ground-truth elements.

    Parameters
    ----------
    strokes : tuple of Stroke
        The pattern in drawing order.
    element_of_stroke : ndarray of int64, shape (n_strokes,)
        Ground-truth element of each stroke, elements numbered in the order of their first stroke.
    dimension : int
        1 (a pattern along a path) or 2 (a pattern in a region).
    path : ndarray, shape (m, 2), or None
        1D only: the polyline the elements were laid along, left to right.
    region : shapely.Polygon or None
        2D only: the region the element centres were drawn in.
    epsilon : float
        Clustering scale at which Barla's rules recover the truth (module docstring, *Epsilon*).
    params : dict of ndarray
        Per-element truth, each of length ``n_elements``: ``position`` (n, 2), ``arc`` (n,),
        ``orientation`` (n,) in [0, pi), ``length`` (n,), ``thickness`` (n,), ``color`` (n,) str,
        ``kind`` (n,) str.
    description : str
        What was drawn; always says that the pattern is synthetic.

    References
    ----------
    Barla et al. 2006, sections 2.1-2.2 (elements as clusters of strokes), Figures 6 and 7.
    """

    strokes: tuple
    element_of_stroke: np.ndarray
    dimension: int
    path: np.ndarray | None
    region: object | None
    epsilon: float
    params: dict
    description: str

    @property
    def n_elements(self) -> int:
        """Number of ground-truth elements."""
        return int(self.params["kind"].shape[0])


# --------------------------------------------------------------------------- argument checks


def _count(value, name: str, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def _between(value, name: str, low: float, high: float) -> float:
    number = positive_number(value, name, allow_zero=True)
    if not low <= number <= high:
        raise ValueError(f"{name} must lie in [{low:g}, {high:g}], got {value!r}")
    return number


def _colors(colors, name: str, minimum: int) -> tuple:
    if isinstance(colors, str):
        raise ValueError(f"{name} must be a sequence of SVG colour strings, got the single string {colors!r}")
    try:
        colors = tuple(colors)
    except TypeError:
        raise ValueError(f"{name} must be a sequence of SVG colour strings, got {colors!r}") from None
    if len(colors) < minimum or not all(isinstance(c, str) and c for c in colors):
        raise ValueError(f"{name} needs at least {minimum} non-empty colour strings, got {colors!r}")
    return colors


# --------------------------------------------------------------------------- drawing primitives


def _place(local, angle: float, center) -> np.ndarray:
    """Map points of an element's local frame (x along its main direction) to the page."""
    cos, sin = math.cos(angle), math.sin(angle)
    return np.asarray(local) @ np.array([[cos, sin], [-sin, cos]]) + np.asarray(center, dtype=float)


def _arc(length: float, sagitta: float = 0.0, n_points: int = 9) -> np.ndarray:
    """A parabolic arc from ``(-length / 2, 0)`` to ``(length / 2, 0)`` bulging by ``sagitta`` at its middle.

    Symmetric about the y axis, so its PCA major axis is exactly the chord (x axis). A zero sagitta gives
    the straight segment as two points.
    """
    if sagitta == 0.0:
        return np.array([(-length / 2.0, 0.0), (length / 2.0, 0.0)])
    x = np.linspace(-length / 2.0, length / 2.0, n_points)
    return np.column_stack([x, sagitta * (1.0 - (2.0 * x / length) ** 2)])


def _wave(length: float, amplitude: float, n_points: int = 15) -> np.ndarray:
    """One period of a cosine wave along the x axis, centred on the origin (an even curve: the PCA
    major axis is exactly the x axis and the box is centred on the origin)."""
    x = np.linspace(-length / 2.0, length / 2.0, n_points)
    return np.column_stack([x, amplitude * np.cos(2.0 * np.pi * x / length)])


def _stroke(local, angle: float, center, width: float, color: str = "#000000") -> Stroke:
    return Stroke(_place(local, angle, center), width, color)


# --------------------------------------------------------------------------- element positions


def _path_arcs(n: int, spacing: float, jitter: float, rng) -> np.ndarray:
    """Arc lengths ``(i + 0.5) * spacing`` jittered uniformly by at most ``jitter * spacing``."""
    return (np.arange(n) + 0.5 + rng.uniform(-jitter, jitter, n)) * spacing


def _lattice(width: float, height: float, spacing: float, *, hexagonal: bool = True) -> np.ndarray:
    """Lattice points (hexagonal rows, or a square grid) keeping half a spacing from the border, centred."""
    row_step = spacing * math.sqrt(3.0) / 2.0 if hexagonal else spacing
    n_rows = int(math.floor((height - spacing) / row_step + 1e-9)) + 1
    points = []
    for row in range(n_rows):
        shift = 0.5 * spacing * (row % 2) if hexagonal else 0.0
        n_cols = int(math.floor((width - spacing - shift) / spacing + 1e-9)) + 1
        points.extend((shift + col * spacing, row * row_step) for col in range(n_cols))
    points = np.array(points, dtype=float).reshape(-1, 2)
    if points.shape[0] == 0:  # a region narrower than one spacing
        return points
    offset = (np.array([width, height]) - (points.min(axis=0) + points.max(axis=0))) / 2.0
    return points + offset


def _disc_jitter(n: int, radius: float, rng) -> np.ndarray:
    """``n`` offsets uniform in the disc of the given radius."""
    r = radius * np.sqrt(rng.uniform(0.0, 1.0, n))
    angle = rng.uniform(0.0, 2.0 * np.pi, n)
    return np.column_stack([r * np.cos(angle), r * np.sin(angle)])


def _drawing_order(centers: np.ndarray, row_height: float) -> np.ndarray:
    """Order in which a user fills a region: rows from the top down, each row left to right."""
    band = np.floor((centers[:, 1].max() - centers[:, 1]) / row_height + 0.5)
    return np.lexsort((centers[:, 0], band))


def _region_centers(width: float, height: float, spacing: float, rng, *,
                    hexagonal: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Jittered lattice centres in drawing order, and each centre's integer lattice cell ``(column, row)``.

    Rows count up from the bottom row. Columns count in spacings on the square lattice (so that
    ``(column + row) % 2`` is a checkerboard colouring) and in half spacings on the hexagonal one (even on
    even rows, odd on the shifted rows: a site's six neighbours are at column +-2 on its row and +-1 on the
    rows above and below, so ``column % 3`` is a colouring in three classes in which no two neighbours
    share a class)."""
    lattice = _lattice(width, height, spacing, hexagonal=hexagonal)
    if lattice.shape[0] < 3:
        raise ValueError(f"a width x height = {width:g} x {height:g} region holds fewer than 3 elements: make it "
                         f"larger")
    lattice = lattice[_drawing_order(lattice, spacing / 2.0)]
    steps = np.array([spacing / 2.0, spacing * math.sqrt(3.0) / 2.0]) if hexagonal else np.array([spacing, spacing])
    cells = np.round((lattice - lattice.min(axis=0)) / steps).astype(int)
    return lattice + _disc_jitter(len(lattice), _LATTICE_JITTER * spacing, rng), cells


def _region(width, height, spacing: float, max_elements) -> tuple[float, float, object]:
    """Validated region size and the rectangle ``shapely.box(0, 0, width, height)``.

    The region must hold at most ``max_elements`` lattice sites ``spacing`` apart (hexagonal rows, the
    denser lattice), counted before any is drawn.
    """
    width = positive_number(width, "width")
    height = positive_number(height, "height")
    sites = (width / spacing + 1.0) * (height / (spacing * math.sqrt(3.0) / 2.0) + 1.0)
    needed = math.ceil(sites) if math.isfinite(sites) else sites
    check_budget(needed, budget(max_elements, "max_elements"), "max_elements",
                 f"elements (lattice sites {spacing:g} apart in a {width:g} x {height:g} region)")
    return width, height, shapely.box(0.0, 0.0, width, height)


# --------------------------------------------------------------------------- assembling the exemplar


def _exemplar(elements, params: dict, *, dimension: int, epsilon: float, description: str,
              path=None, region=None) -> StrokePatternExemplar:
    """Flatten per-element strokes in drawing order and freeze the truth arrays."""
    strokes = tuple(stroke for element in elements for stroke in element)
    element_of_stroke = np.repeat(np.arange(len(elements), dtype=np.int64), [len(e) for e in elements])
    n = len(elements)
    orientation = np.mod(np.asarray(params["orientation"], dtype=float), np.pi)
    orientation[orientation >= np.pi] = 0.0  # mod of a tiny negative angle rounds to pi
    arrays = {
        "position": np.asarray(params["position"], dtype=float).reshape(n, 2),
        "arc": np.asarray(params.get("arc", np.full(n, np.nan)), dtype=float),
        "orientation": orientation,
        "length": np.asarray(params["length"], dtype=float),
        "thickness": np.asarray(params["thickness"], dtype=float),
        "color": np.asarray(params["color"], dtype=str),
        "kind": np.asarray(params["kind"], dtype=str),
    }
    for array in (*arrays.values(), element_of_stroke):
        array.setflags(write=False)
    if path is not None:
        path = np.asarray(path, dtype=float)
        path.setflags(write=False)
    return StrokePatternExemplar(strokes, element_of_stroke, dimension, path, region, float(epsilon), arrays,
                                 description)


def _horizontal_path(n: int, spacing: float) -> np.ndarray:
    return np.array([(0.0, 0.0), (n * spacing, 0.0)])


# --------------------------------------------------------------------------- 1D patterns (Figure 6)


def _check_1d(n_elements, spacing, max_elements) -> tuple[int, float]:
    n = _count(n_elements, "n_elements", 2)
    check_budget(n, budget(max_elements, "max_elements"), "max_elements", "elements")
    return n, positive_number(spacing, "spacing")


def _sketchy_hatch(length: float, angle: float, center, spacing: float, rng) -> list:
    """2-4 overlapping gentle arcs: small lateral offsets, jittered ends, a shared bend (Figure 1)."""
    bend = rng.choice((-1.0, 1.0)) * rng.uniform(0.03, 0.07) * spacing
    strokes = []
    for _ in range(rng.integers(2, 5)):
        start, end = rng.uniform(-0.04, 0.04, 2) * spacing
        local = _arc(length + end - start, bend + rng.uniform(-0.01, 0.01) * spacing, 11)
        local = local + (0.5 * (start + end), rng.uniform(-0.03, 0.03) * spacing)
        tilt = rng.uniform(-0.03, 0.03) * spacing / length  # moves the stroke's ends by 0.015 spacing at most
        strokes.append(_stroke(local, angle + tilt, center, PEN_WIDTH * spacing))
    return strokes


def _dashed_hatch(length: float, angle: float, center, spacing: float, rng) -> list:
    """Two straight collinear dashes with a short gap: only continuation binds them (Figure 2 b)."""
    gap = 0.06 * spacing
    split = -length / 2.0 + rng.uniform(0.35, 0.65) * (length - gap)
    dashes = ([(-length / 2.0, 0.0), (split, 0.0)], [(split + gap, 0.0), (length / 2.0, 0.0)])
    return [_stroke(dash, angle, center, PEN_WIDTH * spacing) for dash in dashes]


def sketchy_hatching_exemplar(n_elements=24, *, spacing=1.0, length=3.0, rng=None,
                              max_elements=MAX_ELEMENTS) -> StrokePatternExemplar:
    """Curved near-vertical hatches drawn with sketchy multi-stroke gestures along a path (synthetic).

    Each hatch is a gentle arc tilted at most 2 degrees from vertical, drawn as 2-4 overlapping strokes
    (lateral offsets up to 0.03 spacing, ends jittered by up to 0.04 spacing, turned so that their ends move
    by at most 0.015 spacing more, bends 0.03-0.07 spacing, shared by the strokes of a hatch up to 0.01),
    except that about one hatch in four (``kind="dashed-hatch"``) is drawn as two straight collinear
    dashes separated by a gap of 0.06 spacing, so that only Barla's continuation measure, not
    proximity, groups them. Hatch positions along the path jitter by up to 0.05 spacing.

    Parameters
    ----------
    n_elements : int
        Number of hatches (>= 2).
    spacing : float
        Designed distance between neighbouring hatches (> 0); ``epsilon = 0.2 * spacing``.
    length : float
        Hatch length, between 1.5 and 5 spacings (longer bent hatches would crowd their neighbours,
        shorter dashes would be close enough for proximity).
    rng : None, int or numpy.random.Generator
    max_elements : int, optional
        Budget: the most elements (default :data:`MAX_ELEMENTS`), checked before drawing.

    Returns
    -------
    StrokePatternExemplar
        One-dimensional; ``kind`` is ``"hatch"`` or ``"dashed-hatch"``.

    Raises
    ------
    ValueError
        On a count below 2, a non-positive spacing or a length out of range.

    References
    ----------
    Barla et al. 2006, Figure 1 (sketchy hatching), Figure 2 (proximity, continuation), Figure 6 a.
    """
    n, spacing = _check_1d(n_elements, spacing, max_elements)
    length = _between(length, "length", 1.5 * spacing, 5.0 * spacing)
    rng = as_generator(rng)
    arcs = _path_arcs(n, spacing, _ARC_JITTER, rng)
    angles = np.pi / 2.0 + np.radians(rng.uniform(-2.0, 2.0, n))
    dashed = rng.random(n) < 0.25
    elements = [(_dashed_hatch if d else _sketchy_hatch)(length, a, (s, 0.0), spacing, rng)
                for s, a, d in zip(arcs, angles, dashed)]
    params = dict(position=np.column_stack([arcs, np.zeros(n)]), arc=arcs, orientation=angles,
                  length=np.full(n, length), thickness=np.full(n, PEN_WIDTH * spacing), color=["#000000"] * n,
                  kind=np.where(dashed, "dashed-hatch", "hatch"))
    return _exemplar(elements, params, dimension=1, epsilon=_EPSILON_1D * spacing, path=_horizontal_path(n, spacing),
                     description=f"synthetic sketchy hatching: {n} curved near-vertical hatches, each 2-4 "
                                 "overlapping strokes or two collinear dashes (stand-in for Barla 2006, Fig. 6a)")


def jittered_hatching_exemplar(n_elements=30, *, spacing=1.0, length=2.5, vertical_jitter=0.4,
                               rng=None,
                               max_elements=MAX_ELEMENTS) -> StrokePatternExemplar:
    """Straight vertical hatches, evenly spaced, with random vertical offsets (synthetic).

    Hatch ``i`` is one straight stroke centred at ``((i + 0.5) * spacing, v_i)`` with ``v_i`` uniform in
    ``[-vertical_jitter, vertical_jitter]``: the irregularity that Barla's variation post-process (shift
    vectors) has to reintroduce in a synthesis.

    Parameters
    ----------
    n_elements : int
        Number of hatches (>= 2).
    spacing : float
        Distance between neighbouring hatches (> 0); ``epsilon = 0.2 * spacing``.
    length : float
        Hatch length (> 0).
    vertical_jitter : float
        Largest vertical offset of a hatch centre (>= 0).
    rng : None, int or numpy.random.Generator
    max_elements : int, optional
        Budget: the most elements (default :data:`MAX_ELEMENTS`), checked before drawing.

    Returns
    -------
    StrokePatternExemplar
        One-dimensional, one stroke per element, ``kind="hatch"``.

    Raises
    ------
    ValueError
        On a count below 2, a non-positive spacing or length, or a negative jitter.

    References
    ----------
    Barla et al. 2006, Figure 6 b and section 3.3 (position variation).
    """
    n, spacing = _check_1d(n_elements, spacing, max_elements)
    length = positive_number(length, "length")
    vertical_jitter = positive_number(vertical_jitter, "vertical_jitter", allow_zero=True)
    rng = as_generator(rng)
    arcs = (np.arange(n) + 0.5) * spacing
    centers = np.column_stack([arcs, rng.uniform(-vertical_jitter, vertical_jitter, n)])
    segment = _arc(length)
    elements = [[_stroke(segment, np.pi / 2.0, c, PEN_WIDTH * spacing)] for c in centers]
    params = dict(position=centers, arc=arcs, orientation=np.full(n, np.pi / 2.0), length=np.full(n, length),
                  thickness=np.full(n, PEN_WIDTH * spacing), color=["#000000"] * n, kind=["hatch"] * n)
    return _exemplar(elements, params, dimension=1, epsilon=_EPSILON_1D * spacing, path=_horizontal_path(n, spacing),
                     description=f"synthetic jittered hatching: {n} vertical strokes with vertical offsets up to "
                                 f"{vertical_jitter:g} (stand-in for Barla 2006, Fig. 6b)")


def gradient_hatching_exemplar(parameter, n_elements=30, *, spacing=1.0, jitter=0.0,
                               rng=None,
                               max_elements=MAX_ELEMENTS) -> StrokePatternExemplar:
    """Single straight strokes whose orientation, length, pen width or colour ramps along the path (synthetic).

    The chosen parameter is a linear, increasing function of the designed arc length ``(i + 0.5) *
    spacing`` from its first to its last value, plus, with ``jitter > 0``, Gaussian noise of standard deviation
    ``jitter`` ramp steps (a hand-drawn ramp); the others stay constant:

    ===============  ==============================  =========================================
    parameter        ramp                            constants
    ===============  ==============================  =========================================
    ``orientation``  50 to 130 degrees from x        length 2.5, pen width 0.08
    ``length``       0.5 to 4.0                      vertical, pen width 0.08
    ``thickness``    pen width 0.05 to 0.75          vertical, length 0.8
    ``color``        RGB (0.85, 0.2, 0.1) to         vertical, length 2.5, pen width 0.25
                     (0.1, 0.2, 0.85)
    ===============  ==============================  =========================================

    (lengths and widths in units of ``spacing``). Each ramp spans at least 5 of the paper's thresholds for
    the measure that sees it (8.9 sigma_par, 5.1 sigma_ov steps, 5.7 sigma_sup, 7.1 sigma_col), so that a
    synthesis that loses the ramp is visible to the matching rule. Positions jitter by at most 0.02 spacing
    along and across the path, small enough to keep the elements in order.

    Parameters
    ----------
    parameter : {"orientation", "length", "thickness", "color"}
    n_elements : int
        Number of strokes (>= 2).
    spacing : float
        Designed distance between neighbouring strokes (> 0); ``epsilon = 0.2 * spacing``.
    jitter : float
        Standard deviation of the noise on the ramped parameter, in ramp steps (>= 0, at most 3); values are
        clipped to the ramp's range.
    rng : None, int or numpy.random.Generator
    max_elements : int, optional
        Budget: the most elements (default :data:`MAX_ELEMENTS`), checked before drawing.

    Returns
    -------
    StrokePatternExemplar
        One-dimensional, one stroke per element, ``kind="hatch"``; ``params["color"]`` holds hex colours.

    Raises
    ------
    ValueError
        On an unknown parameter, a count below 2, a non-positive spacing or a jitter outside [0, 3].

    References
    ----------
    Barla et al. 2006, Figure 6 c-e (smooth changes of orientation, length and thickness) and section 3.1
    (the thresholds).
    """
    check_choice(parameter, sorted(_GRADIENT_RANGES), "parameter")
    n, spacing = _check_1d(n_elements, spacing, max_elements)
    jitter = _between(jitter, "jitter", 0.0, 3.0)
    rng = as_generator(rng)
    low, high = _GRADIENT_RANGES[parameter]
    step = (high - low) / (n - 1)
    ramp = np.clip(low + step * (np.arange(n) + jitter * rng.standard_normal(n)), low, high)
    values = {name: np.full(n, value) for name, value in _GRADIENT_CONSTANTS.items()}
    if parameter == "thickness":
        values["length"] = np.full(n, _THICKNESS_RAMP_LENGTH)
    if parameter == "color":
        values["thickness"] = np.full(n, _COLOR_RAMP_WIDTH)
        start, stop = np.array(_COLOR_RAMP_ENDS)
        colors = [to_hex(start + (stop - start) * t) for t in ramp]
    else:
        values[parameter] = ramp
        colors = ["#000000"] * n
    angles, lengths, widths = np.radians(values["orientation"]), values["length"] * spacing, values["thickness"] * spacing
    ramp_text = "RGB (0.85, 0.2, 0.1) to (0.1, 0.2, 0.85)" if parameter == "color" else f"{low:g} to {high:g}"
    return _straight_strokes_1d(angles, lengths, widths, colors, spacing, rng,
                                f"synthetic gradient hatching: {n} strokes whose {parameter} ramps from {ramp_text} "
                                f"along the path{f' (jitter {jitter:g} steps)' if jitter else ''} (stand-in for "
                                "Barla 2006, Fig. 6c-e)")


def _straight_strokes_1d(angles, lengths, widths, colors, spacing: float, rng, description: str):
    """One straight stroke per element along the horizontal path, a spacing apart, centres jittered by at most
    0.02 spacing along and across the path."""
    n = len(angles)
    centers = np.column_stack([(np.arange(n) + 0.5) * spacing, np.zeros(n)]) + rng.uniform(-0.02, 0.02, (n, 2)) * spacing
    elements = [[_stroke(_arc(ell), a, c, w, col)] for ell, a, c, w, col in zip(lengths, angles, centers, widths, colors)]
    params = dict(position=centers, arc=centers[:, 0], orientation=angles, length=lengths, thickness=widths,
                  color=list(colors), kind=["hatch"] * n)
    return _exemplar(elements, params, dimension=1, epsilon=_EPSILON_1D * spacing, path=_horizontal_path(n, spacing),
                     description=description)


def wave_hatching_exemplar(n_elements=40, *, period=16.0, amplitude=35.0, jitter=1.5, spacing=1.0,
                           rng=None,
                           max_elements=MAX_ELEMENTS) -> StrokePatternExemplar:
    """Straight strokes whose orientation swings back and forth along the path, gradually (synthetic).

    Stroke ``i`` is turned ``90 + amplitude sin(2 pi i / period)`` degrees from x, plus Gaussian noise of
    standard deviation ``jitter`` degrees (a hand-drawn wave); length 2.5, pen width 0.08 (in spacings).
    Unlike a monotone ramp, the pattern is stationary: every neighbourhood recurs, so it can be continued
    along a path longer than the exemplar (the neighbouring differences are what a synthesis must keep).

    Parameters
    ----------
    n_elements : int
        Number of strokes (>= 2).
    period : float
        Wavelength in strokes (>= 2).
    amplitude, jitter : float
        Degrees; amplitude in [0, 85], jitter in [0, 10].
    spacing : float
        Designed distance between neighbouring strokes (> 0); ``epsilon = 0.2 * spacing``.
    rng : None, int or numpy.random.Generator
    max_elements : int, optional
        Budget: the most elements (default :data:`MAX_ELEMENTS`), checked before drawing.

    Returns
    -------
    StrokePatternExemplar
        One-dimensional, one stroke per element, ``kind="hatch"``.

    References
    ----------
    Barla et al. 2006, Figure 6 c (gradual changes of orientation along a path).
    """
    n, spacing = _check_1d(n_elements, spacing, max_elements)
    period = _between(period, "period", 2.0, 1e6)
    amplitude = _between(amplitude, "amplitude", 0.0, 85.0)
    jitter = _between(jitter, "jitter", 0.0, 10.0)
    rng = as_generator(rng)
    angles = np.radians(90.0 + amplitude * np.sin(2.0 * np.pi * np.arange(n) / period) + jitter * rng.standard_normal(n))
    lengths, widths = np.full(n, 2.5 * spacing), np.full(n, PEN_WIDTH * spacing)
    return _straight_strokes_1d(angles, lengths, widths, ["#000000"] * n, spacing, rng,
                                f"synthetic wave hatching: {n} strokes whose orientation swings +-{amplitude:g} deg "
                                f"with a period of {period:g} strokes (jitter {jitter:g} deg)")


def alternating_color_exemplar(n_elements=24, *, colors=("#c0392b", "#1f618d"), rng=None,
                               max_elements=MAX_ELEMENTS) -> StrokePatternExemplar:
    """Thick, slightly wavy brush strokes whose colours alternate along the path (synthetic).

    Stroke ``i`` (one period of a cosine wave of amplitude 0.03, length 1.2 +- 5 %, pen width 0.25,
    tilted up to 6 degrees from vertical) takes ``colors[i % len(colors)]``; strokes are a unit
    spacing apart (jittered by up to 0.05) and ``epsilon = 0.2``.

    Parameters
    ----------
    n_elements : int
        Number of brush strokes (>= 2).
    colors : sequence of str
        At least two SVG colours, used in turn.
    rng : None, int or numpy.random.Generator
    max_elements : int, optional
        Budget: the most elements (default :data:`MAX_ELEMENTS`), checked before drawing.

    Returns
    -------
    StrokePatternExemplar
        One-dimensional, one stroke per element, ``kind="brush"``.

    Raises
    ------
    ValueError
        On a count below 2 or fewer than two colours.

    References
    ----------
    Barla et al. 2006, Figure 6 f (colour pattern) and section 3.1 (colour measure).
    """
    n, spacing = _check_1d(n_elements, 1.0, max_elements)
    colors = _colors(colors, "colors", 2)
    rng = as_generator(rng)
    arcs = _path_arcs(n, spacing, _ARC_JITTER, rng)
    angles = np.pi / 2.0 + np.radians(rng.uniform(-6.0, 6.0, n))
    lengths = 1.2 * rng.uniform(0.95, 1.05, n)
    palette = [colors[i % len(colors)] for i in range(n)]
    elements = [[_stroke(_wave(ell, 0.03), a, (s, 0.0), 0.25, c)]
                for s, a, ell, c in zip(arcs, angles, lengths, palette)]
    params = dict(position=np.column_stack([arcs, np.zeros(n)]), arc=arcs, orientation=angles, length=lengths,
                  thickness=np.full(n, 0.25), color=palette, kind=["brush"] * n)
    return _exemplar(elements, params, dimension=1, epsilon=_EPSILON_1D, path=_horizontal_path(n, spacing),
                     description=f"synthetic brush strokes: {n} wavy strokes alternating {len(colors)} colours "
                                 "(stand-in for Barla 2006, Fig. 6f)")


# --------------------------------------------------------------------------- 2D patterns (Figure 7)


def _unit_petal() -> np.ndarray:
    """A petal loop of unit length: one lobe of a rose curve reaching 1 from the flower's heart along the x
    axis, starting ``_PETAL_BACK`` behind the heart so that neighbouring petals overlap there. Its first and
    last vertex coincide (a closed loop)."""
    phi = np.linspace(-1.0, 1.0, 17)
    radius = (1.0 + _PETAL_BACK) * np.cos(0.5 * np.pi * phi)
    polar = _PETAL_HALF_ANGLE * phi
    return np.column_stack([radius * np.cos(polar) - _PETAL_BACK, radius * np.sin(polar)])


_UNIT_PETAL = _unit_petal()
#: A flower's heart: a short bent stroke, in units of the petal length.
_UNIT_HEART = _arc(0.12, 0.03, 5)


def _flower(center, angle: float, size: float, color: str, rng) -> list:
    """Five petal loops around the heart, then a small loop for the heart (Figure 7 c)."""
    angles = angle + 2.0 * np.pi * np.arange(5) / 5.0 + np.radians(rng.uniform(-4.0, 4.0, 5))
    sizes = size * rng.uniform(0.95, 1.05, 5)
    petals = [_stroke(_UNIT_PETAL * s, a, center, PEN_WIDTH / 2.0, color) for s, a in zip(sizes, angles)]
    return petals + [_stroke(_UNIT_HEART * size, angle, center, PEN_WIDTH / 2.0, color)]


def _drop(length: float, width: float, n_points: int = 33) -> np.ndarray:
    """Closed teardrop outline along the x axis, tip at ``+length / 2``, round end at ``-length / 2``.

    ``(cos t, sin t sin(t / 2))`` is symmetric about the x axis and spans [-1, 1] in x, so the box is
    centred on the origin with its major axis along x; the first vertex (the tip) closes the loop.
    """
    t = np.linspace(0.0, 2.0 * np.pi, n_points)
    y = np.sin(t) * np.sin(t / 2.0)
    local = np.column_stack([np.cos(t) * length / 2.0, y * width / (2.0 * np.abs(y).max())])
    local[-1] = local[0]
    return local


def _highlight(length: float, width: float, side: float) -> np.ndarray:
    """A short arc inside a drop's round end, on one side of its axis (a glint)."""
    angle = np.linspace(0.65, 1.05, 5) * np.pi
    return np.column_stack([0.22 * length * np.cos(angle) - 0.1 * length, side * 0.22 * width * np.sin(angle)])


def _params_2d(centers, angles, lengths, widths, colors, kinds) -> dict:
    return dict(position=centers, orientation=angles, length=lengths, thickness=widths, color=colors, kind=kinds)


def _structure(value, allowed: tuple) -> str:
    if not isinstance(value, str) or value not in allowed:
        raise ValueError(f"structure must be one of {list(allowed)}, got {value!r}")
    return value


def _patches(centers, width: float, height: float, spacing: float, patch_size: float, n_labels: int,
             rng) -> np.ndarray:
    """A label in ``range(n_labels)`` per centre, constant over patches about ``patch_size`` across.

    The patches are the Voronoi cells of a ``round(width / patch_size) x round(height / patch_size)`` grid of
    patch centres (at least 1 x 1), each jittered uniformly by up to 0.3 of its grid cell. Two patches are
    adjacent when two of their centres are lattice neighbours (closer than 1.5 ``spacing``); patches are
    labelled one after the other in a random order, each uniformly among the labels none of its labelled
    neighbours has, or, when every label is taken, among those its neighbours use least.
    """
    nx, ny = max(1, round(width / patch_size)), max(1, round(height / patch_size))
    cell = np.array([width / nx, height / ny])
    grid = np.stack(np.meshgrid(np.arange(nx) + 0.5, np.arange(ny) + 0.5), axis=-1).reshape(-1, 2)
    seeds = (grid + rng.uniform(-0.3, 0.3, grid.shape)) * cell
    owner = np.argmin(((centers[:, None, :] - seeds[None, :, :]) ** 2).sum(axis=-1), axis=1)
    i, j = np.nonzero(np.triu(np.hypot(*(centers[:, None, :] - centers[None, :, :]).transpose(2, 0, 1))
                              < 1.5 * spacing, k=1))
    crossing = owner[i] != owner[j]
    adjacent = np.zeros((len(seeds), len(seeds)), dtype=bool)
    adjacent[owner[i][crossing], owner[j][crossing]] = True
    adjacent |= adjacent.T
    labels = np.full(len(seeds), -1)
    for patch in rng.permutation(len(seeds)):
        used = np.bincount(labels[adjacent[patch] & (labels >= 0)], minlength=n_labels)
        free = np.flatnonzero(used == used.min())
        labels[patch] = free[rng.integers(len(free))]
    return labels[owner]


def bars_exemplar(*, directions_deg=(0.0, 60.0, 120.0), structure="patches", patch_size=4.0, width=12.0,
                  height=12.0, rng=None,
                  max_elements=MAX_ELEMENTS) -> StrokePatternExemplar:
    """Straight bars in several directions filling a region, aligned in patches (synthetic).

    Centres on a hexagonal lattice of spacing 1.25 jittered by up to 0.0625 (about 100 bars in the
    default 12 x 12 region); each bar is one straight stroke of length 0.9 +- 3 % in one of the
    ``directions_deg`` (degrees from the x axis), turned by up to 3 degrees. Which direction, the rule
    the synthesis must reproduce (the "complex relations among similar elements" of section 4):

    - ``structure="patches"`` (default): the region is cut into patches about ``patch_size`` across (the
      Voronoi cells of a jittered grid of patch centres, 3 x 3 patches of about 10 bars in the default
      region) and all the bars of a patch share its direction; adjacent patches take different directions
      wherever the directions allow. Neighbouring bars are parallel inside a patch and turn by a whole
      direction step across a patch border (about 70 % of the neighbour pairs are parallel with patches of
      4, against 1 / len(directions_deg) for independent directions).
    - ``structure="random"``: each bar's direction drawn independently and uniformly (the exemplar before
      issue 19; a shuffle of it is as structured as itself).

    ``epsilon = 0.09``: collinear bars facing each other keep a gap of at least 0.19.

    Parameters
    ----------
    directions_deg : sequence of float
        Directions the bars may take (at least one).
    structure : {"patches", "random"}
        How directions are laid out (above).
    patch_size : float
        Size of a patch (> 0), for ``structure="patches"``.
    width, height : float
        Size of the region ``shapely.box(0, 0, width, height)`` (> 0, room for at least 3 bars).
    rng : None, int or numpy.random.Generator
    max_elements : int, optional
        Budget: the most elements (default :data:`MAX_ELEMENTS`), checked before drawing.

    Returns
    -------
    StrokePatternExemplar
        Two-dimensional, one stroke per element, ``kind="bar"``.

    Raises
    ------
    ValueError
        On no or non-finite directions, an unknown structure, a non-positive patch size, or a region too small.

    References
    ----------
    Barla et al. 2006, Figure 7 a ("bars oriented in multiple directions") and section 4.
    """
    try:
        directions = np.radians(np.asarray(directions_deg, dtype=float).reshape(-1))
    except (TypeError, ValueError):
        raise ValueError(f"directions_deg must be a sequence of angles in degrees, got {directions_deg!r}") from None
    if directions.size == 0 or not np.isfinite(directions).all():
        raise ValueError(f"directions_deg needs at least one finite angle, got {directions_deg!r}")
    structure = _structure(structure, ("patches", "random"))
    patch_size = positive_number(patch_size, "patch_size")
    width, height, region = _region(width, height, 1.25, max_elements)
    rng = as_generator(rng)
    centers, _ = _region_centers(width, height, 1.25, rng)
    n = len(centers)
    if structure == "patches":
        chosen = directions[_patches(centers, width, height, 1.25, patch_size, directions.size, rng)]
    else:
        chosen = rng.choice(directions, n)
    angles = chosen + np.radians(rng.uniform(-3.0, 3.0, n))
    lengths = 0.9 * rng.uniform(0.97, 1.03, n)
    elements = [[_stroke(_arc(ell), a, c, PEN_WIDTH)] for c, a, ell in zip(centers, angles, lengths)]
    params = _params_2d(centers, angles, lengths, np.full(n, PEN_WIDTH), ["#000000"] * n, ["bar"] * n)
    layout = f"aligned in patches about {patch_size:g} across" if structure == "patches" else "drawn independently"
    return _exemplar(elements, params, dimension=2, epsilon=0.09, region=region,
                     description=f"synthetic bars: {n} straight strokes in {directions.size} directions, {layout} "
                                 "(stand-in for Barla 2006, Fig. 7a)")


def drops_exemplar(*, structure="ringed", width=12.0, height=12.0, rng=None,
                   max_elements=MAX_ELEMENTS) -> StrokePatternExemplar:
    """Water drops among short hatches in a region, each drop ringed by hatches (synthetic).

    Centres on a hexagonal lattice of spacing 1.25 jittered by up to 0.0625. Each site is a drop
    (``kind="drop"``: a closed teardrop outline 0.7 long and 0.45 wide, tip up, tilted up to 12 degrees,
    with a 40 % chance of a small highlight arc inside it, then a two-stroke element) or a hatch
    (``kind="hatch"``: a straight stroke 0.5 long at 30 +- 5 degrees). Which sites are drops, the rule the
    synthesis must reproduce:

    - ``structure="ringed"`` (default): the lattice's sites fall in three classes such that no two
      neighbouring sites share a class (a site's column in half spacings, modulo 3); one class, drawn at
      random, carries the drops, the other two the hatches. One site in three is a drop, no two drops are
      neighbours, every drop is ringed by six hatches and every hatch has three drop and three hatch
      neighbours: 1/3 of the neighbour pairs join two elements of the same kind, against 5/9 for the same
      shares drawn independently.
    - ``structure="random"``: each site a drop with probability 1/2, independently (the exemplar before
      issue 19).

    A drop's ``orientation`` is its symmetry axis, its ``length`` the outline's extent along it. The
    highlight nests inside the drop's box (proximity 0); ``epsilon = 0.15``.

    Parameters
    ----------
    structure : {"ringed", "random"}
        How the kinds are laid out (above).
    width, height : float
        Size of the region (> 0, room for at least 3 elements).
    rng : None, int or numpy.random.Generator
    max_elements : int, optional
        Budget: the most elements (default :data:`MAX_ELEMENTS`), checked before drawing.

    Returns
    -------
    StrokePatternExemplar
        Two-dimensional.

    Raises
    ------
    ValueError
        On an unknown structure or a region too small.

    References
    ----------
    Barla et al. 2006, Figure 7 b ("elements of various nature (water drops, hatches)") and section 4.
    """
    structure = _structure(structure, ("ringed", "random"))
    width, height, region = _region(width, height, 1.25, max_elements)
    rng = as_generator(rng)
    centers, cells = _region_centers(width, height, 1.25, rng)
    n = len(centers)
    if structure == "ringed":
        is_drop = cells[:, 0] % 3 == rng.integers(3)
    else:
        is_drop = rng.random(n) < 0.5
    angles = np.where(is_drop, np.pi / 2.0 + np.radians(rng.uniform(-12.0, 12.0, n)),
                      np.radians(30.0 + rng.uniform(-5.0, 5.0, n)))
    lengths = np.where(is_drop, 0.7, 0.5)
    elements = []
    for center, angle, drop in zip(centers, angles, is_drop):
        if not drop:
            elements.append([_stroke(_arc(0.5), angle, center, PEN_WIDTH)])
            continue
        element = [_stroke(_drop(0.7, 0.45), angle, center, PEN_WIDTH)]
        if rng.random() < 0.4:
            element.append(_stroke(_highlight(0.7, 0.45, rng.choice((-1.0, 1.0))), angle, center, PEN_WIDTH / 2.0))
        elements.append(element)
    params = _params_2d(centers, angles, lengths, np.full(n, PEN_WIDTH), ["#000000"] * n,
                        np.where(is_drop, "drop", "hatch"))
    layout = ", each drop ringed by hatches" if structure == "ringed" else ", kinds drawn independently"
    return _exemplar(elements, params, dimension=2, epsilon=0.15, region=region,
                     description=f"synthetic drops and hatches: {int(is_drop.sum())} water drops and "
                                 f"{int(n - is_drop.sum())} short hatches{layout} (stand-in for Barla 2006, Fig. 7b)")


def flowers_exemplar(*, colors=("#c0392b", "#d4ac0d", "#7d3c98"), structure="bands", band_rows=2, width=12.0,
                     height=12.0, rng=None,
                     max_elements=MAX_ELEMENTS) -> StrokePatternExemplar:
    """Small flowers, each drawn with five petal loops and a heart, in colour bands (synthetic).

    Centres on a hexagonal lattice of spacing 1.3 jittered by up to 0.065 (about 90 flowers in the
    default region). A flower of radius 0.28 +- 5 % is five petal loops (lobes that overlap at the heart,
    turned by up to 4 degrees from a regular star whose first petal points in a random direction) and a
    short arc for its heart, all in one colour from ``colors``. Which colour, the rule the synthesis must
    reproduce:

    - ``structure="bands"`` (default): the lattice rows, counted from the top, form horizontal bands of
      ``band_rows`` rows, and the bands take the colours in turn, starting at a random one. A flower has
      two same-colour neighbours on its row and, with two rows per band, two more on the other row of its
      band: 2/3 of the neighbour pairs share a colour, against 1 / len(colors) for colours drawn
      independently.
    - ``structure="random"``: each flower's colour drawn independently and uniformly (the exemplar before
      issue 19).

    ``orientation`` is the designed direction of the first petal (modulo pi), ``length`` the flower's
    designed diameter. ``epsilon = 0.32``: Barla's greedy clustering, which refits the merged box after each
    merge, joins the petals at 0.54 petal length at worst.

    Parameters
    ----------
    colors : sequence of str
        At least one SVG colour.
    structure : {"bands", "random"}
        How the colours are laid out (above).
    band_rows : int
        Rows per colour band (>= 1), for ``structure="bands"``.
    width, height : float
        Size of the region (> 0, room for at least 3 flowers).
    rng : None, int or numpy.random.Generator
    max_elements : int, optional
        Budget: the most elements (default :data:`MAX_ELEMENTS`), checked before drawing.

    Returns
    -------
    StrokePatternExemplar
        Two-dimensional, six strokes per element, ``kind="flower"``.

    Raises
    ------
    ValueError
        On no colours, an unknown structure, a band of fewer than one row, or a region too small.

    References
    ----------
    Barla et al. 2006, Figure 7 c ("small figures like flowers of different colors") and section 2.2 ("a
    small figure (think of a flower) is often drawn using a small number of individual strokes").
    """
    colors = _colors(colors, "colors", 1)
    structure = _structure(structure, ("bands", "random"))
    band_rows = _count(band_rows, "band_rows", 1)
    width, height, region = _region(width, height, 1.3, max_elements)
    rng = as_generator(rng)
    centers, cells = _region_centers(width, height, 1.3, rng)
    n = len(centers)
    angles = rng.uniform(0.0, 2.0 * np.pi, n)
    sizes = 0.28 * rng.uniform(0.95, 1.05, n)
    if structure == "bands":
        band = (cells[:, 1].max() - cells[:, 1]) // band_rows
        palette = [colors[k] for k in (band + rng.integers(len(colors))) % len(colors)]
    else:
        palette = [colors[k] for k in rng.integers(0, len(colors), n)]
    elements = [_flower(c, a, size, color, rng) for c, a, size, color in zip(centers, angles, sizes, palette)]
    params = _params_2d(centers, angles, 2.0 * sizes, np.full(n, PEN_WIDTH / 2.0), palette, ["flower"] * n)
    layout = (f"in bands of {band_rows} row{'s' if band_rows > 1 else ''}" if structure == "bands"
              else "drawn independently")
    return _exemplar(elements, params, dimension=2, epsilon=0.32, region=region,
                     description=f"synthetic flowers: {n} flowers of five petal loops and a heart in "
                                 f"{len(colors)} colours {layout} (stand-in for Barla 2006, Fig. 7c)")


def two_hatchings_exemplar(*, width=12.0, height=12.0, rng=None,
                           max_elements=MAX_ELEMENTS) -> StrokePatternExemplar:
    """Two kinds of hatches alternating in a checkerboard (synthetic).

    Centres on a square lattice of spacing 1.2 jittered by up to 0.06; sites of even parity carry an
    ``"A"`` hatch (three parallel strokes 0.55 long, 0.09 apart, at 30 +- 4 degrees, ends jittered by up
    to 0.03), the others a ``"B"`` hatch (one stroke 1.0 long at 120 +- 4 degrees). The rule the synthesis
    must reproduce: a site's four neighbours along the rows and columns are all of the other kind (its
    diagonal neighbours of its own); on the unskewed Delaunay graph, which keeps one diagonal per square,
    2/3 of the neighbour pairs join an A and a B hatch, against 1/2 for kinds drawn independently.
    ``epsilon = 0.25``.

    Parameters
    ----------
    width, height : float
        Size of the region (> 0, room for at least 3 elements).
    rng : None, int or numpy.random.Generator
    max_elements : int, optional
        Budget: the most elements (default :data:`MAX_ELEMENTS`), checked before drawing.

    Returns
    -------
    StrokePatternExemplar
        Two-dimensional, ``kind`` ``"A"`` or ``"B"``.

    Raises
    ------
    ValueError
        On a region too small.

    References
    ----------
    Barla et al. 2006, Figure 7 d ("alternating two different kinds of elements") and section 4.
    """
    width, height, region = _region(width, height, 1.2, max_elements)
    rng = as_generator(rng)
    centers, cells = _region_centers(width, height, 1.2, rng, hexagonal=False)
    n = len(centers)
    is_a = (cells[:, 0] + cells[:, 1]) % 2 == 0
    angles = np.radians(np.where(is_a, 30.0, 120.0) + rng.uniform(-4.0, 4.0, n))
    lengths = np.where(is_a, 0.55, 1.0)
    elements = []
    for center, angle, a_kind in zip(centers, angles, is_a):
        if not a_kind:
            elements.append([_stroke(_arc(1.0), angle, center, PEN_WIDTH / 2.0)])
            continue
        ends = rng.uniform(-0.03, 0.03, (3, 2))
        elements.append([_stroke([(-0.275 + e0, 0.09 * k), (0.275 + e1, 0.09 * k)], angle, center, PEN_WIDTH / 2.0)
                         for k, (e0, e1) in zip((-1, 0, 1), ends)])
    params = _params_2d(centers, angles, lengths, np.full(n, PEN_WIDTH / 2.0), ["#000000"] * n,
                        np.where(is_a, "A", "B"))
    return _exemplar(elements, params, dimension=2, epsilon=0.25, region=region,
                     description=f"synthetic two hatchings: {int(is_a.sum())} three-stroke 'A' and "
                                 f"{int(n - is_a.sum())} one-stroke 'B' hatches in a checkerboard "
                                 "(stand-in for Barla 2006, Fig. 7d)")


def _clustered_centers(n: int, width: float, height: float, min_distance: float, rng) -> np.ndarray:
    """Dart throwing with a hard core from a clustered density: nine candidates in ten fall around a few
    uniform parents (one per 16 square units, Gaussian spread 0.6), the others anywhere; a candidate is
    kept if inside the region (half a unit from its border) and at least ``min_distance`` from every kept
    centre.

    Fails fast with a ValueError when the discs of radius ``min_distance / 2`` would cover more than 30 %
    of the region, or when a whole batch of candidates finds no room (the clumps are full)."""
    low, high = np.array([0.5, 0.5]), np.array([width - 0.5, height - 0.5])
    inner_area = float(np.prod(np.maximum(high - low, 0.0)))
    if n * np.pi * (min_distance / 2.0) ** 2 > 0.3 * inner_area:
        raise ValueError(f"{n} marks {min_distance:g} apart do not fit in a {width:g} x {height:g} region: "
                         "lower n_elements or enlarge the region")
    parents = rng.uniform(low, high, (max(3, round(width * height / 16.0)), 2))
    kept, count = np.empty((n, 2)), 0
    for _ in range(100):
        candidates = parents[rng.integers(0, len(parents), 4 * n)] + rng.normal(0.0, 0.6, (4 * n, 2))
        background = rng.random(4 * n) < 0.1
        candidates[background] = rng.uniform(low, high, (int(background.sum()), 2))
        before = count
        for point in candidates[np.all((candidates >= low) & (candidates <= high), axis=1)]:
            if count and np.min(np.hypot(*(kept[:count] - point).T)) < min_distance:
                continue
            kept[count], count = point, count + 1
            if count == n:
                return kept
        if count == before:
            break
    raise ValueError(f"could place only {count} of {n} clustered marks {min_distance:g} apart in a "
                     f"{width:g} x {height:g} region: lower n_elements or enlarge the region")


def irregular_exemplar(n_elements=100, *, width=12.0, height=12.0, rng=None,
                       max_elements=MAX_ELEMENTS) -> StrokePatternExemplar:
    """Small single-stroke marks at clearly non-uniform, clustered positions (synthetic).

    Positions come from dart throwing with a hard core of 0.5 from a clustered density (nine candidates
    in ten around one parent per 16 square units, Gaussian spread 0.6, the rest uniform), so dense clumps alternate with empty space: the irregularity that
    Barla's position variation has to reintroduce. Each mark is a gently bent stroke 0.25 long in a
    uniform random direction; ``position`` is the middle of its chord. ``epsilon = 0.1``.

    Parameters
    ----------
    n_elements : int
        Number of marks (>= 3).
    width, height : float
        Size of the region (> 0).
    rng : None, int or numpy.random.Generator
    max_elements : int, optional
        Budget: the most elements (default :data:`MAX_ELEMENTS`), checked before drawing.

    Returns
    -------
    StrokePatternExemplar
        Two-dimensional, one stroke per element, ``kind="mark"``.

    Raises
    ------
    ValueError
        On a count below 3, a region too small, or more marks than the clustered dart throwing can place.

    References
    ----------
    Barla et al. 2006, Figure 7 e and section 3.3 (position variation).
    """
    n = _count(n_elements, "n_elements", 3)
    check_budget(n, budget(max_elements, "max_elements"), "max_elements", "elements")
    width, height, region = _region(width, height, 4.0, max_elements)  # a clump parent per 16 square units
    rng = as_generator(rng)
    centers = _clustered_centers(n, width, height, 0.5, rng)
    centers = centers[_drawing_order(centers, 1.0)]
    angles = rng.uniform(0.0, np.pi, n)
    bends = rng.choice((-1.0, 1.0), n) * rng.uniform(0.015, 0.03, n)
    elements = [[_stroke(_arc(0.25, b), a, c, PEN_WIDTH)] for c, a, b in zip(centers, angles, bends)]
    params = _params_2d(centers, angles, np.full(n, 0.25), np.full(n, PEN_WIDTH), ["#000000"] * n, ["mark"] * n)
    return _exemplar(elements, params, dimension=2, epsilon=0.1, region=region,
                     description=f"synthetic irregular marks: {n} short strokes at clustered positions "
                                 "(stand-in for Barla 2006, Fig. 7e)")
