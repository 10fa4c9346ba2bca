"""Simhon & Dudek 2001, elaboration of hand-drawn sketches: a multi-scale Markov chain steered by a sketch.

- :mod:`.curves` (section 3): curves as unwrapped tangent angles over uniform arc length, repeated
  low-pass filtering into scales, integration back to points, closure correction.
- :mod:`.model` (section 3, eq. 4): training states over scale and history, their similarity, and each
  state's most similar states found through a k-d tree.
- :mod:`.steering` (section 3, eq. 3 and 5): the steered chain that elaborates a sketch, coarse versions of
  curves (the steering component), novelty measures, SVG input.
- :mod:`.measures` (section 3.1's claims): Hausdorff distance to the sketch, turning distribution,
  box-counting dimension.
"""

from .curves import (
    check_curve,
    close_angles,
    close_curve,
    coarse_ring,
    filter_weights,
    gyration_radius,
    integrate_angles,
    lowpass,
    match_size,
    multiscale_angles,
    resample_curve,
    resample_simple,
    tangent_angles,
    total_turning,
    wrap_angle,
)
from .measures import box_counting_dimension, curve_hausdorff, densify, turning_ks, turning_per_sample
from .model import SketchModel, default_weights, state_similarity, train
from .steering import Elaboration, coarsen, copied_runs, crossing_segments, elaborate, sketch_from_svg

__all__ = [
    "box_counting_dimension",
    "curve_hausdorff",
    "densify",
    "turning_ks",
    "turning_per_sample",
    "Elaboration",
    "SketchModel",
    "check_curve",
    "close_angles",
    "close_curve",
    "coarse_ring",
    "coarsen",
    "copied_runs",
    "crossing_segments",
    "default_weights",
    "elaborate",
    "filter_weights",
    "gyration_radius",
    "integrate_angles",
    "lowpass",
    "match_size",
    "multiscale_angles",
    "resample_curve",
    "resample_simple",
    "sketch_from_svg",
    "state_similarity",
    "tangent_angles",
    "total_turning",
    "train",
    "wrap_angle",
]
