"""The k-objective exact free search (``free_front`` with costmap layers or
``search="k"``): brute force over all simple paths (2, 3, 4 objectives,
summed layers, solar at rate 0) and over all walks (solar at a non-zero
rate, where the step index is part of the state), agreement with the
specialised searches on random maps, non-dominance, bit-exact ``F``, the
label budget, progress and bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gapath import ConfigError, NoPathError, Workspace, random_workspace
from gapath.costmap import Costmap, fractal_terrain
from gapath.errors import LabelBudgetError
from gapath.grid import DC, DR, SQRT2, turn
from gapath.objectives import evaluate_path
from gapath.planners.exact import exact_front, exact_path_front, free_front, path_objectives

TOL = 1e-9


def _eq(a, b):
    return abs(a - b) <= TOL * max(1.0, abs(a), abs(b))


def _dominates(a, b):
    le = all(x <= y or _eq(x, y) for x, y in zip(a, b))
    return le and any(not _eq(x, y) for x, y in zip(a, b))


def _front(V):
    """Tolerance-non-dominated vectors, one per tolerance-equal class."""
    V = sorted(map(tuple, V))
    keep = [v for v in V if not any(_dominates(u, v) for u in V)]
    out = []
    for v in keep:
        if not any(all(_eq(x, y) for x, y in zip(u, v)) for u in out):
            out.append(v)
    return np.array(out)


def assert_same_front(A, B):
    assert len(A) == len(B), (len(A), len(B))
    for a in A:
        assert any(all(_eq(x, y) for x, y in zip(a, b)) for b in B), a


def _costmap(ws, seed, rate=0.0):
    h, w = ws.shape
    rng = np.random.default_rng(seed)
    cm = Costmap(
        ws,
        elevation=fractal_terrain((h, w), seed=seed),
        risk=(int(rng.integers(h)), int(rng.integers(w))),
        solar_rate=rate,
        solar_angle0=float(rng.uniform(0, 2 * np.pi)),
    )
    cm.add_layer("sand", rng.integers(0, 3, (h, w)).astype(float))
    cm.add_layer("dust", 0.5 + rng.random((h, w)))  # > 0: bounds the walks' brute force
    return cm


def _values(ws, cm, names):
    """Per-cell layer arrays and the per-step solar table for the brute force."""
    cells = {}
    for n in names:
        if n == "vulnerability":
            cells[n] = ws.potential
        elif n.endswith("_sum"):
            cells[n] = cm.layer(n[:-4])
    table = cm.solar_table(1000) if "solar" in names else None
    return cells, table


def brute_simple(ws, names, cm=None):
    """Objective vectors of every feasible simple path (DFS), summed in path
    order like the search."""
    h, w = ws.shape
    occ = ws.occ
    cells, table = _values(ws, cm, names)
    (sr, sc), goal = ws.start, ws.goal
    out = []
    seen = np.zeros((h, w), bool)

    def ok(r, c, d):
        r2, c2 = r + DR[d], c + DC[d]
        if not (0 <= r2 < h and 0 <= c2 < w) or occ[r2, c2]:
            return False
        if d % 2 and not ws.corner_cutting and (occ[r, c2] or occ[r2, c]):
            return False
        return True

    def dfs(r, c, head, ns, nd, turns, sums, k):
        if (r, c) == goal:
            vec = []
            for n in names:
                if n == "length":
                    vec.append((ns + SQRT2 * nd) * ws.cell_size)
                elif n == "smoothness":
                    vec.append(turns * math.pi / 4)
                else:
                    vec.append(sums[n])
            out.append(vec)
            return
        for d in range(8):
            if not ok(r, c, d):
                continue
            r2, c2 = r + DR[d], c + DC[d]
            if seen[r2, c2]:
                continue
            s2 = dict(sums)
            for n, arr in cells.items():
                s2[n] = sums[n] + float(arr[r2, c2])
            if table is not None:
                s2["solar"] = sums["solar"] + float(table[k if cm.solar_rate else 0, d])
            seen[r2, c2] = True
            dfs(
                r2,
                c2,
                d,
                ns + (1 - d % 2),
                nd + d % 2,
                turns + (turn(head, d) if head >= 0 else 0),
                s2,
                k + 1,
            )
            seen[r2, c2] = False

    seen[sr, sc] = True
    start = {n: float(a[sr, sc]) for n, a in cells.items()}
    start["solar"] = 0.0
    dfs(sr, sc, -1, 0, 0, 0, start, 0)
    return np.array(out)


def _maps():
    out = []
    for seed in range(4):
        rng = np.random.default_rng(seed)
        h, w = (3, 4) if seed % 2 else (4, 3)
        occ = rng.random((h, w)) < 0.2
        start, goal = (h - 1, 0), (0, w - 1)
        occ[start] = occ[goal] = False
        out.append(Workspace(occ, start, goal, corner_cutting=bool(seed % 3 == 0), name=f"tiny{seed}"))
    return out


MAPS = _maps()
SETS = [
    ("length", "risk_sum"),
    ("elevation_sum", "length"),
    ("vulnerability", "smoothness", "sand_sum"),
    ("length", "elevation_sum", "solar", "risk_sum"),
    ("length", "vulnerability", "smoothness", "elevation_sum"),
]


@pytest.mark.parametrize("names", SETS, ids=lambda n: "+".join(n))
@pytest.mark.parametrize("index", range(len(MAPS)))
def test_front_equals_brute_force_over_simple_paths(index, names):
    ws = MAPS[index]
    cm = _costmap(ws, index)
    try:
        front = free_front(ws, names, costmap=cm)
    except NoPathError:
        assert len(brute_simple(ws, names, cm)) == 0
        return
    assert_same_front(front.F, _front(brute_simple(ws, names, cm)))
    for p in front.paths:  # simple paths
        assert len({tuple(c) for c in p}) == len(p)


def test_brute_force_cases_are_non_trivial():
    sizes = []
    for i, ws in enumerate(MAPS):
        try:
            sizes.append(len(free_front(ws, SETS[3], costmap=_costmap(ws, i))))
        except NoPathError:
            pass
    assert len(sizes) >= 3 and max(sizes) >= 4


def brute_walks(ws, names, cm):
    """The front of all walks (cells may repeat) when the solar cost depends
    on the step index: exact Pareto sets per (cell, step count), walks of up
    to K steps, K grown until a lower bound of every longer walk is dominated
    by a point found."""
    h, w = ws.shape
    occ = ws.occ
    cells, table = _values(ws, cm, names)
    lo = {n: float(a[~occ].min()) for n, a in cells.items()}
    assert names[0] == "length"
    min_step = np.concatenate([[0.0], np.cumsum(table.min(axis=1))])
    (sr, sc), goal = ws.start, ws.goal

    def vec(r, c, ns, nd, turns, sums):
        out = []
        for n in names:
            out.append((ns + SQRT2 * nd) * ws.cell_size if n == "length" else sums[n])
        return tuple(out)

    layer = {(sr, sc): [(0, 0, 0, -1, {**{n: float(a[sr, sc]) for n, a in cells.items()}, "solar": 0.0})]}
    found = []
    k = 0
    while True:
        for (r, c), labels in layer.items():
            if (r, c) == goal:
                found += [vec(r, c, *lab[:3], lab[4]) for lab in labels]
        bound = tuple(
            k * ws.cell_size if n == "length" else (min_step[k] if n == "solar" else (k + 1) * lo[n])
            for n in names
        )
        if any(_dominates(f, bound) for f in found):
            break
        nxt = {}
        for (r, c), labels in layer.items():
            if (r, c) == goal:
                continue
            for ns, nd, _turns, _head, sums in labels:
                for d in range(8):
                    r2, c2 = r + DR[d], c + DC[d]
                    if not (0 <= r2 < h and 0 <= c2 < w) or occ[r2, c2]:
                        continue
                    if d % 2 and not ws.corner_cutting and (occ[r, c2] or occ[r2, c]):
                        continue
                    s2 = {n: sums[n] + float(a[r2, c2]) for n, a in cells.items()}
                    s2["solar"] = sums["solar"] + float(table[k, d])
                    nxt.setdefault((r2, c2), []).append((ns + (1 - d % 2), nd + d % 2, 0, d, s2))
        # exact (no tolerance) Pareto filter per state (same future costs), and
        # drop walks a solution already weakly dominates (every objective only
        # grows, the length strictly)
        layer = {}
        for key, labels in nxt.items():
            vs = [vec(*key, *lab[:3], lab[4]) for lab in labels]
            keep, kept = [], []
            for i in sorted(range(len(vs)), key=lambda i: vs[i]):
                if not any(all(x <= y for x, y in zip(u, vs[i])) for u in kept + found):
                    kept.append(vs[i])
                    keep.append(labels[i])
            layer[key] = keep
        k += 1
        assert k < 900
    return _front(found)


def _walk_map(seed):
    rng = np.random.default_rng(seed)
    h, w = [(4, 4), (4, 5), (5, 5)][seed % 3]
    occ = rng.random((h, w)) < 0.15
    occ[h - 1, 0] = occ[0, w - 1] = False
    return Workspace(occ, (h - 1, 0), (0, w - 1), corner_cutting=bool(seed % 2), name=f"walks{seed}")


@pytest.mark.parametrize("names", [("length", "solar"), ("length", "solar", "dust_sum")], ids="+".join)
@pytest.mark.parametrize("rate", [1.0, 2.5])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_timed_solar_equals_brute_force_over_walks(seed, rate, names):
    ws = _walk_map(seed)
    cm = _costmap(ws, seed, rate=rate)
    front = free_front(ws, names, costmap=cm)
    assert front.stats["timed"]
    assert_same_front(front.F, brute_walks(ws, names, cm))
    _check_values(ws, cm, front)


def test_timed_solar_fronts_hold_walks():
    """A detour shifts the later steps to other solar indices: some
    Pareto-optimal paths revisit a cell (so the step count must be part of
    the state)."""
    repeats = 0
    for seed in (1, 2):
        ws = _walk_map(seed)
        front = free_front(ws, ("length", "solar"), costmap=_costmap(ws, seed, rate=2.5))
        repeats += sum(len({tuple(c) for c in p}) < len(p) for p in front.paths)
    assert repeats > 0


def _check_values(ws, cm, front):
    """F is the search's own evaluation of its paths, bit for bit, and the
    library's (SPEC metrics bit for bit, costmap means times the number of
    cells and the solar sum up to the summation order)."""
    F = front.F
    for i, p in enumerate(front.paths):
        assert tuple(p[0]) == ws.start and tuple(p[-1]) == ws.goal
        ref = path_objectives(ws, p, front.objectives, cm)
        assert [ref[n] for n in front.objectives] == F[i].tolist()
        spec = evaluate_path(ws, p)
        assert spec["interfering"] == 0
        assert front.smoothness[i] == spec["smoothness"]
        for j, n in enumerate(front.objectives):
            if n in ("length", "vulnerability", "smoothness"):
                assert F[i, j] == spec[n]
            elif n == "solar":
                assert math.isclose(
                    F[i, j], cm.evaluate_path(p, ["solar"])["solar"], rel_tol=1e-12, abs_tol=1e-12
                )
            else:
                mean = cm.evaluate_path(p, [n[:-4]])[n[:-4]]
                assert math.isclose(F[i, j], mean * len(p), rel_tol=1e-12, abs_tol=1e-12)
    for i in range(len(F)):
        for j in range(len(F)):
            assert i == j or not _dominates(F[j], F[i])
            assert i == j or not all(_eq(x, y) for x, y in zip(F[i], F[j]))


@pytest.mark.parametrize("seed", range(4))
def test_random_maps_four_objectives_are_consistent(seed):
    ws = random_workspace((14, 14), 30, seed=seed)
    cm = _costmap(ws, seed)
    front = free_front(ws, ("length", "elevation_sum", "solar", "risk_sum"), costmap=cm)
    assert len(front) > 1
    _check_values(ws, cm, front)
    assert front.stats["expansions"] > 0 and front.stats["peak_bytes"] > 0


def _agreement_cases():
    out = []
    for seed in range(24):
        rng = np.random.default_rng(100 + seed)
        n = int(rng.integers(5, 15))
        ws = random_workspace((n, n), int(rng.uniform(0, 0.25) * n * n), seed=seed)
        out.append(Workspace(ws.occ, ws.start, ws.goal, corner_cutting=bool(seed % 2), name=ws.name))
    return out


AGREE = _agreement_cases()
SPEC_SETS = [
    ("length", "vulnerability", "smoothness"),
    ("smoothness", "length", "vulnerability"),
    ("length", "vulnerability"),
    ("vulnerability", "smoothness"),
    ("length",),
]


@pytest.mark.parametrize("names", SPEC_SETS, ids="+".join)
def test_agrees_with_the_specialised_searches(names):
    identical = 0
    for ws in AGREE:
        try:
            a = free_front(ws, names)
        except NoPathError:
            with pytest.raises(NoPathError):
                free_front(ws, names, search="k")
            continue
        b = free_front(ws, names, search="k")
        assert_same_front(a.F, b.F)
        identical += np.array_equal(a.F, b.F) and np.array_equal(a.smoothness, b.smoothness)
        _check_values(ws, None, b)
    assert identical >= len(AGREE) // 2


def test_tie_break_none_gives_the_same_front():
    ws = Workspace(np.zeros((6, 7), bool))  # flat potential far from obstacles: many ties
    cm = Costmap(ws, layers={"sand": np.ones((6, 7))})
    a = free_front(ws, ("length", "sand_sum"), costmap=cm)
    b = free_front(ws, ("length", "sand_sum"), costmap=cm, tie_break="none")
    assert_same_front(a.F, b.F)
    assert np.all(a.smoothness <= math.pi / 4 + 1e-12)  # diagonal then straight: one turn at most
    assert b.stats["expansions"] <= a.stats["expansions"]


def test_label_budget_stops_cleanly_and_a_sufficient_one_changes_nothing():
    ws = random_workspace((16, 16), 40, seed=2)
    cm = _costmap(ws, 2)
    names = ("length", "elevation_sum", "risk_sum", "smoothness")
    whole = free_front(ws, names, costmap=cm)
    with pytest.raises(LabelBudgetError, match="max_labels=50") as err:
        free_front(ws, names, costmap=cm, max_labels=50)
    assert err.value.stats["max_labels"] == 50 and err.value.stats["labels"] <= 50
    again = free_front(ws, names, costmap=cm, max_labels=whole.stats["labels"] + 8)
    assert np.array_equal(again.F, whole.F)


def test_labels_held_count_the_parent_entries():
    """An expanded label is kept as a parent entry, not a row, to the end of
    the search: the budget counts the entries, so a budget of half the
    expansions stops the search (the open labels and solutions alone, the
    rows in use, never reach it here)."""
    ws = random_workspace((16, 16), 40, seed=2)
    cm = _costmap(ws, 2)
    names = ("length", "elevation_sum", "risk_sum", "smoothness")
    whole = free_front(ws, names, costmap=cm)
    with pytest.raises(LabelBudgetError):
        free_front(ws, names, costmap=cm, max_labels=whole.stats["expansions"] // 2)


def test_expanded_labels_leave_their_rows():
    """An expanded label is needed only as its children's parent: it keeps a
    cell and a parent entry (8 bytes), not its row (84 bytes for these four
    objectives: 28 bytes of int32 columns, three sums, four f-values). On
    this map (145,223 expansions) the search's arrays, the per-state sets
    (most of them now) and the fixed ones included, then take 2.41 times 84
    bytes per expansion; when every expanded label kept its row, 3.81 times."""
    ws = random_workspace((28, 28), 80, seed=1)
    cm = _costmap(ws, 1)
    s = free_front(ws, ("length", "elevation_sum", "solar", "risk_sum"), costmap=cm).stats
    assert s["expansions"] > 100_000
    assert s["peak_bytes"] < 3 * 84 * s["expansions"]


def test_progress_and_slices(monkeypatch):
    from gapath.planners import exact

    class Tiny(exact._Slices):
        def __init__(self, first, lo, hi):
            super().__init__(8, 8, 8)

        def update(self, done, seconds):
            pass

    ws = random_workspace((12, 12), 20, seed=4)
    cm = _costmap(ws, 4)
    names = ("length", "elevation_sum", "solar", "risk_sum")
    whole = free_front(ws, names, costmap=cm)
    monkeypatch.setattr(exact, "_Slices", Tiny)
    calls = []
    sliced = free_front(ws, names, costmap=cm, progress=calls.append)
    assert np.array_equal(whole.F, sliced.F)
    assert len(calls) > 3 and calls[-1]["phase"] == "free"
    assert [c["expansions"] for c in calls] == sorted(c["expansions"] for c in calls)


def test_exact_front_and_path_front_take_a_costmap():
    ws = random_workspace((8, 8), 8, seed=1)
    cm = _costmap(ws, 1)
    a = exact_front(ws, ["length", "risk_sum"], "free", costmap=cm)
    pf = exact_path_front(ws, ["length", "risk_sum"], "free", costmap=cm)
    assert np.array_equal(pf.F, a.F)
    with pytest.raises(ConfigError, match="monotone"):
        exact_front(ws, ["length", "risk_sum"], "monotone", costmap=cm)


@pytest.mark.parametrize(
    "names, with_costmap, match",
    [
        (("length", "elevation"), True, "MEAN of layer 'elevation'.*'elevation_sum'"),
        (("length", "sand"), True, "MEAN of layer 'sand'"),
        (("length", "risk_sum"), False, "needs a costmap"),
        (("length", "solar"), False, "needs a costmap"),
        (("length", "slope_sum"), True, "unknown exact objective 'slope_sum'"),
        (("length", "interfering", "risk_sum"), True, "constraint"),
        (("length", "risk_sum", "risk_sum"), True, "given twice"),
        ((), True, "at least one"),
    ],
)
def test_bad_objectives(names, with_costmap, match):
    ws = Workspace(np.zeros((4, 4), bool))
    cm = _costmap(ws, 0) if with_costmap else None
    with pytest.raises(ConfigError, match=match):
        free_front(ws, names, costmap=cm)


def test_bad_options():
    ws = Workspace(np.zeros((4, 4), bool))
    other = Workspace(np.zeros((5, 4), bool))
    with pytest.raises(ConfigError, match="differs"):
        free_front(ws, ["length", "risk_sum"], costmap=_costmap(other, 0))
    with pytest.raises(ConfigError, match="search must be"):
        free_front(ws, ["length"], search="fast")
    with pytest.raises(ConfigError, match="max_labels"):
        free_front(ws, ["length", "risk_sum"], costmap=_costmap(ws, 0), max_labels=0)
    occ = np.zeros((4, 4), bool)
    occ[:, 2] = True
    with pytest.raises(NoPathError):
        free_front(Workspace(occ), ["length", "risk_sum"], costmap=_costmap(Workspace(occ), 0))


def test_per_label_helpers_skip_reference_counting():
    """The helpers called for every generated label allocate nothing and
    are compiled without numba's reference counting: counted, their arrays
    cost atomic operations at every call (docs/results/exact_speed.md,
    "Reference counting in the search kernels")."""
    from gapath.planners import _apex_kernels as A
    from gapath.planners import _multi_kernels as M

    helpers = (M._covered, M._gvec, M._fvec, M._push, M._pop, A._covered, A._pop)
    assert all(h.targetoptions.get("_nrt") is False for h in helpers)


def test_search_loops_skip_reference_counting():
    """The loops of the three-objective searches (exact and apex) and of the
    free-path decoders' A* searches allocate nothing and are compiled
    without reference counting: the helpers inlined into them (heap, moves,
    heuristics) bind their arrays anew at every call, which numba counts
    atomically (20 % of the decoder's samples, 8 % of the face searches';
    docs/results/free_paths.md, sixteenth session)."""
    from gapath.encodings import _free_kernels as D
    from gapath.planners import _apex_kernels as A
    from gapath.planners import _exact_kernels as E

    loops = (E._free_steps, A._apex_steps, D._segment, D._turn_segment)
    assert all(f.targetoptions.get("_nrt") is False for f in loops)
