"""The dense-obstacle reproduction (Ahmed & Deb, Table 1): seeded variant
and the report's list of runs without a feasible path."""

import numpy as np

from gapath import dense_workspace
from gapath.experiments import dense
from gapath.experiments.runner import FirstFeasible, run_experiment
from gapath.solver import solve


def test_table1_spec_seeded_variant_differs_only_in_seeding():
    plain = dense.table1_spec(grids=(8,), p0s=(0.5,), runs=2)
    seeded = dense.table1_spec(grids=(8,), p0s=(0.5,), runs=2, seed_from="weighted")
    a, b = plain.runs()[0], seeded.runs()[0]
    assert a["settings"]["seed_from"] == "none" and b["settings"]["seed_from"] == "weighted"
    assert {k: v for k, v in a["settings"].items() if k != "seed_from"} == \
        {k: v for k, v in b["settings"].items() if k != "seed_from"}
    assert a["map"] == b["map"] and a["seed"] == b["seed"]


def test_report_lists_unsuccessful_runs_and_seeded_column(tmp_path):
    # two generations on the densest 16x16 maps: some runs cannot find the
    # single free path in time, the planner-seeded ones always can
    kw = dict(grids=(16,), p0s=(1.0,), runs=6, n_gen=2)
    run_experiment(dense.table1_spec(**kw), tmp_path / "t1", workers=0, progress=False)
    run_experiment(dense.table1_spec(**kw, seed_from="weighted", name="s"), tmp_path / "seeded",
                   workers=0, progress=False)
    rep = dense.dense_report(tmp_path / "t1", tmp_path / "out", seeded_dir=tmp_path / "seeded")
    (row,) = rep["table1"]
    misses = rep["unsuccessful"].get((16, 1.0), [])
    assert misses, "expected some unseeded runs to fail in 2 generations"
    assert row["success_pct"] == 100 * (6 - len(misses)) / 6
    assert row["seeded_success_pct"] == 100 and row["seeded_median_generations"] == 1
    # recomputed independently: exactly the listed seeds find no feasible path
    for s in range(1, 7):
        cb = FirstFeasible(stop=True)
        solve(dense_workspace(16, 1.0, s), pop_size=200, n_gen=2, seed=s, seed_from="none",
              callback=cb)
        assert (cb.generation is None) == (s in misses), s
    md = (tmp_path / "out" / "dense.md").read_text()
    assert "SEEDED success %" in md
    assert f"- 16x16 p0 1: {', '.join(map(str, misses))}" in md
    csv_head = (tmp_path / "out" / "dense.csv").read_text().splitlines()[0].split(",")
    assert "seeded_success_pct" in csv_head


def test_unsuccessful_runs_empty_store_rows(tmp_path):
    run_experiment(dense.table1_spec(grids=(8,), p0s=(0.1,), runs=3, n_gen=50), tmp_path,
                   workers=0, progress=False)
    assert dense.unsuccessful_runs(tmp_path) == {}
    rows = dense._rows(tmp_path)
    assert rows[0]["success_pct"] == 100 and np.isfinite(rows[0]["median_generations"])
