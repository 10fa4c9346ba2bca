"""Registry of benchmarks: each times a case against a baseline run in the same process.

A benchmark module (``benchmarks/bench_*.py``) registers cases with :func:`benchmark`.
The decorated function receives a problem size and returns a zero-argument callable to
time; set-up done before returning is not timed. An optional baseline (same signature)
is timed at the same size in the same run, so the ratio is meaningful on any machine.
External timings that cannot run here (a paper's figure, R's spatstat on this kind of
machine) go in ``reference`` and are copied to the JSON as they are, never as a baseline.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

__all__ = ["Benchmark", "BENCHMARKS", "benchmark"]


@dataclass(frozen=True)
class Benchmark:
    name: str
    sizes: tuple
    case: Callable
    baseline: Callable | None = None
    baseline_name: str = ""
    reference: dict = field(default_factory=dict)  # {size: {"source": seconds}}


BENCHMARKS: list[Benchmark] = []


def benchmark(name: str, sizes, *, baseline=None, baseline_name: str = "", reference=None):
    """Register the decorated case under ``name`` for each of ``sizes``."""
    if baseline is not None and not baseline_name:
        raise ValueError(f"benchmark {name!r}: name the baseline so the table says what the ratio is against")

    def register(case):
        BENCHMARKS.append(Benchmark(name, tuple(sizes), case, baseline, baseline_name, dict(reference or {})))
        return case

    return register
