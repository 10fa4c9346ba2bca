"""Shared vector geometry: strokes, elements and closed curves.

This floor imports no other part of paperlib; every method builds on it.
"""

from .curves import drop_repeated_vertices, oriented_ccw, resample_closed_curve, ring_centroid, signed_area
from .strokes import Element, Stroke, as_points

__all__ = [
    "Element",
    "Stroke",
    "as_points",
    "drop_repeated_vertices",
    "oriented_ccw",
    "resample_closed_curve",
    "ring_centroid",
    "signed_area",
]
