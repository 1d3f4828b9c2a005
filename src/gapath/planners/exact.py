"""Exact Pareto fronts (SPEC "Reference (exact) fronts").

Monotone reference front
    :func:`monotone_front` computes the exact Pareto set of the FEASIBLE
    column-monotone paths, the paths the GA's integer encoding can describe,
    by a multi-objective dynamic programme over the columns of the canonical
    frame (:class:`gapath.monotone.Frame`).

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
    or :func:`gapath.objectives.evaluate_profiles` give for the returned paths
    (when :func:`free_front` picks the smoothest of tied paths after its
    search, the values are summed again along the path it returns).
"""

from __future__ import annotations

import math
import signal
import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from gapath.errors import ConfigError, LabelBudgetError, NoPathError, non_negative
from gapath.grid import SQRT2
from gapath.monotone import Frame, expand_profiles, split_paths
from gapath.objectives import OBJECTIVES, QUARTER_PI, objective_index
from gapath.planners._apex_kernels import _apex_run
from gapath.planners._boa_kernels import (
    C_EDGES,
    C_EXPANDED,
    C_FREE,
    C_GENERATED,
    C_PEAK,
    C_ROWS,
    C_SOLS,
    _boa_bytes,
    _boa_finish,
    _boa_prepare,
    _boa_run,
    _boa_solve,
)
from gapath.planners._exact_heuristics import _free_prepare
from gapath.planners._exact_kernels import (
    DONE,
    F_VUL,
    MODE_CELL,
    MODE_HEADING,
    MODE_THREE,
    ND,
    NS,
    OBJ_LEN,
    OBJ_SMOOTH,
    OBJ_VUL,
    OVER_BUDGET,
    PAUSED,
    S_EXPANDED,
    S_GENERATED,
    S_N,
    S_N_FREE,
    S_PC,
    S_POPS,
    S_SEARCHES,
    S_SIZE,
    S_SOLS,
    SP_USED,
    TURNS,
    _free_run,
    _stair_pool,
    _tolerant_front,
    _trace,
    _trace_parents,
)
from gapath.planners._monotone_kernels import (
    B_LEN,
    B_VUL,
    M_EIGHTHS,
    M_LINK,
    P_BOTH,
    P_DEAD,
    P_LEN,
    P_VUL,
    ST_CANDIDATES,
    ST_HELD,
    ST_K,
    ST_MADE,
    ST_PEAK,
    ST_PEAK_BYTES,
    ST_PRUNED,
    T_PARENT,
    T_ROW,
    _monotone_bounds,
    _monotone_init,
    _monotone_steps,
    _monotone_tradeoffs,
)
from gapath.planners._monotone_kernels import LENGTH as M_LENGTH
from gapath.planners._monotone_kernels import VUL as M_VUL
from gapath.planners._multi import path_objectives

if TYPE_CHECKING:
    from gapath.front import PathFront
    from gapath.workspace import Workspace

__all__ = [
    "ExactFront",
    "monotone_front",
    "free_front",
    "exact_front",
    "exact_path_front",
    "EXACT_MODES",
    "EXACT_OBJECTIVES",
    "path_objectives",
]

#: Objectives the exact planners can minimise (``interfering`` is a constraint:
#: every returned path has ``interfering == 0``).
EXACT_OBJECTIVES = ("length", "vulnerability", "smoothness")

#: Relative tolerance of SPEC "Duplicates and ties".
TOL = 1e-9

#: Largest label budget: label rows are indexed by 32-bit integers.
MAX_LABELS = 2**31 - 1024

#: The monotone DP drops the labels that its goal bounds show cannot reach
#: the front (False: every label is filtered, as the DP did before; tests).
_MONOTONE_GOAL_BOUND = True

#: Weights of length (scaled by the shortest monotone path's) against
#: vulnerability (scaled likewise) of the completions whose paths, through
#: every label, are known points below which the goal bound cuts.
_TRADEOFF_WEIGHTS = np.array([0.05, 0.15, 0.3, 0.5, 0.7, 0.85, 0.95])

#: Seconds of work between two returns of a resumable kernel (progress,
#: Ctrl-C and the budget are handled between kernel calls).
_SLICE_S = 0.1


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
        :mod:`gapath.monotone`); None for :func:`free_front` (free
        paths have no column profile).
    smoothness : (k,) float array
        Total turn of each path (radians), also when smoothness is not an
        objective.
    stats : dict
        How the search went: ``seconds``, ``labels`` (the free search: its
        label rows at their peak, plus, with smoothness an objective and in
        the k-objective search, one parent entry per expanded label; the
        rows of dropped labels, and there of expanded ones, are recycled),
        ``peak_bytes`` (the largest memory its arrays held), and
        ``expansions``/``generated`` (free search) or ``columns`` (monotone
        DP). Not part of :meth:`to_dict`.
    """

    objectives: tuple
    F: np.ndarray
    paths: list
    profiles: tuple | None
    smoothness: np.ndarray
    stats: dict = field(default_factory=dict)

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
# monotone reference front
# ---------------------------------------------------------------------------


def _check_objectives(objectives) -> tuple[str, ...]:
    names = tuple(OBJECTIVES[i] for i in objective_index(objectives))
    bad = [n for n in names if n not in EXACT_OBJECTIVES]
    if bad:
        raise ConfigError(
            f"objective {bad[0]!r} cannot be minimised by the exact planner (it is a "
            f"constraint: every returned path has interfering == 0); "
            f"choose among {', '.join(EXACT_OBJECTIVES)}"
        )
    return names


def _budget(max_labels) -> int:
    """The label budget as an int (``None``: the largest one)."""
    if max_labels is None:
        return MAX_LABELS
    if (
        isinstance(max_labels, bool)
        or not isinstance(max_labels, (int, np.integer))
        or not 1 <= max_labels <= MAX_LABELS
    ):
        raise ConfigError(
            f"max_labels (--max-labels) must be an integer between 1 and {MAX_LABELS:,}, got {max_labels!r}"
        )
    return int(max_labels)


def _expansion_limit(max_expansions) -> float:
    """``max_expansions`` checked: a number >= 0, or None (no limit: inf)."""
    if max_expansions is None:
        return math.inf
    return non_negative(max_expansions, "max_expansions", finite=False, what=" (expansions)")


class _DeferredInterrupt:
    """Hold Ctrl-C while a kernel runs and raise it between kernel calls.

    A SIGINT arriving during a numba call would otherwise surface inside the
    kernel's return-value boxing (which runs a little Python) as a
    SystemError; here it only sets a flag, and :meth:`check` (called after
    each kernel) hands it to the previous handler, normally
    ``KeyboardInterrupt``. Only in the main thread (elsewhere signals are not
    delivered to Python).

    With ``lazy=True`` the handler is installed only by :meth:`arm` (the
    caller arms it once a computation takes more than one kernel call:
    installing and restoring a handler costs several microseconds, more
    than a whole search on a small map). Before that, a SIGINT takes
    Python's normal course, and the SystemError it causes inside numba's
    boxing is replaced, on leaving the block, by the exception the handler
    raised (normally ``KeyboardInterrupt``)."""

    def __init__(self, lazy: bool = False):
        self.lazy = lazy

    def __enter__(self):
        self.hit = None
        self.installed = False
        self.prev = None
        if not self.lazy:
            self.arm()
        return self

    def arm(self):
        """Install the holding handler (once; only in the main thread)."""
        if self.installed or threading.current_thread() is not threading.main_thread():
            return
        try:
            self.prev = signal.signal(signal.SIGINT, self._handler)
            self.installed = True
        except (ValueError, OSError):
            pass

    def _handler(self, signum, frame):
        self.hit = (signum, frame)

    def check(self):
        if self.hit is None:
            return
        signum, frame = self.hit
        self.hit = None
        if callable(self.prev):
            self.prev(signum, frame)
        elif self.prev != signal.SIG_IGN:
            raise KeyboardInterrupt

    def __exit__(self, exc_type, exc, tb):
        if self.installed:
            signal.signal(signal.SIGINT, self.prev if self.prev is not None else signal.default_int_handler)
        if exc_type is None:
            self.check()
        elif exc_type is SystemError and exc.__cause__ is not None:
            # a signal handler raised inside numba's boxing of a kernel's result (the
            # SystemError "returned a result with an exception set", possibly nested)
            cause = exc.__cause__
            while isinstance(cause, SystemError) and cause.__cause__ is not None:
                cause = cause.__cause__
            raise cause.with_traceback(None) from None
        return False


#: Pops per kernel call of a search with ``max_expansions`` (fixed, so that where
#: it stops does not depend on the machine's speed).
CHECK_POPS = 1 << 14


class _Slices:
    """Work per kernel call, adapted so that each call takes about
    ``_SLICE_S`` seconds (see :func:`_slices` for a search with a
    ``max_expansions``)."""

    #: the search's ``max_expansions`` (:func:`_expansion_limit`)
    limit = math.inf

    def __init__(self, first: int, lo: int, hi: int):
        self.n, self.lo, self.hi = first, lo, hi

    def update(self, done: int, seconds: float) -> None:
        if done < self.n:  # the kernel stopped early: nothing to learn
            return
        scale = _SLICE_S / max(seconds, 1e-4)
        self.n = int(min(self.hi, max(self.lo, self.n * min(4.0, max(0.25, scale)))))


def _slices(first: int, lo: int, hi: int, limit: float) -> _Slices:
    """The :class:`_Slices` of a search; with a finite ``limit`` (its
    ``max_expansions``) fixed at :data:`CHECK_POPS` pops per call."""
    slices = _Slices(first, lo, hi)
    if limit < math.inf:
        slices.n = slices.lo = slices.hi = CHECK_POPS
        slices.limit = limit
    return slices


def monotone_front(
    workspace, objectives=("length", "vulnerability"), *, max_labels=None, progress=None
) -> ExactFront:
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
        part of columns), see :class:`gapath.monotone.Frame`.
    objectives : sequence of str or comma-separated str, optional
        Any subset of ``"length"``, ``"vulnerability"``, ``"smoothness"``, in
        the column order wanted for ``F`` (default length, vulnerability).
    max_labels : int, optional
        Label budget: the most labels held at once (the ancestry tree of the
        current column's labels, plus the labels and vertical-run sets of
        the column being built). None: no budget.
    progress : callable, optional
        Called about ten times a second, and once at the end, with a dict
        ``phase="monotone"``, ``columns``, ``n_cols``, ``labels`` (held
        now), ``labels_peak``, ``labels_made``, ``candidates``,
        ``peak_bytes``, ``seconds``. An exception it raises (e.g.
        KeyboardInterrupt) ends the computation and propagates.

    Returns
    -------
    ExactFront
        One path per tolerance-equal Pareto-optimal objective vector, sorted
        lexicographically. Among tolerance-equal paths the smoothest one is
        preferred. ``stats`` has ``columns``, ``labels`` (held at the end:
        the ancestry of the front's paths), ``labels_peak`` (the most held
        at once), ``labels_made`` (labels of all columns together),
        ``candidates`` (labels filtered), ``peak_bytes``, ``seconds``.

    Raises
    ------
    ConfigError
        If an objective is unknown, repeated or ``"interfering"``, or
        ``max_labels`` is not a positive integer.
    NoPathError
        If no feasible column-monotone path exists.
    LabelBudgetError
        If the DP would hold more than ``max_labels`` labels; its message
        says how many columns were done.
    KeyboardInterrupt
        On Ctrl-C, within about a tenth of a second of work.

    Notes
    -----
    The heading of the last step matters for the next turn; rather than
    splitting states by heading, a label with heading ``h_a`` may discard a
    label with heading ``h_b`` at the same row only after its turn count is
    charged with the turn between ``h_a`` and ``h_b`` (the most the next turn
    can differ by). This is exact for smoothness and keeps one state per row.

    The vertical runs are built row by row (the non-dominated partial paths
    going up, or down, at each row of the new column), so a label is not
    extended to every row its run can reach; only the current column's
    labels are held in full, and an ancestry tree (exit row and parent per
    label) whose dead branches are freed as the DP advances gives the
    paths back. Memory is therefore about a column of labels plus the
    ancestry of the live ones.

    For (length, vulnerability) and single objectives other than
    smoothness, a goal bound drops the labels that cannot reach the front:
    backward single-objective DPs give lower bounds of every completion and
    a few actual completions, the paths through the labels along those
    completions are known points, and a label whose objectives plus the
    bounds are dominated by a known point (by a relative margin far above
    the tolerance) is dropped. The front is the same as without it.

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
    primary = {"length": M_LENGTH, "vulnerability": M_VUL, "smoothness": 2}[names[0]]
    budget = _budget(max_labels)
    t0 = time.perf_counter()
    occ, pot = frame.occ, np.ascontiguousarray(frame.potential, dtype=np.float64)
    cs, cc = float(workspace.cell_size), bool(workspace.corner_cutting)
    use = ("length" in names, "vulnerability" in names, "smoothness" in names)
    with _DeferredInterrupt() as interrupt:
        tree, ci, cf, off, st = _monotone_init(occ, pot, sr, frame.col0, cs)
        if _MONOTONE_GOAL_BOUND:
            bounds = _monotone_bounds(occ, pot, gr, frame.col0, frame.n_cols, cs, cc)
            pmode = P_DEAD if use[2] else (P_BOTH if use[0] and use[1] else (P_LEN if use[0] else P_VUL))
        else:  # no label is dropped before the filters (the tests' reference)
            bounds, pmode = np.zeros((12, frame.n_cols, occ.shape[0])), P_DEAD
        comps = np.empty((0, 1, 1))
        if pmode == P_BOTH:
            # completions trading length for vulnerability: more known paths
            # for the goal bound from the first columns on
            best_len, best_vul = bounds[B_LEN, 0].min(), bounds[B_VUL, 0].min()
            if np.isfinite(best_len):  # else there is no monotone path at all
                comps = _monotone_tradeoffs(
                    occ,
                    pot,
                    gr,
                    frame.col0,
                    frame.n_cols,
                    cs,
                    cc,
                    _TRADEOFF_WEIGHTS,
                    max(best_len, 1e-9),
                    max(best_vul, 1e-9),
                )
        stair = np.empty((2, 64))
        slices = _Slices(4, 1, 1 << 20)
        while True:
            k0, t1 = st[ST_K], time.perf_counter()
            tree, ci, cf, off, stair, status = _monotone_steps(
                occ,
                pot,
                gr,
                frame.col0,
                frame.n_cols,
                cs,
                cc,
                *use,
                primary,
                tree,
                ci,
                cf,
                off,
                st,
                slices.n,
                budget,
                bounds,
                pmode,
                stair,
                comps,
            )
            interrupt.check()
            now = time.perf_counter()
            slices.update(st[ST_K] - k0, now - t1)
            stats = {
                "columns": int(st[ST_K]),
                "n_cols": int(frame.n_cols),
                "labels": int(st[ST_HELD]),
                "labels_peak": int(st[ST_PEAK]),
                "labels_made": int(st[ST_MADE]),
                "candidates": int(st[ST_CANDIDATES]),
                "pruned": int(st[ST_PRUNED]),
                "peak_bytes": int(st[ST_PEAK_BYTES] + bounds.nbytes + stair.nbytes + comps.nbytes),
                "seconds": now - t0,
            }
            if status == OVER_BUDGET:
                raise LabelBudgetError(
                    f"monotone DP stopped at the label budget max_labels={budget:,} "
                    f"(--max-labels): {stats['labels']:,} labels held after {stats['columns']} of "
                    f"{stats['n_cols']} columns and more needed for the next one "
                    f"({stats['seconds']:.1f} s); no front (a partial "
                    f"DP is not a Pareto front). Raise the budget, or use a smaller map or fewer "
                    f"objectives",
                    {**stats, "max_labels": budget},
                )
            if progress is not None:
                progress({"phase": "monotone", **stats})
            if status == DONE:
                break
    lo, hi = off[gr], off[gr + 1]
    if hi == lo:
        h, w = workspace.shape
        raise NoPathError(
            f"no feasible column-monotone path from {workspace.start} to {workspace.goal} "
            f"in workspace {workspace.name!r} ({h}x{w}, {workspace.n_obstacles} obstacles, "
            f"corner_cutting={workspace.corner_cutting})"
        )

    # ancestry tree -> exit row of every column
    final = np.arange(lo, hi)
    exits = np.empty((len(final), frame.n_cols), np.int64)
    node = ci[final, M_LINK]
    for k in range(frame.n_cols - 1, -1, -1):
        exits[:, k] = tree[node, T_ROW]
        node = tree[node, T_PARENT]
    entries = np.empty_like(exits)
    entries[:, 0] = sr
    entries[:, 1:] = exits[:, :-1] + np.sign(exits[:, 1:] - exits[:, :-1])

    values = {
        "length": cf[final, M_LENGTH],
        "vulnerability": cf[final, M_VUL],
        "smoothness": ci[final, M_EIGHTHS] * QUARTER_PI,
    }
    F = np.column_stack([values[name] for name in names])
    order = np.lexsort(F.T[::-1])
    F, entries, exits = F[order], entries[order], exits[order]
    cells, n_cells = expand_profiles(frame, entries, exits)
    stats["seconds"] = time.perf_counter() - t0
    return ExactFront(
        objectives=names,
        F=F,
        paths=split_paths(cells, n_cells),
        profiles=(entries, exits),
        smoothness=values["smoothness"][order],
        stats=stats,
    )


# ---------------------------------------------------------------------------
# free reference front (all feasible 8-connected paths)


def _spec_objectives(objectives) -> bool:
    """True if ``objectives`` names only SPEC metrics (the specialised
    searches; errors are theirs to raise)."""
    if isinstance(objectives, str):
        objectives = [o.strip() for o in objectives.split(",") if o.strip()]
    return all(isinstance(n, str) and n in OBJECTIVES for n in objectives)


def _search_plan(names):
    """Internal objectives and mode for the requested ones (see _free_run)."""
    code = {"length": OBJ_LEN, "vulnerability": OBJ_VUL, "smoothness": OBJ_SMOOTH}
    wanted = {code[n] for n in names}
    if len(wanted) == 3:
        return MODE_THREE, OBJ_LEN, OBJ_VUL
    if wanted == {OBJ_LEN, OBJ_VUL}:
        return MODE_CELL, OBJ_LEN, OBJ_VUL
    # one objective x, or (x, smoothness): the (x, smoothness) front, then filtered
    rest = sorted(wanted - {OBJ_SMOOTH})
    return MODE_HEADING, (rest[0] if rest else OBJ_LEN), OBJ_SMOOTH


_PLANS: dict = {}


def _free_plan(objectives):
    """``(names, mode, P, Q)`` of an objectives argument (checked; memoised
    for hashable arguments: the checks cost microseconds, a small search
    not many more)."""
    try:
        return _PLANS[objectives]
    except (KeyError, TypeError):
        pass
    names = _check_objectives(objectives)
    plan = (names, *_search_plan(names))
    if len(_PLANS) < 64:
        try:
            _PLANS[objectives] = plan
        except TypeError:  # a list
            pass
    return plan


def _epsilon(epsilon, mode) -> float:
    """The checked ``epsilon`` of :func:`free_front` (a float >= 0; non-zero
    only for MODE_THREE)."""
    eps = non_negative(epsilon, "epsilon")
    if eps and mode != MODE_THREE:
        raise ConfigError(
            f"epsilon={eps:g} (the approximate search) needs the objectives length, "
            "vulnerability and smoothness; use epsilon=0 for the exact front of these"
        )
    return eps


def free_front(
    workspace,
    objectives=("length", "vulnerability"),
    *,
    costmap=None,
    max_labels=None,
    progress=None,
    tie_break="smoothest",
    search="auto",
    epsilon=0.0,
    max_expansions=None,
) -> ExactFront:
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
    state. Any other set of objectives (four or more, or costmap layers) is
    solved by a k-objective NAMOA*-dr search (see Notes, "k objectives").

    Parameters
    ----------
    workspace : Workspace
        The map, start, goal, cell size and corner rule.
    objectives : sequence of str or comma-separated str, optional
        Any subset of ``"length"``, ``"vulnerability"``, ``"smoothness"``, in
        the column order wanted for ``F`` (default length, vulnerability);
        with a ``costmap`` also ``"solar"`` and the summed cell layers
        ``"<layer>_sum"`` (``"elevation_sum"``, ``"risk_sum"``, a user
        layer's name + ``"_sum"``). The costmap's mean objectives
        (``"elevation"``, ``"risk"``, a user layer's name: the GA's) are
        refused: a mean is not additive along a path and has no exact
        label-setting front; the exact front is over the sums.
    costmap : Costmap, optional
        The layers of ``"solar"`` and ``"<layer>_sum"`` objectives (its
        ``solar_rate`` and ``solar_angle0``); same grid as ``workspace``.
    max_labels : int, optional
        Label budget: the most labels held at once (the rows of dropped
        labels are recycled, so this bounds the memory of the search: with
        smoothness an objective, 8 bytes per expanded label and about 72
        per open one, its row and open-list entry; for length and
        vulnerability about 36 bytes a label plus 24 per open-list entry;
        in the k-objective search, 8 bytes per expanded label, plus its
        state's set member (8 (3k - 2) + 12 bytes until a later label
        drops it), and about 36 + 16 k per open one). None: no budget.
    progress : callable, optional
        Called about ten times a second, and once at the end, with a dict
        ``phase="free"``, ``expansions``, ``generated``, ``labels``, ``open``
        (open-list size), ``solutions`` (found so far; not yet a front),
        ``seconds``. An exception it raises (e.g. KeyboardInterrupt) ends
        the search and propagates.
    tie_break : {"smoothest", "none"}, optional
        Which path represents tolerance-equal objective vectors when
        smoothness is not an objective: the smoothest, then the least
        vulnerable (default), or the first found ("none": BOA* as published;
        the same ``F`` up to the tolerance, a little faster on maps with many
        exact ties, and ``smoothness`` is that of the returned path). Ignored
        when smoothness is an objective: with smoothness and one other
        objective (or alone), the returned path of each point is the one
        best in the third objective among the paths with that vector (the
        least vulnerable for (length, smoothness) and smoothness alone, the
        shortest for (vulnerability, smoothness)), so that each is a point
        of the three-objective front. This holds for vectors the search
        compares as equal along the whole path: SPEC's tolerance is not
        transitive, and a path whose vulnerability is within it of the
        returned one's at the goal but not at some cell before it may be
        shorter.
    search : {"auto", "k"}, optional
        ``"auto"`` (default): the specialised searches above for at most
        three of length, vulnerability, smoothness, the k-objective search
        otherwise; ``"k"``: the k-objective search always (the same front,
        for comparison).
    epsilon : float, optional
        0 (default): the exact front. With the three objectives length,
        vulnerability and smoothness (any column order), ``epsilon > 0``
        makes the search approximate and faster, within a guaranteed
        factor: every point of the exact front is covered by a returned path
        with at most ``1 + epsilon`` times its length and its vulnerability
        and no more turns (see Notes, "Approximate fronts").
    max_expansions : float, optional
        A work budget: the search ends at the first check past this many
        expansions (checks every :data:`CHECK_POPS` open-list pops, so it
        stops at the same place on any machine) and returns the solutions
        found so far, with ``stats["complete"]`` False. Labels leave the
        open list in lexicographic order of their f-vectors, so each such
        solution is a point of the exact front (up to SPEC's tolerance,
        which the final filter can only apply among the points found), and
        they are the front's points with the least values of the search's
        first key: length when it is an objective; else vulnerability, when
        it is one and there are no costmap objectives; else the first
        objective given. A part of the front, never a front to compare with
        (with ``epsilon > 0``, a part of the approximate front). None
        (default): no budget.

    Returns
    -------
    ExactFront
        One path per tolerance-equal Pareto-optimal objective vector, sorted
        lexicographically; among tolerance-equal paths the smoothest one (also
        when smoothness is not an objective). ``profiles`` is None (free paths
        have no column profile). The paths are simple (no repeated cell).
        ``stats`` has ``expansions``, ``generated``, ``labels``,
        ``peak_bytes``, ``heuristic_seconds``, ``seconds`` (and
        ``tie_edges``, the ties recorded, with the default tie-break on
        length and vulnerability; with length, vulnerability and smoothness,
        ``stair_searches``, the staircase searches that the per-cell
        summaries left open (exact search only), and ``stair_floats``, the size of the
        staircase pool); ``complete``, False when ``max_expansions`` ended the
        search.

    Raises
    ------
    ConfigError
        If an objective is unknown, repeated or ``"interfering"``, a layer
        objective comes without a costmap or is a mean (``"elevation"``: use
        ``"elevation_sum"``), the costmap's grid differs, ``max_labels`` is
        not a positive integer, ``max_expansions`` not a number >= 0,
        ``tie_break`` or ``search`` unknown,
        ``epsilon`` negative or not finite, or non-zero with other
        objectives than length, vulnerability and smoothness, or (with
        ``"solar"`` at a non-zero ``solar_rate``) a label would take more
        than twice as many steps as the grid has cells.
    NoPathError
        If no feasible path joins the start and the goal.
    LabelBudgetError
        If the search would hold more than ``max_labels`` labels; its message
        says how far it got.
    KeyboardInterrupt
        On Ctrl-C, within about a tenth of a second of search (the backward
        heuristics, a few Dijkstra passes, are not interrupted).

    See Also
    --------
    monotone_front : the same front over the column-monotone paths only.

    Notes
    -----
    States and objectives
        For (length, vulnerability) a state is a cell, and the search is
        BOA* itself: a label tied with the one already expanded at its cell
        is dropped. The smoothest path among tolerance-equal ones is found
        after the search: each label dropped because it ties, in both
        objectives, the label last expanded at its cell (or the last
        solution) is recorded as an alternative in-edge (parent, step) of
        that label, and the goal test keeps the labels whose f-vector ties
        the last solution (a tied path may leave the first one early). The
        expanded labels and these edges hold every path of every front
        vector (a prefix of a Pareto-optimal path is Pareto-optimal at its
        cell); a dynamic programme over them, on (label, incoming heading),
        gives the smoothest path of each solution, and among equally smooth
        ones the least vulnerable. Its objectives are recomputed along it.
        When smoothness is an objective the state is (cell, incoming
        heading), and labels of the other headings of the cell are compared
        with their turn counts charged by the most the next turn can differ.
        A single objective ``x`` is solved as the (x, smoothness) front
        followed by the tolerance filter on ``x``.

    Tie-breaking cost
        The tied labels are not expanded: the tie-break costs one 12-byte
        edge per dropped tie, the labels whose f-vector ties a solution and
        a pass over the edges after the search (on MovingAI's Berlin_1_256,
        where 36 % of the cells have potential exactly 0: 2-57 % more
        expansions than ``tie_break="none"`` and 5-18 % more time; the
        former search, which kept tied labels that differed in heading or
        turns, expanded up to 5x more).

    Heuristics
        Exact single-objective costs-to-go from backward Dijkstra searches
        from the goal, obstacles and corner rule included, hence admissible
        and consistent: the shortest length (kept as integer step counts so
        that equal f-values are bit-identical), the cheapest potential sum of
        the cells after the current one up to the goal included (the
        label's vulnerability already counts its own cell, the start
        included), and the least total turn from the current cell and
        heading (only when smoothness is an objective: for (length,
        vulnerability) turns only break ties, and 0 is used).

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

    k objectives
        Labels leave the open list in lexicographic order of their whole
        f-vector (the length first when it is an objective); each cell keeps
        its expanded labels that no later one made redundant on the
        objectives other than the first (NAMOA*-dr), the goal its solutions;
        a label is checked against both when generated and when popped.
        Heuristics: one backward Dijkstra pass per objective (length and
        turns as above, each summed layer like the vulnerability, solar at
        rate 0 over the per-direction step costs). Smoothness does not split
        states (headings are charged as above); among tolerance-equal
        vectors the smoothest path is kept (``tie_break``).

    Solar
        A step's solar cost depends on its index along the path when
        ``solar_rate != 0``, so two labels at a cell with different step
        counts face different future costs and neither may discard the
        other: the state is then (step count, cell), which is exact. The
        paths are then walks (a detour may shift later steps to cheaper
        indices, so a Pareto-optimal path may revisit a cell) and the
        search is larger; the heuristic is a backward pass over the step
        index, the least solar cost of a walk from the cell to the goal
        starting at that index (admissible; every label of a state shares
        it), for the first ``2**24 / cells`` indices, and beyond them the
        sum of the cheapest step cost of each index over the fewest steps
        to the goal. With ``solar_rate == 0`` the cost depends on the
        direction only, states are cells and paths are simple.

    Approximate fronts
        ``epsilon > 0`` runs an apex-path search in the manner of A*pex
        (Zhang et al. 2022) on the exact search's states: each open label
        also carries an apex, lower bounds on the length and vulnerability
        of the labels it stands for; a new label is merged into an open
        label of its cell (or replaces it) when one of the two turns at most
        as much and is within ``1 + epsilon`` of both apexes' smaller length
        and vulnerability, and the dominance checks compare apexes. The
        factor therefore never adds up along a path: for every point ``p``
        of the exact front some returned path has length ``<= (1 +
        epsilon) p_length``, vulnerability ``<= (1 + epsilon) p_vul`` and
        turns ``<= p_turns`` (tested against the exact front). Every
        returned path is feasible and simple, its objectives are its own,
        and none dominates a point of the exact front. The front is much
        smaller than the exact one and holds the inside of the front
        better than its edges; the free-path archive
        (:class:`gapath.operators.archive.FreePathArchive`) runs it beside
        its exact two-objective faces. Measured time and hypervolume ratios
        are in ``docs/results/free_paths.md`` ("Apex search").

    Objective values are computed as in :mod:`gapath.objectives` (step
    counts, eighth turns, vulnerability summed from the start in path order),
    so ``F`` equals :func:`gapath.objectives.evaluate_path` on the returned
    paths bit for bit; layer sums and solar equal
    :func:`path_objectives` (cells and steps summed in path order; the
    solar costs of :meth:`gapath.costmap.Costmap.solar_table`) bit for bit,
    and ``Costmap.evaluate_path`` (the mean times the number of cells; the
    solar sum) up to the summation order.

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
    if search not in ("auto", "k"):
        raise ConfigError(f"search must be 'auto' or 'k', got {search!r}")
    limit = _expansion_limit(max_expansions)
    if search == "k" or not _spec_objectives(objectives):
        if epsilon != 0:
            _epsilon(epsilon, None)
        from gapath.planners._multi import multi_front

        return multi_front(
            workspace,
            objectives,
            costmap,
            max_labels=max_labels,
            progress=progress,
            tie_break=tie_break,
            limit=limit,
        )
    names, mode, P, Q = _free_plan(objectives)
    epsilon = _epsilon(epsilon, mode)
    budget = MAX_LABELS if max_labels is None else _budget(max_labels)
    if tie_break not in ("smoothest", "none"):
        raise ConfigError(f"tie_break must be 'smoothest' or 'none', got {tie_break!r}")
    t0 = time.perf_counter()
    occ = np.ascontiguousarray(workspace.occ)
    pot = np.ascontiguousarray(workspace.potential, dtype=np.float64)
    if mode == MODE_CELL:  # (length, vulnerability): BOA*
        return _boa_front(workspace, names, occ, pot, budget, progress, tie_break == "smoothest", t0, limit)
    (sr, sc), (gr, gc) = workspace.start, workspace.goal
    h, w = workspace.shape
    cs = float(workspace.cell_size)
    cc = bool(workspace.corner_cutting)
    # Ctrl-C is held (a handler installed) only once the search takes more than one
    # kernel call: a small map is done before that, without the handler's cost
    with _DeferredInterrupt(lazy=True) as interrupt:
        # masks, heuristics and the initial state in one kernel call (MODE_HEADING or
        # MODE_THREE: two objectives without smoothness are _boa_front's)
        mask, hs, hd, hv, ht, *state = _free_prepare(occ, pot, sr, sc, gr, gc, cs, cc, mode, P, Q)
        t_heur = time.perf_counter() - t0
        if hv[sr * w + sc] == np.inf:
            raise _no_path(workspace)
        args = (
            occ,
            pot,
            (gr, gc),
            cs,
            mask,
            mode,
            P,
            Q,
            (hs, hd, hv, ht),
            state,
            budget,
            progress,
            interrupt,
            epsilon,
            limit,
        )
        total = {"expansions": 0, "generated": 0, "labels": 0, "peak_bytes": 0}
        li, lf, sols, st, pc = _search_pass(*args, total, t0)

    cells, offsets = _trace(li, sols, w) if pc is None else _trace_parents(li, pc, sols, w)
    ns, nd, turns, vul = li[sols, NS], li[sols, ND], li[sols, TURNS], lf[sols, F_VUL]
    values = {
        "length": (ns + SQRT2 * nd) * cs,
        "vulnerability": vul,
        "smoothness": turns * QUARTER_PI,
    }
    F = np.column_stack([values[name] for name in names])
    # among tolerance-equal vectors prefer the smoothest path, then the shortest, then
    # the least vulnerable
    order = np.lexsort((vul, ns + SQRT2 * nd, turns))
    keep = _tolerant_front(np.ascontiguousarray(F), order)
    keep = keep[np.lexsort(F[keep].T[::-1])]
    paths = [cells[offsets[i] : offsets[i + 1]] for i in keep]
    stats = {
        **total,
        "solutions": int(st[S_SOLS]),
        "heuristic_seconds": t_heur,
        "seconds": time.perf_counter() - t0,
    }
    return ExactFront(
        objectives=names,
        F=F[keep],
        paths=paths,
        profiles=None,
        smoothness=values["smoothness"][keep],
        stats=stats,
    )


def _no_path(workspace) -> NoPathError:
    """The error of a free search whose goal cannot be reached."""
    h, w = workspace.shape
    return NoPathError(
        f"no feasible path from {workspace.start} to {workspace.goal} in workspace "
        f"{workspace.name!r} ({h}x{w}, {workspace.n_obstacles} obstacles, "
        f"corner_cutting={workspace.corner_cutting})"
    )


def _boa_front(workspace, names, occ, pot, budget, progress, ties, t0, limit) -> ExactFront:
    """:func:`free_front` on (length, vulnerability), in either column order:
    BOA* (:mod:`gapath.planners._boa_kernels`). A small search is two kernel
    calls (heuristics; search and result arrays); a longer one continues in
    slices like :func:`_search_pass` (progress, Ctrl-C, the budget)."""
    (sr, sc), (gr, gc) = workspace.start, workspace.goal
    w = workspace.shape[1]
    cs = float(workspace.cell_size)
    len_first = names[0] == "length"
    with _DeferredInterrupt(lazy=True) as interrupt:
        mask, hs, hd, hv = _boa_prepare(occ, pot, gr, gc, bool(workspace.corner_cutting))
        t1 = time.perf_counter()
        t_heur = t1 - t0
        if hv[sr * w + sc] == np.inf:
            raise _no_path(workspace)
        slices = _slices(1 << 14, 1 << 10, 1 << 26, limit)
        status, result, state = _boa_solve(
            occ, pot, sr, sc, gr, gc, cs, mask, hs, hd, hv, ties, len_first, slices.n, budget
        )
        interrupt.check()
        complete = True
        if result is None or progress is not None:
            result, complete = _boa_slices(
                workspace, occ, pot, mask, hs, hd, hv, ties, len_first, budget, progress, interrupt,
                slices, status, result, state, t0, t1,
            )  # fmt: skip
    F, smoothness, cells, offsets, counts = result
    stats = {
        "expansions": int(counts[C_EXPANDED]),
        "generated": int(counts[C_GENERATED]),
        "labels": int(counts[C_ROWS]),
        "peak_bytes": int(counts[C_PEAK]),
    }
    if ties:
        stats["tie_edges"] = int(counts[C_EDGES])
    stats["solutions"] = int(counts[C_SOLS])
    stats["complete"] = complete
    stats["heuristic_seconds"] = t_heur
    stats["seconds"] = time.perf_counter() - t0
    return ExactFront(
        objectives=names,
        F=F,
        paths=[cells[offsets[i] : offsets[i + 1]] for i in range(len(F))],
        profiles=None,
        smoothness=smoothness,
        stats=stats,
    )


def _search_stats(st, seconds, total=None) -> dict:
    """How far a free search has got, from its state vector ``st`` (the
    ``S_*`` layout of :mod:`gapath.planners._exact_kernels`), for progress
    reports and budget errors; ``total`` adds the expansions and generated
    labels of earlier passes."""
    done = total or {"expansions": 0, "generated": 0}
    return {
        "expansions": done["expansions"] + int(st[S_EXPANDED]),
        "generated": done["generated"] + int(st[S_GENERATED]),
        "labels": int(st[S_N] - st[S_N_FREE] + st[S_PC]),  # S_PC: 0 but in _free_run
        "open": int(st[S_SIZE]),
        "solutions": int(st[S_SOLS]),
        "seconds": seconds,
    }


def _boa_slices(
    workspace, occ, pot, mask, hs, hd, hv, ties, len_first, budget, progress, interrupt,
    slices, status, result, state, t0, t1,
):  # fmt: skip
    """The rest of a BOA* search that did not end in its first slice (or
    reports progress): slices of :func:`_boa_run`, then :func:`_boa_finish`.
    Returns ``(result, complete)``: ``complete`` is False when the search
    stopped at ``slices.limit`` expansions (the solutions found so far)."""
    (gr, gc), w = workspace.goal, workspace.shape[1]
    cs = float(workspace.cell_size)
    pops = 0
    while True:
        now = time.perf_counter()
        if result is not None:  # done (reported once, for the progress callback)
            counts = result[4]
            stats = {
                "expansions": int(counts[C_EXPANDED]),
                "generated": int(counts[C_GENERATED]),
                "labels": int(counts[C_ROWS] - counts[C_FREE]),
                "open": 0,
                "solutions": int(counts[C_SOLS]),
                "seconds": now - t0,
            }
            progress({"phase": "free", **stats})
            return result, True
        gmin, first, li, lf, sols, hk, hid, st, stf, edges, est = state
        if status == PAUSED:  # a longer search: hold Ctrl-C from now on
            interrupt.arm()
        slices.update(int(st[S_POPS]) - pops, now - t1)
        stats = _search_stats(st, now - t0)
        if status == OVER_BUDGET:
            raise _free_budget_error(budget, stats)
        stop = status == PAUSED and stats["expansions"] > slices.limit
        if status == DONE or stop:
            peak = _boa_bytes(hs, hd, hv, gmin, first, li, lf, sols, hk, hid, edges)
            result = _boa_finish(li, lf, sols, st, edges, est[0], pot, w, cs, ties, len_first, peak)
            interrupt.check()
            if stop:  # the solutions found so far (reported once)
                if progress is not None:
                    progress({"phase": "free", **stats})
                return result, False
            if progress is None:
                return result, True
            continue
        if progress is not None:
            progress({"phase": "free", **stats})
        pops, t1 = int(st[S_POPS]), time.perf_counter()
        li, lf, sols, hk, hid, edges, status = _boa_run(
            occ, pot, gr, gc, cs, mask, hs, hd, hv, gmin, first, li, lf, sols, hk, hid, st, stf,
            edges, est, slices.n, budget, ties,
        )  # fmt: skip
        interrupt.check()
        state = (gmin, first, li, lf, sols, hk, hid, st, stf, edges, est)


def _search_pass(
    occ,
    pot,
    goal,
    cs,
    mask,
    mode,
    P,
    Q,
    heuristics,
    state,
    budget,
    progress,
    interrupt,
    eps,
    limit,
    total,
    t0,
):
    """One run of the free search in slices (progress, Ctrl-C and the budget
    handled between slices) from ``state`` (what :func:`_free_init` returns),
    until done or past ``limit`` expansions; adds its counts to ``total``
    (``complete``: False when stopped at ``limit``). Returns the label
    tables, the solution labels, the scalar state and the parent table
    (:func:`~gapath.planners._exact_kernels._free_run`'s ``pc``; None for
    the approximate search, whose rows keep their parents)."""
    gr, gc = goal
    hs, hd, hv, ht = heuristics
    gmin, first, li, lf, sols, hk, hid, st, stf = state
    fixed = hs.nbytes + hd.nbytes + hv.nbytes + ht.nbytes + gmin.nbytes + first.nbytes
    slices = _slices(1 << 14, 1 << 10, 1 << 26, limit)
    stop = False
    sp = _stair_pool(1 << 16 if mode == MODE_THREE else 0)  # MODE_THREE's staircases
    pc = None
    if eps > 0:  # the approximate search: the last open label of each state
        open_at = np.full(first.shape[0] - 1, -1, np.int32)
        fixed += open_at.nbytes
    else:  # the expanded labels' cells and parents, the stack of free label rows
        pc = np.empty((1 << 16, 2), np.int32)
        fs = np.empty(li.shape[0], np.int32)
    while True:
        pops, t1 = st[S_POPS], time.perf_counter()
        if eps > 0:
            li, lf, sols, hk, hid, sp, status = _apex_run(
                occ, pot, gr, gc, cs, mask, hs, hd, hv, ht, gmin, first,
                li, lf, sols, hk, hid, st, stf, sp, open_at, slices.n, budget, eps,
            )  # fmt: skip
        else:
            li, lf, sols, hk, hid, sp, pc, fs, status = _free_run(
                occ, pot, gr, gc, cs, mask, mode, P, Q, hs, hd, hv, ht, gmin, first,
                li, lf, sols, hk, hid, st, stf, sp, pc, fs, slices.n, budget,
            )  # fmt: skip
        interrupt.check()
        if status == PAUSED:  # a longer search: hold Ctrl-C from now on
            interrupt.arm()
        now = time.perf_counter()
        slices.update(st[S_POPS] - pops, now - t1)
        if status == DONE and progress is None:  # (the dict below costs microseconds)
            break
        stats = _search_stats(st, now - t0, total)
        if status == OVER_BUDGET:
            raise _free_budget_error(budget, stats)
        stop = status == PAUSED and stats["expansions"] > limit
        if progress is not None:
            progress({"phase": "free", **stats})
        if status == DONE or stop:
            break
    total["complete"] = not stop
    total["expansions"] += int(st[S_EXPANDED])
    total["generated"] += int(st[S_GENERATED])
    # rows used at the peak (and the parent entries: an upper bound of the labels held)
    total["labels"] = max(total["labels"], int(st[S_N] + st[S_PC]))
    arrays = li.nbytes + lf.nbytes + hk.nbytes + hid.nbytes + sols.nbytes + sp.nbytes
    if pc is not None:
        arrays += pc.nbytes + fs.nbytes
    total["peak_bytes"] = max(total["peak_bytes"], int(fixed + arrays))
    if mode == MODE_THREE:
        if eps == 0:  # (the approximate search does not count them)
            total["stair_searches"] = total.get("stair_searches", 0) + int(st[S_SEARCHES])
        total["stair_floats"] = max(total.get("stair_floats", 0), int(sp[SP_USED]))
    return li, lf, sols[: st[S_SOLS]], st, pc


def _free_budget_error(budget, stats) -> LabelBudgetError:
    """The error of a free search (either kernel) stopped at the label budget."""
    return LabelBudgetError(
        f"free search stopped at the label budget max_labels={budget:,} "
        f"(--max-labels) after {stats['seconds']:.1f} s: {stats['labels']:,} labels "
        f"held, {stats['expansions']:,} expanded, {stats['open']:,} on the open list, "
        f"{stats['solutions']:,} solutions found so far; no front (a partial search is "
        f"not a Pareto front). Raise the budget, or use a smaller map or fewer "
        f"objectives",
        {**stats, "max_labels": budget},
    )


# ---------------------------------------------------------------------------
# the front a user sees
# ---------------------------------------------------------------------------

#: Path sets of :func:`exact_path_front`.
EXACT_MODES = ("monotone", "free")


def exact_path_front(
    workspace: Workspace,
    objectives: Sequence[str] = ("length", "vulnerability"),
    mode: str = "monotone",
    **options: Any,
) -> PathFront:
    """The exact front as a :class:`gapath.front.PathFront` (what ``gapath
    exact`` writes): :func:`monotone_front` or :func:`free_front`, with
    every path's metrics.

    Parameters
    ----------
    workspace : Workspace
    objectives : sequence of str, default ("length", "vulnerability")
        Some of :data:`EXACT_OBJECTIVES`.
    mode : {"monotone", "free"}, default "monotone"
        Column-monotone paths (the GA's path set) or all 8-connected paths.
    **options
        ``max_labels``, ``progress``; ``costmap``, ``tie_break``, ``search``
        with ``mode="free"`` (see :func:`free_front`).

    Returns
    -------
    PathFront

    Raises
    ------
    ConfigError
        On an unknown mode or objective, or bad options.
    NoPathError
        If no feasible path of the mode joins start and goal.
    LabelBudgetError
        If the search would hold more than ``max_labels`` labels.

    Examples
    --------
    >>> from gapath import Workspace
    >>> front = exact_path_front(Workspace(np.zeros((3, 4), bool)), ["length"])
    >>> len(front), front.marked()
    (1, {'shortest': 0, 'knee': 0})
    """
    from gapath.front import PathFront

    ef = exact_front(workspace, objectives, mode, **options)
    return PathFront.from_paths(workspace, ef.paths, ef.objectives, ef.F)


def exact_front(
    workspace: Workspace,
    objectives: Sequence[str] = ("length", "vulnerability"),
    mode: str = "monotone",
    **options: Any,
) -> ExactFront:
    """:func:`monotone_front` (``mode="monotone"``) or :func:`free_front`
    (``mode="free"``).

    Raises
    ------
    ConfigError
        On an unknown mode, a ``costmap`` with ``mode="monotone"`` (and see
        the two functions).
    """
    if mode == "monotone":
        if options.get("costmap") is not None:
            raise ConfigError(
                "the exact monotone front has no costmap layers; use mode='free' (--mode free) "
                "for layer objectives"
            )
        options.pop("costmap", None)
        return monotone_front(workspace, objectives, **options)
    if mode == "free":
        return free_front(workspace, objectives, **options)
    raise ConfigError(f"unknown exact mode {mode!r}; expected one of {', '.join(EXACT_MODES)}")
