"""ML-textures as SVG: the objects of a rendered structure written as vector polygons, and read back.

The project's rule "vector in, vector out" applied to Alvarez et al. 2015: the objects of an
ML-texture are polygons (Definition 1, section 3), so the texture is written as one SVG
``<polygon>`` per object, in the renderer's painting order (later objects in front, section 3's
occlusion), with the colour and transparency the renderer draws for it (section 5: 5.1 palette,
5.2 transparency, same render seed, same draws; :func:`paperlib.mlts.render_structure`):

- layers are ``<g>`` groups, ``id="layer-m"`` with m = 1 for the image rectangle (the paper's
  ``L_1``), in order;
- transparency ``t`` is ``fill-opacity = 1 - t`` (the painter's ``a = coverage * (1 - t)``);
- "keep father inclusion" (section 3's second inclusion mode, 5.4) writes each object cut by its
  father's polygon (shapely ``intersection``: the samples the painter keeps are those inside
  both polygons), a ``<path>`` with one subpath per piece;
- tessellation (Fig. 15, section 5) writes the cells: the faces of the arrangement of the objects'
  boundaries (shapely ``union_all`` of the boundaries, which nodes them, then ``polygonize``),
  clipped to the image, in ``<g id="tessellation">``, each a ``<path fill-rule="evenodd">`` (its
  outer ring and its holes). A cell takes the colour the renderer gives the pixel-grid cell
  (:func:`paperlib.mlts.tessellation_cells`) at a point inside it (shapely
  ``point_on_surface``). Cells are written largest first: a hole of a cell is a union of smaller
  cells, so a reader that fills every ring (as :func:`read_texture_svg` followed by
  :func:`paperlib.mlts.render_polygons` does) paints the same picture as one honouring the holes.
- the light spot (5.3) has no flat-fill equivalent (its intensity falls as ``h^2 / (h^2 + r^2)``
  inside each object): a light-spot texture is refused with a ValueError rather than written
  wrongly.

Colours are written as 8-bit ``#rrggbb`` and opacities with 4 decimals; SVG readers (svgelements,
browsers) hold colours in 8 bits. Coordinates are written with the shortest decimal that reads
back to the same double, so geometry round-trips exactly.

:func:`read_texture_svg` reads such a file back through :func:`paperlib.geometry.read_svg` (which
carries fills and their opacity as ``#rrggbbaa``) into polygons, colours and transparencies for
:func:`paperlib.mlts.render_polygons`. The tests compare that re-render with the raster render;
the bounds and where they come from are in ``tests/test_mlts_svg.py``.

Written by hand: the SVG text (a few lines of XML); geometry from shapely, parsing from
svgelements (through :func:`paperlib.geometry.read_svg`).

References
----------
.. [1] L. Alvarez, Y. Gousseau, J.-M. Morel, A. Salgado, "Exploring the space of abstract textures
   by principles and random sampling", J. Math. Imaging Vis. 53 (2015), Definition 1, sections 3
   (occlusion, inclusion), 5 (rendering; 5.1-5.4) and Fig. 15 (tessellation).
.. [2] W3C, "Scalable Vector Graphics (SVG) 1.1 (Second Edition)", 2011, sections 5 (``g``),
   8 (paths), 9 (polygons), 11.3-11.4 (fill, fill-rule, fill-opacity).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

from .._atomic import atomic_path
from ..geometry import read_svg
from .raster import coverage
from .render import _object_paint, _render_palette, _tessellation_colours
from .sampler import Structure
from .script import RenderSettings

__all__ = ["read_texture_svg", "texture_svg", "write_texture_svg"]

_HEADER = ('<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{w}" height="{h}" '
           'viewBox="0 0 {w} {h}">\n')


def _number(value: float) -> str:
    """Shortest decimal that reads back to the same double (``repr``), integers without ``.0``."""
    value = float(value)
    return str(int(value)) if value.is_integer() and abs(value) < 2**53 else repr(value)


def _colour(rgb) -> str:
    return "#" + "".join(f"{int(round(float(np.clip(c, 0.0, 1.0)) * 255)):02x}" for c in rgb)


def _points(polygon: np.ndarray) -> str:
    return " ".join(f"{_number(x)},{_number(y)}" for x, y in polygon)


def _ring_path(rings) -> str:
    return " ".join(f"M{_points(np.asarray(ring)[:-1])}Z" for ring in rings)


def _polygon_rings(geometry) -> list:
    """Rings (exterior then interiors) of every polygon piece of a shapely geometry."""
    rings = []
    for piece in shapely.get_parts(geometry):
        if isinstance(piece, shapely.Polygon) and not piece.is_empty and piece.area > 0:
            rings.append(np.asarray(piece.exterior.coords))
            rings += [np.asarray(hole.coords) for hole in piece.interiors]
    return rings


def _check_inputs(structure, settings) -> None:
    if not isinstance(structure, Structure):
        raise ValueError(f"structure must be a paperlib.mlts.Structure, got {type(structure).__name__}")
    if not isinstance(settings, RenderSettings):
        raise ValueError(f"settings must be RenderSettings, got {type(settings).__name__}")
    if settings.light_distance > 0 and not settings.tessellation:
        raise ValueError(f"settings.light_distance={settings.light_distance} asks for the light spot (section 5.3), "
                         "which flat SVG fills cannot show; write the texture with light_distance=0 or as PNG")


def _object_layers(structure: Structure, settings: RenderSettings, colours: np.ndarray) -> str:
    rng = np.random.default_rng(settings.seed)
    polygons, fills, transparency, _, _, clip = _object_paint(structure, settings, colours, rng)
    groups: dict[int, list[str]] = {}
    for index, (item, polygon) in enumerate(zip(structure.objects, polygons)):
        style = f'fill="{_colour(fills[index])}"'
        if transparency[index] > 0:
            style += f' fill-opacity="{1.0 - transparency[index]:.4f}"'
        if clip is not None and clip[index] is not None:
            rings = _polygon_rings(shapely.intersection(shapely.Polygon(polygon), shapely.Polygon(clip[index])))
            if not rings:
                continue
            shape = f'<path d="{_ring_path(rings)}" fill-rule="evenodd" {style}/>'
        else:
            shape = f'<polygon points="{_points(polygon)}" {style}/>'
        groups.setdefault(item.layer, []).append(shape)
    return "".join(f'<g id="layer-{layer + 1}">\n' + "\n".join(shapes) + "\n</g>\n"
                   for layer, shapes in sorted(groups.items()))


def _face_label(rings: list, cells: np.ndarray, samples: int, face) -> int:
    """The pixel-grid cell most of a face's grid points fall in (the raster's colour for it).

    The grid points inside the face (its rings joined, even-odd: the raster's own coverage rule)
    vote; a face holding no grid point takes the cell at shapely's ``point_on_surface``.
    """
    row0, col0, mask = coverage(np.concatenate(rings) * samples, cells.shape, samples=1)
    inside = cells[row0:row0 + mask.shape[0], col0:col0 + mask.shape[1]][mask > 0.5]
    if inside.size:
        return int(np.bincount(inside).argmax())
    x, y = shapely.get_coordinates(shapely.point_on_surface(face))[0] * samples
    return int(cells[min(max(int(y), 0), cells.shape[0] - 1), min(max(int(x), 0), cells.shape[1] - 1)])


def _tessellation_layer(structure: Structure, settings: RenderSettings, colours: np.ndarray) -> str:
    rng = np.random.default_rng(settings.seed)
    cells, cell_colours = _tessellation_colours(structure, colours, settings.samples, rng)
    image = shapely.box(0, 0, structure.width, structure.height)
    boundaries = shapely.boundary(np.array([shapely.Polygon(item.polygon) for item in structure.objects], dtype=object))
    noded = shapely.union_all(np.append(boundaries, image.boundary))
    faces = shapely.get_parts(shapely.polygonize(shapely.get_parts(noded)))
    # a face leaving the image and coming back is cut into pieces: each is a cell of its own
    faces = shapely.get_parts(shapely.intersection(faces, image))
    faces = faces[shapely.area(faces) > 0]
    faces = faces[np.argsort(-shapely.area(faces), kind="stable")]
    shapes = []
    for face in faces:
        rings = _polygon_rings(face)
        label = _face_label(rings, cells, settings.samples, face)
        shapes.append(f'<path d="{_ring_path(rings)}" fill-rule="evenodd" fill="{_colour(cell_colours[label])}"/>')
    return '<g id="tessellation">\n' + "\n".join(shapes) + "\n</g>\n"


def texture_svg(structure: Structure, settings: RenderSettings, palette=None) -> str:
    """The SVG text of a rendered ML-texture (objects as polygons, layers as groups; module docstring).

    Parameters
    ----------
    structure : Structure
        From :func:`paperlib.mlts.sample_structure`.
    settings : RenderSettings
        The render settings (palette, render seed, transparency, tessellation, keep father
        inclusion; ``samples`` is used only to colour tessellation cells as the raster does).
    palette : array_like, optional
        Colours (n, 3) instead of ``settings.palette``, as for :func:`paperlib.mlts.render_structure`.

    Returns
    -------
    str
        A standalone SVG 1.1 document, ``width`` x ``height`` user units (pixels).

    Raises
    ------
    ValueError
        For a structure or settings of the wrong type, a bad palette, or a light spot
        (``settings.light_distance > 0`` without tessellation: no flat-fill equivalent).

    References
    ----------
    Alvarez et al. 2015, Definition 1, sections 3 and 5 (5.1-5.4), Fig. 15.
    """
    _check_inputs(structure, settings)
    colours = _render_palette(settings, palette)
    body = (_tessellation_layer if settings.tessellation else _object_layers)(structure, settings, colours)
    return _HEADER.format(w=structure.width, h=structure.height) + body + "</svg>\n"


def write_texture_svg(structure: Structure, settings: RenderSettings, path, palette=None) -> Path:
    """Write :func:`texture_svg` to ``path`` atomically (a temporary file renamed; parents created).

    Parameters
    ----------
    structure, settings, palette
        As for :func:`texture_svg`.
    path : str or os.PathLike
        The ``.svg`` file to write.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    ValueError
        As :func:`texture_svg` (checked before the file is touched).
    TypeError
        If ``path`` is not a str or os.PathLike.

    References
    ----------
    Alvarez et al. 2015, sections 3 and 5.
    """
    if not isinstance(path, (str, Path)) and not hasattr(path, "__fspath__"):
        raise TypeError(f"path must be a str or os.PathLike, got {type(path).__name__}")
    text = texture_svg(structure, settings, palette)
    path = Path(path)
    with atomic_path(path) as temporary:
        temporary.write_text(text, encoding="utf-8")
    return path


def read_texture_svg(path_or_text) -> tuple[list, np.ndarray, np.ndarray, list]:
    """Polygons, colours and transparencies of an SVG texture, read with :func:`paperlib.geometry.read_svg`.

    Every filled ring becomes one polygon (closing point dropped), in document order, so
    ``render_polygons(polygons, colours, (height, width), alphas=transparency)`` repaints the
    texture as :func:`texture_svg` wrote it.

    Parameters
    ----------
    path_or_text : str, bytes or os.PathLike
        An SVG file or its text (as for :func:`paperlib.geometry.read_svg`).

    Returns
    -------
    polygons : list of ndarray (k, 2)
        Vertices in pixels, y down.
    colours : ndarray (n, 3)
        RGB in [0, 1] (8-bit precision).
    transparency : ndarray (n,)
        ``1 - opacity`` in [0, 1] (8-bit precision).
    groups : list of str
        The name (``id``) of the group each polygon came from (``"layer-1"``...).

    Raises
    ------
    ValueError
        As :func:`paperlib.geometry.read_svg` (malformed SVG, nothing drawable...), or a colour
        that is not ``#rrggbb`` / ``#rrggbbaa``.

    References
    ----------
    Alvarez et al. 2015, section 5; W3C SVG 1.1, section 11.
    """
    polygons, colours, transparency, groups = [], [], [], []
    for element in read_svg(path_or_text, y_up=False):
        for stroke in element.strokes:
            text = stroke.color.lstrip("#")
            if len(text) not in (6, 8) or any(c not in "0123456789abcdefABCDEF" for c in text):
                raise ValueError(f"texture SVG colours must be #rrggbb or #rrggbbaa, got {stroke.color!r}")
            values = [int(text[i:i + 2], 16) / 255.0 for i in range(0, len(text), 2)]
            points = stroke.points
            if len(points) > 1 and np.array_equal(points[0], points[-1]):
                points = points[:-1]
            polygons.append(points)
            colours.append(values[:3])
            transparency.append(1.0 - values[3] if len(values) == 4 else 0.0)
            groups.append(element.name)
    return polygons, np.array(colours).reshape(-1, 3), np.array(transparency), groups
