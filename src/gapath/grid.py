"""The grid's move rules (SPEC), in one place for objectives, planners and encodings.

* The 8 moves ``(dr, dc)`` in one fixed order, E, NE, N, NW, W, SW, S, SE
  (counter-clockwise, row up = -1): :data:`DR`, :data:`DC`, their lengths
  :data:`STEP` (1 or :data:`SQRT2` cell units), and :data:`DIRECTION`, the
  index of a step in that order. A heading is a move index, in eighths of a
  turn counter-clockwise from east; :func:`turn` is the turn between two
  headings.
* The move rule: a step goes to an 8-adjacent cell inside the grid that is
  free; with ``corner_cutting=False`` a diagonal step also needs both
  orthogonally adjacent cells free (MovingAI's rule). :func:`cuts_corner` is
  that corner rule, :func:`can_step` the whole rule and :func:`move_mask` the
  8 moves of a cell as bits.
* Lengths from step counts (:func:`step_counts`, :func:`path_length`,
  :func:`octile`), so that paths with the same counts get bit-identical
  lengths.
* Input checks: a cell (:func:`check_cell`, :func:`check_free_cell`) and a
  path of 8-adjacent cells (:func:`check_path`).

The numba functions are ``@njit`` and may be called from other kernels; all
work in cell units (callers scale by ``cell_size``). A kernel that calls
another passes :data:`ZERO`, :data:`ONE`, :data:`TRUE` or :data:`FALSE`, not
the literals: numba compiles the callee once more for each literal argument.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from gapath.errors import ConfigError

#: 0, 1, True and False typed as int64 and bool, not as literals, for a
#: kernel to pass to another kernel (a literal argument compiles the callee,
#: and every kernel it calls, once more).
ZERO = np.int64(0)
ONE = np.int64(1)
TRUE = np.bool_(True)
FALSE = np.bool_(False)

#: Length of a diagonal step in cell units.
SQRT2 = math.sqrt(2.0)

#: The 8 moves ``(dr, dc)``: E, NE, N, NW, W, SW, S, SE (counter-clockwise,
#: row up = -1). Orthogonal moves have even indices.
DR = np.array([0, -1, -1, -1, 0, 1, 1, 1], dtype=np.int64)
DC = np.array([1, 1, 0, -1, -1, -1, 0, 1], dtype=np.int64)
#: Length of each move in cell units.
STEP = np.array([1.0, SQRT2, 1.0, SQRT2, 1.0, SQRT2, 1.0, SQRT2])
#: ``DIRECTION[dr + 1, dc + 1]``: the index of the move ``(dr, dc)`` (-1 for
#: ``(0, 0)``), its heading in eighths counter-clockwise from east.
DIRECTION = np.array([[3, 2, 1], [4, -1, 0], [5, 6, 7]], dtype=np.int64)


# ---------------------------------------------------------------------------
# the move rule
# ---------------------------------------------------------------------------


@numba.njit(cache=True, inline="always")
def cuts_corner(occ, r, c, r2, c2):
    """True if the step ``(r, c) -> (r2, c2)`` is diagonal and one of the
    two orthogonally adjacent cells ``(r2, c)``, ``(r, c2)`` is an obstacle:
    the step a workspace with ``corner_cutting=False`` forbids.

    ``occ`` is the ``(H, W)`` occupancy; both cells must be inside it.
    """
    return r2 != r and c2 != c and (occ[r2, c] or occ[r, c2])


@numba.njit(cache=True, inline="always")
def can_step(occ, r, c, dr, dc, corner_cutting):
    """True if the move ``(r, c) -> (r + dr, c + dc)`` is allowed.

    The target must be inside the grid and free; a diagonal move with
    ``corner_cutting=False`` must not cut a corner (:func:`cuts_corner`).
    The source is not checked.
    """
    h, w = occ.shape
    r2 = r + dr
    c2 = c + dc
    if r2 < 0 or r2 >= h or c2 < 0 or c2 >= w:
        return False
    if occ[r2, c2]:
        return False
    if not corner_cutting and cuts_corner(occ, r, c, r2, c2):
        return False
    return True


@numba.njit(cache=True, inline="always")
def move_mask(occ, h, w, r, c, corner_cutting):
    """The allowed moves from cell ``(r, c)`` of the raveled ``h x w`` grid
    ``occ`` as bits: bit ``k`` is set if :func:`can_step` allows move ``k``.

    The same rule as :func:`can_step`, unrolled for the raveled grid of the
    searches' hot loops."""
    if r == 0 or c == 0 or r == h - 1 or c == w - 1:
        return _border_move_mask(occ, h, w, r, c, corner_cutting)
    u = r * w + c  # interior: no bounds checks
    e = not occ[u + 1]
    n = not occ[u - w]
    we = not occ[u - 1]
    s = not occ[u + w]
    ne = not occ[u - w + 1]
    nw = not occ[u - w - 1]
    sw = not occ[u + w - 1]
    se = not occ[u + w + 1]
    if not corner_cutting:  # a diagonal needs both sides free
        ne &= n & e
        nw &= n & we
        sw &= s & we
        se &= s & e
    return e | (ne << 1) | (n << 2) | (nw << 3) | (we << 4) | (sw << 5) | (s << 6) | (se << 7)


@numba.njit(cache=True)
def _border_move_mask(occ, h, w, r, c, corner_cutting):
    mask = 0
    for k in range(8):
        r2 = r + DR[k]
        c2 = c + DC[k]
        if r2 < 0 or r2 >= h or c2 < 0 or c2 >= w or occ[r2 * w + c2]:
            continue
        if (k & 1) and not corner_cutting and (occ[r2 * w + c] or occ[r * w + c2]):
            continue
        mask |= 1 << k
    return mask


@numba.njit(cache=True, inline="always")
def turn(prev_dir, d):
    """The turn between headings ``prev_dir`` and ``d`` (move indices), in
    eighths, 0 to 4."""
    t = abs(d - prev_dir)
    if t > 4:
        t = 8 - t
    return t


# ---------------------------------------------------------------------------
# lengths
# ---------------------------------------------------------------------------


@numba.njit(cache=True, inline="always")
def octile(r1, c1, r2, c2):
    """Octile distance: the 8-connected shortest length on an empty grid."""
    dr = abs(r1 - r2)
    dc = abs(c1 - c2)
    if dr < dc:
        return dc + (SQRT2 - 1.0) * dr
    return dr + (SQRT2 - 1.0) * dc


@numba.njit(cache=True)
def step_counts(path):
    """``(n_straight, n_diagonal)`` of a path of 8-adjacent cells."""
    n_straight = 0
    n_diagonal = 0
    for i in range(1, path.shape[0]):
        if path[i, 0] != path[i - 1, 0] and path[i, 1] != path[i - 1, 1]:
            n_diagonal += 1
        else:
            n_straight += 1
    return n_straight, n_diagonal


def path_length(path: np.ndarray, cell_size: float) -> float:
    """Euclidean length of a path of 8-adjacent cells from its integer step
    counts (SPEC), so that paths with the same counts get bit-identical
    lengths.

    Examples
    --------
    >>> path_length(np.array([[1, 0], [0, 1], [0, 2]]), 1.0) == 1 + 2**0.5
    True
    """
    n_straight, n_diagonal = step_counts(path)
    return (n_straight + SQRT2 * n_diagonal) * cell_size


# ---------------------------------------------------------------------------
# input checks
# ---------------------------------------------------------------------------


def check_cell(value, name: str, shape: tuple[int, int]) -> tuple[int, int]:
    """``value`` as a ``(row, col)`` tuple of a cell of a grid of ``shape``.

    Raises
    ------
    ConfigError
        If it is not a pair of integers (bools are not) or is outside the grid.

    Examples
    --------
    >>> check_cell((2.0, 1), "start", (3, 4))
    (2, 1)
    """
    try:
        vals = list(value)
        if len(vals) != 2:
            raise ValueError
        r, c = (int(v) for v in vals)
        if any(isinstance(v, (bool, np.bool_)) or float(v) != int(v) for v in vals):
            raise ValueError
    except (TypeError, ValueError, OverflowError):
        raise ConfigError(f"{name} must be a (row, col) pair of integers, got {value!r}") from None
    h, w = shape
    if not (0 <= r < h and 0 <= c < w):
        raise ConfigError(f"{name} {(r, c)} is outside the {h}x{w} grid (rows 0..{h - 1}, cols 0..{w - 1})")
    return r, c


def check_free_cell(value, name: str, occ: np.ndarray) -> tuple[int, int]:
    """``value`` as a ``(row, col)`` tuple of a free cell of ``occ``.

    Raises
    ------
    ConfigError
        As :func:`check_cell`, or if the cell is an obstacle.
    """
    r, c = check_cell(value, name, occ.shape)
    if occ[r, c]:
        raise ConfigError(f"{name} {(r, c)} is on an obstacle")
    return r, c


def check_path(path, shape: tuple[int, int]) -> np.ndarray:
    """``path`` as an ``(m, 2)`` int64 array of cells of a grid of ``shape``,
    consecutive cells 8-adjacent (obstacles are not checked).

    Raises
    ------
    ConfigError
        If it has fewer than two cells, a cell is not integer or is outside
        the grid, or two consecutive cells are not 8-adjacent.
    """
    p = np.asarray(path)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < 2:
        raise ConfigError(f"a path must be a sequence of at least two (row, col) cells, got shape {p.shape}")
    if not np.issubdtype(p.dtype, np.integer):
        if not np.array_equal(p, np.round(p)):
            raise ConfigError("path cells must be integers")
        p = p.astype(np.int64)
    h, w = shape
    out = (p[:, 0] < 0) | (p[:, 0] >= h) | (p[:, 1] < 0) | (p[:, 1] >= w)
    if out.any():
        k = int(np.flatnonzero(out)[0])
        raise ConfigError(f"path cell {k} {tuple(int(v) for v in p[k])} is outside the {h}x{w} grid")
    step = np.abs(np.diff(p, axis=0)).max(axis=1)
    if (step != 1).any():
        k = int(np.flatnonzero(step != 1)[0])
        raise ConfigError(
            f"path cells {k} {tuple(int(v) for v in p[k])} and {k + 1} "
            f"{tuple(int(v) for v in p[k + 1])} are not 8-adjacent"
        )
    return p.astype(np.int64)
