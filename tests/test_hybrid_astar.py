"""Hybrid A* (NO-MOPP's planner): drivable, collision-free, deterministic."""

import math

import numpy as np
import pytest

from gapath import ConfigError, NoPathError, Workspace
from gapath.dynamic.scenarios import complex_maze
from gapath.planners.geometry import (
    arc_point,
    disc_free,
    dubins,
    sample_arcs,
    segment_free,
    turn_to_point,
)
from gapath.planners.hybrid_astar import (
    CarModel,
    HybridAStar,
    cell_pose,
    hybrid_astar,
    path_objectives,
    pose_cell,
)


@pytest.fixture(scope="module")
def wall_ws():
    occ = np.zeros((14, 24), bool)
    occ[4:14, 11] = True  # a wall from the bottom, open at the top
    occ[0:2, 17] = True
    return Workspace(occ, (11, 3), (11, 20))


@pytest.fixture(scope="module")
def maze_ws():
    return complex_maze(0)


def swept_free(ws, poses, radius):
    """The disc of ``radius`` swept along every segment (fine samples)."""
    occ = ws.occ
    cs = ws.cell_size
    return all(
        segment_free(occ, a[0] / cs, a[1] / cs, b[0] / cs, b[1] / cs, radius / cs, 0.01)
        for a, b in zip(poses[:-1], poses[1:])
    )


def max_curvature(poses):
    """Largest curvature between consecutive poses, exact for arcs:
    chord = 2 R sin(dtheta / 2)."""
    d = np.hypot(*np.diff(poses[:, :2], axis=0).T)
    dth = np.abs(np.diff(poses[:, 2]))
    ok = d > 1e-12
    return float(np.max(2 * np.sin(dth[ok] / 2) / d[ok]))


@pytest.mark.parametrize("which", ["wall", "maze"])
def test_paths_are_collision_free_drivable_and_reach_the_goal(which, wall_ws, maze_ws):
    ws = wall_ws if which == "wall" else maze_ws
    planner = HybridAStar(ws)
    res = planner.plan()
    P = res.poses
    assert swept_free(ws, P, planner.car.radius)
    assert max_curvature(P) <= planner.car.max_curvature * (1 + 1e-6)
    # headings are continuous (no jumps larger than one sample's turn)
    assert np.all(np.abs(np.diff(P[:, 2])) <= planner.car.max_curvature * planner.ds * (1 + 1e-6))
    gx, gy = ws.goal[1] * ws.cell_size, ws.goal[0] * ws.cell_size
    assert math.hypot(P[-1, 0] - gx, P[-1, 1] - gy) <= planner.goal_tolerance + 1e-9
    assert res.reached in ("shot", "tolerance")
    # objectives
    assert res.length == pytest.approx(np.hypot(*np.diff(P[:, :2], axis=0).T).sum())
    assert res.length >= math.hypot(P[0, 0] - gx, P[0, 1] - gy) - 1e-9
    assert res.clearance >= planner.car.radius
    assert res.turning >= 0
    assert res.objectives == {"length": res.length, "turning": res.turning, "clearance": res.clearance}


def test_goal_pose_is_reached_with_its_heading(wall_ws):
    planner = HybridAStar(wall_ws)
    goal = (20.0, 6.0, math.pi / 2)
    res = planner.plan((3.0, 11.0, -math.pi / 2), goal)
    x, y, th = res.poses[-1]
    assert math.hypot(x - 20, y - 6) <= planner.goal_tolerance + 1e-9
    assert abs((th - math.pi / 2 + math.pi) % (2 * math.pi) - math.pi) <= planner.heading_tolerance + 1e-9
    assert max_curvature(res.poses) <= planner.car.max_curvature * (1 + 1e-6)
    assert swept_free(wall_ws, res.poses, planner.car.radius)


def test_world_frame_and_helpers():
    assert cell_pose((3, 5), 0.5, 2.0) == (10.0, 6.0, 0.5)
    assert pose_cell((10.2, 5.8, 0), 2.0) == (3, 5)
    car = CarModel(wheelbase=1.0, max_steer=math.pi / 4)
    assert car.min_turning_radius == pytest.approx(1.0)
    assert car.steering_angles().tolist() == pytest.approx(
        [math.pi / 4, math.pi / 8, 0.0, -math.pi / 8, -math.pi / 4]
    )


def test_determinism(maze_ws):
    a = HybridAStar(maze_ws).plan()
    b = HybridAStar(maze_ws).plan()
    c = hybrid_astar(maze_ws)
    assert np.array_equal(a.poses, b.poses) and np.array_equal(a.poses, c.poses)
    assert a.expansions == b.expansions


def test_reuse_after_map_update(wall_ws):
    planner = HybridAStar(wall_ws)
    first = planner.plan()
    # block the top opening of the wall, then reopen it
    assert planner.update_cells([(r, 11) for r in range(0, 4)], True) == 4
    with pytest.raises(NoPathError):
        planner.plan()
    planner.update_cells([(r, 11) for r in range(0, 4)], False)
    again = planner.plan()
    assert np.array_equal(first.poses, again.poses)


def test_cost_layer_and_blocked_overlay(wall_ws):
    planner = HybridAStar(wall_ws)
    base = planner.plan()
    rows = np.unique(np.round(base.poses[:, 1]).astype(int))
    # an expensive band on the straight route pushes the path elsewhere or
    # makes it cost more, never cheaper
    cost = np.zeros(wall_ws.shape)
    cost[:, 13:16] = 5.0
    costly = planner.plan(cost=cost)
    assert costly.cost >= base.cost - 1e-9
    # blocking the cells the path uses forces a different path
    blocked = np.zeros(wall_ws.shape, bool)
    cells = base.cells()
    mid = cells[len(cells) // 2]
    blocked[mid[0], mid[1]] = True
    other = planner.plan(blocked=blocked)
    assert not any((c == mid).all() for c in other.cells())
    assert len(rows) > 0


def test_max_length_prunes(wall_ws):
    planner = HybridAStar(wall_ws)
    res = planner.plan()
    with pytest.raises(NoPathError):
        planner.plan(max_length=0.5 * res.length)
    assert planner.plan(max_length=res.length * 1.5).length == pytest.approx(res.length)


def test_unreachable_goal_raises_no_path():
    occ = np.zeros((10, 10), bool)
    occ[:, 5] = True
    with pytest.raises(NoPathError, match="not connected"):
        hybrid_astar(Workspace(occ, (5, 1), (5, 8)))
    # connected cells but too narrow for the car's disc
    occ = np.zeros((10, 12), bool)
    occ[:, 6] = True
    occ[5, 6] = False
    occ[4, 5:8] = True
    occ[6, 5:8] = True
    with pytest.raises(NoPathError):
        hybrid_astar(Workspace(occ, (5, 1), (5, 10)), car=CarModel(radius=0.45))


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(wheelbase=0),
        dict(wheelbase=-1),
        dict(speed=0),
        dict(speed=-2),
        dict(max_steer=math.pi / 2),
        dict(max_steer=math.radians(95)),
        dict(max_steer=0),
        dict(max_steer=float("nan")),
        dict(radius=-0.1),
    ],
)
def test_bad_car_raises_config_error(kwargs):
    with pytest.raises(ConfigError):
        CarModel(**kwargs)


def test_bad_settings_raise_config_error(wall_ws):
    with pytest.raises(ConfigError, match="arc_length"):
        HybridAStar(wall_ws, arc_length=math.sqrt(2))
    with pytest.raises(ConfigError):
        HybridAStar(wall_ws, heading_bins=2)
    with pytest.raises(ConfigError):
        HybridAStar(wall_ws, heuristic="manhattan")
    with pytest.raises(ConfigError):
        HybridAStar(wall_ws, heuristic_weight=0)
    with pytest.raises(ConfigError):
        HybridAStar(wall_ws, car="car")
    planner = HybridAStar(wall_ws)
    with pytest.raises(ConfigError, match="start cell ROW,COL 8,11 heading 0 deg is in collision"):
        planner.plan((11.0, 8.0, 0.0))  # inside the wall
    with pytest.raises(ConfigError, match="goal"):
        planner.plan(None, (11.0, 8.0))
    with pytest.raises(ConfigError):
        planner.plan((1.0, 2.0))  # not a pose
    with pytest.raises(ConfigError):
        planner.plan(cost=-np.ones(wall_ws.shape))
    with pytest.raises(ConfigError):
        planner.plan(blocked=np.zeros((3, 3), bool))
    with pytest.raises(ConfigError):
        planner.update_cells([(99, 0)])


# ---------------------------------------------------------------------------
# analytic shots
# ---------------------------------------------------------------------------


def _end(x, y, th, kk, ll):
    for k, length in zip(kk, ll):
        x, y, th = arc_point(x, y, th, k, length)
    return x, y, th


def test_dubins_ends_at_the_goal_pose_and_is_no_longer_than_alternatives():
    rng = np.random.default_rng(3)
    for _ in range(200):
        a = rng.uniform(-5, 5, 3)
        b = rng.uniform(-5, 5, 3)
        R = rng.uniform(0.5, 2.0)
        length, kk, ll = dubins(*a, *b, R)
        assert np.isfinite(length)
        x, y, th = _end(*a, kk, ll)
        assert math.hypot(x - b[0], y - b[1]) < 1e-6
        assert abs((th - b[2] + math.pi) % (2 * math.pi) - math.pi) < 1e-6
        assert length == pytest.approx(ll.sum())
        assert np.all(np.abs(kk) <= 1 / R + 1e-12)
        # never shorter than the straight line
        assert length >= math.hypot(*(b[:2] - a[:2])) - 1e-9
    # straight ahead: the segment itself
    length, kk, ll = dubins(0.0, 0.0, 0.0, 7.0, 0.0, 0.0, 1.0)
    assert length == pytest.approx(7.0)


def test_turn_to_point_hand_cases():
    # straight ahead
    length, kk, ll = turn_to_point(0.0, 0.0, 0.0, 5.0, 0.0, 1.0)
    assert length == pytest.approx(5.0) and ll[0] == pytest.approx(0.0)
    # a point 2R to the left (theta grows towards +y): half a circle
    length, kk, ll = turn_to_point(0.0, 0.0, 0.0, 0.0, 2.0, 1.0)
    assert length == pytest.approx(math.pi)
    # end point of a random case lies on the target
    rng = np.random.default_rng(5)
    for _ in range(100):
        p = rng.uniform(-5, 5, 3)
        q = rng.uniform(-5, 5, 2)
        length, kk, ll = turn_to_point(*p, *q, 0.8)
        if not np.isfinite(length):
            continue
        x, y, _ = _end(*p, kk, ll)
        assert math.hypot(x - q[0], y - q[1]) < 1e-6


def test_sample_arcs_spacing_and_disc_check():
    pts = sample_arcs(0.0, 0.0, 0.0, np.array([1.0, 0.0]), np.array([math.pi / 2, 2.0]), 0.1)
    d = np.hypot(*np.diff(pts[:, :2], axis=0).T)
    assert d.max() <= 0.1 + 1e-12
    assert pts[-1, 2] == pytest.approx(math.pi / 2)
    occ = np.zeros((5, 5), bool)
    occ[2, 2] = True
    assert not disc_free(occ, 2.0, 2.0, 0.0)
    assert disc_free(occ, 1.0, 1.0, 0.7)  # corner of the square at distance 0.707
    assert not disc_free(occ, 1.0, 1.0, 0.71)
    assert disc_free(occ, 1.0, 2.0, 0.49) and not disc_free(occ, 1.0, 2.0, 0.5)
    assert not disc_free(occ, -0.4, 0.0, 0.2)  # leaves the map


def test_path_objectives_of_a_polyline():
    occ = np.zeros((5, 5), bool)
    obj = path_objectives(np.array([[0, 0], [2, 0], [2, 2]], float), occ)
    assert obj["length"] == pytest.approx(4.0)
    assert obj["turning"] == pytest.approx(math.pi / 2)
    assert obj["clearance"] == pytest.approx(0.5)  # the map edge
