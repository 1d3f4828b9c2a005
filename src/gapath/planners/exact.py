"""Exact Pareto fronts (SPEC "Reference (exact) fronts").

Monotone reference front
    :func:`monotone_front` computes the exact Pareto set of the FEASIBLE
    column-monotone paths, the paths the GA's integer encoding can describe,
    by a multi-objective dynamic programme over the columns of the canonical
    frame (:class:`gapath.encodings.base.Frame`).

Free reference front
    The exact Pareto set of all feasible 8-connected paths (label-setting
    search, BOA*/NAMOA* style) will be ``free_front``; see the section at the
    end of this module. It is not implemented yet.

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

__all__ = ["ExactFront", "monotone_front", "EXACT_OBJECTIVES"]

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
    profiles : tuple (entries, exits) of (k, n_cols) int arrays
        Column profiles of the paths in frame coordinates (see
        :mod:`gapath.encodings.base`).
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

        Examples
        --------
        >>> import numpy as np
        >>> from gapath import Workspace
        >>> d = monotone_front(Workspace(np.zeros((2, 3), bool))).to_dict()
        >>> sorted(d)
        ['F', 'entries', 'exits', 'objectives', 'paths', 'smoothness']
        """
        entries, exits = self.profiles
        return {
            "objectives": list(self.objectives),
            "F": self.F.tolist(),
            "smoothness": self.smoothness.tolist(),
            "paths": [p.tolist() for p in self.paths],
            "entries": entries.tolist(),
            "exits": exits.tolist(),
        }


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
# free reference front (all feasible 8-connected paths) -- not implemented yet
# ---------------------------------------------------------------------------
# ``free_front(workspace, objectives=("length", "vulnerability")) -> ExactFront``
# will be a multi-objective label-setting search (BOA* for two objectives,
# NAMOA* otherwise) over all 8-connected paths, with the same tolerance,
# tie-breaking, bit-exact objective arithmetic and ExactFront result (its
# ``profiles`` will be None: free paths have no column profile).
