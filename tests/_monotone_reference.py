"""The monotone DP of gapath.planners.exact as it was before issue 15 item 3
(every label of every column kept, every vertical-run candidate filtered at
its row), kept verbatim as the test reference of the faster DP: fronts must
be bit-identical (F and smoothness)."""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import SQRT2, can_step, turn
from gapath.monotone import Frame
from gapath.objectives import QUARTER_PI

TOL = 1e-9
DONE, PAUSED, OVER_BUDGET = 0, 1, 2

ROW, PARENT, HEAD, N_STRAIGHT, N_DIAG, EIGHTHS = range(6)
LENGTH, VUL = range(2)

# Headings, coded as in gapath.objectives (eighths counter-clockwise from east;
# "up" is towards row 0). Monotone paths only use these five.
NO_HEADING, EAST, NORTH_EAST, NORTH, SOUTH, SOUTH_EAST = -1, 0, 1, 2, 6, 7


@numba.njit(cache=True)
def _grow(table, size):
    """``table`` with at least ``size`` rows (capacity doubled)."""
    if size <= table.shape[0]:
        return table
    out = np.empty((max(size, 2 * table.shape[0]), table.shape[1]), table.dtype)
    out[: table.shape[0]] = table
    return out


@numba.njit(cache=True, inline="always")
def _eq(a, b):
    return abs(a - b) <= TOL * max(1.0, abs(a), abs(b))


@numba.njit(cache=True, inline="always")
def _le(a, b):
    return a <= b or _eq(a, b)


@numba.njit(cache=True, inline="always")
def _heading_gap(ha, hb):
    """Largest amount (eighths) by which the next turn after heading ``ha``
    can exceed the next turn after heading ``hb``."""
    if ha == NO_HEADING:
        return 0
    if hb == NO_HEADING:
        return 4
    return turn(ha, hb)


@numba.njit(cache=True)
def _covers(ai, af, a, bi, bf, b, use_len, use_vul, use_smooth, at_goal):
    """True if label ``a`` makes label ``b`` (same row, same column) useless:
    every completion of ``b`` is dominated by, or tolerance-equal and not
    smoother than, the same completion of ``a``.

    The next turn depends on the heading, so ``a``'s turn count is charged
    with the worst difference its heading can make (nothing at the goal)."""
    strictly_better = False
    if use_len:
        if not _le(af[a, LENGTH], bf[b, LENGTH]):
            return False
        strictly_better = strictly_better or not _eq(af[a, LENGTH], bf[b, LENGTH])
    if use_vul:
        if not _le(af[a, VUL], bf[b, VUL]):
            return False
        strictly_better = strictly_better or not _eq(af[a, VUL], bf[b, VUL])
    gap = 0 if at_goal else _heading_gap(ai[a, HEAD], bi[b, HEAD])
    smoother = ai[a, EIGHTHS] + gap <= bi[b, EIGHTHS]
    if use_smooth:
        return smoother
    # smoothness only breaks ties between tolerance-equal vectors
    return strictly_better or smoother


@numba.njit(cache=True)
def _reach(occ, p, c, corner_cutting):
    """Rows of column ``c`` reachable from row ``p`` of column ``c - 1``.

    Returns ``(top, bottom, flat)``: a diagonal step up followed by vertical
    steps up reaches rows ``top .. p - 1`` (none when ``top == p``), likewise
    ``p + 1 .. bottom`` downwards, and ``flat`` says whether the horizontal
    step to row ``p`` is possible."""
    h = occ.shape[0]
    flat = not occ[p, c]
    top = p
    if can_step(occ, p, c - 1, -1, 1, corner_cutting):
        top = p - 1
        while top > 0 and not occ[top - 1, c]:
            top -= 1
    bottom = p
    if can_step(occ, p, c - 1, 1, 1, corner_cutting):
        bottom = p + 1
        while bottom < h - 1 and not occ[bottom + 1, c]:
            bottom += 1
    return top, bottom, flat


@numba.njit(cache=True)
def _extend(li, lf, a, t, vul, ci, cf, j, cell_size):
    """Write into candidate slot ``j`` the label ``a`` (exit row ``p``)
    extended to exit row ``t`` of the next column, ``vul`` being the
    vulnerability already summed along the new cells in path order."""
    p = li[a, ROW]
    n_straight = li[a, N_STRAIGHT]
    n_diag = li[a, N_DIAG]
    if t == p:
        step = EAST
        n_straight += 1
    else:
        step = NORTH_EAST if t < p else SOUTH_EAST
        n_diag += 1
    eighths = li[a, EIGHTHS]
    if li[a, HEAD] != NO_HEADING:
        eighths += turn(li[a, HEAD], step)
    head = step
    if abs(t - p) >= 2:  # vertical run after the diagonal: one eighth turn
        n_straight += abs(t - p) - 1
        eighths += 1
        head = NORTH if t < p else SOUTH
    ci[j, ROW] = t
    ci[j, PARENT] = a
    ci[j, HEAD] = head
    ci[j, N_STRAIGHT] = n_straight
    ci[j, N_DIAG] = n_diag
    ci[j, EIGHTHS] = eighths
    cf[j, LENGTH] = (n_straight + SQRT2 * n_diag) * cell_size
    cf[j, VUL] = vul


@numba.njit(cache=True, inline="always")
def _key(ti, tf, i, primary):
    """Value of the primary (first) objective of label ``i``."""
    return np.float64(ti[i, EIGHTHS]) if primary == 2 else tf[i, primary]


@numba.njit(cache=True)
def _filter_row(li, lf, n, ci, cf, lo, hi, use_len, use_vul, use_smooth, primary, at_goal):
    """Append to the label tables (which hold ``n`` labels) the labels of one
    state: the candidates ``lo .. hi - 1`` that no other candidate covers.

    Candidates are visited in increasing order of the primary objective, so
    a new label can only cover an earlier one when their primary values tie;
    the running minima of the kept labels let most candidates be accepted or
    rejected without scanning the kept ones. Returns the new label count."""
    first = n
    key = np.empty(hi - lo)
    for j in range(lo, hi):
        key[j - lo] = _key(ci, cf, j, primary)
    big = np.inf
    min_len, min_vul, min_eighths = big, big, big
    for j in np.argsort(key, kind="mergesort") + lo:
        # a kept label can cover j only if it is not worse in every objective
        maybe_covered = n > first
        if use_len and not _le(min_len, cf[j, LENGTH]):
            maybe_covered = False
        if use_vul and not _le(min_vul, cf[j, VUL]):
            maybe_covered = False
        if use_smooth and min_eighths > ci[j, EIGHTHS]:
            maybe_covered = False
        if maybe_covered:
            covered = False
            for i in range(n - 1, first - 1, -1):
                if _covers(li, lf, i, ci, cf, j, use_len, use_vul, use_smooth, at_goal):
                    covered = True
                    break
            if covered:
                continue
        # j can cover a kept label only if their primary values tie
        if n > first and _le(_key(ci, cf, j, primary), _key(li, lf, n - 1, primary)):
            kept = first
            for i in range(first, n):
                if not _covers(ci, cf, j, li, lf, i, use_len, use_vul, use_smooth, at_goal):
                    li[kept] = li[i]
                    lf[kept] = lf[i]
                    kept += 1
            if kept < n:
                n = kept
                min_len, min_vul, min_eighths = big, big, big
                for i in range(first, n):
                    min_len = min(min_len, lf[i, LENGTH])
                    min_vul = min(min_vul, lf[i, VUL])
                    min_eighths = min(min_eighths, np.float64(li[i, EIGHTHS]))
        li[n] = ci[j]
        lf[n] = cf[j]
        min_len = min(min_len, cf[j, LENGTH])
        min_vul = min(min_vul, cf[j, VUL])
        min_eighths = min(min_eighths, np.float64(ci[j, EIGHTHS]))
        n += 1
    return n


@numba.njit(cache=True)
def _monotone_start(occ, pot, start_row, col0, cell_size):
    """Label tables of the start column of the frame: one label per exit row
    reachable by a single vertical run from the start.

    Returns ``(li, lf, off, n)``; ``off[r] .. off[r + 1]`` are the labels of
    exit row ``r`` of the current column, ``n`` the number of labels."""
    h = occ.shape[0]
    li = np.empty((max(256, h), 6), np.int32)
    lf = np.empty((max(256, h), 2))
    n = 0
    off = np.zeros(h + 1, np.int64)
    vul_to = np.full(h, np.nan)
    vul_to[start_row] = pot[start_row, col0]
    for s in (-1, 1):
        r, v = start_row, pot[start_row, col0]
        while 0 <= r + s < h and not occ[r + s, col0]:
            r += s
            v += pot[r, col0]
            vul_to[r] = v
    for r in range(h):
        off[r] = n
        if np.isnan(vul_to[r]):
            continue
        d = abs(r - start_row)
        li[n, ROW] = r
        li[n, PARENT] = -1
        li[n, HEAD] = NO_HEADING if d == 0 else (NORTH if r < start_row else SOUTH)
        li[n, N_STRAIGHT] = d
        li[n, N_DIAG] = 0
        li[n, EIGHTHS] = 0
        lf[n, LENGTH] = d * cell_size
        lf[n, VUL] = vul_to[r]
        n += 1
    off[h] = n
    return li, lf, off, n


@numba.njit(cache=True)
def _monotone_columns(
    occ,
    pot,
    goal_row,
    col0,
    n_cols,
    cell_size,
    corner_cutting,
    use_len,
    use_vul,
    use_smooth,
    primary,
    li,
    lf,
    off,
    st,
    n_steps,
    max_labels,
):
    """Advance the multi-objective DP over the columns of the frame by at
    most ``n_steps`` columns.

    ``st`` holds ``[n, k]`` (labels stored, next column of the frame) and is
    updated in place. Stops before a column whose candidates would take the
    labels held at once beyond ``max_labels``. Returns ``(li, lf, off,
    status, max_candidates)`` (status DONE after the goal column, PAUSED, or
    OVER_BUDGET; the most candidates one column held); the goal's labels are then ``off[goal_row] ..
    off[goal_row + 1]``."""
    h = occ.shape[0]
    n = st[0]
    counts = np.zeros(h + 1, np.int64)
    steps = 0
    max_cand = 0
    while st[1] < n_cols:
        if steps == n_steps:
            st[0] = n
            return li, lf, off, PAUSED, max_cand
        k = st[1]
        c = col0 + k
        at_goal = k == n_cols - 1  # the goal column: exit row = goal row

        # 2. count the candidate labels of each exit row of column c
        counts[:] = 0
        for p in range(h):
            n_labels = off[p + 1] - off[p]
            if n_labels == 0:
                continue
            top, bottom, flat = _reach(occ, p, c, corner_cutting)
            for t in range(top, bottom + 1):
                if (t != p or flat) and (not at_goal or t == goal_row):
                    counts[t + 1] += n_labels
        cand_off = np.cumsum(counts)  # candidates of row t: cand_off[t] .. cand_off[t + 1]
        max_cand = max(max_cand, cand_off[h])
        if n + cand_off[h] > max_labels:
            st[0] = n
            return li, lf, off, OVER_BUDGET, max_cand
        ci = np.empty((cand_off[h], 6), np.int32)
        cf = np.empty((cand_off[h], 2))
        fill = cand_off[:h].copy()

        # 3. extend every label of column c - 1 to every reachable exit row,
        #    summing the potential of the new cells in path order
        for p in range(h):
            if off[p + 1] == off[p]:
                continue
            top, bottom, flat = _reach(occ, p, c, corner_cutting)
            for a in range(off[p], off[p + 1]):
                if flat and (not at_goal or p == goal_row):
                    _extend(li, lf, a, p, lf[a, VUL] + pot[p, c], ci, cf, fill[p], cell_size)
                    fill[p] += 1
                for s, last in ((-1, top), (1, bottom)):
                    v = lf[a, VUL]
                    t = p
                    while t != last:
                        t += s
                        v += pot[t, c]
                        if not at_goal or t == goal_row:
                            _extend(li, lf, a, t, v, ci, cf, fill[t], cell_size)
                            fill[t] += 1

        # 4. keep the non-dominated candidates of each exit row
        li = _grow(li, n + cand_off[h])
        lf = _grow(lf, n + cand_off[h])
        new_off = np.empty(h + 1, np.int64)
        for t in range(h):
            new_off[t] = n
            if cand_off[t + 1] > cand_off[t]:
                n = _filter_row(
                    li,
                    lf,
                    n,
                    ci,
                    cf,
                    cand_off[t],
                    cand_off[t + 1],
                    use_len,
                    use_vul,
                    use_smooth,
                    primary,
                    at_goal,
                )
        new_off[h] = n
        off = new_off
        st[1] = k + 1
        steps += 1
    st[0] = n
    return li, lf, off, DONE, max_cand


def reference_front(workspace, names):
    """``(F, smoothness)`` of the old monotone DP (lexicographically sorted),
    or None when there is no feasible monotone path."""
    frame = Frame.of(workspace)
    (sr, _), (gr, _) = frame.start, frame.goal
    primary = {"length": LENGTH, "vulnerability": VUL, "smoothness": 2}[names[0]]
    occ, pot = frame.occ, np.ascontiguousarray(frame.potential, dtype=np.float64)
    cs, cc = float(workspace.cell_size), bool(workspace.corner_cutting)
    use = ("length" in names, "vulnerability" in names, "smoothness" in names)
    li, lf, off, n = _monotone_start(occ, pot, sr, frame.col0, cs)
    st = np.array([n, 1], np.int64)
    li, lf, off, status, _ = _monotone_columns(
        occ,
        pot,
        gr,
        frame.col0,
        frame.n_cols,
        cs,
        cc,
        *use,
        primary,
        li,
        lf,
        off,
        st,
        frame.n_cols + 1,
        2**62,
    )
    assert status == DONE
    lo, hi = off[gr], off[gr + 1]
    if hi == lo:
        return None
    final = np.arange(lo, hi)
    values = {
        "length": lf[final, LENGTH],
        "vulnerability": lf[final, VUL],
        "smoothness": li[final, EIGHTHS] * QUARTER_PI,
    }
    F = np.column_stack([values[name] for name in names])
    order = np.lexsort(F.T[::-1])
    return F[order], values["smoothness"][order], int(st[0])
