"""The adaptive penalty (gapath.constraints.AdaptivePenalty) and solve's
constraints="adaptive"."""

import numpy as np
import pytest

from gapath import dense_workspace, random_workspace
from gapath.algorithms.fast_nsga2 import pareto_ranks
from gapath.constraints import AdaptivePenalty
from gapath.errors import ConfigError
from gapath.experiments.runner import FirstFeasible
from gapath.solver import solve


def test_penalise_keeps_feasible_rows_and_adds_the_penalty_to_the_others():
    rng = np.random.default_rng(0)
    F = rng.random((50, 3)) * 40
    cv = rng.integers(0, 4, 50).astype(float)
    h = AdaptivePenalty(maximum=7.5)
    P = h.penalise(F, cv)
    feasible = cv == 0
    assert np.array_equal(P[feasible], F[feasible])  # bit for bit
    assert np.array_equal(P[~feasible], F[~feasible] + 7.5 * cv[~feasible, None])
    assert (P[~feasible] > F[~feasible]).all()


def test_update_stays_at_the_maximum_without_feasible_rows_and_stays_in_bounds():
    h = AdaptivePenalty(maximum=1000.0, target=0.3, factor=2.0, minimum=0.01)
    assert [h.update(0.0) for _ in range(5)] == [1000.0] * 5
    values = [h.update(1.0) for _ in range(30)]
    assert values[0] == 500.0 and all(a >= b for a, b in zip(values, values[1:]))
    assert values[-1] == 0.01
    assert h.update(0.29) == 0.02  # below the target: up again
    assert h.update(0.3) == 0.01  # at the target: down
    assert h.history[:5] == [1000.0] * 5 and len(h.history) == 37
    h.reset()
    assert h.value == 1000.0 and h.history == []


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(maximum=0),
        dict(maximum=-1),
        dict(factor=1.0),
        dict(target=-0.1),
        dict(initial=0.001),
        dict(initial=2000.0),
        dict(target="x"),
        dict(target=1.5),
        dict(minimum=0),
        dict(minimum=2000.0),
        dict(maximum="x"),
        dict(maximum=float("inf")),
    ],
)
def test_bad_settings_raise(kwargs):
    with pytest.raises(ConfigError, match="AdaptivePenalty"):
        AdaptivePenalty(**kwargs)


def _first_feasible_run(ws, seed, **kw):
    cb = FirstFeasible(stop=True)
    r = solve(ws, pop_size=60, n_gen=200, seed=seed, seed_from="none", callback=cb, **kw)
    return cb.generation, r


def test_adaptive_is_the_fixed_maximum_penalty_until_the_first_feasible_path():
    ws = dense_workspace(16, 0.6, 2)
    for seed in (1, 2, 3):
        g_fixed, fixed = _first_feasible_run(ws, seed, penalty=1000.0)
        g_adapt, adapt = _first_feasible_run(ws, seed, constraints="adaptive")
        assert g_fixed == g_adapt
        A, B = fixed.pymoo_result.algorithm.arrays, adapt.pymoo_result.algorithm.arrays
        assert np.array_equal(A.X, B.X)
        assert np.array_equal(fixed.front.F, adapt.front.F)
        hist = adapt.pymoo_result.algorithm.constraint_handling.history
        assert hist == [1000.0] * len(hist)


def test_adaptive_runs_are_deterministic_and_rank_on_the_penalised_objectives():
    ws = random_workspace((16, 16), 50, seed=4)
    runs = [
        solve(ws, pop_size=40, n_gen=40, seed=7, seed_from="none", constraints="adaptive") for _ in range(2)
    ]
    A0, A1 = (r.pymoo_result.algorithm for r in runs)
    assert np.array_equal(A0.arrays.X, A1.arrays.X)
    assert A0.constraint_handling.history == A1.constraint_handling.history
    assert runs[0].settings["constraints"] == "adaptive"
    hist = A0.constraint_handling.history
    assert len(hist) == 40 and min(hist) < 1000.0  # it adapted
    # the last survival ranked on F + penalty * CV: its rank-0 rows are
    # mutually non-dominated in those objectives, infeasible ones included
    arr = A0.arrays
    P = arr.F + hist[-1] * arr.CV[:, None]
    top = arr.rank == 0
    assert (pareto_ranks(P[top]) == 0).all()
    # the objectives kept on the individuals are unpenalised (constraint mode)
    M = runs[0].problem.metrics(arr.X)
    assert np.array_equal(arr.F, M[:, :2])
    assert np.array_equal(arr.CV, M[:, 3])
    # the front holds only feasible paths
    assert (runs[0].front.metrics[:, 3] == 0).all()


def test_adaptive_needs_the_fast_engine_and_known_keywords():
    ws = random_workspace((8, 8), 5, seed=1)
    with pytest.raises(ConfigError, match="engine='fast'"):
        solve(ws, pop_size=10, n_gen=2, constraints="adaptive", engine="pymoo")
    with pytest.raises(ConfigError, match="adaptive_penalty"):
        solve(ws, pop_size=10, n_gen=2, constraints="adaptive", adaptive_penalty={"start": 3.0})


def test_ramp_grows_only_without_feasible_rows():
    h = AdaptivePenalty(maximum=1000.0, target=0.0, minimum=0.01, initial=0.3)
    up = [h.update(0.0) for _ in range(15)]
    assert up[:3] == [0.6, 1.2, 2.4] and up[-1] == 1000.0
    down = [h.update(0.002) for _ in range(20)]  # one feasible survivor is enough
    assert down[0] == 500.0 and down == sorted(down, reverse=True) and down[-1] == 0.01


def test_solve_takes_the_adaptive_keywords():
    ws = dense_workspace(16, 0.9, 1)  # nothing feasible for a while
    r = solve(
        ws,
        pop_size=30,
        n_gen=6,
        seed=1,
        seed_from="none",
        constraints="adaptive",
        penalty=500.0,
        adaptive_penalty={"initial": 1.0, "target": 0.0},
    )
    h = r.pymoo_result.algorithm.constraint_handling
    assert r.settings["adaptive_penalty"] == h.settings()
    assert h.maximum == 500.0 and h.history[0] == 1.0
    assert h.history == [min(500.0, 2.0**k) for k in range(len(h.history))]
