"""Learning a class of curves: multi-scale, multi-order states and their similarity (Simhon 2001, section 3).

Each training curve is resampled at ``samples_per_curve`` points equally spaced in arc length (so curves of
every size have the same number of states), or at its own vertex count (``samples_per_curve="vertices"``: each
curve keeps the sample spacing it was digitised at, so the chain learns the detail at the scale a curve of the
class is drawn at), and its tangent angle is analysed at ``scales`` scales
(:mod:`.curves`). The *state* at sample ``t`` is the ``scales x order`` matrix
``gamma(t, s, tau) = theta_s(t - tau)``: the curve's recent history at every scale (the paper's Figure 1;
``A = 1`` attribute, the tangent angle). Closed curves are read cyclically, so every sample has a state and a
successor; on an open curve the first ``order - 1`` samples have no full history and the last has no
successor.

No transition matrix is built (section 3: *"the data is very sparse and the state-space is too large"*).
The transitions out of a state go to the successors of the states most similar to it, weighted by the
similarity of eq. (4),

    D(gamma, gamma') = sum_{s, tau} w(s, tau) G(gamma(s, tau) - gamma'(s, tau)) / sum_{s, tau} w(s, tau),

with ``G(x) = exp(-x^2 / (2 sigma^2))`` of the wrapped angle difference and ``W`` the weight matrix over
scale and history. Training stores, for every state, its ``neighbours`` most similar states and their ``D``:
the paper's *"linked list"* of transition probabilities. How the list weighs them is ``transitions``:

- ``"paper"``: in proportion to D, as section 3 says. D is an *average* of per-component Gaussians, so a
  state's near neighbours score 0.4-0.8 against its own 1: a state's own successor gets about a twelfth of
  its probability, the chain mixes training curves at every step, and a sketch of a training leaf is not
  reconstructed (Fig. 6); and a state's predecessor is among its most similar states, whose successor is the
  state itself, so the chain repeats states (straight stutters in the curve).
- ``"sharp"`` (default, ours): in proportion to ``D ** SHARPNESS``, and within the state's own curve only
  to its successor: the other states of its curve within ``order`` samples are similar because their
  histories overlap with its own, and moving to their successors would repeat the state (the
  predecessor's successor is the state itself), skip samples or go back. Raising D to a power keeps the
  ranking of eq. (4) and makes the state's own successor dominate unless another curve has a nearly as
  similar state: exact where the training data is unambiguous, mixing where it is not.

To find them without comparing every pair of states
(``N^2`` comparisons of ``scales x order`` angles), states are embedded in a low-dimensional Euclidean space
where the distance approximates ``sum w (angle difference)^2`` (the quadratic form of eq. (4) near a match):
the history relative to the state's current coarse angle, reduced by PCA, plus that angle on a circle. A
k-d tree gives a pool of candidates per state, and eq. (4) itself ranks the pool (numba).

References
----------
.. [1] S. Simhon and G. Dudek, "On the Elaboration of Hand-Drawn Sketches", McGill University, 2001:
   section 3 (Figure 1 and eq. 3-4: states over scale and history, transition probabilities from the
   similarity of states), section 3.1 (40 training curves, 5 scales, order 20, a uniform average filter).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from .._checks import check_budget, check_choice, finite_array, integer_at_least, positive_number
from ._kernels import rank_by_similarity
from .curves import (
    check_curve,
    coarse_ring,
    filter_weights,
    gyration_radius,
    integrate_angles,
    multiscale_angles,
    resample_curve,
    resample_simple,
    tangent_angles,
    _wrap,
)

__all__ = ["SketchModel", "default_weights", "state_similarity", "train"]

#: Exponent of D in the ``"sharp"`` transition weights (chosen on held-out coastlines and reconstructed
#: leaves: 1 mixes training curves at every step, 8 keeps the own successor when it is unambiguous).
SHARPNESS = 8.0
TRANSITIONS = ("sharp", "paper")
#: Candidates drawn from the k-d tree per neighbour kept, before eq. (4) ranks them.
POOL_FACTOR = 6
#: Fraction of the relative history's variance the PCA embedding keeps (and at most this many components).
PCA_VARIANCE, PCA_MAX_COMPONENTS = 0.99, 16
#: Default budget of :func:`train` and :func:`default_weights`: the most angle values the states may hold
#: (states x scales x order), 2**27 doubles (1 GiB). Raise it with the ``max_values`` keyword.
MAX_STATE_VALUES = 2**27


@dataclass(frozen=True)
class SketchModel:
    """A trained class of curves (:func:`train`): the states, their successors and most similar states.

    Parameters
    ----------
    order, scales, steering_scale : int
        History length O, number of scales S, and the scale whose angle is compared with the sketch.
    weights : ndarray, shape (scales, order)
        The weight matrix W of eq. (4).
    similarity_sigma : float
        Standard deviation (radians) of eq. (4)'s Gaussian G.
    filter : ndarray
        The low-pass filter's normalised weights.
    causal, subsample : bool
        Whether the filter is causal and the history of coarser scales subsampled (:func:`train`).
    closed : bool
        Whether the training curves were read cyclically.
    samples_per_curve : int or "vertices"
        Samples of each resampled training curve, as :func:`train` was given it.
    curve_samples : ndarray of int, shape (curves,)
        Samples of each resampled training curve (all ``samples_per_curve`` unless ``"vertices"``).
    curves : tuple of ndarray
        The resampled training curves, ``(curve_samples[k], 2)`` each.
    states : ndarray, shape (N, scales, order)
        The states ``gamma(t, s, tau) = theta_s(t - tau)``, unwrapped along each curve.
    angles : ndarray, shape (N, scales)
        Each state's current angle at every scale (``states[:, :, 0]``).
    steering : ndarray, shape (N,)
        Each state's steering angle, which eq. (5) compares with the sketch: the angle at the steering scale
        (``close_steering=False``, the paper), or, for closed classes, the angle that scale's curve has once
        closed as a sketch of the training curve is (:func:`.curves.coarse_ring`; see :func:`train`).
    curve, sample : ndarray of int, shape (N,)
        Training curve and sample index of each state.
    position : ndarray, shape (N,)
        Arc-length fraction of the state along its curve, in [0, 1).
    successor : ndarray of int, shape (N,)
        The state one sample later along the same curve (-1 at the end of an open curve).
    neighbours : ndarray of int, shape (N, k)
        Each state's most similar states by eq. (4), most similar first (the state itself included).
    similarity : ndarray, shape (N, k)
        Their similarity D, in (0, 1].
    transitions : str
        How the transitions weigh the most similar states (``"sharp"`` or ``"paper"``, see the module).
    transition : ndarray, shape (N, k)
        The weight of the move from each state to the successor of each of its most similar states
        (unnormalised; under ``"sharp"`` 0 for the moves along the state's own curve other than to its
        successor).
    extent_ratio : float
        Median over the training curves of the radius of gyration of the curve at the steering scale (its
        angles filtered, integrated back with the same arc length) over that of the curve itself, >= 1 for
        wiggly curves: how much larger the steering curve spans than the detailed curve of the same length.
        :func:`.steering.elaborate` uses it to give the elaboration the size of the sketch.
    """

    order: int
    scales: int
    steering_scale: int
    weights: np.ndarray
    similarity_sigma: float
    filter: np.ndarray
    causal: bool
    subsample: bool
    closed: bool
    samples_per_curve: int | str
    curve_samples: np.ndarray
    curves: tuple
    states: np.ndarray
    angles: np.ndarray
    steering: np.ndarray
    curve: np.ndarray
    sample: np.ndarray
    position: np.ndarray
    successor: np.ndarray
    neighbours: np.ndarray
    similarity: np.ndarray
    transitions: str
    transition: np.ndarray
    extent_ratio: float

    def __len__(self) -> int:
        return len(self.successor)

    @property
    def steering_angles(self) -> np.ndarray:
        """Each state's steering angle (:attr:`steering`): what eq. (5) compares with the sketch."""
        return self.steering


def default_weights(scales: int, order: int, *, max_values: int = MAX_STATE_VALUES) -> np.ndarray:
    """Our default weight matrix W (the paper gives none).

    Section 3: *"We configure the weight matrix to maintain consistency over both high resolution details
    early in the history and overall shape."* So the weight of scale ``s`` decays with the history ``tau`` as
    ``exp(-tau / h_s)`` with ``h_s = order (s + 1) / scales``: the finest scale counts mostly over its most
    recent samples, the coarsest over the whole history.

    Parameters
    ----------
    scales : int
        Number of scales S (>= 1).
    order : int
        History length O (>= 1).
    max_values : int, optional
        Budget: the most entries ``scales * order`` allowed (default :data:`MAX_STATE_VALUES`).

    Returns
    -------
    ndarray of float64, shape (scales, order)
        ``W[s, tau] = exp(-tau / h_s)``, in (0, 1], 1 at ``tau = 0``.

    Raises
    ------
    ValueError
        If ``scales`` or ``order`` is not an integer >= 1, or ``scales * order`` exceeds ``max_values``.
    """
    scales, order = integer_at_least(scales, "scales", 1), integer_at_least(order, "order", 1)
    check_budget(scales * order, integer_at_least(max_values, "max_values", 1), "max_values", "weights")
    scale = np.arange(scales)[:, None]
    history = np.arange(order)[None, :]
    return np.exp(-history / (order * (scale + 1) / scales))


def state_similarity(a, b, weights, sigma: float) -> np.ndarray:
    """Eq. (4): the similarity of states ``a`` and ``b`` (arrays ``(..., scales, order)``), in (0, 1].

    Parameters
    ----------
    a, b : array_like, shape (..., scales, order)
        States ``gamma(t, s, tau)``, angles in radians (finite; broadcast together).
    weights : array_like, shape (scales, order)
        The weight matrix W (non-negative, positive sum).
    sigma : float
        Standard deviation of the Gaussian G, radians (> 0).

    Returns
    -------
    ndarray of float64, shape (...)
        ``D = sum W G(wrap(a - b)) / sum W``, in (0, 1].

    Raises
    ------
    ValueError
        On non-finite input, ``weights`` not a non-negative ``(scales, order)`` matrix with a positive sum that
        matches the last two axes of ``a`` and ``b`` (which must broadcast), or ``sigma`` not positive.
    """
    a, b = finite_array(a, "a"), finite_array(b, "b")
    weights = finite_array(weights, "weights", ndim=2)
    sigma = positive_number(sigma, "sigma")
    if (weights < 0).any() or weights.sum() <= 0:
        raise ValueError("weights must be non-negative and not all zero")
    for name, state in (("a", a), ("b", b)):
        if state.shape[-2:] != weights.shape:
            raise ValueError(f"{name} must end in the weights' shape {weights.shape}, got shape {state.shape}")
    try:
        difference = _wrap(a - b)
    except ValueError:
        raise ValueError(f"a and b must broadcast together, got shapes {a.shape} and {b.shape}") from None
    # sigma**2 in float64 overflows to inf (all similarities 1) or underflows to 0 instead of raising
    # OverflowError; 0 / 0 there is an exact match (similarity 1), as it is for every positive sigma
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        gaussian = np.exp(-(difference**2) / (2.0 * np.float64(sigma) ** 2))
    gaussian[np.isnan(gaussian)] = 1.0
    return (gaussian * weights).sum(axis=(-2, -1)) / weights.sum()


def _check_weights(weights, scales: int, order: int) -> np.ndarray:
    if weights is None:
        return default_weights(scales, order)
    weights = np.array(weights, dtype=np.float64)
    if weights.shape != (scales, order):
        raise ValueError(f"weights must have shape (scales, order) = ({scales}, {order}), got {weights.shape}")
    if not np.isfinite(weights).all() or (weights < 0).any() or weights.sum() <= 0:
        raise ValueError("weights must be finite, non-negative and not all zero")
    return weights


def _curve_list(curves) -> list:
    """The training curves as a non-empty list."""
    try:
        curves = list(curves) if curves is not None else []
    except TypeError:
        raise TypeError(f"curves must be a sequence of (n, 2) point arrays, got {type(curves).__name__}") from None
    if not curves:
        raise ValueError("curves must hold at least one curve, got an empty training set")
    return curves


def _curve_angles(curve, samples: int, scales: int, taps, closed: bool, causal: bool, name: str):
    """One training curve resampled, and its angles at every scale, shape ``(samples or samples - 1, scales)``."""
    points = resample_simple(curve, samples, closed=closed, name=name)
    theta = tangent_angles(points, closed=closed)
    return multiscale_angles(theta, scales, taps, closed=closed, causal=causal).T, points


def train(
    curves,
    *,
    order: int = 20,
    scales: int = 5,
    filter_width: int = 9,
    kernel="uniform",
    steering_scale: int | None = None,
    weights=None,
    similarity_sigma: float = 0.1,
    neighbours: int = 12,
    transitions: str = "sharp",
    causal: bool = False,
    subsample: bool = False,
    samples_per_curve: int | str = 256,
    closed: bool = True,
    close_steering: bool = True,
    max_values: int = MAX_STATE_VALUES,
) -> SketchModel:
    """Learn a class of curves (section 3).

    Parameters
    ----------
    curves : sequence of array_like, each (n_i, 2)
        The training curves (closed rings without a repeated end point when ``closed``): simple, without
        repeated points. Their sizes do not matter: each is simplified at its sample spacing and resampled
        to ``samples_per_curve`` samples (:func:`.curves.resample_simple`), or to its own vertex count.
    order : int
        The history O of a state (>= 1; the paper: 20).
    scales : int
        The number of scales S, the unfiltered angles included (>= 1; the paper: 5).
    filter_width, kernel
        The low-pass filter applied between consecutive scales (:func:`.curves.filter_weights`; the paper:
        a uniform average).
    steering_scale : int, optional
        The scale compared with the sketch in eq. (5) (default: the coarsest, ``scales - 1``).
    weights : array_like, shape (scales, order), optional
        The weight matrix W of eq. (4) (default: :func:`default_weights`).
    similarity_sigma : float
        Standard deviation, in radians, of the Gaussian G of eq. (4) (the paper gives none).
    neighbours : int
        How many of the most similar states each state's transitions go through (>= 1).
    transitions : {"sharp", "paper"}
        How the transitions weigh them (module docstring): ``"paper"`` in proportion to D, ``"sharp"`` (ours)
        to ``D ** SHARPNESS`` without moves back to the state itself.
    causal : bool
        Filter with the paper's causal filter (section 3, eq. 2: each scale lags the finer one by the
        filter's half width) instead of our centred one (:func:`.curves.lowpass`).
    subsample : bool
        Read the history of scale ``s`` every ``2 ** s`` samples (the paper's Psi *"requires less sampling
        points"* at coarser scales, eq. 2: a state of order O then spans ``(O - 1) 2 ** (S - 1)`` samples at the
        coarsest scale) instead of every sample at every scale.
    samples_per_curve : int or "vertices"
        Samples per training curve (> order + 1), or ``"vertices"``: each curve at its own vertex count, equally
        spaced in arc length (every curve then needs more than ``order + 1`` vertices). The paper does not say;
        a fixed count reads a large curve at a coarser spacing than a small one, so the detail the chain
        learns from large curves is coarser than the detail of the curves it is asked to elaborate.
    closed : bool
        Whether the training curves are closed (read cyclically).
    close_steering : bool
        For closed classes, compare the sketch with each training curve's steering scale *closed*, as a
        sketch of the curve is (:func:`.curves.coarse_ring`, the curve :func:`.steering.coarsen` draws), not
        with the filtered angles themselves (``False``, the paper). Filtered angles do not integrate to a
        closed curve (a rounded spike does not return where it left), so no closed sketch has them: the
        sketch of a spiky training curve then differs from its own states by up to 1 rad, and the chain
        leaves the curve there (Fig. 6's exact reconstruction failed on 6 of 14 distinct outlines). A steering
        scale of 0 is the curve's own angle, which needs no closing.
    max_values : int
        Budget: the most angle values the state table may hold (total samples x scales x order;
        default :data:`MAX_STATE_VALUES`), checked before any curve is resampled.

    Returns
    -------
    SketchModel

    Raises
    ------
    ValueError
        On an empty training set, order or scales < 1, a bad curve (NaN, repeated points, self-crossing,
        fewer than 3 points), ``scales`` above ``samples_per_curve`` (no more scales than samples), a state
        table above ``max_values``, or other bad parameters.
    """
    order = integer_at_least(order, "order", 1)
    scales = integer_at_least(scales, "scales", 1)
    neighbours = integer_at_least(neighbours, "neighbours", 1)
    max_values = integer_at_least(max_values, "max_values", 1)
    steering_scale = scales - 1 if steering_scale is None else integer_at_least(steering_scale, "steering_scale", 0)
    if steering_scale >= scales:
        raise ValueError(f"steering_scale must be below scales ({scales}), got {steering_scale}")
    similarity_sigma = positive_number(similarity_sigma, "similarity_sigma")
    for flag, name in ((causal, "causal"), (subsample, "subsample"), (close_steering, "close_steering")):
        if not isinstance(flag, (bool, np.bool_)):
            raise TypeError(f"{name} must be True or False, got {flag!r}")
    check_choice(transitions, TRANSITIONS, "transitions")
    curves = [check_curve(curve, closed=closed, name=f"curves[{k}]") for k, curve in enumerate(_curve_list(curves))]
    counts = _sample_counts(samples_per_curve, curves, order, scales)
    weights = _check_weights(weights, scales, order)
    taps = filter_weights(filter_width, kernel)
    check_budget(int(counts.max()) * scales * order, max_values, "max_values", "angle values per curve")
    check_budget(int(counts.sum()) * scales * order, max_values, "max_values", "state angle values")

    angle_blocks, resampled = [], []
    for k, (curve, samples) in enumerate(zip(curves, counts)):
        angles, points = _curve_angles(curve, int(samples), scales, taps, closed, causal, f"curves[{k}]")
        angle_blocks.append(angles)
        resampled.append(points)
    strides = 2 ** np.arange(scales) if subsample else np.ones(scales, dtype=np.int64)
    if not closed and counts.min() - 1 <= (order - 1) * int(strides[-1]):
        raise ValueError(f"open curves of {counts.min()} samples hold no state of order {order} with subsample=True "
                         f"(the coarsest scale's history spans {(order - 1) * int(strides[-1]) + 1} samples)")
    table = _state_table(angle_blocks, order, closed, strides)
    coarse = _coarse_curves(resampled, angle_blocks, steering_scale, closed)
    neighbour_index, similarity = _most_similar(table["states"], table["angles"][:, steering_scale],
                                                weights, similarity_sigma, neighbours)
    return SketchModel(
        order=order, scales=scales, steering_scale=steering_scale, weights=weights,
        similarity_sigma=similarity_sigma, filter=taps, causal=bool(causal), subsample=bool(subsample),
        closed=closed, samples_per_curve=samples_per_curve, curve_samples=counts,
        curves=tuple(resampled), states=table["states"], angles=table["angles"],
        steering=_steering(coarse, angle_blocks, table, steering_scale, closed and close_steering and steering_scale > 0),
        curve=table["curve"], sample=table["sample"],
        position=table["position"], successor=table["successor"], neighbours=neighbour_index,
        similarity=similarity, transitions=transitions,
        transition=_transition_weights(neighbour_index, similarity, table, transitions, order, counts, closed),
        extent_ratio=float(np.median([gyration_radius(c) / gyration_radius(p) for c, p in zip(coarse, resampled)])),
    )


def _sample_counts(samples_per_curve, curves: list, order: int, scales: int) -> np.ndarray:
    """Samples of each training curve: ``samples_per_curve`` for all, or each curve's vertex count."""
    if isinstance(samples_per_curve, str):
        if samples_per_curve != "vertices":
            raise ValueError(f"samples_per_curve must be an integer or 'vertices', got {samples_per_curve!r}")
        counts = np.array([len(curve) for curve in curves], dtype=np.int64)
        if counts.min() < max(order + 2, scales):
            raise ValueError(f"with samples_per_curve='vertices' every training curve needs at least "
                             f"{max(order + 2, scales)} vertices (order + 2 and scales), training curve "
                             f"{int(counts.argmin())} has {counts.min()}")
        return counts
    samples = integer_at_least(samples_per_curve, "samples_per_curve", order + 2)
    if scales > samples:
        raise ValueError(f"scales must be at most samples_per_curve ({samples}), got {scales}")
    return np.full(len(curves), samples, dtype=np.int64)


def _transition_weights(neighbours, similarity, table: dict, transitions: str, order: int, counts: np.ndarray,
                        closed: bool) -> np.ndarray:
    """The weight of each move to a similar state's successor (see the module docstring)."""
    if transitions == "paper":
        return similarity.copy()
    weights = similarity**SHARPNESS
    state = np.arange(len(neighbours))[:, None]
    gap = np.abs(table["sample"][neighbours] - table["sample"][state])
    if closed:
        samples = counts[table["curve"]][:, None]
        gap = np.minimum(gap, samples - gap)
    # a state's neighbours on its own curve within its history are similar because their histories overlap,
    # not because they continue it otherwise: moving to their successors would repeat, skip or go back
    own_curve = (table["curve"][neighbours] == table["curve"][state]) & (gap <= order) & (neighbours != state)
    weights[own_curve] = 0.0
    return weights


def _mean_step(points: np.ndarray, closed: bool) -> float:
    return float(np.hypot(*np.diff(np.vstack([points, points[:1]]) if closed else points, axis=0).T).mean())


def _coarse_curves(curves, angle_blocks, steering_scale: int, closed: bool) -> list:
    """Each training curve at the steering scale: its angles there integrated back with its own sample spacing
    (closed as :func:`.curves.coarse_ring` closes a sketch)."""
    coarse = []
    for points, angles in zip(curves, angle_blocks):
        theta, step = angles[:, steering_scale], _mean_step(points, closed)
        coarse.append(coarse_ring(theta, step, points[0]) if closed else integrate_angles(theta, step, points[0]))
    return coarse


def _steering(coarse, angle_blocks, table: dict, steering_scale: int, closed_curves: bool) -> np.ndarray:
    """Each state's steering angle (:attr:`SketchModel.steering`): the angle of the closed coarse curve at the
    state's sample, as a sketch resampled by :func:`.steering.elaborate` has it, on the turn of the filtered
    angle; or the filtered angle itself."""
    if not closed_curves:
        return np.ascontiguousarray(table["angles"][:, steering_scale])
    blocks = []
    for ring, angles in zip(coarse, angle_blocks):
        theta = angles[:, steering_scale]
        drawn = tangent_angles(resample_curve(ring, len(theta), closed=True), closed=True)
        blocks.append(theta + _wrap(drawn - theta))
    return np.ascontiguousarray(np.concatenate(blocks))


def _state_table(angle_blocks, order: int, closed: bool, strides: np.ndarray) -> dict:
    """Every state of every curve: current angles, history matrix, curve, sample, position, successor.

    Scale ``s`` looks back ``tau * strides[s]`` samples at history ``tau``.
    """
    columns = {key: [] for key in ("angles", "states", "curve", "sample", "position", "successor")}
    first_state = 0
    for k, angles in enumerate(angle_blocks):
        n = len(angles)
        reach = (order - 1) * int(strides.max())
        samples = np.arange(n) if closed else np.arange(reach, n)
        history = samples[:, None, None] - np.arange(order)[None, :, None] * strides[None, None, :]   # (t, tau, s)
        if closed:
            # the history of an early sample wraps to the curve's end: unwrap it by the curve's total turning
            turning = angles[-1, :] + _wrap(angles[0, :] - angles[-1, :]) - angles[0, :]
            laps = np.floor_divide(history, n)
            states = angles[history % n, np.arange(angles.shape[1])] + laps * turning
        else:
            states = angles[history, np.arange(angles.shape[1])]
        successor = first_state + np.arange(1, len(samples) + 1)
        if closed:
            successor[-1] = first_state
        else:
            successor[-1] = -1
        columns["angles"].append(angles[samples])
        columns["states"].append(np.transpose(states, (0, 2, 1)))
        columns["curve"].append(np.full(len(samples), k))
        columns["sample"].append(samples)
        columns["position"].append(samples / n)
        columns["successor"].append(successor)
        first_state += len(samples)
    return {key: np.ascontiguousarray(np.concatenate(value)) for key, value in columns.items()}


def _embedding(states: np.ndarray, anchor: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Euclidean coordinates whose squared distances approximate ``sum w (angle difference)^2``."""
    root = np.sqrt(weights).ravel()
    relative = (states - anchor[:, None, None]).reshape(len(states), -1) * root
    centred = relative - relative.mean(axis=0)
    # principal axes from the small (scales * order)^2 covariance matrix, largest variance first
    variance, axes = np.linalg.eigh(centred.T @ centred)
    variance, axes = np.clip(variance[::-1], 0.0, None), axes[:, ::-1]
    explained = np.cumsum(variance) / max(float(variance.sum()), 1e-300)
    keep = min(int(np.searchsorted(explained, PCA_VARIANCE)) + 1, PCA_MAX_COMPONENTS, len(variance))
    circle = np.sqrt(weights.sum()) * np.column_stack([np.cos(anchor), np.sin(anchor)])
    return np.hstack([centred @ axes[:, :keep], circle])


def _most_similar(states, anchor, weights, sigma: float, neighbours: int):
    """Each state's ``neighbours`` most similar states by eq. (4), from a k-d tree pool."""
    n = len(states)
    neighbours = min(neighbours, n)
    pool = min(POOL_FACTOR * neighbours, n)
    coordinates = _embedding(states, anchor, weights)
    _, candidates = cKDTree(coordinates).query(coordinates, k=pool, workers=-1)
    candidates = np.asarray(candidates, dtype=np.int64).reshape(n, pool)
    flat = np.ascontiguousarray(states.reshape(n, -1) % (2.0 * np.pi))   # directions in [0, 2 pi)
    return rank_by_similarity(flat, np.ascontiguousarray(weights.ravel()), candidates, sigma, neighbours)
