"""Recording statistics and figures, and checking them against tolerances.

A notebook calls :func:`start` once with its papermill parameters, then
:func:`record` for every quantitative claim and :func:`save_figure` for every figure.
Everything lands in ``out_dir`` (by convention ``figures/<notebook-stem>/``):
``stats.json`` holds the run's seed, quality and statistics, and the numba kernels the run had
used by its last output (``numba_kernels``, what the determinism rerun must cover). :func:`check_stats`
compares those files with ``tests/expected_stats.toml``.

The expected file has one table per notebook and statistic::

    [datasets_overview.n_hershey_fonts]
    kind = "truth"
    value = 32
    source = "ground truth: Hershey-Fonts 2.1 bundles 32 fonts"

    [kim2009_fig07-08_distributions_glcm.glcm_pearson]
    kind = "paper"
    min = 0.99
    source = "paper, section 3.3 and Fig. 8: coefficients 'greater than 0.99'"
    xfail = "measured 0.93-0.95 (seeds 0-4); cause: ..."   # a paper claim we miss

    [kim2009_fig04_tone_extraction.tone_error]
    kind = "seed-study"
    max = 0.05
    source = "seeds 0-9: 0.007-0.034"
    paper = { max = 0.04 }       # override for quality = "paper" runs

A spec holds ``kind``, ``source`` and either ``value`` (with optional ``rtol``/``atol``;
exact when both are absent) or ``min``/``max``. ``kind`` says where the bound comes
from (:data:`KINDS`) and the ``source`` must support it (a paper statistic cites where
the paper says so, an oracle names the independent implementation, a seed study its
seeds). A seed study bounds a float by its spread over seeds, never by one seed's value:
chaotic computations diverge on another processor. ``xfail`` marks a paper claim we
miss, with the measured value and the cause; the run passes while the miss persists and
fails once it is gone. Statistics whose names start with ``time_`` are wall times: they
are shown and never asserted (speed is asserted in ``benchmarks/`` as ratios), and they
are ignored when two runs are compared.

This module knows no method: it only moves numbers and files.
"""

from __future__ import annotations

import importlib.util
import json
import math
import os
import re
import tomllib
from dataclasses import dataclass
from numbers import Integral, Real
from pathlib import Path

import matplotlib
import numpy as np
import pandas as pd

from ._atomic import atomic_path
from ._checks import check_choice, file_path, instance_of, load_json
from ._kernels_used import kernels_used

__all__ = [
    "QUALITIES",
    "KERNELS_KEY",
    "STATS_FILE",
    "atomic_path",
    "check_stats",
    "current_out_dir",
    "load_expected",
    "load_stats",
    "record",
    "save_figure",
    "start",
    "statistics_without_times",
]

QUALITIES = ("ci", "paper")
STATS_FILE = "stats.json"
#: Key of ``stats.json`` listing the paperlib numba kernels the run used (:mod:`paperlib._kernels_used`).
KERNELS_KEY = "numba_kernels"
#: Packages of optional comparisons (the ``requires`` of expected statistics), and the key of ``stats.json``
#: recording which of them the run could import: an entry that requires one is checked when the *run* had
#: it, so the verdicts read from a run do not depend on the packages of the machine that reads it.
OPTIONAL_PACKAGES = ("plenoptic",)
OPTIONAL_PACKAGES_KEY = "optional_packages"
TIME_PREFIX = "time_"
CHECK_COLUMNS = ["notebook", "statistic", "value", "expected", "tolerance", "kind", "source", "status", "ok", "reason"]
#: Row statuses that do not fail a run: within tolerance, a paper miss recorded as expected, a wall time,
#: an entry of an optional comparison whose package (its ``requires``) is not installed.
OK_STATUSES = ("pass", "xfail", "shown", "skipped")
EXPECTED_FILE = "tests/expected_stats.toml"

_NAME_PATTERN = re.compile(r"^[A-Za-z][A-Za-z0-9_.\-]*$")
_PACKAGE_PATTERN = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*$")
_MAX_ITEMS = 10_000  # a statistic is a number or a small table, never raw data
_BOUND_KEYS = {"value", "rtol", "atol", "min", "max", "xfail"}
_SPEC_KEYS = _BOUND_KEYS | {"source", "kind", "requires"}

#: Where an expected number comes from (DESIGN.md, "Validation: what a statistic must prove").
KINDS = ("paper", "oracle", "truth", "seed-study", "budget")
#: What a ``source`` must mention to support its ``kind``, and how to say so in an error.
_KIND_EVIDENCE = {
    "paper": (
        re.compile(r"\bpaper\b.*?\b(section|sec\.|fig\.|figs\.|figure|table|eq\.|eqs\.|equation|abstract|caption)",
                   re.IGNORECASE | re.DOTALL),
        "the paper and where it says so (section, figure, table, equation, abstract or caption)",
    ),
    "oracle": (
        re.compile(r"spatstat|rrcov|scikit-image|skimage|shapely|scipy|\bR\b", re.IGNORECASE),
        "the independent implementation it is checked against (spatstat, rrcov, scikit-image, shapely, SciPy, R)",
    ),
    "truth": (
        re.compile(r"ground truth|closed form|analytic|by construction|by definition|exact|identity|theorem",
                   re.IGNORECASE),
        "the known answer: 'ground truth', 'closed form', 'analytic', 'by construction', 'by definition', 'exact'",
    ),
    "seed-study": (
        re.compile(r"seeds?\s*\d", re.IGNORECASE),
        "the seeds the range was measured over (e.g. 'seeds 0-9: 0.12-0.31')",
    ),
    "budget": (
        re.compile(r"budget|design limit|\bcap\b|\blimit\b", re.IGNORECASE),
        "the budget, cap or design limit it enforces",
    ),
}


@dataclass(frozen=True)
class _Run:
    out_dir: Path
    notebook: str


_current_run: _Run | None = None


# --------------------------------------------------------------------------- files


def _write_json(path, data) -> None:
    with atomic_path(path) as temporary:
        temporary.write_text(json.dumps(data, indent=1, sort_keys=False, allow_nan=False) + "\n")


# --------------------------------------------------------------------------- recording


def start(out_dir, *, seed, quality) -> Path:
    """Begin a notebook run: create ``out_dir`` and a fresh ``stats.json`` in it.

    Parameters
    ----------
    out_dir : str or Path
        The notebook's figure folder, ``figures/<notebook-stem>/``; its name is taken
        as the notebook's name.
    seed : int
        The run's seed, stored beside the statistics.
    quality : {"ci", "paper"}
        The run's quality, stored so that checks pick the matching tolerances.

    Returns
    -------
    Path
        The absolute output folder.

    Raises
    ------
    ValueError
        For an empty ``out_dir`` (which would write ``stats.json`` into the current folder),
        one that names an existing file, a bad ``seed`` or ``quality``.
    TypeError
        If ``out_dir`` is not a str or path.
    """
    out_dir = _output_folder(out_dir)
    check_choice(quality, QUALITIES, "quality")
    if not isinstance(seed, Integral) or isinstance(seed, bool):
        raise ValueError(f"seed must be an int, got {seed!r}")
    out_dir.mkdir(parents=True, exist_ok=True)
    global _current_run
    _current_run = _Run(out_dir, out_dir.name)
    _write_json(
        out_dir / STATS_FILE,
        {"notebook": out_dir.name, "seed": int(seed), "quality": quality, "statistics": {},
         OPTIONAL_PACKAGES_KEY: {name: importlib.util.find_spec(name) is not None for name in OPTIONAL_PACKAGES}},
    )
    return out_dir


def _output_folder(out_dir) -> Path:
    """``out_dir`` as an absolute folder path: not empty, not an existing file."""
    if not isinstance(out_dir, (str, os.PathLike)):
        raise TypeError(f"out_dir must be a folder path (str or Path), got {type(out_dir).__name__}")
    text = os.fspath(out_dir)
    if not isinstance(text, str) or not text.strip() or "\x00" in text:
        raise ValueError(f"out_dir must name a folder (figures/<notebook-stem>), got {out_dir!r}")
    path = Path(text).resolve()
    if path.exists() and not path.is_dir():
        raise ValueError(f"out_dir {str(path)!r} exists and is not a folder")
    return path


def current_out_dir() -> Path:
    """The output folder of the run begun by :func:`start`.

    Returns
    -------
    pathlib.Path
        The ``out_dir`` given to :func:`start`.
    """
    return _require_run().out_dir


def _require_run() -> _Run:
    if _current_run is None:
        raise RuntimeError("no run started: call paperlib.repro.start(out_dir, seed=..., quality=...) first")
    return _current_run


def _to_json_value(value, name: str):
    """Convert NumPy scalars and arrays to plain JSON values, rejecting what JSON cannot hold."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (Integral, np.integer)):
        return int(value)
    if isinstance(value, (Real, np.floating)):
        value = float(value)
        if not math.isfinite(value):
            raise ValueError(f"statistic {name!r} is {value}: record only finite numbers")
        return value
    if isinstance(value, str):
        return value
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        if len(value) > _MAX_ITEMS:
            raise ValueError(f"statistic {name!r} has {len(value)} items; at most {_MAX_ITEMS} are allowed")
        return [_to_json_value(item, name) for item in value]
    if isinstance(value, dict):
        if len(value) > _MAX_ITEMS:
            raise ValueError(f"statistic {name!r} has {len(value)} keys; at most {_MAX_ITEMS} are allowed")
        if not all(isinstance(key, str) for key in value):
            raise ValueError(f"statistic {name!r}: dictionary keys must be strings")
        return {key: _to_json_value(item, name) for key, item in value.items()}
    raise ValueError(
        f"statistic {name!r} has type {type(value).__name__}; "
        "record a number, bool, string, list or small dict"
    )


def record(name: str, value):
    """Record a statistic of the current run in ``stats.json`` and return ``value``.

    Recording the same name again replaces the earlier value (re-running a cell
    interactively must not fail).

    Parameters
    ----------
    name : str
        Letters, digits, ``_``, ``.``, ``-``, starting with a letter. Names starting
        with ``time_`` are wall times (checked against an upper bound only).
    value : number, bool, str, list or dict
        NumPy scalars and arrays are converted; NaN and infinities are rejected.

    Returns
    -------
    object
        ``value``, unchanged (so that a cell can record and use it in one expression).
    """
    run = _require_run()
    if not isinstance(name, str) or not _NAME_PATTERN.match(name):
        raise ValueError(f"statistic name {name!r} must start with a letter and use only letters, digits, _ . -")
    data = load_stats(run.out_dir / STATS_FILE)
    data["statistics"][name] = _to_json_value(value, name)
    data[KERNELS_KEY] = kernels_used()
    _write_json(run.out_dir / STATS_FILE, data)
    return value


def _note_kernels(run: _Run) -> None:
    """Bring the run's list of used numba kernels up to date (after an output that may have needed more)."""
    data = load_stats(run.out_dir / STATS_FILE)
    kernels = kernels_used()
    if data.get(KERNELS_KEY) != kernels:
        data[KERNELS_KEY] = kernels
        _write_json(run.out_dir / STATS_FILE, data)


def save_figure(fig, name: str, *, svg: bool = False, dpi: int = 100) -> list[Path]:
    """Save a matplotlib figure as ``<out_dir>/<name>.png`` (and ``.svg`` when asked).

    Files are written atomically and without timestamps, so the same figure gives the
    same bytes and an interrupted run leaves no partial file.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure to save.
    name : str
        File stem: letters, digits, ``_``, ``.``, ``-``, starting with a letter.
    svg : bool, default False
        Also write ``<name>.svg``.
    dpi : int, default 100
        Resolution of the PNG, dots per inch.

    Returns
    -------
    list of Path
        The files written.
    """
    run = _require_run()
    if not isinstance(name, str) or not _NAME_PATTERN.match(name):
        raise ValueError(f"figure name {name!r} must start with a letter and use only letters, digits, _ . -")
    written = []
    formats = [("png", {"Software": None})] + ([("svg", {"Date": None, "Creator": None})] if svg else [])
    for extension, metadata in formats:
        target = run.out_dir / f"{name}.{extension}"
        # a fixed salt makes matplotlib's SVG element ids the same on every run
        with atomic_path(target) as temporary, matplotlib.rc_context({"svg.hashsalt": "paperlib"}):
            fig.savefig(temporary, format=extension, dpi=dpi, metadata=metadata, bbox_inches="tight")
        written.append(target)
    _note_kernels(run)
    return written


# --------------------------------------------------------------------------- checking


def load_stats(path) -> dict:
    """Read a ``stats.json`` file written by :func:`start` and :func:`record`.

    Parameters
    ----------
    path : str or os.PathLike
        The ``stats.json`` file.

    Returns
    -------
    dict
        The parsed file: ``statistics`` (``{name: value}``) and, when present, ``notebook``,
        ``quality`` and ``seed``.
    """
    path = file_path(path)
    try:
        text = path.read_text()
    except FileNotFoundError:
        raise ValueError(f"path={str(path)!r}: no stats.json (did the notebook call paperlib.repro.start?)") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path}: cannot read stats.json ({exc})") from None
    data = load_json(text, f"a stats.json ({path})", "path")
    if not isinstance(data, dict) or not isinstance(data.get("statistics"), dict):
        raise ValueError(f"{path}: expected an object with a 'statistics' table")
    for key, expected in (("notebook", str), ("quality", str), ("seed", int)):
        if key in data and not isinstance(data[key], expected):
            raise ValueError(f"{path}: {key!r} must be a {expected.__name__}, got {data[key]!r:.80}")
    return data


def statistics_without_times(data: dict) -> dict:
    """The statistics of a loaded ``stats.json`` minus wall times (for comparing runs).

    Parameters
    ----------
    data : dict
        A loaded ``stats.json`` (:func:`load_stats`), with a ``statistics`` table.

    Returns
    -------
    dict
        ``{name: value}`` of its statistics whose names do not start with ``time_``.
    """
    statistics = instance_of(data, dict, "data").get("statistics")
    if not isinstance(statistics, dict):
        raise ValueError(f"data must be a loaded stats.json with a 'statistics' table, got keys {list(data)[:8]}")
    return {name: value for name, value in statistics.items() if not str(name).startswith(TIME_PREFIX)}


def load_expected(path, notebooks=None) -> dict:
    """Read and validate ``expected_stats.toml``: ``{notebook: {statistic: spec}}``.

    Parameters
    ----------
    path : str or Path
        The file; its tables are ``[<notebook>.<statistic>]``.
    notebooks : iterable of str, optional
        Return and validate only these notebooks' statistics (so that running one
        notebook does not depend on another's entries); a notebook without entries
        gets none.

    Returns
    -------
    dict
        ``{notebook: {statistic: spec}}``, each spec a dict of the entry's keys (``kind``,
        bounds, ``xfail``, ...); only the asked ``notebooks`` when given.

    Raises
    ------
    ValueError
        Naming the file and entry, when the file is missing or malformed, or an entry
        has no ``kind``, a kind its ``source`` does not support, a bound on a wall time,
        or an ``xfail`` that is not a missed paper claim with its measured value.
    """
    path = file_path(path)
    expected = read_toml(path)
    if notebooks is not None:
        expected = {notebook: expected[notebook] for notebook in notebooks if notebook in expected}
    for notebook, statistics in expected.items():
        if not isinstance(statistics, dict):
            raise ValueError(f"{path}: [{notebook}] must be a table of statistics")
        for statistic, spec in statistics.items():
            where = f"{path}: [{notebook}.{statistic}]"
            _validate_spec(spec, where, statistic)
            _validate_requires(spec, where)
    return expected


def _validate_requires(spec: dict, where: str) -> None:
    """``requires`` names the Python package an optional comparison needs (e.g. ``"plenoptic"``)."""
    if "requires" in spec and not (isinstance(spec["requires"], str) and _PACKAGE_PATTERN.match(spec["requires"])):
        raise ValueError(f"{where}: 'requires' must name a Python package, got {spec['requires']!r}")


def read_toml(path, what: str = "expected statistics") -> dict:
    """A TOML file's content; a missing or malformed file is a ValueError naming ``what`` and the path."""
    path = file_path(path)
    try:
        return tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise ValueError(f"{what} file not found: path={str(path)!r}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"path={str(path)!r}: invalid TOML ({exc})") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path}: cannot read the {what} file ({exc})") from None


def _validate_spec(spec, where: str, statistic: str) -> None:
    if not isinstance(spec, dict):
        raise ValueError(f"{where} must be a table with 'kind', 'source' and 'value' or 'min'/'max'")
    if statistic.startswith(TIME_PREFIX):
        raise ValueError(
            f"{where}: wall times ({TIME_PREFIX}*) are recorded and shown, never asserted; "
            "assert speed in benchmarks/ as a ratio against a baseline"
        )
    unknown = set(spec) - _SPEC_KEYS - set(QUALITIES)
    if unknown:
        raise ValueError(f"{where}: unknown keys {sorted(unknown)}; allowed: {sorted(_SPEC_KEYS | set(QUALITIES))}")
    if not isinstance(spec.get("source"), str) or not spec["source"].strip():
        raise ValueError(f"{where}: 'source' must say where the expected number comes from")
    for quality in QUALITIES:
        if quality in spec:
            override = spec[quality]
            if not isinstance(override, dict) or not set(override) <= _BOUND_KEYS:
                raise ValueError(f"{where}.{quality}: an override may set only {sorted(_BOUND_KEYS)}")
            resolved = _resolve_spec(spec, quality)
            _validate_kind(resolved, f"{where} ({quality})")
            _validate_bounds(resolved, f"{where} ({quality})")
    _validate_kind(spec, where)
    _validate_bounds(spec, where)


def _validate_kind(spec: dict, where: str) -> None:
    """The entry's ``kind`` is known, its ``source`` supports it, and ``xfail`` is a paper miss."""
    kind = spec.get("kind")
    if kind not in KINDS:
        raise ValueError(f"{where}: 'kind' must be one of {KINDS}, got {kind!r}")
    evidence, wanted = _KIND_EVIDENCE[kind]
    if not evidence.search(spec["source"]):
        raise ValueError(f"{where}: a {kind!r} statistic's source must name {wanted}; got {spec['source']!r}")
    if "xfail" in spec:
        if kind != "paper":
            raise ValueError(
                f"{where}: only a paper's claim may be an expected failure (xfail); a {kind!r} bound that fails "
                "is a regression to fix"
            )
        if not isinstance(spec["xfail"], str) or not re.search(r"\d", spec["xfail"]) or len(spec["xfail"]) < 20:
            raise ValueError(f"{where}: 'xfail' must give the measured value and the cause of the miss")


def _validate_bounds(spec: dict, where: str) -> None:
    if "value" not in spec and "min" not in spec and "max" not in spec:
        raise ValueError(f"{where}: give 'value' (with rtol/atol) or 'min'/'max'")
    for key in ("rtol", "atol"):
        if key in spec and (not _is_number(spec[key]) or spec[key] < 0):
            raise ValueError(f"{where}: {key} must be a non-negative number")
    if spec.get("kind") == "seed-study" and isinstance(spec.get("value"), float) and ("rtol" in spec or "atol" in spec):
        raise ValueError(
            f"{where}: a seed study bounds a float by its spread over seeds (min/max), not by one seed's value "
            "and a tolerance (another processor diverges)"
        )


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _resolve_spec(spec: dict, quality: str | None) -> dict:
    """The spec with the override for ``quality`` applied (bounds replace bounds)."""
    base = {key: item for key, item in spec.items() if key not in QUALITIES}
    override = spec.get(quality, {}) if quality else {}
    if override and ({"value", "min", "max"} & set(override)):
        base = {key: item for key, item in base.items() if key not in {"value", "rtol", "atol", "min", "max"}}
    return {**base, **override}


def _describe(spec: dict) -> tuple[str, str]:
    """Human-readable (expected, tolerance) strings of a resolved spec."""
    if "value" in spec:
        tolerances = [f"{key}={spec[key]:g}" for key in ("rtol", "atol") if key in spec]
        return json.dumps(spec["value"]), ", ".join(tolerances) or "exact"
    expected = " and ".join(
        f"{sign} {json.dumps(spec[key])}" for key, sign in (("min", ">="), ("max", "<=")) if key in spec
    )
    return expected, "bounds"


def _compare(value, spec: dict) -> str:
    """Return '' when ``value`` satisfies ``spec``, else the reason it does not."""
    if "value" in spec:
        return _compare_to_value(value, spec["value"], spec.get("rtol", 0.0), spec.get("atol", 0.0))
    for item in value if isinstance(value, list) else [value]:
        if not _is_number(item):
            return f"expected a number, got {type(item).__name__} {item!r}"
        if "min" in spec and item < spec["min"]:
            return f"{item!r} is below the minimum {spec['min']!r}"
        if "max" in spec and item > spec["max"]:
            return f"{item!r} is above the maximum {spec['max']!r}"
    return ""


def _compare_to_value(value, expected, rtol: float, atol: float) -> str:
    if isinstance(expected, list):
        if not isinstance(value, list) or len(value) != len(expected):
            return f"expected a list of {len(expected)} items, got {value!r}"[:200]
        return _first_reason((f"item {i}", item, want, rtol, atol) for i, (item, want) in enumerate(zip(value, expected)))
    if isinstance(expected, dict):
        if not isinstance(value, dict) or value.keys() != expected.keys():
            return f"expected a table with keys {sorted(expected)}, got {value!r}"[:200]
        return _first_reason((f"key {key!r}", value[key], want, rtol, atol) for key, want in expected.items())
    if _is_number(expected):
        if not _is_number(value):
            return f"expected a number, got {type(value).__name__} {value!r}"
        if abs(value - expected) > atol + rtol * abs(expected):
            return f"{value!r} differs from {expected!r} by {abs(value - expected):.3g}"
        return ""
    if type(value) is not type(expected) or value != expected:
        return f"expected {expected!r}, got {value!r}"
    return ""


def _first_reason(items) -> str:
    """The first failing comparison among (label, value, expected, rtol, atol) items, or ''."""
    for label, value, expected, rtol, atol in items:
        reason = _compare_to_value(value, expected, rtol, atol)
        if reason:
            return f"{label}: {reason}"
    return ""


def check_stats(figures_dir="figures", expected=EXPECTED_FILE, notebooks=None) -> pd.DataFrame:
    """Compare recorded statistics with the expected file.

    Parameters
    ----------
    figures_dir : str or Path
        Folder holding ``<notebook>/stats.json``.
    expected : str, Path or dict
        The expected statistics (see :func:`load_expected`) or their loaded content.
    notebooks : iterable of str, optional
        Notebook stems to check; by default every notebook with expected statistics.

    Returns
    -------
    pandas.DataFrame
        One row per statistic with the columns of ``CHECK_COLUMNS``. ``status`` is
        ``pass``; ``FAIL``; ``xfail`` for a paper claim we miss as recorded in its
        ``xfail``; ``XPASS`` (failing) when such a miss is gone; ``shown`` for a wall
        time, which is never asserted. ``ok`` is true for pass, xfail and shown. A
        statistic recorded but not expected, or expected but not recorded, fails; so
        does a missing ``stats.json``.
    """
    expected = expected if isinstance(expected, dict) else load_expected(expected)
    notebooks = sorted(expected) if notebooks is None else list(notebooks)
    rows = []
    for notebook in notebooks:
        rows.extend(_check_notebook(Path(figures_dir) / notebook, notebook, expected.get(notebook)))
    return pd.DataFrame(rows, columns=CHECK_COLUMNS)


def _row(notebook, statistic, value=None, expected="", tolerance="", kind="", source="", reason="", status=None):
    status = status or ("FAIL" if reason else "pass")
    return dict(
        notebook=notebook,
        statistic=statistic,
        value=value,
        expected=expected,
        tolerance=tolerance,
        kind=kind,
        source=source,
        status=status,
        ok=status in OK_STATUSES,
        reason=reason,
    )


def _check_notebook(folder: Path, notebook: str, specs: dict | None) -> list[dict]:
    if specs is None:
        return [_row(notebook, "", reason=f"notebook has no entry in {EXPECTED_FILE}")]
    try:
        data = load_stats(folder / STATS_FILE)
    except ValueError as exc:
        return [_row(notebook, "", reason=str(exc))]
    recorded = data["statistics"]
    packages = data.get(OPTIONAL_PACKAGES_KEY)
    rows = [_check_statistic(notebook, statistic, spec, recorded, data.get("quality"), packages)
            for statistic, spec in specs.items()]
    for statistic in (name for name in recorded if name not in specs):  # recorded order: INDEX.md is reproducible
        if statistic.startswith(TIME_PREFIX):
            rows.append(_row(notebook, statistic, recorded[statistic], "shown, not asserted", "", "time",
                             "wall time of this run on this machine", status="shown"))
        else:
            rows.append(_row(notebook, statistic, recorded[statistic], reason=f"recorded but not in {EXPECTED_FILE}"))
    return rows


def _run_had_package(package: str, packages: dict | None, recorded: bool) -> bool:
    """Whether the run could import ``package``: as it recorded (:data:`OPTIONAL_PACKAGES_KEY`); a run
    from before that record had it when it recorded the statistic at all."""
    if isinstance(packages, dict) and package in packages:
        return bool(packages[package])
    return recorded


def _check_statistic(notebook: str, statistic: str, spec: dict, recorded: dict, quality: str | None,
                     packages: dict | None) -> dict:
    """One row: pass, FAIL, xfail (a paper claim we miss, as expected), XPASS (the miss is gone) or skipped
    (an optional comparison whose package the run did not have)."""
    resolved = _resolve_spec(spec, quality)
    expected_text, tolerance = _describe(resolved)
    row = dict(notebook=notebook, statistic=statistic, expected=expected_text, tolerance=tolerance,
               kind=spec["kind"], source=spec["source"])
    required = spec.get("requires")
    if required is not None and not _run_had_package(required, packages, statistic in recorded):
        return _row(**row, value=recorded.get(statistic), reason=f"not checked: the run had no {required}",
                    status="skipped")
    if statistic not in recorded:
        return _row(**row, reason="expected but not recorded")
    value = recorded[statistic]
    reason = _compare(value, resolved)
    if "xfail" not in resolved:
        return _row(**row, value=value, reason=reason)
    if reason:
        return _row(**row, value=value, reason=f"expected failure: {resolved['xfail']}", status="xfail")
    return _row(**row, value=value, status="XPASS",
                reason="the paper's bound is now met: remove 'xfail' and update the claims ledger")
