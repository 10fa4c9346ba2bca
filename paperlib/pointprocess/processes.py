"""Reference processes with exact samplers: Poisson (CSR) and Matérn cluster.

These are the "random" and "clustered" patterns the Ripley-L figures compare with
regular ones, and the null model of simulation envelopes. Names follow spatstat
(``rpoispp``, ``rMatClust``).
"""

from __future__ import annotations

import numpy as np

from paperlib._checks import as_generator, budget, check_budget, finite_array, positive_number

from .pattern import PointPattern
from .window import Window

__all__ = ["rMatClust", "rpoispp"]


#: Default budget of :func:`rpoispp`: the expected number of points, intensity x area, summed over types.
MAX_EXPECTED_POINTS = 10**7


def _check_window(window) -> Window:
    if not isinstance(window, Window):
        raise ValueError(f"window must be a paperlib.pointprocess.Window, got {type(window).__name__}")
    return window


def rpoispp(intensity, window: Window, *, categories=None, rng=None,
            max_points: int = MAX_EXPECTED_POINTS) -> PointPattern:
    """Homogeneous Poisson process (complete spatial randomness), one intensity per type.

    Parameters
    ----------
    intensity : float or array_like of float
        Expected points per unit area of each type (>= 0).
    window : Window
    categories : sequence of str, optional
        Type names, one per intensity.
    rng : None, int or numpy.random.Generator
    max_points : int, optional
        Budget: the largest expected number of points, ``sum(intensity) * area`` (default
        :data:`MAX_EXPECTED_POINTS`, 10**7), checked before drawing.

    Returns
    -------
    PointPattern
        Types are independent Poisson processes: counts ~ Poisson(intensity |W|),
        locations uniform in the window.
    """
    window = _check_window(window)
    intensity = np.atleast_1d(finite_array(intensity, "intensity"))
    for value in intensity:
        positive_number(value, "intensity", allow_zero=True)
    check_budget(float(intensity.sum() * window.area), budget(max_points, "max_points"), "max_points",
                 "expected points (intensity x area)")
    rng = as_generator(rng)
    counts = rng.poisson(intensity * window.area)
    points = window.uniform_points(int(counts.sum()), rng)
    marks = np.repeat(np.arange(len(intensity)), counts)
    if categories is None and len(intensity) > 1:
        categories = tuple(str(i) for i in range(len(intensity)))
    return PointPattern(points, window, marks, categories)


def rMatClust(kappa: float, scale: float, mu: float, window: Window, *, rng=None) -> PointPattern:
    """Matérn cluster process: Poisson parents, Poisson(mu) children uniform in a disc.

    Parents (intensity ``kappa``) are drawn in the window dilated by ``scale`` so that
    clusters straddling the edge are not thinned (no edge effect); each has a
    Poisson(``mu``) number of children uniform in the disc of radius ``scale`` around
    it; children outside the window are dropped. Intensity: ``kappa * mu``.

    Parameters
    ----------
    kappa : float
        Intensity of the parents (> 0), points per unit area.
    scale : float
        Radius of the clusters' discs (> 0).
    mu : float
        Mean number of children per parent (> 0).
    window : Window
        The observation window.
    rng : None, int or numpy.random.Generator, optional
        Source of randomness.

    Returns
    -------
    PointPattern
        The children inside ``window`` (an unmarked pattern, repeated points dropped).

    References
    ----------
    Matérn, B. (1960). Spatial variation. spatstat's ``rMatClust``.
    """
    window = _check_window(window)
    kappa, scale, mu = positive_number(kappa, "kappa"), positive_number(scale, "scale"), positive_number(mu, "mu")
    rng = as_generator(rng)
    frame = Window.rectangle(
        (window.xrange[0] - scale, window.xrange[1] + scale), (window.yrange[0] - scale, window.yrange[1] + scale)
    )
    parents = frame.uniform_points(int(rng.poisson(kappa * frame.area)), rng)
    n_children = rng.poisson(mu, size=len(parents))
    radius = scale * np.sqrt(rng.random(n_children.sum()))
    angle = 2 * np.pi * rng.random(n_children.sum())
    children = np.repeat(parents, n_children, axis=0) + radius[:, None] * np.column_stack([np.cos(angle), np.sin(angle)])
    children = children[window.contains(children)]
    return PointPattern(_without_duplicates(children), window)


def _without_duplicates(points: np.ndarray) -> np.ndarray:
    """Continuous draws coincide with probability 0; drop exact repeats (a PointPattern would warn)."""
    _, first = np.unique(points, axis=0, return_index=True)
    return points[np.sort(first)]
