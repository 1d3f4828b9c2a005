"""The three-objective free search's dominance structures (issue 15 item 2).

MODE_THREE keeps, besides each state's (turns, vulnerability) staircase (a
sorted block in a pool of floats), per-cell summaries of the staircases and the goal
front as a prefix minimum over turn counts, both in ``gmin``; the checks
read the summaries first. These tests run the search kernels to the end and
recompute every summary from the staircases and the solutions. The fronts themselves are checked against brute force and an
independent label-setting search in ``test_exact_free.py``; the kernel was
compared with the implementation before the summaries on 584 random cases
(identical ``F``, smoothness and expansions; docs/results/exact_speed.md).
"""

from __future__ import annotations

import numpy as np
import pytest

from gapath import Workspace, random_workspace
from gapath.planners import _exact_heuristics as H
from gapath.planners import _exact_kernels as K
from gapath.planners.exact import _search_plan, free_front

LVS = ("length", "vulnerability", "smoothness")


def _run(ws: Workspace, n_steps: int = 1 << 30):
    """The MODE_THREE search arrays after the search (as free_front runs it)."""
    occ = np.ascontiguousarray(ws.occ)
    pot = np.ascontiguousarray(ws.potential, dtype=np.float64)
    (sr, sc), (gr, gc) = ws.start, ws.goal
    h, w = ws.shape
    mode, P, Q = _search_plan(LVS)
    assert mode == K.MODE_THREE
    mask = H._move_masks(occ, ws.corner_cutting)
    hs, hd, hv, ht = H._free_heuristics(occ, pot, gr, gc, ws.corner_cutting, True, mask)
    state = K._free_init(pot, sr, sc, w, 1.0, mode, P, Q, hs, hd, hv, ht, h * w * K.N_SLOTS)
    gmin, first, li, lf, sols, hk, hid, st, stf = state
    sp = K._stair_pool(16)  # small: the pool grows while the search runs
    pc = np.empty((4, 2), np.int32)  # the parent table and the free rows' stack too
    fs = np.empty(4, np.int32)
    while True:
        li, lf, sols, hk, hid, sp, pc, fs, status = K._free_run(
            occ, pot, gr, gc, 1.0, mask, mode, P, Q, hs, hd, hv, ht, gmin, first,
            li, lf, sols, hk, hid, st, stf, sp, pc, fs, n_steps, 1 << 30,
        )  # fmt: skip
        if status == K.DONE:
            return gmin, first, sp, li, lf, sols[: st[K.S_SOLS]]


def _maps():
    out = []
    for seed in range(6):
        out.append(random_workspace((14, 14), 30, seed=seed))
    rng = np.random.default_rng(7)
    for _ in range(4):  # flat potential far from obstacles: many exact ties
        occ = rng.random((18, 18)) < 0.08
        occ[17, 0] = occ[0, 17] = False
        out.append(Workspace(occ, corner_cutting=bool(rng.integers(2))))
    return out


@pytest.mark.parametrize("ws", _maps(), ids=lambda ws: ws.name)
@pytest.mark.parametrize("n_steps", [1 << 30, 5])
def test_summaries_match_the_staircases(ws, n_steps):
    gmin, first, sp, li, lf, sols = _run(ws, n_steps)
    h, w = ws.shape
    n_cells = h * w
    assert gmin.shape[0] >= (K.THREE_BLOCK + 4) * n_cells + 1
    n_checked = n_cells_used = 0
    for c in range(n_cells):
        base = c * K.THREE_BLOCK
        heads = []
        for k in range(K.N_SLOTS):
            b = base + 1 + 3 * k
            o = first[c * K.N_SLOTS + k]
            if o < 0:
                assert gmin[b] == np.inf
                continue
            n, cap = int(sp[o]), int(sp[o + 1])
            assert 1 <= n <= cap and o + 2 + 2 * cap <= sp[K.SP_USED] <= sp.shape[0]
            assert cap <= sp[K.SP_MAXCAP]
            turns, vul = sp[o + 2 : o + 2 + n], sp[o + 2 + cap : o + 2 + cap + n]
            # a staircase: turns strictly decreasing, vulnerability strictly increasing
            assert all(np.diff(turns) < 0) and all(np.diff(vul) > 0)
            assert (gmin[b], gmin[b + 1], gmin[b + 2]) == (vul[0], turns[0], turns[-1])
            heads.append(vul[0])
            n_checked += 1
        assert gmin[base] == (min(heads) if heads else np.inf)
        n_cells_used += bool(heads)
    assert n_checked > n_cells_used  # several headings at some cells

    # the goal front: prefix minimum of the solutions' vulnerabilities over turns
    goal_base = K.THREE_BLOCK * n_cells
    t_sol, v_sol = li[sols, K.TURNS], lf[sols, K.F_VUL]
    tmax = first[first.shape[0] - 1]
    assert tmax == t_sol.max()
    for u in range(tmax + 1):
        within = v_sol[t_sol <= u]
        assert gmin[goal_base + u] == (within.min() if len(within) else np.inf)


@pytest.mark.parametrize("ws", _maps()[:3] + _maps()[-2:], ids=lambda ws: ws.name)
def test_front_does_not_depend_on_slicing(ws):
    """The summaries live across kernel calls: a search resumed every 3 pops
    gives the front of one call."""
    one = free_front(ws, LVS)
    _, _, _, li, lf, sols = _run(ws, 3)
    F = np.column_stack(
        [(li[sols, K.NS] + np.sqrt(2) * li[sols, K.ND]), lf[sols, K.F_VUL], li[sols, K.TURNS] * np.pi / 4]
    )
    # every front point is among the sliced search's solutions
    for f in one.F:
        assert np.isclose(F, f, rtol=1e-9, atol=1e-9).all(axis=1).any()


@pytest.mark.parametrize("ws", _maps()[:4] + _maps()[-2:], ids=lambda ws: ws.name)
@pytest.mark.parametrize("eps", [0.02, 0.3])
def test_approximate_front_is_valid_and_never_beats_exact(ws, eps):
    """``epsilon > 0``: every path is feasible and simple, ``F`` is its own
    objectives, the front is mutually non-dominated and no point of it
    dominates a point of the exact front; ``epsilon=0`` is the exact search."""
    from test_free_paths import TOL, check_path, dominates

    from gapath.metrics import nondominated
    from gapath.objectives import evaluate_path

    exact = free_front(ws, LVS)
    np.testing.assert_array_equal(free_front(ws, LVS, epsilon=0.0).F, exact.F)
    approx = free_front(ws, LVS, epsilon=eps)
    assert len(approx) > 0
    for path, f in zip(approx.paths, approx.F):
        check_path(ws, path)
        assert len({tuple(c) for c in path.tolist()}) == len(path)  # simple
        m = evaluate_path(ws, path)
        np.testing.assert_array_equal(f, [m[name] for name in LVS])
    assert len(nondominated(approx.F, tol=TOL)) == len(approx)
    for f in approx.F:
        assert not any(dominates(f, r) for r in exact.F)


@pytest.mark.parametrize("ws", _maps() + [random_workspace((40, 40), 320, seed=3)], ids=lambda ws: ws.name)
@pytest.mark.parametrize("eps", [0.01, 0.1, 0.5])
def test_approximate_front_covers_exact_within_epsilon(ws, eps):
    """The apex search's guarantee: every point of the exact front is
    covered by a returned point with at most ``1 + eps`` times its length and
    its vulnerability and no more turns (tolerance 1e-9)."""
    exact = free_front(ws, LVS)
    approx = free_front(ws, LVS, epsilon=eps)
    A, E = approx.F[None, :, :], exact.F[:, None, :]
    slack = (1 + eps) * (1 + 1e-9)
    covers = (A[..., 0] <= E[..., 0] * slack + 1e-9) & (A[..., 1] <= E[..., 1] * slack + 1e-9)
    covers &= A[..., 2] <= E[..., 2] + 1e-9
    assert covers.any(axis=1).all()


def test_approximate_search_prunes_more_on_a_larger_map():
    """On a 40x40 random map epsilon = 0.05 expands fewer labels than the
    exact search and keeps fewer points (the point of it)."""
    ws = random_workspace((40, 40), 320, seed=3)
    exact = free_front(ws, LVS)
    approx = free_front(ws, LVS, epsilon=0.05)
    assert approx.stats["expansions"] < exact.stats["expansions"]
    assert len(approx) < len(exact)


@pytest.mark.parametrize("bad", [-0.1, float("nan"), float("inf"), "x", None])
def test_bad_epsilon(bad):
    from gapath.errors import ConfigError

    ws = random_workspace((8, 8), 6, seed=1)
    with pytest.raises(ConfigError, match="epsilon must be a finite number >= 0"):
        free_front(ws, LVS, epsilon=bad)


@pytest.mark.parametrize("objectives", [("length", "vulnerability"), ("length", "smoothness"), ("length",)])
def test_epsilon_needs_the_three_objectives(objectives):
    from gapath.errors import ConfigError

    ws = random_workspace((8, 8), 6, seed=1)
    with pytest.raises(ConfigError, match="needs the objectives length, vulnerability and smoothness"):
        free_front(ws, objectives, epsilon=0.1)
    assert len(free_front(ws, objectives, epsilon=0)) > 0
