"""Berman-Turner quadrature schemes for maximum pseudolikelihood.

The log pseudolikelihood (Hurtut 2009, section 3.2.3, eq. 3) contains the integral of the
conditional intensity over the window. Berman and Turner (1992) approximate it by a weighted
sum over *quadrature points* (the data points and a set of dummy points) with *counting
weights*, which turns the maximisation into a weighted Poisson regression (Baddeley and Turner
2000). Everything here follows spatstat's ``quadscheme`` with its default ``method = "grid"``:

- **dummy points**: the centres of an ``nd x nd`` grid of cells of the window's frame, plus the
  frame's 4 corners; default ``nd = max(32, 10 * ceil(2 sqrt(n) / 10))``;
- **counting weights**: the frame is cut into ``ntile x ntile`` tiles; every quadrature point
  (data or dummy, marks ignored) gets ``area of its tile / number of points in the tile``. A
  point on the edge between two tiles goes to the lower one. ``ntile = nd`` when nd is
  defaulted; when nd is given, ntile is the smallest divisor of nd that is at least the default
  nd (nd itself if there is none);
- **multitype**: every dummy location is repeated once per type, and every data point is also
  a dummy of each other type, with the weight it has as a data point.

Windows. Rectangles reproduce spatstat exactly. Polygon and mask windows keep the grid, tile
and weight rules of rectangles (spatstat instead derives nd and ntile from its pixel grid) with
two changes that make the weights sum to the window's area: only grid centres inside the window
are dummies, and each tile's area is its area *inside the window* (exact for polygons; for
masks, the exact area of the admissible pixels in the tile); a tile that meets the window but
has no quadrature point gets one dummy at a point of the tile inside the window. A point in a
tile that meets the window in zero area (a data point on the boundary) gets a nominal area, as
in spatstat: a tenth of the smallest positive tile area.

Written by hand: no Python library builds Berman-Turner schemes (spatstat is R).

References
----------
Berman, M. and Turner, T. R. (1992). Approximating point process likelihoods with GLIM.
    Applied Statistics 41, 31-38.
Baddeley, A. and Turner, R. (2000). Practical maximum pseudolikelihood for spatial point
    patterns. Australian and New Zealand Journal of Statistics 42, 283-322.
Hurtut, T., Landes, P.-E., Thollot, J., Gousseau, Y., Drouilhet, R. and Coeurjolly, J.-F.
    (2009). Appearance-guided synthesis of element arrangements by example. NPAR, section 3.2.3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from paperlib._checks import budget, check_budget, integer_at_least

from .pattern import PointPattern
from .window import Window

__all__ = ["QuadratureScheme", "default_nd", "quadscheme"]

SPATSTAT_MIN_ND = 32  # spatstat.options("ndummy.min")
#: Default budget of :func:`quadscheme`: grid dummies over all types, n_types * max(nd, ntile)^2 (2**24, ~16.8 M;
#: our finest default scheme, ``fit.fine_nd``, uses at most 2**19).
MAX_DUMMIES = 2**24


@dataclass(frozen=True, eq=False)
class QuadratureScheme:
    """Quadrature points, their types and counting weights (spatstat's ``quad``).

    The first ``n_data`` points are the data points, in the pattern's order; then the dummy
    points (grid points, type by type, then the copies of data points with other types).

    Parameters
    ----------
    points : ndarray, shape (k, 2)
    types : ndarray of int, shape (k,)
        The type (mark) each quadrature point carries.
    weights : ndarray, shape (k,)
        Counting weights; they sum to ``n_types`` times the window's area.
    n_data : int
    nd, ntile : int
        Dummy grid and weighting tiles are ``nd x nd`` and ``ntile x ntile``.
    window : Window
    """

    points: np.ndarray
    types: np.ndarray
    weights: np.ndarray
    n_data: int
    nd: int
    ntile: int
    window: Window

    @property
    def n_points(self) -> int:
        return len(self.weights)

    @property
    def n_dummy(self) -> int:
        return self.n_points - self.n_data

    @property
    def is_data(self) -> np.ndarray:
        return np.arange(self.n_points) < self.n_data

    @property
    def total_weight(self) -> float:
        return float(self.weights.sum())

    def __repr__(self) -> str:
        return (
            f"QuadratureScheme({self.n_data} data + {self.n_dummy} dummy points, nd={self.nd}, "
            f"ntile={self.ntile}, total weight {self.total_weight:.6g})"
        )


def default_nd(n_points: int) -> int:
    """spatstat's default dummy grid side: ``max(32, 10 * ceil(2 sqrt(n) / 10))``.

    Parameters
    ----------
    n_points : int
        Number of data points (>= 0).

    Returns
    -------
    int
        The side of the dummy grid, at least 32.
    """
    n_points = integer_at_least(n_points, "n_points", 0)
    return max(SPATSTAT_MIN_ND, 10 * math.ceil(2 * math.sqrt(n_points) / 10))


def _tile_count_for(nd: int, n_points: int) -> int:
    """spatstat's tile count when nd is given: the smallest divisor of nd >= the default nd."""
    smallest = default_nd(n_points)
    return next((d for d in range(smallest, nd + 1) if nd % d == 0), nd)


def quadscheme(pattern: PointPattern, nd=None, *, ntile=None, max_dummies: int = MAX_DUMMIES) -> QuadratureScheme:
    """spatstat's default quadrature scheme for a pattern (``quadscheme(X, nd = nd)``).

    Parameters
    ----------
    pattern : PointPattern
    nd : int, optional
        Side of the dummy grid; default ``max(32, 10 * ceil(2 sqrt(n) / 10))``.
    ntile : int, optional
        Side of the grid of weighting tiles; default nd when nd is defaulted, else the
        smallest divisor of nd at least the default nd (spatstat's rule).
    max_dummies : int, optional
        Budget: at most this many grid cells over all types, ``n_types * max(nd, ntile)**2``
        (default :data:`MAX_DUMMIES`, 2**24); a larger scheme raises a ValueError before allocating.

    Returns
    -------
    QuadratureScheme

    Notes
    -----
    Hard-core estimates depend strongly on nd: for spatstat's ``cells`` and
    ``StraussHard(r = 0.1, hc = 0.05)``, gamma is 0.0093 at the default nd = 32 and 0.0047
    at nd = 256. :func:`paperlib.pointprocess.fit.ppm` uses a finer default.

    References
    ----------
    Baddeley, A. and Turner, R. (2000), section 3 (grid dummies and counting weights).
    """
    if not isinstance(pattern, PointPattern):
        raise TypeError(f"pattern must be a PointPattern, got {type(pattern).__name__}")
    max_dummies = budget(max_dummies, "max_dummies")
    nd = default_nd(pattern.n) if nd is None else _checked_side(nd, "nd")
    ntile = None if ntile is None else _checked_side(ntile, "ntile")
    # checked before spatstat's tile rule, which scans the divisors of nd
    check_budget(pattern.n_types * max(nd, ntile or 0) ** 2, max_dummies, "max_dummies",
                 "quadrature grid cells (n_types * max(nd, ntile)^2)")
    if ntile is None:  # the default nd's tiles are its own grid (the rule gives nd itself)
        ntile = _tile_count_for(nd, pattern.n)
    dummies = _grid_dummies(pattern.window, nd)
    tile_of_point, tile_areas = _tiles(pattern.window, ntile, np.vstack([pattern.points, dummies]))
    dummies, tile_of_point = _fill_empty_tiles(pattern.window, ntile, dummies, tile_of_point, tile_areas)
    weights = _counting_weights(tile_of_point, tile_areas)
    return _replicate_over_types(pattern, dummies, weights, nd, ntile)


def _checked_side(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ValueError(f"{name} must be a positive integer, got {value!r}")
    return int(value)


# ---------------------------------------------------------------------------- dummy points


def _cell_centres(low: float, high: float, n: int) -> np.ndarray:
    # spatstat: seq(low, high, length.out = 2n + 1)[2 * (1:n)], computed as R's seq does
    return low + np.arange(1, 2 * n, 2) * ((high - low) / (2 * n))


def _grid_dummies(window: Window, nd: int) -> np.ndarray:
    """Cell centres of the frame's nd x nd grid (x fastest), then the frame's corners."""
    x = _cell_centres(*window.xrange, nd)
    y = _cell_centres(*window.yrange, nd)
    centres = np.column_stack([np.tile(x, nd), np.repeat(y, nd)])
    (x0, x1), (y0, y1) = window.xrange, window.yrange
    corners = np.array([[x0, y0], [x1, y0], [x0, y1], [x1, y1]])
    dummies = np.vstack([centres, corners])
    if window.is_rectangle:
        return dummies
    return dummies[window.contains(dummies)]


# ---------------------------------------------------------------------------- tiles and weights


def _tile_axis_index(values: np.ndarray, low: float, high: float, n: int) -> np.ndarray:
    # spatstat's grid1index: ceiling(n (x - low) / (high - low)), clamped to 1..n; 0-based here.
    # The expression order matches R's so that points on tile edges fall the same way.
    index = np.ceil(n * (values - low) / (high - low)).astype(np.int64)
    return np.clip(index, 1, n) - 1


def _tile_index(window: Window, ntile: int, points: np.ndarray) -> np.ndarray:
    ix = _tile_axis_index(points[:, 0], *window.xrange, ntile)
    iy = _tile_axis_index(points[:, 1], *window.yrange, ntile)
    return iy * ntile + ix


def _tiles(window: Window, ntile: int, points: np.ndarray):
    """Tile of each point and area of each tile inside the window (row-major, y slowest)."""
    tile_of_point = _tile_index(window, ntile, points)
    if window.kind == "rectangle":
        areas = np.full(ntile * ntile, window.area / (ntile * ntile))
    elif window.kind == "polygon":
        areas = _polygon_tile_areas(window, ntile)
    else:
        areas = _mask_tile_areas(window, ntile)
    return tile_of_point, areas


def _tile_edges(window: Window, ntile: int):
    xs = np.linspace(*window.xrange, ntile + 1)
    ys = np.linspace(*window.yrange, ntile + 1)
    return xs, ys


def _polygon_tile_areas(window: Window, ntile: int) -> np.ndarray:
    import shapely

    xs, ys = _tile_edges(window, ntile)
    x0, y0 = np.meshgrid(xs[:-1], ys[:-1])
    x1, y1 = np.meshgrid(xs[1:], ys[1:])
    boxes = shapely.box(x0.ravel(), y0.ravel(), x1.ravel(), y1.ravel())
    return shapely.area(shapely.intersection(boxes, window.shape))


def _interval_overlaps(edges_a: np.ndarray, edges_b: np.ndarray) -> np.ndarray:
    """Lengths of overlap between consecutive intervals of two partitions: (len a - 1, len b - 1)."""
    low = np.maximum(edges_a[:-1, None], edges_b[None, :-1])
    high = np.minimum(edges_a[1:, None], edges_b[None, 1:])
    return np.clip(high - low, 0.0, None)


def _mask_tile_areas(window: Window, ntile: int) -> np.ndarray:
    # exact: area(tile n admissible pixels) = sum_pixels mask * overlap_x * overlap_y, separable
    ny, nx = window.mask_array.shape
    xs, ys = _tile_edges(window, ntile)
    overlap_x = _interval_overlaps(np.linspace(*window.xrange, nx + 1), xs)  # (nx, ntile)
    overlap_y = _interval_overlaps(np.linspace(*window.yrange, ny + 1), ys)  # (ny, ntile)
    return (overlap_y.T @ window.mask_array.astype(np.float64) @ overlap_x).ravel()


def _fill_empty_tiles(window, ntile, dummies, tile_of_point, tile_areas):
    """Give each tile that meets the window but holds no quadrature point one dummy inside it.

    Otherwise that tile's area would be lost from the integral (spatstat warns about it).
    """
    counts = np.bincount(tile_of_point, minlength=ntile * ntile)
    empty = np.flatnonzero((counts == 0) & (tile_areas > 0))
    if window.is_rectangle or empty.size == 0:
        return dummies, tile_of_point
    extra = np.array([_point_of_tile_in_window(window, ntile, tile) for tile in empty])
    return np.vstack([dummies, extra]), np.concatenate([tile_of_point, empty])


def _point_of_tile_in_window(window: Window, ntile: int, tile: int) -> np.ndarray:
    xs, ys = _tile_edges(window, ntile)
    iy, ix = divmod(int(tile), ntile)
    if window.kind == "polygon":
        import shapely

        part = shapely.intersection(shapely.box(xs[ix], ys[iy], xs[ix + 1], ys[iy + 1]), window.shape)
        point = shapely.point_on_surface(part)
        return np.array([point.x, point.y])
    # mask: the centre of the overlap between the tile and its admissible pixel nearest the tile centre
    dx, dy = window.pixel_size
    cols = np.arange(window.mask_array.shape[1])
    rows = np.arange(window.mask_array.shape[0])
    px0, py0 = window.xrange[0] + cols * dx, window.yrange[0] + rows * dy
    in_x = (px0 < xs[ix + 1]) & (px0 + dx > xs[ix])
    in_y = (py0 < ys[iy + 1]) & (py0 + dy > ys[iy])
    r, c = np.nonzero(window.mask_array[np.ix_(in_y, in_x)])
    r, c = rows[in_y][r], cols[in_x][c]
    centre = np.array([(xs[ix] + xs[ix + 1]) / 2, (ys[iy] + ys[iy + 1]) / 2])
    nearest = np.argmin((px0[c] + dx / 2 - centre[0]) ** 2 + (py0[r] + dy / 2 - centre[1]) ** 2)
    c, r = c[nearest], r[nearest]
    low = np.maximum([px0[c], py0[r]], [xs[ix], ys[iy]])
    high = np.minimum([px0[c] + dx, py0[r] + dy], [xs[ix + 1], ys[iy + 1]])
    return (low + high) / 2


def _counting_weights(tile_of_point: np.ndarray, tile_areas: np.ndarray) -> np.ndarray:
    """Tile area shared equally among the quadrature points in the tile (spatstat's countingweights)."""
    counts = np.bincount(tile_of_point, minlength=len(tile_areas))
    areas = tile_areas.copy()
    sliver = (areas == 0) & (counts > 0)
    if sliver.any():  # spatstat's repair for points in tiles of (numerically) zero area
        areas[sliver] = areas[areas > 0].min() / 10
    return areas[tile_of_point] / counts[tile_of_point]


# ---------------------------------------------------------------------------- types


def _replicate_over_types(pattern: PointPattern, dummies, weights, nd, ntile) -> QuadratureScheme:
    """spatstat's quadscheme.replicated: dummies for every type, data points as other types."""
    n, n_types = pattern.n, pattern.n_types
    data_weights, dummy_weights = weights[:n], weights[n:]
    all_types = np.arange(n_types)
    copy_point, copy_type = np.nonzero(pattern.marks[:, None] != all_types[None, :])  # data-major
    order = np.lexsort((copy_point, copy_type))  # spatstat lists them type by type
    copy_point, copy_type = copy_point[order], copy_type[order]
    points = np.vstack([pattern.points, np.tile(dummies, (n_types, 1)), pattern.points[copy_point]])
    types = np.concatenate([pattern.marks, np.repeat(all_types, len(dummies)), copy_type])
    weights = np.concatenate([data_weights, np.tile(dummy_weights, n_types), data_weights[copy_point]])
    for array in (points, types, weights):
        array.setflags(write=False)
    return QuadratureScheme(points, types, weights, n, nd, ntile, pattern.window)
