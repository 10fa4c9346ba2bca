"""Arrangement fit, synthesis and pasting (Hurtut 2009, section 3; Figure 7)."""

import warnings

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.distance import cdist
from shapely.geometry import Point

from paperlib.arrangement.synthesis import (
    Arrangement,
    ArrangementModel,
    element_positions,
    fit,
    render,
    synthesize,
)
from paperlib.datasets import hershey_glyph
from paperlib.geometry import oriented_bounding_box, read_svg
from paperlib.pointprocess import MultiStraussHard, Poisson, Window, fit_strauss_hardcore, rmh

EXEMPLAR_WINDOW = Window.rectangle((0, 16), (0, 16))
# 'o' regular (Strauss gamma 0.2 within r = 1), 'x' random, o-x independent; hard cores only.
TRUE_MODEL = MultiStraussHard([1.0, 0.6], gamma=[[0.2, 1.0], [1.0, 1.0]], r=[[1.0, 0.5], [0.5, 0.5]],
                              hc=[[0.4, 0.3], [0.3, 0.3]], categories=("o", "x"))
GLYPH_SCALE = 0.4


def dress(pattern, chars):
    """Hershey glyphs centred (by oriented box) on the pattern's points, one char per type."""
    glyphs = [hershey_glyph(c).transformed(np.eye(2) * GLYPH_SCALE) for c in chars]
    centres = [oriented_bounding_box(g).center for g in glyphs]
    elements = [glyphs[m].transformed(np.eye(2), p - centres[m]) for p, m in zip(pattern.points, pattern.marks)]
    return elements, np.array(chars)[pattern.marks]


@pytest.fixture(scope="module")
def exemplar():
    pattern = rmh(TRUE_MODEL, EXEMPLAR_WINDOW, 300_000, rng=0)
    elements, labels = dress(pattern, ["o", "x"])
    return pattern, elements, labels


@pytest.fixture(scope="module")
def model(exemplar):
    _, elements, labels = exemplar
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fit(elements, labels, EXEMPLAR_WINDOW, r=TRUE_MODEL.r)


@pytest.fixture(scope="module")
def poisson_model():
    """Two random categories, fitted with a short r = 0.2: gamma ~ 1, tiny hard cores."""
    pattern = rmh(Poisson([0.5, 0.5], categories=("o", "x")), EXEMPLAR_WINDOW, 100_000, rng=3)
    elements, labels = dress(pattern, ["o", "x"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fit(elements, labels, EXEMPLAR_WINDOW, r=0.2)


def assert_no_hardcore_violation(arrangement, hc):
    points, marks = arrangement.pattern.points, arrangement.pattern.marks
    d = cdist(points, points)
    np.fill_diagonal(d, np.inf)
    assert (d >= hc[marks[:, None], marks[None, :]]).all()


# ---------------------------------------------------------------------------- positions and fit


def test_positions_are_box_centres(exemplar):
    pattern, elements, _ = exemplar
    np.testing.assert_allclose(element_positions(elements), pattern.points, atol=1e-12)


def test_fit_recovers_model(exemplar, model):
    pattern, _, _ = exemplar
    assert isinstance(model, ArrangementModel)
    assert model.categories == ("o", "x")
    assert [len(r) for r in model.references] == pattern.counts.tolist()
    # h is the minimum distance (section 3.2.1): never below the true hard core
    assert (model.model.hc >= TRUE_MODEL.hc - 1e-12).all()
    # gamma: MPLE is asymptotically normal; on the log scale the delta-method SE is
    # se / gamma. Bound: 3 SE around the truth (the sandwich SE ignores h's estimation,
    # so a 2-SE bound would be too tight; 8 seeds tried: |z| <= 3.2).
    # The pipeline fits the paper's model, gamma <= 1: a gamma on that bound has no standard
    # error (the constrained maximum is not a stationary point) and must then be one whose true
    # value is 1.
    natural = model.fit.fit.natural.loc["gamma"]
    truth = pd.Series([0.2, 1.0, 1.0], index=natural.index)
    assert (natural.estimate <= 1.0).all(), natural.estimate
    at_bound = natural.estimate == 1.0
    assert (truth[at_bound] == 1.0).all(), natural.estimate
    inside = ~at_bound
    z = (np.log(natural.estimate[inside]) - np.log(truth[inside])) / (natural.se[inside] / natural.estimate[inside])
    assert (np.abs(z.to_numpy()) <= 3).all(), z
    # 'o' is significantly regular: its upper 2-SE bound stays below 1
    assert natural.estimate["o-o"] + 2 * natural.se["o-o"] < 1


def test_fit_bounds_gamma_by_one_unless_asked_not_to(exemplar):
    # The paper's model (section 3.2.2: gamma in [0, 1]) by default; gamma_max=None is the
    # engine's unconstrained pseudolikelihood fit, unchanged. With the true r, the random
    # crosses get an unconstrained gamma of 1.25 on this exemplar.
    _, elements, labels = exemplar
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        bounded = fit(elements, labels, EXEMPLAR_WINDOW, r=TRUE_MODEL.r)
        free = fit(elements, labels, EXEMPLAR_WINDOW, r=TRUE_MODEL.r, gamma_max=None)
        engine = fit_strauss_hardcore(free.pattern, r=TRUE_MODEL.r)
    assert (bounded.model.gamma <= 1.0).all()
    assert (free.model.gamma > 1.0).any(), free.model.gamma
    np.testing.assert_array_equal(free.model.gamma, engine.model.gamma)


def test_references_are_centred(model):
    for refs in model.references:
        np.testing.assert_allclose(element_positions(refs), 0.0, atol=1e-12)


def test_fit_bad_input(exemplar):
    _, elements, labels = exemplar
    with pytest.raises(ValueError, match="labels has"):
        fit(elements, labels[:-1], EXEMPLAR_WINDOW)
    few = labels.copy()
    few[:] = "o"
    few[:2] = "z"
    with pytest.raises(ValueError, match="'z' has 2"):
        fit(elements, few, EXEMPLAR_WINDOW)
    with pytest.raises(ValueError, match="outside the exemplar window"):
        fit(elements, labels, Window.rectangle((0, 8), (0, 16)))
    with pytest.raises(ValueError, match="not among categories"):
        fit(elements, labels, EXEMPLAR_WINDOW, categories=["o"])
    with pytest.raises(ValueError, match="'q' has 0"):
        fit(elements, labels, EXEMPLAR_WINDOW, categories=["o", "x", "q"])
    with pytest.raises(TypeError):
        fit(elements[0], labels, EXEMPLAR_WINDOW)
    with pytest.raises(ValueError, match="non-empty"):
        fit([], [], EXEMPLAR_WINDOW)


# ---------------------------------------------------------------------------- synthesis


def disc(centre, radius):
    return Window.polygon(Point(centre).buffer(radius, 64))


def ring_mask():
    yy, xx = np.mgrid[0:100, 0:100]
    d = np.hypot(xx - 49.5, yy - 49.5)
    return Window.mask((d > 20) & (d < 48), xrange=(0, 20), yrange=(0, 20))


@pytest.mark.parametrize("window", [Window.rectangle((0, 20), (0, 12)), disc((5, 5), 9), ring_mask()],
                         ids=["rectangle", "disc", "mask"])
def test_synthesize_shapes(model, window):
    arrangement = synthesize(model, window, T=100_000, rng=1)
    assert isinstance(arrangement, Arrangement)
    n = len(arrangement)
    # intensity close to the exemplar's (same model; generous: half to double)
    expected = model.pattern.n / model.window.area * window.area
    assert 0.5 * expected < n < 2 * expected
    assert window.contains(arrangement.pattern.points).all()
    assert_no_hardcore_violation(arrangement, model.model.hc)
    # pasted elements are references translated exactly by the points
    for element, point, m, label in zip(arrangement.elements, arrangement.pattern.points,
                                        arrangement.pattern.marks, arrangement.labels):
        assert label == model.categories[m]
        matches = [r for r in model.references[m]
                   if len(r) == len(element)
                   and all(np.array_equal(s.points + point, t.points) and s.width == t.width and s.color == t.color
                           for s, t in zip(r.strokes, element.strokes))]
        assert matches


def test_determinism(model):
    window = disc((0, 0), 6)
    a = synthesize(model, window, T=30_000, rng=7)
    b = synthesize(model, window, T=30_000, rng=7)
    c = synthesize(model, window, T=30_000, rng=8)
    assert np.array_equal(a.pattern.points, b.pattern.points)
    assert np.array_equal(a.pattern.marks, b.pattern.marks)
    assert all(np.array_equal(e.points, f.points) for e, f in zip(a.elements, b.elements))
    assert a.pattern.n != c.pattern.n or not np.array_equal(a.pattern.points, c.pattern.points)


def test_density_ratio(poisson_model):
    """Left half density 1, right half 0.1: given N points, N_right ~ Binomial(N, 1/11).

    For a Poisson process the counts of the two halves are independent Poisson with means
    mu and 0.1 mu, so conditionally on their sum N, N_right is Binomial(N, 0.1 / 1.1). The
    fitted model is Poisson up to tiny hard cores and r = 0.2 (gamma ~ 1), whose effect on
    the counts at this density is below a 1% bias; the bound is 4 binomial SDs.
    """
    window = Window.rectangle((0, 40), (0, 40))
    density = np.ones((4, 8))
    density[:, 4:] = 0.1
    arrangement = synthesize(poisson_model, window, density=density, T=100_000, rng=2)
    x = arrangement.pattern.points[:, 0]
    n, n_right = len(x), int((x >= 20).sum())
    p = 0.1 / 1.1
    assert n > 500
    assert abs(n_right - n * p) <= 4 * np.sqrt(n * p * (1 - p)), (n, n_right)
    ratio = (n - n_right) / n_right
    assert 6 < ratio < 16


def test_density_orientation(poisson_model):
    """Row 0 of the density image is the top of the window."""
    density = np.zeros((2, 1))
    density[0, 0] = 1.0  # top half only
    arrangement = synthesize(poisson_model, Window.rectangle((0, 10), (0, 10)), density=density, T=20_000, rng=0)
    assert arrangement.pattern.n > 10
    assert (arrangement.pattern.points[:, 1] >= 5).all()


def test_density_bad_input(model):
    window = Window.rectangle((0, 10), (0, 10))
    for density, message in [(-np.ones((3, 3)), ">= 0"), (np.zeros((3, 3)), "zero everywhere"),
                             (np.ones(5), "2-D"), (np.ones((0, 3)), "2-D"), (np.full((2, 2), np.nan), "NaN")]:
        with pytest.raises(ValueError, match=message):
            synthesize(model, window, density=density, rng=0)
    outside = np.zeros((10, 10))
    outside[0, 0] = 1  # top-left corner, outside the disc
    with pytest.raises(ValueError, match="whole synthesis window"):
        synthesize(model, disc((5, 5), 3), density=outside, rng=0)


def test_synthesize_bad_input(model):
    window = Window.rectangle((0, 10), (0, 10))
    for T in (0, -5, 1.5):
        with pytest.raises(ValueError, match="T"):
            synthesize(model, window, T=T)
    with pytest.raises(TypeError):
        synthesize(model, (0, 10, 0, 10))
    with pytest.raises(TypeError):
        synthesize(model.model, window)
    tiny = Window.rectangle((0, 0.1), (0, 0.1))
    with pytest.raises(ValueError, match="too small"):
        synthesize(model, tiny, rng=0)
    narrow = Window.rectangle((0, 10), (0, 0.5 * float(model.model.hc.max())))
    with pytest.warns(UserWarning, match="shorter side"):
        synthesize(model, narrow, T=2_000, rng=0)


# ---------------------------------------------------------------------------- output


def test_svg_roundtrip(model, tmp_path):
    arrangement = synthesize(model, disc((4, 4), 5), T=30_000, rng=3)
    path = arrangement.to_svg(tmp_path / "a.svg")
    back = read_svg(path)
    assert len(back) == len(arrangement)
    np.testing.assert_allclose(back[0].points, arrangement.elements[0].points)
    path = arrangement.to_svg(tmp_path / "b.svg", color_by_category=True)
    colours = {s.color for e in read_svg(path) for s in e.strokes}
    assert len(colours) == 2


def test_render(model):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    arrangement = synthesize(model, ring_mask(), T=30_000, rng=4)
    ax = render(arrangement, color_by_category=True)
    assert ax.collections and len(ax.collections[0].get_segments()) == sum(len(e) for e in arrangement.elements)
    fig, ax2 = plt.subplots()
    assert render(arrangement, ax=ax2) is ax2
    plt.close("all")
