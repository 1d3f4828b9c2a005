"""``gapath experiment encodings``: the command line of :mod:`gapath.studies.encodings`."""

from __future__ import annotations

from gapath.errors import ConfigError
from gapath.results import dumps
from gapath.studies.encodings import (
    PROTOCOLS,
    QUICK,
    run,
    write_outputs,
)


def _penalty(text: str):
    from gapath.constraints import HANDLINGS

    text = text.strip()
    if text in HANDLINGS:
        return text
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not value >= 0 or value == float("inf"):
        raise ConfigError(
            f"--penalties: expected numbers >= 0 or one of {', '.join(HANDLINGS)}, got {text!r}"
        )
    return value


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
        "--protocols",
        default="seeds,seeded",
        help="seeds (all-random first population) and/or seeded (default: %(default)s)",
    )
    p.add_argument(
        "--penalties",
        default="1000",
        help="obstacle handlings, comma-separated: penalties per interfering cell and/or "
        "'adaptive' (default: %(default)s)",
    )
    p.add_argument(
        "--binary-rates",
        default="bits",
        help="the binary encoding's initial bit-flip rates, comma-separated: bits (1/number of "
        "bits) and/or grid (1/n, Ahmed & Deb's) (default: %(default)s)",
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
    penalties = tuple(_penalty(v) for v in args.penalties.split(","))
    rates = tuple(v.strip() for v in args.binary_rates.split(","))
    for rate in rates:
        if rate not in ("bits", "grid"):
            raise ConfigError(f"--binary-rates: expected bits and/or grid, got {rate!r}")
    protocols = tuple(v.strip() for v in args.protocols.split(","))
    for protocol in protocols:
        if protocol not in PROTOCOLS:
            raise ConfigError(f"--protocols: expected seeds and/or seeded, got {protocol!r}")
    result = run(
        protocols=protocols,
        runs=runs,
        pop_size=pop,
        n_gen=gen,
        penalties=penalties,
        binary_rates=rates,
        progress=lambda r: print(dumps(r), flush=True),
    )
    for f in write_outputs(result, args.out):
        print(f"wrote {f}")
    return 0
