"""Planners the simulation drives: the :class:`Planner` interface and its adapters (hybrid A*, RRT/RRT*, grid A*, D* Lite)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from gapath.dynamic.world import Robot
from gapath.errors import ConfigError, NoPathError
from gapath.planners.astar import astar
from gapath.planners.dstar_lite import DStarLite
from gapath.planners.geometry import center_blocked
from gapath.planners.hybrid_astar import HybridAStar, pose_cell
from gapath.planners.registry import SIMULATED_PLANNERS
from gapath.planners.rrt import rrt
from gapath.workspace import Workspace


def _poses_from_points(points: np.ndarray) -> np.ndarray:
    pts = np.asarray(points, float)
    if len(pts) == 1:
        return np.column_stack([pts, [0.0]])
    d = np.diff(pts, axis=0)
    th = np.arctan2(d[:, 1], d[:, 0])
    return np.column_stack([pts, np.append(th, th[-1])])


class Planner:
    """Interface of the planners the simulation drives.

    A planner keeps the robot's *known* map: :meth:`reset` gives it the
    static map at the start of a run, :meth:`update_cells` the obstacles the
    sensors find, and :meth:`plan` returns world poses ``(n, 3)`` from
    ``start`` (a pose) to ``goal`` (a point or a pose) or raises
    :class:`~gapath.errors.NoPathError` (or ConfigError when the start is
    not free for it). ``blocked`` marks extra cells for one call (moving
    obstacles' sweeps), ``cost`` is a cost layer (DSO + DMO) a planner may
    use. ``incremental`` planners are always asked for the whole path to
    the goal (so they can repair their previous search); the others are
    asked for local segments too.
    """

    name = "planner"
    incremental = False

    def reset(self, workspace, robot: Robot, seed: int = 0) -> None:
        self.workspace = workspace
        self.robot = robot
        self.cell_size = float(workspace.cell_size)
        self.known = np.array(workspace.occ, dtype=np.bool_, copy=True)
        self.seed = seed

    def update_cells(self, cells, blocked: bool = True) -> None:
        cells = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
        self.known[cells[:, 0], cells[:, 1]] = blocked

    def plan(
        self, start, goal, *, blocked=None, cost=None, max_length=None
    ) -> np.ndarray:  # pragma: no cover
        raise NotImplementedError


class HybridAStarPlanner(Planner):
    """NO-MOPP: hybrid A* (:class:`~gapath.planners.hybrid_astar.HybridAStar`)
    with the DSO + DMO cost layer. Keyword arguments go to ``HybridAStar``
    (``max_expansions`` defaults to 200 000); local plans (to a rejoin pose,
    or with a length bound) get ``local_max_expansions``."""

    name = "hybrid-astar"

    def __init__(self, local_max_expansions: int = 20_000, **settings):
        settings.setdefault("max_expansions", 200_000)
        self.local_max_expansions = int(local_max_expansions)
        self.settings = settings

    def reset(self, workspace, robot, seed=0):
        super().reset(workspace, robot, seed)
        self.planner = HybridAStar(workspace, robot.car, **self.settings)

    def update_cells(self, cells, blocked=True):
        super().update_cells(cells, blocked)
        self.planner.update_cells(cells, blocked)

    def plan(self, start, goal, *, blocked=None, cost=None, max_length=None):
        local = len(goal) == 3 or max_length is not None
        res = self.planner.plan(
            start,
            goal,
            blocked=blocked,
            cost=cost,
            max_length=max_length,
            max_expansions=self.local_max_expansions if local else None,
        )
        self.last = res
        return np.asarray(res.poses)


class RRTPlanner(Planner):
    """RRT or RRT* (:func:`gapath.planners.rrt.rrt`), seeded per run and
    per call. Keyword arguments go to ``rrt``."""

    def __init__(self, star: bool = False, **settings):
        self.star = bool(star)
        self.name = "rrt-star" if self.star else "rrt"
        self.settings = settings

    def reset(self, workspace, robot, seed=0):
        super().reset(workspace, robot, seed)
        self.rng = np.random.default_rng([int(seed), 1 + int(self.star)])

    def plan(self, start, goal, *, blocked=None, cost=None, max_length=None):

        ws = SimpleNamespace(occ=self.known, cell_size=self.cell_size)
        res = rrt(
            ws,
            start[:2],
            goal[:2],
            seed=self.rng,
            radius=self.robot.radius,
            star=self.star,
            blocked=blocked,
            **self.settings,
        )
        self.last = res
        return np.array(res.poses)


class _GridPlanner(Planner):
    """Shared parts of the grid planners: the robot's disc is safe between
    free cell centres without corner cutting when ``radius < 0.5`` cells;
    for larger robots cells whose centre is not free for the disc are
    blocked too (an approximation)."""

    def reset(self, workspace, robot, seed=0):
        super().reset(workspace, robot, seed)
        self._inflate = robot.radius / self.cell_size >= 0.5

    def _grid(self, blocked):
        occ = self.known
        if self._inflate:
            occ = center_blocked(np.ascontiguousarray(occ), self.robot.radius / self.cell_size)
        if blocked is not None:
            occ = occ | blocked
        return occ

    def _cells(self, start, goal):
        cs = self.cell_size
        return pose_cell(start, cs), pose_cell(goal, cs)

    def _poses(self, cells, start, goal):
        cs = self.cell_size
        pts = np.asarray(cells, float)[:, ::-1] * cs
        if np.hypot(*(pts[0] - np.asarray(start[:2]))) > 1e-9:
            pts = np.vstack([np.asarray(start[:2], float), pts])
        if np.hypot(*(pts[-1] - np.asarray(goal[:2]))) > 1e-9:
            pts = np.vstack([pts, np.asarray(goal[:2], float)])
        return _poses_from_points(pts)


class AStarPlanner(_GridPlanner):
    """Grid A* (:func:`gapath.planners.astar.astar`), 8-connected without
    corner cutting, replanning from scratch."""

    name = "astar"

    def plan(self, start, goal, *, blocked=None, cost=None, max_length=None):

        occ = self._grid(blocked)
        s, g = self._cells(start, goal)
        occ = occ.copy()
        occ[s] = False  # the robot's own cell (it is there)
        ws = Workspace(occ, s, g, cell_size=self.cell_size, corner_cutting=False)
        res = astar(ws)
        self.last = res
        return self._poses(res.path, start, goal)


class DStarLitePlanner(_GridPlanner):
    """D* Lite (:class:`gapath.planners.dstar_lite.DStarLite`): one search
    per run, repaired after every map change and robot move."""

    name = "dstar-lite"
    incremental = True

    def reset(self, workspace, robot, seed=0):
        super().reset(workspace, robot, seed)
        self.dstar = None

    def plan(self, start, goal, *, blocked=None, cost=None, max_length=None):

        occ = self._grid(blocked).copy()
        s, g = self._cells(start, goal)
        occ[s] = False
        if occ[g]:
            raise NoPathError(f"the goal cell {g} is blocked")
        if self.dstar is None or self.dstar.goal != g:
            ws = Workspace(occ, s, g, cell_size=self.cell_size, corner_cutting=False)
            self.dstar = DStarLite(ws)
            res = self.dstar.plan()
        else:
            cur = self.dstar.occ
            diff = np.argwhere(cur != occ)
            free = diff[~occ[diff[:, 0], diff[:, 1]]] if len(diff) else diff
            block = diff[occ[diff[:, 0], diff[:, 1]]] if len(diff) else diff
            if len(free):
                self.dstar.update_cells(free, blocked=False)
            self.dstar.move_to(s)
            if len(block):
                self.dstar.update_cells(block, blocked=True)
            res = self.dstar.replan()
        self.last = res
        return self._poses(res.path, start, goal)


#: Names of the planners the simulation drives: the entries of the planner
#: registry (:data:`gapath.planners.PLANNERS`) marked ``simulated``.
PLANNERS = SIMULATED_PLANNERS

#: The simulation's adapter of each planner in :data:`PLANNERS`.
_ADAPTERS = {
    "hybrid-astar": HybridAStarPlanner,
    "rrt": lambda **kw: RRTPlanner(star=False, **kw),
    "rrt-star": lambda **kw: RRTPlanner(star=True, **kw),
    "astar": AStarPlanner,
    "dstar-lite": DStarLitePlanner,
}


def make_planner(name: str, **settings) -> Planner:
    """A planner by name: ``hybrid-astar``, ``rrt``, ``rrt-star``, ``astar``
    or ``dstar-lite`` (:data:`PLANNERS`).

    Raises
    ------
    ConfigError
        On an unknown name.
    """
    if name not in PLANNERS:
        raise ConfigError(f"unknown planner {name!r}; choose one of {', '.join(PLANNERS)}")
    return _ADAPTERS[name](**settings)
