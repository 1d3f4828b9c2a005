"""``gapath experiment dense``: the command line of :mod:`gapath.studies.dense`
(its arguments, handed to :func:`gapath.studies.dense.run`)."""

from __future__ import annotations

from gapath.experiments.spec import ENGINE_ALIASES, ENGINES
from gapath.operators.repair.feasible import REPAIRS
from gapath.studies import dense as _study
from gapath.studies.dense import GENERATORS, MAP_SEED, QUICK


def register(subparsers) -> None:
    from gapath.cli.experiment import add_executor_options

    p = subparsers.add_parser("dense", help="Ahmed & Deb's dense-obstacle experiment (Table 1)")
    p.add_argument("--out", required=True, help="store directory (DIR/table1-map<S>, DIR/large-map<S>, ...)")
    p.add_argument(
        "--quick",
        action="store_true",
        help=f"a few runs on small grids ({QUICK['grids']}, p0 {QUICK['p0s']}, "
        f"{QUICK['runs']} runs per row, at most {QUICK['n_gen']} generations)",
    )
    p.add_argument(
        "--results",
        default=None,
        help="where dense.md/.csv/.png go (default: docs/results; with --quick: --out)",
    )
    p.add_argument("--runs", type=int, default=None, help="GA runs per Table 1 row (default: 100)")
    p.add_argument("--grids", default=None, help="comma-separated grid sides (default: 8,16,32)")
    p.add_argument("--p0", default=None, help="comma-separated p0 values (default: 0.1,...,1.0)")
    p.add_argument(
        "--map-seeds",
        default=str(MAP_SEED),
        help=f"map seeds of the rows, e.g. 1,2,3 or 1-5 (default: {MAP_SEED}): the first "
        "gives the main table, the others a table of every row's success per map",
    )
    p.add_argument(
        "--per-run-maps",
        action="store_true",
        help="also run every row with a new map per run (map seed = run seed; "
        "DIR/table1-per-run-maps, DIR/large-per-run-maps)",
    )
    p.add_argument(
        "--large-runs",
        type=int,
        default=None,
        help="GA runs on the 64x64 and 128x128 maps (default: 10, as the paper; 0 skips them)",
    )
    p.add_argument(
        "--seeded",
        action="store_true",
        help="also run the main table with the initial population seeded from "
        "planners (seed_from=weighted; DIR/table1-map<S>-seeded), reported beside "
        "the paper's protocol and marked SEEDED",
    )
    p.add_argument(
        "--engine",
        choices=(*ENGINES, *ENGINE_ALIASES),
        default="fast",
        help="GA engine: fast (default, FastNSGA2 on arrays) or pymoo (stock pymoo NSGA2), "
        "as gapath solve; paper and auto, the former names, mean pymoo and fast",
    )
    p.add_argument(
        "--generator",
        choices=GENERATORS,
        default="columns",
        help="map generator: columns (default, gapath.dense_workspace: a random walk of -2..2 rows "
        "per column, then the goal column climbed) or walk (a goal-biased 8-connected walk kept "
        "free; runs the Table 1 rows only, DIR/table1-walk-map<S>, and reports them beside the "
        "columns rows)",
    )
    p.add_argument(
        "--from-csv",
        default=None,
        metavar="FILE",
        help="take the columns generator's rows from a dense.csv written earlier instead of "
        "their stores (with --generator walk: e.g. docs/results/dense.csv)",
    )
    p.add_argument(
        "--repair",
        choices=tuple(REPAIRS),
        default="edge",
        help="repair of new genomes: edge (default: Ahmed & Deb's edge-fixing alone, the paper's "
        "protocol) or a feasibility-preserving repair (feasible-local: every column step on an "
        "obstacle moved to the nearest free exit row; a GA change, --engine fast only): runs the "
        "Table 1 rows only with it (DIR/table1-map<S>-<repair>, DIR/table1-walk-map<S>-<repair> "
        "with --generator walk) and reports them beside the penalty rows (their stores in DIR, "
        "or --from-csv)",
    )
    p.add_argument(
        "--repair-csv",
        default=None,
        metavar="FILE",
        help="take the repair rows that no store in DIR holds from a dense_repair.csv written "
        "earlier (e.g. docs/results/dense_repair.csv)",
    )
    add_executor_options(p)
    p.set_defaults(func=run)


def run(args) -> int:
    """The handler of ``gapath experiment dense``: :func:`gapath.studies.dense.run`."""
    try:
        rep = _study.run(
            args.out,
            quick=args.quick,
            grids=tuple(int(g) for g in args.grids.split(",")) if args.grids else None,
            p0s=tuple(float(p) for p in args.p0.split(",")) if args.p0 else None,
            runs=args.runs,
            map_seeds=_seed_list(args.map_seeds),
            per_run_maps=args.per_run_maps,
            large_runs=args.large_runs,
            seeded=args.seeded,
            engine=args.engine,
            results=args.results,
            workers=args.workers,
            scheduler=args.scheduler,
            progress=not args.quiet,
            retry_failed=args.retry_failed,
            generator=args.generator,
            from_csv=args.from_csv,
            repair=args.repair,
            repair_csv=args.repair_csv,
        )
    except KeyboardInterrupt:
        print(f"interrupted: finished runs are kept in {args.out}; run the same command to resume")
        return 130
    if not args.quiet:
        print("wrote " + ", ".join(str(f) for f in rep["files"]))
    return 0 if rep["failed"] == 0 else 1


def _seed_list(text: str) -> list[int]:
    """``"1,2,5-7"`` -> ``[1, 2, 5, 6, 7]`` (map seeds of ``--map-seeds``)."""
    out = []
    for part in text.split(","):
        part = part.strip()
        try:
            if "-" in part:
                a, b = (int(x) for x in part.split("-", 1))
                if b < a:
                    raise ValueError
                out += range(a, b + 1)
            else:
                out.append(int(part))
        except ValueError:
            raise SystemExit(
                f"gapath experiment dense: --map-seeds: expected non-negative integers "
                f"or ranges like 1,2,5-7, got {text!r}"
            ) from None
    if not out or min(out) < 0:
        raise SystemExit(
            f"gapath experiment dense: --map-seeds: expected non-negative integers "
            f"or ranges like 1,2,5-7, got {text!r}"
        )
    return list(dict.fromkeys(out))
