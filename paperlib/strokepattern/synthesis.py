"""Synthesis of a stroke pattern along a path or in a region (Barla 2006, section 3, Algorithm 1).

1. **Seeds** (3.2): N_tar = N_ref A_tar / A_ref seeds, random then relaxed by Lloyd's method: along the path
   in 1D (cells are arc-length intervals, each seed moves to its cell's midpoint), in the region in 2D
   (Voronoi cells clipped to the region, :func:`paperlib.geometry.lloyd_relaxation`). Neighbours: the chain
   (1D) or the unskewed Delaunay edges (2D), as in the analysis.
2. **Growth** (3.2): from the seed nearest the middle of the path or the centroid of the region, outward:
   by the number of graph hops from it, ties by distance. The start and its k-ring are seeded with the
   reference's centre element and its k-ring (``start="centre"``, :func:`_seed_patch`, Efros and Leung's seed
   patch; the paper does not say what the start receives).
3. **Matching** (3.1): the k-ring neighbourhood of each seed (every element within k hops) is compared with
   the k-ring neighbourhood of every reference element: closest elements are paired (mutual nearest
   neighbours in position, Figure 3), the five perceptual measures are averaged, and the neighbourhood
   matches if ``col and (shape or (par and ov and sup))``. Only known (already synthesised) elements are
   measured (section 3.2). The paper as written (``matching="paper"``) sums the measures over the pairs and
   divides by the number of known elements; by default (``matching="coverage"``) a pair further apart than
   half the reference's median neighbour distance is no pair, and each known element left unpaired is charged
   its threshold: a reference neighbourhood must cover the known part of the target's, as an Efros-Leung window
   must lie inside the sample.
4. **Choice** (3.1): among the matching neighbourhoods (the set Omega), the paper picks uniformly
   (``choice="random"``); by default (``choice="close"``) the pick is uniform among those within a tenth of a
   threshold of the best rule score, Efros and Leung's rule. The chosen reference element's strokes are
   copied to the seed.
5. **Fallback** (not in the paper, which notes that "it can happen that no pairing is found" but that
   Lloyd's even distribution keeps it rare): when no reference neighbourhood matches, the one with the
   smallest rule score (:func:`.measures.rule_score`, the fuzzy version of the rule) is taken; elements with
   no known neighbour take a uniformly random reference element. ``Synthesis.matched`` says which elements
   came from the matching set, ``Synthesis.fallback`` which took the fallback.

Why the defaults depart from the paper's rules is measured in the notebook ``barla2006_fig06_1d_results``: with
the paper's thresholds Omega spans several elements of a ramp, and a uniform draw in it (with a random start)
loses the ramps of Figure 6 c-e and makes 1D syntheses jump (a third of consecutive elements of a wave turn by
more than 15 degrees, against 3 % in the reference).

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
from ..geometry.voronoi import MAX_CELLS
from .._checks import as_generator, budget, check_budget, instance_of, point_array, positive_number
from ._kernels import BEST, CLOSE, RANDOM, grow
from .analysis import (
    PatternAnalysis,
    _as_path,
    as_region,
    chain_edges,
    graph_edges,
    path_frames,
    unskewed_delaunay_edges,
)
from .measures import Thresholds, measure_tables

__all__ = ["MAX_SEEDS", "Seeds", "Synthesis", "as_region", "growth_order", "pairing_gate", "reference_centre", "ring_neighbourhoods",
           "seeds_1d", "seeds_2d", "synthesize", "target_count"]

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
    """N_tar = N_ref A_tar / A_ref, rounded, at least 1 (section 3.2).

    Parameters
    ----------
    analysis : PatternAnalysis
        The analysed reference (its element count N_ref, area A_ref and dimension).
    target : array_like or shapely.Polygon
        The target path (1D, an ``(m, 2)`` polyline) or region (2D, see :func:`as_region`).

    Returns
    -------
    int
        N_tar, at least 1.
    """
    instance_of(analysis, PatternAnalysis, "analysis")
    _, extent = _extent(target, analysis.dimension)
    return max(1, int(round(len(analysis) * extent / analysis.area)))


# --------------------------------------------------------------------------- seeds


@dataclass(frozen=True, eq=False)
class Seeds:
    """Relaxed seed positions with their local frames and neighbour graph.

    Parameters
    ----------
    positions : ndarray, shape (n, 2)
        The seed positions.
    frames : ndarray, shape (n,)
        Local frame angle of each seed: the path's tangent (1D), 0 (2D).
    edges : ndarray of int, shape (m, 2)
        The neighbour graph: the chain in path order (1D) or the unskewed Delaunay edges (2D).
    arc : ndarray, shape (n,)
        Arc-length position of each seed along the path (1D); NaN in 2D.
    """

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


#: Default budget of :func:`seeds_1d`, :func:`seeds_2d` and :func:`synthesize` (``max_seeds``): the most
#: seeds, checked before anything is allocated. The paper's figures place hundreds; a 2D Lloyd relaxation
#: of 1e5 seeds already takes minutes.
MAX_SEEDS = 100_000


def seeds_1d(path, n: int, *, iterations: int = LLOYD_ITERATIONS, rng=None, max_seeds: int = MAX_SEEDS,
             max_cells: int = MAX_CELLS) -> Seeds:
    """N seeds along a polyline by Lloyd's method in arc length (section 3.2), chained in path order.

    The random start draws one uniform position in each of n equal arc-length strata: a random start without
    the long-wavelength clumps that 1D Lloyd iterations take O(n^2) steps to even out.

    Parameters
    ----------
    path : array_like, shape (m, 2)
        The target polyline.
    n : int
        Number of seeds.
    iterations : int, default 40
        Lloyd iterations.
    rng : None, int or numpy.random.Generator, optional
        Source of randomness for the start.
    max_seeds : int, optional
        Budget: the most seeds (default :data:`MAX_SEEDS`); a larger ``n`` raises ValueError.
    max_cells : int, optional
        Budget: the most Lloyd cells computed, ``n * iterations`` (default
        :data:`paperlib.geometry.voronoi.MAX_CELLS`, 2**22); a larger request raises ValueError
        before anything is drawn.

    Returns
    -------
    Seeds
        Positions on the path, path tangents as frames, the chain edges and the arc lengths.
    """
    path, length = _extent(path, 1)
    n = _seed_count(n, max_seeds)
    iterations = _lloyd_iterations(iterations, n, max_cells)
    rng = as_generator(rng)
    start = (np.arange(n) + rng.random(n)) * (length / n)
    arc = _lloyd_1d(start, length, iterations)
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


def seeds_2d(region, n: int, *, iterations: int = LLOYD_ITERATIONS, rng=None, max_seeds: int = MAX_SEEDS,
             max_cells: int = MAX_CELLS) -> Seeds:
    """N seeds in a region by Lloyd's method (Voronoi cells clipped to the region, section 3.2).

    Neighbours are the unskewed Delaunay edges (no triangle angle above 2 pi / 3), as in the analysis.

    Parameters
    ----------
    region : shapely.Polygon or array_like
        The target region (see :func:`as_region`).
    n : int
        Number of seeds (>= 3).
    iterations : int, default 40
        Lloyd iterations.
    rng : None, int or numpy.random.Generator, optional
        Source of randomness for the uniform start.
    max_seeds : int, optional
        Budget: the most seeds (default :data:`MAX_SEEDS`); a larger ``n`` raises ValueError.
    max_cells : int, optional
        Budget: the most Lloyd cells computed, ``n * iterations`` (default
        :data:`paperlib.geometry.voronoi.MAX_CELLS`, 2**22); a larger request raises ValueError
        before anything is drawn.

    Returns
    -------
    Seeds
        Positions in the region, zero frames, the unskewed Delaunay edges and NaN arc lengths.
    """
    region, _ = _extent(region, 2)
    n = _seed_count(n, max_seeds)
    if n < 3:
        raise ValueError(f"a 2D synthesis needs at least 3 seeds, got {n}: enlarge the region")
    iterations = _lloyd_iterations(iterations, n, max_cells)
    rng = as_generator(rng)
    positions = lloyd_relaxation(_uniform_in(region, n, rng), region, iterations, max_cells=max_cells)
    return Seeds(positions, np.zeros(n), unskewed_delaunay_edges(positions), np.full(n, np.nan))


def _count(n) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n (the number of seeds) must be an integer >= 1, got {n!r:.80}")
    return int(n)


def _seed_count(n, max_seeds) -> int:
    """The number of seeds, checked against the budget ``max_seeds`` before anything is drawn."""
    n = _count(n)
    check_budget(n, budget(max_seeds, "max_seeds"), "max_seeds", "seeds")
    return n


def _lloyd_iterations(iterations, n: int, max_cells) -> int:
    """The number of Lloyd iterations, checked against the budget on cells (``n * iterations``)."""
    if isinstance(iterations, bool) or not isinstance(iterations, (int, np.integer)) or iterations < 0:
        raise ValueError(f"iterations must be an integer >= 0, got {iterations!r}")
    check_budget(n * int(iterations), budget(max_cells, "max_cells"), "max_cells", "Lloyd cells (seeds x iterations)")
    return int(iterations)


# --------------------------------------------------------------------------- graphs


def _adjacency(n: int, edges) -> sparse.csr_matrix:
    edges = graph_edges(edges, n)
    rows = np.concatenate([edges[:, 0], edges[:, 1]])
    cols = np.concatenate([edges[:, 1], edges[:, 0]])
    return sparse.csr_matrix((np.ones(len(rows), dtype=np.int8), (rows, cols)), shape=(n, n))


#: Default budget of :func:`ring_neighbourhoods` (``max_pairs``): (node, neighbour) entries, nodes included,
#: 2**24 (~16.8 M, about 100 MB of sparse matrix); a synthesis of hundreds of elements uses thousands.
MAX_PAIRS = 2**24


def ring_neighbourhoods(n: int, edges, rings: int, *, max_pairs: int = MAX_PAIRS):
    """The k-ring neighbourhood of every node: all nodes within ``rings`` hops, itself excluded.

    Returns CSR arrays ``(pointers, neighbours)``: node ``i``'s neighbourhood is
    ``neighbours[pointers[i]:pointers[i + 1]]``, sorted. ``max_pairs`` (default :data:`MAX_PAIRS`)
    bounds the ``n`` nodes and, ring by ring, the (node, neighbour) pairs found: a ValueError
    before allocating more.

    Parameters
    ----------
    n : int
        Number of nodes.
    edges : array_like of int, shape (m, 2)
        The neighbour graph.
    rings : int
        The neighbourhood size k, in hops (>= 1).
    max_pairs : int, optional
        Budget on nodes and (node, neighbour) pairs (default :data:`MAX_PAIRS`, 2**24).

    Returns
    -------
    pointers : ndarray of int64, shape (n + 1,)
        CSR row pointers.
    neighbours : ndarray of int64
        The neighbours of every node, node after node, each node's sorted.
    """
    if isinstance(rings, bool) or not isinstance(rings, (int, np.integer)) or rings < 1:
        raise ValueError(f"rings (the neighbourhood size k) must be an integer >= 1, got {rings!r}")
    n, max_pairs = _count(n), budget(max_pairs, "max_pairs")
    check_budget(n, max_pairs, "max_pairs", "nodes")
    adjacency = _adjacency(n, edges).astype(bool)
    # boolean products (or of ands): path counts in int8 would wrap past 127 and drop reachable nodes
    reach = sparse.identity(n, dtype=bool, format="csr")
    degrees = adjacency.getnnz(axis=1).astype(np.int64)
    for _ in range(int(rings)):
        # the next ring holds at most the pairs so far plus one per edge leaving a reached node
        bound = min(n * n, reach.nnz + int(degrees[reach.indices].sum()))
        check_budget(bound, max_pairs, "max_pairs", "neighbourhood pairs (at most)")
        grown = (reach + reach @ adjacency).tocsr()
        if grown.nnz == reach.nnz:  # every neighbourhood is a whole connected component: more rings add nothing
            break
        reach = grown
    reach = (reach.astype(np.int8) - sparse.identity(n, dtype=np.int8, format="csr")).tocsr()
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
    """Nodes by increasing hops from ``start``, ties by distance to it; unreachable nodes last (section 3.2).

    Parameters
    ----------
    positions : array_like, shape (n, 2)
        Node positions (finite).
    edges : array_like of int, shape (m, 2)
        The neighbour graph.
    start : int
        The node growth starts from, in ``[0, n)``.

    Returns
    -------
    ndarray of int, shape (n,)
        The node indices in growth order, ``start`` first.
    """
    positions = point_array(positions, "positions")
    n = len(positions)
    if isinstance(start, bool) or not isinstance(start, (int, np.integer)) or not 0 <= start < n:
        raise ValueError(f"start must be a node index in [0, {n}), got {start!r}")
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


def _check_analysis(analysis) -> PatternAnalysis:
    if not isinstance(analysis, PatternAnalysis):
        raise TypeError(f"analysis must be a PatternAnalysis from analyze(), got {type(analysis).__name__}")
    return analysis


def reference_centre(analysis: PatternAnalysis) -> int:
    """The reference element nearest the middle of its path (1D) or the mean of its centres (2D)."""
    _check_analysis(analysis)
    if analysis.dimension == 1:
        return int(np.argmin(np.abs(analysis.arc - (analysis.arc.min() + analysis.arc.max()) / 2.0)))
    return int(np.argmin(np.hypot(*(analysis.positions - analysis.positions.mean(axis=0)).T)))


def _seed_patch(target_graph, start: int, reference_graph, centre: int, gate: float) -> np.ndarray:
    """The reference elements the start's k-ring is seeded with (``start="centre"``), -1 elsewhere.

    The start copies the reference's centre element, and each element of its k-ring the element of the centre's
    k-ring it pairs with (mutual nearest offsets, no further apart than ``gate``): Efros and Leung's seed patch,
    a piece of the reference copied whole, so that growth begins from a neighbourhood, not from one element
    whose lone neighbour matches several places of the reference equally well.
    """
    (tar_pointers, tar_neighbours, tar_offsets), (ref_pointers, ref_neighbours, ref_offsets) = target_graph, \
        reference_graph
    initial = np.full(len(tar_pointers) - 1, -1, dtype=np.int64)
    initial[start] = centre
    tar_span = slice(tar_pointers[start], tar_pointers[start + 1])
    ref_span = slice(ref_pointers[centre], ref_pointers[centre + 1])
    if tar_span.start == tar_span.stop or ref_span.start == ref_span.stop:
        return initial
    distances = np.hypot(*(tar_offsets[tar_span][:, None, :] - ref_offsets[ref_span][None, :, :]).transpose(2, 0, 1))
    nearest_ref, nearest_tar = distances.argmin(axis=1), distances.argmin(axis=0)
    for k, m in enumerate(nearest_ref):
        if nearest_tar[m] == k and distances[k, m] <= gate:
            initial[tar_neighbours[tar_span][k]] = ref_neighbours[ref_span][m]
    return initial


def pairing_gate(analysis: PatternAnalysis) -> float:
    """Half the median distance between neighbouring reference elements: the furthest two paired neighbours
    may lie apart under ``matching="coverage"`` (closer to another slot than to their own)."""
    ends = _check_analysis(analysis).positions[analysis.edges]
    return 0.5 * float(np.median(np.hypot(*(ends[:, 0] - ends[:, 1]).T)))


# --------------------------------------------------------------------------- synthesis


@dataclass(frozen=True, eq=False)
class Synthesis:
    """A synthesised stroke pattern.

    Parameters
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
        True where the choice came from matching neighbourhoods; False for the fallback, the seed patch, or an
        element with no known neighbour.
    n_candidates : ndarray of int, shape (n,)
        How many reference neighbourhoods matched.
    score : ndarray, shape (n,)
        Rule score of the chosen reference neighbourhood (< 1 matches; NaN for seeded elements and those without
        known neighbours).
    seeded : ndarray of bool, shape (n,)
        The seed patch: elements copied with the start before growth (``start="centre"``).
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
    seeded: np.ndarray
    dimension: int
    rings: int
    target: object

    def __len__(self) -> int:
        return len(self.elements)

    @property
    def fallback(self) -> np.ndarray:
        """Elements whose neighbourhood matched no reference neighbourhood (the smallest rule score was taken)."""
        return ~self.matched & ~np.isnan(self.score)

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


#: Choice rules among the matching reference neighbourhoods, kernel codes.
CHOICES = {"random": RANDOM, "best": BEST, "close": CLOSE}
#: Partial-neighbourhood rules (section 3.2): the paper's as written, and ours (see :func:`synthesize`).
MATCHINGS = ("coverage", "paper")
#: Starting element rules.
STARTS = ("centre", "random")
#: Default ``tolerance`` of ``choice="close"``, in rule-score units (fractions of the thresholds): candidates
#: within a tenth of a threshold of the best, Efros and Leung's epsilon = 0.1.
CLOSE_TOLERANCE = 0.1


def _option(value, allowed, name: str):
    if value not in allowed:
        raise ValueError(f"{name} must be one of {sorted(allowed)}, got {value!r}")
    return value


def synthesize(analysis: PatternAnalysis, target, *, rings: int = 2, n: int | None = None,
               thresholds: Thresholds | None = None, choice: str = "close", tolerance: float = CLOSE_TOLERANCE,
               matching: str = "coverage", start: str = "centre", iterations: int = LLOYD_ITERATIONS,
               rng=None, max_seeds: int = MAX_SEEDS) -> Synthesis:
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
    choice : {"close", "random", "best"}
        Which of the matching reference neighbourhoods (the set Omega of section 3.1) is copied. "random" (the
        paper as written): a uniform choice in Omega. "close" (default): a uniform choice among the members of
        Omega whose rule score is within ``tolerance`` of the best, the rule of Efros and Leung [2] whose
        method the paper follows; with the paper's thresholds Omega spans several elements of a ramp (about
        +-3 along Fig. 6c's orientation ramp), and a uniform draw in it makes the copied position a random walk
        whose steps are as large as the ramp's neighbouring differences times 3. "best": the smallest score.
    tolerance : float
        For ``choice="close"``, in units of the thresholds (rule-score units), >= 0.
    matching : {"coverage", "paper"}
        How a partial neighbourhood is scored (section 3.2). "paper": the measures summed over the mutual
        pairs and divided by the number of known elements, as written. "coverage" (default): pairs further
        apart than half the reference's median neighbour distance do not count, and each known element left
        without a partner is charged its threshold, so that a reference neighbourhood cut by the exemplar's
        border cannot match on the one or two pairs it forms.
    start : {"centre", "random"}
        How growth begins (the paper does not say what the centre element of Algorithm 1 receives). "centre"
        (default): the target's centre element and its k-ring copy the reference's centre element and its
        k-ring (:func:`_seed_patch`, Efros and Leung's seed patch), so that a synthesis as long as the exemplar
        reaches both ends of a ramp (Figure 6 c-e). "random": the centre element copies a uniformly random
        reference element.
    iterations : int
        Lloyd iterations for the seeds.
    rng : None, int or numpy.random.Generator
        Drives the seeds and the choices; same seed, same pattern.
    max_seeds : int, optional
        Budget: the most elements (default :data:`MAX_SEEDS`), checked before the seeds are placed.

    Returns
    -------
    Synthesis

    Raises
    ------
    ValueError
        A target path of zero length, a region of zero area, a 2D target too small for 3 seeds, more elements
        than ``max_seeds``, rings < 1, an unknown choice, matching or start, a negative tolerance.

    References
    ----------
    Barla et al. 2006, sections 3.1-3.2 and Algorithm 1; Efros and Leung 1999, section 2.1 (the choice among
    the patches within (1 + epsilon) of the best).
    """
    if not isinstance(analysis, PatternAnalysis):
        raise ValueError(f"analysis must be a PatternAnalysis from analyze(), got {type(analysis).__name__}")
    thresholds = Thresholds() if thresholds is None else thresholds
    if not isinstance(thresholds, Thresholds):
        raise ValueError(f"thresholds must be a Thresholds, got {type(thresholds).__name__}")
    mode = CHOICES[_option(choice, CHOICES, "choice")]
    tolerance = positive_number(tolerance, "tolerance", allow_zero=True)
    coverage = _option(matching, MATCHINGS, "matching") == "coverage"
    seeded_start = _option(start, STARTS, "start") == "centre"
    dimension = analysis.dimension
    shape, _ = _extent(target, dimension)
    count = target_count(analysis, shape) if n is None else _count(n)
    rng = as_generator(rng)
    seed_rng, choice_rng = rng.spawn(2)
    make_seeds = seeds_1d if dimension == 1 else seeds_2d
    seeds = make_seeds(shape, count, iterations=iterations, rng=seed_rng, max_seeds=max_seeds)
    start_element = _start(seeds, shape, dimension)
    order = growth_order(seeds.positions, seeds.edges, start_element)
    tables = measure_tables(analysis.boxes.half_lengths, analysis.boxes.angles - analysis.frames, analysis.colors)
    sigmas = thresholds.vector(analysis.mean_length)
    target_graph = _graph_arrays(seeds.positions, seeds.frames, seeds.edges, rings)
    reference_graph = _graph_arrays(analysis.positions, analysis.frames, analysis.edges, rings)
    gate = pairing_gate(analysis)
    initial = (_seed_patch(target_graph, start_element, reference_graph, reference_centre(analysis), gate)
               if seeded_start else np.full(count, -1, dtype=np.int64))
    source, matched, n_candidates, score = grow(order, *target_graph, *reference_graph, tables, sigmas,
                                                choice_rng.random(count), initial, mode, tolerance, gate ** 2,
                                                coverage)
    elements = tuple(place_element(analysis.elements[s], analysis.positions[s], frame - analysis.frames[s], position)
                     for s, frame, position in zip(source, seeds.frames, seeds.positions))
    return Synthesis(elements=elements, positions=seeds.positions, frames=seeds.frames, edges=seeds.edges,
                     source=source, order=order, matched=matched, n_candidates=n_candidates, score=score,
                     seeded=initial >= 0, dimension=dimension, rings=int(rings), target=shape)
