"""RRT and RRT* on the occupancy grid (the NO-MOPP paper's baselines).

Kinematics-free: the tree grows by straight segments (S. M. LaValle, "Rapidly
exploring random trees", 1998), and RRT* chooses parents and rewires within a
shrinking radius (S. Karaman and E. Frazzoli, "Sampling-based algorithms for
optimal motion planning", IJRR 2011), as in PythonRobotics' ``rrt`` and
``rrt_star``:

1. Sample a point: the goal with probability ``goal_bias``, otherwise a
   uniform point of the map.
2. Find the nearest tree node and *steer*: move from it towards the sample
   by at most ``step``.
3. Keep the new node only if the segment is collision-free (the disc model
   of :mod:`gapath.planners._geometry`, the same as hybrid A*'s: the robot's
   disc swept along every segment is free).
4. RRT*: among the nodes within ``r_n = min(gamma * sqrt(log(n) / n),
   rewire_radius)`` choose the parent that minimises the cost to come
   (path length), then *rewire* those neighbours through the new node when
   that shortens them.
5. When the new node can see the goal within ``step``, connect it. RRT stops
   at the first connection; RRT* keeps growing for ``extra_iterations``
   more iterations (default: as many as the first solution needed, at least
   500) and returns the cheapest connection.

Randomness comes from :func:`numpy.random.default_rng` with ``seed``: the
same seed gives the same tree. RRT and RRT* with the same seed draw the same
samples, so until RRT stops their trees hold the same points (only the
parents differ); this makes RRT* never worse than RRT on the same seed.

Points are world coordinates ``(x, y) = (col, row) * cell_size`` (the frame
of :mod:`gapath.planners.hybrid_astar`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numba
import numpy as np

from gapath.errors import ConfigError, NoPathError, positive_int
from gapath.planners._geometry import disc_free, segment_free
from gapath.planners.hybrid_astar import check_positive, describe_pose, path_objectives
from gapath.workspace import read_only

__all__ = ["RRTPath", "rrt", "rrt_settings", "rrt_star"]


@dataclass(frozen=True, eq=False)
class RRTPath:
    """A path found by :func:`rrt` or :func:`rrt_star`.

    Attributes
    ----------
    points : (n, 2) float array
        World points ``(x, y)`` from the start to the goal (read-only).
    poses : (n, 3) float array
        The points with the heading of the segment that leaves them (the
        last takes the last segment's).
    length, turning, clearance : float
        Objectives as for hybrid A* (:func:`~gapath.planners.hybrid_astar.path_objectives`).
    cost : float
        Path length (the cost RRT* minimises), world units.
    iterations : int
        Iterations run (samples drawn).
    nodes : int
        Tree size at the end.
    first_solution : int
        Iteration at which the goal was first connected.
    seconds : float
        Wall-clock time of the call.
    """

    points: np.ndarray
    poses: np.ndarray
    length: float
    turning: float
    clearance: float
    cost: float
    iterations: int
    nodes: int
    first_solution: int
    seconds: float

    @property
    def objectives(self) -> dict:
        return {"length": self.length, "turning": self.turning, "clearance": self.clearance}

    def __repr__(self) -> str:
        return (
            f"RRTPath(points={len(self.points)}, length={self.length:.4f}, "
            f"iterations={self.iterations}, nodes={self.nodes}, "
            f"first_solution={self.first_solution}, seconds={self.seconds:.6f})"
        )


@numba.njit(cache=True)
def _unlink(first_child, next_sib, p, c):
    """Remove ``c`` from the child list of ``p``."""
    if first_child[p] == c:
        first_child[p] = next_sib[c]
        return
    a = first_child[p]
    while a != -1:
        if next_sib[a] == c:
            next_sib[a] = next_sib[c]
            return
        a = next_sib[a]


@numba.njit(cache=True)
def _grow(
    occ, sx, sy, gx, gy, samples, step, goal_bias, goal_tol, r_check, ds, star, gamma, rewire_radius, extra
):
    """Grow the tree (cell units). Returns ``(path, iterations, nodes,
    first_solution)``; ``path`` is empty when the goal was never connected."""
    h, w = occ.shape
    cap = samples.shape[0] + 2
    nx = np.empty(cap)
    ny = np.empty(cap)
    cost = np.empty(cap)
    parent = np.empty(cap, dtype=np.int64)
    nx[0] = sx
    ny[0] = sy
    cost[0] = 0.0
    parent[0] = -1
    n = 1
    best_node = -1
    best_cost = np.inf
    first = -1
    stop_at = samples.shape[0]
    near = np.empty(cap, dtype=np.int64)
    first_child = np.full(cap, -1, dtype=np.int64)
    next_sib = np.full(cap, -1, dtype=np.int64)
    stack = np.empty(cap, dtype=np.int64)
    it = 0
    while it < stop_at:
        # 1. sample: the goal with probability goal_bias, else uniform
        if samples[it, 0] < goal_bias:
            qx = gx
            qy = gy
        else:
            qx = -0.5 + samples[it, 1] * w
            qy = -0.5 + samples[it, 2] * h
        it += 1
        # 2. nearest node and steer
        nearest = 0
        dbest = np.inf
        for i in range(n):
            d = (nx[i] - qx) ** 2 + (ny[i] - qy) ** 2
            if d < dbest:
                dbest = d
                nearest = i
        d = math.sqrt(dbest)
        if d < 1e-9:
            continue
        t = min(1.0, step / d)
        px = nx[nearest] + t * (qx - nx[nearest])
        py = ny[nearest] + t * (qy - ny[nearest])
        # 3. collision check of the new segment
        if not segment_free(occ, nx[nearest], ny[nearest], px, py, r_check, ds):
            continue
        par = nearest
        pc = cost[nearest] + math.hypot(px - nx[nearest], py - ny[nearest])
        k = 0
        if star:
            # 4. choose the cheapest parent among the near nodes ...
            rn = rewire_radius
            if n > 1:
                rn = min(rewire_radius, gamma * math.sqrt(math.log(n + 1) / (n + 1)))
            rn2 = rn * rn
            for i in range(n):
                if (nx[i] - px) ** 2 + (ny[i] - py) ** 2 <= rn2:
                    near[k] = i
                    k += 1
            for j in range(k):
                i = near[j]
                c = cost[i] + math.hypot(px - nx[i], py - ny[i])
                if c < pc and i != nearest and segment_free(occ, nx[i], ny[i], px, py, r_check, ds):
                    pc = c
                    par = i
        v = n
        nx[v] = px
        ny[v] = py
        cost[v] = pc
        parent[v] = par
        first_child[v] = -1
        next_sib[v] = first_child[par]
        first_child[par] = v
        n += 1
        if star:
            # ... and rewire them through the new node
            for j in range(k):
                i = near[j]
                if i == par:
                    continue
                c = pc + math.hypot(px - nx[i], py - ny[i])
                if c < cost[i] and segment_free(occ, px, py, nx[i], ny[i], r_check, ds):
                    _unlink(first_child, next_sib, parent[i], i)
                    parent[i] = v
                    next_sib[i] = first_child[v]
                    first_child[v] = i
                    cost[i] = c
                    # propagate the improvement to the subtree of i
                    top = 0
                    stack[0] = i
                    top = 1
                    while top > 0:
                        top -= 1
                        a = stack[top]
                        ch = first_child[a]
                        while ch != -1:
                            cost[ch] = cost[a] + math.hypot(nx[ch] - nx[a], ny[ch] - ny[a])
                            stack[top] = ch
                            top += 1
                            ch = next_sib[ch]
        # 5. connect to the goal
        dg = math.hypot(gx - px, gy - py)
        if dg <= max(step, goal_tol) and (dg <= goal_tol or segment_free(occ, px, py, gx, gy, r_check, ds)):
            c = pc + dg
            if c < best_cost:
                best_cost = c
                best_node = v
            if first < 0:
                first = it
                if not star:
                    break
                stop_at = min(samples.shape[0], it + (extra if extra > 0 else max(it, 500)))
    if best_node < 0:
        return np.empty((0, 2)), it, n, first
    if star:
        # the cheapest goal connection after rewiring
        for i in range(n):
            dg = math.hypot(gx - nx[i], gy - ny[i])
            if dg <= max(step, goal_tol) and cost[i] + dg < best_cost:
                if dg <= goal_tol or segment_free(occ, nx[i], ny[i], gx, gy, r_check, ds):
                    best_cost = cost[i] + dg
                    best_node = i
    m = 1
    v = best_node
    while v != -1:
        m += 1
        v = parent[v]
    out = np.empty((m, 2))
    out[m - 1, 0] = gx
    out[m - 1, 1] = gy
    v = best_node
    for j in range(m - 2, -1, -1):
        out[j, 0] = nx[v]
        out[j, 1] = ny[v]
        v = parent[v]
    # drop a zero-length last segment (node on the goal)
    if m >= 2 and out[m - 2, 0] == gx and out[m - 2, 1] == gy:
        out = out[: m - 1]
    return out, it, n, first


def _unit(value, name, lo, hi):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ConfigError(f"{name} must be a number in [{lo}, {hi}], got {value!r}") from None
    if not (lo <= v <= hi):
        raise ConfigError(f"{name} must be in [{lo}, {hi}], got {value!r}")
    return v


def _point(value, name):
    try:
        vals = tuple(float(v) for v in value)
    except (TypeError, ValueError):
        raise ConfigError(f"{name} must be a point (x, y), got {value!r}") from None
    if len(vals) not in (2, 3) or not all(math.isfinite(v) for v in vals):
        raise ConfigError(f"{name} must be (x, y) (or a pose (x, y, theta)) of finite numbers, got {value!r}")
    return vals[0], vals[1]


def rrt_settings(
    cell_size: float,
    *,
    radius: float = 0.3,
    step: float | None = None,
    goal_bias: float = 0.1,
    goal_tolerance: float | None = None,
    max_iter: int = 20000,
    rewire_radius: float | None = None,
    extra_iterations: int | None = None,
    ds: float | None = None,
) -> tuple:
    """The checked settings of :func:`rrt` (same names and defaults), in
    cell units: ``(radius, step, goal_bias, goal_tolerance, ds, max_iter,
    extra_iterations, rewire_radius)``. Callers that take the settings from
    elsewhere (the CLI) check them here before a run.

    Raises
    ------
    ConfigError
        Naming the first setting out of its range.

    Examples
    --------
    >>> rrt_settings(0.5, step=1.0)[1]
    2.0
    >>> rrt_settings(1.0, goal_bias=2)
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: goal_bias must be in [0.0, 1.0], got 2
    """
    cs = float(cell_size)
    r = check_positive(radius, "radius", allow_zero=True) / cs
    stp = 2.0 if step is None else check_positive(step, "step") / cs
    bias = _unit(goal_bias, "goal_bias", 0.0, 1.0)
    tol = (
        0.5
        if goal_tolerance is None
        else check_positive(goal_tolerance, "goal_tolerance", allow_zero=True) / cs
    )
    dsv = 0.2 if ds is None else check_positive(ds, "ds") / cs
    iters = positive_int(max_iter, "max_iter")
    extra_it = 0 if extra_iterations is None else int(extra_iterations)
    if extra_it < 0:
        raise ConfigError(f"extra_iterations must be >= 0, got {extra_iterations!r}")
    rew = 3.0 * stp if rewire_radius is None else check_positive(rewire_radius, "rewire_radius") / cs
    return r, stp, bias, tol, dsv, iters, extra_it, rew


def rrt(
    workspace,
    start=None,
    goal=None,
    *,
    seed=0,
    radius: float = 0.3,
    step: float | None = None,
    goal_bias: float = 0.1,
    goal_tolerance: float | None = None,
    max_iter: int = 20000,
    star: bool = False,
    rewire_radius: float | None = None,
    extra_iterations: int | None = None,
    ds: float | None = None,
    blocked=None,
) -> RRTPath:
    """A path by RRT (``star=False``) or RRT* (``star=True``).

    Parameters
    ----------
    workspace : Workspace
        Grid, ``cell_size``, default start and goal cells.
    start, goal : (x, y), optional
        World points (a pose's heading is ignored); default the centres of
        the workspace's start and goal cells.
    seed : int or numpy Generator
        Random seed (deterministic).
    radius : float, default 0.3
        Robot disc radius, world units (as :class:`~gapath.planners.hybrid_astar.CarModel`).
    step : float, optional
        Largest extension of the tree, world units (default 2 cells).
    goal_bias : float, default 0.1
        Probability of sampling the goal.
    goal_tolerance : float, optional
        A node this close to the goal counts as on it (default ``0.5 * cell_size``).
    max_iter : int, default 20000
        Iterations (samples) in all.
    star : bool, default False
        RRT* (choose parent and rewire) instead of RRT.
    rewire_radius : float, optional
        RRT*: the neighbourhood radius is ``min(gamma * sqrt(log(n)/n),
        rewire_radius)`` with ``gamma = 2 sqrt(1.5 * free_area / pi)``
        (Karaman & Frazzoli); default ``rewire_radius = 3 * step``.
    extra_iterations : int, optional
        RRT*: iterations after the first solution (default as many as the
        first solution took, at least 500; capped by ``max_iter``).
    ds : float, optional
        Collision sample spacing (default ``0.2 * cell_size``).
    blocked : (H, W) bool array, optional
        Extra obstacles for this call.

    Returns
    -------
    RRTPath

    Raises
    ------
    ConfigError
        On invalid settings or a start/goal in collision.
    NoPathError
        If no path was found within ``max_iter`` iterations.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> ws = Workspace(np.zeros((10, 10), bool))
    >>> res = rrt(ws, seed=1)
    >>> bool(res.points[0, 1] == 9.0 and res.points[-1, 0] == 9.0)
    True
    """
    t0 = time.perf_counter()
    cs = float(workspace.cell_size)
    occ = np.ascontiguousarray(workspace.occ, dtype=np.bool_)
    if blocked is not None:
        extra = np.asarray(blocked, dtype=bool)
        if extra.shape != occ.shape:
            raise ConfigError(f"blocked must have the grid's shape {occ.shape}, got {extra.shape}")
        occ = read_only(occ | extra)  # as the workspace's: one kernel specialization
    r, stp, bias, tol, dsv, iters, extra_it, rew = rrt_settings(
        cs,
        radius=radius,
        step=step,
        goal_bias=goal_bias,
        goal_tolerance=goal_tolerance,
        max_iter=max_iter,
        rewire_radius=rewire_radius,
        extra_iterations=extra_iterations,
        ds=ds,
    )
    if start is None:
        sr, sc = workspace.start
        start = (sc * cs, sr * cs)
    if goal is None:
        gr, gc = workspace.goal
        goal = (gc * cs, gr * cs)
    sx, sy = (v / cs for v in _point(start, "start"))
    gx, gy = (v / cs for v in _point(goal, "goal"))
    r_check = r + 0.5 * dsv
    for label, (px, py) in (("start", (sx, sy)), ("goal", (gx, gy))):
        if not disc_free(occ, px, py, r_check):
            raise ConfigError(
                f"{label} {describe_pose((px * cs, py * cs), cs)} is in collision "
                f"(robot radius {float(radius):g}, --radius) or outside the map"
            )
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    samples = rng.random((iters, 3))
    free_area = float((~occ).sum())
    gamma = 2.0 * math.sqrt(1.5 * free_area / math.pi)
    pts, it, n, first = _grow(
        occ, sx, sy, gx, gy, samples, stp, bias, tol, r_check, dsv, bool(star), gamma, rew, extra_it
    )
    if len(pts) == 0:
        raise NoPathError(
            f"{'RRT*' if star else 'RRT'} found no path from the start "
            f"{describe_pose((sx * cs, sy * cs), cs)} to the goal "
            f"{describe_pose((gx * cs, gy * cs), cs)} in {iters} iterations (tree of {n} "
            "nodes); try more --iterations, a larger --goal-bias or a smaller --radius"
        )
    points = pts * cs
    d = np.diff(points, axis=0)
    heading = np.arctan2(d[:, 1], d[:, 0]) if len(d) else np.zeros(0)
    heading = np.append(heading, heading[-1] if len(heading) else 0.0)
    poses = np.column_stack([points, heading])
    obj = path_objectives(poses, occ, cs)
    points.setflags(write=False)
    poses.setflags(write=False)
    return RRTPath(
        points=points,
        poses=poses,
        length=obj["length"],
        turning=obj["turning"],
        clearance=obj["clearance"],
        cost=obj["length"],
        iterations=int(it),
        nodes=int(n),
        first_solution=int(first),
        seconds=time.perf_counter() - t0,
    )


def rrt_star(workspace, start=None, goal=None, **kwargs) -> RRTPath:
    """RRT* (:func:`rrt` with ``star=True``)."""
    kwargs["star"] = True
    return rrt(workspace, start, goal, **kwargs)
