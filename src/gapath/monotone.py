"""Column-monotone paths: the canonical frame and column profiles.

The GA encodings (:mod:`gapath.encodings`), the exact and weighted-sum
planners and the seeding operators all describe column-monotone paths with
these two ideas.

Frame
    The encodings describe paths that advance exactly one column per
    transition from the start column to the goal column. A :class:`Frame`
    maps a workspace onto a canonical view in which the start column is left
    of the goal column: the grid is mirrored left-right when the goal is left
    of the start, and transposed (rows become columns) only when start and
    goal share a column (the one case with no column-monotone path).
    Objectives are invariant under these maps.

Column profile
    A column-monotone path is fully described, in the frame, by the entry
    row and the exit row of each of its ``n_cols`` columns: column ``k``
    (frame column ``col0 + k``) is the vertical run ``entries[k] ..
    exits[k]``; consecutive columns are joined by one horizontal or diagonal
    step (``|entries[k] - exits[k-1]| <= 1``). Every encoding decodes genes
    into profiles, :func:`gapath.objectives.evaluate_profiles` evaluates
    them, and :func:`expand_profiles` turns them into cells;
    :func:`profiles_of_paths` and :func:`monotone_projection` go the other
    way.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from gapath.errors import ConfigError
from gapath.objectives import evaluate_profiles
from gapath.workspace import Workspace, read_only


@dataclass(frozen=True, eq=False)
class Frame:
    """Canonical column-monotone view of a workspace.

    Attributes
    ----------
    occ, potential : frame-oriented arrays (views of the workspace's).
    start, goal : frame cells; ``start[1] < goal[1]``.
    transpose, flip : how the frame was made from the workspace
        (transpose first, then mirror the columns).
    """

    workspace: Workspace
    occ: np.ndarray
    potential: np.ndarray
    start: tuple[int, int]
    goal: tuple[int, int]
    transpose: bool
    flip: bool

    @classmethod
    def of(cls, workspace: Workspace) -> Frame:
        occ, pot = workspace.occ, workspace.potential
        (sr, sc), (gr, gc) = workspace.start, workspace.goal
        transpose = sc == gc
        if transpose:
            occ, pot = occ.T, pot.T
            (sr, sc), (gr, gc) = (sc, sr), (gc, gr)
        flip = gc < sc
        if flip:
            w = occ.shape[1]
            occ, pot = occ[:, ::-1], pot[:, ::-1]
            sc, gc = w - 1 - sc, w - 1 - gc
        return cls(
            workspace,
            read_only(occ),
            read_only(pot, np.float64),
            (sr, sc),
            (gr, gc),
            transpose,
            flip,
        )

    @property
    def height(self) -> int:
        return self.occ.shape[0]

    @property
    def col0(self) -> int:
        """Frame column of the start."""
        return self.start[1]

    @property
    def n_cols(self) -> int:
        """Number of columns a monotone path visits (start and goal included)."""
        return self.goal[1] - self.start[1] + 1

    def to_workspace(self, cells: np.ndarray) -> np.ndarray:
        """Map frame cells ``(..., 2)`` to workspace cells."""
        cells = np.array(cells, dtype=np.int64, copy=True)
        if self.flip:
            cells[..., 1] = self.occ.shape[1] - 1 - cells[..., 1]
        if self.transpose:
            cells = cells[..., ::-1]
        return np.ascontiguousarray(cells)

    def from_workspace(self, cells: np.ndarray) -> np.ndarray:
        """Map workspace cells ``(..., 2)`` to frame cells."""
        cells = np.array(cells, dtype=np.int64, copy=True)
        if self.transpose:
            cells = np.ascontiguousarray(cells[..., ::-1])
        if self.flip:
            cells[..., 1] = self.occ.shape[1] - 1 - cells[..., 1]
        return cells

    def evaluate(self, entries: np.ndarray, exits: np.ndarray) -> np.ndarray:
        """Objectives ``(N, 4)`` of profiles (see :mod:`gapath.objectives`)."""
        ws = self.workspace
        return evaluate_profiles(
            entries, exits, self.col0, self.occ, self.potential, ws.cell_size, ws.corner_cutting
        )


@numba.njit(cache=True)
def _expand(entries, exits, col0):
    n, n_cols = entries.shape
    lengths = np.zeros(n, dtype=np.int64)
    for i in range(n):
        m = 0
        for k in range(n_cols):
            m += abs(exits[i, k] - entries[i, k]) + 1
        lengths[i] = m
    paths = np.zeros((n, lengths.max() if n else 1, 2), dtype=np.int64)
    for i in range(n):
        m = 0
        for k in range(n_cols):
            a = entries[i, k]
            b = exits[i, k]
            s = 1 if b >= a else -1
            r = a
            while True:
                paths[i, m, 0] = r
                paths[i, m, 1] = col0 + k
                m += 1
                if r == b:
                    break
                r += s
    return paths, lengths


def expand_profiles(frame: Frame, entries, exits, *, workspace_coords: bool = True):
    """Cells of profiled paths.

    Returns
    -------
    paths : (N, L, 2) int array, padded with zeros past each length.
    lengths : (N,) int array.
    """
    paths, lengths = _expand(np.asarray(entries, np.int64), np.asarray(exits, np.int64), frame.col0)
    if workspace_coords:
        paths = frame.to_workspace(paths)
    return paths, lengths


def split_paths(paths: np.ndarray, lengths: np.ndarray) -> list[np.ndarray]:
    """A list of ``(m_i, 2)`` arrays from padded paths."""
    return [paths[i, : lengths[i]].copy() for i in range(len(lengths))]


def profiles_of_paths(frame: Frame, paths) -> tuple[np.ndarray, np.ndarray]:
    """Column profiles of column-monotone paths (workspace cells).

    Raises
    ------
    ConfigError
        If a path does not start at the start, end at the goal, advance one
        column per transition, or move vertically inside a column other than
        in one contiguous run.
    """
    n_cols = frame.n_cols
    entries = np.empty((len(paths), n_cols), np.int64)
    exits = np.empty((len(paths), n_cols), np.int64)
    for i, p in enumerate(paths):
        p = frame.from_workspace(np.asarray(p).reshape(-1, 2))
        if tuple(p[0]) != frame.start or tuple(p[-1]) != frame.goal:
            raise ConfigError(f"path {i} does not run from start to goal")
        cols = p[:, 1] - frame.col0
        if (np.diff(cols) < 0).any() or (np.diff(cols) > 1).any():
            raise ConfigError(f"path {i} is not column-monotone (it must advance one column at a time)")
        for k in range(n_cols):
            rows = p[cols == k, 0]
            if len(rows) == 0:
                raise ConfigError(f"path {i} skips column {k}")
            d = np.diff(rows)
            if len(rows) > 1 and not ((d == 1).all() or (d == -1).all()):
                raise ConfigError(f"path {i} is not one vertical run in column {k}")
            entries[i, k], exits[i, k] = rows[0], rows[-1]
        if (np.abs(entries[i, 1:] - exits[i, :-1]) > 1).any():
            raise ConfigError(f"path {i} has a step that is not 8-adjacent")
    return entries, exits


def monotone_projection(frame: Frame, path) -> tuple[np.ndarray, np.ndarray]:
    """The column-monotone path that follows ``path`` (workspace cells, any
    8-connected path from start to goal) column by column.

    In every frame column between the start and the goal column the exit row
    is the row of the last cell ``path`` visits there (the previous exit row
    when it skips the column); the columns are joined by the integer
    encoding's moves (one step towards the next exit row, then vertical).
    Feasibility is not checked.

    Returns
    -------
    entries, exits : (n_cols,) int arrays (frame rows).
    """
    p = frame.from_workspace(np.asarray(path).reshape(-1, 2))
    n_cols = frame.n_cols
    exits = np.empty(n_cols, np.int64)
    row = frame.start[0]
    for k in range(n_cols):
        rows = p[p[:, 1] == frame.col0 + k, 0]
        row = int(rows[-1]) if len(rows) else row
        exits[k] = row
    exits[-1] = frame.goal[0]
    prev = np.concatenate([[frame.start[0]], exits[:-1]])
    entries = prev + np.sign(exits - prev)
    entries[0] = frame.start[0]
    return entries, exits
