"""The basic mathematical processes of Fig. 5: scaling dead leaves, random tessellations, IFS fractals.

Alvarez et al. (2015, section 2.4 and Fig. 5) compare MLTS with three single-principle models of
abstract images: "a scaling dead leaves model [1, 27], a random tessellation [4], a fractal (iterated
function system)". This module implements them as plain functions returning an RGB float image of
shape ``(H, W, 3)`` in [0, 1] and, on request, the labels and geometry needed to measure them:

* :func:`dead_leaves` -- the scaling dead leaves model of Alvarez, Gousseau and Morel (1999) and
  Lee, Mumford and Huang (2001): discs with power-law radii, the first leaf on top. Its analytic
  coverage (Boolean model) is :func:`dead_leaves_coverage`, with :func:`dead_leaves_mean_area`,
  :func:`dead_leaves_window_area` and the exact standard deviation :func:`dead_leaves_coverage_std`.
* :func:`voronoi_tessellation` (Poisson-Voronoi) and :func:`poisson_line_tessellation` (isotropic
  Poisson lines), the two classic random tessellations of Chiu et al., *Stochastic Geometry and its
  Applications* ([4] in the paper, chapter 9). The paper's text does not say which tessellation its
  Fig. 5 shows; both are offered and the notebook states which one it draws.
* :func:`ifs_fractal` -- the chaos game of an iterated function system (Barnsley fern by default,
  Sierpinski triangle available), with :func:`ifs_chaos_game` for the raw points and
  :func:`box_counting_dimension` to measure them.

Conventions (shared by all MLTS modules): pixel coordinates, x to the right, y down, pixel (row r,
col c) is the unit square [c, c+1] x [r, r+1] with centre (c + 0.5, r + 0.5); colours are drawn
uniformly from a palette given as an ``(n, 3)`` array of RGB colours in [0, 1].

Written by hand: no maintained library offers these simulators. The disc painter and the chaos game
are sequential loops and run as numba kernels; nearest-centre labels use ``scipy.spatial.cKDTree``.

References
----------
.. [1] L. Alvarez, Y. Gousseau, J.-M. Morel, A. Salgado, "Exploring the space of abstract
   textures by principles and random sampling", J. Math. Imaging Vis. 53 (2015), section 2.4 and Fig. 5.
.. [2] L. Alvarez, Y. Gousseau, J.-M. Morel, "The size of objects in natural and artificial
   images", Advances in Imaging and Electron Physics 111, 1999 (ref. [1] of the paper).
.. [3] A. B. Lee, D. Mumford, J. Huang, "Occlusion models for natural images: a statistical study
   of a scale-invariant dead leaves model", IJCV 41, 2001 (ref. [27] of the paper).
.. [4] S. N. Chiu, D. Stoyan, W. S. Kendall, J. Mecke, "Stochastic Geometry and its Applications",
   3rd ed., Wiley, 2013 (ref. [4] of the paper), sections 3.6 (Boolean model), 8 (line processes),
   9 (random tessellations).
.. [5] M. F. Barnsley, "Fractals Everywhere", Academic Press, 1988 (chaos game, fern).
"""

from __future__ import annotations

import math
import operator
import sys
import warnings

import numba
import numpy as np
from scipy.spatial import cKDTree

from paperlib._checks import (as_generator, budget, check_budget, check_choice, check_flag, float_array, point_array,
                              positive_number)

__all__ = [
    "DEFAULT_PALETTE",
    "barnsley_fern",
    "box_counting_dimension",
    "dead_leaves",
    "dead_leaves_coverage",
    "dead_leaves_coverage_std",
    "dead_leaves_mean_area",
    "dead_leaves_window_area",
    "ifs_chaos_game",
    "ifs_fractal",
    "poisson_line_tessellation",
    "sierpinski_triangle",
    "voronoi_tessellation",
]

DEFAULT_PALETTE = np.array(
    [
        [0.85, 0.15, 0.12],  # red
        [0.10, 0.30, 0.70],  # blue
        [0.95, 0.80, 0.10],  # yellow
        [0.10, 0.55, 0.30],  # green
        [0.95, 0.95, 0.92],  # off-white
        [0.10, 0.10, 0.10],  # near-black
    ]
)
"""The default palette: six fixed colours (Mondrian-like primaries, green, off-white, near-black)."""

_LEAF_BATCH = 4096
"""Leaves are drawn in batches of this size, always in the same order, so ``n_leaves=k`` draws exactly
the first k leaves of the sequence a coverage-stopped run would draw with the same seed."""

_MAX_LINES = 10_000
"""Largest expected number of Poisson lines in the image (the cost is one pass over the pixels per line)."""

_MAX_LEAVES = 2_000_000
"""Safety cap on the number of leaves when only a coverage target is given (never hang)."""

#: Default budget of :func:`dead_leaves`, :func:`voronoi_tessellation` and :func:`poisson_line_tessellation`
#: (``max_pixels``): the most image pixels, 2**26 (an 8192 x 8192 image, 1.5 GiB as RGB floats), checked
#: before anything is drawn. Raise it with the ``max_pixels`` keyword.
MAX_PIXELS = 2**26


# ---------------------------------------------------------------------------------------------
# input checks
# ---------------------------------------------------------------------------------------------


def _count(value, name: str, minimum: int) -> int:
    """``value`` as an int >= ``minimum`` (bools and non-integers rejected)."""
    if isinstance(value, bool | np.bool_):
        raise ValueError(f"{name} must be an integer, got {value!r}")
    try:
        number = operator.index(value)
    except TypeError:
        raise ValueError(f"{name} must be an integer, got {value!r}") from None
    if number < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return number


def _check_shape(shape, max_pixels=None) -> tuple[int, int]:
    """``(H, W)`` as two positive ints, or a ValueError; with ``max_pixels``, a ValueError above that budget."""
    try:
        items = tuple(shape)
    except TypeError:
        raise ValueError(f"shape must be a pair (height, width), got {shape!r}") from None
    if len(items) != 2:
        raise ValueError(f"shape must be a pair (height, width), got {shape!r}")
    height, width = _count(items[0], "shape[0] (height)", 1), _count(items[1], "shape[1] (width)", 1)
    if max_pixels is not None:
        check_budget(height * width, budget(max_pixels, "max_pixels"), "max_pixels", "image pixels")
    return height, width


def _check_palette(palette) -> np.ndarray:
    """An ``(n, 3)`` float array of RGB colours in [0, 1] (``None`` gives :data:`DEFAULT_PALETTE`)."""
    if palette is None:
        return DEFAULT_PALETTE.copy()
    colours = float_array(palette, "palette", "an (n, 3) array of RGB colours")
    if colours.ndim != 2 or colours.shape[1] != 3 or colours.shape[0] < 1:
        raise ValueError(f"palette must be an (n, 3) array of RGB colours with n >= 1, got shape {colours.shape}")
    if not np.all(np.isfinite(colours)) or colours.min() < 0 or colours.max() > 1:
        raise ValueError("palette colours must be finite RGB values in [0, 1]")
    return colours


def _check_colour(colour, name: str) -> np.ndarray:
    """One RGB colour in [0, 1] as a float array of shape (3,)."""
    rgb = np.asarray(colour, dtype=float)
    if rgb.shape != (3,) or not np.all(np.isfinite(rgb)) or rgb.min() < 0 or rgb.max() > 1:
        raise ValueError(f"{name} must be an RGB colour (3 values in [0, 1]), got {colour!r}")
    return rgb


def _pixel_centres(height: int, width: int) -> np.ndarray:
    """``(H * W, 2)`` array of pixel centres (x, y), row-major."""
    ys, xs = np.mgrid[0:height, 0:width]
    return np.column_stack([xs.ravel() + 0.5, ys.ravel() + 0.5])


def _paint_labels(labels: np.ndarray, colours: np.ndarray, background: np.ndarray) -> np.ndarray:
    """RGB image with ``colours[label]`` where ``label >= 0`` and ``background`` elsewhere."""
    image = np.empty(labels.shape + (3,))
    image[...] = background
    visible = labels >= 0
    image[visible] = colours[labels[visible]]
    return image


def _outputs(image, labels, geometry, return_labels: bool, return_geometry: bool):
    """The image alone, or a tuple with the labels and/or geometry that were asked for."""
    return_labels = check_flag(return_labels, "return_labels")
    return_geometry = check_flag(return_geometry, "return_geometry")
    extra = ([labels] if return_labels else []) + ([geometry] if return_geometry else [])
    return (image, *extra) if extra else image


# ---------------------------------------------------------------------------------------------
# scaling dead leaves
# ---------------------------------------------------------------------------------------------


def _check_radii(r_min, r_max, alpha) -> tuple[float, float, float]:
    r_min = positive_number(r_min, "r_min")
    r_max = positive_number(r_max, "r_max")
    alpha = positive_number(alpha, "alpha")
    if r_min >= r_max:
        raise ValueError(f"r_min must be smaller than r_max, got r_min={r_min} and r_max={r_max}")
    return r_min, r_max, alpha


def _power_moment(r_min: float, r_max: float, exponent: float) -> float:
    """Integral of r**exponent over [r_min, r_max] (the logarithm when exponent == -1)."""
    if math.isclose(exponent, -1.0, rel_tol=0.0, abs_tol=1e-12):
        return math.log(r_max / r_min)
    power = exponent + 1.0
    return (r_max**power - r_min**power) / power


def _log_power_moment(r_min: float, r_max: float, exponent: float) -> float:
    """log of :func:`_power_moment`, computed from the logarithms of the bounds: no power overflows."""
    log_min, log_max = math.log(r_min), math.log(r_max)
    power = exponent + 1.0
    if math.isclose(power, 0.0, rel_tol=0.0, abs_tol=1e-12):
        return math.log(log_max - log_min)
    high, low = power * log_max, power * log_min
    return max(high, low) + math.log1p(-math.exp(-abs(high - low))) - math.log(abs(power))


def _power_law_radii(u: np.ndarray, r_min: float, r_max: float, alpha: float) -> np.ndarray:
    """Inverse CDF of the density proportional to r**(-alpha) on [r_min, r_max], at ``u`` in [0, 1)."""
    if math.isclose(alpha, 1.0, rel_tol=0.0, abs_tol=1e-12):
        return r_min * (r_max / r_min) ** u  # log-uniform
    power = 1.0 - alpha
    low, high = r_min**power, r_max**power
    return (low + u * (high - low)) ** (1.0 / power)


def dead_leaves_mean_area(r_min, r_max, alpha=3.0) -> float:
    """Mean leaf area E[pi r^2] for radii with density proportional to r^(-alpha) on [r_min, r_max].

    With Z = int r^(-alpha) dr the normalising constant,

    * E[r^2] = (r_max^(3-alpha) - r_min^(3-alpha)) / ((3 - alpha) Z) when alpha != 3,
    * E[r^2] = log(r_max / r_min) / Z when alpha == 3 (the scale-invariant case of Lee et al.),

    and Z = (r_max^(1-alpha) - r_min^(1-alpha)) / (1 - alpha), or log(r_max / r_min) when alpha == 1.

    Parameters
    ----------
    r_min, r_max : float
        Radius bounds in pixels, 0 < r_min < r_max.
    alpha : float
        Power-law exponent, > 0.

    Returns
    -------
    float
        pi E[r^2], in square pixels.

    References
    ----------
    Alvarez et al. 2015, Fig. 5; Lee, Mumford, Huang 2001 (ref. [27]), section 3.
    """
    r_min, r_max, alpha = _check_radii(r_min, r_max, alpha)
    try:
        ratio = _power_moment(r_min, r_max, 2.0 - alpha) / _power_moment(r_min, r_max, -alpha)
    except (OverflowError, ZeroDivisionError):
        ratio = math.nan
    if not 0.0 < ratio < math.inf:  # extreme bounds or exponent: a power over- or underflows, take logarithms
        log_ratio = _log_power_moment(r_min, r_max, 2.0 - alpha) - _log_power_moment(r_min, r_max, -alpha)
        if log_ratio > math.log(sys.float_info.max / math.pi):
            raise ValueError(f"the mean leaf area of r_min={r_min}, r_max={r_max}, alpha={alpha} exceeds the "
                             "largest float")
        ratio = math.exp(log_ratio)
    return math.pi * ratio


def dead_leaves_window_area(shape, r_max) -> float:
    """Area A = (W + 2 r_max)(H + 2 r_max) of the enlarged window where :func:`dead_leaves` drops centres.

    Parameters
    ----------
    shape : (int, int)
        Image shape (H, W) in pixels.
    r_max : float
        Largest leaf radius, pixels (> 0).

    Returns
    -------
    float
        ``(W + 2 r_max) (H + 2 r_max)``, square pixels.
    """
    height, width = _check_shape(shape)
    r_max = positive_number(r_max, "r_max")
    return (width + 2.0 * r_max) * (height + 2.0 * r_max)


def dead_leaves_coverage(n, mean_area, area) -> float:
    """Expected covered fraction 1 - exp(-n a / A) of the image after ``n`` leaves (Boolean model).

    A point of the image is covered by one leaf with probability a / A (the centre must fall in the
    disc of radius r around the point, which lies inside the enlarged window). For a Poisson number
    of leaves of mean n this gives exactly 1 - exp(-n a / A); for exactly n leaves the value is
    1 - (1 - a/A)^n, which differs by O(n (a/A)^2), far below the sampling noise of one image.

    Parameters
    ----------
    n : float
        Number of leaves, >= 0.
    mean_area : float
        Mean leaf area a (see :func:`dead_leaves_mean_area`), > 0.
    area : float
        Area A of the window where centres fall (see :func:`dead_leaves_window_area`), > 0.

    Returns
    -------
    float
        Expected fraction of covered points, in [0, 1).

    References
    ----------
    Alvarez et al. 2015, Fig. 5; Chiu et al. 2013 (ref. [4]), section 3.6 (Boolean model).
    """
    n = positive_number(n, "n", allow_zero=True)
    mean_area = positive_number(mean_area, "mean_area")
    area = positive_number(area, "area")
    return -math.expm1(-n * mean_area / area)


def _mean_lens_area(distances: np.ndarray, r_min, r_max, alpha, n_radii: int = 4097) -> np.ndarray:
    """E[area of D(x, r) n D(y, r)] for |x - y| = ``distances``, r with density ~ r^(-alpha) on [r_min, r_max].

    Composite Simpson in u = log r with the density's weight r f(r): even spacing in log r
    follows the heavy tail of small radii and keeps the rare large ones (a grid in the CDF
    misses the tail and underestimates L(0) = E[pi r^2] by several percent).
    """
    u = np.linspace(math.log(r_min), math.log(r_max), n_radii)
    r = np.exp(u)
    weights = np.full(n_radii, 2.0)
    weights[1::2], weights[0], weights[-1] = 4.0, 1.0, 1.0
    weights *= (u[1] - u[0]) / 3.0 * _radius_density_weights(u, r, r_min, r_max, alpha)
    half = distances[:, None] / 2.0
    ratio = np.clip(half / r[None, :], 0.0, 1.0)
    lens = 2.0 * r[None, :] ** 2 * np.arccos(ratio) - 2.0 * half * np.sqrt(np.maximum(r[None, :] ** 2 - half**2, 0.0))
    return lens @ weights


def _radius_density_weights(u: np.ndarray, r: np.ndarray, r_min, r_max, alpha) -> np.ndarray:
    """r f(r) at ``r = exp(u)``, f the radius density ~ r^(-alpha) on [r_min, r_max].

    The direct formula (same bits as always) unless a power over- or underflows (r_min = 1e-295 with
    alpha = 3); then from the logarithms, as :func:`dead_leaves_mean_area` does.
    """
    with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
        try:
            direct = r ** (1.0 - alpha) / _power_moment(r_min, r_max, -alpha)
        except (OverflowError, ZeroDivisionError):
            direct = None
    if direct is not None and np.all(np.isfinite(direct)) and np.all(direct > 0):
        return direct
    return np.exp((1.0 - alpha) * u - _log_power_moment(r_min, r_max, -alpha))


def dead_leaves_coverage_std(n, shape, r_min, r_max, alpha=3.0) -> float:
    """Standard deviation of the fraction of covered pixel centres after exactly ``n`` leaves.

    Pixel coverages are correlated, so the binomial variance p(1 - p)/(H W) would be far too small.
    For two points at distance d, both stay uncovered by one leaf with probability
    1 - (2 a - L(d)) / A, where L(d) = E[area of the lens of two discs of radius r at distance d];
    hence Cov(d) = (1 - (2a - L(d))/A)^n - (1 - a/A)^(2n), summed over all pairs of pixel centres
    (by displacement, with multiplicities (W - |dx|)(H - |dy|)); pairs farther apart than 2 r_max
    keep the negative covariance of a fixed number of leaves. L is computed by Simpson quadrature
    in log r on a grid of distances and interpolated.

    Parameters
    ----------
    n : int
        Number of leaves, >= 0.
    shape : (int, int)
        Image shape (H, W).
    r_min, r_max, alpha : float
        The radius law of :func:`dead_leaves`.

    Returns
    -------
    float
        The standard deviation of the covered fraction of one image.

    References
    ----------
    Chiu et al. 2013 (ref. [4]), section 3.6 (covariance of the Boolean model).
    """
    n = _count(n, "n", 0)
    height, width = _check_shape(shape)
    mean_area = dead_leaves_mean_area(r_min, r_max, alpha)
    area = dead_leaves_window_area(shape, r_max)
    reach_x = min(width - 1, math.ceil(2 * r_max))
    reach_y = min(height - 1, math.ceil(2 * r_max))
    dx = np.arange(-reach_x, reach_x + 1)
    dy = np.arange(-reach_y, reach_y + 1)
    distance = np.hypot(dx[None, :], dy[:, None])
    grid = np.linspace(0.0, 2.0 * r_max, 1025)
    lens = np.interp(distance, grid, _mean_lens_area(grid, r_min, r_max, alpha))
    both_uncovered = np.exp(n * np.log1p(-(2.0 * mean_area - lens) / area))
    uncovered_squared = np.exp(2 * n * np.log1p(-mean_area / area))
    # Beyond 2 r_max no leaf covers both points, yet the covariance is not 0: with exactly n
    # leaves, one leaf covering x leaves fewer for y, Cov = (1 - 2a/A)^n - (1 - a/A)^(2n) < 0.
    far = math.exp(n * math.log1p(-2.0 * mean_area / area)) - uncovered_squared
    pairs = (height - np.abs(dy))[:, None] * (width - np.abs(dx))[None, :]
    pixels = float(height * width)
    # every ordered pair of pixels: the near ones by displacement, all of them at the far value
    variance = (float(np.sum(pairs * (both_uncovered - uncovered_squared - far))) + pixels**2 * far) / pixels**2
    return math.sqrt(max(variance, 0.0))


@numba.njit(cache=True)
def _drop_leaves(labels, xs, ys, rs, first_index, uncovered, stop_uncovered):
    """Paint discs behind the leaves already there; return (leaves used, pixels still uncovered).

    A pixel takes the index of the first leaf covering its centre (the first leaf is on top). Stops
    after the leaf that brings the uncovered count to ``stop_uncovered`` or below, and as soon as
    nothing is left uncovered (later leaves would be invisible).
    """
    height, width = labels.shape
    for k in range(xs.shape[0]):
        x, y, r = xs[k], ys[k], rs[k]
        # Clamp in floating point before converting, so huge radii never overflow the int cast.
        col0 = int(max(0.0, math.floor(x - r - 0.5)))
        col1 = int(min(width - 1.0, math.ceil(x + r - 0.5)))
        row0 = int(max(0.0, math.floor(y - r - 0.5)))
        row1 = int(min(height - 1.0, math.ceil(y + r - 0.5)))
        r2 = r * r
        for row in range(row0, row1 + 1):
            ddy = row + 0.5 - y
            for col in range(col0, col1 + 1):
                ddx = col + 0.5 - x
                if labels[row, col] < 0 and ddx * ddx + ddy * ddy <= r2:
                    labels[row, col] = first_index + k
                    uncovered -= 1
        if uncovered <= stop_uncovered or uncovered == 0:
            return k + 1, uncovered
    return xs.shape[0], uncovered


def _leaf_batch(rng, size, height, width, r_min, r_max, alpha, n_colours):
    """Centres uniform in the window enlarged by r_max, power-law radii, uniform palette indices."""
    xs = rng.uniform(-r_max, width + r_max, size)
    ys = rng.uniform(-r_max, height + r_max, size)
    rs = _power_law_radii(rng.random(size), r_min, r_max, alpha)
    colour_index = rng.integers(n_colours, size=size)
    return xs, ys, rs, colour_index


def dead_leaves(shape, *, n_leaves=None, coverage_target=None, r_min, r_max, alpha=3.0, palette=None,
                background=(1.0, 1.0, 1.0), rng=None, return_labels=False, return_geometry=False,
                max_pixels: int = MAX_PIXELS):
    """Scaling dead leaves model: discs with power-law radii, each new leaf falling BEHIND the others.

    Leaves are discs whose radius has density proportional to r^(-alpha) on [r_min, r_max] (alpha = 3
    is the scale-invariant model of Lee et al.), with centres uniform in the image enlarged by r_max on
    every side so that no part of the image is less likely to be covered, and a colour drawn uniformly
    from ``palette``. They fall one after another, each one behind those already fallen (the first
    leaf is on top; equivalently the sequence is painted in reverse order). A pixel is covered by a
    disc when its centre lies in the closed disc.

    Stopping rule: with ``n_leaves`` only, exactly ``n_leaves`` leaves fall (the image may keep
    uncovered pixels, painted ``background``; the analytic covered fraction is
    :func:`dead_leaves_coverage`). With ``coverage_target`` only, leaves fall until at least that
    fraction of the pixels is covered (1.0: every pixel, the usual dead leaves image), at most
    2,000,000 leaves (a RuntimeWarning says when the target was not reached). With both,
    ``n_leaves`` is the cap. Leaves are drawn in a fixed order from ``rng``, so for one seed a
    shorter run is always a prefix of a longer one.

    Parameters
    ----------
    shape : (int, int)
        Image shape (H, W) in pixels.
    n_leaves : int, optional
        Number of leaves (>= 0), or the cap when ``coverage_target`` is given.
    coverage_target : float, optional
        Fraction of pixels to cover before stopping, in (0, 1].
    r_min, r_max : float
        Radius bounds in pixels, 0 < r_min < r_max.
    alpha : float
        Power-law exponent, > 0 (default 3, scale invariance).
    palette : (n, 3) array_like, optional
        RGB colours in [0, 1]; default :data:`DEFAULT_PALETTE`.
    background : RGB colour
        Colour of uncovered pixels (default white).
    rng : None, int or numpy.random.Generator
        Random source; same seed, same image.
    return_labels : bool
        Also return the ``(H, W)`` int64 index of the visible leaf per pixel (-1: uncovered).
    return_geometry : bool
        Also return the ``(k, 3)`` array of the leaves used, rows (x, y, r) in drop order (row i is
        leaf i of the labels), and their ``(k,)`` palette indices, as a pair.
    max_pixels : int, optional
        Budget: the most image pixels ``H * W`` (default :data:`MAX_PIXELS`, 2**26), checked before
        anything is drawn.

    Returns
    -------
    image : (H, W, 3) ndarray
        RGB float image in [0, 1].
    labels : (H, W) ndarray of int64
        Only with ``return_labels``.
    geometry : tuple of ((k, 3) ndarray, (k,) ndarray)
        Only with ``return_geometry``.

    References
    ----------
    Alvarez et al. 2015, section 2.4 and Fig. 5 (left); Alvarez, Gousseau, Morel 1999 (ref. [1]);
    Lee, Mumford, Huang 2001 (ref. [27]).
    """
    height, width = _check_shape(shape, max_pixels)
    r_min, r_max, alpha = _check_radii(r_min, r_max, alpha)
    colours = _check_palette(palette)
    background = _check_colour(background, "background")
    if n_leaves is None and coverage_target is None:
        raise ValueError("give n_leaves, coverage_target or both (see the stopping rule)")
    cap = _MAX_LEAVES if n_leaves is None else _count(n_leaves, "n_leaves", 0)
    target = None if coverage_target is None else positive_number(coverage_target, "coverage_target")
    if target is not None and target > 1.0:
        raise ValueError(f"coverage_target must lie in (0, 1], got {coverage_target!r}")
    rng = as_generator(rng)

    n_pixels = height * width
    stop_uncovered = -1 if target is None else n_pixels - math.ceil(target * n_pixels - 1e-9)
    labels = np.full((height, width), -1, dtype=np.int64)
    uncovered, used, batches = n_pixels, 0, []
    while used < cap and (target is None or uncovered > stop_uncovered):
        batch = _leaf_batch(rng, _LEAF_BATCH, height, width, r_min, r_max, alpha, len(colours))
        size = min(_LEAF_BATCH, cap - used)
        count = size
        if uncovered > 0:  # once all is covered, later leaves are invisible: draw them, skip painting
            xs, ys, rs = (np.ascontiguousarray(values[:size]) for values in batch[:3])
            painted, uncovered = _drop_leaves(labels, xs, ys, rs, used, uncovered, stop_uncovered)
            count = size if target is None else painted
        batches.append(tuple(values[:count] for values in batch))
        used += count
    if target is not None and uncovered > stop_uncovered:
        warnings.warn(f"dead_leaves stopped after {used} leaves with {1 - uncovered / n_pixels:.4f} of the image "
                      f"covered (target {target})", RuntimeWarning, stacklevel=2)
    discs, colour_index = _stack_leaves(batches)
    image = _paint_labels(labels, colours[colour_index], background)
    return _outputs(image, labels, (discs, colour_index), return_labels, return_geometry)


def _stack_leaves(batches) -> tuple[np.ndarray, np.ndarray]:
    """Concatenate batches into ``(k, 3)`` discs (x, y, r) and ``(k,)`` palette indices."""
    if not batches:
        return np.empty((0, 3)), np.empty(0, dtype=np.int64)
    xs, ys, rs, colour_index = (np.concatenate(parts) for parts in zip(*batches, strict=True))
    return np.column_stack([xs, ys, rs]), colour_index.astype(np.int64)


# ---------------------------------------------------------------------------------------------
# random tessellations
# ---------------------------------------------------------------------------------------------


def voronoi_tessellation(shape, n_cells, *, palette=None, rng=None, return_labels=False, return_geometry=False,
                         max_pixels: int = MAX_PIXELS):
    """Poisson-Voronoi tessellation of the image: ``n_cells`` uniform centres, one palette colour per cell.

    Centres are independent and uniform in the image rectangle [0, W] x [0, H] (a binomial process,
    i.e. a Poisson process conditioned on its count); each pixel takes the cell of the centre nearest
    to its pixel centre (``scipy.spatial.cKDTree``); each cell gets a colour drawn uniformly from the
    palette. Cells whose region contains no pixel centre are invisible.

    Parameters
    ----------
    shape : (int, int)
        Image shape (H, W).
    n_cells : int
        Number of centres, >= 1.
    palette : (n, 3) array_like, optional
        RGB colours in [0, 1]; default :data:`DEFAULT_PALETTE`.
    rng : None, int or numpy.random.Generator
        Random source; same seed, same image.
    return_labels : bool
        Also return the ``(H, W)`` int64 index of each pixel's cell.
    return_geometry : bool
        Also return the ``(n_cells, 2)`` centres (x, y) and their ``(n_cells,)`` palette indices.
    max_pixels : int, optional
        Budget: the most image pixels ``H * W`` (default :data:`MAX_PIXELS`, 2**26), checked before
        anything is drawn.

    Returns
    -------
    image : (H, W, 3) ndarray
        RGB float image in [0, 1]; then ``labels`` and/or ``geometry`` when asked for.

    References
    ----------
    Alvarez et al. 2015, section 2.4 and Fig. 5 (middle); Chiu et al. 2013 (ref. [4]), section 9.7.
    """
    height, width = _check_shape(shape, max_pixels)
    n_cells = _count(n_cells, "n_cells", 1)
    colours = _check_palette(palette)
    rng = as_generator(rng)
    try:
        centres = np.column_stack([rng.uniform(0.0, width, n_cells), rng.uniform(0.0, height, n_cells)])
        pixels = _pixel_centres(height, width)
    except (ValueError, MemoryError) as err:  # NumPy cannot allocate that many centres or pixels
        raise ValueError(f"n_cells={n_cells:,} cells over shape={(height, width)} pixels are too many to allocate "
                         f"({type(err).__name__}); ask for fewer") from None
    colour_index = rng.integers(len(colours), size=n_cells)
    _, nearest = cKDTree(centres).query(pixels)
    labels = np.asarray(nearest, dtype=np.int64).reshape(height, width)
    image = _paint_labels(labels, colours[colour_index], np.zeros(3))
    return _outputs(image, labels, (centres, colour_index), return_labels, return_geometry)


def _lines_hitting_window(height: int, width: int, intensity: float, rng) -> np.ndarray:
    """Isotropic Poisson lines hitting [0, W] x [0, H] as rows (cos t, sin t, p): x cos t + y sin t = p.

    Lines hitting the disc circumscribing the window (centre c, radius R) have normal directions t
    uniform in [0, 2 pi) and distances to c uniform in [0, R]; their number is Poisson of mean
    intensity * 2 pi R / pi (lines hitting a convex set K: intensity * perimeter(K) / pi).
    Only those that hit the window are kept.
    """
    centre = np.array([width / 2.0, height / 2.0])
    radius = math.hypot(width, height) / 2.0
    count = rng.poisson(2.0 * intensity * radius)
    angles = rng.uniform(0.0, 2.0 * math.pi, count)
    distances = rng.uniform(0.0, radius, count)
    normals = np.column_stack([np.cos(angles), np.sin(angles)])
    offsets = distances + normals @ centre
    corners = np.array([[0.0, 0.0], [width, 0.0], [0.0, height], [width, height]])
    signed = corners @ normals.T - offsets[None, :]
    hits = (signed.min(axis=0) <= 0.0) & (signed.max(axis=0) >= 0.0)
    return np.column_stack([normals[hits], offsets[hits]])


def _line_cell_labels(height: int, width: int, lines: np.ndarray) -> np.ndarray:
    """Cell index per pixel: pixels whose centres lie on the same side of every line share a cell.

    The cells of a line arrangement are convex (intersections of half-planes), so the sign vector
    identifies a cell exactly, even a thin one whose pixel centres are not 4-connected. The signs are
    appended one bit per line to an int64 key; when the key would overflow, keys are renumbered
    densely (``np.unique``), which keeps distinct sign vectors distinct. Cells are numbered in
    increasing key order.
    """
    xs = np.arange(width) + 0.5
    ys = np.arange(height) + 0.5
    keys = np.zeros((height, width), dtype=np.int64)
    free_bits = 62
    for a, b, p in lines:
        if free_bits == 0:
            keys = _dense_labels(keys)
            free_bits = 62 - int(keys.max()).bit_length()
        above = (xs * a)[None, :] + (ys * b)[:, None] > p
        keys = 2 * keys + above
        free_bits -= 1
    return _dense_labels(keys)


def _dense_labels(keys: np.ndarray) -> np.ndarray:
    """Replace each value of ``keys`` by its rank among the distinct values (0, 1, ...)."""
    _, inverse = np.unique(keys, return_inverse=True)
    return inverse.reshape(keys.shape).astype(np.int64)


def poisson_line_tessellation(shape, intensity, *, palette=None, rng=None, return_labels=False,
                              return_geometry=False, max_pixels: int = MAX_PIXELS):
    """Isotropic Poisson line tessellation of the image, each cell coloured independently.

    The line process is stationary and isotropic with the normalisation of Chiu et al.: the number of
    lines hitting a convex window K is Poisson with mean ``intensity * perimeter(K) / pi``
    (Cauchy-Crofton); ``intensity`` is then the mean line length per unit area. Cells are the connected components
    of the image minus the lines; being convex, each is identified by the side of every line its
    pixel centres lie on. Each cell gets a colour drawn uniformly from the palette.

    Parameters
    ----------
    shape : (int, int)
        Image shape (H, W).
    intensity : float
        Line intensity (mean line length per unit area, in 1/pixel), >= 0.
    palette : (n, 3) array_like, optional
        RGB colours in [0, 1]; default :data:`DEFAULT_PALETTE`.
    rng : None, int or numpy.random.Generator
        Random source; same seed, same image.
    return_labels : bool
        Also return the ``(H, W)`` int64 cell index per pixel.
    return_geometry : bool
        Also return the ``(m, 3)`` lines hitting the image, rows (a, b, p) for a x + b y = p with
        (a, b) a unit normal, and the ``(n_cells,)`` palette indices of the cells.
    max_pixels : int, optional
        Budget: the most image pixels ``H * W`` (default :data:`MAX_PIXELS`, 2**26), checked before
        anything is drawn.

    Returns
    -------
    image : (H, W, 3) ndarray
        RGB float image in [0, 1]; then ``labels`` and/or ``geometry`` when asked for.

    References
    ----------
    Alvarez et al. 2015, section 2.4 and Fig. 5 (middle); Chiu et al. 2013 (ref. [4]), sections 8.2
    (Poisson line process, Cauchy-Crofton) and 9.4 (Poisson line tessellation).
    """
    height, width = _check_shape(shape, max_pixels)
    intensity = positive_number(intensity, "intensity", allow_zero=True)
    expected_lines = intensity * 2.0 * (height + width) / math.pi
    if expected_lines > _MAX_LINES:
        raise ValueError(f"intensity {intensity} gives about {expected_lines:.3g} lines in the image; at most "
                         f"{_MAX_LINES} are supported")
    colours = _check_palette(palette)
    rng = as_generator(rng)
    lines = _lines_hitting_window(height, width, intensity, rng)
    labels = _line_cell_labels(height, width, lines)
    colour_index = rng.integers(len(colours), size=int(labels.max()) + 1)
    image = _paint_labels(labels, colours[colour_index], np.zeros(3))
    return _outputs(image, labels, (lines, colour_index), return_labels, return_geometry)


# ---------------------------------------------------------------------------------------------
# iterated function systems
# ---------------------------------------------------------------------------------------------


def sierpinski_triangle(*, right_angled: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The Sierpinski triangle IFS: three maps x -> x/2 + v_i/2 toward the vertices v_i, probabilities 1/3.

    The vertices are (0, 0), (1, 0), (1/2, sqrt(3)/2) (equilateral), or (0, 0), (1, 0), (0, 1) with
    ``right_angled=True`` (the gasket whose level-j copies are exactly dyadic boxes of side 2^-j, so
    that box counting in the frame (0, 0, 1) finds N = 3^j). Both attractors have box-counting (and
    Hausdorff) dimension log 3 / log 2 = 1.585.

    Parameters
    ----------
    right_angled : bool, default False
        Use the right-angled gasket (vertices (0, 0), (1, 0), (0, 1)) instead of the
        equilateral one.

    Returns
    -------
    linear : (3, 2, 2) ndarray
    offsets : (3, 2) ndarray
    probabilities : (3,) ndarray
    """
    top = [0.0, 1.0] if right_angled else [0.5, math.sqrt(3.0) / 2.0]
    vertices = np.array([[0.0, 0.0], [1.0, 0.0], top])
    linear = np.repeat(0.5 * np.eye(2)[None], 3, axis=0)
    return linear, vertices / 2.0, np.full(3, 1.0 / 3.0)


def barnsley_fern() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Barnsley's fern (Fractals Everywhere, 1988, ch. III): four affine maps with probabilities
    0.01 (stem), 0.85 (successively smaller leaflets), 0.07 and 0.07 (largest left and right leaflets).

    Returns ``(linear (4, 2, 2), offsets (4, 2), probabilities (4,))``; the attractor lies in about
    [-2.18, 2.66] x [0, 9.99] (y up). The stem map is singular (rank 1), still a contraction.

    Returns
    -------
    linear : ndarray, shape (4, 2, 2)
        Linear parts of the four maps.
    offsets : ndarray, shape (4, 2)
        Their translations.
    probabilities : ndarray, shape (4,)
        Their probabilities, (0.01, 0.85, 0.07, 0.07).
    """
    linear = np.array([
        [[0.00, 0.00], [0.00, 0.16]],
        [[0.85, 0.04], [-0.04, 0.85]],
        [[0.20, -0.26], [0.23, 0.22]],
        [[-0.15, 0.28], [0.26, 0.24]],
    ])
    offsets = np.array([[0.0, 0.0], [0.0, 1.6], [0.0, 1.6], [0.0, 0.44]])
    return linear, offsets, np.array([0.01, 0.85, 0.07, 0.07])


def _check_ifs(maps) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Validate ``(linear (k, 2, 2), offsets (k, 2), probabilities (k,))``: contractions, probabilities."""
    try:
        linear, offsets, probabilities = maps
    except (TypeError, ValueError):
        raise ValueError("maps must be a triple (linear (k, 2, 2), offsets (k, 2), probabilities (k,))") from None
    linear = np.asarray(linear, dtype=float)
    offsets = np.asarray(offsets, dtype=float)
    probabilities = np.asarray(probabilities, dtype=float)
    k = linear.shape[0] if linear.ndim == 3 else -1
    if k < 1 or linear.shape != (k, 2, 2) or offsets.shape != (k, 2) or probabilities.shape != (k,):
        raise ValueError("maps must be (linear (k, 2, 2), offsets (k, 2), probabilities (k,)) with k >= 1, got "
                         f"shapes {linear.shape}, {offsets.shape}, {probabilities.shape}")
    if not (np.all(np.isfinite(linear)) and np.all(np.isfinite(offsets)) and np.all(np.isfinite(probabilities))):
        raise ValueError("IFS maps and probabilities must be finite")
    norms = np.linalg.norm(linear, ord=2, axis=(1, 2))
    if np.any(norms >= 1.0):
        bad = int(np.argmax(norms >= 1.0))
        raise ValueError(f"every IFS map must be a contraction (spectral norm < 1); map {bad} has norm {norms[bad]:.4g}")
    if np.any(probabilities < 0) or not math.isclose(probabilities.sum(), 1.0, abs_tol=1e-9):
        raise ValueError(f"IFS probabilities must be >= 0 and sum to 1, got {probabilities.tolist()}")
    return linear, offsets, probabilities


@numba.njit(cache=True)
def _chaos_game(linear, offsets, choices, start):
    """Iterate x <- A[i] x + b[i] for the map sequence ``choices``, starting from ``start``."""
    points = np.empty((choices.shape[0], 2))
    x, y = start[0], start[1]
    for t in range(choices.shape[0]):
        i = choices[t]
        x, y = (linear[i, 0, 0] * x + linear[i, 0, 1] * y + offsets[i, 0],
                linear[i, 1, 0] * x + linear[i, 1, 1] * y + offsets[i, 1])
        points[t, 0] = x
        points[t, 1] = y
    return points


#: Default budget of :func:`ifs_chaos_game` and :func:`ifs_fractal`: the most chaos-game points (5e7, 1.2 GB of
#: points and choices). Raise it with the ``max_points`` keyword.
MAX_IFS_POINTS = 50_000_000
#: Default budget of :func:`ifs_fractal`: the most image pixels (2**26, a 8192 x 8192 image, as :data:`MAX_PIXELS`).
#: Raise it with the ``max_pixels`` keyword.
MAX_IFS_PIXELS = MAX_PIXELS


def ifs_chaos_game(maps=None, *, n_points=200_000, rng=None,
                   max_points: int = MAX_IFS_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """Points of an IFS attractor by the chaos game, with the index of the map that produced each.

    The walk starts at the fixed point of map 0, which belongs to the attractor, so every point
    lies on it (up to rounding) and no burn-in is needed; at each step map i is chosen with
    probability ``probabilities[i]``.

    Parameters
    ----------
    maps : (linear (k, 2, 2), offsets (k, 2), probabilities (k,)), optional
        Affine contractions x -> linear[i] @ x + offsets[i] (spectral norm < 1) and their
        probabilities (>= 0, summing to 1). Default :func:`barnsley_fern`.
    n_points : int
        Number of points, >= 1.
    rng : None, int or numpy.random.Generator
        Random source.
    max_points : int
        Budget: the most points (default :data:`MAX_IFS_POINTS`), checked before anything is
        allocated.

    Returns
    -------
    points : (n_points, 2) ndarray
        Points in the IFS's own coordinates.
    map_index : (n_points,) ndarray of int64
        Map applied to obtain each point (which sub-copy of the attractor it lies in).

    References
    ----------
    Alvarez et al. 2015, Fig. 5 (right); Barnsley 1988, ch. III; Demko, Hodges, Naylor 1985 (ref. [6]).
    """
    linear, offsets, probabilities = _check_ifs(barnsley_fern() if maps is None else maps)
    n_points = _count(n_points, "n_points", 1)
    check_budget(n_points, budget(max_points, "max_points"), "max_points", "chaos-game points")
    rng = as_generator(rng)
    choices = rng.choice(len(probabilities), size=n_points, p=probabilities / probabilities.sum())
    start = np.linalg.solve(np.eye(2) - linear[0], offsets[0])
    points = _chaos_game(linear, offsets, choices.astype(np.int64), start)
    return points, choices.astype(np.int64)


def _fit_to_image(points: np.ndarray, height: int, width: int, margin: float) -> np.ndarray:
    """Scale and translate ``points`` (y up) into pixel coordinates (y down), centred, aspect kept."""
    low, high = points.min(axis=0), points.max(axis=0)
    extent = high - low
    room = np.array([width - 2.0 * margin, height - 2.0 * margin])
    scales = [room[i] / extent[i] for i in range(2) if extent[i] > 0]
    scale = min(scales) if scales else 1.0
    middle = (low + high) / 2.0
    x = width / 2.0 + (points[:, 0] - middle[0]) * scale
    y = height / 2.0 - (points[:, 1] - middle[1]) * scale
    return np.column_stack([x, y])


def ifs_fractal(shape, maps=None, *, n_points=200_000, mode="binary", margin=2.0, palette=None,
                background=(1.0, 1.0, 1.0), rng=None, return_labels=False, return_geometry=False,
                max_points: int = MAX_IFS_POINTS, max_pixels: int = MAX_IFS_PIXELS):
    """An IFS fractal drawn by the chaos game, each pixel coloured by the map that produced its points.

    The points of :func:`ifs_chaos_game` are fitted into the image (their bounding box scaled to the
    image minus ``margin`` pixels, aspect ratio kept, centred, y flipped so that the IFS's "up" is up)
    and binned into pixels. A hit pixel takes the colour ``palette[i % n]`` of the map i that produced
    most of its points (ties: the lowest index). ``mode="binary"`` paints hit pixels in that colour;
    ``mode="density"`` blends from ``background`` to it with weight log(1 + count) / log(1 + max count).

    Parameters
    ----------
    shape : (int, int)
        Image shape (H, W).
    maps : (linear, offsets, probabilities), optional
        The IFS (see :func:`ifs_chaos_game`); default :func:`barnsley_fern`.
    n_points : int
        Number of chaos-game points, >= 1.
    mode : {"binary", "density"}
        How hit counts become intensities.
    margin : float
        Empty border in pixels, >= 0 and < min(H, W) / 2.
    palette : (n, 3) array_like, optional
        RGB colours in [0, 1]; default :data:`DEFAULT_PALETTE`.
    background : RGB colour
        Colour of pixels no point hits (default white).
    rng : None, int or numpy.random.Generator
        Random source; same seed, same image.
    return_labels : bool
        Also return the ``(H, W)`` int64 map index per pixel (-1: no point).
    return_geometry : bool
        Also return ``(points in pixel coordinates (n, 2), map_index (n,))``.
    max_points : int
        Budget on ``n_points`` (default :data:`MAX_IFS_POINTS`).
    max_pixels : int
        Budget: the most image pixels ``H * W`` (default :data:`MAX_IFS_PIXELS`), checked before
        anything is allocated.

    Returns
    -------
    image : (H, W, 3) ndarray
        RGB float image in [0, 1]; then ``labels`` and/or ``geometry`` when asked for.

    References
    ----------
    Alvarez et al. 2015, section 2.4 and Fig. 5 (right); Barnsley 1988.
    """
    height, width = _check_shape(shape, max_pixels)
    check_choice(mode, ("binary", "density"), "mode")
    margin = positive_number(margin, "margin", allow_zero=True)
    if 2.0 * margin >= min(height, width):
        raise ValueError(f"margin must be smaller than half the image's smaller side, got {margin}")
    colours = _check_palette(palette)
    background = _check_colour(background, "background")
    maps = _check_ifs(barnsley_fern() if maps is None else maps)
    points, map_index = ifs_chaos_game(maps, n_points=n_points, rng=rng, max_points=max_points)
    n_maps = len(maps[2])
    pixels = _fit_to_image(points, height, width, margin)
    cols = np.clip(np.floor(pixels[:, 0]).astype(np.int64), 0, width - 1)
    rows = np.clip(np.floor(pixels[:, 1]).astype(np.int64), 0, height - 1)
    flat = rows * width + cols
    per_map = np.bincount(flat * n_maps + map_index, minlength=height * width * n_maps).reshape(-1, n_maps)
    counts = per_map.sum(axis=1)
    labels = np.where(counts > 0, per_map.argmax(axis=1), -1).reshape(height, width)
    image = _paint_labels(labels, colours[np.arange(n_maps) % len(colours)], background)
    if mode == "density":
        weight = (np.log1p(counts) / math.log1p(counts.max())).reshape(height, width, 1)
        image = background + weight * (image - background)
    return _outputs(image, labels, (pixels, map_index), return_labels, return_geometry)


def box_counting_dimension(points, *, levels=(2, 7), frame=None) -> float:
    """Box-counting dimension of a point set: slope of log N(eps) against log(1 / eps).

    The points are mapped into the unit square by ``frame`` (default: their bounding box's lower
    corner and larger side); for eps = 2^-j, j = levels[0] ... levels[1], N(eps) is the number of
    boxes of side eps of the grid tiling the unit square that hold at least one point, and the
    dimension is the least-squares slope. At the few levels a sample allows, the estimate depends on
    how the set sits on the grid: a set made of dyadic copies (the right-angled Sierpinski gasket in
    the frame (0, 0, 1)) gives N = 3^j exactly, a sample's own bounding box shifts the grid slightly.

    Parameters
    ----------
    points : (n, 2) array_like
        At least two distinct finite points.
    levels : (int, int)
        Smallest and largest j, 0 <= levels[0] < levels[1] <= 30.
    frame : (float, float, float), optional
        ``(x0, y0, side)``: the square [x0, x0 + side] x [y0, y0 + side] that is tiled; every point
        must lie in it.

    Returns
    -------
    float
        The estimated dimension.

    References
    ----------
    Barnsley 1988, ch. V (box-counting theorem).
    """
    pts = point_array(points, "points", min_points=2)
    try:
        low_level, high_level = (_count(level, "levels", 0) for level in levels)
    except (TypeError, ValueError):
        raise ValueError(f"levels must be a pair of integers 0 <= j0 < j1 <= 30, got {levels!r}") from None
    if not low_level < high_level <= 30:
        raise ValueError(f"levels must be a pair of integers 0 <= j0 < j1 <= 30, got {levels!r}")
    unit = _unit_frame(pts, frame)
    js = np.arange(low_level, high_level + 1)
    counts = [_occupied_boxes(unit, int(j)) for j in js]
    slope = np.polyfit(js * math.log(2.0), np.log(counts), 1)[0]
    return float(slope)


def _unit_frame(points: np.ndarray, frame) -> np.ndarray:
    """``points`` mapped into the unit square by ``frame = (x0, y0, side)`` or by their bounding box."""
    if frame is None:
        side = float((points.max(axis=0) - points.min(axis=0)).max())
        if side == 0.0:
            raise ValueError("points must not all coincide")
        return (points - points.min(axis=0)) / side
    try:
        x0, y0, side = (float(value) for value in frame)
    except (TypeError, ValueError):
        raise ValueError(f"frame must be (x0, y0, side), got {frame!r}") from None
    side = positive_number(side, "frame side")
    unit = (points - np.array([x0, y0])) / side
    if not (np.all(np.isfinite(unit)) and unit.min() >= 0.0 and unit.max() <= 1.0):
        raise ValueError("every point must lie in the frame square")
    return unit


def _occupied_boxes(unit: np.ndarray, level: int) -> int:
    """Number of boxes of side 2^-level of the unit square holding a point of ``unit``.

    Boxes are half-open except the last row and column, closed so that points at 1 add no box; a box
    is coded as one int64 (column * 2^level + row, < 2^60) so that counting is a 1-D ``np.unique``.
    """
    cells = 2**level
    index = np.minimum(np.floor(unit * cells), cells - 1).astype(np.int64)
    return len(np.unique(index[:, 0] * cells + index[:, 1]))
