"""The k-objective search's per-state sets (``_multi_kernels``): chains of
kd-trees (logarithmic method) with boxes and dead members. Random insertion
sequences (primaries non-decreasing, as labels leave the open list) against
a plain list kept by the same rules: the same live members, every box
holding its subtree, few trees, and every coverage query answered as a scan
of the whole list answers it."""

from __future__ import annotations

import numpy as np
import pytest

from gapath.planners._exact_kernels import _tolerant_front
from gapath.planners._multi_kernels import (
    B_CNT,
    B_HEAD,
    B_NTREE,
    K_CELL,
    K_LEN,
    K_TURN,
    M_ALIVE,
    M_HEAD,
    M_TURNS,
    N_CLASS,
    N_SI,
    N_ST,
    N_STACK,
    N_T,
    S_TFREE,
    T_LIVE,
    T_M,
    T_NEXT,
    T_OFF,
    _covered,
    _front_filter,
    _gap,
    _insert,
    _width,
)

TOL = 1e-9


def _eq(a, b):
    return abs(a - b) <= TOL * max(1.0, abs(a), abs(b))


def _le(a, b):
    return a <= b or _eq(a, b)


def _ref_covers(a, x, okind, at_goal, to_go, ties, smooth):
    """Does member ``a = (g, turns, head)`` cover ``x``, by the rules of the
    linked-list implementation this structure replaced."""
    ga, ta, ha = a
    gx, tx, hx = x
    gap = 0 if at_goal else int(_gap(ha, hx))
    strict = False
    for j, kind in enumerate(okind):
        if kind == K_TURN:
            if ga[j] + gap > gx[j]:
                return False
            strict |= ga[j] + gap < gx[j]
        else:
            if not _le(ga[j], gx[j]):
                return False
            strict |= not _eq(ga[j], gx[j])
    if strict or smooth or not ties:
        return True
    return ta <= tx + to_go if at_goal else ta + gap <= tx


def _ref_drops(x, a, okind, at_goal):
    gx, tx, hx = x
    ga, ta, ha = a
    gap = 0 if at_goal else int(_gap(hx, ha))
    for j in range(1, len(okind)):
        if okind[j] == K_TURN:
            if tx + gap > ta:
                return False
        elif not _le(gx[j], ga[j]):
            return False
    return True


def _vector(rng, okind, primary, scale, levels):
    g = np.empty(len(okind))
    g[0] = primary
    turns = int(rng.integers(0, 6))
    for j, kind in enumerate(okind[1:], 1):
        if kind == K_TURN:
            g[j] = turns
        else:  # coarse values (many ties) nudged within and beyond the tolerance
            g[j] = scale * rng.integers(0, levels) + rng.choice([0.0, 0.0, 3e-10, -3e-10, 1e-6])
    if len(okind) >= 3 and okind[-1] != K_TURN:  # the last one opposed to the others: large sets
        g[-1] = scale * (levels * (len(okind) - 2) - g[1:-1].sum() / scale + rng.integers(0, 3))
    return g, turns, int(rng.integers(-1, 8))


def _trees(sv, si, sidx, tdir, k):
    """The live members of set 0, tree by tree, checking every box."""
    members = []
    t = sidx[0, B_HEAD] - 1
    n_trees = 0
    while t >= 0:
        n_trees += 1
        off, m = tdir[t, T_OFF], tdir[t, T_M]
        live = 0
        stack = [(0, m)]
        while stack:
            lo, hi = stack.pop()
            if hi <= lo:
                continue
            mid = (lo + hi) // 2
            sub = sv[off + lo : off + hi]
            for j in range(1, k):
                assert sv[off + mid, k + j - 1] == sub[:, j].min()
                assert sv[off + mid, 2 * k - 1 + j - 1] == sub[:, j].max()
            stack += [(lo, mid), (mid + 1, hi)]
        for r in range(off, off + m):
            if si[r, M_ALIVE]:
                live += 1
                members.append((tuple(sv[r, :k]), int(si[r, M_TURNS]), int(si[r, M_HEAD])))
        assert live == tdir[t, T_LIVE] and 2 * live >= m
        t = tdir[t, T_NEXT] - 1
    assert n_trees == sidx[0, B_NTREE]
    return members, n_trees


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
@pytest.mark.parametrize("at_goal", [False, True])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_sets_match_a_plain_list(k, at_goal, seed):
    rng = np.random.default_rng(100 * k + 10 * seed + at_goal)
    okind = np.full(k, K_CELL, np.int64)
    okind[0] = K_LEN
    if k >= 3 and seed == 1:
        okind[2] = K_TURN
    sv = np.zeros((1 << 15, _width(k)))
    si = np.zeros((1 << 15, N_SI), np.int32)
    sidx = np.zeros((2, 3), np.int64)
    sfree = np.full(N_CLASS, -1, np.int64)
    tdir = np.zeros((1 << 12, N_T), np.int64)
    st = np.zeros(N_ST, np.int64)
    st[S_TFREE] = -1
    stk = np.empty(N_STACK, np.int64)
    ref: list = []
    q = np.zeros((1, k))
    primary = 0.0
    largest = 0
    for step in range(300):
        primary += rng.choice([0.0, 1.0])
        x = _vector(rng, okind, primary, 1.0 + seed, 60 if k == 3 else 8)
        q[0] = x[0]
        ties, smooth = bool(rng.integers(2)), bool(rng.integers(2))
        to_go = int(rng.integers(0, 3))
        got, _, _ = _covered(
            sv, si, tdir, sidx[0, B_HEAD], q, 0, okind, x[1], x[2], at_goal, to_go, ties, smooth, stk
        )
        want = any(_ref_covers(a, x, okind, at_goal, to_go, ties, smooth) for a in ref)
        assert got == want, (step, x)
        if want and rng.random() < 0.8:
            continue
        _insert(sv, si, sidx, sfree, tdir, st, 0, q, 0, okind, x[1], x[2], at_goal, stk)
        ref = [a for a in ref if not _ref_drops(x, a, okind, at_goal)] + [x]
        members, n_trees = _trees(sv, si, sidx, tdir, k)
        assert sidx[0, B_CNT] == len(ref) == len(members)
        assert sorted(members) == sorted((tuple(a[0]), a[1], a[2]) for a in ref)
        assert n_trees <= 2 * max(len(ref), 1).bit_length() + 1
        largest = max(largest, len(ref))
    if k >= 3 and okind[-1] != K_TURN:
        assert largest > 40  # trees of several levels were exercised


@pytest.mark.parametrize("seed", range(4))
def test_front_filter_is_the_pairwise_scan(seed):
    """The final front through a kd-tree keeps the rows the scan over all pairs
    keeps, in the same order: coarse values (many exact and tolerance ties,
    nudges within and beyond it, scales from 1e-3 to 1e6), 1 to 5 columns."""
    rng = np.random.default_rng(seed)
    for _ in range(300):
        n, m = int(rng.integers(1, 90)), int(rng.integers(1, 6))
        F = rng.integers(0, rng.integers(1, 6), (n, m)) * rng.choice([1.0, 1e6, 1e-3])
        F = F + rng.choice([0, 0, 3e-10, -3e-10, 1e-6, 4e-3], (n, m)) * (1 + np.abs(F))
        F = np.ascontiguousarray(F)
        order = rng.permutation(n)
        assert np.array_equal(_front_filter(F, order), _tolerant_front(F, order))
