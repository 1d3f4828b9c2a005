"""Scenario generators: seeded maps, start-goal distances, dynamic obstacles."""

import math

import numpy as np
import pytest

from gapath import ConfigError, Workspace
from gapath.dynamic.scenarios import (
    SEED_DISTANCE,
    _grid_ratio,
    complex_maze,
    dynamic_obstacles,
    load_scenario_map,
    make_scenario,
    straight_line_distance,
    warehouse,
)
from gapath.planners.astar import astar


@pytest.mark.parametrize("seed", [0, 1, 7])
def test_maze_distance_detour_and_determinism(seed):
    ws = complex_maze(seed)
    assert 50.0 <= straight_line_distance(ws) <= 60.0
    assert abs(straight_line_distance(ws) - SEED_DISTANCE["maze"]) < 1.0
    assert _grid_ratio(ws.occ, ws.start, ws.goal) <= 1.20 + 1e-9
    assert ws.cell_size == 1.0
    assert np.array_equal(ws.occ, complex_maze(seed).occ)
    assert not ws.occ[ws.start] and not ws.occ[ws.goal]
    assert ws.occ.mean() > 0.1  # walls are left


def test_mazes_differ_by_seed():
    assert not np.array_equal(complex_maze(0).occ, complex_maze(1).occ)


@pytest.mark.parametrize("seed", [0, 3])
def test_warehouse_distance_and_package_goal(seed):
    ws = warehouse(seed)
    d = straight_line_distance(ws)
    assert 55.0 <= d <= 65.0 and abs(d - SEED_DISTANCE["warehouse"]) < 1.5
    r, c = ws.goal
    # the pick-up point touches a shelf
    assert any(ws.occ[r + dr, c] for dr in (-1, 1) if 0 <= r + dr < ws.shape[0])
    assert np.array_equal(ws.occ, warehouse(seed).occ)
    assert math.isfinite(_grid_ratio(ws.occ, ws.start, ws.goal))


def test_dynamic_obstacles_are_seeded_and_keep_the_goal_reachable():
    ws = complex_maze(0)
    st, mv, ref = dynamic_obstacles(ws, 5)
    st2, mv2, _ = dynamic_obstacles(ws, 5)
    assert len(st) == 3 and len(mv) == 4
    assert all(np.array_equal(a.cells, b.cells) and a.appear_at == b.appear_at for a, b in zip(st, st2))
    assert all(np.array_equal(a.position, b.position) for a, b in zip(mv, mv2))
    occ = ws.occ.copy()
    for o in st:
        assert not occ[o.cells[:, 0], o.cells[:, 1]].any()
        occ[o.cells[:, 0], o.cells[:, 1]] = True
    astar(Workspace(occ, ws.start, ws.goal, corner_cutting=False))  # still connected
    assert tuple(ref[0]) == (ws.start[1], ws.start[0])
    for o in mv:
        assert 0.3 <= o.speed <= 0.7 and o.mode == "bounce"


def test_make_scenario_from_a_map_file(tmp_path):
    rows = ["." * 30] * 20
    p = tmp_path / "open.txt"
    p.write_text("\n".join(rows) + "\n")
    ws = load_scenario_map(p, start=(18, 1), goal=(1, 28))
    assert ws.shape == (20, 30)
    sc = make_scenario(str(p), 2, start=(18, 1), goal=(1, 28), n_stationary=1, n_crossers=1, n_wanderers=1)
    assert sc.workspace.start == (18, 1)
    assert sc.direct_distance == pytest.approx(math.hypot(17, 27))
    assert len(sc.moving) == 2
    sc2 = make_scenario("maze", 0, start=(35, 1))
    assert sc2.workspace.start == (35, 1)


def test_bad_inputs():
    with pytest.raises(ConfigError):
        complex_maze(rows=1)
    with pytest.raises(ConfigError):
        complex_maze(corridor=0)
    with pytest.raises(ConfigError):
        complex_maze(max_detour=0.5)
    with pytest.raises(ConfigError):
        warehouse(missing=1.0)
    with pytest.raises(ConfigError):
        warehouse(height=8)
    ws = complex_maze(0)
    with pytest.raises(ConfigError):
        dynamic_obstacles(ws, speed_range=(0.0, 1.0))
    with pytest.raises(ConfigError):
        dynamic_obstacles(ws, n_stationary=-1)
    with pytest.raises(ConfigError):
        make_scenario("nowhere")
    occ = np.zeros((6, 6), bool)
    occ[:, 3] = True
    with pytest.raises(ConfigError, match="no path"):
        dynamic_obstacles(Workspace(occ, (5, 0), (0, 5)))
