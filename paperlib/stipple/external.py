"""Two stipplers this project did not write, behind thin validated wrappers.

Kim et al. 2009 learn from an artist's tone textures; the project's own exemplars come from its
own generator (:func:`paperlib.datasets.stipple_tone_texture`). To run the pipeline on input it
was not tuned on, these wrappers call two weighted Voronoi stipplers published on PyPI (both
descendants of Secord 2002), as shipped:

- :func:`inksep_stipples`: ``inksep`` 1.0.0, "separation-constrained weighted Voronoi
  stippling" (pixel-grid Lloyd relaxation plus a pass that pushes dark dots apart to
  ``sep_factor`` times the sum of their radii). Called through its public class
  :class:`inksep.InkSep`, which reads an image file: the gray image is written as an 8-bit PNG
  into a temporary directory that is removed afterwards. InkSep blurs it with a 1-px box
  filter (no effect on a flat patch). Dot radii follow InkSep's SVG export
  (``(max_dot - v * dot_scale) / 2`` with ``v`` the brightness under the dot); dots on pure
  white are dropped, as its SVG export drops them.
- :func:`stippler_stipples`: ``stippler`` 0.2.1.1, "hand-drawn weighted Voronoi stippling"
  (Rougier's polygon-Voronoi Lloyd relaxation, early-stopped, optional size and position
  jitter). Called through its public steps :func:`stippler.initialization`,
  :func:`stippler.relax`, :func:`stippler.assign_radii` and
  :func:`stippler.apply_position_jitter` on a density array, not through
  :func:`stippler.stipple`, whose file loader fails on flat patches (0.2.1.1):
  ``scipy.ndimage.zoom(order=0)`` writes zeros into the last row and column at some zoom
  factors (5 for a 256 x 256 patch of 2670 points), and its contrast stretch then turns those
  zeros into the only ink, so every point is sampled on the image's edge. The density given to
  the tool is ``1 - gray`` divided by its maximum (Secord's ``rho / max rho``; centroids do not
  depend on the scale), floored at ``1e-3`` so a cell on pure white has a defined centroid,
  and enlarged by pixel replication with stippler's own rule (each Voronoi region covers
  about 500 density pixels).

Both tools take an integer seed and use no global random state: ``rng`` (``None``, an int or
a :class:`numpy.random.Generator`) is turned into that seed, so the same seed gives the same
output. Neither touches the network.

Flat patches: both tools spread a given number of dots evenly, so on a flat gray patch the tone
comes from the number of dots. By default (``n_points=None``) it is one dot's area per unit of
darkness, :func:`stipple_count`; overlapping dots make the ink fraction of a rasterisation
fall short of the darkness at dark tones.

Coordinates: stipple centres are ``(row, col)`` floats in pixel-index coordinates (pixel
``(i, j)`` centred on ``(i, j)``), the convention of :func:`skimage.draw.disk`, used by
:func:`rasterize_stipples`.

References
----------
Kim et al. (2009). Stippling by example. NPAR, section 3.1-3.2 (example tone textures).
Secord, A. (2002). Weighted Voronoi stippling. NPAR, pp. 37-43 (what both tools implement).
inksep 1.0.0, https://github.com/off-signal/inksep (MIT).
stippler 0.2.1.1, https://github.com/fstwn/stippler (BSD-3-Clause), after N. P. Rougier's
weighted Voronoi stippler.
"""

from __future__ import annotations

import math
import tempfile
from numbers import Integral
from pathlib import Path
from typing import NamedTuple

import numpy as np
from skimage.draw import disk

from paperlib._checks import as_generator, integer_at_least, positive_number

__all__ = [
    "INKSEP_VERSION",
    "STIPPLER_VERSION",
    "ExternalStipples",
    "inksep_stipples",
    "rasterize_stipples",
    "stipple_count",
    "stippler_stipples",
]

#: The versions these wrappers were written and tested against (pyproject's ``test`` extra).
INKSEP_VERSION = "1.0.0"
STIPPLER_VERSION = "0.2.1.1"

#: Smallest side (px) of a gray image given to a stippler.
MIN_SIDE = 8
#: stippler's resolution rule: each Voronoi region covers about this many density pixels.
_STIPPLER_PIXELS_PER_REGION = 500
#: Density floor of the stippler wrapper, relative to the darkest pixel.
_STIPPLER_DENSITY_FLOOR = 1e-3


class ExternalStipples(NamedTuple):
    """Stipple centres and dot radii produced by an external stippler.

    Attributes
    ----------
    centres : numpy.ndarray, shape (n, 2)
        ``(row, col)`` of the dot centres, pixel-index coordinates of the input image.
    radii : numpy.ndarray, shape (n,)
        Dot radii in pixels of the input image.
    """

    centres: np.ndarray
    radii: np.ndarray


def _import(module: str, version: str):
    try:
        return __import__(module)
    except ImportError as error:
        raise ImportError(
            f"{module} is not installed: `pip install {module}=={version}` (or `pip install -e '.[test]'`, "
            "whose test extra lists it)"
        ) from error


def _check_gray(gray) -> np.ndarray:
    array = np.asarray(gray)
    if array.dtype == bool or not (np.issubdtype(array.dtype, np.integer) or np.issubdtype(array.dtype, np.floating)):
        raise ValueError(f"gray must be a real-valued 2-D array in [0, 1], got dtype {array.dtype}")
    if array.ndim != 2:
        raise ValueError(f"gray must be a 2-D grayscale image, got shape {array.shape}")
    if min(array.shape) < MIN_SIDE:
        raise ValueError(f"gray must be at least {MIN_SIDE} x {MIN_SIDE} pixels, got shape {array.shape}")
    array = array.astype(float)
    if not np.all(np.isfinite(array)):
        raise ValueError("gray holds NaN or infinite values: expected grays in [0, 1]")
    low, high = float(array.min()), float(array.max())
    if low < 0.0 or high > 1.0:
        raise ValueError(f"gray must lie in [0, 1] (0 black, 1 white), got values in [{low}, {high}]")
    return array


def _seed(rng) -> int:
    if rng is not None and not isinstance(rng, (Integral, np.random.Generator)) or isinstance(rng, bool):
        raise ValueError(f"rng must be None, an int seed or a numpy.random.Generator, got {rng!r}")
    return int(as_generator(rng).integers(0, 2**32))


def stipple_count(gray, dot_radius: float) -> int:
    """Default number of dots: the image's darkness summed, in dot areas.

    ``round(sum(1 - gray) / (pi * dot_radius**2))``: dots of radius ``dot_radius`` that did not
    overlap would cover as much of the image as its darkness asks.

    Raises
    ------
    ValueError
        Bad ``gray`` (see :func:`inksep_stipples`) or a non-positive ``dot_radius``.
    """
    array = _check_gray(gray)
    radius = positive_number(dot_radius, "dot_radius")
    return int(round(float(np.sum(1.0 - array)) / (math.pi * radius**2)))


def _check_count(n_points, array: np.ndarray, dot_radius: float) -> int:
    if n_points is None:
        return stipple_count(array, dot_radius)
    count = integer_at_least(n_points, "n_points", 0)
    if count > array.size:
        raise ValueError(f"n_points must not exceed the number of pixels ({array.size}), got {n_points!r}")
    if count > 0 and float(array.min()) >= 1.0:
        raise ValueError(f"gray is white everywhere: nothing to stipple with n_points={count}")
    return count


def _empty() -> ExternalStipples:
    return ExternalStipples(np.empty((0, 2)), np.empty(0))


def inksep_stipples(
    gray,
    n_points=None,
    rng=None,
    *,
    dot_radius: float = 2.5,
    dot_size_factor: float = 0.0,
    iterations: int = 30,
    sep_factor: float = 0.85,
    sep_dark_threshold: float = 0.5,
) -> ExternalStipples:
    """Stipple a grayscale image with inksep 1.0.0 (separation-constrained weighted Voronoi).

    Parameters
    ----------
    gray : array_like, 2-D
        Grays in [0, 1] (0 black, 1 white), each side at least 8 px.
    n_points : int, optional
        Number of dots; default :func:`stipple_count` of ``gray`` and ``dot_radius``. 0 gives
        no dots.
    rng : None, int or numpy.random.Generator, optional
        Source of the integer seed handed to inksep (its rejection-sampled start).
    dot_radius : float, optional
        Radius (px) of the smallest dot, the one on white (inksep's ``min_dot_size / 2``),
        default 2.5: a pen's dot.
    dot_size_factor : float, optional
        inksep's growth of dots with darkness: the dot on black is ``1 + dot_size_factor``
        times larger. Default 0: one pen, one dot size.
    iterations : int, optional
        Lloyd generations (default 30, as the paper's 30 synthesis iterations; inksep's own
        default is 100 with early stopping).
    sep_factor, sep_dark_threshold : float, optional
        inksep's separation pass: dots darker than ``sep_dark_threshold`` are pushed apart to
        ``sep_factor`` times the sum of their radii (defaults 0.85 and 0.5, inksep's).

    Returns
    -------
    ExternalStipples
        ``centres`` (n, 2) as ``(row, col)`` and ``radii`` (n,) in pixels.

    Raises
    ------
    ValueError
        ``gray`` not a 2-D finite array in [0, 1] of sides >= 8, white everywhere while dots
        are asked for; bad counts, radii, factors or ``rng``.
    ImportError
        inksep is not installed.

    Notes
    -----
    The image reaches inksep as an 8-bit PNG written into a temporary directory, removed on
    return; borders are off (``border_width=0``), so dots reach to 1 px from the edge.
    """
    array = _check_gray(gray)
    radius = positive_number(dot_radius, "dot_radius")
    count = _check_count(n_points, array, radius)
    factor = positive_number(dot_size_factor, "dot_size_factor", allow_zero=True)
    generations = integer_at_least(iterations, "iterations", 1)
    separation = positive_number(sep_factor, "sep_factor", allow_zero=True)
    threshold = positive_number(sep_dark_threshold, "sep_dark_threshold")
    if threshold > 1.0:
        raise ValueError(f"sep_dark_threshold must lie in (0, 1], got {sep_dark_threshold!r}")
    seed = _seed(rng)
    if count == 0:
        return _empty()
    _import("inksep", INKSEP_VERSION)
    from inksep import InkSep
    from inksep.svg import sample_v, visible_mask
    from PIL import Image

    with tempfile.TemporaryDirectory(prefix="paperlib-inksep-") as folder:
        path = Path(folder) / "gray.png"
        Image.fromarray(np.round(array * 255.0).astype(np.uint8), mode="L").save(path)
        tool = InkSep(
            path,
            n_stipples=count,
            min_dot_size=2.0 * radius,
            dot_size_factor=factor,
            border_width=0,
            sep_factor=separation,
            sep_dark_threshold=threshold,
            show_preview=False,
            seed=seed,
        )
    tool.run(generations=generations, verbose=False)
    particles = np.asarray(tool.particles, dtype=float)
    keep = visible_mask(particles, tool.brightness, tool.config)
    brightness = sample_v(particles[keep], tool.brightness, tool.config)
    radii = (tool.config.max_dot - brightness * tool.config.dot_scale) / 2.0
    return ExternalStipples(particles[keep][:, ::-1].copy(), radii)


def stippler_stipples(
    gray,
    n_points=None,
    rng=None,
    *,
    dot_radius: float = 2.5,
    max_radius=None,
    iterations: int = 10,
    size_jitter: float = 0.0,
    position_jitter: float = 0.0,
) -> ExternalStipples:
    """Stipple a grayscale image with stippler 0.2.1.1 (hand-drawn weighted Voronoi stippling).

    Parameters
    ----------
    gray : array_like, 2-D
        Grays in [0, 1] (0 black, 1 white), each side at least 8 px.
    n_points : int, optional
        Number of dots asked for; default :func:`stipple_count` of ``gray`` and
        ``dot_radius``. 0 gives no dots. stippler may return a few less: its relaxation
        keeps only the points whose Voronoi region closes inside the image.
    rng : None, int or numpy.random.Generator, optional
        Source of the integer seed of stippler's generator (start, size and position jitter).
    dot_radius : float, optional
        Radius (px) of the dot on white, stippler's ``r_min`` (default 2.5: a pen's dot).
    max_radius : float, optional
        Radius (px) of the dot on black, stippler's ``r_max``; default ``dot_radius``.
    iterations : int, optional
        Lloyd iterations (default 10). stippler's "hand-drawn" dial: few iterations leave the
        spacing uneven (its own default is 50).
    size_jitter : float, optional
        stippler's per-dot multiplicative radius noise (default 0).
    position_jitter : float, optional
        stippler's Gaussian position noise, standard deviation in pixels (default 0).

    Returns
    -------
    ExternalStipples
        ``centres`` (n, 2) as ``(row, col)`` and ``radii`` (n,) in pixels.

    Raises
    ------
    ValueError
        ``gray`` not a 2-D finite array in [0, 1] of sides >= 8, white everywhere while dots
        are asked for; bad counts, radii, jitters or ``rng``.
    ImportError
        stippler is not installed.
    """
    array = _check_gray(gray)
    radius = positive_number(dot_radius, "dot_radius")
    largest = radius if max_radius is None else positive_number(max_radius, "max_radius")
    if largest < radius:
        raise ValueError(f"max_radius ({max_radius!r}) must not be below dot_radius ({dot_radius!r})")
    count = _check_count(n_points, array, radius)
    steps = integer_at_least(iterations, "iterations", 0)
    jitter = positive_number(size_jitter, "size_jitter", allow_zero=True)
    shake = positive_number(position_jitter, "position_jitter", allow_zero=True)
    seed = _seed(rng)
    if count == 0:
        return _empty()
    stippler = _import("stippler", STIPPLER_VERSION)

    height, width = array.shape
    zoom = max(1, int(round(math.sqrt(count * _STIPPLER_PIXELS_PER_REGION / (height * width)))))
    darkness = 1.0 - array
    density = np.maximum(darkness / darkness.max(), _STIPPLER_DENSITY_FLOOR)
    density = np.repeat(np.repeat(density, zoom, axis=0), zoom, axis=1)
    density_p = density.cumsum(axis=1)
    density_q = density_p.cumsum(axis=1)
    generator = np.random.default_rng(seed)
    points = stippler.initialization(count, density, generator)
    points = stippler.relax(points, density, density_p, density_q, n_iter=steps)
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    radii = stippler.assign_radii(points, density, radius, largest, jitter, generator)
    points = stippler.apply_position_jitter(points, shake * zoom, generator)
    # stippler's centroids put density pixel k at coordinate k; the original pixel i spans the
    # density pixels i*zoom .. i*zoom + zoom - 1, centred on i*zoom + (zoom - 1) / 2.
    centres = (points[:, ::-1] - (zoom - 1) / 2.0) / zoom
    return ExternalStipples(np.asarray(centres, dtype=float), np.asarray(radii, dtype=float))


def rasterize_stipples(centres, radii, shape) -> np.ndarray:
    """Draw dots as filled discs into a bitonal image (:func:`skimage.draw.disk`).

    Parameters
    ----------
    centres : array_like, shape (n, 2)
        ``(row, col)`` of the dot centres (pixel-index coordinates); n may be 0. Centres may
        lie outside the image: only the part of a disc inside it is drawn.
    radii : float or array_like, shape (n,)
        Dot radii in pixels, positive.
    shape : tuple of int
        ``(height, width)`` of the image, both >= 1.

    Returns
    -------
    numpy.ndarray of bool, shape ``shape``
        ``True`` = ink: the pixels whose centre lies strictly inside a disc.

    Raises
    ------
    ValueError
        Centres not (n, 2) finite numbers, radii not positive finite or of another length,
        a bad shape.
    """
    try:
        dims = tuple(shape)
    except TypeError:
        raise ValueError(f"shape must be a (height, width) pair of positive integers, got {shape!r}") from None
    if len(dims) != 2 or any(isinstance(d, bool) or not isinstance(d, Integral) or d < 1 for d in dims):
        raise ValueError(f"shape must be a (height, width) pair of positive integers, got {shape!r}")
    points = np.asarray(centres, dtype=float)
    if points.size == 0:
        points = points.reshape(0, 2)
    if points.ndim != 2 or points.shape[1] != 2:
        raise ValueError(f"centres must have shape (n, 2) as (row, col), got {np.shape(centres)}")
    if not np.all(np.isfinite(points)):
        raise ValueError("centres hold NaN or infinite coordinates")
    sizes = np.asarray(radii, dtype=float)
    if sizes.ndim == 0:
        sizes = np.full(len(points), float(sizes))
    if sizes.shape != (len(points),):
        raise ValueError(f"radii must be a number or hold one radius per centre ({len(points)}), got shape {sizes.shape}")
    if not np.all(np.isfinite(sizes)) or np.any(sizes <= 0):
        raise ValueError("radii must be positive finite numbers")
    image = np.zeros(dims, dtype=bool)
    for (row, col), size in zip(points, sizes):
        rr, cc = disk((row, col), size, shape=dims)
        image[rr, cc] = True
    return image
