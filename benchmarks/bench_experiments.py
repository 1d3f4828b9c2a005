"""Experiment runner throughput and result-store overhead (JSON lines).

Prints one JSON object per line:

* ``runs_per_minute`` of a slice of the dense-obstacle experiment (Table 1,
  population 200, stop at the first feasible path, engine ``fast``):
  by default ``--slice table1``, the 16x16 and 32x32 rows at p0 0.3 to 1.0,
  20 runs each (320 runs of 0.01-4 s; about 50 s on 2 workers); ``dense32``:
  the earlier 32 runs (32x32, p0 0.4/0.6/0.8/1.0, 8 each); ``short``: 64
  runs of 16x16, mostly 10-50 ms each. Executors: the local process pool
  with 1 and with 2 workers (``pool1``, ``pool2``); a 2-worker Dask
  ``LocalCluster`` (loopback, one process per worker) with Dask's default
  settings, connected to by address as a user's own cluster would be
  (``dask``); and ``dask-local``: what ``gapath experiment run --scheduler
  local --workers 2`` does (``make_executor(2, "local")``: a LocalCluster
  started with gapath's Dask settings, ``gapath.experiments.dask_config``).
  ``--repeat`` rounds: each round starts every executor, warms up every one
  of its workers (imports, numba compilation, the worker's malloc settings)
  outside the timed region, times one ``run_experiment`` of the slice into
  a fresh store and shuts the executor down; rounds alternate the order.
  Reported: medians, every round's time, the CPU seconds of all processes
  (this one with the client, and with a LocalCluster the scheduler and
  nannies, plus the workers), Dask / pool ratios (of medians and per round)
  and start-up apart. Every executor runs with ``run_experiment``'s default
  batching (tasks of about 0.25 s of runs on the pool, 1 s on Dask);
  ``NAME@B`` entries of ``--executors`` set ``batch_seconds=B`` (``@0``:
  one run per task).
* ``store_overhead``: milliseconds per run spent by the store: hashing the
  run (``run_key``), writing its result atomically, and the directory
  listing that decides what to skip (targets: < 5 ms per run).

Run: ``.venv/bin/python benchmarks/bench_experiments.py [--quick] [--repeat 5]
[--slice table1|dense32|short] [--executors pool1,pool2,dask,dask-local]``.
The machine may be shared: timings are noisy, compare medians and the
per-round ratios.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import statistics
import tempfile
import time

#: p0 of the rows of the default slice (``--slice table1``).
TABLE1_P0S = (0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)


def slice_spec(quick: bool, which: str = "table1"):
    """The timed slice: ``table1`` (320 runs: the 16x16 and 32x32 rows of
    Table 1 at p0 0.3-1.0, seeds 1-20), ``dense32`` (32 runs, 32x32, 0.04-2 s
    each), ``short`` (64 runs, 16x16, p0 0.2-0.8, mostly 10-50 ms each: where
    a task's cost shows), or with ``quick`` 8 runs of 16x16."""
    from gapath.studies.dense import table1_spec

    if quick:
        return table1_spec(grids=(16,), p0s=(0.4, 0.6), runs=4, engine="fast", name="bench-slice")
    if which == "short":
        return table1_spec(grids=(16,), p0s=(0.2, 0.4, 0.6, 0.8), runs=16, engine="fast", name="bench-short")
    if which == "dense32":
        return table1_spec(grids=(32,), p0s=(0.4, 0.6, 0.8, 1.0), runs=8, engine="fast", name="bench-slice")
    return table1_spec(grids=(16, 32), p0s=TABLE1_P0S, runs=20, engine="fast", name="bench-table1")


def _cpu_seconds() -> float:
    """CPU seconds of this process and all its children (pool workers; with
    a LocalCluster also its worker processes; scheduler, nannies and client
    run in this process)."""
    import psutil

    me = psutil.Process()
    total = 0.0
    for p in [me, *me.children(recursive=True)]:
        try:
            t = p.cpu_times()
            total += t.user + t.system
        except psutil.Error:
            pass
    return total


def timed_run(spec, executor, batch_seconds: float | None) -> tuple[float, float]:
    """Wall and CPU seconds (all processes) of the whole slice into a fresh store."""
    from gapath.experiments.runner import run_experiment

    with tempfile.TemporaryDirectory() as d:
        c0, t0 = _cpu_seconds(), time.perf_counter()
        r = run_experiment(spec, d, executor=executor, progress=False, batch_seconds=batch_seconds)
        wall, cpu = time.perf_counter() - t0, _cpu_seconds() - c0
        assert r.failed == 0 and r.complete
    return wall, cpu


def warm(executor, spec) -> None:
    """Before the timed region, every worker of ``executor`` imports gapath,
    compiles its kernels and (Dask) sets its malloc thresholds, by running
    the spec's first run: on each Dask worker with ``Client.run``; on the
    pool with tasks until every process has answered."""
    from gapath.experiments.runner import _is_dask, executor_slots, run_batch

    runs = spec.runs()[:1]
    if _is_dask(executor):
        executor.run(run_batch, runs)
        return
    slots, seen = executor_slots(executor), set()
    for _ in range(20):
        futures = [executor.submit(run_batch, runs) for _ in range(2 * slots)]
        seen |= {f.result()[0]["runtime"]["pid"] for f in futures}
        if len(seen) >= slots:
            return
    raise RuntimeError(f"only {len(seen)} of {slots} pool workers answered the warm-up")


def line(**kw) -> None:
    kw.setdefault("load_average", [round(x, 2) for x in os.getloadavg()])
    print(json.dumps(kw), flush=True)


#: Executors of the throughput figure: name -> description.
EXECUTORS = {
    "pool1": "local pool, 1 worker",
    "pool2": "local pool, 2 workers",
    "dask": "dask LocalCluster, 2 worker processes, Dask's default settings (client by address)",
    "dask-local": "--scheduler local: dask LocalCluster, 2 worker processes, gapath's Dask settings",
    # diagnostics, not run by default
    "dask-keep-malloc": "dask LocalCluster, 2 worker processes, GAPATH_KEEP_MALLOC=1 "
    "(the nanny's MALLOC_TRIM_THRESHOLD_ left in force)",
    "dask-noprofile": "dask LocalCluster, 2 worker processes, worker profiler off",
    "dask-lean": "dask LocalCluster, 2 worker processes, gapath's Dask settings (client by address)",
    "dask-local-default": "local_client(2, config={}): --scheduler local's code path, Dask's defaults",
}


@contextlib.contextmanager
def started(name: str):
    """The executor ``name``, started (not warmed up); closed on exit."""
    from gapath.experiments.dask_config import DASK_CONFIG, local_client
    from gapath.experiments.runner import _close, _process_pool, make_executor

    if name.startswith("pool"):
        pool = _process_pool(int(name[4:]))
        try:
            yield pool
        finally:
            pool.shutdown()
        return
    if name in ("dask-local", "dask-local-default"):
        # exactly what `--scheduler local --workers 2` starts (make_executor), or
        # the same code path with Dask's defaults
        client = make_executor(2, "local")[0] if name == "dask-local" else local_client(2, config={})
        try:
            yield client
        finally:
            _close(client)
        return
    import dask
    import distributed

    env = {"GAPATH_KEEP_MALLOC": "1"} if name == "dask-keep-malloc" else {}
    config = {"dask-noprofile": {"distributed.worker.profile.enabled": False}, "dask-lean": DASK_CONFIG}.get(
        name, {}
    )
    with dask.config.set(config):
        with distributed.LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
            env=env,
        ) as cluster:
            with distributed.Client(cluster.scheduler_address) as client:
                client.wait_for_workers(2)
                yield client


def _batch_of(entry: str, default: float | None) -> tuple[str, float | None]:
    """``"dask@0"`` -> ``("dask", 0.0)``; without ``@``, ``default`` (None:
    run_experiment's default for the executor)."""
    name, _, b = entry.partition("@")
    if name not in EXECUTORS:
        raise SystemExit(f"unknown executor {name!r}: one of {', '.join(EXECUTORS)}")
    return name, (float(b) if b else default)


def _effective_batch(name: str, batch: float | None) -> float:
    """The batch_seconds run_experiment uses for executor ``name``."""
    from gapath.experiments.runner import BATCH_SECONDS, DASK_BATCH_SECONDS

    if batch is not None:
        return batch
    return DASK_BATCH_SECONDS if name.startswith("dask") else BATCH_SECONDS


def bench_throughput(spec, rounds: int, executors, batch_seconds: float | None) -> None:
    """Interleaved: each round starts, warms up and times every executor once
    (in reverse order every other round) and shuts it down before the next
    starts, so that load from other jobs falls on all of them alike and an
    idle cluster never runs beside a timed pool. An entry ``NAME@B`` runs
    with ``batch_seconds=B``."""
    if any(e.startswith("dask") for e in executors):
        try:
            import distributed  # noqa: F401
        except ImportError:
            line(bench="runs_per_minute", executor="dask", skipped="distributed not installed")
            executors = [e for e in executors if not e.startswith("dask")]
    n = len(spec)
    walls = {e: [] for e in executors}
    cpus = {e: [] for e in executors}
    cold = {e: [] for e in executors}
    for i in range(rounds):
        for entry in executors if i % 2 == 0 else executors[::-1]:
            name, batch = _batch_of(entry, batch_seconds)
            t0 = time.perf_counter()
            with started(name) as ex:
                warm(ex, spec)
                cold[entry].append(time.perf_counter() - t0)
                wall, cpu = timed_run(spec, ex, batch)
            walls[entry].append(wall)
            cpus[entry].append(cpu)
            line(bench="round", round=i + 1, name=entry, wall_s=round(wall, 3), cpu_s=round(cpu, 2))
    med = {}
    for entry in executors:
        name, batch = _batch_of(entry, batch_seconds)
        med[entry] = statistics.median(walls[entry])
        line(
            bench="runs_per_minute",
            name=entry,
            executor=EXECUTORS[name],
            batch_seconds=_effective_batch(name, batch),
            runs=n,
            median_s=round(med[entry], 3),
            runs_per_minute=round(60 * n / med[entry], 1),
            times_s=[round(t, 3) for t in walls[entry]],
            cpu_s=[round(c, 2) for c in cpus[entry]],
            startup_and_warmup_s=round(statistics.median(cold[entry]), 2),
        )
    out = {}
    if "pool1" in med and "pool2" in med:
        out["speedup_2_vs_1_workers"] = round(med["pool1"] / med["pool2"], 3)
        out["speedup_2_vs_1_workers_per_round"] = [
            round(a / b, 3) for a, b in zip(walls["pool1"], walls["pool2"])
        ]
    if "pool2" in med:
        for entry in executors:
            if entry != "pool2" and not entry.startswith("pool1"):
                key = entry.replace("-", "_")
                out[f"{key}_vs_pool2_time_ratio"] = round(med[entry] / med["pool2"], 3)
                # the same round's timings, paired
                out[f"{key}_vs_pool2_paired_ratios"] = [
                    round(a / b, 3) for a, b in zip(walls[entry], walls["pool2"])
                ]
                out[f"{key}_vs_pool2_cpu_ratio"] = round(
                    statistics.median(cpus[entry]) / statistics.median(cpus["pool2"]), 3
                )
    if out:
        line(
            bench="scaling",
            batch_seconds=batch_seconds,
            rounds=rounds,
            runs=n,
            target_dask_within=0.10,
            **out,
        )


def bench_store(n: int = 300) -> None:
    from gapath.experiments.runner import run_one
    from gapath.experiments.spec import ExperimentSpec, run_key
    from gapath.experiments.store import ResultStore

    # a realistic result: the default 32x32 scenario, a full front
    spec = ExperimentSpec(engines=["fast"], settings={"pop_size": 100, "n_gen": 30}, seeds=1)
    run = spec.runs()[0]
    result = run_one(run)
    size = len(json.dumps(result))
    with tempfile.TemporaryDirectory() as d:
        store = ResultStore(d)
        store.runs_dir.mkdir(parents=True)
        hash_t, write_t, list_t = [], [], []
        for i in range(n):
            r = dict(run, seed=1000 + i)
            t0 = time.perf_counter()
            key = run_key(r)
            t1 = time.perf_counter()
            store.write(dict(result, key=key, run=r, seed=r["seed"]))
            t2 = time.perf_counter()
            store.done_keys()
            t3 = time.perf_counter()
            hash_t.append(t1 - t0)
            write_t.append(t2 - t1)
            list_t.append((t3 - t2) / (i + 1))  # one listing serves every run of an invocation
        files = len(os.listdir(store.runs_dir))
    med = {
        k: statistics.median(v) * 1e3 for k, v in (("hash", hash_t), ("write", write_t), ("listing", list_t))
    }
    line(
        bench="store_overhead",
        runs=n,
        result_bytes=size,
        files=files,
        hash_ms=round(med["hash"], 3),
        write_ms=round(med["write"], 3),
        listing_ms_per_run=round(med["listing"], 4),
        total_ms_per_run=round(sum(med.values()), 3),
        target_ms=5.0,
        front_size=result["indicators"]["front_size"],
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a smaller slice, one repetition")
    ap.add_argument("--repeat", type=int, default=3, help="rounds (every executor once per round)")
    ap.add_argument("--no-throughput", action="store_true")
    ap.add_argument("--no-store", action="store_true", help="skip the store overhead figure")
    ap.add_argument(
        "--executors",
        default="pool1,pool2,dask,dask-local",
        help=f"comma-separated, of {', '.join(EXECUTORS)}; NAME@B: with batch_seconds B "
        "(default: pool1,pool2,dask,dask-local)",
    )
    ap.add_argument(
        "--slice",
        choices=("table1", "dense32", "short"),
        default="table1",
        help="the timed slice (see slice_spec)",
    )
    ap.add_argument(
        "--batch-seconds",
        type=float,
        default=None,
        help="run_experiment's batch_seconds (0: one run per task; default: "
        "run_experiment's, 0.25 s on the pool and 1 s on Dask)",
    )
    args = ap.parse_args()
    line(bench="setup", cpus=os.cpu_count(), engine="fast")
    if not args.no_store:
        bench_store(60 if args.quick else 300)
    if not args.no_throughput:
        bench_throughput(
            slice_spec(args.quick, args.slice),
            1 if args.quick else args.repeat,
            args.executors.split(","),
            args.batch_seconds,
        )


if __name__ == "__main__":
    main()
