"""Stipple distribution and mark extraction (Kim et al. 2009, section 3.2).

An example stipple texture is split into its *distribution* (one pixel per stipple centre, the
*example distribution texture* that sections 3.3-3.4 analyse and synthesise) and its *marks* (the
stipple shapes that the rendering of section 4.2 stamps back).

Levels (section 3.2). The paper sorts Andrews' tones by eye: *light* (tones 1-4, separate black
marks on white), *merged* (tones 5-6, marks touching into blobs, treated as black on white) and
*dark* (tones 7-8, separate white marks on black). It gives no numeric rule, so
:func:`classify_level` states one:

- the *marks* are the minority colour: black (ink) when ink covers at most half the texture,
  white otherwise;
- the marks are 8-connected components (the paper's segmentation). A component is a *blob* when
  its area exceeds ``merge_factor`` (default 3) times the median component area: a single
  hand-drawn dot varies in size by a factor of about 2, while two touching dots already double
  it and the blobs of merged tones hold many dots;
- the marks are *separate* when blobs hold at most ``merged_share`` (default 0.2) of the mark
  pixels. Separate black marks make a light level, separate white marks a dark level, anything
  else a merged level (black marks on white, as the paper says).

On the seeded generator :func:`paperlib.datasets.stipple_tone_texture` the blob share is 0 for
every light and dark tone and at least 0.44 for every merged tone (0.32-0.68), so the thresholds
sit in a wide gap.

Distribution. Separate marks: the centre of each 8-connected component is its centroid
(``skimage.measure.regionprops``). Merged level: the constrained Lloyd algorithm of Kim et al.
(2008) with the black marks as the constraint. The number of stipples is the ink area divided by
the single-stipple size ``S_avg`` (by default the median component area: the dots that stayed
apart in the merged texture). Each blob receives ``max(1, round(area / S_avg))`` points, placed
regularly on it by farthest-point sampling; then Lloyd steps move every point to the centroid of
its Voronoi cell *restricted to the ink pixels of its own blob*
(:func:`paperlib.stipple.voronoi_stippling.weighted_centroids` with the blob as the density), so
points never leave the ink and spread within each merged blob. A centroid that falls on paper (a
curved blob) is snapped to the nearest ink pixel of its blob.

Written by hand: the level rule, the point allocation per blob and the snapping (no library does
them); connected components, centroids and Voronoi cells come from scikit-image and SciPy.

References
----------
Kim, S., Maciejewski, R., Isenberg, T., Andrews, W. M., Chen, W., Sousa, M. C., Ebert, D. S.
(2009). Stippling by example. NPAR, section 3.2 and Figure 5.
Kim, D., Son, M., Lee, Y., Kang, H., Lee, S. (2008). Feature-guided image stippling. Computer
Graphics Forum 27(4) (the constrained Lloyd algorithm).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree
from skimage.measure import label, regionprops

from paperlib._checks import check_choice, positive_number

from .glcm import _checked_bitonal
from .voronoi_stippling import weighted_centroids

__all__ = ["LEVELS", "DistributionResult", "Mark", "classify_level", "extract_distribution", "extract_marks"]

#: The paper's three levels (section 3.2).
LEVELS = ("light", "merged", "dark")
#: A component larger than this many median component areas is a blob of merged stipples.
MERGE_FACTOR = 3.0
#: The marks are separate when blobs hold at most this share of the mark pixels.
MERGED_SHARE = 0.2
#: Default cap and stopping tolerance (largest point move, px) of the constrained Lloyd steps.
LLOYD_ITERATIONS = 50
LLOYD_TOLERANCE = 1e-3


# ============================================================================ results


@dataclass(frozen=True)
class DistributionResult:
    """Example distribution texture of one tone (Kim et al. 2009, section 3.2).

    Parameters
    ----------
    distribution : ndarray of bool
        Same shape as the texture; ``True`` at exactly one pixel per stipple centre.
    centres : ndarray of float, shape (k, 2)
        Stipple centres ``(row, column)``, sub-pixel (component centroids or Lloyd points).
    pixels : ndarray of int, shape (k, 2)
        The distribution pixel ``(row, column)`` of each centre, all distinct.
    level : str
        ``"light"``, ``"merged"`` or ``"dark"``.
    white_marks : bool
        True for the dark level: the centres are those of white marks on black.
    s_avg : float
        Average stipple size (px) used: mean component area for separate marks, the single
        stipple size that set the point count for a merged level.
    lloyd_iterations : int
        Constrained Lloyd steps run (0 for light and dark levels).
    """

    distribution: np.ndarray
    centres: np.ndarray
    pixels: np.ndarray
    level: str
    white_marks: bool
    s_avg: float
    lloyd_iterations: int = 0


@dataclass(frozen=True)
class Mark:
    """One stipple mark cropped to its bounding box (Kim et al. 2009, sections 3.2 and 4.2).

    Parameters
    ----------
    mask : ndarray of bool
        The mark's pixels (``True``) in its bounding box.
    offset : tuple of int
        ``(row, column)`` of the mark's centre pixel inside ``mask``: stamping ``mask`` with its
        corner at ``pixel - offset`` puts the mark back where it was.
    white : bool
        True for a white mark (dark level), drawn as paper on ink.
    """

    mask: np.ndarray
    offset: tuple[int, int]
    white: bool


# ============================================================================ checks


def _fraction(value, name: str) -> float:
    number = positive_number(value, name)
    if number >= 1:
        raise ValueError(f"{name} must lie in (0, 1), got {value!r}")
    return number


def _checked_texture(texture) -> np.ndarray:
    """Bitonal texture that holds both ink and paper (pure white or black tones have no stipples)."""
    ink = _checked_bitonal(texture, "texture")
    if not ink.any():
        raise ValueError("texture is all white (no ink): a pure white tone has no stipples to extract")
    if ink.all():
        raise ValueError("texture is all black (no paper): a pure black tone has no stipples to extract")
    return ink


def _checked_level(level) -> str | None:
    check_choice(level, ("auto", *LEVELS), "level")
    return None if level == "auto" else level


# ============================================================================ levels


def _blob_share(marks: np.ndarray, merge_factor: float) -> float:
    """Share of the mark pixels lying in components larger than ``merge_factor`` median areas."""
    areas = np.bincount(label(marks, connectivity=2).ravel())[1:]
    blobs = areas > merge_factor * np.median(areas)
    return float(areas[blobs].sum() / areas.sum())


def classify_level(texture, *, merge_factor=MERGE_FACTOR, merged_share=MERGED_SHARE) -> str:
    """Light, merged or dark level of an example stipple texture.

    Parameters
    ----------
    texture : array_like, 2-D
        Bitonal texture, ``True`` / 1 = ink, holding both ink and paper.
    merge_factor : float, optional
        A component whose area exceeds ``merge_factor`` times the median component area is a
        blob of merged stipples (default 3).
    merged_share : float, optional
        In (0, 1): the marks are separate when blobs hold at most this share of their pixels
        (default 0.2).

    Returns
    -------
    str
        ``"light"`` (separate black marks, ink <= half), ``"dark"`` (separate white marks, ink >
        half) or ``"merged"``. The module docstring explains the rule and the thresholds.

    Raises
    ------
    ValueError
        Non-bitonal, empty, all-white or all-black texture; bad thresholds.

    References
    ----------
    Kim et al. 2009, section 3.2 (light, merged and dark levels; the paper sorts them by eye).
    """
    ink = _checked_texture(texture)
    merge_factor = positive_number(merge_factor, "merge_factor")
    if merge_factor < 1:
        raise ValueError(f"merge_factor must be at least 1, got {merge_factor!r}")
    merged_share = _fraction(merged_share, "merged_share")
    white_marks = ink.mean() > 0.5
    marks = ~ink if white_marks else ink
    if _blob_share(marks, merge_factor) > merged_share:
        return "merged"
    return "dark" if white_marks else "light"


# ============================================================================ distribution


def _distinct_pixels(centres: np.ndarray, shape: tuple[int, int], allowed: np.ndarray | None = None) -> np.ndarray:
    """Round centres to pixels; a centre whose pixel is taken goes to the nearest free pixel
    (of ``allowed`` when it has one left, so merged-level centres stay on ink).

    Two centroids rarely round to the same pixel (two Lloyd points in a tiny blob), but the
    distribution texture must keep one pixel per stipple.
    """
    pixels = np.clip(np.rint(centres).astype(np.int64), 0, np.array(shape) - 1)
    taken = np.zeros(shape, dtype=bool)
    for index, (row, col) in enumerate(pixels):
        if taken[row, col]:
            free = ~taken if allowed is None or not (allowed & ~taken).any() else allowed & ~taken
            free_rows, free_cols = np.nonzero(free)
            nearest = np.argmin((free_rows - centres[index, 0]) ** 2 + (free_cols - centres[index, 1]) ** 2)
            row, col = free_rows[nearest], free_cols[nearest]
            pixels[index] = (row, col)
        taken[row, col] = True
    return pixels


def _regular_points(blob_rc: np.ndarray, count: int) -> np.ndarray:
    """``count`` blob pixels spread regularly: farthest-point sampling from the pixel nearest
    the blob's centroid (deterministic, the paper's "initial points selected regularly")."""
    first = int(np.argmin(((blob_rc - blob_rc.mean(axis=0)) ** 2).sum(axis=1)))
    chosen = [first]
    distance = ((blob_rc - blob_rc[first]) ** 2).sum(axis=1)
    for _ in range(count - 1):
        chosen.append(int(np.argmax(distance)))
        distance = np.minimum(distance, ((blob_rc - blob_rc[chosen[-1]]) ** 2).sum(axis=1))
    return blob_rc[chosen].astype(float)


def _relax_in_blob(blob: np.ndarray, points_rc: np.ndarray, iterations: int, tol: float) -> tuple[np.ndarray, int]:
    """Lloyd steps whose Voronoi cells are restricted to the blob's pixels (the constraint)."""
    points_xy = points_rc[:, ::-1].copy()
    density = blob.astype(float)
    steps = 0
    while steps < iterations:
        moved, _ = weighted_centroids(points_xy, density)
        steps += 1
        shift = float(np.abs(moved - points_xy).max())
        points_xy = moved
        if shift < tol:
            break
    return points_xy[:, ::-1], steps


def _snap_into(blob_rc: np.ndarray, points_rc: np.ndarray) -> np.ndarray:
    """Move points whose pixel is paper onto the nearest pixel of the blob (centres stay on ink)."""
    _, nearest = cKDTree(blob_rc).query(np.rint(points_rc))
    inside = (np.rint(points_rc) == blob_rc[nearest]).all(axis=1)
    return np.where(inside[:, None], points_rc, blob_rc[nearest].astype(float))


def _merged_centres(ink: np.ndarray, s_avg: float, iterations: int, tol: float) -> tuple[np.ndarray, int]:
    """Constrained Lloyd points of a merged level, blob by blob (see the module docstring)."""
    centres, steps_run = [], 0
    for region in regionprops(label(ink, connectivity=2)):
        top, left = region.bbox[:2]
        blob = region.image
        blob_rc = np.argwhere(blob)
        count = min(len(blob_rc), max(1, int(round(region.area / s_avg))))
        points = _regular_points(blob_rc, count)
        if count > 1:
            points, steps = _relax_in_blob(blob, points, iterations, tol)
            steps_run = max(steps_run, steps)
        else:
            points = blob_rc.mean(axis=0, keepdims=True)
        # snap in image coordinates: np.rint rounds halves to even, so a shift by an odd
        # corner would change which pixel a centre ending in .5 falls on
        corner = np.array([top, left])
        centres.append(_snap_into(blob_rc + corner, points + corner))
    return np.concatenate(centres), steps_run


def _separate_centres(marks: np.ndarray) -> tuple[np.ndarray, float]:
    regions = regionprops(label(marks, connectivity=2))
    centres = np.array([region.centroid for region in regions], dtype=float)
    return centres, float(np.mean([region.area for region in regions]))


def extract_distribution(
    texture,
    level="auto",
    *,
    s_avg=None,
    iterations=LLOYD_ITERATIONS,
    tol=LLOYD_TOLERANCE,
    merge_factor=MERGE_FACTOR,
    merged_share=MERGED_SHARE,
) -> DistributionResult:
    """Example distribution texture of an example stipple texture.

    Parameters
    ----------
    texture : array_like, 2-D
        Bitonal example stipple texture, ``True`` / 1 = ink, holding both ink and paper.
    level : {"auto", "light", "merged", "dark"}, optional
        The texture's level; ``"auto"`` (default) uses :func:`classify_level`.
    s_avg : float, optional
        Merged level only: the size (px) of one stipple, which sets the number of points to
        ``ink area / s_avg`` (split over the blobs). Default: the median 8-connected component
        area of the texture (its dots that did not merge). Pass the ``S_avg`` of a neighbouring
        light tone when the texture has too few separate dots.
    iterations : int, optional
        Maximum constrained Lloyd steps per blob (default 50), >= 1.
    tol : float, optional
        The Lloyd steps stop when no point moves more than ``tol`` pixels (default 1e-3).
    merge_factor, merged_share : float, optional
        Thresholds of :func:`classify_level` (used when ``level="auto"``).

    Returns
    -------
    DistributionResult
        Distribution texture, centres, their pixels, level. Dark levels are analysed on the
        inverted texture (white marks); their distribution marks the white dots' centres.

    Raises
    ------
    ValueError
        Non-bitonal, empty, all-white or all-black texture; unknown level; bad parameters.

    Notes
    -----
    Light and dark levels: the centres are the centroids of the 8-connected components of the
    marks. Merged level: constrained Lloyd relaxation inside each blob of ink (module docstring).
    The result is deterministic: no randomness is involved.

    References
    ----------
    Kim et al. 2009, section 3.2 (connected components with an 8-neighbourhood, the constrained
    Lloyd algorithm of Kim et al. 2008 for merged levels) and Figure 5.
    """
    ink = _checked_texture(texture)
    chosen = _checked_level(level)
    if isinstance(iterations, bool) or not isinstance(iterations, (int, np.integer)) or iterations < 1:
        raise ValueError(f"iterations must be an integer >= 1, got {iterations!r}")
    tol = positive_number(tol, "tol")
    if chosen is None:
        chosen = classify_level(ink, merge_factor=merge_factor, merged_share=merged_share)

    steps = 0
    if chosen == "merged":
        if s_avg is None:
            s_avg = float(np.median(np.bincount(label(ink, connectivity=2).ravel())[1:]))
        s_avg = positive_number(s_avg, "s_avg")
        centres, steps = _merged_centres(ink, s_avg, int(iterations), tol)
    else:
        centres, s_avg = _separate_centres(~ink if chosen == "dark" else ink)

    pixels = _distinct_pixels(centres, ink.shape, ink if chosen == "merged" else None)
    distribution = np.zeros(ink.shape, dtype=bool)
    distribution[pixels[:, 0], pixels[:, 1]] = True
    return DistributionResult(
        distribution=distribution,
        centres=centres,
        pixels=pixels,
        level=chosen,
        white_marks=chosen == "dark",
        s_avg=float(s_avg),
        lloyd_iterations=steps,
    )


# ============================================================================ marks


def extract_marks(texture, level="auto", *, merge_factor=MERGE_FACTOR, merged_share=MERGED_SHARE) -> list[Mark]:
    """The mark library of an example stipple texture: one cropped mask per separate stipple.

    Parameters
    ----------
    texture : array_like, 2-D
        Bitonal example stipple texture, ``True`` / 1 = ink, holding both ink and paper.
    level : {"auto", "light", "merged", "dark"}, optional
        As in :func:`extract_distribution`. Dark levels give white marks (the components of the
        paper); merged levels give only their single stipples, the black components no larger
        than ``merge_factor`` median areas (blobs are not marks).
    merge_factor, merged_share : float, optional
        Thresholds of :func:`classify_level`.

    Returns
    -------
    list of Mark
        In the order of :func:`extract_distribution`'s centres for light and dark levels
        (``regionprops`` label order); each mark's ``offset`` is its centre pixel (the rounded
        centroid) relative to its bounding box.

    Raises
    ------
    ValueError
        As :func:`extract_distribution`.

    References
    ----------
    Kim et al. 2009, section 3.2 ("the segmented stipples are then stored for future use in
    the marker placement step") and section 4.2 (black and white marks).
    """
    ink = _checked_texture(texture)
    chosen = _checked_level(level) or classify_level(ink, merge_factor=merge_factor, merged_share=merged_share)
    white = chosen == "dark"
    regions = regionprops(label(~ink if white else ink, connectivity=2))
    if chosen == "merged":
        largest = positive_number(merge_factor, "merge_factor") * np.median([region.area for region in regions])
        regions = [region for region in regions if region.area <= largest]
    centres = np.array([region.centroid for region in regions], dtype=float).reshape(-1, 2)
    pixels = _distinct_pixels(centres, ink.shape)
    return [
        Mark(mask=region.image.copy(), offset=(int(row - region.bbox[0]), int(col - region.bbox[1])), white=white)
        for region, (row, col) in zip(regions, pixels, strict=True)
    ]
