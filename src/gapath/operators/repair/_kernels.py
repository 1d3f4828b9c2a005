"""numba kernels of :class:`gapath.operators.repair.feasible.FeasibleStepRepair`.

Everything is in the encoding's frame (:class:`gapath.monotone.Frame`):
column ``k`` of a path is frame column ``col0 + k``, the vertical run of
rows ``entries[k] .. exits[k]``; the step into column ``k >= 1`` leaves the
exit row ``r`` of column ``k - 1`` and enters at ``entries[k]`` (``r`` for a
horizontal step, ``r -+ 1`` for a diagonal one).
"""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True)
def free_runs(occ):
    """Per cell, the last free row of its free vertical run downwards
    (``bot``) and the first upwards (``top``); ``bot = -1`` and ``top = H``
    on an obstacle. Rows ``a .. b`` (``a <= b``) of column ``c`` are all free
    exactly when ``bot[a, c] >= b``."""
    h, w = occ.shape
    top = np.empty((h, w), np.int64)
    bot = np.empty((h, w), np.int64)
    for c in range(w):
        for r in range(h):
            if occ[r, c]:
                top[r, c] = h
            elif r > 0 and not occ[r - 1, c]:
                top[r, c] = top[r - 1, c]
            else:
                top[r, c] = r
        for r in range(h - 1, -1, -1):
            if occ[r, c]:
                bot[r, c] = -1
            elif r < h - 1 and not occ[r + 1, c]:
                bot[r, c] = bot[r + 1, c]
            else:
                bot[r, c] = r
    return top, bot


@numba.njit(cache=True, inline="always")
def _run_free(bot, c, a, b):
    lo = a if a < b else b
    hi = b if a < b else a
    return bot[lo, c] >= hi


@numba.njit(cache=True, inline="always")
def _step_ok(occ, bot, c, r, e, t, corner_cutting):
    """The step from exit row ``r`` of column ``c - 1`` entering column
    ``c`` at row ``e``, then vertically to ``t``: no cell on an obstacle
    (and no cut corner when ``corner_cutting`` is False)."""
    if not _run_free(bot, c, e, t):
        return False
    if e != r and not corner_cutting and (occ[e, c - 1] or occ[r, c]):
        return False
    return True


@numba.njit(cache=True, inline="always")
def _entry(r, t):
    """The relative rule's entry row into a column whose exit row is ``t``."""
    return r + (1 if t > r else (-1 if t < r else 0))


@numba.njit(cache=True)
def exit_rows_allowed(occ, col0, n_cols, start_row, goal_row, corner_cutting, lookahead):
    """``allowed[k, t]``: exit row ``t`` of column ``k`` is a candidate of
    the repair.

    Without ``lookahead`` every row is a candidate except in column
    ``n_cols - 2``, whose candidates are the rows from which the encoding's
    end-fix (one step towards the goal row, then vertically to it) is free.
    With ``lookahead`` a row is a candidate when a feasible column-monotone
    path of the relative moves continues from it to the goal (backward
    reachability, one pass over the columns).
    """
    h = occ.shape[0]
    top, bot = free_runs(occ)
    allowed = np.zeros((n_cols, h), np.bool_)
    last = n_cols - 2
    gc = col0 + n_cols - 1
    for r in range(h):
        if not occ[r, col0 + last]:
            allowed[last, r] = _step_ok(occ, bot, gc, r, _entry(r, goal_row), goal_row, corner_cutting)
    for k in range(last):
        for r in range(h):
            allowed[k, r] = True
    if lookahead:
        for k in range(last - 1, -1, -1):
            c = col0 + k + 1
            for r in range(h):
                ok = False
                if not occ[r, col0 + k]:
                    for t in range(h):
                        if allowed[k + 1, t] and _step_ok(occ, bot, c, r, _entry(r, t), t, corner_cutting):
                            ok = True
                            break
                allowed[k, r] = ok
    allowed[n_cols - 1, goal_row] = True
    return allowed


@numba.njit(cache=True, inline="always")
def _nearest(occ, bot, c, r, t, allowed_k, first, corner_cutting, u, use_allowed):
    """The exit row nearest to ``t`` (ties: the upper one when ``u < 0.5``)
    from which the step out of row ``r`` into column ``c`` is free (and,
    with ``use_allowed``, that ``allowed_k`` permits); ``first``: column 0,
    whose run starts at ``r`` itself. -1 when there is none."""
    h = occ.shape[0]
    for d in range(h):
        best = -1
        for side in range(2):
            q = t - d if side == 0 else t + d
            if q < 0 or q >= h or (side == 1 and d == 0):
                continue
            if use_allowed and not allowed_k[q]:
                continue
            if first:
                ok = _run_free(bot, c, r, q)
            else:
                ok = _step_ok(occ, bot, c, r, _entry(r, q), q, corner_cutting)
            if ok:
                if best < 0 or (side == 1 and u >= 0.5):
                    best = q
        if best >= 0:
            return best
    return -1


@numba.njit(cache=True)
def repair_profiles(entries, exits, todo, occ, col0, start_row, goal_row, allowed, corner_cutting, U):
    """Repair the column profiles of the rows ``todo`` in place.

    Left to right, each column whose step (from the previous exit row, by
    the relative rule once an earlier column moved) touches an obstacle, or
    whose exit row ``allowed`` does not permit, gets the nearest exit row
    that is free and permitted (``U[i, k]`` breaks ties); if none is
    permitted, the nearest free one; if none is free (a dead end), the
    column is kept. A column that was not touched keeps its own entry row
    while no earlier column moved. The goal column is re-entered by the
    end-fix.

    Returns
    -------
    (n,) bool: the rows whose profile changed.
    """
    n, n_cols = exits.shape
    top, bot = free_runs(occ)
    changed = np.zeros(n, np.bool_)
    for i in range(n):
        if not todo[i]:
            continue
        moved = False
        r = start_row
        for k in range(n_cols - 1):
            c = col0 + k
            t = exits[i, k]
            if k == 0:
                e = start_row
                ok = _run_free(bot, c, e, t)
            else:
                e = _entry(r, t) if moved else entries[i, k]
                ok = _step_ok(occ, bot, c, r, e, t, corner_cutting)
            if not (ok and allowed[k, t]):
                q = _nearest(occ, bot, c, r, t, allowed[k], k == 0, corner_cutting, U[i, k], True)
                if q < 0:
                    q = _nearest(occ, bot, c, r, t, allowed[k], k == 0, corner_cutting, U[i, k], False)
                if q >= 0:
                    e_q = start_row if k == 0 else _entry(r, q)
                    if q != t or e_q != e:  # the same exit row may need another entry
                        t, e = q, e_q
                        moved = True
            if moved:
                entries[i, k] = e
                exits[i, k] = t
            r = t
        if moved:
            entries[i, n_cols - 1] = _entry(r, goal_row)
            changed[i] = True
    return changed
