"""Numba kernels of the k-objective exact search (private; driver in
:mod:`gapath.planners._multi`, public entry :func:`gapath.planners.exact.free_front`).

A NAMOA*-dr / LTMOA*-style label-setting search over any number of additive
objectives: labels leave a binary heap in lexicographic order of their
f-vectors (all k components, then the label's sequence number); every state
keeps the set of its expanded labels that no later expanded label made
redundant, and the goal keeps the set of solutions. A label is tested
against both sets when it is generated and again when it is popped (the sets
grew meanwhile). Only open labels and solutions hold label rows: an expanded
label leaves its row for an entry of a parent table (:func:`_k_run`). The
search is resumable like :func:`gapath.planners._exact_kernels._free_run`:
its whole state lives in arrays owned by the caller, a call returns after a
number of pops, when an array is full (the wrapper grows it) or when the
label budget is reached.

Objective kinds (internal order: the primary objective first)
    ``K_LEN``: the length, from integer step counts; ``K_TURN``: the total
    turn in eighths; ``K_CELL``: a cell layer summed over the path's cells in
    path order, start included (the vulnerability is the potential layer);
    ``K_SOLAR``: a per-step cost ``table[k, d]`` of step ``k`` in direction
    ``d`` summed over the steps.

States
    A state is a cell, or with ``timed`` (a step cost that depends on the
    step index) a (step count, cell) pair, index ``steps * n_cells + cell``:
    two labels compare only when their future step costs are the same.
    Row ``s`` of ``sidx`` locates state ``s``'s set in the pool (see "per-state
    sets" below), the goal's set last. The
    turn objective does not split states: a label with heading ``ha`` covers
    one with heading ``hb`` only after its turns are charged with the most
    the next turn can differ by (``_gap``).
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import DC, DR, FALSE, ONE, SQRT2, TRUE, ZERO, turn
from gapath.planners._exact_kernels import CELL as _TRACE_CELL
from gapath.planners._exact_kernels import F_PARENT as _TRACE_PARENT
from gapath.planners._exact_kernels import _grow, _grow1

# _k_run calls _grow and _grow1: numba's on-disk cache of this file is keyed on this
# file alone, so a change of their signatures comes with a change here

#: Relative tolerance of SPEC "Duplicates and ties".
TOL = 1e-9

K_LEN, K_TURN, K_CELL, K_SOLAR = range(4)
#: Status codes (NEED_ROOM: internal to _k_run; STEP_LIMIT: a label would
#: take more steps than the solar table holds).
DONE, PAUSED, OVER_BUDGET, NEED_ROOM, STEP_LIMIT = range(5)

# int table of a label: CELL, HEAD (heading of the last step, -1 at the start),
# NS/ND (straight/diagonal steps), TURNS (eighths); PARENT: the parent's entry of
# the parent table ``pc`` (cell, parent entry), where a label goes when it is
# expanded (its row is then recycled); SEQ: the label's sequence number, which
# breaks exact ties of the open list (:func:`_less`)
CELL, HEAD, PARENT, NS, ND, TURNS, SEQ = range(7)
N_INT = 7
# the solutions' paths are traced by _exact_kernels._trace_parents, which reads
# the same two columns
assert (CELL, PARENT) == (_TRACE_CELL, _TRACE_PARENT)
# scalars of the search state (S_SEQ: the next new sequence number)
S_N, S_SIZE, S_SOLS, S_EXPANDED, S_GENERATED, S_GOAL_FIRST, S_SEQ, S_N_FREE, S_POPS, S_SPAN = range(10)
# pool rows in use, members tested by the state and the goal checks
S_PTOP, S_STATE_TESTS, S_GOAL_TESTS = range(10, 13)
# the tree directory: head of its free list, rows in use
S_TFREE, S_TTOP = range(13, 15)
# tree nodes visited by the state and goal checks and by the insertions' drops,
# members written by tree builds
S_STATE_NODES, S_GOAL_NODES, S_DROP_NODES, S_BUILT = range(15, 19)
# entries of the parent table (the expanded labels), free sequence numbers
S_PC, S_N_FREE_SEQ = range(19, 21)
N_ST = 21


@numba.njit(cache=True, inline="always")
def _eq(a, b):
    return abs(a - b) <= TOL * max(1.0, abs(a), abs(b))


@numba.njit(cache=True, inline="always")
def _le(a, b):
    return a <= b or _eq(a, b)


@numba.njit(cache=True, inline="always")
def _gap(ha, hb):
    """Most (eighths) by which the next turn after heading ``ha`` can exceed
    the next turn after heading ``hb`` (``-1``: no heading yet)."""
    if ha < 0:
        return 0
    if hb < 0:
        return 4
    return turn(ha, hb)


@numba.njit(cache=True, inline="always")
def _g(li, lg, x, kind, col, cell_size):
    if kind == K_LEN:
        return (li[x, NS] + SQRT2 * li[x, ND]) * cell_size
    if kind == K_TURN:
        return np.float64(li[x, TURNS])
    return lg[x, col]


# -- heuristics (backward passes from the goal) ---------------------------------


@numba.njit(cache=True)
def _hpush(keys, ids, size, key, node):
    """Push onto a plain binary heap (lazy deletion: stale entries are
    skipped when popped)."""
    i = size
    while i > 0:
        p = (i - 1) >> 1
        if keys[p] <= key:
            break
        keys[i] = keys[p]
        ids[i] = ids[p]
        i = p
    keys[i] = key
    ids[i] = node
    return size + 1


@numba.njit(cache=True)
def _hpop(keys, ids, size):
    key, node = keys[0], ids[0]
    size -= 1
    if size > 0:
        k, v = keys[size], ids[size]
        i = 0
        while True:
            ch = 2 * i + 1
            if ch >= size:
                break
            if ch + 1 < size and keys[ch + 1] < keys[ch]:
                ch += 1
            if keys[ch] >= k:
                break
            keys[i] = keys[ch]
            ids[i] = ids[ch]
            i = ch
        keys[i] = k
        ids[i] = v
    return key, node, size


@numba.njit(cache=True)
def _hops(mask, w, goal):
    """Fewest steps from every cell to the goal (``-1``: unreachable), by
    breadth-first search backwards (moves are symmetric)."""
    n = mask.shape[0]
    hop = np.full(n, -1, np.int64)
    queue = np.empty(n, np.int64)
    hop[goal] = 0
    queue[0] = goal
    head, tail = 0, 1
    while head < tail:
        u = queue[head]
        head += 1
        mk = mask[u]
        for d in range(8):
            if (mk >> d) & 1:
                v = u + DR[d] * w + DC[d]
                if hop[v] < 0:
                    hop[v] = hop[u] + 1
                    queue[tail] = v
                    tail += 1
    return hop


@numba.njit(cache=True)
def _cell_to_go(layer, mask, w, goal):
    """Smallest sum of ``layer`` over the cells after each cell up to the goal
    included (``inf``: unreachable, 0 at the goal): a label's sum already
    counts its own cell, so ``g + h`` is admissible and consistent."""
    n = layer.shape[0]
    D = np.full(n, np.inf)
    h = np.full(n, np.inf)
    D[goal] = layer[goal]
    h[goal] = 0.0
    done = np.zeros(n, np.bool_)
    keys = np.empty(8 * n + 1)
    ids = np.empty(8 * n + 1, np.int64)
    size = _hpush(keys, ids, ZERO, D[goal], goal)
    while size > 0:
        key, u, size = _hpop(keys, ids, size)
        if done[u]:
            continue
        done[u] = True
        mk = mask[u]
        for d in range(8):
            if (mk >> d) & 1:
                v = u + DR[d] * w + DC[d]
                if v == goal or done[v]:
                    continue
                val = layer[v] + D[u]
                if val < D[v]:
                    D[v] = val
                    h[v] = D[u]
                    size = _hpush(keys, ids, size, val, v)
    return h


@numba.njit(cache=True)
def _step_to_go(cost8, mask, w, goal):
    """Smallest sum of per-direction step costs ``cost8[d]`` from every cell
    to the goal (``inf``: unreachable)."""
    n = mask.shape[0]
    h = np.full(n, np.inf)
    h[goal] = 0.0
    done = np.zeros(n, np.bool_)
    keys = np.empty(8 * n + 1)
    ids = np.empty(8 * n + 1, np.int64)
    size = _hpush(keys, ids, ZERO, 0.0, goal)
    while size > 0:
        key, u, size = _hpop(keys, ids, size)
        if done[u]:
            continue
        done[u] = True
        mk = mask[u]
        for d in range(8):
            if (mk >> d) & 1:
                v = u + DR[d] * w + DC[d]
                if done[v]:
                    continue
                val = cost8[(d + 4) % 8] + h[u]  # the step v -> u goes the other way
                if val < h[v]:
                    h[v] = val
                    size = _hpush(keys, ids, size, val, v)
    return h


@numba.njit(cache=True)
def _timed_solar_to_go(table, mask, w, goal, hop, psum, n_rows):
    """Lower bounds ``h[n, c]`` of the solar cost from cell ``c`` to the goal for a
    walk whose next step has index ``n`` (``n < n_rows``): backwards over the step
    index, ``h[n, c] = min_d table[n, d] + h[n + 1, c + d]`` (0 at the goal), from
    ``h[n_rows, c] = psum[n_rows + hop[c]] - psum[n_rows]`` (the least cost of each
    of the fewest steps left), and never below that bound at any ``n``. Any walk
    from ``(n, c)`` to the goal costs at least ``h[n, c]`` (induction on its steps),
    so ``g + h`` stays admissible; every label of a state ``(n, c)`` shares it."""
    n_cells = mask.shape[0]
    h = np.empty((n_rows + 1, n_cells))
    for c in range(n_cells):
        h[n_rows, c] = psum[n_rows + hop[c]] - psum[n_rows] if hop[c] >= 0 else np.inf
    for n in range(n_rows - 1, -1, -1):
        for c in range(n_cells):
            if c == goal:
                h[n, c] = 0.0
                continue
            if hop[c] < 0:
                h[n, c] = np.inf
                continue
            best = np.inf
            mk = mask[c]
            for d in range(8):
                if (mk >> d) & 1:
                    u = c + DR[d] * w + DC[d]
                    v = table[n, d] + h[n + 1, u]
                    if v < best:
                        best = v
            lb = psum[n + hop[c]] - psum[n]
            h[n, c] = best if best > lb else lb
    return h[:n_rows]


# -- open list: binary heap of label rows, lexicographic on lf rows -------------
#
# Exact ties of the f-vectors are broken by the labels' sequence numbers
# (li[:, SEQ]). A new label takes the number last given up by a label dropped at
# its pop, else the next new one: the row it had when every expanded label kept
# its row, so the labels leave in that search's order (and that of the reference,
# tests/_multi_reference*.py), whichever rows they hold now.


@numba.njit(cache=True, inline="always")
def _less(lf, li, a, b, k):
    for j in range(k):
        if lf[a, j] != lf[b, j]:
            return lf[a, j] < lf[b, j]
    return li[a, SEQ] < li[b, SEQ]


@numba.njit(cache=True, _nrt=False)
def _push(hid, size, lf, li, k, x):
    i = size
    while i > 0:
        p = (i - 1) >> 1
        if not _less(lf, li, x, hid[p], k):
            break
        hid[i] = hid[p]
        i = p
    hid[i] = x


@numba.njit(cache=True, _nrt=False)
def _pop(hid, size, lf, li, k):
    """Remove the smallest entry; returns the new size."""
    size -= 1
    if size > 0:
        x = hid[size]
        i = 0
        while True:
            ch = 2 * i + 1
            if ch >= size:
                break
            if ch + 1 < size and _less(lf, li, hid[ch + 1], hid[ch], k):
                ch += 1
            if not _less(lf, li, hid[ch], x, k):
                break
            hid[i] = hid[ch]
            i = ch
        hid[i] = x
    return size


# -- per-state sets: kd-trees in one pool, by the logarithmic method ------------------
#
# The set of a state (and the goal's, the last row of ``sidx``) is a chain of static
# kd-trees (Bentley and Saxe's logarithmic method): a new member starts a tree of its
# own at the head of the chain, which absorbs the next trees while they are smaller
# than twice its size (a binary counter: at most about log2(n) trees, each member
# rebuilt O(log n) times). A tree of ``m`` members is a block of ``m`` rows of the pool
# ``sv`` (floats) / ``si`` (ints) laid out implicitly: the node of rows ``[lo, hi)``
# is row ``(lo + hi) // 2``, the median of the range in one of the objectives other
# than the primary (cycling with the depth), its subtrees ``[lo, mid)`` and ``[mid + 1,
# hi)``. Row ``r`` holds a member's k g-values (internal order, turns as a float) in
# ``sv[r, :k]`` and the least and the largest ``g_j`` (``j >= 1``) of its subtree in the
# columns after them (the box); ``si[r]`` its turns, heading and whether it is alive.
# A query descends only into subtrees whose box may hold a member that covers the
# label (least values within the tolerance of the label's), an insertion only into
# those that may hold a member it drops (largest values at least the new member's);
# ``_le`` is monotone, so the pruning is exact and every decision is that of a scan of
# the whole set. A dropped member is marked dead (a tree whose live members fall below
# half is rebuilt); ``tdir`` rows describe the trees (pool offset, rows, live members,
# next tree + 1, block capacity), ``sidx[s]`` the set (first tree + 1, live members,
# trees). Blocks come from free lists per size class (``4 << c`` rows).

B_HEAD, B_CNT, B_NTREE = range(3)
T_OFF, T_M, T_LIVE, T_NEXT, T_CAP = range(5)
N_T = 5
M_TURNS, M_HEAD, M_ALIVE = range(3)
N_SI = 3
#: Size classes of the pool's blocks (``4 << c`` rows).
N_CLASS = 40
#: Entries of the traversal stack (two per tree level).
N_STACK = 256


@numba.njit(cache=True, inline="always")
def _width(k):
    """Float columns of a pool row: k g-values, then the box (least and largest
    of each objective after the primary)."""
    return k + 2 * (k - 1)


@numba.njit(cache=True)
def _block_class(cap):
    c = 0
    while (4 << c) < cap:
        c += 1
    return c


@numba.njit(cache=True)
def _alloc(si, sfree, st, m):
    """A pool block of at least ``m`` rows: ``(offset, capacity)``."""
    c = _block_class(m)
    if sfree[c] >= 0:
        off = sfree[c]
        sfree[c] = si[off, 0]
    else:
        off = st[S_PTOP]
        st[S_PTOP] += 4 << c
    return off, 4 << c


@numba.njit(cache=True)
def _release(si, sfree, off, cap):
    c = _block_class(cap)
    si[off, 0] = sfree[c]
    sfree[c] = off


@numba.njit(cache=True)
def _tree_new(tdir, st):
    t = st[S_TFREE]
    if t >= 0:
        st[S_TFREE] = tdir[t, T_NEXT]
    else:
        t = st[S_TTOP]
        st[S_TTOP] += 1
    return t


@numba.njit(cache=True)
def _tree_free(tdir, st, t):
    tdir[t, T_NEXT] = st[S_TFREE]
    st[S_TFREE] = t


@numba.njit(cache=True)
def _select(perm, tv, j, lo, hi, kth):
    """Reorder ``perm[lo:hi]`` so that ``perm[kth]`` holds the member of rank
    ``kth - lo`` by ``tv[:, j]``, the smaller ones before it and the larger ones
    after it (quickselect, median-of-three pivots)."""
    while hi - lo > 3:
        a, b, c = perm[lo], perm[(lo + hi) >> 1], perm[hi - 1]
        va, vb, vc = tv[a, j], tv[b, j], tv[c, j]
        if va > vb:
            va, vb = vb, va
        if vb > vc:
            vb = vc
            if va > vb:
                vb = va
        pv = vb
        i, e = lo, hi - 1
        while i <= e:
            while tv[perm[i], j] < pv:
                i += 1
            while tv[perm[e], j] > pv:
                e -= 1
            if i <= e:
                perm[i], perm[e] = perm[e], perm[i]
                i += 1
                e -= 1
        # [lo, e] <= pv <= [i, hi)
        if kth <= e:
            hi = e + 1
        elif kth >= i:
            lo = i
        else:
            return
    for a in range(lo + 1, hi):  # insertion sort of the last few
        p = perm[a]
        v = tv[p, j]
        b = a - 1
        while b >= lo and tv[perm[b], j] > v:
            perm[b + 1] = perm[b]
            b -= 1
        perm[b + 1] = p


@numba.njit(cache=True)
def _build(sv, si, off, tv, ti, m, k):
    """Write the members ``tv[:m]`` (g-values), ``ti[:m]`` (turns, heading) as a
    kd-tree at pool rows ``off ..``, boxes included."""
    b0 = k
    b1 = k + k - 1
    if m == 1:
        for c in range(k):
            sv[off, c] = tv[0, c]
        for j in range(1, k):
            sv[off, b0 + j - 1] = tv[0, j]
            sv[off, b1 + j - 1] = tv[0, j]
        si[off, M_TURNS] = ti[0, 0]
        si[off, M_HEAD] = ti[0, 1]
        si[off, M_ALIVE] = 1
        return
    perm = np.arange(m)
    stack = np.empty((m + 66, 3), np.int64)
    rr = np.empty((m, 2), np.int64)  # the ranges, parents before children
    nr = 0
    stack[0, 0], stack[0, 1], stack[0, 2] = 0, m, 0
    top = 1
    while top > 0:
        top -= 1
        lo, hi, d = stack[top, 0], stack[top, 1], stack[top, 2]
        if hi <= lo:
            continue
        rr[nr, 0] = lo
        rr[nr, 1] = hi
        nr += 1
        mid = (lo + hi) >> 1
        if hi - lo > 1 and k > 1:
            _select(perm, tv, 1 + d % (k - 1), lo, hi, mid)
        stack[top, 0], stack[top, 1], stack[top, 2] = lo, mid, d + 1
        stack[top + 1, 0], stack[top + 1, 1], stack[top + 1, 2] = mid + 1, hi, d + 1
        top += 2
    for i in range(m):
        r = off + i
        p = perm[i]
        for c in range(k):
            sv[r, c] = tv[p, c]
        si[r, M_TURNS] = ti[p, 0]
        si[r, M_HEAD] = ti[p, 1]
        si[r, M_ALIVE] = 1
    for t in range(nr - 1, -1, -1):  # children before parents
        lo, hi = rr[t, 0], rr[t, 1]
        mid = (lo + hi) >> 1
        r = off + mid
        for j in range(1, k):
            sv[r, b0 + j - 1] = sv[r, j]
            sv[r, b1 + j - 1] = sv[r, j]
        for a, b in ((lo, mid), (mid + 1, hi)):
            if b > a:
                rc = off + ((a + b) >> 1)
                for j in range(1, k):
                    if sv[rc, b0 + j - 1] < sv[r, b0 + j - 1]:
                        sv[r, b0 + j - 1] = sv[rc, b0 + j - 1]
                    if sv[rc, b1 + j - 1] > sv[r, b1 + j - 1]:
                        sv[r, b1 + j - 1] = sv[rc, b1 + j - 1]


@numba.njit(cache=True, _nrt=False)
def _covered(sv, si, tdir, head, q, qr, okind, tx, hx, at_goal, to_go, ties, smooth, stk):
    """True if a member of the set whose first tree is ``head - 1`` covers the
    vector ``q[qr]``: at a state, ``q[qr]`` is a label's g-vector and a member
    with heading ``ha`` charges its turns with ``_gap(ha, hx)``; at the goal
    (``at_goal``), ``q[qr]`` is the label's f-vector (a lower bound of its
    completions' costs). Covering: weakly better on every objective within the
    tolerance and strictly on one, or equal and (with ``ties``, smoothness not
    an objective) not less smooth (at the goal: not more turns than the label's
    ``tx`` plus ``to_go``, a lower bound of the turns still to come). ``stk``:
    scratch of ``N_STACK`` ints. Returns ``(covered, members tested, tree nodes
    visited)``.

    This helper and the other per-label ones (:func:`_gvec`, :func:`_fvec`,
    :func:`_push`, :func:`_pop`) allocate nothing and are compiled without
    reference counting (``_nrt=False``): inlined or called, numba counted
    their arrays in and out atomically at every call, 17 % of the samples
    of a four-objective search (docs/results/exact_speed.md, "Reference
    counting in the search kernels")."""
    k = okind.shape[0]
    b0 = k
    tested = 0
    nodes = 0
    t = head - 1
    while t >= 0:
        off = tdir[t, T_OFF]
        stk[0] = 0
        stk[1] = tdir[t, T_M]
        top = 2
        while top > 0:
            top -= 2
            lo, hi = stk[top], stk[top + 1]
            mid = (lo + hi) >> 1
            r = off + mid
            nodes += 1
            inside = True
            for j in range(1, k):
                if not _le(sv[r, b0 + j - 1], q[qr, j]):
                    inside = False
                    break
            if not inside:
                continue
            if si[r, M_ALIVE]:
                tested += 1
                # the member test (written out: a call would pass the arrays again)
                gap = 0 if at_goal else _gap(si[r, M_HEAD], hx)
                ok = True
                strict = False
                for jj in range(k):
                    j = jj + 1 if jj < k - 1 else 0  # the primary last: it rarely decides
                    ga = sv[r, j]
                    gx = q[qr, j]
                    if okind[j] == K_TURN:
                        ga += gap
                        if ga > gx:
                            ok = False
                            break
                        if ga < gx:
                            strict = True
                    else:
                        if not _le(ga, gx):
                            ok = False
                            break
                        if not _eq(ga, gx):
                            strict = True
                if ok:
                    if strict or smooth or not ties:
                        return True, tested, nodes
                    if at_goal:
                        if si[r, M_TURNS] <= tx + to_go:
                            return True, tested, nodes
                    elif si[r, M_TURNS] + gap <= tx:
                        return True, tested, nodes
            if hi > mid + 1:
                stk[top] = mid + 1
                stk[top + 1] = hi
                top += 2
            if mid > lo:  # the lower half first
                stk[top] = lo
                stk[top + 1] = mid
                top += 2
        t = tdir[t, T_NEXT] - 1
    return False, tested, nodes


@numba.njit(cache=True, inline="always")
def _drop_in_tree(sv, si, off, m, q, qr, okind, tx, hx, at_goal, stk):
    """Mark dead the members of a tree the new member drops (those it makes
    redundant for later checks: weakly better on every objective but the
    primary, as later labels are not better in the primary, NAMOA*-dr);
    returns how many and the nodes visited."""
    k = okind.shape[0]
    b1 = k + k - 1
    n = 0
    nodes = 0
    stk[0] = 0
    stk[1] = m
    top = 2
    while top > 0:
        top -= 2
        lo, hi = stk[top], stk[top + 1]
        mid = (lo + hi) >> 1
        r = off + mid
        nodes += 1
        inside = True
        for j in range(1, k):
            if not _le(q[qr, j], sv[r, b1 + j - 1]):
                inside = False
                break
        if not inside:
            continue
        if si[r, M_ALIVE]:
            gap = 0 if at_goal else _gap(hx, si[r, M_HEAD])
            drop = True
            for j in range(1, k):
                if okind[j] == K_TURN:
                    if tx + gap > si[r, M_TURNS]:
                        drop = False
                        break
                elif not _le(q[qr, j], sv[r, j]):
                    drop = False
                    break
            if drop:  # weakly better on every objective but the primary (NAMOA*-dr)
                si[r, M_ALIVE] = 0
                n += 1
        if hi > mid + 1:
            stk[top] = mid + 1
            stk[top + 1] = hi
            top += 2
        if mid > lo:
            stk[top] = lo
            stk[top + 1] = mid
            top += 2
    return n, nodes


@numba.njit(cache=True)
def _gather(sv, si, off, m, tv, ti, n, k):
    """Append the live members of a tree to ``tv``/``ti`` from row ``n``."""
    for i in range(m):
        r = off + i
        if si[r, M_ALIVE]:
            for c in range(k):
                tv[n, c] = sv[r, c]
            ti[n, 0] = si[r, M_TURNS]
            ti[n, 1] = si[r, M_HEAD]
            n += 1
    return n


@numba.njit(cache=True)
def _insert(sv, si, sidx, sfree, tdir, st, s, q, qr, okind, tx, hx, at_goal, stk):
    """Add the member with g-vector ``q[qr]``, turns ``tx`` and heading ``hx``
    to the set of ``s`` and drop the members it makes redundant for later
    checks (:func:`_drop_in_tree`). The caller has made sure the pool holds
    ``_room(live members of s)`` more rows and ``tdir`` two more trees."""
    k = okind.shape[0]
    # drops: marked dead; an emptied tree is freed, a half-dead one rebuilt
    prev = -1
    t = sidx[s, B_HEAD] - 1
    while t >= 0:
        nxt = tdir[t, T_NEXT] - 1
        nd, nn = _drop_in_tree(sv, si, tdir[t, T_OFF], tdir[t, T_M], q, qr, okind, tx, hx, at_goal, stk)
        st[S_DROP_NODES] += nn
        if nd > 0:
            tdir[t, T_LIVE] -= nd
            sidx[s, B_CNT] -= nd
            live = tdir[t, T_LIVE]
            if live == 0:
                if prev >= 0:
                    tdir[prev, T_NEXT] = nxt + 1
                else:
                    sidx[s, B_HEAD] = nxt + 1
                _release(si, sfree, tdir[t, T_OFF], tdir[t, T_CAP])
                _tree_free(tdir, st, t)
                sidx[s, B_NTREE] -= 1
                t = nxt
                continue
            if 2 * live < tdir[t, T_M]:
                tv = np.empty((live, k))
                ti = np.empty((live, 2), np.int64)
                _gather(sv, si, tdir[t, T_OFF], tdir[t, T_M], tv, ti, ZERO, k)
                _release(si, sfree, tdir[t, T_OFF], tdir[t, T_CAP])
                off, cap = _alloc(si, sfree, st, live)
                _build(sv, si, off, tv, ti, live, k)
                st[S_BUILT] += live
                tdir[t, T_OFF] = off
                tdir[t, T_M] = live
                tdir[t, T_CAP] = cap
        prev = t
        t = nxt
    # the new member's tree absorbs the next ones while they are smaller than twice it
    total = 1
    t = sidx[s, B_HEAD] - 1
    while t >= 0 and tdir[t, T_LIVE] < 4 * total:
        total += tdir[t, T_LIVE]
        t = tdir[t, T_NEXT] - 1
    tv = np.empty((total, k))
    ti = np.empty((total, 2), np.int64)
    for c in range(k):
        tv[0, c] = q[qr, c]
    ti[0, 0] = tx
    ti[0, 1] = hx
    n = ONE
    t = sidx[s, B_HEAD] - 1
    while n < total:
        n = _gather(sv, si, tdir[t, T_OFF], tdir[t, T_M], tv, ti, n, k)
        nxt = tdir[t, T_NEXT] - 1
        _release(si, sfree, tdir[t, T_OFF], tdir[t, T_CAP])
        _tree_free(tdir, st, t)
        sidx[s, B_NTREE] -= 1
        t = nxt
    off, cap = _alloc(si, sfree, st, total)
    _build(sv, si, off, tv, ti, total, k)
    st[S_BUILT] += total
    u = _tree_new(tdir, st)
    tdir[u, T_OFF] = off
    tdir[u, T_M] = total
    tdir[u, T_LIVE] = total
    tdir[u, T_CAP] = cap
    tdir[u, T_NEXT] = t + 1
    sidx[s, B_HEAD] = u + 1
    sidx[s, B_NTREE] += 1
    sidx[s, B_CNT] += 1


@numba.njit(cache=True, inline="always")
def _room(live):
    """Pool rows an insertion into a set of ``live`` members may take."""
    return 4 * (live + 1) + 256


@numba.njit(cache=True, _nrt=False)
def _gvec(li, lg, x, okind, ocol, cell_size, q, qr):
    for o in range(okind.shape[0]):
        q[qr, o] = _g(li, lg, x, okind[o], ocol[o], cell_size)


# -- the search -----------------------------------------------------------------------


@numba.njit(cache=True)
def _k_init(start, layers, okind, ocol, cell_size, hs, hd, ht, hfl, hop, psum, hsol, timed, n_float):
    """The state of a new search: the start label alone on the open list.
    Returns ``(li, lg, lf, hid, sols, st, sv, si, sfree, tdir, pc, fs, fseq)``:
    label rows, open list, solution rows, scalars, per-state sets, then the
    parent table, the stack of free rows and that of free sequence numbers
    (:func:`_k_run`)."""
    k = okind.shape[0]
    li = np.empty((1024, N_INT), np.int32)
    lg = np.zeros((1024, max(n_float, 1)))
    lf = np.empty((1024, k))
    hid = np.empty(1024, np.int32)
    sols = np.empty(64, np.int32)
    li[0, CELL] = start
    li[0, HEAD] = -1
    li[0, PARENT] = -1
    li[0, NS] = 0
    li[0, ND] = 0
    li[0, TURNS] = 0
    li[0, SEQ] = 0
    for j in range(k):  # the start cell counts for the cell sums
        if okind[j] == K_CELL:
            lg[0, ocol[j]] = layers[ocol[j], start]
    _fvec(li, lg, lf, 0, okind, ocol, cell_size, hs, hd, ht, hfl, hop, psum, hsol, timed)
    hid[0] = 0
    st = np.zeros(N_ST, np.int64)
    st[S_N] = 1
    st[S_SIZE] = 1
    st[S_GENERATED] = 1
    st[S_SEQ] = 1
    st[S_SPAN] = 1
    st[S_TFREE] = -1
    sv = np.empty((1024, _width(k)))
    si = np.empty((1024, N_SI), np.int32)
    sfree = np.full(N_CLASS, -1, np.int64)
    tdir = np.empty((256, N_T), np.int64)
    pc = np.empty((1024, 2), np.int32)
    fs = np.empty(li.shape[0], np.int32)  # as long as li: every row may be free
    fseq = np.empty(64, np.int32)
    return li, lg, lf, hid, sols, st, sv, si, sfree, tdir, pc, fs, fseq


@numba.njit(cache=True, _nrt=False)
def _fvec(li, lg, lf, j, okind, ocol, cell_size, hs, hd, ht, hfl, hop, psum, hsol, timed):
    """Write the f-vector (``g + h``, internal order) of label ``j``."""
    c = li[j, CELL]
    for o in range(okind.shape[0]):
        kind = okind[o]
        if kind == K_LEN:
            lf[j, o] = ((li[j, NS] + hs[c]) + SQRT2 * (li[j, ND] + hd[c])) * cell_size
        elif kind == K_TURN:
            t = li[j, TURNS]
            if ht.shape[0] > 1:
                hd_ = li[j, HEAD]
                t += ht[c * 9 + (hd_ if hd_ >= 0 else 8)]
            lf[j, o] = np.float64(t)
        elif kind == K_SOLAR and timed:
            n = li[j, NS] + li[j, ND]
            if n < hsol.shape[0]:
                lf[j, o] = lg[j, ocol[o]] + hsol[n, c]
            else:
                lf[j, o] = lg[j, ocol[o]] + (psum[n + hop[c]] - psum[n])
        else:
            lf[j, o] = lg[j, ocol[o]] + hfl[ocol[o], c]


@numba.njit(cache=True)
def _k_run(
    mask,
    w,
    goal,
    layers,
    table,
    okind,
    ocol,
    cell_size,
    hs,
    hd,
    ht,
    hfl,
    hop,
    psum,
    hsol,
    timed,
    smooth,
    ties,
    sidx,
    li,
    lg,
    lf,
    hid,
    sols,
    st,
    sv,
    si,
    sfree,
    tdir,
    pc,
    fs,
    fseq,
    n_steps,
    max_labels,
):
    """Advance the search by at most ``n_steps`` pops. Returns ``(sidx, li,
    lg, lf, hid, sols, sv, si, tdir, pc, fs, fseq, status)``, status DONE (open
    list empty), PAUSED, OVER_BUDGET or STEP_LIMIT; the arrays may have been
    reallocated (grown by doubling).

    Only open labels and solutions hold rows of ``li``/``lg``/``lf``. A label
    dropped when it leaves the open list is referenced by nothing (no
    children, in no set): its row goes on the stack of free rows ``fs`` (int32,
    as long as ``li``; ``st[S_N_FREE]`` of them), from which new labels take
    their rows first, and its sequence number on the stack ``fseq``
    (``st[S_N_FREE_SEQ]``). An expanded label's values go into its state's
    set; it is needed only as its children's parent, so its cell and parent
    go to the next entry of ``pc`` (int32, 2 columns; ``st[S_PC]`` entries),
    its children's PARENT is that entry, and its row is recycled too
    (:func:`gapath.planners._exact_kernels._trace_parents` walks the entries).
    Stops before a pop that could take the labels held (rows in use and
    entries: the rows in use when every expanded label kept its row) beyond
    ``max_labels``."""
    pops0 = st[S_POPS]
    n_cells = mask.shape[0]
    while True:
        status = _k_steps(
            mask,
            w,
            goal,
            layers,
            table,
            okind,
            ocol,
            cell_size,
            hs,
            hd,
            ht,
            hfl,
            hop,
            psum,
            hsol,
            timed,
            smooth,
            ties,
            sidx,
            li,
            lg,
            lf,
            hid,
            sols,
            st,
            sv,
            si,
            sfree,
            tdir,
            pc,
            fs,
            fseq,
            n_steps - (st[S_POPS] - pops0),
            max_labels,
        )
        if status != NEED_ROOM:
            return sidx, li, lg, lf, hid, sols, sv, si, tdir, pc, fs, fseq, status
        if st[S_N] + 8 > li.shape[0]:
            cap = 2 * li.shape[0]
            li2 = np.empty((cap, li.shape[1]), li.dtype)
            li2[: li.shape[0]] = li
            lg2 = np.empty((cap, lg.shape[1]))
            lg2[: lg.shape[0]] = lg
            lf2 = np.empty((cap, lf.shape[1]))
            lf2[: lf.shape[0]] = lf
            li, lg, lf = li2, lg2, lf2
            fs = _grow1(fs, li.shape[0])
        if st[S_SIZE] + 8 > hid.shape[0]:
            hid2 = np.empty(2 * hid.shape[0], hid.dtype)
            hid2[: hid.shape[0]] = hid
            hid = hid2
        if st[S_SOLS] + 1 > sols.shape[0]:
            sols2 = np.empty(2 * sols.shape[0], sols.dtype)
            sols2[: sols.shape[0]] = sols
            sols = sols2
        pc = _grow(pc, st[S_PC] + 1)
        fseq = _grow1(fseq, st[S_N_FREE_SEQ] + 1)
        need = st[S_PTOP] + _room(sidx[:, B_CNT].max())
        if need > sv.shape[0]:
            cap = 2 * sv.shape[0]
            while cap < need:
                cap *= 2
            sv2 = np.empty((cap, sv.shape[1]))
            sv2[: sv.shape[0]] = sv
            si2 = np.empty((cap, si.shape[1]), si.dtype)
            si2[: si.shape[0]] = si
            sv, si = sv2, si2
        if st[S_TTOP] + 2 > tdir.shape[0]:
            tdir2 = np.empty((2 * tdir.shape[0], N_T), tdir.dtype)
            tdir2[: tdir.shape[0]] = tdir
            tdir = tdir2
        if timed:
            x = hid[0]
            span = st[S_SPAN]
            while li[x, NS] + li[x, ND] + 1 >= span:
                span *= 2
            if span > st[S_SPAN]:
                sidx2 = np.zeros((span * n_cells + 1, 3), np.int64)
                sidx2[: sidx.shape[0] - 1] = sidx[:-1]
                sidx2[-1] = sidx[-1]  # the goal's set
                sidx = sidx2
                st[S_SPAN] = span


@numba.njit(cache=True)
def _k_steps(
    mask,
    w,
    goal,
    layers,
    table,
    okind,
    ocol,
    cell_size,
    hs,
    hd,
    ht,
    hfl,
    hop,
    psum,
    hsol,
    timed,
    smooth,
    ties,
    sidx,
    li,
    lg,
    lf,
    hid,
    sols,
    st,
    sv,
    si,
    sfree,
    tdir,
    pc,
    fs,
    fseq,
    n_steps,
    max_labels,
):
    """The search loop of :func:`_k_run`, in arrays it never reallocates:
    returns NEED_ROOM before a pop when one of them could overflow (the free
    rows' stack ``fs`` is as long as ``li``)."""
    k = okind.shape[0]
    n_cells = mask.shape[0]
    n = st[S_N]
    size = st[S_SIZE]
    n_sols = st[S_SOLS]
    n_expanded = st[S_EXPANDED]
    n_generated = st[S_GENERATED]
    n_free = st[S_N_FREE]
    n_seq = st[S_SEQ]
    n_free_seq = st[S_N_FREE_SEQ]
    n_pc = st[S_PC]
    span = st[S_SPAN]
    n_table = table.shape[0]
    use_ht = ht.shape[0] > 1
    gs = sidx.shape[0] - 1  # the goal's set
    gq = np.empty((1, k))
    stk = np.empty(N_STACK, np.int64)
    status = DONE
    steps = 0
    pops0 = st[S_POPS]
    t_state = 0
    t_goal = 0
    v_state = 0
    v_goal = 0
    while size > 0:
        if steps == n_steps:
            status = PAUSED
            break
        if n - n_free + n_pc + 8 > max_labels:  # an expansion adds up to 8 labels
            status = OVER_BUDGET
            break
        if n + 8 > li.shape[0] or size + 8 > hid.shape[0] or n_sols + 1 > sols.shape[0]:
            status = NEED_ROOM
            break
        if n_pc + 1 > pc.shape[0] or n_free_seq + 1 > fseq.shape[0]:
            status = NEED_ROOM
            break
        x = hid[0]
        n_x = li[x, NS] + li[x, ND]  # steps of x
        if timed:
            if n_x + 1 >= n_table:
                status = STEP_LIMIT
                break
            if n_x + 1 >= span:
                status = NEED_ROOM
                break
        c = li[x, CELL]
        s = n_x * n_cells + c if timed else c
        tgt = gs if c == goal else s
        if st[S_PTOP] + _room(sidx[tgt, B_CNT]) > sv.shape[0] or st[S_TTOP] + 2 > tdir.shape[0]:
            status = NEED_ROOM
            break
        steps += 1
        size = _pop(hid, size, lf, li, k)
        hx = np.int64(li[x, HEAD])  # int64, as every caller of _insert passes
        tx = np.int64(li[x, TURNS])
        _gvec(li, lg, x, okind, ocol, cell_size, gq, 0)

        # lazy checks: the sets may have grown since x was generated
        covered = False
        if c != goal:
            covered, nt, nv = _covered(
                sv, si, tdir, sidx[s, B_HEAD], gq, 0, okind, tx, hx, False, 0, ties, smooth, stk
            )
            t_state += nt
            v_state += nv
        if not covered:
            to_go = 0
            if use_ht:
                to_go = ht[c * 9 + (hx if hx >= 0 else 8)]
            covered, nt, nv = _covered(
                sv, si, tdir, sidx[gs, B_HEAD], lf, x, okind, tx, hx, True, to_go, ties, smooth, stk
            )
            t_goal += nt
            v_goal += nv
        if covered:  # nothing refers to x: recycle its row and its sequence number
            fs[n_free] = x
            n_free += 1
            fseq[n_free_seq] = li[x, SEQ]
            n_free_seq += 1
            continue
        if c == goal:  # a solution: recorded, never expanded
            _insert(sv, si, sidx, sfree, tdir, st, gs, gq, ZERO, okind, tx, hx, TRUE, stk)
            sols[n_sols] = x
            n_sols += 1
            continue

        # expand x: it joins its state's set, and leaves its row for a parent entry
        n_expanded += 1
        _insert(sv, si, sidx, sfree, tdir, st, s, gq, ZERO, okind, tx, hx, FALSE, stk)
        pc[n_pc, 0] = c
        pc[n_pc, 1] = li[x, PARENT]
        parent = n_pc
        n_pc += 1
        r, col = c // w, c % w
        mk = mask[c]
        for d in range(8):
            if not (mk >> d) & 1:
                continue
            cell = (r + DR[d]) * w + col + DC[d]
            if hop[cell] < 0:  # the goal cannot be reached from there
                continue
            j = fs[n_free - 1] if n_free > 0 else n  # the row recycled last, else a new one
            li[j, CELL] = cell
            li[j, HEAD] = d
            li[j, PARENT] = parent
            li[j, NS] = li[x, NS] + (1 - d % 2)
            li[j, ND] = li[x, ND] + d % 2
            tj = tx + (turn(hx, d) if hx >= 0 else 0)
            li[j, TURNS] = tj
            for o in range(k):
                kind = okind[o]
                if kind == K_CELL:
                    lg[j, ocol[o]] = lg[x, ocol[o]] + layers[ocol[o], cell]
                elif kind == K_SOLAR:
                    lg[j, ocol[o]] = lg[x, ocol[o]] + table[n_x if timed else 0, d]
            _fvec(li, lg, lf, j, okind, ocol, cell_size, hs, hd, ht, hfl, hop, psum, hsol, timed)
            n_generated += 1
            s2 = (n_x + 1) * n_cells + cell if timed else cell
            if cell != goal and sidx[s2, B_CNT] > 0:
                _gvec(li, lg, j, okind, ocol, cell_size, gq, 0)
                cov, nt, nv = _covered(
                    sv, si, tdir, sidx[s2, B_HEAD], gq, 0, okind, tj, d, False, 0, ties, smooth, stk
                )
                t_state += nt
                v_state += nv
                if cov:
                    continue
            to_go = ht[cell * 9 + d] if use_ht else 0
            cov, nt, nv = _covered(
                sv, si, tdir, sidx[gs, B_HEAD], lf, j, okind, tj, d, True, to_go, ties, smooth, stk
            )
            t_goal += nt
            v_goal += nv
            if cov:
                continue
            if n_free > 0:
                n_free -= 1
            else:
                n += 1
            if n_free_seq > 0:
                n_free_seq -= 1
                li[j, SEQ] = fseq[n_free_seq]
            else:
                li[j, SEQ] = n_seq
                n_seq += 1
            _push(hid, size, lf, li, k, j)
            size += 1
        fs[n_free] = x  # x's values now live in its state's set and in pc
        n_free += 1
    st[S_N] = n
    st[S_SIZE] = size
    st[S_SOLS] = n_sols
    st[S_EXPANDED] = n_expanded
    st[S_GENERATED] = n_generated
    st[S_N_FREE] = n_free
    st[S_SEQ] = n_seq
    st[S_N_FREE_SEQ] = n_free_seq
    st[S_PC] = n_pc
    st[S_POPS] = pops0 + steps
    st[S_STATE_TESTS] += t_state
    st[S_GOAL_TESTS] += t_goal
    st[S_STATE_NODES] += v_state
    st[S_GOAL_NODES] += v_goal
    return status


# -- the final front: tolerant dominance and duplicates through a kd-tree -------------


@numba.njit(cache=True)
def _front_filter(F, order):
    """The rows of ``F`` that no other row dominates up to the tolerance, one
    per tolerance-equal vector: the first one in ``order`` (a permutation of
    the rows, most preferred first), in that order. The same rows as
    :func:`gapath.planners._exact_kernels._tolerant_front` (a scan over all
    pairs); here each row queries a kd-tree over all rows (:func:`_build`, the
    objectives as its columns ``1 ..``), which descends only into boxes that may
    hold a row within the tolerance of it, and only the rows that have a
    tolerance-equal partner are compared pairwise in ``order``."""
    n, m = F.shape
    if n == 0:
        return np.empty(0, np.int64)
    k = m + 1  # column 0 unused: _build boxes columns 1 .. k-1
    tv = np.zeros((n, k))
    tv[:, 1:] = F
    ti = np.zeros((n, 2), np.int64)
    for i in range(n):
        ti[i, 0] = i
    sv = np.empty((n, _width(k)))
    si = np.empty((n, N_SI), np.int32)
    _build(sv, si, ZERO, tv, ti, n, k)
    b0 = k
    keep = np.ones(n, np.bool_)
    partner = np.zeros(n, np.bool_)
    stk = np.empty(N_STACK, np.int64)
    for i in range(n):
        # a row that dominates i (weakly everywhere, strictly somewhere), and
        # whether one is tolerance-equal to i
        stk[0] = 0
        stk[1] = n
        top = 2
        while top > 0 and keep[i]:
            top -= 2
            lo, hi = stk[top], stk[top + 1]
            mid = (lo + hi) >> 1
            inside = True
            for o in range(m):
                if not _le(sv[mid, b0 + o], F[i, o]):
                    inside = False
                    break
            if not inside:
                continue
            j = si[mid, M_TURNS]
            if j != i:
                not_worse = True
                better = False
                for o in range(m):
                    if not _le(F[j, o], F[i, o]):
                        not_worse = False
                        break
                    if not _eq(F[j, o], F[i, o]):
                        better = True
                if not_worse:
                    if better:
                        keep[i] = False
                    else:
                        partner[i] = True
            if hi > mid + 1:
                stk[top] = mid + 1
                stk[top + 1] = hi
                top += 2
            if mid > lo:
                stk[top] = lo
                stk[top + 1] = mid
                top += 2
    out = np.empty(n, np.int64)
    cnt = 0
    eqs = np.empty(n, np.int64)  # kept rows with a tolerance-equal one, in order
    n_eq = 0
    for i in order:
        if not keep[i]:
            continue
        if partner[i]:
            dup = False
            for jj in range(n_eq):
                j = eqs[jj]
                same = True
                for o in range(m):
                    if not _eq(F[j, o], F[i, o]):
                        same = False
                        break
                if same:
                    dup = True
                    break
            if dup:
                continue
            eqs[n_eq] = i
            n_eq += 1
        out[cnt] = i
        cnt += 1
    return out[:cnt]
