"""Tests of the synthetic stipple tone textures and tone-map sheets (Kim 2009 exemplars)."""

import numpy as np
import pytest
from skimage.measure import label

from paperlib.datasets.stipple import stipple_tone_sheet, stipple_tone_texture


@pytest.mark.parametrize("tone", [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9])
def test_ink_fraction_tracks_tone(tone):
    # marks are added until the (white, in dark tones) count reaches the target: the error is
    # below one mark (~60 px of 16384 = 0.004)
    image, truth = stipple_tone_texture(tone, size=128, rng=5, return_truth=True)
    assert image.dtype == bool and image.shape == (128, 128)
    assert abs(image.mean() - tone) <= 0.005
    assert truth["ink_fraction"] == image.mean()
    assert truth["synthetic"] is True and not truth["jammed"]


@pytest.mark.parametrize(("tone", "regime"), [(0.0, "white"), (0.2, "light"), (0.5, "merged"), (0.8, "dark"),
                                              (1.0, "black")])
def test_regimes(tone, regime):
    image, truth = stipple_tone_texture(tone, size=64, rng=0, return_truth=True)
    assert truth["regime"] == regime
    if regime == "white":
        assert not image.any()
    if regime == "black":
        assert image.all()


def test_light_dots_are_separate_and_hard_core():
    image, truth = stipple_tone_texture(0.25, size=128, rng=2, return_truth=True)
    centres = truth["centres"]
    # one 8-connected component per mark, each containing its centre
    components = label(image, connectivity=2)
    assert components.max() == len(centres)
    assert len(np.unique(components[centres[:, 0], centres[:, 1]])) == len(centres)
    distances = np.hypot(*(centres[:, None, :] - centres[None, :, :]).transpose(2, 0, 1))
    np.fill_diagonal(distances, np.inf)
    assert distances.min() >= truth["min_distance"]


def test_dark_is_white_dots_on_black():
    image, truth = stipple_tone_texture(0.8, size=128, rng=3, return_truth=True)
    holes = label(~image, connectivity=2)
    assert holes.max() == len(truth["centres"])  # separate white dots
    assert not image[truth["centres"][:, 0], truth["centres"][:, 1]].any()


def test_merged_marks_merge():
    image, truth = stipple_tone_texture(0.55, size=128, rng=4, return_truth=True)
    assert label(image, connectivity=2).max() < len(truth["centres"]) / 2


def test_texture_is_deterministic():
    a = stipple_tone_texture(0.4, size=64, rng=11)
    b = stipple_tone_texture(0.4, size=64, rng=np.random.default_rng(11))
    c = stipple_tone_texture(0.4, size=64, rng=12)
    assert np.array_equal(a, b) and not np.array_equal(a, c)


@pytest.mark.parametrize(
    "kwargs",
    [dict(tone=-0.1), dict(tone=1.5), dict(tone="dark"), dict(tone=0.5, size=8), dict(tone=0.5, size=32.0),
     dict(tone=0.5, mark_radius=0.5), dict(tone=0.5, light_max=0.6)],
)
def test_texture_bad_input(kwargs):
    with pytest.raises(ValueError):
        stipple_tone_texture(**kwargs)


@pytest.fixture(scope="module")
def sheet():
    return stipple_tone_sheet(n_tones=4, block=64, rng=7, transition=16)


def test_sheet_layout_and_tones(sheet):
    image, truth = sheet
    assert image.shape == (64, 256) and image.dtype == bool
    assert truth["tones"] == pytest.approx([0.2, 0.4, 0.6, 0.8])
    assert truth["synthetic"] is True
    for (r0, c0, r1, c1), (q0, d0, q1, d1), tone in zip(truth["patches"], truth["cores"], truth["tones"]):
        assert (r0, r1, c1 - c0) == (0, 64, 64) and c0 <= d0 < d1 <= c1
        # the core is a crop of the patch's own texture (pure tone): sampling noise only
        assert image[q0:q1, d0:d1].mean() == pytest.approx(tone, abs=0.08)
    # patches get darker from left to right
    assert np.all(np.diff([image[:, c0:c1].mean() for _, c0, _, c1 in truth["patches"]]) > 0)


def test_sheet_transitions_are_dithered():
    # with a band, the boundary columns mix both tones; without one the patches abut sharply
    hard, truth = stipple_tone_sheet(n_tones=2, block=64, rng=1, transition=0)
    soft, _ = stipple_tone_sheet(n_tones=2, block=64, rng=1, transition=32, cell=4)
    assert truth["cores"] == truth["patches"]
    band_ink = soft[:, 48:80].mean()
    assert 1 / 3 - 0.1 < band_ink < 2 / 3 + 0.1


def test_sheet_deterministic_and_bad_input():
    a, _ = stipple_tone_sheet(n_tones=2, block=32, rng=3, transition=8)
    b, _ = stipple_tone_sheet(n_tones=2, block=32, rng=3, transition=8)
    assert np.array_equal(a, b)
    for kwargs in [dict(n_tones=1), dict(block=8), dict(block=32, transition=20), dict(transition=7),
                   dict(cell=0), dict(n_tones=2.0)]:
        with pytest.raises(ValueError):
            stipple_tone_sheet(**kwargs)


def test_mark_rasterisation_equals_scikit_image():
    """The generator's fast ellipse and disk give skimage.draw's pixels, in skimage's order."""
    from skimage.draw import disk, ellipse

    from paperlib.datasets.stipple import _disk, _ellipse

    rng = np.random.default_rng(0)
    shape = (40, 50)
    for _ in range(2000):
        center = tuple(rng.uniform(-5, 55, size=2))
        r_radius, c_radius = rng.uniform(0.3, 9, size=2)
        rotation = rng.uniform(-4, 4)
        expected = ellipse(*center, r_radius, c_radius, shape=shape, rotation=rotation)
        got = _ellipse(center, r_radius, c_radius, shape, rotation=rotation)
        for a, b in zip(expected, got):
            np.testing.assert_array_equal(a, b)
        for a, b in zip(disk(center, r_radius, shape=shape), _disk(center, r_radius, shape)):
            np.testing.assert_array_equal(a, b)


def test_andrews_like_tones_follow_the_papers_geometry_and_levels():
    """Section 3.5: O_min 14.3, O_avg 29.7, O_max 40.8, S_avg 33.7 px on a 256 x 256 tone; section 3.2:
    tones 1-4 light, 5-6 merged, 7-8 dark."""
    from paperlib.datasets.stipple import andrews_like_tones
    from paperlib.stipple import classify_level, extract_distribution
    from paperlib.stipple.synthesis import stipple_geometry

    textures, truths = andrews_like_tones(256, rng=0, return_truth=True)
    assert [truth["regime"] for truth in truths] == ["light"] * 4 + ["merged"] * 2 + ["dark"] * 2
    assert [classify_level(texture) for texture in textures] == ["light"] * 4 + ["merged"] * 2 + ["dark"] * 2
    assert np.all(np.diff([texture.mean() for texture in textures]) > 0)
    distribution = extract_distribution(textures[0], "light")
    geometry = stipple_geometry(distribution.distribution)
    measured = [distribution.s_avg, geometry.o_min, geometry.o_avg, geometry.o_max]
    np.testing.assert_allclose(measured, [33.7, 14.3, 29.7, 40.8], rtol=0.25)
    again = andrews_like_tones(256, rng=0)
    assert all(np.array_equal(a, b) for a, b in zip(again, textures))


def test_hard_core_pair_and_dark_min_are_checked():
    image, truth = stipple_tone_texture(0.05, 64, rng=1, hard_core=(0.3, 0.8), return_truth=True)
    assert truth["regime"] == "light" and truth["min_distance"] > 0
    for kwargs, match in [({"hard_core": 0.9}, "hard_core"), ({"hard_core": (0.8, 0.3)}, "hard_core"),
                          ({"hard_core": (0.1, 0.2, 0.3)}, "hard_core"), ({"dark_min": 0.2}, "dark_min"),
                          ({"dark_min": 1.0}, "dark_min")]:
        with pytest.raises(ValueError, match=match):
            stipple_tone_texture(0.3, 32, rng=0, **kwargs)


def test_a_tone_too_small_for_its_marks_is_drawn_as_no_ink_expected():
    """Random fuzz runs: tone 1e-308 with marks of radius 2.5e16 px underflowed the expected mark count to 0
    and divided by it; radii of 1e191 and 1e308 overflowed. A mark must fit in the texture; a tone too
    small for one mark is white."""
    texture = stipple_tone_texture(1e-308, size=63, mark_radius=31.5, rng=1)
    assert texture.shape == (63, 63) and not texture.any()
    with pytest.raises(ValueError, match=r"^mark_radius must be between 1 pixel and half the size \(31.5 px\)"):
        stipple_tone_texture(1e-308, size=63, mark_radius=2.5e16, rng=1)
