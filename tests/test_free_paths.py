"""Free-path encodings, problem, seeding and GA (issue 14, SPEC "Free path set")."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.optimize import minimize

from gapath import Workspace
from gapath.algorithms import FastNSGA2
from gapath.encodings import _free_kernels as K
from gapath.encodings.free import FieldEncoding, ViaPointEncoding, make_free_encoding
from gapath.errors import ConfigError, NoPathError
from gapath.front import path_front
from gapath.metrics import nondominated
from gapath.objectives import evaluate_paths, pad_paths
from gapath.operators import PathDuplicateElimination
from gapath.operators.sampling.free_sampling import FreeSampling, free_seed_genomes
from gapath.planners.exact import free_front
from gapath.problems import FreePathProblem, path_problem

TOL = 1e-9


# ---------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------


def check_path(ws, path):
    """Assert ``path`` is a simple feasible 8-connected path start -> goal
    obeying the corner rule."""
    p = np.asarray(path)
    assert tuple(p[0]) == ws.start and tuple(p[-1]) == ws.goal
    d = np.abs(np.diff(p, axis=0))
    assert (d.max(axis=1) == 1).all(), "steps must be 8-adjacent"
    assert len({tuple(c) for c in p}) == len(p), "a cell is repeated"
    assert not ws.occ[p[:, 0], p[:, 1]].any(), "a cell is an obstacle"
    if not ws.corner_cutting:
        for a, b in zip(p[:-1], p[1:]):
            if a[0] != b[0] and a[1] != b[1]:
                assert not ws.occ[a[0], b[1]] and not ws.occ[b[0], a[1]], "corner cut"


@st.composite
def workspaces(draw, max_side=9):
    h = draw(st.integers(2, max_side))
    w = draw(st.integers(2, max_side))
    density = draw(st.sampled_from([0.0, 0.15, 0.3, 0.45]))
    seed = draw(st.integers(0, 2**31 - 1))
    occ = np.random.default_rng(seed).random((h, w)) < density
    cells = [(r, c) for r in range(h) for c in range(w)]
    start = draw(st.sampled_from(cells))
    goal = draw(st.sampled_from(cells))
    assume(start != goal)
    occ[start] = occ[goal] = False
    cc = draw(st.booleans())
    ws = Workspace(occ, start, goal, corner_cutting=cc)
    comp = K.component(ws.occ, start[0] * w + start[1], cc)
    assume(comp[goal[0] * w + goal[1]])
    return ws


def random_encoding(draw, ws):
    if draw(st.booleans()):
        return ViaPointEncoding(ws, n_via=draw(st.integers(0, 5)))
    h, w = ws.shape
    gy = draw(st.integers(2, max(2, min(h, 5))))
    gx = draw(st.integers(2, max(2, min(w, 5))))
    return FieldEncoding(ws, field_shape=(gy, gx))


def dominates(a, b):
    le = all(x <= y + TOL * max(1.0, abs(x), abs(y)) for x, y in zip(a, b))
    lt = any(x < y - TOL * max(1.0, abs(x), abs(y)) for x, y in zip(a, b))
    return le and lt


def simple_paths(ws):
    """Every simple feasible path start -> goal (depth-first enumeration)."""
    h, w = ws.shape
    occ = ws.occ
    out, path, on = [], [ws.start], {ws.start}

    def ok(r, c, dr, dc):
        r2, c2 = r + dr, c + dc
        if not (0 <= r2 < h and 0 <= c2 < w) or occ[r2, c2] or (r2, c2) in on:
            return False
        if dr and dc and not ws.corner_cutting and (occ[r2, c] or occ[r, c2]):
            return False
        return True

    def dfs():
        r, c = path[-1]
        if (r, c) == ws.goal:
            out.append(np.array(path))
            return
        for dr in (-1, 0, 1):
            for dc in (-1, 0, 1):
                if (dr or dc) and ok(r, c, dr, dc):
                    path.append((r + dr, c + dc))
                    on.add(path[-1])
                    dfs()
                    on.discard(path.pop())

    dfs()
    return out


def room(h=12, w=14, seed=0, density=0.25, corner_cutting=False):
    occ = np.random.default_rng(seed).random((h, w)) < density
    occ[h - 1, 0] = occ[0, w - 1] = False
    ws = Workspace(occ, corner_cutting=corner_cutting)
    try:
        FreePathProblem(ws)
    except NoPathError:
        return room(h, w, seed + 1000, density, corner_cutting)
    return ws


# ---------------------------------------------------------------------------
# decoding
# ---------------------------------------------------------------------------


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(data=st.data())
def test_any_genome_decodes_to_a_simple_feasible_path(data):
    ws = data.draw(workspaces())
    enc = random_encoding(data.draw, ws)
    n = data.draw(st.integers(1, 6))
    genes = data.draw(st.lists(st.floats(-0.5, 1.5), min_size=n * enc.n_var, max_size=n * enc.n_var))
    X = np.array(genes).reshape(n, enc.n_var)
    P, L = enc.decode(X)
    for i in range(n):
        check_path(ws, P[i, : L[i]])


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(data=st.data())
def test_objectives_match_evaluate_paths(data):
    ws = data.draw(workspaces())
    enc_name = data.draw(st.sampled_from(["via", "field"]))
    objectives = data.draw(
        st.sampled_from([("length", "vulnerability"), ("vulnerability", "smoothness", "length")])
    )
    p = FreePathProblem(
        ws, objectives, encoding=enc_name, constraints=data.draw(st.sampled_from(["penalty", "constraint"]))
    )
    X = np.random.default_rng(data.draw(st.integers(0, 99))).random((8, p.n_var))
    out = p.evaluate(X, return_as_dictionary=True)
    P, L = pad_paths(p.decode(X))
    M = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    col = {"length": 0, "vulnerability": 1, "smoothness": 2}
    np.testing.assert_array_equal(out["F"], M[:, [col[n] for n in objectives]])
    np.testing.assert_array_equal(out["smoothness"], M[:, 2])
    np.testing.assert_array_equal(out["interfering"], 0)


def test_cached_and_fresh_decodes_agree():
    ws = room()
    for name in ("via", "field"):
        enc = make_free_encoding(name, ws)
        rng = np.random.default_rng(3)
        A, B = rng.random((20, enc.n_var)), rng.random((15, enc.n_var))
        first = enc.decode(A)
        mixed = np.concatenate([B[:5], A[::2], B[5:]])
        got = enc.decode(mixed)
        fresh = make_free_encoding(name, ws).decode(mixed)
        np.testing.assert_array_equal(got[1], fresh[1])
        for i in range(len(mixed)):
            np.testing.assert_array_equal(got[0][i, : got[1][i]], fresh[0][i, : fresh[1][i]])
        np.testing.assert_array_equal(enc.path_keys(A), make_free_encoding(name, ws).path_keys(A))
        assert first[0].shape[0] == 20


@pytest.mark.parametrize("name", ["via", "field"])
def test_parallel_and_serial_decodes_agree(name):
    """The paths do not depend on the number of threads."""
    ws = room(seed=4)
    enc = make_free_encoding(name, ws)
    X = np.random.default_rng(7).random((21, enc.n_var))
    if name == "field":
        gy, gx = enc.field_shape
        args = (X, gy, gx, enc.beta, enc._occ, enc._extra, enc._s, enc._t, enc._cc, *enc.lam_range)
        args += (enc._hlen, enc._hext)
        serial, par = K.decode_field, K.decode_field_par
    else:
        args = (X, enc.n_via, enc._occ, enc._extra, enc._snap, enc._s, enc._t, enc._cc, *enc.lam_range)
        args += (enc._hlen, enc._hext, enc._pmin, enc._flen, enc._fext)
        serial, par = K.decode_via, K.decode_via_par
    want = serial(*args)
    for nt in (1, 2, 5):
        for a, b in zip(want, par(*args, nt)):
            np.testing.assert_array_equal(a, b)
    P, L = enc.decode(X)  # whichever kernel the encoding picks
    for i in range(len(X)):
        cells = P[i, : L[i], 0] * ws.shape[1] + P[i, : L[i], 1]
        np.testing.assert_array_equal(cells, want[0][want[1][i] : want[1][i + 1]])


def test_path_keys_identify_paths():
    ws = room()
    enc = ViaPointEncoding(ws)
    X = np.random.default_rng(0).random((200, enc.n_var))
    keys = enc.path_keys(X)
    paths = [p.tobytes() for p in (lambda P, L: [P[i, : L[i]] for i in range(len(L))])(*enc.decode(X))]
    same_key = {}
    for k, p in zip(map(tuple, keys), paths):
        same_key.setdefault(k, set()).add(p)
    assert all(len(v) == 1 for v in same_key.values())
    assert len(same_key) == len(set(paths))


def test_via_genome_reaches_its_via_cell():
    occ = np.zeros((6, 6), bool)
    ws = Workspace(occ)
    enc = ViaPointEncoding(ws, n_via=1)
    P, L = enc.decode(np.array([[0.0, 0.99, 0.5, 0.5]]))  # via the top-right... corner (0, 5)
    cells = {tuple(c) for c in P[0, : L[0]]}
    assert (0, 5) in cells


# ---------------------------------------------------------------------------
# seeding
# ---------------------------------------------------------------------------


def weighted_cost(enc, path, gene):
    lo, hi = enc.lam_range
    lam = 10 ** (lo + (hi - lo) * gene)
    a, b = 1 / (1 + lam), lam / (1 + lam)
    w = enc.shape[1]
    d = np.abs(np.diff(path, axis=0)).sum(axis=1)
    steps = np.where(d == 2, math.sqrt(2), 1.0)
    extra = enc._extra[path[1:, 0] * w + path[1:, 1]]
    return float(np.sum(a * steps + b * extra))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_weighted_seeds_decode_to_optimal_paths(seed):
    ws = room(seed=seed)
    genes = np.linspace(0, 1, 9)
    field = FieldEncoding(ws)
    paths = field.weighted_paths(genes)
    for p, q in zip(paths, field.decode(field.encode(paths, weights=genes))[0]):
        np.testing.assert_array_equal(p, q[: len(p)])
    via = ViaPointEncoding(ws)
    P, L = via.decode(via.encode(paths, weights=genes))
    for i, g in enumerate(genes):
        check_path(ws, P[i, : L[i]])
        assert weighted_cost(via, P[i, : L[i]], g) == pytest.approx(
            weighted_cost(via, paths[i], g), rel=1e-9, abs=1e-12
        )


def test_exact_seeds_reproduce_most_exact_paths():
    ws = room(seed=4)
    p = FreePathProblem(ws, encoding="via")
    ref = free_front(ws)
    X = p.encode(ref.paths)
    F = p.evaluate(X, return_as_dictionary=True)["F"]
    matched = sum(
        any(all(abs(a - b) <= TOL * max(1, abs(a), abs(b)) for a, b in zip(f, r)) for f in F) for r in ref.F
    )
    assert matched >= 0.8 * len(ref.F)


@pytest.mark.parametrize("encoding", ["via", "field"])
def test_free_sampling_distinct_paths_and_seeds_first(encoding):
    ws = room(20, 24)
    p = FreePathProblem(ws, encoding=encoding)
    X = FreeSampling()._do(p, 60, random_state=np.random.default_rng(0))
    assert X.shape == (60, p.n_var)
    keys = p.path_keys(X)
    assert len({tuple(k) for k in keys}) == 60
    seeds = free_seed_genomes(p, "weighted")
    np.testing.assert_array_equal(X[0], seeds[0])


# ---------------------------------------------------------------------------
# the GA against the exact front
# ---------------------------------------------------------------------------


def run_fast(problem, seed, pop=30, gen=15, sampling=None):
    alg = FastNSGA2(pop, sampling=sampling or FreeSampling())
    return minimize(problem, alg, ("n_gen", gen), seed=seed, copy_algorithm=False)


@pytest.mark.parametrize("encoding", ["via", "field"])
@pytest.mark.parametrize("seed", [1, 2])
def test_ga_front_never_dominates_exact_free_front(encoding, seed):
    ws = room(seed=seed, corner_cutting=bool(seed % 2))
    for objectives in (("length", "vulnerability"), ("length", "vulnerability", "smoothness")):
        p = FreePathProblem(ws, objectives, encoding=encoding)
        res = run_fast(p, seed, sampling=FreeSampling("none"))
        front = path_front(p, res.pop.get("X"))
        assert len(front) > 0
        ref = free_front(ws, objectives)
        for f in front.F:
            assert not any(dominates(f, r) for r in ref.F)
        for path in front.paths:
            check_path(ws, path)


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_brute_force_agrees_with_exact_free_front(seed):
    rng = np.random.default_rng(seed)
    h, w = (3, 4) if seed % 2 else (4, 3)
    paths = []
    while not paths:  # a map with at least one path
        occ = rng.random((h, w)) < 0.25
        occ[h - 1, 0] = occ[0, w - 1] = False
        ws = Workspace(occ, corner_cutting=bool(seed // 2))
        paths = simple_paths(ws)
    assert len(paths) > 1 or occ.sum() > 0
    P, L = pad_paths(paths)
    M = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    for cols, names in (
        ([0, 1], ("length", "vulnerability")),
        ([0, 1, 2], ("length", "vulnerability", "smoothness")),
    ):
        F = M[:, cols]
        nd = F[nondominated(F, tol=TOL)]
        ref = free_front(ws, names).F
        for r in ref:  # every exact point is a brute-force optimum
            assert any(np.allclose(r, q, rtol=TOL, atol=0) for q in nd)
        for q in nd:  # and every brute-force optimum is matched
            assert any(np.allclose(q, r, rtol=TOL, atol=0) for r in ref)


@pytest.mark.parametrize("encoding", ["via", "field"])
def test_free_problem_on_a_tiny_map_finds_the_brute_force_front(encoding):
    occ = np.array([[0, 0, 0, 0], [0, 1, 1, 0], [0, 0, 0, 0]], bool)
    ws = Workspace(occ, corner_cutting=False)
    paths = simple_paths(ws)
    P, L = pad_paths(paths)
    M = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)[:, :2]
    nd = M[nondominated(M, tol=TOL)]
    p = FreePathProblem(ws, encoding=encoding)
    res = run_fast(p, 1, pop=20, gen=10, sampling=FreeSampling("none"))
    front = path_front(p, res.pop.get("X"))
    for q in nd:
        assert any(np.allclose(q, f, rtol=TOL, atol=0) for f in front.F)


def test_determinism_for_a_seed():
    ws = room(seed=5)
    for encoding in ("via", "field"):
        a = run_fast(FreePathProblem(ws, encoding=encoding), 7).pop.get("X")
        b = run_fast(FreePathProblem(ws, encoding=encoding), 7).pop.get("X")
        np.testing.assert_array_equal(a, b)


def test_stock_pymoo_nsga2_runs_free_problem():
    ws = room(seed=6)
    p = FreePathProblem(ws)
    alg = NSGA2(pop_size=20, sampling=FreeSampling(), eliminate_duplicates=PathDuplicateElimination().bind(p))
    res = minimize(p, alg, ("n_gen", 4), seed=1)
    keys = p.path_keys(res.pop.get("X"))
    assert len({tuple(k) for k in keys}) == len(keys)
    assert (res.pop.get("interfering") == 0).all()


def test_layer_objectives():
    from gapath.costmap import Costmap

    ws = room(seed=7)
    elev = np.random.default_rng(0).random(ws.shape)
    cm = Costmap(ws, elevation=elev)
    p = FreePathProblem(ws, ("length", "elevation", "solar"), costmap=cm)
    X = np.random.default_rng(1).random((5, p.n_var))
    F = p.evaluate(X, return_as_dictionary=True)["F"]
    for f, path in zip(F, p.decode(X)):
        want = cm.evaluate_path(path, ("length", "elevation", "solar"))
        assert f == pytest.approx([want["length"], want["elevation"], want["solar"]], rel=1e-12)


# ---------------------------------------------------------------------------
# bad input
# ---------------------------------------------------------------------------


def test_unreachable_goal_is_a_no_path_error():
    occ = np.zeros((5, 5), bool)
    occ[:, 2] = True
    ws = Workspace(occ)
    with pytest.raises(NoPathError, match="no feasible path"):
        FreePathProblem(ws)
    with pytest.raises(NoPathError):
        FieldEncoding(ws)
    occ = np.array([[1, 0], [0, 1]], bool)  # start and goal meet only diagonally
    with pytest.raises(NoPathError, match="corner cutting not allowed"):
        FreePathProblem(Workspace(occ, start=(1, 0), goal=(0, 1), corner_cutting=False))
    p = FreePathProblem(Workspace(occ, start=(1, 0), goal=(0, 1), corner_cutting=True))
    assert [q.tolist() for q in p.decode(np.full((1, p.n_var), 0.3))] == [[[1, 0], [0, 1]]]


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(encoding="via", n_via=-1), "n_via"),
        (dict(encoding="via", n_via=1.5), "n_via"),
        (dict(encoding="field", field_shape=(1, 3)), "field_shape"),
        (dict(encoding="field", field_shape=(40, 3)), "finer than"),
        (dict(encoding="field", beta=0), "beta"),
        (dict(encoding="field", n_via=3), "does not apply"),
        (dict(encoding="nope"), "unknown encoding 'nope' for free paths"),
        (dict(objectives=("length", "height")), "unknown objective"),
        (dict(constraints="soft"), "constraint handling"),
        (dict(penalty=-1), "penalty"),
        (dict(lam_range=(2, 1)), "lam_range"),
    ],
)
def test_bad_settings_are_config_errors(kwargs, match):
    ws = room()
    with pytest.raises(ConfigError, match=match):
        FreePathProblem(ws, **kwargs)


def test_bad_genomes_and_paths():
    ws = room()
    p = FreePathProblem(ws)
    with pytest.raises(ConfigError, match="genes"):
        p.decode(np.zeros((2, p.n_var + 1)))
    with pytest.raises(ConfigError, match="finite"):
        p.decode(np.full((1, p.n_var), np.nan))
    with pytest.raises(ConfigError, match="start"):
        p.encode([np.array([[0, 0], [0, 1]])])
    with pytest.raises(ConfigError, match="seed source"):
        FreeSampling("astar")
    with pytest.raises(ConfigError, match="path set"):
        path_problem(ws, paths="curvy")


def test_search_threads_setting(monkeypatch):
    from gapath.encodings.free import search_threads

    monkeypatch.delenv("GAPATH_THREADS", raising=False)
    assert search_threads(1000) == 0  # serial by default
    monkeypatch.setenv("GAPATH_THREADS", "1")
    assert search_threads(1000) == 0
    monkeypatch.setenv("GAPATH_THREADS", "auto")
    assert search_threads(1) == 0  # too few searches to split
    monkeypatch.setenv("GAPATH_THREADS", "two")
    with pytest.raises(ConfigError, match="GAPATH_THREADS"):
        search_threads(1000)


def test_a_held_thread_is_left_to_its_search(monkeypatch):
    """A background search holds one of the wanted threads: the batches run
    serially on two threads while it is held, in parallel again once it is
    released (twice: the second release does nothing)."""
    from gapath.encodings import free

    monkeypatch.setattr(free, "wanted_threads", lambda: 2)
    assert free.search_threads(1000) == 2
    release = free.hold_thread()
    assert free.search_threads(1000) == 0
    release()
    assert free.search_threads(1000) == 2
    release()
    assert free.search_threads(1000) == 2
    monkeypatch.setattr(free, "wanted_threads", lambda: 4)
    with_one = free.hold_thread()
    assert free.search_threads(1000) == 3
    with_one()


@pytest.mark.parametrize("name", ["via", "field"])
@pytest.mark.parametrize("how", ["deepcopy", "pickle"])
def test_copied_encodings_reuse_the_compiled_decoder(name, how):
    """A deep copy or an unpickled encoding (a Dask worker's) decodes with the
    same read-only map arrays, so numba reuses the decoder compiled for the
    original instead of compiling every decode kernel a second time."""
    import copy
    import pickle

    ws = room(seed=5)
    user_layer = np.random.default_rng(0).random(ws.shape)
    enc = make_free_encoding(name, ws, extra=user_layer)
    assert user_layer.flags.writeable  # the caller's array is not frozen
    twin = copy.deepcopy(enc) if how == "deepcopy" else pickle.loads(pickle.dumps(enc))
    for e in (enc, twin):
        assert not (e._occ.flags.writeable or e._extra.flags.writeable)
        assert not (e.workspace.occ.flags.writeable or e.workspace.potential.flags.writeable)
    rng = np.random.default_rng(1)
    dispatchers = (K.decode_field, K.decode_field_par, K.decode_via, K.decode_via_par)
    want = enc.decode(rng.random((6, enc.n_var)))
    compiled = [len(d.signatures) for d in dispatchers]
    X = rng.random((6, enc.n_var))  # not in the twin's copied row cache
    got = twin.decode(X)
    assert [len(d.signatures) for d in dispatchers] == compiled
    fresh = enc.decode(X)
    np.testing.assert_array_equal(got[1], fresh[1])
    np.testing.assert_array_equal(got[0], fresh[0])
    assert want[0].shape[0] == 6
