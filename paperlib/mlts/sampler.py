"""The multi-layered object structure of an ML-texture (Alvarez et al. 2015, Definition 1, section 4).

:func:`sample_structure` builds the collection of objects ``O = {O_{m,k}}`` of Definition 1 from a
list of :class:`~paperlib.mlts.layers.Layer` configurations, as section 4's "Implementation"
describes: the first layer is the image rectangle; every object of layer ``m >= 2`` has a father
in layer ``m - 1`` and is a random affine image of one of the layer's texels; an object that
breaks the layer's inclusion or exclusion rule is rejected and a new affine transform is tried;
after ``Max_T`` failed trials the diameter is multiplied by ``s_R``, at most ``Max_DR`` times, and
then the object is given up ("object insertion trials are alternated with shape size reduction",
Figs. 13 and 14). Giving up is reported, never looped on: every layer ends.

Our reading of the details the paper leaves open (each is a parameter or documented choice):

- For every father, ``Max_O`` objects are tried, in order (fathers in their own order).
- Location: object centres are uniform inside the father (a Poisson process restricted to the
  father, section 3's "object location"), drawn by rejection from its bounding box.
- Orientation: each object is turned toward ``V_0`` or ``V_1`` with probability 1/2 each; its
  texel's x axis points at the chosen point (:func:`paperlib.mlts.texels.orientation_angle`).
  A trial whose centre falls exactly on a finite orientation point fails.
- Size: the layer's ``Max_D`` times the vanishing-point factor ``(d / d_far) ** rF``
  (:mod:`paperlib.mlts.layers`), times ``s_R`` per reduction; the aspect ratio is the layer's.
- Inclusion (``Incl``): the object lies in the interior of its father, not touching its boundary
  (shapely ``contains_properly``, the paper's "forcing the child-object not to touch the boundary
  of its parent"). The other mode, clipping to the father, is a rendering option.
- Exclusion (``Excl``): the object does not intersect any object already placed in its layer
  (shapely ``intersects``). Candidates come from a uniform grid of cells of the layer's ``Max_D``
  over the objects' bounding boxes: shapely's STRtree cannot take insertions, and rebuilding it
  after every accepted object would cost more than the grid.

Written by hand: the layer loop and the grid; texels, affine maps and orientation come from
:mod:`paperlib.mlts.texels`; predicates from shapely.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import shapely
from shapely.geometry import Polygon

from .layers import Layer
from .texels import distances_to, orientation_angles, texel, transform_shared

__all__ = ["MLObject", "Structure", "sample_structure"]

# Centres drawn at once when sampling inside a father by rejection from its bounding box.
CENTRE_BATCH = 16


@dataclass(frozen=True)
class MLObject:
    """One object ``O_{m,k}`` of an ML-texture.

    Attributes
    ----------
    layer : int
        Layer index, 0 for the image rectangle (the paper's ``L_1``).
    father : int
        Index (into :attr:`Structure.objects`) of the father object, -1 for the image rectangle.
    kind : str
        Texel kind (``"image"`` for the rectangle).
    center : tuple of float
        Object centre (x, y), pixels.
    diameter : float
        Length of the object along its orientation, after reductions, pixels.
    angle : float
        Orientation (radians from +x toward +y, y down).
    reductions : int
        Diameter reductions the placement needed.
    polygon : ndarray of float, shape (k, 2)
        The object's vertices (x, y).
    """

    layer: int
    father: int
    kind: str
    center: tuple
    diameter: float
    angle: float
    reductions: int
    polygon: np.ndarray = field(repr=False)


@dataclass(frozen=True)
class Structure:
    """The multi-layered object structure of an ML-texture (Definition 1).

    Attributes
    ----------
    width, height : int
        Image size, pixels.
    layers : tuple of Layer
        The configurations of layers 2..N_L (layer 1 is the image rectangle).
    objects : list of MLObject
        Every object, layer by layer; ``objects[0]`` is the image rectangle.
    tried, placed : ndarray of int, shape (N_L,)
        Objects tried and placed per layer (layer 1: 1 and 1). ``tried - placed`` objects were
        given up after all trials and reductions.
    """

    width: int
    height: int
    layers: tuple
    objects: list
    tried: np.ndarray
    placed: np.ndarray

    def layer_objects(self, layer: int) -> list:
        """The objects of layer ``layer`` (0 = the image rectangle)."""
        return [item for item in self.objects if item.layer == layer]


# ---------------------------------------------------------------------------- checks


def _image_size(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ValueError(f"{name} must be a positive integer number of pixels, got {value!r}")
    return int(value)


def _checked_layers(layers) -> tuple:
    layers = tuple(layers)
    for index, layer in enumerate(layers):
        if not isinstance(layer, Layer):
            raise ValueError(f"layer {index + 2} must be a paperlib.mlts.Layer, got {type(layer).__name__}")
    return layers


# ---------------------------------------------------------------------------- exclusion index


class _GridIndex:
    """Bounding boxes of a layer's objects in a uniform grid, for exclusion candidates."""

    def __init__(self, cell: float):
        self.cell = cell
        self.cells: dict = {}
        self.geometries: list = []

    def _keys(self, bounds):
        x0, y0, x1, y1 = (math.floor(value / self.cell) for value in bounds)
        return ((i, j) for i in range(x0, x1 + 1) for j in range(y0, y1 + 1))

    def intersects(self, geometry) -> bool:
        candidates = {index for key in self._keys(geometry.bounds) for index in self.cells.get(key, ())}
        if not candidates:
            return False
        others = [self.geometries[index] for index in sorted(candidates)]
        return bool(shapely.intersects(others, geometry).any())

    def add(self, geometry) -> None:
        index = len(self.geometries)
        self.geometries.append(geometry)
        for key in self._keys(geometry.bounds):
            self.cells.setdefault(key, []).append(index)


# ---------------------------------------------------------------------------- placement


def _centres_in(father, count: int, rng: np.random.Generator) -> np.ndarray:
    """``count`` uniform points (count, 2) inside the polygon ``father`` (rejection from its box)."""
    x0, y0, x1, y1 = father.bounds
    found = []
    total = 0
    while total < count:
        batch = max(CENTRE_BATCH, 2 * (count - total))
        xs, ys = rng.uniform(x0, x1, batch), rng.uniform(y0, y1, batch)
        inside = shapely.contains_xy(father, xs, ys)
        found.append(np.column_stack([xs[inside], ys[inside]]))
        total += int(inside.sum())
    return np.concatenate(found)[:count]


def _far_distance(point, width: int, height: int) -> float:
    """Largest distance from an orientation point to an image corner (inf at infinity)."""
    corners = np.array([(0.0, 0.0), (width, 0.0), (0.0, height), (width, height)])
    return float(distances_to(corners, point).max())


def _orientations(centres, targets, points, fars, exponent: float):
    """Angles toward each centre's orientation point and the vanishing-point size factors."""
    angles, factors = np.zeros(len(centres)), np.ones(len(centres))
    for target, (point, far) in enumerate(zip(points, fars)):
        chosen = targets == target
        if not chosen.any():
            continue
        distance = distances_to(centres[chosen], point)
        angles[chosen] = orientation_angles(centres[chosen], point)
        if exponent > 0 and math.isfinite(far):
            factors[chosen] = np.minimum(1.0, distance / far) ** exponent
    return angles, factors


def _place(layer: Layer, father, index: _GridIndex | None, points, fars, rng):
    """One object for ``father``: (kind, centre, diameter, angle, reductions, polygon, geometry) or None.

    The ``Max_T`` trials of one diameter are drawn and tested together: the first candidate that
    keeps the rules wins, exactly as if they were tried one by one (nothing is placed between
    them).
    """
    kind = layer.texels[int(rng.integers(len(layer.texels)))]
    shape = texel(kind, rng)
    diameter = layer.max_diameter
    for reductions in range(layer.max_reductions + 1):
        centres = _centres_in(father, layer.max_trials, rng)
        targets = rng.integers(2, size=layer.max_trials)
        # a centre on a finite orientation point has no direction: that trial fails
        usable = np.ones(layer.max_trials, dtype=bool)
        for target, point in enumerate(points):
            usable &= ~((targets == target) & (distances_to(centres, point) == 0))
        centres, targets = centres[usable], targets[usable]
        if not len(centres):
            diameter *= layer.size_reduction
            continue
        angles, factors = _orientations(centres, targets, points, fars, layer.vanishing)
        sizes = diameter * factors
        candidates = transform_shared(shape, centres, sizes, layer.aspect_ratio, angles)
        geometries = shapely.polygons(candidates)
        keeps = shapely.contains_properly(father, geometries) if layer.inclusion else np.ones(len(sizes), bool)
        for trial in np.flatnonzero(keeps):
            if index is None or not index.intersects(geometries[trial]):
                center = (float(centres[trial, 0]), float(centres[trial, 1]))
                return (kind, center, float(sizes[trial]), float(angles[trial]), reductions, candidates[trial],
                        geometries[trial])
        diameter *= layer.size_reduction
    return None


def sample_structure(layers, width: int, height: int, seed=None) -> Structure:
    """Sample the object structure of an ML-texture (section 4, "Implementation").

    Parameters
    ----------
    layers : sequence of Layer
        Configurations of layers 2..N_L (the paper's first layer, the image rectangle, is
        implicit). May be empty: the structure is then the rectangle alone.
    width, height : int
        Image size in pixels.
    seed : None, int or numpy.random.Generator, optional
        The paper's ``Seed(L)``: a seed fixes the structure bit for bit.

    Returns
    -------
    Structure

    Raises
    ------
    ValueError
        Non-integer or non-positive image size, an item that is not a Layer.

    References
    ----------
    Alvarez, Gousseau, Morel, Salgado (2015), Definition 1, sections 3 (interaction principles,
    object spatial organization) and 4 (layer parameters, Implementation), Figs. 13-14.
    """
    width, height = _image_size(width, "width"), _image_size(height, "height")
    layers = _checked_layers(layers)
    rng = np.random.default_rng(seed)
    rectangle = np.array([[0.0, 0.0], [width, 0.0], [width, height], [0.0, height]])
    objects = [MLObject(0, -1, "image", (width / 2, height / 2), math.hypot(width, height), 0.0, 0, rectangle)]
    geometries = [Polygon(rectangle)]
    tried, placed = [1], [1]
    fathers = [0]
    for number, layer in enumerate(layers, start=1):
        points = (layer.v0, layer.v1)
        fars = [_far_distance(point, width, height) for point in points]
        index = _GridIndex(layer.max_diameter) if layer.exclusion else None
        children = []
        for father in fathers:
            if not geometries[father].area > 0:
                continue  # no point lies inside a degenerate father: its children are not tried
            shapely.prepare(geometries[father])
            for _ in range(layer.max_objects):
                found = _place(layer, geometries[father], index, points, fars, rng)
                if found is None:
                    continue
                kind, center, size, angle, reductions, polygon, geometry = found
                children.append(len(objects))
                objects.append(MLObject(number, father, kind, center, size, angle, reductions, polygon))
                geometries.append(geometry)
                if index is not None:
                    index.add(geometry)
        tried.append(len(fathers) * layer.max_objects)  # degenerate fathers' children count as given up
        placed.append(len(children))
        fathers = children
    return Structure(width, height, layers, objects, np.array(tried), np.array(placed))

