"""Numba kernels of :func:`gapath.planners.exact.monotone_front` (private).

The multi-objective DP over the columns of the canonical frame
(:class:`gapath.monotone.Frame`). A label is a partial path ending at an exit
row of the current column. Compared with enumerating, for every label of the
previous column, every exit row its vertical run can reach, the DP here
builds the runs row by row:

* ``up[t]``: the non-dominated partial paths that are at row ``t`` of the
  new column going up (last step north): the diagonal arrivals at ``t + 1``
  and ``up[t + 1]``, each extended by one vertical step. All of them have the
  same heading and the same future, so a label that another one covers at
  ``t`` stays covered along the rest of the run: filtering ``up[t]`` on its
  own loses nothing. ``down[t]`` likewise.
* the labels of exit row ``t``: the non-dominated labels among the
  horizontal arrival, the two diagonal arrivals, ``up[t]`` and ``down[t]``,
  with the same covering rule (and tie order) as before, so the front is the
  same.

Memory: only the current column's labels are kept in full; every label
also has a node (exit row, parent node) in an ancestry tree, and the nodes
no live label descends from are freed by a mark-and-compact pass whenever
the tree has doubled since the last one. The tree then holds the ancestry
of the current column's labels, not every label ever made.

The kernel is resumable like the free search: the state (tree, current
column, counters in ``st``) lives in arrays owned by the caller, and a call
returns after a number of columns or before exceeding the label budget.
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import FALSE, SQRT2, ZERO, can_step, turn
from gapath.planners._exact_kernels import DONE, OVER_BUDGET, PAUSED, _eq, _grow, _heading_gap, _le

# label table (int32): heading of the last step, straight and diagonal step
# counts, total turn in eighths, and LINK: the label's tree node (current
# column) or the index of the label it extends (candidates, next column)
M_HEAD, M_NS, M_ND, M_EIGHTHS, M_LINK = range(5)
M_COLS = 5
LENGTH, VUL = range(2)  # float table
# tree (int32): exit row and parent node (-1 in the start column)
T_ROW, T_PARENT = range(2)

# headings, coded as in gapath.objectives (eighths counter-clockwise from east;
# "up" is towards row 0); monotone paths only use these five
NO_HEADING, EAST, NORTH_EAST, NORTH, SOUTH, SOUTH_EAST = -1, 0, 1, 2, 6, 7

# st: counters shared with the caller
(
    ST_TREE,  # tree nodes held
    ST_K,  # next column of the frame
    ST_LIVE,  # tree nodes kept by the last compaction
    ST_MADE,  # labels made in total (all columns)
    ST_CANDIDATES,  # candidate labels filtered in total
    ST_PEAK,  # most labels held at once (tree + the column being built)
    ST_PEAK_BYTES,  # most bytes held by the DP's arrays
    ST_HELD,  # labels held when the kernel returned
    ST_COMPACTIONS,
    ST_STAIR,  # points of the goal-bound staircase
    ST_PRUNED,  # candidates dropped by the goal bound
) = range(11)
ST_N = 11


@numba.njit(cache=True, inline="always")
def _put(bi, bf, bk, m, head, ns, nd, eighths, vul, link, cell_size, primary):
    """Write candidate ``m`` and its sort key (the primary objective)."""
    bi[m, M_HEAD] = head
    bi[m, M_NS] = ns
    bi[m, M_ND] = nd
    bi[m, M_EIGHTHS] = eighths
    bi[m, M_LINK] = link
    bf[m, LENGTH] = (ns + SQRT2 * nd) * cell_size
    bf[m, VUL] = vul
    if primary == 2:
        bk[m] = np.float64(eighths)
    else:
        bk[m] = bf[m, primary]


@numba.njit(cache=True, inline="always")
def _key(ti, tf, i, primary):
    """Value of the primary (first) objective of label ``i``."""
    return np.float64(ti[i, M_EIGHTHS]) if primary == 2 else tf[i, primary]


@numba.njit(cache=True, inline="always")
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
    gap = 0 if at_goal else _heading_gap(ai[a, M_HEAD], bi[b, M_HEAD])
    smoother = ai[a, M_EIGHTHS] + gap <= bi[b, M_EIGHTHS]
    if use_smooth:
        return smoother
    # smoothness only breaks ties between tolerance-equal vectors
    return strictly_better or smoother


@numba.njit(cache=True, inline="always")
def _before(bk, bi, x, y):
    """Candidate order: primary objective, then the index of the extended
    label (the order in which the previous DP generated its candidates)."""
    return bk[x] < bk[y] or (bk[x] == bk[y] and bi[x, M_LINK] < bi[y, M_LINK])


@numba.njit(cache=True)
def _sort(bk, bi, m, idx, tmp):
    """``idx[:m]``: the candidates ``0 .. m - 1`` in :func:`_before` order.

    A natural merge sort: the candidates arrive as a few sorted runs (one per
    source), which it merges in ``log2(runs)`` passes."""
    for i in range(m):
        idx[i] = i
    if m < 2:
        return idx
    in_order = True
    for i in range(1, m):
        if _before(bk, bi, i, i - 1):
            in_order = False
            break
    if in_order:
        return idx
    src, dst = idx, tmp
    while True:
        # merge neighbouring ascending runs of src into dst
        i = 0
        n_runs = 0
        while i < m:
            j = i + 1
            while j < m and not _before(bk, bi, src[j], src[j - 1]):
                j += 1
            if j == m:  # a last run without a partner
                for q in range(i, m):
                    dst[q] = src[q]
                n_runs += 1
                break
            e = j + 1
            while e < m and not _before(bk, bi, src[e], src[e - 1]):
                e += 1
            a, b, o = i, j, i
            while a < j and b < e:
                if _before(bk, bi, src[b], src[a]):
                    dst[o] = src[b]
                    b += 1
                else:
                    dst[o] = src[a]
                    a += 1
                o += 1
            while a < j:
                dst[o] = src[a]
                a += 1
                o += 1
            while b < e:
                dst[o] = src[b]
                b += 1
                o += 1
            n_runs += 1
            i = e
        src, dst = dst, src
        if n_runs <= 1:
            return src


@numba.njit(cache=True)
def _filter(oi, of, n, bi, bf, bk, order, m, use_len, use_vul, use_smooth, primary, at_goal):
    """Append to ``oi, of`` (which hold ``n`` labels) the candidates
    ``order[:m]`` (sorted by the primary objective) that no other candidate
    covers. Returns the new count.

    A new label can only cover an earlier one when their primary values tie;
    the running minima of the kept labels let most candidates be accepted or
    rejected without scanning the kept ones."""
    first = n
    big = np.inf
    min_len, min_vul, min_eighths = big, big, big
    for q in range(m):
        j = order[q]
        # a kept label can cover j only if it is not worse in every objective
        maybe_covered = n > first
        if use_len and not _le(min_len, bf[j, LENGTH]):
            maybe_covered = False
        if use_vul and not _le(min_vul, bf[j, VUL]):
            maybe_covered = False
        if use_smooth and min_eighths > bi[j, M_EIGHTHS]:
            maybe_covered = False
        if maybe_covered:
            covered = False
            for i in range(n - 1, first - 1, -1):
                if _covers(oi, of, i, bi, bf, j, use_len, use_vul, use_smooth, at_goal):
                    covered = True
                    break
            if covered:
                continue
        # j can cover a kept label only if their primary values tie: the
        # kept labels are sorted, so only a tail of them
        if n > first and _le(bk[j], _key(oi, of, n - 1, primary)):
            tail = n - 1
            while tail > first and _le(bk[j], _key(oi, of, tail - 1, primary)):
                tail -= 1
            kept = tail
            for i in range(tail, n):
                if not _covers(bi, bf, j, oi, of, i, use_len, use_vul, use_smooth, at_goal):
                    if kept != i:
                        for x in range(M_COLS):
                            oi[kept, x] = oi[i, x]
                        of[kept, LENGTH] = of[i, LENGTH]
                        of[kept, VUL] = of[i, VUL]
                    kept += 1
            if kept < n:
                n = kept
                min_len, min_vul, min_eighths = big, big, big
                for i in range(first, n):
                    min_len = min(min_len, of[i, LENGTH])
                    min_vul = min(min_vul, of[i, VUL])
                    min_eighths = min(min_eighths, np.float64(oi[i, M_EIGHTHS]))
        for x in range(M_COLS):
            oi[n, x] = bi[j, x]
        of[n, LENGTH] = bf[j, LENGTH]
        of[n, VUL] = bf[j, VUL]
        min_len = min(min_len, bf[j, LENGTH])
        min_vul = min(min_vul, bf[j, VUL])
        min_eighths = min(min_eighths, np.float64(bi[j, M_EIGHTHS]))
        n += 1
    return n


# ---------------------------------------------------------------------------
# goal bounds: a label whose objectives plus a lower bound of any completion
# are dominated (by a clear margin) by a known monotone path cannot lead to
# the front, and is dropped when it is made
# ---------------------------------------------------------------------------
# bounds[q, k, t] for frame column k and row t: q = 4 * state + value, state
# 0 = at exit row t (next step into column k + 1), 1 = going up at row t of
# column k (may exit at t or step up), 2 = going down; value 0 = least
# remaining length, 1 = the vulnerability of that completion, 2 = least
# remaining vulnerability, 3 = the length of that completion (inf: no
# completion).
B_EXIT, B_UP, B_DOWN = np.int64(0), np.int64(4), np.int64(8)  # typed, not literal (gapath.grid.ZERO)
B_LEN, B_LEN_VUL, B_VUL, B_VUL_LEN = range(4)
#: Relative margin of the goal-bound test (much larger than the tolerance
#: and than the rounding of sums taken in another order).
PRUNE_MARGIN = 1e-6
#: Goal-bound modes: only labels with no completion (a smoothness objective),
#: length alone, vulnerability alone, both.
P_DEAD, P_LEN, P_VUL, P_BOTH = range(4)


@numba.njit(cache=True, inline="always")
def _lex_take(b, q, k, t, a1, a2, c1, c2):
    """``b[q:q+2, k, t] = (c1, c2)`` if that pair is lexicographically
    smaller than ``(a1, a2)`` (the current one)."""
    if c1 < a1 or (c1 == a1 and c2 < a2):
        b[q, k, t] = c1
        b[q + 1, k, t] = c2


@numba.njit(cache=True)
def _monotone_bounds(occ, pot, goal_row, col0, n_cols, cell_size, corner_cutting):
    """Cost-to-go bounds of the monotone paths (see ``B_*``), by one
    single-objective DP per objective backwards over the columns."""
    h = occ.shape[0]
    inf = np.inf
    b = np.full((12, n_cols, h), inf)
    d = SQRT2 * cell_size
    for k in range(n_cols - 1, -1, -1):
        c = col0 + k
        if k == n_cols - 1:
            for q in (B_LEN, B_LEN_VUL, B_VUL, B_VUL_LEN):
                b[B_EXIT + q, k, goal_row] = 0.0
        else:
            for t in range(h):
                if occ[t, c]:
                    continue
                for obj in (B_LEN, B_VUL):
                    q = B_EXIT + obj
                    if not occ[t, c + 1]:
                        r = B_EXIT
                        if obj == B_LEN:
                            x1, x2 = (
                                cell_size + b[r + B_LEN, k + 1, t],
                                pot[t, c + 1] + b[r + B_LEN_VUL, k + 1, t],
                            )
                        else:
                            x1, x2 = (
                                pot[t, c + 1] + b[r + B_VUL, k + 1, t],
                                cell_size + b[r + B_VUL_LEN, k + 1, t],
                            )
                        _lex_take(b, q, k, t, b[q, k, t], b[q + 1, k, t], x1, x2)
                    for dr in (-1, 1):
                        if can_step(occ, t, c, dr, 1, corner_cutting):
                            r = B_UP if dr == -1 else B_DOWN
                            if obj == B_LEN:
                                x1 = d + b[r + B_LEN, k + 1, t + dr]
                                x2 = pot[t + dr, c + 1] + b[r + B_LEN_VUL, k + 1, t + dr]
                            else:
                                x1 = pot[t + dr, c + 1] + b[r + B_VUL, k + 1, t + dr]
                                x2 = d + b[r + B_VUL_LEN, k + 1, t + dr]
                            _lex_take(b, q, k, t, b[q, k, t], b[q + 1, k, t], x1, x2)
        # runs inside column k: exit here, or one more vertical step
        for r, dr in ((B_UP, -1), (B_DOWN, 1)):
            t = 0 if dr == -1 else h - 1
            while 0 <= t < h:
                if not occ[t, c]:
                    for q in range(4):
                        b[r + q, k, t] = b[B_EXIT + q, k, t]
                    u = t + dr
                    if 0 <= u < h and not occ[u, c]:
                        q = r + B_LEN
                        _lex_take(
                            b,
                            q,
                            k,
                            t,
                            b[q, k, t],
                            b[q + 1, k, t],
                            cell_size + b[q, k, u],
                            pot[u, c] + b[q + 1, k, u],
                        )
                        q = r + B_VUL
                        _lex_take(
                            b,
                            q,
                            k,
                            t,
                            b[q, k, t],
                            b[q + 1, k, t],
                            pot[u, c] + b[q, k, u],
                            cell_size + b[q + 1, k, u],
                        )
                t -= dr
    return b


@numba.njit(cache=True)
def _monotone_tradeoffs(
    occ, pot, goal_row, col0, n_cols, cell_size, corner_cutting, weights, len_scale, vul_scale
):
    """Length and vulnerability of the monotone completion from each exit
    state minimising ``w * length / len_scale + (1 - w) * vulnerability /
    vul_scale``, for each ``w`` of ``weights``: ``out[2 * i]`` (length) and
    ``out[2 * i + 1]`` (vulnerability), ``(n_cols, h)`` each, inf where no
    completion exists. Their paths through the labels are points of the
    staircase of the goal bound."""
    h = occ.shape[0]
    inf = np.inf
    out = np.full((2 * weights.shape[0], n_cols, h), inf)
    d = SQRT2 * cell_size
    x = np.empty((3, h))  # exit states of column k: cost, length, vulnerability
    run = np.empty((2, 3, h))  # up / down states of column k + 1
    for i in range(weights.shape[0]):
        wl = weights[i] / len_scale
        wv = (1.0 - weights[i]) / vul_scale
        for k in range(n_cols - 1, -1, -1):
            c = col0 + k
            x[:] = inf
            if k == n_cols - 1:
                x[:, goal_row] = 0.0
            else:
                for t in range(h):
                    if occ[t, c]:
                        continue
                    if not occ[t, c + 1]:
                        ln, vu = cell_size + out[2 * i, k + 1, t], pot[t, c + 1] + out[2 * i + 1, k + 1, t]
                        cost = wl * ln + wv * vu
                        if cost < x[0, t]:
                            x[0, t], x[1, t], x[2, t] = cost, ln, vu
                    for s, dr in ((0, -1), (1, 1)):
                        if can_step(occ, t, c, dr, 1, corner_cutting):
                            ln, vu = d + run[s, 1, t + dr], pot[t + dr, c + 1] + run[s, 2, t + dr]
                            cost = wl * ln + wv * vu
                            if cost < x[0, t]:
                                x[0, t], x[1, t], x[2, t] = cost, ln, vu
            for t in range(h):
                out[2 * i, k, t] = x[1, t]
                out[2 * i + 1, k, t] = x[2, t]
            # runs inside column k (for column k - 1)
            for s, dr in ((0, -1), (1, 1)):
                t = 0 if dr == -1 else h - 1
                while 0 <= t < h:
                    run[s, 0, t], run[s, 1, t], run[s, 2, t] = x[0, t], x[1, t], x[2, t]
                    u = t + dr
                    if not occ[t, c] and 0 <= u < h and not occ[u, c]:
                        ln, vu = cell_size + run[s, 1, u], pot[u, c] + run[s, 2, u]
                        cost = wl * ln + wv * vu
                        if cost < run[s, 0, t]:
                            run[s, 0, t], run[s, 1, t], run[s, 2, t] = cost, ln, vu
                    t -= dr
    return out


@numba.njit(cache=True, inline="always")
def _margin(x):
    return PRUNE_MARGIN * max(1.0, abs(x))


@numba.njit(cache=True, inline="always")
def _last_le(s1, n, x):
    """Index of the last ``s1[:n]`` entry ``<= x`` (-1: none); ``s1`` sorted."""
    lo, hi = 0, n
    while lo < hi:
        mid = (lo + hi) >> 1
        if s1[mid] <= x:
            lo = mid + 1
        else:
            hi = mid
    return lo - 1


@numba.njit(cache=True, inline="always")
def _dominated(stair, n, f1, f2):
    """True if a point of the staircase ``stair[:, :n]`` dominates
    ``(f1, f2)`` with a clear margin in one coordinate."""
    i = _last_le(stair[0], n, f1)
    if i < 0:
        return False
    if stair[1, i] <= f2 - _margin(f2):
        return True
    # the last point clearly left of f1 (the staircase falls to the right)
    x = f1 - _margin(f1)
    while i >= 0 and stair[0, i] > x:
        i -= 1
    return i >= 0 and stair[1, i] <= f2


@numba.njit(cache=True)
def _stair_add(stair, n, p1, p2):
    """Add the point ``(p1, p2)`` to the staircase (``stair[0]`` increasing,
    ``stair[1]`` decreasing, exact comparisons) unless a point dominates or
    equals it; removes the points it dominates. Returns ``(stair, n)``."""
    lo = _last_le(stair[0], n, p1) + 1  # first entry > p1
    if lo > 0 and stair[1, lo - 1] <= p2:
        return stair, n
    # entries from start on have s1 >= p1; those with s2 >= p2 are dominated
    start = lo
    while start > 0 and stair[0, start - 1] == p1:
        start -= 1
    end = start
    while end < n and stair[1, end] >= p2:
        end += 1
    if n - (end - start) + 1 > stair.shape[1]:
        out = np.empty((2, 2 * stair.shape[1]))
        out[:, :n] = stair[:, :n]
        stair = out
    shift = 1 - (end - start)
    if shift > 0:
        for i in range(n - 1, end - 1, -1):
            stair[0, i + shift] = stair[0, i]
            stair[1, i + shift] = stair[1, i]
    elif shift < 0:
        for i in range(end, n):
            stair[0, i + shift] = stair[0, i]
            stair[1, i + shift] = stair[1, i]
    stair[0, start] = p1
    stair[1, start] = p2
    return stair, n + shift


@numba.njit(cache=True)
def _drop_hopeless(oi, of, lo, hi, bounds, r, k, t, pmode, stair, n_stair):
    """Remove from labels ``lo .. hi - 1`` (one set, kept in order) those
    :func:`_hopeless` finds; returns the new end. Checking the filtered set
    drops the same labels as checking every candidate: a label covered by
    a hopeless one is hopeless itself (its bound is not smaller)."""
    kept = lo
    for i in range(lo, hi):
        if _hopeless(bounds, r, k, t, of[i, LENGTH], of[i, VUL], pmode, stair, n_stair):
            continue
        if kept != i:
            for x in range(M_COLS):
                oi[kept, x] = oi[i, x]
            of[kept, LENGTH] = of[i, LENGTH]
            of[kept, VUL] = of[i, VUL]
        kept += 1
    return kept


@numba.njit(cache=True, inline="always")
def _hopeless(bounds, r, k, t, length, vul, pmode, stair, n_stair):
    """True if no completion of a label with ``length, vul`` in state ``r``
    (``B_EXIT``/``B_UP``/``B_DOWN``) at row ``t`` of frame column ``k`` can
    be on the front."""
    bl = bounds[r + B_LEN, k, t]
    if bl == np.inf:
        return True
    if pmode == P_DEAD:
        return False
    if pmode == P_LEN:
        return _dominated(stair, n_stair, length + bl, 0.0)
    if pmode == P_VUL:
        return _dominated(stair, n_stair, vul + bounds[r + B_VUL, k, t], 0.0)
    return _dominated(stair, n_stair, length + bl, vul + bounds[r + B_VUL, k, t])


@numba.njit(cache=True)
def _monotone_init(occ, pot, start_row, col0, cell_size):
    """The DP state after the start column: one label per exit row reachable
    by a single vertical run from the start.

    Returns ``(tree, ci, cf, off, st)``; ``off[r] .. off[r + 1]`` are the
    labels of exit row ``r`` of the current column."""
    h = occ.shape[0]
    ci = np.empty((max(64, h), M_COLS), np.int32)
    cf = np.empty((max(64, h), 2))
    tree = np.empty((max(256, 4 * h), 2), np.int32)
    off = np.zeros(h + 1, np.int64)
    vul_to = np.full(h, np.nan)
    vul_to[start_row] = pot[start_row, col0]
    for s in (-1, 1):
        r, v = start_row, pot[start_row, col0]
        while 0 <= r + s < h and not occ[r + s, col0]:
            r += s
            v += pot[r, col0]
            vul_to[r] = v
    n = 0
    for r in range(h):
        off[r] = n
        if np.isnan(vul_to[r]):
            continue
        d = abs(r - start_row)
        ci[n, M_HEAD] = NO_HEADING if d == 0 else (NORTH if r < start_row else SOUTH)
        ci[n, M_NS] = d
        ci[n, M_ND] = 0
        ci[n, M_EIGHTHS] = 0
        ci[n, M_LINK] = n
        cf[n, LENGTH] = d * cell_size
        cf[n, VUL] = vul_to[r]
        tree[n, T_ROW] = r
        tree[n, T_PARENT] = -1
        n += 1
    off[h] = n
    st = np.zeros(ST_N, np.int64)
    st[ST_TREE] = n
    st[ST_K] = 1
    st[ST_LIVE] = n
    st[ST_MADE] = n
    st[ST_PEAK] = n
    st[ST_HELD] = n
    return tree, ci, cf, off, st


@numba.njit(cache=True)
def _compact(tree, n_tree, ci, n_cur):
    """Free the tree nodes no current label descends from; renumber the
    rest (parents keep smaller numbers than their children) and the current
    labels' links. Returns the number of nodes kept."""
    live = np.zeros(n_tree, np.bool_)
    for j in range(n_cur):
        x = ci[j, M_LINK]
        while x >= 0 and not live[x]:
            live[x] = True
            x = tree[x, T_PARENT]
    new = np.empty(n_tree, np.int32)
    kept = 0
    for x in range(n_tree):
        if live[x]:
            new[x] = kept
            p = tree[x, T_PARENT]
            tree[kept, T_ROW] = tree[x, T_ROW]
            tree[kept, T_PARENT] = new[p] if p >= 0 else -1
            kept += 1
    for j in range(n_cur):
        ci[j, M_LINK] = new[ci[j, M_LINK]]
    return kept


@numba.njit(cache=True)
def _room(bi, bf, bk, idx, tmp, m):
    """Candidate buffers with room for ``m`` candidates."""
    if m > bi.shape[0]:
        size = max(m, 2 * bi.shape[0])
        bi = np.empty((size, M_COLS), np.int32)
        bf = np.empty((size, 2))
        bk = np.empty(size)
        idx = np.empty(size, np.int64)
        tmp = np.empty(size, np.int64)
    return bi, bf, bk, idx, tmp


@numba.njit(cache=True)
def _monotone_steps(
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
    tree,
    ci,
    cf,
    off,
    st,
    n_steps,
    max_labels,
    bounds,
    pmode,
    stair,
    comps,
):
    """Advance the DP by at most ``n_steps`` columns.

    ``st`` (see ``ST_*``) is updated in place. Stops before committing a
    column whose labels, run sets and tree would exceed ``max_labels``
    labels held at once. Candidates that cannot lead to the front (see
    :func:`_hopeless`; ``bounds`` from :func:`_monotone_bounds`, ``pmode``
    a ``P_*`` mode, ``stair`` the known monotone paths' staircase, to which
    the paths through each label along the completions of ``bounds`` and
    of ``comps`` (from :func:`_monotone_tradeoffs`) are added) are
    dropped when made. Returns ``(tree, ci, cf, off, stair, status)`` (status
    DONE after the goal column, PAUSED, or OVER_BUDGET); the goal's labels
    are then ``off[goal_row] .. off[goal_row + 1]``, their ancestry in
    ``tree``."""
    h = occ.shape[0]
    cap = max(64, 2 * off[h])
    ni = np.empty((cap, M_COLS), np.int32)  # the column being built
    nf = np.empty((cap, 2))
    noff = np.empty(h + 1, np.int64)
    ui = np.empty((cap, M_COLS), np.int32)  # up[t] of every row
    uf = np.empty((cap, 2))
    ulo = np.zeros(h, np.int64)
    uhi = np.zeros(h, np.int64)
    di = np.empty((2, max(64, h), M_COLS), np.int32)  # down[t - 1], down[t]
    df = np.empty((2, max(64, h), 2))
    dn = np.zeros(2, np.int64)
    bi = np.empty((64, M_COLS), np.int32)  # candidates of one set
    bf = np.empty((64, 2))
    bk = np.empty(64)
    idx = np.empty(64, np.int64)
    tmp = np.empty(64, np.int64)
    steps = 0
    while st[ST_K] < n_cols:
        if steps == n_steps:
            return tree, ci, cf, off, stair, PAUSED
        k = st[ST_K]
        c = col0 + k
        at_goal = k == n_cols - 1  # the goal column: exit row = goal row
        made = 0
        pruned = 0
        # the paths through the current labels along their best completions
        n_stair = st[ST_STAIR]
        if pmode != P_DEAD and (k < 16 or k % 8 == 1):
            for t in range(h):
                x1 = bounds[B_EXIT + B_LEN, k - 1, t]
                if off[t + 1] == off[t] or x1 == np.inf:
                    continue
                x2 = bounds[B_EXIT + B_LEN_VUL, k - 1, t]
                y1 = bounds[B_EXIT + B_VUL_LEN, k - 1, t]
                y2 = bounds[B_EXIT + B_VUL, k - 1, t]
                for a in range(off[t], off[t + 1]):
                    if pmode == P_BOTH:
                        stair, n_stair = _stair_add(stair, n_stair, cf[a, LENGTH] + x1, cf[a, VUL] + x2)
                        stair, n_stair = _stair_add(stair, n_stair, cf[a, LENGTH] + y1, cf[a, VUL] + y2)
                        for q in range(0, comps.shape[0], 2):
                            z1 = comps[q, k - 1, t]
                            if z1 != np.inf:
                                stair, n_stair = _stair_add(
                                    stair, n_stair, cf[a, LENGTH] + z1, cf[a, VUL] + comps[q + 1, k - 1, t]
                                )
                    elif pmode == P_LEN:
                        stair, n_stair = _stair_add(stair, n_stair, cf[a, LENGTH] + x1, 0.0)
                    else:
                        stair, n_stair = _stair_add(stair, n_stair, cf[a, VUL] + y2, 0.0)
            st[ST_STAIR] = n_stair

        # 1. up[t], t from the bottom: the diagonal arrivals at t + 1 (from
        #    row t + 2) and up[t + 1], one vertical step further
        nu = ZERO
        for t in range(h - 1, -1, -1):
            ulo[t] = nu
            uhi[t] = nu
            if t == h - 1 or occ[t, c] or occ[t + 1, c]:
                continue
            m = ZERO
            p = t + 2
            diag = p < h and off[p + 1] > off[p] and can_step(occ, p, c - 1, -1, 1, corner_cutting)
            need = (off[p + 1] - off[p] if diag else 0) + uhi[t + 1] - ulo[t + 1]
            if need == 0:
                continue
            bi, bf, bk, idx, tmp = _room(bi, bf, bk, idx, tmp, need)
            if diag:
                for a in range(off[p], off[p + 1]):
                    e = ci[a, M_EIGHTHS] + 1
                    if ci[a, M_HEAD] != NO_HEADING:
                        e += turn(ci[a, M_HEAD], NORTH_EAST)
                    v = cf[a, VUL] + pot[t + 1, c]
                    v += pot[t, c]
                    _put(bi, bf, bk, m, NORTH, ci[a, M_NS] + 1, ci[a, M_ND] + 1, e, v, a, cell_size, primary)
                    m += 1
            for x in range(ulo[t + 1], uhi[t + 1]):
                _put(
                    bi,
                    bf,
                    bk,
                    m,
                    NORTH,
                    ui[x, M_NS] + 1,
                    ui[x, M_ND],
                    ui[x, M_EIGHTHS],
                    uf[x, VUL] + pot[t, c],
                    ui[x, M_LINK],
                    cell_size,
                    primary,
                )
                m += 1
            made += m
            order = _sort(bk, bi, m, idx, tmp)
            ui = _grow(ui, nu + m)
            uf = _grow(uf, nu + m)
            nu0 = nu
            nu = _filter(ui, uf, nu, bi, bf, bk, order, m, use_len, use_vul, use_smooth, primary, FALSE)
            kept = _drop_hopeless(ui, uf, nu0, nu, bounds, B_UP, k, t, pmode, stair, n_stair)
            pruned += nu - kept
            nu = kept
            uhi[t] = nu
            if st[ST_TREE] + nu > max_labels:
                st[ST_HELD] = st[ST_TREE]
                return tree, ci, cf, off, stair, OVER_BUDGET
            st[ST_PEAK] = max(st[ST_PEAK], st[ST_TREE] + nu)

        # 2. down[t] from the top (kept for one row), and the labels of
        #    every exit row t
        nn = ZERO
        dn[:] = 0
        last = goal_row if at_goal else h - 1
        for t in range(last + 1):
            noff[t] = nn
            cur = t & 1
            prev = 1 - cur
            # down[t]: the diagonal arrivals at t - 1 (from row t - 2) and
            # down[t - 1], one vertical step further
            dn[cur] = 0
            if t >= 1 and not occ[t, c] and not occ[t - 1, c]:
                m = ZERO
                p = t - 2
                diag = p >= 0 and off[p + 1] > off[p] and can_step(occ, p, c - 1, 1, 1, corner_cutting)
                need = (off[p + 1] - off[p] if diag else 0) + dn[prev]
                if need > 0:
                    bi, bf, bk, idx, tmp = _room(bi, bf, bk, idx, tmp, need)
                    if diag:
                        for a in range(off[p], off[p + 1]):
                            e = ci[a, M_EIGHTHS] + 1
                            if ci[a, M_HEAD] != NO_HEADING:
                                e += turn(ci[a, M_HEAD], SOUTH_EAST)
                            v = cf[a, VUL] + pot[t - 1, c]
                            v += pot[t, c]
                            _put(
                                bi,
                                bf,
                                bk,
                                m,
                                SOUTH,
                                ci[a, M_NS] + 1,
                                ci[a, M_ND] + 1,
                                e,
                                v,
                                a,
                                cell_size,
                                primary,
                            )
                            m += 1
                    for x in range(dn[prev]):
                        _put(
                            bi,
                            bf,
                            bk,
                            m,
                            SOUTH,
                            di[prev, x, M_NS] + 1,
                            di[prev, x, M_ND],
                            di[prev, x, M_EIGHTHS],
                            df[prev, x, VUL] + pot[t, c],
                            di[prev, x, M_LINK],
                            cell_size,
                            primary,
                        )
                        m += 1
                    made += m
                    order = _sort(bk, bi, m, idx, tmp)
                    if m > di.shape[1]:
                        size = max(m, 2 * di.shape[1])
                        d2i = np.empty((2, size, M_COLS), np.int32)
                        d2f = np.empty((2, size, 2))
                        d2i[prev, : dn[prev]] = di[prev, : dn[prev]]
                        d2f[prev, : dn[prev]] = df[prev, : dn[prev]]
                        di, df = d2i, d2f
                    dn[cur] = _filter(
                        di[cur],
                        df[cur],
                        ZERO,
                        bi,
                        bf,
                        bk,
                        order,
                        m,
                        use_len,
                        use_vul,
                        use_smooth,
                        primary,
                        FALSE,
                    )
                    kept = _drop_hopeless(
                        di[cur], df[cur], ZERO, dn[cur], bounds, B_DOWN, k, t, pmode, stair, n_stair
                    )
                    pruned += dn[cur] - kept
                    dn[cur] = kept
            if occ[t, c] or (at_goal and t != goal_row):
                continue
            # the labels of exit row t: horizontal arrival, diagonal arrivals
            # from t + 1 and t - 1, up[t], down[t]
            flat = off[t + 1] - off[t]
            ne = t + 1 < h and off[t + 2] > off[t + 1] and can_step(occ, t + 1, c - 1, -1, 1, corner_cutting)
            se = t >= 1 and off[t] > off[t - 1] and can_step(occ, t - 1, c - 1, 1, 1, corner_cutting)
            need = flat + (off[t + 2] - off[t + 1] if ne else 0) + (off[t] - off[t - 1] if se else 0)
            need += uhi[t] - ulo[t] + dn[cur]
            if need == 0:
                continue
            bi, bf, bk, idx, tmp = _room(bi, bf, bk, idx, tmp, need)
            m = ZERO
            if se:
                for a in range(off[t - 1], off[t]):
                    e = ci[a, M_EIGHTHS]
                    if ci[a, M_HEAD] != NO_HEADING:
                        e += turn(ci[a, M_HEAD], SOUTH_EAST)
                    _put(
                        bi,
                        bf,
                        bk,
                        m,
                        SOUTH_EAST,
                        ci[a, M_NS],
                        ci[a, M_ND] + 1,
                        e,
                        cf[a, VUL] + pot[t, c],
                        a,
                        cell_size,
                        primary,
                    )
                    m += 1
            for x in range(dn[cur]):
                for q in range(M_COLS):
                    bi[m, q] = di[cur, x, q]
                bf[m, LENGTH] = df[cur, x, LENGTH]
                bf[m, VUL] = df[cur, x, VUL]
                bk[m] = _key(bi, bf, m, primary)
                m += 1
            for a in range(off[t], off[t + 1]):
                e = ci[a, M_EIGHTHS]
                if ci[a, M_HEAD] != NO_HEADING:
                    e += turn(ci[a, M_HEAD], EAST)
                _put(
                    bi,
                    bf,
                    bk,
                    m,
                    EAST,
                    ci[a, M_NS] + 1,
                    ci[a, M_ND],
                    e,
                    cf[a, VUL] + pot[t, c],
                    a,
                    cell_size,
                    primary,
                )
                m += 1
            if ne:
                for a in range(off[t + 1], off[t + 2]):
                    e = ci[a, M_EIGHTHS]
                    if ci[a, M_HEAD] != NO_HEADING:
                        e += turn(ci[a, M_HEAD], NORTH_EAST)
                    _put(
                        bi,
                        bf,
                        bk,
                        m,
                        NORTH_EAST,
                        ci[a, M_NS],
                        ci[a, M_ND] + 1,
                        e,
                        cf[a, VUL] + pot[t, c],
                        a,
                        cell_size,
                        primary,
                    )
                    m += 1
            for x in range(ulo[t], uhi[t]):
                for q in range(M_COLS):
                    bi[m, q] = ui[x, q]
                bf[m, LENGTH] = uf[x, LENGTH]
                bf[m, VUL] = uf[x, VUL]
                bk[m] = _key(bi, bf, m, primary)
                m += 1
            made += m
            order = _sort(bk, bi, m, idx, tmp)
            ni = _grow(ni, nn + m)
            nf = _grow(nf, nn + m)
            nn0 = nn
            nn = _filter(ni, nf, nn, bi, bf, bk, order, m, use_len, use_vul, use_smooth, primary, at_goal)
            kept = _drop_hopeless(ni, nf, nn0, nn, bounds, B_EXIT, k, t, pmode, stair, n_stair)
            pruned += nn - kept
            nn = kept
            held = st[ST_TREE] + nn + nu + dn[0] + dn[1]
            if held > max_labels:
                st[ST_HELD] = st[ST_TREE]
                return tree, ci, cf, off, stair, OVER_BUDGET
            if held > st[ST_PEAK]:
                st[ST_PEAK] = held
        for t in range(last + 1, h + 1):
            noff[t] = nn

        # 3. commit: a tree node per new label, the new column becomes current
        n_tree = st[ST_TREE]
        tree = _grow(tree, n_tree + nn)
        for t in range(h):
            for j in range(noff[t], noff[t + 1]):
                tree[n_tree, T_ROW] = t
                tree[n_tree, T_PARENT] = ci[ni[j, M_LINK], M_LINK]
                ni[j, M_LINK] = n_tree
                n_tree += 1
        nbytes = (
            tree.shape[0] * 8
            + (ci.shape[0] + ni.shape[0] + ui.shape[0] + bi.shape[0] + 2 * di.shape[1]) * (4 * M_COLS + 16)
            + bi.shape[0] * 24
        )
        st[ST_PEAK_BYTES] = max(st[ST_PEAK_BYTES], nbytes)
        ci, ni = ni, ci
        cf, nf = nf, cf
        off, noff = noff, off
        st[ST_MADE] += nn
        st[ST_CANDIDATES] += made
        st[ST_PRUNED] += pruned
        if n_tree >= 2 * st[ST_LIVE] + 4 * h or at_goal:
            n_tree = _compact(tree, n_tree, ci, nn)
            st[ST_LIVE] = n_tree
            st[ST_COMPACTIONS] += 1
        st[ST_TREE] = n_tree
        st[ST_HELD] = n_tree
        st[ST_K] = k + 1
        steps += 1
    return tree, ci, cf, off, stair, DONE
