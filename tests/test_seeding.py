import numpy as np
import pytest

from gapath import ConfigError, NoPathError, Workspace
from gapath.generators import random_workspace
from gapath.objectives import evaluate_path
from gapath.operators import PlannerSampling
from gapath.operators.duplicates import duplicate_mask
from gapath.operators.sampling.planner_sampling import planner_paths
from gapath.planners.exact import monotone_front
from gapath.planners.weighted_sum import weighted_sum_path, weighted_sum_paths
from gapath.problems import GridPathProblem


def _grids():
    for seed in range(6):
        rng = np.random.default_rng(seed)
        h, w = rng.integers(5, 12, size=2)
        ws = random_workspace(
            (h, w),
            int(0.2 * h * w),
            seed=seed,
            start=(int(rng.integers(h)), 0),
            goal=(int(rng.integers(h)), w - 1),
        )
        yield ws.replace(corner_cutting=bool(seed % 2))


@pytest.mark.parametrize("ws", list(_grids()), ids=lambda ws: ws.name)
def test_weighted_sum_optimum_equals_best_point_of_exact_front(ws):
    try:
        exact = monotone_front(ws, ("length", "vulnerability"))
    except NoPathError:  # the guaranteed path may cut a corner the map forbids
        with pytest.raises(NoPathError):
            weighted_sum_path(ws)
        return
    for wl, wv in [(1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.2, 3.0), (5.0, 0.1)]:
        path = weighted_sum_path(ws, wl, wv)
        m = evaluate_path(ws, path)
        assert m["interfering"] == 0 and ws.is_valid_path(path)
        value = wl * m["length"] + wv * m["vulnerability"]
        best = (exact.F @ np.array([wl, wv])).min()
        assert value == pytest.approx(best, rel=1e-9, abs=1e-9)


def test_weighted_sum_paths_include_both_extremes():
    ws = random_workspace((16, 16), 50, seed=3)
    exact = monotone_front(ws)
    paths = weighted_sum_paths(ws, 5)
    F = np.array([[evaluate_path(ws, p)[k] for k in ("length", "vulnerability")] for p in paths])
    np.testing.assert_allclose(F[0], exact.F[0], rtol=1e-9)  # shortest
    np.testing.assert_allclose(F[1], exact.F[-1], rtol=1e-9)  # safest
    assert len({p.tobytes() for p in paths}) == len(paths)


def test_weighted_sum_errors():
    occ = np.zeros((5, 5), bool)
    occ[:, 2] = True  # a wall no monotone path crosses
    ws = Workspace(occ)
    with pytest.raises(NoPathError, match="no feasible column-monotone path"):
        weighted_sum_path(ws)
    assert planner_paths(ws, "weighted") == []
    with pytest.raises(ConfigError, match="weights"):
        weighted_sum_path(Workspace(np.zeros((3, 3), bool)), 0.0, 0.0)
    with pytest.raises(ConfigError, match="weights"):
        weighted_sum_path(Workspace(np.zeros((3, 3), bool)), -1.0, 1.0)


@pytest.mark.parametrize("source", ["weighted", "exact", "astar", "none"])
def test_planner_sampling_gives_distinct_valid_paths(source):
    ws = random_workspace((20, 20), 60, seed=1)
    p = GridPathProblem(ws)
    X = PlannerSampling(source)._do(p, 80, random_state=np.random.default_rng(0))
    assert X.shape == (80, p.n_var)
    assert (X >= p.xl).all() and (X <= p.xu).all()
    entries, exits = p.encoding.decode(X)
    assert not duplicate_mask(np.hstack([entries, exits])).any()
    seeds = planner_paths(ws, source)
    if seeds:
        assert np.array_equal(X[: len(seeds)][:1], p.encode(seeds[:1]))
    again = PlannerSampling(source)._do(p, 80, random_state=np.random.default_rng(0))
    assert np.array_equal(X, again)


def test_planner_sampling_caps_the_seeded_share():
    ws = random_workspace((20, 20), 60, seed=1)
    p = GridPathProblem(ws)
    n_exact = len(monotone_front(ws).paths)
    X = PlannerSampling("exact", max_share=0.1)._do(p, 40, random_state=np.random.default_rng(0))
    seeded = {x.tobytes() for x in p.encode(monotone_front(ws).paths).astype(X.dtype)}
    assert n_exact > 4
    assert sum(x.tobytes() in seeded for x in X) == 4  # 10 % of 40


def test_unknown_seed_source():
    with pytest.raises(ConfigError, match="unknown seed source 'magic'"):
        PlannerSampling("magic")


def test_seeded_solve_reaches_the_exact_extremes():
    from gapath.solver import solve

    ws = random_workspace((16, 16), 50, seed=5)
    exact = monotone_front(ws)
    r = solve(ws, pop_size=40, n_gen=10, seed=1)
    assert r.settings["seed_from"] == "weighted"
    np.testing.assert_allclose(r.front.F[0], exact.F[0], rtol=1e-9)
    np.testing.assert_allclose(r.front.F[-1], exact.F[-1], rtol=1e-9)


@pytest.mark.parametrize("encoding", ["integer", "binary", "mixed", "absolute"])
def test_seeded_solve_with_every_encoding(encoding):
    from gapath.solver import solve

    ws = random_workspace((12, 12), 30, seed=5)
    exact = monotone_front(ws)
    r = solve(ws, encoding=encoding, pop_size=30, n_gen=4, seed=1)
    assert r.problem.encoding.name == encoding
    np.testing.assert_allclose(r.front.F[0], exact.F[0], rtol=1e-9)  # the seeded shortest path
    X = PlannerSampling()._do(r.problem, 30, random_state=np.random.default_rng(0))
    assert X.dtype == (np.bool_ if encoding == "binary" else np.int64)


def test_monotone_projection_of_a_monotone_path_is_itself():
    from gapath.generators import random_monotone_path
    from gapath.monotone import Frame, monotone_projection, profiles_of_paths

    ws = random_workspace((15, 15), 0, seed=1)
    frame = Frame.of(ws)
    rng = np.random.default_rng(2)
    for _ in range(20):
        path = random_monotone_path(ws.shape, ws.start, ws.goal, rng, max_step=3)
        e, x = profiles_of_paths(frame, [path])
        pe, px = monotone_projection(frame, path)
        assert np.array_equal(px, x[0]) and np.array_equal(pe, e[0])


def test_astar_seeds_are_valid_monotone_paths():
    ws = random_workspace((20, 20), 60, seed=1)
    p = GridPathProblem(ws)
    paths = planner_paths(ws, "astar")
    assert len(paths) == 4
    for path in paths:
        assert ws.is_valid_path(path)
    p.encode(paths)  # representable in the integer encoding
