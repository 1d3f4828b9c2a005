"""HypervolumeRatioCallback and plot_convergence on short GA runs."""

from __future__ import annotations

import numpy as np
import pytest
from pymoo.optimize import minimize

from gapath import ConfigError, default_workspace
from gapath.algorithms import paper_nsga2
from gapath.convergence import HypervolumeRatioCallback, plot_convergence
from gapath.front import path_front
from gapath.metrics import hv_ratio
from gapath.planners.exact import free_front, monotone_front
from gapath.problems import GridPathProblem


@pytest.fixture(scope="module")
def ws():
    return default_workspace()


@pytest.fixture(scope="module")
def reference(ws):
    return monotone_front(ws, ("length", "vulnerability"))


def _run(problem, callback, n_gen=6, pop_size=40, seed=3):
    return minimize(problem, paper_nsga2(pop_size), ("n_gen", n_gen), seed=seed, callback=callback)


def test_history_rows_match_the_final_population(ws, reference):
    problem = GridPathProblem(ws)
    cb = HypervolumeRatioCallback(reference)
    res = _run(problem, cb)
    H = cb.to_array()
    assert H.shape == (6, 3)
    assert H[:, 0].tolist() == [1, 2, 3, 4, 5, 6]
    assert (np.diff(H[:, 1]) > 0).all() and H[-1, 1] == res.algorithm.evaluator.n_eval
    assert ((H[:, 2] >= 0) & (H[:, 2] <= 1 + 1e-9)).all()
    # the last row is hv_ratio of the final population's front
    front = path_front(problem, res.algorithm.pop.get("X"))
    expected = hv_ratio(front.F, reference.F) if len(front) else 0.0
    assert H[-1, 2] == pytest.approx(expected, abs=1e-12)
    # elitist survival: the ratio never falls much (only crowding may drop points)
    assert H[-1, 2] >= H[0, 2] - 1e-9


def test_problem_decoding_gives_the_same_values(ws, reference):
    problem = GridPathProblem(ws)
    by_columns = HypervolumeRatioCallback(reference)
    _run(problem, by_columns, n_gen=3)
    by_decoding = HypervolumeRatioCallback(reference, problem=problem)
    _run(problem, by_decoding, n_gen=3)
    np.testing.assert_allclose(by_columns.to_array(), by_decoding.to_array(), atol=1e-12)


@pytest.mark.parametrize("constraints", ["penalty", "constraint"])
def test_fast_engine_history_equals_paper_nsga2s(ws, reference, constraints):
    from gapath.algorithms import FastNSGA2
    from gapath.operators import PlannerSampling

    problem = GridPathProblem(ws, constraints=constraints)
    histories = []
    seeded = dict(sampling=PlannerSampling("weighted"))
    for algorithm in (FastNSGA2(40, **seeded), paper_nsga2(40, **seeded)):
        cb = HypervolumeRatioCallback(reference)
        res = minimize(problem, algorithm, ("n_gen", 5), seed=2, callback=cb)
        histories.append(cb.to_array())
    assert histories[0][-1, 2] > 0
    # same populations (bit-identical engines), same columns read: same history
    np.testing.assert_array_equal(histories[0], histories[1])
    front = path_front(problem, res.pop.get("X"))
    expected = hv_ratio(front.F, reference.F) if len(front) else 0.0
    assert histories[0][-1, 2] == pytest.approx(expected, abs=1e-12)


def test_constraint_mode_and_free_reference(ws):
    problem = GridPathProblem(ws, constraints="constraint")
    free = free_front(ws)
    cb = HypervolumeRatioCallback(free)
    _run(problem, cb, n_gen=3)
    H = cb.to_array()
    assert len(H) == 3
    # the GA only reaches monotone paths: below the free front's hypervolume
    assert (H[:, 2] < 1.0).all()


def test_reference_columns_follow_the_problem(ws):
    lv = monotone_front(ws, ("length", "vulnerability"))
    vl = monotone_front(ws, ("vulnerability", "length"))
    a = HypervolumeRatioCallback(lv)
    _run(GridPathProblem(ws), a, n_gen=2)
    b = HypervolumeRatioCallback(vl)
    _run(GridPathProblem(ws), b, n_gen=2)
    np.testing.assert_allclose(a.to_array(), b.to_array(), atol=1e-12)


def test_mismatched_reference_raises(ws):
    three = monotone_front(ws, ("length", "vulnerability", "smoothness"))
    with pytest.raises(ConfigError):
        _run(GridPathProblem(ws), HypervolumeRatioCallback(three), n_gen=1)
    with pytest.raises(ConfigError):
        HypervolumeRatioCallback(np.zeros((0, 2)))


def test_plot_convergence(tmp_path):
    history = [(1, 40, 0.2), (2, 80, 0.5), (3, 120, 0.7)]
    out = plot_convergence(history, tmp_path / "conv.png")
    assert out == tmp_path / "conv.png" and out.stat().st_size > 1000
    out = plot_convergence(np.array(history), tmp_path / "conv.svg", x="n_gen", label="run 1")
    assert out.read_text().lstrip().startswith("<?xml")

    from matplotlib.figure import Figure

    ax = Figure().add_subplot()
    assert plot_convergence(history, ax, label="a") is ax
    assert len(ax.lines) == 2  # the curve and the 1.0 line
    with pytest.raises(ConfigError):
        plot_convergence(history, tmp_path / "x.png", x="time")
    with pytest.raises(ConfigError):
        plot_convergence([[1, 2]], tmp_path / "x.png")


def test_fast_tolerance_front_is_nondominated_with_tolerance():
    from gapath.convergence import _nondominated_tol
    from gapath.metrics import TOL, nondominated

    rng = np.random.default_rng(0)
    for trial in range(30):
        n, m = rng.integers(65, 400), rng.integers(2, 4)
        F = rng.integers(0, 12, size=(n, m)).astype(float)  # many ties
        # near-ties within and just outside the tolerance
        F += rng.choice([0.0, 0.5e-9, -0.5e-9, 5e-9], size=F.shape) * np.maximum(1, np.abs(F))
        if trial % 3 == 0:
            F = np.vstack([F, F[:20]])  # exact duplicates
        np.testing.assert_array_equal(_nondominated_tol(F), nondominated(F, tol=TOL))


def test_every_row_is_the_hv_ratio_of_that_generation(ws, reference):
    """Each row (also those reusing the last generation's value when the
    front did not change) equals the ratio computed from scratch."""
    from pymoo.core.callback import Callback

    from gapath.algorithms import FastNSGA2
    from gapath.callbacks import Callbacks, population_arrays
    from gapath.operators import PlannerSampling

    problem = GridPathProblem(ws)

    class Direct(Callback):
        def __init__(self):
            super().__init__()
            self.rows = []

        def notify(self, algorithm):
            F = path_front(problem, population_arrays(algorithm).X).F
            self.rows.append(hv_ratio(F, reference.F) if len(F) else 0.0)

    cb, direct = HypervolumeRatioCallback(reference), Direct()
    minimize(
        problem,
        FastNSGA2(40, sampling=PlannerSampling("weighted")),
        ("n_gen", 12),
        seed=4,
        callback=Callbacks(cb, direct),
    )
    H = cb.to_array()
    np.testing.assert_allclose(H[:, 2], direct.rows, rtol=0, atol=1e-12)
    assert len(set(H[:, 2])) < len(H)  # some generations kept their front
