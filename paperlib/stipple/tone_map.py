"""Tone-map extraction from a stipple drawing (Kim et al. 2009, section 3.1).

The drawing is cut into ``N x N`` blocks and each block's average gray level computed; blocks of
similar gray are grouped by an 8-connected component analysis (threshold ``T1``); the regions are
sorted by gray level; evenly spaced tones are kept (threshold ``T2``); and the largest
axis-aligned rectangle inside each kept region is cut out as that tone's example texture.

The paper's tone maps have ten levels (section 3.2, Figure 3): "Tone 0 and 9 are pure white and
black respectively", and tones 1-8 are stipple textures. Only the stipple tones are extracted:
regions of pure paper or solid ink (within ``pure`` of white or black) are the two pure levels,
which need no texture; :attr:`ToneMap.level_grays` lists all levels, pure ones included, as the
rendering of section 4 uses them (:func:`paperlib.stipple.rendering.level_grays`).

The paper gives ``N = 30`` for its Figure 4 and no values for ``T1`` or ``T2``; it says that
"extraction should be somewhat controlled by adjusting the size of a block and the two
thresholds". Our defaults and the reading of the paper's sentences are stated in
:func:`extract_tone_map`.

Written by hand: the region growing (on :func:`skimage.measure.label`) and the largest rectangle
in a mask (the classic histogram-and-stack algorithm, O(pixels)), which no maintained library
offers.

References
----------
Kim, S., Maciejewski, R., Isenberg, T., Andrews, W. M., Chen, W., Sousa, M. C., Ebert, D. S.
(2009). Stippling by example. NPAR, section 3.1 and Figure 4; section 6 (limitations).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import uniform_filter
from skimage.measure import label

from paperlib._checks import finite_array, positive_number

__all__ = ["ToneMap", "block_gray_levels", "extract_tone_map", "largest_rectangle", "segment_blocks"]

#: Paper's block size for Figure 4 (pixels).
DEFAULT_BLOCK_SIZE = 30
#: Rounds of re-centring a region on its mean gray before it is frozen.
_REFINE_ROUNDS = 5


@dataclass(frozen=True, eq=False)
class ToneMap:
    """Example textures extracted from a stipple drawing, lightest first.

    Parameters
    ----------
    gray_levels : ndarray of float, shape (k,)
        Average gray level of each selected region's blocks (1 white .. 0 black), decreasing.
    textures : list of ndarray of bool
        The example textures, ``True`` = ink, cut from the drawing by ``rectangles``.
    rectangles : ndarray of int, shape (k, 4)
        ``(row0, col0, row1, col1)`` of each texture in the drawing, end-exclusive.
    region_ids : ndarray of int, shape (k,)
        Label of each selected region in ``block_labels``.
    block_labels : ndarray of int, shape (rows, cols)
        Region number of every block, from 1 (the paper's Figure 4, middle).
    block_gray : ndarray of float, shape (rows, cols)
        Average gray level of every block.
    block_size : int
        ``N``, the block side in pixels.
    """

    gray_levels: np.ndarray
    textures: list
    rectangles: np.ndarray
    region_ids: np.ndarray
    block_labels: np.ndarray
    block_gray: np.ndarray
    block_size: int

    @property
    def tones(self) -> np.ndarray:
        """Ink fraction of each tone, ``1 - gray_levels`` (0 white .. 1 black), increasing."""
        return 1.0 - self.gray_levels

    @property
    def level_grays(self) -> np.ndarray:
        """Grays of the whole tone map: pure white (tone 0), the extracted tones, pure black.

        ``[1, *gray_levels, 0]``: the paper's 10 levels for 8 extracted tones (section 3.2,
        "Tone 0 and 9 are pure white and black respectively"; Figure 3).
        """
        return np.concatenate([[1.0], self.gray_levels, [0.0]])

    def __len__(self) -> int:
        return len(self.textures)


# ============================================================================ input


def _gray_image(image) -> np.ndarray:
    """The drawing as float gray levels in [0, 1], 1 = white, with clear errors."""
    array = np.asarray(image)
    if array.ndim != 2:
        raise ValueError(f"image must be 2-D, got shape {array.shape}")
    if array.size == 0:
        raise ValueError("image is empty")
    if array.dtype == bool:
        return (~array).astype(float)
    if array.dtype == np.uint8:
        return array / 255.0
    if np.issubdtype(array.dtype, np.floating):
        if not np.isfinite(array).all():
            raise ValueError("image contains NaN or infinite values")
        if array.min() < 0.0 or array.max() > 1.0:
            raise ValueError("float images must hold gray levels in [0, 1] (1 = white)")
        return array.astype(float)
    raise ValueError(
        f"image must be bool (True = ink), uint8 (255 = white) or float in [0, 1] (1 = white), got dtype {array.dtype}"
    )


def _positive_int(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ValueError(f"{name} must be a positive integer, got {value!r}")
    return int(value)


def _pure_margin(value) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"pure must be a number in [0, 0.5), got {value!r}") from None
    if not (0.0 <= number < 0.5):
        raise ValueError(f"pure must be in [0, 0.5), got {value!r}")
    return number


def _threshold(value, name: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number in (0, 1), got {value!r}") from None
    if not (0.0 < number < 1.0):
        raise ValueError(f"{name} must be in (0, 1), got {value!r}")
    return number


# ============================================================================ blocks and regions


def block_gray_levels(image, block_size=DEFAULT_BLOCK_SIZE) -> np.ndarray:
    """Average gray level of each ``N x N`` block of a drawing (Kim 2009, section 3.1).

    Parameters
    ----------
    image : array_like, 2-D
        bool (``True`` = ink), uint8 (255 = white) or float gray levels in [0, 1] (1 = white).
    block_size : int, optional
        ``N`` in pixels (default 30, the paper's Figure 4). Rows and columns beyond the last
        whole block are ignored.

    Returns
    -------
    ndarray of float, shape (rows // N, cols // N)
        Mean gray level per block; for a bitonal drawing, the fraction of white pixels.

    Raises
    ------
    ValueError
        For a non-2-D, empty, NaN or wrongly typed image, or an image smaller than one block.
    """
    gray = _gray_image(image)
    n = _positive_int(block_size, "block_size")
    rows, cols = gray.shape[0] // n, gray.shape[1] // n
    if rows == 0 or cols == 0:
        raise ValueError(f"image of shape {gray.shape} is smaller than one {n} x {n} block")
    return gray[: rows * n, : cols * n].reshape(rows, n, cols, n).mean(axis=(1, 3))


def _seed_order(block_gray: np.ndarray) -> np.ndarray:
    """Blocks from the most to the least homogeneous 3 x 3 neighbourhood (stable)."""
    mean = uniform_filter(block_gray, size=3, mode="nearest")
    variance = uniform_filter(block_gray**2, size=3, mode="nearest") - mean**2
    return np.argsort(variance, axis=None, kind="stable")


def _grow_region(block_gray, free, seed, t1):
    """8-connected blocks around ``seed`` within ``t1`` of the region's mean gray."""
    reference = block_gray[seed]
    region = None
    for _ in range(_REFINE_ROUNDS):
        candidates = free & (np.abs(block_gray - reference) <= t1)
        candidates[seed] = True
        components = label(candidates, connectivity=2)
        grown = components == components[seed]
        if region is not None and np.array_equal(grown, region):
            break
        region = grown
        reference = block_gray[region].mean()
    return region


def segment_blocks(block_gray, t1) -> np.ndarray:
    """Group 8-connected blocks of similar gray (Kim 2009, section 3.1, threshold ``T1``).

    Regions are grown one at a time from the free block with the most homogeneous 3 x 3
    neighbourhood: the region is the 8-connected component (:func:`skimage.measure.label`,
    ``connectivity=2``) of free blocks within ``t1`` of the region's mean gray level, which is
    re-estimated until the region is stable (at most 5 rounds).

    Parameters
    ----------
    block_gray : array_like of float, shape (rows, cols)
        Average gray level of every block (finite; 1 white .. 0 black).
    t1 : float
        The threshold ``T1``: largest gray difference of a block from its region's mean (>= 0).

    Returns
    -------
    ndarray of int
        Region number of every block, 1, 2, ... in order of creation.

    Raises
    ------
    ValueError
        If ``block_gray`` is not a finite 2-D array or ``t1`` not a non-negative number.
    """
    finite_array(block_gray, "block_gray", ndim=2)
    positive_number(t1, "t1", allow_zero=True)
    block_gray = np.asarray(block_gray)
    if block_gray.dtype.kind != "f":  # floats are used as given; integers would wrap and bools not subtract
        block_gray = block_gray.astype(np.float64)
    labels = np.zeros(block_gray.shape, dtype=np.int64)
    next_label = 1
    for flat in _seed_order(block_gray):
        seed = np.unravel_index(flat, block_gray.shape)
        if labels[seed]:
            continue
        labels[_grow_region(block_gray, labels == 0, seed, t1)] = next_label
        next_label += 1
    return labels


# ============================================================================ rectangles


def largest_rectangle(mask, min_height=1, min_width=1):
    """Largest axis-aligned rectangle of ``True`` cells in a 2-D mask.

    The classic histogram-and-stack algorithm: row by row, the heights of the runs of ``True``
    ending in that row form a histogram whose maximal rectangles a stack enumerates in
    O(columns); every maximal rectangle of the mask is met this way, so the largest one with
    height >= ``min_height`` and width >= ``min_width`` is found in O(rows x columns).

    Parameters
    ----------
    mask : array_like of bool, 2-D
    min_height, min_width : int, optional
        Smallest accepted sides (cells).

    Returns
    -------
    tuple of int or None
        ``(row0, col0, row1, col1)``, end-exclusive, of the largest-area rectangle (the first in
        raster order of its bottom-right corner among ties), or ``None`` if none fits.
    """
    mask = np.asarray(mask, dtype=bool)
    if mask.ndim != 2:
        raise ValueError(f"mask must be 2-D, got shape {mask.shape}")
    min_height = _positive_int(min_height, "min_height")
    min_width = _positive_int(min_width, "min_width")
    heights = np.zeros(mask.shape[1] + 1, dtype=np.int64)  # sentinel 0 column flushes the stack
    best, best_area = None, 0
    for row in range(mask.shape[0]):
        heights[:-1] = np.where(mask[row], heights[:-1] + 1, 0)
        stack = []  # column indices with increasing heights
        for col in range(mask.shape[1] + 1):
            start = col
            while stack and heights[stack[-1]] >= heights[col]:
                top = stack.pop()
                height = int(heights[top])
                start = stack[-1] + 1 if stack else 0
                width = col - start
                if height >= min_height and width >= min_width and height * width > best_area:
                    best_area = height * width
                    best = (row - height + 1, start, row + 1, col)
            stack.append(col)
    return best


# ============================================================================ tone selection


def _select_even_tones(order, grays, areas, t2):
    """Regions (indices, lightest first) whose tones are evenly spaced within ``t2``.

    Regions whose gray levels differ by less than ``t2`` show the same tone: the one with the
    largest rectangle stands for it. The tone spacing is the median gap between these tones;
    walking from the lightest, a tone closer than ``spacing - t2`` to the last kept one is an
    in-between tone (a dithered transition, a block split across two tones) and is dropped.
    """
    levels = []  # groups of region indices of the same tone
    for index in order:
        if levels and grays[levels[-1][-1]] - grays[index] < t2:
            levels[-1].append(index)
        else:
            levels.append([index])
    representatives = [max(group, key=lambda i: areas[i]) for group in levels]
    if len(representatives) < 2:
        return representatives
    gaps = -np.diff([grays[i] for i in representatives])
    spacing = float(np.median(gaps))
    kept = [representatives[0]]
    for index in representatives[1:]:
        if grays[kept[-1]] - grays[index] >= spacing - t2:
            kept.append(index)
    return kept


def extract_tone_map(image, block_size=DEFAULT_BLOCK_SIZE, t1=0.05, t2=0.03, min_size=64, pure=0.01) -> ToneMap:
    """Extract an artist's tone map from a stipple drawing (Kim 2009, section 3.1).

    Parameters
    ----------
    image : array_like, 2-D
        The drawing: bool (``True`` = ink), uint8 (255 = white) or float gray in [0, 1]
        (1 = white).
    block_size : int, optional
        ``N``, the block side in pixels. Default 30, the paper's value for Figure 4; it "should
        be small enough to represent a single tone" yet hold enough marks that a block's
        average is steady.
    t1 : float, optional
        ``T1``: a block joins a region when its gray level is within ``t1`` of the region's mean.
        Default 0.05, not given by the paper: below half the spacing of a 10-level tone map
        (1/9 / 2 = 0.056), so adjacent tones never merge, and about two standard deviations
        of the block averages of a steady tone at N = 30 with dots of the paper's size.
    t2 : float, optional
        ``T2``: tones closer than ``t2`` are one tone, and kept tones must be spaced at least
        the median spacing minus ``t2``. Default 0.03, not given by the paper: a quarter of
        the 8-tone spacing.
    min_size : int, optional
        Smallest side of an extracted texture in pixels (default 64); regions holding no
        rectangle of whole blocks at least this large on both sides are not tones.
    pure : float, optional
        Regions whose mean ink fraction is below ``pure`` or above ``1 - pure`` are the pure
        white and pure black levels (tones 0 and 9 of section 3.2), not stipple tones: they get
        no texture (default 0.01, a speck of dust per 10 x 10 px; the lightest stipple tone of
        Andrews' maps holds several times more ink). In [0, 0.5); 0 keeps every region.

    Returns
    -------
    ToneMap
        Selected tones (lightest first), textures, rectangles and the block segmentation.

    Raises
    ------
    ValueError
        For a non-2-D, empty, NaN or wrongly typed image, bad parameters, when no region is
        large enough for a ``min_size`` texture (the paper's stated limit: "our method assumes
        that there exists large enough regions in the stipple image for each tone level"), or
        when fewer than two stipple tones are found (pure white and black do not count).

    Notes
    -----
    The paper's sentences and our reading of them:

    1. "divide the image into equally sized N x N blocks ... average gray level ... ratio of
       black and white pixels": :func:`block_gray_levels` (partial blocks at the right and
       bottom edges are ignored).
    2. "group blocks that have similar average gray levels within a threshold, T1, ... connected
       component analysis using an 8-point neighborhood system": :func:`segment_blocks`; the
       threshold is taken relative to the region's mean rather than between neighbouring
       blocks, because chained neighbour differences leak through the artist's gradual,
       dithered transitions from one tone to the next.
    3. "sort the segmented regions by their average gray level and determine the difference of
       gray levels between two neighboring regions. If the tonal values ... are separated
       evenly within a threshold, T2 we extract a rectangular texture": regions large enough
       for a texture are sorted by mean gray, and :func:`_select_even_tones` keeps the evenly
       spaced ones.
    4. The texture of a region is the largest axis-aligned rectangle of its whole blocks
       (:func:`largest_rectangle` on the block grid, exact since a region is a union of blocks)
       whose sides are both at least ``min_size`` pixels.
    5. "Tone 0 and 9 are pure white and black respectively" (section 3.2): regions within
       ``pure`` of white or black are those two levels and are left out of the stipple tones
       (before step 3, so blank paper does not skew the tone spacing).

    References
    ----------
    Kim et al. (2009), Stippling by example, section 3.1 and Figure 4; section 6 (limitations).
    """
    block_gray = block_gray_levels(image, block_size)
    n = int(block_size)
    t1 = _threshold(t1, "t1")
    t2 = _threshold(t2, "t2")
    min_size = _positive_int(min_size, "min_size")
    pure = _pure_margin(pure)
    min_blocks = math.ceil(min_size / n)
    labels = segment_blocks(block_gray, t1)

    region_ids, grays, rectangles = [], [], []
    n_pure = 0
    for region in range(1, labels.max() + 1):
        box = largest_rectangle(labels == region, min_blocks, min_blocks)
        if box is None:
            continue
        gray = float(block_gray[labels == region].mean())
        if pure > 0 and (gray > 1.0 - pure or gray < pure):
            n_pure += 1  # tone 0 or tone 9: pure white or black, no texture (section 3.2)
            continue
        region_ids.append(region)
        grays.append(gray)
        rectangles.append(tuple(n * v for v in box))
    if not region_ids:
        found = f" ({n_pure} large region(s) are pure white or black, which are not stipple tones)" if n_pure else ""
        raise ValueError(
            f"no region holds a {min_size} x {min_size} stipple texture{found}: section 3.1 assumes a large enough "
            f"region per tone; lower block_size or min_size, raise t1, or extract the tones by hand"
        )
    areas = [(r1 - r0) * (c1 - c0) for r0, c0, r1, c1 in rectangles]
    order = sorted(range(len(grays)), key=lambda i: -grays[i])
    kept = _select_even_tones(order, grays, areas, t2)
    if len(kept) < 2:
        raise ValueError(f"found {len(kept)} tone(s) with a {min_size} x {min_size} texture; a tone map needs at least two")

    ink = _gray_image(image) < 0.5
    return ToneMap(
        gray_levels=np.array([grays[i] for i in kept]),
        textures=[ink[r0:r1, c0:c1].copy() for r0, c0, r1, c1 in (rectangles[i] for i in kept)],
        rectangles=np.array([rectangles[i] for i in kept], dtype=np.int64).reshape(-1, 4),
        region_ids=np.array([region_ids[i] for i in kept], dtype=np.int64),
        block_labels=labels,
        block_gray=block_gray,
        block_size=n,
    )
