"""paperlib.widgets.stipple: the Kim 2009 explorer, driven headless through its controls.

Every test sets controls with ``.value =`` or clicks buttons, as a browser would, and checks
that the explorer's outputs (library, rendering, PNG, status text) change as they should. A
small sheet (4 tones of 128 px), 32 px tiles, 5 iterations and 128 px renderings keep the file
fast (about 2 s per explorer).
"""

import ipywidgets
import numpy as np
import pytest

from paperlib.widgets.stipple import IMAGES, gray_ramp, render_input, stipple_explorer, tone_error

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
SMALL = dict(n_tones=4, block=128, tile=32, iterations=5, render_size=128)


@pytest.fixture
def explorer():
    return stipple_explorer(**SMALL)


def test_builds_a_panel_with_a_library_a_rendering_and_a_png(explorer):
    assert isinstance(explorer.widget, ipywidgets.VBox)
    assert explorer.error is None and explorer.message == "" and not explorer.stale
    assert len(explorer.library) == 4 and explorer.library.tiles[0].shape == (32, 32)
    assert explorer.rendering.image.shape == explorer.input_image.shape == (128, 128)
    assert bytes(explorer.image.value).startswith(PNG_MAGIC)
    assert "tones: 4" in explorer.summary and "levels:" in explorer.summary and "final ACE" in explorer.summary
    assert "SYNTHETIC" in explorer.summary and "seconds:" in explorer.summary
    assert 0 <= explorer.error_after_blur < 0.5
    assert explorer.calls == {"source": 1, "tone_map": 1, "learn": 1, "render": 1}


def test_bad_construction_arguments_raise():
    with pytest.raises(ValueError, match="tile"):
        stipple_explorer(tile=50, learn=False)
    with pytest.raises(ValueError, match="iterations"):
        stipple_explorer(iterations=0, learn=False)
    with pytest.raises(ValueError, match="T1"):
        stipple_explorer(T1=0.9, learn=False)
    with pytest.raises(ValueError, match="image"):
        stipple_explorer(image="lena", learn=False)
    with pytest.raises(ValueError, match="source"):
        stipple_explorer(source="andrews", learn=False)


def test_render_controls_rerender_at_once_without_relearning(explorer):
    png, stipples = bytes(explorer.image.value), explorer.rendering.image.copy()
    explorer.image_name.value = "ramp"
    assert explorer.input_image.shape == (64, 128) and bytes(explorer.image.value) != png
    ramp = explorer.rendering.image
    paper = 1.0 - ramp.mean(axis=0)
    assert np.mean(paper[-32:]) > np.mean(paper[:32]) + 0.4  # white on the right, black on the left
    # the pure white and black tones (Kim 2009, 3.2): paper at the white end, solid ink at the black end
    assert np.mean(paper[-3:]) > 0.9 and np.mean(paper[:3]) < 0.1
    explorer.render_size.value = 192
    assert explorer.rendering.image.shape == (96, 192)
    explorer.image_name.value = "camera"
    explorer.render_size.value = 128
    np.testing.assert_array_equal(explorer.rendering.image, stipples)  # same seed, same image
    explorer.min_chunk.value = 1
    assert explorer.rendering.removed_ink == explorer.rendering.removed_paper == 0
    explorer.min_chunk.value = 20
    assert explorer.rendering.removed_ink + explorer.rendering.removed_paper > 0
    assert explorer.calls["learn"] == 1 and explorer.calls["render"] == 7


def test_learn_controls_mark_stale_and_learn_uses_the_cache(explorer):
    library = explorer.library
    explorer.tile.value = 48
    assert explorer.stale and "press learn" in explorer.message and explorer.library is library
    explorer.render_button.click()  # renders with the previous library, and says so
    assert explorer.rendering is not None and "previous library" in explorer.message
    explorer.learn_button.click()
    assert not explorer.stale and explorer.library.tiles[0].shape == (48, 48)
    assert explorer.calls["learn"] == 2 and explorer.calls["source"] == 1
    explorer.tile.value = 32
    assert explorer.stale  # the library shown is the 48 px one
    explorer.tile.value = 48
    assert not explorer.stale and explorer.message == ""  # back to the parameters of the library shown
    explorer.tile.value = 32
    explorer.learn()
    assert explorer.library.tiles[0].shape == (32, 32) and "cache" in explorer.message
    assert explorer.calls["learn"] == 2 and explorer.calls["tone_map"] == 1


def test_same_seed_same_image_different_seed_different(explorer):
    first = explorer.rendering.image.copy()
    explorer.seed.value = 1
    explorer.learn()
    assert not np.array_equal(first, explorer.rendering.image)
    again = stipple_explorer(**SMALL)
    np.testing.assert_array_equal(first, again.rendering.image)
    for mine, theirs in zip(explorer._libraries[again.learn_key()].tiles, again.library.tiles):
        np.testing.assert_array_equal(mine, theirs)


def test_tone_map_parameters_change_the_tones_and_bad_values_are_messages(explorer):
    library = explorer.library
    explorer.N.value = 8  # blocks too small for a steady tone: no 64 px region
    assert explorer.learn() is False
    assert isinstance(explorer.error, ValueError) and "learn failed" in explorer.message
    assert "previous library is kept" in explorer.message and "learn failed" in explorer.status.value
    assert explorer.library is library and explorer.rendering is not None
    explorer.N.value = 32
    explorer.T2.value = 0.2  # tones must be spaced by at least the median spacing - T2: fewer survive? no error
    assert explorer.learn() or explorer.error is not None  # either way, nothing raised
    explorer.n_tones.value = 3
    explorer.T2.value = 0.03
    assert explorer.learn() and len(explorer.library) == 3


def test_single_texture_source_learns_one_tile_and_says_it_cannot_render(explorer):
    explorer.source.value = "texture"
    explorer.tone.value = 0.5
    assert explorer.learn() is False
    assert len(explorer.library) == 1 and explorer.library.levels == ["merged"]
    assert explorer.stipple_source.truth_grays[0] == pytest.approx(0.5)
    assert "at least two tones" in explorer.message and explorer.rendering is None
    assert "no rendering" in explorer.figure.axes[-1].texts[0].get_text()
    assert bytes(explorer.image.value).startswith(PNG_MAGIC)
    explorer.source.value = "sheet"
    assert explorer.learn() and len(explorer.library) == 4 and explorer.calls["source"] == 2


def test_render_without_library_is_a_message():
    explorer = stipple_explorer(**SMALL, learn=False)
    assert explorer.library is None and bytes(explorer.image.value).startswith(PNG_MAGIC)
    assert explorer.render() is False and "press learn" in explorer.message


def test_plain_helpers():
    ramp = gray_ramp(10)
    assert ramp.shape == (5, 10) and ramp[0, 0] == 0 and ramp[0, -1] == 1
    camera = render_input("camera", 100)
    assert camera.shape == (100, 100) and 0 <= camera.min() < camera.max() <= 1
    assert render_input("ramp", 64).shape == (32, 64) and "ramp" in IMAGES
    with pytest.raises(ValueError, match="image"):
        render_input("lena", 64)
    white, black = np.zeros((20, 20), bool), np.ones((20, 20), bool)
    assert tone_error(white, np.ones((20, 20))) == pytest.approx(0)
    assert tone_error(black, np.ones((20, 20))) == pytest.approx(1)
    checker = (np.indices((20, 20)).sum(axis=0) % 2).astype(bool)
    assert tone_error(checker, np.full((20, 20), 0.5)) < 0.02  # blurred, a checkerboard is mid gray
    with pytest.raises(ValueError, match="shape"):
        tone_error(white, np.ones((10, 10)))
