"""Worst-case layer objectives ``<layer>_max``: the largest value of a cell
layer over the path's cells. Recomputed cell by cell from the decoded paths
(free and monotone problems, any frame), their names and errors, and the
free GA's front against the exact (length, risk_max) front of a tiny map
found by enumerating every simple path."""

import numpy as np
import pytest

from gapath import ConfigError, Workspace
from gapath.costmap import CELL_MAX, CELL_MEAN, Costmap, fractal_terrain
from gapath.metrics import close
from gapath.planners import weighted_sum_astar
from gapath.problems import FreePathProblem, GridPathProblem
from gapath.solver import solve


def worst(cm, path, layer):
    """The maximum of ``layer`` over the path's cells, one cell at a time."""
    arr = cm.layer(layer)
    best = -1.0
    for r, c in path:
        best = max(best, float(arr[int(r), int(c)]))
    return best


def costmap(ws, seed=1):
    h, w = ws.shape
    rng = np.random.default_rng(seed)
    return Costmap(
        ws,
        elevation=fractal_terrain((h, w), seed),
        risk=[(h // 2, w // 2), (1, w - 3)],
        layers={"slope": rng.random((h, w))},
    )


def random_workspace(shape, seed, start=None, goal=None):
    rng = np.random.default_rng(seed)
    ws = Workspace(np.zeros(shape, bool), start, goal)
    occ = rng.random(shape) < 0.2
    occ[ws.start] = occ[ws.goal] = False
    return ws.replace(occ=occ)


def test_names_and_aggregation():
    ws = Workspace(np.zeros((4, 5), bool))
    cm = costmap(ws)
    assert cm.max_objective_names == ("elevation_max", "risk_max", "slope_max")
    assert cm.aggregation("risk_max") == CELL_MAX
    assert cm.aggregation("risk") == CELL_MEAN
    assert cm.base_layer("risk_max") == "risk"
    assert cm.base_layer("slope") == "slope"
    # the mean names stay the costmap's objective names; maxima only on request
    assert "risk_max" not in cm.objective_names
    assert cm.check_objectives("length,risk_max", maxima=True) == ("length", "risk_max")
    # a real layer called x_max keeps its name (and is a mean), no x_max_max clash
    cm.add_layer("slope_max", np.ones((4, 5)))
    assert "slope_max" not in cm.max_objective_names
    assert cm.aggregation("slope_max") == CELL_MEAN


def test_errors_name_the_objective():
    ws = Workspace(np.zeros((4, 5), bool))
    cm = Costmap(ws, risk=(1, 1))
    with pytest.raises(ConfigError, match="'elevation_max'"):
        FreePathProblem(ws, ("length", "elevation_max"), costmap=cm)
    with pytest.raises(ConfigError, match="given twice"):
        FreePathProblem(ws, ("length", "risk_max", "risk_max"), costmap=cm)
    # graph-search planners minimise sums: they refuse a maximum with the reason
    with pytest.raises(ConfigError, match="not a sum"):
        weighted_sum_astar(cm, ("length", "risk_max"))
    with pytest.raises(ConfigError, match="reads no cell layer"):
        cm.base_layer("length")


@pytest.mark.parametrize("encoding", ["field", "via"])
def test_free_problem_recomputes_from_paths(encoding):
    ws = random_workspace((12, 14), 5)
    cm = costmap(ws)
    names = ("length", "risk_max", "elevation", "slope_max")
    p = FreePathProblem(ws, names, costmap=cm, encoding=encoding)
    X = np.random.default_rng(2).random((50, p.n_var))
    out = p.evaluate(X, return_as_dictionary=True)
    paths = p.decode(X)
    maxima = set()
    for path, f in zip(paths, out["F"]):
        assert ws.is_valid_path(path)
        assert f[0] == pytest.approx(cm.evaluate_path(path, ["length"])["length"], rel=1e-12)
        assert f[1] == worst(cm, path, "risk")
        assert f[2] == pytest.approx(np.mean([cm.layer("elevation")[tuple(c)] for c in path]), rel=1e-12)
        assert f[3] == worst(cm, path, "slope")
        assert cm.evaluate_path(path, ["risk_max"])["risk_max"] == f[1]
        maxima.add(f[1])
    assert len(maxima) > 1  # the genomes reach different worst cells


@pytest.mark.parametrize(
    "start, goal",
    [(None, None), ((0, 8), (6, 1)), ((7, 4), (0, 4))],  # plain, mirrored, transposed frames
)
def test_monotone_problem_recomputes_from_paths(start, goal):
    ws = random_workspace((8, 9), 3, start, goal)
    cm = costmap(ws)
    p = GridPathProblem(ws, ("length", "risk_max", "slope"), costmap=cm)
    rng = np.random.default_rng(4)
    X = rng.integers(p.xl, p.xu + 1, size=(60, p.n_var))
    M = p.metrics(X)
    for path, row in zip(p.decode(X), M):
        assert row[4] == worst(cm, path, "risk")
        assert row[5] == pytest.approx(np.mean([cm.layer("slope")[tuple(c)] for c in path]), rel=1e-12)


def simple_paths(ws):
    """Every simple 8-connected path from start to goal (tiny maps)."""
    h, w = ws.shape
    out = []
    path = [ws.start]
    seen = {ws.start}

    def walk(cell):
        if cell == ws.goal:
            out.append(list(path))
            return
        r, c = cell
        for dr in (-1, 0, 1):
            for dc in (-1, 0, 1):
                n = (r + dr, c + dc)
                if (dr or dc) and 0 <= n[0] < h and 0 <= n[1] < w and not ws.occ[n] and n not in seen:
                    seen.add(n)
                    path.append(n)
                    walk(n)
                    path.pop()
                    seen.discard(n)

    walk(ws.start)
    return out


def brute_front(cm, paths):
    F = np.array([[cm.evaluate_path(p, ["length"])["length"], worst(cm, p, "risk")] for p in paths])
    keep = []
    for f in F:
        if not any(np.all(g <= f) and np.any(g < f) and not np.all(close(g, f)) for g in F):
            if not any(np.all(close(f, k)) for k in keep):
                keep.append(f)
    return np.array(keep)


def test_free_ga_front_is_never_better_than_the_brute_force_front():
    occ = np.zeros((4, 4), bool)
    occ[1, 1] = occ[2, 2] = True
    ws = Workspace(occ)
    cm = Costmap(ws, risk=[(1, 2), (2, 1)])
    exact = brute_front(cm, simple_paths(ws))
    assert len(exact) >= 2  # a real trade-off on this map
    r = solve(ws, objectives=("length", "risk_max"), paths="free", costmap=cm, pop_size=20, n_gen=15, seed=3)
    for path, f in zip(r.front.paths, r.front.F):
        assert f[1] == worst(cm, path, "risk")
        # no GA point beats the exact front, and each is on it or dominated by it
        assert not any(np.all(f <= e) and np.any(f < e) and not np.all(close(f, e)) for e in exact)
        assert any(np.all((e <= f) | close(e, f)) for e in exact)
