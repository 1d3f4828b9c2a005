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
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from types import SimpleNamespace

import numba
import numpy as np

from gapath.errors import ConfigError, GapathError, NoPathError
from gapath.planners._geometry import center_blocked, disc_free, first_blocked, segment_free
from gapath.planners.hybrid_astar import CarModel, HybridAStar, initial_heading, pose_cell

__all__ = [
    "AStarPlanner", "DStarLitePlanner", "HybridAStarPlanner", "MovingObstacle", "PLANNERS",
    "Planner", "RRTPlanner", "Robot", "SimResult", "SimSettings", "Simulation",
    "StationaryObstacle", "closest_approach", "crossing_point", "make_planner", "path_contact",
    "simulate", "start_pose", "time_to_collision",
]


# ---------------------------------------------------------------------------
# motion equations: prediction of collisions
# ---------------------------------------------------------------------------

@numba.njit(cache=True)
def _first_contact(d0x, d0y, dvx, dvy, radius, tmax):
    """First ``tau`` in ``[0, tmax]`` with ``|d0 + dv tau| <= radius``, else inf."""
    c = d0x * d0x + d0y * d0y - radius * radius
    if c <= 0.0:
        return 0.0
    a = dvx * dvx + dvy * dvy
    if a <= 0.0:
        return np.inf
    b = 2.0 * (d0x * dvx + d0y * dvy)
    if b >= 0.0:                       # moving apart (both roots negative)
        return np.inf
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return np.inf
    tau = (-b - math.sqrt(disc)) / (2.0 * a)
    if tau <= tmax:
        return max(tau, 0.0)
    return np.inf


@numba.njit(cache=True)
def _min_distance(d0x, d0y, dvx, dvy, tmax):
    """Smallest ``|d0 + dv tau|`` over ``tau in [0, tmax]``."""
    a = dvx * dvx + dvy * dvy
    tau = 0.0
    if a > 0.0:
        tau = -(d0x * dvx + d0y * dvy) / a
        tau = min(max(tau, 0.0), tmax)
    return math.hypot(d0x + dvx * tau, d0y + dvy * tau)


def time_to_collision(p_robot, v_robot, p_obstacle, v_obstacle, radius: float) -> float:
    """First time ``t >= 0`` at which two points moving at constant velocity
    come within ``radius`` (the sum of the radii); ``inf`` if never.

    Solves ``|(p_o - p_r) + (v_o - v_r) t| = radius`` (the paper's eqs.
    (7)-(9) with discs instead of points).

    Examples
    --------
    Head-on at 1 m/s each from 10 m apart, radii summing to 1:

    >>> time_to_collision((0, 0), (1, 0), (10, 0), (-1, 0), 1.0)
    4.5
    """
    d0 = np.subtract(p_obstacle, p_robot, dtype=float)
    dv = np.subtract(v_obstacle, v_robot, dtype=float)
    return float(_first_contact(d0[0], d0[1], dv[0], dv[1], float(radius), np.inf))


def closest_approach(p_robot, v_robot, p_obstacle, v_obstacle) -> tuple[float, float]:
    """Time ``t* >= 0`` and distance of the closest approach of two points
    moving at constant velocity.

    Examples
    --------
    >>> closest_approach((0, 0), (1, 0), (5, 5), (0, -1))
    (5.0, 0.0)
    """
    d0 = np.subtract(p_obstacle, p_robot, dtype=float)
    dv = np.subtract(v_obstacle, v_robot, dtype=float)
    a = float(dv @ dv)
    t = 0.0 if a == 0 else max(0.0, -float(d0 @ dv) / a)
    return t, float(np.hypot(*(d0 + dv * t)))


def crossing_point(p_robot, v_robot, p_obstacle, v_obstacle):
    """Where the two straight tracks cross, and when each gets there.

    The paper's eq. (10): ``p_r + v_r t_r = p_o + v_o t_o`` for ``t_r`` and
    ``t_o`` (two unknowns, two equations). Returns ``(point, t_r, t_o)``,
    or None when the tracks are parallel or cross behind either mover.

    Examples
    --------
    >>> crossing_point((0, 0), (1, 0), (5, 5), (0, -1))
    (array([5., 0.]), 5.0, 5.0)
    """
    pr = np.asarray(p_robot, float)
    vr = np.asarray(v_robot, float)
    po = np.asarray(p_obstacle, float)
    vo = np.asarray(v_obstacle, float)
    m = np.column_stack([vr, -vo])
    if abs(np.linalg.det(m)) < 1e-12:
        return None
    t_r, t_o = np.linalg.solve(m, po - pr)
    if t_r < 0 or t_o < 0:
        return None
    return pr + vr * t_r, float(t_r), float(t_o)


@numba.njit(cache=True)
def _path_contact(P, S, s0, v, horizon, ox, oy, ovx, ovy, radius):
    """Robot driving polyline ``P`` (arc lengths ``S``) from ``s0`` at signed
    speed ``v`` (stopping at the ends), obstacle at ``(ox, oy)`` with
    velocity ``(ovx, ovy)``. Returns ``(t_contact, min_distance)`` over
    ``[0, horizon]``; ``t_contact`` is inf when they stay apart."""
    n = P.shape[0]
    send = S[n - 1]
    # segment holding s0
    i = 0
    while i < n - 2 and S[i + 1] <= s0:
        i += 1
    t = 0.0
    s = min(max(s0, 0.0), send)
    dmin = np.inf
    while t < horizon:
        # robot position at s on segment i
        seg = S[i + 1] - S[i] if n > 1 else 0.0
        if seg > 0.0:
            f = (s - S[i]) / seg
            rx = P[i, 0] + f * (P[i + 1, 0] - P[i, 0])
            ry = P[i, 1] + f * (P[i + 1, 1] - P[i, 1])
            ux = (P[i + 1, 0] - P[i, 0]) / seg
            uy = (P[i + 1, 1] - P[i, 1]) / seg
        else:
            rx = P[i, 0]
            ry = P[i, 1]
            ux = 0.0
            uy = 0.0
        # duration of this piece of constant velocity
        if v > 0.0 and s < send:
            target = S[i + 1]
            dt = (target - s) / v
            vx = ux * v
            vy = uy * v
        elif v < 0.0 and s > 0.0:
            target = S[i]
            dt = (s - target) / (-v)
            vx = ux * v
            vy = uy * v
        else:
            target = s
            dt = horizon - t
            vx = 0.0
            vy = 0.0
        dt = min(dt, horizon - t)
        # obstacle at time t, relative motion
        d0x = ox + ovx * t - rx
        d0y = oy + ovy * t - ry
        dvx = ovx - vx
        dvy = ovy - vy
        tau = _first_contact(d0x, d0y, dvx, dvy, radius, dt)
        dm = _min_distance(d0x, d0y, dvx, dvy, min(tau, dt))
        if dm < dmin:
            dmin = dm
        if tau < np.inf:
            return t + tau, dmin
        t += dt
        if dt <= 0.0 and vx == 0.0 and vy == 0.0:
            break
        s = target
        if v > 0.0 and s >= S[i + 1] and i < n - 2:
            i += 1
        elif v < 0.0 and s <= S[i] and i > 0:
            i -= 1
        if (v > 0.0 and s >= send) or (v < 0.0 and s <= 0.0):
            v = 0.0
    return np.inf, dmin


@numba.njit(cache=True)
def _bounce_step(occ, px, py, vx, vy, rc, cs, dt):
    """One step of a bouncing disc (world units): the velocity components
    are reflected (x, then y, then both) until the disc's next position is
    free; a disc that already overlaps an obstacle moves freely; a disc that
    cannot move reverses."""
    inside = disc_free(occ, px / cs, py / cs, rc)
    for f in range(4):
        fx = -1.0 if (f & 1) else 1.0
        fy = -1.0 if (f & 2) else 1.0
        qx = px + vx * fx * dt
        qy = py + vy * fy * dt
        if disc_free(occ, qx / cs, qy / cs, rc) or not inside:
            return qx, qy, vx * fx, vy * fy
    return px, py, -vx, -vy


@numba.njit(cache=True)
def _predict_track(occ, px, py, vx, vy, rc, cs, dt, n, bounce):
    """Positions of a moving obstacle at times ``0, dt, ..., n dt``."""
    out = np.empty((n + 1, 2))
    out[0, 0] = px
    out[0, 1] = py
    for i in range(n):
        if bounce:
            px, py, vx, vy = _bounce_step(occ, px, py, vx, vy, rc, cs, dt)
        else:
            px += vx * dt
            py += vy * dt
        out[i + 1, 0] = px
        out[i + 1, 1] = py
    return out


@numba.njit(cache=True)
def _position_on_path(P, S, s):
    n = P.shape[0]
    if n == 1 or s <= 0.0:
        return P[0, 0], P[0, 1]
    if s >= S[n - 1]:
        return P[n - 1, 0], P[n - 1, 1]
    lo = 0
    hi = n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if S[mid] <= s:
            lo = mid
        else:
            hi = mid
    seg = S[hi] - S[lo]
    f = 0.0 if seg <= 0.0 else (s - S[lo]) / seg
    return P[lo, 0] + f * (P[hi, 0] - P[lo, 0]), P[lo, 1] + f * (P[hi, 1] - P[lo, 1])


@numba.njit(cache=True)
def _track_contact(P, S, s0, v, dt, track, radius):
    """First contact between the robot driving path ``P`` from ``s0`` at
    signed speed ``v`` and an obstacle at ``track[i]`` at time ``i dt``
    (both linear within each step). Returns ``(t_contact, min_distance)``."""
    send = S[P.shape[0] - 1]
    dmin = np.inf
    s = min(max(s0, 0.0), send)
    rx, ry = _position_on_path(P, S, s)
    for i in range(track.shape[0] - 1):
        s1 = min(max(s + v * dt, 0.0), send)
        qx, qy = _position_on_path(P, S, s1)
        d0x = track[i, 0] - rx
        d0y = track[i, 1] - ry
        dvx = (track[i + 1, 0] - track[i, 0] - (qx - rx)) / dt
        dvy = (track[i + 1, 1] - track[i, 1] - (qy - ry)) / dt
        tau = _first_contact(d0x, d0y, dvx, dvy, radius, dt)
        dm = _min_distance(d0x, d0y, dvx, dvy, min(tau, dt))
        if dm < dmin:
            dmin = dm
        if tau < np.inf:
            return i * dt + tau, dmin
        s = s1
        rx = qx
        ry = qy
    return np.inf, dmin


def path_contact(path, s0: float, speed: float, horizon: float, obstacle_position,
                 obstacle_velocity, radius: float) -> tuple[float, float]:
    """Predicted first contact between a robot following a path and a
    constant-velocity obstacle.

    The robot drives the polyline ``path`` (``(n, >=2)`` world points) from
    arc length ``s0`` at signed ``speed`` (negative: backwards along it),
    stopping at its ends; on each segment both move at constant velocity, so
    the contact time solves a quadratic exactly.

    Returns
    -------
    (t_contact, min_distance)
        ``t_contact`` is the first time in ``[0, horizon]`` at which the
        centres are within ``radius``, or ``inf``; ``min_distance`` is the
        smallest centre distance seen before it.

    Examples
    --------
    >>> path = [(0, 0), (10, 0)]
    >>> path_contact(path, 0.0, 1.0, 10.0, (10, 0), (-1, 0), 1.0)
    (4.5, 1.0)
    """
    P = np.ascontiguousarray(np.asarray(path, float)[:, :2])
    d = np.hypot(*np.diff(P, axis=0).T) if len(P) > 1 else np.zeros(0)
    S = np.concatenate([[0.0], np.cumsum(d)])
    t, dm = _path_contact(P, S, float(s0), float(speed), float(horizon),
                          float(obstacle_position[0]), float(obstacle_position[1]),
                          float(obstacle_velocity[0]), float(obstacle_velocity[1]), float(radius))
    return float(t), float(dm)


# ---------------------------------------------------------------------------
# the world
# ---------------------------------------------------------------------------

@dataclass
class StationaryObstacle:
    """Cells ``(row, col)`` that become obstacles at time ``appear_at`` (s)."""

    cells: np.ndarray
    appear_at: float = 0.0

    def __post_init__(self):
        self.cells = np.asarray(self.cells, dtype=np.int64).reshape(-1, 2)
        if len(self.cells) == 0:
            raise ConfigError("a stationary obstacle needs at least one cell")
        if not (math.isfinite(self.appear_at) and self.appear_at >= 0):
            raise ConfigError(f"appear_at must be >= 0, got {self.appear_at!r}")


MOVING_MODES = ("bounce", "pass")


@dataclass
class MovingObstacle:
    """A disc moving at constant velocity (world units).

    Parameters
    ----------
    position : (x, y)
    velocity : (vx, vy), units per second
    radius : float, default 0.4
    mode : {"bounce", "pass"}
        Reflect off the map edges and obstacles, or pass through everything
        and disappear once outside the map.
    appear_at : float, default 0
        Time it enters the world.
    """

    position: tuple
    velocity: tuple
    radius: float = 0.4
    mode: str = "bounce"
    appear_at: float = 0.0

    def __post_init__(self):
        self.position = np.asarray(self.position, dtype=float).reshape(2).copy()
        self.velocity = np.asarray(self.velocity, dtype=float).reshape(2).copy()
        if not (np.all(np.isfinite(self.position)) and np.all(np.isfinite(self.velocity))):
            raise ConfigError("moving obstacle position and velocity must be finite")
        if not (math.isfinite(self.radius) and self.radius > 0):
            raise ConfigError(f"moving obstacle radius must be > 0, got {self.radius!r}")
        if self.mode not in MOVING_MODES:
            raise ConfigError(f"mode must be one of {MOVING_MODES}, got {self.mode!r}")

    @classmethod
    def from_heading(cls, position, speed: float, heading: float, **kwargs) -> "MovingObstacle":
        """An obstacle moving at ``speed`` along ``heading`` (radians)."""
        return cls(position, (speed * math.cos(heading), speed * math.sin(heading)), **kwargs)

    @property
    def speed(self) -> float:
        return float(np.hypot(*self.velocity))

    @property
    def heading(self) -> float:
        return float(math.atan2(self.velocity[1], self.velocity[0]))


@dataclass(frozen=True)
class Robot:
    """The robot: a car with a sensor.

    Parameters
    ----------
    car : CarModel
        Wheelbase, steering, ``speed`` (m/s) and footprint ``radius``.
    sensor_range : float, default 6.0
        World units (>= 0).
    fov : float, default 180
        Half-angle of the field of view in degrees, ``0 < fov <= 180``
        (the paper's +-45, +-90 and +-180).
    line_of_sight : bool, default True
        Static walls hide what is behind them.

    Raises
    ------
    ConfigError
        On a negative sensor range or a field of view outside (0, 180].
    """

    car: CarModel = field(default_factory=CarModel)
    sensor_range: float = 6.0
    fov: float = 180.0
    line_of_sight: bool = True

    def __post_init__(self):
        if not isinstance(self.car, CarModel):
            raise ConfigError(f"car must be a CarModel, got {type(self.car).__name__}")
        try:
            rng = float(self.sensor_range)
            fov = float(self.fov)
        except (TypeError, ValueError):
            raise ConfigError("sensor_range and fov must be numbers") from None
        if not math.isfinite(rng) or rng < 0:
            raise ConfigError(f"sensor_range must be a finite number >= 0, got {self.sensor_range!r}")
        if not (0 < fov <= 180):
            raise ConfigError(f"fov (half-angle, degrees) must be in (0, 180], got {self.fov!r}")
        object.__setattr__(self, "sensor_range", rng)
        object.__setattr__(self, "fov", fov)

    @property
    def speed(self) -> float:
        return self.car.speed

    @property
    def radius(self) -> float:
        return self.car.radius


@dataclass(frozen=True)
class SimSettings:
    """Settings of :class:`Simulation` (seconds and world units).

    Attributes
    ----------
    dt : float, default 0.1
        Tick length.
    max_time : float or None
        Time limit; default ``3 * direct distance / speed + 60``.
    horizon : float, default 6.0
        Collision prediction horizon.
    safety_margin : float, default 0.15
        Added to the sum of the radii for predictions.
    replan_distance : float, default 2.0
        The paper's threshold: replan around a moving obstacle when it is at
        least this far (gap between the discs), otherwise halt.
    halt_time : float, default 1.5
        Halt (do not replan) when the predicted collision is nearer in time.
    sweep_time : float, default 4.0
        Prediction span of a moving obstacle's sweep blocked for replanning.
    replan_cooldown : float, default 1.0
        Least time between two replans for moving obstacles.
    rejoin_margin : float, default 3.0
        Local replans rejoin the path this far beyond the blocked part.
    detour_limit : float, default 4.0
        A replan around a *moving* obstacle is taken only if it is at most
        this much longer than the rest of the current path (otherwise the
        robot keeps its path and waits for the obstacle to pass).
    trail_length : float, default 5.0
        How far back along its driven trajectory the robot may back off.
    memory : float, default 1.0
        A moving obstacle out of view is still predicted for this long.
    goal_tolerance : float, default 0.5
    blocked_patience : float, default 15.0
        Give up (reason "blocked") after this long without any path.
    retry_interval : float, default 1.0
        While blocked, replan this often.
    appear_clearance : float, default 1.0
        A stationary obstacle appears only this far from the robot's disc, a
        moving one only three times as far (gap between the discs).
    predict_bounces : bool, default True
        Predict moving obstacles with their motion model (constant velocity
        reflected off the known map, solved piecewise, to within the chord
        of one tick); False: straight lines only (the paper's eqs. (7)-(10),
        :func:`path_contact`).
    record_world : bool, default True
        Record the moving obstacles' positions every tick (for animations).
    """

    dt: float = 0.1
    max_time: float | None = None
    horizon: float = 6.0
    safety_margin: float = 0.15
    replan_distance: float = 2.0
    halt_time: float = 1.5
    sweep_time: float = 4.0
    replan_cooldown: float = 1.0
    rejoin_margin: float = 3.0
    detour_limit: float = 4.0
    trail_length: float = 5.0
    memory: float = 1.0
    goal_tolerance: float = 0.5
    blocked_patience: float = 15.0
    retry_interval: float = 1.0
    appear_clearance: float = 1.0
    predict_bounces: bool = True
    record_world: bool = True

    def __post_init__(self):
        for name in ("dt", "horizon", "goal_tolerance", "retry_interval"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ConfigError(f"{name} must be > 0, got {v!r}")
        for name in ("safety_margin", "replan_distance", "halt_time", "sweep_time",
                     "replan_cooldown", "rejoin_margin", "detour_limit", "trail_length", "memory", "blocked_patience",
                     "appear_clearance"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise ConfigError(f"{name} must be >= 0, got {v!r}")
        if self.max_time is not None and not (self.max_time > 0):
            raise ConfigError(f"max_time must be > 0, got {self.max_time!r}")


# ---------------------------------------------------------------------------
# planners
# ---------------------------------------------------------------------------

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

    def plan(self, start, goal, *, blocked=None, cost=None,
             max_length=None) -> np.ndarray:  # pragma: no cover
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
        res = self.planner.plan(start, goal, blocked=blocked, cost=cost, max_length=max_length,
                                max_expansions=self.local_max_expansions if local else None)
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
        from gapath.planners.rrt import rrt

        ws = SimpleNamespace(occ=self.known, cell_size=self.cell_size)
        res = rrt(ws, start[:2], goal[:2], seed=self.rng, radius=self.robot.radius,
                  star=self.star, blocked=blocked, **self.settings)
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
        from gapath.planners.astar import astar
        from gapath.workspace import Workspace

        occ = self._grid(blocked)
        s, g = self._cells(start, goal)
        occ = occ.copy()
        occ[s] = False          # the robot's own cell (it is there)
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
        from gapath.planners.dstar_lite import DStarLite
        from gapath.workspace import Workspace

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


#: Planner classes by name (the CLI and the experiment use these names).
PLANNERS = {
    "hybrid-astar": HybridAStarPlanner,
    "rrt": lambda **kw: RRTPlanner(star=False, **kw),
    "rrt-star": lambda **kw: RRTPlanner(star=True, **kw),
    "astar": AStarPlanner,
    "dstar-lite": DStarLitePlanner,
}


def make_planner(name: str, **settings) -> Planner:
    """A planner by name: ``hybrid-astar``, ``rrt``, ``rrt-star``, ``astar``
    or ``dstar-lite``.

    Raises
    ------
    ConfigError
        On an unknown name.
    """
    if name not in PLANNERS:
        raise ConfigError(f"unknown planner {name!r}; choose one of {', '.join(PLANNERS)}")
    return PLANNERS[name](**settings)


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------

@dataclass(eq=False)
class SimResult:
    """What happened in one run.

    Attributes
    ----------
    success : bool
        The goal was reached without collision.
    reason : str
        ``"goal"``, ``"collision"``, ``"blocked"`` or ``"timeout"``.
    time : float
        Simulated seconds until the end.
    path_length : float
        Distance travelled (world units), backing off included.
    direct_distance : float
        Straight-line start-goal distance.
    global_plan_seconds : float
        Wall-clock time of the first (global) plan.
    replan_seconds : list of float
        Wall-clock time of every later planner call (local replanning).
    global_path : (n, 3) array
        The first plan (empty if there was none).
    trajectory : (T, 5) array
        ``t, x, y, theta, v`` every tick (the start at ``t = 0``).
    events : list of dict
        ``{"t", "kind", ...}``; kinds: ``detect``, ``predict``, ``replan``
        (with ``scope`` local or global and, around moving obstacles,
        ``adopted``: False when the new path was still predicted to
        collide), ``replan-failed``, ``halt``, ``back-off``, ``resume``,
        ``appear``, ``blocked``, ``collision``, ``goal``, ``timeout``.
    paths : list of (t, poses)
        Every accepted plan with the time it was adopted.
    obstacles : (T, M, 2) array or None
        Moving obstacles' positions every tick (NaN while absent).
    """

    success: bool
    reason: str
    time: float
    path_length: float
    direct_distance: float
    global_plan_seconds: float
    replan_seconds: list
    global_path: np.ndarray
    trajectory: np.ndarray
    events: list
    paths: list
    obstacles: np.ndarray | None = None
    planner: str = ""
    seed: int = 0

    @property
    def total_plan_seconds(self) -> float:
        """The paper's T_total = T_global + T_local-replanning."""
        return self.global_plan_seconds + float(sum(self.replan_seconds))

    @property
    def n_replans(self) -> int:
        return len(self.replan_seconds)

    def count(self, kind: str) -> int:
        return sum(1 for e in self.events if e["kind"] == kind)

    @property
    def global_length(self) -> float:
        g = self.global_path
        return float(np.hypot(*np.diff(g[:, :2], axis=0).T).sum()) if len(g) > 1 else 0.0

    def summary(self) -> dict:
        """The scalar figures of the run (JSON-friendly)."""
        return {
            "planner": self.planner, "seed": self.seed, "success": self.success,
            "reason": self.reason, "time_s": round(self.time, 3),
            "path_length": float(self.path_length), "global_length": self.global_length,
            "direct_distance": self.direct_distance,
            "global_plan_seconds": self.global_plan_seconds,
            "replan_seconds": float(sum(self.replan_seconds)),
            "total_plan_seconds": self.total_plan_seconds,
            "replans": self.n_replans, "halts": self.count("halt"),
            "back_offs": self.count("back-off"),
        }

    def to_json(self) -> dict:
        """Summary, trajectory, events and paths as plain JSON data."""
        def _num(v):
            if isinstance(v, (np.floating, float)):
                return float(v) if math.isfinite(v) else None
            if isinstance(v, np.integer):
                return int(v)
            return v
        return {
            **self.summary(),
            "global_path": np.round(self.global_path, 5).tolist(),
            "trajectory": np.round(self.trajectory, 5).tolist(),
            "events": [{k: _num(v) for k, v in e.items()} for e in self.events],
            "paths": [{"t": round(t, 3), "poses": np.round(p, 5).tolist()} for t, p in self.paths],
            "replan_seconds_each": [float(v) for v in self.replan_seconds],
        }


# ---------------------------------------------------------------------------
# the simulation
# ---------------------------------------------------------------------------

def start_pose(workspace) -> tuple[float, float, float]:
    """World pose at the workspace's start cell, heading along the first
    steps of the grid shortest path to the goal."""
    from gapath.planners._geometry import grid_dijkstra

    cs = workspace.cell_size
    (sr, sc), (gr, gc) = workspace.start, workspace.goal
    dist = grid_dijkstra(np.ascontiguousarray(workspace.occ, dtype=np.bool_), gr, gc)
    th = initial_heading(dist, (sr, sc))
    if th is None:
        th = math.atan2(gr - sr, gc - sc)
    return (sc * cs, sr * cs, th)


def _arc_lengths(path: np.ndarray) -> np.ndarray:
    d = np.hypot(*np.diff(path[:, :2], axis=0).T) if len(path) > 1 else np.zeros(0)
    return np.concatenate([[0.0], np.cumsum(d)])


def _disc_cells(x, y, radius, shape, cs):
    """Cells whose square meets the disc (world units)."""
    h, w = shape
    xc, yc, r = x / cs, y / cs, radius / cs
    c0, c1 = max(0, int(math.ceil(xc - r - 0.5))), min(w - 1, int(math.floor(xc + r + 0.5)))
    r0, r1 = max(0, int(math.ceil(yc - r - 0.5))), min(h - 1, int(math.floor(yc + r + 0.5)))
    out = []
    for i in range(r0, r1 + 1):
        dy = max(abs(yc - i) - 0.5, 0.0)
        for j in range(c0, c1 + 1):
            dx = max(abs(xc - j) - 0.5, 0.0)
            if dx * dx + dy * dy <= r * r:
                out.append((i, j))
    return out


class Simulation:
    """One seeded run of a robot and a planner among dynamic obstacles.

    Parameters
    ----------
    workspace : Workspace
        The known static map, the start and goal cells, ``cell_size``.
    planner : Planner or str
        A :class:`Planner` or a name for :func:`make_planner`.
    robot : Robot, optional
    stationary : list of StationaryObstacle
    moving : list of MovingObstacle
        (copied: the run does not change them)
    settings : SimSettings, optional
    start : (x, y, theta), optional
        Default :func:`start_pose`.
    seed : int
        Seeds the planner (RRT's samples); the world itself has no
        randomness once its obstacles are given.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> ws = Workspace(np.zeros((10, 20), bool), (5, 1), (5, 18))
    >>> mover = MovingObstacle((10.0, 0.5), (0.0, 0.0))
    >>> res = Simulation(ws, "hybrid-astar", moving=[mover]).run()
    >>> res.success, res.reason
    (True, 'goal')
    """

    def __init__(self, workspace, planner, robot: Robot | None = None, stationary=(),
                 moving=(), settings: SimSettings | None = None, start=None, seed: int = 0):
        self.workspace = workspace
        self.planner = make_planner(planner) if isinstance(planner, str) else planner
        if not isinstance(self.planner, Planner):
            raise ConfigError(f"planner must be a Planner or a name, got {planner!r}")
        self.robot = Robot() if robot is None else robot
        if not isinstance(self.robot, Robot):
            raise ConfigError(f"robot must be a Robot, got {type(robot).__name__}")
        self.settings = SimSettings() if settings is None else settings
        self.stationary = [StationaryObstacle(o.cells.copy(), o.appear_at) for o in stationary]
        self.moving = [MovingObstacle(o.position.copy(), o.velocity.copy(), o.radius, o.mode,
                                      o.appear_at) for o in moving]
        h, w = workspace.shape
        for o in self.stationary:
            if ((o.cells < 0) | (o.cells >= (h, w))).any():
                raise ConfigError(f"stationary obstacle cells {o.cells.tolist()} leave the {h}x{w} grid")
        self.seed = int(seed)
        self.cs = float(workspace.cell_size)
        self.start = start_pose(workspace) if start is None else tuple(float(v) for v in start)
        gr, gc = workspace.goal
        self.goal = (gc * self.cs, gr * self.cs)

    # -- helpers -----------------------------------------------------------------
    def _pose_at(self, s):
        P, S = self.path, self.S
        n = len(P)
        if n == 1:
            return float(P[0, 0]), float(P[0, 1]), float(P[0, 2])
        i = int(np.searchsorted(S, s, side="right")) - 1
        i = min(max(i, 0), n - 2)
        while i < n - 2 and S[i + 1] - S[i] <= 0:
            i += 1
        seg = S[i + 1] - S[i]
        f = 0.0 if seg <= 0 else min(max((s - S[i]) / seg, 0.0), 1.0)
        x = P[i, 0] + f * (P[i + 1, 0] - P[i, 0])
        y = P[i, 1] + f * (P[i + 1, 1] - P[i, 1])
        th = math.atan2(P[i + 1, 1] - P[i, 1], P[i + 1, 0] - P[i, 0]) if seg > 0 else P[i, 2]
        return float(x), float(y), float(th)

    def _set_path(self, path, t):
        """Follow ``path`` from its start (the robot's pose). The last
        ``trail_length`` of the driven trajectory is kept in front of it, so
        that the robot can back off along where it came from."""
        path = np.asarray(path, float)
        self.paths.append((t, path.copy()))
        trail = self._trail()
        if len(trail) > 1:
            path = np.vstack([trail[:-1], path])
        self.path = np.ascontiguousarray(path)
        self.S = _arc_lengths(self.path)
        self.s = float(self.S[len(trail) - 1]) if len(trail) > 1 else 0.0

    def _trail(self):
        """The last ``trail_length`` of the driven trajectory (poses, in
        driving order, ending at the robot's pose)."""
        traj = self._traj
        if len(traj) < 2:
            return np.zeros((0, 3))
        pts = [np.array(traj[-1][1:4])]
        total = 0.0
        for row in reversed(traj[:-1]):
            q = np.array(row[1:4])
            d = math.hypot(q[0] - pts[-1][0], q[1] - pts[-1][1])
            if d < 1e-9:
                continue
            total += d
            pts.append(q)
            if total >= self.settings.trail_length:
                break
        return np.array(pts[::-1])

    def _event(self, t, kind, **info):
        self.events.append({"t": round(t, 4), "kind": kind, **info})

    def _plan(self, start, goal, blocked=None, cost=None, max_length=None):
        t0 = time.perf_counter()
        try:
            path = self.planner.plan(start, goal, blocked=blocked, cost=cost, max_length=max_length)
        except GapathError as exc:
            return None, time.perf_counter() - t0, exc
        if max_length is not None and _arc_lengths(path)[-1] > max_length:
            return None, time.perf_counter() - t0, NoPathError("the path exceeds the detour limit")
        return path, time.perf_counter() - t0, None

    # -- sensing -----------------------------------------------------------------
    def _visible(self, x, y, px, py, radius=0.0):
        rb = self.robot
        dx, dy = px - x, py - y
        d = math.hypot(dx, dy)
        if d - radius > rb.sensor_range:
            return False
        if rb.fov < 180 and d > 1e-9:
            ang = abs((math.atan2(dy, dx) - self.pose[2] + math.pi) % (2 * math.pi) - math.pi)
            if ang > math.radians(rb.fov):
                return False
        if rb.line_of_sight and d > 1e-9:
            cs = self.cs
            if not segment_free(self.static_occ, x / cs, y / cs, px / cs, py / cs, 0.0, 0.25):
                return False
        return True

    def _sense(self, t):
        x, y = self.pose[0], self.pose[1]
        cs = self.cs
        new_cells = []
        for k, o in enumerate(self.stationary):
            if not self.appeared[k] or self.detected[k]:
                continue
            for (r, c) in o.cells:
                if self._visible(x, y, c * cs, r * cs, 0.5 * cs):
                    self.detected[k] = True
                    new_cells.extend(o.cells.tolist())
                    self._event(t, "detect", obstacle=f"stationary-{k}",
                                distance=round(math.hypot(c * cs - x, r * cs - y), 3))
                    break
        for k, o in enumerate(self.moving):
            if not self.active[k]:
                continue
            if self._visible(x, y, o.position[0], o.position[1], o.radius):
                if k not in self.tracks or t - self.tracks[k][0] > self.settings.dt * 1.5:
                    self._event(t, "detect", obstacle=f"moving-{k}",
                                distance=round(float(np.hypot(*(o.position - (x, y)))), 3))
                self.tracks[k] = (t, o.position.copy(), o.velocity.copy(), o.radius)
        for k in [k for k, tr in self.tracks.items() if t - tr[0] > self.settings.memory]:
            del self.tracks[k]
        return new_cells

    def _predicted(self, t):
        """Tracked obstacles now: list of ``(k, position, velocity, radius,
        track)``, the track being the predicted positions every ``dt`` over
        the horizon (bouncing off the known map with ``predict_bounces``)."""
        st = self.settings
        n = int(math.ceil(st.horizon / st.dt))
        out = []
        for k, (ts, p, v, r) in self.tracks.items():
            if st.predict_bounces and ts < t:
                # the obstacle was last seen at ts: catch up with its model
                m = int(round((t - ts) / st.dt))
                tr = _predict_track(self.known, p[0], p[1], v[0], v[1], r / self.cs, self.cs, st.dt,
                                    m, True)
                p = tr[-1]
            elif ts < t:
                p = p + v * (t - ts)
            track = _predict_track(self.known, p[0], p[1], v[0], v[1], r / self.cs, self.cs, st.dt, n,
                                   bool(st.predict_bounces))
            out.append((k, np.asarray(p, float), v, r, track))
        return out

    # -- prediction ----------------------------------------------------------------
    def _contact(self, v, obstacles, path=None, S=None, s=None):
        """Earliest predicted contact over the horizon when the robot drives
        at signed speed ``v``: ``(t_contact, k, gap)`` with ``gap`` the
        current distance between the discs of the robot and obstacle ``k``."""
        P = self.path if path is None else path
        S = self.S if S is None else S
        s = self.s if s is None else s
        st = self.settings
        best = (math.inf, -1, math.inf)
        rr = self.robot.radius + st.safety_margin
        x, y = self._position(P, S, s)
        for k, p, vel, r, track in obstacles:
            if st.predict_bounces:
                tc, _ = _track_contact(P, S, s, v, st.dt, track, rr + r)
            else:
                tc, _ = _path_contact(P, S, s, v, st.horizon, p[0], p[1], vel[0], vel[1], rr + r)
            gap = math.hypot(p[0] - x, p[1] - y) - r - self.robot.radius
            if tc < best[0] or (tc == best[0] and gap < best[2]):
                best = (tc, k, gap)
        return best

    @staticmethod
    def _position(P, S, s):
        return _position_on_path(P, S, float(s))

    def _sweep(self, obstacles):
        """Cells swept by the predicted obstacles over ``sweep_time``, grown
        by the robot's radius and the safety margin (the robot's own
        surroundings and the goal are left free)."""
        st = self.settings
        h, w = self.workspace.shape
        mask = np.zeros((h, w), bool)
        grow = self.robot.radius + st.safety_margin
        n = min(int(math.ceil(st.sweep_time / st.dt)), 10 ** 6)
        for _, p, v, r, track in obstacles:
            for q in track[: n + 1: 2]:
                for cell in _disc_cells(q[0], q[1], r + grow, (h, w), self.cs):
                    mask[cell] = True
        x, y = self.pose[0], self.pose[1]
        for cell in _disc_cells(x, y, self.robot.radius + 0.75 * self.cs, (h, w), self.cs):
            mask[cell] = False
        mask[self.workspace.goal] = False
        return mask

    def _cost_layer(self, sweep=None):
        """DSO + DMO: a Gaussian halo around the detected stationary cells
        and the swept cells of moving obstacles."""
        from gapath.workspace import potential_field

        layer = np.zeros(self.workspace.shape)
        dso = self.known & ~self.static_occ
        if dso.any():
            layer += potential_field(dso, s2=1.0, radius=3)
        if sweep is not None and sweep.any():
            layer += potential_field(sweep, s2=1.0, radius=3)
        return layer

    # -- replanning ---------------------------------------------------------------
    def replan(self, t, reason, s_block=None, blocked=None, cost=None, detour=None):
        """Replan the affected segment; returns the new path or None.

        Local first (non-incremental planners): from the robot's pose to
        rejoin poses 1, 2 and 3 ``rejoin_margin`` beyond ``s_block`` (those
        whose rest of the path is free), the shortest resulting path spliced
        into the current one; if none works, the whole way to the goal.
        With ``detour``, a new path may be at most that much longer than the
        rest of the current one.
        """
        st = self.settings
        tries = []
        if not self.planner.incremental and s_block is not None:
            s_j = s_block + st.rejoin_margin
            for _ in range(3):
                if s_j >= self.S[-1] - 1e-9:
                    break
                tries.append(s_j)
                s_j += st.rejoin_margin
        cur = self.pose
        spent = 0.0
        r_chk = self.robot.radius / self.cs + 0.05
        occ_all = self.known if blocked is None else (self.known | blocked)
        best = None
        for s_j in tries:
            j = min(int(np.searchsorted(self.S, s_j)), len(self.path) - 1)
            rejoin = self.path[j]
            rest = self.path[j:]
            if first_blocked(occ_all, np.ascontiguousarray(rest[:, :2] / self.cs), r_chk, 0.1) >= 0:
                continue
            goal = (rejoin[0], rejoin[1], rejoin[2]) if isinstance(self.planner, HybridAStarPlanner) \
                else (rejoin[0], rejoin[1])
            limit = None if detour is None else float(self.S[j] - self.s) + detour
            local, dt, err = self._plan(cur, goal, blocked, cost, limit)
            spent += dt
            if local is not None:
                total = float(_arc_lengths(local)[-1]) + float(self.S[-1] - self.S[j])
                if best is None or total < best[0]:
                    best = (total, np.vstack([local, rest[1:]]) if len(rest) > 1 else local,
                            float(self.S[j]))
        if best is not None:
            self.replan_seconds.append(spent)
            self._event(t, "replan", reason=reason, scope="local", seconds=round(spent, 6),
                        rejoin=round(best[2], 3))
            return best[1]
        limit = None if detour is None else float(self.S[-1] - self.s) + detour
        new, dt, err = self._plan(cur, self.goal, blocked, cost, limit)
        spent += dt
        self.replan_seconds.append(spent)
        if new is None:
            self._event(t, "replan-failed", reason=reason, error=str(err)[:200],
                        seconds=round(spent, 6))
            return None
        self._event(t, "replan", reason=reason, scope="global", seconds=round(spent, 6))
        return new

    # -- the world ---------------------------------------------------------------
    def _step_world(self, t):
        st = self.settings
        cs = self.cs
        x, y = self.pose[0], self.pose[1]
        changed = False
        for k, o in enumerate(self.stationary):
            if self.appeared[k] or t < o.appear_at:
                continue
            near = False
            for (r, c) in o.cells:
                dx = max(abs(x - c * cs) - 0.5 * cs, 0.0)
                dy = max(abs(y - r * cs) - 0.5 * cs, 0.0)
                if math.hypot(dx, dy) <= self.robot.radius + st.appear_clearance:
                    near = True
                    break
            if near:
                continue
            self.appeared[k] = True
            self.true_occ[o.cells[:, 0], o.cells[:, 1]] = True
            changed = True
            self._event(t, "appear", obstacle=f"stationary-{k}", cells=o.cells.tolist())
        h, w = self.workspace.shape
        dt = st.dt
        for k, o in enumerate(self.moving):
            if not self.active[k]:
                if not self.gone[k] and t >= o.appear_at:
                    gap = math.hypot(o.position[0] - x, o.position[1] - y) - o.radius - \
                        self.robot.radius
                    if gap > 3.0 * st.appear_clearance:
                        self.active[k] = True
                        if o.appear_at > 0:
                            self._event(t, "appear", obstacle=f"moving-{k}")
                continue
            p, v = o.position, o.velocity
            if o.mode == "pass":
                o.position = p + v * dt
                xc, yc = o.position / cs
                if (xc < -0.5 - o.radius / cs or xc > w - 0.5 + o.radius / cs
                        or yc < -0.5 - o.radius / cs or yc > h - 0.5 + o.radius / cs):
                    self.active[k] = False
                    self.gone[k] = True
                continue
            qx, qy, vx, vy = _bounce_step(self.true_occ, p[0], p[1], v[0], v[1], o.radius / cs,
                                          cs, dt)
            o.position = np.array([qx, qy])
            o.velocity = np.array([vx, vy])
        return changed

    def _collides(self, p0, p1):
        """Truth check of the robot's move p0 -> p1 over the tick."""
        cs = self.cs
        r = self.robot.radius
        if not disc_free(self.true_occ, p1[0] / cs, p1[1] / cs, r / cs):
            return "static"
        dt = self.settings.dt
        vr = (np.asarray(p1[:2]) - np.asarray(p0[:2])) / dt
        for k, o in enumerate(self.moving):
            if not self.active[k] and not self.gone[k]:
                continue
            prev = self._prev_pos[k]
            if prev is None:
                continue
            vo = (o.position - prev) / dt
            d0 = prev - np.asarray(p0[:2])
            dv = vo - vr
            if _min_distance(d0[0], d0[1], dv[0], dv[1], dt) < r + o.radius:
                return f"moving-{k}"
        return None

    # -- the run ----------------------------------------------------------------------
    def run(self) -> SimResult:
        """Simulate until the goal, a collision, a blocked robot or the time limit."""
        st = self.settings
        rb = self.robot
        ws = self.workspace
        cs = self.cs
        direct = math.hypot(self.goal[0] - self.start[0], self.goal[1] - self.start[1])
        max_time = st.max_time if st.max_time is not None else 3.0 * direct / rb.speed + 60.0
        self.static_occ = np.array(ws.occ, dtype=np.bool_, copy=True)
        self.true_occ = self.static_occ.copy()
        self.known = self.static_occ.copy()
        self.appeared = [False] * len(self.stationary)
        self.detected = [False] * len(self.stationary)
        self.active = [False] * len(self.moving)
        self.gone = [False] * len(self.moving)
        self.tracks = {}
        self.events = []
        self.paths = []
        self.replan_seconds = []
        self.planner.reset(ws, rb, self.seed)
        traj = []
        world = [] if st.record_world else None
        self.pose = self.start
        for k, o in enumerate(self.moving):
            self.active[k] = o.appear_at <= 0
        self._step_world(0.0)

        def finish(success, reason, t, length, gpath, gsec):
            return SimResult(success=success, reason=reason, time=t, path_length=length,
                             direct_distance=direct, global_plan_seconds=gsec,
                             replan_seconds=list(self.replan_seconds), global_path=gpath,
                             trajectory=np.array(traj).reshape(-1, 5), events=self.events,
                             paths=self.paths,
                             obstacles=None if world is None else np.array(world, float).reshape(
                                 len(world), len(self.moving), 2),
                             planner=self.planner.name, seed=self.seed)

        self._traj = traj

        def record(t, v):
            traj.append((t, self.pose[0], self.pose[1], self.pose[2], v))
            if world is not None:
                world.append([o.position.copy() if self.active[k] else (np.nan, np.nan)
                              for k, o in enumerate(self.moving)])

        # global planning on the known static map
        gpath, gsec, err = self._plan(self.start, self.goal)
        record(0.0, 0.0)
        if gpath is None:
            self._event(0.0, "blocked", error=str(err)[:200])
            return finish(False, "blocked", 0.0, 0.0, np.zeros((0, 3)), gsec)
        self._set_path(gpath, 0.0)
        gpath = self.path.copy()

        t = 0.0
        length = 0.0
        mode = "go"                 # go | halt | back
        blocked_since = None
        last_retry = -math.inf
        last_mover_replan = -math.inf
        predicted = set()
        self._prev_pos = [o.position.copy() for o in self.moving]
        r_chk = rb.radius / cs + 0.05
        n_ticks = int(math.ceil(max_time / st.dt))
        for tick in range(1, n_ticks + 1):
            t = tick * st.dt
            # 1. world
            self._prev_pos = [o.position.copy() if self.active[k] else None
                              for k, o in enumerate(self.moving)]
            self._step_world(t)
            # 2. sense
            new_cells = self._sense(t)
            if new_cells:
                cells = np.asarray(new_cells, dtype=np.int64)
                self.known[cells[:, 0], cells[:, 1]] = True
                self.planner.update_cells(cells, True)
            obstacles = self._predicted(t)
            # 3. known obstacles on the rest of the path
            i0 = max(0, int(np.searchsorted(self.S, self.s, side="right")) - 1)
            rest = np.ascontiguousarray(self.path[i0:, :2] / cs)
            rest = np.vstack([[self.pose[0] / cs, self.pose[1] / cs], rest[1:]]) if len(rest) > 1 else rest
            hit = first_blocked(self.known, np.ascontiguousarray(rest), r_chk, 0.1) \
                if (new_cells or blocked_since is not None) else -1
            if hit >= 0 and (blocked_since is None or t - last_retry >= st.retry_interval):
                s_block = self.S[min(i0 + max(hit, 1), len(self.S) - 1)]
                cost = self._cost_layer() if isinstance(self.planner, HybridAStarPlanner) else None
                new = self.replan(t, "stationary", s_block, None, cost)
                last_retry = t
                if new is not None:
                    self._set_path(new, t)
                    blocked_since = None
                    hit = -1
                elif blocked_since is None:
                    blocked_since = t
                    self._event(t, "blocked")
            if hit < 0 and blocked_since is not None:
                blocked_since = None
            if blocked_since is not None and t - blocked_since > st.blocked_patience:
                self._event(t, "blocked", patience=st.blocked_patience)
                return finish(False, "blocked", t, length, gpath, gsec)
            # 4. moving obstacles: prediction, replanning, halting
            v_cmd = rb.speed
            stop = math.inf
            if blocked_since is not None:
                # do not drive into the known obstacle: stop short of it
                stop = self.S[min(i0 + max(hit, 1), len(self.S) - 1)] - rb.radius - 0.5 * cs
                v_cmd = 0.0 if self.s >= stop - rb.speed * st.dt else rb.speed
            if obstacles:
                tc, k, gap = self._contact(rb.speed, obstacles)
                if tc < math.inf:
                    if k not in predicted:
                        predicted.add(k)
                        self._event(t, "predict", obstacle=f"moving-{k}", t_collision=round(tc, 3),
                                    gap=round(gap, 3))
                    if (gap >= st.replan_distance and tc >= st.halt_time
                            and t - last_mover_replan >= st.replan_cooldown):
                        last_mover_replan = t
                        sweep = self._sweep(obstacles)
                        cost = self._cost_layer(sweep) if isinstance(
                            self.planner, HybridAStarPlanner) else None
                        s_c = min(self.s + rb.speed * tc, self.S[-1])
                        new = self.replan(t, f"moving-{k}", s_c, sweep, cost, st.detour_limit)
                        if new is not None:
                            S_new = _arc_lengths(new)
                            tc2, _, _ = self._contact(rb.speed, obstacles, new, S_new, 0.0)
                            adopted = tc2 == math.inf or tc2 > tc + 1.0
                            self.events[-1]["adopted"] = adopted
                            if adopted:
                                self._set_path(new, t)
                                tc = tc2
                    # halt near the threat; once halted, resume only with some hysteresis
                    waiting = mode != "go" and blocked_since is None
                    near = (gap < st.replan_distance + (0.5 if waiting else 0.0)
                            or tc < st.halt_time + (1.0 if waiting else 0.0))
                    if tc < math.inf and near:
                        # halt and wait, or back off if waiting would be hit too
                        # (or, if every option is hit, the one hit latest)
                        t_halt, _, _ = self._contact(0.0, obstacles)
                        if t_halt == math.inf:
                            v_cmd = 0.0
                        else:
                            t_back = self._contact(-rb.speed, obstacles)[0] if self.s > 0 else 0.0
                            options = [(t_back, -rb.speed), (t_halt, 0.0), (tc, rb.speed)]
                            v_cmd = max(options, key=lambda o: o[0])[1]
                else:
                    predicted.clear()
            new_mode = "go" if v_cmd > 0 else ("halt" if v_cmd == 0 else "back")
            if new_mode != mode:
                kind = {"go": "resume", "halt": "halt", "back": "back-off"}[new_mode]
                if not (new_mode == "halt" and blocked_since is not None and mode == "halt"):
                    self._event(t, kind)
                mode = new_mode
            # 5. move
            p0 = self.pose
            s_new = min(max(self.s + v_cmd * st.dt, 0.0), self.S[-1])
            if s_new > self.s and s_new > stop:
                s_new = max(self.s, stop)
            length += abs(s_new - self.s)
            self.s = s_new
            self.pose = self._pose_at(self.s)
            record(t, v_cmd)
            # 6. truth
            what = self._collides(p0, self.pose)
            if what is not None:
                self._event(t, "collision", obstacle=what)
                return finish(False, "collision", t, length, gpath, gsec)
            if (self.s >= self.S[-1] - 1e-9 and
                    math.hypot(self.pose[0] - self.goal[0], self.pose[1] - self.goal[1])
                    <= st.goal_tolerance):
                self._event(t, "goal")
                return finish(True, "goal", t, length, gpath, gsec)
            if self.s >= self.S[-1] - 1e-9 and blocked_since is None:
                # at the end of a path that stops short of the goal (tolerance): plan on
                new, _, _ = self._plan(self.pose, self.goal)
                if new is not None and len(new) > 1:
                    self._set_path(new, t)
        self._event(t, "timeout", max_time=max_time)
        return finish(False, "timeout", t, length, gpath, gsec)


def simulate(workspace, planner="hybrid-astar", robot=None, stationary=(), moving=(),
             settings=None, start=None, seed: int = 0) -> SimResult:
    """Run one :class:`Simulation` (same parameters) and return its result."""
    return Simulation(workspace, planner, robot, stationary, moving, settings, start, seed).run()
