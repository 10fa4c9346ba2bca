"""Input checks shared by every floor of paperlib (a private utility importing nothing from it)."""

from __future__ import annotations

import math
from numbers import Integral

__all__ = ["integer_at_least", "positive_number"]


def positive_number(value, name: str, *, allow_zero: bool = False) -> float:
    """``value`` as a float, or a ValueError naming ``name`` unless it is finite and > 0 (>= 0)."""
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
