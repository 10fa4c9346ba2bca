"""Numba kernels of :mod:`paperlib.pointprocess`: Metropolis-Hastings steps on a cell grid.

The sequential hot loop of :func:`paperlib.pointprocess.simulate.rmh` (Hurtut 2009,
section 3.3, Figure 4; Geyer & Møller 1994). One step evaluates the Papangelou
conditional intensity of the multitype Strauss hard-core model at one or two locations.
A uniform grid of cells, each at least as wide as the interaction reach, makes that cost
O(neighbours) instead of O(n) (spatstat's ``rmh`` scans every point): a query visits
only the cells that the square ``u +- reach`` overlaps. Below ``DENSE_SCAN_MAX`` points
times types, a branch-free scan of all points is faster than visiting cells and is used
instead; both give the same integer neighbour counts.

Data layout
-----------
Points live in dense arrays ``0 .. n-1`` so that a uniform pick is one index; a death
moves the last point into the freed slot (swap-remove). Each cell keeps the indices of its
points in a row of ``cell_members`` (the first ``cell_count[c]`` entries), and each point
remembers its cell and its slot in that row, so inserting, deleting and moving a point
are all O(1). When a point or cell array is full the kernel stops *before* changing
anything and says which; the caller grows the array and resumes at the same step, which
then replays identically.

Randomness
----------
The kernels draw no random numbers: the caller passes, per chunk of steps, arrays of
uniforms and of proposed locations and types (:class:`Proposals`), so that this kernel and
the pure-Python reference (:mod:`paperlib.pointprocess._reference`) consume the same
stream and agree step for step.

Floating point
--------------
The conditional intensity is ``beta_m`` multiplied by ``gamma_{m t}`` once per neighbour,
type by type in type order (counts first, products after), so its rounding does not depend
on the order in which neighbours are visited: the grid kernel and the O(n) reference get
bit-identical values. Acceptance tests read ``U * den < num`` for the ratio
``R = num / den``: no division, so a zero conditional intensity (a hard-core violation, a
zero of the intensity map) gives a certain rejection of a birth and a certain acceptance
of the death of an offending point, without infinities. Distances are compared squared,
against half-open bounds (``d2 < hc2``, ``d2 < r2``; see :class:`Interaction`).

Speed
-----
Numba increments and decrements the reference count of every array it hands to a compiled
function. The helpers here run several times per step on a dozen arrays, and that
bookkeeping cost more than their work. They are therefore compiled without the runtime
(``_nrt=False``, as numba compiles its own string and sorting helpers) and inlined
into :func:`mh_steps` and :func:`conditional_intensities`, which are compiled the same way
and so must not allocate: their callers pass the scratch and output arrays. With 50 points
this took a step from about 350 to 170 ns, and the scan of all points to about 100 ns
(spatstat: about 400 ns).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

__all__ = [
    "BIRTH", "CELL_FULL", "DEATH", "DONE", "Grid", "Interaction", "Moves", "NO_OP", "POINTS_FULL", "Proposals",
    "SHIFT", "State", "cells_of", "conditional_intensities", "insert_points", "mh_steps",
]

# Step outcomes, recorded per step: +kind when accepted, -kind when rejected, NO_OP when a
# death or shift was proposed to an empty pattern.
NO_OP, BIRTH, DEATH, SHIFT = 0, 1, 2, 3

# Why a kernel call returned.
DONE, POINTS_FULL, CELL_FULL = 0, 1, 2

# Up to this many points x types, a vectorised scan of all points beats visiting cells
# (about 25 vs 70 ns with 50 points; they break even near 100 points of one type).
DENSE_SCAN_MAX = 96

_helper = numba.njit(cache=True, _nrt=False, inline="always")  # see "Speed" above


class Grid(NamedTuple):
    """A uniform grid of ``ncx x ncy`` cells over the frame ``[x0, x0 + width] x [y0, y0 + height]``."""

    x0: float
    y0: float
    width: float
    height: float
    ncx: int
    ncy: int
    x_scale: float  # ncx / width: cells per unit length (multiplying is cheaper than dividing)
    y_scale: float
    reach: float  # the model's reach with a relative margin of 1e-9, so rounding never hides a neighbour
    periodic: bool  # distances on the torus (opposite sides of the frame glued)


class Interaction(NamedTuple):
    """The multitype Strauss hard-core model as the kernel needs it (M types).

    A pair at squared distance d2 is forbidden when ``d2 < hc2`` and counted when
    ``hc2 <= d2 < r2``. The caller turns spatstat's closed convention (d <= hc, d <= r)
    into these half-open bounds by moving them to the next double up.
    """

    beta: np.ndarray  # (M,)
    gamma: np.ndarray  # (M, M)
    r2: np.ndarray  # (M, M) squared interaction radii; 0 where gamma == 1 (such pairs need no count)
    hc2: np.ndarray  # (M, M) squared hard-core distances


class Moves(NamedTuple):
    """Proposal probabilities and the constants of the Hastings ratios."""

    p_shift: float  # probability of a shift; 1 = fixed-count mode
    q_death: float  # probability of a death given a birth-or-death move
    area: float  # |W|, the area proposals are drawn from
    type_prob: np.ndarray  # (M,) probability of proposing each type
    keep_marks: bool  # shifts keep the point's type (fixed count per type)


class Proposals(NamedTuple):
    """Pre-drawn randomness of a chunk of steps (all arrays have one entry per step)."""

    move: np.ndarray  # uniform: the move type
    pick: np.ndarray  # uniform: the point to kill or shift
    x: np.ndarray  # a uniform location in the window ...
    y: np.ndarray
    map_value: np.ndarray  # ... and the intensity map there
    mark: np.ndarray  # the proposed type (int64)
    accept: np.ndarray  # uniform: the Metropolis-Hastings test


class State(NamedTuple):
    """Points (first n entries of the point arrays) and their cell lists; mutated in place."""

    x: np.ndarray
    y: np.ndarray
    mark: np.ndarray
    map_value: np.ndarray  # intensity map at each point, kept so a death needs no look-up
    cell: np.ndarray  # the cell of each point ...
    slot: np.ndarray  # ... and its position in that cell's row of cell_members
    cell_count: np.ndarray  # (ncells,)
    cell_members: np.ndarray  # (ncells, cell capacity)


# ---------------------------------------------------------------------------- grid


@_helper
def _axis_cell(value, origin, scale, n_cells):
    """The cell index of a coordinate along one axis, clamped into the grid."""
    return min(max(math.floor((value - origin) * scale), 0), n_cells - 1)


@_helper
def _cell_of(grid, x, y):
    return _axis_cell(y, grid.y0, grid.y_scale, grid.ncy) * grid.ncx + _axis_cell(x, grid.x0, grid.x_scale, grid.ncx)


@numba.njit(cache=True)
def cells_of(grid, xs, ys):
    """The cell index of each location."""
    cells = np.empty(xs.size, dtype=np.int64)
    for k in range(xs.size):
        cells[k] = _cell_of(grid, xs[k], ys[k])
    return cells


@_helper
def _torus_cells(value, origin, scale, n_cells, reach):
    """First index and count of the cells of one torus axis that ``value +- reach`` overlaps.

    The first index may lie off the grid by less than a lap (wrap it); a range as long as
    the axis is the whole axis, each cell once.
    """
    first = math.floor((value - reach - origin) * scale)
    count = math.floor((value + reach - origin) * scale) - first + 1
    return (0, n_cells) if count >= n_cells else (first, count)


@_helper
def _wrapped(index, size):
    """``index % size`` for ``-size <= index < 2 size``, without an integer division."""
    if index < 0:
        return index + size
    if index >= size:
        return index - size
    return index


@_helper
def _torus_offset(delta, period):
    """|delta| reduced to the minimum image on a circle of length ``period``."""
    delta = abs(delta)
    return min(delta, period - delta)  # branch-free, so loops over points vectorise


# ---------------------------------------------------------------------------- conditional intensity


@_helper
def _tally(d2, mark, other, model, counts):
    """Count a type-``other`` neighbour at squared distance d2 if it is in the Strauss shell.

    Returns True if it is inside the hard core instead (the location is forbidden).
    """
    if d2 < model.hc2[mark, other]:
        return True
    if d2 < model.r2[mark, other]:
        counts[other] += 1
    return False


@_helper
def _tally_all(x, y, mark, skip, n, state, grid, model, counts):
    """Set ``counts`` by a scan of all n points, type by type; True if (x, y) is forbidden.

    No branch depends on the data, so the loop vectorises: for a few dozen points it beats
    visiting cells (see ``DENSE_SCAN_MAX``).
    """
    forbidden = False
    for other in range(counts.size):
        hc2, r2 = model.hc2[mark, other], model.r2[mark, other]
        count = 0
        for j in range(n):
            if grid.periodic:
                dx = _torus_offset(x - state.x[j], grid.width)
                dy = _torus_offset(y - state.y[j], grid.height)
            else:
                dx, dy = x - state.x[j], y - state.y[j]
            d2 = dx * dx + dy * dy
            counted = (state.mark[j] == other) & (j != skip)
            forbidden |= counted & (d2 < hc2)
            count += counted & (d2 < r2)
        counts[other] = count
    return forbidden


@_helper
def _tally_plane(x, y, mark, skip, state, grid, model, counts):
    """:func:`_tally` every point near (x, y) in the plane; True if (x, y) is forbidden."""
    first_column = max(math.floor((x - grid.reach - grid.x0) * grid.x_scale), 0)
    last_column = min(math.floor((x + grid.reach - grid.x0) * grid.x_scale), grid.ncx - 1)
    first_row = max(math.floor((y - grid.reach - grid.y0) * grid.y_scale), 0)
    last_row = min(math.floor((y + grid.reach - grid.y0) * grid.y_scale), grid.ncy - 1)
    for row in range(first_row, last_row + 1):
        for cell in range(row * grid.ncx + first_column, row * grid.ncx + last_column + 1):
            for s in range(state.cell_count[cell]):
                j = state.cell_members[cell, s]
                if j != skip:
                    dx, dy = x - state.x[j], y - state.y[j]
                    if _tally(dx * dx + dy * dy, mark, state.mark[j], model, counts):
                        return True
    return False


@_helper
def _tally_torus(x, y, mark, skip, state, grid, model, counts):
    """:func:`_tally_plane` on the torus (valid because the reach is at most half a side)."""
    first_column, n_columns = _torus_cells(x, grid.x0, grid.x_scale, grid.ncx, grid.reach)
    first_row, n_rows = _torus_cells(y, grid.y0, grid.y_scale, grid.ncy, grid.reach)
    for a in range(n_rows):
        row = _wrapped(first_row + a, grid.ncy)
        for b in range(n_columns):
            cell = row * grid.ncx + _wrapped(first_column + b, grid.ncx)
            for s in range(state.cell_count[cell]):
                j = state.cell_members[cell, s]
                if j != skip:
                    dx = _torus_offset(x - state.x[j], grid.width)
                    dy = _torus_offset(y - state.y[j], grid.height)
                    if _tally(dx * dx + dy * dy, mark, state.mark[j], model, counts):
                        return True
    return False


@_helper
def _papangelou(x, y, mark, skip, n, state, grid, model, counts):
    """lambda(u, m; x minus point ``skip``) without the intensity map (0 when forbidden).

    ``counts`` is scratch space of one entry per type; ``skip = -1`` leaves out nothing.
    Separate plane and torus grid scans keep the common plane case free of wrap-around
    tests. Which scan runs does not change the result: the counts are integers.
    """
    if n * counts.size <= DENSE_SCAN_MAX:
        forbidden = _tally_all(x, y, mark, skip, n, state, grid, model, counts)
    else:
        counts[:] = 0
        if grid.periodic:
            forbidden = _tally_torus(x, y, mark, skip, state, grid, model, counts)
        else:
            forbidden = _tally_plane(x, y, mark, skip, state, grid, model, counts)
    if forbidden:
        return 0.0
    intensity = model.beta[mark]
    for other in range(counts.size):  # type by type: rounding independent of the scan order
        g = model.gamma[mark, other]
        for _ in range(counts[other]):
            intensity *= g
    return intensity


@numba.njit(cache=True, _nrt=False)
def conditional_intensities(n, xs, ys, marks, skips, state, grid, model, counts, out):
    """Set out[k] = lambda(u_k, m_k; x minus point skips[k]) (without the map); ``counts``: scratch."""
    for k in range(xs.size):
        out[k] = _papangelou(xs[k], ys[k], marks[k], skips[k], n, state, grid, model, counts)


# ---------------------------------------------------------------------------- point lists


@_helper
def _link(i, cell, state):
    slot = state.cell_count[cell]
    state.cell_members[cell, slot] = i
    state.cell[i] = cell
    state.slot[i] = slot
    state.cell_count[cell] = slot + 1


@_helper
def _unlink(i, state):
    cell, slot = state.cell[i], state.slot[i]
    last = state.cell_count[cell] - 1
    moved = state.cell_members[cell, last]  # the cell's last member fills the hole
    state.cell_members[cell, slot] = moved
    state.slot[moved] = slot
    state.cell_count[cell] = last


@_helper
def _place(i, x, y, mark, map_value, cell, state):
    state.x[i] = x
    state.y[i] = y
    state.mark[i] = mark
    state.map_value[i] = map_value
    _link(i, cell, state)


@_helper
def _remove(i, n, state):
    """Delete point i of n; the last point takes its index. Returns the new n."""
    _unlink(i, state)
    last = n - 1
    if i != last:
        state.x[i] = state.x[last]
        state.y[i] = state.y[last]
        state.mark[i] = state.mark[last]
        state.map_value[i] = state.map_value[last]
        state.cell[i] = state.cell[last]
        state.slot[i] = state.slot[last]
        state.cell_members[state.cell[i], state.slot[i]] = i
    return last


@_helper
def _cell_is_full(cell, state):
    return state.cell_count[cell] == state.cell_members.shape[1]


@numba.njit(cache=True)
def insert_points(n, xs, ys, marks, map_values, state, grid):
    """Append points to the state. Returns (new n, status); stops before a full array."""
    for k in range(xs.size):
        cell = _cell_of(grid, xs[k], ys[k])
        if n == state.x.size:
            return n, POINTS_FULL
        if _cell_is_full(cell, state):
            return n, CELL_FULL
        _place(n, xs[k], ys[k], marks[k], map_values[k], cell, state)
        n += 1
    return n, DONE


# ---------------------------------------------------------------------------- Metropolis-Hastings


@_helper
def _accepts(uniform, numerator, denominator):
    """The Metropolis-Hastings test U < min(1, numerator / denominator), without dividing."""
    return uniform * denominator < numerator


@numba.njit(cache=True, _nrt=False)
def mh_steps(n, state, grid, model, moves, proposals, outcome, t_begin, counts):
    """Run steps ``t_begin ..`` of a chunk; returns (step reached, n, status).

    Hastings ratios (derived in :func:`paperlib.pointprocess.simulate.rmh`), with
    lambda including the intensity map, pi_m the type-proposal probabilities:

    - birth of (u, m):      R = lambda(u, m; x) |W| q / ((1 - q) (n + 1) pi_m)
    - death of x_i:         R = (1 - q) n pi_{m_i} / (lambda(x_i, m_i; x - x_i) |W| q)
    - shift x_i -> (u, m'): R = lambda(u, m'; x - x_i) pi_{m_i} / (lambda(x_i, m_i; x - x_i) pi_{m'})

    ``outcome[t]`` receives the outcome of step t; ``counts`` is scratch space of one
    int64 per type. ``status`` is DONE when the chunk is finished; POINTS_FULL or
    CELL_FULL when step ``t`` needs a larger array (nothing of step ``t`` is applied).
    """
    shift_below = moves.p_shift
    death_below = moves.p_shift + (1.0 - moves.p_shift) * moves.q_death
    q, area = moves.q_death, moves.area
    for t in range(t_begin, proposals.move.size):
        u = proposals.move[t]
        if u >= death_below:  # birth
            mark = proposals.mark[t]
            x, y = proposals.x[t], proposals.y[t]
            intensity = _papangelou(x, y, mark, -1, n, state, grid, model, counts) * proposals.map_value[t]
            numerator = intensity * area * q
            denominator = (1.0 - q) * (n + 1) * moves.type_prob[mark]
            if not _accepts(proposals.accept[t], numerator, denominator):
                outcome[t] = -BIRTH
                continue
            cell = _cell_of(grid, x, y)
            if n == state.x.size:
                return t, n, POINTS_FULL
            if _cell_is_full(cell, state):
                return t, n, CELL_FULL
            _place(n, x, y, mark, proposals.map_value[t], cell, state)
            n += 1
            outcome[t] = BIRTH
            continue
        if n == 0:  # a death or a shift of nothing
            outcome[t] = NO_OP
            continue
        i = min(int(proposals.pick[t] * n), n - 1)
        old_mark = state.mark[i]
        if u >= shift_below:  # death
            intensity = _papangelou(state.x[i], state.y[i], old_mark, i, n, state, grid, model, counts)
            intensity *= state.map_value[i]
            numerator = (1.0 - q) * n * moves.type_prob[old_mark]
            denominator = intensity * area * q
            if _accepts(proposals.accept[t], numerator, denominator):
                n = _remove(i, n, state)
                outcome[t] = DEATH
            else:
                outcome[t] = -DEATH
            continue
        # shift: point i to a new uniform location, with a new type unless types are fixed
        mark = old_mark if moves.keep_marks else proposals.mark[t]
        x, y = proposals.x[t], proposals.y[t]
        new_intensity = _papangelou(x, y, mark, i, n, state, grid, model, counts) * proposals.map_value[t]
        if new_intensity == 0.0:  # certain rejection: spare the second neighbour scan
            outcome[t] = -SHIFT
            continue
        old_intensity = _papangelou(state.x[i], state.y[i], old_mark, i, n, state, grid, model, counts)
        old_intensity *= state.map_value[i]
        numerator = new_intensity * moves.type_prob[old_mark]
        denominator = old_intensity * moves.type_prob[mark]
        if not _accepts(proposals.accept[t], numerator, denominator):
            outcome[t] = -SHIFT
            continue
        cell = _cell_of(grid, x, y)
        if cell != state.cell[i] and _cell_is_full(cell, state):
            return t, n, CELL_FULL
        _unlink(i, state)
        _place(i, x, y, mark, proposals.map_value[t], cell, state)
        outcome[t] = SHIFT
    return proposals.move.size, n, DONE
