"""Exact Pareto fronts (SPEC "Reference (exact) fronts").

Monotone reference front
    :func:`monotone_front` computes the exact Pareto set of the FEASIBLE
    column-monotone paths, the paths the GA's integer encoding can describe,
    by a multi-objective dynamic programme over the columns of the canonical
    frame (:class:`gapath.encodings.base.Frame`).

Free reference front
    :func:`free_front` computes the exact Pareto set of all FEASIBLE
    8-connected paths by multi-objective label-setting search (BOA* for two
    objectives, NAMOA*-dr / EMOA* for three); see the section at the end of
    this module.

The monotone path set
    In the frame (start column left of the goal column) a path starts at the
    start cell and runs vertically inside the start column to an exit row
    ``e_0`` (one contiguous run). Each following column ``k`` is entered by
    one horizontal step (``e_k == e_{k-1}``) or one diagonal step towards
    ``e_k`` (entry ``e_{k-1} + sign(e_k - e_{k-1})``), followed by vertical
    steps in the same direction up to ``e_k``. The goal column is entered the
    same way with ``e = goal row``. A path is therefore determined by its exit
    rows in the columns before the goal column. It is feasible when none of
    its cells is an obstacle and, if the workspace forbids corner cutting,
    none of its diagonal steps has a blocked orthogonal neighbour.

Ties and tolerance
    Two objective values ``a, b`` are equal when
    ``|a - b| <= 1e-9 * max(1, |a|, |b|)`` (SPEC). Dominance is taken up to
    that tolerance: ``a`` dominates ``b`` when every objective of ``a`` is
    smaller than or equal (within the tolerance) to that of ``b`` and at least
    one is smaller beyond the tolerance. The front keeps one path per
    tolerance-equal objective vector; among such paths it prefers the one
    with the smallest total turn (``smoothness``), also when smoothness is
    not an objective.

Bit-exact objectives
    Labels carry integer step counts (straight, diagonal), an integer count
    of eighth turns and the vulnerability summed cell by cell in path order,
    so the values in :attr:`ExactFront.F` are computed with the arithmetic of
    :mod:`gapath.objectives` and equal what :func:`gapath.objectives.evaluate_path`
    or :func:`gapath.objectives.evaluate_profiles` give for the returned paths.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from gapath.encodings.base import Frame, expand_profiles, split_paths
from gapath.errors import ConfigError, NoPathError
from gapath.objectives import OBJECTIVES, QUARTER_PI, SQRT2, _turn, objective_index
from gapath.planners._grid import DC, DR, can_step

__all__ = ["ExactFront", "monotone_front", "free_front", "EXACT_OBJECTIVES"]

#: Objectives the exact planners can minimise (``interfering`` is a constraint:
#: every returned path has ``interfering == 0``).
EXACT_OBJECTIVES = ("length", "vulnerability", "smoothness")

#: Relative tolerance of SPEC "Duplicates and ties".
TOL = 1e-9


# ---------------------------------------------------------------------------
# result
# ---------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class ExactFront:
    """An exact Pareto front and one path per front point.

    Attributes
    ----------
    objectives : tuple of str
        Objective names, the column order of ``F``.
    F : (k, m) float array
        Objective vectors, sorted lexicographically (first objective first),
        one per tolerance-equal vector.
    paths : list of (m_i, 2) int arrays
        One path per row of ``F``, in workspace coordinates, from start to
        goal in 8-connected steps.
    profiles : tuple (entries, exits) of (k, n_cols) int arrays, or None
        Column profiles of the paths in frame coordinates (see
        :mod:`gapath.encodings.base`); None for :func:`free_front` (free
        paths have no column profile).
    smoothness : (k,) float array
        Total turn of each path (radians), also when smoothness is not an
        objective.
    """

    objectives: tuple
    F: np.ndarray
    paths: list
    profiles: tuple
    smoothness: np.ndarray

    def __len__(self) -> int:
        return len(self.F)

    def to_dict(self) -> dict:
        """Plain Python (JSON-serialisable) form of the front.

        ``entries`` and ``exits`` (the column profiles) are left out when the
        front has none (:func:`free_front`).

        Examples
        --------
        >>> import numpy as np
        >>> from gapath import Workspace
        >>> d = monotone_front(Workspace(np.zeros((2, 3), bool))).to_dict()
        >>> sorted(d)
        ['F', 'entries', 'exits', 'objectives', 'paths', 'smoothness']
        """
        out = {
            "objectives": list(self.objectives),
            "F": self.F.tolist(),
            "smoothness": self.smoothness.tolist(),
            "paths": [p.tolist() for p in self.paths],
        }
        if self.profiles is not None:
            entries, exits = self.profiles
            out["entries"] = entries.tolist()
            out["exits"] = exits.tolist()
        return out


# ---------------------------------------------------------------------------
# labels
# ---------------------------------------------------------------------------
# A label is a partial path ending at some exit row of the current column.
# Labels live in two tables that grow by doubling: an int table with the
# columns below and a float table with the length and the vulnerability.

ROW, PARENT, HEAD, N_STRAIGHT, N_DIAG, EIGHTHS = range(6)
LENGTH, VUL = range(2)

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
    return _turn(ha, hb)


@numba.njit(cache=True)
def _covers(ai, af, a, bi, bf, b, use_len, use_vul, use_smooth, at_goal):
    """True if label ``a`` makes label ``b`` (same row, same column) useless:
    every completion of ``b`` is dominated by, or tolerance-equal and not
    smoother than, the same completion of ``a``.

    The next turn depends on the heading, so ``a``'s turn count is charged
    with the worst difference its heading can make (nothing at the goal)."""
    strictly_better = False
    if use_len:
        if not _le(af[a, LENGTH], bf[b, LENGTH]):
            return False
        strictly_better = strictly_better or not _eq(af[a, LENGTH], bf[b, LENGTH])
    if use_vul:
        if not _le(af[a, VUL], bf[b, VUL]):
            return False
        strictly_better = strictly_better or not _eq(af[a, VUL], bf[b, VUL])
    gap = 0 if at_goal else _heading_gap(ai[a, HEAD], bi[b, HEAD])
    smoother = ai[a, EIGHTHS] + gap <= bi[b, EIGHTHS]
    if use_smooth:
        return smoother
    # smoothness only breaks ties between tolerance-equal vectors
    return strictly_better or smoother


@numba.njit(cache=True)
def _reach(occ, p, c, corner_cutting):
    """Rows of column ``c`` reachable from row ``p`` of column ``c - 1``.

    Returns ``(top, bottom, flat)``: a diagonal step up followed by vertical
    steps up reaches rows ``top .. p - 1`` (none when ``top == p``), likewise
    ``p + 1 .. bottom`` downwards, and ``flat`` says whether the horizontal
    step to row ``p`` is possible."""
    h = occ.shape[0]
    flat = not occ[p, c]
    top = p
    if p > 0 and not occ[p - 1, c] and (corner_cutting or (not occ[p, c] and not occ[p - 1, c - 1])):
        top = p - 1
        while top > 0 and not occ[top - 1, c]:
            top -= 1
    bottom = p
    if p < h - 1 and not occ[p + 1, c] and (corner_cutting or (not occ[p, c] and not occ[p + 1, c - 1])):
        bottom = p + 1
        while bottom < h - 1 and not occ[bottom + 1, c]:
            bottom += 1
    return top, bottom, flat


@numba.njit(cache=True)
def _extend(li, lf, a, t, vul, ci, cf, j, cell_size):
    """Write into candidate slot ``j`` the label ``a`` (exit row ``p``)
    extended to exit row ``t`` of the next column, ``vul`` being the
    vulnerability already summed along the new cells in path order."""
    p = li[a, ROW]
    n_straight = li[a, N_STRAIGHT]
    n_diag = li[a, N_DIAG]
    if t == p:
        step = EAST
        n_straight += 1
    else:
        step = NORTH_EAST if t < p else SOUTH_EAST
        n_diag += 1
    eighths = li[a, EIGHTHS]
    if li[a, HEAD] != NO_HEADING:
        eighths += _turn(li[a, HEAD], step)
    head = step
    if abs(t - p) >= 2:  # vertical run after the diagonal: one eighth turn
        n_straight += abs(t - p) - 1
        eighths += 1
        head = NORTH if t < p else SOUTH
    ci[j, ROW] = t
    ci[j, PARENT] = a
    ci[j, HEAD] = head
    ci[j, N_STRAIGHT] = n_straight
    ci[j, N_DIAG] = n_diag
    ci[j, EIGHTHS] = eighths
    cf[j, LENGTH] = (n_straight + SQRT2 * n_diag) * cell_size
    cf[j, VUL] = vul


@numba.njit(cache=True, inline="always")
def _key(ti, tf, i, primary):
    """Value of the primary (first) objective of label ``i``."""
    return np.float64(ti[i, EIGHTHS]) if primary == 2 else tf[i, primary]


@numba.njit(cache=True)
def _filter_row(li, lf, n, ci, cf, lo, hi, use_len, use_vul, use_smooth, primary, at_goal):
    """Append to the label tables (which hold ``n`` labels) the labels of one
    state: the candidates ``lo .. hi - 1`` that no other candidate covers.

    Candidates are visited in increasing order of the primary objective, so
    a new label can only cover an earlier one when their primary values tie;
    the running minima of the kept labels let most candidates be accepted or
    rejected without scanning the kept ones. Returns the new label count."""
    first = n
    key = np.empty(hi - lo)
    for j in range(lo, hi):
        key[j - lo] = _key(ci, cf, j, primary)
    big = np.inf
    min_len, min_vul, min_eighths = big, big, big
    for j in np.argsort(key, kind="mergesort") + lo:
        # a kept label can cover j only if it is not worse in every objective
        maybe_covered = n > first
        if use_len and not _le(min_len, cf[j, LENGTH]):
            maybe_covered = False
        if use_vul and not _le(min_vul, cf[j, VUL]):
            maybe_covered = False
        if use_smooth and min_eighths > ci[j, EIGHTHS]:
            maybe_covered = False
        if maybe_covered:
            covered = False
            for i in range(n - 1, first - 1, -1):
                if _covers(li, lf, i, ci, cf, j, use_len, use_vul, use_smooth, at_goal):
                    covered = True
                    break
            if covered:
                continue
        # j can cover a kept label only if their primary values tie
        if n > first and _le(_key(ci, cf, j, primary), _key(li, lf, n - 1, primary)):
            kept = first
            for i in range(first, n):
                if not _covers(ci, cf, j, li, lf, i, use_len, use_vul, use_smooth, at_goal):
                    li[kept] = li[i]
                    lf[kept] = lf[i]
                    kept += 1
            if kept < n:
                n = kept
                min_len, min_vul, min_eighths = big, big, big
                for i in range(first, n):
                    min_len = min(min_len, lf[i, LENGTH])
                    min_vul = min(min_vul, lf[i, VUL])
                    min_eighths = min(min_eighths, np.float64(li[i, EIGHTHS]))
        li[n] = ci[j]
        lf[n] = cf[j]
        min_len = min(min_len, cf[j, LENGTH])
        min_vul = min(min_vul, cf[j, VUL])
        min_eighths = min(min_eighths, np.float64(ci[j, EIGHTHS]))
        n += 1
    return n


@numba.njit(cache=True)
def _monotone_dp(occ, pot, start_row, goal_row, col0, n_cols, cell_size, corner_cutting,
                 use_len, use_vul, use_smooth, primary):
    """Multi-objective DP over the columns of the frame.

    Returns the label tables ``(li, lf)`` and the index range ``[lo, hi)`` of
    the final labels (the Pareto set at the goal)."""
    h = occ.shape[0]
    li = np.empty((256, 6), np.int64)
    lf = np.empty((256, 2))
    n = 0
    # off[r] .. off[r + 1]: labels of the current column with exit row r
    off = np.zeros(h + 1, np.int64)

    # 1. start column: one label per reachable exit row (a single vertical run)
    vul_to = np.full(h, np.nan)
    vul_to[start_row] = pot[start_row, col0]
    for s in (-1, 1):
        r, v = start_row, pot[start_row, col0]
        while 0 <= r + s < h and not occ[r + s, col0]:
            r += s
            v += pot[r, col0]
            vul_to[r] = v
    li = _grow(li, h)
    lf = _grow(lf, h)
    for r in range(h):
        off[r] = n
        if np.isnan(vul_to[r]):
            continue
        d = abs(r - start_row)
        li[n, ROW] = r
        li[n, PARENT] = -1
        li[n, HEAD] = NO_HEADING if d == 0 else (NORTH if r < start_row else SOUTH)
        li[n, N_STRAIGHT] = d
        li[n, N_DIAG] = 0
        li[n, EIGHTHS] = 0
        lf[n, LENGTH] = d * cell_size
        lf[n, VUL] = vul_to[r]
        n += 1
    off[h] = n

    counts = np.zeros(h + 1, np.int64)
    for k in range(1, n_cols):
        c = col0 + k
        at_goal = k == n_cols - 1  # the goal column: exit row = goal row

        # 2. count the candidate labels of each exit row of column c
        counts[:] = 0
        for p in range(h):
            n_labels = off[p + 1] - off[p]
            if n_labels == 0:
                continue
            top, bottom, flat = _reach(occ, p, c, corner_cutting)
            for t in range(top, bottom + 1):
                if (t != p or flat) and (not at_goal or t == goal_row):
                    counts[t + 1] += n_labels
        cand_off = np.cumsum(counts)  # candidates of row t: cand_off[t] .. cand_off[t + 1]
        ci = np.empty((cand_off[h], 6), np.int64)
        cf = np.empty((cand_off[h], 2))
        fill = cand_off[:h].copy()

        # 3. extend every label of column c - 1 to every reachable exit row,
        #    summing the potential of the new cells in path order
        for p in range(h):
            if off[p + 1] == off[p]:
                continue
            top, bottom, flat = _reach(occ, p, c, corner_cutting)
            for a in range(off[p], off[p + 1]):
                if flat and (not at_goal or p == goal_row):
                    _extend(li, lf, a, p, lf[a, VUL] + pot[p, c], ci, cf, fill[p], cell_size)
                    fill[p] += 1
                for s, last in ((-1, top), (1, bottom)):
                    v = lf[a, VUL]
                    t = p
                    while t != last:
                        t += s
                        v += pot[t, c]
                        if not at_goal or t == goal_row:
                            _extend(li, lf, a, t, v, ci, cf, fill[t], cell_size)
                            fill[t] += 1

        # 4. keep the non-dominated candidates of each exit row
        li = _grow(li, n + cand_off[h])
        lf = _grow(lf, n + cand_off[h])
        new_off = np.empty(h + 1, np.int64)
        for t in range(h):
            new_off[t] = n
            if cand_off[t + 1] > cand_off[t]:
                n = _filter_row(li, lf, n, ci, cf, cand_off[t], cand_off[t + 1],
                                use_len, use_vul, use_smooth, primary, at_goal)
        new_off[h] = n
        off = new_off

    return li[:n], lf[:n], off[goal_row], off[goal_row + 1]


# ---------------------------------------------------------------------------
# monotone reference front
# ---------------------------------------------------------------------------

def _check_objectives(objectives) -> tuple[str, ...]:
    names = tuple(OBJECTIVES[i] for i in objective_index(objectives))
    bad = [n for n in names if n not in EXACT_OBJECTIVES]
    if bad:
        raise ConfigError(
            f"objective {bad[0]!r} cannot be minimised by the exact planner (it is a "
            f"constraint: every returned path has interfering == 0); "
            f"choose among {', '.join(EXACT_OBJECTIVES)}")
    return names


def monotone_front(workspace, objectives=("length", "vulnerability")) -> ExactFront:
    """Exact Pareto front of the feasible column-monotone paths.

    A dynamic programme over the columns of the canonical frame: the state is
    the exit row in the current column; its labels are the non-dominated
    partial paths ending there (objective values, the heading of the last
    step, a back-pointer). Extending a label by one column follows the
    integer encoding's transition (horizontal or diagonal step, then vertical
    steps in the same direction); obstacle cells and, without corner cutting,
    corner-cutting diagonals are never entered.

    Parameters
    ----------
    workspace : Workspace
        The map, start and goal. When the goal is left of the start the frame
        is mirrored; when they share a column it is transposed (rows play the
        part of columns), see :class:`gapath.encodings.base.Frame`.
    objectives : sequence of str or comma-separated str, optional
        Any subset of ``"length"``, ``"vulnerability"``, ``"smoothness"``, in
        the column order wanted for ``F`` (default length, vulnerability).

    Returns
    -------
    ExactFront
        One path per tolerance-equal Pareto-optimal objective vector, sorted
        lexicographically. Among tolerance-equal paths the smoothest one is
        preferred.

    Raises
    ------
    ConfigError
        If an objective is unknown, repeated or ``"interfering"``.
    NoPathError
        If no feasible column-monotone path exists.

    Notes
    -----
    The heading of the last step matters for the next turn; rather than
    splitting states by heading, a label with heading ``h_a`` may discard a
    label with heading ``h_b`` at the same row only after its turn count is
    charged with the turn between ``h_a`` and ``h_b`` (the most the next turn
    can differ by). This is exact for smoothness and keeps one state per row.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> ws = Workspace(np.zeros((3, 3), bool))
    >>> front = monotone_front(ws, ("length", "smoothness"))
    >>> front.F.round(4).tolist()
    [[2.8284, 0.0]]
    >>> front.paths[0].tolist()
    [[2, 0], [1, 1], [0, 2]]
    """
    names = _check_objectives(objectives)
    frame = Frame.of(workspace)
    (sr, _), (gr, _) = frame.start, frame.goal
    primary = {"length": LENGTH, "vulnerability": VUL, "smoothness": 2}[names[0]]
    li, lf, lo, hi = _monotone_dp(
        frame.occ, frame.potential, sr, gr, frame.col0, frame.n_cols,
        float(workspace.cell_size), bool(workspace.corner_cutting),
        "length" in names, "vulnerability" in names, "smoothness" in names, primary)
    if hi == lo:
        h, w = workspace.shape
        raise NoPathError(
            f"no feasible column-monotone path from {workspace.start} to {workspace.goal} "
            f"in workspace {workspace.name!r} ({h}x{w}, {workspace.n_obstacles} obstacles, "
            f"corner_cutting={workspace.corner_cutting})")

    # back-pointers -> exit row of every column
    final = np.arange(lo, hi)
    exits = np.empty((len(final), frame.n_cols), np.int64)
    idx = final
    for k in range(frame.n_cols - 1, -1, -1):
        exits[:, k] = li[idx, ROW]
        idx = li[idx, PARENT]
    entries = np.empty_like(exits)
    entries[:, 0] = sr
    entries[:, 1:] = exits[:, :-1] + np.sign(exits[:, 1:] - exits[:, :-1])

    values = {
        "length": lf[final, LENGTH],
        "vulnerability": lf[final, VUL],
        "smoothness": li[final, EIGHTHS] * QUARTER_PI,
    }
    F = np.column_stack([values[name] for name in names])
    order = np.lexsort(F.T[::-1])
    F, entries, exits = F[order], entries[order], exits[order]
    cells, n_cells = expand_profiles(frame, entries, exits)
    return ExactFront(objectives=names, F=F, paths=split_paths(cells, n_cells),
                      profiles=(entries, exits), smoothness=values["smoothness"][order])


# ---------------------------------------------------------------------------
# free reference front (all feasible 8-connected paths)
# ---------------------------------------------------------------------------
# The search follows BOA* (Hernandez et al. 2020, 2023) for two objectives and
# NAMOA*-dr / EMOA* (Pulido et al. 2015; Ren et al. 2022) for three:
#
#   1. heuristics: one backward single-objective Dijkstra per objective, from
#      the goal (_free_heuristics);
#   2. an open list of labels ordered lexicographically by their f-vectors
#      (_heap_push / _heap_pop);
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

CELL, F_HEAD, F_PARENT, NS, ND, TURNS, NEXT = range(7)   # int table
F_VUL, RUNMIN = range(2)                                 # float table
# CELL: row * W + col; F_HEAD: heading of the last step (-1 at the start);
# NS/ND: straight/diagonal step counts; TURNS: total turn in eighths; NEXT:
# link to the next label of the same state's list; RUNMIN: the state's
# smallest second objective once this label was accepted.

OBJ_LEN, OBJ_VUL, OBJ_SMOOTH = range(3)
#: Search modes: BOA* on (length, vulnerability) with cells as states and
#: smoothness as tie-break; BOA* on (x, smoothness) with (cell, heading)
#: states; NAMOA*-dr on (length, vulnerability, smoothness).
MODE_CELL, MODE_HEADING, MODE_THREE = range(3)
N_SLOTS = 9          # per cell: the 8 headings and "no heading" (slot 8)
_BIG_TURNS = 1 << 40


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
    entries; the caller makes room first (:func:`_heap_room`)."""
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


@numba.njit(cache=True)
def _heap_room(hk, hid):
    """The heap arrays with twice the capacity (pushing never reallocates,
    so that the arrays need not be returned on every push)."""
    return _grow(hk, hk.shape[0] + 1), _grow1(hid, hid.shape[0] + 1)


@numba.njit(cache=True, inline="always")
def _heap_pop(hk, hid, size):
    """Remove the smallest entry of a heap of ``size`` entries; returns
    ``(node, size - 1)``."""
    top = hid[0]
    size -= 1
    if size > 0:
        k1, k2, k3, node = hk[size, 0], hk[size, 1], hk[size, 2], hid[size]
        i = 0
        while True:
            ch = 2 * i + 1
            if ch >= size:
                break
            if ch + 1 < size and _key_less(hk[ch + 1, 0], hk[ch + 1, 1], hk[ch + 1, 2], hid[ch + 1],
                                           hk[ch, 0], hk[ch, 1], hk[ch, 2], hid[ch]):
                ch += 1
            if not _key_less(hk[ch, 0], hk[ch, 1], hk[ch, 2], hid[ch], k1, k2, k3, node):
                break
            hk[i, 0] = hk[ch, 0]
            hk[i, 1] = hk[ch, 1]
            hk[i, 2] = hk[ch, 2]
            hid[i] = hid[ch]
            i = ch
        hk[i, 0] = k1
        hk[i, 1] = k2
        hk[i, 2] = k3
        hid[i] = node
    return top, size


# -- 1. heuristics ----------------------------------------------------------

@numba.njit(cache=True)
def _free_heuristics(occ, pot, gr, gc, corner_cutting):
    """Exact single-objective costs-to-go, by backward Dijkstra from the goal.

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
        ``k`` (8 = none), to the goal, obstacles and corner rule included.
    """
    h, w = occ.shape
    n = h * w
    goal = gr * w + gc
    hk = np.empty((64, 3))
    hid = np.empty(64, np.int64)

    # length, as step counts
    hs = np.full(n, -1, np.int64)
    hd = np.full(n, -1, np.int64)
    dist = np.full(n, np.inf)
    dist[goal] = 0.0
    hs[goal] = 0
    hd[goal] = 0
    _heap_push(hk, hid, 0, 0.0, 0.0, 0.0, goal)
    size = 1
    while size > 0:
        key = hk[0, 0]
        u, size = _heap_pop(hk, hid, size)
        if key > dist[u]:
            continue
        ur, uc = u // w, u % w
        for d in range(8):
            if not can_step(occ, ur, uc, DR[d], DC[d], corner_cutting):
                continue
            v = (ur + DR[d]) * w + uc + DC[d]
            ns = hs[u] + (1 - d % 2)
            nd = hd[u] + d % 2
            val = ns + SQRT2 * nd
            if val < dist[v]:
                dist[v] = val
                hs[v] = ns
                hd[v] = nd
                if size == hid.shape[0]:
                    hk, hid = _heap_room(hk, hid)
                _heap_push(hk, hid, size, val, 0.0, 0.0, v)
                size += 1

    # vulnerability: D(u) = P(u) + min_v D(v), D(goal) = P(goal); hv(u) = min_v D(v)
    D = np.full(n, np.inf)
    hv = np.full(n, np.inf)
    D[goal] = pot[gr, gc]
    hv[goal] = 0.0
    _heap_push(hk, hid, 0, D[goal], 0.0, 0.0, goal)
    size = 1
    while size > 0:
        key = hk[0, 0]
        u, size = _heap_pop(hk, hid, size)
        if key > D[u]:
            continue
        ur, uc = u // w, u % w
        for d in range(8):
            if not can_step(occ, ur, uc, DR[d], DC[d], corner_cutting):
                continue
            vr, vc = ur + DR[d], uc + DC[d]
            v = vr * w + vc
            if v == goal:
                continue
            val = pot[vr, vc] + D[u]
            if val < D[v]:
                D[v] = val
                hv[v] = D[u]
                if size == hid.shape[0]:
                    hk, hid = _heap_room(hk, hid)
                _heap_push(hk, hid, size, val, 0.0, 0.0, v)
                size += 1

    # turns over (cell, heading) states: T(u, k) = min_d turn(k, d) + T(u + d, d)
    ht = np.full(n * N_SLOTS, _BIG_TURNS, np.int64)
    for k in range(N_SLOTS):
        ht[goal * N_SLOTS + k] = 0
    size = 0
    for d in range(8):
        if size == hid.shape[0]:
            hk, hid = _heap_room(hk, hid)
        _heap_push(hk, hid, size, 0.0, 0.0, 0.0, goal * N_SLOTS + d)
        size += 1
    while size > 0:
        key = hk[0, 0]
        s, size = _heap_pop(hk, hid, size)
        if key > ht[s]:
            continue
        v, d = s // N_SLOTS, s % N_SLOTS
        ur, uc = v // w - DR[d], v % w - DC[d]
        if ur < 0 or ur >= h or uc < 0 or uc >= w or occ[ur, uc]:
            continue
        if not can_step(occ, ur, uc, DR[d], DC[d], corner_cutting):
            continue
        u = ur * w + uc
        for k in range(N_SLOTS):
            val = ht[s] + (_turn(k, d) if k < 8 else 0)
            if val < ht[u * N_SLOTS + k]:
                ht[u * N_SLOTS + k] = val
                if k < 8:
                    if size == hid.shape[0]:
                        hk, hid = _heap_room(hk, hid)
                    _heap_push(hk, hid, size, np.float64(val), 0.0, 0.0, u * N_SLOTS + k)
                    size += 1
    return hs, hd, hv, ht


# -- label values -------------------------------------------------------------

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
    return np.float64(li[i, TURNS] + ht[c * N_SLOTS + _slot(li[i, F_HEAD])])


# -- 3. dominance checks --------------------------------------------------------

@numba.njit(cache=True)
def _stair_min(li, lf, first, s, bound):
    """Smallest vulnerability among the labels of staircase ``s`` whose turn
    count is at most ``bound`` (``inf`` if none).

    A staircase is a linked list of labels sorted by turns, decreasing, with
    vulnerability strictly increasing: the first entry within the bound is
    the least vulnerable one (EMOA* keeps the same 2-D front in a balanced
    tree; the lists here are short)."""
    a = first[s]
    while a >= 0 and li[a, TURNS] > bound:
        a = li[a, NEXT]
    return lf[a, F_VUL] if a >= 0 else np.inf


@numba.njit(cache=True)
def _stair_insert(li, lf, first, s, x):
    """Insert label ``x`` (not covered by staircase ``s``) into it, dropping
    the entries it makes redundant: as many turns or more and as vulnerable
    or more."""
    t = li[x, TURNS]
    v = lf[x, F_VUL]
    keep = -1                       # the last entry before x that stays
    a = first[s]
    while a >= 0 and li[a, TURNS] > t:
        if lf[a, F_VUL] < v:
            keep = a
        a = li[a, NEXT]
    if a >= 0 and li[a, TURNS] == t:  # x is less vulnerable, or it were covered
        a = li[a, NEXT]
    li[x, NEXT] = a
    if keep < 0:
        first[s] = x
    else:
        li[keep, NEXT] = x


@numba.njit(cache=True)
def _state_covered(li, lf, x, mode, P, Q, gmin, first, cell_size):
    """True if a label already expanded at the state of ``x`` covers ``x``.

    Every expanded label ``a`` at the same cell left the open list before
    ``x`` (or before ``x``'s parent), so ``P(a) <= P(x)``; only the other
    objectives are compared. ``a`` covers ``x`` when each completion of ``x``
    is dominated by, or tolerance-equal to and not smoother than, the same
    completion of ``a``: the next turn after ``a``'s heading may exceed the
    one after ``x``'s by ``_heading_gap``, so ``a``'s turns are charged with it.
    """
    c = li[x, CELL]
    hx = li[x, F_HEAD]
    if mode == MODE_CELL:
        # BOA*: g2_min(cell) decides unless x ties it within the tolerance
        q = _g(li, lf, x, Q, cell_size)
        m = gmin[c]
        if m == np.inf or (q < m and not _eq(q, m)):
            return False
        if m < q and not _eq(m, q):
            return True
        p = _g(li, lf, x, P, cell_size)
        a = first[c]
        while a >= 0 and _le(lf[a, RUNMIN], q):
            ap = _g(li, lf, a, P, cell_size)
            aq = _g(li, lf, a, Q, cell_size)
            if _le(ap, p) and _le(aq, q):
                if not _eq(ap, p) or not _eq(aq, q):
                    return True
                if li[a, TURNS] + _heading_gap(li[a, F_HEAD], hx) <= li[x, TURNS]:
                    return True
            a = li[a, NEXT]
        return False
    if mode == MODE_HEADING:
        # BOA* with Q = turns: g2_min of each heading of the cell, charged
        # with the heading gap (0 for x's own state)
        t = li[x, TURNS]
        for k in range(N_SLOTS):
            m = gmin[c * N_SLOTS + k]
            if m < np.inf and m + _heading_gap(k if k < 8 else -1, hx) <= t:
                return True
        return False
    # three objectives: a 2-D (turns, vulnerability) staircase per state
    t = li[x, TURNS]
    v = lf[x, F_VUL]
    for k in range(N_SLOTS):
        s = c * N_SLOTS + k
        if first[s] < 0:
            continue
        bound = t - _heading_gap(k if k < 8 else -1, hx)
        if bound < 0:
            continue
        m = _stair_min(li, lf, first, s, bound)
        if m < np.inf and _le(m, v):
            return True
    return False


@numba.njit(cache=True)
def _goal_covered(li, lf, x, mode, P, Q, goal_min, goal_first, first, goal_state,
                  cell_size, hs, hd, hv, ht):
    """True if a solution already found covers the f-vector of ``x`` (its
    lower bound at the goal), i.e. every completion of ``x`` is dominated by
    a solution or tolerance-equal to one and not smoother."""
    if mode == MODE_THREE:
        fv = _f(li, lf, x, OBJ_VUL, cell_size, hs, hd, hv, ht)
        ft = li[x, TURNS] + ht[li[x, CELL] * N_SLOTS + _slot(li[x, F_HEAD])]
        m = _stair_min(li, lf, first, goal_state, ft)
        return m < np.inf and _le(m, fv)
    if goal_min == np.inf:
        return False
    fq = _f(li, lf, x, Q, cell_size, hs, hd, hv, ht)
    if fq < goal_min and not _eq(fq, goal_min):
        return False
    if goal_min < fq and not _eq(goal_min, fq):
        return True
    if mode == MODE_HEADING:    # Q is smoothness (integers): goal_min == fq
        return True
    fp = _f(li, lf, x, P, cell_size, hs, hd, hv, ht)
    to_go = ht[li[x, CELL] * N_SLOTS + _slot(li[x, F_HEAD])]
    a = goal_first
    while a >= 0 and _le(lf[a, RUNMIN], fq):
        ap = _g(li, lf, a, P, cell_size)
        aq = _g(li, lf, a, Q, cell_size)
        if _le(ap, fp) and _le(aq, fq):
            if not _eq(ap, fp) or not _eq(aq, fq):
                return True
            if li[a, TURNS] <= li[x, TURNS] + to_go:
                return True
        a = li[a, NEXT]
    return False


# -- the search -------------------------------------------------------------------

@numba.njit(cache=True)
def _free_search(occ, pot, sr, sc, gr, gc, cell_size, corner_cutting, mode, P, Q,
                 hs, hd, hv, ht):
    """Multi-objective label-setting search from start to goal.

    ``mode`` is ``MODE_CELL`` (objectives ``P = length``, ``Q =
    vulnerability``, turns as tie-break, states = cells), ``MODE_HEADING``
    (``P`` = length or vulnerability, ``Q`` = smoothness, states = (cell,
    heading)) or ``MODE_THREE`` (length, vulnerability, smoothness, states =
    (cell, heading)).

    Returns the label tables, the solution labels in the order found, and
    the numbers of labels generated and expanded.
    """
    h, w = occ.shape
    goal = gr * w + gc
    n_states = h * w * (1 if mode == MODE_CELL else N_SLOTS)
    goal_state = n_states                    # MODE_THREE: the goal's staircase
    gmin = np.full(n_states, np.inf)         # BOA*: g2_min of each state
    first = np.full(n_states + 1, -1, np.int64)  # newest label / staircase head
    goal_min = np.inf
    goal_first = -1
    second = OBJ_VUL if mode == MODE_THREE else Q

    li = np.empty((1024, 7), np.int64)
    lf = np.empty((1024, 2))
    sols = np.empty(64, np.int64)
    n_sols = 0
    hk = np.empty((1024, 3))
    hid = np.empty(1024, np.int64)

    # the start label: no step, no heading; the start cell counts for vulnerability
    li[0, CELL] = sr * w + sc
    li[0, F_HEAD] = -1
    li[0, F_PARENT] = -1
    li[0, NS] = 0
    li[0, ND] = 0
    li[0, TURNS] = 0
    li[0, NEXT] = -1
    lf[0, F_VUL] = pot[sr, sc]
    lf[0, RUNMIN] = np.inf
    n = 1
    _heap_push(hk, hid, 0, _f(li, lf, 0, P, cell_size, hs, hd, hv, ht),
               _f(li, lf, 0, second, cell_size, hs, hd, hv, ht),
               _f(li, lf, 0, OBJ_SMOOTH, cell_size, hs, hd, hv, ht), 0)
    size = 1
    n_expanded = 0
    n_generated = 1

    while size > 0:
        # 2. the lexicographically smallest label
        x, size = _heap_pop(hk, hid, size)
        c = li[x, CELL]

        # 3. dominance checks (lazy: the sets changed since x was generated)
        if c != goal and _state_covered(li, lf, x, mode, P, Q, gmin, first, cell_size):
            continue
        if _goal_covered(li, lf, x, mode, P, Q, goal_min, goal_first, first, goal_state,
                         cell_size, hs, hd, hv, ht):
            continue

        # 4a. a solution: record it, never expand it
        if c == goal:
            if mode == MODE_THREE:
                _stair_insert(li, lf, first, goal_state, x)
            else:
                goal_min = min(goal_min, _g(li, lf, x, Q, cell_size))
                lf[x, RUNMIN] = goal_min
                li[x, NEXT] = goal_first
                goal_first = x
            sols = _grow1(sols, n_sols + 1)
            sols[n_sols] = x
            n_sols += 1
            continue

        # 4b. expand x: it joins its state's set
        n_expanded += 1
        s = c if mode == MODE_CELL else c * N_SLOTS + _slot(li[x, F_HEAD])
        if mode == MODE_THREE:
            _stair_insert(li, lf, first, s, x)
        else:
            gmin[s] = min(gmin[s], _g(li, lf, x, Q, cell_size))
            lf[x, RUNMIN] = gmin[s]
            li[x, NEXT] = first[s]
            first[s] = x
        r, col = c // w, c % w
        head = li[x, F_HEAD]
        for d in range(8):
            if not can_step(occ, r, col, DR[d], DC[d], corner_cutting):
                continue
            r2, c2 = r + DR[d], col + DC[d]
            if hv[r2 * w + c2] == np.inf:      # the goal cannot be reached from there
                continue
            li = _grow(li, n + 1)
            lf = _grow(lf, n + 1)
            li[n, CELL] = r2 * w + c2
            li[n, F_HEAD] = d
            li[n, F_PARENT] = x
            li[n, NS] = li[x, NS] + (1 - d % 2)
            li[n, ND] = li[x, ND] + d % 2
            li[n, TURNS] = li[x, TURNS] + (_turn(head, d) if head >= 0 else 0)
            li[n, NEXT] = -1
            lf[n, F_VUL] = lf[x, F_VUL] + pot[r2, c2]
            n_generated += 1
            # 3. eager dominance checks (BOA*: prune before the open list)
            if r2 * w + c2 != goal and _state_covered(li, lf, n, mode, P, Q, gmin, first,
                                                      cell_size):
                continue
            if _goal_covered(li, lf, n, mode, P, Q, goal_min, goal_first, first, goal_state,
                             cell_size, hs, hd, hv, ht):
                continue
            if size == hid.shape[0]:
                hk, hid = _heap_room(hk, hid)
            _heap_push(hk, hid, size, _f(li, lf, n, P, cell_size, hs, hd, hv, ht),
                       _f(li, lf, n, second, cell_size, hs, hd, hv, ht),
                       _f(li, lf, n, OBJ_SMOOTH, cell_size, hs, hd, hv, ht), n)
            size += 1
            n += 1
    return li[:n], lf[:n], sols[:n_sols], n_generated, n_expanded


# -- 5. paths and the final filter ------------------------------------------------

@numba.njit(cache=True)
def _trace(li, sols, w):
    """Cells of the solution paths, concatenated, and their offsets."""
    counts = np.empty(len(sols), np.int64)
    for i in range(len(sols)):
        k = 0
        a = sols[i]
        while a >= 0:
            k += 1
            a = li[a, F_PARENT]
        counts[i] = k
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
            a = li[a, F_PARENT]
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


def _search_plan(names):
    """Internal objectives and mode for the requested ones (see _free_search)."""
    code = {"length": OBJ_LEN, "vulnerability": OBJ_VUL, "smoothness": OBJ_SMOOTH}
    wanted = {code[n] for n in names}
    if len(wanted) == 3:
        return MODE_THREE, OBJ_LEN, OBJ_VUL
    if wanted == {OBJ_LEN, OBJ_VUL}:
        return MODE_CELL, OBJ_LEN, OBJ_VUL
    # one objective x, or (x, smoothness): the (x, smoothness) front, then filtered
    rest = sorted(wanted - {OBJ_SMOOTH})
    return MODE_HEADING, (rest[0] if rest else OBJ_LEN), OBJ_SMOOTH


def free_front(workspace, objectives=("length", "vulnerability")) -> ExactFront:
    """Exact Pareto front of all feasible 8-connected paths.

    A multi-objective label-setting search from the start to the goal over
    the 8-connected grid (SPEC moves: no obstacle cell, and with
    ``workspace.corner_cutting=False`` no diagonal move past a blocked
    orthogonal neighbour). For two objectives it is BOA* [1]_: labels leave
    the open list in lexicographic order of their f-vectors, so a label is
    dominated at its state exactly when its second objective is not below
    the smallest one already expanded there (``g2_min``), an O(1) check. For
    three objectives it is NAMOA*-dr / EMOA* [2]_ [3]_: the same order makes
    the check two-dimensional, done on a (turns, vulnerability) staircase per
    state.

    Parameters
    ----------
    workspace : Workspace
        The map, start, goal, cell size and corner rule.
    objectives : sequence of str or comma-separated str, optional
        Any subset of ``"length"``, ``"vulnerability"``, ``"smoothness"``, in
        the column order wanted for ``F`` (default length, vulnerability).

    Returns
    -------
    ExactFront
        One path per tolerance-equal Pareto-optimal objective vector, sorted
        lexicographically; among tolerance-equal paths the smoothest one (also
        when smoothness is not an objective). ``profiles`` is None (free paths
        have no column profile). The paths are simple (no repeated cell).

    Raises
    ------
    ConfigError
        If an objective is unknown, repeated or ``"interfering"``.
    NoPathError
        If no feasible path joins the start and the goal.

    See Also
    --------
    monotone_front : the same front over the column-monotone paths only.

    Notes
    -----
    States and objectives
        For (length, vulnerability) a state is a cell; each label also
        carries the heading of its last step and its total turn, used only to
        keep the smoothest path among tolerance-equal ones: a label ``a``
        discards a tolerance-equal label ``b`` at the same cell only if
        ``turns(a) + gap <= turns(b)``, ``gap`` being the most by which the next
        turn after ``a``'s heading can exceed the one after ``b``'s. When
        smoothness is an objective the state is (cell, incoming heading), and
        labels of the other headings of the cell are compared with the same
        charge. A single objective ``x`` is solved as the (x, smoothness)
        front followed by the tolerance filter on ``x``.

    Heuristics
        Exact single-objective costs-to-go from backward Dijkstra searches
        from the goal, obstacles and corner rule included, hence admissible
        and consistent: the shortest length (kept as integer step counts so
        that equal f-values are bit-identical), the cheapest potential sum of
        the cells after the current one up to the goal included (the
        label's vulnerability already counts its own cell, the start
        included), and the least total turn from the current cell and
        heading.

    Simple paths
        Potentials are non-negative, and removing a loop from a path never
        increases its vulnerability, length or total turn (a closed polygon
        turns by at least 2 pi, Fenchel), so the label that first reached a
        cell covers any later label closing a loop there: returned paths are
        simple.

    Tolerance
        Dominance is SPEC's tolerance dominance (see the module docstring).
        It is not transitive; the solutions are filtered once more with it,
        so the front is mutually non-dominated and has one point per
        tolerance-equal vector. On maps where many values differ by about
        the tolerance (vulnerabilities far from every obstacle), the kept
        representatives, hence the count, may differ from those of another
        exact method; compare fronts by hypervolume and coverage (SPEC).

    Objective values are computed as in :mod:`gapath.objectives` (step
    counts, eighth turns, vulnerability summed from the start in path order),
    so ``F`` equals :func:`gapath.objectives.evaluate_path` on the returned
    paths bit for bit.

    References
    ----------
    .. [1] C. Hernandez, W. Yeoh, J. A. Baier, H. Zhang, L. Suazo, S. Koenig,
       A. Felner. "Simple and efficient bi-objective search algorithms via
       fast dominance checks". Artificial Intelligence 314, 2023 (BOA*,
       SoCS 2020).
    .. [2] F.-J. Pulido, L. Mandow, J.-L. Perez de la Cruz. "Dimensionality
       reduction in multiobjective shortest path search". Computers &
       Operations Research 64, 2015 (NAMOA*-dr).
    .. [3] Z. Ren, R. Zhan, S. Rathinam, M. Likhachev, H. Choset. "Enhanced
       multi-objective A* using balanced binary search trees". SoCS 2022
       (EMOA*).

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> occ = np.zeros((3, 3), bool); occ[1, 1] = True
    >>> front = free_front(Workspace(occ, start=(1, 0), goal=(1, 2)),
    ...                    ("length", "smoothness"))
    >>> front.F.round(4).tolist()
    [[2.8284, 1.5708]]
    >>> front.paths[0].tolist()
    [[1, 0], [0, 1], [1, 2]]
    """
    names = _check_objectives(objectives)
    occ = workspace.occ
    pot = np.ascontiguousarray(workspace.potential, dtype=np.float64)
    (sr, sc), (gr, gc) = workspace.start, workspace.goal
    h, w = workspace.shape
    cs = float(workspace.cell_size)
    cc = bool(workspace.corner_cutting)
    hs, hd, hv, ht = _free_heuristics(occ, pot, gr, gc, cc)
    if hv[sr * w + sc] == np.inf:
        raise NoPathError(
            f"no feasible path from {workspace.start} to {workspace.goal} in workspace "
            f"{workspace.name!r} ({h}x{w}, {workspace.n_obstacles} obstacles, "
            f"corner_cutting={workspace.corner_cutting})")
    mode, P, Q = _search_plan(names)
    li, lf, sols, _, _ = _free_search(occ, pot, sr, sc, gr, gc, cs, cc, mode, P, Q,
                                      hs, hd, hv, ht)

    values = {
        "length": (li[sols, NS] + SQRT2 * li[sols, ND]) * cs,
        "vulnerability": lf[sols, F_VUL],
        "smoothness": li[sols, TURNS] * QUARTER_PI,
    }
    F = np.column_stack([values[name] for name in names])
    # among tolerance-equal vectors prefer the smoothest path, then the shortest
    order = np.lexsort((li[sols, NS] + SQRT2 * li[sols, ND], li[sols, TURNS]))
    keep = _tolerant_front(np.ascontiguousarray(F), order)
    keep = keep[np.lexsort(F[keep].T[::-1])]
    cells, offsets = _trace(li, sols[keep], w)
    paths = [cells[offsets[i]:offsets[i + 1]] for i in range(len(keep))]
    return ExactFront(objectives=names, F=F[keep], paths=paths, profiles=None,
                      smoothness=values["smoothness"][keep])
