"""Tests of Kim 2009 section 3.1: tone-map extraction from a stipple drawing."""

import itertools

import numpy as np
import pytest

from paperlib.datasets.stipple import stipple_tone_sheet
from paperlib.stipple.tone_map import (
    ToneMap,
    block_gray_levels,
    extract_tone_map,
    largest_rectangle,
    segment_blocks,
)

# N = 32 divides the sheet's 256 px patches, so no block straddles two tones (the paper's own
# caveat: "the initial generation of blocks may split across two apparent tones").
BLOCK = 32


@pytest.fixture(scope="module", params=[0, 1])
def sheet(request):
    return stipple_tone_sheet(n_tones=8, block=256, rng=request.param)


@pytest.fixture(scope="module")
def tone_map(sheet):
    return extract_tone_map(sheet[0], block_size=BLOCK)


def test_recovers_the_tones(sheet, tone_map):
    _, truth = sheet
    assert isinstance(tone_map, ToneMap) and len(tone_map) == 8
    # A region may take in blocks of the dithered band (within T1 = 0.05 of its mean) and a
    # 32 x 32 block of ~12 px dots has a standard deviation of ~0.02 in ink: 0.045 < half the
    # 1/9 tone spacing, so each recovered tone is closest to its own true tone.
    assert np.abs(tone_map.tones - truth["tones"]).max() < 0.045
    assert np.all(np.diff(tone_map.tones) > 0)
    np.testing.assert_allclose(tone_map.gray_levels, 1 - tone_map.tones)
    # the textures themselves (crops of one tone's texture) carry their tone
    ink = np.array([texture.mean() for texture in tone_map.textures])
    assert np.abs(ink - truth["tones"]).max() < 0.045


def test_rectangles_lie_in_the_true_patches(sheet, tone_map):
    image, truth = sheet
    for (r0, c0, r1, c1), texture, (p0, q0, p1, q1) in zip(tone_map.rectangles, tone_map.textures,
                                                           truth["patches"]):
        assert p0 <= r0 < r1 <= p1 and q0 <= c0 < c1 <= q1
        assert r1 - r0 >= 64 and c1 - c0 >= 64  # the default min_size
        assert texture.shape == (r1 - r0, c1 - c0) and texture.dtype == bool
        assert np.array_equal(texture, image[r0:r1, c0:c1])
        assert r0 % BLOCK == 0 and c1 % BLOCK == 0  # whole blocks


def test_region_labels_cover_the_selected_rectangles(tone_map):
    labels = tone_map.block_labels
    assert labels.shape == tone_map.block_gray.shape == (8, 64) and labels.min() >= 1
    for region, (r0, c0, r1, c1) in zip(tone_map.region_ids, tone_map.rectangles):
        assert np.all(labels[r0 // BLOCK : r1 // BLOCK, c0 // BLOCK : c1 // BLOCK] == region)


def test_min_size_is_honoured(sheet):
    tone_map = extract_tone_map(sheet[0], block_size=BLOCK, min_size=150)
    for r0, c0, r1, c1 in tone_map.rectangles:
        assert r1 - r0 >= 150 and c1 - c0 >= 150


def test_deterministic(sheet, tone_map):
    again = extract_tone_map(sheet[0].copy(), block_size=BLOCK)
    assert np.array_equal(again.rectangles, tone_map.rectangles)
    assert np.array_equal(again.block_labels, tone_map.block_labels)


def test_input_types_agree(sheet, tone_map):
    image = sheet[0]
    gray8 = np.where(image, 0, 255).astype(np.uint8)
    grayf = (~image).astype(np.float32)
    for other in (gray8, grayf):
        result = extract_tone_map(other, block_size=BLOCK)
        np.testing.assert_allclose(result.gray_levels, tone_map.gray_levels)
        assert np.array_equal(result.rectangles, tone_map.rectangles)


def test_block_gray_levels_known_answer():
    image = np.zeros((5, 7), dtype=bool)
    image[:2, :2] = True  # the first 2 x 2 block all ink
    image[2, 3] = True  # one ink pixel in block (1, 1)
    gray = block_gray_levels(image, 2)
    assert gray.shape == (2, 3)  # the last row and column are not whole blocks
    np.testing.assert_allclose(gray, [[0, 1, 1], [1, 0.75, 1]])


def test_segment_blocks_two_tones_with_noise():
    rng = np.random.default_rng(0)
    gray = np.where(np.arange(12)[None, :] < 6, 0.8, 0.5) + rng.uniform(-0.03, 0.03, (6, 12))
    labels = segment_blocks(gray, 0.05)
    assert len(np.unique(labels[:, :6])) == 1 and len(np.unique(labels[:, 6:])) == 1
    assert labels[0, 0] != labels[0, 11]


def _brute_force_area(mask, min_height, min_width):
    best = 0
    rows, cols = mask.shape
    for r0, r1 in itertools.combinations(range(rows + 1), 2):
        for c0, c1 in itertools.combinations(range(cols + 1), 2):
            if r1 - r0 >= min_height and c1 - c0 >= min_width and mask[r0:r1, c0:c1].all():
                best = max(best, (r1 - r0) * (c1 - c0))
    return best


@pytest.mark.parametrize("seed", range(30))
def test_largest_rectangle_matches_brute_force(seed):
    rng = np.random.default_rng(seed)
    mask = rng.random((rng.integers(1, 8), rng.integers(1, 8))) < rng.uniform(0.5, 0.95)
    min_height, min_width = rng.integers(1, 3, size=2)
    box = largest_rectangle(mask, min_height, min_width)
    expected = _brute_force_area(mask, min_height, min_width)
    if expected == 0:
        assert box is None
    else:
        r0, c0, r1, c1 = box
        assert mask[r0:r1, c0:c1].all() and r1 - r0 >= min_height and c1 - c0 >= min_width
        assert (r1 - r0) * (c1 - c0) == expected


def test_largest_rectangle_simple():
    mask = np.zeros((4, 6), dtype=bool)
    mask[1:4, 2:5] = True
    mask[0, :] = True
    assert largest_rectangle(mask) == (0, 2, 4, 5)  # 4 x 3, through the full top row
    assert largest_rectangle(mask, min_height=1, min_width=6) == (0, 0, 1, 6)
    assert largest_rectangle(np.zeros((3, 3), dtype=bool)) is None


def test_pure_white_and_black_are_levels_not_textures(sheet, tone_map):
    """Section 3.2: "Tone 0 and 9 are pure white and black respectively": blank paper and solid
    ink beside the sheet are those two levels, not stipple tones with a texture."""
    image, _ = sheet
    framed = np.hstack([np.zeros((256, 256), dtype=bool), image, np.ones((256, 256), dtype=bool)])
    with_pure = extract_tone_map(framed, block_size=BLOCK)
    assert len(with_pure) == 8
    np.testing.assert_allclose(with_pure.gray_levels, tone_map.gray_levels)
    assert all(texture.any() and not texture.all() for texture in with_pure.textures)
    levels = with_pure.level_grays
    assert levels.size == 10 and levels[0] == 1.0 and levels[-1] == 0.0  # Figure 3: tones 0..9
    np.testing.assert_array_equal(levels[1:-1], with_pure.gray_levels)
    kept_all = extract_tone_map(framed, block_size=BLOCK, pure=0)  # the pure regions become "tones"
    assert kept_all.gray_levels.max() == 1.0 and kept_all.gray_levels.min() == 0.0


def test_only_pure_regions_is_a_clear_error():
    image = np.zeros((128, 256), dtype=bool)
    image[:, 128:] = True  # blank paper beside solid ink: tones 0 and 9, no stipple tone
    with pytest.raises(ValueError, match="pure white or black"):
        extract_tone_map(image, block_size=32, min_size=64)


def test_no_region_large_enough():
    # a drawing whose tone changes every 32 px: no region holds a 64 x 64 texture
    image = np.zeros((128, 256), dtype=bool)
    image[:, np.arange(256) // 32 % 2 == 1] = True
    with pytest.raises(ValueError, match="large enough"):
        extract_tone_map(image, block_size=32, min_size=64)


def test_fewer_than_two_tones():
    image, _ = stipple_tone_sheet(n_tones=2, block=64, rng=0)
    with pytest.raises(ValueError, match="at least two"):
        extract_tone_map(image[:, :64], block_size=16, min_size=32)


@pytest.mark.parametrize(
    ("image", "kwargs"),
    [
        (np.zeros((64,), dtype=bool), {}),
        (np.zeros((0, 64), dtype=bool), {}),
        (np.full((64, 64), np.nan), {}),
        (np.full((64, 64), 2.0), {}),
        (np.zeros((64, 64), dtype=np.int32), {}),
        (np.zeros((64, 64), dtype=complex), {}),
        (np.zeros((16, 16), dtype=bool), {"block_size": 30}),
        (np.zeros((64, 64), dtype=bool), {"block_size": 0}),
        (np.zeros((64, 64), dtype=bool), {"t1": 0}),
        (np.zeros((64, 64), dtype=bool), {"t2": 1.5}),
        (np.zeros((64, 64), dtype=bool), {"min_size": -1}),
        (np.zeros((64, 64), dtype=bool), {"pure": 0.5}),
        (np.zeros((64, 64), dtype=bool), {"pure": "a"}),
    ],
)
def test_bad_input(image, kwargs):
    with pytest.raises(ValueError):
        extract_tone_map(image, **kwargs)
