"""Spacing and homogeneity of stipple distributions, measured apart from the GLCM objective.

Kim et al. 2009 judge a synthesized distribution by its GLCM statistics (section 3.5, Fig. 8),
the very quantities the synthesis minimises (eq. 5). For a sparse distribution texture (one ink
pixel per stipple) the 2x2 GLCMs along three lines of offsets say little about how far apart the
stipples are: a texture of the example's density placed at random (CSR) fits them almost as
well. These measures look at the stipples as a point pattern instead, the way the field
compares point distributions (nearest-neighbour distances, pair correlation; e.g. Illian et al.
2008, chapters 4.2 and 4.3), and at the large-scale homogeneity of a tile:

- :func:`nearest_neighbour_distances`: the distance from every stipple to its nearest other
  stipple (the paper's O_min / O_avg / O_max are its minimum, mean and maximum, section 3.2);
- :func:`pair_correlation`: the pair correlation function g(r) of the stipple centres, estimated
  by :func:`paperlib.pointprocess.pcf` (spatstat's ``pcf.ppp``, translation correction);
- :func:`compare_spacing`: a texture against a reference (the example): the two-sample
  Kolmogorov-Smirnov statistic of their nearest-neighbour distances and the root mean square
  difference of their pair correlation functions over ``(0, 2.5]`` mean spacings;
- :func:`block_dispersion`: variance-to-mean ratio of the ink counts of square blocks (1 for
  Poisson counts, below 1 for evenly spread stipples, far above 1 for bands and holes).

Stipple pixels are points at their pixel centres ``(col + 0.5, row + 0.5)`` in the window
``[0, width] x [0, height]``; distances are not periodic, so compare textures of equal size.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree
from scipy.stats import ks_2samp

from ..pointprocess import PointPattern, Window, pcf
from .glcm import _checked_bitonal

__all__ = [
    "SpacingComparison",
    "block_dispersion",
    "compare_spacing",
    "nearest_neighbour_distances",
    "pair_correlation",
    "stipple_pattern",
]

#: Pair correlation functions are compared over r in (0, PCF_REACH / sqrt(intensity)].
PCF_REACH = 2.5
#: Number of r values of the comparison grid.
PCF_STEPS = 101


def _stipple_pixels(texture, name: str) -> tuple[np.ndarray, tuple[int, int]]:
    """(row, col) of the ink pixels of a bitonal texture holding at least two of them."""
    ink = _checked_bitonal(texture, "texture")
    pixels = np.argwhere(ink)
    if len(pixels) < 2:
        raise ValueError(f"{name} has {len(pixels)} stipple pixel(s): need at least 2 to measure spacing")
    return pixels, ink.shape


def stipple_pattern(texture) -> PointPattern:
    """The stipple pixels of a distribution texture as a point pattern (x = column, y = row).

    Parameters
    ----------
    texture : array_like, 2-D
        A bitonal distribution texture (bool or 0/1) with at least two ink pixels.

    Returns
    -------
    PointPattern
        One point per ink pixel, at the pixel centre ``(column + 0.5, row + 0.5)``, in the window
        ``[0, width] x [0, height]``.

    Raises
    ------
    ValueError
        Non-bitonal texture or fewer than two stipple pixels.
    """
    pixels, (height, width) = _stipple_pixels(texture, "texture")
    window = Window.rectangle((0.0, float(width)), (0.0, float(height)))
    return PointPattern(pixels[:, ::-1] + 0.5, window)


def nearest_neighbour_distances(texture) -> np.ndarray:
    """Distance (px) from every stipple pixel to its nearest other stipple pixel, not periodic.

    Their minimum, mean and maximum are the paper's O_min, O_avg and O_max when the texture
    holds one pixel per stipple (an example distribution texture, Kim et al. 2009, 3.2).

    Parameters
    ----------
    texture : array_like, 2-D
        A bitonal texture (bool or 0/1) with at least two ink pixels.

    Returns
    -------
    ndarray of float64, shape (n,)
        For each of the ``n`` ink pixels, in row-major order, the distance in pixels to the
        nearest other ink pixel.

    Raises
    ------
    ValueError
        Non-bitonal texture or fewer than two stipple pixels.
    """
    pixels, _ = _stipple_pixels(texture, "texture")
    return cKDTree(pixels).query(pixels, k=2)[0][:, 1]


def _comparison_grid(reference: PointPattern) -> np.ndarray:
    spacing = 1.0 / np.sqrt(len(reference.points) / reference.window.area)
    return np.linspace(0.0, PCF_REACH * spacing, PCF_STEPS)


def _bandwidth(reference: PointPattern) -> float:
    """spatstat's default kernel width for ``reference`` (Stoyan's rule, 0.15 / sqrt(5 lambda))."""
    return 0.15 / np.sqrt(5.0 * len(reference.points) / reference.window.area)


def pair_correlation(texture, r=None, *, bw=None) -> np.ndarray:
    """Pair correlation g(r) of the stipple pixels (translation correction), at radii ``r``.

    Parameters
    ----------
    texture : array_like, 2-D
        Bitonal distribution texture, ``True`` = stipple.
    r : array_like, optional
        Increasing radii from 0 (px); default 0 .. 2.5 mean spacings in 101 steps.
    bw : float, optional
        Kernel standard deviation (px); default spatstat's for this texture's intensity. Pass
        the reference's when comparing two textures, so both are smoothed alike.

    Returns
    -------
    numpy.ndarray
        g at every r: 1 for complete spatial randomness, 0 below a hard core.
    """
    pattern = stipple_pattern(texture)
    grid = _comparison_grid(pattern) if r is None else np.asarray(r, dtype=float)
    table = pcf(pattern, grid, correction="translate", bw=_bandwidth(pattern) if bw is None else bw)
    return table["trans"].to_numpy()


@dataclass(frozen=True)
class SpacingComparison:
    """How far a distribution texture's spacing is from a reference's.

    Parameters
    ----------
    nn_ks : float
        Two-sample Kolmogorov-Smirnov statistic (0 .. 1) of the nearest-neighbour distances.
    pcf_rms : float
        Root mean square of ``g_texture(r) - g_reference(r)`` over the grid ``r``.
    r : numpy.ndarray
        Radii (px) of the comparison: 0 .. 2.5 mean spacings of the reference.
    g_reference, g_texture : numpy.ndarray
        The two pair correlation functions, with the reference's kernel width.
    nn_reference, nn_texture : numpy.ndarray
        The two sets of nearest-neighbour distances (px).
    """

    nn_ks: float
    pcf_rms: float
    r: np.ndarray
    g_reference: np.ndarray
    g_texture: np.ndarray
    nn_reference: np.ndarray
    nn_texture: np.ndarray


def compare_spacing(reference, texture) -> SpacingComparison:
    """Compare the stipple spacing of ``texture`` with that of ``reference`` (e.g. its example).

    Both are bitonal distribution textures of the same shape. The pair correlation functions
    are estimated on the reference's grid with the reference's kernel width; the first radius
    (0) is left out of the root mean square, where the kernel estimate is not defined.

    Parameters
    ----------
    reference : array_like, 2-D
        The reference bitonal distribution texture (one ink pixel per stipple), at least two stipples.
    texture : array_like, 2-D
        The distribution texture to compare, of the same shape, at least two stipples.

    Returns
    -------
    SpacingComparison
        The KS statistic of the nearest-neighbour distances, the RMS difference of the pair
        correlation functions, and the curves and distances they come from.

    Raises
    ------
    ValueError
        Non-bitonal textures, fewer than two stipples in either, or different shapes.
    """
    first, second = _checked_bitonal(reference, "reference"), _checked_bitonal(texture, "texture")
    if first.shape != second.shape:
        raise ValueError(
            f"reference {first.shape} and texture {second.shape} differ in shape: spacing measures are not "
            "periodic, so compare textures of equal size"
        )
    pattern = stipple_pattern(first)
    grid, width = _comparison_grid(pattern), _bandwidth(pattern)
    g_reference = pair_correlation(first, grid, bw=width)
    g_texture = pair_correlation(second, grid, bw=width)
    nn_reference, nn_texture = nearest_neighbour_distances(first), nearest_neighbour_distances(second)
    return SpacingComparison(
        nn_ks=float(ks_2samp(nn_reference, nn_texture).statistic),
        pcf_rms=float(np.sqrt(np.mean((g_texture[1:] - g_reference[1:]) ** 2))),
        r=grid,
        g_reference=g_reference,
        g_texture=g_texture,
        nn_reference=nn_reference,
        nn_texture=nn_texture,
    )


def block_dispersion(texture, block: int = 32) -> float:
    """Variance-to-mean ratio of the ink counts of the texture's whole ``block x block`` blocks.

    About 1 for ink placed independently (Poisson counts), well below 1 for evenly spread
    stipples, and far above 1 when a tile has bands or holes (Kim et al. 2009, Fig. 7's tiles
    should be as homogeneous as their examples).

    Parameters
    ----------
    texture : array_like, 2-D
        A bitonal texture (bool or 0/1), ink ``True``/1.
    block : int, default 32
        Block side in pixels (>= 1); partial blocks at the right and bottom edges are left out.

    Returns
    -------
    float
        Sample variance (ddof 1) over mean of the ink pixel counts per block.

    Raises
    ------
    ValueError
        Non-bitonal texture, a block side < 1, fewer than two whole blocks, or no ink.
    """
    ink = _checked_bitonal(texture, "texture")
    if isinstance(block, bool) or not isinstance(block, (int, np.integer)) or block < 1:
        raise ValueError(f"block must be a positive integer (pixels), got {block!r}")
    rows, cols = ink.shape[0] // block, ink.shape[1] // block
    if rows * cols < 2:
        raise ValueError(f"texture of shape {ink.shape} holds {rows * cols} whole {block}-px block(s): need at least 2")
    counts = ink[: rows * block, : cols * block].reshape(rows, block, cols, block).sum(axis=(1, 3)).ravel()
    if counts.mean() == 0:
        raise ValueError("texture has no ink in its whole blocks: dispersion is undefined")
    return float(counts.var(ddof=1) / counts.mean())
