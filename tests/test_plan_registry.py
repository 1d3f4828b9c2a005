"""The library API behind ``gapath plan``/``simulate``/``exact`` (issue 16):
one planner registry, ``PathFront.from_paths``/``marked``,
``Workspace.describe``, the objective-name and positive-integer checks."""

import json

import numpy as np
import pytest

from gapath import Workspace
from gapath.costmap import PLAN_LAYERS, build_costmap
from gapath.errors import ConfigError, NoPathError, positive_int
from gapath.front import PathFront
from gapath.objectives import OBJECTIVE_NAMES, check_objective_names, evaluate_paths, pad_paths
from gapath.planners import PLANNERS, CarSettings, PlanOutcome, plan, planner_info, planner_names
from gapath.planners.exact import exact_path_front, monotone_front


@pytest.fixture(scope="module")
def small_ws():
    occ = np.zeros((10, 16), bool)
    occ[2:10, 7] = True  # a wall with a gap at the top
    return Workspace(occ, (8, 1), (8, 14), name="wall")


def _options(name):
    return {"seed": 3} if name.startswith("rrt") else {}


@pytest.mark.parametrize("name", list(PLANNERS))
def test_plan_every_planner_gives_a_valid_path(small_ws, name):
    out = plan(small_ws, name, **_options(name))
    assert isinstance(out, PlanOutcome) and out.planner == name
    cells = np.asarray(out.cells)
    assert tuple(cells[0]) == small_ws.start and tuple(cells[-1]) == small_ws.goal
    if planner_info(name).family == "grid":
        assert np.abs(np.diff(cells, axis=0)).max() == 1  # 8-connected steps
    else:  # the cells of the poses (RRT: its waypoints), one per pose change
        assert (np.abs(np.diff(cells, axis=0)).max(axis=1) >= 1).all()
    assert not small_ws.occ[cells[:, 0], cells[:, 1]].any()
    assert out.poses.ndim == 2 and out.poses.shape[1] == 3
    cs = small_ws.cell_size
    assert np.allclose(out.poses[0, :2], [small_ws.start[1] * cs, small_ws.start[0] * cs], atol=0.5 * cs)
    # the wall forces a detour above row 2: longer than the straight line
    assert out.objectives["length"] > 13.0
    assert np.array_equal(out.F, np.array(list(out.objectives.values())))
    assert out.seconds >= 0 and out.result is not None


def test_grid_planners_agree_with_their_costmap_planner(small_ws):
    from gapath.costmap import Costmap
    from gapath.planners.pareto import plan as plan_on_costmap

    for name in planner_names("grid"):
        out = plan(small_ws, name)
        ref = plan_on_costmap(Costmap(small_ws), name, ("length",))
        assert np.array_equal(out.cells, ref.path)
        assert out.objectives == ref.values
        assert out.info["expansions"] == ref.expansions
        # the path's length is a shortest path's (A* on the plain grid)
        from gapath.planners.astar import astar

        assert out.objectives["length"] == pytest.approx(astar(small_ws).length, rel=1e-12)


def test_grid_planner_on_layers_and_bad_costmap(small_ws):
    cm = build_costmap(small_ws, ["risk", "elevation"], terrain_seed=2)
    out = plan(small_ws, "dstar-po", costmap=cm, objectives=("length", "risk", "elevation"))
    assert list(out.objectives) == ["length", "risk", "elevation"]
    assert set(out.info["search_cost"]) == {"length", "risk", "elevation"}
    other = Workspace(np.zeros((10, 16), bool))
    with pytest.raises(ConfigError, match="another workspace"):
        plan(other, "astar", costmap=cm)


def test_unknown_planner_and_option_name_the_value_and_the_choices(small_ws):
    with pytest.raises(ConfigError) as exc:
        plan(small_ws, "dijkstra")
    msg = str(exc.value)
    assert "'dijkstra'" in msg and all(name in msg for name in PLANNERS)
    with pytest.raises(ConfigError, match="unknown option 'iterations' for planner 'hybrid-astar'"):
        plan(small_ws, "hybrid-astar", iterations=10)
    with pytest.raises(ConfigError, match="unknown planner family"):
        planner_names("continuous")


def test_registry_families_and_simulated_planners():
    from gapath.dynamic import PLANNERS as SIMULATED
    from gapath.dynamic import make_planner
    from gapath.planners.pareto import PLANNERS as COSTMAP_PLANNERS

    assert set(planner_names("grid")) | set(planner_names("kinematic")) == set(PLANNERS)
    assert COSTMAP_PLANNERS == planner_names("grid")
    assert set(SIMULATED) == set(planner_names(simulated=True))
    for name in SIMULATED:
        assert make_planner(name).name == name
    assert planner_info("dstar-po").family == "grid" and not planner_info("dstar-po").simulated


def test_registry_options_are_the_planners_settings():
    import inspect

    from gapath.planners.hybrid_astar import HybridAStar
    from gapath.planners.rrt import rrt

    def keywords(fn, drop=()):
        return {n for n, p in inspect.signature(fn).parameters.items() if p.kind == p.KEYWORD_ONLY} - set(
            drop
        )

    assert set(planner_info("hybrid-astar").options) == keywords(HybridAStar) | {"car", "heading"}
    assert set(planner_info("rrt").options) == keywords(rrt, ("radius", "star", "blocked")) | {"car"}
    assert planner_info("rrt-star").options == planner_info("rrt").options
    grid = planner_info("astar").run
    assert set(planner_info("astar").options) == keywords(grid)


def test_no_path_raises(small_ws):
    occ = np.zeros((6, 6), bool)
    occ[:, 3] = True
    ws = Workspace(occ, (5, 0), (0, 5))
    for name in planner_names("grid"):
        with pytest.raises(NoPathError):
            plan(ws, name)
    with pytest.raises(NoPathError):
        plan(ws, "rrt", seed=1, max_iter=300)


def test_car_settings_defaults_are_the_cli_defaults():
    import argparse

    from gapath.cli.simulate import add_planner_arguments, car_from_args

    parser = argparse.ArgumentParser()
    add_planner_arguments(parser)
    args = parser.parse_args([])
    car = CarSettings()
    assert (args.wheelbase, args.max_steer, args.speed, args.radius) == (
        car.wheelbase,
        car.max_steer_deg,
        car.speed,
        car.radius,
    )
    assert car_from_args(args) == car.model()
    # one fact: the CLI's car is the library's default CarModel (0.6 rad)
    from gapath.planners.hybrid_astar import CarModel

    assert car.model() == CarModel()
    with pytest.raises(ConfigError, match="max_steer_deg must be between 0 and 90"):
        CarSettings(max_steer_deg=90.0).model()
    with pytest.raises(ConfigError, match="--max-steer must be between 0 and 90"):
        car_from_args(argparse.Namespace(max_steer=95.0))
    with pytest.raises(ConfigError, match="--wheelbase"):
        car_from_args(argparse.Namespace(wheelbase=-1.0))


def test_hybrid_astar_heading_and_car_options(small_ws):
    wide = plan(small_ws, "hybrid-astar", car=CarSettings(radius=0.45))
    assert wide.info["radius"] == 0.45
    east = plan(small_ws, "hybrid-astar", heading=0.0)
    assert east.poses[0, 2] == pytest.approx(0.0)


def test_path_front_from_paths_matches_the_metrics_kernel(small_ws):
    paths = [plan(small_ws, "astar").cells, plan(small_ws, "rrt", seed=1).cells]
    front = PathFront.from_paths(small_ws, paths, ["length", "smoothness"])
    P, L = pad_paths(paths)
    metrics = evaluate_paths(
        P, L, small_ws.occ, small_ws.potential, small_ws.cell_size, small_ws.corner_cutting
    )
    assert np.array_equal(front.metrics, metrics)
    assert np.array_equal(front.F, metrics[:, [0, 2]])
    assert front.X.shape == (2, 0) and len(front) == 2
    given = PathFront.from_paths(small_ws, paths[:1], ["length", "risk"], np.array([[1.0, 2.0]]))
    assert given.F.tolist() == [[1.0, 2.0]]
    with pytest.raises(ConfigError):
        PathFront.from_paths(small_ws, paths, ["risk"])
    empty = PathFront.from_paths(small_ws, [], ["length"])
    assert len(empty) == 0 and empty.marked() == {}


def test_exact_path_front_and_marked():
    from gapath import default_workspace

    ws = default_workspace()
    ef = monotone_front(ws, ("length", "vulnerability"))
    front = exact_path_front(ws, ["length", "vulnerability"], "monotone")
    assert np.array_equal(front.F, ef.F) and len(front.paths) == len(ef.paths)
    marks = front.marked()
    assert set(marks) == {"shortest", "safest", "knee"}
    assert front.F[marks["shortest"], 0] == front.F[:, 0].min()
    assert front.F[marks["safest"], 1] == front.F[:, 1].min()
    lo, hi = front.F.min(axis=0), front.F.max(axis=0)
    scaled = np.linalg.norm((front.F - lo) / np.where(hi > lo, hi - lo, 1.0), axis=1)
    assert scaled[marks["knee"]] == scaled.min()
    only_length = exact_path_front(ws, ["length", "smoothness"], "monotone").marked()
    assert "safest" not in only_length and "shortest" in only_length
    with pytest.raises(ConfigError, match="unknown exact mode 'all'"):
        exact_path_front(ws, ["length"], "all")


def test_workspace_describe_round_trip_and_json():
    occ = np.zeros((5, 7), bool)
    occ[2, 1:6] = True
    ws = Workspace(occ, (4, 2), (0, 6), cell_size=0.5, corner_cutting=False, name="bar")
    d = ws.describe()
    assert d == json.loads(json.dumps(d))
    back = Workspace(
        ws.occ,
        d["start"],
        d["goal"],
        cell_size=d["cell_size"],
        corner_cutting=d["corner_cutting"],
        name=d["map"],
    )
    assert back == ws and back.name == ws.name and list(back.shape) == d["shape"]


def test_summaries_use_describe(tmp_path, small_ws):
    from gapath.cli.simulate import write_plan

    out = plan(small_ws, "rrt", seed=2)
    write_plan(out, small_ws, tmp_path, plots=False)
    settings = json.loads((tmp_path / "summary.json").read_text())["settings"]
    assert {k: settings[k] for k in small_ws.describe()} == small_ws.describe()


def test_build_costmap_layers(small_ws):
    assert PLAN_LAYERS == ("elevation", "solar", "risk")
    cm = build_costmap(small_ws, ["risk"], risk=(1, 1))
    assert cm.risk_cells == [(1, 1)]
    with pytest.raises(ConfigError, match="unknown layer 'slope'"):
        build_costmap(small_ws, ["slope"])


def test_one_objective_name_check():
    assert check_objective_names(list(OBJECTIVE_NAMES)) == list(OBJECTIVE_NAMES)
    assert check_objective_names(["length", "risk"], layers=("risk",)) == ["length", "risk"]
    with pytest.raises(ConfigError, match="unknown objective 'interfering'"):
        check_objective_names(["interfering"])
    from gapath.problems import GridPathProblem

    with pytest.raises(ConfigError, match="unknown objective 'safety'; expected some of length"):
        GridPathProblem(Workspace(np.zeros((4, 4), bool)), objectives=("length", "safety"))


def test_experiment_spec_uses_the_objective_name_check(tmp_path):
    from gapath.experiments.spec import load_spec

    path = tmp_path / "e.yaml"
    path.write_text("settings: {objectives: [length, interfering]}\n")
    with pytest.raises(ConfigError, match=r"e\.yaml: settings\.objectives: unknown objective 'interfering'"):
        load_spec(path)


@pytest.mark.parametrize("value", [0, -2, 2.5, "x", None, float("nan"), float("inf"), "2.0"])
def test_positive_int_rejects(value):
    with pytest.raises(ConfigError, match="n must be a positive integer"):
        positive_int(value, "n")


def test_positive_int_accepts():
    assert positive_int(3, "n") == 3 and positive_int(3.0, "n") == 3 and positive_int("7", "n") == 7
    assert isinstance(positive_int(np.int64(4), "n"), int)


def test_multirun_summary():
    from gapath.experiments import multirun

    m = multirun(Workspace(np.zeros((6, 8), bool)), runs=2, seed=5, pop_size=10, n_gen=2, progress=False)
    s = m.summary({"quality": {"x": 1}})
    assert s["seeds"] == [5, 6] and s["settings"]["seed"] == 5 and s["settings"]["runs"] == 2
    assert s["front_size"] == len(m.front) and s["run_front_sizes"] == [len(r.front) for r in m.runs]
    assert s["evaluations"] == sum(r.n_eval for r in m.runs) and s["quality"] == {"x": 1}
    with pytest.raises(ConfigError, match="runs must be a positive integer"):
        multirun(Workspace(np.zeros((6, 8), bool)), runs=0)
