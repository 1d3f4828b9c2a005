"""Bounded, interruptible exact searches: the label budget, progress
callbacks, KeyboardInterrupt, resumption in slices and the ``stats`` of a
front (:func:`gapath.planners.exact.free_front` and ``monotone_front``)."""

from __future__ import annotations

import numpy as np
import pytest

from gapath import ConfigError, random_workspace
from gapath.errors import GapathError, LabelBudgetError
from gapath.planners import exact
from gapath.planners.exact import free_front, monotone_front

LV = ("length", "vulnerability")
LVS = ("length", "vulnerability", "smoothness")
SOLVERS = {"free": free_front, "monotone": monotone_front}


def _ws(seed=3, size=20):
    return random_workspace((size, size), int(0.2 * size * size), seed=seed)


class _TinySlices(exact._Slices):
    """The smallest work per kernel call (8 pops, one column), never adapted:
    a search then pauses and resumes many times."""

    def __init__(self, first, lo, hi):
        super().__init__(8 if first > 8 else 1, 1, 1)

    def update(self, done, seconds):
        pass


@pytest.fixture
def tiny_slices(monkeypatch):
    monkeypatch.setattr(exact, "_Slices", _TinySlices)


@pytest.fixture
def interactive_sigint():
    """SIGINT raising KeyboardInterrupt, as in a Python started from a
    terminal: a suite started in the background by a shell without job
    control (``(cmd &)``) inherits SIGINT ignored, and then no Ctrl-C can
    reach the code under test."""
    import signal

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def _same(a, b):
    assert a.objectives == b.objectives
    assert np.array_equal(a.F, b.F)
    assert np.array_equal(a.smoothness, b.smoothness)
    assert len(a.paths) == len(b.paths)
    for p, q in zip(a.paths, b.paths):
        assert np.array_equal(p, q)


@pytest.mark.parametrize("kind", ["free", "monotone"])
@pytest.mark.parametrize("objectives", [LV, LVS, ("length", "smoothness")])
def test_resumed_in_slices_equals_one_call(kind, objectives, monkeypatch):
    ws = _ws(seed=5, size=14)
    whole = SOLVERS[kind](ws, objectives)
    monkeypatch.setattr(exact, "_Slices", _TinySlices)
    calls = []
    sliced = SOLVERS[kind](ws, objectives, progress=calls.append)
    _same(whole, sliced)
    assert len(calls) > 3  # it did pause and resume
    assert calls[-1]["phase"] == kind


@pytest.mark.parametrize("kind", ["free", "monotone"])
def test_stats_are_reported(kind):
    front = SOLVERS[kind](_ws(), LV)
    s = front.stats
    assert s["labels"] > 0 and s["peak_bytes"] > 0 and s["seconds"] >= 0
    if kind == "free":
        assert s["generated"] >= s["expansions"] > 0
        assert s["solutions"] >= len(front)
    else:
        assert s["columns"] == s["n_cols"]
    assert "stats" not in front.to_dict()


def test_progress_is_called_with_growing_counts(tiny_slices):
    calls = []
    front = free_front(_ws(), LVS, progress=calls.append)
    assert len(calls) > 3
    for key in ("expansions", "generated", "labels", "open", "solutions", "seconds"):
        assert key in calls[0]
    exp = [c["expansions"] for c in calls]
    assert exp == sorted(exp)
    assert calls[-1]["open"] == 0
    assert calls[-1]["expansions"] == front.stats["expansions"]


@pytest.mark.parametrize("kind", ["free", "monotone"])
def test_budget_stops_with_a_message(kind):
    ws = _ws()
    full = SOLVERS[kind](ws, LVS)
    # the DP frees labels as it goes: its peak is what a budget bounds
    budget = max(1, full.stats.get("labels_peak", full.stats["labels"]) // 4)
    with pytest.raises(LabelBudgetError) as info:
        SOLVERS[kind](ws, LVS, max_labels=budget)
    err = info.value
    assert isinstance(err, GapathError)
    msg = str(err)
    assert f"max_labels={budget:,}" in msg and "--max-labels" in msg
    assert "not a Pareto front" in msg and "Raise the budget" in msg
    assert err.stats["max_labels"] == budget
    assert 0 < err.stats["labels"] <= budget
    if kind == "free":
        assert err.stats["expansions"] < full.stats["expansions"]
    else:
        assert err.stats["columns"] < full.stats["n_cols"]


@pytest.mark.parametrize("kind", ["free", "monotone"])
def test_a_sufficient_budget_changes_nothing(kind):
    ws = _ws()
    full = SOLVERS[kind](ws, LV)
    # the free search stops when an expansion (8 labels) could exceed the budget; the DP
    # never holds more than its peak
    budget = full.stats["labels"] + 8 if kind == "free" else full.stats["labels_peak"]
    _same(full, SOLVERS[kind](ws, LV, max_labels=budget))


@pytest.mark.parametrize("objectives", [LVS, ("length", "smoothness")])
def test_labels_held_count_the_parent_entries(objectives):
    """The (x, smoothness) and three-objective searches keep an expanded
    label as a parent entry, not a row: ``labels`` still bounds what they
    held, so that budget is enough and a smaller one stops them."""
    ws = _ws(seed=7, size=24)
    full = free_front(ws, objectives)
    _same(full, free_front(ws, objectives, max_labels=full.stats["labels"] + 8))
    # the expanded labels alone are held to the end: half of them is not enough
    with pytest.raises(LabelBudgetError):
        free_front(ws, objectives, max_labels=full.stats["expansions"] // 2)


def test_expanded_labels_leave_their_rows():
    """An expanded label is needed only as its children's parent: it keeps
    a cell and a parent index (8 bytes), not its 36-byte row (28 bytes of
    int32 columns and the vulnerability). On this map (1.2 million
    expansions, three objectives) the search's arrays, the fixed ones
    included, then take 0.89 times 36 bytes per expansion; when every
    expanded label kept its row, 2.15 times."""
    ws = random_workspace((96, 96), int(0.15 * 96 * 96), seed=3)
    s = free_front(ws, LVS).stats
    assert s["expansions"] > 1_000_000
    assert s["peak_bytes"] < 36 * s["expansions"]


@pytest.mark.parametrize("bad", [0, -5, 1.5, "10", True, 2**40])
def test_bad_budget(bad):
    with pytest.raises(ConfigError, match="max_labels"):
        free_front(_ws(), LV, max_labels=bad)


def _recomputed(ws, front):
    """``front``'s paths checked (valid, simple) and their objectives
    recomputed, in ``front.objectives``' order."""
    from test_free_paths import check_path

    from gapath.objectives import evaluate_paths, pad_paths
    from gapath.problems import FreePathProblem

    for path in front.paths:
        check_path(ws, path)
    P, L = pad_paths(front.paths)
    M = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    return FreePathProblem(ws, front.objectives).objective_values(M)


def _matched(f, F, tol=1e-9) -> bool:
    return bool(np.any(np.all(np.abs(F - f) <= tol * (1 + np.abs(f)), axis=1)))


def _room():
    from test_free_paths import room

    return room(h=24, w=28, seed=3)  # a (length, smoothness) front of 6 points


#: one case per free search: BOA*, BOA* on (cell, heading) states (twice),
#: NAMOA*-dr, the k-objective search; with a map whose front has several points
PARTIAL_CASES = [
    (LV, "auto", _ws),
    (("vulnerability", "smoothness"), "auto", _ws),
    (("length", "smoothness"), "auto", _room),
    (LVS, "auto", _ws),
    (LVS, "k", _ws),
]


@pytest.mark.parametrize("objectives, search, make", PARTIAL_CASES)
def test_expansion_budget_returns_a_part_of_the_exact_front(objectives, search, make, monkeypatch):
    """``max_expansions`` ends the search at the first check past it (every
    CHECK_POPS pops) with the solutions found so far: points of the exact
    front, and every exact point with a smaller first key (length, else
    vulnerability) among them; valid paths with ``F`` recomputed; the same
    on every call. A budget the search does not reach changes nothing."""
    monkeypatch.setattr(exact, "CHECK_POPS", 16)
    ws = make(seed=7, size=24) if make is _ws else make()
    checks = []
    full = free_front(ws, objectives, search=search, max_expansions=1e12, progress=checks.append)
    n = full.stats["expansions"]
    assert full.stats["complete"] is True
    # a budget half-way between the first solution and the end
    found = [c["expansions"] for c in checks if 0 < c["solutions"] and c["expansions"] < n]
    budget = found[len(found) // 2]
    part = free_front(ws, objectives, search=search, max_expansions=budget)
    assert part.stats["complete"] is False
    assert budget < part.stats["expansions"] < n
    assert 0 < len(part) < len(full)
    np.testing.assert_allclose(part.F, _recomputed(ws, part), rtol=1e-12, atol=1e-12)
    assert all(_matched(f, full.F) for f in part.F)
    key = objectives.index("length" if "length" in objectives else "vulnerability")
    top = part.F[:, key].max()
    below = full.F[full.F[:, key] < top * (1 - 1e-9)]
    assert len(below) > 0 and all(_matched(f, part.F) for f in below)
    _same(part, free_front(ws, objectives, search=search, max_expansions=budget))
    whole = free_front(ws, objectives, search=search, max_expansions=n)
    assert whole.stats["complete"] is True
    _same(full, whole)


def test_expansion_budget_of_the_approximate_search(monkeypatch):
    """With ``epsilon > 0`` the budget stops the apex search the same way:
    valid paths, ``F`` recomputed, none better than the exact front."""
    monkeypatch.setattr(exact, "CHECK_POPS", 16)
    ws = _ws(seed=7, size=24)
    approx = free_front(ws, LVS, epsilon=0.1)
    part = free_front(ws, LVS, epsilon=0.1, max_expansions=approx.stats["expansions"] // 2)
    assert approx.stats["complete"] is True and part.stats["complete"] is False
    assert 0 < len(part) < len(approx)
    np.testing.assert_allclose(part.F, _recomputed(ws, part), rtol=1e-12, atol=1e-12)
    exact_F = free_front(ws, LVS).F
    for f in part.F:
        assert not np.any(np.all(f <= exact_F, axis=1) & np.any(f < exact_F - 1e-9, axis=1))


@pytest.mark.parametrize("bad", [-1, "x", float("nan")])
def test_bad_expansion_budget(bad):
    with pytest.raises(ConfigError, match="max_expansions"):
        free_front(_ws(), LV, max_expansions=bad)


@pytest.mark.parametrize("kind", ["free", "monotone"])
def test_keyboard_interrupt_propagates_and_leaves_no_state(kind, tiny_slices):
    ws = _ws(seed=4)
    calls = []

    def stop_at_third(info):
        calls.append(info)
        if len(calls) == 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        SOLVERS[kind](ws, LVS, progress=stop_at_third)
    assert len(calls) == 3  # nothing ran after the interrupt
    # a second call works and gives the uninterrupted front
    again = SOLVERS[kind](ws, LVS)
    fresh = SOLVERS[kind](ws.replace(name="fresh"), LVS)
    _same(again, fresh)


# ---------------------------------------------------------------------------
# gapath exact --max-labels, progress and Ctrl-C
# ---------------------------------------------------------------------------


@pytest.fixture
def text_map(tmp_path):
    rows = [
        "...........",
        "...#....#..",
        "......#....",
        "..#........",
        ".....#..#..",
        ".#.........",
        "....#......",
        "...........",
    ]
    p = tmp_path / "small.txt"
    p.write_text("\n".join(rows) + "\n")
    return p


@pytest.mark.parametrize("mode", ["free", "monotone"])
def test_cli_summary_has_search_stats(text_map, tmp_path, mode):
    import json

    from gapath.cli import main

    out = tmp_path / "ex"
    assert (
        main(
            [
                "exact",
                str(text_map),
                "--mode",
                mode,
                "--out",
                str(out),
                "--quiet",
                "--no-plots",
                "--max-labels",
                "100000",
            ]
        )
        == 0
    )
    summary = json.loads((out / "summary.json").read_text())
    assert summary["settings"]["max_labels"] == 100000
    assert summary["search"]["labels"] > 0 and summary["search"]["peak_bytes"] > 0


@pytest.mark.parametrize("mode", ["free", "monotone"])
def test_cli_budget_is_an_error_with_no_front(text_map, tmp_path, capsys, mode):
    from gapath.cli import main

    out = tmp_path / "ex"
    code = main(
        [
            "exact",
            str(text_map),
            "--mode",
            mode,
            "--objectives",
            "length,vulnerability,smoothness",
            "--out",
            str(out),
            "--quiet",
            "--max-labels",
            "20",
        ]
    )
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith("gapath: error: ") and "--max-labels" in err and "labels" in err
    assert "Traceback" not in err
    assert not (out / "front.csv").exists()


@pytest.mark.parametrize("bad", ["0", "-3", "ten"])
def test_cli_bad_budget(text_map, tmp_path, capsys, bad):
    from gapath.cli import main

    with pytest.raises(SystemExit) as info:
        main(["exact", str(text_map), "--max-labels", bad, "--out", str(tmp_path / "x")])
    assert info.value.code == 2
    assert "--max-labels" in capsys.readouterr().err


def test_cli_ctrl_c_exits_130_and_writes_no_front(text_map, tmp_path, capsys, monkeypatch):
    from gapath.cli import main

    def interrupt(info):
        raise KeyboardInterrupt

    monkeypatch.setattr(exact, "_Slices", _TinySlices)
    real = exact.free_front
    monkeypatch.setattr(
        exact,
        "free_front",
        lambda ws, objs, **kw: real(ws, objs, max_labels=kw["max_labels"], progress=interrupt),
    )
    out = tmp_path / "ex"
    assert main(["exact", str(text_map), "--mode", "free", "--out", str(out)]) == 130
    err = capsys.readouterr().err
    assert "interrupted" in err and "no front written" in err
    assert not (out / "front.csv").exists()


def test_progress_line_is_throttled_and_names_the_counts():
    import io

    from gapath.cli.exact import _ProgressLine

    line = _ProgressLine("free")
    line.stream, line.tty, line.every = io.StringIO(), False, 0.0
    info = {"phase": "free", "expansions": 1234567, "labels": 20, "open": 3, "solutions": 2, "seconds": 1.25}
    line(info)
    text = line.stream.getvalue()
    assert "1,234,567 expanded" in text and "2 solutions so far" in text
    line.every = 3600.0
    line(info)  # too soon: nothing more
    assert line.stream.getvalue() == text


@pytest.mark.parametrize("kind", ["free", "monotone"])
def test_sigint_during_a_search_is_a_keyboard_interrupt(kind, tiny_slices, interactive_sigint):
    """A SIGINT held while a kernel runs is raised as KeyboardInterrupt after
    it (never a SystemError from inside numba), before the next progress call."""
    import os
    import signal

    calls = []

    def send_sigint(info):
        calls.append(info)
        if len(calls) == 2:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        SOLVERS[kind](_ws(seed=4), LVS, progress=send_sigint)
    assert len(calls) == 2
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


@pytest.mark.parametrize("objectives, kernel", [(LV, "_boa_prepare"), (LVS, "_free_prepare")])
def test_sigint_inside_the_first_kernel_is_a_keyboard_interrupt(
    monkeypatch, objectives, kernel, interactive_sigint
):
    """Before the holding handler is installed (a search done in one kernel
    call never installs it), a SIGINT raised while a kernel runs surfaces in
    numba's boxing of its result as a SystemError; free_front raises the
    KeyboardInterrupt instead, and a second call works (two objectives:
    BOA*'s first kernel, three: the other searches')."""
    import ctypes
    import signal

    import numba

    libc = ctypes.CDLL(None)
    kill, getpid = libc.kill, libc.getpid
    kill.argtypes, kill.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    getpid.argtypes, getpid.restype = (), ctypes.c_int
    sigint = int(signal.SIGINT)

    @numba.njit
    def raise_sigint_inside(n):  # a Ctrl-C while a kernel runs
        kill(getpid(), sigint)
        return np.zeros(n), np.zeros(n)

    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        raise_sigint_inside(1)  # compile, the signal ignored
    finally:
        signal.signal(signal.SIGINT, previous)
    prepare = getattr(exact, kernel)

    def prepare_then_sigint(*args):
        raise_sigint_inside(1)
        return prepare(*args)

    ws = _ws(seed=4, size=12)
    fresh = free_front(ws, objectives)
    monkeypatch.setattr(exact, kernel, prepare_then_sigint)
    with pytest.raises(KeyboardInterrupt):
        free_front(ws, objectives)
    monkeypatch.setattr(exact, kernel, prepare)
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    _same(free_front(ws, objectives), fresh)
