"""Anti-aliased polygon painter for the MLTS renderer (Alvarez et al. 2015, section 5).

Each object is a polygon in pixel coordinates (x right, y down, pixel (r, c) = [c, c+1] x [r, r+1]).
Its coverage of a pixel is the fraction of a regular ``samples x samples`` grid of sub-pixel sample
points (at the sub-pixel centres) that lie inside it under the even-odd rule. Objects are composited
in order (painter's algorithm: later objects occlude earlier ones), each with its transparency
(section 5.2), optional light-spot attenuation (section 5.3) and optional clipping to its father
("keep father inclusion", section 5.4).

Written by hand because no maintained library offers this combination: scikit-image's
``draw.polygon`` is aliased (pixel centres only) and its anti-aliased routines draw lines, not
filled polygons; a shapely intersection per pixel is exact but far too slow for ~3,000 objects at
1024 x 1024. The kernels below work scanline by scanline: for each row of sub-samples they compute
the sorted x of the edge crossings, turn consecutive pairs into inside intervals (even-odd rule),
intersect them with the clip polygon's intervals when there is one, and add the number of sample
points each interval holds to the pixels it spans, in O(pixels) rather than O(samples).

References
----------
.. [1] L. Alvarez, Y. Gousseau, J.-M. Morel, A. Salgado, "Exploring the space of abstract
   textures by principles and random sampling", J. Math. Imaging Vis. 53 (2015), section 5
   (rendering), 5.2 (transparency), 5.3 (light spot), 5.4 ("keep father inclusion property").
"""

from __future__ import annotations

import operator

import numba
import numpy as np

from paperlib._checks import budget, check_budget, positive_number

from .texels import check_polygon

__all__ = ["coverage", "paint", "render_polygons", "MAX_SAMPLES"]

MAX_SAMPLES = 64
"""Largest accepted ``samples`` (4,096 sample points per pixel); more would only cost time."""


# ---------------------------------------------------------------------------------------------
# numba kernels
# ---------------------------------------------------------------------------------------------


@numba.njit(cache=True)
def _crossings(verts, start, stop, y, x_lo, x_hi, out):
    """Sorted x of the edges of ``verts[start:stop]`` crossing the line ``y``; returns how many.

    The half-open rule (an edge counts when y0 <= y < y1 or y1 <= y < y0) makes the count even and
    counts a vertex lying exactly on the line once. Crossings are clamped to [x_lo, x_hi] (outside
    the box of interest) so that huge coordinates never overflow the later integer conversion;
    clamping is monotone, so the inside intervals within the box are unchanged.
    """
    count = 0
    size = stop - start
    for i in range(size):
        x0 = verts[start + i, 0]
        y0 = verts[start + i, 1]
        j = start + (i + 1) % size
        x1 = verts[j, 0]
        y1 = verts[j, 1]
        if (y0 <= y < y1) or (y1 <= y < y0):
            x = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
            x = min(max(x, x_lo), x_hi)
            # insertion sort: polygons have few vertices, so few crossings per line
            m = count
            while m > 0 and out[m - 1] > x:
                out[m] = out[m - 1]
                m -= 1
            out[m] = x
            count += 1
    return count


@numba.njit(cache=True)
def _add_span(x_a, x_b, col0, width, samples, counts):
    """Add to ``counts`` (pixels col0..col0+width-1) the sample points with x_a <= x < x_b.

    Sample g of a row (global index) sits at x = (g + 0.5) / samples, so it is inside exactly
    when ceil(x_a * samples - 0.5) <= g < ceil(x_b * samples - 0.5).
    """
    g_a = max(int(np.ceil(x_a * samples - 0.5)), col0 * samples)
    g_b = min(int(np.ceil(x_b * samples - 0.5)), (col0 + width) * samples)
    if g_b <= g_a:
        return
    first = g_a // samples
    last = (g_b - 1) // samples
    if first == last:
        counts[first - col0] += g_b - g_a
        return
    counts[first - col0] += (first + 1) * samples - g_a
    for pixel in range(first + 1, last):
        counts[pixel - col0] += samples
    counts[last - col0] += g_b - last * samples


@numba.njit(cache=True)
def _row_counts(verts, start, stop, clip_verts, clip_start, clip_stop, row, col0, width, samples,
                counts, xs, xc):
    """Per pixel of row ``row`` (columns col0..col0+width-1), the samples inside the polygon and
    inside the clip polygon too when ``clip_stop > clip_start``."""
    counts[:width] = 0
    x_lo = col0 - 1.0
    x_hi = col0 + width + 1.0
    has_clip = clip_stop > clip_start
    for i in range(samples):
        y = row + (i + 0.5) / samples
        n = _crossings(verts, start, stop, y, x_lo, x_hi, xs)
        if not has_clip:
            for p in range(0, n, 2):
                _add_span(xs[p], xs[p + 1], col0, width, samples, counts)
            continue
        m = _crossings(clip_verts, clip_start, clip_stop, y, x_lo, x_hi, xc)
        # intersect the two sorted lists of inside intervals (two pointers): a sample is counted
        # exactly when it is inside both polygons
        a = 0
        b = 0
        while a < n and b < m:
            lo = max(xs[a], xc[b])
            hi = min(xs[a + 1], xc[b + 1])
            if lo < hi:
                _add_span(lo, hi, col0, width, samples, counts)
            if xs[a + 1] < xc[b + 1]:
                a += 2
            else:
                b += 2


@numba.njit(cache=True)
def _bbox(verts, start, stop, height, width):
    """Pixel box (row0, row1, col0, col1), half-open and clipped to the image, of a polygon."""
    x_min = verts[start, 0]
    x_max = x_min
    y_min = verts[start, 1]
    y_max = y_min
    for i in range(start + 1, stop):
        x_min = min(x_min, verts[i, 0])
        x_max = max(x_max, verts[i, 0])
        y_min = min(y_min, verts[i, 1])
        y_max = max(y_max, verts[i, 1])
    # clamp in floating point before converting, so huge coordinates cannot overflow
    row0 = int(min(max(np.floor(y_min), 0.0), height))
    row1 = int(min(max(np.ceil(y_max), 0.0), height))
    col0 = int(min(max(np.floor(x_min), 0.0), width))
    col1 = int(min(max(np.ceil(x_max), 0.0), width))
    return row0, row1, col0, col1


@numba.njit(cache=True)
def _object_box(verts, start, stop, clip_verts, clip_start, clip_stop, height, width):
    """Pixel box of an object, intersected with its clip polygon's box when it has one."""
    row0, row1, col0, col1 = _bbox(verts, start, stop, height, width)
    if clip_stop > clip_start:
        c_row0, c_row1, c_col0, c_col1 = _bbox(clip_verts, clip_start, clip_stop, height, width)
        row0 = max(row0, c_row0)
        row1 = min(row1, c_row1)
        col0 = max(col0, c_col0)
        col1 = min(col1, c_col1)
    return row0, max(row1, row0), col0, max(col1, col0)


@numba.njit(cache=True)
def _coverage_kernel(verts, clip_verts, row0, row1, col0, col1, samples):
    """Coverage mask of one polygon (optionally clipped) over the pixel box [row0, row1) x [col0, col1)."""
    width = col1 - col0
    mask = np.zeros((row1 - row0, width))
    counts = np.zeros(max(width, 1), dtype=np.int64)
    xs = np.empty(verts.shape[0] + 1)
    xc = np.empty(clip_verts.shape[0] + 1)
    per_pixel = samples * samples  # divide (not multiply by 1/n) so values are correctly rounded
    for row in range(row0, row1):
        _row_counts(verts, 0, verts.shape[0], clip_verts, 0, clip_verts.shape[0], row, col0, width,
                    samples, counts, xs, xc)
        for k in range(width):
            mask[row - row0, k] = counts[k] / per_pixel
    return mask


@numba.njit(cache=True)
def _paint_kernel(canvas, verts, offsets, clip_verts, clip_offsets, clip_of, colors, opacity,
                  lights, heights, lit, samples):
    """Composite every object in order onto ``canvas`` (see :func:`paint`)."""
    height = canvas.shape[0]
    width = canvas.shape[1]
    counts = np.zeros(max(width, 1), dtype=np.int64)
    longest = 1
    for i in range(offsets.shape[0] - 1):
        longest = max(longest, offsets[i + 1] - offsets[i])
    longest_clip = 1
    for i in range(clip_offsets.shape[0] - 1):
        longest_clip = max(longest_clip, clip_offsets[i + 1] - clip_offsets[i])
    xs = np.empty(longest + 1)
    xc = np.empty(longest_clip + 1)
    per_pixel = samples * samples  # divide (not multiply by 1/n) so values are correctly rounded
    for obj in range(offsets.shape[0] - 1):
        if opacity[obj] == 0.0:
            continue  # fully transparent: nothing to draw
        start = offsets[obj]
        stop = offsets[obj + 1]
        clip_start = 0
        clip_stop = 0
        if clip_of[obj] >= 0:
            clip_start = clip_offsets[clip_of[obj]]
            clip_stop = clip_offsets[clip_of[obj] + 1]
        row0, row1, col0, col1 = _object_box(verts, start, stop, clip_verts, clip_start, clip_stop,
                                             height, width)
        box_width = col1 - col0
        h2 = heights[obj] * heights[obj]
        for row in range(row0, row1):
            _row_counts(verts, start, stop, clip_verts, clip_start, clip_stop, row, col0, box_width,
                        samples, counts, xs, xc)
            for k in range(box_width):
                if counts[k] == 0:
                    continue
                alpha = counts[k] / per_pixel * opacity[obj]
                col = col0 + k
                attenuation = 1.0
                if lit:
                    # inverse square of the 3D distance to a light at height h above the light
                    # point, normalised to 1 at that point (section 5.3)
                    dx = col + 0.5 - lights[obj, 0]
                    dy = row + 0.5 - lights[obj, 1]
                    attenuation = h2 / (h2 + dx * dx + dy * dy)
                for ch in range(3):
                    canvas[row, col, ch] = (canvas[row, col, ch] * (1.0 - alpha)
                                            + colors[obj, ch] * attenuation * alpha)


# ---------------------------------------------------------------------------------------------
# input checks
# ---------------------------------------------------------------------------------------------


def _check_samples(samples) -> int:
    if isinstance(samples, bool):
        raise ValueError(f"samples must be an integer in [1, {MAX_SAMPLES}], got {samples!r}")
    try:
        value = operator.index(samples)
    except TypeError:
        raise ValueError(f"samples must be an integer in [1, {MAX_SAMPLES}], got {samples!r}") from None
    if not 1 <= value <= MAX_SAMPLES:
        raise ValueError(f"samples must be an integer in [1, {MAX_SAMPLES}], got {samples!r}")
    return value


def _check_shape(shape) -> tuple[int, int]:
    try:
        height, width = (operator.index(v) for v in shape)
    except (TypeError, ValueError):
        raise ValueError(f"shape must be a pair of positive integers (H, W), got {shape!r}") from None
    if height <= 0 or width <= 0:
        raise ValueError(f"shape must be a pair of positive integers (H, W), got {shape!r}")
    return height, width


def _pack(polygons: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """All vertices in one (N, 2) array and the offsets (n + 1,) of each polygon in it."""
    sizes = np.array([len(p) for p in polygons], dtype=np.int64)
    offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    verts = np.concatenate(polygons) if polygons else np.zeros((0, 2))
    return np.ascontiguousarray(verts, dtype=np.float64), offsets


def _per_object(values, n: int, name: str, *, low: float, high: float) -> np.ndarray:
    """A scalar or (n,) array of finite numbers in [low, high], broadcast to (n,)."""
    try:
        array = np.array(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number or an array of {n} numbers") from None
    if array.ndim == 0:
        array = np.full(n, float(array))
    if array.shape != (n,):
        raise ValueError(f"{name} must be a number or have shape ({n},), got shape {array.shape}")
    if not np.all(np.isfinite(array)) or np.any(array < low) or np.any(array > high):
        raise ValueError(f"{name} must hold finite numbers in [{low}, {high}]")
    return array


def _check_colors(colors, n: int) -> np.ndarray:
    try:
        array = np.array(colors, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"colors must be an array of shape ({n}, 3)") from None
    if array.shape != (n, 3):
        raise ValueError(f"colors must have shape ({n}, 3) (one RGB colour per polygon), got {array.shape}")
    if not np.all(np.isfinite(array)) or np.any(array < 0) or np.any(array > 1):
        raise ValueError("colors must hold finite RGB values in [0, 1]")
    return array


def _check_lights(lights, light_height, n: int) -> tuple[np.ndarray, np.ndarray, bool]:
    if (lights is None) != (light_height is None):
        raise ValueError("lights and light_height go together: give both or neither")
    if lights is None:
        return np.zeros((n, 2)), np.ones(n), False
    try:
        points = np.array(lights, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"lights must be an array of shape ({n}, 2)") from None
    if points.shape != (n, 2):
        raise ValueError(f"lights must have shape ({n}, 2) (one (x, y) point per polygon), got {points.shape}")
    if not np.all(np.isfinite(points)):
        raise ValueError("lights has NaN or infinite coordinates")
    if np.ndim(light_height) == 0:
        heights = np.full(n, positive_number(light_height, "light_height"))
    else:
        heights = _per_object(light_height, n, "light_height", low=0.0, high=np.inf)
        if np.any(heights <= 0):
            raise ValueError("light_height must be positive (a height in pixels above the image plane)")
    return points, heights, True


def _check_clip(clip, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Packed clip polygons and, per object, the index of its clip polygon (-1: none)."""
    clip_of = np.full(n, -1, dtype=np.int64)
    if clip is None:
        return np.zeros((0, 2)), np.zeros(1, dtype=np.int64), clip_of
    clip = list(clip)
    if len(clip) != n:
        raise ValueError(f"clip must hold one entry (None or a polygon) per polygon: {n}, got {len(clip)}")
    polygons = []
    for i, entry in enumerate(clip):
        if entry is not None:
            clip_of[i] = len(polygons)
            polygons.append(check_polygon(entry, f"clip[{i}]"))
    verts, offsets = _pack(polygons)
    return verts, offsets, clip_of


def _check_background(background) -> np.ndarray:
    try:
        back = np.array(background, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"background must be an RGB triple in [0, 1], got {background!r}") from None
    if back.shape != (3,) or not np.all(np.isfinite(back)) or np.any(back < 0) or np.any(back > 1):
        raise ValueError(f"background must be an RGB triple in [0, 1], got {background!r}")
    return back


def _check_canvas(canvas) -> None:
    if not isinstance(canvas, np.ndarray) or canvas.dtype != np.float64:
        raise ValueError("canvas must be a float64 NumPy array of shape (H, W, 3)")
    if canvas.ndim != 3 or canvas.shape[2] != 3 or canvas.shape[0] == 0 or canvas.shape[1] == 0:
        raise ValueError(f"canvas must have shape (H, W, 3) with H, W > 0, got {canvas.shape}")
    if not canvas.flags.writeable:
        raise ValueError("canvas must be writeable (it is painted in place)")
    if not np.all(np.isfinite(canvas)):
        raise ValueError("canvas has NaN or infinite values")


# ---------------------------------------------------------------------------------------------
# public functions
# ---------------------------------------------------------------------------------------------


#: Default budget of :func:`render_polygons` and :func:`coverage`: the most anti-aliasing samples
#: ``H * W * samples**2`` of one image (of one polygon's box for coverage), 2**27 (as
#: :data:`paperlib.mlts.render.MAX_RENDER_SAMPLES`). Raise it with the ``max_samples`` keyword.
MAX_IMAGE_SAMPLES = 2**27


def coverage(vertices, shape, *, samples: int = 4, clip=None,
             max_samples: int = MAX_IMAGE_SAMPLES) -> tuple[int, int, np.ndarray]:
    """Anti-aliased coverage of one polygon over the pixels of an image.

    Parameters
    ----------
    vertices : array_like, shape (k, 2)
        Polygon vertices (x, y) in pixels, k >= 3, not closed; any orientation (even-odd rule).
    shape : (int, int)
        Image size (H, W); the image covers [0, W] x [0, H].
    samples : int, default 4
        Sub-samples per pixel side: each pixel is tested at the ``samples x samples`` centres of
        its sub-pixels, so coverage values are multiples of ``1 / samples**2``.
    clip : array_like, shape (m, 2), optional
        Second polygon: only samples inside both polygons count (see :func:`paint`).
    max_samples : int, optional
        Budget: the most sub-pixel samples tested, ``h * w * samples**2`` over the polygon's box in the
        image (default :data:`MAX_IMAGE_SAMPLES`, 2**27), checked before the mask is allocated.

    Returns
    -------
    row0, col0 : int
        Pixel of the top-left corner of ``mask``.
    mask : ndarray of float64, shape (h, w)
        Coverage in [0, 1] over the polygon's pixel bounding box clipped to the image (and to the
        clip polygon's box); shape (0, 0) with row0 = col0 = 0 when nothing of it is in the image.

    References
    ----------
    .. [1] Alvarez, Gousseau, Morel, Salgado 2015, section 5 (objects drawn in the image by the rendering rules).
    """
    polygon = check_polygon(vertices, "vertices")
    height, width = _check_shape(shape)
    samples = _check_samples(samples)
    clip_polygon = np.zeros((0, 2)) if clip is None else check_polygon(clip, "clip")
    row0, row1, col0, col1 = _object_box(polygon, 0, len(polygon), clip_polygon, 0, len(clip_polygon),
                                         height, width)
    if row1 <= row0 or col1 <= col0:
        return 0, 0, np.zeros((0, 0))
    check_budget((row1 - row0) * (col1 - col0) * samples**2, budget(max_samples, "max_samples"), "max_samples",
                 "sub-pixel samples (box pixels x samples^2)")
    mask = _coverage_kernel(polygon, clip_polygon, row0, row1, col0, col1, samples)
    return row0, col0, mask


def paint(canvas, polygons, colors, *, alphas=None, lights=None, light_height=None, clip=None,
          samples: int = 4) -> np.ndarray:
    """Composite polygons in order onto ``canvas`` (painter's algorithm), in place.

    Per pixel and object i, with a = coverage * (1 - alphas[i]):
    ``canvas = canvas * (1 - a) + colour * a``. Later polygons are drawn in front (occlusion).

    Parameters
    ----------
    canvas : ndarray of float64, shape (H, W, 3)
        Image painted in place (and returned).
    polygons : sequence of array_like, each (k_i, 2)
        Object polygons in pixels, back to front.
    colors : array_like, shape (n, 3)
        RGB colour of each object, in [0, 1].
    alphas : scalar or array_like (n,), optional
        Transparency of each object in [0, 1] (section 5.2): 0 opaque (default), 1 invisible.
    lights : array_like, shape (n, 2), optional
        Light point (x, y) of each object (section 5.3), chosen by the caller inside the object.
    light_height : float or array_like (n,), optional
        Height h > 0 (pixels) of each light above the image plane; the colour at pixel centre p
        becomes ``colour * h**2 / (h**2 + |p - light|**2)``, the inverse-square law normalised to
        the palette colour at the light point. Required with ``lights``.
    clip : sequence of (None or array_like (m, 2)), optional
        Per object, a polygon (its father) outside which it is not drawn ("keep father inclusion",
        section 5.4): a sample counts only if it is inside both polygons.
    samples : int, default 4
        Sub-samples per pixel side (see :func:`coverage`).

    Returns
    -------
    canvas : ndarray
        The same array, painted.

    References
    ----------
    .. [1] Alvarez, Gousseau, Morel, Salgado 2015, section 3 (occlusion: later objects in front),
       5.2 (transparency), 5.3 (light spot), 5.4 (keep father inclusion).
    """
    _check_canvas(canvas)
    if isinstance(polygons, (str, bytes)) or not hasattr(polygons, "__iter__"):
        raise TypeError(f"polygons must be a sequence of (k, 2) vertex arrays, got {type(polygons).__name__}")
    shapes = [check_polygon(p, f"polygons[{i}]") for i, p in enumerate(polygons)]
    n = len(shapes)
    color_array = _check_colors(colors, n)
    transparency = np.zeros(n) if alphas is None else _per_object(alphas, n, "alphas", low=0.0, high=1.0)
    light_points, heights, lit = _check_lights(lights, light_height, n)
    clip_verts, clip_offsets, clip_of = _check_clip(clip, n)
    samples = _check_samples(samples)
    if n == 0:
        return canvas
    verts, offsets = _pack(shapes)
    _paint_kernel(canvas, verts, offsets, clip_verts, clip_offsets, clip_of, color_array, 1.0 - transparency,
                  light_points, heights, lit, samples)
    return canvas



def render_polygons(polygons, colors, shape, *, background=(1.0, 1.0, 1.0), alphas=None, lights=None,
                    light_height=None, clip=None, samples: int = 4,
                    max_samples: int = MAX_IMAGE_SAMPLES) -> np.ndarray:
    """A new (H, W, 3) float64 image of ``background`` with the polygons painted by :func:`paint`.

    Parameters
    ----------
    polygons, colors, alphas, lights, light_height, clip, samples
        As in :func:`paint`.
    shape : (int, int)
        Image size (H, W).
    background : array_like, shape (3,), default white
        RGB background colour in [0, 1].
    max_samples : int
        Budget: the most anti-aliasing samples ``H * W * samples**2`` (default
        :data:`MAX_IMAGE_SAMPLES`), checked before the image is allocated.

    Returns
    -------
    ndarray of float64, shape (H, W, 3)

    Raises
    ------
    ValueError
        As :func:`paint`; for a shape that is not two positive integers or above ``max_samples``.

    References
    ----------
    .. [1] Alvarez, Gousseau, Morel, Salgado 2015, section 5 (rendering of the geometric structure).
    """
    height, width = _check_shape(shape)
    check_budget(height * width * _check_samples(samples) ** 2, budget(max_samples, "max_samples"), "max_samples",
                 "anti-aliasing samples (H x W x samples^2)")
    back = _check_background(background)
    canvas = np.empty((height, width, 3))
    canvas[:] = back
    return paint(canvas, polygons, colors, alphas=alphas, lights=lights, light_height=light_height, clip=clip,
                 samples=samples)
