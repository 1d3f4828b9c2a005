"""Experiment runner throughput and result-store overhead (JSON lines).

Prints one JSON object per line:

* ``runs_per_minute`` of a slice of the dense-obstacle experiment (Table 1,
  32x32, p0 0.4, 0.6, 0.8 and 1.0, 8 runs each, population 200, stop at the
  first feasible path, engine ``auto``) on
  the local process pool with 1 and with 2 workers, and on a 2-worker Dask
  ``LocalCluster`` (loopback, one process per worker); executors are
  started and warmed up once, then timed over ``--repeat`` fresh stores
  (medians), so the figures are steady-state throughput. The pool's cold
  start (spawning its workers) is reported apart.
* ``store_overhead``: milliseconds per run spent by the store: hashing the
  run (``run_key``), writing its result atomically, and the directory
  listing that decides what to skip (targets: < 5 ms per run).

Run: ``.venv/bin/python benchmarks/bench_experiments.py [--quick] [--repeat 3]``.
The machine may be shared: timings are noisy, compare medians.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import tempfile
import time


def slice_spec(quick: bool):
    from gapath.experiments.dense import table1_spec

    if quick:
        return table1_spec(grids=(16,), p0s=(0.4, 0.6), runs=4, engine="auto", name="bench-slice")
    return table1_spec(grids=(32,), p0s=(0.4, 0.6, 0.8, 1.0), runs=8, engine="auto", name="bench-slice")


def timed_runs(spec, executor, repeat: int) -> list[float]:
    from gapath.experiments.runner import run_experiment

    times = []
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as d:
            t0 = time.perf_counter()
            r = run_experiment(spec, d, executor=executor, progress=False)
            times.append(time.perf_counter() - t0)
            assert r.failed == 0 and r.complete
    return times


def warm(executor, spec) -> None:
    """Run a few runs so that every worker has imported gapath and compiled
    its kernels."""
    from gapath.experiments.runner import _submit, run_one  # noqa: F401
    from gapath.experiments.spec import run_key

    runs = spec.runs()[:4]
    for f in [_submit(executor, r, run_key(r) + f"-warm{i}") for i, r in enumerate(runs)]:
        f.result()


def line(**kw) -> None:
    kw.setdefault("load_average", [round(x, 2) for x in os.getloadavg()])
    print(json.dumps(kw), flush=True)


def bench_throughput(spec, repeat: int) -> None:
    from gapath.experiments.runner import _process_pool

    n = len(spec)
    results = {}
    for workers in (1, 2):
        t0 = time.perf_counter()
        pool = _process_pool(workers)
        warm(pool, spec)
        cold = time.perf_counter() - t0
        try:
            times = timed_runs(spec, pool, repeat)
        finally:
            pool.shutdown()
        med = statistics.median(times)
        results[f"pool{workers}"] = med
        line(bench="runs_per_minute", executor=f"local pool, {workers} worker(s)", runs=n,
             median_s=round(med, 3), runs_per_minute=round(60 * n / med, 1),
             times_s=[round(t, 3) for t in times], startup_and_warmup_s=round(cold, 2))
    try:
        import distributed
    except ImportError:
        line(bench="runs_per_minute", executor="dask", skipped="distributed not installed")
        return
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        with distributed.Client(cluster.scheduler_address) as client:
            warm(client, spec)
            times = timed_runs(spec, client, repeat)
    med = statistics.median(times)
    line(bench="runs_per_minute", executor="dask LocalCluster, 2 worker processes", runs=n,
         median_s=round(med, 3), runs_per_minute=round(60 * n / med, 1),
         times_s=[round(t, 3) for t in times])
    line(bench="scaling", speedup_2_vs_1_workers=round(results["pool1"] / results["pool2"], 3),
         dask_vs_pool2_time_ratio=round(med / results["pool2"], 3), target_dask_within=0.10)


def bench_store(n: int = 300) -> None:
    from gapath.experiments.runner import run_one
    from gapath.experiments.spec import ExperimentSpec, run_key
    from gapath.experiments.store import ResultStore

    # a realistic result: the default 32x32 scenario, a full front
    spec = ExperimentSpec(engines=["auto"], settings={"pop_size": 100, "n_gen": 30}, seeds=1)
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
    med = {k: statistics.median(v) * 1e3 for k, v in (("hash", hash_t), ("write", write_t), ("listing", list_t))}
    line(bench="store_overhead", runs=n, result_bytes=size, files=files,
         hash_ms=round(med["hash"], 3), write_ms=round(med["write"], 3),
         listing_ms_per_run=round(med["listing"], 4),
         total_ms_per_run=round(sum(med.values()), 3), target_ms=5.0,
         front_size=result["indicators"]["front_size"])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a smaller slice, one repetition")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-throughput", action="store_true")
    args = ap.parse_args()
    from gapath.experiments.spec import resolve_engine

    line(bench="setup", cpus=os.cpu_count(), engine=resolve_engine("auto"))
    bench_store(60 if args.quick else 300)
    if not args.no_throughput:
        bench_throughput(slice_spec(args.quick), 1 if args.quick else args.repeat)


if __name__ == "__main__":
    main()
