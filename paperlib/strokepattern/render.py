"""Drawing stroke patterns with matplotlib: strokes at their true pen width, boxes, neighbour graphs.

Strokes are drawn as the region their pen covers (each polyline dilated by half its width with shapely, round
caps), so widths are in data units and a thickness change (Barla 2006, Fig. 6e) shows at any zoom. SVG output
is :func:`paperlib.geometry.write_svg` on ``Synthesis.elements``.
"""

from __future__ import annotations

import numpy as np
import shapely

from .._checks import check_edges, instance_of, point_array
from ..geometry import Element, OrientedBoxes, Stroke

__all__ = ["plot_boxes", "plot_graph", "plot_strokes"]


def _flat_strokes(items) -> list:
    if isinstance(items, (str, bytes, Stroke)) or not hasattr(items, "__iter__"):
        raise ValueError(f"items must be a sequence of Strokes or Elements, got {type(items).__name__}")
    strokes = []
    for item in items:
        strokes.extend(item.strokes if isinstance(item, Element) else [item])
    if not all(isinstance(s, Stroke) for s in strokes):
        raise ValueError("items must hold Strokes or Elements (plot_strokes draws nothing else)")
    return strokes


def _ink(strokes) -> np.ndarray:
    lines = [shapely.linestrings(s.points) if len(s.points) > 1 else shapely.points(s.points[0]) for s in strokes]
    return shapely.buffer(np.array(lines, dtype=object), np.array([s.width / 2.0 for s in strokes]), quad_segs=4)


def plot_strokes(items, ax=None, *, colors=None, alpha: float = 1.0, autoscale: bool = True):
    """Draw strokes (or elements) at their pen width; returns the axes.

    Parameters
    ----------
    items : sequence of Stroke or Element
    colors : sequence of colours, optional
        One per stroke (overrides the strokes' own colours), e.g. to colour strokes by cluster.
    ax : matplotlib.axes.Axes, optional
        The axes to draw on (default: the current axes).
    alpha : float, default 1
        Opacity of the ink.
    autoscale : bool, default True
        Rescale the axes' view to the data and set an equal aspect ratio.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    import matplotlib.pyplot as plt
    from matplotlib.collections import PathCollection
    from matplotlib.path import Path

    ax = plt.gca() if ax is None else ax
    strokes = _flat_strokes(items)
    if not strokes:
        return ax
    colors = [s.color for s in strokes] if colors is None else list(colors)
    if len(colors) != len(strokes):
        raise ValueError(f"colors needs one entry per stroke ({len(strokes)}), got {len(colors)}")
    paths, facecolors = [], []
    # A closed stroke (a loop) dilates to a ring: its hole is an interior ring, drawn as a compound path
    # (exterior counter-clockwise, holes clockwise: the non-zero rule leaves the holes empty).
    for ink, color in zip(_ink(strokes), colors):
        for part in shapely.get_parts(shapely.orient_polygons(ink)):
            rings = [part.exterior, *part.interiors]
            paths.append(Path.make_compound_path(*(Path(np.asarray(r.coords), closed=True) for r in rings)))
            facecolors.append(color)
    ax.add_collection(PathCollection(paths, facecolors=facecolors, edgecolors="none", alpha=alpha))
    if autoscale:
        ax.autoscale_view()
        ax.set_aspect("equal")
    return ax


def plot_boxes(boxes: OrientedBoxes, ax=None, **style):
    """Outline oriented boxes (e.g. ``PatternAnalysis.boxes``); returns the axes.

    Parameters
    ----------
    boxes : OrientedBoxes
        The boxes to outline.
    ax : matplotlib.axes.Axes, optional
        The axes to draw on (default: the current axes).
    **style
        Keyword arguments of :class:`matplotlib.collections.PolyCollection`, over the defaults
        (no fill, orange edges 0.8 wide).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    instance_of(boxes, OrientedBoxes, "boxes")
    ax = plt.gca() if ax is None else ax
    style = {"facecolors": "none", "edgecolors": "tab:orange", "linewidths": 0.8} | style
    ax.add_collection(PolyCollection(list(boxes.corners()), **style))
    return ax


def plot_graph(positions, edges, ax=None, **style):
    """Draw a neighbour graph: segments between the positions of each edge; returns the axes.

    Parameters
    ----------
    positions : array_like, shape (n, 2)
        Node positions (finite).
    edges : array_like of int, shape (m, 2)
        Node pairs, each node in ``[0, n)``.
    ax : matplotlib.axes.Axes, optional
        The axes to draw on (default: the current axes).
    **style
        Keyword arguments of :class:`matplotlib.collections.LineCollection`, over the defaults
        (grey segments 0.6 wide).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn on.
    """
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    positions = point_array(positions, "positions")
    edges = check_edges(edges, len(positions))
    ax = plt.gca() if ax is None else ax
    style = {"colors": "0.55", "linewidths": 0.6} | style
    ax.add_collection(LineCollection(positions[edges], **style))
    return ax
