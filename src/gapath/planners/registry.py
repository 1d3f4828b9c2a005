"""One entry point for every single-path planner: :func:`plan`.

``plan(workspace, planner, **options)`` plans one path from the
workspace's start to its goal with a planner named in :data:`PLANNERS` and
returns a :class:`PlanOutcome`, whatever the planner. The names are the
ones of ``gapath plan --planner`` and ``gapath simulate --planner``:

* grid planners on a layered costmap (:mod:`gapath.planners.pareto`):
  ``astar`` and ``dstar-lite`` (the normalised weighted sum of the
  objectives; without cost layers a shortest path), ``astar-po`` and
  ``dstar-po`` (Lavin's Pareto-optimal A* and D*);
* kinematic planners for a car-like robot, continuous poses:
  ``hybrid-astar`` (:mod:`gapath.planners.hybrid_astar`), ``rrt`` and
  ``rrt-star`` (:mod:`gapath.planners.rrt`).

Every name maps to one thin wrapper (its options, the call, the figures it
reports) over one worker (:func:`plan`: look-up, option check, timing,
result). :data:`PLANNERS` also says which planners the dynamic-obstacle
simulation (:mod:`gapath.dynamic`) drives. :class:`CarSettings` holds the
car in a user's units (steering in degrees) with the defaults of
``gapath plan`` and ``gapath simulate``.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from gapath.errors import ConfigError
from gapath.planners.hybrid_astar import CarModel

if TYPE_CHECKING:
    from gapath.costmap import Costmap
    from gapath.workspace import Workspace

__all__ = [
    "PLANNERS",
    "SIMULATED_PLANNERS",
    "CarSettings",
    "PlanOutcome",
    "PlannerInfo",
    "plan",
    "planner_info",
    "planner_names",
]

#: Planner families: paths of grid cells, or continuous poses of a car.
FAMILIES = ("grid", "kinematic")


@dataclass(frozen=True)
class CarSettings:
    """A car-like robot as a user describes it: the defaults of ``gapath
    plan`` and ``gapath simulate`` (their ``--wheelbase``, ``--max-steer``,
    ``--speed`` and ``--radius``).

    Parameters
    ----------
    wheelbase : float, default 0.6
        Distance between the axles, world units.
    max_steer_deg : float, default ``degrees(0.6)`` (34.38)
        Largest steering angle in degrees, strictly between 0 and 90
        (CarModel's default of 0.6 rad).
    speed : float, default 1.0
        World units per second (the simulation's cruise speed).
    radius : float, default 0.3
        Footprint radius, world units (0 for a point robot).

    Examples
    --------
    >>> car = CarSettings(max_steer_deg=45.0, wheelbase=1.0).model()
    >>> round(car.min_turning_radius, 6)
    1.0
    """

    # the defaults are CarModel's (the steering in degrees: 0.6 rad)
    wheelbase: float = CarModel.wheelbase
    max_steer_deg: float = math.degrees(CarModel.max_steer)
    speed: float = CarModel.speed
    radius: float = CarModel.radius

    def model(self) -> CarModel:
        """The :class:`~gapath.planners.hybrid_astar.CarModel` (steering in
        radians).

        Raises
        ------
        ConfigError
            On a steering angle that is not a number strictly between 0 and
            90 degrees, or a car :class:`CarModel` rejects (e.g. a
            non-positive wheelbase).
        """

        steer = self.max_steer_deg
        try:
            degrees = float(steer)
        except (TypeError, ValueError):
            raise ConfigError(f"max_steer_deg must be a number of degrees, got {steer!r}") from None
        if not 0.0 < degrees < 90.0:
            raise ConfigError(
                f"max_steer_deg must be between 0 and 90 degrees (both excluded), got {degrees:g}"
            )
        return CarModel(
            wheelbase=self.wheelbase, max_steer=math.radians(degrees), speed=self.speed, radius=self.radius
        )


@dataclass(eq=False)
class PlanOutcome:
    """A path from :func:`plan`, the same for every planner.

    Attributes
    ----------
    planner : str
        The planner's name (a key of :data:`PLANNERS`).
    poses : (n, 3) float array
        World poses ``(x, y, theta)`` with ``x = col * cell_size``, ``y =
        row * cell_size`` and ``theta`` from +x towards +y (down the map);
        a grid path's poses are its cell centres, heading along the step
        that leaves them.
    cells : (m, 2) int array
        The cells ``(row, col)`` the path passes through, start to goal.
    objectives : dict of str to float
        The path's objectives: those asked of a grid planner (``length``
        and the cost layers), ``length``, ``turning`` and ``clearance`` for
        a kinematic one.
    seconds : float
        Wall-clock time of the planning call.
    info : dict
        Planner figures for ``summary.json`` (``expansions``,
        ``search_cost``, ``iterations``, ``radius``, ...).
    result : object
        The planner's own result (:class:`~gapath.planners.pareto.ParetoPlanResult`,
        :class:`~gapath.planners.hybrid_astar.HybridPath` or
        :class:`~gapath.planners.rrt.RRTPath`).
    """

    planner: str
    poses: np.ndarray
    cells: np.ndarray
    objectives: dict[str, float]
    seconds: float
    info: dict[str, Any] = field(default_factory=dict)
    result: Any = field(default=None, repr=False)

    @property
    def F(self) -> np.ndarray:
        """The objective values as a ``(k,)`` float array, in the order of
        :attr:`objectives`."""
        return np.array([float(v) for v in self.objectives.values()], dtype=float)

    def records(self) -> list[dict[str, Any]]:
        """``paths.json`` content: ``[{"objectives", "path", "poses"}]``."""
        return [
            {
                "objectives": {k: float(v) for k, v in self.objectives.items()},
                "path": np.asarray(self.cells).tolist(),
                "poses": np.round(self.poses, 6).tolist(),
            }
        ]


@dataclass(frozen=True)
class PlannerInfo:
    """One entry of :data:`PLANNERS`.

    Attributes
    ----------
    name : str
        The planner's name.
    family : {"grid", "kinematic"}
        Paths of grid cells on a costmap, or continuous poses of a car.
    description : str
        One line for help texts.
    options : tuple of str
        The keyword options :func:`plan` accepts for it.
    simulated : bool
        Whether the dynamic-obstacle simulation (:mod:`gapath.dynamic`)
        drives it.
    """

    name: str
    family: str
    description: str
    options: tuple[str, ...]
    simulated: bool
    run: Callable[..., tuple[np.ndarray, np.ndarray, dict[str, float], dict[str, Any], Any]] = field(
        repr=False
    )


# ---------------------------------------------------------------------------
# the wrappers: options in, (poses, cells, objectives, info, result) out
# ---------------------------------------------------------------------------

# the options of each family: the wrapper's own plus the keyword settings of
# the planner it calls (tests/test_plan_registry.py checks them against the
# signatures)
_GRID_OPTIONS = ("costmap", "objectives", "priority", "weights", "baseline")
_HYBRID_OPTIONS = (
    "car",
    "heading",
    "heading_bins",
    "arc_length",
    "ds",
    "steer_cost",
    "steer_change_cost",
    "cost_weight",
    "heuristic",
    "heuristic_weight",
    "goal_tolerance",
    "heading_tolerance",
    "shot_distance",
    "shot_slack",
    "max_expansions",
)
_RRT_OPTIONS = (
    "car",
    "seed",
    "step",
    "goal_bias",
    "goal_tolerance",
    "max_iter",
    "rewire_radius",
    "extra_iterations",
    "ds",
)


def _grid_poses(cells: np.ndarray, cell_size: float) -> np.ndarray:
    """Poses of the cell centres, heading along the step that leaves each
    cell (the last one keeps the last step's heading)."""
    xy = np.asarray(cells, float)[:, ::-1] * cell_size
    if len(xy) == 1:
        return np.column_stack([xy, [0.0]])
    d = np.diff(xy, axis=0)
    th = np.arctan2(d[:, 1], d[:, 0])
    return np.column_stack([xy, np.append(th, th[-1])])


def _pose_cells(poses: np.ndarray, cell_size: float) -> np.ndarray:
    """The cells ``(row, col)`` continuous poses pass through (repeats dropped)."""
    rc = np.floor(np.asarray(poses)[:, [1, 0]] / cell_size + 0.5).astype(np.int64)
    keep = np.ones(len(rc), bool)
    keep[1:] = np.any(rc[1:] != rc[:-1], axis=1)
    return rc[keep]


def _grid(name: str) -> Callable[..., tuple]:
    def run(
        workspace: Workspace,
        *,
        costmap: Costmap | None = None,
        objectives: Any = ("length",),
        priority: str | None = None,
        weights: Any = None,
        baseline: str = "weighted",
    ) -> tuple:
        from gapath.costmap import Costmap
        from gapath.planners.pareto import plan as plan_on_costmap

        if costmap is None:
            costmap = Costmap(workspace)
        elif costmap.workspace is not workspace and costmap.workspace != workspace:
            raise ConfigError("the costmap is over another workspace than the one to plan on")
        res = plan_on_costmap(
            costmap, name, objectives, priority=priority, weights=weights, baseline=baseline
        )
        cells = np.asarray(res.path)
        info = {
            "expansions": res.expansions,
            "search_cost": dict(zip(res.objectives, map(float, res.search_cost))),
        }
        return _grid_poses(cells, workspace.cell_size), cells, res.values, info, res

    return run


def _car(car: CarModel | CarSettings | None) -> CarModel:
    if car is None:
        return CarSettings().model()
    if isinstance(car, CarSettings):
        return car.model()
    return car


def _hybrid_astar(workspace: Workspace, *, car: Any = None, heading: float | None = None, **settings: Any):
    from gapath.planners.hybrid_astar import HybridAStar

    model = _car(car)
    planner = HybridAStar(workspace, model, **settings)
    start = None
    if heading is not None:
        sr, sc = workspace.start
        cs = workspace.cell_size
        start = (sc * cs, sr * cs, float(heading))
    res = planner.plan(start)
    poses = np.asarray(res.poses)
    info = {
        "expansions": res.expansions,
        "reached": res.reached,
        "cost": res.cost,
        "min_turning_radius": model.min_turning_radius,
        "radius": model.radius,
        "heading_bins": planner.heading_bins,
        "arc_length": planner.arc_length,
    }
    objectives = {"length": res.length, "turning": res.turning, "clearance": res.clearance}
    return poses, _pose_cells(poses, workspace.cell_size), objectives, info, res


def _rrt(star: bool) -> Callable[..., tuple]:
    def run(workspace: Workspace, *, car: Any = None, seed: Any = 0, **settings: Any) -> tuple:
        from gapath.planners.rrt import rrt

        model = _car(car)
        res = rrt(workspace, seed=seed, radius=model.radius, star=star, **settings)
        poses = np.asarray(res.poses)
        info = {
            "iterations": res.iterations,
            "nodes": res.nodes,
            "first_solution": res.first_solution,
            "radius": model.radius,
            "seed": seed,
        }
        objectives = {"length": res.length, "turning": res.turning, "clearance": res.clearance}
        return poses, _pose_cells(poses, workspace.cell_size), objectives, info, res

    return run


#: Every planner by name, in the order of ``gapath plan --planner``.
PLANNERS: Mapping[str, PlannerInfo] = {
    p.name: p
    for p in (
        PlannerInfo(
            "astar",
            "grid",
            "A* on the normalised weighted sum of the objectives (Lavin's A*)",
            _GRID_OPTIONS,
            True,
            _grid("astar"),
        ),
        PlannerInfo(
            "dstar-lite",
            "grid",
            "D* Lite on the normalised weighted sum of the objectives (Lavin's D*)",
            _GRID_OPTIONS,
            True,
            _grid("dstar-lite"),
        ),
        PlannerInfo(
            "astar-po", "grid", "Pareto-optimal A* (Lavin's A*-PO)", _GRID_OPTIONS, False, _grid("astar-po")
        ),
        PlannerInfo(
            "dstar-po", "grid", "Pareto-optimal D* (Lavin's D*-PO)", _GRID_OPTIONS, False, _grid("dstar-po")
        ),
        PlannerInfo(
            "hybrid-astar",
            "kinematic",
            "hybrid A* for a car-like robot (NO-MOPP's planner)",
            _HYBRID_OPTIONS,
            True,
            _hybrid_astar,
        ),
        PlannerInfo("rrt", "kinematic", "RRT for a disc robot", _RRT_OPTIONS, True, _rrt(False)),
        PlannerInfo("rrt-star", "kinematic", "RRT* for a disc robot", _RRT_OPTIONS, True, _rrt(True)),
    )
}


def planner_names(family: str | None = None, *, simulated: bool | None = None) -> tuple[str, ...]:
    """Names of :data:`PLANNERS`, optionally of one family or only those
    the simulation does (or does not) drive.

    Parameters
    ----------
    family : {"grid", "kinematic"}, optional
        Only the planners of this family.
    simulated : bool, optional
        Only the planners :mod:`gapath.dynamic` drives (True) or does not
        (False).

    Returns
    -------
    tuple of str
        In the order of :data:`PLANNERS`.

    Raises
    ------
    ConfigError
        On an unknown family.

    Examples
    --------
    >>> planner_names("kinematic")
    ('hybrid-astar', 'rrt', 'rrt-star')
    >>> planner_names("grid", simulated=True)
    ('astar', 'dstar-lite')
    """
    if family is not None and family not in FAMILIES:
        raise ConfigError(f"unknown planner family {family!r}; expected one of {', '.join(FAMILIES)}")
    return tuple(
        p.name
        for p in PLANNERS.values()
        if (family is None or p.family == family) and (simulated is None or p.simulated == simulated)
    )


#: The planners the dynamic-obstacle simulation drives, in the order of
#: ``gapath simulate --planner`` (the kinematic ones, its default first).
SIMULATED_PLANNERS = planner_names("kinematic", simulated=True) + planner_names("grid", simulated=True)


def planner_info(name: str) -> PlannerInfo:
    """The :data:`PLANNERS` entry of ``name``.

    Raises
    ------
    ConfigError
        On an unknown name (the message names it and the choices).

    Examples
    --------
    >>> planner_info("rrt-star").family
    'kinematic'
    >>> planner_info("dijkstra")
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: unknown planner 'dijkstra'; expected one of astar, dstar-lite, astar-po, dstar-po, hybrid-astar, rrt, rrt-star
    """
    try:
        return PLANNERS[name]
    except (KeyError, TypeError):
        raise ConfigError(f"unknown planner {name!r}; expected one of {', '.join(PLANNERS)}") from None


def plan(workspace: Workspace, planner: str = "dstar-po", **options: Any) -> PlanOutcome:
    """Plan one path from the workspace's start to its goal.

    Parameters
    ----------
    workspace : Workspace
        The map, start, goal, cell size and corner rule (grid planners
        follow the corner rule; kinematic ones check their footprint).
    planner : str, default "dstar-po"
        A name of :data:`PLANNERS`: ``astar``, ``dstar-lite``, ``astar-po``,
        ``dstar-po``, ``hybrid-astar``, ``rrt`` or ``rrt-star``.
    **options
        The planner's options (:attr:`PlannerInfo.options`):

        * grid planners: ``costmap`` (a :class:`gapath.costmap.Costmap` over
          ``workspace``; default one without layers), ``objectives``
          (default ``("length",)``: a shortest path), ``priority`` (Pareto
          planners) and ``weights`` (weighted-sum planners), see
          :func:`gapath.planners.pareto.plan`;
        * ``hybrid-astar``: ``car`` (a :class:`CarSettings` or
          :class:`~gapath.planners.hybrid_astar.CarModel`; default
          ``CarSettings()``), ``heading`` (start heading in radians from +x
          towards +y; default towards the goal) and the settings of
          :class:`~gapath.planners.hybrid_astar.HybridAStar`
          (``heading_bins``, ``arc_length``, ``heuristic_weight``, ...);
        * ``rrt``, ``rrt-star``: ``car`` (its ``radius`` is the robot's),
          ``seed`` (default 0) and the settings of
          :func:`~gapath.planners.rrt.rrt` (``max_iter``, ``step``,
          ``goal_bias``, ...).

    Returns
    -------
    PlanOutcome

    Raises
    ------
    ConfigError
        On an unknown planner or option (the message names it and the
        choices), or bad option values.
    NoPathError
        If the planner found no path.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> ws = Workspace(np.zeros((4, 6), bool))
    >>> out = plan(ws, "astar")
    >>> out.objectives["length"] == 5 + 3 * (2**0.5 - 1)
    True
    >>> tuple(out.cells[0]) == ws.start, tuple(out.cells[-1]) == ws.goal
    (True, True)
    >>> plan(ws, "astar", iterations=10)
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: unknown option 'iterations' for planner 'astar'; expected some of costmap, objectives, priority, weights, baseline
    """
    info = planner_info(planner)
    for key in options:
        if key not in info.options:
            raise ConfigError(
                f"unknown option {key!r} for planner {planner!r}; expected some of {', '.join(info.options)}"
            )
    t0 = time.perf_counter()
    poses, cells, objectives, figures, result = info.run(workspace, **options)
    seconds = time.perf_counter() - t0
    return PlanOutcome(
        planner=info.name,
        poses=poses,
        cells=cells,
        objectives=objectives,
        seconds=seconds,
        info=figures,
        result=result,
    )
