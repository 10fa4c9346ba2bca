"""The sequential neighbourhood-matching loop of the synthesis (Barla 2006, Algorithm 1), in numba.

Each target element's choice depends on the choices already made around it, so the loop over the growth
order is inherently sequential: a numba kernel, with :func:`grow_reference`, a plain-Python transcription,
against which the tests check it choice for choice.

Graphs are passed as CSR arrays: node ``i`` owns ``neighbours[pointers[i]:pointers[i + 1]]`` and the matching
``offsets``, the neighbours' positions relative to node ``i`` in node ``i``'s local frame.
"""

from __future__ import annotations

import numba
import numpy as np

#: Row order of the measure tables (see :mod:`.measures`).
SHAPE, PAR, OV, SUP, COL = 0, 1, 2, 3, 4


@numba.njit(cache=True)
def _score(means, sigmas):
    """The rule ``col and (shape or (par and ov and sup))`` as one number, < 1 iff it holds."""
    elongated = max(means[PAR] / sigmas[PAR], means[OV] / sigmas[OV], means[SUP] / sigmas[SUP])
    return max(means[COL] / sigmas[COL], min(means[SHAPE] / sigmas[SHAPE], elongated))


@numba.njit(cache=True)
def _neighbourhood_score(known_offsets, known_sources, ref_offsets, ref_neighbours, tables, sigmas, sums):
    """Pair closest elements (mutual nearest, Figure 3) and score the averaged measures; inf if no pair."""
    n_known, n_ref = known_offsets.shape[0], ref_offsets.shape[0]
    if n_ref == 0:
        return np.inf
    nearest_ref = np.empty(n_known, dtype=np.int64)
    for k in range(n_known):
        best, best_d = 0, np.inf
        for m in range(n_ref):
            d = (known_offsets[k, 0] - ref_offsets[m, 0]) ** 2 + (known_offsets[k, 1] - ref_offsets[m, 1]) ** 2
            if d < best_d:
                best, best_d = m, d
        nearest_ref[k] = best
    sums[:] = 0.0
    pairs = 0
    for m in range(n_ref):
        best, best_d = 0, np.inf
        for k in range(n_known):
            d = (known_offsets[k, 0] - ref_offsets[m, 0]) ** 2 + (known_offsets[k, 1] - ref_offsets[m, 1]) ** 2
            if d < best_d:
                best, best_d = k, d
        if nearest_ref[best] == m:
            a, b = ref_neighbours[m], known_sources[best]
            for q in range(5):
                sums[q] += tables[q, a, b]
            pairs += 1
    if pairs == 0:
        return np.inf
    for q in range(5):
        sums[q] /= pairs
    return _score(sums, sigmas)


@numba.njit(cache=True)
def grow(order, tar_pointers, tar_neighbours, tar_offsets, ref_pointers, ref_neighbours, ref_offsets, tables,
         sigmas, uniforms, best_only):
    """Assign a reference element to every target element, in growth order.

    ``best_only`` replaces the paper's uniform choice among the matching neighbourhoods by the best one (the
    smallest rule score), as an option to show what the random choice costs.

    Returns ``(source, matched, n_candidates, score)``: the chosen reference element; whether it came from
    the matching set (False: the fallback, the smallest rule score, or no known neighbour at all); how many
    reference neighbourhoods matched; the chosen one's rule score (NaN without known neighbours).
    """
    n_tar, n_ref = order.shape[0], ref_pointers.shape[0] - 1
    source = np.full(n_tar, -1, dtype=np.int64)
    matched = np.zeros(n_tar, dtype=np.bool_)
    n_candidates = np.zeros(n_tar, dtype=np.int64)
    chosen_score = np.full(n_tar, np.nan)
    scores = np.empty(n_ref)
    sums = np.empty(5)
    for step in range(n_tar):
        t = order[step]
        start, stop = tar_pointers[t], tar_pointers[t + 1]
        n_known = 0
        for e in range(start, stop):
            if source[tar_neighbours[e]] >= 0:
                n_known += 1
        if n_known == 0:  # the first element, or one cut off from the rest: any reference element
            source[t] = min(int(uniforms[step] * n_ref), n_ref - 1)
            continue
        known_offsets = np.empty((n_known, 2))
        known_sources = np.empty(n_known, dtype=np.int64)
        k = 0
        for e in range(start, stop):
            s = source[tar_neighbours[e]]
            if s >= 0:
                known_offsets[k] = tar_offsets[e]
                known_sources[k] = s
                k += 1
        count, best = 0, 0
        for r in range(n_ref):
            lo, hi = ref_pointers[r], ref_pointers[r + 1]
            scores[r] = _neighbourhood_score(known_offsets, known_sources, ref_offsets[lo:hi], ref_neighbours[lo:hi],
                                             tables, sigmas, sums)
            if scores[r] < 1.0:
                count += 1
            if scores[r] < scores[best]:
                best = r
        n_candidates[t] = count
        if count > 0 and best_only:
            source[t] = best
            matched[t] = True
        elif count > 0:  # uniform choice among the matching neighbourhoods
            pick = min(int(uniforms[step] * count), count - 1)
            for r in range(n_ref):
                if scores[r] < 1.0:
                    if pick == 0:
                        source[t] = r
                        break
                    pick -= 1
            matched[t] = True
        else:
            source[t] = best
        chosen_score[t] = scores[source[t]]
    return source, matched, n_candidates, chosen_score


def _mutual_pairs_reference(known_offsets, ref_offsets):
    distances = ((known_offsets[:, None, :] - ref_offsets[None, :, :]) ** 2).sum(axis=-1)
    nearest_ref = distances.argmin(axis=1)
    nearest_known = distances.argmin(axis=0)
    return [(m, int(nearest_known[m])) for m in range(len(ref_offsets)) if nearest_ref[nearest_known[m]] == m]


def grow_reference(order, tar_pointers, tar_neighbours, tar_offsets, ref_pointers, ref_neighbours, ref_offsets,
                   tables, sigmas, uniforms, best_only):
    """Plain-Python transcription of :func:`grow` (for tests: slow, same results)."""
    from .measures import rule_score

    n_tar, n_ref = len(order), len(ref_pointers) - 1
    source = np.full(n_tar, -1, dtype=np.int64)
    matched = np.zeros(n_tar, dtype=bool)
    n_candidates = np.zeros(n_tar, dtype=np.int64)
    chosen_score = np.full(n_tar, np.nan)
    for step, t in enumerate(order):
        span = slice(tar_pointers[t], tar_pointers[t + 1])
        known = [(offset, source[j]) for j, offset in zip(tar_neighbours[span], tar_offsets[span]) if source[j] >= 0]
        if not known:
            source[t] = min(int(uniforms[step] * n_ref), n_ref - 1)
            continue
        known_offsets = np.array([offset for offset, _ in known])
        scores = np.full(n_ref, np.inf)
        for r in range(n_ref):
            ref_span = slice(ref_pointers[r], ref_pointers[r + 1])
            if ref_pointers[r + 1] == ref_pointers[r]:
                continue
            pairs = _mutual_pairs_reference(known_offsets, ref_offsets[ref_span])
            if pairs:
                means = np.mean([tables[:, ref_neighbours[ref_span][m], known[k][1]] for m, k in pairs], axis=0)
                scores[r] = rule_score(means, sigmas)
        candidates = np.flatnonzero(scores < 1.0)
        n_candidates[t] = len(candidates)
        if len(candidates) and best_only:
            source[t] = int(np.argmin(scores))
            matched[t] = True
        elif len(candidates):
            source[t] = candidates[min(int(uniforms[step] * len(candidates)), len(candidates) - 1)]
            matched[t] = True
        else:
            source[t] = int(np.argmin(scores))
        chosen_score[t] = scores[source[t]]
    return source, matched, n_candidates, chosen_score
