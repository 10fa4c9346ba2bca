"""Pure-Python reference of the Metropolis-Hastings kernel, for the tests.

The same algorithm as :func:`paperlib.pointprocess._kernels.mh_steps`, written with plain
loops over Python lists and no spatial index: the conditional intensity scans every point
(O(n), like spatstat's ``rmh``). It reads the same pre-drawn
:class:`~paperlib.pointprocess._kernels.Proposals`, keeps the points in the same order
(swap-remove on death) and does the same floating-point operations in the same order, so
its step outcomes and final points equal the numba kernel's bit for bit; any difference
is a bug in the cell grid or in one of the two. The cell arrays of the state are left
untouched.
"""

from __future__ import annotations

from ._kernels import BIRTH, DEATH, DONE, NO_OP, POINTS_FULL, SHIFT

__all__ = ["reference_steps"]


def _squared_distance(x1, y1, x2, y2, grid):
    dx, dy = abs(x1 - x2), abs(y1 - y2)
    if grid.periodic:  # minimum image
        if dx > 0.5 * grid.width:
            dx = grid.width - dx
        if dy > 0.5 * grid.height:
            dy = grid.height - dy
    return dx * dx + dy * dy


def _papangelou(x, y, mark, skip, points, grid, model):
    """lambda(u, m; x minus point ``skip``), by a scan of all points (0 when forbidden)."""
    xs, ys, marks = points
    beta, gamma, r2, hc2 = model
    counts = [0] * len(beta)
    for j in range(len(xs)):
        if j == skip:
            continue
        other = marks[j]
        d2 = _squared_distance(x, y, xs[j], ys[j], grid)
        if d2 < hc2[mark][other]:
            return 0.0
        if d2 < r2[mark][other]:
            counts[other] += 1
    intensity = beta[mark]
    for other, count in enumerate(counts):
        for _ in range(count):
            intensity *= gamma[mark][other]
    return intensity


def reference_steps(n, state, grid, model, moves, proposals, outcome, t_begin, _scratch=None):
    """Drop-in replacement of :func:`~paperlib.pointprocess._kernels.mh_steps` (never reports a full cell)."""
    xs, ys = state.x[:n].tolist(), state.y[:n].tolist()
    marks, map_values = state.mark[:n].tolist(), state.map_value[:n].tolist()
    points = (xs, ys, marks)
    model = tuple(array.tolist() for array in model)
    q, area, type_prob = moves.q_death, moves.area, moves.type_prob.tolist()
    shift_below = moves.p_shift
    death_below = shift_below + (1.0 - shift_below) * q
    status, t_end = DONE, proposals.move.size
    for t in range(t_begin, proposals.move.size):
        u, accept = float(proposals.move[t]), float(proposals.accept[t])
        x, y = float(proposals.x[t]), float(proposals.y[t])
        new_map, new_mark = float(proposals.map_value[t]), int(proposals.mark[t])
        n = len(xs)
        if u >= death_below:  # birth
            intensity = _papangelou(x, y, new_mark, -1, points, grid, model) * new_map
            if not accept * ((1.0 - q) * (n + 1) * type_prob[new_mark]) < intensity * area * q:
                outcome[t] = -BIRTH
                continue
            if n == state.x.size:
                status, t_end = POINTS_FULL, t
                break
            xs.append(x), ys.append(y), marks.append(new_mark), map_values.append(new_map)
            outcome[t] = BIRTH
            continue
        if n == 0:
            outcome[t] = NO_OP
            continue
        i = min(int(float(proposals.pick[t]) * n), n - 1)
        old_mark = marks[i]
        old_intensity = _papangelou(xs[i], ys[i], old_mark, i, points, grid, model) * map_values[i]
        if u >= shift_below:  # death: the last point takes index i
            if accept * (old_intensity * area * q) < (1.0 - q) * n * type_prob[old_mark]:
                for values in (xs, ys, marks, map_values):
                    values[i] = values[-1]
                    values.pop()
                outcome[t] = DEATH
            else:
                outcome[t] = -DEATH
            continue
        mark = old_mark if moves.keep_marks else new_mark
        new_intensity = _papangelou(x, y, mark, i, points, grid, model) * new_map
        if accept * (old_intensity * type_prob[mark]) < new_intensity * type_prob[old_mark]:
            xs[i], ys[i], marks[i], map_values[i] = x, y, mark, new_map
            outcome[t] = SHIFT
        else:
            outcome[t] = -SHIFT
    n = len(xs)
    state.x[:n], state.y[:n], state.mark[:n], state.map_value[:n] = xs, ys, marks, map_values
    return t_end, n, status
