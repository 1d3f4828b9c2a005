"""Workspaces made by recipe: Ahmed & Deb's dense protocol, random obstacles
around a guaranteed path, and the bundled default scenario.

Every generator is seeded and deterministic; each draws a random
column-monotone path from start to goal first (:func:`random_monotone_path`)
and keeps it free, so the workspace always has a feasible path.

Examples
--------
>>> ws = random_workspace((6, 8), 10, seed=1)
>>> ws.shape, ws.n_obstacles, ws.start, ws.goal
((6, 8), 10, (5, 0), (0, 7))
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gapath.errors import ConfigError
from gapath.grid import check_cell
from gapath.loaders import load_movingai
from gapath.workspace import Workspace

__all__ = [
    "DEFAULT_SCENARIO",
    "DEFAULT_SCENARIO_RECIPE",
    "column_run",
    "default_workspace",
    "dense_workspace",
    "random_monotone_path",
    "random_workspace",
]


def column_run(prev_row: int, target: int, col: int) -> list[tuple[int, int]]:
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
        cells.extend(column_run(r, target, c))
        r = target
    # last transition: one diagonal towards the goal row, then vertical
    cells.extend(column_run(r, gr, gc))
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
    start = check_cell((h - 1, 0) if start is None else start, "start", (h, w))
    goal = check_cell((0, w - 1) if goal is None else goal, "goal", (h, w))
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
    start = check_cell((h - 1, 0) if start is None else start, "start", (h, w))
    goal = check_cell((0, w - 1) if goal is None else goal, "goal", (h, w))
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


#: The bundled default scenario, a MovingAI map (:func:`default_workspace`).
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
    ws = load_movingai(DEFAULT_SCENARIO, corner_cutting=True)  # SPEC's rule, not MovingAI's
    return ws.replace(name="default-32x32-173")
