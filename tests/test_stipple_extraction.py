"""Tests of the stipple distribution and mark extraction (Kim et al. 2009, section 3.2)."""

import numpy as np
import pytest
from scipy.optimize import linear_sum_assignment
from scipy.spatial.distance import cdist
from skimage.draw import disk
from skimage.measure import label

from paperlib.datasets.stipple import stipple_tone_texture
from paperlib.stipple.extraction import Mark, classify_level, extract_distribution, extract_marks

SIZE = 128


def _texture(tone, seed=3, size=SIZE):
    return stipple_tone_texture(tone, size, rng=seed, return_truth=True)


def _matched_distances(found, truth):
    """Hungarian matching of found centres to true centres; the matched distances."""
    cost = cdist(found, truth)
    rows, cols = linear_sum_assignment(cost)
    return cost[rows, cols]


def _stamp(marks, pixels, shape):
    """Stamp every mark with its centre on its pixel (what the rendering of section 4.2 does)."""
    canvas = np.zeros(shape, dtype=bool)
    for mark, (row, col) in zip(marks, pixels, strict=True):
        top, left = row - mark.offset[0], col - mark.offset[1]
        height, width = mark.mask.shape
        canvas[top : top + height, left : left + width] |= mark.mask
    return canvas


# ---------------------------------------------------------------------------- levels


@pytest.mark.parametrize(
    ("tone", "level"),
    [(0.05, "light"), (0.2, "light"), (0.3, "light"), (0.35, "merged"), (0.5, "merged"), (0.65, "merged"),
     (0.7, "dark"), (0.9, "dark")],
)
def test_classify_level_matches_the_generator_regime(tone, level):
    image, truth = _texture(tone, size=256)
    assert truth["regime"] == level
    assert classify_level(image) == level


def test_classify_level_two_touching_dots_among_separate_ones_stay_light():
    image = np.zeros((60, 60), dtype=bool)
    for centre in [(10, 10), (10, 30), (10, 50), (30, 10), (30, 30), (50, 10), (50, 50)]:
        image[disk(centre, 3, shape=image.shape)] = True
    image[disk((50, 27), 3, shape=image.shape)] = True
    image[disk((50, 32), 3, shape=image.shape)] = True  # one blob of two dots: 2/9 of the ink, about 0.21
    assert classify_level(image) == "light"  # a blob of two dots is below 3 median areas
    assert classify_level(image, merged_share=0.1, merge_factor=1.5) == "merged"


# ---------------------------------------------------------------------------- light and dark


@pytest.mark.parametrize("tone", [0.05, 0.15, 0.3])
def test_light_centres_match_the_true_centres(tone):
    image, truth = _texture(tone)
    result = extract_distribution(image)
    assert result.level == "light" and not result.white_marks
    assert len(result.centres) == len(truth["centres"])
    distances = _matched_distances(result.centres, truth["centres"])
    # a mark's centroid moves off its ellipse centre by its lobe (<= about 1 px) and border clipping
    assert np.median(distances) < 0.5
    assert np.mean(distances <= 1.5) > 0.97
    assert result.lloyd_iterations == 0


@pytest.mark.parametrize("tone", [0.7, 0.85])
def test_dark_levels_find_the_white_dots(tone):
    image, truth = _texture(tone)
    result = extract_distribution(image)
    assert result.level == "dark" and result.white_marks
    assert len(result.centres) == len(truth["centres"])
    assert np.mean(_matched_distances(result.centres, truth["centres"]) <= 1.5) > 0.97
    assert not image[result.pixels[:, 0], result.pixels[:, 1]].any()  # the centres of white dots are paper
    # the same as the light analysis of the inverted texture
    inverted = extract_distribution(~image)
    np.testing.assert_array_equal(inverted.distribution, result.distribution)


def test_light_centres_are_the_component_centroids_of_a_known_texture():
    image = np.zeros((20, 30), dtype=bool)
    image[2:5, 3:6] = True  # 3 x 3 square, centre (3, 4)
    image[10:12, 20:24] = True  # 2 x 4 rectangle, centre (10.5, 21.5)
    image[17, 10] = True  # single pixel
    image[16, 11] = True  # 8-adjacent diagonal: the same stipple, centre (16.5, 10.5)
    result = extract_distribution(image, level="light")
    np.testing.assert_allclose(result.centres, [[3, 4], [10.5, 21.5], [16.5, 10.5]])
    assert result.s_avg == pytest.approx((9 + 8 + 2) / 3)


# ---------------------------------------------------------------------------- merged


@pytest.mark.parametrize("tone", [0.35, 0.5, 0.6])
def test_merged_count_with_the_light_tone_stipple_size(tone):
    # the paper's workflow: S_avg is the size of one separate stipple, measured on a light tone
    s_avg = extract_distribution(_texture(0.2, seed=9, size=256)[0]).s_avg
    image, truth = _texture(tone, size=256)
    result = extract_distribution(image, s_avg=s_avg)
    assert result.level == "merged"
    assert abs(len(result.centres) / len(truth["centres"]) - 1) <= 0.15


@pytest.mark.parametrize("tone", [0.4, 0.5])
def test_merged_count_with_the_default_stipple_size(tone):
    # default S_avg: median component area of the merged texture itself, a noisier estimate
    image, truth = _texture(tone, size=256)
    result = extract_distribution(image)
    assert abs(len(result.centres) / len(truth["centres"]) - 1) <= 0.30


def test_merged_points_lie_on_ink_and_ran_lloyd_steps():
    image, _ = _texture(0.5)
    result = extract_distribution(image)
    assert image[result.pixels[:, 0], result.pixels[:, 1]].all()
    assert result.lloyd_iterations >= 1


def test_constrained_lloyd_splits_two_merged_disks_symmetrically():
    image = np.zeros((31, 41), dtype=bool)
    image[disk((15, 16), 6, shape=image.shape)] = True
    image[disk((15, 24), 6, shape=image.shape)] = True
    single = int(disk((15, 16), 6)[0].size)
    result = extract_distribution(image, level="merged", s_avg=single)
    assert len(result.centres) == 2
    centres = result.centres[np.argsort(result.centres[:, 1])]
    np.testing.assert_allclose(centres[:, 0], 15, atol=1e-6)  # on the axis of symmetry
    # mirror images up to the pixel grid: pixels on the bisector (column 20) are equidistant and
    # the Voronoi assignment gives ties to one point, a bias below half a pixel
    np.testing.assert_allclose(centres[0, 1] + centres[1, 1], 2 * 20, atol=0.5)
    assert 14 <= centres[0, 1] <= 18  # near the left disk's centre (16), pulled to the middle by the overlap


def test_merged_level_forced_on_separate_dots_gives_one_point_per_dot():
    image, truth = _texture(0.2)
    result = extract_distribution(image, level="merged", s_avg=1e6)
    assert len(result.centres) == len(truth["centres"])


# ---------------------------------------------------------------------------- distribution texture


@pytest.mark.parametrize("tone", [0.1, 0.45, 0.8])
def test_distribution_is_bitonal_with_one_pixel_per_centre(tone):
    image, _ = _texture(tone)
    result = extract_distribution(image)
    assert result.distribution.dtype == np.bool_ and result.distribution.shape == image.shape
    assert result.distribution.sum() == len(result.centres) == len(result.pixels)
    assert len({tuple(pixel) for pixel in result.pixels}) == len(result.pixels)
    assert result.distribution[result.pixels[:, 0], result.pixels[:, 1]].all()


def test_colliding_centres_get_distinct_pixels():
    image = np.zeros((9, 9), dtype=bool)
    image[3:6, 3:6] = True  # 9 pixels, forced to hold 9 points
    result = extract_distribution(image, level="merged", s_avg=1)
    assert len(result.centres) == 9
    assert result.distribution.sum() == 9
    np.testing.assert_array_equal(result.distribution, image)


@pytest.mark.parametrize("tone", [0.2, 0.5, 0.8])
def test_extraction_is_deterministic(tone):
    image, _ = _texture(tone)
    first, second = extract_distribution(image), extract_distribution(image.copy())
    np.testing.assert_array_equal(first.centres, second.centres)
    np.testing.assert_array_equal(first.distribution, second.distribution)
    marks_a, marks_b = extract_marks(image), extract_marks(image)
    assert len(marks_a) == len(marks_b)
    assert all(np.array_equal(a.mask, b.mask) and a.offset == b.offset for a, b in zip(marks_a, marks_b, strict=True))


def test_integer_zero_one_texture_is_accepted():
    image, _ = _texture(0.2)
    np.testing.assert_array_equal(extract_distribution(image.astype(np.uint8)).centres, extract_distribution(image).centres)


# ---------------------------------------------------------------------------- marks


def test_light_marks_stamped_at_their_centres_reproduce_the_texture():
    image, _ = _texture(0.25)
    result = extract_distribution(image)
    marks = extract_marks(image)
    assert len(marks) == len(result.pixels)
    assert all(isinstance(mark, Mark) and mark.mask.dtype == np.bool_ and not mark.white for mark in marks)
    np.testing.assert_array_equal(_stamp(marks, result.pixels, image.shape), image)


def test_dark_marks_are_white_and_reproduce_the_paper():
    image, _ = _texture(0.8)
    result = extract_distribution(image)
    marks = extract_marks(image)
    assert all(mark.white for mark in marks)
    np.testing.assert_array_equal(_stamp(marks, result.pixels, image.shape), ~image)


def test_marks_are_cropped_to_their_bounding_box():
    image, _ = _texture(0.15)
    for mark in extract_marks(image):
        assert mark.mask[0].any() and mark.mask[-1].any() and mark.mask[:, 0].any() and mark.mask[:, -1].any()
        assert 0 <= mark.offset[0] < mark.mask.shape[0] and 0 <= mark.offset[1] < mark.mask.shape[1]


def test_merged_marks_exclude_the_blobs():
    image, _ = _texture(0.5)
    marks = extract_marks(image)
    components = np.bincount(label(image, connectivity=2).ravel())[1:]
    singles = components[components <= 3 * np.median(components)]
    assert sorted(mark.mask.sum() for mark in marks) == sorted(singles.tolist())
    assert components.max() > 3 * np.median(components)  # the texture does have blobs, left out


# ---------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "bad",
    [
        np.array([[0, 2], [1, 0]]),  # not bitonal
        np.full((4, 4), 0.5),  # grayscale float
        np.zeros((0, 5), dtype=bool),  # empty
        np.zeros((8, 8), dtype=bool),  # all white
        np.ones((8, 8), dtype=bool),  # all black
        np.zeros((2, 3, 4), dtype=bool),  # not 2-D
    ],
)
@pytest.mark.parametrize("function", [extract_distribution, extract_marks, classify_level])
def test_bad_textures_raise(function, bad):
    with pytest.raises(ValueError):
        function(bad)


@pytest.mark.parametrize(
    "kwargs",
    [{"level": "grey"}, {"iterations": 0}, {"iterations": 2.5}, {"tol": -1.0}, {"level": "merged", "s_avg": 0},
     {"merged_share": 1.5}, {"merge_factor": 0.5}],
)
def test_bad_parameters_raise(kwargs):
    image, _ = _texture(0.5, size=32)
    with pytest.raises(ValueError):
        extract_distribution(image, **kwargs)
