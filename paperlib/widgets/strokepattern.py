"""Interactive explorer of Barla 2006: set the scale epsilon on the live clustering, then synthesize.

:func:`strokepattern_explorer` builds an ipywidgets panel on top of :mod:`paperlib.strokepattern`, the
interactive loop of the paper's section 2 ("the whole analysis process is interactive, hence providing enough
feedback to easily set a convenient scale") followed by section 3's synthesis:

*reference* (left panel): one of the SYNTHETIC exemplars of :mod:`paperlib.datasets.strokepatterns`
(``exemplar``, ``exemplar seed``); the kind of pattern, 1D along a path or 2D in a region, follows the
exemplar. Its strokes are coloured by the element they are clustered into (a qualitative colormap, so
neighbouring elements differ), with the elements' oriented boxes and the neighbour graph (the chain in 1D,
the unskewed Delaunay edges in 2D). The ``epsilon`` slider (logarithmic, starting at the generator's epsilon)
and the ``contour`` checkbox (fit boxes on the pen's contour, section 2.1) re-run **only** the analysis and
redraw at once; the status line gives the number of elements and the generator's truth.

*synthesis* (right panel): the target is a preset (``pick``: a straight line, an arc or an S-curve for 1D;
a square, a disc, an L-shape or a star for 2D, each scaled to :data:`TARGET_FACTOR` times the reference's
length or area, so it holds about three times the reference's elements) or a drawing (``draw``: press, drag
and release on the canvas; a 1D target is the drawn polyline, a 2D target the polygon it closes). The
synthesis (:func:`paperlib.strokepattern.synthesize` with ``rings`` and ``choice``) is followed by the
parameter exchange (:func:`~paperlib.strokepattern.exchange_parameters`) when the variation ``amount`` is
above 0 and by the position variation (:func:`~paperlib.strokepattern.vary_positions`) when checked; it is
drawn with the target outline, the elements whose neighbourhood found no match (the fallback) marked by a red
cross. The status line gives the elements, the fallback fraction and the seconds of each step.

Design
------
*Plain methods.* Every control's effect is a method of :class:`StrokePatternExplorer`
(:meth:`~StrokePatternExplorer.load_exemplar`, :meth:`~StrokePatternExplorer.analyze`,
:meth:`~StrokePatternExplorer.synthesize`, :meth:`~StrokePatternExplorer.clear_drawing`), and the canvas's
mouse handlers are the methods ``_on_mouse_down``, ``_on_mouse_move``, ``_on_mouse_up`` (and
``_on_mouse_out``, which ends a stroke like a release), so tests and notebooks drive the panel, drawing
included, without a browser.

*What re-runs.* Epsilon and contour: the analysis only (the synthesis shown stays, labelled with the epsilon
it was made at, until **synthesize** is pressed). Rings, amount, position variation, choice, seed and target
mode: the synthesis; picking a preset also switches the target to ``pick``. Releasing the mouse after
drawing switches the target to ``draw`` and synthesizes. The exemplar and its seed: everything (epsilon back to
the new exemplar's; an exemplar of the other dimension switches the target back to ``pick``, since a drawn path
is no region, and to the first preset of its kind).

*Canvas.* The canvas shows, for scale, a grey box the size of the reference pattern; canvas pixels map to
pattern units with the y axis flipped (y up), at a scale such that the canvas's width holds 1.2 times the
line preset (1D), or its height 1 / 0.6 times the side of the square preset (2D). The drawing is kept in
pixels, so it keeps its meaning when the exemplar changes. A 2D outline that crosses itself is repaired
(:func:`shapely.make_valid`, polygonal parts kept) and a note says so.

*Errors are messages.* An epsilon so large that the pattern is one element, a 2D pattern whose Delaunay
triangulation has no unskewed triangle, a drawn path of one point, a drawn region of zero area or too small
for three seeds: the exception is kept in ``error`` and shown in red under the figure; nothing is raised out
of a method or a callback.

*Caching.* Exemplars are kept per (name, seed) and analyses per (exemplar, seed, epsilon, contour), the last
:data:`ANALYSIS_CACHE` of them, so going back along the slider is immediate; ``calls`` counts the real runs.

*Randomness.* The synthesis seed fixes the synthesis and the parameter exchange (two streams spawned from
it): same controls, same strokes bit for bit (:attr:`~StrokePatternExplorer.stroke_hash`).

*Headless.* The figure is a plain :class:`matplotlib.figure.Figure` rendered to PNG bytes in an
:class:`ipywidgets.Image`; the canvas is an :class:`ipycanvas.Canvas`, whose commands are only sent to a
browser when there is one.

Written by hand: the layout, the presets, the canvas bookkeeping; every step of the method is a call to
:mod:`paperlib.strokepattern`, drawing is matplotlib and ipycanvas, polygons are shapely.

References
----------
.. [1] P. Barla, S. Breslav, J. Thollot, F. Sillion, L. Markosian, "Stroke Pattern Analysis and Synthesis",
   Computer Graphics Forum (Eurographics) 25(3), 2006: section 2 (the interactive choice of the scale
   epsilon, clustering and distribution), 3.1-3.2 (k-ring synthesis along a path or in a region), 3.3
   (variation), Figures 6 and 7 (1D and 2D results).
"""

from __future__ import annotations

import hashlib
import math
import time
from collections import OrderedDict
from functools import partial

import numpy as np
import shapely
from shapely import affinity

from paperlib.datasets.strokepatterns import (
    alternating_color_exemplar,
    bars_exemplar,
    drops_exemplar,
    flowers_exemplar,
    gradient_hatching_exemplar,
    irregular_exemplar,
    jittered_hatching_exemplar,
    sketchy_hatching_exemplar,
    two_hatchings_exemplar,
    wave_hatching_exemplar,
)
from paperlib.strokepattern.analysis import check_dimension
from paperlib.strokepattern import (
    analyze,
    exchange_parameters,
    plot_boxes,
    plot_graph,
    plot_strokes,
    synthesize,
    vary_positions,
)
from paperlib._checks import check_flag
from paperlib.widgets._base import CanvasDrawing, ExplorerBase, figure_settings

__all__ = ["ANALYSIS_CACHE", "EXEMPLARS", "PRESETS", "StrokePatternExplorer", "TARGET_FACTOR", "drawn_target",
           "preset_target", "stroke_hash", "strokepattern_explorer"]

#: The exemplar generators offered, by name; each is called with ``rng=seed``.
EXEMPLARS = {
    "sketchy_hatching": sketchy_hatching_exemplar,
    "jittered_hatching": jittered_hatching_exemplar,
    "gradient_orientation": partial(gradient_hatching_exemplar, "orientation"),
    "gradient_length": partial(gradient_hatching_exemplar, "length"),
    "gradient_thickness": partial(gradient_hatching_exemplar, "thickness"),
    "gradient_color": partial(gradient_hatching_exemplar, "color"),
    "wave": wave_hatching_exemplar,
    "alternating_color": alternating_color_exemplar,
    "bars": bars_exemplar,
    "drops": drops_exemplar,
    "flowers": flowers_exemplar,
    "two_hatchings": two_hatchings_exemplar,
    "irregular": irregular_exemplar,
}
#: Target presets by pattern dimension: paths (1D) and regions (2D).
PRESETS = {1: ("line", "arc", "s_curve"), 2: ("square", "disc", "l_shape", "star")}
#: A preset's length (1D) or area (2D) over the reference's: it holds about this many times its elements.
TARGET_FACTOR = 3.0
#: Analyses kept in the cache.
ANALYSIS_CACHE = 64
#: The epsilon slider spans this many decades on each side of the exemplar's epsilon.
EPSILON_DECADES = 1.5
RINGS_RANGE = (1, 5)
#: Qualitative colours of the clusters (element i gets colour i mod 10: elements are numbered in drawing
#: order, so neighbouring elements differ).
CLUSTER_COLORS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                  "#bcbd22", "#17becf")
#: Canvas scale (see the module docstring, *Canvas*).
_CANVAS_LINE_SPAN = 1.2
_CANVAS_SQUARE_SPAN = 0.6
#: A drawn region enclosing less than this fraction of its bounding-box diagonal squared has zero area.
_ZERO_AREA = 1e-9
_PRESET_LABELS = {"line": "straight line", "arc": "arc", "s_curve": "S-curve", "square": "square",
                  "disc": "disc", "l_shape": "L-shape", "star": "star"}


# ---------------------------------------------------------------------------- plain functions


def _polyline_length(points: np.ndarray) -> float:
    return float(np.hypot(*np.diff(points, axis=0).T).sum())


def _unit_preset(name: str):
    """The preset's shape before scaling: a polyline (m, 2) or a shapely Polygon."""
    if name == "line":
        return np.array([(0.0, 0.0), (1.0, 0.0)])
    if name == "arc":  # a half circle, bulging up, drawn left to right
        angle = np.linspace(np.pi, 0.0, 65)
        return np.column_stack([np.cos(angle), np.sin(angle)])
    if name == "s_curve":  # one period of a sine, amplitude a quarter of the width
        x = np.linspace(0.0, 1.0, 97)
        return np.column_stack([x, 0.25 * np.sin(2.0 * np.pi * x)])
    if name == "square":
        return shapely.box(-0.5, -0.5, 0.5, 0.5)
    if name == "disc":
        angle = np.linspace(0.0, 2.0 * np.pi, 96, endpoint=False)
        return shapely.Polygon(np.column_stack([np.cos(angle), np.sin(angle)]))
    if name == "l_shape":  # a 2 x 2 square without its upper right quarter
        return shapely.Polygon([(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)])
    if name == "star":  # five points, inner radius half the outer
        angle = np.pi / 2.0 + np.pi * np.arange(10) / 5.0
        radius = np.where(np.arange(10) % 2 == 0, 1.0, 0.5)
        return shapely.Polygon(np.column_stack([radius * np.cos(angle), radius * np.sin(angle)]))
    raise ValueError(f"unknown preset {name!r}; choose one of {', '.join(PRESETS[1] + PRESETS[2])}")


def preset_target(name: str, extent: float):
    """A preset target of a given length (path) or area (region).

    Parameters
    ----------
    name : str
        1D (a path, starting at the origin): ``"line"``, ``"arc"`` (a half circle), ``"s_curve"`` (one period
        of a sine). 2D (a region, centred on the origin): ``"square"``, ``"disc"`` (a 96-gon), ``"l_shape"``,
        ``"star"`` (five points, inner radius half the outer).
    extent : float
        The path's length or the region's area (> 0).

    Returns
    -------
    numpy.ndarray (m, 2) or shapely.Polygon
        The polyline, of length exactly ``extent`` (up to rounding), or the polygon, of area ``extent``.

    Raises
    ------
    ValueError
        An unknown name or a non-positive extent.

    References
    ----------
    Barla et al. 2006, sections 3.2 (synthesis along a 1D path or in a 2D region) and 4 (Figures 6 and 7).
    """
    if isinstance(extent, bool) or not isinstance(extent, (int, float, np.number)) or not (
            math.isfinite(extent) and extent > 0):
        raise ValueError(f"extent must be a positive finite number, got {extent!r}")
    shape = _unit_preset(name)
    if isinstance(shape, np.ndarray):
        return shape * (float(extent) / _polyline_length(shape))
    centred = affinity.translate(shape, -shape.centroid.x, -shape.centroid.y)
    factor = math.sqrt(float(extent) / centred.area)
    return affinity.scale(centred, factor, factor, origin=(0.0, 0.0))


def drawn_target(points, dimension: int):
    """The target a drawn polyline stands for: the path itself (1D) or the polygon it closes (2D).

    Parameters
    ----------
    points : array_like (m, 2)
        The drawn vertices in pattern units, in drawing order; repeated consecutive vertices are dropped.
    dimension : {1, 2}

    Returns
    -------
    numpy.ndarray (m, 2) or shapely.Polygon or shapely.MultiPolygon
        The path, or the region. A self-intersecting outline is repaired with :func:`shapely.make_valid`,
        keeping its polygonal parts.

    Raises
    ------
    ValueError
        Fewer than two distinct points (a path needs a length), fewer than three (a region), non-finite
        coordinates, or an outline enclosing no area.

    References
    ----------
    Barla et al. 2006, section 3.2 (targets: a path or a region).
    """
    check_dimension(dimension)
    array = np.asarray(points, dtype=np.float64)
    if array.size == 0:
        raise ValueError("nothing drawn yet: press, drag and release the mouse on the canvas")
    if array.ndim != 2 or array.shape[1] != 2 or not np.isfinite(array).all():
        raise ValueError(f"drawn points must be finite (x, y) pairs, got an array of shape {array.shape}")
    keep = np.concatenate([[True], np.any(np.diff(array, axis=0) != 0, axis=1)])
    array = array[keep]
    if dimension == 1:
        if len(array) < 2:
            raise ValueError("the drawn path is a single point: drag the mouse to draw a path of some length")
        return array
    if len(array) < 3:
        raise ValueError(f"a drawn region needs at least 3 distinct points, got {len(array)}: "
                         "drag the mouse around the region")
    polygon = shapely.Polygon(array)
    if not polygon.is_valid:
        parts = [part for part in shapely.get_parts(shapely.make_valid(polygon))
                 if isinstance(part, (shapely.Polygon, shapely.MultiPolygon)) and part.area > 0]
        polygon = shapely.union_all(parts) if parts else shapely.Polygon()
    diagonal = float(np.hypot(*(array.max(axis=0) - array.min(axis=0))))
    # Collinear vertices enclose an area of rounding size only: that is zero area too.
    if polygon.is_empty or not polygon.area > _ZERO_AREA * diagonal ** 2:
        raise ValueError("the drawn region has zero area (its outline encloses nothing): draw around a region")
    return polygon


def stroke_hash(strokes) -> str:
    """SHA-256 of strokes' points, widths and colours (the same strokes, bit for bit, give the same hash)."""
    digest = hashlib.sha256()
    for stroke in strokes:
        digest.update(np.ascontiguousarray(stroke.points, dtype=np.float64).tobytes())
        digest.update(np.float64(stroke.width).tobytes())
        digest.update(str(stroke.color).encode())
    return digest.hexdigest()


def _reference_extent(pattern) -> float:
    """The length of a 1D exemplar's path, or the area of a 2D exemplar's region."""
    if pattern.dimension == 1:
        return _polyline_length(np.asarray(pattern.path, dtype=np.float64))
    return float(pattern.region.area)


def _outline_parts(region) -> list:
    """Every ring (exteriors and holes) of a (Multi)Polygon, as (m, 2) arrays."""
    rings = []
    for polygon in shapely.get_parts(region):
        rings.append(np.asarray(polygon.exterior.coords))
        rings.extend(np.asarray(hole.coords) for hole in polygon.interiors)
    return rings


# ---------------------------------------------------------------------------- the explorer


class StrokePatternExplorer(CanvasDrawing, ExplorerBase):
    """Widgets and state of the Barla 2006 explorer (built by :func:`strokepattern_explorer`).

    Parameters
    ----------
    exemplar : str
        One of :data:`EXEMPLARS`: ``sketchy_hatching``, ``jittered_hatching``, ``gradient_orientation``,
        ``gradient_length``, ``gradient_thickness``, ``alternating_color`` (1D); ``bars``, ``drops``,
        ``flowers``, ``two_hatchings``, ``irregular`` (2D).
    exemplar_seed : int
        Seed of the exemplar generator (>= 0).
    contour : bool
        Fit element boxes on the pen's contour (section 2.1) instead of the skeleton.
    rings : int
        k of the k-ring neighbourhoods, 1 to 5.
    amount : float
        Parameter-exchange amount in [0, 1] (section 3.3; 0: none).
    vary : bool
        Apply the position variation (section 3.3).
    choice : {"close", "random", "best"}
        Among the matching reference neighbourhoods: a random one within a tenth of a threshold of the best
        (default, Efros and Leung's rule), a random one (the paper) or the best scored.
    seed : int
        Seed of the synthesis (>= 0); same seed, same strokes.
    figsize : pair of float
        Figure size in inches.
    dpi : int
        Resolution of the figure shown in the widget.
    canvas_size : pair of int
        Width and height of the drawing canvas, pixels (each at least 64).

    Attributes
    ----------
    widget : ipywidgets.VBox
        The panel to ``display``.
    exemplar, exemplar_seed, epsilon, contour, rings, amount, vary, choice, seed, target_mode, preset,
    clear_button, synthesize_button : ipywidgets controls
        See :func:`strokepattern_explorer`.
    canvas : ipycanvas.Canvas
        Where a target is drawn.
    image : ipywidgets.Image
        The figure (reference left, synthesis right), as PNG.
    status : ipywidgets.HTML
    pattern : StrokePatternExemplar or None
        The current exemplar.
    analysis : PatternAnalysis or None
        The analysis at the current epsilon and contour (None when it failed: see ``message``).
    synthesis : Synthesis or None
        The latest synthesis, variation included (None when the latest synthesis failed).
    synthesis_epsilon : float or None
        The epsilon of the analysis the synthesis shown was made from.
    target : numpy.ndarray or shapely geometry or None
        The target of the latest synthesis (pattern units).
    target_label : str
        What that target was ("preset arc", "drawn path", ...).
    drawn_points : list of (float, float)
        The drawn polyline, in canvas pixels.
    figure : matplotlib.figure.Figure or None
    summary, message : str
    error : Exception or None
    times : dict
        Wall time (s) of the latest action's steps.
    calls : dict
        How many exemplars were generated and analyses and syntheses run.
    """

    def __init__(self, *, exemplar: str, exemplar_seed: int, contour: bool, rings: int, amount: float, vary: bool,
                 choice: str, seed: int, figsize, dpi: int, canvas_size):
        if not isinstance(exemplar, str) or exemplar not in EXEMPLARS:
            raise ValueError(f"unknown exemplar {exemplar!r}; choose one of {', '.join(EXEMPLARS)}")
        exemplar_seed = _check_int(exemplar_seed, "exemplar_seed", 0)
        seed = _check_int(seed, "seed", 0)
        rings = _check_int(rings, "rings", *RINGS_RANGE)
        amount = _check_real(amount, "amount", 0.0, 1.0)
        if not isinstance(choice, str) or choice not in ("close", "random", "best"):
            raise ValueError(f"choice must be 'close', 'random' or 'best', got {choice!r}")
        contour, vary = check_flag(contour, "contour"), check_flag(vary, "vary")
        try:
            canvas_size = tuple(_check_int(v, "canvas_size", 64) for v in canvas_size)
        except TypeError:
            raise ValueError(f"canvas_size must be a pair of integers, got {canvas_size!r:.60}") from None
        if len(canvas_size) != 2:
            raise ValueError(f"canvas_size must be a pair of integers, got {canvas_size!r}")
        self._figsize, self._dpi = figure_settings(figsize, dpi)
        self.pattern = self.analysis = self.synthesis = self.synthesis_epsilon = None
        self.target = self.figure = self.error = self._synthesis_analysis = None
        self.target_label = self.summary = self.message = ""
        self.drawn_points: list = []
        self._stroke_active = False
        self.times: dict = {}
        self.calls = {"exemplar": 0, "analyze": 0, "synthesize": 0}
        self._exemplars: dict = {}
        self._analyses: OrderedDict = OrderedDict()
        self._source = exemplar  # the exemplar shown (the dropdown goes back to it if a load fails)
        self._quiet_depth = 0
        self._build_controls(exemplar, exemplar_seed, contour, rings, amount, vary, choice, seed, canvas_size)
        self.widget = self._layout()
        self._connect()

    def _build_controls(self, exemplar, exemplar_seed, contour, rings, amount, vary, choice, seed, canvas_size):
        import ipywidgets as w
        from ipycanvas import Canvas

        wide = {"description_width": "initial"}
        self.exemplar = w.Dropdown(options=[(name.replace("_", " "), name) for name in EXEMPLARS], value=exemplar,
                                   description="exemplar", style=wide)
        self.exemplar_seed = w.BoundedIntText(value=exemplar_seed, min=0, max=2**31 - 1, description="exemplar seed",
                                              style=wide, layout=w.Layout(width="170px"))
        self.epsilon = w.FloatLogSlider(value=1.0, base=10, min=-EPSILON_DECADES, max=EPSILON_DECADES, step=0.02,
                                        description="epsilon (scale, sec. 2.2)", readout_format=".3g",
                                        continuous_update=True, style=wide, layout=w.Layout(width="460px"))
        self.contour = w.Checkbox(value=contour, description="fit on the pen contour (sec. 2.1)", indent=False)
        self.rings = w.IntSlider(value=rings, min=RINGS_RANGE[0], max=RINGS_RANGE[1], description="rings (k)",
                                 continuous_update=False, style=wide)
        self.amount = w.FloatSlider(value=amount, min=0.0, max=1.0, step=0.05, description="variation amount",
                                    continuous_update=False, style=wide)
        self.vary = w.Checkbox(value=vary, description="position variation (sec. 3.3)", indent=False)
        self.choice = w.ToggleButtons(options=[("close to best", "close"), ("random (paper)", "random"), ("best", "best")],
                                      value=choice,
                                      description="choice", style=wide)
        self.seed = w.BoundedIntText(value=seed, min=0, max=2**31 - 1, description="synthesis seed", style=wide,
                                     layout=w.Layout(width="170px"))
        self.target_mode = w.ToggleButtons(options=[("pick a preset", "preset"), ("draw on the canvas", "draw")],
                                           value="preset", description="target", style=wide)
        self.preset = w.Dropdown(options=[("straight line", "line")], value="line", description="preset", style=wide)
        self.clear_button = w.Button(description="clear drawing", icon="eraser")
        self.synthesize_button = w.Button(description="synthesize", icon="play", button_style="primary")
        self.canvas = Canvas(width=int(canvas_size[0]), height=int(canvas_size[1]),
                             layout=w.Layout(border="1px solid #999999"))
        self.image = w.Image(format="png", layout=w.Layout(max_width="100%"))
        self.status = w.HTML()

    def _layout(self):
        import ipywidgets as w

        targets = w.VBox([self.target_mode, self.preset, w.HBox([self.clear_button, self.synthesize_button])])
        return w.VBox([
            w.HBox([self.exemplar, self.exemplar_seed]),
            w.HBox([self.epsilon, self.contour]),
            w.HBox([self.rings, self.amount, self.vary]),
            w.HBox([self.choice, self.seed]),
            w.HBox([targets, self.canvas]),
            self.image,
            self.status,
        ])

    def _connect(self):
        on = self._on_change
        on(self.exemplar, self.load_exemplar)
        on(self.exemplar_seed, self.load_exemplar)
        on(self.epsilon, self.analyze)
        on(self.contour, self.analyze)
        for control in (self.rings, self.amount, self.vary, self.choice, self.seed, self.target_mode):
            on(control, self.synthesize)
        on(self.preset, self._on_preset)
        self.synthesize_button.on_click(lambda _: self.synthesize())
        self.clear_button.on_click(lambda _: self.clear_drawing())
        self._connect_canvas()

    # ------------------------------------------------------------------ actions

    def load_exemplar(self, epsilon: float | None = None) -> bool:
        """Generate the exemplar the controls name, analyse it and synthesize.

        Parameters
        ----------
        epsilon : float, optional
            The scale to start from; default the generator's epsilon (the slider is re-centred on it).

        Returns
        -------
        bool
            Whether a synthesis was produced; on failure ``message`` says why (nothing raised).
        """
        began = time.perf_counter()
        self.times = {}
        name, seed = self.exemplar.value, int(self.exemplar_seed.value)
        try:
            pattern = self._exemplar(name, seed)
        except Exception as error:  # a generator refusing a seed is shown, the previous exemplar stays
            with self._quiet():
                self.exemplar.value = self._source
            self.error, self.message = error, f"could not generate the exemplar {name!r}: {error}"
            self._show_status()
            return False
        if self.pattern is not None and pattern.dimension != self.pattern.dimension:
            with self._quiet():  # a path drawn for 1D is no region for 2D (and back): start from a preset
                self.target_mode.value = "preset"
        self.pattern, self._source = pattern, name
        self.synthesis = self.synthesis_epsilon = self.target = None
        self._set_epsilon_range(pattern.epsilon if epsilon is None else float(epsilon))
        self._set_presets(pattern.dimension)
        analysed = self._run_analysis()
        synthesized = analysed and self._run_synthesis()
        self._redraw_canvas()
        self._show(began)
        return bool(synthesized)

    def analyze(self) -> bool:
        """Re-run only the analysis at the current epsilon and contour, and redraw (the synthesis stays).

        Returns
        -------
        bool
            Whether the analysis succeeded; on failure ``message`` says why.
        """
        began = time.perf_counter()
        self.times = {}
        ok = self._run_analysis()
        self._show(began)
        return ok

    def synthesize(self) -> bool:
        """Synthesize along / inside the current target from the current analysis, then add the variation.

        Returns
        -------
        bool
            Whether a synthesis was produced; on failure ``message`` says why and ``synthesis`` is None.
        """
        began = time.perf_counter()
        self.times = {}
        self._run_synthesis()
        self._redraw_canvas()
        self._show(began)
        return self.error is None

    def _on_preset(self) -> None:
        """Picking a preset makes it the target (leaving the drawing), and synthesizes."""
        with self._quiet():
            self.target_mode.value = "preset"
        self.synthesize()

    def clear_drawing(self) -> None:
        """Forget the drawn target (the synthesis shown stays)."""
        self.drawn_points, self._stroke_active = [], False
        self._redraw_canvas()
        self.error, self.message = None, "drawing cleared: draw a new target on the canvas"
        self._show_status()

    # ------------------------------------------------------------------ steps

    def _exemplar(self, name: str, seed: int):
        key = (name, seed)
        if key not in self._exemplars:
            t0 = time.perf_counter()
            self._exemplars[key] = EXEMPLARS[name](rng=seed)
            self.times["exemplar"] = time.perf_counter() - t0
            self.calls["exemplar"] += 1
        return self._exemplars[key]

    def _set_epsilon_range(self, epsilon: float) -> None:
        """Centre the log slider on ``epsilon`` (EPSILON_DECADES each side) and set it, quietly."""
        centre = math.log10(epsilon)
        low, high = centre - EPSILON_DECADES, centre + EPSILON_DECADES
        slider = self.epsilon
        with self._quiet():
            slider.min, slider.max = min(low, slider.min), max(high, slider.max)
            slider.value = epsilon
            slider.min, slider.max = low, high

    def _set_presets(self, dimension: int) -> None:
        options = [(_PRESET_LABELS[name], name) for name in PRESETS[dimension]]
        with self._quiet():
            keep = self.preset.value if self.preset.value in PRESETS[dimension] else PRESETS[dimension][0]
            self.preset.options = options
            self.preset.value = keep

    def _run_analysis(self) -> bool:
        """The analysis at the controls' epsilon and contour (cached); sets ``analysis``, ``error``, ``message``."""
        epsilon, contour = float(self.epsilon.value), bool(self.contour.value)
        key = (self._source, int(self.exemplar_seed.value), epsilon, contour)
        try:
            if key in self._analyses:
                self._analyses.move_to_end(key)
                self.times["analysis"] = 0.0
            else:
                pattern = self.pattern
                t0 = time.perf_counter()
                self._analyses[key] = analyze(pattern.strokes, epsilon, dimension=pattern.dimension,
                                              contour=contour, path=pattern.path, region=pattern.region)
                self.times["analysis"] = time.perf_counter() - t0
                self.calls["analyze"] += 1
                while len(self._analyses) > ANALYSIS_CACHE:
                    self._analyses.popitem(last=False)
        except Exception as error:  # shown in the widget, never raised out of a callback
            self.analysis, self.error = None, error
            self.message = f"analysis failed at epsilon = {epsilon:.3g}: {error}"
            return False
        self.analysis, self.error, self.message = self._analyses[key], None, ""
        return True

    def current_target(self):
        """The target the controls describe, in pattern units, and a label for it.

        Returns
        -------
        target : numpy.ndarray (m, 2) or shapely geometry
        label : str

        Raises
        ------
        ValueError
            No exemplar, or a drawing that stands for no target (see :func:`drawn_target`).
        """
        if self.pattern is None:
            raise ValueError("no exemplar loaded")
        dimension = self.pattern.dimension
        if self.target_mode.value == "preset":
            extent = TARGET_FACTOR * _reference_extent(self.pattern)
            return preset_target(self.preset.value, extent), f"preset {_PRESET_LABELS[self.preset.value]}"
        target = drawn_target(self.canvas_to_pattern(self.drawn_points), dimension)
        return target, "drawn path" if dimension == 1 else "drawn region"

    def _run_synthesis(self) -> bool:
        notes = []
        try:
            if self.analysis is None:
                reason = f": {self.error}" if self.error is not None else ""
                raise ValueError(f"no analysis at epsilon = {float(self.epsilon.value):.3g}{reason}")
            target, label = self.current_target()
            if label == "drawn region" and not shapely.Polygon(self.canvas_to_pattern(self.drawn_points)).is_valid:
                notes.append("the drawn outline crosses itself: repaired into the parts it encloses")
            synthesis_rng, exchange_rng = np.random.default_rng(int(self.seed.value)).spawn(2)
            t0 = time.perf_counter()
            synthesis = synthesize(self.analysis, target, rings=int(self.rings.value), choice=self.choice.value,
                                   rng=synthesis_rng)
            self.times["synthesis"] = time.perf_counter() - t0
            self.calls["synthesize"] += 1
            if float(self.amount.value) > 0:
                t0 = time.perf_counter()
                synthesis = exchange_parameters(synthesis, self.analysis, float(self.amount.value), rng=exchange_rng)
                self.times["exchange"] = time.perf_counter() - t0
            if self.vary.value:
                t0 = time.perf_counter()
                synthesis = vary_positions(synthesis, self.analysis)
                self.times["positions"] = time.perf_counter() - t0
        except Exception as error:  # shown in the widget, never raised out of a callback
            self.synthesis = self.synthesis_epsilon = self._synthesis_analysis = None
            self.error = error
            self.message = f"synthesis failed: {error}"
            return False
        self.synthesis, self.synthesis_epsilon = synthesis, self.analysis.epsilon
        self._synthesis_analysis = self.analysis
        self.target, self.target_label = target, label
        self.error, self.message = None, "\n".join(notes)
        return True

    # ------------------------------------------------------------------ canvas

    @property
    def canvas_scale(self) -> float:
        """Pattern units per canvas pixel for the current exemplar (module docstring, *Canvas*)."""
        extent = TARGET_FACTOR * _reference_extent(self.pattern)
        if self.pattern.dimension == 1:
            return _CANVAS_LINE_SPAN * extent / self.canvas.width
        return math.sqrt(extent) / (_CANVAS_SQUARE_SPAN * self.canvas.height)

    def canvas_to_pattern(self, points) -> np.ndarray:
        """Canvas pixels (x right, y down) to pattern units (x right, y up), ``(m, 2)``.

        Parameters
        ----------
        points : array_like, shape (m, 2)
            Points in canvas pixels.

        Returns
        -------
        ndarray of float64, shape (m, 2)
            The points in pattern units.
        """
        return self._pixels_to_units(points)

    def _drawing_finished(self) -> None:
        """A released drawing becomes the target, and the pattern is synthesized along / inside it."""
        with self._quiet():
            self.target_mode.value = "draw"
        self.synthesize()

    def _draw_canvas(self) -> None:
        """Background, the reference's size for scale, a hint, and the drawing (closed in 2D)."""
        from ipycanvas import hold_canvas

        canvas = self.canvas
        with hold_canvas():
            canvas.clear()
            canvas.fill_style = "#fbfbfb"
            canvas.fill_rect(0, 0, canvas.width, canvas.height)
            if self.pattern is None:
                return
            self._draw_reference_size(canvas)
            canvas.fill_style = "#777777"
            canvas.font = "11px sans-serif"
            kind = "a path" if self.pattern.dimension == 1 else "the outline of a region"
            canvas.fill_text(f"press, drag and release to draw {kind}", 6, canvas.height - 8)
            self._paint_drawing(canvas, close=self.pattern.dimension == 2 and not self._stroke_active)

    def _draw_reference_size(self, canvas) -> None:
        """A grey box, top left, as large as the reference pattern at the canvas's scale."""
        points = np.vstack([stroke.points for stroke in self.pattern.strokes])
        if self.pattern.dimension == 2:
            xmin, ymin, xmax, ymax = self.pattern.region.bounds
        else:
            (xmin, ymin), (xmax, ymax) = points.min(axis=0), points.max(axis=0)
        scale = self.canvas_scale
        canvas.stroke_style, canvas.line_width = "#bbbbbb", 1
        canvas.stroke_rect(6, 18, (xmax - xmin) / scale, (ymax - ymin) / scale)
        canvas.fill_style = "#999999"
        canvas.font = "11px sans-serif"
        canvas.fill_text("reference size", 6, 13)

    # ------------------------------------------------------------------ results

    @property
    def n_elements(self) -> int | None:
        """Elements of the current analysis (None without one)."""
        return None if self.analysis is None else len(self.analysis)

    @property
    def fallback_fraction(self) -> float | None:
        """Fraction of the synthesized elements whose neighbourhood matched no reference one (the fallback)."""
        return None if self.synthesis is None else float(np.mean(self.synthesis.fallback))

    @property
    def stroke_hash(self) -> str | None:
        """SHA-256 of the synthesis's strokes (:func:`stroke_hash`; None without a synthesis)."""
        return None if self.synthesis is None else stroke_hash(self.synthesis.strokes)

    # ------------------------------------------------------------------ output

    def _summary_text(self) -> str:
        pattern = self.pattern
        if pattern is None:
            return "no exemplar loaded"
        kind = "1D, along a path" if pattern.dimension == 1 else "2D, in a region"
        lines = [f"{self._source} (seed {int(self.exemplar_seed.value)}, {kind}): {len(pattern.strokes)} strokes, "
                 f"{pattern.n_elements} elements by construction; generator epsilon {pattern.epsilon:.3g}"]
        epsilon = float(self.epsilon.value)
        if self.analysis is not None:
            truth = "= the truth" if len(self.analysis) == pattern.n_elements else f"truth {pattern.n_elements}"
            lines.append(f"analysis: epsilon {epsilon:.3g}{', contour' if self.contour.value else ''}: "
                         f"{len(self.analysis)} elements ({truth}), {len(self.analysis.edges)} neighbour edges")
        else:
            lines.append(f"analysis: none at epsilon {epsilon:.3g}")
        if self.synthesis is not None:
            synthesis = self.synthesis
            extra = [f"amount {float(self.amount.value):g}" if float(self.amount.value) > 0 else "",
                     "position variation" if self.vary.value else ""]
            stale = ("" if self._synthesis_analysis is self.analysis else
                     f" (made at epsilon {self.synthesis_epsilon:.3g}: press synthesize)")
            lines.append(f"synthesis ({self.target_label}): {len(synthesis)} elements, "
                         f"{self.fallback_fraction:.0%} fallback, {synthesis.rings} rings, choice {self.choice.value}, "
                         f"seed {int(self.seed.value)}" + "".join(f", {e}" for e in extra if e) + stale)
        else:
            lines.append("synthesis: none")
        if self.times:
            lines.append("seconds: " + ", ".join(f"{name} {value:.3f}" for name, value in self.times.items()))
        return "\n".join(lines)

    def _draw(self):
        from matplotlib.figure import Figure

        figure = Figure(figsize=self._figsize, layout="constrained")
        left, right = figure.subplots(1, 2)
        for ax in (left, right):
            ax.set(xticks=[], yticks=[])
            ax.set_aspect("equal")
        if self.pattern is not None:
            self.draw_reference(left)
            self.draw_synthesis(right)
        return figure

    def draw_reference(self, ax) -> None:
        """Draw the analysed reference on matplotlib axes: strokes coloured by element, boxes, neighbour graph.

        Parameters
        ----------
        ax : matplotlib.axes.Axes
            The axes to draw on.
        """
        pattern, analysis = self.pattern, self.analysis
        epsilon = float(self.epsilon.value)
        if analysis is None:
            plot_strokes(pattern.strokes, ax)
            ax.set_title(f"reference: {self._source}, epsilon {epsilon:.3g}: no analysis", fontsize=10)
            return
        colors = [CLUSTER_COLORS[label % len(CLUSTER_COLORS)] for label in analysis.element_of_stroke]
        plot_strokes(analysis.strokes, ax, colors=colors)
        plot_boxes(analysis.boxes, ax, edgecolors="0.3", linewidths=0.6)
        plot_graph(analysis.positions, analysis.edges, ax, colors="0.55", linewidths=0.6)
        ax.plot(*analysis.positions.T, ".", color="0.2", ms=3)
        ax.set_title(f"reference: {self._source}, epsilon {epsilon:.3g}: {len(analysis)} elements "
                     f"(truth {pattern.n_elements})", fontsize=10)

    def draw_synthesis(self, ax) -> None:
        """Draw the latest synthesis on matplotlib axes, with the target outline and the fallback elements.

        Parameters
        ----------
        ax : matplotlib.axes.Axes
            The axes to draw on.
        """
        synthesis = self.synthesis
        if synthesis is None:
            ax.text(0.5, 0.5, "no synthesis\n(see the message below)", ha="center", va="center",
                    transform=ax.transAxes, color="0.4")
            ax.set_title("synthesis", fontsize=10)
            return
        outlines = [np.asarray(self.target)] if synthesis.dimension == 1 else _outline_parts(self.target)
        for outline in outlines:
            ax.plot(*outline.T, "--", color="0.6", lw=0.8)
        plot_strokes(synthesis.elements, ax)
        fallback = np.asarray(synthesis.fallback)
        if fallback.any():
            ax.plot(*synthesis.positions[fallback].T, "x", color="#d62728", ms=4, mew=1)
        ax.set_title(f"synthesis ({self.target_label}): {len(synthesis)} elements, {self.fallback_fraction:.0%} "
                     f"fallback, k = {synthesis.rings}", fontsize=10)


# ---------------------------------------------------------------------------- factory


def _check_int(value, name: str, low: int, high: int | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low or (
            high is not None and value > high):
        bound = f"in [{low}, {high}]" if high is not None else f">= {low}"
        raise ValueError(f"{name} must be an integer {bound}, got {value!r}")
    return int(value)


def _check_real(value, name: str, low: float, high: float | None = None, *, open_low: bool = False) -> float:
    ok = not isinstance(value, bool) and isinstance(value, (int, float, np.number)) and math.isfinite(value)
    if ok:
        ok = (value > low if open_low else value >= low) and (high is None or value <= high)
    if not ok:
        bound = f"> {low:g}" if open_low else f">= {low:g}"
        raise ValueError(f"{name} must be a finite number {bound}{f' and <= {high:g}' if high is not None else ''}, "
                         f"got {value!r}")
    return float(value)


def strokepattern_explorer(exemplar: str = "sketchy_hatching", *, exemplar_seed: int = 0, epsilon: float | None = None,
                           contour: bool = False, rings: int = 2, amount: float = 0.0, vary: bool = False,
                           choice: str = "close", seed: int = 0, target: str | None = None, figsize=(11, 4.5),
                           dpi: int = 80, canvas_size=(420, 240)) -> StrokePatternExplorer:
    """An interactive explorer of Barla 2006's stroke pattern analysis and synthesis.

    Builds the controls, generates ``exemplar``, analyses it at ``epsilon``, synthesizes once on the preset
    ``target`` and returns the explorer; ``display(explorer)`` (or ``explorer.widget``) shows it. See the
    module docstring for the design.

    Parameters
    ----------
    exemplar : str
        One of :data:`EXEMPLARS`: ``sketchy_hatching``, ``jittered_hatching``, ``gradient_orientation``,
        ``gradient_length``, ``gradient_thickness``, ``alternating_color`` (1D); ``bars``, ``drops``,
        ``flowers``, ``two_hatchings``, ``irregular`` (2D).
    exemplar_seed : int
        Seed of the exemplar generator (>= 0).
    epsilon : float, optional
        The first scale (> 0); default the generator's epsilon, at which the clustering finds its elements.
    contour : bool
        Fit element boxes on the pen's contour (section 2.1) instead of the skeleton.
    rings : int
        k of the k-ring neighbourhoods, 1 to 5.
    amount : float
        Parameter-exchange amount in [0, 1] (section 3.3; 0: none).
    vary : bool
        Apply the position variation (section 3.3).
    choice : {"close", "random", "best"}
        Among the matching reference neighbourhoods: a random one within a tenth of a threshold of the best
        (default, Efros and Leung's rule), a random one (the paper) or the best scored.
    seed : int
        Seed of the synthesis (>= 0); same seed, same strokes.
    target : str, optional
        The first preset, one of :data:`PRESETS` for the exemplar's dimension; default the first (a straight
        line in 1D, a square in 2D).
    figsize : pair of float
        Figure size in inches.
    dpi : int
        Resolution of the figure shown in the widget.
    canvas_size : pair of int
        Width and height of the drawing canvas, pixels (each at least 64).

    Returns
    -------
    StrokePatternExplorer

    Raises
    ------
    ValueError
        For an argument outside the ranges above (at construction; later, errors are shown in the widget).

    References
    ----------
    Barla et al. 2006, sections 2 (interactive analysis at the user scale), 3 (synthesis, variation) and 4.
    """
    if epsilon is not None:
        epsilon = _check_real(epsilon, "epsilon", 0.0, open_low=True)
    explorer = StrokePatternExplorer(exemplar=exemplar, exemplar_seed=exemplar_seed, contour=contour,
                                     rings=rings, amount=amount, vary=vary, choice=choice, seed=seed,
                                     figsize=figsize, dpi=dpi, canvas_size=canvas_size)
    if target is not None:
        dimension = explorer._exemplar(exemplar, exemplar_seed).dimension
        if target not in PRESETS[dimension]:
            raise ValueError(f"target {target!r} is not a {dimension}D preset; choose one of "
                             f"{', '.join(PRESETS[dimension])}")
        explorer._set_presets(dimension)
        with explorer._quiet():
            explorer.preset.value = target
    explorer.load_exemplar(epsilon)
    return explorer
