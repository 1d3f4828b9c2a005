"""Path objectives (SPEC): length, vulnerability, smoothness, interfering.

All kernels are numba ``@njit`` functions over a whole population:

* :func:`evaluate_paths` takes padded cell arrays ``(N, L, 2)`` and the true
  lengths ``(N,)``;
* :func:`evaluate_profiles` takes column-monotone paths as column profiles
  (entry and exit row of every column, see :mod:`gapath.monotone`) and
  never materialises the cells; it visits cells in path order, so both kernels
  give bit-identical values for the same path.

Both return an ``(N, 4)`` float array whose columns follow :data:`OBJECTIVES`.
Lengths are computed from integer step counts and smoothness from a count of
eighth turns, so equal paths (and paths with equal counts) get bit-identical
values.

A diagonal step that cuts a blocked corner (:func:`gapath.grid.cuts_corner`)
counts as one interfering unit when the workspace forbids corner cutting
(``corner_cutting=False``).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import numba
import numpy as np

from gapath.errors import ConfigError
from gapath.grid import DIRECTION, SQRT2, check_path, cuts_corner, turn

#: Names of the per-path metrics, in the column order of the kernels' output.
OBJECTIVES = ("length", "vulnerability", "smoothness", "interfering")
LENGTH, VULNERABILITY, SMOOTHNESS, INTERFERING = range(4)
#: Metrics that may be objectives (``interfering`` is the constraint).
OBJECTIVE_NAMES = ("length", "vulnerability", "smoothness")

#: One eighth turn in radians (smoothness counts eighths).
QUARTER_PI = math.pi / 4.0


def objective_index(names) -> list[int]:
    """Column indices of ``names`` in the kernels' output.

    Raises
    ------
    ConfigError
        If a name is unknown or repeated.
    """
    if isinstance(names, str):
        names = [n.strip() for n in names.split(",") if n.strip()]
    names = list(names)
    if not names:
        raise ConfigError("at least one objective is needed")
    idx = []
    for n in names:
        if n not in OBJECTIVES:
            raise ConfigError(f"unknown objective {n!r}; expected one of {', '.join(OBJECTIVES)}")
        if OBJECTIVES.index(n) in idx:
            raise ConfigError(f"objective {n!r} is given twice")
        idx.append(OBJECTIVES.index(n))
    return idx


def check_objective_names(names: Iterable[str], layers: Sequence[str] = ()) -> list[str]:
    """Check that every name is a path objective: one of
    :data:`OBJECTIVE_NAMES` or of the costmap ``layers``.

    Parameters
    ----------
    names : iterable of str
        The objective names, already split (repeats and emptiness are left
        to the caller, e.g. :func:`objective_index`).
    layers : sequence of str, optional
        Further allowed names (a costmap's layer objectives).

    Returns
    -------
    list of str
        The names, in order.

    Raises
    ------
    ConfigError
        On the first unknown name, naming it and the choices.

    Examples
    --------
    >>> check_objective_names(["length", "smoothness"])
    ['length', 'smoothness']
    >>> check_objective_names(["length", "risk"])
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: unknown objective 'risk'; expected some of length, vulnerability, smoothness
    """
    names = list(names)
    for n in names:
        if n not in OBJECTIVE_NAMES and n not in layers:
            expected = OBJECTIVE_NAMES + tuple(x for x in layers if x not in OBJECTIVE_NAMES)
            raise ConfigError(f"unknown objective {n!r}; expected some of {', '.join(expected)}")
    return names


@numba.njit(cache=True)
def evaluate_paths(paths, lengths, occ, potential, cell_size, corner_cutting):
    """Objectives of padded paths.

    Parameters
    ----------
    paths : (N, L, 2) int array of cells ``(row, col)``; rows past
        ``lengths[i]`` are ignored.
    lengths : (N,) int array, number of cells of each path.
    occ : (H, W) bool occupancy.
    potential : (H, W) float potential field.
    cell_size : float.
    corner_cutting : bool, False to count corner-cutting diagonals as
        interfering.

    Returns
    -------
    (N, 4) float64 array: length, vulnerability, smoothness, interfering.
    """
    n = paths.shape[0]
    out = np.empty((n, 4))
    for i in range(n):
        m = lengths[i]
        n_straight = 0
        n_diag = 0
        eighths = 0
        interf = 0
        vul = 0.0
        prev_dir = -1
        pr = paths[i, 0, 0]
        pc = paths[i, 0, 1]
        for k in range(m):
            r = paths[i, k, 0]
            c = paths[i, k, 1]
            vul += potential[r, c]
            if occ[r, c]:
                interf += 1
            if k > 0:
                dr = r - pr
                dc = c - pc
                if dr != 0 and dc != 0:
                    n_diag += 1
                    if not corner_cutting and cuts_corner(occ, pr, pc, r, c):
                        interf += 1
                else:
                    n_straight += 1
                d = DIRECTION[dr + 1, dc + 1]
                if prev_dir >= 0:
                    eighths += turn(prev_dir, d)
                prev_dir = d
            pr = r
            pc = c
        out[i, 0] = (n_straight + SQRT2 * n_diag) * cell_size
        out[i, 1] = vul
        out[i, 2] = eighths * QUARTER_PI
        out[i, 3] = interf
    return out


@numba.njit(cache=True)
def evaluate_profiles(entries, exits, col0, occ, potential, cell_size, corner_cutting):
    """Objectives of column-monotone paths given as column profiles.

    Column ``k`` of path ``i`` (grid column ``col0 + k``) is the vertical run
    of cells from row ``entries[i, k]`` to row ``exits[i, k]``; consecutive
    columns are joined by one horizontal or diagonal step. This is the
    evaluation used by the GA problems: it visits the cells in path order
    without building them.

    Returns
    -------
    (N, 4) float64 array: length, vulnerability, smoothness, interfering.
    """
    n, n_cols = entries.shape
    out = np.empty((n, 4))
    for i in range(n):
        n_straight = 0
        n_diag = 0
        eighths = 0
        interf = 0
        vul = 0.0
        prev_dir = -1  # heading of the last step, in eighths (0 east, 2 up)
        pr = entries[i, 0]  # exit row of the previous column
        for k in range(n_cols):
            c = col0 + k
            a = entries[i, k]
            b = exits[i, k]
            if k > 0:  # the step into column k
                if a != pr:
                    n_diag += 1
                    d = 1 if a < pr else 7
                    if not corner_cutting and cuts_corner(occ, pr, c - 1, a, c):
                        interf += 1
                else:
                    n_straight += 1
                    d = 0
                if prev_dir >= 0:
                    eighths += turn(prev_dir, d)
                prev_dir = d
            if b == a:
                vul += potential[a, c]
                interf += occ[a, c]
            else:  # the vertical run a..b
                s = 1 if b > a else -1
                r = a
                while True:
                    vul += potential[r, c]
                    interf += occ[r, c]
                    if r == b:
                        break
                    r += s
                n_straight += abs(b - a)
                d = 6 if s > 0 else 2
                if prev_dir >= 0:
                    eighths += turn(prev_dir, d)
                prev_dir = d
            pr = b
        out[i, 0] = (n_straight + SQRT2 * n_diag) * cell_size
        out[i, 1] = vul
        out[i, 2] = eighths * QUARTER_PI
        out[i, 3] = interf
    return out


def pad_paths(paths) -> tuple[np.ndarray, np.ndarray]:
    """Stack a list of (m_i, 2) paths into a padded ``(N, L, 2)`` array and
    the lengths ``(N,)``."""
    paths = [np.asarray(p, dtype=np.int64).reshape(-1, 2) for p in paths]
    lengths = np.array([len(p) for p in paths], dtype=np.int64)
    out = np.zeros((len(paths), int(lengths.max(initial=1)), 2), dtype=np.int64)
    for i, p in enumerate(paths):
        out[i, : len(p)] = p
    return out, lengths


def evaluate_path(workspace, path) -> dict[str, float]:
    """All objectives of one path, as a dict keyed by :data:`OBJECTIVES`.

    Parameters
    ----------
    workspace : :class:`gapath.Workspace`.
    path : sequence of ``(row, col)`` cells, consecutive cells 8-adjacent.

    Raises
    ------
    ConfigError
        If a cell is outside the grid or two consecutive cells are not
        8-adjacent.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> ws = Workspace(np.zeros((2, 2), bool))
    >>> evaluate_path(ws, [(1, 0), (0, 1)])["length"] == 2 ** 0.5
    True
    """
    p = check_path(path, workspace.shape)
    res = evaluate_paths(
        p[None],
        np.array([len(p)]),
        workspace.occ,
        workspace.potential,
        workspace.cell_size,
        workspace.corner_cutting,
    )[0]
    out = dict(zip(OBJECTIVES, (float(v) for v in res)))
    out["interfering"] = int(out["interfering"])
    return out
