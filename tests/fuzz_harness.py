"""Fuzz harness: every public callable of paperlib on Hypothesis inputs, in a bounded worker (issue 21).

Each case runs in a worker subprocess with an address-space limit (``RLIMIT_AS``) and a wall-clock limit
enforced from outside (a case that does not answer in time is a *hang*: the worker is killed and
restarted), in a scratch folder as its current directory (so writers write there). Outcomes:

``ok``            the call returned (``ok-nan`` when its array or float result holds NaN)
``rejected``      ValueError or TypeError raised in paperlib's own code: the contract of issue 21
``rejected-deep`` ValueError or TypeError raised inside a library paperlib calls (numpy, scipy...):
                  still the right type, but the message is the library's, not paperlib's
``not-found``     FileNotFoundError for a path that names no file (documented by the readers)
``usage``         an exception the callable documents for a call out of order (``EXPECTED_EXCEPTIONS``)
``exception``     any other exception type (IndexError, ZeroDivisionError, MemoryError, ...): a bug
``hang``          no answer within the time limit: a bug
``crash``         the worker died (segfault, killed past its memory limit): a bug

Bad outcomes are ``exception``, ``hang`` and ``crash``. Run the full campaign with ``make fuzz``::

    python tests/fuzz_harness.py --examples 40 --jobs 2 --out build/fuzz

which prints the summary table and writes ``summary.md`` and ``outcomes.json`` to ``--out``.
``tests/test_fuzz.py`` runs the bounded CI profile through :func:`run_campaign`.
"""

from __future__ import annotations

import argparse
import collections
import json
import math
import re
import os
import pickle
import struct
import subprocess
import sys
import tempfile
import time
import traceback
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

BAD = ("exception", "hang", "crash")
#: Defaults of the full campaign: 6 GiB and 20 s per case (the limits the issue's campaign used).
FULL_MEMORY, FULL_SECONDS = 6 * 2**30, 20.0


# ------------------------------------------------------------------------------------------- framing


def _send(stream, payload) -> None:
    data = pickle.dumps(payload)
    stream.write(struct.pack("<Q", len(data)) + data)
    stream.flush()


def _receive(stream):
    header = stream.read(8)
    if len(header) < 8:
        raise EOFError
    (size,) = struct.unpack("<Q", header)
    return pickle.loads(stream.read(size))


# ------------------------------------------------------------------------------------------- worker side


def _factory(value):
    """Build the objects the registry draws as :class:`fuzz_registry.Factory`, recursively."""
    import numpy as np
    from fuzz_registry import Factory

    if isinstance(value, Factory):
        rng = np.random.default_rng(value.seed)
        if value.name == "window":
            from paperlib.pointprocess import Window

            return Window.rectangle((0.0, 1.0 + value.seed), (0.0, 1.0))
        if value.name == "pattern":
            from paperlib.pointprocess import PointPattern, Window

            return PointPattern(rng.random((5 + 5 * value.seed, 2)), Window.rectangle((0.0, 1.0), (0.0, 1.0)))
        if value.name in ("layers", "structure"):
            from paperlib.mlts import Layer, sample_structure

            layers = (Layer(max_objects=3, max_diameter=20.0),)
            return layers if value.name == "layers" else sample_structure(layers, 40, 30, seed=value.seed)
        raise ValueError(f"unknown factory {value.name}")
    if isinstance(value, tuple):
        return tuple(_factory(item) for item in value)
    if isinstance(value, list):
        return [_factory(item) for item in value]
    if isinstance(value, dict):
        return {key: _factory(item) for key, item in value.items()}
    return value


def _resolve(name: str):
    import importlib

    module_name, _, attribute = name.rpartition(".")
    return getattr(importlib.import_module(module_name), attribute)


def _raised_in_paperlib(exc: BaseException) -> bool:
    frames = traceback.extract_tb(exc.__traceback__)
    return bool(frames) and "/paperlib/" in frames[-1].filename.replace(os.sep, "/")


def _has_nan(value) -> bool:
    import numpy as np

    if isinstance(value, float):
        return math.isnan(value)
    if isinstance(value, np.ndarray) and value.dtype.kind in "fc":
        return bool(np.isnan(value).any())
    if isinstance(value, (tuple, list)) and len(value) < 64:
        return any(_has_nan(item) for item in value)
    return False


def _classify(function, args, kwargs) -> tuple[str, str]:
    try:
        result = function(*args, **kwargs)
    except (ValueError, TypeError) as exc:
        kind = "rejected" if _raised_in_paperlib(exc) else "rejected-deep"
        return kind, f"{type(exc).__name__}: {str(exc)[:160]}"
    except FileNotFoundError as exc:
        return "not-found", str(exc)[:160]
    except BaseException as exc:  # noqa: B036 - everything else is the finding
        where = traceback.extract_tb(exc.__traceback__)[-1]
        return "exception", f"{type(exc).__name__}: {str(exc)[:160]} at {Path(where.filename).name}:{where.lineno}"
    return ("ok-nan" if _has_nan(result) else "ok"), ""


def worker_main(memory: int) -> None:
    """Serve cases from stdin until EOF, under ``memory`` bytes of address space."""
    import resource
    import warnings

    resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    os.chdir(tempfile.mkdtemp(prefix="paperlib-fuzz-"))
    warnings.simplefilter("ignore")
    import matplotlib

    matplotlib.use("Agg")
    import fuzz_registry  # noqa: F401 - Factory must be importable to unpickle cases

    for module in fuzz_registry.MODULES:
        __import__(module)
    stdin, stdout = sys.stdin.buffer, sys.stdout.buffer
    sys.stdout = sys.stderr  # stray prints must not corrupt the frames
    _send(stdout, "ready")
    while True:
        try:
            name, args, kwargs = _receive(stdin)
        except EOFError:
            return
        began = time.perf_counter()
        try:
            outcome = _classify(_resolve(name), _factory(args), _factory(kwargs))
        except BaseException as exc:  # noqa: B036 - building the case failed (e.g. MemoryError)
            outcome = ("exception", f"harness: {type(exc).__name__}: {exc}"[:200])
        _send(stdout, (*outcome, time.perf_counter() - began))
        import matplotlib.pyplot as plt

        plt.close("all")


# ------------------------------------------------------------------------------------------- driver side


class Worker:
    """One worker subprocess; :meth:`run` restarts it after a hang or a crash."""

    def __init__(self, memory: int, seconds: float):
        self.memory, self.seconds, self.process = memory, seconds, None
        self.restarts = 0

    def _start(self) -> None:
        environment = dict(os.environ, NUMBA_NUM_THREADS="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1",
                           MKL_NUM_THREADS="1", MPLBACKEND="Agg", PYTHONHASHSEED="0")
        self.process = subprocess.Popen([sys.executable, __file__, "--worker", str(self.memory)],
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                        env=environment)
        _receive(self.process.stdout)  # "ready": imports done, outside the case's time

    def close(self) -> None:
        if self.process is not None:
            self.process.kill()
            self.process.wait()
            self.process = None

    def run(self, name: str, args, kwargs) -> tuple[str, str, float]:
        if self.process is None:
            self._start()
        try:
            _send(self.process.stdin, (name, args, kwargs))
        except (BrokenPipeError, pickle.PicklingError, TypeError, AttributeError) as exc:
            self.close()
            return "crash", f"could not send the case: {exc}", 0.0
        with ThreadPoolExecutor(1) as pool:
            answer = pool.submit(_receive, self.process.stdout)
            try:
                return answer.result(timeout=self.seconds)
            except TimeoutError:
                self.close()
                self.restarts += 1
                return "hang", f"no answer within {self.seconds:g} s", self.seconds
            except EOFError:
                code = self.process.wait()
                self.process = None
                self.restarts += 1
                return "crash", f"worker died (exit status {code})", 0.0


def run_callable(worker: Worker, name: str, examples: int, *, derandomize: bool) -> list[tuple]:
    """Run ``examples`` Hypothesis cases of ``name`` in ``worker``; the outcomes, with their inputs."""
    from fuzz_registry import EXPECTED_EXCEPTIONS, case_strategy
    from hypothesis import HealthCheck, Phase, given, settings

    outcomes = []

    @settings(max_examples=examples, deadline=None, database=None, derandomize=derandomize,
              phases=[Phase.generate], suppress_health_check=list(HealthCheck))
    @given(case_strategy(name))
    def fuzz(case):
        args, kwargs = case
        outcome = worker.run(name, args, kwargs)
        if outcome[0] == "exception" and outcome[1].startswith(EXPECTED_EXCEPTIONS.get(name, "\0")):
            outcome = ("usage", *outcome[1:])
        outcomes.append((*outcome, repr((args, kwargs))[:300]))

    fuzz()
    return outcomes


def run_campaign(names, examples: int, *, memory: int, seconds: float, jobs: int = 1, derandomize: bool = True,
                 progress=None) -> dict:
    """Outcomes of every name: ``{name: [(outcome, detail, seconds, input), ...]}`` (names split over jobs)."""
    names = list(names)
    shares = [names[index::jobs] for index in range(jobs)]

    def share_outcomes(share):
        worker, results = Worker(memory, seconds), {}
        try:
            for name in share:
                results[name] = run_callable(worker, name, examples, derandomize=derandomize)
                if progress:
                    progress(name, results[name])
        finally:
            worker.close()
        return results

    with ThreadPoolExecutor(jobs) as pool:
        merged = {}
        for results in pool.map(share_outcomes, shares):
            merged.update(results)
    return {name: merged[name] for name in names}


def bad_outcomes(results: dict) -> dict:
    """``{name: [bad outcomes]}`` for the names with at least one bad outcome."""
    return {name: [o for o in outcomes if o[0] in BAD] for name, outcomes in results.items()
            if any(o[0] in BAD for o in outcomes)}


OUTCOMES = ("ok", "ok-nan", "rejected", "rejected-deep", "not-found", "usage", "exception", "hang", "crash")


def summary_table(results: dict) -> str:
    """A markdown table of outcome counts per subpackage, with a total row."""
    rows = collections.defaultdict(collections.Counter)
    callables = collections.Counter()
    for name, outcomes in results.items():
        module = name.rpartition(".")[0].replace("paperlib.", "")
        callables[module] += 1
        rows[module].update(outcome for outcome, *_ in outcomes)
    header = "| module | callables | inputs | " + " | ".join(OUTCOMES) + " |"
    lines = [header, "|" + "---|" * (len(OUTCOMES) + 3)]
    total = collections.Counter()
    for module in sorted(rows):
        total.update(rows[module])
        cells = [str(rows[module][outcome]) for outcome in OUTCOMES]
        lines.append(f"| {module} | {callables[module]} | {sum(rows[module].values())} | " + " | ".join(cells) + " |")
    cells = [f"**{total[outcome]}**" for outcome in OUTCOMES]
    lines.append(f"| **all** | **{sum(callables.values())}** | **{sum(total.values())}** | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def failure_list(results: dict) -> str:
    """One line per callable with bad outcomes: counts by kind and the first one's detail and input."""
    from fuzz_registry import KNOWN_FAILURES, OPEN_FAILURES

    lines = []
    for name, bad in sorted(bad_outcomes(results).items()):
        kinds = collections.Counter(outcome for outcome, *_ in bad)
        known = " (known)" if name in KNOWN_FAILURES else " (open)" if name in OPEN_FAILURES else ""
        outcome, detail, _, case = bad[0]
        lines.append(f"- `{name}`{known}: {dict(kinds)} of {len(results[name])}; first: {outcome}: {detail}; "
                     f"input {case[:160]}")
    return "\n".join(lines) or "(none)"


def _names_a_parameter(message: str, parameters: list[str]) -> bool:
    return any(re.search(rf"\b{re.escape(parameter)}\b", message) for parameter in parameters)


def unnamed_rejections(results: dict) -> str:
    """The rejections whose message names none of the callable's parameters (issue 21 asks each to name one).

    A budget message names its keyword, so it counts as named. One line per callable, most first.
    """
    import inspect

    counts, first = collections.Counter(), {}
    for name, outcomes in results.items():
        try:
            parameters = list(inspect.signature(_resolve(name)).parameters)
        except (TypeError, ValueError):   # no signature to read (a builtin): not counted
            continue
        for outcome, detail, *_ in outcomes:
            if outcome == "rejected" and not _names_a_parameter(detail, parameters):
                counts[name] += 1
                first.setdefault(name, detail)
    rejected = sum(outcome == "rejected" for outcomes in results.values() for outcome, *_ in outcomes)
    lines = [f"{sum(counts.values())} of {rejected} rejections in {len(counts)} callables name no parameter."]
    lines += [f"- `{name}`: {count}; first: {first[name][:120]}" for name, count in counts.most_common()]
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--examples", type=int, default=40, help="Hypothesis inputs per callable")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--memory", type=int, default=FULL_MEMORY, help="address-space limit per worker, bytes")
    parser.add_argument("--seconds", type=float, default=FULL_SECONDS, help="time limit per case")
    parser.add_argument("--only", default="", help="substring selecting callables")
    parser.add_argument("--random", action="store_true", help="new random inputs (default: derandomized)")
    parser.add_argument("--out", default="build/fuzz")
    parser.add_argument("--worker", type=int, help=argparse.SUPPRESS)
    options = parser.parse_args(argv)
    if options.worker:
        worker_main(options.worker)
        return 0
    from fuzz_registry import NOT_FUZZED, REGISTRY

    names = [name for name in REGISTRY if name not in NOT_FUZZED and options.only in name]
    began = time.perf_counter()
    results = run_campaign(names, options.examples, memory=options.memory, seconds=options.seconds,
                           jobs=options.jobs, derandomize=not options.random,
                           progress=lambda name, outcomes: print(f"{name}: {len(outcomes)}", file=sys.stderr))
    elapsed = time.perf_counter() - began
    text = (f"# Fuzz campaign\n\n{sum(map(len, results.values()))} inputs over {len(results)} callables in "
            f"{elapsed:.0f} s ({options.examples} per callable, {options.memory / 2**30:g} GiB and "
            f"{options.seconds:g} s per case, {options.jobs} workers).\n\n{summary_table(results)}\n\n"
            f"## Callables with bad outcomes\n\n{failure_list(results)}\n\n"
            f"## Rejections that name no parameter\n\n{unnamed_rejections(results)}\n")
    out = Path(options.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "summary.md").write_text(text)
    (out / "outcomes.json").write_text(json.dumps(results, indent=1, default=str))
    print(text)
    registry = __import__("fuzz_registry")
    unexpected = set(bad_outcomes(results)) - set(registry.KNOWN_FAILURES) - set(registry.OPEN_FAILURES)
    return 1 if unexpected else 0


if __name__ == "__main__":
    sys.exit(main())
