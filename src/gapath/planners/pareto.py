"""Multi-objective graph search on layered costmaps: A*-PO, D*-PO and the
weighted-sum A* and D* baselines of A. Lavin, "A Pareto optimal D* search
algorithm for multiobjective path planning".

The search problem
    The graph is the 8-connected grid of the costmap's workspace (SPEC moves,
    corner rule included). Every objective is a *cost sum* along the path
    ("the aim is to minimize these four cost sums", paper section II-A); a
    step ``u -> v`` in direction ``d`` costs, per objective,

    * ``length``: the step length, 1 or sqrt(2) (cell units);
    * a cell layer (``elevation``, ``risk``, user layers): its value at ``v``
      (the start cell's value is a constant added to every path);
    * ``solar``: ``sigma(d, k(u))`` (:meth:`gapath.costmap.Costmap.solar_cost`)
      at the step index ``k(u)``.

    The solar layer is *dynamic*: its cost depends on when a cell is left.
    An exact treatment would search (cell, step index) pairs; instead, the
    search uses the static estimate ``k(u)`` = Chebyshev distance from the
    planner's start (origin) to ``u``: the earliest step at which the rover
    can stand on ``u``. It is exact for every path whose steps all move one
    cell further from the start in Chebyshev distance, keeps the graph static
    (so D* replanning is exact and A*-PO and D*-PO solve the same problem),
    and it is only used inside the search: the returned objectives are
    always recomputed on the path with its true step indices.

    Lengths are carried as integer step counts (straight, diagonal), so two
    partial paths with the same counts have bit-identical lengths (SPEC) and
    ties in length are exact.

Priority and tie-breaking (the total order of cost vectors)
    Cost vectors ``a, b`` (one component per objective) are compared by

    1. the *priority* ``p = sum_j w_j a_j / N_j``,
    2. the *secondary* cost ``s = sum_j a_j / N_j`` (normalised, equal weights),
    3. the components themselves, lexicographically in objective order,

    with the normalisers ``N_j`` = the *mean* cost of one step in objective
    ``j`` on the map, so that every objective weighs about the same in the
    total of a typical path: 1 for length (a step costs 1 or sqrt(2)), 1/2
    for solar (the mean of ``sigma`` over the directions) and the mean of
    the layer over the whole grid for a cell layer (over all cells, so that
    it does not change when cells are blocked; 1 if the layer is all zero).
    (Dividing by the largest per-step cost instead makes the length
    dominate the fractional layer costs: the weighted sum then returns the
    shortest path on every map of the Mars study.) A weighted-sum planner
    uses ``p = s`` with its weights; a Pareto planner uses the configurable
    ``priority`` (by default its first objective, "a preferred criterion" of
    the paper).

A*-PO and D*-PO (paper section III-B and Fig. 1)
    Every open node is projected into objective space by its key vector
    ``f = g + h`` (one dimension per objective; ``h`` is the octile distance
    to the goal for ``length`` and 0 for the other objectives, admissible
    and consistent). The open list keeps, *incrementally*, its non-dominated
    set: a new node is compared with the non-dominated nodes only (if it is
    not dominated, the non-dominated nodes it dominates leave the set); a
    dominated node is filed under one non-dominated node that dominates it
    (the one that comes last in the order below, so that it is re-examined
    as seldom as possible), and when that node leaves the open list only the
    nodes filed under it are inserted again. Dominance is transitive, so
    nothing else can change. At every step the node expanded is, among the
    non-dominated open nodes, the one with the smallest priority (ties:
    secondary cost, components, key ``k2``, cell index), taken from a
    binary heap over the non-dominated nodes.

    Because a node that is dominated always has a strictly larger secondary
    cost than its dominator, the node chosen is also the smallest open node
    in the total order above, and the search is an A* (a D* Lite) over
    cost vectors ordered by it. Hence the guarantee: the returned path
    minimises the order over all paths, so *no path dominates it* in the
    search's cost sums (with the solar estimate above; exactly when the
    solar vector does not turn, ``solar_rate = 0``). With ``priority =
    "length"`` the path is a shortest path and, among the shortest paths,
    the one with the smallest normalised sum of the other objectives.

D*-PO
    :class:`DStarPO` is D* Lite (S. Koenig, M. Likhachev, AAAI 2002, the
    optimized version with ``km``; see :mod:`gapath.planners.dstar_lite`)
    over cost vectors: ``g``, ``rhs`` and the keys
    ``[min(g, rhs) + h(s_start, s) + km; min(g, rhs)]`` are vectors compared
    by the order above, and ``U.Top()`` is chosen through the incremental
    non-dominated set of the first key vectors. It searches backwards from
    the goal and keeps D*'s replanning: :meth:`DStarPO.update_cells` repairs
    the edges around changed cells and :meth:`DStarPO.replan` returns what a
    fresh plan on the new map returns (the step-index origin of the solar
    estimate stays the first start, the "mission clock").

Weighted-sum baselines (the paper's A* and D*)
    :func:`weighted_sum_astar` and :class:`WeightedSumDStar` minimise
    ``sum_j w_j G_j / N_j`` (equal weights by default) with the same kernels
    but a plain priority queue (no Pareto filter). The paper renormalises
    the costs over the open list at every step; a static normalisation is
    used here so that the searches stay exact (A* and D* then return paths
    of equal cost).

Path objectives (the returned ``F``)
    Recomputed on the returned path by
    :meth:`gapath.costmap.Costmap.evaluate_path`: F1 ``length`` (times
    ``cell_size``), F2 ``elevation`` = mean over the waypoints (eq. 5),
    F3 ``solar`` = sum over the steps with their true indices (eq. 6),
    F4 ``risk`` = mean over the waypoints (eq. 7); user layers: mean over
    the waypoints.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numba
import numpy as np

from gapath.errors import ConfigError, NoPathError
from gapath.planners._grid import DC, DR, can_step, check_cell
from gapath.planners._incremental import IncrementalGridPlanner

__all__ = [
    "ParetoPlanResult", "astar_po", "weighted_sum_astar", "DStarPO", "WeightedSumDStar",
    "plan", "PLANNERS", "DEFAULT_OBJECTIVES",
]

SQRT2 = math.sqrt(2.0)
INF = np.inf

#: The paper's four objectives F1..F4.
DEFAULT_OBJECTIVES = ("length", "elevation", "solar", "risk")

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
            _nd_del(z, K, S, ndl, NDK, hn, hk, sz, ucols)   # the last member moves into slot i
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
def _astar_kernel(s, t, occ, cc, kind, cells, soltab, khat, wts, ucols, pareto,
                  V, C, K, S, ndl, NDK, hn, hk, sz, kx, buf, parent, closed):
    """A* over cost vectors from cell ``s`` to ``t``; slots: g(x) = x,
    scratch ``n``. Returns ``(path cell indices, expansions)`` (empty when
    the goal is unreachable)."""
    h, w = occ.shape
    n = h * w
    tmp = n
    _open_reset(S, sz)
    for i in range(n):
        closed[i] = False
        parent[i] = -2                       # -2: not reached yet
    C[s, 0] = 0                              # g(s) = 0
    C[s, 1] = 0
    for j in range(V.shape[1]):
        V[s, j] = 0.0
    parent[s] = -1
    _astar_key(K, s, V, C, t, w, wts)
    _open_insert(s, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto)
    expansions = 0
    reached = False
    while sz[1] > 0:
        u = hn[0]                            # smallest priority among the non-dominated
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
    if C[src, 0] < 0:                                # both infinite: the key is infinite
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
    if _vcmp(V, C, u, n + u, ucols) != 0:           # g(u) != rhs(u)
        if in_u:                                     # U.Update(u, CalculateKey(u))
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
        else:                                        # U.Insert(u, CalculateKey(u))
            _dstar_key(K, u, u, V, C, start, w, km, wts, ucols)
        _open_insert(u, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto)
    elif in_u:                                       # U.Remove(u)
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
def _compute_shortest_path(start, goal, km, occ, cc, kind, cells, soltab, khat, wts, ucols,
                           pareto, V, C, K, S, ndl, NDK, hn, hk, sz, kx, buf):
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
        if sz[1] == 0:                                   # cannot happen
            break
        u = hn[0]                                        # u = U.Top()
        _dstar_key(K, n + 1, u, V, C, start, w, km, wts, ucols)   # k_new = CalculateKey(u)
        if _kcmp(K, u, n + 1, ucols) < 0:                # if (k_old < k_new)
            _open_remove(u, K, S, ndl, NDK, hn, hk, sz, kx, buf, ucols, pareto)
            for j in range(K.shape[1]):                  # U.Update(u, k_new)
                K[u, j] = K[n + 1, j]
            _open_insert(u, K, S, ndl, NDK, hn, hk, sz, kx, ucols, pareto)
        elif _vcmp(V, C, u, n + u, ucols) > 0:           # else if (g(u) > rhs(u))
            expansions += 1
            _vcopy(V, C, u, n + u)                       # g(u) = rhs(u)
            _open_remove(u, K, S, ndl, NDK, hn, hk, sz, kx, buf, ucols, pareto)   # U.Remove(u)
            for d in range(8):                           # for all s in Pred(u)
                s = _neighbour(u, d, h, w)
                if s < 0:
                    continue
                back = (d + 4) & 7                       # the move s -> u
                if s != goal and _passable(occ, cc, s, back, w):
                    # rhs(s) = min(rhs(s), c(s, u) + g(u))
                    _vedge(V, C, t0, u, s, u, back, kind, cells, soltab, khat, wts)
                    if _vcmp(V, C, t0, n + s, ucols) < 0:
                        _vcopy(V, C, n + s, t0)
                _update_vertex(s, start, w, km, wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk,
                               sz, kx, buf)
        else:
            expansions += 1
            _vcopy(V, C, gold, u)                        # g_old = g(u)
            _vinf(V, C, u)                               # g(u) = inf
            for d in range(8):                           # for all s in Pred(u)
                s = _neighbour(u, d, h, w)
                if s < 0:
                    continue
                back = (d + 4) & 7
                if s != goal and _passable(occ, cc, s, back, w):
                    _vedge(V, C, t0, gold, s, u, back, kind, cells, soltab, khat, wts)
                    if _vcmp(V, C, n + s, t0, ucols) == 0:   # if (rhs(s) = c(s, u) + g_old)
                        # rhs(s) = min over s' of c(s, s') + g(s')
                        _min_succ(s, n + s, occ, cc, kind, cells, soltab, khat, wts, ucols, V, C)
                _update_vertex(s, start, w, km, wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk,
                               sz, kx, buf)
            # ... and s = u (no self loops: rhs(u) does not depend on g(u))
            _update_vertex(u, start, w, km, wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk, sz,
                           kx, buf)
    return expansions


@numba.njit(cache=True)
def _update_changed_edges(occ_old, sources, start, goal, km, occ, cc, kind, cells, soltab, khat,
                          wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk, sz, kx, buf):
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
                _vedge(V, C, t0, v, u, v, d, kind, cells, soltab, khat, wts)   # c(u, v) + g(v)
                if now:                                      # if (c_old > c(u, v))
                    if _vcmp(V, C, t0, n + u, ucols) < 0:
                        _vcopy(V, C, n + u, t0)
                elif _vcmp(V, C, n + u, t0, ucols) == 0:     # else if (rhs(u) = c_old + g(v))
                    _min_succ(u, n + u, occ, cc, kind, cells, soltab, khat, wts, ucols, V, C)
            _update_vertex(u, start, w, km, wts, ucols, pareto, V, C, K, S, ndl, NDK, hn, hk, sz,
                           kx, buf)


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

class _Model:
    """Everything the kernels need about the costs, built from a costmap."""

    def __init__(self, costmap, objectives, origin, *, pareto, priority=None, weights=None):
        self.costmap = costmap
        self.objectives = costmap.check_objectives(objectives)
        ws = costmap.workspace
        h, w = ws.shape
        n = h * w
        others = [o for o in self.objectives if o != "length"]
        self.columns = ("length",) + tuple(others)        # internal column order
        m = len(self.columns)
        kind = np.zeros(m, np.int64)
        cells = np.zeros((m, n))
        scale = np.ones(m)                                 # N_j: mean cost of a step
        for j, name in enumerate(self.columns[1:], start=1):
            if name == "solar":
                kind[j] = _SOLAR
                scale[j] = 0.5
            else:
                kind[j] = _CELL
                arr = costmap.layer(name)
                cells[j] = arr.ravel()
                mean = float(arr.mean())
                scale[j] = mean if mean > 0 else 1.0
        used = np.array([("length" in self.objectives)] + [True] * (m - 1))
        self.used = used
        self.scale = scale
        # user order -> internal column
        self.order = np.array([self.columns.index(o) for o in self.objectives], np.int64)
        sw = np.where(used, 1.0 / scale, 0.0)
        if pareto:
            pw = self._priority(priority, used, scale)
        else:
            pw = self._weights(weights, used, scale)
            sw = pw.copy()
        self.wts = np.ascontiguousarray(np.vstack([pw, sw]))
        # solar: static step-index estimate = Chebyshev distance from the origin
        orow, ocol = origin
        rr, cc = np.mgrid[0:h, 0:w]
        self.khat = np.maximum(np.abs(rr - orow), np.abs(cc - ocol)).ravel().astype(np.int64)
        self.soltab = costmap.solar_table(max(h, w))
        self.occ = np.array(ws.occ, dtype=np.bool_, order="C", copy=True)
        self.cc = bool(ws.corner_cutting)
        self.kind = kind
        self.cells = np.ascontiguousarray(cells)
        self.ucols = np.flatnonzero(used).astype(np.int64)
        self.pareto = bool(pareto)

    def costs(self) -> tuple:
        """The kernels' cost arguments ``(kind, cells, soltab, khat, wts)``."""
        return self.kind, self.cells, self.soltab, self.khat, self.wts

    def arrays(self, n: int, n_slots: int) -> tuple:
        """Fresh search arrays: slots ``(V, C)`` and the open list ``(K, S,
        ndl, NDK, hn, hk, sz, kx, buf)``."""
        m = len(self.columns)
        u = max(len(self.ucols), 1)
        return (np.zeros((n_slots, m + 2)), np.zeros((n_slots, 2), np.int64),
                np.zeros((n + 2, 2 * m + 4)), np.full((n, 7), -1, np.int64),
                np.zeros(n, np.int64), np.zeros((n, u)), np.zeros(n, np.int64),
                np.zeros((n, 2)), np.zeros(8, np.int64), np.zeros(u), np.zeros(n, np.int64))

    def _priority(self, priority, used, scale) -> np.ndarray:
        m = len(self.columns)
        if priority is None:
            priority = self.objectives[0]
        if isinstance(priority, str):
            if priority == "sum":
                return np.where(used, 1.0 / scale, 0.0)
            if priority not in self.objectives:
                raise ConfigError(
                    f"priority {priority!r} must be 'sum', one of the objectives "
                    f"({', '.join(self.objectives)}) or a sequence of weights")
            pw = np.zeros(m)
            j = self.columns.index(priority)
            pw[j] = 1.0 / scale[j]
            return pw
        return self._weights(priority, used, scale, label="priority")

    def _weights(self, weights, used, scale, label="weights") -> np.ndarray:
        m = len(self.columns)
        if weights is None:
            return np.where(used, 1.0 / scale, 0.0)
        try:
            wv = np.asarray(weights, dtype=np.float64)
        except (TypeError, ValueError):
            raise ConfigError(f"{label} must be a sequence of numbers, got {weights!r}") from None
        if wv.shape != (len(self.objectives),):
            raise ConfigError(f"{label} needs one weight per objective "
                              f"({len(self.objectives)}: {', '.join(self.objectives)}), "
                              f"got {weights!r}")
        if not np.all(np.isfinite(wv)) or (wv < 0).any() or not (wv > 0).any():
            raise ConfigError(f"{label} must be finite, >= 0 and not all 0, got {weights!r}")
        out = np.zeros(m)
        for name, v in zip(self.objectives, wv):
            j = self.columns.index(name)
            out[j] = v / scale[j]
        return out

    def search_vector(self, path_idx: np.ndarray) -> np.ndarray:
        """The search's cost sums of a path (user order; cell layers include
        the start cell; solar with the static step-index estimate; length in
        cell units times ``cell_size``)."""
        kind, cells, soltab, khat = self.kind, self.cells, self.soltab, self.khat
        w = self.occ.shape[1]
        r, c = path_idx // w, path_idx % w
        dr, dc = np.diff(r), np.diff(c)
        diag = (dr != 0) & (dc != 0)
        out = np.zeros(len(self.columns))
        out[0] = ((len(dr) - diag.sum()) + SQRT2 * diag.sum()) * self.costmap.workspace.cell_size
        dirs = np.array([[3, 2, 1], [4, -1, 0], [5, 6, 7]])[dr + 1, dc + 1]
        for j in range(1, len(self.columns)):
            if kind[j] == _CELL:
                out[j] = cells[j, path_idx].sum()
            else:
                out[j] = soltab[khat[path_idx[:-1]], dirs].sum()
        return out[self.order]


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class ParetoPlanResult:
    """Result of a multi-objective single-path planner.

    Attributes
    ----------
    path : (m, 2) int64 array
        Cells ``(row, col)`` from the start to the goal (read-only).
    objectives : tuple of str
        Objective names (the order of ``F``).
    F : (k,) float array
        The path's objectives, recomputed on the path (module docstring:
        F1 length, F2 mean elevation, F3 solar sum, F4 mean risk).
    search_cost : (k,) float array
        The search's cost sums of the path (cell layers summed over the
        waypoints, solar with the static step-index estimate): the vector
        the planner minimises in its order.
    length : float
        Euclidean length times ``cell_size``.
    expansions : int
        Vertices expanded during this call.
    seconds : float
        Wall-clock time of the call.
    planner : str
        ``astar``, ``dstar-lite``, ``astar-po`` or ``dstar-po``.
    """

    path: np.ndarray
    objectives: tuple
    F: np.ndarray
    search_cost: np.ndarray
    length: float
    expansions: int
    seconds: float
    planner: str

    @property
    def values(self) -> dict[str, float]:
        """``{objective: value}`` of ``F``."""
        return {n: float(v) for n, v in zip(self.objectives, self.F)}

    def __repr__(self) -> str:
        vals = ", ".join(f"{n}={v:.4g}" for n, v in self.values.items())
        return (f"ParetoPlanResult({self.planner}, cells={len(self.path)}, {vals}, "
                f"expansions={self.expansions}, seconds={self.seconds:.6f})")


def _result(model, idx, expansions, t0, planner) -> ParetoPlanResult:
    cm = model.costmap
    w = cm.shape[1]
    path = np.column_stack([idx // w, idx % w]).astype(np.int64)
    if len(path) == 1:
        F = np.array([0.0 if o in ("length", "solar") else float(cm.layer(o)[tuple(path[0])])
                      for o in model.objectives])
    else:
        vals = cm.evaluate_path(path, model.objectives)
        F = np.array([vals[o] for o in model.objectives])
    search = model.search_vector(idx)
    path.setflags(write=False)
    length = _length(path, cm.workspace.cell_size)
    return ParetoPlanResult(path=path, objectives=model.objectives, F=F, search_cost=search,
                            length=length, expansions=int(expansions),
                            seconds=time.perf_counter() - t0, planner=planner)


def _length(path, cell_size) -> float:
    d = np.abs(np.diff(path, axis=0))
    diag = int(np.count_nonzero((d[:, 0] != 0) & (d[:, 1] != 0)))
    return float(((len(d) - diag) + SQRT2 * diag) * cell_size)


def _no_path(ws, src, dst, expansions=None) -> NoPathError:
    h, w = ws.shape
    rule = "allowed" if ws.corner_cutting else "not allowed"
    extra = "" if expansions is None else f"; the search expanded {expansions} cells"
    return NoPathError(f"no path from start {src} to goal {dst} on the {h}x{w} grid "
                       f"(8-connected, corner cutting {rule}{extra})")


# ---------------------------------------------------------------------------
# A*: A*-PO and the weighted-sum baseline
# ---------------------------------------------------------------------------

def _check_origin(origin, default, shape):
    if origin is None:
        return default
    from gapath.costmap import _check_cell as check_any_cell

    return check_any_cell(origin, "origin", shape)


def _astar(costmap, objectives, start, goal, origin, *, pareto, priority=None, weights=None,
           planner="astar-po") -> ParetoPlanResult:
    t0 = time.perf_counter()
    ws = costmap.workspace
    occ = ws.occ
    src = check_cell(ws.start if start is None else start, "start", occ)
    dst = check_cell(ws.goal if goal is None else goal, "goal", occ)
    origin = _check_origin(origin, src, occ.shape)
    model = _Model(costmap, objectives, origin, pareto=pareto, priority=priority, weights=weights)
    h, w = occ.shape
    n = h * w
    arrays = model.arrays(n, n + 1)
    parent = np.empty(n, np.int64)
    closed = np.empty(n, np.bool_)
    idx, expansions = _astar_kernel(src[0] * w + src[1], dst[0] * w + dst[1], model.occ, model.cc,
                                    *model.costs(), model.ucols, model.pareto, *arrays,
                                    parent, closed)
    if len(idx) == 0:
        raise _no_path(ws, src, dst, expansions)
    return _result(model, idx, expansions, t0, planner)


def astar_po(costmap, objectives=DEFAULT_OBJECTIVES, *, priority=None, start=None,
             goal=None, origin=None) -> ParetoPlanResult:
    """A*-PO: A* choosing, at every step, the non-dominated open node of
    smallest priority (Lavin; see :mod:`gapath.planners.pareto`).

    Parameters
    ----------
    costmap : :class:`gapath.costmap.Costmap`
        Layers and workspace (grid, start, goal, cell size, corner rule).
    objectives : sequence of str or comma-separated str
        Among :attr:`gapath.costmap.Costmap.objective_names`; default the
        paper's ``("length", "elevation", "solar", "risk")``.
    priority : str or sequence of float, optional
        Cost that picks among the non-dominated open nodes: an objective name
        (default: the first objective), ``"sum"`` (normalised equal-weight
        sum) or one non-negative weight per objective (normalised weighted
        sum). Ties: normalised sum, then the components in objective order.
    start, goal : (row, col), optional
        Override the workspace's start and goal.
    origin : (row, col), optional
        Cell from which the solar step index is estimated (default: the
        start; see :mod:`gapath.planners.pareto`).

    Returns
    -------
    ParetoPlanResult
        The path and its objectives ``F`` (recomputed on the path).

    Raises
    ------
    ConfigError
        On an unknown, unset or repeated objective, a bad priority, or a start
        or goal outside the grid or on an obstacle.
    NoPathError
        If the goal cannot be reached.

    See Also
    --------
    DStarPO : the same search, backwards, with replanning.
    weighted_sum_astar : the weighted-sum baseline.

    Notes
    -----
    No path dominates the returned one in the search's cost sums (module
    docstring), since it is the minimum of a total order that extends
    dominance.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> from gapath.costmap import Costmap
    >>> ws = Workspace(np.zeros((3, 7), bool), start=(2, 0), goal=(2, 6))
    >>> cm = Costmap(ws, risk=(2, 3))
    >>> res = astar_po(cm, ("length", "risk"))          # priority: length
    >>> res.path.tolist()
    [[2, 0], [2, 1], [2, 2], [2, 3], [2, 4], [2, 5], [2, 6]]
    >>> [round(float(v), 4) for v in res.F]
    [6.0, 0.5317]
    >>> res = astar_po(cm, ("length", "risk"), priority="risk")
    >>> res.path.tolist()
    [[2, 0], [1, 1], [0, 2], [0, 3], [0, 4], [1, 5], [2, 6]]
    >>> [round(float(v), 4) for v in res.F]
    [7.6569, 0.1817]
    """
    return _astar(costmap, objectives, start, goal, origin, pareto=True, priority=priority,
                  planner="astar-po")


def weighted_sum_astar(costmap, objectives=DEFAULT_OBJECTIVES, *, weights=None, start=None,
                       goal=None, origin=None) -> ParetoPlanResult:
    """A* on the normalised weighted sum of the objectives (the paper's A*
    baseline): minimises ``sum_j w_j G_j / N_j`` (module docstring), equal
    weights by default.

    Parameters
    ----------
    costmap, objectives, start, goal, origin : see :func:`astar_po`.
    weights : sequence of float, optional
        One non-negative weight per objective (not all zero); default 1 each.

    Returns
    -------
    ParetoPlanResult

    Raises
    ------
    ConfigError, NoPathError
        As :func:`astar_po`.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> from gapath.costmap import Costmap
    >>> ws = Workspace(np.zeros((3, 7), bool), start=(2, 0), goal=(2, 6))
    >>> cm = Costmap(ws, risk=(2, 3))
    >>> weighted_sum_astar(cm, ("length", "risk")).path.tolist()
    [[2, 0], [1, 1], [0, 2], [0, 3], [0, 4], [1, 5], [2, 6]]
    >>> weighted_sum_astar(cm, ("length", "risk"), weights=(1, 0.01)).path.tolist()
    [[2, 0], [2, 1], [2, 2], [2, 3], [2, 4], [2, 5], [2, 6]]
    """
    return _astar(costmap, objectives, start, goal, origin, pareto=False, weights=weights,
                  planner="astar")


# ---------------------------------------------------------------------------
# D*: D*-PO and the weighted-sum baseline
# ---------------------------------------------------------------------------

class DStarPO(IncrementalGridPlanner):
    """D*-PO: D* Lite over cost vectors with Pareto selection of ``U.Top()``
    (Lavin; see :mod:`gapath.planners.pareto`), with replanning.

    The planner keeps its own copy of the occupancy grid; the layers are
    static. Cells are blocked or freed with :meth:`update_cells`, the robot
    is advanced with :meth:`move_to`, and :meth:`replan` repairs the previous
    search; every result equals (in objective values; the cells may differ
    only between paths of equal cost) what a fresh planner returns on
    :attr:`workspace`.

    Parameters
    ----------
    costmap : :class:`gapath.costmap.Costmap`
    objectives, priority : see :func:`astar_po`.
    start, goal : (row, col), optional
        Override the workspace's start (the robot's cell) and goal.
    origin : (row, col), optional
        Cell from which the solar step index is estimated (default: the
        start; it stays fixed when the robot moves).

    Raises
    ------
    ConfigError
        On bad objectives or priority, or a start or goal outside the grid or
        on an obstacle.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> from gapath.costmap import Costmap
    >>> cm = Costmap(Workspace(np.zeros((5, 5), bool)), risk=(2, 2))
    >>> planner = DStarPO(cm, ("length", "risk"))
    >>> [round(float(v), 4) for v in planner.plan().F]
    [5.6569, 0.45]
    >>> planner.update_cells([(2, 2), (1, 1)], blocked=True)
    2
    >>> [round(float(v), 4) for v in planner.replan().F]
    [6.2426, 0.4417]
    """

    _pareto = True
    _name = "dstar-po"

    def __init__(self, costmap, objectives=DEFAULT_OBJECTIVES, *, priority=None, start=None,
                 goal=None, origin=None):
        self._setup(costmap, objectives, start, goal, origin, priority=priority)

    def _setup(self, costmap, objectives, start, goal, origin, *, priority=None, weights=None):
        ws = costmap.workspace
        occ = np.array(ws.occ, dtype=np.bool_, order="C", copy=True)
        self._occ = occ
        self._start = check_cell(ws.start if start is None else start, "start", occ)
        self._goal = check_cell(ws.goal if goal is None else goal, "goal", occ)
        self.costmap = costmap
        self.origin = _check_origin(origin, self._start, occ.shape)
        self._model = _Model(costmap, objectives, self.origin, pareto=self._pareto,
                             priority=priority, weights=weights)
        self._model.occ = occ                     # the planner's own, changing grid
        n = occ.size
        self._arrays = self._model.arrays(n, 2 * n + 3)
        self._V, self._C = self._arrays[:2]
        self._km = np.zeros(2, np.int64)
        self._last = self._start
        self._initialized = False

    # -- state ------------------------------------------------------------
    @property
    def objectives(self) -> tuple[str, ...]:
        return self._model.objectives

    @property
    def workspace(self):
        """The current map as a :class:`~gapath.workspace.Workspace`
        (start = the robot's cell)."""
        from gapath.workspace import Workspace

        ws = self.costmap.workspace
        return Workspace(self._occ.copy(), self._start, self._goal, cell_size=ws.cell_size,
                         corner_cutting=ws.corner_cutting, name=ws.name)

    def plan(self) -> ParetoPlanResult:
        """Search from scratch: Initialize(), then ComputeShortestPath().

        Raises
        ------
        NoPathError
            If the goal is unreachable (the planner stays usable).
        """
        t0 = time.perf_counter()
        n = self._occ.size
        V, C = self._V, self._C
        V[: 2 * n] = INF                                         # rhs(s) = g(s) = inf
        C[: 2 * n, 0] = -1
        C[: 2 * n, 1] = 0
        V, C, K, S, ndl, NDK, hn, hk, sz, kx, buf = self._arrays
        _open_reset(S, sz)                                       # U = empty
        self._km[:] = 0                                          # km = 0
        self._last = self._start                                 # s_last = s_start
        goal = self._index(self._goal)
        V[n + goal] = 0.0                                        # rhs(s_goal) = 0
        C[n + goal] = 0
        model = self._model
        # U.Insert(s_goal, [h(s_start, s_goal); 0])
        _dstar_insert(goal, self._index(self._start), self._km, self._occ.shape[1], model.wts,
                      model.ucols, model.pareto, V, C, K, S, ndl, NDK, hn, hk, sz, kx)
        self._initialized = True
        return self._search(t0)

    # -- helpers -----------------------------------------------------------
    def _repair_edges(self, occ_old, src) -> None:
        model = self._model
        _update_changed_edges(occ_old, src, self._index(self._start), self._index(self._goal),
                              self._km, self._occ, model.cc, *model.costs(), model.ucols,
                              model.pareto, *self._arrays)

    def _sync_km(self) -> None:
        """km = km + h(s_last, s_start); s_last = s_start."""
        if self._last != self._start:
            w = self._occ.shape[1]
            a, b = _octile_counts(self._index(self._last), self._index(self._start), w)
            self._km[0] += a
            self._km[1] += b
            self._last = self._start

    def _search(self, t0) -> ParetoPlanResult:
        start = self._index(self._start)
        goal = self._index(self._goal)
        model = self._model
        expansions = _compute_shortest_path(start, goal, self._km, self._occ, model.cc,
                                            *model.costs(), model.ucols, model.pareto,
                                            *self._arrays)
        ws = self.costmap.workspace
        if start == goal:
            idx = np.array([start], np.int64)
        elif self._C[self._occ.size + start, 0] < 0:
            raise _no_path(ws, self._start, self._goal, expansions)
        else:
            idx = _extract_path(start, goal, self._occ, model.cc, *model.costs(), model.ucols,
                                self._V, self._C)
            if len(idx) == 0:  # pragma: no cover - would be a bug
                raise RuntimeError("D*-PO: inconsistent g-values while extracting the path")
        return _result(self._model, idx, expansions, t0, self._name)

    def __repr__(self) -> str:
        h, w = self._occ.shape
        return (f"{type(self).__name__}(shape={h}x{w}, objectives={self.objectives}, "
                f"start={self._start}, goal={self._goal})")


class WeightedSumDStar(DStarPO):
    """D* Lite on the normalised weighted sum of the objectives (the paper's
    D* baseline): :class:`DStarPO` without the Pareto filter, minimising
    ``sum_j w_j G_j / N_j``.

    Parameters
    ----------
    costmap, objectives, start, goal, origin : see :class:`DStarPO`.
    weights : sequence of float, optional
        One non-negative weight per objective; default 1 each.
    """

    _pareto = False
    _name = "dstar-lite"

    def __init__(self, costmap, objectives=DEFAULT_OBJECTIVES, *, weights=None, start=None,
                 goal=None, origin=None):
        self._setup(costmap, objectives, start, goal, origin, weights=weights)


# ---------------------------------------------------------------------------
# one entry point
# ---------------------------------------------------------------------------

#: Planner names (CLI ``gapath plan --planner``).
PLANNERS = ("astar", "dstar-lite", "astar-po", "dstar-po")


def plan(costmap, planner: str = "dstar-po", objectives=DEFAULT_OBJECTIVES, *, priority=None,
         weights=None, start=None, goal=None) -> ParetoPlanResult:
    """Plan one path with a named planner.

    Parameters
    ----------
    costmap : :class:`gapath.costmap.Costmap`
    planner : {"astar", "dstar-lite", "astar-po", "dstar-po"}
        Weighted-sum A*, weighted-sum D* Lite, A*-PO or D*-PO.
    objectives, start, goal : see :func:`astar_po`.
    priority : Pareto planners' priority (see :func:`astar_po`).
    weights : weighted-sum planners' weights.

    Raises
    ------
    ConfigError
        On an unknown planner or bad settings.
    NoPathError
        If the goal cannot be reached.
    """
    if planner == "astar":
        return weighted_sum_astar(costmap, objectives, weights=weights, start=start, goal=goal)
    if planner == "astar-po":
        return astar_po(costmap, objectives, priority=priority, start=start, goal=goal)
    if planner == "dstar-lite":
        return WeightedSumDStar(costmap, objectives, weights=weights, start=start,
                                goal=goal).plan()
    if planner == "dstar-po":
        return DStarPO(costmap, objectives, priority=priority, start=start, goal=goal).plan()
    raise ConfigError(f"unknown planner {planner!r}; expected one of {', '.join(PLANNERS)}")
