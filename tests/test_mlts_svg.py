"""SVG out and back for ML-textures (paperlib.mlts.svg; Alvarez et al. 2015, sections 3 and 5, Fig. 15).

The written SVG is read back with paperlib.geometry.read_svg (through read_texture_svg), repainted with
render_polygons and compared with the raster render of the same structure and render seed.

Where the bounds come from:

- Objects (opaque, or cut by their father): the geometry round-trips bit for bit (shortest repr of
  every double) and the painter samples the same points, so the only difference is the 8-bit colour
  of SVG (``#rrggbb``, which svgelements reads back in 8 bits): at most 0.5/255 per channel
  (analytic; measured 0.19-0.33/255 on sample_script seeds 1 and 2).
- Transparent objects: each composite ``c (1 - a) + colour a`` adds at most the colour's 0.5/255
  and the opacity's 0.5/255 (also 8-bit after reading), so a pixel under d objects is off by at
  most (0.5 + d)/255 (analytic; measured 0.36/255).
- Tessellation: the SVG holds the exact faces of the arrangement (shapely), the raster labels
  8-connected components of a grid ``samples`` times finer than the pixels. Compared on that grid
  (one sample per grid point, so anti-aliasing plays no part), the two differ only where the grid
  splits a face at a neck thinner than a grid step (the face takes the colour of the component
  most of its grid points fall in): measured 0.29-1.35% of grid points on sample_script seeds
  1, 2, 4, 5, 6 at 128 x 128; bound 3%. A shuffled colouring differs on most grid points (control).
  At pixel level the two also differ on cell edges, where a coverage painter (ours, and browsers)
  blends adjacent cells with the background ("conflation"); not asserted.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from paperlib.mlts import (
    coverage, read_texture_svg, render_polygons, render_structure, sample_script, sample_structure, texture_svg,
    write_texture_svg,
)
from paperlib.mlts.render import _render_palette, _tessellation_colours

SIZE = 128


def _textured(seed: int, **settings):
    script = sample_script(seed, width=SIZE, height=SIZE)
    render = dataclasses.replace(script.render, light_distance=0.0, tessellation=False, transparency=0.0,
                                 keep_father_inclusion=False)
    render = dataclasses.replace(render, **settings)
    return sample_structure(script.layers, SIZE, SIZE, seed=script.seed), render


def _repaint(structure, settings):
    polygons, colours, transparency, groups = read_texture_svg(texture_svg(structure, settings))
    image = render_polygons(polygons, colours, (structure.height, structure.width), alphas=transparency,
                            samples=settings.samples)
    return image, polygons, groups


@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("keep", [False, True])
def test_opaque_objects_read_back_within_8_bit_colour_rounding(seed, keep):
    structure, settings = _textured(seed, keep_father_inclusion=keep)
    raster = render_structure(structure, settings)
    image, polygons, groups = _repaint(structure, settings)
    assert np.abs(raster - image).max() <= 0.5 / 255 + 1e-9
    if not keep:  # one polygon per object, in painting order, grouped by layer
        assert len(polygons) == len(structure.objects)
        assert groups == [f"layer-{item.layer + 1}" for item in structure.objects]
        assert all(np.array_equal(p, item.polygon) for p, item in zip(polygons, structure.objects))


def test_transparent_objects_read_back_within_the_compositing_bound():
    structure, settings = _textured(1, transparency=0.8)
    raster = render_structure(structure, settings)
    image, polygons, _ = _repaint(structure, settings)
    depth = np.zeros((SIZE, SIZE))
    for item in structure.objects:
        row0, col0, mask = coverage(item.polygon, (SIZE, SIZE), samples=1)
        depth[row0:row0 + mask.shape[0], col0:col0 + mask.shape[1]] += np.ceil(mask)
    error = np.abs(raster - image).max(axis=2)
    assert np.all(error <= (0.5 + depth + 1) / 255 + 1e-9)  # +1: a pixel edge touched but its centre not
    text = texture_svg(structure, settings)
    assert "fill-opacity" in text  # transparency is written, not dropped


def test_tessellation_cells_are_polygons_coloured_as_the_raster():
    structure, settings = _textured(1, tessellation=True)
    text = texture_svg(structure, settings)
    assert '<g id="tessellation">' in text and 'fill-rule="evenodd"' in text
    polygons, colours, transparency, groups = read_texture_svg(text)
    assert set(groups) == {"tessellation"} and not transparency.any()
    samples = settings.samples
    cells, cell_colours = _tessellation_colours(structure, _render_palette(settings, None), samples,
                                                np.random.default_rng(settings.seed))
    fine = render_polygons([p * samples for p in polygons], colours, cells.shape, samples=1)
    differing = (np.abs(cell_colours[cells] - fine).max(axis=2) > 0.5 / 255 + 1e-9).mean()
    assert differing <= 0.03
    shuffled = render_polygons([p * samples for p in polygons], colours[np.random.default_rng(0).permutation(len(colours))],
                               cells.shape, samples=1)
    assert (np.abs(cell_colours[cells] - shuffled).max(axis=2) > 0.5 / 255 + 1e-9).mean() > 0.5


def test_same_inputs_same_svg_and_atomic_write(tmp_path):
    structure, settings = _textured(1)
    path = write_texture_svg(structure, settings, tmp_path / "sub" / "texture.svg")
    assert path.read_text() == texture_svg(structure, settings)
    assert [p.name for p in path.parent.iterdir()] == ["texture.svg"]


def test_light_spot_and_bad_inputs_are_refused(tmp_path):
    structure, settings = _textured(1, light_distance=50.0)
    with pytest.raises(ValueError, match="light_distance"):
        texture_svg(structure, settings)
    with pytest.raises(ValueError, match="light_distance"):
        write_texture_svg(structure, settings, tmp_path / "t.svg")
    assert not (tmp_path / "t.svg").exists()
    with pytest.raises(ValueError, match="structure"):
        texture_svg("structure", settings)
    with pytest.raises(ValueError, match="settings"):
        texture_svg(structure, {"seed": 1})
    with pytest.raises(TypeError, match="path"):
        write_texture_svg(structure, dataclasses.replace(settings, light_distance=0.0), 3)
    with pytest.raises(ValueError):
        read_texture_svg("<svg xmlns='http://www.w3.org/2000/svg'><rect width='1' height='1' fill='url(#g)'/></svg>x")
