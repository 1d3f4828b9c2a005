"""``gapath experiment dense``: the command line of :mod:`gapath.studies.dense`."""

from __future__ import annotations

import time
from pathlib import Path

from gapath.studies.dense import (
    MAP_SEED,
    P0S,
    QUICK,
    _seed_list,
    dense_report,
    large_spec,
    table1_spec,
)


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
        choices=("auto", "paper", "fast"),
        default="auto",
        help="GA engine (default: fast when available, else paper)",
    )
    add_executor_options(p)
    p.set_defaults(func=run)


def run(args) -> int:
    from gapath.experiments.runner import run_experiment

    quick = args.quick
    grids = (
        tuple(int(g) for g in args.grids.split(","))
        if args.grids
        else (QUICK["grids"] if quick else (8, 16, 32))
    )
    p0s = tuple(float(p) for p in args.p0.split(",")) if args.p0 else (QUICK["p0s"] if quick else P0S)
    runs = args.runs or (QUICK["runs"] if quick else 100)
    n_gen = QUICK["n_gen"] if quick else 500
    map_seeds = _seed_list(args.map_seeds)
    main = map_seeds[0]
    large_runs = args.large_runs if args.large_runs is not None else (QUICK["large_runs"] if quick else 10)
    out = Path(args.out)
    sfx = "-quick" if quick else ""
    jobs = [
        (
            f"table1-map{m}",
            table1_spec(
                grids,
                p0s,
                runs,
                n_gen=n_gen,
                engine=args.engine,
                map_seed=m,
                name=f"dense-table1-map{m}{sfx}",
            ),
        )
        for m in map_seeds
    ]
    if args.seeded:
        jobs.append(
            (
                f"table1-map{main}-seeded",
                table1_spec(
                    grids,
                    p0s,
                    runs,
                    n_gen=n_gen,
                    engine=args.engine,
                    map_seed=main,
                    seed_from="weighted",
                    name=f"dense-table1-map{main}-seeded{sfx}",
                ),
            )
        )
    if args.per_run_maps:
        jobs.append(
            (
                "table1-per-run-maps",
                table1_spec(
                    grids,
                    p0s,
                    runs,
                    n_gen=n_gen,
                    engine=args.engine,
                    map_seed="run",
                    name=f"dense-table1-per-run-maps{sfx}",
                ),
            )
        )
    if large_runs > 0:
        lkw = dict(
            pop_size=QUICK["large_pop"] if quick else 500,
            n_gen=QUICK["large_gen"] if quick else 500,
            engine=args.engine,
        )
        sizes = QUICK["large_sizes"] if quick else (64, 128)
        jobs.append(
            (
                f"large-map{main}",
                large_spec(sizes, large_runs, map_seed=main, name=f"dense-large-map{main}{sfx}", **lkw),
            )
        )
        if args.per_run_maps:
            jobs.append(
                (
                    "large-per-run-maps",
                    large_spec(
                        sizes, large_runs, map_seed="run", name=f"dense-large-per-run-maps{sfx}", **lkw
                    ),
                )
            )
    wall = {}
    kw = dict(
        workers=args.workers,
        scheduler=args.scheduler,
        progress=not args.quiet,
        retry_failed=args.retry_failed,
    )
    failed = 0
    try:
        for name, spec in jobs:
            t0 = time.perf_counter()
            r = run_experiment(spec, out / name, **kw)
            failed += r.failed
            if r.ran:  # a resumed store that ran nothing has no wall time to report
                wall[name] = time.perf_counter() - t0
    except KeyboardInterrupt:
        print(f"interrupted: finished runs are kept in {out}; run the same command to resume")
        return 130
    results = Path(args.results) if args.results else (out if quick else Path("docs/results"))
    wall = {
        k.replace(f"-map{main}", "")
        if k in (f"table1-map{main}", f"table1-map{main}-seeded", f"large-map{main}")
        else k: v
        for k, v in wall.items()
    }
    rep = dense_report(
        out / f"table1-map{main}",
        results,
        out / f"large-map{main}" if large_runs > 0 else None,
        seeded_dir=out / f"table1-map{main}-seeded",
        other_map_dirs=[out / f"table1-map{m}" for m in map_seeds[1:]],
        per_run_dir=out / "table1-per-run-maps",
        large_per_run_dir=out / "large-per-run-maps" if large_runs > 0 else None,
        wall_seconds=wall,
        workers=args.workers,
    )
    if not args.quiet:
        print("wrote " + ", ".join(str(f) for f in rep["files"]))
    return 0 if failed == 0 else 1
