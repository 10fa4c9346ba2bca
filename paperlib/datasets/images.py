"""Test images bundled inside the scikit-image wheel, loaded without any network.

Many ``skimage.data`` functions (``brain``, ``kidney``, ``lily``, ``cells3d``,
``eagle``, ``skin``, ...) fetch their file with ``pooch`` on first use. Only the
images listed below are used here: their files are physically present in the
installed ``skimage/data`` directory with the SHA-256 hash recorded in skimage's
registry, so ``skimage.data`` returns them from the package directory (checked by
the tests, for scikit-image 0.26). Every other name is refused before skimage is
asked for anything.

Colour photographs (for palettes), ``(h, w, 3)`` uint8, as returned by skimage:

=====================  ============  =============================================
name                   size (h x w)  source and licence (skimage docstrings)
=====================  ============  =============================================
astronaut              512 x 512     Eileen Collins, NASA Great Images; public domain
chelsea                300 x 451     Chelsea the cat; CC0, Stefan van der Walt
coffee                 400 x 600     coffee cup; CC0, Rachel Michetti
hubble_deep_field      872 x 1000    Hubble eXtreme Deep Field, NASA; public domain
immunohistochemistry   512 x 512     IHC micrograph, CMMI; no known copyright restrictions
retina                 1411 x 1411   fundus photograph, M. Haggstrom, Wikimedia; CC0
rocket                 427 x 640     Falcon 9 / DSCOVR launch, SpaceX; public domain
=====================  ============  =============================================

Grayscale test images (for stippling), native 8-bit grayscale:

=====================  ============  =============================================
name                   size (h x w)  source and licence (skimage docstrings)
=====================  ============  =============================================
brick                  512 x 512     brick wall, CC0Textures; CC0
camera                 512 x 512     cameraman; CC0, Lav Varshney
cell                   660 x 550     quantitative phase image of a cell; CC0
clock                  300 x 400     motion-blurred clock; public domain, S. van der Walt
coins                  303 x 384     Greek coins, Brooklyn Museum; no known copyright restrictions
grass                  512 x 512     grass, DeviantArt; CC0
gravel                 512 x 512     gravel, CC0Textures; CC0
moon                   512 x 512     lunar surface; licence not stated by skimage
page                   191 x 384     scanned page; licence not stated by skimage
text                   172 x 448     "Corner.png", Wikipedia; public domain
=====================  ============  =============================================

:func:`grayscale_names` also offers every colour photograph, converted to
luminance with :func:`skimage.color.rgb2gray` (``0.2125 R + 0.7154 G + 0.0721 B``,
ITU-R BT.709 weights, on values scaled to [0, 1]). Native grayscale images are
converted from uint8 by dividing by 255.

Left out although bundled: synthetic or graphic images (``checkerboard``,
``colorwheel``, ``logo``, ``shepp_logan_phantom``, ``horse`` which is binary),
``microaneurysms`` (102 x 102, too small), and ``stereo_motorcycle`` (its licence
is not stated and its loader also reads a disparity map).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

__all__ = ["photograph_names", "photograph", "grayscale_names", "grayscale_image"]

# name -> file under skimage/data; the skimage.data function has the same name.
PHOTOGRAPH_FILES = {
    "astronaut": "astronaut.png",
    "chelsea": "chelsea.png",
    "coffee": "coffee.png",
    "hubble_deep_field": "hubble_deep_field.jpg",
    "immunohistochemistry": "ihc.png",
    "retina": "retina.jpg",
    "rocket": "rocket.jpg",
}

GRAYSCALE_FILES = {
    "brick": "brick.png",
    "camera": "camera.png",
    "cell": "cell.png",
    "clock": "clock_motion.png",
    "coins": "coins.png",
    "grass": "grass.png",
    "gravel": "gravel.png",
    "moon": "moon.png",
    "page": "page.png",
    "text": "text.png",
}


def photograph_names() -> list[str]:
    """Names of the bundled colour photographs, sorted (see the module docstring).

    Returns
    -------
    list of str
        The photograph names, sorted.
    """
    return sorted(PHOTOGRAPH_FILES)


def grayscale_names() -> list[str]:
    """Names accepted by :func:`grayscale_image`, sorted.

    The native grayscale images plus every colour photograph (converted to
    luminance).

    Returns
    -------
    list of str
        The names, sorted.
    """
    return sorted({**GRAYSCALE_FILES, **PHOTOGRAPH_FILES})


def _check_name(name, valid: list[str], kind: str) -> None:
    if not isinstance(name, str) or name not in valid:
        raise ValueError(f"unknown {kind} {name!r}: name must be one of {', '.join(valid)}")


@lru_cache(maxsize=None)
def _load_bundled(name: str) -> np.ndarray:
    """Load a whitelisted image through its ``skimage.data`` function, read-only."""
    import skimage.data

    image = np.array(getattr(skimage.data, name)())
    image.setflags(write=False)
    return image


def photograph(name: str) -> np.ndarray:
    """A bundled colour photograph.

    Parameters
    ----------
    name : str
        One of :func:`photograph_names`.

    Returns
    -------
    ndarray, shape (h, w, 3), dtype uint8
        RGB pixels, row 0 at the top, read-only (shared between calls).

    Raises
    ------
    ValueError
        If ``name`` is not a whitelisted photograph.
    """
    _check_name(name, photograph_names(), "photograph")
    return _load_bundled(name)


@lru_cache(maxsize=None)
def _grayscale(name: str) -> np.ndarray:
    from skimage.color import rgb2gray

    image = _load_bundled(name)
    if image.ndim == 3:
        gray = rgb2gray(image).astype(np.float64)
    else:
        gray = image.astype(np.float64) / 255.0
    gray.setflags(write=False)
    return gray


def grayscale_image(name: str) -> np.ndarray:
    """A bundled grayscale image, or a colour photograph converted to luminance.

    Parameters
    ----------
    name : str
        One of :func:`grayscale_names`.

    Returns
    -------
    ndarray, shape (h, w), dtype float64
        Intensities in [0, 1] (0 black, 1 white), row 0 at the top, read-only
        (shared between calls). Native 8-bit images are divided by 255; colour
        photographs go through :func:`skimage.color.rgb2gray`.

    Raises
    ------
    ValueError
        If ``name`` is not whitelisted.
    """
    _check_name(name, grayscale_names(), "grayscale image")
    return _grayscale(name)
