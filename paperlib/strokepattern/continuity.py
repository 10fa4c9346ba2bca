"""Local continuity of a stroke pattern: how neighbouring elements differ, in the reference and in a synthesis.

Barla et al. 2006 claim that a k-ring synthesis "reproduces the smooth change" of orientation, length or
thickness along a path (section 4, Figure 6 c-e) and "the complex relations among similar elements" in 2D
(Figure 7). A global ramp can only be judged on a path as long as the exemplar; what must hold everywhere is
that *neighbouring* synthesised elements differ as neighbouring reference elements do. This module measures
that, independently of the matching rule the synthesis optimises:

- :func:`element_parameters`: orientation (major-axis angle in the element's local frame), length (major
  axis), thickness (minor axis) and colour of every element, fitted on its geometry (section 2.1), so a
  synthesis, a shuffle or a hand-edited pattern are measured alike;
- :func:`neighbour_differences`: for every edge of the neighbour graph, the difference of each parameter
  (orientation as the angle between axes, in [0, pi/2]; length and thickness as absolute differences; colour
  as the RGB distance, the paper's ``par``, ``sup`` and ``col`` measures, with the length difference in
  place of the ``ov`` ratio);
- :func:`compare_continuity`: the two-sample Kolmogorov-Smirnov distance between the reference's and the
  synthesis' neighbour differences, per parameter, against the KS test's critical value at the 1 % level
  (Smirnov: ``1.628 sqrt((n + m) / (n m))``), differences compared at a hundredth of the paper's threshold
  (:func:`resolutions`); along a path also the longest run of copies of one reference element and the longest
  oscillation around one element (A x A x A ..., :func:`alternation_length`);
- :func:`allowed_run` and :func:`allowed_alternation`: how many consecutive (or every-other) reference
  elements the matching rule cannot tell apart, the longest copy run and alternation the reference itself
  allows;
- :func:`shuffled`: the control, the same elements at the same places in a random order.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from paperlib._checks import as_generator
from scipy.stats import ks_2samp

from ..geometry import Element
from .analysis import PatternAnalysis, _element_colors, fit_elements, graph_edges
from .measures import Thresholds, measure_tables, rule_score
from .synthesis import place_element

__all__ = ["PARAMETERS", "Continuity", "allowed_alternation", "allowed_run", "alternation_length", "compare_continuity",
           "element_parameters", "ks_critical_value", "longest_copy_run", "neighbour_differences", "resolutions",
           "shuffled"]

#: The element parameters whose neighbour differences are compared.
PARAMETERS = ("orientation", "length", "thickness", "color")

#: Differences are compared at a resolution of this fraction of the paper's threshold for the measure that
#: sees them (sigma_par, sigma_shape, sigma_sup, sigma_col): far below what the rule can perceive, far above
#: floating-point noise (a parameter constant in the reference must not be compared on its rounding errors).
RESOLUTION_FRACTION = 0.01

#: Significance level of the KS bound: a synthesis passes when the test cannot tell its neighbour differences
#: from the reference's at this level.
KS_ALPHA = 0.01


def element_parameters(elements, frames, *, contour: bool = False) -> dict[str, np.ndarray]:
    """Orientation (in the local frame), length, thickness and colour of each element, fitted on its strokes.

    Parameters
    ----------
    elements : sequence of Element
    frames : array_like, shape (n,)
        Each element's local frame angle (path tangent in 1D, 0 in 2D).
    contour : bool
        Fit on the pen's contour (pen width included), as the analysis did (section 2.1).
    """
    elements = tuple(elements)
    if not elements or not all(isinstance(e, Element) for e in elements):
        raise TypeError("elements must be a non-empty sequence of Element")
    frames = np.asarray(frames, dtype=np.float64).reshape(-1)
    if frames.shape != (len(elements),):
        raise ValueError(f"frames must hold one angle per element ({len(elements)}), got shape {frames.shape}")
    boxes = fit_elements(elements, contour=contour)
    return {"orientation": boxes.angles - frames, "length": 2.0 * boxes.half_lengths[:, 0],
            "thickness": 2.0 * boxes.half_lengths[:, 1], "color": _element_colors(elements)}


def neighbour_differences(parameters: dict, edges, resolution: dict | None = None) -> dict[str, np.ndarray]:
    """The difference of each parameter across every edge ``(i, j)`` of the neighbour graph.

    With ``resolution`` (per parameter), differences are floored to multiples of it.
    """
    missing = set(PARAMETERS) - set(parameters)
    if missing:
        raise ValueError(f"parameters lacks {sorted(missing)}: pass element_parameters(...)")
    edges = graph_edges(edges, len(parameters["length"]))
    i, j = edges[:, 0], edges[:, 1]
    turn = np.mod(parameters["orientation"][i] - parameters["orientation"][j], np.pi)
    differences = {"orientation": np.minimum(turn, np.pi - turn),
                   "length": np.abs(parameters["length"][i] - parameters["length"][j]),
                   "thickness": np.abs(parameters["thickness"][i] - parameters["thickness"][j]),
                   "color": np.sqrt(((parameters["color"][i] - parameters["color"][j]) ** 2).sum(axis=1))}
    if resolution is None:
        return differences
    return {name: np.floor(value / resolution[name]) * resolution[name] for name, value in differences.items()}


def resolutions(analysis: PatternAnalysis, thresholds: Thresholds | None = None) -> dict[str, float]:
    """The resolution of each parameter's differences: :data:`RESOLUTION_FRACTION` of the paper's threshold of the
    measure that sees it (orientation: sigma_par; length: sigma_shape = 0.1 L; thickness: sigma_sup; colour:
    sigma_col; section 3.1)."""
    thresholds = Thresholds() if thresholds is None else thresholds
    length = analysis.mean_length
    return {"orientation": RESOLUTION_FRACTION * thresholds.par, "length": RESOLUTION_FRACTION * thresholds.shape * length,
            "thickness": RESOLUTION_FRACTION * thresholds.sup * length, "color": RESOLUTION_FRACTION * thresholds.col}


def ks_critical_value(n: int, m: int, alpha: float = KS_ALPHA) -> float:
    """Smirnov's asymptotic critical value of the two-sample KS statistic, ``c(alpha) sqrt((n + m) / (n m))``."""
    if n < 1 or m < 1:
        raise ValueError(f"both samples need at least one value, got sizes {n} and {m}")
    if not 0.0 < alpha < 1.0:
        raise ValueError(f"alpha must be in (0, 1), got {alpha!r}")
    return float(np.sqrt(-np.log(alpha / 2.0) / 2.0) * np.sqrt((n + m) / (n * m)))


def _sources(source) -> np.ndarray:
    source = np.asarray(source)
    if source.ndim != 1 or (source.size and not np.issubdtype(source.dtype, np.integer)):
        raise ValueError(f"source must be a 1D integer array of reference indices, got {source.dtype} of shape "
                         f"{source.shape}")
    return source


def longest_copy_run(source) -> int:
    """The longest run of consecutive elements (in chain order) that copy the same reference element."""
    source = _sources(source)
    if len(source) == 0:
        return 0
    breaks = np.flatnonzero(np.diff(source) != 0)
    bounds = np.concatenate([[-1], breaks, [len(source) - 1]])
    return int(np.diff(bounds).max())


def alternation_length(source) -> int:
    """The longest stretch in which one reference element is copied at every other position (A x A x A ...).

    Counted in elements, ``2 m - 1`` for ``m`` copies: 3 for A B A (a one-element step back), 5 for A B A C A,
    the oscillation of a synthesis stuck between a reference element and whatever follows it. 0 when no element
    recurs two positions later.
    """
    source = _sources(source)
    best = 0
    for parity in (0, 1):
        every_other = source[parity::2]
        between = source[parity + 1::2]
        run = 1
        for k in range(1, len(every_other)):
            # a copy two positions later, with a different element in between
            if every_other[k] == every_other[k - 1] and between[k - 1] != every_other[k]:
                run += 1
                best = max(best, 2 * run - 1)
            else:
                run = 1
    return best


def _alike_in_chain_order(analysis: PatternAnalysis, thresholds: Thresholds | None):
    """Reference elements in path order, and which pairs the rule cannot tell apart (rule score < 1)."""
    if analysis.dimension != 1:
        raise ValueError("copy runs and alternations are measured along a path: the analysis must be 1D")
    thresholds = Thresholds() if thresholds is None else thresholds
    tables = measure_tables(analysis.boxes.half_lengths, analysis.boxes.angles - analysis.frames, analysis.colors)
    alike = rule_score(np.moveaxis(tables, 0, -1), thresholds.vector(analysis.mean_length)) < 1.0
    return np.argsort(analysis.arc, kind="stable"), alike


def _longest_alike_chain(order, alike, step: int) -> int:
    """The most elements ``order[i], order[i + step], ...`` in a row that all match ``order[i]``."""
    best = 1
    for start in range(len(order)):
        stop = start + step
        while stop < len(order) and alike[order[start], order[stop]]:
            stop += step
        best = max(best, (stop - start) // step)
    return best


def allowed_run(analysis: PatternAnalysis, thresholds: Thresholds | None = None) -> int:
    """The longest copy run a 1D reference allows: its longest chain of consecutive elements that all match the
    chain's first element by the rule ``col and (shape or (par and ov and sup))`` (section 3.1).

    A synthesis that copies one element more times in a row than this has repeated something the reference
    never shows (a plateau where the reference changes).
    """
    return _longest_alike_chain(*_alike_in_chain_order(analysis, thresholds), step=1)


def allowed_alternation(analysis: PatternAnalysis, thresholds: Thresholds | None = None) -> int:
    """The longest alternation a 1D reference allows, in elements (``2 m - 1``, as :func:`alternation_length`):
    its longest stretch in which every other element matches the stretch's first by the rule (section 3.1).

    Copying one element at every other position is an oscillation only where the reference changes between
    those positions: in an alternation of two colours whose strokes all look alike, the reference itself
    repeats the look of one element every other position along its whole length.
    """
    m = _longest_alike_chain(*_alike_in_chain_order(analysis, thresholds), step=2)
    return 2 * m - 1 if m > 1 else 0


@dataclass(frozen=True)
class Continuity:
    """Neighbour-difference comparison of a synthesis with its reference.

    Attributes
    ----------
    ks : dict
        Per parameter, the two-sample KS distance between the reference's and the synthesis' neighbour
        differences.
    bound : float
        The KS test's critical value at the 1 % level for the two edge counts.
    copy_run, allowed_run : int or None
        1D only: the synthesis' longest copy run and the reference's (:func:`allowed_run`).
    alternation, allowed_alternation : int or None
        1D only: the synthesis' longest stretch copying one element at every other position
        (:func:`alternation_length`) and the reference's (:func:`allowed_alternation`).
    """

    ks: dict
    bound: float
    copy_run: int | None = None
    allowed_run: int | None = None
    alternation: int | None = None
    allowed_alternation: int | None = None

    def passes(self, parameter: str) -> bool:
        return self.ks[parameter] <= self.bound


def compare_continuity(analysis: PatternAnalysis, synthesis, *, thresholds: Thresholds | None = None) -> Continuity:
    """Compare how neighbouring elements differ in ``synthesis`` and in the reference ``analysis``.

    ``synthesis`` is anything with ``elements``, ``frames``, ``edges`` (and ``source`` for the 1D copy runs):
    a :class:`~.synthesis.Synthesis`, a varied or a :func:`shuffled` one.
    """
    if not isinstance(analysis, PatternAnalysis):
        raise TypeError(f"analysis must be a PatternAnalysis, got {type(analysis).__name__}")
    if len(synthesis.edges) == 0:
        raise ValueError("the synthesis has no neighbour edges to compare")
    resolution = resolutions(analysis, thresholds)
    reference = neighbour_differences(
        element_parameters(analysis.elements, analysis.frames, contour=analysis.contour), analysis.edges, resolution)
    target = neighbour_differences(
        element_parameters(synthesis.elements, synthesis.frames, contour=analysis.contour), synthesis.edges,
        resolution)
    ks = {name: float(ks_2samp(reference[name], target[name]).statistic) for name in PARAMETERS}
    bound = ks_critical_value(len(analysis.edges), len(synthesis.edges))
    if analysis.dimension != 1:
        return Continuity(ks, bound)
    return Continuity(ks, bound, longest_copy_run(synthesis.source), allowed_run(analysis, thresholds),
                      alternation_length(synthesis.source), allowed_alternation(analysis, thresholds))


@dataclass(frozen=True, eq=False)
class _Shuffled:
    elements: tuple
    frames: np.ndarray
    edges: np.ndarray
    source: np.ndarray


def shuffled(synthesis, *, rng=None):
    """The control: the synthesis' elements moved to the same places in a uniformly random order.

    Each element keeps its orientation relative to its local frame; the result has ``elements``, ``frames``,
    ``edges`` and ``source`` like the synthesis, for :func:`compare_continuity`.
    """
    rng = as_generator(rng)
    order = rng.permutation(len(synthesis.elements))
    centres = fit_elements(synthesis.elements).centers
    elements = tuple(place_element(synthesis.elements[k], centres[k], synthesis.frames[i] - synthesis.frames[k],
                                   centres[i]) for i, k in enumerate(order))
    return _Shuffled(elements, synthesis.frames, synthesis.edges, np.asarray(synthesis.source)[order])
