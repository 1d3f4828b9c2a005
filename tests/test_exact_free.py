"""The free reference front against brute-force enumeration.

Every simple 8-connected path of small grids is enumerated by depth-first
search (independently of the planner), its objectives summed along the way
in path order (so they are bit-identical to :func:`gapath.objectives.evaluate_path`),
the feasible ones Pareto-filtered with SPEC's tolerance and compared with
:func:`gapath.planners.exact.free_front`.
"""

from __future__ import annotations

import functools
import heapq
import json
import math

import numpy as np
import pytest

from gapath import ConfigError, NoPathError, Workspace, random_workspace
from gapath.objectives import evaluate_path
from gapath.planners.exact import ExactFront, free_front, monotone_front

TOL = 1e-9
NAMES = ("length", "vulnerability", "smoothness")
OBJECTIVE_SETS = [
    ("length", "vulnerability"),
    ("length", "smoothness"),
    ("vulnerability", "smoothness"),
    ("length", "vulnerability", "smoothness"),
    ("smoothness", "vulnerability", "length"),
    ("length",),
    ("vulnerability",),
    ("smoothness",),
]
MOVES = [(0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0), (1, 1)]


# ---------------------------------------------------------------------------
# brute force
# ---------------------------------------------------------------------------


def _close(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return np.abs(a - b) <= TOL * np.maximum(1.0, np.maximum(np.abs(a), np.abs(b)))


def all_simple_paths(ws: Workspace):
    """``(length, vulnerability, smoothness)`` and the cells of every simple
    feasible 8-connected path from start to goal."""
    occ, pot = ws.occ, ws.potential
    h, w = ws.shape
    goal = ws.goal
    out_F, out_P = [], []
    seen = np.zeros((h, w), bool)
    path = [ws.start]

    def dfs(r, c, head, ns, nd, eighths, vul):
        if (r, c) == goal:
            out_F.append(((ns + math.sqrt(2.0) * nd) * ws.cell_size, vul, eighths * math.pi / 4))
            out_P.append(list(path))
            return
        seen[r, c] = True
        for d, (dr, dc) in enumerate(MOVES):
            r2, c2 = r + dr, c + dc
            if not (0 <= r2 < h and 0 <= c2 < w) or occ[r2, c2] or seen[r2, c2]:
                continue
            diagonal = dr != 0 and dc != 0
            if diagonal and not ws.corner_cutting and (occ[r2, c] or occ[r, c2]):
                continue
            turn = 0 if head < 0 else min(abs(d - head), 8 - abs(d - head))
            path.append((r2, c2))
            dfs(r2, c2, d, ns + (not diagonal), nd + diagonal, eighths + turn, vul + pot[r2, c2])
            path.pop()
        seen[r, c] = False

    dfs(*ws.start, -1, 0, 0, 0, 0.0 + pot[ws.start])
    return np.array(out_F).reshape(-1, 3), out_P


def pareto_with_tolerance(F: np.ndarray, prefer: np.ndarray) -> np.ndarray:
    """Rows of ``F`` no other row dominates up to the tolerance, one per
    tolerance-equal vector (the one with the smallest ``prefer``).

    Only the rows of the exact Pareto set and the rows tolerance-equal to one
    of them can qualify (a row exactly dominated by a front row and not
    tolerance-equal to it is dominated up to the tolerance), so only those
    are checked, each against all rows."""
    from pymoo.util.nds.non_dominated_sorting import NonDominatedSorting

    # identical rows: keep the preferred one
    by_pref = np.argsort(prefer, kind="stable")
    _, first = np.unique(F[by_pref], axis=0, return_index=True)
    rows = by_pref[np.sort(first)]
    F, prefer = F[rows], prefer[rows]
    exact = NonDominatedSorting().do(F, only_non_dominated_front=True)
    candidates = set(int(i) for i in exact)
    for z in F[exact]:
        candidates.update(int(i) for i in np.flatnonzero(_close(F, z).all(axis=1)))
    keep = []
    for i in sorted(candidates):
        eq = _close(F, F[i])
        not_worse = ((F <= F[i]) | eq).all(axis=1)
        better = ((F < F[i]) & ~eq).any(axis=1)
        if not (not_worse & better).any():
            keep.append(i)
    keep = np.array(keep, dtype=int)
    keep = keep[np.argsort(prefer[keep], kind="stable")]
    out = []
    for i in keep:
        if not any(_close(F[j], F[i]).all() for j in out):
            out.append(i)
    return F[np.array(out, dtype=int)]


def assert_same_front(A: np.ndarray, B: np.ndarray):
    """Same number of points, and every point of one is tolerance-equal to a
    point of the other."""
    assert A.shape == B.shape, (A, B)
    for a in A:
        assert _close(B, a).all(axis=1).any(), (a, B)
    for b in B:
        assert _close(A, b).all(axis=1).any(), (b, A)


# ---------------------------------------------------------------------------
# workspaces
# ---------------------------------------------------------------------------


def _random(shape, p, seed, **kw):
    rng = np.random.default_rng(seed)
    occ = rng.random(shape) < p
    h, w = shape
    start = kw.setdefault("start", (h - 1, 0))
    goal = kw.setdefault("goal", (0, w - 1))
    occ[start] = occ[goal] = False
    return Workspace(occ, name=f"rand-{h}x{w}-p{p}-s{seed}", **kw)


_WORKSPACES = {
    # seeds chosen for non-trivial fronts (up to 4 points) and < 12000 paths
    "4x4-p15-s0": lambda: _random((4, 4), 0.15, 0),
    "4x4-p20-s21": lambda: _random((4, 4), 0.2, 21),
    "4x4-p20-s14-nocut": lambda: _random((4, 4), 0.2, 14, corner_cutting=False),
    "4x4-p25-s0-nocut": lambda: _random((4, 4), 0.25, 0, corner_cutting=False),
    "4x4-p30-s10": lambda: _random((4, 4), 0.3, 10),
    "4x4-p30-s24": lambda: _random((4, 4), 0.3, 24),
    "4x4-p40-s19": lambda: _random((4, 4), 0.4, 19),
    "4x4-inner": lambda: _random((4, 4), 0.2, 7, start=(2, 1), goal=(0, 3)),
    "4x4-inner-nocut": lambda: _random((4, 4), 0.2, 8, start=(1, 2), goal=(3, 1), corner_cutting=False),
    "4x4-same-column": lambda: _random((4, 4), 0.2, 9, start=(3, 2), goal=(0, 2)),
    "4x4-backwards": lambda: _random((4, 4), 0.2, 4, start=(0, 3), goal=(2, 0)),
    "4x4-cell-size": lambda: _random((4, 4), 0.2, 11, cell_size=0.5),
    "3x5-empty": lambda: Workspace(np.zeros((3, 5), bool), start=(1, 0), goal=(1, 4)),
    "4x5-p30-s1": lambda: _random((4, 5), 0.3, 1),
    "5x5-p20-s0": lambda: _random((5, 5), 0.2, 0),
}


@functools.cache
def _brute_cached(key):
    return all_simple_paths(_WORKSPACES[key]())


@pytest.fixture(scope="module", params=sorted(_WORKSPACES))
def case(request):
    key = request.param
    ws = _WORKSPACES[key]()
    F, paths = _brute_cached(key)
    return key, ws, F, paths


def test_brute_force_cases_are_non_trivial():
    for key in _WORKSPACES:
        F, _ = _brute_cached(key)
        assert len(F) > 1, key


# ---------------------------------------------------------------------------
# the front equals the brute-force front
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("objectives", OBJECTIVE_SETS, ids=lambda o: "+".join(o))
def test_front_equals_brute_force(case, objectives):
    key, ws, all_F, _ = case
    cols = [NAMES.index(n) for n in objectives]
    expected = pareto_with_tolerance(all_F[:, cols], prefer=all_F[:, 2])
    front = free_front(ws, objectives)
    assert front.objectives == tuple(objectives)
    assert_same_front(front.F, expected)
    check_front(ws, front)


@pytest.mark.parametrize("objectives", [("length", "vulnerability"), ("vulnerability",), ("length",)])
def test_ties_prefer_smoothest_path(case, objectives):
    """Without smoothness among the objectives, each front point's path has
    the least total turn of all feasible paths with that objective vector."""
    key, ws, all_F, _ = case
    cols = [NAMES.index(n) for n in objectives]
    front = free_front(ws, objectives)
    for f, smooth in zip(front.F, front.smoothness):
        same = _close(all_F[:, cols], f).all(axis=1)
        assert same.any()
        assert smooth == all_F[same, 2].min()


@pytest.mark.parametrize(
    "objectives", [("length", "smoothness"), ("vulnerability", "smoothness"), ("smoothness",)]
)
def test_ties_with_smoothness_prefer_the_best_third_objective(case, objectives):
    """With smoothness and one other objective, each front point's path is
    best in the third objective (the vulnerability for (length,
    smoothness) and smoothness alone, the length for (vulnerability,
    smoothness)) among all feasible paths with that objective vector: a
    point of the three-objective front, never one dominated in it."""
    key, ws, all_F, _ = case
    cols = [NAMES.index(n) for n in objectives]
    third = NAMES.index("vulnerability" if "vulnerability" not in objectives else "length")
    front = free_front(ws, objectives)
    for f, path in zip(front.F, front.paths):
        same = _close(all_F[:, cols], f).all(axis=1)
        assert same.any()
        own = evaluate_path(ws, path)[NAMES[third]]
        best = all_F[same, third].min()
        assert own <= best + 1e-9 * max(1.0, abs(best)), (key, f, own, best)


@pytest.mark.parametrize("seed", range(4))
def test_faces_with_smoothness_are_points_of_the_three_objective_front(seed):
    """On sparse 20x26 maps (many paths tie in length and turns, their
    vulnerabilities differ), every point of the (length, smoothness) and
    (vulnerability, smoothness) fronts is, with its path's third objective,
    a point of the exact three-objective front (up to the tolerance):
    never one that front dominates. (Before the tie-break, 13 of the 43
    points of these fronts were not.)"""
    occ = np.random.default_rng(seed).random((20, 26)) < 0.04
    occ[19, 0] = occ[0, 25] = False
    ws = Workspace(occ, start=(19, 0), goal=(0, 25), corner_cutting=False)
    E = free_front(ws, NAMES).F
    for pair in (("length", "smoothness"), ("vulnerability", "smoothness")):
        front = free_front(ws, pair)
        for path in front.paths:
            own = evaluate_path(ws, path)
            f = np.array([own[n] for n in NAMES])
            assert _close(E, f).all(axis=1).any(), (seed, pair, f)


def test_tie_break_none_gives_the_same_front(case):
    """``tie_break="none"`` (BOA* as published): the same front up to the
    tolerance, each path's objectives and smoothness its own."""
    key, ws, all_F, _ = case
    expected = pareto_with_tolerance(all_F[:, :2], prefer=all_F[:, 2])
    front = free_front(ws, ("length", "vulnerability"), tie_break="none")
    assert_same_front(front.F, expected)
    check_front(ws, front)


def test_tie_break_none_on_a_flat_map():
    """Zero potential everywhere: every path of a given step count ties; the
    front is the same, with fewer labels expanded."""
    ws = Workspace(np.zeros((12, 12), bool), start=(11, 0), goal=(0, 9))
    assert not ws.potential.any()
    smooth = free_front(ws, ("length", "vulnerability"))
    fast = free_front(ws, ("length", "vulnerability"), tie_break="none")
    assert_same_front(fast.F, smooth.F)
    assert fast.stats["expansions"] <= smooth.stats["expansions"]
    assert (smooth.smoothness <= fast.smoothness).all()
    check_front(ws, fast)
    with pytest.raises(ConfigError, match="tie_break"):
        free_front(ws, tie_break="first")


def check_front(ws: Workspace, front: ExactFront):
    F = front.F
    k, m = F.shape
    assert m == len(front.objectives) and k >= 1
    assert len(front.paths) == k and front.smoothness.shape == (k,)
    assert front.profiles is None
    # sorted lexicographically
    assert (np.lexsort(F.T[::-1]) == np.arange(k)).all()
    # mutually non-dominated and distinct, up to the tolerance
    for i in range(k):
        eq = _close(F, F[i])
        not_worse = ((F <= F[i]) | eq).all(axis=1)
        better = ((F < F[i]) & ~eq).any(axis=1)
        assert not (not_worse & better).any()
        assert eq.all(axis=1).sum() == 1
    # every path is a simple feasible start..goal path whose objectives are F
    for path, f, smooth in zip(front.paths, F, front.smoothness):
        assert path.dtype.kind == "i" and path.shape[1] == 2
        assert ws.is_valid_path(path)
        assert len({tuple(c) for c in path.tolist()}) == len(path), "not simple"
        v = evaluate_path(ws, path)
        assert v["interfering"] == 0
        np.testing.assert_array_equal([v[n] for n in front.objectives], f)
        assert v["smoothness"] == smooth


# ---------------------------------------------------------------------------
# larger maps: an independent label-setting reference
# ---------------------------------------------------------------------------


def martins_front(ws: Workspace) -> np.ndarray:
    """The exact (length, vulnerability, smoothness) Pareto set of the
    feasible paths, by Martins' label-setting algorithm: no heuristic, exact
    dominance (no tolerance), states (cell, incoming heading), every
    non-dominated label kept. Loops are not excluded; they never yield a
    vector that a simple path does not match or beat."""
    occ, pot = ws.occ, ws.potential
    h, w = ws.shape
    goal = ws.goal
    alive: dict = {}  # state -> list of label ids
    vec: list = []  # label id -> (length, vul, eighths)
    info: list = []  # label id -> (cell, heading, ns, nd)
    dead: set = set()
    heap: list = []

    def offer(state, v, extra):
        for a in alive.get(state, ()):
            if all(x <= y for x, y in zip(vec[a], v)):
                return
        keep = []
        for a in alive.get(state, ()):
            if all(x <= y for x, y in zip(v, vec[a])):
                dead.add(a)
            else:
                keep.append(a)
        i = len(vec)
        vec.append(v)
        info.append(extra)
        keep.append(i)
        alive[state] = keep
        heapq.heappush(heap, (v, i))

    start = ws.start
    offer((start, -1), (0.0, float(pot[start]), 0), (start, -1, 0, 0))
    while heap:
        v, i = heapq.heappop(heap)
        if i in dead:
            continue
        (r, c), head, ns, nd = info[i]
        if (r, c) == goal:
            continue
        for d, (dr, dc) in enumerate(MOVES):
            r2, c2 = r + dr, c + dc
            if not (0 <= r2 < h and 0 <= c2 < w) or occ[r2, c2]:
                continue
            diagonal = dr != 0 and dc != 0
            if diagonal and not ws.corner_cutting and (occ[r2, c] or occ[r, c2]):
                continue
            ns2, nd2 = ns + (not diagonal), nd + diagonal
            turn = 0 if head < 0 else min(abs(d - head), 8 - abs(d - head))
            v2 = ((ns2 + math.sqrt(2.0) * nd2) * ws.cell_size, v[1] + pot[r2, c2], v[2] + turn)
            state = ("goal",) if (r2, c2) == goal else ((r2, c2), d)
            offer(state, v2, ((r2, c2), d, ns2, nd2))
    G = np.array([vec[i] for i in alive.get(("goal",), [])], dtype=float).reshape(-1, 3)
    G[:, 2] *= math.pi / 4
    return G


_MEDIUM = {
    # seeds chosen for fronts of 5 to 22 points
    "10x10-p10-s2": lambda: _random((10, 10), 0.1, 2),
    "12x12-p20-s2": lambda: _random((12, 12), 0.2, 2),
    "14x14-p20-s0": lambda: _random((14, 14), 0.2, 0),
    "14x14-p10-s0-nocut": lambda: _random((14, 14), 0.1, 0, corner_cutting=False),
    "14x14-p20-s2-nocut": lambda: _random((14, 14), 0.2, 2, corner_cutting=False),
    "12x12-inner": lambda: _random((12, 12), 0.2, 4, start=(9, 3), goal=(2, 8)),
}


@pytest.mark.parametrize("key", sorted(_MEDIUM))
def test_front_equals_label_setting_reference(key):
    """Every objective subset's front is the tolerance front of the
    projection of the exact three-objective set, and the smoothest paths
    among ties are the ones of that set."""
    ws = _MEDIUM[key]()
    G = martins_front(ws)
    assert len(G) > 3
    for objectives in OBJECTIVE_SETS:
        cols = [NAMES.index(n) for n in objectives]
        front = free_front(ws, objectives)
        assert_same_front(front.F, pareto_with_tolerance(G[:, cols], prefer=G[:, 2]))
        check_front(ws, front)
        if "smoothness" not in objectives:
            for f, smooth in zip(front.F, front.smoothness):
                assert smooth == G[_close(G[:, cols], f).all(axis=1), 2].min()


# ---------------------------------------------------------------------------
# larger maps: consistency and the monotone front
# ---------------------------------------------------------------------------


def _weakly_dominated_by(A: np.ndarray, B: np.ndarray) -> bool:
    """Every point of A is dominated by, or tolerance-equal to, a point of B."""
    for a in A:
        if not (((B <= a) | _close(B, a)).all(axis=1)).any():
            return False
    return True


@pytest.mark.parametrize("seed", range(6))
def test_monotone_front_is_weakly_dominated(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(8, 13))
    ws = random_workspace((n, n), int(0.2 * n * n), seed=seed)
    if seed % 2:
        ws = ws.replace(corner_cutting=False)
    for objectives in [("length", "vulnerability"), ("length", "vulnerability", "smoothness")]:
        try:
            mono = monotone_front(ws, objectives)
        except NoPathError:
            continue
        free = free_front(ws, objectives)
        check_front(ws, free)
        assert _weakly_dominated_by(mono.F, free.F)


@pytest.mark.parametrize(
    "objectives",
    [("length", "vulnerability"), ("length", "vulnerability", "smoothness")],
    ids=lambda o: "+".join(o),
)
def test_default_scenario_is_consistent(objectives):
    from gapath import default_workspace

    ws = default_workspace()
    front = free_front(ws, objectives)
    check_front(ws, front)
    assert _weakly_dominated_by(monotone_front(ws, objectives).F, front.F)


def test_objective_order():
    ws = _WORKSPACES["4x4-p20-s21"]()
    lv = free_front(ws, ("length", "vulnerability"))
    vl = free_front(ws, "vulnerability, length")
    assert vl.objectives == ("vulnerability", "length")
    swapped = vl.F[:, ::-1]
    assert_same_front(swapped[np.lexsort(swapped.T[::-1])], lv.F)


def test_empty_grid_has_one_point():
    ws = Workspace(np.zeros((5, 7), bool))
    front = free_front(ws, ("length", "vulnerability", "smoothness"))
    assert front.F.shape == (1, 3)
    np.testing.assert_array_equal(front.F[0], [(2 + 4 * 2**0.5), 0.0, np.pi / 4])


def test_to_dict_is_json():
    front = free_front(_WORKSPACES["4x4-p30-s10"]())
    d = json.loads(json.dumps(front.to_dict()))
    assert sorted(d) == ["F", "objectives", "paths", "smoothness"]
    assert np.array_equal(np.array(d["F"]), front.F)


# ---------------------------------------------------------------------------
# errors
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "objectives",
    [("length", "vulnerability"), ("length", "smoothness"), ("length", "vulnerability", "smoothness")],
)
def test_wall_raises_no_path_error(objectives):
    occ = np.zeros((5, 5), bool)
    occ[:, 2] = True
    with pytest.raises(NoPathError, match="walled"):
        free_front(Workspace(occ, name="walled"), objectives)


def test_enclosed_goal_raises_no_path_error():
    occ = np.zeros((6, 6), bool)
    occ[0:3, 2] = occ[2, 2:] = True
    with pytest.raises(NoPathError):
        free_front(Workspace(occ, start=(5, 0), goal=(0, 5)))


def test_backwards_pocket_is_found():
    """The only feasible path moves back a column: no monotone path, but a
    free one."""
    occ = np.array(
        [
            [0, 0, 0, 0, 0],
            [0, 1, 1, 0, 0],
            [0, 1, 0, 0, 0],
            [0, 1, 1, 0, 0],
            [0, 0, 0, 0, 0],
        ],
        bool,
    )
    ws = Workspace(occ, start=(2, 0), goal=(2, 2), name="pocket")
    with pytest.raises(NoPathError):
        monotone_front(ws)
    front = free_front(ws, ("length",))
    over = [[2, 0], [1, 0], [0, 1], [0, 2], [1, 3], [2, 2]]
    under = [[2, 0], [3, 0], [4, 1], [4, 2], [3, 3], [2, 2]]
    assert front.paths[0].tolist() in (over, under)


def test_corner_cutting_only_path():
    occ = np.array(
        [
            [1, 0, 0],
            [1, 0, 1],
            [0, 1, 1],
        ],
        bool,
    )
    ws = Workspace(occ, start=(2, 0), goal=(0, 2))
    front = free_front(ws)
    assert front.paths[0].tolist() == [[2, 0], [1, 1], [0, 2]]
    with pytest.raises(NoPathError):
        free_front(ws.replace(corner_cutting=False))


@pytest.mark.parametrize("objectives", [("length", "interfering"), ("length", "length"), ("speed",), ()])
def test_bad_objectives(objectives):
    with pytest.raises(ConfigError):
        free_front(_WORKSPACES["4x4-p15-s0"](), objectives)
