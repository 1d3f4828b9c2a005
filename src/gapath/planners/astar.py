"""A* on the 8-connected grid of a :class:`~gapath.workspace.Workspace`.

The search runs in a numba kernel on the raveled grid, with per-thread
scratch arrays that are reused between calls (only the cells a search touched
are reset) and an indexed binary heap that holds back a new entry that would
be popped next instead of pushing it (:func:`gapath.openlist.open_push`;
the expansion order is that of a plain heap). Moves follow SPEC: 8-connected,
straight step 1 and diagonal step sqrt(2) (times ``cell_size``); with
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

import math
import threading
import time
from dataclasses import dataclass

import numba
import numpy as np

from gapath.errors import ConfigError, NoPathError
from gapath.grid import DC, DR, SQRT2, STEP, check_free_cell, move_mask
from gapath.openlist import NOT_HELD, open_decrease, open_pop, open_push
from gapath.planners._grid import HEURISTICS, layer_path_cost
from gapath.planners._grid import (
    heuristic as _heuristic,
)

__all__ = ["PlanResult", "astar"]

_UNSEEN = 0
_CLOSED = -1
_NO_COST = np.zeros((1, 1))


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
        return (
            f"PlanResult(cells={len(self.path)}, cost={self.cost!r}, "
            f"length={self.length!r}, expansions={self.expansions}, "
            f"seconds={self.seconds:.6f})"
        )


@numba.njit(cache=True)
def _astar_kernel(
    occ2d, cost2d, use_cost, s, t, corner_cutting, weight, hkind, state, g, came, heap, touched
):
    """A* from cell ``s`` to cell ``t`` (row-major indices) of the grid ``occ2d``.

    ``cost2d`` is the cost layer (unused unless ``use_cost``). The per-cell
    scratch arrays are reused between calls:

    * ``state[v]``: ``_UNSEEN`` (0), ``_CLOSED``, or while ``v`` is open its
      place in the open list (see :func:`~gapath.openlist.open_push`);
      it is 0 everywhere on entry and reset to 0 for every cell in
      ``touched`` before returning, so ``g`` and ``came`` need no clearing;
    * ``g[v]``: best known cost from the start; ``came[v]``: the move (0..7)
      that reached ``v`` with it;
    * ``heap``: the open list, ordered by ``(f, weight * h, cell)``.

    Returns ``(path, n_straight, n_diagonal, expansions)``: ``path``
    (``(row, col)`` cells, start first) is empty when the goal is
    unreachable; ``expansions`` is -1 if the start or the goal is blocked.
    """
    h, w = occ2d.shape
    occ = occ2d.ravel()  # views, cell v at [v]
    cost = cost2d.ravel()
    if occ[s] or occ[t]:
        return np.empty((0, 2), dtype=np.int64), 0, 0, -1
    offset = np.empty(8, dtype=np.int64)  # index step of each move
    for k in range(8):
        offset[k] = DR[k] * w + DC[k]
    tr = t // w
    tc = t - tr * w

    g[s] = 0.0
    touched[0] = s
    n_touched = 1
    hs = weight * _heuristic(hkind, s // w, s % w, tr, tc)
    size, held = open_push(heap, state, 0, NOT_HELD, hs, hs, s)
    expansions = 0
    reached = False

    while True:
        u, size, held = open_pop(heap, state, size, held)
        if u < 0:  # open list exhausted
            break
        state[u] = _CLOSED
        expansions += 1
        if u == t:
            reached = True
            break
        ur = u // w
        uc = u - ur * w
        moves = move_mask(occ, h, w, ur, uc, corner_cutting)
        gu = g[u]
        for k in range(8):
            if not (moves >> k) & 1:
                continue
            v = u + offset[k]
            sv = state[v]
            if sv == _CLOSED:
                continue
            step = STEP[k]
            if use_cost:
                step *= 1.0 + 0.5 * (cost[u] + cost[v])
            ng = gu + step
            if sv != _UNSEEN and ng >= g[v]:  # open, and no shorter way
                continue
            g[v] = ng
            came[v] = k
            hv = weight * _heuristic(hkind, ur + DR[k], uc + DC[k], tr, tc)
            if sv == _UNSEEN:
                touched[n_touched] = v
                n_touched += 1
                size, held = open_push(heap, state, size, held, ng + hv, hv, v)
            else:
                held = open_decrease(heap, state, held, ng + hv, hv, v)

    for i in range(n_touched):  # leave state all _UNSEEN
        state[touched[i]] = _UNSEEN
    if not reached:
        return np.empty((0, 2), dtype=np.int64), 0, 0, expansions
    m = 1
    v = t
    while v != s:
        v -= offset[came[v]]
        m += 1
    path = np.empty((m, 2), dtype=np.int64)
    n_diagonal = 0
    v = t
    for i in range(m - 1, -1, -1):
        vr = v // w
        path[i, 0] = vr
        path[i, 1] = v - vr * w
        if i > 0:
            k = came[v]
            n_diagonal += k & 1
            v -= offset[k]
    return path, m - 1 - n_diagonal, n_diagonal, expansions


class _Scratch(threading.local):
    """Per-thread search arrays, grown on demand and reused across calls
    (allocating and clearing them for every query would dominate short
    searches on large maps). The kernel leaves ``state`` all zero."""

    n = -1
    arrays: tuple = ()

    def get(self, n: int):
        if n > self.n:
            index = np.int32 if n < 2**31 - 1 else np.int64
            self.arrays = (
                np.zeros(n, index),  # state
                np.empty(n),  # g
                np.empty(n, np.uint8),  # came
                np.empty(3 * n),  # open list (heap)
                np.empty(n, index),
            )  # touched cells
            self.n = n
        return self.arrays


_scratch = _Scratch()


def _cell_index(value, name: str, occ: np.ndarray) -> int:
    """Row-major index of the cell ``value``; raises like :func:`gapath.grid.check_free_cell`,
    except that obstacles are checked by the kernel (fast path for a tuple
    of two ``int``)."""
    h, w = occ.shape
    if type(value) is tuple and len(value) == 2:
        r, c = value
        if type(r) is int and type(c) is int and 0 <= r < h and 0 <= c < w:
            return r * w + c
    r, c = check_free_cell(value, name, occ)
    return r * w + c


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
            f"cost must be an array of shape {tuple(shape)}, got {type(cost).__name__}"
        ) from None
    if arr.dtype == np.bool_ or not (
        np.issubdtype(arr.dtype, np.integer) or np.issubdtype(arr.dtype, np.floating)
    ):
        raise ConfigError(f"cost must be a numeric array, got dtype {arr.dtype}")
    if arr.shape != tuple(shape):
        raise ConfigError(f"cost must have the grid's shape {tuple(shape)}, got shape {arr.shape}")
    arr = np.ascontiguousarray(arr, dtype=np.float64)
    bad = ~np.isfinite(arr)
    if bad.any():
        r, c = np.argwhere(bad)[0]
        raise ConfigError(
            f"cost must be finite, got {float(arr[r, c])!r} at (row {r}, col {c}) "
            f"(mark impassable cells as obstacles instead)"
        )
    neg = arr < 0
    if neg.any():
        r, c = np.argwhere(neg)[0]
        raise ConfigError(f"cost must be non-negative, got {float(arr[r, c])!r} at (row {r}, col {c})")
    return arr


def _check_weight(weight) -> float:
    try:
        wv = float(weight)
    except (TypeError, ValueError):
        raise ConfigError(f"weight must be a non-negative number, got {weight!r}") from None
    if not math.isfinite(wv) or wv < 0:
        raise ConfigError(f"weight must be a finite number >= 0, got {weight!r}")
    return wv


def astar(
    workspace, start=None, goal=None, *, cost=None, weight: float = 1.0, heuristic: str = "octile"
) -> PlanResult:
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
    occ = workspace.occ  # C-contiguous read-only bool (Workspace)
    start = workspace.start if start is None else start
    goal = workspace.goal if goal is None else goal
    s = _cell_index(start, "start", occ)
    t = _cell_index(goal, "goal", occ)
    wv = weight if type(weight) is float and 0.0 <= weight < math.inf else _check_weight(weight)
    hkind = HEURISTICS.get(heuristic) if isinstance(heuristic, str) else None
    if hkind is None:
        raise ConfigError(f"heuristic must be one of {', '.join(map(repr, HEURISTICS))}, got {heuristic!r}")
    if cost is None:
        layer = _NO_COST
        use_cost = False
    else:
        layer = check_cost_layer(cost, occ.shape)
        use_cost = True
    path, n_straight, n_diagonal, expansions = _astar_kernel(
        occ, layer, use_cost, s, t, workspace.corner_cutting, wv, hkind, *_scratch.get(occ.size)
    )
    if len(path) == 0:
        src = check_free_cell(start, "start", occ)  # raises if on an obstacle
        dst = check_free_cell(goal, "goal", occ)
        h, w = occ.shape
        rule = "allowed" if workspace.corner_cutting else "not allowed"
        raise NoPathError(
            f"no path from start {src} to goal {dst} on the {h}x{w} grid "
            f"(8-connected, corner cutting {rule}; the search closed {expansions} cells)"
        )
    cs = workspace.cell_size
    length = (n_straight + SQRT2 * n_diagonal) * cs  # as path_length (SPEC)
    total = layer_path_cost(path, layer) * cs if use_cost else length
    path.setflags(write=False)
    return PlanResult(
        path=path,
        cost=float(total),
        length=float(length),
        expansions=int(expansions),
        seconds=time.perf_counter() - t0,
    )
