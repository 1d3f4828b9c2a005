"""The ``gapath`` command line.

``gapath solve MAP ...`` runs the seeds' NSGA-II on a map and writes
``front.csv``, ``paths.json``, ``summary.json``, ``front.png`` and
``paths.png``; ``gapath demo`` does so on the bundled scenario. Bad input
prints one clear message and exits with status 2 (no traceback).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from gapath.errors import ConfigError, GapathError


def _cell(text: str) -> tuple[int, int]:
    try:
        r, c = (int(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected ROW,COL (two integers), got {text!r}") from None
    return r, c


def _load(map_arg: str, start, goal, corner_cutting):
    from gapath.workspace import default_workspace

    kw = {} if corner_cutting is None else {"corner_cutting": corner_cutting}
    if map_arg == "default":
        ws = default_workspace()
        changes = {k: v for k, v in (("start", start), ("goal", goal)) if v is not None}
        return ws.replace(**changes, **kw) if changes or kw else ws
    from gapath.loaders import load_map

    return load_map(map_arg, start=start, goal=goal, **kw)


def _add_run_options(p: argparse.ArgumentParser, *, pop: int, gen: int, out: str | None) -> None:
    p.add_argument("--objectives", default="length,vulnerability",
                   help="comma-separated objectives among length, vulnerability, smoothness "
                        "(default: %(default)s)")
    p.add_argument("--encoding", default=None,
                   help="genome encoding: integer, binary, mixed or absolute for monotone paths "
                        "(default integer); field or via for free paths (default field)")
    p.add_argument("--constraints", choices=("penalty", "constraint"), default=None,
                   help="obstacle handling (default: penalty; constraint for one objective)")
    p.add_argument("--sbx-eta", type=float, default=None,
                   help="SBX distribution index (default: 10; 2 for one objective)")
    p.add_argument("--penalty", type=float, default=1000.0,
                   help="penalty per interfering cell (default: %(default)s)")
    p.add_argument("--tiebreak", choices=("smoothness", "none"), default="smoothness",
                   help="tie-break inside a non-dominated rank (default: %(default)s)")
    p.add_argument("--seed-from", choices=("weighted", "exact", "astar", "none"), default="weighted",
                   help="initial population: shortest, safest and weighted-sum monotone paths "
                        "plus random ones (weighted), the exact monotone front (exact), A* "
                        "paths projected onto monotone paths (astar), or all random as in the "
                        "seeds' protocol (none) (default: %(default)s)")
    p.add_argument("--engine", choices=("fast", "pymoo"), default="fast",
                   help="NSGA-II engine: FastNSGA2 on arrays (fast) or stock pymoo NSGA2 (pymoo); "
                        "same results for the same seed (default: %(default)s)")
    p.add_argument("--pop", type=int, default=pop, help="population size (default: %(default)s)")
    p.add_argument("--gen", type=int, default=gen, help="generations (default: %(default)s)")
    p.add_argument("--seed", type=int, default=1, help="random seed (default: %(default)s)")
    p.add_argument("--runs", type=int, default=1,
                   help="independent runs with seeds SEED..SEED+RUNS-1, each written to "
                        "OUT/runs/<seed>/, their merged front to OUT (default: %(default)s)")
    p.add_argument("--out", default=out, help="output directory (default: %(default)s)")
    p.add_argument("--reference", metavar="monotone|free|FILE",
                   help="judge the front against the exact monotone front, the exact free front "
                        "or a front.csv: adds hypervolume ratio, IGD+ and the share of reference "
                        "points found to summary.json")
    p.add_argument("--no-plots", action="store_true", help="skip front.png and paths.png")
    p.add_argument("--quiet", action="store_true", help="no progress bar or report")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="gapath", description="Multi-objective grid path planning with pymoo.")
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("solve", help="run NSGA-II on a map and write its Pareto front")
    p.add_argument("map", help="map file (.map, .yaml, .txt, .grid, .npy, .pgm, .png) "
                               "or 'default' for the bundled 32x32 scenario")
    p.add_argument("--start", type=_cell, help="start cell ROW,COL (default: bottom-left)")
    p.add_argument("--goal", type=_cell, help="goal cell ROW,COL (default: top-right)")
    cc = p.add_mutually_exclusive_group()
    cc.add_argument("--corner-cutting", dest="corner_cutting", action="store_true", default=None,
                    help="allow diagonal moves past blocked corners (the default)")
    cc.add_argument("--no-corner-cutting", dest="corner_cutting", action="store_false",
                    help="a diagonal move needs both orthogonal neighbours free (MovingAI)")
    _add_run_options(p, pop=500, gen=500, out="gapath-out")
    p.add_argument("--paths", choices=("free", "monotone"), default="free",
                   help="path set: any simple 8-connected path (free) or Ahmed & Deb's "
                        "column-monotone paths (monotone) (default: %(default)s)")

    d = sub.add_parser("demo", help="the bundled scenario with the seeds' settings")
    _add_run_options(d, pop=500, gen=500, out="gapath-demo")

    from gapath.commands import register_all

    register_all(sub)
    return parser


def _report(result, out_dir: Path) -> None:
    front = result.front
    print(f"{result.workspace!r}")
    status = "interrupted after" if result.interrupted else "finished"
    print(f"{status} {result.n_gen} generations, {result.n_eval} evaluations, "
          f"{result.seconds:.1f} s; {len(front)} non-dominated feasible paths")
    from gapath.plotting import marked_paths

    for label, i in marked_paths(front).items():
        values = ", ".join(f"{n}={v:.4f}" for n, v in zip(front.objectives, front.F[i]))
        print(f"  {label:9s} {values}")
    print(f"wrote {out_dir}/front.csv, paths.json, summary.json"
          + ("" if result.settings.get("plots") is False else ", front.png, paths.png"))


def _reference(args, workspace):
    if not args.reference:
        return None
    from gapath.problems.grid_path import OBJECTIVE_NAMES
    from gapath.reference import reference_front

    names = [o.strip() for o in args.objectives.split(",") if o.strip()]
    bad = [n for n in names if n not in OBJECTIVE_NAMES]
    if bad:
        raise ConfigError(f"unknown objective {bad[0]!r}; expected some of {', '.join(OBJECTIVE_NAMES)}")
    return reference_front(workspace, names, args.reference)


def _quality(args, reference, F) -> dict:
    if reference is None:
        return {}
    from gapath.reference import front_quality

    return {"quality": {"reference": str(args.reference), **front_quality(F, reference)}}


def _print_quality(extra: dict) -> None:
    if extra:
        q = extra["quality"]
        print(f"against the {q['reference']} reference: hv ratio {q['hv_ratio']:.4f}, "
              f"IGD+ {q['igd_plus']:.4g}, {q['reference_points_found']:.0%} of its points found")


def _run(args, workspace) -> int:
    from gapath.results import write_result
    from gapath.solver import solve

    kwargs = dict(objectives=args.objectives, encoding=args.encoding, constraints=args.constraints,
                  penalty=args.penalty, pop_size=args.pop, n_gen=args.gen,
                  tiebreak=None if args.tiebreak == "none" else args.tiebreak,
                  sbx_eta=args.sbx_eta, seed_from=args.seed_from, engine=args.engine,
                  progress=not args.quiet, paths=getattr(args, "paths", "monotone"))
    out_dir = Path(args.out)
    reference = _reference(args, workspace)
    if args.runs != 1:
        return _multirun(args, workspace, kwargs, out_dir, reference)
    tracker = None
    if reference is not None:
        from gapath.convergence import HypervolumeRatioCallback

        tracker = HypervolumeRatioCallback(reference)
    result = solve(workspace, seed=args.seed, callback=tracker, **kwargs)
    extra = _quality(args, reference, result.front.F)
    write_result(result, out_dir, plots=not args.no_plots, extra=extra)
    if tracker is not None and tracker.history:
        _write_convergence(tracker, out_dir, plots=not args.no_plots)
    if not args.quiet:
        _report(result, out_dir)
        _print_quality(extra)
    return 130 if result.interrupted else 0


def _write_convergence(tracker, out_dir: Path, plots: bool) -> None:
    from gapath.convergence import plot_convergence
    from gapath.results import atomic_write

    rows = ["n_gen,n_eval,hv_ratio"] + [f"{int(g)},{int(e)},{h!r}" for g, e, h in tracker.history]
    atomic_write(out_dir / "convergence.csv", "\n".join(rows) + "\n")
    if plots:
        plot_convergence(tracker.history, out_dir / "convergence.png")


def _multirun(args, workspace, kwargs, out_dir: Path, reference) -> int:
    from gapath.experiments import multirun
    from gapath.results import versions, write_front, write_result

    def write_run(r):
        write_result(r, out_dir / "runs" / str(r.settings["seed"]), plots=not args.no_plots)
        if not args.quiet:
            print(f"run {r.settings['seed']}: {len(r.front)} paths, {r.seconds:.1f} s", flush=True)

    m = multirun(workspace, runs=args.runs, seed=args.seed, on_run=write_run, **kwargs)
    extra = _quality(args, reference, m.front.F)
    summary = {
        "settings": {**m.runs[0].settings, "seed": m.seeds[0], "runs": args.runs},
        "seeds": m.seeds,
        "versions": versions(),
        "wall_time_s": round(sum(r.seconds for r in m.runs), 3),
        "evaluations": sum(r.n_eval for r in m.runs),
        "interrupted": m.interrupted,
        "front_size": len(m.front),
        "run_front_sizes": [len(r.front) for r in m.runs],
        **extra,
    }
    write_front(out_dir, workspace, m.front, summary, plots=not args.no_plots)
    if not args.quiet:
        print(f"merged front of {len(m.runs)} runs: {len(m.front)} paths; wrote {out_dir}/front.csv, "
              f"paths.json, summary.json and {out_dir}/runs/<seed>/")
        _print_quality(extra)
    return 130 if m.interrupted else 0


def main(argv=None) -> int:
    import matplotlib

    matplotlib.use("Agg")  # the CLI only writes image files (library modules leave the backend alone)
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if getattr(args, "func", None) is not None:
            return args.func(args)
        if args.command == "solve":
            workspace = _load(args.map, args.start, args.goal, args.corner_cutting)
        else:
            from gapath.workspace import default_workspace

            workspace = default_workspace()
        return _run(args, workspace)
    except GapathError as exc:
        print(f"gapath: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"gapath: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
