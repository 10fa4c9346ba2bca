"""The many-runs helper: its cost over a plain loop, in-process and in two processes."""

import numpy as np

from paperlib.parallel import run_many
from registry import benchmark


def simulate(task, rng):
    """A stand-in for one simulation: 2e5 normal draws reduced to a number."""
    return float(rng.standard_normal(200_000).sum())


def plain_loop(n_runs):
    def run():
        rng = np.random.default_rng(0)
        return [simulate(i, rng) for i in range(n_runs)]

    return run


@benchmark("run_many, in-process (workers=1)", sizes=[20, 200], baseline=plain_loop, baseline_name="plain loop")
def run_many_serial(n_runs):
    return lambda: run_many(simulate, range(n_runs), rng=0, workers=1)


@benchmark("run_many, 2 processes", sizes=[20, 200], baseline=plain_loop, baseline_name="plain loop")
def run_many_processes(n_runs):
    return lambda: run_many(simulate, range(n_runs), rng=0, workers=2)
