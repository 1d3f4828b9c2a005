"""``gapath exact``: the exact Pareto front of a map."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np


def register(subparsers) -> None:
    from gapath.commands._args import add_map_arguments

    p = subparsers.add_parser("exact", help="compute the exact Pareto front (monotone or free paths)")
    add_map_arguments(p)
    p.add_argument("--objectives", default="length,vulnerability",
                   help="comma-separated objectives among length, vulnerability, smoothness "
                        "(default: %(default)s)")
    p.add_argument("--mode", choices=("monotone", "free"), default="monotone",
                   help="column-monotone paths (the GA's path set) or all 8-connected paths "
                        "(default: %(default)s)")
    p.add_argument("--out", default="gapath-exact", help="output directory (default: %(default)s)")
    p.add_argument("--no-plots", action="store_true", help="skip front.png and paths.png")
    p.add_argument("--quiet", action="store_true", help="no report")
    p.set_defaults(func=run)


def exact_path_front(workspace, objectives, mode):
    """The exact front as a :class:`gapath.front.PathFront`."""
    from gapath.front import PathFront
    from gapath.objectives import evaluate_paths, pad_paths
    from gapath.planners import exact

    solver = exact.monotone_front if mode == "monotone" else exact.free_front
    ef = solver(workspace, objectives)
    P, L = pad_paths(ef.paths)
    metrics = evaluate_paths(P, L, workspace.occ, workspace.potential, workspace.cell_size,
                             workspace.corner_cutting)
    return PathFront(tuple(ef.objectives), ef.F, metrics, np.empty((len(ef.F), 0)), list(ef.paths))


def run(args) -> int:
    from gapath.commands._args import load_workspace
    from gapath.errors import NoPathError
    from gapath.results import versions, write_front

    choice = load_workspace(args)
    ws = choice.workspace
    objectives = [o.strip() for o in args.objectives.split(",") if o.strip()]
    t0 = time.perf_counter()
    try:
        front = exact_path_front(ws, objectives, args.mode)
    except NoPathError as exc:               # exit status 1, with the reason and what to try
        from gapath.cli import no_path_error

        why = no_path_error(ws, monotone=args.mode == "monotone",
                            free_hint="try --mode free (the exact front of all 8-connected paths)")
        raise (why or exc) from None
    seconds = time.perf_counter() - t0
    summary = {
        "settings": dict(map=ws.name, shape=list(ws.shape), start=list(ws.start), goal=list(ws.goal),
                         cell_size=ws.cell_size, corner_cutting=ws.corner_cutting,
                         objectives=list(front.objectives), mode=args.mode, algorithm="exact"),
        "versions": versions(),
        "wall_time_s": round(seconds, 4),
        "front_size": len(front),
    }
    summary["settings"].update(choice.settings())
    shortest = (float(front.F[:, front.objectives.index("length")].min())
                if len(front) and "length" in front.objectives else None)
    if choice.scenario is not None:
        summary["scenario"] = choice.scenario_record(shortest)
    write_front(Path(args.out), ws, front, summary, plots=not args.no_plots)
    if not args.quiet:
        print(f"{ws!r}\n{choice.corner_line()}\nexact {args.mode} front: {len(front)} paths in "
              f"{seconds:.3f} s; wrote {args.out}/front.csv, paths.json, summary.json")
        if choice.scenario is not None:
            print(choice.scenario_line(shortest, f"shortest length on the {args.mode} front"))
    return 0
