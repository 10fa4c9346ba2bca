"""Metropolis-Hastings simulation of multitype Strauss hard-core processes (spatstat's ``rmh``).

Hurtut 2009 synthesises new arrangements by running a birth-death Metropolis-Hastings
chain (section 3.3, Figure 4; Geyer & Møller 1994) whose equilibrium is the fitted
multitype Strauss hard-core model. :func:`rmh` runs that chain, with spatstat's optional
shift moves, a fixed-count mode, periodic boundaries for tileable output, windows of any
shape, and an intensity map that scales beta per location (the gray-level brush of
Hurtut's Figure 7).

The chain itself runs in numba (:mod:`._kernels`) on a cell grid, so a step costs
O(neighbours); all random numbers are drawn here, per chunk of steps, from the caller's
``numpy.random.Generator``, so the kernel and the pure-Python reference
(:mod:`._reference`) agree step for step and a seed fixes the output bit for bit.
Written by hand because no maintained Python library simulates Gibbs point processes;
spatstat (R) is the reference it is checked against.

References
----------
Hurtut, T., Landes, P.-E., Thollot, J., Gousseau, Y., Drouilhet, R., Coeurjolly, J.-F.
(2009). Appearance-guided synthesis of element arrangements by example. NPAR,
section 3.3 and Figure 4.
Geyer, C. J., Møller, J. (1994). Simulation procedures and likelihood inference for
spatial point processes. Scandinavian Journal of Statistics 21, 359-373.
Baddeley, A., Rubak, E., Turner, R. (2015). Spatial Point Patterns: Methodology and
Applications with R, section 13.5 (``rmh``).
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass

import numpy as np
from tqdm.auto import tqdm

from paperlib._checks import as_generator, budget, check_budget, instance_of, point_array

from . import _kernels
from ._kernels import CELL_FULL, DONE, POINTS_FULL, Grid, Interaction, Moves, Proposals, State
from .models import MultiStraussHard
from .pattern import PointPattern, require_distinct
from .window import Window

__all__ = ["intensity_map_values", "rmh"]

#: Default budget of :func:`rmh` (``max_steps``): 10**8 steps, about ten seconds (the paper uses 10**5).
MAX_STEPS = 10**8
_CHUNK_STEPS = 1 << 15  # steps per kernel call: ~2 MB of pre-drawn randomness
_MAX_CELLS = 1 << 20
_POINTS_PER_CELL = 2.0
_MIN_POINT_CAPACITY = 64
_MIN_CELL_CAPACITY = 4
_CELL_SLACK = 2  # free slots above the start's fullest cell: cells rarely overflow, rows stay short


def rmh(
    model: MultiStraussHard,
    window: Window,
    T: int = 100_000,
    *,
    start=None,
    p: float = 0.0,
    q: float = 0.5,
    ptypes=None,
    fixall: bool = False,
    periodic: bool = False,
    intensity_map=None,
    rng=None,
    progress: bool = False,
    max_steps: int = MAX_STEPS,
) -> PointPattern:
    r"""Simulate a multitype Strauss hard-core process by Metropolis-Hastings.

    Runs ``T`` steps of the birth-death chain of Hurtut 2009, Figure 4 (Geyer & Møller
    1994), optionally mixed with spatstat's shift moves, and returns the final state.
    Each step proposes one of

    - *birth* (probability ``(1 - p)(1 - q)``): a location u uniform in the window and
      a type m drawn from ``ptypes``;
    - *death* (probability ``(1 - p) q``): a point x_i of the current n, uniformly;
    - *shift* (probability ``p``): a point x_i moves to a new uniform location u and
      gets a new type m' drawn from ``ptypes`` (keeps its type when ``fixall``);

    and accepts it with probability min(1, R), where, with lambda the model's
    Papangelou conditional intensity (times the intensity map) and pi the type-proposal
    probabilities,

    .. math::

        R_\mathrm{birth} = \frac{\lambda(u, m; x)\,|W|\,q}{(1 - q)\,(n + 1)\,\pi_m},\quad
        R_\mathrm{death} = \frac{(1 - q)\,n\,\pi_{m_i}}{\lambda(x_i, m_i; x \setminus x_i)\,|W|\,q},\quad
        R_\mathrm{shift} = \frac{\lambda(u, m'; x \setminus x_i)\,\pi_{m_i}}
                                {\lambda(x_i, m_i; x \setminus x_i)\,\pi_{m'}}.

    These are the Metropolis-Hastings-Green ratios f(x') P(x' -> x) / (f(x) P(x -> x')):
    a birth of (u, m) is proposed with density (1 - p)(1 - q) pi_m / |W| and undone by
    the death of that one point among n + 1, proposed with probability (1 - p) q / (n + 1),
    and f(x + u) / f(x) = lambda(u, m; x). A shift proposal is symmetric but for the types.
    With the paper's equiprobable moves (q = 1/2) and one type, R_birth =
    f(x + u) / f(x) |W| / (n + 1) and R_death = f(x - x_i) / f(x) n / |W|.

    Parameters
    ----------
    model : MultiStraussHard
        The model (Hurtut eq. 2). Its ``closed`` flag sets the tie convention: pairs at
        d < r interact and d < hc are forbidden, or d <= r and d <= hc when closed.
        ``gamma[i, j] > 1`` needs hard cores ``hc[i, i] > 0`` and ``hc[j, j] > 0``,
        without which the density is not integrable and the chain explodes.
    window : Window
        The synthesis window W_S: rectangle, polygon (proposals exactly uniform in the
        polygon, by rejection from its frame with shapely's exact test; |W| = polygon
        area) or mask (uniform in the union of admissible pixels, |W| = their area).
    T : int
        Number of steps (``10**5`` in the paper, section 3.3).
    start : None, PointPattern, int or sequence of int
        Initial state x_0. ``None`` (default): the empty pattern, which always has
        positive density; the chain fills the window by births (spatstat starts from
        random points instead). A PointPattern inside ``window`` with marks ``< M``: the
        paper initialises x_0 = x, the reference arrangement. An int n: n uniform points
        with types drawn from ``ptypes`` (spatstat's ``n.start``); a sequence: that many
        uniform points of each type. Random starts usually violate hard cores, and a
        PointPattern start may too (with a warning, as may a point where the intensity
        map is 0): the chain leaves such zero-density states, since the death or shift
        of an offending point is always accepted.
    p : float
        Probability of a shift move (spatstat's ``p``; its default is 0.9, the paper's
        is 0). ``p = 1`` is the fixed-count mode: shifts only, n never changes.
    q : float
        Probability that a birth-or-death move is a death, ``0 < q < 1`` (the paper's
        equiprobable moves; also spatstat's default, ``rmhcontrol(q = 0.5)``).
    ptypes : array_like, shape (M,), optional
        Probability of proposing each type (positive, summing to 1); default uniform,
        as the paper's "random category label".
    fixall : bool
        With ``p = 1``, shifts keep the point's type, so the count of every type is fixed
        (spatstat's ``fixall``).
    periodic : bool
        Simulate on the torus obtained by gluing opposite sides of a rectangular window,
        for tileable output; the model's reach must be at most half the window's sides.
    intensity_map : array_like, shape (ny, nx), optional
        Non-negative factor of beta per location over the window's frame, pixel
        ``[i, j]`` covering x in ``[x0 + j dx, x0 + (j + 1) dx)`` and y in
        ``[y0 + i dy, ...)`` (row 0 at the bottom, as :meth:`Window.mask`; flip an
        image read top-down with ``np.flipud``). The model becomes
        beta_m(u) = beta_m map(u) (Hurtut Figure 7's brush). Proposals stay uniform;
        the map enters through lambda: births multiply R by map(u), deaths divide it by
        map(x_i), shifts multiply it by map(u) / map(x_i).
    rng : None, int or numpy.random.Generator
        Randomness; the same seed gives the same pattern bit for bit.
    progress : bool
        Show a tqdm progress bar (updated per chunk of 32768 steps).
    max_steps : int, optional
        Budget: the largest ``T`` allowed (default :data:`MAX_STEPS`, 10**8, about ten seconds).

    Returns
    -------
    PointPattern
        The state after ``T`` steps, in ``window``, categories ``model.categories``.

    Raises
    ------
    ValueError
        Before any simulation, for: T < 1; p outside [0, 1], q outside (0, 1); bad
        ``ptypes``; ``fixall`` without ``p = 1``; a start outside the window, with marks
        out of range or with repeated locations, or an empty start in fixed-count mode;
        ``periodic`` with a non-rectangular window or a reach above half a side; an intensity map that is
        not a non-empty 2-D array of finite non-negative values with a positive one; an
        unstable model (gamma > 1 without hard cores). Models with gamma < 0 or hc > r,
        and masks without an admissible pixel, are rejected when they are built.
    TypeError
        When ``model`` or ``window`` is of the wrong type.

    Notes
    -----
    *Deviation from the paper.* Figure 4 prints R_b = f(x')/f(x) n_t / A_t and
    R_d = f(x')/f(x) A_t / n_t. The factors are inverted relative to Geyer & Møller
    (R_b = f(x')/f(x) A / (n + 1), R_d = f(x')/f(x) n / A for equiprobable moves and one
    type): as printed, births of a Poisson process with beta = 100 on the unit square
    are accepted with probability min(1, 100 n), and the count runs off to ~5e4 within
    1e5 steps instead of settling at beta |W| = 100. We implement the Geyer-Møller
    ratios, which give the right mean count (the tests check it), with the factor
    1 / pi_m (= M for uniform types) that the random type of a birth requires and the
    printed formula omits.

    *Conventions shared with spatstat.* Distances are compared squared (d^2 < r^2, as
    ``rmh``; the closed convention uses the next double above r^2); the interaction radius of a pair with gamma = 1 plays no role, so the
    cell grid is sized by the *effective* reach (the largest hard core, and the largest
    r among pairs with gamma != 1). Unlike ``rmh(fitted_model)``, the window is never
    expanded: this is ``rmh(..., expand = 1, periodic = FALSE)`` (or ``TRUE``).

    References
    ----------
    Hurtut et al. (2009), Appearance-guided synthesis of element arrangements by
    example, section 3.3, Figure 4 (and Figure 7 for the intensity map).
    Geyer, C. J., Møller, J. (1994). Simulation procedures and likelihood inference for
    spatial point processes. Scand. J. Statist. 21, 359-373, section 3.
    Baddeley, Rubak, Turner (2015). Spatial Point Patterns, section 13.5.
    """
    _check_steps(T)
    check_budget(int(T), budget(max_steps, "max_steps"), "max_steps", "Metropolis-Hastings steps (T)")
    pattern, _ = _simulate(
        model, window, T, stepper=_kernels.mh_steps, start=start, p=p, q=q, ptypes=ptypes, fixall=fixall,
        periodic=periodic, intensity_map=intensity_map, rng=rng, progress=progress,
    )
    return pattern


# ---------------------------------------------------------------------------- set-up and validation


@dataclass(frozen=True)
class _Setup:
    """Everything about a simulation that does not change while it runs."""

    window: Window
    categories: tuple
    grid: Grid
    model: Interaction
    moves: Moves
    intensity_map: _IntensityMap | None
    uniform_types: bool  # draw types with integers() rather than choice(): faster, same law


@dataclass(frozen=True)
class _IntensityMap:
    """A non-negative image over the window's frame, row 0 at the bottom."""

    image: np.ndarray
    xrange: tuple
    yrange: tuple

    def at(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        ny, nx = self.image.shape
        columns = np.floor((x - self.xrange[0]) / (self.xrange[1] - self.xrange[0]) * nx).astype(np.int64)
        rows = np.floor((y - self.yrange[0]) / (self.yrange[1] - self.yrange[0]) * ny).astype(np.int64)
        return self.image[np.clip(rows, 0, ny - 1), np.clip(columns, 0, nx - 1)]


def _simulate(model, window, T, *, stepper, trace=False, start=None, p=0.0, q=0.5, ptypes=None, fixall=False,
              periodic=False, intensity_map=None, rng=None, progress=False):
    """:func:`rmh` with a choice of kernel; returns the pattern and, with ``trace``, the step outcomes."""
    setup = _prepare(model, window, T, p=p, q=q, ptypes=ptypes, fixall=fixall, periodic=periodic,
                     intensity_map=intensity_map)
    _check_start_spec(start, setup)
    rng = as_generator(rng)
    chain = _Chain(setup, *_start_points(start, setup, rng))
    if isinstance(start, PointPattern):  # a random start violates hard cores by design
        chain.warn_if_zero_density()
    outcomes = chain.run(T, rng, stepper, progress=progress, trace=trace)
    return chain.pattern(), outcomes


def _prepare(model, window, T, *, p, q, ptypes, fixall, periodic, intensity_map) -> _Setup:
    if not isinstance(model, MultiStraussHard):
        raise TypeError(f"model must be a MultiStraussHard (or Poisson/Strauss/StraussHard), got {type(model).__name__}")
    if not isinstance(window, Window):
        raise TypeError(f"window must be a paperlib.pointprocess.Window, got {type(window).__name__}")
    _check_steps(T)
    interaction, reach = _interaction(model)
    intensity = _checked_intensity_map(intensity_map, window)
    moves = _moves(p, q, ptypes, fixall, model.n_types, window.area)
    if periodic and not window.is_rectangle:
        raise ValueError(f"periodic=True needs a rectangular window (a torus), got a {window.kind} window")
    if periodic and 2 * reach > min(window.width, window.height):
        raise ValueError(f"periodic=True needs the model's reach ({reach:g}) to be at most half the window's "
                         f"shorter side ({min(window.width, window.height):g})")
    map_max = 1.0 if intensity is None else float(intensity.image.max())
    expected_upper = float(model.beta.sum()) * window.area * map_max  # the dominating Poisson process
    return _Setup(window, model.categories, _grid(window, reach, bool(periodic), expected_upper), interaction,
                  moves, intensity, ptypes is None)


def _check_steps(T) -> None:
    if isinstance(T, bool) or not isinstance(T, (int, np.integer)):
        if not (isinstance(T, float) and T.is_integer()):
            raise ValueError(f"T (number of steps) must be an integer >= 1, got {T!r}")
    if T < 1:
        raise ValueError(f"T (number of steps) must be >= 1, got {T!r}")


def _interaction(model: MultiStraussHard) -> tuple[Interaction, float]:
    """The kernel's view of the model, and its effective reach."""
    gamma = np.array(model.gamma, dtype=np.float64)  # writable copies: numba types read-only arrays apart
    self_core = np.diag(model.hc) > 0
    unstable = (gamma > 1) & ~(self_core[:, None] & self_core[None, :])
    if unstable.any():
        i, j = map(int, np.argwhere(unstable)[0])
        raise ValueError(f"gamma[{i}, {j}] = {gamma[i, j]:g} > 1 without hard cores for types {i} and {j} "
                         "(hc[i, i] > 0 and hc[j, j] > 0): the density is not integrable, the chain would explode")
    counted_r = np.where(gamma != 1.0, model.r, 0.0)  # a pair with gamma = 1 interacts only by its hard core
    r2, hc2 = counted_r**2, np.array(model.hc, dtype=np.float64) ** 2
    if model.closed:  # d <= r becomes d2 < next double above r^2 (hc = 0 forbids nothing)
        r2 = np.where(r2 > 0, np.nextafter(r2, np.inf), 0.0)
        hc2 = np.where(hc2 > 0, np.nextafter(hc2, np.inf), 0.0)
    interaction = Interaction(np.array(model.beta, dtype=np.float64), gamma, r2, hc2)
    return interaction, float(max(counted_r.max(), model.hc.max()))


def _moves(p, q, ptypes, fixall, n_types, area) -> Moves:
    p, q = float(p), float(q)
    if not 0.0 <= p <= 1.0:
        raise ValueError(f"p (probability of a shift) must be in [0, 1], got {p}")
    if p < 1.0 and not 0.0 < q < 1.0:
        raise ValueError(f"q (probability that a birth-or-death move is a death) must be in (0, 1), got {q}")
    if fixall and p != 1.0:
        raise ValueError("fixall=True holds the count of each type fixed and needs the fixed-count mode p=1")
    if ptypes is None:
        type_prob = np.full(n_types, 1.0 / n_types)
    else:
        type_prob = np.array(ptypes, dtype=np.float64).reshape(-1)
        if type_prob.size != n_types or not np.isfinite(type_prob).all() or (type_prob <= 0).any():
            raise ValueError(f"ptypes must be {n_types} positive probabilities, one per type, got {ptypes!r}")
        if abs(type_prob.sum() - 1.0) > 1e-9:
            raise ValueError(f"ptypes must sum to 1, got {type_prob.sum():.12g}")
        type_prob = type_prob / type_prob.sum()
    return Moves(p, q, float(area), type_prob, bool(fixall))


def _checked_intensity_map(intensity_map, window: Window) -> _IntensityMap | None:
    if intensity_map is None:
        return None
    try:
        image = np.array(intensity_map, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError("intensity_map must be a 2-D array of numbers") from None
    if image.ndim != 2 or min(image.shape) < 1:
        raise ValueError(f"intensity_map must be a non-empty 2-D image (rows, columns) over the window's frame, "
                         f"got shape {image.shape}")
    if not np.isfinite(image).all() or (image < 0).any():
        raise ValueError("intensity_map values must be finite and >= 0 (a factor of beta per location)")
    if not (image > 0).any():
        raise ValueError("intensity_map is zero everywhere: no point could ever be born")
    return _IntensityMap(image, window.xrange, window.yrange)


def intensity_map_values(intensity_map, window: Window, points) -> np.ndarray:
    """The values of an rmh ``intensity_map`` at points (the pixel of the frame holding each).

    Parameters
    ----------
    intensity_map : array_like, shape (rows, columns)
        Non-negative factor of beta over the window's frame, row 0 at the bottom, as for
        :func:`rmh`.
    window : Window
    points : array_like, shape (k, 2)

    Returns
    -------
    ndarray, shape (k,)
        Points outside the frame take the value of the nearest edge pixel.

    Raises
    ------
    ValueError
        For a map that :func:`rmh` would refuse (not 2-D, negative, non-finite, all zero).
    """
    if intensity_map is None:
        raise ValueError("intensity_map must be a non-empty 2-D image (rows, columns), got None")
    instance_of(window, Window, "window")
    points = point_array(points, "points")
    return _checked_intensity_map(intensity_map, window).at(points[:, 0], points[:, 1])


def _grid(window: Window, reach: float, periodic: bool, expected_points: float) -> Grid:
    """Square-ish cells about ``_POINTS_PER_CELL`` expected points large, and at least ``reach`` wide.

    A query scans the cells that the square ``u +- reach`` overlaps: at most 4 when cells
    are twice the reach, 9 when they equal it. Cells of ~2 points balance the cost per
    cell visited against the cost per point tested (measured on the benchmark models).
    """
    width, height = window.width, window.height
    side = max(math.sqrt(_POINTS_PER_CELL * width * height / max(expected_points, 1.0)), reach,
               math.sqrt(width * height / _MAX_CELLS))
    ncx, ncy = max(1, math.floor(width / side)), max(1, math.floor(height / side))
    return Grid(float(window.xrange[0]), float(window.yrange[0]), float(width), float(height), ncx, ncy,
                ncx / width, ncy / height, reach * (1 + 1e-9), periodic)


# ---------------------------------------------------------------------------- start


def _check_start_spec(start, setup: _Setup) -> None:
    n_types = setup.model.beta.size
    if isinstance(start, PointPattern):
        require_distinct(start, "rmh's start pattern")
        inside = setup.window.contains(start.points)
        if not inside.all():
            raise ValueError(f"{np.sum(~inside)} start point(s) lie outside the synthesis window {setup.window}")
        if start.n and start.marks.max() >= n_types:
            raise ValueError(f"start marks must lie in 0..{n_types - 1} (the model's types), got {start.marks.max()}")
        n_start = start.n
    elif start is None:
        n_start = 0
    else:
        counts = np.array(start).reshape(-1)
        if counts.size not in (1, n_types) or not np.issubdtype(counts.dtype, np.integer) or (counts < 0).any():
            raise ValueError(f"start must be None, a PointPattern, a number of points or one count per type "
                             f"({n_types}), got {start!r}")
        n_start = int(counts.sum())
    if setup.moves.p_shift == 1.0 and n_start == 0:
        raise ValueError("the fixed-count mode (p=1) keeps the start's number of points: give a non-empty start")


def _start_points(start, setup: _Setup, rng) -> tuple[np.ndarray, np.ndarray]:
    """Coordinates and types of x_0 (validated by :func:`_check_start_spec`)."""
    if start is None:
        return np.empty((0, 2)), np.empty(0, dtype=np.int64)
    if isinstance(start, PointPattern):
        return start.points, start.marks.astype(np.int64)
    counts = np.array(start).reshape(-1)
    if counts.size == 1:
        marks = _draw_types(int(counts[0]), setup, rng)
    else:
        marks = np.repeat(np.arange(counts.size), counts)
    x, y = _uniform_locations(setup.window, marks.size, rng)
    return np.column_stack([x, y]), marks


# ---------------------------------------------------------------------------- randomness


def _uniform_locations(window: Window, size: int, rng) -> tuple[np.ndarray, np.ndarray]:
    """``size`` independent uniform locations in the window (exact for every kind)."""
    if window.is_rectangle:  # no rejection needed: 2 draws per location
        return (window.xrange[0] + rng.random(size) * window.width,
                window.yrange[0] + rng.random(size) * window.height)
    xy = window.uniform_points(size, rng)
    return np.ascontiguousarray(xy[:, 0]), np.ascontiguousarray(xy[:, 1])


def _draw_types(size: int, setup: _Setup, rng) -> np.ndarray:
    n_types = setup.model.beta.size
    if n_types == 1:
        return np.zeros(size, dtype=np.int64)
    if setup.uniform_types:
        return rng.integers(n_types, size=size, dtype=np.int64)
    return rng.choice(n_types, size=size, p=setup.moves.type_prob).astype(np.int64)


def _map_values(setup: _Setup, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    if setup.intensity_map is None:
        return np.ones(x.size)
    return setup.intensity_map.at(x, y)


def _draw_proposals(setup: _Setup, size: int, rng) -> Proposals:
    """The randomness of ``size`` steps, drawn in a fixed order from ``rng``."""
    move, pick = rng.random(size), rng.random(size)
    x, y = _uniform_locations(setup.window, size, rng)
    mark = _draw_types(size, setup, rng)
    accept = rng.random(size)
    return Proposals(move, pick, x, y, _map_values(setup, x, y), mark, accept)


# ---------------------------------------------------------------------------- the chain


def _empty_state(n_cells: int, point_capacity: int, cell_capacity: int) -> State:
    cell_capacity += cell_capacity % 2  # even, so that every row of cell records is aligned
    return State(
        x=np.zeros(point_capacity), y=np.zeros(point_capacity), mark=np.zeros(point_capacity, dtype=np.int64),
        map_value=np.zeros(point_capacity), place=np.zeros((point_capacity, 2), dtype=np.int64),
        cell_count=np.zeros(n_cells, dtype=np.int64), cell_points=_cell_records(n_cells, cell_capacity),
    )


def _cell_records(n_cells: int, cell_capacity: int) -> np.ndarray:
    """Zeroed ``State.cell_points`` whose rows start on 64-byte (cache line) boundaries.

    A record is 32 bytes and the capacity is even, so with an aligned start every row is
    aligned and a cell's first two points share one cache line (numpy only guarantees
    16-byte alignment, with which they would straddle two lines about half of the time).
    """
    assert cell_capacity % 2 == 0, "an even capacity keeps every row aligned"
    size = n_cells * cell_capacity * 4
    buffer = np.zeros(size + 8)
    first = (-buffer.ctypes.data % 64) // 8
    return buffer[first: first + size].reshape(n_cells, cell_capacity, 4)


def _with_more_points(state: State) -> State:
    """The state with twice the point capacity (cell records refer to indices, which stay valid)."""
    grown = {name: np.concatenate([getattr(state, name), np.zeros_like(getattr(state, name))])
             for name in ("x", "y", "mark", "map_value", "place")}
    return state._replace(**grown)


def _with_bigger_cells(state: State) -> State:
    """The state with 1.5 times the slots per cell (slot numbers, and so ``state.place``, stay valid).

    A geometric growth keeps the number of regrowths logarithmic; a factor below 2 keeps
    the records compact, since every row is as long as the fullest cell needs and a
    neighbour scan pays for the memory of the whole grid (see ``_kernels``, "Memory").
    """
    n_cells, capacity, _ = state.cell_points.shape
    grown = capacity + max(2, capacity // 2)
    bigger = _cell_records(n_cells, grown + grown % 2)  # even, as _cell_records needs
    bigger[:, :capacity] = state.cell_points
    return state._replace(cell_points=bigger)


def _grown(state: State, status: int) -> State:
    if status == POINTS_FULL:
        return _with_more_points(state)
    if status == CELL_FULL:
        return _with_bigger_cells(state)
    raise RuntimeError(f"unexpected kernel status {status}")


class _Chain:
    """The Markov chain between kernel calls: its state grows when the kernel asks."""

    def __init__(self, setup: _Setup, points: np.ndarray, marks: np.ndarray):
        self.setup = setup
        self.scratch = np.zeros(setup.model.beta.size, dtype=np.int64)  # the kernel must not allocate
        grid = setup.grid
        x, y = np.array(points[:, 0], dtype=np.float64), np.array(points[:, 1], dtype=np.float64)
        occupancy = np.bincount(_kernels.cells_of(grid, x, y), minlength=1).max(initial=0)
        self.state = _empty_state(grid.ncx * grid.ncy, max(_MIN_POINT_CAPACITY, 2 * len(x)),
                                  max(_MIN_CELL_CAPACITY, int(occupancy) + _CELL_SLACK))
        self.n, status = _kernels.insert_points(0, x, y, marks, _map_values(setup, x, y), self.state, grid)
        assert status == DONE, "capacities were sized for the start"

    def conditional_intensities(self, locations, types, skips) -> np.ndarray:
        """lambda(u, m; x minus point skip) times the intensity map, at many locations."""
        out = np.empty(len(locations))
        x, y = np.array(locations[:, 0], dtype=np.float64), np.array(locations[:, 1], dtype=np.float64)
        _kernels.conditional_intensities(self.n, x, y, np.asarray(types, dtype=np.int64),
                                         np.asarray(skips, dtype=np.int64), self.state, self.setup.grid,
                                         self.setup.model, self.scratch, out)
        return out * _map_values(self.setup, x, y)

    def warn_if_zero_density(self) -> None:
        n, state = self.n, self.state
        points = np.column_stack([state.x[:n], state.y[:n]])
        zero = np.sum(self.conditional_intensities(points, state.mark[:n], np.arange(n)) == 0)
        if zero:
            warnings.warn(
                f"the start pattern has zero density: {zero} of its {n} points violate a hard core "
                "or sit where the intensity map is 0; the chain removes them (their death or shift is always "
                "accepted), so allow enough steps", stacklevel=4)

    def run(self, T: int, rng, stepper, *, progress: bool = False, trace: bool = False):
        """Run T steps in chunks; returns the step outcomes when ``trace``."""
        outcomes, T = [], int(T)
        with tqdm(total=T, disable=not progress, unit="step", desc="rmh", mininterval=0.5) as bar:
            for begin in range(0, T, _CHUNK_STEPS):
                size = min(_CHUNK_STEPS, T - begin)
                outcome = np.zeros(size, dtype=np.int8)
                self._run_chunk(_draw_proposals(self.setup, size, rng), outcome, stepper)
                if trace:
                    outcomes.append(outcome)
                bar.update(size)
        return np.concatenate(outcomes) if trace else None

    def _run_chunk(self, proposals: Proposals, outcome: np.ndarray, stepper) -> None:
        setup, step = self.setup, 0
        while True:
            step, self.n, status = stepper(self.n, self.state, setup.grid, setup.model, setup.moves, proposals,
                                           outcome, step, self.scratch)
            if status == DONE:
                return
            self.state = _grown(self.state, status)

    def pattern(self) -> PointPattern:
        n, state = self.n, self.state
        return PointPattern(np.column_stack([state.x[:n], state.y[:n]]), self.setup.window,
                            marks=state.mark[:n].copy(), categories=self.setup.categories)


# ---------------------------------------------------------------------------- warm-up


def _warm_up() -> float:
    """Load (or compile) every kernel with the exact argument types rmh uses; returns seconds."""
    from .models import StraussHard

    began = time.perf_counter()
    start = PointPattern([[0.25, 0.25], [0.75, 0.75]], Window.rectangle())
    rmh(StraussHard(10.0, 0.5, 0.1, 0.01), Window.rectangle(), T=16, start=start, p=0.5, rng=0)
    return time.perf_counter() - began


_warm_up()
