"""``gapath solve`` per generation: both engines, with and without the bar.

Runs :func:`gapath.solver.solve` with the arguments the CLI gives it for
``gapath solve default --pop 500 [--engine pymoo] [--quiet]`` (parsed by the
CLI's own parser), four configurations side by side in one process:
``fast+bar``, ``fast+quiet``, ``pymoo+bar``, ``pymoo+quiet``. After a
warm-up of each engine (numba compilation, the planners that seed the first
population), the configurations run in turn ``--repeats`` times, the order
rotated every repeat.

Per-generation CPU time (``time.process_time``: this process, all threads)
is measured by a callback that solve notifies after its progress bar: the
CPU time between the first generation's notification (the initial
population, its seeding and setup excluded) and the last one, divided by
the generations in between. The bar draws to ``os.devnull`` (tqdm's cost
is the same; the terminal's drawing is another process's).

Records (JSON lines):

* ``cli_engines.run``: one per run (configuration, repeat, ms per
  generation, the generation at which ``algorithm.pop`` was found built by
  a callback, if any: FastNSGA2 builds its pymoo Population lazily and no
  callback should make it);
* ``cli_engines.summary``: medians per configuration, the fast engine's
  speed-up over pymoo with and without the bar, the bar's overhead in per
  cent of a generation of the same engine (the difference of the medians,
  and, less exposed to the machine's noise, the CPU time spent inside the
  bar's ``notify``, measured in separate runs), and that of the hypervolume
  tracker ``gapath solve --reference monotone`` adds (a fifth
  configuration, ``fast+bar+reference``).

The machine is shared (2 cores): the load average is printed with every
record; timings are medians of interleaved repeats.

Usage: python benchmarks/bench_cli_engines.py [--gen G] [--pop P] [--repeats N] [--quick]
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import platform
import statistics
import time

from pymoo.core.callback import Callback

import gapath.callbacks
from gapath import default_workspace
from gapath.callbacks import Callbacks
from gapath.cli.main import build_parser
from gapath.convergence import HypervolumeRatioCallback
from gapath.reference import reference_front
from gapath.solver import solve

CONFIGS = (("fast", True), ("fast", False), ("pymoo", True), ("pymoo", False))


def emit(**record):
    record.setdefault(
        "machine", f"{platform.machine()} {os.cpu_count()} cpu, python {platform.python_version()}"
    )
    record["load_avg_1min"] = round(os.getloadavg()[0], 2)
    print(json.dumps(record), flush=True)


def cli_kwargs(argv):
    """``solve``'s keyword arguments for ``gapath solve ARGV`` (as ``gapath.cli._run``)."""
    args = build_parser().parse_args(["solve", "default", *argv])
    return dict(
        objectives=args.objectives,
        encoding=args.encoding,
        constraints=args.constraints,
        penalty=args.penalty,
        pop_size=args.pop,
        n_gen=args.gen,
        tiebreak=None if args.tiebreak == "none" else args.tiebreak,
        sbx_eta=args.sbx_eta,
        seed_from=args.seed_from,
        engine=args.engine,
        progress=not args.quiet,
        seed=args.seed,
    )


class GenerationClock(Callback):
    """CPU time at the first and the last generation notified; the first
    generation at which a FastNSGA2 had its pymoo ``pop`` built."""

    def __init__(self):
        super().__init__()
        self.first = self.last = None
        self.pop_built_at = None

    def notify(self, algorithm):
        t = time.process_time()
        gen = int(algorithm.n_gen)
        if self.first is None:
            self.first = (gen, t)
        self.last = (gen, t)
        if (
            self.pop_built_at is None
            and getattr(algorithm, "_pop", None) is not None
            and hasattr(algorithm, "arrays")
        ):
            self.pop_built_at = gen

    def ms_per_gen(self) -> float:
        (g0, t0), (g1, t1) = self.first, self.last
        return 1000.0 * (t1 - t0) / (g1 - g0)


class BarTimer:
    """CPU time spent inside ``ProgressBar.notify`` (wrapped while active)."""

    def __init__(self):
        self.seconds = 0.0
        self.calls = 0

    def __enter__(self):
        original = self.original = gapath.callbacks.ProgressBar.notify

        def timed(bar, algorithm):
            t = time.process_time()
            original(bar, algorithm)
            self.seconds += time.process_time() - t
            self.calls += 1

        gapath.callbacks.ProgressBar.notify = timed
        return self

    def __exit__(self, *exc):
        gapath.callbacks.ProgressBar.notify = self.original


def run(ws, engine, bar, common, reference=None):
    """One ``solve`` as ``gapath solve default COMMON [--engine pymoo] [--quiet]``
    (with ``reference``: ``--reference monotone``, the CLI's hv tracker)."""
    argv = [*common] + ([] if engine == "fast" else ["--engine", "pymoo"]) + ([] if bar else ["--quiet"])
    clock = GenerationClock()
    callback = clock if reference is None else Callbacks(HypervolumeRatioCallback(reference), clock)
    with open(os.devnull, "w") as sink, contextlib.redirect_stderr(sink):
        r = solve(ws, callback=callback, **cli_kwargs(argv))
    return r, clock


def run_timing_bar(ws, engine, common):
    """The bar's own CPU time per generation (inside its ``notify``), in µs."""
    with BarTimer() as timer:
        run(ws, engine, True, common)
    return 1e6 * timer.seconds / timer.calls


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pop", type=int, default=500)
    ap.add_argument("--gen", type=int, default=500, help="generations per run (CLI default 500)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="pop 100, 30 generations, 1 repeat")
    a = ap.parse_args(argv)
    if a.quick:
        a.pop, a.gen, a.repeats = 100, 30, 1
    ws = default_workspace()
    common = ["--pop", str(a.pop), "--gen", str(a.gen)]
    for engine in ("fast", "pymoo"):  # warm-up: numba compile, planners
        run(ws, engine, True, ["--pop", str(a.pop), "--gen", "3"])
    reference = reference_front(ws, ["length", "vulnerability"], "monotone")
    configs = CONFIGS + (("fast", "reference"),)
    times = {c: [] for c in configs}
    fronts = {}
    for rep in range(a.repeats):
        k = rep % len(configs)
        for engine, bar in configs[k:] + configs[:k]:
            r, clock = run(ws, engine, bool(bar), common, reference if bar == "reference" else None)
            ms = clock.ms_per_gen()
            times[(engine, bar)].append(ms)
            fronts.setdefault(engine, r.front.F.tolist())
            emit(
                record="cli_engines.run",
                engine=engine,
                bar=bar,
                repeat=rep,
                pop=a.pop,
                n_gen=a.gen,
                cpu_ms_per_gen=round(ms, 4),
                pop_built_at=clock.pop_built_at,
                front_size=len(r.front),
            )
    bar_us = {
        e: statistics.median(run_timing_bar(ws, e, common) for _ in range(a.repeats))
        for e in ("fast", "pymoo")
    }
    label = {True: "bar", False: "quiet", "reference": "bar+reference"}
    med = {f"{e}+{label[b]}": statistics.median(v) for (e, b), v in times.items()}
    emit(
        record="cli_engines.summary",
        pop=a.pop,
        n_gen=a.gen,
        repeats=a.repeats,
        clock="process_time (CPU)",
        cpu_ms_per_gen={k: round(v, 4) for k, v in med.items()},
        speedup_with_bar=round(med["pymoo+bar"] / med["fast+bar"], 2),
        speedup_quiet=round(med["pymoo+quiet"] / med["fast+quiet"], 2),
        bar_overhead_pct={
            e: round(100 * (med[f"{e}+bar"] / med[f"{e}+quiet"] - 1), 2) for e in ("fast", "pymoo")
        },
        bar_notify_cpu_us_per_gen={e: round(v, 2) for e, v in bar_us.items()},
        bar_notify_pct_of_gen={e: round(100 * v / (1000 * med[f"{e}+bar"]), 3) for e, v in bar_us.items()},
        reference_tracker_pct=round(100 * (med["fast+bar+reference"] / med["fast+bar"] - 1), 2),
        same_front=fronts["fast"] == fronts["pymoo"],
        targets={"speedup_with_bar": ">= 15", "bar_overhead_pct": "<= 5"},
    )


if __name__ == "__main__":
    main()
