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


#: Choice rules among the matching reference neighbourhoods (the ``choice`` argument of ``synthesize``).
RANDOM, BEST, CLOSE = 0, 1, 2


@numba.njit(cache=True)
def _neighbourhood_score(known_offsets, known_sources, ref_offsets, ref_neighbours, tables, sigmas, sums, gate2,
                         coverage):
    """Pair closest elements (mutual nearest, Figure 3) and score the averaged measures; inf if no pair.

    ``coverage`` False (the paper as written, section 3.2): the measures are summed over the mutual pairs and
    normalised by the number of known elements. True: a pair further apart than ``sqrt(gate2)`` is no pair,
    and every known element left without a partner is charged its threshold for each measure, so a reference
    neighbourhood that does not cover the known elements (an exemplar's border) cannot score well on the few
    pairs it forms.
    """
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
        if nearest_ref[best] == m and (not coverage or best_d <= gate2):
            a, b = ref_neighbours[m], known_sources[best]
            for q in range(5):
                sums[q] += tables[q, a, b]
            pairs += 1
    if pairs == 0:
        return np.inf
    for q in range(5):
        if coverage:
            sums[q] += (n_known - pairs) * sigmas[q]
        sums[q] /= n_known
    return _score(sums, sigmas)


@numba.njit(cache=True)
def grow(order, tar_pointers, tar_neighbours, tar_offsets, ref_pointers, ref_neighbours, ref_offsets, tables,
         sigmas, uniforms, initial, mode, tolerance, gate2, coverage):
    """Assign a reference element to every target element, in growth order.

    ``initial`` holds the reference element each target element is seeded with (-1: to synthesise); an element
    to synthesise with no known neighbour takes a uniform draw. ``mode`` picks
    among the matching neighbourhoods (rule score < 1): RANDOM, a uniform choice (the paper); BEST, the smallest
    score; CLOSE, a uniform choice among those within ``tolerance`` of the smallest score (Efros and Leung's
    rule). ``gate2`` and ``coverage`` are passed to :func:`_neighbourhood_score`.

    Returns ``(source, matched, n_candidates, score)``: the chosen reference element; whether it came from
    the matching set (False: the fallback, the smallest rule score, or no known neighbour at all); how many
    reference neighbourhoods matched; the chosen one's rule score (NaN without known neighbours).
    """
    n_tar, n_ref = order.shape[0], ref_pointers.shape[0] - 1
    source = initial.copy()
    matched = np.zeros(n_tar, dtype=np.bool_)
    n_candidates = np.zeros(n_tar, dtype=np.int64)
    chosen_score = np.full(n_tar, np.nan)
    scores = np.empty(n_ref)
    sums = np.empty(5)
    for step in range(n_tar):
        t = order[step]
        if source[t] >= 0:  # seeded
            continue
        start, stop = tar_pointers[t], tar_pointers[t + 1]
        n_known = 0
        for e in range(start, stop):
            if source[tar_neighbours[e]] >= 0:
                n_known += 1
        if n_known == 0:  # the first element, or one cut off from the rest
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
                                             tables, sigmas, sums, gate2, coverage)
            if scores[r] < 1.0:
                count += 1
            if scores[r] < scores[best]:
                best = r
        n_candidates[t] = count
        if count > 0 and mode == BEST:
            source[t] = best
            matched[t] = True
        elif count > 0:  # uniform choice among the matching (RANDOM) or the close-to-best (CLOSE) neighbourhoods
            cutoff = min(1.0, scores[best] + tolerance) if mode == CLOSE else 1.0
            pool = 0
            for r in range(n_ref):
                if scores[r] < 1.0 and scores[r] <= cutoff:
                    pool += 1
            pick = min(int(uniforms[step] * pool), pool - 1)
            for r in range(n_ref):
                if scores[r] < 1.0 and scores[r] <= cutoff:
                    if pick == 0:
                        source[t] = r
                        break
                    pick -= 1
            matched[t] = True
        else:
            source[t] = best
        chosen_score[t] = scores[source[t]]
    return source, matched, n_candidates, chosen_score


def _mutual_pairs_reference(known_offsets, ref_offsets, gate2, coverage):
    distances = ((known_offsets[:, None, :] - ref_offsets[None, :, :]) ** 2).sum(axis=-1)
    nearest_ref = distances.argmin(axis=1)
    nearest_known = distances.argmin(axis=0)
    return [(m, int(nearest_known[m])) for m in range(len(ref_offsets))
            if nearest_ref[nearest_known[m]] == m and (not coverage or distances[nearest_known[m], m] <= gate2)]


def grow_reference(order, tar_pointers, tar_neighbours, tar_offsets, ref_pointers, ref_neighbours, ref_offsets,
                   tables, sigmas, uniforms, initial, mode, tolerance, gate2, coverage):
    """Plain-Python transcription of :func:`grow` (for tests: slow, same results)."""
    from .measures import rule_score

    n_tar, n_ref = len(order), len(ref_pointers) - 1
    source = np.array(initial, dtype=np.int64)
    matched = np.zeros(n_tar, dtype=bool)
    n_candidates = np.zeros(n_tar, dtype=np.int64)
    chosen_score = np.full(n_tar, np.nan)
    for step, t in enumerate(order):
        if source[t] >= 0:
            continue
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
            pairs = _mutual_pairs_reference(known_offsets, ref_offsets[ref_span], gate2, coverage)
            if pairs:
                measures = np.array([tables[:, ref_neighbours[ref_span][m], known[k][1]] for m, k in pairs])
                total = measures.sum(axis=0)
                if coverage:
                    total = total + (len(known) - len(pairs)) * sigmas
                scores[r] = rule_score(total / len(known), sigmas)
        candidates = np.flatnonzero(scores < 1.0)
        n_candidates[t] = len(candidates)
        if len(candidates) and mode == BEST:
            source[t] = int(np.argmin(scores))
            matched[t] = True
        elif len(candidates):
            if mode == CLOSE:
                candidates = candidates[scores[candidates] <= min(1.0, scores.min() + tolerance)]
            source[t] = candidates[min(int(uniforms[step] * len(candidates)), len(candidates) - 1)]
            matched[t] = True
        else:
            source[t] = int(np.argmin(scores))
        chosen_score[t] = scores[source[t]]
    return source, matched, n_candidates, chosen_score
