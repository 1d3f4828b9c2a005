"""The map arguments of the CLI and the defaults a user of grid planners
expects (issue 13, section 5): ``plan`` is the shortest path, the corner rule
follows the map's source, ``--scen FILE:INDEX`` and ``gapath scen``, ROS maps
in their world frame, messages in the CLI's words, timings without numba's
compilation, axis labels with units on every plot.

Real maps come from the shared data folder (``../shared/data``, see
``tests/conftest.py``).
"""

from __future__ import annotations

import json
import math
import shutil

import numpy as np
import pytest
from PIL import Image

from gapath.cli._args import matches_optimum
from gapath.cli.main import build_parser, main
from gapath.loaders import load_map, load_occupancy, load_scenarios

SCEN = "movingai/mapf/random-32-32-20-random-1.scen"
ARENA_SCEN = "movingai/grid/arena.map.scen"
DEPOT = "ros/nav2_depot/depot.yaml"


def _summary(out):
    return json.loads((out / "summary.json").read_text())


def _ros_world(frame_yaml, cells):
    """World points of cells by map_server's convention, written out
    independently of gapath: the image is flipped so that grid row ``my = 0``
    is its last row, and cell ``(mx, my)`` has its centre at ``origin + (m +
    0.5) * resolution`` (yaw 0)."""
    import yaml

    meta = yaml.safe_load(frame_yaml.read_text())
    h = np.asarray(Image.open(frame_yaml.parent / meta["image"])).shape[0]
    ox, oy, _ = meta["origin"]
    res = meta["resolution"]
    out = []
    for r, c in cells:
        mx, my = c, h - 1 - r
        out.append((ox + (mx + 0.5) * res, oy + (my + 0.5) * res))
    return np.array(out)


def _corner_cut_scenarios(data_dir, name, k):
    """Up to ``k`` scenarios of ``name`` whose optimum changes when corners
    may be cut (so a planner with the wrong rule misses it)."""
    from gapath.planners.astar import astar

    scens = load_scenarios(data_dir / name)
    occ = load_occupancy(scens[0].resolve_map())
    from gapath.workspace import Workspace

    out = []
    for i, sc in enumerate(scens):
        if sc.start == sc.goal:
            continue
        cut = astar(Workspace(occ, sc.start, sc.goal, corner_cutting=True)).cost
        if not matches_optimum(cut, sc.optimal):
            out.append(i)
        if len(out) == k:
            break
    assert len(out) == k
    return out


# ---------------------------------------------------------------------------
# plan: the shortest path by default
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("planner", ["astar", "dstar-lite", "dstar-po"])
def test_plan_default_is_the_movingai_optimum(planner, data_dir, tmp_path, capsys):
    """With nothing but the map, start and goal, plan returns MovingAI's
    optimum, on scenarios where cutting corners would give a shorter path."""
    scens = load_scenarios(data_dir / SCEN)
    for i in _corner_cut_scenarios(data_dir, SCEN, 4):
        sc = scens[i]
        out = tmp_path / f"{planner}-{i}"
        args = [
            "plan",
            str(sc.resolve_map()),
            "--planner",
            planner,
            "--start",
            f"{sc.start[0]},{sc.start[1]}",
            "--goal",
            f"{sc.goal[0]},{sc.goal[1]}",
            "--out",
            str(out),
            "--quiet",
            "--no-plots",
        ]
        assert main(args) == 0
        s = _summary(out)
        assert s["settings"]["objectives"] == ["length"]
        assert s["settings"]["corner_cutting"] is False
        assert matches_optimum(s["objectives"]["length"], sc.optimal), (i, s["objectives"])
        assert (out / "front.csv").read_text().splitlines()[0] == "length"


def test_plan_layers_are_opt_in(tmp_path):
    out = tmp_path / "layers"
    assert (
        main(
            [
                "plan",
                "default",
                "--planner",
                "astar",
                "--layers",
                "elevation,solar,risk",
                "--out",
                str(out),
                "--quiet",
                "--no-plots",
            ]
        )
        == 0
    )
    assert (out / "front.csv").read_text().splitlines()[0] == "length,elevation,solar,risk"
    assert _summary(out)["settings"]["terrain"] == "fractal seed=1"
    plain = tmp_path / "plain"
    assert main(["plan", "default", "--planner", "astar", "--out", str(plain), "--quiet", "--no-plots"]) == 0
    assert _summary(plain)["settings"]["terrain"] is None
    # the layered path is never shorter than the shortest one
    assert _summary(plain)["objectives"]["length"] <= _summary(out)["objectives"]["length"] + 1e-9


@pytest.mark.parametrize(
    "flag,fragment",
    [
        (["--dem", "x.npy"], "--dem sets the elevation layer"),
        (["--risk", "3,3"], "--risk sets the risk layer"),
        (["--layers", "height"], "--layers: unknown layer 'height'"),
    ],
)
def test_layer_options_without_their_layer(flag, fragment, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    np.save(tmp_path / "x.npy", np.random.default_rng(1).random((8, 8)))  # a valid DEM
    assert main(["plan", "default", *flag, "--out", str(tmp_path / "o"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert fragment in err and "Traceback" not in err


def test_mars_study_sets_its_own_layers():
    from gapath.studies import mars

    assert tuple(mars.OBJECTIVES) == ("length", "elevation", "solar", "risk")


def test_plan_reports_compile_time_apart(tmp_path, capsys):
    out = tmp_path / "t"
    assert main(["plan", "default", "--planner", "astar", "--out", str(out), "--no-plots"]) == 0
    s = _summary(out)
    assert s["compile_s"] >= 0 and s["wall_time_s"] >= 0
    assert "numba warm-up" in capsys.readouterr().out


# ---------------------------------------------------------------------------
# corner rule by source, printed and stored
# ---------------------------------------------------------------------------


def test_corner_rule_by_source_in_every_command(data_dir, tmp_path, capsys):
    arena = data_dir / "movingai/grid/arena.map"
    text = tmp_path / "g.txt"
    text.write_text("S...\n.#..\n...G\n")
    runs = [
        (["plan", str(arena), "--start", "40,3", "--goal", "3,40"], False, "MovingAI .map"),
        (["exact", str(arena), "--start", "40,3", "--goal", "3,40"], False, "MovingAI .map"),
        (
            ["solve", str(arena), "--start", "40,3", "--goal", "3,40", "--pop", "10", "--gen", "2"],
            False,
            "MovingAI .map",
        ),
        (["plan", str(text)], True, "text grid"),
        (["exact", "default"], True, "bundled scenario"),
        (
            ["plan", str(arena), "--start", "40,3", "--goal", "3,40", "--corner-cutting"],
            True,
            "--corner-cutting",
        ),
        (["plan", str(text), "--no-corner-cutting"], False, "--no-corner-cutting"),
    ]
    for k, (args, expected, source) in enumerate(runs):
        out = tmp_path / f"run{k}"
        assert main(args + ["--out", str(out), "--no-plots"]) == 0, args
        report = capsys.readouterr().out
        settings = _summary(out)["settings"]
        assert settings["corner_cutting"] is expected, args
        assert source in settings["corner_rule"], args
        line = next(ln for ln in report.splitlines() if ln.startswith("corner cutting:"))
        assert ("allowed" in line and "not allowed" not in line) is expected, line
        assert source in line


# ---------------------------------------------------------------------------
# --scen FILE:INDEX and gapath scen
# ---------------------------------------------------------------------------


def test_plan_scen_uses_the_line_and_reports_the_optimum(data_dir, tmp_path, capsys):
    scens = load_scenarios(data_dir / SCEN)
    out = tmp_path / "p"
    assert (
        main(
            ["plan", "--scen", f"{data_dir / SCEN}:7", "--planner", "astar", "--out", str(out), "--no-plots"]
        )
        == 0
    )
    s = _summary(out)
    assert s["settings"]["start"] == list(scens[7].start)
    assert s["settings"]["goal"] == list(scens[7].goal)
    assert s["settings"]["corner_cutting"] is False
    rec = s["scenario"]
    assert rec["index"] == 7 and rec["line"] == 9 and rec["optimal"] == scens[7].optimal
    assert rec["matches"] is True and matches_optimum(rec["length"], rec["optimal"])
    report = capsys.readouterr().out
    assert f"MovingAI optimum {scens[7].optimal:.8g}" in report and "matches" in report


def test_scen_with_corner_cutting_override_misses_the_optimum(data_dir, tmp_path, capsys):
    i = _corner_cut_scenarios(data_dir, SCEN, 1)[0]
    out = tmp_path / "cut"
    assert (
        main(
            [
                "plan",
                "--scen",
                f"{data_dir / SCEN}:{i}",
                "--planner",
                "astar",
                "--corner-cutting",
                "--out",
                str(out),
                "--no-plots",
            ]
        )
        == 0
    )
    rec = _summary(out)["scenario"]
    assert rec["matches"] is False and rec["length"] < rec["optimal"]
    assert "the optimum assumes no corner cutting" in capsys.readouterr().out


def test_scen_explicit_map_wins(data_dir, tmp_path):
    scen_dir = tmp_path / "elsewhere"
    scen_dir.mkdir()
    shutil.copy(data_dir / SCEN, scen_dir / "s.scen")  # its map is not next to it
    assert main(["plan", "--scen", f"{scen_dir / 's.scen'}:0", "--out", str(tmp_path / "x"), "--quiet"]) == 2
    copy = tmp_path / "renamed.map"
    shutil.copy(data_dir / "movingai/mapf/random-32-32-20.map", copy)
    out = tmp_path / "y"
    assert (
        main(
            [
                "plan",
                str(copy),
                "--scen",
                f"{scen_dir / 's.scen'}:0",
                "--planner",
                "astar",
                "--out",
                str(out),
                "--quiet",
                "--no-plots",
            ]
        )
        == 0
    )
    assert _summary(out)["settings"]["map"] == "renamed"
    assert _summary(out)["scenario"]["matches"] is True


def test_exact_and_solve_take_scen(data_dir, tmp_path):
    scens = load_scenarios(data_dir / ARENA_SCEN)
    i = next(k for k, s in enumerate(scens) if abs(s.start[1] - s.goal[1]) >= 3 and s.optimal > 3)
    ex = tmp_path / "exact"
    assert (
        main(
            [
                "exact",
                "--scen",
                f"{data_dir / ARENA_SCEN}:{i}",
                "--mode",
                "free",
                "--objectives",
                "length",
                "--out",
                str(ex),
                "--quiet",
                "--no-plots",
            ]
        )
        == 0
    )
    rec = _summary(ex)["scenario"]
    assert rec["matches"] is True  # the exact free front holds a shortest path
    so = tmp_path / "solve"
    code = main(
        [
            "solve",
            "--scen",
            f"{data_dir / ARENA_SCEN}:{i}",
            "--pop",
            "20",
            "--gen",
            "3",
            "--out",
            str(so),
            "--quiet",
            "--no-plots",
        ]
    )
    assert code in (0, 1)
    s = _summary(so)
    assert s["scenario"]["optimal"] == scens[i].optimal
    assert s["settings"]["start"] == list(scens[i].start) and s["settings"]["corner_cutting"] is False
    if s["scenario"]["length"] is not None:  # monotone paths: never below the optimum
        assert s["scenario"]["length"] >= scens[i].optimal * (1 - 1e-5)


@pytest.mark.parametrize(
    "args,fragment",
    [
        (["plan", "--scen", "{scen}:99999"], "expected an index 0..408"),
        (["plan", "--scen", "{scen}"], "expected FILE:INDEX"),
        (["plan", "--scen", "{scen}:1", "--start", "1,1"], "--scen gives the start and the goal"),
        (["plan", "{arena}", "--scen", "{scen}:1"], "is for a 32x32 map"),
        (["plan"], "a MAP is needed"),
        (["exact"], "a MAP is needed"),
        (["solve"], "a MAP is needed"),
    ],
)
def test_scen_bad_input(args, fragment, data_dir, tmp_path, capsys):
    args = [a.format(scen=data_dir / SCEN, arena=data_dir / "movingai/grid/arena.map") for a in args]
    try:
        code = main(args + ["--out", str(tmp_path / "o"), "--quiet"])
    except SystemExit as exc:  # argparse's own errors
        code = exc.code
    assert code == 2
    err = capsys.readouterr().err
    assert fragment in err and "Traceback" not in err


def test_scen_command_all_match(data_dir, capsys):
    assert main(["scen", str(data_dir / SCEN), "--limit", "40"]) == 0
    assert "40/40 scenarios match" in capsys.readouterr().out
    assert main(["scen", str(data_dir / ARENA_SCEN), "--planner", "dstar-lite", "--quiet"]) == 0
    assert "160/160" in capsys.readouterr().out


def test_scen_command_reports_a_wrong_optimum(data_dir, tmp_path, capsys):
    lines = (data_dir / SCEN).read_text().splitlines()
    cols = lines[3].split("\t")
    cols[8] = f"{float(cols[8]) + 1:.8f}"  # line 4: one more than the optimum
    lines[3] = "\t".join(cols)
    bad = tmp_path / "random-32-32-20-random-1.scen"
    bad.write_text("\n".join(lines[:11]) + "\n")
    shutil.copy(data_dir / "movingai/mapf/random-32-32-20.map", tmp_path)
    assert main(["scen", str(bad)]) == 1
    out = capsys.readouterr().out
    assert "9/10 scenarios match" in out and "line 4:" in out and "(-1)" in out


def test_scen_command_bad_input(tmp_path, capsys):
    assert main(["scen", str(tmp_path / "none.scen")]) == 2
    assert "none.scen" in capsys.readouterr().err
    (tmp_path / "e.scen").write_text("version 1\n")
    assert main(["scen", str(tmp_path / "e.scen")]) == 2
    assert "no scenario" in capsys.readouterr().err


# ---------------------------------------------------------------------------
# ROS maps in their world frame
# ---------------------------------------------------------------------------


def test_ros_frame_agrees_with_map_server(data_dir):
    path = data_dir / DEPOT
    occ = load_occupancy(path)
    free = np.argwhere(~occ)
    cells = [tuple(free[0]), tuple(free[-1]), tuple(free[len(free) // 2]), (0, 0), (306, 603)]
    ws = load_map(path, tuple(free[-1]), tuple(free[0]))
    assert ws.frame is not None and ws.frame.resolution == 0.05
    world = ws.frame.to_world(cells)
    assert np.allclose(world, _ros_world(path, cells))
    # row 0 is the top of the image: the largest y
    assert world[3, 1] > world[4, 1] and world[3, 0] < world[4, 0]
    for (r, c), (x, y) in zip(cells, world):
        assert ws.frame.to_cell(x, y) == (r, c)
        # any point inside the cell maps to it
        assert ws.frame.to_cell(x + 0.024, y - 0.024) == (r, c)


def test_frame_with_yaw_round_trips():
    from gapath.loaders import MapFrame

    f = MapFrame(1.0, -2.0, math.pi / 3, 0.1, 20, 30)
    cells = [(r, c) for r in range(0, 20, 3) for c in range(0, 30, 4)]
    assert [f.to_cell(*p) for p in f.to_world(cells)] == cells


def test_plan_start_goal_xy_on_a_ros_map(data_dir, tmp_path):
    path = data_dir / DEPOT
    occ = load_occupancy(path)
    free = np.argwhere(~occ)
    west, east = free[free[:, 1] < 100], free[free[:, 1] > 400]
    s_cell, g_cell = tuple(map(int, west[len(west) // 2])), tuple(map(int, east[len(east) // 2]))
    (sx, sy), (gx, gy) = _ros_world(path, [s_cell, g_cell])
    out = tmp_path / "ros"
    # negative metres parse without '='
    assert (
        main(
            [
                "plan",
                str(path),
                "--start-xy",
                f"{sx},{sy}",
                "--goal-xy",
                f"{gx},{gy}",
                "--planner",
                "astar",
                "--out",
                str(out),
                "--quiet",
            ]
        )
        == 0
    )
    s = _summary(out)["settings"]
    assert (tuple(s["start"]), tuple(s["goal"])) == (s_cell, g_cell)
    assert s["corner_cutting"] is False and s["frame"]["origin"] == [-7.14, -7.83, 0]
    assert np.allclose(s["start_xy"], (sx, sy)) and sx < 0
    rec = json.loads((out / "paths.json").read_text())[0]
    assert np.allclose(rec["world"], _ros_world(path, rec["path"]))
    assert (out / "paths.png").exists()


def test_kinematic_plan_world_poses(data_dir, tmp_path):
    path = data_dir / "ros/lse_arena/lse_arena.yaml"
    out = tmp_path / "rrt"
    assert (
        main(
            [
                "plan",
                str(path),
                "--start",
                "50,10",
                "--goal",
                "10,70",
                "--planner",
                "rrt",
                "--radius",
                "0.05",
                "--step",
                "0.2",
                "--out",
                str(out),
                "--quiet",
            ]
        )
        == 0
    )
    rec = json.loads((out / "paths.json").read_text())[0]
    assert np.allclose(rec["world"], _ros_world(path, rec["path"]))
    wp = np.array(rec["world_poses"])
    assert np.allclose(wp[0, :2], _ros_world(path, [(50, 10)])[0])
    assert np.allclose(wp[-1, :2], _ros_world(path, [(10, 70)])[0])
    d = np.diff(wp[:, :2], axis=0)
    moving = np.hypot(d[:, 0], d[:, 1]) > 1e-9
    heading = np.arctan2(d[moving, 1], d[moving, 0])  # the world heading of each segment
    diff = np.angle(np.exp(1j * (heading - wp[:-1][moving, 2])))
    assert np.allclose(diff, 0.0, atol=1e-5)
    assert "compile_s" in _summary(out)


@pytest.mark.parametrize(
    "args,fragment",
    [
        (["--start-xy", "1,2"], "needs a map with a world frame"),
        (["--start", "1,1", "--start-xy", "1,2"], "--start and --start-xy both give the start"),
        (["--start-xy", "x,2"], "expected X,Y"),
    ],
)
def test_xy_bad_input(args, fragment, data_dir, tmp_path, capsys):
    try:
        code = main(
            [
                "plan",
                str(data_dir / "movingai/grid/arena.map"),
                *args,
                "--out",
                str(tmp_path / "o"),
                "--quiet",
            ]
        )
    except SystemExit as exc:
        code = exc.code
    assert code == 2
    assert fragment in capsys.readouterr().err


def test_xy_outside_the_ros_map(data_dir, tmp_path, capsys):
    assert (
        main(["plan", str(data_dir / DEPOT), "--goal-xy", "100,0", "--out", str(tmp_path / "o"), "--quiet"])
        == 2
    )
    err = capsys.readouterr().err
    assert "--goal-xy" in err and "outside the map" in err and "-7.14.." in err


# ---------------------------------------------------------------------------
# plots: axis labels and units
# ---------------------------------------------------------------------------


def test_plots_have_axis_labels_with_units(data_dir):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from gapath import default_workspace
    from gapath.dynamic.plots import plot_map as _base
    from gapath.planners.exact import exact_path_front
    from gapath.plotting import plot_front, plot_paths

    ws = default_workspace()
    front = exact_path_front(ws, ["length", "vulnerability"], "monotone")
    ax = plot_front(front, workspace=ws)
    assert ax.get_xlabel() == "length (cells)" and "unitless" in ax.get_ylabel()
    ax = plot_paths(ws, front)
    assert ax.get_xlabel() == "column (cells)" and ax.get_ylabel().startswith("row (cells")
    ros = load_map(data_dir / "ros/lse_arena/lse_arena.yaml", (50, 10), (10, 70))
    rfront = exact_path_front(ros, ["length"], "monotone")
    ax = plot_paths(ros, rfront)
    assert ax.get_xlabel() == "x (m, map frame)" and ax.get_ylabel() == "y (m, map frame)"
    ticks = [float(t.get_text()) for t in ax.get_yticklabels()]
    assert ticks == sorted(ticks, reverse=True) or ticks == sorted(ticks)
    # the y tick at the top of the image is the largest (y grows up the image)
    ys = ax.get_yticks()
    assert ticks[int(np.argmin(ys))] == max(ticks)
    assert plot_front(rfront, workspace=ros).get_xlabel() == "length (m)"
    _, ax = plt.subplots()
    _base(ws, ax)
    assert "m" in ax.get_xlabel() and ax.get_ylabel()
    plt.close("all")


# ---------------------------------------------------------------------------
# messages in the CLI's words, papers by name
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "args,fragment",
    [
        (["--planner", "rrt", "--iterations", "0"], "--iterations must be an integer >= 1, got 0"),
        (["--planner", "rrt", "--goal-bias", "2"], "--goal-bias must be a number in [0, 1], got 2.0"),
        (["--planner", "hybrid-astar", "--heading-bins", "2"], "--heading-bins must be"),
        (
            ["--planner", "hybrid-astar", "--max-steer", "95"],
            "--max-steer must be a number in (0, 90), got 95.0",
        ),
        (["--planner", "hybrid-astar", "--wheelbase", "-1"], "--wheelbase must be"),
        (["--planner", "rrt", "--radius", "3"], "start cell ROW,COL 7,0 is in collision"),
        (["--planner", "hybrid-astar", "--radius", "3"], "start cell ROW,COL 7,0 heading"),
    ],
)
def test_kinematic_messages_use_flags_and_cells(args, fragment, tmp_path, capsys):
    grid = tmp_path / "g.txt"
    grid.write_text("\n".join(["." * 10] * 8) + "\n")
    assert main(["plan", str(grid), *args, "--out", str(tmp_path / "o"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert fragment in err, err
    assert "max_iter" not in err and "(x, y)" not in err and "Traceback" not in err


def test_simulate_messages_use_flags(tmp_path, capsys):
    assert (
        main(
            [
                "simulate",
                "maze",
                "--planner",
                "rrt",
                "--iterations",
                "-5",
                "--out",
                str(tmp_path / "o"),
                "--quiet",
            ]
        )
        == 2
    )
    assert "--iterations must be" in capsys.readouterr().err


def test_help_names_the_papers_not_the_seeds():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    texts = [parser.format_help()]
    for p in sub.choices.values():
        texts.append(p.format_help())
        for a in p._actions:
            if a.__class__.__name__ == "_SubParsersAction":
                texts.extend(q.format_help() for q in a.choices.values())
    joined = "\n".join(texts)
    assert "seeds'" not in joined
    assert "Ahmed & Deb" in joined


def test_heading_on_a_ros_map_is_a_map_frame_yaw(data_dir, tmp_path):
    path = data_dir / "ros/lse_arena/lse_arena.yaml"
    out = tmp_path / "h"
    # 90 degrees: north in the map frame, i.e. up the image
    assert (
        main(
            [
                "plan",
                str(path),
                "--start",
                "50,10",
                "--goal",
                "10,12",
                "--planner",
                "hybrid-astar",
                "--radius",
                "0.05",
                "--wheelbase",
                "0.2",
                "--heading",
                "90",
                "--out",
                str(out),
                "--quiet",
                "--no-plots",
            ]
        )
        == 0
    )
    rec = json.loads((out / "paths.json").read_text())[0]
    assert rec["world_poses"][0][2] == pytest.approx(math.pi / 2)
    assert rec["poses"][0][2] == pytest.approx(-math.pi / 2)  # planner frame: y down
