"""Global Monte Carlo goodness-of-fit tests: spatstat's ``dclf.test`` and ``mad.test``.

A pointwise envelope (:func:`~paperlib.pointprocess.envelope.envelope`) cannot test a model: a
curve leaving it at some r out of hundreds is expected. A global test reduces the deviation of
the observed summary function from the model's to one number T over an interval of r, computes
the same number for ``nsim`` simulations of the model, and ranks the observed T among them
(Baddeley et al. 2014):

- Diggle-Cressie-Loosmore-Ford (DCLF, :func:`dclf_test`): T = integral over the r interval of
  the squared deviation, spatstat's ``u = (r_hi - r_lo) * mean over r of d(r)^2``;
- maximum absolute deviation (MAD, :func:`mad_test`): T = max over the interval of d(r).

The deviation d(r) of a curve f from the reference follows spatstat's ``envelopeTest``. With
the theoretical function as reference (spatstat's default under CSR, ``use.theory``), d = f -
theo. Otherwise the reference is the pointwise mean of the simulated curves and the observed
one, and d is, by ``leaveout``: 0, f - mean; 1 (default), (f - mean) (nsim + 1) / nsim, i.e. f
minus the mean of the *other* nsim curves; 2, f minus the mean of the simulated curves other
than f (for the observed curve, spatstat leaves out the first simulated curve). ``alternative``
"two.sided" uses |d|; "less" -d (or its positive part with ``clamp``); "greater" d (idem), and
DCLF then integrates sign(d) d^2 unless clamped.

The p-value is (1 + #{simulated T >= observed T}) / (nsim + 1): the observed pattern is rejected
at level alpha = k / (nsim + 1) when its T is among the k largest. spatstat's default breaks
ties between T values at random (``tie.rule = "randomise"``); ``ties`` offers that and its
"mean" rule. With continuous summary functions ties have probability zero.

The simulations go through the machinery of :func:`~paperlib.pointprocess.envelope.envelope`
(CSR with the observed intensities, a :class:`~paperlib.pointprocess.models.MultiStraussHard`
simulated by ``rmh``, or given patterns, spatstat's ``simulate = <list>``), in parallel and
seeded per simulation. Not implemented: spatstat's ``scale`` and ``interpolate`` options.

References
----------
Diggle, P. J. (1986). Displaced amacrine cells in the retina of a rabbit: analysis of a
    bivariate spatial point pattern. J. Neuroscience Methods 18, 115-125.
Cressie, N. A. C. (1991). Statistics for Spatial Data. Wiley, section 8.2.
Loosmore, N. B. and Ford, E. D. (2006). Statistical inference using the G or K point pattern
    spatial statistics. Ecology 87, 1925-1931.
Baddeley, A., Diggle, P. J., Hardegen, A., Lawrence, T., Milne, R. K. and Nair, G. (2014). On
    tests of spatial pattern based on simulation envelopes. Ecological Monographs 84, 477-489.
Baddeley, A., Rubak, E. and Turner, R. (2015). Spatial Point Patterns, section 10.7
    (spatstat's ``dclf.test``, ``mad.test``).
Hurtut et al. (2009), section 3.2.2: the L functions by which arrangements are compared.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import pandas as pd

from paperlib._checks import check_choice, check_flag

from .envelope import _simulated_curves

__all__ = ["GlobalTest", "dclf_test", "mad_test"]

ALTERNATIVES = ("two.sided", "less", "greater")
TIE_RULES = ("conservative", "mean", "randomise")
LEAVEOUT = (0, 1, 2)


@dataclass(frozen=True, eq=False)
class GlobalTest:
    """The result of a global Monte Carlo test (spatstat's ``htest`` from ``envelopeTest``).

    Parameters
    ----------
    test : str
        ``"DCLF"`` or ``"MAD"``.
    statistic : float
        T of the observed pattern (spatstat's ``statistic``: ``u`` for DCLF, ``mad`` for MAD).
    p_value : float
        rank / (n_sim + 1), rank = 1 + #{simulated T > observed T} + the tie rule's share.
    n_sim : int
        Number of simulated curves.
    rinterval : tuple of float
        The interval of r the deviations were taken over (spatstat's ``attr(, "rinterval")``,
        after its adjustments).
    simulated : ndarray, shape (n_sim,)
        T of each simulated curve.
    column : str
        The estimate of the summary function used (e.g. ``"iso"``).
    alternative : str
    reference : str
        ``"theoretical"`` or ``"sample mean"``.
    leaveout : int
        0, 1 or 2 (0 whenever the reference is theoretical).
    """

    test: str
    statistic: float
    p_value: float
    n_sim: int
    rinterval: tuple
    simulated: np.ndarray
    column: str
    alternative: str
    reference: str
    leaveout: int

    def __repr__(self) -> str:
        lo, hi = self.rinterval
        return (f"GlobalTest({self.test}, statistic={self.statistic:.6g}, p_value={self.p_value:.4g}, "
                f"n_sim={self.n_sim}, rinterval=({lo:.6g}, {hi:.6g}), column={self.column!r}, "
                f"alternative={self.alternative!r}, reference={self.reference!r}, leaveout={self.leaveout})")


_PARAMETERS = """
    Parameters
    ----------
    observed : PointPattern or pandas.DataFrame
        The pattern tested; under CSR it fixes the window and the intensity of each type. Or
        an envelope made with ``savefuns=True`` (:func:`~paperlib.pointprocess.envelope.envelope`),
        tested against the curves it kept, as spatstat's ``dclf.test(E)``: one set of simulations
        serves both tests. Then ``fun`` and the options that make curves (``model``, ``patterns``,
        ``nsim``, ``r``, ``column``, ``fun_kwargs``, ``simulate_kwargs``, ``client``, ``workers``,
        ``progress``) are not given, and ``rng`` only draws ties.
    fun : callable
        A summary function ``fun(pattern, r=r, **fun_kwargs) -> DataFrame`` with columns
        ``r``, ``theo`` and estimates (:func:`~paperlib.pointprocess.summary.Lest`, ``Kest``,
        ``Lcross``, ``pcf``, ...); module-level, as it goes to worker processes.
    model : MultiStraussHard, optional
        The null model, simulated by :func:`~paperlib.pointprocess.simulate.rmh` in the
        observed window (``simulate_kwargs`` go to rmh). Default: CSR with the observed
        intensity of each type.
    patterns : sequence of PointPattern, optional
        Simulated patterns to use instead (spatstat's ``simulate = <list>``), e.g. from
        another program; not with ``model``.
    nsim : int, optional
        Number of simulations (default 99, or all the ``patterns``).
    r : array_like, optional
        Distances; default the grid ``fun`` chooses for ``observed``.
    column : str, optional
        Estimate to use; default the first column after ``r`` and ``theo`` (pass ``"iso"``
        for spatstat's default with ``Kest``/``Lest``/``pcf``).
    rinterval : (float, float), optional
        Interval of r over which deviations count (default: the whole grid). An upper end
        beyond the grid is trimmed with a warning; where the observed curve is not finite at
        the first r only (``pcf`` at 0), that r is dropped and the interval starts at the
        next, with a warning (both as spatstat).
    alternative : {"two.sided", "less", "greater"}
        Deviations counted: both ways, or only below / above the reference.
    clamp : bool
        With a one-sided alternative, count deviations the other way as 0 instead of negative.
    leaveout : {0, 1, 2}
        How the sample-mean reference leaves out the curve compared (see the module notes).
    use_theory : bool, optional
        Use the ``theo`` column as reference. Default: when the null model is CSR simulated
        here (spatstat's rule), not with ``model`` or ``patterns``.
    ties : {"conservative", "mean", "randomise"}
        Share of the rank given to ties between observed and simulated T: all of them (the
        p-value (1 + #{T_sim >= T_obs}) / (nsim + 1)), half, or a uniform random number of them
        (spatstat's default).
    fun_kwargs, simulate_kwargs : dict, optional
        Extra arguments of ``fun`` and of ``rmh``.
    rng : None, int or Generator
        Parent of the per-simulation seeds (and of the tie draw).
    client, workers, progress
        As for :func:`~paperlib.pointprocess.envelope.envelope`.

    Returns
    -------
    GlobalTest

    Raises
    ------
    ValueError, TypeError
        Bad options (named), a model and patterns together, nsim above the number of
        patterns, an rinterval holding no r value, observed or simulated curves that are
        nowhere finite.
"""


def dclf_test(observed, fun=None, *, model=None, patterns=None, nsim=None, r=None, column=None,
              rinterval=None, alternative: str = "two.sided", clamp: bool = False, leaveout: int = 1,
              use_theory=None, ties: str = "conservative", fun_kwargs=None, simulate_kwargs=None, rng=None,
              client=None, workers=None, progress: bool = False) -> GlobalTest:
    return _global_test(2, **locals())


def mad_test(observed, fun=None, *, model=None, patterns=None, nsim=None, r=None, column=None,
             rinterval=None, alternative: str = "two.sided", clamp: bool = False, leaveout: int = 1,
             use_theory=None, ties: str = "conservative", fun_kwargs=None, simulate_kwargs=None, rng=None,
             client=None, workers=None, progress: bool = False) -> GlobalTest:
    return _global_test(np.inf, **locals())


dclf_test.__doc__ = """Diggle-Cressie-Loosmore-Ford test of a point process model (spatstat's ``dclf.test``).

    T = the integral over ``rinterval`` of the squared deviation of the summary function from
    its reference (see :mod:`paperlib.pointprocess.gof`), observed and for each simulation;
    p = (1 + #{simulated T >= observed T}) / (nsim + 1).
""" + _PARAMETERS + """
    References
    ----------
    Diggle (1986); Cressie (1991); Loosmore and Ford (2006); Baddeley et al. (2014);
    spatstat's ``dclf.test``. Hurtut 2009, section 3.2.2 (L functions).
"""

mad_test.__doc__ = """Maximum absolute deviation test of a point process model (spatstat's ``mad.test``).

    T = the maximum over ``rinterval`` of the deviation of the summary function from its
    reference (see :mod:`paperlib.pointprocess.gof`), observed and for each simulation;
    p = (1 + #{simulated T >= observed T}) / (nsim + 1). The test of a global envelope.
""" + _PARAMETERS + """
    References
    ----------
    Ripley (1977); Baddeley et al. (2014); spatstat's ``mad.test``. Hurtut 2009,
    section 3.2.2 (L functions).
"""


def _global_test(exponent, observed, fun, *, model, patterns, nsim, r, column, rinterval, alternative, clamp,
                 leaveout, use_theory, ties, fun_kwargs, simulate_kwargs, rng, client, workers,
                 progress) -> GlobalTest:
    _check_options(alternative, clamp, leaveout, use_theory, ties)
    progress = check_flag(progress, "progress")
    curve_options = dict(model=model, patterns=patterns, nsim=nsim, r=r, column=column, fun_kwargs=fun_kwargs,
                         simulate_kwargs=simulate_kwargs, client=client, workers=workers)
    if isinstance(observed, pd.DataFrame):
        given = {name for name, value in {"fun": fun, **curve_options}.items() if value is not None}
        observed_values, column, simulated, csr = _saved_curves(observed, given | ({"progress"} if progress else set()))
    else:
        if not callable(fun):
            raise TypeError(f"fun must be a summary function such as Lest, got {type(fun).__name__} {fun!r:.40}")
        observed_values, column, simulated = _simulated_curves(
            observed, fun, rng=rng, progress=progress, desc="dclf_test" if exponent == 2 else "mad_test",
            **curve_options)
        csr = model is None and patterns is None
    r, obs = observed_values["r"].to_numpy(), observed_values[column].to_numpy()
    if use_theory is None:
        use_theory = csr and "theo" in observed_values
    if use_theory and "theo" not in observed_values:
        raise ValueError("use_theory=True but fun gives no theoretical column 'theo'")
    if use_theory:
        reference, leaveout = observed_values["theo"].to_numpy(), 0
    else:
        reference = _sample_mean(simulated if leaveout == 2 else np.vstack([simulated, obs]))
    rows, interval = _r_rows(r, obs, simulated, rinterval)
    n = len(simulated)
    deviations = np.vstack([_deviation(obs, reference, leaveout, n, simulated[0]),
                            _deviation(simulated, reference, leaveout, n, simulated)])
    # one array, one summation order: equal curves give equal T (ties)
    t_obs, *t_sim = _statistic(exponent, deviations[:, rows], alternative, clamp, interval)
    t_sim = np.array(t_sim)
    return GlobalTest("DCLF" if exponent == 2 else "MAD", float(t_obs), _p_value(t_obs, t_sim, ties, rng), n,
                      interval, t_sim, column, alternative, "theoretical" if use_theory else "sample mean",
                      leaveout)


def _saved_curves(envelope: pd.DataFrame, given: set):
    """The observed curve, its column, the simulated curves and whether the null was CSR, from an envelope
    made with ``savefuns=True``; ``given``: the names of curve-making options passed besides (an error)."""
    if given:
        raise ValueError(f"an envelope carries its curves: {', '.join(sorted(given))} must not be given with it")
    missing = {"r", "obs", "theo"} - set(envelope.columns)
    if missing or "simulated" not in envelope.attrs:
        raise ValueError("observed must be a PointPattern or an envelope made with savefuns=True "
                         f"(columns r, obs, theo and attrs['simulated']); got columns {list(envelope.columns)[:8]} "
                         f"and attrs {sorted(envelope.attrs)[:8]}")
    simulated = np.asarray(envelope.attrs["simulated"], dtype=float)
    if simulated.ndim != 2 or simulated.shape[1] != len(envelope) or len(simulated) < 1:
        raise ValueError(f"the envelope's saved curves have shape {simulated.shape}, expected (nsim, {len(envelope)})")
    column = envelope.attrs.get("column", "obs")
    observed_values = pd.DataFrame({"r": envelope["r"].to_numpy(), "theo": envelope["theo"].to_numpy(),
                                    column: envelope["obs"].to_numpy()})
    return observed_values, column, simulated, envelope.attrs.get("null") == "csr"


def _check_options(alternative, clamp, leaveout, use_theory, ties) -> None:
    check_choice(alternative, ALTERNATIVES, "alternative")
    check_choice(ties, TIE_RULES, "ties")
    integer = isinstance(leaveout, (int, np.integer)) and not isinstance(leaveout, (bool, np.bool_))
    if not integer or leaveout not in LEAVEOUT:
        raise ValueError(f"leaveout must be 0, 1 or 2, got {leaveout!r:.80}")
    check_flag(clamp, "clamp")
    if use_theory is not None and not isinstance(use_theory, (bool, np.bool_)):
        raise TypeError(f"use_theory must be None, True or False, got {use_theory!r}")


def _r_rows(r, obs, simulated, rinterval):
    """Rows of the r grid in the interval and the interval itself, with spatstat's adjustments."""
    lo, hi = _checked_rinterval(rinterval, r)
    rows = (lo <= r) & (r <= hi)
    if not rows.any():
        raise ValueError(f"rinterval ({lo:g}, {hi:g}) holds no r value of the grid")
    bad = ~np.isfinite(obs)
    if bad.all():
        raise ValueError("the observed summary function is nowhere finite")
    first = int(np.argmax(rows))
    if bad[rows].any():
        if bad[first] and not bad[rows][1:].any():
            rows[first] = False
            lo = float(r[first + 1]) if first + 1 < len(r) else lo
            warnings.warn(f"the observed summary function is not finite at r = {r[first]:g}: the r interval "
                          f"starts at {lo:g} instead", stacklevel=4)
        else:
            warnings.warn(f"the observed summary function is not finite at some r up to {r[bad].max():g}; "
                          "consider a shorter rinterval", stacklevel=4)
    nowhere = ~np.isfinite(simulated[:, rows]).any(axis=1)
    if nowhere.all():
        raise ValueError("the simulated summary functions are nowhere finite in rinterval (empty simulations?)")
    if nowhere.any():
        warnings.warn(f"in {nowhere.sum()} of {len(nowhere)} simulations the summary function is nowhere finite "
                      "in rinterval (empty patterns?)", stacklevel=4)
    return rows, (float(lo), float(hi))


def _checked_rinterval(rinterval, r):
    if rinterval is None:
        return float(r[0]), float(r[-1])
    try:
        lo, hi = (float(v) for v in rinterval)
    except (TypeError, ValueError):
        raise ValueError(f"rinterval must be two numbers (r_lo, r_hi), got {rinterval!r}") from None
    if not (np.isfinite(lo) and np.isfinite(hi) and 0 <= lo < hi):
        raise ValueError(f"rinterval must satisfy 0 <= r_lo < r_hi (finite), got {rinterval!r}")
    if lo > r[-1]:
        raise ValueError(f"rinterval ({lo:g}, {hi:g}) lies beyond the largest r of the grid, {r[-1]:g}")
    if hi > r[-1]:
        warnings.warn(f"rinterval ({lo:g}, {hi:g}) is trimmed to the r grid: ({lo:g}, {r[-1]:g})", stacklevel=5)
        hi = float(r[-1])
    return lo, hi


def _sample_mean(curves):
    """Mean over curves at each r, NaNs ignored (NaN where all are, silently, as spatstat)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return np.nanmean(curves, axis=0)


def _deviation(curves, reference, leaveout, n, left_out):
    """spatstat's ``Deviation``: the curve minus its reference, per ``leaveout`` (inf - inf is NaN)."""
    with np.errstate(invalid="ignore"):
        if leaveout == 0:
            return curves - reference
        if leaveout == 1:
            return (curves - reference) * (n + 1) / n
        return curves - (n * reference - left_out) / (n - 1)


def _statistic(exponent, deviation, alternative, clamp, interval):
    """T over the last axis: max (MAD) or interval length times the mean of d^2 (DCLF), NaNs ignored."""
    if alternative == "two.sided":
        d = np.abs(deviation)
    else:
        d = deviation if alternative == "greater" else -deviation
        d = np.maximum(d, 0.0) if clamp else d
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN rows give NaN, as spatstat
        if np.isinf(exponent):
            return np.nanmax(d, axis=-1)
        length = interval[1] - interval[0] if d.shape[-1] > 1 else 1.0
        return length * np.nanmean(np.sign(d) * d**2, axis=-1)


def _p_value(t_obs, t_sim, ties, rng) -> float:
    above = np.sum(t_sim > t_obs)
    tied = int(np.sum(t_sim == t_obs))
    if ties == "conservative":
        share = tied
    elif ties == "mean":
        share = tied / 2
    else:
        share = int(np.random.default_rng(rng).integers(1, tied + 1)) if tied else 0
    return float((1 + above + share) / (len(t_sim) + 1))
