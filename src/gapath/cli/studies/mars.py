"""``gapath experiment mars``: the command line of :mod:`gapath.studies.mars`."""

from __future__ import annotations

from pathlib import Path

from gapath.errors import ConfigError
from gapath.studies import mars as _study  # find_mars_dtm looked up at call time
from gapath.studies.mars import (
    FULL,
    QUICK,
    mars_study,
    record_line,
    study_stats,
    write_results,
)


def register(subparsers) -> None:
    p = subparsers.add_parser("mars", help="Lavin's Mars rover study (Table I): A*, D*, D*-PO, GA")
    add_arguments(p)
    p.set_defaults(func=run)


def add_arguments(p) -> None:
    """The options of ``gapath experiment mars`` and ``benchmarks/mars_study.py``."""
    p.add_argument(
        "--quick",
        action="store_true",
        help=f"{QUICK['n_workspaces']} workspaces, GA pop {QUICK['ga_pop']} x {QUICK['ga_gen']} generations",
    )
    p.add_argument(
        "--n",
        type=int,
        default=None,
        help=f"workspaces (default: {FULL['n_workspaces']}; --quick: {QUICK['n_workspaces']})",
    )
    p.add_argument("--seed", type=int, default=2015, help="workspace seed (default: %(default)s)")
    p.add_argument("--size", type=int, default=100, help="grid side (default: %(default)s)")
    p.add_argument("--ga-pop", type=int, default=None, help=f"GA population (default: {FULL['ga_pop']})")
    p.add_argument("--ga-gen", type=int, default=None, help=f"GA generations (default: {FULL['ga_gen']})")
    p.add_argument(
        "--ga-seed-from",
        default="weighted",
        help="the GA's first population: weighted (default, as gapath solve), exact, "
        "astar or none (all random)",
    )
    p.add_argument(
        "--terrain",
        choices=("auto", "mars", "fractal"),
        default="auto",
        help="elevation source: the Mars DTM (mars; an error when it is not found), "
        "seeded fractal terrain (fractal), or the DTM when found and fractal "
        "terrain otherwise, said so in the output (auto) (default: %(default)s)",
    )
    p.add_argument(
        "--out",
        default=None,
        help="where mars.md and mars.csv go (default: gapath-mars; --quick: "
        "gapath-mars-quick; docs/results holds the committed results)",
    )
    p.add_argument("--jsonl", default=None, help="also append the JSON lines to this file")
    p.add_argument("--quiet", action="store_true", help="no JSON lines on stdout")


def run(args) -> int:

    cfg = dict(QUICK if args.quick else FULL)
    if args.n is not None:
        cfg["n_workspaces"] = args.n
    if args.ga_pop is not None:
        cfg["ga_pop"] = args.ga_pop
    if args.ga_gen is not None:
        cfg["ga_gen"] = args.ga_gen
    out = Path(args.out) if args.out else Path("gapath-mars-quick" if args.quick else "gapath-mars")
    sink = open(args.jsonl, "a") if args.jsonl else None

    from gapath.results import dumps

    def emit(obj):
        line = dumps(obj)
        if not args.quiet:
            print(line, flush=True)
        if sink is not None:
            sink.write(line + "\n")
            sink.flush()

    dem = "fractal" if args.terrain == "fractal" else None
    if args.terrain != "fractal":
        path = _study.find_mars_dtm()
        if path is None and args.terrain == "mars":
            raise ConfigError(
                "--terrain mars: the Mars DTM dem/mars_dtm.npy was not found (looked "
                "in $GAPATH_SHARED_DATA and in shared/data beside the gapath "
                "sources); set GAPATH_SHARED_DATA to the data folder, or use "
                "--terrain fractal"
            )
        if path is None:
            import sys

            print(
                "gapath: the Mars DTM dem/mars_dtm.npy was not found; the study uses seeded "
                "fractal terrain (labelled so in mars.md; --terrain mars makes this an error)",
                file=sys.stderr,
            )
    try:
        study = mars_study(
            cfg["n_workspaces"],
            seed=args.seed,
            size=args.size,
            dem=dem,
            ga_pop=cfg["ga_pop"],
            ga_gen=cfg["ga_gen"],
            ga_seed_from=args.ga_seed_from,
            on_record=lambda r: emit({"kind": "mars_workspace", **record_line(r)}),
        )
        files = write_results(study, out)
        for row in study.rows:
            emit({"kind": "mars_table", **study.settings, **row})
        emit({"kind": "mars_stats", **study.settings, **study_stats(study.records), "seconds": study.seconds})
    finally:
        if sink is not None:
            sink.close()
    if not args.quiet:
        print("wrote " + ", ".join(str(f) for f in files))
    return 0
