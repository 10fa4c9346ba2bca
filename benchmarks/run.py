"""Run the registered benchmarks, print a table and write ``benchmarks/results.json``.

Usage::

    python benchmarks/run.py [--only PATTERN] [--repeat N] [--quick] [--output PATH]

Each case is called once untimed (to warm numba caches and imports), then ``--repeat``
times; the table shows the median wall seconds, the baseline's median at the same size
(run in this same process) and their ratio (below 1: faster than the baseline). One more
untimed call runs under :mod:`tracemalloc` and gives the case's peak memory: the largest
amount of Python and NumPy memory (NumPy reports its buffers to tracemalloc) held at once
during the call, above what was held before it. Memory that numba kernels allocate
internally is not seen; ours allocate nothing inside their loops.
"""

from __future__ import annotations

import argparse
import fnmatch
import importlib
import json
import platform
import statistics
import sys
import time
import tracemalloc
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from registry import BENCHMARKS  # noqa: E402


def load_benchmark_modules() -> None:
    for path in sorted(HERE.glob("bench_*.py")):
        importlib.import_module(path.stem)


def median_seconds(run, repeat: int) -> float:
    run()  # warm-up: imports, numba compilation, file caches
    times = []
    for _ in range(repeat):
        began = time.perf_counter()
        run()
        times.append(time.perf_counter() - began)
    return statistics.median(times)


def peak_mebibytes(run) -> float:
    """Peak traced memory (MiB) of one call of ``run`` above what was allocated before it."""
    tracemalloc.start()
    try:
        before, _ = tracemalloc.get_traced_memory()
        tracemalloc.reset_peak()
        run()
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return (peak - before) / 2**20


def measure(selected, repeat: int, quick: bool) -> list[dict]:
    rows = []
    for bench in selected:
        for size in bench.sizes[:1] if quick else bench.sizes:
            run = bench.case(size)
            seconds = median_seconds(run, repeat)
            peak = peak_mebibytes(run)
            baseline = median_seconds(bench.baseline(size), repeat) if bench.baseline else None
            rows.append(
                {
                    "name": bench.name,
                    "size": size,
                    "seconds": seconds,
                    "peak_mib": peak,
                    "baseline": bench.baseline_name or None,
                    "baseline_seconds": baseline,
                    "ratio": seconds / baseline if baseline else None,
                    "reference": bench.reference.get(size, {}),
                }
            )
    return rows


def format_table(rows) -> str:
    header = f"{'name':<36} {'size':>8} {'seconds':>10} {'peak MiB':>9} {'baseline':<28} {'base s':>10} {'ratio':>7}"
    lines = [header, "-" * len(header)]
    for row in rows:
        base = f"{row['baseline_seconds']:.4g}" if row["baseline_seconds"] is not None else "-"
        ratio = f"{row['ratio']:.3g}" if row["ratio"] is not None else "-"
        lines.append(
            f"{row['name']:<36} {row['size']:>8} {row['seconds']:>10.4g} {row['peak_mib']:>9.1f} "
            f"{row['baseline'] or '-':<28} {base:>10} {ratio:>7}"
        )
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", metavar="PATTERN", help="glob or substring of benchmark names")
    parser.add_argument("--repeat", type=int, default=5, help="timed repetitions per case (default 5)")
    parser.add_argument("--quick", action="store_true", help="smallest size only, one repetition")
    parser.add_argument("--output", type=Path, default=HERE / "results.json")
    args = parser.parse_args(argv)
    if args.repeat < 1:
        parser.error("--repeat must be at least 1")
    load_benchmark_modules()
    selected = BENCHMARKS
    if args.only:
        glob = args.only if any(c in args.only for c in "*?[") else f"*{args.only}*"
        selected = [b for b in BENCHMARKS if fnmatch.fnmatchcase(b.name, glob)]
        if not selected:
            print(f"error: no benchmark matches {args.only!r} (available: {', '.join(b.name for b in BENCHMARKS)})",
                  file=sys.stderr)
            return 2
    rows = measure(selected, 1 if args.quick else args.repeat, args.quick)
    print(format_table(rows))
    result = {
        "machine": {"python": platform.python_version(), "platform": platform.platform(), "processor": platform.machine()},
        "repeat": 1 if args.quick else args.repeat,
        "results": rows,
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    temporary = args.output.with_name(f".{args.output.name}.tmp")
    temporary.write_text(json.dumps(result, indent=1) + "\n")
    temporary.replace(args.output)
    print(f"\nwrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
