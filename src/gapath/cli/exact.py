"""``gapath exact``: the exact Pareto front of a map.

``--objectives`` takes length, vulnerability, smoothness and, with ``--mode
free``, the costmap layers as sums along the path: ``solar`` and
``<layer>_sum`` (``elevation_sum``, ``risk_sum``, a ``--layer NAME=FILE``
user layer's ``NAME_sum``), any number of them (the k-objective search of
:func:`gapath.planners.exact.free_front`). The GA's mean objectives
(``elevation``, ``risk``) and worst cells (``risk_max``) are refused with the
reason: neither is a sum along the path, so no label-setting search gives
their exact front. The layer flags are those of ``gapath solve``
(:func:`gapath.cli._args.add_costmap_arguments`).

``--epsilon E`` (``--mode free`` with length, vulnerability and smoothness)
runs the approximate search instead (``free_front(..., epsilon=E)``): every
point of the exact front is covered by a returned path with at most ``1 + E``
times its length and vulnerability and no more turns; much sooner on large
maps; recorded as ``"epsilon"`` in ``summary.json`` and said in the report
line.
"""

from __future__ import annotations

import time
from pathlib import Path


def register(subparsers) -> None:
    from gapath.cli._args import add_costmap_arguments, add_map_arguments

    p = subparsers.add_parser("exact", help="compute the exact Pareto front (monotone or free paths)")
    add_map_arguments(p)
    p.add_argument(
        "--objectives",
        default="length,vulnerability",
        help="comma-separated objectives among length, vulnerability, smoothness and, with "
        "--mode free, the costmap layers summed along the path: solar, elevation_sum, "
        "risk_sum, a --layer NAME's NAME_sum (any number of objectives) (default: %(default)s)",
    )
    p.add_argument(
        "--mode",
        choices=("monotone", "free"),
        default="monotone",
        help="column-monotone paths (the GA's path set) or all 8-connected paths (default: %(default)s)",
    )
    p.add_argument(
        "--max-labels",
        type=_positive_int,
        default=None,
        metavar="N",
        help="label budget: stop with a message (no front) when the search would hold "
        "more than N labels, instead of exhausting memory (free search with smoothness: 8 "
        "bytes per expanded label, about 72 per open one)",
    )
    p.add_argument(
        "--epsilon",
        type=_epsilon,
        default=0.0,
        metavar="E",
        help="with --mode free and the objectives length,vulnerability,smoothness: an "
        "approximate front, sooner: every exact point is covered by a path with at most 1+E "
        "times its length and vulnerability and no more turns (e.g. 0.1) (default: 0, exact)",
    )
    p.add_argument("--out", default="gapath-exact", help="output directory (default: %(default)s)")
    p.add_argument("--no-plots", action="store_true", help="skip front.png and paths.png")
    p.add_argument("--quiet", action="store_true", help="no report")
    add_costmap_arguments(p)
    p.set_defaults(func=run)


def _positive_int(text):
    import argparse

    from gapath.errors import ConfigError, positive_int

    try:
        return positive_int(text, "N")
    except ConfigError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None


def _epsilon(text):
    import argparse

    from gapath.errors import ConfigError, non_negative

    try:
        return non_negative(text, "E")
    except ConfigError:
        raise argparse.ArgumentTypeError(f"expected a finite number >= 0, got {text!r}") from None


class _ProgressLine:
    """A throttled progress line on stderr: rewritten in place on a terminal
    (at most 4 times a second), a new line every 10 s otherwise."""

    def __init__(self, mode):
        import sys

        self.mode, self.stream = mode, sys.stderr
        self.tty = self.stream.isatty()
        self.every = 0.25 if self.tty else 10.0
        self.last = time.perf_counter()
        self.shown = False

    def __call__(self, info):
        now = time.perf_counter()
        if now - self.last < self.every:
            return
        self.last = now
        if info["phase"] == "free":
            text = (
                f"exact free: {info['expansions']:,} expanded, {info['labels']:,} labels, "
                f"{info['open']:,} open, {info['solutions']:,} solutions so far, "
                f"{info['seconds']:.1f} s"
            )
        else:
            text = (
                f"exact monotone: column {info['columns']:,}/{info['n_cols']:,}, "
                f"{info['labels']:,} labels, {info['seconds']:.1f} s"
            )
        self.stream.write(("\r" + text + "\x1b[K") if self.tty else text + "\n")
        self.stream.flush()
        self.shown = True

    def close(self):
        if self.shown and self.tty:
            self.stream.write("\n")
            self.stream.flush()


def run(args) -> int:
    from gapath.cli._args import costmap_from_args, costmap_settings, load_workspace
    from gapath.errors import ConfigError, NoPathError
    from gapath.front import PathFront
    from gapath.planners.exact import exact_front
    from gapath.results import versions, write_front

    choice = load_workspace(args)
    ws = choice.workspace
    objectives = [o.strip() for o in args.objectives.split(",") if o.strip()]
    costmap = costmap_from_args(args, ws, objectives, kind="exact")
    if costmap is not None and args.mode == "monotone":
        layered = [o for o in objectives if o not in ("length", "vulnerability", "smoothness")]
        raise ConfigError(
            f"--objectives {','.join(objectives)}: the exact monotone front has no costmap layers "
            f"({', '.join(layered)}); add --mode free (the exact front of all 8-connected paths)"
        )
    options = {} if costmap is None else {"costmap": costmap}
    if args.epsilon:
        if args.mode != "free":
            raise ConfigError(
                f"--epsilon {args.epsilon:g}: the approximate search is over free paths; "
                "add --mode free (with --objectives length,vulnerability,smoothness)"
            )
        if set(objectives) != {"length", "vulnerability", "smoothness"} or len(objectives) != 3:
            raise ConfigError(
                f"--epsilon {args.epsilon:g} needs --objectives length,vulnerability,smoothness "
                f"(any order), got {','.join(objectives)}"
            )
        options["epsilon"] = args.epsilon
    t0 = time.perf_counter()
    bar = None if args.quiet else _ProgressLine(args.mode)
    try:
        ef = exact_front(ws, objectives, args.mode, max_labels=args.max_labels, progress=bar, **options)
    except NoPathError as exc:  # exit status 1, with the reason and what to try
        from gapath.cli.main import no_path_error

        why = no_path_error(
            ws,
            monotone=args.mode == "monotone",
            free_hint="try --mode free (the exact front of all 8-connected paths)",
        )
        raise (why or exc) from None
    except KeyboardInterrupt:
        import sys

        from gapath.errors import EXIT_INTERRUPTED

        print(
            f"\ngapath: interrupted after {time.perf_counter() - t0:.1f} s: no front written "
            f"(a partial exact search is not a Pareto front)",
            file=sys.stderr,
        )
        return EXIT_INTERRUPTED
    finally:
        if bar is not None:
            bar.close()
    front = PathFront.from_paths(ws, ef.paths, ef.objectives, ef.F)
    seconds = time.perf_counter() - t0
    summary = {
        "settings": {
            **ws.describe(),
            "objectives": list(front.objectives),
            "mode": args.mode,
            "algorithm": "exact",
            "max_labels": args.max_labels,
        },
        "versions": versions(),
        "wall_time_s": round(seconds, 4),
        "front_size": len(front),
        "search": {k: (round(v, 4) if isinstance(v, float) else v) for k, v in ef.stats.items()},
    }
    summary["settings"].update(choice.settings())
    if args.epsilon:  # not the exact front: say so where the front is read back
        summary["settings"]["epsilon"] = args.epsilon
    if costmap is not None:
        summary["settings"]["costmap"] = costmap_settings(args, costmap, objectives, kind="exact")
    shortest = (
        float(front.F[:, front.objectives.index("length")].min())
        if len(front) and "length" in front.objectives
        else None
    )
    if choice.scenario is not None:
        summary["scenario"] = choice.scenario_record(shortest)
    write_front(Path(args.out), ws, front, summary, plots=not args.no_plots)
    if not args.quiet:
        kind = f"approximate (epsilon {args.epsilon:g})" if args.epsilon else "exact"
        print(
            f"{ws!r}\n{choice.corner_line()}\n{kind} {args.mode} front: {len(front)} paths in "
            f"{seconds:.3f} s; wrote {args.out}/front.csv, paths.json, summary.json"
        )
        if choice.scenario is not None:
            print(choice.scenario_line(shortest, f"shortest length on the {args.mode} front"))
    return 0
