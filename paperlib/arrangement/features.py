"""Appearance features of stroke-based elements (Hurtut et al. 2009, section 2.1).

Hurtut et al. describe each element by five features taken from Julesz's texton theory (plus
area and elongation), and normalise each before comparison:

=====================  ===========================================  ================================
feature                measured on                                  normalisation
=====================  ===========================================  ================================
area                   the smallest rectangle holding the ink       / (5% of the reference area),
                                                                    capped at 1 ("large")
orientation            the box's major axis, angle in [0, pi)       / 2 pi, so in [0, 0.5)
elongation             box major over minor extent (>= 1)           / 3, capped at 1
                                                                    ("very elongated")
extremities            points of strong curvature of the strokes    / 10 (not capped)
crossings              crossings of the strokes within the element  / 10 (not capped)
=====================  ===========================================  ================================

The normalisations are the paper's, to the letter. The paper does not say in which range the
orientation lies; a box axis has no front, so it is ``[0, pi)`` and the normalised orientation
``[0, 0.5)``, a half of the unit interval left unused by the paper's ``2 pi``. Orientation is
circular (0 and pi are the same axis) and the feature ignores it, as the paper does. The paper
caps area and elongation only; counts above 10 give values above 1, and are left so. The
"large" and "very elongated" tags are the paper's: they record that the value was capped, and
have no other effect on the categorisation (a capped value of 1 is what the robust PCA sees).

The box of orientation and elongation is :func:`paperlib.geometry.oriented_bounding_boxes`,
fitted by PCA along the strokes (Barla et al. 2006, section 2.1); the area is that of the
smallest enclosing rectangle (:func:`minimum_box_areas`), which a hand's wobble cannot swing
round the way it swings the PCA axes of a near-isotropic glyph. By default it covers the pen's ink (``include_width=True``):
a straight stroke then has the area and the finite elongation it is seen with, not 0 and
infinity, so straight hatches of different lengths differ in area.

Extremities and crossings
-------------------------
The paper counts "the number of points of strong curvature along the elements' curves", which
"intuitively corresponds to the number of perceived extremities", and "the number of crossings
within each element", without further definition. Ours, measured in each element's own frame
(lengths as fractions of its box diagonal ``D``, so every count is invariant to translation,
rotation and scale):

*Curves.* Stroke ends closer than the join tolerance ``t = max(join_tolerance * D, pen width)``
form one node (inks closer than the pen's width touch: the bar of futural 'A' stops 0.3 grid
units short of the legs, inked over by its 1-unit pen). Two ends alone at a node are joined:
the strokes continue each other (the two strokes of an 'L', the seam of a closed 'o'), so
strokes chain into maximal curves, open or closed. Three ends or more make a junction.

*Extremities* are free ends, bends and dots:

- a free end is an end of an open curve alone at its node and touching no other curve (not
  within ``t`` of a segment, except along its own first ``2 t`` of arc): the stem of a 'T'
  ends on the bar and the tail of a '6' on its own bowl, so neither is free; ends at junctions
  are not free either;
- a bend is where the curve turns by more than ``corner_angle`` along an arc of length
  ``W = max(curvature_scale * D, pen width)``: the signed sum of the exterior angles at the
  vertices inside the open arc ``(s - W/2, s + W/2)``, the integral of the curvature over it,
  exceeds the angle in absolute value. Each maximal stretch of such window centres ``s`` is one
  extremity, and stretches closer than ``W`` (their windows see the same bend) are one. Being
  a total turn over a fixed length of arc, it does not depend on how finely the curve is
  digitised (inserting vertices changes nothing), an S-bend whose turns cancel is no corner,
  and nothing shorter than the pen is seen. On an open curve the windows stay on the curve
  (``W/2 <= s <= L - W/2``) and a bend reaching those limits belongs to the curve's end (a
  hook at the end of a stroke is not a second extremity). A closed curve bent all around, or
  not longer than ``W``, is a blob and counts once: a dot drawn as a little diamond, a tiny
  loop;
- a dot, a stroke of zero length, is one extremity (a warning says such strokes were met).

So a closed smooth curve ('o') has none, a square has four (one per corner), and 'L' (two free
ends and a corner) and 'T' (three free ends) both have three and no crossing: the two textons
Julesz found indiscriminable, while '+' (four, one crossing) and 'L' are told apart.

Defaults. ``corner_angle`` 60 degrees: over the default window, the smooth curves of futural's
letters and digits turn by at most 53 degrees ('s'; 45 in '6', '8', '9', 'S') and their corners
by 84 ('5') to 180 degrees, with nothing in between. ``curvature_scale`` 5%: a window shorter
than the distance between distinct corners of a glyph (a quarter of it or more), long enough to
smooth the digitisation of curves; at 10% the tighter curves of futural 'm', 'S' and '8' start
to count as corners. ``join_tolerance`` 1%: ends that close meet at any size the element is
viewed at.

*Crossings* are points where two curves, or two parts of one curve more than ``W`` of arc
apart, pass through each other: one of them splits the neighbourhood of the point in two and
the other has an arm on each side. The test works on the arms at the point, so a crossing
through a vertex counts as one in the middle of two segments. Not crossings: T-junctions (an
end on a curve), joins and junctions of ends, tangential touches, collinear overlaps, loops
shorter than ``W``, which are part of a bend, loops whose mean width (twice their area over their
length) is below half of ``t``, which the ink fills (a hairpin retraced by a hand), and points closer than ``t`` along a curve to the end
of an open curve: an end that overshoots another curve by less than the pen's width is a
T-junction drawn by a hand, as one that stops short of it is.

Crossings are then judged at the pen's scale, where a hand's wobble pushes strokes that meet in
the ink across each other (Hershey's complex faces, which draw a stem as parallel lines and a
serif as a stroke of its own, made the one-type control of a Times 'w' split at every seed): a
crossing stands only if the chords of both curves from ``2 t`` of arc before the point to ``2 t``
after still cross (a corner where two stroke ends join, poking through a serif, has both arms on
one side); not if one curve runs within ``t / 2`` of the other from the point to its nearer end
(a branch leaving a stroke at a shallow angle, the arch of a Times 'n'); and not, both of them, for
two consecutive crossings of the same two curves more than ``2 t`` apart between which one runs
within ``t / 2`` of the other (a curve drawn along another and pushed in and out of its ink, the
bowl of an italic 'a' on its stem). Crossings closer than ``2 t`` are one place: the three strokes
of '*' through one point make one crossing, and so does a bar across a stem drawn as two parallel
lines (0.3-1.3 ``t`` apart over the categorization test matrix; distinct crossings, as in '#', are
4.6 ``t`` apart or more).

*On the ink.* All of the above reads the pen's lines. Bold, triplex and sketchy drawings draw one
line the eye sees as several pen lines side by side, whose ends and mutual crossings that reading
counts one by one (a Times-bold 'c' reads 1-5 extremities, a bold 'x' 6-12). With
``topology="ink"`` the same counts are taken on the centrelines of the ink instead
(:func:`paperlib.arrangement.ink_centrelines`: skeleton of the pen's footprint, spurs removed,
crossings re-joined by good continuation, two forks of a shallow crossing joined where the pen's
lines, read as above, cross between them); ``"auto"`` (the default) does so when the arrangement's
median element is overdrawn (:func:`paperlib.arrangement.overdrawn_fraction` above 0.35), so
drawings made of single pen lines keep the reading above, unchanged. Reading every drawing on its
ink was measured and not kept: where a pen is thick for its glyph the ink closes small counters and
loops (the '8' of the Figure 3 top row, small 'z's, cursive loops: ARI 0 to 0.57 at seeds 0-4 on five
single-line cases of the test matrix). See :mod:`paperlib.arrangement.ink`.

Distances and turns within a relative ``1e-9`` of a threshold count as beyond or within it
respectively, so that ties in the data (Hershey glyphs live on an integer grid and the default
pen is one grid unit; a regular hexagon turns by exactly 60 degrees) are decided alike at any
position, rotation and scale: the counts of the glyphs of all 32 Hershey fonts are invariant.

Everything runs on all elements at once, each in its own frame and the frames laid side by
side so that they never meet: ends are merged with SciPy's ``cKDTree``; candidate pairs of
segments, and of ends and segments, come from a vectorised sweep and prune along x (shapely's
``STRtree`` gives the same pairs ten times slower for many small elements); segment
intersections, joining strokes into curves and measuring turns along them are written here with
NumPy, as no library does them on many polylines at once. Only the walk along joined strokes is
a Python loop, over strokes rather than vertices.

References
----------
.. [1] T. Hurtut, P.-E. Landes, J. Thollot, Y. Gousseau, R. Drouilhet, J.-F. Coeurjolly,
   "Appearance-guided Synthesis of Element Arrangements by Example", NPAR 2009, section 2.1
   (features and normalisation constants).
.. [2] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern Analysis and
   Synthesis", Computer Graphics Forum 25(3), 2006, section 2.1 (oriented box fitting).
.. [3] B. Julesz, "Texton gradients: the texton theory revisited", Biological Cybernetics 54,
   1986 (terminators and crossings as texton features).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import pandas as pd
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import ConvexHull, QhullError, cKDTree

from paperlib._checks import check_choice, finite_array, positive_number
from paperlib.geometry import (
    Element,
    StackedStrokes,
    oriented_bounding_boxes,
    resample_open_curve,
    signed_area,
    stack_strokes,
)

from .ink import ink_centrelines, reads_on_ink

__all__ = [
    "AREA_FRACTION",
    "COUNT_SCALE",
    "DEFAULT_CORNER_ANGLE",
    "DEFAULT_CURVATURE_SCALE",
    "DEFAULT_JOIN_TOLERANCE",
    "ELONGATION_CAP",
    "TOPOLOGY_READINGS",
    "ORIENTATION_PERIOD",
    "crossing_points",
    "element_features",
    "extremity_points",
    "minimum_box_areas",
    "normalized_area",
    "normalized_count",
    "normalized_elongation",
    "normalized_orientation",
]

#: Elements larger than this fraction of the reference surface are "large" (area feature 1).
AREA_FRACTION = 0.05
#: The orientation is divided by this.
ORIENTATION_PERIOD = 2.0 * np.pi
#: Elongations above this are "very elongated" (elongation feature 1).
ELONGATION_CAP = 3.0
#: Counts of extremities and of crossings are divided by this.
COUNT_SCALE = 10.0

DEFAULT_CURVATURE_SCALE = 0.05
DEFAULT_CORNER_ANGLE = np.pi / 3.0
DEFAULT_JOIN_TOLERANCE = 0.01
#: Where extremities and crossings can be read (``topology`` of :func:`element_features`).
TOPOLOGY_READINGS = ("auto", "strokes", "ink")

#: Intersection parameters this close to 0 or 1 are at the segment's vertex.
_VERTEX_SNAP = 1e-9
#: Distances (turns) within this relative margin of a threshold count as beyond (within) it, so
#: that exact ties in the data (Hershey glyphs live on an integer grid, a hexagon turns by exactly
#: 60 degrees) are decided alike at any pose and scale.
_TIE_MARGIN = 1e-9
#: Arms closer than this angle (radians) overlap: the curves touch or run together, they do not cross.
_ANGLE_TOLERANCE = 1e-9


# --------------------------------------------------------------------------- the area's box


def minimum_box_areas(elements, *, include_width: bool = True) -> np.ndarray:
    """Area of the smallest rectangle, at any angle, that holds each element (its ink by default).

    Hurtut et al. estimate the area "on [the element's] fitted bounding box" (section 2.1). The
    PCA box (:func:`~paperlib.geometry.oriented_bounding_boxes`) that gives orientation and
    elongation is the wrong box for it on a drawing: for a glyph whose two principal moments are
    close (a serif 'n', an 'x'), the hand's wobble swings the PCA axes by tens of degrees and the
    box's area with them, by up to x1.4 (measured on hand-drawn ``rowmans`` 'n': a log10-area
    spread of 0.076 against 0.034 for this box), which blurs area categories that are a factor 2
    in size apart. The smallest enclosing rectangle does not depend on an axis estimate.

    Parameters
    ----------
    elements : sequence of Element or StackedStrokes
        At least one element.
    include_width : bool, optional
        If true (default), the rectangle holds the pen's ink: each side is widened by the
        element's widest pen (its skeleton dilated by the largest half-width).

    Returns
    -------
    ndarray of float64, shape (n_elements,)
        The rectangles' areas, in the squared units of the coordinates.

    Notes
    -----
    Rotating calipers: the product of the two widths, each widened by the pen, is concave in the
    angle between two consecutive edge directions of the convex hull (Freeman and Shapira 1975,
    whose argument holds for widths plus a constant), so its minimum is at one of those
    directions; every direction of the hull is tried.
    """
    stack = elements if isinstance(elements, StackedStrokes) else stack_strokes(elements)
    offsets = stack.element_vertex_offsets
    half_pen = np.zeros(stack.n_elements)
    if include_width:
        np.maximum.at(half_pen, stack.stroke_element, stack.stroke_width / 2.0)
    return np.array([_smallest_rectangle_area(stack.vertices[offsets[e] : offsets[e + 1]], 2.0 * half_pen[e])
                     for e in range(stack.n_elements)])


def _smallest_rectangle_area(points: np.ndarray, pen: float) -> float:
    """Smallest ``(width + pen) * (height + pen)`` over the edge directions of the points' hull."""
    directions = _hull_edge_directions(points)
    along = points @ directions.T
    across = points @ np.column_stack([-directions[:, 1], directions[:, 0]]).T
    return float(np.min((np.ptp(along, axis=0) + pen) * (np.ptp(across, axis=0) + pen)))


def _hull_edge_directions(points: np.ndarray) -> np.ndarray:
    """Unit directions of the convex hull's edges; one direction for collinear or single points."""
    try:
        hull = ConvexHull(points)
    except QhullError:  # fewer than three points, or all on one line
        chord = points - points[0]
        far = chord[np.argmax(np.einsum("ij,ij->i", chord, chord))]
        length = np.hypot(*far)
        return (far / length)[None, :] if length > 0 else np.array([[1.0, 0.0]])
    ring = points[hull.vertices]
    edges = np.roll(ring, -1, axis=0) - ring
    return edges / np.hypot(edges[:, 0], edges[:, 1])[:, None]


# --------------------------------------------------------------------------- normalisations


def normalized_area(area, reference_area):
    """Box area over 5% of the reference surface, capped at 1 (Hurtut 2009, section 2.1).

    Parameters
    ----------
    area : float or array_like
        Box areas, in the units of ``reference_area``.
    reference_area : float
        Area of the reference arrangement's surface (> 0).

    Returns
    -------
    ndarray of float64
        ``min(area / (0.05 * reference_area), 1)``, the shape of ``area``, in ``[0, 1]`` for
        non-negative areas.
    """
    area = finite_array(area, "area", allow_infinite=True)
    return np.minimum(area / (AREA_FRACTION * positive_number(reference_area, "reference_area")), 1.0)


def normalized_orientation(angle):
    """Major-axis angle in ``[0, pi)`` over 2 pi, so in ``[0, 0.5)`` (Hurtut 2009, section 2.1).

    Parameters
    ----------
    angle : float or array_like
        Angles of the elements' major axes in radians, in ``[0, pi)``.

    Returns
    -------
    ndarray of float64
        ``angle / (2 pi)``, the shape of ``angle``.
    """
    return finite_array(angle, "angle") / ORIENTATION_PERIOD


def normalized_elongation(elongation):
    """Elongation over 3, capped at 1 (Hurtut 2009, section 2.1); infinite elongation gives 1.

    Parameters
    ----------
    elongation : float or array_like
        Elongations of the elements' oriented boxes (major over minor extent, >= 1;
        ``inf`` for a degenerate box).

    Returns
    -------
    ndarray of float64
        ``min(elongation / 3, 1)``, the shape of ``elongation``.
    """
    return np.minimum(finite_array(elongation, "elongation", allow_infinite=True) / ELONGATION_CAP, 1.0)


def normalized_count(count):
    """Number of extremities or crossings over 10, not capped (Hurtut 2009, section 2.1).

    Parameters
    ----------
    count : int or array_like of int
        Numbers of extremities or crossings of the elements (finite).

    Returns
    -------
    ndarray of float64
        ``count / 10``, the shape of ``count``.
    """
    return finite_array(count, "count") / COUNT_SCALE


# --------------------------------------------------------------------------- public API


def element_features(
    elements,
    reference_area,
    *,
    include_width: bool = True,
    curvature_scale: float = DEFAULT_CURVATURE_SCALE,
    corner_angle: float = DEFAULT_CORNER_ANGLE,
    join_tolerance: float = DEFAULT_JOIN_TOLERANCE,
    topology: str = "auto",
) -> pd.DataFrame:
    """The five appearance features of each element, normalised as Hurtut et al. do.

    Parameters
    ----------
    elements : sequence of Element
        At least one element.
    reference_area : float
        Area of the reference arrangement's surface (e.g. its window), in the elements' units.
    include_width : bool, optional
        Fit the boxes to the pen's ink rather than to the skeleton (default true; see the module
        docstring). Extremities and crossings do not depend on it.
    curvature_scale : float, optional
        Length ``W`` of the arcs along which turns are measured, as a fraction of the element's
        box diagonal (default 0.05); never less than the element's widest pen. In ``(0, 0.5)``.
    corner_angle : float, optional
        Turn along such an arc, in radians, above which the curve bends strongly there (default
        pi/3, 60 degrees). In ``(0, pi)``.
    join_tolerance : float, optional
        Distance below which stroke ends join or touch a stroke, as a fraction of the element's
        box diagonal (default 0.01); never less than the element's widest pen. In ``[0, 0.5)``.
    topology : {"auto", "strokes", "ink"}, optional
        Where extremities and crossings are read: along the pen's strokes (the paper's
        reading), along the centrelines of the ink (:func:`~paperlib.arrangement.ink_centrelines`),
        or, by default, on the ink when the arrangement's median element is overdrawn
        (:func:`~paperlib.arrangement.overdrawn_fraction` above 0.35: bold or sketchy lines drawn
        as several pen lines) and on the strokes otherwise. One reading for all the elements.

    Returns
    -------
    pandas.DataFrame
        One row per element, in order, with the normalised features ``area``, ``orientation``,
        ``elongation``, ``extremities``, ``crossings``, the paper's tags ``large`` and
        ``very_elongated``, and the raw values ``area_raw`` (box area), ``orientation_raw``
        (radians, ``[0, pi)``), ``elongation_raw`` (``inf`` for a straight stroke without
        width), ``extremities_raw`` and ``crossings_raw`` (counts), and ``length_raw``, the total
        length of the element's strokes (not one of the paper's features: the recursive
        categorization's witness, :func:`~paperlib.arrangement.categorize`). ``attrs`` records the
        parameters and ``topology_read_on`` (``"strokes"`` or ``"ink"``).

    Raises
    ------
    TypeError
        If an item is not an Element.
    ValueError
        If there are no elements, ``reference_area`` is not positive, or a parameter is out of
        range.

    Warns
    -----
    UserWarning
        If some strokes have zero length; each counts as a dot, one extremity.

    Notes
    -----
    Definitions of extremities and crossings, and the reasons for the default parameters, are
    in the module docstring. Features of 1e4 Hershey glyphs take a fraction of a second.

    References
    ----------
    .. [1] Hurtut et al. 2009, "Appearance-guided Synthesis of Element Arrangements by Example",
       section 2.1 and its table of normalisation constants.
    .. [2] Barla et al. 2006, "Stroke Pattern Analysis and Synthesis", section 2.1.
    """
    reference_area = positive_number(reference_area, "reference_area")
    stack = stack_strokes(elements)
    read_on = _topology_reading(elements, topology)
    boxes = oriented_bounding_boxes(stack, include_width=include_width)
    extremities, crossings = _measured_topology(
        lambda curves: (np.bincount(_extremities(curves)[1], minlength=stack.n_elements),
                        np.bincount(_crossings(curves)[1], minlength=stack.n_elements)),
        stack, elements, read_on, curvature_scale, corner_angle, join_tolerance)
    areas = minimum_box_areas(stack, include_width=include_width)
    angles, elongations = boxes.angles, boxes.elongations
    table = pd.DataFrame(
        {
            "area": normalized_area(areas, reference_area),
            "orientation": normalized_orientation(angles),
            "elongation": normalized_elongation(elongations),
            "extremities": normalized_count(extremities),
            "crossings": normalized_count(crossings),
            "large": areas > AREA_FRACTION * reference_area,
            "very_elongated": elongations > ELONGATION_CAP,
            "area_raw": areas,
            "orientation_raw": angles,
            "elongation_raw": elongations,
            "extremities_raw": extremities,
            "crossings_raw": crossings,
            "length_raw": stack.element_lengths,
        }
    )
    table.attrs.update(
        reference_area=reference_area,
        include_width=include_width,
        curvature_scale=curvature_scale,
        corner_angle=corner_angle,
        join_tolerance=join_tolerance,
        topology=topology,
        topology_read_on=read_on,
    )
    return table


def extremity_points(
    element,
    *,
    curvature_scale: float = DEFAULT_CURVATURE_SCALE,
    corner_angle: float = DEFAULT_CORNER_ANGLE,
    join_tolerance: float = DEFAULT_JOIN_TOLERANCE,
    topology: str = "auto",
) -> np.ndarray:
    """Where an element's extremities (points of strong curvature) are.

    Parameters
    ----------
    element : Element
    curvature_scale, corner_angle, join_tolerance, topology
        As for :func:`element_features`; ``"auto"`` decides on this element alone.

    Returns
    -------
    ndarray, shape (k, 2)
        Free ends, then bends (the middle of each bent stretch of curve; a blob at its first
        vertex), then dots, in the element's coordinates; ``k`` is the element's raw number of
        extremities.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.1 ("number of points of strong curvature").
    """
    return _one_element_topology(lambda curves: _extremities(curves)[0], element, topology, curvature_scale,
                                 corner_angle, join_tolerance)


def crossing_points(
    element,
    *,
    curvature_scale: float = DEFAULT_CURVATURE_SCALE,
    join_tolerance: float = DEFAULT_JOIN_TOLERANCE,
    topology: str = "auto",
) -> np.ndarray:
    """Where an element's strokes cross (each crossing once).

    Parameters
    ----------
    element : Element
    curvature_scale, join_tolerance, topology
        As for :func:`element_features`; ``"auto"`` decides on this element alone.

    Returns
    -------
    ndarray, shape (c, 2)
        Crossing points in the element's coordinates; ``c`` is the raw number of crossings.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.1 ("the number of crossings within each element").
    """
    return _one_element_topology(lambda curves: _crossings(curves)[0], element, topology, curvature_scale,
                                 DEFAULT_CORNER_ANGLE, join_tolerance)


def _one_element_topology(measure, element, topology, curvature_scale, corner_angle, join_tolerance):
    if not isinstance(element, Element):
        raise TypeError(f"element must be an Element, got {type(element).__name__}")
    read_on = _topology_reading([element], topology)
    return _measured_topology(measure, stack_strokes([element]), [element], read_on, curvature_scale, corner_angle,
                              join_tolerance)


def _topology_reading(elements, topology) -> str:
    """``"strokes"`` or ``"ink"``: where the elements' extremities and crossings are read."""
    check_choice(topology, TOPOLOGY_READINGS, "topology")
    if topology != "auto":
        return topology
    return "ink" if reads_on_ink(elements) else "strokes"


def _measured_topology(measure, stack, elements, read_on, curvature_scale, corner_angle, join_tolerance):
    """``measure(curves)`` on the curves of the strokes, or of the ink centrelines (read_on ``"ink"``)."""
    if read_on == "strokes":
        return measure(_build_curves(stack, curvature_scale, corner_angle, join_tolerance))
    with warnings.catch_warnings():
        # A dot of ink is a single-point centreline, one extremity: nothing to warn the user of.
        warnings.filterwarnings("ignore", message=r".*stroke\(s\) of zero length", category=UserWarning)
        # Where the pen's lines cross tells the ink which pairs of forks are one shallow crossing.
        points, owner = _crossings(_build_curves(stack, curvature_scale, corner_angle, join_tolerance))
        stack = stack_strokes([ink_centrelines(element, crossings=points[owner == k])
                               for k, element in enumerate(elements)])
        return measure(_build_curves(stack, curvature_scale, corner_angle, join_tolerance))


def _check_parameters(curvature_scale, corner_angle, join_tolerance) -> None:
    checks = (
        ("curvature_scale", curvature_scale, 0.0, 0.5, False),
        ("corner_angle", corner_angle, 0.0, np.pi, False),
        ("join_tolerance", join_tolerance, 0.0, 0.5, True),
    )
    for name, value, low, high, low_allowed in checks:
        ok = isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)
        ok = ok and np.isfinite(value) and (low <= value if low_allowed else low < value) and value < high
        if not ok:
            bracket = "[" if low_allowed else "("
            raise ValueError(f"{name} must be a number in {bracket}{low:g}, {high:g}), got {value!r}")


# --------------------------------------------------------------------------- strokes chained into curves


@dataclass(frozen=True, eq=False)
class _Curves:
    """The strokes of many elements chained into curves, in each element's normalised frame.

    Frame coordinates are an element's vertices minus its box centre, over its box diagonal, so
    every length here is a fraction of the element's size. Chain ``c`` visits the vertices
    ``entry_vertex[chain_offsets[c]:chain_offsets[c + 1]]`` in order; two joined stroke ends
    (and the repeated end of a closed stroke) are one entry.
    """

    stack: StackedStrokes
    frame: np.ndarray  # (n, 2) vertices in their element's frame
    layout: np.ndarray  # (n, 2) frames side by side along x, for the spatial searches
    window: np.ndarray  # (n_elements,) arc length W over which turns are measured
    tolerance: np.ndarray  # (n_elements,) join tolerance t
    corner_angle: float
    lonely_end: np.ndarray  # (n,) the vertex is a stroke end alone at its node
    entry_vertex: np.ndarray  # (m,)
    entry_chain: np.ndarray  # (m,)
    entry_arc: np.ndarray  # (m,) arc length from the chain's first entry
    vertex_entry: np.ndarray  # (n,) the entry of each vertex, -1 for dots
    vertex_arc: np.ndarray  # (n,) arc of each vertex along its chain (L for the closing vertex)
    chain_offsets: np.ndarray  # (c + 1,)
    chain_closed: np.ndarray  # (c,)
    chain_length: np.ndarray  # (c,)

    @cached_property
    def chain_element(self) -> np.ndarray:
        return self.stack.vertex_element[self.entry_vertex[self.chain_offsets[:-1]]]

    @cached_property
    def neighbour_entries(self) -> tuple[np.ndarray, np.ndarray]:
        """Previous and next entry along each entry's chain (wrapping if closed, -1 past an end)."""
        first, last = self.chain_offsets[:-1][self.entry_chain], self.chain_offsets[1:][self.entry_chain] - 1
        closed = self.chain_closed[self.entry_chain]
        index = np.arange(self.entry_vertex.size)
        previous = np.where(index > first, index - 1, np.where(closed, last, -1))
        following = np.where(index < last, index + 1, np.where(closed, first, -1))
        return previous, following


def _build_curves(stack: StackedStrokes, curvature_scale, corner_angle, join_tolerance) -> _Curves:
    _check_parameters(curvature_scale, corner_angle, join_tolerance)
    skeleton = oriented_bounding_boxes(stack)
    unit = np.where(skeleton.diagonals > 0, skeleton.diagonals, 1.0)  # a one-point element has no size
    vertex_element = stack.vertex_element
    frame = (stack.vertices - skeleton.centers[vertex_element]) / unit[vertex_element, None]
    widest_pen = np.zeros(stack.n_elements)
    np.maximum.at(widest_pen, stack.stroke_element, stack.stroke_width)
    # Nothing finer than the pen is seen: inks closer than its width touch, shorter turns are inked over.
    pen = widest_pen / unit
    window, tolerance = np.maximum(curvature_scale, pen), np.maximum(join_tolerance, pen)
    layout = frame + _layout_offsets(stack.n_elements, tolerance.max())[vertex_element]
    partner, lonely_end = _join_stroke_ends(stack, layout, tolerance)
    items, chain_closed = _walk_chains(partner, stack.stroke_offsets)
    entry_vertex, entry_chain, vertex_entry, closing_vertex = _chain_entries(stack, items, chain_closed)
    chain_offsets = np.concatenate([[0], np.cumsum(np.bincount(entry_chain, minlength=chain_closed.size))])
    entry_arc, chain_length = _chain_arcs(frame[entry_vertex], entry_chain, chain_offsets, chain_closed)
    vertex_arc = np.zeros(stack.vertices.shape[0])
    on_chain = vertex_entry >= 0
    vertex_arc[on_chain] = entry_arc[vertex_entry[on_chain]]
    vertex_arc[closing_vertex] = chain_length[entry_chain[vertex_entry[closing_vertex]]]
    return _Curves(
        stack=stack,
        frame=frame,
        layout=layout,
        window=window,
        tolerance=tolerance,
        corner_angle=float(corner_angle),
        lonely_end=lonely_end,
        entry_vertex=entry_vertex,
        entry_chain=entry_chain,
        entry_arc=entry_arc,
        vertex_entry=vertex_entry,
        vertex_arc=vertex_arc,
        chain_offsets=chain_offsets,
        chain_closed=chain_closed,
        chain_length=chain_length,
    )


def _layout_offsets(n_elements: int, tolerance: float) -> np.ndarray:
    """Offsets placing the element frames in a row along x, more than ``tolerance`` apart.

    A frame lies within half a diagonal, 1/2, of its origin, so frames ``2 + tolerance`` apart
    are never within the tolerance of each other, not even in x alone, which keeps the sweep of
    :func:`_overlapping_boxes` within elements.
    """
    return np.column_stack([(2.0 + tolerance) * np.arange(n_elements), np.zeros(n_elements)])


def _join_stroke_ends(stack: StackedStrokes, layout, tolerance):
    """Merge stroke ends closer than their element's ``tolerance`` into nodes.

    Stroke ``s`` has ends ``2 s`` (first vertex) and ``2 s + 1`` (last vertex). Returns the
    partner of each end when exactly two ends share a node (-1 otherwise), and a mask of the
    vertices that are stroke ends alone at their node. Dots (strokes of one vertex) take no part.
    """
    end_vertex = np.column_stack([stack.stroke_offsets[:-1], stack.stroke_offsets[1:] - 1]).ravel()
    ends = np.flatnonzero(np.repeat(np.diff(stack.stroke_offsets) > 1, 2))
    pairs = _close_pairs(layout[end_vertex[ends]], tolerance[stack.stroke_element[ends // 2]])
    _, node = connected_components(_adjacency(pairs, ends.size), directed=False)
    node_size = np.bincount(node)[node]
    partner = np.full(end_vertex.size, -1)
    joined = ends[pairs[node_size[pairs[:, 0]] == 2]]
    partner[joined[:, 0]], partner[joined[:, 1]] = joined[:, 1], joined[:, 0]
    lonely_end = np.zeros(stack.vertices.shape[0], dtype=bool)
    lonely_end[end_vertex[ends[node_size == 1]]] = True
    return partner, lonely_end


def _walk_chains(partner, stroke_offsets):
    """Chain the strokes joined end to end: rows ``(stroke, reversed, chain)`` and closed flags.

    Open chains are walked from an end without partner; what is left is cycles. This is the one
    Python loop of the module: it visits each stroke once, and elements have few strokes.
    """
    partner = partner.tolist()
    visited = (np.diff(stroke_offsets) <= 1).tolist()  # dots are no part of any chain
    items, closed = [], []

    def walk(stroke, forward):
        chain = len(closed)
        while True:
            visited[stroke] = True
            items.append((stroke, not forward, chain))
            next_end = partner[2 * stroke + (1 if forward else 0)]
            if next_end < 0 or visited[next_end // 2]:
                closed.append(next_end >= 0)
                return
            stroke, forward = next_end // 2, next_end % 2 == 0

    for end, other in enumerate(partner):
        if other < 0 and not visited[end // 2]:
            walk(end // 2, end % 2 == 0)
    for stroke, done in enumerate(visited):
        if not done:
            walk(stroke, True)
    return np.array(items, dtype=int).reshape(-1, 3), np.array(closed, dtype=bool)


def _chain_entries(stack: StackedStrokes, items, chain_closed):
    """Vertices of the chains in walking order, one entry per joined pair of ends.

    The first vertex of every stroke but the first of its chain is the joined end of the
    previous stroke, and the last vertex of a closed chain is its first: both are skipped and
    mapped to the entry they coincide with. Returns ``entry_vertex``, ``entry_chain``,
    ``vertex_entry`` (-1 for the vertices of dots) and the skipped closing vertices.
    """
    stroke, reverse, chain = items.T
    first_of_chain = _run_starts(chain)
    skip_first, skip_last = ~first_of_chain, _run_stops(chain) & chain_closed[chain]
    counts = np.diff(stack.stroke_offsets)[stroke] - skip_first - skip_last
    item_start = np.cumsum(counts) - counts
    item = np.repeat(np.arange(stroke.size), counts)
    step = np.arange(item.size) - item_start[item] + skip_first[item]
    low, high = stack.stroke_offsets[stroke], stack.stroke_offsets[stroke + 1] - 1
    entry_vertex = np.where(reverse[item], high[item] - step, low[item] + step)
    vertex_entry = np.full(stack.vertices.shape[0], -1)
    vertex_entry[entry_vertex] = np.arange(entry_vertex.size)
    vertex_entry[np.where(reverse, high, low)[skip_first]] = item_start[skip_first] - 1  # the previous entry
    closing_vertex = np.where(reverse, low, high)[skip_last]
    vertex_entry[closing_vertex] = item_start[first_of_chain][chain[skip_last]]  # the chain's first entry
    return entry_vertex, chain[item], vertex_entry, closing_vertex


def _chain_arcs(points, entry_chain, chain_offsets, chain_closed):
    """Arc length of every entry from its chain's first entry, and the length of every chain."""
    step = np.hypot(*np.diff(points, axis=0).T)
    step[entry_chain[1:] != entry_chain[:-1]] = 0.0
    arc = np.concatenate([[0.0], np.cumsum(step)])[: points.shape[0]]
    first, last = chain_offsets[:-1], chain_offsets[1:] - 1
    arc -= arc[first][entry_chain]
    closing = np.where(chain_closed, np.hypot(*(points[first] - points[last]).T), 0.0)
    return arc, arc[last] + closing


# --------------------------------------------------------------------------- extremities


def _extremities(curves: _Curves):
    """Free ends, bends and dots: their points ``(k, 2)`` and element indices ``(k,)``."""
    vertices, vertex_element = curves.stack.vertices, curves.stack.vertex_element
    free, dots = _free_ends(curves), _dots(curves)
    bends, bend_chain = _bends(curves)
    points = np.concatenate([vertices[free], bends, vertices[dots]])
    element = np.concatenate([vertex_element[free], curves.chain_element[bend_chain], vertex_element[dots]])
    return points, element


def _dots(curves: _Curves) -> np.ndarray:
    """Vertices of the strokes of zero length, each a dot (warns if there are any)."""
    dots = curves.stack.stroke_offsets[:-1][np.diff(curves.stack.stroke_offsets) == 1]
    if dots.size:
        warnings.warn(
            f"{dots.size} stroke(s) of zero length: each counted as a dot, one extremity and no crossing",
            UserWarning,
            stacklevel=4,
        )
    return dots


def _free_ends(curves: _Curves) -> np.ndarray:
    """Vertices ending an open curve alone at their node and touching no other curve."""
    open_chains = np.flatnonzero(~curves.chain_closed)
    heads, tails = curves.chain_offsets[open_chains], curves.chain_offsets[open_chains + 1] - 1
    entries, at_head = np.concatenate([heads, tails]), np.repeat([True, False], open_chains.size)
    lonely = curves.lonely_end[curves.entry_vertex[entries]]
    entries, at_head = entries[lonely], at_head[lonely]
    vertex, chain = curves.entry_vertex[entries], curves.entry_chain[entries]
    tolerance = curves.tolerance[curves.chain_element[chain]]
    end, segment = _ends_near_segments(curves.layout, vertex, tolerance, curves.stack.segment_starts)
    # The end's own first stretch of curve is where it is drawn from, not a touch.
    start_arc, stop_arc = curves.vertex_arc[segment], curves.vertex_arc[segment + 1]
    to_tail = curves.chain_length[chain[end]] - np.maximum(start_arc, stop_arc)
    from_end = np.where(at_head[end], np.minimum(start_arc, stop_arc), to_tail)
    own_curve = curves.entry_chain[curves.vertex_entry[segment]] == chain[end]
    touching = np.zeros(vertex.size, dtype=bool)
    touching[end[~(own_curve & _closer(from_end, 2.0 * tolerance[end]))]] = True
    return vertex[~touching]


def _bends(curves: _Curves):
    """Points of strong curvature inside the curves: their points ``(k, 2)`` and chains ``(k,)``.

    A bend is a maximal stretch of window centres ``s`` where the curve turns by more than the
    corner angle within the open arc ``(s - W/2, s + W/2)``; stretches closer than ``W`` are one
    bend. On an open curve the windows stay on the curve (``W/2 <= s <= L - W/2``) and a bend
    reaching those limits belongs to the curve's end. A closed curve bent all around, or not
    longer than ``W``, is a blob: one bend, at its first vertex. Other bends are located at the
    middle of their stretch (a sharp corner: at the corner).
    """
    window = curves.window[curves.chain_element]
    half = window * (1.0 - _TIE_MARGIN) / 2.0  # so that corners exactly W apart are two at any pose
    blob = curves.chain_closed & ~(2.0 * half < curves.chain_length)
    chain, low, high = _window_centre_intervals(curves, half, blob)
    middle = (low + high) / 2.0
    turn = _TurnIndex(curves, half).turn_within(chain, middle - half[chain], middle + half[chain])
    bent = np.abs(turn) > curves.corner_angle * (1.0 + _TIE_MARGIN)  # a hexagon turns by exactly 60 degrees
    stretches = _bent_stretches(chain, low, high, bent)
    bend_chain, bend_arc, all_around = _merge_stretches(curves, *stretches, window)
    blob[bend_chain[all_around]] = True
    inner = ~blob[bend_chain]
    blobs = np.flatnonzero(blob)
    blob_points = curves.stack.vertices[curves.entry_vertex[curves.chain_offsets[blobs]]]
    inner_points = _point_at_arc(curves, bend_chain[inner], bend_arc[inner], curves.stack.vertices)
    return np.concatenate([inner_points, blob_points]), np.concatenate([bend_chain[inner], blobs])


def _window_centre_intervals(curves: _Curves, half, blob):
    """Cut each chain's range of window centres where the window's content changes.

    The turn within ``(s - W/2, s + W/2)`` changes only when an end of the window crosses an
    entry, at ``s = a -+ W/2`` for the arc ``a`` of each entry: between consecutive cuts it is
    constant. Returns the chain, start and end of every interval, in chain and arc order, blobs
    left out. The ranges are ``[W/2, L - W/2]`` on open chains and ``[0, L]`` on closed ones.
    """
    length, closed = curves.chain_length, curves.chain_closed
    lowest, highest = np.where(closed, 0.0, half), np.where(closed, length, length - half)
    usable = ~blob & (lowest < highest)
    chain = np.tile(curves.entry_chain, 2)
    cut = np.concatenate([curves.entry_arc - half[curves.entry_chain], curves.entry_arc + half[curves.entry_chain]])
    period = np.where(length > 0, length, 1.0)[chain]  # a dot is a closed chain of length 0
    cut = np.where(closed[chain], np.mod(cut, period), cut)
    inside = usable[chain] & (cut > lowest[chain]) & (cut < highest[chain])
    ranged = np.flatnonzero(usable)
    chain = np.concatenate([chain[inside], ranged, ranged])
    cut = np.concatenate([cut[inside], lowest[ranged], highest[ranged]])
    order = np.lexsort((cut, chain))
    chain, cut = chain[order], cut[order]
    interval = (chain[1:] == chain[:-1]) & (cut[1:] > cut[:-1])
    return chain[:-1][interval], cut[:-1][interval], cut[1:][interval]


class _TurnIndex:
    """Signed turn of the chains within arcs, from cumulative exterior angles.

    The entries of all chains are laid on one axis, each chain in a stretch of its own three
    periods long, and closed chains repeated one period before and after, so that a window
    across the seam needs no care.
    """

    def __init__(self, curves: _Curves, half):
        length = curves.chain_length
        margin = float(half.max(initial=0.0)) + 1.0
        span = 3.0 * length + 2.0 * margin
        self.origin = np.cumsum(span) - span + margin + length  # arc 0 of the middle period
        chain, arc, turn = curves.entry_chain, curves.entry_arc, _signed_turns(curves)
        periodic = np.flatnonzero(curves.chain_closed[chain])
        copy = np.concatenate([np.arange(chain.size), periodic, periodic])
        shift = np.concatenate([np.zeros(chain.size), -length[chain[periodic]], length[chain[periodic]]])
        position = self.origin[chain[copy]] + arc[copy] + shift
        order = np.argsort(position, kind="stable")
        self.axis = position[order]
        self.cumulative = np.concatenate([[0.0], np.cumsum(turn[copy][order])])

    def turn_within(self, chain, low, high) -> np.ndarray:
        """Sum of the exterior angles at the entries with arc strictly between ``low`` and ``high``."""
        origin = self.origin[chain]
        after_low = np.searchsorted(self.axis, origin + low, side="right")
        before_high = np.searchsorted(self.axis, origin + high, side="left")
        return self.cumulative[before_high] - self.cumulative[after_low]


def _signed_turns(curves: _Curves) -> np.ndarray:
    """Signed exterior angle at every entry, in ``[-pi, pi]``: 0 at the ends of open chains."""
    previous, following = curves.neighbour_entries
    point = curves.frame[curves.entry_vertex]
    incoming, outgoing = point - point[previous], point[following] - point
    cross = incoming[:, 0] * outgoing[:, 1] - incoming[:, 1] * outgoing[:, 0]
    dot = np.einsum("ij,ij->i", incoming, outgoing)
    return np.where((previous >= 0) & (following >= 0), np.arctan2(cross, dot), 0.0)


def _bent_stretches(chain, low, high, bent):
    """Runs of consecutive bent intervals: chain, start, end, and which ends of the range they reach."""
    label = np.where(bent, chain, -1)  # runs of equal labels are bent intervals of one chain
    start, stop = np.flatnonzero(bent & _run_starts(label)), np.flatnonzero(bent & _run_stops(label))
    reaches = np.column_stack([_run_starts(chain)[start], _run_stops(chain)[stop]])
    return chain[start], low[start], high[stop], reaches


def _merge_stretches(curves: _Curves, chain, low, high, reaches, window):
    """Bends from the bent stretches: their chain, middle arc, and whether they go all around.

    Stretches of a chain closer than a window (their windows see the same bend) merge, across
    the seam of a closed chain too. On an open chain, bends reaching an end of the range belong
    to that end of the curve and are dropped.
    """
    close_to_previous = (chain[1:] == chain[:-1]) & _closer(low[1:] - high[:-1], window[chain[1:]])
    group = np.cumsum(np.r_[True, ~close_to_previous][: chain.size])
    first, last = np.flatnonzero(_run_starts(group)), np.flatnonzero(_run_stops(group))
    chain, low, high = chain[first], low[first], high[last]
    reaches_start, reaches_stop = reaches[first, 0], reaches[last, 1]
    length, closed = curves.chain_length[chain], curves.chain_closed[chain]
    head, tail = np.flatnonzero(_run_starts(chain)), np.flatnonzero(_run_stops(chain))
    across_seam = closed[head] & _closer(length[tail] - high[tail] + low[head], window[chain[head]])
    all_around = np.zeros(chain.size, dtype=bool)
    all_around[head[across_seam & (head == tail)]] = True
    merge = across_seam & (head != tail)
    low[head[merge]] = low[tail[merge]] - length[tail[merge]]
    keep = closed | ~(reaches_start | reaches_stop)
    keep[tail[merge]] = False
    middle = np.mod((low + high) / 2.0, length)
    return chain[keep], middle[keep], all_around[keep]


def _point_at_arc(curves: _Curves, chain, arc, coordinates) -> np.ndarray:
    """Points of ``coordinates`` (per vertex) interpolated at arc positions along chains.

    Chains are laid end to end on one axis so that a single ``np.interp`` serves them all; a
    closed chain gets its first point again at arc L. Frame and element coordinates differ by a
    similarity, so frame arcs interpolate either.
    """
    if chain.size == 0:  # np.interp refuses an empty table even for no points
        return np.zeros((0, 2))
    closed_chains = np.flatnonzero(curves.chain_closed)
    offset = np.cumsum(curves.chain_length + 1.0) - (curves.chain_length + 1.0)
    axis = np.concatenate(
        [offset[curves.entry_chain] + curves.entry_arc, offset[closed_chains] + curves.chain_length[closed_chains]]
    )
    vertices = np.concatenate([curves.entry_vertex, curves.entry_vertex[curves.chain_offsets[closed_chains]]])
    order = np.argsort(axis, kind="stable")
    position = offset[chain] + arc
    return np.column_stack([np.interp(position, axis[order], coordinates[vertices[order], k]) for k in range(2)])


# --------------------------------------------------------------------------- crossings


def _crossings(curves: _Curves):
    """Points where curves cross, one per group closer than the tolerance, and their elements."""
    starts = curves.stack.segment_starts
    first, second = starts[_overlapping_boxes(*_segment_boxes(curves.layout, starts))].T
    t, u, proper = _line_parameters(curves.frame, first, second)
    first, second, t, u = first[proper], second[proper], t[proper], u[proper]
    crossing = _arms_alternate(curves, first, t, second, u) & ~_same_bend(curves, first, t, second, u)
    crossing &= _cross_at_pen_scale(curves, first, t, second, u)
    crossing &= ~(_near_an_end(curves, first, t) | _near_an_end(curves, second, u))
    for inked_over in (_inked_loop, _an_end_runs_along, _in_and_out_of_the_ink):  # loops: run on the survivors
        crossing[crossing] = ~inked_over(curves, first[crossing], t[crossing], second[crossing], u[crossing])
    first, t = first[crossing], t[crossing]
    element = curves.stack.vertex_element[first]
    layout = curves.layout[first] + t[:, None] * (curves.layout[first + 1] - curves.layout[first])
    # Crossings closer than two pens are one place of ink: a stroke crossing a thick stem that a complex
    # face draws as two or three parallel lines (Hershey's timesr, scriptc) crosses each line, 0.3-1.3
    # tolerances apart over the test matrix, while distinct crossings ('#') are 4.6 or more apart.
    kept = _one_per_cluster(layout, 2.0 * curves.tolerance[element])
    vertices = curves.stack.vertices
    return vertices[first[kept]] + t[kept, None] * (vertices[first[kept] + 1] - vertices[first[kept]]), element[kept]


def _line_parameters(frame, first, second):
    """Parameters ``t``, ``u`` of the intersection of segments ``v -> v + 1``, snapped to vertices.

    ``proper`` is false for parallel segments (collinear overlaps are not crossings) and for
    intersections outside the segments (the candidates only have overlapping boxes).
    """
    a, b = frame[first], frame[second]
    da, db = frame[first + 1] - a, frame[second + 1] - b
    offset = b - a
    denominator = da[:, 0] * db[:, 1] - da[:, 1] * db[:, 0]
    parallel = np.abs(denominator) <= 1e-12 * np.hypot(*da.T) * np.hypot(*db.T)
    safe = np.where(parallel, 1.0, denominator)
    t = _snap_to_vertex((offset[:, 0] * db[:, 1] - offset[:, 1] * db[:, 0]) / safe)
    u = _snap_to_vertex((offset[:, 0] * da[:, 1] - offset[:, 1] * da[:, 0]) / safe)
    proper = ~parallel & (t >= 0) & (t <= 1) & (u >= 0) & (u <= 1)
    return t, u, proper


def _snap_to_vertex(parameter):
    parameter = np.where(np.abs(parameter) <= _VERTEX_SNAP, 0.0, parameter)
    return np.where(np.abs(parameter - 1.0) <= _VERTEX_SNAP, 1.0, parameter)


def _arms(curves: _Curves, segment_start, t):
    """The two arms of a curve leaving the point at parameter ``t`` of segment ``v -> v + 1``.

    Inside a segment the arms are its two halves; at a vertex they go to the previous and the
    next entry of the chain. ``valid`` is false at an open chain's end, which has one arm.
    """
    frame = curves.frame
    direction = frame[segment_start + 1] - frame[segment_start]
    at_vertex = (t == 0) | (t == 1)
    entry = curves.vertex_entry[np.where(t == 1, segment_start + 1, segment_start)]
    previous, following = curves.neighbour_entries
    before, after = previous[entry], following[entry]
    centre = frame[curves.entry_vertex[entry]]
    back = np.where(at_vertex[:, None], frame[curves.entry_vertex[before]] - centre, -direction)
    ahead = np.where(at_vertex[:, None], frame[curves.entry_vertex[after]] - centre, direction)
    return back, ahead, ~at_vertex | ((before >= 0) & (after >= 0))


def _arms_alternate(curves: _Curves, first, t, second, u) -> np.ndarray:
    """True where the second curve has an arm on each side of the first one: they cross."""
    back_a, ahead_a, valid_a = _arms(curves, first, t)
    back_b, ahead_b, valid_b = _arms(curves, second, u)
    start = np.arctan2(back_a[:, 1], back_a[:, 0])

    def angle_from_start(arm):  # counter-clockwise from the first curve's back arm, in [0, 2 pi)
        return np.mod(np.arctan2(arm[:, 1], arm[:, 0]) - start, 2.0 * np.pi)

    split, angle_b1, angle_b2 = angle_from_start(ahead_a), angle_from_start(back_b), angle_from_start(ahead_b)
    on_first_curve = _along_arms(angle_b1, split) | _along_arms(angle_b2, split)
    opposite_sides = (angle_b1 < split) != (angle_b2 < split)
    return valid_a & valid_b & opposite_sides & ~on_first_curve


def _along_arms(angle, split) -> np.ndarray:
    """True for angles (from the first arm, in ``[0, 2 pi)``) along the first or the second arm."""
    along_first = (angle <= _ANGLE_TOLERANCE) | (angle >= 2.0 * np.pi - _ANGLE_TOLERANCE)
    return along_first | (np.abs(angle - split) <= _ANGLE_TOLERANCE)


def _cross_at_pen_scale(curves: _Curves, first, t, second, u) -> np.ndarray:
    """True where the curves still cross when seen at the pen's scale, twice the join tolerance.

    Each curve is replaced, around the crossing, by its chord from the point ``2 t`` of arc before
    to the point ``2 t`` after (clamped to an open curve's ends): the crossing stands when the two
    chords cross. A stroke end that meets another stroke at a corner where it joins a third (the
    stem and serif of a complex face, Hershey's ``timesr``) pokes through that stroke by less than
    the pen when a hand draws it: the raw curves cross, but both arms of the corner stay on one
    side, and the eye sees a junction. Crossings whose curves part at a shallow angle stand as long
    as the chords cross: whether the curves part is the business of :func:`_an_end_runs_along` and
    :func:`_in_and_out_of_the_ink`.
    """
    tolerance = curves.tolerance[curves.stack.vertex_element[first]]
    chords = [_chord_around(curves, start, parameter, 2.0 * tolerance) for start, parameter in ((first, t), (second, u))]
    (a0, a1), (b0, b1) = chords
    return _strictly_opposite(a0, a1, b0, b1) & _strictly_opposite(b0, b1, a0, a1)


def _chord_around(curves: _Curves, segment_start, t, reach):
    """The points ``reach`` of arc before and after the point, along its chain (clamped, or wrapped if closed)."""
    chain = curves.entry_chain[curves.vertex_entry[segment_start]]
    arc, length = _arc_at(curves, segment_start, t), curves.chain_length[chain]
    closed = curves.chain_closed[chain]
    ends = []
    for sign in (-1.0, 1.0):
        shifted = arc + sign * reach
        shifted = np.where(closed, np.mod(shifted, np.where(length > 0, length, 1.0)), np.clip(shifted, 0.0, length))
        ends.append(_point_at_arc(curves, chain, shifted, curves.frame))
    return ends


def _strictly_opposite(p, q, a, b) -> np.ndarray:
    """True where ``a`` and ``b`` lie strictly on opposite sides of the line through ``p`` and ``q``."""
    direction = q - p
    side_a = direction[:, 0] * (a - p)[:, 1] - direction[:, 1] * (a - p)[:, 0]
    side_b = direction[:, 0] * (b - p)[:, 1] - direction[:, 1] * (b - p)[:, 0]
    return side_a * side_b < 0.0


def _same_bend(curves: _Curves, first, t, second, u) -> np.ndarray:
    """True where both points lie on one chain less than ``W`` of arc apart (a loop in a bend)."""
    chain_a = curves.entry_chain[curves.vertex_entry[first]]
    chain_b = curves.entry_chain[curves.vertex_entry[second]]
    gap = np.abs(_arc_at(curves, first, t) - _arc_at(curves, second, u))
    length = curves.chain_length[chain_a]
    gap = np.where(curves.chain_closed[chain_a], np.minimum(gap, length - gap), gap)
    return (chain_a == chain_b) & _closer(gap, curves.window[curves.chain_element[chain_a]])


def _inked_loop(curves: _Curves, first, t, second, u) -> np.ndarray:
    """True where both points lie on one chain and the loop between them is filled by the ink.

    The loop (the shorter of the two, on a closed chain) is the curve's arc from one point to the
    other, closed by the point itself; its mean width is ``2 A / P`` (area over half the arc
    length; a round loop's radius). Below half the join tolerance (the pen's width at least), a
    round loop's hole is covered by the pen and the two sides of a thin one are one line of ink:
    a hairpin retraced by a wobbling hand (the stem of a cursive 'a' drawn up and back down)
    crosses itself where the eye sees a cusp and no hole. Over the categorization test matrix
    (all families, seed 0) the loops of self-crossings fall in two clusters, 0.02-0.3 and
    1.8-6.8 times the tolerance (hairpins, and the loops of '8', 'g', '&', cursive 'l'), on
    either side of the threshold.
    """
    chain = curves.entry_chain[curves.vertex_entry[first]]
    same = chain == curves.entry_chain[curves.vertex_entry[second]]
    inked = np.zeros(first.size, dtype=bool)
    arcs = np.sort(np.column_stack([_arc_at(curves, first, t), _arc_at(curves, second, u)]), axis=1)
    for k in np.flatnonzero(same):
        c, (low, high) = chain[k], arcs[k]
        entries = np.arange(curves.chain_offsets[c], curves.chain_offsets[c + 1])
        arc, points = curves.entry_arc[entries], curves.frame[curves.entry_vertex[entries]]
        length = curves.chain_length[c]
        inside = (arc > low) & (arc < high)
        if curves.chain_closed[c] and high - low > length - high + low:  # the other way round is shorter
            inside, low, high = ~inside & (arc != low) & (arc != high), high, low + length
        loop = np.concatenate([points[inside & (arc >= low)], points[inside & (arc < low)]])
        corner = _point_at_arc(curves, np.array([c]), np.array([np.mod(low, length)]), curves.frame)
        ring = np.concatenate([corner, loop])
        area = abs(signed_area(ring))
        inked[k] = _closer(2.0 * area / (high - low), curves.tolerance[curves.chain_element[c]] / 2.0)
    return inked


def _near_an_end(curves: _Curves, segment_start, t) -> np.ndarray:
    """True where the point is closer than the join tolerance, along its curve, to an open curve's end.

    An end that overshoots a curve by less than the tolerance (the pen's width at least) is an end
    on that curve, a T-junction inked over, as an end that stops short of it by as much is.
    """
    chain = curves.entry_chain[curves.vertex_entry[segment_start]]
    arc = _arc_at(curves, segment_start, t)
    tolerance = curves.tolerance[curves.chain_element[chain]]
    near = _closer(arc, tolerance) | _closer(curves.chain_length[chain] - arc, tolerance)
    return ~curves.chain_closed[chain] & near


def _an_end_runs_along(curves: _Curves, first, t, second, u) -> np.ndarray:
    """True where either curve runs inside the other's ink from the point to its nearer end."""
    return _end_runs_along(curves, first, t, second, u) | _end_runs_along(curves, second, u, first, t)


def _end_runs_along(curves: _Curves, first, t, second, u) -> np.ndarray:
    """True where the first curve, from the point to its nearer open end, runs inside the second's ink.

    A stroke that branches off another at a shallow angle (the arch of a complex face's 'n' leaving its
    stem) runs within ``t / 2`` of it for a while before it parts: a hand's wobble makes the two cross
    anywhere along that stretch, and the eye sees the branch's end joined to the other stroke, the
    junction of :func:`_near_an_end` drawn long. On a self-crossing the other curve is the rest of the
    chain, beyond the point.
    """
    chain_a = curves.entry_chain[curves.vertex_entry[first]]
    chain_b = curves.entry_chain[curves.vertex_entry[second]]
    arc = _arc_at(curves, first, t)
    along = np.zeros(first.size, dtype=bool)
    for k in np.flatnonzero(~curves.chain_closed[chain_a]):
        a, b, length = chain_a[k], chain_b[k], curves.chain_length[chain_a[k]]
        near_end, far_end = (0.0, length) if arc[k] < length / 2.0 else (length, 0.0)
        if a == b:
            other = _stretch_between(curves, a, arc[k], far_end)
        else:
            other = curves.frame[curves.entry_vertex[np.arange(curves.chain_offsets[b], curves.chain_offsets[b + 1])]]
            other = np.concatenate([other, other[:1]]) if curves.chain_closed[b] else other
        tolerance = curves.tolerance[curves.chain_element[a]]
        along[k] = _runs_inside(_stretch_between(curves, a, arc[k], near_end), other, tolerance)
    return along


def _in_and_out_of_the_ink(curves: _Curves, first, t, second, u) -> np.ndarray:
    """True for pairs of crossings of the same two curves between which they run inside each other's ink.

    A curve drawn along another (the bowl of an italic 'a' closing on its stem, Hershey's ``timesi``)
    is pushed across it and back by the hand: two crossings, more than two tolerances apart (closer,
    they are one place, see :func:`_crossings`), with one curve's stretch between them within half
    the tolerance of the other's, where the eye sees one line of ink touching another. Crossings
    consecutive along a curve are compared; both are dropped.
    """
    chain = curves.entry_chain[curves.vertex_entry[np.stack([first, second])]]
    arc = np.stack([_arc_at(curves, first, t), _arc_at(curves, second, u)])
    swap = (chain[0] > chain[1]) | ((chain[0] == chain[1]) & (arc[0] > arc[1]))
    chain[:, swap], arc[:, swap] = chain[::-1, swap], arc[::-1, swap]
    touch = np.zeros(first.size, dtype=bool)
    order = np.lexsort((arc[0], chain[1], chain[0]))
    same_pair = np.all(chain[:, order[1:]] == chain[:, order[:-1]], axis=0)
    for i, j in zip(order[:-1][same_pair], order[1:][same_pair]):
        tolerance = curves.tolerance[curves.chain_element[chain[0, i]]]
        stretches = [_stretch_between(curves, chain[k, i], arc[k, i], arc[k, j]) for k in (0, 1)]
        if min(_polyline_length(stretch) for stretch in stretches) <= 2.0 * tolerance:
            continue
        if any(_runs_inside(stretches[k], stretches[1 - k], tolerance) for k in (0, 1)):
            touch[[i, j]] = True
    return touch


def _runs_inside(stretch, other, tolerance) -> bool:
    """True if every point of the polyline ``stretch`` lies within ``tolerance / 2`` of the polyline ``other``.

    The stretch is sampled every quarter tolerance, so that a long straight segment is judged along
    its length, not at its ends only.
    """
    length = _polyline_length(stretch)
    if length > 0:
        stretch = resample_open_curve(stretch, int(np.ceil(4.0 * length / tolerance)) + 1)
    return bool(np.all(_closer(_distance_to_polyline(stretch, other), tolerance / 2.0)))


def _stretch_between(curves: _Curves, chain, low, high) -> np.ndarray:
    """The polyline of a chain from one arc to another (the shorter way round a closed chain), ends included."""
    entries = np.arange(curves.chain_offsets[chain], curves.chain_offsets[chain + 1])
    arc, length = curves.entry_arc[entries], curves.chain_length[chain]
    low, high = min(low, high), max(low, high)
    inner = entries[(arc > low) & (arc < high)]
    if curves.chain_closed[chain] and high - low > length / 2.0:  # through the seam: from high on, then to low
        inner, low, high = np.concatenate([entries[arc > high], entries[arc < low]]), high, low
    ends = _point_at_arc(curves, np.array([chain, chain]), np.array([low, high]), curves.frame)
    return np.concatenate([ends[:1], curves.frame[curves.entry_vertex[inner]], ends[1:]])


def _polyline_length(points) -> float:
    return float(np.hypot(*np.diff(points, axis=0).T).sum())


def _distance_to_polyline(points, polyline) -> np.ndarray:
    """Distance from each point ``(k, 2)`` to the polyline ``(m, 2)`` (a single vertex: to that point)."""
    if polyline.shape[0] == 1:
        return np.hypot(*(points - polyline[0]).T)
    start, step = polyline[:-1], np.diff(polyline, axis=0)
    offset = points[:, None, :] - start[None, :, :]
    squared = np.einsum("ij,ij->i", step, step)
    along = np.clip(np.einsum("kij,ij->ki", offset, step) / np.where(squared > 0, squared, 1.0), 0.0, 1.0)
    gap = offset - along[:, :, None] * step[None, :, :]
    return np.sqrt(np.min(np.einsum("kij,kij->ki", gap, gap), axis=1))


def _arc_at(curves: _Curves, segment_start, t) -> np.ndarray:
    start_arc, stop_arc = curves.vertex_arc[segment_start], curves.vertex_arc[segment_start + 1]
    return start_arc + t * (stop_arc - start_arc)


# --------------------------------------------------------------------------- array helpers


def _closer(distance, threshold):
    """``distance < threshold``, ties up to rounding excluded (see ``_TIE_MARGIN``)."""
    return distance < threshold * (1.0 - _TIE_MARGIN)


def _run_starts(labels) -> np.ndarray:
    """True where a run of equal consecutive labels starts."""
    return np.r_[True, labels[1:] != labels[:-1]][: labels.size]


def _run_stops(labels) -> np.ndarray:
    """True where a run of equal consecutive labels ends."""
    return np.r_[labels[1:] != labels[:-1], True][: labels.size]


def _adjacency(pairs, n_nodes):
    return coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n_nodes, n_nodes))


def _close_pairs(points, tolerance) -> np.ndarray:
    """Pairs ``(i, j)``, ``i < j``, of points closer than the tolerance of point ``i``.

    The tolerance is per element and points of different elements are never that close in
    layout coordinates, so either point's tolerance will do.
    """
    if points.shape[0] == 0:
        return np.zeros((0, 2), dtype=int)
    pairs = cKDTree(points).query_pairs(tolerance.max(), output_type="ndarray")
    distance = np.hypot(*(points[pairs[:, 0]] - points[pairs[:, 1]]).T)
    return pairs[_closer(distance, tolerance[pairs[:, 0]])]


def _one_per_cluster(points, tolerance) -> np.ndarray:
    """Index of one point of each group of points chained closer than their tolerance."""
    _, cluster = connected_components(_adjacency(_close_pairs(points, tolerance), points.shape[0]), directed=False)
    return np.unique(cluster, return_index=True)[1]


def _segment_boxes(points, starts):
    """Lower and upper corners of the axis-aligned boxes of segments ``v -> v + 1``."""
    a, b = points[starts], points[starts + 1]
    return np.minimum(a, b), np.maximum(a, b)


def _overlapping_boxes(lower, upper) -> np.ndarray:
    """Pairs ``(i, j)`` of axis-aligned boxes that overlap (touching counts), each pair once.

    Sweep and prune along x: with the boxes sorted by their left side, two boxes overlap in x
    exactly when the left side of the later one lies within the x-range of the earlier one, so
    the candidates of each box are a contiguous run of the sorted boxes after it; the y ranges
    then prune. Vectorised, it takes 0.03 s for the 1e5 segments of 1e4 glyphs, where shapely's
    ``STRtree`` takes 0.3 s: the layout keeps elements apart in x.
    """
    order = np.argsort(lower[:, 0], kind="stable")
    stop = np.searchsorted(lower[order, 0], upper[order, 0], side="right")
    count = stop - np.arange(1, order.size + 1)
    owner = np.repeat(np.arange(order.size), count)
    other = owner + 1 + np.arange(owner.size) - np.repeat(np.cumsum(count) - count, count)
    i, j = order[owner], order[other]
    overlap_y = (lower[i, 1] <= upper[j, 1]) & (lower[j, 1] <= upper[i, 1])
    return np.column_stack([i, j])[overlap_y]


def _ends_near_segments(layout, vertex, tolerance, segment_starts):
    """Pairs (index into ``vertex``, segment start) of ends closer than their tolerance to a segment."""
    points = layout[vertex]
    lower, upper = _segment_boxes(layout, segment_starts)
    reach = tolerance[:, None]
    boxes = np.concatenate([lower, points - reach]), np.concatenate([upper, points + reach])
    pairs = np.sort(_overlapping_boxes(*boxes))
    n_segments = segment_starts.size
    pairs = pairs[(pairs[:, 0] < n_segments) & (pairs[:, 1] >= n_segments)]  # a segment and an end
    segment, end = segment_starts[pairs[:, 0]], pairs[:, 1] - n_segments
    a, b = layout[segment], layout[segment + 1]
    along = np.clip(np.einsum("ij,ij->i", points[end] - a, b - a) / np.einsum("ij,ij->i", b - a, b - a), 0.0, 1.0)
    distance = np.hypot(*(a + along[:, None] * (b - a) - points[end]).T)
    close = _closer(distance, tolerance[end])
    return end[close], segment[close]
