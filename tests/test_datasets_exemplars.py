"""Exemplar generators: determinism, ground truth, Hershey geometry, containment, bad input."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import cKDTree

from paperlib.datasets import hershey_glyph
from paperlib.datasets.exemplars import (
    Exemplar,
    amacrine_exemplar,
    big_small_exemplar,
    hatching_exemplar,
    lattice_exemplar,
    near_identical_exemplar,
    regularity_exemplar,
    two_category_exemplar,
)
from paperlib.pointprocess import Window

GENERATORS = {
    "two_category": lambda rng: two_category_exemplar(rng=rng),
    "two_category_independent": lambda rng: two_category_exemplar(between="independent", rng=rng),
    "big_small": lambda rng: big_small_exemplar(rng=rng),
    "regularity": lambda rng: regularity_exemplar(0.3, rng=rng),
    "lattice": lambda rng: lattice_exemplar(angle_jitter=3.0, rng=rng),
    "hatching": lambda rng: hatching_exemplar(rng=rng),
    "near_identical": lambda rng: near_identical_exemplar(rng=rng),
    "amacrine": lambda rng: amacrine_exemplar(),
}


def bbox_centres(exemplar: Exemplar) -> np.ndarray:
    bounds = np.array([element.bounds() for element in exemplar.elements])
    return (bounds[:, :2] + bounds[:, 2:]) / 2


def cross_min_distance(a: np.ndarray, b: np.ndarray) -> float:
    return float(cKDTree(b).query(a)[0].min())


def within_min_distance(a: np.ndarray) -> float:
    return float(cKDTree(a).query(a, k=2)[0][:, 1].min())


def assert_same(a: Exemplar, b: Exemplar) -> None:
    np.testing.assert_array_equal(a.pattern.points, b.pattern.points)
    np.testing.assert_array_equal(a.labels, b.labels)
    assert a.categories == b.categories and a.truth == b.truth and a.description == b.description
    assert a.window == b.window and a.pattern.window == b.pattern.window
    assert len(a.elements) == len(b.elements)
    assert all(x == y for x, y in zip(a.elements, b.elements))


# ============================================================================ shared invariants


@pytest.mark.parametrize("name", sorted(GENERATORS))
def test_generator_invariants(name):
    exemplar = GENERATORS[name](7)
    assert isinstance(exemplar, Exemplar)
    n = len(exemplar)
    assert n == exemplar.pattern.n >= 20
    # labels are the pattern's marks, read-only, and name the categories
    np.testing.assert_array_equal(exemplar.labels, exemplar.pattern.marks)
    assert not exemplar.labels.flags.writeable
    assert exemplar.categories == tuple(exemplar.pattern.categories)
    np.testing.assert_array_equal(exemplar.counts, np.bincount(exemplar.labels, minlength=len(exemplar.categories)))
    assert (exemplar.counts >= 3).all()  # Hurtut needs >= 3 elements per category
    # position = bounding-box centre of each element
    np.testing.assert_allclose(bbox_centres(exemplar), exemplar.positions, rtol=0, atol=1e-12)
    # all ink, pen half-width included, inside the frame; positions inside the pattern window
    frame = exemplar.window
    for element in exemplar.elements:
        half_pen = max(stroke.width for stroke in element.strokes) / 2
        xmin, ymin, xmax, ymax = element.bounds()
        assert xmin - half_pen >= frame.xrange[0] - 1e-12 and xmax + half_pen <= frame.xrange[1] + 1e-12
        assert ymin - half_pen >= frame.yrange[0] - 1e-12 and ymax + half_pen <= frame.yrange[1] + 1e-12
    inner, (mx, my) = exemplar.pattern.window, exemplar.truth["margin"]
    assert inner.xrange == pytest.approx((frame.xrange[0] + mx, frame.xrange[1] - mx), abs=1e-12)
    assert inner.yrange == pytest.approx((frame.yrange[0] + my, frame.yrange[1] - my), abs=1e-12)
    # each element is the category's Hershey glyph
    for element, label in zip(exemplar.elements, exemplar.labels):
        char = exemplar.truth["glyphs"][exemplar.categories[label]]
        assert element.name == f"futural:{char}"
        assert [len(s) for s in element.strokes] == [len(s) for s in hershey_glyph(char).strokes]
    json.dumps(exemplar.truth)  # plain values only
    assert isinstance(exemplar.description, str) and exemplar.description


@pytest.mark.parametrize("name", sorted(set(GENERATORS) - {"amacrine"}))
def test_same_seed_same_exemplar_bit_for_bit(name):
    assert_same(GENERATORS[name](11), GENERATORS[name](11))
    assert_same(GENERATORS[name](np.random.default_rng(11)), GENERATORS[name](11))
    other = GENERATORS[name](12)
    assert other.pattern.n != GENERATORS[name](11).pattern.n or not np.array_equal(
        other.pattern.points, GENERATORS[name](11).pattern.points)


def test_glyph_geometry_is_hershey():
    exemplar = two_category_exemplar(rng=3)
    o, x = (exemplar.elements[int(np.argmax(exemplar.labels == k))] for k in range(2))
    assert len(x.strokes) == 2 and len(o.strokes) == 1
    assert len(o.strokes[0]) == 17 and np.array_equal(o.strokes[0].points[0], o.strokes[0].points[-1])
    # the placed 'x' is the Hershey 'x' scaled (size = longer bbox side) and translated
    size = exemplar.truth["sizes"]["x"]
    reference = hershey_glyph("x")
    xmin, ymin, xmax, ymax = reference.bounds()
    scale = size / max(xmax - xmin, ymax - ymin)
    expected = (reference.points - [(xmin + xmax) / 2, (ymin + ymax) / 2]) * scale
    got = x.points - [(a + b) / 2 for a, b in zip(x.bounds()[:2], x.bounds()[2:])]
    np.testing.assert_allclose(got, expected, atol=1e-12)
    assert x.strokes[0].width == pytest.approx(scale / 21)


# ============================================================================ ground truth per generator


def test_two_category_truth_and_hard_cores():
    for between in ("repulsive", "independent"):
        exemplar = two_category_exemplar(between=between, rng=5)
        hc = np.array(exemplar.truth["hc"])
        o, x = (exemplar.pattern.of_type(k) for k in (0, 1))
        assert within_min_distance(o) >= hc[0, 0] and within_min_distance(x) >= hc[1, 1]
        assert exemplar.truth["between"] == between
        if between == "repulsive":
            assert cross_min_distance(o, x) >= hc[0, 1] == 0.035
            assert exemplar.truth["gamma"][0][1] == 0.2
        else:
            assert hc[0, 1] == 0 and exemplar.truth["gamma"][0][1] == 1.0
    assert exemplar.categories == ("o", "x")
    assert exemplar.truth["beta"] == [300.0, 150.0]


def test_regular_o_more_regular_than_random_x():
    # mean nearest-neighbour distance relative to the Poisson value 1 / (2 sqrt(lambda)): Clark-Evans R
    ratios = []
    for seed in range(3):
        exemplar = two_category_exemplar(rng=seed)
        area = exemplar.pattern.window.area
        r = []
        for k in range(2):
            pts = exemplar.pattern.of_type(k)
            r.append(cKDTree(pts).query(pts, k=2)[0][:, 1].mean() * 2 * np.sqrt(len(pts) / area))
        ratios.append(r)
    ratios = np.array(ratios).mean(axis=0)
    assert ratios[0] > 1.3 and ratios[0] > ratios[1] + 0.2, ratios


def test_big_small_hard_cores_push_small_glyphs_back():
    exemplar = big_small_exemplar(rng=2)
    hc = np.array(exemplar.truth["hc"])
    big, small = (exemplar.pattern.of_type(k) for k in (0, 1))
    assert len(big) >= 5 and len(small) >= 30
    assert hc[0, 1] > hc[1, 1]
    assert cross_min_distance(big, small) >= hc[0, 1]
    assert within_min_distance(big) >= hc[0, 0] and within_min_distance(small) >= hc[1, 1]
    assert exemplar.truth["sizes"] == {"O": 0.1, "x": 0.025}
    assert np.all(np.array(exemplar.truth["gamma"]) == 1.0)
    # default hard cores: sums of bounding radii, so ink of different glyphs never overlaps
    boxes = [np.array(exemplar.elements[int(np.argmax(exemplar.labels == k))].bounds()) for k in (0, 1)]
    radii = [np.hypot(*(b[2:] - b[:2])) / 2 for b in boxes]
    np.testing.assert_allclose(hc, [[2 * radii[0], radii[0] + radii[1]], [radii[0] + radii[1], 2 * radii[1]]])


def test_regularity_family_from_regular_to_random():
    def clark_evans(gamma):
        values = []
        for seed in range(3):
            pattern = regularity_exemplar(gamma, rng=seed).pattern
            d = cKDTree(pattern.points).query(pattern.points, k=2)[0][:, 1]
            values.append(d.mean() * 2 * np.sqrt(pattern.n / pattern.window.area))
        return np.mean(values)

    regular, middle, random = clark_evans(0.0), clark_evans(0.5), clark_evans(1.0)
    assert regular > middle > random
    assert regular > 1.4 and random < 1.3
    exemplar = regularity_exemplar(0.0, rng=1)
    assert within_min_distance(exemplar.pattern.points) >= exemplar.truth["r"][0][0]  # gamma = 0: r is a hard core
    assert exemplar.truth["gamma"] == [[0.0]] and exemplar.truth["T"] == 100_000


def test_lattice_spacing_recovered():
    exemplar = lattice_exemplar(spacing=(0.1, 0.08), jitter=0.004, rng=4)
    nx, ny = exemplar.truth["shape"]
    assert exemplar.pattern.n == nx * ny
    points = exemplar.pattern.points
    d = cKDTree(points).query(points, k=2)[0][:, 1]
    bound = 2 * np.sqrt(2) * 0.004
    assert np.all(np.abs(d - 0.08) <= bound + 1e-12)
    assert np.median(d) == pytest.approx(0.08, abs=0.004)
    # both spacings from the neighbour pairs along the rows and along the columns
    pairs = np.array(sorted(cKDTree(points).query_pairs(0.12)))
    delta = np.abs(points[pairs[:, 0]] - points[pairs[:, 1]])
    along_x, along_y = delta[delta[:, 1] < 0.04, 0], delta[delta[:, 0] < 0.05, 1]
    assert len(along_x) == (nx - 1) * ny and len(along_y) == nx * (ny - 1)
    assert np.median(along_x) == pytest.approx(0.1, abs=0.002)
    assert np.median(along_y) == pytest.approx(0.08, abs=0.002)
    assert exemplar.truth["spacing"] == [0.1, 0.08] and exemplar.truth["process"] == "lattice"
    # every point within the jitter of its lattice node
    origin, spacing = np.array(exemplar.truth["origin"]), np.array([0.1, 0.08])
    nodes = origin + np.round((points - origin) / spacing) * spacing
    assert np.abs(points - nodes).max() <= 0.004 + 1e-12


def test_hatching_strokes_are_long_parallel_and_cross():
    exemplar = hatching_exemplar(angle=30.0, angle_jitter=4.0, rng=8)
    angles = []
    for element in exemplar.elements:
        (stroke,) = element.strokes
        dx, dy = stroke.points[-1] - stroke.points[0]
        assert np.hypot(dx, dy) == pytest.approx(0.15)
        angles.append(np.degrees(np.arctan2(dy, dx)) % 180)
    angles = np.array(angles)
    np.testing.assert_allclose(angles, np.array(exemplar.truth["angles"]) % 180, atol=1e-9)
    assert abs(angles.mean() - 30) < 2 and 2 < angles.std() < 7
    # centroid distances far below the stroke length: the strokes' extents overlap
    assert np.median(cKDTree(exemplar.positions).query(exemplar.positions, k=2)[0][:, 1]) < 0.15 / 2
    assert within_min_distance(exemplar.positions) >= exemplar.truth["hc"][0][0]


def test_near_identical_is_one_process_with_random_labels():
    exemplar = near_identical_exemplar(chars="oce", proportions=(0.5, 0.25, 0.25), rng=9)
    assert exemplar.categories == ("o", "c", "e") and exemplar.truth["perceptual_groups"] == 1
    np.testing.assert_allclose(exemplar.truth["beta"], [150.0, 75.0, 75.0])
    assert np.all(np.array(exemplar.truth["hc"]) == 0.025)  # one interaction for every pair
    assert within_min_distance(exemplar.positions) >= 0.025
    counts = exemplar.counts
    assert counts[0] > counts[1] and counts[0] > counts[2]
    sizes = {max(e.bounds()[2] - e.bounds()[0], e.bounds()[3] - e.bounds()[1]) for e in exemplar.elements}
    np.testing.assert_allclose(sorted(sizes), 0.02, atol=1e-12)


def test_amacrine_positions_are_spatstats():
    exemplar = amacrine_exemplar()
    data = json.loads((Path(__file__).parent / "oracle" / "summary.json").read_text())
    data = data["datasets"]["amacrine"]["pattern"]
    np.testing.assert_array_equal(exemplar.pattern.points[:, 0], np.array(data["x"], dtype=float))
    np.testing.assert_array_equal(exemplar.pattern.points[:, 1], np.array(data["y"], dtype=float))
    assert exemplar.categories == ("off", "on")
    assert [exemplar.categories[k] for k in exemplar.labels] == data["marks"]
    assert exemplar.counts.tolist() == [142, 152]
    assert exemplar.pattern.window.xrange == pytest.approx((0, 1.6012084592145015), abs=1e-15)
    on = exemplar.elements[int(np.argmax(exemplar.labels == 1))]
    off = exemplar.elements[int(np.argmax(exemplar.labels == 0))]
    assert on.name == "futural:o" and len(on.strokes) == 1
    assert off.name == "futural:x" and len(off.strokes) == 2
    assert_same(exemplar, amacrine_exemplar())


def test_amacrine_missing_fixture_is_a_clear_error(tmp_path):
    with pytest.raises(FileNotFoundError, match="amacrine fixture"):
        amacrine_exemplar(path=tmp_path / "nope.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"datasets": {}}')
    with pytest.raises(ValueError, match="does not hold the amacrine pattern"):
        amacrine_exemplar(path=bad)


def test_other_windows():
    window = Window.rectangle((2.0, 4.0), (-1.0, 0.0))
    exemplar = regularity_exemplar(0.2, window, rng=1)
    assert exemplar.window == window
    assert exemplar.pattern.n > 40
    with pytest.raises(ValueError, match="rectangles"):
        regularity_exemplar(window=Window.polygon([(0, 0), (1, 0), (0, 1)]))
    with pytest.raises(TypeError, match="Window"):
        regularity_exemplar(window=(1.0, 1.0))
    with pytest.raises(ValueError, match="too small"):
        hatching_exemplar(window=Window.rectangle((0, 0.1), (0, 1)))


# ============================================================================ bad parameters


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: two_category_exemplar(chars=("o", "o")), "distinct"),
        (lambda: two_category_exemplar(chars=("o",)), "2 characters"),
        (lambda: two_category_exemplar(chars=("o", "xy")), "single characters"),
        (lambda: two_category_exemplar(sizes=(0.03, -1)), "sizes"),
        (lambda: two_category_exemplar(beta=(1.0, np.nan)), "beta"),
        (lambda: two_category_exemplar(gamma=(1.5, 1.0)), "gamma"),
        (lambda: two_category_exemplar(hc=(0.2, 0.0)), "exceeds r"),
        (lambda: two_category_exemplar(between="attractive"), "between"),
        (lambda: two_category_exemplar(between_hc=0.1, between_r=0.05), "between_hc"),
        (lambda: two_category_exemplar(T=0), "T"),
        (lambda: two_category_exemplar(T=1.5), "T"),
        (lambda: two_category_exemplar(font="nope"), "unknown Hershey font"),
        (lambda: big_small_exemplar(sizes=(0.02, 0.05)), "big glyph first"),
        (lambda: big_small_exemplar(hc_between=0.0), "hc_between"),
        (lambda: regularity_exemplar(-0.1), "gamma"),
        (lambda: regularity_exemplar(char=" "), "no strokes"),
        (lambda: regularity_exemplar(size=0), "size"),
        (lambda: lattice_exemplar(spacing=(0.1, 0)), "spacing"),
        (lambda: lattice_exemplar(spacing=0.1, jitter=0.03), "jitter"),
        (lambda: lattice_exemplar(spacing=0.99), "2 x 2"),
        (lambda: lattice_exemplar(angle_jitter=-1), "angle_jitter"),
        (lambda: hatching_exemplar(angle=np.inf), "angle"),
        (lambda: hatching_exemplar(length="long"), "length"),
        (lambda: near_identical_exemplar(proportions=(0.7, 0.7)), "proportions"),
        (lambda: near_identical_exemplar(proportions=(1.0,)), "proportions"),
        (lambda: near_identical_exemplar(chars="o"), "at least 2"),
        (lambda: amacrine_exemplar(size=-0.01), "size"),
        (lambda: lattice_exemplar(size=1e308), "size must keep the glyphs' coordinates finite"),  # a fuzz run
    ],
)
def test_bad_parameters_raise_clear_errors(call, match):
    with pytest.raises(ValueError, match=match):
        call()


@pytest.mark.parametrize("call", [
    lambda: amacrine_exemplar(font=np.array([1.0, -1.0, 1.0])),  # found by a random fuzz run: numpy's ambiguous truth value
    lambda: regularity_exemplar(0.3, font=3, rng=0),
    lambda: hatching_exemplar(font=None, rng=0),
])
def test_a_font_that_is_not_a_name_is_refused_naming_it(call):
    with pytest.raises(TypeError, match="font must be a str"):
        call()
