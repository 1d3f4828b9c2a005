"""Every bad input gives one message and exit 2; every search that finds
nothing gives its reason and exit 1 (README, "Exit status")."""

import importlib
import json
import os
import stat
import subprocess
import sys
import warnings

import numpy as np
import pytest

from gapath.cli.main import build_parser, main
from gapath.errors import EXIT_BAD_INPUT, EXIT_INTERNAL, EXIT_INTERRUPTED, EXIT_NO_RESULT
from gapath.loaders import load_map
from gapath.objectives import evaluate_path


def write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return p


def strict_json(path):
    """Parse a JSON file, failing on NaN / Infinity tokens."""

    def refuse(token):
        raise AssertionError(f"{path.name} holds {token}")

    return json.loads(path.read_text(), parse_constant=refuse)


def run(capsys, args):
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    return code, out, err


# every route from (0, 0) to (0, 4) must step back from column 2 to columns 1 and 0
BACKTRACK = "...#.\n##.#.\n...#.\n.###.\n.....\n"
BACKTRACK_ARGS = ["--start", "0,0", "--goal", "0,4"]


# ---------------------------------------------------------------------------
# section 3: tiny maps are solved, not crashed on
# ---------------------------------------------------------------------------

TINY = {
    "free3": "...\n...\n...\n",
    "row1x5": ".....\n",
    "col4x1": ".\n.\n.\n.\n",
    "free3x5": ".....\n.....\n.....\n",
    "u3": ".#.\n.#.\n...\n",
}


@pytest.mark.parametrize("engine", ["fast", "pymoo"])
@pytest.mark.parametrize("name", sorted(TINY))
def test_tiny_maps_are_solved(name, engine, tmp_path, capsys):
    path = write(tmp_path, f"{name}.txt", TINY[name])
    out = tmp_path / "out"
    code, _, err = run(
        capsys,
        ["solve", path, "--pop", 20, "--gen", 5, "--engine", engine, "--out", out, "--quiet", "--no-plots"],
    )
    assert code == 0, err
    ws = load_map(path)
    records = strict_json(out / "paths.json")
    assert records
    for rec in records:
        assert tuple(rec["path"][0]) == ws.start and tuple(rec["path"][-1]) == ws.goal
        assert evaluate_path(ws, rec["path"])["interfering"] == 0
    assert strict_json(out / "summary.json")["front_size"] == len(records)


def test_early_end_on_a_tiny_map_is_reported(tmp_path, capsys):
    path = write(tmp_path, "free3.txt", TINY["free3"])
    code, out, _ = run(
        capsys, ["solve", path, "--pop", 20, "--gen", 5, "--out", tmp_path / "o", "--no-plots"]
    )
    assert code == 0
    n_gen = strict_json(tmp_path / "o" / "summary.json")["generations"]
    assert n_gen < 5 and "stopped before generation 5" in out


def test_sampling_stops_at_the_distinct_paths_of_a_tiny_map():
    from gapath import Workspace
    from gapath.operators import PlannerSampling
    from gapath.problems import GridPathProblem

    p = GridPathProblem(Workspace(np.zeros((3, 3), bool)))
    for source in ("weighted", "none"):
        X = PlannerSampling(source)._do(p, 50, random_state=np.random.default_rng(1))
        entries, exits = p.encoding.decode(X)
        keys = {tuple(k) for k in np.concatenate([entries, exits], axis=1)}
        assert 1 <= len(X) < 50  # fewer distinct paths than asked
        assert len(keys) == len(X)  # all distinct, no padding with copies


def test_duplicate_mask_of_nothing_is_empty():
    from gapath.operators.duplicates import duplicate_mask

    assert duplicate_mask(np.zeros((0, 3), int)).shape == (0,)
    assert duplicate_mask(np.zeros((0, 3), int), np.ones((2, 3), int)).shape == (0,)
    assert duplicate_mask(np.ones((2, 3), int), np.zeros((0, 3), int)).tolist() == [False, True]


# ---------------------------------------------------------------------------
# section 3: numeric flags, files, values
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "args,message",
    [
        (["solve", "default", "--sbx-eta", "-1"], "--sbx-eta must be a number >= 0, got -1.0"),
        (["solve", "default", "--sbx-eta", "nan"], "--sbx-eta must be a finite number, got nan"),
        (["solve", "default", "--penalty", "inf"], "--penalty must be a finite number, got inf"),
        (["solve", "default", "--seed", "-1"], "--seed must be an integer >= 0, got -1"),
        (["solve", "default", "--runs", "0"], "--runs must be an integer >= 1, got 0"),
        (["demo", "--pop", "0"], "--pop must be an integer >= 1, got 0"),
        (["simulate", "warehouse", "--map-seed", "-1"], "--map-seed must be an integer >= 0, got -1"),
        (["simulate", "maze", "--fov", "200"], "--fov must be a number in (0, 180], got 200.0"),
        (["simulate", "maze", "--dt", "0"], "--dt must be a number > 0, got 0.0"),
        (
            ["plan", "default", "--goal-bias", "2", "--planner", "rrt"],
            "--goal-bias must be a number in [0, 1], got 2.0",
        ),
        (["plan", "default", "--terrain-seed", "-5"], "--terrain-seed must be an integer >= 0, got -5"),
        (["plan", "default", "--solar-rate", "nan"], "--solar-rate must be a finite number, got nan"),
        (
            ["plan", "default", "--max-steer", "90", "--planner", "hybrid-astar"],
            "--max-steer must be a number in (0, 90), got 90.0",
        ),
    ],
)
def test_numeric_flags_are_checked_by_name(args, message, tmp_path, capsys):
    out = tmp_path / "never"
    code, _, err = run(capsys, args + ["--out", out, "--quiet"])
    assert code == EXIT_BAD_INPUT
    assert err.strip() == f"gapath: error: {message}"
    assert not out.exists()  # rejected before anything ran


@pytest.fixture
def binary_file(tmp_path):
    p = tmp_path / "blob.bin"
    p.write_bytes(bytes(range(128, 256)) * 8)
    return p


@pytest.mark.parametrize("suffix", [".csv", ".bin"])
def test_binary_reference_is_named(suffix, binary_file, tmp_path, capsys):
    ref = binary_file.rename(binary_file.with_suffix(suffix))
    code, _, err = run(
        capsys,
        ["solve", "default", "--reference", ref, "--pop", 10, "--gen", 2, "--out", tmp_path / "o", "--quiet"],
    )
    assert code == EXIT_BAD_INPUT
    assert f"--reference: {ref}: not a text front.csv" in err


@pytest.mark.parametrize("suffix", [".yaml", ".toml", ".dat"])
def test_binary_experiment_spec_is_named(suffix, binary_file, tmp_path, capsys):
    spec = binary_file.rename(binary_file.with_suffix(suffix))
    code, _, err = run(
        capsys, ["experiment", "run", spec, "--out", tmp_path / "store", "--quiet", "--workers", "0"]
    )
    assert code == EXIT_BAD_INPUT
    assert f"{spec}: not a text file" in err


def test_dem_files_are_checked(tmp_path, capsys):
    garbage = write(tmp_path, "garbage.npy", "garbage")
    objects = tmp_path / "objects.npy"
    np.save(objects, np.array([{"a": 1}], dtype=object))
    good = tmp_path / "good.npy"
    np.save(good, np.random.default_rng(1).random((12, 9)))
    cases = [
        (garbage, "is not a NumPy .npy array"),
        (objects, "holds Python objects (pickled)"),
        (tmp_path / "missing.npy", "does not exist"),
        (good.with_suffix(".tif"), "must be .npy or .npz"),
    ]
    for dem, message in cases:
        code, _, err = run(
            capsys,
            [
                "plan",
                "default",
                "--planner",
                "astar",
                "--layers",
                "elevation",
                "--dem",
                dem,
                "--out",
                tmp_path / "o",
                "--quiet",
            ],
        )
        assert code == EXIT_BAD_INPUT, dem
        assert err.startswith(f"gapath: error: --dem: DEM file '{dem}'") and message in err
    code, _, _ = run(
        capsys,
        [
            "plan",
            "default",
            "--planner",
            "astar",
            "--layers",
            "elevation",
            "--dem",
            good,
            "--out",
            tmp_path / "o",
            "--quiet",
        ],
    )
    assert code == 0


def test_experiment_spec_start_and_goal_are_checked_when_read(tmp_path, capsys):
    for entry, message in [
        ("{default: {start: [40, 0]}}", "maps[0].default: start (40, 0) is outside the 32x32 grid"),
        ("{default: {goal: [0, 0]}}", "maps[0].default: goal (0, 0) is on an obstacle"),
        (
            "{dense: {n: 8, p0: 0.3, seed: run, start: [9, 0]}}",
            "maps[0].dense: start (9, 0) is outside the 8x8 grid",
        ),
    ]:
        spec = write(
            tmp_path,
            "bad.yaml",
            f"name: bad\nmaps: [{entry}]\nsettings: {{pop_size: 10, n_gen: 2}}\nseeds: 2\n",
        )
        store = tmp_path / "store"
        code, _, err = run(capsys, ["experiment", "run", spec, "--out", store, "--quiet", "--workers", "0"])
        assert code == EXIT_BAD_INPUT
        assert message in err
        assert not (store / "experiment.json").exists()


# ---------------------------------------------------------------------------
# section 4: exit statuses
# ---------------------------------------------------------------------------


def test_solve_without_a_monotone_path_exits_1_with_the_reason(tmp_path, capsys):
    m = write(tmp_path, "back.txt", BACKTRACK)
    out = tmp_path / "out"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no leaked matplotlib legend warning
        code, _, err = run(
            capsys,
            [
                "solve",
                m,
                *BACKTRACK_ARGS,
                "--paths",
                "monotone",
                "--pop",
                10,
                "--gen",
                3,
                "--reference",
                "free",
                "--out",
                out,
                "--quiet",
            ],
        )
    assert code == EXIT_NO_RESULT
    assert err.startswith(
        "gapath: no column-monotone path joins (0, 0) and (0, 4); every route "
        "must step back a column -- try `--paths free` (the GA over all simple "
        "8-connected paths) or `gapath exact "
    )
    assert f"{m} --mode free --start 0,0 --goal 0,4`" in err
    summary = strict_json(out / "summary.json")  # the empty front is written, strictly
    assert summary["front_size"] == 0
    assert summary["quality"]["igd_plus"] is None
    assert summary["quality"]["hv_ratio"] == 0.0
    assert (out / "front.png").exists() and (out / "paths.png").exists()


def test_solve_finds_free_paths_where_no_monotone_path_exists(tmp_path, capsys):
    m = write(tmp_path, "back.txt", BACKTRACK)
    out = tmp_path / "out"
    code, _, err = run(
        capsys,
        [
            "solve",
            m,
            *BACKTRACK_ARGS,
            "--pop",
            10,
            "--gen",
            3,
            "--reference",
            "free",
            "--out",
            out,
            "--quiet",
        ],
    )
    assert code == 0, err
    summary = strict_json(out / "summary.json")
    assert summary["settings"]["paths"] == "free" and summary["front_size"] >= 1


def test_exact_monotone_without_path_suggests_free_mode(tmp_path, capsys):
    m = write(tmp_path, "back.txt", BACKTRACK)
    code, _, err = run(capsys, ["exact", m, *BACKTRACK_ARGS, "--out", tmp_path / "o", "--quiet"])
    assert code == EXIT_NO_RESULT
    assert "every route must step back a column -- try --mode free" in err
    code, _, _ = run(
        capsys, ["exact", m, *BACKTRACK_ARGS, "--mode", "free", "--out", tmp_path / "o", "--quiet"]
    )
    assert code == 0


@pytest.mark.parametrize(
    "args",
    [
        ["solve", "--pop", "10", "--gen", "2"],
        ["exact"],
        ["exact", "--mode", "free"],
        ["plan", "--planner", "astar"],
        ["plan", "--planner", "dstar-po"],
    ],
)
def test_disconnected_start_and_goal_exit_1(args, tmp_path, capsys):
    m = write(tmp_path, "wall.txt", "S###G\n")
    code, _, err = run(capsys, [args[0], m, *args[1:], "--out", tmp_path / "o", "--quiet"])
    assert code == EXIT_NO_RESULT
    assert err.startswith("gapath: no path") and "(0, 0)" in err and "(0, 4)" in err
    assert "check the map, --start and --goal" in err


def test_no_corner_cutting_hint(tmp_path, capsys):
    m = write(tmp_path, "diag.txt", ".#\n#.\n")
    args = ["--start", "0,0", "--goal", "1,1", "--out", tmp_path / "o", "--quiet"]
    code, _, err = run(capsys, ["solve", m, "--no-corner-cutting", "--pop", 8, "--gen", 2, *args])
    assert code == EXIT_NO_RESULT
    assert "corner cutting not allowed" in err and "try --corner-cutting" in err
    code, _, _ = run(capsys, ["solve", m, "--corner-cutting", "--pop", 8, "--gen", 2, *args])
    assert code == 0


def test_ga_that_finds_nothing_says_so(tmp_path, capsys, monkeypatch):
    import gapath.solver
    from gapath.front import PathFront

    real = gapath.solver.solve

    def empty_front(workspace, **kw):  # a run that ends without a feasible path
        res = real(workspace, **kw)
        f = res.front
        res.front = PathFront(f.objectives, f.F[:0], f.metrics[:0], f.X[:0], [])
        return res

    monkeypatch.setattr(gapath.solver, "solve", empty_front)
    code, _, err = run(
        capsys,
        ["solve", "default", "--pop", 10, "--gen", 2, "--out", tmp_path / "o", "--quiet", "--no-plots"],
    )
    assert code == EXIT_NO_RESULT
    assert "the GA found no feasible path" in err and "column-monotone paths join" in err
    assert "try --seed-from weighted" in err


def test_plan_rrt_without_path_suggests_iterations(tmp_path, capsys):
    m = write(tmp_path, "wall.txt", "S###G\n")
    code, _, err = run(
        capsys, ["plan", m, "--planner", "rrt", "--iterations", 50, "--out", tmp_path / "o", "--quiet"]
    )
    assert code == EXIT_NO_RESULT
    assert "RRT found no path" in err and "try more --iterations (now 50)" in err


def test_simulate_failure_exits_1_with_the_reason_also_when_quiet(tmp_path, capsys):
    out = tmp_path / "sim"
    code, _, err = run(
        capsys, ["simulate", "maze", "--max-time", "0.5", "--out", out, "--quiet", "--no-plots"]
    )
    assert code == EXIT_NO_RESULT
    assert err.startswith("gapath: the robot did not reach the goal: ")
    summary = strict_json(out / "summary.json")
    assert summary["success"] is False
    m = write(tmp_path, "wall.txt", "S###G\n")
    code, _, err = run(capsys, ["simulate", m, "--out", out, "--quiet", "--no-plots"])
    assert code == EXIT_NO_RESULT and "has no path from start to goal" in err


def test_internal_error_and_interrupt(tmp_path, capsys, monkeypatch):
    def crash(args, workspace):
        raise ZeroDivisionError("division by zero")

    monkeypatch.setattr(importlib.import_module("gapath.cli.main"), "_run", crash)
    monkeypatch.delenv("GAPATH_TRACEBACK", raising=False)
    code, _, err = run(capsys, ["solve", "default", "--out", tmp_path / "o"])
    assert code == EXIT_INTERNAL
    assert err.startswith("gapath: internal error: ZeroDivisionError: division by zero")

    def interrupted(args, workspace):
        raise KeyboardInterrupt

    monkeypatch.setattr(importlib.import_module("gapath.cli.main"), "_run", interrupted)
    code, _, err = run(capsys, ["solve", "default", "--out", tmp_path / "o"])
    assert code == EXIT_INTERRUPTED and "interrupted" in err


def test_exit_codes_of_the_process(tmp_path):
    m = write(tmp_path, "back.txt", BACKTRACK)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "gapath.cli",
            "exact",
            str(m),
            *BACKTRACK_ARGS,
            "--out",
            str(tmp_path / "o"),
            "--quiet",
        ],
        capture_output=True,
        text=True,
        env=env,
    )
    assert proc.returncode == 1 and "Traceback" not in proc.stderr
    assert "step back a column" in proc.stderr
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "gapath.cli",
            "solve",
            "default",
            "--sbx-eta",
            "-1",
            "--out",
            str(tmp_path / "o2"),
        ],
        capture_output=True,
        text=True,
        env=env,
    )
    assert (
        proc.returncode == 2
        and proc.stderr.strip() == "gapath: error: --sbx-eta must be a number >= 0, got -1.0"
    )


def test_version(capsys):
    from importlib import metadata

    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0
    out = capsys.readouterr().out.strip()
    try:
        expected = metadata.version("gapath")
    except metadata.PackageNotFoundError:
        import gapath

        expected = gapath.__version__
    assert out == f"gapath {expected}"


# ---------------------------------------------------------------------------
# section 4: strict JSON, output directory, umask
# ---------------------------------------------------------------------------


def test_dumps_is_strict():
    from gapath.results import dumps

    text = dumps(
        {
            "a": float("inf"),
            "b": [np.nan, np.float64(1.5), np.int64(2)],
            "c": np.array([[1.0, -np.inf]]),
            "d": (np.True_, None),
        },
        sort_keys=True,
    )
    assert json.loads(text, parse_constant=lambda t: pytest.fail(t)) == {
        "a": None,
        "b": [None, 1.5, 2],
        "c": [[1.0, None]],
        "d": [True, None],
    }


def test_no_json_writer_bypasses_the_strict_helper():
    import pathlib

    import gapath

    src = pathlib.Path(gapath.__file__).parent
    offenders = []
    for p in src.rglob("*.py"):
        text = p.read_text()
        for i in [i for i in range(len(text)) if text.startswith("json.dump", i)]:
            call = text[i : text.find(")\n", i)]  # strict either way: the helper or allow_nan
            if p.name != "results.py" and "allow_nan=False" not in call:
                offenders.append(f"{p.relative_to(src)}:{text.count(chr(10), 0, i) + 1}")
    assert offenders == []


@pytest.mark.parametrize(
    "command",
    [
        ["solve", "default"],
        ["exact", "default"],
        ["plan", "default"],
        ["simulate", "maze"],
        ["experiment", "encodings", "--quick"],
    ],
)
def test_unusable_output_directory_is_refused_before_computing(command, tmp_path, capsys, monkeypatch):
    import gapath.solver

    def never(*a, **k):
        raise AssertionError("computed before checking --out")

    monkeypatch.setattr(gapath.solver, "solve", never)
    afile = write(tmp_path, "afile", "x")
    for out, message in [
        (afile, f"--out '{afile}' is a file; expected a directory"),
        (afile / "sub", f"--out '{afile / 'sub'}' is below '{afile}', a file"),
    ]:
        code, _, err = run(capsys, command + ["--out", out])
        assert code == EXIT_BAD_INPUT
        assert err.startswith(f"gapath: error: {message}")


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="root writes into read-only directories")
def test_read_only_output_directory_is_refused(tmp_path, capsys):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        code, _, err = run(capsys, ["solve", "default", "--out", ro / "run", "--quiet"])
    finally:
        ro.chmod(0o755)
    assert code == EXIT_BAD_INPUT and "cannot write there" in err


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="needs Linux /proc")
def test_unwritable_output_directory_is_refused(tmp_path, capsys):
    code, _, err = run(capsys, ["solve", "default", "--out", "/proc/self/gapath-out", "--quiet"])
    assert code == EXIT_BAD_INPUT and "--out '/proc/self/gapath-out': cannot write there" in err


@pytest.mark.skipif(os.name != "posix", reason="POSIX permissions")
@pytest.mark.parametrize("umask,mode", [(0o022, 0o644), (0o027, 0o640), (0o002, 0o664)])
def test_output_files_honour_the_umask(umask, mode, tmp_path, capsys):
    m = write(tmp_path, "free3.txt", TINY["free3"])
    old = os.umask(umask)
    try:
        code, _, _ = run(capsys, ["solve", m, "--pop", 8, "--gen", 2, "--out", tmp_path / "o", "--quiet"])
    finally:
        os.umask(old)
    assert code == 0
    for name in ("front.csv", "paths.json", "summary.json", "front.png", "paths.png"):
        assert stat.S_IMODE((tmp_path / "o" / name).stat().st_mode) == mode, name


# ---------------------------------------------------------------------------
# section 4: experiment outputs and stores
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "argv,default",
    [
        (["experiment", "encodings", "--quick"], "gapath-encodings"),
        (["experiment", "dynamic", "--quick"], "gapath-dynamic"),
    ],
)
def test_experiments_do_not_default_to_docs_results(argv, default):
    assert build_parser().parse_args(argv).out == default


def test_experiment_store_of_another_spec_needs_force(tmp_path, capsys):
    a = write(tmp_path, "A.yaml", "name: a\nmaps: [default]\nsettings: {pop_size: 10, n_gen: 2}\nseeds: 1\n")
    b = write(tmp_path, "B.yaml", "name: b\nmaps: [default]\nsettings: {pop_size: 12, n_gen: 2}\nseeds: 1\n")
    store = tmp_path / "store"
    opts = ["--out", store, "--workers", 0, "--quiet", "--no-report"]
    assert run(capsys, ["experiment", "run", a, *opts])[0] == 0
    assert run(capsys, ["experiment", "run", a, *opts])[0] == 0  # resuming is fine
    code, _, err = run(capsys, ["experiment", "run", b, *opts])
    assert code == EXIT_BAD_INPUT
    assert "holds the experiment 'a' of another spec (name, settings differ; 1 of its 1 runs" in err
    assert "--force" in err
    assert json.loads((store / "experiment.json").read_text())["name"] == "a"
    assert run(capsys, ["experiment", "run", b, *opts, "--force"])[0] == 0
    assert json.loads((store / "experiment.json").read_text())["name"] == "b"
    other = tmp_path / "other"
    assert (
        run(capsys, ["experiment", "run", a, "--out", other, "--workers", 0, "--quiet", "--no-report"])[0]
        == 0
    )
    code, _, err = run(capsys, ["experiment", "run", other, *opts])  # a store as SPEC
    assert code == EXIT_BAD_INPUT and "holds the experiment 'b' of another spec" in err
    more = write(
        tmp_path, "B2.yaml", "name: b2\nmaps: [default]\nsettings: {pop_size: 12, n_gen: 2}\nseeds: 3\n"
    )  # the same experiment, grown
    code, _, err = run(capsys, ["experiment", "run", more, "--out", store, "--workers", 0, "--no-report"])
    assert code == 0 and "extending the experiment 'b'" in err and "2 new runs" in err
    assert json.loads((store / "experiment.json").read_text())["seeds"] == [1, 2, 3]


def test_experiment_with_failed_runs_exits_1(tmp_path, capsys, monkeypatch):
    import gapath.solver

    def broken(*a, **k):
        raise RuntimeError("boom")

    monkeypatch.setattr(gapath.solver, "solve", broken)
    spec = write(
        tmp_path, "A.yaml", "name: a\nmaps: [default]\nsettings: {pop_size: 10, n_gen: 2}\nseeds: 2\n"
    )
    code, _, err = run(
        capsys, ["experiment", "run", spec, "--out", tmp_path / "s", "--workers", 0, "--quiet", "--no-report"]
    )
    assert code == EXIT_NO_RESULT
    assert "gapath: 2 of 2 runs failed" in err


def test_mars_terrain_is_labelled_and_a_missing_dtm_fails(tmp_path, capsys, monkeypatch):
    from gapath.studies import mars

    monkeypatch.setattr(mars, "find_mars_dtm", lambda: None)
    code, _, err = run(
        capsys, ["experiment", "mars", "--terrain", "mars", "--quick", "--out", tmp_path / "m"]
    )
    assert code == EXIT_BAD_INPUT
    assert err.startswith("gapath: error: --terrain mars: the Mars DTM dem/mars_dtm.npy was not found")
    study = mars.mars_study(1, size=20, ga_pop=8, ga_gen=2)
    assert study.settings["terrain"] == mars.FALLBACK_TERRAIN
    assert study.records[0]["terrain"].startswith("fractal")
    text = mars._markdown(study, mars.study_stats(study.records))
    assert "seeded fractal terrain" in text and "was not found" in text
    assert "elevation windows of the HiRISE Mars DTM" not in text


def test_argument_type_message_exits_2(tmp_path, capsys):
    with pytest.raises(SystemExit, match="--map-seeds: expected non-negative integers") as info:
        main(["experiment", "dense", "--quick", "--out", str(tmp_path), "--map-seeds", "x"])
    assert info.value.code == EXIT_BAD_INPUT
    assert "--map-seeds: expected non-negative integers" in capsys.readouterr().err
