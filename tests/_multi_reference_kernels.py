"""The k-objective search's kernels as they were before the per-state sets
became contiguous blocks (linked lists through the label table, scanned
linearly), kept verbatim as the test reference of the faster sets: fronts,
expansion and generation counts must be identical. Original docstring:

Numba kernels of the k-objective exact search (private; driver in
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
    ``heads`` holds the head of each state's set, the goal's set last. The
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
N_ST = 10


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


# -- dominance ----------------------------------------------------------------------


@numba.njit(cache=True)
def _state_covered(li, lg, heads, s, x, okind, ocol, cell_size, ties, smooth):
    """True if an expanded label of state ``s`` covers label ``x``: every
    completion of ``x`` is dominated by, or tolerance-equal to and (with
    ``ties``, smoothness not an objective) not smoother than, the same
    completion of that label. The covering label moves to the front of the
    set (the next labels tested are often alike)."""
    k = okind.shape[0]
    hx = li[x, HEAD]
    prev = -1
    a = heads[s]
    while a >= 0:
        gap = _gap(li[a, HEAD], hx)
        ok = True
        strict = False
        for jj in range(k):
            j = jj + 1 if jj < k - 1 else 0  # the primary last: it rarely decides
            kind = okind[j]
            if kind == K_TURN:
                ta = li[a, TURNS] + gap
                tx = li[x, TURNS]
                if ta > tx:
                    ok = False
                    break
                if ta < tx:
                    strict = True
            else:
                ga = _g(li, lg, a, kind, ocol[j], cell_size)
                gx = _g(li, lg, x, kind, ocol[j], cell_size)
                if not _le(ga, gx):
                    ok = False
                    break
                if not _eq(ga, gx):
                    strict = True
        if ok and (strict or smooth or not ties or li[a, TURNS] + gap <= li[x, TURNS]):
            if prev >= 0:
                li[prev, NEXT] = li[a, NEXT]
                li[a, NEXT] = heads[s]
                heads[s] = a
            return True
        prev = a
        a = li[a, NEXT]
    return False


@numba.njit(cache=True)
def _goal_covered(li, lg, lf, heads, x, okind, ocol, cell_size, ties, smooth, to_go):
    """True if a solution covers the f-vector of ``x`` (its lower bound at
    the goal); ``to_go`` is a lower bound of the turns still to come (0 when
    the turn heuristic is not computed). The goal's set is headed by
    ``heads[-1]``; the covering solution moves to its front."""
    k = okind.shape[0]
    g = heads.shape[0] - 1
    prev = -1
    a = heads[g]
    while a >= 0:
        ok = True
        strict = False
        for jj in range(k):
            j = jj + 1 if jj < k - 1 else 0
            kind = okind[j]
            fx = lf[x, j]
            ga = _g(li, lg, a, kind, ocol[j], cell_size)
            if kind == K_TURN:
                if ga > fx:
                    ok = False
                    break
                if ga < fx:
                    strict = True
            else:
                if not _le(ga, fx):
                    ok = False
                    break
                if not _eq(ga, fx):
                    strict = True
        if ok and (strict or smooth or not ties or li[a, TURNS] <= li[x, TURNS] + to_go):
            if prev >= 0:
                li[prev, NEXT] = li[a, NEXT]
                li[a, NEXT] = heads[g]
                heads[g] = a
            return True
        prev = a
        a = li[a, NEXT]
    return False


@numba.njit(cache=True)
def _insert(li, lg, first, x, okind, ocol, cell_size, at_goal):
    """Put label ``x`` at the head of the set whose head is ``first`` and
    unlink the members it makes redundant for later checks: those it weakly
    dominates on every objective but the primary (later labels are not
    better in the primary, NAMOA*-dr). Returns the new head."""
    k = okind.shape[0]
    hx = li[x, HEAD]
    prev = -1
    a = first
    while a >= 0:
        nxt = li[a, NEXT]
        gap = 0 if at_goal else _gap(hx, li[a, HEAD])
        drop = True
        for j in range(1, k):
            kind = okind[j]
            if kind == K_TURN:
                if li[x, TURNS] + gap > li[a, TURNS]:
                    drop = False
                    break
            elif not _le(_g(li, lg, x, kind, ocol[j], cell_size), _g(li, lg, a, kind, ocol[j], cell_size)):
                drop = False
                break
        if drop:
            if prev < 0:
                first = nxt
            else:
                li[prev, NEXT] = nxt
        else:
            prev = a
        a = nxt
    li[x, NEXT] = first
    return x


# -- the search -----------------------------------------------------------------------


@numba.njit(cache=True)
def _k_init(start, layers, okind, ocol, cell_size, hs, hd, ht, hfl, hop, psum, timed, n_float):
    """The state of a new search: the start label alone on the open list.
    Returns ``(li, lg, lf, hid, sols, st)``."""
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
    return li, lg, lf, hid, sols, st


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
    heads,
    li,
    lg,
    lf,
    hid,
    sols,
    st,
    n_steps,
    max_labels,
):
    """Advance the search by at most ``n_steps`` pops. Returns ``(heads, li,
    lg, lf, hid, sols, status)``, status DONE (open list empty), PAUSED,
    OVER_BUDGET or STEP_LIMIT; the arrays may have been reallocated (grown
    by doubling)."""
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
            heads,
            li,
            lg,
            lf,
            hid,
            sols,
            st,
            n_steps - (st[S_POPS] - pops0),
            max_labels,
        )
        if status != NEED_ROOM:
            return heads, li, lg, lf, hid, sols, status
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
        if timed:
            x = hid[0]
            span = st[S_SPAN]
            while li[x, NS] + li[x, ND] + 1 >= span:
                span *= 2
            if span > st[S_SPAN]:
                heads2 = np.full(span * n_cells + 1, -1, np.int32)
                heads2[: heads.shape[0] - 1] = heads[:-1]
                heads2[-1] = heads[-1]  # the goal's set
                heads = heads2
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
    heads,
    li,
    lg,
    lf,
    hid,
    sols,
    st,
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
    status = DONE
    steps = 0
    pops0 = st[S_POPS]
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
        steps += 1
        size = _pop(hid, size, lf, k)
        c = li[x, CELL]
        s = n_x * n_cells + c if timed else c

        # lazy checks: the sets may have grown since x was generated
        covered = c != goal and _state_covered(li, lg, heads, s, x, okind, ocol, cell_size, ties, smooth)
        if not covered:
            to_go = 0
            if use_ht:
                hx = li[x, HEAD]
                to_go = ht[c * 9 + (hx if hx >= 0 else 8)]
            covered = _goal_covered(li, lg, lf, heads, x, okind, ocol, cell_size, ties, smooth, to_go)
        if covered:
            li[x, NEXT] = free  # nothing refers to x: recycle its row
            free = x
            n_free += 1
            continue
        if c == goal:  # a solution: recorded, never expanded
            heads[-1] = _insert(li, lg, heads[-1], x, okind, ocol, cell_size, True)
            sols[n_sols] = x
            n_sols += 1
            continue

        n_expanded += 1
        heads[s] = _insert(li, lg, heads[s], x, okind, ocol, cell_size, False)
        r, col = c // w, c % w
        head = li[x, HEAD]
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
            li[j, TURNS] = li[x, TURNS] + (turn(head, d) if head >= 0 else 0)
            for o in range(k):
                kind = okind[o]
                if kind == K_CELL:
                    lg[j, ocol[o]] = lg[x, ocol[o]] + layers[ocol[o], cell]
                elif kind == K_SOLAR:
                    lg[j, ocol[o]] = lg[x, ocol[o]] + table[n_x if timed else 0, d]
            _fvec(li, lg, lf, j, okind, ocol, cell_size, hs, hd, ht, hfl, hop, psum, timed)
            n_generated += 1
            s2 = (n_x + 1) * n_cells + cell if timed else cell
            if cell != goal and _state_covered(li, lg, heads, s2, j, okind, ocol, cell_size, ties, smooth):
                continue
            to_go = ht[cell * 9 + d] if use_ht else 0
            if _goal_covered(li, lg, lf, heads, j, okind, ocol, cell_size, ties, smooth, to_go):
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
