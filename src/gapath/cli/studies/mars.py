"""``gapath experiment mars``: the command line of :mod:`gapath.studies.mars`
(its arguments, handed to :func:`gapath.studies.mars.run`)."""

from __future__ import annotations

from pathlib import Path

from gapath.errors import ConfigError
from gapath.studies import mars as _study  # find_mars_dtm looked up at call time
from gapath.studies.mars import FULL, QUICK, TERRAINS, record_line, study_stats, write_results


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
        "--solar-rate",
        type=float,
        default=1.0,
        help="the solar vector's turn per path step in the main tables, radians "
        "(default: %(default)s, Lavin section IV)",
    )
    p.add_argument(
        "--compare-solar-rate",
        type=_rate_or_none,
        default=0.01,
        help="the planners are run again at this rate, radians per path step, or none "
        "(default: %(default)s, Lavin section II)",
    )
    p.add_argument(
        "--terrain",
        choices=TERRAINS,
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


def _rate_or_none(text: str):
    """``--compare-solar-rate``: a number of radians, or ``none``."""
    import argparse
    import math

    if text.strip().lower() == "none":
        return None
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of radians or 'none', got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number of radians, got {text!r}")
    return value


def run(args) -> int:
    """The handler of ``gapath experiment mars``: :func:`gapath.studies.mars.run`,
    its JSON lines on stdout (and ``--jsonl``), its tables in ``--out``."""
    import sys

    from gapath.results import dumps

    if args.terrain != "fractal" and _study.find_mars_dtm() is None:
        if args.terrain == "mars":
            raise ConfigError(
                "--terrain mars: the Mars DTM dem/mars_dtm.npy was not found (looked "
                "in $GAPATH_SHARED_DATA and in shared/data beside the gapath "
                "sources); set GAPATH_SHARED_DATA to the data folder, or use "
                "--terrain fractal"
            )
        print(
            "gapath: the Mars DTM dem/mars_dtm.npy was not found; the study uses seeded "
            "fractal terrain (labelled so in mars.md; --terrain mars makes this an error)",
            file=sys.stderr,
        )
    out = Path(args.out) if args.out else Path("gapath-mars-quick" if args.quick else "gapath-mars")
    sink = open(args.jsonl, "a") if args.jsonl else None

    def emit(obj):
        line = dumps(obj)
        if not args.quiet:
            print(line, flush=True)
        if sink is not None:
            sink.write(line + "\n")
            sink.flush()

    try:
        study = _study.run(
            args.n,
            quick=args.quick,
            seed=args.seed,
            size=args.size,
            terrain=args.terrain,
            ga_pop=args.ga_pop,
            ga_gen=args.ga_gen,
            ga_seed_from=args.ga_seed_from,
            solar_rate=args.solar_rate,
            compare_solar_rate=args.compare_solar_rate,
            on_record=lambda r: emit({"kind": "mars_workspace", **record_line(r)}),
        )
        files = write_results(study, out)
        for row in study.rows:
            emit({"kind": "mars_table", **study.settings, **row})
        for row in study.rows_compare:
            emit({"kind": "mars_table_solar_compare", **study.settings, **row})
        emit({"kind": "mars_stats", **study.settings, **study_stats(study.records), "seconds": study.seconds})
    finally:
        if sink is not None:
            sink.close()
    if not args.quiet:
        print("wrote " + ", ".join(str(f) for f in files))
    return 0
