"""The k-objective exact free search (private; public entry
:func:`gapath.planners.exact.free_front`, kernels in
:mod:`gapath.planners._multi_kernels`).

Objective names (see ``docs/CONVENTIONS.md``, "Exact fronts over costmap layers")
    ``length``, ``vulnerability``, ``smoothness`` as in SPEC; with a
    :class:`gapath.costmap.Costmap`: ``solar`` (already a sum over the steps,
    the GA's value) and ``<layer>_sum`` for a cell layer (``elevation_sum``,
    ``risk_sum``, ``<user layer>_sum``): the layer summed over the path's
    cells, start and goal included. The GA's ``elevation``, ``risk`` and user
    layer objectives are path MEANS (sum / number of cells); a mean is not
    additive along a path (extending a path can lower it), so no
    label-setting search gives its exact front, and those names are refused
    with a pointer to the ``_sum`` form.
"""

from __future__ import annotations

import time

import numpy as np

from gapath.errors import ConfigError, NoPathError
from gapath.grid import DC, DR, SQRT2, check_path
from gapath.objectives import QUARTER_PI
from gapath.planners._exact_kernels import _trace_parents
from gapath.planners._multi_kernels import (
    DONE,
    K_CELL,
    K_LEN,
    K_SOLAR,
    K_TURN,
    ND,
    NS,
    OVER_BUDGET,
    PAUSED,
    S_BUILT,
    S_DROP_NODES,
    S_EXPANDED,
    S_GENERATED,
    S_GOAL_NODES,
    S_GOAL_TESTS,
    S_N,
    S_N_FREE,
    S_PC,
    S_POPS,
    S_SIZE,
    S_SOLS,
    S_STATE_NODES,
    S_STATE_TESTS,
    STEP_LIMIT,
    TURNS,
    _cell_to_go,
    _front_filter,
    _hops,
    _k_init,
    _k_run,
    _step_to_go,
    _timed_solar_to_go,
)

#: Objective names of the k-objective search that need no costmap.
BASE_OBJECTIVES = ("length", "vulnerability", "smoothness")
#: Steps per cell the timed-solar search may take (its solar table's rows);
#: longer walks stop the search with a ConfigError.
TIMED_STEPS = 40
#: Floats of the timed-solar bound table (step index x cell), 128 MB.
TIMED_BOUND_FLOATS = 1 << 24
#: Suffix of a summed cell layer objective (``elevation_sum``).
SUM_SUFFIX = "_sum"


def parse_objectives(objectives, costmap) -> tuple[tuple[str, ...], list[tuple[int, str | None]]]:
    """The objective names and, for each, ``(kind, layer)``: the kernel's
    kind and the layer it reads (``None`` for length, smoothness and solar;
    ``"vulnerability"`` reads the workspace potential).

    Raises
    ------
    ConfigError
        On an empty or repeated list, ``interfering``, a mean layer
        objective, a layer objective without a costmap, or an unknown name.
    """
    if isinstance(objectives, str):
        objectives = [o.strip() for o in objectives.split(",") if o.strip()]
    names: tuple[str, ...] = tuple(objectives)
    if not names:
        raise ConfigError("at least one objective is needed")
    out: list[tuple[int, str | None]] = []
    for n in names:
        if not isinstance(n, str):
            raise ConfigError(f"objective names must be strings, got {n!r}")
        if names.count(n) > 1:
            raise ConfigError(f"objective {n!r} is given twice")
        if n == "length":
            out.append((K_LEN, None))
        elif n == "smoothness":
            out.append((K_TURN, None))
        elif n == "vulnerability":
            out.append((K_CELL, "vulnerability"))
        elif n == "interfering":
            raise ConfigError(
                "objective 'interfering' cannot be minimised by the exact planner (it is a "
                "constraint: every returned path has interfering == 0)"
            )
        elif costmap is None:
            raise ConfigError(
                f"objective {n!r} needs a costmap (free_front(..., costmap=Costmap(...))); "
                f"without one choose among {', '.join(BASE_OBJECTIVES)}"
            )
        elif n == "solar":
            out.append((K_SOLAR, None))
        elif n.endswith(SUM_SUFFIX) and n[: -len(SUM_SUFFIX)] in _cell_layers(costmap):
            out.append((K_CELL, n[: -len(SUM_SUFFIX)]))
        elif n in _cell_layers(costmap):
            raise ConfigError(
                f"objective {n!r} is the MEAN of layer {n!r} over the path's cells (the GA's "
                f"objective); a mean is not additive along a path, so no exact label-setting "
                f"front exists for it: use {n + SUM_SUFFIX!r}, the layer summed over the cells "
                f"(the exact front is then over the sum)"
            )
        else:
            avail = list(BASE_OBJECTIVES) + (["solar"] if costmap is not None else [])
            avail += [f"{c}{SUM_SUFFIX}" for c in _cell_layers(costmap)]
            raise ConfigError(f"unknown exact objective {n!r}; expected some of {', '.join(avail)}")
    return names, out


def _cell_layers(costmap) -> tuple[str, ...]:
    return tuple(n for n in costmap.objective_names if n not in ("length", "solar"))


def _check_costmap(workspace, costmap):
    if costmap is None:
        return
    if tuple(costmap.shape) != tuple(workspace.shape):
        raise ConfigError(
            f"the costmap's grid {costmap.shape} differs from the workspace's {workspace.shape}"
        )


def path_objectives(workspace, path, objectives, costmap=None) -> dict[str, float]:
    """The k-objective exact search's objectives of one path, computed the way
    the search computes them (the reference for its ``F``, bit for bit).

    ``length`` from the integer step counts, ``vulnerability`` and
    ``smoothness`` as :func:`gapath.objectives.evaluate_path`, a
    ``<layer>_sum`` as the layer summed over the path's cells in path order,
    start and goal included (``Costmap.evaluate_path``'s mean times the
    number of cells, up to the summation order), ``solar`` as the per-step
    costs of :meth:`Costmap.solar_table` summed in path order (the value of
    ``Costmap.evaluate_path`` up to the summation order).

    Parameters
    ----------
    workspace : Workspace
    path : (m, 2) cells, consecutive cells 8-adjacent.
    objectives : sequence of str or comma-separated str
        Names as for :func:`gapath.planners.exact.free_front`.
    costmap : Costmap, optional
        Needed for ``solar`` and the ``<layer>_sum`` objectives.

    Returns
    -------
    dict name -> float

    Raises
    ------
    ConfigError
        On a bad objective (see :func:`gapath.planners.exact.free_front`) or path.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> from gapath.costmap import Costmap
    >>> ws = Workspace(np.zeros((2, 3), bool))
    >>> cm = Costmap(ws, layers={"sand": np.arange(6.0).reshape(2, 3)})
    >>> path_objectives(ws, [(1, 0), (1, 1), (0, 2)], ["length", "sand_sum"], cm)["sand_sum"]
    9.0
    """
    from gapath.objectives import evaluate_path

    names, spec = parse_objectives(objectives, costmap)
    _check_costmap(workspace, costmap)
    p = check_path(path, workspace.shape)
    d = np.diff(p, axis=0)
    base = evaluate_path(workspace, p)
    out = {}
    for name, (kind, layer) in zip(names, spec):
        if kind == K_LEN:
            diag = int(np.count_nonzero((d[:, 0] != 0) & (d[:, 1] != 0)))
            out[name] = (len(d) - diag + SQRT2 * diag) * float(workspace.cell_size)
        elif kind == K_TURN:
            out[name] = base["smoothness"]
        elif kind == K_CELL:
            values = workspace.potential if layer == "vulnerability" else costmap.layer(layer)
            acc = 0.0
            for r, c in p:
                acc += float(values[r, c])
            out[name] = acc
        else:
            table = costmap.solar_table(max(len(d), 1))
            move = {(int(a), int(b)): i for i, (a, b) in enumerate(zip(DR, DC))}
            acc = 0.0
            for i, (a, b) in enumerate(d):
                acc += float(table[i, move[(int(a), int(b))]])
            out[name] = acc
    return out


def _set_sizes(sidx) -> dict[str, float]:
    """Sizes of the per-state sets at the end (non-empty ones) and of the goal's."""
    cnt = sidx[:-1, 1]
    cnt = cnt[cnt > 0]
    return {
        "states": int(len(cnt)),
        "mean": float(cnt.mean()) if len(cnt) else 0.0,
        "p90": float(np.percentile(cnt, 90)) if len(cnt) else 0.0,
        "max": int(cnt.max()) if len(cnt) else 0,
        "goal": int(sidx[-1, 1]),
    }


def multi_front(
    workspace,
    objectives,
    costmap=None,
    *,
    max_labels=None,
    progress=None,
    tie_break="smoothest",
    limit=float("inf"),
):
    """The k-objective exact free front (see :func:`gapath.planners.exact.free_front`;
    ``limit``: its ``max_expansions``, checked)."""
    from gapath.planners import exact
    from gapath.planners._exact_heuristics import _free_heuristics, _move_masks

    names, spec = parse_objectives(objectives, costmap)
    _check_costmap(workspace, costmap)
    budget = exact._budget(max_labels)
    if tie_break not in ("smoothest", "none"):
        raise ConfigError(f"tie_break must be 'smoothest' or 'none', got {tie_break!r}")
    t0 = time.perf_counter()
    occ = np.ascontiguousarray(workspace.occ)
    pot = np.ascontiguousarray(workspace.potential, dtype=np.float64)
    (sr, sc), (gr, gc) = workspace.start, workspace.goal
    h, w = workspace.shape
    n_cells = h * w
    cs = float(workspace.cell_size)
    cc = bool(workspace.corner_cutting)
    smooth = any(kind == K_TURN for kind, _ in spec)

    # internal order: the length first when it is an objective (exact integer ties
    # in the primary key), the others as given; float columns for the sums
    order = sorted(range(len(names)), key=lambda i: spec[i][0] != K_LEN)
    okind = np.array([spec[i][0] for i in order], np.int64)
    ocol = np.zeros(len(order), np.int64)
    float_cols = [i for i in order if spec[i][0] in (K_CELL, K_SOLAR)]
    n_float = len(float_cols)
    for o, i in enumerate(order):
        if i in float_cols:
            ocol[o] = float_cols.index(i)
    solar = any(kind == K_SOLAR for kind, _ in spec)
    timed = solar and costmap.solar_rate != 0.0

    with exact._DeferredInterrupt() as interrupt:
        mask = _move_masks(occ, cc)
        goal = gr * w + gc
        hop = _hops(mask, w, goal)
        if hop[sr * w + sc] < 0:
            raise NoPathError(
                f"no feasible path from {workspace.start} to {workspace.goal} in workspace "
                f"{workspace.name!r} ({h}x{w}, {workspace.n_obstacles} obstacles, "
                f"corner_cutting={workspace.corner_cutting})"
            )
        hs, hd, _, ht = _free_heuristics(occ, pot, gr, gc, cc, smooth, mask)
        layers = np.zeros((max(n_float, 1), n_cells))
        hfl = np.zeros((max(n_float, 1), n_cells))
        # solar: the per-step costs of Costmap.solar_table (numpy, as evaluate_path);
        # with a rate, a table long enough for any label the search may make
        n_table = TIMED_STEPS * n_cells + 64 if timed else 1
        table = (
            np.ascontiguousarray(costmap.solar_table(n_table + n_cells + 1)) if solar else np.zeros((1, 8))
        )
        psum = np.zeros(1)
        hsol = np.zeros((0, 1))
        if timed:
            psum = np.concatenate([[0.0], np.cumsum(table.min(axis=1))])
            table = np.ascontiguousarray(table[:n_table])
            # per (step index, cell) solar bounds for the first steps (a table of
            # at most TIMED_BOUND_FLOATS floats), the per-step least cost beyond
            n_rows = min(n_table - 1, max(1, TIMED_BOUND_FLOATS // n_cells))
            hsol = _timed_solar_to_go(table, mask, w, goal, hop, psum, n_rows)
        for col, i in enumerate(float_cols):
            kind, layer = spec[i]
            if kind == K_CELL:
                values = pot if layer == "vulnerability" else costmap.layer(layer)
                layers[col] = np.ascontiguousarray(values, dtype=np.float64).ravel()
                hfl[col] = _cell_to_go(layers[col], mask, w, goal)
            elif not timed:
                hfl[col] = _step_to_go(np.ascontiguousarray(table[0]), mask, w, goal)
        interrupt.check()
        t_heur = time.perf_counter() - t0
        sidx = np.zeros((n_cells + 1, 3), np.int64)  # per-state set blocks, the goal's last
        li, lg, lf, hid, sols, st, sv, si, sfree, tdir, pc, fs, fseq = _k_init(
            sr * w + sc, layers, okind, ocol, cs, hs, hd, ht, hfl, hop, psum, hsol, timed, n_float
        )
        fixed = sum(a.nbytes for a in (hs, hd, ht, hfl, layers, table, psum, hsol, hop, mask))
        slices = exact._slices(1 << 12, 1 << 8, 1 << 24, limit)
        stop = False
        peak = 0
        while True:
            pops, t1 = st[S_POPS], time.perf_counter()
            sidx, li, lg, lf, hid, sols, sv, si, tdir, pc, fs, fseq, status = _k_run(
                mask, w, goal, layers, table, okind, ocol, cs, hs, hd, ht, hfl, hop, psum,
                hsol, timed, smooth, tie_break == "smoothest", sidx, li, lg, lf, hid, sols, st,
                sv, si, sfree, tdir, pc, fs, fseq, slices.n, budget,
            )  # fmt: skip
            interrupt.check()
            now = time.perf_counter()
            slices.update(st[S_POPS] - pops, now - t1)
            arrays = (sidx, li, lg, lf, hid, sols, sv, si, tdir, pc, fs, fseq)
            peak = max(peak, fixed + sum(a.nbytes for a in arrays))
            stats = {
                "expansions": int(st[S_EXPANDED]),
                "generated": int(st[S_GENERATED]),
                "labels": int(st[S_N] - st[S_N_FREE] + st[S_PC]),  # rows in use and entries
                "open": int(st[S_SIZE]),
                "solutions": int(st[S_SOLS]),
                "seconds": now - t0,
            }
            if status == OVER_BUDGET:
                raise exact._free_budget_error(budget, stats)
            if status == STEP_LIMIT:
                raise ConfigError(
                    f"free search stopped: a path of {table.shape[0]:,} steps is still open "
                    f"(solar_rate={costmap.solar_rate:g} makes the step index part of the state "
                    f"and the solar table covers 40 times the number of cells); no front. Use "
                    f"solar_rate=0 or a label budget (max_labels)"
                )
            stop = status == PAUSED and stats["expansions"] > limit
            if progress is not None:
                progress({"phase": "free", **stats})
            if status == DONE or stop:
                break

    sols = sols[: st[S_SOLS]]
    n_straight = li[sols, NS].astype(np.int64)
    n_diag = li[sols, ND].astype(np.int64)
    turns = li[sols, TURNS].astype(np.int64)
    columns = {}
    for o, i in enumerate(order):
        kind = okind[o]
        if kind == K_LEN:
            columns[i] = (n_straight + SQRT2 * n_diag) * cs
        elif kind == K_TURN:
            columns[i] = turns * QUARTER_PI
        else:
            columns[i] = lg[sols, ocol[o]]
    F = np.column_stack([columns[i] for i in range(len(names))]) if len(sols) else np.zeros((0, len(names)))
    # among tolerance-equal vectors prefer the smoothest path, then the shortest
    pick = np.lexsort((n_straight + SQRT2 * n_diag, turns))
    keep = _front_filter(np.ascontiguousarray(F), pick)
    keep = keep[np.lexsort(F[keep].T[::-1])]
    cells, offsets = _trace_parents(li, pc, sols[keep], w)
    paths = [cells[offsets[i] : offsets[i + 1]] for i in range(len(keep))]
    stats = {
        "expansions": int(st[S_EXPANDED]),
        "generated": int(st[S_GENERATED]),
        # rows used at the peak and the parent entries: an upper bound of the labels held
        "labels": int(st[S_N] + st[S_PC]),
        "peak_bytes": int(peak),
        "solutions": int(st[S_SOLS]),
        "state_tests": int(st[S_STATE_TESTS]),
        "set_sizes": _set_sizes(sidx),
        "goal_tests": int(st[S_GOAL_TESTS]),
        "state_nodes": int(st[S_STATE_NODES]),
        "goal_nodes": int(st[S_GOAL_NODES]),
        "drop_nodes": int(st[S_DROP_NODES]),
        "built": int(st[S_BUILT]),
        "heuristic_seconds": t_heur,
        "seconds": time.perf_counter() - t0,
        "search": "k-objective",
        "timed": bool(timed),
        "complete": not stop,
    }
    return exact.ExactFront(
        objectives=names,
        F=F[keep],
        paths=paths,
        profiles=None,
        smoothness=(turns * QUARTER_PI)[keep],
        stats=stats,
    )
