"""Observation and synthesis windows: rectangles, polygons and binary masks.

spatstat calls these ``owin``. A rectangle is the window of the reference drawings and
of spatstat's data sets; polygons and masks are the "various shapes" synthesis windows of
Hurtut 2009 (section 4.1, Figure 7). Points on the boundary count as inside, as in
spatstat's ``inside.owin``.

Mask convention: ``mask[i, j]`` is the pixel with x in ``[x0 + j dx, x0 + (j+1) dx)`` and
y in ``[y0 + i dy, y0 + (i+1) dy)``: row 0 is at the *bottom* (y up, like the points).
"""

from __future__ import annotations

import numpy as np

from paperlib._checks import check_choice
from paperlib.geometry import as_points

__all__ = ["Window"]

_KINDS = ("rectangle", "polygon", "mask")


def _check_range(values, name: str) -> tuple[float, float]:
    try:
        low, high = (float(v) for v in values)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair of numbers (low, high), got {values!r}") from None
    if not (np.isfinite(low) and np.isfinite(high)) or high <= low:
        raise ValueError(f"{name} must be finite with low < high (a window of positive area), got {values!r}")
    return low, high


class Window:
    """A planar window: rectangle, polygon (shapely, holes allowed) or binary mask.

    Build one with :meth:`rectangle`, :meth:`polygon` or :meth:`mask`.

    Parameters
    ----------
    kind : {"rectangle", "polygon", "mask"}
        The kind of window.
    xrange, yrange : tuple of float
        The bounding box (the frame, in spatstat's words).
    area : float
        The window's area (> 0).
    polygon : shapely.Polygon or shapely.MultiPolygon, optional
        The region, for ``kind="polygon"``.
    mask : ndarray of bool, optional
        The admissible pixels, for ``kind="mask"``.

    Attributes
    ----------
    kind : {"rectangle", "polygon", "mask"}
        The kind of window.
    xrange, yrange : tuple of float
        The bounding box.
    area : float
        The window's area.
    """

    __slots__ = ("kind", "xrange", "yrange", "area", "_polygon", "_mask", "_boundary_distance")

    def __init__(self, kind, xrange, yrange, area, polygon=None, mask=None):
        check_choice(kind, _KINDS, "kind")
        if not isinstance(area, (int, float, np.integer, np.floating)) or isinstance(area, bool) or not area > 0:
            raise ValueError(f"area: a window must have positive area, got {area!r:.80}")
        self.kind, self.xrange, self.yrange, self.area = kind, xrange, yrange, float(area)
        self._polygon, self._mask, self._boundary_distance = polygon, mask, None

    # ------------------------------------------------------------------ constructors

    @classmethod
    def rectangle(cls, xrange=(0.0, 1.0), yrange=(0.0, 1.0)) -> "Window":
        """The rectangle ``xrange x yrange`` (spatstat ``owin(xrange, yrange)``).

        Parameters
        ----------
        xrange, yrange : (float, float), default (0, 1)
            The x and y extents, finite, ``low < high``.

        Returns
        -------
        Window
            The rectangle window.
        """
        xrange, yrange = _check_range(xrange, "xrange"), _check_range(yrange, "yrange")
        return cls("rectangle", xrange, yrange, (xrange[1] - xrange[0]) * (yrange[1] - yrange[0]))

    @classmethod
    def polygon(cls, shape) -> "Window":
        """A polygon window from a shapely (Multi)Polygon or an ``(n, 2)`` vertex array.

        Parameters
        ----------
        shape : shapely.Polygon, shapely.MultiPolygon or array_like, shape (n, 2)
            The region (holes allowed), or the vertices of a simple polygon (n >= 3); it must be
            valid and of positive area.

        Returns
        -------
        Window
            The polygon window, with its bounding box as frame.
        """
        import shapely
        from shapely.geometry import MultiPolygon, Polygon

        if not isinstance(shape, (Polygon, MultiPolygon)):
            shape = Polygon(as_points(shape, name="polygon vertices", min_points=3))
        if shape.is_empty or not shape.is_valid:
            raise ValueError(f"polygon window is empty or invalid: {shapely.is_valid_reason(shape)}")
        if not shape.area > 0:
            raise ValueError("polygon window has zero area")
        xmin, ymin, xmax, ymax = shape.bounds
        shapely.prepare(shape)
        return cls("polygon", (xmin, xmax), (ymin, ymax), shape.area, polygon=shape)

    @classmethod
    def mask(cls, mask, xrange=(0.0, 1.0), yrange=(0.0, 1.0)) -> "Window":
        """A binary-mask window; ``mask[i, j]`` is True for admissible pixels (row 0 at the bottom).

        Parameters
        ----------
        mask : array_like of bool or 0/1, shape (rows, cols)
            The admissible pixels (at least one), row 0 at the bottom.
        xrange, yrange : (float, float), default (0, 1)
            The frame the pixels tile.

        Returns
        -------
        Window
            The mask window; its area is the admissible pixels' area.
        """
        mask = np.array(mask)
        if mask.ndim != 2 or min(mask.shape) < 1:
            raise ValueError(f"mask must be a non-empty 2-D array, got shape {mask.shape}")
        if mask.dtype != bool:
            if not np.isin(mask, (0, 1)).all():
                raise ValueError("mask must be boolean (or 0/1)")
            mask = mask.astype(bool)
        if not mask.any():
            raise ValueError("mask has no admissible pixel: the window would be empty")
        xrange, yrange = _check_range(xrange, "xrange"), _check_range(yrange, "yrange")
        mask.setflags(write=False)
        pixel_area = (xrange[1] - xrange[0]) * (yrange[1] - yrange[0]) / mask.size
        return cls("mask", xrange, yrange, mask.sum() * pixel_area, mask=mask)

    # ------------------------------------------------------------------ properties

    @property
    def width(self) -> float:
        return self.xrange[1] - self.xrange[0]

    @property
    def height(self) -> float:
        return self.yrange[1] - self.yrange[0]

    @property
    def is_rectangle(self) -> bool:
        return self.kind == "rectangle"

    @property
    def shape(self):
        """The shapely polygon of a polygon window (None otherwise)."""
        return self._polygon

    @property
    def mask_array(self):
        """The read-only boolean array of a mask window (None otherwise)."""
        return self._mask

    @property
    def pixel_size(self) -> tuple[float, float]:
        """``(dx, dy)`` of a mask window's pixels."""
        if self._mask is None:
            raise ValueError("only mask windows have pixels")
        return self.width / self._mask.shape[1], self.height / self._mask.shape[0]

    def __repr__(self) -> str:
        return f"Window.{self.kind}(xrange={self.xrange}, yrange={self.yrange}, area={self.area:g})"

    def __eq__(self, other) -> bool:
        if not isinstance(other, Window):
            return NotImplemented
        same_frame = (self.kind, self.xrange, self.yrange) == (other.kind, other.xrange, other.yrange)
        if not same_frame:
            return False
        if self.kind == "polygon":
            return self._polygon.equals(other._polygon)
        if self.kind == "mask":
            return np.array_equal(self._mask, other._mask)
        return True

    __hash__ = None

    # ------------------------------------------------------------------ geometry

    def _pixel_indices(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        dx, dy = self.pixel_size
        ny, nx = self._mask.shape
        cols = np.clip(np.floor((points[:, 0] - self.xrange[0]) / dx).astype(np.int64), 0, nx - 1)
        rows = np.clip(np.floor((points[:, 1] - self.yrange[0]) / dy).astype(np.int64), 0, ny - 1)
        return rows, cols

    def contains(self, points) -> np.ndarray:
        """Boolean array: which of the ``(n, 2)`` points lie in the window (boundary included).

        Parameters
        ----------
        points : array_like, shape (n, 2)
            Point coordinates.

        Returns
        -------
        ndarray of bool, shape (n,)
            True for the points in the window, boundary included.
        """
        points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        x, y = points[:, 0], points[:, 1]
        in_frame = (x >= self.xrange[0]) & (x <= self.xrange[1]) & (y >= self.yrange[0]) & (y <= self.yrange[1])
        if self.kind == "rectangle":
            return in_frame
        if self.kind == "polygon":
            import shapely

            return in_frame & shapely.intersects_xy(self._polygon, x, y)
        rows, cols = self._pixel_indices(points)
        return in_frame & self._mask[rows, cols]

    def boundary_distance(self, points) -> np.ndarray:
        """Distance from each point (inside the window) to the window's boundary.

        Exact for rectangles and polygons; for masks, the Euclidean distance transform
        of the mask at pixel resolution (pixel centres), so accurate to about one pixel.

        Parameters
        ----------
        points : array_like, shape (n, 2)
            Points inside the window.

        Returns
        -------
        ndarray of float64, shape (n,)
            Distance from each point to the window's boundary, in the window's units.
        """
        points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        if self.kind == "rectangle":
            x, y = points[:, 0], points[:, 1]
            return np.minimum.reduce(
                [x - self.xrange[0], self.xrange[1] - x, y - self.yrange[0], self.yrange[1] - y]
            )
        if self.kind == "polygon":
            import shapely

            return shapely.distance(self._polygon.boundary, shapely.points(points))
        if self._boundary_distance is None:
            from scipy import ndimage

            dx, dy = self.pixel_size
            padded = np.pad(self._mask, 1, constant_values=False)  # the frame's edge is a boundary too
            distance = ndimage.distance_transform_edt(padded, sampling=(dy, dx))[1:-1, 1:-1]
            self._boundary_distance = distance - 0.5 * min(dx, dy)
        rows, cols = self._pixel_indices(points)
        return np.maximum(self._boundary_distance[rows, cols], 0.0)

    def uniform_points(self, n: int, rng=None) -> np.ndarray:
        """``n`` independent uniform points in the window (rejection from the frame).

        Parameters
        ----------
        n : int
            Number of points (>= 0).
        rng : None, int or numpy.random.Generator, optional
            Source of randomness.

        Returns
        -------
        ndarray of float64, shape (n, 2)
            The points, independent and uniform in the window.
        """
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
            raise ValueError(f"n must be a non-negative integer, got {n!r}")
        rng = np.random.default_rng(rng)
        low = np.array([self.xrange[0], self.yrange[0]])
        size = np.array([self.width, self.height])
        accepted = np.empty((0, 2))
        acceptance = self.area / (self.width * self.height)
        while len(accepted) < n:
            batch = int((n - len(accepted)) / acceptance * 1.2) + 16
            candidates = low + rng.random((batch, 2)) * size
            accepted = np.vstack([accepted, candidates[self.contains(candidates)]])
        return accepted[:n]
