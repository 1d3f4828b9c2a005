"""RRT and RRT* baselines: collision-free, seeded, RRT* no worse than RRT."""

import numpy as np
import pytest

from gapath import ConfigError, NoPathError, Workspace
from gapath.dynamic.scenarios import complex_maze
from gapath.planners.geometry import segment_free
from gapath.planners.rrt import rrt, rrt_star


@pytest.fixture(scope="module")
def ws():
    rng = np.random.default_rng(11)
    occ = rng.random((24, 24)) < 0.18
    occ[20:, :4] = False
    occ[:4, 20:] = False
    return Workspace(occ, (22, 1), (1, 22))


def swept_free(ws, pts, radius):
    return all(segment_free(ws.occ, a[0], a[1], b[0], b[1], radius, 0.01) for a, b in zip(pts[:-1], pts[1:]))


@pytest.mark.parametrize("star", [False, True])
def test_paths_are_collision_free_and_join_start_and_goal(ws, star):
    res = rrt(ws, seed=4, star=star, radius=0.3)
    P = res.points
    assert tuple(P[0]) == (1.0, 22.0) and tuple(P[-1]) == (22.0, 1.0)
    assert swept_free(ws, P, 0.3)
    assert res.length == pytest.approx(np.hypot(*np.diff(P, axis=0).T).sum())
    assert res.cost == res.length
    assert res.poses.shape == (len(P), 3)
    assert res.clearance >= 0.3
    assert 0 < res.first_solution <= res.iterations


def test_determinism(ws):
    a = rrt(ws, seed=9)
    b = rrt(ws, seed=9)
    c = rrt(ws, seed=10)
    assert np.array_equal(a.points, b.points)
    assert not np.array_equal(a.points, c.points)
    assert np.array_equal(rrt_star(ws, seed=9).points, rrt_star(ws, seed=9).points)


def test_rrt_star_is_no_worse_than_rrt_on_average(ws):
    plain = [rrt(ws, seed=s).cost for s in range(12)]
    star = [rrt_star(ws, seed=s).cost for s in range(12)]
    assert np.mean(star) <= np.mean(plain)
    # same samples until RRT stops: RRT* is never worse on the same seed
    assert all(b <= a + 1e-9 for a, b in zip(plain, star))


def test_maze_paths():
    maze = complex_maze(0)
    res = rrt_star(maze, seed=1, radius=0.3)
    assert swept_free(maze, res.points, 0.3)


def test_bad_inputs(ws):
    with pytest.raises(ConfigError):
        rrt(ws, goal_bias=1.5)
    with pytest.raises(ConfigError):
        rrt(ws, step=0)
    with pytest.raises(ConfigError):
        rrt(ws, max_iter=0)
    with pytest.raises(ConfigError):
        rrt(ws, radius=-1)
    with pytest.raises(ConfigError):
        rrt(ws, extra_iterations=-1, star=True)
    occ = np.zeros((10, 10), bool)
    occ[4, 4] = True
    w = Workspace(occ, (9, 0), (0, 9))
    with pytest.raises(ConfigError, match="start"):
        rrt(w, start=(4.0, 4.0))
    with pytest.raises(ConfigError, match="goal"):
        rrt(w, goal=(4.2, 3.9))
    with pytest.raises(ConfigError):
        rrt(w, start=(1.0,))


def test_unreachable_goal_raises_no_path():
    occ = np.zeros((10, 10), bool)
    occ[:, 5] = True
    with pytest.raises(NoPathError, match="RRT"):
        rrt(Workspace(occ, (5, 1), (5, 8)), max_iter=500)
