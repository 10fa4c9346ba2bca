"""Simulation envelopes of summary functions (spatstat's ``envelope``).

An envelope brackets a summary function (``Lest``, ``Lcross``, ...) of an observed
pattern by the same function computed on ``nsim`` simulations of a null model: CSR with
the observed intensities, or a fitted Gibbs model simulated by Metropolis-Hastings. It is
how the figures compare a synthesised arrangement with its exemplar (Hurtut 2009,
section 3.2.2 reads regularity off the L function).

The simulations go through :func:`paperlib.parallel.run_many`, so ``nsim = 999`` can run
on a Dask cluster by passing ``client``; each simulation gets its own spawned seed, so
the envelope is the same whatever runs it.

References
----------
Ripley, B. D. (1981). Spatial Statistics, section 8.3 (Monte Carlo tests).
Baddeley, A., Rubak, E., Turner, R. (2015). Spatial Point Patterns, section 10.7.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd

from paperlib._checks import check_choice, check_flag
from paperlib.parallel import run_many

from .models import MultiStraussHard
from .pattern import PointPattern
from .processes import rpoispp

__all__ = ["envelope"]

_KINDS = ("pointwise", "global")
DEFAULT_NSIM = 99  # spatstat's


def _simulate(task, rng):
    """One simulation of the null model, summarised: ``fun(pattern, r=r, **fun_kwargs)[column]``."""
    fun, fun_kwargs, column, r, model, window, categories, intensity, simulate_kwargs = task
    if model is None:
        pattern = rpoispp(intensity, window, categories=categories, rng=rng)
    else:
        from .simulate import rmh

        pattern = rmh(model, window, rng=rng, **simulate_kwargs)
    return _curve(fun, pattern, r, column, fun_kwargs)


def _summarise(task):
    """A given pattern, summarised (spatstat's ``envelope(..., simulate = <list of patterns>)``)."""
    fun, fun_kwargs, column, r, pattern = task
    return _curve(fun, pattern, r, column, fun_kwargs)


def _curve(fun, pattern, r, column, fun_kwargs):
    return fun(pattern, r=r, **fun_kwargs)[column].to_numpy()


def _simulated_curves(observed: PointPattern, fun, *, model=None, patterns=None, nsim=None, r=None, column=None,
                     fun_kwargs=None, simulate_kwargs=None, rng=None, client=None, workers=None,
                     progress: bool = False, desc: str = "envelope"):
    """The observed summary function and ``nsim`` simulated ones on its r grid.

    The one place where simulations of a null model (CSR with the observed intensity of each
    type, or ``model`` by :func:`~paperlib.pointprocess.simulate.rmh`), or given patterns, are
    summarised, through :func:`paperlib.parallel.run_many`; :func:`envelope` and the global
    tests of :mod:`paperlib.pointprocess.gof` use it. Arguments as for :func:`envelope`, plus
    ``patterns``: a sequence of PointPatterns used instead of simulations (its first ``nsim``;
    all of them when ``nsim`` is None).

    Returns
    -------
    observed_values : pandas.DataFrame
        ``fun(observed, r=r, **fun_kwargs)``.
    column : str
        The estimate used (default: the first column after ``r`` and ``theo``).
    simulated : ndarray, shape (nsim, len(r))
    """
    if not isinstance(observed, PointPattern):
        raise ValueError(f"observed must be a PointPattern, got {type(observed).__name__}")
    if model is not None and patterns is not None:
        raise ValueError("give a model to simulate or a list of patterns, not both")
    patterns = _checked_patterns(patterns)
    nsim = _checked_nsim(nsim, patterns)
    if model is not None and model.n_types != observed.n_types:
        raise ValueError(f"the model has {model.n_types} types, the observed pattern {observed.n_types}")
    fun_kwargs = dict(fun_kwargs or {})
    observed_values = fun(observed, r=r, **fun_kwargs)
    column = column or [c for c in observed_values.columns if c not in ("r", "theo")][0]
    if column not in observed_values.columns:
        raise ValueError(f"fun gives no column {column!r}; it gives {list(observed_values.columns)}")
    r = observed_values["r"].to_numpy()
    options = dict(client=client, workers=workers, progress=progress, desc=desc)
    if patterns is not None:
        tasks = [(fun, fun_kwargs, column, r, pattern) for pattern in patterns[:nsim]]
        curves = run_many(_summarise, tasks, seeded=False, **options)
    else:
        intensity = observed.counts / observed.window.area
        task = (fun, fun_kwargs, column, r, model, observed.window, observed.categories, intensity,
                dict(simulate_kwargs or {}))
        curves = run_many(_simulate, [task] * nsim, rng=rng, **options)
    return observed_values, column, np.vstack(curves)


def _checked_patterns(patterns):
    if patterns is None:
        return None
    if isinstance(patterns, PointPattern) or not isinstance(patterns, Sequence):
        raise TypeError(f"patterns must be a sequence (list, tuple) of PointPatterns, got {type(patterns).__name__}")
    wrong = [i for i, pattern in enumerate(patterns) if not isinstance(pattern, PointPattern)]
    if wrong:
        raise TypeError(f"patterns[{wrong[0]}] is a {type(patterns[wrong[0]]).__name__}, not a PointPattern")
    if not patterns:
        raise ValueError("patterns is empty: give at least one simulated pattern")
    return list(patterns)


def _checked_nsim(nsim, patterns) -> int:
    if nsim is None:
        return DEFAULT_NSIM if patterns is None else len(patterns)
    if isinstance(nsim, bool) or not isinstance(nsim, (int, np.integer)) or nsim < 1:
        raise ValueError(f"nsim must be a positive integer, got {nsim!r}")
    if patterns is not None and nsim > len(patterns):
        raise ValueError(f"nsim={nsim} but only {len(patterns)} patterns were given")
    return int(nsim)


def envelope(
    observed: PointPattern,
    fun,
    *,
    model: MultiStraussHard | None = None,
    patterns=None,
    nsim: int | None = None,
    nrank: int = 1,
    kind: str = "pointwise",
    r=None,
    column: str | None = None,
    fun_kwargs: dict | None = None,
    simulate_kwargs: dict | None = None,
    rng=None,
    client=None,
    workers=None,
    progress: bool = False,
    savefuns: bool = False,
) -> pd.DataFrame:
    """Pointwise or global simulation envelope of a summary function.

    Parameters
    ----------
    observed : PointPattern
        The pattern whose summary function is bracketed; it fixes the window and,
        under CSR, the intensity of each type.
    fun : callable
        ``fun(pattern, r=r, **fun_kwargs) -> DataFrame`` with columns ``r``, ``theo``
        and estimates, e.g. :func:`~paperlib.pointprocess.summary.Lest`. Must be a
        module-level function (it is sent to worker processes).
    model : MultiStraussHard, optional
        Null model simulated with :func:`~paperlib.pointprocess.simulate.rmh` in the
        observed window. Default: CSR with the observed intensity of each type.
    patterns : sequence of PointPattern, optional
        Simulated patterns to use instead (spatstat's ``simulate = <list>``); not with ``model``.
    nsim : int, optional
        Number of simulations (default 99, spatstat's, or all the ``patterns``).
    nrank : int
        Rank of the envelope: pointwise, the ``nrank``-th smallest and largest
        simulated value at each r (two-sided significance ``2 nrank / (nsim + 1)``);
        global, ``theo ± `` the ``nrank``-th largest maximum absolute deviation.
    kind : {"pointwise", "global"}
    r : array_like, optional
        Distances; default the grid ``fun`` chooses for the observed pattern.
    column : str, optional
        Which estimate to use; default the first column after ``r`` and ``theo``.
    fun_kwargs, simulate_kwargs : dict, optional
        Extra arguments of ``fun`` and of ``rmh``.
    rng : None, int or Generator
        Parent of the per-simulation seeds.
    client : dask.distributed.Client, optional
        Run the simulations on this cluster.
    workers : int, optional
        Local processes (default: all CPUs; 1 runs in this process).
    progress : bool
        Show a progress bar.
    savefuns : bool
        Keep the simulated curves in the result (spatstat's ``savefuns``), so that
        :func:`~paperlib.pointprocess.gof.dclf_test` and :func:`~paperlib.pointprocess.gof.mad_test`
        can test the observed pattern against them without simulating again.

    Returns
    -------
    pandas.DataFrame
        Columns ``r``, ``obs``, ``theo``, ``lo``, ``hi``, ``mean`` (mean of the
        simulations); ``attrs`` hold ``nsim``, ``nrank``, ``kind``, ``column``, the
        significance level ``alpha`` and ``null`` (``"csr"``, ``"model"`` or ``"patterns"``); with
        ``savefuns``, ``attrs["simulated"]`` holds the ``nsim`` curves, as nested lists (an array
        would break pandas' comparison of attrs).
    """
    check_choice(kind, _KINDS, "kind")
    savefuns = check_flag(savefuns, "savefuns")
    nsim = _checked_nsim(nsim, _checked_patterns(patterns))
    if isinstance(nrank, bool) or not isinstance(nrank, (int, np.integer)) or nrank < 1:
        raise ValueError(f"nrank must be a positive integer, got {nrank!r}")
    if 2 * nrank > nsim:
        raise ValueError(f"nrank={nrank} needs at least {2 * nrank} simulations, got nsim={nsim}")
    observed_values, column, simulated = _simulated_curves(
        observed, fun, model=model, patterns=patterns, nsim=nsim, r=r, column=column, fun_kwargs=fun_kwargs,
        simulate_kwargs=simulate_kwargs, rng=rng, client=client, workers=workers, progress=progress)
    r = observed_values["r"].to_numpy()
    theo = observed_values["theo"].to_numpy()
    lo, hi = _bounds(simulated, theo, nrank, kind)
    result = pd.DataFrame(
        {"r": r, "obs": observed_values[column].to_numpy(), "theo": theo, "lo": lo, "hi": hi,
         "mean": simulated.mean(axis=0)}
    )
    alpha = 2 * nrank / (nsim + 1) if kind == "pointwise" else nrank / (nsim + 1)
    null = "csr" if model is None and patterns is None else "model" if patterns is None else "patterns"
    result.attrs.update(nsim=nsim, nrank=nrank, kind=kind, column=column, alpha=alpha, null=null)
    if savefuns:
        result.attrs["simulated"] = simulated.tolist()
    return result


def _bounds(simulated: np.ndarray, theo: np.ndarray, nrank: int, kind: str):
    if kind == "pointwise":
        ordered = np.sort(simulated, axis=0)
        return ordered[nrank - 1], ordered[-nrank]
    # global: maximum absolute deviation from the theoretical curve over r (NaNs ignored)
    deviation = np.nanmax(np.abs(simulated - theo), axis=1)
    bound = np.sort(deviation)[-nrank]
    return theo - bound, theo + bound
