"""Robust principal component analysis (ROBPCA) of the appearance features (Hurtut 2009, section 2.2).

Hurtut et al. categorise the elements of one area category by projecting their four appearance
features onto the first *robust* principal component [Hubert et al. 2002] and looking for MM-modes
of the projections: a few odd elements must not tilt the axis the categories are read along. We
implement ROBPCA (Hubert, Rousseeuw and Vanden Branden 2005), the same authors' successor of the
2002 projection-pursuit method, step by step as R's ``rrcov::PcaHubert(x, k, alpha, mcd = FALSE)``
computes it, so that rrcov serves as an oracle (``tests/oracle/rrcov_robpca.R``):

1. Reduce the data to the affine subspace they span (classical SVD), so a constant feature or
   more features than observations cost nothing.
2. Stahel-Donoho outlyingness of every observation: the largest standardised distance to the
   robust centre over directions through pairs of observations (all pairs when there are at most
   250, else 250 random pairs), with the reweighted univariate MCD as location and scale. The h
   least outlying observations form the h-subset, h = h(alpha, n, k) as in robustbase.
3. The classical PCA of the h-subset spans a k-dimensional subspace. The observations whose
   orthogonal distance to it is below the cutoff are refitted by classical PCA (rrcov's extra
   reweighting, Engelen et al. 2005), and all observations are projected onto its first k axes.
4. Within those k dimensions: concentration steps from the h-subset, then the reweighted MCD,
   computed by FAST-MCD with the concentrated subset among its starts so that the lower
   determinant of the two wins, as ROBPCA prescribes. The eigenvectors and eigenvalues of its
   scatter, mapped back, are the robust components and their variances.
5. Score distances (Mahalanobis within the subspace, cutoff sqrt(chi2_k(0.975))) and orthogonal
   distances (to the subspace, cutoff from the Wilson-Hilferty approximation od^(2/3) ~ normal
   with median and MAD) flag the outliers.

The features are neither standardised nor rescaled (rrcov's ``scale = FALSE``): Hurtut's feature
normalisations (section 2.1) are what makes them commensurate.

Degenerate data. Too few observations for the h-subset (n < k + 2) and more components than
the dimension the data span raise ``ValueError``. Exact fits -- at least h identical
observations, or h observations on a subspace of fewer than k of the robust dimensions -- raise
:class:`ExactFitError`, a ``ValueError`` the categorisation can catch to treat the area category
as a single appearance mode. A constant feature is simply left out of the components.

Where we depart from rrcov: our 250 directions come from ``rng`` (rrcov's from a generator with a
fixed seed), so for n > 22 the h-subset, and with it the answer, can differ by the same amount
rrcov's own answer moves when the rows are merely reordered; rrcov caps k at the rank and
carries on through exact fits with warnings, where we raise; and where Pison's small-sample
formula turns negative (n far below its fitted range) we leave the scatter uncorrected.

Written by hand, as the design asks where no maintained library does the job: no maintained
Python package provides ROBPCA (the project's issue reports seeding bugs in the one on PyPI), and
an MCD without robustbase's consistency and small-sample factors would not flag the same outliers
as R.

References
----------
Hurtut, T., Landes, P.-E., Thollot, J., Gousseau, Y., Drouilhet, R. and Coeurjolly, J.-F.
    (2009). Appearance-guided synthesis of element arrangements by example. NPAR, section 2.2
    (categorisation algorithm, second step).
Hubert, M., Rousseeuw, P. J. and Verboven, S. (2002). A fast method for robust principal
    components with applications to chemometrics. Chemometrics and Intelligent Laboratory
    Systems 60, 101-111.
Hubert, M., Rousseeuw, P. J. and Vanden Branden, K. (2005). ROBPCA: a new approach to robust
    principal component analysis. Technometrics 47(1), 64-79.
Engelen, S., Hubert, M. and Vanden Branden, K. (2005). A comparison of three procedures for
    robust PCA in high dimensions. Austrian Journal of Statistics 34(2), 117-126.
Rousseeuw, P. J. and Van Driessen, K. (1999). A fast algorithm for the minimum covariance
    determinant estimator. Technometrics 41(3), 212-223.
Croux, C. and Haesbroeck, G. (1999). Influence function and efficiency of the minimum covariance
    determinant scatter matrix estimator. Journal of Multivariate Analysis 71, 161-190.
Pison, G., Van Aelst, S. and Willems, G. (2002). Small sample corrections for LTS and MCD.
    Metrika 55, 111-123.
Todorov, V. and Filzmoser, P. (2009). An object-oriented framework for robust multivariate
    analysis. Journal of Statistical Software 32(3) (rrcov's ``PcaHubert``).
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import NamedTuple

import numpy as np
from scipy import stats

from paperlib._checks import as_generator, integer_at_least

__all__ = ["DistanceCutoffs", "ExactFitError", "RobustPCA", "robust_pca", "subset_size"]

CUTOFF_QUANTILE = 0.975  # rrcov's crit.pca.distances and robustbase's reweighting quantile
MAX_DIRECTIONS = 250  # rrcov's maxdir: directions through pairs for the outlyingness
MCD_STARTS = 250  # rrcov's nsamp for the MCD within the PCA subspace
MCD_KEPT = 10  # FAST-MCD iterates the 10 best subsets to convergence (Rousseeuw and Van Driessen 1999)
MAX_C_STEPS = 100  # rrcov's niter; concentration converges in a handful of steps in practice
MAD_CONSTANT = 1.4826  # R's mad(): consistent for the standard deviation at the normal
SINGULAR = 1e-12  # relative size below which a variance or scale counts as zero


class ExactFitError(ValueError):
    """At least h observations lie on a subspace too small for the robust fit (an exact fit)."""


class DistanceCutoffs(NamedTuple):
    """Cutoffs of the score and orthogonal distances beyond which an observation is an outlier.

    ``orthogonal`` is infinite when the components span all the dimensions the data span: then
    there is no orthogonal complement and the orthogonal distances are rounding noise.

    Parameters
    ----------
    score : float
        Cutoff of the score (Mahalanobis) distances.
    orthogonal : float
        Cutoff of the orthogonal distances (infinite when there is no orthogonal complement).
    """

    score: float
    orthogonal: float


@dataclass(frozen=True)
class RobustPCA:
    """A robust principal component fit of ``n`` observations of ``p`` features, ``k`` components.

    Parameters
    ----------
    center : ndarray, shape (p,)
        Robust centre.
    components : ndarray, shape (p, k)
        Orthonormal robust principal directions, by decreasing robust variance; each column's
        entry of largest magnitude is positive (rrcov's sign convention).
    eigenvalues : ndarray, shape (k,)
        Robust variances along the components.
    scores : ndarray, shape (n, k)
        Coordinates of the observations along the components, ``(X - center) @ components``.
    score_distances : ndarray, shape (n,)
        Mahalanobis distances of the scores, ``sqrt(sum(scores**2 / eigenvalues))``.
    orthogonal_distances : ndarray, shape (n,)
        Euclidean distances of the observations to the affine subspace of the components.
    cutoffs : DistanceCutoffs
        Outlier cutoffs of the two distances.
    is_outlier : ndarray of bool, shape (n,)
        Observations beyond either cutoff.
    subset_size : int
        h, the number of observations the fit rests on.
    method : str
        ``"ROBPCA"``.
    """

    center: np.ndarray
    components: np.ndarray
    eigenvalues: np.ndarray
    scores: np.ndarray
    score_distances: np.ndarray
    orthogonal_distances: np.ndarray
    cutoffs: DistanceCutoffs
    is_outlier: np.ndarray
    subset_size: int
    method: str = "ROBPCA"

    def __post_init__(self):
        # Frozen means frozen: the arrays are read-only views, so nobody edits a shared fit.
        for field in fields(self):
            value = getattr(self, field.name)
            if isinstance(value, np.ndarray):
                value.flags.writeable = False

    def transform(self, X) -> np.ndarray:
        """Scores of new observations: ``(X - center) @ components``, shape (m, k).

        Parameters
        ----------
        X : array_like, shape (m, p)
            Observations of the same ``p`` features as the fit.

        Returns
        -------
        ndarray, shape (m, k)
        """
        X = _as_data_matrix(X, min_rows=1)
        if X.shape[1] != self.center.shape[0]:
            raise ValueError(f"X has {X.shape[1]} features; this fit has {self.center.shape[0]}")
        return (X - self.center) @ self.components


def subset_size(n: int, k: int, alpha: float) -> int:
    """h, the size of the subset a robust fit with coverage ``alpha`` rests on (robustbase's h.alpha.n).

    h = floor(2 m - n + 2 (n - m) alpha) with m = floor((n + k + 1) / 2): alpha = 1/2 gives the
    largest breakdown point, m observations; alpha = 1 gives all n.

    Parameters
    ----------
    n : int
        Number of observations (>= 1).
    k : int
        Number of principal components fitted (>= 1).
    alpha : float
        Coverage, in ``[0.5, 1]``: the fraction of observations the fit should rest on.

    Returns
    -------
    int
        h = floor(2 m - n + 2 (n - m) alpha) with m = floor((n + k + 1) / 2).
    """
    n, k, alpha = integer_at_least(n, "n", 1), integer_at_least(k, "k", 1), _checked_alpha(alpha)
    half = (n + k + 1) // 2
    return int(np.floor(2 * half - n + 2 * (n - half) * alpha))


def robust_pca(X, n_components: int = 1, *, alpha: float = 0.75, rng=None) -> RobustPCA:
    """ROBPCA: robust principal components, with score and orthogonal distances and outlier flags.

    Parameters
    ----------
    X : array_like, shape (n, p)
        Observations in rows (for Hurtut's categorisation: the elements of one area category,
        their four normalised appearance features in columns). Finite values only.
    n_components : int
        k, the number of robust components, between 1 and the dimension the data span.
    alpha : float
        Coverage in [0.5, 1]: the fit rests on the h = :func:`subset_size` (n, k, alpha) least
        outlying observations and resists up to n - h outliers; 0.5 resists the most, 1 is
        classical PCA followed by one reweighting.
    rng : None, int or numpy.random.Generator
        Seed of the random directions (when n (n - 1) / 2 > 250) and of FAST-MCD's random starts
        (when k >= 2). With at most 22 observations and k = 1 the result does not depend on it.

    Returns
    -------
    RobustPCA
        Centre, components, eigenvalues, scores, distances, cutoffs and outlier flags.

    Raises
    ------
    TypeError
        Non-numeric ``X``, ``alpha`` or ``n_components`` (which must be an int).
    ValueError
        Malformed ``X`` (not 2-D, NaN or infinite values), ``n_components`` or ``alpha`` out of
        range, fewer than k + 2 observations, more components than the dimension the data span.
    ExactFitError
        At least h observations are identical, or lie on a subspace of fewer than k dimensions.

    Notes
    -----
    The steps are those of rrcov's ``PcaHubert(X, k, alpha = alpha, mcd = FALSE)``; see the
    module docstring. rrcov draws its directions with a fixed generator and its MCD starts from
    R's random state, we draw both from ``rng``: the answers agree up to the randomness of the two
    algorithms (``tests/test_robpca.py`` measures it).

    References
    ----------
    Hubert, Rousseeuw and Vanden Branden (2005), section 3 (the three stages of ROBPCA) and
    section 4 (the outlier map and its cutoffs); Hubert, Rousseeuw and Verboven (2002), the
    projection-pursuit method Hurtut et al. (2009, section 2.2) cite; Rousseeuw and Van Driessen
    (1999), FAST-MCD. Full entries in the module docstring.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> X = rng.normal(size=(40, 4)) * [3.0, 1.0, 0.5, 0.2]
    >>> X[:4] += [0.0, 25.0, 0.0, 0.0]  # four gross outliers
    >>> fit = robust_pca(X, 1, rng=0)
    >>> bool(abs(fit.components[0, 0]) > 0.98), fit.is_outlier[:4].tolist()
    (True, [True, True, True, True])
    """
    X = _as_data_matrix(X, min_rows=2)
    n, p = X.shape
    k = _checked_n_components(n_components, n, p)
    alpha = _checked_alpha(alpha)
    rng = as_generator(rng)
    h = subset_size(n, k, alpha)
    _refuse_identical_majority(X, h)

    span = _classical_pca(X)
    if k > span.rank:
        raise ValueError(f"the data span {span.rank} dimension(s); n_components={k} is too many")
    Y = (X - span.center) @ span.loadings  # coordinates within the data's affine span

    h_subset = _least_outlying(Y, h, rng)
    subspace = _classical_pca(Y[h_subset])
    _require_rank(subspace, k, f"the {h} least outlying observations")
    if k < span.rank:
        subspace = _refit_within_orthogonal_cutoff(Y, subspace, k, h)

    basis = subspace.loadings[:, :k]
    Z = (Y - subspace.center) @ basis
    mcd_center, mcd_scatter = _robust_scatter(Z, subspace.eigenvalues[:k], h, alpha, rng)
    eigenvalues, directions = _descending_eigh(mcd_scatter)

    center = span.center + (subspace.center + mcd_center @ basis.T) @ span.loadings.T
    components = _positive_largest_entries(span.loadings @ basis @ directions)
    return _with_distances(X, center, components, eigenvalues, span.rank, h)


# --- input checks -------------------------------------------------------------------------------


def _as_data_matrix(X, min_rows: int) -> np.ndarray:
    try:
        X = np.asarray(X, dtype=float)
    except (TypeError, ValueError) as error:
        raise TypeError(f"X must be a numeric array of shape (n_samples, n_features): {error}") from None
    if X.ndim != 2:
        raise ValueError(f"X must be 2-D, shape (n_samples, n_features); got shape {X.shape}")
    if X.shape[0] < min_rows or X.shape[1] < 1:
        raise ValueError(f"X needs at least {min_rows} row(s) and one column; got shape {X.shape}")
    if not np.isfinite(X).all():
        raise ValueError("X contains NaN or infinite values")
    return X


def _checked_n_components(n_components, n: int, p: int) -> int:
    if isinstance(n_components, bool) or not isinstance(n_components, (int, np.integer)):
        raise TypeError(f"n_components must be an int; got {n_components!r}")
    k = int(n_components)
    if not 1 <= k <= p:
        raise ValueError(f"n_components must be between 1 and the number of features {p}; got {k}")
    if n < k + 2:
        # The MCD of k-dimensional scores needs an h-subset of k + 1 points out of at least k + 2.
        raise ValueError(f"n_components={k} robust component(s) need at least {k + 2} observations (rows of X); "
                         f"got {n}")
    return k


def _checked_alpha(alpha) -> float:
    try:
        alpha = float(alpha)
    except (TypeError, ValueError):
        raise TypeError(f"alpha must be a number in [0.5, 1]; got {alpha!r}") from None
    if not 0.5 <= alpha <= 1.0:
        raise ValueError(f"alpha must be in [0.5, 1]; got {alpha}")
    return alpha


def _refuse_identical_majority(X: np.ndarray, h: int) -> None:
    _, counts = np.unique(X, axis=0, return_counts=True)
    if counts.max() >= h:
        raise ExactFitError(
            f"X: {counts.max()} of the {len(X)} observations are identical: robust PCA needs fewer than "
            f"h = {h} identical observations (an exact fit; treat them as a single mode)"
        )


def _require_rank(pca: _PCA, k: int, what: str) -> None:
    if pca.rank < k:
        raise ExactFitError(f"{what} span only {pca.rank} dimension(s), fewer than n_components={k} (an exact fit)")


# --- stage 1 and classical PCA of subsets --------------------------------------------------------


class _PCA(NamedTuple):
    center: np.ndarray
    loadings: np.ndarray  # (dimension, rank), orthonormal columns
    eigenvalues: np.ndarray  # (rank,), decreasing
    rank: int


def _classical_pca(X: np.ndarray) -> _PCA:
    """Mean, principal axes and variances of the rows of ``X``, truncated to its numerical rank."""
    center = X.mean(axis=0)
    _, singular_values, vt = np.linalg.svd(X - center, full_matrices=False)
    # robustbase's rankMM tolerance: singular values below max(n, p) * eps * largest are zero.
    tolerance = max(X.shape) * np.finfo(float).eps * singular_values[0]
    rank = int(np.sum(singular_values > tolerance)) if singular_values[0] > 0 else 0
    eigenvalues = singular_values[:rank] ** 2 / (len(X) - 1)
    return _PCA(center, vt[:rank].T, eigenvalues, rank)


# --- stage 2: Stahel-Donoho outlyingness ---------------------------------------------------------


def _least_outlying(Y: np.ndarray, h: int, rng: np.random.Generator) -> np.ndarray:
    """Indices of the h observations of smallest Stahel-Donoho outlyingness (ties by index)."""
    return np.sort(np.argsort(_outlyingness(Y, h, rng), kind="stable")[:h])


def _outlyingness(Y: np.ndarray, h: int, rng: np.random.Generator) -> np.ndarray:
    """max over directions a of |a.y - location| / scale, robust location and scale of a.Y.

    A direction along which h observations project to one value has zero scale: it says that h
    observations lie on a hyperplane, not how outlying the others are, so it is skipped (as in
    rrcov). If every direction is skipped all outlyingnesses are zero.
    """
    projections = Y @ _pair_directions(Y, rng).T
    location, scale = _univariate_mcd(projections, h)
    informative = scale > SINGULAR * np.abs(Y).max()
    if not informative.any():
        return np.zeros(len(Y))
    standardised = np.abs(projections[:, informative] - location[informative]) / scale[informative]
    return standardised.max(axis=1)


def _pair_directions(Y: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Unit directions through pairs of observations: all pairs, or MAX_DIRECTIONS random pairs.

    Directions through data points adapt to the data's shape, which random directions on the
    sphere would not (Hubert et al. 2005, section 3, stage 2).
    """
    n = len(Y)
    if n * (n - 1) // 2 <= MAX_DIRECTIONS:
        first, second = np.triu_indices(n, 1)
    else:
        first = rng.integers(n, size=MAX_DIRECTIONS)
        second = (first + rng.integers(1, n, size=MAX_DIRECTIONS)) % n  # never the same point
    differences = Y[first] - Y[second]
    norms = np.linalg.norm(differences, axis=1)
    distinct = norms > SINGULAR * norms.max()  # duplicated observations give no direction
    return differences[distinct] / norms[distinct, None]


def _univariate_mcd(values: np.ndarray, h: int) -> tuple[np.ndarray, np.ndarray]:
    """Reweighted univariate MCD location and scale of each column of ``values`` (rrcov's unimcd).

    Raw fit: the h consecutive order statistics of least variance (the exact univariate MCD;
    among tied windows the middle one). Their spread is rescaled so that the h-th smallest
    squared residual sits at the chi2_1 quantile h/n, then observations within the 97.5% chi2_1
    cutoff give the final mean and standard deviation. A column whose h-subset is constant has
    scale 0 and location that constant.
    """
    n = values.shape[0]
    if h == n:
        return values.mean(axis=0), values.std(axis=0, ddof=1)
    window = _best_windows(np.sort(values, axis=0), h)
    squared = (values - window.mean) ** 2
    raw_variance = np.partition(squared, h - 1, axis=0)[h - 1] / stats.chi2.ppf(h / n, 1)
    degenerate = raw_variance <= (SINGULAR * np.ptp(values, axis=0)) ** 2
    weights = squared < stats.chi2.ppf(CUTOFF_QUANTILE, 1) * np.where(degenerate, 1.0, raw_variance)
    weights[:, degenerate] = True  # never used: keeps the sums below away from 0 / 0
    counts = weights.sum(axis=0)
    location = (weights * values).sum(axis=0) / counts
    variance = (weights * (values - location) ** 2).sum(axis=0) / np.maximum(counts - 1, 1)
    location = np.where(degenerate, window.mean, location)
    return location, np.where(degenerate, 0.0, np.sqrt(variance))


class _Windows(NamedTuple):
    start: np.ndarray  # index of the first order statistic of the chosen window, per column
    mean: np.ndarray


def _best_windows(ordered: np.ndarray, h: int) -> _Windows:
    """The window of h consecutive sorted values of least variance in each column of ``ordered``.

    Exact ties (common with discrete features) go to the middle tied window, as in rrcov.
    """
    # Moments from cumulative sums, about each column's median so that a large common offset
    # does not cancel catastrophically in sum(x^2) - sum(x)^2 / h.
    shift = ordered[len(ordered) // 2]
    centred = ordered - shift
    zero = np.zeros((1, ordered.shape[1]))
    cumulative = np.vstack([zero, np.cumsum(centred, axis=0)])
    cumulative_squares = np.vstack([zero, np.cumsum(centred**2, axis=0)])
    window_sums = cumulative[h:] - cumulative[:-h]
    window_squares = cumulative_squares[h:] - cumulative_squares[:-h]
    sum_of_squares = np.maximum(window_squares - window_sums**2 / h, 0.0)
    spread = ordered[-1] - ordered[0]
    # Cumulative sums leave rounding of order n eps spread^2: windows closer than that are tied.
    tied = sum_of_squares <= sum_of_squares.min(axis=0) + SINGULAR * h * spread**2
    middle = (tied.sum(axis=0) + 1) // 2
    start = np.argmax(tied & (np.cumsum(tied, axis=0) == middle), axis=0)
    columns = np.arange(ordered.shape[1])
    return _Windows(start, window_sums[start, columns] / h + shift)


# --- stage 3: orthogonal-distance reweighting -----------------------------------------------------


def _refit_within_orthogonal_cutoff(Y: np.ndarray, subspace: _PCA, k: int, h: int) -> _PCA:
    """Classical PCA of the observations close enough to the k-dimensional subspace of ``subspace``.

    The h-subset chosen by outlyingness can miss good observations; refitting on every
    observation within the orthogonal-distance cutoff gains efficiency (rrcov; Engelen et al. 2005).
    """
    centred = Y - subspace.center
    basis = subspace.loadings[:, :k]
    distances = np.linalg.norm(centred - centred @ basis @ basis.T, axis=1)
    location, scale = _univariate_mcd((distances ** (2 / 3))[:, None], h)
    kept = distances <= _wilson_hilferty_cutoff(location[0], scale[0])
    if kept.sum() <= k:
        raise ExactFitError(f"only {kept.sum()} observations lie near the {k}-dimensional robust subspace")
    refit = _classical_pca(Y[kept])
    _require_rank(refit, k, "the observations near the robust subspace")
    return refit


def _wilson_hilferty_cutoff(location: float, scale: float) -> float:
    """Cutoff of orthogonal distances: od^(2/3) is roughly normal (Hubert et al. 2005, section 4)."""
    return float(max(location + scale * stats.norm.ppf(CUTOFF_QUANTILE), 0.0) ** 1.5)


# --- stage 4: reweighted MCD in the k-dimensional subspace ---------------------------------------


def _robust_scatter(
    Z: np.ndarray, eigenvalues: np.ndarray, h: int, alpha: float, rng: np.random.Generator
) -> tuple[np.ndarray, np.ndarray]:
    """Reweighted MCD centre and scatter of the k-dimensional scores ``Z``.

    ROBPCA first concentrates the subset of the h observations closest to the origin in the
    metric of the subspace's variances, then runs FAST-MCD and keeps whichever h-subset has the
    lower determinant: we hand the concentrated subset to FAST-MCD as one more start.
    """
    if Z.shape[1] == 1:
        subset = _exact_univariate_mcd_subset(Z[:, 0], h)
    else:
        nearest = _smallest(np.sum(Z**2 / eigenvalues, axis=1), h)
        concentrated, _ = _c_steps(Z, nearest[None, :], MAX_C_STEPS)
        subset = _fast_mcd_subset(Z, h, rng, extra_starts=concentrated)
    return _reweighted_mcd(Z, subset, alpha)


def _exact_univariate_mcd_subset(z: np.ndarray, h: int) -> np.ndarray:
    """The h observations of least variance: h consecutive order statistics (exact in 1-D)."""
    order = np.argsort(z, kind="stable")
    start = int(_best_windows(z[order][:, None], h).start[0])
    subset = order[start : start + h]
    # Recomputed directly: the cumulative sums leave rounding noise where the variance is zero.
    if np.std(z[subset]) <= SINGULAR * np.ptp(z):
        raise ExactFitError(f"{h} observations have the same robust score (an exact fit)")
    return np.sort(subset)


def _fast_mcd_subset(Z: np.ndarray, h: int, rng: np.random.Generator, extra_starts: np.ndarray) -> np.ndarray:
    """The h-subset of least covariance determinant found by FAST-MCD (Rousseeuw and Van Driessen 1999).

    MCD_STARTS random (k + 1)-subsets are grown to h-subsets and given two concentration steps
    each (``extra_starts`` too); the MCD_KEPT best are concentrated to convergence. With the few
    hundred observations of a drawing no nested subsampling is needed.
    """
    starts = np.vstack([_random_h_subsets(Z, h, rng, MCD_STARTS), extra_starts])
    subsets, log_determinants = _c_steps(Z, starts, 2)
    best = np.argsort(log_determinants, kind="stable")[:MCD_KEPT]
    subsets, log_determinants = _c_steps(Z, subsets[best], MAX_C_STEPS)
    return subsets[np.argmin(log_determinants)]


def _random_h_subsets(Z: np.ndarray, h: int, rng: np.random.Generator, count: int) -> np.ndarray:
    """h-subsets closest to random (k + 1)-subsets, each grown by further random points until its
    covariance is non-singular (Rousseeuw and Van Driessen 1999, section 3)."""
    n, k = Z.shape
    orders = rng.permuted(np.tile(np.arange(n), (count, 1)), axis=1)
    subsets = np.empty((count, h), dtype=int)
    for row, order in enumerate(orders):
        size = k + 1
        while _is_singular(np.cov(Z[order[:size]], rowvar=False)) and size < n:
            size += 1
        sample = Z[order[:size]]
        center, scatter = sample.mean(axis=0), np.cov(sample, rowvar=False)
        if _is_singular(scatter):
            raise ExactFitError("the robust scores lie on a line or plane (an exact fit)")
        subsets[row] = _smallest(_mahalanobis_squared(Z, center[None], scatter[None])[0], h)
    return subsets


def _c_steps(Z: np.ndarray, subsets: np.ndarray, max_steps: int) -> tuple[np.ndarray, np.ndarray]:
    """Concentration steps on each row of ``subsets`` (h-subsets, sorted indices), all at once.

    One step replaces a subset by the h observations closest to its mean in the metric of its
    covariance; the determinant never increases (Rousseeuw and Van Driessen 1999, theorem 1), and
    a subset that maps to itself has converged.
    """
    h = subsets.shape[1]
    for _ in range(max_steps):
        centers, scatters = _subset_moments(Z, subsets)
        distances = _mahalanobis_squared(Z, centers, scatters)
        updated = np.sort(np.argsort(distances, axis=1, kind="stable")[:, :h], axis=1)
        if np.array_equal(updated, subsets):
            break
        subsets = updated
    _, scatters = _subset_moments(Z, subsets)
    return subsets, np.linalg.slogdet(scatters)[1]


def _subset_moments(Z: np.ndarray, subsets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    points = Z[subsets]  # (count, h, k)
    centers = points.mean(axis=1)
    deviations = points - centers[:, None, :]
    scatters = np.einsum("shi,shj->sij", deviations, deviations) / (subsets.shape[1] - 1)
    if _is_singular(scatters).any():
        h = subsets.shape[1]
        raise ExactFitError(f"{h} observations lie on a line or plane of the robust subspace (an exact fit)")
    return centers, scatters


def _reweighted_mcd(Z: np.ndarray, subset: np.ndarray, alpha: float) -> tuple[np.ndarray, np.ndarray]:
    """Reweighted MCD from the raw MCD h-subset, with robustbase's covMcd factors.

    The raw scatter, made consistent at the normal model and corrected for small samples,
    selects the observations within the 97.5% chi2_k cutoff; their mean and covariance, made
    consistent and corrected in turn, are the estimate (Rousseeuw and Van Driessen 1999,
    section 2; Pison et al. 2002).
    """
    n, k = Z.shape
    h = len(subset)
    # robustbase divides the raw univariate variance by h, the raw covariance by h - 1; we follow
    # it so that the reweighting keeps exactly the observations R keeps.
    raw_scatter = np.atleast_2d(np.cov(Z[subset], rowvar=False, ddof=0 if k == 1 else 1))
    raw_scatter = raw_scatter * _mcd_consistency(k, h / n) * _small_sample_correction(k, n, alpha, "raw")
    raw_center = Z[subset].mean(axis=0)
    kept = _mahalanobis_squared(Z, raw_center[None], raw_scatter[None])[0] <= stats.chi2.ppf(CUTOFF_QUANTILE, k)
    center = Z[kept].mean(axis=0)
    scatter = np.atleast_2d(np.cov(Z[kept], rowvar=False))
    if _is_singular(scatter):
        raise ExactFitError(f"the {kept.sum()} observations the MCD keeps span fewer than {k} dimensions")
    if kept.sum() < n:
        scatter = scatter * _mcd_consistency(k, kept.mean()) * _small_sample_correction(k, n, alpha, "reweighted")
    return center, scatter


def _mcd_consistency(k: int, fraction: float) -> float:
    """Factor making the covariance of the central ``fraction`` of a normal sample consistent.

    The fraction of N(0, I_k) within the chi2_k quantile q has covariance P(chi2_{k+2} <= q) /
    fraction times the identity (Croux and Haesbroeck 1999); we divide that out.
    """
    if fraction >= 1:
        return 1.0
    return fraction / stats.chi2.cdf(stats.chi2.ppf(fraction, k), k + 2)


# Pison, Van Aelst and Willems (2002): at coverage 0.5 and 0.875 the MCD scatter, already made
# consistent, is still too small by a factor 1 - exp(a) / n^b at small n; values fitted by
# simulation there (as robustbase uses them). k = 1, 2 have their own (a, b); for k > 2, a and b
# follow from two fitted points, 1 - factor = -c / k^d at n = m k^2, written (c, d, m).
_CORRECTION_SMALL_K = {
    ("raw", 1): ((0.262024211897096, 0.604756680630497), (-0.351584646688712, 1.01646567502486)),
    ("raw", 2): ((0.673292623522027, 0.691365864961895), (0.446537815635445, 1.06690782995919)),
    ("reweighted", 1): ((1.11098143415027, 1.5182890270453), (-0.66046776772861, 0.88939595831888)),
    ("reweighted", 2): ((3.11101712909049, 1.91401056721863), (0.79473550581058, 1.10081930350091)),
}
_CORRECTION_LARGE_K = {
    "raw": (
        ((-1.42764571687802, 1.26263336932151, 2), (-1.06141115981725, 1.28907991440387, 3)),
        ((-0.455179464070565, 1.11192541278794, 2), (-0.294241208320834, 1.09649329149811, 3)),
    ),
    "reweighted": (
        ((-1.02842572724793, 1.67659883081926, 2), (-0.26800273450853, 1.35968562893582, 3)),
        ((-0.544482443573914, 1.25994483222292, 2), (-0.343791072183285, 1.25159004257133, 3)),
    ),
}


def _small_sample_correction(k: int, n: int, alpha: float, stage: str) -> float:
    """Pison et al. (2002) small-sample factor of the raw or reweighted MCD scatter.

    Interpolated linearly in alpha between the fits at 0.5 and 0.875, and from 0.875 to 1 at
    alpha = 1 (robustbase's rule; at alpha = 0.5 robustbase prefers tabulated simulations for
    small n, which we do not carry). 1 (no correction) where n is too small for the fits.
    """
    if k <= 2:
        pairs = _CORRECTION_SMALL_K[stage, k]
    else:
        pairs = tuple(_exponent_fit(points, k) for points in _CORRECTION_LARGE_K[stage])
    at_half, at_875 = (1 - np.exp(a) / n**b for a, b in pairs)
    if alpha <= 0.875:
        shrinkage = at_half + (at_875 - at_half) * (alpha - 0.5) / 0.375
    else:
        shrinkage = at_875 + (1 - at_875) * (alpha - 0.875) / 0.125
    if shrinkage <= 0:
        # n far below the range of Pison's fits (e.g. n = 7, k = 3): the formula turns negative,
        # and robustbase's covariance with it. We leave the scatter uncorrected instead.
        return 1.0
    return float(1 / shrinkage)


def _exponent_fit(points, k: int) -> tuple[float, float]:
    """(a, b) with log(1 - factor) = a - b log n through Pison's two points (c, d, m) for this k."""
    logs = [np.log(-c / k**d) for c, d, _ in points]
    design = [[1.0, -np.log(m * k**2)] for _, _, m in points]
    a, b = np.linalg.solve(design, logs)
    return float(a), float(b)


# --- small linear-algebra helpers ----------------------------------------------------------------


def _smallest(values: np.ndarray, h: int) -> np.ndarray:
    """Sorted indices of the h smallest ``values`` (ties by index)."""
    return np.sort(np.argsort(values, kind="stable")[:h])


def _is_singular(scatter: np.ndarray) -> np.ndarray:
    """Whether each (stacked) covariance matrix has an eigenvalue below SINGULAR times its largest."""
    eigenvalues = np.linalg.eigvalsh(scatter)
    return eigenvalues[..., 0] <= SINGULAR * eigenvalues[..., -1]


def _mahalanobis_squared(Z: np.ndarray, centers: np.ndarray, scatters: np.ndarray) -> np.ndarray:
    """Squared Mahalanobis distances of the rows of ``Z`` for each (center, scatter): (count, n)."""
    deviations = Z[None, :, :] - centers[:, None, :]
    return np.einsum("sni,sij,snj->sn", deviations, np.linalg.inv(scatters), deviations)


def _descending_eigh(scatter: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    eigenvalues, vectors = np.linalg.eigh(scatter)
    return eigenvalues[::-1], vectors[:, ::-1]


def _positive_largest_entries(components: np.ndarray) -> np.ndarray:
    """Flip each column so that its entry of largest magnitude is positive (rrcov's signflip)."""
    largest = components[np.argmax(np.abs(components), axis=0), np.arange(components.shape[1])]
    return components * np.where(largest < 0, -1.0, 1.0)


# --- stage 5: distances and flags ----------------------------------------------------------------


def _with_distances(
    X: np.ndarray, center: np.ndarray, components: np.ndarray, eigenvalues: np.ndarray, rank: int, h: int
) -> RobustPCA:
    """Scores, score and orthogonal distances, cutoffs and flags (Hubert et al. 2005, section 4)."""
    k = len(eigenvalues)
    centred = X - center
    scores = centred @ components
    score_distances = np.sqrt(np.sum(scores**2 / eigenvalues, axis=1))
    orthogonal_distances = np.linalg.norm(centred - scores @ components.T, axis=1)
    if k < rank:
        transformed = orthogonal_distances ** (2 / 3)
        median = np.median(transformed)
        mad = MAD_CONSTANT * np.median(np.abs(transformed - median))
        orthogonal_cutoff = _wilson_hilferty_cutoff(median, mad)
    else:
        orthogonal_cutoff = np.inf
    cutoffs = DistanceCutoffs(float(np.sqrt(stats.chi2.ppf(CUTOFF_QUANTILE, k))), orthogonal_cutoff)
    is_outlier = (score_distances > cutoffs.score) | (orthogonal_distances > cutoffs.orthogonal)
    return RobustPCA(
        center=center,
        components=components,
        eigenvalues=eigenvalues,
        scores=scores,
        score_distances=score_distances,
        orthogonal_distances=orthogonal_distances,
        cutoffs=cutoffs,
        is_outlier=is_outlier,
        subset_size=h,
    )
