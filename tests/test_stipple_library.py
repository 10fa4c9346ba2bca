"""learn_stipple_library: the chain of Kim 2009's Figure 2, from example textures to renderings."""

import numpy as np
import pytest

from paperlib.datasets import stipple_tone_texture
from paperlib.stipple import (
    StippleLibrary,
    extract_distribution,
    extract_marks,
    learn_stipple_library,
    synthesize_distribution,
    tone_gray_levels,
)
from paperlib.stipple.tone_map import ToneMap

TONES = (0.08, 0.45, 0.85)  # one light, one merged, one dark level


@pytest.fixture(scope="module")
def examples():
    return [stipple_tone_texture(tone, 64, rng=index) for index, tone in enumerate(TONES)]


@pytest.fixture(scope="module")
def library(examples):
    return learn_stipple_library(examples, size=48, iterations=5, rng=3)


def test_library_holds_one_of_each_step_per_tone(library, examples):
    assert isinstance(library, StippleLibrary) and len(library) == len(TONES)
    assert library.levels == ["light", "merged", "dark"]
    light_s_avg = extract_distribution(examples[0]).s_avg
    assert library.distributions[1].s_avg == light_s_avg  # merged blobs split into light-tone stipples
    for example, distribution, tile, marks in zip(examples, library.distributions, library.tiles, library.marks):
        s_avg = light_s_avg if distribution.level == "merged" else None
        np.testing.assert_array_equal(distribution.distribution, extract_distribution(example, s_avg=s_avg).distribution)
        assert tile.shape == (48, 48) and tile.any() and marks
    light_marks = extract_marks(examples[0], "light")  # merged stipples are drawn with the light tone's marks
    assert len(library.marks[1]) == len(light_marks)
    assert all(np.array_equal(a.mask, b.mask) and a.offset == b.offset for a, b in zip(library.marks[1], light_marks))
    # lighter tones render lighter: the pre-simulated grays decrease with the ink tone
    assert np.all(np.diff(library.tone_grays) < 0)


def test_library_steps_agree_with_the_functions_they_chain(library):
    """The tiles and grays are what the step functions give (seeds spawned as documented)."""
    from paperlib.parallel import spawn_seeds

    synthesis_seed, gray_seed = spawn_seeds(3, 2)
    tone_seeds = spawn_seeds(synthesis_seed, len(TONES))
    for distribution, tile, seed in zip(library.distributions, library.tiles, tone_seeds):
        again = synthesize_distribution(distribution.distribution, size=48, iterations=5, rng=np.random.default_rng(seed))
        np.testing.assert_array_equal(tile, again.texture)
    grays = tone_gray_levels(library.tiles, library.marks, rng=np.random.default_rng(gray_seed))
    np.testing.assert_array_equal(library.tone_grays, grays)


def test_same_seed_same_library_in_one_or_two_processes(examples, library):
    parallel = learn_stipple_library(examples, size=48, iterations=5, rng=3, workers=2)
    for a, b in zip(library.tiles, parallel.tiles):
        np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(library.tone_grays, parallel.tone_grays)


def test_accepts_a_tone_map_and_defaults_to_the_shortest_side(examples):
    tone_map = ToneMap(np.array([0.9, 0.2]), [examples[0][:40], examples[2]], np.zeros((2, 4), int),
                       np.arange(2), np.zeros((1, 1), int), np.zeros((1, 1)), 32)
    learnt = learn_stipple_library(tone_map, iterations=1, rng=0)
    assert [tile.shape for tile in learnt.tiles] == [(40, 40), (40, 40)]


def test_render_uses_the_library_and_is_reproducible(library):
    ramp = np.tile(np.linspace(0.05, 0.95, 96), (64, 1))
    first, second = library.render(ramp, rng=7), library.render(ramp, rng=7)
    np.testing.assert_array_equal(first.image, second.image)
    np.testing.assert_array_equal(first.tone_grays, library.tone_grays)
    # the dark end of the ramp holds more ink than the light end
    assert first.image[:, :24].mean() > first.image[:, -24:].mean() + 0.3


def test_render_frames_the_tones_with_pure_white_and_black(library):
    """Section 3.2: tone 0 is pure white, the darkest tone pure black; the library's tones lie between."""
    np.testing.assert_array_equal(library.level_grays, np.concatenate([[1.0], library.tone_grays, [0.0]]))
    white, black = library.render(np.ones((48, 48)), rng=1), library.render(np.zeros((48, 48)), rng=1)
    assert not white.image.any() and black.image.all()
    old_white = library.render(np.ones((48, 48)), pure_levels=False, rng=1)
    assert old_white.image.mean() > 0.03  # clamped to the lightest tone (gray 0.92 here)
    assert np.all(old_white.tone_index == 0) and np.all(white.tone_index == 0)  # tone 1 then, pure white now


@pytest.mark.parametrize(
    "arguments, message",
    [
        (dict(tone_textures=[]), "at least two tone textures"),
        (dict(tone_textures=["one"]), "at least two tone textures"),
        (dict(size=1), "size must be an integer >= 2"),
        (dict(size=2.5), "size must be an integer >= 2"),
        (dict(levels=["light"]), "one level per tone texture"),
        (dict(iterations=0), "iterations"),
    ],
)
def test_bad_input(examples, arguments, message):
    call = dict(tone_textures=examples[:2], size=32, iterations=1, rng=0)
    call.update(arguments)
    with pytest.raises(ValueError, match=message):
        learn_stipple_library(call.pop("tone_textures"), **call)


def test_non_bitonal_or_empty_textures_are_rejected(examples):
    gray = examples[0].astype(float) * 0.5
    with pytest.raises(ValueError, match="bitonal|to_bitonal"):
        learn_stipple_library([gray, examples[1]], size=32, iterations=1)
    with pytest.raises(ValueError, match="empty|white|ink"):
        learn_stipple_library([np.zeros((64, 64), bool), examples[1]], size=32, iterations=1)


def test_a_tone_map_without_a_light_level_still_reaches_white_and_black(examples):
    """Merged and dark tones only (no light level, no separate black dots): the pure levels still
    frame them, so white stays paper and black is solid ink (section 3.2)."""
    learnt = learn_stipple_library(examples[1:], size=48, iterations=3, rng=0)
    assert learnt.levels == ["merged", "dark"]
    ramp = np.tile(np.linspace(0.0, 1.0, 200), (50, 1))
    rendered = learnt.render(ramp, rng=0).image
    assert rendered[:, :5].mean() > 0.95 and rendered[:, -5:].mean() < 0.05  # 1 - g: 0.99 and 0.01


def test_progress_bar_reports_tones_and_changes_nothing(examples, library, capsys):
    """The tqdm bar over the tones (issue 22): shown on request, never changes the library."""
    shown = learn_stipple_library(examples, size=48, iterations=5, rng=3, progress=True)
    err = capsys.readouterr().err
    assert "stipple tones" in err and "3/3" in err
    for a, b in zip(library.tiles, shown.tiles):
        np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(library.tone_grays, shown.tone_grays)
    learn_stipple_library(examples[:2], size=32, iterations=1, rng=0)  # default: stderr is no terminal here
    assert "stipple tones" not in capsys.readouterr().err
    with pytest.raises(TypeError, match="progress must be True, False or None"):
        learn_stipple_library(examples[:2], size=32, iterations=1, progress="yes")
