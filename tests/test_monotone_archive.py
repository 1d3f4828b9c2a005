"""The monotone-path archive and its column re-routing (issue 14, the monotone GA)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pymoo.optimize import minimize

from gapath.algorithms import FastNSGA2
from gapath.errors import ConfigError, NoPathError
from gapath.generators import random_workspace
from gapath.metrics import TOL, close, nondominated
from gapath.monotone import Frame, profiles_of_paths
from gapath.objectives import evaluate_paths, pad_paths
from gapath.operators import PlannerSampling
from gapath.operators._monotone_archive_kernels import (
    entries_of,
    pareto_stretches,
    reroute_columns,
    reroute_sweep,
)
from gapath.operators.archive import run_archive
from gapath.operators.monotone_archive import MonotonePathArchive, default_refine
from gapath.planners.exact import monotone_front
from gapath.planners.weighted_sum import weighted_sum_path
from gapath.problems import FreePathProblem, GridPathProblem
from gapath.solver import solve

OBJ = ("length", "vulnerability")


def small_map(seed, corner_cutting=True, shape=(12, 14), k=40):
    ws = random_workspace(shape, k, seed=seed)
    return ws if corner_cutting else ws.replace(corner_cutting=False)


def feasible_map(seed, corner_cutting=True):
    """A small map with a feasible monotone path under its corner rule."""
    for s in range(seed, seed + 50):
        ws = small_map(s, corner_cutting)
        try:
            monotone_front(ws, ("length",))
        except NoPathError:
            continue
        return ws
    raise AssertionError("no feasible map")


def check_front(ws, problem, front):
    """Valid feasible monotone paths whose recomputed objectives are F."""
    frame = Frame.of(ws)
    assert len(front) > 0
    profiles_of_paths(frame, front.paths)  # start to goal, column-monotone, 8-connected
    P, L = pad_paths(front.paths)
    M = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    assert (M[:, 3] == 0).all()  # no interfering cell
    np.testing.assert_allclose(M[:, :2], front.F, rtol=1e-12, atol=1e-12)
    # the genomes decode to the same paths (objectives recomputed through the problem)
    np.testing.assert_allclose(problem.metrics(front.X)[:, :2], front.F, rtol=1e-12, atol=1e-12)
    assert len(nondominated(front.F)) == len(front.F)


def never_dominates(F, exact):
    """No point of F beats an exact point (beyond the tolerance)."""
    for f in F:
        better = (f[None, :] <= exact).all(axis=1) & ~close(f[None, :], exact, TOL).all(axis=1)
        assert not better.any(), f
        # and every GA point is matched or dominated by an exact point
        assert ((exact <= f + TOL * np.maximum(1, np.abs(f))).all(axis=1)).any(), f


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(1, 200),
    corner_cutting=st.booleans(),
    lam=st.floats(1e-3, 1e3),
    data=st.data(),
)
def test_rerouting_keeps_the_ends_and_never_costs_more(seed, corner_cutting, lam, data):
    ws = feasible_map(seed, corner_cutting)
    f = Frame.of(ws)
    problem = GridPathProblem(ws)
    n = f.n_cols
    _, ex = profiles_of_paths(f, [weighted_sum_path(ws, 1.0, 1e-7), weighted_sum_path(ws, 1e-7, 1.0)])
    k0 = np.array([data.draw(st.integers(-1, n - 3)) for _ in range(4)])
    k1 = np.array([data.draw(st.integers(int(a) + 2, n - 1)) for a in k0])
    pick = np.array([0, 1, 0, 1])
    w = np.full(4, lam)
    out = reroute_columns(
        ex,
        pick,
        k0,
        k1,
        np.ones(4),
        w,
        f.occ,
        f.potential,
        f.start[0],
        f.col0,
        ws.cell_size,
        ws.corner_cutting,
    )
    M = problem.metrics(np.empty((4, 0)), profiles=(entries_of(out, f.start[0]), out))
    M0 = problem.metrics(np.empty((4, 0)), profiles=(entries_of(ex[pick], f.start[0]), ex[pick]))
    assert (M[:, 3] == 0).all()
    for b in range(4):
        # outside the stretch nothing changes (the exit rows at its ends included)
        keep = np.r_[0 : max(k0[b], 0) + (k0[b] >= 0), k1[b] : n]
        assert (out[b, keep] == ex[pick[b], keep]).all()
        # the stretch is optimal, so the path costs no more under its weights
        assert M[b, 0] + lam * M[b, 1] <= M0[b, 0] + lam * M0[b, 1] + 1e-9
    profiles_of_paths(
        f, [p for p in problem.decode(problem.encoding.encode_profiles(entries_of(out, f.start[0]), out))]
    )


@pytest.mark.parametrize("corner_cutting", [True, False])
def test_rerouting_the_whole_path_is_the_weighted_sum_optimum(corner_cutting):
    for seed in range(1, 8):
        ws = feasible_map(seed * 7, corner_cutting)
        f = Frame.of(ws)
        problem = GridPathProblem(ws)
        _, ex = profiles_of_paths(f, [weighted_sum_path(ws, 1.0, 0.0)])
        for lam in (0.01, 0.5, 3.0, 40.0):
            _, opt = profiles_of_paths(f, [weighted_sum_path(ws, 1.0, lam)])
            out = reroute_columns(
                ex,
                np.array([0]),
                np.array([-1]),
                np.array([f.n_cols - 1]),
                np.ones(1),
                np.array([lam]),
                f.occ,
                f.potential,
                f.start[0],
                f.col0,
                ws.cell_size,
                ws.corner_cutting,
            )
            both = np.vstack([out, opt])
            M = problem.metrics(np.empty((2, 0)), profiles=(entries_of(both, f.start[0]), both))
            assert M[0, 3] == 0
            assert M[0, 0] + lam * M[0, 1] == pytest.approx(M[1, 0] + lam * M[1, 1], rel=1e-12)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_archive_front_is_valid_and_never_beats_the_exact_front(seed):
    ws = feasible_map(seed * 11)
    problem = GridPathProblem(ws)
    archive = MonotonePathArchive(problem, n_refine=30, seed=seed)
    minimize(problem, FastNSGA2(30, sampling=PlannerSampling()), ("n_gen", 15), seed=seed, callback=archive)
    front = archive.front()
    check_front(ws, problem, front)
    never_dominates(front.F, monotone_front(ws, OBJ).F)
    assert archive.n_eval > 0


def test_solve_with_the_archive_is_valid_deterministic_and_no_worse():
    ws = feasible_map(5)
    exact = monotone_front(ws, OBJ).F
    kw = dict(pop_size=30, n_gen=15, seed=3)
    a = solve(ws, refine=True, **kw)
    b = solve(ws, refine=True, **kw)
    check_front(ws, a.problem, a.front)
    never_dominates(a.front.F, exact)
    assert np.array_equal(a.front.F, b.front.F) and np.array_equal(a.front.X, b.front.X)
    assert all(np.array_equal(p, q) for p, q in zip(a.front.paths, b.front.paths))
    assert a.settings["refine"] == default_refine(30) == 6
    assert a.n_eval == b.n_eval > solve(ws, refine=False, **kw).n_eval
    assert run_archive(a.pymoo_result.algorithm) is not None
    # the population evolves as without the archive: the archive holds its front
    plain = solve(ws, refine=False, **kw)
    assert run_archive(plain.pymoo_result.algorithm) is None
    for f in plain.front.F:
        assert ((a.front.F <= f + 1e-9).all(axis=1)).any()


def test_solve_keeps_ahmed_and_deb_runs_without_an_archive():
    ws = feasible_map(9)
    kw = dict(pop_size=20, n_gen=5, seed=2)
    r = solve(ws, **kw)
    assert "refine" not in r.settings and run_archive(r.pymoo_result.algorithm) is None
    s = solve(ws, refine=False, **kw)
    assert np.array_equal(r.front.F, s.front.F) and np.array_equal(r.front.X, s.front.X)


def test_bad_settings():
    ws = feasible_map(1)
    p = GridPathProblem(ws)
    with pytest.raises(ConfigError, match="n_refine"):
        MonotonePathArchive(p, n_refine=-1)
    with pytest.raises(ConfigError, match="segment"):
        MonotonePathArchive(p, segment=(0.5, 2.0))
    with pytest.raises(ConfigError, match="weight_range"):
        MonotonePathArchive(p, weight_range=(1.0, float("nan")))
    with pytest.raises(ConfigError, match="n_pareto"):
        MonotonePathArchive(p, n_pareto=-2)
    with pytest.raises(ConfigError, match="pareto_cap"):
        MonotonePathArchive(p, pareto_cap=0)
    with pytest.raises(ConfigError, match="pareto_span"):
        MonotonePathArchive(p, pareto_span=(1, 4))
    with pytest.raises(ConfigError, match="GridPathProblem"):
        MonotonePathArchive(FreePathProblem(ws))
    with pytest.raises(ConfigError, match="exit rows"):
        MonotonePathArchive(p).add_exits(np.zeros((1, 3), int))


def test_cli_demo_keeps_ahmed_and_deb_settings_and_solve_monotone_gets_the_archive(tmp_path):
    import json

    from gapath.cli.main import main

    out = tmp_path / "demo"
    assert main(["demo", "--pop", "10", "--gen", "2", "--out", str(out), "--quiet", "--no-plots"]) == 0
    assert "refine" not in json.loads((out / "summary.json").read_text())["settings"]
    out = tmp_path / "solve"
    args = ["solve", "default", "--paths", "monotone", "--pop", "10", "--gen", "2", "--out", str(out)]
    assert main(args + ["--quiet", "--no-plots"]) == 0
    assert json.loads((out / "summary.json").read_text())["settings"]["refine"] == 2


@pytest.mark.parametrize("corner_cutting", [True, False])
def test_one_sweep_gives_every_end_column_of_the_single_reroutes(corner_cutting):
    rng = np.random.default_rng(4)
    for seed in range(1, 6):
        ws = feasible_map(seed * 13, corner_cutting)
        f = Frame.of(ws)
        n = f.n_cols
        _, ex = profiles_of_paths(f, [weighted_sum_path(ws, 1.0, 1e-7), weighted_sum_path(ws, 1e-7, 1.0)])
        B = 5
        pick, k0, lam = rng.integers(0, 2, B), rng.integers(-1, n - 2, B), 10 ** rng.uniform(-2, 2, B)
        lo, hi = np.full(B, 2), np.full(B, n)
        args = (f.occ, f.potential, f.start[0], f.col0, ws.cell_size, ws.corner_cutting)
        out, src = reroute_sweep(ex, pick, k0, lo, hi, np.ones(B), lam, *args)
        expected = 0
        for b in range(B):
            for k1 in range(k0[b] + 2, n):
                one = reroute_columns(
                    ex, pick[b : b + 1], k0[b : b + 1], np.array([k1]), np.ones(1), lam[b : b + 1], *args
                )[0]
                if (one != ex[pick[b]]).any():
                    expected += 1
                    assert (out[src == b] == one).all(axis=1).any()
        assert len(out) == expected
        assert not (out == ex[pick[src]]).all(axis=1).any()  # only paths that changed


def _pareto_of(problem, frame, exits):
    """The distinct non-dominated (length, vulnerability) vectors of the
    feasible paths among ``exits``, rounded."""
    M = problem.metrics(np.empty((len(exits), 0)), profiles=(entries_of(exits, frame.start[0]), exits))
    F = np.unique(np.round(M[M[:, 3] == 0][:, :2], 9), axis=0)
    return F[nondominated(F)] if len(F) else F


@pytest.mark.parametrize("corner_cutting", [True, False])
def test_pareto_stretches_agree_with_brute_force_on_tiny_windows(corner_cutting):
    """Every stretch of up to 2 replaced columns of a 6-row map: the kernel
    gives exactly the Pareto set of all the splices of every exit row."""
    checked = 0
    for seed in range(1, 12):
        ws = random_workspace((6, 7), 8, seed=seed)
        ws = ws if corner_cutting else ws.replace(corner_cutting=False)
        try:
            monotone_front(ws, ("length",))
        except NoPathError:
            continue
        f, problem = Frame.of(ws), GridPathProblem(ws)
        _, ex = profiles_of_paths(f, [weighted_sum_path(ws, 1.0, 1e-7), weighted_sum_path(ws, 1e-7, 1.0)])
        h, n = f.occ.shape[0], f.n_cols
        args = (f.occ, f.potential, f.start[0], f.col0, ws.cell_size, ws.corner_cutting)
        for src in (0, 1):
            for a in range(-1, n - 1):
                for z in range(max(a + 1, 1), min(n, a + 4)):
                    cols = list(range(max(a + 1, 0), z))
                    out, where = pareto_stretches(
                        ex, np.array([src]), np.array([a]), np.array([z]), *args, 100, False
                    )
                    assert (where == 0).all()
                    # outside the stretch nothing changes
                    outside = [k for k in range(n) if k not in cols]
                    assert (out[:, outside] == ex[src, outside]).all()
                    cand = np.repeat(ex[src : src + 1], h ** len(cols), axis=0)
                    if cols:
                        cand[:, cols] = np.array(list(itertools.product(range(h), repeat=len(cols))))
                    expected = _pareto_of(problem, f, cand)
                    got = _pareto_of(problem, f, out)
                    assert len(got) == len(out)  # every path it gives is feasible and non-dominated
                    np.testing.assert_allclose(got, expected, rtol=1e-12)
                    checked += 1
    assert checked > 100


def test_pareto_stretches_skip_unchanged_and_cap():
    ws = feasible_map(3)
    f = Frame.of(ws)
    _, ex = profiles_of_paths(f, [weighted_sum_path(ws, 1.0, 1e-7), weighted_sum_path(ws, 1e-7, 1.0)])
    args = (f.occ, f.potential, f.start[0], f.col0, ws.cell_size, ws.corner_cutting)
    pick, k0, k1 = np.array([0, 1, 0]), np.array([-1, 2, 1]), np.array([f.n_cols - 1, 9, 8])
    full, src_full = pareto_stretches(ex, pick, k0, k1, *args, 64, False)
    new, src_new = pareto_stretches(ex, pick, k0, k1, *args, 64, True)
    assert not (new == ex[pick[src_new]]).all(axis=1).any()
    assert len(full) > len(new) > 0
    capped, src_c = pareto_stretches(ex, pick, k0, k1, *args, 2, False)
    assert np.bincount(src_c, minlength=3).max() <= 2
    # the whole path re-routed (no label set reaches the cap here): the exact monotone front
    problem = GridPathProblem(ws)
    F = _pareto_of(problem, f, full[src_full == 0])
    exact = monotone_front(ws, OBJ).F
    np.testing.assert_allclose(F, exact[np.lexsort(exact.T[::-1])], rtol=1e-9)


@pytest.mark.parametrize("seed", [1, 2])
def test_archive_with_pareto_stretches_is_valid_deterministic_and_leaves_the_population(seed):
    ws = feasible_map(seed * 17)
    problem = GridPathProblem(ws)
    exact = monotone_front(ws, OBJ).F

    def run(n_pareto):
        archive = MonotonePathArchive(problem, n_refine=10, seed=seed, n_pareto=n_pareto, pareto_span=(3, 8))
        res = minimize(
            problem, FastNSGA2(30, sampling=PlannerSampling()), ("n_gen", 10), seed=seed, callback=archive
        )
        return archive, res

    a, ra = run(5)
    b, rb = run(5)
    plain, rp = run(0)
    front = a.front()
    check_front(ws, problem, front)
    never_dominates(front.F, exact)
    assert np.array_equal(front.F, b.front().F) and np.array_equal(front.X, b.front().X)
    assert a.n_eval == b.n_eval and a.n_eval != plain.n_eval
    # the population evolves bit for bit as without the Pareto stretches
    assert np.array_equal(ra.pop.get("X"), rp.pop.get("X"))
    assert np.array_equal(ra.pop.get("F"), rp.pop.get("F"))
