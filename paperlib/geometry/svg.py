"""SVG in and out: elements of strokes from and to SVG documents.

Parsing, styles, units and transforms are :mod:`svgelements`' work. Written here, because
no maintained library does them: the flattening of curves with a guaranteed tolerance,
the grouping of shapes into elements, and the writer.

Coordinates
-----------
Paperlib's elements are y-up (Hershey glyphs are flipped to y up); SVG is y-down. With
``y_up=True`` (the default) the two frames are mirror images in the x axis, ``(x, y) <->
(x, -y)``: a negation, exact in floating point, so :func:`read_svg` of :func:`write_svg`
gives back the same coordinates bit for bit. The coordinates are those of the root
``<svg>``'s user space (the numbers of its ``viewBox``), not of the viewport: the root's
``width``/``height``/``viewBox`` mapping only says how large to display the drawing, so it
is not applied. Every transform inside the document is applied, and lengths with units
(``"2mm"``) are resolved to user units at 96 per inch, as SVG specifies.

Grouping (which shapes form one element)
----------------------------------------
* A ``<g>`` (or a ``<use>``, or a nested ``<svg>``) whose parent is a *layer* is one
  element; every shape inside it, at any depth, belongs to it.
* A shape whose parent is a layer is an element of its own, so a document without
  groups gives one element per shape.
* Layers are the root ``<svg>``, Inkscape layers (``inkscape:groupmode="layer"``), and a
  *wrapper*: a ``<g>`` that is the only child with shapes of a layer and that holds
  another ``<g>`` or ``<use>`` (a group around a grouped drawing, e.g. to apply one
  transform to all of it, as unmarked layers of other editors are). A lone ``<g>`` of
  plain shapes is one element, so a single written element reads back as one.
* An element is named by its ``inkscape:label``, else its ``id``, else ``""``.

Shapes, curves and styles
-------------------------
Paths, lines, polylines, polygons, rectangles (rounded too), circles and ellipses are
read; text and images are not. Each subpath becomes one :class:`Stroke`; closed
subpaths (``Z``, polygons, rectangles, circles, ellipses) end with their first point
repeated, as Hershey's closed strokes do. Curves are flattened so that the polyline lies
within ``tolerance`` user units of the true curve (Hausdorff distance): a curve piece
``B(t)`` on a parameter interval of length ``L`` with ``|B''| <= M`` is sampled at ``n =
ceil(L sqrt(M / (8 tolerance)))`` equal parameter steps ``h``; the chord interpolant
then deviates from the curve by at most ``h**2 M / 8 <= tolerance`` at every parameter,
the classical bound for linear interpolation [2]_, which holds for plane curves too since
the error is the integral of ``B''`` against a positive kernel of mass
``(t - t0)(t1 - t) / 2``. ``M`` is the maximum of ``|B''|``: ``2 |P0 - 2 P1 + P2|`` for a
quadratic Bezier,
``6 max(|P0 - 2 P1 + P2|, |P1 - 2 P2 + P3|)`` for a cubic (``B''`` is linear in ``t``,
so its norm peaks at an end), the larger semi-axis for an elliptical arc in its angle
parameter (``L`` = the swept angle). Curves are flattened in their own coordinates with
the tolerance divided by the largest stretch (singular value) of their transform, so the
guarantee holds after any affine transform, skews included.

The colour of a stroke is the shape's ``stroke`` paint, or, for a shape painted only by
``fill`` (or whose stroke width is 0), its ``fill`` paint: the outline of a filled shape
is what a stroke method can use. Colours come back as ``"#rrggbb"`` (``"#rrggbbaa"`` when
translucent); svgelements reads unknown paints, gradients included, as black. Shapes
painted by neither are invisible and skipped. The width is ``stroke-width`` scaled by
``sqrt(|det|)`` of the transform (as :meth:`Stroke.transformed` does), and 1 if that comes
out 0. Degenerate subpaths (``M x y Z``, zero length) are skipped with one warning: SVG
draws them as a dot at most, and a stroke method cannot use them. A bare moveto draws
nothing and is dropped silently.

Writing
-------
:func:`write_svg` writes each element as a ``<g>`` of ``<polyline>`` s (a stroke of one
point as a zero-length polyline, which SVG draws as a dot with the round caps used here),
with the shortest decimal form that reads back to the same double, and replaces the
file atomically. A ``background`` is a ``<rect>`` with id ``paperlib-background``, which
:func:`read_svg` ignores.

References
----------
.. [1] W3C, "Scalable Vector Graphics (SVG) 1.1 (Second Edition)", 2011: section 5
   (document structure: ``g``, ``use``), 7 (coordinate systems, ``viewBox``), 8 (paths),
   9 (basic shapes), 11 (painting), appendix F.6 (elliptical arcs).
.. [2] C. de Boor, "A Practical Guide to Splines", revised ed., Springer, 2001,
   chapter III (broken line interpolation: error at most ``|h|**2 |g''| / 8``).
.. [3] T. Hurtut et al., "Appearance-guided Synthesis of Element Arrangements by
   Example", NPAR 2009, section 2 (vector elements made of strokes).
"""

from __future__ import annotations

import io
import math
import os
import re
import warnings
import xml.etree.ElementTree as ET
import zlib
from xml.parsers import expat
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np
import svgelements

from .._atomic import atomic_path
from .._checks import budget, check_budget
from .strokes import Element, Stroke, as_elements

__all__ = ["DEFAULT_TOLERANCE", "MAX_DOCUMENT_BYTES", "MAX_FLATTENED_POINTS", "read_svg", "svg_string", "write_svg"]

#: Default flattening tolerance, in user units: a tenth of a CSS pixel in px drawings.
DEFAULT_TOLERANCE = 0.1
#: Default budget of :func:`read_svg`: the most points all flattened strokes of one document may hold
#: (5 million points, 80 MB of coordinates). Raise it with the ``max_points`` keyword.
MAX_FLATTENED_POINTS = 5_000_000
#: Default budget of :func:`read_svg`: the largest document, in bytes, after ``.svgz`` decompression
#: (64 MiB). Raise it with the ``max_bytes`` keyword.
MAX_DOCUMENT_BYTES = 64 * 2**20

_SVG_NAMESPACE = "http://www.w3.org/2000/svg"
_INKSCAPE_NAMESPACE = "http://www.inkscape.org/namespaces/inkscape"
_INKSCAPE_LABEL = f"{{{_INKSCAPE_NAMESPACE}}}label"
_INKSCAPE_GROUPMODE = f"{{{_INKSCAPE_NAMESPACE}}}groupmode"
_BACKGROUND_ID = "paperlib-background"
_CONTAINERS = (svgelements.Group, svgelements.Use)  # svgelements.SVG is a Group
_FALLBACK_WIDTH = 1.0
# A flattened curve of more points than this is a mistake (tolerance far too small).
_MAX_POINTS_PER_SEGMENT = 1_000_000
# A closing point this close (relative to the coordinates) to the last point is the
# same point up to rounding (a circle's last arc ends at cos/sin(2 pi)): replace, not add.
_CLOSING_SNAP = 1e-12
_NOT_XML_CHARACTER = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")
_CSS_LENGTH = re.compile(r"^\s*(\d*\.?\d+(?:[eE][-+]?\d+)?)\s*(?:px|mm|cm|in|pt|pc|em|ex|%)?\s*$")


# --------------------------------------------------------------------------- reading


def read_svg(path_or_text, *, tolerance: float = DEFAULT_TOLERANCE, y_up: bool = True,
             max_points: int = MAX_FLATTENED_POINTS, max_bytes: int = MAX_DOCUMENT_BYTES) -> list[Element]:
    """Read the drawable shapes of an SVG document as elements of polyline strokes.

    Parameters
    ----------
    path_or_text : str, bytes or os.PathLike
        A file name (``.svg``, or gzip-compressed ``.svgz``), or the SVG text itself (a
        ``str`` that starts with ``<``, or ``bytes``).
    tolerance : float
        Largest distance, in user units, between a flattened curve and the true curve
        (> 0). Straight segments are exact whatever the tolerance.
    y_up : bool
        Return y-up coordinates, ``(x, -y_svg)`` (the frame of paperlib's elements);
        ``False`` keeps SVG's y-down ``(x, y_svg)``.
    max_points : int
        Budget: the most points the flattened strokes of the whole document may hold
        (default :data:`MAX_FLATTENED_POINTS`); a larger document raises ValueError before
        flattening further.
    max_bytes : int
        Budget: the largest document, in bytes, read from a file or decompressed from
        ``.svgz`` (default :data:`MAX_DOCUMENT_BYTES`); decompression stops at the limit.

    Returns
    -------
    list of Element
        In document order, grouped as the module docstring describes, in the root's
        user units.

    Raises
    ------
    FileNotFoundError
        If ``path_or_text`` names no file.
    ValueError
        If the document is not well-formed XML, is not SVG, declares entities, an internal DTD subset or a non-SVG DOCTYPE
        (rejected: entity expansion is a denial-of-service vector and SVG needs neither),
        has path data, attributes or arithmetic svgelements cannot read, exceeds
        ``max_points`` or ``max_bytes``, or has no drawable element; if ``tolerance`` is not
        a positive number.

    Warns
    -----
    UserWarning
        When degenerate subpaths (a lone point, zero length) are skipped.

    References
    ----------
    .. [1] W3C, "Scalable Vector Graphics (SVG) 1.1 (Second Edition)", 2011, sections
       5, 7, 8, 9, 11.
    .. [2] T. Hurtut et al., "Appearance-guided Synthesis of Element Arrangements by
       Example", NPAR 2009, section 2.
    """
    return _read_elements(path_or_text, "path_or_text", tolerance=tolerance, y_up=y_up, max_points=max_points,
                          max_bytes=max_bytes)


def _read_elements(source, name: str, *, tolerance, y_up: bool, max_points, max_bytes) -> list[Element]:
    """:func:`read_svg` for a public function whose SVG parameter is called ``name``: every rejection of the
    document (unreadable, malformed, nothing drawable, over a budget) is a ValueError starting ``"{name}: "``.
    Call it directly from a public function (the warning about skipped subpaths names that function's caller)."""
    tolerance = _check_tolerance(tolerance)
    points = _PointBudget(budget(max_points, "max_points"))
    max_bytes = budget(max_bytes, "max_bytes")
    try:
        document = _parse_svg(_read_source(source, max_bytes, name))
        try:
            elements, degenerate = _document_elements(document, tolerance, y_up, points)
        except (ArithmeticError, AttributeError, IndexError, TypeError, KeyError, RecursionError) as exc:
            # svgelements and float arithmetic fail on hostile data with assorted types: report it as bad SVG
            raise ValueError(f"malformed SVG: cannot flatten its shapes ({type(exc).__name__}: {exc})") from None
        if degenerate:
            _warn_skipped(degenerate, stacklevel=4)
        if not elements:
            raise ValueError(
                "the SVG has no drawable element: no path, line, polyline, polygon, rect, circle or ellipse "
                "with a visible stroke or fill and a non-zero length"
                + (f" ({len(degenerate)} degenerate subpath(s) skipped)" if degenerate else "")
            )
    except ValueError as err:
        raise ValueError(f"{name}: {err}") from err
    return elements


class _PointBudget:
    """The flattened points left to a document (``max_points`` of :func:`read_svg`)."""

    def __init__(self, limit: int):
        self.limit, self.used = limit, 0

    def take(self, count: int) -> None:
        self.used += count
        check_budget(self.used, self.limit, "max_points", "flattened points (so far)")


def _document_elements(document, tolerance: float, y_up: bool, points: _PointBudget):
    """The elements of a parsed document and the names of those with degenerate subpaths skipped."""
    elements, degenerate = [], []
    for node in _element_nodes(document):
        name = _own_attribute(node, _INKSCAPE_LABEL) or _own_attribute(node, "id") or ""
        strokes, skipped = _node_strokes(node, tolerance, y_up, points)
        degenerate += [name] * skipped
        if strokes:
            elements.append(Element(tuple(strokes), name))
    return elements, degenerate


def _warn_skipped(element_names: list[str], stacklevel: int) -> None:
    """One warning for all skipped degenerate subpaths, naming up to five elements."""
    named = sorted({repr(name) for name in element_names if name})
    where = f" in element(s) {', '.join(named[:5])}{' ...' if len(named) > 5 else ''}" if named else ""
    warnings.warn(
        f"read_svg skipped {len(element_names)} degenerate subpath(s) (a lone point or zero length){where}",
        UserWarning,
        stacklevel=stacklevel,
    )


def _positive(value) -> float | None:
    """``value`` as a float if it is a finite positive real number (not a bool), else None."""
    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool):
        number = float(value)
        if math.isfinite(number) and number > 0:
            return number
    return None


def _check_tolerance(tolerance) -> float:
    value = _positive(tolerance)
    if value is None:
        raise ValueError(f"tolerance must be a positive number of user units, got {tolerance!r}")
    return value


def _read_source(path_or_text, max_bytes: int = MAX_DOCUMENT_BYTES, name: str = "path_or_text") -> str | bytes:
    """The document's text: ``str`` text as given, file contents as bytes (so that the
    XML parser honours their encoding declaration), gzip (.svgz) decompressed; at most
    ``max_bytes`` either way. ``name`` is the caller's parameter, for the TypeError (the caller
    prefixes its ValueErrors with it)."""
    if isinstance(path_or_text, str) and not path_or_text.strip():
        raise ValueError("must be SVG text or a file name, got an empty string")
    if isinstance(path_or_text, str) and path_or_text.lstrip("\ufeff \t\r\n").startswith("<"):
        return path_or_text.lstrip("\ufeff")
    if isinstance(path_or_text, (bytes, bytearray)):
        data = bytes(path_or_text)
    elif isinstance(path_or_text, (str, os.PathLike)):
        path = Path(path_or_text)
        try:
            is_file = path.is_file()
        except (OSError, ValueError):  # a name too long or holding a NUL byte names no file
            is_file = False
        if not is_file:
            raise FileNotFoundError(f"no SVG file at {str(path)[:200]!r}")
        check_budget(path.stat().st_size, max_bytes, "max_bytes", "bytes of SVG file")
        data = path.read_bytes()
    else:
        raise TypeError(f"{name} must be an SVG file name or SVG text, got {type(path_or_text).__name__}")
    check_budget(len(data), max_bytes, "max_bytes", "bytes of SVG")
    if data[:2] == b"\x1f\x8b":
        data = _gunzip(data, max_bytes)
    return data


def _gunzip(data: bytes, max_bytes: int) -> bytes:
    """Decompress a gzip stream (members concatenated), stopping with a ValueError past ``max_bytes``."""
    out, rest = [], data
    size = 0
    try:
        while rest:
            stream = zlib.decompressobj(wbits=16 + zlib.MAX_WBITS)
            while rest:
                chunk = stream.decompress(rest, max_bytes + 1 - size)
                size += len(chunk)
                out.append(chunk)
                check_budget(size, max_bytes, "max_bytes", "bytes of decompressed SVGZ (at least)")
                rest = stream.unconsumed_tail
                if stream.eof:
                    break
            if not stream.eof:
                raise ValueError("malformed SVGZ: the gzip stream is truncated")
            rest = stream.unused_data.lstrip(b"\x00")
    except zlib.error as exc:
        raise ValueError(f"malformed SVGZ: the gzip stream is corrupt ({exc})") from None
    return b"".join(out)


def _reject_declarations(text: str | bytes) -> None:
    """ValueError for a document that declares entities or an internal DTD subset, before the tree
    parser sees it.

    SVG needs neither, and entity expansion ("billion laughs", external entities) is a classic
    denial of service; expat's own amplification limits are not relied on. A plain DOCTYPE that
    only names a W3C SVG DTD (``<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" "...">``, written
    by Inkscape, Illustrator and matplotlib) declares nothing and is accepted (no parser here
    fetches the DTD); a DOCTYPE pointing anywhere else is refused.
    """
    def refuse(*_args):
        raise ValueError("malformed SVG: ENTITY declarations, internal DTD subsets and non-SVG DOCTYPEs are not accepted")

    def doctype(_name, system_id, public_id, has_internal_subset):
        if has_internal_subset or (system_id is not None and not str(public_id).startswith("-//W3C//DTD SVG")):
            refuse()

    scanner = expat.ParserCreate()
    scanner.StartDoctypeDeclHandler = doctype
    scanner.EntityDeclHandler = refuse
    scanner.ExternalEntityRefHandler = refuse
    try:
        scanner.Parse(text, True)
    except expat.ExpatError as exc:
        raise ValueError(f"malformed SVG: not well-formed XML ({exc})") from None


def _parse_svg(text: str | bytes) -> svgelements.SVG:
    """Parse with svgelements, lazily (``reify=False``: shapes keep their own coordinates
    and a transform matrix, which :func:`_shape_polylines` applies) and in the root's user
    space (see :func:`_without_root_viewport`)."""
    _reject_declarations(text)
    try:
        root = ET.fromstring(text)
    except (ET.ParseError, RecursionError) as exc:
        raise ValueError(f"malformed SVG: not well-formed XML ({exc})") from None
    if _local_name(root.tag) != "svg":
        raise ValueError(f"not an SVG document: the root element is <{_local_name(root.tag)}>, expected <svg>")
    _without_root_viewport(root)
    try:
        return svgelements.SVG.parse(io.BytesIO(ET.tostring(root)), reify=False, on_error="raise")
    except Exception as exc:  # svgelements signals bad data with assorted exception types
        raise ValueError(f"malformed SVG: {_describe_parse_failure(root, exc)}") from None


def _without_root_viewport(root: ET.Element) -> None:
    """Drop the root's viewBox, so that svgelements maps nothing onto a viewport.

    Its viewport transform (viewBox to width/height) would scale and shift every
    coordinate, and svgelements rounds it to 12 decimals, so it could not be undone
    exactly. The viewBox size stays as the root's width and height: percentages of
    lengths keep resolving against it, as SVG specifies.
    """
    viewbox = root.attrib.pop("viewBox", None)
    root.attrib.pop("preserveAspectRatio", None)
    if viewbox is None:
        return
    numbers = re.split(r"[\s,]+", viewbox.strip())
    try:
        _, _, width, height = (float(number) for number in numbers)
    except ValueError:
        raise ValueError(f"malformed SVG: viewBox={viewbox!r} is not four numbers") from None
    if not (width > 0 and height > 0):
        raise ValueError(f"malformed SVG: viewBox={viewbox!r} has no positive width and height")
    root.set("width", repr(width))
    root.set("height", repr(height))


def _describe_parse_failure(root: ET.Element, exc: Exception) -> str:
    """Name the offending path if it is bad path data (the usual failure), else say what
    svgelements raised."""
    for node in root.iter():
        if _local_name(node.tag) == "path":
            data = node.get("d", "")
            try:
                svgelements.Path(data)
            except Exception:
                where = f" id={node.get('id')!r}" if node.get("id") else ""
                return f"<path{where}> has invalid path data d={data[:80]!r}"
    return f"svgelements could not read it ({type(exc).__name__}: {exc or 'no detail'})"


def _local_name(tag: str) -> str:
    return tag.rpartition("}")[2]


def _own_attribute(node, key: str) -> str | None:
    """An attribute set on the node itself (svgelements' ``values`` also hold inherited ones)."""
    return getattr(node, "values", {}).get(svgelements.SVG_STRUCT_ATTRIB, {}).get(key)


def _has_shapes(node) -> bool:
    """Whether the node is a shape (other than a paperlib background) or a container
    holding one at any depth; invisible shapes count, they are skipped later."""
    if isinstance(node, svgelements.Shape):
        return _own_attribute(node, "id") != _BACKGROUND_ID
    return isinstance(node, _CONTAINERS) and any(_has_shapes(child) for child in node)


def _element_nodes(container):
    """Yield the nodes that become elements, in document order (grouping rule: module docstring)."""
    children = [child for child in container if _has_shapes(child)]
    for child in children:
        if _is_layer(child, alone=len(children) == 1):
            yield from _element_nodes(child)
        else:
            yield child


def _is_layer(node, *, alone: bool) -> bool:
    if not isinstance(node, svgelements.Group):
        return False
    if _own_attribute(node, _INKSCAPE_GROUPMODE) == "layer":
        return True
    return alone and any(isinstance(child, _CONTAINERS) and _has_shapes(child) for child in node)


def _shapes(node):
    """The drawable shapes in a node, at any depth, in document order."""
    if isinstance(node, svgelements.Shape):
        if _has_shapes(node):
            yield node
    elif isinstance(node, _CONTAINERS):
        for child in node:
            yield from _shapes(child)


def _node_strokes(node, tolerance: float, y_up: bool, points_left: _PointBudget) -> tuple[list[Stroke], int]:
    """Strokes of all shapes in ``node`` and how many degenerate subpaths were skipped."""
    strokes, skipped = [], 0
    for shape in _shapes(node):
        style = _stroke_style(shape)
        if style is None:
            continue
        for points in _shape_polylines(shape, tolerance, y_up, points_left):
            if not np.isfinite(points).all():
                raise ValueError("malformed SVG: a shape's coordinates overflow to infinity or NaN once transformed")
            if np.any(points != points[0]):
                strokes.append(Stroke(points, *style))
            else:
                skipped += 1
    return strokes, skipped


def _stroke_style(shape) -> tuple[float, str] | None:
    """``(width, color)`` of a shape's strokes, or None for an invisible shape."""
    width = float(shape.implicit_stroke_width or 0.0)
    if _is_painted(shape.stroke) and width > 0:
        color = shape.stroke.hex
    elif _is_painted(shape.fill):
        color = shape.fill.hex
    else:
        return None
    return (width if width > 0 else _FALLBACK_WIDTH), color


def _is_painted(paint) -> bool:
    return paint is not None and paint.value is not None


def _shape_polylines(shape, tolerance: float, y_up: bool, points_left: _PointBudget):
    """Yield one ``(n, 2)`` polyline per subpath of the shape, transformed to user space."""
    matrix = shape.transform
    linear = np.array([[matrix.a, matrix.c], [matrix.b, matrix.d]])
    offset = np.array([matrix.e, matrix.f])
    stretch = np.linalg.norm(linear, 2)  # the most the transform lengthens a distance
    local_tolerance = tolerance / stretch if stretch > 0 else math.inf
    if not (np.isfinite(linear).all() and np.isfinite(offset).all()):
        raise ValueError("malformed SVG: a transform is not finite")
    for local in _subpath_polylines(shape.segments(transformed=False), local_tolerance, points_left):
        points = local @ linear.T + offset
        if y_up:
            points[:, 1] = 0.0 - points[:, 1]  # 0.0 - y, not -y: no -0.0 in the output
        yield points


def _subpath_polylines(segments, tolerance: float, points_left: _PointBudget):
    """Yield the flattened polyline of each subpath of svgelements path segments. A bare
    moveto draws nothing in SVG and yields nothing; ``M x y Z`` yields its one point."""
    current = None
    for segment in segments:
        if isinstance(segment, svgelements.Move):
            if current and len(current) > 1:
                yield np.vstack(current)
            current = [_xy(segment.end)[None]]
            continue
        if current is None:  # a segment after Z starts a new subpath at the closing point
            current = [_xy(segment.start)[None]]
        if isinstance(segment, svgelements.Close):
            yield np.vstack(_closed(current))
            current = None
        else:
            current.append(_flatten_segment(segment, tolerance, points_left))
    if current and len(current) > 1:
        yield np.vstack(current)


def _closed(pieces: list[np.ndarray]) -> list[np.ndarray]:
    """The pieces of a subpath, ending exactly at its first point."""
    first, last = pieces[0][0], pieces[-1][-1]
    if np.abs(last - first).max() <= _CLOSING_SNAP * (1.0 + np.abs(first).max()):
        pieces[-1] = np.vstack([pieces[-1][:-1], first])
        return pieces
    return [*pieces, first[None]]


def _xy(point) -> np.ndarray:
    return np.array([point.x, point.y], dtype=np.float64)


def _flatten_segment(segment, tolerance: float, points_left: _PointBudget) -> np.ndarray:
    """The polyline of one segment, without its start point and ending exactly at its end."""
    bound = _second_derivative_bound(segment)
    if bound is None:  # a straight segment
        points_left.take(1)
        return _xy(segment.end)[None]
    span, curvature = bound
    count = _segment_count(span, curvature, tolerance)
    points_left.take(count)
    points = np.array(segment.npoint(np.arange(1, count + 1) / count), dtype=np.float64).reshape(-1, 2)
    points[-1] = _xy(segment.end)
    return points


def _second_derivative_bound(segment) -> tuple[float, float] | None:
    """``(L, M)``: the parameter span of a curved segment and a bound on ``|B''|`` over it
    (see the module docstring); None for a straight one."""
    if isinstance(segment, svgelements.QuadraticBezier):
        p0, p1, p2 = (_xy(p) for p in (segment.start, segment.control, segment.end))
        return 1.0, 2.0 * float(np.hypot(*(p0 - 2 * p1 + p2)))
    if isinstance(segment, svgelements.CubicBezier):
        p0, p1, p2, p3 = (_xy(p) for p in (segment.start, segment.control1, segment.control2, segment.end))
        return 1.0, 6.0 * max(float(np.hypot(*(p0 - 2 * p1 + p2))), float(np.hypot(*(p1 - 2 * p2 + p3))))
    if isinstance(segment, svgelements.Arc):
        # svgelements samples arcs uniformly in the ellipse's angle parameter t:
        # B(t) = c + R (rx cos t, ry sin t), so |B''(t)| = |B(t) - c| <= max(rx, ry).
        return abs(float(segment.sweep)), max(float(segment.rx), float(segment.ry))
    return None


def _segment_count(span: float, curvature: float, tolerance: float) -> int:
    """Fewest equal parameter steps over ``span`` for which the chord error bound
    ``step**2 curvature / 8`` is at most ``tolerance``."""
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # overflow is reported just below
        steps = float(span * np.sqrt(np.float64(curvature) / (8.0 * np.float64(tolerance))))
    if not math.isfinite(steps):
        raise ValueError(f"cannot flatten a curve (parameter span {span!r}, curvature bound {curvature!r}) within "
                         f"tolerance={tolerance:g}: the curve is not finite or the tolerance is far too small")
    count = max(1, math.ceil(steps))
    if count > _MAX_POINTS_PER_SEGMENT:
        raise ValueError(
            f"flattening a curve within tolerance={tolerance:g} needs {count} points; "
            "use a larger tolerance (it is in the shape's own user units)"
        )
    return count


# --------------------------------------------------------------------------- writing


def svg_string(
    elements,
    *,
    width=None,
    height=None,
    viewbox=None,
    background: str | None = None,
    y_up: bool = True,
    decimals: int | None = None,
) -> str:
    """The SVG text of elements: one ``<g>`` of ``<polyline>`` s per element.

    Parameters
    ----------
    elements : sequence of Element
        The drawing; element names become ``inkscape:label`` attributes.
    width, height : float or str, optional
        Displayed size: a positive number (user units, i.e. CSS px) or a CSS length such
        as ``"120mm"``. Both default to the viewbox size; if only one is given the other
        is left out, and viewers keep the viewbox's aspect ratio.
    viewbox : (x, y, width, height), optional
        The rectangle of the plane to show, in the elements' own coordinates (y up when
        ``y_up``, so ``(x, y)`` is its lower-left corner). Defaults to the bounding box of
        all strokes, including half of each stroke's width.
    background : str, optional
        A colour to fill the viewbox with (written as a ``<rect>`` that :func:`read_svg`
        ignores); transparent by default.
    y_up : bool
        Whether the elements are y-up; they are then mirrored to SVG's y-down frame as
        ``(x, -y)``.
    decimals : int, optional
        Round coordinates to this many decimals (smaller files). By default each
        coordinate is written in the shortest form that reads back to the same double,
        so :func:`read_svg` returns exactly the points written. Widths are always exact.

    Returns
    -------
    str
        A standalone SVG 1.1 document.

    Raises
    ------
    TypeError
        If ``elements`` is not a sequence of :class:`Element`.
    ValueError
        If there are no elements and no ``viewbox``, or the viewbox, sizes, decimals or
        names are invalid.

    References
    ----------
    .. [1] W3C, "Scalable Vector Graphics (SVG) 1.1 (Second Edition)", 2011, sections
       5.2 (``g``), 7.7 (``viewBox``), 9.6 (``polyline``).
    """
    elements = as_elements(elements)
    decimals = _check_decimals(decimals)
    box = _check_viewbox(viewbox) if viewbox is not None else _drawing_bounds(elements)
    x, y, box_width, box_height = box
    svg_box = (x, 0.0 - (y + box_height), box_width, box_height) if y_up else box
    if width is None and height is None:
        width, height = box_width, box_height
    size = "".join(
        f" {name}={quoteattr(_css_length(value, name))}"
        for name, value in (("width", width), ("height", height))
        if value is not None
    )
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="{_SVG_NAMESPACE}" xmlns:inkscape="{_INKSCAPE_NAMESPACE}" version="1.1"{size} '
        f'viewBox="{" ".join(map(_number, svg_box))}" fill="none" stroke-linecap="round" stroke-linejoin="round">',
    ]
    if background is not None:
        bx, by, bw, bh = map(_number, svg_box)
        lines.append(
            f'<rect id="{_BACKGROUND_ID}" x="{bx}" y="{by}" width="{bw}" height="{bh}" '
            f'fill={_xml_attribute(background, "background")} stroke="none"/>'
        )
    for element in elements:
        label = f" inkscape:label={_xml_attribute(element.name, 'element name')}" if element.name else ""
        lines.append(f"<g{label}>")
        lines += [_polyline(stroke, y_up, decimals) for stroke in element.strokes]
        lines.append("</g>")
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


def write_svg(elements, path, **options) -> Path:
    """Write elements to an SVG file, atomically.

    Parameters
    ----------
    elements : sequence of Element
        The drawing.
    path : str or os.PathLike
        The file to write; missing parent folders are created.
    **options
        ``width``, ``height``, ``viewbox``, ``background``, ``y_up``, ``decimals``, as
        for :func:`svg_string`.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    TypeError, ValueError
        As :func:`svg_string`; the input is checked in full before the file is touched,
        and a failure while writing leaves any previous file as it was.

    References
    ----------
    .. [1] W3C, "Scalable Vector Graphics (SVG) 1.1 (Second Edition)", 2011.
    """
    text = svg_string(elements, **options)
    path = Path(path)
    with atomic_path(path) as temporary:
        temporary.write_text(text, encoding="utf-8")
    return path


def _check_decimals(decimals) -> int | None:
    if decimals is None:
        return None
    if isinstance(decimals, bool) or not isinstance(decimals, (int, np.integer)) or decimals < 0:
        raise ValueError(f"decimals must be None or an integer >= 0, got {decimals!r}")
    return int(decimals)


def _check_viewbox(viewbox) -> tuple[float, float, float, float]:
    try:
        box = tuple(float(v) for v in viewbox)
    except (TypeError, ValueError):
        box = ()
    if len(box) != 4 or not all(map(math.isfinite, box)) or box[2] <= 0 or box[3] <= 0:
        raise ValueError(
            f"viewbox must be four finite numbers (x, y, width, height) with width, height > 0, got {viewbox!r}"
        )
    return box


def _drawing_bounds(elements: list[Element]) -> tuple[float, float, float, float]:
    """``(x, y, width, height)`` of all strokes, each widened by half its pen width."""
    if not elements:
        raise ValueError("no elements to draw: pass at least one Element, or a viewbox for an empty drawing")
    strokes = [stroke for element in elements for stroke in element.strokes]
    low = np.min([stroke.points.min(axis=0) - stroke.width / 2 for stroke in strokes], axis=0)
    high = np.max([stroke.points.max(axis=0) + stroke.width / 2 for stroke in strokes], axis=0)
    return float(low[0]), float(low[1]), float(high[0] - low[0]), float(high[1] - low[1])


def _css_length(value, name: str) -> str:
    """A positive number (user units) or CSS length string, as attribute text."""
    if isinstance(value, str):
        length = _CSS_LENGTH.match(value)
        number = _positive(float(length.group(1))) if length else None
    else:
        number = _positive(value)
    if number is None:
        raise ValueError(f"{name} must be a positive number or a CSS length such as '120mm', got {value!r}")
    return value.strip() if isinstance(value, str) else _number(number)


def _number(value: float) -> str:
    """Shortest decimal text that parses back to the same double (Python's repr)."""
    return repr(float(value))


def _xml_attribute(text: str, what: str) -> str:
    """``text`` quoted for an XML attribute; raises on characters XML cannot hold."""
    bad = _NOT_XML_CHARACTER.search(text)
    if bad:
        raise ValueError(f"{what} {text!r} holds {bad.group()!r}, a character XML cannot represent")
    return quoteattr(text, {"\n": "&#10;", "\r": "&#13;", "\t": "&#9;"})


def _polyline(stroke: Stroke, y_up: bool, decimals: int | None) -> str:
    points = stroke.points if len(stroke) > 1 else np.repeat(stroke.points, 2, axis=0)  # a dot
    if y_up:
        points = points * [1.0, -1.0]
    if decimals is not None:
        points = np.round(points, decimals)
    points = points + 0.0  # -0.0 becomes 0.0
    text = " ".join(f"{x!r},{y!r}" for x, y in points.tolist())
    return (
        f"<polyline stroke={_xml_attribute(stroke.color, 'stroke color')} "
        f'stroke-width="{_number(stroke.width)}" points="{text}"/>'
    )
