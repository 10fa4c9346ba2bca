"""paperlib.stipple.spacing: stipple spacing and tile homogeneity, apart from the GLCM objective."""

import numpy as np
import pytest

from paperlib.stipple.spacing import (
    block_dispersion,
    compare_spacing,
    nearest_neighbour_distances,
    pair_correlation,
    stipple_pattern,
)


def grid(shape=(60, 60), step=6, offset=2):
    texture = np.zeros(shape, dtype=bool)
    texture[offset::step, offset::step] = True
    return texture


def uniform(count, shape, seed):
    flat = np.zeros(shape[0] * shape[1], dtype=bool)
    flat[np.random.default_rng(seed).choice(flat.size, count, replace=False)] = True
    return flat.reshape(shape)


def test_nearest_neighbour_distances_of_a_grid():
    np.testing.assert_array_equal(nearest_neighbour_distances(grid()), np.full(100, 6.0))
    pattern = stipple_pattern(grid())
    assert pattern.points.min() == 2.5 and pattern.window.area == 3600  # pixel centres, (x, y) = (col, row)


def test_pair_correlation_is_one_for_csr_and_zero_inside_a_hard_core():
    csr = uniform(2000, (200, 200), 0)
    r = np.linspace(0, 12, 25)
    g = pair_correlation(csr, r)
    assert np.all(np.abs(g[8:] - 1) < 0.15)  # r >= 4 px: within the estimator's noise of 1
    g_grid = pair_correlation(grid((120, 120)), np.linspace(0, 4, 9))
    assert np.all(g_grid[1:6] < 0.05)  # no pair closer than 6 px


def test_compare_spacing_tells_a_regular_pattern_from_csr():
    regular = grid((120, 120))
    shifted = grid((120, 120), offset=4)
    same = compare_spacing(regular, shifted)
    assert same.nn_ks == 0 and same.pcf_rms < 0.05
    random = compare_spacing(regular, uniform(int(regular.sum()), regular.shape, 1))
    assert random.nn_ks > 0.8 and random.pcf_rms > 0.3
    assert len(random.r) == len(random.g_reference) == len(random.g_texture) == 101


def test_block_dispersion_known_answers():
    assert block_dispersion(grid((64, 64), step=4, offset=0), 16) == 0  # every block holds 16 stipples
    poisson = np.mean([block_dispersion(uniform(4000, (256, 256), seed), 32) for seed in range(5)])
    assert poisson == pytest.approx(1.0, abs=0.2)
    banded = np.zeros((128, 128), dtype=bool)
    banded[:32] = uniform(1000, (32, 128), 2)
    assert block_dispersion(banded, 32) > 20


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: nearest_neighbour_distances(np.zeros((8, 8), bool)), "at least 2"),
        (lambda: nearest_neighbour_distances(np.full((8, 8), 0.5)), "bitonal|dtype"),
        (lambda: compare_spacing(grid((60, 60)), grid((66, 60))), "shape"),
        (lambda: block_dispersion(grid(), 0), "block"),
        (lambda: block_dispersion(grid(), 40), "at least 2"),
        (lambda: block_dispersion(np.zeros((64, 64), bool), 32), "no ink"),
    ],
)
def test_bad_input_raises_value_error(call, match):
    with pytest.raises(ValueError, match=match):
        call()
