"""Barla 2006 stroke patterns: synthesis along a path and in a region (analysis done once, not timed).

"strokepattern: 1D path, 5-ring": the length-ramp hatching of Fig. 6d (``gradient_hatching_exemplar``,
30 elements, seed 0) analysed once, then synthesised with 5-ring neighbourhoods along a straight path long
enough for n elements (N_tar = N_ref A_tar / A_ref), seeds included. Target (issue 7): <= 0.2 s for 200
elements; paper: "of the order of a second" for 1D patterns. Baseline, same run: the same synthesis with the
matching loop in plain Python (``_kernels.grow_reference``, the transcription the tests check the numba
kernel against), so the ratio is what the kernel buys.

"strokepattern: 2D region, 3-ring": the bars of Fig. 7a (``bars_exemplar``, seed 0) analysed once, then
synthesised with 3-ring neighbourhoods in a square region sized for n elements, seeds (Lloyd, 40 steps)
included. Target (issue 7): <= 1 s for 500 elements; paper: 5-10 s for 2D patterns. Baseline, same run:
the Lloyd seeds alone (``seeds_2d``), so the ratio shows how the time splits between seeding and matching.
"""

import math
from functools import cache
from unittest import mock

import numpy as np

from paperlib.datasets.strokepatterns import bars_exemplar, gradient_hatching_exemplar
from paperlib.strokepattern import analyze, seeds_2d, synthesize, target_count
from paperlib.strokepattern import synthesis as synthesis_module
from paperlib.strokepattern._kernels import grow_reference
from registry import benchmark


@cache
def reference_1d():
    exemplar = gradient_hatching_exemplar("length", rng=0)
    return analyze(exemplar.strokes, exemplar.epsilon, dimension=1, path=exemplar.path)


@cache
def reference_2d():
    exemplar = bars_exemplar(rng=0)
    return analyze(exemplar.strokes, exemplar.epsilon, dimension=2, region=exemplar.region)


def path_for(n):
    analysis = reference_1d()
    return np.array([(0.0, 0.0), (analysis.area * n / len(analysis), 0.0)])


def region_for(n):
    analysis = reference_2d()
    side = math.sqrt(analysis.area * n / len(analysis))
    return (0.0, side, 0.0, side)


def python_matching_1d(n):
    analysis, path = reference_1d(), path_for(n)

    def run():
        with mock.patch.object(synthesis_module, "grow", grow_reference):
            synthesize(analysis, path, rings=5, rng=0)
    return run


@benchmark("strokepattern: 1D path, 5-ring (n elements)", sizes=[200], baseline=python_matching_1d,
           baseline_name="same synthesis, matching loop in plain Python",
           reference={200: {"Barla 2006 (paper, 1D patterns)": 1.0}})
def path_1d(n):
    analysis, path = reference_1d(), path_for(n)
    assert target_count(analysis, path) == n
    synthesize(analysis, path, rings=5, rng=0)  # warm the numba kernel
    return lambda: synthesize(analysis, path, rings=5, rng=0)


def seeds_only(n):
    region = region_for(n)
    return lambda: seeds_2d(region, n, rng=0)


@benchmark("strokepattern: 2D region, 3-ring (n elements)", sizes=[500], baseline=seeds_only,
           baseline_name="Lloyd seeds alone (40 steps)",
           reference={500: {"Barla 2006 (paper, 2D patterns, low end)": 5.0}})
def region_2d(n):
    analysis, region = reference_2d(), region_for(n)
    assert abs(target_count(analysis, region) - n) <= 1
    synthesize(analysis, (0, 4, 0, 4), rings=3, rng=0)  # warm the numba kernel
    return lambda: synthesize(analysis, region, rings=3, rng=0)
