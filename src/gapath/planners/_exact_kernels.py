"""Numba kernels of :mod:`gapath.planners.exact` (private).

The free label-setting search (:func:`_free_run`) is resumable, like the
monotone DP of :mod:`gapath.planners._monotone_kernels`: its whole state
lives in arrays owned by the caller, and each call returns after a bounded
amount of work (a number of expansions) or when the label budget is exceeded, so
that Python can report progress, honour Ctrl-C and stop at a budget between
calls. Label tables grow by doubling.
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import DC, DR, SQRT2, turn

#: Relative tolerance of SPEC "Duplicates and ties".
TOL = 1e-9

#: Status codes of the resumable kernels (NEED_ROOM: internal to _free_run).
DONE, PAUSED, OVER_BUDGET, NEED_ROOM = range(4)

# ---------------------------------------------------------------------------
# monotone DP
# ---------------------------------------------------------------------------
# (the DP itself is in _monotone_kernels.py; the helpers below are shared)

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


# ---------------------------------------------------------------------------
# free search
# ---------------------------------------------------------------------------
# The search follows BOA* (Hernandez et al. 2020, 2023) for two objectives and
# NAMOA*-dr / EMOA* (Pulido et al. 2015; Ren et al. 2022) for three:
#
#   1. heuristics: one backward single-objective search per objective, from
#      the goal (_free_heuristics, in _exact_heuristics.py);
#   2. an open list of labels ordered lexicographically by their f-vectors
#      (_heap4_push / _heap4_pop; _free_init's first entry by _heap_push);
#   3. a label is dropped, when generated and again when popped, if a label
#      already expanded at its state covers it (_state_covered) or if a
#      solution already found covers its f-vector (_goal_covered); because
#      labels leave the open list in lexicographic order, these checks only
#      look at the objectives after the first one (dimensionality reduction);
#   4. otherwise a label at the goal is a solution; any other label joins its
#      state's set (g2_min / staircase) and is expanded along the 8 moves;
#   5. the solutions are traced back to paths (_trace) and filtered once more
#      with the tolerance (_tolerant_front).
#
# Labels live in two growable tables, like the monotone DP's:

CELL, F_HEAD, F_PARENT, NS, ND, TURNS, NEXT = range(7)  # int table
F_VUL = 0  # float table (one column)
# CELL: row * W + col; F_HEAD: heading of the last step (-1 at the start);
# NS/ND: straight/diagonal step counts; TURNS: total turn in eighths; NEXT:
# link of the apex search's free list of recycled rows (:func:`_free_run` keeps
# a stack of them instead; MODE_THREE's staircases are in their own pool,
# :func:`_stair_pool`). F_PARENT: the row of the parent label, except in
# :func:`_free_run`, where an expanded label leaves its row for an entry of a
# compact parent table (``pc``: cell, parent entry; 8 bytes instead of the
# row's 36) and F_PARENT is that entry (:func:`_trace_parents`).

OBJ_LEN, OBJ_VUL, OBJ_SMOOTH = range(3)
#: Search modes: BOA* on (length, vulnerability) with cells as states and
#: smoothness as tie-break; BOA* on (x, smoothness) with (cell, heading)
#: states; NAMOA*-dr on (length, vulnerability, smoothness).
MODE_CELL, MODE_HEADING, MODE_THREE = range(3)
N_SLOTS = 9  # per cell: the 8 headings and "no heading" (slot 8)
_BIG_TURNS = 1 << 40
#: MODE_THREE keeps per-cell summaries of its staircases in ``gmin`` (which the
#: two-objective modes use for g2_min): a block of THREE_BLOCK floats per cell,
#: the smallest vulnerability in any of the cell's 9 staircases, then for each
#: slot the head's vulnerability (the staircase's smallest; inf if empty), the
#: head's turns (the largest) and the tail's turns (the smallest); after the
#: blocks, the goal front (:func:`_goal_insert`). 4 * H * W * N_SLOTS floats.
THREE_BLOCK = 1 + 3 * N_SLOTS


@numba.njit(cache=True)
def _grow1(arr, size):
    """1-D ``arr`` with at least ``size`` entries (capacity doubled)."""
    if size <= arr.shape[0]:
        return arr
    out = np.empty(max(size, 2 * arr.shape[0]), arr.dtype)
    out[: arr.shape[0]] = arr
    return out


@numba.njit(cache=True, inline="always")
def _slot(head):
    """State slot of a heading (``-1``, no heading, is slot 8)."""
    return head if head >= 0 else 8


# -- open list: binary heap on (k1, k2, k3, label) ---------------------------


@numba.njit(cache=True, inline="always")
def _key_less(a1, a2, a3, an, b1, b2, b3, bn):
    if a1 != b1:
        return a1 < b1
    if a2 != b2:
        return a2 < b2
    if a3 != b3:
        return a3 < b3
    return an < bn


@numba.njit(cache=True, inline="always")
def _heap_push(hk, hid, size, k1, k2, k3, node):
    """Insert ``node`` with key ``(k1, k2, k3)`` into a heap of ``size``
    entries; the caller makes room first (:func:`_free_run`)."""
    i = size
    while i > 0:
        p = (i - 1) >> 1
        if not _key_less(k1, k2, k3, node, hk[p, 0], hk[p, 1], hk[p, 2], hid[p]):
            break
        hk[i, 0] = hk[p, 0]
        hk[i, 1] = hk[p, 1]
        hk[i, 2] = hk[p, 2]
        hid[i] = hid[p]
        i = p
    hk[i, 0] = k1
    hk[i, 1] = k2
    hk[i, 2] = k3
    hid[i] = node


@numba.njit(cache=True, inline="always")
def _heap4_push(hk, size, k1, k2, k3, node):
    """:func:`_heap_push` on a heap whose rows hold the label too (column 3,
    as a float: exact below 2**53), one row per level touched instead of
    two arrays (the open list of :func:`_free_steps` and of the apex
    search); the same order."""
    i = size
    fn = np.float64(node)
    while i > 0:
        p = (i - 1) >> 1
        if not _key_less(k1, k2, k3, fn, hk[p, 0], hk[p, 1], hk[p, 2], hk[p, 3]):
            break
        hk[i, 0] = hk[p, 0]
        hk[i, 1] = hk[p, 1]
        hk[i, 2] = hk[p, 2]
        hk[i, 3] = hk[p, 3]
        i = p
    hk[i, 0] = k1
    hk[i, 1] = k2
    hk[i, 2] = k3
    hk[i, 3] = fn


@numba.njit(cache=True, inline="always")
def _heap4_pop(hk, size):
    """Remove the smallest entry of a heap of :func:`_heap4_push` with
    ``size`` entries; returns ``(label, size - 1)``."""
    top = np.int64(hk[0, 3])
    size -= 1
    if size > 0:
        k1, k2, k3, node = hk[size, 0], hk[size, 1], hk[size, 2], hk[size, 3]
        i = 0
        while True:
            ch = 2 * i + 1
            if ch >= size:
                break
            if ch + 1 < size and _key_less(
                hk[ch + 1, 0],
                hk[ch + 1, 1],
                hk[ch + 1, 2],
                hk[ch + 1, 3],
                hk[ch, 0],
                hk[ch, 1],
                hk[ch, 2],
                hk[ch, 3],
            ):
                ch += 1
            if not _key_less(hk[ch, 0], hk[ch, 1], hk[ch, 2], hk[ch, 3], k1, k2, k3, node):
                break
            hk[i, 0] = hk[ch, 0]
            hk[i, 1] = hk[ch, 1]
            hk[i, 2] = hk[ch, 2]
            hk[i, 3] = hk[ch, 3]
            i = ch
        hk[i, 0] = k1
        hk[i, 1] = k2
        hk[i, 2] = k3
        hk[i, 3] = node
    return top, size


# -- 1. heuristics: gapath/planners/_exact_heuristics.py ---------------------


# -- label values -------------------------------------------------------------


@numba.njit(cache=True, inline="always")
def _ht(ht, c, head):
    """Turn heuristic of cell ``c`` arrived with heading ``head``; 0 (a valid
    lower bound) when ``ht`` is the 1-entry placeholder of a search that does
    not need it (two objectives without smoothness: turns only break ties)."""
    if ht.shape[0] == 1:
        return 0
    return ht[c * N_SLOTS + _slot(head)]


@numba.njit(cache=True, inline="always")
def _g(li, lf, i, o, cell_size):
    """Objective ``o`` of label ``i`` (smoothness in eighths)."""
    if o == OBJ_LEN:
        return (li[i, NS] + SQRT2 * li[i, ND]) * cell_size
    if o == OBJ_VUL:
        return lf[i, F_VUL]
    return np.float64(li[i, TURNS])


@numba.njit(cache=True, inline="always")
def _f(li, lf, i, o, cell_size, hs, hd, hv, ht):
    """Lower bound ``g + h`` of objective ``o`` over the completions of label ``i``."""
    c = li[i, CELL]
    if o == OBJ_LEN:
        return ((li[i, NS] + hs[c]) + SQRT2 * (li[i, ND] + hd[c])) * cell_size
    if o == OBJ_VUL:
        return lf[i, F_VUL] + hv[c]
    return np.float64(li[i, TURNS] + _ht(ht, c, li[i, F_HEAD]))


# -- 3. dominance checks --------------------------------------------------------


@numba.njit(cache=True)
def _goal_insert(li, lf, gmin, base, first, goal_state, x):
    """Record solution ``x`` in MODE_THREE's goal front.

    Solutions leave the open list in order of length, so covering a label at
    the goal is a 2-D question on (turns, vulnerability), like a state's
    staircase, but asked for every generated label; it is answered in O(1)
    by a prefix minimum over turn counts: ``gmin[base + u]`` is the smallest
    vulnerability of a solution with at most ``u`` eighth turns, for ``u <=
    first[goal_state]``, the largest turn count of a solution (-1: none
    yet). A solution's path is simple, so its turn count is below ``4 * H *
    W``, the room left after the cells' blocks (see THREE_BLOCK)."""
    _goal_record(gmin, base, first, goal_state, li[x, TURNS], lf[x, F_VUL])


@numba.njit(cache=True)
def _goal_record(gmin, base, first, goal_state, t, v):
    """Record a solution with ``t`` turns and vulnerability ``v`` in
    MODE_THREE's goal front (see :func:`_goal_insert`)."""
    tmax = first[goal_state]
    if t > tmax:
        fill = gmin[base + tmax] if tmax >= 0 else np.inf
        for u in range(tmax + 1, t + 1):
            gmin[base + u] = fill
        tmax = t
        first[goal_state] = t
    for u in range(t, tmax + 1):  # non-increasing: stop at the first entry <= v
        if gmin[base + u] <= v:
            break
        gmin[base + u] = v


#: MODE_THREE's staircases live in a pool of floats (``sp``, made by
#: :func:`_stair_pool`, grown by :func:`_free_run`): ``sp[SP_USED]`` floats
#: are in use, ``sp[SP_MAXCAP]`` is the largest block capacity so far. A
#: state ``s`` with a staircase owns the block at ``o = first[s]``:
#: ``sp[o]`` entries of ``sp[o + 1]`` capacity, their turns at ``sp[o + 2
#: + i]`` (decreasing) and their vulnerabilities at ``sp[o + 2 + cap + i]``
#: (increasing), ``i`` from the head (most turns, least vulnerable) to the
#: tail. A full block is replaced by one twice as large at the end of the
#: pool (the old one is left unused). Offsets are int32 (``first``): 2**31
#: floats, 17 GB of staircases, far beyond the label table of such a search.
SP_USED, SP_MAXCAP, SP_HEADER = 0, 1, 2
STAIR_CAP0 = 2


@numba.njit(cache=True)
def _stair_pool(n):
    """An empty staircase pool of ``n`` floats (at least the header)."""
    sp = np.empty(max(n, SP_HEADER + 2 + 2 * STAIR_CAP0))
    sp[SP_USED] = SP_HEADER
    sp[SP_MAXCAP] = STAIR_CAP0
    return sp


@numba.njit(cache=True, inline="always")
def _stair_room(sp):
    """Floats that one insertion may append to the pool."""
    return 2 + 4 * int(sp[SP_MAXCAP])


@numba.njit(cache=True, inline="always")
def _stair_covered(sp, o, bound, v):
    """True if the first entry of the staircase at ``o`` with at most
    ``bound`` turns is not more vulnerable than ``v`` (tolerance); the
    caller knows that the head has more turns than ``bound`` and the tail
    not (binary search over the entries in between). Vulnerability grows
    along the staircase, so that entry decides."""
    lo = 1
    hi = int(sp[o]) - 1  # the tail is within the bound
    while lo < hi:
        mid = (lo + hi) >> 1
        if sp[o + 2 + mid] <= bound:
            hi = mid
        else:
            lo = mid + 1
    return _le(sp[o + 2 + int(sp[o + 1]) + lo], v)


@numba.njit(cache=True)
def _three_insert(sp, first, gmin, s, t, v):
    """Insert an expanded label with ``t`` turns and vulnerability ``v``,
    which staircase ``s`` does not cover, into it (MODE_THREE), dropping
    the entries it makes redundant (as many turns or more and as
    vulnerable or more), and update the summaries of ``s`` and its cell
    (see THREE_BLOCK). The head's vulnerability never increases (a new head
    is less vulnerable than every entry)."""
    o = first[s]
    if o < 0:  # a new staircase
        o = int(sp[SP_USED])
        sp[SP_USED] = o + 2 + 2 * STAIR_CAP0
        sp[o] = 0
        sp[o + 1] = STAIR_CAP0
        first[s] = o
    n = int(sp[o])
    cap = int(sp[o + 1])
    tt = o + 2
    vv = o + 2 + cap
    p = 0  # the first entry with at most t turns
    while p < n and sp[tt + p] > t:
        p += 1
    q = p  # entries before q stay (less vulnerable than x)
    while q > 0 and not sp[vv + q - 1] < v:
        q -= 1
    r = p  # entries from r on stay (x is less vulnerable than one with t turns)
    if r < n and sp[tt + r] == t:
        r += 1
    m = q + 1 + n - r
    if m > cap:  # a block twice as large at the end of the pool
        cap2 = 2 * cap
        o2 = int(sp[SP_USED])
        sp[SP_USED] = o2 + 2 + 2 * cap2
        if cap2 > sp[SP_MAXCAP]:
            sp[SP_MAXCAP] = cap2
        tt2 = o2 + 2
        vv2 = o2 + 2 + cap2
        for i in range(q):
            sp[tt2 + i] = sp[tt + i]
            sp[vv2 + i] = sp[vv + i]
        for i in range(r, n):
            sp[tt2 + i - r + q + 1] = sp[tt + i]
            sp[vv2 + i - r + q + 1] = sp[vv + i]
        sp[o2 + 1] = cap2
        o, tt, vv = o2, tt2, vv2
        first[s] = o
    elif q + 1 < r:  # entries dropped: move the rest forward
        for i in range(r, n):
            sp[tt + i - r + q + 1] = sp[tt + i]
            sp[vv + i - r + q + 1] = sp[vv + i]
    elif q + 1 > r:  # nothing dropped: move the rest back by one
        for i in range(n - 1, r - 1, -1):
            sp[tt + i + 1] = sp[tt + i]
            sp[vv + i + 1] = sp[vv + i]
    sp[tt + q] = t
    sp[vv + q] = v
    sp[o] = m
    c = s // N_SLOTS
    b = c * THREE_BLOCK + 1 + 3 * (s % N_SLOTS)
    gmin[b] = sp[vv]
    gmin[b + 1] = sp[tt]
    gmin[b + 2] = sp[tt + m - 1]
    gmin[c * THREE_BLOCK] = min(gmin[c * THREE_BLOCK], gmin[b])


#: MODE_HEADING's floats per state in ``gmin`` (:func:`_state_covered`): the
#: charged turns of every state first (read at every check), then a ``(P, third
#: objective)`` pair per state (read on a tie).
HEADING_BLOCK = 3


@numba.njit(cache=True, inline="always")
def _state_covered(gmin, s, t, gp, gr):
    """MODE_HEADING: True if a label already expanded at the cell of state
    ``s`` covers a label at ``s`` with ``t`` turns, ``P`` value ``gp`` and
    third objective ``gr`` (:func:`_third`).

    BOA* with ``Q`` = turns: every expanded label ``a`` at the cell left the
    open list before ``x`` (or before ``x``'s parent), so ``P(a) <= P(x)``;
    ``a`` covers ``x`` when its turns, charged with the most by which the
    next turn after ``a``'s heading may exceed the one after ``x``'s
    (``_heading_gap``, 0 for ``x``'s own state), are below ``x``'s, or equal
    with ``P(a) < P(x)`` or, ``P`` tied too, with a third objective not
    above ``x``'s: among paths with equal ``(P, Q)`` the one best in the
    third objective is kept, so the front's paths are points of the
    three-objective front. :func:`_state_expand` keeps, for each heading of
    the cell, the least of those charged turns over the expanded labels,
    the ``P`` of the first label that reached it (the least) and the least
    third objective among those with that ``P``: one entry decides.
    """
    m = gmin[s]
    if m != t:
        return m < t
    return _tie_covered(gmin, s, gp, gr)


@numba.njit(cache=True, inline="always")
def _tie_covered(gmin, s, gp, gr):
    """MODE_HEADING: :func:`_state_covered` for a label whose turn count
    equals state ``s``'s least charged one."""
    b = gmin.shape[0] // HEADING_BLOCK + 2 * s
    return not _eq(gmin[b], gp) or _le(gmin[b + 1], gr)


@numba.njit(cache=True, inline="always")
def _state_expand(gmin, c, ha, t, gp, gr):
    """MODE_HEADING: label with heading ``ha``, ``t`` turns, ``P`` value ``gp``
    and third objective ``gr`` expanded at cell ``c``: each heading's entry of
    the cell (see :func:`_state_covered`) takes ``t`` charged with
    :func:`_heading_gap` from ``ha`` to it."""
    base = c * N_SLOTS
    pairs = gmin.shape[0] // HEADING_BLOCK + 2 * base
    for k in range(N_SLOTS):
        e = t + _heading_gap(ha, k if k < 8 else NO_HEADING)
        m = gmin[base + k]
        if e < m:
            gmin[base + k] = e
            gmin[pairs + 2 * k] = gp
            gmin[pairs + 2 * k + 1] = gr
        elif e == m and gr < gmin[pairs + 2 * k + 1] and _eq(gp, gmin[pairs + 2 * k]):
            gmin[pairs + 2 * k + 1] = gr


@numba.njit(cache=True, inline="always")
def _third(P):
    """MODE_HEADING (``Q`` = turns): the objective that breaks ``(P, Q)``
    ties, the vulnerability when ``P`` is the length, else the length."""
    return OBJ_VUL if P == OBJ_LEN else OBJ_LEN


@numba.njit(cache=True, inline="always")
def _p_third(P, length, vul):
    """MODE_HEADING: ``(P value, third objective's value)`` of a length and a
    vulnerability (:func:`_third`)."""
    if P == OBJ_LEN:
        return length, vul
    return vul, length


@numba.njit(cache=True, inline="always")
def _goal_covers(goal_min, goal_p, goal_r, fq, fp, fr):
    """MODE_HEADING: True if a solution already found covers the f-vector
    ``(fp, fq, fr)`` of a label (its lower bound at the goal; ``fr`` the
    third objective's, :func:`_third`). ``goal_min`` is the least turn count
    of the solutions, ``goal_p`` the ``P`` of the first one with it (the
    least: they leave the open list in ``P`` order) and ``goal_r`` the least
    third objective of those with that ``P``. Q is the (integer) turn count,
    so a tie within the tolerance is an equal turn count: covered when the
    ``P`` is larger or, tied too, the third objective is not smaller (the
    sums of float potentials behind a vulnerability tie differ in their
    rounding, so the open list's order alone cannot decide it)."""
    if goal_min == np.inf:
        return False
    if not _eq(fq, goal_min):
        return fq > goal_min
    return not _eq(goal_p, fp) or _le(goal_r, fr)


@numba.njit(cache=True, inline="always")
def _goal_covered(li, lf, x, P, Q, goal_min, goal_p, goal_r, cell_size, hs, hd, hv, ht):
    """MODE_HEADING: :func:`_goal_covers` for label ``x``."""
    if goal_min == np.inf:
        return False
    fq = _f(li, lf, x, Q, cell_size, hs, hd, hv, ht)
    if not _eq(fq, goal_min):  # (as _goal_covers; the P and third objective only on a tie)
        return fq > goal_min
    fp = _f(li, lf, x, P, cell_size, hs, hd, hv, ht)
    fr = _f(li, lf, x, _third(P), cell_size, hs, hd, hv, ht)
    return _goal_covers(goal_min, goal_p, goal_r, fq, fp, fr)


# -- the search -------------------------------------------------------------------

# scalars of the search state (int array ``st`` and float array ``stf``)
S_N, S_SIZE, S_SOLS, S_EXPANDED, S_GENERATED, S_GOAL_FIRST, S_FREE, S_N_FREE, S_POPS = range(9)
#: MODE_THREE's count of staircase searches (:func:`_stair_covered`: the checks the
#: summaries could not decide), at pops and at generation
S_SEARCHES = 9
#: :func:`_free_run`'s entries in the parent table ``pc`` (its expanded labels)
S_PC = 10
N_ST = 11
SF_GOAL_MIN = 0
#: MODE_HEADING: the ``P`` and the least third objective of the solutions with
#: ``SF_GOAL_MIN`` turns (:func:`_goal_covers`)
SF_GOAL_P, SF_GOAL_R = 1, 2


@numba.njit(cache=True)
def _free_init(pot, sr, sc, w, cell_size, mode, P, Q, hs, hd, hv, ht, n_states):
    """State of a new free search over ``n_states`` states: the start label
    alone on the open list.

    Returns ``(gmin, first, li, lf, sols, hk, hid, st, stf)``, the arrays
    :func:`_free_run` resumes from."""
    # BOA*: g2_min of each state; MODE_HEADING: HEADING_BLOCK floats per state;
    # MODE_THREE: staircase summaries and goal front (THREE_BLOCK)
    per_state = 4 if mode == MODE_THREE else (HEADING_BLOCK if mode == MODE_HEADING else 1)
    gmin = np.full(n_states * per_state, np.inf)
    first = np.full(n_states + 1, -1, np.int32)  # MODE_THREE: staircase block (_stair_pool)
    li = np.empty((1024, 7), np.int32)
    lf = np.empty((1024, 1))
    sols = np.empty(64, np.int32)
    hk = np.empty((1024, 3))
    hid = np.empty(1024, np.int32)
    # the start label: no step, no heading; the start cell counts for vulnerability
    li[0, CELL] = sr * w + sc
    li[0, F_HEAD] = -1
    li[0, F_PARENT] = -1
    li[0, NS] = 0
    li[0, ND] = 0
    li[0, TURNS] = 0
    li[0, NEXT] = -1
    lf[0, F_VUL] = pot[sr, sc]
    st = np.zeros(N_ST, np.int64)
    st[S_N] = 1
    st[S_SIZE] = 1
    st[S_GENERATED] = 1
    st[S_GOAL_FIRST] = -1
    st[S_FREE] = -1
    stf = np.full(3, np.inf)
    second = OBJ_VUL if mode == MODE_THREE else Q
    third = _third(P) if mode == MODE_HEADING else OBJ_SMOOTH
    _heap_push(
        hk,
        hid,
        0,
        _f(li, lf, 0, P, cell_size, hs, hd, hv, ht),
        _f(li, lf, 0, second, cell_size, hs, hd, hv, ht),
        _f(li, lf, 0, third, cell_size, hs, hd, hv, ht),
        0,
    )
    return gmin, first, li, lf, sols, hk, hid, st, stf


@numba.njit(cache=True, nogil=True)
def _free_run(
    occ,
    pot,
    gr,
    gc,
    cell_size,
    mask,
    mode,
    P,
    Q,
    hs,
    hd,
    hv,
    ht,
    gmin,
    first,
    li,
    lf,
    sols,
    hk,
    hid,
    st,
    stf,
    sp,
    pc,
    fs,
    n_steps,
    max_labels,
):
    """Advance the multi-objective label-setting search from start to goal
    by at most ``n_steps`` pops of the open list.

    ``mode`` is ``MODE_HEADING`` (``P`` = length or vulnerability, ``Q`` =
    smoothness, states = (cell, heading); the open list's third key and
    the ties of ``(P, Q)`` go to the other of length and vulnerability,
    :func:`_third`) or ``MODE_THREE`` (length,
    vulnerability, smoothness, states = (cell, heading)); ``MODE_CELL``
    (length, vulnerability) is BOA* in :mod:`gapath.planners._boa_kernels`.
    ``mask``: the allowed moves of each cell
    (:func:`gapath.planners._exact_heuristics._move_masks`).

    The state is the arrays made by :func:`_free_init`, the scalars in
    ``st``/``stf`` (updated in place) and MODE_THREE's staircase pool ``sp``
    (:func:`_stair_pool`; any small one in the other mode). A label dropped when it leaves the
    open list is referenced by nothing (it has no children and belongs to
    no state's set): its row is recycled, pushed on the stack of free rows
    ``fs`` (int32, at least as long as ``li``; ``st[S_N_FREE]`` of them),
    from which new labels take their rows first. An expanded label is
    needed only as its children's parent: its cell and parent go to the
    next entry of ``pc`` (int32, 2 columns; ``st[S_PC]`` entries used), its
    children's F_PARENT is that entry, and its row is recycled too. Only
    open labels and solutions keep rows. Stops before a pop that could
    take the labels held (rows in use and entries) beyond ``max_labels``.
    Returns ``(li, lf, sols, hk, hid, sp, pc, fs, status)``,
    status DONE (open list empty), PAUSED or OVER_BUDGET. The open list
    keeps each label in its heap row (column 3, :func:`_heap4_push`): the
    3-column heap of :func:`_free_init` is widened at the first call (``hid``
    then only sets the heap's capacity).

    The search itself is :func:`_free_steps`, which never reallocates (an
    array reassigned inside a numba loop is reference-counted at every
    branch, which cost most of the time): it returns when an array is full,
    and this loop doubles it.
    """
    pops0 = st[S_POPS]
    if hk.shape[1] == 3:  # a new search: labels into the heap rows
        hk = _heap_rows(hk, hid, st[S_SIZE])
    while True:
        status = _free_steps(
            occ,
            pot,
            gr,
            gc,
            cell_size,
            mask,
            mode,
            P,
            Q,
            hs,
            hd,
            hv,
            ht,
            gmin,
            first,
            li,
            lf,
            sols,
            hk,
            hid,
            st,
            stf,
            sp,
            pc,
            fs,
            n_steps - (st[S_POPS] - pops0),
            max_labels,
        )
        if status != NEED_ROOM:
            return li, lf, sols, hk, hid, sp, pc, fs, status
        li, lf, sols, hk, hid, sp = _make_room(li, lf, sols, hk, hid, sp, st, mode == MODE_THREE)
        pc = _grow(pc, st[S_PC] + 1)  # (each returns its table when it is large enough)
        fs = _grow1(fs, li.shape[0])


@numba.njit(cache=True)
def _heap_rows(hk, hid, size):
    """The open list of a new search (either mode, and the apex search):
    the 3-column heap of :func:`_free_init` with each entry's label in a
    4th column."""
    hk4 = np.empty((hk.shape[0], 4))
    for i in range(size):
        hk4[i, :3] = hk[i]
        hk4[i, 3] = hid[i]
    return hk4


@numba.njit(cache=True)
def _make_room(li, lf, sols, hk, hid, sp, st, three):
    """The tables of a search loop that returned NEED_ROOM, each doubled
    if the next pop could overflow it (the staircase pool with ``three``)."""
    if st[S_N] + 8 > li.shape[0]:
        li = _grow(li, st[S_N] + 8)
        lf = _grow(lf, st[S_N] + 8)
    if st[S_SIZE] + 8 > hid.shape[0]:
        hk = _grow(hk, st[S_SIZE] + 8)
        hid = _grow1(hid, st[S_SIZE] + 8)
    if st[S_SOLS] + 1 > sols.shape[0]:
        sols = _grow1(sols, st[S_SOLS] + 1)
    if three and sp[SP_USED] + _stair_room(sp) > sp.shape[0]:
        sp = _grow1(sp, int(sp[SP_USED]) + _stair_room(sp))
    return li, lf, sols, hk, hid, sp


@numba.njit(cache=True, _nrt=False)
def _free_steps(
    occ,
    pot,
    gr,
    gc,
    cell_size,
    mask,
    mode,
    P,
    Q,
    hs,
    hd,
    hv,
    ht,
    gmin,
    first,
    li,
    lf,
    sols,
    hk,
    hid,
    st,
    stf,
    sp,
    pc,
    fs,
    n_steps,
    max_labels,
):
    """The search loop of :func:`_free_run`, in arrays it never reallocates:
    returns NEED_ROOM before a pop when the label tables, the heap, the
    solution list or the parent table could overflow (the free rows' stack
    ``fs`` is as long as the label table)."""
    h, w = occ.shape
    goal = gr * w + gc
    goal_state = first.shape[0] - 1  # MODE_THREE: first[goal_state] = largest solution turns (_goal_insert)
    goal_base = THREE_BLOCK * h * w  # MODE_THREE: the goal front in gmin (_goal_insert)
    second = OBJ_VUL if mode == MODE_THREE else Q
    n = st[S_N]
    size = st[S_SIZE]
    n_sols = st[S_SOLS]
    n_expanded = st[S_EXPANDED]
    n_generated = st[S_GENERATED]
    n_free = st[S_N_FREE]
    goal_min = stf[SF_GOAL_MIN]
    goal_p = stf[SF_GOAL_P]
    goal_r = stf[SF_GOAL_R]
    status = DONE
    steps = 0
    pops0 = st[S_POPS]
    n_searches = st[S_SEARCHES]
    n_pc = st[S_PC]
    gp = gr = 0.0  # MODE_HEADING: the popped label's P and third objective (_p_third)

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
        if n_pc + 1 > pc.shape[0]:
            status = NEED_ROOM
            break
        if mode == MODE_THREE and sp[SP_USED] + _stair_room(sp) > sp.shape[0]:
            status = NEED_ROOM
            break
        steps += 1
        # 2. the lexicographically smallest label
        x, size = _heap4_pop(hk, size)
        c = li[x, CELL]

        # 3. dominance checks (lazy: the sets changed since x was generated)
        if mode == MODE_THREE:
            # the staircases walked here, as at generation (see below); x's heading is
            # -1 only for the start label
            t = li[x, TURNS]
            v = lf[x, F_VUL]
            hx = li[x, F_HEAD]
            covered = False
            base = c * THREE_BLOCK
            if c != goal and gmin[base] < np.inf and _le(gmin[base], v):
                for k in range(N_SLOTS):
                    b = base + 1 + 3 * k
                    if gmin[b] == np.inf or not _le(gmin[b], v):
                        continue
                    bound = t - (0 if k == 8 else (4 if hx < 0 else turn(k, hx)))  # _heading_gap
                    if gmin[b + 2] > bound:  # the tail: nothing within the bound
                        continue
                    if gmin[b + 1] <= bound:  # the head: the least vulnerable is within it
                        covered = True
                        break
                    # the first entry within the bound (vulnerability grows along it)
                    n_searches += 1
                    if _stair_covered(sp, first[c * N_SLOTS + k], bound, v):
                        covered = True
                        break
            tmax = first[goal_state]
            if not covered and tmax >= 0:
                bound = t + (ht[c * N_SLOTS + (hx if hx >= 0 else 8)] if ht.shape[0] > 1 else 0)
                m = gmin[goal_base + min(bound, tmax)]
                covered = m < np.inf and _le(m, v + hv[c])
        else:
            # x's P and third objective: its state's tie-break, its solution's, its expansion's
            gp, gr = _p_third(P, _g(li, lf, x, OBJ_LEN, cell_size), lf[x, F_VUL])
            covered = c != goal and _state_covered(
                gmin, c * N_SLOTS + _slot(li[x, F_HEAD]), li[x, TURNS], gp, gr
            )
            covered = covered or _goal_covered(
                li, lf, x, P, Q, goal_min, goal_p, goal_r, cell_size, hs, hd, hv, ht
            )
        if covered:
            fs[n_free] = x  # recycle the row
            n_free += 1
            continue

        # 4a. a solution: record it, never expand it
        if c == goal:
            if mode == MODE_THREE:
                _goal_insert(li, lf, gmin, goal_base, first, goal_state, x)
            else:
                gq = _g(li, lf, x, Q, cell_size)
                if gq < goal_min:
                    goal_min, goal_p, goal_r = gq, gp, gr
                elif gq == goal_min and gr < goal_r and _eq(gp, goal_p):
                    goal_r = gr
            sols[n_sols] = x
            n_sols += 1
            continue

        # 4b. expand x: it joins its state's set, and leaves its row for a parent entry
        n_expanded += 1
        pc[n_pc, 0] = c
        pc[n_pc, 1] = li[x, F_PARENT]
        parent = n_pc
        n_pc += 1
        s = c * N_SLOTS + _slot(li[x, F_HEAD])
        if mode == MODE_THREE:
            _three_insert(sp, first, gmin, s, li[x, TURNS], lf[x, F_VUL])
        else:  # MODE_HEADING: charged g2_min, and the P and third objective at it
            _state_expand(gmin, c, li[x, F_HEAD], li[x, TURNS], gp, gr)
        r, col = c // w, c % w
        head = li[x, F_HEAD]
        x_ns, x_nd, x_t, x_v = li[x, NS], li[x, ND], li[x, TURNS], lf[x, F_VUL]
        mk = mask[c]
        for d in range(8):
            if not (mk >> d) & 1:
                continue
            r2, c2 = r + DR[d], col + DC[d]
            cell = r2 * w + c2
            if hv[cell] == np.inf:  # the goal cannot be reached from there
                continue
            if n_free > 0:  # the row recycled last (the free rows are a stack)
                j = fs[n_free - 1]
            else:
                j = n
            # the new label's values; its row is written only once it is kept (most
            # generated labels are not)
            ns_j = x_ns + (1 - d % 2)
            nd_j = x_nd + d % 2
            t = x_t + (turn(head, d) if head >= 0 else 0)
            v = x_v + pot[r2, c2]
            n_generated += 1
            # the f-vector, written out (helper calls on the arrays cost reference counting)
            f_len = ((ns_j + hs[cell]) + SQRT2 * (nd_j + hd[cell])) * cell_size
            f_vul = v + hv[cell]
            f_turn = np.float64(t + (ht[cell * N_SLOTS + d] if ht.shape[0] > 1 else 0))
            # 3. eager dominance checks (prune before the open list)
            if mode == MODE_THREE:
                # the (turns, vulnerability) staircases, searched here (see above)
                covered = False
                base = cell * THREE_BLOCK
                if cell != goal and gmin[base] < np.inf and _le(gmin[base], v):
                    for k in range(N_SLOTS):
                        b = base + 1 + 3 * k
                        if gmin[b] == np.inf or not _le(gmin[b], v):
                            continue
                        bound = t - (0 if k == 8 else turn(k, d))  # _heading_gap
                        if gmin[b + 2] > bound:  # the tail: nothing within the bound
                            continue
                        if gmin[b + 1] <= bound:  # the head: the least vulnerable is within it
                            covered = True
                            break
                        n_searches += 1
                        if _stair_covered(sp, first[cell * N_SLOTS + k], bound, v):  # as at the pop
                            covered = True
                            break
                tmax = first[goal_state]
                if not covered and tmax >= 0:
                    bound = t + (ht[cell * N_SLOTS + d] if ht.shape[0] > 1 else 0)
                    m = gmin[goal_base + min(bound, tmax)]
                    covered = m < np.inf and _le(m, f_vul)
                if covered:
                    continue
            else:  # _state_covered and _goal_covered on the values (Q = turns)
                if cell != goal:
                    gp, gr = _p_third(P, (ns_j + SQRT2 * nd_j) * cell_size, v)
                    if _state_covered(gmin, cell * N_SLOTS + d, t, gp, gr):
                        continue
                fp, fr = _p_third(P, f_len, f_vul)
                if _goal_covers(goal_min, goal_p, goal_r, f_turn, fp, fr):
                    continue
            if n_free > 0:
                n_free -= 1
            else:
                n += 1
            li[j, CELL] = cell
            li[j, F_HEAD] = d
            li[j, F_PARENT] = parent
            li[j, NS] = ns_j
            li[j, ND] = nd_j
            li[j, TURNS] = t
            lf[j, F_VUL] = v
            k1 = f_len if P == OBJ_LEN else (f_vul if P == OBJ_VUL else f_turn)
            k2 = f_len if second == OBJ_LEN else (f_vul if second == OBJ_VUL else f_turn)
            # MODE_HEADING: (P, turns, the third objective); MODE_THREE: (length, vul, turns)
            k3 = f_turn if mode == MODE_THREE else _p_third(P, f_len, f_vul)[1]
            _heap4_push(hk, size, k1, k2, k3, j)
            size += 1
        fs[n_free] = x  # x's values now live in its state's set and in pc
        n_free += 1
    st[S_N] = n
    st[S_SIZE] = size
    st[S_SOLS] = n_sols
    st[S_EXPANDED] = n_expanded
    st[S_GENERATED] = n_generated
    st[S_N_FREE] = n_free
    st[S_POPS] = pops0 + steps
    st[S_SEARCHES] = n_searches
    st[S_PC] = n_pc
    stf[SF_GOAL_MIN] = goal_min
    stf[SF_GOAL_P] = goal_p
    stf[SF_GOAL_R] = goal_r
    return status


# -- 5. paths and the final filter ------------------------------------------------


@numba.njit(cache=True, nogil=True)
def _trace(li, sols, w):
    """Cells of the solution paths, concatenated, and their offsets, where
    each label's row holds its parent's row (BOA*, the apex search):
    :func:`_trace_parents` with the rows' (CELL, F_PARENT) columns as the
    parent table."""
    return _trace_parents(li, li[:, CELL : F_PARENT + 1 : F_PARENT - CELL], sols, w)


@numba.njit(cache=True, nogil=True)
def _trace_parents(li, pc, sols, w):
    """Cells of the solution paths, concatenated, and their offsets: each
    solution's row, then its chain of parents, ``pc[a]`` = (cell, parent)
    (:func:`_free_run`'s parent table)."""
    counts = np.empty(len(sols), np.int64)
    for i in range(len(sols)):
        k = 1
        a = li[sols[i], F_PARENT]
        while a >= 0:
            k += 1
            a = pc[a, 1]
        counts[i] = k
    offsets = np.zeros(len(sols) + 1, np.int64)
    offsets[1:] = np.cumsum(counts)
    cells = np.empty((offsets[-1], 2), np.int64)
    for i in range(len(sols)):
        j = offsets[i + 1] - 1
        cells[j, 0] = li[sols[i], CELL] // w
        cells[j, 1] = li[sols[i], CELL] % w
        a = li[sols[i], F_PARENT]
        while a >= 0:
            j -= 1
            cells[j, 0] = pc[a, 0] // w
            cells[j, 1] = pc[a, 0] % w
            a = pc[a, 1]
    return cells, offsets


@numba.njit(cache=True)
def _tolerant_front(F, order):
    """Indices of the rows of ``F`` that no other row dominates up to the
    tolerance, one per tolerance-equal vector: the first one in ``order``
    (a permutation of the rows, most preferred first)."""
    k, m = F.shape
    keep = np.ones(k, np.bool_)
    for i in range(k):
        for j in range(k):
            if j == i:
                continue
            not_worse = True
            better = False
            for o in range(m):
                if not _le(F[j, o], F[i, o]):
                    not_worse = False
                    break
                if not _eq(F[j, o], F[i, o]):
                    better = True
            if not_worse and better:
                keep[i] = False
                break
    out = np.empty(k, np.int64)
    n = 0
    for i in order:
        if not keep[i]:
            continue
        dup = False
        for jj in range(n):
            j = out[jj]
            same = True
            for o in range(m):
                if not _eq(F[j, o], F[i, o]):
                    same = False
                    break
            if same:
                dup = True
                break
        if not dup:
            out[n] = i
            n += 1
    return out[:n]
