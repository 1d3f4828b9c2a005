"""gapath as a pymoo plug-in: what a pymoo user relies on.

* Algorithms and results pickle (checkpoints, multiprocessing), and a
  pickled checkpoint resumes to the same population as an uninterrupted run.
* ``problem.pareto_front()`` is the exact front of the problem's path set in
  its objective space, so pymoo's IGD/GD/HV and verbose output use it; it is
  never computed unasked on a large map.
* Stock float operators on an integer encoding warn once per problem;
  gapath's own operators never do.
* The README's pymoo example runs as written (smaller budget).
"""

from __future__ import annotations

import pickle
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.indicators.gd import GD
from pymoo.indicators.hv import HV
from pymoo.indicators.igd import IGD
from pymoo.optimize import minimize
from pymoo.termination.max_gen import MaximumGenerationTermination

import gapath.planners.exact as exact
from gapath import ConfigError, NoPathError, Workspace, default_workspace
from gapath.algorithms import FastNSGA2, paper_nsga2
from gapath.costmap import Costmap
from gapath.encodings import ENCODINGS
from gapath.front import path_front
from gapath.generators import random_workspace
from gapath.operators import PlannerSampling, SmoothnessTournament
from gapath.problems import GenomeWarning, GridPathProblem
from gapath.problems.grid_path import EXACT_FRONT_AUTO_CELLS

README = Path(__file__).resolve().parents[1] / "README.md"
ENGINES = {"paper_nsga2": paper_nsga2, "FastNSGA2": FastNSGA2}


def sorted_rows(A):
    A = np.asarray(A)
    return A[np.lexsort(A.T[::-1])]


def roundtrip(obj):
    return pickle.loads(pickle.dumps(obj))


# ---------------------------------------------------------------------------
# pickling
# ---------------------------------------------------------------------------


def test_tournament_comparison_pickles_without_its_cache():
    sel = SmoothnessTournament(tiebreak=False)
    again = roundtrip(sel)
    assert again.tiebreak is False and again.func_comp.tiebreak is False
    assert again.func_comp._cache._pop is None


@pytest.mark.parametrize("engine", ENGINES)
def test_algorithm_and_result_pickle_before_and_after_minimize(engine):
    make = ENGINES[engine]
    problem = GridPathProblem(default_workspace())
    fresh = roundtrip(make(pop_size=20))  # before minimize
    res = minimize(problem, make(pop_size=20), ("n_gen", 6), seed=3)
    res_unpickled = minimize(problem, fresh, ("n_gen", 6), seed=3)
    assert np.array_equal(res.pop.get("X"), res_unpickled.pop.get("X"))
    again = roundtrip(res)  # pymoo's Result
    assert np.array_equal(again.F, res.F) and np.array_equal(again.X, res.X)
    assert np.array_equal(again.pop.get("X"), res.pop.get("X"))
    assert type(again.algorithm) is type(res.algorithm)  # after minimize
    assert np.array_equal(roundtrip(res.algorithm).pop.get("F"), res.pop.get("F"))


@pytest.mark.parametrize("engine", ENGINES)
def test_pickled_checkpoint_resumes_like_an_uninterrupted_run(engine):
    """pymoo's checkpoint recipe: run, pickle the algorithm, load, extend the
    termination, run on; same seed, same population as one long run."""
    make = ENGINES[engine]
    problem = GridPathProblem(default_workspace())
    straight = minimize(problem, make(pop_size=20), ("n_gen", 10), seed=5)
    algorithm = make(pop_size=20)
    minimize(problem, algorithm, ("n_gen", 4), seed=5, copy_algorithm=False)
    checkpoint = roundtrip(algorithm)
    checkpoint.termination = MaximumGenerationTermination(10)
    resumed = minimize(problem, checkpoint, copy_algorithm=False)
    assert resumed.algorithm.n_gen == straight.algorithm.n_gen
    assert np.array_equal(resumed.pop.get("X"), straight.pop.get("X"))
    assert np.array_equal(resumed.pop.get("F"), straight.pop.get("F"))


# ---------------------------------------------------------------------------
# pareto_front
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "objectives",
    [
        ("length", "vulnerability"),
        ("vulnerability", "length"),
        ("length", "smoothness"),
        ("length", "vulnerability", "smoothness"),
    ],
)
@pytest.mark.parametrize("constraints", ["penalty", "constraint"])
def test_pareto_front_is_the_exact_monotone_front(objectives, constraints):
    ws = random_workspace((12, 14), 30, seed=4)
    exact_front = exact.monotone_front(ws, objectives)
    for encoding in ENCODINGS:  # binary: corner cutting is on here
        problem = GridPathProblem(ws, objectives=objectives, encoding=encoding, constraints=constraints)
        pf = problem.pareto_front()
        assert np.array_equal(pf, exact_front.F)
        assert pf.shape == (len(exact_front), len(objectives))
        # the problem's own F for those paths: the same numbers (feasible, no penalty)
        out = problem.evaluate(problem.encode(exact_front.paths), return_as_dictionary=True)
        assert np.array_equal(out["F"], pf)
        assert not out["interfering"].any()
        if constraints == "constraint":
            assert (out["G"] <= 0).all()


def test_pareto_front_is_cached_and_copied(monkeypatch):
    problem = GridPathProblem(default_workspace())
    calls = []
    real = exact.monotone_front
    monkeypatch.setattr(exact, "monotone_front", lambda *a, **k: calls.append(1) or real(*a, **k))
    pf = problem.pareto_front()
    pf[:] = -1.0  # the caller's copy
    again = problem.pareto_front()
    assert len(calls) == 1 and (again >= 0).all()
    assert np.array_equal(roundtrip(problem).pareto_front(), again)
    assert len(calls) == 1  # the cache is pickled with the problem
    assert np.array_equal(problem.nadir_point(), again.max(axis=0))
    assert np.array_equal(problem.ideal_point(), again.min(axis=0))


def test_pymoo_indicators_work_with_it():
    problem = GridPathProblem(default_workspace())
    pf = problem.pareto_front()
    assert IGD(pf)(pf) == 0.0 and GD(pf)(pf) == 0.0
    res = minimize(problem, paper_nsga2(30, sampling=PlannerSampling()), ("n_gen", 5), seed=1)
    front = path_front(problem, res.pop.get("X"))
    assert len(front) > 0
    igd, gd = IGD(pf)(front.F), GD(pf)(front.F)
    assert np.isfinite(igd) and igd >= 0 and np.isfinite(gd) and gd >= 0
    ref = pf.max(axis=0) * 1.1
    assert 0 < HV(ref_point=ref)(front.F) <= HV(ref_point=ref)(pf) * (1 + 1e-9)


def test_verbose_output_shows_igd_on_a_small_map(capsys):
    problem = GridPathProblem(default_workspace())
    minimize(problem, paper_nsga2(10), ("n_gen", 2), seed=1, verbose=True)
    header = capsys.readouterr().out.splitlines()[1]
    assert "igd" in header and "gd" in header and "hv" in header


def test_large_map_is_not_solved_unasked(monkeypatch, capsys):
    ws = random_workspace((40, 40), 200, seed=2)
    assert ws.occ.size > EXACT_FRONT_AUTO_CELLS
    problem = GridPathProblem(ws)
    real = exact.monotone_front

    def forbidden(*args, **kwargs):
        raise AssertionError("monotone_front called")

    monkeypatch.setattr(exact, "monotone_front", forbidden)
    minimize(problem, paper_nsga2(10), ("n_gen", 2), seed=1, verbose=True)
    header = capsys.readouterr().out.splitlines()[1]
    assert "igd" not in header and "eps" in header  # pymoo's front-free columns
    with pytest.raises(ConfigError, match=r"40x40 workspace.*pareto_front\(force=True\)"):
        problem.pareto_front()
    monkeypatch.setattr(exact, "monotone_front", real)
    pf = problem.pareto_front(force=True)
    assert np.array_equal(pf, real(ws).F)
    assert np.array_equal(problem.pareto_front(), pf)  # cached: no force needed now


def test_no_front_for_layer_objectives_or_binary_without_corner_cutting():
    ws = random_workspace((10, 10), 15, seed=1)
    with_layers = GridPathProblem(ws, objectives="length,risk", costmap=Costmap(ws, risk=(5, 5)))
    with pytest.raises(ConfigError, match="layer objective.*risk"):
        with_layers.pareto_front()
    binary = GridPathProblem(ws.replace(corner_cutting=False), encoding="binary")
    with pytest.raises(ConfigError, match="binary encoding without corner cutting"):
        binary.pareto_front()
    integer = GridPathProblem(ws.replace(corner_cutting=False))
    assert np.array_equal(integer.pareto_front(), exact.monotone_front(ws.replace(corner_cutting=False)).F)


def test_no_monotone_path_raises_each_time():
    occ = np.zeros((4, 5), bool)
    occ[:, 2] = True  # a wall: no path at all
    problem = GridPathProblem(Workspace(occ))
    for _ in range(2):
        with pytest.raises(NoPathError, match="no feasible column-monotone path"):
            problem.pareto_front()


def test_binary_genomes_never_beat_the_front_with_corner_cutting():
    """The binary set's extra (horizontal-then-vertical) transitions are
    dominated when corner cutting is allowed: random binary paths, and
    mutants of the front's own genomes, never dominate a front point."""
    rng = np.random.default_rng(11)
    for seed in range(3):
        ws = random_workspace((9, 10), 12, seed=seed)
        problem = GridPathProblem(ws, objectives=("length", "vulnerability", "smoothness"), encoding="binary")
        pf = problem.pareto_front()
        base = problem.encode(exact.monotone_front(ws, problem.objectives).paths)
        mutants = np.repeat(base, 200, axis=0) ^ (rng.random((len(base) * 200, problem.n_var)) < 0.05)
        X = np.vstack([rng.random((20000, problem.n_var)) < 0.5, mutants])
        M = problem.metrics(X)
        F = problem.objective_values(M)[M[:, 3] == 0]
        scale = 1e-9 * np.maximum(1.0, np.abs(pf))
        for f in F:
            dominated = (f <= pf + scale).all(axis=1) & (f < pf - scale).any(axis=1)
            assert not dominated.any(), (seed, f)


# ---------------------------------------------------------------------------
# non-integral genes
# ---------------------------------------------------------------------------


def _genome_warnings(record):
    return [w for w in record if issubclass(w.category, GenomeWarning)]


@pytest.mark.parametrize("encoding", ["integer", "mixed", "absolute"])
def test_stock_float_operators_warn_once_per_problem(encoding):
    problem = GridPathProblem(default_workspace(), encoding=encoding)
    with pytest.warns(GenomeWarning, match="non-integral genes") as record:
        minimize(problem, NSGA2(pop_size=20), ("n_gen", 4), seed=1)
    assert len(_genome_warnings(record)) == 1
    message = str(_genome_warnings(record)[0].message)
    assert f"{encoding} encoding" in message and "paper_nsga2" in message
    with warnings.catch_warnings(record=True) as again:
        warnings.simplefilter("always")
        minimize(problem, NSGA2(pop_size=20), ("n_gen", 2), seed=2)
    assert not _genome_warnings(again)  # once per problem instance
    with pytest.warns(GenomeWarning):  # a new problem warns again
        GridPathProblem(default_workspace(), encoding=encoding).evaluate(np.full((1, problem.n_var), 0.5))


@pytest.mark.filterwarnings("ignore:invalid value encountered in cast:RuntimeWarning")
def test_integral_floats_do_not_warn_but_nan_does():
    problem = GridPathProblem(default_workspace())
    X = np.random.default_rng(0).integers(problem.xl, problem.xu + 1, (30, problem.n_var))
    with warnings.catch_warnings():
        warnings.simplefilter("error", GenomeWarning)
        problem.evaluate(X)
        problem.evaluate(X.astype(float))
    bad = X.astype(float)
    bad[3, 4] = np.nan
    with pytest.warns(GenomeWarning, match="1 of 30 genomes"):
        problem.evaluate(bad)


@pytest.mark.parametrize("encoding", list(ENCODINGS))
@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("seeded", [False, True])
def test_gapath_operators_never_warn(encoding, engine, seeded):
    problem = GridPathProblem(random_workspace((16, 16), 40, seed=3), encoding=encoding)
    kwargs = {"sampling": PlannerSampling()} if seeded else {}
    with warnings.catch_warnings():
        warnings.simplefilter("error", GenomeWarning)
        res = minimize(
            problem, ENGINES[engine](pop_size=20, encoding=encoding, **kwargs), ("n_gen", 8), seed=1
        )
    assert res.pop is not None and len(res.pop) == 20


@pytest.mark.parametrize("encoding", ["integer", "absolute"])
def test_stock_nsga2_with_gapath_operators_does_not_warn(encoding):
    """The README's advice for stock algorithms: gapath's integer operators."""
    from pymoo.operators.sampling.rnd import IntegerRandomSampling

    from gapath.operators import DiscretePM, DiscreteSBX, EdgeFixingRepair

    problem = GridPathProblem(random_workspace((16, 16), 40, seed=3), encoding=encoding)
    algorithm = NSGA2(
        pop_size=20,
        sampling=IntegerRandomSampling(),
        crossover=DiscreteSBX(),
        mutation=DiscretePM(),
        repair=EdgeFixingRepair(),
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error", GenomeWarning)
        minimize(problem, algorithm, ("n_gen", 8), seed=1)


# ---------------------------------------------------------------------------
# the README's pymoo example
# ---------------------------------------------------------------------------


def readme_pymoo_code() -> str:
    text = README.read_text()
    section = text.split("## Use it from pymoo", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, flags=re.S)
    assert blocks, "no python block in the README's 'Use it from pymoo' section"
    return "\n".join(blocks)


def test_readme_pymoo_example_runs(capsys):
    code = readme_pymoo_code()
    small = code
    for old, new in (("pop_size=500", "pop_size=40"), ('("n_gen", 500)', '("n_gen", 10)')):
        assert old in code, f"the README example no longer contains {old!r}"
        small = small.replace(old, new)
    assert "PlannerSampling" in code  # the seeded form is shown
    namespace: dict = {}
    exec(compile(small, str(README), "exec"), namespace)
    printed = capsys.readouterr().out
    assert printed.strip()
    front, problem = namespace["front"], namespace["problem"]
    ws = problem.workspace
    assert len(front) > 0 and not front.metrics[:, 3].any()  # feasible paths
    assert all(ws.is_valid_path(p) for p in front.paths)
    assert tuple(front.paths[0][0]) == ws.start and tuple(front.paths[0][-1]) == ws.goal
