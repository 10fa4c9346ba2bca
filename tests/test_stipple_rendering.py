"""Tests of Kim 2009 section 4 rendering (paperlib.stipple.rendering)."""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest
from scipy.ndimage import gaussian_filter
from skimage.measure import label
from skimage.morphology import remove_small_holes, remove_small_objects

from paperlib.stipple import rendering
from paperlib.datasets.stipple import stipple_tone_texture
from paperlib.stipple.extraction import Mark, extract_distribution, extract_marks
from paperlib.stipple.rendering import (
    PURE_BLACK,
    PURE_WHITE,
    distribution_image,
    level_grays,
    place_marks,
    remove_small_chunks,
    render_stippling,
    render_tone,
    select_tones,
    tone_gray_levels,
)

TONES = (0.05, 0.15, 0.3, 0.5, 0.7, 0.85)


@pytest.fixture(scope="module")
def tone_set():
    """Distribution tiles and mark libraries of six synthetic tones (light, merged and dark)."""
    tiles, libraries = [], []
    for seed, tone in enumerate(TONES):
        texture = stipple_tone_texture(tone, 128, rng=seed)
        tiles.append(extract_distribution(texture).distribution)
        libraries.append(extract_marks(texture))
    return tiles, libraries


@pytest.fixture(scope="module")
def grays(tone_set):
    return tone_gray_levels(*tone_set, rng=0)


DOT = Mark(mask=np.ones((3, 3), dtype=bool), offset=(1, 1), white=False)
HOLE = Mark(mask=np.ones((3, 3), dtype=bool), offset=(1, 1), white=True)


# ---------------------------------------------------------------- step 1: pre-simulation


def test_tone_grays_match_example_paper_fraction(tone_set, grays):
    # Rendering a tone's own distribution with its own marks rebuilds (almost) the example.
    assert np.all(np.abs(grays - (1 - np.array(TONES))) < 0.03)
    assert np.all(np.diff(grays) < 0)


def test_tone_gray_known_answer_periodic():
    # One centre per 8 x 8 cell, 3 x 3 square marks: 9/64 ink, also for a centre on the border.
    tile = np.zeros((16, 16), dtype=bool)
    tile[::8, ::8] = True
    white_tile = np.zeros((16, 16), dtype=bool)
    grays = tone_gray_levels([tile, white_tile], [[DOT], [HOLE]], rng=0)
    np.testing.assert_allclose(grays, [1 - 9 / 64, 0.0])


def test_render_tone_white_marks_cut_paper():
    tile = np.zeros((8, 8), dtype=bool)
    tile[4, 4] = True
    out = render_tone(tile, [HOLE], rng=0)
    assert out.sum() == 64 - 9 and not out[3:6, 3:6].any()


# ---------------------------------------------------------------- step 2: tone selection


def test_selection_halfway_picks_each_about_half():
    grays = np.array([0.2, 0.8, 0.5])
    picked = select_tones(np.full((200, 200), 0.35), grays, rng=3, pure_levels=False)
    assert set(np.unique(picked)) == {0, 2}
    share = np.mean(picked == 2)
    assert abs(share - 0.5) < 4 * 0.5 / 200  # four standard errors of 40000 draws


def test_selection_probability_is_linear():
    picked = select_tones(np.full((200, 200), 0.65), [0.5, 0.8], rng=4, pure_levels=False)
    assert abs(np.mean(picked == 1) - 0.5) < 0.01
    picked = select_tones(np.full((200, 200), 0.56), [0.5, 0.8], rng=4, pure_levels=False)
    assert abs(np.mean(picked == 1) - 0.2) < 0.01
    # with the pure levels the same tones are levels 1 and 2: the same draws, shifted by one
    shifted = select_tones(np.full((200, 200), 0.56), [0.5, 0.8], rng=4)
    np.testing.assert_array_equal(shifted, picked + 1)


def test_selection_exact_gray_and_outside_range_without_pure_levels():
    grays = [0.9, 0.1, 0.5]
    for tone, gray in enumerate(grays):
        assert np.all(select_tones(np.full((50, 50), gray), grays, rng=1, pure_levels=False) == tone)
    assert np.all(select_tones(np.full((5, 5), 1.0), grays, rng=1, pure_levels=False) == 0)
    assert np.all(select_tones(np.zeros((5, 5)), grays, rng=1, pure_levels=False) == 1)


# ---------------------------------------------------------------- pure white and black (3.2)


def test_level_grays_frame_the_tones_with_pure_white_and_black():
    np.testing.assert_array_equal(level_grays([0.9, 0.1, 0.5]), [PURE_WHITE, 0.9, 0.1, 0.5, PURE_BLACK])
    assert (PURE_WHITE, PURE_BLACK) == (1.0, 0.0)
    np.testing.assert_array_equal(level_grays([0.9, 0.1], pure_levels=False), [0.9, 0.1])
    # 8 stipple tones give the paper's 10 levels, tone 0 white .. tone 9 black (Figure 3)
    assert level_grays(np.linspace(0.9, 0.1, 8)).size == 10


def test_selection_with_pure_levels_covers_every_gray():
    grays = [0.9, 0.1, 0.5]  # levels: 0 white, 1..3 these tones, 4 black
    for tone, gray in enumerate(grays):
        assert np.all(select_tones(np.full((50, 50), gray), grays, rng=1) == tone + 1)
    assert np.all(select_tones(np.full((50, 50), 1.0), grays, rng=1) == 0)
    assert np.all(select_tones(np.zeros((50, 50)), grays, rng=1) == 4)
    # between the lightest tone (0.9) and white: p_r of white = (0.96 - 0.9) / 0.1 = 0.6
    picked = select_tones(np.full((200, 200), 0.96), grays, rng=2)
    assert set(np.unique(picked)) == {0, 1}
    assert abs(np.mean(picked == 0) - 0.6) < 4 * np.sqrt(0.24 / picked.size)
    # between black and the darkest tone (0.1): p of black = 1 - 0.03 / 0.1 = 0.7
    picked = select_tones(np.full((200, 200), 0.03), grays, rng=2)
    assert set(np.unique(picked)) == {2, 4}
    assert abs(np.mean(picked == 4) - 0.7) < 4 * np.sqrt(0.21 / picked.size)


def test_white_stays_paper_and_black_is_solid_ink(tone_set, grays):
    white = render_stippling(np.ones((96, 96)), *tone_set, tone_grays=grays, rng=3)
    black = render_stippling(np.zeros((96, 96)), *tone_set, tone_grays=grays, rng=3)
    assert not white.image.any() and not white.distribution.any() and np.all(white.tone_index == 0)
    assert black.image.all() and not black.distribution.any() and np.all(black.tone_index == len(grays) + 1)
    np.testing.assert_array_equal(white.level_grays, level_grays(grays))
    np.testing.assert_array_equal(white.tone_grays, grays)
    assert white.pure_levels
    # the old rendering, still reachable: white takes the lightest tone, black the darkest
    old_white = render_stippling(np.ones((96, 96)), *tone_set, tone_grays=grays, rng=3, pure_levels=False)
    old_black = render_stippling(np.zeros((96, 96)), *tone_set, tone_grays=grays, rng=3, pure_levels=False)
    assert abs(old_white.image.mean() - (1 - grays.max())) < 0.03
    assert abs(old_black.image.mean() - (1 - grays.min())) < 0.03
    assert not old_white.pure_levels and old_white.level_grays.size == len(grays)


def test_pure_levels_change_nothing_inside_the_tone_range(tone_set, grays):
    """Inside the tones' range no pixel selects a pure level: the same image bit for bit."""
    image = np.tile(np.linspace(grays.min(), grays.max(), 160), (96, 1))
    new = render_stippling(image, *tone_set, tone_grays=grays, rng=5)
    old = render_stippling(image, *tone_set, tone_grays=grays, rng=5, pure_levels=False)
    np.testing.assert_array_equal(new.image, old.image)
    np.testing.assert_array_equal(new.tone_index, old.tone_index + 1)


def test_mixtures_with_pure_levels_keep_the_expected_ink(tone_set, grays):
    """Between white and the lightest tone, and between the darkest tone and black, Figure 10's
    rule gives each pixel an expected ink of 1 - g; the marks' density scales with the tone's
    share there, so the rendered ink follows (measured error 0.0004 and 0.0013)."""
    for low, high in ((grays.max(), 1.0), (0.0, grays.min())):
        image = np.tile(np.linspace(low, high, 256), (256, 1))
        rendered = render_stippling(image, *tone_set, tone_grays=grays, rng=6).image
        old = render_stippling(image, *tone_set, tone_grays=grays, rng=6, pure_levels=False).image
        expected = 1.0 - image.mean()
        assert abs(rendered.mean() - expected) < 0.02
        # clamped to one tone, the old rendering is off by half the interval (0.026 and 0.079)
        assert abs(old.mean() - expected) > 0.4 * (high - low)


# ---------------------------------------------------------------- step 3: distribution image


def test_distribution_image_copies_rotated_tiles():
    rng = np.random.default_rng(0)
    tiles = [rng.random((8, 8)) < 0.3 for _ in range(2)]
    index = np.zeros((20, 28), dtype=int)
    index[:, 14:] = 1
    out = distribution_image(index, tiles, rng=5, pure_levels=False)
    rotations = [[np.rot90(tile, k) for k in range(4)] for tile in tiles]
    for tone, c0 in ((0, 0), (1, 16)):  # tone 1 occupies columns >= 14; its full cells start at 16
        block = out[0:8, c0 : c0 + 8]
        assert any(np.array_equal(block, rotation) for rotation in rotations[tone])
    assert out.sum() > 0


def test_distribution_image_uses_several_rotations():
    tile = np.zeros((8, 8), dtype=bool)
    tile[0, 1] = True  # asymmetric: its four rotations differ
    out = distribution_image(np.zeros((80, 80), dtype=int), [tile, tile], rng=2, pure_levels=False)
    blocks = {out[r : r + 8, c : c + 8].tobytes() for r in range(0, 80, 8) for c in range(0, 80, 8)}
    assert len(blocks) == 4


# ---------------------------------------------------------------- step 4: mark placement


def test_place_marks_pure_levels_place_no_marks():
    centres = np.ones((12, 12), dtype=bool)  # centres everywhere, even on the pure levels
    index = np.zeros((12, 12), dtype=int)    # left third pure white, middle a dark tone, right pure black
    index[:, 4:8] = 2
    index[:, 8:] = 3
    out = place_marks(centres, index, [[DOT], [HOLE]], rng=0)
    assert not out[:, :3].any()   # paper: no black mark centred on pure white (marks spill 1 px)
    assert out[:, 9:].all()       # solid ink: no white mark centred on pure black


def test_place_marks_black_then_white():
    centres = np.zeros((10, 10), dtype=bool)
    centres[5, 3] = centres[5, 5] = True
    index = np.zeros((10, 10), dtype=int)
    index[:, 5:] = 1  # right half dark: starts as ink, white marks
    out = place_marks(centres, index, [[DOT], [HOLE]], rng=0, pure_levels=False)
    assert out[4:7, 2:4].all()  # black mark at (5, 3) ...
    assert not out[4:7, 4:7].any()  # ... partly cut by the later white mark at (5, 5)
    assert out[:, 7:].all() and not out[:, :2].any()


def test_place_marks_draws_from_library():
    small = Mark(mask=np.ones((1, 1), dtype=bool), offset=(0, 0), white=False)
    centres = np.zeros((60, 60), dtype=bool)
    centres[5::10, 5::10] = True
    out = place_marks(centres, np.zeros((60, 60), dtype=int), [[DOT, small], [HOLE]], rng=1, pure_levels=False)
    areas = np.bincount(label(out, connectivity=2).ravel())[1:]
    assert set(areas) == {1, 9}


# ---------------------------------------------------------------- step 5: chunk removal


def test_chunk_removal_known_answer():
    image = np.zeros((20, 20), dtype=bool)
    image[1, 1] = True  # ink chunk of 1
    image[1, 4:6] = True  # ink chunk of 2
    image[1, 8:11] = True  # ink chunk of 3 (kept)
    image[10:20, 10:20] = True
    image[14, 14] = False  # paper chunk of 1
    image[16, 12:15] = False  # paper chunk of 3 (kept)
    result = remove_small_chunks(image, 3)
    assert (result.removed_ink, result.removed_paper) == (3, 1)
    expected = image.copy()
    expected[1, 1] = expected[1, 4:6] = False
    expected[14, 14] = True
    np.testing.assert_array_equal(result.image, expected)


def test_chunk_removal_matches_label_oracle():
    image = np.random.default_rng(7).random((64, 64)) < 0.45
    result = remove_small_chunks(image, 4)
    labels = label(image, connectivity=2)
    areas = np.bincount(labels.ravel())
    small_ink = (labels > 0) & (areas[labels] < 4)
    no_specks = image & ~small_ink
    holes = label(~no_specks, connectivity=2)
    hole_areas = np.bincount(holes.ravel())
    small_paper = (holes > 0) & (hole_areas[holes] < 4)
    np.testing.assert_array_equal(result.image, no_specks | small_paper)
    assert result.removed_ink == small_ink.sum() and result.removed_paper == small_paper.sum()
    assert result.removed_ink > 0 and result.removed_paper > 0
    assert np.array_equal(remove_small_chunks(image, 1).image, image)


def whole_image_chunk_removal(image, min_size, connectivity):
    """Step 5 on the whole image at once, as the rendering did before it worked in bands."""
    no_specks = remove_small_objects(image, connectivity=connectivity, max_size=min_size - 1)
    cleaned = remove_small_holes(no_specks, connectivity=connectivity, max_size=min_size - 1)
    return cleaned, int(np.count_nonzero(image & ~no_specks)), int(np.count_nonzero(cleaned & ~no_specks))


@pytest.mark.parametrize("connectivity", [1, 2])
@pytest.mark.parametrize("min_size", [2, 3, 6, 13])
def test_chunk_removal_in_bands_equals_the_whole_image(monkeypatch, min_size, connectivity):
    """Bands of 3 rows with halos (chunks taller than a band, crossing several) give the whole-image result."""
    rng = np.random.default_rng(min_size)
    image = rng.random((61, 37)) < 0.45
    image[20:40, 5] = True  # a thin ink line crossing many bands
    image[10:30, 20] = False  # and a paper one
    expected, ink, paper = whole_image_chunk_removal(image, min_size, connectivity)
    monkeypatch.setattr(rendering, "CHUNK_BAND_PIXELS", 3 * image.shape[1])
    result = remove_small_chunks(image, min_size, connectivity=connectivity)
    np.testing.assert_array_equal(result.image, expected)
    assert (result.removed_ink, result.removed_paper) == (ink, paper)
    assert ink > 0 and paper > 0


# ---------------------------------------------------------------- whole rendering


def straightforward_rendering(image, tiles, libraries, grays, min_chunk, rng):
    """Steps 2-5 with the public functions and whole-image arrays (int64 level map, no bands)."""
    rng = np.random.default_rng(rng)
    tone_index = select_tones(image, grays, rng)
    distribution = distribution_image(tone_index, tiles, rng)
    stippled = place_marks(distribution, tone_index, libraries, rng)
    cleaned, ink, paper = whole_image_chunk_removal(stippled, min_chunk, 2)
    return tone_index, distribution, cleaned, ink, paper


def test_rendering_equals_the_straightforward_steps(monkeypatch, tone_set, grays):
    """Bit for bit, with the level map in int8 and the chunk removal in bands of 5 rows."""
    image = np.clip(np.add.outer(np.linspace(-0.1, 0.6, 150), np.linspace(0.0, 0.5, 170)), 0, 1)
    expected = straightforward_rendering(image, *tone_set, grays, 4, 5)
    monkeypatch.setattr(rendering, "CHUNK_BAND_PIXELS", 5 * image.shape[1])
    result = render_stippling(image, *tone_set, tone_grays=grays, min_chunk=4, rng=5)
    assert result.tone_index.dtype == np.int8
    np.testing.assert_array_equal(result.tone_index, expected[0])
    np.testing.assert_array_equal(result.distribution, expected[1])
    np.testing.assert_array_equal(result.image, expected[2])
    assert (result.removed_ink, result.removed_paper) == expected[3:]
    assert expected[3] > 0 and expected[4] > 0


def test_distribution_image_reads_any_integer_level_map(tone_set):
    tiles, _ = tone_set
    index = np.random.default_rng(3).integers(0, len(tiles) + 2, size=(300, 200))
    wide = distribution_image(index, tiles, rng=4)
    np.testing.assert_array_equal(distribution_image(index.astype(np.int8), tiles, rng=4), wide)
    for dtype in (np.uint8, np.uint16, np.int32, np.uint64):
        np.testing.assert_array_equal(distribution_image(index.astype(dtype), tiles, rng=4), wide)
    assert not wide[(index == 0) | (index == len(tiles) + 1)].any()


def test_rendering_peak_memory_is_a_few_bytes_per_pixel(monkeypatch, tone_set, grays):
    """tracemalloc peak of a 1024 x 1024 rendering with 64 Ki-pixel bands: <= 7 bytes per pixel.

    The result holds three one-byte images (stipples, level map, distribution); the canvas of
    the marks is a fourth until the chunk removal has copied it. Before the bands and the int8
    level map it was 25 bytes per pixel (int64 level map, whole-image labels).
    """
    image = np.tile(np.linspace(0.0, 1.0, 1024), (1024, 1))
    monkeypatch.setattr(rendering, "SELECTION_BAND_PIXELS", 1 << 16)
    monkeypatch.setattr(rendering, "CHUNK_BAND_PIXELS", 1 << 16)
    tracemalloc.start()
    try:
        before, _ = tracemalloc.get_traced_memory()
        tracemalloc.reset_peak()
        result = render_stippling(image, *tone_set, tone_grays=grays, min_chunk=3, rng=1)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert result.image.any()
    assert (peak - before) / image.size <= 7.0


def test_blurred_rendering_tracks_gradient(tone_set, grays):
    gradient = np.tile(np.linspace(grays.min(), grays.max(), 512), (256, 1))
    result = render_stippling(gradient, *tone_set, tone_grays=grays, rng=1)
    blurred = gaussian_filter(1.0 - result.image.astype(float), sigma=8)  # sigma 8 px
    inner = slice(24, -24)  # away from the image border where the blur sees padding
    error = np.abs(blurred[inner, inner].mean(axis=0) - gradient[inner, inner].mean(axis=0))
    # Measured 0.037 / 0.077: mixing two levels pixel by pixel lets their marks overlap, so middle
    # tones come out up to ~0.07 lighter (the paper's Figure 11 limitation); the ends track closely.
    assert error.mean() < 0.05 and error.max() < 0.1


def test_rendering_is_deterministic(tone_set):
    image = np.tile(np.linspace(0.2, 0.9, 96), (64, 1))
    first = render_stippling(image, *tone_set, min_chunk=3, rng=11)
    second = render_stippling(image, *tone_set, min_chunk=3, rng=11)
    other = render_stippling(image, *tone_set, min_chunk=3, rng=12)
    np.testing.assert_array_equal(first.image, second.image)
    np.testing.assert_array_equal(first.tone_index, second.tone_index)
    assert not np.array_equal(first.image, other.image)
    assert first.image.dtype == np.bool_ and first.image.shape == image.shape


# ---------------------------------------------------------------- bad input


def test_bad_input(tone_set):
    tiles, libraries = tone_set
    image = np.full((16, 16), 0.5)
    with pytest.raises(ValueError, match="floating point"):
        render_stippling((image * 255).astype(np.uint8), tiles, libraries)
    with pytest.raises(ValueError, match="within"):
        select_tones(image + 1, [0.2, 0.8])
    with pytest.raises(ValueError, match="at least two"):
        render_stippling(image, tiles[:1], libraries[:1])
    with pytest.raises(ValueError, match="at least two"):
        select_tones(image, [0.5])
    with pytest.raises(ValueError, match="distinct"):
        select_tones(image, [0.5, 0.5])
    with pytest.raises(ValueError):
        render_stippling(image, [tiles[0] * 2, tiles[1]], libraries[:2])
    with pytest.raises(ValueError, match="square"):
        tone_gray_levels([tiles[0], tiles[1][:64]], libraries[:2])
    with pytest.raises(ValueError, match="mixes"):
        tone_gray_levels(tiles[:2], [[DOT, HOLE], [DOT]])
    with pytest.raises(ValueError, match="empty"):
        tone_gray_levels(tiles[:2], [[], [DOT]])
    with pytest.raises(ValueError, match="tone_index"):
        distribution_image(np.full((4, 4), 8), tiles)  # 6 tones + white (0) + black (7)
    with pytest.raises(ValueError, match="tone_index"):
        distribution_image(np.full((4, 4), 6), tiles, pure_levels=False)
    with pytest.raises(ValueError, match="pure white or black"):
        select_tones(image, [1.0, 0.5])
    with pytest.raises(ValueError, match="pure white or black"):
        render_stippling(image, tiles[:2], libraries[:2], tone_grays=[0.5, 0.0])
    with pytest.raises(ValueError, match="pure_levels"):
        render_stippling(image, tiles, libraries, pure_levels="yes")
    # a tone whose texture holds no stipple at all is pure white, not a stipple tone
    with pytest.raises(ValueError, match="pure white or black"):
        render_stippling(image, [np.zeros_like(tiles[0]), tiles[1]], libraries[:2])
    with pytest.raises(ValueError, match="one shape"):
        place_marks(np.zeros((4, 4), dtype=bool), np.zeros((5, 5), dtype=int), [[DOT], [HOLE]])
    with pytest.raises(ValueError, match="min_size"):
        remove_small_chunks(np.zeros((4, 4), dtype=bool), 0)
