"""Bundled scikit-image images: whitelists, files on disk, no network, shapes."""

import hashlib
import os
import socket

import numpy as np
import pytest
import skimage.data
import skimage.data._fetchers as skimage_fetchers  # private: patched to refuse downloads
from skimage.data._registry import registry as skimage_registry  # private: file hashes

from paperlib.datasets import images
from paperlib.datasets.images import (
    grayscale_image,
    grayscale_names,
    photograph,
    photograph_names,
)

SKIMAGE_DATA_DIR = os.path.dirname(skimage.data.__file__)

PHOTO_SHAPES = {
    "astronaut": (512, 512, 3),
    "chelsea": (300, 451, 3),
    "coffee": (400, 600, 3),
    "hubble_deep_field": (872, 1000, 3),
    "immunohistochemistry": (512, 512, 3),
    "retina": (1411, 1411, 3),
    "rocket": (427, 640, 3),
}
GRAY_SHAPES = {
    "brick": (512, 512),
    "camera": (512, 512),
    "cell": (660, 550),
    "clock": (300, 400),
    "coins": (303, 384),
    "grass": (512, 512),
    "gravel": (512, 512),
    "moon": (512, 512),
    "page": (191, 384),
    "text": (172, 448),
}
ALL_FILES = {**images.PHOTOGRAPH_FILES, **images.GRAYSCALE_FILES}


class DownloadAttempted(Exception):
    pass


class _RefusingFetcher:
    """Stands in for skimage's pooch fetcher: any fetch is a test failure."""

    def __init__(self, cache):
        self.abspath = cache
        self.path = cache

    def fetch(self, filename, *args, **kwargs):
        raise DownloadAttempted(filename)


@pytest.fixture
def offline(monkeypatch, tmp_path):
    """No sockets, no pooch fetcher, empty caches: loading must come from disk."""

    def refuse(*args, **kwargs):
        raise DownloadAttempted("network access")

    monkeypatch.setattr(socket, "socket", refuse)
    monkeypatch.setattr(socket, "create_connection", refuse)
    monkeypatch.setattr(skimage_fetchers, "_image_fetcher", _RefusingFetcher(str(tmp_path)))
    images._load_bundled.cache_clear()
    images._grayscale.cache_clear()
    yield
    images._load_bundled.cache_clear()
    images._grayscale.cache_clear()


def test_whitelists():
    assert photograph_names() == sorted(PHOTO_SHAPES)
    assert grayscale_names() == sorted({**GRAY_SHAPES, **PHOTO_SHAPES})
    for never in ("brain", "kidney", "lily", "cells3d", "eagle", "skin", "human_mitosis"):
        assert never not in grayscale_names() and never not in photograph_names()


@pytest.mark.parametrize("name", sorted(ALL_FILES))
def test_whitelisted_file_is_in_the_package_with_registry_hash(name):
    filename = ALL_FILES[name]
    path = os.path.join(SKIMAGE_DATA_DIR, filename)
    assert os.path.isfile(path), f"{filename} is not bundled in {SKIMAGE_DATA_DIR}"
    with open(path, "rb") as handle:
        assert hashlib.sha256(handle.read()).hexdigest() == skimage_registry[f"data/{filename}"]
    assert callable(getattr(skimage.data, name))


def test_loading_everything_offline_never_downloads(offline):
    for name in photograph_names():
        assert photograph(name).shape == PHOTO_SHAPES[name]
    for name in grayscale_names():
        assert grayscale_image(name).ndim == 2


def test_offline_fixture_catches_a_download(offline, monkeypatch):
    # Sanity check of the harness: a non-bundled image would hit the fetcher.
    monkeypatch.setitem(images.PHOTOGRAPH_FILES, "eagle", "eagle.png")
    assert not os.path.exists(os.path.join(SKIMAGE_DATA_DIR, "eagle.png"))
    with pytest.raises(DownloadAttempted):
        photograph("eagle")


@pytest.mark.parametrize("name", sorted(PHOTO_SHAPES))
def test_photograph_shape_dtype_read_only(name):
    image = photograph(name)
    assert image.shape == PHOTO_SHAPES[name] and image.dtype == np.uint8
    assert not image.flags.writeable
    with pytest.raises(ValueError):
        image[0, 0, 0] = 1
    assert np.array_equal(image, getattr(skimage.data, name)())


@pytest.mark.parametrize("name", sorted(GRAY_SHAPES))
def test_native_grayscale_is_uint8_over_255(name):
    image = grayscale_image(name)
    assert image.shape == GRAY_SHAPES[name] and image.dtype == np.float64
    assert not image.flags.writeable
    assert 0.0 <= image.min() and image.max() <= 1.0
    np.testing.assert_array_equal(image * 255.0, getattr(skimage.data, name)().astype(float))


def test_photograph_as_grayscale_is_bt709_luminance():
    gray = grayscale_image("coffee")
    rgb = photograph("coffee").astype(np.float64) / 255.0
    assert gray.shape == (400, 600) and gray.dtype == np.float64
    np.testing.assert_allclose(gray, rgb @ [0.2125, 0.7154, 0.0721], atol=1e-12)
    assert 0.0 <= gray.min() and gray.max() <= 1.0


def test_known_pixels_and_determinism():
    assert grayscale_image("camera") is grayscale_image("camera")
    assert photograph("astronaut")[0, 0].tolist() == skimage.data.astronaut()[0, 0].tolist()
    assert grayscale_image("moon")[0, 0] == pytest.approx(skimage.data.moon()[0, 0] / 255.0)


@pytest.mark.parametrize("bad", ["brain", "eagle", "Camera", "", None])
def test_unknown_grayscale_name_lists_valid_names(bad):
    with pytest.raises(ValueError, match="unknown grayscale image.*camera.*moon"):
        grayscale_image(bad)


def test_grayscale_only_name_is_not_a_photograph():
    with pytest.raises(ValueError, match="unknown photograph 'camera'.*astronaut"):
        photograph("camera")
