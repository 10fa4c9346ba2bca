"""Elaborating a sketch: the Markov chain steered by the hand-drawn curve (Simhon 2001, section 3).

The sketch is resampled at ``n_samples`` points equally spaced in arc length; its tangent angle ``phi_in(t)``
steers a chain whose states are the training states of a :class:`~.model.SketchModel`. Section 3's
algorithm, as :func:`elaborate` runs it:

1. start with equal probabilities on every training state;
2. condition on the sketch, eq. (5): ``p_i <- p_i G(phi_in(t) - theta_{s,i})`` with ``theta_{s,i}`` the
   state's angle at the steering scale and ``G`` a Gaussian of standard deviation ``sigma`` (the *variance
   parameter*: large means little confidence in the sketch);
3. threshold: keep the ``top`` most probable states, renormalised;
4. instantiate the sample: the finest-scale angle of the most probable state (``mode="max"``, the paper's
   choice) or of a state drawn with its probability (``mode="sample"``: different seeds give different
   elaborations); with the model's ``"sharp"`` transitions, never the previous sample's state again (a
   repeated state repeats its angle: a straight stutter);
5. for every next sample, predict with the transition probabilities, eq. (3): the probability of each
   candidate ``j`` flows to the successors of its most similar states, in proportion to their transition
   weights (:attr:`.model.SketchModel.transition`: eq. 4's D for ``transitions="paper"``); then condition and
   threshold as in 2-3, and instantiate as in 4.

The instantiated angles are integrated from the sketch's first point with the sketch's sample spacing. By
default the result is then scaled to the sketch's radius of gyration and moved onto its centroid
(``match_extent``, our addition: the detail's wiggles use up arc length, so a detailed curve as long as the
sketch spans less, by about ``model.extent_ratio``, and the conditioning error drifts it). The paper reports
*"issues with curve closures and intersections which are primarily due to accumulated errors and the
stochastic nature of the algorithm"* (section 3.1). Our corrections, on by default, each with the paper's
behaviour as an option:

- ``coarse="sketch"``: each sample's direction is the sketch's plus the state's detail, so the conditioning
  error does not accumulate into drift (``"state"``: the state's own angle, the paper);
- ``closure="turn"`` (the default for a closed sketch): the curve is closed by the smallest change of its
  tangent angles that closes it with every segment's length kept (:func:`.curves.close_angles`), a smooth
  change with the direction, so no kink appears and the samples stay equally spaced (``"distribute"``: the
  gap between the curve's end and its start is spread evenly along it, every segment moving by the same small
  vector, which changes the segments' lengths by up to the gap per sample, so that a curve resampled at equal
  arc length cuts its corners, turning by a third less at the coastlines' vertex counts; ``"none"``: the gap
  stays, the paper);
- ``untangle=True``: where the curve crosses itself, two crossing segments close a loop (the shorter
  stretch between them); the detail on it (the output's direction minus the sketch's) is halved and the
  curve rebuilt, until it is simple (after :data:`UNTANGLE_ROUNDS` halvings the detail on a loop is dropped;
  if crossings remain on loops without detail, it is dropped everywhere: the resampled sketch, which is
  simple, so this ends).

Two situations the paper does not cover get a documented answer: when no predicted state survives the
conditioning (all probabilities underflow, the chain has lost the sketch), the chain restarts from step 2
over all states and :attr:`Elaboration.restarts` counts it; with a search window ``window`` (the paper's
``Delta t`` for non-stationary classes), only states whose arc-length position is within ``window`` of the
sketch's ``t / n`` take part.

References
----------
.. [1] S. Simhon and G. Dudek, "On the Elaboration of Hand-Drawn Sketches", McGill University, 2001:
   section 3 (eq. 3: the non-stationary chain; eq. 5: conditioning on the sketch; the algorithm's summary;
   the search range Delta t), section 3.1 (closure problems), Figures 3, 4 and 6.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np
import shapely

from .._checks import (as_generator, check_choice, check_flag, instance_of, integer_array, integer_at_least,
                       positive_number)
from ..geometry import as_points
from ..geometry.svg import MAX_DOCUMENT_BYTES, MAX_FLATTENED_POINTS, _read_elements
from ._kernels import steer
from .curves import (
    check_curve,
    close_angles,
    close_curve,
    coarse_ring,
    integrate_angles,
    match_size,
    multiscale_angles,
    resample_curve,
    resample_simple,
    tangent_angles,
    _wrap,
)
from .model import SketchModel

__all__ = ["Elaboration", "coarsen", "copied_runs", "crossing_segments", "elaborate", "sketch_from_svg"]

MODES = ("max", "sample")
CLOSURES = (None, "turn", "distribute", "none")
#: Halvings of the detail on a loop before it is dropped there (0.5 ** 8 < 0.4 %), and the samples beyond
#: the two crossing segments that the loop's stretch includes.
UNTANGLE_ROUNDS, UNTANGLE_REACH = 8, 4
COARSE = ("state", "sketch")


@dataclass(frozen=True)
class Elaboration:
    """An elaborated curve (:func:`elaborate`).

    Parameters
    ----------
    points : ndarray, shape (n, 2) or (n + 1, 2)
        The elaborated curve: ``n`` points of a closed ring (no repeated end point) when the sketch is
        closed, ``n + 1`` points of an open polyline otherwise.
    angles : ndarray, shape (n,) or (n - 1,)
        Its tangent angles (the instantiated finest-scale angles, unwrapped).
    sketch : ndarray
        The sketch resampled at uniform arc length.
    steering : ndarray
        The sketch's tangent angles ``phi_in``.
    states : ndarray of int
        The training state instantiated at every sample.
    closed : bool
    closing_gap : float
        Distance between the end and the start of the integrated curve before any closure correction,
        divided by the sketch's length (0 for an open sketch).
    restarts : int
        How often the chain lost every candidate and restarted from the sketch alone.
    crossings : int
        Pairs of segments of :attr:`points` that cross (0: a simple curve).
    untangled : int
        Samples whose detail was reduced to remove crossings (``untangle``; 0 when none crossed).
    """

    points: np.ndarray
    angles: np.ndarray
    sketch: np.ndarray
    steering: np.ndarray
    states: np.ndarray
    closed: bool
    closing_gap: float
    restarts: int
    crossings: int
    untangled: int


def _check_choice(value, name: str, choices) -> None:
    check_choice(value, choices, name)


def _instantiated_angles(model: SketchModel, states: np.ndarray, phi: np.ndarray, keep_coarse: str) -> np.ndarray:
    """The output angle of every sample: the state's finest angle, on the turn nearest the sketch's angle.

    A state's finest and steering angles are unwrapped along the same training curve, so the state's
    *detail* ``theta_0 - theta_s`` needs no wrapping. ``keep_coarse="state"`` (the paper) outputs
    ``theta_0``: the sketch's angle, plus the conditioning error ``theta_s - phi_in`` (within about
    ``sigma``), plus the detail. ``"sketch"`` drops the conditioning error: ``phi_in + detail``.
    """
    detail = model.angles[states, 0] - model.steering_angles[states]
    if keep_coarse == "sketch":
        return phi + detail
    return phi + _wrap(model.steering_angles[states] - phi) + detail


def elaborate(
    model: SketchModel,
    sketch,
    *,
    closed: bool | None = None,
    n_samples: int = 1000,
    sigma: float = 0.1,
    top: int = 20,
    mode: str = "max",
    window: float | None = None,
    closure: str | None = None,
    match_extent: bool = True,
    coarse: str = "sketch",
    untangle: bool = True,
    rng=None,
) -> Elaboration:
    """Elaborate a hand-drawn sketch into a detailed curve of the model's class (section 3).

    Parameters
    ----------
    model : SketchModel
        A trained class (:func:`.model.train`).
    sketch : array_like, shape (m, 2)
        The user's curve: at least ``model.order`` points, no repeated point, not crossing itself.
    closed : bool, optional
        Whether the sketch is closed (default: as the training curves).
    n_samples : int
        Samples of the elaboration (> model.order). One sample of the sketch takes one training sample's
        detail, so a sketch of ``n_samples`` samples gets the detail of ``n_samples / samples_per_curve``
        training curves.
    sigma : float
        Standard deviation (radians) of the Gaussian of eq. (5): the user's confidence in the sketch.
    top : int
        States kept after each thresholding (>= 1).
    mode : {"max", "sample"}
        Instantiate the most probable state (the paper's choice) or draw one.
    window : float, optional
        Search window Delta t as a fraction of the curve (in (0, 0.5]): for non-stationary classes.
    closure : {None, "turn", "distribute", "none"}
        ``"turn"`` (what None means for a closed sketch) closes a closed elaboration by the smallest change of
        its angles, segment lengths kept (:func:`.curves.close_angles`); ``"distribute"`` by spreading its end
        gap evenly along it (:func:`.curves.close_curve`); ``"none"`` leaves the gap (the paper). Open sketches
        take None only. A curve too far from closed for ``"turn"`` (segments nearly all parallel) is closed by
        ``"distribute"``.
    match_extent : bool
        Scale the elaboration about its centroid to the sketch's radius of gyration and move it onto the
        sketch's centroid (our addition, on by default, :func:`.curves.match_size`). ``False`` integrates
        from the sketch's first point with the sketch's sample spacing, as the paper does: the detail's
        wiggles use up arc length, so the elaboration comes out smaller than the sketch (by about
        ``model.extent_ratio``) and drifts with the accumulated conditioning error.
    coarse : {"sketch", "state"}
        The coarse direction of each output sample: the sketch's (``"sketch"``, our default: the sketch's
        angle plus the state's detail, finest minus steering-scale angle), which removes the conditioning
        error that accumulates into drift, or the instantiated state's (``"state"``, the paper: the state's
        finest angle as it is).
    untangle : bool
        Reduce the detail where the curve crosses itself until it is simple (module docstring; our
        correction). False keeps the crossings, as the paper reports them.
    rng : None, int or numpy.random.Generator
        Drives ``mode="sample"``.

    Returns
    -------
    Elaboration

    Raises
    ------
    ValueError
        On a bad sketch (too few points, NaN, repeated points, self-crossing) or bad parameters.
    """
    if not isinstance(model, SketchModel):
        raise ValueError("model must be a SketchModel (from paperlib.sketch.train)")
    closed = model.closed if closed is None else bool(closed)
    sketch = check_curve(sketch, closed=closed, min_points=max(model.order, 3), name="sketch")
    n_samples = integer_at_least(n_samples, "n_samples (above the model's order)", model.order + 1)
    sigma = positive_number(sigma, "sigma")
    top = integer_at_least(top, "top", 1)
    _check_choice(mode, "mode", MODES)
    _check_choice(closure, "closure", CLOSURES)
    _check_choice(coarse, "coarse", COARSE)
    if not isinstance(untangle, (bool, np.bool_)):
        raise TypeError(f"untangle must be True or False, got {untangle!r}")
    if window is not None:
        window = positive_number(window, "window")
        if window > 0.5:
            raise ValueError(f"window must be at most 0.5 (half the curve), got {window}")
    if closure is not None and not closed:
        raise ValueError("closure applies to closed sketches only")
    closure = closure or ("turn" if closed else "none")

    resampled = resample_curve(sketch, n_samples, closed=closed)
    phi = tangent_angles(resampled, closed=closed)
    uniforms = as_generator(rng).random(phi.size)
    states, restarts = steer(
        phi, np.ascontiguousarray(model.steering_angles), model.position, model.successor, model.neighbours,
        model.transition, sigma, top, mode == "sample", uniforms, -1.0 if window is None else window,
        model.closed, model.transitions == "paper",
    )
    if restarts < 0:
        raise ValueError("no training state lies in the search window: widen window")
    angles = _instantiated_angles(model, states, phi, coarse)
    segments = np.diff(np.vstack([resampled, resampled[:1]]) if closed else resampled, axis=0)
    step = float(np.hypot(*segments.T).mean())
    gain = np.ones(angles.size)

    def build():
        """The curve of the angles with the current detail gain: integrated, closed, sized."""
        output = phi + gain * (angles - phi)
        path = integrate_angles(output, step, start=resampled[0])
        gap = float(np.hypot(*(path[-1] - path[0])) / (step * angles.size)) if closed else 0.0
        if closed:
            path = _closed_ring(path, output, step, closure)
        return (match_size(path, resampled) if match_extent else path), gap

    path, gap = build()
    crossing = crossing_segments(path, closed=closed)
    if untangle and crossing.size:
        path, crossing = _untangle(build, gain, crossing, closed)
    angles = phi + gain * (angles - phi)
    return Elaboration(points=path, angles=angles, sketch=resampled, steering=phi, states=states,
                       closed=closed, closing_gap=gap, restarts=int(restarts),
                       crossings=len(crossing), untangled=int(np.count_nonzero(gain < 1.0)))


def _closed_ring(path: np.ndarray, angles: np.ndarray, step: float, closure: str) -> np.ndarray:
    """The ring of a closed elaboration (``n`` points): its end gap kept, turned away or distributed."""
    if closure == "none":
        return path[:-1]
    if closure == "turn":
        try:
            return integrate_angles(close_angles(angles), step, start=path[0])[:-1]
        except ValueError:   # nearly parallel segments cannot be turned closed: shift them instead
            pass
    return close_curve(path)


def _untangle(build, gain: np.ndarray, pairs: np.ndarray, closed: bool):
    """Reduce ``gain`` (in place) on the loops the crossings close until ``build()`` gives a simple curve.

    Two crossing segments close a loop: the shorter stretch of curve between them (on a closed curve, either
    way round). Its detail is halved, and dropped once below ``0.5 ** UNTANGLE_ROUNDS``; when the loops of
    the remaining crossings have no detail left, the detail is dropped everywhere (the resampled sketch,
    which is simple), so this ends.
    """
    path = None
    while pairs.size:
        loops = _loops(pairs, gain.size, closed)
        if not gain[loops].any():   # the crossing comes from the detail elsewhere (it moves the whole curve)
            loops = slice(None)
        gain[loops] *= 0.5
        gain[gain < 0.5**UNTANGLE_ROUNDS] = 0.0
        path, _ = build()
        pairs = crossing_segments(path, closed=closed)
        if not gain.any():
            break
    return path, pairs


def _loops(pairs: np.ndarray, n: int, closed: bool) -> np.ndarray:
    """The samples on the shorter stretch between the two segments of every crossing pair, margins included."""
    samples = []
    for first, second in pairs:
        inside = np.arange(first - UNTANGLE_REACH, second + UNTANGLE_REACH + 1)
        if closed and n - (second - first) < second - first:   # shorter the other way round
            inside = np.arange(second - UNTANGLE_REACH, first + n + UNTANGLE_REACH + 1)
        samples.append(inside % n if closed else inside[(inside >= 0) & (inside < n)])
    return np.unique(np.concatenate(samples))


def crossing_segments(points, *, closed: bool) -> np.ndarray:
    """The pairs of segments of a polyline that cross, shape ``(m, 2)``, first segment first (empty: simple).

    Segment ``i`` joins point ``i`` to point ``i + 1`` (to point 0 for the last segment of a closed ring).
    Segments that share an end point count only if they overlap along a line (a turn back on itself).

    Parameters
    ----------
    points : array_like, shape (n, 2)
        The polyline's vertices; a closed ring without its first point repeated.
    closed : bool
        Whether the last vertex joins the first.

    Returns
    -------
    ndarray of int64, shape (m, 2)
        One row ``(i, j)``, ``i < j``, per pair of crossing segments.

    Raises
    ------
    ValueError
        If ``points`` is not finite ``(n, 2)`` coordinates with at least 3 points (closed) or 2 (open).
    """
    closed = check_flag(closed, "closed")
    points = as_points(points, name="points", min_points=3 if closed else 2)
    path = np.vstack([points, points[:1]]) if closed else points
    line = shapely.LinearRing(path) if closed else shapely.LineString(path)
    if line.is_simple:
        return np.empty((0, 2), dtype=np.int64)
    segments = shapely.linestrings(np.stack([path[:-1], path[1:]], axis=1))
    first, second = shapely.STRtree(segments).query(segments, predicate="intersects")
    n = len(segments)
    apart = np.abs(first - second)
    if closed:
        apart = np.minimum(apart, n - apart)
    pairs = (first < second) & (apart > 1)
    adjacent = (first < second) & (apart == 1)
    if adjacent.any():   # neighbours meet at their shared point; they cross only if they overlap
        overlap = shapely.length(shapely.intersection(segments[first[adjacent]], segments[second[adjacent]])) > 0
        pairs[np.flatnonzero(adjacent)[overlap]] = True
    return np.column_stack([first[pairs], second[pairs]]).astype(np.int64)


def coarsen(curve, model: SketchModel, *, n_samples: int | None = None, closed: bool | None = None) -> np.ndarray:
    """The curve at the model's steering scale: the sketch a user would draw of it (eq. 1-2, phi = psi(theta)).

    The curve is resampled as training resamples its curves (:func:`.curves.resample_simple`, at ``n_samples``
    points, default ``model.samples_per_curve``, or the curve's own vertex count when the model was trained at
    ``samples_per_curve="vertices"``), its angles are filtered ``steering_scale`` times with the
    model's filter and integrated back; a closed curve is closed as :func:`.curves.coarse_ring` closes it.
    The smooth curve is then brought to the detailed curve's size and place (:func:`.curves.match_size`):
    with the same arc length it would span about ``model.extent_ratio`` times more, which no user drawing the
    curve would do.

    Parameters
    ----------
    curve : array_like, shape (n, 2)
        The detailed curve (simple, no repeated points); a closed curve without its first point
        repeated.
    model : SketchModel
        The trained class (its filter, steering scale and sampling).
    n_samples : int, optional
        Samples the curve is resampled at (default: as the model was trained).
    closed : bool, optional
        Whether the curve is closed (default: ``model.closed``).

    Returns
    -------
    ndarray of float64, shape (n_samples, 2) or (n_samples + 1, 2)
        The sketch: ``n_samples`` points of a closed ring, or ``n_samples + 1`` points of an open
        polyline, with the size and centroid of the resampled curve.

    Raises
    ------
    TypeError
        If ``model`` is not a :class:`~.model.SketchModel`.
    ValueError
        On a bad curve (too few points, NaN, repeated points, self-crossing) or ``n_samples``.
    """
    instance_of(model, SketchModel, "model")
    closed = model.closed if closed is None else bool(closed)
    curve = check_curve(curve, closed=closed, name="curve")
    if n_samples is None:
        n_samples = len(curve) if model.samples_per_curve == "vertices" else model.samples_per_curve
    points = resample_simple(curve, n_samples, closed=closed)   # as training reads its curves
    theta = tangent_angles(points, closed=closed)
    coarse = multiscale_angles(theta, model.steering_scale + 1, model.filter, closed=closed, causal=model.causal)[-1]
    lengths = np.hypot(*np.diff(np.vstack([points, points[:1]]) if closed else points, axis=0).T)
    step = float(lengths.mean())
    path = coarse_ring(coarse, step, points[0]) if closed else integrate_angles(coarse, step, start=points[0])
    return match_size(path, points)


def copied_runs(model: SketchModel, states, *, slack: int = 0) -> np.ndarray:
    """Lengths (in samples) of the runs an elaboration copies from one training curve.

    A run continues while each instantiated state is the training successor of the previous one (``slack=0``),
    so a run of length ``L`` reproduces ``L`` consecutive training samples. The longest run measures novelty.
    Neighbouring samples of a curve are each other's most similar states, so the chain also moves along a
    training curve by repeating a sample or skipping one; ``slack=1`` counts those moves (an advance of 0, 1
    or 2 samples on the same curve) as copying too, a stricter test of novelty.

    Parameters
    ----------
    model : SketchModel
        The trained class the states index.
    states : array_like of int
        The states an elaboration instantiated, one per sample (:attr:`Elaboration.states`).
    slack : int, default 0
        0: a run continues only through training successors; 1 also counts repeating or skipping a
        sample on the same curve as copying.

    Returns
    -------
    ndarray of int
        The lengths of the successive runs, in order; they sum to ``len(states)``.

    Raises
    ------
    TypeError
        If ``model`` is not a :class:`~.model.SketchModel`.
    ValueError
        If ``states`` are not whole numbers indexing the model's states, or ``slack`` is negative.
    """
    instance_of(model, SketchModel, "model")
    states = integer_array(states, "states").ravel()
    if states.size and (states.min() < 0 or states.max() >= len(model)):
        raise ValueError(f"states must be indices of the model's {len(model)} states, got values in "
                         f"[{states.min()}, {states.max()}]")
    slack = integer_at_least(slack, "slack", 0)
    if slack == 0:
        follows = model.successor[states[:-1]] == states[1:]
    else:
        n = model.curve_samples[model.curve[states[:-1]]]
        advance = model.sample[states[1:]] - model.sample[states[:-1]]
        if model.closed:
            advance %= n
        follows = (model.curve[states[1:]] == model.curve[states[:-1]]) & (np.abs(advance - 1) <= slack)
    boundaries = np.flatnonzero(np.concatenate([[True], ~follows, [True]]))
    return np.diff(boundaries)


def sketch_from_svg(source, *, tolerance: float = 0.5) -> tuple[np.ndarray, bool]:
    """A user's sketch from an SVG file or string: the longest stroke's points, and whether it is closed.

    A stroke whose last point repeats its first (a closed path, a polygon, a circle) is closed; the
    repeated point is dropped. Coordinates are y-up (:func:`paperlib.geometry.read_svg`).

    Parameters
    ----------
    source : str, bytes or os.PathLike
        An SVG file name or SVG text.
    tolerance : float, default 0.5
        Flattening tolerance of curves, in SVG user units (:func:`paperlib.geometry.read_svg`).

    Returns
    -------
    points : ndarray of float64, shape (n, 2)
        The longest stroke's points, y up, without a repeated end point when closed.
    closed : bool
        Whether the stroke is closed.
    """
    if not isinstance(source, (str, bytes, bytearray, os.PathLike)):
        raise TypeError(f"source must be an SVG file name or SVG text, got {type(source).__name__}")
    elements = _read_elements(source, "source", tolerance=tolerance, y_up=True, max_points=MAX_FLATTENED_POINTS,
                              max_bytes=MAX_DOCUMENT_BYTES)
    strokes = [stroke for element in elements for stroke in element.strokes]
    stroke = max(strokes, key=lambda s: float(np.hypot(*np.diff(s.points, axis=0).T).sum()) if len(s.points) > 1
                 else 0.0)
    points = np.array(stroke.points)
    closed = len(points) > 3 and np.allclose(points[0], points[-1])
    return (points[:-1] if closed else points), bool(closed)
