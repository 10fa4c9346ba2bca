"""Analysis of a reference stroke pattern: element fitting, clustering, distribution (Barla 2006, section 2).

The three steps of section 2:

1. **Element fitting** (2.1): each stroke gets an oriented bounding box whose axes are the eigenvectors of
   its points' covariance (:func:`paperlib.geometry.oriented_bounding_boxes`); on the skeleton (the gesture)
   or, with ``contour=True``, on the region the pen covers, so stroke width counts.
2. **Clustering** (2.2): a greedy pass over the strokes in drawing order merges elements that meet the
   proximity measure (2.2.1, Hausdorff distance between boxes) or the continuation measure (2.2.2,
   near-collinear boxes with a small gap along the axis) against the user scale epsilon; a merged element is
   refitted on the union of its strokes.
3. **Distribution** (2.3): neighbours along a chain for 1D patterns; for 2D patterns the edges of a Delaunay
   triangulation of the element centres that belong to at least one unskewed triangle (no angle above
   2 pi / 3); the shift vector S_ref from the barycentre of an element's neighbours to the element.

Everything measured on boxes is vectorised over the elements still in the queue; no library offers Barla's
measures, so they are written here with NumPy on top of :mod:`paperlib.geometry`.

References
----------
.. [1] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern Analysis and Synthesis",
   Computer Graphics Forum (Eurographics) 25(3), 2006, section 2.
.. [2] A. Etemadi, J.-P. Schmidt, G. Matas, J. Illingworth, J. Kittler, "Low-level grouping of straight line
   segments", BMVC 1991 (the proximity and continuation criteria Barla et al. build on).
"""

from __future__ import annotations

from dataclasses import dataclass
from numbers import Real

import numpy as np
import shapely
from matplotlib.colors import to_rgb
from scipy.spatial import Delaunay, QhullError

from .._checks import check_edges, float_array, instance_of, label, point_array, positive_number
from ..geometry import (
    Element,
    OrientedBoxes,
    Stroke,
    as_points,
    directed_hausdorff_boxes,
    oriented_bounding_boxes,
)

__all__ = [
    "PatternAnalysis",
    "analyze",
    "as_region",
    "chain_edges",
    "cluster_strokes",
    "continuation",
    "fit_elements",
    "proximity",
    "shift_vectors",
    "unskewed_delaunay_edges",
]

#: Largest angle of an unskewed triangle (section 2.3).
MAX_UNSKEWED_ANGLE = 2.0 * np.pi / 3.0
#: Two boxes whose bounding circles are farther apart than this many epsilons can meet neither measure:
#: proximity needs a box distance below epsilon, continuation one below sqrt(1 + 1/4) epsilon.
_CANDIDATE_REACH = 1.25


# --------------------------------------------------------------------------- strokes in


def as_strokes(strokes, *, min_count: int = 2) -> tuple:
    """The strokes of a pattern as a tuple, in drawing order.

    Accepts a sequence of :class:`~paperlib.geometry.Stroke`, or of :class:`~paperlib.geometry.Element`
    (e.g. from :func:`paperlib.geometry.read_svg`), whose strokes are taken in order.
    """
    if isinstance(strokes, (Stroke, Element)):
        raise ValueError(f"strokes must be a sequence of strokes (or elements), got a single {type(strokes).__name__}: "
                         "wrap it in a list")
    if isinstance(strokes, (str, bytes)) or not hasattr(strokes, "__iter__"):
        raise ValueError(f"strokes must be a sequence of Strokes (or Elements), got {type(strokes).__name__}")
    flat = []
    for index, item in enumerate(strokes):
        if isinstance(item, Element):
            flat.extend(item.strokes)
        elif isinstance(item, Stroke):
            flat.append(item)
        else:
            raise ValueError(f"strokes[{index}] (pattern item {index}) is a {type(item).__name__}, "
                             "expected a Stroke or an Element")
    if len(flat) < min_count:
        raise ValueError(f"strokes must hold at least {min_count} strokes (a stroke pattern needs them), got {len(flat)}")
    return tuple(flat)


def _check_no_dots(strokes, contour: bool) -> None:
    if contour:
        return  # a dot's contour is the square its pen draws
    for index, stroke in enumerate(strokes):
        if len(stroke) < 2 or stroke.length() == 0:
            raise ValueError(f"stroke {index} is a single point: its skeleton has no box to fit; "
                             "fit on the contour (contour=True) to use its pen width")


def stroke_rgb(strokes) -> np.ndarray:
    """RGB colours in [0, 1] of strokes, shape ``(n, 3)``."""
    try:
        return np.array([to_rgb(stroke.color) for stroke in strokes], dtype=np.float64).reshape(-1, 3)
    except ValueError as exc:
        raise ValueError(f"stroke colour is not a colour matplotlib can read: {exc}") from None


# --------------------------------------------------------------------------- 2.1 element fitting


def fit_elements(groups, *, contour: bool = False) -> OrientedBoxes:
    """Fit an oriented bounding box to each group of strokes (section 2.1).

    Parameters
    ----------
    groups : sequence of Element, or sequence of sequences of Stroke
        One entry per element.
    contour : bool
        False: fit the skeleton (the points of the gesture). True: fit the contour, the region the pen covers,
        so stroke width is taken into account.

    Returns
    -------
    OrientedBoxes
        PCA axes (eigenvectors of the covariance), extents and centre from the projections on the axes.

    References
    ----------
    Barla et al. 2006, section 2.1.
    """
    if isinstance(groups, (str, bytes, Element)) or not hasattr(groups, "__iter__"):
        raise TypeError(f"groups must be a sequence of Elements or of stroke groups, got {type(groups).__name__}")
    groups = list(groups)
    if not groups:
        raise ValueError("groups must hold at least 1 element (an Element or a group of strokes), got 0")
    elements = []
    for index, group in enumerate(groups):
        if not isinstance(group, Element) and (isinstance(group, (str, bytes)) or not hasattr(group, "__iter__")):
            raise TypeError(f"groups[{index}] must be an Element or a sequence of Stroke, got {type(group).__name__}")
        try:
            elements.append(group if isinstance(group, Element) else Element(tuple(group)))
        except (TypeError, ValueError) as error:
            raise type(error)(f"groups[{index}]: {error}") from None
    return oriented_bounding_boxes(elements, include_width=contour)


# --------------------------------------------------------------------------- 2.2 measures


def proximity(corners_a, corners_b):
    """Proximity of elements (section 2.2.1): ``min(dH(E1, E2), dH(E2, E1))`` between their boxes.

    ``corners_*`` are box corners ``(4, 2)`` or ``(k, 4, 2)`` (broadcasting); the directed Hausdorff distance is
    exact between the filled boxes (:func:`paperlib.geometry.directed_hausdorff_boxes`). Small when one box
    nests in, or hugs, the other.

    Parameters
    ----------
    corners_a, corners_b : array_like, shape (4, 2) or (k, 4, 2)
        Box corners (broadcast together).

    Returns
    -------
    float or ndarray of float
        The proximity of each pair of boxes, in the boxes' units (the broadcast shape without the
        corner axes).
    """
    return np.minimum(directed_hausdorff_boxes(corners_a, corners_b), directed_hausdorff_boxes(corners_b, corners_a))


def _gap_along(axis, center, corners_a, corners_b, epsilon):
    """Continuation gap of ``b`` relative to one axis line of ``a`` (inf where ``b`` is not near-collinear).

    ``axis`` ``(k, 2)`` is a unit direction through ``center`` ``(k, 2)``; near-collinear means every corner
    of ``b`` lies within epsilon / 2 of that line; the gap is the distance between the projections of the two
    boxes on the line (0 when they overlap).
    """
    normal = np.stack([-axis[:, 1], axis[:, 0]], axis=-1)
    offset_b = corners_b - center[:, None, :]
    collinear = np.all(np.abs(np.einsum("kpi,ki->kp", offset_b, normal)) < epsilon / 2.0, axis=1)
    along_a = np.einsum("kpi,ki->kp", corners_a - center[:, None, :], axis)
    along_b = np.einsum("kpi,ki->kp", offset_b, axis)
    gap = np.maximum.reduce([along_b.min(axis=1) - along_a.max(axis=1),
                             along_a.min(axis=1) - along_b.max(axis=1), np.zeros(len(axis))])
    return np.where(collinear, gap, np.inf)


def continuation(boxes_a: OrientedBoxes, boxes_b: OrientedBoxes, epsilon: float) -> np.ndarray:
    """Continuation measure of element pairs (section 2.2.2), the smallest of its four configurations.

    For each axis (major and minor) of each element of a pair, the other element is near-collinear when all its
    points lie within epsilon / 2 of the axis line; the measure is then the gap between the two elements'
    projections on that axis. Boxes stand for the points, as in the paper ("we also use the bounding boxes to
    speed up this computation"): the projections of a box are those of its corners.

    Parameters
    ----------
    boxes_a, boxes_b : OrientedBoxes
        The pairs, row by row (equal lengths).
    epsilon : float
        The user scale (> 0).

    Returns
    -------
    ndarray, shape (k,)
        The smallest gap over the configurations where the elements are near-collinear, ``inf`` if none.

    References
    ----------
    Barla et al. 2006, section 2.2.2 and Figure 2(b).
    """
    epsilon = positive_number(epsilon, "epsilon")
    instance_of(boxes_a, OrientedBoxes, "boxes_a")
    if len(instance_of(boxes_b, OrientedBoxes, "boxes_b")) != len(boxes_a):
        raise ValueError(f"boxes_a and boxes_b hold the pairs row by row: {len(boxes_a)} and {len(boxes_b)} boxes")
    corners_a, corners_b = boxes_a.corners(), boxes_b.corners()
    gaps = [_gap_along(first.axes[:, :, column], first.centers, c_first, c_second, epsilon)
            for first, c_first, c_second in ((boxes_a, corners_a, corners_b), (boxes_b, corners_b, corners_a))
            for column in (0, 1)]
    return np.minimum.reduce(gaps)


# --------------------------------------------------------------------------- 2.2 greedy clustering


class _BoxTable:
    """Boxes of the elements under construction, by slot, refitted when an element absorbs another."""

    def __init__(self, strokes, contour: bool):
        self.strokes, self.contour = strokes, contour
        self.members = [[i] for i in range(len(strokes))]
        boxes = fit_elements([[s] for s in strokes], contour=contour)
        self.centers = np.array(boxes.centers)
        self.axes = np.array(boxes.axes)
        self.half_lengths = np.array(boxes.half_lengths)
        self.angles = np.array(boxes.angles)

    def boxes(self, slots) -> OrientedBoxes:
        return OrientedBoxes(self.centers[slots], self.axes[slots], self.half_lengths[slots], self.angles[slots])

    def radii(self, slots) -> np.ndarray:
        return np.hypot(self.half_lengths[slots, 0], self.half_lengths[slots, 1])

    def merge(self, target: int, absorbed: int) -> None:
        self.members[target] = sorted(self.members[target] + self.members[absorbed])
        box = fit_elements([[self.strokes[i] for i in self.members[target]]], contour=self.contour)
        self.centers[target], self.axes[target] = box.centers[0], box.axes[0]
        self.half_lengths[target], self.angles[target] = box.half_lengths[0], box.angles[0]


def _clusterable(table: _BoxTable, slot: int, others: np.ndarray, epsilon: float) -> np.ndarray:
    """Which of ``others`` meet the proximity or the continuation test with ``slot`` (section 2.2)."""
    passed = np.zeros(len(others), dtype=bool)
    reach = np.hypot(*(table.centers[others] - table.centers[slot]).T) - table.radii(others) - table.radii([slot])
    near = np.flatnonzero(reach < _CANDIDATE_REACH * epsilon)
    if near.size == 0:
        return passed
    one = table.boxes(np.full(near.size, slot))
    many = table.boxes(others[near])
    close = proximity(one.corners(), many.corners()) < epsilon
    close |= continuation(one, many, epsilon) < epsilon
    passed[near] = close
    return passed


def _absorb_neighbours(table: _BoxTable, slot: int, queue: list, epsilon: float) -> bool:
    """Test ``slot`` against the queue in order, merging each element that passes; True if any merged.

    As in the paper, every element of the queue is tested once against the element as it grows: after a
    merge the remaining ones are tested against the refitted box.
    """
    merged_any, position = False, 0
    while position < len(queue):
        others = np.asarray(queue[position:])
        passed = _clusterable(table, slot, others, epsilon)
        if not passed.any():
            break
        first = position + int(np.argmax(passed))
        table.merge(slot, queue.pop(first))
        merged_any, position = True, first
    return merged_any


def cluster_strokes(strokes, epsilon: float, *, contour: bool = False) -> np.ndarray:
    """Greedy clustering of strokes into elements at the user scale epsilon (section 2.2).

    The strokes are fitted with boxes and queued in drawing order. At each step an element E* is popped and
    every element of the queue is tested against it; those meeting the proximity measure (< epsilon) or the
    continuation measure (< epsilon) are merged into E* (which is refitted) and leave the queue. If any merge
    happened, E* goes back to the end of the queue; otherwise it is an output element. The loop ends when the
    queue is empty.

    Parameters
    ----------
    strokes : sequence of Stroke or Element
        The reference pattern in drawing order (at least 2 strokes).
    epsilon : float
        The user scale: the minimum distance at which two elements are perceived separately (> 0).
    contour : bool
        Fit boxes on the pen's contour (stroke width included) instead of the skeleton.

    Returns
    -------
    ndarray of int, shape (n_strokes,)
        The element of each stroke; elements are numbered in the order of their first stroke.

    Raises
    ------
    ValueError
        On fewer than 2 strokes, epsilon <= 0, or a single-point stroke with ``contour=False``.

    References
    ----------
    Barla et al. 2006, section 2.2 (greedy algorithm), 2.2.1 (proximity), 2.2.2 (continuation).
    """
    strokes = as_strokes(strokes)
    epsilon = positive_number(epsilon, "epsilon")
    _check_no_dots(strokes, contour)
    table = _BoxTable(strokes, contour)
    queue, output = list(range(len(strokes))), []
    while queue:
        slot = queue.pop(0)
        if _absorb_neighbours(table, slot, queue, epsilon):
            queue.append(slot)
        else:
            output.append(slot)
    labels = np.empty(len(strokes), dtype=np.int64)
    firsts = sorted(output, key=lambda s: table.members[s][0])
    for element, slot in enumerate(firsts):
        labels[table.members[slot]] = element
    return labels


# --------------------------------------------------------------------------- 2.3 distribution


def check_dimension(dimension) -> int:
    """``dimension`` unchanged if it is 1 (a path) or 2 (a region), else a ValueError naming it."""
    if not isinstance(dimension, Real) or dimension not in (1, 2):
        raise ValueError(f"dimension must be 1 (a path) or 2 (a region), got {dimension!r:.80}")
    return dimension


def graph_edges(edges, n: int, name: str = "edges") -> np.ndarray:
    """``edges`` as an ``(m, 2)`` int64 array of node pairs, each node in ``[0, n)``; ValueError otherwise.

    Parameters
    ----------
    edges : array_like of int, shape (m, 2)
        Node pairs.
    n : int
        Number of nodes.
    name : str, default "edges"
        How error messages name the argument.

    Returns
    -------
    ndarray of int64, shape (m, 2)
        The edges.
    """
    return check_edges(edges, n, label(name))


def chain_edges(order) -> np.ndarray:
    """Edges between consecutive elements of a 1D chain, ``(n - 1, 2)`` (section 2.3).

    Parameters
    ----------
    order : array_like of int, shape (n,)
        Node indices in chain order.

    Returns
    -------
    ndarray of int64, shape (n - 1, 2)
        ``(order[k], order[k + 1])`` for each consecutive pair.
    """
    order = np.asarray(order)
    if order.ndim != 1 or (order.size and not np.issubdtype(order.dtype, np.integer)):
        raise ValueError(f"order must be a 1D array of integer node indices, got {order.dtype} of shape {order.shape}")
    order = order.astype(np.int64)
    return np.column_stack([order[:-1], order[1:]])


def unskewed_delaunay_edges(points, *, max_angle: float = MAX_UNSKEWED_ANGLE) -> np.ndarray:
    """Edges of the Delaunay triangulation that belong to at least one unskewed triangle (section 2.3).

    A triangle is unskewed when none of its angles exceeds ``max_angle`` (2 pi / 3 in the paper); skewed
    triangles lie mostly along the border of the triangulation, where their long edges join elements that
    are not perceived as neighbours.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        Element centres (finite, n >= 3, not all collinear).
    max_angle : float, default 2 pi / 3
        Largest angle, radians, of an unskewed triangle.

    Returns
    -------
    ndarray of int, shape (m, 2)
        Unique edges ``(i, j)`` with ``i < j``, sorted.

    Raises
    ------
    ValueError
        Fewer than 3 points, all points collinear or repeated, or no unskewed triangle.
    """
    points = point_array(points, "points")
    if len(points) < 3:
        raise ValueError(f"a 2D distribution needs at least 3 points (element centres), got {len(points)}")
    try:
        triangles = Delaunay(points).simplices
    except QhullError:
        raise ValueError("the points (element centres) are collinear (or repeated): they span no triangle; "
                         "analyse the pattern as 1D (dimension=1)") from None
    corners = points[triangles]
    sides = np.stack([corners[:, (k + 2) % 3] - corners[:, (k + 1) % 3] for k in range(3)], axis=1)
    lengths = np.hypot(sides[..., 0], sides[..., 1])
    # Angle at vertex k from the law of cosines on the opposite side k.
    a, b, c = lengths[:, 0], lengths[:, 1], lengths[:, 2]
    cosines = np.stack([(b * b + c * c - a * a) / (2 * b * c), (a * a + c * c - b * b) / (2 * a * c),
                        (a * a + b * b - c * c) / (2 * a * b)], axis=1)
    largest = np.arccos(np.clip(cosines, -1.0, 1.0)).max(axis=1)
    kept = triangles[largest <= max_angle]
    if len(kept) == 0:
        raise ValueError("the Delaunay triangulation of the points (element centres) has no unskewed triangle "
                         f"(every triangle has an angle above max_angle = {np.degrees(max_angle):.0f} degrees)")
    edges = np.sort(np.concatenate([kept[:, [0, 1]], kept[:, [1, 2]], kept[:, [0, 2]]]), axis=1)
    return np.unique(edges, axis=0)


def neighbour_lists(n: int, edges) -> list:
    """The neighbours of each of ``n`` nodes of an undirected graph given by ``edges`` ``(m, 2)``."""
    neighbours = [[] for _ in range(n)]
    for i, j in graph_edges(edges, n):
        neighbours[i].append(int(j))
        neighbours[j].append(int(i))
    return neighbours


def shift_vectors(positions, edges) -> np.ndarray:
    """Shift vectors S_ref: each element's position minus the barycentre of its neighbours (section 2.3).

    Returns ``(n, 2)``; NaN for an element without neighbours.

    Parameters
    ----------
    positions : array_like, shape (n, 2)
        Element positions (finite).
    edges : array_like of int, shape (m, 2)
        The neighbour graph.

    Returns
    -------
    ndarray of float64, shape (n, 2)
        S_ref per element; NaN for an element without neighbours.
    """
    positions = point_array(positions, "positions")
    edges = graph_edges(edges, len(positions))
    sums = np.zeros_like(positions)
    counts = np.bincount(edges.ravel(), minlength=len(positions)).astype(np.float64)
    np.add.at(sums, edges[:, 0], positions[edges[:, 1]])
    np.add.at(sums, edges[:, 1], positions[edges[:, 0]])
    with np.errstate(invalid="ignore", divide="ignore"):
        return positions - sums / counts[:, None]


def neighbourhood_areas(positions, edges, dimension: int) -> np.ndarray:
    """Size of each element's neighbourhood: the span of its chain neighbours (1D), or the area of their
    convex hull (2D). NaN where it is undefined (no neighbour in 1D, fewer than 3 in 2D)."""
    positions = np.asarray(positions, dtype=np.float64)
    areas = np.full(len(positions), np.nan)
    for index, neighbours in enumerate(neighbour_lists(len(positions), edges)):
        points = positions[neighbours]
        if dimension == 1 and len(points) >= 1:
            span = points if len(points) > 1 else np.vstack([points, positions[index]])
            areas[index] = float(np.hypot(*(span.max(axis=0) - span.min(axis=0))))
        elif dimension == 2 and len(points) >= 3:
            areas[index] = shapely.convex_hull(shapely.multipoints(points)).area
    return areas


# --------------------------------------------------------------------------- the whole analysis


@dataclass(frozen=True, eq=False)
class PatternAnalysis:
    """A reference stroke pattern analysed at one scale (section 2).

    Parameters
    ----------
    strokes : tuple of Stroke
        The input, in drawing order.
    epsilon : float
        The user scale.
    contour : bool
        Whether boxes were fitted on the pen's contour (True) or the skeleton.
    dimension : int
        1 (a pattern along a path) or 2 (a pattern in a region).
    element_of_stroke : ndarray of int, shape (n_strokes,)
    elements : tuple of Element
        The clustered elements, their strokes in drawing order.
    boxes : OrientedBoxes
        One box per element; ``boxes.centers`` are the element positions.
    colors : ndarray, shape (n, 3)
        Element colour: the length-weighted mean RGB of its strokes.
    frames : ndarray, shape (n,)
        Angle of each element's local frame: the path's tangent at the element (1D), 0 (2D). Orientations and
        neighbour offsets are measured in that frame, so elements can follow a curved target path.
    arc : ndarray, shape (n,)
        Arc-length position along the path (1D); NaN in 2D.
    edges : ndarray of int, shape (m, 2)
        The neighbour graph: the chain (1D) or the unskewed Delaunay edges (2D).
    shifts : ndarray, shape (n, 2)
        S_ref, position minus the barycentre of the neighbours.
    neighbourhood_area : ndarray, shape (n,)
        Size of each neighbourhood (see :func:`neighbourhood_areas`).
    area : float
        A_ref, the length (1D) or area (2D) the pattern covers, for N_tar = N_ref A_tar / A_ref.
    """

    strokes: tuple
    epsilon: float
    contour: bool
    dimension: int
    element_of_stroke: np.ndarray
    elements: tuple
    boxes: OrientedBoxes
    colors: np.ndarray
    frames: np.ndarray
    arc: np.ndarray
    edges: np.ndarray
    shifts: np.ndarray
    neighbourhood_area: np.ndarray
    area: float

    def __len__(self) -> int:
        return len(self.elements)

    @property
    def positions(self) -> np.ndarray:
        """Element centres (box centres), ``(n, 2)``."""
        return self.boxes.centers

    @property
    def mean_length(self) -> float:
        """L, the average length (major axis) of the reference elements (section 3.1)."""
        return float(2.0 * self.boxes.half_lengths[:, 0].mean())


def _element_colors(elements) -> np.ndarray:
    colors = []
    for element in elements:
        rgb = stroke_rgb(element.strokes)
        weights = np.array([max(stroke.length(), stroke.width) for stroke in element.strokes])
        colors.append(weights @ rgb / weights.sum())
    return np.array(colors)


def _as_path(path, name: str = "path") -> np.ndarray:
    """A polyline ``(m, 2)`` of positive length, as a float array without repeated vertices."""
    points = np.array(as_points(path, name=name, min_points=2))
    keep = np.concatenate([[True], np.any(np.diff(points, axis=0) != 0, axis=1)])
    points = points[keep]
    if len(points) < 2:
        raise ValueError(f"{name} has zero length: it needs two distinct points")
    return points


def as_region(region):
    """A region as a valid shapely (Multi)Polygon of positive area.

    Accepts a shapely (Multi)Polygon, a polygon's vertices ``(m, 2)`` or a rectangle ``(xmin, xmax, ymin, ymax)``.

    Parameters
    ----------
    region : shapely.Polygon, shapely.MultiPolygon or array_like
        A polygon, polygon vertices ``(m, 2)`` with m >= 3, or a rectangle ``(xmin, xmax, ymin, ymax)``.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon
        The region, valid and of positive area.
    """
    from shapely.geometry import MultiPolygon, Polygon

    if not isinstance(region, (Polygon, MultiPolygon)):
        array = float_array(region, "region", "a shapely Polygon, polygon vertices (m, 2) with m >= 3, or a "
                                              "rectangle (xmin, xmax, ymin, ymax)")
        if array.shape == (4,):
            xmin, xmax, ymin, ymax = array
            region = shapely.box(xmin, ymin, xmax, ymax)
        elif array.ndim == 2 and array.shape[1] == 2 and len(array) >= 3 and np.isfinite(array).all():
            region = shapely.Polygon(array)
        else:
            raise ValueError("region must be a shapely Polygon, polygon vertices (m, 2) with m >= 3, or a rectangle "
                             f"(xmin, xmax, ymin, ymax); got an array of shape {array.shape}")
    if region.is_empty or not region.is_valid or not region.area > 0:
        raise ValueError("the region must be a valid polygon of positive area "
                         f"(got area {region.area:g}, {shapely.is_valid_reason(region)})")
    return region


def path_frames(path: np.ndarray, arc: np.ndarray) -> np.ndarray:
    """Tangent angle of a polyline at arc-length positions (the direction of the segment holding each)."""
    steps = np.diff(path, axis=0)
    cumulative = np.concatenate([[0.0], np.cumsum(np.hypot(*steps.T))])
    segment = np.clip(np.searchsorted(cumulative, arc, side="right") - 1, 0, len(steps) - 1)
    return np.arctan2(steps[segment, 1], steps[segment, 0])


def _principal_line(points: np.ndarray) -> np.ndarray:
    """The segment spanned by the points' projections on their principal axis (a default 1D path)."""
    centre = points.mean(axis=0)
    _, _, vt = np.linalg.svd(points - centre, full_matrices=False)
    direction = vt[0] if vt[0, 0] >= 0 else -vt[0]  # left to right
    along = (points - centre) @ direction
    return centre + np.outer([along.min(), along.max()], direction)


def _distribution_1d(positions, path):
    path = _principal_line(positions) if path is None else _as_path(path)
    line = shapely.linestrings(path)
    arc = shapely.line_locate_point(line, shapely.points(positions))
    order = np.argsort(arc, kind="stable")
    span = arc[order[-1]] - arc[order[0]]
    if span <= 0:
        raise ValueError("the elements all project to one point of the path: a 1D pattern needs a spread")
    # The chain covers its span plus one spacing (half a spacing beyond each end element).
    area = span * len(arc) / (len(arc) - 1)
    return arc, path_frames(path, arc), chain_edges(order), area


def _distribution_2d(positions, strokes, region):
    if region is None:
        region = shapely.convex_hull(shapely.multipoints(np.vstack([s.points for s in strokes])))
    area = float(as_region(region).area)
    return np.full(len(positions), np.nan), np.zeros(len(positions)), unskewed_delaunay_edges(positions), area


def analyze(strokes, epsilon: float, *, dimension: int = 2, contour: bool = False, path=None,
            region=None) -> PatternAnalysis:
    """Analyse a reference stroke pattern (Barla 2006, section 2): fit, cluster, distribution.

    Parameters
    ----------
    strokes : sequence of Stroke or Element
        The reference pattern in drawing order (at least 2 strokes).
    epsilon : float
        The user scale of section 2.2 (> 0).
    dimension : {1, 2}
        1: a pattern along a path (neighbours along a chain); 2: a pattern in a region (unskewed Delaunay).
    contour : bool
        Fit boxes on the pen's contour, stroke width included (section 2.1), instead of the skeleton.
    path : array_like (m, 2), optional
        1D only: the path the reference was drawn along; default the principal axis of the element centres.
    region : shapely Polygon, optional
        2D only: the region the reference fills, for A_ref; default the convex hull of all stroke points.

    Returns
    -------
    PatternAnalysis

    Raises
    ------
    ValueError
        Fewer than 2 strokes, a single-point stroke (skeleton fitting), epsilon <= 0, a pattern that clusters
        into fewer than 2 elements (1D) or 3 (2D), collinear centres or no unskewed triangle in 2D, a path of
        zero length, a region of zero area.

    References
    ----------
    Barla et al. 2006, sections 2.1-2.3.
    """
    check_dimension(dimension)
    strokes = as_strokes(strokes)
    labels = cluster_strokes(strokes, epsilon, contour=contour)
    n_elements = int(labels.max()) + 1
    if n_elements < dimension + 1:
        raise ValueError(f"the pattern clusters into {n_elements} element(s) at epsilon = {epsilon:g}; "
                         f"a {dimension}D pattern needs at least {dimension + 1}: lower epsilon")
    elements = tuple(Element(tuple(s for s, label in zip(strokes, labels) if label == e)) for e in range(n_elements))
    boxes = fit_elements(elements, contour=contour)
    if dimension == 1:
        arc, frames, edges, area = _distribution_1d(boxes.centers, path)
    else:
        arc, frames, edges, area = _distribution_2d(boxes.centers, strokes, region)
    return PatternAnalysis(
        strokes=strokes, epsilon=float(epsilon), contour=contour, dimension=dimension, element_of_stroke=labels,
        elements=elements, boxes=boxes, colors=_element_colors(elements), frames=frames, arc=arc, edges=edges,
        shifts=shift_vectors(boxes.centers, edges), neighbourhood_area=neighbourhood_areas(boxes.centers, edges,
                                                                                           dimension),
        area=float(area))
