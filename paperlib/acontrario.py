"""A contrario analysis of 1-D histograms: meaningful intervals, gaps and modes.

Hurtut et al. 2009 (section 2.2) split vector elements into categories by the *maximal
meaningful modes* ("MM-modes") of their area histogram, then of their first robust
principal component, following Desolneux, Moisan & Morel. This module implements that
mode detector on a histogram of ``L`` bins holding ``M`` samples.

The background model (the "a contrario" hypothesis) is that the ``M`` samples fall
independently in the bins with probabilities ``prior`` (uniform, ``1/L``, by default, as
in the paper). An interval of bins ``[a, b]`` holding ``k`` samples, whose prior mass is
``p``, is tested against that model with the binomial tail

    B(M, k, p) = P[Binomial(M, p) >= k],

and, since all ``N = L (L + 1) / 2`` intervals are tested, its *number of false alarms*
is ``NFA = N B(M, k, p)``: the expected number of intervals at least that dense under the
background model. This is Hurtut's eq. (1), the binomial form of Desolneux et al.'s
definition (their book also gives a large-deviation form based on the relative entropy
``H(r, p)``; we do not use it). Everything is computed on log10 NFA, because the
interesting tails are far below the smallest double (1e-308).

Written by hand because no maintained Python library detects a contrario histogram
modes. SciPy provides the binomial tail (``scipy.special.betainc``) but not its
logarithm, so tails that underflow are finished by a continued fraction evaluated in
log space.

References
----------
.. [1] Hurtut, T., Landes, P.-E., Thollot, J., Gousseau, Y., Drouilhet, R. and
   Coeurjolly, J.-F. (2009). Appearance-guided synthesis of element arrangements by
   example. NPAR 2009, section 2.2, eq. (1).
.. [2] Desolneux, A., Moisan, L. and Morel, J.-M. (2003). A grouping principle and four
   applications. IEEE TPAMI 25(4), 508-513.
.. [3] Desolneux, A., Moisan, L. and Morel, J.-M. (2008). From Gestalt Theory to Image
   Analysis: a Probabilistic Approach. Springer, chapter 7 (modes of a histogram).
.. [4] Delon, J., Desolneux, A., Lisani, J.-L. and Petro, A.-B. (2007). A nonparametric
   approach for histogram segmentation. IEEE TIP 16(1), 253-261.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.special import betainc, betaln

from paperlib._checks import budget, check_budget, finite_array, integer_array, positive_number

__all__ = [
    "HistogramModes",
    "Interval",
    "MAX_BINS",
    "MAX_SEGMENTED_BINS",
    "gap_log10_nfa",
    "histogram_modes",
    "interval_labels",
    "interval_log10_nfa",
    "log_binomial_tail",
    "maximal_meaningful_modes",
    "meaningful_gaps",
    "meaningful_intervals",
    "meaningful_modes",
    "outlier_intervals",
    "unimodal_segments",
]

# Below this, betainc's result nears the subnormal range and loses relative precision,
# so the log-space continued fraction takes over.
_SMALLEST_DIRECT_TAIL = 1e-280
_CONTINUED_FRACTION_TOLERANCE = 1e-15
_CONTINUED_FRACTION_MAX_TERMS = 100_000
_PRIOR_SUM_TOLERANCE = 1e-9
#: Default budget of the NFA tables: the most histogram bins ``L``. The tables hold all ``L (L + 1) / 2``
#: intervals in ``(L, L)`` arrays (about 100 L^2 bytes at the peak: 1.7 GB at 4096 bins). Raise it with the
#: ``max_bins`` keyword of every function that builds them.
MAX_BINS = 4096


# --------------------------------------------------------------------------- results


@dataclass(frozen=True)
class Interval:
    """An interval of histogram bins ``start..end`` (both inclusive, 0-based).

    Parameters
    ----------
    start, end : int
        First and last bin of the interval.
    log10_nfa : float
        log10 of its number of false alarms: the upper-tail NFA for intervals and
        modes, the lower-tail NFA for gaps. The interval is epsilon-meaningful when
        ``log10_nfa < log10(epsilon)``; the lower, the more meaningful.
    """

    start: int
    end: int
    log10_nfa: float

    @property
    def bins(self) -> range:
        """The bin indices the interval covers."""
        return range(self.start, self.end + 1)


@dataclass(frozen=True)
class HistogramModes:
    """The a contrario reading of one histogram, as Hurtut 2009 section 2.2 uses it.

    Parameters
    ----------
    counts : ndarray of int64, shape (L,)
        The analysed histogram (read-only).
    prior : ndarray of float64, shape (L,)
        Bin probabilities of the background model (read-only).
    epsilon : float
        Meaningfulness threshold on the NFA.
    modes : tuple of Interval
        The maximal meaningful modes (the paper's MM-modes), ordered by position.
    outliers : tuple of (int, int)
        The outlier intervals: maximal runs of consecutive bins outside every MM-mode
        that hold at least one sample, as ``(start, end)`` inclusive. Each is an
        "outlier category" of section 2.2.
    """

    counts: np.ndarray
    prior: np.ndarray
    epsilon: float
    modes: tuple[Interval, ...]
    outliers: tuple[tuple[int, int], ...]

    def bin_labels(self) -> np.ndarray:
        """Index of the MM-mode holding each bin, -1 for bins outside every mode.

        Returns
        -------
        ndarray of int, shape (L,)
            For each bin of :attr:`counts`, the index in :attr:`modes` of the MM-mode that
            holds it, or -1 when no mode holds it.
        """
        return _bin_labels([(mode.start, mode.end) for mode in self.modes], self.counts.size)


# --------------------------------------------------------------------------- binomial tail


def log_binomial_tail(n, k, p) -> np.ndarray:
    """Natural log of the binomial tail ``B(n, k, p) = P[Binomial(n, p) >= k]``.

    Accurate to about 1e-13 relative where the tail is a normal double (SciPy's
    regularized incomplete beta), and still to about 1e-15 relative in the logarithm far
    beyond, where the tail underflows (e.g. ``B(2000, 1990, 0.01)`` ~ 1e-3954). Hurtut
    2009 writes the same function ``B(p, n, k)``, arguments in another order.

    Parameters
    ----------
    n : array_like of int
        Number of trials (>= 0).
    k : array_like of int
        Threshold; ``k <= 0`` gives ``log 1 = 0`` and ``k > n`` gives ``-inf``.
    p : array_like of float
        Success probability in ``[0, 1]``.

    Returns
    -------
    ndarray of float64
        ``log B(n, k, p)``, broadcast over the inputs, in ``[-inf, 0]``.

    Raises
    ------
    ValueError
        If ``n`` or ``k`` are not integers, ``n < 0``, or ``p`` is outside ``[0, 1]``
        or NaN.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2 (the tail B below eq. (1)).
    .. [2] NIST DLMF 8.17.5 (binomial tail as a regularized incomplete beta function)
       and 8.17.22 (its continued fraction).
    """
    n, k, p = integer_array(n, "n"), integer_array(k, "k"), finite_array(p, "p")
    try:
        n, k, p = np.broadcast_arrays(n, k, p)
    except ValueError:
        raise ValueError(f"n, k and p must broadcast to one shape, got {n.shape}, {k.shape} and {p.shape}") from None
    if np.any(n < 0):
        raise ValueError("n (number of trials) must be >= 0")
    if not np.all((p >= 0) & (p <= 1)):
        raise ValueError("p must be a probability in [0, 1] (no NaN)")

    log_tail = np.zeros(n.shape)  # k <= 0: the tail is certain
    log_tail[k > n] = -np.inf
    log_tail[(p == 0) & (k > 0)] = -np.inf
    # p == 1 with 0 < k <= n is certain too: already 0.
    open_case = (k > 0) & (k <= n) & (p > 0) & (p < 1)
    log_tail[open_case] = _log_tail_inside(n[open_case], k[open_case], p[open_case])
    return log_tail


def _log_tail_inside(n: np.ndarray, k: np.ndarray, p: np.ndarray) -> np.ndarray:
    """log B for 0 < k <= n and 0 < p < 1, through I_p(k, n - k + 1) (DLMF 8.17.5)."""
    a = k.astype(np.float64)
    b = (n - k + 1).astype(np.float64)
    tail = betainc(a, b, p)
    log_tail = np.empty(tail.shape)
    direct = tail >= _SMALLEST_DIRECT_TAIL
    log_tail[direct] = np.log(tail[direct])
    far = ~direct
    log_tail[far] = _log_incomplete_beta_by_continued_fraction(a[far], b[far], p[far])
    return log_tail


def _log_incomplete_beta_by_continued_fraction(a: np.ndarray, b: np.ndarray, x: np.ndarray) -> np.ndarray:
    """log I_x(a, b) from its continued fraction (DLMF 8.17.22), modified Lentz method.

    I_x(a, b) = x^a (1 - x)^b / (a B(a, b)) * 1 / (1 + d1 / (1 + d2 / (1 + ...))), with
    d_{2m+1} = -(a + m)(a + b + m) x / ((a + 2m)(a + 2m + 1)) and
    d_{2m} = m (b - m) x / ((a + 2m - 1)(a + 2m)). The prefactor is taken in log space
    and the fraction itself is of order one, so nothing underflows. The fraction
    converges fast for x < (a + 1) / (a + b + 2), which holds wherever the tail is small
    enough to be sent here.
    """
    log_prefactor = a * np.log(x) + b * np.log1p(-x) - np.log(a) - betaln(a, b)
    fraction = _lentz_incomplete_beta_fraction(a, b, x)
    return log_prefactor + np.log(fraction)


def _lentz_incomplete_beta_fraction(a: np.ndarray, b: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Evaluate 1 / (1 + d1 / (1 + d2 / ...)) elementwise by the modified Lentz method."""
    tiny = 1e-300  # keeps Lentz's ratios away from division by zero

    def guard(values):
        return np.where(np.abs(values) < tiny, tiny, values)

    c = np.ones_like(x)
    d = 1.0 / guard(1.0 - (a + b) * x / (a + 1.0))
    value = d.copy()
    active = np.ones(x.shape, dtype=bool)
    for m in range(1, _CONTINUED_FRACTION_MAX_TERMS + 1):
        if not active.any():
            return value
        am, bm, xm = a[active], b[active], x[active]
        cm, dm = c[active], d[active]
        even = m * (bm - m) * xm / ((am + 2 * m - 1) * (am + 2 * m))
        dm = 1.0 / guard(1.0 + even * dm)
        cm = guard(1.0 + even / cm)
        step = dm * cm
        odd = -(am + m) * (am + bm + m) * xm / ((am + 2 * m) * (am + 2 * m + 1))
        dm = 1.0 / guard(1.0 + odd * dm)
        cm = guard(1.0 + odd / cm)
        last_step = dm * cm
        value[active] *= step * last_step
        c[active], d[active] = cm, dm
        active[active] = np.abs(last_step - 1.0) > _CONTINUED_FRACTION_TOLERANCE
    raise RuntimeError("the binomial-tail continued fraction did not converge")  # pragma: no cover


# --------------------------------------------------------------------------- NFA tables


def interval_log10_nfa(counts, prior=None, *, max_bins: int = MAX_BINS) -> np.ndarray:
    """log10 NFA of every interval of bins as a candidate mode: Hurtut 2009 eq. (1).

    ``NFA[a, b] = N B(M, k_ab, p_ab)`` with ``N = L (L + 1) / 2`` tested intervals,
    ``M`` samples, ``k_ab`` samples and prior mass ``p_ab`` in bins ``a..b``.

    Parameters
    ----------
    counts : array_like of int, shape (L,)
        Histogram counts (non-negative integers, not all zero, L >= 2).
    prior : array_like of float, shape (L,), optional
        Bin probabilities of the background model (positive, summing to 1);
        uniform by default, as in the paper.
    max_bins : int
        Budget: the most bins ``L`` accepted (default :data:`MAX_BINS`); the tables are
        ``(L, L)``, so a larger histogram raises ValueError before allocating them.

    Returns
    -------
    ndarray of float64, shape (L, L)
        ``[a, b]`` holds log10 NFA of bins ``a..b`` for ``a <= b``; ``+inf`` below the
        diagonal, where there is no interval.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2, eq. (1).
    .. [2] Desolneux, Moisan & Morel 2003; 2008, chapter 7.
    """
    counts, prior = _validated_histogram(counts, prior, max_bins)
    return _log10_nfa_tables(counts, *_interval_counts_and_masses(counts, prior))[0]


def gap_log10_nfa(counts, prior=None, *, max_bins: int = MAX_BINS) -> np.ndarray:
    """log10 NFA of every interval of bins as a candidate gap.

    ``NFA[a, b] = N B(M, M - k_ab, 1 - p_ab)``, i.e. ``N P[Binomial(M, p_ab) <= k_ab]``:
    the expected number of intervals at least that empty under the background model
    (Hurtut 2009 section 2.2, the inequality after eq. (1)). Parameters and layout as
    in :func:`interval_log10_nfa`.

    Parameters
    ----------
    counts : array_like of int, shape (L,)
        Histogram counts (non-negative integers, not all zero, L >= 2).
    prior : array_like of float, shape (L,), optional
        Bin probabilities of the background model (positive, summing to 1);
        uniform by default, as in the paper.
    max_bins : int
        Budget: the most bins ``L`` accepted (default :data:`MAX_BINS`); the tables are
        ``(L, L)``, so a larger histogram raises ValueError before allocating them.

    Returns
    -------
    ndarray of float64, shape (L, L)
        ``[a, b]`` holds the lower-tail log10 NFA of bins ``a..b`` as a gap for
        ``a <= b``; ``+inf`` below the diagonal, where there is no interval.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2.
    .. [2] Desolneux, Moisan & Morel 2008, chapter 7.
    """
    counts, prior = _validated_histogram(counts, prior, max_bins)
    return _log10_nfa_tables(counts, *_interval_counts_and_masses(counts, prior))[1]


def _log10_nfa_tables(counts: np.ndarray, inside: np.ndarray, mass: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(interval, gap) log10 NFA tables, +inf below the diagonal, from per-interval k and p."""
    n_bins = counts.size
    total = int(counts.sum())
    log_tests = np.log(n_bins * (n_bins + 1) / 2)
    log_interval = log_tests + log_binomial_tail(total, inside, mass)
    # Lower tail through the complement, as the paper writes it: B(M, M - k, 1 - p).
    log_gap = log_tests + log_binomial_tail(total, total - inside, 1.0 - mass)
    return (
        _upper_triangle(log_interval / np.log(10), n_bins, fill=np.inf),
        _upper_triangle(log_gap / np.log(10), n_bins, fill=np.inf),
    )


def _interval_counts_and_masses(counts: np.ndarray, prior: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Samples ``k`` and prior mass ``p`` of every interval, in ``np.triu_indices`` order."""
    start, end = np.triu_indices(counts.size)
    cumulated_counts = np.concatenate(([0], np.cumsum(counts)))
    inside = cumulated_counts[end + 1] - cumulated_counts[start]
    if np.all(prior == prior[0]):
        # Exact lengths / L for the uniform prior: cumulative float sums would break
        # the mirror symmetry of the tables by rounding.
        mass = (end - start + 1) / counts.size
    else:
        cumulated_prior = np.concatenate(([0.0], np.cumsum(prior)))
        mass = np.clip(cumulated_prior[end + 1] - cumulated_prior[start], 0.0, 1.0)
    return inside, mass


def _upper_triangle(values: np.ndarray, n_bins: int, *, fill) -> np.ndarray:
    """An (L, L) table holding ``values`` (in ``np.triu_indices`` order) on and above the diagonal."""
    table = np.full((n_bins, n_bins), fill, dtype=np.asarray(values).dtype)
    table[np.triu_indices(n_bins)] = values
    return table


# --------------------------------------------------------------------------- detection


def meaningful_intervals(counts, epsilon: float = 1.0, prior=None, *, max_bins: int = MAX_BINS) -> list[Interval]:
    """The epsilon-meaningful intervals of a histogram (Hurtut 2009 eq. (1)).

    Bins ``a..b`` form an epsilon-meaningful interval when they hold more samples than
    the background model expects (``k / M > p``) and ``N B(M, k, p) < epsilon``.

    Parameters
    ----------
    counts : array_like of int, shape (L,)
        Histogram counts (non-negative integers, not all zero, L >= 2).
    epsilon : float, default 1
        Threshold on the number of false alarms (> 0); 1 is the paper's choice.
    prior : array_like of float, shape (L,), optional
        Bin probabilities (positive, summing to 1); uniform by default.
    max_bins : int
        Budget: the most bins ``L`` accepted (default :data:`MAX_BINS`, see
        :func:`interval_log10_nfa`). The other detectors below take it too.

    Returns
    -------
    list of Interval
        Sorted by (start, end), each with its log10 NFA.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2, eq. (1).
    .. [2] Desolneux, Moisan & Morel 2003; 2008, chapter 7.
    """
    detection = _detect(counts, epsilon, prior, max_bins)
    return _intervals_where(detection.is_interval, detection.log10_nfa_interval)


def meaningful_gaps(counts, epsilon: float = 1.0, prior=None, *, max_bins: int = MAX_BINS) -> list[Interval]:
    """The epsilon-meaningful gaps of a histogram.

    Bins ``a..b`` form an epsilon-meaningful gap when they hold fewer samples than the
    background model expects (``k / M < p``) and ``N B(M, M - k, 1 - p) < epsilon``.
    Each gap carries its lower-tail log10 NFA.

    Parameters
    ----------
    counts : array_like of int, shape (L,)
        Histogram counts (non-negative integers, not all zero, L >= 2).
    epsilon : float, default 1
        Threshold on the number of false alarms (> 0); 1 is the paper's choice.
    prior : array_like of float, shape (L,), optional
        Bin probabilities (positive, summing to 1); uniform by default.
    max_bins : int
        Budget: the most bins ``L`` accepted (default :data:`MAX_BINS`, see
        :func:`interval_log10_nfa`).

    Returns
    -------
    list of Interval
        The meaningful gaps sorted by (start, end), each with its lower-tail log10 NFA.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2.
    .. [2] Desolneux, Moisan & Morel 2008, chapter 7.
    """
    detection = _detect(counts, epsilon, prior, max_bins)
    return _intervals_where(detection.is_gap, detection.log10_nfa_gap)


def meaningful_modes(counts, epsilon: float = 1.0, prior=None, *, max_bins: int = MAX_BINS) -> list[Interval]:
    """The epsilon-meaningful modes: meaningful intervals that contain no meaningful gap.

    Parameters
    ----------
    counts : array_like of int, shape (L,)
        Histogram counts (non-negative integers, not all zero, L >= 2).
    epsilon : float, default 1
        Threshold on the number of false alarms (> 0); 1 is the paper's choice.
    prior : array_like of float, shape (L,), optional
        Bin probabilities (positive, summing to 1); uniform by default.
    max_bins : int
        Budget: the most bins ``L`` accepted (default :data:`MAX_BINS`, see
        :func:`interval_log10_nfa`).

    Returns
    -------
    list of Interval
        The meaningful modes sorted by (start, end), each with its (upper-tail) log10 NFA.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2.
    .. [2] Desolneux, Moisan & Morel 2008, chapter 7.
    """
    detection = _detect(counts, epsilon, prior, max_bins)
    return _intervals_where(detection.is_mode, detection.log10_nfa_interval)


def maximal_meaningful_modes(counts, epsilon: float = 1.0, prior=None, *, max_bins: int = MAX_BINS) -> list[Interval]:
    """The maximal meaningful modes of a histogram: Hurtut 2009's "MM-modes".

    A meaningful mode ``I`` is maximal when

    * no meaningful mode inside ``I`` is strictly more meaningful (has a strictly
      lower NFA), and
    * every meaningful mode strictly containing ``I`` is strictly less meaningful
      (has a strictly higher NFA).

    So among nested modes the most meaningful one wins, and on a tie the larger one.
    This is Desolneux, Moisan & Morel's definition, read with the binomial NFA of
    Hurtut's eq. (1) as the measure of meaningfulness (their book states it with the
    relative entropy, where higher entropy means lower NFA).

    Parameters
    ----------
    counts : array_like of int, shape (L,)
        Histogram counts (non-negative integers, not all zero, L >= 2).
    epsilon : float, default 1
        Threshold on the number of false alarms (> 0); 1 is the paper's choice.
    prior : array_like of float, shape (L,), optional
        Bin probabilities (positive, summing to 1); uniform by default.
    max_bins : int
        Budget: the most bins ``L`` accepted (default :data:`MAX_BINS`, see
        :func:`interval_log10_nfa`).

    Returns
    -------
    list of Interval
        Sorted by (start, end). Maximality only compares nested modes, so two MM-modes
        may in principle overlap without either containing the other;
        :meth:`HistogramModes.bin_labels` says how such a bin is assigned.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2.
    .. [2] Desolneux, Moisan & Morel 2003 (maximal meaningful intervals); 2008,
       chapter 7 (maximal meaningful modes).
    """
    detection = _detect(counts, epsilon, prior, max_bins)
    return _intervals_where(detection.is_maximal_mode, detection.log10_nfa_interval)


def outlier_intervals(counts, modes: Sequence[Interval | tuple[int, int]]) -> list[tuple[int, int]]:
    """Runs of consecutive bins outside every mode that hold at least one sample.

    Hurtut 2009 section 2.2: "Any connected interval of bins which does not belong to
    an MM-mode is considered as an outlier [...] category." Runs holding no sample are
    left out, since they would be empty categories.

    Parameters
    ----------
    counts : array_like of int, shape (L,)
        Histogram counts.
    modes : sequence of Interval or (start, end)
        The modes (inclusive bin ranges), usually the MM-modes.

    Returns
    -------
    list of (int, int)
        ``(start, end)`` inclusive, in increasing order.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2 (categorization algorithm).
    """
    counts, _ = _validated_histogram(counts, None)
    covered = _bin_labels(_as_bin_ranges(modes, counts.size, "modes"), counts.size) >= 0
    runs = _runs_of_true(~covered)
    return [(start, end) for start, end in runs if counts[start : end + 1].sum() > 0]


# --------------------------------------------------------------------------- unimodal segmentation (FTC)

#: Most bins :func:`unimodal_segments` takes: a unimodality test costs ``L^3`` binomial tails and the
#: merging up to ``L^2`` tests (64 bins: 1.5 s for random counts, 10 s for the worst, alternating ones).
MAX_SEGMENTED_BINS = 64


def unimodal_segments(counts, epsilon: float = 1.0) -> list[tuple[int, int]]:
    """The coarsest segmentation of a histogram into unimodal runs of bins (Delon et al.'s FTC).

    The histogram is first cut at every local minimum (the middle bin of a lowest plateau), then
    consecutive segments are merged, two at a time and then more, while their union follows the
    *unimodal hypothesis*: for some bin ``c``, the histogram is explained by the Grenander
    estimator increasing up to ``c`` and decreasing after it (the isotonic fits by pool adjacent
    violators), i.e. no run of bins ``[i, j]`` of the union holds meaningfully more or fewer
    samples than the estimator gives it: ``NFA = L (L + 1) / 2 * B < epsilon`` for neither tail,
    with ``B`` the binomial tail of the union's ``M`` samples (counts above ``M r`` at the
    estimator's mass ``p``, or below). Unlike maximal meaningful modes, which test density
    against a uniform background, this separates two populations whose bins all stand above the
    background but with a dip between them that one population alone would not make.

    Parameters
    ----------
    counts : array_like of int, shape (L,)
        Histogram counts (``2 <= L <=`` :data:`MAX_SEGMENTED_BINS`, not all zero).
    epsilon : float, optional
        Meaningfulness threshold of a rejection (default 1).

    Returns
    -------
    list of (int, int)
        ``(start, end)`` inclusive bin ranges, in order, covering ``0 .. L - 1``; a separating
        bin goes to the segment on its left.

    Raises
    ------
    ValueError
        If ``counts`` is not a non-empty histogram of at most :data:`MAX_SEGMENTED_BINS` bins, or
        ``epsilon`` is not positive.

    References
    ----------
    .. [1] Delon, Desolneux, Lisani and Petro (2007), "A nonparametric approach for histogram
       segmentation", IEEE TIP 16(1), sections III (Grenander estimator, meaningful rejections)
       and IV (the fine-to-coarse algorithm).
    """
    counts, _ = _validated_histogram(counts, None, MAX_SEGMENTED_BINS)
    epsilon = positive_number(epsilon, "epsilon")
    log10_epsilon_per_test = np.log10(epsilon) - np.log10(counts.size * (counts.size + 1) / 2)
    cuts = [0, *_local_minima(counts), counts.size - 1]
    merged = True
    while merged:  # pairs first, then longer unions; back to pairs after every merge
        merged = False
        for span in range(2, len(cuts)):
            for first in range(len(cuts) - span):
                if _is_unimodal(counts[cuts[first] : cuts[first + span] + 1], log10_epsilon_per_test):
                    del cuts[first + 1 : first + span]
                    merged = True
                    break
            if merged:
                break
    return [(cuts[k] + (k > 0), cuts[k + 1]) for k in range(len(cuts) - 1)]


def _local_minima(counts: np.ndarray) -> list[int]:
    """Bins strictly below both neighbouring plateaus (the middle of a lowest plateau), in order."""
    change = np.flatnonzero(np.diff(counts)) + 1
    starts, ends = np.concatenate([[0], change]), np.concatenate([change - 1, [counts.size - 1]])
    levels = counts[starts]
    return [int((starts[k] + ends[k]) // 2) for k in range(1, len(starts) - 1)
            if levels[k - 1] > levels[k] < levels[k + 1]]


def _is_unimodal(counts: np.ndarray, log10_threshold: float) -> bool:
    """Whether some increasing-then-decreasing Grenander fit explains ``counts`` (no meaningful rejection)."""
    total = int(counts.sum())
    if counts.size <= 2 or total == 0:
        return True
    upper = np.triu(np.ones((counts.size, counts.size), dtype=bool))
    cumulative = np.concatenate([[0], np.cumsum(counts)])
    observed = (cumulative[None, 1:] - cumulative[:-1, None])[upper]
    for peak in range(counts.size):
        fit = np.concatenate([_increasing_fit(counts[: peak + 1]), _increasing_fit(counts[peak + 1 :][::-1])[::-1]])
        mass = np.concatenate([[0.0], np.cumsum(fit)]) / total
        expected = np.clip((mass[None, 1:] - mass[:-1, None])[upper], 0.0, 1.0)
        excess = log_binomial_tail(total, observed, expected)
        deficit = log_binomial_tail(total, total - observed, 1.0 - expected)
        if np.minimum(excess, deficit).min() / np.log(10.0) >= log10_threshold:
            return True
    return False


def _increasing_fit(values: np.ndarray) -> np.ndarray:
    """Least-squares non-decreasing fit (pool adjacent violators): the Grenander estimator's shape."""
    sums, sizes = [], []
    for value in values.astype(float):
        sums.append(value)
        sizes.append(1)
        while len(sums) > 1 and sums[-2] / sizes[-2] > sums[-1] / sizes[-1]:
            last_sum, last_size = sums.pop(), sizes.pop()
            sums[-1] += last_sum
            sizes[-1] += last_size
    return np.repeat(np.array(sums) / np.array(sizes), sizes) if sums else np.zeros(0)


def histogram_modes(counts, epsilon: float = 1.0, prior=None, *, max_bins: int = MAX_BINS) -> HistogramModes:
    """MM-modes and outlier intervals of a histogram, as Hurtut 2009 categorizes by.

    Parameters
    ----------
    counts : array_like of int, shape (L,)
        Histogram counts (non-negative integers, not all zero, L >= 2).
    epsilon : float, default 1
        Threshold on the number of false alarms (> 0); 1 is the paper's choice.
    prior : array_like of float, shape (L,), optional
        Bin probabilities (positive, summing to 1); uniform by default.
    max_bins : int
        Budget: the most bins ``L`` accepted (default :data:`MAX_BINS`, see
        :func:`interval_log10_nfa`).

    Returns
    -------
    HistogramModes
        The maximal meaningful modes and the non-empty outlier intervals around them.

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2, eq. (1) and the categorization algorithm.
    .. [2] Desolneux, Moisan & Morel 2003; 2008, chapter 7.
    """
    detection = _detect(counts, epsilon, prior, max_bins)
    modes = _intervals_where(detection.is_maximal_mode, detection.log10_nfa_interval)
    detection.counts.setflags(write=False)  # the result is frozen, its arrays too
    detection.prior.setflags(write=False)
    return HistogramModes(
        counts=detection.counts,
        prior=detection.prior,
        epsilon=float(epsilon),
        modes=tuple(modes),
        outliers=tuple(outlier_intervals(detection.counts, modes)),
    )


def interval_labels(values, bin_edges, intervals: Sequence[Interval | tuple[int, int]]) -> np.ndarray:
    """Index of the interval holding each value's bin, or -1 if none does.

    Values are binned as :func:`numpy.histogram` does with the same edges: half-open
    bins ``[e_i, e_{i+1})``, the last one closed. Values outside ``[e_0, e_L]`` get -1.
    Pass the MM-modes to label elements by mode (-1 for outliers), the outlier intervals
    to number the outlier categories.

    Parameters
    ----------
    values : array_like of float, shape (n,)
        The samples the histogram was built from (finite).
    bin_edges : array_like of float, shape (L + 1,)
        Strictly increasing, finite bin edges.
    intervals : sequence of Interval or (start, end)
        Inclusive bin ranges, within ``0..L-1``. Where intervals overlap, a bin goes to
        the one listed first.

    Returns
    -------
    ndarray of int64, shape (n,)

    References
    ----------
    .. [1] Hurtut et al. 2009, section 2.2 (categorization algorithm).
    """
    values = _as_finite_vector(values, "values", min_size=0)
    edges = _as_finite_vector(bin_edges, "bin_edges", min_size=2)
    if np.any(np.diff(edges) <= 0):
        raise ValueError("bin_edges must be strictly increasing")
    n_bins = edges.size - 1
    labels_of_bins = _bin_labels(_as_bin_ranges(intervals, n_bins, "intervals"), n_bins)
    bins = np.searchsorted(edges, values, side="right") - 1
    bins[values == edges[-1]] = n_bins - 1  # the last bin is closed, as in numpy
    inside = (bins >= 0) & (bins < n_bins)
    labels = np.full(values.shape, -1, dtype=np.int64)
    labels[inside] = labels_of_bins[bins[inside]]
    return labels


# --------------------------------------------------------------------------- internals


@dataclass(frozen=True)
class _Detection:
    """Every per-interval table of one analysis, indexed [start, end]."""

    counts: np.ndarray
    prior: np.ndarray
    log10_nfa_interval: np.ndarray
    log10_nfa_gap: np.ndarray
    is_interval: np.ndarray
    is_gap: np.ndarray
    is_mode: np.ndarray
    is_maximal_mode: np.ndarray


def _detect(counts, epsilon, prior, max_bins) -> _Detection:
    counts, prior = _validated_histogram(counts, prior, max_bins)
    log10_epsilon = np.log10(positive_number(epsilon, "epsilon"))
    inside, mass = _interval_counts_and_masses(counts, prior)
    log10_nfa_interval, log10_nfa_gap = _log10_nfa_tables(counts, inside, mass)
    expected = counts.sum() * mass
    # The density conditions r > p and r < p of Desolneux et al. only bite when epsilon
    # is large enough for a tail probability above 1/2 to pass the NFA test.
    denser = _upper_triangle(inside > expected, counts.size, fill=False)
    sparser = _upper_triangle(inside < expected, counts.size, fill=False)

    is_interval = denser & (log10_nfa_interval < log10_epsilon)
    is_gap = sparser & (log10_nfa_gap < log10_epsilon)
    is_mode = is_interval & ~_contains_interval(is_gap)
    is_maximal_mode = _maximal(np.where(is_mode, log10_nfa_interval, np.inf)) & is_mode
    return _Detection(counts, prior, log10_nfa_interval, log10_nfa_gap, is_interval, is_gap, is_mode, is_maximal_mode)


def _contains_interval(flagged: np.ndarray) -> np.ndarray:
    """``out[a, b]``: some flagged interval ``[c, d]`` has ``a <= c <= d <= b``."""
    n_bins = flagged.shape[0]
    # Shortest flagged interval starting at each bin (its end; n_bins if none) ...
    first_end = np.where(flagged.any(axis=1), np.argmax(flagged, axis=1), n_bins)
    # ... then the earliest end among intervals starting at or after each bin.
    earliest_end_from = np.minimum.accumulate(first_end[::-1])[::-1]
    ends = np.arange(n_bins)
    return earliest_end_from[:, None] <= ends[None, :]


def _maximal(nfa: np.ndarray) -> np.ndarray:
    """Maximality among nested intervals, for a table whose non-candidates are +inf.

    ``out[a, b]``: no interval strictly inside ``[a, b]`` has a strictly lower value and
    no interval strictly containing it has a lower or equal one. Two dynamic programs
    over interval lengths give, for every interval, the least value inside it and the
    least value around it in O(L^2).
    """
    n_bins = nfa.shape[0]
    least_inside = nfa.copy()  # least value over intervals contained in [a, b]
    for length in range(2, n_bins + 1):
        a = np.arange(n_bins - length + 1)
        b = a + length - 1
        least_inside[a, b] = np.minimum(nfa[a, b], np.minimum(least_inside[a + 1, b], least_inside[a, b - 1]))
    least_around = nfa.copy()  # least value over intervals containing [a, b]
    for length in range(n_bins - 1, 0, -1):
        a = np.arange(n_bins - length + 1)
        b = a + length - 1
        left = np.where(a > 0, least_around[np.maximum(a - 1, 0), b], np.inf)
        right = np.where(b < n_bins - 1, least_around[a, np.minimum(b + 1, n_bins - 1)], np.inf)
        least_around[a, b] = np.minimum(nfa[a, b], np.minimum(left, right))

    strictly_inside = np.full_like(nfa, np.inf)
    strictly_inside[:-1, 1:] = np.minimum(least_inside[1:, 1:], least_inside[:-1, :-1])
    strictly_around = np.full_like(nfa, np.inf)
    strictly_around[1:, :] = least_around[:-1, :]
    strictly_around[:, :-1] = np.minimum(strictly_around[:, :-1], least_around[:, 1:])
    return (strictly_inside >= nfa) & (strictly_around > nfa)


def _intervals_where(mask: np.ndarray, log10_nfa: np.ndarray) -> list[Interval]:
    starts, ends = np.nonzero(mask)  # row-major: sorted by (start, end)
    return [Interval(int(a), int(b), float(log10_nfa[a, b])) for a, b in zip(starts, ends)]


def _bin_labels(bin_ranges: Sequence[tuple[int, int]], n_bins: int) -> np.ndarray:
    """Per bin, the index of the first range covering it, -1 where none does."""
    labels = np.full(n_bins, -1, dtype=np.int64)
    for index in range(len(bin_ranges) - 1, -1, -1):  # backwards: the first range wins
        start, end = bin_ranges[index]
        labels[start : end + 1] = index
    return labels


def _runs_of_true(flags: np.ndarray) -> list[tuple[int, int]]:
    """Maximal runs of consecutive True values, as inclusive (start, end) pairs."""
    padded = np.concatenate(([False], flags, [False])).astype(np.int8)
    changes = np.flatnonzero(np.diff(padded))
    return [(int(start), int(stop) - 1) for start, stop in zip(changes[::2], changes[1::2])]


# --------------------------------------------------------------------------- validation


def _validated_histogram(counts, prior, max_bins=None) -> tuple[np.ndarray, np.ndarray]:
    """Counts as int64 and prior as float64 (uniform if None), both checked; at most ``max_bins`` bins
    when given (the NFA tables are quadratic in the bins, see :data:`MAX_BINS`)."""
    values = _as_finite_vector(counts, "counts", min_size=2)
    if max_bins is not None:
        check_budget(values.size, budget(max_bins, "max_bins"), "max_bins", "histogram bins")
    if np.any(values < 0):
        raise ValueError("counts must be non-negative")
    if np.any(values != np.round(values)):
        raise ValueError("counts must be whole numbers (a histogram of sample counts)")
    if values.sum() == 0:
        raise ValueError("the histogram is empty: all counts are zero")
    counts = values.astype(np.int64)
    if prior is None:
        return counts, np.full(counts.size, 1.0 / counts.size)
    prior = _as_finite_vector(prior, "prior", min_size=0)
    if prior.size != counts.size:
        raise ValueError(f"prior has {prior.size} bins but counts has {counts.size}")
    if np.any(prior <= 0):
        raise ValueError("prior probabilities must be strictly positive")
    if abs(prior.sum() - 1.0) > _PRIOR_SUM_TOLERANCE:
        raise ValueError(f"prior must sum to 1, got {prior.sum():.12g}")
    return counts, prior / prior.sum()


def _as_finite_vector(values, name: str, *, min_size: int) -> np.ndarray:
    return finite_array(values, name, ndim=1, min_size=min_size)


def _as_bin_ranges(intervals, n_bins: int, name: str) -> list[tuple[int, int]]:
    """Inclusive (start, end) pairs from Interval objects or pairs, checked against L; ``name``: the caller's
    parameter, for the messages."""
    expected = "an Interval or a (start, end) pair of bin indices"
    if isinstance(intervals, (str, bytes)):
        raise TypeError(f"{name} must be a sequence of Interval or (start, end) pairs, got {intervals!r:.60}")
    try:
        intervals = list(intervals)
    except TypeError:
        raise TypeError(f"{name} must be a sequence of Interval or (start, end) pairs, got "
                        f"{type(intervals).__name__}") from None
    ranges = []
    for index, interval in enumerate(intervals):
        try:
            start, end = (interval.start, interval.end) if isinstance(interval, Interval) else interval
            inside = bool(0 <= start <= end < n_bins)
        except (TypeError, ValueError):
            raise ValueError(f"{name}[{index}] must be {expected}, got {interval!r:.60}") from None
        if not inside:
            raise ValueError(f"{name}[{index}]: interval ({start}, {end}) is not a bin range within 0..{n_bins - 1}")
        ranges.append((int(start), int(end)))
    return ranges
