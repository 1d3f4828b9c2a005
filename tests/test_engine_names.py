"""One engine vocabulary (solve's ``fast`` and ``pymoo``), with the former
spec names ``paper`` and ``auto`` as aliases that keep every stored run key."""

import hashlib
import json

import pytest

from gapath.errors import ConfigError
from gapath.experiments.runner import run_experiment, run_one
from gapath.experiments.spec import (
    ENGINE_ALIASES,
    ENGINES,
    ExperimentSpec,
    canonical_json,
    config_key,
    load_spec,
    resolve_engine,
    run_key,
)


def _spec(engine):
    return ExperimentSpec(
        maps=[{"dense": {"n": 8, "p0": 0.3, "seed": "run"}}],
        engines=[engine],
        settings={"pop_size": 20, "n_gen": 5, "seed_from": "none"},
        seeds=[3],
    )


def _old_key(run, engine):
    """The key as computed before the engine names became solve's: the
    sha256 of the run's canonical JSON with the spec's name of its engine."""
    return hashlib.sha256(canonical_json(dict(run, engine=engine)).encode("ascii")).hexdigest()


def test_the_vocabulary_is_solves_and_the_old_names_are_aliases():
    from gapath.solver import ENGINES as SOLVE_ENGINES

    assert ENGINES == ("fast", "pymoo") and set(ENGINES) == set(SOLVE_ENGINES)
    assert ENGINE_ALIASES == {"paper": "pymoo", "auto": "fast"}
    assert [resolve_engine(e) for e in ("fast", "pymoo", "auto", "paper")] == ["fast", "pymoo"] * 2
    assert ExperimentSpec().to_dict()["engines"] == ["fast"]


@pytest.mark.parametrize(("old", "new"), [("paper", "pymoo"), ("auto", "fast")])
def test_old_engine_names_keep_their_run_keys(old, new):
    (run_old,), (run_new,) = _spec(old).runs(), _spec(new).runs()
    assert run_old == run_new and run_new["engine"] == new
    stored_name = "paper" if old == "paper" else "fast"  # what the spec stored before
    assert run_key(run_new) == _old_key(run_new, stored_name)
    # a run record of a store written before (engine under its old name)
    stored = json.loads(json.dumps(dict(run_new, engine=stored_name)))
    assert run_key(stored) == run_key(run_new) and config_key(stored) == config_key(run_new)


def test_the_pinned_key_of_a_paper_spec_is_unchanged():
    (run,) = _spec("paper").runs()
    assert run_key(run) == "5052aae65717b722049b90a7e70c417a02f05d2b35d1c1ccd7ed27ffadce0347"
    assert run_key(run) != run_key(_spec("fast").runs()[0])


def test_a_run_stored_under_the_old_name_still_runs_on_pymoo():
    (run,) = _spec("pymoo").runs()
    res = run_one(dict(run, engine="paper"))
    assert res["status"] == "ok" and res["settings"]["engine"] == "pymoo"
    assert res["key"] == run_key(run)
    bad = run_one(dict(run, engine="turbo"))
    assert bad["status"] == "failed" and "unknown engine 'turbo'" in bad["error"]


def test_a_store_written_with_the_old_names_keeps_its_files_and_resumes(tmp_path):
    from gapath.experiments.store import ResultStore

    spec_file = tmp_path / "old.yaml"
    spec_file.write_text(
        "name: old\nmaps: [{dense: {n: 8, p0: 0.3, seed: 1}}]\nengines: [paper, auto]\n"
        "settings: {pop_size: 10, n_gen: 3, seed_from: none}\nseeds: 2\n"
    )
    spec = load_spec(spec_file)
    out = tmp_path / "store"
    assert run_experiment(spec, out, workers=0, progress=False).ran == 4
    names = {"pymoo": "paper", "fast": "fast"}  # the names the spec stored before
    files = sorted(f.name for f in (out / "runs").glob("*.json"))
    assert files == sorted(f"{_old_key(r, names[r['engine']])}.json" for r in spec.runs())
    # a store of the former names: experiment.json and the run records say "paper"
    for f in [out / "experiment.json", *(out / "runs").glob("*.json")]:
        f.write_text(f.read_text().replace('"pymoo"', '"paper"'))
    saved = ResultStore(out).spec()
    assert saved.to_dict()["engines"] == ["pymoo", "fast"]
    assert ResultStore(out).status()["done"] == 4 and len(ResultStore(out).results()) == 4
    again = run_experiment(spec_file, out, workers=0, progress=False)
    assert again.ran == 0 and again.skipped == 4


def test_an_unknown_engine_names_the_choices():
    with pytest.raises(
        ConfigError, match=r"engines\[0\]: unknown engine 'turbo'; expected one of fast, pymoo"
    ):
        _spec("turbo")


# ---------------------------------------------------------------------------
# the engines read the problem's encoding (no separate encoding= needed)
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("encoding", ["integer", "binary", "mixed", "absolute"])
def test_paper_nsga2_takes_its_operators_from_the_problems_encoding(encoding):
    import numpy as np
    from pymoo.optimize import minimize

    from gapath.algorithms import FastNSGA2, paper_nsga2
    from gapath.generators import default_workspace
    from gapath.operators import default_operators
    from gapath.problems import GridPathProblem

    p = GridPathProblem(default_workspace(), encoding=encoding)
    algo = paper_nsga2(20)
    told = minimize(p, paper_nsga2(20, encoding=encoding), ("n_gen", 4), seed=3)
    read = minimize(p, algo, ("n_gen", 4), seed=3)
    fast = minimize(p, FastNSGA2(20), ("n_gen", 4), seed=3)
    for res in (read, fast):
        np.testing.assert_array_equal(res.pop.get("X"), told.pop.get("X"))
        np.testing.assert_array_equal(res.pop.get("F"), told.pop.get("F"))
    ops, algo = default_operators(encoding), read.algorithm  # minimize set up a copy
    assert type(algo.mating.crossover) is type(ops["crossover"])
    assert type(algo.mating.mutation) is type(ops["mutation"])
    assert type(algo.initialization.sampling) is type(ops["sampling"])


def test_paper_nsga2_keeps_a_given_sampling_when_it_reads_the_encoding():
    import numpy as np
    from pymoo.optimize import minimize

    from gapath.algorithms import paper_nsga2
    from gapath.generators import default_workspace
    from gapath.problems import GridPathProblem

    p = GridPathProblem(default_workspace(), encoding="binary")
    rng = np.random.default_rng(0)
    X = p.encoding.edge_fix(rng.random((12, p.n_var)) < 0.5, np.random.default_rng(1))
    res = minimize(p, paper_nsga2(12, sampling=X), ("n_gen", 1), seed=1)
    assert res.pop.get("X").dtype == bool and len(res.pop) == 12
