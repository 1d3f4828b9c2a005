"""What the incremental planners (D* Lite, D*-PO) share: the robot's cell,
the goal, the changing occupancy grid and the checked cell updates.

A subclass keeps ``self._occ`` (the current grid, writable), ``self._start``,
``self._goal``, ``self._initialized`` and implements ``plan()``,
``_sync_km()`` (the paper's ``km = km + h(s_last, s_start)``),
``_repair_edges(occ_old, src)`` (UpdateVertex for every cell in ``src`` whose
outgoing edges may have changed) and ``_search(t0)`` (ComputeShortestPath and
the path's result, ``t0`` the ``time.perf_counter()`` at the call).
"""

from __future__ import annotations

import time

import numpy as np

from gapath.errors import ConfigError
from gapath.grid import check_free_cell


class IncrementalGridPlanner:
    """Base of planners that repair their search when cells change.

    A subclass sets ``_occ``, ``_start``, ``_goal`` and ``_initialized`` and
    provides ``_sync_km`` and ``_repair_edges``.
    """

    _occ: np.ndarray
    _start: tuple[int, int]
    _goal: tuple[int, int]
    _initialized: bool

    def _sync_km(self) -> None:
        """Bring ``km`` up to date with the robot's moves."""
        raise NotImplementedError

    def _repair_edges(self, occ_old: np.ndarray, src: np.ndarray) -> None:
        """Repair the search after the edges out of the cells ``src`` changed."""
        raise NotImplementedError

    @property
    def start(self) -> tuple[int, int]:
        """The robot's cell ``s_start``."""
        return self._start

    @property
    def goal(self) -> tuple[int, int]:
        return self._goal

    @property
    def occ(self) -> np.ndarray:
        """Read-only view of the current occupancy grid."""
        view = self._occ.view()
        view.setflags(write=False)
        return view

    def _index(self, cell) -> int:
        return cell[0] * self._occ.shape[1] + cell[1]

    def move_to(self, cell) -> None:
        """Move the robot to ``cell`` (the new ``s_start``).

        Usually ``cell`` is the next cell of the current path, but any free
        cell is accepted. ``km`` is updated lazily, at the next
        :meth:`update_cells` or :meth:`replan`, as in the paper.

        Raises
        ------
        ConfigError
            If ``cell`` is outside the grid or on an obstacle.
        """
        self._start = check_free_cell(cell, "cell", self._occ)

    def update_cells(self, cells, blocked=True) -> int:
        """Mark cells blocked (obstacle) or free.

        Parameters
        ----------
        cells : (row, col) or (k, 2) array-like of cells
        blocked : bool or (k,) array-like of bool
            New state of each cell (one value for all, or one per cell).

        Returns
        -------
        int
            Number of cells whose state actually changed.

        Raises
        ------
        ConfigError
            If a cell is outside the grid, if ``blocked`` does not match the
            cells, or if the robot's cell or the goal would be blocked.
        """
        arr, flags = self._checked_cells(cells, blocked)
        occ = self._occ
        changed = occ[arr[:, 0], arr[:, 1]] != flags
        if not changed.any():
            return 0
        arr, flags = arr[changed], flags[changed]
        occ_old = occ.copy()
        occ[arr[:, 0], arr[:, 1]] = flags  # scan graph: the new edge costs
        if not self._initialized:
            return int(len(arr))
        self._sync_km()
        self._repair_edges(occ_old, _neighbourhood(arr, occ.shape))
        return int(len(arr))

    def replan(self):
        """Repair the previous search after :meth:`update_cells` /
        :meth:`move_to` and return the new path (ComputeShortestPath()).
        The first call without a previous ``plan()`` plans from scratch.

        Raises
        ------
        NoPathError
            If the goal is unreachable (the planner stays usable).
        """
        if not self._initialized:
            return self.plan()
        t0 = time.perf_counter()
        self._sync_km()
        return self._search(t0)

    def _checked_cells(self, cells, blocked) -> tuple[np.ndarray, np.ndarray]:
        h, w = self._occ.shape
        try:
            arr = np.asarray(cells, dtype=np.float64)
        except (TypeError, ValueError):
            raise ConfigError(f"cells must be (row, col) pairs of integers, got {cells!r}") from None
        if arr.ndim == 1 and arr.shape[0] == 2:
            arr = arr[None, :]
        if arr.ndim != 2 or arr.shape[1] != 2 or not np.all(np.isfinite(arr)) or np.any(arr != np.round(arr)):
            raise ConfigError(f"cells must be (row, col) pairs of integers, got {cells!r}")
        arr = arr.astype(np.int64)
        flags = np.asarray(blocked)
        if flags.ndim == 0:
            flags = np.full(len(arr), bool(flags))
        elif flags.shape != (len(arr),):
            raise ConfigError(
                f"blocked must be one bool or one per cell ({len(arr)}), got shape {flags.shape}"
            )
        flags = flags.astype(bool)
        for (r, c), b in zip(arr, flags):
            if not (0 <= r < h and 0 <= c < w):
                raise ConfigError(
                    f"cell {(int(r), int(c))} is outside the {h}x{w} grid (rows 0..{h - 1}, cols 0..{w - 1})"
                )
            if b and (r, c) == self._start:
                raise ConfigError(f"cannot block the robot's cell (start) {self._start}")
            if b and (r, c) == self._goal:
                raise ConfigError(f"cannot block the goal {self._goal}")
        return arr, flags


def _neighbourhood(cells: np.ndarray, shape) -> np.ndarray:
    """Flat indices of every cell whose outgoing edges may change when
    ``cells`` change: the cells and their 8 neighbours (this covers the
    diagonals that pass a changed corner), sorted."""
    h, w = shape
    sources = set()
    for r, c in cells:
        for dr in (-1, 0, 1):
            for dc in (-1, 0, 1):
                rr, cc = r + dr, c + dc
                if 0 <= rr < h and 0 <= cc < w:
                    sources.add(int(rr) * w + int(cc))
    return np.array(sorted(sources), dtype=np.int64)
