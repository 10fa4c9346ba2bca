"""Adding variation to a synthesised pattern (Barla 2006, section 3.3).

Two post-processes:

- :func:`exchange_parameters`: "for each element, and for each of its parameters independently, we select a
  set of similar values in the reference pattern [...] Then, we pick one value from this set and use it in
  place of the parameters of the synthesized element." The parameters are the orientation (in the element's
  frame), the length (principal axis) and the thickness (secondary axis). The paper's slider is ``amount`` in
  [0, 1]: the set of similar values is the ``max(1, round(amount * N_ref))`` reference values nearest to the
  element's own (orientation distances modulo pi), so 0 changes nothing and 1 draws from every reference
  value. A new orientation turns the element about its centre; a new length stretches it along its principal
  axis; a new thickness stretches it along its secondary axis and scales its pen widths by the same ratio, so a
  box fitted on the contour scales with it. Colour is not exchanged: it is an attribute the matching keeps.
- :func:`vary_positions`: every element with at least k neighbours (k = 2 in 1D, 4 in 2D) is moved, in
  parallel, to the barycentre of its neighbours plus the shift vector S_ref of the reference element it
  copies, rescaled by the sizes of the two neighbourhoods.

References
----------
.. [1] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern Analysis and Synthesis",
   Computer Graphics Forum (Eurographics) 25(3), 2006, section 3.3.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from paperlib._checks import as_generator, check_choice

from ..geometry import Element, Stroke
from .analysis import PatternAnalysis, neighbour_lists, neighbourhood_areas
from .synthesis import Synthesis

__all__ = ["exchange_parameters", "vary_positions"]

#: Neighbours an element needs before its position is varied (section 3.3: "k = 2 for 1D, k = 4 for 2D").
MIN_NEIGHBOURS = {1: 2, 2: 4}


def _check_pair(synthesis, analysis) -> None:
    if not isinstance(synthesis, Synthesis):
        raise ValueError(f"synthesis must be a Synthesis, got {type(synthesis).__name__}")
    if not isinstance(analysis, PatternAnalysis):
        raise ValueError(f"analysis must be the PatternAnalysis the synthesis was made from, got {type(analysis).__name__}")
    if synthesis.source.max(initial=-1) >= len(analysis):
        raise ValueError("the synthesis copies elements the analysis does not have: pass its own analysis")


def _similar_value(values, own: float, size: int, rng, *, period: float | None = None) -> float:
    """A uniform pick among the ``size`` reference values nearest to ``own``."""
    distance = np.abs(values - own)
    if period is not None:
        distance = np.minimum(np.mod(distance, period), period - np.mod(distance, period))
    nearest = np.argsort(distance, kind="stable")[:size]
    return float(values[nearest[rng.integers(len(nearest))]])


def _ratio(new: float, old: float) -> float:
    """The stretch from ``old`` to ``new``; 1 when either is 0 (a straight skeleton has no thickness to scale,
    and a stretch to 0 would collapse the strokes)."""
    return new / old if new > 0 and old > 0 else 1.0


def _reshaped(element: Element, center, angle: float, turn: float, stretch_major: float,
              stretch_minor: float) -> Element:
    """The element stretched along its axes (at ``angle``) about ``center``, then turned by ``turn``."""
    cos, sin = np.cos(angle), np.sin(angle)
    frame = np.array([[cos, -sin], [sin, cos]])
    cos_t, sin_t = np.cos(turn), np.sin(turn)
    matrix = np.array([[cos_t, -sin_t], [sin_t, cos_t]]) @ frame @ np.diag([stretch_major, stretch_minor]) @ frame.T
    strokes = tuple(Stroke((s.points - center) @ matrix.T + center, s.width * stretch_minor, s.color)
                    for s in element.strokes)
    return Element(strokes, element.name)


def exchange_parameters(synthesis: Synthesis, analysis: PatternAnalysis, amount: float, *, rng=None) -> Synthesis:
    """Exchange orientation, length and thickness with similar reference elements (section 3.3).

    Parameters
    ----------
    synthesis : Synthesis
    analysis : PatternAnalysis
        The reference the synthesis was made from.
    amount : float
        The slider, in [0, 1]: the fraction of the reference values each parameter may be drawn from (the
        nearest ones). 0 returns the synthesis unchanged.
    rng : None, int or numpy.random.Generator

    Returns
    -------
    Synthesis
        The same synthesis with new elements (positions, sources and graph unchanged).

    References
    ----------
    Barla et al. 2006, section 3.3, first paragraph.
    """
    _check_pair(synthesis, analysis)
    amount = float(amount)
    if not 0.0 <= amount <= 1.0:
        raise ValueError(f"amount must lie in [0, 1], got {amount!r}")
    rng = as_generator(rng)
    size = max(1, int(round(amount * len(analysis))))
    angles = np.mod(analysis.boxes.angles - analysis.frames, np.pi)
    lengths, thicknesses = (2.0 * analysis.boxes.half_lengths).T
    elements = []
    for element, source, frame, center in zip(synthesis.elements, synthesis.source, synthesis.frames,
                                              synthesis.positions):
        own = (angles[source], lengths[source], thicknesses[source])
        new_angle = _similar_value(angles, own[0], size, rng, period=np.pi)
        new_length = _similar_value(lengths, own[1], size, rng)
        new_thickness = _similar_value(thicknesses, own[2], size, rng)
        stretch_major = _ratio(new_length, own[1])
        stretch_minor = _ratio(new_thickness, own[2])
        elements.append(_reshaped(element, center, own[0] + frame, new_angle - own[0], stretch_major, stretch_minor))
    return dataclasses.replace(synthesis, elements=tuple(elements))


def vary_positions(synthesis: Synthesis, analysis: PatternAnalysis, *, k: int | None = None,
                   scaling: str = "length") -> Synthesis:
    """Reintroduce the reference's position variation (section 3.3, second paragraph).

    Every element with n >= k neighbours in the target graph is moved, all in parallel, to the barycentre of
    its neighbours translated by ``S_tar``, the reference shift ``S_ref`` of the element it copies rescaled by
    the neighbourhood sizes A (span of the chain neighbours in 1D, area of their convex hull in 2D):

    - ``scaling="length"`` (default): ``S_tar = S_ref * (A_tar / A_ref) ** (1 / d)``, d the dimension, so the
      shift scales like a length; S_ref is already a mean over the neighbours (section 2.3).
    - ``scaling="printed"``: the formula as printed, ``S_tar = S_ref * A_tar / (n * A_ref)``, which in 2D
      shrinks the shift by about n = 6 and scales it like an area.

    Parameters
    ----------
    synthesis : Synthesis
        The synthesised pattern.
    analysis : PatternAnalysis
        The analysed reference it was synthesised from.
    k : int, optional
        Minimum number of neighbours; default 2 in 1D and 4 in 2D, the paper's.
    scaling : {"length", "printed"}, default "length"
        How ``S_ref`` is rescaled (see above).

    Returns
    -------
    Synthesis
        Elements translated to their new positions (``positions`` updated).

    References
    ----------
    Barla et al. 2006, sections 2.3 (S_ref) and 3.3.
    """
    _check_pair(synthesis, analysis)
    check_choice(scaling, ("length", "printed"), "scaling")
    d = synthesis.dimension
    k = MIN_NEIGHBOURS[d] if k is None else int(k)
    if k < 1:
        raise ValueError(f"k must be >= 1, got {k}")
    positions = synthesis.positions
    areas_tar = neighbourhood_areas(positions, synthesis.edges, d)
    new_positions = positions.copy()
    reference_degree = np.bincount(analysis.edges.ravel(), minlength=len(analysis))
    for index, neighbours in enumerate(neighbour_lists(len(positions), synthesis.edges)):
        source = synthesis.source[index]
        s_ref, area_ref = analysis.shifts[source], analysis.neighbourhood_area[source]
        # S_ref of a reference element with fewer than k neighbours (its border) is one-sided: not used.
        if len(neighbours) < k or reference_degree[source] < k or not area_ref > 0 or not areas_tar[index] > 0:
            continue
        ratio = areas_tar[index] / area_ref
        factor = ratio ** (1.0 / d) if scaling == "length" else ratio / len(neighbours)
        turn = synthesis.frames[index] - analysis.frames[source]
        cos, sin = np.cos(turn), np.sin(turn)
        shift = factor * np.array([cos * s_ref[0] - sin * s_ref[1], sin * s_ref[0] + cos * s_ref[1]])
        new_positions[index] = positions[neighbours].mean(axis=0) + shift
    moves = new_positions - positions
    elements = tuple(Element(tuple(Stroke(s.points + move, s.width, s.color) for s in e.strokes), e.name)
                     for e, move in zip(synthesis.elements, moves))
    return dataclasses.replace(synthesis, elements=elements, positions=new_positions)
