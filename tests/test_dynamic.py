"""The dynamic-environment simulation: prediction, replanning, halting, reasons."""

import argparse
import json
import math

import numpy as np
import pytest

from gapath import ConfigError, Workspace
from gapath.cli import main
from gapath.dynamic import (
    PLANNERS,
    MovingObstacle,
    Robot,
    SimSettings,
    Simulation,
    StationaryObstacle,
    closest_approach,
    crossing_point,
    make_planner,
    path_contact,
    simulate,
    time_to_collision,
)
from gapath.planners.geometry import disc_free
from gapath.planners.hybrid_astar import CarModel


@pytest.fixture(scope="module")
def open_ws():
    return Workspace(np.zeros((15, 30), bool), (7, 1), (7, 28))


def crosser():
    """Crosses the straight start-goal line at x = 15 when the robot gets there."""
    return MovingObstacle((15.0, 0.5), (0.0, 0.5))


def events(res, *kinds):
    return [e for e in res.events if e["kind"] in kinds]


# ---------------------------------------------------------------------------
# motion equations, hand-computed
# ---------------------------------------------------------------------------


def test_time_to_collision_hand_cases():
    # head-on, closing at 2 m/s from 10 m, radii summing to 1: (10 - 1) / 2
    assert time_to_collision((0, 0), (1, 0), (10, 0), (-1, 0), 1.0) == pytest.approx(4.5)
    # perpendicular tracks meeting at (5, 0) at t = 5: |d(t)| = sqrt(2) |5 - t| = 1
    assert time_to_collision((0, 0), (1, 0), (5, -5), (0, 1), 1.0) == pytest.approx(5 - 1 / math.sqrt(2))
    # same velocity, or moving apart: never
    assert time_to_collision((0, 0), (1, 0), (3, 0), (1, 0), 1.0) == math.inf
    assert time_to_collision((0, 0), (-1, 0), (3, 0), (1, 0), 1.0) == math.inf
    # passing 2 m apart with radii 1: never
    assert time_to_collision((0, 0), (1, 0), (10, 2), (-1, 0), 1.0) == math.inf
    # already touching
    assert time_to_collision((0, 0), (0, 0), (0.5, 0), (0, 0), 1.0) == 0.0


def test_closest_approach_and_crossing_point():
    assert closest_approach((0, 0), (1, 0), (5, 5), (0, -1)) == (5.0, 0.0)
    t, d = closest_approach((0, 0), (1, 0), (10, 3), (-1, 0))
    assert t == pytest.approx(5.0) and d == pytest.approx(3.0)
    # receding: the closest approach is now
    assert closest_approach((0, 0), (-1, 0), (3, 4), (1, 0)) == (0.0, 5.0)
    point, t_r, t_o = crossing_point((0, 0), (2, 0), (6, -6), (0, 1))
    assert np.allclose(point, (6, 0)) and t_r == pytest.approx(3) and t_o == pytest.approx(6)
    assert crossing_point((0, 0), (1, 0), (0, 1), (1, 0)) is None  # parallel
    assert crossing_point((0, 0), (1, 0), (-5, -5), (0, -1)) is None  # behind both


def test_path_contact_hand_cases():
    path = [(0, 0), (10, 0)]
    # static obstacle 0.5 beside the path: |x - 5|^2 + 0.25 = 1
    t, _ = path_contact(path, 0.0, 1.0, 20.0, (5, 0.5), (0, 0), 1.0)
    assert t == pytest.approx(5 - math.sqrt(0.75))
    # L-shaped path: the robot turns at (5, 0) (t = 5) and meets an obstacle
    # waiting at (5, 4) when 1 away: at t = 5 + 3
    t, _ = path_contact([(0, 0), (5, 0), (5, 10)], 0.0, 1.0, 20.0, (5, 4), (0, 0), 1.0)
    assert t == pytest.approx(8.0)
    # backing off from s0 = 5 towards the start, away from an obstacle behind
    t, dmin = path_contact(path, 5.0, -1.0, 3.0, (8, 0), (0, 0), 1.0)
    assert t == math.inf and dmin == pytest.approx(3.0)
    # standing still at the end of the path, an obstacle comes from ahead
    t, _ = path_contact(path, 10.0, 1.0, 20.0, (15, 0), (-1, 0), 1.0)
    assert t == pytest.approx(4.0)
    # beyond the horizon
    assert path_contact(path, 0.0, 1.0, 3.0, (5, 0.5), (0, 0), 1.0)[0] == math.inf


# ---------------------------------------------------------------------------
# simulations
# ---------------------------------------------------------------------------


def test_moving_obstacle_crossing_the_path_replans_and_succeeds(open_ws):
    res = simulate(open_ws, "hybrid-astar", moving=[crosser()])
    assert res.success and res.reason == "goal"
    assert events(res, "predict")
    adopted = [e for e in events(res, "replan") if e.get("adopted")]
    assert adopted and adopted[0]["reason"] == "moving-0"
    assert res.n_replans >= 1 and res.total_plan_seconds >= res.global_plan_seconds
    # the driven trajectory kept clear of the obstacle
    tr, ob = res.trajectory, res.obstacles[:, 0]
    gaps = np.hypot(tr[:, 1] - ob[:, 0], tr[:, 2] - ob[:, 1]) - 0.3 - 0.4
    assert gaps.min() > 0
    assert res.path_length >= res.direct_distance - 1e-9


def test_halts_when_the_obstacle_is_too_close(open_ws):
    # threshold so large that every predicted collision is handled by halting
    res = simulate(open_ws, "hybrid-astar", moving=[crosser()], settings=SimSettings(replan_distance=100.0))
    assert res.success
    assert events(res, "halt") and not events(res, "replan")
    assert (res.trajectory[:, 4] == 0).sum() >= 3  # it stood still
    # a short sensor: the obstacle is first seen inside the threshold
    res = simulate(open_ws, "astar", Robot(sensor_range=2.0), moving=[crosser()])
    assert res.success and events(res, "halt")
    first = events(res, "predict")[0]
    assert first["gap"] < SimSettings().replan_distance


def test_backs_off_when_waiting_would_be_hit():
    # a corridor; the obstacle comes head-on, the robot must retreat
    occ = np.ones((5, 40), bool)
    occ[1:4, :] = False
    occ[1:4, 20:23] = True
    occ[1, 20:23] = False  # a one-cell bypass the car cannot use quickly
    ws = Workspace(occ, (2, 1), (2, 38))
    mover = MovingObstacle((17.0, 2.0), (-0.4, 0.0), radius=0.4)
    res = simulate(ws, "astar", moving=[mover], settings=SimSettings(max_time=30.0))
    assert events(res, "back-off")
    assert res.reason != "collision"


def test_stationary_obstacle_is_sensed_and_avoided(open_ws):
    block = StationaryObstacle([(7, 14), (6, 14), (8, 14)], appear_at=0.0)
    for name in ("hybrid-astar", "rrt", "astar", "dstar-lite"):
        res = simulate(open_ws, name, stationary=[block], seed=3)
        assert res.success, (name, res.reason)
        assert events(res, "detect") and events(res, "replan")
        occ = open_ws.occ.copy()
        occ[[7, 6, 8], 14] = True
        assert all(disc_free(occ, x, y, 0.3) for x, y in res.trajectory[:, 1:3])


@pytest.mark.parametrize("name", list(PLANNERS))
def test_every_planner_runs_in_the_simulation(open_ws, name):
    res = simulate(open_ws, name, stationary=[StationaryObstacle([(7, 10)], 0.0)], moving=[crosser()], seed=2)
    assert res.success, res.reason
    assert res.planner == name
    assert res.global_plan_seconds > 0


def test_determinism(open_ws):
    a = simulate(open_ws, "rrt", moving=[crosser()], seed=5)
    b = simulate(open_ws, "rrt", moving=[crosser()], seed=5)
    assert np.array_equal(a.trajectory[:, 1:], b.trajectory[:, 1:])
    assert [e["kind"] for e in a.events] == [e["kind"] for e in b.events]


def test_failed_runs_report_their_reason(open_ws):
    wall = StationaryObstacle([(r, 15) for r in range(15)], appear_at=0.0)
    res = simulate(open_ws, "hybrid-astar", stationary=[wall], settings=SimSettings(blocked_patience=2.0))
    assert not res.success and res.reason == "blocked"
    res = simulate(open_ws, "astar", settings=SimSettings(max_time=5.0))
    assert not res.success and res.reason == "timeout"
    blind = Robot(sensor_range=0.0)
    head_on = MovingObstacle((12.0, 7.0), (-1.0, 0.0))
    res = simulate(open_ws, "astar", blind, moving=[head_on])
    assert not res.success and res.reason == "collision"
    assert events(res, "collision")[0]["obstacle"] == "moving-0"
    # a goal the known map cannot reach: failed at once, no exception
    occ = np.zeros((10, 10), bool)
    occ[:, 5] = True
    res = simulate(Workspace(occ, (5, 1), (5, 8)), "hybrid-astar")
    assert not res.success and res.reason == "blocked" and res.time == 0.0
    data = json.loads(json.dumps(res.to_json()))
    assert data["reason"] == "blocked"


def test_bad_inputs(open_ws):
    with pytest.raises(ConfigError, match="sensor_range"):
        Robot(sensor_range=-1.0)
    with pytest.raises(ConfigError, match="fov"):
        Robot(fov=0)
    with pytest.raises(ConfigError, match="fov"):
        Robot(fov=190)
    with pytest.raises(ConfigError):
        Robot(car=CarModel(speed=0))
    with pytest.raises(ConfigError):
        Robot(car=CarModel(max_steer=math.radians(90)))
    with pytest.raises(ConfigError):
        SimSettings(dt=0)
    with pytest.raises(ConfigError):
        SimSettings(horizon=-1)
    with pytest.raises(ConfigError):
        MovingObstacle((0, 0), (1, 0), mode="teleport")
    with pytest.raises(ConfigError):
        MovingObstacle((0, 0), (1, 0), radius=0)
    with pytest.raises(ConfigError):
        StationaryObstacle([], 0.0)
    with pytest.raises(ConfigError):
        StationaryObstacle([(1, 1)], -1.0)
    with pytest.raises(ConfigError, match="unknown planner"):
        make_planner("dijkstra")
    with pytest.raises(ConfigError):
        Simulation(open_ws, "astar", stationary=[StationaryObstacle([(99, 1)])])


# ---------------------------------------------------------------------------
# the study, pictures and the CLI
# ---------------------------------------------------------------------------


def test_experiment_tables_and_outputs(tmp_path):
    from gapath.studies.dynamic import run, write_outputs

    study = run(2, scenarios=("maze",), planners=("astar", "hybrid-astar"))
    assert [r["planner"] for r in study.table] == ["astar", "hybrid-astar"]
    row = study.table[1]
    assert row["runs"] == 2 and 0 <= row["success_pct"] <= 100
    assert row["direct_distance"] == pytest.approx(51.66, abs=0.01)
    md = study.to_markdown()
    assert "NO-MOPP after local replanning" in md and "67.84" in md
    files = write_outputs(study, tmp_path, gif=False)
    names = {f.name for f in files}
    assert {"dynamic.md", "dynamic.csv", "dynamic.jsonl", "dynamic_paths.png"} <= names
    lines = (tmp_path / "dynamic.jsonl").read_text().splitlines()
    assert json.loads(lines[0])["benchmark"] == "dynamic_study"


def test_animation_is_small(open_ws, tmp_path):
    from gapath.dynamic.plots import animate_run

    res = simulate(open_ws, "hybrid-astar", moving=[crosser()])
    n = animate_run(open_ws, res, (), tmp_path / "run.gif", every=2.0)
    assert n >= 5
    assert 0 < (tmp_path / "run.gif").stat().st_size < 2_000_000


@pytest.fixture
def text_map(tmp_path):
    p = tmp_path / "room.txt"
    p.write_text("\n".join(["." * 24] * 12) + "\n")
    return p


def test_cli_simulate(text_map, tmp_path, capsys):
    out = tmp_path / "sim"
    code = main(
        [
            "simulate",
            str(text_map),
            "--planner",
            "astar",
            "--obstacles",
            "1",
            "--stationary",
            "1",
            "--seed",
            "3",
            "--out",
            str(out),
        ]
    )
    assert code == 0
    for name in ("trajectory.json", "summary.json", "run.png"):
        assert (out / name).stat().st_size > 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["success"] and summary["settings"]["planner"] == "astar"
    assert "reached the goal" in capsys.readouterr().out
    # a failed run exits with 1, bad input with 2
    assert main(["simulate", str(text_map), "--max-time", "1", "--quiet", "--out", str(out)]) == 1
    assert json.loads((out / "summary.json").read_text())["reason"] == "timeout"
    assert main(["simulate", str(text_map), "--fov", "0", "--out", str(out)]) == 2
    assert main(["simulate", str(text_map), "--max-steer", "90", "--out", str(out)]) == 2


def test_plan_helpers_for_gapath_plan(tmp_path):
    from gapath.cli.simulate import add_planner_choices, plan_with, write_plan

    parser = argparse.ArgumentParser()
    parser.add_argument("--seed", type=int, default=7)  # already there: kept
    names = add_planner_choices(parser)
    assert names == ("hybrid-astar", "rrt", "rrt-star")
    args = parser.parse_args([])
    assert args.seed == 7 and args.wheelbase == 0.6
    ws = Workspace(np.zeros((12, 20), bool), (10, 1), (1, 18))
    for name in names:
        out = plan_with(name, ws, args)
        assert out.poses.shape[1] == 3 and out.objectives["length"] > 0
        assert tuple(out.cells[0]) == ws.start and tuple(out.cells[-1]) == ws.goal
    files = write_plan(out, ws, tmp_path)
    rec = json.loads((tmp_path / "paths.json").read_text())
    assert rec[0]["path"][0] == list(ws.start) and len(rec[0]["poses"][0]) == 3
    assert (tmp_path / "paths.png") in files
    assert (tmp_path / "front.csv").read_text().splitlines()[0] == "length,turning,clearance"
    with pytest.raises(ConfigError):
        plan_with("astar", ws, args)
    with pytest.raises(ConfigError):
        plan_with("hybrid-astar", ws, argparse.Namespace(max_steer=90.0))
    with pytest.raises(ConfigError):
        plan_with("hybrid-astar", ws, argparse.Namespace(wheelbase=0.0))


def test_experiment_command(tmp_path, capsys):
    from gapath.cli.studies.dynamic import register as register_experiment

    parser = argparse.ArgumentParser()
    register_experiment(parser.add_subparsers(dest="command"))
    args = parser.parse_args(
        [
            "dynamic",
            "--runs",
            "1",
            "--planners",
            "astar",
            "--scenarios",
            "warehouse",
            "--no-gif",
            "--quiet",
            "--out",
            str(tmp_path),
        ]
    )
    assert args.func(args) == 0
    md = (tmp_path / "dynamic.md").read_text()
    assert "## warehouse" in md and "A* (grid)" in md
