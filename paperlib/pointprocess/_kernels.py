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
moves the last point into the freed slot (swap-remove). The dense order is the chain's
state: it decides which point a pick selects and the order of the output.

The neighbour scans read instead a copy of the points stored by cell: row ``c`` of
``cell_points`` holds, in its first ``cell_count[c]`` slots, the x, y, type and dense
index of each point of cell c, one 32-byte record per slot, and ``place[i]`` gives the
cell and slot of point i. Inserting, deleting and moving a point are O(1) (a cell's last
record fills a hole). The dense order is the random birth order, so a scan that went
from a cell's member list to ``x[j]``, ``y[j]`` and ``mark[j]`` read about three scattered
cache lines per neighbour besides the list. A cell's records are contiguous and rows
start on 64-byte boundaries (``simulate._cell_records``), so a cell holding up to two
points is one cache line and a scan reads about one line per cell visited. A picked point
is read the same way (``place[i]``, then its cell's row, which the scan around it reads
anyway). Only integer neighbour counts come out of a scan, so the layout changes no
result.

When a point or cell array is full the kernel stops *before* changing anything and says
which; the caller grows the array and resumes at the same step, which then replays
identically.

Memory
------
Profiled on the benchmark family (StraussHard, spatstat's moves), a step cost about
140 ns at 1e3 points, 175 ns at 1e4 and 300 to 600 ns at 1e5 (timings on a loaded 2-core
machine); sorting the start's points by cell gave no consistent gain, and the layout
above alone about 10% at 1e5. The growth is not the order of the points but the
randomness of the proposals: every step reads a dozen cache lines at random places of
the whole grid (the cells around a uniform location, a uniformly picked point and the
cells around it), and beyond the last-level cache (the records of 1e5 points take about
20 MB) each is a wait of the order of 100 ns. But the proposals of a chunk are drawn in
advance, so step t requests (``llvm.prefetch``) the lines that step
``t + PREFETCH_AHEAD`` will read, in two stages for a picked point (its ``place`` entry
``2 * PREFETCH_AHEAD`` steps ahead, the 3 x 3 cells around it ``PREFETCH_AHEAD`` steps
ahead), and the waits overlap: about half the time of a step at 1e5 points. The pick is
predicted with the current n, which a birth or death in between may make wrong; a
prefetch only moves data into the cache, so a wrong one wastes a request and no result
depends on it. Below ``PREFETCH_MIN_BYTES`` of cell records (a few 1e4 points) the
records stay in the cache, the requests cost more instructions than they save (measured
at 1e4 points: 10-30% slower), and a loop compiled without them runs.

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

The three neighbour scans (``_tally_all``, ``_tally_plane``, ``_tally_torus``) are inlined by
LLVM (``forceinline``) rather than in numba's IR: numba retypes a function for every
call it inlines, and the scans, inlined into four conditional intensities of each of the
two loops of :func:`mh_steps`, made its compilation take 39 s on a cold cache (every
first import of :mod:`paperlib.pointprocess`, every CI run on a new processor). Inlined
by LLVM they take 12 s and the steps run as fast (interleaved runs at 1e5 points: medians
296-316 vs 306-325 ns a step), with the same results bit for bit.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np
from llvmlite import ir
from numba.core import cgutils, types
from numba.extending import intrinsic

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
_scan = numba.njit(cache=True, _nrt=False, forceinline=True)  # inlined by LLVM instead: see "Speed"

# Prefetching (see "Memory" in the module docstring): how many steps ahead the locations a
# step will read are requested, and the size of the cell records above which it pays.
PREFETCH_AHEAD = 8
PREFETCH_MIN_BYTES = 8 << 20


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
    """Points (first n entries of the point arrays) and their copy by cell; mutated in place.

    See "Data layout" in the module docstring.
    """

    x: np.ndarray
    y: np.ndarray
    mark: np.ndarray
    map_value: np.ndarray  # intensity map at each point, kept so a death needs no look-up
    place: np.ndarray  # (point capacity, 2): the cell of each point and its slot in that cell's row
    cell_count: np.ndarray  # (ncells,)
    # (ncells, cell capacity, 4): x, y, type and dense index of the point in each slot, as
    # float64 (exact for types and indices below 2**53); rows 64-byte aligned, capacity even
    cell_points: np.ndarray


# Fields of a record of State.cell_points.
_X, _Y, _MARK, _INDEX = 0, 1, 2, 3


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


@_scan
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
def _record_mark(cell, slot, state, counts):
    """The type of a record; with one type, 0 without reading it.

    The float-to-int conversion lies between the load of a neighbour and its test; a
    one-type model (the commonest) need not pay it.
    """
    return int(state.cell_points[cell, slot, _MARK]) if counts.size > 1 else 0


@_scan
def _tally_plane(x, y, mark, skip, state, grid, model, counts):
    """:func:`_tally` every point near (x, y) in the plane; True if (x, y) is forbidden.

    Reads the records of ``cell_points`` (see "Data layout"). The point ``skip`` is left out
    by the index field of the record, in the cache line just read (-1 matches no record).
    """
    first_column = max(math.floor((x - grid.reach - grid.x0) * grid.x_scale), 0)
    last_column = min(math.floor((x + grid.reach - grid.x0) * grid.x_scale), grid.ncx - 1)
    first_row = max(math.floor((y - grid.reach - grid.y0) * grid.y_scale), 0)
    last_row = min(math.floor((y + grid.reach - grid.y0) * grid.y_scale), grid.ncy - 1)
    for row in range(first_row, last_row + 1):
        for cell in range(row * grid.ncx + first_column, row * grid.ncx + last_column + 1):
            for s in range(state.cell_count[cell]):
                if state.cell_points[cell, s, _INDEX] != skip:
                    dx, dy = x - state.cell_points[cell, s, _X], y - state.cell_points[cell, s, _Y]
                    if _tally(dx * dx + dy * dy, mark, _record_mark(cell, s, state, counts), model, counts):
                        return True
    return False


@_scan
def _tally_torus(x, y, mark, skip, state, grid, model, counts):
    """:func:`_tally_plane` on the torus (valid because the reach is at most half a side)."""
    first_column, n_columns = _torus_cells(x, grid.x0, grid.x_scale, grid.ncx, grid.reach)
    first_row, n_rows = _torus_cells(y, grid.y0, grid.y_scale, grid.ncy, grid.reach)
    for a in range(n_rows):
        row = _wrapped(first_row + a, grid.ncy)
        for b in range(n_columns):
            cell = row * grid.ncx + _wrapped(first_column + b, grid.ncx)
            for s in range(state.cell_count[cell]):
                if state.cell_points[cell, s, _INDEX] != skip:
                    dx = _torus_offset(x - state.cell_points[cell, s, _X], grid.width)
                    dy = _torus_offset(y - state.cell_points[cell, s, _Y], grid.height)
                    if _tally(dx * dx + dy * dy, mark, _record_mark(cell, s, state, counts), model, counts):
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
    """Set out[k] = lambda(u_k, m_k; x minus point skips[k]) (without the map); ``counts``: scratch.

    With a large state, the cells of location ``k + PREFETCH_AHEAD`` are requested while
    location k is scanned (see "Memory"): rmh evaluates this at every point of a start.
    """
    prefetching = state.cell_points.size * 8 >= PREFETCH_MIN_BYTES and n * counts.size > DENSE_SCAN_MAX
    for k in range(xs.size):
        if prefetching and k + PREFETCH_AHEAD < xs.size:
            _prefetch_around(xs[k + PREFETCH_AHEAD], ys[k + PREFETCH_AHEAD], state, grid)
        out[k] = _papangelou(xs[k], ys[k], marks[k], skips[k], n, state, grid, model, counts)


# ---------------------------------------------------------------------------- point lists


@_helper
def _link(i, x, y, mark, cell, state):
    """Append point i, at (x, y) with type ``mark``, to the records of ``cell``."""
    slot = state.cell_count[cell]
    state.cell_points[cell, slot, _X] = x
    state.cell_points[cell, slot, _Y] = y
    state.cell_points[cell, slot, _MARK] = mark
    state.cell_points[cell, slot, _INDEX] = i
    state.place[i, 0] = cell
    state.place[i, 1] = slot
    state.cell_count[cell] = slot + 1


@_helper
def _unlink(i, state):
    """Drop point i's record from its cell; the cell's last record fills the hole."""
    cell, slot = state.place[i, 0], state.place[i, 1]
    last = state.cell_count[cell] - 1
    if slot != last:
        for field in range(4):
            state.cell_points[cell, slot, field] = state.cell_points[cell, last, field]
        state.place[int(state.cell_points[cell, slot, _INDEX]), 1] = slot
    state.cell_count[cell] = last


@_helper
def _place(i, x, y, mark, map_value, cell, state):
    state.x[i] = x
    state.y[i] = y
    state.mark[i] = mark
    state.map_value[i] = map_value
    _link(i, x, y, mark, cell, state)


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
        cell, slot = state.place[last, 0], state.place[last, 1]
        state.place[i, 0] = cell
        state.place[i, 1] = slot
        state.cell_points[cell, slot, _INDEX] = i  # the moved point's record keeps its cell and slot
    return last


@_helper
def _cell_is_full(cell, state):
    return state.cell_count[cell] == state.cell_points.shape[1]


@numba.njit(cache=True)
def insert_points(n, xs, ys, marks, map_values, state, grid):
    """Append points to the state. Returns (new n, status); stops before a full array."""
    prefetching = state.cell_points.size * 8 >= PREFETCH_MIN_BYTES
    row_stride = state.cell_points.shape[1] * state.cell_points.shape[2]
    for k in range(xs.size):
        if prefetching and k + PREFETCH_AHEAD < xs.size:  # the cell of a later point (see "Memory")
            ahead = _cell_of(grid, xs[k + PREFETCH_AHEAD], ys[k + PREFETCH_AHEAD])
            _prefetch(state.cell_count, ahead)
            _prefetch(state.cell_points, ahead * row_stride)
        cell = _cell_of(grid, xs[k], ys[k])
        if n == state.x.size:
            return n, POINTS_FULL
        if _cell_is_full(cell, state):
            return n, CELL_FULL
        _place(n, xs[k], ys[k], marks[k], map_values[k], cell, state)
        n += 1
    return n, DONE


# ---------------------------------------------------------------------------- prefetching


@intrinsic
def _prefetch(typingctx, array, index):
    """Ask the CPU to bring ``array.flat[index]`` into the cache (no effect on any value).

    ``llvm.prefetch`` (read, high locality, data cache); ``array`` must be C-contiguous.
    """
    if not (isinstance(array, types.Array) and array.layout == "C" and isinstance(index, types.Integer)):
        return None

    def codegen(context, builder, signature, args):
        data = context.make_array(signature.args[0])(context, builder, args[0]).data
        address = builder.bitcast(builder.gep(data, [args[1]]), ir.IntType(8).as_pointer())  # one declaration
        i32 = ir.IntType(32)
        function = cgutils.get_or_insert_function(
            builder.module, ir.FunctionType(ir.VoidType(), [address.type, i32, i32, i32]), "llvm.prefetch.p0")
        builder.call(function, [address, ir.Constant(i32, 0), ir.Constant(i32, 3), ir.Constant(i32, 1)])
        return context.get_dummy_value()

    return types.void(array, types.intp), codegen


@_helper
def _prefetch_cells(first_column, last_column, first_row, last_row, state, grid):
    """Prefetch the counts and the first record line of the cells in a block of the grid."""
    first_column, last_column = max(first_column, 0), min(last_column, grid.ncx - 1)
    first_row, last_row = max(first_row, 0), min(last_row, grid.ncy - 1)
    row_stride = state.cell_points.shape[1] * state.cell_points.shape[2]
    for row in range(first_row, last_row + 1):
        first = row * grid.ncx + first_column
        _prefetch(state.cell_count, first)
        for cell in range(first, row * grid.ncx + last_column + 1):
            _prefetch(state.cell_points, cell * row_stride)


@_helper
def _prefetch_block(cell, state, grid):
    """Prefetch the 3 x 3 cells centred on ``cell``: all a query at a point of it scans (cells are >= reach wide).

    Flat offsets, without the division that would give the cell's column: at the left and
    right edges a row's neighbours wrap to the next row's, a harmless wasted request.
    """
    row_stride = state.cell_points.shape[1] * state.cell_points.shape[2]
    n_cells = state.cell_count.size
    for first in (cell - grid.ncx - 1, cell - 1, cell + grid.ncx - 1):
        for neighbour in range(max(first, 0), min(first + 3, n_cells)):
            _prefetch(state.cell_points, neighbour * row_stride)
        if 0 <= first + 1 < n_cells:
            _prefetch(state.cell_count, first + 1)


@_helper
def _prefetch_around(x, y, state, grid):
    """Prefetch the cells that a query at (x, y) scans (in the plane; on a torus, but for wrapped cells)."""
    _prefetch_cells(math.floor((x - grid.reach - grid.x0) * grid.x_scale),
                    math.floor((x + grid.reach - grid.x0) * grid.x_scale),
                    math.floor((y - grid.reach - grid.y0) * grid.y_scale),
                    math.floor((y + grid.reach - grid.y0) * grid.y_scale), state, grid)


@_helper
def _prefetch_proposal(t, n, state, grid, proposals, shift_below, death_below):
    """Prefetch what step t will read, as far as it is known now (see "Memory")."""
    ahead = t + PREFETCH_AHEAD
    if ahead < proposals.move.size and (proposals.move[ahead] < shift_below or proposals.move[ahead] >= death_below):
        _prefetch_around(proposals.x[ahead], proposals.y[ahead], state, grid)  # a shift's or birth's location
    if n == 0:
        return
    if ahead < proposals.move.size and proposals.move[ahead] < death_below:  # a death or shift: its point's cells
        i = min(int(proposals.pick[ahead] * n), n - 1)
        _prefetch_block(state.place[i, 0], state, grid)  # place[i] was requested PREFETCH_AHEAD steps ago
    further = ahead + PREFETCH_AHEAD
    if further < proposals.move.size and proposals.move[further] < death_below:
        i = min(int(proposals.pick[further] * n), n - 1)
        _prefetch(state.place, 2 * i)
        _prefetch(state.map_value, i)
        _prefetch(state.x, i)  # written if the move is accepted
        _prefetch(state.y, i)
        _prefetch(state.mark, i)


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

    Once the cell records reach ``PREFETCH_MIN_BYTES`` (and the grid is scanned), the
    steps request the memory of later steps ahead of time (see "Memory"); below, a loop
    without that code runs, as compact as it was before prefetching existed.
    """
    if state.cell_points.size * 8 >= PREFETCH_MIN_BYTES and n * counts.size > DENSE_SCAN_MAX:
        return _steps(n, state, grid, model, moves, proposals, outcome, t_begin, counts, True)
    return _steps(n, state, grid, model, moves, proposals, outcome, t_begin, counts, False)


@_helper
def _steps(n, state, grid, model, moves, proposals, outcome, t_begin, counts, prefetching):
    """The loop of :func:`mh_steps`; a literal ``prefetching`` compiles it with or without prefetches."""
    shift_below = moves.p_shift
    death_below = moves.p_shift + (1.0 - moves.p_shift) * moves.q_death
    q, area = moves.q_death, moves.area
    for t in range(t_begin, proposals.move.size):
        if prefetching:
            _prefetch_proposal(t, n, state, grid, proposals, shift_below, death_below)
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
        # the picked point from its cell record (the same values as x[i], y[i], mark[i]):
        # the scan around it reads that row anyway, the dense arrays would be three more misses
        old_cell, old_slot = state.place[i, 0], state.place[i, 1]
        old_x, old_y = state.cell_points[old_cell, old_slot, _X], state.cell_points[old_cell, old_slot, _Y]
        old_mark = int(state.cell_points[old_cell, old_slot, _MARK])
        if u >= shift_below:  # death
            intensity = _papangelou(old_x, old_y, old_mark, i, n, state, grid, model, counts)
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
        old_intensity = _papangelou(old_x, old_y, old_mark, i, n, state, grid, model, counts)
        old_intensity *= state.map_value[i]
        numerator = new_intensity * moves.type_prob[old_mark]
        denominator = old_intensity * moves.type_prob[mark]
        if not _accepts(proposals.accept[t], numerator, denominator):
            outcome[t] = -SHIFT
            continue
        cell = _cell_of(grid, x, y)
        if cell != old_cell and _cell_is_full(cell, state):
            return t, n, CELL_FULL
        _unlink(i, state)
        _place(i, x, y, mark, proposals.map_value[t], cell, state)
        outcome[t] = SHIFT
    return proposals.move.size, n, DONE
