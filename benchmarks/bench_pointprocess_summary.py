"""Lest (isotropic and border corrections) on uniform points in the unit square, spatstat's default r grid.

Baseline, run in the same process: naive pair enumeration with scipy's cKDTree (in chunks,
so that 1e5 points fit in memory) and ``np.histogram`` of the distances, no edge weights --
the floor for a straightforward Python implementation. spatstat's ``Lest`` timings on this
machine, measured by ``tests/oracle/spatstat_summary.R``, are copied from
``tests/oracle/summary.json`` as the reference.
"""

import json
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from paperlib.pointprocess import PointPattern, Window
from paperlib.pointprocess.summary import Lest, default_r
from registry import benchmark

SIZES = [1_000, 10_000, 100_000]
_ORACLE = Path(__file__).resolve().parent.parent / "tests" / "oracle" / "summary.json"
_SPATSTAT_SECONDS = json.loads(_ORACLE.read_text())["timings"]


def spatstat_reference(correction: str) -> dict:
    return {n: {"spatstat Lest, median of R runs (tests/oracle/summary.json)": _SPATSTAT_SECONDS[str(n)][correction]}
            for n in SIZES}


def uniform_pattern(n: int) -> PointPattern:
    return PointPattern(np.random.default_rng(n).random((n, 2)), Window.rectangle())


def naive_pair_histogram(n: int):
    pattern = uniform_pattern(n)
    r = default_r(pattern.window, pattern.intensity)
    chunk = 5_000

    def run():
        tree = cKDTree(pattern.points)
        counts = np.zeros(len(r) - 1)
        for start in range(0, n, chunk):
            pairs = cKDTree(pattern.points[start:start + chunk]).sparse_distance_matrix(tree, r[-1], output_type="ndarray")
            counts += np.histogram(pairs["v"][pairs["v"] > 0], bins=r)[0]
        k = np.concatenate([[0.0], np.cumsum(counts)]) / (n * (n - 1))
        return np.sqrt(k / np.pi)

    return run


def lest_case(correction: str):
    def make(n: int):
        pattern = uniform_pattern(n)
        return lambda: Lest(pattern, correction=correction)

    return make


benchmark("Lest isotropic, uniform points", sizes=SIZES, baseline=naive_pair_histogram,
          baseline_name="cKDTree pairs + np.histogram", reference=spatstat_reference("isotropic"))(lest_case("isotropic"))
benchmark("Lest border, uniform points", sizes=SIZES, baseline=naive_pair_histogram,
          baseline_name="cKDTree pairs + np.histogram", reference=spatstat_reference("border"))(lest_case("border"))
