"""Rendering of an ML-texture's object structure (Alvarez et al. 2015, section 5).

The function ``F`` of Definition 1 gives every object a colour; :func:`render_structure` draws
the objects layer by layer, the later in front (occlusion), with the rules of section 5:

- 5.1 colour palette: each object's colour is a pixel drawn uniformly from the palette image
  (:func:`load_palette`: a bundled scikit-image photograph, named in the script, or a local image
  file the caller loads and passes explicitly; never a URL);
- 5.2 transparency: each object draws a transparency uniformly in ``[0, transparency]``
  (0 opaque; the paper draws it "between 0 and 1", our bound is a parameter);
- 5.3 light spot: a point drawn uniformly inside the object carries a light at height
  ``light_distance`` above the image plane; a pixel at distance ``r`` from the point receives
  ``h^2 / (h^2 + r^2)`` of the palette colour (inverse square of the 3D distance, 1 at the point);
- tessellation (Fig. 15): instead of the objects, the connected components of the arrangement
  of their boundaries are coloured, each with its own palette draw (and no transparency or
  light, which belong to objects);
- "keep father inclusion" (section 3's second inclusion mode, 5.4): each object is drawn only
  inside its father.

All rendering randomness comes from the render seed, independent of the geometry seed, so one
structure can be recoloured (Fig. 18) and one colouring rule re-applied to a new structure
(Fig. 17). Anti-aliasing: ``samples x samples`` points per pixel (:mod:`paperlib.mlts.raster`).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import shapely
from skimage.measure import label

from .._checks import as_generator, budget, check_budget, integer_in_range
from ..datasets import photograph, photograph_names
from .raster import MAX_SAMPLES, coverage, paint
from .sampler import Structure, sample_structure
from .script import RenderSettings, Script

__all__ = ["load_palette", "render", "render_structure", "tessellation_cells"]

# Palette pixels kept at most (a random subset of larger images, drawn with a fixed seed).
PALETTE_PIXELS = 65536


#: Default budget of :func:`render` and :func:`render_structure`: the most anti-aliasing samples
#: ``width * height * samples**2`` of one image, 2**27 (the tessellation keys alone take 8 bytes each:
#: 1 GiB). Raise it with the ``max_samples`` keyword.
MAX_RENDER_SAMPLES = 2**27

#: Largest palette image read from a local file, in pixels (a decompression-bomb guard).
MAX_PALETTE_IMAGE_PIXELS = 50_000_000


def load_palette(source) -> np.ndarray:
    """The palette of section 5.1: the RGB colours (n, 3) in [0, 1] of an image's pixels.

    Parameters
    ----------
    source : str, os.PathLike or array_like
        A ``str`` names a bundled photograph (:func:`paperlib.datasets.photograph_names`) and
        nothing else: a string from a shared script can neither fetch a URL nor read a file.
        A local image file is passed explicitly as a :class:`pathlib.Path` (any ``os.PathLike``);
        an (h, w, 3) / (n, 3) array is used as it is.

    Returns
    -------
    ndarray of float, shape (n, 3)
        The RGB colours of the image's pixels (or the array's rows), in [0, 1].

    Raises
    ------
    ValueError
        For an unknown photograph name, a path that is not a local file, an unreadable or
        non-colour image, or an image above :data:`MAX_PALETTE_IMAGE_PIXELS` pixels.
    """
    if isinstance(source, str):
        if source not in photograph_names():
            raise ValueError(f"palette source {source[:100]!r} is not a bundled photograph; choose among "
                             f"{', '.join(photograph_names())}, or pass a local image as a pathlib.Path")
        pixels = photograph(source)
    elif isinstance(source, os.PathLike):
        pixels = _read_local_image(Path(source))
    else:
        try:
            pixels = np.asarray(source)
        except (TypeError, ValueError):
            raise ValueError("source (the palette) must be a photograph name, a local image path or an array of "
                             "colours") from None
    return _palette_colours(pixels, source)


def _read_local_image(path: Path) -> np.ndarray:
    """A local image file's pixels (the path must name an existing file: no URL, no other scheme)."""
    from PIL import Image

    if not path.is_file():
        raise ValueError(f"cannot read palette image {str(path)!r}: no such local file")
    try:
        with Image.open(path) as image:
            if image.width * image.height > MAX_PALETTE_IMAGE_PIXELS:
                raise ValueError(f"palette image {str(path)!r} has {image.width * image.height:,} pixels, above "
                                 f"MAX_PALETTE_IMAGE_PIXELS={MAX_PALETTE_IMAGE_PIXELS:,}")
            return np.asarray(image.convert("RGBA") if image.mode in ("LA", "PA", "RGBA") else image.convert("RGB"))
    except (OSError, Image.DecompressionBombError) as exc:
        raise ValueError(f"cannot read palette image {str(path)!r}: {exc}") from None


def _palette_colours(pixels: np.ndarray, source, name: str = "source") -> np.ndarray:
    if pixels.dtype.kind not in "biuf":
        raise ValueError(f"{name} (the palette) colours must be numbers, got dtype {pixels.dtype}")
    if pixels.ndim not in (2, 3) or pixels.shape[-1] not in (3, 4) or pixels.size == 0:
        raise ValueError(f"{name} (the palette) must be an RGB(A) image or an (n, 3) colour list, "
                         f"got shape {pixels.shape}: {source!r:.100}")
    colours = pixels.reshape(-1, pixels.shape[-1])[:, :3]
    if np.issubdtype(colours.dtype, np.integer):
        colours = colours / 255.0
    colours = np.asarray(colours, dtype=np.float64)
    if not np.all(np.isfinite(colours)) or colours.min() < 0 or colours.max() > 1:
        raise ValueError(f"{name} (the palette) colours must lie in [0, 1] (or be 8-bit), got {source!r:.100}")
    if len(colours) > PALETTE_PIXELS:
        colours = colours[np.random.default_rng(0).choice(len(colours), PALETTE_PIXELS, replace=False)]
    return colours


def _light_points(polygons, rng: np.random.Generator) -> np.ndarray:
    """A point drawn uniformly inside each polygon (rejection from its bounding box)."""
    points = np.empty((len(polygons), 2))
    for index, polygon in enumerate(polygons):
        geometry = shapely.Polygon(polygon)
        x0, y0, x1, y1 = geometry.bounds
        while True:
            x, y = rng.uniform(x0, x1), rng.uniform(y0, y1)
            if shapely.contains_xy(geometry, x, y):
                points[index] = (x, y)
                break
    return points


def tessellation_cells(structure: Structure, samples: int, rng=None, *,
                       max_samples: int = MAX_RENDER_SAMPLES) -> np.ndarray:
    """Cell labels (1..k) of the arrangement of object boundaries (Fig. 15), on a grid ``samples`` x finer.

    Each pixel of the fine grid carries the XOR of random 63-bit keys of the objects covering it,
    so equal keys mean the same set of objects; 8-connected components of equal keys are the
    cells. 8 and not 4: a thin face whose pixels touch only at corners stays one cell (with
    4-connectivity such faces split into pieces coloured independently: 65 cells for 55 shapely
    faces in a small test panel, against 55 with 8).

    Parameters
    ----------
    structure : Structure
        From :func:`paperlib.mlts.sample_structure`.
    samples : int
        Grid points per pixel side, in [1, :data:`paperlib.mlts.raster.MAX_SAMPLES`].
    rng : None, int or numpy.random.Generator
        Source of the objects' random keys (the labels do not depend on it, up to a 2**-63
        chance of two sets of objects sharing a key).
    max_samples : int
        Budget: the most grid points ``width * height * samples**2`` (default
        :data:`MAX_RENDER_SAMPLES`), checked before anything is allocated.

    Returns
    -------
    ndarray of int64, shape (height * samples, width * samples)

    Raises
    ------
    ValueError
        For a structure that is not a Structure, a bad ``samples`` or ``rng``, above ``max_samples``.

    References
    ----------
    Alvarez et al. 2015, section 5 ("tessellation") and Fig. 15.
    """
    if not isinstance(structure, Structure):
        raise ValueError(f"structure must be a paperlib.mlts.Structure, got {type(structure).__name__}")
    samples = integer_in_range(samples, "samples", 1, MAX_SAMPLES)
    _check_render_budget(structure.width, structure.height, samples, max_samples)
    rng = as_generator(rng)
    shape = (structure.height * samples, structure.width * samples)
    keys = np.zeros(shape, dtype=np.int64)
    object_keys = rng.integers(1, 2**63 - 1, size=len(structure.objects), dtype=np.int64)
    for item, key in zip(structure.objects, object_keys):
        row0, col0, mask = coverage(item.polygon * samples, shape, samples=1)
        inside = mask > 0.5
        keys[row0 : row0 + mask.shape[0], col0 : col0 + mask.shape[1]][inside] ^= key
    return label(keys, background=-1, connectivity=2)


def _tessellation_colours(structure: Structure, palette: np.ndarray, samples: int, rng):
    """The cells of :func:`tessellation_cells` and a palette colour per cell label (the renderer's draws)."""
    cells = tessellation_cells(structure, samples, rng)
    return cells, palette[rng.integers(len(palette), size=cells.max() + 1)]


def _tessellation(structure: Structure, palette: np.ndarray, samples: int, rng) -> np.ndarray:
    """Colour each cell of :func:`tessellation_cells` from the palette, averaged to pixels (anti-aliased)."""
    cells, colours = _tessellation_colours(structure, palette, samples, rng)
    fine = colours[cells]
    return fine.reshape(structure.height, samples, structure.width, samples, 3).mean(axis=(1, 3))


def _render_palette(settings: RenderSettings, palette) -> np.ndarray:
    """The colours a render uses: ``palette`` when given, else the script's photograph."""
    return load_palette(settings.palette) if palette is None else _palette_colours(np.asarray(palette), palette, "palette")


def _object_paint(structure: Structure, settings: RenderSettings, colours: np.ndarray, rng):
    """The renderer's per-object draws, in its order: colours, transparencies, light points; and the clips.

    Shared by :func:`render_structure` and the SVG writer (:mod:`paperlib.mlts.svg`), so both colour
    the same object the same way for one render seed.
    """
    polygons = [item.polygon for item in structure.objects]
    object_colours = colours[rng.integers(len(colours), size=len(polygons))]
    transparency = rng.uniform(0.0, settings.transparency, size=len(polygons))
    transparency[0] = 0.0  # the image rectangle is the opaque background
    lights, height = None, None
    if settings.light_distance > 0:
        lights, height = _light_points(polygons, rng), settings.light_distance
    clip = None
    if settings.keep_father_inclusion:
        clip = [None if item.father < 0 else structure.objects[item.father].polygon for item in structure.objects]
    return polygons, object_colours, transparency, lights, height, clip


def render_structure(structure: Structure, settings: RenderSettings, palette=None, *,
                     max_samples: int = MAX_RENDER_SAMPLES) -> np.ndarray:
    """Render an object structure with the rules of section 5 (module docstring).

    Parameters
    ----------
    structure : Structure
        From :func:`paperlib.mlts.sample_structure`.
    settings : RenderSettings
        Palette, render seed, transparency bound, light distance, tessellation, keep father
        inclusion, anti-aliasing samples.
    palette : array_like, optional
        Colours (n, 3) to use instead of loading ``settings.palette`` (already loaded palettes,
        or a local image: ``load_palette(pathlib.Path(...))``).
    max_samples : int
        Budget: the most anti-aliasing samples ``width * height * samples**2`` (default
        :data:`MAX_RENDER_SAMPLES`), checked before anything is allocated.

    Returns
    -------
    ndarray of float64, shape (height, width, 3)
        RGB in [0, 1].

    References
    ----------
    Alvarez et al. 2015, section 5 (5.1-5.4) and Figs. 15-18.
    """
    if not isinstance(structure, Structure):
        raise ValueError(f"structure must be a paperlib.mlts.Structure, got {type(structure).__name__}")
    if not isinstance(settings, RenderSettings):
        raise ValueError(f"settings must be RenderSettings, got {type(settings).__name__}")
    _check_render_budget(structure.width, structure.height, settings.samples, max_samples)
    colours = _render_palette(settings, palette)
    rng = np.random.default_rng(settings.seed)
    if settings.tessellation:
        return _tessellation(structure, colours, settings.samples, rng)
    polygons, object_colours, transparency, lights, height, clip = _object_paint(structure, settings, colours, rng)
    canvas = np.ones((structure.height, structure.width, 3))
    paint(canvas, polygons, object_colours, alphas=transparency, lights=lights, light_height=height, clip=clip,
          samples=settings.samples)
    return canvas


def render(script: Script, palette=None, *, max_samples: int = MAX_RENDER_SAMPLES) -> np.ndarray:
    """The image of a script: its structure (:func:`sample_structure`) rendered (:func:`render_structure`).

    The same script gives the same image bit for bit. ``palette`` and ``max_samples`` are those of
    :func:`render_structure`; the budget is checked before the structure is sampled.
    """
    if not isinstance(script, Script):
        raise ValueError(f"script must be a paperlib.mlts.Script, got {type(script).__name__}")
    _check_render_budget(script.width, script.height, script.render.samples, max_samples)
    structure = sample_structure(script.layers, script.width, script.height, seed=script.seed)
    return render_structure(structure, script.render, palette, max_samples=max_samples)


def _check_render_budget(width: int, height: int, samples: int, max_samples) -> None:
    check_budget(width * height * samples**2, budget(max_samples, "max_samples"), "max_samples",
                 "anti-aliasing samples (width x height x samples^2)")
