"""paperlib.widgets: the Hurtut 2009 explorer, driven headless through its controls.

Every test sets controls with ``.value =`` or clicks buttons, exactly as a browser would, and
checks that the explorer's outputs (synthesis, figure, status text) change as they should.
Small exemplars and T = 3000 keep the file fast.
"""

import warnings

import ipywidgets
import numpy as np
import pytest

from paperlib.datasets import hershey_glyph, regularity_exemplar
from paperlib.geometry import write_svg
from paperlib.pointprocess import Window
from paperlib.widgets import DENSITY_KINDS, EXEMPLARS, arrangement_explorer, density_image, scaled_window

T = 3000
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture
def explorer():
    return arrangement_explorer("regularity", T=T)


def relative_x(explorer):
    """Mean x of the synthesized positions, as a fraction of the synthesis window's width."""
    window = explorer.arrangement.window
    return float(np.mean((explorer.arrangement.pattern.points[:, 0] - window.xrange[0]) / window.width))


# ---------------------------------------------------------------------------- building


def test_builds_a_panel_with_a_synthesis_and_a_png_figure(explorer):
    assert isinstance(explorer.widget, ipywidgets.VBox)
    assert explorer.error is None and explorer.message == ""
    assert len(explorer.arrangement) > 0
    assert bytes(explorer.image.value).startswith(PNG_MAGIC)
    assert f"synthesis: {len(explorer.arrangement)} elements" in explorer.summary
    assert "fitted: beta" in explorer.summary and "wall time" in explorer.summary
    assert explorer.calls == {"categorize": 1, "fit": 1, "synthesize": 1}
    assert explorer.exemplar.options[-1][1] == "svg" and set(EXEMPLARS) < {v for _, v in explorer.exemplar.options}


def test_bad_construction_arguments_raise():
    with pytest.raises(ValueError, match="exemplar"):
        arrangement_explorer("no_such_exemplar")
    with pytest.raises(ValueError, match="T must be"):
        arrangement_explorer("regularity", T=10)
    with pytest.raises(ValueError, match="window_scale"):
        arrangement_explorer("regularity", window_scale=5.0)
    with pytest.raises(ValueError, match="density"):
        arrangement_explorer("regularity", density="stripes")


# ---------------------------------------------------------------------------- synthesis controls


def test_window_scale_changes_the_number_of_elements_without_refitting(explorer):
    n1, figure1 = len(explorer.arrangement), bytes(explorer.image.value)
    explorer.window_scale.value = 2.0
    n2 = len(explorer.arrangement)
    assert explorer.arrangement.window.area == pytest.approx(4 * explorer.drawing.window.area)
    assert 2.5 * n1 < n2 < 6 * n1  # about 4 times the elements in 4 times the area
    assert bytes(explorer.image.value) != figure1
    assert explorer.calls == {"categorize": 1, "fit": 1, "synthesize": 2}  # cached categorization and fit


def test_T_changes_the_synthesis_without_refitting(explorer):
    points = explorer.arrangement.pattern.points
    explorer.T.value = 5000
    assert not np.array_equal(points, explorer.arrangement.pattern.points)
    assert "T = 5,000" in explorer.figure.axes[1].get_title()
    assert explorer.calls["fit"] == 1 and explorer.calls["synthesize"] == 2


def test_density_choice_changes_where_elements_fall(explorer):
    explorer.window_scale.value = 2.0
    uniform = relative_x(explorer)
    explorer.density.value = "gradient"
    assert explorer.density_array is not None
    assert relative_x(explorer) > uniform + 0.08  # the left-right ramp pushes elements right
    explorer.density.value = "radial"
    window = explorer.arrangement.window
    centre = np.array([np.mean(window.xrange), np.mean(window.yrange)])
    radial = np.linalg.norm(explorer.arrangement.pattern.points - centre, axis=1) / window.width
    # density 0 outside the inscribed circle (radius 0.5 width); uniform: max ~0.7, mean ~0.38
    assert radial.max() < 0.52 and radial.mean() < 0.31
    explorer.density.value = "image"
    assert explorer.error is None and explorer.density_array.shape[0] > 1
    assert explorer.calls["fit"] == 1


def test_same_seed_same_synthesis_different_seed_different(explorer):
    first = explorer.arrangement.pattern.points.copy()
    explorer.seed.value = 1
    assert not np.array_equal(first, explorer.arrangement.pattern.points)
    explorer.seed.value = 0
    np.testing.assert_array_equal(first, explorer.arrangement.pattern.points)
    explorer.resynthesize_button.click()  # next seed
    assert explorer.seed.value == 1 and not np.array_equal(first, explorer.arrangement.pattern.points)


# ---------------------------------------------------------------------------- categories


def test_categorize_toggle_changes_labels_and_caches_both_fits(explorer):
    assert explorer.arrangement.categories == ("all",)  # categorize's name of an undivided drawing
    explorer.labels.value = "truth"
    assert explorer.arrangement.categories == explorer.drawing.truth_categories == ("o",)
    assert "(truth)" in explorer.summary
    explorer.labels.value = "categorize"
    assert explorer.arrangement.categories == ("all",)
    assert explorer.calls["fit"] == 2 and explorer.calls["categorize"] == 1


def test_exemplar_dropdown_and_seed_load_a_new_drawing(explorer):
    elements = explorer.drawing.elements
    explorer.exemplar_seed.value = 1
    assert explorer.drawing.elements is not elements and explorer.calls["fit"] == 2
    explorer.exemplar.value = "near_identical"
    assert explorer.drawing.name == "near_identical" and explorer.error is None
    assert len(explorer.drawing.truth_categories) == 2 and "ARI vs ground truth" in explorer.summary


# ---------------------------------------------------------------------------- SVG and errors


def test_invalid_svg_path_is_a_message_not_an_exception(explorer, tmp_path):
    drawing = explorer.drawing
    explorer.svg_path.value = str(tmp_path / "missing.svg")
    explorer.load_button.click()
    assert isinstance(explorer.error, FileNotFoundError) and "no SVG file" in explorer.message
    assert "no SVG file" in explorer.status.value
    assert explorer.drawing is drawing and explorer.exemplar.value == "regularity"
    (tmp_path / "bad.svg").write_text("<svg><path d='M 0 0 L'")
    assert explorer.load_svg(tmp_path / "bad.svg") is False and "malformed SVG" in explorer.message
    explorer.exemplar.value = "svg"  # with the bad path still in the box
    assert explorer.drawing is drawing and explorer.exemplar.value == "regularity"


def test_load_svg_round_trip_categorizes_the_drawing(explorer, tmp_path):
    n = len(explorer.arrangement)
    path = explorer.arrangement.to_svg(tmp_path / "synthesis.svg")
    explorer.labels.value = "truth"
    assert explorer.load_svg(path)
    assert explorer.exemplar.value == "svg" and explorer.drawing.name == "synthesis.svg"
    assert len(explorer.drawing.elements) == n and explorer.drawing.truth is None
    assert explorer.labels.value == "categorize" and "no ground-truth labels" in explorer.message
    assert explorer.categorization.n_categories == 1 and len(explorer.arrangement) > 0
    frame = explorer.drawing.window
    bounds = np.array([e.bounds() for e in explorer.drawing.elements])
    assert frame.xrange == (bounds[:, 0].min(), bounds[:, 2].max())
    explorer.labels.value = "truth"
    assert explorer.arrangement is None and "no ground-truth labels" in explorer.message


def test_too_few_elements_in_a_category_is_a_message_until_dropped(tmp_path):
    exemplar = regularity_exemplar(rng=0)
    big = hershey_glyph("x").transformed(0.02 * np.eye(2), (0.5, 0.5))  # one element far larger than the rest
    path = write_svg([*exemplar.elements, big], tmp_path / "odd.svg")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        explorer = arrangement_explorer("regularity", T=T, svg=path)
    assert explorer.arrangement is None and isinstance(explorer.error, ValueError)
    assert "at least 3" in explorer.message and "no synthesis" in explorer.figure.axes[1].texts[0].get_text()
    explorer.drop_small.value = True
    assert explorer.error is None and len(explorer.arrangement) > 0
    assert len(explorer.arrangement.categories) == explorer.categorization.n_categories - 1


# ---------------------------------------------------------------------------- plain helpers


def test_density_images_have_the_window_aspect_and_their_shape():
    window = Window.rectangle((0.0, 2.0), (0.0, 1.0))
    assert density_image("uniform", window) is None
    gradient = density_image("gradient", window, resolution=40)
    assert gradient.shape == (20, 40) and np.all(np.diff(gradient, axis=1) > 0) and gradient[:, 0].max() == 0
    radial = density_image("radial", window, resolution=41)
    assert radial[10, 20] == radial.max() and radial[0, 0] == 0 and radial[-1, -1] == 0
    image = density_image("image", window, resolution=32)
    assert image.shape == (16, 32) and 0 <= image.min() < image.max() <= 1
    assert set(DENSITY_KINDS) == {"uniform", "gradient", "radial", "image"}
    with pytest.raises(ValueError, match="density kind"):
        density_image("stripes", window)
    with pytest.raises(ValueError, match="resolution"):
        density_image("gradient", window, resolution=1)


def test_scaled_window_keeps_the_corner_and_scales_the_sides():
    window = scaled_window(Window.rectangle((1.0, 3.0), (2.0, 3.0)), 1.5)
    assert window.xrange == (1.0, 4.0) and window.yrange == (2.0, 3.5)
    with pytest.raises(ValueError, match="scale"):
        scaled_window(window, 0)
    with pytest.raises(TypeError):
        scaled_window((0, 1), 2.0)


def test_interaction_choice_refits_on_box_distances_and_caches():
    explorer = arrangement_explorer("drawn_hatching", T=T, labels="truth")
    assert explorer.model.interaction == "centre"
    explorer.interaction.value = "box_gap"
    assert explorer.error is None, explorer.message
    assert explorer.model.interaction == "box_gap" and explorer.calls["fit"] == 2
    explorer.interaction.value = "centre"
    assert explorer.calls["fit"] == 2  # the centre fit was cached
    with pytest.raises(ValueError, match="interaction"):
        arrangement_explorer("regularity", T=T, interaction="euclid")
