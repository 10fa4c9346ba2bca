"""Marked point patterns (spatstat's ``ppp``).

A :class:`PointPattern` is what Hurtut 2009 (section 3.1) calls an arrangement: element
positions ``x_i`` with appearance-category labels ``m_i`` observed in a window. Marks are
integers ``0 .. n_types - 1`` indexing ``categories``; an unmarked pattern has one
category.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from paperlib.geometry import as_points

from .window import Window

__all__ = ["PointPattern"]


@dataclass(frozen=True, eq=False)
class PointPattern:
    """Points with integer marks in a window.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        Coordinates; finite, inside ``window`` (boundary included), no two equal.
    window : Window
    marks : array_like of int, shape (n,), optional
        Category index of each point, ``0 <= mark < len(categories)``. Default: all 0.
    categories : sequence of str, optional
        Category names; default ``("0", ..., str(max mark))``, or ``("points",)``
        for an unmarked pattern.

    Raises
    ------
    ValueError
        For NaN/infinite coordinates, points outside the window, coincident points,
        marks of the wrong length or out of range, or duplicate category names.
    """

    points: np.ndarray
    window: Window
    marks: np.ndarray | None = None
    categories: tuple | None = None

    def __post_init__(self):
        points = as_points(np.reshape(self.points, (-1, 2)) if np.size(self.points) == 0 else self.points,
                           name="points", min_points=0)
        if not isinstance(self.window, Window):
            raise ValueError(f"window must be a paperlib.pointprocess.Window, got {type(self.window).__name__}")
        outside = ~self.window.contains(points)
        if outside.any():
            first = points[np.argmax(outside)]
            raise ValueError(f"{outside.sum()} point(s) lie outside the window {self.window}, e.g. {first.tolist()}")
        _reject_coincident(points)
        marks, categories = _checked_marks(self.marks, self.categories, len(points))
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "marks", marks)
        object.__setattr__(self, "categories", categories)

    # ------------------------------------------------------------------ basics

    @property
    def n(self) -> int:
        return self.points.shape[0]

    def __len__(self) -> int:
        return self.n

    @property
    def n_types(self) -> int:
        return len(self.categories)

    @property
    def counts(self) -> np.ndarray:
        """Number of points of each type."""
        return np.bincount(self.marks, minlength=self.n_types)

    @property
    def intensity(self) -> float:
        """Points per unit area, all types together (spatstat's ``intensity``)."""
        return self.n / self.window.area

    def type_index(self, category) -> int:
        """Index of a category given by name or index."""
        if isinstance(category, (int, np.integer)) and not isinstance(category, bool):
            if not 0 <= category < self.n_types:
                raise ValueError(f"type index {category} out of range 0..{self.n_types - 1}")
            return int(category)
        if category not in self.categories:
            raise ValueError(f"unknown category {category!r}; categories: {list(self.categories)}")
        return self.categories.index(category)

    def of_type(self, category) -> np.ndarray:
        """Coordinates of the points of one category (name or index)."""
        return self.points[self.marks == self.type_index(category)]

    def unmark(self) -> "PointPattern":
        """The same points as an unmarked (single-type) pattern."""
        return PointPattern(self.points, self.window)

    def __eq__(self, other) -> bool:
        if not isinstance(other, PointPattern):
            return NotImplemented
        return (
            self.window == other.window
            and self.categories == other.categories
            and np.array_equal(self.points, other.points)
            and np.array_equal(self.marks, other.marks)
        )

    __hash__ = None

    def __repr__(self) -> str:
        counts = ", ".join(f"{name}: {count}" for name, count in zip(self.categories, self.counts))
        return f"PointPattern(n={self.n}, {{{counts}}}, {self.window!r})"


def _reject_coincident(points: np.ndarray) -> None:
    if len(points) < 2:
        return
    order = np.lexsort((points[:, 1], points[:, 0]))
    ordered = points[order]
    same = np.all(ordered[1:] == ordered[:-1], axis=1)
    if same.any():
        raise ValueError(
            f"{same.sum()} coincident point(s), e.g. at {ordered[np.argmax(same)].tolist()}: "
            "a point pattern must not repeat a location"
        )


def _checked_marks(marks, categories, n: int) -> tuple[np.ndarray, tuple]:
    if marks is None:
        marks = np.zeros(n, dtype=np.int64)
    else:
        raw = np.asarray(marks)
        if raw.shape != (n,):
            raise ValueError(f"marks must have shape ({n},) like the points, got {raw.shape}")
        if n and not np.issubdtype(raw.dtype, np.integer):
            if not np.issubdtype(raw.dtype, np.floating) or not np.all(raw == np.round(raw)):
                raise ValueError("marks must be integer category indices (map names with `categories`)")
        marks = raw.astype(np.int64)
    if categories is None:
        n_types = int(marks.max()) + 1 if n else 1
        categories = ("points",) if n_types == 1 else tuple(str(i) for i in range(n_types))
    categories = tuple(str(name) for name in categories)
    if not categories or len(set(categories)) != len(categories):
        raise ValueError(f"categories must be non-empty and distinct, got {categories}")
    if n and (marks.min() < 0 or marks.max() >= len(categories)):
        raise ValueError(f"marks must lie in 0..{len(categories) - 1} (one per category), got {marks.min()}..{marks.max()}")
    marks.setflags(write=False)
    return marks, categories
