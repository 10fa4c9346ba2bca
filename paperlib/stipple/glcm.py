"""GLCM statistics of bitonal stipple textures (Kim et al. 2009, sections 3.3 and 3.4.1).

A stipple distribution texture is a 2-D boolean array, ``True`` (level 1) = ink / black,
``False`` (level 0) = paper / white. For an ``n x n`` texture the paper computes ``3 (n - 1)``
2x2 grey-level co-occurrence matrices (GLCMs): horizontal, vertical and left-down diagonal
displacements of length ``1 .. n - 1`` (section 3.3.2), describes each by contrast, energy and
correlation (eqs. 2-4) and compares two textures by the average co-occurrence error ACE
(eq. 5), which the synthesis (section 3.4) minimises by spin flips.

Conventions (see ``notes/glcm_conventions.md``; angles re-measured on scikit-image 0.26):

- Counts follow eq. (1) literally: ``L_d[i, j]`` counts the pixels ``p`` with ``I[p] = i`` and
  ``I[p + d] = j`` where both pixels lie inside the texture (not periodic, not symmetric), i.e.
  ``skimage.feature.graycomatrix(..., levels=2, symmetric=False)``. In ``graycomatrix`` the
  pair is ``(p, p + (round(d sin a), round(d cos a)))`` in (row, column), rows growing
  downwards: angle 0 is our horizontal ``(0, k)``, ``pi/2`` our vertical ``(k, 0)`` and
  ``3 pi/4`` with distance ``k sqrt(2)`` our left-down diagonal ``(k, -k)``, matrix for matrix
  (the tests check this; the note's "pi/2 looks up" does not hold in 0.26, but as it says,
  reversing an offset only transposes the matrix, which leaves contrast, energy, correlation
  and ACE unchanged).
- The paper's "energy" (eq. 3) is the sum of squared entries: skimage's ``'ASM'``, not its
  ``'energy'`` (the square root).
- Correlation (eq. 4) is undefined when a marginal of the GLCM has zero variance (e.g. an
  all-white texture). We return 1 there, as ``graycoprops`` does, so that our statistics agree
  with scikit-image's everywhere; ACE does not use correlation and is unaffected.

Written by hand, with scikit-image as the oracle of the tests: ``graycomatrix`` takes offsets
as rounded polar (distance, angle) pairs and recomputes every matrix from scratch, whereas the
synthesis needs exact integer ``(dy, dx)`` offsets and counts it can update in O(offsets)
per pixel flip (:func:`flip_update` / :func:`flip_update_kernel`) and ACE changes it can
evaluate before deciding to flip (:func:`ace_change_kernel`). The kernels live here rather than
in a ``_kernels.py`` because they are the module's subject; their reference is the vectorised
recount :func:`cooccurrence_counts`, itself checked against ``graycomatrix``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from numba.extending import overload

from paperlib._checks import budget, check_budget, finite_array, positive_number

__all__ = [
    "GLCMFeatures",
    "ace",
    "ace_change_by_group_kernel",
    "ace_change_kernel",
    "offset_directions",
    "check_bitonal",
    "cooccurrence_counts",
    "flip_update",
    "flip_update_kernel",
    "glcm_features",
    "normalized_glcms",
    "paper_offsets",
    "pair_totals",
    "to_bitonal",
]

# --------------------------------------------------------------------------------------------
# bitonal images


def _as_2d_array(image, name: str) -> np.ndarray:
    """``image`` as a non-empty 2-D array (any dtype), or a ValueError saying what is wrong."""
    try:
        array = np.asarray(image)
    except (TypeError, ValueError) as error:  # ragged nested lists
        raise ValueError(f"{name} cannot be read as an array: {error}") from None
    if array.ndim != 2:
        raise ValueError(
            f"{name} must be a 2-D (grayscale) array, got shape {array.shape}; "
            "convert colour images first, e.g. with skimage.color.rgb2gray"
        )
    if array.size == 0:
        raise ValueError(f"{name} is empty (shape {array.shape})")
    return array


def to_bitonal(image, threshold: float = 0.5) -> np.ndarray:
    """Threshold a grayscale image into a bitonal texture, ``True`` = ink (dark).

    Parameters
    ----------
    image : array_like, 2-D
        Float image with values in [0, 1] (0 = black) or ``uint8`` image with values in
        0..255. Other dtypes are refused: convert them with ``skimage.util.img_as_float``.
    threshold : float, optional
        In [0, 1], on the float scale (multiplied by 255 for ``uint8`` images). Pixels strictly
        darker than the threshold become ink.

    Returns
    -------
    numpy.ndarray of bool
        Same shape as ``image``; ``True`` where ``image < threshold``.

    Raises
    ------
    ValueError
        Empty or non-2-D image, unsupported dtype (bool, complex, object, integers other than
        ``uint8``), NaN or infinite values, float values outside [0, 1], threshold outside [0, 1].

    References
    ----------
    Kim et al. 2009, section 3.3.2: the textures compared by GLCMs are bitonal.
    """
    array = _as_2d_array(image, "image")
    level = positive_number(threshold, "threshold", allow_zero=True)
    if level > 1:
        raise ValueError(f"threshold must lie in [0, 1] (float gray scale), got {threshold!r}")
    if array.dtype == np.uint8:
        return array < level * 255.0
    if array.dtype == np.bool_:
        raise ValueError("image is already boolean (bitonal): use check_bitonal(image) instead of to_bitonal")
    if array.dtype.kind != "f":
        raise ValueError(
            f"image must be a float image in [0, 1] or a uint8 image in 0..255, got dtype {array.dtype}; "
            "convert it with skimage.util.img_as_float"
        )
    if not np.all(np.isfinite(array)):
        raise ValueError("image contains NaN or infinite values")
    low, high = float(array.min()), float(array.max())
    if low < 0 or high > 1:
        raise ValueError(
            f"float image values must lie in [0, 1], got [{low}, {high}]; rescale it (e.g. "
            "skimage.exposure.rescale_intensity(image, out_range=(0, 1)))"
        )
    return array < level


def check_bitonal(image) -> np.ndarray:
    """Check that ``image`` is a bitonal texture and return it as a C-contiguous bool array.

    Parameters
    ----------
    image : array_like, 2-D
        Boolean array, or integer array whose values are all 0 or 1 (1 = ink).

    Returns
    -------
    numpy.ndarray of bool
        ``True`` = ink. No copy when ``image`` is already a C-contiguous boolean array.

    Raises
    ------
    ValueError
        Empty or non-2-D input, a dtype that is neither boolean nor integer, or integer values
        other than 0 and 1. Grayscale images must go through :func:`to_bitonal` first.

    References
    ----------
    Kim et al. 2009, section 3.3.2 ("the input textures are bitonal images").
    """
    return _checked_bitonal(image, "image")


def _checked_bitonal(image, name: str) -> np.ndarray:
    """:func:`check_bitonal` with the messages naming the caller's parameter ``name``."""
    array = _as_2d_array(image, name)
    hint = "threshold it first with paperlib.stipple.glcm.to_bitonal(image, threshold)"
    if array.dtype == np.bool_:
        return np.ascontiguousarray(array)
    if array.dtype.kind not in "iu":
        raise ValueError(f"{name} must be boolean or integer 0/1, got dtype {array.dtype}; {hint}")
    if not np.all((array == 0) | (array == 1)):
        found = np.unique(array)[:6].tolist()
        raise ValueError(f"{name} is not bitonal: values {found}... besides 0 and 1; {hint}")
    return np.ascontiguousarray(array != 0)


# --------------------------------------------------------------------------------------------
# offsets and counts


#: Default budget of :func:`paper_offsets` (``max_n``): the largest texture side, 2**16 (the paper's is 256).
MAX_TEXTURE_SIDE = 2**16


def paper_offsets(n: int, *, max_n: int = MAX_TEXTURE_SIDE) -> np.ndarray:
    """The ``3 (n - 1)`` displacement vectors of Kim et al. for an ``n x n`` texture.

    Parameters
    ----------
    n : int
        Side of the texture, >= 2. For a rectangular texture use its shorter side.
    max_n : int, optional
        Budget: the largest ``n`` allowed (default :data:`MAX_TEXTURE_SIDE`, 2**16).

    Returns
    -------
    numpy.ndarray of int64, shape (3 (n - 1), 2)
        Rows ``(dy, dx)`` (rows down, columns right) in three blocks of ``n - 1``: horizontal
        ``(0, k)``, vertical ``(k, 0)`` and left-down diagonal ``(k, -k)``, each for
        ``k = 1 .. n - 1``. Row ``b (n - 1) + k - 1`` is block ``b``, length ``k``.

    References
    ----------
    Kim et al. 2009, section 3.3.2: horizontal (0 deg), vertical (90 deg) and left-down
    diagonal (45 deg) offsets, ``3 x (n - 1)`` GLCMs per ``n x n`` texture.
    """
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)):
        raise ValueError(f"n must be an integer texture side, got {n!r}")
    if n < 2:
        raise ValueError(f"n must be >= 2 (offsets 1 .. n-1), got {n}")
    check_budget(int(n), budget(max_n, "max_n"), "max_n", "pixels of texture side (n)")
    lengths = np.arange(1, n, dtype=np.int64)
    zeros = np.zeros_like(lengths)
    horizontal = np.column_stack([zeros, lengths])
    vertical = np.column_stack([lengths, zeros])
    left_down = np.column_stack([lengths, -lengths])
    return np.concatenate([horizontal, vertical, left_down])


def offset_directions(offsets) -> np.ndarray:
    """Direction index of every offset: offsets along the same ray share one (0, 1, ...).

    For :func:`paper_offsets` the three blocks (horizontal, vertical, left-down diagonal) get
    0, 1 and 2. Used by the per-direction acceptance rule of the synthesis (section 3.4.1).

    Parameters
    ----------
    offsets : array_like of int, shape (k, 2)
        Displacement vectors ``(dy, dx)``, none zero.

    Returns
    -------
    ndarray of int64, shape (k,)
        Direction index of each offset, numbered 0, 1, ... in order of first appearance.

    Raises
    ------
    ValueError
        Offsets that are not a non-empty (k, 2) integer array, or a zero offset.
    """
    array = np.asarray(offsets)
    if array.ndim != 2 or array.shape[1] != 2 or array.shape[0] == 0 or array.dtype.kind not in "iu":
        raise ValueError(f"offsets must be a non-empty (k, 2) integer array of (dy, dx), got shape {array.shape}")
    array = array.astype(np.int64)
    steps = np.gcd(array[:, 0], array[:, 1])
    if np.any(steps == 0):
        raise ValueError("offset (0, 0) pairs a pixel with itself; every offset must be non-zero")
    _, first_seen, index = np.unique(array // steps[:, None], axis=0, return_index=True, return_inverse=True)
    # number the directions in order of first appearance, not lexicographically
    rank = np.empty(len(first_seen), dtype=np.int64)
    rank[np.argsort(first_seen)] = np.arange(len(first_seen))
    return rank[index.ravel()]


def _check_offsets(offsets, shape: tuple[int, int]) -> np.ndarray:
    """``offsets`` as a C-contiguous (k, 2) int64 array fitting ``shape``, or a ValueError."""
    array = np.asarray(offsets)
    if array.ndim != 2 or array.shape[1] != 2 or array.shape[0] == 0:
        raise ValueError(f"offsets must be a non-empty (k, 2) array of (dy, dx), got shape {array.shape}")
    if array.dtype.kind not in "iu":
        raise ValueError(f"offsets must be integers (pixel steps), got dtype {array.dtype}")
    array = np.ascontiguousarray(array, dtype=np.int64)
    if np.any(np.all(array == 0, axis=1)):
        raise ValueError("offset (0, 0) pairs a pixel with itself; every offset must be non-zero")
    height, width = shape
    too_long = (np.abs(array[:, 0]) >= height) | (np.abs(array[:, 1]) >= width)
    if np.any(too_long):
        dy, dx = array[np.argmax(too_long)]
        raise ValueError(
            f"texture of shape {shape} is smaller than offset ({dy}, {dx}): no pixel pair fits; "
            f"use paper_offsets(min(texture.shape)) or a larger texture"
        )
    return array


def _pair_windows(shape: tuple[int, int], dy: int, dx: int) -> tuple[tuple[slice, slice], tuple[slice, slice]]:
    """Slices of the first pixels ``p`` and of their partners ``p + (dy, dx)``, both inside."""
    height, width = shape
    rows = slice(max(0, -dy), height - max(0, dy))
    cols = slice(max(0, -dx), width - max(0, dx))
    shifted_rows = slice(rows.start + dy, rows.stop + dy)
    shifted_cols = slice(cols.start + dx, cols.stop + dx)
    return (rows, cols), (shifted_rows, shifted_cols)


def pair_totals(shape, offsets) -> np.ndarray:
    """Number of (non-periodic) pixel pairs per offset: ``(h - |dy|) (w - |dx|)``.

    It depends only on the shape, so a normalised GLCM is ``counts / pair_totals`` whatever
    pixels the synthesis flips.

    Parameters
    ----------
    shape : (int, int)
        ``(height, width)`` of the texture, pixels.
    offsets : array_like of int, shape (k, 2)
        Displacement vectors ``(dy, dx)`` (non-zero, fitting the texture).

    Returns
    -------
    ndarray of int, shape (k,)
        ``(h - |dy|) (w - |dx|)`` per offset.

    References
    ----------
    Kim et al. 2009, eq. (1) and the normalised GLCM N of eqs. (2)-(4).
    """
    try:
        height, width = (int(side) for side in shape)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"shape must be a (height, width) pair of integers, got {shape!r:.60}") from None
    checked = _check_offsets(offsets, (height, width))
    return (height - np.abs(checked[:, 0])) * (width - np.abs(checked[:, 1]))


def cooccurrence_counts(texture, offsets) -> np.ndarray:
    """Co-occurrence counts of a bitonal texture for every offset (eq. 1), not periodic.

    Parameters
    ----------
    texture : array_like, 2-D
        Bitonal texture (see :func:`check_bitonal`), 1 / ``True`` = ink.
    offsets : array_like of int, shape (k, 2)
        Displacements ``(dy, dx)``, e.g. :func:`paper_offsets`.

    Returns
    -------
    numpy.ndarray of int64, shape (k, 2, 2)
        ``counts[m, i, j]`` = number of pixels ``p`` with ``texture[p] = i`` and
        ``texture[p + offsets[m]] = j``. Pairs whose second pixel falls outside the texture
        are not counted (eq. 1 is defined only where ``I[r + dr, c + dc]`` exists), so
        ``counts[m].sum() == pair_totals(texture.shape, offsets)[m]``.

    Raises
    ------
    ValueError
        Non-bitonal texture, malformed offsets, zero offsets, or a texture smaller than an
        offset.

    References
    ----------
    Kim et al. 2009, section 3.3.1, eq. (1); section 3.3.2 for the 2x2 bitonal case.
    """
    ink = _checked_bitonal(texture, "texture")
    checked = _check_offsets(offsets, ink.shape)
    counts = np.empty((len(checked), 2, 2), dtype=np.int64)
    for m, (dy, dx) in enumerate(checked):
        first_window, second_window = _pair_windows(ink.shape, int(dy), int(dx))
        first, second = ink[first_window], ink[second_window]
        both = np.count_nonzero(first & second)
        first_ink, second_ink = np.count_nonzero(first), np.count_nonzero(second)
        counts[m, 1, 1] = both
        counts[m, 1, 0] = first_ink - both
        counts[m, 0, 1] = second_ink - both
        counts[m, 0, 0] = first.size - first_ink - second_ink + both
    return counts


# --------------------------------------------------------------------------------------------
# statistics and error


@dataclass(frozen=True)
class GLCMFeatures:
    """Normalised GLCMs of one texture and their statistics, one entry per offset.

    Parameters
    ----------
    glcm : numpy.ndarray, shape (k, 2, 2)
        Normalised GLCMs ``N_d`` (each sums to 1).
    contrast, energy, correlation : numpy.ndarray, shape (k,)
        Eqs. (2), (3) and (4) of Kim et al. 2009; correlation is 1 where a marginal of
        ``N_d`` has zero variance (scikit-image's convention).
    """

    glcm: np.ndarray
    contrast: np.ndarray
    energy: np.ndarray
    correlation: np.ndarray


def normalized_glcms(counts) -> np.ndarray:
    """Counts divided by their total per offset: the normalised GLCMs ``N_d`` of eqs. (2)-(5).

    Parameters
    ----------
    counts : array_like of int, shape (k, 2, 2)
        Co-occurrence counts per offset (:func:`cooccurrence_counts`), non-negative, each offset
        with at least one pair.

    Returns
    -------
    ndarray of float64, shape (k, 2, 2)
        ``N_d``: each offset's counts divided by their sum, so each sums to 1.

    Raises
    ------
    ValueError
        ``counts`` not a (k, 2, 2) array of non-negative integers, or an offset without pairs.
    """
    array = np.asarray(counts)
    if array.ndim != 3 or array.shape[1:] != (2, 2) or array.shape[0] == 0:
        raise ValueError(f"counts must be a (k, 2, 2) array (see cooccurrence_counts), got shape {array.shape}")
    if array.dtype.kind not in "iu":
        raise ValueError(f"counts must be integer pair counts, got dtype {array.dtype}")
    if np.any(array < 0):
        raise ValueError("counts must be non-negative")
    totals = array.sum(axis=(1, 2))
    if np.any(totals == 0):
        raise ValueError(f"offset {int(np.argmin(totals))} has no pixel pairs: cannot normalise its GLCM")
    return array / totals[:, None, None].astype(np.float64)


def glcm_features(counts) -> GLCMFeatures:
    """Contrast, energy and correlation of every normalised 2x2 GLCM (eqs. 2-4).

    Parameters
    ----------
    counts : array_like of int, shape (k, 2, 2)
        Output of :func:`cooccurrence_counts`.

    Returns
    -------
    GLCMFeatures
        For the two levels 0 (paper) and 1 (ink), with ``N = N_d``:
        contrast ``= N[0,1] + N[1,0]`` (eq. 2, ``(i - j)^2`` is 1 off the diagonal);
        energy ``= sum N[i,j]^2`` (eq. 3, skimage's ``'ASM'``);
        correlation ``= (N[1,1] - mu_i mu_j) / (sigma_i sigma_j)`` (eq. 4), where
        ``mu_i = N[1,0] + N[1,1]`` and ``mu_j = N[0,1] + N[1,1]`` are the means of the row and
        column marginals and ``sigma^2 = mu (1 - mu)`` their variances. When a variance is
        zero (a marginal concentrated on one level, e.g. a blank texture) the correlation is
        undefined and we return 1, matching ``skimage.feature.graycoprops``.

    References
    ----------
    Kim et al. 2009, section 3.3.1, eqs. (2), (3), (4).
    """
    glcm = normalized_glcms(counts)
    contrast = glcm[:, 0, 1] + glcm[:, 1, 0]
    energy = np.sum(glcm**2, axis=(1, 2))
    mean_first = glcm[:, 1, 0] + glcm[:, 1, 1]
    mean_second = glcm[:, 0, 1] + glcm[:, 1, 1]
    spread = np.sqrt(mean_first * (1 - mean_first) * mean_second * (1 - mean_second))
    covariance = glcm[:, 1, 1] - mean_first * mean_second
    constant = spread < 1e-15  # same cut as graycoprops; a non-zero spread is >= 1 / pair count
    correlation = np.ones_like(spread)
    correlation[~constant] = covariance[~constant] / spread[~constant]
    return GLCMFeatures(glcm=glcm, contrast=contrast, energy=energy, correlation=correlation)


def _glcm_stack(value, name: str) -> np.ndarray:
    """The normalised GLCMs held by a GLCMFeatures or given as a (k, 2, 2) float array."""
    array = value.glcm if isinstance(value, GLCMFeatures) else np.asarray(value)
    hint = "pass glcm_features(counts) or normalized_glcms(counts)"
    if array.ndim != 3 or array.shape[1:] != (2, 2) or array.shape[0] == 0:
        raise ValueError(f"{name} must hold (k, 2, 2) normalised GLCMs, got shape {array.shape}; {hint}")
    if array.dtype.kind != "f" or not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be finite normalised (float) GLCMs; {hint}")
    if not np.allclose(array.sum(axis=(1, 2)), 1.0, atol=1e-9):
        raise ValueError(f"{name} GLCMs do not each sum to 1 (raw counts?); {hint}")
    return array


def ace(features_a, features_b) -> float:
    """Average co-occurrence error between two textures' normalised GLCMs (eq. 5).

    ``ACE = (1 / T_NGLC) sum_d sum_{i,j} |N_a,d[i, j] - N_b,d[i, j]|`` with ``T_NGLC`` the number
    of displacement offsets ``d``; it lies in [0, 2].

    Parameters
    ----------
    features_a, features_b : GLCMFeatures or array_like, shape (k, 2, 2)
        Normalised GLCMs of the example and synthesized textures for the same k offsets.

    Returns
    -------
    float
        The ACE, in [0, 2]; 0 for identical GLCMs.

    Raises
    ------
    ValueError
        Arrays that are not normalised (k, 2, 2) GLCMs, or different numbers of offsets.

    References
    ----------
    Kim et al. 2009, section 3.4.1, eq. (5) (after Copeland et al. 2001).
    """
    first = _glcm_stack(features_a, "features_a")
    second = _glcm_stack(features_b, "features_b")
    if first.shape != second.shape:
        raise ValueError(f"GLCM stacks differ in number of offsets: {first.shape[0]} vs {second.shape[0]}")
    return float(np.abs(first - second).sum() / first.shape[0])


# --------------------------------------------------------------------------------------------
# incremental update for spin-flip synthesis


@numba.njit(cache=True)
def _flip_update_kernel(texture, counts, y, x, offsets):
    """The numba body of :func:`flip_update_kernel` (its precondition): no checks."""
    height, width = texture.shape
    old = 1 if texture[y, x] != 0 else 0
    new = 1 - old
    for m in range(offsets.shape[0]):
        dy, dx = offsets[m, 0], offsets[m, 1]
        # pair (p - o, p): p is the second pixel, so the GLCM column j moves
        py, px = y - dy, x - dx
        if 0 <= py < height and 0 <= px < width:
            first = 1 if texture[py, px] != 0 else 0
            counts[m, first, old] -= 1
            counts[m, first, new] += 1
        # pair (p, p + o): p is the first pixel, so the GLCM row i moves
        qy, qx = y + dy, x + dx
        if 0 <= qy < height and 0 <= qx < width:
            second = 1 if texture[qy, qx] != 0 else 0
            counts[m, old, second] -= 1
            counts[m, new, second] += 1
    texture[y, x] = new


@numba.njit(cache=True)
def _offset_error_change(texture, counts, y, x, m, dy, dx, target, total):
    """Change of ``sum_ij |count - target * total|`` of offset ``m`` if ``texture[y, x]`` flipped.

    In count units (divide by ``total`` for the normalised GLCM's share of eq. 5). Written
    without data-dependent branches (the ink around p is random, so an ``if delta != 0`` per
    entry mispredicts often): all four entries are evaluated, and one the flip leaves alone
    contributes |r| - |r| = 0.0 exactly. Measured on a 256 x 256 texture, 765 offsets: 9.5 ->
    5.6 us per ACE change, and the same value as the per-entry normalised form to ~1e-18.
    """
    height, width = texture.shape
    sign = -1 if texture[y, x] != 0 else 1  # a flip 0 -> 1 moves pairs towards level 1
    # one-hot level of the pixel before p (first_*) and after p (second_*) along this offset;
    # both zero when that pixel lies outside the texture (no pair)
    first_0 = first_1 = second_0 = second_1 = 0
    py, px = y - dy, x - dx
    if 0 <= py < height and 0 <= px < width:
        first_1 = 1 if texture[py, px] != 0 else 0
        first_0 = 1 - first_1
    qy, qx = y + dy, x + dx
    if 0 <= qy < height and 0 <= qx < width:
        second_1 = 1 if texture[qy, qx] != 0 else 0
        second_0 = 1 - second_1
    # for a flip 0 -> 1 the pair (p - o, p) moves from (f, 0) to (f, 1) and the pair
    # (p, p + o) from (0, s) to (1, s); a flip 1 -> 0 moves them back (sign = -1)
    delta_00 = -sign * (first_0 + second_0)
    delta_01 = sign * (first_0 - second_1)
    delta_10 = sign * (second_0 - first_1)
    delta_11 = sign * (first_1 + second_1)
    residual_00 = counts[m, 0, 0] - target[m, 0, 0] * total
    residual_01 = counts[m, 0, 1] - target[m, 0, 1] * total
    residual_10 = counts[m, 1, 0] - target[m, 1, 0] * total
    residual_11 = counts[m, 1, 1] - target[m, 1, 1] * total
    term = (abs(residual_00 + delta_00) - abs(residual_00)) + (abs(residual_01 + delta_01) - abs(residual_01))
    return term + (abs(residual_10 + delta_10) - abs(residual_10)) + (abs(residual_11 + delta_11) - abs(residual_11))


@numba.njit(cache=True)
def _ace_change_kernel(texture, counts, y, x, offsets, target, totals):
    """The numba body of :func:`ace_change_kernel`: no checks."""
    change = 0.0
    for m in range(offsets.shape[0]):
        change += _offset_error_change(texture, counts, y, x, m, offsets[m, 0], offsets[m, 1], target, totals[m]) / totals[m]
    return change / offsets.shape[0]


@numba.njit(cache=True)
def ace_change_by_group_kernel(texture, counts, y, x, offsets, target, totals, groups, changes):
    """Like :func:`ace_change_kernel`, but summed per group of offsets into ``changes``; no checks.

    ``groups[m]`` (int64, ``0 <= groups[m] < len(changes)``) names the group of offset ``m``,
    e.g. its direction; ``changes[g]`` receives group ``g``'s share of the ACE change (each
    offset weighted ``1 / len(offsets)`` as in eq. 5, so the groups sum to the ACE change).
    Serves the paper's acceptance rule, a flip kept only if the error drops "for all
    displacement offset vectors" (Kim et al. 2009, 3.4.1).
    """
    changes[:] = 0.0
    for m in range(offsets.shape[0]):
        term = _offset_error_change(texture, counts, y, x, m, offsets[m, 0], offsets[m, 1], target, totals[m])
        changes[groups[m]] += term / totals[m]
    changes /= offsets.shape[0]


def flip_update(texture: np.ndarray, counts: np.ndarray, y: int, x: int, offsets: np.ndarray) -> None:
    """Flip one pixel of a bitonal texture in place and update its co-occurrence counts.

    A flip at ``p`` changes, for each offset ``o``, only the pairs ``(p - o, p)`` and
    ``(p, p + o)`` (when inside the texture), so the update costs O(number of offsets) instead
    of a full recount. This wrapper validates its arguments (O(k), the texture's values are not
    scanned) and calls :func:`flip_update_kernel`, which numba loops may call directly.

    Parameters
    ----------
    texture : numpy.ndarray, 2-D, bool or integer 0/1, writeable
        Modified in place.
    counts : numpy.ndarray of int64, shape (k, 2, 2), writeable
        ``cooccurrence_counts(texture, offsets)`` before the flip; modified in place so that
        it still equals the recount after the flip.
    y, x : int
        Row and column of the pixel to flip.
    offsets : numpy.ndarray of int64, shape (k, 2)
        The offsets ``counts`` was computed for.

    References
    ----------
    Kim et al. 2009, section 3.4.1 (Metropolis spin flips of one random pixel).
    """
    _flip_update_kernel(*_checked_flip(texture, counts, y, x, offsets, writeable=True))


def _checked_flip(texture, counts, y, x, offsets, *, writeable: bool) -> tuple:
    """The arguments of a flip kernel, checked in O(k) (the texture's values are not scanned)."""
    if not isinstance(texture, np.ndarray) or texture.ndim != 2 or texture.dtype.kind not in "biu":
        raise ValueError("texture must be a 2-D bool or integer (0/1) numpy array, modified in place")
    if not isinstance(counts, np.ndarray) or counts.dtype != np.int64 or counts.shape[1:] != (2, 2):
        raise ValueError("counts must be the int64 (k, 2, 2) array returned by cooccurrence_counts")
    if writeable and not (texture.flags.writeable and counts.flags.writeable):
        raise ValueError("texture and counts must be writeable: they are updated in place")
    checked = _check_offsets(offsets, texture.shape)
    if len(checked) != len(counts):
        raise ValueError(f"counts hold {len(counts)} offsets but {len(checked)} offsets were given")
    row, col = _pixel_index(y, "y", texture.shape[0]), _pixel_index(x, "x", texture.shape[1])
    return texture, counts, row, col, checked


def flip_update_kernel(texture, counts, y, x, offsets):
    """Flip ``texture[y, x]`` in place and update ``counts`` in O(len(offsets)); checked only from Python.

    Called from Python, it checks its arguments as :func:`flip_update` does (dtype, rank, shape,
    offsets, pixel index: O(k)) before entering numba. Called inside a numba function, it compiles
    to the kernel itself, without checks: the caller's duty there is the precondition below.

    Precondition inside numba: ``texture`` 2-D bool or 0/1 integers, ``counts`` int64 (k, 2, 2)
    equal to ``cooccurrence_counts(texture, offsets)``, ``offsets`` int64 (k, 2) non-zero and
    fitting the texture, ``0 <= y < h``, ``0 <= x < w``. Any non-zero pixel reads as ink, so
    indices into ``counts`` stay in range whatever the texture holds.

    Parameters
    ----------
    texture : ndarray, 2-D, bool or integer
        The distribution texture, flipped in place at ``(y, x)`` (writeable).
    counts : ndarray of int64, shape (k, 2, 2)
        ``cooccurrence_counts(texture, offsets)``, updated in place.
    y, x : int
        Row and column of the pixel to flip.
    offsets : ndarray of int64, shape (k, 2)
        The displacement vectors ``(dy, dx)`` (non-zero, fitting the texture).
    """
    _flip_update_kernel(*_checked_flip(texture, counts, y, x, offsets, writeable=True))


def ace_change_kernel(texture, counts, y, x, offsets, target, totals):
    """ACE(after flipping ``texture[y, x]``) - ACE(now), without changing anything.

    Lets the spin-flip synthesis reject a flip without applying and undoing it: for each offset
    only the (at most four) entries touched by the pairs ``(p - o, p)`` and ``(p, p + o)`` change,
    so the cost is O(len(offsets)) like :func:`flip_update_kernel`. Called from Python its
    arguments are checked (dtype, rank, shape: O(k)) before entering numba; inside a numba
    function it compiles to the kernel itself, without checks.

    Parameters
    ----------
    texture, counts, y, x, offsets
        As for :func:`flip_update_kernel` (same preconditions).
    target : float64 array, shape (k, 2, 2)
        Normalised GLCMs of the example texture, ``N_t`` of eq. (5).
    totals : float64 array, shape (k,)
        ``pair_totals(texture.shape, offsets)``: the normaliser of ``counts``.

    Returns
    -------
    float
        The change of the ACE the flip would make (negative: the flip brings the texture's GLCMs
        closer to ``target``).

    References
    ----------
    Kim et al. 2009, section 3.4.1, eq. (5).
    """
    texture, counts, row, col, checked = _checked_flip(texture, counts, y, x, offsets, writeable=False)
    k = len(checked)
    target = finite_array(target, "target", shape=(k, 2, 2))
    totals = finite_array(totals, "totals", shape=(k,))
    if (totals <= 0).any():
        raise ValueError("totals must be positive pair counts: pass pair_totals(texture.shape, offsets)")
    return _ace_change_kernel(texture, counts, row, col, checked, target, totals)


@overload(flip_update_kernel)
def _flip_update_kernel_in_numba(texture, counts, y, x, offsets):
    return lambda texture, counts, y, x, offsets: _flip_update_kernel(texture, counts, y, x, offsets)


@overload(ace_change_kernel)
def _ace_change_kernel_in_numba(texture, counts, y, x, offsets, target, totals):
    return lambda texture, counts, y, x, offsets, target, totals: _ace_change_kernel(
        texture, counts, y, x, offsets, target, totals)


def _pixel_index(value, name: str, size: int) -> int:
    """``value`` as an int in [0, size), or a ValueError."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{name} must be an integer pixel index, got {value!r}")
    if not 0 <= value < size:
        raise ValueError(f"{name} = {value} is outside the texture (0 .. {size - 1})")
    return int(value)
