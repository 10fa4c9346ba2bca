"""Exemplar arrangements of Hershey glyphs with known ground truth (Hurtut 2009 inputs).

Hurtut et al. (2009) analyse artists' drawings we do not have. These seeded generators
build stand-ins from real vector strokes, the Hershey glyphs of :mod:`.hershey`, placed
by documented processes, so every categorization, fit and synthesis can be checked
against the truth that generated it:

========================================  =====================================================
generator                                 what it shows (paper figure)
========================================  =====================================================
:func:`two_category_exemplar`             a regular and a random category, repulsive or
                                          independent between them (Fig. 5 f-h, Fig. 6)
:func:`big_small_exemplar`                big glyphs whose large hard core pushes small
                                          ones back (Fig. 5-b)
:func:`regularity_exemplar`               one category, regular (gamma = 0) to random
                                          (gamma = 1) (Fig. 5 a-e)
:func:`lattice_exemplar`                  a jittered rectangular lattice (Fig. 8, the
                                          Strauss model's limitation)
:func:`hatching_exemplar`                 long, thin, roughly parallel strokes (Fig. 9 right)
:func:`drawn_hatching_exemplar`           a hatching whose strokes never touch: placed one by
                                          one, as drawn (Fig. 9 right, section 4.3)
:func:`near_identical_exemplar`           small glyphs that differ slightly, one perceptual
                                          group (Fig. 9 left, over-categorization)
:func:`amacrine_exemplar`                 spatstat's real ``amacrine`` pattern dressed with
                                          glyphs
========================================  =====================================================

Conventions shared by every generator
-------------------------------------
*Glyph size.* Each glyph (``futural`` font by default) is scaled uniformly so that the
longer side of its upright axis-aligned bounding box measures ``size`` window units; its
pen width scales with it (the Hershey default, 1/21 cap height, times the same factor).

*Position.* The position of an element is the centre of its axis-aligned bounding box
(of the stroke vertices, after any rotation). Element ``i`` is placed so that this
centre is exactly ``pattern.points[i]`` (up to floating-point rounding), and
``labels[i] == pattern.marks[i]``. For the default glyphs (``o x O + l c``, upright or
rotated) this is also the centre of the element's PCA oriented box, the location used
by ``paperlib.arrangement.synthesis.element_positions``, to within 1e-15; for a lopsided glyph the
two notions may differ.

*Windows: all ink inside.* ``Exemplar.window`` is the drawing's frame and contains
every vertex of every glyph, pen half-width included. The positions are generated in
``Exemplar.pattern.window``, that frame shrunk by a margin ``(mx, my)``: the largest
half-extent of any glyph (in x and in y) plus half its pen width, or, for rotated
glyphs, the largest distance of a vertex from the glyph's box centre plus half the pen
width (a rotated glyph placed by its new box centre stays within that distance along
each axis). Simulated generators take the frame as ``window`` and shrink it;
:func:`amacrine_exemplar`, whose positions are data, grows the data window instead.
Fit models on ``exemplar.pattern`` (its window is the one the process lives in), not on
the frame, or the empty border band biases the estimates.

*Simulation.* Gibbs arrangements are simulated with
:func:`paperlib.pointprocess.rmh` (birth-death Metropolis-Hastings from the empty
pattern) for ``T = 100_000`` steps by default, the paper's setting (section 3.3). For the
default models (at most a few hundred points in the unit square) that is several
hundred proposals per point, well past equilibrium; raise ``T`` in proportion for
bigger windows or intensities. ``rng`` (``None``, an ``int`` or a
``numpy.random.Generator``) drives the chain and then any jitter, so a seed fixes the
exemplar bit for bit.

*Truth.* ``Exemplar.truth`` holds the generating parameters as plain Python values
(floats and nested lists, JSON-serialisable): ``process``, the model's ``beta``
(per category) and ``gamma``, ``r``, ``hc`` (M x M, with the ``rmh`` open convention
d < r, d < hc), ``T``, glyphs, sizes, margin, and generator-specific entries (lattice
spacing, hatching angle, ...).

Written by hand: no library generates glyph arrangements; the point process engine is
:mod:`paperlib.pointprocess`.

References
----------
Hurtut, T., Landes, P.-E., Thollot, J., Gousseau, Y., Drouilhet, R., Coeurjolly, J.-F.
(2009). Appearance-guided synthesis of element arrangements by example. NPAR,
sections 3.3 and 4, Figures 5, 6, 8 and 9.
Baddeley, A., Rubak, E., Turner, R. (2015). Spatial Point Patterns: Methodology and
Applications with R, CRC Press (the ``amacrine`` data, section 1.1.2).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from paperlib._checks import as_generator, budget, check_budget, check_choice, file_path, instance_of, positive_number
from paperlib.geometry import Element, Stroke
from paperlib.pointprocess import MultiStraussHard, PointPattern, Window, rmh
from paperlib.pointprocess.simulate import MAX_STEPS

from .hershey import DEFAULT_STROKE_WIDTH, hershey_glyph
from .outlines import character_outline

__all__ = [
    "Exemplar",
    "amacrine_exemplar",
    "big_small_exemplar",
    "drawn_hatching_exemplar",
    "hatching_exemplar",
    "lattice_exemplar",
    "near_identical_exemplar",
    "regularity_exemplar",
    "two_category_exemplar",
]

#: Path of the spatstat fixture holding the ``amacrine`` pattern, relative to the repository root.
AMACRINE_FIXTURE = Path("tests") / "oracle" / "summary.json"


@dataclass(frozen=True, eq=False)
class Exemplar:
    """An arrangement of glyph elements with the ground truth that generated it.

    Parameters
    ----------
    elements : list of Element
        One glyph per point, in the order of ``pattern.points``.
    labels : ndarray of int, shape (n,)
        Ground-truth category of each element (index into ``categories``); equal to
        ``pattern.marks``. Read-only.
    categories : tuple of str
        Category names.
    window : Window
        The drawing's frame (a rectangle); contains all the ink.
    pattern : PointPattern
        Element positions (bounding-box centres) with marks, in the window where the
        positions were generated (``window`` shrunk by ``truth["margin"]``).
    truth : dict
        Generating parameters (see the module docstring).
    description : str
        One human-readable sentence: what the exemplar is and how it was made.
    """

    elements: list
    labels: np.ndarray
    categories: tuple
    window: Window
    pattern: PointPattern
    truth: dict
    description: str

    def __len__(self) -> int:
        return len(self.elements)

    @property
    def positions(self) -> np.ndarray:
        """Element positions, ``pattern.points``, shape ``(n, 2)``."""
        return self.pattern.points

    @property
    def counts(self) -> np.ndarray:
        """Number of elements per category."""
        return np.bincount(self.labels, minlength=len(self.categories))


# ============================================================================ checks


def _number(value, name: str, low=None, high=None) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(number) or (low is not None and number < low) or (high is not None and number > high):
        bounds = f" in [{low}, {high}]" if low is not None and high is not None else (
            f" >= {low}" if low is not None else "")
        raise ValueError(f"{name} must be a finite number{bounds}, got {value!r}")
    return number


def _pair(values, name: str, check) -> tuple:
    if isinstance(values, (str, bytes)) or np.ndim(values) != 1 or len(values) != 2:
        raise ValueError(f"{name} must be a pair of values (one per category), got {values!r}")
    return tuple(check(v, f"{name}[{i}]") for i, v in enumerate(values))


def _steps(T, max_steps) -> int:
    if isinstance(T, bool) or not isinstance(T, (int, np.integer)) or T < 1:
        raise ValueError(f"T (number of Metropolis-Hastings steps) must be a positive integer, got {T!r}")
    check_budget(int(T), budget(max_steps, "max_steps"), "max_steps", "Metropolis-Hastings steps (T)")
    return int(T)


def _chars(chars, name: str = "chars", count: int | None = None) -> tuple:
    if isinstance(chars, str):
        chars = tuple(chars)
    try:
        chars = tuple(chars)
    except TypeError:
        raise ValueError(f"{name} must be a sequence of single characters, got {chars!r}") from None
    if count is not None and len(chars) != count:
        raise ValueError(f"{name} must hold {count} characters (one per category), got {chars!r}")
    if len(chars) < 2 and count is None:
        raise ValueError(f"{name} must hold at least 2 characters, got {chars!r}")
    for c in chars:
        if not isinstance(c, str) or len(c) != 1:
            raise ValueError(f"{name} must hold single characters, got {c!r}")
    if len(set(chars)) != len(chars):
        raise ValueError(f"{name} must be distinct (they name the categories), got {chars!r}")
    return chars


def _frame(window) -> Window:
    if window is None:
        return Window.rectangle()
    if not isinstance(window, Window):
        raise TypeError(f"window must be a paperlib.pointprocess.Window (a rectangle) or None, "
                        f"got {type(window).__name__}")
    if not window.is_rectangle:
        raise ValueError(f"exemplar windows must be rectangles, got a {window.kind} window")
    return window


# ============================================================================ glyphs and placement


@dataclass(frozen=True, eq=False)
class _Glyph:
    """A glyph scaled to ``size`` and translated so that its bounding-box centre is the origin."""

    element: Element
    half_extent: np.ndarray  # (hx, hy) of the upright glyph
    radius: float  # largest distance of a vertex from the box centre
    pen: float  # pen width after scaling


#: The ``font`` of the glyph generators that draws a character of DejaVu Sans as its outer outline
#: (:func:`~paperlib.datasets.character_outline`), one closed pen line of Hershey's default width.
OUTLINE_FONT = "dejavu_outlines"


def _font_glyph(char: str, font: str) -> Element:
    """The glyph of one Hershey font, or the DejaVu outline of a character for :data:`OUTLINE_FONT`."""
    if instance_of(font, str, "font") != OUTLINE_FONT:
        return hershey_glyph(char, font)
    ring = character_outline(char)
    return Element((Stroke(np.vstack([ring, ring[:1]]), DEFAULT_STROKE_WIDTH),), name=f"{font}:{char}")


def _glyph(char: str, font: str, size: float, name: str = "size") -> _Glyph:
    """The glyph scaled so that its larger extent is ``size`` (the parameter ``name`` of the caller)."""
    glyph = _font_glyph(char, font)
    xmin, ymin, xmax, ymax = glyph.bounds()
    extent = max(xmax - xmin, ymax - ymin)
    if extent <= 0:
        raise ValueError(f"Hershey glyph {char!r} of font {font!r} is a single point and cannot be scaled")
    scale = size / extent
    centre = np.array([(xmin + xmax) / 2, (ymin + ymax) / 2])
    largest = max(float(np.abs(glyph.points - centre).max()), max(stroke.width for stroke in glyph.strokes))
    if not (math.isfinite(scale * largest) and 0.0 < scale * scale < math.inf):  # the pen scales by sqrt(det)
        raise ValueError(f"{name} must keep the glyphs' coordinates finite and their area above 0 in floats, "
                         f"got {size!r}")
    element = glyph.transformed(scale * np.eye(2), -scale * centre)
    points = element.points
    half = np.array([(xmax - xmin) / 2, (ymax - ymin) / 2]) * scale
    return _Glyph(element, half, float(np.hypot(points[:, 0], points[:, 1]).max()),
                  max(s.width for s in element.strokes))


def _margin(glyphs, rotated: bool) -> np.ndarray:
    if rotated:
        return np.full(2, max(g.radius + g.pen / 2 for g in glyphs))
    return np.max([g.half_extent + g.pen / 2 for g in glyphs], axis=0)


def _shrunk(frame: Window, margin: np.ndarray) -> Window:
    xrange = (frame.xrange[0] + margin[0], frame.xrange[1] - margin[0])
    yrange = (frame.yrange[0] + margin[1], frame.yrange[1] - margin[1])
    if not (xrange[1] > xrange[0] and yrange[1] > yrange[0]):
        raise ValueError(f"window {frame} is too small for the glyphs: they need a margin of "
                         f"{margin.tolist()} on each side; use a larger window or smaller glyphs")
    return Window.rectangle(xrange, yrange)


def _rotation(degrees: float) -> np.ndarray:
    t = math.radians(degrees)
    return np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])


def _place(glyphs, points: np.ndarray, marks: np.ndarray, angles=None) -> list:
    """Elements of glyph ``marks[i]`` with bounding-box centre at ``points[i]`` (rotated by ``angles[i]`` degrees)."""
    elements = []
    for i, (point, mark) in enumerate(zip(points, marks)):
        template = glyphs[mark].element
        if angles is None:
            elements.append(template.transformed(np.eye(2), point))
            continue
        matrix = _rotation(angles[i])
        rotated = template.points @ matrix.T
        centre = (rotated.min(axis=0) + rotated.max(axis=0)) / 2
        elements.append(template.transformed(matrix, point - centre))
    return elements


def _matrix(value) -> list:
    return np.asarray(value, dtype=np.float64).tolist()


def _simulate(beta, gamma, r, hc, categories, chars, sizes, frame, T, font, rng, rotated=False, size_name="size"):
    """Simulate the multitype Strauss hard-core model in the shrunk frame; return glyphs, pattern, truth.

    ``size_name`` is the caller's parameter that gave ``sizes``, for the message of a size that cannot be drawn.
    """
    glyphs = [_glyph(c, font, s, size_name) for c, s in zip(chars, sizes)]
    margin = _margin(glyphs, rotated)
    inner = _shrunk(frame, margin)
    model = MultiStraussHard(beta, gamma=gamma, r=r, hc=hc, categories=categories)
    pattern = rmh(model, inner, T, rng=rng, max_steps=T)  # T was checked against the caller's budget
    truth = {
        "process": "MultiStraussHard",
        "beta": _matrix(model.beta),
        "gamma": _matrix(model.gamma),
        "r": _matrix(model.r),
        "hc": _matrix(model.hc),
        "closed": bool(model.closed),
        "T": T,
        "glyphs": dict(zip(categories, chars)),
        "sizes": dict(zip(categories, (float(s) for s in sizes))),
        "font": font,
        "margin": margin.tolist(),
        "position": "bounding-box centre",
    }
    return glyphs, pattern, truth


def _exemplar(glyphs, pattern, frame, truth, description, angles=None) -> Exemplar:
    labels = pattern.marks.copy()
    labels.setflags(write=False)
    elements = _place(glyphs, pattern.points, labels, angles)
    return Exemplar(elements, labels, tuple(pattern.categories), frame, pattern, truth, description)


# ============================================================================ generators


def two_category_exemplar(
    window: Window | None = None,
    *,
    chars=("o", "x"),
    sizes=(0.03, 0.03),
    beta=(300.0, 150.0),
    gamma=(0.05, 1.0),
    r=(0.09, 0.05),
    hc=(0.04, 0.03),
    between: str = "repulsive",
    between_gamma: float = 0.2,
    between_r: float = 0.06,
    between_hc: float = 0.035,
    T: int = 100_000,
    font: str = "futural",
    rng=None,
    max_steps: int = MAX_STEPS,
) -> Exemplar:
    """Two glyph categories, one regular and one random, repulsive or independent between them.

    A bivariate Strauss hard-core process (Hurtut eq. 2) simulated by ``rmh``. With the
    defaults, the circles ``'o'`` are regular (gamma 0.05 within r = 0.09, hard core
    0.04) and the crosses ``'x'`` random (gamma = 1: a Poisson process apart from a
    hard core of 0.03 that keeps glyphs from overlapping), as in Figure 6 (right, top);
    ``between`` selects the inter-category interaction of Figure 5 g (repulsive) or
    h (independent).

    Parameters
    ----------
    window : Window, optional
        Rectangular drawing frame; default the unit square.
    chars : pair of str
        The glyph of each category (distinct); they name the categories.
    sizes : pair of float
        Glyph sizes (longer side of the bounding box) in window units, > 0.
    beta : pair of float
        Per-category intensity parameters, > 0.
    gamma, r, hc : pair of float
        Within-category interaction strength (in [0, 1]), radius (> 0) and hard core
        (0 <= hc <= r) of each category.
    between : {"repulsive", "independent"}
        ``"repulsive"``: the two categories interact with ``between_gamma``,
        ``between_r`` and ``between_hc``; ``"independent"``: gamma = 1 and no hard core
        between them (``between_r`` is kept as the, ineffective, radius).
    between_gamma, between_r, between_hc : float
        Inter-category strength in [0, 1], radius > 0, hard core in [0, between_r].
    T : int
        Metropolis-Hastings steps (default 1e5, the paper's).
    max_steps : int, optional
        Budget: the largest ``T`` allowed (default :data:`paperlib.pointprocess.simulate.MAX_STEPS`,
        10**8), as for :func:`paperlib.pointprocess.rmh`.
    font : str
        Hershey font.
    rng : None, int or numpy.random.Generator

    Returns
    -------
    Exemplar
        ``truth`` holds the model (``beta``, ``gamma``, ``r``, ``hc`` as 2 x 2 lists)
        and ``between``.

    Raises
    ------
    ValueError
        For a value outside the ranges above, ``hc > r``, an unknown ``between``, a
        window too small for the glyphs, or a bad glyph/font.
    TypeError
        If ``window`` is not a Window.
    """
    chars = _chars(chars, count=2)
    sizes = _pair(sizes, "sizes", positive_number)
    beta = _pair(beta, "beta", positive_number)
    gamma = _pair(gamma, "gamma", lambda v, n: _number(v, n, 0.0, 1.0))
    r = _pair(r, "r", positive_number)
    hc = _pair(hc, "hc", lambda v, n: positive_number(v, n, allow_zero=True))
    for i in range(2):
        if hc[i] > r[i]:
            raise ValueError(f"hc[{i}] = {hc[i]} exceeds r[{i}] = {r[i]}: a hard core must not exceed its radius")
    check_choice(between, ("repulsive", "independent"), "between")
    between_gamma = _number(between_gamma, "between_gamma", 0.0, 1.0)
    between_r = positive_number(between_r, "between_r")
    between_hc = positive_number(between_hc, "between_hc", allow_zero=True)
    if between_hc > between_r:
        raise ValueError(f"between_hc = {between_hc} exceeds between_r = {between_r}")
    if between == "independent":
        between_gamma, between_hc = 1.0, 0.0
    frame, T = _frame(window), _steps(T, max_steps)
    gamma_m = [[gamma[0], between_gamma], [between_gamma, gamma[1]]]
    r_m = [[r[0], between_r], [between_r, r[1]]]
    hc_m = [[hc[0], between_hc], [between_hc, hc[1]]]
    glyphs, pattern, truth = _simulate(beta, gamma_m, r_m, hc_m, chars, chars, sizes, frame, T, font, rng,
                                       size_name="sizes")
    truth["between"] = between
    description = (f"{chars[0]!r} (gamma {gamma[0]:g}) and {chars[1]!r} (gamma {gamma[1]:g}) glyphs, "
                   f"{between} between categories: bivariate Strauss hard-core process, rmh T={T}")
    return _exemplar(glyphs, pattern, frame, truth, description)


def big_small_exemplar(
    window: Window | None = None,
    *,
    chars=("O", "x"),
    sizes=(0.1, 0.025),
    beta=(2000.0, 300.0),
    hc_big: float | None = None,
    hc_small: float | None = None,
    hc_between: float | None = None,
    T: int = 100_000,
    font: str = "futural",
    rng=None,
    max_steps: int = MAX_STEPS,
) -> Exemplar:
    """Big glyphs with a large hard core pushing small ones back (Hurtut Fig. 5-b).

    A bivariate hard-core process (gamma = 1 everywhere, so only the hard cores act;
    ``r`` is set equal to ``hc``) simulated by ``rmh``. Each hard core defaults to the
    sum of the two glyphs' bounding radii (half-diagonals of their bounding boxes), the
    smallest centre distance at which the circumscribed discs, hence the glyphs, cannot
    touch: with the defaults 0.126 between big ones, 0.032 between small ones and 0.079
    between a big and a small one. The big glyphs' beta is large (2000) because every
    small glyph forbids a big one a disc of radius ``hc_between`` around it: with
    comparable betas the small ones crowd the big ones out (beta = (40, 400) gives
    almost no big glyph); the defaults give about 20 big and 100 small glyphs in the
    unit square.

    Parameters
    ----------
    window : Window, optional
        Rectangular drawing frame; default the unit square.
    chars : pair of str
        Glyph of the big category, then of the small one.
    sizes : pair of float
        Big size, then small size (window units); the first must exceed the second.
    beta : pair of float
        Intensity parameters (big, small), > 0.
    hc_big, hc_small, hc_between : float, optional
        Hard cores (> 0) between big glyphs, small glyphs, and big and small ones.
    T, font, rng, max_steps
        As for :func:`two_category_exemplar`.

    Returns
    -------
    Exemplar
        Categories ``chars``; ``truth["hc"]`` is the 2 x 2 hard-core matrix.

    Raises
    ------
    ValueError
        For non-positive sizes, beta or hard cores, ``sizes[0] <= sizes[1]``, or a
        window too small.
    """
    chars = _chars(chars, count=2)
    sizes = _pair(sizes, "sizes", positive_number)
    if sizes[0] <= sizes[1]:
        raise ValueError(f"sizes must list the big glyph first (sizes[0] > sizes[1]), got {sizes!r}")
    beta = _pair(beta, "beta", positive_number)
    radii = [math.hypot(*(_glyph(c, font, s, "sizes").half_extent)) for c, s in zip(chars, sizes)]
    defaults = (2 * radii[0], 2 * radii[1], radii[0] + radii[1])
    hcs = []
    for value, default, name in zip((hc_big, hc_small, hc_between), defaults, ("hc_big", "hc_small", "hc_between")):
        hcs.append(default if value is None else positive_number(value, name))
    hc_m = [[hcs[0], hcs[2]], [hcs[2], hcs[1]]]
    frame, T = _frame(window), _steps(T, max_steps)
    glyphs, pattern, truth = _simulate(beta, 1.0, hc_m, hc_m, chars, chars, sizes, frame, T, font, rng,
                                       size_name="sizes")
    description = (f"big {chars[0]!r} (size {sizes[0]:g}) and small {chars[1]!r} (size {sizes[1]:g}) glyphs; "
                   f"hard cores {hcs[0]:.3g} / {hcs[1]:.3g} / between {hcs[2]:.3g}: bivariate hard-core process, "
                   f"rmh T={T}")
    return _exemplar(glyphs, pattern, frame, truth, description)


def regularity_exemplar(
    gamma: float = 0.5,
    window: Window | None = None,
    *,
    char: str = "o",
    size: float = 0.03,
    beta: float = 200.0,
    r: float = 0.08,
    hc: float = 0.035,
    T: int = 100_000,
    font: str = "futural",
    rng=None,
    max_steps: int = MAX_STEPS,
) -> Exemplar:
    """One category from regular (gamma = 0) to random (gamma = 1) (Hurtut Fig. 5 a-e).

    A Strauss hard-core process simulated by ``rmh``: ``gamma = 0`` makes ``r`` a hard
    core (most regular), ``gamma = 1`` a Poisson process apart from the hard core
    ``hc``, which by default exceeds the glyph size so that glyphs never overlap (set
    ``hc=0`` for complete spatial randomness).

    Parameters
    ----------
    gamma : float
        Interaction strength in [0, 1].
    window : Window, optional
        Rectangular drawing frame; default the unit square.
    char : str
        The glyph.
    size, beta, r, hc : float
        Glyph size (window units, > 0), intensity parameter (> 0), interaction radius
        (> 0), hard core (0 <= hc <= r).
    T, font, rng, max_steps
        As for :func:`two_category_exemplar`.

    Returns
    -------
    Exemplar
        One category named ``char``; ``truth`` holds 1 x 1 model matrices.
    """
    gamma = _number(gamma, "gamma", 0.0, 1.0)
    chars = _chars((char,), "char", count=1)
    size, beta, r = positive_number(size, "size"), positive_number(beta, "beta"), positive_number(r, "r")
    hc = positive_number(hc, "hc", allow_zero=True)
    if hc > r:
        raise ValueError(f"hc = {hc} exceeds r = {r}: a hard core must not exceed its radius")
    frame, T = _frame(window), _steps(T, max_steps)
    glyphs, pattern, truth = _simulate([beta], gamma, r, hc, chars, chars, (size,), frame, T, font, rng)
    description = f"{char!r} glyphs, Strauss hard-core gamma={gamma:g} (0 regular .. 1 random), rmh T={T}"
    return _exemplar(glyphs, pattern, frame, truth, description)


def lattice_exemplar(
    window: Window | None = None,
    *,
    char: str = "+",
    size: float = 0.04,
    spacing=0.1,
    jitter: float = 0.005,
    angle_jitter: float = 0.0,
    font: str = "futural",
    rng=None,
) -> Exemplar:
    """Glyphs on a jittered rectangular lattice (Hurtut Fig. 8, the model's limitation).

    Lattice nodes ``origin + (i dx, j dy)`` fill the positions window (the frame shrunk
    by the glyph margin and by ``jitter``) and are centred in it; each position is its
    node plus a displacement uniform in ``[-jitter, jitter]^2``, so nearest-neighbour
    distances stay within ``2 sqrt(2) jitter`` of ``min(dx, dy)``. Not a Gibbs process:
    the point of Figure 8 is that a pairwise Strauss model cannot reproduce it.

    Parameters
    ----------
    window : Window, optional
        Rectangular drawing frame; default the unit square.
    char : str
        The glyph.
    size : float
        Glyph size in window units, > 0.
    spacing : float or pair of float
        Lattice spacing ``(dx, dy)`` (one number: square lattice), > 0.
    jitter : float
        Half-width of the uniform positional jitter, in ``[0, min(dx, dy) / 4)``.
    angle_jitter : float
        Standard deviation, in degrees, of a normal rotation of each glyph (>= 0).
    font : str
    rng : None, int or numpy.random.Generator

    Returns
    -------
    Exemplar
        ``truth``: ``process = "lattice"``, ``spacing``, ``shape`` (nx, ny),
        ``origin``, ``jitter``, ``angle_jitter``.

    Raises
    ------
    ValueError
        For non-positive size or spacing, a jitter out of range, or a window that holds
        fewer than 2 x 2 nodes.
    """
    chars = _chars((char,), "char", count=1)
    size = positive_number(size, "size")
    if np.ndim(spacing) == 0:
        spacing = (spacing, spacing)
    spacing = np.array(_pair(spacing, "spacing", positive_number))
    jitter = positive_number(jitter, "jitter", allow_zero=True)
    if jitter >= spacing.min() / 4:
        raise ValueError(f"jitter must be below a quarter of the smallest spacing ({spacing.min() / 4:g}), "
                         f"or the lattice order is lost; got {jitter!r}")
    angle_jitter = positive_number(angle_jitter, "angle_jitter", allow_zero=True)
    frame = _frame(window)
    rng = as_generator(rng)
    glyphs = [_glyph(char, font, size)]
    margin = _margin(glyphs, angle_jitter > 0)
    inner = _shrunk(frame, margin)
    low = np.array([inner.xrange[0], inner.yrange[0]]) + jitter
    span = np.array([inner.width, inner.height]) - 2 * jitter
    shape = np.floor(np.maximum(span, 0) / spacing + 1e-9).astype(np.int64) + 1
    if (span < 0).any() or (shape < 2).any():
        raise ValueError(f"window {frame} holds fewer than 2 x 2 lattice nodes with spacing {spacing.tolist()} "
                         f"and glyph margin {margin.tolist()}; use a larger window or a smaller spacing")
    origin = low + (span - (shape - 1) * spacing) / 2
    ii, jj = np.meshgrid(np.arange(shape[0]), np.arange(shape[1]), indexing="xy")
    nodes = origin + np.column_stack([ii.ravel(), jj.ravel()]) * spacing
    points = nodes + rng.uniform(-jitter, jitter, size=nodes.shape)
    points = np.clip(points, [inner.xrange[0], inner.yrange[0]], [inner.xrange[1], inner.yrange[1]])
    angles = rng.normal(0.0, angle_jitter, size=len(points)) if angle_jitter > 0 else None
    pattern = PointPattern(points, inner, np.zeros(len(points), dtype=np.int64), chars)
    truth = {
        "process": "lattice",
        "spacing": spacing.tolist(),
        "shape": shape.tolist(),
        "origin": origin.tolist(),
        "jitter": jitter,
        "angle_jitter": angle_jitter,
        "glyphs": {char: char},
        "sizes": {char: size},
        "font": font,
        "margin": margin.tolist(),
        "position": "bounding-box centre",
    }
    description = (f"{char!r} glyphs on a {shape[0]} x {shape[1]} rectangular lattice, spacing "
                   f"{spacing[0]:g} x {spacing[1]:g}, uniform jitter +-{jitter:g}")
    return _exemplar(glyphs, pattern, frame, truth, description, angles)


def _principal_angle(element: Element) -> float:
    """Direction (degrees) of the principal axis of the element's vertices."""
    points = element.points - element.points.mean(axis=0)
    _, vectors = np.linalg.eigh(points.T @ points)
    x, y = vectors[:, -1]
    return math.degrees(math.atan2(y, x))


def hatching_exemplar(
    window: Window | None = None,
    *,
    char: str = "l",
    length: float = 0.15,
    angle: float = 60.0,
    angle_jitter: float = 5.0,
    beta: float = 150.0,
    gamma: float = 0.2,
    r: float = 0.05,
    hc: float = 0.015,
    T: int = 100_000,
    font: str = "futural",
    rng=None,
    max_steps: int = MAX_STEPS,
) -> Exemplar:
    """Long thin strokes, roughly parallel: a hatching (Hurtut Fig. 9 right).

    The glyph (a single straight stroke ``'l'`` by default) is scaled so that the
    longer side of its upright bounding box is ``length``, then rotated so that its
    principal axis points along ``angle`` plus a normal angular jitter. Positions
    (stroke midpoints for a straight stroke: bounding-box centres) follow a Strauss
    hard-core process simulated by ``rmh`` whose distances are much shorter than the
    strokes, so the centroids are regular while the strokes cross: the interaction
    between centroids does not describe the interaction between the elements.

    Parameters
    ----------
    window : Window, optional
        Rectangular drawing frame; default the unit square.
    char : str
        The glyph to stretch (``'l'``, ``'-'``, ``'/'``, ...).
    length : float
        Glyph size (window units), > 0.
    angle : float
        Mean stroke direction, degrees counter-clockwise from the x axis.
    angle_jitter : float
        Standard deviation of the normal angular jitter, degrees, >= 0.
    beta, gamma, r, hc : float
        Strauss hard-core model of the positions: beta > 0, gamma in [0, 1], r > 0,
        0 <= hc <= r.
    T, font, rng, max_steps
        As for :func:`two_category_exemplar`.

    Returns
    -------
    Exemplar
        One category named ``char``; ``truth`` adds ``angle``, ``angle_jitter`` and the
        drawn ``angles`` (degrees, per element).
    """
    chars = _chars((char,), "char", count=1)
    length = positive_number(length, "length")
    angle = _number(angle, "angle")
    angle_jitter = positive_number(angle_jitter, "angle_jitter", allow_zero=True)
    gamma = _number(gamma, "gamma", 0.0, 1.0)
    beta, r = positive_number(beta, "beta"), positive_number(r, "r")
    hc = positive_number(hc, "hc", allow_zero=True)
    if hc > r:
        raise ValueError(f"hc = {hc} exceeds r = {r}: a hard core must not exceed its radius")
    frame, T = _frame(window), _steps(T, max_steps)
    rng = as_generator(rng)
    glyphs, pattern, truth = _simulate([beta], gamma, r, hc, chars, chars, (length,), frame, T, font, rng,
                                       rotated=True, size_name="length")
    angles = angle + rng.normal(0.0, angle_jitter, size=pattern.n) if angle_jitter > 0 else np.full(pattern.n, angle)
    rotations = angles - _principal_angle(glyphs[0].element)
    truth.update(angle=angle, angle_jitter=angle_jitter, angles=angles.tolist())
    description = (f"hatching of {char!r} strokes of length {length:g} at {angle:g} +- {angle_jitter:g} degrees, "
                   f"midpoints from a Strauss hard-core process (gamma {gamma:g}), rmh T={T}")
    return _exemplar(glyphs, pattern, frame, truth, description, rotations)


def drawn_hatching_exemplar(
    window: Window | None = None,
    *,
    n: int = 80,
    char: str = "l",
    length: float = 0.15,
    angle: float = 60.0,
    angle_spread: float = 30.0,
    gap: float = 0.01,
    max_attempts: int = 20_000,
    font: str = "futural",
    rng=None,
) -> Exemplar:
    """A hatching whose strokes keep apart, as an artist draws one (Hurtut Fig. 9 right, 4.3).

    Strokes are placed one at a time by random sequential adsorption: a candidate gets a
    position uniform in the positions window and a direction uniform in ``angle +-
    angle_spread`` degrees, and is kept only if its ink (the stroke polylines, pen width
    ignored) stays at least ``gap`` from the ink of every stroke already kept. Neighbouring
    strokes are therefore nearly parallel and close, and none cross: the interactions act
    between the strokes, which their centres do not describe (Hurtut section 4.3). Not a
    Gibbs process: the truth is the placement rule, ``truth["min_ink_gap"] >= gap``.

    Parameters
    ----------
    window : Window, optional
        Rectangular drawing frame; default the unit square.
    n : int
        Number of strokes wanted, >= 1.
    char : str
        The glyph to stretch (a single straight stroke ``'l'`` by default).
    length : float
        Glyph size (window units), > 0.
    angle : float
        Mean stroke direction, degrees counter-clockwise from the x axis.
    angle_spread : float
        Half-width of the uniform direction range, degrees, in [0, 90].
    gap : float
        Smallest ink distance between two strokes, > 0.
    max_attempts : int
        Candidates drawn at most; fewer than ``n`` strokes are placed (with a warning)
        when the window fills up first.
    font, rng
        As for :func:`two_category_exemplar`.

    Returns
    -------
    Exemplar
        One category named ``char``; ``truth`` holds the rule's parameters, the drawn
        ``angles`` (degrees, per element), ``attempts`` and the realised ``min_ink_gap``.
    """
    import warnings

    import shapely

    (char,) = _chars((char,), "char", count=1)
    n = int(_number(n, "n", 1))
    length, gap = positive_number(length, "length"), positive_number(gap, "gap")
    angle, angle_spread = _number(angle, "angle"), _number(angle_spread, "angle_spread", 0.0, 90.0)
    max_attempts = int(_number(max_attempts, "max_attempts", 1))
    frame, rng = _frame(window), as_generator(rng)
    glyph = _glyph(char, font, length, "length")
    inner = _shrunk(frame, _margin([glyph], rotated=True))
    base = _principal_angle(glyph.element)
    kept_lines, points, angles = [], [], []
    attempts = 0
    while len(points) < n and attempts < max_attempts:
        attempts += 1
        point = inner.uniform_points(1, rng)[0]
        direction = angle + rng.uniform(-angle_spread, angle_spread)
        (element,) = _place([glyph], point[None, :], np.zeros(1, np.int64), [direction - base])
        line = shapely.MultiLineString([stroke.points for stroke in element.strokes])
        if kept_lines and shapely.distance(line, kept_lines).min() < gap:
            continue
        kept_lines.append(line)
        points.append(point)
        angles.append(direction)
    if len(points) < n:
        warnings.warn(f"drawn_hatching_exemplar placed {len(points)} of {n} strokes in {max_attempts} attempts: the "
                      "window is full for this gap and length", UserWarning, stacklevel=2)
    pattern = PointPattern(np.array(points), inner, np.zeros(len(points), np.int64), (char,))
    gaps = shapely.distance(np.array(kept_lines)[:, None], np.array(kept_lines)[None, :])
    np.fill_diagonal(gaps, np.inf)
    truth = {"process": "random sequential adsorption of strokes", "n": n, "length": length, "angle": angle,
             "angle_spread": angle_spread, "gap": gap, "attempts": attempts, "angles": angles,
             "min_ink_gap": float(gaps.min()) if len(points) > 1 else float("inf"), "glyphs": {char: char},
             "font": font, "margin": _margin([glyph], rotated=True).tolist(), "position": "bounding-box centre"}
    description = (f"{len(points)} {char!r} strokes of length {length:g} at {angle:g} +- {angle_spread:g} degrees, "
                   f"placed one by one at least {gap:g} apart (random sequential adsorption)")
    rotations = np.array(angles) - base
    return _exemplar([glyph], pattern, frame, truth, description, rotations)


def near_identical_exemplar(
    window: Window | None = None,
    *,
    chars=("o", "c"),
    size: float = 0.02,
    proportions=None,
    beta: float = 300.0,
    gamma: float = 0.3,
    r: float = 0.06,
    hc: float = 0.025,
    T: int = 100_000,
    font: str = "futural",
    rng=None,
    max_steps: int = MAX_STEPS,
) -> Exemplar:
    """Small glyphs that differ only slightly, arranged as one group (Hurtut Fig. 9 left).

    The positions follow one Strauss hard-core process and each element's glyph is
    drawn independently with ``proportions``: simulated as the multitype model with
    ``beta_m = beta * proportions[m]`` and the same ``gamma``, ``r``, ``hc`` for every
    pair of categories, which is exactly that process with independent marks. The
    perceptual truth is one group (``truth["perceptual_groups"] = 1``); the labels
    record which glyph was drawn, so a categorization that splits them shows
    over-categorization.

    Parameters
    ----------
    window : Window, optional
        Rectangular drawing frame; default the unit square.
    chars : sequence of str
        Two or more distinct glyphs (default ``'o'`` and ``'c'``: a ring and a ring with
        a gap).
    size : float
        Common glyph size (window units), > 0.
    proportions : sequence of float, optional
        Probability of each glyph (non-negative, summing to 1 within 1e-9, every one
        positive); default equal.
    beta, gamma, r, hc : float
        The unmarked Strauss hard-core model: beta > 0, gamma in [0, 1], r > 0,
        0 <= hc <= r.
    T, font, rng, max_steps
        As for :func:`two_category_exemplar`.

    Returns
    -------
    Exemplar
        ``truth`` adds ``proportions``, ``perceptual_groups`` and the unmarked model as
        ``unmarked_beta``.
    """
    chars = _chars(chars)
    size = positive_number(size, "size")
    m = len(chars)
    if proportions is None:
        proportions = np.full(m, 1.0 / m)
    else:
        proportions = np.asarray(proportions, dtype=np.float64).reshape(-1) if np.ndim(proportions) == 1 else None
        if proportions is None or proportions.size != m or not np.isfinite(proportions).all() \
                or (proportions <= 0).any() or abs(proportions.sum() - 1) > 1e-9:
            raise ValueError(f"proportions must be {m} positive numbers summing to 1 (one per glyph)")
    gamma = _number(gamma, "gamma", 0.0, 1.0)
    beta, r = positive_number(beta, "beta"), positive_number(r, "r")
    hc = positive_number(hc, "hc", allow_zero=True)
    if hc > r:
        raise ValueError(f"hc = {hc} exceeds r = {r}: a hard core must not exceed its radius")
    frame, T = _frame(window), _steps(T, max_steps)
    glyphs, pattern, truth = _simulate(beta * proportions, gamma, r, hc, chars, chars, (size,) * m, frame, T,
                                       font, rng)
    truth.update(proportions=proportions.tolist(), perceptual_groups=1, unmarked_beta=beta)
    description = (f"near-identical small glyphs {', '.join(map(repr, chars))} (size {size:g}) drawn at random "
                   f"on one Strauss hard-core process (gamma {gamma:g}), rmh T={T}")
    return _exemplar(glyphs, pattern, frame, truth, description)


def _repository_fixture() -> Path:
    return Path(__file__).resolve().parents[2] / AMACRINE_FIXTURE


def amacrine_exemplar(*, chars=("x", "o"), size: float = 0.02, font: str = "futural", path=None) -> Exemplar:
    """spatstat's ``amacrine`` cells dressed with glyphs: ``'o'`` for "on", ``'x'`` for "off".

    The 294 positions (152 on, 142 off cells in a 1.6012 x 1 rectangle; Diggle 1986, via
    spatstat) are read from the committed oracle fixture ``tests/oracle/summary.json``
    (written by ``tests/oracle/spatstat_summary.R``), so this needs the source checkout:
    it is located relative to the package and a clear error is raised when it is
    missing. Positions are data, hence exact: ``pattern.window`` is the data window
    and ``window`` (the frame holding the ink) is that window grown by the glyph
    margin. With ``size = 0.02`` a few on/off glyphs touch (the closest on-off pair is
    0.0084 apart in the data); same-type pairs are at least 0.025 apart.

    Parameters
    ----------
    chars : pair of str
        Glyphs for spatstat's categories in their order, ``("off", "on")``.
    size : float
        Glyph size in window units, > 0.
    font : str
    path : str or Path, optional
        Another copy of the fixture (same JSON layout); default the repository's.

    Returns
    -------
    Exemplar
        Categories ``("off", "on")``; ``truth``: ``process = "data"``, ``source``,
        ``glyphs``, ``sizes``, ``margin``. Deterministic (no rng).

    Raises
    ------
    FileNotFoundError
        If the fixture is missing (an installed package without the repository).
    ValueError
        For bad glyphs or size, or a fixture without the amacrine pattern.
    """
    chars = _chars(chars, count=2)
    size = positive_number(size, "size")
    fixture = _repository_fixture() if path is None else file_path(path)
    if not fixture.is_file():
        raise FileNotFoundError(
            f"the amacrine fixture {fixture} is missing: amacrine_exemplar reads spatstat's pattern from the "
            f"repository's {AMACRINE_FIXTURE.as_posix()} (regenerate it with tests/oracle/spatstat_summary.R, "
            f"or pass path=)")
    try:
        data = json.loads(fixture.read_text())["datasets"]["amacrine"]["pattern"]
        points = np.column_stack([np.array(data["x"], dtype=np.float64), np.array(data["y"], dtype=np.float64)])
        xrange = tuple(float(v) for v in data["window"]["xrange"])
        yrange = tuple(float(v) for v in data["window"]["yrange"])
        categories = tuple(str(c) for c in data["categories"])
        marks = np.array([categories.index(m) for m in data["marks"]], dtype=np.int64)
    except (KeyError, TypeError, ValueError, json.JSONDecodeError) as exc:
        where = "the repository's fixture" if path is None else "path"
        raise ValueError(f"{where} {str(fixture)!r} does not hold the amacrine pattern (datasets.amacrine.pattern): "
                         f"{exc!r:.200}") from None
    if len(categories) != 2:
        raise ValueError(f"expected the two amacrine categories, got {categories!r}")
    inner = Window.rectangle(xrange, yrange)
    pattern = PointPattern(points, inner, marks, categories)
    glyphs = [_glyph(c, font, size) for c in chars]
    margin = _margin(glyphs, rotated=False)
    frame = Window.rectangle((xrange[0] - margin[0], xrange[1] + margin[0]),
                             (yrange[0] - margin[1], yrange[1] + margin[1]))
    truth = {
        "process": "data",
        "source": "spatstat amacrine (Diggle 1986), tests/oracle/summary.json",
        "glyphs": dict(zip(categories, chars)),
        "sizes": dict.fromkeys(categories, size),
        "font": font,
        "margin": margin.tolist(),
        "position": "bounding-box centre",
    }
    description = (f"spatstat's amacrine cells: {chars[1]!r} for on, {chars[0]!r} for off (size {size:g}), "
                   f"{pattern.n} cells in a {inner.width:.4g} x {inner.height:g} window")
    return _exemplar(glyphs, pattern, frame, truth, description)
