"""Wrappers around the third-party stipplers inksep and stippler (paperlib.stipple.external)."""

import builtins

import numpy as np
import pytest

from paperlib.stipple import external
from paperlib.stipple.external import (
    ExternalStipples,
    inksep_stipples,
    rasterize_stipples,
    stipple_count,
    stippler_stipples,
)

SIZE = 64
# Fast settings: a 64 x 64 patch, few Lloyd steps.
TOOLS = {
    "inksep": lambda gray, **kw: inksep_stipples(gray, iterations=8, **kw),
    "stippler": lambda gray, **kw: stippler_stipples(gray, iterations=4, **kw),
}


def flat(gray, size=SIZE):
    return np.full((size, size), gray)


@pytest.mark.parametrize("tool", sorted(TOOLS))
def test_output_shapes_and_coordinates(tool):
    centres, radii = result = TOOLS[tool](flat(0.6), rng=0)
    assert isinstance(result, ExternalStipples)
    assert centres.ndim == 2 and centres.shape[1] == 2 and centres.dtype == float
    assert radii.shape == (len(centres),) and np.all(radii > 0)
    expected = stipple_count(flat(0.6), 2.5)
    assert expected * 0.9 <= len(centres) <= expected
    # (row, col) inside the image, spread over all of it
    assert np.all(centres >= -0.5) and np.all(centres <= SIZE - 0.5)
    assert np.all(np.ptp(centres, axis=0) > 0.8 * SIZE)
    np.testing.assert_allclose(radii, 2.5)


@pytest.mark.parametrize("tool", sorted(TOOLS))
def test_same_seed_same_output_other_seed_other_output(tool):
    first, second, other = (TOOLS[tool](flat(0.7), rng=seed) for seed in (3, 3, 4))
    np.testing.assert_array_equal(first.centres, second.centres)
    np.testing.assert_array_equal(first.radii, second.radii)
    assert first.centres.shape != other.centres.shape or not np.array_equal(first.centres, other.centres)
    # a Generator is accepted and advanced
    generator = np.random.default_rng(3)
    a, b = TOOLS[tool](flat(0.7), rng=generator), TOOLS[tool](flat(0.7), rng=generator)
    assert not np.array_equal(a.centres, b.centres)


@pytest.mark.parametrize("tool", sorted(TOOLS))
def test_darker_gray_gives_more_ink(tool):
    ink = []
    for gray in (0.9, 0.7, 0.5, 0.3):
        centres, radii = TOOLS[tool](flat(gray), rng=1)
        ink.append(rasterize_stipples(centres, radii, (SIZE, SIZE)).mean())
    assert all(b > a for a, b in zip(ink, ink[1:])), ink
    # evenly spread dots that rarely overlap: the light tones' ink is close to their darkness
    assert abs(ink[0] - 0.1) < 0.03 and abs(ink[1] - 0.3) < 0.05


@pytest.mark.parametrize("tool", sorted(TOOLS))
def test_gradient_puts_more_dots_on_the_dark_side(tool):
    gray = np.tile(np.linspace(1.0, 0.2, SIZE), (SIZE, 1))  # white left, dark right
    centres, _ = TOOLS[tool](gray, rng=2)
    right = np.mean(centres[:, 1] > SIZE / 2)
    assert right > 0.65


@pytest.mark.parametrize("tool", sorted(TOOLS))
def test_white_and_empty_requests(tool):
    centres, radii = TOOLS[tool](flat(1.0), rng=0)  # default count on white: no dots
    assert centres.shape == (0, 2) and radii.shape == (0,)
    centres, radii = TOOLS[tool](flat(0.5), n_points=0, rng=0)
    assert centres.shape == (0, 2)
    with pytest.raises(ValueError, match="white everywhere"):
        TOOLS[tool](flat(1.0), n_points=10, rng=0)


@pytest.mark.parametrize("tool", sorted(TOOLS))
@pytest.mark.parametrize(
    ("gray", "kwargs", "match"),
    [
        (np.full((SIZE, SIZE, 3), 0.5), {}, "gray must be a 2-D"),
        (np.full((4, SIZE), 0.5), {}, "at least 8"),
        (np.full((SIZE, SIZE), 1.5), {}, r"\[0, 1\]"),
        (np.full((SIZE, SIZE), -0.1), {}, r"\[0, 1\]"),
        (np.full((SIZE, SIZE), np.nan), {}, "NaN"),
        (np.zeros((SIZE, SIZE), dtype=bool), {}, "dtype bool"),
        (np.full((SIZE, SIZE), "a"), {}, "dtype"),
        (np.full((SIZE, SIZE), 0.5), {"n_points": -1}, "n_points"),
        (np.full((SIZE, SIZE), 0.5), {"n_points": 2.5}, "n_points"),
        (np.full((SIZE, SIZE), 0.5), {"n_points": SIZE * SIZE + 1}, "n_points"),
        (np.full((SIZE, SIZE), 0.5), {"dot_radius": 0}, "dot_radius"),
        (np.full((SIZE, SIZE), 0.5), {"dot_radius": np.inf}, "dot_radius"),
        (np.full((SIZE, SIZE), 0.5), {"rng": "seed"}, "rng"),
        (np.full((SIZE, SIZE), 0.5), {"rng": 1.5}, "rng"),
    ],
)
def test_bad_input_is_rejected_by_name(tool, gray, kwargs, match):
    with pytest.raises(ValueError, match=match):
        TOOLS[tool](gray, **kwargs)


def test_tool_specific_parameters_are_checked():
    with pytest.raises(ValueError, match="iterations"):
        inksep_stipples(flat(0.5), iterations=0)
    with pytest.raises(ValueError, match="sep_dark_threshold"):
        inksep_stipples(flat(0.5), sep_dark_threshold=1.5)
    with pytest.raises(ValueError, match="dot_size_factor"):
        inksep_stipples(flat(0.5), dot_size_factor=-1)
    with pytest.raises(ValueError, match="max_radius"):
        stippler_stipples(flat(0.5), dot_radius=3, max_radius=2)
    with pytest.raises(ValueError, match="position_jitter"):
        stippler_stipples(flat(0.5), position_jitter=-1)
    with pytest.raises(ValueError, match="iterations"):
        stippler_stipples(flat(0.5), iterations=-1)


def test_inksep_dots_grow_with_darkness_when_asked():
    gray = np.tile(np.linspace(0.95, 0.05, SIZE), (SIZE, 1))
    centres, radii = inksep_stipples(gray, rng=0, iterations=8, dot_size_factor=1.0)
    assert np.all((radii >= 2.5 - 1e-9) & (radii <= 5.0 + 1e-9))
    assert np.corrcoef(centres[:, 1], radii)[0, 1] > 0.9


def test_stippler_jitters_are_seeded():
    a = stippler_stipples(flat(0.6), rng=5, iterations=2, size_jitter=0.2, position_jitter=0.5, max_radius=4)
    b = stippler_stipples(flat(0.6), rng=5, iterations=2, size_jitter=0.2, position_jitter=0.5, max_radius=4)
    np.testing.assert_array_equal(a.centres, b.centres)
    np.testing.assert_array_equal(a.radii, b.radii)
    assert np.ptp(a.radii) > 0 and np.all((a.radii >= 2.5) & (a.radii <= 4))


def test_missing_package_raises_import_error_with_hint(monkeypatch):
    real_import = builtins.__import__

    def fake_import(name, *args, **kwargs):
        if name.split(".")[0] in ("inksep", "stippler"):
            raise ImportError(f"No module named {name!r}")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", fake_import)
    with pytest.raises(ImportError, match=r"pip install inksep==1\.0\.0"):
        inksep_stipples(flat(0.5), rng=0)
    with pytest.raises(ImportError, match=r"pip install stippler==0\.2\.1\.1"):
        stippler_stipples(flat(0.5), rng=0)
    assert external.INKSEP_VERSION == "1.0.0"


def test_inksep_leaves_no_files(tmp_path, monkeypatch):
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path))
    inksep_stipples(flat(0.6), rng=0, iterations=2)
    assert list(tmp_path.iterdir()) == []


def test_rasterize_stipples_draws_discs():
    image = rasterize_stipples([[10.0, 10.0], [30.0, 40.0]], [3.0, 1.0], (50, 60))
    assert image.shape == (50, 60) and image.dtype == bool
    assert image[10, 10] and image[10, 12] and not image[10, 13]
    assert image[30, 40] and not image[30, 41]
    assert image.sum() == 25 + 1  # pixels strictly inside: 25 for r = 3, 1 for r = 1
    # scalar radius, no dots, discs cut by the edge
    assert rasterize_stipples(np.empty((0, 2)), 2.0, (5, 5)).sum() == 0
    assert rasterize_stipples([[0.0, 0.0]], 2.0, (5, 5)).sum() == 4


@pytest.mark.parametrize(
    ("centres", "radii", "shape", "match"),
    [
        ([[1.0, 2.0, 3.0]], 1.0, (5, 5), "centres"),
        ([[np.nan, 2.0]], 1.0, (5, 5), "centres"),
        ([[1.0, 2.0]], [1.0, 2.0], (5, 5), "radii"),
        ([[1.0, 2.0]], 0.0, (5, 5), "radii"),
        ([[1.0, 2.0]], 1.0, (5,), "shape"),
        ([[1.0, 2.0]], 1.0, (5, 0), "shape"),
        ([[1.0, 2.0]], 1.0, 5, "shape"),
    ],
)
def test_rasterize_stipples_rejects_bad_input(centres, radii, shape, match):
    with pytest.raises(ValueError, match=match):
        rasterize_stipples(centres, radii, shape)
