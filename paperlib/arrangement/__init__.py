"""Hurtut 2009 pipeline: element features, appearance categorization, arrangement synthesis.

Built on :mod:`paperlib.geometry`, :mod:`paperlib.acontrario` and :mod:`paperlib.pointprocess`:

- :func:`element_features`: the five appearance features of section 2.1, with extremities and
  crossings read on the strokes or, for drawings made of overlapping pen lines, on the centrelines
  of the ink (:func:`ink_centrelines`, :func:`overdrawn_fraction`);
- :func:`categorize`: section 2.2, by default a recursive a contrario splitting on one feature's
  modes at a time (area first), or with ``method="paper"`` the paper's recipe: maximal meaningful
  modes of the area histogram, then of the first robust principal component (:func:`robust_pca`,
  ROBPCA) of the other features;
- :func:`fit` and :func:`synthesize`: the multitype Strauss hard-core model of section 3 fitted
  on element positions, simulated by Metropolis-Hastings in any window (with a density brush),
  reference elements pasted per category (section 3.3); :func:`render` and ``Arrangement.to_svg``;
- ``fit(..., interaction="box_hausdorff" | "box_gap")``: section 4.3's extension, interactions on
  distances between the elements' bounding boxes (:mod:`.box_interaction`).
"""

from .categorize import (
    DEFAULT_BINS,
    METHODS,
    MIN_FIT_SIZE,
    MIN_SPLIT_SIZE,
    RECURSIVE_FEATURES,
    AreaCategory,
    Categorization,
    FeatureHistogram,
    Split,
    adjusted_rand_index,
    categorize,
    recursive_feature_values,
    separability_ceiling,
    unwrapped_orientation,
)
from .features import (
    AREA_FRACTION,
    COUNT_SCALE,
    ELONGATION_CAP,
    ORIENTATION_PERIOD,
    TOPOLOGY_READINGS,
    crossing_points,
    element_features,
    extremity_points,
    minimum_box_areas,
    normalized_area,
    normalized_count,
    normalized_elongation,
    normalized_orientation,
)
from .ink import MAX_INK_PIXELS, OVERDRAWN_MEDIAN, ink_centrelines, overdrawn_fraction
from .box_interaction import BOX_DISTANCES, box_distance_matrix
from .robpca import DistanceCutoffs, ExactFitError, RobustPCA, robust_pca, subset_size
from .synthesis import INTERACTIONS, Arrangement, ArrangementModel, element_positions, fit, render, synthesize

__all__ = [
    "AREA_FRACTION", "Arrangement", "MAX_INK_PIXELS", "OVERDRAWN_MEDIAN", "TOPOLOGY_READINGS", "ink_centrelines",
    "overdrawn_fraction", "BOX_DISTANCES", "INTERACTIONS", "ArrangementModel", "AreaCategory", "COUNT_SCALE", "Categorization",
    "DEFAULT_BINS", "DistanceCutoffs", "METHODS", "RECURSIVE_FEATURES", "Split", "recursive_feature_values", "ELONGATION_CAP", "ExactFitError", "FeatureHistogram", "MIN_FIT_SIZE",
    "MIN_SPLIT_SIZE", "ORIENTATION_PERIOD", "RobustPCA", "adjusted_rand_index", "box_distance_matrix", "categorize", "crossing_points",
    "element_features", "element_positions", "extremity_points", "fit", "minimum_box_areas", "normalized_area", "normalized_count",
    "normalized_elongation", "normalized_orientation", "render", "robust_pca", "separability_ceiling", "subset_size", "synthesize",
    "unwrapped_orientation",
]
