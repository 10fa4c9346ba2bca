"""paperlib.stipple.synthesis: Kim 2009 section 3.4, GLCM spin-flip synthesis with considered pixels."""

import numpy as np
import pytest

from paperlib.datasets import stipple_tone_texture
from paperlib.stipple.glcm import ace, cooccurrence_counts, normalized_glcms, pair_totals, paper_offsets
from paperlib.stipple.synthesis import (
    StippleGeometry,
    _spin_flip_pass,
    _stipple_radius,
    stipple_geometry,
    synthesize_distribution,
)


@pytest.fixture(scope="module")
def example():
    """An example distribution texture (one pixel per stipple), what section 3.4 synthesizes."""
    from paperlib.stipple.extraction import extract_distribution

    return extract_distribution(stipple_tone_texture(0.15, 64, rng=3)).distribution


@pytest.fixture(scope="module")
def result(example):
    return synthesize_distribution(example, iterations=30, rng=11)


# --------------------------------------------------------------------------------------------
# geometry (section 3.2)


def test_stipple_geometry_known_answer_on_three_blobs():
    texture = np.zeros((40, 40), dtype=bool)
    texture[5:7, 5:7] = True  # 2x2 blob, centre (5.5, 5.5), area 4
    texture[5, 15] = True  # single pixel, centre (5, 15), area 1
    texture[30, 5] = True  # 8-connected with the next pixel (diagonal): one blob of area 2
    texture[31, 6] = True  # centre (30.5, 5.5)
    geometry = stipple_geometry(texture)
    first_second = np.hypot(0.5, 9.5)
    first_third = 25.0
    assert geometry.count == 3
    assert geometry.s_avg == pytest.approx(7 / 3)
    assert geometry.o_min == pytest.approx(first_second)
    assert geometry.o_max == pytest.approx(first_third)
    assert geometry.o_avg == pytest.approx((2 * first_second + first_third) / 3)
    assert not geometry.white_marks


def test_stipple_geometry_reads_white_marks_on_dark_textures():
    texture = np.ones((20, 20), dtype=bool)
    texture[2, 2] = texture[2, 12] = False
    geometry = stipple_geometry(texture)
    assert geometry.white_marks and geometry.count == 2 and geometry.o_min == pytest.approx(10.0)
    with pytest.raises(ValueError, match="at least 2"):
        stipple_geometry(texture, marks="black")  # a single black component


@pytest.mark.parametrize("bad", [np.zeros((8, 8), bool), np.full((4, 4), 0.5), np.zeros(5, bool)])
def test_stipple_geometry_rejects_bad_input(bad):
    with pytest.raises(ValueError):
        stipple_geometry(bad)
    with pytest.raises(ValueError, match="marks"):
        stipple_geometry(np.eye(5, dtype=bool), marks="grey")


def test_stipple_radius_stays_in_the_papers_ranges():
    radius = _stipple_radius.py_func
    o_min, o_avg, o_max = 4.0, 10.0, 25.0
    assert radius(0.5, 0.7, o_min, o_avg, o_max) == o_avg  # probability 0.8, R = 0
    assert o_min <= radius(0.05, 0.7, o_min, o_avg, o_max) < o_avg  # O_min + random(0, O_avg - O_min)
    assert o_avg < radius(0.15, 0.7, o_min, o_avg, o_max) <= o_max  # O_max + random(O_avg - O_max, 0)
    assert radius(0.05, 0.0, o_min, o_avg, o_max) == o_min
    assert radius(0.15, 0.0, o_min, o_avg, o_max) == o_max


# --------------------------------------------------------------------------------------------
# the kernel against a pure Python pass


def reference_pass(texture, offsets, target, order, choices, spreads, radii, fixed_radius, regions):
    """Section 3.4.1-3.4.2 spelled out: full ACE recomputation for every candidate flip."""
    texture, regions = texture.copy(), regions.copy()
    rows, cols = np.indices(texture.shape)

    def disc(y, x, radius):
        return (rows - y) ** 2 + (cols - x) ** 2 <= radius**2

    considered = np.zeros(texture.shape, dtype=bool)
    for y, x in zip(*np.nonzero(texture)):  # the existing stipples' regions, without the stipples
        considered |= disc(y, x, fixed_radius if fixed_radius >= 0 else regions[y, x])
    considered &= ~texture
    current = ace(target, normalized_glcms(cooccurrence_counts(texture, offsets)))
    for t, flat in enumerate(order):
        y, x = divmod(int(flat), texture.shape[1])
        if considered[y, x]:
            continue
        considered[y, x] = True
        texture[y, x] = ~texture[y, x]
        candidate = ace(target, normalized_glcms(cooccurrence_counts(texture, offsets)))
        if candidate < current - 1e-12:
            current = candidate
            radius = fixed_radius if fixed_radius >= 0 else _stipple_radius.py_func(choices[t], spreads[t], *radii)
            regions[y, x] = radius if texture[y, x] else 0.0
            considered |= disc(y, x, radius)
        else:
            texture[y, x] = ~texture[y, x]
    return texture, regions


@pytest.mark.parametrize("fixed_radius", [-1.0, 0.0, 1.5])
def test_spin_flip_pass_matches_python_reference(fixed_radius):
    example = np.random.default_rng(0).random((12, 12)) < 0.2
    seed = np.random.default_rng(1).random((12, 12)) < 0.05
    offsets = paper_offsets(5)
    target = normalized_glcms(cooccurrence_counts(example, offsets))
    rng = np.random.default_rng(2)
    order = rng.permutation(seed.size).astype(np.int64)
    choices, spreads = rng.random(seed.size), rng.random(seed.size)
    radii = np.array([1.0, 2.0, 3.5])
    regions = np.where(seed, 2.5, 0.0)
    expected, expected_regions = reference_pass(seed, offsets, target, order, choices, spreads, radii, fixed_radius,
                                                regions)

    texture, counts = seed.copy(), cooccurrence_counts(seed, offsets)
    totals = pair_totals(seed.shape, offsets).astype(np.float64)
    considered = np.zeros(seed.shape, dtype=bool)
    attempts, accepted = _spin_flip_pass(
        texture, counts, offsets, target, totals, order, choices, spreads, radii, fixed_radius, considered, regions
    )
    np.testing.assert_array_equal(texture, expected)
    np.testing.assert_array_equal(regions, expected_regions)
    np.testing.assert_array_equal(counts, cooccurrence_counts(texture, offsets))
    assert accepted == np.count_nonzero(texture != seed) and accepted >= 1
    assert attempts == seed.size if fixed_radius == 0 else attempts <= seed.size
    assert considered.all()


def test_synthesis_keeps_the_examples_hard_core():
    """Section 3.4.2: no two synthesized stipples closer than the example's O_min."""
    from scipy.spatial.distance import pdist

    from paperlib.stipple.extraction import extract_distribution

    distribution = extract_distribution(stipple_tone_texture(0.1, 96, rng=4)).distribution
    geometry = stipple_geometry(distribution)
    synthesized = synthesize_distribution(distribution, iterations=30, rng=1).texture
    assert pdist(np.argwhere(synthesized)).min() >= geometry.o_min - 1e-9 > 3


# --------------------------------------------------------------------------------------------
# synthesize_distribution


def test_same_seed_same_texture_bit_for_bit(example, result):
    again = synthesize_distribution(example, iterations=30, rng=np.random.default_rng(11))
    np.testing.assert_array_equal(again.texture, result.texture)
    np.testing.assert_array_equal(again.ace_history, result.ace_history)
    other = synthesize_distribution(example, iterations=30, rng=12)
    assert not np.array_equal(other.texture, result.texture)


def test_ace_decreases_every_iteration(example, result):
    history = result.ace_history
    assert history[0] == pytest.approx(ace(normalized_glcms(cooccurrence_counts(example, result.offsets)),
                                           normalized_glcms(cooccurrence_counts(np.zeros_like(example), result.offsets))))
    assert result.final_ace < 0.2 * history[0]
    kept = history[1:] if not result.converged else history[1:-1]
    assert np.all(np.diff(np.concatenate([[history[0]], kept])) < 0)
    assert len(result.accepted_flips) == len(history) - 1 <= 30


def test_final_counts_equal_a_full_recount(example, result):
    np.testing.assert_array_equal(result.counts, cooccurrence_counts(result.texture, result.offsets))
    np.testing.assert_array_equal(result.offsets, paper_offsets(64))
    assert result.texture.dtype == bool and result.texture.shape == (64, 64)
    assert result.final_ace == pytest.approx(
        ace(normalized_glcms(cooccurrence_counts(result.texture, result.offsets)),
            normalized_glcms(cooccurrence_counts(example, result.offsets)))
    )


def test_ink_fraction_close_to_the_examples(example, result):
    # ACE over all offsets pins the marginals of every GLCM, hence the ink fraction: within 0.01
    assert abs(result.texture.mean() - example.mean()) < 0.01


def test_geometric_constraint_reduces_attempts(example, result):
    plain = synthesize_distribution(example, iterations=2, geometry=False, rng=11)
    assert plain.geometry is None
    assert np.all(plain.attempts == example.size)  # every pixel visited once per iteration
    assert result.geometry == stipple_geometry(example)
    assert result.attempts[0] < example.size / 2


def test_stops_when_an_iteration_no_longer_lowers_the_error():
    distribution = np.zeros((48, 48), dtype=bool)
    distribution[4::9, 3::8] = True  # a regular grid of single-pixel stipples
    outcome = synthesize_distribution(distribution, iterations=30, rng=5)
    assert outcome.converged and outcome.accepted_flips[-1] == 0
    assert outcome.ace_history[-1] == outcome.ace_history[-2] < outcome.ace_history[0]


def test_blank_example_and_explicit_seed_and_size():
    blank = synthesize_distribution(np.zeros((16, 16), bool), iterations=3, rng=0)
    assert blank.final_ace == 0 and blank.converged and not blank.texture.any() and blank.geometry is None
    seed = np.ones((20, 24), dtype=np.uint8)
    example = stipple_tone_texture(0.15, 32, rng=1)
    grown = synthesize_distribution(example, seed_texture=seed, iterations=3, rng=0)
    assert grown.texture.shape == (20, 24) and seed.all()  # the seed is not modified
    assert grown.final_ace < grown.ace_history[0]
    resized = synthesize_distribution(example, size=(40, 48), iterations=2, rng=0)
    assert resized.texture.shape == (40, 48) and len(resized.offsets) == 3 * 31
    custom = synthesize_distribution(example, iterations=2, geometry=StippleGeometry(1.0, 2.0, 3.0, 6.0), rng=0)
    assert custom.geometry.o_avg == 3.0


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"example": np.full((16, 16), 0.3)}, "bitonal|dtype"),
        ({"example": np.array([[0, 2], [1, 0]])}, "bitonal"),
        ({"example": np.zeros((1, 16), bool)}, "too small"),
        ({"offsets": np.array([[0, 40]])}, "smaller than offset"),
        ({"size": 8, "offsets": paper_offsets(16)}, "smaller than offset"),
        ({"iterations": 0}, "iterations"),
        ({"iterations": -3}, "iterations"),
        ({"iterations": 2.5}, "iterations"),
        ({"iterations": True}, "iterations"),
        ({"size": 1}, "size"),
        ({"size": (8, 8, 8)}, "size"),
        ({"seed_texture": np.zeros((8, 8)), "size": 9}, "seed_texture|dtype"),
        ({"seed_texture": np.zeros((8, 8), bool), "size": 9}, "seed_texture"),
        ({"geometry": "yes"}, "geometry"),
        ({"geometry": StippleGeometry(1.0, 5.0, 3.0, 4.0)}, "O_min <= O_avg"),
        ({"geometry": StippleGeometry(1.0, float("nan"), 3.0, 4.0)}, "finite"),
    ],
)
def test_bad_input_raises_value_error(kwargs, match):
    arguments = {"example": stipple_tone_texture(0.15, 16, rng=0), "iterations": 1, "rng": 0} | kwargs
    with pytest.raises(ValueError, match=match):
        synthesize_distribution(**arguments)
