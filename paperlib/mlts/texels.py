"""Texels of ML-textures and the affine objects built from them (Alvarez et al. 2015, section 3).

A *texel* is one of the paper's basic shapes: triangle, rectangle, ellipse, regular polygon,
convex polygon or random shape (Fig. 12). Every object of a layer is "obtained by an affine
transformation of a texel" (section 3, after Definition 1); :func:`affine_object` applies that
transformation, a scaling by the layer's diameter and aspect ratio, a rotation towards one of
the layer's two orientation points (:func:`orientation_angle`), and a translation to the
object's centre.

Normalisation. :func:`texel` returns vertices in the texel's own frame with axis-aligned
bounding box exactly ``[-0.5, 0.5] x [-0.5, 0.5]``. The shape is brought there by a
*similarity* (rotation, uniform scale, translation), never by stretching the two axes
differently, so a regular polygon keeps equal sides, a triangle its angles and a convex
polygon its convexity. This is possible because every bounded shape has a rotation whose
bounding box is a square: the difference width - height changes sign when the shape turns by
a quarter turn (width and height swap), so it vanishes in between (intermediate value
theorem); it is solved in closed form (with :func:`scipy.optimize.brentq` as a fallback),
and a last per-axis rescaling of relative size ~1e-15 makes the box exact. The texel's "own proportions" (aspect 1) are
therefore those of a square box, and :func:`affine_object`'s aspect ratio elongates it.

Conventions (shared by all of :mod:`paperlib.mlts`): pixel coordinates with x to the right
and y down; a polygon is a float64 ``(k, 2)`` array of (x, y) vertices, simple, not closed,
with positive shoelace area (counter-clockwise as shapely's ``orient(sign=1.0)`` sees the raw
coordinates); randomness through ``rng`` (``None``, an int or a Generator).

Written by hand: the texel generators and the affine map are a few lines of NumPy; the
convex hull comes from SciPy and the fallback root finding from :func:`scipy.optimize.brentq`.

References
----------
L. Alvarez, Y. Gousseau, J.-M. Morel, A. Salgado, "Exploring the space of abstract textures
by principles and random sampling", J. Math. Imaging Vis. 53 (2015), section 3 (texels,
object orientation towards two projective points, vanishing-point effect) and Fig. 12.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.optimize import brentq
from scipy.spatial import ConvexHull
from scipy.spatial.distance import pdist

from .._checks import positive_number

__all__ = [
    "TEXELS",
    "affine_object",
    "affine_objects",
    "distance_to",
    "distances_to",
    "object_diameter",
    "orientation_angle",
    "orientation_angles",
    "texel",
]

#: Texel kinds of section 3 and Fig. 12, in the order the paper lists them.
TEXELS = ("triangle", "rectangle", "ellipse", "regular_polygon", "convex_polygon", "random_shape")

#: Smallest angle of a random triangle, in degrees: keeps triangles visibly two-dimensional.
MIN_TRIANGLE_ANGLE = 15.0
#: Vertices of the polygon approximating an ellipse (and of a random shape) by default.
DEFAULT_SMOOTH_VERTICES = 64
#: Side counts a regular polygon draws from when ``n_vertices`` is not given.
REGULAR_SIDES = (3, 8)
#: Numbers of random points whose convex hull makes a convex polygon.
CONVEX_POINTS = (5, 12)
#: Convex hulls smaller than this fraction of their bounding box are slivers and are redrawn.
MIN_CONVEX_FILL = 0.05
#: Redraws allowed for a convex polygon before giving up (a sliver: ~7% for 3 points, far less for 5+).
MAX_CONVEX_DRAWS = 100
#: Random-shape radius r(phi) = 1 + sum_j a_j cos(j phi + p_j): harmonics j = 1..J, J drawn here.
RANDOM_SHAPE_HARMONICS = (2, 5)
#: Range of sum_j |a_j|; below 1 the radius stays positive, so the shape is star-shaped.
RANDOM_SHAPE_AMPLITUDE = (0.2, 0.6)
#: Rotations tried at once to bracket the square-box rotation within a quarter turn.
SQUARE_BOX_GRID = 17
#: Closed-form refinements of the square-box rotation before falling back to root finding.
MAX_SINUSOID_STEPS = 4

_QUARTER_TURN_GRID = np.linspace(0.0, 0.5 * math.pi, SQUARE_BOX_GRID)


# ---------------------------------------------------------------------------------------------
# texels
# ---------------------------------------------------------------------------------------------


def texel(kind: str, rng=None, *, n_vertices: int | None = None) -> np.ndarray:
    """One texel in its own frame, bounding box exactly ``[-0.5, 0.5]^2``.

    Parameters
    ----------
    kind : str
        One of :data:`TEXELS`:

        - ``"triangle"``: a random triangle whose angles are uniform on the simplex of angle
          triples with every angle >= 15 degrees (never degenerate);
        - ``"rectangle"``: the unit square (draws nothing from ``rng``);
        - ``"ellipse"``: ``n_vertices`` (default 64) points on the inscribed circle; the aspect
          ratio of :func:`affine_object` makes it an ellipse (draws nothing from ``rng``);
        - ``"regular_polygon"``: a regular polygon with ``n_vertices`` sides, or a number drawn
          uniformly in 3..8, at a random rotation among those giving it a square bounding box
          (see Notes);
        - ``"convex_polygon"``: the convex hull of ``n_vertices`` (default: drawn in 5..12)
          uniform random points, at least 3 hull vertices, slivers redrawn;
        - ``"random_shape"``: a star-shaped, possibly non-convex polygon of ``n_vertices``
          (default 64) vertices whose radius is a smooth random function of the angle,
          ``1 + sum_j a_j cos(j phi + p_j)`` with 2..5 harmonics and ``sum |a_j| < 1``.
    rng : None, int or numpy.random.Generator
        Source of randomness; the same seed gives the same texel bit for bit.
    n_vertices : int, optional
        Vertex count where the kind allows it (see above); for ``"triangle"`` it may only be 3
        and for ``"rectangle"`` only 4.

    Returns
    -------
    numpy.ndarray, shape (k, 2)
        Vertices (x, y) with positive shoelace area. The shape is placed by a similarity whose
        rotation makes its bounding box square (random among those rotations for the random
        kinds); see the module docstring.

    Raises
    ------
    ValueError
        Unknown ``kind`` or a vertex count the kind does not accept.

    Notes
    -----
    Keeping the shape (a similarity) *and* an exactly square box restricts the texel's own
    rotation to the roots of width - height. The rotation is drawn as the first such root after
    a uniform random angle. For most shapes and for regular polygons whose side count is a
    multiple of 4 this is a continuum; other regular polygons have only a few square-box
    placements up to symmetry (4 for odd side counts, 2 for 6 or 10 sides), and the draw picks
    among them. The object's orientation in the image is set by :func:`affine_object`'s angle
    anyway.

    References
    ----------
    Alvarez et al. 2015, section 3 ("Texels are very basic shapes like triangles, rectangles,
    ellipses, and convex polygons") and Fig. 12 (random shapes, regular polygons, ellipses,
    triangles).
    """
    if kind not in TEXELS:
        raise ValueError(f"unknown texel kind {kind!r}; choose among {TEXELS}")
    n_vertices = _vertex_count(kind, n_vertices)
    if kind in ("rectangle", "ellipse"):
        return _fixed_texel(kind, n_vertices).copy()
    rng = np.random.default_rng(rng)
    raw = _RANDOM_GENERATORS[kind](rng, n_vertices)
    return _normalised(raw, rng.uniform(0.0, 2.0 * math.pi))


@functools.lru_cache(maxsize=64)
def _fixed_texel(kind: str, n_vertices: int | None) -> np.ndarray:
    """The texels that draw nothing, computed once per vertex count."""
    if kind == "rectangle":
        return np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]])
    return _normalised(_regular_polygon(n_vertices or DEFAULT_SMOOTH_VERTICES), 0.0)


def _vertex_count(kind: str, n_vertices) -> int | None:
    if n_vertices is None:
        return None
    if isinstance(n_vertices, bool) or not isinstance(n_vertices, (int, np.integer)):
        raise ValueError(f"n_vertices must be an integer, got {n_vertices!r}")
    fixed = {"triangle": 3, "rectangle": 4}
    if kind in fixed and n_vertices != fixed[kind]:
        raise ValueError(f"a {kind} has {fixed[kind]} vertices, got n_vertices={n_vertices}")
    if n_vertices < 3:
        raise ValueError(f"a polygon needs n_vertices >= 3, got {n_vertices}")
    return int(n_vertices)


def _regular_polygon(n_sides: int) -> np.ndarray:
    phi = 2.0 * math.pi * np.arange(n_sides) / n_sides
    return 0.5 * np.column_stack([np.cos(phi), np.sin(phi)])


def _random_triangle(rng: np.random.Generator, n_vertices) -> np.ndarray:
    # Uniform on the simplex of angle triples with every angle >= the minimum: no rejection loop.
    smallest = math.radians(MIN_TRIANGLE_ANGLE)
    alpha, beta, _ = smallest + (math.pi - 3.0 * smallest) * rng.dirichlet(np.ones(3))
    # Base (0,0)-(1,0); the apex follows from the base angles (law of sines).
    side = math.sin(beta) / math.sin(alpha + beta)
    return np.array([[0.0, 0.0], [1.0, 0.0], [side * math.cos(alpha), side * math.sin(alpha)]])


def _random_regular_polygon(rng: np.random.Generator, n_vertices) -> np.ndarray:
    low, high = REGULAR_SIDES
    return _regular_polygon(n_vertices or int(rng.integers(low, high + 1)))


def _random_convex_polygon(rng: np.random.Generator, n_vertices) -> np.ndarray:
    low, high = CONVEX_POINTS
    n_points = n_vertices or int(rng.integers(low, high + 1))
    for _ in range(MAX_CONVEX_DRAWS):
        points = rng.uniform(-0.5, 0.5, size=(n_points, 2))
        hull = ConvexHull(points)  # 2-D hulls list their vertices counter-clockwise, no collinear ones
        extent = np.ptp(points[hull.vertices], axis=0)
        if len(hull.vertices) >= 3 and hull.volume >= MIN_CONVEX_FILL * extent[0] * extent[1]:
            return points[hull.vertices]
    raise ValueError(f"no convex polygon of useful area from {n_points} points in {MAX_CONVEX_DRAWS} draws")


def _random_star_shape(rng: np.random.Generator, n_vertices) -> np.ndarray:
    n_vertices = n_vertices or DEFAULT_SMOOTH_VERTICES
    low, high = RANDOM_SHAPE_HARMONICS
    orders = np.arange(1, int(rng.integers(low, high + 1)) + 1)
    # Amplitudes decay like 1/j so the outline stays smooth; their sum stays below 1 so r > 0.
    weights = rng.uniform(0.0, 1.0, size=orders.size) / orders
    amplitudes = weights / weights.sum() * rng.uniform(*RANDOM_SHAPE_AMPLITUDE)
    phases = rng.uniform(0.0, 2.0 * math.pi, size=orders.size)
    phi = 2.0 * math.pi * np.arange(n_vertices) / n_vertices
    radius = 1.0 + (amplitudes * np.cos(np.outer(phi, orders) + phases)).sum(axis=1)
    # Positive radius at strictly increasing angles: a star-shaped, hence simple, polygon.
    return radius[:, None] * np.column_stack([np.cos(phi), np.sin(phi)])


_RANDOM_GENERATORS = {
    "triangle": _random_triangle,
    "regular_polygon": _random_regular_polygon,
    "convex_polygon": _random_convex_polygon,
    "random_shape": _random_star_shape,
}


def _rotated(vertices: np.ndarray, angle: float) -> np.ndarray:
    cos, sin = math.cos(angle), math.sin(angle)
    return vertices @ np.array([[cos, sin], [-sin, cos]])


def _widths_minus_heights(angles: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Bounding-box width - height of ``vertices`` rotated by each of ``angles``."""
    cos, sin = np.cos(angles)[:, None], np.sin(angles)[:, None]
    x, y = vertices[:, 0], vertices[:, 1]
    rotated_x, rotated_y = cos * x - sin * y, sin * x + cos * y
    return (rotated_x.max(axis=1) - rotated_x.min(axis=1)) - (rotated_y.max(axis=1) - rotated_y.min(axis=1))


def _width_minus_height(angle: float, vertices: np.ndarray) -> float:
    return float(_widths_minus_heights(np.array([angle]), vertices)[0])


def _extremes(vertices: np.ndarray, angle: float) -> np.ndarray:
    """Indices of the vertices with largest and smallest x and y after rotation by ``angle``."""
    rotated = _rotated(vertices, angle)
    return np.concatenate([rotated.argmax(axis=0), rotated.argmin(axis=0)])


def _sinusoid_root(vertices: np.ndarray, extremes: np.ndarray, low: float, high: float) -> float | None:
    """Root in [low, high] of width - height while the extreme vertices stay ``extremes``.

    With fixed extreme vertices, width - height = P cos(t) - Q sin(t), zero at atan2(P, Q) + k pi.
    """
    dx_w, dy_w = vertices[extremes[0]] - vertices[extremes[2]]  # x extent: max x vertex - min x vertex
    dx_h, dy_h = vertices[extremes[1]] - vertices[extremes[3]]  # y extent: max y vertex - min y vertex
    root = math.atan2(dx_w - dy_h, dy_w + dx_h)
    root += math.pi * round((0.5 * (low + high) - root) / math.pi)
    return root if low <= root <= high else None


def _square_box_angle(vertices: np.ndarray, start_angle: float) -> float:
    """First rotation after ``start_angle`` (within a quarter turn) giving a square bounding box.

    A quarter turn swaps width and height, so width - height changes sign on the grid below;
    in the bracket the root is solved in closed form (:func:`_sinusoid_root`), checked, and
    found by :func:`scipy.optimize.brentq` in the rare case the extreme vertices keep changing.
    """
    angles = start_angle + _QUARTER_TURN_GRID
    differences = _widths_minus_heights(angles, vertices)
    if differences[0] == 0.0:
        return start_angle
    changed = np.flatnonzero(np.sign(differences[1:]) != np.sign(differences[0]))
    if changed.size == 0:  # width - height is at rounding level everywhere (e.g. a square)
        return float(angles[np.argmin(np.abs(differences))])
    low, high = float(angles[changed[0]]), float(angles[changed[0] + 1])
    if differences[changed[0] + 1] == 0.0:
        return high
    angle = 0.5 * (low + high)
    for _ in range(MAX_SINUSOID_STEPS):
        extremes = _extremes(vertices, angle)
        root = _sinusoid_root(vertices, extremes, low, high)
        if root is None:
            break
        if np.array_equal(_extremes(vertices, root), extremes):
            return root
        angle = root
    return brentq(_width_minus_height, low, high, args=(vertices,), xtol=1e-15, maxiter=200)


def _normalised(vertices: np.ndarray, start_angle: float) -> np.ndarray:
    """``vertices`` by a similarity onto a square box, then rescaled so the box is exactly [-0.5, 0.5]^2."""
    rotated = _rotated(vertices, _square_box_angle(vertices, start_angle))
    low, high = rotated.min(axis=0), rotated.max(axis=0)
    # (x - low) / (high - low) is exactly 0 at the minimum and exactly 1 at the maximum.
    # Rotation and positive scaling keep the generators' counter-clockwise order.
    return (rotated - low) / (high - low) - 0.5


# ---------------------------------------------------------------------------------------------
# affine objects
# ---------------------------------------------------------------------------------------------


def check_polygon(vertices, name: str = "vertices") -> np.ndarray:
    """``vertices`` as a finite float64 (k, 2) array with k >= 3, or a ValueError naming ``name``."""
    try:
        array = np.asarray(vertices, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of (x, y) vertices of shape (k, 2), k >= 3") from None
    if array.ndim != 2 or array.shape[1] != 2 or array.shape[0] < 3:
        raise ValueError(f"{name} must have shape (k, 2) with k >= 3 vertices, got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} has NaN or infinite coordinates")
    return array


def _finite_vector(value, size: int, name: str) -> np.ndarray:
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be {size} numbers, got {value!r}") from None
    if array.shape != (size,):
        raise ValueError(f"{name} must be {size} numbers, got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return array


def _aspect_ratio(aspect) -> float:
    aspect = positive_number(aspect, "aspect")
    if aspect < 1.0:
        raise ValueError(f"aspect must be >= 1 (1 keeps the texel's proportions), got {aspect!r}")
    return aspect


def _finite_angle(angle) -> float:
    try:
        angle = float(angle)
    except (TypeError, ValueError):
        raise ValueError(f"angle must be a number of radians, got {angle!r}") from None
    if not math.isfinite(angle):
        raise ValueError(f"angle must be finite, got {angle!r}")
    return angle


def affine_object(vertices, center, diameter, aspect, angle) -> np.ndarray:
    """The object ``O = T(center) R(angle) S(diameter, diameter / aspect)`` applied to a texel.

    Parameters
    ----------
    vertices : array_like, shape (k, 2)
        Texel vertices in their own frame, normally from :func:`texel` (box ``[-0.5, 0.5]^2``).
    center : array_like, shape (2,)
        Position (x, y) of the texel's origin in the image, in pixels.
    diameter : float
        Length in pixels given to the texel's x axis (> 0); with a :func:`texel`, the extent of
        the object along its own axis.
    aspect : float
        Aspect ratio >= 1: the texel's y axis gets ``diameter / aspect`` pixels (1 keeps the
        texel's own proportions).
    angle : float
        Rotation in radians of the texel's x axis, measured from the image's +x axis towards
        +y. The image's y axis points down, so a positive angle turns *clockwise on screen*.

    Returns
    -------
    numpy.ndarray, shape (k, 2)
        The object's vertices; the orientation sign (shoelace area) is the texel's, since the
        map has positive determinant.

    Raises
    ------
    ValueError
        Malformed or non-finite vertices or centre, ``diameter <= 0``, ``aspect < 1``, NaN.

    References
    ----------
    Alvarez et al. 2015, section 3: "Each object O_{m,k} is obtained by an affine
    transformation of a texel"; section 4, AspRat_O(L_m) and Max_D(L_m).
    """
    vertices = check_polygon(vertices)
    center = _finite_vector(center, 2, "center")
    diameter = positive_number(diameter, "diameter")
    aspect = _aspect_ratio(aspect)
    angle = _finite_angle(angle)
    scaled = vertices * np.array([diameter, diameter / aspect])
    return _rotated(scaled, angle) + center


def affine_objects(vertices_list, centers, diameters, aspects, angles) -> list[np.ndarray]:
    """:func:`affine_object` for many objects in one vectorised pass.

    Parameters
    ----------
    vertices_list : array_like of shape (k, 2), or sequence of n such arrays
        One texel shared by every object, or one texel per object (vertex counts may differ).
    centers : array_like, shape (n, 2)
    diameters, aspects, angles : array_like, shape (n,)
        Per-object parameters, with the meanings and constraints of :func:`affine_object`.

    Returns
    -------
    list of numpy.ndarray
        The n objects, in order.

    References
    ----------
    Alvarez et al. 2015, section 3 (objects as affine images of texels).
    """
    centers = _centers_array(centers)
    n_objects = centers.shape[0]
    diameters, aspects, angles = (_per_object(values, n_objects, name) for values, name in
                                  ((diameters, "diameters"), (aspects, "aspects"), (angles, "angles")))
    if np.any(diameters <= 0):
        raise ValueError("diameters must be > 0")
    if np.any(aspects < 1):
        raise ValueError("aspects must be >= 1 (1 keeps the texel's proportions)")
    if isinstance(vertices_list, np.ndarray) and vertices_list.ndim == 2:
        return list(transform_shared(check_polygon(vertices_list), centers, diameters, aspects, angles))
    texels = _texels_per_object(vertices_list, n_objects)
    counts = np.array([len(t) for t in texels], dtype=np.intp)
    stacked = np.concatenate(texels) if texels else np.empty((0, 2))
    # Each vertex carries its object's parameters, so one NumPy pass transforms them all.
    scale = np.repeat(np.column_stack([diameters, diameters / aspects]), counts, axis=0)
    cos, sin = np.repeat(np.cos(angles), counts), np.repeat(np.sin(angles), counts)
    x, y = stacked[:, 0] * scale[:, 0], stacked[:, 1] * scale[:, 1]
    moved = np.column_stack([cos * x - sin * y, sin * x + cos * y]) + np.repeat(centers, counts, axis=0)
    return np.split(moved, np.cumsum(counts)[:-1]) if n_objects else []


def transform_shared(vertices: np.ndarray, centers: np.ndarray, diameters, aspects, angles) -> np.ndarray:
    """:func:`affine_objects` of one shared texel as an (n, k, 2) array, WITHOUT input checks.

    For callers that have validated their inputs (the sampler tries thousands of placements):
    ``vertices`` (k, 2), ``centers`` (n, 2), ``diameters``, ``aspects``, ``angles`` (n,) or
    scalars, all finite, diameters > 0, aspects >= 1.
    """
    diameters, aspects, angles = (np.broadcast_to(np.asarray(value, dtype=np.float64), (len(centers),))
                                  for value in (diameters, aspects, angles))
    x = vertices[None, :, 0] * diameters[:, None]
    y = vertices[None, :, 1] * (diameters / aspects)[:, None]
    cos, sin = np.cos(angles)[:, None], np.sin(angles)[:, None]
    return np.stack([cos * x - sin * y + centers[:, 0:1], sin * x + cos * y + centers[:, 1:2]], axis=-1)


def _per_object(values, n_objects: int, name: str) -> np.ndarray:
    array = np.asarray(values, dtype=np.float64)
    if array.shape != (n_objects,):
        raise ValueError(f"{name} must have shape ({n_objects},) like centers, got {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} contain NaN or infinite values")
    return array


def _texels_per_object(vertices_list, n_objects: int) -> list[np.ndarray]:
    if isinstance(vertices_list, np.ndarray) and vertices_list.ndim == 2:
        return [check_polygon(vertices_list)] * n_objects
    texels = [check_polygon(v, f"vertices_list[{i}]") for i, v in enumerate(vertices_list)]
    if len(texels) != n_objects:
        raise ValueError(f"vertices_list has {len(texels)} texels for {n_objects} centers")
    return texels


# ---------------------------------------------------------------------------------------------
# orientation points
# ---------------------------------------------------------------------------------------------


def _projective_point(point) -> np.ndarray:
    point = _finite_vector(point, 3, "point")
    if not np.any(point):
        raise ValueError("(0, 0, 0) is not a projective point")
    return point


def orientation_angle(center, point) -> float:
    """Angle of the direction from ``center`` towards the projective point ``point``.

    Parameters
    ----------
    center : array_like, shape (2,)
        Object centre (x, y) in pixels.
    point : array_like, shape (3,)
        Homogeneous coordinates (X, Y, Z): the finite point (X/Z, Y/Z) when Z != 0, the point at
        infinity in direction (X, Y) when Z == 0 (the same angle for every centre: parallel
        objects).

    Returns
    -------
    float
        ``atan2(dy, dx)`` in (-pi, pi], measured from +x towards +y (clockwise on screen since y
        points down), ready for :func:`affine_object`. (1, 0, 0) gives 0 (horizontal objects),
        (0, 1, 0) gives pi/2 (vertical objects).

    Raises
    ------
    ValueError
        ``point`` is (0, 0, 0), not finite or not 3 numbers; ``center`` malformed; the finite
        point coincides with ``center`` (no direction).

    References
    ----------
    Alvarez et al. 2015, section 3, object orientation: "to each layer are associated two
    random points in projective coordinates (to allow points at infinity) such that each layer
    object is oriented towards one of these two points"; section 4, V_0(L_m), V_1(L_m).
    """
    center = _finite_vector(center, 2, "center")
    x, y, z = _projective_point(point)
    if z == 0.0:
        return math.atan2(y, x)
    dx, dy = x / z - center[0], y / z - center[1]
    if dx == 0.0 and dy == 0.0:
        raise ValueError(f"the orientation point {tuple(point)} coincides with the centre {tuple(center)}")
    return math.atan2(dy, dx)


def distance_to(center, point) -> float:
    """Euclidean distance in pixels from ``center`` to the projective point ``point``.

    Parameters
    ----------
    center : array_like, shape (2,)
    point : array_like, shape (3,)
        Homogeneous coordinates (X, Y, Z), as in :func:`orientation_angle`.

    Returns
    -------
    float
        ``inf`` for a point at infinity (Z == 0), otherwise the distance to (X/Z, Y/Z) (0 when
        they coincide).

    References
    ----------
    Alvarez et al. 2015, section 3, vanishing point effect: "The size of objects are reduced
    according to the distance to such orientation points"; section 4, rF(L_m).
    """
    center = _finite_vector(center, 2, "center")
    x, y, z = _projective_point(point)
    if z == 0.0:
        return math.inf
    return math.hypot(x / z - center[0], y / z - center[1])


def _centers_array(centers) -> np.ndarray:
    try:
        array = np.asarray(centers, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"centers must be an (n, 2) array of (x, y), got {type(centers).__name__}") from None
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(f"centers must have shape (n, 2), got {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError("centers contain NaN or infinite coordinates")
    return array


def orientation_angles(centers, point) -> np.ndarray:
    """:func:`orientation_angle` for many centres and one projective point, vectorised.

    Parameters
    ----------
    centers : array_like, shape (n, 2)
    point : array_like, shape (3,)

    Returns
    -------
    numpy.ndarray, shape (n,)

    Raises
    ------
    ValueError
        As :func:`orientation_angle`, in particular when a finite ``point`` coincides with any
        centre (filter those centres out first, e.g. with :func:`distances_to`).

    References
    ----------
    Alvarez et al. 2015, section 3, object orientation; section 4, V_0(L_m), V_1(L_m).
    """
    centers = _centers_array(centers)
    x, y, z = _projective_point(point)
    if z == 0.0:
        return np.full(len(centers), math.atan2(y, x))
    dx, dy = x / z - centers[:, 0], y / z - centers[:, 1]
    on_point = (dx == 0.0) & (dy == 0.0)
    if on_point.any():
        raise ValueError(f"the orientation point {tuple(point)} coincides with centre {int(np.argmax(on_point))}")
    return np.arctan2(dy, dx)


def distances_to(centers, point) -> np.ndarray:
    """:func:`distance_to` for many centres and one projective point, vectorised.

    Parameters
    ----------
    centers : array_like, shape (n, 2)
    point : array_like, shape (3,)

    Returns
    -------
    numpy.ndarray, shape (n,)
        All ``inf`` for a point at infinity; 0 where a centre is on the point.

    References
    ----------
    Alvarez et al. 2015, section 3, vanishing point effect; section 4, rF(L_m).
    """
    centers = _centers_array(centers)
    x, y, z = _projective_point(point)
    if z == 0.0:
        return np.full(len(centers), math.inf)
    return np.hypot(x / z - centers[:, 0], y / z - centers[:, 1])


def object_diameter(polygon) -> float:
    """The largest distance between two vertices of ``polygon`` (the paper's object diameter).

    Parameters
    ----------
    polygon : array_like, shape (k, 2)

    Returns
    -------
    float

    References
    ----------
    Alvarez et al. 2015, section 4, Max_D(L_m) ("maximum diameter of an object") and the size
    reduction factor s_R(L_m).
    """
    polygon = check_polygon(polygon, "polygon")
    # Texels have at most a few hundred vertices: all pairs in C are cheaper than a hull.
    return float(pdist(polygon).max())

