"""Tests of paperlib.sketch (Simhon & Dudek 2001): curves, training states, eq. (4), the steered chain."""

import numpy as np
import pytest

from paperlib.sketch import (
    check_curve,
    close_angles,
    close_curve,
    coarse_ring,
    coarsen,
    copied_runs,
    crossing_segments,
    default_weights,
    elaborate,
    filter_weights,
    gyration_radius,
    integrate_angles,
    lowpass,
    match_size,
    multiscale_angles,
    resample_curve,
    resample_simple,
    sketch_from_svg,
    state_similarity,
    tangent_angles,
    total_turning,
    train,
    wrap_angle,
)
from paperlib.datasets import glyph_outline, hand_drawn_curve
from paperlib.sketch._kernels import steer
from paperlib.sketch.model import SHARPNESS


def circle(n=200, radius=1.0, clockwise=False):
    t = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    points = radius * np.column_stack([np.cos(t), np.sin(t)])
    return points[::-1] if clockwise else points


def wiggly(n=400, lobes=3, teeth=25, depth=0.04, phase=0.0):
    """A closed star-shaped curve with coarse lobes and fine teeth (simple for these amplitudes)."""
    t = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    r = 1.0 + 0.2 * np.cos(lobes * t + phase) + depth * np.sin(teeth * t)
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


@pytest.fixture(scope="module")
def model():
    curves = [wiggly(lobes=k % 3 + 2, teeth=20 + 3 * k, phase=0.3 * k) for k in range(6)]
    return train(curves, order=8, scales=3, filter_width=5, samples_per_curve=96, neighbours=6)


# --------------------------------------------------------------------------- curves


def test_integrating_the_tangent_angles_gives_the_curve_back():
    points = resample_curve(wiggly(), 300, closed=True)
    theta = tangent_angles(points, closed=True)
    steps = np.hypot(*np.diff(np.vstack([points, points[:1]]), axis=0).T)
    # equal arc-length samples of a smooth curve: chords of nearly equal length
    path = integrate_angles(theta, steps.mean(), start=points[0])
    assert np.abs(path[:-1] - points).max() < 5e-3
    assert theta.size == 300 and np.all(np.abs(np.diff(theta)) < np.pi)


def test_total_turning_is_plus_or_minus_two_pi():
    assert total_turning(tangent_angles(circle(), closed=True)) == pytest.approx(2.0 * np.pi)
    assert total_turning(tangent_angles(circle(clockwise=True), closed=True)) == pytest.approx(-2.0 * np.pi)


def test_lowpass_keeps_a_circle_and_averages_cyclically():
    theta = tangent_angles(circle(90), closed=True)
    np.testing.assert_allclose(lowpass(theta, filter_weights(7), closed=True), theta, atol=1e-12)
    signal = np.sin(np.linspace(0, 2 * np.pi, 50, endpoint=False) * 3) + 2 * np.pi * np.arange(50) / 50
    smoothed = lowpass(signal, filter_weights(3), closed=True)
    trend = 2 * np.pi * np.arange(50) / 50
    periodic = signal - trend
    expected = (np.roll(periodic, 1) + periodic + np.roll(periodic, -1)) / 3 + trend
    np.testing.assert_allclose(smoothed, expected, atol=1e-12)


def test_multiscale_rows_are_repeated_passes():
    theta = tangent_angles(resample_curve(wiggly(), 128, closed=True), closed=True)
    weights = filter_weights(5)
    levels = multiscale_angles(theta, 4, weights, closed=True)
    assert levels.shape == (4, 128)
    np.testing.assert_array_equal(levels[0], theta)
    np.testing.assert_allclose(levels[3], lowpass(lowpass(lowpass(theta, weights, closed=True), weights,
                                                         closed=True), weights, closed=True))
    # each pass removes high frequencies: the turning per sample gets smaller
    roughness = [np.abs(np.diff(level)).mean() for level in levels]
    assert all(a > b for a, b in zip(roughness, roughness[1:]))


def test_filter_weights():
    np.testing.assert_allclose(filter_weights(5), np.full(5, 0.2))
    np.testing.assert_allclose(filter_weights(5, "binomial"), np.array([1, 4, 6, 4, 1]) / 16)
    np.testing.assert_allclose(filter_weights(kernel=[1.0, 2.0, 1.0]), [0.25, 0.5, 0.25])
    for width in (0, 4, 2.0, True):
        with pytest.raises(ValueError, match="filter_width"):
            filter_weights(width)
    with pytest.raises(ValueError, match="kernel"):
        filter_weights(5, "gaussian")
    with pytest.raises(ValueError, match="symmetric"):
        filter_weights(kernel=[1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="odd length"):
        filter_weights(kernel=[1.0, 1.0])


def test_close_curve_closes_and_keeps_the_start():
    path = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.1, 0.2]])
    ring = close_curve(path)
    assert ring.shape == (4, 2)
    np.testing.assert_array_equal(ring[0], path[0])
    np.testing.assert_allclose(ring[3], path[3] - 0.75 * path[4])


def test_check_curve_rejects_bad_sketches():
    with pytest.raises(ValueError, match="NaN"):
        check_curve([[0, 0], [1, np.nan], [2, 0]], closed=False)
    with pytest.raises(ValueError, match="repeats a point at index 1"):
        check_curve([[0, 0], [1, 0], [1, 0], [2, 1]], closed=False)
    with pytest.raises(ValueError, match="crosses itself"):
        check_curve([[0, 0], [1, 1], [1, 0], [0, 1]], closed=True)
    with pytest.raises(ValueError, match="at least 5 points"):
        check_curve([[0, 0], [1, 0], [1, 1]], closed=True, min_points=5)
    # a closed curve given with its start repeated at the end is accepted, without the copy
    square = [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]
    assert check_curve(square, closed=True).shape == (4, 2)


def test_wrap_angle():
    np.testing.assert_allclose(wrap_angle([0.0, 3 * np.pi / 2, -3 * np.pi / 2, 2 * np.pi]),
                               [0.0, -np.pi / 2, np.pi / 2, 0.0], atol=1e-12)


# --------------------------------------------------------------------------- training


def test_states_are_histories_over_scale(model):
    n = len(model)
    assert model.states.shape == (n, 3, 8) and n == 6 * 96
    np.testing.assert_array_equal(model.states[:, :, 0], model.angles)
    # the successor's history is the state's history shifted by one sample; unwrapped within each state,
    # so after the curve's last sample the next lap starts 2 pi lower, as a whole
    shift = model.states[model.successor][:, :, 1:] - model.states[:, :, :-1]
    np.testing.assert_allclose(wrap_angle(shift), 0.0, atol=1e-12)
    np.testing.assert_allclose(np.ptp(shift, axis=(1, 2)), 0.0, atol=1e-12)
    assert np.all(model.curve[model.successor] == model.curve)
    assert np.all((model.sample[model.successor] - model.sample) % 96 == 1)


def test_neighbours_are_ranked_by_eq4(model):
    d = state_similarity(model.states[:, None], model.states[model.neighbours], model.weights,
                         model.similarity_sigma)
    np.testing.assert_allclose(model.similarity, d, atol=1e-12)
    assert np.all(np.diff(model.similarity, axis=1) <= 1e-15)
    np.testing.assert_array_equal(model.neighbours[:, 0], np.arange(len(model)))   # D = 1 with itself
    np.testing.assert_allclose(model.similarity[:, 0], 1.0)


def test_similarity_reaches_its_limits_at_extreme_sigma():
    """A random fuzz run: sigma = 1e200 raised OverflowError from sigma**2. Huge sigma: every state alike (1);
    sigma whose square underflows: 1 for equal states, 0 for different ones, as the limits of eq. (4)."""
    state, weights = np.zeros((3, 3)), np.ones((3, 3))
    assert state_similarity(state, state + 0.1, weights, 1e200) == 1.0
    assert state_similarity(state, state, weights, 1e-200) == 1.0
    assert state_similarity(state, state + 0.1, weights, 1e-200) == 0.0
    old_formula = (np.exp(-((state - (state + 0.1)) ** 2) / (2.0 * 0.3**2)) * weights).sum() / weights.sum()
    assert state_similarity(state, state + 0.1, weights, 0.3) == old_formula  # same bits as before the fix


def test_kd_tree_pool_finds_most_of_the_exact_neighbours(model):
    """Ground truth: eq. (4) against every state. The pool misses few of the true most similar states."""
    exact = state_similarity(model.states[:, None], model.states[None], model.weights, model.similarity_sigma)
    truth = np.argsort(-exact, axis=1, kind="stable")[:, : model.neighbours.shape[1]]
    recall = np.mean([np.isin(model.neighbours[i], truth[i]).mean() for i in range(len(model))])
    assert recall > 0.9
    # and what it finds is as similar as the truth, nearly
    best = np.take_along_axis(exact, truth, axis=1)
    assert np.mean(best.sum(axis=1) - model.similarity.sum(axis=1)) < 0.02 * model.neighbours.shape[1]


def test_default_weights_favour_recent_fine_and_all_coarse_history():
    w = default_weights(5, 20)
    assert w.shape == (5, 20) and np.all(w[:, 0] == 1.0)
    assert w[0, 19] < 0.01 and w[4, 19] > 0.3


def test_extent_ratio():
    assert train([circle(300)], order=4, scales=3, samples_per_curve=64).extent_ratio == pytest.approx(1.0, abs=0.01)
    assert train([wiggly(teeth=40, depth=0.08)], order=4, scales=4, samples_per_curve=200).extent_ratio > 1.05


def test_train_rejects_bad_input():
    curve = wiggly()
    with pytest.raises(ValueError, match="empty"):
        train([])
    for key in ("order", "scales", "neighbours"):
        with pytest.raises(ValueError, match=key):
            train([curve], **{key: 0})
    with pytest.raises(ValueError, match="samples_per_curve"):
        train([curve], order=20, samples_per_curve=20)
    with pytest.raises(ValueError, match="steering_scale"):
        train([curve], scales=3, steering_scale=3)
    with pytest.raises(ValueError, match="weights must have shape"):
        train([curve], scales=2, order=3, weights=np.ones((3, 2)))
    with pytest.raises(ValueError, match=r"curves\[1\] crosses itself"):
        train([curve, [[0, 0], [1, 1], [1, 0], [0, 1]]])
    with pytest.raises(ValueError, match="similarity_sigma"):
        train([curve], similarity_sigma=0.0)


# --------------------------------------------------------------------------- steering


def steer_by_the_paper(phi, model, sigma, top, uniforms, sample):
    """Section 3's algorithm written plainly with dense probability vectors (no window)."""
    n_states = len(model)
    steering = model.steering_angles

    def condition(p, angle):
        return p * np.exp(-wrap_angle(angle - steering) ** 2 / (2 * sigma**2))

    def threshold(p):
        order = np.argsort(-p, kind="mergesort")[:top]
        kept = np.zeros(n_states)
        kept[order] = p[order]
        return kept / kept.sum(), order

    def instantiate(p, order, u, previous):
        if model.transitions == "sharp" and len(order) > 1:   # never the previous sample's state again
            order = order[order != previous]
        if not sample:
            return order[0]
        mass = np.cumsum(p[order]) / p[order].sum()
        return order[min(np.searchsorted(mass, u, side="right"), len(order) - 1)]

    p, order = threshold(condition(np.ones(n_states), phi[0]))
    chosen = [instantiate(p, order, uniforms[0], -1)]
    for t in range(1, len(phi)):
        predicted = np.zeros(n_states)
        for j in np.flatnonzero(p):
            transitions = model.transition[j] / model.transition[j].sum()
            np.add.at(predicted, model.successor[model.neighbours[j]], p[j] * transitions)
        p, order = threshold(condition(predicted, phi[t]))
        chosen.append(instantiate(p, order, uniforms[t], chosen[-1]))
    return np.array(chosen)


@pytest.mark.parametrize("transitions", ["sharp", "paper"])
@pytest.mark.parametrize("sample", [False, True])
def test_kernel_follows_the_algorithm_of_section_3(transitions, sample):
    curves = [wiggly(lobes=lobes, teeth=teeth) for lobes, teeth in [(2, 20), (3, 28), (4, 16)]]
    model = train(curves, order=6, scales=3, filter_width=5, samples_per_curve=64, transitions=transitions)
    sketch = resample_curve(wiggly(lobes=2, depth=0.0), 150, closed=True)
    phi = tangent_angles(sketch, closed=True)
    uniforms = np.random.default_rng(3).random(phi.size)
    chosen, restarts = steer(phi, np.ascontiguousarray(model.steering_angles), model.position, model.successor,
                             model.neighbours, model.transition, 0.3, 5, sample, uniforms, -1.0, True,
                             transitions == "paper")
    assert restarts == 0
    np.testing.assert_array_equal(chosen, steer_by_the_paper(phi, model, 0.3, 5, uniforms, sample))


def test_sharp_transitions_weigh_d_to_the_power_and_never_return_to_the_state():
    curves = [wiggly(lobes=lobes, teeth=teeth) for lobes, teeth in [(2, 20), (3, 28)]]
    sharp, paper = (train(curves, order=6, scales=3, samples_per_curve=64, transitions=t) for t in ("sharp", "paper"))
    np.testing.assert_array_equal(paper.transition, paper.similarity)
    state = np.arange(len(sharp))[:, None]
    back = sharp.successor[sharp.neighbours] == state
    gap = np.abs(sharp.sample[sharp.neighbours] - sharp.sample[state]) % 64
    own = (sharp.curve[sharp.neighbours] == sharp.curve[state]) & (np.minimum(gap, 64 - gap) <= 6)
    own &= sharp.neighbours != state
    assert back.any() and np.all(own[back]) and np.all(sharp.transition[own] == 0.0)
    np.testing.assert_allclose(sharp.transition[~own], sharp.similarity[~own] ** SHARPNESS)
    result = elaborate(sharp, wiggly(lobes=2, depth=0.0), n_samples=300)
    assert np.all(result.states[1:] != result.states[:-1])          # no stutter
    with pytest.raises(ValueError, match="transitions"):
        train(curves, transitions="uniform")


def test_crossing_segments_finds_the_crossing_pair_and_nothing_on_a_simple_curve():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    assert crossing_segments(square, closed=True).shape == (0, 2)
    bow_tie = np.array([[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]])
    np.testing.assert_array_equal(crossing_segments(bow_tie, closed=True), [[0, 2]])
    back_on_itself = np.array([[0.0, 0.0], [2.0, 0.0], [1.0, 0.0]])
    np.testing.assert_array_equal(crossing_segments(back_on_itself, closed=False), [[0, 1]])
    with pytest.raises(ValueError, match="at least 3"):
        crossing_segments(square[:2], closed=True)
    with pytest.raises(ValueError, match="NaN"):
        crossing_segments([[0.0, 0.0], [np.nan, 1.0]], closed=False)


@pytest.mark.parametrize("seed", range(4))
def test_untangled_elaborations_are_simple_and_the_paper_rules_are_not_always(model, seed):
    """Section 3.1's intersections: with untangle (default) every elaboration is a simple curve."""
    blob = hand_drawn_curve(200, rng=seed, size=2.0)
    result = elaborate(model, blob, n_samples=400, mode="sample", rng=seed)
    assert result.crossings == 0 and crossing_segments(result.points, closed=True).size == 0
    raw = elaborate(model, blob, n_samples=400, mode="sample", rng=seed, untangle=False)
    np.testing.assert_array_equal(raw.states, result.states)
    assert raw.crossings == len(crossing_segments(raw.points, closed=True))
    assert (raw.crossings == 0) == (result.untangled == 0)
    with pytest.raises(TypeError, match="untangle"):
        elaborate(model, blob, n_samples=400, untangle="yes")


def test_elaboration_is_reproducible_and_seeds_differ(model):
    sketch = wiggly(lobes=2, depth=0.0)
    first = elaborate(model, sketch, n_samples=200, mode="sample", rng=7)
    again = elaborate(model, sketch, n_samples=200, mode="sample", rng=7)
    other = elaborate(model, sketch, n_samples=200, mode="sample", rng=8)
    assert first.points.tobytes() == again.points.tobytes()
    assert not np.array_equal(first.points, other.points)
    assert first.points.shape == (200, 2) and first.restarts == 0


def test_elaboration_follows_the_sketch_direction(model):
    """Eq. (5): every instantiated state's steering angle lies near the sketch's angle."""
    paper = train([wiggly(lobes=lobes, teeth=teeth) for lobes, teeth in [(2, 20), (3, 28), (4, 16)]],
                  order=8, scales=4, filter_width=5, samples_per_curve=96, transitions="paper")
    result = elaborate(paper, wiggly(lobes=3, depth=0.0), n_samples=300, sigma=0.1, coarse="state")
    error = wrap_angle(paper.steering_angles[result.states] - result.steering)
    assert np.abs(error).max() < 0.5 and np.abs(error).mean() < 0.1
    # sharp transitions follow the training curve more and the sketch less: on average within 3 sigma (states
    # drawn at random would be pi / 2 off)
    sharp = elaborate(model, wiggly(lobes=3, depth=0.0), n_samples=300, sigma=0.1, coarse="state")
    assert np.abs(wrap_angle(model.steering_angles[sharp.states] - sharp.steering)).mean() < 0.3
    # with coarse="sketch" (the default) the output's direction minus the state's detail is exactly the sketch's
    exact = elaborate(model, wiggly(lobes=3, depth=0.0), n_samples=300, sigma=0.1, untangle=False)
    detail = model.angles[exact.states, 0] - model.steering_angles[exact.states]
    np.testing.assert_allclose(exact.angles - detail, exact.steering, atol=1e-12)


def test_training_curve_is_reconstructed_from_its_own_coarse_version():
    """The paper's Fig. 6 (top centre): with the curve in the training set, the chain copies it whole."""
    curve = wiggly(teeth=30)
    single = train([curve], order=10, scales=4, filter_width=5, samples_per_curve=120, neighbours=4)
    sketch = coarsen(curve, single)
    result = elaborate(single, sketch, n_samples=120, sigma=0.05, window=0.05)
    runs = copied_runs(single, result.states)
    assert runs.max() >= 110
    np.testing.assert_array_equal(single.sample[result.states], np.arange(120))


def test_closure_option_closes_the_curve(model):
    sketch = wiggly(lobes=2, depth=0.0)
    plain = elaborate(model, sketch, n_samples=200, mode="sample", rng=1)
    closed = elaborate(model, sketch, n_samples=200, mode="sample", rng=1, closure="distribute")
    np.testing.assert_array_equal(closed.states, plain.states)
    gap = np.vstack([closed.points, closed.points[:1]])
    steps = np.hypot(*np.diff(gap, axis=0).T)
    assert steps[-1] == pytest.approx(steps[:-1].mean(), rel=0.5)   # the last segment is an ordinary one
    assert plain.closing_gap == closed.closing_gap > 0


@pytest.mark.parametrize("closure", ["turn", "distribute"])
def test_closures_close_the_curve_and_turning_keeps_the_spacing(model, closure):
    sketch = wiggly(lobes=2, depth=0.0)
    result = elaborate(model, sketch, n_samples=200, rng=1, closure=closure, match_extent=False, untangle=False)
    steps = np.hypot(*np.diff(np.vstack([result.points, result.points[:1]]), axis=0).T)
    assert result.closing_gap > 0.005
    if closure == "turn":   # every segment keeps the sample spacing, the last (closing) one included
        np.testing.assert_allclose(steps, steps.mean(), rtol=1e-9)
    else:                   # shifting every segment by the same vector changes their lengths
        assert steps.std() / steps.mean() > 1e-3


def test_close_angles_is_the_smallest_smooth_change_that_closes():
    theta = tangent_angles(resample_curve(wiggly(), 200, closed=True), closed=True)
    bent = theta + 0.1 * np.sin(np.linspace(0.0, np.pi, theta.size))   # an open curve
    closed = close_angles(bent)
    moves = np.column_stack([np.cos(closed), np.sin(closed)])
    assert np.hypot(*moves.sum(axis=0)) < 1e-9
    delta = closed - bent
    # least squares over the closure equations: delta = a cos(theta) + b sin(theta), for the final angles
    basis = np.column_stack([np.cos(closed), np.sin(closed)])
    fit, *_ = np.linalg.lstsq(basis, delta, rcond=None)
    assert np.abs(basis @ fit - delta).max() < 0.1 * np.abs(delta).max()
    assert np.abs(close_angles(theta) - theta).max() < 0.01   # a closed curve hardly changes
    with pytest.raises(ValueError, match="too far from closed"):
        close_angles(np.zeros(50))                                     # a straight line cannot close
    with pytest.raises(ValueError, match="at least 3"):
        close_angles([0.0, 1.0])


def test_coarse_ring_is_simple_and_closed_by_turning_when_it_can_be():
    theta = tangent_angles(resample_curve(wiggly(), 200, closed=True), closed=True)
    smooth = multiscale_angles(theta, 4, filter_weights(9), closed=True)[-1]
    ring = coarse_ring(smooth, 0.03, (0.0, 0.0))
    steps = np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T)
    assert len(ring) == 200 and np.ptp(steps) < 1e-9 and not crossing_segments(ring, closed=True).size
    straight = coarse_ring(np.zeros(20), 1.0, (0.0, 0.0))                 # cannot turn closed: distributed
    np.testing.assert_allclose(straight, 0.0, atol=1e-12)


def test_every_spiky_training_curve_is_reconstructed_with_closed_steering():
    """Fig. 6 (top centre): the sketch of a training curve is elaborated from that curve alone. Filtered angles
    of spiky curves do not close, so with the paper's steering (the filtered angles) the closed sketch
    disagrees with its own states and the chain leaves the curve."""
    curves = [glyph_outline(name, 512) for name in ("club", "floral_heart", "spade", "heart", "shamrock")]
    fractions = {}
    for close_steering in (True, False):
        model = train(curves, order=10, scales=4, filter_width=5, samples_per_curve=128, neighbours=8,
                      close_steering=close_steering)
        fractions[close_steering] = [
            np.mean(model.curve[elaborate(model, coarsen(curve, model), n_samples=128, sigma=0.05,
                                          window=0.05).states] == k) for k, curve in enumerate(curves)]
        if close_steering:
            sketch = resample_curve(coarsen(curves[0], model), 128, closed=True)
            np.testing.assert_allclose(wrap_angle(tangent_angles(sketch, closed=True) - model.steering[:128]), 0.0,
                                       atol=1e-9)
    assert min(fractions[True]) == 1.0
    assert min(fractions[False]) < 1.0


def test_training_at_each_curves_own_vertex_count():
    curves = [wiggly(n=120), wiggly(n=200, lobes=4), circle(90)]
    model = train(curves, order=8, scales=3, samples_per_curve="vertices")
    np.testing.assert_array_equal(model.curve_samples, [120, 200, 90])
    assert len(model) == 410 and [len(c) for c in model.curves] == [120, 200, 90]
    assert model.position[model.curve == 2].max() == pytest.approx(89 / 90)
    assert len(coarsen(curves[1], model)) == 200                         # a sketch at the curve's own count
    assert copied_runs(model, np.arange(120, 320), slack=1).max() == 200
    with pytest.raises(ValueError, match="at least 10 vertices"):
        train([wiggly(), circle(9)], order=8, scales=3, samples_per_curve="vertices")
    with pytest.raises(ValueError, match="samples_per_curve must be an integer or 'vertices'"):
        train(curves, samples_per_curve="native")


def test_match_size_moves_and_scales_onto_the_reference():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    moved = match_size(square, 3.0 * square + [5.0, -2.0])
    np.testing.assert_allclose(moved, 3.0 * square + [5.0, -2.0], atol=1e-12)
    assert gyration_radius(square) == pytest.approx(np.sqrt(0.5))


def test_coarse_version_keeps_the_size_and_place_of_the_curve():
    curve = resample_curve(wiggly(teeth=40, depth=0.08), 200, closed=True)
    model = train([curve], order=4, scales=4, samples_per_curve=200)
    sketch, as_trained = coarsen(curve, model), resample_simple(curve, 200, closed=True)
    assert gyration_radius(sketch) == pytest.approx(gyration_radius(as_trained), rel=1e-12)
    np.testing.assert_allclose(sketch.mean(axis=0), as_trained.mean(axis=0), atol=1e-12)
    assert total_turning(tangent_angles(sketch, closed=True)) == pytest.approx(2 * np.pi)


def test_open_sketch_gives_an_open_curve(model):
    t = np.linspace(0.0, 3.0, 60)
    stroke = np.column_stack([t, 0.3 * np.sin(2 * t)])
    result = elaborate(model, stroke, closed=False, n_samples=100)
    assert result.points.shape == (100, 2) and not result.closed and result.closing_gap == 0.0
    np.testing.assert_allclose(result.points.mean(axis=0), result.sketch.mean(axis=0), atol=1e-12)
    assert gyration_radius(result.points) == pytest.approx(gyration_radius(result.sketch), rel=1e-12)
    as_drawn = elaborate(model, stroke, closed=False, n_samples=100, match_extent=False)
    np.testing.assert_array_equal(as_drawn.points[0], stroke[0])


def test_elaborate_rejects_bad_input(model):
    good = wiggly(lobes=2, depth=0.0)
    with pytest.raises(ValueError, match="at least 8 points"):
        elaborate(model, good[:5])
    with pytest.raises(ValueError, match="NaN"):
        elaborate(model, np.vstack([good[:-1], [[np.nan, 0.0]]]))
    with pytest.raises(ValueError, match="repeats a point"):
        elaborate(model, np.vstack([good[:10], good[9:]]))
    with pytest.raises(ValueError, match="crosses itself"):
        elaborate(model, [[0, 0], [1, 1], [1, 0], [0, 1], [0.5, -1], [-1, 0.5], [-1, -1], [-0.5, -2]])
    for kwargs, message in [({"n_samples": 8}, "n_samples"), ({"sigma": -1.0}, "sigma"), ({"top": 0}, "top"),
                            ({"mode": "best"}, "mode"), ({"closure": "snap"}, "closure"),
                            ({"coarse": "fine"}, "coarse"), ({"window": 0.7}, "window")]:
        with pytest.raises(ValueError, match=message):
            elaborate(model, good, **kwargs)
    with pytest.raises(ValueError, match="closed sketches only"):
        elaborate(model, good[:50], closed=False, closure="distribute")
    with pytest.raises(ValueError, match="SketchModel"):
        elaborate("model", good)


def test_sketch_from_svg():
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">'
           '<path d="M 10 10 L 20 10 L 20 20 Z"/><path d="M 0 0 L 50 0 L 50 50 L 0 60" fill="none" stroke="black"/></svg>')
    points, closed = sketch_from_svg(svg)
    assert not closed and points.shape == (4, 2)
    np.testing.assert_allclose(points[2], [50.0, -50.0])    # y up
    points, closed = sketch_from_svg('<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 9 0 L 9 9 L 0 9 Z"/></svg>')
    assert closed and points.shape == (4, 2)


def test_copied_runs_with_slack_follow_stutters_and_skips():
    model = train([circle(40), wiggly(lobes=3, depth=0.2)], order=4, scales=2, samples_per_curve=40)
    exact = np.array([3, 4, 5, 6, 50, 51])
    np.testing.assert_array_equal(copied_runs(model, exact), [4, 2])
    stutter = np.array([3, 4, 4, 6, 7, 50])            # repeat, skip one, then another curve
    np.testing.assert_array_equal(copied_runs(model, stutter), [2, 1, 2, 1])
    np.testing.assert_array_equal(copied_runs(model, stutter, slack=1), [5, 1])
    wraps = np.array([38, 39, 0, 1])                   # closed curves continue across their start
    np.testing.assert_array_equal(copied_runs(model, wraps, slack=1), [4])
    with pytest.raises(ValueError, match="slack"):
        copied_runs(model, exact, slack=-1)


# --------------------------------------------------------------------------- the paper's causal filter, subsampling


def test_causal_filter_weighs_the_past_only():
    """Eq. (2)'s causal filter: output t is sum_k w_k theta(t - k), the first sample repeated before the start."""
    theta = np.random.default_rng(0).normal(size=30)
    weights = filter_weights(5, "binomial")
    past = np.concatenate([np.full(4, theta[0]), theta])
    expected = np.array([np.dot(weights, past[t + 4 - np.arange(5)]) for t in range(30)])
    np.testing.assert_allclose(lowpass(theta, weights, closed=False, causal=True), expected, atol=1e-14)
    # closed: the past wraps around, one lap of turning below
    ring = np.cumsum(np.full(40, 2 * np.pi / 40)) + 0.2 * np.sin(np.arange(40) * 2 * np.pi * 3 / 40)
    wrapped = np.concatenate([ring[-4:] - 2 * np.pi, ring])
    expected = np.array([np.dot(weights, wrapped[t + 4 - np.arange(5)]) for t in range(40)])
    np.testing.assert_allclose(lowpass(ring, weights, closed=True, causal=True), expected, atol=1e-13)


def test_subsampled_states_read_coarser_scales_every_two_to_the_s_samples():
    curves = [wiggly(lobes=2, teeth=20), wiggly(lobes=3, teeth=28)]
    model = train(curves, order=5, scales=3, samples_per_curve=64, subsample=True, causal=True)
    assert model.causal and model.subsample
    first = model.angles[:64]                    # curve 0's angles, (64, scales)
    turning = np.array([total_turning(first[:, s]) for s in range(3)])
    for t in (0, 3, 40):
        for s in range(3):
            for tau in range(5):
                back = t - tau * 2**s
                expected = first[back % 64, s] + np.floor_divide(back, 64) * turning[s]
                assert model.states[t, s, tau] == pytest.approx(expected, abs=1e-12)
    with pytest.raises(ValueError, match="subsample"):
        train([curve[:40] for curve in curves], closed=False, order=20, scales=5, samples_per_curve=64, subsample=True)
    with pytest.raises(TypeError, match="causal"):
        train(curves, causal="yes")
