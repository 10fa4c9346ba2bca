"""An element's topology read on its ink: centrelines of overdrawn strokes (Hurtut et al. 2009, section 2.1).

Hurtut et al. count extremities and crossings "along the elements' curves". That reading holds
while each line the eye sees is drawn by one pen line. Heavy and sketchy drawings break it: a
bold face draws a thick stroke as three or four parallel pen lines, a sketcher goes over a line
twice. Counted pen line by pen line, a bold 'c' has one to five free ends and a bold 'x' six to
twelve (Hershey's ``timesrb``; issue 27), so one type splits into many categories. What the eye
counts there are the ends and crossings of the *ink*.

:func:`ink_centrelines` redraws an element along the skeleton of its ink:

1. *Ink.* The pen's footprint (each stroke swept by a disc of its width) is rasterised at
   ``pixels_per_pen`` pixels per pen width (6; at most :data:`MAX_INK_PIXELS` pixels on the longer
   side). Holes narrower than the pen (the largest disc they hold has a radius below half a pen),
   the slits left between pen lines that part a little, are filled: the eye sees no hole there.
2. *Skeleton.* scikit-image's ``skeletonize`` thins the ink to one-pixel lines; ``skan`` splits
   the skeleton into paths between its ends and junctions.
3. *Spurs.* A path from a junction to a free end that ends less than ``spur_length`` pen widths
   (0.5) beyond the disc inscribed in the ink at the junction is a bump of the ink's outline, not
   a stroke: it is removed, and the skeleton re-thinned, until none is left.
4. *Junctions.* Junctions whose inscribed discs overlap (two forks of a thick 'x', joined by a
   path shorter than the sum of their radii) are one junction. Strokes crossing at a shallower
   angle share their ink over a length, which the skeleton splits into two forks farther apart (a
   Greek alpha, a script 't'): when told where the pen's lines cross (``crossings``, as
   :func:`~paperlib.arrangement.element_features` does), the path between two forks that is the
   skeleton's nearest to such a point, and shorter than four times the sum of their radii, joins
   them too (not a fork already joined: the crossing is read there). Without the pen's crossings,
   bold strokes crossing at 20 to 45 degrees read no crossing; with them, one. At a junction of four arms or
   more, arms are paired by good continuation, the two most nearly opposite first (while they
   turn by less than a right angle), and each pair is one curve through the junction: two curves
   passing through each other is a crossing, as it is for pen lines. A junction of three arms (a
   'T', a 'Y') is left as the meeting of three curve ends, as the pen lines of a 'T' meet.
5. *Curves.* The paths, chained through paired arms, are smoothed by a Gaussian of a third of the
   pen width along their length (the staircase of pixel centres would otherwise turn by 45
   degrees at every step) and returned in the element's coordinates, with the element's widest
   pen. An ink component whose skeleton is a single pixel (a dot) is a single-point stroke.

:func:`overdrawn_fraction` says how much of an element's pen path runs over its own ink: the
fraction of points along the strokes (every half pen width) lying within one pen width of another
stroke, or of the same stroke more than three pen widths of arc away. Per element it does not
separate the two kinds of drawing (over the categorization test matrix of issue 27, seed 0, single
pen lines read up to 0.30, a cursive 'a' whose stem is retraced; parallel pen lines down to 0.24, a
Times 'i'), so the choice is made once per arrangement:
:func:`paperlib.arrangement.element_features` reads topology on the ink when the *median* element
is above :data:`OVERDRAWN_MEDIAN` (0.35), on the strokes otherwise. Over seeds 0-19 of the 46 test
cases that median is 0 to 0.245 for the drawings in one pen line per line (Hershey's simplex,
script and cursive faces) and 0.452 to 0.882 for those drawn in parallel pen lines (complex,
duplex, triplex, bold and blackletter faces); 0.35 is the middle of the gap. Copies of one type are
thus never read two ways.

References
----------
.. [1] T. Hurtut et al., "Appearance-guided Synthesis of Element Arrangements by Example", NPAR
   2009, section 2.1 (extremities and crossings).
.. [2] T. Y. Zhang and C. Y. Suen, "A fast parallel algorithm for thinning digital patterns",
   Communications of the ACM 27(3), 1984 (the thinning of ``skimage.morphology.skeletonize``).
.. [3] J. Nunez-Iglesias et al., "A new Python library to analyse skeleton images confirms
   malaria parasite remodelling of the red blood cell membrane skeleton", PeerJ 6, 2018 (skan).
"""

from __future__ import annotations

import numpy as np
from scipy import ndimage
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree
from skan import Skeleton
from skimage.morphology import skeletonize

from paperlib._checks import finite_array
from paperlib.geometry import Element, Stroke

__all__ = ["MAX_INK_PIXELS", "MAX_PATH_SAMPLES", "OVERDRAWN_MEDIAN", "ink_centrelines", "overdrawn_fraction"]

#: The ink raster's longer side never exceeds this many pixels (memory stays bounded for a pen
#: far thinner than its drawing; the pixel then grows beyond a sixth of the pen).
MAX_INK_PIXELS = 1024
#: Median :func:`overdrawn_fraction` of an arrangement's elements above which their topology is
#: read on the ink (see the module docstring for the measured gap it sits in).
OVERDRAWN_MEDIAN = 0.35

#: At most this many points are taken along an element's pen path (the spacing grows beyond half a pen,
#: or a pixel's third, for longer paths: memory stays bounded for any element).
MAX_PATH_SAMPLES = 2_000_000
#: Neighbours looked at around each point of the path (a bold face's parallel lines put about
#: twelve within a pen width; a bound on memory for a scribble that piles thousands there).
_NEIGHBOURS = 24
#: Pen path points closer than this many pen widths to another stretch of the path are overdrawn,
_OVERDRAW_DISTANCE = 1.0
#: where "another stretch" of the same stroke is more than this many pen widths of arc away.
_OVERDRAW_ARC = 3.0
#: Smoothing of the centrelines: Gaussian sigma, in pen widths.
_SMOOTHING = 1.0 / 3.0
#: At most this many rounds of spur removal (each removes every spur present; two suffice in practice).
_MAX_PRUNING_ROUNDS = 20
#: Two forks joined by a path shorter than this times the sum of their inscribed radii, the path nearest
#: to a crossing of the pen's lines, are one crossing.
_CROSSING_BRIDGE = 4.0
#: Arm directions at a junction are read this many pen widths along the arm.
_ARM_REACH = 2.0


def overdrawn_fraction(element) -> float:
    """Fraction of an element's pen path lying within one pen width of another stretch of it.

    Parameters
    ----------
    element : Element

    Returns
    -------
    float
        In ``[0, 1]``: the fraction of points taken every half pen width along the strokes that lie
        within one pen width of a point of another stroke, or of the same stroke more than three
        pen widths of arc away. 0 for a drawing of separate single lines, near 1 for a bold face
        drawn as parallel pen lines.

    Raises
    ------
    TypeError
        If ``element`` is not an Element.

    References
    ----------
    .. [1] Module docstring (issue 27's measurements on the categorization test matrix).
    """
    pen = _pen(element)
    step = max(pen / 2.0, _path_length(element) / MAX_PATH_SAMPLES)
    points, stroke_of, arc = _path_samples(element, step)
    k = min(_NEIGHBOURS, len(points))
    neighbour = cKDTree(points).query(points, k=k, distance_upper_bound=_OVERDRAW_DISTANCE * pen)[1].reshape(-1, k)
    found = neighbour < len(points)
    other = np.where(found, neighbour, 0)
    apart = (stroke_of[other] != stroke_of[:, None]) | (np.abs(arc[other] - arc[:, None]) > _OVERDRAW_ARC * pen)
    return float(np.mean(np.any(found & apart, axis=1)))


def ink_centrelines(element, *, pixels_per_pen: int = 6, spur_length: float = 0.5, crossings=None) -> Element:
    """The element redrawn along the skeleton of its ink, one curve per line the eye sees.

    Parameters
    ----------
    element : Element
    pixels_per_pen : int, optional
        Resolution of the ink raster, in pixels per pen width (default 6), in ``[3, 32]``.
    spur_length : float, optional
        Skeleton branches that end less than this many pen widths beyond the disc inscribed in
        the ink where they leave are outline bumps and are removed (default 0.5), in ``[0, 4]``.
    crossings : array_like, shape (k, 2), optional
        Points where the pen's lines cross (``crossing_points(element, topology="strokes")``, which
        :func:`~paperlib.arrangement.element_features` passes): two forks of the skeleton joined
        along the ink of one of them are one crossing (strokes crossing at a shallow angle share
        their ink over a length, which the skeleton splits into two forks).

    Returns
    -------
    Element
        Same name; its strokes are the ink's centrelines (open or closed; a dot of ink is a
        single-point stroke), all with the element's widest pen and its first stroke's colour.

    Raises
    ------
    TypeError
        If ``element`` is not an Element or a parameter has the wrong type.
    ValueError
        If a parameter is out of range, or the strokes are too long to rasterise
        (:data:`MAX_PATH_SAMPLES`).

    Notes
    -----
    The steps and their reasons are in the module docstring. An element of ``n`` pixels takes a
    few milliseconds (a Hershey glyph at the default resolution is about 100 x 100 pixels).

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.1; Zhang and Suen 1984 (thinning); skan (skeleton paths).
    """
    pen = _pen(element)
    pixels_per_pen = _checked_resolution(pixels_per_pen)
    spur_length = _checked_spur_length(spur_length)
    crossings = np.zeros((0, 2)) if crossings is None else finite_array(crossings, "crossings", shape=(None, 2))
    origin, pixel, ink = _ink_raster(element, pen, pixels_per_pen)
    ink = _fill_narrow_holes(ink, pen / pixel)
    radius = ndimage.distance_transform_edt(ink)
    graph = _pruned_skeleton(skeletonize(ink), radius, spur_length * pen / pixel)
    crossing_pixels = ((crossings - origin) / pixel - 0.5)[:, ::-1]  # (row, column), as the skeleton's
    curves = _skeleton_curves(graph, radius, _ARM_REACH * pen / pixel, crossing_pixels) if graph is not None else []
    sigma = max(_SMOOTHING * pen / pixel, 1.0)
    curves = [_smoothed(curve, sigma) for curve in curves] + _dots(ink, graph)
    colour = element.strokes[0].color
    strokes = tuple(Stroke(origin + (curve[:, ::-1] + 0.5) * pixel, pen, colour) for curve in curves)
    return Element(strokes, name=element.name)


def reads_on_ink(elements) -> bool:
    """Whether an arrangement's topology is read on the ink (median overdrawn fraction > OVERDRAWN_MEDIAN)."""
    return bool(np.median([overdrawn_fraction(element) for element in elements]) > OVERDRAWN_MEDIAN)


# --------------------------------------------------------------------------- checks


def _pen(element) -> float:
    if not isinstance(element, Element):
        raise TypeError(f"element must be an Element, got {type(element).__name__}")
    return float(max(stroke.width for stroke in element.strokes))


def _checked_resolution(pixels_per_pen) -> int:
    if isinstance(pixels_per_pen, bool) or not isinstance(pixels_per_pen, (int, np.integer)):
        raise TypeError(f"pixels_per_pen must be an integer, got {pixels_per_pen!r}")
    if not 3 <= pixels_per_pen <= 32:
        raise ValueError(f"pixels_per_pen must be in [3, 32], got {pixels_per_pen}")
    return int(pixels_per_pen)


def _checked_spur_length(spur_length) -> float:
    if isinstance(spur_length, bool) or not isinstance(spur_length, (int, float, np.integer, np.floating)):
        raise TypeError(f"spur_length must be a number of pen widths, got {spur_length!r}")
    if not 0.0 <= spur_length <= 4.0:
        raise ValueError(f"spur_length must be in [0, 4] pen widths, got {spur_length}")
    return float(spur_length)


# --------------------------------------------------------------------------- the ink


def _path_length(element: Element) -> float:
    return float(sum(np.hypot(*np.diff(stroke.points, axis=0).T).sum() for stroke in element.strokes))


def _path_samples(element: Element, step: float):
    """Points every ``step`` along each stroke, with their stroke and arc length (a stroke's last point included)."""
    points, stroke_of, arc = [], [], []
    for index, stroke in enumerate(element.strokes):
        vertices = stroke.points
        lengths = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(vertices, axis=0).T))])
        samples = np.append(np.arange(0.0, lengths[-1], step), lengths[-1])
        points.append(np.column_stack([np.interp(samples, lengths, vertices[:, 0]),
                                       np.interp(samples, lengths, vertices[:, 1])]))
        stroke_of.append(np.full(len(samples), index))
        arc.append(samples)
    return np.vstack(points), np.concatenate(stroke_of), np.concatenate(arc)


def _ink_raster(element: Element, pen: float, pixels_per_pen: int):
    """Origin, pixel size and boolean raster (rows along y) of the pen's footprint."""
    low = element.points.min(axis=0) - pen
    extent = element.points.max(axis=0) + pen - low
    pixel = max(pen / pixels_per_pen, float(extent.max()) / MAX_INK_PIXELS)
    shape = tuple((np.ceil(extent / pixel).astype(int) + 1).tolist()[::-1])
    if _path_length(element) / (pixel / 3.0) > MAX_PATH_SAMPLES:
        raise ValueError(f"element's strokes are too long to rasterise ({_path_length(element):.4g}, more than "
                         f"{MAX_PATH_SAMPLES} samples a third of a pixel apart; pixel {pixel:.4g})")
    ink = np.zeros(shape, dtype=bool)
    for width in sorted({stroke.width for stroke in element.strokes}):
        same_pen = Element(tuple(stroke for stroke in element.strokes if stroke.width == width))
        points = _path_samples(same_pen, pixel / 3.0)[0]
        # A pen thinner than the capped pixel still leaves a connected line of pixels.
        radius = max(width / 2.0, 0.75 * pixel)
        # Only pixels within the radius of a sample's pixel can be inked: measure distances there alone.
        near = np.zeros(shape, dtype=bool)
        column, row = np.floor((points - low) / pixel).astype(int).T
        near[row, column] = True
        near = ndimage.binary_dilation(near, np.ones((3, 3), dtype=bool), iterations=int(np.ceil(radius / pixel)) + 1)
        rows, columns = np.nonzero(near)
        centres = low + (np.column_stack([columns, rows]) + 0.5) * pixel
        inked = cKDTree(points).query(centres, distance_upper_bound=radius)[0] <= radius
        ink[rows[inked], columns[inked]] = True
    return low, pixel, ink


def _fill_narrow_holes(ink: np.ndarray, pen_pixels: float) -> np.ndarray:
    holes = ndimage.binary_fill_holes(ink) & ~ink
    labels, n_holes = ndimage.label(holes)
    if n_holes == 0:
        return ink
    widest = ndimage.maximum(ndimage.distance_transform_edt(holes), labels, np.arange(1, n_holes + 1))
    narrow = np.flatnonzero(np.asarray(widest) <= pen_pixels / 2.0) + 1
    return ink | np.isin(labels, narrow)


# --------------------------------------------------------------------------- the skeleton


def _pruned_skeleton(skeleton: np.ndarray, radius: np.ndarray, spur_pixels: float):
    """The skeleton's graph with its spurs removed, or None when no path is left (the ink is a dot)."""
    graph = _skeleton_graph(skeleton)
    for _ in range(_MAX_PRUNING_ROUNDS):
        spurs = _spurs(graph, radius, spur_pixels) if graph is not None else []
        if not spurs:
            break
        graph = _skeleton_graph(_without_paths(graph, spurs))
    return graph


def _skeleton_graph(skeleton: np.ndarray):
    """skan's graph of a skeleton image, or None when no two of its pixels touch.

    skan builds no graph from isolated pixels (it raises on a one-pixel skeleton, e.g. the
    ink of a stroke shorter than its pen); :func:`_dots` reads such components as dots.
    """
    neighbours = ndimage.convolve(skeleton.astype(np.uint8), np.ones((3, 3), np.uint8), mode="constant")
    return Skeleton(skeleton) if np.any(skeleton & (neighbours > 1)) else None


def _without_paths(graph: Skeleton, indices) -> np.ndarray:
    """The skeleton image without the given paths' pixels, junctions kept, thinned again.

    What ``Skeleton.prune_paths`` computes before it builds a graph, which it cannot do when
    only isolated pixels are left.
    """
    image = np.array(graph.skeleton_image, dtype=bool)
    for index in indices:
        pixels = graph.path(index)
        pixels = pixels[graph.degrees[pixels] <= 2]
        rows, columns = np.round(graph.coordinates[pixels]).astype(int).T
        image[rows, columns] = False
    return skeletonize(image)


def _spurs(graph: Skeleton, radius: np.ndarray, spur_pixels: float) -> list:
    """Paths from a junction to a free end that stop within ``spur_pixels`` of the junction's inscribed disc."""
    degrees, lengths = graph.degrees, graph.path_lengths()
    spurs = []
    for index, path in enumerate(graph.paths_list()):
        ends = degrees[[path[0], path[-1]]]
        if (ends == 1).sum() != 1 or (ends > 2).sum() != 1:
            continue
        junction = path[0] if ends[0] > 2 else path[-1]
        if lengths[index] < _radius_at(radius, graph.coordinates[junction]) + spur_pixels:
            spurs.append(index)
    return spurs


def _radius_at(radius: np.ndarray, coordinate) -> float:
    row, column = np.round(coordinate).astype(int)
    return float(radius[row, column])


def _skeleton_curves(graph: Skeleton, radius: np.ndarray, reach: float, crossing_pixels: np.ndarray) -> list:
    """Pixel polylines (row, column) of the skeleton's paths, chained through paired junction arms."""
    paths = [np.asarray(path) for path in graph.paths_list()]
    if not paths:
        return []
    node_of, kept = _junction_nodes(graph, paths, radius, crossing_pixels)
    coordinates = graph.coordinates
    arms = {}
    for index in kept:
        for end in (0, 1):
            arms.setdefault(node_of[paths[index][-end]], []).append((index, end))
    partner = {}
    for node_arms in arms.values():
        partner.update(_paired_arms([_arm_direction(coordinates[paths[i]], end, reach) for i, end in node_arms],
                                    node_arms))
    centre = {node: coordinates[[paths[i][-end] for i, end in node_arms]].mean(axis=0)
              for node, node_arms in arms.items()}
    return _chains(paths, kept, partner, node_of, centre, coordinates)


def _junction_nodes(graph: Skeleton, paths, radius, crossing_pixels):
    """Node of each path end pixel (junctions that are one place merged), and the paths kept.

    Two junctions joined by a path (a bridge) are one node when their inscribed discs overlap (the
    bridge is shorter than the sum of their radii), or when the pen's lines cross nearer to that
    bridge than to any other path of the skeleton, within its ink, and the bridge is shorter than
    :data:`_CROSSING_BRIDGE` times the sum of the radii: a shallow crossing, whose shared ink the
    skeleton splits into two forks.
    """
    ends = np.unique([path[[0, -1]] for path in paths])
    position = {pixel: k for k, pixel in enumerate(ends)}
    degrees, lengths, coordinates = graph.degrees, graph.path_lengths(), graph.coordinates
    bridges = [index for index, path in enumerate(paths)
               if path[0] != path[-1] and degrees[path[0]] > 2 and degrees[path[-1]] > 2]
    radii = {index: _radius_at(radius, coordinates[paths[index][0]]) + _radius_at(radius, coordinates[paths[index][-1]])
             for index in bridges}
    inner = [index for index in bridges if lengths[index] <= radii[index]]
    # A fork already merged into a junction of four is a crossing read as such: leave it.
    merged = {pixel for index in inner for pixel in paths[index][[0, -1]]}
    crossed = _nearest_paths(paths, coordinates, crossing_pixels)
    inner += [index for index in bridges if index in crossed and lengths[index] <= _CROSSING_BRIDGE * radii[index]
              and lengths[index] > radii[index] and not merged & set(paths[index][[0, -1]].tolist())]
    rows = [position[paths[i][0]] for i in inner]
    columns = [position[paths[i][-1]] for i in inner]
    adjacency = coo_matrix((np.ones(len(inner)), (rows, columns)), shape=(len(ends), len(ends)))
    labels = connected_components(adjacency, directed=False)[1]
    node_of = {pixel: int(labels[position[pixel]]) for pixel in ends}
    inner = set(inner)
    return node_of, [index for index in range(len(paths)) if index not in inner]


def _nearest_paths(paths, coordinates, crossing_pixels) -> set:
    """Paths whose inner pixels are the nearest to a crossing point, within the ink's reach of it."""
    inner = [path[1:-1] for path in paths]
    owner = np.concatenate([np.full(len(pixels), index) for index, pixels in enumerate(inner)])
    if not len(crossing_pixels) or not len(owner):
        return set()
    distance, nearest = cKDTree(coordinates[np.concatenate(inner)]).query(crossing_pixels)
    return set(owner[nearest].tolist())


def _arm_direction(path_coordinates: np.ndarray, end: int, reach: float) -> np.ndarray:
    """Unit vector from an arm's junction end to its point ``reach`` pixels of arc along it."""
    along = path_coordinates if end == 0 else path_coordinates[::-1]
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(along, axis=0).T))])
    direction = along[min(int(np.searchsorted(arc, reach)), len(along) - 1)] - along[0]
    norm = np.hypot(*direction)
    return direction / norm if norm > 0 else direction


def _paired_arms(directions, node_arms) -> dict:
    """Arms of a junction of four or more paired by good continuation, most nearly opposite first."""
    if len(node_arms) < 4:
        return {}
    free = list(range(len(node_arms)))
    pairs = {}
    while len(free) >= 2:
        cosine, first, second = min((directions[a] @ directions[b], a, b)
                                    for k, a in enumerate(free) for b in free[k + 1:])
        if cosine >= 0.0:
            break
        pairs[node_arms[first]] = node_arms[second]
        pairs[node_arms[second]] = node_arms[first]
        free.remove(first)
        free.remove(second)
    return pairs


def _chains(paths, kept, partner, node_of, centre, coordinates) -> list:
    """Walk paths through paired arms: chains from unpaired ends first, then the closed ones."""
    used = set()

    def walk(index, end):
        pieces = []
        while True:
            used.add(index)
            path = paths[index] if end == 0 else paths[index][::-1]
            pieces.append(coordinates[path])
            onward = partner.get((index, 1 - end))
            if onward is None or onward[0] in used:
                return np.vstack(pieces)
            pieces.append(centre[node_of[path[-1]]][None])
            index, end = onward

    chains = [walk(index, end) for index in kept for end in (0, 1)
              if (index, end) not in partner and index not in used]
    chains += [walk(index, 0) for index in kept if index not in used]
    return chains


def _smoothed(curve: np.ndarray, sigma: float) -> np.ndarray:
    if len(curve) < 3:
        return curve.astype(float)
    closed = np.hypot(*(curve[0] - curve[-1])) <= 1.5
    return ndimage.gaussian_filter1d(curve.astype(float), sigma, axis=0, mode="wrap" if closed else "nearest")


def _dots(ink: np.ndarray, graph) -> list:
    """Single-point curves (row, column) at the centres of ink components the skeleton has no path in."""
    labels, n_components = ndimage.label(ink, structure=np.ones((3, 3)))
    with_path = set()
    if graph is not None and graph.n_paths:
        pixels = np.round(graph.coordinates[np.concatenate(graph.paths_list())]).astype(int)
        with_path = set(labels[pixels[:, 0], pixels[:, 1]].tolist())
    return [np.argwhere(labels == component).mean(axis=0)[None] for component in range(1, n_components + 1)
            if component not in with_path]
