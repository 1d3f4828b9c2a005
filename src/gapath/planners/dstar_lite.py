"""D* Lite: incremental replanning on the 8-connected grid.

This is the *optimized* D* Lite of S. Koenig and M. Likhachev, "D* Lite",
AAAI 2002 (the version with the key modifier ``km``). The search
runs backwards, from the goal to the robot's cell ``s_start``: ``g(s)`` and
``rhs(s)`` estimate the cost from ``s`` to the goal, and the priority queue
``U`` is ordered by the keys

    ``CalculateKey(s) = [min(g(s), rhs(s)) + h(s_start, s) + km; min(g(s), rhs(s))]``

with the heuristic ``h`` (the octile distance, see :data:`H_FACTOR`). When
cells become blocked or free, only the edges that change are repaired (the
``rhs`` of their sources) and ``ComputeShortestPath`` re-expands the part of
the search that is affected; when the robot moves, ``km`` grows by
``h(s_last, s_start)`` so that the keys already in ``U`` stay lower bounds.

Graph
    Vertices are the grid cells; ``c(u, v)`` is the step length (1 or
    sqrt(2), in cell units) for 8-adjacent ``u``, ``v`` when both are free and,
    with ``corner_cutting=False``, a diagonal step has both orthogonally
    adjacent cells free; otherwise ``c(u, v) = inf``. The graph is
    undirected, so ``Succ(s) = Pred(s)`` = the 8 neighbours.

The procedures below (numba kernels) follow the paper's pseudocode and use
its names; the comments quote the pseudocode lines. The priority queue is the
indexed binary heap of :mod:`gapath.planners._grid`, ordered by the key and
then by the row-major cell index (deterministic ties).
"""

from __future__ import annotations

import time

import numba
import numpy as np

from gapath.errors import NoPathError
from gapath.grid import DC, DR, STEP, can_step, check_free_cell, octile, path_length
from gapath.planners._grid import heap_pop, heap_push, heap_remove, heap_update
from gapath.planners._incremental import IncrementalGridPlanner
from gapath.planners.astar import PlanResult
from gapath.workspace import Workspace

__all__ = ["DStarLite"]

INF = np.inf

#: ``h`` is the octile distance times this factor. Keys are floats: on a
#: shortest path through straight stretches ``g(s) + octile(s_start, s)`` is
#: mathematically *equal* to ``g(s_start)``, and a rounding error of one ulp
#: would put such a vertex's key above the start's key, so that
#: ComputeShortestPath could stop with it inconsistent. Shrinking ``h`` by a
#: relative 1e-9 (far above the rounding of path costs below ~1e6 cell units,
#: far below the smallest gap ~1e-5 between different path costs on these
#: grids) keeps those keys strictly below; ``h`` stays admissible and
#: consistent, and the metric properties that ``km`` relies on hold.
H_FACTOR = 1.0 - 1e-9


# ---------------------------------------------------------------------------
# the graph
# ---------------------------------------------------------------------------


@numba.njit(cache=True, inline="always")
def _c(occ, corner_cutting, ur, uc, k):
    """c(u, v) for the neighbour ``v`` of ``u`` in direction ``k``."""
    if occ[ur, uc] or not can_step(occ, ur, uc, DR[k], DC[k], corner_cutting):
        return INF
    return STEP[k]


@numba.njit(cache=True, inline="always")
def _neighbour(u, k, h, w):
    """Index of the neighbour of cell ``u`` in direction ``k`` (-1 if outside)."""
    ur = u // w
    uc = u - ur * w
    vr = ur + DR[k]
    vc = uc + DC[k]
    if vr < 0 or vr >= h or vc < 0 or vc >= w:
        return -1
    return vr * w + vc


@numba.njit(cache=True)
def _min_succ(occ, cc, g, u):
    """min over s' in Succ(u) of c(u, s') + g(s')."""
    h, w = occ.shape
    ur = u // w
    uc = u - ur * w
    best = INF
    for k in range(8):
        v = _neighbour(u, k, h, w)
        if v < 0:
            continue
        cand = _c(occ, cc, ur, uc, k) + g[v]
        if cand < best:
            best = cand
    return best


# ---------------------------------------------------------------------------
# the priority queue U and the keys
# ---------------------------------------------------------------------------


@numba.njit(cache=True, inline="always")
def _key_less(a1, a2, b1, b2):
    """Lexicographic ``[a1; a2] < [b1; b2]``."""
    return a1 < b1 or (a1 == b1 and a2 < b2)


@numba.njit(cache=True, inline="always")
def _h(a, b, w):
    """h(a, b) between the cells with indices ``a`` and ``b`` (``H_FACTOR`` x octile)."""
    return H_FACTOR * octile(a // w, a % w, b // w, b % w)


@numba.njit(cache=True, inline="always")
def _calculate_key(g, rhs, s, start, w, km):
    """return [min(g(s), rhs(s)) + h(s_start, s) + km; min(g(s), rhs(s))]."""
    m = min(g[s], rhs[s])
    return m + _h(start, s, w) + km, m


@numba.njit(cache=True)
def _update_vertex(u, g, rhs, hnode, hk1, hk2, pos, size, start, w, km):
    """UpdateVertex(u); returns the new size of U."""
    in_u = pos[u] >= 0
    if g[u] != rhs[u] and in_u:  # U.Update(u, CalculateKey(u))
        key1, key2 = _calculate_key(g, rhs, u, start, w, km)
        heap_update(hnode, hk1, hk2, pos, size, u, key1, key2)
    elif g[u] != rhs[u] and not in_u:  # U.Insert(u, CalculateKey(u))
        key1, key2 = _calculate_key(g, rhs, u, start, w, km)
        size = heap_push(hnode, hk1, hk2, pos, size, u, key1, key2)
    elif g[u] == rhs[u] and in_u:  # U.Remove(u)
        size = heap_remove(hnode, hk1, hk2, pos, size, u)
    return size


@numba.njit(cache=True)
def _compute_shortest_path(occ, cc, g, rhs, hnode, hk1, hk2, pos, size, start, goal, km):
    """ComputeShortestPath(); returns ``(size, expansions)``.

    An expansion is a vertex taken from U whose g-value is then changed
    (made consistent, or set to infinity).
    """
    h, w = occ.shape
    expansions = 0
    while True:
        # while (U.TopKey() < CalculateKey(s_start) OR rhs(s_start) > g(s_start))
        if size > 0:
            top1 = hk1[0]
            top2 = hk2[0]
        else:
            top1 = INF
            top2 = INF
        s1, s2 = _calculate_key(g, rhs, start, start, w, km)
        if not (_key_less(top1, top2, s1, s2) or rhs[start] > g[start]):
            break
        u = hnode[0]  # u = U.Top()
        kold1 = top1  # k_old = U.TopKey()
        kold2 = top2
        knew1, knew2 = _calculate_key(g, rhs, u, start, w, km)  # k_new = CalculateKey(u)
        if _key_less(kold1, kold2, knew1, knew2):  # if (k_old < k_new)
            # U.Update(u, k_new)
            heap_update(hnode, hk1, hk2, pos, size, u, knew1, knew2)
        elif g[u] > rhs[u]:  # else if (g(u) > rhs(u))
            expansions += 1
            g[u] = rhs[u]  # g(u) = rhs(u)
            _, size = heap_pop(hnode, hk1, hk2, pos, size)  # U.Remove(u)
            ur = u // w
            uc = u - ur * w
            for k in range(8):  # for all s in Pred(u)
                s = _neighbour(u, k, h, w)
                if s < 0:
                    continue
                if s != goal:  # if (s != s_goal) rhs(s) = min(rhs(s), c(s,u) + g(u))
                    cand = _c(occ, cc, ur, uc, k) + g[u]
                    if cand < rhs[s]:
                        rhs[s] = cand
                # UpdateVertex(s)
                size = _update_vertex(s, g, rhs, hnode, hk1, hk2, pos, size, start, w, km)
        else:  # else
            expansions += 1
            g_old = g[u]  # g_old = g(u)
            g[u] = INF  # g(u) = inf
            ur = u // w
            uc = u - ur * w
            for k in range(8):  # for all s in Pred(u)
                s = _neighbour(u, k, h, w)
                if s < 0:
                    continue
                if rhs[s] == _c(occ, cc, ur, uc, k) + g_old:  # if (rhs(s) = c(s,u) + g_old)
                    if s != goal:  # if (s != s_goal) rhs(s) = min_s' c(s,s') + g(s')
                        rhs[s] = _min_succ(occ, cc, g, s)
                # UpdateVertex(s)
                size = _update_vertex(s, g, rhs, hnode, hk1, hk2, pos, size, start, w, km)
            # ... and s = u: there are no self loops, so rhs(u) does not
            # depend on g(u); only UpdateVertex(u)
            size = _update_vertex(u, g, rhs, hnode, hk1, hk2, pos, size, start, w, km)
    return size, expansions


@numba.njit(cache=True)
def _update_changed_edges(occ_old, occ, cc, sources, g, rhs, hnode, hk1, hk2, pos, size, start, goal, km):
    """for all directed edges (u, v) with changed edge costs.

    ``sources`` lists every cell ``u`` whose outgoing edges may have changed;
    ``c_old`` is read from ``occ_old`` and the new ``c(u, v)`` from ``occ``.
    Returns the new size of U.
    """
    h, w = occ.shape
    for i in range(sources.shape[0]):
        u = sources[i]
        ur = u // w
        uc = u - ur * w
        for k in range(8):
            v = _neighbour(u, k, h, w)
            if v < 0:
                continue
            c_old = _c(occ_old, cc, ur, uc, k)  # c_old = c(u, v)
            c_new = _c(occ, cc, ur, uc, k)  # update c(u, v)
            if c_old == c_new:
                continue
            if c_old > c_new:  # if (c_old > c(u, v))
                if u != goal:  # if (u != s_goal) rhs(u) = min(rhs(u), c(u,v) + g(v))
                    cand = c_new + g[v]
                    if cand < rhs[u]:
                        rhs[u] = cand
            elif rhs[u] == c_old + g[v]:  # else if (rhs(u) = c_old + g(v))
                if u != goal:  # if (u != s_goal) rhs(u) = min_s' c(u,s') + g(s')
                    rhs[u] = _min_succ(occ, cc, g, u)
            # UpdateVertex(u)
            size = _update_vertex(u, g, rhs, hnode, hk1, hk2, pos, size, start, w, km)
    return size


@numba.njit(cache=True)
def _extract_path(occ, cc, g, start, goal):
    """Follow argmin over s' of c(s, s') + g(s') from s_start to s_goal.

    Returns an (m, 2) array of cells, or an empty array if a step finds no
    finite successor (no path). Ties go to the first direction in the fixed
    order E, NE, N, NW, W, SW, S, SE.
    """
    h, w = occ.shape
    n = h * w
    cells = np.empty(n + 1, dtype=np.int64)
    cells[0] = start
    m = 1
    s = start
    while s != goal:
        if m > n:  # cannot happen with consistent g
            return np.empty((0, 2), dtype=np.int64)
        sr = s // w
        sc = s - sr * w
        best = INF
        nxt = -1
        for k in range(8):
            v = _neighbour(s, k, h, w)
            if v < 0:
                continue
            cand = _c(occ, cc, sr, sc, k) + g[v]
            if cand < best:
                best = cand
                nxt = v
        if nxt < 0:
            return np.empty((0, 2), dtype=np.int64)
        cells[m] = nxt
        m += 1
        s = nxt
    path = np.empty((m, 2), dtype=np.int64)
    for i in range(m):
        path[i, 0] = cells[i] // w
        path[i, 1] = cells[i] % w
    return path


# ---------------------------------------------------------------------------
# the planner
# ---------------------------------------------------------------------------


class DStarLite(IncrementalGridPlanner):
    """Incremental shortest paths under changing obstacles (D* Lite).

    The planner keeps its own copy of the occupancy grid. Cells are blocked or
    freed with :meth:`update_cells`, the robot (the start) is advanced with
    :meth:`move_to`, and :meth:`replan` repairs the previous search instead
    of starting over. Every result is an optimal path of the current map:
    its cost equals that of a fresh :func:`~gapath.planners.astar.astar` on
    ``planner.workspace``.

    Parameters
    ----------
    workspace : Workspace
        The initial grid, ``cell_size`` and corner rule (``corner_cutting``).
    start, goal : (row, col), optional
        Override the workspace's start (the robot's cell) and goal.

    Raises
    ------
    ConfigError
        If start or goal is outside the grid or on an obstacle.

    See Also
    --------
    gapath.planners.astar.astar : one-shot search.

    Notes
    -----
    S. Koenig and M. Likhachev, "D* Lite", Proc. AAAI 2002, pp. 476-483
    (the optimized version). ``PlanResult.expansions`` counts the
    vertices whose g-value changed during that call.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> planner = DStarLite(Workspace(np.zeros((5, 5), bool)))
    >>> planner.plan().cost
    5.656854249492381
    >>> planner.update_cells([(2, 2)], blocked=True)
    1
    >>> round(planner.replan().cost, 6)
    6.242641
    """

    def __init__(self, workspace, start=None, goal=None):
        occ = np.array(workspace.occ, dtype=np.bool_, order="C", copy=True)
        self._occ = occ
        self._start = check_free_cell(workspace.start if start is None else start, "start", occ)
        self._goal = check_free_cell(workspace.goal if goal is None else goal, "goal", occ)
        self.cell_size = float(workspace.cell_size)
        self.corner_cutting = bool(workspace.corner_cutting)
        self.name = getattr(workspace, "name", "workspace")
        n = occ.size
        self._g = np.empty(n)
        self._rhs = np.empty(n)
        self._pos = np.empty(n, dtype=np.int64)  # slot of a cell in U, -1 if not in U
        self._hnode = np.empty(n, dtype=np.int64)  # U: cells in heap order
        self._hk1 = np.empty(n)  # ... and their keys
        self._hk2 = np.empty(n)
        self._size = 0
        self._km = 0.0
        self._last = self._start
        self._initialized = False

    # -- state ------------------------------------------------------------
    @property
    def workspace(self):
        """The current map as a :class:`~gapath.workspace.Workspace`
        (start = the robot's cell)."""
        return Workspace(
            self._occ.copy(),
            self._start,
            self._goal,
            cell_size=self.cell_size,
            corner_cutting=self.corner_cutting,
            name=self.name,
        )

    # -- the paper's Main(); move_to and update_cells: IncrementalGridPlanner --
    def plan(self) -> PlanResult:
        """Search from scratch: Initialize(), then ComputeShortestPath().

        Returns
        -------
        PlanResult
            The path from the robot's cell to the goal.

        Raises
        ------
        NoPathError
            If the goal is unreachable (the planner stays usable).
        """
        t0 = time.perf_counter()
        self._g.fill(INF)  # rhs(s) = g(s) = inf
        self._rhs.fill(INF)
        self._pos.fill(-1)  # U = empty
        self._size = 0
        self._km = 0.0  # km = 0
        self._last = self._start  # s_last = s_start
        goal = self._index(self._goal)
        self._rhs[goal] = 0.0  # rhs(s_goal) = 0
        h_start_goal = _h(self._index(self._start), goal, self._occ.shape[1])
        self._size = heap_push(
            self._hnode, self._hk1, self._hk2, self._pos, 0, goal, h_start_goal, 0.0
        )  # U.Insert(s_goal, [h(s_start, s_goal); 0])
        self._initialized = True
        return self._search(t0)

    # -- helpers -----------------------------------------------------------
    def _repair_edges(self, occ_old, src) -> None:
        self._size = _update_changed_edges(
            occ_old,
            self._occ,
            self.corner_cutting,
            src,
            self._g,
            self._rhs,
            self._hnode,
            self._hk1,
            self._hk2,
            self._pos,
            self._size,
            self._index(self._start),
            self._index(self._goal),
            self._km,
        )

    def _sync_km(self) -> None:
        """km = km + h(s_last, s_start); s_last = s_start.

        Done whenever the robot has moved since the keys were last computed,
        so that the keys in U stay lower bounds of the current keys."""
        if self._last != self._start:
            self._km += _h(self._index(self._last), self._index(self._start), self._occ.shape[1])
            self._last = self._start

    def _search(self, t0: float) -> PlanResult:
        start = self._index(self._start)
        goal = self._index(self._goal)
        self._size, expansions = _compute_shortest_path(
            self._occ,
            self.corner_cutting,
            self._g,
            self._rhs,
            self._hnode,
            self._hk1,
            self._hk2,
            self._pos,
            self._size,
            start,
            goal,
            self._km,
        )
        if start == goal:
            path = np.array([self._start], dtype=np.int64)
        elif not np.isfinite(self._rhs[start]):
            rule = "allowed" if self.corner_cutting else "not allowed"
            h, w = self._occ.shape
            raise NoPathError(
                f"no path from start {self._start} to goal {self._goal} on the {h}x{w} grid "
                f"(8-connected, corner cutting {rule})"
            )
        else:
            path = _extract_path(self._occ, self.corner_cutting, self._g, start, goal)
            if len(path) == 0:  # pragma: no cover - would be a bug
                raise RuntimeError("D* Lite: inconsistent g-values while extracting the path")
        length = path_length(path, self.cell_size)
        path.setflags(write=False)
        return PlanResult(
            path=path,
            cost=float(length),
            length=float(length),
            expansions=int(expansions),
            seconds=time.perf_counter() - t0,
        )

    def __repr__(self) -> str:
        h, w = self._occ.shape
        return (
            f"DStarLite(shape={h}x{w}, start={self._start}, goal={self._goal}, "
            f"corner_cutting={self.corner_cutting}, km={self._km:g})"
        )
