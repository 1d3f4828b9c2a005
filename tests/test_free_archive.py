"""The free-path archive and its segment re-routing (issue 14)."""

from __future__ import annotations

import threading

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.optimize import minimize
from test_free_paths import TOL, check_path, dominates, room, workspaces

from gapath.algorithms import FastNSGA2
from gapath.convergence import HypervolumeRatioCallback
from gapath.encodings import _free_kernels as K
from gapath.encodings.free import FieldEncoding, ViaPointEncoding
from gapath.errors import ConfigError
from gapath.front import path_front
from gapath.metrics import hv_ratio, nondominated
from gapath.objectives import evaluate_paths, pad_paths
from gapath.operators.archive import (
    APPROX_EPSILON,
    APPROX_RETRY_BELOW,
    APPROX_RETRY_EPSILON,
    FreePathArchive,
    eps_cover,
    run_archive,
)
from gapath.operators.sampling.free_sampling import FreeSampling
from gapath.planners.exact import free_front
from gapath.problems import FreePathProblem, GridPathProblem
from gapath.solver import solve

OBJ3 = ("length", "vulnerability", "smoothness")


def _check_front(ws, p, front, exact_objectives=None):
    """Every path valid, ``F`` recomputed from the paths, mutually
    non-dominated and (with ``exact_objectives``) never better than the
    exact front; returns the recomputed metrics."""
    for path in front.paths:
        check_path(ws, path)
    P, L = pad_paths(front.paths)
    M = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    np.testing.assert_allclose(front.F, p.objective_values(M), rtol=0, atol=0)
    assert len(nondominated(front.F, tol=TOL)) == len(front)
    if exact_objectives is not None:
        exact = free_front(ws, exact_objectives).F
        for f in front.F:
            assert not any(dominates(f, r) for r in exact)
    return M


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(data=st.data())
def test_rerouted_paths_are_simple_feasible_paths(data):
    ws = data.draw(workspaces())
    enc = (
        ViaPointEncoding(ws, n_via=data.draw(st.integers(0, 3)))
        if data.draw(st.booleans())
        else FieldEncoding(ws, field_shape=(2, 2))
    )
    n = data.draw(st.integers(1, 6))
    rng = np.random.default_rng(data.draw(st.integers(0, 2**31 - 1)))
    flat, offsets, _ = enc.decode_flat(rng.random((n, enc.n_var)))
    k = data.draw(st.integers(1, 12))
    pick = rng.integers(0, n, k)
    i0 = rng.integers(-2, 12, k)
    i1 = i0 + rng.integers(-1, 14, k)
    lam = data.draw(st.sampled_from([None, (-3.0, 12.0), (0.0, 1.0)]))
    turns = rng.random(k) if data.draw(st.booleans()) else None
    margin = data.draw(st.sampled_from([-1, 0, 1, 3, 64]))  # the window around a stretch
    f2, o2, keys = enc.reroute(flat, offsets, pick, i0, i1, rng.random(k), lam, turns, margin=margin)
    P, L = enc.padded(f2, o2)
    assert len(L) == k
    for i in range(k):
        check_path(ws, P[i, : L[i]])
    assert (keys[:, 0] == L).all()


@pytest.mark.parametrize("turns", [False, True])
def test_parallel_and_serial_reroutes_agree(turns):
    ws = room(seed=5)
    enc = FieldEncoding(ws)
    rng = np.random.default_rng(2)
    flat, offsets, _ = enc.decode_flat(rng.random((6, enc.n_var)))
    k = 13
    pick = rng.integers(0, 6, k)
    m = np.diff(offsets)[pick]
    i0 = (rng.random(k) * m // 2).astype(np.int64)
    i1 = i0 + (rng.random(k) * m // 2).astype(np.int64)
    args = [flat, offsets, pick, i0, i1, rng.random(k)]
    extra = [rng.random(k)] if turns else []
    tail = (enc._occ, enc._extra, enc._cc, -3.0, 12.0)
    if turns:
        kern, par = K.reroute_turns, K.reroute_turns_par
        rest = (-2.0, 2.0, 3, enc._pmin, enc._hlen, enc._hext, enc._flen, enc._fext)
    else:
        kern, par = K.reroute, K.reroute_par
        rest = (enc._t, enc._hlen, enc._hext, enc._pmin, enc._flen, enc._fext, 3)
    want = kern(*args, *extra, *tail, *rest)
    for nt in (1, 2, 3):
        got = par(*args, *extra, *tail, *rest, nt)
        for a, b in zip(want, got):
            np.testing.assert_array_equal(a, b)


def test_rerouting_a_whole_path_gives_the_weighted_path():
    ws = room(seed=3)
    enc = FieldEncoding(ws)
    genes = np.array([0.0, 0.5, 1.0])
    flat, offsets, _ = enc.decode_flat(np.full((1, enc.n_var), 0.5))
    f2, o2, _ = enc.reroute(flat, offsets, np.zeros(3, np.int64), np.zeros(3), np.full(3, 10**6), genes)
    P, L = enc.padded(f2, o2)
    for i, want in enumerate(enc.weighted_paths(genes)):
        np.testing.assert_array_equal(P[i, : L[i]], want)


@pytest.mark.parametrize("objectives", [("length", "vulnerability"), OBJ3])
@pytest.mark.parametrize("seed", [1, 2])
def test_archive_front_is_valid_non_dominated_and_never_beats_exact(objectives, seed):
    ws = room(seed=seed, corner_cutting=bool(seed % 2))
    p = FreePathProblem(ws, objectives)
    archive = FreePathArchive(p, n_refine=20, seed=seed)
    minimize(p, FastNSGA2(20, sampling=FreeSampling("none")), ("n_gen", 8), seed=seed, callback=archive)
    front = archive.front()
    assert len(front) > 0
    M = _check_front(ws, p, front, objectives)  # objectives recomputed from the paths
    np.testing.assert_allclose(front.metrics, M, rtol=0, atol=0)


def test_archive_holds_the_population_front():
    """Nothing the population's front holds is missing from (or dominating)
    the archive: it has seen every offspring."""
    ws = room(seed=4)
    p = FreePathProblem(ws, OBJ3)
    archive = FreePathArchive(p, n_refine=0, faces=0, approx=0)
    res = minimize(p, FastNSGA2(16, sampling=FreeSampling("none")), ("n_gen", 10), seed=3, callback=archive)
    pop_front = path_front(p, res.pop.get("X"))
    A = archive.front()
    assert A.X.shape == (len(A), p.n_var)  # no re-routing: every path has its genome
    np.testing.assert_array_equal(A.F, path_front(p, A.X).F)
    for f in pop_front.F:
        assert not any(dominates(f, a) for a in A.F)
        assert any(np.allclose(f, a, rtol=TOL, atol=0) or dominates(a, f) for a in A.F)


def test_solve_free_returns_the_archive_deterministically():
    ws = room(seed=6)
    runs = [solve(ws, paths="free", pop_size=20, n_gen=6, seed=5) for _ in range(2)]
    a, b = (r.front for r in runs)
    np.testing.assert_array_equal(a.F, b.F)
    assert [x.tolist() for x in a.paths] == [x.tolist() for x in b.paths]
    assert runs[0].settings["refine"] == 10
    three = solve(ws, objectives=OBJ3, paths="free", pop_size=10, n_gen=2, seed=5, tiebreak=None)
    assert three.settings["refine"] == 160  # 16 x pop with smoothness (default_refine)
    assert runs[0].n_eval > runs[0].pymoo_result.algorithm.evaluator.n_eval
    arch = run_archive(runs[0].pymoo_result.algorithm)
    np.testing.assert_array_equal(arch.F, a.F)
    plain = solve(ws, paths="free", pop_size=20, n_gen=6, seed=5, refine=False)
    assert plain.front.X.shape[1] == plain.problem.n_var
    assert "refine" not in plain.settings
    for f in plain.front.F:  # the archive front is at least as good
        assert not any(dominates(f, x) for x in a.F)


def test_convergence_callback_reads_the_archive():
    ws = room(seed=7)
    cb = HypervolumeRatioCallback(free_front(ws))
    r = solve(ws, paths="free", pop_size=20, n_gen=5, seed=2, callback=cb)
    from gapath.metrics import hv_ratio

    assert cb.history[-1][2] == pytest.approx(hv_ratio(r.front.F, free_front(ws).F), abs=1e-12)


def test_stock_pymoo_algorithm_with_archive():
    ws = room(seed=8)
    p = FreePathProblem(ws)
    archive = FreePathArchive(p, n_refine=5)
    minimize(p, NSGA2(12), ("n_gen", 4), seed=1, callback=archive)
    assert len(archive) > 0
    for path in archive.paths():
        check_path(ws, path)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(n_refine=-1), "n_refine"),
        (dict(n_refine="x"), "n_refine"),
        (dict(segment=(0.5, 0.1)), "segment"),
        (dict(segment=3), "segment"),
        (dict(lam_range=(2, 1)), "lam_range"),
    ],
)
def test_bad_archive_settings(kwargs, match):
    with pytest.raises(ConfigError, match=match):
        FreePathArchive(FreePathProblem(room(seed=1)), **kwargs)


def test_archive_needs_a_free_problem():
    # (monotone runs take ``refine`` too since MonotonePathArchive:
    # tests/test_monotone_archive.py)
    ws = room(seed=1)
    with pytest.raises(ConfigError, match="FreePathProblem"):
        FreePathArchive(GridPathProblem(ws))


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(data=st.data())
def test_straightened_paths_are_simple_feasible_paths(data):
    ws = data.draw(workspaces())
    enc = FieldEncoding(ws, field_shape=(2, 2))
    n = data.draw(st.integers(1, 6))
    rng = np.random.default_rng(data.draw(st.integers(0, 2**31 - 1)))
    flat, offsets, _ = enc.decode_flat(rng.random((n, enc.n_var)))
    k = data.draw(st.integers(1, 12))
    pick = rng.integers(0, n, k)
    i0 = rng.integers(-2, 12, k)
    i1 = i0 + rng.integers(-1, 14, k)
    f2, o2, _ = enc.shortcut(flat, offsets, pick, i0, i1, rng.random(k) < 0.5)
    P, L = enc.padded(f2, o2)
    P0, L0 = enc.padded(flat, offsets)
    M = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    M0 = evaluate_paths(P0, L0, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    for i in range(k):
        check_path(ws, P[i, : L[i]])
        # never longer: the one-bend path is a shortest path between its ends
        assert M[i, 0] <= M0[pick[i], 0] + 1e-9


def test_shortcut_share_setting():
    ws = room(seed=2)
    assert FreePathArchive(FreePathProblem(ws)).shortcut == 0.0
    assert FreePathArchive(FreePathProblem(ws, OBJ3)).shortcut == 0.25
    with pytest.raises(ConfigError, match="shortcut"):
        FreePathArchive(FreePathProblem(ws), shortcut=1.5)


def test_turn_weighted_reroute_of_a_whole_path_is_no_less_smooth_than_plain():
    """With a heavy turn weight the (cell, move) search of a whole path
    finds a path with no more turns than the plain weighted search."""
    for seed in range(4):
        ws = room(seed=seed)
        enc = FieldEncoding(ws)
        flat, off, _ = enc.decode_flat(np.full((1, enc.n_var), 0.5))
        args = (flat, off, np.zeros(2, np.int64), np.zeros(2), np.full(2, 10**6), np.array([0.0, 0.0]))
        plain = enc.padded(*enc.reroute(*args)[:2])
        turny = enc.padded(*enc.reroute(*args, turn_genes=np.array([1.0, 1.0]))[:2])
        Mp = evaluate_paths(*plain, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
        Mt = evaluate_paths(*turny, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
        assert (Mt[:, 2] <= Mp[:, 2] + 1e-9).all()
        for i in range(2):
            check_path(ws, turny[0][i, : turny[1][i]])


# -- incremental update, parent picking, cap (eighth session) -------------------


def _batch_front(problem, flat, offsets, keys):
    """The archive's front as the first archive computed it: every path seen,
    one row per path, the feasible non-dominated ones (select_front)."""
    from gapath.front import select_front

    enc = problem.encoding
    P, L = enc.padded(flat, offsets)
    M = problem.path_metrics(P, L)
    _, first = np.unique(keys, axis=0, return_index=True)
    rows = np.sort(first)
    rows = rows[M[rows, 3] == 0]
    F = problem.objective_values(M[rows])
    return F[select_front(F, M[rows])]


@pytest.mark.parametrize("objectives", [("length", "vulnerability"), OBJ3])
def test_incremental_update_gives_the_batch_front(objectives):
    """Genome batches added one at a time give the front of all of them
    taken together (the archive is non-dominated, so the incremental
    update loses nothing)."""
    ws = room(h=14, w=16, seed=11)
    p = FreePathProblem(ws, objectives)
    enc = p.encoding
    archive = FreePathArchive(p, n_refine=0, cap=None)
    rng = np.random.default_rng(4)
    seen = None
    for _ in range(6):
        X = rng.random((30, p.n_var))
        archive.add(X)
        f, o, k = enc.decode_flat(X)
        seen = (
            (f, o, k)
            if seen is None
            else (*enc.concat_flat(seen[0], seen[1], f, o), np.concatenate([seen[2], k]))
        )
        np.testing.assert_array_equal(archive.F, _batch_front(p, *seen))


@pytest.mark.parametrize("cap", [8, 12])
def test_cap_holds_and_keeps_the_extremes(cap):
    ws = room(h=20, w=24, seed=12)  # 25 points uncapped
    p = FreePathProblem(ws, OBJ3)
    archive = FreePathArchive(p, n_refine=30, seed=3, cap=cap)
    free = FreePathArchive(p, n_refine=0, cap=None)  # the same offspring, uncapped, no refinement

    class Both:
        def __call__(self, algorithm):
            archive.notify(algorithm)
            free.notify(algorithm)
            assert len(archive) <= cap

    minimize(p, FastNSGA2(20, sampling=FreeSampling("none")), ("n_gen", 8), seed=2, callback=Both())
    A = archive.front()
    assert 0 < len(A) <= cap
    assert archive.n_dropped > 0
    _check_front(ws, p, A)
    # no kept path is dominated by a dropped one, nor by a path the uncapped archive holds
    from gapath.operators.archive import dominated_by

    assert not dominated_by(A.F, archive._shadow).any()
    # the best value of every objective is never lost to the cap
    for j in range(p.n_obj):
        assert A.F[:, j].min() <= free.F[:, j].min() * (1 + TOL)


def test_capped_archive_is_deterministic():
    ws = room(h=20, w=24, seed=12)
    out = []
    for _ in range(2):
        p = FreePathProblem(ws, OBJ3)
        a = FreePathArchive(p, n_refine=25, seed=7, cap=6)
        minimize(p, FastNSGA2(16, sampling=FreeSampling("none")), ("n_gen", 5), seed=4, callback=a)
        out.append(a)
    np.testing.assert_array_equal(out[0].F, out[1].F)
    assert [x.tolist() for x in out[0].paths()] == [x.tolist() for x in out[1].paths()]
    np.testing.assert_array_equal(out[0]._shadow, out[1]._shadow)


def test_aimed_weight_genes_lie_between_the_neighbours_trade_offs():
    ws = room(h=14, w=16, seed=14)
    p = FreePathProblem(ws)
    assert FreePathArchive(p).sparse == 0.0 and FreePathArchive(FreePathProblem(ws, OBJ3)).sparse == 0.5
    a = FreePathArchive(p, n_refine=0, sparse=0.5)
    a.add(np.random.default_rng(1).random((200, p.n_var)))
    assert a._aim and len(a) >= 3
    F = a.F
    n = 400
    pick, aimed = a._parents(n)
    assert aimed.sum() == n // 2
    (lo, top), g = a._weight_genes(pick, aimed, np.random.default_rng(2).random(n))
    assert lo == a.lam_range[0] and top > a.lam_range[1]
    assert ((g >= 0) & (g <= 1)).all()
    lam = lo + (top - lo) * g
    slope = np.clip(np.log10(np.diff(F[:, 0]) / -np.diff(F[:, 1])), lo, top)
    for i, lm, aim in zip(pick, lam, aimed):
        if not aim:
            assert a.lam_range[0] - 1e-9 <= lm <= a.lam_range[1] + 1e-9
            continue
        near = (slope[i - 1] if i > 0 else lo, slope[i] if i < len(F) - 1 else top)
        assert max(lo, min(near) - 0.5) - 1e-9 <= lm <= top + 1e-9
    assert not FreePathArchive(FreePathProblem(ws, OBJ3))._aim


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(sparse=-0.1), "sparse"),
        (dict(sparse="x"), "sparse"),
        (dict(cap=1), "cap"),
        (dict(cap=2.5), "cap"),
        (dict(cap="many"), "cap"),
        (dict(extremes=-1), "extremes"),
        (dict(extremes=0.5), "extremes"),
    ],
)
def test_bad_sparse_and_cap(kwargs, match):
    with pytest.raises(ConfigError, match=match):
        FreePathArchive(FreePathProblem(room(seed=1)), **kwargs)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_extreme_reroutes_reach_the_smoothest_exact_point(seed):
    """With smoothness as an objective and no face searches, the whole-path
    re-routings under a heavy turn weight give the front's smoothest point
    (exact search on a small map says which it is); with the faces (the
    default) there are none by default, and the faces give that point."""
    ws = room(h=14, w=16, seed=20 + seed, density=0.2)
    p = FreePathProblem(ws, OBJ3)
    want = free_front(ws, OBJ3).F[:, 2].min()
    for faces in (0, None):
        archive = FreePathArchive(p, n_refine=4, seed=seed, faces=faces, approx=0 if faces == 0 else None)
        assert archive.extremes == (4 if faces == 0 else 0)
        minimize(p, FastNSGA2(10, sampling=FreeSampling("none")), ("n_gen", 2), seed=seed, callback=archive)
        assert archive.F[:, 2].min() == pytest.approx(want, rel=TOL, abs=1e-12)
    plain = FreePathArchive(p, n_refine=4, seed=seed, extremes=0, faces=0)
    assert plain.extremes == 0


@pytest.mark.parametrize("objectives", [("length", "vulnerability"), OBJ3])
def test_exact_stretches_splice_valid_paths_and_never_beat_exact(objectives):
    ws = room(h=14, w=16, seed=31)
    p = FreePathProblem(ws, objectives)
    archive = FreePathArchive(p, n_refine=0, seed=2, exact_stretches=3)
    minimize(p, FastNSGA2(12, sampling=FreeSampling("none")), ("n_gen", 4), seed=2, callback=archive)
    assert archive.n_eval > 0  # spliced paths were evaluated
    front = archive.front()
    P, L = pad_paths(front.paths)
    M = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    np.testing.assert_allclose(front.F, p.objective_values(M), rtol=0, atol=0)
    for path in front.paths:
        check_path(ws, path)
    exact = free_front(ws, objectives).F
    for f in front.F:
        assert not any(dominates(f, r) for r in exact)
    with pytest.raises(ConfigError, match="exact_stretches"):
        FreePathArchive(p, exact_stretches=-2)


PAIRS = [("length", "smoothness"), ("length", "vulnerability"), ("vulnerability", "smoothness")]


def _covers(FA, idx, f) -> bool:
    """Some row of ``FA`` is at least as good as ``f`` in the columns ``idx``."""
    return bool(np.any(np.all(FA[:, idx] <= f + TOL * np.abs(f) + 1e-12, axis=1)))


@pytest.mark.parametrize("seed", [1, 2])
def test_faces_cover_every_pairwise_exact_front(seed):
    """With three objectives the first refinement archives the exact front
    of each pair of objectives: every point of each pair's front is matched
    in that pair by an archived path (its own, or one that dominates it in
    all three); without faces a random population of 10 does not get there."""
    ws = room(h=14, w=16, seed=40 + seed)
    p = FreePathProblem(ws, OBJ3)
    runs = {}
    for faces in (None, 0):
        archive = FreePathArchive(p, n_refine=0, seed=seed, extremes=0, faces=faces, approx=0)
        minimize(p, FastNSGA2(10, sampling=FreeSampling("none")), ("n_gen", 1), seed=seed, callback=archive)
        runs[faces] = archive
    with_faces, without = runs[None], runs[0]
    assert [pair for pair, _, _ in with_faces.face_sizes] == PAIRS
    assert without.face_sizes == [] and without.faces == 0
    missed = 0
    for pair, n, done in with_faces.face_sizes:
        face = free_front(ws, pair).F
        assert done and n == len(face)
        idx = [OBJ3.index(name) for name in pair]
        assert all(_covers(with_faces.F, idx, f) for f in face)
        missed += sum(not _covers(without.F, idx, f) for f in face)
    assert missed > 0
    _check_front(ws, p, with_faces.front(), OBJ3)


def _on_front(F, exact) -> bool:
    """Every row of ``F`` is a point of ``exact`` (up to the tolerance)."""
    return all(np.any(np.all(np.abs(exact - f) <= TOL * np.abs(f) + 1e-12, axis=1)) for f in F)


def test_faces_over_budget_keep_what_they_found_and_two_objectives_have_none(monkeypatch):
    """A face search that reaches what is left of the budget stops there
    (checked every CHECK_POPS pops, 8 here) and keeps the points it found,
    each on its exact face; the searches after it do not run."""
    from gapath.planners import exact

    monkeypatch.setattr(exact, "CHECK_POPS", 8)
    ws = room(h=14, w=16, seed=43)
    p = FreePathProblem(ws, OBJ3)
    archive = FreePathArchive(p, n_refine=0, extremes=0, faces=1e-6, approx=0)
    minimize(p, FastNSGA2(10, sampling=FreeSampling("none")), ("n_gen", 1), seed=1, callback=archive)
    (first, k, done), *rest = archive.face_sizes
    assert first == PAIRS[0] and not done
    assert rest == [(pair, None, False) for pair in PAIRS[1:]]
    assert archive.n_eval == k
    # a budget that the first search fits, with what the second needs to find half
    # of its solutions left for the rest: the second stops there and keeps them
    full = [free_front(ws, pair) for pair in PAIRS]
    checks = []
    free_front(ws, PAIRS[1], max_expansions=1e12, progress=checks.append)
    found = [c["expansions"] for c in checks if 0 < c["solutions"] < len(full[1])]
    m = found[len(found) // 2] + 0.5
    budget = full[0].stats["expansions"] + m
    shared = FreePathArchive(p, n_refine=0, extremes=0, faces=budget / p.encoding.n_reachable, approx=0)
    minimize(p, FastNSGA2(10, sampling=FreeSampling("none")), ("n_gen", 1), seed=1, callback=shared)
    assert shared.face_sizes[0] == (PAIRS[0], len(full[0]), True)
    (second, k2, done2), third = shared.face_sizes[1:]
    assert second == PAIRS[1] and not done2 and 0 < k2 < len(full[1])
    assert third == (PAIRS[2], None, False)
    part = free_front(ws, PAIRS[1], max_expansions=m)
    assert len(part) == k2 and _on_front(part.F, full[1].F)
    idx = [OBJ3.index(name) for name in PAIRS[1]]
    assert all(_covers(shared.F, idx, f) for f in part.F)
    assert FreePathArchive(FreePathProblem(ws), n_refine=0).faces == 0
    for bad in (-1, "x", float("nan")):
        with pytest.raises(ConfigError, match="faces"):
            FreePathArchive(p, faces=bad)


def test_approximate_search_follows_the_faces_within_its_own_budget(monkeypatch):
    """With length, vulnerability and smoothness the faces are followed by
    the approximate three-objective search (its own budget): its points are
    archived (each matched by an archived path at least as good), the front
    stays valid and never beats the exact one; a budget it reaches stops
    it (keeping what it found) and nothing else; other objective sets have
    none."""
    from gapath.planners import exact

    monkeypatch.setattr(exact, "CHECK_POPS", 8)
    ws = room(h=14, w=16, seed=44)
    p = FreePathProblem(ws, OBJ3)
    archive = FreePathArchive(p, n_refine=0, extremes=0)
    minimize(p, FastNSGA2(10, sampling=FreeSampling("none")), ("n_gen", 1), seed=1, callback=archive)
    assert archive.approx == APPROX_EPSILON
    assert [objs for objs, _, _ in archive.face_sizes] == PAIRS + [OBJ3]
    approx = free_front(ws, OBJ3, epsilon=APPROX_EPSILON)
    assert archive.face_sizes[-1] == (OBJ3, len(approx), True)
    assert all(_covers(archive.F, [0, 1, 2], f) for f in approx.F)
    _check_front(ws, p, archive.front(), OBJ3)
    # the approximate search alone, and one over its budget (the faces untouched)
    alone = FreePathArchive(p, n_refine=0, extremes=0, faces=0)
    over = FreePathArchive(p, n_refine=0, extremes=0, approx_budget=1e-6)
    for a in (alone, over):
        minimize(p, FastNSGA2(10, sampling=FreeSampling("none")), ("n_gen", 1), seed=1, callback=a)
    assert alone.face_sizes == [(OBJ3, len(approx), True)]
    stopped = free_front(ws, OBJ3, epsilon=APPROX_EPSILON, max_expansions=1)
    assert not stopped.stats["complete"] and len(stopped) < len(approx)
    assert over.face_sizes == archive.face_sizes[:3] + [(OBJ3, len(stopped), False)]
    # not run when a face stopped short of its front; the (length,
    # vulnerability) face is searched first (it decides approx_retry's rule)
    # and recorded in face_pairs's order
    dropped = FreePathArchive(p, n_refine=0, extremes=0, faces=1e-6)
    minimize(p, FastNSGA2(10, sampling=FreeSampling("none")), ("n_gen", 1), seed=1, callback=dropped)
    k = len(free_front(ws, PAIRS[1], max_expansions=1))
    assert dropped.face_sizes == [(PAIRS[0], None, False), (PAIRS[1], k, False), (PAIRS[2], None, False)] + [
        (OBJ3, None, False)
    ]
    assert dropped.n_eval == k and dropped.approx_shortfall is None
    # without the rule, the faces' own order
    plain = FreePathArchive(p, n_refine=0, extremes=0, faces=1e-6, approx_retry=0)
    minimize(p, FastNSGA2(10, sampling=FreeSampling("none")), ("n_gen", 1), seed=1, callback=plain)
    k = len(free_front(ws, PAIRS[0], max_expansions=1))
    assert plain.face_sizes == [(PAIRS[0], k, False)] + [(pair, None, False) for pair in PAIRS[1:]] + [
        (OBJ3, None, False)
    ]
    assert FreePathArchive(FreePathProblem(ws), n_refine=0).approx == 0
    assert (
        FreePathArchive(FreePathProblem(ws, ("length", "smoothness", "vulnerability")), n_refine=0).approx > 0
    )


def _two_threads(monkeypatch, log=None) -> list:
    """Ask for two threads (whatever the machine has) and record every
    second-thread search the archive starts (appended to the returned list,
    and ``"search"`` to ``log``)."""
    from gapath.encodings import free
    from gapath.operators import archive as A

    started: list = []

    class Spy(A._Background):
        def __init__(self, fn):
            started.append(self)
            if log is not None:
                log.append("search")
            super().__init__(fn)

    monkeypatch.setattr(A, "_Background", Spy)
    monkeypatch.setattr(free, "wanted_threads", lambda: 2)
    return started


@pytest.mark.parametrize("seed, faces", [(44, None), (44, 1e-6), (45, None)])
def test_approximate_search_in_a_second_thread_gives_the_serial_archive(monkeypatch, seed, faces):
    """With two threads asked for (``GAPATH_THREADS``) an approximate
    search runs in a second thread beside the faces: the archive gets the
    same paths, points and records as serially, whether approx_retry's
    rule fires (room 45: the finer search in the second thread, the first
    one in this thread after the faces) or not (room 44). When a face stops
    short the second thread's search is cancelled and dropped, as serially
    it is not run; no thread is left behind."""

    ws = room(h=14, w=16, seed=seed)
    p = FreePathProblem(ws, OBJ3)

    def run():
        a = FreePathArchive(p, n_refine=0, extremes=0, faces=faces)
        minimize(p, FastNSGA2(10, sampling=FreeSampling("none")), ("n_gen", 1), seed=1, callback=a)
        return a

    serial = run()
    fired = serial.retry_size is not None
    assert fired == (seed == 45)  # both cases are exercised
    started = _two_threads(monkeypatch)
    threaded = run()
    # the approximate search, replaced by the finer one when the rule fires
    assert len(started) == (2 if fired else 1)
    assert not any(s._thread.is_alive() for s in started)
    assert threaded.face_sizes == serial.face_sizes
    assert threaded.retry_size == serial.retry_size
    assert threaded.approx_shortfall == serial.approx_shortfall
    assert (serial.face_sizes[-1][1] is None) == (faces is not None)  # both cases are exercised
    np.testing.assert_array_equal(threaded.F, serial.F)
    assert all(np.array_equal(a, b) for a, b in zip(threaded.paths(), serial.paths(), strict=True))
    assert threaded.n_eval == serial.n_eval
    assert not any(t.name == "gapath-approx-search" for t in threading.enumerate())
    # the two threads run at once only if the searches' kernels release the GIL
    from gapath.planners import _apex_kernels, _boa_kernels, _exact_heuristics, _exact_kernels

    kernels = (
        _apex_kernels._apex_run,
        _exact_kernels._free_run,
        _exact_kernels._trace_parents,
        _exact_heuristics._free_prepare,
        _boa_kernels._boa_run,
        _boa_kernels._boa_prepare,
        _boa_kernels._boa_solve,
        _boa_kernels._boa_finish,
    )
    assert all(k.targetoptions.get("nogil") for k in kernels)


def test_search_started_before_sampling_gives_the_serial_run(monkeypatch):
    """``solve`` starts the second thread's search before the first
    population is sampled (:meth:`FreePathArchive.start`): the run's front
    is the serial run's; :meth:`FreePathArchive.close` cancels a search
    that was not taken, and a later :meth:`add_faces` runs it again."""

    ws = room(h=14, w=16, seed=45)
    serial = solve(ws, objectives=OBJ3, paths="free", pop_size=10, n_gen=2, seed=3)
    log: list[str] = []
    started = _two_threads(monkeypatch, log)
    evaluate = FreePathProblem._evaluate

    def logged(self, *args, **kwargs):
        log.append("evaluate")
        return evaluate(self, *args, **kwargs)

    monkeypatch.setattr(FreePathProblem, "_evaluate", logged)
    threaded = solve(ws, objectives=OBJ3, paths="free", pop_size=10, n_gen=2, seed=3)
    # the approximate search, then the finer one instead (room 45's face is coarse)
    assert len(started) == 2 and started[0]._event.is_set()
    assert not any(s._thread.is_alive() for s in started)
    assert log[0] == "search" and "evaluate" in log  # before the first population
    np.testing.assert_array_equal(threaded.front.F, serial.front.F)
    p = FreePathProblem(ws, OBJ3)
    archive = FreePathArchive(p, n_refine=0, extremes=0)
    archive.start()
    archive.start()  # once
    assert len(started) == 4
    archive.close()
    assert started[3]._event.is_set() and not started[3]._thread.is_alive()
    archive.add_faces()  # the finer search again (the face searched by start() is kept)
    assert len(started) == 5 and archive.face_sizes[-1][0] == OBJ3 and archive.face_sizes[-1][1]
    assert archive.retry_size is not None and archive.retry_size[1]
    archive.start()  # after the faces: nothing
    assert len(started) == 5


def test_second_thread_errors_and_interrupts_end_both_searches(monkeypatch):
    """An error in the second thread's search reaches the caller; a Ctrl-C
    (KeyboardInterrupt) during the faces cancels the second thread's search,
    which ends before the interrupt leaves :meth:`add_faces`."""
    from gapath.operators import archive as A

    ws = room(h=14, w=16, seed=44)
    p = FreePathProblem(ws, OBJ3)
    started = _two_threads(monkeypatch)
    real = A._budget_search

    def failing(ws, objectives, eps, budget, cancel=None):
        if eps > 0:
            raise RuntimeError("approximate search failed")
        return real(ws, objectives, eps, budget, cancel)

    monkeypatch.setattr(A, "_budget_search", failing)
    with pytest.raises(RuntimeError, match="approximate search failed"):
        FreePathArchive(p, n_refine=0, extremes=0).add_faces()

    def interrupted(ws, objectives, eps, budget, cancel=None):
        if eps > 0:  # runs until cancelled
            while not cancel.wait(0.01):
                pass
            raise A._Cancelled
        raise KeyboardInterrupt

    monkeypatch.setattr(A, "_budget_search", interrupted)
    with pytest.raises(KeyboardInterrupt):
        FreePathArchive(p, n_refine=0, extremes=0).add_faces()
    # the failing run: the approximate search (room 44's face is not coarse);
    # the interrupted one: the approximate search (the faces never ended)
    assert len(started) == 2 and all(not b._thread.is_alive() for b in started)


def test_second_thread_search_holds_a_thread_until_it_ends(monkeypatch):
    """While the second thread's search runs, the main thread's batches of
    searches run serially (they would wait for a thread sharing its core);
    the thread is given back when the search ends, fails or is cancelled."""
    from gapath.encodings import free
    from gapath.operators import archive as A

    _two_threads(monkeypatch)
    assert free.search_threads(1000) == 2

    def waiting(cancel):
        while not cancel.wait(0.01):
            pass
        return "cancelled"

    def failing(cancel):
        raise RuntimeError("search failed")

    b = A._Background(waiting)
    assert free.search_threads(1000) == 0
    b.cancel()
    assert free.search_threads(1000) == 2
    b = A._Background(failing)
    with pytest.raises(RuntimeError, match="search failed"):
        b.result()
    assert free.search_threads(1000) == 2
    b = A._Background(lambda cancel: 7)
    assert b.result() == 7 and free.search_threads(1000) == 2


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"approx": -0.1}, "approx must be"),
        ({"approx": float("nan")}, "approx must be"),
        ({"approx": "x"}, "approx must be"),
        ({"approx_budget": -1}, "approx_budget"),
        ({"approx_budget": "x"}, "approx_budget"),
        ({"approx_retry": -0.5}, "approx_retry"),
        ({"approx_retry": "x"}, "approx_retry"),
        ({"approx_retry_epsilon": 0}, "approx_retry_epsilon must be an epsilon > 0"),
        ({"approx_retry_epsilon": -0.01}, "approx_retry_epsilon"),
        ({"approx_retry_epsilon": "x"}, "approx_retry_epsilon"),
    ],
)
def test_bad_approx_settings(kwargs, match):
    p = FreePathProblem(room(seed=1), OBJ3)
    with pytest.raises(ConfigError, match=match):
        FreePathArchive(p, **kwargs)
    with pytest.raises(ConfigError, match="needs the objectives length, vulnerability and smoothness"):
        FreePathArchive(FreePathProblem(room(seed=1)), approx=0.1)


@pytest.mark.parametrize("threads", [1, 2])
def test_coarse_face_adds_the_search_at_a_smaller_epsilon(monkeypatch, threads):
    """When the exact (length, vulnerability) face, cut to its eps_cover at
    ``approx``, keeps less than ``approx_retry`` of its HV, the search also
    runs at ``approx_retry_epsilon``: the share is recorded as computed from
    the face, every point of the finer front is matched in the archive, the
    front stays valid, and two threads give the serial archive. Above the
    bound (or with ``approx_retry=0``) nothing more runs and the archive is
    the one without the rule. With two threads the finer search runs in the
    second thread (never in the main one) and the first one in the main
    thread after the faces."""
    from gapath.operators import archive as A

    ws = room(h=14, w=16, seed=45)
    p = FreePathProblem(ws, OBJ3)
    face = free_front(ws, ("length", "vulnerability")).F
    shortfall = hv_ratio(face[eps_cover(face, APPROX_EPSILON)], face)
    assert 0 < shortfall < APPROX_RETRY_BELOW  # the default fires here; the bounds below fall on both sides

    def run(bound, **kw):
        a = FreePathArchive(p, n_refine=0, extremes=0, approx_retry=bound, **kw)
        minimize(p, FastNSGA2(10, sampling=FreeSampling("none")), ("n_gen", 1), seed=1, callback=a)
        return a

    serial = {b: run(b) for b in (0, shortfall - 1e-6, shortfall + 1e-6)}
    started: list = []
    in_main: list = []
    if threads == 2:
        started = _two_threads(monkeypatch)
        search = A._budget_search

        def spy(ws, objectives, eps, budget, cancel=None):
            if threading.current_thread() is threading.main_thread():
                in_main.append(eps)
            return search(ws, objectives, eps, budget, cancel)

        monkeypatch.setattr(A, "_budget_search", spy)
    second = free_front(ws, OBJ3, epsilon=APPROX_RETRY_EPSILON)
    for bound, a in serial.items():
        n, m = len(started), len(in_main)
        b = run(bound) if threads == 2 else a
        fired = bound > shortfall
        if threads == 2:  # the first search, and the finer one instead of it when the rule fires
            assert len(started) - n == (2 if fired else 1)
            assert not any(s._thread.is_alive() for s in started)
            assert APPROX_RETRY_EPSILON not in in_main
            assert (APPROX_EPSILON in in_main[m:]) == fired
        assert b.approx_shortfall == (None if bound == 0 else pytest.approx(shortfall, abs=1e-12))
        assert b.retry_size == ((len(second), True) if fired else None)
        assert all(_covers(b.F, [0, 1, 2], f) for f in second.F) or not fired
        _check_front(ws, p, b.front(), OBJ3)
        np.testing.assert_array_equal(b.F, a.F)
        assert b.n_eval == a.n_eval
    np.testing.assert_array_equal(serial[0].F, serial[shortfall - 1e-6].F)
    assert serial[shortfall + 1e-6].n_eval == serial[0].n_eval + len(second)
    # another epsilon for the finer search; one not below approx switches the rule off
    other = run(shortfall + 1e-6, approx_retry_epsilon=0.05)
    assert other.retry_size == (len(free_front(ws, OBJ3, epsilon=0.05)), True)
    off = run(shortfall + 1e-6, approx_retry_epsilon=APPROX_EPSILON)
    assert off.retry_size is None and off.approx_shortfall is None
    np.testing.assert_array_equal(off.F, serial[0].F)


def _covered_within(F, keep, eps) -> bool:
    """Whether each row of ``F`` has a row of ``F[keep]`` within ``1 + eps`` in both objectives."""
    C = F[keep]
    return bool(((C[None, :, :] <= (1 + eps) * F[:, None, :] + 1e-12).all(axis=2).any(axis=1)).all())


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.tuples(st.floats(0.0, 5.0), st.floats(0.0, 5.0)), min_size=1, max_size=9),
    st.sampled_from([0.0, 0.01, 0.1, 0.5]),
)
def test_eps_cover_is_a_smallest_cover(steps, eps):
    """eps_cover keeps increasing indices of a subset that covers every point
    of a two-objective front within 1 + eps, and no smaller subset does
    (every subset checked)."""
    from itertools import combinations

    d = np.asarray(steps) + 0.05
    F = np.column_stack([np.cumsum(d[:, 0]), np.cumsum(d[::-1, 1])[::-1] - 0.05])  # a front, costs >= 0
    perm = np.random.default_rng(len(F)).permutation(len(F))
    F = F[perm]
    keep = eps_cover(F, eps)
    assert np.all(np.diff(keep) > 0) and _covered_within(F, keep, eps)
    smaller = (
        _covered_within(F, list(c), eps) for r in range(1, len(keep)) for c in combinations(range(len(F)), r)
    )
    assert not any(smaller)
    if eps == 0.0:
        assert len(keep) == len(F)
