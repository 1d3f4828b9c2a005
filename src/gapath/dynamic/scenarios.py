"""Scenarios for the dynamic-environment study (NO-MOPP, Neeraja & Narsimha).

A *scenario* is a static map with a start and a goal (a
:class:`~gapath.workspace.Workspace`, 1 m cells) plus the dynamic obstacles
of one run: stationary obstacles that appear during the run and moving
obstacles (:mod:`gapath.dynamic`). Everything is seeded.

Maps
    :func:`complex_maze`
        NO-MOPP's "complex map": a maze of 4 m corridors and 1 m walls on a
        coarse lattice (a perfect maze by randomised depth-first search),
        braided by removing walls in a random order until the shortest grid
        path is at most ``max_detour`` times the straight-line distance.
        The default 1.20 follows NO-MOPP: its offline path was 1.245
        times the direct distance (64.56 m / 51.86 m, Table I), which a
        perfect maze (detours of 2-4x) does not allow. Start and goal are
        cells of the bottom-left and top-right corridor cells chosen so that
        the straight-line distance is nearest ``target_distance`` (51.86 m).
    :func:`warehouse`
        NO-MOPP's "package pick-up in a warehouse": rows of shelves (2 m
        deep) separated by 4 m aisles and 4 m cross aisles, a loading dock
        with pallets at the bottom, the start at the dock (bottom left) and
        the goal in an aisle beside a shelf (the package) at the top right,
        the straight-line distance nearest ``target_distance`` (62.15 m).
    :func:`load_scenario_map`
        Any map gapath reads (:func:`gapath.loaders.load_map`).

Dynamic obstacles
    :func:`dynamic_obstacles` draws, for any map, stationary obstacles on the
    reference (shortest) path that appear before the robot gets there, and
    moving obstacles: "crossers" timed to meet the robot on its reference
    path (the paper's Fig. 5) and "wanderers" bouncing through the map.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gapath.dynamic import MovingObstacle, StationaryObstacle, simulate, start_pose
from gapath.errors import ConfigError, NoPathError
from gapath.loaders import load_map
from gapath.planners.astar import astar
from gapath.planners.geometry import disc_free
from gapath.workspace import Workspace

__all__ = [
    "Scenario",
    "complex_maze",
    "dynamic_obstacles",
    "load_scenario_map",
    "make_scenario",
    "straight_line_distance",
    "warehouse",
    "SCENARIOS",
]

#: NO-MOPP's straight-line start-goal distances (Tables I and II).
SEED_DISTANCE = {"maze": 51.856, "warehouse": 62.1488}


def straight_line_distance(workspace) -> float:
    """Euclidean start-goal distance between cell centres, world units."""
    (sr, sc), (gr, gc) = workspace.start, workspace.goal
    return math.hypot(sr - gr, sc - gc) * workspace.cell_size


def _grid_ratio(occ, start, goal) -> float:

    ws = Workspace(occ.copy(), start, goal, corner_cutting=False)
    try:
        res = astar(ws)
    except NoPathError:
        return math.inf
    return res.length / math.hypot(start[0] - goal[0], start[1] - goal[1])


def _closest_pair(cells_a, cells_b, target):
    best = None
    for a in cells_a:
        for b in cells_b:
            d = math.hypot(a[0] - b[0], a[1] - b[1])
            key = (abs(d - target), a, b)
            if best is None or key < best:
                best = key
    return best[1], best[2]


def _check_int(value, name, lo):
    try:
        v = int(value)
    except (TypeError, ValueError):
        raise ConfigError(f"{name} must be an integer >= {lo}, got {value!r}") from None
    if v != value or v < lo:
        raise ConfigError(f"{name} must be an integer >= {lo}, got {value!r}")
    return v


# ---------------------------------------------------------------------------
# complex maze
# ---------------------------------------------------------------------------


def complex_maze(
    seed: int = 0,
    *,
    rows: int = 8,
    cols: int = 8,
    corridor: int = 4,
    max_detour: float = 1.20,
    target_distance: float = SEED_DISTANCE["maze"],
    cell_size: float = 1.0,
) -> Workspace:
    """A braided maze with wide corridors (NO-MOPP's "complex map").

    Parameters
    ----------
    seed : int
        Random seed (the same seed gives the same maze).
    rows, cols : int, default 8
        Maze cells (the coarse lattice); the grid has
        ``rows * (corridor + 1) - 1`` rows, likewise for columns.
    corridor : int, default 4
        Corridor width in cells; walls are one cell thick. (Four cells leave
        a car room to pass an obstacle of one or two cells without
        manoeuvring.)
    max_detour : float, default 1.20
        Walls are removed until the shortest 8-connected path (no corner
        cutting) is at most this times the straight-line distance.
    target_distance : float, default 51.856
        Start and goal are chosen in the corner maze cells so that their
        distance (world units) is nearest this.
    cell_size : float, default 1.0
        Metres per cell.

    Returns
    -------
    Workspace
        Named ``maze-s<seed>``.

    Raises
    ------
    ConfigError
        On sizes below 2 maze cells, a corridor below 1, or ``max_detour < 1``.

    Examples
    --------
    >>> ws = complex_maze(0)
    >>> ws.shape, 50 <= straight_line_distance(ws) <= 60
    ((39, 39), True)
    """
    nr = _check_int(rows, "rows", 2)
    nc = _check_int(cols, "cols", 2)
    k = _check_int(corridor, "corridor", 1)
    if not float(max_detour) >= 1.0:
        raise ConfigError(f"max_detour must be >= 1, got {max_detour!r}")
    rng = np.random.default_rng(seed)
    p = k + 1
    h, w = nr * p - 1, nc * p - 1
    occ = np.zeros((h, w), bool)
    for i in range(1, nr):
        occ[i * p - 1, :] = True
    for j in range(1, nc):
        occ[:, j * p - 1] = True

    def wall_cells(a, b):
        """Cells of the wall between maze cells a and b (adjacent)."""
        (i1, j1), (i2, j2) = sorted((a, b))
        if i1 == i2:  # east-west neighbours
            col = j2 * p - 1
            return (slice(i1 * p, i1 * p + k), slice(col, col + 1))
        row = i2 * p - 1
        return (slice(row, row + 1), slice(j1 * p, j1 * p + k))

    # perfect maze: randomised depth-first search
    seen = np.zeros((nr, nc), bool)
    stack = [(nr - 1, 0)]
    seen[nr - 1, 0] = True
    while stack:
        i, j = stack[-1]
        nbrs = [
            (i + di, j + dj)
            for di, dj in ((0, 1), (1, 0), (0, -1), (-1, 0))
            if 0 <= i + di < nr and 0 <= j + dj < nc and not seen[i + di, j + dj]
        ]
        if not nbrs:
            stack.pop()
            continue
        nxt = nbrs[int(rng.integers(len(nbrs)))]
        occ[wall_cells((i, j), nxt)] = False
        seen[nxt] = True
        stack.append(nxt)

    def corner_cells(i, j):
        return [(i * p + a, j * p + b) for a in range(k) for b in range(k)]

    start, goal = _closest_pair(
        corner_cells(nr - 1, 0), corner_cells(0, nc - 1), float(target_distance) / cell_size
    )
    # braid: remove the remaining walls in a random order until the detour is small
    walls = [((i, j), (i, j + 1)) for i in range(nr) for j in range(nc - 1)] + [
        ((i, j), (i + 1, j)) for i in range(nr - 1) for j in range(nc)
    ]
    walls = [wl for wl in walls if occ[wall_cells(*wl)].all()]
    order = rng.permutation(len(walls))
    ratio = _grid_ratio(occ, start, goal)
    for idx in order:
        if ratio <= max_detour:
            break
        occ[wall_cells(*walls[idx])] = False
        ratio = _grid_ratio(occ, start, goal)
    return Workspace(occ, start, goal, cell_size=cell_size, name=f"maze-s{seed}")


# ---------------------------------------------------------------------------
# warehouse
# ---------------------------------------------------------------------------


def warehouse(
    seed: int = 0,
    *,
    height: int = 48,
    width: int = 66,
    shelf_length: int = 10,
    aisle: int = 4,
    dock_depth: int = 7,
    missing: float = 0.1,
    pallets: int = 6,
    target_distance: float = SEED_DISTANCE["warehouse"],
    cell_size: float = 1.0,
) -> Workspace:
    """A warehouse floor with shelves, aisles and a loading dock.

    Shelves are 2 cells deep and ``shelf_length`` long, in rows separated by
    aisles ``aisle`` wide and in columns separated by cross aisles ``aisle``
    wide, with an ``aisle``-wide free band along every wall; a share
    ``missing`` of the shelf blocks is left out (empty bays). The bottom
    ``dock_depth`` rows are the loading dock with ``pallets`` single-cell
    pallets. The start is a dock cell at the bottom left; the goal (the
    package pick-up point) is an aisle cell touching a shelf at the top
    right, the pair chosen with the straight-line distance nearest
    ``target_distance``.

    Parameters
    ----------
    seed : int
    height, width : int, default 48 and 66
        Grid size (cells).
    shelf_length, aisle, dock_depth : int
    missing : float in [0, 1), default 0.1
    pallets : int, default 6
    target_distance : float, default 62.1488 (NO-MOPP's Table II)
    cell_size : float, default 1.0

    Returns
    -------
    Workspace
        Named ``warehouse-s<seed>``.

    Raises
    ------
    ConfigError
        On sizes that leave no room for shelves, or ``missing`` outside [0, 1).

    Examples
    --------
    >>> ws = warehouse(0)
    >>> 55 <= straight_line_distance(ws) <= 65
    True
    """
    h = _check_int(height, "height", 16)
    w = _check_int(width, "width", 16)
    L = _check_int(shelf_length, "shelf_length", 1)
    a = _check_int(aisle, "aisle", 1)
    dock = _check_int(dock_depth, "dock_depth", 2)
    n_pal = _check_int(pallets, "pallets", 0)
    if not 0.0 <= float(missing) < 1.0:
        raise ConfigError(f"missing must be in [0, 1), got {missing!r}")
    rng = np.random.default_rng(seed)
    occ = np.zeros((h, w), bool)
    top = a
    bottom = h - dock  # shelves end above the dock
    shelf_rows = list(range(top, bottom - 2 - a + 1, 2 + a))
    shelf_cols = list(range(a, w - a - L + 1, L + a))
    if not shelf_rows or not shelf_cols:
        raise ConfigError(f"a {h}x{w} warehouse leaves no room for shelves")
    faces = []
    for r0 in shelf_rows:
        for c0 in shelf_cols:
            if rng.random() < missing:
                continue
            occ[r0 : r0 + 2, c0 : c0 + L] = True
            faces.extend((r0 - 1, c) for c in range(c0, c0 + L))  # aisle above
            faces.extend((r0 + 2, c) for c in range(c0, c0 + L))  # aisle below
    # pallets on the dock, away from the start corner
    dock_cells = [(r, c) for r in range(bottom + 1, h - 1) for c in range(6, w - 1)]
    for idx in rng.choice(len(dock_cells), size=min(n_pal, len(dock_cells)), replace=False):
        occ[dock_cells[idx]] = True
    starts = [(r, c) for r in range(h - 3, h - 1) for c in range(1, 4) if not occ[r, c]]
    goals = [(r, c) for (r, c) in faces if 0 <= r < h and not occ[r, c] and r <= h // 3 and c >= (2 * w) // 3]
    if not starts or not goals:
        raise ConfigError("the warehouse layout left no start or goal cell")
    start, goal = _closest_pair(starts, goals, float(target_distance) / cell_size)
    return Workspace(occ, start, goal, cell_size=cell_size, name=f"warehouse-s{seed}")


def load_scenario_map(path, start=None, goal=None, **kwargs) -> Workspace:
    """Any map file gapath reads (see :func:`gapath.loaders.load_map`)."""

    return load_map(path, start=start, goal=goal, **kwargs)


#: Map generators by scenario name.
SCENARIOS = {"maze": complex_maze, "warehouse": warehouse}


# ---------------------------------------------------------------------------
# dynamic obstacles and whole scenarios
# ---------------------------------------------------------------------------


@dataclass(eq=False)
class Scenario:
    """A static map with its start and goal and the dynamic obstacles of
    one run.

    Attributes
    ----------
    workspace : Workspace
    stationary : list of :class:`gapath.dynamic.StationaryObstacle`
    moving : list of :class:`gapath.dynamic.MovingObstacle`
    start : (x, y, theta)
        The robot's start pose (world units).
    reference_path : (n, 2) float array
        The grid shortest path (world points) the obstacles were placed on.
    name : str
    seed : int
        The obstacle seed.
    """

    workspace: Workspace
    stationary: list
    moving: list
    start: tuple
    reference_path: np.ndarray
    name: str = "scenario"
    seed: int = 0

    @property
    def direct_distance(self) -> float:
        return straight_line_distance(self.workspace)

    def simulate(self, planner="hybrid-astar", robot=None, settings=None, seed=None):
        """Run this scenario (see :func:`gapath.dynamic.simulate`)."""

        return simulate(
            self.workspace,
            planner,
            robot,
            self.stationary,
            self.moving,
            settings,
            self.start,
            self.seed if seed is None else seed,
        )


def _reference_path(workspace) -> np.ndarray:

    ws = workspace.replace(corner_cutting=False)
    cells = astar(ws).path
    return cells[:, ::-1].astype(float) * workspace.cell_size


def _free_run(occ, p, direction, radius, max_len, cs, step=0.25):
    """How far a disc can go from ``p`` along ``direction`` (world units)."""

    d = 0.0
    while d + step <= max_len:
        q = p + direction * (d + step)
        if not disc_free(occ, q[0] / cs, q[1] / cs, radius / cs):
            break
        d += step
    return d


def dynamic_obstacles(
    workspace,
    seed: int = 0,
    *,
    n_stationary: int = 3,
    n_crossers: int = 2,
    n_wanderers: int = 2,
    robot_speed: float = 1.0,
    sensor_range: float = 6.0,
    obstacle_radius: float = 0.4,
    speed_range=(0.3, 0.7),
    min_run: float = 4.0,
):
    """Seeded dynamic obstacles for one run on any map.

    * ``n_stationary`` obstacles of one or two cells on the reference path
      (the grid shortest path, no corner cutting), spread along its middle
      (15-85 % of its length), appearing while the robot is still more than
      ``sensor_range + 2`` away from them at cruise speed (so they are first
      seen from afar, as new obstacles are in the paper); a placement that
      would disconnect start and goal is redrawn.
    * ``n_crossers`` moving obstacles timed to cross the reference path
      where the robot would be at cruise speed (the paper's Fig. 5): a point
      of the path at 15-85 % of its length and a direction are drawn; the
      obstacle starts on the line through that point, at least ``min_run``
      back along free space (it appears there at the matching time if the
      free run is shorter than the time to the crossing needs).
    * ``n_wanderers`` moving obstacles at random free places at least 8 m
      from the start, in random directions.

    Moving obstacles bounce; their speeds are uniform in ``speed_range`` and
    their radius is ``obstacle_radius``.

    Returns
    -------
    (stationary, moving, reference_path)

    Raises
    ------
    ConfigError
        On negative counts or speeds, or a map without a path.
    """

    for name, v in (("n_stationary", n_stationary), ("n_crossers", n_crossers), ("n_wanderers", n_wanderers)):
        _check_int(v, name, 0)
    lo, hi = (float(v) for v in speed_range)
    if not 0 < lo <= hi:
        raise ConfigError(f"speed_range must be 0 < low <= high, got {speed_range!r}")
    if not robot_speed > 0:
        raise ConfigError(f"robot_speed must be > 0, got {robot_speed!r}")
    if not obstacle_radius > 0:
        raise ConfigError(f"obstacle_radius must be > 0, got {obstacle_radius!r}")
    rng = np.random.default_rng(seed)
    cs = workspace.cell_size
    try:
        ref = _reference_path(workspace)
    except NoPathError as exc:
        raise ConfigError(f"the map has no path from start to goal: {exc}") from None
    S = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(ref, axis=0).T))])
    L = S[-1]
    occ = np.array(workspace.occ, dtype=bool)
    start = np.array(ref[0])
    goal = np.array(ref[-1])

    def point_at(s):
        i = min(int(np.searchsorted(S, s, side="right")) - 1, len(ref) - 2)
        f = (s - S[i]) / max(S[i + 1] - S[i], 1e-12)
        return ref[i] + f * (ref[i + 1] - ref[i])

    stationary = []
    blocked = occ.copy()
    for i in range(int(n_stationary)):
        for _ in range(50):
            a, b = 0.15 + 0.7 * i / max(n_stationary, 1), 0.15 + 0.7 * (i + 1) / max(n_stationary, 1)
            s = float(rng.uniform(a, b) * L)
            p = point_at(s)
            r, c = int(round(p[1] / cs)), int(round(p[0] / cs))
            cells = [(r, c)]
            if rng.random() < 0.5:
                dr, dc = ((0, 1), (1, 0), (0, -1), (-1, 0))[int(rng.integers(4))]
                if 0 <= r + dr < occ.shape[0] and 0 <= c + dc < occ.shape[1]:
                    cells.append((r + dr, c + dc))
            if any(occ[q] or blocked[q] for q in cells):
                continue
            if any(
                math.hypot(q[1] * cs - e[0], q[0] * cs - e[1]) < 3.0 * cs
                for q in cells
                for e in (start, goal)
            ):
                continue
            trial = blocked.copy()
            for q in cells:
                trial[q] = True
            if not math.isfinite(_grid_ratio(trial, workspace.start, workspace.goal)):
                continue
            blocked = trial
            latest = max(0.0, (s - sensor_range - 2.0) / robot_speed)
            stationary.append(StationaryObstacle(np.array(cells), float(rng.uniform(0, latest))))
            break

    moving = []
    for _ in range(int(n_crossers)):
        best = None
        for _ in range(40):
            s = float(rng.uniform(0.15, 0.85) * L)
            p = point_at(s)
            if not disc_free(occ, p[0] / cs, p[1] / cs, obstacle_radius / cs):
                continue
            ang = float(rng.uniform(0, 2 * math.pi))
            u = float(rng.uniform(lo, hi))
            direction = np.array([math.cos(ang), math.sin(ang)])
            t_cross = s / robot_speed
            need = u * t_cross
            run = _free_run(occ, p, -direction, obstacle_radius, need, cs)
            if best is None or run > best[0]:
                best = (run, p, direction, u, t_cross, need)
            if run >= min(need, 2 * min_run):
                break
        if best is None or best[0] < min(min_run, best[5]):
            continue
        run, p, direction, u, t_cross, need = best
        q = p - direction * min(run, need)
        appear = max(0.0, t_cross - min(run, need) / u)
        moving.append(MovingObstacle(q, direction * u, obstacle_radius, "bounce", appear))
    free = np.argwhere(~occ)
    for _ in range(int(n_wanderers)):
        for _ in range(100):
            r, c = free[int(rng.integers(len(free)))]
            p = np.array([c * cs, r * cs], float)
            if np.hypot(*(p - start)) < 8.0 or np.hypot(*(p - goal)) < 3.0:
                continue
            if not disc_free(occ, p[0] / cs, p[1] / cs, obstacle_radius / cs):
                continue
            ang = float(rng.uniform(0, 2 * math.pi))
            u = float(rng.uniform(lo, hi))
            moving.append(
                MovingObstacle(p, (u * math.cos(ang), u * math.sin(ang)), obstacle_radius, "bounce", 0.0)
            )
            break
    return stationary, moving, ref


def make_scenario(
    kind="maze", seed: int = 0, *, map_seed: int = 0, start=None, goal=None, **obstacle_kw
) -> Scenario:
    """A scenario: the map (``"maze"``, ``"warehouse"``, a map file path or a
    Workspace) with seeded dynamic obstacles (:func:`dynamic_obstacles`).

    ``map_seed`` seeds the generated map (the same map for every run of a
    study); ``seed`` seeds the obstacles.

    Raises
    ------
    ConfigError
        On an unknown kind or bad obstacle settings.
    """

    if isinstance(kind, Workspace):
        ws = kind
    elif kind in SCENARIOS:
        ws = SCENARIOS[kind](map_seed)
    elif isinstance(kind, str) and "." in kind:
        ws = load_scenario_map(kind, start=start, goal=goal)
    else:
        raise ConfigError(
            f"unknown scenario {kind!r}; choose one of {', '.join(SCENARIOS)} or give a map file"
        )
    generated = isinstance(kind, Workspace) or kind in SCENARIOS
    changes = {k: v for k, v in (("start", start), ("goal", goal)) if v is not None}
    if generated and changes:
        ws = ws.replace(**changes)
    stationary, moving, ref = dynamic_obstacles(ws, seed, **obstacle_kw)
    return Scenario(ws, stationary, moving, start_pose(ws), ref, name=f"{ws.name}-o{seed}", seed=int(seed))
