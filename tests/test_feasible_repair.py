"""FeasibleStepRepair (gapath.operators.repair.feasible) and solve's repair=."""

import numpy as np
import pytest

from gapath import Workspace, default_workspace, dense_workspace
from gapath.errors import ConfigError
from gapath.objectives import INTERFERING
from gapath.operators.repair._kernels import exit_rows_allowed, free_runs
from gapath.operators.repair.feasible import REPAIRS, FeasibleStepRepair, make_repair
from gapath.planners.exact import monotone_front
from gapath.problems import GridPathProblem
from gapath.solver import solve

ENCODINGS = ("integer", "mixed", "binary", "absolute")


def _random_genomes(problem, n, rng):
    """Random genomes within the encoding's bounds (small moves for the
    relative integer genes, so that paths wander)."""
    enc = problem.encoding
    if enc.name == "binary":
        return rng.random((n, problem.n_var)) < 0.5
    if enc.name == "integer":
        return rng.integers(-4, 5, (n, problem.n_var))
    return rng.integers(problem.xl, problem.xu + 1, (n, problem.n_var))


def _maps():
    yield default_workspace()
    yield dense_workspace(32, 0.6, seed=3)
    yield dense_workspace(16, 0.8, seed=2)
    occ = np.random.default_rng(5).random((12, 20)) < 0.3
    occ[11, 0] = occ[0, 19] = False
    yield Workspace(occ, (11, 0), (0, 19), corner_cutting=False)  # may have no feasible path


def _has_monotone_path(ws):
    try:
        monotone_front(ws, ("length",))
    except Exception:
        return False
    return True


def _step_cells_free(frame, entries, exits):
    """Per row, per column: the column's run of cells is free."""
    n, n_cols = exits.shape
    ok = np.ones((n, n_cols), bool)
    for i in range(n):
        for k in range(n_cols):
            a, b = sorted((entries[i, k], exits[i, k]))
            ok[i, k] = not frame.occ[a : b + 1, frame.col0 + k].any()
    return ok


@pytest.mark.parametrize("encoding", ENCODINGS)
@pytest.mark.parametrize("mode", ["local", "reach"])
def test_repaired_genomes_are_valid_and_decode_to_the_repaired_paths(encoding, mode):
    rng = np.random.default_rng(11)
    for ws in _maps():
        p = GridPathProblem(ws, encoding=encoding)
        X = _random_genomes(p, 300, rng)
        Y = FeasibleStepRepair(mode)._do(p, X, random_state=np.random.default_rng(3))
        assert Y.shape == X.shape
        assert (Y >= p.xl).all() and (Y <= p.xu).all()
        # Lamarckian: the genes say what is evaluated, and re-encoding them is stable
        entries, exits = p.encoding.decode(Y)
        assert np.array_equal(p.encoding.decode(p.encoding.edge_fix(Y, np.random.default_rng(0)))[1], exits)
        # valid 8-connected monotone paths from start to goal
        f = p.frame
        assert (exits[:, -1] == f.goal[0]).all() and (entries[:, 0] == f.start[0]).all()
        assert (np.abs(entries[:, 1:] - exits[:, :-1]) <= 1).all()


@pytest.mark.parametrize("encoding", ENCODINGS)
def test_reach_makes_every_path_feasible_on_a_map_with_a_feasible_monotone_path(encoding):
    rng = np.random.default_rng(12)
    checked = 0
    for ws in _maps():
        if not _has_monotone_path(ws):
            continue
        p = GridPathProblem(ws, encoding=encoding)
        X = _random_genomes(p, 300, rng)
        Y = FeasibleStepRepair("reach")._do(p, X, random_state=np.random.default_rng(4))
        assert (p.metrics(Y)[:, INTERFERING] == 0).all()
        checked += 1
    assert checked >= 3


@pytest.mark.parametrize("encoding", ENCODINGS)
def test_local_frees_every_column_that_has_a_free_exit_and_never_adds_interference(encoding):
    rng = np.random.default_rng(13)
    for ws in _maps():
        p = GridPathProblem(ws, encoding=encoding)
        f = p.frame
        X = _random_genomes(p, 300, rng)
        before = p.metrics(p.encoding.edge_fix(X, np.random.default_rng(5)))[:, INTERFERING]
        R = FeasibleStepRepair("local")
        Y = R._do(p, X, random_state=np.random.default_rng(5))  # the same edge-fixing draws first
        after = p.metrics(Y)[:, INTERFERING]
        entries, exits = p.encoding.decode(Y)
        ok = _step_cells_free(f, entries, exits)
        top, bot = free_runs(f.occ)
        # a column (before the goal column) still on an obstacle is a dead end:
        # from the previous exit row no exit row of that column is free
        for i, k in zip(*np.nonzero(~ok[:, :-1])):
            r = f.start[0] if k == 0 else exits[i, k - 1]
            c = f.col0 + k
            assert k > 0, "the start column always has a free exit row: the start row"
            for q in range(f.height):
                e = r + np.sign(q - r)
                lo, hi = sorted((e, q))
                free = not f.occ[lo : hi + 1, c].any()
                if free and not ws.corner_cutting and e != r:
                    free = not (f.occ[e, c - 1] or f.occ[r, c])
                assert not free, (ws.name, i, k, q)
        # the goal column (the end-fix) still on an obstacle: no exit row of the
        # column before it, reachable by a free step, has a free end-fix
        last = f.n_cols - 1
        for i in np.flatnonzero(~ok[:, last] & ok[:, last - 1]):
            r = f.start[0] if last == 1 else exits[i, last - 2]
            for q in range(f.height):
                e = f.start[0] if last == 1 else r + np.sign(q - r)
                lo, hi = sorted((e, q))
                if f.occ[lo : hi + 1, f.col0 + last - 1].any():
                    continue
                if (
                    last > 1
                    and not ws.corner_cutting
                    and e != r
                    and (f.occ[e, f.col0 + last - 2] or f.occ[r, f.col0 + last - 1])
                ):
                    continue
                g = q + np.sign(f.goal[0] - q)
                lo, hi = sorted((g, f.goal[0]))
                end_free = not f.occ[lo : hi + 1, f.col0 + last].any()
                if end_free and not ws.corner_cutting and g != q:
                    end_free = not (f.occ[g, f.col0 + last - 1] or f.occ[q, f.col0 + last])
                assert not end_free, (ws.name, i, q)
        # rows that were feasible stay so
        assert (after[before == 0] == 0).all()
        # and on the maps with a feasible path most rows end feasible
        if _has_monotone_path(ws) and ws.n_obstacles < 0.3 * ws.occ.size:
            assert np.mean(after == 0) > np.mean(before == 0)


def test_share_repairs_only_a_share_and_leaves_the_others_edge_fixed():
    ws = default_workspace()
    p = GridPathProblem(ws)
    X = _random_genomes(p, 400, np.random.default_rng(14))
    edge = p.encoding.edge_fix(X, np.random.default_rng(6))
    Y = FeasibleStepRepair("reach", share=0.5)._do(p, X, random_state=np.random.default_rng(6))
    same = (Y == edge).all(axis=1)
    feasible = p.metrics(Y)[:, INTERFERING] == 0
    assert feasible.all() or (~feasible <= same).all()  # every infeasible row kept its genes
    assert 0.3 < np.mean(~same) < 0.7  # about half changed (all random rows are infeasible)
    assert np.array_equal(FeasibleStepRepair("reach", share=0.0)._do(p, X, np.random.default_rng(6)), edge)


def test_feasible_rows_are_kept_bit_for_bit():
    ws = default_workspace()
    p = GridPathProblem(ws)
    exact = monotone_front(ws, ("length", "vulnerability"))
    X = p.encoding.encode(exact.paths)
    for mode in ("local", "reach"):
        assert np.array_equal(FeasibleStepRepair(mode)._do(p, X, random_state=np.random.default_rng(1)), X)


def test_reach_table_is_the_set_of_rows_that_still_reach_the_goal():
    ws = dense_workspace(16, 0.6, seed=4)
    p = GridPathProblem(ws)
    f = p.frame
    table = exit_rows_allowed(f.occ, f.col0, f.n_cols, f.start[0], f.goal[0], True, True)
    # a row is allowed exactly when the exact planner finds a path through it
    # (checked from the start column: allowed exit rows that the start reaches)
    sr = f.start[0]
    reachable = [
        t for t in range(f.height) if table[0, t] and not f.occ[min(t, sr) : max(t, sr) + 1, f.col0].any()
    ]
    assert bool(reachable) == _has_monotone_path(ws)
    # the goal column's entry: only rows whose end-fix is free are allowed before it
    for t in np.flatnonzero(table[-2]):
        e = t + np.sign(f.goal[0] - t)
        lo, hi = sorted((e, f.goal[0]))
        assert not f.occ[lo : hi + 1, f.col0 + f.n_cols - 1].any()


def test_bad_settings_raise():
    with pytest.raises(ConfigError, match="mode"):
        FeasibleStepRepair("nearest")
    with pytest.raises(ConfigError, match="share"):
        FeasibleStepRepair(share=1.5)
    with pytest.raises(ConfigError, match="unknown repair"):
        make_repair("feasible")
    with pytest.raises(ConfigError, match="engine='fast'"):
        solve(default_workspace(), pop_size=10, n_gen=1, repair="feasible-local", engine="pymoo")
    assert set(REPAIRS) >= {"edge", "feasible-local", "feasible-reach"}


def test_solve_with_the_repair_is_seeded_and_keeps_the_default_unchanged():
    ws = dense_workspace(32, 0.6, seed=1)
    a = solve(ws, pop_size=30, n_gen=5, seed=2, seed_from="none", repair="feasible-local")
    b = solve(ws, pop_size=30, n_gen=5, seed=2, seed_from="none", repair="feasible-local")
    assert np.array_equal(a.front.F, b.front.F) and a.settings["repair"] == "feasible-local"
    c = solve(ws, pop_size=30, n_gen=5, seed=2, seed_from="none")
    d = solve(ws, pop_size=30, n_gen=5, seed=2, seed_from="none", repair="edge")
    assert np.array_equal(c.front.F, d.front.F) and "repair" not in c.settings
    r = solve(ws, pop_size=30, n_gen=2, seed=2, seed_from="none", repair="feasible-reach")
    assert len(r.front) > 0  # every repaired path is feasible here


def test_cli_solve_takes_the_repair_and_records_it(tmp_path, capsys):
    from gapath.cli.main import main

    occ = dense_workspace(16, 0.6, seed=2).occ
    path = tmp_path / "dense.txt"
    path.write_text("\n".join("".join("#" if c else "." for c in row) for row in occ) + "\n")
    out = tmp_path / "o"
    args = [
        "solve",
        str(path),
        "--paths",
        "monotone",
        "--start",
        "15,0",
        "--goal",
        "0,15",
        "--seed-from",
        "none",
    ]
    args += ["--pop", "20", "--gen", "3", "--quiet", "--no-plots", "--out", str(out)]
    assert main(args + ["--repair", "feasible-reach"]) == 0
    assert "feasible-reach" in (out / "summary.json").read_text()
    assert main(args + ["--repair", "nearest"]) == 2
    assert "unknown repair 'nearest'" in capsys.readouterr().err
