"""numba kernels of the sketch elaboration: ranking states by eq. (4), and the steered Markov chain (section 3).

Both are plain loops over small candidate sets; they are compiled once and cached on disk (``cache=True``).
The tests check :func:`steer` against a plain-Python transcription of section 3's algorithm.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

TWO_PI = 2.0 * math.pi


@njit(cache=True)
def _wrap(angle):
    return (angle + math.pi) % TWO_PI - math.pi


@njit(cache=True)
def _direction_difference(a, b):
    """Signed difference of two directions given in [0, 2 pi), in [-pi, pi)."""
    d = a - b
    if d >= math.pi:
        d -= TWO_PI
    elif d < -math.pi:
        d += TWO_PI
    return d


@njit(cache=True, parallel=True)
def rank_by_similarity(directions, weights, candidates, sigma, keep):
    """For every state, the ``keep`` candidates most similar to it by eq. (4), most similar first.

    ``directions`` is ``(N, scales * order)``, the states' angles taken modulo ``2 pi``; ``weights`` the
    flattened W; ``candidates`` ``(N, pool)``. Returns the chosen indices ``(N, keep)`` and their
    similarities D (ties keep the pool's order).
    """
    n, pool = candidates.shape
    total = weights.sum()
    scale = -0.5 / (sigma * sigma)
    chosen = np.empty((n, keep), dtype=np.int64)
    similarity = np.empty((n, keep), dtype=np.float64)
    for i in prange(n):
        values = np.empty(pool, dtype=np.float64)
        for m in range(pool):
            j = candidates[i, m]
            acc = 0.0
            for c in range(directions.shape[1]):
                d = _direction_difference(directions[i, c], directions[j, c])
                acc += weights[c] * math.exp(scale * d * d)
            values[m] = acc / total
        order = np.argsort(-values, kind="mergesort")
        for m in range(keep):
            chosen[i, m] = candidates[i, order[m]]
            similarity[i, m] = values[order[m]]
    return chosen, similarity


@njit(cache=True)
def _in_window(position, u, window, cyclic):
    if window < 0.0:
        return True
    d = abs(position - u)
    if cyclic:
        d = min(d, 1.0 - d)
    return d <= window


@njit(cache=True)
def _condition_all(phi, steering, position, u, window, cyclic, sigma_in, probability, touched):
    """Eq. (5) over every state (the start, and a restart): returns how many states were touched."""
    scale = -0.5 / (sigma_in * sigma_in)
    count = 0
    for k in range(steering.size):
        if _in_window(position[k], u, window, cyclic):
            d = _wrap(phi - steering[k])
            probability[k] = math.exp(scale * d * d)
            touched[count] = k
            count += 1
    return count


@njit(cache=True)
def _keep_top(probability, touched, count, top, candidates, weights):
    """Threshold: the ``top`` most probable touched states, normalised; returns how many (0 if no mass)."""
    values = np.empty(count, dtype=np.float64)
    for m in range(count):
        values[m] = probability[touched[m]]
    order = np.argsort(-values, kind="mergesort")
    kept = min(top, count)
    mass = 0.0
    for m in range(kept):
        mass += values[order[m]]
    if not mass > 0.0:
        return 0
    for m in range(kept):
        candidates[m] = touched[order[m]]
        weights[m] = values[order[m]] / mass
    return kept


@njit(cache=True)
def _instantiate(candidates, weights, kept, sample, uniform, excluded):
    """The maximum-probability candidate (ties: the first), or one drawn with its probability.

    ``excluded`` (-1: none) is never chosen while another candidate is kept: the previous sample's state,
    so that the chain does not repeat a state (a repeated state repeats its angle: a straight stutter).
    """
    mass = 0.0
    for m in range(kept):
        if candidates[m] != excluded:
            mass += weights[m]
    if not mass > 0.0:
        return candidates[0]
    if not sample:
        for m in range(kept):
            if candidates[m] != excluded:
                return candidates[m]
    acc = 0.0
    last = candidates[0]
    for m in range(kept):
        if candidates[m] == excluded:
            continue
        last = candidates[m]
        acc += weights[m] / mass
        if uniform < acc:
            return candidates[m]
    return last


@njit(cache=True)
def steer(phi, steering, position, successor, neighbours, transition, sigma_in, top, sample, uniforms,
          window, cyclic, repeat):
    """The steered chain of section 3; returns the instantiated state of every sample and the restarts.

    ``phi[t]`` is the sketch's angle at sample ``t``; ``steering`` every state's angle at the steering scale;
    ``position`` its arc-length fraction; ``successor`` the next state (-1: none); ``neighbours`` and
    ``transition`` each state's most similar states and the weight of the move to each one's successor
    (:attr:`.model.SketchModel.transition`). ``repeat`` False never instantiates the previous sample's state
    again while another candidate is kept. ``window`` (< 0: none) keeps only
    states whose position is within it of the sketch's ``t / n``. A restart happens when the predicted
    states all have zero probability after conditioning: the chain starts again from eq. (5) over all states.
    """
    n = phi.size
    n_states = steering.size
    probability = np.zeros(n_states, dtype=np.float64)
    seen = np.zeros(n_states, dtype=np.bool_)
    touched = np.empty(n_states, dtype=np.int64)
    candidates = np.empty(top, dtype=np.int64)
    weights = np.empty(top, dtype=np.float64)
    chosen = np.empty(n, dtype=np.int64)
    scale = -0.5 / (sigma_in * sigma_in)
    restarts = 0
    count = _condition_all(phi[0], steering, position, 0.0, window, cyclic, sigma_in, probability, touched)
    kept = _keep_top(probability, touched, count, top, candidates, weights)
    for m in range(count):
        probability[touched[m]] = 0.0
    if kept == 0:
        return chosen, -1
    chosen[0] = _instantiate(candidates, weights, kept, sample, uniforms[0], -1)
    for t in range(1, n):
        u = t / n
        count = 0
        # predict: P(t) = M(t) P(t - 1), M's rows from eq. (4) over the most similar states (eq. 3)
        for c in range(kept):
            j = candidates[c]
            norm = 0.0
            for m in range(neighbours.shape[1]):
                nxt = successor[neighbours[j, m]]
                if nxt >= 0 and _in_window(position[nxt], u, window, cyclic):
                    norm += transition[j, m]
            if norm <= 0.0:
                continue
            for m in range(neighbours.shape[1]):
                nxt = successor[neighbours[j, m]]
                if nxt >= 0 and _in_window(position[nxt], u, window, cyclic):
                    if not seen[nxt]:
                        seen[nxt] = True
                        touched[count] = nxt
                        count += 1
                    probability[nxt] += weights[c] * transition[j, m] / norm
        # condition on the sketch (eq. 5)
        for m in range(count):
            k = touched[m]
            d = _wrap(phi[t] - steering[k])
            probability[k] *= math.exp(scale * d * d)
        kept = _keep_top(probability, touched, count, top, candidates, weights)
        for m in range(count):
            probability[touched[m]] = 0.0
            seen[touched[m]] = False
        if kept == 0:
            restarts += 1
            count = _condition_all(phi[t], steering, position, u, window, cyclic, sigma_in, probability, touched)
            kept = _keep_top(probability, touched, count, top, candidates, weights)
            for m in range(count):
                probability[touched[m]] = 0.0
            if kept == 0:
                return chosen, -1
        chosen[t] = _instantiate(candidates, weights, kept, sample, uniforms[t], -1 if repeat else chosen[t - 1])
    return chosen, restarts
