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

- For every father, ``Max_O`` objects are tried (fathers in their own order); each object draws
  its texel once, and its trials are new affine transforms of it.
- Location: object centres are uniform inside the father (a Poisson process restricted to the
  father, section 3's "object location"), drawn by rejection from its bounding box.
- Orientation: each object is turned toward ``V_0`` or ``V_1`` with probability 1/2 each; its
  texel's x axis points at the chosen point (:func:`paperlib.mlts.texels.orientation_angle`).
  A trial whose centre falls exactly on a finite orientation point fails.
- Size: the layer's ``Max_D`` times the vanishing-point factor ``(d / d_far) ** rF``
  (:mod:`paperlib.mlts.layers`), times ``s_R`` per reduction; the aspect ratio is the layer's.
- Inclusion (``Incl``): the object lies in the interior of its father, not touching its boundary
  (shapely ``contains_properly`` against the prepared father, the paper's "forcing the
  child-object not to touch the boundary of its parent"). The other mode, clipping to the
  father, is a rendering option.
- Exclusion (``Excl``): the object does not intersect any object already placed in its layer
  (shapely ``intersects``, candidates from STRtree queries).
- Order of insertion ("object insertion trials are alternated with shape size reduction", Figs.
  13-14), ``order="rounds"`` (the default): a layer is filled in rounds, one per diameter level.
  Round r gives every object still unplaced its ``Max_T`` trials at diameter ``Max_D * s_R**r``,
  objects in order, each against every object placed before it (earlier rounds and earlier in this
  round); the objects that fail all of them wait for round r + 1. So every object alternates
  trials and reductions as in the paper, and when the layer has no exclusion rule (objects do not
  interact) this is exactly the object-by-object process. Under exclusion it differs from
  finishing each object's reductions before the next object starts in one way: the larger trials
  of all objects come first and the smaller ones fill the gaps, the order a packing would use. We
  chose it because it lets every round run as a few vectorised shapely calls (about 3,000 objects
  in a fraction of a second, section 4's "less than 5 s" being the reference); the paper does not
  say which order its implementation uses. ``order="sequential"`` is the other reading, Fig. 13's
  caption taken literally ("all objects are iteratively added ... with the constraint of not
  intersecting any of the former ones"): object k makes all its trials and reductions before
  object k + 1 starts, so an early object that fails at full size is placed small at once and a
  later object may then fit large. The notebook of Figs. 13-14 measures what the two change on
  Fig. 13's layer: the sequential order places 1.1-1.5 times as many objects, smaller ones, at
  about the same packing density and rejected trials, about ten times slower (one shapely call per
  object and diameter).

Speed, without changing the result: trials are drawn for many objects at once; in layers
without exclusion ``TRIAL_CHUNK`` trials per object at a time (most objects need the first
few); under inclusion, a few vertices of each trial (``PROBE_VERTICES``) are tested against the
father with ``contains_xy`` before its polygon is built, a necessary condition that rejects most
failing trials at a fraction of the cost.

Written by hand: the layer loop and the rounds; texels, affine maps and orientation come from
:mod:`paperlib.mlts.texels`; predicates and spatial indexes from shapely (prepared geometries,
STRtree).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import shapely
from shapely.geometry import Polygon

from .._checks import as_generator, budget, check_budget
from .layers import Layer, checked_layers
from .raster import coverage
from .texels import affine_map, distances_to, orientation_angles, texel_batch

__all__ = ["MLObject", "Structure", "rule_violations", "sample_structure"]

#: Trials drawn at once per object in a layer without exclusion (most objects need only the first few).
TRIAL_CHUNK = 4
#: Rejection rounds for a centre inside a father before the trial fails (round k draws 2**k points
#: per centre, at most MAX_CENTRE_DRAWS and CENTRE_POINTS in all: only slivers of less than ~1e-5
#: of their bounding box ever get to the end).
MAX_CENTRE_ROUNDS = 24
MAX_CENTRE_DRAWS = 1024
CENTRE_POINTS = 2**20
#: Vertices of each trial tested against the father before its polygon is built (inclusion layers):
#: most trials of crowded layers fail there, at a fraction of the cost of building the polygon.
PROBE_VERTICES = 8
#: Trials drawn and tested together at most (objects per block: this over Max_T); bounds the memory
#: of very large layers.
ROUND_TRIALS = 32768


@dataclass(frozen=True)
class MLObject:
    """One object ``O_{m,k}`` of an ML-texture.

    Parameters
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

    Parameters
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
    trials : ndarray of int, shape (N_L,), optional
        Placement trials made per layer (layer 1: 0), counted as the sequential process makes
        them: an object's trials up to and including the one that succeeds, all of them when it
        is given up; ``trials - placed`` were rejected. None for structures built by hand.
    order : str
        The insertion order used (``"rounds"`` or ``"sequential"``, :func:`sample_structure`).
    """

    width: int
    height: int
    layers: tuple
    objects: list
    tried: np.ndarray
    placed: np.ndarray
    trials: np.ndarray | None = None
    order: str = "rounds"

    def layer_objects(self, layer: int) -> list:
        """The objects of layer ``layer`` (0 = the image rectangle).

        Parameters
        ----------
        layer : int
            Layer index: 0 for the image rectangle, m - 1 for the paper's ``L_m``.

        Returns
        -------
        list of MLObject
            Its objects, in insertion order.
        """
        return [item for item in self.objects if item.layer == layer]


# ---------------------------------------------------------------------------- checks


def _image_size(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ValueError(f"{name} must be a positive integer number of pixels, got {value!r}")
    return int(value)


# ---------------------------------------------------------------------------- slots and candidates


@dataclass(frozen=True)
class _Slots:
    """The objects a layer tries, one slot per (father, k < Max_O), with their texels.

    ``vertices[offsets[i]:offsets[i + 1]]`` is slot ``i``'s texel (drawn once per object: the
    trials of an object are new affine transforms of the same texel).
    """

    fathers: np.ndarray  # object index of each slot's father
    father_shapes: np.ndarray  # shapely polygons (prepared), one per slot
    father_frames: np.ndarray  # (n, 3, 2): centre c and axes e1, e2 of the father's box c + u e1 + v e2
    kinds: np.ndarray  # texel kind of each slot (str)
    vertices: np.ndarray  # (V, 2) all texels, slot after slot
    offsets: np.ndarray  # (n + 1,)
    probes: np.ndarray  # (n, PROBE_VERTICES, 2) a few vertices of each texel, for the inclusion pre-test


@dataclass(frozen=True)
class _Candidates:
    """Trial placements: ``rows`` (slot of each), centres, sizes, angles; polygons only where still possible.

    ``keeps`` starts as "may keep the rules" (usable centre, probe vertices inside the father
    under inclusion); shapely polygons are built for those candidates only (``shapes`` holds
    None elsewhere), with their vertices at ``vertices[offsets[j]:offsets[j + 1]]`` for the j-th
    built candidate ``built[j]``.
    """

    rows: np.ndarray
    centres: np.ndarray
    sizes: np.ndarray
    angles: np.ndarray
    keeps: np.ndarray
    built: np.ndarray
    vertices: np.ndarray
    offsets: np.ndarray
    shapes: np.ndarray

    position: np.ndarray  # position in ``built`` of each candidate, -1 where no polygon was built

    def polygon(self, index: int) -> np.ndarray:
        j = self.position[index]
        return self.vertices[self.offsets[j]:self.offsets[j + 1]].copy()


def _layer_slots(layer: Layer, fathers: list, shapes: list, frames: list, rng: np.random.Generator) -> _Slots:
    """Slots of every father with positive area (no point lies inside a degenerate father)."""
    usable = [father for father in fathers if shapes[father].area > 0]
    father_of = np.repeat(np.array(usable, dtype=np.int64), layer.max_objects)
    father_shapes = np.array([shapes[father] for father in father_of], dtype=object)
    shapely.prepare(father_shapes)
    kinds = np.array(layer.texels)[rng.integers(len(layer.texels), size=len(father_of))]
    drawn = [None] * len(father_of)
    for kind in layer.texels:  # one vectorised draw per kind, in the layer's order
        rows = np.flatnonzero(kinds == kind)
        for row, vertices in zip(rows, texel_batch(kind, len(rows), rng)):
            drawn[row] = vertices
    counts = np.array([len(vertices) for vertices in drawn], dtype=np.int64)
    vertices = np.concatenate(drawn) if drawn else np.zeros((0, 2))
    probes = np.array([shape[np.arange(PROBE_VERTICES) * len(shape) // PROBE_VERTICES] for shape in drawn])
    father_frames = np.array([frames[father] for father in father_of]).reshape(-1, 3, 2)
    return _Slots(father_of, father_shapes, father_frames, kinds, vertices, np.concatenate([[0], np.cumsum(counts)]),
                  probes.reshape(-1, PROBE_VERTICES, 2))


def _frame(centre, diameter: float, aspect: float, angle: float) -> np.ndarray:
    """The box of an object: its texel's [-0.5, 0.5]^2 under the object's affine map, as (c, e1, e2)."""
    cos, sin = math.cos(angle), math.sin(angle)
    return np.array([centre, (diameter * cos, diameter * sin), (-diameter / aspect * sin, diameter / aspect * cos)])


def _centres_in_fathers(slots: _Slots, rows: np.ndarray, rng: np.random.Generator):
    """Uniform points inside each row's father, and which were found.

    Rejection from the father's own box (its texel's square under its affine map, so an
    elongated, turned father is not sampled through its much larger axis-aligned box): round k
    draws 2**k points per missing centre and keeps the first inside, so thin fathers take a few
    rounds, not hundreds.
    """
    frames = slots.father_frames[rows]
    centres = frames[:, 0].copy()
    missing = np.arange(len(rows))
    for attempt in range(MAX_CENTRE_ROUNDS):
        if not missing.size:
            break
        draws = max(1, min(2**attempt, MAX_CENTRE_DRAWS, CENTRE_POINTS // len(missing)))
        u, v = rng.uniform(-0.5, 0.5, size=(2, len(missing), draws, 1))
        box = frames[missing][:, None]
        points = (box[..., 0, :] + u * box[..., 1, :] + v * box[..., 2, :]).reshape(-1, 2)
        inside = shapely.contains_xy(np.repeat(slots.father_shapes[rows[missing]], draws), points[:, 0], points[:, 1])
        inside = inside.reshape(-1, draws)
        found = inside.any(axis=1)
        first = np.arange(len(missing)) * draws + inside.argmax(axis=1)
        centres[missing[found]] = points[first[found]]
        missing = missing[~found]
    found = np.ones(len(rows), dtype=bool)
    found[missing] = False  # a sliver father: those trials fail rather than loop
    return centres, found


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


def _probe_test(slots: _Slots, rows, centres, sizes, aspect: float, angles, inclusion: bool,
                occupancy: "_Occupancy | None") -> np.ndarray:
    """Whether each trial's probe vertices pass the cheap pre-tests, tested one vertex at a time.

    A trial fails as soon as a probe vertex lies outside its father (inclusion) or strictly
    inside an object already placed (``occupancy``, exclusion): both are necessary conditions
    of the full test, so no trial the rules would keep is lost. Most failing trials of a crowded
    layer fail at the first vertex, so the later ones are tested on few trials.
    """
    passing = np.ones(len(rows), dtype=bool)
    active = np.arange(len(rows))
    for vertex in range(PROBE_VERTICES):
        if not active.size:
            break
        point = affine_map(slots.probes[rows[active], vertex], sizes[active], aspect, angles[active],
                            centres[active])
        ok = np.ones(len(active), dtype=bool)
        if inclusion:
            ok = shapely.contains_xy(slots.father_shapes[rows[active]], point[:, 0], point[:, 1])
        if occupancy is not None:
            ok[ok] = ~occupancy.inside(point[ok])
        passing[active[~ok]] = False
        active = active[ok]
    return passing


def _polygons(slots: _Slots, rows, centres, sizes, aspect: float, angles):
    """Every row's texel under its affine map: flat vertices, offsets and shapely polygons."""
    counts = np.diff(slots.offsets)[rows]
    offsets = np.concatenate([[0], np.cumsum(counts)])
    owner = np.repeat(np.arange(len(rows)), counts)
    texel_vertices = slots.vertices[slots.offsets[rows][owner] + np.arange(offsets[-1]) - offsets[:-1][owner]]
    vertices = affine_map(texel_vertices, sizes[owner], aspect, angles[owner], centres[owner])
    shapes = shapely.polygons(shapely.linearrings(vertices, indices=owner)) if len(rows) else np.zeros(0, object)
    return vertices, offsets, shapes


def _candidates(slots: _Slots, rows, layer: Layer, diameter: float, points, fars, rng,
                occupancy: "_Occupancy | None" = None) -> _Candidates:
    """One trial placement per entry of ``rows`` at ``diameter`` (before the vanishing-point factor).

    Polygons are built only for the trials that pass the cheap pre-tests: probe vertices inside
    the father (inclusion) and none inside an object already placed (``occupancy``, exclusion).
    """
    centres, keeps = _centres_in_fathers(slots, rows, rng)
    targets = rng.integers(2, size=len(rows))
    for target, point in enumerate(points):
        # a centre on a finite orientation point has no direction: that trial fails
        keeps &= ~((targets == target) & (distances_to(centres, point) == 0))
    angles, sizes = np.zeros(len(rows)), np.full(len(rows), diameter)
    angles[keeps], factors = _orientations(centres[keeps], targets[keeps], points, fars, layer.vanishing)
    sizes[keeps] *= factors
    if (layer.inclusion or occupancy is not None) and keeps.any():
        kept = np.flatnonzero(keeps)
        keeps[kept] = _probe_test(slots, rows[kept], centres[kept], sizes[kept], layer.aspect_ratio, angles[kept],
                                  layer.inclusion, occupancy)
    built = np.flatnonzero(keeps)
    vertices, offsets, built_shapes = _polygons(slots, rows[built], centres[built], sizes[built],
                                                layer.aspect_ratio, angles[built])
    shapes = np.full(len(rows), None, dtype=object)
    shapes[built] = built_shapes
    position = np.full(len(rows), -1, dtype=np.int64)
    position[built] = np.arange(len(built))
    if layer.inclusion and built.size:
        keeps[built] = shapely.contains_properly(slots.father_shapes[rows[built]], built_shapes)
    return _Candidates(rows, centres, sizes, angles, keeps, built, vertices, offsets, shapes, position)


class _Occupancy:
    """The objects placed so far in an exclusion layer: their STRtree and a pixel map of which covers what.

    ``labels[row, col]`` is the object covering pixel (row, col)'s centre (-1: none; objects of
    an exclusion layer do not overlap). A trial with a vertex strictly inside a placed object
    intersects it, so :meth:`inside` rejects it before its polygon is built: the pixel map
    names the one object to test each vertex against (shapely ``contains_xy``), so the test is
    exact, never rejecting a trial the full test would keep.
    """

    def __init__(self, width: int, height: int):
        self.labels = np.full((height, width), -1, dtype=np.int64)
        self.shapes: list = []
        self.shapes_array = np.zeros(0, dtype=object)
        self._tree = None

    def add(self, shapes: list, polygons: list) -> None:
        shapely.prepare(shapes)  # many point tests per object follow
        for shape, polygon in zip(shapes, polygons):
            row0, col0, mask = coverage(polygon, self.labels.shape, samples=1)  # 1 sample: the pixel centre
            self.labels[row0:row0 + mask.shape[0], col0:col0 + mask.shape[1]][mask > 0] = len(self.shapes)
            self.shapes.append(shape)
        self.shapes_array = np.array(self.shapes, dtype=object)
        self._tree = None

    def tree(self) -> shapely.STRtree:
        if self._tree is None:
            self._tree = shapely.STRtree(self.shapes)
        return self._tree

    def inside(self, points: np.ndarray) -> np.ndarray:
        """Whether each point (m, 2) lies strictly inside a placed object."""
        x, y = points[:, 0], points[:, 1]
        height, width = self.labels.shape
        on_image = (x >= 0) & (x < width) & (y >= 0) & (y < height)
        owner = np.full(len(x), -1, dtype=np.int64)
        owner[on_image] = self.labels[y[on_image].astype(np.int64), x[on_image].astype(np.int64)]
        covered = np.flatnonzero(owner >= 0)
        inside = np.zeros(len(x), dtype=bool)
        if covered.size:
            inside[covered] = shapely.contains_xy(self.shapes_array[owner[covered]], x[covered], y[covered])
        return inside


# ---------------------------------------------------------------------------- placement


def _first_in_each_row(keeps: np.ndarray, trials: int) -> np.ndarray:
    """Index of the first True candidate of each group of ``trials`` consecutive ones, -1 if none."""
    grid = keeps.reshape(-1, trials)
    first = grid.argmax(axis=1) + trials * np.arange(len(grid))
    return np.where(grid.any(axis=1), first, -1)


def _independent_round(slots, pending, layer, diameter, points, fars, rng):
    """Trials of one diameter for objects that do not interact (no exclusion), ``TRIAL_CHUNK`` at a time.

    Without exclusion an object's placement does not depend on the others', so trying every
    pending object's trials chunk by chunk is the sequential process exactly.
    """
    chosen, used = [], 0
    left = layer.max_trials
    while left and pending.size:
        trials = min(TRIAL_CHUNK, left)
        candidates = _candidates(slots, np.repeat(pending, trials), layer, diameter, points, fars, rng)
        first = _first_in_each_row(candidates.keeps, trials)
        chosen += [(int(pending[row]), candidates, int(index)) for row, index in enumerate(first) if index >= 0]
        used += _trials_used(first, trials)
        pending = pending[first < 0]
        left -= trials
    return chosen, pending, used


def _exclusion_round(slots, pending, layer, diameter, occupancy: _Occupancy, points, fars, rng):
    """Trials of one diameter under exclusion: pending objects in order, each against everything placed.

    All ``Max_T`` trials of every pending object are drawn together; their intersections with the
    objects placed before (``occupancy``) come from one STRtree query, and the objects of this
    round are resolved in order by :func:`_resolve_in_order`.
    """
    trials = layer.max_trials
    candidates = _candidates(slots, np.repeat(pending, trials), layer, diameter, points, fars, rng, occupancy)
    alive = candidates.keeps.copy()
    if occupancy.shapes and alive.any():
        hits, _ = occupancy.tree().query(candidates.shapes[alive], predicate="intersects")
        alive[np.flatnonzero(alive)[hits]] = False
    chosen = _resolve_in_order(candidates.shapes, alive, trials)
    placed = chosen >= 0
    return [(int(slot), candidates, int(index)) for slot, index in zip(pending[placed], chosen[placed])], \
        pending[~placed], _trials_used(chosen, trials)


def _trials_used(first: np.ndarray, trials: int) -> int:
    """Trials the sequential process makes: up to and including the first success, all ``trials`` on failure.

    ``first[i]`` is the index (in a block of ``trials`` candidates per object) of object i's chosen
    trial, -1 when none succeeded.
    """
    rows = np.arange(len(first))
    placed = first >= 0
    return int(np.sum(first[placed] - rows[placed] * trials + 1) + np.sum(~placed) * trials)


def _resolve_in_order(shapes: np.ndarray, alive: np.ndarray, trials: int) -> np.ndarray:
    """Object i (trials ``i * trials ...``) takes its first alive trial not intersecting an earlier choice.

    The sequential rule within a round, computed without testing every pair: a chosen shape
    removes the later objects' alive trials that intersect it (one STRtree query per choice, so
    the work follows the choices' neighbourhoods, never all pairs of trials). Returns the chosen
    candidate per object, -1 if none.
    """
    alive = alive.copy()
    live = np.flatnonzero(alive)
    tree = shapely.STRtree(shapes[live]) if live.size else None
    chosen = np.full(len(alive) // trials, -1, dtype=np.int64)
    for row in range(len(chosen)):
        group = alive[row * trials:(row + 1) * trials]
        if not group.any():
            continue
        chosen[row] = index = row * trials + int(group.argmax())
        hits = live[tree.query(shapes[index], predicate="intersects")]
        alive[hits[hits >= (row + 1) * trials]] = False  # later objects' trials only
    return chosen


def _place_layer(layer: Layer, slots: _Slots, width: int, height: int, points, fars, rng,
                 order: str = "rounds") -> tuple[list, int]:
    """(slot, centre, size, angle, reductions, polygon, shape) of every placed object, in slot order, and trials made.

    ``order="rounds"``: each round runs on blocks of at most ``ROUND_TRIALS / Max_T`` objects, in
    order, every block against all objects placed before it: the same rule as one block (every
    object against everything placed before it), with bounded memory. ``order="sequential"``
    (exclusion layers): :func:`_sequential_exclusion`. Without exclusion objects do not interact
    and both orders are the same process; the rounds are used.
    """
    occupancy = _Occupancy(width, height) if layer.exclusion else None
    if order == "sequential" and occupancy is not None:
        return _sequential_exclusion(layer, slots, occupancy, points, fars, rng)
    pending = np.arange(len(slots.fathers))
    placed, used = [], 0
    diameter = layer.max_diameter
    for reductions in range(layer.max_reductions + 1):
        waiting = []
        block_size = max(1, ROUND_TRIALS // layer.max_trials)
        for block in np.array_split(pending, max(1, -(-len(pending) // block_size))):
            if not block.size:
                continue
            if occupancy is not None:
                chosen, left, count = _exclusion_round(slots, block, layer, diameter, occupancy, points, fars, rng)
            else:
                chosen, left, count = _independent_round(slots, block, layer, diameter, points, fars, rng)
            new = _placements(chosen, reductions)
            if occupancy is not None:
                occupancy.add([item[6] for item in new], [item[5] for item in new])
            placed += new
            used += count
            waiting.append(left)
        pending = np.concatenate(waiting) if waiting else pending
        if not pending.size:
            break
        diameter *= layer.size_reduction
    return sorted(placed, key=lambda item: item[0]), used


def _placements(chosen, reductions: int) -> list:
    return [(slot, candidates.centres[index].copy(), float(candidates.sizes[index]), float(candidates.angles[index]),
             reductions, candidates.polygon(index), candidates.shapes[index]) for slot, candidates, index in chosen]


def _sequential_exclusion(layer: Layer, slots: _Slots, occupancy: "_Occupancy", points, fars, rng) -> tuple[list, int]:
    """The paper's order read literally: objects one by one, each finishing its trials and reductions.

    Object k gets ``Max_T`` trials at ``Max_D``, then ``Max_T`` at ``Max_D s_R``, ... (at most
    ``Max_DR`` reductions), each trial tested against every object placed before it; only then does
    object k + 1 start (Fig. 13's caption: "all objects are iteratively added by MLTS with the
    constraint of not intersecting any of the former ones. Object insertion trials are alternated
    with shape size reduction"). One shapely call per object and diameter: slower than the rounds.
    """
    placed, used = [], 0
    for slot in range(len(slots.fathers)):
        diameter = layer.max_diameter
        for reductions in range(layer.max_reductions + 1):
            chosen, _, count = _exclusion_round(slots, np.array([slot]), layer, diameter, occupancy, points, fars, rng)
            used += count
            if chosen:
                new = _placements(chosen, reductions)
                occupancy.add([item[6] for item in new], [item[5] for item in new])
                placed += new
                break
            diameter *= layer.size_reduction
    return placed, used


#: Insertion orders of :func:`sample_structure` (module docstring, "Order of insertion").
ORDERS = ("rounds", "sequential")


#: Default budget of :func:`sample_structure`: the most placement trials of one layer
#: (fathers x Max_O x Max_T x (Max_DR + 1)), 2e7. Raise it with the ``max_trials`` keyword.
MAX_LAYER_TRIALS = 20_000_000


def sample_structure(layers, width: int, height: int, seed=None, *, max_trials: int = MAX_LAYER_TRIALS,
                     order: str = "rounds") -> Structure:
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
    max_trials : int
        Budget: the most placement trials one layer may make, ``fathers x Max_O x Max_T x
        (Max_DR + 1)`` with the fathers actually placed (default :data:`MAX_LAYER_TRIALS`); nested
        layers multiply, so a deep script is stopped with a ValueError before the layer that
        would exceed it.
    order : {"rounds", "sequential"}
        Order of insertion in exclusion layers (module docstring): ``"rounds"`` (default) gives
        every object its trials at one diameter before any object is reduced; ``"sequential"``
        inserts objects one by one, each finishing all its trials and reductions before the next
        starts (Fig. 13's caption read literally). Layers without exclusion are the same process
        either way (objects do not interact) and are sampled identically.

    Returns
    -------
    Structure

    Raises
    ------
    ValueError
        Non-integer or non-positive image size, an item that is not a Layer, a layer above
        ``max_trials``; an ``order`` not in :data:`ORDERS`.

    References
    ----------
    Alvarez, Gousseau, Morel, Salgado (2015), Definition 1, sections 3 (interaction principles,
    object spatial organization) and 4 (layer parameters, Implementation), Figs. 13-14.
    """
    width, height = _image_size(width, "width"), _image_size(height, "height")
    layers = checked_layers(layers)
    rng = as_generator(seed, "seed")
    max_trials = budget(max_trials, "max_trials")
    if not isinstance(order, str) or order not in ORDERS:
        raise ValueError(f"order must be one of {ORDERS}, got {order!r:.80}")
    rectangle = np.array([[0.0, 0.0], [width, 0.0], [width, height], [0.0, height]])
    objects = [MLObject(0, -1, "image", (width / 2, height / 2), math.hypot(width, height), 0.0, 0, rectangle)]
    geometries = [Polygon(rectangle)]
    frames = [np.array([(width / 2, height / 2), (width, 0.0), (0.0, height)])]
    tried, placed, used = [1], [1], [0]
    fathers = [0]
    for number, layer in enumerate(layers, start=1):
        points = (layer.v0, layer.v1)
        fars = [_far_distance(point, width, height) for point in points]
        # texels and placements from separate streams: changing T(L_m) leaves the trials' centres and
        # orientations as they were (Figs. 12 and 18 compare textures that differ only by shape)
        trials = len(fathers) * layer.max_objects * layer.max_trials * (layer.max_reductions + 1)
        check_budget(trials, max_trials, "max_trials", f"placement trials in layer {number + 1}")
        texel_rng, placement_rng = rng.spawn(2)
        slots = _layer_slots(layer, fathers, geometries, frames, texel_rng)
        children = []
        placements, count = _place_layer(layer, slots, width, height, points, fars, placement_rng, order)
        for slot, centre, size, angle, reductions, polygon, shape in placements:
            children.append(len(objects))
            objects.append(MLObject(number, int(slots.fathers[slot]), str(slots.kinds[slot]),
                                    (float(centre[0]), float(centre[1])), size, angle, reductions, polygon))
            geometries.append(shape)
            frames.append(_frame(centre, size, layer.aspect_ratio, angle))
        tried.append(len(fathers) * layer.max_objects)  # degenerate fathers' children count as given up
        placed.append(len(children))
        used.append(count)
        fathers = children
    return Structure(width, height, layers, objects, np.array(tried), np.array(placed), np.array(used), order)


def rule_violations(structure: Structure) -> dict:
    """Objects that break their layer's inclusion or exclusion rule, counted by shapely.

    An independent check of :func:`sample_structure` (the notebooks record it, the tests assert
    zero): for every layer whose ``Excl`` is on, the number of intersecting pairs of its objects
    (shapely STRtree query, predicate ``intersects``); for every layer whose ``Incl`` is on, the
    number of objects not properly contained in their father (``contains_properly``).

    Parameters
    ----------
    structure : Structure
        A sampled structure (:func:`sample_structure`).

    Returns
    -------
    dict
        ``{"exclusion": int, "inclusion": int, "exclusion_per_layer": list, "inclusion_per_layer":
        list}``; the per-layer lists have one entry per drawn layer (``None`` where the rule is off).
    """
    if not isinstance(structure, Structure):
        raise ValueError(f"structure must be a paperlib.mlts.Structure, got {type(structure).__name__}")
    shapes = np.array([Polygon(item.polygon) for item in structure.objects], dtype=object)
    layer_of = np.array([item.layer for item in structure.objects])
    fathers = np.array([item.father for item in structure.objects])
    exclusion, inclusion = [], []
    for number, layer in enumerate(structure.layers, start=1):
        members = np.flatnonzero(layer_of == number)
        exclusion.append(_intersecting_pairs(shapes[members]) if layer.exclusion else None)
        if layer.inclusion and len(members):
            inside = shapely.contains_properly(shapes[fathers[members]], shapes[members])
            inclusion.append(int(np.sum(~inside)))
        else:
            inclusion.append(0 if layer.inclusion else None)
    return {"exclusion": sum(count or 0 for count in exclusion), "inclusion": sum(count or 0 for count in inclusion),
            "exclusion_per_layer": exclusion, "inclusion_per_layer": inclusion}


def _intersecting_pairs(shapes: np.ndarray) -> int:
    if len(shapes) < 2:
        return 0
    left, right = shapely.STRtree(shapes).query(shapes, predicate="intersects")
    return int(np.sum(left < right))
