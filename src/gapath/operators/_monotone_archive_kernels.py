"""numba kernels of :mod:`gapath.operators.monotone_archive`: re-routing a
stretch of columns of column-monotone paths, a whole batch per call."""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import SQRT2, cuts_corner


@numba.njit(cache=True)
def _relax_column(cost, new, back, occ, pot, c, w_len, w_vul, cell_size, corner_cutting):
    """One column of the re-routing programme, in O(rows).

    ``cost[p]`` is the best weighted cost of a partial path leaving frame
    column ``c - 1`` at exit row ``p``; ``new[e]`` becomes that of leaving
    column ``c`` at ``e`` and ``back[e]`` the previous exit row. Column ``c``
    is entered by one horizontal step (exit row ``p`` itself) or by one
    diagonal step to ``p -/+ 1`` followed by vertical steps the same way
    (the relative-move path set), never into an obstacle nor, without corner
    cutting, across a corner. The upward and downward runs are swept once
    each: a run reaching ``e`` either continues the best run at the
    neighbouring row or starts at ``e`` by the diagonal step."""
    h = occ.shape[0]
    inf = np.inf
    straight = w_len * cell_size
    diagonal = w_len * SQRT2 * cell_size
    for e in range(h):
        new[e] = inf
        back[e] = -1
        if not occ[e, c] and cost[e] < inf:
            new[e] = cost[e] + straight + w_vul * pot[e, c]
            back[e] = e
    for s in (-1, 1):  # -1: runs going up (entered from row e + 1), +1: down
        run = inf
        origin = -1
        e = h - 1 if s < 0 else 0
        while 0 <= e < h:
            if occ[e, c]:
                run = inf
            else:
                here = w_vul * pot[e, c]
                if run < inf:
                    run += straight + here
                p = e - s
                if 0 <= p < h and cost[p] < inf and (corner_cutting or not cuts_corner(occ, p, c - 1, e, c)):
                    v = cost[p] + diagonal + here
                    if v < run:
                        run = v
                        origin = p
                if run < new[e]:
                    new[e] = run
                    back[e] = origin
            e += s


@numba.njit(cache=True)
def reroute_columns(exits, pick, k0, k1, w_len, w_vul, occ, pot, start_row, col0, cell_size, corner_cutting):
    """Re-route stretches of column-monotone paths optimally.

    Path ``b`` is row ``pick[b]`` of ``exits`` (exit rows per column, frame
    rows, the relative-move path set of :mod:`gapath.encodings._relative`).
    Its exit rows of columns ``k0[b] + 1 .. k1[b] - 1`` are replaced by those
    of the path minimising ``w_len[b] * length + w_vul[b] * vulnerability``
    over the feasible column-monotone paths that leave column ``k0[b]`` at
    its exit row and leave column ``k1[b]`` at its exit row (``k0[b] = -1``:
    from the start cell, the start column's vertical run included). The
    path outside the stretch is unchanged, and so is every step outside it.

    Returns
    -------
    (B, n_cols) int64 exit rows of the re-routed paths (the original ones
    where the stretch has no feasible re-routing, which cannot happen for a
    feasible path: its own stretch is a candidate).
    """
    n_b = len(pick)
    h = occ.shape[0]
    n_cols = exits.shape[1]
    out = np.empty((n_b, n_cols), np.int64)
    cost = np.empty(h)
    new = np.empty(h)
    back = np.empty((n_cols, h), np.int64)
    inf = np.inf
    for b in range(n_b):
        src = pick[b]
        for k in range(n_cols):
            out[b, k] = exits[src, k]
        a, z = k0[b], k1[b]
        wl, wv = w_len[b], w_vul[b]
        cost[:] = inf
        if a < 0:  # the start column: a vertical run from the start row
            first = 1
            cost[start_row] = wv * pot[start_row, col0]
            for s in (-1, 1):
                e = start_row + s
                v = cost[start_row]
                while 0 <= e < h and not occ[e, col0]:
                    v += wl * cell_size + wv * pot[e, col0]
                    cost[e] = v
                    e += s
            if z == 0:
                continue
        else:
            first = a + 1
            cost[exits[src, a]] = 0.0
        target = exits[src, z]
        for k in range(first, z + 1):
            _relax_column(cost, new, back[k], occ, pot, col0 + k, wl, wv, cell_size, corner_cutting)
            cost[:] = new
        if cost[target] == inf:
            continue
        r = target
        for k in range(z, first - 1, -1):
            r = back[k, r]
            if k - 1 >= 0:
                out[b, k - 1] = r
    return out


@numba.njit(cache=True)
def entries_of(exits, start_row):
    """Entry rows of the relative-move path set: one step from the previous
    exit row towards the column's exit row (the start row in column 0)."""
    n, n_cols = exits.shape
    entries = np.empty((n, n_cols), np.int64)
    for i in range(n):
        prev = start_row
        for k in range(n_cols):
            e = exits[i, k]
            entries[i, k] = start_row if k == 0 else prev + (1 if e > prev else (-1 if e < prev else 0))
            prev = e
    return entries


@numba.njit(cache=True)
def reroute_sweep(
    exits, pick, k0, lo, hi, w_len, w_vul, occ, pot, start_row, col0, cell_size, corner_cutting
):
    """Every re-routing of :func:`reroute_columns` that starts at column
    ``k0[b]`` of path ``pick[b]``, for every end column ``k1`` with ``lo[b]
    <= k1 - k0[b] <= hi[b]``, from one forward sweep of the programme.

    Returns
    -------
    out : (R, n_cols) int64 exit rows of the re-routed paths that differ
        from their source path.
    src : (R,) int64, the index into ``pick`` each row came from.
    """
    n_b = len(pick)
    h = occ.shape[0]
    n_cols = exits.shape[1]
    cap = 0
    for b in range(n_b):
        cap += max(0, min(hi[b], n_cols - 1 - k0[b]) - lo[b] + 1)
    out = np.empty((cap, n_cols), np.int64)
    src_of = np.empty(cap, np.int64)
    cost = np.empty(h)
    new = np.empty(h)
    back = np.empty((n_cols, h), np.int64)
    inf = np.inf
    n_out = 0
    for b in range(n_b):
        src = pick[b]
        a = k0[b]
        wl, wv = w_len[b], w_vul[b]
        cost[:] = inf
        if a < 0:  # the start column: a vertical run from the start row
            first = 1
            cost[start_row] = wv * pot[start_row, col0]
            for s in (-1, 1):
                e = start_row + s
                v = cost[start_row]
                while 0 <= e < h and not occ[e, col0]:
                    v += wl * cell_size + wv * pot[e, col0]
                    cost[e] = v
                    e += s
        else:
            first = a + 1
            cost[exits[src, a]] = 0.0
        last = min(n_cols - 1, a + hi[b])
        for k in range(first, last + 1):
            _relax_column(cost, new, back[k], occ, pot, col0 + k, wl, wv, cell_size, corner_cutting)
            cost[:] = new
            if k - a < lo[b]:
                continue
            target = exits[src, k]
            if cost[target] == inf:
                continue
            # the stretch a+1 .. k-1 re-routed, the rest as the source path
            changed = False
            r = target
            for kk in range(k, first - 1, -1):
                r = back[kk, r]
                if kk - 1 >= 0:
                    out[n_out, kk - 1] = r
                    if r != exits[src, kk - 1]:
                        changed = True
            if not changed:
                continue
            for kk in range(n_cols):
                if kk < first - 1 or kk >= k:
                    out[n_out, kk] = exits[src, kk]
            src_of[n_out] = b
            n_out += 1
    return out[:n_out], src_of[:n_out]
