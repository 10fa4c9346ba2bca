"""Gibbs point process models: Poisson, Strauss, StraussHard, MultiStraussHard.

Hurtut 2009, section 3.1, eq. (2): the density of a multitype pairwise-interaction process

    f(x) ∝ prod_i beta_{m_i} · prod_{i<j} c_{m_i m_j}(x_i, x_j),

with the Strauss hard-core interaction c = 0 when d < h, gamma when h <= d < r, 1
otherwise. Its Papangelou conditional intensity at a location u of type m is

    lambda(u, m; x) = beta_m · prod_j gamma_{m m_j}^{1[h <= d(u, x_j) < r]}   (0 if any d < h),

which is all that pseudolikelihood fitting (section 3.2.3, eq. 3) and Metropolis-Hastings
(section 3.3, Figure 4) need. Every model here is stored in that general multitype form
(:class:`MultiStraussHard`); the single-type models are constructors with spatstat's names.

Distance conventions (see ``shared/notes/spatstat_conventions.md``): by default
``closed=False``, a pair interacts when d < r and is forbidden when d < h (the paper's
definition, spatstat's ``MultiStraussHard`` and ``rmh``). ``closed=True`` counts d <= r and
forbids d <= h, as spatstat's ``Strauss``/``StraussHard`` fits do; the two differ only on
exact ties, which gridded data sets (``cells``, ``swedishpines``) do contain.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from paperlib._checks import check_flag, finite_array, float_array, instance_of, integer_array

__all__ = ["MultiStraussHard", "PairDistance", "Poisson", "Strauss", "StraussHard", "interaction_counts",
           "interaction_pairs"]


def _square(values, m: int, name: str, *, positive: bool = False) -> np.ndarray:
    """A symmetric ``(m, m)`` float array from a scalar or a matrix, validated."""
    array = np.array(float_array(values, name, f"a number or a {m}x{m} matrix of numbers"))
    if array.ndim == 0:
        array = np.full((m, m), float(array))
    if array.shape != (m, m):
        raise ValueError(f"{name} must be a scalar or a {m}x{m} matrix, got shape {array.shape}")
    if not np.isfinite(array).all():
        raise ValueError(f"{name} must be finite")
    if not np.allclose(array, array.T, rtol=0, atol=0):
        raise ValueError(f"{name} must be symmetric (interactions are symmetric, Hurtut section 3.1)")
    if (array < 0).any() or (positive and (array <= 0).any()):
        raise ValueError(f"{name} must be {'positive' if positive else 'non-negative'}, got {array.tolist()}")
    array.setflags(write=False)
    return array


@dataclass(frozen=True, eq=False)
class MultiStraussHard:
    """Multitype Strauss hard-core model (Hurtut 2009, eq. 2; spatstat ``MultiStraussHard``).

    Parameters
    ----------
    beta : array_like, shape (M,)
        Per-type intensity parameter (the paper's occurrence constants ``d_m``), > 0.
    gamma : float or array_like, shape (M, M)
        Symmetric interaction strengths, >= 0 (the paper restricts to [0, 1]; values
        above 1 are allowed, as in spatstat, but such models are not stable for
        simulation without a hard core).
    r : float or array_like, shape (M, M)
        Symmetric interaction radii, > 0.
    hc : float or array_like, shape (M, M)
        Symmetric hard-core distances, 0 <= hc <= r.
    categories : sequence of str, optional
        Type names (default ``"0", "1", ...``).
    closed : bool
        Count pairs with d <= r and forbid d <= hc (spatstat's single-type Strauss and
        StraussHard) instead of d < r and d < hc (default; the paper, ``rmh``).
    """

    beta: np.ndarray
    gamma: np.ndarray = 1.0
    r: np.ndarray = 1.0
    hc: np.ndarray = 0.0
    categories: tuple | None = None
    closed: bool = False

    def __post_init__(self):
        beta = np.array(float_array(self.beta, "beta", "positive numbers, one per type")).reshape(-1)
        if beta.size == 0 or not np.isfinite(beta).all() or (beta <= 0).any():
            raise ValueError(f"beta must be positive and finite, one per type, got {self.beta!r}")
        beta.setflags(write=False)
        m = beta.size
        gamma = _square(self.gamma, m, "gamma")
        r = _square(self.r, m, "r", positive=True)
        hc = _square(self.hc, m, "hc")
        if (hc > r).any():
            raise ValueError(f"hard-core distances must not exceed interaction radii (hc <= r): hc={hc.tolist()}, r={r.tolist()}")
        categories = tuple(str(c) for c in self.categories) if self.categories is not None else tuple(
            str(i) for i in range(m)
        )
        if len(categories) != m or len(set(categories)) != m:
            raise ValueError(f"categories must be {m} distinct names, got {categories}")
        for name, value in (("beta", beta), ("gamma", gamma), ("r", r), ("hc", hc), ("categories", categories)):
            object.__setattr__(self, name, value)
        object.__setattr__(self, "closed", check_flag(self.closed, "closed"))

    @property
    def n_types(self) -> int:
        return self.beta.size

    @property
    def reach(self) -> float:
        """The largest interaction distance: beyond it points do not interact."""
        return float(self.r.max())

    @property
    def hard_core_only(self) -> bool:
        return bool(np.all(self.gamma == 1.0))

    def log_conditional_intensity(self, locations, types, pattern_points, pattern_marks, exclude=None) -> np.ndarray:
        """log lambda(u, m; x) at many locations at once (``-inf`` where forbidden).

        Parameters
        ----------
        locations : array_like, shape (k, 2)
        types : array_like of int, shape (k,)
            Type of the point proposed at each location.
        pattern_points : array_like, shape (n, 2)
            The configuration x.
        pattern_marks : array_like of int, shape (n,)
        exclude : array_like of int, shape (k,), optional
            Index in the pattern of a point to leave out for each location (-1: none):
            lambda(x_i; x minus x_i) at data point i needs ``exclude[i] = i``.

        Returns
        -------
        ndarray of float64, shape (k,)
            log lambda(u_i, m_i; x) = log beta_{m_i} + sum_t c_{it} log gamma_{m_i t}, with c_{it} the
            number of pattern points of type t in the Strauss shell of location i; ``-inf`` where a
            pattern point lies in the hard core or a gamma of 0 meets a neighbour.
        """
        types = np.asarray(types, dtype=np.int64)
        counts, forbidden = interaction_counts(self, locations, types, pattern_points, pattern_marks, exclude)
        gamma = self.gamma[types]
        # gamma = 0 forbids only when a neighbour is actually in the shell (0^0 = 1)
        killed = ((counts > 0) & (gamma == 0)).any(axis=1)
        log_lambda = np.log(self.beta[types]) + (counts * np.log(np.where(gamma > 0, gamma, 1.0))).sum(axis=1)
        return np.where(forbidden | killed, -np.inf, log_lambda)

    def __repr__(self) -> str:
        return (
            f"MultiStraussHard(categories={self.categories}, beta={self.beta.tolist()}, gamma={self.gamma.tolist()}, "
            f"r={self.r.tolist()}, hc={self.hc.tolist()}, closed={self.closed})"
        )


def interaction_pairs(model, locations, types, pattern_points, pattern_marks, exclude=None, pair_distance=None):
    """Pairs (location i, pattern point j) closer than the model's reach, classified.

    The one place where the Strauss shell and hard-core rules (and the distances, taken
    from cKDTree so that ties are decided the same way everywhere) are applied.

    Parameters
    ----------
    model : MultiStraussHard
    locations : array_like, shape (k, 2)
    types : array_like of int, shape (k,)
    pattern_points : array_like, shape (n, 2)
    pattern_marks : array_like of int, shape (n,)
    exclude : array_like of int, shape (k,), optional
        Pattern index to leave out for each location (-1: none).
    pair_distance : PairDistance, optional
        Distances between the objects at the points (e.g. elements' bounding boxes, Hurtut
        2009, section 4.3), used instead of the distances between the points.

    Returns
    -------
    i, j : ndarray of int
        Location and pattern indices of every pair within the reach.
    in_shell : ndarray of bool
        ``hc <= d < r`` for the pair's types (``hc < d <= r`` when ``model.closed``, ``0 <= d <= r``
        when closed with ``hc = 0``: coincident points interact).
    inside_core : ndarray of bool
        ``d < hc`` (``d <= hc`` with ``hc > 0`` when ``model.closed``).
    """
    instance_of(model, MultiStraussHard, "model")
    locations, pattern_points = _flat_points(locations, "locations"), _flat_points(pattern_points, "pattern_points")
    types, pattern_marks = integer_array(types, "types").reshape(-1), integer_array(pattern_marks, "pattern_marks").reshape(-1)
    k, m = len(locations), model.n_types
    if types.shape != (k,) or pattern_marks.shape != (len(pattern_points),):
        raise ValueError("one type per location and one mark per pattern point are needed")
    if k and (types.min() < 0 or types.max() >= m) or len(pattern_marks) and (
        pattern_marks.min() < 0 or pattern_marks.max() >= m
    ):
        raise ValueError(f"types and marks must lie in 0..{m - 1}")
    if k == 0 or len(pattern_points) == 0:
        empty = np.zeros(0, dtype=np.int64)
        return empty, empty, np.zeros(0, bool), np.zeros(0, bool)
    padding = 0.0 if pair_distance is None else instance_of(pair_distance, PairDistance, "pair_distance").padding
    pairs = cKDTree(locations).sparse_distance_matrix(cKDTree(pattern_points), model.reach + padding,
                                                      output_type="ndarray")
    # the "ndarray" output keeps pairs at distance 0 (dummy copies of data points need them)
    i, j, d = pairs["i"].astype(np.int64), pairs["j"].astype(np.int64), pairs["v"]
    if exclude is not None:
        exclude = integer_array(exclude, "exclude").reshape(-1)
        if exclude.shape != (k,):
            raise ValueError(f"exclude must have one entry per location ({k}), got shape {exclude.shape}")
        keep = exclude[i] != j
        i, j, d = i[keep], j[keep], d[keep]
    if pair_distance is not None:
        d = _object_distances(pair_distance, i, j, d)
    r, hc = model.r[types[i], pattern_marks[j]], model.hc[types[i], pattern_marks[j]]
    if model.closed:  # hc = 0: no hard core, and a pair at distance 0 interacts (spatstat's Strauss, d <= r)
        inside_core, in_shell = (d <= hc) & (hc > 0), ((d > hc) | (hc == 0)) & (d <= r)
    else:
        inside_core, in_shell = d < hc, (d >= hc) & (d < r)
    return i, j, in_shell, inside_core


def _flat_points(values, name: str) -> np.ndarray:
    """Finite coordinates as an (n, 2) array (any shape holding pairs: a single point may be (2,))."""
    array = finite_array(values, name)
    if array.size % 2:
        raise ValueError(f"{name} must hold (x, y) pairs, got shape {array.shape}")
    return array.reshape(-1, 2)


@dataclass(frozen=True)
class PairDistance:
    """A distance between the objects carried by points, for the interactions of a model.

    Parameters
    ----------
    distance : callable
        ``distance(i, j) -> d``: distances between the objects at locations ``i`` and at
        pattern points ``j`` (integer arrays of one length; which locations and points is the
        caller's convention, e.g. quadrature points and data points in :func:`ppm`).
    padding : float
        How much shorter than the distance between the two points an object distance can be
        (>= 0): ``d >= |x_i - x_j| - padding`` for every pair. 0 for the Hausdorff distance
        between centrally symmetric shapes centred on the points; the sum of the two largest
        object radii for the gap between shapes. Pairs are searched among points closer than
        the model's reach plus ``padding``.
    """

    distance: object
    padding: float = 0.0

    def __post_init__(self):
        if not callable(self.distance):
            raise TypeError("PairDistance.distance must be callable as distance(i, j)")
        if not (np.isfinite(self.padding) and self.padding >= 0):
            raise ValueError(f"padding must be finite and >= 0, got {self.padding!r}")


def _object_distances(pair_distance: PairDistance, i, j, point_distance) -> np.ndarray:
    """Distances between the objects of candidate pairs, checked against the padding."""
    d = np.asarray(pair_distance.distance(i, j), dtype=np.float64).reshape(-1)
    if d.shape != point_distance.shape:
        raise ValueError(f"pair_distance returned {d.shape[0]} distances for {point_distance.shape[0]} pairs")
    slack = 1e-12 * np.maximum(point_distance, 1.0)
    if (d < point_distance - pair_distance.padding - slack).any():
        raise ValueError("pair_distance returned a distance shorter than the points' distance minus its padding: "
                         "pairs beyond the searched range could interact and would be missed")
    return d


def interaction_counts(model, locations, types, pattern_points, pattern_marks, exclude=None, pair_distance=None):
    """Neighbour counts per type in the Strauss shell, and hard-core violations.

    Parameters are those of :func:`interaction_pairs`.

    Parameters
    ----------
    model : MultiStraussHard
        The model whose shells and hard cores are applied.
    locations : array_like, shape (k, 2)
        Locations u_i.
    types : array_like of int, shape (k,)
        Type proposed at each location.
    pattern_points : array_like, shape (n, 2)
        The configuration x.
    pattern_marks : array_like of int, shape (n,)
        Type of each pattern point.
    exclude : array_like of int, shape (k,), optional
        Pattern index to leave out for each location (-1: none).
    pair_distance : PairDistance, optional
        Distances between the objects at the points, used instead of the distances between
        the points (see :func:`interaction_pairs`).

    Returns
    -------
    counts : ndarray, shape (k, M)
        ``counts[i, t]`` = number of pattern points of type t in the shell of location i.
    forbidden : ndarray of bool, shape (k,)
        Whether some pattern point lies within the hard core of location i.
    """
    i, j, in_shell, inside_core = interaction_pairs(model, locations, types, pattern_points, pattern_marks, exclude,
                                                    pair_distance)
    k = len(np.asarray(locations).reshape(-1, 2))
    counts = np.zeros((k, model.n_types), dtype=np.int64)
    forbidden = np.zeros(k, dtype=bool)
    forbidden[i[inside_core]] = True
    np.add.at(counts, (i[in_shell], np.asarray(pattern_marks, dtype=np.int64).reshape(-1)[j[in_shell]]), 1)
    return counts, forbidden


def Poisson(beta, categories=None) -> MultiStraussHard:
    """Poisson process (no interaction) with intensity ``beta`` per type.

    Parameters
    ----------
    beta : array_like, shape (M,)
        Intensity of each type (positive, finite).
    categories : sequence, optional
        Names of the M types.

    Returns
    -------
    MultiStraussHard
        The model with ``gamma = 1`` (and ``hc = 0``): no interaction.
    """
    return MultiStraussHard(beta, gamma=1.0, r=1.0, hc=0.0, categories=categories)


def Strauss(beta, gamma, r, *, closed=True) -> MultiStraussHard:
    """Strauss process (spatstat ``Strauss(r)``): pairs closer than r weigh ``gamma``.

    Parameters
    ----------
    beta : float
        Intensity parameter (> 0).
    gamma : float
        Interaction parameter, in ``[0, 1]`` for a valid (inhibitory) process.
    r : float
        Interaction distance (> 0).
    closed : bool, default True
        Count pairs with ``d <= r``, as spatstat's Strauss does (``d < r`` when False).

    Returns
    -------
    MultiStraussHard
        The single-type model with ``hc = 0``.
    """
    return MultiStraussHard([beta], gamma=gamma, r=r, hc=0.0, closed=closed)


def StraussHard(beta, gamma, r, hc, *, closed=True) -> MultiStraussHard:
    """Strauss hard-core process (spatstat ``StraussHard(r, hc)``).

    Parameters
    ----------
    beta : float
        Intensity parameter (> 0).
    gamma : float
        Interaction parameter for pairs in the shell ``hc .. r``.
    r : float
        Interaction distance (> 0).
    hc : float
        Hard-core distance, ``0 <= hc <= r``.
    closed : bool, default True
        Count pairs with ``d <= r`` and forbid ``d <= hc``, as spatstat's StraussHard does
        (``d < r`` and ``d < hc`` when False).

    Returns
    -------
    MultiStraussHard
        The single-type model.
    """
    return MultiStraussHard([beta], gamma=gamma, r=r, hc=hc, closed=closed)
