"""The k-objective search's per-state sets (``_multi_kernels``): contiguous
blocks sorted by the first non-primary objective, with prefix and chunk
minima. Random insertion sequences (primaries non-decreasing, as labels
leave the open list) against a plain list kept by the same rules: the same
members, sorted blocks, minima equal to their recomputation, and every
coverage query answered as a scan of the whole list answers it."""

from __future__ import annotations

import numpy as np
import pytest

from gapath.planners._multi_kernels import (
    B_CNT,
    B_OFF,
    CHUNK,
    K_CELL,
    K_LEN,
    K_TURN,
    N_CLASS,
    N_ST,
    _covered,
    _gap,
    _insert,
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


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
@pytest.mark.parametrize("at_goal", [False, True])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_sets_match_a_plain_list(k, at_goal, seed):
    rng = np.random.default_rng(100 * k + 10 * seed + at_goal)
    okind = np.full(k, K_CELL, np.int64)
    okind[0] = K_LEN
    if k >= 3 and seed == 1:
        okind[2] = K_TURN
    sv = np.zeros((1 << 14, k + 2 * max(k - 2, 0)))
    si = np.zeros((1 << 14, 2), np.int32)
    sidx = np.zeros((2, 3), np.int64)
    sfree = np.full(N_CLASS, -1, np.int64)
    st = np.zeros(N_ST, np.int64)
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
        off, cnt = sidx[0, B_OFF], sidx[0, B_CNT]
        got, _ = _covered(sv, si, off, cnt, q, 0, okind, x[1], x[2], at_goal, to_go, ties, smooth)
        want = any(_ref_covers(a, x, okind, at_goal, to_go, ties, smooth) for a in ref)
        assert got == want, (step, x)
        if want and rng.random() < 0.8:
            continue
        _insert(sv, si, sidx, sfree, st, 0, q, 0, okind, x[1], x[2], at_goal)
        ref = [a for a in ref if not _ref_drops(x, a, okind, at_goal)] + [x]
        off, cnt = sidx[0, B_OFF], sidx[0, B_CNT]
        largest = max(largest, cnt)
        rows = sv[off : off + cnt]
        assert cnt == len(ref)
        got_members = sorted((tuple(r[:k]), int(t), int(h)) for r, (t, h) in zip(rows, si[off : off + cnt]))
        assert got_members == sorted((tuple(a[0]), a[1], a[2]) for a in ref)
        if k >= 2:
            assert np.all(np.diff(rows[:, 1]) >= 0)
        for j in range(2, k):
            assert np.array_equal(rows[:, k + j - 2], np.minimum.accumulate(rows[:, j]))
            for c0 in range(0, cnt, CHUNK):
                assert rows[c0, 2 * k - 2 + j - 2] == rows[c0 : c0 + CHUNK, j].min()
    if k >= 3 and okind[-1] != K_TURN:
        assert largest > 2 * CHUNK  # the chunks were exercised
