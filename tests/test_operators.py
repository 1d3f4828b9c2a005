import numpy as np
import pytest
from pymoo.core.population import Population

from gapath import ConfigError, Workspace
from gapath.operators import (
    DiscretePM,
    DiscreteSBX,
    EdgeFixingRepair,
    PathDuplicateElimination,
    RankAndSmoothnessSurvival,
    compare_rank_smoothness_crowding,
    survival_order,
)
from gapath.operators.duplicates import duplicate_mask
from gapath.problems import GridPathProblem


def test_survival_order_on_hand_built_population():
    # front 0: a, b, c, d ; front 1: e, f
    F = np.array(
        [
            [1.0, 5.0],  # a  extreme
            [2.0, 3.0],  # b
            [3.0, 2.0],  # c
            [5.0, 1.0],  # d  extreme
            [3.0, 5.0],  # e  (dominated by b)
            [6.0, 2.0],
        ]
    )  # f  (dominated by c)
    smooth = np.array([2.0, 0.5, 0.5, 3.0, 0.0, 1.0])
    order, rank, crowding = survival_order(F, smooth)
    # rank first; inside rank 0 smoothness (b, c tie at 0.5 -> crowding), then a (2.0), d (3.0)
    assert rank.tolist() == [0, 0, 0, 0, 1, 1]
    assert order[:2].tolist() in ([1, 2], [2, 1])
    assert order[2:].tolist() == [0, 3, 4, 5]
    # without the tie-break: crowding only, extremes (infinite crowding) first
    order2, _, _ = survival_order(F)
    assert set(order2[:2].tolist()) == {0, 3}


def test_survival_truncates_last_front_by_smoothness():
    F = np.array([[1.0, 3.0], [2.0, 2.0], [3.0, 1.0], [4.0, 4.0]])
    smooth = np.array([3.0, 1.0, 2.0, 0.0])
    order, rank, _ = survival_order(F, smooth, n_survive=2)
    assert order.tolist() == [1, 2]
    assert rank.tolist() == [0, 0]


def test_infeasible_come_last_by_cv():
    F = np.array([[1.0, 1.0], [2.0, 2.0], [0.0, 0.0], [0.5, 0.5]])
    CV = np.array([[0.0], [0.0], [3.0], [1.0]])
    order, rank, crowding = survival_order(F, None, CV)
    assert order.tolist() == [0, 1, 3, 2]
    assert rank.tolist() == [0, 1, 2, 3]
    assert crowding[2:].tolist() == [0.0, 0.0]


def _pop(**cols):
    n = len(next(iter(cols.values())))
    pop = Population.new("X", np.zeros((n, 1)))
    for k, v in cols.items():
        pop.set(k, v)
    return pop


def test_tournament_order_of_criteria():
    pop = _pop(
        CV=np.array([[0.0], [1.0], [0.0], [0.0], [0.0], [0.0]]),
        rank=np.array([0, 0, 1, 0, 0, 0]),
        smoothness=np.array([1.0, 0.0, 0.0, 2.0, 1.0, 1.0]),
        crowding=np.array([1.0, 9.0, 9.0, 9.0, 2.0, 1.0]),
    )
    P = np.array(
        [
            [0, 1],  # feasible beats infeasible
            [2, 0],  # rank 0 beats rank 1
            [3, 0],  # equal rank: smoother wins
            [4, 0],  # equal rank and smoothness: more crowding wins
        ]
    )
    rng = np.random.default_rng(0)
    won = compare_rank_smoothness_crowding(pop, P, random_state=rng)[:, 0]
    assert won.tolist() == [0, 0, 0, 4]
    # without the tie-break, crowding decides pair (3, 0)
    won = compare_rank_smoothness_crowding(pop, P, random_state=rng, tiebreak=False)[:, 0]
    assert won.tolist() == [0, 0, 3, 4]
    # full tie: both sides win sometimes
    P = np.tile([[0, 5]], (200, 1))
    won = compare_rank_smoothness_crowding(pop, P, random_state=rng)[:, 0]
    assert set(won.tolist()) == {0, 5}


def test_duplicate_mask():
    k = np.array([[1, 2], [3, 4], [1, 2], [5, 6]])
    assert duplicate_mask(k).tolist() == [False, False, True, False]
    assert duplicate_mask(k, np.array([[5, 6]])).tolist() == [False, False, False, True]


def test_path_duplicates_are_found_through_decoding():
    ws = Workspace(np.zeros((5, 5), bool))
    p = GridPathProblem(ws)
    # gene values past the top edge are clamped: these decode to the same path
    X = np.array([[4, 0, 0, 0], [4, 0, 0, 0], [4, 1, 0, 0], [3, 0, 0, 0]])
    X[2, 1] = 3
    pop = Population.new("X", X)
    elim = PathDuplicateElimination().bind(p)
    kept = elim.do(pop)
    assert len(kept) == 2  # rows 0/1 identical genes; row 2 clamps onto row 0's path
    assert len(PathDuplicateElimination().do(pop)) == 3  # unbound: by genes


def test_discrete_operators_keep_integers(small_ws):
    p = GridPathProblem(small_ws)
    rng = np.random.default_rng(0)
    X = rng.integers(p.xl, p.xu + 1, size=(40, p.n_var))
    pop = Population.new("X", X)
    parents = rng.integers(0, 40, size=(20, 2))
    off = DiscreteSBX()(p, pop, parents, random_state=rng)
    Xo = off.get("X")
    assert np.issubdtype(Xo.dtype, np.integer)
    assert (Xo >= p.xl).all() and (Xo <= p.xu).all()
    mut = DiscretePM()(p, off, random_state=rng)
    Xm = mut.get("X")
    assert np.issubdtype(Xm.dtype, np.integer)
    assert (Xm >= p.xl).all() and (Xm <= p.xu).all()
    assert DiscretePM().get_prob_var(p) == pytest.approx(1 / (p.n_var + 1))


def test_edge_fixing_repair(small_ws):
    p = GridPathProblem(small_ws)
    X = np.full((5, p.n_var), 50)
    out = EdgeFixingRepair()._do(p, X, random_state=np.random.default_rng(0))
    assert (out >= p.xl).all() and (out <= p.xu).all()
    # deterministic without a random_state too
    a = EdgeFixingRepair()._do(p, X)
    b = EdgeFixingRepair()._do(p, X)
    assert np.array_equal(a, b)
    with pytest.raises(ConfigError, match="needs a gapath path problem"):
        from pymoo.problems import get_problem

        EdgeFixingRepair()._do(get_problem("zdt1"), X)


def test_survival_sets_rank_and_crowding(small_ws):
    p = GridPathProblem(small_ws)
    rng = np.random.default_rng(0)
    X = p.encoding.edge_fix(rng.integers(p.xl, p.xu + 1, size=(30, p.n_var)), rng)
    from pymoo.core.evaluator import Evaluator

    pop = Evaluator().eval(p, Population.new("X", X))
    surv = RankAndSmoothnessSurvival().do(p, pop, n_survive=10)
    assert len(surv) == 10
    assert surv.get("rank").dtype != object and surv.get("crowding").dtype != object
    with pytest.raises(ConfigError):
        RankAndSmoothnessSurvival(tiebreak="turns")
