"""Collision prediction: the motion equations of NO-MOPP (eqs. (7)-(10)) for a robot on a path and obstacles at constant velocity."""

from __future__ import annotations

import math

import numba
import numpy as np

from gapath.planners.geometry import disc_free


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
    if b >= 0.0:  # moving apart (both roots negative)
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


def path_contact(
    path, s0: float, speed: float, horizon: float, obstacle_position, obstacle_velocity, radius: float
) -> tuple[float, float]:
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
    t, dm = _path_contact(
        P,
        S,
        float(s0),
        float(speed),
        float(horizon),
        float(obstacle_position[0]),
        float(obstacle_position[1]),
        float(obstacle_velocity[0]),
        float(obstacle_velocity[1]),
        float(radius),
    )
    return float(t), float(dm)
