"""Interactive explorer of Hurtut 2009: categorize an exemplar, fit, re-synthesize.

:func:`arrangement_explorer` builds an ipywidgets panel on top of :mod:`paperlib.arrangement`:
pick one of the seeded exemplars of :mod:`paperlib.datasets` (or load an SVG drawing), see its
appearance categories (section 2.2, or the generator's ground truth), and tune the synthesis
(section 3.3): the number T of Metropolis-Hastings steps, the size of the synthesis window
W_S, and a gray-level density image (the brush of Figure 7, section 4.1). The figure shows
the exemplar coloured by category beside the synthesis, with the density image faintly under
it; a text line gives the counts per category, the fitted parameters of the multitype Strauss
hard-core model (eq. 2) and the wall times.

Design
------
*Plain methods.* Everything a control does is a method of :class:`ArrangementExplorer`
(:meth:`~ArrangementExplorer.load_exemplar`, :meth:`~ArrangementExplorer.load_svg`,
:meth:`~ArrangementExplorer.synthesize`, ...), so tests and notebooks drive the explorer
without a browser, and a control's callback only calls a method.

*Errors are messages.* A failing step (a missing or malformed SVG, a category of fewer than
3 elements, a window too small for the hard cores) never raises out of a method or a
callback: the step's exception is kept in ``error`` and shown in the widget; a failed load
leaves the previous drawing in place. Warnings of the steps (e.g. a window narrower than a
hard core) are shown too.

*Caching.* Categorization and fit depend only on the drawing and the label source: they are
computed once per drawing (per label source) and reused, so changing T, the window scale,
the density or the seed re-runs only the synthesis (``calls`` counts each step).

*Headless.* The figure is a plain :class:`matplotlib.figure.Figure` (no pyplot state),
rendered to PNG bytes into an :class:`ipywidgets.Image`: it works with the Agg backend, in
papermill and in tests, and the latest figure is ``explorer.figure``.

*Windows.* A generated exemplar is fitted in ``exemplar.pattern.window``, the frame where its
positions were generated (see :mod:`paperlib.datasets.exemplars`); categorization uses the
drawing frame's area as the reference surface. An SVG drawing has no other frame than its
ink: its window is the bounding box of all its strokes, for both. The synthesis window is the
fitting window scaled by ``window_scale`` about its lower-left corner (both sides).

*Density images* (values are factors of the fitted beta, row 0 at the top, as
:func:`paperlib.arrangement.synthesize` reads them): ``"uniform"`` (none), ``"gradient"``
(0 at the left edge to 1 at the right), ``"radial"`` (1 at the centre, falling linearly to 0
on the ellipse inscribed in the window) and ``"image"``: a grayscale image of
:func:`paperlib.datasets.grayscale_image`, resized to the window's aspect, with dark pixels
dense (density = 1 - gray), as ink on paper.

Written by hand: the layout and the bookkeeping; every computation is a call to
:mod:`paperlib.arrangement`, drawing is matplotlib, resizing is scikit-image.

References
----------
Hurtut, T., Landes, P.-E., Thollot, J., Gousseau, Y., Drouilhet, R., Coeurjolly, J.-F.
(2009). Appearance-guided synthesis of element arrangements by example. NPAR, sections 2.2
(categorization), 3.2 (fit), 3.3 (synthesis) and 4.1 (Figure 7: density brush; about 5 s to
categorize and generate each example).
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from paperlib import datasets
from paperlib._checks import check_choice
from paperlib.widgets._base import ExplorerBase, check_file_root, figure_settings, uploaded_file, user_path
from paperlib.arrangement import Arrangement, adjusted_rand_index, categorize, fit, render, synthesize
from paperlib.arrangement import element_positions
from paperlib.geometry import as_elements, read_svg
from paperlib.pointprocess import PointPattern, Window

__all__ = ["DENSITY_KINDS", "EXEMPLARS", "INTERACTIONS", "ArrangementExplorer", "Drawing", "arrangement_explorer",
           "density_image", "scaled_window"]

#: The exemplar generators offered, by name (all of :mod:`paperlib.datasets.exemplars`).
EXEMPLARS = {
    "two_category": datasets.two_category_exemplar,
    "big_small": datasets.big_small_exemplar,
    "regularity": datasets.regularity_exemplar,
    "lattice": datasets.lattice_exemplar,
    "hatching": datasets.hatching_exemplar,
    "drawn_hatching": datasets.drawn_hatching_exemplar,
    "near_identical": datasets.near_identical_exemplar,
    "amacrine": datasets.amacrine_exemplar,
}
#: Density images offered by :func:`density_image`.
DENSITY_KINDS = ("uniform", "gradient", "radial", "image")
SVG_SOURCE = "svg"  # the exemplar dropdown's entry for a loaded SVG drawing
T_RANGE = (1_000, 100_000)
SCALE_RANGE = (0.5, 3.0)
MIN_FIT_SIZE = 3  # Hurtut 2009, section 3.2: at least three elements per category
#: Pair distances of the interactions offered (:func:`paperlib.arrangement.fit`'s ``interaction``).
INTERACTIONS = ("centre", "box_hausdorff", "box_gap")


# ---------------------------------------------------------------------------- plain functions


def scaled_window(window: Window, scale: float) -> Window:
    """The rectangle of ``window``'s frame with both sides scaled by ``scale``, lower-left corner kept.

    Parameters
    ----------
    window : Window
        The exemplar's fitting window W_R (its frame is used).
    scale : float
        Factor on each side, > 0 (the area is multiplied by ``scale ** 2``).

    Returns
    -------
    Window
        A rectangle: the synthesis window W_S (Hurtut 2009, section 3.3, "at the desired scale").
    """
    if not isinstance(window, Window):
        raise TypeError(f"window must be a paperlib.pointprocess.Window, got {type(window).__name__}")
    if isinstance(scale, bool) or not isinstance(scale, (int, float, np.number)) or not (
            math.isfinite(scale) and scale > 0):
        raise ValueError(f"scale must be a positive finite number, got {scale!r}")
    (x0, _), (y0, _) = window.xrange, window.yrange
    return Window.rectangle((x0, x0 + scale * window.width), (y0, y0 + scale * window.height))


def density_image(kind: str, window: Window, *, image: str = "camera", resolution: int = 64):
    """A gray-level density image over ``window``'s frame (the brush of Hurtut 2009, Figure 7).

    Parameters
    ----------
    kind : {"uniform", "gradient", "radial", "image"}
        See the module docstring.
    window : Window
        The synthesis window; the image covers its frame, with square-ish pixels.
    image : str
        For ``kind="image"``: a name of :func:`paperlib.datasets.grayscale_names`.
    resolution : int
        Pixels along the longer side of the frame (>= 2).

    Returns
    -------
    numpy.ndarray or None
        ``None`` for ``"uniform"`` (the fitted intensity everywhere); otherwise an array of
        values in [0, 1], row 0 at the top, for ``synthesize(..., density=...)``.

    Raises
    ------
    ValueError
        For an unknown ``kind`` or image name, or ``resolution < 2``.

    References
    ----------
    Hurtut et al. (2009), section 4.1, Figure 7 (user-drawn gray-level density).
    """
    check_choice(kind, DENSITY_KINDS, "density kind")
    if isinstance(resolution, bool) or not isinstance(resolution, (int, np.integer)) or resolution < 2:
        raise ValueError(f"resolution must be an integer >= 2, got {resolution!r}")
    if not isinstance(window, Window):
        raise TypeError(f"window must be a paperlib.pointprocess.Window, got {type(window).__name__}")
    if kind == "uniform":
        return None
    longer = max(window.width, window.height)
    rows = max(2, round(resolution * window.height / longer))
    cols = max(2, round(resolution * window.width / longer))
    if kind == "gradient":
        return np.tile(np.linspace(0.0, 1.0, cols), (rows, 1))
    if kind == "radial":
        v, u = np.meshgrid(np.linspace(-1, 1, rows), np.linspace(-1, 1, cols), indexing="ij")
        return np.clip(1.0 - np.hypot(u, v), 0.0, 1.0)
    from skimage.transform import resize

    gray = resize(datasets.grayscale_image(image), (rows, cols), anti_aliasing=True)
    return np.clip(1.0 - gray, 0.0, 1.0)


# ---------------------------------------------------------------------------- state


@dataclass(frozen=True, eq=False)
class Drawing:
    """The exemplar the explorer works on.

    Parameters
    ----------
    name : str
        Generator name, or the SVG file name.
    elements : list of Element
        The drawing's elements.
    frame : Window
        The drawing's frame (its area is the categorization's reference surface).
    window : Window
        The fitting window W_R (every element position inside).
    truth : numpy.ndarray or None
        Ground-truth category of each element (index into ``truth_categories``); None for SVG.
    truth_categories : tuple or None
        The ground-truth category names; None for SVG.
    description : str
        One sentence saying what the drawing is.
    """

    name: str
    elements: list
    frame: Window
    window: Window
    truth: np.ndarray | None
    truth_categories: tuple | None
    description: str


def _exemplar_drawing(name: str, seed: int) -> Drawing:
    if name not in EXEMPLARS:
        raise ValueError(f"unknown exemplar {name!r}; choose one of {', '.join(EXEMPLARS)}")
    generator = EXEMPLARS[name]
    exemplar = generator() if name == "amacrine" else generator(rng=seed)  # amacrine is data, not random
    return Drawing(name, list(exemplar.elements), exemplar.window, exemplar.pattern.window,
                   np.asarray(exemplar.labels), tuple(exemplar.categories), exemplar.description)


def _svg_drawing(path_or_bytes, name: str | None = None) -> Drawing:
    """The drawing of an SVG file (a Path) or of an uploaded document (bytes, with its file ``name``)."""
    if isinstance(path_or_bytes, bytes):
        path = Path(name or "uploaded.svg")
    else:
        path = Path(path_or_bytes)
        if not path.is_file():
            raise FileNotFoundError(f"no SVG file at {str(path)!r}")
    elements = as_elements(read_svg(path_or_bytes))
    bounds = np.array([element.bounds() for element in elements])
    (x0, y0), (x1, y1) = bounds[:, :2].min(axis=0), bounds[:, 2:].max(axis=0)
    if not (x1 > x0 and y1 > y0):
        raise ValueError(f"the drawing in {path.name} is flat (its bounding box has zero area)")
    frame = Window.rectangle((float(x0), float(x1)), (float(y0), float(y1)))
    description = f"{len(elements)} elements read from {path.name}; window: the drawing's bounding box"
    return Drawing(path.name, elements, frame, frame, None, None, description)


# ---------------------------------------------------------------------------- the explorer


class ArrangementExplorer(ExplorerBase):
    """Widgets and state of the Hurtut 2009 explorer (built by :func:`arrangement_explorer`).

    Parameters
    ----------
    exemplar : str
        One of :data:`EXEMPLARS` (``two_category``, ``big_small``, ``regularity``,
        ``lattice``, ``hatching``, ``drawn_hatching``, ``near_identical``, ``amacrine``).
    exemplar_seed : int
        Seed of the exemplar generator and of categorize's ROBPCA.
    seed : int
        Seed of the synthesis (same seed, same arrangement).
    T : int
        Metropolis-Hastings steps, in [1e3, 1e5] (the paper uses 1e5).
    window_scale : float
        Side of the synthesis window over the exemplar's, in [0.5, 3].
    density : {"uniform", "gradient", "radial", "image"}
        Density image (:func:`density_image`).
    labels : {"categorize", "truth"}
        Categories from section 2.2's categorization or the generator's ground truth.
    interaction : {"centre", "box_hausdorff", "box_gap"}
        The pair distance of the model: element positions (the paper's model), or the
        elements' bounding boxes (section 4.3's proposal, and our gap variant).
    image : str
        Grayscale image of the ``"image"`` density (:func:`paperlib.datasets.grayscale_names`).
    figsize : pair of float
        Figure size in inches.
    dpi : int
        Resolution of the figure shown in the widget.
    file_root : str, os.PathLike or None
        None: the SVG box reads any path. A folder: the box reads only files inside it (relative
        paths from it), as a served app must (:mod:`paperlib.apps`); the upload button reads files
        from the browser either way.

    Attributes
    ----------
    widget : ipywidgets.VBox
        The panel to ``display``.
    exemplar, exemplar_seed, labels, drop_small, svg_path, load_button, T, window_scale,
    density, seed, resynthesize_button : ipywidgets controls
        See :func:`arrangement_explorer`.
    upload : ipywidgets.FileUpload
        Loads an SVG drawing from the browser (the only way in for files outside ``file_root``).
    image : ipywidgets.Image
        The figure, as PNG.
    status : ipywidgets.HTML
        Counts, fitted parameters, times and messages.
    drawing : Drawing or None
        The current exemplar.
    categorization : Categorization or None
        Section 2.2's result on the current drawing (computed on demand, cached).
    model : ArrangementModel or None
        The fitted model used by the latest synthesis.
    arrangement : Arrangement or None
        The latest synthesis (None after a failure).
    density_array : numpy.ndarray or None
        The density image of the latest synthesis.
    figure : matplotlib.figure.Figure or None
        The latest figure.
    summary : str
        The status text, plain.
    message : str
        Errors and warnings of the latest action ("" if none).
    error : Exception or None
        The exception of the latest failed step.
    times : dict
        Wall time (s) of the latest categorize, fit, synthesize and total.
    calls : dict
        How many times each step ran (categorize, fit, synthesize): shows the caching.
    """

    def __init__(self, *, exemplar: str, exemplar_seed: int, seed: int, T: int, window_scale: float,
                 density: str, labels: str, interaction: str, image: str, figsize, dpi: int, file_root=None):
        import ipywidgets as w

        _check_choice(exemplar, tuple(EXEMPLARS), "exemplar")
        _check_choice(density, DENSITY_KINDS, "density")
        _check_choice(labels, ("categorize", "truth"), "labels")
        _check_choice(interaction, INTERACTIONS, "interaction")
        _check_choice(image, tuple(datasets.grayscale_names()), "image")
        for name, value in (("exemplar_seed", exemplar_seed), ("seed", seed)):
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 0 <= value < 2**31:
                raise ValueError(f"{name} must be an integer in [0, 2**31), got {value!r}")
        if isinstance(T, bool) or not isinstance(T, (int, np.integer)) or not T_RANGE[0] <= T <= T_RANGE[1]:
            raise ValueError(f"T must be an integer in [{T_RANGE[0]}, {T_RANGE[1]}], got {T!r}")
        if (isinstance(window_scale, bool) or not isinstance(window_scale, (int, float))
                or not SCALE_RANGE[0] <= window_scale <= SCALE_RANGE[1]):
            raise ValueError(f"window_scale must be in [{SCALE_RANGE[0]}, {SCALE_RANGE[1]}], got {window_scale!r}")
        exemplar_seed, seed, T, window_scale = int(exemplar_seed), int(seed), int(T), float(window_scale)
        self._figsize, self._dpi = figure_settings(figsize, dpi)
        self._file_root = check_file_root(file_root)
        self._image_name = image
        self.drawing = self.categorization = self.model = self.arrangement = None
        self.density_array = self.figure = self.error = None
        self.summary = self.message = ""
        self.times: dict = {}
        self.calls = {"categorize": 0, "fit": 0, "synthesize": 0}
        self._models: dict = {}
        self._source = exemplar  # the dropdown entry of the drawing shown
        self._quiet_depth = 0
        self._build_controls(w, exemplar, exemplar_seed, seed, T, window_scale, density, labels, interaction, image)
        self._connect()

    # ------------------------------------------------------------------ layout

    def _build_controls(self, w, exemplar, exemplar_seed, seed, T, window_scale, density, labels, interaction,
                        image):
        wide = {"description_width": "initial"}
        options = [(name.replace("_", " "), name) for name in EXEMPLARS] + [("SVG file", SVG_SOURCE)]
        self.exemplar = w.Dropdown(options=options, value=exemplar, description="exemplar", style=wide)
        self.exemplar_seed = w.BoundedIntText(value=exemplar_seed, min=0, max=2**31 - 1, description="exemplar seed",
                                              style=wide, layout=w.Layout(width="170px"))
        self.labels = w.ToggleButtons(options=[("categorize (sec. 2.2)", "categorize"), ("ground truth", "truth")],
                                      value=labels, description="categories", style=wide)
        self.interaction = w.Dropdown(options=[("centres (sec. 3)", "centre"),
                                               ("box Hausdorff (sec. 4.3)", "box_hausdorff"),
                                               ("box gap (ours)", "box_gap")],
                                      value=interaction, description="interaction", style=wide)
        self.drop_small = w.Checkbox(value=False, description=f"drop categories of < {MIN_FIT_SIZE} elements",
                                     indent=False)
        where = "path/to/drawing.svg" if self._file_root is None else f"drawing.svg (in {self._file_root.name}/)"
        self.svg_path = w.Text(value="", placeholder=where, description="SVG", style=wide,
                               layout=w.Layout(width="420px"))
        self.load_button = w.Button(description="load SVG", icon="folder-open")
        self.upload = w.FileUpload(accept=".svg,.svgz", multiple=False, description="upload SVG")
        self.T = w.FloatLogSlider(value=T, base=10, min=math.log10(T_RANGE[0]), max=math.log10(T_RANGE[1]),
                                  step=0.05, description="T (MCMC steps)", readout_format=".3g",
                                  continuous_update=False, style=wide)
        self.window_scale = w.FloatSlider(value=window_scale, min=SCALE_RANGE[0], max=SCALE_RANGE[1], step=0.1,
                                          description="window scale", continuous_update=False, style=wide)
        density_options = [("uniform", "uniform"), ("left-right gradient", "gradient"), ("radial", "radial"),
                           (f"image: {image}", "image")]
        self.density = w.Dropdown(options=density_options, value=density, description="density", style=wide)
        self.seed = w.BoundedIntText(value=seed, min=0, max=2**31 - 1, description="seed", style=wide,
                                     layout=w.Layout(width="130px"))
        self.resynthesize_button = w.Button(description="re-synthesize (next seed)", icon="refresh",
                                            layout=w.Layout(width="210px"))
        self.image = w.Image(format="png", layout=w.Layout(max_width="100%"))
        self.status = w.HTML()
        self.widget = w.VBox([
            w.HBox([self.exemplar, self.exemplar_seed, self.labels]),
            w.HBox([self.svg_path, self.load_button, self.upload, self.drop_small]),
            w.HBox([self.interaction]),
            w.HBox([self.T, self.window_scale]),
            w.HBox([self.density, self.seed, self.resynthesize_button]),
            self.image,
            self.status,
        ])

    def _connect(self):
        on = self._on_change
        on(self.exemplar, self._on_exemplar)
        on(self.exemplar_seed, self._on_exemplar)
        on(self.labels, self.synthesize)
        on(self.drop_small, self.synthesize)
        on(self.interaction, self.synthesize)
        for control in (self.T, self.window_scale, self.density, self.seed):
            on(control, self.synthesize)
        self.load_button.on_click(lambda _: self.load_svg(self.svg_path.value))
        self.upload.observe(lambda _: self.load_upload(), names="value")
        self.resynthesize_button.on_click(lambda _: self.next_seed())

    # ------------------------------------------------------------------ actions

    def _on_exemplar(self):
        if self.exemplar.value == SVG_SOURCE:
            self.load_svg(self.svg_path.value)
        else:
            self.load_exemplar(self.exemplar.value)

    def load_exemplar(self, name: str) -> bool:
        """Generate exemplar ``name`` (seed ``exemplar_seed``), categorize, fit and synthesize.

        Parameters
        ----------
        name : str
            One of :data:`EXEMPLARS`.

        Returns
        -------
        bool
            Whether a synthesis was produced; on failure ``message`` says why (nothing raised).
        """
        return self._load(lambda: _exemplar_drawing(name, int(self.exemplar_seed.value)), name)

    def load_svg(self, path) -> bool:
        """Read the elements of an SVG file (:func:`paperlib.geometry.read_svg`) and synthesize.

        The window is the drawing's bounding box. A missing or unreadable file leaves the
        current drawing in place and shows the error.

        Parameters
        ----------
        path : str or os.PathLike
            The SVG file (inside ``file_root`` when the explorer has one).

        Returns
        -------
        bool
            Whether a synthesis was produced.
        """
        with self._quiet():
            self.svg_path.value = str(path)
        return self._load(lambda: _svg_drawing(user_path(path, self._file_root, "SVG")), SVG_SOURCE)

    def load_upload(self) -> bool:
        """Read the SVG file last chosen in the **upload SVG** button and synthesize (as :meth:`load_svg`).

        Returns
        -------
        bool
            Whether a synthesis was produced (False, with nothing changed, when no file is chosen).
        """
        chosen = uploaded_file(self.upload)
        if chosen is None:
            return False
        name, content = chosen
        return self._load(lambda: _svg_drawing(content, name), SVG_SOURCE)

    def _svg_label_note(self) -> list:
        """An SVG has no ground truth: switch the label source to categorize, and say so."""
        if self._source != SVG_SOURCE or self.labels.value != "truth":
            return []
        with self._quiet():
            self.labels.value = "categorize"
        return ["an SVG drawing has no ground-truth labels: categories from categorize"]

    def _load(self, make, source: str) -> bool:
        began = time.perf_counter()
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                drawing = make()
        except Exception as error:  # a bad file or name is the user's, not a crash
            with self._quiet():  # the dropdown goes back to the drawing still shown
                self.exemplar.value = self._source
            self._fail(error, "could not load the exemplar")
            return False
        self.drawing, self.categorization, self._models, self._source = drawing, None, {}, source
        with self._quiet():
            self.exemplar.value = source
        return self._update(began, _warning_lines(caught) + self._svg_label_note())

    def next_seed(self) -> bool:
        """Re-synthesize with the next seed (the re-synthesize button).

        Returns
        -------
        bool
            Whether a synthesis was produced (see :meth:`synthesize`).
        """
        with self._quiet():
            self.seed.value = int(self.seed.value) + 1
        return self.synthesize()

    def synthesize(self) -> bool:
        """Synthesize with the current controls, reusing the cached categorization and fit.

        Returns
        -------
        bool
            Whether a synthesis was produced.
        """
        return self._update(time.perf_counter(), [])

    def _update(self, began: float, notes: list) -> bool:
        self.times = {}
        self.error, self.arrangement, self.model, self.density_array = None, None, None, None
        if self.drawing is None:
            self._fail(ValueError("no exemplar loaded"), "nothing to synthesize")
            return False
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                self.model = self._fitted_model()
                self._run_synthesis()
        except Exception as error:  # shown in the widget, never raised out of a callback
            self.error = error
            notes = notes + [f"{type(error).__name__}: {error}"]
        self.message = "\n".join(notes + _warning_lines(caught, skip=RuntimeWarning))
        self._show(began)
        return self.error is None

    def _fail(self, error: Exception, what: str):
        self.error = error
        self.message = f"{what}: {type(error).__name__}: {error}"
        self._show(time.perf_counter())

    # ------------------------------------------------------------------ steps (cached)

    def _categorization(self):
        if self.categorization is None:
            t0 = time.perf_counter()
            self.categorization = categorize(self.drawing.elements, self.drawing.frame.area,
                                             rng=int(self.exemplar_seed.value))
            self.times["categorize"] = time.perf_counter() - t0
            self.calls["categorize"] += 1
        return self.categorization

    def current_labels(self) -> tuple[np.ndarray, tuple]:
        """Category index of each element and category names, from the chosen label source.

        Returns
        -------
        labels : numpy.ndarray of int
            Category index of each element of ``drawing``.
        categories : tuple
            The category names the labels index.

        Raises
        ------
        ValueError
            When ground truth is asked of an SVG drawing, which has none.
        """
        if self.labels.value == "truth":
            if self.drawing.truth is None:
                raise ValueError("an SVG drawing has no ground-truth labels: choose 'categorize'")
            return self.drawing.truth, self.drawing.truth_categories
        result = self._categorization()
        return result.labels, result.categories

    def _fitted_model(self):
        key = (self.labels.value, bool(self.drop_small.value), self.interaction.value)
        if key not in self._models:
            labels, names = self.current_labels()
            keep = np.ones(len(labels), dtype=bool)
            counts = np.bincount(labels, minlength=len(names))
            if self.drop_small.value:
                keep = counts[labels] >= MIN_FIT_SIZE
            kept = tuple(name for name, count in zip(names, counts) if count and (count >= MIN_FIT_SIZE
                                                                                   or not self.drop_small.value))
            if not kept:
                raise ValueError(f"every category has fewer than {MIN_FIT_SIZE} elements: nothing to fit")
            elements = [e for e, k in zip(self.drawing.elements, keep) if k]
            t0 = time.perf_counter()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)  # pseudolikelihood on nearly empty shells
                self._models[key] = fit(elements, np.asarray(names, dtype=object)[labels[keep]],
                                        self.drawing.window, categories=kept, interaction=self.interaction.value)
            self.times["fit"] = time.perf_counter() - t0
            self.calls["fit"] += 1
        return self._models[key]

    def _run_synthesis(self):
        window = scaled_window(self.drawing.window, float(self.window_scale.value))
        self.density_array = density_image(self.density.value, window, image=self._image_name)
        t0 = time.perf_counter()
        self.arrangement = synthesize(self.model, window, density=self.density_array,
                                      T=int(round(self.T.value)), rng=int(self.seed.value))
        self.times["synthesize"] = time.perf_counter() - t0
        self.calls["synthesize"] += 1

    # ------------------------------------------------------------------ output

    def _summary_text(self) -> str:
        if self.drawing is None:
            return "no exemplar loaded"
        lines = [f"{self.drawing.name}: {self.drawing.description}"]
        lines += self._category_lines()
        if self.model is not None:
            lines.append(_parameters_line(self.model))
        if self.arrangement is not None:
            counts = np.bincount(self.arrangement.pattern.marks, minlength=len(self.arrangement.categories))
            lines.append(f"synthesis: {len(self.arrangement)} elements ("
                         + ", ".join(f"{c}: {k}" for c, k in zip(self.arrangement.categories, counts)) + ")")
        lines.append("wall time: " + ", ".join(f"{k} {v:.2f} s" for k, v in self.times.items()))
        return "\n".join(lines)

    def _category_lines(self) -> list:
        try:
            labels, names = self.current_labels()
        except Exception:  # the error is already in the message
            return []
        counts = np.bincount(labels, minlength=len(names))
        line = (f"exemplar: {len(labels)} elements, {len(names)} categories ({self.labels.value}): "
                + ", ".join(f"{c}: {k}" for c, k in zip(names, counts)))
        if self.labels.value == "categorize" and self.drawing.truth is not None:
            line += f"; ARI vs ground truth {adjusted_rand_index(labels, self.drawing.truth):.3f}"
        return [line]

    def _draw(self):
        from matplotlib.figure import Figure
        from matplotlib.patches import Patch

        figure = Figure(figsize=self._figsize, layout="constrained")
        left, right = figure.subplots(1, 2)
        for ax in (left, right):
            ax.set(xticks=[], yticks=[])
        if self.drawing is None:
            return figure
        exemplar = self._exemplar_arrangement()
        if exemplar is not None:
            render(exemplar, ax=left, color_by_category=True)
            left.legend(handles=[Patch(color=c, label=str(n)) for c, n in zip(exemplar.colors(), exemplar.categories)],
                        fontsize=7, loc="upper left", bbox_to_anchor=(0, -0.01), ncols=4, frameon=False)
        left.set_title(f"exemplar: {self.drawing.name}", fontsize=10)
        if self.arrangement is None:
            right.text(0.5, 0.5, "no synthesis\n(see the message below)", ha="center", va="center",
                       transform=right.transAxes, color="0.4")
            right.set_title("synthesis", fontsize=10)
            return figure
        self._draw_density(right)
        render(self.arrangement, ax=right, color_by_category=True)
        (x0, x1), (y0, y1) = self.drawing.window.xrange, self.drawing.window.yrange
        right.plot([x0, x1, x1, x0, x0], [y0, y0, y1, y1, y0], "k--", lw=0.8, label="exemplar window")
        right.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0, -0.01), frameon=False)
        right.set_title(f"synthesis: T = {int(round(self.T.value)):,}, window x {self.window_scale.value:g}, "
                        f"density {self.density.value}, seed {self.seed.value}", fontsize=10)
        return figure

    def _draw_density(self, ax):
        if self.density_array is None:
            return
        window = self.arrangement.window
        ax.imshow(self.density_array, extent=(*window.xrange, *window.yrange), origin="upper", cmap="Greys",
                  vmin=0, vmax=1, alpha=0.3, interpolation="nearest", zorder=0)

    def _exemplar_arrangement(self):
        """The drawing as an Arrangement coloured by its current categories (None if not drawable)."""
        try:
            labels, names = self.current_labels()
            pattern = PointPattern(element_positions(self.drawing.elements), self.drawing.frame,
                                   np.asarray(labels), tuple(str(n) for n in names))
        except Exception:  # e.g. coincident positions in an SVG: the fit reports it
            return None
        return Arrangement(pattern, list(self.drawing.elements), np.asarray(labels), self.drawing.frame,
                           tuple(names))


def _warning_lines(caught, skip=()) -> list:
    return [f"warning: {w.message}" for w in caught if not issubclass(w.category, skip or ())]


def _parameters_line(model) -> str:
    m = model.model
    fmt = {"float_kind": lambda v: f"{v:.3g}"}

    def matrix(a):
        return np.array2string(np.asarray(a), formatter=fmt, separator=" ").replace("\n", "")

    return (f"fitted: beta {matrix(m.beta)}, gamma {matrix(m.gamma)}, r {matrix(m.r)}, "
            f"hard core {matrix(m.hc)}")


def arrangement_explorer(exemplar: str = "two_category", *, exemplar_seed: int = 0, seed: int = 0,
                         T: int = 100_000, window_scale: float = 1.0, density: str = "uniform",
                         labels: str = "categorize", interaction: str = "centre", image: str = "camera",
                         figsize=(11, 5), dpi: int = 80, svg=None, file_root=None) -> ArrangementExplorer:
    """An interactive explorer of Hurtut 2009's categorization and synthesis.

    Builds the controls, loads ``exemplar`` (or the SVG file ``svg``), categorizes, fits and
    synthesizes once, and returns the explorer; ``display(explorer)`` (or
    ``explorer.widget``) shows it. See the module docstring for the design.

    Parameters
    ----------
    exemplar : str
        One of :data:`EXEMPLARS` (``two_category``, ``big_small``, ``regularity``,
        ``lattice``, ``hatching``, ``drawn_hatching``, ``near_identical``, ``amacrine``).
    exemplar_seed : int
        Seed of the exemplar generator and of categorize's ROBPCA.
    seed : int
        Seed of the synthesis (same seed, same arrangement).
    T : int
        Metropolis-Hastings steps, in [1e3, 1e5] (the paper uses 1e5).
    window_scale : float
        Side of the synthesis window over the exemplar's, in [0.5, 3].
    density : {"uniform", "gradient", "radial", "image"}
        Density image (:func:`density_image`).
    labels : {"categorize", "truth"}
        Categories from section 2.2's categorization or the generator's ground truth.
    interaction : {"centre", "box_hausdorff", "box_gap"}
        The pair distance of the model: element positions (the paper's model), or the
        elements' bounding boxes (section 4.3's proposal, and our gap variant).
    image : str
        Grayscale image of the ``"image"`` density (:func:`paperlib.datasets.grayscale_names`).
    figsize : pair of float
        Figure size in inches.
    dpi : int
        Resolution of the figure shown in the widget.
    svg : str or os.PathLike, optional
        Start from this SVG drawing instead of ``exemplar``.
    file_root : str, os.PathLike or None
        None: the SVG box reads any path. A folder: the box reads only files inside it (relative
        paths from it), as a served app must (:mod:`paperlib.apps`); the upload button reads files
        from the browser either way.

    Returns
    -------
    ArrangementExplorer

    Raises
    ------
    ValueError
        For a parameter outside the ranges above (bad input at construction time raises;
        later, errors are shown in the widget).

    References
    ----------
    Hurtut et al. (2009), sections 2.2, 3.2, 3.3 and 4.1 (Figure 7).
    """
    explorer = ArrangementExplorer(exemplar=exemplar, exemplar_seed=exemplar_seed, seed=seed, T=T,
                                   window_scale=window_scale, density=density, labels=labels,
                                   interaction=interaction, image=image, figsize=figsize, dpi=dpi,
                                   file_root=file_root)
    if svg is not None:
        explorer.load_svg(svg)
    else:
        explorer.load_exemplar(exemplar)
    return explorer


def _check_choice(value, choices: tuple, name: str) -> None:
    check_choice(value, choices, name)
