"""The two-objective BOA* kernels against their previous version
(``tests/_boa_reference.py``, kept verbatim): :func:`free_front` on
(length, vulnerability) must give bit-identical ``F`` and smoothness, the
same expansions and tie edges, and paths with exactly the reference paths'
objectives, on hundreds of random small grids built to have many exact and
near ties, and on real MovingAI queries with thousands of tie edges.

Since the fourteenth session the smoothest tie-break drops, when a bucket of
the open list is poured, the waiting labels its pop would drop without an
edge; their rows are reused earlier, and the row breaks exact ties of the
open list's keys, so among paths with exactly equal (length, vulnerability,
smoothness) another one may be returned (docs/CONVENTIONS.md). With
``tie_break="none"`` nothing is dropped early: the paths are the same too."""

from __future__ import annotations

import _boa_reference as ref
import numpy as np
import pytest
from data_files import data_path

from gapath import Workspace
from gapath.errors import NoPathError
from gapath.loaders import load_movingai, load_scenarios
from gapath.objectives import evaluate_path
from gapath.planners.exact import free_front

LV = ("length", "vulnerability")


def _case(i: int) -> Workspace:
    """4x4 to 24x24 grids with 0-30 % obstacles, either corner rule, random
    start and goal; one in three gets a potential of a few dyadic values,
    half of them 0 (exact ties everywhere), one in three is a sparse 14x14 to
    29x29 map with its true potential (exact zeros, near-ties)."""
    rng = np.random.default_rng(5000 + i)
    kind = i % 3
    h, w = int(rng.integers(4, 25)), int(rng.integers(4, 25))
    if kind == 2:
        h, w = int(rng.integers(14, 30)), int(rng.integers(14, 30))
        p = rng.uniform(0.0, 0.04)
    else:
        p = rng.uniform(0.0, 0.3)
    occ = rng.random((h, w)) < p
    free = np.argwhere(~occ)
    if len(free) < 2:
        occ[:] = False
        free = np.argwhere(~occ)
    a, b = rng.choice(len(free), 2, replace=False)
    ws = Workspace(
        occ,
        start=tuple(int(x) for x in free[a]),
        goal=tuple(int(x) for x in free[b]),
        corner_cutting=bool(rng.integers(2)),
    )
    if kind == 1:
        pot = rng.choice([0.0, 0.0, 0.0, 0.25, 0.5, 1.0], size=(h, w))
        pot.setflags(write=False)
        ws.__dict__["potential"] = pot  # the cached property, replaced
    return ws


def reference_front(ws: Workspace, names, ties: bool):
    """``(F, smoothness, paths, expansions, tie edges, generated labels)`` of
    the reference kernels, or None when the goal cannot be reached."""
    occ = np.ascontiguousarray(ws.occ)
    pot = np.ascontiguousarray(ws.potential, dtype=np.float64)
    (sr, sc), (gr, gc) = ws.start, ws.goal
    w = ws.shape[1]
    mask, hs, hd, hv = ref._boa_prepare(occ, pot, gr, gc, bool(ws.corner_cutting))
    if hv[sr * w + sc] == np.inf:
        return None
    status, result, _ = ref._boa_solve(
        occ, pot, sr, sc, gr, gc, float(ws.cell_size), mask, hs, hd, hv, ties, names[0] == "length",
        1 << 60, 1 << 60,
    )  # fmt: skip
    assert status == ref.DONE
    F, smooth, cells, offsets, counts = result
    paths = [cells[offsets[i] : offsets[i + 1]] for i in range(len(F))]
    return (
        F,
        smooth,
        paths,
        int(counts[ref.C_EXPANDED]),
        int(counts[ref.C_EDGES]),
        int(counts[ref.C_GENERATED]),
    )


def _assert_same(ws, names, tie_break):
    want = reference_front(ws, names, tie_break == "smoothest")
    try:
        got = free_front(ws, names, tie_break=tie_break)
    except NoPathError:
        assert want is None
        return 0
    assert want is not None
    F, smooth, paths, expansions, edges, generated = want
    assert np.array_equal(got.F, F)
    assert np.array_equal(got.smoothness, smooth)
    assert len(got.paths) == len(paths)
    for p, q in zip(got.paths, paths):
        if tie_break == "none":
            assert np.array_equal(p, q)
        else:  # the same objectives, bit for bit (F is summed along the path)
            assert tuple(p[0]) == ws.start and tuple(p[-1]) == ws.goal
            assert len(p) == len(q)
            assert evaluate_path(ws, p) == evaluate_path(ws, q)
    assert got.stats["expansions"] == expansions
    assert got.stats["generated"] == generated  # (the steps back are counted, not generated)
    if tie_break == "smoothest":  # labels dropped early are ones that record no edge
        assert got.stats["tie_edges"] == edges
    return len(F)


@pytest.mark.parametrize("block", range(4))
@pytest.mark.parametrize("tie_break", ["smoothest", "none"])
def test_equals_the_previous_kernels_on_random_grids(block, tie_break):
    points = 0
    for i in range(block * 100, block * 100 + 100):
        names = LV if i % 2 == 0 else LV[::-1]
        points += _assert_same(_case(i), names, tie_break)
    assert points > 100  # the cases are not trivial


@pytest.mark.parametrize(
    "name, lines",
    [("maze-32-32-2", (0, 166)), ("den312d", (0, 749, 999))],
)
def test_equals_the_previous_kernels_on_movingai_queries(name, lines):
    mp = data_path(f"movingai/mapf/{name}.map")
    scen = load_scenarios(data_path(f"movingai/mapf/{name}-random-1.scen"))
    for i in lines:
        ws = load_movingai(mp, scen[i].start, scen[i].goal, corner_cutting=False)
        for tie_break in ("smoothest", "none"):
            assert _assert_same(ws, LV, tie_break) > 0


@pytest.mark.parametrize("line", [500, 0])
def test_equals_the_previous_kernels_on_a_berlin_query(line):
    """Berlin_1_256 (optional data): tens of thousands of tie edges. On
    query 0 a label tied with g2_min from below when its bucket is poured
    records an edge later (dropping it at the pour, which _pour_drops_tied
    does not do, loses one of its 38,495 edges)."""
    mp = data_path("movingai/mapf/Berlin_1_256.map")
    scen = load_scenarios(data_path("movingai/mapf/Berlin_1_256-random-1.scen"))
    ws = load_movingai(mp, scen[line].start, scen[line].goal, corner_cutting=False)
    for tie_break in ("smoothest", "none"):
        assert _assert_same(ws, LV, tie_break) > 0


@pytest.mark.parametrize("n_buckets", [1, 2, 8])
def test_small_bucket_windows_give_the_same_fronts(n_buckets):
    """The open list's later labels wait in a window of buckets and an
    overflow list beyond it; the default window (8 cells of f_length) is
    never passed on a grid (a step adds at most 2 sqrt(2) cells), so tiny
    windows exercise the overflow here, run in slices of 7 pops (resumed
    state)."""
    from gapath.planners import _boa_kernels as K

    n_over = 0
    for i in range(60):
        ws = _case(i)
        occ = np.ascontiguousarray(ws.occ)
        pot = np.ascontiguousarray(ws.potential, dtype=np.float64)
        (sr, sc), (gr, gc) = ws.start, ws.goal
        w = ws.shape[1]
        cs = float(ws.cell_size)
        mask, hs, hd, hv = K._boa_prepare(occ, pot, gr, gc, bool(ws.corner_cutting))
        if hv[sr * w + sc] == np.inf:
            continue
        for ties in (True, False):
            want = reference_front(ws, LV, ties)
            gmin, first, li, lf, sols, hk, hid, st, stf, edges, est = K._boa_start(
                pot, sr, sc, w, cs, hs, hd, hv, ties, n_buckets
            )
            status = K.PAUSED
            while status != K.DONE:
                li, lf, sols, hk, hid, edges, status = K._boa_run(
                    occ, pot, gr, gc, cs, mask, hs, hd, hv, gmin, first, li, lf, sols, hk, hid, st, stf,
                    edges, est, 7, 1 << 60, ties,
                )  # fmt: skip
                n_over = max(n_over, int(est[K.E_NOVER]))
            F, smooth, cells, offsets, counts = K._boa_finish(
                li, lf, sols, st, edges, est[K.E_EDGES], pot, w, cs, ties, True, 0
            )
            assert np.array_equal(F, want[0])
            assert np.array_equal(smooth, want[1])
            if not ties:  # (with ties an exactly equal path may be returned instead)
                assert np.array_equal(cells, np.concatenate(want[2]))
            assert int(counts[K.C_EXPANDED]) == want[3]
            assert int(counts[K.C_EDGES]) == want[4]
    assert n_over > 0  # the overflow list was used


def _pops(K, ws, ties):
    """Pops of the open list of module ``K``'s kernels on ``ws`` (whole search)."""
    occ = np.ascontiguousarray(ws.occ)
    pot = np.ascontiguousarray(ws.potential, dtype=np.float64)
    (sr, sc), (gr, gc) = ws.start, ws.goal
    mask, hs, hd, hv = K._boa_prepare(occ, pot, gr, gc, bool(ws.corner_cutting))
    state = K._boa_solve(occ, pot, sr, sc, gr, gc, 1.0, mask, hs, hd, hv, ties, True, 1, 1 << 60)[2]
    gmin, first, li, lf, sols, hk, hid, st, stf, edges, est = state
    status = K.PAUSED
    while status != K.DONE:
        li, lf, sols, hk, hid, edges, status = K._boa_run(
            occ, pot, gr, gc, 1.0, mask, hs, hd, hv, gmin, first, li, lf, sols, hk, hid, st, stf,
            edges, est, 1 << 40, 1 << 60, ties,
        )  # fmt: skip
    return int(st[ref.S_POPS])


@pytest.mark.parametrize("name, line", [("den312d", 749), ("random-64-64-10", 999)])
def test_labels_dropped_at_the_pour_are_many_and_record_no_edge(name, line):
    """The smoothest tie-break drops, when their bucket is poured, the labels
    their cell's g2_min already covers beyond the tolerance: fewer pops than
    the reference, the same expansions and tie edges (a dropped label that
    would have tied an expanded one, or the goal's last solution, is a lost
    edge: the mutation that drops tied labels too fails here and on the
    random grids above). Without ties nothing is dropped early."""
    from gapath.planners import _boa_kernels as K

    mp = data_path(f"movingai/mapf/{name}.map")
    sc = load_scenarios(data_path(f"movingai/mapf/{name}-random-1.scen"))[line]
    ws = load_movingai(mp, sc.start, sc.goal, corner_cutting=False)
    assert _pops(K, ws, True) < 0.9 * _pops(ref, ws, True)
    assert _pops(K, ws, False) == _pops(ref, ws, False)
    got = free_front(ws, LV)
    want = reference_front(ws, LV, True)
    assert got.stats["tie_edges"] == want[4] > 0
    assert got.stats["expansions"] == want[3]
    assert np.array_equal(got.F, want[0])
    assert np.array_equal(got.smoothness, want[1])


def test_pour_drops_only_labels_its_pop_drops_without_an_edge():
    """The rules themselves: a label covered by g2_min beyond the tolerance
    is dropped; one tied with g2_min from above (q >= g2_min) only when its
    length does not tie the label last expanded at its cell; one tied from
    below, or below g2_min, is kept unless the last solution covers it by more
    than three tolerances (and it is clear of g2_min); at the goal the last
    solution's vulnerability decides alone."""
    from gapath.planners._boa_kernels import GOAL_MARGIN, _pour_drops, _pour_drops_tied

    inf = np.inf
    assert _pour_drops(2.0, 1.0, 5.0, inf, False)
    assert not _pour_drops(1.0 + 5e-10, 1.0, 5.0, inf, False)  # tied: may record an edge
    assert not _pour_drops(1.0 - 5e-10, 1.0, 5.0, inf, False)
    assert not _pour_drops(0.5, 1.0, 5.0, inf, False)
    assert not _pour_drops(0.5, inf, 5.0, inf, False)
    # covered by the last solution only: beyond the margin dropped, within it kept
    assert _pour_drops(0.5, inf, 5.0, 1.0, False)
    assert _pour_drops(0.5, 1.0, 5.0, 1.0, False)
    assert not _pour_drops(1.0 - 5e-10, 1.0, 5.0, 1.0, False)  # tied with g2_min: kept
    assert not _pour_drops(0.5, inf, 1.0 + 2e-9, 1.0, False)
    assert not _pour_drops(0.5, inf, 1.0 + 0.99 * GOAL_MARGIN, 1.0, False)
    assert _pour_drops(0.5, inf, 1.0 + 1.01 * GOAL_MARGIN, 1.0, False)
    assert not _pour_drops(0.5, inf, 4e6 * (1 + 2.9e-9), 4e6, False)  # relative
    assert _pour_drops(5.0, inf, 5.0, 1.0, True)  # at the goal
    assert not _pour_drops(1.0 + 5e-10, inf, 1.0 + 5e-10, 1.0, True)
    assert not _pour_drops(5.0, inf, 5.0, inf, True)
    # tied with g2_min from above: dropped unless tied in length with first
    assert _pour_drops_tied(1.0, 1.0, 3.0, 2.0)
    assert _pour_drops_tied(1.0 + 5e-10, 1.0, 3.0, 2.0)
    assert not _pour_drops_tied(1.0 + 5e-10, 1.0, 2.0 + 1e-12, 2.0)
    assert not _pour_drops_tied(1.0 - 5e-10, 1.0, 3.0, 2.0)  # from below: kept


def _doubles_tied(x, up):
    """The farthest double from ``x`` (above it if ``up``, else below) that
    ``_eq`` ties with ``x`` (bisection on the bit patterns of non-negative
    doubles, which are ordered like the values)."""
    from gapath.planners._exact_kernels import _eq

    def b(v):
        return int(np.array([v]).view(np.int64)[0])

    span = 1e-8 * max(1.0, x)  # ten tolerances
    lo, hi = (b(x), b(x + span)) if up else (b(max(0.0, x - span)), b(x))
    if not up and _eq(0.0, x):
        return 0.0
    while hi - lo > 1:  # invariant: the end near x ties, the far end does not
        mid = (lo + hi) // 2
        t = np.array([mid]).view(np.float64)[0]
        if _eq(t, x) == up:
            lo = mid
        else:
            hi = mid
    return np.array([lo if up else hi]).view(np.float64)[0]


def _lowest(pred, a, b):
    """The lowest double in (a, b] where ``pred`` holds (false at a, true at b,
    monotone between)."""
    lo, hi = int(np.array([a]).view(np.int64)[0]), int(np.array([b]).view(np.int64)[0])
    assert pred(b) and not pred(a)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if pred(np.array([mid]).view(np.float64)[0]):
            hi = mid
        else:
            lo = mid
    return np.array([hi]).view(np.float64)[0]


def _next(x, k=1):
    return np.array([np.array([x]).view(np.int64)[0] + k]).view(np.float64)[0]


MAGNITUDES = [0.0, 1e-12, 3e-9, 0.3, 1.0, 1.5, 7.25, 1e3 / 3, 4096.0, 2.0**20 + 0.1, 1e6 / 7]


def test_tied_from_above_stays_apart_from_every_lower_g2_min():
    """The step of _pour_drops_tied's proof, at the tolerance's edges: for
    q >= m, and m' below m beyond the tolerance (an expansion there), q and m'
    are not tied, however close m' is to m and q is to the far end of m's
    tolerance. A q below m may be tied with such an m' (the tolerance is not
    transitive): those labels are kept."""
    from gapath.planners._exact_kernels import _eq

    for m in MAGNITUDES:
        if _eq(0.0, m):  # no g2_min below m beyond the tolerance
            continue
        m1 = _next(_doubles_tied(m, False), -1)  # the highest m' beyond the tolerance below m
        assert m1 < m and not _eq(m1, m)
        far = _doubles_tied(m, True)
        for q in (m, _next(m), _next(m, 2), (m + far) / 2, _next(far, -1), far):
            assert q >= m and _eq(q, m)
            assert not _eq(q, m1), (m, q, m1)
            assert not _eq(q, _next(m1, -1000))
        below = _doubles_tied(m, False)
        assert _eq(below, m1)  # tied from below: a lower g2_min may tie it


def test_goal_margin_keeps_a_dropped_label_apart_from_every_expansion():
    """The step of _pour_drops' goal rule, at the tolerance's edges: a label
    whose f_vulnerability f exceeds the last solution's G by more than
    GOAL_MARGIN has a g2 not tied with that of any label expanded at its cell
    later (f_vulnerability at most tied with a G' <= G, from above at worst),
    whatever the cell's vulnerability to go. With one tolerance instead of
    three it would not hold."""
    from gapath.planners._boa_kernels import GOAL_MARGIN, _pour_drops
    from gapath.planners._exact_kernels import TOL, _eq

    for g in MAGNITUDES:
        for hv in (0.0, 1e-11, 0.5, 3.0, 250.0, 1e4 / 3):
            fz = _doubles_tied(g, True)  # the highest f_vulnerability tied with G
            fy = _lowest(lambda f, g=g: f - g > GOAL_MARGIN * max(1.0, f), g, g + 4 * TOL * max(1.0, g))
            for qz_try in (fz - hv, _next(fz - hv, -1), _next(fz - hv, 1)):
                for qy_try in (fy - hv, _next(fy - hv, -1), _next(fy - hv, 1)):
                    if qy_try < 0 or qz_try < 0:
                        continue
                    if qz_try + hv > fz or qy_try + hv < fy:
                        continue  # not these f_vulnerabilities
                    assert _pour_drops(qy_try, np.inf, qy_try + hv, g, False)
                    assert not _eq(qy_try, qz_try), (g, hv, qy_try, qz_try)
    # one tolerance would not do: a label just beyond it can tie an expansion
    # tied with G from above
    g, hv = 1000.0, 0.0
    fz = _doubles_tied(g, True)
    fy = _next(g + TOL * g * (1 + 1e-6))
    assert fy - g > TOL * fy and _eq(fy, fz)


def test_back_step_is_covered_by_the_parents_g2():
    """The first step of _back_step_drops' proof: the child stepping back to
    its grandparent's cell has a g2, ``fl(fl(q_p + P) + P')``, at or above
    ``q_p`` for non-negative potentials (rounding is monotone), however
    small the potentials are against ``q_p``."""
    for q_p in MAGNITUDES:
        for p1 in (0.0, 5e-324, 1e-300, 1e-17, 2.0**-60, 0.25, 1.0 / 3):
            for p2 in (0.0, 5e-324, 1e-17, 0.5):
                assert (q_p + p1) + p2 >= q_p


def test_back_step_drops_exactly_when_the_eager_length_test_cannot_tie():
    """_back_step_drops computes the lengths the eager check would compare
    when the label last expanded at the grandparent's cell is the
    grandparent itself (two steps apart): it drops the step back iff they are
    not tied, which holds for any cell size above the tolerance's scale, and
    not at the cell size (found by bisection) where two steps from the start
    tie. Without ties the step back is always dropped."""
    from gapath.planners._boa_kernels import _back_step_drops
    from gapath.planners._exact_kernels import _eq

    sqrt2 = np.sqrt(2.0)
    for ns, nd in ((1, 0), (0, 1), (5, 3), (700, 1200), (10**6, 10**6)):
        for s in (0, 1):
            if (ns if s else nd) < 1:  # x was entered by such a step
                continue
            for cs in (1.0, 0.05, 3.7, 1e-6):
                assert _back_step_drops(ns, nd, s, 1 - s, cs, True)
                assert _back_step_drops(ns, nd, s, 1 - s, cs, False)

    def tied(cs, s):  # x one step from the start: the child is two steps from p
        a = ((s + s) + sqrt2 * ((1 - s) + (1 - s))) * cs
        return _eq(a, 0.0 * cs)

    for s in (0, 1):
        lo, hi = 1e-12, 1.0  # tied at lo, not at hi
        assert tied(lo, s) and not tied(hi, s)
        for _ in range(200):
            mid = (lo + hi) / 2
            if mid in (lo, hi):
                break
            lo, hi = (mid, hi) if tied(mid, s) else (lo, mid)
        assert not _back_step_drops(s, 1 - s, s, 1 - s, lo, True)
        assert _back_step_drops(s, 1 - s, s, 1 - s, hi, True)
        assert _back_step_drops(s, 1 - s, s, 1 - s, lo, False)
