"""Hausdorff distances between point sets and between convex polygons (e.g. oriented boxes).

The directed Hausdorff distance from a set A to a set B is how far A strays from B,

    h(A, B) = max over a in A of  min over b in B of |a - b|,

and the Hausdorff distance is the larger of the two directions, H(A, B) = max(h(A, B),
h(B, A)). Barla et al. 2006 compare elements by the smaller of the two directions,
computed between their bounding boxes; Hurtut et al. 2009 propose the distance between
bounding boxes instead of the distance between centroids as the interaction distance for
elongated elements.

Point sets go through a KD-tree (``scipy.spatial.cKDTree``): O((n + m) log m), exact.
``scipy.spatial.distance.directed_hausdorff`` is exact too but O(n m) in the worst case.
Convex polygons are compared as *filled regions*, exactly, from their vertices alone (see
:func:`directed_hausdorff_boxes`); no library offers that vectorised over many pairs, so
it is written here with NumPy.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from .strokes import as_points

__all__ = ["directed_hausdorff", "directed_hausdorff_boxes", "hausdorff", "hausdorff_boxes"]

# Pairs of polygons handled at once: bounds the (chunk, p, q, 2) temporaries (~8 MB for boxes).
_PAIRS_PER_CHUNK = 1 << 15
# Convexity is checked up to this fraction of the squared polygon extent (rounding noise).
_CONVEXITY_SLACK = 1e-9


# --------------------------------------------------------------------------- point sets


def directed_hausdorff(a, b) -> float:
    """Directed Hausdorff distance from the point set ``a`` to the point set ``b``.

    Parameters
    ----------
    a, b : array_like, shape (n, 2) and (m, 2)
        Non-empty sets of points (e.g. ``Element.points``).

    Returns
    -------
    float
        ``max_i min_j |a_i - b_j|``: 0 when every point of ``a`` is a point of ``b``.

    Raises
    ------
    ValueError
        If a set is empty, is not ``(n, 2)``, or holds NaN or infinite coordinates.

    See Also
    --------
    hausdorff : the symmetric distance.

    Notes
    -----
    One nearest-neighbour query per point of ``a`` in a KD-tree of ``b``: O((n + m) log m).

    References
    ----------
    .. [1] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern
       Analysis and Synthesis", Computer Graphics Forum 25(3), 2006, section 2.2.1
       (definition of dH).
    """
    a = as_points(a, name="a")
    b = as_points(b, name="b")
    return _directed_points(a, b)


def hausdorff(a, b) -> float:
    """Hausdorff distance between two point sets: the larger of the two directed ones.

    Parameters
    ----------
    a, b : array_like, shape (n, 2) and (m, 2)
        Non-empty sets of points.

    Returns
    -------
    float
        ``max(directed_hausdorff(a, b), directed_hausdorff(b, a))``; symmetric, 0 iff the
        sets hold the same points.

    Raises
    ------
    ValueError
        If a set is empty, is not ``(n, 2)``, or holds NaN or infinite coordinates.

    References
    ----------
    .. [1] P. Barla et al., "Stroke Pattern Analysis and Synthesis", Computer Graphics
       Forum 25(3), 2006, section 2.2.1.
    """
    a = as_points(a, name="a")
    b = as_points(b, name="b")
    return max(_directed_points(a, b), _directed_points(b, a))


def _directed_points(a: np.ndarray, b: np.ndarray) -> float:
    distances, _ = cKDTree(b).query(a, k=1)
    return float(distances.max())


# --------------------------------------------------------------------------- convex polygons


def directed_hausdorff_boxes(corners_a, corners_b):
    """Directed Hausdorff distance between filled convex polygons, for one or many pairs.

    Parameters
    ----------
    corners_a, corners_b : array_like, shape (..., p, 2) and (..., q, 2)
        Vertices of convex polygons in boundary order (either orientation), e.g. the four
        corners of oriented bounding boxes, shape ``(4, 2)`` or ``(k, 4, 2)``. The leading
        dimensions broadcast against each other, so one box can be compared with ``k``
        boxes. Degenerate polygons are fine: a box of zero width is a segment, one of
        zero size a point.

    Returns
    -------
    float or ndarray
        ``h(A, B) = max over points x of region A of the distance from x to region B``
        (0 when A lies inside B). A float for one pair, else an array of the broadcast
        leading shape.

    Raises
    ------
    ValueError
        If the arrays are not ``(..., p, 2)`` with ``p >= 1``, hold NaN or infinite
        values, have leading shapes that do not broadcast, or a polygon is not convex
        with its vertices in boundary order.

    See Also
    --------
    hausdorff_boxes : the symmetric distance.

    Notes
    -----
    The result is exact, computed from the vertices of A alone. Why the vertices suffice:
    the distance to a convex set B, ``d_B(x) = min over y in B of |x - y|``, is a convex
    function of x (for x1, x2 with nearest points y1, y2 in B, the point
    ``t y1 + (1 - t) y2`` lies in B, so ``d_B(t x1 + (1 - t) x2) <= t d_B(x1) +
    (1 - t) d_B(x2)``). Every point of the filled polygon A is a convex combination of
    its vertices, so by convexity ``d_B`` there is at most its largest value at a vertex:
    ``h(A, B) = max over vertices v of A of d_B(v)`` [2]_. And ``d_B(v)`` is 0 when v is
    inside B, else the distance from v to the nearest edge of B. Cost O(p q) per pair.

    References
    ----------
    .. [1] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern
       Analysis and Synthesis", Computer Graphics Forum 25(3), 2006, sections 2.2.1
       (proximity: "computed using point-line distances between the bounding boxes")
       and 3.1 (shape measure).
    .. [2] M. J. Atallah, "A linear time algorithm for the Hausdorff distance between
       convex polygons", Information Processing Letters 17(4), 1983, 207-209.
    .. [3] T. Hurtut, P.-E. Landes, J. Thollot, Y. Gousseau, R. Drouilhet,
       J.-F. Coeurjolly, "Appearance-guided Synthesis of Element Arrangements by
       Example", NPAR 2009, section 4.3 (Hausdorff distance between bounding boxes as
       the interaction distance for elongated elements).
    """
    a, b, shape = _polygon_pairs(corners_a, corners_b)
    return _per_pair(_directed_convex(a, b), shape)


def hausdorff_boxes(corners_a, corners_b):
    """Hausdorff distance between filled convex polygons, for one or many pairs.

    Parameters
    ----------
    corners_a, corners_b : array_like, shape (..., p, 2) and (..., q, 2)
        Vertices of convex polygons in boundary order, e.g. oriented bounding boxes as
        ``(4, 2)`` or ``(k, 4, 2)`` arrays; leading dimensions broadcast.

    Returns
    -------
    float or ndarray
        ``max(h(A, B), h(B, A))`` of :func:`directed_hausdorff_boxes`: a float for one
        pair, else an array of the broadcast leading shape.

    Raises
    ------
    ValueError
        As :func:`directed_hausdorff_boxes`.

    References
    ----------
    .. [1] P. Barla et al., "Stroke Pattern Analysis and Synthesis", Computer Graphics
       Forum 25(3), 2006, section 2.2.1.
    .. [2] T. Hurtut et al., "Appearance-guided Synthesis of Element Arrangements by
       Example", NPAR 2009, section 4.3.
    """
    a, b, shape = _polygon_pairs(corners_a, corners_b)
    return _per_pair(np.maximum(_directed_convex(a, b), _directed_convex(b, a)), shape)


def _polygon_pairs(corners_a, corners_b) -> tuple[np.ndarray, np.ndarray, tuple]:
    """Validate both inputs; return them as ``(k, p, 2)`` and ``(k, q, 2)`` plus the
    broadcast leading shape (``()`` for a single pair)."""
    a = _as_convex_polygons(corners_a, "corners_a")
    b = _as_convex_polygons(corners_b, "corners_b")
    try:
        shape = np.broadcast_shapes(a.shape[:-2], b.shape[:-2])
    except ValueError:
        raise ValueError(
            f"corners_a {a.shape} and corners_b {b.shape}: the leading (pair) dimensions do not broadcast"
        ) from None
    a = np.broadcast_to(a, shape + a.shape[-2:]).reshape(-1, *a.shape[-2:])
    b = np.broadcast_to(b, shape + b.shape[-2:]).reshape(-1, *b.shape[-2:])
    return a, b, shape


def _per_pair(values: np.ndarray, shape: tuple):
    return float(values[0]) if shape == () else values.reshape(shape)


def _as_convex_polygons(corners, name: str) -> np.ndarray:
    try:
        polygons = np.array(corners, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be numeric (..., p, 2) polygon vertices: {exc}") from None
    if polygons.ndim < 2 or polygons.shape[-1] != 2 or polygons.shape[-2] < 1:
        raise ValueError(f"{name} must have shape (..., p, 2) with p >= 1 vertices, got {polygons.shape}")
    if not np.isfinite(polygons).all():
        raise ValueError(f"{name} contains NaN or infinite coordinates")
    flat = polygons.reshape(-1, *polygons.shape[-2:])
    bad = np.flatnonzero(~_by_chunks(_is_convex, flat))
    if bad.size:
        index = "".join(f"[{int(i)}]" for i in np.unravel_index(bad[0], polygons.shape[:-2]))
        raise ValueError(
            f"{name}{index} is not a convex polygon with its vertices in boundary order: {flat[bad[0]].tolist()}"
        )
    return polygons


def _orientation(polygons: np.ndarray) -> np.ndarray:
    """Sign of the shoelace area of each ``(p, 2)`` polygon: +1 counter-clockwise
    (y up), -1 clockwise, 0 for a degenerate (segment or point) polygon."""
    x, y = polygons[..., 0], polygons[..., 1]
    twice_area = (x * np.roll(y, -1, axis=-1) - np.roll(x, -1, axis=-1) * y).sum(axis=-1)
    return np.sign(twice_area)


def _edges_and_offsets(polygons: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Edge vectors ``(k, 1, q, 2)`` of ``(k, q, 2)`` polygons and the offsets ``(k, n, q, 2)``
    of each of ``(k, n, 2)`` points from each edge's start vertex."""
    edge = np.roll(polygons, -1, axis=1) - polygons
    offset = points[:, :, None, :] - polygons[:, None, :, :]
    return edge[:, None], offset


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def _is_convex(polygons: np.ndarray) -> np.ndarray:
    """Whether each polygon of ``(k, p, 2)`` is convex with vertices in boundary order:
    every vertex lies on the inner side of (or on) every edge line, up to rounding. A
    polygon of zero signed area must have all its vertices on one line (then any closed
    walk through them covers their hull, a segment); a bow tie has zero area too and fails.
    """
    slack = _CONVEXITY_SLACK * np.ptp(polygons, axis=1).max(axis=1)[:, None, None] ** 2
    side = _cross(*_edges_and_offsets(polygons, polygons))
    orientation = _orientation(polygons)[:, None, None]
    ok = np.where(orientation == 0, np.abs(side) <= slack, side * orientation >= -slack)
    return np.all(ok, axis=(1, 2))


def _directed_convex(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """h(A_i, B_i) for every pair of ``(k, p, 2)`` and ``(k, q, 2)`` convex polygons."""
    return _by_chunks(lambda a, b: _distance_to_region(a, b).max(axis=1), a, b)


def _by_chunks(function, *arrays: np.ndarray) -> np.ndarray:
    """``function`` applied to consecutive slices of the ``arrays`` (all of one length),
    results concatenated: bounds the memory of the (pairs, p, q, 2) temporaries."""
    starts = range(0, max(len(arrays[0]), 1), _PAIRS_PER_CHUNK)
    return np.concatenate([function(*(x[s : s + _PAIRS_PER_CHUNK] for x in arrays)) for s in starts])


def _distance_to_region(points: np.ndarray, polygons: np.ndarray) -> np.ndarray:
    """Distance from each of the ``(k, n, 2)`` points to the filled convex polygon of its
    pair: 0 inside, else the distance to the nearest edge. Shape ``(k, n)``."""
    edge, offset = _edges_and_offsets(polygons, points)
    squared_length = (edge**2).sum(axis=-1)
    along = (offset * edge).sum(axis=-1) / np.where(squared_length > 0, squared_length, 1.0)
    gap = offset - np.clip(along, 0.0, 1.0)[..., None] * edge
    distance = np.hypot(gap[..., 0], gap[..., 1]).min(axis=2)
    # Inside: on the inner side of every edge. A degenerate polygon (orientation 0) has
    # no interior; its region is its edges, already measured above.
    orientation = _orientation(polygons)[:, None, None]
    inside = np.all(_cross(edge, offset) * orientation >= 0, axis=2) & (orientation[..., 0] != 0)
    return np.where(inside, 0.0, distance)
