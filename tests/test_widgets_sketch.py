"""paperlib.widgets.sketch: the Simhon 2001 explorer, driven headless through its controls and canvas.

Every test sets controls with ``.value =``, clicks buttons, or feeds mouse events to the canvas the way the
browser sends them (``Canvas._handle_frontend_event``), and checks what the explorer shows (elaboration, PNG,
status, message). Training on the 40 coastlines takes about a second, so one explorer is built per module and
every test starts from its default controls (the ``explorer`` fixture resets them; its model cache makes that
an elaboration only). 300 samples and 40-dpi figures keep each elaboration and redraw near 0.2 s.

ipywidgets swallows exceptions raised by event callbacks (it logs them as warnings), so tests that feed events
also check the log: a handler that raised would otherwise pass unnoticed.
"""

import logging

import ipywidgets
import numpy as np
import pytest
from matplotlib.figure import Figure

from paperlib.datasets import coastlines, leaf_outlines
from paperlib.geometry import hausdorff, signed_area
from paperlib.sketch import coarsen
from paperlib.sketch import elaborate as run_elaboration
from paperlib.widgets.sketch import (
    DEFAULT_PRESET,
    PRESETS,
    SketchExplorer,
    drawn_sketch,
    points_hash,
    sketch_explorer,
)

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
SAMPLES = 300
SMALL = dict(n_samples=SAMPLES, figsize=(6, 2.5), dpi=40)
DEFAULTS = dict(training="coastlines", order=20, scales=5, sigma=0.1, top=20, mode="max", closure="turn",
                use_window=False, window=0.1, samples=SAMPLES, seed=0, source="preset", preset="coastline_41")
#: Hausdorff distance between a drawing and its elaboration, over the drawing's perimeter. Measured on the
#: ellipse below with the 40 coastlines (order 20, 5 scales): 0.043 at the most probable states, 0.021-0.047 over
#: 8 seeds of mode "sample" (and at most 0.056 with 1,000 samples); the presets at 300 samples give 0.033-0.045
#: for the held-out coastlines, up to 0.080 for the wobbliest blob. On the ellipse the bound is 58 px of its
#: 730 px perimeter, 0.29 of its height: the sketch moved up by half its height fails it.
NEAR = 0.08


def ellipse_pixels(points=60):
    """A three-lobed ellipse in canvas pixels (y down), clockwise once y points up, at whole pixels."""
    t = np.linspace(0.0, 2.0 * np.pi, points, endpoint=False)
    return np.round(np.column_stack([210 + 130 * np.cos(t) + 20 * np.cos(3 * t), 160 + 100 * np.sin(t)]))


def figure_eight_pixels(points=60):
    t = np.linspace(0.0, 2.0 * np.pi, points, endpoint=False)
    return np.column_stack([210 + 150 * np.sin(t), 160 + 80 * np.sin(t) * np.cos(t)])


@pytest.fixture(scope="module")
def built():
    """The module's explorer, with what it showed right after construction."""
    explorer = sketch_explorer(**SMALL)
    return explorer, {"calls": dict(explorer.calls), "summary": explorer.summary, "png": bytes(explorer.image.value),
                      "hash": explorer.points_hash}


@pytest.fixture
def explorer(built):
    """The module's explorer back at its default controls, with no drawing."""
    explorer = built[0]
    with explorer._quiet():
        for name, value in DEFAULTS.items():
            getattr(explorer, name).value = value
    explorer.clear_drawing()
    explorer.load_training()
    assert explorer.error is None
    return explorer


@pytest.fixture
def no_callback_errors(caplog):
    """Fail if an event callback raised (ipywidgets logs it instead of raising)."""
    caplog.set_level(logging.WARNING)
    yield
    assert "Exception in callback" not in caplog.text


def feed(explorer, event, x, y):
    """A mouse event as the browser sends it to the canvas widget."""
    explorer.canvas._handle_frontend_event(None, {"event": event, "x": float(x), "y": float(y)}, None)


def draw(explorer, pixels):
    """Press at the first point, drag through the others, release at the last."""
    feed(explorer, "mouse_down", *pixels[0])
    for point in pixels[1:-1]:
        feed(explorer, "mouse_move", *point)
    feed(explorer, "mouse_up", *pixels[-1])


# ---------------------------------------------------------------------------- building


def test_builds_a_panel_with_an_elaboration_of_the_default_preset(built):
    explorer, first = built
    assert isinstance(explorer, SketchExplorer) and isinstance(explorer.widget, ipywidgets.VBox)
    assert first["calls"] == {"train": 1, "elaborate": 1}
    assert first["png"].startswith(PNG_MAGIC)
    assert "40 curves, 10240 states, order 20, scales 5: trained in" in first["summary"]
    assert "held-out coastline 41, coarse, 256 points" in first["summary"]
    model = explorer._models[("coastlines", 20, 5)]
    assert len(model) == 40 * 256 and (model.order, model.scales) == (20, 5)
    held_out = coastlines(54)[41]  # the preset's curve is not a training curve
    assert not any(len(curve) == len(held_out) and np.array_equal(curve, held_out) for curve in coastlines(40))
    np.testing.assert_array_equal(explorer.sketch, coarsen(held_out, model))
    assert first["hash"] == points_hash(run_elaboration(model, explorer.sketch, n_samples=SAMPLES).points)


def test_default_state_and_status(explorer):
    assert explorer.preset.value == DEFAULT_PRESET["coastlines"] and explorer.source.value == "preset"
    assert explorer.n_samples == SAMPLES and explorer.restarts == 0 and explorer.message == ""
    assert 0 < explorer.hausdorff_ratio < NEAR
    assert 1 <= explorer.longest_copy < SAMPLES
    assert "cached model" in explorer.summary and f"{SAMPLES} samples, 0 restarts" in explorer.summary
    assert bytes(explorer.image.value).startswith(PNG_MAGIC)
    assert {"train", "sketch", "elaborate", "draw", "total"} <= set(explorer.times)


def test_bad_construction_arguments_raise():
    for kwargs, match in (({"training": "rivers"}, "unknown training class"), ({"order": 0}, "order"),
                          ({"order": 41}, "order"), ({"order": True}, "order"), ({"scales": 8}, "scales"),
                          ({"sigma": 0.0}, "sigma"), ({"sigma": float("nan")}, "sigma"), ({"sigma": 10.0}, "sigma"),
                          ({"top": 0}, "top"), ({"mode": "mean"}, "mode"), ({"closure": "snap"}, "closure"),
                          ({"window": 0.7}, "window"), ({"seed": -1}, "seed"), ({"seed": 1.5}, "seed"),
                          ({"n_samples": 10}, "n_samples"), ({"n_samples": 6000}, "n_samples"),
                          ({"preset": "spiral"}, "unknown preset"), ({"canvas_size": (10, 10)}, "canvas_size"),
                          ({"canvas_size": 5}, "canvas_size"), ({"figsize": (6, -1)}, "figsize"),
                          ({"dpi": 0}, "dpi")):
        with pytest.raises(ValueError, match=match):
            sketch_explorer(**kwargs)


# ---------------------------------------------------------------------------- what re-runs


def test_elaboration_controls_rerun_only_the_elaboration(explorer):
    base, trained = explorer.points_hash, explorer.calls["train"]
    runs = explorer.calls["elaborate"]
    explorer.seed.value = 7  # the seed only drives mode "sample": the most probable states do not change
    assert explorer.points_hash == base
    hashes = [base]
    for control, value in ((explorer.sigma, 0.3), (explorer.top, 5), (explorer.mode, "sample"),
                           (explorer.use_window, True), (explorer.closure, "none")):
        control.value = value  # each one changes the elaboration
        assert explorer.error is None and explorer.times["train"] == 0.0
        hashes.append(explorer.points_hash)
    assert len(set(hashes)) == len(hashes)
    assert "sample, sigma 0.3, top 5, seed 7, closure none, window 0.1" in explorer.summary
    explorer.samples.value = 500
    assert explorer.n_samples == 500 and "500 samples" in explorer.summary
    assert explorer.calls["train"] == trained and explorer.calls["elaborate"] == runs + 7


def test_closure_closes_the_gap_without_changing_the_chain(explorer):
    gap, states = explorer.elaboration.closing_gap, explorer.elaboration.states
    assert "closure turn" in explorer.summary
    for closure in ("distribute", "none"):
        explorer.closure.value = closure
        assert explorer.elaboration.closing_gap == gap > 0  # measured before the correction
        np.testing.assert_array_equal(explorer.elaboration.states, states)
        assert f"closure {closure}" in explorer.summary


def test_order_and_scales_retrain_and_models_are_cached(explorer):
    base, trained = explorer.points_hash, explorer.calls["train"]
    explorer.order.value = 12
    assert explorer.model.order == 12 and explorer.calls["train"] == trained + 1
    assert "order 12, scales 5: trained in" in explorer.summary and explorer.times["train"] > 0
    assert explorer.error is None and explorer.points_hash != base
    explorer.scales.value = 3
    assert explorer.model.scales == 3 and explorer.calls["train"] == trained + 2
    explorer.scales.value = 5
    explorer.order.value = 20  # back to the first model: from the cache, the same elaboration
    assert explorer.calls["train"] == trained + 2 and "cached model" in explorer.summary
    assert explorer.model is explorer._models[("coastlines", 20, 5)] and explorer.points_hash == base


def test_same_seed_same_elaboration_and_sample_mode_seeds_differ(explorer):
    explorer.mode.value = "sample"
    explorer.seed.value = 1
    first = explorer.points_hash
    explorer.seed.value = 2
    assert explorer.points_hash != first
    explorer.seed.value = 1
    assert explorer.points_hash == first
    direct = run_elaboration(explorer.model, explorer.sketch, **explorer.elaboration_options())
    assert points_hash(direct.points) == first
    assert explorer.elaboration_options()["rng"] == 1 and explorer.elaboration_options()["mode"] == "sample"


def test_every_preset_elaborates_near_its_sketch(explorer):
    for name in PRESETS:
        explorer.preset.value = name
        assert explorer.error is None and explorer.sketch_label == f"preset: {PRESETS[name]}"
        assert explorer.restarts == 0 and 0 < explorer.hausdorff_ratio < 0.1  # measured: at most 0.080
    explorer.source.value = "drawing"  # nothing drawn: a message, not an exception
    assert explorer.elaboration is None and "nothing drawn yet" in explorer.message
    explorer.preset.value = "blob_1"  # picking a preset leaves the drawing
    assert explorer.source.value == "preset" and explorer.error is None


# ---------------------------------------------------------------------------- drawing


def test_drawing_a_closed_loop_elaborates_it(explorer, no_callback_errors):
    pixels = ellipse_pixels()
    draw(explorer, pixels)
    assert explorer.source.value == "drawing" and explorer.sketch_label == "drawing"
    assert explorer.drawn_points == [tuple(map(float, p)) for p in pixels]
    assert explorer.error is None and "drawn clockwise: reversed" in explorer.message
    scale = explorer.canvas_scale
    assert scale == pytest.approx(np.median([np.hypot(*np.ptp(c, axis=0)) for c in coastlines(40)]) / 320)
    units = explorer.canvas_to_sketch(pixels)
    np.testing.assert_allclose(units[0], (pixels[0, 0] * scale, (320 - pixels[0, 1]) * scale))  # y flipped
    np.testing.assert_array_equal(explorer.sketch[0], units[0])  # reversed about its start
    np.testing.assert_array_equal(explorer.sketch[1:], units[:0:-1])
    assert signed_area(explorer.sketch) > 0
    assert explorer.restarts == 0 and 0 < explorer.hausdorff_ratio < NEAR
    sketch = explorer.elaboration.sketch  # the bound can fail: not for the sketch moved by half its height
    moved = sketch + [0.0, 0.5 * np.ptp(sketch[:, 1])]
    perimeter = np.hypot(*np.diff(np.vstack([sketch, sketch[:1]]), axis=0).T).sum()
    assert hausdorff(moved, explorer.elaboration.points) / perimeter > NEAR
    drawn_hash = explorer.points_hash
    draw(explorer, np.vstack([pixels[:1], pixels[:0:-1]]))  # the same loop drawn the other way round
    assert explorer.message == "" and explorer.points_hash == drawn_hash


def test_bad_drawings_are_messages_not_exceptions(explorer, no_callback_errors):
    draw(explorer, figure_eight_pixels())
    assert explorer.elaboration is None and isinstance(explorer.error, ValueError)
    assert "crosses itself" in explorer.message and "#b00020" in explorer.status.value
    assert bytes(explorer.image.value).startswith(PNG_MAGIC)
    left = Figure().subplots()
    explorer.draw_sketch(left)  # the refused drawing is shown
    assert "refused" in left.get_title() and len(left.lines) == 1
    draw(explorer, [(50, 50), (52, 50)])  # a click with a twitch
    assert explorer.elaboration is None and "too short (2 distinct points)" in explorer.message
    draw(explorer, [(50, 50), (50, 50)])
    assert "too short (1 distinct point)" in explorer.message
    draw(explorer, [(20, 40), (60, 80), (100, 120), (140, 160)])  # a straight drag
    assert "encloses no area" in explorer.message
    explorer.clear_button.click()
    assert explorer.drawn_points == [] and "cleared" in explorer.message
    explorer.elaborate_button.click()
    assert explorer.elaboration is None and "nothing drawn yet" in explorer.message
    explorer.preset.value = "coastline_42"
    assert explorer.error is None and explorer.elaboration is not None


def test_a_quick_flick_is_resampled_to_the_order(explorer, no_callback_errors):
    t = np.linspace(0.0, 2.0 * np.pi, 8, endpoint=False)
    draw(explorer, np.column_stack([200 + 80 * np.cos(t), 160 - 80 * np.sin(t)]))  # counter-clockwise, y up
    assert explorer.error is None and len(explorer.sketch) == explorer.model.order == 20
    assert "only 8 points drawn: resampled at 20" in explorer.message and "clockwise" not in explorer.message


def test_mouse_events_outside_a_stroke_are_ignored_and_leaving_the_canvas_ends_it(explorer, no_callback_errors):
    runs, base = explorer.calls["elaborate"], explorer.points_hash
    feed(explorer, "mouse_move", 10, 10)  # hovering, button up
    feed(explorer, "mouse_up", 20, 20)
    assert explorer.drawn_points == [] and explorer.source.value == "preset"
    assert explorer.calls["elaborate"] == runs and explorer.points_hash == base
    pixels = ellipse_pixels(40)
    feed(explorer, "mouse_down", *pixels[0])
    for point in pixels[1:-1]:
        feed(explorer, "mouse_move", *point)
    feed(explorer, "mouse_out", *pixels[-1])  # released outside: the stroke ends there
    assert explorer.source.value == "drawing" and explorer.error is None and len(explorer.drawn_points) == 40
    feed(explorer, "mouse_move", 300, 300)  # after the end: not part of the drawing
    assert len(explorer.drawn_points) == 40


# ---------------------------------------------------------------------------- classes and output


def test_switching_to_leaves_trains_them_and_swaps_the_preset(explorer):
    trained = explorer.calls["train"]
    explorer.training.value = "leaves"
    assert explorer.error is None and explorer.preset.value == DEFAULT_PRESET["leaves"] == "leaf"
    assert len(explorer.model.curves) == 14 and len(explorer.model) == 14 * 256
    assert "leaves (14, SYNTHETIC)" in explorer.summary and explorer.calls["train"] == trained + 1
    assert explorer.restarts == 0 and explorer.hausdorff_ratio < NEAR  # measured 0.024
    explorer.use_window.value = True  # the search window suits the leaves' large-scale structure
    assert explorer.error is None and "window 0.1" in explorer.summary
    leaf_size = np.median([np.hypot(*np.ptp(leaf, axis=0)) for leaf in leaf_outlines(14, rng=0)])
    assert explorer.canvas_scale == pytest.approx(leaf_size / 320)  # the canvas is a typical leaf high
    explorer.preset.value = "blob_0"
    explorer.training.value = "coastlines"  # back: the cached model; a blob stays a blob
    assert explorer.calls["train"] == trained + 1 and explorer.preset.value == "blob_0"
    assert explorer.error is None and "cached model" in explorer.summary


def test_draw_methods_fill_notebook_axes(explorer):
    left, right = Figure().subplots(1, 2)
    explorer.draw_sketch(left)
    explorer.draw_elaboration(right)
    assert len(left.lines) == 2 and "held-out coastline 41" in left.get_title()  # the ring and its start
    assert len(right.lines) == 2 and "Hausdorff / perimeter" in right.get_title()  # sketch and elaboration
    elaboration = right.lines[1].get_xydata()
    np.testing.assert_array_equal(elaboration[:-1], explorer.elaboration.points)
    explorer.source.value = "drawing"  # nothing drawn: no elaboration
    empty_left, empty_right = Figure().subplots(1, 2)
    explorer.draw_sketch(empty_left)
    explorer.draw_elaboration(empty_right)
    assert not empty_left.lines and not empty_right.lines and len(empty_right.texts) == 1


# ---------------------------------------------------------------------------- plain functions


def test_drawn_sketch_cleans_orients_and_checks():
    square = [(0, 0), (0, 0), (2, 0), (2, 2), (2, 2), (0, 2), (0, 0)]  # repeats and a closing point
    ring, notes = drawn_sketch(square)
    np.testing.assert_array_equal(ring, [(0, 0), (2, 0), (2, 2), (0, 2)])
    assert notes == []
    clockwise, notes = drawn_sketch([(0, 0), (0, 2), (2, 2), (2, 0)])
    np.testing.assert_array_equal(clockwise, [(0, 0), (2, 0), (2, 2), (0, 2)])
    assert notes == ["drawn clockwise: reversed to run counter-clockwise like the training curves"]
    dense, notes = drawn_sketch(ring, min_points=12)
    assert len(dense) == 12 and signed_area(dense) == pytest.approx(4.0) and "resampled at 12" in notes[0]
    for points, match in (([], "nothing drawn"), ([(0, 0), (np.nan, 1), (1, 1)], "finite"),
                          ([(1, 1), (1, 1), (2, 2)], "too short"), ([(0, 0), (1, 1), (2, 2)], "no area"),
                          ([(0, 0), (1, 0), (0.5, 1e-12)], "no area"),
                          ([(0, 0), (2, 2), (2, 0), (0, 2)], "crosses itself")):
        with pytest.raises(ValueError, match=match):
            drawn_sketch(points)
    with pytest.raises(ValueError, match="min_points"):
        drawn_sketch(ring, min_points=2)


def test_points_hash_follows_the_points():
    points = np.arange(10.0).reshape(5, 2)
    assert points_hash(points) == points_hash(points.copy()) == points_hash(points.astype(np.float32))
    nudged = points.copy()
    nudged[2, 1] = np.nextafter(nudged[2, 1], np.inf)
    assert points_hash(nudged) != points_hash(points)
