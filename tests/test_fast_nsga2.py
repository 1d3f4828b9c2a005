"""FastNSGA2: Ahmed & Deb's NSGA-II on arrays, inside pymoo."""

import time

import numpy as np
import pytest
from pymoo.core.callback import Callback
from pymoo.core.population import Population
from pymoo.core.problem import Problem
from pymoo.core.result import Result
from pymoo.operators.crossover.sbx import SBX
from pymoo.operators.mutation.pm import PM
from pymoo.optimize import minimize

from gapath import ConfigError, default_workspace
from gapath.algorithms import FastNSGA2, paper_nsga2
from gapath.algorithms._kernels import binary_tournament, stable_argsort
from gapath.algorithms._variation import (
    discrete_supported,
    discrete_variation,
    pm_mutation,
    sbx_crossover,
    sbx_supported,
)
from gapath.algorithms.fast_nsga2 import PathArrays, fast_survival_order, pareto_ranks, path_duplicate_mask
from gapath.front import path_front
from gapath.generators import random_workspace
from gapath.metrics import hv_ratio
from gapath.objectives import evaluate_path
from gapath.operators import (
    DiscretePM,
    DiscreteSBX,
    compare_rank_smoothness_crowding,
    survival_order,
)
from gapath.operators.duplicates import duplicate_mask
from gapath.planners.exact import monotone_front
from gapath.problems import GridPathProblem


@pytest.fixture(scope="module")
def ws():
    return random_workspace((12, 12), 25, seed=4)


@pytest.fixture(scope="module")
def problem(ws):
    return GridPathProblem(ws)


def _nondominated(F):
    return not any(
        (b <= a).all() and (b < a).any() for i, a in enumerate(F) for j, b in enumerate(F) if i != j
    )


def _paths(problem, X):
    entries, exits = problem.encoding.decode(X)
    return np.hstack([entries, exits])


# -- through pymoo's minimize -------------------------------------------------


def test_minimize_returns_result_with_valid_front(ws, problem):
    res = minimize(problem, FastNSGA2(60), ("n_gen", 40), seed=3)
    assert isinstance(res, Result) and isinstance(res.algorithm, FastNSGA2)
    assert isinstance(res.pop, Population) and len(res.pop) == 60
    assert res.F.shape[1] == 2 and len(res.X) == len(res.F)
    assert _nondominated(res.F)
    assert (res.CV <= 0).all()
    # every returned path is feasible and its objectives recompute exactly
    for f, path in zip(res.F, problem.decode(res.X)):
        assert ws.is_valid_path(path)
        m = evaluate_path(ws, path)
        assert m["interfering"] == 0
        np.testing.assert_allclose(f, [m["length"], m["vulnerability"]], rtol=1e-12)
    front = path_front(problem, res.pop.get("X"))
    assert len(front) >= 2 and _nondominated(front.F)
    # pymoo's per-individual bookkeeping is there
    assert res.pop.get("rank").min() == 0 and res.pop.get("crowding").shape == (60,)
    np.testing.assert_array_equal(res.pop.get("smoothness"), problem.metrics(res.pop.get("X"))[:, 2])


def test_same_seed_same_population_bit_for_bit(problem):
    a = minimize(problem, FastNSGA2(40), ("n_gen", 15), seed=11)
    b = minimize(problem, FastNSGA2(40), ("n_gen", 15), seed=11)
    assert np.array_equal(a.pop.get("X"), b.pop.get("X")) and np.array_equal(a.F, b.F)
    c = minimize(problem, FastNSGA2(40), ("n_gen", 15), seed=12)
    assert not np.array_equal(a.pop.get("X"), c.pop.get("X"))


class _Watch(Callback):
    def __init__(self):
        super().__init__()
        self.sizes, self.distinct, self.F = [], [], []

    def notify(self, algorithm):
        pop = algorithm.pop
        self.sizes.append(len(pop))
        self.distinct.append(len(np.unique(_paths(algorithm.problem, pop.get("X")), axis=0)))
        self.F.append(pop.get("F"))


def test_population_stays_distinct_and_full_and_callback_sees_it(problem):
    watch = _Watch()
    res = minimize(problem, FastNSGA2(50), ("n_gen", 20), seed=2, callback=watch)
    assert watch.sizes == [50] * 20 and watch.distinct == [50] * 20
    assert all(F.shape == (50, 2) and np.isfinite(F).all() for F in watch.F)
    np.testing.assert_array_equal(watch.F[-1], res.pop.get("F"))


@pytest.mark.parametrize(
    "settings",
    [
        dict(constraints="constraint"),
        dict(objectives="length,vulnerability,smoothness", tiebreak=None),
        dict(objectives="length,vulnerability,smoothness", constraints="constraint", tiebreak=None),
        dict(tiebreak=None),
        dict(objectives="length"),
    ],
)
def test_modes_are_pymoos_nsga2_bit_for_bit(ws, settings):
    """Same seed, same operators: FastNSGA2 returns paper_nsga2's population."""
    settings = dict(settings)
    tiebreak = settings.pop("tiebreak", "smoothness")
    p = GridPathProblem(ws, **settings)
    stock = minimize(p, paper_nsga2(40, tiebreak=tiebreak), ("n_gen", 12), seed=5)
    fast = minimize(p, FastNSGA2(40, tiebreak=tiebreak), ("n_gen", 12), seed=5)
    np.testing.assert_array_equal(fast.pop.get("X"), stock.pop.get("X"))
    np.testing.assert_array_equal(fast.pop.get("F"), stock.pop.get("F"))
    np.testing.assert_array_equal(fast.pop.get("rank"), stock.pop.get("rank"))
    np.testing.assert_array_equal(fast.pop.get("crowding"), stock.pop.get("crowding"))
    assert fast.algorithm.evaluator.n_eval == stock.algorithm.evaluator.n_eval
    np.testing.assert_array_equal(np.atleast_2d(fast.X), np.atleast_2d(stock.X))


def test_bundled_scenario_matches_paper_nsga2_and_generic_operators():
    p = GridPathProblem(default_workspace())
    stock = minimize(p, paper_nsga2(100), ("n_gen", 15), seed=1)
    fast = minimize(p, FastNSGA2(100), ("n_gen", 15), seed=1)
    slow = minimize(p, FastNSGA2(100, fast_operators=False), ("n_gen", 15), seed=1)
    np.testing.assert_array_equal(fast.pop.get("X"), stock.pop.get("X"))
    np.testing.assert_array_equal(slow.pop.get("X"), stock.pop.get("X"))


def test_constraint_mode_front_is_feasible(ws):
    p = GridPathProblem(ws, objectives="length,vulnerability,smoothness", constraints="constraint")
    res = minimize(p, FastNSGA2(40, tiebreak=None), ("n_gen", 20), seed=1)
    assert res.F.shape[1] == 3 and (res.G <= 0).all() and _nondominated(res.F)
    assert (p.metrics(res.X)[:, 3] == 0).all()


def test_single_objective(ws):
    p = GridPathProblem(ws, objectives="length")
    res = minimize(p, FastNSGA2(30), ("n_gen", 15), seed=1)
    best = monotone_front(ws, "length").F[0, 0]
    assert res.F.shape[-1] == 1 and res.F.min() >= best - 1e-9


# -- terminations, history, output ----------------------------------------------


def test_n_eval_and_time_terminations(problem):
    res = minimize(problem, FastNSGA2(40), ("n_eval", 500), seed=1)
    n_eval = res.algorithm.evaluator.n_eval
    assert 500 <= n_eval < 540
    t0 = time.time()
    res = minimize(problem, FastNSGA2(40), ("time", 0.5), seed=1)
    assert 0.5 <= time.time() - t0 < 5 and res.algorithm.n_gen > 2


def test_default_termination_and_verbose_output(problem, capsys):
    res = minimize(problem, FastNSGA2(20), seed=1, verbose=True)
    out = capsys.readouterr().out
    assert "n_gen" in out and "n_nds" in out and res.algorithm.termination.has_terminated()
    assert res.algorithm.n_gen < 1000


def test_save_history(problem):
    res = minimize(problem, FastNSGA2(30), ("n_gen", 6), seed=1, save_history=True)
    assert len(res.history) == 6
    assert [h.n_gen for h in res.history] == [1, 2, 3, 4, 5, 6]
    assert all(len(h.pop) == 30 and h.pop.get("F").shape == (30, 2) for h in res.history)
    np.testing.assert_array_equal(res.history[-1].pop.get("X"), res.pop.get("X"))


def test_ask_and_tell_matches_minimize(problem):
    algorithm = FastNSGA2(30)
    algorithm.setup(problem, termination=("n_gen", 8), seed=4)
    while algorithm.has_next():
        pop = algorithm.ask()
        algorithm.evaluator.eval(problem, pop)
        algorithm.tell(infills=pop)
    ref = minimize(problem, FastNSGA2(30), ("n_gen", 8), seed=4)
    np.testing.assert_array_equal(algorithm.result().pop.get("X"), ref.pop.get("X"))


def test_initial_sampling_array_and_population(problem):
    X0 = np.zeros((5, problem.n_var), int)  # five copies of one path
    res = minimize(problem, FastNSGA2(20, sampling=X0), ("n_gen", 1), seed=1)
    assert len(res.pop) == 1  # pymoo collapses duplicate seeds too
    res = minimize(problem, FastNSGA2(20, sampling=X0), ("n_gen", 3), seed=1)
    assert len(res.pop) == 20
    seeded = minimize(problem, FastNSGA2(20), ("n_gen", 2), seed=2).pop
    res = minimize(problem, FastNSGA2(20, sampling=seeded), ("n_gen", 2), seed=3)
    assert len(res.pop) == 20
    assert res.algorithm.evaluator.n_eval == 20  # the seeds were evaluated already


# -- errors ------------------------------------------------------------------------


class _Sphere(Problem):
    def __init__(self):
        super().__init__(n_var=3, n_obj=2, xl=0.0, xu=1.0)

    def _evaluate(self, X, out, *args, **kwargs):
        out["F"] = np.column_stack([X[:, 0], 1 - X[:, 0]])


def test_non_gapath_problem_is_a_config_error():
    with pytest.raises(ConfigError, match="_Sphere"):
        minimize(_Sphere(), FastNSGA2(10), ("n_gen", 2), seed=1)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(pop_size=1), "pop_size"),
        (dict(pop_size="x"), "pop_size"),
        (dict(tiebreak="length"), "tiebreak"),
        (dict(n_offsprings=0), "n_offsprings"),
    ],
)
def test_bad_settings(kwargs, match):
    with pytest.raises(ConfigError, match=match):
        FastNSGA2(**kwargs)


# -- array kernels against the code they replace ---------------------------------


def test_survival_order_kernel_matches_survival_order():
    rng = np.random.default_rng(0)
    for trial in range(30):
        n, m = rng.integers(2, 80), rng.integers(1, 4)
        F = rng.integers(0, 6, size=(n, m)).astype(float)  # many ties and duplicates
        smooth = rng.integers(0, 3, size=n).astype(float) if trial % 2 else None
        CV = np.where(rng.random(n) < 0.3, rng.integers(0, 3, n), 0.0)[:, None] if trial % 3 else None
        k = int(rng.integers(1, n + 1))
        for a, b in zip(fast_survival_order(F, smooth, CV, k), survival_order(F, smooth, CV, k)):
            np.testing.assert_array_equal(a, b)


def test_survival_order_kernel_matches_survival_order_on_large_fronts():
    """Fronts of more than 32 rows (the kernels' sorts change algorithm
    there), with ties on both objectives and duplicate rows."""
    rng = np.random.default_rng(4)
    for trial in range(12):
        n = int(rng.integers(60, 400))
        f1 = rng.integers(0, 50, n).astype(float)
        F = np.column_stack([f1, 50 - f1 + rng.integers(0, 3, n) * (trial % 2)])
        smooth = rng.integers(0, 2, size=n).astype(float) if trial % 3 else None
        k = int(rng.integers(1, n + 1))
        for a, b in zip(fast_survival_order(F, smooth, None, k), survival_order(F, smooth, None, k)):
            np.testing.assert_array_equal(a, b)


def test_stable_argsort_is_numpys_stable_order():
    rng = np.random.default_rng(6)
    for n in (0, 1, 2, 5, 31, 32, 33, 80):
        v = rng.integers(0, 4, n).astype(float)
        v[rng.random(n) < 0.2] = np.nan
        v[rng.random(n) < 0.2] = -np.inf
        np.testing.assert_array_equal(stable_argsort(v), np.argsort(v, kind="stable"))


def test_take_merged_is_concat_then_take():
    rng = np.random.default_rng(8)

    def arrays(n):
        return PathArrays(
            rng.integers(0, 9, (n, 4)),
            rng.random((n, 2)),
            np.zeros((n, 0)),
            np.zeros((n, 0)),
            rng.random(n),
            rng.integers(0, 5, n),
            data={"smoothness": rng.random(n), "interfering": rng.integers(0, 2, n) > 0},
            keys=rng.integers(0, 9, (n, 6)),
            hashes=rng.integers(0, 99, n),
        )

    a, b = arrays(7), arrays(5)
    idx = rng.permutation(12)[:9]
    got, want = a.take_merged(b, idx), a.concat(b).take(idx)
    for k in (*PathArrays._ROWS, "keys", "hashes"):
        np.testing.assert_array_equal(getattr(got, k), getattr(want, k))
        assert getattr(got, k).dtype == getattr(want, k).dtype
    assert got.data.keys() == want.data.keys()
    for k in got.data:
        np.testing.assert_array_equal(got.data[k], want.data[k])


def test_pareto_ranks_match_moocore():
    from moocore import pareto_rank

    rng = np.random.default_rng(5)
    for trial in range(40):
        n, m = rng.integers(1, 300), (2, 2, 3)[trial % 3]
        F = rng.integers(0, (4, 30)[trial % 2], size=(n, m)).astype(float)
        np.testing.assert_array_equal(pareto_ranks(F), pareto_rank(F))


def test_duplicate_mask_kernel_matches_duplicate_mask():
    rng = np.random.default_rng(1)
    for _ in range(30):
        keys = rng.integers(0, 3, size=(rng.integers(1, 60), 3))
        other = rng.integers(0, 3, size=(rng.integers(0, 20), 3))
        expected = duplicate_mask(keys) | (duplicate_mask(keys, other) if len(other) else False)
        np.testing.assert_array_equal(path_duplicate_mask(keys, other), expected)


def test_tournament_kernel_matches_compare_function():
    rng = np.random.default_rng(2)
    n = 50
    cv, rank = rng.integers(0, 2, n) * 1.0, rng.integers(0, 3, n) * 1.0
    smooth, crowd = rng.integers(0, 2, n) * 1.0, np.where(rng.random(n) < 0.2, np.inf, rng.integers(0, 2, n))
    P = rng.integers(0, n, size=(200, 2))
    for tiebreak in (True, False):
        keys = [(cv, 1), (rank, 1)] + ([(smooth, 1)] if tiebreak else []) + [(crowd, -1)]
        expected = compare_rank_smoothness_crowding(
            None, P, random_state=np.random.default_rng(9), keys=keys
        )[:, 0]
        coin = np.random.default_rng(9).random(len(P))
        np.testing.assert_array_equal(binary_tournament(P, cv, rank, smooth, crowd, tiebreak, coin), expected)


@pytest.mark.parametrize("op", [DiscreteSBX(), DiscreteSBX(prob=0.5, eta=2), SBX(eta=15, prob=1.0)])
def test_sbx_twin_is_bit_identical(problem, op):
    assert sbx_supported(op)
    rng = np.random.default_rng(3)
    X = rng.integers(problem.xl, problem.xu + 1, size=(2, 37, problem.n_var)).astype(float)
    X[1, :5] = X[0, :5]  # identical parents
    a, b = np.random.default_rng(7), np.random.default_rng(7)
    off = op.do(
        problem,
        Population.new("X", X.reshape(-1, problem.n_var)),
        parents=np.arange(74).reshape(2, 37).T,
        random_state=a,
    )
    twin = sbx_crossover(op, problem, X, b)
    np.testing.assert_array_equal(twin, off.get("X"))
    assert a.random() == b.random()  # same number of draws


@pytest.mark.parametrize("op", [DiscretePM(), DiscretePM(eta=5, prob_var=0.3), PM(eta=20, prob=0.7)])
def test_pm_twin_is_bit_identical(problem, op):
    rng = np.random.default_rng(4)
    X = rng.integers(problem.xl, problem.xu + 1, size=(64, problem.n_var)).astype(float)
    a, b = np.random.default_rng(8), np.random.default_rng(8)
    mutated = op.do(problem, Population.new("X", X.copy()), random_state=a).get("X")
    np.testing.assert_array_equal(pm_mutation(op, problem, X, b), mutated)
    assert a.random() == b.random()


@pytest.mark.parametrize("seed", range(4))
def test_twins_are_bit_identical_on_real_valued_parents(problem, seed):
    """Real-valued genes (every power has a non-trivial base), some outside
    the bounds (negative beta, NaN alpha: pymoo's betaq of 0), odd sizes and
    eta, eta 1 (exponents 0.5 and 2, which NumPy special-cases for a scalar
    exponent but not for pymoo's array of exponents): the children, NaN where
    pymoo's are, and the generator's state."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 90))
    lo, hi = np.asarray(problem.xl, float), np.asarray(problem.xu, float)
    half = (hi - lo) / 2 * (1.3 if seed % 2 else 1.0)
    X = (lo + hi) / 2 + (2 * rng.random((2, n, problem.n_var)) - 1) * half
    eta = float(rng.uniform(1.5, 30))
    for op in (SBX(eta=eta, prob=0.9, prob_var=0.7), SBX(eta=2.5, prob=1.0), SBX(eta=1.0, prob=1.0)):
        a, b = np.random.default_rng(seed + 10), np.random.default_rng(seed + 10)
        with np.errstate(all="ignore"):
            off = op.do(
                problem,
                Population.new("X", X.reshape(-1, problem.n_var)),
                parents=np.arange(2 * n).reshape(2, n).T,
                random_state=a,
            ).get("X")
            twin = sbx_crossover(op, problem, X, b)
        np.testing.assert_array_equal(twin, off)
        assert a.random() == b.random()
    for op in (PM(eta=eta, prob=0.8, prob_var=0.5), PM(eta=20, prob=1.0), PM(eta=1.0, prob=1.0)):
        a, b = np.random.default_rng(seed + 20), np.random.default_rng(seed + 20)
        with np.errstate(all="ignore"):
            mutated = op.do(problem, Population.new("X", X[0].copy()), random_state=a).get("X")
            twin = pm_mutation(op, problem, X[0], b)
        np.testing.assert_array_equal(twin, mutated)
        assert a.random() == b.random()


def test_fused_discrete_variation_is_bit_identical(problem):
    sbx, pm = DiscreteSBX(), DiscretePM()
    assert discrete_supported(sbx, pm, problem) and not discrete_supported(SBX(), pm, problem)
    rng = np.random.default_rng(6)
    X = rng.integers(problem.xl, problem.xu + 1, size=(2, 41, problem.n_var))
    X[1, :7] = X[0, :7]
    a, b = np.random.default_rng(9), np.random.default_rng(9)
    pop = Population.new("X", X.reshape(-1, problem.n_var))
    off = sbx(problem, pop, parents=np.arange(82).reshape(2, 41).T, random_state=a)
    off = pm(problem, off, random_state=a)
    np.testing.assert_array_equal(discrete_variation(sbx, pm, problem, X, b), off.get("X"))
    assert a.random() == b.random()


# -- quality -------------------------------------------------------------------------


def test_hv_ratio_not_worse_than_paper_nsga2_over_seeds(ws):
    """Over 5 seeds on a small map, FastNSGA2's median HV ratio (vs the exact
    monotone front) is within 0.01 of paper_nsga2's (here: equal, as the
    runs are the same)."""
    p = GridPathProblem(ws)
    exact = monotone_front(ws).F
    ratios = {"fast": [], "paper": []}
    for seed in range(1, 6):
        for name, alg in (("fast", FastNSGA2(40)), ("paper", paper_nsga2(40))):
            res = minimize(p, alg, ("n_gen", 25), seed=seed)
            ratios[name].append(hv_ratio(path_front(p, res.pop.get("X")).F, exact))
    assert np.median(ratios["fast"]) >= np.median(ratios["paper"]) - 0.01
    assert np.median(ratios["fast"]) > 0.5


# -- encodings -------------------------------------------------------------------------


def _encodings():
    from gapath.encodings import ENCODINGS

    return sorted(ENCODINGS)


@pytest.mark.parametrize("encoding", _encodings())
def test_every_encoding_is_pymoos_nsga2_bit_for_bit(ws, encoding):
    p = GridPathProblem(ws, encoding=encoding)
    stock = minimize(p, paper_nsga2(30, encoding=encoding), ("n_gen", 10), seed=2)
    for fast in (FastNSGA2(30), FastNSGA2(30, encoding=encoding)):
        res = minimize(p, fast, ("n_gen", 10), seed=2)
        np.testing.assert_array_equal(res.pop.get("X"), stock.pop.get("X"))
        np.testing.assert_array_equal(res.pop.get("F"), stock.pop.get("F"))


def test_encoding_mismatch_is_a_config_error(ws):
    from gapath.encodings import ENCODINGS

    other = next(e for e in ENCODINGS if e != "integer")
    with pytest.raises(ConfigError, match=f"configured for the {other!r} encoding"):
        minimize(GridPathProblem(ws), FastNSGA2(10, encoding=other), ("n_gen", 2), seed=1)
    with pytest.raises(ConfigError, match="unknown encoding"):
        FastNSGA2(10, encoding="morse")
