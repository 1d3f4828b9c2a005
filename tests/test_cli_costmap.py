"""The costmap flags on the command line (``gapath solve``, ``exact``,
``plan``): layer objectives reach the library, the written fronts are what
the library computes from the same costmap, summary.json records how the
costmap was built, and every bad input is one message with exit status 2."""

import csv
import json

import numpy as np
import pytest

from gapath.cli.main import main
from gapath.costmap import Costmap, fractal_terrain
from gapath.errors import EXIT_BAD_INPUT
from gapath.generators import default_workspace
from gapath.loaders import load_text
from gapath.planners.exact import free_front, path_objectives

SMALL = [
    "..........",
    "...#......",
    "......#...",
    "..#.......",
    ".....#..#.",
    ".#........",
    "....#.....",
    "..........",
]
TINY_RUN = ["--pop", "16", "--gen", "4", "--no-plots", "--quiet"]


@pytest.fixture
def small_map(tmp_path):
    p = tmp_path / "small.txt"
    p.write_text("\n".join(SMALL) + "\n")
    return p


def run(capsys, argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    return code, out, err


def front_csv(out):
    rows = list(csv.reader((out / "front.csv").open()))
    return rows[0], np.array([[float(v) for v in r] for r in rows[1:]])


def paths_json(out):
    return [np.array(rec["path"]) for rec in json.loads((out / "paths.json").read_text())]


def settings(out):
    return json.loads((out / "summary.json").read_text())["settings"]


def test_solve_free_elevation_front_is_the_library_value_of_its_paths(tmp_path, capsys):
    out = tmp_path / "s"
    code, _, _ = run(
        capsys,
        ["solve", "default", "--paths", "free", "--objectives", "length,elevation", "--terrain-seed", "3"]
        + TINY_RUN
        + ["--out", out],
    )
    assert code == 0
    header, F = front_csv(out)
    assert header == ["length", "elevation"]
    ws = default_workspace()
    cm = Costmap(ws)
    cm.set_elevation(fractal_terrain(ws.shape, seed=3))
    paths = paths_json(out)
    assert len(paths) == len(F) >= 1
    for p, row in zip(paths, F):
        assert tuple(p[0]) == ws.start and tuple(p[-1]) == ws.goal
        assert not ws.occ[p[:, 0], p[:, 1]].any()
        want = cm.evaluate_path(p, ["length", "elevation"])
        np.testing.assert_allclose(row, [want["length"], want["elevation"]], rtol=1e-12, atol=1e-12)
    # another terrain seed is another layer: the same paths score differently
    other = Costmap(ws)
    other.set_elevation(fractal_terrain(ws.shape, seed=4))
    assert any(
        abs(other.evaluate_path(p, ["elevation"])["elevation"] - row[1]) > 1e-6 for p, row in zip(paths, F)
    )
    s = settings(out)
    assert s["objectives"] == ["length", "elevation"]
    assert s["costmap"]["layers"] == ["elevation"]
    assert s["costmap"]["elevation"] == {"source": "fractal terrain", "terrain_seed": 3, "hurst": 0.8}
    assert "mean" in s["costmap"]["objectives"]["elevation"]


def test_solve_worst_case_risk(tmp_path, capsys):
    out = tmp_path / "r"
    code, _, _ = run(
        capsys,
        ["solve", "default", "--objectives", "length,risk_max", "--risk", "12,20"]
        + TINY_RUN
        + ["--out", out],
    )
    assert code == 0
    header, F = front_csv(out)
    assert header == ["length", "risk_max"]
    ws = default_workspace()
    cm = Costmap(ws, risk=(12, 20))
    layer = cm.layer("risk")
    for p, row in zip(paths_json(out), F):
        assert row[1] == pytest.approx(float(layer[p[:, 0], p[:, 1]].max()), rel=1e-12)
        assert row[0] == pytest.approx(cm.evaluate_path(p, ["length"])["length"], rel=1e-12)
    s = settings(out)["costmap"]
    assert s["risk"] == {"cells": [[12, 20]], "cap": 1.0}
    assert "largest value" in s["objectives"]["risk_max"]


def test_solve_monotone_user_layer_and_solar(small_map, tmp_path, capsys):
    slope = np.random.default_rng(5).random((8, 10))
    np.save(tmp_path / "slope.npy", slope)
    out = tmp_path / "m"
    argv = ["solve", small_map, "--paths", "monotone", "--objectives", "length,slope,solar"]
    argv += ["--layer", f"slope={tmp_path / 'slope.npy'}", "--solar-rate", "0.2"]
    code, _, _ = run(capsys, argv + TINY_RUN + ["--out", out])
    assert code == 0
    header, F = front_csv(out)
    assert header == ["length", "slope", "solar"]
    cm = Costmap(load_text(small_map), solar_rate=0.2, layers={"slope": slope})
    for p, row in zip(paths_json(out), F):
        want = cm.evaluate_path(p, header)
        np.testing.assert_allclose(row, [want[n] for n in header], rtol=1e-12)
    s = settings(out)["costmap"]
    assert s["layers"] == ["solar", "slope"]
    assert s["solar"] == {"rate": 0.2, "angle0": 0.0}
    assert (
        s["user_layers"]["slope"]["file"].endswith("slope.npy")
        and len(s["user_layers"]["slope"]["sha256"]) == 64
    )


def test_solve_runs_record_the_costmap_in_every_summary(small_map, tmp_path, capsys):
    out = tmp_path / "multi"
    argv = ["solve", small_map, "--objectives", "length,risk", "--risk", "3,4", "--runs", "2"]
    code, _, _ = run(capsys, argv + TINY_RUN + ["--out", out])
    assert code == 0
    assert front_csv(out)[0] == ["length", "risk"]
    for d in (out, out / "runs" / "1", out / "runs" / "2"):
        assert settings(d)["costmap"]["risk"]["cells"] == [[3, 4]], d


def test_exact_three_objectives_agree_with_free_front(small_map, tmp_path, capsys):
    out = tmp_path / "e"
    argv = ["exact", small_map, "--mode", "free", "--objectives", "length,vulnerability,risk_sum"]
    code, _, _ = run(capsys, argv + ["--risk", "4,4", "--no-plots", "--quiet", "--out", out])
    assert code == 0
    header, F = front_csv(out)
    assert header == ["length", "vulnerability", "risk_sum"]
    ws = load_text(small_map)
    cm = Costmap(ws, risk=(4, 4))
    ef = free_front(ws, header, costmap=cm)
    assert len(ef.F) >= 2  # a real trade-off, not a single point
    np.testing.assert_array_equal(F, ef.F)
    for p, q, row in zip(paths_json(out), ef.paths, F):
        np.testing.assert_array_equal(p, q)
        want = path_objectives(ws, p, header, cm)
        np.testing.assert_allclose(row, [want[n] for n in header], rtol=1e-12)
    s = settings(out)
    assert s["objectives"] == header and s["mode"] == "free"
    assert s["costmap"]["risk"]["cells"] == [[4, 4]]
    assert "summed over the path's cells" in s["costmap"]["objectives"]["risk_sum"]
    plain = tmp_path / "plain"
    code, _, _ = run(capsys, ["exact", small_map, "--mode", "free", "--no-plots", "--quiet", "--out", plain])
    assert code == 0 and "costmap" not in settings(plain)


def test_exact_k_objectives_with_a_user_layer_and_elevation(small_map, tmp_path, capsys):
    slope = np.random.default_rng(7).random((8, 10))
    np.save(tmp_path / "slope.npy", slope)
    out = tmp_path / "k"
    names = ["length", "elevation_sum", "slope_sum", "solar"]
    argv = ["exact", small_map, "--mode", "free", "--objectives", ",".join(names), "--terrain-seed", "2"]
    argv += ["--layer", f"slope={tmp_path / 'slope.npy'}", "--solar-rate", "0"]
    code, _, _ = run(capsys, argv + ["--no-plots", "--quiet", "--out", out])
    assert code == 0
    header, F = front_csv(out)
    assert header == names
    ws = load_text(small_map)
    cm = Costmap(ws, solar_rate=0.0, layers={"slope": slope})
    cm.set_elevation(fractal_terrain(ws.shape, seed=2))
    np.testing.assert_array_equal(F, free_front(ws, names, costmap=cm).F)


def test_plan_keeps_its_layers_and_takes_user_layers(tmp_path, capsys):
    out = tmp_path / "p"
    argv = ["plan", "default", "--planner", "astar", "--layers", "elevation,solar,risk", "--risk", "10,12"]
    code, _, _ = run(capsys, argv + ["--no-plots", "--quiet", "--out", out])
    assert code == 0
    assert front_csv(out)[0] == ["length", "elevation", "solar", "risk"]
    s = settings(out)
    assert s["terrain"] == "fractal seed=1" and s["risk_cells"] == [[10, 12]] and s["solar_rate"] == 0.01
    assert s["costmap"]["layers"] == ["elevation", "solar", "risk"]
    # the planner's costs: the same path as the library's own planner
    from gapath.costmap import build_costmap
    from gapath.planners import plan

    ws = default_workspace()
    cm = build_costmap(ws, ["elevation", "solar", "risk"], risk=(10, 12))
    res = plan(ws, "astar", costmap=cm, objectives=("length", "elevation", "solar", "risk"))
    np.testing.assert_array_equal(paths_json(out)[0], res.cells)
    # a user layer
    np.save(tmp_path / "sand.npy", np.random.default_rng(3).random((32, 32)))
    out2 = tmp_path / "p2"
    argv = [
        "plan",
        "default",
        "--planner",
        "astar-po",
        "--layers",
        "sand",
        "--layer",
        f"sand={tmp_path / 'sand.npy'}",
    ]
    code, _, _ = run(capsys, argv + ["--no-plots", "--quiet", "--out", out2])
    assert code == 0
    assert front_csv(out2)[0] == ["length", "sand"]
    assert set(settings(out2)["costmap"]["user_layers"]) == {"sand"}
    # no layer, no costmap entry
    out3 = tmp_path / "p3"
    code, _, _ = run(
        capsys, ["plan", "default", "--planner", "astar", "--no-plots", "--quiet", "--out", out3]
    )
    assert code == 0 and "costmap" not in settings(out3)


# ---------------------------------------------------------------------------
# bad input: one message naming the flag and value, exit status 2
# ---------------------------------------------------------------------------


def _files(tmp_path):
    np.save(tmp_path / "ok32.npy", np.random.default_rng(1).random((32, 32)))
    np.save(tmp_path / "small.npy", np.random.default_rng(1).random((8, 8)))
    np.save(tmp_path / "flat.npy", np.arange(5.0))
    np.save(tmp_path / "neg.npy", -np.ones((32, 32)))
    nan = np.ones((32, 32))
    nan[3, 4] = np.nan
    np.save(tmp_path / "nan.npy", nan)
    (tmp_path / "garbage.npy").write_text("not an array")


BAD = [
    # unknown or misplaced objectives
    (["solve", "default", "--objectives", "length,height"], "--objectives: unknown objective 'height'"),
    (
        ["solve", "default", "--objectives", "length,risk,risk"],
        "--objectives: objective 'risk' is given twice",
    ),
    (
        ["solve", "default", "--objectives", "length,risk_sum"],
        "'risk_sum' (layer 'risk' summed over the path's cells) is an objective of gapath exact",
    ),
    (
        ["exact", "default", "--mode", "free", "--objectives", "length,risk_max"],
        "--objectives: 'risk_max' is the worst cell of the path, not a sum along it; the exact search minimises sums",
    ),
    (
        ["exact", "default", "--mode", "free", "--objectives", "length,elevation"],
        "--objectives: 'elevation' is the MEAN of layer 'elevation'",
    ),
    (
        ["exact", "default", "--objectives", "length,risk_sum"],
        "the exact monotone front has no costmap layers (risk_sum); add --mode free",
    ),
    (
        ["exact", "default", "--mode", "free", "--objectives", "length,slope_sum"],
        "--objectives: unknown objective 'slope_sum'",
    ),
    (["plan", "default", "--layers", "risk_max"], "--layers: 'risk_max' is the worst cell of the path"),
    # a layer flag without its objective
    (
        ["solve", "default", "--dem", "{d}/ok32.npy"],
        "--dem sets the elevation layer, which no objective uses: add elevation (or elevation_max) to --objectives",
    ),
    (
        ["exact", "default", "--mode", "free", "--risk", "3,3"],
        "--risk sets the risk layer, which no objective uses: add risk_sum to --objectives",
    ),
    (
        ["solve", "default", "--solar-rate", "0.5"],
        "--solar-rate sets the solar layer, which no objective uses",
    ),
    (
        ["solve", "default", "--terrain-seed", "4"],
        "--terrain-seed sets the elevation layer, which no objective uses",
    ),
    (
        ["solve", "default", "--objectives", "length,vulnerability", "--layer", "sand={d}/ok32.npy"],
        "--layer sand={d}/ok32.npy sets the user layer 'sand', which no objective uses: add sand (or sand_max) to --objectives",
    ),
    (
        [
            "solve",
            "default",
            "--objectives",
            "length,elevation",
            "--dem",
            "{d}/ok32.npy",
            "--terrain-seed",
            "2",
        ],
        "--terrain-seed 2 seeds the fractal terrain, which --dem {d}/ok32.npy replaces",
    ),
    (
        ["solve", "default", "--objectives", "length,elevation", "--dem-method", "reflect"],
        "--dem-method reflect applies to a --dem FILE",
    ),
    # DEM files
    (
        ["solve", "default", "--objectives", "length,elevation", "--dem", "{d}/missing.npy"],
        "--dem: DEM file '{d}/missing.npy' does not exist",
    ),
    (
        ["solve", "default", "--objectives", "length,elevation", "--dem", "{d}/garbage.npy"],
        "--dem: DEM file '{d}/garbage.npy' is not a NumPy .npy array",
    ),
    (
        [
            "exact",
            "default",
            "--mode",
            "free",
            "--objectives",
            "length,elevation_sum",
            "--dem",
            "{d}/flat.npy",
        ],
        "--dem: layer 'dem flat.npy' must be a non-empty 2-D array, got shape (5,)",
    ),
    (
        ["solve", "default", "--objectives", "length,elevation", "--dem", "{d}/nan.npy"],
        "--dem: layer 'dem nan.npy' holds NaN at (row 3, col 4)",
    ),
    # user layer files
    (
        ["solve", "default", "--objectives", "length,sand", "--layer", "sand={d}/small.npy"],
        "--layer sand={d}/small.npy: layer 'sand' must have the grid's shape (32, 32), got shape (8, 8)",
    ),
    (
        ["solve", "default", "--objectives", "length,sand", "--layer", "sand={d}/neg.npy"],
        "--layer sand={d}/neg.npy: layer 'sand' holds the negative value -1.0 at (row 0, col 0)",
    ),
    (
        [
            "exact",
            "default",
            "--mode",
            "free",
            "--objectives",
            "length,sand_sum",
            "--layer",
            "sand={d}/missing.npy",
        ],
        "--layer sand={d}/missing.npy: layer file '{d}/missing.npy' does not exist",
    ),
    (
        ["solve", "default", "--objectives", "length,sand", "--layer", "sand={d}/garbage.npy"],
        "layer file '{d}/garbage.npy' is not a NumPy .npy array",
    ),
    (
        [
            "solve",
            "default",
            "--objectives",
            "length,sand",
            "--layer",
            "sand={d}/ok32.npy",
            "--layer",
            "sand={d}/ok32.npy",
        ],
        "--layer: layer 'sand' is given twice",
    ),
    # risk cells and solar rates
    (
        ["solve", "default", "--objectives", "length,risk", "--risk", "99,3"],
        "--risk 99,3: risk cell (99, 3) is outside the 32x32 grid",
    ),
    (
        ["exact", "default", "--mode", "free", "--objectives", "length,solar", "--solar-rate", "nan"],
        "--solar-rate must be a finite number, got nan",
    ),
    (
        ["solve", "default", "--objectives", "length,solar", "--solar-rate", "inf"],
        "--solar-rate must be a finite number, got inf",
    ),
    (
        ["solve", "default", "--paths", "monotone", "--seed-from", "exact", "--objectives", "length,risk"],
        "--seed-from exact seeds from the exact monotone front, which has no costmap layers (risk)",
    ),
    # no exact reference front for a mean
    (
        ["solve", "default", "--objectives", "length,risk", "--reference", "free"],
        "--reference: no exact free front exists for objective 'risk'",
    ),
]


@pytest.mark.parametrize("argv,message", BAD, ids=[" ".join(a[:1] + a[-2:]) for a, _ in BAD])
def test_bad_costmap_input(argv, message, tmp_path, capsys):
    _files(tmp_path)
    d = str(tmp_path)
    out = tmp_path / "out"
    code, _, err = run(capsys, [a.replace("{d}", d) for a in argv] + ["--out", out, "--quiet"])
    assert code == EXIT_BAD_INPUT, err
    assert err.startswith("gapath: error: "), err
    assert message.replace("{d}", d) in err, err
    assert len(err.strip().splitlines()) == 1
    assert not (out / "front.csv").exists()


@pytest.mark.parametrize(
    "value,message",
    [
        ("sand", "expected NAME=FILE"),
        ("risk=x.npy", "layer name 'risk' is built in (--risk ROW,COL sets it)"),
        ("length=x.npy", "layer name 'length' is reserved"),
        ("sand_max=x.npy", "layer name 'sand_max' must not end in _max or _sum"),
        ("9lives=x.npy", "layer name '9lives' must start with a letter"),
    ],
)
def test_bad_layer_flag_is_a_usage_error(value, message, tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["solve", "default", "--layer", value, "--out", str(tmp_path / "o")])
    assert exc.value.code == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err


def test_exact_epsilon_writes_the_approximate_front(small_map, tmp_path, capsys):
    out = tmp_path / "a"
    argv = ["exact", small_map, "--mode", "free", "--objectives", "length,vulnerability,smoothness"]
    code, stdout, _ = run(capsys, argv + ["--epsilon", "0.1", "--no-plots", "--out", out])
    assert code == 0
    assert "approximate (epsilon 0.1) free front" in stdout
    header, F = front_csv(out)
    ef = free_front(load_text(small_map), header, epsilon=0.1)
    np.testing.assert_array_equal(F, ef.F)
    assert settings(out)["epsilon"] == 0.1
    exact = tmp_path / "e"
    code, stdout, _ = run(capsys, argv + ["--no-plots", "--out", exact])
    assert code == 0 and "exact free front" in stdout and "epsilon" not in settings(exact)


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--epsilon", "-1"], "expected a finite number >= 0, got '-1'"),
        (["--epsilon", "nan"], "expected a finite number >= 0, got 'nan'"),
        (["--epsilon", "x"], "expected a finite number >= 0, got 'x'"),
        (["--epsilon", "0.1"], "add --mode free"),
        (["--epsilon", "0.1", "--mode", "free"], "needs --objectives length,vulnerability,smoothness"),
    ],
)
def test_exact_bad_epsilon_exits_2(small_map, tmp_path, capsys, extra, message):
    try:
        code, _, err = run(capsys, ["exact", small_map, *extra, "--quiet", "--out", tmp_path / "o"])
    except SystemExit as exc:  # argparse's own errors
        code, err = exc.code, capsys.readouterr().err
    assert code == EXIT_BAD_INPUT
    assert message in err and err.count("error") == 1  # one message (after argparse's usage), no traceback
