from types import SimpleNamespace

import numpy as np
import pytest
from pymoo.core.population import Population
from pymoo.operators.crossover.pntx import TwoPointCrossover
from pymoo.operators.sampling.rnd import BinaryRandomSampling, IntegerRandomSampling
from pymoo.optimize import minimize
from pymoo.termination import get_termination
from pymoo.termination.max_gen import MaximumGenerationTermination

from gapath import ConfigError, Workspace
from gapath.algorithms import paper_nsga2
from gapath.front import path_front
from gapath.generators import random_workspace
from gapath.objectives import evaluate_path
from gapath.operators import (
    DecayingBitflipMutation,
    DiscretePM,
    DiscreteSBX,
    MixedCrossover,
    MixedMutation,
    default_operators,
)
from gapath.operators.mutation.decaying_bitflip import final_generation
from gapath.problems import GridPathProblem

ENCODINGS = ["integer", "binary", "mixed", "absolute"]


@pytest.fixture(scope="module")
def ws():
    return random_workspace((12, 12), 25, seed=4)


def _population(p, rng, n=40):
    X = p.encoding.edge_fix(
        BinaryRandomSampling()._do(p, n, random_state=rng)
        if p.encoding.vtype is bool
        else rng.integers(p.xl, p.xu + 1, size=(n, p.n_var)),
        rng,
    )
    return Population.new("X", X)


def _fake_algorithm(n_gen, termination):
    return SimpleNamespace(n_gen=n_gen, termination=termination)


# -- defaults -------------------------------------------------------------


def test_default_operators_per_encoding():
    ops = default_operators("integer")
    assert isinstance(ops["sampling"], IntegerRandomSampling)
    assert isinstance(ops["crossover"], DiscreteSBX) and isinstance(ops["mutation"], DiscretePM)
    assert ops["crossover"].prob.value == 0.9 and ops["crossover"].eta.value == 10
    assert ops["mutation"].eta.value == 20
    assert type(default_operators("absolute")["crossover"]) is DiscreteSBX
    ops = default_operators("binary")
    assert isinstance(ops["sampling"], BinaryRandomSampling)
    assert type(ops["crossover"]) is TwoPointCrossover and ops["crossover"].prob.value == 0.9
    assert isinstance(ops["mutation"], DecayingBitflipMutation) and ops["mutation"].prob_var is None
    ops = default_operators("mixed")
    assert isinstance(ops["crossover"], MixedCrossover) and isinstance(ops["mutation"], MixedMutation)
    assert ops["crossover"].eta.value == 10 and ops["mutation"].eta.value == 20
    assert default_operators("mixed")["crossover"] is not ops["crossover"]  # fresh each call
    with pytest.raises(ConfigError, match="unknown encoding 'gray'"):
        default_operators("gray")


def test_paper_nsga2_takes_the_encodings_operators(ws):
    for name in ENCODINGS:
        algo = paper_nsga2(10, encoding=name)
        assert type(algo.mating.crossover) is type(default_operators(name)["crossover"])
        assert type(algo.mating.mutation) is type(default_operators(name)["mutation"])
        assert type(algo.initialization.sampling) is type(default_operators(name)["sampling"])
    with pytest.raises(ConfigError, match="unknown encoding 'gray'"):
        paper_nsga2(10, encoding="gray")


def test_paper_nsga2_refuses_another_encoding(ws):
    p = GridPathProblem(ws, encoding="integer")
    with pytest.raises(
        ConfigError,
        match="paper_nsga2 was configured for the 'binary' encoding but the problem uses 'integer'",
    ):
        minimize(p, paper_nsga2(10, encoding="binary"), ("n_gen", 2), seed=1)


def test_paper_nsga2_sampling_override_still_works(ws):
    p = GridPathProblem(ws, encoding="binary")
    X = p.encoding.edge_fix(np.random.default_rng(0).random((12, p.n_var)) < 0.5, np.random.default_rng(1))
    res = minimize(p, paper_nsga2(12, encoding="binary", sampling=X), ("n_gen", 1), seed=1)
    got = res.pop.get("X")
    assert got.dtype == bool
    assert {r.tobytes() for r in got} <= {r.tobytes() for r in X}


# -- binary operators ----------------------------------------------------


def test_two_point_crossover_keeps_booleans(ws):
    p = GridPathProblem(ws, encoding="binary")
    rng = np.random.default_rng(0)
    pop = _population(p, rng)
    parents = rng.integers(0, len(pop), size=(20, 2))
    off = TwoPointCrossover(prob=1.0)(p, pop, parents, random_state=rng)
    Xo = off.get("X")
    assert Xo.dtype == bool and Xo.shape == (40, p.n_var)
    X = pop.get("X")
    for k, (a, b) in enumerate(parents):
        c1, c2 = Xo[k], Xo[20 + k]
        differ = X[a] != X[b]
        swapped = c1 != X[a]
        assert not (swapped & ~differ).any()
        assert np.array_equal(c2, np.where(swapped, X[a], X[b]))
        idx = np.flatnonzero(swapped)
        if len(idx):  # one contiguous swapped segment
            assert swapped[idx[0] : idx[-1] + 1][differ[idx[0] : idx[-1] + 1]].all()


@pytest.mark.parametrize("dtype", [bool, np.int64])
def test_decaying_bitflip_keeps_booleans(ws, dtype):
    p = GridPathProblem(ws, encoding="binary")
    X = (np.random.default_rng(0).random((30, p.n_var)) < 0.5).astype(dtype)
    Y = DecayingBitflipMutation(prob_var=0.2)._do(p, X, random_state=np.random.default_rng(1))
    assert Y.dtype == bool and Y.shape == X.shape
    assert 0 < (Y != X.astype(bool)).mean() < 0.3
    pop = DecayingBitflipMutation()(
        p, Population.new("X", X.astype(bool)), random_state=np.random.default_rng(2)
    )
    assert pop.get("X").dtype == bool


def test_decaying_rate_schedule():
    m = DecayingBitflipMutation(prob_var=0.05)
    term = MaximumGenerationTermination(101)
    assert m.rate(None, _fake_algorithm(1, term)) == pytest.approx(0.05)
    assert m.rate(None, _fake_algorithm(51, term)) == pytest.approx(0.05 * 0.6)
    assert m.rate(None, _fake_algorithm(101, term)) == pytest.approx(0.01)
    assert m.rate(None, _fake_algorithm(500, term)) == pytest.approx(0.01)  # past the end: clipped
    # unknown final generation, or no algorithm: the initial rate
    assert m.rate(None, _fake_algorithm(80, get_termination("time", "00:01:00"))) == 0.05
    assert m.rate(None, _fake_algorithm(80, None)) == 0.05
    assert m.rate(None) == 0.05
    assert m.rate(None, _fake_algorithm(1, MaximumGenerationTermination(1))) == 0.05
    # default: 1 / n_bits
    assert DecayingBitflipMutation().rate(SimpleNamespace(n_var=200), None) == pytest.approx(1 / 200)


def test_final_generation_of_pymoo_terminations():
    from pymoo.core.termination import TerminateIfAny
    from pymoo.termination.default import DefaultMultiObjectiveTermination

    assert final_generation(get_termination("n_gen", 40)) == 40
    assert final_generation(DefaultMultiObjectiveTermination(n_max_gen=300)) == 300
    assert final_generation(TerminateIfAny(get_termination("n_gen", 70), get_termination("n_gen", 50))) == 50
    assert final_generation(get_termination("n_eval", 1000)) is None
    assert final_generation(MaximumGenerationTermination()) is None  # infinite


def test_decaying_bitflip_is_stateless_and_flips_at_its_rate():
    p = SimpleNamespace(n_var=100)
    m = DecayingBitflipMutation(prob_var=0.1)
    before = dict(vars(m))
    X = np.zeros((4000, 100), bool)
    term = MaximumGenerationTermination(11)
    last = m._do(p, X, random_state=np.random.default_rng(0), algorithm=_fake_algorithm(11, term))
    first = m._do(p, X, random_state=np.random.default_rng(0), algorithm=_fake_algorithm(1, term))
    assert last.mean() == pytest.approx(0.02, abs=0.002)
    assert first.mean() == pytest.approx(0.1, abs=0.003)
    # same call, same result: nothing carried over between calls
    again = m._do(p, X, random_state=np.random.default_rng(0), algorithm=_fake_algorithm(11, term))
    assert np.array_equal(last, again)
    assert vars(m).keys() == before.keys() and all(vars(m)[k] is before[k] for k in before)


def test_decaying_rate_in_a_run(ws):
    seen = []

    class Spy(DecayingBitflipMutation):
        def _do(self, problem, X, random_state=None, algorithm=None, **kwargs):
            seen.append((algorithm.n_gen, self.rate(problem, algorithm)))
            return super()._do(problem, X, random_state=random_state, algorithm=algorithm, **kwargs)

    p = GridPathProblem(ws, encoding="binary")
    algo = paper_nsga2(20, encoding="binary")
    algo.mating.mutation = Spy()
    minimize(p, algo, ("n_gen", 5), seed=1)
    p0 = 1 / p.n_var
    gens = sorted({g for g, _ in seen})
    assert gens == [2, 3, 4, 5]  # offspring of generations 2..5
    for g, rate in seen:
        assert rate == pytest.approx(p0 * (1 - 0.8 * (g - 1) / 4))


# -- mixed operators -----------------------------------------------------


def test_mixed_crossover_keeps_integers_and_bounds(ws):
    p = GridPathProblem(ws, encoding="mixed")
    rng = np.random.default_rng(0)
    pop = _population(p, rng)
    parents = rng.integers(0, len(pop), size=(20, 2))
    off = MixedCrossover(prob=1.0)(p, pop, parents, random_state=rng)
    Xo = off.get("X")
    assert np.issubdtype(Xo.dtype, np.integer)
    assert (Xo >= p.xl).all() and (Xo <= p.xu).all()
    m = p.encoding.n_bits
    X = pop.get("X")
    for k, (a, b) in enumerate(parents):
        c1, c2 = Xo[k, :m], Xo[20 + k, :m]
        # single point: a prefix of one parent then the rest of the other
        cut = [j for j in range(1, m) if np.array_equal(c1, np.r_[X[a, :j], X[b, j:m]])]
        assert cut and np.array_equal(c2, np.r_[X[b, : cut[0]], X[a, cut[0] : m]])
    # same seed, same children
    again = MixedCrossover(prob=1.0)(p, pop, parents, random_state=np.random.default_rng(0))
    first = MixedCrossover(prob=1.0)(p, pop, parents, random_state=np.random.default_rng(0))
    assert np.array_equal(again.get("X"), first.get("X"))


def test_mixed_operators_on_a_two_column_grid():
    # one gene: one bit (no crossing point) and one integer
    p = GridPathProblem(Workspace(np.zeros((5, 2), bool)), encoding="mixed")
    rng = np.random.default_rng(0)
    pop = Population.new("X", np.array([[0, 1], [1, 4], [1, 0], [0, 3]]))
    off = MixedCrossover(prob=1.0)(p, pop, np.array([[0, 1], [2, 3]]), random_state=rng)
    assert (off.get("X") >= p.xl).all() and (off.get("X") <= p.xu).all()
    mut = MixedMutation()(p, off, random_state=rng)
    assert (mut.get("X") >= p.xl).all() and (mut.get("X") <= p.xu).all()


def test_mixed_mutation_keeps_integers_and_bounds(ws):
    p = GridPathProblem(ws, encoding="mixed")
    rng = np.random.default_rng(0)
    X = np.tile(np.r_[np.zeros(p.encoding.n_bits, int), np.full(p.encoding.n_genes, 6)], (3000, 1))
    m = MixedMutation()
    assert m.gene_rate(p) == pytest.approx(1 / (p.encoding.n_genes + 1))  # 1/n, n columns
    Y = m._do(p, X, random_state=rng)
    assert np.issubdtype(Y.dtype, np.integer)
    assert (Y >= p.xl).all() and (Y <= p.xu).all()
    nb = p.encoding.n_bits
    assert Y[:, :nb].mean() == pytest.approx(m.gene_rate(p), abs=0.01)  # bits flipped 0 -> 1
    changed = (Y[:, nb:] != 6).mean()  # PM (eta 20) then rounding often lands back on 6
    assert 0.01 < changed <= m.gene_rate(p) + 0.01


# -- end to end ------------------------------------------------------------


def _nondominated(F):
    return not any((b <= a).all() and (b < a).any() for a in F for b in F)


@pytest.mark.parametrize("encoding", ENCODINGS)
def test_end_to_end_per_encoding(ws, encoding):
    p = GridPathProblem(ws, encoding=encoding)
    res = minimize(p, paper_nsga2(40, encoding=encoding), ("n_gen", 15), seed=1)
    X = res.pop.get("X")
    assert X.dtype == (bool if encoding == "binary" else np.int64)
    assert (X >= p.xl).all() and (X <= p.xu).all()
    front = path_front(p, X)
    assert len(front) >= 1 and _nondominated(front.F)
    for f, path in zip(front.F, front.paths):
        assert ws.is_valid_path(path) and len({tuple(c) for c in path}) == len(path)
        recomputed = evaluate_path(ws, path)
        assert recomputed["interfering"] == 0
        np.testing.assert_allclose(f, [recomputed["length"], recomputed["vulnerability"]], rtol=1e-12)
    again = minimize(p, paper_nsga2(40, encoding=encoding), ("n_gen", 15), seed=1)
    assert np.array_equal(again.pop.get("X"), X)
