"""Perceptual measures between elements and the matching rule (Barla 2006, section 3.1).

Each measure compares a reference element with a target element "in their respective frame; i.e., the
element centers are first aligned":

- ``shape``: symmetric Hausdorff distance between the two boxes (centres aligned), for isotropic elements;
- ``par``: the angle between the principal axes (folded into [0, pi/2]: an axis has no direction);
- ``ov``: overlapping, ``max(|A_ref| / |A_tar|, |A_tar| / |A_ref|)`` with ``|A|`` the principal-axis length;
- ``sup``: superimposition, ``| |B_ref| - |B_tar| |`` with ``|B|`` the secondary-axis length (thickness);
- ``col``: the RGB distance between colours in [0, 1].

Averaged over the paired elements of two neighbourhoods, each is compared with its threshold (sigma_shape =
0.1 L, sigma_par = pi/20, sigma_ov = 1.5, sigma_sup = 0.1 L, sigma_col = 0.15, L the average reference
element length) and combined by ``col and (shape or (par and ov and sup))``.

Because a synthesised element is a copy of a reference element, every pair compares two reference elements:
the five measures are tabulated once for all pairs of reference elements (:func:`measure_tables`) and the
synthesis only looks them up.

Written out, the rule is a single number: with ``r_m = m / sigma_m`` (and m < sigma_m iff r_m < 1),
``col and (shape or (par and ov and sup))`` holds iff
``max(r_col, min(r_shape, max(r_par, r_ov, r_sup))) < 1``. That *rule score* (:func:`rule_score`) is how
the synthesis tests candidates, and its smallest value picks the documented fallback when no candidate
passes.

References
----------
.. [1] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern Analysis and Synthesis",
   Computer Graphics Forum (Eurographics) 25(3), 2006, section 3.1 and Figure 4.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._checks import finite_array, positive_number
from ..geometry import hausdorff_boxes

__all__ = ["MEASURES", "Thresholds", "measure_tables", "rule_score"]

#: Order of the measures in every table and threshold vector.
MEASURES = ("shape", "par", "ov", "sup", "col")


@dataclass(frozen=True)
class Thresholds:
    """Perceptual thresholds of section 3.1; ``shape`` and ``sup`` are fractions of L, the mean element length.

    The defaults are the paper's: sigma_shape = 0.1 L, sigma_par = pi / 20, sigma_ov = 1.5, sigma_sup = 0.1 L,
    sigma_col = 0.15.

    Parameters
    ----------
    shape : float, default 0.1
        sigma_shape as a fraction of the mean element length L.
    par : float, default pi / 20
        sigma_par, radians.
    ov : float, default 1.5
        sigma_ov (a ratio of lengths).
    sup : float, default 0.1
        sigma_sup as a fraction of the mean element length L.
    col : float, default 0.15
        sigma_col (an RGB distance).
    """

    shape: float = 0.1
    par: float = np.pi / 20.0
    ov: float = 1.5
    sup: float = 0.1
    col: float = 0.15

    def __post_init__(self):
        for name in MEASURES:
            object.__setattr__(self, name, positive_number(getattr(self, name), f"threshold {name}"))
        if self.ov <= 1.0:
            raise ValueError(f"threshold ov is a ratio of lengths and must exceed 1, got {self.ov!r}")

    def vector(self, mean_length: float) -> np.ndarray:
        """The five thresholds in :data:`MEASURES` order, shape and sup scaled by ``mean_length``.

        Parameters
        ----------
        mean_length : float
            L, the mean element length, in the pattern's units.

        Returns
        -------
        ndarray of float64, shape (5,)
            ``(shape L, par, ov, sup L, col)``.
        """
        return np.array([self.shape * mean_length, self.par, self.ov, self.sup * mean_length, self.col])


def rule_score(means, sigmas) -> np.ndarray:
    """``max(r_col, min(r_shape, max(r_par, r_ov, r_sup)))`` with ``r_m = mean_m / sigma_m``; < 1 iff matching.

    ``means`` has the measures on its last axis, in :data:`MEASURES` order.

    Parameters
    ----------
    means : array_like, shape (..., 5)
        Mean measures, in :data:`MEASURES` order on the last axis.
    sigmas : array_like, shape (5,)
        The thresholds (positive, finite; :meth:`Thresholds.vector`).

    Returns
    -------
    ndarray of float64, shape (...)
        The rule score; below 1 where the neighbourhoods match.
    """
    for value, name in ((means, "means"), (sigmas, "sigmas")):
        if isinstance(value, (str, bytes)):
            raise ValueError(f"{name} must be an array of numbers, got {type(value).__name__}")
        try:
            np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError, OverflowError):
            raise ValueError(f"{name} must be an array of numbers, got {type(value).__name__}") from None
    means, sigmas = np.asarray(means, dtype=np.float64), np.asarray(sigmas, dtype=np.float64)
    if means.ndim < 1 or means.shape[-1] != len(MEASURES):
        raise ValueError(f"means must hold the {len(MEASURES)} measures {MEASURES} on its last axis, got shape "
                         f"{means.shape}")
    if sigmas.shape != (len(MEASURES),) or not (np.isfinite(sigmas).all() and (sigmas > 0).all()):
        raise ValueError(f"sigmas must be {len(MEASURES)} positive finite thresholds, got {sigmas!r}")
    r = means / sigmas
    shape, par, ov, sup, col = np.moveaxis(r, -1, 0)
    return np.maximum(col, np.minimum(shape, np.maximum.reduce([par, ov, sup])))


def _local_corners(half_lengths, angles) -> np.ndarray:
    """Box corners centred at the origin, ``(n, 4, 2)``, at the given angles."""
    unit = np.array([(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)])
    cos, sin = np.cos(angles), np.sin(angles)
    local = unit[None] * half_lengths[:, None, :]
    x, y = local[..., 0], local[..., 1]
    return np.stack([cos[:, None] * x - sin[:, None] * y, sin[:, None] * x + cos[:, None] * y], axis=-1)


def measure_tables(half_lengths, angles, colors) -> np.ndarray:
    """The five measures between every pair of reference elements, shape ``(5, n, n)``.

    Parameters
    ----------
    half_lengths : array_like, shape (n, 2)
        Box half lengths (major, minor).
    angles : array_like, shape (n,)
        Major-axis angles *in each element's local frame* (box angle minus frame angle).
    colors : array_like, shape (n, 3)
        RGB in [0, 1].

    Returns
    -------
    ndarray of float64, shape (5, n, n)
        ``[m, i, j]``: measure ``m`` (``shape``, ``par``, ``ov``, ``sup``, ``col``, :data:`MEASURES`
        order) between elements ``i`` and ``j``; symmetric in ``i, j``.

    Notes
    -----
    ``ov`` of two zero-length elements is 1 and of a zero-length and a non-zero-length one is inf.

    References
    ----------
    Barla et al. 2006, section 3.1 (the four geometric measures and the colour distance).
    """
    angles = finite_array(angles, "angles", ndim=1)
    n = len(angles)
    half_lengths = finite_array(half_lengths, "half_lengths", shape=(n, 2))
    colors = finite_array(colors, "colors", shape=(n, 3))
    corners = _local_corners(half_lengths, angles)
    shape = hausdorff_boxes(corners[:, None], corners[None, :]).reshape(n, n)
    difference = np.mod(angles[:, None] - angles[None, :], np.pi)
    par = np.minimum(difference, np.pi - difference)
    major = 2.0 * half_lengths[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = major[:, None] / major[None, :]
        ov = np.maximum(ratio, 1.0 / ratio)
    ov[(major[:, None] == 0) & (major[None, :] == 0)] = 1.0
    minor = 2.0 * half_lengths[:, 1]
    sup = np.abs(minor[:, None] - minor[None, :])
    col = np.sqrt(((colors[:, None, :] - colors[None, :, :]) ** 2).sum(axis=-1))
    return np.stack([shape, par, ov, sup, col])
