"""How an elaboration compares with its sketch and its training class (the statistics of Figs. 3-6).

Simhon 2001 claims (section 3.1) that the synthesized curves *"maintain the statistical properties of the
training set and the overall shape of the hand-drawn curve"* and that *"most of the curves generated are
novel ones, never seen in the training set"*. These measures make the claims checkable:

- :func:`curve_hausdorff`: how far the elaboration strays from the sketch (the overall shape);
- :func:`turning_per_sample` and :func:`turning_ks`: the distribution of the turning between successive
  samples, the finest-scale statistic the chain learns, compared by the two-sample Kolmogorov-Smirnov
  distance;
- :func:`box_counting_dimension`: the roughness across scales, a coastline's classic statistic;
- :func:`.steering.copied_runs`: novelty, the runs copied from one training curve.

Curves are compared as polylines at equal arc-length samples; the turning statistics assume both curves
have the same number of samples per unit of detail (an elaboration and the training curves do: one sample
of the sketch takes one training sample's detail).
"""

from __future__ import annotations

from numbers import Real

import numpy as np
from scipy.stats import ks_2samp

from .._checks import budget, check_budget, check_flag, float_array
from ..geometry import as_points, hausdorff, turning_angles

__all__ = ["MAX_DENSE_SAMPLES", "box_counting_dimension", "curve_hausdorff", "densify", "turning_ks",
           "turning_per_sample"]

#: Default budget (``max_samples``) of :func:`densify` and of the measures that densify: the most points
#: a densified curve may hold (1e7 points, 160 MB), checked before anything is allocated.
MAX_DENSE_SAMPLES = 10_000_000

# Box sizes as fractions of the curve's larger side: coarse enough to see several boxes, fine enough to stay
# above the sample spacing of a 256-sample coastline (about 1/40 of its side).
BOX_FRACTIONS = (1 / 4, 1 / 8, 1 / 16, 1 / 32)


def _polyline(points, closed: bool, name: str) -> np.ndarray:
    closed = check_flag(closed, "closed")
    points = as_points(points, name=name)
    if len(points) < 2:
        raise ValueError(f"{name} needs at least 2 points, got {len(points)}")
    return np.vstack([points, points[:1]]) if closed else points


def densify(points, *, closed: bool, spacing: float, max_samples: int = MAX_DENSE_SAMPLES) -> np.ndarray:
    """The polyline's vertices plus points every ``spacing`` (at most) along each of its segments.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The polyline's vertices (finite, at least 2); a closed ring without its first point repeated.
    closed : bool
        Whether the last vertex joins the first.
    spacing : float
        Largest distance between consecutive output points (> 0).
    max_samples : int, optional
        Budget: the most output points (default :data:`MAX_DENSE_SAMPLES`); a spacing that needs more
        raises ValueError before anything is allocated.

    Returns
    -------
    ndarray of float64, shape (m, 2)
        The vertices and the points between them, in order; for a closed ring the first vertex is not
        repeated at the end, for an open polyline the last vertex ends it.
    """
    closed = check_flag(closed, "closed")
    if not isinstance(spacing, Real) or not spacing > 0:
        raise ValueError(f"spacing must be positive, got {spacing!r:.60}")
    polyline = _polyline(points, closed, "points")
    starts, moves = polyline[:-1], np.diff(polyline, axis=0)
    pieces = np.maximum(np.ceil(np.hypot(*moves.T) / spacing), 1.0)  # float: no int64 overflow before the check
    check_budget(float(pieces.sum()) + 1, budget(max_samples, "max_samples"), "max_samples", "densified points")
    pieces = pieces.astype(np.int64)
    segment = np.repeat(np.arange(len(starts)), pieces)
    fraction = (np.arange(pieces.sum()) - np.repeat(np.cumsum(pieces) - pieces, pieces)) / np.repeat(pieces, pieces)
    dense = starts[segment] + fraction[:, None] * moves[segment]
    return dense if closed else np.vstack([dense, polyline[-1:]])


def curve_hausdorff(a, b, *, closed: bool, resolution: float | None = None,
                    max_samples: int = MAX_DENSE_SAMPLES) -> float:
    """Hausdorff distance between two curves (not only their vertices).

    Both polylines are densified to ``resolution`` (default: a hundredth of the smaller of their two mean
    segment lengths), so the result is the distance between the curves within ``resolution``.

    Parameters
    ----------
    a, b : array_like, shape (n, 2)
        The two curves' vertices (finite, at least 2 each), closed curves without a repeated end point.
    closed : bool
        Whether both curves are closed rings.
    resolution : float, optional
        Spacing the curves are densified to, in their units (> 0).
    max_samples : int, optional
        Budget of each densified curve (see :func:`densify`): two curves of very different sizes at the
        default resolution can need more.

    Returns
    -------
    float
        The Hausdorff distance between the densified curves, in the curves' units.
    """
    a, b = _polyline(a, closed, "a"), _polyline(b, closed, "b")
    if resolution is None:
        means = [float(np.hypot(*np.diff(c, axis=0).T).mean()) for c in (a, b)]
        resolution = 0.01 * min(means)
        if not resolution > 0:
            raise ValueError(f"{'a' if means[0] == 0 else 'b'} has zero length (all its points coincide): the "
                             f"default resolution is undefined; pass resolution= explicitly")
    elif not isinstance(resolution, Real) or not resolution > 0:
        raise ValueError(f"resolution must be a positive number or None, got {resolution!r:.60}")
    kept = slice(None, -1) if closed else slice(None)
    return hausdorff(densify(a[kept], closed=closed, spacing=resolution, max_samples=max_samples),
                     densify(b[kept], closed=closed, spacing=resolution, max_samples=max_samples))


def turning_per_sample(points, *, closed: bool) -> np.ndarray:
    """The signed turning (radians) at every sample: differences of successive tangent angles.

    A closed curve of ``n`` samples has ``n`` turnings, the closing turn included (they sum to its total
    turning); an open one ``n - 2``.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The curve's samples (finite, no two consecutive equal); a closed curve without its first
        point repeated.
    closed : bool
        Whether the last sample joins the first.

    Returns
    -------
    ndarray of float64, shape (n,) or (n - 2,)
        The turnings in radians, ``n`` for a closed curve and ``n - 2`` for an open one: the
        exterior angles of :func:`paperlib.geometry.turning_angles`, which are the differences of
        section 3.1's tangent angles.
    """
    return turning_angles(points, closed=closed)


def turning_ks(a, b) -> float:
    """Two-sample Kolmogorov-Smirnov distance between two sets of turnings (0: same distribution, 1: disjoint).

    Parameters
    ----------
    a, b : array_like
        The two sets of turnings, radians (finite, non-empty; flattened).

    Returns
    -------
    float
        The two-sample Kolmogorov-Smirnov statistic, in [0, 1].
    """
    try:
        a, b = (np.asarray(x, dtype=np.float64).ravel() for x in (a, b))
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"a and b must be arrays of turnings (numbers), got {type(a).__name__} and "
                         f"{type(b).__name__}") from None
    if a.size == 0 or b.size == 0 or not (np.isfinite(a).all() and np.isfinite(b).all()):
        raise ValueError(f"a and b must be non-empty sets of finite turnings, got sizes {a.size} and {b.size}")
    return float(ks_2samp(a, b).statistic)


def box_counting_dimension(points, *, closed: bool, fractions=BOX_FRACTIONS,
                           max_samples: int = MAX_DENSE_SAMPLES) -> float:
    """Box-counting dimension of a curve: the slope of log N(eps) against log(1 / eps).

    ``N(eps)`` counts the grid cells of side ``eps`` the curve passes through, ``eps`` running over
    ``fractions`` of the curve's larger side; the curve is densified to an eighth of the smallest box so
    that every cell a segment crosses is counted. 1 for a smooth curve, towards 2 for a space-filling one;
    the answer depends on the box sizes, so compare curves at the same sizes and the same sampling.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The curve's vertices (finite, at least 2, not all one point); a closed curve without its
        first point repeated.
    closed : bool
        Whether the last vertex joins the first.
    fractions : sequence of float, default (1/4, 1/8, 1/16, 1/32)
        Box sides as fractions of the curve's larger bounding-box side, at least two, each in (0, 1).
    max_samples : int, optional
        Budget of the densified curve (see :func:`densify`): very small boxes need more points.

    Returns
    -------
    float
        The least-squares slope of ``log N(eps)`` against ``log(1 / eps)``.
    """
    fractions = float_array(fractions, "fractions", "at least two box sizes in (0, 1)")
    if fractions.ndim != 1 or fractions.size < 2 or np.any(fractions <= 0) or np.any(fractions >= 1):
        raise ValueError("fractions must hold at least two box sizes in (0, 1)")
    polyline = _polyline(points, closed, "points")
    side = float(np.ptp(polyline, axis=0).max())
    if side == 0:
        raise ValueError("points: the curve is a single point (all its points coincide)")
    dense = densify(polyline[:-1] if closed else polyline, closed=closed, spacing=fractions.min() * side / 8,
                    max_samples=max_samples)
    origin = dense.min(axis=0)
    counts = [len(np.unique(np.floor((dense - origin) / (f * side)).astype(np.int64), axis=0)) for f in fractions]
    return float(np.polyfit(np.log(1 / fractions), np.log(counts), 1)[0])
