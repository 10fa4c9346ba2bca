"""Lloyd relaxation: seeds moved to the centroids of their Voronoi cells clipped to a region.

Barla et al. 2006 (section 3.2, "Synthesizing a pattern") seed their 2D synthesis with
Lloyd's method: start from random seeds, then repeatedly compute the Voronoi diagram of the
seeds and move each seed to the centre of its Voronoi region; the seeds converge to a
centroidal Voronoi tessellation, "close to regular". Hurtut et al. 2009 (section 4.2,
Figure 6 right) compare their synthesis with that seeding.

The region is given as geometry, not as a :class:`paperlib.pointprocess.Window` (this floor
imports no other part of paperlib): a shapely (Multi)Polygon, e.g. a polygon window's
``window.shape``, or a rectangle ``(xmin, xmax, ymin, ymax)``, e.g. ``(*window.xrange,
*window.yrange)``.

Each iteration is vectorised in GEOS through shapely: :func:`shapely.voronoi_polygons`
(``ordered=True``, one cell per seed, extended to cover the region's envelope), one
:func:`shapely.intersection` with the region, :func:`shapely.centroid`. In a convex region the
clipped cells are convex and hold their centroid; in a non-convex region a clipped cell may
not, and a centroid outside its cell is replaced by the cell's nearest point to it
(:func:`shapely.shortest_line`), so the seeds never leave the region (the constrained
centroidal tessellation's usual projection). Nothing is written by hand that shapely offers.

References
----------
.. [1] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern Analysis and
   Synthesis", Computer Graphics Forum (Eurographics) 25(3), 2006, section 3.2 (seeding by
   Lloyd's method, N_tar = N_ref A_tar / A_ref seeds).
.. [2] S. P. Lloyd, "Least squares quantization in PCM", IEEE Transactions on Information
   Theory 28(2), 1982.
.. [3] Q. Du, V. Faber, M. Gunzburger, "Centroidal Voronoi tessellations: applications and
   algorithms", SIAM Review 41(4), 1999 (convergence to a centroidal tessellation).
.. [4] T. Hurtut et al., "Appearance-guided Synthesis of Element Arrangements by Example",
   NPAR 2009, section 4.2 and Figure 6 (right).
"""

from __future__ import annotations

import math

import numpy as np

from .._checks import budget, check_budget
from .strokes import as_points

__all__ = ["lloyd_relaxation"]


def _region(window):
    """The region as a prepared shapely (Multi)Polygon of positive area."""
    import shapely
    from shapely.geometry import MultiPolygon, Polygon

    if isinstance(window, (Polygon, MultiPolygon)):
        region = window
    else:
        if isinstance(window, (str, bytes)) or np.ndim(window) != 1 or len(window) != 4:
            raise ValueError("window must be a shapely (Multi)Polygon or a rectangle (xmin, xmax, ymin, ymax), "
                             f"got {window!r}")
        try:
            xmin, xmax, ymin, ymax = (float(v) for v in window)
        except (TypeError, ValueError):
            raise ValueError(f"window rectangle (xmin, xmax, ymin, ymax) must hold numbers, got {window!r}") from None
        if not all(map(math.isfinite, (xmin, xmax, ymin, ymax))) or not (xmax > xmin and ymax > ymin):
            raise ValueError("window rectangle (xmin, xmax, ymin, ymax) must be finite with xmax > xmin and "
                             f"ymax > ymin, got {window!r}")
        region = shapely.box(xmin, ymin, xmax, ymax)
    if region.is_empty or not region.is_valid or not region.area > 0:
        raise ValueError(f"window polygon must be valid with positive area, got {shapely.is_valid_reason(region)}"
                         f" and area {region.area:g}")
    shapely.prepare(region)
    return region


#: Default budget of :func:`lloyd_relaxation` (``max_cells``): Voronoi cells computed, points times
#: iterations, 2**22 (about a minute at some 13 microseconds a cell: 40 iterations of 1e5 seeds fit).
MAX_CELLS = 2**22


def _iterations(iterations) -> int:
    if isinstance(iterations, bool) or not isinstance(iterations, (int, np.integer)) or iterations < 0:
        raise ValueError(f"iterations must be an integer >= 0, got {iterations!r}")
    return int(iterations)


def _check_inside(points: np.ndarray, region) -> None:
    import shapely

    outside = ~shapely.intersects_xy(region, points[:, 0], points[:, 1])
    if outside.any():
        i = int(np.argmax(outside))
        raise ValueError(f"{int(outside.sum())} point(s) lie outside the window, e.g. point {i} at "
                         f"{points[i].tolist()}: Lloyd relaxation moves points within the window that holds them")
    if len(np.unique(points, axis=0)) != len(points):
        raise ValueError("points must be distinct: coincident seeds share one Voronoi cell")


def _lloyd_step(points: np.ndarray, region) -> np.ndarray:
    """One Lloyd step: each point to the centroid of its Voronoi cell clipped to the region."""
    import shapely

    if len(points) == 1:
        cells = np.array([region])
    else:
        diagram = shapely.voronoi_polygons(shapely.multipoints(points), extend_to=region, ordered=True)
        cells = shapely.intersection(np.asarray(shapely.get_parts(diagram)), region)
    centroids = shapely.centroid(cells)
    # A non-convex clipped cell may not hold its centroid: take the cell's nearest point to it.
    outside = ~shapely.intersects(cells, centroids)
    if outside.any():
        lines = shapely.shortest_line(cells[outside], centroids[outside])
        centroids[outside] = shapely.points(shapely.get_coordinates(lines)[::2])
    return shapely.get_coordinates(centroids)


def lloyd_relaxation(points, window, iterations: int = 50, *, tol: float = 0.0,
                     max_cells: int = MAX_CELLS) -> np.ndarray:
    """Relax points by Lloyd's method in a window (the seeding of Barla et al. 2006).

    At each iteration every point moves to the centroid of its Voronoi cell intersected with
    the window. The result is deterministic (no randomness: the random start is the caller's).

    Parameters
    ----------
    points : array_like, shape (n, 2)
        Distinct starting points (n >= 1), finite, inside the window (boundary included).
    window : shapely.Polygon, shapely.MultiPolygon or sequence of 4 floats
        The region: a valid polygon of positive area (e.g. a polygon window's ``.shape``),
        or a rectangle ``(xmin, xmax, ymin, ymax)`` (e.g. ``(*window.xrange, *window.yrange)``).
    iterations : int
        Number of Lloyd steps, >= 0 (0 returns a copy of the points). Barla et al. iterate
        "until convergence"; a few tens of steps bring uniform random seeds close to a
        centroidal tessellation.
    tol : float
        Stop early once no point moved by more than ``tol`` in a step (default 0: run all
        ``iterations``).
    max_cells : int, optional
        Budget: the most Voronoi cells computed, ``n * iterations`` (default :data:`MAX_CELLS`,
        2**22); a larger request raises ValueError before the first step.

    Returns
    -------
    numpy.ndarray, shape (n, 2)
        The relaxed points, in the order of ``points``, all in the window.

    Raises
    ------
    ValueError
        If ``points`` is empty, not ``(n, 2)``, holds NaN/inf or repeated points, or has a
        point outside the window; if the window is not a valid polygon of positive area or a
        finite rectangle with ``xmax > xmin`` and ``ymax > ymin``; if ``iterations`` is not an
        integer >= 0 or ``tol`` is negative; if ``n * iterations`` exceeds ``max_cells``.

    Notes
    -----
    Cells come from :func:`shapely.voronoi_polygons` with ``ordered=True``, which returns
    them in the order of the input points. In a non-convex window, a centroid falling
    outside its clipped cell is replaced by the nearest point of that cell.

    References
    ----------
    Barla et al. 2006, section 3.2 (Lloyd's method for the seeds); Lloyd 1982; Hurtut et al.
    2009, section 4.2 and Figure 6 (right).

    Examples
    --------
    >>> lloyd_relaxation([(0.1, 0.1), (0.2, 0.9), (0.9, 0.2), (0.8, 0.8)], (0, 1, 0, 1), 100).round(3)
    array([[0.25, 0.25],
           [0.25, 0.75],
           [0.75, 0.25],
           [0.75, 0.75]])
    """
    points = np.array(as_points(points, name="points"))
    region = _region(window)
    iterations = _iterations(iterations)
    try:
        tol = float(tol)
    except (TypeError, ValueError):
        raise ValueError(f"tol must be a number >= 0, got {tol!r}") from None
    if not tol >= 0:
        raise ValueError(f"tol must be a number >= 0, got {tol!r}")
    check_budget(len(points) * iterations, budget(max_cells, "max_cells"), "max_cells",
                 "Voronoi cells (points x iterations)")
    _check_inside(points, region)
    for _ in range(iterations):
        moved = _lloyd_step(points, region)
        step = np.hypot(*(moved - points).T).max()
        points = moved
        if step <= tol:
            break
    return points
