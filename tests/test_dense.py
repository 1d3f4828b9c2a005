"""The dense-obstacle reproduction (Ahmed & Deb, Table 1): one map per row
(or a new map per run), the seeded variant, the rows on other maps and the
report's list of runs without a feasible path."""

import numpy as np
import pytest

from gapath import dense_workspace
from gapath.cli import main
from gapath.experiments.runner import FirstFeasible, run_experiment
from gapath.experiments.store import ResultStore
from gapath.solver import solve
from gapath.studies import dense


def test_table1_spec_one_map_per_row_by_default():
    spec = dense.table1_spec(grids=(8, 16), p0s=(0.5, 1.0), runs=3)
    runs = spec.runs()
    assert len(runs) == 12
    assert {r["map"]["dense"]["seed"] for r in runs} == {dense.MAP_SEED}
    assert sorted({r["seed"] for r in runs}) == [1, 2, 3]
    # the maps of a grid nest: the same free path, more obstacles as p0 grows
    lo, hi = dense_workspace(16, 0.5, dense.MAP_SEED), dense_workspace(16, 1.0, dense.MAP_SEED)
    assert np.all(hi.occ[lo.occ]) and hi.n_obstacles > lo.n_obstacles
    per_run = dense.table1_spec(grids=(8,), p0s=(0.5,), runs=3, map_seed="run").runs()
    assert [r["map"]["dense"]["seed"] for r in per_run] == ["run"] * 3
    assert dense.table1_spec(grids=(8,), p0s=(0.5,), runs=1, map_seed=7).runs()[0]["map"] == {
        "dense": {"n": 8, "p0": 0.5, "seed": 7}
    }


@pytest.mark.parametrize("bad", [-1, 1.5, "one", True, None])
def test_table1_spec_rejects_bad_map_seed(bad):
    with pytest.raises(ValueError, match="map_seed: expected a non-negative integer or 'run'"):
        dense.table1_spec(grids=(8,), p0s=(0.5,), runs=1, map_seed=bad)


def test_table1_spec_seeded_variant_differs_only_in_seeding():
    plain = dense.table1_spec(grids=(8,), p0s=(0.5,), runs=2)
    seeded = dense.table1_spec(grids=(8,), p0s=(0.5,), runs=2, seed_from="weighted")
    a, b = plain.runs()[0], seeded.runs()[0]
    assert a["settings"]["seed_from"] == "none" and b["settings"]["seed_from"] == "weighted"
    assert {k: v for k, v in a["settings"].items() if k != "seed_from"} == {
        k: v for k, v in b["settings"].items() if k != "seed_from"
    }
    assert a["map"] == b["map"] and a["seed"] == b["seed"]


def _first_feasible(ws, seed, n_gen):
    cb = FirstFeasible(stop=True)
    solve(ws, pop_size=200, n_gen=n_gen, seed=seed, seed_from="none", callback=cb)
    return cb.generation


def test_report_lists_unsuccessful_runs_and_seeded_column(tmp_path):
    # two generations on the densest 16x16 map: some runs cannot find the
    # single free path in time, the planner-seeded ones always can
    kw = dict(grids=(16,), p0s=(1.0,), runs=6, n_gen=2)
    run_experiment(dense.table1_spec(**kw), tmp_path / "t1", workers=0, progress=False)
    run_experiment(
        dense.table1_spec(**kw, seed_from="weighted", name="s"),
        tmp_path / "seeded",
        workers=0,
        progress=False,
    )
    rep = dense.dense_report(tmp_path / "t1", tmp_path / "out", seeded_dir=tmp_path / "seeded")
    (row,) = rep["table1"]
    misses = rep["unsuccessful"].get((16, 1.0), [])
    assert misses, "expected some unseeded runs to fail in 2 generations"
    assert row["success_pct"] == 100 * (6 - len(misses)) / 6
    assert row["seeded_success_pct"] == 100 and row["seeded_median_generations"] == 1
    # one map, its exact obstacle count; recomputed independently: exactly
    # the listed GA seeds find no feasible path on it
    ws = dense_workspace(16, 1.0, dense.MAP_SEED)
    assert row["obstacles_mean"] == ws.n_obstacles
    for s in range(1, 7):
        assert (_first_feasible(ws, s, 2) is None) == (s in misses), s
    md = (tmp_path / "out" / "dense.md").read_text()
    assert "SEEDED success %" in md and "Why one map per row" in md
    assert f"- 16x16 p0 1: {', '.join(map(str, misses))}" in md
    assert f"dense_workspace(grid, p0, {dense.MAP_SEED})" in md
    csv_head = (tmp_path / "out" / "dense.csv").read_text().splitlines()[0].split(",")
    assert "seeded_success_pct" in csv_head and "map_seed" in csv_head


def test_report_other_maps_and_per_run_maps(tmp_path):
    kw = dict(grids=(16,), p0s=(0.9, 1.0), runs=4, n_gen=3)
    for m in (1, 2):
        run_experiment(
            dense.table1_spec(**kw, map_seed=m, name=f"m{m}"), tmp_path / f"m{m}", workers=0, progress=False
        )
    run_experiment(
        dense.table1_spec(**kw, map_seed="run", name="pr"), tmp_path / "pr", workers=0, progress=False
    )
    rep = dense.dense_report(
        tmp_path / "m1", tmp_path / "out", other_map_dirs=[tmp_path / "m2"], per_run_dir=tmp_path / "pr"
    )
    assert list(rep["other_maps"]) == [2]
    for p0 in (0.9, 1.0):
        # each map's row, recomputed from scratch with the GA seeds 1..4
        for m, rows in ((1, rep["table1"]), (2, rep["other_maps"][2])):
            (row,) = [r for r in rows if r["p0"] == p0]
            ws = dense_workspace(16, p0, m)
            ok = sum(_first_feasible(ws, s, 3) is not None for s in range(1, 5))
            assert row["success_pct"] == 100 * ok / 4 and row["obstacles_mean"] == ws.n_obstacles
        # a new map for every run: map seed = GA seed
        (row,) = [r for r in rep["per_run"] if r["p0"] == p0]
        ok = sum(_first_feasible(dense_workspace(16, p0, s), s, 3) is not None for s in range(1, 5))
        assert row["success_pct"] == 100 * ok / 4
    md = (tmp_path / "out" / "dense.md").read_text()
    assert "## The same rows on other maps" in md and "| map 1 | map 2 |" in md
    assert "## A new map for every run" in md
    parts = [line.split(",")[0] for line in (tmp_path / "out" / "dense.csv").read_text().splitlines()[1:]]
    assert parts == ["table1"] * 2 + ["table1-other-map"] * 2 + ["table1-per-run-maps"] * 2


def test_cli_map_seeds_and_per_run_maps(tmp_path):
    assert (
        main(
            [
                "experiment",
                "dense",
                "--quick",
                "--out",
                str(tmp_path),
                "--workers",
                "0",
                "--quiet",
                "--grids",
                "8",
                "--p0",
                "0.5",
                "--map-seeds",
                "3,1-2",
                "--per-run-maps",
                "--large-runs",
                "0",
            ]
        )
        == 0
    )
    for name, seed in (
        ("table1-map3", 3),
        ("table1-map1", 1),
        ("table1-map2", 2),
        ("table1-per-run-maps", "run"),
    ):
        assert ResultStore(tmp_path / name).spec().to_dict()["maps"] == [
            {"dense": {"n": 8, "p0": 0.5, "seed": seed}}
        ]
    md = (tmp_path / "dense.md").read_text()
    assert "dense_workspace(grid, p0, 3)" in md and "| map 3 | map 1 | map 2 |" in md


@pytest.mark.parametrize("bad", ["x", "3-1", "-2", ""])
def test_cli_rejects_bad_map_seeds(tmp_path, bad, capsys):
    with pytest.raises(SystemExit, match="--map-seeds: expected non-negative integers"):
        main(["experiment", "dense", "--quick", "--out", str(tmp_path), "--map-seeds", bad])


def test_unsuccessful_runs_empty_store_rows(tmp_path):
    run_experiment(
        dense.table1_spec(grids=(8,), p0s=(0.1,), runs=3, n_gen=50), tmp_path, workers=0, progress=False
    )
    assert dense.unsuccessful_runs(tmp_path) == {}
    rows = dense._rows(tmp_path)
    assert rows[0]["success_pct"] == 100 and np.isfinite(rows[0]["median_generations"])
