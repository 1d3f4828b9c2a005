"""The tick loop of a dynamic run (NO-MOPP's Algorithm 2): :class:`Simulation` and :func:`simulate`."""

from __future__ import annotations

import math
import time

import numpy as np

from gapath.dynamic.planners import HybridAStarPlanner, Planner, make_planner
from gapath.dynamic.prediction import (
    _bounce_step,
    _min_distance,
    _path_contact,
    _position_on_path,
    _predict_track,
    _track_contact,
)
from gapath.dynamic.results import SimResult
from gapath.dynamic.world import MovingObstacle, Robot, SimSettings, StationaryObstacle
from gapath.errors import ConfigError, GapathError, NoPathError
from gapath.planners.geometry import disc_free, first_blocked, grid_dijkstra, segment_free
from gapath.planners.hybrid_astar import initial_heading
from gapath.workspace import potential_field


def start_pose(workspace) -> tuple[float, float, float]:
    """World pose at the workspace's start cell, heading along the first
    steps of the grid shortest path to the goal."""

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

    def __init__(
        self,
        workspace,
        planner,
        robot: Robot | None = None,
        stationary=(),
        moving=(),
        settings: SimSettings | None = None,
        start=None,
        seed: int = 0,
    ):
        self.workspace = workspace
        self.planner = make_planner(planner) if isinstance(planner, str) else planner
        if not isinstance(self.planner, Planner):
            raise ConfigError(f"planner must be a Planner or a name, got {planner!r}")
        self.robot = Robot() if robot is None else robot
        if not isinstance(self.robot, Robot):
            raise ConfigError(f"robot must be a Robot, got {type(robot).__name__}")
        self.settings = SimSettings() if settings is None else settings
        self.stationary = [StationaryObstacle(o.cells.copy(), o.appear_at) for o in stationary]
        self.moving = [
            MovingObstacle(o.position.copy(), o.velocity.copy(), o.radius, o.mode, o.appear_at)
            for o in moving
        ]
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
            for r, c in o.cells:
                if self._visible(x, y, c * cs, r * cs, 0.5 * cs):
                    self.detected[k] = True
                    new_cells.extend(o.cells.tolist())
                    self._event(
                        t,
                        "detect",
                        obstacle=f"stationary-{k}",
                        distance=round(math.hypot(c * cs - x, r * cs - y), 3),
                    )
                    break
        for k, o in enumerate(self.moving):
            if not self.active[k]:
                continue
            if self._visible(x, y, o.position[0], o.position[1], o.radius):
                if k not in self.tracks or t - self.tracks[k][0] > self.settings.dt * 1.5:
                    self._event(
                        t,
                        "detect",
                        obstacle=f"moving-{k}",
                        distance=round(float(np.hypot(*(o.position - (x, y)))), 3),
                    )
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
                tr = _predict_track(self.known, p[0], p[1], v[0], v[1], r / self.cs, self.cs, st.dt, m, True)
                p = tr[-1]
            elif ts < t:
                p = p + v * (t - ts)
            track = _predict_track(
                self.known, p[0], p[1], v[0], v[1], r / self.cs, self.cs, st.dt, n, bool(st.predict_bounces)
            )
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
        n = min(int(math.ceil(st.sweep_time / st.dt)), 10**6)
        for _, _p, _v, r, track in obstacles:
            for q in track[: n + 1 : 2]:
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
            goal = (
                (rejoin[0], rejoin[1], rejoin[2])
                if isinstance(self.planner, HybridAStarPlanner)
                else (rejoin[0], rejoin[1])
            )
            limit = None if detour is None else float(self.S[j] - self.s) + detour
            local, dt, err = self._plan(cur, goal, blocked, cost, limit)
            spent += dt
            if local is not None:
                total = float(_arc_lengths(local)[-1]) + float(self.S[-1] - self.S[j])
                if best is None or total < best[0]:
                    best = (total, np.vstack([local, rest[1:]]) if len(rest) > 1 else local, float(self.S[j]))
        if best is not None:
            self.replan_seconds.append(spent)
            self._event(
                t, "replan", reason=reason, scope="local", seconds=round(spent, 6), rejoin=round(best[2], 3)
            )
            return best[1]
        limit = None if detour is None else float(self.S[-1] - self.s) + detour
        new, dt, err = self._plan(cur, self.goal, blocked, cost, limit)
        spent += dt
        self.replan_seconds.append(spent)
        if new is None:
            self._event(t, "replan-failed", reason=reason, error=str(err)[:200], seconds=round(spent, 6))
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
            for r, c in o.cells:
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
                    gap = math.hypot(o.position[0] - x, o.position[1] - y) - o.radius - self.robot.radius
                    if gap > 3.0 * st.appear_clearance:
                        self.active[k] = True
                        if o.appear_at > 0:
                            self._event(t, "appear", obstacle=f"moving-{k}")
                continue
            p, v = o.position, o.velocity
            if o.mode == "pass":
                o.position = p + v * dt
                xc, yc = o.position / cs
                if (
                    xc < -0.5 - o.radius / cs
                    or xc > w - 0.5 + o.radius / cs
                    or yc < -0.5 - o.radius / cs
                    or yc > h - 0.5 + o.radius / cs
                ):
                    self.active[k] = False
                    self.gone[k] = True
                continue
            qx, qy, vx, vy = _bounce_step(self.true_occ, p[0], p[1], v[0], v[1], o.radius / cs, cs, dt)
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
            return SimResult(
                success=success,
                reason=reason,
                time=t,
                path_length=length,
                direct_distance=direct,
                global_plan_seconds=gsec,
                replan_seconds=list(self.replan_seconds),
                global_path=gpath,
                trajectory=np.array(traj).reshape(-1, 5),
                events=self.events,
                paths=self.paths,
                obstacles=None
                if world is None
                else np.array(world, float).reshape(len(world), len(self.moving), 2),
                planner=self.planner.name,
                seed=self.seed,
            )

        self._traj = traj

        def record(t, v):
            traj.append((t, self.pose[0], self.pose[1], self.pose[2], v))
            if world is not None:
                world.append(
                    [
                        o.position.copy() if self.active[k] else (np.nan, np.nan)
                        for k, o in enumerate(self.moving)
                    ]
                )

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
        mode = "go"  # go | halt | back
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
            self._prev_pos = [
                o.position.copy() if self.active[k] else None for k, o in enumerate(self.moving)
            ]
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
            hit = (
                first_blocked(self.known, np.ascontiguousarray(rest), r_chk, 0.1)
                if (new_cells or blocked_since is not None)
                else -1
            )
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
                        self._event(
                            t, "predict", obstacle=f"moving-{k}", t_collision=round(tc, 3), gap=round(gap, 3)
                        )
                    if (
                        gap >= st.replan_distance
                        and tc >= st.halt_time
                        and t - last_mover_replan >= st.replan_cooldown
                    ):
                        last_mover_replan = t
                        sweep = self._sweep(obstacles)
                        cost = (
                            self._cost_layer(sweep) if isinstance(self.planner, HybridAStarPlanner) else None
                        )
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
                    near = gap < st.replan_distance + (0.5 if waiting else 0.0) or tc < st.halt_time + (
                        1.0 if waiting else 0.0
                    )
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
            if (
                self.s >= self.S[-1] - 1e-9
                and math.hypot(self.pose[0] - self.goal[0], self.pose[1] - self.goal[1]) <= st.goal_tolerance
            ):
                self._event(t, "goal")
                return finish(True, "goal", t, length, gpath, gsec)
            if self.s >= self.S[-1] - 1e-9 and blocked_since is None:
                # at the end of a path that stops short of the goal (tolerance): plan on
                new, _, _ = self._plan(self.pose, self.goal)
                if new is not None and len(new) > 1:
                    self._set_path(new, t)
        self._event(t, "timeout", max_time=max_time)
        return finish(False, "timeout", t, length, gpath, gsec)


def simulate(
    workspace,
    planner="hybrid-astar",
    robot=None,
    stationary=(),
    moving=(),
    settings=None,
    start=None,
    seed: int = 0,
) -> SimResult:
    """Run one :class:`Simulation` (same parameters) and return its result."""
    return Simulation(workspace, planner, robot, stationary, moving, settings, start, seed).run()
