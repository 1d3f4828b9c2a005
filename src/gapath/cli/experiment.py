"""``gapath experiment``: run, watch and report grids of GA runs.

Sub-commands::

    gapath experiment run SPEC --out DIR [--scheduler tcp://HOST:PORT|local] [--workers N]
    gapath experiment status DIR
    gapath experiment report DIR
    gapath experiment dense [--quick] --out DIR      (Ahmed & Deb's Table 1)

``SPEC`` is a YAML, TOML or JSON experiment file (schema:
:mod:`gapath.experiments.spec`, docs/EXPERIMENTS.md) or a store directory
(its saved ``experiment.json``, to resume). The paper studies' sub-commands
live in :mod:`gapath.cli.studies` (encodings, dense, mars, dynamic). The
group is extensible: every module named in :data:`EXPERIMENT_MODULES` (none
by default) defines ``register_experiment(subparsers)``, which adds its
parser(s) to the experiment group and sets ``func=run`` (``run(args) ->
int``) with ``set_defaults``.
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

#: Modules of other packages that add ``gapath experiment`` sub-commands
#: after gapath's own studies (a plug-in point; empty in gapath itself).
EXPERIMENT_MODULES: list[str] = []


def add_executor_options(p) -> None:
    """``--workers``, ``--scheduler``, ``--quiet`` and ``--retry-failed``
    (shared by the sub-commands that run experiments)."""
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        help="processes of the local pool, or of the LocalCluster with --scheduler "
        "local (default: the number of CPUs; 0: run in this process)",
    )
    p.add_argument(
        "--scheduler",
        default=None,
        metavar="tcp://HOST:PORT|local",
        help="run on this Dask scheduler instead; 'local': start a Dask LocalCluster "
        "of --workers processes with gapath's Dask settings, run on it, close it "
        "(default: $GAPATH_SCHEDULER if set)",
    )
    p.add_argument(
        "--no-retry-failed",
        dest="retry_failed",
        action="store_false",
        help="do not run again the runs whose last attempt failed",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar or report")


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "experiment",
        help="grids of runs: run, status, report, dense, ...",
        description="Run grids of GA runs on a process pool or a Dask "
        "cluster, resumably; aggregate them into tables.",
    )
    sub = p.add_subparsers(dest="experiment_command", required=True, metavar="COMMAND")

    r = sub.add_parser("run", help="run (or resume) an experiment from a YAML/TOML spec")
    r.add_argument("spec", help="experiment spec (.yaml, .yml, .toml, .json) or a store directory")
    r.add_argument(
        "--out",
        required=False,
        default=None,
        help="store directory (default: the spec's directory when SPEC is a store)",
    )
    add_executor_options(r)
    r.add_argument(
        "--force",
        action="store_true",
        help="run SPEC in a store of another experiment (one whose runs SPEC does "
        "not all include), replacing its experiment.json (its runs whose keys "
        "match are reused); a spec that only adds runs needs no --force",
    )
    r.add_argument("--no-report", action="store_true", help="do not write the report at the end")
    r.add_argument("--no-plots", action="store_true", help="report without plots")
    r.set_defaults(func=run_command)

    s = sub.add_parser("status", help="count the finished, failed and pending runs of a store")
    s.add_argument("dir", help="store directory")
    s.set_defaults(func=status_command)

    rep = sub.add_parser("report", help="write summary.csv/.md, merged fronts and plots of a store")
    rep.add_argument("dir", help="store directory")
    rep.add_argument("--no-plots", action="store_true")
    rep.add_argument("--quiet", action="store_true")
    rep.set_defaults(func=report_command)

    from gapath.cli.studies import dense, dynamic, encodings, mars

    for study in (encodings, dense, mars, dynamic):  # help order
        study.register(sub)
    for name in EXPERIMENT_MODULES:
        importlib.import_module(name).register_experiment(sub)


def _spec_and_out(args):
    from gapath.errors import ConfigError
    from gapath.experiments.store import ResultStore

    path = Path(args.spec)
    if path.is_dir():
        spec, out = ResultStore(path).spec(), Path(args.out) if args.out else path
    elif args.out is None:
        raise ConfigError("--out DIR is required when SPEC is a file")
    else:
        from gapath.experiments.spec import load_spec

        spec, out = load_spec(path), Path(args.out)
    if not getattr(args, "force", False):
        _check_same_experiment(spec, out, quiet=getattr(args, "quiet", False))
    return spec, out


def _check_same_experiment(spec, out: Path, quiet: bool = False) -> None:
    """Refuse to run ``spec`` in a store made from another experiment (it
    would replace the store's ``experiment.json``).

    The same experiment may grow: a spec that keeps every run of the stored
    one (more seeds, more grid values, more maps; the name may change) is
    accepted, and said so unless ``quiet``.

    Raises
    ------
    ConfigError
        Naming the store, its experiment and the keys that differ, when
        ``spec`` leaves out runs of the stored experiment.
    """
    from gapath.errors import ConfigError
    from gapath.experiments.spec import canonical_json, run_key
    from gapath.experiments.store import ResultStore

    store = ResultStore(out)
    if not store.exists():
        return
    stored_spec = store.spec()
    saved, new = stored_spec.to_dict(), spec.to_dict()
    if canonical_json(saved) == canonical_json(new):
        return
    differ = [
        k for k in sorted(set(saved) | set(new)) if canonical_json(saved.get(k)) != canonical_json(new.get(k))
    ]
    old_keys = {run_key(r) for r in stored_spec.runs()}
    new_keys = {run_key(r) for r in spec.runs()}
    if old_keys <= new_keys:
        if not quiet:
            print(
                f"gapath: extending the experiment {saved.get('name')!r} in {out} "
                f"({', '.join(differ)} changed): {len(new_keys - old_keys)} new runs",
                file=sys.stderr,
            )
        return
    raise ConfigError(
        f"--out {str(out)!r} holds the experiment {saved.get('name')!r} of another spec "
        f"({', '.join(differ)} differ; {len(old_keys - new_keys)} of its {len(old_keys)} runs "
        f"are not in SPEC); give another --out, run 'gapath experiment run {out}' to resume "
        f"it, or add --force to replace its experiment.json (stored runs whose keys match are "
        f"reused)"
    )


def run_command(args) -> int:
    from gapath.experiments.report import report
    from gapath.experiments.runner import run_experiment

    spec, out = _spec_and_out(args)
    try:
        res = run_experiment(
            spec,
            out,
            workers=args.workers,
            scheduler=args.scheduler,
            progress=not args.quiet,
            retry_failed=args.retry_failed,
        )
    except KeyboardInterrupt:
        print(
            f"interrupted: finished runs are kept in {out}; run the same command to resume", file=sys.stderr
        )
        return 130
    if not args.quiet:
        print(
            f"{res.ran} runs executed on {res.executor} in {res.seconds:.1f} s, "
            f"{res.skipped} already done, {res.failed} failed; store: {out}"
        )
        for key, err in res.failures[:5]:
            print(f"  failed {key[:10]}: {err}")
    if not args.no_report:
        rep = report(out, plots=not args.no_plots)
        if not args.quiet:
            print(f"wrote {out}/summary.md, summary.csv ({len(rep.rows)} configurations)")
    if res.failed:  # the runs ran and some failed: exit status 1
        print(
            f"gapath: {res.failed} of {res.ran} runs failed; their errors are in "
            f"{out}/runs/*.failed.json (run the same command to retry them)",
            file=sys.stderr,
        )
        return 1
    return 0


def status_command(args) -> int:
    from gapath.experiments.store import ResultStore

    store = ResultStore(args.dir)
    st = store.status()
    name = store.spec().to_dict()["name"]
    print(
        f"{name}: {st['done']}/{st['total']} done, {st['failed']} failed, "
        f"{st['pending']} pending" + (f", {st['extra']} stored runs not in the spec" if st["extra"] else "")
    )
    return 0


def report_command(args) -> int:
    from gapath.experiments.report import report

    rep = report(args.dir, plots=not args.no_plots)
    if not args.quiet:
        print(rep.markdown)
        print("wrote " + ", ".join(str(f) for f in rep.files))
    return 0
