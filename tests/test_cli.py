import csv
import json
import os
import subprocess
import sys

import numba
import pytest

from gapath.cli import main
from gapath.loaders import load_text
from gapath.objectives import evaluate_path


@pytest.fixture
def text_map(tmp_path):
    rows = [
        "..........",
        "...#......",
        "......#...",
        "..#.......",
        ".....#..#.",
        ".#........",
        "....#.....",
        "..........",
    ]
    p = tmp_path / "small.txt"
    p.write_text("\n".join(rows) + "\n")
    return p


def test_solve_writes_all_outputs(text_map, tmp_path, capsys):
    out = tmp_path / "run"
    code = main(["solve", str(text_map), "--pop", "30", "--gen", "10", "--seed", "2", "--out", str(out)])
    assert code == 0
    for name in ("front.csv", "paths.json", "summary.json", "front.png", "paths.png"):
        assert (out / name).stat().st_size > 0, name
    rows = list(csv.reader((out / "front.csv").open()))
    assert rows[0] == ["length", "vulnerability"]
    records = json.loads((out / "paths.json").read_text())
    assert len(records) == len(rows) - 1 >= 1
    ws = load_text(text_map)
    for rec, row in zip(records, rows[1:]):
        m = evaluate_path(ws, rec["path"])
        assert m["interfering"] == 0
        assert rec["objectives"]["length"] == pytest.approx(m["length"], rel=1e-12)
        assert float(row[1]) == pytest.approx(m["vulnerability"], rel=1e-12)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["settings"]["pop_size"] == 30 and summary["settings"]["seed"] == 2
    assert summary["evaluations"] >= 30 * 10
    assert {"gapath", "pymoo", "numpy", "numba", "python"} <= set(summary["versions"])
    assert "shortest" in capsys.readouterr().out


def test_solve_is_reproducible(text_map, tmp_path):
    for d in ("a", "b"):
        assert (
            main(
                [
                    "solve",
                    str(text_map),
                    "--pop",
                    "20",
                    "--gen",
                    "6",
                    "--out",
                    str(tmp_path / d),
                    "--quiet",
                    "--no-plots",
                ]
            )
            == 0
        )
    for name in ("front.csv", "paths.json"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()


def test_solve_three_objectives_and_start_goal(text_map, tmp_path):
    out = tmp_path / "three"
    assert (
        main(
            [
                "solve",
                str(text_map),
                "--objectives",
                "length,vulnerability,smoothness",
                "--start",
                "7,1",
                "--goal",
                "0,8",
                "--tiebreak",
                "none",
                "--constraints",
                "constraint",
                "--pop",
                "20",
                "--gen",
                "5",
                "--out",
                str(out),
                "--quiet",
            ]
        )
        == 0
    )
    rows = list(csv.reader((out / "front.csv").open()))
    assert rows[0] == ["length", "vulnerability", "smoothness"]
    rec = json.loads((out / "paths.json").read_text())[0]
    assert rec["path"][0] == [7, 1] and rec["path"][-1] == [0, 8]


@pytest.mark.parametrize(
    "args,message",
    [
        (["solve", "missing.map"], "missing.map"),
        (["solve", "{map}", "--start", "9,0"], "start (9, 0) is outside the 8x10 grid"),
        (["solve", "{map}", "--goal", "1,3"], "goal (1, 3) is on an obstacle"),
        (["solve", "{map}", "--objectives", "length,speed"], "unknown objective 'speed'"),
        (["solve", "{map}", "--pop", "0"], "--pop must be an integer >= 1, got 0"),
        (["solve", "{map}", "--gen", "-3"], "--gen must be an integer >= 1, got -3"),
        (["solve", "{map}", "--encoding", "gray"], "unknown encoding 'gray'"),
        (["solve", "{bad}"], "line 2"),
        (
            ["solve", "{map}", "--constraints", "adaptive", "--engine", "pymoo"],
            "--constraints adaptive needs --engine fast",
        ),
        (["solve", "{map}", "--repair", "feasible-local"], "--repair feasible-local needs --paths monotone"),
        (["solve", "{map}", "--paths", "monotone", "--repair", "tidy"], "unknown repair 'tidy'"),
        (["solve", "{map}", "--refine", "-2"], "--refine must be auto, off or an integer >= 0, got '-2'"),
        (["solve", "{map}", "--refine", "lots"], "--refine must be auto, off or an integer >= 0"),
        (
            ["solve", "{map}", "--threads", "0"],
            "--threads: expected a number of threads (1 or more) or 'auto', got '0'",
        ),
        (["solve", "{map}", "--threads", "many"], "--threads: expected a number of threads"),
        (
            ["solve", "{map}", "--paths", "monotone", "--refine", "-1"],
            "--refine must be auto, off or an integer",
        ),
    ],
)
def test_bad_input_exits_2_with_a_clear_message(args, message, text_map, tmp_path, capsys):
    bad = tmp_path / "bad.txt"
    bad.write_text("....\n..x.\n....\n")
    args = [a.format(map=text_map, bad=bad) for a in args]
    assert main(args + ["--out", str(tmp_path / "o"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert message in err
    assert "Traceback" not in err


def test_cli_process_has_no_traceback(tmp_path):
    bad = tmp_path / "ragged.map"
    bad.write_text("type octile\nheight 2\nwidth 3\nmap\n...\n..\n")
    proc = subprocess.run(
        [sys.executable, "-m", "gapath.cli", "solve", str(bad)], capture_output=True, text=True
    )
    assert proc.returncode == 2
    assert "ragged.map" in proc.stderr and "line 6" in proc.stderr
    assert "Traceback" not in proc.stderr
    proc = subprocess.run(
        [sys.executable, "-m", "gapath.cli", "solve", "default", "--start", "x"],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2 and "ROW,COL" in proc.stderr


def test_exact_command_and_reference(text_map, tmp_path, capsys):
    ex = tmp_path / "exact"
    assert main(["exact", str(text_map), "--out", str(ex), "--quiet"]) == 0
    rows = list(csv.reader((ex / "front.csv").open()))
    assert rows[0] == ["length", "vulnerability"] and len(rows) > 1
    assert (ex / "paths.png").exists()
    ws = load_text(text_map)
    for rec in json.loads((ex / "paths.json").read_text()):
        assert evaluate_path(ws, rec["path"])["interfering"] == 0
    run = tmp_path / "run"
    assert (
        main(
            [
                "solve",
                str(text_map),
                "--pop",
                "40",
                "--gen",
                "10",
                "--out",
                str(run),
                "--reference",
                str(ex / "front.csv"),
                "--quiet",
                "--no-plots",
            ]
        )
        == 0
    )
    q = json.loads((run / "summary.json").read_text())["quality"]
    assert 0.0 < q["hv_ratio"] <= 1.0 + 1e-9
    assert q["reference_size"] == len(rows) - 1
    assert (
        main(
            [
                "solve",
                str(text_map),
                "--pop",
                "40",
                "--gen",
                "5",
                "--out",
                str(run),
                "--reference",
                "monotone",
                "--quiet",
                "--no-plots",
            ]
        )
        == 0
    )
    q2 = json.loads((run / "summary.json").read_text())["quality"]
    assert q2["reference"] == "monotone" and q2["reference_size"] == q["reference_size"]
    conv = (run / "convergence.csv").read_text().splitlines()
    assert conv[0] == "n_gen,n_eval,hv_ratio" and len(conv) == 1 + 5
    last = float(conv[-1].split(",")[2])
    assert last == pytest.approx(q2["hv_ratio"], rel=1e-9)


def test_reference_file_errors(text_map, tmp_path, capsys):
    bad = tmp_path / "front.csv"
    bad.write_text("length,smoothness\n1,2\n")
    assert (
        main(
            [
                "solve",
                str(text_map),
                "--pop",
                "10",
                "--gen",
                "2",
                "--out",
                str(tmp_path / "o"),
                "--reference",
                str(bad),
                "--quiet",
                "--no-plots",
            ]
        )
        == 2
    )
    assert "reference front has objectives" in capsys.readouterr().err
    bad.write_text("length,vulnerability\n1,x\n")
    assert (
        main(
            [
                "solve",
                str(text_map),
                "--pop",
                "10",
                "--gen",
                "2",
                "--out",
                str(tmp_path / "o"),
                "--reference",
                str(bad),
                "--quiet",
                "--no-plots",
            ]
        )
        == 2
    )
    assert "line 2" in capsys.readouterr().err


@pytest.mark.parametrize("planner", ["astar-po", "rrt"])
def test_plan_command(planner, text_map, tmp_path):
    out = tmp_path / planner
    assert main(["plan", str(text_map), "--planner", planner, "--out", str(out), "--quiet"]) == 0
    rec = json.loads((out / "paths.json").read_text())[0]
    assert rec["path"][0] == [7, 0] and rec["path"][-1] == [0, 9]
    assert (out / "summary.json").exists() and (out / "front.csv").exists()


@pytest.mark.parametrize("paths", ["free", "monotone"])
@pytest.mark.parametrize("flag,expected", [("7", 7), ("off", None), ("auto", 5)])
def test_solve_refine_flag_reaches_the_run(flag, expected, paths, text_map, tmp_path):
    out = tmp_path / "o"
    args = ["solve", str(text_map), "--pop", "10", "--gen", "3", "--refine", flag, "--out", str(out)]
    args += ["--paths", paths]  # monotone: the column re-routing archive (monotone_lift.md)
    assert main(args + ["--quiet", "--no-plots"]) == 0
    settings = json.loads((out / "summary.json").read_text())["settings"]
    if paths == "monotone" and flag == "auto":
        expected = 2  # pop // 5 re-routed paths (docs/results/monotone_lift.md)
    assert settings.get("refine") == expected  # auto: pop // 2 with two objectives


def test_solve_threads_flag_gives_the_serial_front(text_map, tmp_path, monkeypatch):
    monkeypatch.setenv("GAPATH_THREADS", "1")  # restored after the test
    fronts = {}
    for flag in ("1", "2"):
        out = tmp_path / flag
        args = ["solve", str(text_map), "--paths", "free", "--pop", "12", "--gen", "4", "--seed", "3"]
        assert main(args + ["--threads", flag, "--out", str(out), "--quiet", "--no-plots"]) == 0
        settings = json.loads((out / "summary.json").read_text())["settings"]
        assert settings["threads"] == min(int(flag), numba.get_num_threads())
        fronts[flag] = (out / "front.csv").read_text()
        assert os.environ["GAPATH_THREADS"] == "1"  # the flag holds for its run only
    assert fronts["1"] == fronts["2"]
