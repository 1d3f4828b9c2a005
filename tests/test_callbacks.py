"""Callbacks read arrays from the engine: no pymoo Population per generation
on FastNSGA2, the same values as from pymoo's population, each path decoded
once."""

from __future__ import annotations

import io

import numpy as np
import pytest
from pymoo.core.callback import Callback
from pymoo.optimize import minimize

from gapath import ConfigError, default_workspace
from gapath.algorithms import FastNSGA2, paper_nsga2
from gapath.algorithms.fast_nsga2 import PathArrays
from gapath.callbacks import Callbacks, ProgressBar, population_arrays, population_status
from gapath.convergence import HypervolumeRatioCallback
from gapath.experiments.runner import FirstFeasible
from gapath.front import path_front
from gapath.generators import random_workspace
from gapath.metrics import hv_ratio
from gapath.operators import PlannerSampling
from gapath.operators.columns import column
from gapath.planners.exact import monotone_front
from gapath.problems import GridPathProblem
from gapath.solver import solve


@pytest.fixture(scope="module")
def ws():
    return default_workspace()


class _Watch(Callback):
    """Records, every generation, whether a FastNSGA2 has its pymoo
    Population built, and the status read from the algorithm."""

    def __init__(self):
        super().__init__()
        self.pop_built = []
        self.status = []

    def notify(self, algorithm):
        self.pop_built.append(getattr(algorithm, "_pop", None) is not None)
        self.status.append(population_status(algorithm))


def _count_populations(monkeypatch):
    """Generations at which PathArrays.to_population was called."""
    calls = []
    original = PathArrays.to_population

    def counting(self):
        calls.append(len(self))
        return original(self)

    monkeypatch.setattr(PathArrays, "to_population", counting)
    return calls


def test_bar_and_callbacks_build_no_population_on_the_fast_engine(ws, monkeypatch):
    calls = _count_populations(monkeypatch)
    hv = HypervolumeRatioCallback(monotone_front(ws))
    first = FirstFeasible(stop=False)
    watch = _Watch()
    n_gen = 6
    r = solve(ws, pop_size=40, n_gen=n_gen, seed=2, progress=True, callback=Callbacks(hv, first, watch))
    assert r.n_gen == n_gen and len(hv.history) == n_gen and first.generation == 1
    # the bar, the hv ratio and the first-feasible watch ran before _Watch every generation
    assert watch.pop_built == [False] * n_gen
    # the only Populations built are the final Result's (pop and opt)
    assert len(calls) <= 2 and calls[0] == 40


def test_bar_reads_the_status_of_the_last_generation(ws):
    out = io.StringIO()
    bar = ProgressBar(5, file=out, mininterval=1e9)  # never redrawn on time
    r = solve(ws, pop_size=30, n_gen=5, seed=4, callback=bar)
    bar.close()
    assert bar.last_gen == 5 and bar.status["gen"] == 5
    expected = population_status(r.pymoo_result.algorithm)
    assert expected.pop("gen") == 6  # pymoo's n_gen after the run
    assert bar.status == {"gen": 5, **expected}
    text = out.getvalue()
    assert f"feasible={expected['feasible']} front={expected['front']}" in text
    assert "5/5" in text


def test_bar_reads_the_status_only_when_it_redraws(ws, monkeypatch):
    import gapath.callbacks

    calls = []
    original = gapath.callbacks.population_status

    def counting(algorithm, arrays=None):
        calls.append(int(algorithm.n_gen))
        return original(algorithm, arrays)

    monkeypatch.setattr(gapath.callbacks, "population_status", counting)
    bar = ProgressBar(6, file=io.StringIO(), mininterval=1e9)
    solve(ws, pop_size=20, n_gen=6, seed=1, callback=bar)
    bar.close()
    assert calls == [1, 6]  # the first drawing and the last generation
    calls.clear()
    bar = ProgressBar(6, file=io.StringIO(), mininterval=0, miniters=1)
    solve(ws, pop_size=20, n_gen=6, seed=1, callback=bar)
    bar.close()
    assert calls == [1, 2, 3, 4, 5, 6]


def _status_from_population(pop, problem, n_gen):
    """population_status computed independently from a pymoo Population."""
    interfering = column(pop, "interfering")
    feasible = interfering == 0
    rank = column(pop, "rank")
    status = {"gen": n_gen, "feasible": int(feasible.sum()), "front": int(((rank == 0) & feasible).sum())}
    if feasible.any():
        F = pop.get("F")[feasible]
        status.update({n: float(v) for n, v in zip(problem.objectives, F.min(axis=0))})
    return status


@pytest.mark.parametrize("constraints", ["penalty", "constraint"])
def test_status_equals_the_final_pymoo_population(ws, constraints):
    problem = GridPathProblem(ws, constraints=constraints)
    watches = {}
    results = {}
    seeded = dict(sampling=PlannerSampling("weighted"))
    for name, algorithm in (("fast", FastNSGA2(40, **seeded)), ("pymoo", paper_nsga2(40, **seeded))):
        watches[name] = _Watch()
        results[name] = minimize(problem, algorithm, ("n_gen", 5), seed=7, callback=watches[name])
    # the fast engine's arrays give what pymoo's own population gives
    assert watches["fast"].status == watches["pymoo"].status
    for name, res in results.items():
        expected = _status_from_population(res.pop, problem, 5)
        assert watches[name].status[-1] == expected
        assert expected["feasible"] > 0 and expected["front"] > 0


def test_population_arrays_match_the_pymoo_population(ws):
    problem = GridPathProblem(ws, constraints="constraint")
    for algorithm in (FastNSGA2(30), paper_nsga2(30)):
        res = minimize(problem, algorithm, ("n_gen", 3), seed=5)
        A = population_arrays(res.algorithm)
        pop = res.pop
        assert len(A) == len(pop) == 30
        np.testing.assert_array_equal(A.X, pop.get("X"))
        np.testing.assert_array_equal(A.F, pop.get("F"))
        np.testing.assert_array_equal(A.G, pop.get("G"))
        np.testing.assert_array_equal(A.CV, pop.get("CV")[:, 0])
        for key in ("rank", "smoothness", "interfering"):
            np.testing.assert_array_equal(getattr(A, key), pop.get(key))
        np.testing.assert_array_equal(A.feasible, pop.get("interfering") == 0)


def test_population_arrays_before_a_population_and_without_interfering():
    class _Nothing:
        pop = None
        n_gen = None

    assert population_arrays(_Nothing()) is None
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.problems import get_problem

    res = minimize(get_problem("zdt1", n_var=5), NSGA2(pop_size=10), ("n_gen", 2), seed=1)
    A = population_arrays(res.algorithm)
    assert A.interfering is None and A.smoothness is None
    assert A.feasible.all() and population_status(res.algorithm)["feasible"] == 10


def test_hv_history_and_first_feasible_are_the_same_on_both_engines(ws):
    reference = monotone_front(ws)
    out = {}
    for engine in ("fast", "pymoo"):
        hv = HypervolumeRatioCallback(reference)
        first = FirstFeasible(stop=False)
        r = solve(
            random_workspace((14, 14), 40, seed=3),
            pop_size=30,
            n_gen=6,
            seed=1,
            seed_from="none",
            engine=engine,
            callback=Callbacks(first),
        )
        solve(ws, pop_size=30, n_gen=6, seed=1, engine=engine, callback=hv)
        out[engine] = (hv.to_array(), first.generation, r)
    np.testing.assert_array_equal(out["fast"][0], out["pymoo"][0])
    assert out["fast"][1] == out["pymoo"][1] is not None
    # the last row is the hv ratio of the final population's front
    r = solve(ws, pop_size=30, n_gen=6, seed=1)
    front = path_front(r.problem, r.pymoo_result.pop.get("X"))
    assert out["fast"][0][-1, 2] == pytest.approx(hv_ratio(front.F, reference.F), abs=1e-12)


# -- decode once ------------------------------------------------------------


def _count_decodes(monkeypatch, problem):
    """Rows decoded by problem.encoding outside and inside evaluations."""
    rows = {"outside": 0, "inside": 0}
    state = {"where": "outside"}

    def counting(decode):
        def counted(X):
            rows[state["where"]] += len(X)
            return decode(X)

        return counted

    for name in ("decode", "decode_keys"):  # decode_keys: the profiles as one array
        if hasattr(problem.encoding, name):
            monkeypatch.setattr(problem.encoding, name, counting(getattr(problem.encoding, name)))
    metrics = problem.metrics

    def watched(X, profiles=None):
        state["where"] = "inside"
        try:
            return metrics(X, profiles)
        finally:
            state["where"] = "outside"

    monkeypatch.setattr(problem, "metrics", watched)
    return rows


def test_fast_engine_decodes_each_offspring_once(ws, monkeypatch):
    problem = GridPathProblem(ws)
    rows = _count_decodes(monkeypatch, problem)
    n_eval = minimize(problem, FastNSGA2(40), ("n_gen", 4), seed=3).algorithm.evaluator.n_eval
    # every evaluated path was decoded for duplicate elimination, not again
    assert rows["outside"] >= n_eval > 0
    assert rows["inside"] == 0
    # without the profiles, each evaluation decodes its genomes
    problem2 = GridPathProblem(ws)
    problem2.accepts_profiles = False
    rows2 = _count_decodes(monkeypatch, problem2)
    minimize(problem2, FastNSGA2(40), ("n_gen", 4), seed=3)
    assert rows2["inside"] == n_eval
    assert rows2["outside"] == rows["outside"]


@pytest.mark.parametrize("encoding", ["integer", "binary", "mixed", "absolute"])
def test_decode_once_keeps_results_identical(ws, encoding):
    runs = []
    for accepts in (True, False):
        problem = GridPathProblem(ws, encoding=encoding)
        problem.accepts_profiles = accepts
        res = minimize(problem, FastNSGA2(30, encoding=encoding), ("n_gen", 4), seed=11)
        runs.append(res.algorithm.arrays)
    a, b = runs
    for key in ("X", "F", "G", "CV", "rank", "crowding"):
        np.testing.assert_array_equal(getattr(a, key), getattr(b, key))
    for key in ("smoothness", "interfering"):
        np.testing.assert_array_equal(a.data[key], b.data[key])


def test_metrics_checks_the_profiles(ws):
    problem = GridPathProblem(ws)
    X = np.zeros((3, problem.n_var), int)
    entries, exits = problem.encoding.decode(X)
    np.testing.assert_array_equal(problem.metrics(X, (entries, exits)), problem.metrics(X))
    with pytest.raises(ConfigError, match="profiles"):
        problem.metrics(X, (entries[:2], exits[:2]))


def test_progress_module_is_the_callbacks_module():
    import gapath.callbacks
    import gapath.progress

    for name in ("Callbacks", "ProgressBar", "population_status", "population_arrays"):
        assert getattr(gapath.progress, name) is getattr(gapath.callbacks, name)
