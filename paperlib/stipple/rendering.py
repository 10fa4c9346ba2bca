"""Stipple rendering of a grayscale image (Kim et al. 2009, section 4).

The rendering turns a grayscale image into a bitonal stipple image in five steps:

1. :func:`tone_gray_levels` gives every tone level its average gray by *pre-simulation*: the
   tone's synthesized distribution texture is rendered with the tone's marks and the paper
   fraction of the result is measured (4.1). The tile is simulated inside a 3 x 3 periodic
   tiling so that marks crossing its border count as they will once tiles are stitched.
2. :func:`select_tones` picks a tone level for every pixel: a gray ``g`` between the grays
   ``g_i < g_{i+1}`` of two neighbouring levels picks level ``i + 1`` with probability
   ``p_r = (g - g_i) / (g_{i+1} - g_i)`` and level ``i`` otherwise (``p_l = 1 - p_r``, Figure
   10). The levels are the paper's whole tone map (section 3.2, "Tone 0 and 9 are pure white
   and black respectively"): pure white (gray 1), the stipple tones, pure black (gray 0); see
   *Pure levels* below.
3. :func:`distribution_image` copies, pixel by pixel, the chosen level's distribution texture
   into the *distribution image* (Figure 9). Each level's texture is stitched into a large one
   from copies of its tile, every copy rotated at random by 0, 90, 180 or 270 degrees (4.1).
4. :func:`place_marks` stamps a mark, drawn uniformly from the level's mark library, at every
   stipple pixel of the distribution image: black marks of the light and merged levels first,
   then white marks of the dark levels (4.2). The level map is ``tone_index``. The paper does
   not say what lies under the white marks; here the pixels of dark levels start as ink (the
   dark textures are white marks on black) and all others as paper. Pure white pixels stay
   paper and pure black pixels ink: no mark is centred on them.
5. :func:`remove_small_chunks` removes the stray ink and paper pixel chunks that the mixture of
   middle levels leaves (Figure 11). The paper *moves* each chunk toward its nearest stipple
   mark and gives no details; we delete the chunks (``skimage.morphology``), which removes the
   isolated pixels it shows in Figure 11 but does not add their ink to a neighbouring mark.

:func:`render_stippling` runs the five steps.

Pure levels
-----------
The paper's tone maps have ten levels (section 3.2 and Figure 3): tone 0 is pure white and tone
9 pure black, tones 1-8 are stipple textures. Only tones 1-8 are extracted, synthesized and
pre-simulated (sections 3.1-4.1); the two pure levels need no texture, their grays are 1 and 0
by definition. With ``pure_levels=True`` (the default of every step) the level map counts them:
level 0 is pure white (paper, no marks), levels ``1 .. n`` are the ``n`` stipple tones in the
order given, level ``n + 1`` is pure black (solid ink, no white marks); :func:`level_grays` gives
their grays ``[1, g_1, ..., g_n, 0]``. Figure 10's rule then covers every gray: a pixel lighter
than the lightest stipple tone mixes that tone with pure white, one darker than the darkest tone
mixes it with pure black, so a white input stays paper white and a black one solid ink, and the
level map's expected gray equals the input everywhere. Marks are stamped around their centres,
so the marks of a stipple tone next to pure pixels spill over them, as between any two levels;
in a mixture with a pure level the marks' density scales with the tone's share, so the expected
ink stays linear in the gray there (unlike a mixture of a black-mark and a white-mark level).
``pure_levels=False`` restores the previous rendering: the level map has the ``n`` stipple tones
only and grays outside their range take the nearest tone (a white area renders at the lightest
tone's ink, 11-12% with the synthetic exemplars of ``paperlib.datasets.stipple_tone_sheet``, and
a black one at the darkest tone's, about 88%).

Conventions: input images and tone grays are intensities in [0, 1] (0 black, 1 white, as
:func:`paperlib.datasets.grayscale_image`); bitonal textures and outputs are bool, ``True`` =
ink; distribution textures hold one ``True`` pixel per stipple centre (section 3.2).

Written by hand: the tone selection, the rotated tiling and the mark stamping (simple NumPy, no
library does them); connected components come from scikit-image.

References
----------
Kim, S., Maciejewski, R., Isenberg, T., Andrews, W. M., Chen, W., Sousa, M. C., Ebert, D. S.
(2009). Stippling by example. NPAR, section 4 (4.1, 4.2) and Figures 9-11; section 3.2 and
Figure 3 (the ten-level tone maps, tone 0 pure white and tone 9 pure black).
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from paperlib._checks import as_generator
from skimage.morphology import remove_small_holes, remove_small_objects

from .extraction import Mark
from .glcm import _checked_bitonal

__all__ = [
    "PURE_BLACK",
    "PURE_WHITE",
    "ChunkRemoval",
    "StippleRendering",
    "distribution_image",
    "level_grays",
    "place_marks",
    "remove_small_chunks",
    "render_stippling",
    "render_tone",
    "select_tones",
    "tone_gray_levels",
]


# Pixels per band of uniforms drawn at once in select_tones (1 Mi: 8 MiB of float64).
SELECTION_BAND_PIXELS = 1 << 20
# Pixels per band of the small-chunk removal (1 Mi: its int32 labels take 4 MiB per band, where
# the whole 4096 x 4096 image took 64 MiB, plus 128 MiB for the look-up of the removed labels).
CHUNK_BAND_PIXELS = 1 << 20

#: Gray of tone 0, pure white (section 3.2): paper, no marks.
PURE_WHITE = 1.0
#: Gray of the darkest tone (tone 9 of the paper's 10-level maps, section 3.2): solid ink.
PURE_BLACK = 0.0


# ============================================================================ results


@dataclass(frozen=True)
class ChunkRemoval:
    """Result of :func:`remove_small_chunks`.

    Parameters
    ----------
    image : ndarray of bool
        The cleaned stipple image, ``True`` = ink.
    removed_ink : int
        Ink pixels turned to paper (small black chunks on white).
    removed_paper : int
        Paper pixels turned to ink (small white chunks on black).
    """

    image: np.ndarray
    removed_ink: int
    removed_paper: int


@dataclass(frozen=True)
class StippleRendering:
    """Result of :func:`render_stippling` (Kim et al. 2009, section 4).

    Parameters
    ----------
    image : ndarray of bool
        Final stipple image, ``True`` = ink.
    tone_index : ndarray of int
        The level map: the level chosen for every pixel, an index into ``level_grays``. With
        pure levels, 0 = pure white, ``1 .. n`` = the stipple tones in the order given, ``n + 1``
        = pure black (the paper's tone 0 .. tone 9 for an 8-tone library, lightest first).
        :func:`render_stippling` stores it in the smallest signed integer type that holds the
        levels (int8 up to 127 levels), not int64: at 4096 x 4096 that is 16 MiB, not 128 MiB.
    distribution : ndarray of bool
        The distribution image of Figure 9, ``True`` = stipple centre.
    tone_grays : ndarray of float
        Gray of every stipple tone in [0, 1] (1 white), given or pre-simulated (4.1).
    removed_ink, removed_paper : int
        Pixels changed by the small-chunk removal (0 when it is off).
    level_grays : ndarray of float
        Gray of every level of ``tone_index``: ``[1, *tone_grays, 0]`` with pure levels,
        ``tone_grays`` without (:func:`level_grays`).
    pure_levels : bool
        Whether the level map holds the pure white and black levels (section 3.2).
    """

    image: np.ndarray
    tone_index: np.ndarray
    distribution: np.ndarray
    tone_grays: np.ndarray
    removed_ink: int
    removed_paper: int
    level_grays: np.ndarray
    pure_levels: bool


# ============================================================================ checks


def _checked_tiles(distribution_textures) -> list[np.ndarray]:
    """The distribution tiles as bool arrays: at least two, square, all of one shape."""
    if isinstance(distribution_textures, (str, bytes)) or not hasattr(distribution_textures, "__iter__"):
        raise TypeError("distribution_textures must be a sequence of bitonal 2-D arrays, "
                        f"got {type(distribution_textures).__name__}")
    tiles = [_checked_bitonal(texture, f"distribution_textures[{index}]")
             for index, texture in enumerate(distribution_textures)]
    if len(tiles) < 2:
        raise ValueError(f"distribution_textures must hold at least two tone levels, got {len(tiles)} textures")
    shape = tiles[0].shape
    if shape[0] != shape[1] or any(tile.shape != shape for tile in tiles):
        raise ValueError(
            "distribution textures must be square and share one shape (they are rotated by 90 degrees), "
            f"got shapes {sorted({tile.shape for tile in tiles})}"
        )
    return tiles


def _checked_library(marks, tone: int, name: str = "marks") -> tuple[list[Mark], bool]:
    """One tone's mark library and its colour (True = white marks); ``name``: the caller's parameter."""
    try:
        library = list(marks)
    except TypeError:
        raise TypeError(f"{name}: the mark library of tone {tone} must be a sequence of "
                        f"paperlib.stipple.extraction.Mark, got {type(marks).__name__}") from None
    if not library:
        raise ValueError(f"{name}: tone {tone} has an empty mark library")
    for mark in library:
        if not isinstance(mark, Mark):
            raise ValueError(f"{name}: tone {tone}: marks must be paperlib.stipple.extraction.Mark, got "
                             f"{type(mark).__name__}")
        if mark.mask.ndim != 2 or mark.mask.dtype != np.bool_ or not mark.mask.any():
            raise ValueError(f"{name}: tone {tone}: a mark's mask must be a non-empty 2-D bool array")
    colours = {bool(mark.white) for mark in library}
    if len(colours) != 1:
        raise ValueError(f"{name}: tone {tone} mixes black and white marks; a level uses one colour (section 4.2)")
    return library, colours.pop()


def _checked_libraries(marks_per_tone, n_tones: int | None) -> tuple[list[list[Mark]], np.ndarray]:
    """All mark libraries, one per tone (``n_tones`` of them, any number when None), and the per-tone colour
    (True = white marks)."""
    try:
        libraries = list(marks_per_tone)
    except TypeError:
        raise TypeError(f"marks_per_tone must be a sequence of mark libraries, one per tone, got "
                        f"{type(marks_per_tone).__name__}") from None
    if n_tones is not None and len(libraries) != n_tones:
        raise ValueError(f"marks_per_tone: need one mark library per tone: {n_tones} tones, {len(libraries)} "
                         f"libraries")
    checked = [_checked_library(marks, tone, "marks_per_tone") for tone, marks in enumerate(libraries)]
    return [library for library, _ in checked], np.array([white for _, white in checked], dtype=bool)


def _checked_image(image) -> np.ndarray:
    """A 2-D float image with every value in [0, 1]."""
    array = np.asarray(image)
    if array.ndim != 2 or array.size == 0:
        raise ValueError(f"image must be a non-empty 2-D array, got shape {array.shape}")
    if not np.issubdtype(array.dtype, np.floating):
        raise ValueError(
            f"image must be floating point with intensities in [0, 1], got dtype {array.dtype}; "
            "convert 8-bit images with skimage.util.img_as_float"
        )
    # min and max are NaN when any value is (and +-inf fail the range test): no image-sized
    # temporary of np.isfinite (16 MiB at 4096 x 4096)
    low, high = array.min(), array.max()
    if not (np.isfinite(low) and np.isfinite(high)) or low < 0 or high > 1:
        raise ValueError("image values must be finite and within [0, 1] (0 black, 1 white)")
    return array


def _checked_grays(tone_grays) -> np.ndarray:
    """Tone grays as a 1-D float array of at least two distinct values in [0, 1]."""
    try:
        grays = np.asarray(tone_grays, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"tone_grays must be a 1-D array of numbers in [0, 1], got {type(tone_grays).__name__}") from None
    if grays.ndim != 1 or grays.size < 2:
        raise ValueError(f"tone_grays must hold the grays of at least two tone levels (1-D), got shape {grays.shape}")
    if not np.all(np.isfinite(grays)) or grays.min() < 0 or grays.max() > 1:
        raise ValueError("tone_grays must be finite and within [0, 1]")
    if np.unique(grays).size != grays.size:
        raise ValueError(f"tone_grays must be distinct (the selection interpolates between them), got {grays}")
    return grays


def _checked_pure_levels(pure_levels) -> bool:
    if not isinstance(pure_levels, (bool, np.bool_)):
        raise ValueError(f"pure_levels must be True or False, got {pure_levels!r}")
    return bool(pure_levels)


def _checked_tone_index(tone_index, n_tones: int, pure_levels: bool = False) -> np.ndarray:
    """A 2-D integer level map whose values are level numbers (``n_tones + 2`` levels with pure levels)."""
    index = np.asarray(tone_index)
    if index.ndim != 2 or index.size == 0 or not np.issubdtype(index.dtype, np.integer):
        raise ValueError(f"tone_index must be a non-empty 2-D integer array, got shape {index.shape}, dtype {index.dtype}")
    n_levels = n_tones + 2 if pure_levels else n_tones
    if index.min() < 0 or index.max() >= n_levels:
        counted = (f"{n_tones} stipple tones between pure white (0) and pure black ({n_levels - 1})" if pure_levels
                   else f"{n_tones} tones, no pure levels")
        raise ValueError(f"tone_index values must lie in [0, {n_levels - 1}] ({counted})")
    return index


def level_grays(tone_grays, *, pure_levels: bool = True) -> np.ndarray:
    """Grays of the levels of the level map: the stipple tones, between pure white and black.

    Parameters
    ----------
    tone_grays : array_like of float, shape (n_tones,)
        Distinct grays of at least two stipple tones in [0, 1] (1 white), any order, e.g.
        :func:`tone_gray_levels`. With ``pure_levels`` they must lie strictly inside (0, 1): a
        tone of gray 1 would hold no ink and one of gray 0 no paper, which are the pure levels.
    pure_levels : bool, optional
        Add the paper's pure white (tone 0) and pure black (tone 9) levels (default True).

    Returns
    -------
    ndarray of float
        ``[1, *tone_grays, 0]`` with ``pure_levels`` (level 0 pure white, level ``n + 1`` pure
        black), else ``tone_grays``.

    Raises
    ------
    ValueError
        Fewer than two, repeated, non-finite or out-of-range grays, or (with ``pure_levels``) a
        tone gray of exactly 0 or 1.

    References
    ----------
    Kim et al. 2009, section 3.2 ("Tone 0 and 9 are pure white and black respectively") and
    Figure 3 (the 10-level tone maps).
    """
    grays = _checked_grays(tone_grays)
    if not _checked_pure_levels(pure_levels):
        return grays
    pure = grays[(grays >= PURE_WHITE) | (grays <= PURE_BLACK)]
    if pure.size:
        raise ValueError(
            f"tone grays {pure.tolist()} are pure white or black: with pure_levels=True tone 0 (gray 1) and the "
            "darkest tone (gray 0) are added to the stipple tones (section 3.2), whose grays must therefore hold "
            "ink and paper, strictly between 0 and 1; drop that tone or pass pure_levels=False"
        )
    return np.concatenate([[PURE_WHITE], grays, [PURE_BLACK]])


# ============================================================================ mark stamping


@numba.njit(cache=True)
def _stamp_kernel(canvas, rows, cols, chosen, masks, offsets, value):
    """Stamp ``masks[chosen[k]]`` centred on ``(rows[k], cols[k])`` with ``value``, clipped."""
    height, width = canvas.shape
    for k in range(rows.shape[0]):
        mark = chosen[k]
        top, left = rows[k] - offsets[mark, 0], cols[k] - offsets[mark, 1]
        for i in range(max(0, -top), min(masks.shape[1], height - top)):
            for j in range(max(0, -left), min(masks.shape[2], width - left)):
                if masks[mark, i, j]:
                    canvas[top + i, left + j] = value


def _packed(library: list[Mark]) -> tuple[np.ndarray, np.ndarray]:
    """The library's masks zero-padded into one (n, h, w) array, and their (row, col) offsets."""
    height = max(mark.mask.shape[0] for mark in library)
    width = max(mark.mask.shape[1] for mark in library)
    masks = np.zeros((len(library), height, width), dtype=np.bool_)
    for index, mark in enumerate(library):
        masks[index, : mark.mask.shape[0], : mark.mask.shape[1]] = mark.mask
    return masks, np.array([mark.offset for mark in library], dtype=np.int64).reshape(-1, 2)


def _stamp_random_marks(canvas, rows, cols, library: list[Mark], value: bool, rng) -> None:
    """Stamp a mark drawn uniformly, with replacement, from ``library`` at every (row, col) (4.2)."""
    chosen = rng.integers(0, len(library), size=rows.size)
    masks, offsets = _packed(library)
    _stamp_kernel(canvas, rows.astype(np.int64), cols.astype(np.int64), chosen, masks, offsets, value)


def render_tone(distribution, marks, rng=None) -> np.ndarray:
    """Render one tone level: a mark of its library stamped at every stipple pixel.

    Parameters
    ----------
    distribution : array_like, 2-D
        Bitonal distribution texture, ``True`` / 1 = stipple centre.
    marks : sequence of Mark
        The level's mark library, all black or all white.
    rng : None, int or numpy.random.Generator, optional
        Random source of the mark choice.

    Returns
    -------
    ndarray of bool
        ``True`` = ink: black marks on paper, or white marks cut out of ink. Marks are clipped at
        the border.

    Raises
    ------
    ValueError
        Non-bitonal distribution, empty or mixed-colour mark library.

    References
    ----------
    Kim et al. 2009, section 4.2 ("a random mark is uniformly selected and placed").
    """
    centres = _checked_bitonal(distribution, "distribution")
    library, white = _checked_library(marks, 0)
    rng = as_generator(rng)
    canvas = np.full(centres.shape, white)
    rows, cols = np.nonzero(centres)
    _stamp_random_marks(canvas, rows, cols, library, not white, rng)
    return canvas


# ============================================================================ steps 1-5


def tone_gray_levels(distribution_textures, marks_per_tone, *, repeats: int = 1, rng=None) -> np.ndarray:
    """The average gray of every tone level by pre-simulation (step 1).

    Each tone's distribution tile is tiled 3 x 3 (periodically, as tiles are stitched in the
    rendering), rendered with :func:`render_tone`, and the paper fraction of the central tile is
    its gray; ``repeats`` renderings with new random marks are averaged. Only the stipple tones
    are pre-simulated: the pure white and black levels of section 3.2 have grays 1 and 0 by
    definition (:func:`level_grays`).

    Parameters
    ----------
    distribution_textures : sequence of array_like
        One bitonal distribution texture per tone level (at least two), square, one shape.
    marks_per_tone : sequence of sequence of Mark
        One mark library per tone level.
    repeats : int, optional
        Number of pre-simulations averaged per tone, >= 1.
    rng : None, int or numpy.random.Generator, optional
        Random source of the mark choice.

    Returns
    -------
    ndarray of float, shape (n_tones,)
        Gray of each tone in [0, 1], 1 = white (paper fraction), in the order given.

    Raises
    ------
    ValueError
        Fewer than two tones, non-bitonal or mis-shaped textures, bad mark libraries, or
        ``repeats`` < 1.

    References
    ----------
    Kim et al. 2009, section 4.1 ("all synthesized distribution textures are assigned their
    average gray value through pre-simulation in which stipple marks are placed on the
    synthesized distribution").
    """
    tiles = _checked_tiles(distribution_textures)
    libraries, _ = _checked_libraries(marks_per_tone, len(tiles))
    if isinstance(repeats, bool) or not isinstance(repeats, (int, np.integer)) or repeats < 1:
        raise ValueError(f"repeats must be an integer >= 1, got {repeats!r}")
    rng = as_generator(rng)
    side = tiles[0].shape[0]
    grays = np.empty(len(tiles))
    for tone, (tile, library) in enumerate(zip(tiles, libraries)):
        papers = [
            1.0 - render_tone(np.tile(tile, (3, 3)), library, rng)[side : 2 * side, side : 2 * side].mean()
            for _ in range(repeats)
        ]
        grays[tone] = float(np.mean(papers))
    return grays


def select_tones(image, tone_grays, rng=None, *, pure_levels: bool = True) -> np.ndarray:
    """Probability-based tone level selection of every pixel (step 2, Figure 10).

    With the level grays sorted, ``g_i <= g < g_{i+1}``, a pixel of gray ``g`` takes level
    ``i + 1`` with probability ``p_r = (g - g_i) / (g_{i+1} - g_i)`` and level ``i`` with
    ``p_l = 1 - p_r``, so the expected gray equals ``g`` and a gray equal to a level's picks that
    level only.

    With ``pure_levels`` (default) the levels are pure white (gray 1), the stipple tones and pure
    black (gray 0) (:func:`level_grays`): they span [0, 1], so every gray is mixed from its two
    neighbouring levels and the expected gray of the level map equals the input everywhere; a
    gray lighter than the lightest tone mixes it with pure white, one darker than the darkest
    tone mixes it with pure black. Without them, grays outside the tones' range take the nearest
    (lightest or darkest) tone.

    Parameters
    ----------
    image : array_like of float, 2-D
        Input intensities in [0, 1] (0 black, 1 white).
    tone_grays : array_like of float, shape (n_tones,)
        Distinct grays of the stipple tones in [0, 1] (strictly inside with ``pure_levels``), any
        order (see :func:`tone_gray_levels`).
    rng : None, int or numpy.random.Generator, optional
        Random source; a seed fixes the output bit for bit.
    pure_levels : bool, optional
        Add the pure white and black levels (section 3.2); default True.

    Returns
    -------
    ndarray of int64, shape of ``image``
        The level map: index into ``level_grays(tone_grays, pure_levels=pure_levels)`` of every
        pixel's level: with pure levels 0 = pure white, ``k + 1`` = ``tone_grays[k]``,
        ``n_tones + 1`` = pure black; without, ``k`` = ``tone_grays[k]``.

    Raises
    ------
    ValueError
        Non-float or out-of-range image, fewer than two or repeated tone grays, a tone gray of
        0 or 1 with ``pure_levels``.

    References
    ----------
    Kim et al. 2009, section 4.1 and Figure 10 (probabilities ``p_l`` and ``p_r``); section 3.2
    (tones 0 and 9 pure white and black).
    """
    gray = _checked_image(image)
    grays = level_grays(tone_grays, pure_levels=pure_levels)
    return _selected_levels(gray, grays, as_generator(rng), np.int64)


def _level_dtype(n_levels: int) -> type:
    """The smallest signed integer type holding level numbers 0 .. n_levels - 1."""
    for dtype in (np.int8, np.int16, np.int32):
        if n_levels - 1 <= np.iinfo(dtype).max:
            return dtype
    return np.int64


def _selected_levels(gray, grays, rng, dtype) -> np.ndarray:
    """:func:`select_tones` on checked input (``grays`` the level grays), as a ``dtype`` level map."""
    order = np.argsort(grays)
    tone_index = np.empty(gray.shape, dtype=dtype)
    # uniforms drawn a band of rows at a time (the same stream as one draw of the whole image)
    # so that a 4096 x 4096 image needs no 128 MiB array of them
    band = max(1, SELECTION_BAND_PIXELS // gray.shape[1])
    for top in range(0, gray.shape[0], band):
        rows = slice(top, top + band)
        _select_kernel(gray[rows], grays[order], order, rng.random(gray[rows].shape), tone_index[rows])
    return tone_index


@numba.njit(cache=True)
def _select_kernel(gray, ordered, order, uniforms, out):
    """Figure 10's choice between the two tones whose sorted grays bracket each pixel's gray."""
    last = ordered.shape[0] - 1
    for r in range(gray.shape[0]):
        for c in range(gray.shape[1]):
            g = min(max(gray[r, c], ordered[0]), ordered[last])
            left = 0
            while left < last - 1 and ordered[left + 1] <= g:
                left += 1
            p_right = (g - ordered[left]) / (ordered[left + 1] - ordered[left])
            out[r, c] = order[left + 1] if uniforms[r, c] < p_right else order[left]


def distribution_image(tone_index, distribution_textures, rng=None, *, pure_levels: bool = True) -> np.ndarray:
    """The distribution image of Figure 9 (step 3).

    Every tone's tile is stitched into a texture as large as ``tone_index``, each copy of the
    tile rotated at random by a multiple of 90 degrees (independently per tone and per copy,
    all rotations drawn before any is used); each pixel then copies the pixel of its own
    level's large texture. Pure levels have no texture: their pixels hold no stipple centre.

    Parameters
    ----------
    tone_index : array_like of int, 2-D
        The level map (:func:`select_tones`, same ``pure_levels``).
    distribution_textures : sequence of array_like
        One bitonal, square distribution tile per stipple tone, one shape for all.
    rng : None, int or numpy.random.Generator, optional
        Random source of the rotations.
    pure_levels : bool, optional
        Whether ``tone_index`` counts the pure levels (0 white, ``n + 1`` black); default True.

    Returns
    -------
    ndarray of bool, shape of ``tone_index``
        ``True`` = stipple centre.

    Raises
    ------
    ValueError
        Fewer than two tones, non-bitonal or mis-shaped tiles, level numbers out of range.

    References
    ----------
    Kim et al. 2009, section 4.1 ("applying a random rotation to each small texture when merging
    them into their larger counterparts") and Figure 9; section 3.2 (pure levels).
    """
    tiles = _checked_tiles(distribution_textures)
    pure_levels = _checked_pure_levels(pure_levels)
    index = _checked_tone_index(tone_index, len(tiles), pure_levels)
    rng = as_generator(rng)
    side = tiles[0].shape[0]
    cells = (-(-index.shape[0] // side), -(-index.shape[1] // side))
    turns = rng.integers(0, 4, size=(len(tiles), *cells))
    out = np.empty(index.shape, dtype=np.bool_)
    # the level map is read as it is (any integer dtype, no image-sized int64 copy of it)
    _stitch_kernel(index, np.stack(tiles), turns, 1 if pure_levels else 0, out)
    return out


@numba.njit(cache=True)
def _stitch_kernel(index, tiles, turns, first, out):
    """``out[r, c]`` = pixel (r, c) of the large texture of stipple tone ``index[r, c] - first``.

    The large texture of tone t holds, in tile cell (R, C), ``np.rot90(tiles[t], turns[t, R, C])``.
    With ``first = 1`` (pure levels) levels 0 and ``len(tiles) + 1`` are pure white and black:
    no texture, no stipple centre.
    """
    side = tiles.shape[1]
    last = side - 1
    n_tones = tiles.shape[0]
    for r in range(index.shape[0]):
        i = r % side
        for c in range(index.shape[1]):
            j = c % side
            tone = np.int64(index[r, c]) - first  # int64 whatever the map's type (uint64 - int64 is a float)
            if tone < 0 or tone >= n_tones:  # a pure level (the level map was checked)
                out[r, c] = False
                continue
            turn = turns[tone, r // side, c // side]
            if turn == 0:
                out[r, c] = tiles[tone, i, j]
            elif turn == 1:  # np.rot90(a, 1)[i, j] == a[j, last - i]
                out[r, c] = tiles[tone, j, last - i]
            elif turn == 2:
                out[r, c] = tiles[tone, last - i, last - j]
            else:
                out[r, c] = tiles[tone, last - j, i]


def place_marks(distribution, tone_index, marks_per_tone, rng=None, *, pure_levels: bool = True) -> np.ndarray:
    """Stamp the stipple marks onto the distribution image (step 4).

    Pixels of levels with white marks (dark levels) and of pure black start as ink, all others
    (black-mark levels, pure white) as paper. Black marks are stamped first at the stipple
    pixels of black-mark levels, then white marks at those of white-mark levels (the paper's
    order), each drawn uniformly from its level's library and centred on the stipple pixel
    (clipped at the border). Pure levels place no mark: stipple pixels on them are ignored.

    Parameters
    ----------
    distribution : array_like, 2-D
        Bitonal distribution image (:func:`distribution_image`), ``True`` = stipple centre.
    tone_index : array_like of int, 2-D
        The level map, same shape.
    marks_per_tone : sequence of sequence of Mark
        One mark library per stipple tone; a level's colour is its marks' colour.
    rng : None, int or numpy.random.Generator, optional
        Random source of the mark choice.
    pure_levels : bool, optional
        Whether ``tone_index`` counts the pure levels (0 white, ``n + 1`` black); default True.

    Returns
    -------
    ndarray of bool
        The stipple image, ``True`` = ink.

    Raises
    ------
    ValueError
        Non-bitonal distribution, shapes that differ, bad level map or mark libraries.

    References
    ----------
    Kim et al. 2009, section 4.2 (black marks, then white marks; the level map; uniform choice
    of a mark); section 3.2 (tones 0 and 9 pure white and black).
    """
    centres = _checked_bitonal(distribution, "distribution")
    libraries, white = _checked_libraries(marks_per_tone, None)
    if len(libraries) < 2:
        raise ValueError(f"marks_per_tone must hold at least two tone levels, got {len(libraries)} mark libraries")
    pure_levels = _checked_pure_levels(pure_levels)
    index = _checked_tone_index(tone_index, len(libraries), pure_levels)
    if index.shape != centres.shape:
        raise ValueError(f"distribution {centres.shape} and tone_index {index.shape} must have one shape")
    rng = as_generator(rng)
    # the starting colour of every level (True = ink) and the library of every stipple level
    starts_as_ink = np.concatenate([[False], white, [True]]) if pure_levels else white
    first = 1 if pure_levels else 0
    canvas = starts_as_ink[index]
    rows, cols = np.nonzero(centres)
    tones = index[rows, cols] - first
    for colour in (False, True):
        for tone in np.flatnonzero(white == colour):
            here = tones == tone
            _stamp_random_marks(canvas, rows[here], cols[here], libraries[tone], not colour, rng)
    return canvas


def remove_small_chunks(image, min_size: int, *, connectivity: int = 2) -> ChunkRemoval:
    """Remove ink and paper chunks of fewer than ``min_size`` pixels (step 5, Figure 11).

    Small ink components on paper are erased first
    (``skimage.morphology.remove_small_objects``), then small paper components inside ink are
    filled (``remove_small_holes``). The paper moves each chunk toward its nearest stipple mark
    without giving the rule; we delete it.

    Parameters
    ----------
    image : array_like, 2-D
        Bitonal stipple image, ``True`` / 1 = ink.
    min_size : int
        Components with fewer pixels are removed, >= 1 (1 removes nothing).
    connectivity : {1, 2}, optional
        4- (1) or 8-connectivity (2, default, as the mark segmentation of section 3.2).

    Returns
    -------
    ChunkRemoval
        Cleaned image and the number of ink and paper pixels changed.

    Raises
    ------
    ValueError
        Non-bitonal image, ``min_size`` not an integer >= 1, bad connectivity.

    References
    ----------
    Kim et al. 2009, section 4.2 and Figure 11 ("identifying the small pixel chunks, both white
    on a black background and black on a white background").
    """
    ink = _checked_bitonal(image, "image")
    if isinstance(min_size, bool) or not isinstance(min_size, (int, np.integer)) or min_size < 1:
        raise ValueError(f"min_size must be an integer >= 1, got {min_size!r}")
    if connectivity not in (1, 2):
        raise ValueError(f"connectivity must be 1 or 2, got {connectivity!r}")
    largest_removed = int(min_size) - 1
    cleaned = ink.copy()
    if largest_removed == 0:
        return ChunkRemoval(image=cleaned, removed_ink=0, removed_paper=0)
    # Bands of rows with a halo. A chunk of at most m = largest_removed pixels spans at most
    # m rows, so one that touches a band lies inside the band grown by m rows, and there it is
    # whole; a larger component that leaves the grown band crosses its m halo rows and keeps
    # more than m pixels inside it, so it is not removed there either: every band pixel gets
    # the verdict of the whole-image removal. The holes are looked for in the chunk-free image,
    # which the first step gives for the band grown by m from the band grown by 2 m.
    height = ink.shape[0]
    halo = largest_removed
    band = max(1, CHUNK_BAND_PIXELS // ink.shape[1])
    removed_ink = removed_paper = 0
    for top in range(0, height, band):
        bottom = min(top + band, height)
        near_top, near_bottom = max(0, top - halo), min(height, bottom + halo)
        far_top, far_bottom = max(0, top - 2 * halo), min(height, bottom + 2 * halo)
        no_specks = remove_small_objects(ink[far_top:far_bottom], connectivity=connectivity,
                                         max_size=largest_removed)[near_top - far_top:near_bottom - far_top]
        filled = remove_small_holes(no_specks, connectivity=connectivity, max_size=largest_removed)
        rows = slice(top - near_top, bottom - near_top)
        removed_ink += int(np.count_nonzero(ink[top:bottom] & ~no_specks[rows]))
        removed_paper += int(np.count_nonzero(filled[rows] & ~no_specks[rows]))
        cleaned[top:bottom] = filled[rows]
    return ChunkRemoval(image=cleaned, removed_ink=removed_ink, removed_paper=removed_paper)


def render_stippling(
    image, distribution_textures, marks_per_tone, *, tone_grays=None, min_chunk: int = 1, pure_levels: bool = True,
    rng=None,
) -> StippleRendering:
    """Render a grayscale image as stipples (section 4: steps 1-5 of the module docstring).

    Parameters
    ----------
    image : array_like of float, 2-D
        Input intensities in [0, 1] (0 black, 1 white).
    distribution_textures : sequence of array_like
        One synthesized distribution tile per stipple tone (at least two), square, one shape.
    marks_per_tone : sequence of sequence of Mark
        One mark library per stipple tone (:func:`paperlib.stipple.extraction.extract_marks`).
    tone_grays : array_like of float, optional
        Gray of each stipple tone; default pre-simulated with :func:`tone_gray_levels`.
    min_chunk : int, optional
        :func:`remove_small_chunks`' ``min_size``; default 1 (no removal).
    pure_levels : bool, optional
        Render with the paper's pure white (tone 0) and pure black (tone 9) levels around the
        stipple tones (section 3.2; default True): grays lighter than the lightest tone mix it
        with paper white, grays darker than the darkest mix it with solid ink. False: the
        stipple tones only, grays outside their range clamped to the nearest tone (the
        rendering before pure levels were added).
    rng : None, int or numpy.random.Generator, optional
        Random source; a seed fixes the output bit for bit.

    Returns
    -------
    StippleRendering

    Raises
    ------
    ValueError
        As the five steps; with ``pure_levels``, a tone gray of exactly 0 or 1 (a texture with
        no paper or no ink is a pure level, not a stipple tone).

    References
    ----------
    Kim et al. 2009, section 4 and Figures 9-11; section 3.2 and Figure 3 (tones 0 and 9 pure
    white and black).
    """
    gray = _checked_image(image)
    tiles = _checked_tiles(distribution_textures)
    libraries, _ = _checked_libraries(marks_per_tone, len(tiles))
    pure_levels = _checked_pure_levels(pure_levels)
    rng = as_generator(rng)
    if tone_grays is None:
        grays = tone_gray_levels(tiles, libraries, rng=rng)
    else:
        grays = _checked_grays(tone_grays)
        if grays.size != len(tiles):
            raise ValueError(f"need one gray per tone: {len(tiles)} tones, {grays.size} grays")
    levels = level_grays(grays, pure_levels=pure_levels)
    # the level map in the smallest integer type that holds it: int64 would take 128 MiB at
    # 4096 x 4096, more than the whole rendering needs otherwise
    tone_index = _selected_levels(gray, levels, rng, _level_dtype(levels.size))
    distribution = distribution_image(tone_index, tiles, rng, pure_levels=pure_levels)
    stippled = place_marks(distribution, tone_index, libraries, rng, pure_levels=pure_levels)
    cleaned = remove_small_chunks(stippled, min_chunk)
    return StippleRendering(
        image=cleaned.image,
        tone_index=tone_index,
        distribution=distribution,
        tone_grays=grays,
        removed_ink=cleaned.removed_ink,
        removed_paper=cleaned.removed_paper,
        level_grays=levels,
        pure_levels=pure_levels,
    )
