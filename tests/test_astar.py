"""Tests of gapath.planners.astar.

* MovingAI: a deterministic sample of every ``.scen`` file under
  ``movingai/mapf`` and ``movingai/grid`` (every 25th line; every 100th for
  the files with more than 2000 lines), maps loaded with their default rule
  (MovingAI's: no corner cutting); cost == column 9 within
  ``abs(a - b) <= 1e-5 * max(1, b)`` (data/README.md).
* Agreement with a brute-force Dijkstra (plain Python) on random small grids,
  both corner rules, with and without a cost layer.
* The documented tie-breaking: paths and expansion counts equal those of a
  plain-Python A* with a ``heapq`` open list ordered the same way; the open
  list (held-back entry) pops like a plain heap; the move mask follows the
  move rule; scratch arrays reused across grids and threads.
* Returned paths are valid; every error case.
"""

from __future__ import annotations

import dataclasses
import heapq
import math
import threading
from pathlib import Path

import numpy as np
import pytest
from data_files import glob_data

from gapath import ConfigError, NoPathError, Workspace
from gapath.grid import DC, DR, can_step, move_mask
from gapath.openlist import HELD, NOT_HELD, open_decrease, open_pop, open_push
from gapath.planners.astar import PlanResult, astar

SQRT2 = math.sqrt(2.0)


# ---------------------------------------------------------------------------
# real data (tests/data, plus ../shared/data when present)
# ---------------------------------------------------------------------------

#: Every ``.scen`` file of tests/data (the small maps, always there) and of
#: the optional shared data folder (the 256x256 and 512x512 maps), once each.
SCEN_FILES = glob_data("movingai/*/*.scen")


def _load_movingai_sample(scen_path: Path):
    """``(occ, [(start, goal, optimal), ...])`` of a ``.scen`` file and its map."""
    try:
        from gapath.loaders import load_movingai, load_scenarios
    except ImportError:  # pragma: no cover - before gapath.loaders existed
        return _read_movingai_fallback(scen_path)
    scens = load_scenarios(scen_path)
    ref = next(s for s in scens if s.start != s.goal)
    ws = load_movingai(ref.resolve_map(), ref.start, ref.goal)  # MovingAI's rule by default
    assert ws.corner_cutting is False
    return ws.occ, [(s.start, s.goal, s.optimal) for s in scens]


def _read_movingai_fallback(scen_path: Path):  # pragma: no cover
    lines = scen_path.read_text().splitlines()[1:]
    rows = [ln.split("\t") for ln in lines if ln.strip()]
    map_name = rows[0][1].replace("\\", "/").split("/")[-1]
    text = (scen_path.parent / map_name).read_text().splitlines()
    h = int(text[1].split()[1])
    grid = [ln.rstrip("\r") for ln in text[4 : 4 + h]]
    occ = np.array([[ch not in ".GS" for ch in ln] for ln in grid], dtype=bool)
    scens = [((int(r[5]), int(r[4])), (int(r[7]), int(r[6])), float(r[8])) for r in rows]
    return occ, scens


# ---------------------------------------------------------------------------
# reference solver and path checks
# ---------------------------------------------------------------------------


def brute_force(occ, start, goal, corner_cutting, cost=None) -> float:
    """Plain-Python Dijkstra over the 8-connected grid (inf if unreachable)."""
    h, w = occ.shape
    dist = {start: 0.0}
    queue = [(0.0, start)]
    while queue:
        d, (r, c) = heapq.heappop(queue)
        if d > dist[(r, c)]:
            continue
        if (r, c) == goal:
            return d
        for dr in (-1, 0, 1):
            for dc in (-1, 0, 1):
                rr, cc = r + dr, c + dc
                if (dr, dc) == (0, 0) or not (0 <= rr < h and 0 <= cc < w) or occ[rr, cc]:
                    continue
                if dr and dc and not corner_cutting and (occ[r + dr, c] or occ[r, c + dc]):
                    continue
                step = SQRT2 if dr and dc else 1.0
                if cost is not None:
                    step *= 1.0 + (cost[r, c] + cost[rr, cc]) / 2.0
                nd = d + step
                if nd < dist.get((rr, cc), math.inf):
                    dist[(rr, cc)] = nd
                    heapq.heappush(queue, (nd, (rr, cc)))
    return math.inf


def assert_valid_path(res: PlanResult, occ, start, goal, corner_cutting, cell_size=1.0, cost=None):
    path = res.path
    assert isinstance(path, np.ndarray) and path.ndim == 2 and path.shape[1] == 2
    assert np.issubdtype(path.dtype, np.integer)
    assert tuple(path[0]) == tuple(start) and tuple(path[-1]) == tuple(goal)
    h, w = occ.shape
    assert (path[:, 0] >= 0).all() and (path[:, 0] < h).all()
    assert (path[:, 1] >= 0).all() and (path[:, 1] < w).all()
    assert not occ[path[:, 0], path[:, 1]].any(), "path crosses an obstacle"
    steps = np.diff(path, axis=0)
    assert (np.abs(steps).max(axis=1) == 1).all(), "consecutive cells must be 8-adjacent"
    n_diag = 0
    total = 0.0
    for (r, c), (dr, dc) in zip(path[:-1], steps):
        if dr and dc:
            n_diag += 1
            if not corner_cutting:
                assert not occ[r + dr, c] and not occ[r, c + dc], "diagonal cuts a corner"
        if cost is not None:
            total += (SQRT2 if dr and dc else 1.0) * (1 + (cost[r, c] + cost[r + dr, c + dc]) / 2)
    n_straight = len(steps) - n_diag
    length = (n_straight + SQRT2 * n_diag) * cell_size
    assert res.length == length
    if cost is None:
        assert res.cost == res.length
    else:
        assert res.cost == pytest.approx(total * cell_size, rel=1e-12)
    assert res.expansions >= 1 and res.seconds >= 0


def random_grid(rng, max_side=14):
    h, w = (int(v) for v in rng.integers(2, max_side + 1, size=2))
    occ = rng.random((h, w)) < rng.uniform(0.0, 0.45)
    free = np.argwhere(~occ)
    if len(free) < 2:
        occ[0, 0] = occ[-1, -1] = False
        free = np.argwhere(~occ)
    i, j = rng.choice(len(free), size=2, replace=False)
    return occ, tuple(int(v) for v in free[i]), tuple(int(v) for v in free[j])


# ---------------------------------------------------------------------------
# MovingAI benchmark sample
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("scen_path", SCEN_FILES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_movingai_sample_matches_optimal(scen_path):
    occ, scens = _load_movingai_sample(scen_path)
    stride = 25 if len(scens) <= 2000 else 100
    ws = _workspace_for(occ, scens)
    bad = []
    sample = scens[::stride]
    for start, goal, optimal in sample:
        res = astar(ws, start, goal)
        if abs(res.cost - optimal) > 1e-5 * max(1.0, optimal):
            bad.append((start, goal, optimal, res.cost))
    assert not bad, f"{len(bad)}/{len(sample)} mismatches, first: {bad[:3]}"
    # the last sampled query also yields a valid path
    assert_valid_path(res, occ, start, goal, corner_cutting=False)


def _workspace_for(occ, scens):
    start, goal, _ = next(s for s in scens if s[0] != s[1])
    return Workspace(occ, start, goal, corner_cutting=False)


# ---------------------------------------------------------------------------
# agreement with brute force
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("corner_cutting", [False, True])
@pytest.mark.parametrize("with_cost", [False, True])
def test_agrees_with_brute_force_dijkstra(corner_cutting, with_cost):
    rng = np.random.default_rng(1000 + 2 * corner_cutting + with_cost)
    n_reachable = 0
    for _ in range(150):
        occ, start, goal = random_grid(rng)
        cost = None
        if with_cost:
            cost = rng.uniform(0.0, 3.0, occ.shape) * (rng.random(occ.shape) < 0.7)
        ws = Workspace(occ, start, goal, corner_cutting=corner_cutting)
        expected = brute_force(occ, start, goal, corner_cutting, cost)
        if math.isinf(expected):
            with pytest.raises(NoPathError):
                astar(ws, cost=cost)
            continue
        n_reachable += 1
        res = astar(ws, cost=cost)
        assert res.cost == pytest.approx(expected, rel=1e-12, abs=1e-12)
        assert_valid_path(res, occ, start, goal, corner_cutting, cost=cost)
    assert n_reachable > 75


@pytest.mark.parametrize("heuristic", ["octile", "euclidean", "chebyshev", "zero"])
def test_every_heuristic_is_optimal(heuristic):
    rng = np.random.default_rng(7)
    for _ in range(40):
        occ, start, goal = random_grid(rng)
        expected = brute_force(occ, start, goal, False)
        ws = Workspace(occ, start, goal, corner_cutting=False)
        if math.isinf(expected):
            continue
        res = astar(ws, heuristic=heuristic)
        assert res.cost == pytest.approx(expected, rel=1e-12)
        assert_valid_path(res, occ, start, goal, False)


def test_weights():
    rng = np.random.default_rng(11)
    for _ in range(40):
        occ, start, goal = random_grid(rng, max_side=20)
        expected = brute_force(occ, start, goal, True)
        if math.isinf(expected):
            continue
        ws = Workspace(occ, start, goal)
        assert astar(ws, weight=0.0).cost == pytest.approx(expected, rel=1e-12)
        assert astar(ws, weight=0.5).cost == pytest.approx(expected, rel=1e-12)
        res = astar(ws, weight=2.5)
        assert expected - 1e-9 <= res.cost <= 2.5 * expected + 1e-9
        assert_valid_path(res, occ, start, goal, True)


def test_octile_expands_fewer_cells_than_dijkstra():
    ws = Workspace(np.zeros((40, 40), bool))
    a = astar(ws)
    d = astar(ws, heuristic="zero")
    assert a.cost == d.cost == 39 * SQRT2
    assert a.expansions == 40 < d.expansions


# ---------------------------------------------------------------------------
# tie-breaking and the kernel's building blocks
# ---------------------------------------------------------------------------


def _h(kind, r, c, tr, tc):
    dr, dc = abs(r - tr), abs(c - tc)
    if kind == "octile":
        return dc + (SQRT2 - 1.0) * dr if dr < dc else dr + (SQRT2 - 1.0) * dc
    if kind == "euclidean":
        return math.sqrt(dr * dr + dc * dc)
    if kind == "chebyshev":
        return float(max(dr, dc))
    return 0.0


def reference_astar(occ, start, goal, corner_cutting, cost=None, weight=1.0, heuristic="octile"):
    """Plain-Python A* with the documented order: ``(f, weight * h, index)``,
    moves E, NE, N, NW, W, SW, S, SE, parent changed only on a smaller g.
    Returns ``(path, expansions)`` (path None if unreachable)."""
    h, w = occ.shape
    s, t = start[0] * w + start[1], goal[0] * w + goal[1]
    g, parent, closed = {s: 0.0}, {s: -1}, set()
    hs = weight * _h(heuristic, *start, *goal)
    queue = [(hs, hs, s)]
    expansions = 0
    while queue:
        _, _, u = heapq.heappop(queue)
        if u in closed:  # stale copy
            continue
        closed.add(u)
        expansions += 1
        if u == t:
            path = []
            while u != -1:
                path.append(divmod(u, w))
                u = parent[u]
            return path[::-1], expansions
        r, c = divmod(u, w)
        for k in range(8):
            if not can_step(occ, r, c, DR[k], DC[k], corner_cutting):
                continue
            v = u + int(DR[k]) * w + int(DC[k])
            if v in closed:
                continue
            step = SQRT2 if k & 1 else 1.0
            if cost is not None:
                step *= 1.0 + 0.5 * (cost.flat[u] + cost.flat[v])
            ng = g[u] + step
            if v in g and ng >= g[v]:
                continue
            g[v], parent[v] = ng, u
            hv = weight * _h(heuristic, *divmod(v, w), *goal)
            heapq.heappush(queue, (ng + hv, hv, v))
    return None, expansions


def test_paths_and_expansions_follow_the_documented_order():
    rng = np.random.default_rng(2024)
    n_checked = 0
    for i in range(300):
        occ, start, goal = random_grid(rng, max_side=18)
        corner_cutting = bool(i % 2)
        kwargs = {}
        if i % 3 == 0:
            kwargs["cost"] = rng.uniform(0.0, 2.0, occ.shape) * (rng.random(occ.shape) < 0.5)
        if i % 5 == 0:
            kwargs["weight"] = float(rng.choice([0.0, 0.5, 2.0, 3.5]))
        if i % 7 == 0:
            kwargs["heuristic"] = str(rng.choice(["euclidean", "chebyshev", "zero"]))
        expected, expansions = reference_astar(occ, start, goal, corner_cutting, **kwargs)
        ws = Workspace(occ, start, goal, corner_cutting=corner_cutting)
        if expected is None:
            with pytest.raises(NoPathError, match=f"closed {expansions} cells"):
                astar(ws, **kwargs)
            continue
        res = astar(ws, **kwargs)
        assert res.path.tolist() == [list(cell) for cell in expected]
        assert res.expansions == expansions
        n_checked += 1
    assert n_checked > 150


def test_open_list_pops_like_a_plain_heap():
    """Random pushes and decreases, with many ties: the held-back entry never
    changes the order."""
    rng = np.random.default_rng(9)
    n = 400
    for _ in range(20):
        heap = np.empty(3 * n)
        where = np.zeros(n, np.int64)
        key = {}
        size, held = 0, NOT_HELD
        popped, expected = [], []
        for _ in range(3 * n):
            op = rng.random()
            open_nodes = [v for v in key if where[v] != 0]
            if op < 0.45 and len(key) < n:
                v = int(rng.integers(n))
                if v in key:
                    continue
                key[v] = (float(rng.integers(0, 6)), float(rng.integers(0, 3)))
                size, held = open_push(heap, where, size, held, *key[v], v)
            elif op < 0.7 and open_nodes:
                v = int(rng.choice(open_nodes))
                k1, k2 = key[v]
                key[v] = (k1 - float(rng.integers(0, 2)), k2 - float(rng.integers(0, 2)))
                held = open_decrease(heap, where, held, *key[v], v)
            else:
                best = min(((key[v][0], key[v][1], v) for v in open_nodes), default=None)
                v, size, held = open_pop(heap, where, size, held)
                expected.append(-1 if best is None else best[2])
                popped.append(v)
                if v >= 0:
                    where[v] = 0
                    key[v] = (math.inf, math.inf)  # closed: never pushed again
            n_open = sum(1 for v in key if where[v] != 0)
            assert size + (held[2] >= 0) == n_open
            assert sum(1 for v in key if where[v] == HELD) == (held[2] >= 0)
        assert popped == expected


@pytest.mark.parametrize("corner_cutting", [False, True])
def test_move_mask_follows_the_move_rule(corner_cutting):
    rng = np.random.default_rng(4)
    for _ in range(30):
        h, w = (int(v) for v in rng.integers(1, 9, size=2))
        occ = rng.random((h, w)) < 0.4
        flat = occ.ravel()
        for r in range(h):
            for c in range(w):
                mask = move_mask(flat, h, w, r, c, corner_cutting)
                for k in range(8):
                    assert bool(mask >> k & 1) == can_step(occ, r, c, DR[k], DC[k], corner_cutting)


def test_scratch_reuse_across_grids_and_threads():
    rng = np.random.default_rng(12)
    cases = []
    for side in (40, 7, 90, 3, 40):
        occ = rng.random((side, side + 3)) < 0.2
        occ[-1, 0] = occ[0, -1] = False
        cases.append(Workspace(occ, corner_cutting=False))
    first = []
    for ws in cases:
        try:
            first.append(astar(ws))
        except NoPathError:
            first.append(None)

    def check(out):
        for ws, ref in zip(cases * 3, first * 3):
            try:
                res = astar(ws)
            except NoPathError:
                res = None
            out.append(
                ref is res is None
                or (
                    ref is not None
                    and res is not None
                    and np.array_equal(res.path, ref.path)
                    and res.expansions == ref.expansions
                )
            )

    results = []
    threads = [threading.Thread(target=check, args=(results,)) for _ in range(4)]
    for th in threads:
        th.start()
    check(results)
    for th in threads:
        th.join()
    assert len(results) == 5 * 15 and all(results)


# ---------------------------------------------------------------------------
# semantics
# ---------------------------------------------------------------------------


def test_corner_rule():
    occ = np.array([[1, 0], [0, 1]], bool)
    ws = Workspace(occ, (1, 0), (0, 1), corner_cutting=True)
    res = astar(ws)
    assert res.path.tolist() == [[1, 0], [0, 1]] and res.cost == SQRT2
    with pytest.raises(NoPathError, match="corner cutting not allowed"):
        astar(ws.replace(corner_cutting=False))
    # one blocked side is enough to forbid the diagonal
    occ = np.array([[0, 0], [0, 1]], bool)
    res = astar(Workspace(occ, (1, 0), (0, 1), corner_cutting=False))
    assert res.path.tolist() == [[1, 0], [0, 0], [0, 1]] and res.cost == 2.0


def test_cost_layer_detour():
    occ = np.zeros((3, 3), bool)
    cost = np.zeros((3, 3))
    cost[1, 1] = 10.0
    res = astar(Workspace(occ, (1, 0), (1, 2)), cost=cost)
    assert res.path.tolist() in ([[1, 0], [0, 1], [1, 2]], [[1, 0], [2, 1], [1, 2]])
    assert res.cost == pytest.approx(2 * SQRT2)
    assert res.length == pytest.approx(2 * SQRT2)
    plain = astar(Workspace(occ, (1, 0), (1, 2)))
    assert plain.path.tolist() == [[1, 0], [1, 1], [1, 2]] and plain.cost == 2.0
    # a uniform layer scales the cost, not the length
    res = astar(Workspace(occ, (1, 0), (1, 2)), cost=np.full((3, 3), 2))
    assert res.cost == pytest.approx(6.0) and res.length == 2.0


def test_cell_size_scales_cost_and_length():
    rng = np.random.default_rng(3)
    occ, start, goal = random_grid(rng, max_side=25)
    occ[:] = False
    base = astar(Workspace(occ, start, goal))
    res = astar(Workspace(occ, start, goal, cell_size=0.25))
    assert res.length == base.length * 0.25 and res.cost == res.length
    cost = rng.uniform(0, 1, occ.shape)
    base = astar(Workspace(occ, start, goal), cost=cost)
    res = astar(Workspace(occ, start, goal, cell_size=0.25), cost=cost)
    assert res.cost == pytest.approx(base.cost * 0.25, rel=1e-12)


def test_start_goal_overrides_and_same_cell():
    ws = Workspace(np.zeros((5, 6), bool))
    res = astar(ws, start=(2, 2), goal=(2, 5))
    assert res.path.tolist() == [[2, 2], [2, 3], [2, 4], [2, 5]] and res.cost == 3.0
    res = astar(ws, start=(1, 1), goal=(1, 1))
    assert res.path.tolist() == [[1, 1]] and res.cost == 0.0 and res.length == 0.0


def test_deterministic_and_result_is_immutable():
    rng = np.random.default_rng(5)
    occ = rng.random((30, 30)) < 0.25
    occ[-1, 0] = occ[0, -1] = False
    ws = Workspace(occ, corner_cutting=False)
    try:
        first = astar(ws)
    except NoPathError:  # pragma: no cover - seed dependent
        pytest.skip("unreachable sample")
    for _ in range(3):
        again = astar(Workspace(occ.copy(), corner_cutting=False))
        assert np.array_equal(again.path, first.path)
        assert again.cost == first.cost and again.expansions == first.expansions
    with pytest.raises(dataclasses.FrozenInstanceError):
        first.cost = 0.0
    with pytest.raises(ValueError):
        first.path[0, 0] = 5
    assert "PlanResult(" in repr(first)


def test_cost_layer_is_not_modified_and_ints_accepted():
    occ = np.zeros((4, 4), bool)
    cost = np.arange(16).reshape(4, 4)
    keep = cost.copy()
    res = astar(Workspace(occ), cost=cost)
    assert np.array_equal(cost, keep)
    assert res.cost > res.length


# ---------------------------------------------------------------------------
# errors
# ---------------------------------------------------------------------------


@pytest.fixture
def ws():
    occ = np.zeros((3, 4), bool)
    occ[1, 1] = True
    return Workspace(occ)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(start=(3, 0)), r"start \(3, 0\) is outside the 3x4 grid"),
        (dict(start=(0, -1)), r"start \(0, -1\) is outside"),
        (dict(goal=(0, 4)), r"goal \(0, 4\) is outside"),
        (dict(start=(1, 1)), r"start \(1, 1\) is on an obstacle"),
        (dict(goal=(1, 1)), r"goal \(1, 1\) is on an obstacle"),
        (dict(start=(1,)), r"start must be a \(row, col\) pair"),
        (dict(start="ab"), r"start must be a \(row, col\) pair"),
        (dict(goal=(0.5, 1)), r"goal must be a \(row, col\) pair"),
        (dict(cost=np.zeros((4, 3))), r"cost must have the grid's shape \(3, 4\), got shape \(4, 3\)"),
        (dict(cost=np.zeros(12)), r"got shape \(12,\)"),
        (dict(cost=np.full((3, 4), np.nan)), r"cost must be finite, got nan at \(row 0, col 0\)"),
        (dict(cost=np.where(np.eye(3, 4, k=2) > 0, np.inf, 0.0)), r"finite, got inf at \(row 0, col 2\)"),
        (dict(cost=-np.eye(3, 4)), r"non-negative, got -1\.0 at \(row 0, col 0\)"),
        (dict(cost=np.full((3, 4), "x")), r"cost must be a numeric array"),
        (dict(cost=np.ones((3, 4), bool)), r"cost must be a numeric array"),
        (dict(weight=-1), r"weight must be a finite number >= 0, got -1"),
        (dict(weight=float("nan")), r"weight must be a finite number >= 0"),
        (dict(weight="heavy"), r"weight must be a non-negative number, got 'heavy'"),
        (dict(heuristic="manhattan"), r"heuristic must be one of .*got 'manhattan'"),
    ],
)
def test_config_errors(ws, kwargs, match):
    with pytest.raises(ConfigError, match=match):
        astar(ws, **kwargs)


def test_no_path_error_is_raised_not_a_numba_error():
    occ = np.zeros((5, 5), bool)
    occ[:, 2] = True
    ws = Workspace(occ)
    with pytest.raises(NoPathError, match=r"no path from start \(4, 0\) to goal \(0, 4\)") as info:
        astar(ws)
    assert isinstance(info.value, ValueError)
    with pytest.raises(NoPathError):
        astar(ws, cost=np.ones((5, 5)))
