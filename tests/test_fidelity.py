"""paperlib.fidelity (issue 24): oracles (spatstat through its fixtures, scikit-image) and known answers.

Known answers: an exemplar scored against itself is perfect (0, better than every control draw); a
synthesis drawn from the control itself (CSR, a shuffle) scores as chance over several seeds (ratio
near 1, rarely better than the control); a synthesis drawn from the exemplar's own process scores
clearly better than the control.
"""

import json
from pathlib import Path

import numpy as np
import pytest
import shapely
from skimage.feature import graycomatrix, graycoprops

from paperlib import fidelity
from paperlib.geometry import lloyd_relaxation
from paperlib.pointprocess import Lcross, Lest, PointPattern, Window

ORACLE = json.loads((Path(__file__).parent / "oracle" / "summary.json").read_text())["datasets"]
SEEDS = range(5)
UNIT = Window.rectangle()


def floats(values) -> np.ndarray:
    return np.array([np.nan if v is None else float(v) for v in values])


def spatstat_pattern(name) -> PointPattern:
    spec = ORACLE[name]["pattern"]
    window = Window.rectangle(floats(spec["window"]["xrange"]), floats(spec["window"]["yrange"]))
    return PointPattern(np.column_stack([floats(spec["x"]), floats(spec["y"])]), window)


def regular(n, seed, window=UNIT):
    box = shapely.box(window.xrange[0], window.yrange[0], window.xrange[1], window.yrange[1])
    return PointPattern(lloyd_relaxation(window.uniform_points(n, np.random.default_rng(seed)), box, 15), window)


def csr(n, seed, window=UNIT):
    return PointPattern(window.uniform_points(n, np.random.default_rng(seed)), window)


# ------------------------------------------------------------------------------------------------- oracles


def test_l_score_is_the_sup_distance_of_spatstats_L_functions():
    cells, redwood = ORACLE["cells"]["Lest_offgrid"], ORACLE["redwood"]["Lest_offgrid"]
    r = floats(cells["r"])
    assert cells["every"] == 1 and np.array_equal(r, floats(redwood["r"]))
    expected = np.nanmax(np.abs(floats(redwood["trans"]) - floats(cells["trans"])))
    score = fidelity.l_score(spatstat_pattern("cells"), spatstat_pattern("redwood"), r=r, nsim=3, rng=0)
    assert score.value == pytest.approx(expected, rel=1e-8)
    # regular cells and clustered redwood differ far more than either differs from the other's CSR
    assert score.value > 0.05


def test_lcross_score_matches_paperlibs_spatstat_equal_lcross():
    rng = np.random.default_rng(3)
    ex = PointPattern(rng.random((60, 2)), UNIT, rng.integers(0, 2, 60), ("a", "b"))
    syn = PointPattern(rng.random((50, 2)), UNIT, rng.integers(0, 2, 50), ("a", "b"))
    r = np.linspace(0, 0.2, 41)
    direct = [Lcross(p, 0, 1, r, correction="translate")["trans"].to_numpy() for p in (ex, syn)]
    score = fidelity.lcross_score(ex, syn, "a", "b", r=r, nsim=4, rng=1)
    assert score.value == pytest.approx(np.nanmax(np.abs(direct[1] - direct[0])), rel=1e-12)
    assert score.control_kind == "random labelling" and len(score.controls) == 4


def test_glcm_correlation_is_skimages_averaged_over_four_directions():
    image = np.random.default_rng(0).random((40, 50)) < 0.3
    distances = [1, 2, 5]
    angles = [0, np.pi / 4, np.pi / 2, 3 * np.pi / 4]
    glcm = graycomatrix(image.astype(np.uint8), distances, angles, levels=2, symmetric=True, normed=True)
    expected = graycoprops(glcm, "correlation").mean(axis=1)
    np.testing.assert_allclose(fidelity.glcm_correlation(image, distances), expected, rtol=1e-12)


def test_glcm_correlation_of_stripes_is_known():
    stripes = np.tile([0, 1], (10, 8))  # columns alternate: horizontal and diagonal neighbours differ
    # d = 1: -1 at 0, 45 and 135 degrees, +1 at 90. d = 2: +1 at 0 and 90; skimage rounds the diagonal offsets
    # (2 cos 45, 2 sin 45) to (1, 1), an odd column shift: -1 at 45 and 135.
    np.testing.assert_allclose(fidelity.glcm_correlation(stripes, [1, 2]), [-0.5, 0.0], atol=1e-12)


def test_turning_angles_of_a_regular_polygon_are_its_exterior_angles():
    n = 7
    angles = 2 * np.pi * np.arange(n) / n
    ring = np.column_stack([np.cos(angles), np.sin(angles)])
    np.testing.assert_allclose(fidelity.turning_angles(ring, closed=True), np.full(n, 2 * np.pi / n), atol=1e-12)
    np.testing.assert_allclose(fidelity.turning_angles(ring[::-1], closed=False), np.full(n - 2, -2 * np.pi / n),
                               atol=1e-12)


def test_turning_angles_equal_simhons_turning_per_sample():
    # the floor's turning angles (geometry, re-exported by fidelity) are the sketch method's, to rounding
    from paperlib.datasets import coastlines
    from paperlib.sketch import turning_per_sample

    coast = coastlines(54)[3]
    for closed in (True, False):
        np.testing.assert_allclose(fidelity.turning_angles(coast, closed=closed),
                                   turning_per_sample(coast, closed=closed), atol=1e-12)


# ------------------------------------------------------------------------------------------------- known answers


@pytest.mark.parametrize("score", [fidelity.l_score, fidelity.pcf_score, fidelity.nn_distance_score])
def test_an_exemplar_against_itself_is_perfect(score):
    exemplar = regular(80, 0)
    result = score(exemplar, exemplar, nsim=9, rng=0)
    assert result.value == 0 and result.ratio == 0 and result.better_than_control
    assert result.p_value == pytest.approx(0.1)


@pytest.mark.parametrize("score", [fidelity.l_score, fidelity.pcf_score, fidelity.nn_distance_score])
def test_csr_scores_as_chance_and_a_same_process_synthesis_beats_it(score):
    exemplar = regular(80, 100)
    chance = [score(exemplar, csr(80, seed), rng=seed) for seed in SEEDS]
    assert sum(s.better_than_control for s in chance) <= 1
    assert 0.6 < np.median([s.ratio for s in chance]) < 1.6
    good = [score(exemplar, regular(80, 200 + seed), rng=seed) for seed in SEEDS]
    assert all(s.better_than_control for s in good)
    assert max(s.ratio for s in good) < 0.6


def test_lcross_random_labelling_scores_as_chance():
    def segregated(seed):  # type a in the left half, type b in the right: strong cross-type segregation
        points = np.random.default_rng(seed).random((80, 2)) * [0.5, 1.0]
        points[40:, 0] += 0.5
        return PointPattern(points, UNIT, np.repeat([0, 1], 40), ("a", "b"))

    exemplar = segregated(100)
    same = [fidelity.lcross_score(exemplar, segregated(s), 0, 1, rng=s) for s in SEEDS]
    assert all(s.better_than_control and s.ratio < 0.6 for s in same)
    relabelled = [fidelity.lcross_score(exemplar, PointPattern(exemplar.points, UNIT, np.random.default_rng(s).permutation(
        exemplar.marks), ("a", "b")), 0, 1, rng=s) for s in SEEDS]
    assert sum(s.better_than_control for s in relabelled) <= 1
    assert 0.6 < np.median([s.ratio for s in relabelled]) < 1.6


def test_mark_difference_score_sees_neighbour_correlation_and_not_the_shuffle():
    def field(pattern):  # orientation varying smoothly across the window (axes, period pi)
        return np.mod(3.0 * pattern.points[:, 0] + 2.0 * pattern.points[:, 1], np.pi)

    exemplar = regular(100, 1)
    perfect = fidelity.mark_difference_score(exemplar, field(exemplar), exemplar, field(exemplar), period=np.pi,
                                             rng=0)
    assert perfect.value == 0 and perfect.better_than_control
    good, chance = [], []
    for seed in SEEDS:
        synthesis = regular(100, 50 + seed)
        good.append(fidelity.mark_difference_score(exemplar, field(exemplar), synthesis, field(synthesis),
                                                   period=np.pi, rng=seed))
        shuffled = np.random.default_rng(seed).permutation(field(synthesis))
        chance.append(fidelity.mark_difference_score(exemplar, field(exemplar), synthesis, shuffled,
                                                     period=np.pi, rng=seed))
    assert all(s.better_than_control for s in good)
    assert sum(s.better_than_control for s in chance) <= 1
    assert 0.6 < np.median([s.ratio for s in chance]) < 1.6


def test_period_folds_angle_differences():
    exemplar = regular(30, 2)
    marks = np.where(np.arange(30) % 2 == 0, 0.0, np.pi)  # the same axis: pi folds to 0
    score = fidelity.mark_difference_score(exemplar, np.zeros(30), exemplar, marks, period=np.pi, nsim=3, rng=0)
    assert score.value == 0
    unfolded = fidelity.mark_difference_score(exemplar, np.zeros(30), exemplar, marks, nsim=3, rng=0)
    assert unfolded.value > 0.3


def test_glcm_score_self_is_perfect_and_pixel_shuffle_is_chance():
    def blobs(seed):  # stipple-like: separated 2 x 2 dots on a jittered grid
        rng = np.random.default_rng(seed)
        image = np.zeros((64, 64), bool)
        for y in range(2, 62, 6):
            for x in range(2, 62, 6):
                dy, dx = rng.integers(0, 3, 2)
                image[y + dy:y + dy + 2, x + dx:x + dx + 2] = True
        return image

    exemplar = blobs(0)
    assert fidelity.glcm_score(exemplar, exemplar, nsim=5, rng=0).value == 0
    good = [fidelity.glcm_score(exemplar, blobs(1 + s), rng=s) for s in SEEDS]
    assert all(s.better_than_control and s.ratio < 0.3 for s in good)
    shuffled = [fidelity.glcm_score(exemplar, np.random.default_rng(s).permutation(blobs(9).ravel()).reshape(64, 64),
                                    rng=s) for s in SEEDS]
    assert sum(s.better_than_control for s in shuffled) <= 1
    assert 0.8 < np.median([s.ratio for s in shuffled]) < 1.25


def _wiggly(guide_angles, amplitude, seed, n=400):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    rng = np.random.default_rng(seed)
    radius = 1 + amplitude * np.convolve(rng.normal(size=n + 8), np.ones(9) / 9, "valid")[:n]
    return np.column_stack([radius * np.cos(t), radius * np.sin(t)])


def test_curve_scores_known_answers():
    guide = _wiggly(None, 0.0, 0, n=40)
    training = [_wiggly(None, 0.3, seed) for seed in (1, 2, 3)]
    synthesis = _wiggly(None, 0.3, 4)
    turning = fidelity.turning_score(training, synthesis, guide, closed=True)
    assert turning.better_than_control and turning.ratio < 0.5
    assert turning.control_kind == "guide (smoothing)"
    smooth = fidelity.turning_score(training, _wiggly(None, 0.0, 0), guide, closed=True)
    assert not smooth.better_than_control  # the smoothing itself scores as the control
    own = fidelity.hausdorff_score(guide, guide, closed=True, nsim=5, rng=0)
    assert own.value == pytest.approx(0, abs=1e-9) and own.better_than_control
    near = fidelity.hausdorff_score(guide, synthesis, closed=True, rng=0)
    assert near.better_than_control and near.value < 0.2
    # the Hausdorff distance over the guide's diameter, as documented: radius 1.5 around radius 1, over the bounding-box diagonal 2 sqrt 2
    assert fidelity.hausdorff_score(guide, 1.5 * _wiggly(None, 0.0, 0), closed=True, nsim=2,
                                    rng=0).value == pytest.approx(0.5 / (2 * np.sqrt(2)), rel=0.01)


def test_l_score_control_is_csr_with_the_synthesis_count():
    exemplar = regular(60, 0)
    score = fidelity.l_score(exemplar, csr(60, 1), nsim=5, rng=2)
    expected_r = np.linspace(0, min(0.25, 3 / np.sqrt(60)), 65)
    first = PointPattern(UNIT.uniform_points(60, np.random.default_rng(2)), UNIT)
    reference = Lest(exemplar, expected_r, correction="translate")["trans"].to_numpy()
    first_distance = np.nanmax(np.abs(Lest(first, expected_r, correction="translate")["trans"].to_numpy() - reference))
    assert score.controls[0] == pytest.approx(first_distance, rel=1e-12)


# ------------------------------------------------------------------------------------------------- bad input


@pytest.mark.parametrize("call, error, words", [
    (lambda: fidelity.l_score(np.zeros((5, 2)), regular(5, 0)), TypeError, "exemplar"),
    (lambda: fidelity.l_score(regular(5, 0), regular(5, 0), nsim=0), ValueError, "nsim"),
    (lambda: fidelity.l_score(regular(5, 0), regular(5, 0), r=[0.1, 0.2]), ValueError, "r must"),
    (lambda: fidelity.nn_distance_score(regular(5, 0), PointPattern(np.zeros((1, 2)), UNIT)), ValueError, "synthesis"),
    (lambda: fidelity.lcross_score(regular(5, 0), regular(5, 0), 0, 1), ValueError, "type"),
    (lambda: fidelity.mark_difference_score(regular(5, 0), np.zeros(4), regular(5, 1), np.zeros(5)), ValueError,
     "exemplar_marks"),
    (lambda: fidelity.glcm_correlation(np.full((8, 8), 0.5)), ValueError, "binary"),
    (lambda: fidelity.glcm_correlation(np.zeros((8, 8)), [1, 9]), ValueError, "distances"),
    (lambda: fidelity.glcm_score("x", np.zeros((8, 8))), TypeError, "exemplar"),
    (lambda: fidelity.turning_angles([[0, 0], [1, 0], [1, 0], [2, 1]], closed=False), ValueError, "repeated"),
    (lambda: fidelity.turning_angles([[0, 0], [1, 0], [2, 1]], closed="yes"), TypeError, "closed"),
    (lambda: fidelity.hausdorff_score(np.zeros((3, 2)) + [[0, 0], [1, 0], [2, 0]], [[0, 0], [1, 1]], closed=False),
     ValueError, "synthesis"),
])
def test_bad_input_is_named(call, error, words):
    with pytest.raises(error, match=words):
        call()
