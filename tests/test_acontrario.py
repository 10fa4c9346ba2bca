"""paperlib.acontrario: binomial tails, meaningful intervals, gaps and (maximal) modes."""

import math
from fractions import Fraction

import numpy as np
import pytest

from paperlib.acontrario import (
    HistogramModes,
    Interval,
    gap_log10_nfa,
    histogram_modes,
    interval_labels,
    interval_log10_nfa,
    log_binomial_tail,
    maximal_meaningful_modes,
    meaningful_gaps,
    meaningful_intervals,
    meaningful_modes,
    outlier_intervals,
    unimodal_segments,
)
from paperlib.acontrario import _maximal  # the maximality rule on hand-made tables

SINGLE_BUMP = [0, 0, 1, 8, 15, 9, 1, 0, 0, 0]
TWO_BUMPS = [0, 1, 6, 12, 6, 1, 0, 0, 0, 0, 0, 0, 1, 6, 12, 6, 1, 0, 0, 0]


def exact_log_tail(n, k, p):
    """log P[Binomial(n, p) >= k] from exact rational arithmetic."""
    p = Fraction(p)
    tail = sum(math.comb(n, i) * p**i * (1 - p) ** (n - i) for i in range(max(k, 0), n + 1))
    if tail == 0:
        return -math.inf
    return math.log(tail.numerator) - math.log(tail.denominator)  # exact big ints, no underflow


def spans(intervals):
    return [(interval.start, interval.end) for interval in intervals]


def reference_detection(counts, epsilon=1.0):
    """The definitions transcribed literally, O(L^4): intervals, gaps, modes, MM-modes."""
    n_bins, total = len(counts), sum(counts)
    up, down = interval_log10_nfa(counts), gap_log10_nfa(counts)
    candidates = [(a, b) for a in range(n_bins) for b in range(a, n_bins)]
    samples = {(a, b): sum(counts[a : b + 1]) for a, b in candidates}
    expected = {(a, b): total * (b - a + 1) / n_bins for a, b in candidates}
    intervals = [s for s in candidates if samples[s] > expected[s] and up[s] < math.log10(epsilon)]
    gaps = [s for s in candidates if samples[s] < expected[s] and down[s] < math.log10(epsilon)]

    def strictly_inside(inner, outer):
        return inner != outer and outer[0] <= inner[0] and inner[1] <= outer[1]

    modes = [s for s in intervals if not any(g == s or strictly_inside(g, s) for g in gaps)]
    maximal = [
        s
        for s in modes
        if all(up[j] >= up[s] for j in modes if strictly_inside(j, s))
        and all(up[j] > up[s] for j in modes if strictly_inside(s, j))
    ]
    return intervals, gaps, modes, maximal


# --------------------------------------------------------------------------- binomial tail


@pytest.mark.parametrize(
    "n, k, p",
    [
        (10, 3, Fraction(1, 10)),
        (50, 25, Fraction(1, 2)),  # tail near 1/2: no cancellation trouble
        (100, 60, Fraction(1, 4)),
        (1000, 150, Fraction(1, 10)),
        (1000, 400, Fraction(1, 10)),  # ~1e-137
        (200, 200, Fraction(1, 3)),  # a single term
        (2000, 1990, Fraction(1, 100)),  # ~1e-3954: far below the smallest double
        (1500, 700, Fraction(1, 10)),  # ~1e-288, just past the switch to the continued fraction
    ],
)
def test_log_binomial_tail_matches_exact_rational_values(n, k, p):
    assert log_binomial_tail(n, k, float(p)) == pytest.approx(exact_log_tail(n, k, p), rel=1e-12, abs=1e-12)


@pytest.mark.parametrize(
    "n, k, p, expected",
    [
        (10, 0, 0.3, 0.0),  # certain
        (10, -2, 0.3, 0.0),
        (10, 11, 0.3, -np.inf),  # impossible
        (10, 1, 0.0, -np.inf),
        (10, 0, 0.0, 0.0),
        (10, 10, 1.0, 0.0),
        (0, 0, 0.5, 0.0),
    ],
)
def test_log_binomial_tail_edge_cases(n, k, p, expected):
    assert log_binomial_tail(n, k, p) == expected


def test_log_binomial_tail_is_continuous_and_decreasing_across_the_underflow_switch():
    k = np.arange(500, 5001)
    log_tail = log_binomial_tail(5000, k, 0.1)
    assert log_tail.min() < -1000  # the sweep crosses the switch to the continued fraction
    steps = np.diff(log_tail)
    assert np.all(steps < 0)
    # log-concavity of the binomial tail: the steps themselves keep decreasing smoothly
    assert np.all(np.diff(steps) < 0)


def test_log_binomial_tail_broadcasts():
    out = log_binomial_tail(20, np.array([[1], [5]]), np.array([0.1, 0.5]))
    assert out.shape == (2, 2)
    assert out[1, 0] == pytest.approx(exact_log_tail(20, 5, Fraction(1, 10)))


@pytest.mark.parametrize(
    "n, k, p",
    [(10, 2, 1.5), (10, 2, -0.1), (10, 2, np.nan), (-1, 0, 0.5), (10, 2.5, 0.5), (10.5, 2, 0.5), ("a", 1, 0.5)],
)
def test_log_binomial_tail_rejects_bad_input(n, k, p):
    with pytest.raises(ValueError):
        log_binomial_tail(n, k, p)


# --------------------------------------------------------------------------- NFA tables (eq. 1)


def test_interval_nfa_is_number_of_tests_times_binomial_tail():
    counts = [1, 4, 0, 2, 3]  # L = 5, M = 10, N = 15
    table = interval_log10_nfa(counts)
    # bins 1..3 hold 6 of the 10 samples with prior mass 3/5
    expected = (math.log(15) + exact_log_tail(10, 6, Fraction(3, 5))) / math.log(10)
    assert table[1, 3] == pytest.approx(expected, rel=1e-12)
    assert np.all(np.isinf(table[np.tril_indices(5, -1)]))


def test_gap_nfa_is_the_lower_tail():
    counts = [1, 4, 0, 2, 3]
    table = gap_log10_nfa(counts)
    # bins 2..3 hold 2 samples; P[Bin(10, 2/5) <= 2] = P[Bin(10, 3/5) >= 8]
    expected = (math.log(15) + exact_log_tail(10, 8, Fraction(3, 5))) / math.log(10)
    assert table[2, 3] == pytest.approx(expected, rel=1e-12)


def test_explicit_uniform_prior_equals_the_default():
    counts = [3, 0, 9, 12, 2, 0, 1]
    explicit = interval_log10_nfa(counts, prior=np.full(7, 1 / 7))
    np.testing.assert_allclose(explicit, interval_log10_nfa(counts), rtol=1e-12)


# --------------------------------------------------------------------------- known answers


@pytest.mark.parametrize("counts", [[10] * 10, [100] * 20, [1, 1]])
def test_flat_histogram_has_no_mode(counts):
    assert meaningful_intervals(counts) == []
    assert maximal_meaningful_modes(counts) == []
    assert histogram_modes(counts).outliers == ((0, len(counts) - 1),)


def test_single_bump_gives_one_mode_around_its_peak():
    (mode,) = maximal_meaningful_modes(SINGLE_BUMP)
    assert (mode.start, mode.end) == (3, 5)
    assert mode.log10_nfa < -10


def test_two_separated_bumps_give_two_modes_at_their_places():
    modes = maximal_meaningful_modes(TWO_BUMPS)
    assert spans(modes) == [(2, 4), (13, 15)]
    assert modes[0].log10_nfa == pytest.approx(modes[1].log10_nfa)  # same bump shape
    assert any(gap.start >= 5 and gap.end <= 12 for gap in meaningful_gaps(TWO_BUMPS))


def test_union_of_two_bumps_is_meaningful_but_not_a_mode():
    union = interval_log10_nfa(TWO_BUMPS)[2, 15]
    assert union < 0  # as dense as a meaningful interval ...
    assert (2, 15) in spans(meaningful_intervals(TWO_BUMPS))
    assert (2, 15) not in spans(meaningful_modes(TWO_BUMPS))  # ... but it holds a meaningful gap


def test_bump_with_far_isolated_samples_gives_one_mode_and_outliers():
    rng = np.random.default_rng(7)
    bump = rng.normal(0.22, 0.04, size=30)
    isolated = np.array([0.86, 0.97])
    values = np.concatenate([bump, isolated])
    counts, edges = np.histogram(values, bins=10, range=(0.0, 1.0))

    result = histogram_modes(counts)
    assert len(result.modes) == 1
    mode_labels = interval_labels(values, edges, result.modes)
    assert np.all(mode_labels[-2:] == -1)  # the isolated samples are outliers
    assert np.mean(mode_labels[:-2] == 0) > 0.8  # most of the bump is the mode
    # the isolated samples share the outlier interval beyond the mode
    outlier_labels = interval_labels(values, edges, result.outliers)
    assert outlier_labels[-1] == outlier_labels[-2] >= 0
    assert result.outliers[outlier_labels[-1]][1] == 9


def test_scaling_counts_up_makes_a_weak_bump_meaningful():
    weak = np.array([3, 3, 3, 6, 3, 3, 3, 3, 3, 3])
    assert maximal_meaningful_modes(weak) == []
    (mode,) = maximal_meaningful_modes(10 * weak)
    assert (mode.start, mode.end) == (3, 3)


def test_a_larger_epsilon_accepts_more_intervals():
    counts = [5, 9, 4, 1, 0, 0, 2, 8, 3, 0]
    strict = set(spans(meaningful_intervals(counts, epsilon=1e-3)))
    default = set(spans(meaningful_intervals(counts)))
    loose = set(spans(meaningful_intervals(counts, epsilon=100.0)))
    assert strict < default < loose


def test_a_prior_shaped_like_the_histogram_removes_its_modes():
    prior = np.array(SINGLE_BUMP, dtype=float) + 0.5
    prior /= prior.sum()
    assert maximal_meaningful_modes(SINGLE_BUMP, prior=prior) == []


def test_mirrored_histogram_gives_mirrored_modes_and_gaps():
    counts = np.array([5, 9, 4, 1, 0, 0, 2, 8, 3, 0, 7, 1])
    n_bins = counts.size

    def mirrored(intervals):
        return sorted((n_bins - 1 - i.end, n_bins - 1 - i.start, i.log10_nfa) for i in intervals)

    def plain(intervals):
        return [(i.start, i.end, i.log10_nfa) for i in intervals]

    for detector in (meaningful_gaps, meaningful_modes, maximal_meaningful_modes):
        assert plain(detector(counts[::-1])) == mirrored(detector(counts))


def test_symmetric_histogram_gives_symmetric_modes():
    counts = [0, 2, 9, 3, 0, 1, 1, 0, 3, 9, 2, 0]
    modes = spans(maximal_meaningful_modes(counts))
    assert modes == [(2, 2), (9, 9)]
    assert sorted((11 - b, 11 - a) for a, b in modes) == modes


# --------------------------------------------------------------------------- definitions


def test_detection_matches_the_literal_definitions_on_random_histograms():
    rng = np.random.default_rng(2009)
    for trial in range(300):
        n_bins = int(rng.integers(2, 9))
        weights = rng.dirichlet(np.full(n_bins, 0.5))
        counts = rng.multinomial(int(rng.integers(1, 60)), weights).tolist()
        epsilon = [1.0, 1e-2, 10.0][trial % 3]
        expected = reference_detection(counts, epsilon)
        found = [
            spans(detector(counts, epsilon))
            for detector in (meaningful_intervals, meaningful_gaps, meaningful_modes, maximal_meaningful_modes)
        ]
        assert found == [sorted(part) for part in expected], (counts, epsilon)


def test_maximality_prefers_the_more_meaningful_and_the_larger_on_ties():
    inf = np.inf
    # [0, 2] contains [1, 1], which is strictly more meaningful: only [1, 1] is maximal.
    nested = np.array([[inf, inf, -3.0], [inf, -5.0, inf], [inf, inf, inf]])
    assert np.argwhere(_maximal(nested)).tolist() == [[1, 1]]
    # The same with a tie: the larger interval wins.
    tie = np.array([[inf, inf, -5.0], [inf, -5.0, inf], [inf, inf, inf]])
    assert np.argwhere(_maximal(tie)).tolist() == [[0, 2]]
    # Overlapping but not nested: maximality does not compare them.
    overlapping = np.array([[inf, -2.0, inf], [inf, inf, -4.0], [inf, inf, inf]])
    assert np.argwhere(_maximal(overlapping)).tolist() == [[0, 1], [1, 2]]


def test_mm_modes_are_disjoint_meaningful_modes():
    rng = np.random.default_rng(3)
    for _ in range(100):
        counts = rng.poisson(rng.uniform(0, 25, size=int(rng.integers(3, 25))))
        if counts.sum() == 0:
            continue
        modes = maximal_meaningful_modes(counts)
        assert set(spans(modes)) <= set(spans(meaningful_modes(counts)))
        for left, right in zip(modes, modes[1:]):
            assert left.end < right.start


# --------------------------------------------------------------------------- outliers, labels


def test_outlier_intervals_are_the_non_empty_runs_outside_the_modes():
    counts = [0, 0, 1, 8, 15, 9, 0, 0, 2, 0]
    assert outlier_intervals(counts, [(3, 5)]) == [(0, 2), (6, 9)]
    assert outlier_intervals(counts, [Interval(2, 5, -3.0)]) == [(6, 9)]  # (0, 1) is empty
    assert outlier_intervals(counts, []) == [(0, 9)]


def test_histogram_modes_bundles_modes_outliers_and_bin_labels():
    result = histogram_modes(TWO_BUMPS)
    assert isinstance(result, HistogramModes)
    assert spans(result.modes) == spans(maximal_meaningful_modes(TWO_BUMPS))
    assert result.outliers == ((0, 1), (5, 12), (16, 19))
    labels = result.bin_labels()
    assert labels.tolist() == [-1, -1, 0, 0, 0] + [-1] * 8 + [1, 1, 1] + [-1] * 4
    assert result.epsilon == 1.0 and result.counts.sum() == sum(TWO_BUMPS)
    with pytest.raises(ValueError):
        result.counts[0] = 99  # frozen result, read-only arrays


def test_interval_labels_bins_like_numpy_histogram():
    edges = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
    values = np.array([0.0, 0.999, 1.0, 2.5, 4.0, -0.1, 4.1])
    counts, _ = np.histogram(values, bins=edges)
    assert counts.tolist() == [2, 1, 1, 1]  # -0.1 and 4.1 fall outside, 4.0 in the last bin
    labels = interval_labels(values, edges, [(0, 0), (2, 3)])
    assert labels.tolist() == [0, 0, -1, 1, 1, -1, -1]


def test_interval_labels_gives_a_shared_bin_to_the_first_interval():
    labels = interval_labels([0.5, 1.5, 2.5], [0, 1, 2, 3], [(1, 2), (0, 1)])
    assert labels.tolist() == [1, 0, 0]


def test_interval_labels_accepts_no_values():
    assert interval_labels([], [0, 1, 2], [(0, 1)]).shape == (0,)


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "counts, message",
    [
        ([3, -1, 2], "non-negative"),
        ([0, 0, 0], "empty"),
        ([], "at least 2"),
        ([5], "at least 2"),
        ([1, np.nan, 2], "NaN"),
        ([1, np.inf, 2], "NaN or infinite"),
        ([1.5, 2, 3], "whole numbers"),
        ([[1, 2], [3, 4]], "1-D"),
        (["a", "b"], "numbers"),
    ],
)
def test_bad_histograms_are_rejected(counts, message):
    for detector in (meaningful_intervals, maximal_meaningful_modes, histogram_modes, interval_log10_nfa):
        with pytest.raises(ValueError, match=message):
            detector(counts)


@pytest.mark.parametrize("epsilon", [0.0, -1.0, np.nan, np.inf])
def test_bad_epsilon_is_rejected(epsilon):
    with pytest.raises(ValueError, match="epsilon"):
        histogram_modes(SINGLE_BUMP, epsilon=epsilon)


@pytest.mark.parametrize(
    "prior, message",
    [
        (np.full(10, 0.2), "sum to 1"),
        (np.full(9, 1 / 9), "9 bins"),
        (np.r_[0.0, np.full(9, 1 / 9)], "strictly positive"),
        (np.r_[np.nan, np.full(9, 0.1)], "NaN"),
    ],
)
def test_bad_prior_is_rejected(prior, message):
    with pytest.raises(ValueError, match=message):
        maximal_meaningful_modes(SINGLE_BUMP, prior=prior)


@pytest.mark.parametrize(
    "values, edges, intervals, message",
    [
        ([0.5], [0, 1, 1, 2], [(0, 0)], "strictly increasing"),
        ([np.nan], [0, 1, 2], [(0, 0)], "NaN"),
        ([0.5], [0], [], "at least 2"),
        ([0.5], [0, 1, 2], [(1, 2)], "bin range"),
        ([0.5], [0, 1, 2], [(1, 0)], "bin range"),
    ],
)
def test_interval_labels_rejects_bad_input(values, edges, intervals, message):
    with pytest.raises(ValueError, match=message):
        interval_labels(values, edges, intervals)


def test_outlier_intervals_rejects_modes_outside_the_histogram():
    with pytest.raises(ValueError, match="bin range"):
        outlier_intervals([1, 2, 3], [(2, 3)])


# --------------------------------------------------------------------------- speed


def test_a_few_hundred_bins_find_the_two_modes():
    rng = np.random.default_rng(0)
    values = np.concatenate([rng.normal(0.3, 0.05, 50_000), rng.normal(0.7, 0.02, 50_000)])
    counts, _ = np.histogram(values, bins=300, range=(0, 1))
    modes = maximal_meaningful_modes(counts)  # speed: benchmarks/, never a wall time in a test
    assert len(modes) == 2


# --------------------------------------------------------------------------- unimodal segmentation (FTC)


def test_two_populations_above_the_background_are_cut_at_their_dip():
    # Extremity counts of three drawn outlines: 5 and 6 (two florettes), a dip, then 8-10 (a shamrock).
    # Every filled bin is denser than the uniform background, so the MM-modes make one mode of 5-10.
    counts = [0, 0, 0, 0, 0, 25, 24, 2, 17, 6, 1, 1]
    assert len(maximal_meaningful_modes(counts)) == 1
    assert unimodal_segments(counts) == [(0, 7), (8, 11)]


@pytest.mark.parametrize("counts", [
    [0, 0, 0, 15, 5, 0, 0, 0, 0, 0, 0],  # a hand moves a fifth of the copies one count up
    [0, 0, 0, 0, 0, 3, 15, 26, 6, 0, 0],  # a spread over four counts
    [0, 0, 0, 20, 28, 0, 0, 1, 0, 0, 0],  # one far copy: too little to reject a decreasing tail
    [0, 0, 5, 0, 5, 0, 0, 0, 0, 0, 0],  # a dip, but too few samples to mean anything
    SINGLE_BUMP,
])
def test_unimodal_histograms_stay_one_segment(counts):
    assert unimodal_segments(counts) == [(0, len(counts) - 1)]


def test_segments_cover_the_histogram_and_find_separated_bumps():
    assert unimodal_segments(TWO_BUMPS) == [(0, 8), (9, 19)]  # cut in the middle of the empty run
    rng = np.random.default_rng(0)
    for _ in range(20):
        counts = rng.integers(0, 20, rng.integers(2, 30))
        if counts.sum() == 0:
            continue
        segments = unimodal_segments(counts)
        assert segments[0][0] == 0 and segments[-1][1] == len(counts) - 1
        assert all(a[1] + 1 == b[0] for a, b in zip(segments[:-1], segments[1:]))
        assert unimodal_segments(counts[::-1]) is not None  # runs both ways without error


def test_a_smaller_epsilon_merges_more():
    counts = [0, 20, 5, 20, 0]
    assert len(unimodal_segments(counts, epsilon=1.0)) == 2
    assert len(unimodal_segments(counts, epsilon=1e-3)) == 1


@pytest.mark.parametrize("counts, epsilon, error", [
    ([0, 0, 0], 1.0, ValueError),
    ([1] * 65, 1.0, ValueError),
    ([1, -1, 2], 1.0, ValueError),
    ([1, 2, 3], 0.0, ValueError),
])
def test_unimodal_segments_rejects_bad_input(counts, epsilon, error):
    with pytest.raises(error):
        unimodal_segments(counts, epsilon)
