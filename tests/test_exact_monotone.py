"""The monotone reference front against brute-force enumeration.

Every column-monotone path of small grids is enumerated from its exit rows
(independently of the planner and of the encodings' profile code), evaluated
with :func:`gapath.objectives.evaluate_path`, Pareto-filtered with SPEC's
tolerance and compared with :func:`gapath.planners.exact.monotone_front`.
"""

from __future__ import annotations

import functools
import itertools
import json

import numpy as np
import pytest

from gapath import ConfigError, NoPathError, Workspace, random_workspace
from gapath.monotone import Frame, profiles_of_paths
from gapath.objectives import evaluate_path, evaluate_profiles
from gapath.planners.exact import ExactFront, monotone_front

TOL = 1e-9
NAMES = ("length", "vulnerability", "smoothness")
OBJECTIVE_SETS = [
    ("length", "vulnerability"),
    ("length", "smoothness"),
    ("length", "vulnerability", "smoothness"),
]


# ---------------------------------------------------------------------------
# brute force
# ---------------------------------------------------------------------------


def _close(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return np.abs(a - b) <= TOL * np.maximum(1.0, np.maximum(np.abs(a), np.abs(b)))


def _run(frm: int, to: int, col: int) -> list[tuple[int, int]]:
    """Cells entered in column ``col`` when leaving row ``frm`` of the
    previous column for exit row ``to``: one horizontal or diagonal step,
    then vertical steps in the same direction."""
    if to == frm:
        return [(to, col)]
    s = 1 if to > frm else -1
    return [(r, col) for r in range(frm + s, to + s, s)]


def all_monotone_paths(ws: Workspace):
    """Every column-monotone path (workspace coordinates), one per sequence
    of exit rows of the columns before the goal column."""
    h, _ = ws.shape
    (sr, sc), (gr, gc) = ws.start, ws.goal
    assert sc != gc
    dc = 1 if gc > sc else -1
    inner = list(range(sc + dc, gc, dc))
    for exits in itertools.product(range(h), repeat=1 + len(inner)):
        e0 = exits[0]
        s = 1 if e0 >= sr else -1
        cells = [(r, sc) for r in range(sr, e0 + s, s)]
        prev = e0
        for col, e in zip(inner, exits[1:]):
            cells += _run(prev, e, col)
            prev = e
        cells += _run(prev, gr, gc)
        yield np.array(cells)


@functools.cache
def _brute_cached(key):
    ws = _WORKSPACES[key]()
    F = []
    for p in all_monotone_paths(ws):
        v = evaluate_path(ws, p)
        if v["interfering"] == 0:
            F.append([v[n] for n in NAMES])
    return np.array(F).reshape(-1, 3)


def pareto_with_tolerance(F: np.ndarray, prefer: np.ndarray) -> np.ndarray:
    """Rows of ``F`` no other row dominates up to the tolerance, one per
    tolerance-equal vector (the one with the smallest ``prefer``)."""
    keep = []
    for i in range(len(F)):
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
    ws_kw = dict(kw)
    h, w = shape
    start = ws_kw.setdefault("start", (h - 1, 0))
    goal = ws_kw.setdefault("goal", (0, w - 1))
    occ[start] = occ[goal] = False
    return Workspace(occ, name=f"rand-{h}x{w}-p{p}-s{seed}", **ws_kw)


def _sparse():
    occ = np.zeros((6, 6), bool)
    occ[2, 3] = occ[4, 1] = True
    return Workspace(occ, name="sparse")


# seeds chosen for non-trivial fronts
_WORKSPACES = {
    "5x5-s19": lambda: _random((5, 5), 0.2, 19),
    "5x5-s28": lambda: _random((5, 5), 0.2, 28),
    "5x5-s19-nocut": lambda: _random((5, 5), 0.2, 19, corner_cutting=False),
    "5x5-s3-nocut": lambda: _random((5, 5), 0.2, 3, corner_cutting=False),
    "6x6-s24": lambda: _random((6, 6), 0.2, 24),
    "6x6-s10": lambda: _random((6, 6), 0.2, 10),
    "6x6-s10-nocut": lambda: _random((6, 6), 0.2, 10, corner_cutting=False),
    "6x6-s23-cell": lambda: _random((6, 6), 0.2, 23, cell_size=0.5),
    "6x6-inner": lambda: _random((6, 6), 0.2, 6, start=(3, 1), goal=(1, 4)),
    "6x6-mirror": lambda: _random((6, 6), 0.2, 11, start=(4, 5), goal=(1, 0)),
    "5x6-mirror-nocut": lambda: _random((5, 6), 0.2, 14, start=(0, 4), goal=(4, 1), corner_cutting=False),
    "6x6-sparse": _sparse,
    "6x5-empty": lambda: Workspace(np.zeros((6, 5), bool)),
}


@pytest.fixture(scope="module", params=sorted(_WORKSPACES))
def case(request):
    key = request.param
    ws = _WORKSPACES[key]()
    return key, ws, _brute_cached(key)


def test_brute_force_cases_have_paths():
    # the fixtures are meant to exercise the DP, not NoPathError
    for key in _WORKSPACES:
        assert len(_brute_cached(key)) > 0, key


# ---------------------------------------------------------------------------
# the front equals the brute-force front
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("objectives", OBJECTIVE_SETS, ids=lambda o: "+".join(o))
def test_front_equals_brute_force(case, objectives):
    key, ws, all_F = case
    cols = [NAMES.index(n) for n in objectives]
    expected = pareto_with_tolerance(all_F[:, cols], prefer=all_F[:, 2])
    front = monotone_front(ws, objectives)
    assert front.objectives == tuple(objectives)
    assert_same_front(front.F, expected)


@pytest.mark.parametrize("objectives", [("length", "vulnerability"), ("vulnerability",)])
def test_ties_prefer_smoothest_path(case, objectives):
    """Without smoothness among the objectives, each front point's path has
    the least total turn of all feasible paths with that objective vector."""
    key, ws, all_F = case
    cols = [NAMES.index(n) for n in objectives]
    front = monotone_front(ws, objectives)
    for f, smooth in zip(front.F, front.smoothness):
        same = _close(all_F[:, cols], f).all(axis=1)
        assert same.any()
        assert smooth == all_F[same, 2].min()


@pytest.mark.parametrize("objectives", OBJECTIVE_SETS, ids=lambda o: "+".join(o))
def test_front_rows_are_consistent(case, objectives):
    _, ws, _ = case
    front = monotone_front(ws, objectives)
    check_front(ws, front)


def check_front(ws: Workspace, front: ExactFront):
    F = front.F
    k, m = F.shape
    assert m == len(front.objectives) and k >= 1
    assert len(front.paths) == k and front.smoothness.shape == (k,)
    # sorted lexicographically
    assert (np.lexsort(F.T[::-1]) == np.arange(k)).all()
    # mutually non-dominated and distinct, up to the tolerance
    for i in range(k):
        eq = _close(F, F[i])
        not_worse = ((F <= F[i]) | eq).all(axis=1)
        better = ((F < F[i]) & ~eq).any(axis=1)
        assert not (not_worse & better).any()
        assert eq.all(axis=1).sum() == 1
    # every path is a feasible monotone path whose objectives are F
    frame = Frame.of(ws)
    for path, f, smooth in zip(front.paths, F, front.smoothness):
        assert path.dtype.kind == "i" and path.shape[1] == 2
        assert ws.is_valid_path(path)
        v = evaluate_path(ws, path)
        assert v["interfering"] == 0
        np.testing.assert_allclose([v[n] for n in front.objectives], f, rtol=0, atol=1e-12)
        assert abs(v["smoothness"] - smooth) <= 1e-12
    entries, exits = profiles_of_paths(frame, front.paths)  # raises if not monotone
    np.testing.assert_array_equal(entries, front.profiles[0])
    np.testing.assert_array_equal(exits, front.profiles[1])
    # the GA's profile evaluation gives the same values
    G = evaluate_profiles(
        entries, exits, frame.col0, frame.occ, frame.potential, ws.cell_size, ws.corner_cutting
    )
    cols = [("length", "vulnerability", "smoothness").index(n) for n in front.objectives]
    np.testing.assert_allclose(G[:, cols], F, rtol=0, atol=1e-12)
    assert (G[:, 3] == 0).all()


def test_transposed_frame():
    """Start and goal in the same column: the frame is transposed, and the
    front is the one of the transposed workspace."""
    base = _random((6, 5), 0.2, 11, start=(5, 2), goal=(0, 2))
    twin = Workspace(base.occ.T, start=(2, 5), goal=(2, 0), name="twin")
    all_F = np.array(
        [
            [evaluate_path(twin, p)[n] for n in NAMES]
            for p in all_monotone_paths(twin)
            if evaluate_path(twin, p)["interfering"] == 0
        ]
    )
    for objectives in OBJECTIVE_SETS:
        cols = [NAMES.index(n) for n in objectives]
        front = monotone_front(base, objectives)
        assert_same_front(front.F, pareto_with_tolerance(all_F[:, cols], all_F[:, 2]))
        check_front(base, front)


@pytest.mark.parametrize("objectives", OBJECTIVE_SETS, ids=lambda o: "+".join(o))
def test_larger_map_is_consistent(objectives):
    ws = random_workspace((24, 24), int(0.17 * 24 * 24), seed=3)
    check_front(ws, monotone_front(ws, objectives))
    check_front(
        ws.replace(corner_cutting=False), monotone_front(ws.replace(corner_cutting=False), objectives)
    )


def test_objective_order_and_single_objective():
    ws = _WORKSPACES["6x6-s10"]()
    lv = monotone_front(ws, ("length", "vulnerability"))
    vl = monotone_front(ws, "vulnerability, length")
    assert vl.objectives == ("vulnerability", "length")
    assert_same_front(vl.F[:, ::-1][np.lexsort(vl.F[:, ::-1].T[::-1])], lv.F)
    shortest = monotone_front(ws, ("length",))
    assert shortest.F.shape == (1, 1)
    assert shortest.F[0, 0] == lv.F[0, 0]


def test_empty_grid_shortest_path_is_the_diagonal():
    ws = Workspace(np.zeros((4, 4), bool))
    front = monotone_front(ws, ("length", "vulnerability", "smoothness"))
    assert front.F.tolist() == [[3 * 2**0.5, 0.0, 0.0]]
    assert front.paths[0].tolist() == [[3, 0], [2, 1], [1, 2], [0, 3]]


def test_to_dict_is_json():
    front = monotone_front(_WORKSPACES["5x5-s19"](), ("length", "vulnerability"))
    d = json.loads(json.dumps(front.to_dict()))
    assert d["objectives"] == ["length", "vulnerability"]
    assert np.array_equal(np.array(d["F"]), front.F)
    assert len(d["paths"]) == len(front)


# ---------------------------------------------------------------------------
# errors
# ---------------------------------------------------------------------------


def test_wall_raises_no_path_error():
    occ = np.zeros((5, 5), bool)
    occ[:, 2] = True
    ws = Workspace(occ, name="walled")
    with pytest.raises(NoPathError, match="walled"):
        monotone_front(ws)


def test_pocket_opening_backwards_raises_no_path_error():
    """A feasible 8-connected path exists, but it must move back a column."""
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
    assert not any(evaluate_path(ws, p)["interfering"] == 0 for p in all_monotone_paths(ws))
    free = [(2, 0), (1, 0), (0, 1), (0, 2), (1, 3), (2, 2)]
    assert evaluate_path(ws, free)["interfering"] == 0
    with pytest.raises(NoPathError, match="pocket"):
        monotone_front(ws, ("length", "vulnerability", "smoothness"))


def test_corner_cutting_only_path():
    """Every monotone path cuts a corner: feasible with corner cutting,
    NoPathError without."""
    occ = np.array(
        [
            [1, 0, 0],
            [1, 0, 1],
            [0, 1, 1],
        ],
        bool,
    )
    ws = Workspace(occ, start=(2, 0), goal=(0, 2))
    front = monotone_front(ws)
    assert front.paths[0].tolist() == [[2, 0], [1, 1], [0, 2]]
    with pytest.raises(NoPathError):
        monotone_front(ws.replace(corner_cutting=False))


@pytest.mark.parametrize("objectives", [("length", "interfering"), ("length", "length"), ("speed",), ()])
def test_bad_objectives(objectives):
    with pytest.raises(ConfigError):
        monotone_front(_WORKSPACES["5x5-s19"](), objectives)
