"""paperlib.stipple.glcm: Kim 2009 GLCMs (3.3), ACE (eq. 5) and incremental counts, against scikit-image."""

import numba
import numpy as np
import pytest
from skimage.feature import graycomatrix, graycoprops

from paperlib.stipple.glcm import (
    GLCMFeatures,
    ace,
    ace_change_kernel,
    check_bitonal,
    cooccurrence_counts,
    flip_update,
    flip_update_kernel,
    glcm_features,
    normalized_glcms,
    pair_totals,
    paper_offsets,
    to_bitonal,
)


def random_texture(shape, density, seed):
    return np.random.default_rng(seed).random(shape) < density


def skimage_glcms(texture, offsets):
    """Non-symmetric 2x2 GLCMs from graycomatrix, one per (dy, dx) offset of the paper's three directions."""
    image = texture.astype(np.uint8)
    matrices = []
    for dy, dx in offsets:
        if dy == 0:  # horizontal: angle 0 is (0, +d)
            distance, angle = dx, 0.0
        elif dx == 0:  # vertical: angle pi/2 is (+d, 0) in skimage 0.26 (rows grow downwards)
            distance, angle = dy, np.pi / 2
        else:  # left-down diagonal (k, -k): angle 3 pi/4, distance k sqrt(2) rounds to k steps
            assert dx == -dy
            distance, angle = dy * np.sqrt(2), 3 * np.pi / 4
        matrices.append(graycomatrix(image, [distance], [angle], levels=2, symmetric=False))
    return np.concatenate(matrices, axis=2)  # (2, 2, k, 1), graycoprops' layout


# --------------------------------------------------------------------------------------------
# bitonal helpers


def test_to_bitonal_thresholds_float_and_uint8_images_with_ink_below_threshold():
    gray = np.array([[0.0, 0.2, 0.5], [0.7, 1.0, 0.49]])
    np.testing.assert_array_equal(to_bitonal(gray), [[True, True, False], [False, False, True]])
    np.testing.assert_array_equal(to_bitonal(gray, threshold=0.8), [[True, True, True], [True, False, True]])
    assert not to_bitonal(gray, threshold=0.0).any()
    as_bytes = np.array([[0, 127, 128, 255]], dtype=np.uint8)
    np.testing.assert_array_equal(to_bitonal(as_bytes), [[True, True, False, False]])
    assert to_bitonal(gray.astype(np.float32)).dtype == bool


@pytest.mark.parametrize(
    ("image", "match"),
    [
        (np.zeros((0, 4)), "empty"),
        (np.zeros(5), "2-D"),
        (np.zeros((4, 4, 3)), "2-D"),
        (np.array([[0.1, np.nan]]), "NaN"),
        (np.array([[0.1, np.inf]]), "NaN or infinite"),
        (np.array([[0.1, 1.5]]), r"\[0, 1\]"),
        (np.array([[-0.1, 0.5]]), r"\[0, 1\]"),
        (np.array([[0.1 + 1j, 0.5]]), "dtype complex"),
        (np.array([[None, 0.5]], dtype=object), "dtype object"),
        (np.array([[0, 300]], dtype=np.uint16), "dtype uint16"),
        (np.array([[True, False]]), "check_bitonal"),
        ([[0.1, 0.2], [0.3]], "cannot be read"),
    ],
)
def test_to_bitonal_refuses_bad_images(image, match):
    with pytest.raises(ValueError, match=match):
        to_bitonal(image)


@pytest.mark.parametrize("threshold", [-0.1, 1.5, float("nan"), "half"])
def test_to_bitonal_refuses_bad_thresholds(threshold):
    with pytest.raises(ValueError, match="threshold"):
        to_bitonal(np.full((2, 2), 0.5), threshold=threshold)


def test_check_bitonal_accepts_bool_and_integer_zero_one():
    texture = random_texture((5, 7), 0.4, 1)
    assert check_bitonal(texture) is texture  # already contiguous bool: no copy
    as_int = check_bitonal(texture.astype(np.int32))
    assert as_int.dtype == bool
    np.testing.assert_array_equal(as_int, texture)


@pytest.mark.parametrize(
    ("image", "match"),
    [
        (np.array([[0.0, 1.0]]), "to_bitonal"),
        (np.array([[0, 2]]), "to_bitonal"),
        (np.array([[0, -1]], dtype=np.int8), "not bitonal"),
        (np.zeros((3, 0), dtype=bool), "empty"),
        (np.zeros(4, dtype=bool), "2-D"),
    ],
)
def test_check_bitonal_refuses_everything_else(image, match):
    with pytest.raises(ValueError, match=match):
        check_bitonal(image)


# --------------------------------------------------------------------------------------------
# offsets and counts


def test_paper_offsets_are_three_directions_of_lengths_one_to_n_minus_one():
    offsets = paper_offsets(4)
    expected = [[0, 1], [0, 2], [0, 3], [1, 0], [2, 0], [3, 0], [1, -1], [2, -2], [3, -3]]
    np.testing.assert_array_equal(offsets, expected)
    assert offsets.dtype == np.int64
    assert paper_offsets(256).shape == (3 * 255, 2)


@pytest.mark.parametrize("n", [1, 0, -3, 2.0, True, "8"])
def test_paper_offsets_refuse_bad_sides(n):
    with pytest.raises(ValueError, match="n must"):
        paper_offsets(n)


@pytest.mark.parametrize(("shape", "density", "seed"), [((17, 17), 0.3, 0), ((12, 20), 0.08, 1), ((9, 9), 0.7, 2)])
def test_counts_match_skimage_graycomatrix_non_symmetric(shape, density, seed):
    texture = random_texture(shape, density, seed)
    offsets = paper_offsets(min(shape))
    counts = cooccurrence_counts(texture, offsets)
    expected = skimage_glcms(texture, offsets)[:, :, :, 0].transpose(2, 0, 1)
    np.testing.assert_array_equal(counts, expected)
    np.testing.assert_array_equal(counts.sum(axis=(1, 2)), pair_totals(shape, offsets))


def test_counts_are_not_periodic_and_follow_eq_1_on_a_tiny_texture():
    texture = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 0]])
    counts = cooccurrence_counts(texture, np.array([[0, 1], [1, -1], [2, -2]]))
    # (0, 1): two pairs per row, six in all: ink -> paper from both ink pixels, paper -> ink once
    np.testing.assert_array_equal(counts[0], [[3, 1], [2, 0]])
    # (1, -1): p in rows 0-1, columns 1-2; partners one row down, one column left
    np.testing.assert_array_equal(counts[1], [[2, 1], [1, 0]])
    # (2, -2): the single pair (0, 2) -> (2, 0), paper -> paper
    np.testing.assert_array_equal(counts[2], [[1, 0], [0, 0]])


def test_counts_refuse_textures_smaller_than_offsets_and_bad_offsets():
    texture = random_texture((8, 8), 0.3, 3)
    with pytest.raises(ValueError, match="smaller than offset"):
        cooccurrence_counts(texture, paper_offsets(9))
    with pytest.raises(ValueError, match="smaller than offset"):
        cooccurrence_counts(texture[:, :5], paper_offsets(8))
    with pytest.raises(ValueError, match=r"\(0, 0\)"):
        cooccurrence_counts(texture, np.array([[0, 0], [0, 1]]))
    with pytest.raises(ValueError, match="integers"):
        cooccurrence_counts(texture, np.array([[0.0, 1.0]]))
    with pytest.raises(ValueError, match=r"\(k, 2\)"):
        cooccurrence_counts(texture, np.array([1, 2]))
    with pytest.raises(ValueError, match="to_bitonal"):
        cooccurrence_counts(texture * 0.5, paper_offsets(8))


# --------------------------------------------------------------------------------------------
# statistics (eqs. 2-4) and ACE (eq. 5)


@pytest.mark.parametrize(("shape", "density", "seed"), [((24, 24), 0.2, 4), ((16, 30), 0.5, 5), ((10, 10), 0.03, 6)])
def test_features_match_graycoprops(shape, density, seed):
    texture = random_texture(shape, density, seed)
    offsets = paper_offsets(min(shape))
    features = glcm_features(cooccurrence_counts(texture, offsets))
    reference = skimage_glcms(texture, offsets)
    np.testing.assert_allclose(features.contrast, graycoprops(reference, "contrast")[:, 0], atol=1e-12)
    np.testing.assert_allclose(features.energy, graycoprops(reference, "ASM")[:, 0], atol=1e-12)  # eq. 3 = ASM
    np.testing.assert_allclose(features.correlation, graycoprops(reference, "correlation")[:, 0], atol=1e-12)


def test_features_known_answers_on_a_checkerboard():
    checker = (np.indices((8, 8)).sum(axis=0) % 2).astype(bool)
    features = glcm_features(cooccurrence_counts(checker, paper_offsets(8)))
    horizontal = slice(0, 7)
    odd, even = features.contrast[horizontal][0::2], features.contrast[horizontal][1::2]
    np.testing.assert_allclose(odd, 1.0)  # every odd step changes the colour
    np.testing.assert_allclose(even, 0.0)
    np.testing.assert_allclose(features.correlation[horizontal][0::2], -1.0)
    np.testing.assert_allclose(features.correlation[horizontal][1::2], 1.0)
    np.testing.assert_allclose(features.energy[horizontal], 0.5)
    np.testing.assert_allclose(features.contrast[14:], 0.0)  # the left-down diagonal keeps the colour


def test_correlation_of_zero_variance_is_one_like_skimage_and_never_nan():
    blank = np.zeros((6, 6), dtype=bool)
    lone_ink = blank.copy()
    lone_ink[2, 5] = True  # last column: the first pixels of every horizontal pair are all paper
    for texture in (blank, ~blank, lone_ink):
        offsets = paper_offsets(6)
        features = glcm_features(cooccurrence_counts(texture, offsets))
        assert np.all(np.isfinite(features.correlation))
        expected = graycoprops(skimage_glcms(texture, offsets), "correlation")[:, 0]
        np.testing.assert_allclose(features.correlation, expected, atol=1e-12)
    np.testing.assert_array_equal(glcm_features(cooccurrence_counts(lone_ink, offsets)).correlation[:5], 1.0)


def test_statistics_and_ace_do_not_depend_on_offset_sign():
    texture = random_texture((20, 20), 0.3, 7)
    other = random_texture((20, 20), 0.1, 8)
    offsets = paper_offsets(20)
    forward = [glcm_features(cooccurrence_counts(t, offsets)) for t in (texture, other)]
    backward = [glcm_features(cooccurrence_counts(t, -offsets)) for t in (texture, other)]
    np.testing.assert_allclose(backward[0].glcm, forward[0].glcm.transpose(0, 2, 1))
    for name in ("contrast", "energy", "correlation"):
        np.testing.assert_allclose(getattr(backward[0], name), getattr(forward[0], name), atol=1e-12)
    assert ace(*backward) == pytest.approx(ace(*forward), abs=1e-15)


def test_ace_is_eq_5():
    offsets = paper_offsets(16)
    example = glcm_features(cooccurrence_counts(random_texture((16, 16), 0.2, 9), offsets))
    synthesized = glcm_features(cooccurrence_counts(random_texture((16, 16), 0.35, 10), offsets))
    by_hand = sum(
        abs(example.glcm[d, i, j] - synthesized.glcm[d, i, j]) for d in range(len(offsets)) for i in (0, 1) for j in (0, 1)
    ) / len(offsets)
    assert ace(example, synthesized) == pytest.approx(by_hand, rel=1e-12)
    assert ace(example.glcm, synthesized.glcm) == ace(example, synthesized)
    assert ace(synthesized, example) == ace(example, synthesized)
    assert ace(example, example) == 0.0
    white = glcm_features(cooccurrence_counts(np.zeros((16, 16), bool), offsets))
    black = glcm_features(cooccurrence_counts(np.ones((16, 16), bool), offsets))
    assert ace(white, black) == pytest.approx(2.0)  # the largest possible error


def test_ace_and_features_refuse_bad_input():
    counts = cooccurrence_counts(random_texture((8, 8), 0.3, 11), paper_offsets(8))
    features = glcm_features(counts)
    assert isinstance(features, GLCMFeatures)
    with pytest.raises(ValueError, match="raw counts"):
        ace(counts.astype(float), features)
    with pytest.raises(ValueError, match="number of offsets"):
        ace(features, features.glcm[:5])
    with pytest.raises(ValueError, match=r"\(k, 2, 2\)"):
        ace(features, np.ones((3, 3)))
    with pytest.raises(ValueError, match="no pixel pairs"):
        normalized_glcms(np.zeros((2, 2, 2), dtype=np.int64))
    with pytest.raises(ValueError, match="non-negative"):
        glcm_features(-counts)
    with pytest.raises(ValueError, match="integer"):
        glcm_features(counts / 2)
    with pytest.raises(ValueError, match=r"\(k, 2, 2\)"):
        glcm_features(counts[:, 0])


# --------------------------------------------------------------------------------------------
# incremental update


@pytest.mark.parametrize("dtype", [bool, np.uint8])
def test_many_random_flips_keep_counts_equal_to_a_recount(dtype):
    rng = np.random.default_rng(12)
    texture = random_texture((64, 64), 0.15, 13).astype(dtype)
    offsets = paper_offsets(64)
    counts = cooccurrence_counts(texture, offsets)
    for y, x in rng.integers(0, 64, size=(10_000, 2)):
        flip_update(texture, counts, y, x, offsets)
    np.testing.assert_array_equal(counts, cooccurrence_counts(texture, offsets))
    assert texture.dtype == dtype and set(np.unique(texture).tolist()) <= {0, 1}


def test_flipping_twice_restores_texture_and_counts_including_corners():
    texture = random_texture((31, 23), 0.3, 14)
    offsets = paper_offsets(23)
    counts = cooccurrence_counts(texture, offsets)
    before_texture, before_counts = texture.copy(), counts.copy()
    for y, x in [(0, 0), (0, 22), (30, 0), (30, 22), (15, 11)]:
        flip_update(texture, counts, y, x, offsets)
        assert texture[y, x] != before_texture[y, x]
        np.testing.assert_array_equal(counts, cooccurrence_counts(texture, offsets))
        flip_update(texture, counts, y, x, offsets)
        np.testing.assert_array_equal(texture, before_texture)
        np.testing.assert_array_equal(counts, before_counts)


@numba.njit
def _flip_all(texture, counts, pixels, offsets):
    for n in range(pixels.shape[0]):
        flip_update_kernel(texture, counts, pixels[n, 0], pixels[n, 1], offsets)


def test_kernel_runs_inside_numba_loops_as_synthesis_will_call_it():
    texture = random_texture((40, 40), 0.2, 15).astype(np.uint8)
    offsets = paper_offsets(40)
    counts = cooccurrence_counts(texture, offsets)
    pixels = np.random.default_rng(16).integers(0, 40, size=(5_000, 2))
    _flip_all(texture, counts, pixels, offsets)
    np.testing.assert_array_equal(counts, cooccurrence_counts(texture, offsets))


def test_flip_update_refuses_bad_arguments_without_touching_anything():
    texture = random_texture((8, 8), 0.3, 17)
    offsets = paper_offsets(8)
    counts = cooccurrence_counts(texture, offsets)
    before_texture, before_counts = texture.copy(), counts.copy()
    bad_calls = [
        ((texture, counts, 8, 0, offsets), "outside"),
        ((texture, counts, 0, -1, offsets), "outside"),
        ((texture, counts, 1.0, 0, offsets), "integer"),
        ((texture, counts[:-1], 0, 0, offsets), "offsets"),
        ((texture, counts.astype(np.int32), 0, 0, offsets), "int64"),
        ((texture.astype(float), counts, 0, 0, offsets), "bool or integer"),
        ((texture, counts, 0, 0, paper_offsets(9)), "smaller than offset"),
    ]
    for arguments, match in bad_calls:
        with pytest.raises(ValueError, match=match):
            flip_update(*arguments)
    frozen = texture.copy()
    frozen.flags.writeable = False
    with pytest.raises(ValueError, match="writeable"):
        flip_update(frozen, counts, 0, 0, offsets)
    np.testing.assert_array_equal(texture, before_texture)
    np.testing.assert_array_equal(counts, before_counts)


def test_ace_change_kernel_predicts_the_ace_of_the_flipped_texture_without_flipping():
    offsets = paper_offsets(24)
    target = glcm_features(cooccurrence_counts(random_texture((24, 24), 0.25, 18), offsets)).glcm
    texture = random_texture((24, 24), 0.1, 19)
    counts = cooccurrence_counts(texture, offsets)
    totals = pair_totals(texture.shape, offsets).astype(np.float64)
    for y, x in np.random.default_rng(20).integers(0, 24, size=(200, 2)):
        before_texture, before_counts = texture.copy(), counts.copy()
        change = ace_change_kernel(texture, counts, y, x, offsets, target, totals)
        np.testing.assert_array_equal(texture, before_texture)
        np.testing.assert_array_equal(counts, before_counts)
        current = ace(target, normalized_glcms(counts))
        flip_update(texture, counts, y, x, offsets)
        assert change == pytest.approx(ace(target, normalized_glcms(counts)) - current, abs=1e-12)


def test_ace_change_kernel_is_exact_at_every_pixel_for_any_offsets_and_both_flip_directions():
    # rectangular texture, offsets of every sign (some reach only part of the texture), every
    # pixel including corners and edges, ink and paper pixels alike: the branch-free kernel
    # must give the recomputed ACE change to rounding, far inside the 1e-12 acceptance margin
    offsets = np.array([[0, 1], [1, 0], [2, -3], [-1, 4], [5, 5], [0, -6], [6, 0]])
    texture = random_texture((7, 9), 0.4, 21)
    target = normalized_glcms(cooccurrence_counts(random_texture((7, 9), 0.2, 22), offsets))
    counts = cooccurrence_counts(texture, offsets)
    totals = pair_totals(texture.shape, offsets).astype(np.float64)
    current = ace(target, normalized_glcms(counts))
    for y in range(texture.shape[0]):
        for x in range(texture.shape[1]):
            flipped = texture.copy()
            flipped[y, x] = ~flipped[y, x]
            expected = ace(target, normalized_glcms(cooccurrence_counts(flipped, offsets))) - current
            assert ace_change_kernel(texture, counts, y, x, offsets, target, totals) == pytest.approx(
                expected, abs=1e-15
            )


# --------------------------------------------------------------------------------------------
# per-direction error changes (the paper's acceptance rule, section 3.4.1)


def test_offset_directions_groups_the_papers_three_blocks():
    from paperlib.stipple.glcm import offset_directions

    groups = offset_directions(paper_offsets(6))
    np.testing.assert_array_equal(groups, np.repeat([0, 1, 2], 5))
    np.testing.assert_array_equal(offset_directions(np.array([[0, 2], [1, 1], [0, 1], [-2, -2], [2, 2]])), [0, 1, 0, 2, 1])
    with pytest.raises(ValueError, match="non-zero"):
        offset_directions(np.array([[0, 0]]))
    with pytest.raises(ValueError, match="integer"):
        offset_directions(np.array([[0.5, 1.0]]))


def test_group_changes_sum_to_the_ace_change_and_match_a_recount():
    from paperlib.stipple.glcm import ace_change_by_group_kernel, ace_change_kernel, offset_directions

    rng = np.random.default_rng(5)
    texture, example = rng.random((14, 11)) < 0.3, rng.random((14, 11)) < 0.2
    offsets = paper_offsets(9)
    groups = offset_directions(offsets)
    target = normalized_glcms(cooccurrence_counts(example, offsets))
    totals = pair_totals(texture.shape, offsets).astype(np.float64)
    counts = cooccurrence_counts(texture, offsets)
    changes = np.zeros(3)
    for y, x in [(0, 0), (5, 7), (13, 10), (7, 0)]:
        ace_change_by_group_kernel(texture, counts, y, x, offsets, target, totals, groups, changes)
        assert changes.sum() == pytest.approx(ace_change_kernel(texture, counts, y, x, offsets, target, totals), abs=1e-15)
        flipped = texture.copy()
        flipped[y, x] = ~flipped[y, x]
        before = np.abs(normalized_glcms(counts) - target).sum(axis=(1, 2))
        after = np.abs(normalized_glcms(cooccurrence_counts(flipped, offsets)) - target).sum(axis=(1, 2))
        expected = [(after - before)[groups == g].sum() / len(offsets) for g in range(3)]
        np.testing.assert_allclose(changes, expected, atol=1e-14)
