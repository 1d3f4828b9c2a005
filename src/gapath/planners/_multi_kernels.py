"""Numba kernels of the k-objective exact search (private; driver in
:mod:`gapath.planners._multi`, public entry :func:`gapath.planners.exact.free_front`).

A NAMOA*-dr / LTMOA*-style label-setting search over any number of additive
objectives: labels leave a binary heap in lexicographic order of their
f-vectors (all k components, then the label row); every state keeps the set
of its expanded labels that no later expanded label made redundant, and the
goal keeps the set of solutions. A label is tested against both sets when it
is generated and again when it is popped (the sets grew meanwhile). The
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

from gapath.grid import DC, DR, SQRT2, turn

#: Relative tolerance of SPEC "Duplicates and ties".
TOL = 1e-9

K_LEN, K_TURN, K_CELL, K_SOLAR = range(4)
#: Status codes (NEED_ROOM: internal to _k_run; STEP_LIMIT: a label would
#: take more steps than the solar table holds).
DONE, PAUSED, OVER_BUDGET, NEED_ROOM, STEP_LIMIT = range(5)

# int table of a label
CELL, HEAD, PARENT, NS, ND, TURNS, NEXT = range(7)
N_INT = 7
# scalars of the search state
S_N, S_SIZE, S_SOLS, S_EXPANDED, S_GENERATED, S_GOAL_FIRST, S_FREE, S_N_FREE, S_POPS, S_SPAN = range(10)
# pool rows in use, members tested by the state and the goal checks
S_PTOP, S_STATE_TESTS, S_GOAL_TESTS = range(10, 13)
N_ST = 13


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
    size = _hpush(keys, ids, 0, D[goal], goal)
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
    size = _hpush(keys, ids, 0, 0.0, goal)
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


# -- open list: binary heap of label rows, lexicographic on lf rows -------------


@numba.njit(cache=True, inline="always")
def _less(lf, a, b, k):
    for j in range(k):
        if lf[a, j] != lf[b, j]:
            return lf[a, j] < lf[b, j]
    return a < b


@numba.njit(cache=True)
def _push(hid, size, lf, k, x):
    i = size
    while i > 0:
        p = (i - 1) >> 1
        if not _less(lf, x, hid[p], k):
            break
        hid[i] = hid[p]
        i = p
    hid[i] = x


@numba.njit(cache=True)
def _pop(hid, size, lf, k):
    """Remove the smallest entry; returns the new size."""
    size -= 1
    if size > 0:
        x = hid[size]
        i = 0
        while True:
            ch = 2 * i + 1
            if ch >= size:
                break
            if ch + 1 < size and _less(lf, hid[ch + 1], hid[ch], k):
                ch += 1
            if not _less(lf, hid[ch], x, k):
                break
            hid[i] = hid[ch]
            i = ch
        hid[i] = x
    return size


# -- per-state sets: contiguous blocks in one pool ------------------------------------
#
# The set of a state (and the goal's, the last row of ``sidx``) is a block of rows
# of the pool ``sv`` (floats) / ``si`` (ints): row ``r`` holds a member's k g-values
# (internal order, the turns as a float) in ``sv[r, :k]``, and for ``j >= 2`` the
# least ``g_j`` of the members up to this one in ``sv[r, k + j - 2]`` (prefix
# minima); ``si[r]`` its turns and heading. A block is sorted by ``g_1`` (the first
# objective after the primary). A query walks back from the last member whose
# ``g_1`` is within the tolerance of the label's and stops as soon as a prefix
# minimum is beyond it (no earlier member can cover the label): for k = 3 the set
# is a staircase and the walk touches a few rows; the outcome (covered or not, and
# which members an insertion drops) is that of a scan of the whole set.
# Blocks double when full; a freed block goes to a free list of its size class.

B_OFF, B_CNT, B_CAP = range(3)
M_TURNS, M_HEAD = range(2)
#: Size classes of the pool's blocks (``4 << c`` rows).
N_CLASS = 40
#: Members per chunk of a block (chunk minima let a query skip a chunk).
CHUNK = 8


@numba.njit(cache=True)
def _cut(sv, off, cnt, q1):
    """Number of members whose ``g_1`` is ``<=`` ``q1`` within the tolerance
    (``_le`` is monotone in its first argument, the block sorted by ``g_1``)."""
    lo, hi = 0, cnt
    while lo < hi:
        m = (lo + hi) >> 1
        if _le(sv[off + m, 1], q1):
            lo = m + 1
        else:
            hi = m
    return lo


@numba.njit(cache=True)
def _covered(sv, si, off, cnt, q, qr, okind, tx, hx, at_goal, to_go, ties, smooth):
    """True if a member of the block covers the vector ``q[qr]``: at a state,
    ``q[qr]`` is a label's g-vector and a member with heading ``ha`` charges
    its turns with ``_gap(ha, hx)``; at the goal (``at_goal``), ``q[qr]`` is
    the label's f-vector (a lower bound of its completions' costs). Covering:
    weakly better on every objective within the tolerance and strictly on
    one, or equal and (with ``ties``, smoothness not an objective) not less
    smooth (at the goal: not more turns than the label's ``tx`` plus
    ``to_go``, a lower bound of the turns still to come). Returns ``(covered,
    members tested)``."""
    k = okind.shape[0]
    if cnt == 0:
        return False, 0
    i = _cut(sv, off, cnt, q[qr, 1]) - 1 if k > 1 else cnt - 1
    tested = 0
    cm = k + max(k - 2, 0)  # first column of the chunk minima
    top = i
    while i >= 0:
        r = off + i
        stop = False
        for j in range(2, k):
            if not _le(sv[r, k + j - 2], q[qr, j]):
                stop = True
                break
        if stop:
            break
        if k > 2 and (i == top or (i + 1) % CHUNK == 0):
            # entering a chunk (from its end, or the cut): its minima first
            c0 = off + (i // CHUNK) * CHUNK
            skip = False
            for j in range(2, k):
                if not _le(sv[c0, cm + j - 2], q[qr, j]):
                    skip = True
                    break
            if skip:
                i = (i // CHUNK) * CHUNK - 1
                continue
        i -= 1
        tested += 1
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
        if not ok:
            continue
        if strict or smooth or not ties:
            return True, tested
        if at_goal:
            if si[r, M_TURNS] <= tx + to_go:
                return True, tested
        elif si[r, M_TURNS] + gap <= tx:
            return True, tested
    return False, tested


@numba.njit(cache=True)
def _prefix_min(sv, off, cnt, k, first):
    """Recompute the prefix minima of the block from member ``first`` on, and
    the minima of the chunks from ``first``'s on (kept in the chunk's first
    row)."""
    cm = k + max(k - 2, 0)
    for i in range(first, cnt):
        r = off + i
        for j in range(2, k):
            v = sv[r, j]
            if i > 0 and sv[r - 1, k + j - 2] < v:
                v = sv[r - 1, k + j - 2]
            sv[r, k + j - 2] = v
    for c0 in range((first // CHUNK) * CHUNK, cnt, CHUNK):
        for j in range(2, k):
            v = sv[off + c0, j]
            for i in range(c0 + 1, min(c0 + CHUNK, cnt)):
                if sv[off + i, j] < v:
                    v = sv[off + i, j]
            sv[off + c0, cm + j - 2] = v


@numba.njit(cache=True)
def _block_class(cap):
    c = 0
    while (4 << c) < cap:
        c += 1
    return c


@numba.njit(cache=True)
def _insert(sv, si, sidx, sfree, st, s, q, qr, okind, tx, hx, at_goal):
    """Add the member with g-vector ``q[qr]``, turns ``tx`` and heading ``hx``
    to the set of ``s`` and drop the members it makes redundant for later
    checks: those it weakly dominates on every objective but the primary
    (later labels are not better in the primary, NAMOA*-dr). The caller has
    made sure the pool holds ``2 * cap + 4`` more rows."""
    k = okind.shape[0]
    off, cnt, cap = sidx[s, B_OFF], sidx[s, B_CNT], sidx[s, B_CAP]
    # members it drops have g_1 >= its own within the tolerance: a suffix
    first = cnt
    if cnt > 0:
        if k > 1:
            lo, hi = 0, cnt
            while lo < hi:
                m = (lo + hi) >> 1
                if _le(q[qr, 1], sv[off + m, 1]):
                    hi = m
                else:
                    lo = m + 1
            first = lo
        else:
            first = 0
    wr = first
    n_before = cnt
    for i in range(first, cnt):
        r = off + i
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
        if not drop:
            if wr != i:
                for c in range(sv.shape[1]):
                    sv[off + wr, c] = sv[r, c]
                si[off + wr, 0] = si[r, 0]
                si[off + wr, 1] = si[r, 1]
            wr += 1
    cnt = wr
    if cnt + 1 > cap:  # move to a block twice as large
        ncap = 4 if cap == 0 else 2 * cap
        c = _block_class(ncap)
        if sfree[c] >= 0:
            noff = sfree[c]
            sfree[c] = si[noff, 0]
        else:
            noff = st[S_PTOP]
            st[S_PTOP] += ncap
        for i in range(cnt):
            for cc in range(sv.shape[1]):
                sv[noff + i, cc] = sv[off + i, cc]
            si[noff + i, 0] = si[off + i, 0]
            si[noff + i, 1] = si[off + i, 1]
        if cap > 0:
            oc = _block_class(cap)
            si[off, 0] = sfree[oc]
            sfree[oc] = off
        off, cap = noff, ncap
        sidx[s, B_OFF] = off
        sidx[s, B_CAP] = cap
    # its place: after the members with g_1 <= its own
    pos = cnt
    if k > 1:
        lo, hi = 0, cnt
        while lo < hi:
            m = (lo + hi) >> 1
            if sv[off + m, 1] <= q[qr, 1]:
                lo = m + 1
            else:
                hi = m
        pos = lo
    if wr < n_before or k <= 2:  # members dropped: shift, recompute the minima after them
        for i in range(cnt, pos, -1):
            for cc in range(k):
                sv[off + i, cc] = sv[off + i - 1, cc]
            si[off + i, 0] = si[off + i - 1, 0]
            si[off + i, 1] = si[off + i - 1, 1]
        for cc in range(k):
            sv[off + pos, cc] = q[qr, cc]
        si[off + pos, M_TURNS] = tx
        si[off + pos, M_HEAD] = hx
        cnt += 1
        sidx[s, B_CNT] = cnt
        if k > 2:
            _prefix_min(sv, off, cnt, k, min(pos, first))
        return
    _shift_in(sv, si, off, cnt, pos, q, qr, k, tx, hx)
    sidx[s, B_CNT] = cnt + 1


@numba.njit(cache=True)
def _shift_in(sv, si, off, cnt, pos, q, qr, k, tx, hx):
    """Insert a member at ``pos`` of a block of ``cnt`` members (k > 2) and
    update the prefix and chunk minima incrementally (nothing was dropped)."""
    cm = k + k - 2
    wid = sv.shape[1]
    fv = sv.reshape(-1)  # whole rows move up one row (a memmove)
    for t in range((off + cnt + 1) * wid - 1, (off + pos + 1) * wid - 1, -1):
        fv[t] = fv[t - wid]
    fi = si.reshape(-1)
    for t in range(2 * (off + cnt + 1) - 1, 2 * (off + pos + 1) - 1, -1):
        fi[t] = fi[t - 2]
    r = off + pos
    for cc in range(k):
        sv[r, cc] = q[qr, cc]
    si[r, M_TURNS] = tx
    si[r, M_HEAD] = hx
    for j in range(2, k):
        v = q[qr, j]
        if pos > 0 and sv[r - 1, k + j - 2] < v:
            v = sv[r - 1, k + j - 2]
        sv[r, k + j - 2] = v
    for i in range(pos + 1, cnt + 1):  # the prefix minima after it: min with its values
        r = off + i
        same = True
        for j in range(2, k):
            if sv[r, k + j - 2] > q[qr, j]:
                sv[r, k + j - 2] = q[qr, j]
                same = False
        if same:
            break
    n = cnt + 1
    cp = pos // CHUNK
    for c in range(cp, (n - 1) // CHUNK + 1):
        c0 = off + c * CHUNK
        end = min((c + 1) * CHUNK, n)
        old = c * CHUNK < cnt  # the chunk existed: its minima are in its old first row
        o0 = c0 + 1 if c * CHUNK >= pos else c0
        out = (c + 1) * CHUNK < n  # a member left it for the next chunk
        for j in range(2, k):
            if old:
                m = sv[o0, cm + j - 2]
                inc = q[qr, j] if c == cp else sv[c0, j]
                if out and sv[off + (c + 1) * CHUNK, j] <= m:
                    m = sv[c0, j]  # the least may have left: recompute
                    for i in range(c * CHUNK + 1, end):
                        if sv[off + i, j] < m:
                            m = sv[off + i, j]
                elif inc < m:
                    m = inc
            else:
                m = sv[c0, j]
                for i in range(c * CHUNK + 1, end):
                    if sv[off + i, j] < m:
                        m = sv[off + i, j]
            sv[c0, cm + j - 2] = m


@numba.njit(cache=True, inline="always")
def _gvec(li, lg, x, okind, ocol, cell_size, q, qr):
    for o in range(okind.shape[0]):
        q[qr, o] = _g(li, lg, x, okind[o], ocol[o], cell_size)


# -- the search -----------------------------------------------------------------------


@numba.njit(cache=True)
def _k_init(start, layers, okind, ocol, cell_size, hs, hd, ht, hfl, hop, psum, timed, n_float):
    """The state of a new search: the start label alone on the open list.
    Returns ``(li, lg, lf, hid, sols, st, sv, si, sfree)``."""
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
    li[0, NEXT] = -1
    for j in range(k):  # the start cell counts for the cell sums
        if okind[j] == K_CELL:
            lg[0, ocol[j]] = layers[ocol[j], start]
    _fvec(li, lg, lf, 0, okind, ocol, cell_size, hs, hd, ht, hfl, hop, psum, timed)
    hid[0] = 0
    st = np.zeros(N_ST, np.int64)
    st[S_N] = 1
    st[S_SIZE] = 1
    st[S_GENERATED] = 1
    st[S_FREE] = -1
    st[S_SPAN] = 1
    sv = np.empty((1024, k + 2 * max(k - 2, 0)))
    si = np.empty((1024, 2), np.int32)
    sfree = np.full(N_CLASS, -1, np.int64)
    return li, lg, lf, hid, sols, st, sv, si, sfree


@numba.njit(cache=True, inline="always")
def _fvec(li, lg, lf, j, okind, ocol, cell_size, hs, hd, ht, hfl, hop, psum, timed):
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
    n_steps,
    max_labels,
):
    """Advance the search by at most ``n_steps`` pops. Returns ``(sidx, li,
    lg, lf, hid, sols, sv, si, status)``, status DONE (open list empty),
    PAUSED, OVER_BUDGET or STEP_LIMIT; the arrays may have been reallocated
    (grown by doubling)."""
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
            n_steps - (st[S_POPS] - pops0),
            max_labels,
        )
        if status != NEED_ROOM:
            return sidx, li, lg, lf, hid, sols, sv, si, status
        if st[S_N] + 8 > li.shape[0]:
            cap = 2 * li.shape[0]
            li2 = np.empty((cap, li.shape[1]), li.dtype)
            li2[: li.shape[0]] = li
            lg2 = np.empty((cap, lg.shape[1]))
            lg2[: lg.shape[0]] = lg
            lf2 = np.empty((cap, lf.shape[1]))
            lf2[: lf.shape[0]] = lf
            li, lg, lf = li2, lg2, lf2
        if st[S_SIZE] + 8 > hid.shape[0]:
            hid2 = np.empty(2 * hid.shape[0], hid.dtype)
            hid2[: hid.shape[0]] = hid
            hid = hid2
        if st[S_SOLS] + 1 > sols.shape[0]:
            sols2 = np.empty(2 * sols.shape[0], sols.dtype)
            sols2[: sols.shape[0]] = sols
            sols = sols2
        need = st[S_PTOP] + 2 * max(sidx[:, B_CAP].max(), 4) + 4
        if need > sv.shape[0]:
            cap = 2 * sv.shape[0]
            while cap < need:
                cap *= 2
            sv2 = np.empty((cap, sv.shape[1]))
            sv2[: sv.shape[0]] = sv
            si2 = np.empty((cap, 2), si.dtype)
            si2[: si.shape[0]] = si
            sv, si = sv2, si2
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
    n_steps,
    max_labels,
):
    """The search loop of :func:`_k_run`, in arrays it never reallocates."""
    k = okind.shape[0]
    n_cells = mask.shape[0]
    n = st[S_N]
    size = st[S_SIZE]
    n_sols = st[S_SOLS]
    n_expanded = st[S_EXPANDED]
    n_generated = st[S_GENERATED]
    free = st[S_FREE]
    n_free = st[S_N_FREE]
    span = st[S_SPAN]
    n_table = table.shape[0]
    use_ht = ht.shape[0] > 1
    gs = sidx.shape[0] - 1  # the goal's set
    gq = np.empty((1, k))
    status = DONE
    steps = 0
    pops0 = st[S_POPS]
    t_state = 0
    t_goal = 0
    while size > 0:
        if steps == n_steps:
            status = PAUSED
            break
        if n - n_free + 8 > max_labels:  # an expansion adds up to 8 labels
            status = OVER_BUDGET
            break
        if n + 8 > li.shape[0] or size + 8 > hid.shape[0] or n_sols + 1 > sols.shape[0]:
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
        if st[S_PTOP] + 2 * max(sidx[tgt, B_CAP], 4) + 4 > sv.shape[0]:
            status = NEED_ROOM
            break
        steps += 1
        size = _pop(hid, size, lf, k)
        hx = li[x, HEAD]
        tx = li[x, TURNS]
        _gvec(li, lg, x, okind, ocol, cell_size, gq, 0)

        # lazy checks: the sets may have grown since x was generated
        covered = False
        if c != goal:
            covered, nt = _covered(
                sv, si, sidx[s, B_OFF], sidx[s, B_CNT], gq, 0, okind, tx, hx, False, 0, ties, smooth
            )
            t_state += nt
        if not covered:
            to_go = 0
            if use_ht:
                to_go = ht[c * 9 + (hx if hx >= 0 else 8)]
            covered, nt = _covered(
                sv, si, sidx[gs, B_OFF], sidx[gs, B_CNT], lf, x, okind, tx, hx, True, to_go, ties, smooth
            )
            t_goal += nt
        if covered:
            li[x, NEXT] = free  # nothing refers to x: recycle its row
            free = x
            n_free += 1
            continue
        if c == goal:  # a solution: recorded, never expanded
            _insert(sv, si, sidx, sfree, st, gs, gq, 0, okind, tx, hx, True)
            sols[n_sols] = x
            n_sols += 1
            continue

        n_expanded += 1
        _insert(sv, si, sidx, sfree, st, s, gq, 0, okind, tx, hx, False)
        r, col = c // w, c % w
        mk = mask[c]
        for d in range(8):
            if not (mk >> d) & 1:
                continue
            cell = (r + DR[d]) * w + col + DC[d]
            if hop[cell] < 0:  # the goal cannot be reached from there
                continue
            j = free if free >= 0 else n
            li[j, CELL] = cell
            li[j, HEAD] = d
            li[j, PARENT] = x
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
            _fvec(li, lg, lf, j, okind, ocol, cell_size, hs, hd, ht, hfl, hop, psum, timed)
            n_generated += 1
            s2 = (n_x + 1) * n_cells + cell if timed else cell
            if cell != goal and sidx[s2, B_CNT] > 0:
                _gvec(li, lg, j, okind, ocol, cell_size, gq, 0)
                cov, nt = _covered(
                    sv, si, sidx[s2, B_OFF], sidx[s2, B_CNT], gq, 0, okind, tj, d, False, 0, ties, smooth
                )
                t_state += nt
                if cov:
                    continue
            to_go = ht[cell * 9 + d] if use_ht else 0
            cov, nt = _covered(
                sv, si, sidx[gs, B_OFF], sidx[gs, B_CNT], lf, j, okind, tj, d, True, to_go, ties, smooth
            )
            t_goal += nt
            if cov:
                continue
            if j == free:
                free = li[j, NEXT]
                n_free -= 1
            else:
                n += 1
            li[j, NEXT] = -1
            _push(hid, size, lf, k, j)
            size += 1
    st[S_N] = n
    st[S_SIZE] = size
    st[S_SOLS] = n_sols
    st[S_EXPANDED] = n_expanded
    st[S_GENERATED] = n_generated
    st[S_FREE] = free
    st[S_N_FREE] = n_free
    st[S_POPS] = pops0 + steps
    st[S_STATE_TESTS] += t_state
    st[S_GOAL_TESTS] += t_goal
    return status


@numba.njit(cache=True)
def _k_trace(li, sols, w):
    """Cells of the solution paths, concatenated, and their offsets."""
    counts = np.empty(len(sols), np.int64)
    for i in range(len(sols)):
        m = 0
        a = sols[i]
        while a >= 0:
            m += 1
            a = li[a, PARENT]
        counts[i] = m
    offsets = np.zeros(len(sols) + 1, np.int64)
    offsets[1:] = np.cumsum(counts)
    cells = np.empty((offsets[-1], 2), np.int64)
    for i in range(len(sols)):
        j = offsets[i + 1] - 1
        a = sols[i]
        while a >= 0:
            cells[j, 0] = li[a, CELL] // w
            cells[j, 1] = li[a, CELL] % w
            j -= 1
            a = li[a, PARENT]
    return cells, offsets
