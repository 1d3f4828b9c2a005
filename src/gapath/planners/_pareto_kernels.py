"""numba kernels of :mod:`gapath.planners.pareto` (private: the public API is
there; these work on arrays only).
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import DC, DR, SQRT2, can_step

INF = np.inf


# objective kinds (column 0 is always the length, possibly unused)
_LENGTH, _CELL, _SOLAR = 0, 1, 2
# sz[0]: non-dominated nodes, sz[1]: heap size; counters (statistics only):
# sz[2] dominance tests, sz[3] re-insertions of filed nodes, sz[4] insertions
# columns of the open-list bookkeeping table S
_ST, _NDP, _HP, _DOM, _CH, _NX, _PV = range(7)
# node states
_OUT, _ND, _DOMINATED = 0, 1, 2


# ---------------------------------------------------------------------------
# cost vectors
# ---------------------------------------------------------------------------
# Vectors live in "slots": rows of V and C. V[i, :M] holds the M objective
# components (column 0 the length, possibly unused), V[i, M] the priority p
# and V[i, M + 1] the secondary cost s of the vector; C[i] holds the
# straight and diagonal step counts of the length, C[i, 0] < 0 marking the
# infinite vector. V[i, 0] is always C[i, 0] + sqrt(2) * C[i, 1], computed
# from the counts, and p, s are computed from the components (never summed
# incrementally), so equal components give bit-identical p and s.
#
# The model arrays: kind (M,) objective kinds; cells (M, n) cell layers
# (raveled; rows of other kinds unused); soltab (T, 8) solar cost by step
# index estimate and move; khat (n,) step index estimate of each cell;
# wts (2, M) priority and secondary weights (already divided by the
# normalisers); ucols the used (objective) columns.
#
# Small helpers are inlined: numba passes arrays to an outlined call with
# reference counting, which costs more than these helpers themselves.


@numba.njit(cache=True, inline="always")
def _vinf(V, C, i):
    C[i, 0] = -1
    C[i, 1] = 0
    for j in range(V.shape[1]):
        V[i, j] = INF


@numba.njit(cache=True, inline="always")
def _vcopy(V, C, dst, src):
    C[dst, 0] = C[src, 0]
    C[dst, 1] = C[src, 1]
    for j in range(V.shape[1]):
        V[dst, j] = V[src, j]


@numba.njit(cache=True, inline="always")
def _passable(occ, cc, u, d, w):
    """True if the move from cell index ``u`` in direction ``d`` is allowed
    (``u`` free, target inside and free, SPEC corner rule)."""
    ur = u // w
    uc = u - ur * w
    if occ[ur, uc]:
        return False
    return can_step(occ, ur, uc, DR[d], DC[d], cc)


@numba.njit(cache=True, inline="always")
def _neighbour(u, d, h, w):
    """Index of the neighbour of cell ``u`` in direction ``d`` (-1 outside)."""
    ur = u // w
    vr = ur + DR[d]
    vc = u - ur * w + DC[d]
    if vr < 0 or vr >= h or vc < 0 or vc >= w:
        return -1
    return vr * w + vc


@numba.njit(cache=True, inline="always")
def _vedge(V, C, dst, src, frm, to, d, kind, cells, soltab, khat, wts):
    """``dst = src + c(frm -> to)`` for the move in direction ``d``."""
    if C[src, 0] < 0:
        for j in range(V.shape[1]):
            V[dst, j] = INF
        C[dst, 0] = -1
        C[dst, 1] = 0
        return
    m = kind.shape[0]
    a = C[src, 0]
    b = C[src, 1]
    if d & 1:
        b += 1
    else:
        a += 1
    C[dst, 0] = a
    C[dst, 1] = b
    v0 = a + b * SQRT2
    V[dst, 0] = v0
    p = wts[0, 0] * v0
    s = wts[1, 0] * v0
    for j in range(1, m):
        if kind[j] == _CELL:
            v = V[src, j] + cells[j, to]
        else:
            v = V[src, j] + soltab[khat[frm], d]
        V[dst, j] = v
        p += wts[0, j] * v
        s += wts[1, j] * v
    V[dst, m] = p
    V[dst, m + 1] = s


@numba.njit(cache=True, inline="always")
def _vcmp(V, C, a, b, ucols):
    """-1, 0, 1 as vector ``a`` is before, equal to, after ``b`` in the order
    (priority, secondary, components); the infinite vector is last."""
    ainf = C[a, 0] < 0
    binf = C[b, 0] < 0
    if ainf or binf:
        if ainf and binf:
            return 0
        return 1 if ainf else -1
    m = V.shape[1] - 2
    if V[a, m] != V[b, m]:
        return -1 if V[a, m] < V[b, m] else 1
    if V[a, m + 1] != V[b, m + 1]:
        return -1 if V[a, m + 1] < V[b, m + 1] else 1
    for t in range(ucols.shape[0]):
        j = ucols[t]
        if V[a, j] != V[b, j]:
            return -1 if V[a, j] < V[b, j] else 1
    return 0


# ---------------------------------------------------------------------------
# keys
# ---------------------------------------------------------------------------
# K[x] = [k1 (M floats) | k2 (M floats) | p(k1) s(k1) p(k2) s(k2)]


@numba.njit(cache=True, inline="always")
def _finish_key(K, row, wts):
    m = wts.shape[1]
    p1 = 0.0
    s1 = 0.0
    p2 = 0.0
    s2 = 0.0
    for j in range(m):
        p1 += wts[0, j] * K[row, j]
        s1 += wts[1, j] * K[row, j]
        p2 += wts[0, j] * K[row, m + j]
        s2 += wts[1, j] * K[row, m + j]
    K[row, 2 * m] = p1
    K[row, 2 * m + 1] = s1
    K[row, 2 * m + 2] = p2
    K[row, 2 * m + 3] = s2


@numba.njit(cache=True, inline="always")
def _kcmp(K, a, b, ucols):
    """Compare the keys ``[k1; k2]`` of rows ``a`` and ``b``: -1, 0, 1."""
    m = (K.shape[1] - 4) // 2
    c = 2 * m
    if K[a, c] != K[b, c]:
        return -1 if K[a, c] < K[b, c] else 1
    c += 1
    if K[a, c] != K[b, c]:
        return -1 if K[a, c] < K[b, c] else 1
    for t in range(ucols.shape[0]):
        j = ucols[t]
        if K[a, j] != K[b, j]:
            return -1 if K[a, j] < K[b, j] else 1
    c += 1
    if K[a, c] != K[b, c]:
        return -1 if K[a, c] < K[b, c] else 1
    c += 1
    if K[a, c] != K[b, c]:
        return -1 if K[a, c] < K[b, c] else 1
    for t in range(ucols.shape[0]):
        j = m + ucols[t]
        if K[a, j] != K[b, j]:
            return -1 if K[a, j] < K[b, j] else 1
    return 0


@numba.njit(cache=True, inline="always")
def _kbefore(K, a, b, ucols):
    c = _kcmp(K, a, b, ucols)
    if c != 0:
        return c < 0
    return a < b


@numba.njit(cache=True, inline="always")
def _octile_counts(a, b, w):
    """Octile distance between cell indices ``a`` and ``b`` as (straight,
    diagonal) step counts."""
    ar = a // w
    br = b // w
    dr = abs(ar - br)
    dc = abs((a - ar * w) - (b - br * w))
    if dr < dc:
        return dc - dr, dr
    return dr - dc, dc


# ---------------------------------------------------------------------------
# the open list: a binary heap over the non-dominated nodes, plus the
# dominated nodes filed under a non-dominated dominator
# ---------------------------------------------------------------------------
#   S[x] = state, slot in ndl, slot in hn, dominator, first child, next and
#          previous sibling (children = the dominated nodes filed under x)
#   ndl[:sz[0]]  the non-dominated nodes; NDK[i] = the k1 (used columns) of ndl[i]
#   hn[:sz[1]]   binary heap of the non-dominated nodes, ordered by _kbefore;
#                hk[i] = p(k1), s(k1) of hn[i], kept in heap order
#   kx, buf      scratch


@numba.njit(cache=True, inline="always")
def _hbefore(hk, i, node_i, j, node_j, K, ucols):
    """Heap entry ``i`` (node ``node_i``) before entry ``j``: the priority and
    secondary cost of k1 are kept in heap order in ``hk`` (cache friendly);
    the full key comparison runs only on ties."""
    if hk[i, 0] != hk[j, 0]:
        return hk[i, 0] < hk[j, 0]
    if hk[i, 1] != hk[j, 1]:
        return hk[i, 1] < hk[j, 1]
    return _kbefore(K, node_i, node_j, ucols)


@numba.njit(cache=True)
def _hup(hn, hk, S, K, i, ucols):
    node = hn[i]
    k0 = hk[i, 0]
    k1 = hk[i, 1]
    while i > 0:
        parent = (i - 1) >> 1
        pn = hn[parent]
        if k0 != hk[parent, 0]:
            before = k0 < hk[parent, 0]
        elif k1 != hk[parent, 1]:
            before = k1 < hk[parent, 1]
        else:
            before = _kbefore(K, node, pn, ucols)
        if not before:
            break
        hn[i] = pn
        hk[i, 0] = hk[parent, 0]
        hk[i, 1] = hk[parent, 1]
        S[pn, _HP] = i
        i = parent
    hn[i] = node
    hk[i, 0] = k0
    hk[i, 1] = k1
    S[node, _HP] = i


@numba.njit(cache=True)
def _hdown(hn, hk, S, K, i, size, ucols):
    node = hn[i]
    k0 = hk[i, 0]
    k1 = hk[i, 1]
    while True:
        child = 2 * i + 1
        if child >= size:
            break
        right = child + 1
        if right < size and _hbefore(hk, right, hn[right], child, hn[child], K, ucols):
            child = right
        cn = hn[child]
        if hk[child, 0] != k0:
            before = hk[child, 0] < k0
        elif hk[child, 1] != k1:
            before = hk[child, 1] < k1
        else:
            before = _kbefore(K, cn, node, ucols)
        if not before:
            break
        hn[i] = cn
        hk[i, 0] = hk[child, 0]
        hk[i, 1] = hk[child, 1]
        S[cn, _HP] = i
        i = child
    hn[i] = node
    hk[i, 0] = k0
    hk[i, 1] = k1
    S[node, _HP] = i


@numba.njit(cache=True, inline="always")
def _nd_add(x, K, S, ndl, NDK, hn, hk, sz, ucols):
    """x joins the non-dominated set (and the heap)."""
    i = sz[0]
    ndl[i] = x
    S[x, _NDP] = i
    for t in range(ucols.shape[0]):
        NDK[i, t] = K[x, ucols[t]]
    sz[0] = i + 1
    S[x, _ST] = _ND
    m = (K.shape[1] - 4) // 2
    j = sz[1]
    hn[j] = x
    hk[j, 0] = K[x, 2 * m]
    hk[j, 1] = K[x, 2 * m + 1]
    sz[1] = j + 1
    _hup(hn, hk, S, K, j, ucols)


@numba.njit(cache=True, inline="always")
def _nd_del(x, K, S, ndl, NDK, hn, hk, sz, ucols):
    """x leaves the non-dominated set (and the heap); the last member takes
    its slot."""
    i = S[x, _NDP]
    last = sz[0] - 1
    if i != last:
        y = ndl[last]
        ndl[i] = y
        S[y, _NDP] = i
        for t in range(NDK.shape[1]):
            NDK[i, t] = NDK[last, t]
    sz[0] = last
    S[x, _NDP] = -1
    i = S[x, _HP]
    sz[1] -= 1
    last = sz[1]
    if i < last:
        moved = hn[last]
        hn[i] = moved
        hk[i, 0] = hk[last, 0]
        hk[i, 1] = hk[last, 1]
        S[moved, _HP] = i
        _hup(hn, hk, S, K, i, ucols)
        _hdown(hn, hk, S, K, S[moved, _HP], last, ucols)
    S[x, _HP] = -1


@numba.njit(cache=True, inline="always")
def _attach(S, c, y):
    """File node ``c`` under its dominator ``y``."""
    S[c, _DOM] = y
    head = S[y, _CH]
    S[c, _NX] = head
    S[c, _PV] = -1
    if head >= 0:
        S[head, _PV] = c
    S[y, _CH] = c
    S[c, _ST] = _DOMINATED


@numba.njit(cache=True, inline="always")
def _detach(S, c):
    y = S[c, _DOM]
    prev = S[c, _PV]
    nxt = S[c, _NX]
    if prev >= 0:
        S[prev, _NX] = nxt
    else:
        S[y, _CH] = nxt
    if nxt >= 0:
        S[nxt, _PV] = prev
    S[c, _DOM] = -1
    S[c, _NX] = -1
    S[c, _PV] = -1


@numba.njit(cache=True, inline="always")
def _splice(S, y, x):
    """Move every node filed under ``y`` to ``x`` (``x`` dominates ``y``)."""
    c = S[y, _CH]
    if c >= 0:
        tail = -1
        while c >= 0:
            S[c, _DOM] = x
            tail = c
            c = S[c, _NX]
        head = S[x, _CH]
        S[tail, _NX] = head
        if head >= 0:
            S[head, _PV] = tail
        S[x, _CH] = S[y, _CH]
        S[y, _CH] = -1


@numba.njit(cache=True, inline="always")
def _find_dominator(x, K, ndl, NDK, sz, kx, ucols):
    """The non-dominated node whose k1 dominates that of ``x`` (not worse in
    any used component, better in one) and that comes *last* in the key
    order (it leaves the open list last, so ``x`` is re-examined as seldom
    as possible), or -1; leaves k1(x) in ``kx``."""
    u = ucols.shape[0]
    for t in range(u):
        kx[t] = K[x, ucols[t]]
    best = -1
    sz[2] += sz[0]
    for i in range(sz[0]):
        better = False
        dominated = True
        for t in range(u):
            a = NDK[i, t]
            if a > kx[t]:
                dominated = False
                break
            if a < kx[t]:
                better = True
        if dominated and better:
            y = ndl[i]
            if best < 0 or _kbefore(K, best, y, ucols):
                best = y
    return best


@numba.njit(cache=True)
def _open_insert(x, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto):
    """Insert node ``x`` (its key already in ``K[x]``) into the open list."""
    sz[4] += 1
    if not pareto:
        _nd_add(x, K, S, ndl, NDK, hn, hk, sz, ucols)
        return
    y = _find_dominator(x, K, ndl, NDK, sz, kx, ucols)
    if y >= 0:
        _attach(S, x, y)
        return
    # x is non-dominated: the non-dominated nodes it dominates are filed
    # under it, with everything that was filed under them
    u = ucols.shape[0]
    i = 0
    while i < sz[0]:
        better = False
        dominates = True
        for t in range(u):
            a = NDK[i, t]
            if kx[t] > a:
                dominates = False
                break
            if kx[t] < a:
                better = True
        if dominates and better:
            z = ndl[i]
            _nd_del(z, K, S, ndl, NDK, hn, hk, sz, ucols)  # the last member moves into slot i
            _splice(S, z, x)
            _attach(S, z, x)
        else:
            i += 1
    _nd_add(x, K, S, ndl, NDK, hn, hk, sz, ucols)


@numba.njit(cache=True)
def _open_remove(x, K, S, ndl, NDK, hn, hk, sz, kx, buf, ucols, pareto):
    """Remove node ``x`` from the open list; the nodes filed under it are
    inserted again (compared with the non-dominated nodes only)."""
    st = S[x, _ST]
    if st == _DOMINATED:
        _detach(S, x)
    elif st == _ND:
        _nd_del(x, K, S, ndl, NDK, hn, hk, sz, ucols)
        if pareto and S[x, _CH] >= 0:
            m = 0
            c = S[x, _CH]
            while c >= 0:
                buf[m] = c
                m += 1
                c = S[c, _NX]
            S[x, _CH] = -1
            sz[3] += m
            for i in range(m):
                c = buf[i]
                S[c, _DOM] = -1
                S[c, _NX] = -1
                S[c, _PV] = -1
                S[c, _ST] = _OUT
                _open_insert(c, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto)
    S[x, _ST] = _OUT


@numba.njit(cache=True)
def _open_reset(S, sz):
    for i in range(S.shape[0]):
        for j in range(S.shape[1]):
            S[i, j] = -1
        S[i, _ST] = _OUT
    for i in range(sz.shape[0]):
        sz[i] = 0


# ---------------------------------------------------------------------------
# A*-PO (forward search)
# ---------------------------------------------------------------------------


@numba.njit(cache=True, inline="always")
def _astar_key(K, x, V, C, t, w, wts):
    """k1 = g(x) + h(x, goal), k2 = h(x, goal) (deeper nodes first on ties)."""
    m = wts.shape[1]
    ha, hb = _octile_counts(x, t, w)
    K[x, 0] = (C[x, 0] + ha) + (C[x, 1] + hb) * SQRT2
    K[x, m] = ha + hb * SQRT2
    for j in range(1, m):
        K[x, j] = V[x, j]
        K[x, m + j] = 0.0
    _finish_key(K, x, wts)


@numba.njit(cache=True)
def _astar_kernel(
    s,
    t,
    occ,
    cc,
    kind,
    cells,
    soltab,
    khat,
    wts,
    ucols,
    pareto,
    V,
    C,
    K,
    S,
    ndl,
    NDK,
    hn,
    hk,
    sz,
    kx,
    buf,
    parent,
    closed,
):
    """A* over cost vectors from cell ``s`` to ``t``; slots: g(x) = x,
    scratch ``n``. Returns ``(path cell indices, expansions)`` (empty when
    the goal is unreachable)."""
    h, w = occ.shape
    n = h * w
    tmp = n
    _open_reset(S, sz)
    for i in range(n):
        closed[i] = False
        parent[i] = -2  # -2: not reached yet
    C[s, 0] = 0  # g(s) = 0
    C[s, 1] = 0
    for j in range(V.shape[1]):
        V[s, j] = 0.0
    parent[s] = -1
    _astar_key(K, s, V, C, t, w, wts)
    _open_insert(s, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto)
    expansions = 0
    reached = False
    while sz[1] > 0:
        u = hn[0]  # smallest priority among the non-dominated
        _open_remove(u, K, S, ndl, NDK, hn, hk, sz, kx, buf, ucols, pareto)
        closed[u] = True
        expansions += 1
        if u == t:
            reached = True
            break
        for d in range(8):
            if not _passable(occ, cc, u, d, w):
                continue
            v = _neighbour(u, d, h, w)
            if closed[v]:
                continue
            _vedge(V, C, tmp, u, u, v, d, kind, cells, soltab, khat, wts)
            if parent[v] == -2:
                _vcopy(V, C, v, tmp)
                parent[v] = u
                _astar_key(K, v, V, C, t, w, wts)
                _open_insert(v, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto)
            elif _vcmp(V, C, tmp, v, ucols) < 0:
                _open_remove(v, K, S, ndl, NDK, hn, hk, sz, kx, buf, ucols, pareto)
                _vcopy(V, C, v, tmp)
                parent[v] = u
                _astar_key(K, v, V, C, t, w, wts)
                _open_insert(v, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto)
    if not reached:
        return np.empty(0, np.int64), expansions
    m = 0
    v = t
    while v != -1:
        m += 1
        v = parent[v]
    out = np.empty(m, np.int64)
    v = t
    for i in range(m - 1, -1, -1):
        out[i] = v
        v = parent[v]
    return out, expansions


# ---------------------------------------------------------------------------
# D*-PO (D* Lite over cost vectors; backward search)
# ---------------------------------------------------------------------------
# slots: g(s) = s, rhs(s) = n + s, scratch 2n, 2n + 1, 2n + 2
# key rows: K[s] for s in U, scratch rows n (the start's key) and n + 1


@numba.njit(cache=True, inline="always")
def _dstar_key(K, row, x, V, C, start, w, km, wts, ucols):
    """CalculateKey(x) into row ``row``:
    [min(g(x), rhs(x)) + h(s_start, x) + km; min(g(x), rhs(x))]."""
    n = K.shape[0] - 2
    m = wts.shape[1]
    src = x if _vcmp(V, C, x, n + x, ucols) <= 0 else n + x
    if C[src, 0] < 0:  # both infinite: the key is infinite
        for j in range(K.shape[1]):
            K[row, j] = INF
    else:
        ha, hb = _octile_counts(start, x, w)
        K[row, 0] = (C[src, 0] + ha + km[0]) + (C[src, 1] + hb + km[1]) * SQRT2
        K[row, m] = V[src, 0]
        for j in range(1, m):
            K[row, j] = V[src, j]
            K[row, m + j] = V[src, j]
        _finish_key(K, row, wts)


@numba.njit(cache=True)
def _update_vertex(u, start, w, km, wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk, sz, kx, buf):
    """UpdateVertex(u)."""
    n = K.shape[0] - 2
    in_u = S[u, _ST] != _OUT
    if _vcmp(V, C, u, n + u, ucols) != 0:  # g(u) != rhs(u)
        if in_u:  # U.Update(u, CalculateKey(u))
            _dstar_key(K, n + 1, u, V, C, start, w, km, wts, ucols)
            same = True
            for j in range(K.shape[1]):
                if K[n + 1, j] != K[u, j]:
                    same = False
                    break
            if same:
                return
            _open_remove(u, K, S, ndl, NDK, hn, hk, sz, kx, buf, ucols, pareto)
            for j in range(K.shape[1]):
                K[u, j] = K[n + 1, j]
        else:  # U.Insert(u, CalculateKey(u))
            _dstar_key(K, u, u, V, C, start, w, km, wts, ucols)
        _open_insert(u, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto)
    elif in_u:  # U.Remove(u)
        _open_remove(u, K, S, ndl, NDK, hn, hk, sz, kx, buf, ucols, pareto)


@numba.njit(cache=True)
def _min_succ(s, dst, occ, cc, kind, cells, soltab, khat, wts, ucols, V, C):
    """Slot ``dst`` = min over s' in Succ(s) of c(s, s') + g(s')."""
    h, w = occ.shape
    tmp = 2 * h * w + 2
    _vinf(V, C, dst)
    for d in range(8):
        if not _passable(occ, cc, s, d, w):
            continue
        v = _neighbour(s, d, h, w)
        _vedge(V, C, tmp, v, s, v, d, kind, cells, soltab, khat, wts)
        if _vcmp(V, C, tmp, dst, ucols) < 0:
            _vcopy(V, C, dst, tmp)


@numba.njit(cache=True)
def _dstar_insert(x, start, km, w, wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk, sz, kx):
    """U.Insert(x, CalculateKey(x)) (Initialize() inserts the goal)."""
    _dstar_key(K, x, x, V, C, start, w, km, wts, ucols)
    _open_insert(x, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto)


@numba.njit(cache=True)
def _compute_shortest_path(
    start,
    goal,
    km,
    occ,
    cc,
    kind,
    cells,
    soltab,
    khat,
    wts,
    ucols,
    pareto,
    V,
    C,
    K,
    S,
    ndl,
    NDK,
    hn,
    hk,
    sz,
    kx,
    buf,
):
    """ComputeShortestPath(); returns the number of expansions."""
    h, w = occ.shape
    n = h * w
    t0 = 2 * n
    gold = 2 * n + 1
    expansions = 0
    while True:
        # while (U.TopKey() < CalculateKey(s_start) OR rhs(s_start) > g(s_start))
        _dstar_key(K, n, start, V, C, start, w, km, wts, ucols)
        top_less = sz[1] > 0 and _kcmp(K, hn[0], n, ucols) < 0
        if not (top_less or _vcmp(V, C, n + start, start, ucols) > 0):
            break
        if sz[1] == 0:  # cannot happen
            break
        u = hn[0]  # u = U.Top()
        _dstar_key(K, n + 1, u, V, C, start, w, km, wts, ucols)  # k_new = CalculateKey(u)
        if _kcmp(K, u, n + 1, ucols) < 0:  # if (k_old < k_new)
            _open_remove(u, K, S, ndl, NDK, hn, hk, sz, kx, buf, ucols, pareto)
            for j in range(K.shape[1]):  # U.Update(u, k_new)
                K[u, j] = K[n + 1, j]
            _open_insert(u, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto)
        elif _vcmp(V, C, u, n + u, ucols) > 0:  # else if (g(u) > rhs(u))
            expansions += 1
            _vcopy(V, C, u, n + u)  # g(u) = rhs(u)
            _open_remove(u, K, S, ndl, NDK, hn, hk, sz, kx, buf, ucols, pareto)  # U.Remove(u)
            for d in range(8):  # for all s in Pred(u)
                s = _neighbour(u, d, h, w)
                if s < 0:
                    continue
                back = (d + 4) & 7  # the move s -> u
                if s != goal and _passable(occ, cc, s, back, w):
                    # rhs(s) = min(rhs(s), c(s, u) + g(u))
                    _vedge(V, C, t0, u, s, u, back, kind, cells, soltab, khat, wts)
                    if _vcmp(V, C, t0, n + s, ucols) < 0:
                        _vcopy(V, C, n + s, t0)
                _update_vertex(s, start, w, km, wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk, sz, kx, buf)
        else:
            expansions += 1
            _vcopy(V, C, gold, u)  # g_old = g(u)
            _vinf(V, C, u)  # g(u) = inf
            for d in range(8):  # for all s in Pred(u)
                s = _neighbour(u, d, h, w)
                if s < 0:
                    continue
                back = (d + 4) & 7
                if s != goal and _passable(occ, cc, s, back, w):
                    _vedge(V, C, t0, gold, s, u, back, kind, cells, soltab, khat, wts)
                    if _vcmp(V, C, n + s, t0, ucols) == 0:  # if (rhs(s) = c(s, u) + g_old)
                        # rhs(s) = min over s' of c(s, s') + g(s')
                        _min_succ(s, n + s, occ, cc, kind, cells, soltab, khat, wts, ucols, V, C)
                _update_vertex(s, start, w, km, wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk, sz, kx, buf)
            # ... and s = u (no self loops: rhs(u) does not depend on g(u))
            _update_vertex(u, start, w, km, wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk, sz, kx, buf)
    return expansions


@numba.njit(cache=True)
def _update_changed_edges(
    occ_old,
    sources,
    start,
    goal,
    km,
    occ,
    cc,
    kind,
    cells,
    soltab,
    khat,
    wts,
    ucols,
    pareto,
    V,
    C,
    K,
    S,
    ndl,
    NDK,
    hn,
    hk,
    sz,
    kx,
    buf,
):
    """for all directed edges (u, v) with changed edge costs: update c(u, v)
    and rhs(u); UpdateVertex(u). Only passability changes (the cost values
    are static); ``sources`` lists every cell whose outgoing edges may have
    changed."""
    h, w = occ.shape
    n = h * w
    t0 = 2 * n
    for i in range(sources.shape[0]):
        u = sources[i]
        for d in range(8):
            v = _neighbour(u, d, h, w)
            if v < 0:
                continue
            was = _passable(occ_old, cc, u, d, w)
            now = _passable(occ, cc, u, d, w)
            if was == now:
                continue
            if u != goal:
                _vedge(V, C, t0, v, u, v, d, kind, cells, soltab, khat, wts)  # c(u, v) + g(v)
                if now:  # if (c_old > c(u, v))
                    if _vcmp(V, C, t0, n + u, ucols) < 0:
                        _vcopy(V, C, n + u, t0)
                elif _vcmp(V, C, n + u, t0, ucols) == 0:  # else if (rhs(u) = c_old + g(v))
                    _min_succ(u, n + u, occ, cc, kind, cells, soltab, khat, wts, ucols, V, C)
            _update_vertex(u, start, w, km, wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk, sz, kx, buf)


@numba.njit(cache=True)
def _extract_path(start, goal, occ, cc, kind, cells, soltab, khat, wts, ucols, V, C):
    """Follow argmin over s' of c(s, s') + g(s') from s_start to s_goal (ties:
    first direction in E, NE, N, ... order). Empty when stuck."""
    h, w = occ.shape
    n = h * w
    best = 2 * n + 1
    tmp = 2 * n + 2
    out = np.empty(n + 1, np.int64)
    out[0] = start
    m = 1
    s = start
    while s != goal:
        if m > n:
            return np.empty(0, np.int64)
        _vinf(V, C, best)
        nxt = -1
        for d in range(8):
            if not _passable(occ, cc, s, d, w):
                continue
            v = _neighbour(s, d, h, w)
            _vedge(V, C, tmp, v, s, v, d, kind, cells, soltab, khat, wts)
            if _vcmp(V, C, tmp, best, ucols) < 0:
                _vcopy(V, C, best, tmp)
                nxt = v
        if nxt < 0:
            return np.empty(0, np.int64)
        out[m] = nxt
        m += 1
        s = nxt
    return out[:m].copy()


# ---------------------------------------------------------------------------
# the model: objectives, normalisers, priority
# ---------------------------------------------------------------------------
