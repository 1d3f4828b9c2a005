import numpy as np
import pytest
from pymoo.optimize import minimize

from gapath import ConfigError, Workspace, default_workspace
from gapath.algorithms import paper_nsga2
from gapath.front import path_front
from gapath.generators import random_workspace
from gapath.objectives import evaluate_path
from gapath.problems import GridPathProblem
from gapath.problems.grid_path import GenomeWarning


@pytest.fixture(scope="module")
def ws():
    return random_workspace((12, 12), 25, seed=4)


def _nondominated(F):
    for i, a in enumerate(F):
        for j, b in enumerate(F):
            if i != j and (b <= a).all() and (b < a).any():
                return False
    return True


def test_problem_shapes_and_penalty(ws):
    p = GridPathProblem(ws)
    assert (p.n_var, p.n_obj, p.n_ieq_constr) == (11, 2, 0)
    X = np.random.default_rng(0).integers(p.xl, p.xu + 1, size=(30, p.n_var))
    out = p.evaluate(X, return_as_dictionary=True)
    M = p.metrics(X)
    np.testing.assert_array_equal(out["F"], M[:, :2] + 1000 * M[:, 3:4])
    np.testing.assert_array_equal(out["smoothness"], M[:, 2])


def test_constraint_mode(ws):
    p = GridPathProblem(ws, objectives="length,vulnerability,smoothness", constraints="constraint")
    assert (p.n_obj, p.n_ieq_constr) == (3, 1)
    X = np.random.default_rng(0).integers(p.xl, p.xu + 1, size=(10, p.n_var))
    out = p.evaluate(X, return_as_dictionary=True)
    M = p.metrics(X)
    np.testing.assert_array_equal(out["F"], M[:, :3])
    np.testing.assert_array_equal(out["G"][:, 0], M[:, 3])


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(objectives=("length", "speed")), "unknown objective 'speed'"),
        (dict(objectives=("interfering",)), "unknown objective 'interfering'"),
        (dict(encoding="gray"), "unknown encoding"),
        (dict(constraints="soft"), "unknown constraint handling 'soft'"),
        (dict(penalty=-1), "penalty must be a number >= 0"),
        (dict(penalty="lots"), "penalty must be a number >= 0"),
    ],
)
def test_bad_problem_settings(ws, kwargs, match):
    with pytest.raises(ConfigError, match=match):
        GridPathProblem(ws, **kwargs)


def test_minimize_end_to_end(ws):
    p = GridPathProblem(ws)
    res = minimize(p, paper_nsga2(60), ("n_gen", 40), seed=3)
    front = path_front(p, res.pop.get("X"))
    assert len(front) >= 2
    assert _nondominated(front.F)
    for f, path in zip(front.F, front.paths):
        assert ws.is_valid_path(path)
        recomputed = evaluate_path(ws, path)
        assert recomputed["interfering"] == 0
        np.testing.assert_allclose(f, [recomputed["length"], recomputed["vulnerability"]], rtol=1e-12)
        # F stored by pymoo (penalty 0 for feasible paths) matches too
    F_res = p.evaluate(front.X)
    np.testing.assert_allclose(F_res, front.F, rtol=1e-12)
    # smoothest among equal objective vectors: no two rows equal
    assert len(np.unique(front.F.round(9), axis=0)) == len(front)


def test_same_seed_same_front_bit_for_bit(ws):
    p = GridPathProblem(ws)
    a = minimize(p, paper_nsga2(40), ("n_gen", 15), seed=11)
    b = minimize(p, paper_nsga2(40), ("n_gen", 15), seed=11)
    assert np.array_equal(a.pop.get("X"), b.pop.get("X"))
    assert np.array_equal(a.F, b.F)
    c = minimize(p, paper_nsga2(40), ("n_gen", 15), seed=12)
    assert not np.array_equal(a.pop.get("X"), c.pop.get("X"))


def test_population_keeps_distinct_paths(ws):
    p = GridPathProblem(ws)
    res = minimize(p, paper_nsga2(50), ("n_gen", 20), seed=2)
    entries, exits = p.encoding.decode(res.pop.get("X"))
    assert len(np.unique(np.hstack([entries, exits]), axis=0)) == len(res.pop)


def test_constraint_mode_end_to_end(ws):
    p = GridPathProblem(ws, constraints="constraint")
    res = minimize(p, paper_nsga2(40), ("n_gen", 25), seed=1)
    front = path_front(p, res.pop.get("X"))
    assert len(front) >= 1 and _nondominated(front.F)


@pytest.mark.parametrize("name", ["NSGA2", "NSGA3", "SMSEMOA", "AGEMOEA"])
def test_runs_with_stock_pymoo_algorithms(ws, name):
    from pymoo.algorithms.moo.age import AGEMOEA
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.algorithms.moo.nsga3 import NSGA3
    from pymoo.algorithms.moo.sms import SMSEMOA
    from pymoo.operators.sampling.rnd import IntegerRandomSampling
    from pymoo.util.ref_dirs import get_reference_directions

    from gapath.operators import DiscretePM, DiscreteSBX, EdgeFixingRepair

    ops = dict(
        sampling=IntegerRandomSampling(),
        crossover=DiscreteSBX(),
        mutation=DiscretePM(),
        repair=EdgeFixingRepair(),
    )
    algo = {
        "NSGA2": lambda: NSGA2(pop_size=30, **ops),
        "NSGA3": lambda: NSGA3(
            ref_dirs=get_reference_directions("das-dennis", 2, n_partitions=12), pop_size=30, **ops
        ),
        "SMSEMOA": lambda: SMSEMOA(pop_size=20, **ops),
        "AGEMOEA": lambda: AGEMOEA(pop_size=30, **ops),
    }[name]()
    p = GridPathProblem(ws)
    res = minimize(p, algo, ("n_gen", 8), seed=1)
    assert res.F is not None and res.F.shape[1] == 2
    for path in p.decode(res.X):
        assert ws.is_valid_path(path)


def test_stock_nsga2_with_default_float_operators(ws):
    from pymoo.algorithms.moo.nsga2 import NSGA2

    p = GridPathProblem(ws)
    with pytest.warns(GenomeWarning, match="non-integral genes"):  # the float operators are named
        res = minimize(p, NSGA2(pop_size=20), ("n_gen", 5), seed=1)
    for path in p.decode(res.X):
        assert ws.is_valid_path(path)


def test_paper_nsga2_settings():
    a = paper_nsga2()
    assert a.pop_size == 500
    assert a.mating.crossover.eta.value == 10 and a.mating.crossover.prob.value == 0.9
    assert a.mating.mutation.eta.value == 20
    with pytest.raises(ConfigError):
        paper_nsga2(1)
    with pytest.raises(ConfigError):
        paper_nsga2(10, tiebreak="turns")


def test_default_problem_on_bundled_scenario():
    p = GridPathProblem(default_workspace())
    assert p.n_var == 31
    assert (p.xl[0], p.xu[0]) == (0, 31)


def test_decode_single_genome(ws):
    p = GridPathProblem(ws)
    (path,) = p.decode(np.zeros(p.n_var, int))
    assert ws.is_valid_path(path)
    assert isinstance(Workspace, type)
