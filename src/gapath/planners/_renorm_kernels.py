"""numba kernels of the renormalised baselines of :mod:`gapath.planners.pareto`
(Lavin's A* and D*: a composite cost whose objectives are renormalised to
[0, 1] over the open list at every search step). Private: arrays only.

Shared conventions (those of :mod:`gapath.planners._pareto_kernels`)
    ``kind`` (M,) objective kinds, column 0 the length; ``cells`` (M, n) cell
    layers (a step into cell ``v`` costs ``cells[j, v]``); ``soltab`` (T, 8)
    solar cost by step-index estimate and move, ``khat`` (n,) the estimate of
    each cell (a step leaving ``u`` costs ``soltab[khat[u], d]``). Lengths are
    carried as (straight, diagonal) step counts.

The composite (one search step)
    Every open node ``x`` is projected to its cost vector ``P(x)``, one
    column per objective (the length column ``g + h`` for A*, the distance
    travelled plus the octile heuristic); column ``c`` is mapped to [0, 1] by ``(P_c - lo_c) / (hi_c - lo_c)``, the
    minimum and maximum over the open nodes *now* (a column with
    ``hi_c = lo_c`` maps to 0), and the composite is ``sum_c w_c`` times
    that. The open node of smallest composite is expanded (ties: the static
    normalised sum ``sec``, then the smaller cell index). A tentative cost
    replaces a stored one when its composite under the same step's ranges is
    smaller (ties: ``sec``), so the decision is the one the step's
    normalisation makes.
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import DC, DR, SQRT2, can_step

_CELL = 1

# node states
_NEW, _OPEN, _CLOSED = 0, 1, 2


@numba.njit(cache=True)
def _search_arrays(n, m):
    """The arrays of one search over ``n`` cells and ``m`` objective
    columns: ``G`` (n + 1, m) and ``N`` (n + 1, 2) cost sums and step
    counts (row ``n`` a scratch row), ``hlen`` (n,) the length heuristic,
    the back-pointers (-1), the node states, the open list and its
    positions (-1), and three (m,) work rows (``lo``, ``hi``, ``sw``)."""
    return (
        np.zeros((n + 1, m)),
        np.zeros((n + 1, 2), np.int64),
        np.zeros(n),
        np.full(n, -1, np.int64),
        np.zeros(n, np.int8),
        np.empty(n, np.int64),
        np.full(n, -1, np.int64),
        np.empty(m),
        np.empty(m),
        np.empty(m),
    )


@numba.njit(cache=True, inline="always")
def _passable(occ, cc, u, d, w):
    ur = u // w
    uc = u - ur * w
    if occ[ur, uc]:
        return False
    return can_step(occ, ur, uc, DR[d], DC[d], cc)


@numba.njit(cache=True, inline="always")
def _octile(a, b, w):
    ar = a // w
    br = b // w
    dr = abs(ar - br)
    dc = abs((a - ar * w) - (b - br * w))
    if dr < dc:
        return (dc - dr) + dr * SQRT2
    return (dr - dc) + dc * SQRT2


@numba.njit(cache=True, inline="always")
def _edge(G, N, x, src, frm, to, d, kind, cells, soltab, khat):
    """Row ``x`` of (G, N) = row ``src`` + the cost of the move ``frm -> to``
    in direction ``d`` (G[:, 0] recomputed from the step counts N)."""
    a = N[src, 0]
    b = N[src, 1]
    if d & 1:
        b += 1
    else:
        a += 1
    N[x, 0] = a
    N[x, 1] = b
    G[x, 0] = a + b * SQRT2
    for j in range(1, kind.shape[0]):
        if kind[j] == _CELL:
            G[x, j] = G[src, j] + cells[j, to]
        else:
            G[x, j] = G[src, j] + soltab[khat[frm], d]


@numba.njit(cache=True)
def _ranges(olist, size, G, hlen, lo, hi):
    """lo, hi of every projected column over the open nodes ``olist[:size]``:
    column 0 is G[:, 0] + hlen (the length key g + h), column j G[:, j]."""
    m = G.shape[1]
    for c in range(m):
        lo[c] = np.inf
        hi[c] = -np.inf
    for i in range(size):
        x = olist[i]
        for j in range(m):
            v = G[x, j]
            if j == 0:
                v += hlen[x]
            if v < lo[j]:
                lo[j] = v
            if v > hi[j]:
                hi[j] = v


@numba.njit(cache=True)
def _step_weights(wq, lo, hi, out):
    """out[c] = wq[c] / (hi[c] - lo[c]) (0 for an empty range)."""
    for c in range(wq.shape[0]):
        r = hi[c] - lo[c]
        out[c] = wq[c] / r if (wq[c] > 0 and r > 0) else 0.0


@numba.njit(cache=True, inline="always")
def _composite(G, x, hx, sw, lo):
    s = 0.0
    if sw[0] > 0:
        s = sw[0] * (G[x, 0] + hx - lo[0])
    for j in range(1, G.shape[1]):
        if sw[j] > 0:
            s += sw[j] * (G[x, j] - lo[j])
    return s


@numba.njit(cache=True, inline="always")
def _static(G, x, sec):
    s = 0.0
    for j in range(G.shape[1]):
        s += sec[j] * G[x, j]
    return s


@numba.njit(cache=True)
def _pop_best(olist, size, G, hlen, sw, lo, sec):
    """Position in ``olist`` of the open node of smallest composite (ties:
    static sum ``sec``, then the cell index)."""
    best = -1
    bc = np.inf
    bs = np.inf
    bx = -1
    for i in range(size):
        x = olist[i]
        c = _composite(G, x, hlen[x], sw, lo)
        if c < bc:
            take = True
        elif c == bc:
            s = _static(G, x, sec)
            take = s < bs or (s == bs and x < bx)
        else:
            take = False
        if take:
            best = i
            bc = c
            bs = _static(G, x, sec)
            bx = x
    return best


@numba.njit(cache=True, inline="always")
def _better(G, a, b, sw, sec):
    """Cost row ``a`` better than row ``b`` under the step's weights ``sw``
    (ties: the static sum ``sec``); the heuristic column is the same for both."""
    ca = 0.0
    cb = 0.0
    for j in range(G.shape[1]):
        if sw[j] > 0:
            ca += sw[j] * G[a, j]
            cb += sw[j] * G[b, j]
    if ca != cb:
        return ca < cb
    return _static(G, a, sec) < _static(G, b, sec)


@numba.njit(cache=True, inline="always")
def _remove_at(olist, opos, size, i):
    x = olist[i]
    last = olist[size - 1]
    olist[i] = last
    opos[last] = i
    opos[x] = -1
    return size - 1


@numba.njit(cache=True, inline="always")
def _push(olist, opos, size, x):
    olist[size] = x
    opos[x] = size
    return size + 1


@numba.njit(cache=True)
def renormalised_astar(s, t, occ, cc, kind, cells, soltab, khat, wq, sec):
    """Lavin's A* baseline from cell ``s`` to ``t``: best-first search with
    a closed set (no re-expansion), projection ``P(x) = [g_1(x) + h(x),
    g_2(x) .. g_M(x)]`` (the cost sums so far, the octile distance to ``t``
    added to the length), renormalised at every step.

    ``wq`` (M,) the weights of the objective columns (0: unused), ``sec``
    (M,) the static tie-break weights. Returns ``(path cell indices,
    expansions)``; empty when ``t`` is unreachable.
    """
    h, w = occ.shape
    n = h * w
    m = kind.shape[0]
    G, N, hlen, parent, state, olist, opos, lo, hi, sw = _search_arrays(n, m)
    tmp = n
    for i in range(n):
        hlen[i] = _octile(i, t, w)
    size = _push(olist, opos, 0, s)
    state[s] = _OPEN
    expansions = 0
    reached = False
    while size > 0:
        _ranges(olist, size, G, hlen, lo, hi)
        _step_weights(wq, lo, hi, sw)
        i = _pop_best(olist, size, G, hlen, sw, lo, sec)
        u = olist[i]
        size = _remove_at(olist, opos, size, i)
        state[u] = _CLOSED
        expansions += 1
        if u == t:
            reached = True
            break
        for d in range(8):
            if not _passable(occ, cc, u, d, w):
                continue
            v = (u // w + DR[d]) * w + (u % w + DC[d])
            if state[v] == _CLOSED:
                continue
            _edge(G, N, tmp, u, u, v, d, kind, cells, soltab, khat)
            if state[v] == _NEW or _better(G, tmp, v, sw, sec):
                for j in range(m):
                    G[v, j] = G[tmp, j]
                N[v, 0] = N[tmp, 0]
                N[v, 1] = N[tmp, 1]
                parent[v] = u
                if state[v] == _NEW:
                    state[v] = _OPEN
                    size = _push(olist, opos, size, v)
    if not reached:
        return np.empty(0, np.int64), expansions
    k = 1
    v = t
    while v != s:
        v = parent[v]
        k += 1
    out = np.empty(k, np.int64)
    v = t
    for i in range(k - 1, -1, -1):
        out[i] = v
        v = parent[v]
    return out, expansions


@numba.njit(cache=True, inline="always")
def _leads_to(back, x, y, t, n):
    """True if the back-pointer chain from ``x`` passes ``y`` before ``t``."""
    v = x
    k = 0
    while v != t and v >= 0 and k <= n:
        if v == y:
            return True
        v = back[v]
        k += 1
    return False


@numba.njit(cache=True)
def renormalised_dstar(s, t, occ, cc, kind, cells, soltab, khat, wq, sec, max_pops):
    """Lavin's D* baseline: the first search of Stentz's D* (1994), from the
    goal ``t`` back to the start ``s``, with the renormalised composite.

    Every state keeps its cost-to-goal vector ``h(X)`` and back-pointer
    ``b(X)``; the open list is ordered by the composite of ``h`` (no focusing
    heuristic, as in the original D*; in a first search every state is a
    LOWER state, ``k = h``). Expanding ``X``, every neighbour ``Y`` with a
    passable move ``Y -> X`` is (re)inserted with ``h(Y) = c(Y, X) + h(X)``
    and ``b(Y) = X`` when it is NEW, when ``b(Y) = X`` and ``h(Y)`` differs
    (propagation), or when ``b(Y) != X`` and the new cost is better under the
    step's normalisation and ``X``'s back-pointer chain does not pass
    ``Y`` (with a fixed order that cannot happen; with an order that changes
    between steps a stale chain could close a cycle); CLOSED states are
    reopened by that rule (D*'s LOWER states). The search stops when ``s`` is expanded, or after
    ``max_pops`` expansions (then no path is returned). The path follows
    ``b`` from ``s``.

    Returns ``(path cell indices, expansions)``; empty when ``s`` is not
    reached (unreachable, a back-pointer cycle, or the cap).
    """
    h, w = occ.shape
    n = h * w
    m = kind.shape[0]
    G, N, hlen, back, state, olist, opos, lo, hi, sw = _search_arrays(n, m)
    tmp = n
    size = _push(olist, opos, 0, t)
    state[t] = _OPEN
    expansions = 0
    reached = False
    while size > 0 and expansions < max_pops:
        _ranges(olist, size, G, hlen, lo, hi)  # hlen = 0: no focusing heuristic
        _step_weights(wq, lo, hi, sw)
        i = _pop_best(olist, size, G, hlen, sw, lo, sec)
        x = olist[i]
        size = _remove_at(olist, opos, size, i)
        state[x] = _CLOSED
        expansions += 1
        if x == s:
            reached = True
            break
        for d in range(8):
            yr = x // w + DR[d]
            yc = x % w + DC[d]
            if yr < 0 or yr >= h or yc < 0 or yc >= w:
                continue
            y = yr * w + yc
            bd = (d + 4) & 7  # the move y -> x
            if y == t or not _passable(occ, cc, y, bd, w):
                continue
            _edge(G, N, tmp, x, y, x, bd, kind, cells, soltab, khat)
            if state[y] == _NEW:
                update = True
            elif back[y] == x:
                update = N[y, 0] != N[tmp, 0] or N[y, 1] != N[tmp, 1]
                for j in range(1, m):
                    update = update or G[y, j] != G[tmp, j]
            else:
                # a cheaper cost by this step's scaling; never through y itself
                # (the scaling changes between steps, so a stale chain could
                # otherwise close a back-pointer cycle)
                update = _better(G, tmp, y, sw, sec) and not _leads_to(back, x, y, t, n)
            if update:
                for j in range(m):
                    G[y, j] = G[tmp, j]
                N[y, 0] = N[tmp, 0]
                N[y, 1] = N[tmp, 1]
                back[y] = x
                if state[y] != _OPEN:
                    state[y] = _OPEN
                    size = _push(olist, opos, size, y)
    if not reached:
        return np.empty(0, np.int64), expansions
    out = np.empty(n + 1, np.int64)
    out[0] = s
    k = 1
    v = s
    while v != t:
        v = back[v]
        if v < 0 or k > n:
            return np.empty(0, np.int64), expansions
        out[k] = v
        k += 1
    return out[:k].copy(), expansions
