"""Tests of paperlib.strokepattern (Barla et al. 2006): analysis, measures, synthesis, variation."""

import numpy as np
import pytest
import shapely

from paperlib.geometry import Element, OrientedBoxes, Stroke, oriented_bounding_boxes
from paperlib.strokepattern import (
    MEASURES,
    Thresholds,
    analyze,
    chain_edges,
    cluster_strokes,
    continuation,
    exchange_parameters,
    growth_order,
    measure_tables,
    proximity,
    ring_neighbourhoods,
    rule_score,
    seeds_1d,
    seeds_2d,
    shift_vectors,
    synthesize,
    target_count,
    unskewed_delaunay_edges,
    vary_positions,
)
from paperlib.strokepattern._kernels import BEST, CLOSE, RANDOM, grow, grow_reference
from paperlib.strokepattern.synthesis import _graph_arrays, pairing_gate, _seed_patch


def segment(a, b, width=0.05, color="#000000"):
    return Stroke(np.array([a, b], dtype=float), width, color)


def boxes_of(*strokes):
    return oriented_bounding_boxes([Element((s,)) for s in strokes])


def hatching(n=20, spacing=1.0, length=2.0, colors=("#000000",), seed=0):
    """Vertical strokes along the x axis, each drawn twice (a sketchy double stroke)."""
    rng = np.random.default_rng(seed)
    strokes = []
    for i in range(n):
        x = i * spacing + rng.uniform(-0.05, 0.05)
        for _ in range(2):
            dx = rng.uniform(-0.03, 0.03)
            strokes.append(segment((x + dx, -length / 2), (x + dx + 0.01, length / 2), color=colors[i % len(colors)]))
    return strokes


def bars_2d(seed=0, size=8.0, spacing=1.0):
    """Bars in three directions on a jittered triangular lattice."""
    rng = np.random.default_rng(seed)
    strokes = []
    for row in range(int(size / (spacing * 0.866))):
        for column in range(int(size / spacing)):
            centre = np.array([column * spacing + (row % 2) * spacing / 2, row * spacing * 0.866])
            centre += rng.uniform(-0.05, 0.05, 2)
            angle = rng.choice([0.0, np.pi / 3, 2 * np.pi / 3])
            half = 0.3 * np.array([np.cos(angle), np.sin(angle)])
            strokes.append(segment(centre - half, centre + half))
    return strokes


# --------------------------------------------------------------------------- section 2.2 measures


def test_proximity_of_nested_and_separate_boxes():
    boxes = boxes_of(segment((0, 0), (4, 0)), segment((1, 0), (2, 0)), segment((0, 3), (4, 3)))
    corners = boxes.corners()
    assert proximity(corners[0], corners[1]) == pytest.approx(0.0)  # nested: dH(small, big) = 0
    assert proximity(corners[0], corners[2]) == pytest.approx(3.0)


def test_continuation_gap_of_collinear_segments():
    a, b = boxes_of(segment((0, 0), (2, 0))), boxes_of(segment((2.3, 0.05), (4, 0.05)))
    assert continuation(a, b, 0.5) == pytest.approx([0.3])
    off_axis = boxes_of(segment((2.3, 0.4), (4, 0.4)))  # farther than epsilon / 2 from the axis
    assert continuation(a, off_axis, 0.5) == [np.inf]
    # Symmetric, and the proximity of two collinear dashes end to end is large.
    assert continuation(b, a, 0.5) == pytest.approx([0.3])
    assert proximity(a.corners()[0], b.corners()[0]) > 1.5


def test_cluster_strokes_groups_overlapping_and_continuing_strokes():
    strokes = [
        segment((0, 0), (0, 2)), segment((0.05, 0.1), (0.04, 2.1)),  # a sketchy double hatch
        segment((3, 0), (3, 0.9)), segment((3, 1.1), (3, 2)),  # a dashed hatch: continuation only
        segment((6, 0), (6, 2)),
    ]
    assert cluster_strokes(strokes, 0.5).tolist() == [0, 0, 1, 1, 2]
    assert cluster_strokes(strokes, 0.1).tolist() == [0, 0, 1, 2, 3]  # gap 0.2 > epsilon
    assert cluster_strokes(strokes, 5.0).max() == 0  # everything within epsilon


def test_cluster_labels_follow_drawing_order():
    strokes = [segment((5, 0), (5, 1)), segment((0, 0), (0, 1)), segment((5.05, 0), (5.05, 1))]
    assert cluster_strokes(strokes, 0.3).tolist() == [0, 1, 0]


@pytest.mark.parametrize("bad, message", [
    ([segment((0, 0), (1, 0))], "at least 2 strokes"),
    ([], "at least 2 strokes"),
    ([segment((0, 0), (1, 0)), Stroke([[3.0, 3.0]])], "single point"),
    ([segment((0, 0), (1, 0)), "not a stroke"], "expected a Stroke"),
])
def test_cluster_strokes_rejects_bad_patterns(bad, message):
    with pytest.raises(ValueError, match=message):
        cluster_strokes(bad, 0.5)


@pytest.mark.parametrize("epsilon", [0, -1, np.nan, np.inf])
def test_cluster_strokes_rejects_bad_epsilon(epsilon):
    with pytest.raises(ValueError, match="epsilon"):
        cluster_strokes(hatching(3), epsilon)


def test_single_point_strokes_fit_on_their_contour():
    strokes = [Stroke([[0.0, 0.0]], 0.2), Stroke([[3.0, 0.0]], 0.2), Stroke([[6.0, 0.0]], 0.2)]
    assert cluster_strokes(strokes, 0.5, contour=True).tolist() == [0, 1, 2]


# --------------------------------------------------------------------------- section 2.3 distribution


def test_unskewed_delaunay_drops_obtuse_triangles():
    # A flat triangle (angle 160 degrees at the apex) next to a right triangle.
    points = np.array([(0, 0), (2, 0), (1, 0.18), (1, -20.0)])  # the far point keeps edge 0-1 Delaunay
    edges = unskewed_delaunay_edges(points)
    triangles_ok = {tuple(e) for e in edges}
    assert (0, 2) not in triangles_ok and (1, 2) not in triangles_ok  # only in the skewed triangle
    assert {(0, 1), (0, 3), (1, 3)} <= triangles_ok


def test_unskewed_delaunay_errors():
    with pytest.raises(ValueError, match="collinear"):
        unskewed_delaunay_edges([(0, 0), (1, 0), (2, 0), (3, 0)])
    with pytest.raises(ValueError, match="no unskewed triangle"):
        unskewed_delaunay_edges([(0, 0), (2, 0), (1, 0.1)])
    with pytest.raises(ValueError, match="at least 3"):
        unskewed_delaunay_edges([(0, 0), (1, 0)])


def test_shift_vectors_are_offsets_from_the_neighbour_barycentre():
    positions = np.array([(0.0, 0.0), (1.0, 0.3), (2.0, 0.0)])
    shifts = shift_vectors(positions, [(0, 1), (1, 2)])
    assert shifts[1] == pytest.approx([0.0, 0.3])
    assert shifts[0] == pytest.approx([-1.0, -0.3])


def test_analyze_1d_hatching_finds_every_hatch():
    analysis = analyze(hatching(20), 0.4, dimension=1)
    assert len(analysis) == 20
    assert analysis.edges.shape == (19, 2)
    assert analysis.area == pytest.approx(20.0, rel=0.02)  # span + one spacing
    assert analysis.mean_length == pytest.approx(2.0, rel=0.01)
    assert np.all(np.abs(np.mod(analysis.boxes.angles, np.pi) - np.pi / 2) < 0.02)


def test_analyze_rejects_bad_input():
    with pytest.raises(ValueError, match="at least 2"):
        analyze(hatching(1), 5.0, dimension=1)
    with pytest.raises(ValueError, match="dimension"):
        analyze(hatching(5), 0.4, dimension=3)
    with pytest.raises(ValueError, match="collinear"):
        analyze(hatching(5), 0.4, dimension=2)


# --------------------------------------------------------------------------- section 3.1 measures


def test_measure_tables_known_values():
    half_lengths = np.array([(1.0, 0.1), (1.5, 0.1), (1.0, 0.3)])
    angles = np.array([0.0, np.pi / 2, np.pi - 0.1])
    colors = np.array([(0, 0, 0), (1, 0, 0), (0, 0, 0)], dtype=float)
    tables = dict(zip(MEASURES, measure_tables(half_lengths, angles, colors)))
    assert tables["par"][0, 1] == pytest.approx(np.pi / 2)
    assert tables["par"][0, 2] == pytest.approx(0.1)  # axes have no direction
    assert tables["ov"][0, 1] == pytest.approx(1.5) and tables["ov"][1, 0] == pytest.approx(1.5)
    assert tables["sup"][0, 2] == pytest.approx(0.4)
    assert tables["col"][0, 1] == pytest.approx(1.0)
    assert np.diag(tables["shape"]) == pytest.approx(0.0)
    assert tables["shape"][0, 1] == pytest.approx(tables["shape"][1, 0])


def test_rule_score_is_the_boolean_rule():
    rng = np.random.default_rng(0)
    sigmas = Thresholds().vector(2.0)
    means = rng.uniform(0, 2, (2000, 5)) * sigmas * np.array([1, 1, 1, 1, 1])
    means[:, 2] = rng.uniform(1.0, 2.0, 2000)
    passes = means < sigmas
    rule = passes[:, 4] & (passes[:, 0] | (passes[:, 1] & passes[:, 2] & passes[:, 3]))
    assert np.array_equal(rule_score(means, sigmas) < 1, rule)


def test_thresholds_validate():
    assert Thresholds().vector(1.0) == pytest.approx([0.1, np.pi / 20, 1.5, 0.1, 0.15])
    with pytest.raises(ValueError, match="ov"):
        Thresholds(ov=0.9)
    with pytest.raises(ValueError, match="par"):
        Thresholds(par=-1)


# --------------------------------------------------------------------------- section 3.2 seeds and graphs


def test_seeds_1d_are_even_along_a_curved_path():
    path = np.column_stack([np.linspace(0, 10, 50), np.sin(np.linspace(0, 3, 50))])
    seeds = seeds_1d(path, 25, rng=0)
    spacing = np.diff(seeds.arc)
    # Lloyd in 1D is a diffusion: short wavelengths of the random start vanish in a few steps, the longest
    # decay slowly; after the default 40 steps the spacing varies by about 1 % (std / mean).
    assert spacing.std() / spacing.mean() < 0.02
    exact = np.diff(seeds_1d(path, 25, iterations=2000, rng=0).arc)
    assert exact.std() / exact.mean() < 1e-3  # the fixed point: equal spacing
    assert shapely.distance(shapely.linestrings(path), shapely.points(seeds.positions)).max() < 1e-9
    with pytest.raises(ValueError, match="zero length"):
        seeds_1d([(1, 1), (1, 1)], 5)


def test_seeds_2d_fill_the_region_evenly():
    region = shapely.Polygon([(0, 0), (10, 0), (10, 6), (4, 10), (0, 10)])
    seeds = seeds_2d(region, 60, rng=1)
    assert shapely.contains_xy(region, *seeds.positions.T).all()
    lengths = np.hypot(*(seeds.positions[seeds.edges[:, 0]] - seeds.positions[seeds.edges[:, 1]]).T)
    assert lengths.std() / lengths.mean() < 0.25  # near-regular after Lloyd
    with pytest.raises(ValueError, match="positive area"):
        seeds_2d(shapely.Polygon([(0, 0), (1, 1), (2, 2)]), 10)
    with pytest.raises(ValueError, match="positive area|xmax"):
        seeds_2d((0, 0, 0, 1), 10)


def test_seed_counts_beyond_the_budget_are_refused_before_allocating():
    """A random fuzz run asked seeds_1d for 1e12 seeds and got a MemoryError (7 TiB)."""
    path = np.array([(0.0, 0.0), (1.0, 0.0)])
    with pytest.raises(ValueError, match="max_seeds"):
        seeds_1d(path, 10**12)
    with pytest.raises(ValueError, match="max_seeds"):
        seeds_2d((0, 1, 0, 1), 11, max_seeds=10)
    assert len(seeds_1d(path, 11, max_seeds=11).arc) == 11
    analysis = analyze(hatching(20), 0.4, dimension=1)
    with pytest.raises(ValueError, match="max_seeds"):
        synthesize(analysis, [(0, 0), (100, 0)], n=10**12)
    with pytest.raises(ValueError, match="max_seeds"):
        synthesize(analysis, [(0, 0), (100, 0)], max_seeds=5)


def test_lloyd_work_beyond_the_budget_is_refused_before_drawing():
    """A random fuzz run asked seeds_2d for 10**9 Lloyd iterations, which ran as long as asked."""
    path = np.array([(0.0, 0.0), (1.0, 0.0)])
    with pytest.raises(ValueError, match="max_cells"):
        seeds_2d((0, 1, 0, 1), 5, iterations=10**9)
    with pytest.raises(ValueError, match="max_cells"):
        seeds_1d(path, 10, iterations=10**9)
    with pytest.raises(ValueError, match="max_cells"):
        seeds_2d((0, 1, 0, 1), 5, iterations=3, max_cells=14)
    assert len(seeds_2d((0, 1, 0, 1), 5, iterations=3, max_cells=15, rng=0).positions) == 5
    assert len(seeds_1d(path, 10, iterations=4, max_cells=40, rng=0).arc) == 10


def test_ring_neighbourhoods_on_a_chain():
    pointers, neighbours = ring_neighbourhoods(6, [(0, 1), (1, 2), (2, 3), (3, 4), (4, 5)], 2)
    assert neighbours[pointers[2]:pointers[3]].tolist() == [0, 1, 3, 4]
    assert neighbours[pointers[0]:pointers[1]].tolist() == [1, 2]
    with pytest.raises(ValueError, match="rings"):
        ring_neighbourhoods(6, [(0, 1)], 0)


def test_growth_order_goes_outward():
    positions = np.column_stack([np.arange(7.0), np.zeros(7)])
    order = growth_order(positions, [(i, i + 1) for i in range(6)], 3)
    assert order[0] == 3
    assert [abs(int(i) - 3) for i in order] == sorted(abs(int(i) - 3) for i in order)


# --------------------------------------------------------------------------- synthesis


def test_kernel_matches_python_reference():
    analysis = analyze(bars_2d(0), 0.1, dimension=2)
    seeds = seeds_2d((0, 6, 0, 6), 40, rng=3)
    order = growth_order(seeds.positions, seeds.edges, 0)
    tables = measure_tables(analysis.boxes.half_lengths, analysis.boxes.angles, analysis.colors)
    sigmas = Thresholds().vector(analysis.mean_length)
    uniforms = np.random.default_rng(4).random(40)
    gate2 = pairing_gate(analysis) ** 2
    for rings in (1, 2):
        target_graph = _graph_arrays(seeds.positions, seeds.frames, seeds.edges, rings)
        reference_graph = _graph_arrays(analysis.positions, analysis.frames, analysis.edges, rings)
        patch = _seed_patch(target_graph, order[0], reference_graph, 5, pairing_gate(analysis))
        free = np.full(40, -1)
        for mode, initial, coverage in ((RANDOM, free, False), (BEST, patch, True), (CLOSE, patch, True),
                                        (CLOSE, free, False)):
            arguments = (order, *target_graph, *reference_graph, tables, sigmas, uniforms, initial, mode, 0.1, gate2,
                         coverage)
            fast, slow = grow(*arguments), grow_reference(*arguments)
            for a, b in zip(fast, slow):
                np.testing.assert_array_equal(a, b)
            seeded = initial >= 0
            np.testing.assert_array_equal(fast[0][seeded], initial[seeded])
        ring_size = target_graph[0][order[0] + 1] - target_graph[0][order[0]]
        assert 1 < (patch >= 0).sum() <= ring_size + 1


def test_synthesis_is_reproducible_and_copies_reference_elements():
    analysis = analyze(bars_2d(1), 0.1, dimension=2)
    first = synthesize(analysis, (0, 12, 0, 12), rings=2, rng=7)
    second = synthesize(analysis, (0, 12, 0, 12), rings=2, rng=7)
    assert [s.points.tobytes() for s in first.strokes] == [s.points.tobytes() for s in second.strokes]
    other = synthesize(analysis, (0, 12, 0, 12), rings=2, rng=8)
    assert not np.array_equal(first.positions, other.positions)
    assert len(first) == target_count(analysis, (0, 12, 0, 12))
    assert target_count(analysis, (0, 12, 0, 12)) == round(len(analysis) * 144 / analysis.area)
    boxes = oriented_bounding_boxes(first.elements)
    np.testing.assert_allclose(boxes.half_lengths, analysis.boxes.half_lengths[first.source], atol=1e-9)
    np.testing.assert_allclose(boxes.centers, first.positions, atol=1e-9)
    assert first.matched.mean() > 0.8


def test_1d_synthesis_follows_a_curved_path():
    analysis = analyze(hatching(20), 0.4, dimension=1)
    t = np.linspace(0, np.pi, 80)
    path = np.column_stack([10 * np.cos(t), 10 * np.sin(t)])  # a half circle, radius 10
    result = synthesize(analysis, path, rings=2, rng=0)
    assert len(result) == round(20 * 10 * np.pi / analysis.area)
    boxes = oriented_bounding_boxes(result.elements)
    # Hatches stay perpendicular to the path: the element axis is radial.
    radial = np.mod(np.arctan2(boxes.centers[:, 1], boxes.centers[:, 0]), np.pi)
    difference = np.abs(np.mod(boxes.angles - radial + np.pi / 2, np.pi) - np.pi / 2)
    assert difference.max() < 0.1


def test_colour_alternation_is_kept():
    analysis = analyze(hatching(24, colors=("#c0392b", "#1f618d")), 0.4, dimension=1)
    result = synthesize(analysis, [(0, 0), (40, 0)], rings=1, rng=0)
    colors = np.array([e.strokes[0].color for e in result.elements])[np.argsort(result.positions[:, 0])]
    assert np.mean(colors[1:] != colors[:-1]) > 0.9


def test_synthesize_rejects_bad_targets():
    analysis = analyze(hatching(10), 0.4, dimension=1)
    with pytest.raises(ValueError, match="zero length"):
        synthesize(analysis, [(0, 0), (0, 0)])
    with pytest.raises(ValueError, match="rings"):
        synthesize(analysis, [(0, 0), (5, 0)], rings=0)
    with pytest.raises(ValueError, match="choice"):
        synthesize(analysis, [(0, 0), (5, 0)], choice="first")
    analysis_2d = analyze(bars_2d(0), 0.1, dimension=2)
    with pytest.raises(ValueError, match="positive area"):
        synthesize(analysis_2d, shapely.Polygon([(0, 0), (1, 0), (2, 0)]))


# --------------------------------------------------------------------------- section 3.3 variation


def test_exchange_with_zero_amount_changes_nothing_and_full_amount_draws_reference_values():
    analysis = analyze(bars_2d(2), 0.1, dimension=2)
    result = synthesize(analysis, (0, 8, 0, 8), rings=2, rng=0)
    same = exchange_parameters(result, analysis, 0.0, rng=1)
    for a, b in zip(same.strokes, result.strokes):
        np.testing.assert_allclose(a.points, b.points, atol=1e-12)
    varied = exchange_parameters(result, analysis, 1.0, rng=1)
    boxes = oriented_bounding_boxes(varied.elements)
    reference_lengths = 2 * analysis.boxes.half_lengths[:, 0]
    lengths = 2 * boxes.half_lengths[:, 0]
    assert np.min(np.abs(lengths[:, None] - reference_lengths[None]), axis=1).max() < 1e-9
    with pytest.raises(ValueError, match="amount"):
        exchange_parameters(result, analysis, 1.5)


def test_vary_positions_moves_interior_elements_to_barycentre_plus_shift():
    analysis = analyze(hatching(12), 0.4, dimension=1)
    result = synthesize(analysis, [(0, 0), (12, 0)], rings=1, rng=0)
    varied = vary_positions(result, analysis)
    order = np.argsort(result.positions[:, 0])
    ends = order[[0, -1]]
    np.testing.assert_array_equal(varied.positions[ends], result.positions[ends])  # one neighbour: unmoved
    i = order[5]
    s_ref = analysis.shifts[result.source[i]]
    barycentre = result.positions[order[[4, 6]]].mean(axis=0)
    assert np.linalg.norm(varied.positions[i] - barycentre) == pytest.approx(np.linalg.norm(s_ref), rel=0.1)
    printed = vary_positions(result, analysis, scaling="printed")
    assert np.linalg.norm(printed.positions[i] - barycentre) == pytest.approx(np.linalg.norm(s_ref) / 2, rel=0.1)


def test_boxes_type_roundtrip():
    boxes = boxes_of(segment((0, 0), (1, 0)), segment((0, 1), (0, 3)))
    assert isinstance(boxes, OrientedBoxes) and len(boxes) == 2


def test_exchange_keeps_strokes_valid_when_a_reference_element_has_zero_thickness():
    strokes = hatching(12)  # straight double strokes: thin but non-zero boxes
    strokes += [segment((12.0, -1.0), (12.0, 1.0))]  # one perfectly straight hatch: skeleton thickness 0
    analysis = analyze(strokes, 0.4, dimension=1)
    assert (analysis.boxes.half_lengths[:, 1] == 0).any()
    result = synthesize(analysis, [(0, 0), (20, 0)], rings=1, rng=0)
    for seed in range(5):
        varied = exchange_parameters(result, analysis, 1.0, rng=seed)
        assert all(s.width > 0 for s in varied.strokes)


def test_plot_strokes_leaves_the_hole_of_a_closed_stroke_empty():
    """A loop dilates to a ring: its inside stays paper-white, the ring itself is inked (the drops, petals)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from paperlib.strokepattern import plot_strokes

    angles = np.linspace(0.0, 2.0 * np.pi, 65)
    loop = Stroke(np.column_stack([np.cos(angles), np.sin(angles)]), 0.2, "#000000")
    fig = plt.figure(figsize=(2, 2), dpi=50)
    ax = fig.add_axes((0, 0, 1, 1))
    plot_strokes([loop], ax, autoscale=False)
    ax.set_xlim(-1.5, 1.5)
    ax.set_ylim(-1.5, 1.5)
    ax.set_axis_off()
    fig.canvas.draw()
    pixels = np.asarray(fig.canvas.buffer_rgba())[..., :3]
    plt.close(fig)
    centre, on_ring = pixels[50, 50], pixels[50, int(round(50 + 50 * 1.0 / 1.5))]
    assert centre.min() == 255
    assert on_ring.max() < 64


def test_graph_helpers_validate_and_ring_growth_stops():
    # rings beyond the graph's diameter add nothing: the growth stops instead of looping 10**9 times
    pointers, neighbours = ring_neighbourhoods(4, [[0, 1], [1, 2], [2, 3]], 10**9)
    assert list(np.diff(pointers)) == [3, 3, 3, 3]
    with pytest.raises(ValueError, match="outside"):
        ring_neighbourhoods(3, [[0, 5]], 1)
    with pytest.raises(ValueError, match="edges"):
        shift_vectors(np.zeros((3, 2)), [[0.5, 1.0]])
    with pytest.raises(ValueError, match="order"):
        chain_edges([0.0, np.nan])
    with pytest.raises(ValueError, match="start"):
        growth_order(np.zeros((3, 2)), [[0, 1]], 7)
    with pytest.raises(ValueError, match="means"):
        rule_score([1.0, 2.0], Thresholds().vector(1.0))
    with pytest.raises(ValueError, match="sigmas"):
        rule_score(np.ones(5), [1, 1, 1, 1, 0])
