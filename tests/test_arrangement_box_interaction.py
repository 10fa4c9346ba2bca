"""Interactions on distances between bounding boxes (Hurtut 2009, section 4.3)."""

import warnings

import numpy as np
import pytest
import shapely

from paperlib.arrangement import fit, synthesize
from paperlib.arrangement.box_interaction import box_distance_matrix, box_gap, box_hausdorff
from paperlib.datasets import drawn_hatching_exemplar, two_category_exemplar
from paperlib.geometry import hausdorff_boxes
from paperlib.pointprocess import PairDistance, PointPattern, Window, interaction_pairs, ppm, quadscheme


def random_boxes(rng, n, degenerate=False):
    """Oriented rectangles (or segments) as (n, 4, 2) corners, in either orientation."""
    centres = rng.random((n, 2))
    angles = rng.random(n) * np.pi
    half = rng.random((n, 2)) * 0.3
    if degenerate:
        half[:, 1] = 0.0
    u = np.stack([np.cos(angles), np.sin(angles)], axis=1)
    v = np.stack([-np.sin(angles), np.cos(angles)], axis=1)
    signs = np.array([[1, 1], [-1, 1], [-1, -1], [1, -1]], dtype=float)
    if rng.random() < 0.5:
        signs = signs[::-1]
    return (centres[:, None] + signs[None, :, :1] * half[:, None, :1] * u[:, None]
            + signs[None, :, 1:] * half[:, None, 1:] * v[:, None])


@pytest.fixture(scope="module")
def hatching():
    return drawn_hatching_exemplar(n=40, rng=3)


def quiet_fit(*args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # pseudolikelihood notes on empty shells
        return fit(*args, **kwargs)


# ---------------------------------------------------------------------------- distances


@pytest.mark.parametrize("degenerate", [False, True])
def test_numba_hausdorff_matches_geometry(degenerate):
    rng = np.random.default_rng(1)
    a, b = random_boxes(rng, 200, degenerate), random_boxes(rng, 200)
    expected = hausdorff_boxes(a, b)
    ours = np.array([box_hausdorff(x, y) for x, y in zip(a, b)])
    np.testing.assert_allclose(ours, expected, atol=1e-12)


@pytest.mark.parametrize("degenerate", [False, True])
def test_gap_matches_shapely_distance(degenerate):
    rng = np.random.default_rng(2)
    a, b = random_boxes(rng, 300, degenerate), random_boxes(rng, 300, degenerate)

    def shape(corners):
        return shapely.LineString(corners[:2]) if degenerate else shapely.Polygon(corners)

    expected = [shapely.distance(shape(x), shape(y)) for x, y in zip(a, b)]
    ours = [box_gap(x, y) for x, y in zip(a, b)]
    np.testing.assert_allclose(ours, expected, atol=1e-12)
    assert min(ours) == 0.0 and max(ours) > 0.0  # both cases occur


def test_gap_known_answers():
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    assert box_gap(square, square + [3, 0]) == pytest.approx(2.0)
    assert box_gap(square, square + [0.5, 0.5]) == 0.0
    assert box_gap(square, square * 0.2 + 0.4) == 0.0  # one inside the other, no edges crossing
    cross_a = np.array([[-1, 0], [1, 0], [1, 0], [-1, 0]], dtype=float)
    cross_b = cross_a[:, ::-1].copy()
    assert box_gap(cross_a, cross_b) == 0.0  # crossing segments: no corner inside, edges cross
    assert box_gap(cross_a, cross_a + [3, 0]) == pytest.approx(1.0)  # collinear, disjoint
    assert box_hausdorff(square, square + [0.3, 0.4]) == pytest.approx(0.5)  # translation: its length


def test_distance_matrix_and_bad_kind():
    rng = np.random.default_rng(3)
    boxes = random_boxes(rng, 5)
    matrix = box_distance_matrix(boxes, distance="gap")
    assert matrix.shape == (5, 5) and np.allclose(matrix, matrix.T) and np.all(np.diag(matrix) == 0)
    with pytest.raises(ValueError, match="distance must be one of"):
        box_distance_matrix(boxes, distance="euclid")


# ---------------------------------------------------------------------------- the pointprocess hook


def test_ppm_with_point_distances_as_pair_distance_is_the_plain_fit():
    rng = np.random.default_rng(4)
    pattern = PointPattern(rng.random((60, 2)), Window.rectangle())
    scheme = quadscheme(pattern, nd=32)
    points = scheme.points

    def centre_distance(i, j):
        return np.hypot(*(points[i] - pattern.points[j]).T)

    distances = np.hypot(*(pattern.points[:, None] - pattern.points[None]).transpose(2, 0, 1))
    hc = 0.5 * distances[np.triu_indices(60, 1)].min()
    plain = ppm(pattern, 0.08, hc, quadrature=scheme)
    hooked = ppm(pattern, 0.08, hc, quadrature=scheme, pair_distance=PairDistance(centre_distance))
    np.testing.assert_allclose(hooked.coefficients["estimate"], plain.coefficients["estimate"], rtol=1e-12)
    np.testing.assert_allclose(hooked.vcov.to_numpy(), plain.vcov.to_numpy(), rtol=1e-10)


def test_pair_distance_shorter_than_promised_is_refused():
    rng = np.random.default_rng(5)
    points = rng.random((30, 2))
    model = ppm(PointPattern(points, Window.rectangle()), 0.1).model
    too_short = PairDistance(lambda i, j: np.zeros(len(i)))
    with pytest.raises(ValueError, match="shorter than the points' distance"):
        interaction_pairs(model, points, np.zeros(30, int), points, np.zeros(30, int), pair_distance=too_short)
    with pytest.raises(ValueError, match="padding"):
        PairDistance(lambda i, j: i, padding=-1.0)
    with pytest.raises(ValueError, match="explicit quadrature"):
        ppm(PointPattern(points, Window.rectangle()), 0.1, pair_distance=PairDistance(lambda i, j: i))


# ---------------------------------------------------------------------------- fit and synthesis


def test_gap_fit_hard_core_is_the_exemplar_smallest_ink_gap(hatching):
    model = quiet_fit(hatching.elements, hatching.labels, hatching.pattern.window, interaction="box_gap")
    # a straight stroke's oriented box is the stroke itself, so box gaps are ink gaps
    assert model.model.hc[0, 0] == pytest.approx(hatching.truth["min_ink_gap"], abs=1e-9)
    assert model.interaction == "box_gap" and model.fit.distance == "gap"


def test_hausdorff_fit_hard_core_is_the_smallest_box_hausdorff(hatching):
    model = quiet_fit(hatching.elements, hatching.labels, hatching.pattern.window, interaction="box_hausdorff")
    corners = np.concatenate(model.reference_corners) + hatching.pattern.points[:, None, :]
    distances = box_distance_matrix(corners)
    np.fill_diagonal(distances, np.inf)
    assert model.model.hc[0, 0] == pytest.approx(distances.min(), abs=1e-12)
    assert model.model.r[0, 0] > model.model.hc[0, 0]


def test_gap_synthesis_respects_the_hard_core_and_is_reproducible(hatching):
    window = hatching.pattern.window
    model = quiet_fit(hatching.elements, hatching.labels, window, interaction="box_gap")
    first = synthesize(model, window, T=20_000, rng=7)
    again = synthesize(model, window, T=20_000, rng=7)
    assert len(first) > 10
    assert np.array_equal(first.pattern.points, again.pattern.points)
    assert all(np.array_equal(a.points, b.points) for a, b in zip(first.elements, again.elements))
    lines = [shapely.LineString(np.vstack([s.points for s in e.strokes])) for e in first.elements]
    gaps = shapely.distance(np.array(lines)[:, None], np.array(lines)[None, :])
    np.fill_diagonal(gaps, np.inf)
    assert gaps.min() >= model.model.hc[0, 0] - 1e-12
    assert window.contains(first.pattern.points).all()


def test_box_synthesis_pastes_the_reference_the_chain_chose():
    ex = two_category_exemplar(rng=0, T=20_000)
    model = quiet_fit(ex.elements, ex.labels, ex.pattern.window, interaction="box_hausdorff")
    result = synthesize(model, ex.pattern.window, T=20_000, rng=1)
    assert set(np.unique(result.pattern.marks)) == {0, 1}
    for element, point in zip(result.elements, result.pattern.points):
        lo, hi = element.points.min(axis=0), element.points.max(axis=0)
        assert np.all(lo <= point) and np.all(point <= hi)


def test_density_steers_box_synthesis(hatching):
    window = hatching.pattern.window
    model = quiet_fit(hatching.elements, hatching.labels, window, interaction="box_gap")
    left_only = np.array([[1.0, 0.0]])
    result = synthesize(model, window, density=left_only, T=20_000, rng=2)
    middle = (window.xrange[0] + window.xrange[1]) / 2
    assert len(result) > 0 and (result.pattern.points[:, 0] < middle).all()


def test_bad_interaction_and_start(hatching):
    window = hatching.pattern.window
    with pytest.raises(ValueError, match="interaction must be one of"):
        fit(hatching.elements, hatching.labels, window, interaction="box")
    model = quiet_fit(hatching.elements, hatching.labels, window, interaction="box_gap")
    with pytest.raises(ValueError, match="start from the empty arrangement"):
        synthesize(model, window, T=10, start=model.pattern, rng=0)


def test_drawn_hatching_truth_holds(hatching):
    lines = [shapely.LineString(np.vstack([s.points for s in e.strokes])) for e in hatching.elements]
    gaps = shapely.distance(np.array(lines)[:, None], np.array(lines)[None, :])
    np.fill_diagonal(gaps, np.inf)
    assert gaps.min() >= hatching.truth["gap"] and gaps.min() == pytest.approx(hatching.truth["min_ink_gap"])
    assert len(hatching) == 40
    directions = np.asarray(hatching.truth["angles"])
    assert np.all(np.abs(directions - 60.0) <= 30.0)
    with pytest.raises(ValueError):
        drawn_hatching_exemplar(gap=0.0)
    with pytest.warns(UserWarning, match="placed"):
        drawn_hatching_exemplar(n=500, max_attempts=50, rng=0)
