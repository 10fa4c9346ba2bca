"""Synthetic, hand-drawn-like stipple tone textures and tone-map sheets (Kim 2009's exemplars).

Kim et al. (2009) learn from artists' stipple drawings (William M. Andrews' tone maps, Emily S.
Damstra's blastoid shell) that we cannot ship. These seeded generators make SYNTHETIC stand-ins
with the features the paper relies on, and return the truth that made them:

======================================  ====================================================
generator                               what it makes (paper)
======================================  ====================================================
:func:`stipple_tone_texture`            one bitonal tone texture: separate dots (light),
                                        merged blobs (merged) or white dots on black (dark),
                                        section 3.2 and Figure 3
:func:`stipple_tone_sheet`              a strip of tone patches of increasing darkness with
                                        dithered transitions, section 3.1 and Figure 4
:func:`andrews_like_tones`              tones 1-8 calibrated to the paper's reported geometry
                                        (section 3.5) and level split (section 3.2)
======================================  ====================================================

Conventions
-----------
*Images.* Boolean arrays, ``True`` = ink (black), rows first. A *tone* is the requested ink
fraction, 0 (white) .. 1 (black); the paper's gray level is ``1 - tone``.

*Marks.* A mark is an ellipse drawn with :func:`skimage.draw.ellipse` around an integer pixel
centre, with semi-axes ``r (1 + e)`` and ``r (1 - e)``, ``r`` uniform in
``[0.6, 1.4] * mark_radius``, eccentricity ``e`` uniform in ``[0, 0.35]`` and a uniform
orientation; with probability 0.3 a smaller ellipse (0.5-0.7 r) is attached at 0.6 r from the
centre, giving the comma-like blobs of a pen. Marks are clipped at the image border.

*Placement.* Centres come from hard-core dart throwing on the pixel grid: the pixels are visited
in a random order and a pixel becomes a centre only if it lies at distance >= ``min_distance``
from every earlier centre (exact, since centres are integer pixels); marks are added until the
ink count reaches ``round(tone * n_pixels)``, so the realised ink fraction exceeds the request by
less than one mark (about 30 px of 65 536 at the defaults). The hard-core distance is
``HARD_CORE = 0.7`` times the mean spacing ``sqrt(n_pixels / m)`` of the ``m`` marks of area
``pi * mark_radius**2`` that a Boolean model needs to cover the ink fraction
(``m = -n_pixels log(1 - ink) / area``): artists space their dots evenly, and the hard core
keeps the local tone steady (block averages vary far less than under Poisson placement). The
regimes, after section 3.2:

- ``"light"`` (``tone <= light_max``): the hard core is at least one mark diameter
  ``2 * mark_radius``, and a mark is also rejected when one of its pixels is ink or 8-adjacent
  to earlier ink, so dots stay separate 8-connected components, as the paper's light levels
  assume;
- ``"merged"`` (``light_max < tone < 1 - light_max``): the spacing rule alone; dots overlap into
  blobs (the paper's tones 5-6);
- ``"dark"`` (``tone >= 1 - light_max``): the light generator run for the white fraction
  ``1 - tone`` and inverted: separate white dots on black (tones 7-8);
- ``"white"`` / ``"black"`` for tones 0 and 1 exactly.

If a texture jams (every free pixel tried) before reaching its tone, which needs ``light_max`` or
``mark_radius`` well above the defaults, the throwing continues without the separation test and
the truth says ``jammed=True``; if even the hard core jams, a last pass drops it, so the
requested tone is always reached.

*Randomness.* ``rng`` is ``None``, an ``int`` seed or a :class:`numpy.random.Generator`; a seed
fixes the output bit for bit.

Written by hand: no library generates stipple drawings; drawing uses :mod:`skimage.draw`.

References
----------
Kim, S., Maciejewski, R., Isenberg, T., Andrews, W. M., Chen, W., Sousa, M. C., Ebert, D. S.
(2009). Stippling by example. NPAR, sections 3.1 (tone maps, Figure 4: "the artist will
naturally dither the edges between two adjacent tones") and 3.2 (light, merged and dark levels).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from paperlib._checks import as_generator, budget, check_budget, check_flag, positive_number

__all__ = ["andrews_like_tones", "stipple_tone_sheet", "stipple_tone_texture"]

#: Default upper tone of the light regime (and 1 - lower tone of the dark one).
LIGHT_MAX = 0.3
#: Smallest texture side accepted, in pixels.
MIN_SIZE = 16
#: Default budget of the generators here (``max_pixels``): pixels drawn by one call, 2**23 (~8.4 M, about
#: ten seconds); the paper's sizes (a 256 x 256 texture, eight of them in a sheet) use 2**16 to 2**19.
MAX_PIXELS = 2**23
#: Hard-core distance as a fraction of the mean spacing between marks (random sequential
#: adsorption jams near 0.83, so 0.7 stays reachable while making the placement regular).
HARD_CORE = 0.7
#: Largest hard-core fraction accepted (random sequential adsorption jams near 0.83).
MAX_HARD_CORE = 0.8
#: Probability that a mark gets an attached second lobe.
LOBE_PROBABILITY = 0.3


# ============================================================================ checks


def _check_tone(tone) -> float:
    try:
        value = float(tone)
    except (TypeError, ValueError):
        raise ValueError(f"tone must be a number in [0, 1], got {tone!r}") from None
    if not (0.0 <= value <= 1.0):
        raise ValueError(f"tone must be in [0, 1] (0 white .. 1 black), got {tone!r}")
    return value


def _check_hard_core(hard_core):
    """A fraction in [0, MAX_HARD_CORE], or an increasing (low, high) pair of them."""
    pair = isinstance(hard_core, (tuple, list, np.ndarray))
    values = [positive_number(value, "hard_core", allow_zero=True) for value in (hard_core if pair else [hard_core])]
    if len(values) != (2 if pair else 1) or max(values) > MAX_HARD_CORE or (pair and values[0] > values[1]):
        raise ValueError(
            f"hard_core must be a fraction in [0, {MAX_HARD_CORE}] (dart throwing jams near 0.83) or an increasing "
            f"(low, high) pair of them, got {hard_core!r}"
        )
    return tuple(values) if pair else values[0]


def _check_pixels(pixels: int, max_pixels) -> None:
    check_budget(pixels, budget(max_pixels, "max_pixels"), "max_pixels", "pixels")


def _check_mark_radius(mark_radius, side: int, side_name: str) -> float:
    """A mark radius of at least 1 pixel whose mark fits in a texture of ``side`` pixels (named ``side_name``)."""
    mark_radius = positive_number(mark_radius, "mark_radius")
    if not 1.0 <= mark_radius <= side / 2:
        raise ValueError(f"mark_radius must be between 1 pixel and half the {side_name} ({side / 2:g} px), "
                         f"got {mark_radius!r}")
    return mark_radius


def _check_size(size, name: str, minimum: int) -> int:
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)):
        raise ValueError(f"{name} must be an integer, got {size!r}")
    if size < minimum:
        raise ValueError(f"{name} must be at least {minimum} pixels, got {size}")
    return int(size)


# ============================================================================ marks


@numba.njit(cache=True)
def _inside_ellipse(top, left, bottom, right, center_r, center_c, r_radius, c_radius, sin_alpha, cos_alpha):
    """Pixels of the box [top, bottom] x [left, right] strictly inside the ellipse, row-major."""
    rows = np.empty((bottom - top + 1) * (right - left + 1), dtype=np.int64)
    cols = np.empty_like(rows)
    count = 0
    shifted_r, shifted_c = center_r - top, center_c - left
    for i in range(bottom - top + 1):
        r = float(i) - shifted_r
        for j in range(right - left + 1):
            c = float(j) - shifted_c
            along = (r * cos_alpha + c * sin_alpha) / r_radius
            across = (r * sin_alpha - c * cos_alpha) / c_radius
            if along * along + across * across < 1:
                rows[count], cols[count] = top + i, left + j
                count += 1
    return rows[:count], cols[:count]


def _ellipse(center, r_radius, c_radius, shape, rotation=0.0):
    """``skimage.draw.ellipse(*center, r_radius, c_radius, shape=shape, rotation=rotation)``.

    The same pixels in the same order (the tests compare them), without its per-call array
    overhead: the generator draws tens of thousands of small marks.
    """
    rotation %= math.pi
    sin_alpha, cos_alpha = float(np.sin(rotation)), float(np.cos(rotation))
    r_extent = abs(r_radius * cos_alpha) + c_radius * sin_alpha
    c_extent = r_radius * sin_alpha + abs(c_radius * cos_alpha)
    top, left = max(math.ceil(center[0] - r_extent), 0), max(math.ceil(center[1] - c_extent), 0)
    bottom = min(math.floor(center[0] + r_extent), shape[0] - 1)
    right = min(math.floor(center[1] + c_extent), shape[1] - 1)
    if bottom < top or right < left:
        return np.empty(0, np.int64), np.empty(0, np.int64)
    return _inside_ellipse(top, left, bottom, right, float(center[0]), float(center[1]), float(r_radius),
                           float(c_radius), sin_alpha, cos_alpha)


def _disk(center, radius, shape):
    """``skimage.draw.disk(center, radius, shape=shape)``."""
    return _ellipse(center, radius, radius, shape)


def _mark_pixels(center, axes, angle, lobe, shape):
    """Flat indices (unique) of one mark's pixels: its ellipse plus the optional lobe."""
    rows, cols = _ellipse(center, axes[0], axes[1], shape, rotation=angle)
    if lobe is not None:
        lobe_center, lobe_radius = lobe
        lrows, lcols = _disk(lobe_center, lobe_radius, shape)
        rows, cols = np.concatenate([rows, lrows]), np.concatenate([cols, lcols])
    return np.unique(np.ravel_multi_index((rows, cols), shape))


@numba.njit(cache=True)
def _touches(ink, flat):
    """Whether any 8-neighbour (or the pixel itself) of the pixels ``flat`` is ink."""
    height, width = ink.shape
    for index in flat:
        row, col = index // width, index % width
        for r in range(max(row - 1, 0), min(row + 2, height)):
            for c in range(max(col - 1, 0), min(col + 2, width)):
                if ink[r, c]:
                    return True
    return False


def _random_mark(center, mark_radius: float, rng: np.random.Generator):
    """Semi-axes, orientation and optional lobe ((centre), radius) of one hand-drawn-like mark."""
    radius = mark_radius * rng.uniform(0.6, 1.4)
    eccentricity = rng.uniform(0.0, 0.35)
    angle = rng.uniform(0.0, math.pi)
    axes = (radius * (1 + eccentricity), radius * (1 - eccentricity))
    lobe = None
    if rng.random() < LOBE_PROBABILITY:
        direction = rng.uniform(0.0, 2 * math.pi)
        offset = 0.6 * radius
        lobe_center = (center[0] + offset * math.sin(direction), center[1] + offset * math.cos(direction))
        lobe = (lobe_center, radius * rng.uniform(0.5, 0.7))
    return radius, axes, angle, lobe


# ============================================================================ placement


def _throw_marks(shape, target, mark_radius, min_distance, separate, rng):
    """Dart-throw marks until ``target`` ink pixels; return ink, centres, radii, jammed flag.

    ``min_distance`` is one hard-core distance, or a (low, high) pair: then every mark draws
    its own exclusion distance uniformly in that range, and later centres keep out of it.
    """
    ink = np.zeros(shape, dtype=bool)
    count = 0
    centres, radii, exclusions = [], [], []
    jammed = False
    spread = np.ndim(min_distance) == 1
    # pass 1: the regime's rule; pass 2: hard core only; pass 3: no constraint (always terminates)
    passes = [(True, separate), (True, False), (False, False)]
    for hard, keep_separate in passes:
        forbidden = np.zeros(shape, dtype=bool)
        for centre, exclusion in zip(centres, exclusions):  # the hard core keeps applying to earlier marks
            if hard:
                forbidden[_disk(centre, exclusion, shape)] = True
        for flat in rng.permutation(shape[0] * shape[1]):
            if count >= target:
                return ink, centres, radii, jammed
            row, col = divmod(int(flat), shape[1])
            if forbidden[row, col]:
                continue
            radius, axes, angle, lobe = _random_mark((row, col), mark_radius, rng)
            flat_mark = _mark_pixels((row, col), axes, angle, lobe, shape)
            if keep_separate and _touches(ink, flat_mark):
                forbidden[row, col] = True  # this pixel cannot host a separate mark; do not retry it
                continue
            flat_ink = ink.reshape(-1)
            count += int(np.count_nonzero(~flat_ink[flat_mark]))
            flat_ink[flat_mark] = True
            centres.append((row, col))
            radii.append(radius)
            exclusions.append(rng.uniform(*min_distance) if spread else min_distance)
            if hard and exclusions[-1] > 0:
                forbidden[_disk((row, col), exclusions[-1], shape)] = True
        if count >= target:
            break
        jammed = True
    return ink, centres, radii, jammed


def _min_distance(ink_tone, shape, mark_radius, regime, hard_core=HARD_CORE):
    """Hard-core distance between mark centres: ``hard_core`` times the mean spacing of the
    marks a Boolean model needs for this ink fraction, and at least one mark diameter for
    separate (light and dark) dots; a (low, high) pair of distances when ``hard_core`` is one."""
    if ink_tone <= 0.0:
        return 2.0 * mark_radius
    mark_area = math.pi * mark_radius * mark_radius
    expected_marks = -shape[0] * shape[1] * math.log1p(-min(ink_tone, 0.999)) / mark_area
    if expected_marks <= 0.0:  # a subnormal tone (5e-324) whose count underflows to 0: as for no ink
        return 2.0 * mark_radius
    spacing = math.sqrt(shape[0] * shape[1] / expected_marks)
    floor = 0.0 if regime == "merged" else 2.0 * mark_radius
    if np.ndim(hard_core) == 1:
        return tuple(max(floor, fraction * spacing) for fraction in hard_core)
    return max(floor, hard_core * spacing)


def _regime(tone: float, light_max: float, dark_min: float) -> str:
    if tone == 0.0:
        return "white"
    if tone == 1.0:
        return "black"
    if tone <= light_max:
        return "light"
    if tone >= dark_min:
        return "dark"
    return "merged"


def stipple_tone_texture(tone, size=256, rng=None, *, mark_radius=3.0, light_max=LIGHT_MAX, dark_min=None,
                         hard_core=HARD_CORE, return_truth=False, max_pixels=MAX_PIXELS):
    """Generate one SYNTHETIC hand-drawn-like stipple texture of a given tone.

    Parameters
    ----------
    tone : float
        Requested ink fraction in [0, 1], 0 white .. 1 black.
    size : int, optional
        Side of the square texture in pixels, at least 16 (default 256, the paper's texture size).
    rng : None, int or numpy.random.Generator, optional
        Random source; a seed fixes the output bit for bit.
    mark_radius : float, optional
        Mean mark radius in pixels (default 3: about 28 px per dot, close to the paper's
        ``S_avg = 33.7`` for Andrews' 256 x 256 tones, section 3.5). At least 1.
    light_max : float, optional
        Largest tone of the light regime, in (0, 0.5). Default 0.3.
    dark_min : float, optional
        Smallest tone of the dark regime, in (``light_max``, 1); default ``1 - light_max``.
        Tones strictly between the two are merged.
    hard_core : float or (float, float), optional
        Hard-core distance between mark centres as a fraction of their mean spacing, in
        [0, 0.8] (default 0.7: evenly spaced dots; lower values give a less regular drawing).
        A (low, high) pair gives every mark its own exclusion distance, uniform in that range:
        mostly even spacing with a few closer pairs, like a hand's.
    return_truth : bool, optional
        Also return the generating truth.
    max_pixels : int, optional
        Budget: the most pixels (``size * size``) allowed (default :data:`MAX_PIXELS`, 2**23);
        a larger texture raises ValueError before allocating it.

    Returns
    -------
    image : ndarray of bool, shape (size, size)
        ``True`` = ink. Its ink fraction is ``tone`` plus less than one mark's area.
    truth : dict, only if ``return_truth``
        ``tone`` (requested), ``ink_fraction`` (realised), ``regime`` (``"white"``, ``"light"``,
        ``"merged"``, ``"dark"`` or ``"black"``), ``centres`` (int array (k, 2), rows and
        columns of the marks; white marks in the dark regime), ``radii`` (k mean radii),
        ``min_distance`` (smallest hard-core distance between centres, px), ``jammed`` (bool) and
        ``synthetic`` (always True).

    Raises
    ------
    ValueError
        If ``tone`` is outside [0, 1], ``size`` is not an integer >= 16, ``mark_radius`` is not in
        ``[1, size / 2]``,
        ``light_max`` is outside (0, 0.5), ``dark_min`` is not in (``light_max``, 1) or
        ``hard_core`` is outside [0, 0.8].

    Notes
    -----
    See the module docstring for the marks, the hard-core dart throwing and the regimes.

    References
    ----------
    Kim et al. (2009), Stippling by example, section 3.2 (light, merged and dark levels) and
    Figure 3 (Andrews' tone map).
    """
    tone = _check_tone(tone)
    size = _check_size(size, "size", MIN_SIZE)
    _check_pixels(size * size, max_pixels)
    mark_radius = _check_mark_radius(mark_radius, size, "size")
    light_max = positive_number(light_max, "light_max")
    if light_max >= 0.5:
        raise ValueError(f"light_max must be in (0, 0.5), got {light_max!r}")
    dark_min = 1.0 - light_max if dark_min is None else positive_number(dark_min, "dark_min")
    if not light_max < dark_min < 1.0:
        raise ValueError(f"dark_min must lie in (light_max = {light_max}, 1), got {dark_min!r}")
    hard_core = _check_hard_core(hard_core)
    return_truth = check_flag(return_truth, "return_truth")
    regimes = (light_max, dark_min, hard_core)
    image, truth = _tone_texture(tone, (size, size), as_generator(rng), mark_radius, *regimes)
    return (image, truth) if return_truth else image


def _tone_texture(tone, shape, rng, mark_radius, light_max, dark_min=None, hard_core=HARD_CORE):
    """Validated core of :func:`stipple_tone_texture` for a rectangle ``shape``."""
    regime = _regime(tone, light_max, 1.0 - light_max if dark_min is None else dark_min)
    ink_tone = 1.0 - tone if regime in ("dark", "black") else tone  # dark tones: throw white marks
    min_distance = _min_distance(ink_tone, shape, mark_radius, regime, hard_core)
    target = round(ink_tone * shape[0] * shape[1])
    ink, centres, radii, jammed = _throw_marks(shape, target, mark_radius, min_distance, regime != "merged", rng)
    image = ~ink if regime in ("dark", "black") else ink
    truth = {
        "tone": tone,
        "ink_fraction": float(image.mean()),
        "regime": regime,
        "centres": np.asarray(centres, dtype=np.int64).reshape(-1, 2),
        "radii": np.asarray(radii, dtype=float),
        "min_distance": float(np.min(min_distance)),
        "jammed": bool(jammed),
        "synthetic": True,
    }
    return image, truth


# ============================================================================ a tone map like the paper's

#: Ink fractions of tones 1-8 of :func:`andrews_like_tones` (tone 0 white and 9 black excluded).
ANDREWS_LIKE_INK = (0.025, 0.06, 0.12, 0.2, 0.35, 0.5, 0.7, 0.85)
#: Their generator settings: the pen (S_avg about 34 px), the spread of spacings, and the
#: regimes that give the paper's split (tones 1-4 light, 5-6 merged, 7-8 dark, section 3.2).
ANDREWS_LIKE_SETTINGS = {"mark_radius": 3.3, "hard_core": (0.25, 0.8), "light_max": 0.25, "dark_min": 0.6}


def andrews_like_tones(size=256, rng=None, *, return_truth=False, max_pixels=MAX_PIXELS):
    """Eight SYNTHETIC tone textures calibrated to what the paper reports of Andrews' tone map.

    Kim et al. 2009 give the geometry of one 256 x 256 Andrews tone texture (section 3.5:
    ``O_min = 14.3``, ``O_max = 40.8``, ``O_avg = 29.7``, ``S_avg = 33.7`` px) and the levels of
    his tone map (section 3.2: tones 1-4 light, 5-6 merged, 7-8 dark). These textures follow
    both: tone 1 is drawn with marks of mean radius 3.3 px (S_avg about 34 px) and per-mark
    exclusion distances of 0.25-0.8 mean spacings, which over seeds 0-5 at 256 x 256 gives
    S_avg 34.3, O_min 13.9, O_avg 26.4, O_max 44.6 (within 11% of the paper's; dart throwing
    cannot be as regular as his O_avg / O_max, it jams near 0.83 spacings). The darker tones
    use the same pen at the ink fractions :data:`ANDREWS_LIKE_INK`, an assumption: the paper
    does not give them.

    Parameters
    ----------
    size : int, optional
        Side of every texture (default 256, the paper's), at least 16.
    rng : None, int or numpy.random.Generator, optional
        Random source; a seed fixes the textures bit for bit.
    return_truth : bool, optional
        Also return each texture's truth dict (:func:`stipple_tone_texture`).
    max_pixels : int, optional
        Budget: the most pixels of the eight textures together (default :data:`MAX_PIXELS`).

    Returns
    -------
    list of ndarray of bool, or (list, list of dict)
        Tones 1-8, lightest first, ``True`` = ink.
    """
    size = _check_size(size, "size", MIN_SIZE)
    return_truth = check_flag(return_truth, "return_truth")
    _check_pixels(len(ANDREWS_LIKE_INK) * size * size, max_pixels)
    generator = as_generator(rng)
    made = [stipple_tone_texture(ink, size, generator, return_truth=True, max_pixels=max_pixels,
                                 **ANDREWS_LIKE_SETTINGS)
            for ink in ANDREWS_LIKE_INK]
    textures, truths = [texture for texture, _ in made], [truth for _, truth in made]
    return (textures, truths) if return_truth else textures


# ============================================================================ sheet


def _dither_mask(height, width, cell, rng):
    """True where the darker tone wins in a transition band: cells of ``cell`` px whose
    probability of being dark rises linearly across the band (0 at the left, 1 at the right)."""
    n_rows, n_cols = -(-height // cell), -(-width // cell)
    position = (np.arange(n_cols) + 0.5) / n_cols
    cells = rng.random((n_rows, n_cols)) < position[None, :]
    return np.repeat(np.repeat(cells, cell, axis=0), cell, axis=1)[:height, :width]


def stipple_tone_sheet(n_tones=8, block=256, rng=None, *, transition=32, cell=8, mark_radius=2.0,
                       max_pixels=MAX_PIXELS):
    """A SYNTHETIC tone-map sheet: ``n_tones`` stipple patches of increasing darkness in a row.

    Parameters
    ----------
    n_tones : int, optional
        Number of patches, at least 2 (default 8, the inner tones 1-8 of Andrews' map, Fig. 3).
        Patch ``k`` (0-based) has tone ``(k + 1) / (n_tones + 1)``: evenly spaced, excluding
        pure white and black.
    block : int, optional
        Side of each square patch in pixels (default 256). At least ``max(16, 2 * transition)``.
    rng : None, int or numpy.random.Generator, optional
        Random source; a seed fixes the sheet bit for bit.
    transition : int, optional
        Width in pixels of the dithered band centred on each boundary between patches
        (default 32; 0 gives hard edges). Must be even.
    cell : int, optional
        Side of the dithering cells in pixels (default 8, a few dots wide).
    mark_radius : float, optional
        Mean mark radius (default 2, smaller than a single texture's 3): a sheet stands for a
        whole drawing cut into N = 30-32 px blocks (Fig. 4), and smaller dots make each block's
        average steady (standard deviation about 0.02 in ink at N = 32).
    max_pixels : int, optional
        Budget: the most pixels of the sheet, ``n_tones * block**2`` (default :data:`MAX_PIXELS`).

    Returns
    -------
    image : ndarray of bool, shape (block, n_tones * block)
        ``True`` = ink.
    truth : dict
        ``tones`` (n requested tones), ``patches`` (n rectangles ``(row0, col0, row1, col1)``,
        end-exclusive, each patch's full extent), ``cores`` (the same rectangles without the
        dithered bands: pure single-tone texture), ``transition``, ``cell``, ``textures``
        (each patch texture's truth dict from :func:`stipple_tone_texture`) and ``synthetic``.

    Raises
    ------
    ValueError
        If ``n_tones`` < 2, ``block`` is too small, ``transition`` / ``cell`` are invalid, or
        ``mark_radius`` is not in ``[1, block / 2]``.

    Notes
    -----
    Each patch texture is generated ``transition / 2`` pixels wider on each inner side. Within a
    band of ``transition`` columns centred on the boundary between patches k and k + 1, the
    sheet is tiled by ``cell x cell`` cells, and each cell shows patch k + 1's texture with a
    probability rising linearly across the band (patch k's otherwise). The marks of both tones
    thus interleave in cell-sized clumps, an imitation of the artist's dithering (section 3.1).

    References
    ----------
    Kim et al. (2009), Stippling by example, section 3.1 and Figures 3 and 4.
    """
    n_tones = _check_size(n_tones, "n_tones", 2)
    transition = _check_size(transition, "transition", 0)
    if transition % 2:
        raise ValueError(f"transition must be even, got {transition}")
    block = _check_size(block, "block", max(MIN_SIZE, 2 * transition))
    _check_pixels(n_tones * block * block, max_pixels)
    cell = _check_size(cell, "cell", 1)
    mark_radius = _check_mark_radius(mark_radius, block, "block")
    rng = as_generator(rng)

    half = transition // 2
    tones = [(k + 1) / (n_tones + 1) for k in range(n_tones)]
    image = np.zeros((block, n_tones * block), dtype=bool)
    textures = []
    padded = []  # (texture, first sheet column it covers)
    for k, tone in enumerate(tones):
        left = half if k > 0 else 0
        right = half if k < n_tones - 1 else 0
        width = block + left + right
        texture, texture_truth = _tone_texture(tone, (block, width), rng, mark_radius, LIGHT_MAX)
        padded.append((texture, k * block - left))
        textures.append(texture_truth)
        image[:, k * block : (k + 1) * block] = texture[:, left : left + block]

    for k in range(n_tones - 1):
        if transition == 0:
            continue
        start = (k + 1) * block - half
        light, light_start = padded[k]
        dark, dark_start = padded[k + 1]
        band_light = light[:, start - light_start : start - light_start + transition]
        band_dark = dark[:, start - dark_start : start - dark_start + transition]
        image[:, start : start + transition] = np.where(_dither_mask(block, transition, cell, rng), band_dark, band_light)

    patches = [(0, k * block, block, (k + 1) * block) for k in range(n_tones)]
    cores = [
        (0, k * block + (half if k > 0 else 0), block, (k + 1) * block - (half if k < n_tones - 1 else 0))
        for k in range(n_tones)
    ]
    truth = {
        "tones": tones,
        "patches": patches,
        "cores": cores,
        "transition": transition,
        "cell": cell,
        "textures": textures,
        "synthetic": True,
    }
    return image, truth
