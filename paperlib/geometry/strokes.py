"""Strokes and elements: the vector primitives every method shares.

A *stroke* is one pen trace, a polyline with a width and a colour; an *element* is a
group of strokes that a method treats as one object (a Hershey glyph, a hatch made of
several sketchy lines, a flower drawn with five strokes). Hurtut 2009 (section 2) calls
these "elements", Barla 2006 (section 2.1) groups strokes into "elements" by clustering.

Both types are immutable: their coordinate arrays are read-only copies, so an element
can be shared between a reference arrangement and the synthesised one without defensive
copies.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from paperlib._checks import integer_at_least, label, point_array, positive_number

__all__ = ["Element", "StackedStrokes", "Stroke", "as_elements", "as_points", "stack_strokes"]


def as_points(points, *, name: str = "points", min_points: int = 1) -> np.ndarray:
    """Validate and return a read-only float64 ``(n, 2)`` copy of ``points``.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        Point coordinates (finite numbers).
    name : str, default "points"
        How error messages name the argument.
    min_points : int, default 1
        The fewest points (rows) accepted.

    Returns
    -------
    ndarray of float64, shape (n, 2)
        A read-only copy of ``points``.

    Raises
    ------
    ValueError
        If the array is not ``(n, 2)``, has fewer than ``min_points`` rows, or holds
        NaN or infinite coordinates.
    """
    name = label(name)
    min_points = integer_at_least(min_points, "min_points", 0)
    array = np.array(point_array(points, name, min_points=min_points))
    array.setflags(write=False)
    return array


@dataclass(frozen=True)
class Stroke:
    """One pen trace: a polyline of ``(n, 2)`` points, a width and a colour.

    Parameters
    ----------
    points : array_like, shape (n, 2)
        Vertices in drawing order (n >= 1; a single point is a dot).
    width : float
        Pen width in the same units as the points (> 0).
    color : str
        Any SVG colour string, e.g. ``"#000000"`` or ``"black"``.
    """

    points: np.ndarray
    width: float = 1.0
    color: str = "#000000"

    def __post_init__(self):
        object.__setattr__(self, "points", as_points(self.points, name="stroke points"))
        object.__setattr__(self, "width", positive_number(self.width, "width"))
        if not isinstance(self.color, str) or not self.color:
            raise ValueError(f"stroke color must be a non-empty SVG colour string, got {self.color!r}")

    def __len__(self) -> int:
        return self.points.shape[0]

    def __eq__(self, other):
        if not isinstance(other, Stroke):
            return NotImplemented
        return (
            self.width == other.width
            and self.color == other.color
            and np.array_equal(self.points, other.points)
        )

    __hash__ = None

    def length(self) -> float:
        """Arc length of the polyline.

        Returns
        -------
        float
            Sum of the lengths of its segments, in the units of the coordinates.
        """
        return float(np.hypot(*np.diff(self.points, axis=0).T).sum())

    def transformed(self, matrix, offset=(0.0, 0.0)) -> "Stroke":
        """Return the stroke mapped by ``x -> matrix @ x + offset``.

        The width is scaled by sqrt(|det matrix|), the factor by which the map scales
        lengths on average, so a uniformly scaled glyph keeps its look.

        Parameters
        ----------
        matrix : array_like, shape (2, 2)
            Linear part of the map (finite, non-singular).
        offset : array_like, shape (2,), default (0, 0)
            Translation applied after ``matrix`` (finite).

        Returns
        -------
        Stroke
            A new stroke with mapped points, width scaled by sqrt(|det matrix|) and the same colour.
        """
        matrix = np.asarray(matrix, dtype=np.float64)
        if matrix.shape != (2, 2) or not np.isfinite(matrix).all():
            raise ValueError(f"matrix must be a finite 2x2 array, got shape {matrix.shape}")
        offset = as_points(np.reshape(offset, (1, 2)), name="offset")[0]
        scale = np.sqrt(abs(np.linalg.det(matrix)))
        if scale == 0:
            raise ValueError("matrix is singular: the stroke would collapse")
        return Stroke(self.points @ matrix.T + offset, self.width * scale, self.color)


@dataclass(frozen=True)
class Element:
    """A group of strokes treated as one object (Hurtut 2009, section 2).

    Parameters
    ----------
    strokes : sequence of Stroke
        At least one stroke.
    name : str
        Optional label (e.g. the glyph it came from); not used by any computation.
    """

    strokes: tuple = field(default_factory=tuple)
    name: str = ""

    def __post_init__(self):
        if isinstance(self.strokes, (str, bytes)) or not hasattr(self.strokes, "__iter__"):
            raise TypeError(f"strokes must be a sequence of Stroke, got {type(self.strokes).__name__}")
        strokes = tuple(self.strokes)
        if not strokes:
            raise ValueError("strokes must hold at least one stroke (an element needs one), got an empty sequence")
        for i, stroke in enumerate(strokes):
            if not isinstance(stroke, Stroke):
                raise TypeError(f"strokes[{i}] (element stroke {i}) is a {type(stroke).__name__}, expected Stroke")
        object.__setattr__(self, "strokes", strokes)

    def __len__(self) -> int:
        return len(self.strokes)

    def __iter__(self):
        return iter(self.strokes)

    @property
    def points(self) -> np.ndarray:
        """All vertices of all strokes, stacked into one ``(n, 2)`` array."""
        return np.vstack([stroke.points for stroke in self.strokes])

    def bounds(self) -> tuple[float, float, float, float]:
        """Axis-aligned bounding box ``(xmin, ymin, xmax, ymax)`` of the vertices.

        Returns
        -------
        tuple of float
            ``(xmin, ymin, xmax, ymax)`` over the vertices of all its strokes.
        """
        points = self.points
        (xmin, ymin), (xmax, ymax) = points.min(axis=0), points.max(axis=0)
        return float(xmin), float(ymin), float(xmax), float(ymax)

    def transformed(self, matrix, offset=(0.0, 0.0)) -> "Element":
        """Return the element with every stroke mapped by ``x -> matrix @ x + offset``.

        Parameters
        ----------
        matrix : array_like, shape (2, 2)
            Linear part of the map (finite, non-singular).
        offset : array_like, shape (2,), default (0, 0)
            Translation applied after ``matrix``.

        Returns
        -------
        Element
            A new element with the same name; each stroke mapped as :meth:`Stroke.transformed`
            does (widths scaled by sqrt(|det matrix|)).
        """
        return Element(tuple(s.transformed(matrix, offset) for s in self.strokes), self.name)


def as_elements(elements, *, name: str = "elements", min_count: int = 0) -> list:
    """Validate a sequence of :class:`Element` and return it as a list.

    The one check behind every function that takes a drawing (SVG output, stacking,
    categorization, synthesis), so that all of them refuse bad input alike.

    Parameters
    ----------
    elements : iterable of Element
        The drawing; a single Element or Stroke is refused.
    name : str, default "elements"
        How error messages name the argument.
    min_count : int, default 0
        The fewest elements accepted.

    Returns
    -------
    list of Element
        The elements, in order.

    Raises
    ------
    TypeError
        If ``elements`` is a single Element or Stroke, is not iterable, or holds
        something other than Elements (the message names the first offending item).
    ValueError
        If there are fewer than ``min_count`` elements.
    """
    name = label(name)
    min_count = integer_at_least(min_count, "min_count", 0)
    if isinstance(elements, (Element, Stroke)):
        raise TypeError(f"{name} must be a sequence of Element (a list of elements), got one "
                        f"{type(elements).__name__}: wrap it in a list")
    try:
        elements = list(elements)
    except TypeError:
        raise TypeError(f"{name} must be a sequence of Element (a list of elements), got "
                        f"{type(elements).__name__}") from None
    for index, element in enumerate(elements):
        if not isinstance(element, Element):
            raise TypeError(f"{name}[{index}] is a {type(element).__name__}, expected paperlib.geometry.Element "
                            f"({name} must hold only elements)")
    if len(elements) < min_count:
        plural = "" if min_count == 1 else "s"
        raise ValueError(f"{name} needs at least {min_count} element{plural}, got {len(elements)} "
                         f"(min_count={min_count})")
    return elements


# --------------------------------------------------------------------------- many elements as flat arrays


@dataclass(frozen=True, eq=False)
class StackedStrokes:
    """The strokes of many elements as flat arrays, for vectorised geometry.

    Built by :func:`stack_strokes`. Consecutive repeated vertices are dropped, so every segment
    has positive length; a stroke of zero length keeps a single vertex and has no segment.

    Parameters
    ----------
    vertices : ndarray, shape (n, 2)
        All vertices, stroke after stroke, element after element.
    stroke_offsets : ndarray, shape (k + 1,)
        Stroke ``i`` owns ``vertices[stroke_offsets[i]:stroke_offsets[i + 1]]``.
    stroke_element : ndarray, shape (k,)
        Index of the element each stroke belongs to (non-decreasing).
    stroke_width : ndarray, shape (k,)
        Pen width of each stroke.
    n_elements : int
    """

    vertices: np.ndarray
    stroke_offsets: np.ndarray
    stroke_element: np.ndarray
    stroke_width: np.ndarray
    n_elements: int

    @cached_property
    def vertex_stroke(self) -> np.ndarray:
        """Stroke index of every vertex, shape ``(n,)``."""
        return np.repeat(np.arange(self.stroke_element.size), np.diff(self.stroke_offsets))

    @cached_property
    def vertex_element(self) -> np.ndarray:
        """Element index of every vertex, shape ``(n,)``."""
        return self.stroke_element[self.vertex_stroke]

    @cached_property
    def element_lengths(self) -> np.ndarray:
        """Total length of every element's strokes (its skeleton, pen width left out), shape ``(n_elements,)``."""
        same_stroke = self.vertex_stroke[1:] == self.vertex_stroke[:-1]
        segments = np.hypot(*np.diff(self.vertices, axis=0).T)[same_stroke]
        return np.bincount(self.vertex_element[1:][same_stroke], weights=segments, minlength=self.n_elements)

    @property
    def element_vertex_offsets(self) -> np.ndarray:
        """Element ``e`` owns vertices ``[offsets[e], offsets[e + 1])``, shape ``(n_elements + 1,)``."""
        counts = np.bincount(self.vertex_element, minlength=self.n_elements)
        return np.concatenate([[0], np.cumsum(counts)])

    @cached_property
    def segment_starts(self) -> np.ndarray:
        """Index of the first vertex of every segment (the next vertex is its end)."""
        last_of_stroke = np.zeros(self.vertices.shape[0], dtype=bool)
        last_of_stroke[self.stroke_offsets[1:] - 1] = True
        return np.flatnonzero(~last_of_stroke)


def stack_strokes(elements) -> StackedStrokes:
    """Stack the strokes of ``elements`` into flat arrays (see :class:`StackedStrokes`).

    Parameters
    ----------
    elements : sequence of Element
        At least one element.

    Returns
    -------
    StackedStrokes
        The vertices, stroke offsets, stroke elements and widths as flat arrays.

    Raises
    ------
    TypeError
        If an item is not an :class:`~paperlib.geometry.Element`.
    ValueError
        If there are no elements.
    """
    elements = as_elements(elements, min_count=1)
    strokes, stroke_element = [], []
    for index, element in enumerate(elements):
        strokes.extend(element.strokes)
        stroke_element.extend([index] * len(element.strokes))
    counts = np.array([len(stroke) for stroke in strokes])
    vertices = np.concatenate([stroke.points for stroke in strokes])
    vertex_stroke = np.repeat(np.arange(len(strokes)), counts)
    repeated = np.zeros(vertices.shape[0], dtype=bool)
    repeated[1:] = (vertex_stroke[1:] == vertex_stroke[:-1]) & np.all(vertices[1:] == vertices[:-1], axis=1)
    kept_counts = np.bincount(vertex_stroke[~repeated], minlength=len(strokes))
    return StackedStrokes(
        vertices=vertices[~repeated],
        stroke_offsets=np.concatenate([[0], np.cumsum(kept_counts)]),
        stroke_element=np.array(stroke_element),
        stroke_width=np.array([stroke.width for stroke in strokes]),
        n_elements=len(elements),
    )
