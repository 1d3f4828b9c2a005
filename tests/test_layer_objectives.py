"""Costmap layers as GA objectives: GridPathProblem(..., costmap=cm) computes
layer objectives with a numba kernel over column profiles; they must equal a
plain-Python computation on the decoded paths (any frame: plain, mirrored,
transposed)."""

import math

import numpy as np
import pytest

from gapath import ConfigError, Workspace
from gapath.costmap import Costmap, fractal_terrain
from gapath.front import path_front
from gapath.problems import GridPathProblem


def plain_python(cm, path, name):
    """The paper's definitions, cell by cell and step by step."""
    path = [tuple(int(v) for v in c) for c in path]
    if name == "solar":
        total = 0.0
        th0, rate = cm.solar_angle0, cm.solar_rate
        for k, (a, b) in enumerate(zip(path, path[1:])):
            dr, dc = b[0] - a[0], b[1] - a[1]
            x, y = dc / math.hypot(dr, dc), -dr / math.hypot(dr, dc)  # east, north
            sx, sy = math.cos(th0 + rate * k), math.sin(th0 + rate * k)
            total += 0.5 * (1.0 + x * sx + y * sy)
        return total
    layer = cm.layer(name)
    return sum(float(layer[c]) for c in path) / len(path)


def make_costmap(ws, seed):
    h, w = ws.shape
    rng = np.random.default_rng(seed)
    return Costmap(
        ws,
        elevation=fractal_terrain((h, w), seed),
        risk=(h // 2, w // 3),
        solar_rate=0.37,
        solar_angle0=0.2,
        layers={"slope": rng.random((h, w))},
    )


@pytest.mark.parametrize(
    "start, goal",
    [
        (None, None),  # bottom-left -> top-right (plain frame)
        ((0, 8), (6, 1)),  # goal left of the start: mirrored frame
        ((7, 4), (0, 4)),  # same column: transposed frame
        ((1, 6), (7, 6)),  # same column, downwards
    ],
)
def test_kernel_matches_plain_python(start, goal):
    rng = np.random.default_rng(3)
    occ = rng.random((8, 9)) < 0.2
    ws = Workspace(np.zeros((8, 9), bool), start, goal)
    occ[ws.start] = occ[ws.goal] = False
    ws = ws.replace(occ=occ)
    cm = make_costmap(ws, 1)
    names = ("length", "elevation", "solar", "risk", "slope")
    p = GridPathProblem(ws, objectives=names, costmap=cm)
    X = rng.integers(p.xl, p.xu + 1, size=(60, p.n_var))
    M = p.metrics(X)
    assert M.shape == (60, 4 + 4)
    assert p.layer_objectives == ("elevation", "solar", "risk", "slope")
    for path, row in zip(p.decode(X), M):
        assert ws.is_valid_path(path)
        for j, name in enumerate(p.layer_objectives):
            assert row[4 + j] == pytest.approx(plain_python(cm, path, name), rel=1e-12, abs=1e-12)
        values = cm.evaluate_path(path, names)
        assert row[0] == values["length"]
    # F: unpenalised objectives + penalty * interfering, in the requested order
    out = {}
    p._evaluate(X, out)
    np.testing.assert_allclose(out["F"], M[:, [0, 4, 5, 6, 7]] + 1000.0 * M[:, [3]])


def test_existing_objectives_unchanged_and_mixed_order():
    ws = Workspace(np.zeros((6, 7), bool))
    cm = make_costmap(ws, 2)
    X = np.random.default_rng(0).integers(-3, 4, size=(20, 6))
    plain = GridPathProblem(ws)
    mixed = GridPathProblem(ws, objectives="risk,length,vulnerability,solar", costmap=cm)
    np.testing.assert_array_equal(mixed.metrics(X)[:, :4], plain.metrics(X))
    out_p, out_m = {}, {}
    plain._evaluate(X, out_p)
    mixed._evaluate(X, out_m)
    np.testing.assert_array_equal(out_m["F"][:, [1, 2]], out_p["F"])
    assert mixed.n_obj == 4 and mixed.objectives == ("risk", "length", "vulnerability", "solar")
    front = path_front(mixed, X)
    assert front.F.shape[1] == 4 and len(front) >= 1
    for f, path in zip(front.F, front.paths):
        assert f[0] == pytest.approx(plain_python(cm, path, "risk"))


def test_layer_objective_errors():
    ws = Workspace(np.zeros((5, 5), bool))
    with pytest.raises(ConfigError, match="unknown objective 'elevation'"):
        GridPathProblem(ws, objectives=("length", "elevation"))
    cm = Costmap(ws)  # no elevation set
    with pytest.raises(ConfigError, match="unknown objective 'elevation'"):
        GridPathProblem(ws, objectives=("length", "elevation"), costmap=cm)
    with pytest.raises(ConfigError, match="given twice"):
        GridPathProblem(ws, objectives=("solar", "length", "solar"), costmap=cm)
    other = Costmap(Workspace(np.zeros((4, 5), bool)))
    with pytest.raises(ConfigError, match="differs"):
        GridPathProblem(ws, objectives=("length", "solar"), costmap=other)
