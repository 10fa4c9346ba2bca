"""Closed curves (rings): area, centroid, orientation, resampling at uniform arc length.

A *ring* is an ``(n, 2)`` array of the vertices of a closed polyline given without a
repeated end point; the edge from the last vertex back to the first belongs to it.
Coastlines, country borders and leaf outlines are rings; Simhon 2001 (section 3)
resamples curves at uniform arc length before computing tangent angles.
"""

from __future__ import annotations

import numpy as np

from .._checks import budget, check_budget, check_flag, integer_at_least, point_array
from .strokes import as_points

__all__ = [
    "MAX_RESAMPLE_POINTS",
    "drop_repeated_vertices",
    "oriented_ccw",
    "resample_closed_curve",
    "resample_open_curve",
    "ring_centroid",
    "signed_area",
    "turning_angles",
]

#: Default budget of the resamplers (``max_points``): the most output points, checked before allocating.
MAX_RESAMPLE_POINTS = 10**7


def _checked_count(n_points, minimum: int, max_points) -> int:
    n_points = integer_at_least(n_points, "n_points", minimum)
    check_budget(n_points, budget(max_points, "max_points"), "max_points", "resampled points")
    return n_points


def _shoelace_terms(ring: np.ndarray) -> np.ndarray:
    x, y = ring[:, 0], ring[:, 1]
    return x * np.roll(y, -1) - np.roll(x, -1) * y


def signed_area(ring) -> float:
    """Shoelace area of a ring: positive when counter-clockwise (y up).

    Parameters
    ----------
    ring : array_like, shape (n, 2)
        Vertices of a closed polyline (finite), without a repeated end vertex.

    Returns
    -------
    float
        The shoelace area: positive when counter-clockwise (y up), negative when clockwise.

    Raises
    ------
    ValueError
        If ``ring`` is not a finite ``(n, 2)`` array.
    """
    return 0.5 * float(_shoelace_terms(point_array(ring, "ring")).sum())


def ring_centroid(ring) -> np.ndarray:
    """Centroid of the region enclosed by a simple ring (not the mean of its vertices).

    Parameters
    ----------
    ring : array_like, shape (n, 2)
        Vertices of a simple closed polyline (finite), without a repeated end vertex.

    Returns
    -------
    ndarray of float64, shape (2,)
        The area-weighted centroid ``(x, y)`` of the enclosed region.

    Raises
    ------
    ValueError
        If the ring is not a finite ``(n, 2)`` array or encloses no area.
    """
    ring = point_array(ring, "ring")
    cross = _shoelace_terms(ring)
    area = 0.5 * cross.sum()
    if area == 0:
        raise ValueError("the ring encloses no area: its centroid is undefined")
    return ((ring + np.roll(ring, -1, axis=0)) * cross[:, None]).sum(axis=0) / (6.0 * area)


def drop_repeated_vertices(ring) -> np.ndarray:
    """The ring without consecutive duplicate vertices, cyclically.

    Of a run of equal vertices the last copy stays, so a closed polyline given with its
    first vertex repeated at the end loses the end copy and keeps its start vertex.

    Parameters
    ----------
    ring : array_like, shape (n, 2)
        Vertices of a closed polyline (finite), without or with a repeated end vertex.

    Returns
    -------
    ndarray of float64, shape (m, 2)
        The vertices with no two cyclically consecutive ones equal (m <= n).

    Raises
    ------
    ValueError
        If ``ring`` is not a finite ``(n, 2)`` array.
    """
    ring = point_array(ring, "ring")
    return ring[np.any(ring != np.roll(ring, -1, axis=0), axis=1)]


def oriented_ccw(ring) -> np.ndarray:
    """The ring, traversed the other way if needed so that its signed area is positive.

    The start vertex stays first (only the order of the others is reversed), so where a
    curve starts does not depend on how its source happened to orient it.

    Parameters
    ----------
    ring : array_like, shape (n, 2)
        Vertices of a closed polyline (finite), without a repeated end vertex.

    Returns
    -------
    ndarray of float64, shape (n, 2)
        The ring, counter-clockwise (non-negative signed area), starting at the same vertex.

    Raises
    ------
    ValueError
        If ``ring`` is not a finite ``(n, 2)`` array.
    """
    ring = point_array(ring, "ring")
    return ring if signed_area(ring) >= 0 else np.concatenate([ring[:1], ring[:0:-1]])


def resample_closed_curve(ring, n_points: int, *, max_points: int = MAX_RESAMPLE_POINTS) -> np.ndarray:
    """Resample a ring at ``n_points`` points equally spaced in arc length.

    Parameters
    ----------
    ring : array_like, shape (m, 2)
        Vertices of the closed curve, without a repeated end point.
    n_points : int
        Number of output points (>= 3).
    max_points : int, optional
        Budget: the largest ``n_points`` allowed (default :data:`MAX_RESAMPLE_POINTS`, 10**7).

    Returns
    -------
    ndarray, shape (n_points, 2)
        The points at arc lengths ``k L / n_points`` (``k = 0 .. n_points - 1``, ``L``
        the perimeter) from the first vertex, by linear interpolation along the
        polyline, so they lie on the input curve; no repeated end point.

    Raises
    ------
    ValueError
        If ``n_points`` is not an integer >= 3 (or above ``max_points``) or the curve has zero length.
    """
    return _resampled_ring(ring, n_points, max_points, "ring")


def _resampled_ring(ring, n_points, max_points, name: str) -> np.ndarray:
    """:func:`resample_closed_curve`, its messages naming the ring ``name`` (for callers whose parameter it is)."""
    n_points = _checked_count(n_points, 3, max_points)
    ring = as_points(ring, name=name, min_points=2)
    closed = np.vstack([ring, ring[:1]])
    arc = _arc_lengths(closed, name)
    return _points_at(closed, arc, np.arange(n_points) * (arc[-1] / n_points))


def resample_open_curve(points, n_points: int, *, max_points: int = MAX_RESAMPLE_POINTS) -> np.ndarray:
    """Resample an open polyline at ``n_points`` points equally spaced in arc length.

    The first and last output points are the polyline's end points; the others lie on it
    at arc lengths ``k L / (n_points - 1)``. ``max_points`` is the budget of
    :func:`resample_closed_curve`.

    Parameters
    ----------
    points : array_like, shape (m, 2)
        Vertices of the polyline (finite, at least 2, positive length).
    n_points : int
        Number of output points (>= 2).
    max_points : int, optional
        Budget: the largest ``n_points`` allowed (default :data:`MAX_RESAMPLE_POINTS`, 10**7).

    Returns
    -------
    ndarray of float64, shape (n_points, 2)
        The points along the polyline, from its first to its last vertex.

    Raises
    ------
    ValueError
        If ``n_points`` is not an integer >= 2 (or above ``max_points``) or the polyline has zero length.
    """
    n_points = _checked_count(n_points, 2, max_points)
    points = as_points(points, name="points", min_points=2)
    arc = _arc_lengths(points, "points")
    return _points_at(points, arc, np.linspace(0.0, arc[-1], n_points))


def _arc_lengths(polyline: np.ndarray, name: str) -> np.ndarray:
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(polyline, axis=0).T))])
    if arc[-1] <= 0:
        raise ValueError(f"{name}: cannot resample a curve of zero length (all its vertices coincide)")
    return arc


def _points_at(polyline: np.ndarray, arc: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """Points at the given arc lengths, by linear interpolation along the polyline."""
    return np.column_stack([np.interp(targets, arc, polyline[:, 0]), np.interp(targets, arc, polyline[:, 1])])


def turning_angles(points, *, closed: bool) -> np.ndarray:
    """The signed turning angle (radians, in ``(-pi, pi]``) at every vertex of a polyline.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        Vertices, ``n >= 3``, no two consecutive equal; a closed curve without a repeated end.
    closed : bool
        True: the edge from the last vertex to the first belongs to the curve and every vertex turns
        (``n`` angles, the first at vertex 1, the last at vertex 0; they sum to the total turning).
        False: the ``n - 2`` interior vertices.

    Returns
    -------
    numpy.ndarray
        ``atan2(cross, dot)`` of successive edge vectors: the exterior angle, positive to the left.
        What ``paperlib.sketch.turning_per_sample`` returns: the differences of Simhon
        2001's tangent angles (section 3.1) at uniform arc-length samples.

    Raises
    ------
    ValueError
        Fewer than 3 vertices, non-finite coordinates, repeated consecutive vertices, or a closed
        curve that repeats its first vertex at the end.
    TypeError
        ``closed`` not a bool.
    """
    closed = check_flag(closed, "closed")
    points = point_array(points, "points", min_points=3)
    if np.any(np.all(np.diff(points, axis=0) == 0, axis=1)):
        raise ValueError("points has repeated consecutive vertices: drop them first (drop_repeated_vertices)")
    if closed:
        if np.all(points[-1] == points[0]):
            raise ValueError("points of a closed curve must not repeat the first vertex at the end")
        points = np.vstack([points, points[:2]])
    edges = np.diff(points, axis=0)
    a, b = edges[:-1], edges[1:]
    return np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.einsum("ij,ij->i", a, b))
