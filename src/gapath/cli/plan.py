"""``gapath plan``: one path by a graph-search planner, by default the shortest.

Without ``--layers`` every grid planner (``astar``, ``dstar-lite``,
``astar-po``, ``dstar-po``) returns a shortest path under the map's corner
rule; ``--layers elevation,solar,risk`` adds Lavin's cost layers as
objectives (the weighted-sum planners then minimise a normalised sum, the
Pareto planners select among non-dominated paths), and ``--layers slope``
with ``--layer slope=FILE`` a user layer. The layer flags (``--dem``,
``--risk``, ``--solar-rate``, ``--layer``, ...) are those of
:func:`gapath.cli._args.add_costmap_arguments`, shared with ``gapath
solve`` and ``gapath exact``. Writes the same files as
``gapath solve`` (``front.csv`` with one row, ``paths.json``,
``summary.json``, ``front.png``, ``paths.png``) through
:func:`gapath.results.write_front`. The planning time excludes numba's
compilation: the planner is first run on a tiny map, and that warm-up is
reported as ``compile_s``.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from gapath.costmap import PLAN_LAYERS as LAYERS  # the layers --layers accepts


def register(subparsers) -> None:
    from gapath.cli._args import add_costmap_arguments, add_map_arguments
    from gapath.cli.simulate import add_planner_choices
    from gapath.planners.registry import PLANNERS

    p = subparsers.add_parser(
        "plan",
        help="plan one path: the shortest by A*, D* Lite, A*-PO or D*-PO (Lavin's cost "
        "layers with --layers), or hybrid A* / RRT / RRT* for a car-like robot",
    )
    add_map_arguments(p)
    add_planner_choices(p)
    p.add_argument(
        "--planner",
        choices=tuple(PLANNERS),
        default="dstar-po",
        help="astar / dstar-lite / astar-po / dstar-po: a shortest path, or with "
        "--layers a normalised weighted sum (astar, dstar-lite) or a Pareto "
        "selection (astar-po, dstar-po) of the length and the layers; "
        "hybrid-astar / rrt / rrt-star: continuous paths (see 'gapath "
        "simulate') (default: %(default)s)",
    )
    p.add_argument(
        "--layers",
        default="",
        help="comma-separated cost layers used as objectives besides the length, "
        "among elevation, solar, risk (Lavin's) and the --layer NAME=FILE user "
        "layers; default none: the shortest path",
    )
    add_costmap_arguments(p)
    p.add_argument(
        "--priority",
        default=None,
        help="Pareto planners: objective name or 'sum' choosing among non-dominated "
        "open nodes (default: length)",
    )
    p.add_argument("--out", default="gapath-plan", help="output directory (default: %(default)s)")
    p.add_argument("--no-plots", action="store_true", help="skip front.png and paths.png")
    p.add_argument("--quiet", action="store_true", help="no report")
    p.set_defaults(func=run)


def parse_layers(text, args=None) -> list[str]:
    """The ``--layers`` names; with ``args``, the ``--layer NAME=FILE`` user
    layers are known names too (the layer flags given without their layer
    are refused by :func:`gapath.cli._args.costmap_from_args`).

    Raises
    ------
    ConfigError
        On an unknown or repeated layer, or a worst-cell ``<layer>_max``
        (the planners minimise sums).

    Examples
    --------
    >>> parse_layers("elevation, risk")
    ['elevation', 'risk']
    >>> parse_layers("")
    []
    """
    from gapath.cli._args import layer_objectives

    layers = [s.strip() for s in str(text).split(",") if s.strip()]
    user = [n for n, _ in (getattr(args, "layer", None) or [])]
    layer_objectives(layers, user, kind="plan", flag="--layers")
    return layers


def _tiny_costmap(tiny, costmap, layers, args):
    """A costmap over the warm-up map with the layers of ``costmap`` (or,
    without it, those :func:`gapath.costmap.build_costmap` makes for
    ``layers``), so that the warm-up compiles the same kernels."""
    from gapath.costmap import build_costmap

    if costmap is None:
        seed = getattr(args, "terrain_seed", None)
        rate = getattr(args, "solar_rate", None)
        return build_costmap(
            tiny,
            [n for n in layers if n in LAYERS],
            terrain_seed=1 if seed is None else seed,
            solar_rate=0.01 if rate is None else rate,
        )
    user = {
        n: np.zeros(tiny.shape)
        for n in costmap.names
        if n not in ("distance", "heuristic", "solar", "elevation", "risk")
    }
    return build_costmap(
        tiny,
        [n for n in layers if n in LAYERS],
        solar_rate=costmap.solar_rate,
        user_layers=user,
    )


def warm_up(planner, objectives, layers, args, corner_cutting, costmap=None) -> float:
    """Run ``planner`` once on a tiny map so that numba compiles (or loads
    from its cache) the kernels before the timed run; returns the seconds.
    ``costmap``: the run's, whose layers the tiny map's costmap copies."""
    from gapath.errors import GapathError
    from gapath.planners import plan
    from gapath.workspace import Workspace

    t0 = time.perf_counter()
    tiny = Workspace(np.zeros((5, 5), bool), corner_cutting=corner_cutting, name="warm-up")
    try:
        cm = _tiny_costmap(tiny, costmap, layers, args)
        plan(tiny, planner, costmap=cm, objectives=objectives, priority=args.priority)
    except GapathError:
        pass  # a bad option is reported by the real run
    return time.perf_counter() - t0


def warm_up_kinematic(planner) -> float:
    from gapath.errors import GapathError
    from gapath.planners import plan
    from gapath.workspace import Workspace

    t0 = time.perf_counter()
    try:
        plan(Workspace(np.zeros((12, 12), bool), name="warm-up"), planner, seed=1)
    except GapathError:
        pass
    return time.perf_counter() - t0


def _plan_kinematic(args, choice) -> int:
    from gapath.cli._args import update_summary
    from gapath.cli.simulate import plan_with, write_plan

    ws = choice.workspace
    compile_s = warm_up_kinematic(args.planner)
    outcome = plan_with(args.planner, ws, args)
    write_plan(outcome, ws, args.out, plots=not args.no_plots)
    length = float(outcome.objectives["length"])
    update_summary(
        args.out,
        {"compile_s": round(compile_s, 4), "scenario": choice.scenario_record(length)},
        choice.settings(),
    )
    if not args.quiet:
        print(
            f"{ws!r}\n{args.planner}: "
            + ", ".join(f"{k}={v:.4g}" for k, v in outcome.objectives.items())
            + f" in {outcome.seconds * 1000:.1f} ms (numba warm-up {compile_s * 1000:.0f} ms "
            f"not counted); wrote {args.out}"
        )
        if choice.scenario is not None:
            print(choice.scenario_line(length, f"{args.planner} length"))
    return 0


def run(args) -> int:
    from gapath.cli._args import costmap_from_args, costmap_settings, load_workspace
    from gapath.costmap import build_costmap
    from gapath.front import PathFront
    from gapath.planners import plan, planner_info
    from gapath.results import versions, write_front

    layers = parse_layers(args.layers, args)
    choice = load_workspace(args)
    ws = choice.workspace
    if planner_info(args.planner).family == "kinematic":
        costmap_from_args(args, ws, layers, kind="plan", flag="--layers")  # no stray layer flag
        return _plan_kinematic(args, choice)
    cm = costmap_from_args(args, ws, layers, kind="plan", flag="--layers")
    if cm is None:
        cm = build_costmap(ws, [])
    objectives = ("length",) + tuple(layers)
    compile_s = warm_up(args.planner, objectives, layers, args, ws.corner_cutting, costmap=cm)
    res = plan(ws, args.planner, costmap=cm, objectives=objectives, priority=args.priority)
    seconds = res.seconds
    front = PathFront.from_paths(ws, [res.cells], tuple(res.objectives), res.F[None, :])
    terrain = None
    if "elevation" in layers:
        if args.dem:
            terrain = f"{args.dem} ({args.dem_method or 'bilinear'})"
        else:
            terrain = f"fractal seed={1 if args.terrain_seed is None else args.terrain_seed}"
    summary = {
        "settings": {
            **ws.describe(),
            "planner": args.planner,
            "objectives": list(objectives),
            "layers": layers,
            "priority": args.priority,
            "terrain": terrain,
            "risk_cells": [list(c) for c in cm.risk_cells],
            "solar_rate": cm.solar_rate if "solar" in layers else None,
            "algorithm": args.planner,
            **choice.settings(),
        },
        "versions": versions(),
        "wall_time_s": round(seconds, 4),
        "compile_s": round(compile_s, 4),
        "expansions": res.info["expansions"],
        "front_size": 1,
        "objectives": res.objectives,
        "search_cost": res.info["search_cost"],
    }
    if layers:
        summary["settings"]["costmap"] = costmap_settings(args, cm, layers, kind="plan")
    length = float(res.objectives["length"])
    if choice.scenario is not None:
        summary["scenario"] = choice.scenario_record(length)
    write_front(Path(args.out), ws, front, summary, plots=not args.no_plots)
    if not args.quiet:
        vals = ", ".join(f"{k}={v:.4f}" for k, v in res.objectives.items())
        what = "shortest path" if not layers else f"length and {', '.join(layers)}"
        print(
            f"{ws!r}\n{choice.corner_line()}\n{args.planner} ({what}): {len(res.cells)} cells, "
            f"{vals}; {res.info['expansions']} expansions in {seconds * 1000:.1f} ms (numba warm-up "
            f"{compile_s * 1000:.0f} ms not counted)\nwrote {args.out}/front.csv, paths.json, "
            f"summary.json" + ("" if args.no_plots else ", front.png, paths.png")
        )
        if choice.scenario is not None:
            print(choice.scenario_line(length, f"{args.planner} length"))
    return 0
