"""Interactive explorer of Alvarez 2015: every MLTS script parameter behind a control, live image.

:func:`mlts_explorer` builds an ipywidgets panel on top of :mod:`paperlib.mlts`: the paper's
"supervised mode" (section 4: "the user can guide the choice of parameters ... the proposed demo
allows the user to vary the initial parameters") next to its automatic mode. Every field of a
:class:`~paperlib.mlts.Script` has a control, in three tabs:

*geometry*: image ``width`` and ``height`` (px), the geometry seed ``Seed(L)``, the number of
layers ``N_L`` (counting the image rectangle, as the paper does) and **add layer** / **remove
layer** buttons (a new layer goes after the selected one);

*layer*: a selector of the layer ``L_m`` (m >= 2) and every :class:`~paperlib.mlts.Layer` field of
that layer: its texels (a multi-select of :data:`paperlib.mlts.TEXELS`), ``Max_O``, ``AspRat_O``,
``Max_D``, ``Max_T``, ``s_R``, ``Max_DR``, the ``Incl`` and ``Excl`` toggles, the orientation
points ``V_0`` and ``V_1`` as projective points ``(x, y, w)`` (``w = 0``: at infinity in the
direction ``(x, y)``; else the image point ``(x / w, y / w)``) and the vanishing reduction
``rF``;

*rendering*: every :class:`~paperlib.mlts.RenderSettings` field (section 5.4): the palette image
(a scikit-image photograph, :func:`paperlib.datasets.photograph_names`), the render seed, the
transparency bound, the light distance (0: no light spot), tessellation, "keep father
inclusion" and the anti-aliasing samples.

Above the tabs: **random** draws a whole script with :func:`paperlib.mlts.sample_script` (the
automatic mode; image size and palette are kept, "the only parameter which is left to the user is
the input color image") from the seed shown in ``random seed`` and sets every control from it;
each press uses the next seed, and typing a seed draws from it at once. **save script** and
**load script** write and read the JSON script at ``path`` (:meth:`Script.save`,
:meth:`Script.load`).

Below the image: **save PNG**, **save SVG** and **save JSON** write the texture shown (the last
valid script) as ``<name>.png`` (the image, 8 bits per channel), ``<name>.svg`` (its objects as
polygons, layers as groups, :func:`paperlib.mlts.write_texture_svg`; refused with a message for a
light-spot texture, which flat SVG fills cannot show) and ``<name>.json`` (its script) in the
``output folder`` (default :func:`default_output_dir`, under ``build/``). A folder inside the
repository's ``figures/`` is refused: only ``make reproduce`` writes there. Files are written
atomically.

The live image is the texture itself (PNG, at its pixel size); the status line gives, per layer,
the objects placed and tried, the rule violations counted independently by shapely
(:func:`paperlib.mlts.rule_violations`) and the seconds of geometry, check, render and PNG.

Design
------
*Plain methods.* Every control's effect is a method of :class:`MLTSExplorer`
(:meth:`~MLTSExplorer.update`, :meth:`~MLTSExplorer.randomize`, :meth:`~MLTSExplorer.save`,
:meth:`~MLTSExplorer.export`,
:meth:`~MLTSExplorer.load`, :meth:`~MLTSExplorer.add_layer`, :meth:`~MLTSExplorer.remove_layer`,
:meth:`~MLTSExplorer.set_script`), so tests and notebooks drive the panel without a browser.

*The script.* ``explorer.script`` is the :class:`Script` of the image shown, and
``explorer.image_array`` that image (RGB floats in [0, 1], bit for bit
``paperlib.mlts.render(explorer.script)``). :meth:`~MLTSExplorer.controls_script` builds the
script the controls describe (it raises ``ValueError`` when they are invalid). The layers' values
are kept as plain dictionaries (one per layer), so a half-edited, invalid layer is never lost
when another layer is selected.

*Errors are messages.* Control values a :class:`Layer`, :class:`RenderSettings` or
:class:`Script` rejects (no texel selected, a projective point (0, 0, 0), a negative seed), an
unreadable palette, a missing, malformed or rejected script file, a path that cannot be written:
the exception is kept in ``error``, its message is shown in red under the image, the image and
``script`` stay those of the previous valid script, and nothing is raised out of a method or a
callback. A random or loaded script that fails to render puts the previous script's controls back.

*Interactive size.* A script whose layers could try more than ``max_tried`` objects in one layer
(the product of ``Max_O`` down to that layer bounds the objects it tries) is refused with a
message rather than left running for minutes; the automatic mode never exceeds 4,000.

*Caching.* Structures are kept per geometry (size, seed, layers; the last
:data:`STRUCTURE_CACHE` of them) and palettes per name, so changing only the rendering settings
(palette, render seed, transparency, light, tessellation, clipping, samples) re-renders the same
:class:`~paperlib.mlts.Structure` object (:func:`paperlib.mlts.render_structure`) without sampling
again, and going back to an earlier geometry is immediate; ``calls`` counts the real runs.

*Randomness.* The geometry seed fixes the structure, the render seed the colours: same script,
same image, bit for bit. **random** is reproducible from the seed it shows.

*Headless.* The image is PNG bytes in an :class:`ipywidgets.Image`; :meth:`~MLTSExplorer.draw`
returns a matplotlib figure of it for notebooks.

Written by hand: the layout and the bookkeeping; every computation is a call to
:mod:`paperlib.mlts` (sampling, checking, rendering, scripts).

References
----------
Alvarez, L., Gousseau, Y., Morel, J.-M., Salgado, A. (2015). Exploring the space of abstract
textures by principles and random sampling. J. Math. Imaging Vis. 53, section 4 (layer
parameters, automatic and supervised modes, scripts) and 5.4 (rendering parameters).
"""

from __future__ import annotations

import hashlib
import io
import time
from collections import OrderedDict
from pathlib import Path

import numpy as np

from paperlib.datasets import photograph_names
from paperlib._atomic import atomic_path
from paperlib.mlts import (
    TEXELS,
    Layer,
    RenderSettings,
    Script,
    load_palette,
    render_structure,
    rule_violations,
    sample_script,
    sample_structure,
    write_texture_svg,
)
from paperlib.mlts.script import _pixels
from paperlib.widgets._base import ExplorerBase, check_file_root, expanded_path, uploaded_file, user_path

__all__ = ["EXPORT_FORMATS", "LAYER_FIELDS", "MAX_TRIED", "MLTSExplorer", "STRUCTURE_CACHE", "default_output_dir",
           "default_script", "mlts_explorer", "png_bytes"]

#: What the explorer's save buttons write (:meth:`MLTSExplorer.export`).
EXPORT_FORMATS = ("png", "svg", "json")

#: The fields of :class:`paperlib.mlts.Layer`, in the order of the "layer" tab.
LAYER_FIELDS = ("texels", "max_objects", "aspect_ratio", "max_diameter", "max_trials", "size_reduction",
                "max_reductions", "inclusion", "exclusion", "v0", "v1", "vanishing")
#: Largest number of objects one layer may try (product of Max_O down to it) in the explorer.
MAX_TRIED = 20_000
#: Structures kept in the cache (per image size, geometry seed and layers).
STRUCTURE_CACHE = 8
#: Initial slider ranges; a script with a value outside is shown by widening the slider.
SIZE_RANGE = (16, 1024)
LAYERS_RANGE = (2, 8)
NEW_LAYER_OBJECTS = 5


def default_script(width: int = 256, height: int = 256) -> Script:
    """The explorer's starting script: two layers showing exclusion, inclusion and a vanishing point.

    Layer 2: up to 30 rectangles and ellipses of aspect 2.5 and diameter 0.35 of the shorter side,
    oriented horizontally or vertically (points at infinity), not intersecting (``Excl``).
    Layer 3: up to 6 ellipses and regular polygons per father, a tenth of the shorter side, inside
    their father (``Incl``) and apart (``Excl``), turned toward the image centre and shrinking
    toward it (``rF = 0.5``). Rendered from "chelsea" with transparency up to 0.3.
    """
    short = min(width, height)
    first = Layer(texels=("rectangle", "ellipse"), max_objects=30, aspect_ratio=2.5, max_diameter=0.35 * short,
                  max_trials=20, size_reduction=0.8, max_reductions=5, inclusion=False, exclusion=True,
                  v0=(1.0, 0.0, 0.0), v1=(0.0, 1.0, 0.0), vanishing=0.0)
    second = Layer(texels=("ellipse", "regular_polygon"), max_objects=6, aspect_ratio=1.5,
                   max_diameter=0.1 * short, max_trials=20, size_reduction=0.8, max_reductions=5, inclusion=True,
                   exclusion=True, v0=(width / 2, height / 2, 1.0), v1=(width / 2, height / 2, 1.0),
                   vanishing=0.5)
    return Script(width, height, 0, (first, second), RenderSettings(palette="chelsea", seed=0, transparency=0.3))


def _repository_root() -> Path | None:
    """The checkout paperlib runs from (the folder holding ``pyproject.toml`` beside ``paperlib/``), if any."""
    root = Path(__file__).resolve().parents[2]
    return root if (root / "pyproject.toml").is_file() and (root / "paperlib").is_dir() else None


def default_output_dir() -> Path:
    """Where the explorer saves textures by default: ``build/mlts_explorer`` of the checkout.

    Returns
    -------
    Path
        ``<repository>/build/mlts_explorer`` when paperlib runs from a checkout, else
        ``build/mlts_explorer`` under the current folder. Never under ``figures/``, which only
        ``make reproduce`` writes.
    """
    root = _repository_root()
    return (root if root is not None else Path.cwd()) / "build" / "mlts_explorer"


def _check_output_dir(folder, name: str = "output folder") -> Path:
    """The output folder as a Path, refused (ValueError) when empty or inside the repository's ``figures/``;
    ``name``: the parameter (or the box, ``"output folder"``) it came from, for the messages."""
    if not str(folder).strip():
        raise ValueError(f"no {name} given: type a folder in 'output folder'")
    path = expanded_path(folder, name)
    root = _repository_root()
    figures = (root if root is not None else Path.cwd()) / "figures"
    resolved = path.resolve()
    if resolved == figures.resolve() or figures.resolve() in resolved.parents:
        raise ValueError(f"{name} {str(path)!r} is inside {figures}: only `make reproduce` writes figures/; "
                         "choose a folder under build/")
    return path


def _check_stem(name) -> str:
    name = str(name).strip()
    if not name or name in (".", "..") or any(c in name for c in '/\\:*?"<>|\0'):
        raise ValueError(f"file name {name!r} must be a plain name without folders or the characters /\\:*?\"<>|")
    return name


def png_bytes(image) -> bytes:
    """PNG bytes of an RGB image in [0, 1] (8 bits per channel, rounded)."""
    from PIL import Image

    pixels = np.round(np.clip(np.asarray(image, dtype=float), 0.0, 1.0) * 255).astype(np.uint8)
    buffer = io.BytesIO()
    Image.fromarray(pixels).save(buffer, format="PNG", compress_level=1)
    return buffer.getvalue()


def _layer_values(layer: Layer) -> dict:
    """A layer as the dictionary of raw values the explorer edits."""
    return {name: getattr(layer, name) for name in LAYER_FIELDS}


def _new_layer_values(before: dict) -> dict:
    """A new layer after ``before``: its fields, 5 objects per father, a third of its Max_D, inside it."""
    values = dict(before)
    diameter = before.get("max_diameter")
    if isinstance(diameter, (int, float)) and diameter > 0:
        values["max_diameter"] = max(2.0, float(diameter) / 3)
    values["max_objects"] = NEW_LAYER_OBJECTS
    values["inclusion"] = True
    return values


def _check_interactive(layers, max_tried: int) -> None:
    """ValueError when a layer could try more than ``max_tried`` objects."""
    fathers = 1
    for number, layer in enumerate(layers, start=2):
        fathers *= layer.max_objects
        if fathers > max_tried:
            raise ValueError(f"layer L{number} could try up to {fathers:,} objects (the product of Max_O down to it), "
                             f"more than this explorer's limit of {max_tried:,}: lower Max_O (or build the "
                             f"explorer with a larger max_tried)")


class MLTSExplorer(ExplorerBase):
    """Widgets and state of the Alvarez 2015 explorer (built by :func:`mlts_explorer`).

    Parameters
    ----------
    random_seed : int
        Seed of the first **random** draw (the next ones use the next integers).
    max_tried : int
        Largest number of objects one layer may try (product of Max_O down to it); bigger
        scripts are refused with a message.
    output_dir : str, Path or None
        Folder of the **save PNG / SVG / JSON** buttons (default :func:`default_output_dir`, under
        ``build/``; ``file_root`` when one is given); refused inside the repository's ``figures/``.
    file_root : str, os.PathLike or None
        None: the script path and output folder boxes name any path. A folder: they name only paths
        inside it (relative paths from it), as a served app must (:mod:`paperlib.apps`); the upload
        button reads scripts from the browser either way.

    Attributes
    ----------
    widget : ipywidgets.VBox
        The panel to ``display``.
    width, height, seed, n_layers, add_layer_button, remove_layer_button : ipywidgets controls
        Image size, geometry seed ``Seed(L)``, ``N_L`` (image rectangle included).
    layer : ipywidgets.Dropdown
        The layer the "layer" tab edits (value: index 0 for ``L_2``).
    texels, max_objects, aspect_ratio, max_diameter, max_trials, size_reduction, max_reductions,
    inclusion, exclusion, vanishing : ipywidgets controls
        The selected layer's fields (:class:`paperlib.mlts.Layer`).
    v0, v1 : tuple of three ipywidgets.FloatText
        The orientation points ``(x, y, w)``.
    palette, render_seed, transparency, light_distance, tessellation, keep_father_inclusion, samples :
    ipywidgets controls
        The :class:`paperlib.mlts.RenderSettings` fields.
    random_seed, random_button, path, save_button, load_button : ipywidgets controls
    upload : ipywidgets.FileUpload
        Loads a JSON script from the browser (the only way in for files outside ``file_root``).
    output_dir, output_name, save_png_button, save_svg_button, save_json_button : ipywidgets controls
        Where and under which name :meth:`export` writes the texture shown.
    exported : dict
        The files the latest :meth:`export` calls wrote, by format.
    image : ipywidgets.Image
        The texture, as PNG.
    status : ipywidgets.HTML
    script : Script or None
        The script of the image shown (the last valid one).
    structure : Structure or None
        Its object structure.
    image_array : ndarray (height, width, 3) or None
        Its RGB image in [0, 1].
    violations : dict or None
        :func:`paperlib.mlts.rule_violations` of ``structure``.
    origin : str
        Where the script shown came from ("initial script", "random, seed 3", "loaded from ...",
        "edited").
    random_seed_used : int or None
        Seed of the latest **random** draw.
    summary, message : str
    error : Exception or None
    times : dict
        Wall time (s) of the latest update's steps.
    calls : dict
        How many structures were sampled and images rendered.
    """

    def __init__(self, *, random_seed: int, max_tried: int, output_dir=None, file_root=None):
        import ipywidgets as w

        _check_counts(random_seed=(random_seed, 0), max_tried=(max_tried, 1))
        if output_dir is not None:
            if not isinstance(output_dir, (str, Path)):
                raise ValueError(f"output_dir must be a str, a Path or None, got {type(output_dir).__name__}")
        self._file_root = check_file_root(file_root)
        if output_dir is None:
            output_dir = default_output_dir() if self._file_root is None else self._file_root
        self._output_dir = self._folder(output_dir, "output_dir")
        self.exported: dict = {}

        self._dpi = 100
        self._max_tried = int(max_tried)
        self.script = self.structure = self.image_array = self.violations = self.error = None
        self.random_seed_used = None
        self.origin = "initial script"
        self.summary = self.message = ""
        self.times: dict = {}
        self.calls = {"geometry": 0, "render": 0}
        self._structures: OrderedDict = OrderedDict()
        self._palettes: dict = {}
        self._layer_values: list[dict] = []
        self._structure_cached = False
        self._quiet_depth = 0
        self._build_controls(w, random_seed)
        self._connect()

    # ------------------------------------------------------------------ layout

    def _build_controls(self, w, random_seed: int) -> None:
        wide = {"description_width": "120px"}
        text = w.Layout(width="250px")
        slider = dict(continuous_update=False, style=wide, layout=w.Layout(width="420px"))

        self.width = w.IntSlider(value=256, min=SIZE_RANGE[0], max=SIZE_RANGE[1], step=16, description="width (px)",
                                 **slider)
        self.height = w.IntSlider(value=256, min=SIZE_RANGE[0], max=SIZE_RANGE[1], step=16,
                                  description="height (px)", **slider)
        self.seed = w.IntText(value=0, description="geometry seed", style=wide, layout=text)
        self.n_layers = w.IntSlider(value=3, min=LAYERS_RANGE[0], max=LAYERS_RANGE[1], description="N_L (layers)",
                                    **slider)
        self.add_layer_button = w.Button(description="add layer", icon="plus",
                                         tooltip="insert a layer after the selected one")
        self.remove_layer_button = w.Button(description="remove layer", icon="minus",
                                            tooltip="remove the selected layer")

        self.layer = w.Dropdown(options=[("L2", 0)], value=0, description="layer", style=wide, layout=text)
        self.texels = w.SelectMultiple(options=list(TEXELS), value=("rectangle",), rows=len(TEXELS),
                                       description="texels T", style=wide, layout=w.Layout(width="320px"))
        self.max_objects = w.IntSlider(value=10, min=1, max=400, description="Max_O (per father)", **slider)
        self.aspect_ratio = w.FloatSlider(value=1.0, min=1.0, max=10.0, step=0.05, description="AspRat_O",
                                          **slider)
        self.max_diameter = w.FloatSlider(value=100.0, min=1.0, max=1024.0, step=1.0, description="Max_D (px)",
                                          readout_format=".1f", **slider)
        self.max_trials = w.IntSlider(value=20, min=1, max=100, description="Max_T (trials)", **slider)
        self.size_reduction = w.FloatSlider(value=0.8, min=0.05, max=0.99, step=0.01, description="s_R",
                                            readout_format=".3f", **slider)
        self.max_reductions = w.IntSlider(value=5, min=0, max=20, description="Max_DR", **slider)
        self.inclusion = w.Checkbox(value=False, description="Incl (inside the father)", indent=False)
        self.exclusion = w.Checkbox(value=False, description="Excl (no intersection)", indent=False)
        point = w.Layout(width="150px")
        self.v0 = tuple(w.FloatText(value=value, description=label, style={"description_width": "40px"},
                                    layout=point) for label, value in (("V_0 x", 1.0), ("y", 0.0), ("w", 0.0)))
        self.v1 = tuple(w.FloatText(value=value, description=label, style={"description_width": "40px"},
                                    layout=point) for label, value in (("V_1 x", 0.0), ("y", 1.0), ("w", 0.0)))
        self.vanishing = w.FloatSlider(value=0.0, min=0.0, max=3.0, step=0.05, description="rF (vanishing)",
                                       readout_format=".3f", **slider)

        self.palette = w.Dropdown(options=list(photograph_names()), value="chelsea", description="palette",
                                  style=wide, layout=text)
        self.render_seed = w.IntText(value=0, description="render seed", style=wide, layout=text)
        self.transparency = w.FloatSlider(value=0.0, min=0.0, max=1.0, step=0.01, description="transparency",
                                          readout_format=".3f", **slider)
        self.light_distance = w.FloatSlider(value=0.0, min=0.0, max=1024.0, step=1.0,
                                            description="light distance", readout_format=".1f", **slider)
        self.tessellation = w.Checkbox(value=False, description="tessellation", indent=False)
        self.keep_father_inclusion = w.Checkbox(value=False, description="keep father inclusion (clip)",
                                                indent=False)
        self.samples = w.IntSlider(value=4, min=1, max=16, description="samples (AA)", **slider)

        self.random_seed = w.IntText(value=int(random_seed), description="random seed", style=wide,
                                     layout=w.Layout(width="220px"))
        self.random_button = w.Button(description="random", icon="random", button_style="primary",
                                      tooltip="draw a whole script (automatic mode, sample_script)")
        self.path = w.Text(value="mlts_script.json", description="script path", style={"description_width": "80px"},
                           layout=w.Layout(width="340px"))
        self.save_button = w.Button(description="save script", icon="save")
        self.load_button = w.Button(description="load script", icon="folder-open")
        self.upload = w.FileUpload(accept=".json", multiple=False, description="upload script")
        self.image = w.Image(format="png", layout=w.Layout(max_width="100%"))
        self.status = w.HTML()
        self.output_dir = w.Text(value=str(self._output_dir), description="output folder",
                                 style={"description_width": "90px"}, layout=w.Layout(width="420px"))
        self.output_name = w.Text(value="texture", description="file name", style={"description_width": "70px"},
                                  layout=w.Layout(width="220px"))
        self.save_png_button = w.Button(description="save PNG", icon="image",
                                        tooltip="the texture shown, as <file name>.png in the output folder")
        self.save_svg_button = w.Button(description="save SVG", icon="pencil",
                                        tooltip="the texture shown as vector polygons, <file name>.svg")
        self.save_json_button = w.Button(description="save JSON", icon="file",
                                         tooltip="the script of the texture shown, <file name>.json")

        geometry = w.VBox([self.width, self.height, self.seed, self.n_layers,
                           w.HBox([self.add_layer_button, self.remove_layer_button])])
        layer = w.VBox([self.layer, self.texels, self.max_objects, self.aspect_ratio, self.max_diameter,
                        self.max_trials, self.size_reduction, self.max_reductions,
                        w.HBox([self.inclusion, self.exclusion]), w.HBox(list(self.v0)), w.HBox(list(self.v1)),
                        self.vanishing])
        rendering = w.VBox([self.palette, self.render_seed, self.transparency, self.light_distance,
                            self.tessellation, self.keep_father_inclusion, self.samples])
        self.tabs = w.Tab(children=[geometry, layer, rendering], titles=("geometry", "layer", "rendering"))
        self.widget = w.VBox([
            w.HBox([self.random_seed, self.random_button, self.path, self.save_button, self.load_button,
                    self.upload]),
            w.HBox([self.tabs, w.VBox([self.image], layout=w.Layout(padding="0 0 0 12px"))]),
            w.HBox([self.output_dir, self.output_name, self.save_png_button, self.save_svg_button,
                    self.save_json_button]),
            self.status,
        ])

    def _layer_controls(self) -> dict:
        """Each layer field's control(s)."""
        return {"texels": self.texels, "max_objects": self.max_objects, "aspect_ratio": self.aspect_ratio,
                "max_diameter": self.max_diameter, "max_trials": self.max_trials,
                "size_reduction": self.size_reduction, "max_reductions": self.max_reductions,
                "inclusion": self.inclusion, "exclusion": self.exclusion, "v0": self.v0, "v1": self.v1,
                "vanishing": self.vanishing}

    def _render_controls(self) -> dict:
        return {"palette": self.palette, "seed": self.render_seed, "transparency": self.transparency,
                "light_distance": self.light_distance, "tessellation": self.tessellation,
                "keep_father_inclusion": self.keep_father_inclusion, "samples": self.samples}

    def _connect(self) -> None:
        on = self._on_change
        for control in (self.width, self.height, self.seed, *self._render_controls().values()):
            on(control, self._edited)
        for name, control in self._layer_controls().items():
            for part in control if isinstance(control, tuple) else (control,):
                on(part, lambda name=name: self._edit_layer(name))
        on(self.layer, self._show_layer)
        on(self.n_layers, lambda: self.set_layer_count(int(self.n_layers.value)))
        on(self.random_seed, lambda: self.randomize(int(self.random_seed.value)))
        self.add_layer_button.on_click(lambda _: self.add_layer())
        self.remove_layer_button.on_click(lambda _: self.remove_layer())
        self.random_button.on_click(lambda _: self.randomize())
        self.save_button.on_click(lambda _: self.save())
        self.load_button.on_click(lambda _: self.load())
        self.upload.observe(lambda _: self.load_upload(), names="value")
        self.save_png_button.on_click(lambda _: self.export("png"))
        self.save_svg_button.on_click(lambda _: self.export("svg"))
        self.save_json_button.on_click(lambda _: self.export("json"))

    # ------------------------------------------------------------------ controls <-> script

    @staticmethod
    def _put(control, value) -> None:
        """Set a control, widening a slider's range when the value lies outside it."""
        if hasattr(control, "max") and hasattr(control, "min"):
            if value > control.max:
                control.max = value
            if value < control.min:
                control.min = value
        control.value = value

    def _read(self, name: str):
        control = self._layer_controls()[name]
        if isinstance(control, tuple):
            return tuple(float(part.value) for part in control)
        if name == "texels":
            return tuple(control.value)
        return control.value

    def _show_layer(self) -> None:
        """Load the selected layer's values into the layer tab (no re-render)."""
        values = self._layer_values[int(self.layer.value)]
        with self._quiet():
            for name, control in self._layer_controls().items():
                value = values[name]
                if isinstance(control, tuple):
                    for part, coordinate in zip(control, value):
                        part.value = float(coordinate)
                elif name == "texels":
                    control.value = tuple(kind for kind in value if kind in TEXELS)
                else:
                    self._put(control, value)

    def _refresh_layer_choices(self, selected: int) -> None:
        with self._quiet():
            count = len(self._layer_values)
            self.layer.options = [(f"L{number + 2}", number) for number in range(count)]
            self.layer.value = min(max(selected, 0), count - 1)
            self._put(self.n_layers, count + 1)
        self._show_layer()

    def _set_controls(self, script: Script) -> None:
        """Set every control from ``script`` without re-rendering."""
        with self._quiet():
            self._put(self.width, script.width)
            self._put(self.height, script.height)
            self.seed.value = script.seed
            settings = script.render
            if settings.palette not in self.palette.options:
                self.palette.options = list(self.palette.options) + [settings.palette]
            for name, control in self._render_controls().items():
                self._put(control, getattr(settings, name))
            self._layer_values = [_layer_values(layer) for layer in script.layers]
        self._refresh_layer_choices(int(self.layer.value) if self.layer.value is not None else 0)

    def controls_script(self) -> Script:
        """The script the controls describe.

        Returns
        -------
        Script
            The validated script of the current control values.

        Raises
        ------
        ValueError
            When a control value is rejected by :class:`Layer`, :class:`RenderSettings` or
            :class:`Script` (the message names the layer and the field).
        """
        layers = []
        for number, values in enumerate(self._layer_values, start=2):
            try:
                layers.append(Layer(**values))
            except (TypeError, ValueError) as error:
                raise ValueError(f"layer L{number}: {error}") from None
        values = {name: control.value for name, control in self._render_controls().items()}
        settings = RenderSettings(**values)
        return Script(int(self.width.value), int(self.height.value), int(self.seed.value), tuple(layers), settings)

    @property
    def image_hash(self) -> str | None:
        """SHA-256 of the current image's float64 bytes (None without an image)."""
        if self.image_array is None:
            return None
        return hashlib.sha256(np.ascontiguousarray(self.image_array, dtype=np.float64).tobytes()).hexdigest()

    # ------------------------------------------------------------------ actions

    def _edited(self) -> None:
        self.origin = "edited"
        self.update()

    def _edit_layer(self, name: str) -> None:
        self._layer_values[int(self.layer.value)][name] = self._read(name)
        self._edited()

    def update(self, notes=()) -> bool:
        """Sample (or reuse) the structure of the controls' script and render it.

        Parameters
        ----------
        notes : iterable of str, optional
            Lines shown before the outcome in ``message``.

        Returns
        -------
        bool
            Whether the image now shows the controls' script; on failure ``message`` says why,
            nothing is raised, and the previous image and ``script`` stay.
        """
        began = time.perf_counter()
        self.times = {}
        notes = list(notes)
        try:
            script = self.controls_script()
            _check_interactive(script.layers, self._max_tried)
            structure, violations = self._structure(script)
            colours = self._palette(script.render.palette)
            t0 = time.perf_counter()
            image = render_structure(structure, script.render, palette=colours)
            self.times["render"] = time.perf_counter() - t0
            self.calls["render"] += 1
        except Exception as error:  # shown in the widget, never raised out of a callback
            self.error = error
            kept = "; the image shows the previous script" if self.script is not None else ""
            self.message = "\n".join(notes + [f"invalid: {error}{kept}"])
            self._show_status()
            return False
        self.script, self.structure, self.violations, self.image_array = script, structure, violations, image
        self.error, self.message = None, "\n".join(notes)
        self._show(began)
        return True

    def _structure(self, script: Script):
        key = (script.width, script.height, script.seed, script.layers)
        self._structure_cached = key in self._structures
        if self._structure_cached:
            self._structures.move_to_end(key)
            self.times["geometry"] = 0.0
            return self._structures[key]
        t0 = time.perf_counter()
        structure = sample_structure(script.layers, script.width, script.height, seed=script.seed)
        self.times["geometry"] = time.perf_counter() - t0
        self.calls["geometry"] += 1
        t0 = time.perf_counter()
        violations = rule_violations(structure)
        self.times["check"] = time.perf_counter() - t0
        self._structures[key] = (structure, violations)
        while len(self._structures) > STRUCTURE_CACHE:
            self._structures.popitem(last=False)
        return structure, violations

    def _palette(self, name: str) -> np.ndarray:
        if name not in self._palettes:
            self._palettes[name] = load_palette(name)
        return self._palettes[name]

    def set_script(self, script: Script, origin: str = "script", notes=()) -> bool:
        """Show ``script``: set every control from it and render.

        If it cannot be rendered (an unreadable palette, too many objects), the message says why
        and the previous script's controls and image come back.

        Parameters
        ----------
        script : Script
            The script to show.
        origin : str, default "script"
            Where it came from, shown in the status and the figure title (``origin``).
        notes : iterable of str, optional
            Lines shown before the outcome in ``message``.

        Returns
        -------
        bool
            Whether ``script`` is now shown.
        """
        if not isinstance(script, Script):
            self.error = ValueError(f"script must be a paperlib.mlts.Script, got {type(script).__name__}")
            self.message = str(self.error)
            self._show_status()
            return False
        previous, previous_origin = self.script, self.origin
        self._set_controls(script)
        self.origin = origin
        if self.update(notes):
            return True
        error, message = self.error, self.message
        if previous is not None:
            self._set_controls(previous)
            self.origin = previous_origin
            self.update()
            message += "\nthe previous script is restored"
        self.error, self.message = error, message
        self._show_status()
        return False

    def randomize(self, seed: int | None = None) -> bool:
        """Draw a whole script in the automatic mode (:func:`paperlib.mlts.sample_script`) and show it.

        Parameters
        ----------
        seed : int, optional
            The draw's seed; by default the one shown in ``random seed`` for the first draw, then
            the next integer. The seed used is shown in ``random seed``. Image size and palette
            are kept from the controls.

        Returns
        -------
        bool
        """
        if seed is None:
            seed = int(self.random_seed.value) + (0 if self.random_seed_used is None else 1)
        with self._quiet():
            self.random_seed.value = int(seed)
        try:
            script = sample_script(int(seed), width=int(self.width.value), height=int(self.height.value),
                                   palette=self.palette.value)
        except Exception as error:
            self.error, self.message = error, f"random draw failed: {error}"
            self._show_status()
            return False
        self.random_seed_used = int(seed)
        return self.set_script(script, f"random (sample_script, seed {seed})",
                               [f"random script drawn with sample_script(rng={seed})"])

    def save(self, path=None) -> bool:
        """Write the controls' script as JSON to ``path`` (default: the ``path`` field).

        Parameters
        ----------
        path : str or os.PathLike, optional
            The JSON file to write (inside ``file_root`` when the explorer has one); default the
            ``path`` field.

        Returns
        -------
        bool
            Whether the file was written; an invalid script or an unwritable path is a message.
        """
        path = self.path.value if path is None else str(path)
        try:
            written = self.controls_script().save(user_path(path, self._file_root, "script path"))
        except (OSError, ValueError) as error:
            self.error, self.message = error, f"save failed: {error}"
            self._show_status()
            return False
        self.error, self.message = None, f"script saved to {written}"
        self._show_status()
        return True

    def load(self, path=None) -> bool:
        """Read the JSON script at ``path`` (default: the ``path`` field) and show it.

        Parameters
        ----------
        path : str or os.PathLike, optional
            The JSON script to read (inside ``file_root`` when the explorer has one); default the
            ``path`` field.

        Returns
        -------
        bool
            Whether it is shown; a missing file, invalid JSON or rejected keys are a message and
            leave the previous script in place.
        """
        path = self.path.value if path is None else str(path)
        return self._load_script(lambda: Script.load(user_path(path, self._file_root, "script path")), path)

    def load_upload(self) -> bool:
        """Read the JSON script last chosen in the **upload script** button and show it (as :meth:`load`).

        Returns
        -------
        bool
            Whether it is shown (False, with nothing changed, when no file is chosen).
        """
        chosen = uploaded_file(self.upload)
        if chosen is None:
            return False
        name, content = chosen
        return self._load_script(lambda: Script.from_json(content.decode("utf-8", errors="replace")), name)

    def _load_script(self, read, source: str) -> bool:
        """Show the script ``read()`` returns; a failure is a message and keeps the previous script."""
        try:
            script = read()
        except (OSError, ValueError) as error:
            self.error, self.message = error, f"load failed: {error}\nthe previous script is kept"
            self._show_status()
            return False
        return self.set_script(script, f"loaded from {source}", [f"script loaded from {source}"])

    def _folder(self, folder, name: str = "output folder") -> Path:
        """The output folder typed (inside ``file_root`` when there is one), never under ``figures/``."""
        if self._file_root is not None:
            folder = user_path(folder, self._file_root, name)
        return _check_output_dir(folder, name)

    def export(self, kind: str, folder=None, name=None) -> Path | None:
        """Save the texture shown as PNG, SVG or its JSON script in the output folder.

        Parameters
        ----------
        kind : {"png", "svg", "json"}
            PNG: the image shown (8 bits per channel). SVG: its objects as polygons
            (:func:`paperlib.mlts.write_texture_svg`; a light-spot texture is refused). JSON: its
            script (:meth:`Script.save`).
        folder : str or Path, optional
            Default: the ``output folder`` field. Created if missing; refused inside ``figures/``.
        name : str, optional
            File name without extension; default: the ``file name`` field.

        Returns
        -------
        Path or None
            The file written (also in ``exported[kind]``); None on failure, with the reason in
            ``message`` (nothing is raised, no partial file is left).
        """
        try:
            if kind not in EXPORT_FORMATS:
                raise ValueError(f"kind must be one of {EXPORT_FORMATS}, got {kind!r}")
            if self.script is None:
                raise ValueError("no texture to save yet")
            folder = self._folder(self.output_dir.value if folder is None else folder)
            path = folder / f"{_check_stem(self.output_name.value if name is None else name)}.{kind}"
            if kind == "png":
                from PIL import Image

                pixels = np.round(np.clip(self.image_array, 0.0, 1.0) * 255).astype(np.uint8)
                with atomic_path(path) as temporary:
                    Image.fromarray(pixels).save(temporary, format="PNG", optimize=True)
            elif kind == "svg":
                write_texture_svg(self.structure, self.script.render, path,
                                  palette=self._palette(self.script.render.palette))
            else:
                self.script.save(path)
        except (OSError, ValueError, TypeError) as error:
            self.error, self.message = error, f"save {kind} failed: {error}"
            self._show_status()
            return None
        self.exported[kind] = path
        self.error, self.message = None, f"texture saved as {path}"
        self._show_status()
        return path

    def set_layer_count(self, count: int) -> bool:
        """Set ``N_L`` (image rectangle included): add layers at the end or remove the last ones.

        Parameters
        ----------
        count : int
            The new ``N_L`` (>= 2).

        Returns
        -------
        bool
            Whether the image now shows the new layers (see :meth:`update`); False with a message for
            ``count < 2``.
        """
        count = int(count)
        if count < 2:
            self.error, self.message = ValueError("N_L must be >= 2"), "N_L must be >= 2 (the image and a layer)"
            self._show_status()
            return False
        while len(self._layer_values) + 1 < count:
            self._layer_values.append(_new_layer_values(self._layer_values[-1]))
        del self._layer_values[count - 1:]
        self._refresh_layer_choices(int(self.layer.value))
        self.origin = "edited"
        return self.update()

    def add_layer(self) -> bool:
        """Insert a layer after the selected one (its texels and shape, 5 objects per father, a third
        of its Max_D, inclusion on) and select it.

        Returns
        -------
        bool
            Whether the image now shows the new script (see :meth:`update`).
        """
        selected = int(self.layer.value)
        self._layer_values.insert(selected + 1, _new_layer_values(self._layer_values[selected]))
        self._refresh_layer_choices(selected + 1)
        self.origin = "edited"
        return self.update()

    def remove_layer(self) -> bool:
        """Remove the selected layer (not the last one left: N_L >= 2).

        Returns
        -------
        bool
            Whether the image now shows the new script (see :meth:`update`); False with a message
            when only one layer is left.
        """
        if len(self._layer_values) < 2:
            self.error = ValueError("cannot remove the only layer")
            self.message = "cannot remove the only layer: a texture needs N_L >= 2"
            self._show_status()
            return False
        selected = int(self.layer.value)
        del self._layer_values[selected]
        self._refresh_layer_choices(selected)
        self.origin = "edited"
        return self.update()

    # ------------------------------------------------------------------ output

    def _show(self, began: float) -> None:
        """The image as PNG into the image widget (no matplotlib: it is the texture itself)."""
        t0 = time.perf_counter()
        self.image.value = png_bytes(self.image_array)
        self.times["png"] = time.perf_counter() - t0
        self.times["total"] = time.perf_counter() - began
        self._show_status()

    def _summary_text(self) -> str:
        script, structure = self.script, self.structure
        if script is None:
            return "no image yet"
        settings = script.render
        lines = [f"script ({self.origin}): {script.width} x {script.height} px, N_L = {len(script.layers) + 1} "
                 f"(image + {len(script.layers)} layers), geometry seed {script.seed}; palette {settings.palette}, "
                 f"render seed {settings.seed}"]
        for number, layer in enumerate(script.layers, start=1):
            rules = " ".join(name for name, on in (("Incl", layer.inclusion), ("Excl", layer.exclusion)) if on)
            lines.append(f"L{number + 1} [{', '.join(layer.texels)}]{' ' + rules if rules else ''}: placed "
                         f"{int(structure.placed[number])} of {int(structure.tried[number])} tried")
        violations = self.violations
        lines.append(f"objects: {len(structure.objects) - 1} (+ the image rectangle); rule violations (shapely): "
                     f"exclusion {violations['exclusion']}, inclusion {violations['inclusion']}")
        times = ", ".join(f"{name} {value:.3f}" for name, value in self.times.items())
        lines.append(f"seconds: {times}" + (" (structure from the cache)" if self._structure_cached else ""))
        return "\n".join(lines)

    def draw(self, *, title: bool = True, figsize=None):
        """A matplotlib figure of the current image (for notebooks), titled with the script's origin.

        By default one image pixel per figure pixel at 100 dpi.

        Parameters
        ----------
        title : bool, default True
            Add a title: the script's origin, object count, ``N_L`` and palette.
        figsize : pair of float, optional
            Figure size in inches (default: the image's size at 100 dpi, plus room for the title).

        Returns
        -------
        matplotlib.figure.Figure
            The figure (not attached to pyplot).

        Raises
        ------
        ValueError
            When no image has been rendered yet.
        """
        from matplotlib.figure import Figure

        if self.image_array is None:
            raise ValueError("no image yet")
        height, width = self.image_array.shape[:2]
        if figsize is None:  # one image pixel per figure pixel at 100 dpi
            figsize = (width / 100, height / 100 + (0.4 if title else 0.0))
        figure = Figure(figsize=figsize)
        ax = figure.add_axes((0, 0, 1, 1 - (0.4 / figsize[1] if title else 0.0)))
        ax.imshow(self.image_array, interpolation="nearest")
        ax.set_axis_off()
        if title:
            script = self.script
            figure.suptitle(f"{self.origin}: {len(self.structure.objects) - 1} objects, N_L = "
                            f"{len(script.layers) + 1}, palette {script.render.palette}", fontsize=9,
                            y=1 - 0.1 / figsize[1], va="top")
        return figure


def _check_counts(**values) -> None:
    """A ValueError naming the parameter unless each ``name=(value, least)`` is an integer >= least."""
    for name, (value, low) in values.items():
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
            raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")


def mlts_explorer(script=None, *, size: int = 256, random_seed: int = 0, max_tried: int = MAX_TRIED,
                  output_dir=None, file_root=None) -> MLTSExplorer:
    """An interactive explorer of Alvarez 2015's multi-layer texture sampler.

    Builds the controls, shows ``script`` and returns the explorer; ``display(explorer)`` (or
    ``explorer.widget``) shows it. See the module docstring for the design.

    Parameters
    ----------
    script : Script, str, Path or None
        The first script: a :class:`paperlib.mlts.Script`, the path of a JSON script, or None for
        :func:`default_script` at ``size`` x ``size`` px.
    size : int
        Image side of the default script, px (ignored with a script).
    random_seed : int
        Seed of the first **random** draw (the next ones use the next integers).
    max_tried : int
        Largest number of objects one layer may try (product of Max_O down to it); bigger
        scripts are refused with a message.
    output_dir : str, Path or None
        Folder of the **save PNG / SVG / JSON** buttons (default :func:`default_output_dir`, under
        ``build/``; ``file_root`` when one is given); refused inside the repository's ``figures/``.
    file_root : str, os.PathLike or None
        None: the script path and output folder boxes name any path. A folder: they name only paths
        inside it (relative paths from it), as a served app must (:mod:`paperlib.apps`); the upload
        button reads scripts from the browser either way.

    Returns
    -------
    MLTSExplorer

    Raises
    ------
    ValueError
        For a bad argument or an unreadable script file (at construction; later, errors are
        shown in the widget).

    References
    ----------
    Alvarez et al. (2015), sections 4 (layer parameters, automatic and supervised modes, scripts)
    and 5.4 (rendering parameters).
    """
    _check_counts(size=(size, 1), random_seed=(random_seed, 0), max_tried=(max_tried, 1))
    _pixels(int(size), "size")
    if script is None:
        script = default_script(int(size), int(size))
    elif isinstance(script, (str, Path)):
        script = Script.load(script)
    elif not isinstance(script, Script):
        raise ValueError(f"script must be a paperlib.mlts.Script, a path or None, got {type(script).__name__}")
    explorer = MLTSExplorer(random_seed=int(random_seed), max_tried=int(max_tried), output_dir=output_dir,
                            file_root=file_root)
    explorer.set_script(script, "initial script")
    return explorer
