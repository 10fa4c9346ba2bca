"""Synthetic leaf outlines and hand-drawn-like sketches: simple, oriented, anchored, seeded, checked."""

import numpy as np
import pytest
import shapely
from scipy.spatial import cKDTree

from paperlib.datasets.sketches import (
    LEAF_KINDS,
    MAX_TREMOR,
    MAX_WOBBLE,
    hand_drawn_curve,
    leaf_outline,
    leaf_outlines,
)
from paperlib.geometry import signed_area


def edge_lengths(points, closed=True):
    if closed:
        points = np.vstack([points, points[:1]])
    return np.hypot(*np.diff(points, axis=0).T)


def is_simple_ring(ring):
    return shapely.Polygon(ring).is_valid and shapely.LinearRing(ring).is_simple


def concave_runs(ring):
    """Runs of clockwise turns along a counter-clockwise ring: one per sinus (tooth gap or lobe gap)."""
    forward = np.roll(ring, -1, axis=0) - ring
    following = np.roll(forward, -1, axis=0)
    concave = forward[:, 0] * following[:, 1] - forward[:, 1] * following[:, 0] < 0
    return int(np.sum(concave & ~np.roll(concave, 1)))


# ---------------------------------------------------------------------------------------------
# Leaves
# ---------------------------------------------------------------------------------------------


def test_leaf_kinds():
    assert LEAF_KINDS == ("ovate", "lanceolate", "lobed", "palmate", "cordate")


@pytest.mark.parametrize("kind", LEAF_KINDS)
def test_leaf_is_a_simple_ccw_ring_at_every_resolution(kind):
    for seed in range(6):
        for n_points in (16, 33, 128, 200, 512, 1001):
            leaf = leaf_outline(kind, rng=seed, n_points=n_points)
            assert leaf.shape == (n_points, 2) and leaf.dtype == np.float64
            assert np.isfinite(leaf).all()
            assert np.all(edge_lengths(leaf) > 0)  # no repeated points, no repeated end point
            assert signed_area(leaf) > 0
            assert is_simple_ring(leaf), (kind, seed, n_points)


@pytest.mark.parametrize("kind", LEAF_KINDS)
def test_leaf_starts_at_its_base_on_the_midrib(kind):
    for seed in range(10):
        leaf = leaf_outline(kind, rng=seed)
        assert leaf[0].tolist() == [0.0, 0.0]
        # The midrib x = 0 crosses the blade from the base (0, 0) up to the tip (0, ~1).
        midrib = shapely.Polygon(leaf).intersection(shapely.LineString([(0, -5), (0, 5)]))
        assert midrib.geom_type == "LineString"
        low, high = midrib.bounds[1], midrib.bounds[3]
        assert low == pytest.approx(0.0, abs=1e-12)
        assert high == pytest.approx(1.0, abs=0.5 * edge_lengths(leaf).max())


@pytest.mark.parametrize("kind", LEAF_KINDS)
def test_leaf_tip_is_its_top_near_half_way_round(kind):
    for seed in range(10):
        leaf = leaf_outline(kind, rng=seed, n_points=512)
        spacing = edge_lengths(leaf).max()
        tip = int(np.argmin(np.hypot(leaf[:, 0], leaf[:, 1] - 1.0)))
        assert np.hypot(*(leaf[tip] - (0.0, 1.0))) <= 0.5 * spacing
        assert abs(tip / 512 - 0.5) <= 0.03  # arc-length position of the tip
        assert 1.0 - spacing <= leaf[:, 1].max() <= 1.0 + 1e-12  # length 1: the tip is the top


def test_leaf_points_are_equally_spaced_in_arc_length():
    for kind in LEAF_KINDS:
        fine = leaf_outline(kind, rng=3, n_points=20000)
        perimeter = edge_lengths(fine).sum()
        leaf = leaf_outline(kind, rng=3, n_points=256)
        chords = edge_lengths(leaf)
        # Chords never exceed the arc between their ends (the fine perimeter cuts corners too, by
        # less than 0.1 %) and only shorten across sharp teeth.
        assert chords.max() <= perimeter / 256 * 1.001
        assert np.median(chords) >= 0.97 * perimeter / 256


# Large-scale structure of each kind, from the ranges in the module docstring (with the
# teeth's few thousandths): widths of the bounding box, solidity (area over convex-hull area),
# sinuses (concave runs: each tooth or lobe gap) and how far the blade reaches below its base.
KIND_FACTS = {
    "ovate": dict(width=(0.5, 0.7), solidity=(0.95, 1.0), sinuses=(20, 45), lowest=0.0),
    "lanceolate": dict(width=(0.17, 0.25), solidity=(0.93, 1.0), sinuses=(40, 80), lowest=0.0),
    "lobed": dict(width=(0.45, 0.66), solidity=(0.6, 0.85), sinuses=(8, 24), lowest=0.0),
    "palmate": dict(width=(1.1, 1.6), solidity=(0.4, 0.6), sinuses=(16, 45), lowest=-0.05),
    "cordate": dict(width=(0.9, 1.3), solidity=(0.93, 1.0), sinuses=(16, 40), lowest=-0.12),
}


@pytest.mark.parametrize("kind", LEAF_KINDS)
def test_leaf_kinds_have_their_large_scale_structure(kind):
    facts = KIND_FACTS[kind]
    for seed in range(8):
        leaf = leaf_outline(kind, rng=seed, n_points=1024)
        polygon = shapely.Polygon(leaf)
        assert facts["width"][0] <= np.ptp(leaf[:, 0]) <= facts["width"][1]
        assert facts["solidity"][0] <= polygon.area / polygon.convex_hull.area <= facts["solidity"][1]
        assert facts["sinuses"][0] <= concave_runs(leaf) <= facts["sinuses"][1]
        if facts["lowest"] < 0:  # basal lobes hang below the petiole
            assert leaf[:, 1].min() < facts["lowest"]
        else:
            assert leaf[:, 1].min() >= -1e-12


# Deepest bay of each kind: how far the outline retreats from its convex hull (teeth only on the
# ovate and lanceolate leaves, sinuses between lobes on the others).
DEEPEST_BAY = {
    "ovate": (0.005, 0.03),
    "lanceolate": (0.002, 0.015),
    "lobed": (0.08, 0.25),
    "palmate": (0.3, 0.55),
    "cordate": (0.12, 0.3),
}


@pytest.mark.parametrize("kind", LEAF_KINDS)
def test_leaf_bays_are_teeth_or_sinuses(kind):
    low, high = DEEPEST_BAY[kind]
    for seed in range(4):
        leaf = leaf_outline(kind, rng=seed, n_points=256)
        hull = shapely.Polygon(leaf).convex_hull.exterior
        assert low < shapely.distance(hull, shapely.points(leaf)).max() < high


def test_leaf_is_nearly_but_not_exactly_symmetric():
    for kind in LEAF_KINDS:
        leaf = leaf_outline(kind, rng=11, n_points=1000)
        mirrored = leaf * (-1.0, 1.0)
        distance, _ = cKDTree(leaf).query(mirrored)
        assert 1e-4 < distance.max() < 0.06, kind


def test_leaf_determinism():
    for kind in LEAF_KINDS:
        a = leaf_outline(kind, rng=5)
        assert a.tobytes() == leaf_outline(kind, rng=5).tobytes()
        assert a.tobytes() == leaf_outline(kind, rng=np.random.default_rng(5)).tobytes()
        assert a.tobytes() != leaf_outline(kind, rng=6).tobytes()


def test_leaf_outlines_cycle_over_the_kinds_with_their_own_seeds():
    leaves = leaf_outlines(rng=7, n_points=128)
    assert len(leaves) == 14
    children = np.random.default_rng(7).spawn(14)
    for i, (leaf, child) in enumerate(zip(leaves, children)):
        expected = leaf_outline(LEAF_KINDS[i % 5], rng=child, n_points=128)
        assert leaf.tobytes() == expected.tobytes()
    assert leaves[0].tobytes() != leaves[5].tobytes()  # two ovate leaves, different variations
    again = leaf_outlines(rng=7, n_points=128)
    assert all(a.tobytes() == b.tobytes() for a, b in zip(leaves, again))
    assert leaf_outlines(rng=8, n_points=128)[0].tobytes() != leaves[0].tobytes()
    assert len(leaf_outlines(3, n_points=64)) == 3


@pytest.mark.parametrize("kind", ["oak", "", "Ovate", 3, None])
def test_leaf_unknown_kind(kind):
    with pytest.raises(ValueError, match="unknown leaf kind"):
        leaf_outline(kind)


@pytest.mark.parametrize("n_points", [15, 0, -3, 128.0, "512", True, None])
def test_leaf_bad_n_points(n_points):
    with pytest.raises(ValueError, match="n_points must be an integer >= 16"):
        leaf_outline("ovate", n_points=n_points)
    with pytest.raises(ValueError, match="n_points must be an integer >= 16"):
        leaf_outlines(2, n_points=n_points)


@pytest.mark.parametrize("n", [0, -1, 2.5, "14", True, None])
def test_leaf_outlines_bad_n(n):
    with pytest.raises(ValueError, match="n must be an integer >= 1"):
        leaf_outlines(n)


# ---------------------------------------------------------------------------------------------
# Hand-drawn curves
# ---------------------------------------------------------------------------------------------


def test_sketches_are_simple_finite_without_repeated_points():
    settings = [dict(), dict(tremor=MAX_TREMOR, wobble=MAX_WOBBLE), dict(tremor=0.0, wobble=0.0)]
    for seed in range(40):
        for closed in (True, False):
            for setting in settings:
                curve = hand_drawn_curve(128, closed=closed, rng=seed, **setting)
                assert curve.shape == (128, 2) and curve.dtype == np.float64
                assert np.isfinite(curve).all()
                assert len(np.unique(curve, axis=0)) == 128
                if closed:
                    assert is_simple_ring(curve), (seed, setting)
                    assert signed_area(curve) > 0
                else:
                    assert shapely.LineString(curve).is_simple, (seed, setting)


@pytest.mark.parametrize("closed", [True, False])
def test_sketch_size_centre_and_spacing(closed):
    for size in (0.5, 1.0, 7.0):
        curve = hand_drawn_curve(1000, closed=closed, size=size, rng=2)
        lower, upper = curve.min(axis=0), curve.max(axis=0)
        assert np.hypot(*(upper - lower)) == pytest.approx(size, rel=1e-12)
        np.testing.assert_allclose(lower + upper, 0.0, atol=1e-12 * size)
        chords = edge_lengths(curve, closed=closed)
        assert chords.max() / chords.min() < 1.05  # equal arc length on a smooth curve
    assert len(hand_drawn_curve(rng=0)) == 1000


def test_smooth_sketches_without_wobble_are_a_circle_and_a_segment():
    circle = hand_drawn_curve(500, rng=4, wobble=0.0, tremor=0.0)
    radii = np.hypot(*(circle - circle.mean(axis=0)).T)
    assert radii.std() / radii.mean() < 1e-6
    segment = hand_drawn_curve(500, closed=False, rng=4, wobble=0.0, tremor=0.0)
    direction = (segment[-1] - segment[0]) / np.hypot(*(segment[-1] - segment[0]))
    offsets = (segment - segment[0]) @ np.array([-direction[1], direction[0]])
    assert np.abs(offsets).max() < 1e-9


def test_stroke_never_turns_back():
    for seed in range(30):
        stroke = hand_drawn_curve(400, closed=False, rng=seed, wobble=MAX_WOBBLE, tremor=MAX_TREMOR)
        step = np.diff(stroke, axis=0)
        heading = np.unwrap(np.arctan2(step[:, 1], step[:, 0]))
        assert np.ptp(heading) < np.radians(160.0)


@pytest.mark.parametrize("closed", [True, False])
def test_tremor_displaces_the_curve_by_about_tremor_times_size(closed):
    for seed in range(5):
        for tremor in (0.002, MAX_TREMOR):
            shaky = hand_drawn_curve(3000, closed=closed, size=2.0, rng=seed, tremor=tremor)
            steady = hand_drawn_curve(3000, closed=closed, size=2.0, rng=seed, tremor=0.0)
            distance, _ = cKDTree(steady).query(shaky)
            assert 0.5 < np.sqrt(np.mean(distance**2)) / (tremor * 2.0) < 2.5


def test_sketch_wobble_controls_the_departure_from_a_circle():
    def radius_spread(curve):
        radii = np.hypot(*(curve - curve.mean(axis=0)).T)
        return radii.std() / radii.mean()

    for seed in range(5):
        small = radius_spread(hand_drawn_curve(rng=seed, wobble=0.05, tremor=0.0))
        large = radius_spread(hand_drawn_curve(rng=seed, wobble=0.3, tremor=0.0))
        assert small < 0.1 < large


def test_sketch_determinism():
    for closed in (True, False):
        a = hand_drawn_curve(300, closed=closed, rng=9)
        assert a.tobytes() == hand_drawn_curve(300, closed=closed, rng=9).tobytes()
        assert a.tobytes() == hand_drawn_curve(300, closed=closed, rng=np.random.default_rng(9)).tobytes()
        assert a.tobytes() != hand_drawn_curve(300, closed=closed, rng=10).tobytes()


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(n_points=15), "n_points must be an integer >= 16"),
        (dict(n_points=100.0), "n_points must be an integer >= 16"),
        (dict(size=0.0), "size must be a positive finite number"),
        (dict(size=-1.0), "size must be a positive finite number"),
        (dict(size=float("nan")), "size must be a positive finite number"),
        (dict(size="big"), "size must be a number"),
        (dict(tremor=-0.001), "tremor must be a non-negative finite number"),
        (dict(tremor=float("inf")), "tremor must be a non-negative finite number"),
        (dict(tremor=0.02), "tremor must be at most 0.015"),
        (dict(wobble=-0.1), "wobble must be a non-negative finite number"),
        (dict(wobble=0.6), "wobble must be at most 0.5"),
        (dict(closed="yes"), "closed must be True or False"),
    ],
)
def test_sketch_bad_input(kwargs, message):
    with pytest.raises(ValueError, match=message):
        hand_drawn_curve(**kwargs)
