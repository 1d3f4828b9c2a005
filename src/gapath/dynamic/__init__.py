"""Dynamic environments: a seeded simulation of a robot among appearing and
moving obstacles, with collision prediction and local replanning (NO-MOPP).

The world
    * the *known static* obstacles of a :class:`~gapath.workspace.Workspace`
      (the robot knows them before it starts);
    * :class:`StationaryObstacle` -- cells that become obstacles at a given
      time (the paper's "dynamic stationary obstacles", unknown to the robot
      until its sensor sees them). One appears only when it does not overlap
      the robot's disc grown by ``appear_clearance`` (otherwise it waits);
    * :class:`MovingObstacle` -- discs with their own constant velocity that
      either ``"bounce"`` off the map edges and the obstacles (each velocity
      component is reflected on contact) or ``"pass"`` through the map
      (straight through everything until they leave it);
    * a :class:`Robot`: a car (:class:`~gapath.planners.hybrid_astar.CarModel`:
      wheelbase, steering, speed, footprint radius) with a sensor of range
      ``sensor_range`` and field of view ``+-fov`` degrees around its heading
      (45, 90 or 180 in the paper), blocked by the static walls
      (line of sight).

Coordinates are the world frame of :mod:`gapath.planners.hybrid_astar`:
``x = col * cell_size``, ``y = row * cell_size``, headings from ``+x``
towards ``+y``.

Each tick (``dt`` seconds) of :class:`Simulation` -- the paper's Algorithm 2
-- does, in order:

1. *World*: stationary obstacles due appear; moving obstacles move.
2. *Sense*: obstacles in range, in the field of view and in line of sight
   are detected. New stationary cells go into the robot's known map (and
   the planner's: :meth:`Planner.update_cells`); moving obstacles are
   tracked with their position and velocity (kept ``memory`` seconds after
   they leave the view, extrapolated at constant velocity).
3. *Known obstacles on the path*: if the rest of the path now meets a known
   obstacle, the affected segment is replanned (:meth:`Simulation.replan`):
   a *local* plan from the robot's pose to a rejoin pose on the path beyond
   the blocked part (``rejoin_margin`` further; further candidates, then the
   goal, if that fails), spliced into the path. Incremental planners (D*
   Lite) replan to the goal instead, repairing their previous search.
4. *Collision prediction* (eqs. (7)-(10) of the paper): for every tracked
   moving obstacle, the robot's motion along its path at cruise speed and
   the obstacle's constant-velocity motion are solved exactly, segment by
   segment of the path, for the first time their distance falls to
   ``robot.radius + obstacle.radius + safety_margin``
   (:func:`path_contact`; :func:`time_to_collision` and
   :func:`closest_approach` for two constant-velocity points).
   If a collision is predicted and the obstacle is still at least
   ``replan_distance`` away (and the time to collision at least
   ``halt_time``), the segment is replanned around the obstacle's predicted
   sweep over ``sweep_time`` seconds (blocked cells, plus the DMO cost layer
   for the hybrid A*) and the new path is taken if no collision is
   predicted on it. Otherwise, once the obstacle is nearer than
   ``replan_distance`` or the collision nearer than ``halt_time``, the robot
   *halts and waits* for it to pass -- or, if waiting in place would be hit
   too, *backs off* along its path, whichever is predicted safe (the
   latest collision if neither).
5. *Move* along the path by ``speed * dt`` (0 when halted, negative when
   backing off).
6. *Check* the truth: the robot's disc against the static and appeared
   obstacles, and against every moving obstacle over the whole tick
   (closest approach of the two straight motions). A collision ends the run
   as failed.

A run ends with ``reason`` ``"goal"`` (success: within ``goal_tolerance``
of the goal with no collision), ``"collision"``, ``"blocked"`` (no path for
``blocked_patience`` seconds, including no global path at the start) or
``"timeout"`` (``max_time``). It never raises for these: an unreachable goal
is a failed run with its reason.

Planners plug in through :class:`Planner`: :class:`HybridAStarPlanner`
(NO-MOPP), :class:`RRTPlanner` (RRT and RRT*), :class:`AStarPlanner` and
:class:`DStarLitePlanner`; :func:`make_planner` builds one by name.

Modules: :mod:`~gapath.dynamic.prediction` (motion equations),
:mod:`~gapath.dynamic.world` (obstacles, robot, settings),
:mod:`~gapath.dynamic.planners` (planner adapters),
:mod:`~gapath.dynamic.results` and :mod:`~gapath.dynamic.simulation`.
"""

from gapath.dynamic.planners import (
    PLANNERS,
    AStarPlanner,
    DStarLitePlanner,
    HybridAStarPlanner,
    Planner,
    RRTPlanner,
    make_planner,
)
from gapath.dynamic.prediction import closest_approach, crossing_point, path_contact, time_to_collision
from gapath.dynamic.results import SimResult
from gapath.dynamic.simulation import Simulation, simulate, start_pose
from gapath.dynamic.world import MovingObstacle, Robot, SimSettings, StationaryObstacle

__all__ = [
    "AStarPlanner",
    "DStarLitePlanner",
    "HybridAStarPlanner",
    "MovingObstacle",
    "PLANNERS",
    "Planner",
    "RRTPlanner",
    "Robot",
    "SimResult",
    "SimSettings",
    "Simulation",
    "StationaryObstacle",
    "closest_approach",
    "crossing_point",
    "make_planner",
    "path_contact",
    "simulate",
    "start_pose",
    "time_to_collision",
]
