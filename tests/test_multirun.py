import json

import numpy as np
import pytest

from gapath import ConfigError
from gapath.cli import main
from gapath.experiments import merge_fronts, multirun
from gapath.generators import random_workspace
from gapath.metrics import nondominated
from gapath.solver import objective_mode, solve


@pytest.fixture(scope="module")
def ws():
    return random_workspace((14, 14), 40, seed=8)


def test_multirun_merges_runs_into_one_nondominated_front(ws):
    m = multirun(ws, runs=3, seed=5, pop_size=30, n_gen=8, seed_from="none")
    assert m.seeds == [5, 6, 7] and len(m.runs) == 3
    F = m.front.F
    assert len(nondominated(F, tol=1e-9)) == len(F)
    # every run's front point is dominated by or equal to a merged point
    for r in m.runs:
        for f in r.front.F:
            assert ((F <= f + 1e-9).all(axis=1)).any()
    # merged points come from the runs, with the smoothest path per vector
    for f, met in zip(F, m.front.metrics):
        cands = [
            rm[2]
            for r in m.runs
            for rf, rm in zip(r.front.F, r.front.metrics)
            if np.allclose(rf, f, rtol=1e-9)
        ]
        assert cands and met[2] == min(cands)


def test_merge_rejects_mixed_objectives(ws):
    a = solve(ws, pop_size=20, n_gen=2).front
    b = solve(ws, objectives=("length", "smoothness"), pop_size=20, n_gen=2).front
    with pytest.raises(ConfigError, match="cannot merge"):
        merge_fronts([a, b])
    with pytest.raises(ConfigError, match="runs must be a positive integer"):
        multirun(ws, runs=0)


def test_merged_genomes_are_the_genomes_of_their_paths_or_none(ws):
    a = solve(ws, pop_size=20, n_gen=3).front
    b = solve(ws, pop_size=20, n_gen=3, seed=2).front
    both = merge_fronts([a, b])
    assert both.X.shape == (len(both.F), a.X.shape[1]) and a.X.shape[1] > 0
    rows = {tuple(x): tuple(map(tuple, p)) for f in (a, b) for x, p in zip(f.X, f.paths)}
    for x, p in zip(both.X, both.paths):
        assert rows[tuple(x)] == tuple(map(tuple, p))
    # a front without genomes (a free-path archive's) makes the merged front genome-free
    bare = type(b)(b.objectives, b.F, b.metrics, np.zeros((len(b.F), 0)), b.paths)
    merged = merge_fronts([a, bare])
    assert merged.X.shape == (len(merged.F), 0)


def test_objective_modes():
    assert objective_mode(("length",)) == dict(constraints="constraint", sbx_eta=2.0, tiebreak="smoothness")
    assert objective_mode("length,vulnerability")["constraints"] == "penalty"
    assert objective_mode(("length",), constraints="penalty", sbx_eta=5)["sbx_eta"] == 5


def test_single_objective_mode_finds_a_feasible_shortest_path(ws):
    from gapath.planners.exact import monotone_front

    r = solve(ws, objectives=("length",), pop_size=40, n_gen=15, seed=1)
    assert r.settings["constraints"] == "constraint" and r.settings["sbx_eta"] == 2.0
    assert len(r.front) == 1 and r.front.metrics[0, 3] == 0
    assert r.front.F[0, 0] >= monotone_front(ws, ("length",)).F[0, 0] - 1e-9


def test_three_objective_mode(ws):
    r = solve(
        ws, objectives=("length", "vulnerability", "smoothness"), tiebreak=None, pop_size=40, n_gen=8, seed=1
    )
    assert r.front.F.shape[1] == 3 and len(r.front) >= 1


def test_cli_runs_writes_each_run_and_is_reproducible(ws, tmp_path):
    from gapath.loaders import save_movingai

    mp = tmp_path / "m.map"
    save_movingai(ws, mp)
    outs = []
    for d in ("a", "b"):
        out = tmp_path / d
        assert (
            main(
                [
                    "solve",
                    str(mp),
                    "--runs",
                    "3",
                    "--seed",
                    "4",
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
        outs.append(out)
    for out in outs:
        assert sorted(p.name for p in (out / "runs").iterdir()) == ["4", "5", "6"]
        s = json.loads((out / "summary.json").read_text())
        assert s["seeds"] == [4, 5, 6] and s["settings"]["runs"] == 3
    names = ["front.csv", "paths.json", "front.png", "paths.png"]
    for rel in names + [f"runs/{k}/{n}" for k in (4, 5, 6) for n in names]:
        assert (outs[0] / rel).read_bytes() == (outs[1] / rel).read_bytes(), rel
