"""Synthesis of a stroke pattern along a path or in a region (Barla 2006, section 3, Algorithm 1).

1. **Seeds** (3.2): N_tar = N_ref A_tar / A_ref seeds, random then relaxed by Lloyd's method: along the path
   in 1D (cells are arc-length intervals, each seed moves to its cell's midpoint), in the region in 2D
   (Voronoi cells clipped to the region, :func:`paperlib.geometry.lloyd_relaxation`). Neighbours: the chain
   (1D) or the unskewed Delaunay edges (2D), as in the analysis.
2. **Growth** (3.2): from the seed nearest the middle of the path or the centroid of the region, outward:
   by the number of graph hops from it, ties by distance.
3. **Matching** (3.1): the k-ring neighbourhood of each seed (every element within k hops) is compared with
   the k-ring neighbourhood of every reference element: closest elements are paired (mutual nearest
   neighbours in position, Figure 3), the five perceptual measures are averaged over the pairs, and the
   neighbourhood matches if ``col and (shape or (par and ov and sup))``. Only known (already synthesised)
   elements take part: the average runs over the pairs they form, so a partial neighbourhood is normalised
   by its known count (section 3.2). One matching reference element is chosen at random and its strokes are
   copied to the seed.
4. **Fallback** (not in the paper, which notes that "it can happen that no pairing is found" but that
   Lloyd's even distribution keeps it rare): when no reference neighbourhood matches, the one with the
   smallest rule score (:func:`.measures.rule_score`, the fuzzy version of the rule) is taken; elements with
   no known neighbour (the first one) take a uniformly random reference element. ``Synthesis.matched`` says
   which elements came from the matching set.

In 1D each element has a local frame, the tangent of its path: neighbour offsets and orientations are
measured in it, and a copied element is turned by the difference between the target's and the reference's
tangents, so a pattern drawn along a straight line follows a curved target path.

References
----------
.. [1] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern Analysis and Synthesis",
   Computer Graphics Forum (Eurographics) 25(3), 2006, section 3 and Algorithm 1.
.. [2] A. A. Efros, T. K. Leung, "Texture synthesis by non-parametric sampling", ICCV 1999 (growth from the
   centre with partial neighbourhoods).
.. [3] S. P. Lloyd, "Least squares quantization in PCM", IEEE Trans. Information Theory 28(2), 1982.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from scipy import sparse
from scipy.sparse.csgraph import breadth_first_order

from ..geometry import Element, Stroke, lloyd_relaxation
from ._kernels import grow
from .analysis import (
    PatternAnalysis,
    _as_path,
    as_region,
    chain_edges,
    path_frames,
    unskewed_delaunay_edges,
)
from .measures import Thresholds, measure_tables

__all__ = ["Seeds", "Synthesis", "as_region", "growth_order", "ring_neighbourhoods", "seeds_1d", "seeds_2d",
           "synthesize", "target_count"]

#: Lloyd iterations by default. From a stratified random start in 1D the spacing then varies by about 1 %
#: (std / mean; Lloyd in 1D is a diffusion whose longest wavelengths decay slowly); in 2D, from a uniform start,
#: the unskewed Delaunay edge lengths vary by under 25 % (see the tests).
LLOYD_ITERATIONS = 40


# --------------------------------------------------------------------------- targets


def _extent(target, dimension: int):
    """The target as a path (1D) or region (2D), and its length or area."""
    if dimension == 1:
        path = _as_path(target, name="target path")
        return path, float(np.hypot(*np.diff(path, axis=0).T).sum())
    region = as_region(target)
    return region, float(region.area)


def target_count(analysis: PatternAnalysis, target) -> int:
    """N_tar = N_ref A_tar / A_ref, rounded, at least 1 (section 3.2)."""
    _, extent = _extent(target, analysis.dimension)
    return max(1, int(round(len(analysis) * extent / analysis.area)))


# --------------------------------------------------------------------------- seeds


@dataclass(frozen=True, eq=False)
class Seeds:
    """Relaxed seed positions with their local frames and neighbour graph."""

    positions: np.ndarray
    frames: np.ndarray
    edges: np.ndarray
    arc: np.ndarray


def _lloyd_1d(arc: np.ndarray, length: float, iterations: int) -> np.ndarray:
    """Lloyd's method on [0, length]: each sorted seed to the midpoint of its cell (between midpoints)."""
    arc = np.sort(arc)
    for _ in range(iterations):
        bounds = np.concatenate([[0.0], (arc[1:] + arc[:-1]) / 2.0, [length]])
        arc = (bounds[1:] + bounds[:-1]) / 2.0
    return arc


def _points_on_path(path: np.ndarray, arc: np.ndarray) -> np.ndarray:
    return shapely.get_coordinates(shapely.line_interpolate_point(shapely.linestrings(path), arc))


def seeds_1d(path, n: int, *, iterations: int = LLOYD_ITERATIONS, rng=None) -> Seeds:
    """N seeds along a polyline by Lloyd's method in arc length (section 3.2), chained in path order.

    The random start draws one uniform position in each of n equal arc-length strata: a random start without
    the long-wavelength clumps that 1D Lloyd iterations take O(n^2) steps to even out.
    """
    path, length = _extent(path, 1)
    n = _count(n)
    rng = np.random.default_rng(rng)
    start = (np.arange(n) + rng.random(n)) * (length / n)
    arc = _lloyd_1d(start, length, _iterations(iterations))
    return Seeds(_points_on_path(path, arc), path_frames(path, arc), chain_edges(np.arange(n)), arc)


def _uniform_in(region, n: int, rng) -> np.ndarray:
    """n distinct uniform points in a region, by rejection from its bounding box."""
    xmin, ymin, xmax, ymax = region.bounds
    shapely.prepare(region)
    kept = np.empty((0, 2))
    while len(kept) < n:
        batch = 2 * (n - len(kept)) + 16
        candidates = np.column_stack([rng.uniform(xmin, xmax, batch), rng.uniform(ymin, ymax, batch)])
        inside = shapely.contains_xy(region, candidates[:, 0], candidates[:, 1])
        kept = np.vstack([kept, candidates[inside]])
    return kept[:n]


def seeds_2d(region, n: int, *, iterations: int = LLOYD_ITERATIONS, rng=None) -> Seeds:
    """N seeds in a region by Lloyd's method (Voronoi cells clipped to the region, section 3.2).

    Neighbours are the unskewed Delaunay edges (no triangle angle above 2 pi / 3), as in the analysis.
    """
    region, _ = _extent(region, 2)
    n = _count(n)
    if n < 3:
        raise ValueError(f"a 2D synthesis needs at least 3 seeds, got {n}: enlarge the region")
    rng = np.random.default_rng(rng)
    positions = lloyd_relaxation(_uniform_in(region, n, rng), region, _iterations(iterations))
    return Seeds(positions, np.zeros(n), unskewed_delaunay_edges(positions), np.full(n, np.nan))


def _count(n) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"the number of seeds must be an integer >= 1, got {n!r}")
    return int(n)


def _iterations(iterations) -> int:
    if isinstance(iterations, bool) or not isinstance(iterations, (int, np.integer)) or iterations < 0:
        raise ValueError(f"iterations must be an integer >= 0, got {iterations!r}")
    return int(iterations)


# --------------------------------------------------------------------------- graphs


def _adjacency(n: int, edges) -> sparse.csr_matrix:
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    rows = np.concatenate([edges[:, 0], edges[:, 1]])
    cols = np.concatenate([edges[:, 1], edges[:, 0]])
    return sparse.csr_matrix((np.ones(len(rows), dtype=np.int8), (rows, cols)), shape=(n, n))


def ring_neighbourhoods(n: int, edges, rings: int):
    """The k-ring neighbourhood of every node: all nodes within ``rings`` hops, itself excluded.

    Returns CSR arrays ``(pointers, neighbours)``: node ``i``'s neighbourhood is
    ``neighbours[pointers[i]:pointers[i + 1]]``, sorted.
    """
    if isinstance(rings, bool) or not isinstance(rings, (int, np.integer)) or rings < 1:
        raise ValueError(f"rings (the neighbourhood size k) must be an integer >= 1, got {rings!r}")
    adjacency = _adjacency(n, edges)
    reach = sparse.identity(n, dtype=np.int8, format="csr")
    for _ in range(int(rings)):
        reach = ((reach + reach @ adjacency) > 0).astype(np.int8)
    reach = (reach - sparse.identity(n, dtype=np.int8, format="csr")).tocsr()
    reach.eliminate_zeros()
    reach.sort_indices()
    return reach.indptr.astype(np.int64), reach.indices.astype(np.int64)


def _local_offsets(positions, frames, pointers, neighbours) -> np.ndarray:
    """Each neighbour's position relative to its node, in the node's frame."""
    owner = np.repeat(np.arange(len(positions)), np.diff(pointers))
    relative = positions[neighbours] - positions[owner]
    cos, sin = np.cos(frames[owner]), np.sin(frames[owner])
    return np.column_stack([cos * relative[:, 0] + sin * relative[:, 1], -sin * relative[:, 0] + cos * relative[:, 1]])


def growth_order(positions, edges, start: int) -> np.ndarray:
    """Nodes by increasing hops from ``start``, ties by distance to it; unreachable nodes last (section 3.2)."""
    n = len(positions)
    hops = np.full(n, np.inf)
    visited, predecessors = breadth_first_order(_adjacency(n, edges), start, directed=False)
    hops[start] = 0
    for node in visited[1:]:
        hops[node] = hops[predecessors[node]] + 1
    distance = np.hypot(*(positions - positions[start]).T)
    return np.lexsort((np.arange(n), distance, hops))


def _start(seeds: Seeds, target, dimension: int) -> int:
    """GetCenterElement: the seed nearest the middle of the path (1D) or the region's centroid (2D)."""
    if dimension == 1:
        return int(np.argmin(np.abs(seeds.arc - seeds.arc[-1] / 2.0 - seeds.arc[0] / 2.0)))
    centre = np.array(target.centroid.coords[0])
    return int(np.argmin(np.hypot(*(seeds.positions - centre).T)))


# --------------------------------------------------------------------------- synthesis


@dataclass(frozen=True, eq=False)
class Synthesis:
    """A synthesised stroke pattern.

    Attributes
    ----------
    elements : tuple of Element
        The synthesised elements, one per seed (copies of reference elements).
    positions : ndarray, shape (n, 2)
        Element centres (the seeds, or shifted by :func:`.variation.vary_positions`).
    frames : ndarray, shape (n,)
        Local frame angle of each seed (path tangent in 1D, 0 in 2D).
    edges : ndarray of int, shape (m, 2)
        The target's neighbour graph (chain or unskewed Delaunay).
    source : ndarray of int, shape (n,)
        The reference element each element copies.
    order : ndarray of int, shape (n,)
        The growth order.
    matched : ndarray of bool, shape (n,)
        True where the choice came from matching neighbourhoods, False for the fallback (or no known neighbour).
    n_candidates : ndarray of int, shape (n,)
        How many reference neighbourhoods matched.
    score : ndarray, shape (n,)
        Rule score of the chosen reference neighbourhood (< 1 matches; NaN without known neighbours).
    dimension : int
    rings : int
    target : ndarray or shapely geometry
        The target path (1D) or region (2D).
    """

    elements: tuple
    positions: np.ndarray
    frames: np.ndarray
    edges: np.ndarray
    source: np.ndarray
    order: np.ndarray
    matched: np.ndarray
    n_candidates: np.ndarray
    score: np.ndarray
    dimension: int
    rings: int
    target: object

    def __len__(self) -> int:
        return len(self.elements)

    @property
    def strokes(self) -> list:
        """All strokes, element after element."""
        return [stroke for element in self.elements for stroke in element.strokes]


def place_element(element: Element, center, angle: float, new_center) -> Element:
    """The element turned by ``angle`` about ``center``, then moved so that ``center`` lands on ``new_center``."""
    cos, sin = np.cos(angle), np.sin(angle)
    rotation = np.array([[cos, -sin], [sin, cos]])
    offset = np.asarray(new_center) - rotation @ np.asarray(center)
    strokes = tuple(Stroke(s.points @ rotation.T + offset, s.width, s.color) for s in element.strokes)
    return Element(strokes, element.name)


def _graph_arrays(positions, frames, edges, rings):
    pointers, neighbours = ring_neighbourhoods(len(positions), edges, rings)
    return pointers, neighbours, _local_offsets(positions, frames, pointers, neighbours)


def synthesize(analysis: PatternAnalysis, target, *, rings: int = 2, n: int | None = None,
               thresholds: Thresholds | None = None, choice: str = "random", iterations: int = LLOYD_ITERATIONS,
               rng=None) -> Synthesis:
    """Synthesise a pattern like the analysed reference along a path (1D) or in a region (2D) (Algorithm 1).

    Parameters
    ----------
    analysis : PatternAnalysis
        The reference, from :func:`.analysis.analyze`; its ``dimension`` decides the kind of target.
    target : array_like (m, 2) or shapely Polygon or (xmin, xmax, ymin, ymax)
        1D: the polyline to fill (positive length). 2D: the region (positive area).
    rings : int
        k of the k-ring neighbourhoods (>= 1). The paper uses 5 for Fig. 6 c-e, 3 and 2 in Fig. 7.
    n : int, optional
        Number of elements; default N_tar = N_ref A_tar / A_ref (:func:`target_count`).
    thresholds : Thresholds, optional
        The perceptual thresholds; default the paper's.
    choice : {"random", "best"}
        "random" (the paper): a uniform choice among the matching reference neighbourhoods. "best": the one
        with the smallest rule score (an option, to show what the random choice trades for variety).
    iterations : int
        Lloyd iterations for the seeds.
    rng : None, int or numpy.random.Generator
        Drives the seeds and the choices; same seed, same pattern.

    Returns
    -------
    Synthesis

    Raises
    ------
    ValueError
        A target path of zero length, a region of zero area, a 2D target too small for 3 seeds, rings < 1.

    References
    ----------
    Barla et al. 2006, sections 3.1-3.2 and Algorithm 1.
    """
    if not isinstance(analysis, PatternAnalysis):
        raise ValueError(f"analysis must be a PatternAnalysis from analyze(), got {type(analysis).__name__}")
    thresholds = Thresholds() if thresholds is None else thresholds
    if not isinstance(thresholds, Thresholds):
        raise ValueError(f"thresholds must be a Thresholds, got {type(thresholds).__name__}")
    if choice not in ("random", "best"):
        raise ValueError(f"choice must be 'random' or 'best', got {choice!r}")
    dimension = analysis.dimension
    shape, _ = _extent(target, dimension)
    count = target_count(analysis, shape) if n is None else _count(n)
    rng = np.random.default_rng(rng)
    seed_rng, choice_rng = rng.spawn(2)
    make_seeds = seeds_1d if dimension == 1 else seeds_2d
    seeds = make_seeds(shape, count, iterations=iterations, rng=seed_rng)
    order = growth_order(seeds.positions, seeds.edges, _start(seeds, shape, dimension))
    tables = measure_tables(analysis.boxes.half_lengths, analysis.boxes.angles - analysis.frames, analysis.colors)
    sigmas = thresholds.vector(analysis.mean_length)
    source, matched, n_candidates, score = grow(
        order, *_graph_arrays(seeds.positions, seeds.frames, seeds.edges, rings),
        *_graph_arrays(analysis.positions, analysis.frames, analysis.edges, rings),
        tables, sigmas, choice_rng.random(count), choice == "best")
    elements = tuple(place_element(analysis.elements[s], analysis.positions[s], frame - analysis.frames[s], position)
                     for s, frame, position in zip(source, seeds.frames, seeds.positions))
    return Synthesis(elements=elements, positions=seeds.positions, frames=seeds.frames, edges=seeds.edges,
                     source=source, order=order, matched=matched, n_candidates=n_candidates, score=score,
                     dimension=dimension, rings=int(rings), target=shape)
