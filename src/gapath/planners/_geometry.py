"""Continuous geometry on the occupancy grid (numba kernels).

Shared by :mod:`gapath.planners.hybrid_astar`, :mod:`gapath.planners.rrt` and
:mod:`gapath.dynamic`.

Frame (cell units)
    A point is ``(x, y)`` with ``x`` the column axis and ``y`` the row axis:
    the centre of cell ``(row, col)`` is ``(x, y) = (col, row)`` (SPEC: cell
    centres at ``(row, col)``), and the cell covers the closed square
    ``[col - 1/2, col + 1/2] x [row - 1/2, row + 1/2]``. A heading ``theta``
    is measured from the ``+x`` axis (east) towards ``+y`` (south, down the
    image), so on a picture drawn with row 0 on top a positive curvature
    turns clockwise. Public functions scale by ``cell_size`` (world units =
    cell units times ``cell_size``); the kernels here work in cell units.

Collision model
    The robot is a disc of radius ``r`` (``r = 0`` is a point). It collides
    when the closed disc meets an obstacle cell (a closed square) or leaves
    the map ``[-1/2, W - 1/2] x [-1/2, H - 1/2]``. A path is checked at
    samples spaced at most ``ds`` apart with the radius ``r + ds / 2``:
    every point of the path is within ``ds / 2`` of a sample, so the disc of
    radius ``r`` swept along the whole path is collision-free, not only the
    samples (see :func:`sweep_radius`).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from gapath.grid import DC, DR, STEP, ZERO, can_step
from gapath.planners._grid import heap_decrease, heap_pop, heap_push

TWO_PI = 2.0 * math.pi


def sweep_radius(radius: float, ds: float) -> float:
    """The radius to check samples ``ds`` apart with so that the disc of
    ``radius`` swept along the path between them is collision-free."""
    return radius + 0.5 * ds


@numba.njit(cache=True)
def mod2pi(a):
    """``a`` in ``[0, 2 pi)``."""
    a = a - TWO_PI * math.floor(a / TWO_PI)
    if a >= TWO_PI or a < 0.0:
        a = 0.0
    return a


@numba.njit(cache=True)
def angle_diff(a, b):
    """Absolute difference of two angles, in ``[0, pi]``."""
    d = mod2pi(a - b)
    return d if d <= math.pi else TWO_PI - d


# ---------------------------------------------------------------------------
# discs against the grid
# ---------------------------------------------------------------------------


@numba.njit(cache=True)
def disc_free(occ, x, y, r):
    """True if the closed disc of radius ``r`` at ``(x, y)`` (cell units)
    meets no obstacle cell and stays inside the map."""
    h, w = occ.shape
    if x - r < -0.5 or x + r > w - 0.5 or y - r < -0.5 or y + r > h - 0.5:
        return False
    c0 = max(0, int(math.ceil(x - r - 0.5)))
    c1 = min(w - 1, int(math.floor(x + r + 0.5)))
    r0 = max(0, int(math.ceil(y - r - 0.5)))
    r1 = min(h - 1, int(math.floor(y + r + 0.5)))
    rr = r * r
    for i in range(r0, r1 + 1):
        dy = abs(y - i) - 0.5
        if dy < 0.0:
            dy = 0.0
        for j in range(c0, c1 + 1):
            if occ[i, j]:
                dx = abs(x - j) - 0.5
                if dx < 0.0:
                    dx = 0.0
                if dx * dx + dy * dy <= rr:
                    return False
    return True


@numba.njit(cache=True)
def segment_free(occ, x0, y0, x1, y1, r, ds):
    """True if samples at most ``ds`` apart on the segment, ends included,
    are all free for a disc of radius ``r``."""
    d = math.hypot(x1 - x0, y1 - y0)
    n = max(1, int(math.ceil(d / ds)))
    for i in range(n + 1):
        t = i / n
        if not disc_free(occ, x0 + t * (x1 - x0), y0 + t * (y1 - y0), r):
            return False
    return True


@numba.njit(cache=True)
def first_blocked(occ, pts, r, ds):
    """Index of the first polyline vertex ``i`` such that the piece from
    ``pts[i-1]`` to ``pts[i]`` (or ``pts[0]`` itself) is not free; -1 if the
    whole polyline is free. ``pts`` is ``(n, >=2)`` with ``x, y`` first."""
    if pts.shape[0] == 0:
        return -1
    if not disc_free(occ, pts[0, 0], pts[0, 1], r):
        return 0
    for i in range(1, pts.shape[0]):
        if not segment_free(occ, pts[i - 1, 0], pts[i - 1, 1], pts[i, 0], pts[i, 1], r, ds):
            return i
    return -1


@numba.njit(cache=True)
def point_clearance(occ, x, y, cap):
    """Distance from ``(x, y)`` to the nearest obstacle cell or map edge,
    capped at ``cap`` (cell units)."""
    h, w = occ.shape
    best = min(cap, x + 0.5, w - 0.5 - x, y + 0.5, h - 0.5 - y)
    if best <= 0.0:
        return 0.0
    c0 = max(0, int(math.ceil(x - best - 0.5)))
    c1 = min(w - 1, int(math.floor(x + best + 0.5)))
    r0 = max(0, int(math.ceil(y - best - 0.5)))
    r1 = min(h - 1, int(math.floor(y + best + 0.5)))
    b2 = best * best
    for i in range(r0, r1 + 1):
        dy = abs(y - i) - 0.5
        if dy < 0.0:
            dy = 0.0
        for j in range(c0, c1 + 1):
            if occ[i, j]:
                dx = abs(x - j) - 0.5
                if dx < 0.0:
                    dx = 0.0
                d2 = dx * dx + dy * dy
                if d2 < b2:
                    b2 = d2
    return math.sqrt(b2)


@numba.njit(cache=True)
def path_clearance(occ, pts, cap):
    """Smallest :func:`point_clearance` over the vertices of a polyline."""
    best = cap
    for i in range(pts.shape[0]):
        c = point_clearance(occ, pts[i, 0], pts[i, 1], cap)
        if c < best:
            best = c
    return best


# ---------------------------------------------------------------------------
# arcs of a simple car
# ---------------------------------------------------------------------------


@numba.njit(cache=True)
def arc_point(x, y, th, kappa, s):
    """Pose after driving the arc of curvature ``kappa`` for length ``s``
    (``kappa = 0`` is a straight line)."""
    if abs(kappa) < 1e-12:
        return x + s * math.cos(th), y + s * math.sin(th), th
    th1 = th + kappa * s
    return (x + (math.sin(th1) - math.sin(th)) / kappa, y - (math.cos(th1) - math.cos(th)) / kappa, th1)


@numba.njit(cache=True)
def sample_arcs(x, y, th, kappas, lengths, ds):
    """Poses along consecutive arcs (curvature, length), at most ``ds``
    apart, the first pose included; headings are not wrapped."""
    n = 1
    for k in range(kappas.shape[0]):
        if lengths[k] > 0.0:
            n += max(1, int(math.ceil(lengths[k] / ds)))
    out = np.empty((n, 3))
    out[0, 0] = x
    out[0, 1] = y
    out[0, 2] = th
    m = 1
    for k in range(kappas.shape[0]):
        if lengths[k] <= 0.0:
            continue
        steps = max(1, int(math.ceil(lengths[k] / ds)))
        for i in range(1, steps + 1):
            px, py, pt = arc_point(x, y, th, kappas[k], lengths[k] * i / steps)
            out[m, 0] = px
            out[m, 1] = py
            out[m, 2] = pt
            m += 1
        x, y, th = arc_point(x, y, th, kappas[k], lengths[k])
    return out


@numba.njit(cache=True)
def arcs_free(occ, x, y, th, kappas, lengths, r, ds):
    """True if the consecutive arcs are free (samples at most ``ds`` apart,
    disc radius ``r``)."""
    for k in range(kappas.shape[0]):
        if lengths[k] <= 0.0:
            continue
        steps = max(1, int(math.ceil(lengths[k] / ds)))
        for i in range(1, steps + 1):
            px, py, _ = arc_point(x, y, th, kappas[k], lengths[k] * i / steps)
            if not disc_free(occ, px, py, r):
                return False
        x, y, th = arc_point(x, y, th, kappas[k], lengths[k])
    return True


# ---------------------------------------------------------------------------
# Dubins curves (forward only, minimum turning radius R)
# ---------------------------------------------------------------------------
# The six words of L. E. Dubins (1957), in the closed forms of A. M. Shkel and
# V. J. Lumelsky (2001) as in PythonRobotics' dubins_path_planner: the start
# is rotated and scaled so that the goal lies on the x axis at distance
# d = D / R, with alpha, beta the start and goal headings in that frame.
# Segment curvature signs: L = +1 (theta grows), S = 0, R = -1. Each
# candidate is integrated and kept only when it really ends at the goal pose,
# so a slip in a formula can cost optimality but never correctness.

_WORDS = np.array([[1, 0, 1], [-1, 0, -1], [1, 0, -1], [-1, 0, 1], [-1, 1, -1], [1, -1, 1]], dtype=np.int64)


@numba.njit(cache=True)
def _dubins_word(word, alpha, beta, d):
    """Normalised segment lengths ``(t, p, q)`` of one word, or -1s."""
    sa = math.sin(alpha)
    sb = math.sin(beta)
    ca = math.cos(alpha)
    cb = math.cos(beta)
    cab = math.cos(alpha - beta)
    if word == 0:  # LSL
        p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sa - sb)
        if p2 < 0.0:
            return -1.0, -1.0, -1.0
        tmp = math.atan2(cb - ca, d + sa - sb)
        return mod2pi(-alpha + tmp), math.sqrt(p2), mod2pi(beta - tmp)
    if word == 1:  # RSR
        p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa)
        if p2 < 0.0:
            return -1.0, -1.0, -1.0
        tmp = math.atan2(ca - cb, d - sa + sb)
        return mod2pi(alpha - tmp), math.sqrt(p2), mod2pi(-beta + tmp)
    if word == 2:  # LSR
        p2 = -2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb)
        if p2 < 0.0:
            return -1.0, -1.0, -1.0
        p = math.sqrt(p2)
        tmp = math.atan2(-ca - cb, d + sa + sb) - math.atan2(-2.0, p)
        return mod2pi(-alpha + tmp), p, mod2pi(-mod2pi(beta) + tmp)
    if word == 3:  # RSL
        p2 = d * d - 2.0 + 2.0 * cab - 2.0 * d * (sa + sb)
        if p2 < 0.0:
            return -1.0, -1.0, -1.0
        p = math.sqrt(p2)
        tmp = math.atan2(ca + cb, d - sa - sb) - math.atan2(2.0, p)
        return mod2pi(alpha - tmp), p, mod2pi(beta - tmp)
    if word == 4:  # RLR
        tmp = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0
        if abs(tmp) > 1.0:
            return -1.0, -1.0, -1.0
        p = mod2pi(TWO_PI - math.acos(tmp))
        t = mod2pi(alpha - math.atan2(ca - cb, d - sa + sb) + p / 2.0)
        return t, p, mod2pi(alpha - beta - t + p)
    tmp = (6.0 - d * d + 2.0 * cab + 2.0 * d * (-sa + sb)) / 8.0  # LRL
    if abs(tmp) > 1.0:
        return -1.0, -1.0, -1.0
    p = mod2pi(TWO_PI - math.acos(tmp))
    t = mod2pi(-alpha - math.atan2(ca - cb, d + sa - sb) + p / 2.0)
    return t, p, mod2pi(mod2pi(beta) - alpha - t + mod2pi(p))


@numba.njit(cache=True)
def dubins(x0, y0, th0, x1, y1, th1, radius):
    """Shortest Dubins path between two poses.

    Returns ``(length, kappas, lengths)``: three segments of curvature
    ``kappas[i]`` (``+-1/radius`` or 0) and length ``lengths[i]``; the length
    is ``inf`` if no word applies (never for distinct poses).
    """
    dx = x1 - x0
    dy = y1 - y0
    d = math.hypot(dx, dy) / radius
    theta = mod2pi(math.atan2(dy, dx)) if d > 1e-12 else 0.0
    alpha = mod2pi(th0 - theta)
    beta = mod2pi(th1 - theta)
    best = np.inf
    kap = np.zeros(3)
    lens = np.zeros(3)
    ck = np.zeros(3)
    cl = np.zeros(3)
    for word in range(6):
        t, p, q = _dubins_word(word, alpha, beta, d)
        if t < 0.0:
            continue
        total = (t + p + q) * radius
        if total >= best:
            continue
        for i in range(3):
            ck[i] = _WORDS[word, i] / radius
        cl[0] = t * radius
        cl[1] = p * radius
        cl[2] = q * radius
        # verify the end pose (guards the closed forms)
        ex, ey, et = x0, y0, th0
        for i in range(3):
            ex, ey, et = arc_point(ex, ey, et, ck[i], cl[i])
        if math.hypot(ex - x1, ey - y1) > 1e-6 * max(1.0, radius) or angle_diff(et, th1) > 1e-6:
            continue
        best = total
        kap[:] = ck
        lens[:] = cl
    return best, kap, lens


@numba.njit(cache=True)
def turn_to_point(x0, y0, th0, x1, y1, radius):
    """Shortest forward path from a pose to a point (free final heading): an
    arc of the minimum radius to the left or right, then a straight line
    (the CS curves; a straight line when the point is ahead).

    Returns ``(length, kappas, lengths)`` with two segments; ``inf`` length
    when the point lies inside both turning circles.
    """
    best = np.inf
    kap = np.zeros(2)
    lens = np.zeros(2)
    for side in (1.0, -1.0):
        # centre of the turning circle on this side
        cx = x0 - side * radius * math.sin(th0)
        cy = y0 + side * radius * math.cos(th0)
        vx = x1 - cx
        vy = y1 - cy
        dist = math.hypot(vx, vy)
        if dist < radius:
            continue
        tangent = math.sqrt(max(dist * dist - radius * radius, 0.0))
        alpha = math.atan2(vy, vx)
        psi0 = th0 - side * 0.5 * math.pi  # robot's angle on the circle
        psi1 = alpha - side * math.atan2(tangent, radius)  # tangent point's angle
        sweep = mod2pi(side * (psi1 - psi0))
        if sweep > TWO_PI - 1e-9:
            sweep = 0.0
        total = radius * sweep + tangent
        if total < best:
            best = total
            kap[0] = side / radius
            kap[1] = 0.0
            lens[0] = radius * sweep
            lens[1] = tangent
    return best, kap, lens


# ---------------------------------------------------------------------------
# the 2-D grid distance used as heuristic and reachability test
# ---------------------------------------------------------------------------


@numba.njit(cache=True)
def grid_dijkstra(occ, gr, gc):
    """8-connected shortest distances (cell units, steps 1 and sqrt(2),
    corner cutting allowed) from every free cell to cell ``(gr, gc)``;
    ``inf`` for obstacle cells and cells that cannot reach it."""
    h, w = occ.shape
    n = h * w
    dist = np.full(n, np.inf)
    pos = np.full(n, -1, dtype=np.int64)
    hnode = np.empty(n, dtype=np.int64)
    hk1 = np.empty(n)
    hk2 = np.zeros(n)
    closed = np.zeros(n, dtype=np.bool_)
    if occ[gr, gc]:
        return dist.reshape(h, w)
    s = gr * w + gc
    dist[s] = 0.0
    size = heap_push(hnode, hk1, hk2, pos, ZERO, s, 0.0, 0.0)
    while size > 0:
        u, size = heap_pop(hnode, hk1, hk2, pos, size)
        closed[u] = True
        ur = u // w
        uc = u - ur * w
        du = dist[u]
        for k in range(8):
            if not can_step(occ, ur, uc, DR[k], DC[k], True):
                continue
            v = (ur + DR[k]) * w + uc + DC[k]
            if closed[v]:
                continue
            nd = du + STEP[k]
            if nd < dist[v]:
                if pos[v] >= 0:
                    dist[v] = nd
                    heap_decrease(hnode, hk1, hk2, pos, v, nd, 0.0)
                else:
                    dist[v] = nd
                    size = heap_push(hnode, hk1, hk2, pos, size, v, nd, 0.0)
    return dist.reshape(h, w)


@numba.njit(cache=True)
def center_blocked(occ, r):
    """Cells whose centre is not free for a disc of radius ``r``."""
    h, w = occ.shape
    out = np.zeros((h, w), dtype=np.bool_)
    for i in range(h):
        for j in range(w):
            out[i, j] = not disc_free(occ, float(j), float(i), r)
    return out
