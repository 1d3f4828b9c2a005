"""A*-PO, D*-PO and the weighted-sum A* / D* baselines (gapath.planners.pareto).

* path validity; on tiny grids, against every simple path (brute force):
  no path dominates the returned one in the search's cost sums, and the
  weighted-sum planners return the minimum of their weighted sum;
* A*-PO and D*-PO solve the same problem; with priority "length" the path is
  a shortest path;
* D*-PO (and weighted-sum D*) replanning after cell changes and robot moves
  equals a fresh plan on the new map;
* bad input.
"""

import math

import numpy as np
import pytest

from gapath import ConfigError, NoPathError, Workspace
from gapath.costmap import Costmap, fractal_terrain
from gapath.planners import astar
from gapath.planners.pareto import (
    PLANNERS,
    DStarPO,
    WeightedSumDStar,
    astar_po,
    plan,
    weighted_sum_astar,
)

MOVES = [(0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0), (1, 1)]
OBJS = ("length", "elevation", "solar", "risk")


def simple_paths(ws, limit=8000):
    """Every simple 8-connected path from start to goal (SPEC moves)."""
    occ = ws.occ
    h, w = occ.shape
    out, path, seen = [], [ws.start], {ws.start}

    def rec(u):
        if len(out) > limit:
            raise RuntimeError("too many paths")
        if u == ws.goal:
            out.append(list(path))
            return
        for dr, dc in MOVES:
            v = (u[0] + dr, u[1] + dc)
            if not (0 <= v[0] < h and 0 <= v[1] < w) or occ[v] or v in seen:
                continue
            if dr and dc and not ws.corner_cutting and (occ[u[0] + dr, u[1]] or occ[u[0], u[1] + dc]):
                continue
            seen.add(v)
            path.append(v)
            rec(v)
            path.pop()
            seen.discard(v)

    rec(ws.start)
    return out


def search_costs(cm, path, objectives, origin):
    """The search's cost sums (plain Python): length, cell layers summed over
    every waypoint, solar at the step index estimate = Chebyshev distance of
    the step's first cell from the origin."""
    out = []
    for o in objectives:
        if o == "length":
            out.append(
                sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(path, path[1:]))
                * cm.workspace.cell_size
            )
        elif o == "solar":
            total = 0.0
            for a, b in zip(path, path[1:]):
                dr, dc = b[0] - a[0], b[1] - a[1]
                k = max(abs(a[0] - origin[0]), abs(a[1] - origin[1]))
                th = cm.solar_angle0 + cm.solar_rate * k
                total += 0.5 * (1 + (dc * math.cos(th) - dr * math.sin(th)) / math.hypot(dr, dc))
            out.append(total)
        else:
            layer = cm.layer(o).tolist()
            out.append(sum(layer[r][c] for r, c in path))
    return np.array(out)


def dominated_by_any(costs, b, tol=1e-9):
    """Some row of ``costs`` dominates ``b`` beyond SPEC's tolerance."""
    eq = np.abs(costs - b) <= tol * np.maximum(1.0, np.maximum(np.abs(costs), np.abs(b)))
    return bool(np.any(np.all((costs <= b) | eq, axis=1) & np.any((costs < b) & ~eq, axis=1)))


def tiny_cases(n, seed):
    rng = np.random.default_rng(seed)
    cases = []
    while len(cases) < n:
        h, w = (int(v) for v in rng.integers(3, 5, 2))
        occ = rng.random((h, w)) < 0.2
        occ[h - 1, 0] = occ[0, w - 1] = False
        ws = Workspace(occ, corner_cutting=bool(rng.integers(2)))
        cm = Costmap(
            ws,
            elevation=rng.random((h, w)),
            risk=(int(rng.integers(h)), int(rng.integers(w))),
            solar_rate=float(rng.choice([0.0, 0.4, 1.0])),
            layers={"slope": rng.random((h, w))},
        )
        try:
            paths = simple_paths(ws)
        except RuntimeError:
            continue
        if paths:
            k = int(rng.integers(1, 5))
            objs = tuple(rng.choice(["length", "elevation", "solar", "risk", "slope"], k, replace=False))
            cases.append((cm, objs, paths))
    return cases


def check_path(ws, path):
    assert ws.is_valid_path(path)
    assert not ws.occ[path[:, 0], path[:, 1]].any()
    d = np.abs(np.diff(path, axis=0))
    if not ws.corner_cutting:
        for (r0, c0), (r1, c1) in zip(path[:-1], path[1:]):
            if r0 != r1 and c0 != c1:
                assert not ws.occ[r1, c0] and not ws.occ[r0, c1]
    assert (d.max(axis=1) == 1).all()


@pytest.mark.parametrize("seed", [0, 1])
def test_not_dominated_by_any_simple_path(seed):
    for cm, objs, paths in tiny_cases(25, seed):
        ws = cm.workspace
        costs = np.array([search_costs(cm, p, objs, ws.start) for p in paths])
        for priority in (None, "sum", objs[-1]):
            res = astar_po(cm, objs, priority=priority)
            check_path(ws, res.path)
            mine = search_costs(cm, [tuple(c) for c in res.path], objs, ws.start)
            np.testing.assert_allclose(res.search_cost, mine, rtol=1e-12, atol=1e-12)
            assert not dominated_by_any(costs, mine), (objs, priority, res.path.tolist())
            # D*-PO solves the same problem: the same minimum of the same order
            d = DStarPO(cm, objs, priority=priority).plan()
            check_path(ws, d.path)
            np.testing.assert_allclose(d.search_cost, res.search_cost, rtol=1e-12, atol=1e-12)
        if cm.solar_rate == 0.0:
            # a fixed sun: the search's costs are the path objectives as sums
            n = len(res.path)
            true = np.array([v * (n if o not in ("length", "solar") else 1) for o, v in zip(objs, res.F)])
            np.testing.assert_allclose(true, res.search_cost, rtol=1e-12, atol=1e-12)


def test_weighted_sum_planners_minimise_their_sum():
    rng = np.random.default_rng(5)
    for cm, objs, paths in tiny_cases(20, 11):
        ws = cm.workspace
        costs = np.array([search_costs(cm, p, objs, ws.start) for p in paths])
        # normalisers: the mean cost of a step (search_cost's length is in cell_size units)
        scale = np.array(
            [ws.cell_size if o == "length" else (0.5 if o == "solar" else cm.layer(o).mean()) for o in objs]
        )
        weights = rng.random(len(objs)) + 0.05
        total = (costs / scale) @ weights
        for res in (
            weighted_sum_astar(cm, objs, weights=weights),
            WeightedSumDStar(cm, objs, weights=weights).plan(),
        ):
            check_path(ws, res.path)
            assert (res.search_cost / scale) @ weights == pytest.approx(total.min(), rel=1e-12)


def test_length_priority_gives_a_shortest_path():
    rng = np.random.default_rng(2)
    occ = rng.random((30, 40)) < 0.25
    occ[29, 0] = occ[0, 39] = False
    ws = Workspace(occ)
    try:
        best = astar(ws).length
    except NoPathError:  # pragma: no cover - seed dependent
        pytest.skip("unreachable")
    cm = Costmap(ws, elevation=fractal_terrain((30, 40), 1), risk=(10, 10))
    for name in ("astar-po", "dstar-po"):
        assert plan(cm, name).length == best
    # the weighted sum trades length for the other objectives
    ws_res = plan(cm, "astar")
    assert ws_res.length >= best


def test_planners_agree_on_a_mars_like_map():
    from gapath.studies.mars import mars_costmap, mars_workspace

    ws = mars_workspace(3, size=40)
    cm = mars_costmap(ws, 3, dem="fractal")
    res = {name: plan(cm, name) for name in PLANNERS}
    for r in res.values():
        check_path(ws, r.path)
        assert r.objectives == OBJS and r.F.shape == (4,)
        assert r.F[0] == r.length
        vals = cm.evaluate_path(r.path)
        np.testing.assert_allclose(r.F, [vals[o] for o in OBJS])
    np.testing.assert_allclose(res["astar"].search_cost, res["dstar-lite"].search_cost, rtol=1e-9)
    np.testing.assert_allclose(res["astar-po"].search_cost, res["dstar-po"].search_cost, rtol=1e-9)


@pytest.mark.parametrize("cls", [DStarPO, WeightedSumDStar])
def test_replan_equals_fresh_plan(cls):
    rng = np.random.default_rng(8)
    h, w = 14, 17
    n_checked = 0
    for trial in range(4):
        occ = rng.random((h, w)) < 0.2
        occ[h - 1, 0] = occ[0, w - 1] = False
        ws = Workspace(occ, corner_cutting=bool(trial % 2))
        cm = Costmap(ws, elevation=fractal_terrain((h, w), trial), risk=(5, 7), solar_rate=0.3)
        planner = cls(cm)
        try:
            planner.plan()
        except NoPathError:
            pass
        for step in range(6):
            cells = [tuple(int(v) for v in c) for c in rng.integers(0, (h, w), size=(5, 2))]
            cells = [c for c in cells if c not in (planner.start, planner.goal)]
            if cells:
                planner.update_cells(cells, rng.random(len(cells)) < 0.6)
            if step % 2:
                try:
                    nxt = planner.replan().path
                    if len(nxt) > 2:
                        planner.move_to(tuple(nxt[1]))
                except NoPathError:
                    pass
            fresh_cm = cm.with_workspace(planner.workspace)
            try:
                got = planner.replan()
            except NoPathError:
                got = None
            try:
                want = cls(fresh_cm, origin=ws.start).plan()
            except NoPathError:
                want = None
            assert (got is None) == (want is None)
            if got is not None:
                check_path(planner.workspace, got.path)
                np.testing.assert_allclose(got.search_cost, want.search_cost, rtol=1e-12, atol=1e-12)
                np.testing.assert_allclose(got.F, want.F, rtol=1e-9, atol=1e-12)
                n_checked += 1
    assert n_checked >= 10


def test_bad_input():
    occ = np.zeros((5, 5), bool)
    occ[2, :] = True  # a wall: goal unreachable
    ws = Workspace(occ)
    cm = Costmap(ws, risk=(0, 0))
    for name in PLANNERS:
        with pytest.raises(NoPathError, match="no path"):
            plan(cm, name, ("length", "risk"))
    with pytest.raises(ConfigError, match="on an obstacle"):
        astar_po(cm, ("length",), start=(2, 2))
    with pytest.raises(ConfigError, match="on an obstacle"):
        DStarPO(cm, ("length",), goal=(2, 0))
    with pytest.raises(ConfigError, match="outside"):
        weighted_sum_astar(cm, ("length",), goal=(7, 0))
    with pytest.raises(ConfigError, match="unknown objective 'height'"):
        astar_po(cm, ("length", "height"))
    with pytest.raises(ConfigError, match="'elevation' is not set"):
        astar_po(cm, ("length", "elevation"))
    with pytest.raises(ConfigError, match="priority"):
        astar_po(cm, ("length", "risk"), priority="solar")
    with pytest.raises(ConfigError, match="one weight per objective"):
        weighted_sum_astar(cm, ("length", "risk"), weights=(1, 2, 3))
    with pytest.raises(ConfigError, match="not all 0"):
        weighted_sum_astar(cm, ("length", "risk"), weights=(0, 0))
    with pytest.raises(ConfigError, match="unknown planner"):
        plan(cm, "dijkstra")
    # D*-PO stays usable after NoPathError and after bad updates
    planner = DStarPO(cm, ("length", "risk"))
    with pytest.raises(NoPathError):
        planner.plan()
    with pytest.raises(ConfigError, match="cannot block the goal"):
        planner.update_cells([(0, 4)], blocked=True)
    planner.update_cells([(2, 3)], blocked=False)
    res = planner.replan()
    assert tuple(res.path[0]) == (4, 0) and tuple(res.path[-1]) == (0, 4)
    assert planner.occ[2, 3] == 0


def test_start_equals_goal_and_single_objective():
    ws = Workspace(np.zeros((3, 3), bool))
    cm = Costmap(ws, elevation=np.arange(9.0).reshape(3, 3))
    res = astar_po(cm, ("elevation",), goal=(2, 1))
    # elevation only: the lowest cells, whatever the length
    assert res.path.tolist()[0] == [2, 0] and res.path.tolist()[-1] == [2, 1]
    one = DStarPO(cm, ("length", "elevation"), goal=(2, 0)).plan()
    assert one.path.tolist() == [[2, 0]] and one.F[0] == 0.0


def test_cli_plan(tmp_path, data_dir):
    import json

    from gapath.cli import main

    out = tmp_path / "plan"
    rc = main(
        [
            "plan",
            "default",
            "--planner",
            "dstar-po",
            "--layers",
            "elevation,solar,risk",
            "--dem",
            str(data_dir / "dem" / "mars_dtm.npy"),
            "--dem-method",
            "reflect",
            "--risk",
            "10,12",
            "--out",
            str(out),
            "--quiet",
        ]
    )
    assert rc == 0
    assert sorted(p.name for p in out.iterdir()) == [
        "front.csv",
        "front.png",
        "paths.json",
        "paths.png",
        "summary.json",
    ]
    assert (out / "front.csv").read_text().splitlines()[0] == "length,elevation,solar,risk"
    summary = json.loads((out / "summary.json").read_text())
    assert summary["settings"]["planner"] == "dstar-po"
    assert summary["settings"]["risk_cells"] == [[10, 12]]
    rec = json.loads((out / "paths.json").read_text())
    assert len(rec) == 1 and rec[0]["path"][0] == [31, 0] and rec[0]["path"][-1] == [0, 31]
    assert set(rec[0]["objectives"]) == {"length", "elevation", "solar", "risk"}
    # length only, no plots
    assert (
        main(
            [
                "plan",
                "default",
                "--planner",
                "astar",
                "--layers",
                "",
                "--no-plots",
                "--out",
                str(tmp_path / "l"),
                "--quiet",
            ]
        )
        == 0
    )
    assert (tmp_path / "l" / "front.csv").read_text().splitlines()[0] == "length"
    # bad input: one message, exit status 2
    assert main(["plan", "default", "--layers", "height", "--out", str(tmp_path / "x")]) == 2
    assert main(["plan", "default", "--layers", "risk", "--risk", "99,99", "--out", str(tmp_path / "x")]) == 2


# ---------------------------------------------------------------------------
# Lavin's renormalised baselines (baseline="renormalised")
# ---------------------------------------------------------------------------


def renorm_maps():
    """Small maps with random blocks, fractal elevation and a risk cell."""
    out = []
    for seed in range(4):
        rng = np.random.default_rng([17, seed])
        h, w = 14, 18
        occ = rng.random((h, w)) < 0.2
        occ[h - 2 :, :2] = False
        occ[:2, w - 2 :] = False
        ws = Workspace(occ, corner_cutting=bool(seed % 2))
        try:
            astar(ws)
        except NoPathError:
            continue
        cm = Costmap(
            ws,
            elevation=fractal_terrain((h, w), seed=seed),
            risk=(h // 2, w // 2) if not occ[h // 2, w // 2] else ws.start,
            solar_rate=1.0,
        )
        out.append(cm)
    assert len(out) >= 3
    return out


@pytest.mark.parametrize("planner", ["astar", "dstar-lite"])
def test_renormalised_baselines_valid_and_deterministic(planner):
    for cm in renorm_maps():
        res = plan(cm, planner, OBJS, baseline="renormalised")
        ws = cm.workspace
        assert tuple(res.path[0]) == ws.start and tuple(res.path[-1]) == ws.goal
        check_path(ws, res.path)
        assert len({tuple(c) for c in res.path}) == len(res.path)  # no cell twice
        vals = cm.evaluate_path(res.path, OBJS)
        np.testing.assert_allclose(res.F, [vals[o] for o in OBJS])
        again = plan(cm, planner, OBJS, baseline="renormalised")
        np.testing.assert_array_equal(res.path, again.path)
        assert res.expansions == again.expansions


def test_renormalised_single_objective_is_plain_search():
    # min-max scaling of a single column keeps the order: plain A* / Dijkstra
    for cm in renorm_maps():
        best = astar(cm.workspace).length
        for planner in ("astar", "dstar-lite"):
            res = plan(cm, planner, ("length",), baseline="renormalised")
            assert res.F[0] == pytest.approx(best, rel=1e-12)


def test_renormalisation_changes_the_baseline():
    """The renormalised A* is not the weighted-sum optimum: on these maps the
    exact weighted sum is never worse, and strictly better on at least one
    (the order over the open list changes from step to step)."""
    strictly = 0
    for seed in range(3):
        from gapath.studies.mars import study_workspace

        _, cm = study_workspace(seed, size=40, dem="fractal")
        ws_res = weighted_sum_astar(cm, OBJS)
        for planner in ("astar", "dstar-lite"):
            rn = plan(cm, planner, OBJS, baseline="renormalised")
            # the weighted sum (statically normalised) of the search's cost sums
            wsum = weighted_sum_astar(cm, OBJS)  # same call twice: deterministic
            np.testing.assert_array_equal(wsum.path, ws_res.path)
            scale = np.array([1.0, cm.layer("elevation").mean(), 0.5, cm.layer("risk").mean()])
            a = float(np.sum(ws_res.search_cost / scale))
            b = float(np.sum(rn.search_cost / scale))
            assert a <= b * (1 + 1e-12)
            strictly += a < b * (1 - 1e-9)
    assert strictly >= 1


def test_renormalised_baseline_bad_input():
    cm = renorm_maps()[0]
    with pytest.raises(ConfigError, match="baseline"):
        plan(cm, "astar", OBJS, baseline="dynamic")
    with pytest.raises(ConfigError, match="baseline"):
        weighted_sum_astar(cm, OBJS, baseline="")
    blocked = Workspace(np.array([[0, 1, 0], [0, 1, 0], [0, 1, 0]], bool), start=(2, 0), goal=(0, 2))
    for planner in ("astar", "dstar-lite"):
        with pytest.raises(NoPathError):
            plan(Costmap(blocked), planner, ("length",), baseline="renormalised")
