"""Pseudolikelihood fit of a Strauss hard-core model, against spatstat's ppm.

The case is spatstat's ``ppm(X ~ 1, StraussHard(r))`` on uniform points in the unit square:
hard core estimated as spatstat does (minimum distance * n/(n+1)), spatstat's default
quadrature, border correction, r = 0.05 sqrt(1000 / n) (about 7.9 neighbours per point). The
spatstat timings were measured by tests/oracle/spatstat_ppm.R on the same case and are read
from its fixture. The baseline, timed in the same run, is the Berman-Turner design alone
(quadrature scheme and interaction statistics): the ratio shows what the Newton solve, the
border correction and both variance estimates add.
"""

import json
from pathlib import Path

import numpy as np

from paperlib.pointprocess import PointPattern, Window, interaction_counts
from paperlib.pointprocess.fit import hardcore_distances, ppm
from paperlib.pointprocess.models import StraussHard
from paperlib.pointprocess.quadrature import quadscheme
from registry import benchmark

SIZES = [1_000, 10_000]
_ORACLE = json.loads((Path(__file__).resolve().parents[1] / "tests" / "oracle" / "ppm.json").read_text())
SPATSTAT = {int(n): {"spatstat ppm (R, default nd)": t["seconds"]} for n, t in _ORACLE["timings"].items()}


def uniform_pattern(n: int) -> PointPattern:
    return PointPattern(np.random.default_rng(1).random((n, 2)), Window.rectangle())


def radius(n: int) -> float:
    return 0.05 * np.sqrt(1000 / n)


def design_only(n):
    pattern, r = uniform_pattern(n), radius(n)

    def run():
        hc = hardcore_distances(pattern, "spatstat")
        scheme = quadscheme(pattern)
        model = StraussHard(1.0, 1.0, r, hc[0, 0])
        exclude = np.where(scheme.is_data, np.arange(scheme.n_points), -1)
        return interaction_counts(model, scheme.points, scheme.types, pattern.points, pattern.marks, exclude)

    return run


@benchmark("ppm fit StraussHard, spatstat quad", sizes=SIZES, baseline=design_only,
           baseline_name="quadrature + statistics only", reference=SPATSTAT)
def fit_strauss_hard(n):
    pattern, r = uniform_pattern(n), radius(n)
    return lambda: ppm(pattern, r, hardcore_distances(pattern, "spatstat"), closed=True, quadrature="spatstat")
