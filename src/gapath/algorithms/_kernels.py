"""numba kernels of :class:`gapath.algorithms.FastNSGA2`: tournament,
duplicate paths, non-dominated ranks, crowding distance and the survival
ordering. Each computes exactly what the pymoo, moocore or gapath code it
replaces computes (see the docstrings); ``tests/test_fast_nsga2.py``
compares them."""

from __future__ import annotations

import numba
import numpy as np

__all__ = [
    "accept_new_rows",
    "binary_tournament",
    "crowding_by_front",
    "lexicographic_order",
    "order_survivors",
    "path_table",
    "pareto_rank_2d",
    "profile_keys",
    "repeated_rows",
    "row_hashes",
    "stable_argsort",
    "take_rows",
    "take_values",
]


@numba.njit(cache=True)
def binary_tournament(P, cv, rank, smooth, crowding, use_smooth, coin):
    """Winners of the tournaments ``P`` (n, 2):
    :func:`gapath.operators.compare_rank_smoothness_crowding` on arrays.

    Smaller ``cv`` wins, then smaller ``rank``, then (``use_smooth``)
    smaller ``smooth``, then larger ``crowding``; a remaining tie goes to
    ``P[t, 0]`` when ``coin[t] < 0.5``, else to ``P[t, 1]``.
    """
    n = P.shape[0]
    out = np.empty(n, np.int64)
    for t in range(n):
        a, b = P[t, 0], P[t, 1]
        if cv[a] < cv[b]:
            w = a
        elif cv[b] < cv[a]:
            w = b
        elif rank[a] < rank[b]:
            w = a
        elif rank[b] < rank[a]:
            w = b
        elif use_smooth and smooth[a] < smooth[b]:
            w = a
        elif use_smooth and smooth[b] < smooth[a]:
            w = b
        elif crowding[a] > crowding[b]:
            w = a
        elif crowding[b] > crowding[a]:
            w = b
        else:
            w = a if coin[t] < 0.5 else b
        out[t] = w
    return out


@numba.njit(cache=True)
def _hash_weights(m):
    w = np.empty(m, np.int64)
    x = np.int64(0x2545F4914F6CDD1D)
    for j in range(m):  # xorshift64: fixed odd 64-bit weights
        x ^= x << 13
        x ^= (x >> 7) & np.int64(0x01FFFFFFFFFFFFFF)
        x ^= x << 17
        w[j] = x | 1
    return w


@numba.njit(cache=True)
def row_hashes(K):
    """64-bit hash of every row of the int64 matrix ``K``: a weighted sum
    of the values with fixed random odd weights (wrapping), then mixed.
    Independent products, so it vectorises; equal rows hash equally and
    unequal rows rarely do (every use confirms matches value by value)."""
    n, m = K.shape
    w = _hash_weights(m)
    h = np.empty(n, np.int64)
    for i in range(n):
        x = np.int64(0)
        for j in range(m):
            x += (K[i, j] + 1) * w[j]
        x ^= (x >> 31) & np.int64(0x1FFFFFFFF)
        x *= np.int64(-7046029254386353131)
        h[i] = x
    return h


@numba.njit(cache=True)
def profile_keys(entries, exits):
    """Path keys ``[entries | exits]`` (n, 2 n_cols) int64 and their
    :func:`row_hashes`, in one pass."""
    n, c = entries.shape
    K = np.empty((n, 2 * c), np.int64)
    for i in range(n):
        for j in range(c):
            K[i, j] = entries[i, j]
            K[i, c + j] = exits[i, j]
    return K, row_hashes(K)


@numba.njit(cache=True, inline="always")
def _slot(h, mask):
    return (h ^ (h >> 29)) & mask


@numba.njit(cache=True)
def path_table(h, capacity):
    """An open-addressing hash table of the hashes ``h``: ``(table, mask)``,
    ``table`` of a power-of-two size at least twice ``capacity`` (the rows
    it will hold), each slot -1 (empty) or a row index; rows ``0 ..
    len(h) - 1`` are inserted (linear probing)."""
    size = 16
    while size < 2 * capacity:
        size *= 2
    table = np.full(size, -1, np.int64)
    mask = np.int64(size - 1)
    for i in range(len(h)):
        s = _slot(h[i], mask)
        while table[s] != -1:
            s = (s + 1) & mask
        table[s] = i
    return table, mask


@numba.njit(cache=True)
def accept_new_rows(K, h, pop_K, pop_h, table, mask, off_K, off_h, n_off, n_max, check):
    """Indices of the first ``n_max`` rows of ``K`` that are new: not in the
    population ``pop_K`` (hashes ``pop_h``), not among the ``n_off``
    offspring of ``off_K`` accepted before, and not repeating an earlier
    row of ``K`` (without ``check``: the first ``n_max`` rows).

    ``table``/``mask`` (see :func:`path_table`) hold the population's rows
    as ``0 .. len(pop_K) - 1`` and the accepted offspring's as
    ``len(pop_K) + j``; matches by hash are confirmed value by value. The
    accepted rows and hashes are appended to ``off_K``/``off_h`` and to
    the table, in place. O(n) expected."""
    n = K.shape[0]
    n_pop = pop_K.shape[0]
    out = np.empty(min(n, n_max), np.int64)
    m = 0
    for i in range(n):
        if m == n_max:
            break
        if check:
            s = _slot(h[i], mask)
            dup = False
            while table[s] != -1:
                j = table[s]
                if j < n_pop:
                    dup = pop_h[j] == h[i] and _same_row(K, i, pop_K, j)
                else:
                    dup = off_h[j - n_pop] == h[i] and _same_row(K, i, off_K, j - n_pop)
                if dup:
                    break
                s = (s + 1) & mask
            if dup:
                continue
            table[s] = n_pop + n_off + m
        out[m] = i
        off_K[n_off + m] = K[i]
        off_h[n_off + m] = h[i]
        m += 1
    return out[:m]


@numba.njit(cache=True, inline="always")
def _same_row(A, i, B, j):
    for c in range(A.shape[1]):
        if A[i, c] != B[j, c]:
            return False
    return True


@numba.njit(cache=True)
def repeated_rows(h, K, h_old, K_old, old_order):
    """``dup[i]``: row ``i`` of ``K`` equals a row of ``K_old`` or an
    earlier row of ``K``.

    ``h``, ``h_old`` are the rows' :func:`row_hashes`; ``old_order`` sorts
    ``h_old``. Rows are matched by hash (binary search, then a sort of the
    new hashes) and confirmed value by value, so hash collisions do not
    matter. O((n + k) log k) for n new and k old rows.
    """
    n = K.shape[0]
    dup = np.zeros(n, np.bool_)
    hs = h_old[old_order]
    for i in range(n):
        p = np.searchsorted(hs, h[i])
        while p < len(hs) and hs[p] == h[i]:
            if _same_row(K, i, K_old, old_order[p]):
                dup[i] = True
                break
            p += 1
    order = np.argsort(h, kind="mergesort")  # stable: equal hashes by index
    g = 0
    while g < n:
        e = g + 1
        while e < n and h[order[e]] == h[order[g]]:
            e += 1
        for a in range(g + 1, e):
            if dup[order[a]]:
                continue
            for b in range(g, a):
                if _same_row(K, order[a], K, order[b]):
                    dup[order[a]] = True
                    break
        g = e
    return dup


@numba.njit(cache=True, inline="always")
def _lt(a, b):
    """NumPy's sort order for floats: NaN after everything."""
    return a < b or (b != b and a == a)


@numba.njit(cache=True)
def stable_argsort(vals):
    """``np.argsort(vals, kind="mergesort")``: the stable order (unique, so
    any stable sort gives it); insertion sort below 32 values, where the
    fronts of a population mostly are, NumPy's mergesort above."""
    c = len(vals)
    if c > 32:
        return np.argsort(vals, kind="mergesort")
    order = np.empty(c, np.int64)
    for a in range(c):
        v = vals[a]
        b = a - 1
        while b >= 0 and _lt(v, vals[order[b]]):
            order[b + 1] = order[b]
            b -= 1
        order[b + 1] = a
    return order


@numba.njit(cache=True)
def crowding_by_front(F, front, n_fronts):
    """pymoo's ``calc_crowding_distance`` of every front, in one pass.

    ``front[i]`` is the front of row ``i`` of ``F``; inside a front the rows
    are taken in their order in ``F`` (as ``np.where`` lists them), so ties
    are broken exactly as pymoo breaks them: a stable sort per objective,
    infinite distance at both ends, no contribution from an objective on
    which the front is flat (pymoo's NaN set to 0), the sum over objectives
    divided by their number.
    """
    n, m = F.shape
    cd = np.zeros(n)
    order = np.argsort(front, kind="mergesort")
    counts = np.zeros(n_fronts, np.int64)
    for i in range(n):
        counts[front[i]] += 1
    start = 0
    for k in range(n_fronts):
        c = counts[k]
        members = order[start : start + c]
        start += c
        acc = np.zeros((c, m))
        vals = np.empty(c)
        for j in range(m):
            for p in range(c):
                vals[p] = F[members[p], j]
            srt = stable_argsort(vals)
            norm = vals[srt[c - 1]] - vals[srt[0]]
            if norm == 0.0 or np.isnan(norm):
                continue
            for p in range(c):
                last = vals[srt[p]] - vals[srt[p - 1]] if p > 0 else np.inf
                nxt = vals[srt[p + 1]] - vals[srt[p]] if p < c - 1 else np.inf
                a = last / norm
                b = nxt / norm
                if np.isnan(a):
                    a = 0.0
                if np.isnan(b):
                    b = 0.0
                acc[srt[p], j] = a + b
        for p in range(c):
            s = 0.0
            for j in range(m):
                s += acc[p, j]
            cd[members[p]] = s / m
    return cd


@numba.njit(cache=True)
def lexicographic_order(F, order):
    """``order`` (sorting ``F[:, 0]``, any tie order) made lexicographic in
    place: the rows of each run of equal ``F[:, 0]`` sorted by ``F[:, 1]``."""
    n = len(order)
    s = 0
    while s < n:
        f = F[order[s], 0]
        e = s + 1
        while e < n and F[order[e], 0] == f:
            e += 1
        if e - s > 1:
            run = order[s:e].copy()
            vals = np.empty(e - s)
            for p in range(e - s):
                vals[p] = F[run[p], 1]
            o = stable_argsort(vals)
            for p in range(e - s):
                order[s + p] = run[o[p]]
        s = e
    return order


@numba.njit(cache=True)
def pareto_rank_2d(F, order):
    """Non-dominated rank of every row of ``F`` (n, 2), minimising both
    columns; the same ranks as moocore's ``pareto_rank`` (equal rows share
    a rank, as neither dominates the other). ``order`` sorts ``F[:, 0]``
    (ties in any order: e.g. ``np.argsort(F[:, 0])``); it is reordered.

    Rows are swept in lexicographic order; every dominator of a row comes
    before it, and the fronts that hold a dominator are a prefix of the
    fronts, so a binary search over the fronts' smallest second objective
    places each row. The ranks do not depend on the order of equal rows.
    O(n log n).
    """
    n = F.shape[0]
    order = lexicographic_order(F, order)
    rank = np.empty(n, np.int64)
    min_f2 = np.empty(n)  # per front: smallest f2, and the f1 of that point
    f1_at = np.empty(n)
    n_fronts = 0
    for t in range(n):
        i = order[t]
        f1, f2 = F[i, 0], F[i, 1]
        lo, hi = 0, n_fronts  # first front without a dominator of i
        while lo < hi:
            mid = (lo + hi) // 2
            dominated = (min_f2[mid] < f2) | ((min_f2[mid] == f2) & (f1_at[mid] < f1))
            lo = mid + 1 if dominated else lo
            hi = hi if dominated else mid
        rank[i] = lo
        new_front = lo == n_fronts
        if new_front or f2 < min_f2[lo]:
            min_f2[lo] = f2
            f1_at[lo] = f1
        n_fronts += np.int64(new_front)
    return rank


@numba.njit(cache=True)
def order_survivors(F, smooth, cv, feasible, ranks, n_survive):
    """The survival ordering of :func:`gapath.operators.survival_order`
    given the Pareto ranks of the ``feasible`` rows: feasible rows by rank,
    inside a rank by smaller ``smooth``, larger crowding distance, smaller
    index; then infeasible rows by smaller ``cv`` (stable). Only the fronts
    needed for ``n_survive`` are crowded.

    Returns ``(order, rank, crowding)``, each of length ``n_survive``.
    """
    n_feas = len(feasible)
    n_total = n_feas
    for i in range(len(cv)):
        if cv[i] > 0:
            n_total += 1
    n_survive = min(n_survive, n_total)
    order = np.empty(n_survive, np.int64)
    rank = np.empty(n_survive, np.int64)
    crowd = np.zeros(n_survive)
    n_fronts = 0
    m = 0
    if n_feas:
        n_all = ranks.max() + 1
        counts = np.zeros(n_all, np.int64)
        for i in range(n_feas):
            counts[ranks[i]] += 1
        covered = 0
        while n_fronts < n_all and covered < n_survive:
            covered += counts[n_fronts]
            n_fronts += 1
        keep = np.flatnonzero(ranks < n_fronts)
        idx = feasible[keep]
        r = ranks[keep]
        cd = crowding_by_front(np.ascontiguousarray(F[idx]), r, n_fronts)
        by_front = np.argsort(r, kind="mergesort")  # index order inside a front
        start = 0
        for k in range(n_fronts):
            c = counts[k]
            members = by_front[start : start + c]
            start += c
            o = stable_argsort(-cd[members])
            members = members[o]
            o = stable_argsort(smooth[idx[members]])
            members = members[o]
            for p in range(c):
                if m == n_survive:
                    break
                order[m] = idx[members[p]]
                rank[m] = k
                crowd[m] = cd[members[p]]
                m += 1
    if m < n_survive:
        infeasible = np.flatnonzero(cv > 0)
        o = np.argsort(cv[infeasible], kind="mergesort")
        for p in range(len(o)):
            if m == n_survive:
                break
            order[m] = infeasible[o[p]]
            rank[m] = n_fronts + p
            m += 1
    return order, rank, crowd


@numba.njit(cache=True)
def take_rows(A, B, idx):
    """``np.concatenate([A, B])[idx]`` for 2-D ``A``, ``B`` of one dtype
    and width, without building the concatenation."""
    n_a, w = A.shape
    out = np.empty((len(idx), w), A.dtype)
    for p in range(len(idx)):
        i = idx[p]
        if i < n_a:
            for j in range(w):
                out[p, j] = A[i, j]
        else:
            for j in range(w):
                out[p, j] = B[i - n_a, j]
    return out


@numba.njit(cache=True)
def take_values(a, b, idx):
    """``np.concatenate([a, b])[idx]`` for 1-D ``a``, ``b`` of one dtype."""
    n_a = len(a)
    out = np.empty(len(idx), a.dtype)
    for p in range(len(idx)):
        i = idx[p]
        out[p] = a[i] if i < n_a else b[i - n_a]
    return out
