"""paperlib.widgets.strokepattern: the Barla 2006 explorer, driven headless through its controls and canvas.

Every test sets controls with ``.value =``, clicks buttons, or feeds mouse events to the canvas the way the
browser sends them (``Canvas._handle_frontend_event``), and checks that the explorer's outputs (analysis,
synthesis, PNG, status text) change as they should. Small figures at 40 dpi keep each explorer under half a
second; the 1D sketchy hatching (64 strokes, 24 elements) and the 2D irregular marks (100 one-stroke
elements) are the quickest exemplars of each kind.
"""

import ipywidgets
import numpy as np
import pytest
import shapely

from paperlib.datasets.strokepatterns import irregular_exemplar, sketchy_hatching_exemplar
from paperlib.strokepattern import analyze, target_count
from paperlib.widgets.strokepattern import (
    EXEMPLARS,
    PRESETS,
    TARGET_FACTOR,
    StrokePatternExplorer,
    drawn_target,
    preset_target,
    stroke_hash,
    strokepattern_explorer,
)

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
SMALL = dict(figsize=(6, 2.5), dpi=40)


@pytest.fixture
def explorer():
    return strokepattern_explorer("sketchy_hatching", **SMALL)


@pytest.fixture
def explorer_2d():
    return strokepattern_explorer("irregular", **SMALL)


def feed(explorer, event, x, y):
    """A mouse event as the browser sends it to the canvas widget."""
    explorer.canvas._handle_frontend_event(None, {"event": event, "x": float(x), "y": float(y)}, None)


def draw(explorer, pixels):
    """Press at the first point, drag through the others, release at the last."""
    feed(explorer, "mouse_down", *pixels[0])
    for point in pixels[1:-1]:
        feed(explorer, "mouse_move", *point)
    feed(explorer, "mouse_up", *pixels[-1])


def test_builds_a_panel_with_the_analysis_at_the_generator_epsilon_and_a_synthesis(explorer):
    truth = sketchy_hatching_exemplar(rng=0)
    assert isinstance(explorer, StrokePatternExplorer) and isinstance(explorer.widget, ipywidgets.VBox)
    assert explorer.error is None and explorer.message == ""
    assert explorer.epsilon.value == pytest.approx(truth.epsilon)
    assert explorer.n_elements == truth.n_elements == 24  # the generator's truth at its epsilon
    np.testing.assert_array_equal(explorer.analysis.element_of_stroke, truth.element_of_stroke)
    assert tuple(value for _, value in explorer.preset.options) == PRESETS[1] and explorer.preset.value == "line"
    line = preset_target("line", TARGET_FACTOR * 24.0)
    assert len(explorer.synthesis) == target_count(explorer.analysis, line) == 72  # 3 x 24 elements
    assert bytes(explorer.image.value).startswith(PNG_MAGIC)
    assert "24 elements (= the truth)" in explorer.summary and "synthesis (preset straight line): 72" in explorer.summary
    assert explorer.calls == {"exemplar": 1, "analyze": 1, "synthesize": 1}


def test_bad_construction_arguments_raise():
    for kwargs, match in (({"exemplar": "bricks"}, "unknown exemplar"), ({"rings": 0}, "rings"),
                          ({"rings": 6}, "rings"), ({"amount": 1.5}, "amount"), ({"epsilon": 0.0}, "epsilon"),
                          ({"choice": "worst"}, "choice"), ({"seed": -1}, "seed"),
                          ({"target": "disc"}, "not a 1D preset"), ({"canvas_size": (10, 10)}, "canvas_size")):
        with pytest.raises(ValueError, match=match):
            strokepattern_explorer(**kwargs)


def test_epsilon_reruns_only_the_analysis_and_changes_count_and_image(explorer):
    png, synthesis = bytes(explorer.image.value), explorer.synthesis
    explorer.epsilon.value = 10 ** explorer.epsilon.min  # 0.2 / 10 ** 1.5: no two strokes group
    assert explorer.error is None and 24 < explorer.n_elements <= len(explorer.pattern.strokes)
    assert bytes(explorer.image.value) != png and f"{explorer.n_elements} elements" in explorer.summary
    assert explorer.synthesis is synthesis and explorer.calls["synthesize"] == 1  # the synthesis stays
    assert "press synthesize" in explorer.summary
    explorer.epsilon.value = 0.2  # back: from the cache
    assert explorer.n_elements == 24 and explorer.calls["analyze"] == 2 and explorer.times["analysis"] == 0.0
    explorer.contour.value = True  # boxes on the pen's contour are wider than on the skeleton
    assert explorer.analysis.contour and explorer.calls["analyze"] == 3 and explorer.calls["synthesize"] == 1


def test_huge_epsilon_and_synthesizing_without_analysis_are_messages(explorer):
    explorer.epsilon.value = 10 ** explorer.epsilon.max  # everything clusters into one element
    assert explorer.analysis is None and isinstance(explorer.error, ValueError)
    assert "analysis failed" in explorer.message and "lower epsilon" in explorer.message
    assert "#b00020" in explorer.status.value and bytes(explorer.image.value).startswith(PNG_MAGIC)
    explorer.synthesize_button.click()
    assert explorer.synthesis is None and "no analysis at epsilon" in explorer.message
    explorer.epsilon.value = 0.2
    explorer.synthesize_button.click()
    assert explorer.error is None and len(explorer.synthesis) == 72


def test_synthesis_controls_change_the_result(explorer):
    base_hash, base = explorer.stroke_hash, explorer.synthesis
    explorer.rings.value = 5  # a larger seed patch and other near-best matches: other strokes
    assert explorer.synthesis.rings == 5 and explorer.stroke_hash != base_hash
    explorer.rings.value = 2
    assert explorer.stroke_hash == base_hash
    explorer.amount.value = 0.5  # parameter exchange: new shapes, same seeds and sources
    exchanged = explorer.synthesis
    assert explorer.stroke_hash != base_hash and "exchange" in explorer.times
    np.testing.assert_array_equal(exchanged.positions, base.positions)
    np.testing.assert_array_equal(exchanged.source, base.source)
    explorer.amount.value = 0.0
    explorer.vary.value = True  # position variation: elements move, sources stay
    assert not np.array_equal(explorer.synthesis.positions, base.positions) and "positions" in explorer.times
    np.testing.assert_array_equal(explorer.synthesis.source, base.source)
    explorer.vary.value = False
    explorer.choice.value = "best"
    assert explorer.stroke_hash != base_hash
    explorer.choice.value = "random"
    assert explorer.stroke_hash != base_hash
    explorer.choice.value = "close"
    explorer.seed.value = 1
    assert explorer.stroke_hash != base_hash
    for preset in PRESETS[1]:
        explorer.preset.value = preset
        assert explorer.error is None and len(explorer.synthesis) == 72  # every preset has the line's length


def test_rings_change_the_matching_on_a_length_gradient():
    # Fig. 6 d with the paper's uniform choice: the ring size decides how many neighbourhoods match
    explorer = strokepattern_explorer("gradient_length", choice="random", **SMALL)
    hashes, candidates = [], []
    for rings in (1, 3, 5):
        explorer.rings.value = rings
        assert explorer.error is None and explorer.synthesis.rings == rings
        hashes.append(explorer.stroke_hash)
        candidates.append(explorer.synthesis.n_candidates.mean())
    assert len(set(hashes)) == 3
    assert candidates[0] > candidates[2]  # larger neighbourhoods match fewer reference elements
    explorer.rings.value = 1
    assert explorer.stroke_hash == hashes[0]  # the same seed again


def test_same_seed_gives_the_same_strokes(explorer):
    again = strokepattern_explorer("sketchy_hatching", amount=0.0, **SMALL)
    assert explorer.stroke_hash == again.stroke_hash == stroke_hash(again.synthesis.strokes)
    for control in (explorer, again):
        control.amount.value = 0.3
        control.vary.value = True
    assert explorer.stroke_hash == again.stroke_hash


def test_drawing_a_path_synthesizes_along_it(explorer):
    pixels = [(30 + 12 * k, 200 - 5 * k) for k in range(30)]
    draw(explorer, pixels)
    assert explorer.target_mode.value == "draw" and explorer.target_label == "drawn path"
    assert explorer.error is None and explorer.drawn_points == [tuple(map(float, p)) for p in pixels]
    path = explorer.canvas_to_pattern(pixels)
    np.testing.assert_allclose(path[0], (30 * explorer.canvas_scale, 40 * explorer.canvas_scale))  # y flipped
    line = shapely.LineString(path)
    synthesis = explorer.synthesis
    assert len(synthesis) == round(24 * line.length / explorer.analysis.area)  # N_tar = N_ref A_tar / A_ref
    assert shapely.distance(line, shapely.points(synthesis.positions)).max() < 1e-9  # seeds on the path
    ink = np.vstack([stroke.points for stroke in synthesis.strokes])
    assert shapely.distance(line, shapely.points(ink)).max() < 2.0  # hatches of length 3 across it
    explorer.clear_button.click()
    assert explorer.drawn_points == [] and "cleared" in explorer.message
    explorer.synthesize_button.click()
    assert explorer.synthesis is None and "nothing drawn yet" in explorer.message
    explorer.preset.value = "arc"  # picking a preset leaves the drawing
    assert explorer.target_mode.value == "preset" and explorer.error is None and explorer.target_label == "preset arc"


def test_mouse_events_outside_a_stroke_are_ignored_and_leaving_the_canvas_ends_it(explorer):
    hash_before = explorer.stroke_hash
    feed(explorer, "mouse_move", 10, 10)  # hovering, button up
    feed(explorer, "mouse_up", 20, 20)
    assert explorer.drawn_points == [] and explorer.target_mode.value == "preset"
    assert explorer.stroke_hash == hash_before and explorer.calls["synthesize"] == 1
    feed(explorer, "mouse_down", 20, 120)
    feed(explorer, "mouse_move", 200, 110)
    feed(explorer, "mouse_out", 419, 100)  # released outside: the stroke ends at the border
    assert explorer.target_mode.value == "draw" and explorer.drawn_points[-1] == (419.0, 100.0)
    assert explorer.error is None and explorer.target_label == "drawn path"
    feed(explorer, "mouse_move", 300, 300)  # after the end: not part of the drawing
    assert len(explorer.drawn_points) == 3


def test_draw_methods_fill_notebook_axes(explorer):
    from matplotlib.figure import Figure

    left, right = Figure().subplots(1, 2)
    explorer.draw_reference(left)
    explorer.draw_synthesis(right)
    assert len(left.collections) == 3 and "24 elements" in left.get_title()  # strokes, boxes, graph
    assert len(right.collections) == 1 and "72 elements" in right.get_title()


def test_a_one_point_path_is_a_message(explorer):
    draw(explorer, [(50, 50), (50, 50)])
    assert explorer.synthesis is None and isinstance(explorer.error, ValueError)
    assert "single point" in explorer.message and "#b00020" in explorer.status.value


def test_2d_regions_drawn_degenerate_or_crossed(explorer_2d):
    explorer = explorer_2d
    assert explorer.pattern.dimension == 2 and explorer.n_elements == irregular_exemplar(rng=0).n_elements == 100
    assert tuple(value for _, value in explorer.preset.options) == PRESETS[2] and explorer.preset.value == "square"
    draw(explorer, [(20, 40), (60, 80), (100, 120), (140, 160)])  # collinear: zero area
    assert explorer.synthesis is None and "zero area" in explorer.message
    draw(explorer, [(20, 20), (22, 20), (21, 22)])  # a sliver too small for three seeds
    assert explorer.synthesis is None and "at least 3 seeds" in explorer.message
    draw(explorer, [(100, 40), (220, 200), (220, 40), (100, 200)])  # a bow tie, closed back to its start
    assert explorer.error is None and "crosses itself" in explorer.message
    assert isinstance(explorer.target, shapely.MultiPolygon) and len(explorer.target.geoms) == 2
    region = explorer.target.buffer(1e-9)
    assert shapely.contains_xy(region, *explorer.synthesis.positions.T).all()


def test_changing_the_exemplar_follows_its_dimension(explorer):
    explorer.preset.value = "arc"
    draw(explorer, [(30, 200), (200, 100), (380, 200)])  # a path: no region for a 2D pattern
    explorer.exemplar.value = "irregular"
    truth = irregular_exemplar(rng=0)
    assert explorer.pattern.dimension == 2 and explorer.preset.value == "square"
    assert explorer.target_mode.value == "preset" and explorer.target_label == "preset square"
    assert explorer.epsilon.value == pytest.approx(truth.epsilon) and explorer.n_elements == 100
    assert explorer.epsilon.min == pytest.approx(np.log10(truth.epsilon) - 1.5)
    assert explorer.target.area == pytest.approx(TARGET_FACTOR * truth.region.area)
    explorer.exemplar_seed.value = 3
    assert explorer.pattern is not None and explorer.n_elements == irregular_exemplar(rng=3).n_elements
    assert set(EXEMPLARS) >= {"sketchy_hatching", "bars", "flowers", "two_hatchings", "gradient_length"}


def test_preset_targets_have_the_asked_extent():
    for name in PRESETS[1]:
        path = preset_target(name, 50.0)
        assert shapely.LineString(path).length == pytest.approx(50.0)
    np.testing.assert_allclose(preset_target("line", 50.0), [(0, 0), (50, 0)])
    radii = np.hypot(*preset_target("arc", 50.0).T)  # a half circle: 64 chords of total length 50
    np.testing.assert_allclose(radii, radii[0])
    np.testing.assert_allclose(radii[0], 50.0 / np.pi, rtol=1e-3)
    for name in PRESETS[2]:
        region = preset_target(name, 30.0)
        assert region.is_valid and region.area == pytest.approx(30.0)
        assert np.allclose(region.centroid.coords[0], (0.0, 0.0), atol=1e-9)
    for name, extent, match in (("spiral", 1.0, "unknown preset"), ("line", 0.0, "extent"),
                                ("disc", float("nan"), "extent")):
        with pytest.raises(ValueError, match=match):
            preset_target(name, extent)


def test_drawn_target_checks_its_points():
    np.testing.assert_array_equal(drawn_target([(0, 0), (0, 0), (1, 0)], 1), [(0, 0), (1, 0)])
    square = drawn_target([(0, 0), (2, 0), (2, 2), (0, 2)], 2)
    assert square.area == pytest.approx(4.0)
    for points, dimension, match in (([], 1, "nothing drawn"), ([(1, 1), (1, 1)], 1, "single point"),
                                     ([(0, 0), (1, 1)], 2, "at least 3"), ([(0, 0), (1, 1), (2, 2)], 2, "zero area"),
                                     ([(0, 0), (np.nan, 1)], 1, "finite"), ([(0, 0), (1, 0)], 3, "dimension")):
        with pytest.raises(ValueError, match=match):
            drawn_target(points, dimension)


def test_stroke_hash_follows_the_strokes():
    pattern = sketchy_hatching_exemplar(rng=0)
    assert stroke_hash(pattern.strokes) == stroke_hash(sketchy_hatching_exemplar(rng=0).strokes)
    assert stroke_hash(pattern.strokes) != stroke_hash(sketchy_hatching_exemplar(rng=1).strokes)
    analysis = analyze(pattern.strokes, pattern.epsilon, dimension=1, path=pattern.path)
    assert len(analysis) == pattern.n_elements
