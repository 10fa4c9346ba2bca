"""Hurtut 2009 pipeline: element features, appearance categorization, arrangement synthesis.

Built on :mod:`paperlib.geometry`, :mod:`paperlib.acontrario` and :mod:`paperlib.pointprocess`.
So far: the appearance features of section 2.1 (:func:`element_features`) and the robust PCA
(ROBPCA) of section 2.2 (:func:`robust_pca`).
"""

from .features import (
    AREA_FRACTION,
    COUNT_SCALE,
    ELONGATION_CAP,
    ORIENTATION_PERIOD,
    crossing_points,
    element_features,
    extremity_points,
    normalized_area,
    normalized_count,
    normalized_elongation,
    normalized_orientation,
)
from .robpca import DistanceCutoffs, ExactFitError, RobustPCA, robust_pca, subset_size

__all__ = [
    "AREA_FRACTION", "COUNT_SCALE", "DistanceCutoffs", "ELONGATION_CAP", "ExactFitError", "ORIENTATION_PERIOD",
    "RobustPCA", "crossing_points", "element_features", "extremity_points", "normalized_area", "normalized_count",
    "normalized_elongation", "normalized_orientation", "robust_pca", "subset_size",
]
