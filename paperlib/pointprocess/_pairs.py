"""Pair sums behind the summary functions: close pairs, edge-correction weights, r-bin histograms.

Every second-order summary (K, L, pair correlation) is a sum over ordered pairs of points
``(i, j)`` closer than some reach, each pair weighted by an edge correction and filed under
an r bin. This module does that work twice:

* a reference path in NumPy/SciPy: close pairs from ``scipy.spatial.cKDTree`` in chunks of
  first points (memory stays bounded), weights and bins vectorised; it serves every window
  and is what the tests check the kernel against;
* a numba kernel for rectangles, over a grid of cells of side >= half the reach, that files
  each pair straight into the histograms (never materialising the 1e8 pairs of a 1e5-point
  pattern) with spatstat's rectangle weights inlined.

Both return the same ``(5, M + 2)`` array of per-bin sums for an r grid of ``M + 1`` values
(rows ``UN``, ``TRANS``, ``ISO``: pair counts and weight sums filed at the first r that
counts the pair; ``BORDER_START``/``BORDER_STOP``: where a pair starts and stops counting
for the border estimate). Cumulating them into K is the caller's business.

Binning rules (spatstat has two; see ``shared/notes/spatstat_conventions.md``):

* ``closed=True`` -- spatstat's C engines (``Krect``, ``Kborder``, ``Knone``): a pair with
  ``d^2 < r_max^2`` counts from bin ``ceil(d / step)`` on, i.e. at every ``r >= d``; a
  point is border-eligible at ``r_k`` when ``k <= ceil(b / step) - 1``, i.e. ``r_k < b``.
* ``closed=False`` -- spatstat's histogram code (``whist``/``Kount``: ``Kest`` on other
  windows or uneven grids, ``Kmulti``): a pair with ``d^2 <= r_max^2`` counts at ``r_k``
  when ``d < r_k`` (and at the last r when ``d <= r_max``); a point is eligible at ``r_k``
  when ``b >= r_(k-1)``.

Edge weights (spatstat's, capped at ``MAX_EDGE_WEIGHT`` = its ``maxedgewt``):

* isotropic (Ripley 1977): the reciprocal of the fraction of the circle centred at the
  *first* point of the pair, through the second, that lies inside the window. Rectangles:
  spatstat's closed form (``ripleybox``). Polygons: the circle's crossings with every edge,
  each arc between crossings classified by its midpoint -- exact up to rounding, as
  spatstat's ``ripleypoly``. Masks (spatstat has none): the same with the pixel grid lines
  where the pixel status changes, exact for the pixelated window.
* translate (Ohser & Stoyan 1981): ``|W| / |W n (W + v)|`` for the pair vector ``v``.
  Rectangles: closed form. Polygons: exact overlap areas from shapely (GEOS), vectorised;
  spatstat instead rasterises polygons (128 x 128 pixels), so its values differ by up to a
  few percent. Masks: the set covariance of the pixel set, computed once by FFT at integer
  pixel lags; between lags it is exactly the bilinear interpolation of those values (the
  overlap of two pixels is a product of tents), so the weights are exact for the mask.

Window geometry for the radii where spatstat leaves estimates undefined (diameter,
bounding radius, shortest vector with no overlap) is here too.

Written by hand because no maintained library computes edge-corrected K functions with
spatstat's conventions (astropy's ``RipleysKEstimator`` differs in its Ripley mode and is
O(n^2) in memory; pointpats has no edge corrections).

References
----------
.. [1] Ripley, B. D. (1977). Modelling spatial patterns. JRSS B 39(2), 172-212.
.. [2] Ohser, J. and Stoyan, D. (1981). On the second-order and orientation analysis of
   planar stationary point processes. Biometrical Journal 23, 523-533.
.. [3] Baddeley, A., Rubak, E. and Turner, R. (2015). Spatial Point Patterns: Methodology
   and Applications with R, chapter 7. Chapman & Hall/CRC.
"""

from __future__ import annotations

import os
from typing import Iterator, NamedTuple

import numba
import numpy as np
from scipy.spatial import cKDTree

UN, TRANS, ISO, BORDER_START, BORDER_STOP = range(5)
N_CHANNELS = 5
MAX_EDGE_WEIGHT = 100.0  # spatstat.options("maxedgewt")

# pairs held in memory at once by the reference path
_CHUNK_PAIRS = 2_000_000


# ---------------------------------------------------------------------------- binning


def distance_bins(d2: np.ndarray, r: np.ndarray, closed: bool) -> np.ndarray:
    """Index of the first r bin that counts each pair of squared distance ``d2``; -1 if none."""
    rmax = r[-1]
    last = len(r) - 1
    d = np.sqrt(d2)
    if closed:
        step = rmax / last
        bins = np.minimum(np.ceil(d / step), last).astype(np.int64)
        bins[d2 >= rmax * rmax] = -1
    else:
        bins = np.minimum(np.searchsorted(r, d, side="right"), last)
        bins[d2 > rmax * rmax] = -1
    return bins


def border_last_bins(b: np.ndarray, r: np.ndarray, closed: bool) -> np.ndarray:
    """Last r bin at which each point (at boundary distance ``b``) enters the border estimate."""
    last = len(r) - 1
    if closed:
        step = r[-1] / last
        return np.minimum(np.ceil(b / step).astype(np.int64) - 1, last)
    return np.minimum(np.searchsorted(r, b, side="right"), last)


# ---------------------------------------------------------------------------- close pairs


class PairChunk(NamedTuple):
    """Ordered pairs ``(i, j)``: indices into the first and second point sets, ``xj - xi``, ``yj - yi``, ``d^2``."""

    i: np.ndarray
    j: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    d2: np.ndarray


def close_pairs(points_i: np.ndarray, points_j: np.ndarray, reach: float, *, same: bool) -> Iterator[PairChunk]:
    """All ordered pairs with ``d^2 <= reach^2`` (and ``i != j`` when ``same``), in chunks.

    The KD-tree query is padded by a relative 1e-9 and the pairs then filtered on ``d^2``
    computed as spatstat does, ``dx * dx + dy * dy``, so that ties with r values are decided
    by the same doubles.
    """
    tree_j = cKDTree(points_j)
    extent = np.ptp(points_j, axis=0) if len(points_j) > 1 else np.ones(2)
    density = len(points_j) / max(extent[0] * extent[1], reach * reach, np.finfo(float).tiny)
    per_point = max(1.0, density * np.pi * reach * reach)
    chunk = max(1, int(_CHUNK_PAIRS / per_point))
    padded = reach * (1.0 + 1e-9)
    for start in range(0, len(points_i), chunk):
        block = points_i[start : start + chunk]
        found = cKDTree(block).sparse_distance_matrix(tree_j, padded, output_type="ndarray")
        i = found["i"] + start
        j = found["j"]
        if same:
            keep = i != j
            i, j = i[keep], j[keep]
        dx = points_j[j, 0] - points_i[i, 0]
        dy = points_j[j, 1] - points_i[i, 1]
        d2 = dx * dx + dy * dy
        keep = d2 <= reach * reach
        yield PairChunk(i[keep], j[keep], dx[keep], dy[keep], d2[keep])


# ---------------------------------------------------------------------------- edge weights


class RectangleWeights:
    """Edge weights in the rectangle ``frame = (x0, x1, y0, y1)`` for pairs starting at ``points``."""

    def __init__(self, frame, points: np.ndarray):
        self.frame = tuple(float(v) for v in frame)
        self.points = points

    def isotropic(self, i: np.ndarray, d: np.ndarray) -> np.ndarray:
        x0, x1, y0, y1 = self.frame
        x, y = self.points[i, 0], self.points[i, 1]
        return box_isotropic_weights(x - x0, x1 - x, y - y0, y1 - y, d)

    def translate(self, dx: np.ndarray, dy: np.ndarray) -> np.ndarray:
        x0, x1, y0, y1 = self.frame
        width, height = x1 - x0, y1 - y0
        weights = width * height / ((width - np.abs(dx)) * (height - np.abs(dy)))
        return np.minimum(weights, MAX_EDGE_WEIGHT)


def box_isotropic_weights(left, right, down, up, d) -> np.ndarray:
    """Ripley's isotropic weight in a rectangle, spatstat's ``ripleybox`` formula, vectorised.

    ``left, right, down, up`` are the distances from the circle's centre to the four sides.
    The exterior angle is summed side by side, each side's half-angle ``acos(side / d)``
    capped by the angles to its two corners; a centre exactly at a corner adds pi/2. Circles
    inside the rectangle get weight 1 without trigonometry (the formula gives exactly 1).
    """
    sides = np.broadcast_arrays(*(np.asarray(a, dtype=np.float64) for a in (left, right, down, up, d)))
    weights = np.ones(sides[0].shape)
    crossing = sides[4] > np.minimum(np.minimum(sides[0], sides[1]), np.minimum(sides[2], sides[3]))
    left, right, down, up, d = (a[crossing] for a in sides)
    half = [np.where(s < d, np.arccos(np.minimum(s / d, 1.0)), 0.0) for s in (left, right, down, up)]
    a_left, a_right, a_down, a_up = half
    exterior = (
        np.minimum(a_left, np.arctan2(up, left)) + np.minimum(a_left, np.arctan2(down, left))
        + np.minimum(a_right, np.arctan2(up, right)) + np.minimum(a_right, np.arctan2(down, right))
        + np.minimum(a_up, np.arctan2(left, up)) + np.minimum(a_up, np.arctan2(right, up))
        + np.minimum(a_down, np.arctan2(left, down)) + np.minimum(a_down, np.arctan2(right, down))
    ) / (2.0 * np.pi)
    eps = np.finfo(np.float64).eps
    at_corner = sum((np.abs(s) < eps).astype(np.int64) for s in (left, right, down, up)) >= 2
    weights[crossing] = 1.0 / (1.0 - (exterior + np.where(at_corner, 0.25, 0.0)))
    return np.clip(weights, 1.0, MAX_EDGE_WEIGHT)


class PolygonWeights:
    """Edge weights in a shapely polygon window (holes and several parts allowed)."""

    def __init__(self, polygon, points: np.ndarray, boundary_distance: np.ndarray):
        import shapely

        self.polygon = polygon
        self.points = points
        self.boundary_distance = boundary_distance
        rings = [ring for part in getattr(polygon, "geoms", [polygon]) for ring in (part.exterior, *part.interiors)]
        starts = np.concatenate([np.asarray(ring.coords)[:-1] for ring in rings])
        ends = np.concatenate([np.asarray(ring.coords)[1:] for ring in rings])
        self.edges = np.ascontiguousarray(np.hstack([starts, ends]))  # x0, y0, x1, y1
        self._n_vertices = len(shapely.get_coordinates(polygon))

    def isotropic(self, i: np.ndarray, d: np.ndarray) -> np.ndarray:
        fractions = _polygon_circle_fractions(
            self.points[i, 0], self.points[i, 1], np.asarray(d, np.float64), self.boundary_distance[i], self.edges
        )
        return _weights_from_fractions(fractions)

    def translate(self, dx: np.ndarray, dy: np.ndarray) -> np.ndarray:
        """``|W| / |W n (W + v)|``, one GEOS intersection per distinct vector up to sign."""
        import shapely

        vectors = np.column_stack([dx, dy])
        flip = (vectors[:, 0] < 0) | ((vectors[:, 0] == 0) & (vectors[:, 1] < 0))
        vectors[flip] *= -1  # |W n (W + v)| = |W n (W - v)|
        distinct, inverse = np.unique(vectors, axis=0, return_inverse=True)
        copies = np.full(len(distinct), self.polygon, dtype=object)
        offsets = np.repeat(distinct, self._n_vertices, axis=0)
        shifted = shapely.transform(copies, lambda coords: coords + offsets)
        overlap = shapely.area(shapely.intersection(self.polygon, shifted))
        with np.errstate(divide="ignore"):
            weights = self.polygon.area / overlap
        return np.minimum(weights, MAX_EDGE_WEIGHT)[np.ravel(inverse)]


class MaskWeights:
    """Edge weights in a binary-mask window (``paperlib.pointprocess.Window.mask`` convention)."""

    def __init__(self, window, points: np.ndarray):
        from scipy import ndimage

        self.mask = np.ascontiguousarray(window.mask_array)
        self.origin = (window.xrange[0], window.yrange[0])
        self.pixel = window.pixel_size
        self.area = window.area
        self.points = points
        self.covariance = pixel_covariance(self.mask)
        # A lower bound of each centre's distance to the outside: circles no larger are whole.
        dx, dy = self.pixel
        padded = np.pad(self.mask, 1, constant_values=False)
        centre_distance = ndimage.distance_transform_edt(padded, sampling=(dy, dx))[1:-1, 1:-1]
        rows, cols = pixel_indices(points, self.origin, self.pixel, self.mask.shape)
        self.safe_radius = centre_distance[rows, cols] - np.hypot(dx, dy)

    def isotropic(self, i: np.ndarray, d: np.ndarray) -> np.ndarray:
        fractions = _mask_circle_fractions(
            self.points[i, 0], self.points[i, 1], np.asarray(d, np.float64), self.safe_radius[i],
            self.mask, self.origin[0], self.origin[1], self.pixel[0], self.pixel[1],
        )
        return _weights_from_fractions(fractions)

    def translate(self, dx: np.ndarray, dy: np.ndarray) -> np.ndarray:
        overlap = self.overlap_area(np.asarray(dx, np.float64), np.asarray(dy, np.float64))
        with np.errstate(divide="ignore"):
            return np.minimum(self.area / overlap, MAX_EDGE_WEIGHT)

    def overlap_area(self, dx: np.ndarray, dy: np.ndarray) -> np.ndarray:
        """``|W n (W + v)|``: bilinear interpolation of the pixel-lag set covariance (exact)."""
        ny, nx = self.mask.shape
        u, v = dx / self.pixel[0], dy / self.pixel[1]
        col0, row0 = np.floor(u).astype(np.int64), np.floor(v).astype(np.int64)
        tu, tv = u - col0, v - row0
        total = np.zeros_like(u)
        for row_step, col_step, weight in ((0, 0, (1 - tv) * (1 - tu)), (0, 1, (1 - tv) * tu),
                                           (1, 0, tv * (1 - tu)), (1, 1, tv * tu)):
            row, col = row0 + row_step, col0 + col_step
            valid = (np.abs(row) < ny) & (np.abs(col) < nx)
            total[valid] += weight[valid] * self.covariance[row[valid] + ny - 1, col[valid] + nx - 1]
        return total * self.pixel[0] * self.pixel[1]


def pixel_covariance(mask: np.ndarray) -> np.ndarray:
    """Number of admissible pixel pairs at each integer lag: shape ``(2 ny - 1, 2 nx - 1)``, lag 0 at the centre."""
    ny, nx = mask.shape
    shape = (2 * ny, 2 * nx)  # zero padding: no wrap-around for lags up to n - 1
    spectrum = np.fft.rfft2(mask.astype(np.float64), shape)
    counts = np.fft.irfft2(spectrum * np.conj(spectrum), shape)
    counts = np.rint(np.fft.fftshift(counts))  # integer counts; rint removes FFT round-off
    return counts[1:, 1:]


def pixel_indices(points: np.ndarray, origin, pixel, shape) -> tuple[np.ndarray, np.ndarray]:
    """Row and column of the mask pixel holding each point (points on the far edges go to the last pixel)."""
    ny, nx = shape
    cols = np.clip(np.floor((points[:, 0] - origin[0]) / pixel[0]).astype(np.int64), 0, nx - 1)
    rows = np.clip(np.floor((points[:, 1] - origin[1]) / pixel[1]).astype(np.int64), 0, ny - 1)
    return rows, cols


def _weights_from_fractions(fractions: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore"):
        return np.clip(1.0 / fractions, 1.0, MAX_EDGE_WEIGHT)


@numba.njit
def _angle(v, u):  # pragma: no cover - numba
    """``atan2(v, u)`` in [0, 2 pi)."""
    angle = np.arctan2(v, u)
    return angle + 2.0 * np.pi if angle < 0.0 else angle


@numba.njit
def _admissible(mask, row, col):  # pragma: no cover - numba
    return 0 <= row < mask.shape[0] and 0 <= col < mask.shape[1] and mask[row, col]


@numba.njit(cache=True)
def _inside_mask(x, y, mask, x0, y0, dx, dy):  # pragma: no cover - numba
    """Whether the point lies in an admissible pixel (outside the frame: no)."""
    return _admissible(mask, int(np.floor((y - y0) / dy)), int(np.floor((x - x0) / dx)))


@numba.njit(cache=True)
def _arcs(angles):  # pragma: no cover - numba
    """Middle angle and length of each arc between consecutive crossing angles (in [0, 2 pi)).

    Sorts ``angles`` in place, by insertion: a circle crosses a window's boundary a handful
    of times, and numba compiles this in a tenth of the time ``np.sort`` takes.
    """
    n = len(angles)
    for k in range(1, n):
        angle, m = angles[k], k - 1
        while m >= 0 and angles[m] > angle:
            angles[m + 1] = angles[m]
            m -= 1
        angles[m + 1] = angle
    middles, lengths = np.empty(n), np.empty(n)
    for k in range(n):
        stop = angles[k + 1] if k + 1 < n else angles[0] + 2.0 * np.pi
        middles[k] = 0.5 * (angles[k] + stop)
        lengths[k] = stop - angles[k]
    return middles, lengths


@numba.njit(cache=True)
def _inside_polygon(x, y, edges):  # pragma: no cover - numba
    """Even-odd crossing test against all edges (x0, y0, x1, y1 rows): holes handled."""
    inside = False
    for k in range(edges.shape[0]):
        x0, y0, x1, y1 = edges[k, 0], edges[k, 1], edges[k, 2], edges[k, 3]
        if (y0 > y) != (y1 > y):
            if x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
                inside = not inside
    return inside


@numba.njit(cache=True)
def _polygon_circle_fractions(cx, cy, radius, safe_radius, edges):  # pragma: no cover - numba
    """Fraction of each circle inside the polygon with the given edges.

    The circle's crossings with every edge (roots in [0, 1] of the segment's quadratic), the
    arcs between consecutive crossings classified by their midpoints. ``safe_radius``: the
    centre's distance to the boundary, within which circles are whole (ripleypoly's test).
    """
    out = np.ones(len(cx))
    angles = np.empty(2 * edges.shape[0])
    for p in range(len(cx)):
        if safe_radius[p] > radius[p] or radius[p] == 0.0:  # as ripleypoly: the whole circle is inside
            continue
        r2 = radius[p] * radius[p]
        n_angles = 0
        for k in range(edges.shape[0]):
            ex, ey = edges[k, 2] - edges[k, 0], edges[k, 3] - edges[k, 1]
            fx, fy = edges[k, 0] - cx[p], edges[k, 1] - cy[p]
            a = ex * ex + ey * ey
            b = 2.0 * (ex * fx + ey * fy)
            c = fx * fx + fy * fy - r2
            disc = b * b - 4.0 * a * c
            if a == 0.0 or disc < 0.0:
                continue
            root = np.sqrt(disc)
            for t in ((-b - root) / (2.0 * a), (-b + root) / (2.0 * a)):
                if 0.0 <= t <= 1.0:
                    angles[n_angles] = _angle(fy + t * ey, fx + t * ex)
                    n_angles += 1
        if n_angles == 0:  # no crossing: the circle is wholly inside or wholly outside
            out[p] = 1.0 if _inside_polygon(cx[p] + radius[p], cy[p], edges) else 0.0
            continue
        middles, lengths = _arcs(angles[:n_angles])
        inside = 0.0
        for k in range(n_angles):
            if _inside_polygon(cx[p] + radius[p] * np.cos(middles[k]), cy[p] + radius[p] * np.sin(middles[k]), edges):
                inside += lengths[k]
        out[p] = inside / (2.0 * np.pi)
    return out


@numba.njit(cache=True)
def _mask_circle_fractions(cx, cy, radius, safe_radius, mask, x0, y0, dx, dy):  # pragma: no cover - numba
    """Fraction of each circle inside the mask.

    The circle crosses pixel grid lines; only crossings between an admissible and an
    inadmissible pixel change its status, and finding those takes a square root and two
    pixel look-ups per grid line -- no trigonometry. The arcs between those crossings are
    then classified by their midpoints. Exact up to rounding (a circle through a pixel
    corner where the status changes diagonally is the one degenerate case).
    """
    out = np.ones(len(cx))
    for p in range(len(cx)):
        rad = radius[p]
        if safe_radius[p] >= rad or rad == 0.0:  # a circle of radius 0 (coincident points): weight 1
            continue
        k_lo, k_hi = int(np.ceil((cx[p] - rad - x0) / dx)), int(np.floor((cx[p] + rad - x0) / dx))
        m_lo, m_hi = int(np.ceil((cy[p] - rad - y0) / dy)), int(np.floor((cy[p] + rad - y0) / dy))
        angles = np.empty(2 * max(0, k_hi - k_lo + 1) + 2 * max(0, m_hi - m_lo + 1))
        n_angles = 0
        for k in range(k_lo, k_hi + 1):  # vertical grid lines: pixels (row, k - 1) | (row, k)
            u = x0 + k * dx - cx[p]
            h = np.sqrt(max(rad * rad - u * u, 0.0))
            for v in (h, -h):
                row = int(np.floor((cy[p] + v - y0) / dy))
                if _admissible(mask, row, k - 1) != _admissible(mask, row, k):
                    angles[n_angles] = _angle(v, u)
                    n_angles += 1
        for m in range(m_lo, m_hi + 1):  # horizontal grid lines: pixels (m - 1, col) / (m, col)
            v = y0 + m * dy - cy[p]
            h = np.sqrt(max(rad * rad - v * v, 0.0))
            for u in (h, -h):
                col = int(np.floor((cx[p] + u - x0) / dx))
                if _admissible(mask, m - 1, col) != _admissible(mask, m, col):
                    angles[n_angles] = _angle(v, u)
                    n_angles += 1
        if n_angles == 0:  # the circle stays in pixels of one status
            out[p] = 1.0 if _inside_mask(cx[p] + rad, cy[p], mask, x0, y0, dx, dy) else 0.0
            continue
        middles, lengths = _arcs(angles[:n_angles])
        inside = 0.0
        for k in range(n_angles):
            if _inside_mask(cx[p] + rad * np.cos(middles[k]), cy[p] + rad * np.sin(middles[k]), mask, x0, y0, dx, dy):
                inside += lengths[k]
        out[p] = inside / (2.0 * np.pi)
    return out


# ---------------------------------------------------------------------------- window geometry
#
# The radii from which spatstat reports isotropic and translation estimates as NA. Exact
# for rectangles; for polygons and masks computed on pixels (at most _RASTER_SIDE on a side
# for polygons), as spatstat does on its own 128-pixel masks -- so within about a pixel.

_RASTER_SIDE = 256


def diameter(window) -> float:
    """Largest distance between two points of the window (spatstat's ``diameter.owin``)."""
    if window.is_rectangle:
        return float(np.hypot(window.width, window.height))
    hull = _hull_vertices(window)
    gaps = hull[:, None, :] - hull[None, :, :]
    return float(np.sqrt((gaps**2).sum(axis=-1).max()))


def bounding_radius(window) -> float:
    """Radius of the smallest disc centred in the window containing it (spatstat's ``boundingradius``).

    Rectangles exactly; otherwise the best centre among the window's pixel centres.
    """
    if window.is_rectangle:
        return float(np.hypot(window.width, window.height) / 2)
    mask, origin, pixel = _raster(window)
    rows, cols = np.nonzero(mask)
    stride = max(1, len(rows) // 65536)  # a sample of centres suffices at pixel accuracy
    centres = np.column_stack([origin[0] + (cols[::stride] + 0.5) * pixel[0], origin[1] + (rows[::stride] + 0.5) * pixel[1]])
    hull = _hull_vertices(window)
    farthest = np.zeros(len(centres))
    for vertex in hull:  # the farthest point of W from any centre is a hull vertex
        farthest = np.maximum(farthest, np.hypot(centres[:, 0] - vertex[0], centres[:, 1] - vertex[1]))
    return float(farthest.min())


def translate_limit(window) -> float:
    """Length of the shortest v with ``|W n (W + v)| = 0`` (spatstat's ``rmax.Trans``).

    Rectangles: the short side (spatstat's value). Masks and polygons: the nearest pixel lag
    with no admissible pixel pair, which is exact for a mask since the set covariance is the
    bilinear interpolation of those lags (see :class:`MaskWeights`).
    """
    if window.is_rectangle:
        return float(min(window.width, window.height))
    mask, _, (dx, dy) = _raster(window)
    ny, nx = mask.shape
    rows, cols = np.nonzero(pixel_covariance(mask) == 0)
    nearest = np.hypot((cols - (nx - 1)) * dx, (rows - (ny - 1)) * dy).min(initial=np.inf)
    return float(min(nearest, nx * dx, ny * dy))  # lags beyond the frame have no pair either


def _raster(window):
    """(mask, origin, pixel size) of a mask window, or of a polygon rasterised at pixel centres."""
    if window.kind == "mask":
        return window.mask_array, (window.xrange[0], window.yrange[0]), window.pixel_size
    import shapely

    side = max(window.width, window.height) / _RASTER_SIDE
    nx, ny = max(1, int(np.ceil(window.width / side))), max(1, int(np.ceil(window.height / side)))
    dx, dy = window.width / nx, window.height / ny
    xs = window.xrange[0] + (np.arange(nx) + 0.5) * dx
    ys = window.yrange[0] + (np.arange(ny) + 0.5) * dy
    grid_x, grid_y = np.meshgrid(xs, ys)
    return shapely.contains_xy(window.shape, grid_x, grid_y), (window.xrange[0], window.yrange[0]), (dx, dy)


def _hull_vertices(window) -> np.ndarray:
    import shapely

    if window.kind == "polygon":
        shape = window.shape
    else:
        rows, cols = np.nonzero(window.mask_array)
        dx, dy = window.pixel_size
        corners = np.unique(np.concatenate([np.column_stack([cols + a, rows + b]) for a in (0, 1) for b in (0, 1)]), axis=0)
        shape = shapely.multipoints(np.column_stack([window.xrange[0] + corners[:, 0] * dx,
                                                     window.yrange[0] + corners[:, 1] * dy]))
    hull = shape.convex_hull
    coords = np.asarray(hull.exterior.coords)[:-1] if hull.geom_type == "Polygon" else shapely.get_coordinates(hull)
    return coords


# ---------------------------------------------------------------------------- reference path


def pair_sums_reference(points_i, points_j, *, same, r, closed, weights, border=None, uncorrected=True,
                        isotropic=False, translate=False) -> np.ndarray:
    """Per-bin pair sums by KD-tree pair enumeration and NumPy (every window kind).

    Parameters
    ----------
    points_i, points_j : ndarray, shape (n, 2)
        First and second points of the ordered pairs (the same array when ``same``).
    same : bool
        Pairs within one pattern (``i != j``) rather than between two.
    r : ndarray
        The r grid (starts at 0, increasing).
    closed : bool
        spatstat's C-engine binning (True) or its histogram binning (False); see the module notes.
    weights : RectangleWeights, PolygonWeights or MaskWeights
        Edge weights for pairs starting at ``points_i``.
    border : tuple of ndarray, optional
        ``(b, last_bin)`` of the first points: boundary distances and :func:`border_last_bins`.
    uncorrected, isotropic, translate : bool
        Which sums to compute (rows ``UN``, ``ISO``, ``TRANS``; the others stay 0).

    Returns
    -------
    ndarray, shape (5, len(r) + 1)
        Rows ``UN, TRANS, ISO, BORDER_START, BORDER_STOP``, not cumulated.
    """
    n_bins = len(r) + 1
    sums = np.zeros((N_CHANNELS, n_bins))
    for pairs in close_pairs(points_i, points_j, r[-1], same=same):
        bins = distance_bins(pairs.d2, r, closed)
        keep = bins >= 0
        bins, i, d = bins[keep], pairs.i[keep], np.sqrt(pairs.d2[keep])
        if uncorrected:
            sums[UN] += np.bincount(bins, minlength=n_bins)
        if translate:
            sums[TRANS] += np.bincount(bins, weights.translate(pairs.dx[keep], pairs.dy[keep]), minlength=n_bins)
        if isotropic:
            sums[ISO] += np.bincount(bins, weights.isotropic(i, d), minlength=n_bins)
        if border is not None:
            b, last_bin = border
            counted = (d <= b[i]) & (bins <= last_bin[i])
            sums[BORDER_START] += np.bincount(bins[counted], minlength=n_bins)
            sums[BORDER_STOP] += np.bincount(last_bin[i[counted]] + 1, minlength=n_bins)
    return sums


# ---------------------------------------------------------------------------- numba grid kernel


def pair_sums_grid(points_i, points_j, *, same, r, closed, frame, border=None, uncorrected=True,
                   isotropic=False, translate=False) -> np.ndarray:
    """Per-bin pair sums in the rectangle ``frame = (x0, x1, y0, y1)`` by the numba cell-grid kernel.

    Same parameters and result as :func:`pair_sums_reference` with ``RectangleWeights(frame)``.
    """
    points_i = np.ascontiguousarray(points_i, dtype=np.float64)
    points_j = np.ascontiguousarray(points_j, dtype=np.float64)
    if border is None:
        b, last_bin = np.zeros(len(points_i)), np.full(len(points_i), -1, dtype=np.int64)
    else:
        b, last_bin = np.ascontiguousarray(border[0], dtype=np.float64), np.ascontiguousarray(border[1], dtype=np.int64)
    frame = np.asarray(frame, dtype=np.float64)
    r = np.ascontiguousarray(r, dtype=np.float64)
    flags = (bool(uncorrected), border is not None, bool(isotropic), bool(translate), MAX_EDGE_WEIGHT)
    if same:
        return _self_pair_sums(points_i, b, last_bin, r, bool(closed), frame, *flags)
    return _cross_pair_sums(points_i, b, last_bin, points_j, r, bool(closed), frame, *flags)


# Cells of side >= reach / 2, each point meeting the 5 x 5 cells around its own: half the
# candidate pairs of reach-sized cells (3 x 3), and 1.3-1.7 times faster overall.
_CELLS_PER_REACH = 2


@numba.njit(cache=True)
def _cell_grid(points, frame, reach):  # pragma: no cover - numba
    """Counting sort of points into cells of side >= reach / _CELLS_PER_REACH: (order, cell starts, nx, ny)."""
    n = points.shape[0]
    width, height = frame[1] - frame[0], frame[3] - frame[2]
    most = max(1, int(np.sqrt(4.0 * n)) + 1)  # at most ~4n cells however small the reach
    side = reach / _CELLS_PER_REACH
    nx = max(1, min(most, int(width / side))) if side > 0 else 1
    ny = max(1, min(most, int(height / side))) if side > 0 else 1
    cell = np.empty(n, np.int64)
    for p in range(n):
        cell[p] = _cell_of(points[p, 0], points[p, 1], frame, nx, ny)
    starts = np.zeros(nx * ny + 1, np.int64)
    for p in range(n):
        starts[cell[p] + 1] += 1
    for c in range(nx * ny):
        starts[c + 1] += starts[c]
    fill = starts[:-1].copy()
    order = np.empty(n, np.int64)
    for p in range(n):
        order[fill[cell[p]]] = p
        fill[cell[p]] += 1
    return order, starts, nx, ny


@numba.njit
def _cell_of(x, y, frame, nx, ny):  # pragma: no cover - numba
    cx = min(max(int((x - frame[0]) / (frame[1] - frame[0]) * nx), 0), nx - 1)
    cy = min(max(int((y - frame[2]) / (frame[3] - frame[2]) * ny), 0), ny - 1)
    return cy * nx + cx


@numba.njit
def _bin_of(d2, r, closed, step):  # pragma: no cover - numba
    last = len(r) - 1
    rmax = r[last]
    if closed:
        if d2 >= rmax * rmax:
            return -1
        return min(int(np.ceil(np.sqrt(d2) / step)), last)
    if d2 > rmax * rmax:
        return -1
    return min(np.searchsorted(r, np.sqrt(d2), side="right"), last)


# Per-pair helpers return scalars and the kernels update the sums themselves: passing the
# sums array into a helper cost reference-count updates per pair and made the kernel 10
# times slower. _box_isotropic_weight is inlined in numba's IR (isotropic sums 12 % faster;
# LLVM inlines the other helpers by itself).
@numba.njit(inline="always")
def _box_isotropic_weight(x, y, d, x0, x1, y0, y1, trim):  # pragma: no cover - numba
    """Scalar twin of :func:`box_isotropic_weights` (1 exactly when the circle stays inside)."""
    left, right, down, up = x - x0, x1 - x, y - y0, y1 - y
    if d <= min(min(left, right), min(down, up)):
        return 1.0
    # A side farther than d contributes min(0, angle) = 0: only the sides the circle crosses
    # count. Each contributes its half-angle capped by the angles to its two corners, and a
    # cap binds only when that corner lies inside the circle (see _corner_capped).
    exterior = 0.0
    if left < d:
        half = np.arccos(left / d)
        exterior += _corner_capped(half, left, up, d) + _corner_capped(half, left, down, d)
    if right < d:
        half = np.arccos(right / d)
        exterior += _corner_capped(half, right, up, d) + _corner_capped(half, right, down, d)
    if up < d:
        half = np.arccos(up / d)
        exterior += _corner_capped(half, up, left, d) + _corner_capped(half, up, right, d)
    if down < d:
        half = np.arccos(down / d)
        exterior += _corner_capped(half, down, left, d) + _corner_capped(half, down, right, d)
    exterior /= 2.0 * np.pi
    eps = 2.220446049250313e-16
    n_small = int(abs(left) < eps) + int(abs(right) < eps) + int(abs(down) < eps) + int(abs(up) < eps)
    if n_small >= 2:
        exterior += 0.25
    return min(max(1.0 / (1.0 - exterior), 1.0), trim)


@numba.njit
def _corner_capped(half, across, along, d):  # pragma: no cover - numba
    """``min(half, atan2(along, across))`` without the arctangent when the corner is outside the circle.

    The circle crosses the side at angle ``half = acos(across / d)`` from its perpendicular;
    the corner at ``(across, along)`` is at angle ``atan2(along, across)``, the larger of the
    two exactly when the corner lies outside the circle.
    """
    if d * d <= across * across + along * along:
        return half
    return min(half, np.arctan2(along, across))


@numba.njit
def _rectangle_translate_weight(dx, dy, width, height, trim):  # pragma: no cover - numba
    return min(width * height / ((width - abs(dx)) * (height - abs(dy))), trim)


#: The rows of cells are shared among this many blocks, each summed on its own and the blocks then
#: added in order: the sums do not depend on how many threads take the blocks, or whether any do.
_ROW_BLOCKS = 64
#: The process that imported this module. A process forked from it after a parallel kernel ran would
#: inherit a GNU OpenMP that cannot run in it (numba terminates it): it runs the serial twin instead.
_IMPORTING_PROCESS = os.getpid()


def _self_pair_sums(*arguments):
    """Pairs within one pattern: the parallel kernel, or its serial twin in a forked process (same sums)."""
    if os.getpid() == _IMPORTING_PROCESS:
        return _self_pair_sums_parallel(*arguments)
    return _self_pair_sums_serial(*arguments)


@numba.njit(cache=True, parallel=True)
def _self_pair_sums_parallel(points, b, last_bin, r, closed, frame, do_un, do_border, do_iso, do_trans,
                             trim):  # pragma: no cover - numba
    """Each unordered pair once (half stencil), filed in both orders: blocks of rows of cells in parallel."""
    x, y, bs, ls, starts, nx, ny, partial = _blocks_of_rows(points, b, last_bin, r, frame)
    for block in numba.prange(partial.shape[0]):
        _block_pair_sums(block, x, y, bs, ls, starts, nx, ny, r, closed, frame, do_un, do_border, do_iso, do_trans,
                         trim, partial[block])
    return _added_in_order(partial)


@numba.njit(cache=True)
def _self_pair_sums_serial(points, b, last_bin, r, closed, frame, do_un, do_border, do_iso, do_trans,
                           trim):  # pragma: no cover - numba
    """:func:`_self_pair_sums_parallel` block after block in one thread: the same sums, bit for bit."""
    x, y, bs, ls, starts, nx, ny, partial = _blocks_of_rows(points, b, last_bin, r, frame)
    for block in range(partial.shape[0]):
        _block_pair_sums(block, x, y, bs, ls, starts, nx, ny, r, closed, frame, do_un, do_border, do_iso, do_trans,
                         trim, partial[block])
    return _added_in_order(partial)


@numba.njit
def _blocks_of_rows(points, b, last_bin, r, frame):  # pragma: no cover - numba
    """The points sorted into cells (coordinates, border distances and last bins in cell order), and
    zeroed sums for each of the ``min(rows, _ROW_BLOCKS)`` blocks of rows."""
    order, starts, nx, ny = _cell_grid(points, frame, r[len(r) - 1])
    partial = np.zeros((min(ny, _ROW_BLOCKS), N_CHANNELS, len(r) + 1))
    return points[order, 0], points[order, 1], b[order], last_bin[order], starts, nx, ny, partial


@numba.njit
def _added_in_order(partial):  # pragma: no cover - numba
    sums = np.zeros(partial.shape[1:])
    for block in range(partial.shape[0]):
        sums += partial[block]
    return sums


@numba.njit
def _block_pair_sums(block, x, y, bs, ls, starts, nx, ny, r, closed, frame, do_un, do_border, do_iso, do_trans,
                     trim, sums):  # pragma: no cover - numba
    """Add the pairs of the rows of cells of one block to ``sums``."""
    blocks = min(ny, _ROW_BLOCKS)
    for cy in range(block * ny // blocks, (block + 1) * ny // blocks):
        _row_pair_sums(cy, x, y, bs, ls, starts, nx, ny, r, closed, frame, do_un, do_border, do_iso, do_trans,
                       trim, sums)


@numba.njit
def _row_pair_sums(cy, x, y, bs, ls, starts, nx, ny, r, closed, frame, do_un, do_border, do_iso, do_trans,
                   trim, sums):  # pragma: no cover - numba
    """Add the pairs of the points of one row of cells with the half neighbourhood after them to ``sums``."""
    n_r = len(r)
    step = r[n_r - 1] / (n_r - 1)
    x0, x1, y0, y1 = frame[0], frame[1], frame[2], frame[3]
    reach = _CELLS_PER_REACH
    for cx in range(nx):
        first, stop = starts[cy * nx + cx], starts[cy * nx + cx + 1]
        # the cell itself and the half of its neighbourhood after it: each cell pair once
        for oy in range(-reach, reach + 1):
            for ox in range(0, reach + 1):
                ncx, ncy = cx + ox, cy + oy
                if (ox == 0 and oy < 0) or ncx >= nx or ncy < 0 or ncy >= ny:
                    continue
                own_cell = ox == 0 and oy == 0
                other_first, other_stop = starts[ncy * nx + ncx], starts[ncy * nx + ncx + 1]
                for p in range(first, stop):
                    xp, yp = x[p], y[p]
                    for q in range(p + 1 if own_cell else other_first, other_stop):
                        dx = x[q] - xp
                        dy = y[q] - yp
                        d2 = dx * dx + dy * dy
                        k = _bin_of(d2, r, closed, step)
                        if k < 0:
                            continue
                        d = np.sqrt(d2)
                        if do_un:
                            sums[UN, k] += 2.0
                        if do_trans:
                            sums[TRANS, k] += 2.0 * _rectangle_translate_weight(dx, dy, x1 - x0, y1 - y0, trim)
                        if do_iso:
                            sums[ISO, k] += (_box_isotropic_weight(xp, yp, d, x0, x1, y0, y1, trim)
                                             + _box_isotropic_weight(x[q], y[q], d, x0, x1, y0, y1, trim))
                        if do_border:
                            # a point's pairs stop counting after its last bin (whole numbers: exact in any order)
                            if k <= ls[p] and d <= bs[p]:
                                sums[BORDER_START, k] += 1.0
                                sums[BORDER_STOP, ls[p] + 1] += 1.0
                            if k <= ls[q] and d <= bs[q]:
                                sums[BORDER_START, k] += 1.0
                                sums[BORDER_STOP, ls[q] + 1] += 1.0


@numba.njit(cache=True)
def _cross_pair_sums(points_i, b, last_bin, points_j, r, closed, frame, do_un, do_border, do_iso, do_trans,
                     trim):  # pragma: no cover - numba
    """Pairs from one pattern to another: each first point against the cells around it."""
    n_r = len(r)
    step = r[n_r - 1] / (n_r - 1)
    sums = np.zeros((N_CHANNELS, n_r + 1))
    x0, x1, y0, y1 = frame[0], frame[1], frame[2], frame[3]
    order, starts, nx, ny = _cell_grid(points_j, frame, r[n_r - 1])
    xj, yj = points_j[order, 0], points_j[order, 1]
    reach = _CELLS_PER_REACH
    for p in range(points_i.shape[0]):
        xi, yi = points_i[p, 0], points_i[p, 1]
        cell = _cell_of(xi, yi, frame, nx, ny)
        cx, cy = cell % nx, cell // nx
        border_pairs = 0.0
        for ncy in range(max(cy - reach, 0), min(cy + reach + 1, ny)):
            for ncx in range(max(cx - reach, 0), min(cx + reach + 1, nx)):
                for q in range(starts[ncy * nx + ncx], starts[ncy * nx + ncx + 1]):
                    dx = xj[q] - xi
                    dy = yj[q] - yi
                    d2 = dx * dx + dy * dy
                    k = _bin_of(d2, r, closed, step)
                    if k < 0:
                        continue
                    d = np.sqrt(d2)
                    if do_un:
                        sums[UN, k] += 1.0
                    if do_trans:
                        sums[TRANS, k] += _rectangle_translate_weight(dx, dy, x1 - x0, y1 - y0, trim)
                    if do_iso:
                        sums[ISO, k] += _box_isotropic_weight(xi, yi, d, x0, x1, y0, y1, trim)
                    if do_border and k <= last_bin[p] and d <= b[p]:
                        sums[BORDER_START, k] += 1.0
                        border_pairs += 1.0
        if border_pairs > 0:
            sums[BORDER_STOP, last_bin[p] + 1] += border_pairs
    return sums
