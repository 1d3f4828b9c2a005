"""``gapath scen``: check a grid planner against a MovingAI scenario file.

``gapath scen FILE [--planner astar] [--limit N] [--map MAP]`` plans every
line of a ``.scen`` file (the first ``N`` with ``--limit``) with the planner
``gapath plan`` uses, under MovingAI's rule (no corner cutting, the rule its
optima assume), and compares each length with the line's optimal length:
a length matches when ``abs(length - optimal) <= 1e-5 * max(1, optimal)``
(the files print 6 significant digits or 8 decimals). It prints
``matched/total`` and the lines that do not match; the exit status is 0
when every line matches and 1 otherwise (2 for bad input).

The map of a line is its map name (basename) looked up next to the
``.scen`` file, or ``--map`` when given.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

#: How many differing lines the report lists.
SHOWN = 10


def register(subparsers) -> None:
    from gapath.planners.registry import planner_names

    p = subparsers.add_parser(
        "scen", help="check a grid planner against every optimum of a MovingAI .scen file"
    )
    p.add_argument("file", metavar="FILE", help="MovingAI scenario file (.scen)")
    p.add_argument(
        "--planner",
        choices=planner_names("grid"),
        default="astar",
        help="grid planner, as in 'gapath plan' without --layers (default: %(default)s)",
    )
    p.add_argument(
        "--limit", type=int, default=None, metavar="N", help="check only the first N scenarios (default: all)"
    )
    p.add_argument(
        "--map", default=None, metavar="MAP", help="the map file (default: each line's map, next to FILE)"
    )
    p.add_argument("--quiet", action="store_true", help="print only the matched/total line")
    p.set_defaults(func=run)


def check_scenarios(scenarios, planner="astar", map_path=None, on_line=None):
    """Plan every scenario and compare its length with the optimum.

    Parameters
    ----------
    scenarios : list of :class:`gapath.loaders.Scenario`
    planner : {"astar", "dstar-lite", "astar-po", "dstar-po"}
    map_path : path-like, optional
        The map of every line (default: each line's map next to its file).
    on_line : callable, optional
        Called with ``(scenario, length or None, matches)`` after each line.

    Returns
    -------
    list of (Scenario, float or None, bool)
        The length found (None when no path was found) and whether it
        matches the optimum.

    Raises
    ------
    MapError
        If a map is missing or malformed.
    ConfigError
        If a map's size differs from its scenario's.
    """
    from gapath.cli._args import matches_optimum
    from gapath.errors import ConfigError, NoPathError
    from gapath.loaders import load_occupancy
    from gapath.planners import plan
    from gapath.workspace import Workspace

    maps: dict[Path, np.ndarray] = {}
    out = []
    for sc in scenarios:
        path = Path(map_path) if map_path is not None else sc.resolve_map()
        occ = maps.get(path)
        if occ is None:
            occ = maps[path] = load_occupancy(path)
        if occ.shape != (sc.height, sc.width):
            raise ConfigError(
                f"{sc.source}, line {sc.line}: the scenario is for a {sc.width}x"
                f"{sc.height} map (width x height), {path} is "
                f"{occ.shape[1]}x{occ.shape[0]}"
            )
        if sc.start == sc.goal:
            length = 0.0
        else:
            ws = Workspace(occ, sc.start, sc.goal, corner_cutting=False, name=path.stem)
            try:
                length = float(plan(ws, planner, objectives=("length",)).result.length)
            except NoPathError:
                length = None
        ok = matches_optimum(length, sc.optimal)
        out.append((sc, length, ok))
        if on_line is not None:
            on_line(sc, length, ok)
    return out


def run(args) -> int:
    from gapath.cli.plan import warm_up
    from gapath.errors import ConfigError, positive_int
    from gapath.loaders import load_scenarios

    if args.limit is not None:
        positive_int(args.limit, "--limit")
    scenarios = load_scenarios(args.file)
    if not scenarios:
        raise ConfigError(f"{args.file}: the file holds no scenario")
    scenarios = scenarios[: args.limit]
    import argparse

    compile_s = warm_up(
        args.planner,
        ("length",),
        [],
        argparse.Namespace(terrain_seed=1, solar_rate=0.01, priority=None),
        False,
    )
    t0 = time.perf_counter()
    results = check_scenarios(scenarios, args.planner, args.map)
    seconds = time.perf_counter() - t0
    bad = [(sc, length) for sc, length, ok in results if not ok]
    if not args.quiet:
        for sc, length in bad[:SHOWN]:
            found = "no path" if length is None else f"{length:.8g} ({length - sc.optimal:+.3g})"
            print(
                f"  line {sc.line}: start {sc.start[0]},{sc.start[1]} goal "
                f"{sc.goal[0]},{sc.goal[1]} (ROW,COL): optimum {sc.optimal:.8g}, found {found}"
            )
        if len(bad) > SHOWN:
            print(f"  ... and {len(bad) - SHOWN} more")
    print(
        f"{args.file}: {len(results) - len(bad)}/{len(results)} scenarios match the MovingAI "
        f"optimum ({args.planner}, no corner cutting, tolerance 1e-5 relative; "
        f"{seconds:.2f} s, numba warm-up {compile_s:.2f} s not counted)"
    )
    return 0 if not bad else 1
