"""Tests of gapath.planners.dstar_lite.DStarLite.

Seeded random sequences of blocking/unblocking cells on random 20x20..40x40
grids, with and without robot moves: after every change the replanned cost
equals a fresh A* on the changed map, the path is valid, and over each
sequence set the replans expand fewer cells than the fresh searches.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from data_files import data_path

from gapath import ConfigError, NoPathError, Workspace
from gapath.planners.astar import astar
from gapath.planners.dstar_lite import DStarLite

SQRT2 = math.sqrt(2.0)


def assert_valid_path(res, occ, start, goal, corner_cutting, cell_size=1.0):
    path = res.path
    assert path.ndim == 2 and path.shape[1] == 2 and np.issubdtype(path.dtype, np.integer)
    assert tuple(path[0]) == tuple(start) and tuple(path[-1]) == tuple(goal)
    assert not occ[path[:, 0], path[:, 1]].any(), "path crosses an obstacle"
    steps = np.diff(path, axis=0)
    if len(steps):
        assert (np.abs(steps).max(axis=1) == 1).all(), "consecutive cells must be 8-adjacent"
    n_diag = 0
    for (r, c), (dr, dc) in zip(path[:-1], steps):
        if dr and dc:
            n_diag += 1
            if not corner_cutting:
                assert not occ[r + dr, c] and not occ[r, c + dc], "diagonal cuts a corner"
    length = (len(steps) - n_diag + SQRT2 * n_diag) * cell_size
    assert res.length == length and res.cost == length


def random_planner(rng, corner_cutting):
    h, w = (int(v) for v in rng.integers(20, 41, size=2))
    occ = rng.random((h, w)) < rng.uniform(0.1, 0.3)
    free = np.argwhere(~occ)
    i, j = rng.choice(len(free), size=2, replace=False)
    ws = Workspace(occ, tuple(free[i]), tuple(free[j]), corner_cutting=corner_cutting)
    return DStarLite(ws)


def random_changes(rng, planner, path):
    """A few cells to block or unblock: half of the time cells of the
    current path (forcing a detour), otherwise anywhere."""
    h, w = planner.occ.shape
    if path is not None and len(path) > 2 and rng.random() < 0.5:
        inner = path[1:-1]
        cells = inner[rng.choice(len(inner), size=min(len(inner), int(rng.integers(1, 4))), replace=False)]
        blocked = np.ones(len(cells), bool)
    else:
        k = int(rng.integers(1, 6))
        cells = np.column_stack([rng.integers(0, h, k), rng.integers(0, w, k)])
        blocked = rng.random(k) < 0.5
    keep = np.array([tuple(c) not in (planner.start, planner.goal) for c in cells], bool)
    return cells[keep], blocked[keep]


@pytest.mark.parametrize("corner_cutting", [False, True])
@pytest.mark.parametrize("moves", [False, True], ids=["static", "moving"])
def test_replan_matches_fresh_astar(corner_cutting, moves):
    rng = np.random.default_rng(2024 + 2 * corner_cutting + moves)
    replan_expansions = fresh_expansions = 0
    n_checked = n_unreachable = 0
    for _ in range(8):
        planner = random_planner(rng, corner_cutting)
        try:
            path = planner.plan().path
        except NoPathError:
            path = None
        for _ in range(25):
            cells, blocked = random_changes(rng, planner, path)
            planner.update_cells(cells, blocked)
            ws = planner.workspace
            try:
                fresh = astar(ws)
            except NoPathError:
                fresh = None
            try:
                res = planner.replan()
            except NoPathError:
                assert fresh is None, "D* Lite found no path but A* did"
                n_unreachable += 1
                path = None
                continue
            assert fresh is not None, "A* found no path but D* Lite did"
            assert res.cost == pytest.approx(fresh.cost, rel=1e-12)
            assert_valid_path(res, ws.occ, planner.start, planner.goal, corner_cutting)
            replan_expansions += res.expansions
            fresh_expansions += fresh.expansions
            n_checked += 1
            path = res.path
            if moves and len(path) > 2:
                planner.move_to(tuple(path[1]))
                path = path[1:]
    assert n_checked > 60
    assert replan_expansions < fresh_expansions, (replan_expansions, fresh_expansions)


def test_movingai_map_with_blocked_path_cells():
    """den312d (65x81): a scenario's path is cut again and again."""
    try:
        from gapath.loaders import load_movingai, load_scenarios
    except ImportError:  # pragma: no cover - before gapath.loaders existed
        pytest.skip("gapath.loaders not available")
    scen = load_scenarios(data_path("movingai/mapf/den312d-random-1.scen"))[-1]
    ws = load_movingai(scen.resolve_map(), scen.start, scen.goal, corner_cutting=False)
    planner = DStarLite(ws)
    res = planner.plan()
    assert res.cost == pytest.approx(scen.optimal, abs=1e-7)
    rng = np.random.default_rng(0)
    replan_expansions = fresh_expansions = 0
    for _ in range(12):
        inner = res.path[1:-1]
        cell = tuple(int(v) for v in inner[rng.integers(len(inner))])
        planner.update_cells([cell], blocked=True)
        fresh = astar(planner.workspace)
        res = planner.replan()
        assert res.cost == fresh.cost
        assert_valid_path(res, planner.occ, planner.start, planner.goal, False)
        replan_expansions += res.expansions
        fresh_expansions += fresh.expansions
    assert replan_expansions < fresh_expansions


def test_robot_walks_to_the_goal_while_the_map_changes():
    rng = np.random.default_rng(99)
    occ = rng.random((30, 30)) < 0.2
    occ[-1, 0] = occ[0, -1] = False
    planner = DStarLite(Workspace(occ, corner_cutting=False))
    try:
        res = planner.plan()
    except NoPathError:  # pragma: no cover - seed dependent
        pytest.skip("unreachable sample")
    steps = 0
    while planner.start != planner.goal and steps < 200:
        nxt = tuple(int(v) for v in res.path[1])
        # a new obstacle appears two cells ahead (if any), as a sensor would see it
        if len(res.path) > 3:
            ahead = tuple(int(v) for v in res.path[3])
            if ahead != planner.goal:
                planner.update_cells([ahead], blocked=True)
        planner.move_to(nxt)
        try:
            res = planner.replan()
        except NoPathError:
            with pytest.raises(NoPathError):
                astar(planner.workspace)
            return
        if planner.start != planner.goal:
            assert res.cost == astar(planner.workspace).cost
        steps += 1
    assert planner.start == planner.goal
    assert res.path.tolist() == [list(planner.goal)] and res.cost == 0.0


def test_plan_equals_astar_on_random_grids():
    rng = np.random.default_rng(7)
    for corner_cutting in (False, True):
        for _ in range(10):
            planner = random_planner(rng, corner_cutting)
            ws = planner.workspace
            try:
                fresh = astar(ws)
            except NoPathError:
                with pytest.raises(NoPathError):
                    planner.plan()
                continue
            res = planner.plan()
            assert res.cost == fresh.cost
            assert_valid_path(res, ws.occ, ws.start, ws.goal, corner_cutting)


def test_unreachable_then_reconnected():
    occ = np.zeros((6, 6), bool)
    planner = DStarLite(Workspace(occ))
    assert planner.plan().cost == pytest.approx(5 * SQRT2)
    wall = [(r, 3) for r in range(6)]
    assert planner.update_cells(wall, blocked=True) == 6
    with pytest.raises(NoPathError, match="no path"):
        planner.replan()
    assert planner.update_cells([(2, 3)], blocked=False) == 1
    res = planner.replan()
    assert res.cost == astar(planner.workspace).cost
    assert_valid_path(res, planner.occ, planner.start, planner.goal, True)


def test_replan_without_plan_and_changes_before_plan():
    occ = np.zeros((5, 5), bool)
    planner = DStarLite(Workspace(occ))
    planner.update_cells([(1, 1), (2, 2), (3, 3)], blocked=True)
    res = planner.replan()  # plans from scratch
    assert res.cost == astar(planner.workspace).cost
    res2 = planner.replan()  # nothing changed: no work
    assert res2.expansions == 0 and np.array_equal(res2.path, res.path)


def test_update_cells_forms_and_counts():
    planner = DStarLite(Workspace(np.zeros((5, 5), bool)))
    planner.plan()
    assert planner.update_cells((2, 2)) == 1  # one cell, default blocked
    assert planner.update_cells([(2, 2)], blocked=True) == 0  # no change
    assert planner.update_cells(np.array([[2, 2], [1, 3]]), blocked=[False, True]) == 2
    assert planner.occ[1, 3] and not planner.occ[2, 2]
    with pytest.raises(ValueError):
        planner.occ[0, 0] = True  # read-only view
    assert planner.replan().cost == astar(planner.workspace).cost


def test_cell_size_and_corner_rule_carried_over():
    occ = np.array([[0, 0, 0], [0, 1, 0], [0, 0, 0]], bool)
    ws = Workspace(occ, (2, 0), (0, 2), cell_size=2.0, corner_cutting=False)
    planner = DStarLite(ws)
    res = planner.plan()
    assert res.cost == astar(ws).cost == 8.0
    assert planner.workspace == ws


def test_deterministic():
    def run():
        rng = np.random.default_rng(5)
        planner = random_planner(rng, False)
        out = []
        path = None
        for _ in range(10):
            cells, blocked = random_changes(rng, planner, path)
            planner.update_cells(cells, blocked)
            try:
                res = planner.replan()
            except NoPathError:
                out.append(None)
                path = None
                continue
            out.append((res.path.tolist(), res.cost, res.expansions))
            path = res.path
        return out

    assert run() == run()


@pytest.fixture
def planner():
    occ = np.zeros((4, 5), bool)
    occ[1, 1] = True
    return DStarLite(Workspace(occ))


def test_errors(planner):
    with pytest.raises(ConfigError, match=r"start \(1, 1\) is on an obstacle"):
        DStarLite(planner.workspace, start=(1, 1))
    with pytest.raises(ConfigError, match=r"goal \(9, 9\) is outside the 4x5 grid"):
        DStarLite(planner.workspace, goal=(9, 9))
    with pytest.raises(ConfigError, match=r"cannot block the robot's cell \(start\) \(3, 0\)"):
        planner.update_cells([(3, 0)], blocked=True)
    with pytest.raises(ConfigError, match=r"cannot block the goal \(0, 4\)"):
        planner.update_cells([(0, 4)], blocked=True)
    with pytest.raises(ConfigError, match=r"cell \(4, 0\) is outside the 4x5 grid"):
        planner.update_cells([(4, 0)], blocked=False)
    with pytest.raises(ConfigError, match=r"blocked must be one bool or one per cell \(2\)"):
        planner.update_cells([(0, 0), (0, 1)], blocked=[True, False, True])
    with pytest.raises(ConfigError, match=r"cells must be \(row, col\) pairs"):
        planner.update_cells([(0.5, 1)])
    with pytest.raises(ConfigError, match=r"cells must be \(row, col\) pairs"):
        planner.update_cells("a cell")
    with pytest.raises(ConfigError, match=r"cell \(1, 1\) is on an obstacle"):
        planner.move_to((1, 1))
    with pytest.raises(ConfigError, match=r"cell \(-1, 0\) is outside"):
        planner.move_to((-1, 0))
    # unblocking the start or goal (already free) is fine
    assert planner.update_cells([(3, 0), (0, 4)], blocked=False) == 0
    assert "DStarLite(" in repr(planner)
