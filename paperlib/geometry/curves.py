"""Closed curves (rings): area, centroid, orientation, resampling at uniform arc length.

A *ring* is an ``(n, 2)`` array of the vertices of a closed polyline given without a
repeated end point; the edge from the last vertex back to the first belongs to it.
Coastlines, country borders and leaf outlines are rings; Simhon 2001 (section 3)
resamples curves at uniform arc length before computing tangent angles.
"""

from __future__ import annotations

import numpy as np

from .._checks import budget, check_budget, integer_at_least, point_array
from .strokes import as_points

__all__ = [
    "MAX_RESAMPLE_POINTS",
    "drop_repeated_vertices",
    "oriented_ccw",
    "resample_closed_curve",
    "resample_open_curve",
    "ring_centroid",
    "signed_area",
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

    Raises
    ------
    ValueError
        If ``ring`` is not a finite ``(n, 2)`` array.
    """
    return 0.5 * float(_shoelace_terms(point_array(ring, "ring")).sum())


def ring_centroid(ring) -> np.ndarray:
    """Centroid of the region enclosed by a simple ring (not the mean of its vertices).

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
    n_points = _checked_count(n_points, 3, max_points)
    ring = as_points(ring, name="ring", min_points=2)
    closed = np.vstack([ring, ring[:1]])
    arc = _arc_lengths(closed)
    return _points_at(closed, arc, np.arange(n_points) * (arc[-1] / n_points))


def resample_open_curve(points, n_points: int, *, max_points: int = MAX_RESAMPLE_POINTS) -> np.ndarray:
    """Resample an open polyline at ``n_points`` points equally spaced in arc length.

    The first and last output points are the polyline's end points; the others lie on it
    at arc lengths ``k L / (n_points - 1)``. ``max_points`` is the budget of
    :func:`resample_closed_curve`.

    Raises
    ------
    ValueError
        If ``n_points`` is not an integer >= 2 (or above ``max_points``) or the polyline has zero length.
    """
    n_points = _checked_count(n_points, 2, max_points)
    points = as_points(points, name="points", min_points=2)
    arc = _arc_lengths(points)
    return _points_at(points, arc, np.linspace(0.0, arc[-1], n_points))


def _arc_lengths(polyline: np.ndarray) -> np.ndarray:
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(polyline, axis=0).T))])
    if arc[-1] <= 0:
        raise ValueError("cannot resample a curve of zero length")
    return arc


def _points_at(polyline: np.ndarray, arc: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """Points at the given arc lengths, by linear interpolation along the polyline."""
    return np.column_stack([np.interp(targets, arc, polyline[:, 0]), np.interp(targets, arc, polyline[:, 1])])
