"""Interactive explorer of Simhon & Dudek 2001: draw a rough closed curve, see it elaborated in real time.

:func:`sketch_explorer` builds an ipywidgets panel on top of :mod:`paperlib.sketch`, the paper's *"graphical
user interface where users can draw curves and see the results. The interface also allows to set parameters,
such as scales, orders, weights and variances"* (section 3.1):

*training class*: ``coastlines`` (the 40 largest GSHHS land masses, real data,
:func:`paperlib.datasets.coastlines`; the paper's *"40 curves of world country borders"*) or ``leaves``
(14 SYNTHETIC leaf outlines, :func:`paperlib.datasets.leaf_outlines` with seed 0; the paper's class *"that
exhibits large-scale properties"*, Figures 5-6). The model is :func:`paperlib.sketch.train` with the ``order``
and ``scales`` sliders (the paper: order 20, 5 scales; the other training settings are ``train``'s defaults).

*sketch*: a preset or a drawing. Presets: hand-drawn-like blobs (:func:`paperlib.datasets.hand_drawn_curve`,
seeds 0-2, the size of a typical training curve), the coarse versions (:func:`paperlib.sketch.coarsen`, at the
current model's steering scale) of three held-out coastlines (``coastlines(54)[41:44]``, not among the 40
training curves) and of a held-out leaf (``leaf_outlines(15, rng=0)[14]``, a cordate leaf the training set of
14 does not hold). A drawing: press, drag and release on the canvas; the curve is closed by a straight segment
from the release point back to the start.

*elaboration* (section 3, eq. 3 and 5): :func:`paperlib.sketch.elaborate` with the variance ``sigma`` of
eq. (5), the threshold ``top``, the instantiation ``mode`` (``max``: the paper's most probable state;
``sample``: a state drawn with its probability, so seeds differ), the closure correction (``turn`` or
``distribute``, our options for the closure problem the paper reports; ``none``, the paper), the search window Delta t (a fraction of the curve,
for non-stationary classes such as leaves; it compares arc-length positions, so a drawn leaf should start
at its petiole, as the training leaves do), the number of samples and the seed.

The figure shows the sketch (left, its start marked) and the elaboration drawn as a line over the sketch
(right). The status line gives the training (curves, states, seconds, or "cached"), the sketch, the
elaboration's restarts (the chain lost every candidate and restarted from the sketch alone), its closing gap,
its Hausdorff distance to the sketch over the sketch's perimeter (:attr:`SketchExplorer.hausdorff_ratio`),
its longest run copied from one training curve (:func:`paperlib.sketch.copied_runs`, a novelty measure) and
the seconds of each step.

Design
------
*Plain methods.* Every control's effect is a method of :class:`SketchExplorer`
(:meth:`~SketchExplorer.load_training`, :meth:`~SketchExplorer.elaborate`, :meth:`~SketchExplorer.clear_drawing`),
and the canvas's mouse handlers are the methods ``_on_mouse_down``, ``_on_mouse_move``, ``_on_mouse_up`` and
``_on_mouse_out`` (leaving the canvas ends a stroke like a release), so tests and notebooks drive the panel,
drawing included, without a browser.

*What re-runs.* Class, order and scales: the training (or a cached model), then the elaboration (a new class
also swaps a preset coarse coastline or leaf for the new class's own, :data:`DEFAULT_PRESET`). Every other
control (sigma, top, mode, closure, window, samples, seed, preset, sketch source): only the elaboration,
milliseconds. Releasing the mouse after drawing switches the sketch to the drawing and elaborates; picking a
preset switches it back to the preset.

*Caching.* Trained models are kept per (class, order, scales), the last :data:`MODEL_CACHE` of them, so going
back along a slider is immediate; the training curves of each class are loaded once per process. ``calls``
counts the real trainings and elaborations.

*Canvas.* Canvas pixels (y down) map to sketch units (y up) at a scale where the canvas's height is the median
bounding-box diagonal of the class's training curves (about 900 km for the coastlines, 1.18 leaf lengths for
the leaves): a drawing filling the canvas has the size of a typical training curve. The elaboration does not
depend on that scale (the method works on tangent angles); the units only label the figure. The drawing is
kept in pixels, so it keeps its shape when the class changes.

*Drawn input.* Consecutive duplicate points (a mouse that did not move) are dropped. A drawing of fewer than
3 distinct points, one enclosing no area, or one that crosses itself (also through its closing segment) is
refused with a message. A drawing traversed clockwise is reversed: the training curves all run
counter-clockwise, and a clockwise sketch asks the chain for turns the class never makes (measured on a drawn
ellipse against the 40 coastlines: Hausdorff ratio about 0.07 clockwise, 0.016 counter-clockwise). A drawing
of fewer points than the order (a quick flick of the mouse) is resampled at ``order`` points equally spaced in
arc length, which :func:`paperlib.sketch.elaborate` would otherwise refuse.

*Errors are messages.* A sketch or a training the method refuses (too short, self-crossing, a window with no
training state): the exception is kept in ``error``, shown in red under the figure, the elaboration is None;
nothing is raised out of a method or a callback.

*Randomness.* The seed drives ``mode="sample"``: same controls, same elaboration bit for bit
(:attr:`~SketchExplorer.points_hash`).

*Headless.* The figure is a plain :class:`matplotlib.figure.Figure` rendered to PNG bytes in an
:class:`ipywidgets.Image`; the canvas is an :class:`ipycanvas.Canvas`, whose commands reach a browser only
when there is one.

Written by hand: the layout, the presets, the canvas bookkeeping; every step of the method is a call to
:mod:`paperlib.sketch`, the Hausdorff distance is :func:`paperlib.geometry.hausdorff` (a k-d tree), drawing is
matplotlib and ipycanvas, polygon predicates are shapely.

References
----------
.. [1] S. Simhon and G. Dudek, "On the Elaboration of Hand-Drawn Sketches", McGill University, 2001:
   section 3 (eq. 1-2: the steering component; eq. 4: the similarity with weights over scale and history;
   eq. 3 and 5: the steered chain, its variance and threshold; the search range Delta t), section 3.1 (the
   interactive interface; 40 training curves, 5 scales, order 20; closure problems), Figures 3-4 (sketches and
   elaborated coastlines), Figures 5-6 (leaves).
"""

from __future__ import annotations

import hashlib
import time
from collections import OrderedDict
from functools import cache

import numpy as np
import shapely

from paperlib._checks import check_choice, integer_at_least, positive_number
from paperlib.datasets import coastlines, hand_drawn_curve, leaf_outlines
from paperlib.geometry import drop_repeated_vertices, hausdorff, oriented_ccw, resample_closed_curve, signed_area
from paperlib.sketch import coarsen, copied_runs, train
from paperlib.sketch import elaborate as run_elaboration
from paperlib.widgets._base import CanvasDrawing, ExplorerBase

__all__ = ["CLASSES", "DEFAULT_PRESET", "MODEL_CACHE", "PRESETS", "SketchExplorer", "drawn_sketch", "points_hash", "sketch_explorer"]

#: Training classes: label, loader description, and the unit of their coordinates.
CLASSES = {"coastlines": ("coastlines (GSHHS, 40 largest)", "km"),
           "leaves": ("leaves (14, SYNTHETIC)", "leaf lengths")}
#: Preset sketches by name, with their labels (module docstring).
PRESETS = {
    "blob_0": "hand-drawn blob, seed 0",
    "blob_1": "hand-drawn blob, seed 1",
    "blob_2": "hand-drawn blob, seed 2",
    "coastline_41": "held-out coastline 41, coarse",
    "coastline_42": "held-out coastline 42, coarse",
    "coastline_43": "held-out coastline 43, coarse",
    "leaf": "held-out leaf (cordate), coarse",
}
#: The preset shown first for each class.
DEFAULT_PRESET = {"coastlines": "coastline_41", "leaves": "leaf"}
#: Trained models kept in an explorer's cache.
MODEL_CACHE = 6
ORDER_RANGE, SCALES_RANGE, TOP_RANGE, SAMPLES_RANGE = (1, 40), (1, 7), (1, 200), (64, 5000)
#: log10 bounds of the eq. (5) standard deviation sigma (radians): 0.003 to 3.2.
SIGMA_DECADES = (-2.5, 0.5)
WINDOW_RANGE = (0.01, 0.5)
#: The closure corrections the explorer offers (:func:`paperlib.sketch.elaborate`'s ``closure``).
CLOSURES = ("turn", "distribute", "none")
#: Training curves of each class, then how many more are loaded and held out for the presets.
N_COASTLINES, N_COASTLINES_LOADED = 40, 54
N_LEAVES, LEAF_SEED = 14, 0
#: Points of a hand-drawn blob preset.
BLOB_POINTS = 200
#: A drawing whose points' convex hull is smaller than this fraction of its bounding diagonal squared is flat.
_FLAT = 1e-9


# ---------------------------------------------------------------------------- plain functions


@cache
def _class_curves(name: str) -> tuple[tuple, tuple, float]:
    """The class's training curves, its held-out curves, and the median bounding diagonal of the training ones."""
    if name == "coastlines":
        curves = coastlines(N_COASTLINES_LOADED)  # sorted by area: the first 40 are coastlines(40)
        training, held_out = curves[:N_COASTLINES], curves[N_COASTLINES:]
    else:
        curves = leaf_outlines(N_LEAVES + 1, rng=LEAF_SEED)  # spawned seeds: the first 14 are leaf_outlines(14)
        training, held_out = curves[:N_LEAVES], curves[N_LEAVES:]
    for curve in curves:  # shared by every explorer of the process: nobody may change them
        curve.setflags(write=False)
    typical = float(np.median([np.hypot(*np.ptp(curve, axis=0)) for curve in training]))
    return tuple(training), tuple(held_out), typical


def _perimeter(ring: np.ndarray) -> float:
    return float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum())


def drawn_sketch(points, *, min_points: int = 3) -> tuple[np.ndarray, list[str]]:
    """The closed sketch a drawn polyline stands for, cleaned and checked, and notes on what was changed.

    Parameters
    ----------
    points : array_like, shape (m, 2)
        The drawn vertices in sketch units (y up), in drawing order; the curve closes from the last back to
        the first.
    min_points : int
        The fewest points the sketch must have (the model's order): a valid drawing with fewer is resampled
        at ``min_points`` points equally spaced in arc length.

    Returns
    -------
    sketch : ndarray, shape (n, 2)
        A simple, counter-clockwise ring without repeated points (a repeated end point dropped).
    notes : list of str
        What was changed (a clockwise drawing reversed, a short one resampled).

    Raises
    ------
    ValueError
        Nothing drawn, non-finite coordinates, fewer than 3 distinct points, points on a line (no enclosed
        area), or a curve that crosses itself (the closing segment included).

    References
    ----------
    Simhon & Dudek 2001, section 3 (the user's closed curve steers the chain; the training curves and the
    sketch are read along their arc length).
    """
    min_points = integer_at_least(min_points, "min_points", 3)
    array = np.asarray(points, dtype=np.float64)
    if array.size == 0:
        raise ValueError("nothing drawn yet: press, drag around a loop and release on the canvas")
    if array.ndim != 2 or array.shape[1] != 2 or not np.isfinite(array).all():
        raise ValueError(f"drawn points must be finite (x, y) pairs, got an array of shape {array.shape}")
    ring = drop_repeated_vertices(array) if len(array) > 1 else array  # (it would drop a lone point)
    if len(ring) < 3:
        count = f"{len(ring)} distinct point{'s' if len(ring) > 1 else ''}"
        raise ValueError(f"the drawing is too short ({count}): press, drag around a loop and release")
    diagonal = float(np.hypot(*np.ptp(ring, axis=0)))
    # Points on a line (a straight drag) span no area even around their hull; checked before the crossings,
    # since such a curve also doubles back on itself and "crosses itself" would not say what is wrong.
    if not shapely.MultiPoint(ring).convex_hull.area > _FLAT * diagonal**2:
        raise ValueError("the drawn curve encloses no area (its points lie on a line): draw around a region")
    if not shapely.LinearRing(ring).is_simple:
        raise ValueError("the drawn curve crosses itself (it is closed by a straight segment from the release "
                         "point back to the start): draw a simple loop")
    notes = []
    if signed_area(ring) < 0:
        ring = oriented_ccw(ring)  # reversed, keeping its start
        notes.append("drawn clockwise: reversed to run counter-clockwise like the training curves")
    if len(ring) < min_points:
        notes.append(f"only {len(ring)} points drawn: resampled at {min_points} (the order)")
        ring = resample_closed_curve(ring, min_points)
    return ring, notes


def points_hash(points) -> str:
    """SHA-256 of an array of points as float64 (the same points, bit for bit, give the same hash)."""
    return hashlib.sha256(np.ascontiguousarray(points, dtype=np.float64).tobytes()).hexdigest()


def _preset_sketch(name: str, model, class_name: str) -> np.ndarray:
    """The preset sketch, in the units of the class it is taken from (module docstring)."""
    if name.startswith("blob_"):
        return hand_drawn_curve(BLOB_POINTS, rng=int(name[5:]), size=_class_curves(class_name)[2])
    if name.startswith("coastline_"):
        return coarsen(_class_curves("coastlines")[1][int(name[10:]) - N_COASTLINES], model)
    return coarsen(_class_curves("leaves")[1][0], model)


# ---------------------------------------------------------------------------- the explorer


class SketchExplorer(CanvasDrawing, ExplorerBase):
    """Widgets and state of the Simhon 2001 explorer (built by :func:`sketch_explorer`).

    Parameters
    ----------
    training : {"coastlines", "leaves"}
        The training class: the 40 largest GSHHS coastlines (real) or 14 SYNTHETIC leaf outlines.
    order : int
        History O of a state, 1 to 40 (the paper: 20).
    scales : int
        Number of scales S, 1 to 7 (the paper: 5).
    sigma : float
        Standard deviation (radians) of eq. (5)'s Gaussian, 10**-2.5 to 10**0.5: the confidence in the sketch.
    top : int
        States kept by the threshold, 1 to 200.
    mode : {"max", "sample"}
        Instantiate the most probable state (the paper) or draw one (seeds then differ).
    closure : {"turn", "distribute", "none"}
        Close the elaboration by turning its segments (our correction, the default), by distributing its end
        gap, or leave the gap (the paper); :func:`paperlib.sketch.elaborate`.
    window : float, optional
        Search window Delta t as a fraction of the curve, 0.01 to 0.5 (None: no window).
    seed : int
        Seed of ``mode="sample"`` (>= 0).
    n_samples : int
        Samples of the elaboration, 64 to 5000 (so always above ``order``).
    preset : str, optional
        The first sketch, one of :data:`PRESETS` (default: a held-out coarse coastline for ``coastlines``, the
        held-out coarse leaf for ``leaves``).
    figsize : pair of float
        Figure size in inches.
    dpi : int
        Resolution of the figure shown in the widget (>= 10).
    canvas_size : pair of int
        Width and height of the drawing canvas, pixels (each at least 64).

    Attributes
    ----------
    widget : ipywidgets.VBox
        The panel to ``display``.
    training, order, scales, sigma, top, mode, closure, use_window, window, samples, seed, source, preset,
    clear_button, elaborate_button : ipywidgets controls
        See :func:`sketch_explorer`.
    canvas : ipycanvas.Canvas
        Where a sketch is drawn.
    image : ipywidgets.Image
        The figure (sketch left, elaboration right), as PNG.
    status : ipywidgets.HTML
    model : paperlib.sketch.SketchModel or None
        The model of the current class, order and scales (None when training failed).
    sketch : ndarray or None
        The sketch of the latest elaboration attempt, as given to :func:`paperlib.sketch.elaborate`.
    sketch_label : str
    elaboration : paperlib.sketch.Elaboration or None
        The latest elaboration (None when it failed: see ``message``).
    drawn_points : list of (float, float)
        The drawn polyline, in canvas pixels.
    figure : matplotlib.figure.Figure or None
    summary, message : str
    error : Exception or None
    times : dict
        Wall time (s) of the latest action's steps ("train" is 0 for a cached model).
    calls : dict
        How many trainings and elaborations really ran.
    """

    def __init__(self, *, training: str, order: int, scales: int, sigma: float, top: int, mode: str,
                 closure: str | None, window: float | None, seed: int, n_samples: int, preset: str | None,
                 figsize, dpi: int, canvas_size):
        (training, order, scales, sigma, top, mode, closure, window, seed, n_samples, preset, figsize, dpi,
         canvas_size) = _checked_settings(training, order, scales, sigma, top, mode, closure, window, seed, n_samples,
                                          preset, figsize, dpi, canvas_size)
        self._figsize, self._dpi = tuple(figsize), int(dpi)
        self.model = self.sketch = self.elaboration = self.figure = self.error = None
        self.sketch_label = self.summary = self.message = ""
        self.drawn_points: list = []
        self._stroke_active = False
        self._sketch_notes: list = []
        self._trained_now = False
        self.times: dict = {}
        self.calls = {"train": 0, "elaborate": 0}
        self._models: OrderedDict = OrderedDict()
        self._quiet_depth = 0
        self._build_controls(training, order, scales, sigma, top, mode, closure, window, seed, n_samples, preset,
                             canvas_size)
        self.widget = self._layout()
        self._connect()

    def _build_controls(self, training, order, scales, sigma, top, mode, closure, window, seed, n_samples, preset,
                        canvas_size):
        import ipywidgets as w
        from ipycanvas import Canvas

        wide = {"description_width": "initial"}
        self.training = w.Dropdown(options=[(label, name) for name, (label, _) in CLASSES.items()], value=training,
                                   description="training class", style=wide)
        self.order = w.IntSlider(value=order, min=ORDER_RANGE[0], max=ORDER_RANGE[1], description="order O",
                                 continuous_update=False, style=wide)
        self.scales = w.IntSlider(value=scales, min=SCALES_RANGE[0], max=SCALES_RANGE[1], description="scales S",
                                  continuous_update=False, style=wide)
        self.sigma = w.FloatLogSlider(value=sigma, base=10, min=SIGMA_DECADES[0], max=SIGMA_DECADES[1], step=0.05,
                                      description="sigma (eq. 5, rad)", readout_format=".3g",
                                      continuous_update=False, style=wide, layout=w.Layout(width="380px"))
        self.top = w.IntSlider(value=top, min=TOP_RANGE[0], max=TOP_RANGE[1], description="top (threshold)",
                               continuous_update=False, style=wide)
        self.mode = w.ToggleButtons(options=[("max (paper)", "max"), ("sample", "sample")], value=mode,
                                    description="instantiate", style=wide)
        self.closure = w.ToggleButtons(options=[("turn", "turn"), ("distribute", "distribute"),
                                                ("none (paper)", "none")], value=closure, description="close",
                                       style=wide)
        self.use_window = w.Checkbox(value=window is not None, description="search window \u0394t", indent=False)
        self.window = w.FloatSlider(value=0.1 if window is None else window, min=WINDOW_RANGE[0],
                                    max=WINDOW_RANGE[1], step=0.01, description="\u0394t (fraction)",
                                    continuous_update=False, style=wide)
        self.samples = w.BoundedIntText(value=n_samples, min=SAMPLES_RANGE[0], max=SAMPLES_RANGE[1],
                                        description="samples", style=wide, layout=w.Layout(width="170px"))
        self.seed = w.BoundedIntText(value=seed, min=0, max=2**31 - 1, description="seed", style=wide,
                                     layout=w.Layout(width="150px"))
        self.source = w.ToggleButtons(options=[("preset", "preset"), ("drawing", "drawing")], value="preset",
                                      description="sketch", style=wide)
        self.preset = w.Dropdown(options=[(label, name) for name, label in PRESETS.items()], value=preset,
                                 description="preset", style=wide)
        self.clear_button = w.Button(description="clear drawing", icon="eraser")
        self.elaborate_button = w.Button(description="elaborate", icon="play", button_style="primary")
        self.canvas = Canvas(width=int(canvas_size[0]), height=int(canvas_size[1]),
                             layout=w.Layout(border="1px solid #999999"))
        self.image = w.Image(format="png", layout=w.Layout(max_width="100%"))
        self.status = w.HTML()

    def _layout(self):
        import ipywidgets as w

        sketch_controls = w.VBox([self.source, self.preset, w.HBox([self.clear_button, self.elaborate_button])])
        return w.VBox([
            w.HBox([self.training, self.order, self.scales]),
            w.HBox([self.sigma, self.top, self.mode]),
            w.HBox([self.closure, self.use_window, self.window, self.samples, self.seed]),
            w.HBox([sketch_controls, self.canvas]),
            self.image,
            self.status,
        ])

    def _connect(self):
        self._on_change(self.training, self._on_class)
        for control in (self.order, self.scales):
            self._on_change(control, self.load_training)
        for control in (self.sigma, self.top, self.mode, self.closure, self.use_window, self.window, self.samples,
                        self.seed, self.source):
            self._on_change(control, self.elaborate)
        self._on_change(self.preset, self._on_preset)
        self.elaborate_button.on_click(lambda _: self.elaborate())
        self.clear_button.on_click(lambda _: self.clear_drawing())
        self._connect_canvas()

    # ------------------------------------------------------------------ actions

    def load_training(self) -> bool:
        """Train (or take from the cache) the model of the current class, order and scales, then elaborate.

        Returns
        -------
        bool
            Whether an elaboration was produced; on failure ``message`` says why (nothing raised).
        """
        began = time.perf_counter()
        self.times = {}
        elaborated = self._run_training() and self._run_elaboration()
        self._redraw_canvas()
        self._show(began)
        return bool(elaborated)

    def elaborate(self) -> bool:
        """Elaborate the current sketch with the current model and controls (no retraining).

        Returns
        -------
        bool
            Whether an elaboration was produced; on failure ``message`` says why and ``elaboration`` is None.
        """
        began = time.perf_counter()
        self.times = {"train": 0.0}
        self._trained_now = False
        elaborated = self._run_elaboration()
        self._show(began)
        return elaborated

    def clear_drawing(self) -> None:
        """Forget the drawing (the elaboration shown stays)."""
        self.drawn_points, self._stroke_active = [], False
        self._redraw_canvas()
        self.error, self.message = None, "drawing cleared: draw a new closed curve on the canvas"
        self._show_status()

    def _on_class(self) -> None:
        """A new class: a preset taken from the other class gives way to this class's own, then train."""
        if not self.preset.value.startswith("blob_"):
            with self._quiet():
                self.preset.value = DEFAULT_PRESET[self.training.value]
        self.load_training()

    def _on_preset(self) -> None:
        """Picking a preset makes it the sketch (leaving the drawing), and elaborates."""
        with self._quiet():
            self.source.value = "preset"
        self.elaborate()

    # ------------------------------------------------------------------ steps

    def _run_training(self) -> bool:
        """The model of the controls' class, order and scales (cached); sets ``model``, ``error``, ``message``."""
        key = (self.training.value, int(self.order.value), int(self.scales.value))
        self._trained_now = key not in self._models
        try:
            if self._trained_now:
                curves = _class_curves(key[0])[0]
                t0 = time.perf_counter()
                self._models[key] = train(curves, order=key[1], scales=key[2])
                self.times["train"] = time.perf_counter() - t0
                self.calls["train"] += 1
                while len(self._models) > MODEL_CACHE:
                    self._models.popitem(last=False)
            else:
                self._models.move_to_end(key)
                self.times["train"] = 0.0
        except Exception as error:  # shown in the widget, never raised out of a callback
            self.model = self.elaboration = self.sketch = None
            self.error, self.message = error, f"training failed: {error}"
            return False
        self.model = self._models[key]
        return True

    def current_sketch(self) -> tuple[np.ndarray, str, list[str]]:
        """The sketch the controls describe, its label and notes on how a drawing was cleaned.

        Returns
        -------
        sketch : ndarray of float64, shape (n, 2)
            The sketch, in sketch units (a preset, or the cleaned drawing).
        label : str
            What the sketch is (``"preset: ..."`` or ``"drawing"``).
        notes : list of str
            How the drawing was cleaned (empty for a preset).

        Raises
        ------
        ValueError
            No model, or a drawing the method cannot take (see :func:`drawn_sketch`).
        """
        if self.model is None:
            raise ValueError("no trained model: see the training message")
        if self.source.value == "preset":
            name = self.preset.value
            return _preset_sketch(name, self.model, self.training.value), f"preset: {PRESETS[name]}", []
        sketch, notes = drawn_sketch(self.canvas_to_sketch(self.drawn_points), min_points=self.model.order)
        return sketch, "drawing", notes

    def elaboration_options(self) -> dict:
        """The keyword arguments of :func:`paperlib.sketch.elaborate` the controls set (``rng`` included).

        Returns
        -------
        dict
            ``n_samples``, ``sigma``, ``top``, ``mode``, ``closure``, ``window`` (None when the window
            is off) and ``rng`` (the seed).
        """
        return dict(n_samples=int(self.samples.value), sigma=float(self.sigma.value), top=int(self.top.value),
                    mode=self.mode.value, closure=self.closure.value,
                    window=float(self.window.value) if self.use_window.value else None, rng=int(self.seed.value))

    def _run_elaboration(self) -> bool:
        self.sketch, self._sketch_notes = None, []
        try:
            t0 = time.perf_counter()
            sketch, label, notes = self.current_sketch()
            self.sketch, self.sketch_label, self._sketch_notes = sketch, label, notes
            self.times["sketch"] = time.perf_counter() - t0
            t0 = time.perf_counter()
            elaboration = run_elaboration(self.model, sketch, **self.elaboration_options())
            self.times["elaborate"] = time.perf_counter() - t0
            self.calls["elaborate"] += 1
        except Exception as error:  # shown in the widget, never raised out of a callback
            self.elaboration, self.error = None, error
            kind = "" if isinstance(error, ValueError) else f"{type(error).__name__}: "
            self.message = f"elaboration failed: {kind}{error}"
            return False
        self.elaboration, self.error = elaboration, None
        self.message = "\n".join(self._sketch_notes)
        return True

    # ------------------------------------------------------------------ canvas

    @property
    def canvas_scale(self) -> float:
        """Sketch units per canvas pixel: the canvas's height is a typical training curve's diagonal."""
        return _class_curves(self.training.value)[2] / self.canvas.height

    def canvas_to_sketch(self, points) -> np.ndarray:
        """Canvas pixels (x right, y down) to sketch units (x right, y up), ``(m, 2)``.

        Parameters
        ----------
        points : array_like, shape (m, 2)
            Points in canvas pixels.

        Returns
        -------
        ndarray of float64, shape (m, 2)
            The points in sketch units.
        """
        return self._pixels_to_units(points)

    def _drawing_finished(self) -> None:
        """A released drawing becomes the sketch, and it is elaborated."""
        with self._quiet():
            self.source.value = "drawing"
        self._redraw_canvas()
        self.elaborate()

    def _draw_canvas(self) -> None:
        """Background, a hint with the canvas's scale, and the drawing (closed once released)."""
        from ipycanvas import hold_canvas

        canvas = self.canvas
        with hold_canvas():
            canvas.clear()
            canvas.fill_style = "#fbfbfb"
            canvas.fill_rect(0, 0, canvas.width, canvas.height)
            canvas.fill_style = "#777777"
            canvas.font = "11px sans-serif"
            canvas.fill_text("press, drag around a loop and release (it closes back to its start)", 6,
                             canvas.height - 8)
            unit = CLASSES[self.training.value][1]
            canvas.fill_text(f"canvas height: {_class_curves(self.training.value)[2]:.3g} {unit}", 6, 14)
            self._paint_drawing(canvas, close=not self._stroke_active)

    # ------------------------------------------------------------------ results

    @property
    def n_samples(self) -> int | None:
        """Points of the elaboration (None without one)."""
        return None if self.elaboration is None else len(self.elaboration.points)

    @property
    def restarts(self) -> int | None:
        """How often the chain lost every candidate and restarted (None without an elaboration)."""
        return None if self.elaboration is None else self.elaboration.restarts

    @property
    def hausdorff_ratio(self) -> float | None:
        """Hausdorff distance between the elaboration and the resampled sketch, over the sketch's perimeter.

        Both are ``n_samples`` points (the elaboration's and the sketch's samples at uniform arc length), so this
        is the curves' distance to within a sample spacing. None without an elaboration.
        """
        if self.elaboration is None:
            return None
        sketch = self.elaboration.sketch
        return hausdorff(sketch, self.elaboration.points) / _perimeter(sketch)

    @property
    def longest_copy(self) -> int | None:
        """Longest run of samples copied from one training curve (:func:`paperlib.sketch.copied_runs`)."""
        return None if self.elaboration is None else int(copied_runs(self.model, self.elaboration.states).max())

    @property
    def points_hash(self) -> str | None:
        """SHA-256 of the elaboration's points (:func:`points_hash`; None without an elaboration)."""
        return None if self.elaboration is None else points_hash(self.elaboration.points)

    # ------------------------------------------------------------------ output

    def _summary_text(self) -> str:
        lines = []
        label = CLASSES[self.training.value][0]
        order, scales = int(self.order.value), int(self.scales.value)
        if self.model is not None:
            how = f"trained in {self.times.get('train', 0.0):.2f} s" if self._trained_now else "cached model"
            lines.append(f"training: {label}, {len(self.model.curves)} curves, {len(self.model)} states, "
                         f"order {order}, scales {scales}: {how}")
        else:
            lines.append(f"training: {label}, order {order}, scales {scales}: no model")
        if self.sketch is not None:
            lines.append(f"sketch: {self.sketch_label}, {len(self.sketch)} points")
        options = self.elaboration_options()
        settings = (f"{options['mode']}, sigma {options['sigma']:.3g}, top {options['top']}, seed {options['rng']}"
                    + f", closure {options['closure']}"
                    + (f", window {options['window']:g}" if options["window"] is not None else ""))
        if self.elaboration is not None:
            lines.append(f"elaboration ({settings}): {self.n_samples} samples, {self.restarts} restarts, "
                         f"closing gap {self.elaboration.closing_gap:.3f} of the length, Hausdorff to the sketch "
                         f"{self.hausdorff_ratio:.3f} of its perimeter, longest copied run {self.longest_copy} "
                         "samples")
        else:
            lines.append(f"elaboration ({settings}): none")
        if self.times:
            lines.append("seconds: " + ", ".join(f"{name} {value:.3f}" for name, value in self.times.items()))
        return "\n".join(lines)

    def _draw(self):
        from matplotlib.figure import Figure

        figure = Figure(figsize=self._figsize)
        left, right = figure.subplots(1, 2)
        # fixed margins: a constrained layout would double the redraw time, which the elaboration is far below
        figure.subplots_adjust(left=0.07, right=0.99, bottom=0.11, top=0.91, wspace=0.18)
        for ax in (left, right):
            ax.set_aspect("equal")
            ax.tick_params(labelsize=7)
        self.draw_sketch(left)
        self.draw_elaboration(right)
        return figure

    def draw_sketch(self, ax) -> None:
        """Draw the sketch on matplotlib axes (its start marked); a refused drawing in red, dashed.

        Parameters
        ----------
        ax : matplotlib.axes.Axes
            The axes to draw on.
        """
        if self.sketch is not None:
            ring = np.vstack([self.sketch, self.sketch[:1]])
            ax.plot(*ring.T, "-", color="0.15", lw=1.2)
            ax.plot(*self.sketch[0], "o", color="#2ca02c", ms=5)
            ax.set_title(f"sketch: {self.sketch_label}", fontsize=9)
        elif self.source.value == "drawing" and len(self.drawn_points) >= 2:
            drawn = self.canvas_to_sketch(self.drawn_points)
            ax.plot(*np.vstack([drawn, drawn[:1]]).T, "--", color="#b00020", lw=1.0)
            ax.set_title("drawing (refused: see the message below)", fontsize=9)
        else:
            ax.text(0.5, 0.5, "no sketch\n(see the message below)", ha="center", va="center",
                    transform=ax.transAxes, color="0.4")
            ax.set_title("sketch", fontsize=9)
        ax.set_xlabel(CLASSES[self.training.value][1], fontsize=8)

    def draw_elaboration(self, ax) -> None:
        """Draw the elaboration as a line over the sketch (dashed grey) on matplotlib axes.

        Parameters
        ----------
        ax : matplotlib.axes.Axes
            The axes to draw on.
        """
        if self.elaboration is None:
            ax.text(0.5, 0.5, "no elaboration\n(see the message below)", ha="center", va="center",
                    transform=ax.transAxes, color="0.4")
            ax.set_title("elaboration", fontsize=9)
            return
        sketch, points = self.elaboration.sketch, self.elaboration.points
        ax.plot(*np.vstack([sketch, sketch[:1]]).T, "--", color="0.6", lw=0.8)
        ax.plot(*np.vstack([points, points[:1]]).T, "-", color="#1f77b4", lw=0.8)  # a ring, as elaborate returns
        ax.set_title(f"elaboration ({self.training.value}): Hausdorff / perimeter {self.hausdorff_ratio:.3f}",
                     fontsize=9)
        ax.set_xlabel(CLASSES[self.training.value][1], fontsize=8)


# ---------------------------------------------------------------------------- factory


def _checked_settings(training, order, scales, sigma, top, mode, closure, window, seed, n_samples, preset, figsize,
                      dpi, canvas_size) -> tuple:
    """The explorer's settings checked against the ranges of :func:`sketch_explorer` (a ValueError naming the
    parameter otherwise), ``preset=None`` replaced by the training class's default preset."""
    if not isinstance(training, str) or training not in CLASSES:
        raise ValueError(f"training: unknown training class {training!r:.80}; choose one of {', '.join(CLASSES)}")
    order = _integer_in(order, "order", ORDER_RANGE)
    scales = _integer_in(scales, "scales", SCALES_RANGE)
    sigma = _number_in(sigma, "sigma", 10 ** SIGMA_DECADES[0], 10 ** SIGMA_DECADES[1])
    top = _integer_in(top, "top", TOP_RANGE)
    check_choice(mode, ("max", "sample"), "mode")
    check_choice(closure, CLOSURES, "closure")
    if window is not None:
        window = _number_in(window, "window", *WINDOW_RANGE)
    seed = integer_at_least(seed, "seed", 0)
    n_samples = _integer_in(n_samples, "n_samples", SAMPLES_RANGE)  # its least, 64, exceeds the largest order
    preset = DEFAULT_PRESET[training] if preset is None else preset
    if not isinstance(preset, str) or preset not in PRESETS:
        raise ValueError(f"preset: unknown preset {preset!r:.80}; choose one of {', '.join(PRESETS)}")
    dpi = integer_at_least(dpi, "dpi", 10)
    figsize = _pair(figsize, "figsize", positive_number)
    canvas_size = _pair(canvas_size, "canvas_size", lambda value, name: integer_at_least(value, name, 64))
    return (training, order, scales, sigma, top, mode, closure, window, seed, n_samples, preset, figsize, dpi,
            canvas_size)


def _integer_in(value, name: str, bounds: tuple[int, int]) -> int:
    number = integer_at_least(value, name, bounds[0])
    if number > bounds[1]:
        raise ValueError(f"{name} must be an integer in [{bounds[0]}, {bounds[1]}], got {value!r}")
    return number


def _number_in(value, name: str, low: float, high: float) -> float:
    number = positive_number(value, name)
    if not low <= number <= high:
        raise ValueError(f"{name} must be a number in [{low:.3g}, {high:.3g}], got {value!r}")
    return number


def _pair(values, name: str, check) -> tuple:
    try:
        pair = tuple(check(value, name) for value in values)
    except TypeError:
        raise ValueError(f"{name} must be a pair of numbers, got {values!r}") from None
    if len(pair) != 2:
        raise ValueError(f"{name} must be a pair, got {values!r}")
    return pair


def sketch_explorer(training: str = "coastlines", *, order: int = 20, scales: int = 5, sigma: float = 0.1,
                    top: int = 20, mode: str = "max", closure: str = "turn", window: float | None = None,
                    seed: int = 0, n_samples: int = 1000, preset: str | None = None, figsize=(10, 4.5), dpi: int = 80,
                    canvas_size=(420, 320)) -> SketchExplorer:
    """An interactive explorer of Simhon & Dudek 2001's elaboration of hand-drawn sketches.

    Builds the controls, trains the model of ``training`` (or loads it from the cache), elaborates the preset
    sketch and returns the explorer; ``display(explorer)`` (or ``explorer.widget``) shows it. See the module
    docstring for the design.

    Parameters
    ----------
    training : {"coastlines", "leaves"}
        The training class: the 40 largest GSHHS coastlines (real) or 14 SYNTHETIC leaf outlines.
    order : int
        History O of a state, 1 to 40 (the paper: 20).
    scales : int
        Number of scales S, 1 to 7 (the paper: 5).
    sigma : float
        Standard deviation (radians) of eq. (5)'s Gaussian, 10**-2.5 to 10**0.5: the confidence in the sketch.
    top : int
        States kept by the threshold, 1 to 200.
    mode : {"max", "sample"}
        Instantiate the most probable state (the paper) or draw one (seeds then differ).
    closure : {"turn", "distribute", "none"}
        Close the elaboration by turning its segments (our correction, the default), by distributing its end
        gap, or leave the gap (the paper); :func:`paperlib.sketch.elaborate`.
    window : float, optional
        Search window Delta t as a fraction of the curve, 0.01 to 0.5 (None: no window).
    seed : int
        Seed of ``mode="sample"`` (>= 0).
    n_samples : int
        Samples of the elaboration, 64 to 5000 (so always above ``order``).
    preset : str, optional
        The first sketch, one of :data:`PRESETS` (default: a held-out coarse coastline for ``coastlines``, the
        held-out coarse leaf for ``leaves``).
    figsize : pair of float
        Figure size in inches.
    dpi : int
        Resolution of the figure shown in the widget (>= 10).
    canvas_size : pair of int
        Width and height of the drawing canvas, pixels (each at least 64).

    Returns
    -------
    SketchExplorer

    Raises
    ------
    ValueError
        For an argument outside the ranges above (at construction; later, errors are shown in the widget).

    References
    ----------
    Simhon & Dudek 2001, section 3 (eq. 3-5, the threshold, Delta t) and section 3.1 (the interface, the
    paper's settings), Figures 3, 4 and 6.
    """
    explorer = SketchExplorer(training=training, order=order, scales=scales, sigma=sigma, top=top, mode=mode,
                              closure=closure, window=window, seed=seed, n_samples=n_samples, preset=preset,
                              figsize=figsize, dpi=dpi, canvas_size=canvas_size)
    explorer.load_training()
    return explorer
