"""Interactions on the Hausdorff distance between bounding boxes (Hurtut 2009, section 4.3).

Section 4.3 of the paper names a limitation and its remedy: "When elements are strongly
elongated, [the centroid] representation is not adapted [...] interactions between centroids
is not representative of interactions between the actual elements. This drawback could be
circumvented by using the Hausdorff distance between bounding boxes instead of the Euclidean
distance as the parameter for the interaction functions." This module builds that model.

The model is eq. (2)'s multitype Strauss hard-core density with the pair distance
d(x_i, x_j) replaced by a distance between the filled oriented bounding boxes B_i, B_j of the
two elements *as placed*: each point carries the reference element pasted on it (a mark,
uniform over its category's references), so the interaction depends on where the element is
and on its shape and orientation. Two box distances are offered:

- ``"hausdorff"``, d_H(B_i, B_j): the paper's proposal. It is never shorter than the distance
  of the box centres (boxes are centrally symmetric: the support functions of B_i and B_j
  differ by at least |(c_i - c_j) . u| in the direction u or -u), and it *equals* it for two
  translated copies of one box. So for near-parallel elements of one shape, as a hatching, it
  is the centroid model again; for crossing strokes of length L at angle delta it is about
  (L/2) sin(delta), i.e. it measures how different two placed boxes are, not how close.
- ``"gap"``, the distance between the two filled boxes (0 when they intersect): our variant,
  not in the paper. A hard core on it forbids boxes closer than h, so an exemplar without
  overlapping boxes gives a synthesis without them. It can be shorter than the centres'
  distance by up to the two boxes' half-diagonals (the ``padding`` of
  :class:`paperlib.pointprocess.PairDistance`).

Notebook ``hurtut2009_fig09_limitations`` measures both against the centroid model.

Fit (section 3.2's three steps on box distances), :func:`fit_box_model`:

1. h_ab = the smallest box distance between exemplar elements of categories a and b (3.2.1;
   0 for the gap when two exemplar boxes intersect: no hard core);
2. r_ab = the first minimum of the centred "box L function" sqrt(K_H/pi) - t, where
   K_H(t) = |W| / (n_a n_b) sum_{i in a, j in b, i != j} e_ij 1[d_H(B_i, B_j) <= t] with the
   translation edge correction e_ij = |W| / |W cap (W + x_j - x_i)| of the box centres (exact
   for rectangles; other windows use their frame), read off by the same rule as the centroid
   model (:func:`paperlib.pointprocess.select_radius`, rebound 3 CSR standard deviations);
3. beta and gamma by maximum pseudolikelihood (:func:`paperlib.pointprocess.ppm` with its
   ``pair_distance``): every dummy quadrature point of category m carries a reference box of
   m, reference ``j mod N_m`` for the j-th dummy of that category (a deterministic spread over
   the references that integrates the conditional intensity over the mark).

Simulation, :func:`simulate_box_model`: the birth-death Metropolis-Hastings chain of Figure 4
(Geyer and Moller 1994, equiprobable births and deaths) over marked points (location,
category, reference). A birth proposes a location uniform in the window's frame, a category
uniform among the K categories and a reference uniform in it; with f the density,
R_birth = beta_m rho(u) prod gamma^t |F| K / (n + 1) and R_death = n / (|F| K lambda(x_i)),
the number of references cancelling. Births outside the window (or its mask) are rejected.
The numba kernel compares a candidate with every current element whose centre is closer than
the largest radius plus the padding, so a step costs O(n): meant for the arrangements of the
paper (hundreds of elements), not for 1e5.

References
----------
Hurtut, T., Landes, P.-E., Thollot, J., Gousseau, Y., Drouilhet, R., Coeurjolly, J.-F.
(2009). Appearance-guided synthesis of element arrangements by example. NPAR, sections 3.2,
3.3 (Figure 4) and 4.3 (Figure 9 right).
Geyer, C. J. and Moller, J. (1994). Simulation procedures and likelihood inference for
spatial point processes. Scandinavian Journal of Statistics 21, 359-373.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np
import pandas as pd

from paperlib._checks import as_generator, check_choice, finite_array
from paperlib.pointprocess import (
    MultiStraussHard,
    PairDistance,
    PPMFit,
    PointPattern,
    Window,
    csr_L_sd,
    fine_nd,
    intensity_map_values,
    ppm,
    quadscheme,
    select_radius,
)
from paperlib.pointprocess.summary import default_r

__all__ = ["BOX_DISTANCES", "BoxInteractionFit", "box_distance_matrix", "box_gap", "box_hausdorff", "box_L",
           "fit_box_model", "simulate_box_model"]

BOX_DISTANCES = ("hausdorff", "gap")  # code 0 and 1 in the numba kernels
REBOUND = 3.0  # CSR standard deviations confirming a minimum of L, as interaction_radii
# Quadrature grid side cap: fine_nd (spacing below h / 4) asks for 512^2 dummies when h is a small gap,
# and each dummy carries a box; 128^2 keeps the fit under a second.
MAX_ND = 128
_CHUNK = 8192  # MCMC proposals drawn (in NumPy) per kernel call


@dataclass(frozen=True, eq=False)
class BoxInteractionFit:
    """The section 3.2 estimation on box distances.

    Attributes
    ----------
    ppm : PPMFit
        Step 3 (beta, gamma) with its coefficient table and variances.
    distance : {"hausdorff", "gap"}
        The box distance the interactions act on.
    distances : pandas.DataFrame
        Per category pair: ``a``, ``b``, ``h``, ``r``, ``rule``, ``noise_sd``, ``rebound_height``.
    curves : dict
        ``(a, b) -> DataFrame`` with columns ``r`` and ``L`` (the centred box L function).
    """

    ppm: PPMFit
    distance: str
    distances: pd.DataFrame
    curves: dict

    @property
    def model(self) -> MultiStraussHard:
        return self.ppm.model


# ---------------------------------------------------------------------------- distances


def _kind(distance: str) -> int:
    check_choice(distance, BOX_DISTANCES, "distance")
    return BOX_DISTANCES.index(distance)


def box_distance_matrix(corners_a, corners_b=None, distance: str = "hausdorff") -> np.ndarray:
    """Box distances between every box of ``corners_a`` and every box of ``corners_b``.

    Parameters
    ----------
    corners_a, corners_b : array_like, shape (n, 4, 2) and (m, 4, 2)
        Box corners in boundary order (``OrientedBoxes.corners()``); ``corners_b`` defaults
        to ``corners_a``.
    distance : {"hausdorff", "gap"}

    Returns
    -------
    ndarray, shape (n, m)
    """
    kind = _kind(distance)
    a = np.ascontiguousarray(finite_array(corners_a, "corners_a", shape=(None, 4, 2)))
    b = a if corners_b is None else np.ascontiguousarray(finite_array(corners_b, "corners_b", shape=(None, 4, 2)))
    return _all_pairs(kind, a, b)


def _paired_distances(kind: int, corners_a: np.ndarray, corners_b: np.ndarray, cutoff: float) -> np.ndarray:
    """Box distance of each pair (a[i], b[i]); pairs surely beyond ``cutoff`` get a lower bound >= cutoff."""
    return _each_pair(kind, np.ascontiguousarray(corners_a), np.ascontiguousarray(corners_b), cutoff)


def _translation_weights(window: Window, points: np.ndarray) -> np.ndarray:
    """e_ij = |F| / |F cap (F + x_j - x_i)| for the window's frame F (pairs farther apart than F: 0)."""
    dx = np.abs(points[:, None, 0] - points[None, :, 0])
    dy = np.abs(points[:, None, 1] - points[None, :, 1])
    overlap = np.clip(window.width - dx, 0, None) * np.clip(window.height - dy, 0, None)
    with np.errstate(divide="ignore"):
        return np.where(overlap > 0, window.width * window.height / overlap, 0.0)


def box_L(distances, positions, marks, window: Window, a: int, b: int, t) -> np.ndarray:
    """The centred box L function sqrt(K_H(t)/pi) - t of categories a and b (module docstring).

    Parameters
    ----------
    distances : ndarray, shape (n, n)
        Box distances between the exemplar's elements (:func:`box_distance_matrix`).
    positions : ndarray, shape (n, 2)
        Box centres (for the translation edge correction).
    marks : ndarray of int, shape (n,)
    window : Window
    a, b : int
        Categories.
    t : array_like
        Distances at which to evaluate, increasing.

    Returns
    -------
    ndarray, shape like ``t``
    """
    t = np.asarray(t, dtype=np.float64)
    first, second = np.flatnonzero(marks == a), np.flatnonzero(marks == b)
    d = distances[np.ix_(first, second)]
    weight = _translation_weights(window, positions)[np.ix_(first, second)]
    if a == b:
        np.fill_diagonal(d, np.inf)
    order = np.argsort(d, axis=None)
    cumulative = np.concatenate([[0.0], np.cumsum(weight.reshape(-1)[order])])
    below = np.searchsorted(d.reshape(-1)[order], t, side="right")
    K = window.area * cumulative[below] / (len(first) * len(second))
    return np.sqrt(K / np.pi) - t


# ---------------------------------------------------------------------------- fit


def _pairs(m: int) -> list[tuple[int, int]]:
    return [(a, b) for b in range(m) for a in range(b + 1)]


def _hardcores(distances: np.ndarray, marks: np.ndarray, m: int) -> np.ndarray:
    """Section 3.2.1 on box distances: the smallest distance of each category pair."""
    d = distances.copy()
    np.fill_diagonal(d, np.inf)
    h = np.empty((m, m))
    for a, b in _pairs(m):
        h[a, b] = h[b, a] = d[np.ix_(marks == a, marks == b)].min()
    return h


def _radii(distances, pattern: PointPattern, h: np.ndarray, rmax, rebound: float):
    """Section 3.2.2 on box distances: the first minimum of each centred box L function."""
    m, names = pattern.n_types, pattern.categories
    t = default_r(pattern.window, pattern.intensity, rmax)
    radii, rows, curves = np.empty((m, m)), [], {}
    for a, b in _pairs(m):
        L = box_L(distances, pattern.points, pattern.marks, pattern.window, a, b, t)
        noise = csr_L_sd(pattern.window.area, pattern.counts[a], pattern.counts[b], a == b)
        r_star, rule = select_radius(t, L, h[a, b], rebound * noise)
        radii[a, b] = radii[b, a] = r_star
        curves[(names[a], names[b])] = pd.DataFrame({"r": t, "L": L})
        rows.append({"a": names[a], "b": names[b], "h": h[a, b], "r": r_star, "rule": rule, "noise_sd": noise,
                     "rebound_height": rebound * noise})
    return radii, pd.DataFrame(rows), curves


def _quadrature_corners(scheme, pattern: PointPattern, corners: np.ndarray, reference_corners) -> np.ndarray:
    """A box for every quadrature point: data keep theirs, dummies get a reference of their category."""
    boxes = np.empty((scheme.n_points, 4, 2))
    boxes[: pattern.n] = corners
    dummies = np.flatnonzero(~scheme.is_data)
    for m, references in enumerate(reference_corners):
        of_type = dummies[scheme.types[dummies] == m]
        picks = np.arange(len(of_type)) % len(references)
        boxes[of_type] = references[picks] + scheme.points[of_type, None, :]
    return boxes


def fit_box_model(pattern: PointPattern, corners, reference_corners, *, distance: str = "hausdorff", rmax=None,
                  rebound: float = REBOUND, nd=None, gamma_max: float | None = 1.0) -> BoxInteractionFit:
    """Fit the multitype Strauss hard-core model on box distances (Hurtut 2009, 3.2 and 4.3).

    Parameters
    ----------
    pattern : PointPattern
        Element positions (box centres) with category marks, >= 3 per category.
    corners : ndarray, shape (n, 4, 2)
        Each element's oriented bounding box, in the order of ``pattern.points``.
    reference_corners : sequence of ndarray, shape (N_m, 4, 2)
        Per category, its elements' boxes centred on the origin (what is pasted).
    distance : {"hausdorff", "gap"}
        The box distance (module docstring): the paper's proposal, or our gap.
    rmax : float, optional
        Largest distance examined for r (default: spatstat's rule).
    rebound : float
        Rebound height, in CSR standard deviations, that confirms a minimum of L.
    nd : int, optional
        Quadrature grid side (default :func:`paperlib.pointprocess.fine_nd`, at most ``MAX_ND``).
    gamma_max : float or None
        Upper bound of gamma (default 1, the paper's model; ``None``: unconstrained), as for
        :func:`paperlib.pointprocess.ppm`.

    Returns
    -------
    BoxInteractionFit

    Raises
    ------
    ValueError
        For an unknown ``distance``, or as :func:`paperlib.pointprocess.ppm`.
    """
    corners = np.asarray(corners, dtype=np.float64)
    if corners.shape != (pattern.n, 4, 2):
        raise ValueError(f"corners must have shape ({pattern.n}, 4, 2), got {corners.shape}")
    kind = _kind(distance)
    distances = box_distance_matrix(corners, distance=distance)
    h = _hardcores(distances, pattern.marks, pattern.n_types)
    radii, table, curves = _radii(distances, pattern, h, rmax, rebound)
    scheme = quadscheme(pattern, nd=nd if nd is not None else min(fine_nd(pattern, radii, h), MAX_ND))
    boxes = _quadrature_corners(scheme, pattern, corners, reference_corners)
    cutoff = float(radii.max())
    pair_distance = PairDistance(lambda i, j: _paired_distances(kind, boxes[i], corners[j], cutoff),
                                 _padding(kind, corners, reference_corners))
    fitted = ppm(pattern, radii, h, closed=False, quadrature=scheme, pair_distance=pair_distance, gamma_max=gamma_max)
    return BoxInteractionFit(fitted, distance, table, curves)


def _padding(kind: int, *corner_sets) -> float:
    """How much shorter than the centres' distance a box distance can be: 0, or two half-diagonals."""
    if kind == 0:
        return 0.0
    largest = 0.0
    for corners in corner_sets:
        for boxes in (corners if isinstance(corners, (list, tuple)) else [corners]):
            boxes = np.asarray(boxes, dtype=np.float64)
            if len(boxes):
                centres = boxes.mean(axis=1, keepdims=True)
                largest = max(largest, float(np.sqrt(((boxes - centres) ** 2).sum(axis=2)).max()))
    return 2.0 * largest


# ---------------------------------------------------------------------------- simulation


@numba.njit(cache=True)
def _distance_to_box(px, py, box):
    """Distance from a point to a filled convex quadrilateral (0 inside; degenerate boxes allowed)."""
    area = 0.0
    for k in range(4):
        x0, y0 = box[k, 0], box[k, 1]
        x1, y1 = box[(k + 1) % 4, 0], box[(k + 1) % 4, 1]
        area += x0 * y1 - x1 * y0
    sign = 1.0 if area >= 0 else -1.0
    inside = True
    best = np.inf
    for k in range(4):
        x0, y0 = box[k, 0], box[k, 1]
        ex, ey = box[(k + 1) % 4, 0] - x0, box[(k + 1) % 4, 1] - y0
        wx, wy = px - x0, py - y0
        if sign * (ex * wy - ey * wx) < 0:
            inside = False
        length2 = ex * ex + ey * ey
        s = 0.0 if length2 == 0 else min(1.0, max(0.0, (wx * ex + wy * ey) / length2))
        dx, dy = wx - s * ex, wy - s * ey
        best = min(best, np.sqrt(dx * dx + dy * dy))
    return 0.0 if inside and area != 0 else best


@numba.njit(cache=True)
def _directed(a, b):
    # the distance to a convex set is convex, so its maximum over the filled box a is at a corner
    worst = 0.0
    for k in range(4):
        worst = max(worst, _distance_to_box(a[k, 0], a[k, 1], b))
    return worst


@numba.njit(cache=True)
def box_hausdorff(a, b):
    """Hausdorff distance between two filled convex quadrilaterals (numba; as geometry.hausdorff_boxes)."""
    return max(_directed(a, b), _directed(b, a))


@numba.njit(cache=True)
def _orientation(ax, ay, bx, by, cx, cy):
    value = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    return (value > 0) - (value < 0)


@numba.njit(cache=True)
def _segments_cross(px, py, qx, qy, rx, ry, sx, sy):
    """Whether segments pq and rs share a point (collinear overlaps included)."""
    o1 = _orientation(px, py, qx, qy, rx, ry)
    o2 = _orientation(px, py, qx, qy, sx, sy)
    o3 = _orientation(rx, ry, sx, sy, px, py)
    o4 = _orientation(rx, ry, sx, sy, qx, qy)
    if o1 != o2 and o3 != o4:
        return True
    if o1 == 0 and o2 == 0 and o3 == 0 and o4 == 0:  # collinear: overlapping projections on both axes
        return (max(px, qx) >= min(rx, sx) and max(rx, sx) >= min(px, qx)
                and max(py, qy) >= min(ry, sy) and max(ry, sy) >= min(py, qy))
    return False


@numba.njit(cache=True)
def _bounds_overlap(a, b):
    return (a[:, 0].max() >= b[:, 0].min() and b[:, 0].max() >= a[:, 0].min()
            and a[:, 1].max() >= b[:, 1].min() and b[:, 1].max() >= a[:, 1].min())


@numba.njit(cache=True)
def box_gap(a, b):
    """Distance between two filled convex quadrilaterals: 0 when they intersect (numba).

    Disjoint convex polygons are closest at a corner of one of them; they intersect when a
    corner of one lies in the other (distance 0) or two edges cross.
    """
    if _bounds_overlap(a, b):
        for k in range(4):
            k1 = (k + 1) % 4
            for l in range(4):
                l1 = (l + 1) % 4
                if _segments_cross(a[k, 0], a[k, 1], a[k1, 0], a[k1, 1], b[l, 0], b[l, 1], b[l1, 0], b[l1, 1]):
                    return 0.0
    best = np.inf
    for k in range(4):
        best = min(best, _distance_to_box(a[k, 0], a[k, 1], b), _distance_to_box(b[k, 0], b[k, 1], a))
    return best


@numba.njit(cache=True)
def _box_distance(kind, a, b):
    return box_hausdorff(a, b) if kind == 0 else box_gap(a, b)


@numba.njit(cache=True)
def _all_pairs(kind, a, b):
    out = np.empty((a.shape[0], b.shape[0]))
    for i in range(a.shape[0]):
        for j in range(b.shape[0]):
            out[i, j] = _box_distance(kind, a[i], b[j])
    return out


@numba.njit(cache=True)
def _circumcircle(box):
    cx, cy = 0.25 * box[:, 0].sum(), 0.25 * box[:, 1].sum()
    radius = 0.0
    for k in range(4):
        radius = max(radius, np.hypot(box[k, 0] - cx, box[k, 1] - cy))
    return cx, cy, radius


@numba.njit(cache=True)
def _each_pair(kind, a, b, cutoff):
    out = np.empty(a.shape[0])
    for i in range(a.shape[0]):
        ax, ay, ar = _circumcircle(a[i])
        bx, by, br = _circumcircle(b[i])
        bound = np.hypot(ax - bx, ay - by) - ar - br  # no two points of the boxes are closer
        out[i] = bound if bound >= cutoff else _box_distance(kind, a[i], b[i])
    return out


@numba.njit(cache=True)
def _log_interaction(kind, box, cx, cy, mark, skip, n, xs, ys, marks, corners, log_gamma, r, hc, reach, search2):
    """log prod gamma^t of a candidate box against the current elements; -inf inside a hard core."""
    total = 0.0
    radius = _circumcircle(box)[2]
    for j in range(n):
        if j == skip:
            continue
        dx, dy = xs[j] - cx, ys[j] - cy
        d2 = dx * dx + dy * dy
        if d2 >= search2:
            continue  # centres farther than the largest radius plus the padding: out of reach
        if kind == 1 and np.sqrt(d2) - radius - _circumcircle(corners[j])[2] >= reach:
            continue  # the circumcircles are farther apart than the reach
        d = _box_distance(kind, box, corners[j])
        other = marks[j]
        if d < hc[mark, other]:
            return -np.inf
        if d < r[mark, other]:
            total += log_gamma[mark, other]
    return total


@numba.njit(cache=True)
def _birth_death_steps(kind, n, xs, ys, marks, refs, rho, corners, reference_corners, reference_start, log_beta,
                       log_gamma, r, hc, reach, search2, log_frame_k, births, ux, uy, um, uk, urho, u_death,
                       u_accept):
    """Run one chunk of birth-death steps in place; returns the new number of elements."""
    box = np.empty((4, 2))
    for step in range(births.shape[0]):
        if births[step]:
            if urho[step] <= 0:
                continue  # outside the window, or zero density
            m, k = um[step], uk[step]
            reference = reference_corners[reference_start[m] + k]
            for c in range(4):
                box[c, 0] = reference[c, 0] + ux[step]
                box[c, 1] = reference[c, 1] + uy[step]
            log_lambda = log_beta[m] + np.log(urho[step]) + _log_interaction(
                kind, box, ux[step], uy[step], m, -1, n, xs, ys, marks, corners, log_gamma, r, hc, reach, search2)
            if np.log(u_accept[step]) < log_lambda + log_frame_k - np.log(n + 1.0):
                xs[n], ys[n], marks[n], refs[n], rho[n] = ux[step], uy[step], m, k, urho[step]
                corners[n] = box
                n += 1
        elif n > 0:
            i = min(int(u_death[step] * n), n - 1)
            log_lambda = log_beta[marks[i]] + np.log(rho[i]) + _log_interaction(
                kind, corners[i], xs[i], ys[i], marks[i], i, n, xs, ys, marks, corners, log_gamma, r, hc, reach,
                search2)
            if np.log(u_accept[step]) < np.log(n * 1.0) - log_frame_k - log_lambda:
                last = n - 1
                xs[i], ys[i], marks[i], refs[i], rho[i] = xs[last], ys[last], marks[last], refs[last], rho[last]
                corners[i] = corners[last]
                n = last
    return n


def simulate_box_model(model: MultiStraussHard, reference_corners, window: Window, T: int, *,
                       distance: str = "hausdorff", intensity_map=None, rng=None) -> tuple[PointPattern, np.ndarray]:
    """Run T birth-death steps of the box-distance model from the empty arrangement.

    Parameters
    ----------
    model : MultiStraussHard
        beta, gamma, r, hc on box distances (open convention: d < hc forbidden, d < r interacts).
    reference_corners : sequence of ndarray, shape (N_m, 4, 2)
        Per category, the boxes of its references centred on the origin.
    window : Window
    T : int
    distance : {"hausdorff", "gap"}
        The box distance the model was fitted on.
    intensity_map : ndarray, optional
        Factor of beta over the window's frame, row 0 at the bottom (rmh's convention).
    rng : None, int or numpy.random.Generator

    Returns
    -------
    pattern : PointPattern
        Box centres with category marks.
    references : ndarray of int
        The reference (index within its category) pasted on each point.
    """
    kind = _kind(distance)
    rng = as_generator(rng)
    k = model.n_types
    counts = np.array([len(c) for c in reference_corners], dtype=np.int64)
    flat = np.ascontiguousarray(np.concatenate([np.asarray(c, dtype=np.float64) for c in reference_corners]))
    start = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
    with np.errstate(divide="ignore"):
        log_beta, log_gamma = np.log(np.asarray(model.beta, float)), np.log(np.asarray(model.gamma, float))
    r, hc = np.ascontiguousarray(model.r, dtype=np.float64), np.ascontiguousarray(model.hc, dtype=np.float64)
    reach = float(np.max(r))
    search2 = (reach + _padding(kind, list(reference_corners))) ** 2
    frame_area = window.width * window.height
    log_frame_k = float(np.log(frame_area * k))
    capacity = _CHUNK
    xs, ys, rho = np.empty(capacity), np.empty(capacity), np.empty(capacity)
    marks, refs = np.empty(capacity, np.int64), np.empty(capacity, np.int64)
    corners = np.empty((capacity, 4, 2))
    n = 0
    for begin in range(0, int(T), _CHUNK):
        size = min(_CHUNK, int(T) - begin)
        if n + size > capacity:
            capacity = 2 * (n + size)
            xs, ys, rho, marks, refs, corners = (np.resize(a, (capacity, *a.shape[1:]))
                                                 for a in (xs, ys, rho, marks, refs, corners))
        births = rng.random(size) < 0.5
        ux = window.xrange[0] + window.width * rng.random(size)
        uy = window.yrange[0] + window.height * rng.random(size)
        um = rng.integers(0, k, size)
        uk = np.minimum((rng.random(size) * counts[um]).astype(np.int64), counts[um] - 1)
        locations = np.column_stack([ux, uy])
        urho = np.where(window.contains(locations), 1.0, 0.0)
        if intensity_map is not None:
            urho *= intensity_map_values(intensity_map, window, locations)
        u_death, u_accept = rng.random(size), rng.random(size)
        n = _birth_death_steps(kind, n, xs, ys, marks, refs, rho, corners, flat, start, log_beta, log_gamma, r, hc,
                               reach, search2, log_frame_k, births, ux, uy, um, uk, urho, u_death, u_accept)
    points = np.column_stack([xs[:n], ys[:n]])
    pattern = PointPattern(points, window, marks[:n].copy(), model.categories)
    return pattern, refs[:n].copy()
