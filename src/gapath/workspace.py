"""The grid workspace: occupancy, start, goal, cell size, corner rule, potential.

Conventions (``SPEC.md``): ``occ[r, c]`` is True for an obstacle; row 0 is the
top row; cells are named ``(row, col)``; the default start is the bottom-left
cell ``(H-1, 0)`` and the default goal the top-right cell ``(0, W-1)``.
"""

from __future__ import annotations

from collections.abc import Iterable
from functools import cached_property
from pathlib import Path
from typing import Any

import numba
import numpy as np

from gapath.errors import ConfigError, MapError

#: Variance of the Gaussian potential of one obstacle, in cell units squared.
POTENTIAL_S2 = 0.5
#: Half width of the square window over which the potential is summed.
POTENTIAL_RADIUS = 5


@numba.njit(cache=True)
def _potential_kernel(occ, s2, radius):
    h, w = occ.shape
    weight = np.empty((2 * radius + 1, 2 * radius + 1))
    for i in range(-radius, radius + 1):
        for j in range(-radius, radius + 1):
            weight[i + radius, j + radius] = np.exp(-(i * i + j * j) / (2.0 * s2))
    pot = np.zeros((h, w))
    for r in range(h):
        for c in range(w):
            acc = 0.0
            for i in range(max(0, r - radius), min(h, r + radius + 1)):
                for j in range(max(0, c - radius), min(w, c + radius + 1)):
                    if occ[i, j]:
                        acc += weight[i - r + radius, j - c + radius]
            pot[r, c] = acc
    return pot


def potential_field(occ: np.ndarray, s2: float = POTENTIAL_S2, radius: int = POTENTIAL_RADIUS) -> np.ndarray:
    """Potential ``P(c) = sum_o exp(-|c - o|^2 / (2 s2))`` of every cell.

    The sum runs over the obstacle cells ``o`` in the square window
    ``|dr| <= radius, |dc| <= radius`` around ``c`` (SPEC: each dropped term is
    below 3e-16 for the default ``radius=5``).

    Parameters
    ----------
    occ : (H, W) bool array, True for obstacles.
    s2 : variance in cell units squared (default 0.5).
    radius : half width of the summation window (default 5).

    Returns
    -------
    (H, W) float64 array.

    Examples
    --------
    >>> occ = np.zeros((3, 3), bool); occ[1, 1] = True
    >>> float(potential_field(occ)[1, 1])
    1.0
    """
    return _potential_kernel(np.ascontiguousarray(occ, dtype=np.bool_), float(s2), int(radius))


def _as_cell(value, name: str, shape: tuple[int, int]) -> tuple[int, int]:
    try:
        r, c = (int(v) for v in value)
        if any(float(v) != int(v) for v in value):
            raise ValueError
    except (TypeError, ValueError):
        raise ConfigError(f"{name} must be a (row, col) pair of integers, got {value!r}") from None
    h, w = shape
    if not (0 <= r < h and 0 <= c < w):
        raise ConfigError(f"{name} {(r, c)} is outside the {h}x{w} grid (rows 0..{h - 1}, cols 0..{w - 1})")
    return r, c


class Workspace:
    """A grid with obstacles, a start and a goal cell.

    Parameters
    ----------
    occ : (H, W) array of bool (or 0/1 integers), True/1 for an obstacle.
    start, goal : ``(row, col)``; default bottom-left ``(H-1, 0)`` and
        top-right ``(0, W-1)``.
    cell_size : length of a cell side (scales path lengths, not potentials).
    corner_cutting : if False a diagonal move needs both orthogonally
        adjacent cells free (MovingAI convention); default True (SPEC).
    name : a label used in outputs.
    frame : optional :class:`gapath.loaders.MapFrame`, the map's world frame
        (ROS maps; None when the grid has no world frame).

    Raises
    ------
    MapError
        If ``occ`` is not a non-empty 2-D boolean (or 0/1) array.
    ConfigError
        If start or goal is outside the grid or on an obstacle, if they are
        equal, if ``cell_size`` is not positive, or if ``corner_cutting`` is
        not a bool (``"no"`` would otherwise read as True).

    Examples
    --------
    >>> ws = Workspace(np.zeros((4, 5), bool))
    >>> ws.start, ws.goal
    ((3, 0), (0, 4))
    """

    def __init__(
        self,
        occ,
        start=None,
        goal=None,
        *,
        cell_size: float = 1.0,
        corner_cutting: bool = True,
        name: str = "workspace",
        frame=None,
    ):
        arr = np.asarray(occ)
        if arr.ndim != 2 or arr.shape[0] == 0 or arr.shape[1] == 0:
            raise MapError(f"occupancy must be a non-empty 2-D array, got shape {arr.shape}")
        if arr.dtype != np.bool_:
            if not (np.issubdtype(arr.dtype, np.integer) or np.issubdtype(arr.dtype, np.floating)):
                raise MapError(f"occupancy must be boolean, got dtype {arr.dtype}")
            bad = ~np.isin(arr, (0, 1))
            if bad.any():
                r, c = np.argwhere(bad)[0]
                raise MapError(
                    f"occupancy must be boolean (or 0/1), got {arr[r, c].item()!r} at (row {r}, col {c})"
                )
            arr = arr.astype(bool)
        self._occ = np.ascontiguousarray(arr, dtype=np.bool_)
        self._occ.setflags(write=False)
        h, w = self._occ.shape
        try:
            cs = float(cell_size)
        except (TypeError, ValueError):
            raise ConfigError(f"cell_size must be a positive number, got {cell_size!r}") from None
        if not np.isfinite(cs) or cs <= 0:
            raise ConfigError(f"cell_size must be a positive number, got {cell_size!r}")
        self.cell_size = cs
        if not isinstance(corner_cutting, (bool, np.bool_)):
            raise ConfigError(f"corner_cutting must be True or False, got {corner_cutting!r}")
        self.corner_cutting = bool(corner_cutting)
        self.name = str(name)
        self.frame = frame
        self.start = _as_cell((h - 1, 0) if start is None else start, "start", (h, w))
        self.goal = _as_cell((0, w - 1) if goal is None else goal, "goal", (h, w))
        for label, cell in (("start", self.start), ("goal", self.goal)):
            if self._occ[cell]:
                raise ConfigError(f"{label} {cell} is on an obstacle")
        if self.start == self.goal:
            raise ConfigError(f"start and goal are the same cell {self.start}")

    # -- basic properties -------------------------------------------------
    @property
    def occ(self) -> np.ndarray:
        """Read-only (H, W) bool occupancy array."""
        return self._occ

    @property
    def shape(self) -> tuple[int, int]:
        return self._occ.shape

    @property
    def n_obstacles(self) -> int:
        return int(self._occ.sum())

    @cached_property
    def potential(self) -> np.ndarray:
        """Potential field of SPEC (cell units), computed once and cached."""
        pot = potential_field(self._occ)
        pot.setflags(write=False)
        return pot

    def replace(self, **changes) -> Workspace:
        """A copy with some of ``occ, start, goal, cell_size, corner_cutting,
        name, frame`` replaced."""
        kw = dict(
            occ=self._occ,
            start=self.start,
            goal=self.goal,
            cell_size=self.cell_size,
            corner_cutting=self.corner_cutting,
            name=self.name,
            frame=self.frame,
        )
        unknown = set(changes) - set(kw)
        if unknown:
            raise ConfigError(f"unknown workspace field(s): {sorted(unknown)}")
        kw.update(changes)
        occ = kw.pop("occ")
        return Workspace(occ, **kw)

    def describe(self) -> dict[str, Any]:
        """The workspace's settings as written to ``summary.json``: ``map``
        (the name), ``shape``, ``start``, ``goal`` (lists), ``cell_size`` and
        ``corner_cutting``; with the occupancy they rebuild the workspace.

        Returns
        -------
        dict
            Plain JSON values.

        Examples
        --------
        >>> ws = Workspace(np.zeros((4, 5), bool), name="open")
        >>> ws.describe()
        {'map': 'open', 'shape': [4, 5], 'start': [3, 0], 'goal': [0, 4], 'cell_size': 1.0, 'corner_cutting': True}
        >>> d = ws.describe()
        >>> Workspace(ws.occ, d["start"], d["goal"], cell_size=d["cell_size"],
        ...           corner_cutting=d["corner_cutting"], name=d["map"]) == ws
        True
        """
        return {
            "map": self.name,
            "shape": list(self.shape),
            "start": list(self.start),
            "goal": list(self.goal),
            "cell_size": self.cell_size,
            "corner_cutting": self.corner_cutting,
        }

    def __repr__(self) -> str:
        h, w = self.shape
        return (
            f"Workspace(name={self.name!r}, shape={h}x{w}, obstacles={self.n_obstacles}, "
            f"start={self.start}, goal={self.goal}, cell_size={self.cell_size}, "
            f"corner_cutting={self.corner_cutting})"
        )

    def __eq__(self, other) -> bool:
        if not isinstance(other, Workspace):
            return NotImplemented
        return (
            np.array_equal(self._occ, other._occ)
            and self.start == other.start
            and self.goal == other.goal
            and self.cell_size == other.cell_size
            and self.corner_cutting == other.corner_cutting
        )

    __hash__ = None  # type: ignore[assignment]  # mutable arrays: unhashable

    # -- text form ---------------------------------------------------------
    def to_text(self) -> str:
        """The grid as plain text: ``.`` free, ``#`` obstacle, ``S``/``G``."""
        rows = [["#" if v else "." for v in row] for row in self._occ]
        rows[self.start[0]][self.start[1]] = "S"
        rows[self.goal[0]][self.goal[1]] = "G"
        return "\n".join("".join(r) for r in rows) + "\n"

    # -- loading -----------------------------------------------------------
    @classmethod
    def load(cls, path, start=None, goal=None, **kwargs) -> Workspace:
        """Load a map file, the format chosen by extension.

        See :func:`gapath.loaders.load_map` for the formats.
        """
        from gapath.loaders import load_map

        return load_map(path, start=start, goal=goal, **kwargs)

    # -- path checks -------------------------------------------------------
    def is_valid_path(self, path: Iterable) -> bool:
        """True if ``path`` goes from start to goal in 8-connected steps
        inside the grid (obstacles are not checked: see ``interfering``)."""
        p = np.asarray(path)
        if p.ndim != 2 or p.shape[1] != 2 or len(p) < 2:
            return False
        h, w = self.shape
        if (p[:, 0] < 0).any() or (p[:, 0] >= h).any() or (p[:, 1] < 0).any() or (p[:, 1] >= w).any():
            return False
        if tuple(p[0]) != self.start or tuple(p[-1]) != self.goal:
            return False
        d = np.abs(np.diff(p, axis=0))
        return bool((d.max(axis=1) == 1).all())


# ---------------------------------------------------------------------------
# generators
# ---------------------------------------------------------------------------


def _column_run(prev_row: int, target: int, col: int) -> list[tuple[int, int]]:
    """Cells entered in column ``col`` when moving from ``prev_row`` of the
    previous column to ``target``: one diagonal (or horizontal) step, then
    vertical steps in the same direction."""
    s = int(np.sign(target - prev_row))
    return [(rr, col) for rr in range(prev_row + s, target + s, s)] if s else [(target, col)]


def random_monotone_path(shape, start, goal, rng: np.random.Generator, max_step: int = 2) -> np.ndarray:
    """A random column-monotone path from ``start`` to ``goal``.

    Columns advance by one per transition; in each new column the row changes
    by a random amount in ``[-max_step, max_step]`` (kept inside the grid),
    and the last transition goes straight (diagonal, then vertical) to the
    goal, like the integer encoding's end-fixing.

    Returns
    -------
    (m, 2) int array of cells.
    """
    h, w = shape
    (sr, sc), (gr, gc) = start, goal
    step_c = 1 if gc >= sc else -1
    if sc == gc:
        raise ConfigError("start and goal share a column: no column-monotone path")
    cells = [(sr, sc)]
    r = sr
    for c in range(sc + step_c, gc, step_c):
        target = int(np.clip(r + rng.integers(-max_step, max_step + 1), 0, h - 1))
        cells.extend(_column_run(r, target, c))
        r = target
    # last transition: one diagonal towards the goal row, then vertical
    cells.extend(_column_run(r, gr, gc))
    return np.asarray(cells, dtype=np.int64)


def _check_shape(shape):
    try:
        h, w = (int(v) for v in shape)
    except (TypeError, ValueError):
        raise ConfigError(f"shape must be (rows, cols), got {shape!r}") from None
    if h <= 0 or w <= 0:
        raise ConfigError(f"grid size must be positive, got {h}x{w}")
    if w < 2:
        raise ConfigError(f"a column-monotone path needs at least 2 columns, got {w}")
    return h, w


def dense_workspace(
    n: int | tuple[int, int], p0: float, seed: int = 0, *, start=None, goal=None, name: str | None = None
) -> Workspace:
    """Ahmed & Deb's dense protocol (section 6).

    A random column-monotone path from start to goal is drawn first; then
    every other cell becomes an obstacle with probability ``p0``. ``p0 = 1``
    leaves only the path free. Seeded and deterministic.

    Parameters
    ----------
    n : grid side, or ``(rows, cols)``.
    p0 : obstacle probability in [0, 1].
    seed : random seed.

    Raises
    ------
    ConfigError
        On a non-positive size or ``p0`` outside [0, 1].
    """
    h, w = _check_shape((n, n) if np.isscalar(n) else n)
    if not (0.0 <= float(p0) <= 1.0):
        raise ConfigError(f"p0 must be in [0, 1], got {p0!r}")
    rng = np.random.default_rng(seed)
    start = _as_cell((h - 1, 0) if start is None else start, "start", (h, w))
    goal = _as_cell((0, w - 1) if goal is None else goal, "goal", (h, w))
    path = random_monotone_path((h, w), start, goal, rng)
    occ = rng.random((h, w)) < p0
    occ[path[:, 0], path[:, 1]] = False
    return Workspace(occ, start, goal, name=name or f"dense-{h}x{w}-p{p0:g}-s{seed}")


def random_workspace(
    shape, n_obstacles: int, seed: int = 0, *, start=None, goal=None, name: str | None = None
) -> Workspace:
    """``n_obstacles`` random obstacles with a guaranteed feasible
    column-monotone path (drawn first and kept free). Seeded.

    Raises
    ------
    ConfigError
        If there are not enough free cells off the path.
    """
    h, w = _check_shape(shape)
    k = int(n_obstacles)
    if k < 0:
        raise ConfigError(f"n_obstacles must be >= 0, got {n_obstacles!r}")
    rng = np.random.default_rng(seed)
    start = _as_cell((h - 1, 0) if start is None else start, "start", (h, w))
    goal = _as_cell((0, w - 1) if goal is None else goal, "goal", (h, w))
    path = random_monotone_path((h, w), start, goal, rng)
    free = np.ones(h * w, bool)
    free[path[:, 0] * w + path[:, 1]] = False
    candidates = np.flatnonzero(free)
    if k > len(candidates):
        raise ConfigError(f"n_obstacles={k} exceeds the {len(candidates)} cells off the guaranteed path")
    chosen = rng.choice(candidates, size=k, replace=False)
    occ = np.zeros(h * w, bool)
    occ[chosen] = True
    return Workspace(occ.reshape(h, w), start, goal, name=name or f"random-{h}x{w}-k{k}-s{seed}")


DEFAULT_SCENARIO = Path(__file__).with_name("data") / "default-32x32-173.map"
#: How the bundled default scenario was generated (kept for regeneration).
DEFAULT_SCENARIO_RECIPE = dict(shape=(32, 32), n_obstacles=173, seed=2013)


def default_workspace() -> Workspace:
    """The bundled default scenario: 32x32, 173 random obstacles, start
    bottom-left, goal top-right (Ahmed & Deb's Fig. 3 set-up).

    It is stored as a MovingAI map in the package (``gapath/data``) so that it
    does not depend on NumPy's random streams; it was made by
    ``random_workspace((32, 32), 173, seed=2013)``.
    """
    from gapath.loaders import load_movingai

    ws = load_movingai(DEFAULT_SCENARIO, corner_cutting=True)  # SPEC's rule, not MovingAI's
    return ws.replace(name="default-32x32-173")
