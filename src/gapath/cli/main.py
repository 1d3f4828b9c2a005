"""The ``gapath`` command line.

``gapath solve MAP ...`` runs Ahmed & Deb's NSGA-II on a map and writes
``front.csv``, ``paths.json``, ``summary.json``, ``front.png`` and
``paths.png``; ``gapath demo`` does so on the bundled scenario.

Exit statuses, the same for every command (:mod:`gapath.errors`, README
"Exit status"): 0 a result was found; 1 the search ran but found nothing
feasible (the reason and what to try are printed); 2 bad input (one message
naming the flag, file or value, no traceback); 3 an internal error (a bug:
one message; ``GAPATH_TRACEBACK=1`` shows the traceback); 130 interrupted
(partial results written).
"""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import sys
from collections.abc import Iterator
from pathlib import Path

from gapath.errors import (
    EXIT_BAD_INPUT,
    EXIT_INTERNAL,
    EXIT_INTERRUPTED,
    EXIT_NO_RESULT,
    ConfigError,
    GapathError,
    MapError,
    NoPathError,
)


def _load(map_arg, start=None, goal=None, corner_cutting=None):
    """The workspace of the map arguments: ``_load(args)`` with a parsed
    namespace (MAP, --start/--goal, --start-xy/--goal-xy, --scen, corner
    rule: :func:`gapath.cli._args.load_workspace`), or
    ``_load(MAP, start, goal, corner_cutting)``."""
    from gapath.cli._args import load_workspace

    if isinstance(map_arg, argparse.Namespace):
        return load_workspace(map_arg).workspace
    args = argparse.Namespace(
        map=map_arg,
        start=start,
        goal=goal,
        corner_cutting=corner_cutting,
        start_xy=None,
        goal_xy=None,
        scen=None,
    )
    return load_workspace(args).workspace


def _solve(args) -> int:
    """``gapath solve``: the map arguments, the run, then the corner rule and
    the ``--scen`` optimum in the report and in ``summary.json``."""
    from gapath.cli._args import load_workspace, shortest_in_csv, update_summary

    choice = load_workspace(args)
    code = _run(args, choice.workspace)
    shortest = shortest_in_csv(Path(args.out) / "front.csv") if choice.scenario else None
    update_summary(args.out, {"scenario": choice.scenario_record(shortest)}, choice.settings())
    if not args.quiet:
        print(choice.corner_line())
        if choice.scenario is not None:
            print(choice.scenario_line(shortest, "shortest length on the front"))
    return code


def _add_run_options(p: argparse.ArgumentParser, *, pop: int, gen: int, out: str | None) -> None:
    p.add_argument(
        "--objectives",
        default="length,vulnerability",
        help="comma-separated objectives among length, vulnerability, smoothness and the "
        "costmap layers: elevation, risk, solar, a --layer NAME (the mean over the "
        "path's cells; solar summed over the steps) and <layer>_max (the worst cell, "
        "e.g. risk_max) (default: %(default)s)",
    )
    p.add_argument(
        "--encoding",
        default=None,
        help="genome encoding: integer, binary, mixed or absolute for monotone paths "
        "(default integer); field or via for free paths (default field)",
    )
    p.add_argument(
        "--constraints",
        choices=("penalty", "constraint", "adaptive"),
        default=None,
        help="obstacle handling (default: penalty; constraint for one objective; adaptive: "
        "a penalty starting at --penalty that adapts to the share of feasible paths)",
    )
    p.add_argument(
        "--repair",
        default="edge",
        help="repair of new genomes (with --paths monotone and the fast engine): edge (default: Ahmed & Deb's "
        "edge-fixing), feasible-local (then every column step on an obstacle moved to the nearest "
        "free exit row), feasible-reach, feasible-local-half, feasible-reach-half",
    )
    p.add_argument(
        "--sbx-eta",
        type=float,
        default=None,
        help="SBX distribution index (default: 10; 2 for one objective)",
    )
    p.add_argument(
        "--penalty", type=float, default=1000.0, help="penalty per interfering cell (default: %(default)s)"
    )
    p.add_argument(
        "--tiebreak",
        choices=("smoothness", "none"),
        default="smoothness",
        help="tie-break inside a non-dominated rank (default: %(default)s)",
    )
    p.add_argument(
        "--seed-from",
        choices=("weighted", "exact", "astar", "none"),
        default="weighted",
        help="initial population: shortest, safest and weighted-sum monotone paths "
        "plus random ones (weighted), the exact monotone front (exact), A* "
        "paths projected onto monotone paths (astar), or all random as in "
        "Ahmed & Deb's protocol (none) (default: %(default)s)",
    )
    p.add_argument(
        "--engine",
        choices=("fast", "pymoo"),
        default="fast",
        help="NSGA-II engine: FastNSGA2 on arrays (fast) or stock pymoo NSGA2 (pymoo); "
        "same results for the same seed (default: %(default)s)",
    )
    p.add_argument("--pop", type=int, default=pop, help="population size (default: %(default)s)")
    p.add_argument("--gen", type=int, default=gen, help="generations (default: %(default)s)")
    p.add_argument("--seed", type=int, default=1, help="random seed (default: %(default)s)")
    p.add_argument(
        "--runs",
        type=int,
        default=1,
        help="independent runs with seeds SEED..SEED+RUNS-1, each written to "
        "OUT/runs/<seed>/, their merged front to OUT (default: %(default)s)",
    )
    p.add_argument("--out", default=out, help="output directory (default: %(default)s)")
    p.add_argument(
        "--reference",
        metavar="monotone|free|FILE",
        help="judge the front against the exact monotone front, the exact free front "
        "or a front.csv: adds hypervolume ratio, IGD+ and the share of reference "
        "points found to summary.json",
    )
    p.add_argument(
        "--threads",
        metavar="N|auto",
        default=None,
        help="threads for the free-path GA's batches of searches and generation 1's second "
        "search (the same results as one thread; sets GAPATH_THREADS; auto: every core numba "
        "sees, at most 4) (default: GAPATH_THREADS, else 1)",
    )
    p.add_argument("--no-plots", action="store_true", help="skip front.png and paths.png")
    p.add_argument("--quiet", action="store_true", help="no progress bar or report")


def _version() -> str:
    from importlib import metadata

    try:
        return metadata.version("gapath")
    except metadata.PackageNotFoundError:  # a source tree on PYTHONPATH
        from gapath import __version__

        return __version__


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="gapath",
        description="Multi-objective grid path planning with pymoo.",
        epilog="exit status: 0 a result was found, 1 the search found nothing feasible "
        "(the reason is printed), 2 bad input, 3 internal error, 130 interrupted",
    )
    parser.add_argument("--version", action="version", version=f"gapath {_version()}")
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("solve", help="run NSGA-II on a map and write its Pareto front")
    from gapath.cli._args import add_map_arguments

    add_map_arguments(p)
    _add_run_options(p, pop=500, gen=500, out="gapath-out")
    p.add_argument(
        "--paths",
        choices=("free", "monotone"),
        default="free",
        help="path set: any simple 8-connected path (free) or Ahmed & Deb's "
        "column-monotone paths (monotone) (default: %(default)s)",
    )
    p.add_argument(
        "--refine",
        default="auto",
        help="archived paths re-routed per generation, auto (free paths: pop/2 with two "
        "objectives, 16 x pop with three or more among which smoothness, 2 x pop with other "
        "three or more; monotone paths: pop/5), an integer >= 0, or off "
        "(no archive: the last population's front) (default: %(default)s)",
    )
    from gapath.cli._args import add_costmap_arguments

    add_costmap_arguments(p)
    p.set_defaults(func=_solve)

    d = sub.add_parser("demo", help="the bundled scenario with Ahmed & Deb's settings")
    _add_run_options(d, pop=500, gen=500, out="gapath-demo")

    from gapath.cli import exact, experiment, plan, scen, simulate

    for command in (exact, experiment, simulate, plan, scen):  # help order
        command.register(sub)
    return parser


def _report(result, out_dir: Path) -> None:
    front = result.front
    print(f"{result.workspace!r}")
    status = "interrupted after" if result.interrupted else "finished"
    print(
        f"{status} {result.n_gen} generations, {result.n_eval} evaluations, "
        f"{result.seconds:.1f} s; {len(front)} non-dominated feasible paths"
    )
    asked = result.settings.get("n_gen")
    if not result.interrupted and isinstance(asked, int) and result.n_gen < asked:
        print(
            f"  stopped before generation {asked}: mating found no path not yet in the "
            f"population (the map has few distinct paths)"
        )
    for label, i in front.marked().items():
        values = ", ".join(f"{n}={v:.4f}" for n, v in zip(front.objectives, front.F[i]))
        print(f"  {label:9s} {values}")
    print(
        f"wrote {out_dir}/front.csv, paths.json, summary.json"
        + ("" if result.settings.get("plots") is False else ", front.png, paths.png")
    )


def _objective_names(args) -> list[str]:
    return [o.strip() for o in str(args.objectives).split(",") if o.strip()]


def _reference(args, workspace, costmap=None):
    if not args.reference:
        return None
    from gapath.objectives import check_objective_names
    from gapath.reference import reference_front

    layers = () if costmap is None else costmap.objective_names + costmap.max_objective_names
    names = check_objective_names(_objective_names(args), layers)
    layered = [n for n in names if n in layers and n != "length"]
    try:
        if layered and args.reference in ("monotone", "free"):
            # the exact free front takes solar (a sum over the steps); no exact
            # front has the GA's means or worst cells, nor the monotone one any layer
            means = [n for n in layered if n != "solar"]
            if means or args.reference == "monotone":
                what = means[0] if means else "solar"
                why = (
                    "a mean or a worst cell over the path is not a sum along it"
                    if means
                    else "the exact monotone front has no costmap layers"
                )
                raise ConfigError(
                    f"no exact {args.reference} front exists for objective {what!r} ({why}); "
                    f"give --reference FILE (a front.csv with the columns {','.join(names)})"
                )
            from gapath.planners.exact import free_front

            return free_front(workspace, tuple(names), costmap=costmap).F
        return reference_front(workspace, names, args.reference)
    except (ConfigError, MapError) as exc:
        raise type(exc)(f"--reference: {exc}") from None


def _quality(args, reference, F) -> dict:
    if reference is None:
        return {}
    from gapath.reference import front_quality

    return {"quality": {"reference": str(args.reference), **front_quality(F, reference)}}


def _print_quality(extra: dict) -> None:
    if extra:
        q = extra["quality"]
        print(
            f"against the {q['reference']} reference: hv ratio {q['hv_ratio']:.4f}, "
            f"IGD+ {q['igd_plus']:.4g}, {q['reference_points_found']:.0%} of its points found"
        )


def _refine(args):
    """``--refine`` as ``solve``'s keyword: None (auto), False (off) or an integer."""
    text = str(getattr(args, "refine", "auto")).strip().lower()
    if not hasattr(args, "paths"):  # gapath demo: Ahmed & Deb's runs, no archive
        return None
    if text == "auto":  # monotone: the archive's default count (docs/results/monotone_lift.md)
        return None if args.paths == "free" else True
    if text == "off":
        return False
    try:
        n = int(text)
    except ValueError:
        n = -1
    if n < 0:
        raise ConfigError(f"--refine must be auto, off or an integer >= 0, got {args.refine!r}")
    return n


@contextlib.contextmanager
def _threads(value: str | None) -> Iterator[None]:
    """``--threads``, checked, given to the library as ``GAPATH_THREADS``
    (:func:`gapath.encodings.free.wanted_threads` reads it) for the run, and
    the variable restored after it."""
    if value is None:
        yield
        return
    from gapath.encodings.free import THREADS_ENV

    text = value.strip().lower()
    if text != "auto" and not (text.isdigit() and int(text) >= 1):
        raise ConfigError(f"--threads: expected a number of threads (1 or more) or 'auto', got {value!r}")
    before = os.environ.get(THREADS_ENV)
    os.environ[THREADS_ENV] = text
    try:
        yield
    finally:
        if before is None:
            del os.environ[THREADS_ENV]
        else:
            os.environ[THREADS_ENV] = before


def _run(args, workspace) -> int:
    with _threads(getattr(args, "threads", None)):
        return _run_with(args, workspace)


def _run_with(args, workspace) -> int:
    from gapath.cli._args import costmap_from_args, costmap_settings
    from gapath.results import write_result
    from gapath.solver import solve

    costmap = costmap_from_args(args, workspace, _objective_names(args))
    cm_settings = costmap_settings(args, costmap, _objective_names(args))
    kwargs = dict(
        objectives=args.objectives,
        encoding=args.encoding,
        constraints=args.constraints,
        penalty=args.penalty,
        pop_size=args.pop,
        n_gen=args.gen,
        tiebreak=None if args.tiebreak == "none" else args.tiebreak,
        sbx_eta=args.sbx_eta,
        seed_from=args.seed_from,
        engine=args.engine,
        progress=not args.quiet,
        paths=getattr(args, "paths", "monotone"),
        repair=args.repair,
        refine=_refine(args),
    )
    if costmap is not None:
        kwargs["costmap"] = costmap
        if args.seed_from == "exact" and kwargs["paths"] == "monotone":
            layered = [
                n for n in _objective_names(args) if n not in ("length", "vulnerability", "smoothness")
            ]
            raise ConfigError(
                f"--seed-from exact seeds from the exact monotone front, which has no costmap "
                f"layers ({', '.join(layered)}); use --seed-from weighted (the default) or --paths free"
            )
    if args.constraints == "adaptive" and args.engine == "pymoo":
        raise ConfigError(
            "--constraints adaptive needs --engine fast (the stock pymoo engine has no "
            "adaptive penalty); use --constraints penalty with --engine pymoo"
        )
    if args.repair != "edge" and (kwargs["paths"] != "monotone" or args.engine != "fast"):
        raise ConfigError(
            f"--repair {args.repair} needs --paths monotone and --engine fast "
            f"(got --paths {kwargs['paths']}, --engine {args.engine})"
        )
    out_dir = Path(args.out)
    if kwargs["paths"] == "free":  # no path at all: exit 1 with the reason, before the GA
        why = no_path_error(workspace, monotone=False)
        if why is not None:
            raise why
    reference = _reference(args, workspace, costmap)
    if args.runs != 1:
        return _multirun(args, workspace, kwargs, out_dir, reference, cm_settings)
    tracker = None
    if reference is not None:
        from gapath.convergence import HypervolumeRatioCallback

        tracker = HypervolumeRatioCallback(reference)
    result = solve(workspace, seed=args.seed, callback=tracker, **kwargs)
    if cm_settings is not None:
        result.settings["costmap"] = cm_settings
    extra = _quality(args, reference, result.front.F)
    write_result(result, out_dir, plots=not args.no_plots, extra=extra)
    if tracker is not None and tracker.history:
        _write_convergence(tracker, out_dir, plots=not args.no_plots)
    if not args.quiet:
        _report(result, out_dir)
        _print_quality(extra)
    if result.interrupted:
        return EXIT_INTERRUPTED
    if len(result.front) == 0:
        raise empty_front_error(workspace, result.n_gen, result.n_eval, free_hint=_exact_free_command(args))
    return 0


def _write_convergence(tracker, out_dir: Path, plots: bool) -> None:
    from gapath.convergence import plot_convergence
    from gapath.results import atomic_write

    rows = ["n_gen,n_eval,hv_ratio"] + [f"{int(g)},{int(e)},{h!r}" for g, e, h in tracker.history]
    atomic_write(out_dir / "convergence.csv", "\n".join(rows) + "\n")
    if plots:
        plot_convergence(tracker.history, out_dir / "convergence.png")


def _multirun(args, workspace, kwargs, out_dir: Path, reference, cm_settings=None) -> int:
    from gapath.experiments import multirun
    from gapath.results import write_front, write_result

    def write_run(r):
        if cm_settings is not None:
            r.settings["costmap"] = cm_settings
        write_result(r, out_dir / "runs" / str(r.settings["seed"]), plots=not args.no_plots)
        if not args.quiet:
            print(f"run {r.settings['seed']}: {len(r.front)} paths, {r.seconds:.1f} s", flush=True)

    m = multirun(workspace, runs=args.runs, seed=args.seed, on_run=write_run, **kwargs)
    extra = _quality(args, reference, m.front.F)
    write_front(out_dir, workspace, m.front, m.summary(extra), plots=not args.no_plots)
    if not args.quiet:
        print(
            f"merged front of {len(m.runs)} runs: {len(m.front)} paths; wrote {out_dir}/front.csv, "
            f"paths.json, summary.json and {out_dir}/runs/<seed>/"
        )
        _print_quality(extra)
    if m.interrupted:
        return EXIT_INTERRUPTED
    if len(m.front) == 0:
        raise empty_front_error(
            workspace,
            sum(r.n_gen for r in m.runs),
            sum(r.n_eval for r in m.runs),
            runs=len(m.runs),
            free_hint=_exact_free_command(args),
        )
    return 0


def no_path_error(workspace, *, monotone: bool = True, free_hint: str | None = None):
    """Why no feasible path joins the workspace's start and goal, as a
    :class:`NoPathError` with a hint, or None when a path of the asked kind
    exists.

    Start and goal in separate free regions: no path at all (the hint names
    ``--corner-cutting`` when allowing it would join them). With
    ``monotone``, a map whose every route steps back a column: no
    column-monotone path (the hint is ``free_hint``).

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> occ = np.array([[0, 1, 0], [0, 1, 0], [0, 1, 0]], bool)
    >>> print(no_path_error(Workspace(occ, (2, 0), (0, 2))))
    no path joins (2, 0) and (0, 2) at all: they lie in separate free regions of the 3x3 map (8-connected, corner cutting allowed)
    >>> no_path_error(Workspace(np.zeros((3, 3), bool))) is None
    True
    """
    from gapath.planners.astar import astar

    s, g = tuple(workspace.start), tuple(workspace.goal)
    try:
        astar(workspace)
    except NoPathError:
        h, w = workspace.shape
        rule = "allowed" if workspace.corner_cutting else "not allowed"
        hint = "check the map, --start and --goal"
        if not workspace.corner_cutting:
            try:
                astar(workspace.replace(corner_cutting=True))
                hint = "try --corner-cutting (diagonal moves past blocked corners join them)"
            except NoPathError:
                pass
        return NoPathError(
            f"no path joins {s} and {g} at all: they lie in separate free regions "
            f"of the {h}x{w} map (8-connected, corner cutting {rule})",
            hint=hint,
        )
    if not monotone:
        return None
    from gapath.planners.weighted_sum import weighted_sum_path

    try:
        weighted_sum_path(workspace)
    except NoPathError:
        return NoPathError(
            f"no column-monotone path joins {s} and {g}; every route must step back a column", hint=free_hint
        )
    return None


def _exact_free_command(args) -> str:
    cmd = ["gapath", "exact", getattr(args, "map", "default"), "--mode", "free"]
    for flag in ("start", "goal"):
        cell = getattr(args, flag, None)
        if cell is not None:
            cmd += [f"--{flag}", f"{cell[0]},{cell[1]}"]
    return (
        "try `--paths free` (the GA over all simple 8-connected paths) or `"
        + " ".join(cmd)
        + "` (their exact front)"
    )


def empty_front_error(
    workspace, n_gen: int, n_eval: int, runs: int = 1, free_hint: str | None = None
) -> NoPathError:
    """The :class:`NoPathError` of a GA run whose front is empty: no
    column-monotone path exists (:func:`no_path_error`; ``free_hint`` says
    what to try), or the GA found none of those that do."""
    err = no_path_error(workspace, free_hint=free_hint or "try `gapath exact MAP --mode free`")
    if err is not None:
        return err
    what = f"{runs} runs" if runs != 1 else "the run"
    return NoPathError(
        f"the GA found no feasible path ({what}: {n_gen} generations, {n_eval} evaluations), "
        f"although column-monotone paths join {tuple(workspace.start)} and {tuple(workspace.goal)}",
        hint="try --seed-from weighted (the default), or a larger --pop or --gen",
    )


#: Ranges of the numeric options of every command, by argparse ``dest``:
#: ``(low, low_included, high, high_included)``, None for no bound. Every
#: float option must also be finite (``nan`` and ``inf`` parse as floats).
NUMERIC_RANGES: dict[str, tuple] = {
    **{
        d: (0, True, None, False)
        for d in ("seed", "map_seed", "terrain_seed", "obstacles", "stationary", "workers", "large_runs")
    },
    **{
        d: (1, True, None, False)
        for d in ("pop", "gen", "runs", "iterations", "n", "size", "ga_pop", "ga_gen", "max_labels")
    },
    "heading_bins": (4, True, None, False),
    **{d: (0, True, None, False) for d in ("sbx_eta", "penalty", "radius", "sensor_range")},
    **{
        d: (0, False, None, False)
        for d in ("wheelbase", "speed", "dt", "max_time", "step", "arc_length", "heuristic_weight")
    },
    "goal_bias": (0, True, 1, True),
    "fov": (0, False, 180, True),
    "max_steer": (0, False, 90, False),
}


def check_numbers(args) -> None:
    """Check every numeric option of the parsed ``args``: floats finite, and
    values within :data:`NUMERIC_RANGES`.

    Raises
    ------
    ConfigError
        Naming the flag, the expected range and the value.

    Examples
    --------
    >>> check_numbers(argparse.Namespace(sbx_eta=float("nan")))
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: --sbx-eta must be a finite number, got nan
    >>> check_numbers(argparse.Namespace(seed=-1))
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: --seed must be an integer >= 0, got -1
    """
    for dest, value in vars(args).items():
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            continue
        flag = "--" + dest.replace("_", "-")
        kind = "an integer" if isinstance(value, int) else "a number"
        if isinstance(value, float) and not math.isfinite(value):
            raise ConfigError(f"{flag} must be a finite number, got {value!r}")
        if dest not in NUMERIC_RANGES:
            continue
        lo, lo_in, hi, hi_in = NUMERIC_RANGES[dest]
        below = lo is not None and (value < lo if lo_in else value <= lo)
        above = hi is not None and (value > hi if hi_in else value >= hi)
        if below or above:
            if hi is None:
                want = f"{'>=' if lo_in else '>'} {lo}"
            else:
                want = f"in {'[' if lo_in else '('}{lo}, {hi}{']' if hi_in else ')'}"
            raise ConfigError(f"{flag} must be {kind} {want}, got {value!r}")


def _default_hint(args) -> str | None:
    """What to try when ``gapath plan`` or ``simulate`` found no path."""
    planner = getattr(args, "planner", None) if args.command == "plan" else None
    if args.command == "simulate":
        return "check the map, --start and --goal"
    if planner in ("rrt", "rrt-star"):
        return f"try more --iterations (now {args.iterations}) or another --seed"
    if planner == "hybrid-astar":
        return "try a smaller --radius or a larger --max-steer (a tighter turn), or check --start and --goal"
    if planner is None:
        return None
    if getattr(args, "corner_cutting", None) is False:
        return "check the map, --start and --goal, or try --corner-cutting"
    return "check the map, --start and --goal"


def _no_result(exc: NoPathError, args) -> int:
    hint = exc.hint if getattr(exc, "hint", None) else _default_hint(args)
    hint = f" -- {hint}" if hint else ""
    print(f"gapath: {exc}{hint}", file=sys.stderr)
    return EXIT_NO_RESULT


def _dispatch(args) -> int:
    check_numbers(args)
    if getattr(args, "dem", None) is not None:
        from gapath.costmap import check_dem_file

        try:
            check_dem_file(args.dem)
        except ConfigError as exc:
            raise ConfigError(f"--dem: {exc}") from None
    out = getattr(args, "out", None)
    if out is not None:
        from gapath.results import check_output_dir

        check_output_dir(out)
    if getattr(args, "func", None) is not None:
        return args.func(args)
    from gapath.generators import default_workspace  # demo: every other command has its func

    return _run(args, default_workspace())


def _usage_exit(exc: SystemExit) -> SystemExit:
    """``SystemExit("message")`` (a command's own usage check) exits with
    status 2 after printing its message, as argparse's errors do; its text
    (``str(exc)``) is kept."""
    if isinstance(exc.code, str):
        print(exc.code, file=sys.stderr)
        exc.code = EXIT_BAD_INPUT
    return exc


def main(argv=None) -> int:
    """Run the ``gapath`` command line on ``argv`` (default: ``sys.argv[1:]``)
    and return its exit status (see the module docstring); ``--help``,
    ``--version`` and usage errors raise ``SystemExit`` as argparse does."""
    import matplotlib

    matplotlib.use("Agg")  # the CLI only writes image files (library modules leave the backend alone)
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:
        raise _usage_exit(exc) from None
    try:
        return _dispatch(args)
    except SystemExit as exc:
        raise _usage_exit(exc) from None
    except NoPathError as exc:
        return _no_result(exc, args)
    except GapathError as exc:
        print(f"gapath: error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("gapath: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except OSError as exc:
        name = f"{exc.filename}: " if exc.filename and str(exc.filename) not in str(exc.strerror) else ""
        print(f"gapath: error: {name}{exc.strerror or exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except Exception as exc:  # a bug: one message, the traceback on request
        if os.environ.get("GAPATH_TRACEBACK"):
            import traceback

            traceback.print_exc()
        print(
            f"gapath: internal error: {type(exc).__name__}: {exc} (a bug in gapath; set "
            f"GAPATH_TRACEBACK=1 to see the traceback)",
            file=sys.stderr,
        )
        return EXIT_INTERNAL


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
