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

import numpy as np
import pandas as pd

from paperlib.parallel import run_many

from .models import MultiStraussHard
from .pattern import PointPattern
from .processes import rpoispp

__all__ = ["envelope"]

_KINDS = ("pointwise", "global")


def _simulate(task, rng):
    """One simulation of the null model, summarised: ``fun(pattern, r=r, **fun_kwargs)[column]``."""
    fun, fun_kwargs, column, r, model, window, categories, intensity, simulate_kwargs = task
    if model is None:
        pattern = rpoispp(intensity, window, categories=categories, rng=rng)
    else:
        from .simulate import rmh

        pattern = rmh(model, window, rng=rng, **simulate_kwargs)
    return fun(pattern, r=r, **fun_kwargs)[column].to_numpy()


def envelope(
    observed: PointPattern,
    fun,
    *,
    model: MultiStraussHard | None = None,
    nsim: int = 99,
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
    nsim : int
        Number of simulations.
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

    Returns
    -------
    pandas.DataFrame
        Columns ``r``, ``obs``, ``theo``, ``lo``, ``hi``, ``mean`` (mean of the
        simulations); ``attrs`` hold ``nsim``, ``nrank``, ``kind``, ``column`` and the
        significance level ``alpha``.
    """
    if not isinstance(observed, PointPattern):
        raise ValueError(f"observed must be a PointPattern, got {type(observed).__name__}")
    if kind not in _KINDS:
        raise ValueError(f"kind must be one of {_KINDS}, got {kind!r}")
    for name, value in (("nsim", nsim), ("nrank", nrank)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
            raise ValueError(f"{name} must be a positive integer, got {value!r}")
    if 2 * nrank > nsim:
        raise ValueError(f"nrank={nrank} needs at least {2 * nrank} simulations, got nsim={nsim}")
    if model is not None and model.n_types != observed.n_types:
        raise ValueError(f"the model has {model.n_types} types, the observed pattern {observed.n_types}")
    fun_kwargs = dict(fun_kwargs or {})
    observed_values = fun(observed, r=r, **fun_kwargs)
    column = column or [c for c in observed_values.columns if c not in ("r", "theo")][0]
    if column not in observed_values.columns:
        raise ValueError(f"fun gives no column {column!r}; it gives {list(observed_values.columns)}")
    r = observed_values["r"].to_numpy()
    intensity = observed.counts / observed.window.area
    task = (fun, fun_kwargs, column, r, model, observed.window, observed.categories, intensity,
            dict(simulate_kwargs or {}))
    simulated = np.vstack(
        run_many(_simulate, [task] * nsim, rng=rng, client=client, workers=workers, progress=progress,
                 desc="envelope")
    )
    theo = observed_values["theo"].to_numpy()
    lo, hi = _bounds(simulated, theo, nrank, kind)
    result = pd.DataFrame(
        {"r": r, "obs": observed_values[column].to_numpy(), "theo": theo, "lo": lo, "hi": hi,
         "mean": simulated.mean(axis=0)}
    )
    alpha = 2 * nrank / (nsim + 1) if kind == "pointwise" else nrank / (nsim + 1)
    result.attrs.update(nsim=nsim, nrank=nrank, kind=kind, column=column, alpha=alpha)
    return result


def _bounds(simulated: np.ndarray, theo: np.ndarray, nrank: int, kind: str):
    if kind == "pointwise":
        ordered = np.sort(simulated, axis=0)
        return ordered[nrank - 1], ordered[-nrank]
    # global: maximum absolute deviation from the theoretical curve over r (NaNs ignored)
    deviation = np.nanmax(np.abs(simulated - theo), axis=1)
    bound = np.sort(deviation)[-nrank]
    return theo - bound, theo + bound
