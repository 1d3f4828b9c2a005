"""The relative-move path set shared by the integer, mixed and absolute encodings.

Those three encodings describe the same paths: in every column after the
start column, the path enters by one diagonal step towards its exit row (or
one horizontal step when the exit row equals the previous one), then moves
vertically in that same direction; the goal column is reached by the
integer encoding's end-fixing. A path of that set is fully given by the
signed row change between consecutive exit rows (up positive).
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.errors import ConfigError


@numba.njit(cache=True, inline="always")
def linear_draw(current, edge, u):
    """A row between ``edge`` and ``current`` (excluded), probability growing
    linearly from zero at ``current`` to its maximum at ``edge``."""
    n = abs(edge - current)
    if n == 0:
        return current
    target = u * (n * (n + 1) // 2)
    m = 1
    while m * (m + 1) // 2 < target and m < n:
        m += 1
    return current + m * (1 if edge > current else -1)


def relative_moves(frame, entries, exits, encoding: str) -> np.ndarray:
    """Signed moves ``(N, n_cols - 1)`` (up positive) of column profiles.

    Move 0 is the vertical move inside the start column; move ``k >= 1`` the
    row change from the exit of column ``k-1`` to the exit of column ``k``.

    Raises
    ------
    ConfigError
        If a profile enters a column anywhere else than the relative rule
        says (a horizontal step followed by vertical steps, a diagonal
        followed by vertical steps the other way, or an end that differs
        from the end-fixing rule); the message names ``encoding``.
    """
    entries = np.asarray(entries, np.int64)
    exits = np.asarray(exits, np.int64)
    sr = frame.start[0]
    prev = np.concatenate([np.full((len(exits), 1), sr), exits[:, :-1]], axis=1)
    expected = prev + np.sign(exits - prev)
    expected[:, 0] = sr
    bad = np.argwhere(entries != expected)
    if len(bad):
        i, k = bad[0]
        raise ConfigError(
            f"path {i} is not representable in the {encoding} encoding at column {k}: "
            f"it enters at row {entries[i, k]} where the encoding enters at row {expected[i, k]}"
        )
    return (prev - exits)[:, :-1].astype(np.int64)


@numba.njit(cache=True)
def edge_fix_moves(D, U, start_row, height):
    """Ahmed & Deb's edge-fixing on signed moves ``D`` (N, n_moves), in place.

    Row ``r`` is the current exit row (the start row before move 0). A move
    whose target ``r - D[i, k]`` lies outside ``[0, height - 1]`` is replaced
    by a row drawn with linear probability between the violated edge
    (highest) and ``r`` (zero), using the uniform number ``U[i, k]``. Unlike
    the integer encoding's kernel, move 0 (the start column) is fixed the
    same way, since the mixed and binary genes can code start moves that
    leave the grid.
    """
    n, n_moves = D.shape
    for i in range(n):
        r = start_row
        for k in range(n_moves):
            t = r - D[i, k]
            if t < 0:
                t = linear_draw(r, 0, U[i, k])
                D[i, k] = r - t
            elif t > height - 1:
                t = linear_draw(r, height - 1, U[i, k])
                D[i, k] = r - t
            r = t
    return D


@numba.njit(cache=True, inline="always")
def _walk(X, i, start_row, goal_row, height, E, e0, T, t0):
    """Decode genome ``i`` of ``X``: its entry rows into ``E[i, e0:]``, its
    exit rows into ``T[i, t0:]``."""
    n_var = X.shape[1]
    r = start_row
    for k in range(n_var):
        t = min(max(r - X[i, k], 0), height - 1)
        E[i, e0 + k] = r if k == 0 else r + np.sign(t - r)
        T[i, t0 + k] = t
        r = t
    E[i, e0 + n_var] = r + np.sign(goal_row - r)
    T[i, t0 + n_var] = goal_row


@numba.njit(cache=True)
def decode_moves(X, start_row, goal_row, height):
    """Column profiles ``(entries, exits)``, ``(N, n_var + 1)`` each, of the
    signed exit-row changes ``X`` ``(N, n_var)`` (up positive, clipped to the
    grid); the last column goes to ``goal_row`` by the end-fixing."""
    n, n_var = X.shape
    entries = np.empty((n, n_var + 1), np.int64)
    exits = np.empty((n, n_var + 1), np.int64)
    for i in range(n):
        _walk(X, i, start_row, goal_row, height, entries, 0, exits, 0)
    return entries, exits


@numba.njit(cache=True)
def decode_move_keys(X, start_row, goal_row, height):
    """:func:`decode_moves` as one ``(N, 2 (n_var + 1))`` array, ``[entries |
    exits]`` (the path keys of duplicate elimination), in one pass."""
    n, n_var = X.shape
    K = np.empty((n, 2 * (n_var + 1)), np.int64)
    for i in range(n):
        _walk(X, i, start_row, goal_row, height, K, 0, K, n_var + 1)
    return K
