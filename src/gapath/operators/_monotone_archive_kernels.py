"""numba kernels of :mod:`gapath.operators.monotone_archive`: re-routing a
stretch of columns of column-monotone paths, a whole batch per call."""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import SQRT2, ZERO, cuts_corner


@numba.njit(cache=True, inline="always")
def _start_run(cost, occ, pot, start_row, col0, wl, wv, cell_size):
    """Weighted costs of the start column's cells reached by a vertical run
    from the start row (the other cells of ``cost`` are left as they are)."""
    h = occ.shape[0]
    cost[start_row] = wv * pot[start_row, col0]
    for s in (-1, 1):
        e = start_row + s
        v = cost[start_row]
        while 0 <= e < h and not occ[e, col0]:
            v += wl * cell_size + wv * pot[e, col0]
            cost[e] = v
            e += s


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
            _start_run(cost, occ, pot, start_row, col0, wl, wv, cell_size)
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
            _start_run(cost, occ, pot, start_row, col0, wl, wv, cell_size)
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


@numba.njit(cache=True)
def _pareto_filter(L, V, P, n, cap, oL, oV, oP):
    """The non-dominated ones of the ``n`` labels ``(L, V, P)`` (first
    ``n`` entries), written to ``oL, oV, oP`` in increasing length; at most
    ``cap`` of them (evenly spread over the set, both ends kept). Returns
    their count. Equal labels are kept once."""
    if n == 0:
        return 0
    o1 = np.argsort(V[:n], kind="mergesort")
    o2 = np.argsort(L[:n][o1], kind="mergesort")
    order = o1[o2]  # by length, ties by vulnerability
    keep = np.empty(n, np.int64)
    m = 0
    best = np.inf
    for i in order:
        v = V[i]
        if m == 0 or v < best - 1e-9 * max(1.0, abs(best)):
            if m > 0 and L[i] <= L[keep[m - 1]] + 1e-9 * max(1.0, abs(L[i])):
                m -= 1  # the same length up to rounding, less vulnerable: replaces it
            keep[m] = i
            m += 1
            best = v
    if m > cap:
        for j in range(cap):
            q = keep[(j * (m - 1)) // (cap - 1)] if cap > 1 else keep[0]
            oL[j], oV[j], oP[j] = L[q], V[q], P[q]
        return cap
    for j in range(m):
        q = keep[j]
        oL[j], oV[j], oP[j] = L[q], V[q], P[q]
    return m


@numba.njit(cache=True)
def pareto_stretches(
    exits, pick, k0, k1, occ, pot, start_row, col0, cell_size, corner_cutting, cap, skip_unchanged
):
    """Every Pareto-optimal (length, vulnerability) re-routing of a stretch
    of columns of column-monotone paths, a whole batch per call.

    Stretch ``b`` is that of :func:`reroute_columns`: the exit rows of
    columns ``k0[b] + 1 .. k1[b] - 1`` of path ``pick[b]`` (a row of
    ``exits``) are replaced, the exit rows at ``k0[b]`` (``-1``: the start
    cell) and ``k1[b]`` and everything outside are kept. A bi-objective
    label programme over the stretch's columns keeps, per exit row, the
    non-dominated (length, vulnerability) partial stretches (at most
    ``cap`` of them, evenly spread when more); every non-dominated stretch
    reaching the end row is spliced into the path.

    Returns
    -------
    out : (R, n_cols) int64 exit rows of the spliced paths (those equal to
        their source path left out when ``skip_unchanged``).
    src : (R,) int64, the index into ``pick`` each row came from.
    """
    n_b = len(pick)
    h = occ.shape[0]
    n_cols = exits.shape[1]
    straight = cell_size
    diagonal = SQRT2 * cell_size
    out = np.empty((n_b * cap, n_cols), np.int64)
    src_of = np.empty(n_b * cap, np.int64)
    n_out = 0
    max_layers = n_cols + 1
    size = max_layers * h * cap
    pL = np.empty(size)
    pV = np.empty(size)
    pP = np.empty(size, np.int64)  # parent label (global index), -1 at layer 0
    cnt = np.zeros((max_layers, h), np.int64)
    cand_n = np.zeros(h, np.int64)
    cL = np.empty((h, 3 * cap))
    cV = np.empty((h, 3 * cap))
    cP = np.empty((h, 3 * cap), np.int64)
    rL = np.empty(2 * cap)
    rV = np.empty(2 * cap)
    rP = np.empty(2 * cap, np.int64)
    tL = np.empty(2 * cap)
    tV = np.empty(2 * cap)
    tP = np.empty(2 * cap, np.int64)
    for b in range(n_b):
        src = pick[b]
        a, z = k0[b], k1[b]
        cnt[:, :] = 0
        # layer 0: the labels leaving column a (or the start column)
        if a < 0:
            first = 1
            for s in (-1, 1):
                e = start_row
                lv, vv = 0.0, pot[start_row, col0]
                while 0 <= e < h and not occ[e, col0]:
                    if e != start_row or s < 0:
                        q = e * cap
                        pL[q], pV[q], pP[q] = lv, vv, -1
                        cnt[0, e] = 1
                    e += s
                    if 0 <= e < h:
                        lv += straight
                        vv += pot[e, col0]
        else:
            first = a + 1
            r0 = exits[src, a]
            q = r0 * cap
            pL[q], pV[q], pP[q] = 0.0, 0.0, -1
            cnt[0, r0] = 1
        if z < first:
            continue
        n_layers = z - first + 1
        for j in range(1, n_layers + 1):
            c = col0 + first + j - 1
            base_prev = (j - 1) * h * cap
            cand_n[:] = 0
            for e in range(h):  # horizontal steps
                if occ[e, c]:
                    continue
                for t in range(cnt[j - 1, e]):
                    q = base_prev + e * cap + t
                    m = cand_n[e]
                    cL[e, m] = pL[q] + straight
                    cV[e, m] = pV[q] + pot[e, c]
                    cP[e, m] = q
                    cand_n[e] = m + 1
            for s in (-1, 1):  # vertical runs, started by a diagonal step
                nr = 0
                e = h - 1 if s < 0 else 0
                while 0 <= e < h:
                    if occ[e, c]:
                        nr = 0
                        e += s
                        continue
                    here = pot[e, c]
                    nt = ZERO
                    for t in range(nr):
                        tL[nt], tV[nt], tP[nt] = rL[t] + straight, rV[t] + here, rP[t]
                        nt += 1
                    p = e - s
                    if (
                        0 <= p < h
                        and cnt[j - 1, p] > 0
                        and (corner_cutting or not cuts_corner(occ, p, c - 1, e, c))
                    ):
                        for t in range(cnt[j - 1, p]):
                            q = base_prev + p * cap + t
                            tL[nt], tV[nt], tP[nt] = pL[q] + diagonal, pV[q] + here, q
                            nt += 1
                    nr = _pareto_filter(tL, tV, tP, nt, cap, rL, rV, rP)
                    m = cand_n[e]
                    for t in range(nr):
                        cL[e, m], cV[e, m], cP[e, m] = rL[t], rV[t], rP[t]
                        m += 1
                    cand_n[e] = m
                    e += s
            base = j * h * cap
            for e in range(h):
                o = base + e * cap
                cnt[j, e] = _pareto_filter(
                    cL[e], cV[e], cP[e], cand_n[e], cap, pL[o : o + cap], pV[o : o + cap], pP[o : o + cap]
                )
        target = exits[src, z]
        base = n_layers * h * cap
        for t in range(cnt[n_layers, target]):
            q = base + target * cap + t
            for kk in range(n_cols):
                out[n_out, kk] = exits[src, kk]
            # walk back: the label at layer j sits in row (q % (h * cap)) // cap
            qq = q
            changed = False
            for j in range(n_layers, -1, -1):
                row = (qq % (h * cap)) // cap
                k = first + j - 1
                if k >= 0:
                    if out[n_out, k] != row:
                        changed = True
                    out[n_out, k] = row
                qq = pP[qq]
            if skip_unchanged and not changed:
                continue
            src_of[n_out] = b
            n_out += 1
    return out[:n_out], src_of[:n_out]
