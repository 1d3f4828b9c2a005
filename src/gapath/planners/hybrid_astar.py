"""Hybrid A* for a car-like robot on an occupancy grid (NO-MOPP's planner).

This is the global planner of K. Neeraja and G. Narsimha's NO-MOPP (their
MOHC-OPF level), the hybrid A* of D. Dolgov et al. (2008) with five forward
steering actions, as in PythonRobotics' ``hybrid_a_star``:

1. A state is a continuous pose ``(x, y, theta)``; it is *rounded* to a
   discrete state (the cell holding ``(x, y)`` and a heading bin) only to
   decide which states are the same (the closed set).
2. A state is expanded by the five steering actions of a simple car --
   maximum left, left (half the maximum), straight, right, maximum right --
   each driving an arc of length ``arc_length > sqrt(2) * cell_size`` (eq. (4)
   of the paper: long enough to leave the current cell) with curvature
   ``kappa = tan(steer) / wheelbase`` (eq. (6); the minimum turning radius is
   ``wheelbase / tan(max_steer)``).
3. Every arc is checked against the grid (a disc footprint, see
   :mod:`gapath.planners._geometry`); its cost is

       ``g' = g + arc_length + SO + DSO + DMO``

   with SO = ``steer_cost * |steer| + steer_change_cost * |steer - steer_parent|``
   (radians; the cost of switching orientation) and DSO + DMO =
   ``cost_weight * integral of the cost layer along the arc`` (the caller's
   layer holds the costs near dynamic stationary and moving obstacles, see
   :mod:`gapath.dynamic`). The open list is ordered by ``f = g' + h``
   (eq. (1) of the paper, ``f = g + h + SO + DSO + DMO``).
4. ``h`` is the Euclidean distance to the goal (eq. (5)); with
   ``heuristic="dijkstra"`` (the default) it is the larger of the Euclidean
   distance and the 8-connected grid distance around the known obstacles,
   computed once per goal by Dijkstra. The grid distance is what makes the
   search fast in mazes; it can exceed the true distance by up to ~8 %, so
   the search is not strictly optimal (hybrid A* never is: it prunes by
   rounded states). Cells from which the goal cell cannot be reached are
   never entered, and an unreachable goal cell is reported at once.
5. The goal is reached when a state comes within ``goal_tolerance`` (and,
   for a goal pose, ``heading_tolerance``) or when an *analytic shot*
   succeeds: from every state nearer than ``shot_distance`` the planner tries
   the shortest Dubins path to the goal pose, or with a free goal heading a
   minimum-radius turn followed by a straight line to the goal point, and
   stops if it is collision-free and not much longer than the distance left
   (``shot_slack``). The returned path then ends exactly at the goal.

The paths are drivable: every pose follows from the previous one by an arc
of curvature at most ``1 / min_turning_radius``, headings are continuous,
and the disc of radius ``car.radius`` swept along the whole path is
collision-free.

World frame
    A pose ``(x, y, theta)`` is in world units: ``x = col * cell_size`` and
    ``y = row * cell_size``, so the centre of cell ``(row, col)`` is
    ``(col, row) * cell_size`` (SPEC: cell centres at ``(row, col)``) and the
    cell covers ``x in [col - 1/2, col + 1/2] * cell_size`` (likewise for
    ``y``). ``theta`` is measured from ``+x`` (east, increasing column)
    towards ``+y`` (south, increasing row); "left" steering (positive
    curvature) makes ``theta`` grow, which looks clockwise on a picture with
    row 0 on top. Use :func:`cell_pose` and :func:`pose_cell` to convert.

The search runs in one numba kernel; its arrays are kept between calls and
stamped with a generation number, so repeated (local) plans do not pay for
allocating and clearing them.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numba
import numpy as np

from gapath.errors import ConfigError, NoPathError, positive_int
from gapath.planners._geometry import (
    TWO_PI,
    angle_diff,
    arc_point,
    arcs_free,
    disc_free,
    dubins,
    grid_dijkstra,
    mod2pi,
    path_clearance,
    sample_arcs,
    turn_to_point,
)
from gapath.planners._grid import heap_pop, heap_push, heap_update
from gapath.planners.astar import check_cost_layer
from gapath.workspace import read_only

__all__ = [
    "CarModel",
    "HybridAStar",
    "HybridPath",
    "cell_pose",
    "hybrid_astar",
    "initial_heading",
    "pose_cell",
    "path_objectives",
]

#: Clearance objectives are capped at this many cells (the search for the
#: nearest obstacle stops there).
CLEARANCE_CAP = 5.0


# ---------------------------------------------------------------------------
# the robot
# ---------------------------------------------------------------------------


def check_positive(value, name: str, *, allow_zero: bool = False) -> float:
    """``value`` as a finite float, > 0 (``>= 0`` with ``allow_zero``).

    Raises
    ------
    ConfigError
        Naming ``name``, if ``value`` is not such a number.
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ConfigError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise ConfigError(f"{name} must be a finite number {bound}, got {value!r}")
    return v


def describe_pose(pose, cell_size: float) -> str:
    """A pose or point in the CLI's words: its cell ``ROW,COL``, the world
    point when it is not the cell's centre, the heading in whole degrees.

    Examples
    --------
    >>> describe_pose((3.0, 2.0, math.pi / 2), 1.0)
    'cell ROW,COL 2,3 heading 90 deg'
    >>> describe_pose((3.25, 2.0), 0.5)
    'cell ROW,COL 4,7 (x=3.25, y=2 world units)'
    """
    x, y = float(pose[0]), float(pose[1])
    cs = float(cell_size)
    r, c = math.floor(y / cs + 0.5), math.floor(x / cs + 0.5)
    text = f"cell ROW,COL {r},{c}"
    if abs(x - c * cs) > 1e-9 or abs(y - r * cs) > 1e-9:
        text += f" (x={x:.4g}, y={y:.4g} world units)"
    if len(pose) > 2:
        text += f" heading {math.degrees(float(pose[2])) % 360:.0f} deg"
    return text


@dataclass(frozen=True)
class CarModel:
    """A simple car: LaValle, *Planning Algorithms* (2006), eq. (6) of NO-MOPP.

    ``x' = u cos(theta)``, ``y' = u sin(theta)``,
    ``theta' = u tan(steer) / wheelbase``; the minimum turning radius is
    ``wheelbase / tan(max_steer)``. The robot is a disc of ``radius`` for
    collision checks.

    Parameters
    ----------
    wheelbase : float, default 0.6
        Distance between the axles (world units, e.g. metres).
    max_steer : float, default 0.6 rad (34.4 degrees)
        Largest steering angle, in radians, ``0 < max_steer < pi / 2``.
    speed : float, default 1.0
        Cruise speed (world units per second), used by the simulation.
    radius : float, default 0.3
        Footprint radius (0 for a point robot).

    Raises
    ------
    ConfigError
        On a non-positive wheelbase or speed, a steering angle outside
        ``(0, 90)`` degrees, or a negative radius.

    Examples
    --------
    >>> round(CarModel(wheelbase=1.0, max_steer=math.pi / 4).min_turning_radius, 6)
    1.0
    """

    wheelbase: float = 0.6
    max_steer: float = 0.6
    speed: float = 1.0
    radius: float = 0.3

    def __post_init__(self):
        object.__setattr__(self, "wheelbase", check_positive(self.wheelbase, "wheelbase"))
        object.__setattr__(self, "speed", check_positive(self.speed, "speed"))
        object.__setattr__(self, "radius", check_positive(self.radius, "radius", allow_zero=True))
        try:
            steer = float(self.max_steer)
        except (TypeError, ValueError):
            raise ConfigError(f"max_steer must be a number of radians, got {self.max_steer!r}") from None
        if not math.isfinite(steer) or not 0 < steer < math.pi / 2:
            raise ConfigError(
                f"max_steer must be in (0, pi/2) radians (0 to 90 degrees, exclusive), "
                f"got {steer:.4g} rad"
                + (f" ({math.degrees(steer):.1f} degrees)" if math.isfinite(steer) else "")
            )
        object.__setattr__(self, "max_steer", steer)

    @property
    def min_turning_radius(self) -> float:
        """``wheelbase / tan(max_steer)``."""
        return self.wheelbase / math.tan(self.max_steer)

    @property
    def max_curvature(self) -> float:
        """``1 / min_turning_radius``."""
        return math.tan(self.max_steer) / self.wheelbase

    def steering_angles(self) -> np.ndarray:
        """The five actions: maximum left, left, straight, right, maximum right."""
        m = self.max_steer
        return np.array([m, m / 2, 0.0, -m / 2, -m])


# ---------------------------------------------------------------------------
# frames and results
# ---------------------------------------------------------------------------


def cell_pose(cell, heading: float = 0.0, cell_size: float = 1.0) -> tuple[float, float, float]:
    """World pose ``(x, y, theta)`` at the centre of cell ``(row, col)``."""
    r, c = cell
    return (float(c) * cell_size, float(r) * cell_size, float(heading))


def pose_cell(pose, cell_size: float = 1.0) -> tuple[int, int]:
    """The cell ``(row, col)`` holding the point of a world pose."""
    return (int(math.floor(pose[1] / cell_size + 0.5)), int(math.floor(pose[0] / cell_size + 0.5)))


def path_objectives(poses: np.ndarray, occ: np.ndarray, cell_size: float = 1.0) -> dict:
    """Objectives of a path of world poses.

    Returns
    -------
    dict
        ``length`` (sum of the distances between consecutive poses, world
        units), ``turning`` (sum of the absolute heading changes, radians;
        headings of point paths are taken from the segments when missing)
        and ``clearance`` (smallest distance from a pose to an obstacle cell
        or the map edge, world units, capped at ``CLEARANCE_CAP`` cells).
    """
    p = np.asarray(poses, dtype=float)
    if len(p) < 2:
        length = 0.0
        turning = 0.0
    else:
        d = np.diff(p[:, :2], axis=0)
        length = float(np.hypot(d[:, 0], d[:, 1]).sum())
        if p.shape[1] >= 3:
            th = p[:, 2]
        else:
            th = np.arctan2(d[:, 1], d[:, 0])
        dth = np.diff(th)
        turning = float(np.abs((dth + np.pi) % (2 * np.pi) - np.pi).sum())
    pts = np.ascontiguousarray(p[:, :2] / cell_size) if len(p) else np.zeros((0, 2))
    clearance = path_clearance(read_only(occ, np.bool_), pts, CLEARANCE_CAP) if len(pts) else 0.0
    return {"length": length, "turning": turning, "clearance": float(clearance) * cell_size}


@dataclass(frozen=True, eq=False)
class HybridPath:
    """A drivable path found by :class:`HybridAStar`.

    Attributes
    ----------
    poses : (n, 3) float array
        World poses ``(x, y, theta)`` from the start, at most ``ds`` apart
        (read-only). Headings are continuous (not wrapped).
    length, turning, clearance : float
        The objectives (see :func:`path_objectives`).
    cost : float
        The search cost ``g`` of the last state (length plus SO, DSO, DMO)
        plus the length of the analytic shot, world units.
    expansions : int
        States expanded.
    seconds : float
        Wall-clock time of the call.
    reached : str
        ``"shot"`` (analytic expansion: ends exactly at the goal),
        ``"tolerance"`` (a state within the goal tolerance) or ``"start"``
        (the start already satisfied the goal).
    steering : (k,) float array
        Steering angle of each expanded arc, radians (the shot excluded).
    """

    poses: np.ndarray
    length: float
    turning: float
    clearance: float
    cost: float
    expansions: int
    seconds: float
    reached: str
    steering: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def objectives(self) -> dict:
        return {"length": self.length, "turning": self.turning, "clearance": self.clearance}

    def cells(self, cell_size: float = 1.0) -> np.ndarray:
        """The cells ``(row, col)`` the poses pass through, consecutive
        repeats removed."""
        rc = np.floor(self.poses[:, [1, 0]] / cell_size + 0.5).astype(np.int64)
        keep = np.ones(len(rc), bool)
        keep[1:] = np.any(rc[1:] != rc[:-1], axis=1)
        return rc[keep]

    def __repr__(self) -> str:
        return (
            f"HybridPath(poses={len(self.poses)}, length={self.length:.4f}, "
            f"turning={self.turning:.4f}, clearance={self.clearance:.4f}, "
            f"expansions={self.expansions}, seconds={self.seconds:.6f}, reached={self.reached!r})"
        )


# ---------------------------------------------------------------------------
# the search kernel (cell units)
# ---------------------------------------------------------------------------

_CLOSED = -2
#: status codes of the kernel
_FOUND_TOL, _FOUND_SHOT, _EXHAUSTED, _LIMIT = 0, 1, 2, 3


@numba.njit(cache=True)
def _state(x, y, th, w, nh):
    """Index of the discrete state of a pose (its cell and heading bin)."""
    c = int(math.floor(x + 0.5))
    r = int(math.floor(y + 0.5))
    b = int(math.floor(mod2pi(th) * nh / TWO_PI + 0.5)) % nh
    return (r * w + c) * nh + b


@numba.njit(cache=True)
def _search(
    occ,
    layer,
    use_layer,
    hgrid,
    use_grid_h,
    sx,
    sy,
    sth,
    gx,
    gy,
    gth,
    has_gth,
    pos_tol,
    th_tol,
    kappas,
    steers,
    arc_len,
    ds,
    r_check,
    nh,
    steer_cost,
    steer_change_cost,
    layer_weight,
    h_weight,
    shot_dist,
    shot_radius,
    shot_slack,
    max_exp,
    max_len,
    stamp,
    gen,
    pos,
    gval,
    px,
    py,
    pth,
    parent,
    psteer,
    hnode,
    hk1,
    hk2,
):
    """Hybrid A* from pose ``s`` to goal ``g`` (cell units).

    Returns ``(status, goal_state, shot_kappas, shot_lengths, expansions)``.
    The per-state arrays (``pos`` ... ``psteer``) are valid for a state only
    when ``stamp[state] == gen``.
    """
    h, w = occ.shape
    n_act = kappas.shape[0]
    straight = n_act // 2
    shot_k = np.zeros(3)
    shot_l = np.zeros(3)

    s = _state(sx, sy, sth, w, nh)
    stamp[s] = gen
    gval[s] = 0.0
    px[s] = sx
    py[s] = sy
    pth[s] = sth
    parent[s] = -1
    psteer[s] = straight
    h0 = math.hypot(gx - sx, gy - sy)
    size = heap_push(hnode, hk1, hk2, pos, 0, s, h_weight * h0, h0)
    expansions = 0

    while size > 0:
        u, size = heap_pop(hnode, hk1, hk2, pos, size)
        pos[u] = _CLOSED
        expansions += 1
        x = px[u]
        y = py[u]
        th = pth[u]

        # goal test: within the tolerance
        dgoal = math.hypot(gx - x, gy - y)
        if dgoal <= pos_tol and (not has_gth or angle_diff(th, gth) <= th_tol):
            return _FOUND_TOL, u, shot_k, shot_l, expansions
        # analytic expansion (Dubins shot / turn-then-straight to the point),
        # not taken when it is much longer than the distance left (loops)
        if dgoal <= shot_dist:
            left = hgrid[int(math.floor(y + 0.5)), int(math.floor(x + 0.5))]
            if left < dgoal:
                left = dgoal
            max_shot = shot_slack * left + arc_len
            if has_gth:
                length, kk, ll = dubins(x, y, th, gx, gy, gth, shot_radius)
                if length <= max_shot and arcs_free(occ, x, y, th, kk, ll, r_check, ds):
                    shot_k[:] = kk
                    shot_l[:] = ll
                    return _FOUND_SHOT, u, shot_k, shot_l, expansions
            else:
                length, kk, ll = turn_to_point(x, y, th, gx, gy, shot_radius)
                if length <= max_shot and arcs_free(occ, x, y, th, kk, ll, r_check, ds):
                    shot_k[0] = kk[0]
                    shot_k[1] = kk[1]
                    shot_l[0] = ll[0]
                    shot_l[1] = ll[1]
                    return _FOUND_SHOT, u, shot_k, shot_l, expansions
        if expansions >= max_exp:
            return _LIMIT, -1, shot_k, shot_l, expansions

        # the five steering actions
        gu = gval[u]
        su = psteer[u]
        for k in range(n_act):
            # drive the arc, checking samples at most ds apart
            steps = max(1, int(math.ceil(arc_len / ds)))
            ok = True
            lc = 0.0
            for i in range(1, steps + 1):
                qx, qy, _ = arc_point(x, y, th, kappas[k], arc_len * i / steps)
                if not disc_free(occ, qx, qy, r_check):
                    ok = False
                    break
                if use_layer:
                    lc += layer[int(math.floor(qy + 0.5)), int(math.floor(qx + 0.5))]
            if not ok:
                continue
            nx, ny, nth = arc_point(x, y, th, kappas[k], arc_len)
            nr = int(math.floor(ny + 0.5))
            nc = int(math.floor(nx + 0.5))
            hg = hgrid[nr, nc]
            if hg == np.inf:  # the goal cell is not reachable from here
                continue
            v = _state(nx, ny, nth, w, nh)
            seen = stamp[v] == gen
            if seen and pos[v] == _CLOSED:
                continue
            # g + length + SO + (DSO + DMO)
            ng = (
                gu
                + arc_len
                + steer_cost * abs(steers[k])
                + steer_change_cost * abs(steers[k] - steers[su])
                + layer_weight * lc * (arc_len / steps)
            )
            if seen and ng >= gval[v]:
                continue
            he = math.hypot(gx - nx, gy - ny)
            if ng + he > max_len:  # cannot end within max_length
                continue
            if use_grid_h and hg > he:
                he = hg
            f = ng + h_weight * he
            if not seen:
                stamp[v] = gen
                gval[v] = ng
                px[v] = nx
                py[v] = ny
                pth[v] = nth
                parent[v] = u
                psteer[v] = k
                size = heap_push(hnode, hk1, hk2, pos, size, v, f, he)
            else:
                gval[v] = ng
                px[v] = nx
                py[v] = ny
                pth[v] = nth
                parent[v] = u
                psteer[v] = k
                heap_update(hnode, hk1, hk2, pos, size, v, f, he)
    return _EXHAUSTED, -1, shot_k, shot_l, expansions


@numba.njit(cache=True)
def _extract(goal_state, parent, psteer, px, py, pth, kappas, arc_len, ds, shot_k, shot_l):
    """Poses from the start state to ``goal_state`` then along the shot, and
    the action index of every arc."""
    m = 0
    v = goal_state
    while v != -1:
        m += 1
        v = parent[v]
    chain = np.empty(m, dtype=np.int64)
    v = goal_state
    for i in range(m - 1, -1, -1):
        chain[i] = v
        v = parent[v]
    steps = max(1, int(math.ceil(arc_len / ds)))
    n_shot = 0
    for k in range(shot_l.shape[0]):
        if shot_l[k] > 0.0:
            n_shot += max(1, int(math.ceil(shot_l[k] / ds)))
    out = np.empty((1 + (m - 1) * steps + n_shot, 3))
    actions = np.empty(m - 1, dtype=np.int64)
    s0 = chain[0]
    out[0, 0] = px[s0]
    out[0, 1] = py[s0]
    out[0, 2] = pth[s0]
    j = 1
    for i in range(1, m):
        a = chain[i - 1]
        b = chain[i]
        k = psteer[b]
        actions[i - 1] = k
        for q in range(1, steps + 1):
            qx, qy, qt = arc_point(px[a], py[a], pth[a], kappas[k], arc_len * q / steps)
            out[j, 0] = qx
            out[j, 1] = qy
            out[j, 2] = qt
            j += 1
    if n_shot:
        last = chain[m - 1]
        pts = sample_arcs(px[last], py[last], pth[last], shot_k, shot_l, ds)
        for q in range(1, pts.shape[0]):
            out[j, 0] = pts[q, 0]
            out[j, 1] = pts[q, 1]
            out[j, 2] = pts[q, 2]
            j += 1
    return out[:j], actions


# ---------------------------------------------------------------------------
# the planner
# ---------------------------------------------------------------------------


def initial_heading(dist: np.ndarray, cell, steps: int = 3) -> float | None:
    """Heading from ``cell`` towards the cell ``steps`` moves down the grid
    distance ``dist`` (the first steps of a shortest grid path); None if
    the cell is not connected to the goal or is the goal."""
    h, w = dist.shape
    r, c = cell
    if not np.isfinite(dist[r, c]) or dist[r, c] == 0:
        return None
    cr, cc = r, c
    for _ in range(steps):
        best = (dist[cr, cc], cr, cc)
        for dr in (-1, 0, 1):
            for dc in (-1, 0, 1):
                rr, c2 = cr + dr, cc + dc
                if 0 <= rr < h and 0 <= c2 < w:
                    step = math.hypot(dr, dc)
                    if dist[rr, c2] + step <= dist[cr, cc] + 1e-9 and dist[rr, c2] < best[0]:
                        best = (dist[rr, c2], rr, c2)
        if best[1:] == (cr, cc):
            break
        cr, cc = best[1], best[2]
    if (cr, cc) == (r, c):
        return None
    return math.atan2(cr - r, cc - c)


HEURISTIC_KINDS = ("dijkstra", "euclidean")


def _as_pose(value, name: str, n: tuple[int, ...] = (3,)) -> tuple[float, ...]:
    try:
        vals = tuple(float(v) for v in value)
    except (TypeError, ValueError):
        raise ConfigError(f"{name} must be a pose (x, y, theta), got {value!r}") from None
    if len(vals) not in n or not all(math.isfinite(v) for v in vals):
        want = " or ".join({2: "(x, y)", 3: "(x, y, theta)"}[k] for k in n)
        raise ConfigError(f"{name} must be {want} of finite numbers (world units), got {value!r}")
    return vals


class HybridAStar:
    """Hybrid A* planner for a car on a known occupancy grid.

    The planner keeps its own copy of the map (:meth:`update_cells` adds or
    removes obstacles as sensors find them), the goal distance grids it has
    computed and its search arrays, so that repeated plans (local replanning
    in :mod:`gapath.dynamic`) are cheap.

    Parameters
    ----------
    workspace : Workspace
        The grid (``occ``) and ``cell_size``; its start and goal are the
        defaults of :meth:`plan`.
    car : CarModel, optional
        Wheelbase, maximum steering, footprint radius (default ``CarModel()``).
    heading_bins : int, default 72
        Heading bins of the discrete states (5 degrees).
    arc_length : float, optional
        Length of one expansion, world units; must exceed
        ``sqrt(2) * cell_size`` (default ``1.5 * cell_size``).
    ds : float, optional
        Spacing of the collision samples and of the returned poses (default
        ``0.2 * cell_size``). Samples are checked with the radius
        ``car.radius + ds / 2``, which makes the swept disc collision-free.
    steer_cost, steer_change_cost : float, default 0.1 and 0.5
        SO: cost per radian of steering and of steering change, per arc
        (world units).
    cost_weight : float, default 1.0
        Weight of the cost layer (DSO + DMO) passed to :meth:`plan`.
    heuristic : {"dijkstra", "euclidean"}, default "dijkstra"
        Euclidean distance (the paper's eq. (5)), or its maximum with the
        8-connected grid distance around the known obstacles.
    heuristic_weight : float, default 1.1
        Multiplies ``h`` (weighted A*: with 1.1 the maze and warehouse
        scenarios need ~10x fewer expansions than with 1.0 for paths within
        ~1 % of the same length).
    goal_tolerance : float, optional
        Distance to the goal point that counts as reached (default
        ``0.5 * cell_size``).
    heading_tolerance : float, default 0.26 rad (15 degrees)
        With a goal heading: the heading difference that counts as reached.
    shot_distance : float, optional
        Analytic shots are tried from states nearer than this to the goal
        (default ``12 * cell_size``).
    shot_slack : float, default 1.5
        A shot is taken only if its length is at most ``shot_slack`` times
        the distance left (the larger of the Euclidean and the grid
        distance) plus one ``arc_length``: this keeps Dubins loops out of
        the paths.
    max_expansions : int, default 1_000_000
        Give up (NoPathError) after this many expansions.

    Raises
    ------
    ConfigError
        On invalid settings (see :class:`CarModel` for the robot's).

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> occ = np.zeros((12, 20), bool); occ[3:12, 9] = True
    >>> planner = HybridAStar(Workspace(occ, (10, 2), (10, 17)))
    >>> res = planner.plan()
    >>> res.reached, res.length > 15
    ('shot', True)
    """

    def __init__(
        self,
        workspace,
        car: CarModel | None = None,
        *,
        heading_bins: int = 72,
        arc_length: float | None = None,
        ds: float | None = None,
        steer_cost: float = 0.1,
        steer_change_cost: float = 0.5,
        cost_weight: float = 1.0,
        heuristic: str = "dijkstra",
        heuristic_weight: float = 1.1,
        goal_tolerance: float | None = None,
        heading_tolerance: float = math.radians(15),
        shot_distance: float | None = None,
        shot_slack: float = 1.5,
        max_expansions: int = 1_000_000,
    ):
        self.car = CarModel() if car is None else car
        if not isinstance(self.car, CarModel):
            raise ConfigError(f"car must be a CarModel, got {type(car).__name__}")
        cs = float(workspace.cell_size)
        self.cell_size = cs
        self.workspace = workspace
        self._occ = np.array(workspace.occ, dtype=np.bool_, order="C", copy=True)
        try:
            nh = int(heading_bins)
        except (TypeError, ValueError):
            raise ConfigError(f"heading_bins must be an integer >= 4, got {heading_bins!r}") from None
        if nh != heading_bins or nh < 4:
            raise ConfigError(f"heading_bins must be an integer >= 4, got {heading_bins!r}")
        self.heading_bins = nh
        self.arc_length = 1.5 * cs if arc_length is None else check_positive(arc_length, "arc_length")
        if self.arc_length <= math.sqrt(2) * cs:
            raise ConfigError(
                f"arc_length must exceed sqrt(2) * cell_size = {math.sqrt(2) * cs:.4f} (an "
                f"expansion must leave its cell, eq. (4)), got {arc_length!r}"
            )
        self.ds = 0.2 * cs if ds is None else check_positive(ds, "ds")
        if self.ds > self.arc_length:
            raise ConfigError(f"ds must not exceed arc_length, got {ds!r}")
        self.steer_cost = check_positive(steer_cost, "steer_cost", allow_zero=True)
        self.steer_change_cost = check_positive(steer_change_cost, "steer_change_cost", allow_zero=True)
        self.cost_weight = check_positive(cost_weight, "cost_weight", allow_zero=True)
        if heuristic not in HEURISTIC_KINDS:
            raise ConfigError(f"heuristic must be one of {HEURISTIC_KINDS}, got {heuristic!r}")
        self.heuristic = heuristic
        self.heuristic_weight = check_positive(heuristic_weight, "heuristic_weight")
        self.goal_tolerance = (
            0.5 * cs
            if goal_tolerance is None
            else check_positive(goal_tolerance, "goal_tolerance", allow_zero=True)
        )
        self.heading_tolerance = check_positive(heading_tolerance, "heading_tolerance", allow_zero=True)
        self.shot_distance = (
            12.0 * cs
            if shot_distance is None
            else check_positive(shot_distance, "shot_distance", allow_zero=True)
        )
        self.shot_slack = check_positive(shot_slack, "shot_slack")
        self.max_expansions = positive_int(max_expansions, "max_expansions")
        self._version = 0
        self._hcache: dict = {}
        self._scratch_n = 0
        self._gen = 0
        self._scratch: tuple = ()

    # -- map ------------------------------------------------------------------
    @property
    def occ(self) -> np.ndarray:
        """Read-only view of the planner's current map."""
        v = self._occ.view()
        v.setflags(write=False)
        return v

    def update_cells(self, cells, blocked=True) -> int:
        """Mark cells ``(row, col)`` blocked or free; returns how many changed.

        Raises
        ------
        ConfigError
            If a cell is outside the grid.
        """
        arr = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
        h, w = self._occ.shape
        if len(arr) and (
            (arr[:, 0] < 0).any() or (arr[:, 0] >= h).any() or (arr[:, 1] < 0).any() or (arr[:, 1] >= w).any()
        ):
            bad = arr[(arr[:, 0] < 0) | (arr[:, 0] >= h) | (arr[:, 1] < 0) | (arr[:, 1] >= w)][0]
            raise ConfigError(f"cell {tuple(int(v) for v in bad)} is outside the {h}x{w} grid")
        flags = np.broadcast_to(np.asarray(blocked, dtype=bool), (len(arr),))
        changed = self._occ[arr[:, 0], arr[:, 1]] != flags
        if changed.any():
            self._occ[arr[changed, 0], arr[changed, 1]] = flags[changed]
            self._version += 1
            self._hcache.clear()
        return int(changed.sum())

    def set_map(self, occ) -> None:
        """Replace the planner's map (same shape)."""
        occ = np.asarray(occ, dtype=np.bool_)
        if occ.shape != self._occ.shape:
            raise ConfigError(f"map must have shape {self._occ.shape}, got {occ.shape}")
        if not np.array_equal(occ, self._occ):
            self._occ = np.array(occ, order="C", copy=True)
            self._version += 1
            self._hcache.clear()

    def _goal_grid(self, occ, cell, cached: bool) -> np.ndarray:
        if not cached:
            return grid_dijkstra(occ, cell[0], cell[1])
        key = cell
        grid = self._hcache.get(key)
        if grid is None:
            if len(self._hcache) > 16:
                self._hcache.clear()
            grid = grid_dijkstra(occ, cell[0], cell[1])
            self._hcache[key] = grid
        return grid

    def _arrays(self, n: int):
        if n > self._scratch_n:
            self._scratch = (
                np.zeros(n, np.int64),  # stamp
                np.empty(n, np.int64),
                np.empty(n),  # pos, g
                np.empty(n),
                np.empty(n),
                np.empty(n),  # x, y, theta
                np.empty(n, np.int64),
                np.empty(n, np.int64),  # parent, steer
                np.empty(n, np.int64),
                np.empty(n),
                np.empty(n),
            )  # heap
            self._scratch_n = n
            self._gen = 0
        self._gen += 1
        return self._gen, self._scratch

    # -- planning ---------------------------------------------------------------
    def default_start(self, goal=None) -> tuple[float, float, float]:
        """The workspace's start cell centre, heading along the first steps
        of the grid shortest path to the goal (straight at the goal when it
        is not connected)."""
        cs = self.cell_size
        (sr, sc) = self.workspace.start
        if goal is None:
            gr, gc = self.workspace.goal
            gx, gy = gc * cs, gr * cs
        else:
            gx, gy = goal[0], goal[1]
        gcell = (int(math.floor(gy / cs + 0.5)), int(math.floor(gx / cs + 0.5)))
        h, w = self._occ.shape
        if 0 <= gcell[0] < h and 0 <= gcell[1] < w:
            heading = initial_heading(self._goal_grid(self._occ, gcell, True), (sr, sc))
            if heading is not None:
                return (sc * cs, sr * cs, heading)
        return (sc * cs, sr * cs, math.atan2(gy - sr * cs, gx - sc * cs))

    def plan(
        self, start=None, goal=None, *, cost=None, blocked=None, max_length=None, max_expansions=None
    ) -> HybridPath:
        """Plan a drivable path from ``start`` to ``goal``.

        Parameters
        ----------
        start : (x, y, theta), optional
            World pose; default the workspace's start cell centre, heading
            towards the goal.
        goal : (x, y) or (x, y, theta), optional
            Goal point (any final heading) or pose; default the workspace's
            goal cell centre.
        cost : (H, W) array of float, optional
            Cost layer per unit length (the DSO + DMO terms), non-negative;
            weighted by ``cost_weight``.
        blocked : (H, W) array of bool, optional
            Extra obstacles for this call only (e.g. the predicted sweep of a
            moving obstacle).
        max_length : float, optional
            Only paths whose search cost can stay within this (world units)
            are sought: states with ``g + euclidean distance`` above it are
            pruned (NoPathError if none is left).
        max_expansions : int, optional
            Expansion budget of this call (default the planner's).

        Returns
        -------
        HybridPath

        Raises
        ------
        ConfigError
            If the start or the goal pose is outside the map or in collision,
            or ``cost``/``blocked`` have the wrong shape or invalid values.
        NoPathError
            If the goal cannot be reached (not connected, or every state was
            expanded, or ``max_expansions`` was reached).
        """
        t0 = time.perf_counter()
        cs = self.cell_size
        occ = self.occ  # read-only, as every map handed to a kernel (workspace.read_only)
        cached = True
        if blocked is not None:
            extra = np.asarray(blocked, dtype=bool)
            if extra.shape != occ.shape:
                raise ConfigError(f"blocked must have the grid's shape {occ.shape}, got {extra.shape}")
            if extra.any():
                occ = read_only(occ | extra)
                cached = False
        if goal is None:
            gr, gc = self.workspace.goal
            goal = (gc * cs, gr * cs)
        g = _as_pose(goal, "goal", (2, 3))
        s = self.default_start(g) if start is None else _as_pose(start, "start")
        sx, sy, sth = s[0] / cs, s[1] / cs, s[2]
        gx, gy = g[0] / cs, g[1] / cs
        has_gth = len(g) == 3
        gth = g[2] if has_gth else 0.0
        r = self.car.radius / cs
        r_check = r + 0.5 * self.ds / cs
        if not disc_free(occ, sx, sy, r_check):
            raise ConfigError(
                f"start {describe_pose(s, cs)} is in collision (robot radius "
                f"{self.car.radius:g}, --radius, plus the sampling margin {0.5 * self.ds:.3g}) "
                "or outside the map"
            )
        if not disc_free(occ, gx, gy, r_check):
            raise ConfigError(
                f"goal {describe_pose(g, cs)} is in collision (robot radius "
                f"{self.car.radius:g}, --radius, plus the sampling margin {0.5 * self.ds:.3g}) "
                "or outside the map"
            )
        h, w = occ.shape
        gcell = (int(math.floor(gy + 0.5)), int(math.floor(gx + 0.5)))
        hgrid = self._goal_grid(occ, gcell, cached)
        scell = (int(math.floor(sy + 0.5)), int(math.floor(sx + 0.5)))
        if not np.isfinite(hgrid[scell]):
            raise NoPathError(
                f"no path from the start {describe_pose(s, cs)} to the goal "
                f"{describe_pose(g, cs)}: the goal cell is not connected to the start cell"
            )
        if cost is None:
            layer = np.zeros((1, 1))
            use_layer = False
        else:
            layer = check_cost_layer(cost, occ.shape)
            use_layer = bool(layer.any())
        max_len = np.inf if max_length is None else check_positive(max_length, "max_length") / cs
        budget = (
            self.max_expansions if max_expansions is None else positive_int(max_expansions, "max_expansions")
        )
        if hgrid[scell] / 1.09 > max_len + 1.0:
            raise NoPathError(
                f"no path within max_length={max_length:g}: the grid distance to the goal is "
                f"{hgrid[scell] * cs:.3f}"
            )
        steers = self.car.steering_angles()
        kappas = np.tan(steers) / (self.car.wheelbase / cs)
        gen, arr = self._arrays(h * w * self.heading_bins)
        status, goal_state, shot_k, shot_l, expansions = _search(
            occ,
            layer,
            use_layer,
            hgrid,
            self.heuristic == "dijkstra",
            sx,
            sy,
            sth,
            gx,
            gy,
            gth,
            has_gth,
            self.goal_tolerance / cs,
            self.heading_tolerance,
            kappas,
            steers,
            self.arc_length / cs,
            self.ds / cs,
            r_check,
            self.heading_bins,
            self.steer_cost / cs,
            self.steer_change_cost / cs,
            self.cost_weight,
            self.heuristic_weight,
            self.shot_distance / cs,
            self.car.min_turning_radius / cs,
            self.shot_slack,
            budget,
            max_len,
            arr[0],
            gen,
            *arr[1:],
        )
        if status in (_EXHAUSTED, _LIMIT):
            why = (
                "every reachable state was expanded"
                if status == _EXHAUSTED
                else f"the budget of {budget} expansions was reached"
            )
            if max_length is not None and status == _EXHAUSTED:
                why += f" within max_length={max_length:g}"
            raise NoPathError(
                f"no drivable path from the start {describe_pose(s, cs)} to the goal "
                f"{describe_pose(g, cs)} for a car with minimum turning radius "
                f"{self.car.min_turning_radius:.3g} and radius {self.car.radius:g}: {why} "
                f"({expansions} expansions); try a tighter turn (a larger --max-steer or a shorter "
                "--wheelbase), a smaller --radius or more --heading-bins"
            )
        stamp, pos, gval, px, py, pth, parent, psteer = arr[:8]
        pts, actions = _extract(
            goal_state,
            parent,
            psteer,
            px,
            py,
            pth,
            kappas,
            self.arc_length / cs,
            self.ds / cs,
            shot_k,
            shot_l,
        )
        poses = pts.copy()
        poses[:, :2] *= cs
        poses.setflags(write=False)
        obj = path_objectives(poses, occ, cs)
        total = gval[goal_state] * cs + float(shot_l.sum()) * cs
        reached = "shot" if status == _FOUND_SHOT else ("start" if len(poses) == 1 else "tolerance")
        return HybridPath(
            poses=poses,
            length=obj["length"],
            turning=obj["turning"],
            clearance=obj["clearance"],
            cost=float(total),
            expansions=int(expansions),
            seconds=time.perf_counter() - t0,
            reached=reached,
            steering=steers[actions],
        )

    def __repr__(self) -> str:
        h, w = self._occ.shape
        return (
            f"HybridAStar(shape={h}x{w}, R_min={self.car.min_turning_radius:.3g}, "
            f"radius={self.car.radius:g}, heading_bins={self.heading_bins}, "
            f"arc_length={self.arc_length:g})"
        )


def hybrid_astar(workspace, start=None, goal=None, *, car: CarModel | None = None, **kwargs) -> HybridPath:
    """One hybrid A* plan on ``workspace`` (see :class:`HybridAStar`).

    Parameters
    ----------
    workspace : Workspace
    start : (x, y, theta), optional
        World pose; default the start cell centre heading towards the goal.
    goal : (x, y) or (x, y, theta), optional
        Default the goal cell centre, any heading.
    car : CarModel, optional
    **kwargs
        Settings of :class:`HybridAStar`, and ``cost``/``blocked`` of
        :meth:`HybridAStar.plan`.

    Returns
    -------
    HybridPath

    Raises
    ------
    ConfigError
        Invalid settings, or a start/goal in collision.
    NoPathError
        The goal is unreachable.
    """
    plan_kw = {k: kwargs.pop(k) for k in ("cost", "blocked") if k in kwargs}
    return HybridAStar(workspace, car, **kwargs).plan(start, goal, **plan_kw)
