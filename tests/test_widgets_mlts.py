"""paperlib.widgets.mlts: the Alvarez 2015 explorer, driven headless through its controls.

Every test sets controls with ``.value =`` or clicks buttons, as a browser would, and checks that
the explorer's outputs (script, structure, image, PNG, status text) change as they should. The
default two-layer script at 128 px keeps each explorer well under a second; the random draws use
seed 1, a small script.
"""

import json

import ipywidgets
import numpy as np
import pytest

from paperlib.mlts import TEXELS, Layer, Script, render, sample_script
from paperlib.widgets.mlts import LAYER_FIELDS, MLTSExplorer, default_script, mlts_explorer, png_bytes

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
SIZE = 128
RANDOM_SEED = 1  # small and quick scripts at 128 px: seeds 1, 13, 14 (300, 1,500 and 140 objects)


@pytest.fixture
def explorer():
    return mlts_explorer(size=SIZE, random_seed=RANDOM_SEED)


def test_builds_a_panel_with_the_default_script_and_a_png(explorer):
    assert isinstance(explorer, MLTSExplorer) and isinstance(explorer.widget, ipywidgets.VBox)
    assert explorer.error is None and explorer.message == ""
    assert explorer.script == default_script(SIZE, SIZE) == explorer.controls_script()
    assert explorer.image_array.shape == (SIZE, SIZE, 3)
    assert 0 <= explorer.image_array.min() and explorer.image_array.max() <= 1
    assert bytes(explorer.image.value).startswith(PNG_MAGIC)
    np.testing.assert_array_equal(explorer.image_array, render(explorer.script))  # the library's image
    structure = explorer.structure
    assert np.all(structure.placed <= structure.tried) and structure.placed[1] > 0
    assert explorer.violations["exclusion"] == explorer.violations["inclusion"] == 0
    assert "L2 [rectangle, ellipse] Excl: placed" in explorer.summary and "L3 [" in explorer.summary
    assert "rule violations (shapely): exclusion 0, inclusion 0" in explorer.summary
    assert "geometry" in explorer.summary and "render" in explorer.summary
    assert explorer.calls == {"geometry": 1, "render": 1}
    assert explorer.n_layers.value == 3 and [value for _, value in explorer.layer.options] == [0, 1]
    assert tuple(explorer.texels.options) == TEXELS and explorer.palette.value == "chelsea"


def test_bad_construction_arguments_raise(tmp_path):
    with pytest.raises(ValueError, match="size"):
        mlts_explorer(size=0)
    with pytest.raises(ValueError, match="script"):
        mlts_explorer(script={"width": 64})
    with pytest.raises(ValueError, match="cannot read script"):
        mlts_explorer(script=tmp_path / "missing.json")


def test_every_script_field_has_a_control(explorer):
    controls = explorer._layer_controls()
    assert set(controls) == set(LAYER_FIELDS) == {field for field in Layer.__dataclass_fields__}
    assert set(explorer._render_controls()) == set(explorer.script.render.__dataclass_fields__)


def test_a_layer_parameter_changes_the_geometry_and_the_image(explorer):
    png, image, structure = bytes(explorer.image.value), explorer.image_array.copy(), explorer.structure
    placed = int(structure.placed[2])
    explorer.layer.value = 1  # L3
    assert explorer.max_objects.value == 6 and explorer.inclusion.value and explorer.calls["geometry"] == 1
    explorer.max_objects.value = 2
    assert explorer.error is None and explorer.script.layers[1].max_objects == 2
    assert explorer.structure is not structure and explorer.structure.placed[2] < placed
    assert not np.array_equal(image, explorer.image_array) and bytes(explorer.image.value) != png
    assert explorer.script.layers[0] == default_script(SIZE, SIZE).layers[0]  # L2 untouched
    explorer.v0[2].value = 0.0  # V_0 at infinity in the direction (64, 64)
    assert explorer.script.layers[1].v0 == (SIZE / 2, SIZE / 2, 0.0)
    explorer.max_objects.value = 6
    explorer.v0[2].value = 1.0
    assert explorer.structure is structure  # back to the first geometry: from the cache
    np.testing.assert_array_equal(explorer.image_array, image)
    assert "structure from the cache" in explorer.summary


def test_render_settings_reuse_the_structure(explorer):
    structure, image = explorer.structure, explorer.image_array.copy()
    explorer.render_seed.value = 7
    assert explorer.structure is structure and explorer.calls["geometry"] == 1
    assert not np.array_equal(image, explorer.image_array)
    recoloured = explorer.image_array.copy()
    explorer.palette.value = "rocket"
    assert explorer.structure is structure and not np.array_equal(recoloured, explorer.image_array)
    explorer.tessellation.value = True
    explorer.keep_father_inclusion.value = True
    explorer.light_distance.value = 40.0
    explorer.transparency.value = 0.7
    explorer.samples.value = 2
    assert explorer.structure is structure and explorer.calls == {"geometry": 1, "render": 8}
    assert explorer.script.render.tessellation and explorer.script.render.samples == 2
    np.testing.assert_array_equal(explorer.image_array, render(explorer.script))


def test_random_button_sets_every_control_from_the_sampled_script(explorer):
    explorer.random_button.click()
    sampled = sample_script(RANDOM_SEED, width=SIZE, height=SIZE, palette="chelsea")
    assert explorer.error is None and explorer.random_seed_used == RANDOM_SEED
    assert explorer.script == sampled == explorer.controls_script()
    assert explorer.n_layers.value == len(sampled.layers) + 1 and explorer.seed.value == sampled.seed
    assert explorer.render_seed.value == sampled.render.seed
    explorer.layer.value = len(sampled.layers) - 1
    last = sampled.layers[-1]
    assert tuple(explorer.texels.value) == last.texels and explorer.max_objects.value == last.max_objects
    assert tuple(part.value for part in explorer.v1) == last.v1 and explorer.vanishing.value == last.vanishing
    assert f"sample_script(rng={RANDOM_SEED})" in explorer.message and explorer.random_seed.value == RANDOM_SEED
    np.testing.assert_array_equal(explorer.image_array, render(sampled))
    assert explorer.violations["exclusion"] == explorer.violations["inclusion"] == 0
    explorer.palette.value = "coffee"
    explorer.random_seed.value = 13  # typing a seed draws from it, with the current palette
    assert explorer.script == sample_script(13, width=SIZE, height=SIZE, palette="coffee")
    explorer.random_button.click()  # the next seed
    assert explorer.random_seed.value == explorer.random_seed_used == 14


def test_save_then_load_round_trip(explorer, tmp_path):
    explorer.layer.value = 0
    explorer.aspect_ratio.value = 3.3
    explorer.render_seed.value = 5
    saved, image_hash = explorer.script, explorer.image_hash
    explorer.path.value = str(tmp_path / "texture.json")
    explorer.save_button.click()
    assert explorer.error is None and "saved" in explorer.message
    assert Script.load(tmp_path / "texture.json") == saved
    explorer.aspect_ratio.value = 1.0
    explorer.render_seed.value = 6
    assert explorer.image_hash != image_hash
    explorer.load_button.click()
    assert explorer.error is None and explorer.script == saved == explorer.controls_script()
    assert explorer.image_hash == image_hash and explorer.aspect_ratio.value == 3.3
    fresh = mlts_explorer(tmp_path / "texture.json")
    assert fresh.script == saved and fresh.image_hash == image_hash


def test_bad_files_are_messages_and_keep_the_state(explorer, tmp_path):
    script, image_hash = explorer.script, explorer.image_hash
    explorer.path.value = str(tmp_path / "missing.json")
    explorer.load_button.click()
    assert isinstance(explorer.error, ValueError) and "load failed" in explorer.message
    assert "#b00020" in explorer.status.value and "previous script is kept" in explorer.status.value
    assert explorer.script == script and explorer.image_hash == image_hash
    values = script.to_dict()
    values["layers"][0]["colour"] = "red"
    (tmp_path / "unknown.json").write_text(json.dumps(values))
    assert explorer.load(tmp_path / "unknown.json") is False and "unknown layer parameter" in explorer.message
    (tmp_path / "broken.json").write_text("{not json")
    assert explorer.load(tmp_path / "broken.json") is False and "not a JSON script" in explorer.message
    assert explorer.script == script == explorer.controls_script() and explorer.image_hash == image_hash
    assert explorer.save(tmp_path / "missing.json" / "inside" / "x.json") is True  # folders are created
    (tmp_path / "file").write_text("")
    assert explorer.save(tmp_path / "file" / "x.json") is False and "save failed" in explorer.message
    explorer.path.value = " "
    assert explorer.save() is False and "no path" in explorer.message


def test_invalid_controls_are_messages(explorer):
    script, image_hash = explorer.script, explorer.image_hash
    explorer.layer.value = 1
    explorer.texels.value = ()
    assert isinstance(explorer.error, ValueError) and "layer L3" in explorer.message
    assert "texel" in explorer.message and explorer.script == script and explorer.image_hash == image_hash
    explorer.save()  # the invalid controls cannot be saved
    assert "save failed" in explorer.message
    explorer.layer.value = 0  # the half-edited layer is kept while another is shown
    explorer.layer.value = 1
    assert explorer.texels.value == ()
    explorer.texels.value = ("ellipse", "regular_polygon")
    assert explorer.error is None and explorer.script == script
    for part in explorer.v1:
        part.value = 0.0
    assert "v1 (V_1) = (0, 0, 0)" in explorer.message
    explorer.v1[2].value = 1.0
    explorer.v1[0].value = explorer.v1[1].value = SIZE / 2
    assert explorer.error is None and explorer.script == script
    explorer.render_seed.value = -1
    assert "render seed" in explorer.message and explorer.image_hash == image_hash
    explorer.render_seed.value = 0
    assert explorer.error is None and explorer.script == script


def test_too_many_objects_is_a_message():
    explorer = mlts_explorer(size=SIZE, max_tried=100)  # L3 could try 30 fathers x 6 = 180 objects
    assert explorer.script is None and explorer.image_array is None and explorer.image_hash is None
    assert "layer L3 could try up to 180 objects" in explorer.message and "no image yet" in explorer.summary
    explorer.layer.value = 1
    explorer.max_objects.value = 3
    assert explorer.error is None and explorer.script.layers[1].max_objects == 3
    assert bytes(explorer.image.value).startswith(PNG_MAGIC)


def test_add_and_remove_layers(explorer):
    explorer.layer.value = 0
    explorer.add_layer_button.click()  # a new L3 between L2 and the old L3
    assert explorer.error is None and len(explorer.script.layers) == 3 and explorer.n_layers.value == 4
    assert explorer.layer.value == 1 and [label for label, _ in explorer.layer.options] == ["L2", "L3", "L4"]
    new = explorer.script.layers[1]
    assert new.inclusion and new.max_objects == 5
    assert new.max_diameter == pytest.approx(explorer.script.layers[0].max_diameter / 3)
    assert explorer.violations["inclusion"] == 0 and len(explorer.structure.placed) == 4
    explorer.remove_layer_button.click()
    assert explorer.script == default_script(SIZE, SIZE) and explorer.n_layers.value == 3
    explorer.n_layers.value = 2
    assert len(explorer.script.layers) == 1 and [value for _, value in explorer.layer.options] == [0]
    assert explorer.remove_layer() is False and "N_L >= 2" in explorer.message
    explorer.n_layers.value = 4
    assert len(explorer.script.layers) == 3 and explorer.error is None
    assert all(layer.inclusion for layer in explorer.script.layers[1:])


def test_a_loaded_script_with_a_file_palette_is_rejected_and_the_previous_one_kept(explorer, tmp_path):
    # issue 21: a script's palette names a bundled photograph only (no file, no URL), checked on loading
    script = explorer.script
    values = script.to_dict()
    values["render"]["palette"] = str(tmp_path / "no_such_image.png")
    (tmp_path / "palette.json").write_text(json.dumps(values))
    assert explorer.load(tmp_path / "palette.json") is False
    assert "bundled photograph" in explorer.message and "previous script is kept" in explorer.message
    assert explorer.script == script == explorer.controls_script()


def test_size_controls_and_plain_helpers(explorer):
    explorer.width.value = 96
    assert explorer.image_array.shape == (SIZE, 96, 3) and explorer.script.width == 96
    assert explorer.draw().axes[0].images[0].get_array().shape[:2] == (SIZE, 96)
    big = Script(1100, 32, 0, (Layer(max_objects=2, max_diameter=20.0),))
    assert explorer.set_script(big) and explorer.width.max >= 1100 and explorer.width.value == 1100
    assert png_bytes(np.zeros((4, 5, 3))).startswith(PNG_MAGIC)


# ---------------------------------------------------------------------------- saving the texture shown


def test_save_buttons_write_png_svg_and_json_of_the_texture_shown(tmp_path):
    from PIL import Image

    from paperlib.mlts import read_texture_svg, render_polygons

    explorer = mlts_explorer(size=SIZE, random_seed=RANDOM_SEED, output_dir=tmp_path / "out")
    assert explorer.output_dir.value == str(tmp_path / "out")
    explorer.output_name.value = "mine"
    for button in (explorer.save_png_button, explorer.save_svg_button, explorer.save_json_button):
        button.click()
        assert explorer.error is None, explorer.message
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["mine.json", "mine.png", "mine.svg"]
    assert "texture saved as" in explorer.status.value
    pixels = np.asarray(Image.open(tmp_path / "out" / "mine.png"))
    np.testing.assert_array_equal(pixels, np.round(explorer.image_array * 255).astype(np.uint8))
    assert Script.load(tmp_path / "out" / "mine.json") == explorer.script
    polygons, colours, transparency, groups = read_texture_svg(tmp_path / "out" / "mine.svg")
    assert len(polygons) == len(explorer.structure.objects)
    again = render_polygons(polygons, colours, (SIZE, SIZE), alphas=transparency, samples=explorer.script.render.samples)
    # 8-bit colours and opacities; the default script has at most 3 objects over a pixel (see test_mlts_svg.py)
    assert np.abs(again - explorer.image_array).max() <= 4.5 / 255


def test_saving_follows_the_controls_and_keeps_the_shown_texture(tmp_path):
    explorer = mlts_explorer(size=SIZE, random_seed=RANDOM_SEED, output_dir=tmp_path)
    explorer.render_seed.value = 5  # a re-render: the saved script follows what is shown
    explorer.output_dir.value = str(tmp_path / "second")
    explorer.save_json_button.click()
    assert Script.load(tmp_path / "second" / "texture.json").render.seed == 5
    explorer.texels.value = ()  # invalid controls (no texel): the shown (valid) texture is what is saved
    assert explorer.error is not None
    path = explorer.export("json", name="kept")
    assert path is not None and Script.load(path) == explorer.script


def test_saving_refuses_figures_light_spot_svg_and_bad_names(tmp_path):
    from paperlib.widgets.mlts import _repository_root, default_output_dir

    explorer = mlts_explorer(size=SIZE, random_seed=RANDOM_SEED, output_dir=tmp_path)
    root = _repository_root()
    assert root is not None and default_output_dir() == root / "build" / "mlts_explorer"
    explorer.output_dir.value = str(root / "figures" / "alvarez2015_explorer")
    before = sorted((root / "figures" / "alvarez2015_explorer").iterdir())
    explorer.save_png_button.click()
    assert explorer.error is not None and "figures" in explorer.message
    assert sorted((root / "figures" / "alvarez2015_explorer").iterdir()) == before
    with pytest.raises(ValueError, match="figures"):
        mlts_explorer(size=SIZE, output_dir=root / "figures")
    explorer.output_dir.value = str(tmp_path)
    explorer.light_distance.value = 40.0
    assert explorer.export("svg") is None and "light_distance" in explorer.message
    assert not (tmp_path / "texture.svg").exists()
    assert explorer.export("png") is not None  # the light spot is in the PNG
    for name in ("", "../escape", "a/b"):
        assert explorer.export("json", name=name) is None and "file name" in explorer.message
    assert explorer.export("gif") is None and "kind" in explorer.message
    assert sorted(p.name for p in tmp_path.iterdir()) == ["texture.png"]
