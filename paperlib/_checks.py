"""Input checks shared by every floor of paperlib (a private utility importing nothing from it)."""

from __future__ import annotations

import json
import math
import os
from numbers import Integral

import numpy as np

__all__ = ["integer_at_least", "positive_number"]


def positive_number(value, name: str, *, allow_zero: bool = False) -> float:
    """``value`` as a float, or a ValueError naming ``name`` unless it is finite and > 0 (>= 0).

    A bool or a string is not a number here, though ``float`` would convert it (True to 1.0, "3" to 3.0).
    """
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise ValueError(f"{name} must be a number, got {value!r:.80}")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(number) or number < 0 or (number == 0 and not allow_zero):
        expected = "a non-negative finite number" if allow_zero else "a positive finite number"
        raise ValueError(f"{name} must be {expected}, got {value!r}")
    return number


def integer_at_least(value, name: str, minimum: int) -> int:
    """``value`` as an int, or a ValueError naming ``name`` unless it is an integer (not a bool) >= ``minimum``."""
    if isinstance(value, bool) or not isinstance(value, Integral) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


# --------------------------------------------------------------------------- added for issue 21
# Everything below is shared by the public functions of paperlib: one place for each check, so the
# same bad input gets the same message wherever it enters. Each helper returns the normalised value
# and raises ValueError (a bad value) or TypeError (a value of the wrong kind) naming the parameter.

__all__ += [
    "as_generator",
    "check_budget",
    "check_choice",
    "check_edges",
    "check_flag",
    "check_rng",
    "data_frame",
    "file_path",
    "finite_array",
    "float_array",
    "real_number",
    "instance_of",
    "integer_array",
    "integer_in_range",
    "label",
    "load_json",
    "budget",
    "point_array",
]

def integer_in_range(value, name: str, minimum: int, maximum: int) -> int:
    """``value`` as an int, or a ValueError naming ``name`` unless it is an integer in ``[minimum, maximum]``."""
    if isinstance(value, bool) or not isinstance(value, Integral) or not minimum <= value <= maximum:
        raise ValueError(f"{name} must be an integer in [{minimum}, {maximum}], got {value!r}")
    return int(value)


def check_choice(value, choices, name: str):
    """``value`` unchanged, or a ValueError naming ``name`` unless it is one of ``choices``.

    Safe on any value: an array, a list or an unhashable object is refused with the message, never with
    NumPy's "truth value of an array is ambiguous" or a TypeError from a set lookup.
    """
    try:
        found = bool(value in choices)
    except (TypeError, ValueError):
        found = False
    if not found:
        raise ValueError(f"{name} must be one of {tuple(choices)}, got {value!r:.80}")
    return value


def check_flag(value, name: str) -> bool:
    """``value`` as a bool, or a TypeError naming ``name`` unless it is True or False (numpy bools too)."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def check_budget(needed, limit, name: str, what: str) -> None:
    """ValueError when ``needed`` exceeds the budget ``limit``, passed as the keyword ``name``.

    Parameters
    ----------
    needed : int or float
        What the call would use (points, bytes, bins, samples...), estimated before allocating.
    limit : int or float
        The ceiling in force; ``name`` is the keyword argument that sets it.
    name : str
        The budget's keyword argument, named in the message so the caller knows how to raise it.
    what : str
        What is counted, e.g. ``"flattened points"``.
    """
    if needed > limit:
        raise ValueError(f"this call needs {_amount(needed)} {what}, above the budget {name}={_amount(limit)}; "
                         f"pass a larger {name}= to allow it (or reduce the input)")


def _amount(value) -> str:
    """A count for a message: with thousands separators, or in scientific notation when it is huge."""
    try:
        return f"{value:,}" if abs(value) < 10**15 else f"{float(value):.3g}"
    except OverflowError:
        return "more than 1e308"


def budget(value, name: str) -> int:
    """A budget keyword's value as an int >= 1 (the ceilings themselves are validated too)."""
    return integer_at_least(value, name, 1)


def as_generator(rng, name: str = "rng") -> np.random.Generator:
    """The one normalisation of a random source: ``numpy.random.default_rng`` after a type check.

    Parameters
    ----------
    rng : None, int, numpy.random.SeedSequence or numpy.random.Generator
        None draws fresh entropy; a non-negative int or a SeedSequence gives the same stream every
        time; a Generator is used as it is (the same object, so the caller's stream advances).
    name : str
        The parameter's name, for the message.

    Returns
    -------
    numpy.random.Generator
        Exactly ``numpy.random.default_rng(rng)``: same seed, same numbers, bit for bit.

    Raises
    ------
    TypeError
        For any other kind of value: strings, floats, bools, a legacy ``numpy.random.RandomState``
        (which cannot spawn independent streams; pass ``numpy.random.default_rng(seed)`` instead).
    ValueError
        For a negative int seed.
    """
    return np.random.default_rng(check_rng(rng, name))


def check_rng(rng, name: str = "rng"):
    """``rng`` unchanged (an int as a Python int) if it is a valid random source for :func:`as_generator`.

    Raises the TypeError or ValueError :func:`as_generator` documents; creates no generator, so a
    caller that spawns seed sequences itself (``paperlib.parallel``) checks with the same rule.
    """
    if rng is None or isinstance(rng, (np.random.Generator, np.random.SeedSequence)):
        return rng
    if isinstance(rng, np.random.RandomState):
        raise TypeError(f"{name} must be None, an int seed, a SeedSequence or a numpy.random.Generator; a legacy "
                        f"RandomState cannot spawn independent streams: pass numpy.random.default_rng(seed)")
    if isinstance(rng, (bool, np.bool_)) or not isinstance(rng, Integral):
        raise TypeError(f"{name} must be None, an int seed, a SeedSequence or a numpy.random.Generator, "
                        f"got {type(rng).__name__} {rng!r:.80}")
    if rng < 0:
        raise ValueError(f"{name} must be a non-negative int seed, got {rng!r}")
    return int(rng)


def float_array(values, name: str, expected: str = "an array of numbers") -> np.ndarray:
    """``values`` as a float64 array (``numpy.asarray``), or a ValueError naming ``name`` unless it is numeric.

    Only the conversion: no check of shape or finiteness. ``expected`` completes "``name`` must be ...".
    """
    if isinstance(values, (str, bytes)):
        raise ValueError(f"{name} must be {expected}, got {type(values).__name__} {values!r:.40}")
    try:
        return np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name} must be {expected}, got {type(values).__name__} {values!r:.40}") from None


def real_number(value, name: str, expected: str = "a number") -> float:
    """``value`` as a float (infinities and NaN pass through), or a ValueError naming ``name`` unless it is one
    real number (a Python or NumPy scalar, or a 0-d array; not a string)."""
    array = float_array(value, name, expected)
    if array.ndim != 0:
        raise ValueError(f"{name} must be {expected}, got an array of shape {array.shape}")
    return float(array)


def finite_array(values, name: str, *, ndim: int | None = None, min_size: int = 0,
                 shape: tuple | None = None, allow_infinite: bool = False) -> np.ndarray:
    """``values`` as a float64 array, or a ValueError naming ``name`` unless numeric, finite, of ``ndim``.

    ``shape``, when given, is the expected shape with ``None`` for a free axis (``(None, 4, 2)``);
    ``allow_infinite`` lets infinities through (NaN never passes).
    """
    array = float_array(values, name)
    if ndim is not None and array.ndim != ndim:
        raise ValueError(f"{name} must be {ndim}-D ({ndim}-dimensional), got shape {array.shape}")
    if shape is not None and (array.ndim != len(shape) or any(
            expected is not None and size != expected for size, expected in zip(array.shape, shape))):
        wanted = "(" + ", ".join("n" if size is None else str(size) for size in shape) + ")"
        raise ValueError(f"{name} must be an array of shape {wanted}, got shape {array.shape}")
    if array.size < min_size:
        raise ValueError(f"{name} needs at least {min_size} values, got {array.size}")
    if np.isnan(array).any() if allow_infinite else not np.isfinite(array).all():
        raise ValueError(f"{name} contains NaN{'' if allow_infinite else ' or infinite'} values")
    return array


def integer_array(values, name: str) -> np.ndarray:
    """``values`` as an int64 array, or a ValueError naming ``name`` unless every value is a whole number.

    Integer and bool arrays pass; float arrays pass when every value is finite, whole and within int64.
    """
    if isinstance(values, (str, bytes)):
        raise ValueError(f"{name} must be an array of integers, got {type(values).__name__} {values!r:.40}")
    try:
        array = np.asarray(values)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name} must be an array of integers, got {type(values).__name__}") from None
    if array.dtype.kind in "iub":
        return array.astype(np.int64)
    if array.dtype.kind == "f" and np.isfinite(array).all() and (np.abs(array) < 2.0**63).all() and (
            array == np.round(array)).all():
        return array.astype(np.int64)
    if array.size == 0 and array.dtype.kind in "fO":
        return np.zeros(array.shape, dtype=np.int64)
    raise ValueError(f"{name} must be an array of integers, got {array.dtype} values {array.ravel()[:4]!r:.80}")


def point_array(values, name: str, *, min_points: int = 0) -> np.ndarray:
    """``values`` as a finite float64 ``(n, 2)`` array with ``n >= min_points``, or a ValueError naming ``name``."""
    array = float_array(values, name, "an (n, 2) array of numeric points")
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(f"{name} must be an (n, 2) array of points, got shape {array.shape}")
    if len(array) < min_points:
        raise ValueError(f"{name} needs at least {min_points} points, got {len(array)}")
    if not np.isfinite(array).all():
        raise ValueError(f"{name} contains NaN or infinite values: points must be finite")
    return array


def check_edges(edges, n_nodes: int, name: str = "edges") -> np.ndarray:
    """``edges`` as an int64 ``(m, 2)`` array of integer node pairs, each in ``[0, n_nodes)``, or a ValueError."""
    n_nodes = integer_at_least(n_nodes, "n", 0)
    try:
        array = np.asarray(edges)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an (m, 2) array of edges (integer node pairs)") from None
    if array.size == 0:
        return np.empty((0, 2), dtype=np.int64)
    if array.ndim != 2 or array.shape[1] != 2 or not np.issubdtype(array.dtype, np.integer):
        raise ValueError(f"{name} must be an (m, 2) array of edges (integer node pairs), got {array.dtype} of "
                         f"shape {array.shape}")
    if array.min() < 0 or array.max() >= n_nodes:
        raise ValueError(f"{name} name nodes outside [0, {n_nodes}) (n = {n_nodes} nodes): "
                         f"{int(array.min())} to {int(array.max())}")
    return array.astype(np.int64)


def load_json(text, what: str, name: str = "text"):
    """Parse JSON text, mapping every parser failure (syntax, nesting too deep) to a ValueError naming ``what``.

    ``what`` is a noun phrase such as ``"a JSON script"``, ``name`` the caller's parameter the text came from:
    messages read ``"text: not a JSON script: ..."``.
    """
    if isinstance(text, (bytes, bytearray)):
        text = bytes(text).decode("utf-8", errors="replace")
    if not isinstance(text, str):
        raise TypeError(f"{name} must be JSON text (str) holding {what}, got {type(text).__name__}")
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise ValueError(f"{name}: not {what}: {exc}") from exc
    except RecursionError:   # no chaining: the recursion's traceback is thousands of frames
        raise ValueError(f"{name}: {what} nests too deeply to be read") from None


def label(value, name: str = "name") -> str:
    """``value`` unchanged if it is a str: the ``name`` keyword of a validator, printed in its messages."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a str (the parameter name printed in messages), got "
                        f"{type(value).__name__} {value!r:.60}")
    return value


def instance_of(value, types, name: str):
    """``value`` unchanged, or a TypeError naming ``name`` unless it is an instance of ``types``.

    For the objects a public function takes from another of paperlib (a fitted model, a pattern, a
    result dataclass): the message names the class expected and the type received.
    """
    if not isinstance(value, types):
        expected = " or ".join(t.__name__ for t in (types if isinstance(types, tuple) else (types,)))
        article = "an" if expected[0] in "AEIOUaeiou" else "a"
        raise TypeError(f"{name} must be {article} {expected}, got {type(value).__name__} {value!r:.60}")
    return value


def file_path(path, name: str = "path"):
    """``path`` as a ``pathlib.Path`` naming a file to read or write, or a TypeError/ValueError naming ``name``.

    A str or path-like object is accepted; an empty string (the current folder) or a path that names an
    existing folder is a ValueError, so a reader or writer never fails later with IsADirectoryError.
    """
    from pathlib import Path

    if not isinstance(path, (str, os.PathLike)) or isinstance(path, bytes):
        raise TypeError(f"{name} must be a file path (str or pathlib.Path), got {type(path).__name__} {path!r:.60}")
    if isinstance(path, str) and (not path.strip() or "\x00" in path):
        raise ValueError(f"{name} must name a file, got {path!r}")
    path = Path(path)
    if path.is_dir():
        raise ValueError(f"{name} must name a file, got the folder {str(path)!r}")
    return path


def data_frame(value, name: str, columns):
    """``value`` unchanged if it is a pandas DataFrame holding ``columns``; else a TypeError or ValueError naming ``name``."""
    import pandas as pd

    instance_of(value, pd.DataFrame, name)
    missing = [column for column in columns if column not in value.columns]
    if missing:
        raise ValueError(f"{name} lacks the columns {missing} (has {list(value.columns)[:12]})")
    return value
