"""``gapath plan``: one path by a graph-search planner over a layered costmap.

Writes the same files as ``gapath solve`` (``front.csv`` with one row,
``paths.json``, ``summary.json``, ``front.png``, ``paths.png``) through
:func:`gapath.results.write_front`.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

#: Layers ``--layers`` accepts.
LAYERS = ("elevation", "solar", "risk")


def register(subparsers) -> None:
    from gapath.cli import _cell
    from gapath.commands.dynamic import add_planner_choices
    from gapath.planners.pareto import PLANNERS

    p = subparsers.add_parser(
        "plan", help="plan one path: A*, D* Lite, A*-PO or D*-PO over costmap layers, "
                     "or hybrid A* / RRT / RRT* for a car-like robot")
    p.add_argument("map", help="map file or 'default' (see 'gapath solve')")
    kinematic = add_planner_choices(p)
    p.add_argument("--planner", choices=tuple(PLANNERS) + tuple(kinematic), default="dstar-po",
                   help="astar / dstar-lite: normalised weighted sum of the objectives; "
                        "astar-po / dstar-po: Pareto selection; hybrid-astar / rrt / rrt-star: "
                        "continuous paths (see 'gapath simulate') (default: %(default)s)")
    p.add_argument("--layers", default="elevation,solar,risk",
                   help="comma-separated cost layers used as objectives besides the length, "
                        "among elevation, solar, risk; '' for length only (default: %(default)s)")
    p.add_argument("--dem", metavar="FILE",
                   help="elevation raster (.npy or .npz) resampled to the grid; default: "
                        "seeded fractal terrain")
    p.add_argument("--dem-method", choices=("bilinear", "reflect"), default="bilinear",
                   help="bilinear: stretch the DEM over the grid; reflect: one pixel per cell, "
                        "tiled with reflection (default: %(default)s)")
    p.add_argument("--terrain-seed", type=int, default=1,
                   help="seed of the fractal terrain when no --dem is given (default: %(default)s)")
    p.add_argument("--risk", type=_cell, metavar="R,C",
                   help="the maximum-risk cell (default: the centre of the grid)")
    p.add_argument("--solar-rate", type=float, default=0.01,
                   help="rotation of the solar vector per path step, radians (default: %(default)s)")
    p.add_argument("--priority", default=None,
                   help="Pareto planners: objective name or 'sum' choosing among non-dominated "
                        "open nodes (default: length)")
    p.add_argument("--start", type=_cell, help="start cell ROW,COL (default: bottom-left)")
    p.add_argument("--goal", type=_cell, help="goal cell ROW,COL (default: top-right)")
    cc = p.add_mutually_exclusive_group()
    cc.add_argument("--corner-cutting", dest="corner_cutting", action="store_true", default=None)
    cc.add_argument("--no-corner-cutting", dest="corner_cutting", action="store_false")
    p.add_argument("--out", default="gapath-plan", help="output directory (default: %(default)s)")
    p.add_argument("--no-plots", action="store_true", help="skip front.png and paths.png")
    p.add_argument("--quiet", action="store_true", help="no report")
    p.set_defaults(func=run)


def build_costmap(workspace, layers, *, dem=None, dem_method="bilinear", terrain_seed=1,
                  risk=None, solar_rate=0.01):
    """The costmap ``gapath plan`` uses (see its options).

    Raises
    ------
    ConfigError
        On an unknown layer or a bad DEM, risk cell or solar rate.
    """
    from gapath.costmap import Costmap, fractal_terrain
    from gapath.errors import ConfigError

    for name in layers:
        if name not in LAYERS:
            raise ConfigError(f"unknown layer {name!r}; expected some of {', '.join(LAYERS)}")
    cm = Costmap(workspace, solar_rate=solar_rate)
    if "elevation" in layers:
        if dem is not None:
            cm.set_elevation(Path(dem), method=dem_method)
        else:
            cm.set_elevation(fractal_terrain(workspace.shape, seed=terrain_seed))
    if "risk" in layers:
        h, w = workspace.shape
        cm.set_risk((h // 2, w // 2) if risk is None else risk)
    return cm


def run(args) -> int:
    from gapath.cli import _load
    from gapath.front import PathFront
    from gapath.objectives import evaluate_paths, pad_paths
    from gapath.planners.pareto import plan
    from gapath.results import versions, write_front

    ws = _load(args.map, args.start, args.goal, args.corner_cutting)
    from gapath.commands.dynamic import PLANNER_CHOICES, plan_with, write_plan

    if args.planner in PLANNER_CHOICES:
        outcome = plan_with(args.planner, ws, args)
        write_plan(outcome, ws, args.out, plots=not args.no_plots)
        if not args.quiet:
            print(f"{ws!r}\n{args.planner}: " + ", ".join(
                f"{k}={v:.4g}" for k, v in outcome.objectives.items()) + f"; wrote {args.out}")
        return 0
    layers = [s.strip() for s in args.layers.split(",") if s.strip()]
    cm = build_costmap(ws, layers, dem=args.dem, dem_method=args.dem_method,
                       terrain_seed=args.terrain_seed, risk=args.risk, solar_rate=args.solar_rate)
    objectives = ("length",) + tuple(layers)
    t0 = time.perf_counter()
    res = plan(cm, args.planner, objectives, priority=args.priority)
    seconds = time.perf_counter() - t0
    P, L = pad_paths([res.path])
    metrics = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    front = PathFront(res.objectives, res.F[None, :], metrics, np.empty((1, 0)), [res.path])
    terrain = None
    if "elevation" in layers:
        terrain = (f"{args.dem} ({args.dem_method})" if args.dem
                   else f"fractal seed={args.terrain_seed}")
    summary = {
        "settings": dict(map=ws.name, shape=list(ws.shape), start=list(ws.start),
                         goal=list(ws.goal), cell_size=ws.cell_size,
                         corner_cutting=ws.corner_cutting, planner=args.planner,
                         objectives=list(objectives), priority=args.priority,
                         terrain=terrain, risk_cells=[list(c) for c in cm.risk_cells],
                         solar_rate=cm.solar_rate, algorithm=args.planner),
        "versions": versions(),
        "wall_time_s": round(seconds, 4),
        "expansions": res.expansions,
        "front_size": 1,
        "objectives": res.values,
        "search_cost": dict(zip(res.objectives, map(float, res.search_cost))),
    }
    write_front(Path(args.out), ws, front, summary, plots=not args.no_plots)
    if not args.quiet:
        vals = ", ".join(f"{k}={v:.4f}" for k, v in res.values.items())
        print(f"{ws!r}\n{args.planner}: {len(res.path)} cells, {vals}; {res.expansions} "
              f"expansions in {seconds * 1000:.1f} ms\nwrote {args.out}/front.csv, paths.json, "
              f"summary.json" + ("" if args.no_plots else ", front.png, paths.png"))
    return 0
