"""``gapath experiment encodings``: the command line of :mod:`gapath.studies.encodings`."""

from __future__ import annotations

from gapath.results import dumps
from gapath.studies.encodings import (
    QUICK,
    run,
    write_outputs,
)


def register(subparsers) -> None:
    p = subparsers.add_parser("encodings", help="Ahmed & Deb's encoding comparison (Fig. 3 set-up)")
    p.add_argument("--runs", type=int, default=10)
    p.add_argument("--pop", type=int, default=500)
    p.add_argument("--gen", type=int, default=500)
    p.add_argument(
        "--quick",
        action="store_true",
        help=f"{QUICK['runs']} runs x pop {QUICK['pop_size']} x {QUICK['n_gen']} generations",
    )
    p.add_argument(
        "--out",
        default="gapath-encodings",
        help="output directory (default: %(default)s; docs/results holds the committed results)",
    )
    p.set_defaults(func=_cli)


def _cli(args) -> int:
    runs, pop, gen = (
        (QUICK["runs"], QUICK["pop_size"], QUICK["n_gen"]) if args.quick else (args.runs, args.pop, args.gen)
    )
    result = run(runs=runs, pop_size=pop, n_gen=gen, progress=lambda r: print(dumps(r), flush=True))
    for f in write_outputs(result, args.out):
        print(f"wrote {f}")
    return 0
