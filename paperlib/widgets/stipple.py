"""Interactive explorer of Kim 2009: learn a stipple library from tone textures, stipple an image.

:func:`stipple_explorer` builds an ipywidgets panel on top of :mod:`paperlib.stipple`. It runs
the paper's system (its Figure 2) in two steps, each behind a button:

*learn*: the example tone textures come either from a SYNTHETIC tone-map sheet
(:func:`paperlib.datasets.stipple.stipple_tone_sheet`: ``n tones`` patches of increasing darkness,
``sheet seed``, ``sheet block`` px per patch) cut into tones by section 3.1
(:func:`paperlib.stipple.extract_tone_map` with the block side ``N`` and the thresholds ``T1``,
``T2``), or from one SYNTHETIC tone texture (:func:`paperlib.datasets.stipple.stipple_tone_texture`
at ``tone``, ``sheet block`` px square). Every texture then goes through sections 3.2 (distribution
and marks), 3.4 (synthesis of a square distribution tile of side ``tile``, at most
``iterations`` iterations) and 4.1 (tone gray by pre-simulation):
:func:`paperlib.stipple.library.learn_stipple_library`.

*render*: the chosen image (a scikit-image photograph, or a horizontal gray ramp from black to
white), resized so that its longer side is ``render size`` pixels, is stippled with the library
(section 4: :meth:`StippleLibrary.render`, small chunks of fewer than ``min chunk`` pixels
removed, Fig. 11).

The figure shows the example tone textures (top row, lightest first, with their level and
gray), the synthesized distribution tiles (second row, with their final ACE, eq. 5), the input
image and its stippling. The status line gives the tones, levels, final ACE, the mean-tone error
of the rendering (:func:`tone_error`) and the wall times.

No hand-drawn stipple data are public: the exemplars are synthetic stand-ins for William M.
Andrews' tone maps, and the panel says so.

Design
------
*Plain methods.* Every control's effect is a method of :class:`StippleExplorer`
(:meth:`~StippleExplorer.learn`, :meth:`~StippleExplorer.render`), so tests and notebooks drive
the panel without a browser. The learn controls (source, sheet, N, T1, T2, iterations, tile,
seed) only mark the library stale (the status says so) until **learn** is pressed: learning takes
about two seconds at the defaults. The render controls (image, render size, min chunk) re-render
at once (a tenth of a second), as does **render**.

*Errors are messages.* A failing step (no tone region as large as the texture size, fewer than
two tones, a single tone texture asked to render an image) never raises out of a method or a
callback: the exception is kept in ``error``, shown in red under the figure, and the previous
library stays in place for rendering.

*Caching.* Sources (per source parameters), tone maps (per source and N, T1, T2), libraries
(per tone map, tile, iterations and seed) and resized images are kept, so going back to earlier
parameters is immediate; ``calls`` counts how often each step really ran.

*Randomness.* ``seed`` fixes the synthesis and the rendering (rendering uses ``seed`` too), so
the same controls give the same image bit for bit.

*Headless.* The figure is a plain :class:`matplotlib.figure.Figure` rendered to PNG bytes in an
:class:`ipywidgets.Image` (Agg, papermill and tests work); the latest is ``explorer.figure``.

Written by hand: the layout, the bookkeeping and :func:`tone_error`; every step of the method is
a call to :mod:`paperlib.stipple`.

References
----------
Kim, S., Maciejewski, R., Isenberg, T., Andrews, W. M., Chen, W., Sousa, M. C., Ebert, D. S.
(2009). Stippling by example. NPAR, Figure 2 (the system), sections 3.1-3.4 and 4.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass

import numpy as np

from paperlib._checks import as_generator, check_choice

from paperlib import datasets
from paperlib.widgets._base import ExplorerBase, figure_settings
from paperlib.datasets.stipple import stipple_tone_sheet, stipple_tone_texture
from paperlib.stipple import (
    extract_distribution,
    extract_marks,
    extract_tone_map,
    render_tone,
    synthesize_distribution,
)
from paperlib.stipple.library import StippleLibrary, learn_stipple_library

__all__ = ["IMAGES", "SOURCES", "TILE_SIZES", "StippleExplorer", "StippleSource", "gray_ramp", "render_input",
           "stipple_explorer", "tone_error"]

#: Images offered: scikit-image photographs (:func:`paperlib.datasets.grayscale_image`) and a ramp.
IMAGES = ("camera", "moon", "coins", "astronaut", "chelsea", "coffee", "brick", "grass", "page", "ramp")
#: Tone texture sources: the tone-map sheet cut by section 3.1, or one tone texture.
SOURCES = ("sheet", "texture")
#: Side of the synthesized distribution tiles offered (the paper: 256).
TILE_SIZES = (32, 48, 64, 96, 128, 192, 256)
#: Side of a sheet patch (or of the single texture) offered, px.
BLOCKS = (128, 160, 192, 256)
ITERATIONS_RANGE = (1, 30)
N_TONES_RANGE = (2, 10)
RENDER_SIZE_RANGE = (64, 1024)
BLOCK_SIZE_RANGE = (8, 64)
THRESHOLD_RANGE = (0.005, 0.2)
MIN_CHUNK_RANGE = (1, 50)
#: Gaussian blur of :func:`tone_error` (px): about one stipple spacing of the mid tones.
BLUR_SIGMA = 3.0


# ---------------------------------------------------------------------------- plain functions


def gray_ramp(size: int) -> np.ndarray:
    """A horizontal gray ramp, black (0) at the left to white (1) at the right, ``size // 2 x size``.

    Parameters
    ----------
    size : int
        Width in pixels, >= 2.

    Returns
    -------
    ndarray of float, shape (max(1, size // 2), size)
    """
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or size < 2:
        raise ValueError(f"size must be an integer >= 2, got {size!r}")
    return np.tile(np.linspace(0.0, 1.0, int(size)), (max(1, int(size) // 2), 1))


def render_input(name: str, size: int) -> np.ndarray:
    """The image ``name`` of :data:`IMAGES` as intensities in [0, 1], longer side ``size`` px.

    Photographs are resized with anti-aliasing (:func:`skimage.transform.resize`), keeping their
    aspect; ``"ramp"`` is :func:`gray_ramp`.

    Raises
    ------
    ValueError
        For an unknown name or ``size`` < 2.
    """
    check_choice(name, tuple(IMAGES), "image")
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or size < 2:
        raise ValueError(f"size must be an integer >= 2, got {size!r}")
    if name == "ramp":
        return gray_ramp(int(size))
    from skimage.transform import resize

    gray = datasets.grayscale_image(name)
    scale = size / max(gray.shape)
    shape = (max(2, round(gray.shape[0] * scale)), max(2, round(gray.shape[1] * scale)))
    return np.clip(resize(gray, shape, anti_aliasing=True), 0.0, 1.0)


def tone_error(stipples, image, sigma: float = BLUR_SIGMA) -> float:
    """Mean absolute difference between a stippling and its input after a Gaussian blur.

    Both the paper fraction of the stippling (``1 - ink``) and the input intensities are blurred
    with :func:`skimage.filters.gaussian` of standard deviation ``sigma`` px (reflecting
    borders), which averages the stipples into a tone as the eye does at a distance; 0 is a
    perfect tone reproduction, 0.5 a white image for a black one on average.

    Parameters
    ----------
    stipples : array_like of bool, 2-D
        The stippling, ``True`` = ink.
    image : array_like of float, same shape
        The input intensities in [0, 1] (0 black).
    sigma : float
        Blur in pixels, > 0.

    Returns
    -------
    float
    """
    from skimage.filters import gaussian

    stipples, image = np.asarray(stipples), np.asarray(image, dtype=float)
    if stipples.shape != image.shape or stipples.ndim != 2:
        raise ValueError(f"stipples and image must be 2-D of one shape, got {stipples.shape} and {image.shape}")
    if not sigma > 0:
        raise ValueError(f"sigma must be > 0, got {sigma!r}")
    paper = 1.0 - stipples.astype(float)
    return float(np.mean(np.abs(gaussian(paper, sigma, mode="reflect") - gaussian(image, sigma, mode="reflect"))))


# ---------------------------------------------------------------------------- state


@dataclass(frozen=True, eq=False)
class StippleSource:
    """The example tone textures the explorer learns from.

    Attributes
    ----------
    kind : {"sheet", "texture"}
    image : ndarray of bool
        The synthetic sheet, or the single texture (``True`` = ink).
    textures : list of ndarray of bool
        The tone textures, lightest first (extracted by section 3.1 for a sheet).
    gray_levels : ndarray of float
        Measured gray of every texture (1 = white).
    truth_grays : ndarray of float
        The generator's requested grays (``1 - tone``) of the sheet's patches, or of the texture.
    tone_map : ToneMap or None
        Section 3.1's result for a sheet.
    description : str
    """

    kind: str
    image: np.ndarray
    textures: list
    gray_levels: np.ndarray
    truth_grays: np.ndarray
    tone_map: object
    description: str


def _single_tone_library(texture, *, size: int, iterations: int, rng) -> StippleLibrary:
    """Sections 3.2, 3.4 and 4.1 for one texture (a library of one tone cannot render an image)."""
    rng = as_generator(rng)
    distribution = extract_distribution(texture)
    synthesis = synthesize_distribution(distribution.distribution, size=size, iterations=iterations, rng=rng)
    marks = extract_marks(texture, distribution.level)
    side = synthesis.texture.shape[0]
    rendered = render_tone(np.tile(synthesis.texture, (3, 3)), marks, rng)[side:2 * side, side:2 * side]
    return StippleLibrary([texture], [distribution], [synthesis], [marks], np.array([1.0 - rendered.mean()]))


# ---------------------------------------------------------------------------- the explorer


class StippleExplorer(ExplorerBase):
    """Widgets and state of the Kim 2009 explorer (built by :func:`stipple_explorer`).

    Parameters
    ----------
    source : {"sheet", "texture"}
        A synthetic tone-map sheet cut into tones by section 3.1, or one synthetic tone texture.
    sheet_seed : int
        Seed of the exemplar generator.
    n_tones : int
        Patches of the sheet, in [2, 10] (default 8, the inner tones of Andrews' map).
    block : int
        Side of a sheet patch or of the single texture, px: one of 128, 160, 192, 256.
    tone : float
        Ink fraction of the single texture, in [0.05, 0.95].
    N, T1, T2 : int, float, float
        Section 3.1's block side (in [8, 64]) and thresholds (in [0.005, 0.2]).
    iterations : int
        Maximum synthesis iterations, in [1, 30] (paper: 30).
    tile : int
        Side of the synthesized tiles, one of :data:`TILE_SIZES` (paper: 256).
    seed : int
        Seed of the synthesis and the rendering.
    image : str
        One of :data:`IMAGES`.
    render_size : int
        Longer side of the rendered image, in [64, 1024].
    min_chunk : int
        Chunks of fewer pixels are removed (Fig. 11), in [1, 50] (1: none).
    workers : int
        Processes learning the tones in parallel (:func:`learn_stipple_library`); the library does
        not depend on it.
    figsize : pair of float
        Figure size in inches.
    dpi : int
        Resolution of the figure shown in the widget.

    Attributes
    ----------
    widget : ipywidgets.VBox
        The panel to ``display``.
    source, sheet_seed, n_tones, block, tone, N, T1, T2, iterations, tile, seed, image_name, render_size,
    min_chunk, learn_button, render_button : ipywidgets controls
        See :func:`stipple_explorer`.
    image : ipywidgets.Image
        The figure, as PNG.
    status : ipywidgets.HTML
        Tones, levels, ACE, error, times and messages.
    stipple_source : StippleSource or None
        The tone textures of the current library.
    library : StippleLibrary or None
        The current library (kept when a later learn fails).
    rendering : StippleRendering or None
        The latest rendering (None after a failed render).
    input_image : ndarray or None
        The image of the latest rendering, in [0, 1].
    error_after_blur : float or None
        :func:`tone_error` of the latest rendering.
    figure : matplotlib.figure.Figure or None
    summary : str
        The status text, plain.
    message : str
        Errors and notes of the latest action ("" if none).
    error : Exception or None
        The exception of the latest failed step.
    stale : bool
        True when the learn controls differ from those of the current library.
    times : dict
        Wall time (s) of the latest steps.
    calls : dict
        How many times each step really ran (source, tone_map, learn, render): shows the caching.
    """

    def __init__(self, *, source, sheet_seed, n_tones, block, tone, N, T1, T2, iterations, tile, seed, image,
                 render_size, min_chunk, workers, figsize, dpi):
        import ipywidgets as w

        _check_choice(source, SOURCES, "source")
        _check_choice(block, BLOCKS, "block")
        _check_choice(tile, TILE_SIZES, "tile")
        _check_choice(image, IMAGES, "image")
        for name, value, (low, high) in (("sheet_seed", sheet_seed, (0, 2**31 - 1)), ("seed", seed, (0, 2**31 - 1)),
                                         ("n_tones", n_tones, N_TONES_RANGE), ("N", N, BLOCK_SIZE_RANGE),
                                         ("iterations", iterations, ITERATIONS_RANGE),
                                         ("render_size", render_size, RENDER_SIZE_RANGE),
                                         ("min_chunk", min_chunk, MIN_CHUNK_RANGE), ("workers", workers, (1, 64))):
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not low <= value <= high:
                raise ValueError(f"{name} must be an integer in [{low}, {high}], got {value!r}")
        for name, value, (low, high) in (("tone", tone, (0.05, 0.95)), ("T1", T1, THRESHOLD_RANGE),
                                         ("T2", T2, THRESHOLD_RANGE)):
            if isinstance(value, bool) or not isinstance(value, (int, float, np.number)) or not low <= value <= high:
                raise ValueError(f"{name} must be a number in [{low}, {high}], got {value!r}")
        sheet_seed, n_tones, block, N, iterations = int(sheet_seed), int(n_tones), int(block), int(N), int(iterations)
        tile, seed, render_size, min_chunk = int(tile), int(seed), int(render_size), int(min_chunk)
        tone, T1, T2 = float(tone), float(T1), float(T2)
        self._figsize, self._dpi = figure_settings(figsize, dpi)
        self._workers = int(workers)
        self.stipple_source = self.library = self.rendering = self.input_image = None
        self.error_after_blur = self.figure = self.error = None
        self.summary = self.message = ""
        self.stale = True
        self.times: dict = {}
        self.calls = {"source": 0, "tone_map": 0, "learn": 0, "render": 0}
        self._sources: dict = {}
        self._libraries: dict = {}
        self._images: dict = {}
        self._library_key = None
        self._quiet_depth = 0
        self._build_controls(w, source, sheet_seed, n_tones, block, tone, N, T1, T2, iterations, tile, seed, image,
                             render_size, min_chunk)
        self._connect()

    # ------------------------------------------------------------------ layout

    def _build_controls(self, w, source, sheet_seed, n_tones, block, tone, N, T1, T2, iterations, tile, seed,
                        image, render_size, min_chunk):
        wide = {"description_width": "initial"}
        box = w.Layout(width="170px")
        self.source = w.ToggleButtons(options=[("tone-map sheet (sec. 3.1)", "sheet"),
                                               ("one tone texture", "texture")],
                                      value=source, description="SYNTHETIC exemplar", style=wide)
        self.sheet_seed = w.BoundedIntText(value=sheet_seed, min=0, max=2**31 - 1, description="sheet seed",
                                           style=wide, layout=box)
        self.n_tones = w.IntSlider(value=n_tones, min=N_TONES_RANGE[0], max=N_TONES_RANGE[1], description="n tones",
                                   continuous_update=False, style=wide)
        self.block = w.Dropdown(options=list(BLOCKS), value=block, description="sheet block (px)", style=wide,
                                layout=w.Layout(width="190px"))
        self.tone = w.FloatSlider(value=tone, min=0.05, max=0.95, step=0.01, description="tone (ink)",
                                  continuous_update=False, style=wide)
        self.N = w.IntSlider(value=N, min=BLOCK_SIZE_RANGE[0], max=BLOCK_SIZE_RANGE[1], description="N (block)",
                             continuous_update=False, style=wide)
        self.T1 = w.FloatSlider(value=T1, min=THRESHOLD_RANGE[0], max=THRESHOLD_RANGE[1], step=0.005,
                                description="T1", readout_format=".3f", continuous_update=False, style=wide)
        self.T2 = w.FloatSlider(value=T2, min=THRESHOLD_RANGE[0], max=THRESHOLD_RANGE[1], step=0.005,
                                description="T2", readout_format=".3f", continuous_update=False, style=wide)
        self.iterations = w.IntSlider(value=iterations, min=ITERATIONS_RANGE[0], max=ITERATIONS_RANGE[1],
                                      description="iterations", continuous_update=False, style=wide)
        self.tile = w.Dropdown(options=list(TILE_SIZES), value=tile, description="tile (px)", style=wide,
                               layout=w.Layout(width="150px"))
        self.seed = w.BoundedIntText(value=seed, min=0, max=2**31 - 1, description="seed", style=wide, layout=box)
        self.learn_button = w.Button(description="learn", icon="cogs", button_style="primary")
        self.image_name = w.Dropdown(options=list(IMAGES), value=image, description="image", style=wide,
                                     layout=w.Layout(width="190px"))
        self.render_size = w.IntSlider(value=render_size, min=RENDER_SIZE_RANGE[0], max=RENDER_SIZE_RANGE[1],
                                       step=32, description="render size", continuous_update=False, style=wide)
        self.min_chunk = w.IntSlider(value=min_chunk, min=MIN_CHUNK_RANGE[0], max=MIN_CHUNK_RANGE[1],
                                     description="min chunk", continuous_update=False, style=wide)
        self.render_button = w.Button(description="render", icon="paint-brush")
        self.image = w.Image(format="png", layout=w.Layout(max_width="100%"))
        self.status = w.HTML()
        self.widget = w.VBox([
            w.HBox([self.source]),
            w.HBox([self.sheet_seed, self.n_tones, self.block, self.tone]),
            w.HBox([self.N, self.T1, self.T2]),
            w.HBox([self.iterations, self.tile, self.seed, self.learn_button]),
            w.HBox([self.image_name, self.render_size, self.min_chunk, self.render_button]),
            self.image,
            self.status,
        ])

    def _learn_controls(self):
        return (self.source, self.sheet_seed, self.n_tones, self.block, self.tone, self.N, self.T1, self.T2,
                self.iterations, self.tile, self.seed)

    def _connect(self):
        on = self._on_change
        for control in self._learn_controls():
            on(control, self._mark_stale)
        for control in (self.image_name, self.render_size, self.min_chunk):
            on(control, self.render)
        self.learn_button.on_click(lambda _: self.learn())
        self.render_button.on_click(lambda _: self.render())

    # ------------------------------------------------------------------ keys

    def _source_key(self) -> tuple:
        if self.source.value == "sheet":
            return ("sheet", int(self.sheet_seed.value), int(self.n_tones.value), int(self.block.value))
        return ("texture", int(self.sheet_seed.value), round(float(self.tone.value), 4), int(self.block.value))

    def _tone_map_key(self) -> tuple:
        if self.source.value == "sheet":
            return self._source_key() + (int(self.N.value), round(float(self.T1.value), 4),
                                         round(float(self.T2.value), 4))
        return self._source_key()

    def learn_key(self) -> tuple:
        """The parameters a library depends on (the library cache's key).

        Returns
        -------
        tuple
            The source and tone-map controls (sheet seed, tones, block or tone, and N, T1, T2 for a
            sheet), then tile size, iterations and seed.
        """
        return self._tone_map_key() + (int(self.tile.value), int(self.iterations.value), int(self.seed.value))

    def _mark_stale(self):
        self.stale = self.learn_key() != self._library_key
        self.message = "learn parameters changed: press learn" if self.stale else ""
        self.error = None
        self._show_status()

    # ------------------------------------------------------------------ actions

    def learn(self) -> bool:
        """Learn the library of the current learn controls (cached), then render.

        Returns
        -------
        bool
            Whether a library was learnt and the image rendered; on failure ``message`` says
            why (nothing raised) and the previous library stays.
        """
        began = time.perf_counter()
        self.times, self.error, notes = {}, None, []
        key = self.learn_key()
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                source = self._stipple_source()
                if key not in self._libraries:
                    t0 = time.perf_counter()
                    self._libraries[key] = self._learn_library(source)
                    self.times["learn"] = time.perf_counter() - t0
                    self.calls["learn"] += 1
                else:
                    notes.append("library from the cache")
            notes += [f"warning: {w.message}" for w in caught if not issubclass(w.category, RuntimeWarning)]
        except Exception as error:  # shown in the widget, never raised out of a callback
            self.error = error
            self.message = "\n".join(notes + [f"learn failed: {type(error).__name__}: {error}"]
                                     + (["the previous library is kept"] if self.library is not None else []))
            self.stale = True
            self._show(began)
            return False
        self.stipple_source, self.library, self._library_key = source, self._libraries[key], key
        self.stale = False
        return self._render(began, notes)

    def render(self) -> bool:
        """Stipple the chosen image with the current library (section 4).

        Returns
        -------
        bool
            Whether a rendering was produced; on failure ``message`` says why.
        """
        self.times, self.error = {}, None
        notes = ["learn parameters changed: press learn (rendering with the previous library)"] if self.stale \
            and self.library is not None else []
        return self._render(time.perf_counter(), notes)

    def _render(self, began: float, notes: list) -> bool:
        self.rendering = self.error_after_blur = None
        try:
            if self.library is None:
                raise ValueError("no stipple library yet: press learn")
            if len(self.library) < 2:
                raise ValueError("a single tone texture has no tone map: rendering an image needs at least two "
                                 "tones (choose the tone-map sheet); its texture and tile are shown")
            key = (self.image_name.value, int(self.render_size.value))
            if key not in self._images:
                self._images[key] = render_input(*key)
            self.input_image = self._images[key]
            t0 = time.perf_counter()
            self.rendering = self.library.render(self.input_image, min_chunk=int(self.min_chunk.value),
                                                 rng=int(self.seed.value))
            self.times["render"] = time.perf_counter() - t0
            self.calls["render"] += 1
            self.error_after_blur = tone_error(self.rendering.image, self.input_image)
        except Exception as error:
            self.error = error
            notes = notes + [f"render failed: {type(error).__name__}: {error}"]
        self.message = "\n".join(notes)
        self._show(began)
        return self.error is None

    # ------------------------------------------------------------------ steps (cached)

    def _stipple_source(self) -> StippleSource:
        key = self._tone_map_key()
        if key in self._sources:
            return self._sources[key]
        kind, sheet_seed, _, block = self._source_key()
        raw_key = self._source_key()
        t0 = time.perf_counter()
        if raw_key not in self._sources:
            if kind == "sheet":
                made = stipple_tone_sheet(n_tones=int(self.n_tones.value), block=block, rng=sheet_seed)
            else:
                made = stipple_tone_texture(float(self.tone.value), block, rng=sheet_seed, return_truth=True)
            self._sources[raw_key] = made
            self.calls["source"] += 1
            self.times["source"] = time.perf_counter() - t0
        image, truth = self._sources[raw_key]
        if kind == "sheet":
            t0 = time.perf_counter()
            tone_map = extract_tone_map(image, block_size=int(self.N.value), t1=float(self.T1.value),
                                        t2=float(self.T2.value))
            self.calls["tone_map"] += 1
            self.times["tone map"] = time.perf_counter() - t0
            source = StippleSource("sheet", image, list(tone_map.textures), np.asarray(tone_map.gray_levels),
                                   1.0 - np.asarray(truth["tones"]), tone_map,
                                   f"SYNTHETIC tone-map sheet ({len(truth['tones'])} patches of {block} px, "
                                   f"seed {sheet_seed}): section 3.1 found {len(tone_map.textures)} tones")
        else:
            source = StippleSource("texture", image, [image], np.array([1.0 - image.mean()]),
                                   np.array([1.0 - truth["tone"]]), None,
                                   f"one SYNTHETIC tone texture, tone {truth['tone']:.2f} ({truth['regime']}), "
                                   f"{block} px, seed {sheet_seed}")
        self._sources[key] = source
        return source

    def _learn_library(self, source: StippleSource) -> StippleLibrary:
        tile, iterations, seed = int(self.tile.value), int(self.iterations.value), int(self.seed.value)
        if source.kind == "texture":
            return _single_tone_library(source.textures[0], size=tile, iterations=iterations, rng=seed)
        return learn_stipple_library(source.tone_map, size=tile, iterations=iterations, rng=seed,
                                     workers=self._workers)

    # ------------------------------------------------------------------ output

    def _summary_text(self) -> str:
        lines = ["exemplars are SYNTHETIC (paperlib.datasets.stipple), not W. M. Andrews' hand-drawn tone maps"]
        if self.library is None:
            return "\n".join(lines + ["no library yet"])
        source, library = self.stipple_source, self.library
        lines.append(source.description)
        aces = [float(s.ace_history[-1]) if len(s.ace_history) else float("nan") for s in library.syntheses]
        lines.append(f"tones: {len(library)}; example grays {_floats(source.gray_levels)}; "
                     f"tone grays (pre-simulated) {_floats(library.tone_grays)}")
        lines.append(f"levels: {', '.join(library.levels)}; final ACE {_floats(aces, '.4f')} "
                     f"(tile {library.tiles[0].shape[0]} px, iterations run "
                     f"{', '.join(str(len(s.ace_history) - 1) for s in library.syntheses)})")
        if self.rendering is not None:
            height, width = self.rendering.image.shape
            lines.append(f"rendering: {self.image_name.value} {width} x {height} px, ink "
                         f"{self.rendering.image.mean():.3f}, removed chunks: {self.rendering.removed_ink} ink + "
                         f"{self.rendering.removed_paper} paper px; mean-tone error after a {BLUR_SIGMA:g} px "
                         f"blur {self.error_after_blur:.4f}")
        lines.append("seconds: " + ", ".join(f"{k} {v:.2f}" for k, v in self.times.items()))
        return "\n".join(lines)

    def _draw(self):
        from matplotlib.figure import Figure

        figure = Figure(figsize=self._figsize)  # fixed margins: constrained layout costs ~1 s per draw
        left, right = figure.subfigures(1, 2, width_ratios=[1.25, 1])
        left.subplots_adjust(left=0.07, right=0.99, bottom=0.02, top=0.82, wspace=0.08, hspace=0.35)
        right.subplots_adjust(left=0.02, right=0.98, bottom=0.02, top=0.9, wspace=0.05)
        library = self.library
        if library is None:
            ax = left.subplots()
            ax.set_axis_off()
            ax.text(0.5, 0.5, "no library\n(see the message below)", ha="center", va="center", color="0.4")
        else:
            n = len(library)
            axes = np.atleast_2d(left.subplots(2, n, squeeze=False))
            for k in range(n):
                top, bottom = axes[0, k], axes[1, k]
                top.imshow(~library.examples[k], cmap="gray", vmin=0, vmax=1, interpolation="nearest")
                top.set_title(f"{k + 1}: {library.levels[k]}\ngray {self.stipple_source.gray_levels[k]:.2f}",
                              fontsize=7)
                bottom.imshow(~library.tiles[k], cmap="gray", vmin=0, vmax=1, interpolation="nearest")
                history = library.syntheses[k].ace_history
                bottom.set_title(f"ACE {history[-1]:.4f}" if len(history) else "", fontsize=7)
                for ax in (top, bottom):
                    ax.set(xticks=[], yticks=[])
            axes[0, 0].set_ylabel("example\ntextures", fontsize=8)
            axes[1, 0].set_ylabel("synthesized\ndistributions", fontsize=8)
            left.suptitle("SYNTHETIC tone textures (lightest first) and synthesized tiles", fontsize=9)
        image_ax, stipple_ax = right.subplots(1, 2)
        for ax in (image_ax, stipple_ax):
            ax.set(xticks=[], yticks=[])
        if self.input_image is not None:
            image_ax.imshow(self.input_image, cmap="gray", vmin=0, vmax=1)
            image_ax.set_title(f"input: {self.image_name.value}", fontsize=8)
        if self.rendering is not None:
            stipple_ax.imshow(~self.rendering.image, cmap="gray", vmin=0, vmax=1, interpolation="nearest")
            stipple_ax.set_title(f"stippled, seed {self.seed.value}, min chunk {self.min_chunk.value}", fontsize=8)
        else:
            stipple_ax.text(0.5, 0.5, "no rendering\n(see the message below)", ha="center", va="center",
                            transform=stipple_ax.transAxes, color="0.4", fontsize=8)
        return figure


def _floats(values, fmt: str = ".2f") -> str:
    return "[" + " ".join(format(float(v), fmt) for v in values) + "]"


def stipple_explorer(source: str = "sheet", *, sheet_seed: int = 0, n_tones: int = 8, block: int = 192,
                     tone: float = 0.3, N: int = 32, T1: float = 0.05, T2: float = 0.03, iterations: int = 30,
                     tile: int = 64, seed: int = 0, image: str = "camera", render_size: int = 256,
                     min_chunk: int = 4, workers: int = 1, figsize=(12, 4.2), dpi: int = 80,
                     learn: bool = True) -> StippleExplorer:
    """An interactive explorer of Kim 2009's stippling by example.

    Builds the controls, learns a library from the SYNTHETIC exemplar and stipples ``image``
    once (unless ``learn=False``), and returns the explorer; ``display(explorer)`` (or
    ``explorer.widget``) shows it. See the module docstring for the design.

    Parameters
    ----------
    source : {"sheet", "texture"}
        A synthetic tone-map sheet cut into tones by section 3.1, or one synthetic tone texture.
    sheet_seed : int
        Seed of the exemplar generator.
    n_tones : int
        Patches of the sheet, in [2, 10] (default 8, the inner tones of Andrews' map).
    block : int
        Side of a sheet patch or of the single texture, px: one of 128, 160, 192, 256.
    tone : float
        Ink fraction of the single texture, in [0.05, 0.95].
    N, T1, T2 : int, float, float
        Section 3.1's block side (in [8, 64]) and thresholds (in [0.005, 0.2]).
    iterations : int
        Maximum synthesis iterations, in [1, 30] (paper: 30).
    tile : int
        Side of the synthesized tiles, one of :data:`TILE_SIZES` (paper: 256).
    seed : int
        Seed of the synthesis and the rendering.
    image : str
        One of :data:`IMAGES`.
    render_size : int
        Longer side of the rendered image, in [64, 1024].
    min_chunk : int
        Chunks of fewer pixels are removed (Fig. 11), in [1, 50] (1: none).
    workers : int
        Processes learning the tones in parallel (:func:`learn_stipple_library`); the library does
        not depend on it.
    figsize : pair of float
    dpi : int
    learn : bool
        Learn and render at once (default True).

    Returns
    -------
    StippleExplorer

    Raises
    ------
    ValueError
        For a parameter outside the ranges above (at construction; later, errors are shown in
        the widget).

    References
    ----------
    Kim et al. (2009), Figure 2, sections 3.1-3.4 and 4.
    """
    explorer = StippleExplorer(source=source, sheet_seed=sheet_seed, n_tones=n_tones, block=block, tone=tone, N=N,
                               T1=T1, T2=T2, iterations=iterations, tile=tile, seed=seed, image=image,
                               render_size=render_size, min_chunk=min_chunk, workers=workers, figsize=figsize, dpi=dpi)
    if learn:
        explorer.learn()
    else:
        explorer._show(time.perf_counter())
    return explorer


def _check_choice(value, choices: tuple, name: str) -> None:
    check_choice(value, choices, name)
