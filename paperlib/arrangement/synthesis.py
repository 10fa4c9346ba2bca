"""Arrangement modelling and synthesis: Hurtut 2009, section 3 (fit, MCMC, pasting).

:func:`fit` turns categorized vector elements into a multitype point pattern (element
positions with category marks) and estimates the multitype Strauss hard-core model of
section 3.2 with :func:`paperlib.pointprocess.fit_strauss_hardcore`. :func:`synthesize`
simulates that model in any synthesis window with :func:`paperlib.pointprocess.rmh`
(section 3.3, Figure 4), optionally under a gray-level density image (the brush of
Figure 7), then pastes a reference element of the right category on every synthesised
point (section 3.3, last paragraph). :meth:`Arrangement.to_svg` and :func:`render` write
and draw the result.

Choices
-------
*Position.* An element's location x_i is the centre of its oriented bounding box
(:func:`paperlib.geometry.oriented_bounding_boxes`, PCA of the arc-length measure): the
paper computes its features "on their fitted bounding box" (section 2.1), and the box
centre, unlike the centroid of the ink, is the middle of the element's extent, so a
pasted element is centred on its point whatever the distribution of its strokes.

*Density orientation.* ``density`` is an image as it is read: row 0 at the *top* of the
window's frame. It is flipped (``np.flipud``) into rmh's ``intensity_map``, whose row 0
is at the bottom (y up). Values are factors of the fitted beta: 1 everywhere reproduces
the exemplar's intensity, 0 forbids births.

*Small windows.* If the synthesis window's frame diagonal is below the smallest hard-core
distance of the model, no two points can coexist and the result could never be an
arrangement: :func:`synthesize` raises ``ValueError``. If only the shorter side of the
frame is below the largest hard-core distance, some category pairs can hardly coexist:
it warns (``UserWarning``) and runs.

Nothing here is written by hand that a library offers: the fit and the chain are
:mod:`paperlib.pointprocess`, SVG is :mod:`paperlib.geometry`, drawing is matplotlib.

References
----------
Hurtut, T., Landes, P.-E., Thollot, J., Gousseau, Y., Drouilhet, R., Coeurjolly, J.-F.
(2009). Appearance-guided synthesis of element arrangements by example. NPAR,
sections 3.1-3.3 (eq. 2, Figure 4) and 4.1 (Figure 7).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from paperlib._checks import as_generator, budget, check_budget, check_choice
from paperlib.geometry import Element, Stroke, as_elements, oriented_bounding_boxes, write_svg
from paperlib.pointprocess import (
    MultiStraussHard,
    PointPattern,
    StraussHardcoreFit,
    Window,
    fit_strauss_hardcore,
    rmh,
)

from paperlib.pointprocess.simulate import MAX_STEPS

from .box_interaction import BoxInteractionFit, fit_box_model, simulate_box_model

__all__ = ["INTERACTIONS", "Arrangement", "ArrangementModel", "element_positions", "fit", "render", "synthesize"]

MIN_ELEMENTS_PER_CATEGORY = 3  # Hurtut 2009, section 3.2
INTERACTIONS = ("centre", "box_hausdorff", "box_gap")  # pair distance: positions, or boxes (section 4.3)
_PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
            "#bcbd22", "#17becf")  # matplotlib's tab10


# ---------------------------------------------------------------------------- positions


def element_positions(elements) -> np.ndarray:
    """The location x_i of each element: the centre of its oriented bounding box.

    Parameters
    ----------
    elements : sequence of Element
        At least one element.

    Returns
    -------
    numpy.ndarray, shape (n, 2)
        Box centres, in the elements' (y-up) coordinates.

    Notes
    -----
    The box is :func:`paperlib.geometry.oriented_bounding_boxes`' PCA box of the strokes
    (without pen width). Its centre is the middle of the element's extent along its
    principal axes, which is where a pasted element should sit on its point; the centroid
    of the ink would pull a lopsided element (a 'b', a flag) off centre.

    References
    ----------
    Hurtut et al. (2009), sections 2.1 (fitted bounding box) and 3.1 (locations x_i).
    """
    elements = as_elements(elements)
    if not elements:
        raise ValueError("elements must hold at least one element (element_positions needs one), got none")
    return np.array(oriented_bounding_boxes(elements).centers, dtype=np.float64).reshape(-1, 2)


def _translated(element: Element, offset: np.ndarray) -> Element:
    """The element moved by ``offset`` (points + offset exactly; widths and colours kept)."""
    return Element(tuple(Stroke(s.points + offset, s.width, s.color) for s in element.strokes), element.name)


# ---------------------------------------------------------------------------- the model


@dataclass(frozen=True, eq=False)
class ArrangementModel:
    """A fitted arrangement model: multitype Strauss hard-core process + reference elements.

    Parameters
    ----------
    model : MultiStraussHard
        The fitted model (Hurtut eq. 2), type names ``str(category)``. With box interactions
        (``"box_hausdorff"``, ``"box_gap"``) its h and r are distances between bounding boxes.
    fit : StraussHardcoreFit or BoxInteractionFit
        The whole estimation (h, r, beta, gamma with standard errors, L curves).
    references : tuple of tuple of Element
        Per category (in the order of ``categories``), its exemplar elements translated so
        that their position (:func:`element_positions`) is the origin: pasting one on a
        point is a translation by the point.
    categories : tuple
        The category labels as given to :func:`fit` (ints, strings, ...).
    window : Window
        The exemplar window W_R.
    pattern : PointPattern
        The exemplar as a marked point pattern (positions, category marks).
    interaction : {"centre", "box_hausdorff", "box_gap"}
        The pair distance of the interactions: between element positions (sections 3.1-3.3),
        or between the elements' oriented bounding boxes as placed (the extension of section
        4.3, :mod:`paperlib.arrangement.box_interaction`): their Hausdorff distance (the
        paper's proposal) or their gap (ours).
    reference_corners : tuple of ndarray
        Per category, the (N_m, 4, 2) bounding boxes of ``references`` (box interactions only).
    """

    model: MultiStraussHard
    fit: StraussHardcoreFit | BoxInteractionFit
    references: tuple
    categories: tuple
    window: Window
    pattern: PointPattern
    interaction: str = "centre"
    reference_corners: tuple = ()

    @property
    def n_categories(self) -> int:
        return len(self.categories)

    def __repr__(self) -> str:
        counts = ", ".join(f"{c!r}: {len(r)}" for c, r in zip(self.categories, self.references))
        return f"ArrangementModel({{{counts}}}, {self.model!r})"


def _check_window(window, name: str) -> Window:
    if not isinstance(window, Window):
        raise TypeError(f"{name} must be a paperlib.pointprocess.Window (rectangle, polygon or mask), "
                        f"got {type(window).__name__}")
    return window


def _category_marks(labels, n: int, categories) -> tuple[np.ndarray, tuple]:
    if isinstance(labels, (str, bytes)):
        raise TypeError("labels must be a sequence with one category label per element, got a string")
    labels = list(np.asarray(labels, dtype=object).reshape(-1)) if np.ndim(labels) else None
    if labels is None:
        raise TypeError("labels must be a sequence with one category label per element")
    if len(labels) != n:
        raise ValueError(f"labels has {len(labels)} entries for {n} elements: give one category label per element")
    if categories is None:
        try:
            categories = tuple(sorted(set(labels)))
        except TypeError:
            raise TypeError("labels of mixed types cannot be sorted: pass categories= to fix their order") from None
    else:
        categories = tuple(categories)
        if len(set(categories)) != len(categories):
            raise ValueError(f"categories must be distinct, got {categories}")
    index = {c: i for i, c in enumerate(categories)}
    unknown = sorted({repr(label) for label in labels if label not in index})
    if unknown:
        raise ValueError(f"labels {', '.join(unknown)} are not among categories {categories}")
    marks = np.fromiter((index[label] for label in labels), dtype=np.int64, count=n)
    counts = np.bincount(marks, minlength=len(categories))
    small = [f"{c!r} has {k}" for c, k in zip(categories, counts) if k < MIN_ELEMENTS_PER_CATEGORY]
    if small:
        raise ValueError(f"category {', '.join(small)} element(s); the model needs at least "
                         f"{MIN_ELEMENTS_PER_CATEGORY} per category (Hurtut 2009, section 3.2): merge such "
                         "categories into others or drop their elements")
    return marks, categories


def fit(elements, labels, window, *, categories=None, interaction: str = "centre", gamma_max: float | None = 1.0,
        **fit_options) -> ArrangementModel:
    """Fit the arrangement model of Hurtut 2009, section 3.2, to categorized elements.

    Parameters
    ----------
    elements : sequence of Element
        The reference arrangement (y-up coordinates).
    labels : sequence
        The category of each element (e.g. the labels of ``categorize``); any hashable values.
    window : Window
        The exemplar window W_R; every element position must lie in it.
    categories : sequence, optional
        The categories and their order (default: the sorted distinct labels). Each must hold
        at least 3 elements.
    interaction : {"centre", "box_hausdorff", "box_gap"}
        ``"centre"`` (the paper's model): interactions on the distance between element
        positions. ``"box_hausdorff"``: on the Hausdorff distance between the elements'
        oriented bounding boxes, the remedy section 4.3 proposes for elongated elements;
        ``"box_gap"``: on the distance between the boxes, 0 when they intersect (ours; see
        :mod:`paperlib.arrangement.box_interaction` for why).
    gamma_max : float or None
        Upper bound of every interaction strength. The default 1.0 is the paper's model
        (section 3.2.2: gamma is "a scalar in range [0, 1]", repulsion or none); an
        unconstrained pseudolikelihood fit can give gamma > 1 on a small or clustered
        exemplar (attraction in a thin shell, which the paper's model excludes). ``None``
        fits gamma without a bound (the point-process engine's default).
    **fit_options
        ``"centre"``: passed to :func:`paperlib.pointprocess.fit_strauss_hardcore`
        (``hardcore``, ``r``, ``correction``, ``quadrature``, ``L_correction``, ``rmax``,
        ``rebound``). Box interactions: to :func:`~paperlib.arrangement.box_interaction.fit_box_model`
        (``rmax``, ``rebound``, ``nd``).

    Returns
    -------
    ArrangementModel

    Raises
    ------
    TypeError
        If ``elements`` is not a sequence of Element or ``window`` not a Window.
    ValueError
        If there are no elements, labels and elements differ in length, a label is not among
        ``categories``, a category has fewer than 3 elements (named in the message), or an
        element position lies outside the window.

    References
    ----------
    Hurtut et al. (2009), sections 3.1 and 3.2 (3.2.1-3.2.3, eqs. 2-3), and 4.3.
    """
    elements = as_elements(elements)
    window = _check_window(window, "window")
    check_choice(interaction, INTERACTIONS, "interaction")
    if not elements:
        raise ValueError("fit needs a non-empty reference arrangement (no elements given)")
    marks, categories = _category_marks(labels, len(elements), categories)
    positions = element_positions(elements)
    outside = ~window.contains(positions)
    if outside.any():
        i = int(np.argmax(outside))
        raise ValueError(f"{int(outside.sum())} element position(s) lie outside the exemplar window {window}, "
                         f"e.g. element {i} at {positions[i].tolist()}: give a window that holds every element's "
                         "bounding-box centre")
    pattern = PointPattern(positions, window, marks, tuple(str(c) for c in categories))
    members = [np.flatnonzero(marks == m) for m in range(len(categories))]
    references = tuple(tuple(_translated(elements[i], -positions[i]) for i in ids) for ids in members)
    if interaction == "centre":
        estimate = fit_strauss_hardcore(pattern, gamma_max=gamma_max, **fit_options)
        return ArrangementModel(estimate.model, estimate, references, categories, window, pattern)
    corners = oriented_bounding_boxes(elements).corners()
    reference_corners = tuple(corners[ids] - positions[ids, None, :] for ids in members)
    estimate = fit_box_model(pattern, corners, reference_corners, distance=interaction.removeprefix("box_"),
                             gamma_max=gamma_max, **fit_options)
    return ArrangementModel(estimate.model, estimate, references, categories, window, pattern, interaction,
                            reference_corners)


# ---------------------------------------------------------------------------- synthesis


@dataclass(frozen=True, eq=False)
class Arrangement:
    """A synthesised arrangement: points of the model, with reference elements pasted on them.

    Parameters
    ----------
    pattern : PointPattern
        The simulated marked points (categories named ``str(category)``).
    elements : list of Element
        One pasted element per point, in the order of ``pattern.points``.
    labels : numpy.ndarray
        The category (as given to :func:`fit`) of each element.
    window : Window
        The synthesis window W_S.
    categories : tuple
        The model's categories, in order (for colours and legends).
    """

    pattern: PointPattern
    elements: list
    labels: np.ndarray
    window: Window
    categories: tuple

    def __len__(self) -> int:
        return len(self.elements)

    def colors(self) -> list[str]:
        """One colour per category (matplotlib's tab10 cycle), in the order of ``categories``.

        Returns
        -------
        list of str
            ``len(categories)`` hex colours of matplotlib's tab10 cycle (``"#1f77b4"``, ...), one per
            category, cycling after ten.
        """
        return [_PALETTE[i % len(_PALETTE)] for i in range(len(self.categories))]

    def to_svg(self, path, *, color_by_category: bool = False, **options):
        """Write the arrangement to an SVG file (atomically), one ``<g>`` per element.

        Parameters
        ----------
        path : str or os.PathLike
        color_by_category : bool
            Recolour every stroke with its category's colour (:meth:`colors`) instead of
            the reference element's own colour.
        **options
            For :func:`paperlib.geometry.write_svg` (``width``, ``height``, ``viewbox``,
            ``background``, ``decimals``). The default viewbox holds the window's frame and
            every stroke.

        Returns
        -------
        pathlib.Path
        """
        elements = self.elements
        if color_by_category:
            palette = self.colors()
            elements = [Element(tuple(Stroke(s.points, s.width, palette[m]) for s in e.strokes), e.name)
                        for e, m in zip(elements, self.pattern.marks)]
        options.setdefault("viewbox", _viewbox(self))
        return write_svg(elements, path, **options)


def _viewbox(arrangement: Arrangement) -> tuple[float, float, float, float]:
    (x0, x1), (y0, y1) = arrangement.window.xrange, arrangement.window.yrange
    for element in arrangement.elements:
        pad = max(s.width for s in element.strokes) / 2
        ex0, ey0, ex1, ey1 = element.bounds()
        x0, y0, x1, y1 = min(x0, ex0 - pad), min(y0, ey0 - pad), max(x1, ex1 + pad), max(y1, ey1 + pad)
    return (x0, y0, x1 - x0, y1 - y0)


def _check_room(model: MultiStraussHard, window: Window) -> None:
    hc = np.asarray(model.hc)
    diagonal = math.hypot(window.width, window.height)
    if diagonal < hc.min():
        raise ValueError(f"the synthesis window {window} is too small for the model: its frame diagonal "
                         f"({diagonal:.6g}) is below the smallest hard-core distance ({hc.min():.6g}), so no two "
                         "elements could ever coexist; enlarge the window (or fit on an exemplar drawn at this scale)")
    if min(window.width, window.height) < hc.max():
        warnings.warn(f"the synthesis window's shorter side ({min(window.width, window.height):.6g}) is below the "
                      f"model's largest hard-core distance ({hc.max():.6g}): some categories can hardly coexist "
                      "in it, the arrangement will not look like the exemplar", UserWarning, stacklevel=3)


def _intensity_map(density, window: Window) -> np.ndarray | None:
    """The density image (row 0 at the top) as rmh's intensity map (row 0 at the bottom)."""
    if density is None:
        return None
    try:
        image = np.array(density, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError("density must be a 2-D array of numbers (a gray-level image)") from None
    if image.ndim != 2 or min(image.shape) < 1:
        raise ValueError(f"density must be a non-empty 2-D gray-level image (rows, columns) over the synthesis "
                         f"window's frame, got shape {image.shape}")
    if not np.isfinite(image).all():
        raise ValueError("density contains NaN or infinite values: expected finite values >= 0")
    if (image < 0).any():
        raise ValueError(f"density must be >= 0 everywhere (a factor of the fitted intensity), got a minimum of "
                         f"{image.min():g}")
    if not (image > 0).any():
        raise ValueError("density is zero everywhere: no element could be placed; give a positive density "
                         "somewhere (1 = the exemplar's intensity)")
    flipped = np.ascontiguousarray(np.flipud(image))
    if not window.is_rectangle and not _positive_somewhere_inside(flipped, window):
        raise ValueError("density is zero over the whole synthesis window (positive only outside its shape): "
                         "no element could be placed")
    return flipped


def _positive_somewhere_inside(image: np.ndarray, window: Window) -> bool:
    """Whether some pixel of positive density (row 0 at the bottom) meets the window."""
    ny, nx = image.shape
    rows, cols = np.nonzero(image > 0)
    dx, dy = window.width / nx, window.height / ny
    x0, y0 = window.xrange[0] + cols * dx, window.yrange[0] + rows * dy
    if window.kind == "polygon":
        import shapely

        return bool(shapely.intersects(window.shape, shapely.box(x0, y0, x0 + dx, y0 + dy)).any())
    # mask: the centres of the positive density pixels and of the admissible mask pixels
    centres = np.column_stack([x0 + dx / 2, y0 + dy / 2])
    if window.contains(centres).any():
        return True
    mrows, mcols = np.nonzero(window.mask_array)
    mdx, mdy = window.pixel_size
    mx = window.xrange[0] + (mcols + 0.5) * mdx
    my = window.yrange[0] + (mrows + 0.5) * mdy
    i = np.clip(np.floor((my - window.yrange[0]) / dy).astype(np.int64), 0, ny - 1)
    j = np.clip(np.floor((mx - window.xrange[0]) / dx).astype(np.int64), 0, nx - 1)
    return bool((image[i, j] > 0).any())


def synthesize(model: ArrangementModel, window, *, density=None, T: int = 100_000, start=None, rng=None,
               progress: bool = False, max_steps: int = MAX_STEPS) -> Arrangement:
    """Synthesise a new arrangement from a fitted model (Hurtut 2009, section 3.3).

    Runs ``T`` Metropolis-Hastings steps of the fitted multitype Strauss hard-core model in
    the synthesis window W_S (:func:`paperlib.pointprocess.rmh`, the paper's equiprobable
    births and deaths), then pastes on each simulated point a reference element of its
    category, picked uniformly at random and translated to the point.

    Parameters
    ----------
    model : ArrangementModel
        From :func:`fit`.
    window : Window
        The synthesis window: rectangle, polygon or mask (Hurtut's "various shapes").
    density : array_like, shape (rows, columns), optional
        A gray-level image over the window's frame (Figure 7's brush), read as an image:
        row 0 at the *top*, column 0 at the left. Values >= 0 multiply the fitted beta at
        each location (1 = the exemplar's intensity, 0 = no element). Flipped to rmh's
        ``intensity_map`` (row 0 at the bottom).
    T : int
        Number of MCMC steps (1e5 in the paper). The chain starts empty and fills the
        window by births: a window holding n elements needs T of several times n (about
        20 n reaches equilibrium for the benchmark models).
    start : None, PointPattern, int or sequence of int
        The chain's initial state, as for :func:`rmh` (e.g. ``model.pattern`` when the
        synthesis window contains the exemplar window: the paper's x_0 = x). Models with
        box interactions always start from the empty arrangement.
    rng : None, int or numpy.random.Generator
        Randomness; the same seed gives the same arrangement bit for bit. Two independent
        streams are spawned from it: one for the chain, one for picking references.
    progress : bool
        Show rmh's progress bar.
    max_steps : int, optional
        Budget: the largest ``T`` allowed (default :data:`paperlib.pointprocess.simulate.MAX_STEPS`, 10**8).

    Returns
    -------
    Arrangement

    Raises
    ------
    TypeError
        If ``model`` is not an ArrangementModel or ``window`` not a Window.
    ValueError
        For T < 1; a density that is not a non-empty 2-D array of finite values >= 0, or is
        zero everywhere (or everywhere in the window); a window so small that no two
        elements fit (frame diagonal below the smallest hard-core distance). A window
        whose shorter side is below the largest hard-core distance only warns.

    References
    ----------
    Hurtut et al. (2009), section 3.3 (Figure 4 and its last paragraph: pasting reference
    elements) and section 4.1 (Figure 7: density brush, various shapes).
    """
    if not isinstance(model, ArrangementModel):
        raise TypeError(f"model must be an ArrangementModel (from fit), got {type(model).__name__}")
    window = _check_window(window, "window")
    if isinstance(T, bool) or not isinstance(T, (int, np.integer)) or T < 1:
        raise ValueError(f"T (number of MCMC steps) must be an integer >= 1, got {T!r}")
    check_budget(int(T), budget(max_steps, "max_steps"), "max_steps", "MCMC steps (T)")
    intensity_map = _intensity_map(density, window)
    _check_room(model.model, window)
    chain_rng, paste_rng = as_generator(rng).spawn(2)
    if model.interaction != "centre":
        if start is not None:
            raise ValueError("models with box interactions start from the empty arrangement: pass start=None")
        pattern, picks = simulate_box_model(model.model, model.reference_corners, window, int(T),
                                            distance=model.fit.distance, intensity_map=intensity_map, rng=chain_rng)
    else:
        pattern = rmh(model.model, window, int(T), start=start, intensity_map=intensity_map, rng=chain_rng,
                      progress=progress, max_steps=max_steps)
        n_refs = np.array([len(r) for r in model.references], dtype=np.int64)
        picks = paste_rng.integers(0, n_refs[pattern.marks]) if pattern.n else np.empty(0, dtype=np.int64)
    marks = pattern.marks
    elements = [_translated(model.references[m][k], point) for m, k, point in zip(marks, picks, pattern.points)]
    labels = np.empty(len(marks), dtype=object)
    labels[:] = [model.categories[m] for m in marks]
    return Arrangement(pattern, elements, labels, window, model.categories)


# ---------------------------------------------------------------------------- drawing


def render(arrangement: Arrangement, ax=None, color_by_category: bool = False, *, show_window: bool = True,
           linewidth: float = 0.8):
    """Draw an arrangement with matplotlib (y up, equal aspect); returns the Axes.

    Parameters
    ----------
    arrangement : Arrangement
    ax : matplotlib.axes.Axes, optional
        Axes to draw in (default: a new figure's).
    color_by_category : bool
        Colour strokes by category (:meth:`Arrangement.colors`) instead of their own colour.
    show_window : bool
        Outline the synthesis window (its frame for masks).
    linewidth : float
        Line width in points (stroke widths are in drawing units; a PNG wants a constant).

    Returns
    -------
    matplotlib.axes.Axes
        Nothing is written to disk: the caller saves the figure.
    """
    if not isinstance(arrangement, Arrangement):
        raise TypeError(f"arrangement must be an Arrangement (from synthesize), got {type(arrangement).__name__}")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    if ax is None:
        _, ax = plt.subplots()
    palette = arrangement.colors()
    lines, colors = [], []
    for element, m in zip(arrangement.elements, arrangement.pattern.marks):
        for stroke in element.strokes:
            lines.append(stroke.points)
            colors.append(palette[m] if color_by_category else stroke.color)
    ax.add_collection(LineCollection(lines, colors=colors, linewidths=linewidth, capstyle="round"))
    window = arrangement.window
    if show_window:
        if window.kind == "polygon":
            polygons = getattr(window.shape, "geoms", [window.shape])
            for polygon in polygons:
                for ring in [polygon.exterior, *polygon.interiors]:
                    xy = np.asarray(ring.coords)
                    ax.plot(xy[:, 0], xy[:, 1], color="0.6", linewidth=0.6)
        else:
            (x0, x1), (y0, y1) = window.xrange, window.yrange
            ax.plot([x0, x1, x1, x0, x0], [y0, y0, y1, y1, y0], color="0.6", linewidth=0.6)
    x, y, w, h = _viewbox(arrangement)
    ax.set_xlim(x, x + w)
    ax.set_ylim(y, y + h)
    ax.set_aspect("equal")
    return ax
