"""Alvarez 2015 MLTS: about 3,000 objects with inclusion and exclusion at 1024 x 1024, and the scaling curve.

"mlts: structure + render, ~3,000 objects, 1024x1024": three layers under the image rectangle
(made in the timed call from a fixed configuration, seed 0):

- 40 rectangles or ellipses of diameter 250 px, aspect 2, exclusion on (Fig. 13's rule);
- 8 triangles or convex polygons per father, diameter 80 px, inclusion and exclusion (Fig. 10);
- 13 random shapes per father, diameter 25 px, inclusion (Fig. 14);

then rendered with the chelsea palette, transparency up to 0.5, a light spot at 300 px and 4 x 4
anti-aliasing samples. Paper: about 3,000 objects "in less than 5 s on a laptop"; target (issue 6):
<= 0.5 s for geometry and rendering. Baseline, same run: the rendering alone of the same
structure, so the ratio shows how the time splits.

"mlts: exclusion layer, objects one by one": Fig. 13's layer (600 objects tried, exclusion) sampled with
``order="sequential"`` (each object finishes its trials and reductions before the next starts, issue 25)
against the default rounds by size; the ratio is what the literal order costs (measured about 9).

"mlts: scaling at constant density": the same three layers on a square image whose area grows
with the number of objects (side 1024 * sqrt(n / 3000), the first layer's ``Max_O`` 40 * n / 3000),
for about n = 3,000 to 30,000 objects. Issue 6 asks that it stay near-linear. Baseline, same
run: the 3,000-object texture made n / 3000 times, i.e. perfectly linear scaling; a ratio near 1
is linear, above 1 is the super-linear part.
"""

import math
from dataclasses import replace
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


SCALING_OBJECTS = [3000, 7500, 15000, 30000]


def scaled(objects):
    """The benchmark's layers on a larger image at the same density: (layers, side)."""
    factor = objects / 3000
    layers = (replace(LAYERS[0], max_objects=round(LAYERS[0].max_objects * factor)),) + LAYERS[1:]
    return layers, round(1024 * math.sqrt(factor))


def make_texture(layers, side):
    return render_structure(sample_structure(layers, side, side, seed=0), SETTINGS)


def linear_reference(objects):
    def run():
        for _ in range(round(objects / 3000)):
            make_texture(LAYERS, 1024)
    return run


@benchmark("mlts: scaling at constant density (n objects)", sizes=SCALING_OBJECTS, baseline=linear_reference,
           baseline_name="the 3,000-object texture n/3000 times (linear)")
def scaling(objects):
    layers, side = scaled(objects)
    return lambda: make_texture(layers, side)


# Fig. 13's layer (notebook alvarez2015_fig13-14_exclusion_inclusion, paper quality): 600 objects tried with
# exclusion, Max_T = 20, s_R = 0.8, Max_DR = 10, on 512 x 512.
FIG13 = Layer(texels=("ellipse", "rectangle", "triangle"), max_objects=600, aspect_ratio=2.0, max_diameter=120.0,
              max_trials=20, size_reduction=0.8, max_reductions=10, exclusion=True, v0=(1.0, 0.0, 0.0),
              v1=(0.0, 1.0, 0.0))


def rounds_order(side):
    return lambda: sample_structure([FIG13], side, side, seed=0)


@benchmark("mlts: exclusion layer, objects one by one (order='sequential')", sizes=[512], baseline=rounds_order,
           baseline_name="the same layer in rounds by size (the default)")
def sequential_order(side):
    """Issue 25: the paper's literal insertion order costs one shapely call per object and diameter."""
    return lambda: sample_structure([FIG13], side, side, seed=0, order="sequential")
