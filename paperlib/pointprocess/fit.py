"""Fitting the multitype Strauss hard-core model (Hurtut 2009, section 3.2).

Hurtut et al. estimate the model of eq. (2) in three steps, one per kind of parameter:

1. hard-core distances h per category pair: the minimum distance between points of the two
   categories (section 3.2.1) -- :func:`hardcore_distances`, with spatstat's n/(n+1) variant;
2. interaction radii r per pair: the first local minimum of the centered cross-L function
   sqrt(K/pi) - r (section 3.2.2) -- :func:`interaction_radii`;
3. intensities beta and interaction strengths gamma by maximum pseudolikelihood, eq. (3)
   (section 3.2.3) -- :func:`ppm`, named after spatstat's function, which it reproduces.

:func:`fit_strauss_hardcore` runs the three steps and returns everything the figures need.

Pseudolikelihood
----------------
The log pseudolikelihood (Besag 1977; Jensen and Moller 1991) of conditional intensity
lambda_theta(u, m; x) = exp(theta . s(u, m; x)) is

    log PL(theta) = sum_i log lambda(x_i, m_i; x minus x_i) - sum_m integral_W lambda(u, m; x) du.

With a Berman-Turner quadrature scheme (:mod:`.quadrature`: points u_j, types m_j, weights w_j)
the integral becomes sum_j w_j lambda(u_j, m_j) and log PL is the log likelihood of a Poisson
GLM with log link, weights w and responses z/w (z = 1 for data points): Baddeley and Turner
(2000). It is concave, and we maximise it by Newton's method with step halving (IRLS on the
GLM takes the same steps). As in spatstat: quadrature points with zero conditional intensity
(inside a hard core) are dropped; with the border correction (default) only quadrature points at
least ``rbord`` (the largest interaction radius) from the window's boundary enter the sums,
while every data point still counts as a neighbour.

Parametrisation (spatstat's, with ``~marks`` for multitype patterns): ``(Intercept)`` =
log beta of the first category, ``marks<name>`` = log(beta_m / beta_1), then one log gamma per
unordered category pair: ``Interaction`` for one category, ``mark<a>x<b>`` otherwise (pairs
in spatstat's order: column by column of the upper triangle). The paper's eq. (3) divides the
integral by the number of categories N_c, i.e. takes a uniform probability on the marks as
reference measure; that multiplies every beta by N_c and leaves every gamma unchanged. We keep
spatstat's convention (counting measure on marks), the one ``rmh``-style simulation uses.

Variances. ``vcov`` is spatstat's default for Gibbs models fitted by pseudolikelihood, the
Coeurjolly-Rubak sandwich A1^-1 (A1 + A2 + A3) A1^-1 with A1 = sum over fitted data points of
s s^T and A2, A3 sums over close data pairs (Coeurjolly and Rubak 2013; spatstat's
``vcov.ppm``); ``vcov_hessian`` is the inverse Fisher information of the log PL, the inverse of
its negative Hessian sum_j w_j lambda_j s_j s_j^T (spatstat's ``vcov(fit, hessian = TRUE)``,
the GLM's variance). The Hessian version ignores the dependence between points and
understates the variance of interaction parameters (for ``cells``, the sandwich SE of log gamma
is 1.7 times the Hessian one).

Boundary and unidentifiable interactions. For an interaction term whose statistic is zero at
every fitted data point (no data pair in the shell h <= d < r of that category pair), the
log PL increases without bound as gamma -> 0: the maximum is gamma = 0. We return gamma = 0
exactly (log gamma = -inf, no standard error): the quadrature points with a neighbour in that
shell get zero intensity and are dropped, and the remaining terms are refitted. (spatstat's glm
instead stops at some large negative coefficient.) A term that is zero at *every* fitted
quadrature point (e.g. r = h) carries no information: gamma is fixed at 1 (no interaction) and
reported as not identifiable. Both cases are flagged in the coefficient table's ``status``
column and by a warning. A category with no fitted data point (all of them within rbord of the
boundary) has no finite intensity estimate: a ``ValueError`` says so.

Hurtut's constraint 0 <= gamma <= 1. The paper's model (section 3.1) has gamma in [0, 1]; the
unconstrained maximum of the log PL gives gamma > 1 on clustered data. ``ppm(..., gamma_max=1.0)``
maximises the log PL over log gamma <= log gamma_max (a primal active-set Newton method, with the
KKT conditions checked: :func:`_maximise_bounded`). A gamma held at the bound is reported with
status ``"boundary (gamma = gamma_max)"`` and no standard error; the other coefficients and
their variances are those of the submodel with that gamma fixed (an offset). With gamma_max = 1
this is what spatstat's ``ppm(..., project = TRUE)`` returns for the interactions it requires to
have gamma <= 1 (``Strauss``; ``MultiStraussHard`` pairs without hard core): the valid submodel,
refitted without the offending terms, of largest log PL. spatstat accepts gamma > 1 when there is
a hard core, Hurtut does not; there the bounded fit equals spatstat's fit of that submodel
(``Hardcore``, or a ``MultiStraussHard`` whose dropped pairs keep their hard cores).

References
----------
Hurtut, T., Landes, P.-E., Thollot, J., Gousseau, Y., Drouilhet, R. and Coeurjolly, J.-F.
    (2009). Appearance-guided synthesis of element arrangements by example. NPAR, section 3.2,
    eqs. (2) and (3).
Besag, J. (1977). Some methods of statistical analysis for spatial data. Bulletin of the
    International Statistical Institute 47, 77-92.
Jensen, J. L. and Moller, J. (1991). Pseudolikelihood for exponential family models of spatial
    point processes. Annals of Applied Probability 1, 445-461.
Baddeley, A. and Turner, R. (2000). Practical maximum pseudolikelihood for spatial point
    patterns. Australian and New Zealand Journal of Statistics 42, 283-322.
Coeurjolly, J.-F. and Rubak, E. (2013). Fast covariance estimation for innovations computed
    from a spatial Gibbs point process. Scandinavian Journal of Statistics 40, 669-684.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.spatial import cKDTree

from paperlib._checks import (check_choice, check_flag, finite_array, float_array, instance_of, integer_at_least,
                              positive_number, real_number)

from .models import MultiStraussHard, interaction_counts, interaction_pairs
from .pattern import PointPattern, require_distinct
from .quadrature import QuadratureScheme, default_nd, quadscheme
from .summary import Lcross, Lest

__all__ = [
    "PPMFit",
    "RadiusSelection",
    "StraussHardcoreFit",
    "csr_L_sd",
    "fit_strauss_hardcore",
    "fine_nd",
    "hardcore_distances",
    "interaction_radii",
    "ppm",
    "select_radius",
]

MIN_POINTS_PER_CATEGORY = 3  # Hurtut 2009, section 3.2: "less than three elements" is hazardous
CORRECTIONS = ("border", "none")
HARDCORE_METHODS = ("minimum", "spatstat")
HARDCORE_ONLY_RULE = "hard core only (h beyond rmax)"
L_COLUMNS = {"none": "un", "border": "border", "isotropic": "iso", "translate": "trans"}

# our default quadrature (see fine_nd): grid spacing at most 1/DUMMIES_PER_SCALE of the
# smallest interaction length scale, nd at most MAX_FINE_ND and n_types * nd^2 at most
# MAX_FINE_DUMMIES (the model matrix has n_types + n_types (n_types + 1) / 2 columns)
DUMMIES_PER_SCALE = 16
MAX_FINE_ND = 512
MAX_FINE_DUMMIES = 2**19

NEWTON_MAX_ITERATIONS = 100
MAX_ACTIVE_SET_CHANGES = 100  # bounded fits: changes of the set of coefficients held at their bound
NEWTON_TOLERANCE = 1e-11
ROUNDING_RESOLUTION = 64 * np.finfo(np.float64).eps  # relative precision of the log PL's value

GAMMA_ZERO = "boundary (gamma = 0)"
GAMMA_MAX = "boundary (gamma = gamma_max)"
NOT_IDENTIFIABLE = "not identifiable (gamma = 1)"
NOT_IDENTIFIABLE_CAPPED = "not identifiable (gamma = gamma_max)"


# ============================================================================ input checks


def _check_pattern(pattern) -> PointPattern:
    """A pattern that can be fitted: >= 2 points, >= 3 per category (Hurtut 2009, section 3.2)."""
    if not isinstance(pattern, PointPattern):
        raise TypeError(f"pattern must be a PointPattern, got {type(pattern).__name__}")
    if pattern.n < 2:
        raise ValueError(f"cannot fit an interaction model to a pattern of {pattern.n} point(s): at least 2 are needed")
    small = [(name, int(count)) for name, count in zip(pattern.categories, pattern.counts)
             if count < MIN_POINTS_PER_CATEGORY]
    if small:
        listed = ", ".join(f"{name!r} has {count}" for name, count in small)
        raise ValueError(
            f"category {listed} point(s); fitting needs at least {MIN_POINTS_PER_CATEGORY} per category "
            "(Hurtut 2009, section 3.2): merge it into another category or drop it"
        )
    return pattern


def _check_choice(value, choices, name: str) -> str:
    return check_choice(value, choices, name)


def _interaction(pattern: PointPattern, r, hc, closed: bool) -> MultiStraussHard:
    """The interaction to fit: a MultiStraussHard with beta = gamma = 1 (it validates r and hc)."""
    return MultiStraussHard(np.ones(pattern.n_types), 1.0, r, hc, pattern.categories, closed)


def _check_data_respect_hardcore(pattern: PointPattern, interaction: MultiStraussHard, pair_distance=None) -> None:
    """Every data point must be legal: a hard core larger than a data distance has zero likelihood."""
    _, forbidden = interaction_counts(interaction, pattern.points, pattern.marks, pattern.points, pattern.marks,
                                      exclude=np.arange(pattern.n), pair_distance=pair_distance)
    if not forbidden.any():
        return
    if pair_distance is not None:
        point = int(np.argmax(forbidden))
        raise ValueError(f"data point {point} lies within the hard core of another under pair_distance: "
                         "the data would have zero pseudolikelihood (use smaller hard cores)")
    minimum = hardcore_distances(pattern, "minimum")
    hc = interaction.hc
    violated = minimum <= hc if interaction.closed else minimum < hc
    a, b = np.argwhere(violated)[0]
    names = pattern.categories
    raise ValueError(
        f"hard core hc[{names[a]!r}, {names[b]!r}] = {hc[a, b]:.6g} {'reaches' if interaction.closed else 'exceeds'} "
        f"the smallest distance {minimum[a, b]:.6g} between such points: the data would have zero "
        "pseudolikelihood (use hardcore='spatstat', a smaller hc, or closed=False)"
    )


# ============================================================================ step 1: hard cores


def hardcore_distances(pattern: PointPattern, method: str = "minimum") -> np.ndarray:
    """Hard-core distance of every category pair (Hurtut 2009, section 3.2.1).

    Parameters
    ----------
    pattern : PointPattern
    method : {"minimum", "spatstat"}
        ``"minimum"``: the minimum distance between points of the two categories, the
        paper's maximum likelihood estimate; use it with the open convention (a pair is
        forbidden when d < h), under which the closest pair itself stays legal.
        ``"spatstat"``: that minimum times m/(m+1), m = the smaller of the two categories'
        counts (spatstat's self-starting ``StraussHard`` and ``MultiStraussHard``), which
        keeps the data legal under either convention.

    Returns
    -------
    ndarray, shape (n_types, n_types)
        Symmetric; ``inf`` where a category has a single point (no pair of its own).

    Raises
    ------
    ValueError
        For a pattern with repeated locations (:meth:`PointPattern.duplicated`): a hard core
        of 0 is no hard core; drop them with :meth:`PointPattern.unique`.

    References
    ----------
    Hurtut et al. (2009), section 3.2.1.
    """
    _check_choice(method, HARDCORE_METHODS, "method")
    if not isinstance(pattern, PointPattern):
        raise TypeError(f"pattern must be a PointPattern, got {type(pattern).__name__}")
    require_distinct(pattern, "estimating hard cores (hardcore_distances, fit_strauss_hardcore)")
    minimum = _minimum_distances(pattern)
    if method == "minimum":
        return minimum
    smaller = np.minimum.outer(pattern.counts, pattern.counts).astype(np.float64)
    return minimum * smaller / (smaller + 1)


def _minimum_distances(pattern: PointPattern) -> np.ndarray:
    m = pattern.n_types
    by_type = [pattern.of_type(t) for t in range(m)]
    trees = [cKDTree(points) if len(points) else None for points in by_type]
    minimum = np.full((m, m), np.inf)
    for a in range(m):
        for b in range(a, m):
            if trees[b] is None or len(by_type[a]) == 0 or (a == b and len(by_type[a]) < 2):
                continue
            k = 2 if a == b else 1  # the nearest point of one's own type is oneself
            distances, _ = trees[b].query(by_type[a], k=k)
            minimum[a, b] = minimum[b, a] = (distances[:, 1] if a == b else distances).min()
    return minimum


# ============================================================================ step 2: radii


@dataclass(frozen=True, eq=False)
class RadiusSelection:
    """Interaction radii chosen from centered L functions (Hurtut 2009, section 3.2.2).

    Parameters
    ----------
    r : ndarray, shape (n_types, n_types)
        The chosen radii (symmetric).
    table : pandas.DataFrame
        One row per unordered category pair: ``a``, ``b``, ``h``, ``r``, ``rule`` (which rule
        chose r), ``noise_sd`` (CSR standard deviation of the L estimate) and
        ``rebound_height`` (the rise that confirms a minimum).
    curves : dict
        ``(a, b) -> DataFrame`` with columns ``r`` and ``L`` (centered, sqrt(K/pi) - r): the
        curves the radii were read from, for the figures.
    """

    r: np.ndarray
    table: pd.DataFrame
    curves: dict


def select_radius(r, L, hardcore: float, rebound_height: float) -> tuple[float, str]:
    """The first local minimum of a centered L curve beyond the hard core, robust to noise.

    An estimated L curve is a staircase: L - r falls with slope -1 between pair distances and
    jumps up at each of them, so a literal "first local minimum" sits just before the first
    pair beyond the hard core whatever the pattern. We therefore call r* a local minimum only
    once the curve has *risen* by ``rebound_height`` above its running minimum: r* is the
    argmin of L on (hardcore, r_rise], where r_rise is the first r at which L exceeds
    min L(hardcore, r] by that height. Dips shallower than ``rebound_height`` (the noise
    level) are thereby ignored, without smoothing the curve or moving the minimum.

    Parameters
    ----------
    r, L : array_like
        The r grid (increasing) and centered L values; non-finite values are ignored.
    hardcore : float
        Only r > hardcore is considered (the Strauss shell must not be empty).
    rebound_height : float
        The rise that confirms a minimum, >= 0 (0: the literal first local minimum).

    Returns
    -------
    r_star : float
    rule : str
        ``"first local minimum"``, or ``"global minimum (no rebound)"`` when L never rises
        by ``rebound_height``: then r* is the argmin of L over (hardcore, rmax], the most
        regular scale examined -- the paper's "regularity with maximal amplitude" read
        literally (L still falling at rmax puts r* at rmax: regularity grows up to there).

    Raises
    ------
    ValueError
        If no finite L value lies beyond the hard core (pass a larger rmax).

    References
    ----------
    Hurtut et al. (2009), section 3.2.2.
    """
    r, L = float_array(r, "r"), float_array(L, "L")
    if r.shape != L.shape or r.ndim != 1:
        raise ValueError(f"r and L must be 1-D arrays of one length, got shapes {r.shape} and {L.shape}")
    hardcore = real_number(hardcore, "hardcore")
    rebound_height = real_number(rebound_height, "rebound_height", "a number >= 0")
    if not rebound_height >= 0:
        raise ValueError(f"rebound_height must be >= 0, got {rebound_height}")
    usable = (r > hardcore) & np.isfinite(L)
    if not usable.any():
        raise ValueError(
            f"no finite L value at r > hard core {hardcore:.6g} (largest r examined: {r.max():.6g}): pass a larger rmax"
        )
    r, L = r[usable], L[usable]
    rise = L - np.minimum.accumulate(L)
    confirmed = np.flatnonzero(rise >= rebound_height) if rebound_height > 0 else np.flatnonzero(rise > 0)
    if confirmed.size:
        return float(r[np.argmin(L[: confirmed[0] + 1])]), "first local minimum"
    return float(r[np.argmin(L)]), "global minimum (no rebound)"


def csr_L_sd(area: float, n_a: int, n_b: int, same_type: bool) -> float:
    """Standard deviation of an estimated L(r) under CSR, independent of r.

    The pair count within r is about Poisson: for one type, ordered pairs number twice a
    Poisson count of mean n^2 pi r^2 / (2|W|), so Var K = 2 pi r^2 |W| / n^2; across types,
    Var K = pi r^2 |W| / (n_a n_b). By the delta method (dL/dK = 1 / (2 pi r) at K = pi r^2),
    Var L = |W| / (2 pi n^2) and |W| / (4 pi n_a n_b): constant in r (edge effects ignored).

    Parameters
    ----------
    area : float
        Area |W| of the window (> 0).
    n_a, n_b : int
        Number of points of the two types (>= 1); equal for one type.
    same_type : bool
        Whether L is the single-type L (True) or the cross-type L between two types (False).

    Returns
    -------
    float
        ``sqrt(|W| / (2 pi n_a n_b))`` for one type, ``sqrt(|W| / (4 pi n_a n_b))`` across types.
    """
    area = positive_number(area, "area")
    n_a, n_b, same_type = integer_at_least(n_a, "n_a", 1), integer_at_least(n_b, "n_b", 1), check_flag(same_type, "same_type")
    return math.sqrt(area / ((2.0 if same_type else 4.0) * math.pi * n_a * n_b))


def _centered_L(pattern: PointPattern, a: int, b: int, correction: str, rmax) -> pd.DataFrame:
    column = L_COLUMNS[correction]
    if pattern.n_types == 1:
        table = Lest(pattern, correction=correction, rmax=rmax, centered=True)
    else:
        names = pattern.categories
        table = Lcross(pattern, names[a], names[b], correction=correction, rmax=rmax, centered=True)
    return pd.DataFrame({"r": np.asarray(table["r"], dtype=np.float64), "L": np.asarray(table[column], dtype=np.float64)})


def interaction_radii(pattern: PointPattern, hardcore, *, correction: str = "isotropic", rmax=None,
                      rebound: float = 3.0) -> RadiusSelection:
    """Interaction radius of every category pair from its centered cross-L function.

    For categories a <= b, r_ab is read off Hurtut's L_ab(r) = sqrt(K_ab(r)/pi) - r
    (``Lcross(pattern, a, b, centered=True)``; ``Lest`` for a single category) by
    :func:`select_radius`, with the rebound height ``rebound`` times the CSR standard deviation
    of L: sqrt(|W| / (2 pi n_a^2)) for a = b, sqrt(|W| / (4 pi n_a n_b)) across categories.
    Why 3: the rebound is the difference of two L estimates, whose CSR standard deviation is
    at most sqrt(2) sd, so 3 sd is about a one-sided 98% level; and a single pair of points
    just beyond the hard core already makes L jump by 2 sd (K from 0 to 2|W|/n^2), so a
    smaller threshold lets one isolated pair decide r (with 2, ``swedishpines`` gets
    r = 2.8 from two close pairs; with 3, r = 7.0, in the broad dip of its L curve between
    6.7 and 9.8). (The cross-L of a and b uses the a points as centres; with the isotropic
    correction it differs slightly from that of b and a, and we use a <= b.)

    Parameters
    ----------
    pattern : PointPattern
    hardcore : array_like, shape (n_types, n_types)
        Hard-core distances (:func:`hardcore_distances`); each r is > its h.
    correction : {"isotropic", "translate", "border", "none"}
        Edge correction of the K estimate.
    rmax : float, optional
        Largest r examined (default: spatstat's rule, as the summary functions).
    rebound : float
        Rebound height in CSR standard deviations (>= 0).

    Returns
    -------
    RadiusSelection
        Warns when some pair has no confirmed local minimum (the fallback rule was used), and
        when a pair's hard core lies beyond rmax (a category of a few widely spaced points):
        then r = h, a pure hard core (rule ``"hard core only (h beyond rmax)"``).

    References
    ----------
    Hurtut et al. (2009), section 3.2.2.
    """
    pattern = _check_pattern(pattern)
    _check_choice(correction, tuple(L_COLUMNS), "correction")
    m = pattern.n_types
    hardcore = float_array(hardcore, "hardcore", f"a {m}x{m} matrix (one per category pair)")
    if hardcore.shape != (m, m):
        raise ValueError(f"hardcore must be a {m}x{m} matrix (one per category pair), got shape {hardcore.shape}")
    if not real_number(rebound, "rebound", "a number >= 0") >= 0:
        raise ValueError(f"rebound must be >= 0, got {rebound}")
    radii = np.zeros((m, m))
    rows, curves = [], {}
    names = pattern.categories
    for a, b in _pairs(m):
        curve = _centered_L(pattern, a, b, correction, rmax)
        noise = csr_L_sd(pattern.window.area, pattern.counts[a], pattern.counts[b], a == b)
        if not (curve["r"] > hardcore[a, b]).any():
            # a hard core beyond rmax (a few widely spaced elements): no L value to read, no shell
            r_star, rule = float(hardcore[a, b]), HARDCORE_ONLY_RULE
        else:
            r_star, rule = select_radius(curve["r"], curve["L"], hardcore[a, b], rebound * noise)
        radii[a, b] = radii[b, a] = r_star
        curves[(names[a], names[b])] = curve
        rows.append({"a": names[a], "b": names[b], "h": hardcore[a, b], "r": r_star, "rule": rule,
                     "noise_sd": noise, "rebound_height": rebound * noise})
    table = pd.DataFrame(rows)
    beyond = table[table["rule"] == HARDCORE_ONLY_RULE]
    if len(beyond):
        pairs = ", ".join(f"({row.a}, {row.b})" for row in beyond.itertuples())
        warnings.warn(f"the hard core of {pairs} is beyond the largest r examined: r = h (a pure hard core, gamma "
                      "not identifiable); pass a larger rmax to look for a Strauss shell", stacklevel=2)
    fallback = table[~table["rule"].isin(["first local minimum", HARDCORE_ONLY_RULE])]
    if len(fallback):
        pairs = ", ".join(f"({row.a}, {row.b})" for row in fallback.itertuples())
        warnings.warn(f"no local minimum of the centered L function stands out from CSR noise for {pairs}: "
                      "r is the global minimum over (h, rmax] instead", stacklevel=2)
    return RadiusSelection(radii, table, curves)


def _pairs(m: int) -> list[tuple[int, int]]:
    """Unordered category pairs in spatstat's order: column by column of the upper triangle."""
    return [(a, b) for b in range(m) for a in range(b + 1)]


# ============================================================================ step 3: pseudolikelihood


@dataclass(frozen=True, eq=False)
class PPMFit:
    """A multitype Strauss hard-core model fitted by maximum pseudolikelihood.

    Parameters
    ----------
    model : MultiStraussHard
        The fitted model (beta, gamma, with the r and hc it was fitted for).
    coefficients : pandas.DataFrame
        spatstat's parametrisation (see the module docstring), indexed by spatstat's
        coefficient names, with columns ``estimate``, ``se`` (Coeurjolly-Rubak sandwich, what
        spatstat reports), ``se_hessian`` (inverse Fisher information of the log PL) and
        ``status`` (``"estimated"``, ``"boundary (gamma = 0)"``, ``"boundary (gamma =
        gamma_max)"``, ``"not identifiable (gamma = 1)"``, or ``"not identifiable (gamma =
        gamma_max)"`` when gamma_max < 1).
    vcov, vcov_hessian : pandas.DataFrame
        The two variance matrices over the estimated coefficients (those at a bound excluded).
    log_pl : float
        The maximised log pseudolikelihood (spatstat's ``logLik``).
    quadrature : QuadratureScheme
    correction : {"border", "none"}
    rbord : float
        Border correction distance (0 without correction).
    n_fitted : int
        Number of quadrature points in the sums (spatstat's ``sum(getglmsubset(fit))``).
    iterations : int
        Newton iterations used.
    gamma_max : float or None
        The upper bound on gamma the fit was constrained by (None: unconstrained).
    """

    model: MultiStraussHard
    coefficients: pd.DataFrame
    vcov: pd.DataFrame
    vcov_hessian: pd.DataFrame
    log_pl: float
    quadrature: QuadratureScheme
    correction: str
    rbord: float
    n_fitted: int
    iterations: int
    gamma_max: float | None = None

    @property
    def beta(self) -> pd.Series:
        """Fitted intensity parameter per category."""
        return pd.Series(self.model.beta, index=list(self.model.categories), name="beta")

    @property
    def gamma(self) -> pd.DataFrame:
        """Fitted interaction strength per category pair (symmetric)."""
        names = list(self.model.categories)
        return pd.DataFrame(self.model.gamma, index=names, columns=names)

    @property
    def natural(self) -> pd.DataFrame:
        """beta per category and gamma per pair, with delta-method standard errors."""
        return _natural_table(self)

    def __repr__(self) -> str:
        return f"PPMFit(log_pl={self.log_pl:.6g}, {self.model!r}, {self.quadrature!r})"


def fine_nd(pattern: PointPattern, r, hc) -> int:
    """Dummy grid side of our default quadrature: fine enough for the interaction's scales.

    The Berman-Turner sum integrates a conditional intensity that jumps on circles of radius
    h and r around every data point, so its error is governed by the grid spacing relative
    to the narrowest of these features: the hard-core radii h and the shell widths r - h
    (only those > 0). We take nd so that the spacing (longest frame side / nd) is at most
    1/16 of the smallest of them, rounded up to a multiple of spatstat's default nd (so that
    spatstat's tile rule keeps its default tiles, each then holding several dummies), and
    clipped to [spatstat's default nd, cap]. The cap, 512 or less so that all types together
    have at most 2^19 dummies, bounds time and memory; tiny hard cores (which hit it) matter
    little, as the integral's error scales with the area of the features.

    Measured (spatstat's ``cells``, StraussHard(r = 0.1, hc = 0.05)): this gives nd = 320
    against the default 32; the estimates are then within 0.015 of their nd -> infinity
    limits (log beta 7.79, log gamma -5.38; standard errors 0.86 and 1.35), whereas spatstat's
    default scheme is 0.7 away from them. ``swedishpines``, Strauss(r = 7): nd = 256, within
    0.005 (standard errors 0.30 and 0.35). Reproduce with ``ppm(..., quadrature=nd)`` over nd.

    Parameters
    ----------
    pattern : PointPattern
    r, hc : array_like, shape (n_types, n_types)
        Interaction radii and hard cores.

    Returns
    -------
    int
    """
    base = default_nd(instance_of(pattern, PointPattern, "pattern").n)
    cap = min(MAX_FINE_ND, math.isqrt(MAX_FINE_DUMMIES // pattern.n_types))
    r, hc = finite_array(r, "r"), finite_array(hc, "hc")
    try:
        np.broadcast_shapes(r.shape, hc.shape)
    except ValueError:
        raise ValueError(f"r and hc must have one shape (n_types, n_types), got {r.shape} and {hc.shape}") from None
    scales = np.concatenate([np.ravel(hc[hc > 0]), np.ravel((r - hc)[r > hc])])
    if scales.size == 0:
        return base
    side = max(pattern.window.width, pattern.window.height)
    ratio = DUMMIES_PER_SCALE * side / scales.min() / base
    wanted = base * math.ceil(ratio) if math.isfinite(ratio) else cap  # a scale tiny beside the window: the cap
    return max(base, min(cap, wanted))


def _resolve_quadrature(quadrature, pattern: PointPattern, interaction: MultiStraussHard) -> QuadratureScheme:
    if quadrature is None:
        return quadscheme(pattern, nd=fine_nd(pattern, interaction.r, interaction.hc))
    if isinstance(quadrature, str):
        _check_choice(quadrature, ("spatstat",), "quadrature (a string)")
        return quadscheme(pattern)
    if isinstance(quadrature, QuadratureScheme):
        same = (quadrature.n_data == pattern.n and quadrature.window == pattern.window
                and np.array_equal(quadrature.points[: pattern.n], pattern.points)
                and np.array_equal(quadrature.types[: pattern.n], pattern.marks))
        if not same:
            raise ValueError("the quadrature scheme was not built for this pattern (its data points differ)")
        return quadrature
    if isinstance(quadrature, (int, np.integer)) and not isinstance(quadrature, bool):
        if quadrature < 1:
            raise ValueError(f"quadrature (an nd, the dummy grid's side) must be >= 1, got {quadrature!r}")
        return quadscheme(pattern, nd=int(quadrature))
    raise ValueError(f"quadrature must be None, 'spatstat', an nd (int) or a QuadratureScheme, got {quadrature!r}")


def _coefficient_names(categories) -> list[str]:
    if len(categories) == 1:
        return ["(Intercept)", "Interaction"]
    trend = ["(Intercept)"] + [f"marks{name}" for name in categories[1:]]
    return trend + [f"mark{categories[a]}x{categories[b]}" for a, b in _pairs(len(categories))]


def _pair_columns(m: int) -> np.ndarray:
    """(m, m) symmetric index of each category pair's interaction term."""
    index = np.empty((m, m), dtype=np.int64)
    for column, (a, b) in enumerate(_pairs(m)):
        index[a, b] = index[b, a] = column
    return index


def _model_matrix(interaction: MultiStraussHard, quadrature: QuadratureScheme, pattern: PointPattern,
                  pair_distance=None):
    """Sufficient statistics s(u_j, m_j; x) of every quadrature point, and hard-core violations.

    Columns: intercept, one indicator per category after the first, then the number of data
    neighbours in the Strauss shell of each category pair. A data point does not count itself;
    a dummy copy of a data point counts it (at distance 0), as in spatstat.
    """
    m, k = interaction.n_types, quadrature.n_points
    exclude = np.where(quadrature.is_data, np.arange(k), -1)
    counts, forbidden = interaction_counts(interaction, quadrature.points, quadrature.types, pattern.points,
                                           pattern.marks, exclude, pair_distance)
    trend = (quadrature.types[:, None] == np.arange(m)).astype(np.float64)
    trend[:, 0] = 1.0  # intercept; the first category is the baseline of the contrasts
    statistics = np.zeros((k, len(_pairs(m))))
    statistics[np.arange(k)[:, None], _pair_columns(m)[quadrature.types]] = counts
    return np.hstack([trend, statistics]), forbidden


def _resolve_degenerate_terms(design, is_data, fitted, n_trend):
    """Interaction terms with no data pair in their shell: gamma = 0 or not identifiable.

    Returns the fitted mask (points given zero intensity by gamma = 0 removed) and the status
    of every interaction term. Removing points can empty another term, hence the loop.
    """
    n_terms = design.shape[1] - n_trend
    status = np.array(["estimated"] * n_terms, dtype=object)
    while True:
        active = np.flatnonzero(status == "estimated")
        statistics = design[:, n_trend + active]
        on_data = statistics[fitted & is_data].sum(axis=0)
        anywhere = statistics[fitted].sum(axis=0)
        unidentifiable = active[(on_data == 0) & (anywhere == 0)]
        boundary = active[(on_data == 0) & (anywhere > 0)]
        if unidentifiable.size == 0 and boundary.size == 0:
            return fitted, status
        status[unidentifiable] = NOT_IDENTIFIABLE
        status[boundary] = GAMMA_ZERO
        fitted = fitted & (design[:, n_trend + boundary] == 0).all(axis=1)


def _check_categories_fitted(pattern: PointPattern, fitted_data, rbord) -> None:
    counts = np.bincount(pattern.marks[fitted_data], minlength=pattern.n_types)
    empty = [name for name, count in zip(pattern.categories, counts) if count == 0]
    if empty:
        raise ValueError(
            f"category {', '.join(map(repr, empty))} has no data point farther than rbord = {rbord:.6g} from the "
            "window's boundary: its intensity cannot be estimated (use correction='none' or smaller radii)"
        )


@dataclass(frozen=True)
class _Maximum:
    theta: np.ndarray
    log_pl: float
    information: np.ndarray  # negative Hessian of the log PL (Fisher information) over the free coefficients
    iterations: int
    at_bound: np.ndarray | None = None  # bounded fits: which coefficients are held at their upper bound


def _log_pl(theta, design, weights, data_statistic):
    with np.errstate(over="ignore"):
        intensity = weights * np.exp(design @ theta)  # w_j lambda_j
    return data_statistic @ theta - intensity.sum(), intensity


def _maximise_log_pl(design, weights, is_data, start) -> _Maximum:
    """Newton's method with step halving on the concave log PL (= IRLS on the Poisson GLM).

    Stops when the Newton decrement g^T H^-1 g (twice the predicted remaining gain) is below
    ``NEWTON_TOLERANCE^2 (1 + |log PL|)``, i.e. the coefficients are within about 1e-11 of the
    maximum in the metric of the information matrix, or below what float64 can resolve in the
    log PL (a sum over up to 1e6 quadrature terms): past that, Newton steps only chase rounding
    noise and would never meet the first bound.
    """
    data_statistic = design[is_data].sum(axis=0)
    theta = start
    value, intensity = _log_pl(theta, design, weights, data_statistic)
    for iteration in range(NEWTON_MAX_ITERATIONS + 1):
        information = (design * intensity[:, None]).T @ design
        gradient = data_statistic - design.T @ intensity
        try:
            step = np.linalg.solve(information, gradient)
        except np.linalg.LinAlgError:
            raise ValueError("the pseudolikelihood's information matrix is singular: the interaction statistics are "
                             "collinear on the fitted quadrature points (try other radii)") from None
        if gradient @ step <= max(NEWTON_TOLERANCE**2, ROUNDING_RESOLUTION) * (1 + abs(value)):
            return _Maximum(theta, float(value), information, iteration)
        theta, value, intensity = _halving_step(theta, step, value, design, weights, data_statistic)
    raise ValueError(
        f"the pseudolikelihood maximisation did not converge in {NEWTON_MAX_ITERATIONS} Newton steps "
        f"(coefficients {theta.tolist()}): the maximum may not exist for these data and radii"
    )


def _halving_step(theta, step, value, design, weights, data_statistic):
    for _ in range(60):
        candidate = theta + step
        new_value, intensity = _log_pl(candidate, design, weights, data_statistic)
        if new_value >= value:
            return candidate, new_value, intensity
        step = step / 2
    raise ValueError("the pseudolikelihood maximisation stalled (no ascent along the Newton direction)")


def _maximise_bounded(design, weights, is_data, start, upper) -> _Maximum:
    """Maximise the concave log PL subject to theta <= upper, by a primal active-set method.

    The iterate stays feasible. Each round maximises the log PL over the free coefficients,
    those at their bound held fixed (:func:`_maximise_with_fixed`, Newton as in
    :func:`_maximise_log_pl`). If that maximiser leaves the box, the iterate moves towards it
    only as far as the first bound it meets (the log PL, concave, increases along the way) and
    that coefficient joins the fixed set. Otherwise it is the maximum over this fixed set, and
    the KKT conditions are checked: a fixed coefficient whose partial derivative is negative
    (the log PL would grow by lowering it) by more than the Newton tolerance is released, the
    most negative first. The log PL strictly increases from one fixed set to the next, so none
    recurs and the method terminates; it stops at a point satisfying the KKT conditions, which
    for a concave function is the constrained maximum. With no finite bound (``gamma_max``
    None) the first round is :func:`_maximise_log_pl` from ``start`` and nothing else runs.

    Returns a :class:`_Maximum` whose ``information`` is over the free coefficients only and
    whose ``at_bound`` marks the fixed ones (their ``theta`` equals ``upper``).
    """
    theta = np.minimum(start, upper)  # a feasible start (start itself unless gamma_max < 1)
    fixed = np.zeros(len(theta), dtype=bool)
    data_statistic = design[is_data].sum(axis=0)
    iterations = 0
    for _ in range(MAX_ACTIVE_SET_CHANGES):
        maximum = _maximise_with_fixed(design, weights, is_data, theta, fixed)
        iterations += maximum.iterations
        target = maximum.theta
        leaving = ~fixed & (target > upper)
        if leaving.any():
            theta, fixed = _step_to_first_bound(theta, target, upper, leaving, fixed)
            continue
        release = _kkt_violations(target, fixed, design, weights, data_statistic, maximum.log_pl)
        if release < 0:
            return _Maximum(target, maximum.log_pl, maximum.information, iterations, fixed)
        theta, fixed = target, fixed.copy()
        fixed[release] = False
    raise ValueError(f"the bounded pseudolikelihood maximisation did not settle on its active set in "
                     f"{MAX_ACTIVE_SET_CHANGES} changes (coefficients {theta.tolist()})")


def _maximise_with_fixed(design, weights, is_data, theta, fixed) -> _Maximum:
    """Maximise over the free coefficients, the fixed ones entering as an offset in the weights.

    log PL = s . theta - sum_j w_j exp(eta_j): with eta = X_f theta_f + X_x theta_x, the fixed
    part multiplies the weights by exp(X_x theta_x) and adds s_x . theta_x to the value.
    """
    if not fixed.any():
        maximum = _maximise_log_pl(design, weights, is_data, theta)
        return _Maximum(maximum.theta, maximum.log_pl, maximum.information, maximum.iterations, fixed)
    offset = design[:, fixed] @ theta[fixed]
    free = _maximise_log_pl(design[:, ~fixed], weights * np.exp(offset), is_data, theta[~fixed])
    full = theta.copy()
    full[~fixed] = free.theta
    log_pl = free.log_pl + float(offset[is_data].sum())
    return _Maximum(full, log_pl, free.information, free.iterations, fixed)


def _step_to_first_bound(theta, target, upper, leaving, fixed):
    """Move from feasible ``theta`` towards ``target`` up to the first bound met; fix it there."""
    step = target - theta
    fractions = np.full(len(theta), np.inf)
    fractions[leaving] = (upper[leaving] - theta[leaving]) / step[leaving]
    alpha = fractions.min()
    moved = np.minimum(theta + alpha * step, upper)
    hits = fractions <= alpha
    moved[hits] = upper[hits]
    return moved, fixed | hits


def _kkt_violations(theta, fixed, design, weights, data_statistic, value) -> int:
    """The fixed coefficient to release (most negative scaled derivative), or -1 if KKT holds.

    At an upper bound the KKT condition is d logPL / d theta_c >= 0. A negative derivative
    counts only if lowering theta_c alone would gain more than Newton's stopping rule
    resolves: g_c^2 / I_cc > tolerance (1 + |log PL|), I_cc the Fisher information of theta_c.
    """
    if not fixed.any():
        return -1
    _, intensity = _log_pl(theta, design, weights, data_statistic)
    columns = design[:, fixed]
    gradient = data_statistic[fixed] - columns.T @ intensity
    information = (columns * columns * intensity[:, None]).sum(axis=0)
    scaled = np.where(gradient < 0, -gradient**2 / information, 0.0)
    tolerance = max(NEWTON_TOLERANCE**2, ROUNDING_RESOLUTION) * (1 + abs(value))
    if scaled.min() >= -tolerance:
        return -1
    return int(np.flatnonzero(fixed)[np.argmin(scaled)])


def _upper_bounds(n_coefficients: int, n_trend: int, gamma_max) -> np.ndarray:
    """Upper bound of every estimated coefficient: none for the trend, log gamma_max for gamma."""
    upper = np.full(n_coefficients, np.inf)
    if gamma_max is not None:
        upper[n_trend:] = math.log(gamma_max)
    return upper


def _check_gamma_max(gamma_max):
    if gamma_max is None:
        return None
    if isinstance(gamma_max, (bool, np.bool_)) or not isinstance(gamma_max, (int, float, np.integer, np.floating)):
        raise ValueError(f"gamma_max must be a positive finite float or None, got {gamma_max!r}")
    if not (math.isfinite(gamma_max) and gamma_max > 0):
        raise ValueError(f"gamma_max must be a positive finite float or None (1.0 for Hurtut's 0 <= gamma <= 1), "
                         f"got {gamma_max!r}")
    return float(gamma_max)


def _starting_point(design, weights, is_data, types, n_types):
    # log of the observed intensity per category, as contrasts with the first; no interaction
    fitted_counts = np.bincount(types[is_data], minlength=n_types)
    fitted_areas = np.bincount(types, weights=weights, minlength=n_types)
    log_intensity = np.log(fitted_counts / fitted_areas)
    start = np.zeros(design.shape[1])
    start[0] = log_intensity[0]
    start[1:n_types] = log_intensity[1:] - log_intensity[0]
    return start


def ppm(pattern: PointPattern, r, hc=0.0, *, closed: bool = False, correction: str = "border",
        quadrature=None, pair_distance=None, gamma_max: float | None = None) -> PPMFit:
    """Fit beta and gamma of a (multitype) Strauss hard-core model by maximum pseudolikelihood.

    spatstat's ``ppm(X ~ marks, MultiStraussHard(iradii = r, hradii = hc))`` (``ppm(X ~ 1,
    StraussHard(r, hc))`` with one category), for given radii and hard cores.

    Parameters
    ----------
    pattern : PointPattern
        At least 3 points per category.
    r : float or array_like, shape (n_types, n_types)
        Interaction radii (symmetric, > 0).
    hc : float or array_like, shape (n_types, n_types)
        Hard-core distances (symmetric, 0 <= hc <= r).
    closed : bool
        False (default): a pair interacts when hc <= d < r and is forbidden when d < hc (the
        paper; spatstat's ``MultiStraussHard``). True: hc < d <= r and d <= hc (spatstat's
        ``Strauss`` and ``StraussHard``). They differ only on exact ties.
    correction : {"border", "none"}
        Border correction (default, spatstat's): only quadrature points at least
        rbord = max r from the boundary enter the sums.
    quadrature : None, "spatstat", int or QuadratureScheme
        None (default): spatstat's grid scheme with the finer nd of :func:`fine_nd`, because
        hard-core estimates depend strongly on nd. ``"spatstat"``: spatstat's default scheme.
        An int: that nd with spatstat's tile rule. Or a scheme built by
        :func:`~paperlib.pointprocess.quadrature.quadscheme` for this pattern.
    pair_distance : PairDistance, optional
        Distances between objects carried by the points, used instead of the points'
        distances: ``pair_distance.distance(i, j)`` for quadrature points ``i`` (the data
        points come first, as in every scheme) and data points ``j``. This is how Hurtut's
        section 4.3 extension (interactions on distances between bounding boxes) is fitted:
        the caller gives each quadrature point an object (:mod:`paperlib.arrangement`).
        Requires an explicit ``quadrature`` scheme, whose indices the callable knows. The
        border correction then uses rbord = max r + ``pair_distance.padding``.
    gamma_max : float, optional
        Upper bound on every gamma, a positive finite float. None (default): unconstrained,
        as spatstat's ``ppm``. 1.0: Hurtut's model, whose interaction strengths lie in [0, 1]
        (section 3.1; clustered data otherwise give gamma > 1). The log PL is maximised over
        log gamma <= log gamma_max by an active-set Newton method (KKT conditions checked; see
        the module notes). A gamma at the bound has status ``"boundary (gamma =
        gamma_max)"``, no standard error, and is left out of ``vcov``; the other coefficients
        are those of the model refitted with it fixed there. With gamma_max = 1 this is
        spatstat's ``ppm(..., project = TRUE)`` for interactions it requires to have gamma <= 1
        (``Strauss``, ``MultiStrauss``, ``MultiStraussHard`` pairs without hard core): their
        projection refits the model without the offending terms (gamma = 1) and keeps the
        valid submodel of highest log PL. spatstat accepts gamma > 1 with a hard core (a valid
        model, unlike Hurtut's); the constrained fit then equals spatstat's fit of the
        submodel (``Hardcore``, or ``MultiStraussHard`` with ``iradii`` NA for those pairs).

    Returns
    -------
    PPMFit

    Raises
    ------
    ValueError
        For a pattern of fewer than 2 points or a category of fewer than 3; inconsistent or
        invalid r / hc (shape, symmetry, hc > r); repeated locations with some hc > 0 (without
        hard core they are fitted as spatstat does: a pair at distance 0 interacts); a hard
        core that some data pair violates; a category with no point inside the
        border-corrected window; no convergence; a bad ``gamma_max``.

    References
    ----------
    Hurtut et al. (2009), section 3.2.3, eq. (3); Baddeley and Turner (2000); Besag (1977);
    Jensen and Moller (1991); Coeurjolly and Rubak (2013).
    """
    pattern = _check_pattern(pattern)
    _check_choice(correction, CORRECTIONS, "correction")
    gamma_max = _check_gamma_max(gamma_max)
    interaction = _interaction(pattern, r, hc, closed)
    if (interaction.hc > 0).any():
        require_distinct(pattern, "ppm with a hard core (hc > 0)")
    if pair_distance is not None and not isinstance(quadrature, QuadratureScheme):
        raise ValueError("pair_distance needs an explicit quadrature scheme (its indices are the callable's i)")
    _check_data_respect_hardcore(pattern, interaction, pair_distance)
    quadrature = _resolve_quadrature(quadrature, pattern, interaction)

    design, forbidden = _model_matrix(interaction, quadrature, pattern, pair_distance)
    padding = 0.0 if pair_distance is None else pair_distance.padding
    rbord = interaction.reach + padding if correction == "border" else 0.0
    fitted = ~forbidden
    if rbord > 0:
        fitted &= quadrature.window.boundary_distance(quadrature.points) >= rbord
    _check_categories_fitted(pattern, fitted[: pattern.n], rbord)
    n_trend = pattern.n_types
    fitted, status = _resolve_degenerate_terms(design, quadrature.is_data, fitted, n_trend)
    names = _coefficient_names(pattern.categories)
    _warn_degenerate(names[n_trend:], status)
    active = np.concatenate([np.arange(n_trend), n_trend + np.flatnonzero(status == "estimated")])

    X, w, is_data = design[fitted][:, active], quadrature.weights[fitted], quadrature.is_data[fitted]
    start = _starting_point(X, w, is_data, quadrature.types[fitted], pattern.n_types)
    maximum = _maximise_bounded(X, w, is_data, start, _upper_bounds(len(active), n_trend, gamma_max))
    status = _bound_status(status, active[maximum.at_bound] - n_trend, gamma_max)
    estimated = active[~maximum.at_bound]
    vcov_hessian = _inverse_or_nan(maximum.information, "Fisher information")
    vcov = _sandwich_vcov(pattern, interaction, maximum.theta, design[: pattern.n][:, estimated], fitted[: pattern.n],
                          active, ~maximum.at_bound, n_trend, pair_distance)

    estimated_names = [names[i] for i in estimated]
    return PPMFit(
        model=_fitted_model(interaction, maximum.theta, active, status, n_trend, gamma_max),
        coefficients=_coefficient_table(names, maximum.theta, active, estimated, status, vcov, vcov_hessian, n_trend),
        vcov=pd.DataFrame(vcov, index=estimated_names, columns=estimated_names),
        vcov_hessian=pd.DataFrame(vcov_hessian, index=estimated_names, columns=estimated_names),
        log_pl=maximum.log_pl,
        quadrature=quadrature,
        correction=correction,
        rbord=float(rbord),
        n_fitted=int(fitted.sum()),
        iterations=maximum.iterations,
        gamma_max=gamma_max,
    )


def _bound_status(status, at_bound, gamma_max):
    """Interaction terms held at gamma_max, and unidentifiable ones capped by gamma_max < 1."""
    status = status.copy()
    status[at_bound] = GAMMA_MAX
    if gamma_max is not None and gamma_max < 1:
        status[status == NOT_IDENTIFIABLE] = NOT_IDENTIFIABLE_CAPPED
    return status


def _warn_degenerate(term_names, status) -> None:
    degenerate = [f"{name}: {state}" for name, state in zip(term_names, status) if state != "estimated"]
    if degenerate:
        warnings.warn("interaction terms with no data pair in their shell: " + "; ".join(degenerate), stacklevel=3)


# ---------------------------------------------------------------------------- variance


def _shell_pairs(interaction: MultiStraussHard, points: np.ndarray, marks: np.ndarray, pair_distance=None):
    """Ordered data pairs (i, j), i != j, in the Strauss shell of their category pair."""
    i, j, in_shell, _ = interaction_pairs(interaction, points, marks, points, marks, exclude=np.arange(len(points)),
                                          pair_distance=pair_distance)
    return i[in_shell], j[in_shell]


def _sandwich_vcov(pattern, interaction, theta, data_design, fitted_data, active, free, n_trend,
                   pair_distance=None) -> np.ndarray:
    """Coeurjolly and Rubak's (2013) variance A1^-1 (A1 + A2 + A3) A1^-1, as spatstat's vcov.

    A1 = sum over fitted data points of s_i s_i^T. For ordered pairs (i, j) of fitted data
    points in the shell of term c, removing j lowers s_i by the unit vector e_c and scales
    lambda(x_i) by 1/gamma_c: A2 adds (1/gamma_c - 1) (s_i - e_c)(s_j - e_c)^T and A3 adds
    e_c e_c^T. ``theta`` is over the ``active`` coefficients, ``free`` marks those estimated
    (not held at gamma_max), the columns of ``data_design``: a term at its bound is an offset,
    whose pairs still scale lambda (e_c = 0 for them, and they add nothing to A3).
    """
    n_free = int(free.sum())
    A1 = data_design[fitted_data].T @ data_design[fitted_data]
    i, j = _shell_pairs(interaction, pattern.points, pattern.marks, pair_distance)
    term = _pair_columns(interaction.n_types)[pattern.marks[i], pattern.marks[j]]
    position = np.full(n_trend + len(_pairs(interaction.n_types)), -1)
    position[active] = np.arange(len(active))
    index = position[n_trend + term]
    keep = fitted_data[i] & fitted_data[j] & (index >= 0)
    i, j, index = i[keep], j[keep], index[keep]
    column = np.where(free, np.cumsum(free) - 1, -1)[index]  # -1 for terms at their bound
    unit = np.eye(n_free + 1)[column][:, :n_free]  # row -1 of the identity sliced: e_c = 0
    pair_weight = np.expm1(-theta[index])  # 1/gamma - 1
    A2 = ((data_design[i] - unit) * pair_weight[:, None]).T @ (data_design[j] - unit)
    A3 = np.diag(np.bincount(column[column >= 0], minlength=n_free).astype(np.float64))
    sigma = A1 + A2 + A3
    sigma = (sigma + sigma.T) / 2
    inverse = _inverse_or_nan(A1, "sandwich's A1")
    return inverse @ sigma @ inverse


def _inverse_or_nan(matrix: np.ndarray, what: str) -> np.ndarray:
    """The inverse, or NaNs and a warning when singular (as spatstat's checksolve)."""
    try:
        return np.linalg.inv(matrix)
    except np.linalg.LinAlgError:
        warnings.warn(f"the {what} matrix is singular: variances are not available", stacklevel=3)
        return np.full_like(matrix, np.nan)


# ---------------------------------------------------------------------------- results


def _fitted_model(interaction, theta, active, status, n_trend, gamma_max=None) -> MultiStraussHard:
    m = interaction.n_types
    full = np.zeros(n_trend + len(status))
    full[active] = theta
    log_beta = full[0] + np.concatenate([[0.0], full[1:n_trend]])
    log_gamma = full[n_trend:].copy()
    log_gamma[status == GAMMA_ZERO] = -np.inf
    gamma = np.exp(log_gamma)
    if gamma_max is not None:
        gamma[(status == GAMMA_MAX) | (status == NOT_IDENTIFIABLE_CAPPED)] = gamma_max  # exactly, not exp(log)
    gamma = gamma[_pair_columns(m)]
    return MultiStraussHard(np.exp(log_beta), gamma, interaction.r, interaction.hc, interaction.categories,
                            interaction.closed)


def _coefficient_table(names, theta, active, estimated, status, vcov, vcov_hessian, n_trend) -> pd.DataFrame:
    k = len(names)
    estimate, se, se_hessian = np.full(k, np.nan), np.full(k, np.nan), np.full(k, np.nan)
    estimate[active] = theta
    se[estimated] = np.sqrt(np.diag(vcov))
    se_hessian[estimated] = np.sqrt(np.diag(vcov_hessian))
    full_status = np.concatenate([["estimated"] * n_trend, status])
    estimate[full_status == GAMMA_ZERO] = -np.inf
    return pd.DataFrame({"estimate": estimate, "se": se, "se_hessian": se_hessian, "status": full_status},
                        index=pd.Index(names, name="coefficient"))


def _natural_table(fit: PPMFit) -> pd.DataFrame:
    """beta_m = exp(theta_0 + theta_m), gamma = exp(theta_c); SEs by the delta method."""
    names = list(fit.coefficients.index)
    rows = []
    for kind, label, terms, value in _natural_quantities(fit.model):
        row = {"parameter": kind, "label": label, "estimate": value}
        keys = [names[i] for i in terms]
        for column, vcov in (("se", fit.vcov), ("se_hessian", fit.vcov_hessian)):
            estimable = all(key in vcov.index for key in keys)
            # se(exp(sum of coefficients)) = value * sqrt(sum of their covariances)
            row[column] = value * math.sqrt(vcov.loc[keys, keys].to_numpy().sum()) if estimable else np.nan
        rows.append(row)
    return pd.DataFrame(rows).set_index(["parameter", "label"])


def _natural_quantities(model: MultiStraussHard):
    """(kind, label, coefficient indices whose sum is its log, value) of every beta and gamma."""
    categories, n_trend = model.categories, model.n_types
    for t, name in enumerate(categories):
        yield "beta", name, [0] if t == 0 else [0, t], float(model.beta[t])
    for column, (a, b) in enumerate(_pairs(n_trend)):
        yield "gamma", f"{categories[a]}-{categories[b]}", [n_trend + column], float(model.gamma[a, b])


# ============================================================================ all three steps


@dataclass(frozen=True, eq=False)
class StraussHardcoreFit:
    """Hurtut's estimation of a multitype Strauss hard-core model (section 3.2).

    Parameters
    ----------
    fit : PPMFit
        The pseudolikelihood fit of beta and gamma (step 3).
    hardcore : str
        How h was estimated ("minimum" or "spatstat").
    distances : pandas.DataFrame
        One row per unordered category pair: ``a``, ``b``, ``h``, ``r``, ``rule`` (how r was
        chosen), ``noise_sd`` and ``rebound_height`` (see :func:`interaction_radii`; NaN when
        the radii were given).
    L_curves : dict
        ``(a, b) -> DataFrame[r, L]``: the centered L curves r was read from (empty when the
        radii were given).
    """

    fit: PPMFit
    hardcore: str
    distances: pd.DataFrame
    L_curves: dict

    @property
    def model(self) -> MultiStraussHard:
        return self.fit.model

    @property
    def coefficients(self) -> pd.DataFrame:
        return self.fit.coefficients

    @property
    def log_pl(self) -> float:
        return self.fit.log_pl

    @property
    def vcov(self) -> pd.DataFrame:
        return self.fit.vcov

    @property
    def quadrature(self) -> QuadratureScheme:
        return self.fit.quadrature

    @property
    def beta(self) -> pd.Series:
        return self.fit.beta

    @property
    def gamma(self) -> pd.DataFrame:
        return self.fit.gamma

    def __repr__(self) -> str:
        return f"StraussHardcoreFit(hardcore={self.hardcore!r}, {self.fit!r})"


def fit_strauss_hardcore(pattern: PointPattern, *, hardcore: str = "minimum", r=None, correction: str = "border",
                         quadrature=None, L_correction: str = "isotropic", rmax=None,
                         rebound: float = 3.0, gamma_max: float | None = None) -> StraussHardcoreFit:
    """Estimate a multitype Strauss hard-core model as Hurtut et al. (2009), section 3.2.

    Step 1: h per category pair (:func:`hardcore_distances`); step 2: r per pair from the
    centered cross-L functions (:func:`interaction_radii`), unless given; step 3: beta and
    gamma by maximum pseudolikelihood (:func:`ppm`, open convention: pairs at d < h are
    forbidden, h <= d < r interact).

    Parameters
    ----------
    pattern : PointPattern
        At least 3 points per category (the paper's assumption).
    hardcore : {"minimum", "spatstat"}
        The paper's minimum distance, or spatstat's minimum * m/(m+1).
    r : float or array_like, optional
        Interaction radii to use instead of step 2; each must be >= its h.
    correction : {"border", "none"}
        Edge correction of the pseudolikelihood (see :func:`ppm`).
    quadrature : None, "spatstat", int or QuadratureScheme
        See :func:`ppm`.
    L_correction : {"isotropic", "translate", "border", "none"}
        Edge correction of the L estimates of step 2.
    rmax : float, optional
        Largest r examined in step 2.
    rebound : float
        Step 2's rebound height in CSR standard deviations of L.
    gamma_max : float, optional
        Upper bound on gamma in step 3 (see :func:`ppm`): None (default) fits gamma freely,
        1.0 keeps the paper's 0 <= gamma <= 1 (section 3.1).

    Returns
    -------
    StraussHardcoreFit

    References
    ----------
    Hurtut et al. (2009), section 3.2 (3.2.1-3.2.3), eqs. (2) and (3).
    """
    pattern = _check_pattern(pattern)
    _check_choice(hardcore, HARDCORE_METHODS, "hardcore")
    _check_choice(correction, CORRECTIONS, "correction")
    gamma_max = _check_gamma_max(gamma_max)
    h = hardcore_distances(pattern, hardcore)
    if r is None:
        selection = interaction_radii(pattern, h, correction=L_correction, rmax=rmax, rebound=rebound)
        radii, distances, curves = selection.r, selection.table, selection.curves
    else:
        radii = _given_radii(pattern, r, h)
        distances = pd.DataFrame([{"a": pattern.categories[a], "b": pattern.categories[b], "h": h[a, b],
                                   "r": radii[a, b], "rule": "given", "noise_sd": np.nan,
                                   "rebound_height": np.nan} for a, b in _pairs(pattern.n_types)])
        curves = {}
    fit = ppm(pattern, radii, h, closed=False, correction=correction, quadrature=quadrature, gamma_max=gamma_max)
    return StraussHardcoreFit(fit, hardcore, distances, curves)


def _given_radii(pattern: PointPattern, r, h) -> np.ndarray:
    m = pattern.n_types
    radii = finite_array(r, "r")
    if radii.ndim == 0:
        radii = np.full((m, m), float(radii))
    if radii.shape != (m, m):
        raise ValueError(f"r must be a scalar or a {m}x{m} matrix, got shape {radii.shape}")
    if (radii < h).any():
        a, b = np.argwhere(radii < h)[0]
        raise ValueError(f"r[{pattern.categories[a]!r}, {pattern.categories[b]!r}] = {radii[a, b]:.6g} is below the "
                         f"hard core h = {h[a, b]:.6g}: the interaction radius must be >= h")
    return radii
