"""``gapath experiment dynamic``: the command line of :mod:`gapath.studies.dynamic`."""

from __future__ import annotations

from gapath.studies.dynamic import (
    PLANNER_ORDER,
    SCENARIO_ORDER,
    run,
    run_fov,
    write_outputs,
)


def register(subparsers) -> None:
    """``gapath experiment dynamic``: the study, written to ``--out``."""
    p = subparsers.add_parser(
        "dynamic",
        help="NO-MOPP's dynamic-environment study (its Tables I-IV)",
        description="Hybrid A* (NO-MOPP), RRT, RRT*, A* and D* Lite among appearing and moving "
        "obstacles on the complex maze and the warehouse; writes dynamic.md/.csv/"
        ".jsonl, a picture of the paths and one animation per scenario.",
    )
    p.add_argument(
        "--runs", type=int, default=None, help="runs per scenario and planner (default: 100; 5 with --quick)"
    )
    p.add_argument("--quick", action="store_true", help="5 runs per row, no field-of-view study")
    p.add_argument(
        "--out",
        default="gapath-dynamic",
        help="output directory (default: %(default)s; docs/results holds the committed results)",
    )
    p.add_argument(
        "--planners", default=",".join(PLANNER_ORDER), help="comma-separated planners (default: %(default)s)"
    )
    p.add_argument(
        "--scenarios",
        default=",".join(SCENARIO_ORDER),
        help="comma-separated scenarios or map files (default: %(default)s)",
    )
    p.add_argument("--seed", type=int, default=0, help="first obstacle seed (default: 0)")
    p.add_argument("--map-seed", type=int, default=0, help="seed of the maps (default: 0)")
    p.add_argument(
        "--fov", type=float, default=180.0, help="sensor half-angle, degrees (default: %(default)s)"
    )
    p.add_argument(
        "--fov-study", action="store_true", help="also run NO-MOPP with +-45, +-90 and +-180 degree sensors"
    )
    p.add_argument(
        "--prediction",
        choices=("straight", "bounce"),
        default="straight",
        help="moving obstacles predicted on straight lines (NO-MOPP) or with their own "
        "reflecting model (default: %(default)s)",
    )
    p.add_argument("--no-gif", action="store_true", help="skip the animations")
    p.add_argument("--quiet", action="store_true")
    p.set_defaults(func=run_command)


def run_command(args) -> int:
    import sys
    from dataclasses import replace

    from gapath.dynamic import Robot, SimSettings

    n = args.runs if args.runs is not None else (5 if args.quick else 100)
    planners = tuple(p.strip() for p in args.planners.split(",") if p.strip())
    scenarios = tuple(s.strip() for s in args.scenarios.split(",") if s.strip())
    robot = replace(Robot(), fov=args.fov)
    settings = SimSettings(predict_bounces=args.prediction == "bounce")
    total = n * len(planners) * len(scenarios)
    done = [0]

    def progress(scen, planner, i, res):
        done[0] += 1
        if not args.quiet and (done[0] % 10 == 0 or done[0] == total):
            print(f"\r{done[0]}/{total} runs", end="", file=sys.stderr, flush=True)

    study = run(
        n,
        scenarios=scenarios,
        planners=planners,
        seed=args.seed,
        map_seed=args.map_seed,
        robot=robot,
        settings=settings,
        progress=progress,
    )
    fov_rows = []
    if args.fov_study and not args.quick:
        fov_rows = run_fov(n, scenarios=scenarios, seed=args.seed, map_seed=args.map_seed, settings=settings)
    files = write_outputs(study, args.out, gif=not args.no_gif, fov_rows=fov_rows)
    if not args.quiet:
        print(file=sys.stderr)
        print(study.to_markdown())
        print("wrote " + ", ".join(str(f) for f in files))
    return 0
