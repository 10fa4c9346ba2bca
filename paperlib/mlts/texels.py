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
theorem); it is solved in closed form (with bisection as a fallback), for many texels at once,
and a last per-axis rescaling of relative size ~1e-15 makes the box exact. The texel's "own proportions" (aspect 1) are
therefore those of a square box, and :func:`affine_object`'s aspect ratio elongates it.

Conventions (shared by all of :mod:`paperlib.mlts`): pixel coordinates with x to the right
and y down; a polygon is a float64 ``(k, 2)`` array of (x, y) vertices, simple, not closed,
with positive shoelace area (counter-clockwise as shapely's ``orient(sign=1.0)`` sees the raw
coordinates); randomness through ``rng`` (``None``, an int or a Generator).

Written by hand: the texel generators and the affine map are a few lines of NumPy; the
convex hull comes from SciPy.

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
from scipy.spatial import ConvexHull
from scipy.spatial.distance import pdist

from .._checks import as_generator, budget, check_budget, check_choice, float_array, positive_number

__all__ = [
    "TEXELS",
    "affine_map",
    "affine_object",
    "affine_objects",
    "distance_to",
    "distances_to",
    "object_diameter",
    "orientation_angle",
    "orientation_angles",
    "texel",
    "texel_batch",
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
#: Default budget of :func:`texel_batch`: the most texels of one call (10**7; the sampler draws a few thousand).
#: Raise it with the ``max_count`` keyword.
MAX_TEXEL_BATCH = 10_000_000
#: Random-shape radius r(phi) = 1 + sum_j a_j cos(j phi + p_j): harmonics j = 1..J, J drawn here.
RANDOM_SHAPE_HARMONICS = (2, 5)
#: Range of sum_j |a_j|; below 1 the radius stays positive, so the shape is star-shaped.
RANDOM_SHAPE_AMPLITUDE = (0.2, 0.6)
#: Rotations tried at once to bracket the square-box rotation within a quarter turn.
SQUARE_BOX_GRID = 9
#: Closed-form refinements of the square-box rotation before falling back to bisection.
MAX_SINUSOID_STEPS = 4
#: Bisection steps of the fallback: a bracket of a sixteenth turn shrinks to rounding level in < 60.
BISECTION_STEPS = 64
#: Texels normalised together at most (the rotation grid holds 17 x vertices floats per texel).
NORMALISE_CHUNK = 1024

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
    anyway. ``texel(kind, rng)`` is ``texel_batch(kind, 1, rng)[0]``.

    References
    ----------
    Alvarez et al. 2015, section 3 ("Texels are very basic shapes like triangles, rectangles,
    ellipses, and convex polygons") and Fig. 12 (random shapes, regular polygons, ellipses,
    triangles).
    """
    return texel_batch(kind, 1, rng, n_vertices=n_vertices)[0]


def texel_batch(kind: str, count: int, rng=None, *, n_vertices: int | None = None,
                max_count: int = MAX_TEXEL_BATCH) -> list[np.ndarray]:
    """``count`` independent texels of one kind, drawn together (the sampler's fast path).

    Each is distributed as :func:`texel` describes; drawing them in one call vectorises the
    random draws and the square-box normalisation over texels of equal vertex count.

    Parameters
    ----------
    kind : str
        One of :data:`TEXELS` (see :func:`texel`).
    count : int
        Number of texels (>= 0).
    rng : None, int or numpy.random.Generator
        Source of randomness; the same seed gives the same texels bit for bit.
    n_vertices : int, optional
        Vertex count where the kind allows it (see :func:`texel`).
    max_count : int, optional
        Budget: the most texels (default :data:`MAX_TEXEL_BATCH`), checked before anything is drawn.

    Returns
    -------
    list of numpy.ndarray, each (k, 2)
        The texels, in draw order (vertex counts may differ for regular and convex polygons).

    Raises
    ------
    ValueError
        Unknown ``kind``, a vertex count the kind does not accept, a negative ``count`` or one above
        ``max_count``.
    """
    check_choice(kind, TEXELS, "kind")
    n_vertices = _vertex_count(kind, n_vertices)
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 0:
        raise ValueError(f"count must be a non-negative integer, got {count!r}")
    check_budget(count, budget(max_count, "max_count"), "max_count", "texels")
    if kind in ("rectangle", "ellipse"):
        fixed = _fixed_texel(kind, n_vertices)
        return [fixed.copy() for _ in range(count)]
    rng = as_generator(rng)
    raw = _RANDOM_GENERATORS[kind](rng, int(count), n_vertices)
    return _normalised_all(raw, rng.uniform(0.0, 2.0 * math.pi, size=count))


@functools.lru_cache(maxsize=64)
def _fixed_texel(kind: str, n_vertices: int | None) -> np.ndarray:
    """The texels that draw nothing, computed once per vertex count."""
    if kind == "rectangle":
        return np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]])
    return _normalised_all([_regular_polygon(n_vertices or DEFAULT_SMOOTH_VERTICES)], np.zeros(1))[0]


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


def _random_triangles(rng: np.random.Generator, count: int, n_vertices) -> np.ndarray:
    # Uniform on the simplex of angle triples with every angle >= the minimum: no rejection loop.
    smallest = math.radians(MIN_TRIANGLE_ANGLE)
    angles = smallest + (math.pi - 3.0 * smallest) * rng.dirichlet(np.ones(3), size=count)
    alpha, beta = angles[:, 0], angles[:, 1]
    # Base (0,0)-(1,0); the apex follows from the base angles (law of sines).
    side = np.sin(beta) / np.sin(alpha + beta)
    triangles = np.zeros((count, 3, 2))
    triangles[:, 1, 0] = 1.0
    triangles[:, 2, 0], triangles[:, 2, 1] = side * np.cos(alpha), side * np.sin(alpha)
    return triangles


def _random_regular_polygons(rng: np.random.Generator, count: int, n_vertices) -> list[np.ndarray]:
    low, high = REGULAR_SIDES
    sides = np.full(count, n_vertices) if n_vertices else rng.integers(low, high + 1, size=count)
    return [_regular_polygon(int(n_sides)) for n_sides in sides]


def _random_convex_polygons(rng: np.random.Generator, count: int, n_vertices) -> list[np.ndarray]:
    low, high = CONVEX_POINTS
    sizes = np.full(count, n_vertices) if n_vertices else rng.integers(low, high + 1, size=count)
    return [_random_convex_polygon(rng, int(n_points)) for n_points in sizes]


def _random_convex_polygon(rng: np.random.Generator, n_points: int) -> np.ndarray:
    for _ in range(MAX_CONVEX_DRAWS):
        points = rng.uniform(-0.5, 0.5, size=(n_points, 2))
        hull = ConvexHull(points)  # 2-D hulls list their vertices counter-clockwise, no collinear ones
        extent = np.ptp(points[hull.vertices], axis=0)
        if len(hull.vertices) >= 3 and hull.volume >= MIN_CONVEX_FILL * extent[0] * extent[1]:
            return points[hull.vertices]
    raise ValueError(f"no convex polygon of useful area from {n_points} points in {MAX_CONVEX_DRAWS} draws")


def _random_star_shapes(rng: np.random.Generator, count: int, n_vertices) -> np.ndarray:
    n_vertices = n_vertices or DEFAULT_SMOOTH_VERTICES
    low, high = RANDOM_SHAPE_HARMONICS
    orders = np.arange(1, high + 1)
    used = orders[None, :] <= rng.integers(low, high + 1, size=count)[:, None]  # harmonics 1..J of each shape
    # Amplitudes decay like 1/j so the outline stays smooth; their sum stays below 1 so r > 0.
    weights = np.where(used, rng.uniform(0.0, 1.0, size=(count, high)) / orders, 0.0)
    amplitudes = weights / weights.sum(axis=1, keepdims=True) * rng.uniform(*RANDOM_SHAPE_AMPLITUDE, size=(count, 1))
    phases = rng.uniform(0.0, 2.0 * math.pi, size=(count, high))
    phi = 2.0 * math.pi * np.arange(n_vertices) / n_vertices
    waves = np.cos(phi[None, :, None] * orders[None, None, :] + phases[:, None, :])  # (count, k, J)
    radius = 1.0 + np.einsum("nkj,nj->nk", waves, amplitudes)
    # Positive radius at strictly increasing angles: a star-shaped, hence simple, polygon.
    return radius[:, :, None] * np.stack([np.cos(phi), np.sin(phi)], axis=-1)[None]


_RANDOM_GENERATORS = {
    "triangle": _random_triangles,
    "regular_polygon": _random_regular_polygons,
    "convex_polygon": _random_convex_polygons,
    "random_shape": _random_star_shapes,
}


def _rotated_all(vertices: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """Each of ``vertices`` (n, k, 2) rotated by its angle (n,) (counter-clockwise as x right, y up)."""
    cos, sin = np.cos(angles)[:, None], np.sin(angles)[:, None]
    x, y = vertices[..., 0], vertices[..., 1]
    return np.stack([cos * x - sin * y, sin * x + cos * y], axis=-1)


def _box_differences(angles: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Bounding-box width - height of each shape (n, k, 2) rotated by each of its angles (n, g)."""
    cos, sin = np.cos(angles)[:, :, None], np.sin(angles)[:, :, None]
    x, y = vertices[:, None, :, 0], vertices[:, None, :, 1]
    rotated_x, rotated_y = cos * x - sin * y, sin * x + cos * y
    return np.ptp(rotated_x, axis=2) - np.ptp(rotated_y, axis=2)


def _widths_minus_heights(angles: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Bounding-box width - height of one shape ``vertices`` (k, 2) rotated by each of ``angles``."""
    return _box_differences(np.asarray(angles, dtype=float)[None], np.asarray(vertices, dtype=float)[None])[0]


def _extremes_all(vertices: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """(n, 4) indices of each shape's vertices with largest x, y then smallest x, y after rotation."""
    rotated = _rotated_all(vertices, angles)
    return np.concatenate([rotated.argmax(axis=1), rotated.argmin(axis=1)], axis=1)


def _sinusoid_roots(vertices: np.ndarray, extremes: np.ndarray, low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """Roots in [low, high] of width - height while the extreme vertices stay ``extremes`` (NaN: none).

    With fixed extreme vertices, width - height = P cos(t) - Q sin(t), zero at atan2(P, Q) + k pi.
    """
    rows = np.arange(len(vertices))[:, None]
    picked = vertices[rows, extremes]  # (n, 4, 2): max x, max y, min x, min y vertices
    dx_w, dy_w = (picked[:, 0] - picked[:, 2]).T  # x extent: max x vertex - min x vertex
    dx_h, dy_h = (picked[:, 1] - picked[:, 3]).T  # y extent: max y vertex - min y vertex
    root = np.arctan2(dx_w - dy_h, dy_w + dx_h)
    root += math.pi * np.round((0.5 * (low + high) - root) / math.pi)
    return np.where((low <= root) & (root <= high), root, np.nan)


def _square_box_angles(vertices: np.ndarray, start_angles: np.ndarray) -> np.ndarray:
    """First rotation of each shape (n, k, 2) after its start angle (within a quarter turn) giving a square box.

    A quarter turn swaps width and height, so width - height changes sign on the grid below;
    in the bracket the root is solved in closed form (:func:`_sinusoid_roots`), checked, and
    found by bisection (:func:`_bisected_roots`) in the rare case the extreme vertices keep changing.
    """
    grid = start_angles[:, None] + _QUARTER_TURN_GRID[None, :]
    differences = _box_differences(grid, vertices)
    changed = np.sign(differences[:, 1:]) != np.sign(differences[:, :1])
    first = changed.argmax(axis=1)
    rows = np.arange(len(vertices))
    low, high = grid[rows, first], grid[rows, first + 1]
    angles = np.full(len(vertices), np.nan)
    # exact zeros on the grid; no sign change: width - height is at rounding level everywhere (a square)
    angles = np.where(differences[:, 0] == 0.0, start_angles, angles)
    flat = ~changed.any(axis=1) & np.isnan(angles)
    angles[flat] = grid[flat, np.argmin(np.abs(differences[flat]), axis=1)]
    on_grid = np.isnan(angles) & (differences[rows, first + 1] == 0.0)
    angles[on_grid] = high[on_grid]
    open_rows = np.flatnonzero(np.isnan(angles))
    guess = 0.5 * (low + high)
    for _ in range(MAX_SINUSOID_STEPS):
        if not open_rows.size:
            break
        shapes = vertices[open_rows]
        extremes = _extremes_all(shapes, guess[open_rows])
        roots = _sinusoid_roots(shapes, extremes, low[open_rows], high[open_rows])
        found = ~np.isnan(roots)
        settled = found.copy()
        settled[found] = np.all(_extremes_all(shapes[found], roots[found]) == extremes[found], axis=1)
        angles[open_rows[settled]] = roots[settled]
        guess[open_rows[found]] = roots[found]
        open_rows = open_rows[found & ~settled]  # no root in the bracket: straight to bisection
    rest = np.flatnonzero(np.isnan(angles))
    if rest.size:
        angles[rest] = _bisected_roots(vertices[rest], low[rest], high[rest])
    return angles


def _bisected_roots(vertices: np.ndarray, low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """Roots of width - height in brackets [low, high] where it changes sign, by bisection to rounding level."""
    low, high = low.copy(), high.copy()
    low_sign = np.sign(_box_differences(low[:, None], vertices)[:, 0])
    for _ in range(BISECTION_STEPS):
        middle = 0.5 * (low + high)
        middle_sign = np.sign(_box_differences(middle[:, None], vertices)[:, 0])
        same = middle_sign == low_sign
        low, high = np.where(same, middle, low), np.where(same, high, middle)
        if np.all((high - low) <= np.spacing(np.abs(high))) or np.all(middle_sign == 0):
            break
    return 0.5 * (low + high)


def _square_box_angle(vertices: np.ndarray, start_angle: float) -> float:
    """:func:`_square_box_angles` of one shape (k, 2)."""
    return float(_square_box_angles(np.asarray(vertices, dtype=float)[None], np.array([start_angle]))[0])


def _normalised_all(shapes, start_angles: np.ndarray) -> list[np.ndarray]:
    """Each shape by a similarity onto a square box, then rescaled so the box is exactly [-0.5, 0.5]^2.

    Shapes of equal vertex count are normalised together.
    """
    shapes = list(shapes)
    result = [None] * len(shapes)
    counts = np.array([len(shape) for shape in shapes])
    for count in np.unique(counts):
        for rows in _chunks(np.flatnonzero(counts == count), NORMALISE_CHUNK):
            _normalise_group(shapes, rows, start_angles, result)
    return result


def _chunks(rows: np.ndarray, size: int) -> list[np.ndarray]:
    return np.array_split(rows, max(1, -(-len(rows) // size)))


def _normalise_group(shapes: list, rows: np.ndarray, start_angles: np.ndarray, result: list) -> None:
    """:func:`_normalised_all` of shapes ``rows`` (all with the same vertex count), into ``result``."""
    group = np.stack([shapes[row] for row in rows])
    rotated = _rotated_all(group, _square_box_angles(group, start_angles[rows]))
    low, high = rotated.min(axis=1, keepdims=True), rotated.max(axis=1, keepdims=True)
    # (x - low) / (high - low) is exactly 0 at the minimum and exactly 1 at the maximum.
    # Rotation and positive scaling keep the generators' counter-clockwise order.
    normalised = (rotated - low) / (high - low) - 0.5
    for row, shape in zip(rows, normalised):
        result[row] = shape


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


def affine_map(points: np.ndarray, diameters, aspects, angles, centers) -> np.ndarray:
    """Texel points (..., 2) scaled by (diameter, diameter / aspect), rotated by angle, moved to the centre.

    The map of :func:`affine_object` WITHOUT input checks, for callers that validated their
    inputs (the sampler tries many thousands of placements): ``diameters``, ``aspects``,
    ``angles`` broadcast against ``points[..., 0]`` and ``centers`` against ``points``.
    """
    x, y = points[..., 0] * diameters, points[..., 1] * (diameters / aspects)
    cos, sin = np.cos(angles), np.sin(angles)
    return np.stack([cos * x - sin * y + centers[..., 0], sin * x + cos * y + centers[..., 1]], axis=-1)


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
    return affine_map(vertices, diameter, aspect, angle, center)


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
        vertices = check_polygon(vertices_list)
        return list(affine_map(vertices[None], diameters[:, None], aspects[:, None], angles[:, None], centers[:, None]))
    texels = _texels_per_object(vertices_list, n_objects)
    counts = np.array([len(t) for t in texels], dtype=np.intp)
    stacked = np.concatenate(texels) if texels else np.empty((0, 2))
    # Each vertex carries its object's parameters, so one NumPy pass transforms them all.
    owner = np.repeat(np.arange(n_objects), counts)
    moved = affine_map(stacked, diameters[owner], aspects[owner], angles[owner], centers[owner])
    return np.split(moved, np.cumsum(counts)[:-1]) if n_objects else []


def _per_object(values, n_objects: int, name: str) -> np.ndarray:
    array = float_array(values, name, f"{n_objects} numbers, one per object")
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

