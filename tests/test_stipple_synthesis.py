"""paperlib.stipple.synthesis: Kim 2009 section 3.4, GLCM spin-flip synthesis with considered pixels."""

import numpy as np
import pytest

from paperlib.datasets import stipple_tone_texture
from paperlib.stipple.glcm import (
    _offset_error_change,
    ace,
    cooccurrence_counts,
    flip_update_kernel,
    normalized_glcms,
    offset_directions,
    pair_totals,
    paper_offsets,
)
from paperlib.stipple.spacing import compare_spacing
from paperlib.stipple.synthesis import (
    StippleGeometry,
    _decision_margin,
    _fast_flip_decision,
    _fill_change_table,
    _fill_prefix_sums,
    _flip_lowers_error,
    _line_decision,
    _mark_considered,
    _mark_stipple_regions,
    _paper_block_length,
    _set_line_pixel,
    _spin_flip_pass,
    _stipple_radius,
    paper_radius_quantiles,
    stipple_geometry,
    synthesize_distribution,
)

#: Offsets that are not the paper's three blocks: the pass takes its generic fast test.
GENERIC_OFFSETS = np.array([[0, 1], [1, 0], [1, 1], [2, -1], [0, 3], [3, 2]], dtype=np.int64)


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


def test_paper_radius_quantiles_follow_the_papers_rule():
    """3.4.2: D = O_min + random(0, O_avg - O_min) w.p. 0.1, O_avg w.p. 0.8, O_max + random(O_avg - O_max, 0)."""
    o_min, o_avg, o_max = 4.0, 10.0, 25.0
    quantiles = paper_radius_quantiles(StippleGeometry(30.0, o_min, o_avg, o_max))
    radius = _stipple_radius.py_func
    draws = np.array([radius(u, quantiles) for u in np.random.default_rng(0).random(20000)])
    assert draws.min() >= o_min and draws.max() <= o_max
    assert np.mean(draws == o_avg) == pytest.approx(0.8, abs=0.01)
    low, high = draws[draws < o_avg], draws[draws > o_avg]
    assert len(low) / len(draws) == pytest.approx(0.1, abs=0.01) and len(high) / len(draws) == pytest.approx(0.1, abs=0.01)
    # R is uniform: the halves of each range are equally likely
    assert np.mean(low < (o_min + o_avg) / 2) == pytest.approx(0.5, abs=0.05)
    assert np.mean(high < (o_avg + o_max) / 2) == pytest.approx(0.5, abs=0.05)
    assert radius(0.0, quantiles) == o_min and radius(0.999999, quantiles) == pytest.approx(o_max, abs=1e-3)


# --------------------------------------------------------------------------------------------
# the kernel against a pure Python pass


def direction_errors(target, texture, offsets, groups):
    """The ACE share of every group of offsets, recomputed from scratch."""
    glcm = normalized_glcms(cooccurrence_counts(texture, offsets))
    share = np.abs(glcm - target).sum(axis=(1, 2)) / len(offsets)
    return np.array([share[groups == g].sum() for g in range(groups.max() + 1)])


def reference_pass(texture, offsets, target, groups, order, uniforms, quantiles, fixed_radius, regions):
    """Section 3.4.1-3.4.2 spelled out: full error recomputation for every candidate flip; a flip is
    kept when the error of every group drops (one group: the ACE of eq. 5)."""
    texture, regions = texture.copy(), regions.copy()
    rows, cols = np.indices(texture.shape)

    def disc(y, x, radius):  # open disc: a stipple may sit at exactly D
        return (rows - y) ** 2 + (cols - x) ** 2 < radius**2

    considered = np.zeros(texture.shape, dtype=bool)
    for y, x in zip(*np.nonzero(texture)):  # the existing stipples' regions, without the stipples
        considered |= disc(y, x, fixed_radius if fixed_radius >= 0 else regions[y, x])
    considered &= ~texture
    current = direction_errors(target, texture, offsets, groups)
    for t, flat in enumerate(order):
        y, x = divmod(int(flat), texture.shape[1])
        if considered[y, x]:
            continue
        considered[y, x] = True
        texture[y, x] = ~texture[y, x]
        candidate = direction_errors(target, texture, offsets, groups)
        if np.all(candidate < current - 1e-12):
            current = candidate
            radius = fixed_radius if fixed_radius >= 0 else _stipple_radius.py_func(uniforms[t], quantiles)
            regions[y, x] = radius if texture[y, x] else 0.0
            considered |= disc(y, x, radius)
        else:
            texture[y, x] = ~texture[y, x]
    return texture, regions


@pytest.mark.parametrize("paper", [True, False])
@pytest.mark.parametrize("every_direction", [False, True])
@pytest.mark.parametrize("fixed_radius", [-1.0, 0.0, 1.5])
def test_spin_flip_pass_matches_python_reference(fixed_radius, every_direction, paper):
    example = np.random.default_rng(0).random((12, 12)) < 0.2
    seed = np.random.default_rng(1).random((12, 12)) < 0.05
    offsets = paper_offsets(5) if paper else GENERIC_OFFSETS
    groups = offset_directions(offsets) if every_direction else np.zeros(len(offsets), dtype=np.int64)
    target = normalized_glcms(cooccurrence_counts(example, offsets))
    rng = np.random.default_rng(2)
    order = rng.permutation(seed.size).astype(np.int64)
    uniforms = rng.random(seed.size)
    quantiles = np.array([1.0, 1.5, 2.0, 2.0, 3.5])
    regions = np.where(seed, 2.5, 0.0)
    expected, expected_regions = reference_pass(seed, offsets, target, groups, order, uniforms, quantiles,
                                                fixed_radius, regions)

    texture, counts = seed.copy(), cooccurrence_counts(seed, offsets)
    totals = pair_totals(seed.shape, offsets).astype(np.float64)
    considered = np.zeros(seed.shape, dtype=bool)
    changes = np.zeros(groups.max() + 1)
    attempts, accepted = _spin_flip_pass(
        texture, counts, offsets, target, totals, groups, changes, order, uniforms, quantiles, fixed_radius,
        considered, regions,
    )
    np.testing.assert_array_equal(texture, expected)
    np.testing.assert_array_equal(regions, expected_regions)
    np.testing.assert_array_equal(counts, cooccurrence_counts(texture, offsets))
    assert accepted == np.count_nonzero(texture != seed) and accepted >= 1
    assert attempts == seed.size if fixed_radius == 0 else attempts <= seed.size
    assert considered.all()


def exact_rule_pass(texture, counts, offsets, target, totals, order, uniforms, quantiles, fixed_radius, regions):
    """The pass as it was before the fast acceptance tests: the exact ACE change for every attempt."""
    width = texture.shape[1]
    groups, changes = np.zeros(len(offsets), dtype=np.int64), np.zeros(1)
    considered = np.zeros(texture.shape, dtype=bool)
    _mark_stipple_regions(considered, texture, regions, fixed_radius)
    for t, flat in enumerate(order):
        y, x = divmod(int(flat), width)
        if considered[y, x]:
            continue
        considered[y, x] = True
        if _flip_lowers_error(texture, counts, y, x, offsets, target, totals, groups, changes):
            flip_update_kernel(texture, counts, y, x, offsets)
            radius = fixed_radius if fixed_radius >= 0 else _stipple_radius(uniforms[t], quantiles)
            regions[y, x] = radius if texture[y, x] else 0.0
            _mark_considered(considered, y, x, radius)


@pytest.mark.parametrize(
    ("tone", "shape", "generic"),
    [(0.1, (64, 64), False), (0.5, (64, 64), False), (0.85, (64, 64), False), (0.4, (48, 72), False),
     (0.3, (40, 40), True)],
)
def test_fast_passes_keep_the_exact_rules_flips(tone, shape, generic):
    """Four passes from the same states: the same texture, counts and regions bit for bit as with the exact
    ACE change of every attempt (paper offsets: line sums; other offsets: the table sum)."""
    from paperlib.stipple.extraction import extract_distribution

    example = extract_distribution(stipple_tone_texture(tone, max(shape), rng=3)).distribution[: shape[0], : shape[1]]
    offsets = GENERIC_OFFSETS if generic else paper_offsets(min(shape))
    target = normalized_glcms(cooccurrence_counts(example, offsets))
    totals = pair_totals(shape, offsets).astype(np.float64)
    quantiles = paper_radius_quantiles(stipple_geometry(example))
    rng = np.random.default_rng(int(tone * 100))
    fast_texture = np.zeros(shape, dtype=bool)
    fast_counts, fast_regions = cooccurrence_counts(fast_texture, offsets), np.zeros(shape)
    texture, counts, regions = fast_texture.copy(), fast_counts.copy(), fast_regions.copy()
    kept = 0
    for fixed_radius in (-1.0, -1.0, quantiles[0], -1.0):
        order, uniforms = rng.permutation(example.size).astype(np.int64), rng.random(example.size)
        exact_rule_pass(texture, counts, offsets, target, totals, order, uniforms, quantiles, fixed_radius, regions)
        _, accepted = _spin_flip_pass(fast_texture, fast_counts, offsets, target, totals, np.zeros(len(offsets), np.int64),
                                      np.zeros(1), order, uniforms, quantiles, fixed_radius,
                                      np.zeros(shape, dtype=bool), fast_regions)
        kept += accepted
        np.testing.assert_array_equal(fast_texture, texture)
        np.testing.assert_array_equal(fast_counts, counts)
        np.testing.assert_array_equal(fast_regions, regions)
    assert kept > 10


def decision_setting(seed, shape, offsets, ink, target_ink):
    """A random texture, its counts and change table, for a target with more ink (so flips go both ways)."""
    rng = np.random.default_rng(seed)
    texture = rng.random(shape) < ink
    target = normalized_glcms(cooccurrence_counts(rng.random(shape) < target_ink, offsets))
    counts = cooccurrence_counts(texture, offsets)
    totals = pair_totals(shape, offsets).astype(np.float64)
    table = np.empty((2, len(offsets), 9))
    _fill_change_table(counts, target, totals, table)
    return texture, counts, target, totals, table


@pytest.mark.parametrize(("shape", "ink"), [((64, 64), 0.03), ((50, 70), 0.2), ((33, 21), 0.5)])
def test_fast_decisions_are_the_exact_rules(shape, ink):
    """Every decision the fast tests take is the exact kernel's; they decline (-1) only near the threshold."""
    offsets = paper_offsets(min(shape))
    texture, counts, target, totals, table = decision_setting(1, shape, offsets, ink, 2 * ink)
    length = _paper_block_length(offsets)
    height, width = shape
    prefix = np.zeros((2, 3, 3, length + 1))
    _fill_prefix_sums(table, length, prefix)
    stride, per_line = max(shape), (max(shape) + 63) // 64
    line_bytes = np.zeros((2 * (height + width) - 1) * stride, dtype=np.uint8)
    line_bits = np.zeros((2 * (height + width) - 1) * per_line, dtype=np.uint64)
    for y, x in zip(*np.nonzero(texture)):
        _set_line_pixel(line_bytes, line_bits, stride, per_line, height, width, y, x, 1)
    margin = _decision_margin(totals)
    groups, changes = np.zeros(len(offsets), dtype=np.int64), np.zeros(1)
    exact, by_lines, by_table = [], [], []
    for y in range(height):
        for x in range(width):
            exact.append(int(_flip_lowers_error(texture, counts, y, x, offsets, target, totals, groups, changes)))
            level = int(texture[y, x])
            by_lines.append(_line_decision(line_bytes, line_bits, stride, per_line, height, width, y, x, level,
                                           length, table, prefix, margin))
            by_table.append(_fast_flip_decision(texture, y, x, offsets, table, margin))
    exact, by_lines, by_table = np.array(exact), np.array(by_lines), np.array(by_table)
    assert 0 < exact.sum() < exact.size  # flips kept and flips rejected
    for decided in (by_lines, by_table):
        np.testing.assert_array_equal(decided[decided >= 0], exact[decided >= 0])
        assert np.count_nonzero(decided < 0) <= 2
    # an infinite margin decides nothing: the exact rule then runs
    assert _line_decision(line_bytes, line_bits, stride, per_line, height, width, 3, 4, 0, length, table, prefix,
                          np.inf) == -1
    assert _fast_flip_decision(texture, 3, 4, offsets, table, np.inf) == -1


def test_change_table_holds_the_kernels_changes():
    """table[v, m, first * 3 + second] is glcm's change of offset m over its pair total, to 1.5 eps."""
    shape, offsets = (30, 26), paper_offsets(26)
    texture, counts, target, totals, table = decision_setting(4, shape, offsets, 0.3, 0.4)
    height, width = shape
    for y, x in [(0, 0), (5, 7), (29, 25), (15, 3), (12, 20)]:
        level = int(texture[y, x])
        for m, (dy, dx) in enumerate(offsets):
            first = int(texture[y - dy, x - dx]) if 0 <= y - dy < height and 0 <= x - dx < width else 2
            second = int(texture[y + dy, x + dx]) if 0 <= y + dy < height and 0 <= x + dx < width else 2
            change = _offset_error_change(texture, counts, y, x, m, dy, dx, target, totals[m]) / totals[m]
            assert abs(table[level, m, first * 3 + second] - change) <= 1.5 * np.finfo(float).eps * abs(change)
    assert _paper_block_length(offsets) == 25 and _paper_block_length(GENERIC_OFFSETS) == 0
    assert _paper_block_length(paper_offsets(26)[::-1].copy()) == 0


def test_matched_spacing_reaches_the_examples_distances():
    """The paper's radius rule leaves the nearest-neighbour distances of a light tone far from the
    example's (most end up just above O_avg); the matched radii come much closer, and both are far
    closer than complete spatial randomness."""
    from paperlib.stipple.extraction import extract_distribution

    distribution = extract_distribution(stipple_tone_texture(0.1, 128, rng=6, mark_radius=2.0)).distribution
    matched = synthesize_distribution(distribution, rng=2)
    paper = synthesize_distribution(distribution, spacing="paper", rng=2)
    csr = np.zeros(distribution.size, dtype=bool)
    csr[np.random.default_rng(3).choice(csr.size, int(distribution.sum()), replace=False)] = True
    ks = {name: compare_spacing(distribution, texture).nn_ks
          for name, texture in (("matched", matched.texture), ("paper", paper.texture), ("csr", csr.reshape(128, 128)))}
    assert ks["matched"] < 0.5 * ks["paper"] and ks["paper"] < 0.6 * ks["csr"]
    assert matched.spacing == "matched" and matched.trials > 1 and len(matched.radius_quantiles) == 21
    assert paper.spacing == "paper" and paper.trials == 1 and len(paper.radius_quantiles) == 11


def test_every_direction_acceptance_keeps_flips_that_lower_each_direction():
    from paperlib.stipple.extraction import extract_distribution

    distribution = extract_distribution(stipple_tone_texture(0.2, 48, rng=1)).distribution
    outcome = synthesize_distribution(distribution, acceptance="every_direction", rng=4)
    assert outcome.acceptance == "every_direction"
    assert outcome.final_ace < 0.3 * outcome.ace_history[0]


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
    custom = synthesize_distribution(example, iterations=2, geometry=StippleGeometry(1.0, 2.0, 3.0, 6.0),
                                     spacing="paper", rng=0)
    assert custom.geometry.o_avg == 3.0 and custom.radius_quantiles[5] == 3.0


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
        ({"geometry": StippleGeometry(1.0, 5.0, 3.0, 4.0), "spacing": "paper"}, "O_min <= O_avg"),
        ({"geometry": StippleGeometry(1.0, float("nan"), 3.0, 4.0), "spacing": "paper"}, "finite"),
        ({"geometry": StippleGeometry(1.0, 2.0, 3.0, 4.0)}, "spacing='paper'"),
        ({"spacing": "even"}, "spacing"),
        ({"acceptance": "all"}, "acceptance"),
    ],
)
def test_bad_input_raises_value_error(kwargs, match):
    arguments = {"example": stipple_tone_texture(0.15, 16, rng=0), "iterations": 1, "rng": 0} | kwargs
    with pytest.raises(ValueError, match=match):
        synthesize_distribution(**arguments)
