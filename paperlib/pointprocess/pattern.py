"""Marked point patterns (spatstat's ``ppp``).

A :class:`PointPattern` is what Hurtut 2009 (section 3.1) calls an arrangement: element
positions ``x_i`` with appearance-category labels ``m_i`` observed in a window. Marks are
stored as integers ``0 .. n_types - 1`` indexing ``categories``; they may be given as such or
as names (strings, or a pandas Categorical: spatstat's factor marks). An unmarked pattern has
one category.

Duplicated points. As spatstat's ``ppp``, a pattern may repeat a location (real data do:
spatstat's ``lansing`` has a duplicated tree); it is accepted with a warning, and
:meth:`PointPattern.duplicated` / :meth:`PointPattern.unique` find and drop the repeats
(spatstat's ``duplicated.ppp``, ``unique.ppp``). Summary functions count the pairs at distance
0 as spatstat does; only what a hard core forbids refuses them (hard-core fitting, a start
pattern for simulation), through :func:`require_distinct`.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from paperlib._checks import check_choice
from paperlib.geometry import as_points

from .window import Window

__all__ = ["PointPattern", "require_distinct"]

DUPLICATE_RULES = ("spatstat", "unmark")


@dataclass(frozen=True, eq=False)
class PointPattern:
    """Points with integer marks in a window.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        Coordinates; finite, inside ``window`` (boundary included). Repeated locations are
        accepted with a ``UserWarning`` (spatstat: "data contain duplicated points").
    window : Window
    marks : array_like, shape (n,), optional
        Category of each point: an index ``0 <= mark < len(categories)``, or a name (strings,
        or a pandas Categorical, as spatstat's factor marks). Default: all 0.
    categories : sequence of str, optional
        Category names. Default: with integer marks ``("0", ..., str(max mark))``, or
        ``("points",)`` for an unmarked pattern; with a Categorical, its categories in order;
        with names, the sorted distinct names (R's ``factor``). Given with names, it fixes
        their order and must contain every name.

    Raises
    ------
    ValueError
        For NaN/infinite coordinates, points outside the window, marks of the wrong length,
        out of range or not among the categories, or duplicate category names.

    References
    ----------
    Baddeley, Rubak and Turner (2015), chapter 3 (spatstat's ``ppp``, ``duplicated.ppp``).
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
        marks, categories = _checked_marks(self.marks, self.categories, len(points))
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "marks", marks)
        object.__setattr__(self, "categories", categories)
        _warn_if_duplicated(self)

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

    def type_index(self, category, name: str = "category") -> int:
        """Index of a category given by name or index (``name``: the caller's parameter, for messages).

        Parameters
        ----------
        category : int or str
            A type index in ``0 .. n_types - 1``, or a category name (an entry of ``categories``).
        name : str, default "category"
            The caller's name for ``category``, that error messages start with.

        Returns
        -------
        int
            The type index.

        Raises
        ------
        ValueError
            For an index out of range or an unknown name.
        """
        if isinstance(category, (int, np.integer)) and not isinstance(category, bool):
            if not 0 <= category < self.n_types:
                raise ValueError(f"{name}: type index {category} out of range 0..{self.n_types - 1}")
            return int(category)
        if not isinstance(category, str) or category not in self.categories:
            raise ValueError(f"{name}: unknown category {category!r:.80}; categories: {list(self.categories)}")
        return self.categories.index(category)

    def of_type(self, category) -> np.ndarray:
        """Coordinates of the points of one category (name or index).

        Parameters
        ----------
        category : int or str
            A type index or a category name (see :meth:`type_index`).

        Returns
        -------
        ndarray of float64, shape (k, 2)
            The coordinates of the points of that category, in the pattern's order.
        """
        return self.points[self.marks == self.type_index(category)]

    def unmark(self) -> "PointPattern":
        """The same points as an unmarked (single-type) pattern.

        Returns
        -------
        PointPattern
            The points in the same window, all of a single type.
        """
        return PointPattern(self.points, self.window)

    def duplicated(self, rule: str = "spatstat") -> np.ndarray:
        """Whether each point repeats an earlier point (spatstat's ``duplicated.ppp``).

        Parameters
        ----------
        rule : {"spatstat", "unmark"}
            ``"spatstat"``: same location and same mark (spatstat's default); ``"unmark"``:
            same location, whatever the marks.

        Returns
        -------
        ndarray of bool, shape (n,)
            False for the first point at each location (and mark), True for its repeats.
        """
        return self._first_copies(rule) != np.arange(self.n)

    def unique(self, rule: str = "spatstat") -> "PointPattern":
        """The pattern without its repeated points (spatstat's ``unique.ppp``); see :meth:`duplicated`.

        Parameters
        ----------
        rule : {"spatstat", "unmark"}
            ``"spatstat"``: a repeat has the same location and the same mark; ``"unmark"``: the
            same location, whatever the marks.

        Returns
        -------
        PointPattern
            The first point at each location (and mark), in the pattern's order, with their marks,
            the same window and categories.
        """
        keep = ~self.duplicated(rule)
        return PointPattern(self.points[keep], self.window, self.marks[keep], self.categories)

    def _first_copies(self, rule: str) -> np.ndarray:
        """For each point, the index of the first point at its location (and with its mark)."""
        check_choice(rule, DUPLICATE_RULES, "rule")
        if self.n == 0:
            return np.zeros(0, dtype=np.int64)
        keys = self.points if rule == "unmark" else np.column_stack([self.points, self.marks])
        order = np.lexsort(keys.T[::-1])  # stable: equal keys keep their order, the first copy leads
        ordered = keys[order]
        leads = np.concatenate([[True], np.any(ordered[1:] != ordered[:-1], axis=1)])
        first = np.empty(self.n, dtype=np.int64)
        first[order] = order[np.maximum.accumulate(np.where(leads, np.arange(self.n), 0))]
        return first

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


def _repeated_locations(pattern: PointPattern) -> tuple[np.ndarray, np.ndarray]:
    """Indices of the points repeating an earlier location, and each point's first copy."""
    first = pattern._first_copies("unmark")
    return np.flatnonzero(first != np.arange(pattern.n)), first


def _warn_if_duplicated(pattern: PointPattern) -> None:
    """spatstat's "data contain duplicated points", naming how many and the first repeat."""
    repeats, first = _repeated_locations(pattern)
    if repeats.size:
        i = int(repeats[0])
        warnings.warn(
            f"data contain duplicated points: {repeats.size} point(s) repeat the location of an earlier point, "
            f"the first is point {i} at {pattern.points[i].tolist()} (a copy of point {int(first[i])}); "
            "PointPattern.unique(rule='unmark') drops them", UserWarning, stacklevel=4)


def require_distinct(pattern: PointPattern, what: str) -> None:
    """A ValueError naming the first repeated location, for what a hard core forbids.

    Parameters
    ----------
    pattern : PointPattern
    what : str
        What needs distinct points (for the message), e.g. ``"a hard-core fit"``.
    """
    repeats, first = _repeated_locations(pattern)
    if repeats.size:
        i = int(repeats[0])
        raise ValueError(
            f"point {i} at {pattern.points[i].tolist()} repeats the location of point {int(first[i])} "
            f"({repeats.size} repeated point(s) in all): {what} needs distinct locations, since a hard core "
            "forbids coincident points; drop the repeats with pattern.unique(rule='unmark')")


def _checked_marks(marks, categories, n: int) -> tuple[np.ndarray, tuple]:
    if _is_categorical(marks):
        marks, categories = _categorical_marks(marks, categories)
    elif marks is not None and n and _are_names(np.asarray(marks)):
        marks, categories = _named_marks(np.asarray(marks), categories)
    if marks is None:
        marks = np.zeros(n, dtype=np.int64)
    else:
        raw = np.asarray(marks)
        if raw.shape != (n,):
            raise ValueError(f"marks must have shape ({n},) like the points, got {raw.shape}")
        if n and not np.issubdtype(raw.dtype, np.integer):
            if not np.issubdtype(raw.dtype, np.floating) or not np.all(raw == np.round(raw)):
                raise ValueError("marks must be integer category indices or category names (strings or a "
                                 f"pandas Categorical), got dtype {raw.dtype}")
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


def _is_categorical(marks) -> bool:
    import pandas as pd

    return isinstance(marks, pd.Categorical) or (isinstance(marks, pd.Series)
                                                 and isinstance(marks.dtype, pd.CategoricalDtype))


def _are_names(raw: np.ndarray) -> bool:
    return raw.dtype.kind in "US" or (raw.dtype == object and all(isinstance(m, str) for m in raw.ravel()))


def _categorical_marks(marks, categories):
    """Codes of a pandas Categorical, its categories in order (spatstat's factor levels)."""
    import pandas as pd

    marks = pd.Categorical(marks)
    if pd.isna(marks).any():
        raise ValueError(f"marks must name a category for every point; missing at point {int(np.argmax(pd.isna(marks)))}")
    if categories is None:
        return marks.codes.astype(np.int64), tuple(str(c) for c in marks.categories)
    return _named_marks(np.asarray(marks.astype(str)), categories)


def _named_marks(names: np.ndarray, categories):
    """Indices of mark names among ``categories`` (default: the sorted distinct names)."""
    names = names.astype(str)
    categories = tuple(sorted(set(names.tolist()))) if categories is None else tuple(str(c) for c in categories)
    index = {name: k for k, name in enumerate(categories)}
    unknown = sorted(set(names.tolist()) - set(index))
    if unknown:
        raise ValueError(f"mark name(s) {unknown} are not among the categories {list(categories)}")
    return np.array([index[name] for name in names.tolist()], dtype=np.int64), categories
