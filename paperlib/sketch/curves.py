"""Curves as tangent-angle signals over arc length, and their multi-scale analysis (Simhon 2001, section 3).

A curve is resampled at ``n`` points equally spaced in arc length; its *tangent angle* ``theta(t)`` is the
direction of the segment from sample ``t`` to sample ``t + 1``, unwrapped so that it varies continuously (a
counter-clockwise closed curve turns by ``2 pi`` in total). Integrating the angles with the sample spacing
gives the curve back (:func:`integrate_angles`), so any signal of angles is a curve.

The multi-scale analysis filters ``theta`` repeatedly with a low-pass filter: scale 0 is ``theta`` itself,
scale ``s`` is ``s`` passes of the filter (section 3: *"Multi-scale analysis is performed by repeatedly
filtering the training curves using a low-pass filter"*; the paper used *"a uniform average filter"*). On a
closed curve the filter runs cyclically on ``theta`` minus its linear trend (the total turning spread evenly),
which is periodic; the trend is added back, as a symmetric filter leaves a linear function unchanged.

References
----------
.. [1] S. Simhon and G. Dudek, "On the Elaboration of Hand-Drawn Sketches", McGill University, 2001:
   section 3 (eq. 1-2: the steering component as a low-pass filter of theta; the multi-scale analysis).
"""

from __future__ import annotations

from math import comb

import numpy as np
import shapely
from scipy.ndimage import convolve1d

from .._checks import (check_budget, check_flag, finite_array, integer_at_least, label, point_array,
                       positive_number)
from ..geometry import as_points, resample_open_curve
from ..geometry.curves import MAX_RESAMPLE_POINTS, _resampled_ring

__all__ = [
    "check_curve",
    "close_angles",
    "coarse_ring",
    "close_curve",
    "filter_weights",
    "gyration_radius",
    "integrate_angles",
    "lowpass",
    "match_size",
    "multiscale_angles",
    "resample_curve",
    "resample_simple",
    "tangent_angles",
    "total_turning",
    "wrap_angle",
]

#: Default budget of :func:`multiscale_angles`: the most values (scales x samples) it may hold, 2**26 doubles
#: (512 MiB). Raise it with the ``max_values`` keyword.
MAX_SCALE_VALUES = 2**26
#: The widest built-in filter: wider than any curve's samples would average it flat many times over.
MAX_FILTER_WIDTH = 2**16 + 1


def wrap_angle(angle):
    """Angles wrapped to ``[-pi, pi)``: the signed difference of two directions.

    Parameters
    ----------
    angle : float or array_like
        Angles in radians (finite).

    Returns
    -------
    float64 or ndarray of float64
        The angles wrapped to ``[-pi, pi)``, the shape of ``angle``.

    Raises
    ------
    ValueError
        If ``angle`` is not numeric or holds NaN or infinite values.
    """
    return _wrap(finite_array(angle, "angle"))


def _wrap(angle):
    """:func:`wrap_angle` without the check, for the package's own finite arrays."""
    return (np.asarray(angle) + np.pi) % (2.0 * np.pi) - np.pi


def check_curve(points, *, closed: bool, min_points: int = 3, name: str = "curve") -> np.ndarray:
    """Validate a drawn curve: finite ``(n, 2)`` points, no repeated point, not self-crossing.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The vertices; a closed curve is given without its first point repeated at the end (a repeated end
        point is dropped).
    closed : bool
        Whether the last vertex joins the first.
    min_points : int
        The fewest vertices accepted.
    name : str, default "curve"
        How error messages name the curve.

    Returns
    -------
    ndarray, shape (n, 2), float64

    Raises
    ------
    ValueError
        On NaN or infinite coordinates, fewer than ``min_points`` vertices, two consecutive equal vertices
        (a zero-length segment, whose tangent is undefined), or a curve that crosses itself.
    """
    name = label(name)
    closed = check_flag(closed, "closed")
    min_points = integer_at_least(min_points, "min_points", 0)
    points = np.array(as_points(points, name=name, min_points=2))
    if closed and len(points) > 2 and np.array_equal(points[0], points[-1]):
        points = points[:-1]
    if len(points) < min_points:
        raise ValueError(f"{name} needs at least {min_points} points, got {len(points)}")
    following = np.roll(points, -1, axis=0) if closed else points[1:]
    repeated = np.flatnonzero(np.all(following == points[: len(following)], axis=1))
    if repeated.size:
        raise ValueError(f"{name} repeats a point at index {int(repeated[0])} (a zero-length segment): successive "
                         f"points must differ")
    line = shapely.LinearRing(points) if closed else shapely.LineString(points)
    if not line.is_simple:
        raise ValueError(f"{name} crosses itself; draw a simple curve through the points")
    return points


def resample_curve(points, n_points: int, *, closed: bool) -> np.ndarray:
    """``n_points`` samples equally spaced in arc length along a closed ring or an open polyline.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The vertices (finite); a closed ring without its first point repeated.
    n_points : int
        Number of samples (>= 3 closed, >= 2 open).
    closed : bool
        Whether the last vertex joins the first.

    Returns
    -------
    ndarray of float64, shape (n_points, 2)
        The samples, starting at the first vertex (an open polyline's last sample is its last vertex).
    """
    closed = check_flag(closed, "closed")
    if closed:
        return _resampled_ring(points, n_points, MAX_RESAMPLE_POINTS, "points")
    return resample_open_curve(points, n_points)


def resample_simple(points, n_points: int, *, closed: bool, name: str = "curve") -> np.ndarray:
    """Resample a simple curve at ``n_points`` samples equally spaced in arc length, keeping it simple.

    Equal arc-length samples of a curve with features narrower than the spacing (a coastline's thin
    peninsulas) can join across them and cross. When they do, the curve is first simplified (Douglas-Peucker
    with topology preserved, shapely) at a quarter, a half, then one sample spacing, until the resampled
    curve is simple; a curve that resamples simply is left as it is.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The simple curve's vertices (finite); a closed ring without its first point repeated.
    n_points : int
        Number of samples (>= 3 closed, >= 2 open).
    closed : bool
        Whether the last vertex joins the first.
    name : str, default "curve"
        How error messages name the curve.

    Returns
    -------
    ndarray of float64, shape (n_points, 2)
        The samples, equally spaced in arc length along the curve (or along its simplification),
        forming a simple curve.

    Raises
    ------
    ValueError
        If ``points`` is not a finite ``(n, 2)`` array of at least 3 points (closed) or 2 (open), ``n_points`` is
        not an integer of at least that many, or the resampled curve still crosses itself (ask for more samples).
    """
    closed = check_flag(closed, "closed")
    name = label(name)
    least = 3 if closed else 2
    points = point_array(points, "points", min_points=least)
    n_points = integer_at_least(n_points, "n_points", least)
    line = shapely.LinearRing(points) if closed else shapely.LineString(points)
    if line.length == 0:
        raise ValueError("points are all one point: a curve needs length to be resampled")
    for fraction in (0.0, 0.25, 0.5, 1.0):
        geometry = line.simplify(fraction * line.length / n_points, preserve_topology=True)
        if geometry is None or geometry.is_empty:  # GEOS could not simplify at this tolerance: try the next
            continue
        simplified = np.asarray(geometry.coords)
        resampled = resample_curve(simplified[:-1] if closed else simplified, n_points, closed=closed)
        if (shapely.LinearRing(resampled) if closed else shapely.LineString(resampled)).is_simple:
            return resampled
    raise ValueError(f"{name} crosses itself once resampled at n_points={n_points} samples; use more samples")


def tangent_angles(points, *, closed: bool) -> np.ndarray:
    """Unwrapped tangent angle ``theta(t)`` of each segment (section 3).

    Returns ``n`` angles for a closed curve of ``n`` samples (the last segment joins the last sample to the
    first), ``n - 1`` for an open one.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The curve's samples (finite, n >= 2, no two successive equal); a closed curve without its first
        point repeated.
    closed : bool
        Whether the last sample joins the first.

    Returns
    -------
    ndarray of float64, shape (n,) or (n - 1,)
        The unwrapped angles, radians.

    Raises
    ------
    ValueError
        If ``points`` is not a finite ``(n, 2)`` array of at least 2 points, or two successive points coincide.
    TypeError
        If ``closed`` is not True or False.
    """
    closed = check_flag(closed, "closed")
    points = point_array(points, "points", min_points=2)
    path = np.vstack([points, points[:1]]) if closed else points
    steps = np.diff(path, axis=0)
    if np.any(np.all(steps == 0.0, axis=1)):
        raise ValueError("points: the curve has a zero-length segment (two successive points coincide): its tangent "
                         "angle is undefined")
    return np.unwrap(np.arctan2(steps[:, 1], steps[:, 0]))


def total_turning(theta) -> float:
    """Total turning of a closed curve's angles, the closing turn from the last segment to the first included.

    Parameters
    ----------
    theta : array_like, shape (n,)
        Unwrapped tangent angles of a closed curve, radians (finite, non-empty).

    Returns
    -------
    float
        The total turning in radians (2 pi for a simple counter-clockwise curve).

    Raises
    ------
    ValueError
        If ``theta`` is not a non-empty finite 1-D array.
    """
    return _total_turning(finite_array(theta, "theta", ndim=1, min_size=1))


def _total_turning(theta: np.ndarray) -> float:
    return float(theta[-1] + _wrap(theta[0] - theta[-1]) - theta[0])


def filter_weights(filter_width: int = 9, kernel="uniform") -> np.ndarray:
    """The low-pass filter's weights, normalised to sum 1.

    Parameters
    ----------
    filter_width : int
        Odd number of taps of the built-in kernels (>= 1; 1 is no filtering).
    kernel : {"uniform", "binomial"} or array_like
        ``"uniform"``: the moving average of the paper; ``"binomial"``: binomial weights (a discrete
        Gaussian); or any symmetric odd-length array of weights with a positive sum (``filter_width`` is then
        ignored).

    Returns
    -------
    ndarray of float64, shape (k,)
        The taps, symmetric and summing to 1 (``k = filter_width`` for the built-in kernels).
    """
    if isinstance(kernel, str):
        if isinstance(filter_width, bool) or not isinstance(filter_width, (int, np.integer)):
            raise ValueError(f"filter_width must be an odd integer >= 1, got {filter_width!r}")
        if filter_width < 1 or filter_width % 2 == 0 or filter_width > MAX_FILTER_WIDTH:
            raise ValueError(f"filter_width must be an odd integer in [1, {MAX_FILTER_WIDTH}], got {filter_width!r}")
        if kernel == "uniform":
            weights = np.ones(filter_width)
        elif kernel == "binomial":
            weights = np.array([float(comb(filter_width - 1, k)) for k in range(filter_width)])
        else:
            raise ValueError(f"kernel must be 'uniform', 'binomial' or an array of weights, got {kernel!r}")
    else:
        weights = np.asarray(kernel, dtype=np.float64)
        if weights.ndim != 1 or weights.size % 2 == 0 or not np.isfinite(weights).all():
            raise ValueError("a kernel array must be one-dimensional, of odd length and finite")
        if not np.allclose(weights, weights[::-1]) or weights.sum() <= 0:
            raise ValueError("a kernel array must be symmetric with a positive sum (a low-pass filter)")
    return weights / weights.sum()


def lowpass(theta, weights, *, closed: bool, causal: bool = False) -> np.ndarray:
    """One pass of the low-pass filter over a tangent-angle signal (cyclic on a closed curve).

    ``causal=False`` centres the filter on each sample (it looks ``len(weights) // 2`` samples ahead);
    ``causal=True`` is the paper's *"time-invariant causal linear filter"* (section 3, eq. 2): output ``t``
    weighs samples ``t, t - 1, ..., t - len(weights) + 1`` only, so the result lags the signal by the
    filter's mean delay ``sum_k k w_k`` (half its width for a symmetric filter).

    Parameters
    ----------
    theta : array_like, shape (n,)
        Tangent angles, radians (finite, non-empty).
    weights : array_like, shape (k,)
        The filter's taps (:func:`filter_weights`).
    closed : bool
        Filter cyclically (a closed curve, the linear trend of its total turning removed first) or,
        for an open one, with the end samples repeated beyond the ends.
    causal : bool, default False
        Use the paper's causal filter instead of the centred one.

    Returns
    -------
    ndarray of float64, shape (n,)
        The filtered angles.

    Raises
    ------
    ValueError
        If ``theta`` or ``weights`` is not a non-empty finite 1-D array.
    TypeError
        If ``closed`` or ``causal`` is not a bool.
    """
    theta, weights = _signal(theta), _taps(weights)
    return _lowpass(theta, weights, check_flag(closed, "closed"), check_flag(causal, "causal"))


def _signal(theta) -> np.ndarray:
    return finite_array(theta, "theta", ndim=1, min_size=1)


def _taps(weights) -> np.ndarray:
    return finite_array(weights, "weights", ndim=1, min_size=1)


def _lowpass(theta: np.ndarray, weights: np.ndarray, closed: bool, causal: bool) -> np.ndarray:
    # convolve1d centres the kernel; moving its origin by half its width makes it use the past only
    origin = -(weights.size // 2) if causal else 0
    if not closed:
        return convolve1d(theta, weights, mode="nearest", origin=origin)
    slope = _total_turning(theta) / theta.size
    trend = slope * np.arange(theta.size)
    lag = float(np.dot(np.arange(weights.size), weights)) if causal else 0.0
    return convolve1d(theta - trend, weights, mode="wrap", origin=origin) + trend - slope * lag


def multiscale_angles(theta, scales: int, weights, *, closed: bool, causal: bool = False,
                      max_values: int = MAX_SCALE_VALUES) -> np.ndarray:
    """The angles at ``scales`` scales, shape ``(scales, n)``: row ``s`` is ``s`` passes of the filter.

    Parameters
    ----------
    theta : array_like, shape (n,)
        Tangent angles (finite).
    scales : int
        Number of scales, the unfiltered angles included: at least 1 and at most ``n``, the signal's
        length (a signal of ``n`` samples has no more scales to tell apart than samples).
    weights : array_like
        The filter's taps (:func:`filter_weights`).
    closed, causal : bool
        As in :func:`lowpass`.
    max_values : int
        Budget: the most values ``scales * n`` the result may hold (default :data:`MAX_SCALE_VALUES`).

    Returns
    -------
    ndarray of float64, shape (scales, n)
        Row 0 the angles themselves, row ``s`` after ``s`` passes of the filter.

    Raises
    ------
    ValueError
        On non-finite input, ``scales`` out of ``[1, n]``, or a result above ``max_values``.
    """
    theta, weights = _signal(theta), _taps(weights)
    scales = integer_at_least(scales, "scales", 1)
    if scales > theta.size:
        raise ValueError(f"scales must be at most the signal's length {theta.size}, got {scales}")
    check_budget(scales * theta.size, integer_at_least(max_values, "max_values", 1), "max_values", "angle values")
    closed, causal = check_flag(closed, "closed"), check_flag(causal, "causal")
    levels = [theta]
    for _ in range(scales - 1):
        levels.append(_lowpass(levels[-1], weights, closed, causal))
    return np.stack(levels)


def integrate_angles(theta, step: float, start=(0.0, 0.0)) -> np.ndarray:
    """The polyline whose segments have length ``step`` and directions ``theta``: ``len(theta) + 1`` points.

    Parameters
    ----------
    theta : array_like, shape (n,)
        Segment directions, radians (finite).
    step : float
        Length of every segment (> 0).
    start : array_like, shape (2,), default (0, 0)
        The first point.

    Returns
    -------
    ndarray of float64, shape (n + 1, 2)
        The polyline's points, from ``start``.

    Raises
    ------
    ValueError
        If ``theta`` is not a finite 1-D array, ``step`` not a positive finite number or ``start`` not a finite
        point.
    """
    theta = finite_array(theta, "theta", ndim=1)
    step = positive_number(step, "step")
    start = point_array(np.reshape(finite_array(start, "start"), (1, -1)), "start")[0]
    moves = step * np.column_stack([np.cos(theta), np.sin(theta)])
    return np.vstack([np.zeros((1, 2)), np.cumsum(moves, axis=0)]) + start


def gyration_radius(points) -> float:
    """Root mean square distance of the points to their centroid: a curve's size, robust to its wiggles.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The points (finite, n >= 1).

    Returns
    -------
    float
        ``sqrt(mean |p - centroid|^2)``, in the points' units.

    Raises
    ------
    ValueError
        If ``points`` is not a finite ``(n, 2)`` array with ``n >= 1``.
    """
    points = point_array(points, "points", min_points=1)
    return float(np.sqrt(((points - points.mean(axis=0)) ** 2).sum(axis=1).mean()))


def match_size(points, reference) -> np.ndarray:
    """``points`` scaled about their centroid to the radius of gyration of ``reference``, moved onto its centroid.

    A detailed curve and a smooth curve of the same arc length differ in size (the detail's wiggles use up
    length), so a coarse version or an elaboration is brought to the size and place of the curve it stands
    for. Both are sets of samples equally spaced in arc length, so their centroids are the curves'.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The curve to move and scale (finite, not all one point).
    reference : array_like, shape (m, 2)
        The curve whose size and place it takes (finite).

    Returns
    -------
    ndarray of float64, shape (n, 2)
        ``points`` scaled about their centroid to the radius of gyration of ``reference`` and
        centred on its centroid.

    Raises
    ------
    ValueError
        If either is not a finite ``(n, 2)`` array, or ``points`` are all one point (no size to scale).
    """
    points, reference = point_array(points, "points", min_points=1), point_array(reference, "reference", min_points=1)
    centre = points.mean(axis=0)
    size = gyration_radius(points)
    if size == 0:
        raise ValueError("points are all the same point: they have no size to match")
    scale = gyration_radius(reference) / size
    return (points - centre) * scale + reference.mean(axis=0)


#: Newton iterations of :func:`close_angles` and the closing error (relative to the curve's length) it stops at.
CLOSE_ITERATIONS, CLOSE_TOLERANCE = 50, 1e-12


def close_angles(theta) -> np.ndarray:
    """The smallest change of a closed curve's tangent angles that closes it with the sample spacing kept.

    Segments of equal length in the directions ``theta`` end where they started only if
    ``sum exp(i theta) = 0``; a curve built from filtered or instantiated angles does not. This returns
    ``theta + delta`` with the least-squares ``delta`` that closes it (Gauss-Newton on the two closure
    equations, minimum-norm steps): ``delta`` is a smooth function of the direction (``a sin theta + b cos theta``
    to first order), so no kink appears, and every segment keeps its length, so the samples stay equally
    spaced in arc length (unlike :func:`close_curve`, which shifts every segment by the same vector and so
    changes their lengths).

    Parameters
    ----------
    theta : array_like, shape (n,)
        Tangent angles of a closed curve's equal-length segments, radians (finite, n >= 3).

    Returns
    -------
    ndarray of float64, shape (n,)
        ``theta + delta``, whose unit segments sum to zero (within ``n`` times the closing tolerance).

    Raises
    ------
    ValueError
        If ``theta`` is not a finite 1-D array of at least 3 angles, or the curve cannot be closed by turning
        its segments (all of them nearly parallel).
    """
    theta = finite_array(theta, "theta", ndim=1).copy()
    if theta.size < 3:
        raise ValueError(f"theta must hold at least 3 angles to close a curve, got {theta.size}")
    for _ in range(CLOSE_ITERATIONS):
        cos, sin = np.cos(theta), np.sin(theta)
        gap = np.array([cos.sum(), sin.sum()])
        if np.hypot(*gap) <= CLOSE_TOLERANCE * theta.size:
            return theta
        jacobian = np.vstack([-sin, cos])
        normal = jacobian @ jacobian.T
        if np.linalg.cond(normal) > 1e12:
            break
        theta -= jacobian.T @ np.linalg.solve(normal, gap)
    raise ValueError("theta cannot be closed by turning its segments: the curve is too far from closed")


def coarse_ring(theta, step: float, start) -> np.ndarray:
    """The closed curve of a closed curve's coarse angles: what a sketch of the curve looks like (``n`` points).

    Filtered angles of a closed curve do not integrate to a closed curve (a rounded spike no longer returns
    where it left), so they are closed: by turning the segments (:func:`close_angles`; equal spacing kept, so
    the ring's own tangent angles are the closed angles), or, when that crosses itself or cannot close, by
    distributing the gap (:func:`close_curve`). :func:`.steering.coarsen` draws sketches with it, and
    :func:`.model.train` compares the sketch with the training curves' steering scale as it draws them.

    Parameters
    ----------
    theta : array_like, shape (n,)
        The coarse (filtered) tangent angles of a closed curve, radians (finite, n >= 3).
    step : float
        Segment length, the curve's sample spacing (> 0).
    start : array_like, shape (2,)
        The ring's first point.

    Returns
    -------
    ndarray of float64, shape (n, 2)
        The closed ring, without a repeated end point.

    Raises
    ------
    ValueError
        If ``theta`` is not a finite 1-D array of at least 3 angles, ``step`` not positive or ``start`` not a
        finite point.
    """
    theta = finite_array(theta, "theta", ndim=1)
    if theta.size < 3:
        raise ValueError(f"theta must hold at least 3 angles (a closed curve), got {theta.size}")
    try:
        ring = integrate_angles(close_angles(theta), step, start=start)[:-1]
        if shapely.LinearRing(ring).is_simple:
            return ring
    except ValueError:   # too far from closed to turn closed
        pass
    return close_curve(integrate_angles(theta, step, start=start))


def close_curve(path: np.ndarray) -> np.ndarray:
    """Distribute a closed curve's closing error along it (our correction of the paper's closure problem).

    ``path`` holds ``n + 1`` points whose last should equal the first. Point ``k`` moves by ``-k / n`` of the
    gap, so the curve closes exactly, the start stays, and every segment changes by the same small vector.
    Returns the ``n`` points of the closed ring (the repeated end dropped).

    Parameters
    ----------
    path : array_like, shape (n + 1, 2)
        The integrated curve (finite, at least 2 points), whose last point should equal the first.

    Returns
    -------
    ndarray of float64, shape (n, 2)
        The closed ring, starting at ``path[0]``, without a repeated end point.

    Raises
    ------
    ValueError
        If ``path`` is not a finite ``(n + 1, 2)`` array with at least 2 points.
    """
    path = point_array(path, "path", min_points=2)
    gap = path[-1] - path[0]
    n = len(path) - 1
    return (path - np.outer(np.arange(n + 1) / n, gap))[:-1]
