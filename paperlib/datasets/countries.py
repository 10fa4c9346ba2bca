"""Named country outlines from the world map SVG shipped with ``pygal_maps_world``.

Source
------
``pygal_maps_world`` 1.0.2 (Kozea, https://www.pygal.org), file
``pygal_maps_world/worldmap.svg`` inside the installed package (777 928 bytes,
``viewBox="0 0 2475 1388"``, no transforms). It holds one ``<g class="<code> country
map-element">`` per country, 184 countries and territories keyed by lower-case ISO
3166-1 alpha-2 codes (``"fr"``, ``"us"``, ...), with 2 038 ``<path>`` elements (one
ring each, except Germany's first path, which has three subpaths) made of 25 716
cubic Bezier and 312 line segments. Subpaths are not closed with ``z``; their last
point coincides with the first (largest gap 1.2 user units, in ``"mx"``), so each is read
as a closed ring. English names come from ``pygal_maps_world.i18n.COUNTRIES``, which
covers exactly the 184 codes of the SVG. The map projection is not documented by the
package; treat the coordinates as map units, not as lon/lat.

Licence
-------
The package metadata declares ``License: GNU LGPL v3+`` (classifier "GNU Lesser General
Public License v3 or later (LGPLv3+)"), and ``maps.py`` carries the LGPL-3.0-or-later
notice; the wheel ships no separate licence file. The SVG is read from the installed
package at run time and not copied into this repository.

Flattening
----------
Paths are parsed with :mod:`svgelements`; every segment is converted to a cubic Bezier
(lines and quadratics exactly, arcs by ``svgelements``' approximation) and each cubic
``B`` is sampled at ``m`` equal parameter steps with ``m = ceil(sqrt(0.75 * M /
tolerance))``, ``M = max |P0 - 2 P1 + P2|, |P1 - 2 P2 + P3|``. Since ``|B''| <= 6 M``,
the polyline then lies within ``tolerance`` user units of the curve (the classical
``h^2 max|B''| / 8`` chord bound). The default ``tolerance=0.1`` is 1/24750 of the map
width and gives about 100 000 vertices for the whole map.
"""

from __future__ import annotations

import difflib
import importlib.resources
from functools import lru_cache

import numpy as np
import svgelements

from paperlib.geometry import as_points, drop_repeated_vertices, oriented_ccw, signed_area

__all__ = ["country_names", "country_english_names", "country_outline"]

_PACKAGE = "pygal_maps_world"
_SVG_NAME = "worldmap.svg"
_NON_CODE_CLASSES = {"country", "map-element"}


@lru_cache(maxsize=1)
def _parsed_map() -> tuple[dict[str, tuple], svgelements.Viewbox]:
    """Parse the SVG once: ``({code: (Path, ...)}, viewbox)`` in document order."""
    try:
        source = importlib.resources.files(_PACKAGE).joinpath(_SVG_NAME)
    except ModuleNotFoundError:
        raise ModuleNotFoundError(
            f"{_PACKAGE} is not installed: `pip install pygal_maps_world==1.0.2`"
        ) from None
    with importlib.resources.as_file(source) as path:
        svg = svgelements.SVG.parse(str(path), reify=True)
    countries = {}
    for group in svg.select(lambda e: isinstance(e, svgelements.Group)):
        classes = set(group.values.get("class", "").split())
        if "country" not in classes:
            continue
        (code,) = classes - _NON_CODE_CLASSES
        paths = tuple(e for e in group if isinstance(e, svgelements.Path))
        countries[code] = countries.get(code, ()) + paths
    return countries, svg.viewbox


def country_names() -> list[str]:
    """Sorted country codes of the SVG (lower-case ISO 3166-1 alpha-2, e.g. ``"fr"``).

    Returns
    -------
    list of str
        The country codes, sorted.
    """
    return sorted(_parsed_map()[0])


def country_english_names() -> dict[str, str]:
    """``{code: English name}`` for every code of :func:`country_names`, from
    ``pygal_maps_world.i18n.COUNTRIES`` (the code itself if a name is missing).

    Returns
    -------
    dict of str to str
        ``{code: English name}``, keys in the order of :func:`country_names`.
    """
    from pygal_maps_world.i18n import COUNTRIES  # plain dict; does not import pygal

    return {code: COUNTRIES.get(code, code) for code in country_names()}


def _check_code(code) -> str:
    if not isinstance(code, str):
        raise ValueError(f"unknown country code {code!r:.60}: code must be a str (an ISO 3166-1 alpha-2 country code), "
                         f"got {type(code).__name__}")
    countries = _parsed_map()[0]
    key = code.strip().lower() if isinstance(code, str) else code
    if key in countries:
        return key
    names = {name.lower(): c for c, name in country_english_names().items()}
    guess = names.get(key) if isinstance(key, str) else None
    if isinstance(key, str) and guess is None:
        close = difflib.get_close_matches(key, list(names), n=1)
        guess = names[close[0]] if close else None
    hint = f"; did you mean {guess!r} ({country_english_names()[guess]})?" if guess else "."
    raise ValueError(
        f"unknown country code {code!r}{hint} Codes are lower-case ISO 3166-1 alpha-2 as "
        f"in the SVG, e.g. 'de', 'fr', 'us' ({len(countries)} in all, see country_names())"
    )


def _as_cubics(path: svgelements.Path) -> list[np.ndarray]:
    """Control points ``(k, 4)`` complex array per subpath, every segment as a cubic."""
    rings = []
    for subpath in path.as_subpaths():
        controls = []
        for seg in subpath:
            if isinstance(seg, svgelements.Move):
                continue
            if isinstance(seg, svgelements.Arc):
                controls += [_cubic_controls(c) for c in seg.as_cubic_curves()]
            else:
                controls.append(_cubic_controls(seg))
        if controls:
            rings.append(np.array(controls))
    return rings


def _cubic_controls(seg) -> list[complex]:
    """Four cubic control points for a Line, Close, QuadraticBezier or CubicBezier."""
    p0, p3 = complex(seg.start), complex(seg.end)
    if isinstance(seg, svgelements.CubicBezier):
        return [p0, complex(seg.control1), complex(seg.control2), p3]
    if isinstance(seg, svgelements.QuadraticBezier):  # exact degree elevation
        q = complex(seg.control)
        return [p0, p0 + 2 * (q - p0) / 3, p3 + 2 * (q - p3) / 3, p3]
    return [p0, p0 + (p3 - p0) / 3, p0 + 2 * (p3 - p0) / 3, p3]  # Line / Close


def _flatten(controls: np.ndarray, tolerance: float) -> np.ndarray:
    """Polyline (complex) through a chain of cubics, within ``tolerance`` of them."""
    p0, p1, p2, p3 = controls.T
    second = np.maximum(np.abs(p0 - 2 * p1 + p2), np.abs(p1 - 2 * p2 + p3))
    steps = np.maximum(1, np.ceil(np.sqrt(0.75 * second / tolerance))).astype(np.int64)
    owner = np.repeat(np.arange(len(steps)), steps)
    t = (np.arange(len(owner)) - np.repeat(np.cumsum(steps) - steps, steps) + 1) / steps[owner]
    u = 1.0 - t
    points = (
        u**3 * p0[owner] + 3 * u * u * t * p1[owner] + 3 * u * t * t * p2[owner] + t**3 * p3[owner]
    )
    return np.concatenate([p0[:1], points])


def _oriented_xy(ring: np.ndarray, height: float, y_up: bool) -> np.ndarray:
    """``(n, 2)`` float array of an SVG-frame ring, y flipped if asked, with positive
    shoelace area."""
    return oriented_ccw(np.column_stack([ring[:, 0], height - ring[:, 1] if y_up else ring[:, 1]]))


@lru_cache(maxsize=256)
def _outline(code: str, tolerance: float, y_up: bool) -> tuple[np.ndarray, ...]:
    paths, viewbox = _parsed_map()[0][code], _parsed_map()[1]
    height = 2 * viewbox.y + viewbox.height  # mirror inside the viewBox
    rings = []
    for path in paths:
        for controls in _as_cubics(path):
            polyline = _flatten(controls, tolerance)  # 1-D complex, one entry per vertex
            # A vertex equal to its cyclic predecessor goes (of a last point equal to the
            # first, the first copy), as before when this compared the complex vector
            # with np.roll(polyline, 1). Done on exact (x, y_svg) copies before the y
            # flip: height - y can round two distinct y to one value and drop a vertex
            # the source keeps. A ring of one repeated point comes out empty (it used to
            # keep one point) and is skipped below either way.
            ring = drop_repeated_vertices(np.column_stack([polyline.real, polyline.imag]))
            if len(ring) >= 3:
                rings.append(as_points(_oriented_xy(ring, height, y_up), name=f"{code} ring"))
    order = sorted(range(len(rings)), key=lambda i: (-abs(signed_area(rings[i])), i))
    return tuple(rings[i] for i in order)


def country_outline(code: str, tolerance: float = 0.1, y_up: bool = True) -> list[np.ndarray]:
    """Outline of one country as closed polylines, one per ring (island), largest first.

    Parameters
    ----------
    code : str
        Country code as in the SVG (lower-case ISO 3166-1 alpha-2; case and surrounding
        blanks are ignored), see :func:`country_names`.
    tolerance : float
        Maximum distance, in SVG user units, between the polyline and the Bezier path
        (see the module docstring; > 0). The map is 2475 x 1388 units.
    y_up : bool
        If True (default), ``y = 1388 - y_svg`` so north is up, as in
        :func:`paperlib.datasets.coastlines.coastlines`; if False, raw SVG coordinates
        with y pointing down.

    Returns
    -------
    list of numpy.ndarray
        Read-only float64 ``(n_i, 2)`` arrays, each a closed ring read cyclically (the
        first vertex is not repeated), with positive shoelace area in the returned
        frame (counter-clockwise when ``y_up``), sorted by decreasing area (ties keep
        document order). Rings are returned as drawn: the SVG encodes no holes, and
        about 8 % of the rings (mostly in ca, us, id, gl, ru) self-intersect slightly,
        as the source paths already do.

    Raises
    ------
    ValueError
        If ``code`` is unknown (the message names valid codes and a likely match) or
        ``tolerance`` is not a positive finite number.
    """
    key = _check_code(code)
    try:
        tolerance = float(tolerance)
    except (TypeError, ValueError):
        tolerance = float("nan")
    if not np.isfinite(tolerance) or tolerance <= 0:
        raise ValueError("tolerance must be a positive finite number of SVG user units")
    return list(_outline(key, tolerance, bool(y_up)))
