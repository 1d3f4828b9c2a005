"""Multi-objective graph search on layered costmaps: A*-PO, D*-PO and the
weighted-sum A* and D* baselines of A. Lavin, "A Pareto optimal D* search
algorithm for multiobjective path planning".

The search problem
    The graph is the 8-connected grid of the costmap's workspace (SPEC moves,
    corner rule included). Every objective is a *cost sum* along the path
    ("the aim is to minimize these four cost sums", paper section II-A); a
    step ``u -> v`` in direction ``d`` costs, per objective,

    * ``length``: the step length, 1 or sqrt(2) (cell units);
    * a cell layer (``elevation``, ``risk``, user layers): its value at ``v``
      (the start cell's value is a constant added to every path);
    * ``solar``: ``sigma(d, k(u))`` (:meth:`gapath.costmap.Costmap.solar_cost`)
      at the step index ``k(u)``.

    The solar layer is *dynamic*: its cost depends on when a cell is left.
    An exact treatment would search (cell, step index) pairs; instead, the
    search uses the static estimate ``k(u)`` = Chebyshev distance from the
    planner's start (origin) to ``u``: the earliest step at which the rover
    can stand on ``u``. It is exact for every path whose steps all move one
    cell further from the start in Chebyshev distance, keeps the graph static
    (so D* replanning is exact and A*-PO and D*-PO solve the same problem),
    and it is only used inside the search: the returned objectives are
    always recomputed on the path with its true step indices.

    Lengths are carried as integer step counts (straight, diagonal), so two
    partial paths with the same counts have bit-identical lengths (SPEC) and
    ties in length are exact.

Priority and tie-breaking (the total order of cost vectors)
    Cost vectors ``a, b`` (one component per objective) are compared by

    1. the *priority* ``p = sum_j w_j a_j / N_j``,
    2. the *secondary* cost ``s = sum_j a_j / N_j`` (normalised, equal weights),
    3. the components themselves, lexicographically in objective order,

    with the normalisers ``N_j`` = the *mean* cost of one step in objective
    ``j`` on the map, so that every objective weighs about the same in the
    total of a typical path: 1 for length (a step costs 1 or sqrt(2)), 1/2
    for solar (the mean of ``sigma`` over the directions) and the mean of
    the layer over the whole grid for a cell layer (over all cells, so that
    it does not change when cells are blocked; 1 if the layer is all zero).
    (Dividing by the largest per-step cost instead makes the length
    dominate the fractional layer costs: the weighted sum then returns the
    shortest path on every map of the Mars study.) A weighted-sum planner
    uses ``p = s`` with its weights; a Pareto planner uses the configurable
    ``priority`` (by default its first objective, "a preferred criterion" of
    the paper).

A*-PO and D*-PO (paper section III-B and Fig. 1)
    Every open node is projected into objective space by its key vector
    ``f = g + h`` (one dimension per objective; ``h`` is the octile distance
    to the goal for ``length`` and 0 for the other objectives, admissible
    and consistent). The open list keeps, *incrementally*, its non-dominated
    set: a new node is compared with the non-dominated nodes only (if it is
    not dominated, the non-dominated nodes it dominates leave the set); a
    dominated node is filed under one non-dominated node that dominates it
    (the one that comes last in the order below, so that it is re-examined
    as seldom as possible), and when that node leaves the open list only the
    nodes filed under it are inserted again. Dominance is transitive, so
    nothing else can change. At every step the node expanded is, among the
    non-dominated open nodes, the one with the smallest priority (ties:
    secondary cost, components, key ``k2``, cell index), taken from a
    binary heap over the non-dominated nodes.

    Because a node that is dominated always has a strictly larger secondary
    cost than its dominator, the node chosen is also the smallest open node
    in the total order above, and the search is an A* (a D* Lite) over
    cost vectors ordered by it. Hence the guarantee: the returned path
    minimises the order over all paths, so *no path dominates it* in the
    search's cost sums (with the solar estimate above; exactly when the
    solar vector does not turn, ``solar_rate = 0``). With ``priority =
    "length"`` the path is a shortest path and, among the shortest paths,
    the one with the smallest normalised sum of the other objectives.

D*-PO
    :class:`DStarPO` is D* Lite (S. Koenig, M. Likhachev, AAAI 2002, the
    optimized version with ``km``; see :mod:`gapath.planners.dstar_lite`)
    over cost vectors: ``g``, ``rhs`` and the keys
    ``[min(g, rhs) + h(s_start, s) + km; min(g, rhs)]`` are vectors compared
    by the order above, and ``U.Top()`` is chosen through the incremental
    non-dominated set of the first key vectors. It searches backwards from
    the goal and keeps D*'s replanning: :meth:`DStarPO.update_cells` repairs
    the edges around changed cells and :meth:`DStarPO.replan` returns what a
    fresh plan on the new map returns (the step-index origin of the solar
    estimate stays the first start, the "mission clock").

Weighted-sum baselines (the paper's A* and D*)
    :func:`weighted_sum_astar` and :class:`WeightedSumDStar` minimise
    ``sum_j w_j G_j / N_j`` (equal weights by default) with the same kernels
    but a plain priority queue (no Pareto filter). The paper renormalises
    the costs over the open list at every step; the static normalisation
    (``baseline="weighted"``, the default) keeps the searches exact (A* and
    D* then return paths of equal cost); the paper's rule is
    ``baseline="renormalised"`` (below).

Renormalised baselines (Lavin's A* and D*, ``baseline="renormalised"``)
    The paper's A* and D* sum the objectives after normalising each to
    [0, 1] *over the nodes in the open list, at every search step* (section
    III-A). :func:`weighted_sum_astar` and :func:`renormalised_dstar` with
    ``baseline="renormalised"`` do that (kernels in
    :mod:`gapath.planners._renorm_kernels`): every open node is projected to
    its cost vector, one column per objective (for A*, the length column is
    ``g + h``, distance travelled plus octile heuristic: the paper's distance
    and heuristic layers both "contribute to F1"), each column is min-max
    scaled over the open nodes, and the node of smallest (weighted) sum is
    expanded. With a single objective the scaling does not change the
    order, and the searches are plain A* and Dijkstra ("the algorithms
    yield the same solutions for single path cost problems", section
    IV-A). The order changes from step to
    step, so neither search is exact: the returned path minimises no fixed
    function, and that is the baseline the paper measured against.

    * A*: forward best-first search with a closed set (a node is expanded
      once); a cheaper tentative cost, judged by the step's normalisation,
      replaces the stored one of an open node.
    * D*: the first search of Stentz's D* (1994): backwards from the goal,
      each state's cost to the goal and back-pointer, no focusing
      heuristic (the original D*), CLOSED states reopened when a cheaper
      cost (by the step's normalisation) reaches them, back-pointer
      children updated when their parent's cost changes; stops when the
      start is expanded. Only this first plan is implemented: D*'s
      replanning after cost changes (RAISE states) is not, and the study
      never replans (the paper's Table I plans once per workspace).

Path objectives (the returned ``F``)
    Recomputed on the returned path by
    :meth:`gapath.costmap.Costmap.evaluate_path`: F1 ``length`` (times
    ``cell_size``), F2 ``elevation`` = mean over the waypoints (eq. 5),
    F3 ``solar`` = sum over the steps with their true indices (eq. 6),
    F4 ``risk`` = mean over the waypoints (eq. 7); user layers: mean over
    the waypoints.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from gapath.errors import ConfigError, NoPathError
from gapath.grid import DIRECTION, SQRT2, check_cell, check_free_cell, path_length
from gapath.planners._incremental import IncrementalGridPlanner
from gapath.planners._pareto_kernels import (
    _CELL,
    _SOLAR,
    INF,
    _astar_kernel,
    _compute_shortest_path,
    _dstar_insert,
    _extract_path,
    _octile_counts,
    _open_reset,
    _update_changed_edges,
)
from gapath.planners.registry import planner_names
from gapath.workspace import Workspace

__all__ = [
    "ParetoPlanResult",
    "astar_po",
    "weighted_sum_astar",
    "renormalised_dstar",
    "BASELINES",
    "DStarPO",
    "WeightedSumDStar",
    "plan",
    "PLANNERS",
    "DEFAULT_OBJECTIVES",
]

#: The paper's four objectives F1..F4.
DEFAULT_OBJECTIVES = ("length", "elevation", "solar", "risk")
#: The baselines' composite costs: ``"weighted"`` (static normalisers, an
#: exact search) or ``"renormalised"`` (Lavin's: renormalised over the open
#: list at every step).
BASELINES = ("weighted", "renormalised")


class _Model:
    """Everything the kernels need about the costs, built from a costmap."""

    def __init__(self, costmap, objectives, origin, *, pareto, priority=None, weights=None):
        self.costmap = costmap
        self.objectives = costmap.check_objectives(objectives)
        ws = costmap.workspace
        h, w = ws.shape
        n = h * w
        others = [o for o in self.objectives if o != "length"]
        self.columns = ("length",) + tuple(others)  # internal column order
        m = len(self.columns)
        kind = np.zeros(m, np.int64)
        cells = np.zeros((m, n))
        scale = np.ones(m)  # N_j: mean cost of a step
        for j, name in enumerate(self.columns[1:], start=1):
            if name == "solar":
                kind[j] = _SOLAR
                scale[j] = 0.5
            else:
                kind[j] = _CELL
                arr = costmap.layer(name)
                cells[j] = arr.ravel()
                mean = float(arr.mean())
                scale[j] = mean if mean > 0 else 1.0
        used = np.array([("length" in self.objectives)] + [True] * (m - 1))
        self.used = used
        self.scale = scale
        # user order -> internal column
        self.order = np.array([self.columns.index(o) for o in self.objectives], np.int64)
        sw = np.where(used, 1.0 / scale, 0.0)
        if pareto:
            pw = self._priority(priority, used, scale)
        else:
            pw = self._weights(weights, used, scale)
            sw = pw.copy()
        self.wts = np.ascontiguousarray(np.vstack([pw, sw]))
        # solar: static step-index estimate = Chebyshev distance from the origin
        orow, ocol = origin
        rr, cc = np.mgrid[0:h, 0:w]
        self.khat = np.maximum(np.abs(rr - orow), np.abs(cc - ocol)).ravel().astype(np.int64)
        self.soltab = costmap.solar_table(max(h, w))
        self.occ = np.array(ws.occ, dtype=np.bool_, order="C", copy=True)
        self.cc = bool(ws.corner_cutting)
        self.kind = kind
        self.cells = np.ascontiguousarray(cells)
        self.ucols = np.flatnonzero(used).astype(np.int64)
        self.pareto = bool(pareto)

    def costs(self) -> tuple:
        """The kernels' cost arguments ``(kind, cells, soltab, khat, wts)``."""
        return self.kind, self.cells, self.soltab, self.khat, self.wts

    def arrays(self, n: int, n_slots: int) -> tuple:
        """Fresh search arrays: slots ``(V, C)`` and the open list ``(K, S,
        ndl, NDK, hn, hk, sz, kx, buf)``."""
        m = len(self.columns)
        u = max(len(self.ucols), 1)
        return (
            np.zeros((n_slots, m + 2)),
            np.zeros((n_slots, 2), np.int64),
            np.zeros((n + 2, 2 * m + 4)),
            np.full((n, 7), -1, np.int64),
            np.zeros(n, np.int64),
            np.zeros((n, u)),
            np.zeros(n, np.int64),
            np.zeros((n, 2)),
            np.zeros(8, np.int64),
            np.zeros(u),
            np.zeros(n, np.int64),
        )

    def _priority(self, priority, used, scale) -> np.ndarray:
        m = len(self.columns)
        if priority is None:
            priority = self.objectives[0]
        if isinstance(priority, str):
            if priority == "sum":
                return np.where(used, 1.0 / scale, 0.0)
            if priority not in self.objectives:
                raise ConfigError(
                    f"priority {priority!r} must be 'sum', one of the objectives "
                    f"({', '.join(self.objectives)}) or a sequence of weights"
                )
            pw = np.zeros(m)
            j = self.columns.index(priority)
            pw[j] = 1.0 / scale[j]
            return pw
        return self._weights(priority, used, scale, label="priority")

    def _weights(self, weights, used, scale, label="weights") -> np.ndarray:
        m = len(self.columns)
        if weights is None:
            return np.where(used, 1.0 / scale, 0.0)
        try:
            wv = np.asarray(weights, dtype=np.float64)
        except (TypeError, ValueError):
            raise ConfigError(f"{label} must be a sequence of numbers, got {weights!r}") from None
        if wv.shape != (len(self.objectives),):
            raise ConfigError(
                f"{label} needs one weight per objective "
                f"({len(self.objectives)}: {', '.join(self.objectives)}), "
                f"got {weights!r}"
            )
        if not np.all(np.isfinite(wv)) or (wv < 0).any() or not (wv > 0).any():
            raise ConfigError(f"{label} must be finite, >= 0 and not all 0, got {weights!r}")
        out = np.zeros(m)
        for name, v in zip(self.objectives, wv):
            j = self.columns.index(name)
            out[j] = v / scale[j]
        return out

    def search_vector(self, path_idx: np.ndarray) -> np.ndarray:
        """The search's cost sums of a path (user order; cell layers include
        the start cell; solar with the static step-index estimate; length in
        cell units times ``cell_size``)."""
        kind, cells, soltab, khat = self.kind, self.cells, self.soltab, self.khat
        w = self.occ.shape[1]
        r, c = path_idx // w, path_idx % w
        dr, dc = np.diff(r), np.diff(c)
        diag = (dr != 0) & (dc != 0)
        out = np.zeros(len(self.columns))
        out[0] = ((len(dr) - diag.sum()) + SQRT2 * diag.sum()) * self.costmap.workspace.cell_size
        dirs = DIRECTION[dr + 1, dc + 1]
        for j in range(1, len(self.columns)):
            if kind[j] == _CELL:
                out[j] = cells[j, path_idx].sum()
            else:
                out[j] = soltab[khat[path_idx[:-1]], dirs].sum()
        return out[self.order]


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ParetoPlanResult:
    """Result of a multi-objective single-path planner.

    Attributes
    ----------
    path : (m, 2) int64 array
        Cells ``(row, col)`` from the start to the goal (read-only).
    objectives : tuple of str
        Objective names (the order of ``F``).
    F : (k,) float array
        The path's objectives, recomputed on the path (module docstring:
        F1 length, F2 mean elevation, F3 solar sum, F4 mean risk).
    search_cost : (k,) float array
        The search's cost sums of the path (cell layers summed over the
        waypoints, solar with the static step-index estimate): the vector
        the planner minimises in its order.
    length : float
        Euclidean length times ``cell_size``.
    expansions : int
        Vertices expanded during this call.
    seconds : float
        Wall-clock time of the call.
    planner : str
        ``astar``, ``dstar-lite``, ``astar-po`` or ``dstar-po``; ``dstar``
        for :func:`renormalised_dstar`.
    """

    path: np.ndarray
    objectives: tuple
    F: np.ndarray
    search_cost: np.ndarray
    length: float
    expansions: int
    seconds: float
    planner: str

    @property
    def values(self) -> dict[str, float]:
        """``{objective: value}`` of ``F``."""
        return {n: float(v) for n, v in zip(self.objectives, self.F)}

    def __repr__(self) -> str:
        vals = ", ".join(f"{n}={v:.4g}" for n, v in self.values.items())
        return (
            f"ParetoPlanResult({self.planner}, cells={len(self.path)}, {vals}, "
            f"expansions={self.expansions}, seconds={self.seconds:.6f})"
        )


def _result(model, idx, expansions, t0, planner) -> ParetoPlanResult:
    cm = model.costmap
    w = cm.shape[1]
    path = np.column_stack([idx // w, idx % w]).astype(np.int64)
    if len(path) == 1:
        F = np.array(
            [
                0.0 if o in ("length", "solar") else float(cm.layer(o)[tuple(path[0])])
                for o in model.objectives
            ]
        )
    else:
        vals = cm.evaluate_path(path, model.objectives)
        F = np.array([vals[o] for o in model.objectives])
    search = model.search_vector(idx)
    path.setflags(write=False)
    length = path_length(path, cm.workspace.cell_size)
    return ParetoPlanResult(
        path=path,
        objectives=model.objectives,
        F=F,
        search_cost=search,
        length=length,
        expansions=int(expansions),
        seconds=time.perf_counter() - t0,
        planner=planner,
    )


def _no_path(ws, src, dst, expansions=None) -> NoPathError:
    h, w = ws.shape
    rule = "allowed" if ws.corner_cutting else "not allowed"
    extra = "" if expansions is None else f"; the search expanded {expansions} cells"
    return NoPathError(
        f"no path from start {src} to goal {dst} on the {h}x{w} grid "
        f"(8-connected, corner cutting {rule}{extra})"
    )


# ---------------------------------------------------------------------------
# A*: A*-PO and the weighted-sum baseline
# ---------------------------------------------------------------------------


def _check_origin(origin, default, shape):
    if origin is None:
        return default
    return check_cell(origin, "origin", shape)


def _astar(
    costmap, objectives, start, goal, origin, *, pareto, priority=None, weights=None, planner="astar-po"
) -> ParetoPlanResult:
    t0 = time.perf_counter()
    ws = costmap.workspace
    occ = ws.occ
    src = check_free_cell(ws.start if start is None else start, "start", occ)
    dst = check_free_cell(ws.goal if goal is None else goal, "goal", occ)
    origin = _check_origin(origin, src, occ.shape)
    model = _Model(costmap, objectives, origin, pareto=pareto, priority=priority, weights=weights)
    h, w = occ.shape
    n = h * w
    arrays = model.arrays(n, n + 1)
    parent = np.empty(n, np.int64)
    closed = np.empty(n, np.bool_)
    idx, expansions = _astar_kernel(
        src[0] * w + src[1],
        dst[0] * w + dst[1],
        model.occ,
        model.cc,
        *model.costs(),
        model.ucols,
        model.pareto,
        *arrays,
        parent,
        closed,
    )
    if len(idx) == 0:
        raise _no_path(ws, src, dst, expansions)
    return _result(model, idx, expansions, t0, planner)


def astar_po(
    costmap, objectives=DEFAULT_OBJECTIVES, *, priority=None, start=None, goal=None, origin=None
) -> ParetoPlanResult:
    """A*-PO: A* choosing, at every step, the non-dominated open node of
    smallest priority (Lavin; see :mod:`gapath.planners.pareto`).

    Parameters
    ----------
    costmap : :class:`gapath.costmap.Costmap`
        Layers and workspace (grid, start, goal, cell size, corner rule).
    objectives : sequence of str or comma-separated str
        Among :attr:`gapath.costmap.Costmap.objective_names`; default the
        paper's ``("length", "elevation", "solar", "risk")``.
    priority : str or sequence of float, optional
        Cost that picks among the non-dominated open nodes: an objective name
        (default: the first objective), ``"sum"`` (normalised equal-weight
        sum) or one non-negative weight per objective (normalised weighted
        sum). Ties: normalised sum, then the components in objective order.
    start, goal : (row, col), optional
        Override the workspace's start and goal.
    origin : (row, col), optional
        Cell from which the solar step index is estimated (default: the
        start; see :mod:`gapath.planners.pareto`).

    Returns
    -------
    ParetoPlanResult
        The path and its objectives ``F`` (recomputed on the path).

    Raises
    ------
    ConfigError
        On an unknown, unset or repeated objective, a bad priority, or a start
        or goal outside the grid or on an obstacle.
    NoPathError
        If the goal cannot be reached.

    See Also
    --------
    DStarPO : the same search, backwards, with replanning.
    weighted_sum_astar : the weighted-sum baseline.

    Notes
    -----
    No path dominates the returned one in the search's cost sums (module
    docstring), since it is the minimum of a total order that extends
    dominance.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> from gapath.costmap import Costmap
    >>> ws = Workspace(np.zeros((3, 7), bool), start=(2, 0), goal=(2, 6))
    >>> cm = Costmap(ws, risk=(2, 3))
    >>> res = astar_po(cm, ("length", "risk"))          # priority: length
    >>> res.path.tolist()
    [[2, 0], [2, 1], [2, 2], [2, 3], [2, 4], [2, 5], [2, 6]]
    >>> [round(float(v), 4) for v in res.F]
    [6.0, 0.5317]
    >>> res = astar_po(cm, ("length", "risk"), priority="risk")
    >>> res.path.tolist()
    [[2, 0], [1, 1], [0, 2], [0, 3], [0, 4], [1, 5], [2, 6]]
    >>> [round(float(v), 4) for v in res.F]
    [7.6569, 0.1817]
    """
    return _astar(
        costmap, objectives, start, goal, origin, pareto=True, priority=priority, planner="astar-po"
    )


def _check_baseline(baseline) -> str:
    if baseline not in BASELINES:
        raise ConfigError(f"baseline must be one of {', '.join(BASELINES)}, got {baseline!r}")
    return baseline


def _renormalised(costmap, objectives, start, goal, origin, weights, *, dstar) -> ParetoPlanResult:
    """Lavin's renormalised A* (``dstar=False``) or D* (module docstring)."""
    from gapath.planners import _renorm_kernels as rk

    t0 = time.perf_counter()
    ws = costmap.workspace
    occ = ws.occ
    src = check_free_cell(ws.start if start is None else start, "start", occ)
    dst = check_free_cell(ws.goal if goal is None else goal, "goal", occ)
    origin = _check_origin(origin, src, occ.shape)
    model = _Model(costmap, objectives, origin, pareto=False, weights=weights)
    wq = np.ascontiguousarray(model.wts[0] * model.scale)  # the user's weights, per internal column
    h, w = occ.shape
    args = (
        src[0] * w + src[1],
        dst[0] * w + dst[1],
        model.occ,
        model.cc,
        model.kind,
        model.cells,
        model.soltab,
        model.khat,
        wq,
        np.ascontiguousarray(model.wts[1]),
    )
    if dstar:
        idx, expansions = rk.renormalised_dstar(*args, 50 * h * w)
    else:
        idx, expansions = rk.renormalised_astar(*args)
    if len(idx) == 0:
        raise _no_path(ws, src, dst, expansions)
    return _result(model, idx, expansions, t0, "dstar" if dstar else "astar")


def weighted_sum_astar(
    costmap,
    objectives=DEFAULT_OBJECTIVES,
    *,
    weights=None,
    start=None,
    goal=None,
    origin=None,
    baseline="weighted",
) -> ParetoPlanResult:
    """A* on the normalised weighted sum of the objectives (the paper's A*
    baseline): by default minimises ``sum_j w_j G_j / N_j`` (module
    docstring), equal weights by default; with ``baseline="renormalised"``
    the paper's own rule (objectives renormalised over the open list at
    every step, module docstring).

    Parameters
    ----------
    costmap, objectives, start, goal, origin : see :func:`astar_po`.
    weights : sequence of float, optional
        One non-negative weight per objective (not all zero); default 1 each.
    baseline : {"weighted", "renormalised"}
        ``"weighted"``: static normalisers, an exact search of the weighted
        sum. ``"renormalised"``: Lavin's A* (each objective renormalised
        over the open list at every step, the length as ``g + h``).

    Returns
    -------
    ParetoPlanResult

    Raises
    ------
    ConfigError, NoPathError
        As :func:`astar_po`.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> from gapath.costmap import Costmap
    >>> ws = Workspace(np.zeros((3, 7), bool), start=(2, 0), goal=(2, 6))
    >>> cm = Costmap(ws, risk=(2, 3))
    >>> weighted_sum_astar(cm, ("length", "risk")).path.tolist()
    [[2, 0], [1, 1], [0, 2], [0, 3], [0, 4], [1, 5], [2, 6]]
    >>> weighted_sum_astar(cm, ("length", "risk"), weights=(1, 0.01)).path.tolist()
    [[2, 0], [2, 1], [2, 2], [2, 3], [2, 4], [2, 5], [2, 6]]
    >>> res = weighted_sum_astar(cm, ("length", "risk"), baseline="renormalised")
    >>> res.path[0].tolist(), res.path[-1].tolist()
    ([2, 0], [2, 6])
    """
    if _check_baseline(baseline) == "renormalised":
        return _renormalised(costmap, objectives, start, goal, origin, weights, dstar=False)
    return _astar(costmap, objectives, start, goal, origin, pareto=False, weights=weights, planner="astar")


def renormalised_dstar(
    costmap, objectives=DEFAULT_OBJECTIVES, *, weights=None, start=None, goal=None, origin=None
) -> ParetoPlanResult:
    """Lavin's D* baseline: the first search of Stentz's D* from the goal
    back to the start, with the objectives renormalised over the open list
    at every step (module docstring). It plans once; for replanning use
    :class:`WeightedSumDStar` (D* Lite, exact weighted sum) or
    :class:`DStarPO`.

    Parameters
    ----------
    costmap, objectives, start, goal, origin : see :func:`astar_po`.
    weights : sequence of float, optional
        One non-negative weight per objective (not all zero); default 1 each.

    Returns
    -------
    ParetoPlanResult
        ``planner`` is ``"dstar"``.

    Raises
    ------
    ConfigError, NoPathError
        As :func:`astar_po`.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> from gapath.costmap import Costmap
    >>> ws = Workspace(np.zeros((3, 7), bool), start=(2, 0), goal=(2, 6))
    >>> res = renormalised_dstar(Costmap(ws, risk=(2, 3)), ("length", "risk"))
    >>> res.planner, res.path[0].tolist(), res.path[-1].tolist()
    ('dstar', [2, 0], [2, 6])
    """
    return _renormalised(costmap, objectives, start, goal, origin, weights, dstar=True)


# ---------------------------------------------------------------------------
# D*: D*-PO and the weighted-sum baseline
# ---------------------------------------------------------------------------


class DStarPO(IncrementalGridPlanner):
    """D*-PO: D* Lite over cost vectors with Pareto selection of ``U.Top()``
    (Lavin; see :mod:`gapath.planners.pareto`), with replanning.

    The planner keeps its own copy of the occupancy grid; the layers are
    static. Cells are blocked or freed with :meth:`update_cells`, the robot
    is advanced with :meth:`move_to`, and :meth:`replan` repairs the previous
    search; every result equals (in objective values; the cells may differ
    only between paths of equal cost) what a fresh planner returns on
    :attr:`workspace`.

    Parameters
    ----------
    costmap : :class:`gapath.costmap.Costmap`
    objectives, priority : see :func:`astar_po`.
    start, goal : (row, col), optional
        Override the workspace's start (the robot's cell) and goal.
    origin : (row, col), optional
        Cell from which the solar step index is estimated (default: the
        start; it stays fixed when the robot moves).

    Raises
    ------
    ConfigError
        On bad objectives or priority, or a start or goal outside the grid or
        on an obstacle.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> from gapath.costmap import Costmap
    >>> cm = Costmap(Workspace(np.zeros((5, 5), bool)), risk=(2, 2))
    >>> planner = DStarPO(cm, ("length", "risk"))
    >>> [round(float(v), 4) for v in planner.plan().F]
    [5.6569, 0.45]
    >>> planner.update_cells([(2, 2), (1, 1)], blocked=True)
    2
    >>> [round(float(v), 4) for v in planner.replan().F]
    [6.2426, 0.4417]
    """

    _pareto = True
    _name = "dstar-po"

    def __init__(
        self, costmap, objectives=DEFAULT_OBJECTIVES, *, priority=None, start=None, goal=None, origin=None
    ):
        self._setup(costmap, objectives, start, goal, origin, priority=priority)

    def _setup(self, costmap, objectives, start, goal, origin, *, priority=None, weights=None):
        ws = costmap.workspace
        occ = np.array(ws.occ, dtype=np.bool_, order="C", copy=True)
        self._occ = occ
        self._start = check_free_cell(ws.start if start is None else start, "start", occ)
        self._goal = check_free_cell(ws.goal if goal is None else goal, "goal", occ)
        self.costmap = costmap
        self.origin = _check_origin(origin, self._start, occ.shape)
        self._model = _Model(
            costmap, objectives, self.origin, pareto=self._pareto, priority=priority, weights=weights
        )
        self._model.occ = occ  # the planner's own, changing grid
        n = occ.size
        self._arrays = self._model.arrays(n, 2 * n + 3)
        self._V, self._C = self._arrays[:2]
        self._km = np.zeros(2, np.int64)
        self._last = self._start
        self._initialized = False

    # -- state ------------------------------------------------------------
    @property
    def objectives(self) -> tuple[str, ...]:
        return self._model.objectives

    @property
    def workspace(self):
        """The current map as a :class:`~gapath.workspace.Workspace`
        (start = the robot's cell)."""
        ws = self.costmap.workspace
        return Workspace(
            self._occ.copy(),
            self._start,
            self._goal,
            cell_size=ws.cell_size,
            corner_cutting=ws.corner_cutting,
            name=ws.name,
        )

    def plan(self) -> ParetoPlanResult:
        """Search from scratch: Initialize(), then ComputeShortestPath().

        Raises
        ------
        NoPathError
            If the goal is unreachable (the planner stays usable).
        """
        t0 = time.perf_counter()
        n = self._occ.size
        V, C = self._V, self._C
        V[: 2 * n] = INF  # rhs(s) = g(s) = inf
        C[: 2 * n, 0] = -1
        C[: 2 * n, 1] = 0
        V, C, K, S, ndl, NDK, hn, hk, sz, kx, buf = self._arrays
        _open_reset(S, sz)  # U = empty
        self._km[:] = 0  # km = 0
        self._last = self._start  # s_last = s_start
        goal = self._index(self._goal)
        V[n + goal] = 0.0  # rhs(s_goal) = 0
        C[n + goal] = 0
        model = self._model
        # U.Insert(s_goal, [h(s_start, s_goal); 0])
        _dstar_insert(
            goal,
            self._index(self._start),
            self._km,
            self._occ.shape[1],
            model.wts,
            model.ucols,
            model.pareto,
            V,
            C,
            K,
            S,
            ndl,
            NDK,
            hn,
            hk,
            sz,
            kx,
        )
        self._initialized = True
        return self._search(t0)

    # -- helpers -----------------------------------------------------------
    def _repair_edges(self, occ_old, src) -> None:
        model = self._model
        _update_changed_edges(
            occ_old,
            src,
            self._index(self._start),
            self._index(self._goal),
            self._km,
            self._occ,
            model.cc,
            *model.costs(),
            model.ucols,
            model.pareto,
            *self._arrays,
        )

    def _sync_km(self) -> None:
        """km = km + h(s_last, s_start); s_last = s_start."""
        if self._last != self._start:
            w = self._occ.shape[1]
            a, b = _octile_counts(self._index(self._last), self._index(self._start), w)
            self._km[0] += a
            self._km[1] += b
            self._last = self._start

    def _search(self, t0) -> ParetoPlanResult:
        start = self._index(self._start)
        goal = self._index(self._goal)
        model = self._model
        expansions = _compute_shortest_path(
            start,
            goal,
            self._km,
            self._occ,
            model.cc,
            *model.costs(),
            model.ucols,
            model.pareto,
            *self._arrays,
        )
        ws = self.costmap.workspace
        if start == goal:
            idx = np.array([start], np.int64)
        elif self._C[self._occ.size + start, 0] < 0:
            raise _no_path(ws, self._start, self._goal, expansions)
        else:
            idx = _extract_path(
                start, goal, self._occ, model.cc, *model.costs(), model.ucols, self._V, self._C
            )
            if len(idx) == 0:  # pragma: no cover - would be a bug
                raise RuntimeError("D*-PO: inconsistent g-values while extracting the path")
        return _result(self._model, idx, expansions, t0, self._name)

    def __repr__(self) -> str:
        h, w = self._occ.shape
        return (
            f"{type(self).__name__}(shape={h}x{w}, objectives={self.objectives}, "
            f"start={self._start}, goal={self._goal})"
        )


class WeightedSumDStar(DStarPO):
    """D* Lite on the normalised weighted sum of the objectives (the paper's
    D* baseline): :class:`DStarPO` without the Pareto filter, minimising
    ``sum_j w_j G_j / N_j``.

    Parameters
    ----------
    costmap, objectives, start, goal, origin : see :class:`DStarPO`.
    weights : sequence of float, optional
        One non-negative weight per objective; default 1 each.
    """

    _pareto = False
    _name = "dstar-lite"

    def __init__(
        self, costmap, objectives=DEFAULT_OBJECTIVES, *, weights=None, start=None, goal=None, origin=None
    ):
        self._setup(costmap, objectives, start, goal, origin, weights=weights)


# ---------------------------------------------------------------------------
# one entry point
# ---------------------------------------------------------------------------

#: Names of the planners :func:`plan` dispatches to: the grid family of the
#: planner registry (:data:`gapath.planners.PLANNERS`).
PLANNERS = planner_names("grid")


def plan(
    costmap,
    planner: str = "dstar-po",
    objectives=DEFAULT_OBJECTIVES,
    *,
    priority=None,
    weights=None,
    start=None,
    goal=None,
    baseline="weighted",
) -> ParetoPlanResult:
    """Plan one path with a named planner.

    Parameters
    ----------
    costmap : :class:`gapath.costmap.Costmap`
    planner : {"astar", "dstar-lite", "astar-po", "dstar-po"}
        Weighted-sum A*, weighted-sum D* Lite, A*-PO or D*-PO.
    objectives, start, goal : see :func:`astar_po`.
    priority : Pareto planners' priority (see :func:`astar_po`).
    weights : weighted-sum planners' weights.
    baseline : {"weighted", "renormalised"}
        The composite of ``astar`` and ``dstar-lite``: ``"weighted"``
        (static normalisers; A* and D* Lite, exact) or ``"renormalised"``
        (Lavin's A* and D*: renormalised over the open list at every step;
        ``dstar-lite`` then runs :func:`renormalised_dstar`, the first search
        of Stentz's D*, not D* Lite). Ignored by the Pareto planners.

    Raises
    ------
    ConfigError
        On an unknown planner or bad settings.
    NoPathError
        If the goal cannot be reached.
    """
    _check_baseline(baseline)
    if planner == "astar":
        return weighted_sum_astar(
            costmap, objectives, weights=weights, start=start, goal=goal, baseline=baseline
        )
    if planner == "dstar-lite" and baseline == "renormalised":
        return renormalised_dstar(costmap, objectives, weights=weights, start=start, goal=goal)
    if planner == "astar-po":
        return astar_po(costmap, objectives, priority=priority, start=start, goal=goal)
    if planner == "dstar-lite":
        return WeightedSumDStar(costmap, objectives, weights=weights, start=start, goal=goal).plan()
    if planner == "dstar-po":
        return DStarPO(costmap, objectives, priority=priority, start=start, goal=goal).plan()
    raise ConfigError(f"unknown planner {planner!r}; expected one of {', '.join(PLANNERS)}")
