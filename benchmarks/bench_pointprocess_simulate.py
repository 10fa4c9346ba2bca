"""rmh: Metropolis-Hastings steps of Strauss hard-core models, against spatstat's rmh.

Models (tests/oracle/rmh.json, made by tests/oracle/spatstat_rmh.R): one StraussHard family
scaled to the point count (beta = 2 n, gamma = 0.3, r = 0.08 sqrt(50 / n), hc = r / 4 in
the unit square: about 50, 630 and 1e4 points at equilibrium) and a three-type
MultiStraussHard with about 300 points. Each case runs a fixed number of steps from an
equilibrium pattern (made untimed) with spatstat's default moves (rmhcontrol's p = 0.9 shifts,
q = 0.9 births among the other proposals), as spatstat's timings were measured; steps/s = steps / seconds.

Baseline, same process: the same numba kernel on a grid of a single cell, i.e. spatstat's
O(n) scan of all points per conditional intensity. Reference: spatstat's rmh rate on this
machine, from the fixture, converted to seconds for the same number of steps.
Targets (issue 3): at least 2x spatstat's steps/s at the same model and point count, and
at least 1e6 steps/s for StraussHard at 1e4 points (spatstat: ~7e4, its step being O(n)).

Scaling (issue 26): the same family at n = 1e3, 1e4 and 1e5, each run for 10**6 steps so
that the O(n) work of a call (validating the start, building the grid, the output pattern:
about 0.1 s at 1e5 points) is a small part of the time and seconds / 10**6 is the cost of
a step. Targets: cost per step at 1e5 points at most 1.5x that at 1e3, and at least 5e6
steps/s at 1e4. No baseline there: the O(n) scan would take minutes at 1e5 points.

Every label names what was run: the model family and its parameters, the window,
spatstat's move probabilities (p, q), ``expand = 1`` (the window is never expanded),
``periodic`` and the number of steps; the size column is the family's nominal point
count n (equilibrium holds about 0.93 n points; the three-type model about 300).
Timings on a shared 2-core machine vary by up to 40% between runs.
"""

import dataclasses
import json
from pathlib import Path

import numpy as np

import functools

from paperlib.pointprocess import MultiStraussHard, StraussHard, Window
from paperlib.pointprocess import _kernels, simulate
from paperlib.pointprocess.simulate import rmh
from registry import benchmark

_ORACLE = json.loads((Path(__file__).resolve().parent.parent / "tests" / "oracle" / "rmh.json").read_text())
_TIMING = _ORACLE["timing"]
UNIT = Window.rectangle()
SPATSTAT_MOVES = dict(p=0.9, q=0.9)  # rmhcontrol()'s defaults in spatstat 3.0-3
STRAUSS_SIZES = [50, 630, 10_000]
SCALING_SIZES = [1_000, 10_000, 100_000]
SCALING_STEPS = 1_000_000
MULTITYPE_SIZE = 300
FAMILY = "StraussHard(beta=2n, gamma=0.3, r=0.08 sqrt(50/n), hc=r/4, open ties) in the unit square"
RUN = "from equilibrium, p=0.9 q=0.9 (spatstat's defaults), expand=1, periodic=False"


def steps_for(n_points: int) -> int:
    """Steps per timed run: ~40 ms with the grid; fewer at 1e4 points, where the O(n) baseline crawls."""
    return 200_000 if n_points < 5_000 else 50_000


def strauss_family(n: int):
    r = 0.08 * np.sqrt(50 / n)  # the R script's strauss_family()
    return StraussHard(2 * n, 0.3, r, r / 4, closed=False)


def three_types():
    par = _TIMING["MultiStraussHard3"]["model"]
    return MultiStraussHard(par["beta"], gamma=par["gamma"], r=par["r"], hc=par["hc"])


def model_for(n_points: int):
    return three_types() if n_points == MULTITYPE_SIZE else strauss_family(n_points)


@functools.lru_cache(maxsize=None)
def equilibrium(n_points: int):
    """A pattern of the model at ``n_points`` after enough steps to forget the empty start (cached)."""
    return rmh(model_for(n_points), UNIT, max(200_000, 60 * n_points), rng=0)


def spatstat_seconds(timing: dict, n_points: int) -> dict:
    source = f"spatstat rmh {timing['steps_per_second']:.3g} steps/s at {timing['points']} points (tests/oracle/rmh.json)"
    return {n_points: {source: steps_for(n_points) / timing["steps_per_second"]}}


def grid_kernel(n_points: int):
    model = model_for(n_points)
    start = equilibrium(n_points)
    return lambda: rmh(model, UNIT, steps_for(n_points), start=start, rng=1, **SPATSTAT_MOVES)


def long_run(n_points: int):
    """``SCALING_STEPS`` steps from equilibrium: seconds / steps is the cost of one step."""
    model = strauss_family(n_points)
    start = equilibrium(n_points)
    return lambda: rmh(model, UNIT, SCALING_STEPS, start=start, rng=1, **SPATSTAT_MOVES)


def one_cell_kernel(n_points: int):
    """The same chain with every point in one cell: an O(n) scan per conditional intensity."""
    model = model_for(n_points)
    start = equilibrium(n_points)
    setup = simulate._prepare(model, UNIT, 1, ptypes=None, fixall=False, periodic=False, intensity_map=None,
                              **SPATSTAT_MOVES)
    one_cell = setup.grid._replace(ncx=1, ncy=1, x_scale=1.0 / setup.grid.width, y_scale=1.0 / setup.grid.height)
    setup = dataclasses.replace(setup, grid=one_cell)

    def run():
        chain = simulate._Chain(setup, start.points, start.marks.astype(np.int64))
        chain.run(steps_for(n_points), np.random.default_rng(1), _kernels.mh_steps)
        return chain.pattern()

    return run


strauss_reference = {}
for size, timing in _TIMING["StraussHard"].items():
    strauss_reference.update(spatstat_seconds(timing, int(size)))

benchmark(f"rmh {FAMILY}, {RUN}, 2e5 steps (5e4 at n=1e4)", sizes=STRAUSS_SIZES, baseline=one_cell_kernel,
          baseline_name="same kernel, O(n) scan", reference=strauss_reference)(grid_kernel)
benchmark(f"rmh {FAMILY}, {RUN}, 1e6 steps (per-step scaling)", sizes=SCALING_SIZES)(long_run)
benchmark("rmh MultiStraussHard 3 types (tests/oracle/rmh.json: beta 240,160,320, r 0.032-0.049, "
          f"hc 0.007-0.018) in the unit square, {RUN}, 2e5 steps", sizes=[MULTITYPE_SIZE],
          baseline=one_cell_kernel, baseline_name="same kernel, O(n) scan",
          reference=spatstat_seconds(_TIMING["MultiStraussHard3"], MULTITYPE_SIZE))(grid_kernel)
