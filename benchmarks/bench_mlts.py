"""Alvarez 2015 MLTS: about 3,000 objects with inclusion and exclusion at 1024 x 1024.

"mlts: structure + render, ~3,000 objects, 1024x1024": three layers under the image rectangle
(made in the timed call from a fixed configuration, seed 0):

- 40 rectangles or ellipses of diameter 250 px, aspect 2, exclusion on (Fig. 13's rule);
- 8 triangles or convex polygons per father, diameter 80 px, inclusion and exclusion (Fig. 10);
- 13 random shapes per father, diameter 25 px, inclusion (Fig. 14);

then rendered with the chelsea palette, transparency up to 0.5, a light spot at 300 px and 4 x 4
anti-aliasing samples. Paper: about 3,000 objects "in less than 5 s on a laptop"; target (issue 6):
<= 0.5 s for geometry and rendering. Baseline, same run: the rendering alone of the same
structure, so the ratio shows how the time splits.
"""

from functools import cache

from paperlib.mlts import Layer, RenderSettings, render_structure, sample_structure
from registry import benchmark

LAYERS = (
    Layer(texels=("rectangle", "ellipse"), max_objects=40, aspect_ratio=2.0, max_diameter=250.0, exclusion=True,
          max_trials=20, max_reductions=5),
    Layer(texels=("triangle", "convex_polygon"), max_objects=8, max_diameter=80.0, inclusion=True, exclusion=True,
          max_trials=20, max_reductions=5),
    Layer(texels=("random_shape",), max_objects=13, max_diameter=25.0, inclusion=True, max_trials=20,
          max_reductions=5),
)
SETTINGS = RenderSettings(palette="chelsea", seed=1, transparency=0.5, light_distance=300.0)


@cache
def structure(side):
    return sample_structure(LAYERS, side, side, seed=0)


def render_only(side):
    made = structure(side)
    return lambda: render_structure(made, SETTINGS)


@benchmark("mlts: structure + render, ~3,000 objects", sizes=[1024], baseline=render_only,
           baseline_name="rendering alone, same structure", reference={1024: {"Alvarez 2015 (paper, laptop)": 5.0}})
def structure_and_render(side):
    return lambda: render_structure(sample_structure(LAYERS, side, side, seed=0), SETTINGS)
