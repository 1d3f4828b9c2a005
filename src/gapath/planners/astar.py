"""A* on the 8-connected grid of a :class:`~gapath.workspace.Workspace`.

The search runs in a numba kernel with an indexed binary heap in
preallocated arrays. Moves follow SPEC: 8-connected, straight step 1 and
diagonal step sqrt(2) (times ``cell_size``); with
``workspace.corner_cutting=False`` a diagonal move needs both orthogonally
adjacent cells free (the MovingAI convention).

Optional cost layer
    ``cost`` is an ``(H, W)`` array of non-negative finite numbers. A step
    from ``a`` to ``b`` then costs ``length(a, b) * (1 + (cost[a] + cost[b]) / 2)``:
    never less than its length, so the octile heuristic stays admissible and
    consistent, and the search stays optimal. A zero layer gives the plain
    lengths.

Tie-breaking
    Open cells are ordered by ``f = g + weight * h``, then by the smaller
    ``weight * h`` (deeper cells first), then by the smaller row-major cell
    index ``row * W + col``. Neighbours are generated in the fixed order
    E, NE, N, NW, W, SW, S, SE and a cell's parent changes only on a strictly
    smaller ``g``. Results are therefore deterministic.
"""

from __future__ import annotations

import threading
import time
from dataclasses import dataclass

import numba
import numpy as np

from gapath.errors import ConfigError, NoPathError
from gapath.planners._grid import (
    DC,
    DR,
    HEURISTICS,
    STEP,
    check_cell,
    heap_decrease,
    heap_pop,
    heap_push,
    heuristic as _heuristic,
    layer_path_cost,
    path_length,
)

__all__ = ["PlanResult", "astar"]

_CLOSED = -2


@dataclass(frozen=True, eq=False)
class PlanResult:
    """Result of a single-path planner.

    Attributes
    ----------
    path : (m, 2) int64 array
        Cells ``(row, col)`` from the start to the goal (read-only).
    cost : float
        Cost of the path: its length, or with a cost layer the sum of the
        step costs (see :mod:`gapath.planners.astar`), times ``cell_size``.
    length : float
        Euclidean length ``(n_straight + sqrt(2) * n_diagonal) * cell_size``.
    expansions : int
        Number of cells the search expanded (for D* Lite: during this call).
    seconds : float
        Wall-clock time of the call.
    """

    path: np.ndarray
    cost: float
    length: float
    expansions: int
    seconds: float

    def __repr__(self) -> str:
        return (f"PlanResult(cells={len(self.path)}, cost={self.cost!r}, "
                f"length={self.length!r}, expansions={self.expansions}, "
                f"seconds={self.seconds:.6f})")


@numba.njit(cache=True)
def _astar_kernel(pocc, pcost, use_cost, w2, s, t, corner_cutting, weight, hkind,
                  stamp, gen, pos, g, parent, hnode, hk1, hk2):
    """A* from cell ``s`` to cell ``t`` on a padded, flattened grid.

    ``pocc`` is the occupancy with a one-cell blocked border, raveled (row
    length ``w2 = W + 2``), so neighbours need no bounds checks; ``pcost`` is
    the cost layer padded the same way (unused unless ``use_cost``). The
    scratch arrays (``stamp`` ... ``hk2``, at least ``pocc.size`` long) are
    reused between calls without being cleared: a cell's entries are valid
    only when ``stamp[cell] == gen``, and ``gen`` is new for every call.

    Returns ``(path, g_goal, expansions)``; ``path`` (unpadded ``(row, col)``
    cells) is empty when the goal is unreachable.
    """
    offset = np.empty(8, dtype=np.int64)
    for k in range(8):
        offset[k] = DR[k] * w2 + DC[k]
    tr = t // w2
    tc = t - tr * w2

    stamp[s] = gen
    g[s] = 0.0
    parent[s] = -1
    sr = s // w2
    hs = weight * _heuristic(hkind, sr, s - sr * w2, tr, tc)
    size = heap_push(hnode, hk1, hk2, pos, 0, s, hs, hs)
    expansions = 0
    reached = False

    while size > 0:
        u, size = heap_pop(hnode, hk1, hk2, pos, size)
        pos[u] = _CLOSED
        expansions += 1
        if u == t:
            reached = True
            break
        ur = u // w2
        uc = u - ur * w2
        gu = g[u]
        for k in range(8):
            v = u + offset[k]
            if pocc[v]:
                continue
            if (k & 1) and not corner_cutting:        # diagonal: both sides free
                if pocc[u + DR[k] * w2] or pocc[u + DC[k]]:
                    continue
            seen = stamp[v] == gen
            if seen and pos[v] == _CLOSED:
                continue
            step = STEP[k]
            if use_cost:
                step *= 1.0 + 0.5 * (pcost[u] + pcost[v])
            ng = gu + step
            if not seen:
                stamp[v] = gen
                g[v] = ng
                parent[v] = u
                hv = weight * _heuristic(hkind, ur + DR[k], uc + DC[k], tr, tc)
                size = heap_push(hnode, hk1, hk2, pos, size, v, ng + hv, hv)
            elif ng < g[v]:
                g[v] = ng
                parent[v] = u
                hv = weight * _heuristic(hkind, ur + DR[k], uc + DC[k], tr, tc)
                heap_decrease(hnode, hk1, hk2, pos, v, ng + hv, hv)

    if not reached:
        return np.empty((0, 2), dtype=np.int64), np.inf, expansions
    m = 0
    v = t
    while v != -1:
        m += 1
        v = parent[v]
    path = np.empty((m, 2), dtype=np.int64)
    v = t
    for i in range(m - 1, -1, -1):
        path[i, 0] = v // w2 - 1
        path[i, 1] = v % w2 - 1
        v = parent[v]
    return path, g[t], expansions


class _Scratch(threading.local):
    """Per-thread search arrays, grown on demand and reused across calls
    (allocating and clearing them for every query would dominate short
    searches on large maps)."""

    def __init__(self):
        self.n = 0
        self.gen = 0
        self.arrays = ()

    def get(self, n: int):
        if n > self.n:
            self.arrays = (np.zeros(n, np.int64),              # stamp
                           np.empty(n, np.int64),               # pos (heap slot or closed)
                           np.empty(n),                         # g
                           np.empty(n, np.int64),               # parent
                           np.empty(n, np.int64),               # heap: nodes
                           np.empty(n), np.empty(n))            # heap: f, weight * h
            self.n = n
            self.gen = 0
        self.gen += 1
        return self.gen, self.arrays


_scratch = _Scratch()


def _padded(arr: np.ndarray, fill) -> np.ndarray:
    """``arr`` with a one-cell border of ``fill``, raveled."""
    h, w = arr.shape
    out = np.full((h + 2, w + 2), fill, dtype=arr.dtype)
    out[1:-1, 1:-1] = arr
    return out.ravel()


def check_cost_layer(cost, shape) -> np.ndarray:
    """Validate a cost layer; return it as a C-contiguous float64 array.

    Raises
    ------
    ConfigError
        If ``cost`` is not numeric, does not have the grid's shape, or holds
        NaN, infinite or negative values (the first offending cell is named).
    """
    try:
        arr = np.asarray(cost)
    except Exception:  # pragma: no cover - exotic objects
        raise ConfigError(
            f"cost must be an array of shape {tuple(shape)}, got {type(cost).__name__}") from None
    if arr.dtype == np.bool_ or not (np.issubdtype(arr.dtype, np.integer)
                                     or np.issubdtype(arr.dtype, np.floating)):
        raise ConfigError(f"cost must be a numeric array, got dtype {arr.dtype}")
    if arr.shape != tuple(shape):
        raise ConfigError(
            f"cost must have the grid's shape {tuple(shape)}, got shape {arr.shape}")
    arr = np.ascontiguousarray(arr, dtype=np.float64)
    bad = ~np.isfinite(arr)
    if bad.any():
        r, c = np.argwhere(bad)[0]
        raise ConfigError(
            f"cost must be finite, got {float(arr[r, c])!r} at (row {r}, col {c}) "
            f"(mark impassable cells as obstacles instead)")
    neg = arr < 0
    if neg.any():
        r, c = np.argwhere(neg)[0]
        raise ConfigError(
            f"cost must be non-negative, got {float(arr[r, c])!r} at (row {r}, col {c})")
    return arr


def _check_weight(weight) -> float:
    try:
        wv = float(weight)
    except (TypeError, ValueError):
        raise ConfigError(f"weight must be a non-negative number, got {weight!r}") from None
    if not np.isfinite(wv) or wv < 0:
        raise ConfigError(f"weight must be a finite number >= 0, got {weight!r}")
    return wv


def astar(workspace, start=None, goal=None, *, cost=None, weight: float = 1.0,
          heuristic: str = "octile") -> PlanResult:
    """Shortest 8-connected path by A*.

    Parameters
    ----------
    workspace : Workspace
        The grid (``occ``), the default start and goal, ``cell_size`` and the
        corner rule ``corner_cutting``.
    start, goal : (row, col), optional
        Override the workspace's start and goal. ``start == goal`` gives a
        one-cell path of cost 0.
    cost : (H, W) array of float, optional
        Cost layer, non-negative and finite. A step from ``a`` to ``b`` costs
        ``length(a, b) * (1 + (cost[a] + cost[b]) / 2)``; without a layer a
        step costs its length.
    weight : float, default 1.0
        Heuristic weight (weighted A*). Values in ``[0, 1]`` keep the result
        optimal (``0`` is Dijkstra); ``weight > 1`` usually expands fewer
        cells and returns a path at most ``weight`` times the optimum (cells
        are not reopened).
    heuristic : {"octile", "euclidean", "chebyshev", "zero"}, default "octile"
        Distance estimate to the goal, in cell units. All are admissible and
        consistent on the 8-connected grid; octile is the tightest.

    Returns
    -------
    PlanResult
        ``path`` from start to goal, its ``cost`` and Euclidean ``length``
        (both times ``cell_size``), the number of ``expansions`` and
        ``seconds``.

    Raises
    ------
    ConfigError
        If start or goal is outside the grid or on an obstacle, if ``cost``
        has the wrong shape or holds NaN, infinite or negative values, or if
        ``weight`` or ``heuristic`` is invalid.
    NoPathError
        If the goal cannot be reached from the start.

    See Also
    --------
    gapath.planners.dstar_lite.DStarLite : incremental replanning.

    Notes
    -----
    Ties are broken deterministically: by ``f``, then smaller ``weight * h``,
    then smaller row-major index; see :mod:`gapath.planners.astar`.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> occ = np.zeros((3, 3), bool); occ[1, 1] = True
    >>> res = astar(Workspace(occ, corner_cutting=False))
    >>> res.path.tolist()
    [[2, 0], [1, 0], [0, 0], [0, 1], [0, 2]]
    >>> res.cost
    4.0
    """
    t0 = time.perf_counter()
    occ = workspace.occ
    src = check_cell(workspace.start if start is None else start, "start", occ)
    dst = check_cell(workspace.goal if goal is None else goal, "goal", occ)
    wv = _check_weight(weight)
    if not isinstance(heuristic, str) or heuristic not in HEURISTICS:
        raise ConfigError(
            f"heuristic must be one of {', '.join(map(repr, HEURISTICS))}, got {heuristic!r}")
    if cost is None:
        layer = np.zeros((1, 1))
        use_cost = False
    else:
        layer = check_cost_layer(cost, occ.shape)
        use_cost = True
    w2 = occ.shape[1] + 2
    pocc = _padded(np.asarray(occ, dtype=np.bool_), True)
    pcost = _padded(layer, 0.0) if use_cost else layer.ravel()
    gen, scratch = _scratch.get(pocc.size)
    path, _, expansions = _astar_kernel(
        pocc, pcost, use_cost, w2, (src[0] + 1) * w2 + src[1] + 1, (dst[0] + 1) * w2 + dst[1] + 1,
        bool(workspace.corner_cutting), wv, HEURISTICS[heuristic], scratch[0], gen, *scratch[1:])
    if len(path) == 0:
        rule = "allowed" if workspace.corner_cutting else "not allowed"
        raise NoPathError(
            f"no path from start {src} to goal {dst} on the {occ.shape[0]}x{occ.shape[1]} grid "
            f"(8-connected, corner cutting {rule}; the search closed {expansions} cells)")
    cs = float(workspace.cell_size)
    length = path_length(path, cs)
    total = layer_path_cost(path, layer) * cs if use_cost else length
    path.setflags(write=False)
    return PlanResult(path=path, cost=float(total), length=float(length),
                      expansions=int(expansions), seconds=time.perf_counter() - t0)
