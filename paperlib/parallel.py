"""Many runs, one door: independent repetitions in local processes or on Dask.

Simulation envelopes, galleries, parameter sweeps and notebook batches all go through
:func:`run_many`. It runs in local processes by default and on a Dask distributed
cluster when a ``client`` is passed, so work that outgrows one machine needs no new
code. Every run gets its own random stream spawned from the parent ``rng``
(``numpy.random.SeedSequence.spawn``): run ``i`` sees the same numbers whether the runs
go one by one, in four processes or on forty Dask workers.

Written by hand because neither ``concurrent.futures`` nor Dask spawns seeds or keeps
results in task order across both back ends.
"""

from __future__ import annotations

import os
import pickle
import sys
from concurrent.futures import ProcessPoolExecutor, as_completed

import numpy as np

from paperlib._checks import check_rng, integer_in_range

#: The most seed sequences :func:`spawn_seeds` makes in one call (each run of :func:`run_many` takes one).
MAX_SEEDS = 10_000_000

__all__ = ["run_many", "spawn_seeds"]


def spawn_seeds(rng, n: int) -> list[np.random.SeedSequence]:
    """Spawn ``n`` independent seed sequences from ``rng``.

    Parameters
    ----------
    rng : None, int, SeedSequence or numpy.random.Generator
        The parent. An int or SeedSequence gives the same children every time; a
        Generator gives children that depend on how many it has already spawned.
    n : int
        Number of children.

    Returns
    -------
    list of numpy.random.SeedSequence
        ``n`` independent child seed sequences, one per run.
    """
    n = integer_in_range(n, "n", 0, MAX_SEEDS)
    rng = check_rng(rng)
    if isinstance(rng, np.random.Generator):
        return rng.bit_generator.seed_seq.spawn(n)
    if isinstance(rng, np.random.SeedSequence):
        return rng.spawn(n)
    return np.random.SeedSequence(rng).spawn(n)


def _call_seeded(fn, task, seed_sequence):
    return fn(task, rng=np.random.default_rng(seed_sequence))


def _call(fn, task, _seed_sequence):
    return fn(task)


def progress_enabled(progress) -> bool:
    """Whether a progress bar shows: ``progress`` if a bool, else (None) whether stderr is a terminal.

    Parameters
    ----------
    progress : bool or None
        True or False to force the bar on or off; None (the usual default) shows it only when
        standard error is a terminal, so logs, CI runs and papermill kernels get no bar.

    Returns
    -------
    bool
    """
    if progress is None:
        stream = sys.stderr
        try:
            return bool(stream is not None and stream.isatty())
        except (AttributeError, ValueError):  # a replaced or closed stream
            return False
    if not isinstance(progress, (bool, np.bool_)):
        raise TypeError(f"progress must be True, False or None (on when stderr is a terminal), got {progress!r}")
    return bool(progress)


def progress_bar(iterable=None, *, progress=None, total=None, desc=None, unit="it"):
    """A tqdm bar over ``iterable`` (or to update by hand), shown when :func:`progress_enabled` says so.

    A bar only reports: it never changes what the loop computes.

    Parameters
    ----------
    iterable : iterable, optional
        What to iterate over; None for a bar updated with ``bar.update(n)``.
    progress : bool or None
        See :func:`progress_enabled`.
    total : int, optional
        Number of steps (default ``len(iterable)`` when it has one).
    desc : str, optional
        Label of the bar.
    unit : str
        Name of one step.

    Returns
    -------
    tqdm.tqdm
        Disabled (a plain pass-through) when the bar is off.
    """
    from tqdm.auto import tqdm

    return tqdm(iterable, total=total, desc=desc, unit=unit, disable=not progress_enabled(progress),
                mininterval=0.5)


_FN_FIX = ("define the function at the top level of a module or notebook (def my_run(task, rng): ...), not as a "
           "lambda or a function nested in another, and bind fixed arguments with functools.partial of it")
_TASK_FIX = "make the tasks plain data (numbers, strings, arrays, tuples, dataclasses), not open files, locks or generators"


def _check_picklable(value, what: str, fix: str, workers: int) -> None:
    """A TypeError naming the fix when ``value`` cannot go to worker processes (instead of a bare PicklingError)."""
    try:
        pickle.dumps(value)
    except Exception as exc:  # PicklingError, AttributeError ("local object"), TypeError (locks, generators)
        raise TypeError(
            f"{what} cannot be sent to {workers} worker processes because it cannot be pickled "
            f"({type(exc).__name__}: {exc}): {fix}; or pass workers=1 to run in this process"
        ) from exc


def run_many(fn, tasks, *, rng=None, seeded=True, client=None, workers=None, progress=False, desc=None):
    """Run ``fn`` on every task, independently, and return the results in task order.

    Parameters
    ----------
    fn : callable
        ``fn(task, rng=generator)`` when ``seeded``, else ``fn(task)``. Must be
        picklable (a module-level function) to run in processes or on Dask.
    tasks : iterable
        One item per run (parameters, file names, or just ``range(n)``).
    rng : None, int, SeedSequence or Generator
        Parent of the per-run seeds (see :func:`spawn_seeds`). Ignored when not seeded.
    seeded : bool
        Pass each run its own ``numpy.random.Generator`` as ``rng``.
    client : dask.distributed.Client, optional
        Run on this Dask cluster instead of local processes.
    workers : int, optional
        Local processes (default: the number of CPUs). ``1`` runs in this process,
        which is what tests and debuggers want.
    progress : bool or None
        Show a tqdm progress bar; None: only when stderr is a terminal (:func:`progress_enabled`).
    desc : str, optional
        Label of the progress bar.

    Returns
    -------
    list
        ``[fn(task_0, ...), fn(task_1, ...), ...]``. The first exception raised by a
        run propagates (after the other local runs are cancelled).

    Raises
    ------
    TypeError
        When ``fn`` (or a task) must go to worker processes but cannot be pickled (a lambda,
        a nested function): the message names the fix, a module-level function.
    """
    tasks = list(tasks)
    if not callable(fn):
        raise ValueError(f"fn must be callable, got {fn!r}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ValueError(f"workers must be a positive int, got {workers!r}")
    progress_enabled(progress)  # a wrong value fails before any work
    seeds = spawn_seeds(rng, len(tasks)) if seeded else [None] * len(tasks)
    call = _call_seeded if seeded else _call
    if client is not None:
        return _run_on_dask(client, call, fn, tasks, seeds, progress, desc)
    workers = min(workers or os.cpu_count() or 1, max(len(tasks), 1))
    if workers == 1:
        return [call(fn, task, seed) for task, seed in _progress(zip(tasks, seeds), progress, len(tasks), desc)]
    _check_picklable(fn, f"fn={getattr(fn, '__qualname__', type(fn).__name__)!r}", _FN_FIX, workers)
    _check_picklable(tasks[0], f"the first task (a {type(tasks[0]).__name__})", _TASK_FIX, workers)
    return _run_in_processes(call, fn, tasks, seeds, workers, progress, desc)


def _progress(iterable, enabled, total: int, desc):
    return progress_bar(iterable, progress=enabled, total=total, desc=desc)


def _run_in_processes(call, fn, tasks, seeds, workers, progress, desc):
    results = [None] * len(tasks)
    with ProcessPoolExecutor(max_workers=workers) as pool:
        futures = {pool.submit(call, fn, task, seed): index for index, (task, seed) in enumerate(zip(tasks, seeds))}
        try:
            for future in _progress(as_completed(futures), progress, len(futures), desc):
                results[futures[future]] = future.result()
        except BaseException:
            for future in futures:
                future.cancel()
            raise
    return results


def _run_on_dask(client, call, fn, tasks, seeds, progress, desc):
    from distributed import as_completed as dask_as_completed

    futures = client.map(call, [fn] * len(tasks), tasks, seeds, pure=False)
    order = {future.key: index for index, future in enumerate(futures)}
    results = [None] * len(tasks)
    for future in _progress(dask_as_completed(futures), progress, len(futures), desc):
        results[order[future.key]] = future.result()
    return results
