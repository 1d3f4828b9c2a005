"""Numba kernel of the approximate three-objective search (private).

:func:`gapath.planners.exact.free_front` with ``epsilon > 0`` on the
objectives length, vulnerability and smoothness runs :func:`_apex_run`, an
apex-path search in the manner of A*pex (Zhang et al. 2022) over the states
and staircases of the exact search (NAMOA*-dr on (cell, heading) states,
:func:`gapath.planners._exact_kernels._free_run`, MODE_THREE):

* every open label carries, beside its path's values, an *apex*: lower
  bounds on the length and the vulnerability of the labels it stands for
  (columns ``F_APEX_LEN``, in steps, and ``F_APEX`` of the float table; its
  turns are the path's own). The open list is ordered by the apex's
  f-values;
* a label generated at a cell is *merged* with an open label of the same
  cell (the last one pushed at each heading) when one of the two turns at
  most as much (headings charged as in the exact search) and has at most
  ``1 + eps`` times the smaller of the two apexes' length and vulnerability:
  that one stays open with the smaller apex (in a new row when its apex got
  shorter: its key changes), the other is dropped;
* the dominance checks of the exact search (expanded labels of the cell, the
  solutions found) compare apexes: an expanded label's staircase entry and a
  solution's goal entry hold its apex.

So every label's path is within ``1 + eps`` of its apex, a label is dropped
only when a label whose apex is as good covers it, and the factor never
adds up along a path: every point of the exact front is covered by a
returned path with at most ``1 + eps`` times its length and its
vulnerability and no more turns (the test suite checks this against the
exact front).

The state arrays are those of :func:`_free_init` (the float table widened to
three columns at the first call), with ``open_at`` (the last open label of
each state, -1 none) beside them.
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.grid import DC, DR, SQRT2, TRUE, turn
from gapath.planners._exact_kernels import (
    CELL,
    DONE,
    F_HEAD,
    F_PARENT,
    F_VUL,
    N_SLOTS,
    ND,
    NEED_ROOM,
    NEXT,
    NS,
    OVER_BUDGET,
    PAUSED,
    S_EXPANDED,
    S_FREE,
    S_GENERATED,
    S_N,
    S_N_FREE,
    S_POPS,
    S_SIZE,
    S_SOLS,
    SP_USED,
    THREE_BLOCK,
    TURNS,
    _goal_record,
    _heap4_pop,
    _heap4_push,
    _heap_rows,
    _le,
    _make_room,
    _slot,
    _stair_covered,
    _stair_room,
    _three_insert,
)

#: Columns of a label's apex in the float table (F_VUL: its path's
#: vulnerability): its vulnerability and its length in steps.
F_APEX, F_APEX_LEN = 1, 2
#: ``NEXT`` of an open label merged into another one: dropped when popped.
MERGED = -2


@numba.njit(cache=True, _nrt=False)
def _covered(gmin, sp, first, c, goal, goal_base, goal_state, t, a, hx, tgoal, ahv):
    """True if an expanded label of cell ``c`` (its staircases of (turns,
    apex)) or a solution (the goal front of apexes) covers a label with
    ``t`` turns, heading ``hx`` (-1: the start) and apex ``a``; ``tgoal`` and
    ``ahv`` are its turn and vulnerability lower bounds at the goal.

    Compiled without numba's reference counting (``_nrt=False``: it
    allocates nothing). Inlined into the loop, or called as an ordinary
    function, its three arrays were counted in and out at every call: six
    atomic operations per generated label, 16 % of the search's samples on
    gen256-s1 (fifteenth session, ``docs/results/free_paths.md``)."""
    base = c * THREE_BLOCK
    if c != goal and gmin[base] < np.inf and _le(gmin[base], a):
        for k in range(N_SLOTS):
            b = base + 1 + 3 * k
            if gmin[b] == np.inf or not _le(gmin[b], a):
                continue
            bound = t - (0 if k == 8 else (4 if hx < 0 else turn(k, hx)))  # _heading_gap
            if gmin[b + 2] > bound:
                continue
            if gmin[b + 1] <= bound:
                return True
            if _stair_covered(sp, first[c * N_SLOTS + k], bound, a):
                return True
    tmax = first[goal_state]
    if tmax >= 0:
        m = gmin[goal_base + min(tgoal, tmax)]
        if m < np.inf and _le(m, ahv):
            return True
    return False


@numba.njit(cache=True, _nrt=False)
def _pop(hk, size):
    """:func:`_heap4_pop` as a call without reference counting (see
    :func:`_covered`)."""
    return _heap4_pop(hk, size)


@numba.njit(cache=True, nogil=True)
def _apex_run(
    occ,
    pot,
    gr,
    gc,
    cell_size,
    mask,
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
    open_at,
    n_steps,
    max_labels,
    eps,
):
    """Advance the apex search by at most ``n_steps`` pops; the arguments and
    the result ``(li, lf, sols, hk, hid, sp, status)`` are those of
    :func:`gapath.planners._exact_kernels._free_run` in MODE_THREE, with
    ``open_at`` (``n_states`` int32, -1) and ``eps`` > 0. A new search's
    tables (one float column, a 3-column heap) are widened at the first
    call."""
    pops0 = st[S_POPS]
    if hk.shape[1] == 3:  # a new search: labels into the heap rows, apexes beside the values
        hk = _heap_rows(hk, hid, st[S_SIZE])
    if lf.shape[1] == 1:
        lf2 = np.empty((lf.shape[0], 3))
        for i in range(st[S_N]):
            lf2[i, F_VUL] = lf[i, F_VUL]
            lf2[i, F_APEX] = lf[i, F_VUL]
            lf2[i, F_APEX_LEN] = li[i, NS] + SQRT2 * li[i, ND]
        lf = lf2
    while True:
        status = _apex_steps(
            occ,
            pot,
            gr,
            gc,
            cell_size,
            mask,
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
            st,
            sp,
            open_at,
            n_steps - (st[S_POPS] - pops0),
            max_labels,
            eps,
        )
        if status != NEED_ROOM:
            return li, lf, sols, hk, hid, sp, status
        li, lf, sols, hk, hid, sp = _make_room(li, lf, sols, hk, hid, sp, st, TRUE)


@numba.njit(cache=True, _nrt=False)
def _apex_steps(
    occ,
    pot,
    gr,
    gc,
    cell_size,
    mask,
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
    st,
    sp,
    open_at,
    n_steps,
    max_labels,
    eps,
):
    """The loop of :func:`_apex_run`, in arrays it never reallocates."""
    h, w = occ.shape
    goal = gr * w + gc
    goal_state = first.shape[0] - 1
    goal_base = THREE_BLOCK * h * w
    has_ht = ht.shape[0] > 1
    slack = 1.0 + eps
    n = st[S_N]
    size = st[S_SIZE]
    n_sols = st[S_SOLS]
    n_expanded = st[S_EXPANDED]
    n_generated = st[S_GENERATED]
    free = st[S_FREE]
    n_free = st[S_N_FREE]
    status = DONE
    steps = 0
    pops0 = st[S_POPS]

    while size > 0:
        if steps == n_steps:
            status = PAUSED
            break
        if n - n_free + 8 > max_labels:
            status = OVER_BUDGET
            break
        if n + 8 > li.shape[0] or size + 8 > hk.shape[0] or n_sols + 1 > sols.shape[0]:
            status = NEED_ROOM
            break
        if sp[SP_USED] + _stair_room(sp) > sp.shape[0]:
            status = NEED_ROOM
            break
        steps += 1
        x, size = _pop(hk, size)
        if li[x, NEXT] == MERGED:  # another open label stands for it
            li[x, NEXT] = free
            free = x
            n_free += 1
            continue
        c = li[x, CELL]
        hx = li[x, F_HEAD]
        sx = c * N_SLOTS + _slot(hx)
        if open_at[sx] == x:
            open_at[sx] = -1
        t = li[x, TURNS]
        a = lf[x, F_APEX]
        tgoal = t + (ht[c * N_SLOTS + (hx if hx >= 0 else 8)] if has_ht else 0)
        if _covered(gmin, sp, first, c, goal, goal_base, goal_state, t, a, hx, tgoal, a + hv[c]):
            li[x, NEXT] = free
            free = x
            n_free += 1
            continue
        if c == goal:
            _goal_record(gmin, goal_base, first, goal_state, t, a)
            sols[n_sols] = x
            n_sols += 1
            continue
        n_expanded += 1
        _three_insert(sp, first, gmin, sx, t, a)
        r, col = c // w, c % w
        x_ns, x_nd, x_v, x_al = li[x, NS], li[x, ND], lf[x, F_VUL], lf[x, F_APEX_LEN]
        mk = mask[c]
        for d in range(8):
            if not (mk >> d) & 1:
                continue
            r2, c2 = r + DR[d], col + DC[d]
            cell = r2 * w + c2
            if hv[cell] == np.inf:
                continue
            n_generated += 1
            ns_j = x_ns + (1 - d % 2)
            nd_j = x_nd + d % 2
            t_j = t + (turn(hx, d) if hx >= 0 else 0)
            p = pot[r2, c2]
            v_j = x_v + p
            a_j = a + p
            tg = t_j + (ht[cell * N_SLOTS + d] if has_ht else 0)
            if _covered(gmin, sp, first, cell, goal, goal_base, goal_state, t_j, a_j, d, tg, a_j + hv[cell]):
                continue
            # merge with the last open label of a state of this cell
            len_j = ns_j + SQRT2 * nd_j
            al_j = x_al + (1.0 if d % 2 == 0 else SQRT2)
            merged = False
            copy = -1  # o stands for both with a shorter apex: o's path in a new row
            for k in range(8):
                o = open_at[cell * N_SLOTS + k]
                if o < 0:
                    continue
                amin = min(a_j, lf[o, F_APEX])
                almin = min(al_j, lf[o, F_APEX_LEN])
                len_o = li[o, NS] + SQRT2 * li[o, ND]
                t_o = li[o, TURNS]
                if _le(len_o, slack * almin) and t_o + turn(k, d) <= t_j and lf[o, F_VUL] <= slack * amin:
                    if almin >= lf[o, F_APEX_LEN]:  # o's key stays
                        lf[o, F_APEX] = amin
                        merged = True
                    else:
                        copy = o
                        li[o, NEXT] = MERGED
                        open_at[cell * N_SLOTS + k] = -1
                    a_j = amin
                    al_j = almin
                    break
                if _le(len_j, slack * almin) and t_j + turn(d, k) <= t_o and v_j <= slack * amin:
                    li[o, NEXT] = MERGED  # the new label stands for o
                    open_at[cell * N_SLOTS + k] = -1
                    a_j = amin
                    al_j = almin
                    break
            if merged:
                continue
            if free >= 0:
                j = free
                free = li[j, NEXT]
                n_free -= 1
            else:
                j = n
                n += 1
            if copy >= 0:
                dj = li[copy, F_HEAD]
                li[j, CELL] = cell
                li[j, F_HEAD] = dj
                li[j, F_PARENT] = li[copy, F_PARENT]
                li[j, NS] = li[copy, NS]
                li[j, ND] = li[copy, ND]
                li[j, TURNS] = li[copy, TURNS]
                lf[j, F_VUL] = lf[copy, F_VUL]
                tg = li[copy, TURNS] + (ht[cell * N_SLOTS + dj] if has_ht else 0)
            else:
                dj = d
                li[j, CELL] = cell
                li[j, F_HEAD] = d
                li[j, F_PARENT] = x
                li[j, NS] = ns_j
                li[j, ND] = nd_j
                li[j, TURNS] = t_j
                lf[j, F_VUL] = v_j
            li[j, NEXT] = -1
            lf[j, F_APEX] = a_j
            lf[j, F_APEX_LEN] = al_j
            f_len = (al_j + hs[cell] + SQRT2 * hd[cell]) * cell_size
            _heap4_push(hk, size, f_len, a_j + hv[cell], np.float64(tg), j)
            size += 1
            open_at[cell * N_SLOTS + dj] = j
    st[S_N] = n
    st[S_SIZE] = size
    st[S_SOLS] = n_sols
    st[S_EXPANDED] = n_expanded
    st[S_GENERATED] = n_generated
    st[S_FREE] = free
    st[S_N_FREE] = n_free
    st[S_POPS] = pops0 + steps
    return status
