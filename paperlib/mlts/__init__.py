"""Alvarez et al. 2015, abstract textures by a multi-layered texture sampler (MLTS).

- :mod:`.texels`: the texels of section 3 (triangles, rectangles, ellipses, regular and random
  convex polygons, random shapes), objects as their affine images, orientation toward projective
  points;
- :mod:`.layers`: every layer parameter of section 4 (:class:`Layer`);
- :mod:`.sampler`: the multi-layered object structure of Definition 1 with inclusion and
  exclusion by trials and diameter reductions (:func:`sample_structure`, in rounds by size or, as an
  option, object by object), and an independent
  count of rule breaches (:func:`rule_violations`);
- :mod:`.raster`: the anti-aliased painter (occlusion, transparency, light spot, clipping to
  the father) in numba;
- :mod:`.render`: section 5's rendering (palette from an image, transparency, light spot,
  tessellation, "keep father inclusion") and :func:`render` of a script;
- :mod:`.script`: JSON scripts with every hyper-parameter and both seeds, the automatic mode
  :func:`sample_script`;
- :mod:`.svg`: a rendered texture as SVG (objects as polygons, layers as groups, tessellation
  cells as polygons) and back (:func:`texture_svg`, :func:`write_texture_svg`,
  :func:`read_texture_svg`);
- :mod:`.basic`: the basic processes of Fig. 5 (scaling dead leaves, Voronoi and Poisson-line
  tessellations, IFS fractals).

The explorer widget is :func:`paperlib.widgets.mlts_explorer`.
"""

from .basic import (
    DEFAULT_PALETTE,
    barnsley_fern,
    box_counting_dimension,
    dead_leaves,
    dead_leaves_coverage,
    dead_leaves_coverage_std,
    dead_leaves_mean_area,
    dead_leaves_window_area,
    ifs_chaos_game,
    ifs_fractal,
    poisson_line_tessellation,
    sierpinski_triangle,
    voronoi_tessellation,
)
from .layers import Layer
from .raster import coverage, paint, render_polygons
from .render import load_palette, render, render_structure, tessellation_cells
from .sampler import MLObject, Structure, rule_violations, sample_structure
from .svg import read_texture_svg, texture_svg, write_texture_svg
from .script import RenderSettings, Script, sample_script
from .texels import TEXELS, affine_object, affine_objects, object_diameter, orientation_angle, texel, texel_batch

__all__ = [
    "DEFAULT_PALETTE", "Layer", "MLObject", "RenderSettings", "Script", "Structure", "TEXELS", "affine_object",
    "affine_objects", "barnsley_fern", "box_counting_dimension", "coverage", "dead_leaves", "dead_leaves_coverage",
    "dead_leaves_coverage_std", "dead_leaves_mean_area", "dead_leaves_window_area", "ifs_chaos_game", "ifs_fractal",
    "load_palette", "object_diameter", "orientation_angle", "paint", "poisson_line_tessellation", "render",
    "render_polygons", "render_structure", "rule_violations", "sample_script", "sample_structure",
    "sierpinski_triangle", "tessellation_cells", "texel", "texel_batch", "voronoi_tessellation",
    "read_texture_svg", "texture_svg", "write_texture_svg",
]
