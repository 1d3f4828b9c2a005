"""numba kernels of the free-path encodings (:mod:`gapath.encodings.free`).

Everything works on the raveled grid (cell ``v = row * W + col``) and on a
whole population at once:

* :func:`component` -- the cells reachable from the start under the move
  rule (8-connected, corner rule of the workspace);
* :func:`snap_table` -- for every cell, the nearest cell of that component
  (multi-source breadth-first search), so any point of the map snaps to a
  reachable free cell;
* :func:`_segment` -- one A* search between two cells of the component with
  step cost ``a * step * m(v) + b * extra[v]`` (``m`` the bilinear cost field
  of the field encoding, 1 for the via-point encoding);
* :func:`decode_via` / :func:`decode_field` -- a population of genomes to
  simple paths (flat cell indices with offsets) and their identity keys;
* :func:`to_padded` -- flat paths to the padded ``(N, L, 2)`` cell arrays of
  :func:`gapath.objectives.evaluate_paths`.

The batch kernels (:func:`decode_via`, :func:`decode_field`,
:func:`reroute`, :func:`reroute_turns`) have ``*_par`` twins that run the
batch on ``nt`` threads (``numba.prange``; each item searched by one thread
with its own scratch arrays, results stored in order): the same output for
any ``nt``. :func:`gapath.encodings.free.search_threads` picks one.

Loops are cut while segments are joined: when a segment enters a cell the
path already holds, the path is cut back to that cell, so every decoded path
is simple; every step is a move of the search, so it respects the corner
rule.
"""

from __future__ import annotations

import heapq
import math

import numba
import numpy as np

from gapath.grid import DC, DR, ONE, STEP, TRUE, ZERO, move_mask, octile
from gapath.openlist import NOT_HELD, open_decrease, open_pop, open_push

_UNSEEN = 0
_CLOSED = -1


@numba.njit(cache=True)
def component(occ, s, corner_cutting):
    """Boolean mask ``(H*W,)`` of the cells reachable from cell ``s`` of the
    ``(H, W)`` grid ``occ`` (the move rule is symmetric, so these are also
    the cells from which ``s`` is reachable)."""
    h, w = occ.shape
    flat = occ.ravel()
    seen = np.zeros(h * w, np.bool_)
    if flat[s]:
        return seen
    queue = np.empty(h * w, np.int64)
    queue[0] = s
    seen[s] = True
    head, tail = 0, 1
    while head < tail:
        u = queue[head]
        head += 1
        ur = u // w
        uc = u - ur * w
        moves = move_mask(flat, h, w, ur, uc, corner_cutting)
        for k in range(8):
            if (moves >> k) & 1:
                v = u + DR[k] * w + DC[k]
                if not seen[v]:
                    seen[v] = True
                    queue[tail] = v
                    tail += 1
    return seen


@numba.njit(cache=True)
def snap_table(comp, h, w):
    """For every cell, the nearest cell of the component ``comp`` (breadth
    first over 8-neighbours from all component cells at once; ties go to the
    component cell met first in row-major order)."""
    n = h * w
    snap = np.full(n, -1, np.int64)
    queue = np.empty(n, np.int64)
    tail = 0
    for v in range(n):
        if comp[v]:
            snap[v] = v
            queue[tail] = v
            tail += 1
    head = 0
    while head < tail:
        u = queue[head]
        head += 1
        ur = u // w
        uc = u - ur * w
        for k in range(8):
            r = ur + DR[k]
            c = uc + DC[k]
            if 0 <= r < h and 0 <= c < w:
                v = r * w + c
                if snap[v] < 0:
                    snap[v] = snap[u]
                    queue[tail] = v
                    tail += 1
    return snap


@numba.njit(cache=True)
def goal_heuristics(occ, extra, t, corner_cutting, forward=False):
    """Exact costs-to-go to cell ``t`` by two backward Dijkstra searches
    (moves are symmetric): ``hlen[v]`` the shortest length from ``v`` to
    ``t`` (cell units) and ``hext[v]`` the smallest sum of ``extra`` over the
    cells after ``v`` up to ``t`` included; ``inf`` where ``t`` is
    unreachable. With them ``a * mmin * hlen + b * hext`` is a consistent
    heuristic of the decoders' step cost towards ``t``.

    With ``forward`` the costs from ``t`` instead (the sum of ``extra`` over
    the cells after ``t`` up to ``v``): the landmark bounds of searches
    between two other cells (see :func:`_segment`)."""
    h, w = occ.shape
    flat = occ.ravel()
    n = h * w
    out = np.full((2, n), np.inf)
    for which in range(2):
        dist = out[which]
        dist[t] = 0.0
        heap = [(0.0, t)]
        while len(heap) > 0:
            d, u = heapq.heappop(heap)
            if d > dist[u]:
                continue
            ur = u // w
            uc = u - ur * w
            moves = move_mask(flat, h, w, ur, uc, corner_cutting)
            for k in range(8):
                if (moves >> k) & 1:
                    v = u + DR[k] * w + DC[k]
                    if which == 0:
                        nd = d + STEP[k]
                    elif forward:
                        nd = d + extra[v]  # the step u -> v enters v
                    else:
                        nd = d + extra[u]  # the step v -> u enters u
                    if nd < dist[v]:
                        dist[v] = nd
                        heapq.heappush(heap, (nd, v))
    return out[0].copy(), out[1].copy()


@numba.njit(cache=True, inline="always")
def _field_value(genes, gy, gx, h, w, r, c):
    """Bilinear interpolation of the ``gy x gx`` control genes at cell (r, c);
    control point (i, j) sits at row ``i * (h - 1) / (gy - 1)``."""
    fr = r * (gy - 1) / max(h - 1, 1)
    fc = c * (gx - 1) / max(w - 1, 1)
    i0 = min(int(fr), gy - 2)
    j0 = min(int(fc), gx - 2)
    ar = fr - i0
    ac = fc - j0
    g00 = genes[i0 * gx + j0]
    g01 = genes[i0 * gx + j0 + 1]
    g10 = genes[(i0 + 1) * gx + j0]
    g11 = genes[(i0 + 1) * gx + j0 + 1]
    return (1.0 - ar) * ((1.0 - ac) * g00 + ac * g01) + ar * ((1.0 - ac) * g10 + ac * g11)


@numba.njit(cache=True, inline="always")
def _landmark_h(v, t, tr, tc, w, ha, b, pmin, hlen, hext, flen, fext):
    vr = v // w
    vc = v - vr * w
    hl = max(octile(vr, vc, tr, tc), hlen[v] - hlen[t], flen[t] - flen[v])
    he = max(pmin * max(abs(vr - tr), abs(vc - tc)), hext[v] - hext[t], fext[t] - fext[v])
    return ha * hl + b * he


@numba.njit(cache=True, _nrt=False)
def _segment(
    occ,
    h,
    w,
    extra,
    s,
    t,
    a,
    b,
    corner_cutting,
    fgenes,
    gy,
    gx,
    beta,
    mmin,
    hlen,
    hext,
    goal_h,
    pmin,
    flen,
    fext,
    state,
    g,
    came,
    heap,
    touched,
    mcache,
    buf,
    win,
):
    """A* from cell ``s`` to cell ``t``; a step into ``v`` by move ``k`` costs
    ``a * STEP[k] * m(v) + b * extra[v]``, ``m(v) = exp(beta * (2 f(v) - 1))``
    for the bilinear field ``f`` of ``fgenes`` (``gy > 0``), else 1.

    Heuristic: when ``goal_h`` (``t`` is the goal) ``a * mmin * hlen[v] + b *
    hext[v]``, the exact costs-to-go of each part (:func:`goal_heuristics`);
    otherwise ``a * mmin * hl + b * he`` with ``hl`` the largest of the octile
    distance and the landmark bounds from the goal and the start (triangle
    inequality: ``d(v, t) >= hlen[v] - hlen[t]`` and ``>= flen[t] - flen[v]``,
    ``flen``/``fext`` the costs from the start) and ``he`` the same for the
    cell cost, at least ``pmin`` (a floor of ``extra``) per step. All are
    consistent (``mmin`` bounds ``m``).

    The search stays inside the window ``win = (r0, r1, c0, c1)`` (rows
    ``r0 .. r1``, columns ``c0 .. c1``; the whole grid for the decoders).

    Writes the cells ``s .. t`` into ``buf``; returns their number (0 when
    ``t`` is unreachable). Scratch arrays as in :mod:`gapath.planners.astar`
    (``state`` all zero on entry and on return)."""
    tr = t // w
    tc = t - tr * w
    ha = a * mmin
    g[s] = 0.0
    touched[0] = s
    n_touched = 1
    if goal_h:
        hs = ha * hlen[s] + b * hext[s]
    else:
        hs = _landmark_h(s, t, tr, tc, w, ha, b, pmin, hlen, hext, flen, fext)
    size, held = open_push(heap, state, 0, NOT_HELD, hs, hs, s)
    reached = False
    use_field = gy > 0
    while True:
        u, size, held = open_pop(heap, state, size, held)
        if u < 0:
            break
        state[u] = _CLOSED
        if u == t:
            reached = True
            break
        ur = u // w
        uc = u - ur * w
        moves = move_mask(occ, h, w, ur, uc, corner_cutting)
        gu = g[u]
        for k in range(8):
            if not (moves >> k) & 1:
                continue
            v = u + DR[k] * w + DC[k]
            sv = state[v]
            if sv == _CLOSED:
                continue
            vr = ur + DR[k]
            vc = uc + DC[k]
            if vr < win[0] or vr > win[1] or vc < win[2] or vc > win[3]:
                continue
            if use_field:
                if sv == _UNSEEN:
                    mcache[v] = math.exp(beta * (2.0 * _field_value(fgenes, gy, gx, h, w, vr, vc) - 1.0))
                step = a * STEP[k] * mcache[v] + b * extra[v]
            else:
                step = a * STEP[k] + b * extra[v]
            ng = gu + step
            if sv != _UNSEEN and ng >= g[v]:
                continue
            g[v] = ng
            came[v] = k
            if goal_h:
                hv = ha * hlen[v] + b * hext[v]
            else:
                hv = _landmark_h(v, t, tr, tc, w, ha, b, pmin, hlen, hext, flen, fext)
            if sv == _UNSEEN:
                touched[n_touched] = v
                n_touched += 1
                size, held = open_push(heap, state, size, held, ng + hv, hv, v)
            else:
                held = open_decrease(heap, state, held, ng + hv, hv, v)
    for i in range(n_touched):
        state[touched[i]] = _UNSEEN
    if not reached:
        return 0
    m = 1
    v = t
    while v != s:
        v -= DR[came[v]] * w + DC[came[v]]
        m += 1
    v = t
    for i in range(m - 1, -1, -1):
        buf[i] = v
        if i > 0:
            v -= DR[came[v]] * w + DC[came[v]]
    return m


@numba.njit(cache=True, inline="always")
def _weights(gene, lam_lo, lam_hi):
    """Length and cell-cost weights ``(a, b)``, ``a + b = 1``, of a weight
    gene in [0, 1]: the cell cost counts ``lam = 10 ** (lam_lo + (lam_hi -
    lam_lo) * gene)`` times as much as the length."""
    x = min(max(gene, 0.0), 1.0)
    lam = 10.0 ** (lam_lo + (lam_hi - lam_lo) * x)
    return 1.0 / (1.0 + lam), lam / (1.0 + lam)


@numba.njit(cache=True, inline="always")
def _append(c, cur, pos, m):
    """Append cell ``c`` to the simple path ``cur[:m]``, cutting the loop when
    ``c`` is already on it; return the new length."""
    p = pos[c]
    if p >= 0:
        for q in range(p + 1, m):
            pos[cur[q]] = -1
        return p + 1
    pos[c] = m
    cur[m] = c
    return m + 1


@numba.njit(cache=True)
def _store(cur, m, i, flat, offsets, keys):
    """Copy path ``cur[:m]`` as individual ``i`` into ``flat`` (grown when
    full) and its identity key (length and two 64-bit hashes) into ``keys``."""
    start = offsets[i]
    if start + m > flat.shape[0]:
        grown = np.empty(max(2 * flat.shape[0], start + m), np.int64)
        grown[:start] = flat[:start]
        flat = grown
    h1 = np.uint64(1469598103934665603)
    h2 = np.uint64(7)
    for j in range(m):
        c = np.uint64(cur[j] + 1)
        flat[start + j] = cur[j]
        h1 = (h1 ^ c) * np.uint64(1099511628211)
        h2 = h2 * np.uint64(6364136223846793005) + c * np.uint64(1442695040888963407)
    offsets[i + 1] = start + m
    keys[i, 0] = m
    keys[i, 1] = np.int64(h1)
    keys[i, 2] = np.int64(h2)
    return flat


@numba.njit(cache=True)
def _scratch(n):
    return (
        np.zeros(n, np.int64),
        np.empty(n),
        np.empty(n, np.uint8),
        np.empty(3 * n),
        np.empty(n, np.int64),
        np.empty(n),
        np.empty(n, np.int64),
    )


@numba.njit(cache=True)
def _scratch2(nt, n):
    """One row of :func:`_scratch` arrays per thread."""
    return (
        np.zeros((nt, n), np.int64),
        np.empty((nt, n)),
        np.empty((nt, n), np.uint8),
        np.empty((nt, 3 * n)),
        np.empty((nt, n), np.int64),
        np.empty((nt, n)),
        np.empty((nt, n), np.int64),
    )


@numba.njit(cache=True)
def _block(nt, n):
    """Genomes decoded per parallel block: 8 per thread, fewer on huge maps
    (a block keeps one ``n``-cell path row per genome, at most 64 MB)."""
    return nt * max(1, min(8, (1 << 23) // max(1, n * nt)))


@numba.njit(cache=True)
def _via_cell(u, v, h, w, snap):
    r = min(max(int(u * h), 0), h - 1)
    c = min(max(int(v * w), 0), w - 1)
    return snap[r * w + c]


@numba.njit(cache=True)
def _via_one(
    X,
    i,
    n_via,
    flat_occ,
    h,
    w,
    extra,
    snap,
    s,
    t,
    corner_cutting,
    lam_lo,
    lam_hi,
    hlen,
    hext,
    pmin,
    flen,
    fext,
    state,
    g,
    came,
    heap,
    touched,
    mcache,
    buf,
    pos,
    cur,
):
    """The path of via-point genome ``X[i]`` into ``cur``; returns its
    number of cells (``pos`` all -1 on entry and on return)."""
    dummy = np.zeros(1)
    pos[s] = 0
    cur[0] = s
    m = 1
    prev = s
    for k in range(n_via + 1):
        nxt = t if k == n_via else _via_cell(X[i, 2 * k], X[i, 2 * k + 1], h, w, snap)
        if nxt == prev:
            continue
        a, b = _weights(X[i, 2 * n_via + k], lam_lo, lam_hi)
        cnt = _segment(
            flat_occ,
            h,
            w,
            extra,
            prev,
            nxt,
            a,
            b,
            corner_cutting,
            dummy,
            ZERO,
            ZERO,
            0.0,
            1.0,
            hlen,
            hext,
            nxt == t,
            pmin,
            flen,
            fext,
            state,
            g,
            came,
            heap,
            touched,
            mcache,
            buf,
            (ZERO, h - 1, ZERO, w - 1),
        )
        for j in range(1, cnt):
            m = _append(buf[j], cur, pos, m)
        prev = nxt
    for j in range(m):
        pos[cur[j]] = -1
    return m


@numba.njit(cache=True)
def decode_via(
    X, n_via, occ, extra, snap, s, t, corner_cutting, lam_lo, lam_hi, hlen, hext, pmin, flen, fext
):
    """Paths of via-point genomes ``X`` (N, 3 K + 1): genes ``2k, 2k + 1``
    place via point ``k`` (row and column fractions, snapped to the start's
    component), genes ``2K .. 3K`` weight the ``K + 1`` segments.

    Returns ``(flat, offsets, keys)``: the cells of path ``i`` are
    ``flat[offsets[i]:offsets[i + 1]]`` (row-major indices), ``keys[i]`` its
    identity (length, two hashes). :func:`decode_via_par` gives the same on
    ``nt`` threads."""
    h, w = occ.shape
    flat_occ = occ.ravel()
    n = X.shape[0]
    state, g, came, heap, touched, mcache, buf = _scratch(h * w)
    pos = np.full(h * w, -1, np.int64)
    cur = np.empty(h * w, np.int64)
    flat = np.empty(max(16, n * (h + w)), np.int64)
    offsets = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    for i in range(n):
        m = _via_one(
            X, i, n_via, flat_occ, h, w, extra, snap, s, t, corner_cutting, lam_lo, lam_hi, hlen, hext,
            pmin, flen, fext, state, g, came, heap, touched, mcache, buf, pos, cur,
        )  # fmt: skip
        flat = _store(cur, m, i, flat, offsets, keys)
    return flat[: offsets[n]], offsets, keys


@numba.njit(cache=True, parallel=True)
def decode_via_par(
    X, n_via, occ, extra, snap, s, t, corner_cutting, lam_lo, lam_hi, hlen, hext, pmin, flen, fext, nt
):
    """:func:`decode_via` on ``nt`` threads (each genome decoded by one
    thread with its own scratch arrays: the same paths for any ``nt``)."""
    h, w = occ.shape
    hw = h * w
    flat_occ = occ.ravel()
    n = X.shape[0]
    state, g, came, heap, touched, mcache, buf = _scratch2(nt, hw)
    pos = np.full((nt, hw), -1, np.int64)
    bsz = _block(nt, hw)
    rows = np.empty((bsz, hw), np.int64)
    cnts = np.zeros(bsz, np.int64)
    flat = np.empty(max(16, n * (h + w)), np.int64)
    offsets = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    for lo in range(0, n, bsz):
        hi = min(n, lo + bsz)
        for k in numba.prange(nt):
            for i in range(lo + k, hi, nt):
                cnts[i - lo] = _via_one(
                    X, i, n_via, flat_occ, h, w, extra, snap, s, t, corner_cutting, lam_lo, lam_hi, hlen,
                    hext, pmin, flen, fext, state[k], g[k], came[k], heap[k], touched[k], mcache[k], buf[k],
                    pos[k], rows[i - lo],
                )  # fmt: skip
        for i in range(lo, hi):
            flat = _store(rows[i - lo], cnts[i - lo], i, flat, offsets, keys)
    return flat[: offsets[n]], offsets, keys


@numba.njit(cache=True)
def _field_one(
    X,
    i,
    gy,
    gx,
    beta,
    flat_occ,
    h,
    w,
    extra,
    s,
    t,
    corner_cutting,
    lam_lo,
    lam_hi,
    hlen,
    hext,
    genes,
    state,
    g,
    came,
    heap,
    touched,
    mcache,
    buf,
):
    """The path of cost-field genome ``X[i]`` into ``buf``; returns its
    number of cells."""
    nf = gy * gx
    gmin = 1.0
    for j in range(nf):
        genes[j] = min(max(X[i, j], 0.0), 1.0)
        gmin = min(gmin, genes[j])
    a, b = _weights(X[i, nf], lam_lo, lam_hi)
    mmin = math.exp(beta * (2.0 * gmin - 1.0))
    return _segment(
        flat_occ,
        h,
        w,
        extra,
        s,
        t,
        a,
        b,
        corner_cutting,
        genes,
        gy,
        gx,
        beta,
        mmin,
        hlen,
        hext,
        TRUE,
        0.0,
        hlen,
        hext,
        state,
        g,
        came,
        heap,
        touched,
        mcache,
        buf,
        (ZERO, h - 1, ZERO, w - 1),
    )


@numba.njit(cache=True)
def decode_field(X, gy, gx, beta, occ, extra, s, t, corner_cutting, lam_lo, lam_hi, hlen, hext):
    """Paths of cost-field genomes ``X`` (N, gy * gx + 1): genes ``0 ..
    gy * gx - 1`` are the control points of the cost multiplier field (row
    major), the last gene weights the cell cost against the length. One A*
    search per genome. Returns ``(flat, offsets, keys)`` as :func:`decode_via`;
    :func:`decode_field_par` gives the same on ``nt`` threads."""
    h, w = occ.shape
    flat_occ = occ.ravel()
    n = X.shape[0]
    state, g, came, heap, touched, mcache, buf = _scratch(h * w)
    flat = np.empty(max(16, n * (h + w)), np.int64)
    offsets = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    genes = np.empty(gy * gx)
    for i in range(n):
        cnt = _field_one(
            X, i, gy, gx, beta, flat_occ, h, w, extra, s, t, corner_cutting, lam_lo, lam_hi, hlen, hext,
            genes, state, g, came, heap, touched, mcache, buf,
        )  # fmt: skip
        flat = _store(buf, cnt, i, flat, offsets, keys)
    return flat[: offsets[n]], offsets, keys


@numba.njit(cache=True, parallel=True)
def decode_field_par(X, gy, gx, beta, occ, extra, s, t, corner_cutting, lam_lo, lam_hi, hlen, hext, nt):
    """:func:`decode_field` on ``nt`` threads (each genome decoded by one
    thread with its own scratch arrays: the same paths for any ``nt``)."""
    h, w = occ.shape
    hw = h * w
    flat_occ = occ.ravel()
    n = X.shape[0]
    state, g, came, heap, touched, mcache, buf = _scratch2(nt, hw)
    genes = np.empty((nt, gy * gx))
    bsz = _block(nt, hw)
    rows = np.empty((bsz, hw), np.int64)
    cnts = np.zeros(bsz, np.int64)
    flat = np.empty(max(16, n * (h + w)), np.int64)
    offsets = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    for lo in range(0, n, bsz):
        hi = min(n, lo + bsz)
        for k in numba.prange(nt):
            for i in range(lo + k, hi, nt):
                cnts[i - lo] = _field_one(
                    X, i, gy, gx, beta, flat_occ, h, w, extra, s, t, corner_cutting, lam_lo, lam_hi, hlen,
                    hext, genes[k], state[k], g[k], came[k], heap[k], touched[k], mcache[k], rows[i - lo],
                )  # fmt: skip
        for i in range(lo, hi):
            flat = _store(rows[i - lo], cnts[i - lo], i, flat, offsets, keys)
    return flat[: offsets[n]], offsets, keys


@numba.njit(cache=True)
def weighted_paths(occ, extra, s, t, corner_cutting, genes, lam_lo, lam_hi, hlen, hext):
    """The single-search paths ``s -> t`` for each weight gene of ``genes``
    (the decoders' cost with a neutral field). Returns ``(flat, offsets, keys)``."""
    h, w = occ.shape
    flat_occ = occ.ravel()
    n = genes.shape[0]
    state, g, came, heap, touched, mcache, buf = _scratch(h * w)
    flat = np.empty(max(16, n * (h + w)), np.int64)
    offsets = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    dummy = np.zeros(1)
    for i in range(n):
        a, b = _weights(genes[i], lam_lo, lam_hi)
        cnt = _segment(
            flat_occ,
            h,
            w,
            extra,
            s,
            t,
            a,
            b,
            corner_cutting,
            dummy,
            ZERO,
            ZERO,
            0.0,
            1.0,
            hlen,
            hext,
            TRUE,
            0.0,
            hlen,
            hext,
            state,
            g,
            came,
            heap,
            touched,
            mcache,
            buf,
            (ZERO, h - 1, ZERO, w - 1),
        )
        flat = _store(buf, cnt, i, flat, offsets, keys)
    return flat[: offsets[n]], offsets, keys


@numba.njit(cache=True)
def fit_segment_weights(
    cells,
    offsets,
    via_idx,
    occ,
    extra,
    corner_cutting,
    candidates,
    lam_lo,
    lam_hi,
    t,
    hlen,
    hext,
    pmin,
    flen,
    fext,
):
    """For each path ``i`` (cells ``cells[offsets[i]:offsets[i+1]]``) and each
    of its segments between consecutive via indices ``via_idx[i]`` (positions
    on the path, first 0, last the goal), the candidate weight gene whose
    segment search reproduces the path's sub-path best: the fewest cells not
    on the sub-path, ties to the closer length. Returns ``(N, n_seg)``."""
    h, w = occ.shape
    flat_occ = occ.ravel()
    n, n_pts = via_idx.shape
    n_seg = n_pts - 1
    state, g, came, heap, touched, mcache, buf = _scratch(h * w)
    mark = np.zeros(h * w, np.int64)
    out = np.zeros((n, n_seg))
    dummy = np.zeros(1)
    for i in range(n):
        base = offsets[i]
        for k in range(n_seg):
            p0 = via_idx[i, k]
            p1 = via_idx[i, k + 1]
            if p1 <= p0:
                out[i, k] = 0.0
                continue
            for j in range(p0, p1 + 1):
                mark[cells[base + j]] = 1
            best = -1.0
            best_miss = 1 << 60
            best_dl = 1 << 60
            for q in range(candidates.shape[0]):
                a, b = _weights(candidates[q], lam_lo, lam_hi)
                cnt = _segment(
                    flat_occ,
                    h,
                    w,
                    extra,
                    cells[base + p0],
                    cells[base + p1],
                    a,
                    b,
                    corner_cutting,
                    dummy,
                    ZERO,
                    ZERO,
                    0.0,
                    1.0,
                    hlen,
                    hext,
                    cells[base + p1] == t,
                    pmin,
                    flen,
                    fext,
                    state,
                    g,
                    came,
                    heap,
                    touched,
                    mcache,
                    buf,
                    (ZERO, h - 1, ZERO, w - 1),
                )
                miss = 0
                for j in range(cnt):
                    if mark[buf[j]] == 0:
                        miss += 1
                dl = abs(cnt - (p1 - p0 + 1))
                if miss < best_miss or (miss == best_miss and dl < best_dl):
                    best_miss = miss
                    best_dl = dl
                    best = candidates[q]
                if best_miss == 0 and best_dl == 0:
                    break
            for j in range(p0, p1 + 1):
                mark[cells[base + j]] = 0
            out[i, k] = best
    return out


@numba.njit(cache=True)
def to_padded(flat, offsets, w):
    """Padded ``(N, L, 2)`` cells (zeros past each length) and lengths of
    flat paths."""
    n = offsets.shape[0] - 1
    lengths = np.empty(n, np.int64)
    L = 1
    for i in range(n):
        lengths[i] = offsets[i + 1] - offsets[i]
        L = max(L, lengths[i])
    out = np.zeros((n, L, 2), np.int64)
    for i in range(n):
        for j in range(lengths[i]):
            v = flat[offsets[i] + j]
            r = v // w
            out[i, j, 0] = r
            out[i, j, 1] = v - r * w
    return out, lengths


@numba.njit(cache=True)
def gather(flat_a, off_a, flat_b, off_b, src, idx):
    """Flat paths picked row by row: row ``i`` is path ``idx[i]`` of ``a``
    when ``src[i] == 0``, of ``b`` otherwise."""
    n = src.shape[0]
    offsets = np.zeros(n + 1, np.int64)
    for i in range(n):
        j = idx[i]
        m = (off_a[j + 1] - off_a[j]) if src[i] == 0 else (off_b[j + 1] - off_b[j])
        offsets[i + 1] = offsets[i] + m
    flat = np.empty(offsets[n], np.int64)
    for i in range(n):
        j = idx[i]
        if src[i] == 0:
            flat[offsets[i] : offsets[i + 1]] = flat_a[off_a[j] : off_a[j + 1]]
        else:
            flat[offsets[i] : offsets[i + 1]] = flat_b[off_b[j] : off_b[j + 1]]
    return flat, offsets


@numba.njit(cache=True)
def row_hash(X):
    """64-bit hash of every row of the float matrix ``X`` (its bit patterns)."""
    n, m = X.shape
    bits = X.view(np.int64)
    out = np.empty(n, np.int64)
    for i in range(n):
        x = np.uint64(1469598103934665603)
        for j in range(m):
            x = (x ^ np.uint64(bits[i, j])) * np.uint64(1099511628211)
            x ^= x >> np.uint64(29)
        out[i] = np.int64(x)
    return out


@numba.njit(cache=True, inline="always")
def _window(u, v, w, h, margin):
    """Rows and columns ``(r0, r1, c0, c1)`` of the box around cells ``u``
    and ``v`` widened by ``max(margin, extent)`` on every side (``extent``
    the larger side of their box); the whole grid when ``margin < 0``."""
    if margin < 0:
        return (ZERO, h - 1, ZERO, w - 1)
    ur = u // w
    uc = u - ur * w
    vr = v // w
    vc = v - vr * w
    m = max(margin, max(abs(ur - vr), abs(uc - vc)))
    return (
        max(0, min(ur, vr) - m),
        min(h - 1, max(ur, vr) + m),
        max(0, min(uc, vc) - m),
        min(w - 1, max(uc, vc) + m),
    )


@numba.njit(cache=True)
def _reroute_one(
    flat,
    offsets,
    pick,
    i0,
    i1,
    genes,
    r,
    flat_occ,
    h,
    w,
    extra,
    corner_cutting,
    lam_lo,
    lam_hi,
    t,
    hlen,
    hext,
    pmin,
    flen,
    fext,
    margin,
    state,
    g,
    came,
    heap,
    touched,
    mcache,
    buf,
    pos,
    cur,
):
    """Row ``r`` of :func:`reroute` into ``cur``; returns its number of
    cells (``pos`` all -1 on entry and on return)."""
    dummy = np.zeros(1)
    base = offsets[pick[r]]
    m_old = offsets[pick[r] + 1] - base
    p0 = min(max(i0[r], 0), m_old - 1)
    p1 = min(max(i1[r], p0), m_old - 1)
    m = 0
    for j in range(p0 + 1):
        m = _append(flat[base + j], cur, pos, m)
    if p1 > p0:
        a, b = _weights(genes[r], lam_lo, lam_hi)
        u = flat[base + p0]
        v = flat[base + p1]
        cnt = _segment(
            flat_occ,
            h,
            w,
            extra,
            u,
            v,
            a,
            b,
            corner_cutting,
            dummy,
            ZERO,
            ZERO,
            0.0,
            1.0,
            hlen,
            hext,
            v == t,
            pmin,
            flen,
            fext,
            state,
            g,
            came,
            heap,
            touched,
            mcache,
            buf,
            _window(u, v, w, h, margin),
        )
        if cnt == 0:  # cannot happen between cells of one path; keep the old cells
            for j in range(p0 + 1, p1 + 1):
                m = _append(flat[base + j], cur, pos, m)
        else:
            for j in range(1, cnt):
                m = _append(buf[j], cur, pos, m)
    for j in range(p1 + 1, m_old):
        m = _append(flat[base + j], cur, pos, m)
    for j in range(m):
        pos[cur[j]] = -1
    return m


@numba.njit(cache=True)
def reroute(
    flat,
    offsets,
    pick,
    i0,
    i1,
    genes,
    occ,
    extra,
    corner_cutting,
    lam_lo,
    lam_hi,
    t,
    hlen,
    hext,
    pmin,
    flen,
    fext,
    margin,
):
    """Paths made from others by re-routing one segment: row ``r`` takes
    path ``pick[r]`` (cells ``flat[offsets[p]:offsets[p + 1]]``), replaces
    its cells between positions ``i0[r] < i1[r]`` by the optimal path
    between them under the weight gene ``genes[r]`` (the decoders' step
    cost, neutral field) inside the window of :func:`_window` (``margin``)
    and cuts the loops the splice makes, so every result is a simple path
    with the same ends. Returns ``(flat, offsets, keys)`` as
    :func:`decode_via`; :func:`reroute_par` gives the same on ``nt``
    threads."""
    h, w = occ.shape
    flat_occ = occ.ravel()
    n = pick.shape[0]
    state, g, came, heap, touched, mcache, buf = _scratch(h * w)
    pos = np.full(h * w, -1, np.int64)
    cur = np.empty(h * w, np.int64)
    out = np.empty(max(16, n * (h + w)), np.int64)
    out_off = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    for r in range(n):
        m = _reroute_one(
            flat, offsets, pick, i0, i1, genes, r, flat_occ, h, w, extra, corner_cutting, lam_lo, lam_hi, t,
            hlen, hext, pmin, flen, fext, margin, state, g, came, heap, touched, mcache, buf, pos, cur,
        )  # fmt: skip
        out = _store(cur, m, r, out, out_off, keys)
    return out[: out_off[n]], out_off, keys


@numba.njit(cache=True, parallel=True)
def reroute_par(
    flat,
    offsets,
    pick,
    i0,
    i1,
    genes,
    occ,
    extra,
    corner_cutting,
    lam_lo,
    lam_hi,
    t,
    hlen,
    hext,
    pmin,
    flen,
    fext,
    margin,
    nt,
):
    """:func:`reroute` on ``nt`` threads (the same paths for any ``nt``)."""
    h, w = occ.shape
    hw = h * w
    flat_occ = occ.ravel()
    n = pick.shape[0]
    state, g, came, heap, touched, mcache, buf = _scratch2(nt, hw)
    pos = np.full((nt, hw), -1, np.int64)
    bsz = _block(nt, hw)
    rows = np.empty((bsz, hw), np.int64)
    cnts = np.zeros(bsz, np.int64)
    out = np.empty(max(16, n * (h + w)), np.int64)
    out_off = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    for lo in range(0, n, bsz):
        hi = min(n, lo + bsz)
        for k in numba.prange(nt):
            for r in range(lo + k, hi, nt):
                cnts[r - lo] = _reroute_one(
                    flat, offsets, pick, i0, i1, genes, r, flat_occ, h, w, extra, corner_cutting, lam_lo,
                    lam_hi, t, hlen, hext, pmin, flen, fext, margin, state[k], g[k], came[k], heap[k],
                    touched[k], mcache[k], buf[k], pos[k], rows[r - lo],
                )  # fmt: skip
        for r in range(lo, hi):
            out = _store(rows[r - lo], cnts[r - lo], r, out, out_off, keys)
    return out[: out_off[n]], out_off, keys


@numba.njit(cache=True, inline="always")
def _move_index(dr, dc):
    """Index ``k`` of the move ``(dr, dc)`` in ``DR``/``DC`` (-1 if none)."""
    for k in range(8):
        if DR[k] == dr and DC[k] == dc:
            return k
    return -1


@numba.njit(cache=True)
def shortcut(flat, offsets, pick, i0, i1, diagonal_first, occ, corner_cutting):
    """Paths made from others by straightening one segment: row ``r`` takes
    path ``pick[r]`` and replaces its cells between positions ``i0[r] <
    i1[r]`` by the octile path with one bend between them (the diagonal
    steps first when ``diagonal_first[r]``, else the straight ones): as
    short as a path between the two cells can be, with at most one turn.
    Where that path meets an obstacle or cuts a corner the rule forbids,
    the row keeps the original path. Loops the splice makes are cut.
    Returns ``(flat, offsets, keys)`` as :func:`decode_via`."""
    h, w = occ.shape
    flat_occ = occ.ravel()
    n = pick.shape[0]
    pos = np.full(h * w, -1, np.int64)
    cur = np.empty(h * w, np.int64)
    seg = np.empty(h + w + 2, np.int64)
    out = np.empty(max(16, n * (h + w)), np.int64)
    out_off = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    for r in range(n):
        base = offsets[pick[r]]
        m_old = offsets[pick[r] + 1] - base
        p0 = min(max(i0[r], 0), m_old - 1)
        p1 = min(max(i1[r], p0), m_old - 1)
        u = flat[base + p0]
        v = flat[base + p1]
        ur = u // w
        uc = u - ur * w
        dr = v // w - ur
        dc = v - (v // w) * w - uc
        sr = 1 if dr > 0 else (-1 if dr < 0 else 0)
        sc = 1 if dc > 0 else (-1 if dc < 0 else 0)
        nd = min(abs(dr), abs(dc))
        ns = max(abs(dr), abs(dc)) - nd
        kd = _move_index(sr, sc)
        ks = _move_index(sr, 0) if abs(dr) > abs(dc) else _move_index(0, sc)
        cnt = 0
        ok = p1 > p0
        rr = ur
        cc = uc
        for phase in range(2):
            if not ok:
                break
            diag = (phase == 0) == diagonal_first[r]
            steps = nd if diag else ns
            k = kd if diag else ks
            for _ in range(steps):
                if not (move_mask(flat_occ, h, w, rr, cc, corner_cutting) >> k) & 1:
                    ok = False
                    break
                rr += DR[k]
                cc += DC[k]
                seg[cnt] = rr * w + cc
                cnt += 1
        m = 0
        for j in range(p0 + 1):
            m = _append(flat[base + j], cur, pos, m)
        if ok:
            for j in range(cnt):
                m = _append(seg[j], cur, pos, m)
        else:
            for j in range(p0 + 1, p1 + 1):
                m = _append(flat[base + j], cur, pos, m)
        for j in range(p1 + 1, m_old):
            m = _append(flat[base + j], cur, pos, m)
        for j in range(m):
            pos[cur[j]] = -1
        out = _store(cur, m, r, out, out_off, keys)
    return out[: out_off[n]], out_off, keys


@numba.njit(cache=True, inline="always")
def _eighths(k1, k2):
    """Turn between moves ``k1`` and ``k2`` in eighths of a full turn (0 when
    either is 8, no move)."""
    if k1 == 8 or k2 == 8:
        return 0
    d = abs(k1 - k2)
    return min(d, 8 - d)


@numba.njit(cache=True, _nrt=False)
def _turn_segment(
    occ,
    h,
    w,
    extra,
    s,
    kin,
    t,
    kout,
    a,
    b,
    c,
    corner_cutting,
    state,
    g,
    came,
    heap,
    touched,
    buf,
    win,
    pmin,
    hlen,
    hext,
    flen,
    fext,
):
    """A* from cell ``s`` (entered by move ``kin``, 8: none) to cell ``t``
    (left by move ``kout``, 8: none) over (cell, last move) states: a step
    into ``v`` by move ``k`` after move ``k0`` costs ``a * STEP[k] + b *
    extra[v] + c * pi/4 * eighths(k0, k)``, plus the turn onto ``kout`` on
    the step into ``t``. Heuristic: the landmark bounds of :func:`_segment`
    on the length and the cell cost (turns count 0; consistent). Writes the cells ``s .. t`` into ``buf`` (a cell may
    repeat: the caller cuts loops); returns their number, 0 if unreachable.
    The search stays inside the window ``win`` (see :func:`_segment`).
    Scratch arrays of ``9 * H * W`` states (``state`` zero on entry and on
    return)."""
    eighth = math.pi / 4.0
    tr = t // w
    tc = t - tr * w
    s_id = s * 9 + kin
    g[s_id] = 0.0
    came[s_id] = 8
    touched[0] = s_id
    n_touched = 1
    hs = _landmark_h(s, t, tr, tc, w, a, b, pmin, hlen, hext, flen, fext)
    size, held = open_push(heap, state, 0, NOT_HELD, hs, hs, s_id)
    goal = -1
    while True:
        x, size, held = open_pop(heap, state, size, held)
        if x < 0:
            break
        state[x] = _CLOSED
        u = x // 9
        k0 = x - u * 9
        if u == t:
            goal = x
            break
        ur = u // w
        uc = u - ur * w
        moves = move_mask(occ, h, w, ur, uc, corner_cutting)
        gu = g[x]
        for k in range(8):
            if not (moves >> k) & 1:
                continue
            vr = ur + DR[k]
            vc = uc + DC[k]
            if vr < win[0] or vr > win[1] or vc < win[2] or vc > win[3]:
                continue
            v = vr * w + vc
            y = v * 9 + k
            sy = state[y]
            if sy == _CLOSED:
                continue
            ng = gu + a * STEP[k] + b * extra[v] + c * eighth * _eighths(k0, k)
            if v == t:
                ng += c * eighth * _eighths(k, kout)
            if sy != _UNSEEN and ng >= g[y]:
                continue
            g[y] = ng
            came[y] = k0
            hv = _landmark_h(v, t, tr, tc, w, a, b, pmin, hlen, hext, flen, fext)
            if sy == _UNSEEN:
                touched[n_touched] = y
                n_touched += 1
                size, held = open_push(heap, state, size, held, ng + hv, hv, y)
            else:
                held = open_decrease(heap, state, held, ng + hv, hv, y)
    for i in range(n_touched):
        state[touched[i]] = _UNSEEN
    if goal < 0:
        return 0
    m = 0
    x = goal
    while True:
        u = x // 9
        buf[m] = u
        m += 1
        if x == s_id:
            break
        k = x - u * 9
        prev = u - DR[k] * w - DC[k]
        x = prev * 9 + came[x]
    for i in range(m // 2):
        tmp = buf[i]
        buf[i] = buf[m - 1 - i]
        buf[m - 1 - i] = tmp
    return m


@numba.njit(cache=True)
def _reroute_turns_one(
    flat,
    offsets,
    pick,
    i0,
    i1,
    genes,
    tgenes,
    r,
    flat_occ,
    h,
    w,
    extra,
    corner_cutting,
    lam_lo,
    lam_hi,
    tau_lo,
    tau_hi,
    margin,
    pmin,
    hlen,
    hext,
    flen,
    fext,
    state,
    g,
    came,
    heap,
    touched,
    buf,
    pos,
    cur,
):
    """Row ``r`` of :func:`reroute_turns` into ``cur``; returns its number
    of cells (``pos`` all -1 on entry and on return)."""
    base = offsets[pick[r]]
    m_old = offsets[pick[r] + 1] - base
    p0 = min(max(i0[r], 0), m_old - 1)
    p1 = min(max(i1[r], p0), m_old - 1)
    m = 0
    for j in range(p0 + 1):
        m = _append(flat[base + j], cur, pos, m)
    cnt = 0
    if p1 > p0:
        u = flat[base + p0]
        v = flat[base + p1]
        kin = 8
        if p0 > 0:
            q = flat[base + p0 - 1]
            kin = _move_index(u // w - q // w, (u - (u // w) * w) - (q - (q // w) * w))
        kout = 8
        if p1 < m_old - 1:
            q = flat[base + p1 + 1]
            kout = _move_index(q // w - v // w, (q - (q // w) * w) - (v - (v // w) * w))
        a, b = _weights(genes[r], lam_lo, lam_hi)
        x = min(max(tgenes[r], 0.0), 1.0)
        c = a * 10.0 ** (tau_lo + (tau_hi - tau_lo) * x)
        cnt = _turn_segment(
            flat_occ,
            h,
            w,
            extra,
            u,
            kin,
            v,
            kout,
            a,
            b,
            c,
            corner_cutting,
            state,
            g,
            came,
            heap,
            touched,
            buf,
            _window(u, v, w, h, margin),
            pmin,
            hlen,
            hext,
            flen,
            fext,
        )
    if cnt == 0:
        for j in range(p0 + 1, p1 + 1):
            m = _append(flat[base + j], cur, pos, m)
    else:
        for j in range(1, cnt):
            m = _append(buf[j], cur, pos, m)
    for j in range(p1 + 1, m_old):
        m = _append(flat[base + j], cur, pos, m)
    for j in range(m):
        pos[cur[j]] = -1
    return m


@numba.njit(cache=True)
def _turn_scratch(nt, ns):
    return (
        np.zeros((nt, ns), np.int64),
        np.empty((nt, ns)),
        np.empty((nt, ns), np.uint8),
        np.empty((nt, 3 * ns)),
        np.empty((nt, ns), np.int64),
        np.empty((nt, ns), np.int64),
    )


@numba.njit(cache=True)
def reroute_turns(
    flat,
    offsets,
    pick,
    i0,
    i1,
    genes,
    tgenes,
    occ,
    extra,
    corner_cutting,
    lam_lo,
    lam_hi,
    tau_lo,
    tau_hi,
    margin,
    pmin,
    hlen,
    hext,
    flen,
    fext,
):
    """:func:`reroute` with turns weighed too: the segment search
    (:func:`_turn_segment`) adds ``c * angle`` per turn, ``c / a = 10 **
    (tau_lo + (tau_hi - tau_lo) * tgenes[r])``, including the turns where
    the segment meets the rest of the path; it stays inside the window of
    :func:`_window` (``margin``). Returns ``(flat, offsets, keys)``;
    :func:`reroute_turns_par` gives the same on ``nt`` threads."""
    h, w = occ.shape
    flat_occ = occ.ravel()
    n = pick.shape[0]
    state, g, came, heap, touched, buf = _turn_scratch(ONE, 9 * h * w)
    pos = np.full(h * w, -1, np.int64)
    cur = np.empty(h * w, np.int64)
    out = np.empty(max(16, n * (h + w)), np.int64)
    out_off = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    for r in range(n):
        m = _reroute_turns_one(
            flat, offsets, pick, i0, i1, genes, tgenes, r, flat_occ, h, w, extra, corner_cutting, lam_lo,
            lam_hi, tau_lo, tau_hi, margin, pmin, hlen, hext, flen, fext, state[0], g[0], came[0], heap[0],
            touched[0], buf[0], pos, cur,
        )  # fmt: skip
        out = _store(cur, m, r, out, out_off, keys)
    return out[: out_off[n]], out_off, keys


@numba.njit(cache=True, parallel=True)
def reroute_turns_par(
    flat,
    offsets,
    pick,
    i0,
    i1,
    genes,
    tgenes,
    occ,
    extra,
    corner_cutting,
    lam_lo,
    lam_hi,
    tau_lo,
    tau_hi,
    margin,
    pmin,
    hlen,
    hext,
    flen,
    fext,
    nt,
):
    """:func:`reroute_turns` on ``nt`` threads (the same paths for any ``nt``)."""
    h, w = occ.shape
    hw = h * w
    flat_occ = occ.ravel()
    n = pick.shape[0]
    state, g, came, heap, touched, buf = _turn_scratch(nt, 9 * hw)
    pos = np.full((nt, hw), -1, np.int64)
    bsz = _block(nt, hw)
    rows = np.empty((bsz, hw), np.int64)
    cnts = np.zeros(bsz, np.int64)
    out = np.empty(max(16, n * (h + w)), np.int64)
    out_off = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    for lo in range(0, n, bsz):
        hi = min(n, lo + bsz)
        for k in numba.prange(nt):
            for r in range(lo + k, hi, nt):
                cnts[r - lo] = _reroute_turns_one(
                    flat, offsets, pick, i0, i1, genes, tgenes, r, flat_occ, h, w, extra, corner_cutting,
                    lam_lo, lam_hi, tau_lo, tau_hi, margin, pmin, hlen, hext, flen, fext, state[k], g[k],
                    came[k], heap[k], touched[k], buf[k], pos[k], rows[r - lo],
                )  # fmt: skip
        for r in range(lo, hi):
            out = _store(rows[r - lo], cnts[r - lo], r, out, out_off, keys)
    return out[: out_off[n]], out_off, keys
