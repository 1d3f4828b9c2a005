"""The backward heuristics of the free exact search
(:mod:`gapath.planners._exact_heuristics`) against plain-Python Dijkstra
searches (heapq, no buckets, no move masks) on small random grids, with
random, tied and all-zero potentials and both corner rules."""

from __future__ import annotations

import heapq
import math

import numpy as np
import pytest

from gapath.grid import can_step
from gapath.planners._exact_heuristics import (
    BIG_TURNS,
    N_SLOTS,
    _free_heuristics,
    _length_to_go,
    _move_masks,
    _turns_to_go,
    _vulnerability_to_go,
)

MOVES = [(0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0), (1, 1)]


def _allowed(occ, r, c, d, cc):
    """Move ``d`` from free cell (r, c), written from the SPEC rule."""
    h, w = occ.shape
    dr, dc = MOVES[d]
    r2, c2 = r + dr, c + dc
    if not (0 <= r2 < h and 0 <= c2 < w) or occ[r2, c2]:
        return False
    if dr and dc and not cc and (occ[r2, c] or occ[r, c2]):
        return False
    return True


def _turn(a, b):
    t = abs(a - b)
    return min(t, 8 - t)


def reference(occ, pot, goal, cc):
    """hs, hd, hv, ht by textbook Dijkstra searches from the goal."""
    h, w = occ.shape
    n = h * w
    g = goal[0] * w + goal[1]
    free = [(r, c) for r in range(h) for c in range(w) if not occ[r, c]]

    def preds(v):  # cells u with an allowed move u -> v, and the move
        r, c = divmod(v, w)
        for d, (dr, dc) in enumerate(MOVES):
            ur, uc = r - dr, c - dc
            if 0 <= ur < h and 0 <= uc < w and not occ[ur, uc] and _allowed(occ, ur, uc, d, cc):
                yield ur * w + uc, d

    # length: the pair (ns, nd) of least ns + sqrt(2) nd
    best = {g: (0.0, 0, 0)}
    heap = [(0.0, 0, 0, g)]
    done = set()
    while heap:
        val, ns, nd, v = heapq.heappop(heap)
        if v in done:
            continue
        done.add(v)
        for u, d in preds(v):
            cand = (ns + (d % 2 == 0), nd + (d % 2))
            cval = cand[0] + math.sqrt(2.0) * cand[1]
            if u not in best or cval < best[u][0]:
                best[u] = (cval, *cand)
                heapq.heappush(heap, (cval, *cand, u))
    hs = np.full(n, -1, np.int64)
    hd = np.full(n, -1, np.int64)
    for v, (_, ns, nd) in best.items():
        hs[v], hd[v] = ns, nd

    # vulnerability: D(goal) = P(goal), D(u) = P(u) + min D(v); hv(u) = min D(v)
    D = {g: float(pot.flat[g])}
    heap = [(D[g], g)]
    done = set()
    while heap:
        val, v = heapq.heappop(heap)
        if v in done:
            continue
        done.add(v)
        for u, _ in preds(v):
            cand = float(pot.flat[u]) + val
            if u != g and (u not in D or cand < D[u]):
                D[u] = cand
                heapq.heappush(heap, (cand, u))
    hv = np.full(n, np.inf)
    for r, c in free:
        u = r * w + c
        if u == g:
            hv[u] = 0.0
            continue
        vals = [
            D[(r + dr) * w + c + dc]
            for d, (dr, dc) in enumerate(MOVES)
            if _allowed(occ, r, c, d, cc) and (r + dr) * w + c + dc in D
        ]
        if vals:
            hv[u] = min(vals)

    # turns over (cell, heading slot): T(u, k) = min_d turn(k, d) + T(u + d, d)
    T = {(g, k): 0 for k in range(N_SLOTS)}
    heap = [(0, g, d) for d in range(8)]
    done = set()
    while heap:
        t, v, d = heapq.heappop(heap)
        if (v, d) in done:
            continue
        done.add((v, d))
        for u, d2 in preds(v):
            if d2 != d:
                continue
            for k in range(N_SLOTS):
                cand = t + (_turn(k, d) if k < 8 else 0)
                if cand < T.get((u, k), BIG_TURNS):
                    T[(u, k)] = cand
                    if k < 8:
                        heapq.heappush(heap, (cand, u, k))
    ht = np.full(n * N_SLOTS, BIG_TURNS, np.int64)
    for (u, k), t in T.items():
        ht[u * N_SLOTS + k] = t
    return hs, hd, hv, ht


def _cases():
    rng = np.random.default_rng(2026)
    out = []
    for i in range(48):
        h, w = (int(x) for x in rng.integers(1, 11, 2))
        occ = rng.random((h, w)) < rng.uniform(0.0, 0.4)
        goal = (int(rng.integers(h)), int(rng.integers(w)))
        occ[goal] = False
        kind = i % 3  # random, tied (many equal sums) and all-zero potentials
        if kind == 0:
            pot = rng.random((h, w))
        elif kind == 1:
            pot = rng.integers(0, 3, (h, w)) * 0.5
        else:
            pot = np.zeros((h, w))
        out.append((occ, np.ascontiguousarray(pot), goal, bool(i % 2)))
    return out


CASES = _cases()


def test_cases_are_non_trivial():
    reached = [(reference(*c)[0] >= 0).sum() for c in CASES]
    assert max(reached) >= 40 and sum(r > 1 for r in reached) >= 30
    assert any(not cc for *_, cc in CASES) and any(cc for *_, cc in CASES)


@pytest.mark.parametrize("i", range(len(CASES)))
def test_heuristics_equal_plain_dijkstra(i):
    occ, pot, (gr, gc), cc = CASES[i]
    mask = _move_masks(occ, cc)
    hs, hd, hv, ht = _free_heuristics(occ, pot, gr, gc, cc, True, mask)
    rs, rd, rv, rt = reference(occ, pot, (gr, gc), cc)
    np.testing.assert_array_equal(hs, rs)
    np.testing.assert_array_equal(hd, rd)
    np.testing.assert_array_equal(hv, rv)  # bit-identical: the same sums in the same order
    np.testing.assert_array_equal(ht, rt)
    # without turns: the same length and vulnerability, a 1-entry placeholder
    hs2, hd2, hv2, ht2 = _free_heuristics(occ, pot, gr, gc, cc, False, mask)
    np.testing.assert_array_equal(hs2, rs)
    np.testing.assert_array_equal(hv2, rv)
    assert ht2.shape == (1,) and ht2[0] == 0


@pytest.mark.parametrize("i", range(0, len(CASES), 4))
def test_move_masks_follow_can_step(i):
    occ, _, _, cc = CASES[i]
    h, w = occ.shape
    mask = _move_masks(occ, cc)
    for r in range(h):
        for c in range(w):
            want = 0
            if not occ[r, c]:
                for d, (dr, dc) in enumerate(MOVES):
                    if can_step(occ, r, c, dr, dc, cc):
                        assert _allowed(occ, r, c, d, cc)
                        want |= 1 << d
            assert mask[r * w + c] == want


def test_passes_on_a_larger_grid():
    """The bucket queue's ring and the deque wrap around many times."""
    rng = np.random.default_rng(5)
    occ = rng.random((40, 50)) < 0.25
    occ[39, 0] = False
    pot = rng.random((40, 50))
    mask = _move_masks(occ, False)
    rs, rd, rv, rt = reference(occ, pot, (39, 0), False)
    n = occ.size
    hs, hd = np.full(n, -1, np.int64), np.full(n, -1, np.int64)
    _length_to_go(mask, 50, 39 * 50, hs, hd)
    hv = np.full(n, np.inf)
    _vulnerability_to_go(mask, pot, 50, 39 * 50, hv)
    ht = np.empty(n * N_SLOTS, np.int64)
    _turns_to_go(mask, 40, 50, 39 * 50, ht)
    assert (rs >= 0).sum() > 1000
    np.testing.assert_array_equal(hs, rs)
    np.testing.assert_array_equal(hd, rd)
    np.testing.assert_array_equal(hv, rv)
    np.testing.assert_array_equal(ht, rt)
