"""Backward heuristics and set-up of the free exact search (private; numba kernels).

:func:`_free_prepare` is the one kernel call that starts a search (move
masks, heuristics, the initial search state); :func:`_free_heuristics` computes, by label-setting searches from the goal,
the exact single-objective costs-to-go that :func:`gapath.planners.exact.free_front`
uses as its heuristics; :func:`_move_masks` the allowed moves of every cell.
Each pass uses the queue its costs allow:

* length (steps of 1 and sqrt(2)): Dinitz's bucket queue, buckets half a
  step wide: every distance in the lowest non-empty bucket is final (a
  predecessor on a shortest path is at least one step, two buckets, lower),
  so a bucket is emptied in any order, without a heap;
* vulnerability (non-negative real potentials): a 4-ary heap with stale
  entries skipped, sifting a hole rather than swapping;
* turns (eighths, 0 to 4 per step): the state (cell, heading) is split into
  "rotate by one eighth" (cost 1) and "step straight on" (cost 0), so that
  the least total turn is a 0-1 breadth-first search with a double-ended
  queue (three arcs per state instead of nine).

The passes are written out in one function each (numba's inlining of helper
functions that take arrays reference-counts every copy, which dominated the
time of the previous heap-based passes). Their results are exact, hence
independent of the order in which equal keys are processed: the arrays are
the same as those of any textbook Dijkstra (tests/test_exact_heuristics.py
checks them against one).
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import DC, DR, SQRT2
from gapath.planners._exact_kernels import _BIG_TURNS as BIG_TURNS
from gapath.planners._exact_kernels import MODE_CELL, N_SLOTS, _free_init

# _free_prepare calls _free_init: numba's on-disk cache of this file does not see a
# change there (it is keyed on this file alone), so a change of the search state's
# layout (N_ST = 11 since the parent table, twentieth session) comes with a change here


def _bit_tables():
    """``MOVES[m, :COUNT[m]]``: the moves (set bits) of mask ``m``, in order,
    so that the passes loop over the allowed moves only (a test per bit is a
    branch the processor cannot predict)."""
    moves = np.zeros((256, 8), np.int64)
    count = np.zeros(256, np.int64)
    for m in range(256):
        bits = [d for d in range(8) if (m >> d) & 1]
        moves[m, : len(bits)] = bits
        count[m] = len(bits)
    return moves, count


MOVES, COUNT = _bit_tables()


@numba.njit(cache=True)
def _move_masks(occ, corner_cutting):
    """(H*W,) uint8: bit ``d`` set if move ``d`` (:data:`gapath.grid.DR`,
    :data:`gapath.grid.DC`) from the cell is allowed: the target is inside
    the grid and free and, without corner cutting, a diagonal move has both
    orthogonal neighbours free (:func:`gapath.grid.can_step`). 0 for obstacle
    cells. The moves are symmetric: ``d`` from ``u`` to ``v`` is allowed iff
    the opposite move from ``v`` to ``u`` is.

    Branch-free per cell: the free cells are read from a copy of the grid
    with a blocked border."""
    h, w = occ.shape
    free = np.zeros((h + 2, w + 2), np.uint8)
    for r in range(h):
        for c in range(w):
            free[r + 1, c + 1] = 0 if occ[r, c] else 1
    m = np.empty(h * w, np.uint8)
    for r in range(h):
        for c in range(w):
            e = free[r + 1, c + 2]
            n = free[r, c + 1]
            wst = free[r + 1, c]
            s = free[r + 2, c + 1]
            ne = free[r, c + 2]
            nw = free[r, c]
            sw = free[r + 2, c]
            se = free[r + 2, c + 2]
            if not corner_cutting:
                ne &= n & e
                nw &= n & wst
                sw &= s & wst
                se &= s & e
            b = e | (ne << 1) | (n << 2) | (nw << 3) | (wst << 4) | (sw << 5) | (s << 6) | (se << 7)
            m[r * w + c] = b * free[r + 1, c + 1]
    return m


@numba.njit(cache=True)
def _length_to_go(mask, w, goal, hs, hd):
    """Fill ``hs``/``hd`` (int, ``-1`` preset) with the straight and diagonal
    step counts of a shortest path from each cell to ``goal``.

    Dinitz's bucket queue: bucket ``floor(2 * dist)``, 8 of them in a ring
    (a tentative distance exceeds the smallest one by at most sqrt(2), 3
    buckets); a bucket is a doubly linked list threaded through ``nxt`` /
    ``prv``, ``where`` the bucket of a queued cell (-1: not queued)."""
    n = mask.shape[0]
    off = np.empty(8, np.int64)
    for d in range(8):
        off[d] = DR[d] * w + DC[d]
    dist = np.full(n, np.inf)
    nxt = np.empty(n, np.int32)
    prv = np.empty(n, np.int32)
    where = np.full(n, -1, np.int8)
    head = np.full(8, -1, np.int32)
    dist[goal] = 0.0
    hs[goal] = 0
    hd[goal] = 0
    head[0] = goal
    nxt[goal] = -1
    prv[goal] = -1
    where[goal] = 0
    queued = 1
    cur = 0
    while queued > 0:
        b = cur & 7
        u = head[b]
        if u < 0:
            cur += 1
            continue
        head[b] = nxt[u]
        if nxt[u] >= 0:
            prv[nxt[u]] = -1
        where[u] = -1
        queued -= 1
        mk = mask[u]
        su = hs[u]
        du = hd[u]
        for j in range(COUNT[mk]):
            d = MOVES[mk, j]
            v = u + off[d]
            odd = d & 1
            ns = su + 1 - odd
            nd = du + odd
            val = ns + SQRT2 * nd
            if val < dist[v]:
                wb = where[v]
                if wb >= 0:  # unlink v from its bucket
                    a, z = prv[v], nxt[v]
                    if a >= 0:
                        nxt[a] = z
                    else:
                        head[wb] = z
                    if z >= 0:
                        prv[z] = a
                else:
                    queued += 1
                dist[v] = val
                hs[v] = ns
                hd[v] = nd
                nb = np.int8(np.int64(2.0 * val) & 7)
                z = head[nb]
                nxt[v] = z
                prv[v] = -1
                if z >= 0:
                    prv[z] = v
                head[nb] = v
                where[v] = nb


@numba.njit(cache=True)
def _vulnerability_to_go(mask, pot, w, goal, hv):
    """Fill ``hv`` (``inf`` preset) with the smallest potential sum over the
    cells after each cell up to the goal included (0 at the goal).

    Dijkstra on ``D(u) = pot(u) + min_v D(v)``, ``D(goal) = pot(goal)``,
    ``hv(u) = min_v D(v)`` over the allowed moves ``u -> v``, with a 4-ary
    heap of (key, cell) entries, sifting a hole. The cost of entering a cell
    is its own potential, so a cell's key is final when it is first reached:
    the first neighbour settled next to it gives the least ``D`` (one settled
    later has a key at least as large, and rounding is monotone). So a cell,
    when reached, is cleared from its neighbours' moves (``rem``; the moves
    are symmetric, and the goal is cleared first), and a settled cell relaxes
    the moves left with no test of the key: each cell is reached and pushed
    once (its moves in are cleared when it is), so the heap needs one entry
    a cell and has no stale ones, and ``D`` is not stored: ``D(u)`` is
    ``pot(u) + hv(u)``, the sum that set it. A cell whose potential is 0 (a
    third of Berlin_1_256's free cells: no obstacle within the kernel's
    window) gets the key of the cell that reaches it, the least key there
    is, so it is settled next without entering the heap. The settling order stays
    non-decreasing in key, so the values are those of any Dijkstra: ``hv``
    of a cell is the key of the first neighbour to reach its least ``D``,
    and neighbours with different keys are settled in key order."""
    n = mask.shape[0]
    off = np.empty(8, np.int64)
    for d in range(8):
        off[d] = DR[d] * w + DC[d]
    pf = pot.reshape(n)
    keys = np.empty(n)  # each cell is pushed at most once (see above)
    ids = np.empty(n, np.int32)
    hv[goal] = 0.0
    keys[0] = pf[goal]  # D(goal)
    ids[0] = goal
    size = 1
    # the moves not yet known useless: a move into a reached cell (its key is
    # final when first reached, see above) or into the goal relaxes nothing,
    # so a cell, when reached, is cleared from its neighbours' moves (the
    # moves are symmetric), and the loop below tests no key
    rem = mask.copy()
    mk = mask[goal]
    for j in range(COUNT[mk]):
        d = MOVES[mk, j]
        rem[goal + off[d]] &= ~np.uint8(1 << ((d + 4) & 7))
    # a cell reached through a zero potential gets the key of the cell being
    # settled, the least there is: it waits on a stack (each cell at most
    # once, its key falls no further), emptied before the heap is popped
    stack = np.empty(n, np.int32)
    sp = 0
    while size > 0 or sp > 0:
        if sp > 0:
            sp -= 1
            u = stack[sp]
            du = pf[u] + hv[u]  # D(u), the sum that set it
        else:
            # pop the smallest entry
            u = ids[0]
            du = keys[0]
            size -= 1
            if size > 0:
                # bottom-up: the hole goes down along the least child (four
                # compared without branches) to a leaf, then the last entry
                # rises from there
                key = keys[size]
                x = ids[size]
                i = 0
                ch = 1
                while ch + 3 < size:
                    a, b = keys[ch], keys[ch + 1]
                    c, d = keys[ch + 2], keys[ch + 3]
                    ia = ch + (b < a)
                    a = min(a, b)
                    ic = ch + 2 + (d < c)
                    c = min(c, d)
                    if c < a:
                        ia = ic
                        a = c
                    keys[i] = a
                    ids[i] = ids[ia]
                    i = ia
                    ch = 4 * i + 1
                if ch < size:
                    ia = ch
                    a = keys[ch]
                    for c2 in range(ch + 1, size):
                        if keys[c2] < a:
                            a = keys[c2]
                            ia = c2
                    keys[i] = a
                    ids[i] = ids[ia]
                    i = ia
                while i > 0:
                    p = (i - 1) >> 2
                    if not key < keys[p]:
                        break
                    keys[i] = keys[p]
                    ids[i] = ids[p]
                    i = p
                keys[i] = key
                ids[i] = x
        mk = rem[u]
        for j in range(COUNT[mk]):
            v = u + off[MOVES[mk, j]]
            val = pf[v] + du  # D(v): v is reached now, for good
            hv[v] = du
            mv = mask[v]
            for jj in range(COUNT[mv]):
                dd = MOVES[mv, jj]
                rem[v + off[dd]] &= ~np.uint8(1 << ((dd + 4) & 7))
            if val == du:  # a zero potential: settled next, from the stack
                stack[sp] = v
                sp += 1
                continue
            i = size  # push: sift the hole up
            size += 1
            while i > 0:
                p = (i - 1) >> 2
                if not val < keys[p]:
                    break
                keys[i] = keys[p]
                ids[i] = ids[p]
                i = p
            keys[i] = val
            ids[i] = v


@numba.njit(cache=True)
def _turns_to_go(mask, h, w, goal, ht):
    """Fill ``ht`` (``(H*W*9,)``, :data:`BIG_TURNS` preset) with the least
    total turn (eighths) from each cell, arrived with heading slot ``k``
    (8 = no heading), to the goal.

    ``T(u, k) = min_d turn(k, d) + T(u + d, d)`` over the allowed moves ``d``,
    ``T(goal, k) = 0``. ``turn(k, d)`` is the number of one-eighth rotations
    between the headings, so ``T`` is also the least cost over a graph with
    two kinds of arcs: rotate at ``u`` (``(u, k) -> (u, k +- 1)``, cost 1) and
    step straight on (``(u, k) -> (u + k, k)``, cost 0): a 0-1 breadth-first
    search, here backwards from the goal with a ring-buffer deque (0-arcs
    in front, 1-arcs at the back; a state is queued at most twice). Slot 8
    (no heading: the first step is free) is ``min_k T(u, k)``."""
    n = h * w
    n8 = n * 8
    off = np.empty(8, np.int64)
    for d in range(8):
        off[d] = DR[d] * w + DC[d]
    t = np.full(n8, BIG_TURNS, np.int64)  # T over (cell, heading 0..7)
    done = np.zeros(n8, np.bool_)
    cap = 1
    while cap < 2 * n8 + 8:
        cap *= 2
    ring = np.empty(cap, np.int32)
    cm = cap - 1
    lo = 0  # index of the front entry
    hi = 0  # one past the back entry
    for k in range(8):
        s = goal * 8 + k
        t[s] = 0
        ring[hi & cm] = s
        hi += 1
    while lo != hi:
        s = ring[lo & cm]
        lo += 1
        if done[s]:
            continue
        done[s] = True
        ts = t[s]
        v = s >> 3
        d = s & 7
        # step straight on: (u, d) -> (v, d) with u = v - d, if d is allowed at u,
        # i.e. (the moves are symmetric) if the opposite move is allowed at v
        if (mask[v] >> ((d + 4) & 7)) & 1:
            p = (v - off[d]) * 8 + d
            if ts < t[p]:
                t[p] = ts
                lo -= 1
                ring[lo & cm] = p
        # rotate: (v, d +- 1) -> (v, d)
        t1 = ts + 1
        p = v * 8 + ((d + 1) & 7)
        if t1 < t[p]:
            t[p] = t1
            ring[hi & cm] = p
            hi += 1
        p = v * 8 + ((d + 7) & 7)
        if t1 < t[p]:
            t[p] = t1
            ring[hi & cm] = p
            hi += 1
    for c in range(n):
        m = BIG_TURNS
        for k in range(8):
            x = t[c * 8 + k]
            ht[c * N_SLOTS + k] = x
            if x < m:
                m = x
        ht[c * N_SLOTS + 8] = m


@numba.njit(cache=True)
def _free_heuristics(occ, pot, gr, gc, corner_cutting, with_turns, mask):
    """Exact single-objective costs-to-go, by backward searches from the goal.

    Returns
    -------
    hs, hd : (H*W,) int arrays
        Straight and diagonal step counts of a shortest path from each cell
        to the goal (``-1`` if the goal cannot be reached); the length
        heuristic is ``(ns + hs + sqrt(2) * (nd + hd)) * cell_size``, computed
        from integer totals so that equal f-values are bit-identical.
    hv : (H*W,) float array
        Smallest potential sum over the cells AFTER the cell up to the goal,
        goal included (``inf`` if unreachable, 0 at the goal). A label's
        vulnerability already counts its own cell, so ``g + hv`` is an
        admissible and consistent bound of the path's vulnerability.
    ht : (H*W*9,) int array
        Smallest total turn (eighths) from a cell, arrived with heading slot
        ``k`` (8 = none), to the goal, obstacles and corner rule included
        (:data:`BIG_TURNS` if unreachable); without ``with_turns`` a 1-entry
        placeholder (0 is then used, see ``_ht`` in ``_exact_kernels``).

    ``mask`` is :func:`_move_masks` of ``occ`` and ``corner_cutting`` (the
    two arguments are kept for the callers; ``mask`` alone decides).
    """
    h, w = occ.shape
    n = h * w
    goal = gr * w + gc
    hs = np.full(n, -1, np.int64)
    hd = np.full(n, -1, np.int64)
    _length_to_go(mask, w, goal, hs, hd)
    hv = np.full(n, np.inf)
    _vulnerability_to_go(mask, pot, w, goal, hv)
    if not with_turns:
        return hs, hd, hv, np.zeros(1, np.int64)
    ht = np.empty(n * N_SLOTS, np.int64)
    _turns_to_go(mask, h, w, goal, ht)
    return hs, hd, hv, ht


@numba.njit(cache=True, nogil=True)
def _free_prepare(occ, pot, sr, sc, gr, gc, cell_size, corner_cutting, mode, P, Q):
    """Everything a new free search needs, in one kernel call (each call and
    each returned array costs Python time, which dominated small maps): the
    move masks, the heuristics (the turns only outside ``MODE_CELL``) and the
    state of :func:`gapath.planners._exact_kernels._free_init`.

    Returns ``(mask, hs, hd, hv, ht, gmin, first, li, lf, sols, hk, hid, st,
    stf)``; the goal cannot be reached from the start iff
    ``hv[sr * W + sc] == inf``."""
    h, w = occ.shape
    mask = _move_masks(occ, corner_cutting)
    hs, hd, hv, ht = _free_heuristics(occ, pot, gr, gc, corner_cutting, mode != MODE_CELL, mask)
    n_states = h * w * (1 if mode == MODE_CELL else N_SLOTS)
    gmin, first, li, lf, sols, hk, hid, st, stf = _free_init(
        pot, sr, sc, w, cell_size, mode, P, Q, hs, hd, hv, ht, n_states
    )
    return mask, hs, hd, hv, ht, gmin, first, li, lf, sols, hk, hid, st, stf
