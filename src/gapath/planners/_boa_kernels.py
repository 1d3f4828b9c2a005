"""Numba kernels of the two-objective free search (private): BOA* on
(length, vulnerability) and the smoothest representative of tied vectors.

:func:`_boa_run` is BOA* (Hernandez et al. 2020, 2023) with cells as states,
resumable like :func:`gapath.planners._exact_kernels._free_run` (its state,
built by :func:`_boa_start`: the arrays of
:func:`gapath.planners._exact_kernels._free_init` with the open list's
bucket heads in ``hid``, plus an edge table and
the counters ``est``). Its open list is a small heap fed by buckets of
f_length (see ``BUCKETS_PER_CELL``). With ``ties=False`` it is BOA* as published: a label whose
second objective ties ``g2_min`` of its cell within SPEC's tolerance is
dropped, whatever its path.

With ``ties=True`` (the default tie-break: the smoothest path among
tolerance-equal objective vectors) the search expands the same labels, and
three things change:

* a label dropped because it ties, in both objectives and within the
  tolerance, the label last expanded at its cell (or the last solution, at
  the goal) is recorded as an alternative in-edge of that label: a row
  ``(label, parent, direction)`` of the edge table. The dropped label's
  paths are the parent's paths plus one step; they have the tied label's
  vector, so that label stands for all of them. Labels dropped because they
  are dominated are not recorded;
* the goal test keeps a label whose f-vector ties the last solution in both
  objectives (BOA* drops it): a tied path that left the first one earlier
  would be lost otherwise;
* a waiting label that its cell's ``g2_min`` covers beyond the tolerance
  when its bucket is poured is dropped there instead of at its pop (see
  :func:`_pour_drops`), and so is one tied with ``g2_min`` from above whose
  length does not tie the label last expanded at its cell
  (:func:`_pour_drops_tied`), and one clear of ``g2_min`` that the last
  solution covers by more than three tolerances (``GOAL_MARGIN``): its pop
  would drop each of them without an edge, whatever happens before then.
  The same decisions, fewer heap operations. Its row
  is reused earlier, and rows break exact ties of the open list's keys, so
  among paths with exactly equal (length, vulnerability, smoothness)
  another may be returned than without it (``F`` and smoothness are the
  same). Without ties nothing is dropped early.

The expanded labels and their in-edges (the primary one, to the label's own
parent, and the recorded ones) form a DAG that holds, up to the tolerance,
every path whose prefixes are Pareto-optimal at their cells, hence every
path of every front vector. :func:`_smoothest` runs a min-turn dynamic
programme over that DAG, state (label, incoming heading), and traces the
smoothest path of each solution, with its objectives recomputed along the
path in path order (so that they equal :func:`gapath.objectives.evaluate_path`).
Tied labels are never expanded: the cost of the tie-break is one row per
tie and about eight operations per edge after the search.
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import DC, DIRECTION, DR, SQRT2, turn
from gapath.objectives import QUARTER_PI
from gapath.planners._exact_heuristics import COUNT, MOVES, _length_to_go, _move_masks, _vulnerability_to_go
from gapath.planners._exact_kernels import (
    CELL,
    DONE,
    F_HEAD,
    F_PARENT,
    F_VUL,
    MODE_CELL,
    ND,
    NEED_ROOM,
    NEXT,
    NS,
    OBJ_LEN,
    OBJ_VUL,
    OVER_BUDGET,
    PAUSED,
    S_EXPANDED,
    S_FREE,
    S_GENERATED,
    S_GOAL_FIRST,
    S_N,
    S_N_FREE,
    S_POPS,
    S_SIZE,
    S_SOLS,
    SF_GOAL_MIN,
    TOL,
    TURNS,
    _eq,
    _free_init,
    _grow,
    _grow1,
    _tolerant_front,
    _trace,
)

# _boa_start calls _free_init: numba's on-disk cache of this file does not see a
# change there (it is keyed on this file alone), so a change of the search state's
# layout (N_ST = 11 since the parent table, twentieth session) comes with a change here

#: Columns of the edge table: the label the edge enters, its parent (an
#: expanded label) and the direction of the step.
E_NODE, E_PARENT, E_DIR = range(3)

_BIG = np.int64(1) << 40

#: Open-list keys: ``(f_length, f_vulnerability, turns * ROW_SPAN + row)``, the
#: third exact while below 2**53 (turns < 2**22). The start label's key of
#: ``_free_init`` (third entry 0.0, row 0) is such a key.
ROW_SPAN = float(1 << 31)
ROW_MASK = np.int64((1 << 31) - 1)

#: The open list is two-level (f_length never decreases from pop to pop, and
#: runs of tens to hundreds of pops share one value): a 4-ary heap ``hk`` on the
#: full keys holds the labels whose bucket ``floor(f_length * BUCKETS_PER_CELL /
#: cell_size)`` is at most the current one (``E_CUR``); the later ones wait,
#: unordered, in singly linked lists through the rows' NEXT: one per bucket of
#: the window ``(cur, cur + N_BUCKETS)`` (heads in ``hid``) and one overflow list
#: beyond it. A bucket is poured into the heap when the heap runs empty. The heap
#: orders by the full keys, which are distinct, so the pops come in the same order
#: as from one heap. A waiting label's keys are recomputed from its row when its
#: bucket is poured (the same sums as at the push, hence the same floats):
#: keeping them in the label float table was slower (a wider table) and took
#: 16 more bytes a row.
BUCKETS_PER_CELL = 32.0
N_BUCKETS = 256
#: Entries of ``est``: edges recorded, the current bucket, the overflow list's
#: head, its least bucket, the labels waiting in the window and in the overflow.
E_EDGES, E_CUR, E_OHEAD, E_OMIN, E_NWIN, E_NOVER = range(6)
_NO_BUCKET = np.int64(1) << 62
#: A waiting label away from the goal is dropped at the pour when its
#: f_vulnerability exceeds the last solution's by more than this (relative,
#: as SPEC's tolerance), see _pour_drops: three tolerances, one more than
#: the proof needs.
GOAL_MARGIN = 3.0 * TOL
#: The label tables start with 4 rows a cell, at most this many (see _boa_start).
LABEL_ROWS = 1 << 18

#: Bits set in a byte, and the heading of a byte's single set bit.
_POPCOUNT = np.array([bin(b).count("1") for b in range(256)], np.int64)
_LOWBIT = np.zeros(256, np.int64)
for _d in range(8):
    _LOWBIT[1 << _d] = _d


@numba.njit(cache=True, nogil=True)
def _boa_run(
    occ,
    pot,
    gr,
    gc,
    cell_size,
    mask,
    hs,
    hd,
    hv,
    gmin,
    first,
    li,
    lf,
    sols,
    hk,
    hid,
    st,
    stf,
    edges,
    est,
    n_steps,
    max_labels,
    ties,
):
    """Advance BOA* by at most ``n_steps`` pops of the open list.

    The arguments are those of :func:`gapath.planners._exact_kernels._free_run`
    for ``mode=MODE_CELL`` (without the turn heuristic, which a two-objective
    search does not use) plus ``edges``, the (capacity, 3) int32 edge table,
    and ``est``, the ``E_*`` counters (updated in place: the number of edges
    and the open list's buckets); ``hid`` holds the buckets' heads. ``first[c]`` is the
    label last expanded at cell ``c``. Returns ``(li, lf, sols, hk, hid,
    edges, status)``; status DONE (open list empty), PAUSED or OVER_BUDGET.
    :func:`_boa_steps` never reallocates (reference counting of arrays
    reassigned in a numba loop cost most of the time); this loop grows what
    it asks for.
    """
    pops0 = st[S_POPS]
    while True:
        status = _boa_steps(
            occ,
            pot,
            gr,
            gc,
            cell_size,
            mask,
            hs,
            hd,
            hv,
            gmin,
            first,
            li,
            lf,
            sols,
            hk,
            hid,
            st,
            stf,
            edges,
            est,
            n_steps - (st[S_POPS] - pops0),
            max_labels,
            ties,
        )
        if status != NEED_ROOM:
            return li, lf, sols, hk, hid, edges, status
        if st[S_N] + 8 > li.shape[0]:
            li = _grow(li, st[S_N] + 8)
            lf = _grow(lf, st[S_N] + 8)
        if st[S_SIZE] + 8 > hk.shape[0]:
            hk = _grow(hk, st[S_SIZE] + 8)
        if st[S_SOLS] + 1 > sols.shape[0]:
            sols = _grow1(sols, st[S_SOLS] + 1)
        if est[E_EDGES] + 9 > edges.shape[0]:
            edges = _grow(edges, est[E_EDGES] + 9)


@numba.njit(cache=True, inline="always")
def _sift_up(hf, i, f_len, f_vul, k3):
    """Push keys ``(f_len, f_vul, k3)`` into the 4-ary heap ``hf`` (three floats
    an entry) whose first free slot is ``i``: sift the hole up, then write."""
    while i > 0:
        pa = (i - 1) >> 2
        b1, b2 = hf[3 * pa], hf[3 * pa + 1]
        if not (f_len < b1 or (f_len == b1 and (f_vul < b2 or (f_vul == b2 and k3 < hf[3 * pa + 2])))):
            break
        hf[3 * i] = b1
        hf[3 * i + 1] = b2
        hf[3 * i + 2] = hf[3 * pa + 2]
        i = pa
    hf[3 * i] = f_len
    hf[3 * i + 1] = f_vul
    hf[3 * i + 2] = k3


@numba.njit(cache=True, inline="always")
def _pour_drops(q, m, f_vul, goal_min, at_goal):
    """Whether a waiting label (g2 ``q`` at a cell whose ``g2_min`` is ``m``,
    f_vulnerability ``f_vul``) can be dropped when its bucket is poured, with
    the smoothest tie-break: its pop would drop it and record no tie edge,
    whatever happens before then.

    ``g2_min`` and the goal's least vulnerability only decrease, and
    vulnerabilities are sums of a non-negative potential, so a value beyond
    the tolerance above them now stays beyond it. A label so covered by its
    cell's ``g2_min`` is dropped at its pop with no edge (an edge needs a tie
    with ``g2_min``); so is a label at the goal so covered by the last
    solution. One elsewhere covered only by the last solution is kept: its
    pop tests ``g2_min`` first, which may by then tie it (an edge), unless it
    is clear of ``g2_min`` (not tied with it) and its f_vulnerability exceeds
    the last solution's by more than three tolerances (``GOAL_MARGIN``): then
    every label expanded at its cell before its pop has a g2 more than one
    tolerance below its own (such a label's f_vulnerability is at most one
    tolerance above the last solution's, even when kept as tied with it), so
    no ``g2_min`` it meets at its pop ties it (docs/results/exact_speed.md,
    fifteenth session)."""
    if at_goal:
        return f_vul > goal_min and not _eq(f_vul, goal_min)
    if q > m and not _eq(q, m):
        return True
    return (m == np.inf or not _eq(q, m)) and f_vul - goal_min > GOAL_MARGIN * max(1.0, f_vul)


@numba.njit(cache=True, inline="always")
def _pour_drops_tied(q, m, len_q, len_first):
    """Whether a waiting label (not at the goal) that ties its cell's
    ``g2_min`` ``m`` within the tolerance (g2 ``q``, length ``len_q``) can be
    dropped when its bucket is poured, with the smoothest tie-break: when
    ``q >= m`` and its length does not tie ``len_first``, that of the label
    last expanded at the cell (``first``). Its pop would drop it with no edge.

    Proof. Until its pop, the label stays covered, and it records an edge only
    if it ties, in g2 and in length, the label then last expanded at its
    cell. If none is expanded there before its pop, that is ``first``, whose
    length it does not tie. If one is, with g2 ``m'``, then ``m' < m`` and not
    ``_eq(m', m)`` (the expansion test), and then not ``_eq(q, m')`` for any
    ``q >= m`` (docs/results/exact_speed.md, fifteenth session: the
    tolerance is not transitive, but moving away from ``m'`` only widens the
    gap faster than the tolerance grows); the same holds for every later
    expansion there, each below the one before. So it records no edge at its
    pop. A label with ``q < m`` is kept: a later ``m'`` may tie it."""
    return q >= m and not _eq(len_q, len_first)


@numba.njit(cache=True, inline="always")
def _back_step_drops(ns_x, nd_x, s, t, cell_size, ties):
    """Whether the child of an expanded label ``x`` (step counts ``ns_x``,
    ``nd_x``, entered by a straight step if ``s == 1``, a diagonal one if
    ``t == 1``) that steps back to the cell of its parent ``p`` would be
    dropped by its eager check without an edge.

    Proof. The potential is non-negative and rounding is monotone, so the
    child's g2, ``fl(fl(q_p + P(x's cell)) + P(p's cell))``, is at least
    ``q_p``, and ``g2_min`` of ``p``'s cell is at most ``q_p`` (``p`` was
    expanded there): the child is covered. It records an edge only if it
    ties, in g2 and in length, the label ``a`` last expanded at that cell.
    If ``a`` is not ``p``, ``a`` was expanded after ``p`` with a g2 below
    ``q_p`` beyond the tolerance, and each later expansion there below the
    one before: then no value at or above ``q_p`` ties it (the step of rule 1,
    docs/results/exact_speed.md, fifteenth session). If ``a`` is ``p``, the
    lengths are those computed here, the child's (two steps more than
    ``p``'s) and ``p``'s, which do not tie unless the cell size is below
    the tolerance's scale. Without ties nothing is recorded."""
    if not ties:
        return True
    len_child = ((ns_x + s) + SQRT2 * (nd_x + t)) * cell_size
    len_p = ((ns_x - s) + SQRT2 * (nd_x - t)) * cell_size
    return not _eq(len_child, len_p)


@numba.njit(cache=True)
def _boa_steps(
    occ,
    pot,
    gr,
    gc,
    cell_size,
    mask,
    hs,
    hd,
    hv,
    gmin,
    first,
    li,
    lf,
    sols,
    hk,
    hid,
    st,
    stf,
    edges,
    est,
    n_steps,
    max_labels,
    ties,
):
    """The loop of :func:`_boa_run`, in arrays it never reallocates: returns
    NEED_ROOM before a pop when the label tables, the heap, the solution
    list or the edge table could overflow (a pop records at most 9 edges)."""
    h, w = occ.shape
    goal = gr * w + gc
    pf = pot.reshape(h * w)
    hf = hk.reshape(3 * hk.shape[0])  # the heap's keys, flat: entry i at 3 i
    off = np.empty(8, np.int64)  # move d from cell c: to c + off[d]
    for d in range(8):
        off[d] = DR[d] * w + DC[d]
    n = st[S_N]
    heads = hid  # the window's bucket lists (row or -1), bucket b at b % nb
    nb = hid.shape[0]  # a power of 2
    rq = BUCKETS_PER_CELL / cell_size
    cur = est[E_CUR]
    ohead = est[E_OHEAD]
    omin = est[E_OMIN]
    nwin = est[E_NWIN]
    nover = est[E_NOVER]
    size = st[S_SIZE] - nwin - nover  # the heap's own labels
    n_sols = st[S_SOLS]
    n_expanded = st[S_EXPANDED]
    n_generated = st[S_GENERATED]
    goal_first = st[S_GOAL_FIRST]  # the last solution found
    free = st[S_FREE]
    n_free = st[S_N_FREE]
    goal_min = stf[SF_GOAL_MIN]
    # length of the last solution: the strict goal test compares with it
    goal_len = np.inf
    if goal_first >= 0:
        goal_len = (li[goal_first, NS] + SQRT2 * li[goal_first, ND]) * cell_size
    ne = est[E_EDGES]
    status = DONE
    steps = 0
    pops0 = st[S_POPS]

    while size + nwin + nover > 0:
        if steps == n_steps:
            status = PAUSED
            break
        if n - n_free + 8 > max_labels:  # an expansion adds up to 8 labels
            status = OVER_BUDGET
            break
        if (
            n + 8 > li.shape[0]
            or size + nwin + nover + 8 > hk.shape[0]
            or n_sols + 1 > sols.shape[0]
            or ne + 9 > edges.shape[0]
        ):
            status = NEED_ROOM
            break
        if size == 0:  # the heap ran empty: pour the next nonempty bucket into it
            while size == 0 and nwin + nover > 0:  # (a pour may drop all its labels)
                if nwin == 0:
                    cur = omin - 1
                while True:
                    cur += 1
                    if nover > 0 and omin < cur + nb:  # the overflow's labels now in the window
                        y = ohead
                        ohead = -1
                        omin = _NO_BUCKET
                        while y >= 0:
                            nxt = li[y, NEXT]
                            cy = li[y, CELL]
                            f_len = ((li[y, NS] + hs[cy]) + SQRT2 * (li[y, ND] + hd[cy])) * cell_size
                            qz = np.int64(f_len * rq)
                            if qz < cur + nb:
                                b = qz & (nb - 1)
                                li[y, NEXT] = heads[b]
                                heads[b] = y
                                nwin += 1
                                nover -= 1
                            else:
                                li[y, NEXT] = ohead
                                ohead = y
                                omin = min(omin, qz)
                            y = nxt
                    if heads[cur & (nb - 1)] >= 0:
                        break
                b = cur & (nb - 1)
                y = heads[b]
                heads[b] = -1
                while y >= 0:
                    nxt = li[y, NEXT]
                    cy = li[y, CELL]  # the keys as at the push (the same sums)
                    qy = lf[y, F_VUL]
                    f_vul = qy + hv[cy]
                    # a label its pop would drop without an edge is dropped now (see
                    # _pour_drops): its row is free for the labels generated before then
                    if ties:
                        m = gmin[cy]
                        drop = _pour_drops(qy, m, f_vul, goal_min, cy == goal)
                        if not drop and cy != goal and qy >= m:  # tied with g2_min, from above
                            a = first[cy]
                            drop = _pour_drops_tied(
                                qy,
                                m,
                                (li[y, NS] + SQRT2 * li[y, ND]) * cell_size,
                                (li[a, NS] + SQRT2 * li[a, ND]) * cell_size,
                            )
                    else:
                        drop = False
                    if drop:
                        li[y, NEXT] = free
                        free = y
                        n_free += 1
                        nwin -= 1
                        y = nxt
                        continue
                    f_len = ((li[y, NS] + hs[cy]) + SQRT2 * (li[y, ND] + hd[cy])) * cell_size
                    k3 = np.float64(li[y, TURNS]) * ROW_SPAN + np.float64(y)
                    _sift_up(hf, size, f_len, f_vul, k3)
                    size += 1
                    nwin -= 1
                    y = nxt
            if size == 0:  # every waiting label was dropped: the search is done
                break
        steps += 1
        # pop the least key (the heap written out: helpers that take the arrays
        # cost reference counting); the keys are distinct (the row is in the
        # third), so any heap pops them in the same order
        x = np.int64(hf[3 * (0) + 2]) & ROW_MASK
        size -= 1
        if size > 0:
            # a 4-ary heap, bottom-up: the hole goes down along the least of the
            # children to a leaf (the children compared without branches), then
            # the last entry rises from there (rarely more than a level)
            k1, k2, k3 = hf[3 * size], hf[3 * size + 1], hf[3 * size + 2]
            i = 0
            ch = 1
            while ch + 3 < size:
                a1, a2, a3 = hf[3 * ch], hf[3 * ch + 1], hf[3 * ch + 2]
                b1, b2, b3 = hf[3 * (ch + 1)], hf[3 * (ch + 1) + 1], hf[3 * (ch + 1) + 2]
                c1, c2, c3 = hf[3 * (ch + 2)], hf[3 * (ch + 2) + 1], hf[3 * (ch + 2) + 2]
                d1, d2, d3 = hf[3 * (ch + 3)], hf[3 * (ch + 3) + 1], hf[3 * (ch + 3) + 2]
                lt = (b1 < a1) | ((b1 == a1) & ((b2 < a2) | ((b2 == a2) & (b3 < a3))))
                ia = ch + lt
                if lt:
                    a1, a2, a3 = b1, b2, b3
                lt = (d1 < c1) | ((d1 == c1) & ((d2 < c2) | ((d2 == c2) & (d3 < c3))))
                ic = ch + 2 + lt
                if lt:
                    c1, c2, c3 = d1, d2, d3
                lt = (c1 < a1) | ((c1 == a1) & ((c2 < a2) | ((c2 == a2) & (c3 < a3))))
                if lt:
                    a1, a2, a3 = c1, c2, c3
                    ia = ic
                hf[3 * i] = a1
                hf[3 * i + 1] = a2
                hf[3 * i + 2] = a3
                i = ia
                ch = 4 * i + 1
            if ch < size:  # 1 to 3 children left
                a1, a2, a3 = hf[3 * ch], hf[3 * ch + 1], hf[3 * ch + 2]
                ia = ch
                for cc in range(ch + 1, size):
                    b1, b2, b3 = hf[3 * cc], hf[3 * cc + 1], hf[3 * cc + 2]
                    if b1 < a1 or (b1 == a1 and (b2 < a2 or (b2 == a2 and b3 < a3))):
                        a1, a2, a3 = b1, b2, b3
                        ia = cc
                hf[3 * i] = a1
                hf[3 * i + 1] = a2
                hf[3 * i + 2] = a3
                i = ia
            _sift_up(hf, i, k1, k2, k3)
        c = li[x, CELL]
        q = lf[x, F_VUL]

        # lazy checks: g2_min of the cell, then the last solution
        covered = False
        tie = -1  # the label x ties: x's in-edge becomes one of its in-edges
        if c != goal:
            m = gmin[c]
            if m < np.inf and not (q < m and not _eq(q, m)):
                covered = True
                if ties and _eq(q, m):
                    a = first[c]
                    if _eq(
                        (li[x, NS] + SQRT2 * li[x, ND]) * cell_size,
                        (li[a, NS] + SQRT2 * li[a, ND]) * cell_size,
                    ):
                        tie = a
        if not covered and goal_min < np.inf:
            fq = q + hv[c]
            if not (fq < goal_min and not _eq(fq, goal_min)):
                covered = True
                if ties and _eq(fq, goal_min):
                    fl = ((li[x, NS] + hs[c]) + SQRT2 * (li[x, ND] + hd[c])) * cell_size
                    if _eq(fl, goal_len):  # ties the last solution: keep, or attach at the goal
                        if c == goal:
                            tie = goal_first
                        else:
                            covered = False
        if covered:
            if tie >= 0:
                edges[ne, E_NODE] = tie
                edges[ne, E_PARENT] = li[x, F_PARENT]
                edges[ne, E_DIR] = li[x, F_HEAD]
                ne += 1
            li[x, NEXT] = free  # recycle the row: nothing refers to x
            free = x
            n_free += 1
            continue

        # a solution: record it, never expand it
        if c == goal:
            goal_min = q
            goal_len = (li[x, NS] + SQRT2 * li[x, ND]) * cell_size
            li[x, NEXT] = goal_first
            goal_first = x
            sols[n_sols] = x
            n_sols += 1
            continue

        # expand x (q < g2_min of the cell beyond the tolerance)
        n_expanded += 1
        gmin[c] = q
        first[c] = x
        head = li[x, F_HEAD]
        ns_x, nd_x, turns_x = li[x, NS], li[x, ND], li[x, TURNS]
        mk = np.int64(mask[c])
        n_generated += COUNT[mk]
        if head >= 0:
            # the step back to the parent's cell is not generated: its eager check
            # would drop it with no edge (see _back_step_drops)
            s_x = 1 - head % 2
            if _back_step_drops(ns_x, nd_x, s_x, 1 - s_x, cell_size, ties):
                mk &= ~(1 << ((head + 4) & 7))
        for jm in range(COUNT[mk]):  # the allowed moves (a test per bit mispredicts)
            d = MOVES[mk, jm]
            cell = c + off[d]  # (the goal can be reached from there: _boa_prepare's mask)
            ns_j = ns_x + (1 - d % 2)
            nd_j = nd_x + d % 2
            qj = q + pf[cell]
            # eager checks (BOA*: prune before the open list), on the values alone
            if cell != goal:
                m = gmin[cell]
                if m < np.inf and not (qj < m and not _eq(qj, m)):
                    if ties and _eq(qj, m):
                        a = first[cell]
                        if _eq(
                            (ns_j + SQRT2 * nd_j) * cell_size,
                            (li[a, NS] + SQRT2 * li[a, ND]) * cell_size,
                        ):
                            edges[ne, E_NODE] = a
                            edges[ne, E_PARENT] = x
                            edges[ne, E_DIR] = d
                            ne += 1
                    continue
            f_vul = qj + hv[cell]
            f_len = ((ns_j + hs[cell]) + SQRT2 * (nd_j + hd[cell])) * cell_size
            if goal_min < np.inf and not (f_vul < goal_min and not _eq(f_vul, goal_min)):
                if not (ties and _eq(f_vul, goal_min) and _eq(f_len, goal_len)):
                    continue
                if cell == goal:  # ties the last solution
                    edges[ne, E_NODE] = goal_first
                    edges[ne, E_PARENT] = x
                    edges[ne, E_DIR] = d
                    ne += 1
                    continue
            # a new label: a recycled row (its NEXT links the free list) or a new one
            if free >= 0:
                j = free
                free = li[j, NEXT]
                n_free -= 1
            else:
                j = n
                n += 1
            turns_j = turns_x + (turn(head, d) if head >= 0 else 0)
            li[j, CELL] = cell
            li[j, F_HEAD] = d
            li[j, F_PARENT] = x
            li[j, NS] = ns_j
            li[j, ND] = nd_j
            li[j, TURNS] = turns_j  # (NEXT is read only on free rows and solutions)
            lf[j, F_VUL] = qj
            qz = np.int64(f_len * rq)
            if qz > cur:  # a later bucket: wait in its list
                if qz < cur + nb:
                    b = qz & (nb - 1)
                    li[j, NEXT] = heads[b]
                    heads[b] = j
                    nwin += 1
                else:
                    li[j, NEXT] = ohead
                    ohead = j
                    omin = min(omin, qz)
                    nover += 1
                continue
            # push (sift the hole up); third key: turns, then the row (exact below 2**53)
            k3 = np.float64(turns_j) * ROW_SPAN + np.float64(j)
            _sift_up(hf, size, f_len, f_vul, k3)
            size += 1
    st[S_N] = n
    st[S_SIZE] = size + nwin + nover
    est[E_CUR] = cur
    est[E_OHEAD] = ohead
    est[E_OMIN] = omin
    est[E_NWIN] = nwin
    est[E_NOVER] = nover
    st[S_SOLS] = n_sols
    st[S_EXPANDED] = n_expanded
    st[S_GENERATED] = n_generated
    st[S_GOAL_FIRST] = goal_first
    st[S_FREE] = free
    st[S_N_FREE] = n_free
    st[S_POPS] = pops0 + steps
    stf[SF_GOAL_MIN] = goal_min
    est[E_EDGES] = ne
    return status


@numba.njit(cache=True)
def _smoothest(li, lf, n_rows, sols, edges, n_edges, pot, w, reuse):
    """The smoothest path of each solution over the DAG of expanded labels.

    Nodes are the label rows reachable backward from ``sols``; the in-edges
    of a node are ``(parent, heading)`` of its own row and the rows of
    ``edges[:n_edges]`` that enter it. ``(T, V)[v, d]`` is the
    lexicographically least (total turn in eighths, vulnerability) of a path
    of the DAG that ends at ``v`` with heading ``d``: over the in-edges
    ``(p, d)`` of ``v`` and the headings ``h`` of ``p``, ``(T[p, h] +
    turn(h, d), V[p, h] + P(v))``; ``(0, P(start))`` at the start label (it
    has no heading). ``V`` is summed in path order, so it is the value the
    path's own evaluation gives; among equally smooth tied paths the least
    vulnerable one is taken. Nodes are taken in the post-order of a
    depth-first search from the solutions, so parents come before children.
    The trace prefers, at each node, its own in-edge, then the recorded
    ones in the order they were recorded, and the lowest heading: the first
    (in-edge, heading) that gives the node's value, which the programme
    keeps (``bp``, ``bs``: the parent and its slot) as it finds it. Only
    the headings a node is entered with have a slot (``hoff``, ``hm``): one
    for most nodes, where an 8-heading table per node took 8 times the
    memory and most of the programme's time in page faults and cache misses.

    The label tables are dead by then and their first ``n_rows`` rows are
    already in memory (written by the search), so the arrays indexed by row
    (``off``, ``idx``) are carved out of the float table ``lf``, each row's
    parent, cell and heading are copied, in one pass in row order, into
    ``li``'s first rows (the depth-first search then reads them from there
    instead of rows scattered over the table, a cache miss each), and the
    programme's arrays (``T``, ``V``, ``bp``, ``bs``) are carved out of ``li``
    after them, when they fit, if ``reuse`` is true: no fresh pages for them.
    Both tables are then overwritten (the search cannot go on); the values are
    the same either way.

    Returns ``(cells, offsets, n_straight, n_diag, turns, vul, scratch_bytes)``:
    the cells of solution ``i``'s path are ``cells[offsets[i]:offsets[i + 1]]``
    (``(row, col)``), its step counts, total turn and vulnerability summed
    along it in path order from the start cell; ``scratch_bytes``, the memory
    of the programme's fresh arrays.
    """
    # alternative in-edges by node (counting sort); off and idx in lf's rows
    scratch = 0
    fb = lf.reshape(lf.size).view(np.int32)  # two int32 a row
    if reuse and 2 * n_rows + 1 <= fb.shape[0]:  # (row n_rows's first half: one page at most)
        off = fb[: n_rows + 1]
        idx = fb[n_rows + 1 : 2 * n_rows + 1]
    else:
        off = np.empty(n_rows + 1, np.int32)
        idx = np.empty(n_rows, np.int32)
        scratch += off.nbytes + idx.nbytes
    off[:] = 0
    for e in range(n_edges):
        off[edges[e, E_NODE] + 1] += 1
    for v in range(n_rows):
        off[v + 1] += off[v]
    ep = np.empty(n_edges, np.int32)
    edir = np.empty(n_edges, np.int8)
    for e in range(n_edges):  # off[v] is v's fill pointer, then its end
        v = edges[e, E_NODE]
        k = off[v]
        ep[k] = edges[e, E_PARENT]
        edir[k] = edges[e, E_DIR]
        off[v] = k + 1
    for v in range(n_rows, 0, -1):  # back to the starts
        off[v] = off[v - 1]
    off[0] = 0

    # post-order of the nodes reachable from the solutions; idx: -1 unseen (set
    # in the copy pass below), -2 open, else the node's place in the order. A
    # node is finished after its parents, so when it is, its in-edges are
    # written out in that order's numbers (kin_p, kin_d: its own first, then
    # the recorded ones in the order they were recorded; none for the start
    # label) with its cell and its slots (below): the programme then reads
    # these compact arrays in order instead of label rows scattered over the
    # table
    # each row's parent, cell and heading, compact, in one pass in row order:
    # the search's reads of label rows scattered over the table were a cache
    # miss each. Written over li's first rows, already read (row v's three
    # entries below row v), when reuse
    n_sols = len(sols)
    total = 0  # (the labels' step counts are read before)
    for si in range(n_sols):
        total += li[sols[si], NS] + li[sols[si], ND] + 1
    fb = li.reshape(li.size)
    if reuse:
        pch = fb[: 3 * n_rows]
    else:
        pch = np.empty(3 * n_rows, np.int32)
        scratch += pch.nbytes
    for v in range(n_rows):
        p = li[v, F_PARENT]
        cv = li[v, CELL]
        hd_v = li[v, F_HEAD]
        pch[3 * v] = p
        pch[3 * v + 1] = cv
        pch[3 * v + 2] = hd_v
        idx[v] = -1
    ncell = np.empty(n_rows, np.int32)
    kin_off = np.empty(n_rows + 1, np.int32)
    kin_p = np.empty(n_rows + n_edges, np.int32)
    kin_d = np.empty(n_rows + n_edges, np.int8)
    stack = np.empty(n_rows + n_edges + len(sols) + 1, np.int32)
    # one slot per (node, incoming heading) that occurs (most nodes have one):
    # the slots of node i are hoff[i]:hoff[i + 1], in heading order (hm: the
    # headings; 0 for the start label, which has one slot and no heading)
    hm = np.empty(n_rows, np.uint8)  # (written in order, as hoff)
    hoff = np.empty(n_rows + 1, np.int64)
    hoff[0] = 0
    kin_off[0] = 0
    k = 0
    for s in sols:
        if idx[s] != -1:
            continue
        sp = 0
        stack[sp] = s
        sp += 1
        while sp > 0:
            v = stack[sp - 1]
            if idx[v] >= 0:
                sp -= 1
            elif idx[v] == -1:
                idx[v] = -2
                p = pch[3 * v]
                if p >= 0 and idx[p] == -1:
                    stack[sp] = p
                    sp += 1
                for e in range(off[v], off[v + 1]):
                    p = ep[e]
                    if idx[p] == -1:
                        stack[sp] = p
                        sp += 1
            else:
                idx[v] = k
                ncell[k] = pch[3 * v + 1]
                t = kin_off[k]
                bits = 0
                p = pch[3 * v]
                if p >= 0:
                    d = pch[3 * v + 2]
                    kin_p[t] = idx[p]
                    kin_d[t] = d
                    t += 1
                    bits = 1 << d
                    for e in range(off[v], off[v + 1]):
                        kin_p[t] = idx[ep[e]]
                        kin_d[t] = edir[e]
                        t += 1
                        bits |= 1 << edir[e]
                kin_off[k + 1] = t
                hm[k] = bits
                hoff[k + 1] = hoff[k] + (_POPCOUNT[bits] if bits else 1)
                k += 1
                sp -= 1
    n_slots = hoff[k]
    # least (turns, vulnerability) per slot, and the first (in-edge, parent
    # slot) giving it: the trace's choice, kept; in li's rows after pch when
    # they fit (6 int32 a slot, 7 a row)
    o = 3 * n_rows + (n_rows & 1)  # (even: T and V 8-byte aligned)
    if reuse and o + 6 * n_slots <= 7 * n_rows:
        T = fb[o : o + 2 * n_slots].view(np.int64)
        V = fb[o + 2 * n_slots : o + 4 * n_slots].view(np.float64)
        bp = fb[o + 4 * n_slots : o + 5 * n_slots]  # the parent's place in the order
        bs = fb[o + 5 * n_slots : o + 6 * n_slots]
    else:
        T = np.empty(n_slots, np.int64)
        V = np.empty(n_slots)
        bp = np.empty(n_slots, np.int32)
        bs = np.empty(n_slots, np.int32)
        scratch += T.nbytes + V.nbytes + bp.nbytes + bs.nbytes
    pf = pot.reshape(pot.size)
    for i in range(k):
        pv = pf[ncell[i]]
        s0 = hoff[i]
        bits_v = np.int64(hm[i])
        if bits_v == 0:  # the start label: no heading, no turn to come
            T[s0] = 0
            V[s0] = pv
            bp[s0] = -1
            continue
        for j in range(s0, hoff[i + 1]):
            T[j] = _BIG
            V[j] = np.inf
        for e in range(kin_off[i], kin_off[i + 1]):
            ip = kin_p[e]
            d = np.int64(kin_d[e])
            sd = s0 + _POPCOUNT[bits_v & ((1 << d) - 1)]
            bt, bv = T[sd], V[sd]
            b_p, b_s = bp[sd], bs[sd]
            bits = np.int64(hm[ip])
            sp_ = hoff[ip]
            if bits == 0:  # the parent is the start label
                t = T[sp_]
                if t < bt or (t == bt and V[sp_] + pv < bv):
                    bt, bv = t, V[sp_] + pv
                    b_p, b_s = ip, sp_
            else:
                while bits:
                    hh = _LOWBIT[bits & -bits]
                    bits &= bits - 1
                    t = T[sp_] + turn(hh, d)
                    if t < bt or (t == bt and V[sp_] + pv < bv):
                        bt, bv = t, V[sp_] + pv
                        b_p, b_s = ip, sp_
                    sp_ += 1
            T[sd] = bt
            V[sd] = bv
            bp[sd] = b_p
            bs[sd] = b_s

    # trace each solution back from its least (T, V) (the steps written out: a
    # helper call per step cost most of the time), then evaluate it forwards
    offsets = np.zeros(n_sols + 1, np.int64)
    out_ns = np.zeros(n_sols, np.int64)
    out_nd = np.zeros(n_sols, np.int64)
    out_turns = np.zeros(n_sols, np.int64)
    out_vul = np.zeros(n_sols)
    buf = np.empty(k, np.int32)  # the nodes of one path, goal first (distinct nodes)
    dtab = np.zeros(2 * w + 3, np.int64)  # heading of a step by its cell difference + w + 1
    for d in range(8):
        dtab[DR[d] * w + DC[d] + w + 1] = d
    cells = np.empty((total, 2), np.int64)
    for si in range(n_sols):
        i = idx[sols[si]]
        j = hoff[i]  # the least (T, V), the lowest heading first
        for jj in range(hoff[i] + 1, hoff[i + 1]):
            if T[jj] < T[j] or (T[jj] == T[j] and V[jj] < V[j]):
                j = jj
        m = 0
        while True:
            buf[m] = i
            m += 1
            if hm[i] == 0:  # the start label
                break
            # the first in-edge of i (its own first) and slot of its parent giving T, V
            i, j = bp[j], bs[j]
        a = offsets[si]
        b = a + m
        offsets[si + 1] = b
        if b > cells.shape[0]:  # not reached when tied paths have equal step counts
            grown = np.empty((max(b, 2 * cells.shape[0]), 2), np.int64)
            grown[:a] = cells[:a]
            cells = grown
        # the cells and the objectives along the path, in path order (as
        # gapath.objectives does); a step's heading from the difference of the
        # cell numbers (dtab), the row and column by steps from the first cell's
        c = np.int64(ncell[buf[m - 1]])
        r0 = c // w
        c0 = c - r0 * w
        cells[a, 0] = r0
        cells[a, 1] = c0
        vul = pf[c]
        ns = 0
        nd = 0
        eighths = 0
        prev = -1
        for t in range(1, m):
            cn = np.int64(ncell[buf[m - 1 - t]])
            if w >= 3:
                d = dtab[cn - c + w + 1]
                r0 += DR[d]
                c0 += DC[d]
            else:  # (the differences are not distinct)
                r1 = cn // w
                c1 = cn - r1 * w
                d = DIRECTION[r1 - r0 + 1, c1 - c0 + 1]
                r0, c0 = r1, c1
            cells[a + t, 0] = r0
            cells[a + t, 1] = c0
            vul += pf[cn]
            if d % 2 == 1:
                nd += 1
            else:
                ns += 1
            if prev >= 0:
                eighths += turn(prev, d)
            prev = d
            c = cn
        out_ns[si] = ns
        out_nd[si] = nd
        out_turns[si] = eighths
        out_vul[si] = vul
    cells = cells[: offsets[n_sols]]
    for arr_bytes in (ep.nbytes, edir.nbytes, ncell.nbytes, kin_off.nbytes, stack.nbytes):
        scratch += arr_bytes
    scratch += kin_p.nbytes + kin_d.nbytes + hm.nbytes + hoff.nbytes + buf.nbytes + cells.nbytes
    return cells, offsets, out_ns, out_nd, out_turns, out_vul, scratch


# -- one call for a whole small search (the fixed cost of a call) ----------------
#
# On a 32x32 map the whole search takes about as long as the Python around it
# took (numba dispatch, boxing of every returned array, the result's sorts and
# fancy indexing). _boa_prepare (masks and heuristics, timed apart by the
# caller) and _boa_solve (initial state, the first slice of the search and, if
# that finishes it, the front's arrays) are the two calls of a small search;
# a longer one continues from the state _boa_solve returns with _boa_run and
# ends with _boa_finish.

#: Entries of the counts array of :func:`_boa_finish`.
C_EXPANDED, C_GENERATED, C_ROWS, C_FREE, C_SOLS, C_EDGES, C_PEAK = range(7)


@numba.njit(cache=True, nogil=True)
def _boa_prepare(occ, pot, gr, gc, corner_cutting):
    """The move masks and the length and vulnerability heuristics of a
    two-objective search: ``(mask, hs, hd, hv)`` as
    :func:`gapath.planners._exact_heuristics._free_heuristics` (without the
    turn heuristic), except that ``mask`` has no move into a cell from which
    the goal cannot be reached (``hv == inf``; BOA* never generates a label
    there)."""
    h, w = occ.shape
    n = h * w
    goal = gr * w + gc
    mask = _move_masks(occ, corner_cutting)
    hs = np.full(n, -1, np.int64)
    hd = np.full(n, -1, np.int64)
    _length_to_go(mask, w, goal, hs, hd)
    hv = np.full(n, np.inf)
    _vulnerability_to_go(mask, pot, w, goal, hv)
    # no move into a cell the goal cannot be reached from (the search's own test
    # before). The moves are symmetric, so the cells a cell can move to can reach
    # the goal iff it can: the moves to clear are all those of the cells with
    # hv == inf, and no other
    for c in range(n):
        if hv[c] == np.inf:
            mask[c] = 0
    return mask, hs, hd, hv


@numba.njit(cache=True)
def _boa_bytes(hs, hd, hv, gmin, first, li, lf, sols, hk, hid, edges):
    """Bytes of a search's arrays (``stats["peak_bytes"]``; the 1-entry turn
    placeholder included, as for the other searches)."""
    fixed = hs.nbytes + hd.nbytes + hv.nbytes + 8 + gmin.nbytes + first.nbytes
    return fixed + li.nbytes + lf.nbytes + hk.nbytes + hid.nbytes + sols.nbytes + edges.nbytes


@numba.njit(cache=True)
def _boa_start(pot, sr, sc, w, cell_size, hs, hd, hv, ties, n_buckets):
    """The state of a new search (the start label alone on the open list):
    ``(gmin, first, li, lf, sols, hk, hid, st, stf, edges, est)``, with a
    window of ``n_buckets`` buckets (a power of 2; the tests use small ones)."""
    ht = np.zeros(1, np.int64)
    # int64s, not literals: the same specialization as _free_prepare's call
    mode, p, q = np.int64(MODE_CELL), np.int64(OBJ_LEN), np.int64(OBJ_VUL)
    gmin, first, li, lf, sols, hk, hid, st, stf = _free_init(
        pot, sr, sc, w, cell_size, mode, p, q, hs, hd, hv, ht, hs.shape[0]
    )
    hid = np.full(n_buckets, -1, np.int32)  # the buckets' heads
    # room for 4 labels a cell up to 2**18 rows (9.4 MB): doubling from 1,024 rows
    # cost a Berlin_1_256 search 3-8 ms of copies and page faults (the pages
    # are touched only as rows are used)
    rows = min(4 * hs.shape[0], LABEL_ROWS)
    if rows > li.shape[0]:
        li2 = np.empty((rows, li.shape[1]), li.dtype)
        lf2 = np.empty((rows, lf.shape[1]), lf.dtype)
        li2[: st[S_N]] = li[: st[S_N]]  # the start label
        lf2[: st[S_N]] = lf[: st[S_N]]
        li, lf = li2, lf2
    # the edge table: two rows a cell, at most LABEL_ROWS (about one tie edge per
    # two expansions on Berlin_1_256: doubling from 1,024 rows copied 1.5 MB and
    # touched twice the pages used; the rows are touched only as edges are
    # recorded)
    edges = np.empty((max(1024, min(2 * hs.shape[0], LABEL_ROWS)) if ties else 16, 3), np.int32)
    est = np.zeros(6, np.int64)
    est[E_CUR] = np.int64(hk[0, 0] * (BUCKETS_PER_CELL / cell_size))  # the start label's bucket
    est[E_OHEAD] = -1
    est[E_OMIN] = _NO_BUCKET
    return gmin, first, li, lf, sols, hk, hid, st, stf, edges, est


@numba.njit(cache=True, nogil=True)
def _boa_solve(occ, pot, sr, sc, gr, gc, cell_size, mask, hs, hd, hv, ties, len_first, n_steps, max_labels):
    """Start BOA* (:func:`_boa_run`) and run at most ``n_steps`` pops.

    Returns ``(status, result, state)``: when the search is done, ``result``
    is what :func:`_boa_finish` returns and ``state`` is None; otherwise
    (PAUSED or OVER_BUDGET) ``result`` is None and ``state`` is ``(gmin,
    first, li, lf, sols, hk, hid, st, stf, edges, est)``, from which
    :func:`_boa_run` continues. (A None is returned at no cost; every array
    costs Python a fraction of a microsecond.)"""
    w = occ.shape[1]
    gmin, first, li, lf, sols, hk, hid, st, stf, edges, est = _boa_start(
        pot, sr, sc, w, cell_size, hs, hd, hv, ties, np.int64(N_BUCKETS)
    )  # int64, not a literal: one specialization with the tests' calls
    li, lf, sols, hk, hid, edges, status = _boa_run(
        occ, pot, gr, gc, cell_size, mask, hs, hd, hv, gmin, first, li, lf, sols, hk, hid, st, stf,
        edges, est, n_steps, max_labels, ties,
    )  # fmt: skip
    if status != DONE:
        return status, None, (gmin, first, li, lf, sols, hk, hid, st, stf, edges, est)
    peak = _boa_bytes(hs, hd, hv, gmin, first, li, lf, sols, hk, hid, edges)
    result = _boa_finish(li, lf, sols, st, edges, est[E_EDGES], pot, w, cell_size, ties, len_first, peak)
    return status, result, None


@numba.njit(cache=True, nogil=True)
def _boa_finish(li, lf, sols, st, edges, n_edges, pot, w, cell_size, ties, len_first, peak):
    """The front of a finished search: its paths, the tolerance filter and
    the final order, as arrays.

    With ``ties`` and recorded edges, the smoothest path of each solution
    (:func:`_smoothest`); otherwise each solution's own path (without tie
    edges the DAG of :func:`_smoothest` is the labels' tree: the same path
    and, summed in the same order, the same objectives). Among
    tolerance-equal vectors the front keeps the smoothest path, then the
    shortest (``_tolerant_front`` in the order of ``np.lexsort((length,
    turns))``), and sorts the points lexicographically (``len_first``: length
    is the first column of ``F``, else vulnerability).

    Returns ``(F, smoothness, cells, offsets, counts)``: ``F`` (k, 2), the
    path of point ``i`` is ``cells[offsets[i]:offsets[i + 1]]``, ``counts``
    the int64 figures indexed by ``C_*`` (``C_PEAK``: ``peak`` plus the
    dynamic programme's fresh scratch memory). With ``ties`` the label tables
    ``li`` and ``lf`` are overwritten (:func:`_smoothest` works in them): the
    search cannot be continued after its finish.
    """
    n_sols = st[S_SOLS]
    sols = sols[:n_sols]
    if ties and n_edges > 0:
        cells, offsets, ns, nd, turns, vul, scratch = _smoothest(
            li, lf, st[S_N], sols, edges, n_edges, pot, w, True
        )
        peak += scratch
    else:
        cells, offsets = _trace(li, sols, w)
        ns = np.empty(n_sols, np.int64)
        nd = np.empty(n_sols, np.int64)
        turns = np.empty(n_sols, np.int64)
        vul = np.empty(n_sols)
        for i in range(n_sols):
            x = sols[i]
            ns[i] = li[x, NS]
            nd[i] = li[x, ND]
            turns[i] = li[x, TURNS]
            vul[i] = lf[x, F_VUL]
    steps = np.empty(n_sols)
    F = np.empty((n_sols, 2))
    for i in range(n_sols):
        steps[i] = ns[i] + SQRT2 * nd[i]
        length = steps[i] * cell_size
        F[i, 0] = length if len_first else vul[i]
        F[i, 1] = vul[i] if len_first else length
    # np.lexsort((steps, turns)) by two stable sorts: the smoothest, then the shortest first
    p = np.argsort(steps, kind="mergesort")
    order = p[np.argsort(turns[p], kind="mergesort")]
    keep = _tolerant_front(F, order)
    # lexicographic order of F (np.lexsort(F[keep].T[::-1]))
    p = np.argsort(F[keep, 1], kind="mergesort")
    keep = keep[p[np.argsort(F[keep[p], 0], kind="mergesort")]]
    k = len(keep)
    out_f = np.empty((k, 2))
    smooth = np.empty(k)
    out_off = np.zeros(k + 1, np.int64)
    for t in range(k):
        i = keep[t]
        out_f[t, 0] = F[i, 0]
        out_f[t, 1] = F[i, 1]
        smooth[t] = turns[i] * QUARTER_PI
        out_off[t + 1] = out_off[t] + offsets[i + 1] - offsets[i]
    out_cells = np.empty((out_off[k], 2), np.int64)
    for t in range(k):
        i = keep[t]
        a = out_off[t]
        for j in range(offsets[i], offsets[i + 1]):
            out_cells[a, 0] = cells[j, 0]
            out_cells[a, 1] = cells[j, 1]
            a += 1
    counts = np.zeros(7, np.int64)
    counts[C_EXPANDED] = st[S_EXPANDED]
    counts[C_GENERATED] = st[S_GENERATED]
    counts[C_ROWS] = st[S_N]
    counts[C_FREE] = st[S_N_FREE]
    counts[C_SOLS] = n_sols
    counts[C_EDGES] = n_edges
    counts[C_PEAK] = peak
    return out_f, smooth, out_cells, out_off, counts
