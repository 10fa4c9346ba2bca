"""Interactive ipywidgets explorers, one per method, on top of the methods (DESIGN.md).

- :func:`arrangement_explorer`: Hurtut 2009 (:mod:`paperlib.arrangement`): pick an exemplar or
  load an SVG, see its appearance categories, tune T, the synthesis window and a density image,
  re-synthesize.
- :func:`stipple_explorer`: Kim 2009 (:mod:`paperlib.stipple`): learn a stipple library from
  synthetic tone textures (tone-map parameters, iterations, tile size), stipple an image.
- :func:`mlts_explorer`: Alvarez 2015 (:mod:`paperlib.mlts`): every layer and rendering
  parameter of a script, a "random" button (the automatic mode), save and load scripts.
- :func:`strokepattern_explorer`: Barla 2006 (:mod:`paperlib.strokepattern`): the clustering live
  under an epsilon slider, rings, variation, a target path or region picked or drawn with the
  mouse (ipycanvas), synthesize.
- :func:`sketch_explorer`: Simhon 2001 (:mod:`paperlib.sketch`): draw a closed curve with the mouse
  (ipycanvas) or pick a preset sketch, pick the class (coastlines, leaves) and the parameters (order,
  scales, variance, threshold, instantiation, window, closure), see the elaboration update.

Each explorer keeps its update logic in plain methods, so tests and notebooks drive it without a
browser, and renders its figure to PNG (works headless, with the Agg backend and in papermill).
"""

from .arrangement import (
    DENSITY_KINDS,
    EXEMPLARS,
    ArrangementExplorer,
    Drawing,
    arrangement_explorer,
    density_image,
    scaled_window,
)
from .mlts import MLTSExplorer, mlts_explorer
from .sketch import SketchExplorer, sketch_explorer
from .stipple import StippleExplorer, stipple_explorer
from .strokepattern import StrokePatternExplorer, strokepattern_explorer

__all__ = [
    "DENSITY_KINDS", "EXEMPLARS", "ArrangementExplorer", "Drawing", "arrangement_explorer", "density_image",
    "scaled_window", "MLTSExplorer", "mlts_explorer", "StippleExplorer", "stipple_explorer",
    "StrokePatternExplorer", "strokepattern_explorer", "SketchExplorer", "sketch_explorer",
]
