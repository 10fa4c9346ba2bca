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
Timings on a shared 2-core machine vary by up to 40% between runs.
"""

import dataclasses
import json
from pathlib import Path

import numpy as np

from paperlib.pointprocess import MultiStraussHard, StraussHard, Window
from paperlib.pointprocess import _kernels, simulate
from paperlib.pointprocess.simulate import rmh
from registry import benchmark

_ORACLE = json.loads((Path(__file__).resolve().parent.parent / "tests" / "oracle" / "rmh.json").read_text())
_TIMING = _ORACLE["timing"]
UNIT = Window.rectangle()
SPATSTAT_MOVES = dict(p=0.9, q=0.9)  # rmhcontrol()'s defaults in spatstat 3.0-3
STRAUSS_SIZES = [50, 630, 10_000]
MULTITYPE_SIZE = 300


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


def equilibrium(model, n_points: int):
    return rmh(model, UNIT, max(200_000, 60 * n_points), rng=0)


def spatstat_seconds(timing: dict, n_points: int) -> dict:
    source = f"spatstat rmh {timing['steps_per_second']:.3g} steps/s at {timing['points']} points (tests/oracle/rmh.json)"
    return {n_points: {source: steps_for(n_points) / timing["steps_per_second"]}}


def grid_kernel(n_points: int):
    model = model_for(n_points)
    start = equilibrium(model, n_points)
    return lambda: rmh(model, UNIT, steps_for(n_points), start=start, rng=1, **SPATSTAT_MOVES)


def one_cell_kernel(n_points: int):
    """The same chain with every point in one cell: an O(n) scan per conditional intensity."""
    model = model_for(n_points)
    start = equilibrium(model, n_points)
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

benchmark("rmh StraussHard, spatstat moves", sizes=STRAUSS_SIZES, baseline=one_cell_kernel,
          baseline_name="same kernel, O(n) scan", reference=strauss_reference)(grid_kernel)
benchmark("rmh MultiStraussHard 3 types", sizes=[MULTITYPE_SIZE], baseline=one_cell_kernel,
          baseline_name="same kernel, O(n) scan",
          reference=spatstat_seconds(_TIMING["MultiStraussHard3"], MULTITYPE_SIZE))(grid_kernel)
