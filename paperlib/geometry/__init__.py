"""Shared vector geometry: strokes, elements, closed curves, oriented boxes, Hausdorff, SVG, Lloyd.

This floor imports no other part of paperlib; every method builds on it.
"""

from .boxes import OrientedBox, OrientedBoxes, oriented_bounding_box, oriented_bounding_boxes
from .curves import (
    drop_repeated_vertices,
    oriented_ccw,
    resample_closed_curve,
    resample_open_curve,
    ring_centroid,
    signed_area,
    turning_angles,
)
from .hausdorff import directed_hausdorff, directed_hausdorff_boxes, hausdorff, hausdorff_boxes
from .strokes import Element, StackedStrokes, Stroke, as_elements, as_points, stack_strokes
from .svg import read_svg, svg_string, write_svg
from .voronoi import lloyd_relaxation

__all__ = [
    "Element",
    "OrientedBox",
    "OrientedBoxes",
    "StackedStrokes",
    "Stroke",
    "as_elements",
    "as_points",
    "directed_hausdorff",
    "directed_hausdorff_boxes",
    "drop_repeated_vertices",
    "hausdorff",
    "hausdorff_boxes",
    "lloyd_relaxation",
    "oriented_bounding_box",
    "oriented_bounding_boxes",
    "oriented_ccw",
    "read_svg",
    "resample_closed_curve",
    "resample_open_curve",
    "ring_centroid",
    "signed_area",
    "stack_strokes",
    "svg_string",
    "turning_angles",
    "write_svg",
]
