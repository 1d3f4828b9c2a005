"""Run an experiment's grid of runs on a process pool or a Dask cluster.

An experiment (:class:`gapath.experiments.spec.ExperimentSpec`, written in
Python, YAML or TOML: see :mod:`gapath.experiments.spec` for the schema) is
a list of runs. Each run is a plain dict executed by the pure function
:func:`run_one`, which returns a JSON-serialisable dict: the front (``F``,
``metrics``, genomes ``X`` and ``paths``), the settings solve ran with, the
seed, the package versions, per-run indicators and the timings.

:func:`run_experiment` hands the runs not yet in the result store
(:class:`gapath.experiments.store.ResultStore`) to an executor-like object,
in tasks of one or more runs (:func:`run_batch`: about ``batch_seconds``
of work each, shorter towards the end; at most two tasks per worker in
flight, more submitted as tasks finish), and writes each run's result as
soon as its task returns:

* by default a local ``concurrent.futures.ProcessPoolExecutor`` with
  ``workers`` processes (default: the number of CPUs; ``workers=0`` runs in
  this process, one run after the other). Its workers are started with
  multiprocessing's ``spawn`` method (they inherit no threads or locks) and,
  on Linux, die with the process that started them; as with any ``spawn``
  pool, a *script* that calls :func:`run_experiment` must do so under
  ``if __name__ == "__main__":`` (the CLI and notebooks need nothing);
* with ``scheduler="tcp://HOST:PORT"`` (or the environment variable
  ``GAPATH_SCHEDULER``) a ``distributed.Client`` connected to that Dask
  scheduler; the workers must have gapath installed and be able to read any
  map *files* of the spec at the same path;
* with ``scheduler="local"`` (or ``GAPATH_SCHEDULER=local``) a Dask
  ``LocalCluster`` of ``workers`` single-threaded worker processes on
  loopback, started with gapath's Dask settings
  (:data:`gapath.experiments.dask_config.DASK_CONFIG`: no worker profiler,
  slow monitors) and closed at the end;
* any object with ``submit(fn, *args)`` (a ``concurrent.futures.Executor``
  or a ``distributed.Client``) passed as ``executor``.

The code path is the same for all of them (``submit(run_batch, runs)``
then the first finished task), and so are the results: a run depends on
its dict only, so the pool, a Dask cluster, any batching or an
interrupted-and-resumed experiment store bit-identical fronts and
indicators (only the ``runtime`` entry, with timings and host, differs).
On a Dask worker started by a nanny, the first task also replaces the
fixed malloc thresholds that the nanny's ``MALLOC_TRIM_THRESHOLD_`` imposes (see
:func:`_tune_malloc`: a page fault per allocated page otherwise, +30-45 %
CPU here).

Per-run indicators (``result["indicators"]``)
    ``feasible`` (a feasible path was found), ``front_size``,
    ``min_length`` (length of the shortest feasible path, or None),
    ``n_obstacles`` of the run's map, ``first_feasible_gen`` (with the
    options ``stop_at_first_feasible`` or ``record_first_feasible``: the
    first generation whose population holds a feasible path, 1 being the
    initial population, None if none did; with them also
    ``min_length_population``, the shortest path of the final population,
    feasible or not) and, with the option
    ``reference``, ``hv_ratio``, ``igd_plus`` and ``reference_points_found``
    against the exact monotone or free front.
"""

from __future__ import annotations

import os
import platform
import time
import traceback
import uuid
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from pymoo.core.callback import Callback

from gapath import solver  # solver.solve at call time (tests replace it)
from gapath.callbacks import population_arrays
from gapath.costmap import costmap_from_settings, costmap_record
from gapath.errors import ConfigError
from gapath.experiments.dask_config import LOCAL_SCHEDULER  # "local": see make_executor
from gapath.experiments.spec import (
    ENGINES,
    ExperimentSpec,
    build_costmap_settings,
    build_workspace,
    config_key,
    load_spec,
    map_label,
    resolve_engine,
    run_key,
)
from gapath.experiments.store import ResultStore, store_versions
from gapath.front import PathFront
from gapath.objectives import LENGTH

__all__ = [
    "ExperimentRun",
    "FirstFeasible",
    "executor_slots",
    "front_from_dict",
    "front_to_dict",
    "make_executor",
    "run_batch",
    "run_experiment",
    "run_one",
    "stable_part",
]

#: Environment variable naming a Dask scheduler (``tcp://HOST:PORT``, or
#: ``local``: a LocalCluster started with gapath's Dask settings).
SCHEDULER_ENV = "GAPATH_SCHEDULER"


# ---------------------------------------------------------------------------
# one run
# ---------------------------------------------------------------------------


def _feasible_count(algorithm) -> int:
    """Paths without interfering cells in the algorithm's population (read
    with :func:`gapath.callbacks.population_arrays`: from the arrays of
    :class:`gapath.algorithms.FastNSGA2`, no pymoo ``Population`` is built)."""

    A = population_arrays(algorithm)
    return 0 if A is None else int(A.feasible.sum())


class FirstFeasible(Callback):
    """A pymoo callback that records the first generation whose population
    holds a feasible path (no interfering cell) and, with ``stop``, ends the
    run there through the algorithm's termination (``terminate()``).

    Parameters
    ----------
    stop : end the run at the first feasible generation.

    Attributes
    ----------
    generation : that generation (pymoo's ``n_gen``: 1 is the initial
        population), or None.

    Examples
    --------
    >>> from gapath import dense_workspace
    >>> from gapath.solver import solve
    >>> cb = FirstFeasible()
    >>> r = solve(dense_workspace(8, 0.3, seed=1), pop_size=20, n_gen=50, seed=1,
    ...           seed_from="none", callback=cb)
    >>> r.n_gen == cb.generation
    True
    """

    def __init__(self, stop: bool = True):
        super().__init__()
        self.stop = bool(stop)
        self.generation = None

    def notify(self, algorithm):
        if self.generation is not None or _feasible_count(algorithm) == 0:
            return
        self.generation = int(algorithm.n_gen)
        if self.stop and algorithm.termination is not None:
            algorithm.termination.terminate()
            algorithm.termination.update(algorithm)


def front_to_dict(front) -> dict:
    """A :class:`gapath.front.PathFront` as JSON-ready lists (exact floats)."""
    return {
        "objectives": list(front.objectives),
        "F": np.asarray(front.F).tolist(),
        "metrics": np.asarray(front.metrics).tolist(),
        "X": np.asarray(front.X).tolist(),
        "paths": [np.asarray(p).tolist() for p in front.paths],
    }


def front_from_dict(d: dict):
    """The :class:`gapath.front.PathFront` of :func:`front_to_dict`."""

    m = len(d["objectives"])
    k = len(d["F"])
    X = np.asarray(d["X"])
    return PathFront(
        tuple(d["objectives"]),
        np.asarray(d["F"], float).reshape(k, m),
        np.asarray(d["metrics"], float).reshape(k, -1) if k else np.zeros((0, 4)),  # 4 + a costmap's layers
        X.reshape(k, -1) if X.size else np.zeros((k, 0)),
        [np.asarray(p, np.int64).reshape(-1, 2) for p in d["paths"]],
    )


def _solve_kwargs(run: dict) -> dict:
    s = dict(run["settings"])
    engine = resolve_engine(run.get("engine", "pymoo"))  # runs stored before: "paper"
    if engine not in ENGINES:
        raise ConfigError(f"unknown engine {engine!r} in a run; expected one of {', '.join(ENGINES)}")
    return dict(
        objectives=tuple(s["objectives"]),
        constraints=s["constraints"],
        penalty=s["penalty"],
        pop_size=s["pop_size"],
        n_gen=s["n_gen"],
        tiebreak=s["tiebreak"],
        sbx_eta=s["sbx_eta"],
        seed_from=s["seed_from"],
        paths=s.get("paths", "monotone"),
        repair=s.get("repair", "edge"),
        engine=engine,
    )


def run_one(run: dict) -> dict:
    """Execute one run of an experiment and return its result.

    A pure function of ``run`` (a dict of :meth:`ExperimentSpec.runs`): the
    same dict gives the same result on any process or machine, except for
    the ``runtime`` entry. Errors do not raise: they give a result with
    ``status: "failed"`` and the error message.

    Parameters
    ----------
    run : ``{"map", "encoding", "engine", "settings", "options", "seed"}``.

    Returns
    -------
    dict with ``key`` (:func:`gapath.experiments.spec.run_key`), ``config``
    (:func:`gapath.experiments.spec.config_key`), ``run``, ``seed``,
    ``status`` (``"ok"`` or ``"failed"``), ``versions``; when ok also
    ``settings`` (as solve reports them), ``front`` (:func:`front_to_dict`),
    ``n_gen``, ``n_eval`` and ``indicators`` (see the module docstring); when
    failed ``error``; always ``runtime`` (``seconds`` of the optimisation,
    ``wall_seconds``, ``started``, ``host``, ``pid``, and a failure's
    ``traceback``).

    Examples
    --------
    >>> spec = ExperimentSpec(settings={"pop_size": 20, "n_gen": 3}, seeds=1)
    >>> r = run_one(spec.runs()[0])
    >>> r["status"], r["n_gen"], r["indicators"]["feasible"]
    ('ok', 3, True)
    """

    started, t0 = time.time(), time.perf_counter()
    result = {
        "key": run_key(run),
        "config": config_key(run),
        "run": run,
        "seed": run["seed"],
        "versions": store_versions(),
    }
    runtime = {"started": started, "host": platform.node(), "pid": os.getpid()}
    try:
        ws = build_workspace(run["map"], run["seed"])
        kwargs = _solve_kwargs(run)
        cm_spec = run["settings"].get("costmap")
        costmap = cm_settings = None
        if cm_spec is not None:  # the layers of the layer objectives, as gapath solve builds them
            cm_settings = build_costmap_settings(cm_spec)
            costmap = costmap_from_settings(cm_settings, ws, kwargs["objectives"])
            if costmap is not None:
                kwargs["costmap"] = costmap
        options = run.get("options") or {}
        watch = None
        if options.get("stop_at_first_feasible") or options.get("record_first_feasible"):
            watch = FirstFeasible(stop=bool(options.get("stop_at_first_feasible")))
        res = solver.solve(
            ws,
            encoding=run["encoding"],
            seed=int(run["seed"]),
            progress=False,
            callback=watch,
            **kwargs,
        )
        if res.interrupted:  # Ctrl-C inside solve: not a result
            raise KeyboardInterrupt
        if cm_settings is not None:
            res.settings["costmap"] = costmap_record(cm_settings, costmap, kwargs["objectives"])
        front = res.front
        indicators = {
            "feasible": len(front) > 0,
            "front_size": len(front),
            "n_obstacles": ws.n_obstacles,
            "min_length": float(front.metrics[:, LENGTH].min()) if len(front) else None,
        }
        if watch is not None:
            indicators["first_feasible_gen"] = watch.generation
            pop = getattr(res.pymoo_result, "pop", None)
            if pop is not None and len(pop):
                lengths = res.problem.metrics(pop.get("X"))[:, LENGTH]
                indicators["min_length_population"] = float(lengths.min())
        if options.get("reference"):
            from gapath.reference import front_quality, reference_front

            ref = reference_front(ws, front.objectives, options["reference"])
            q = front_quality(front.F, ref)
            indicators.update({k: q[k] for k in ("hv_ratio", "igd_plus", "reference_points_found")})
        result.update(
            status="ok",
            settings=res.settings,
            front=front_to_dict(front),
            n_gen=int(res.n_gen),
            n_eval=int(res.n_eval),
            indicators=indicators,
        )
        runtime["seconds"] = res.seconds
    except Exception as exc:  # a failed run is a result too
        result.update(status="failed", error=f"{type(exc).__name__}: {exc}")
        runtime["traceback"] = traceback.format_exc()
    runtime["wall_seconds"] = time.perf_counter() - t0
    result["runtime"] = runtime
    return result


def stable_part(result: dict) -> dict:
    """``result`` without ``runtime`` (timings, host, pid): what must be
    bit-identical wherever and whenever the run executed."""
    return {k: v for k, v in result.items() if k != "runtime"}


# ---------------------------------------------------------------------------
# executors
# ---------------------------------------------------------------------------


class _InlineFuture:
    """A future computed when its result is asked for (``workers=0``)."""

    def __init__(self, fn, args):
        self.fn, self.args, self._done, self._value = fn, args, False, None

    def result(self):
        if not self._done:
            self._value, self._done = self.fn(*self.args), True
        return self._value

    def cancel(self):
        return True


class InlineExecutor:
    """Runs submitted calls in this process, lazily, in submission order."""

    def submit(self, fn, *args, **kwargs):
        return _InlineFuture(fn, args)

    def shutdown(self, wait=True, cancel_futures=False):
        pass


def _die_with_parent() -> None:  # pragma: no cover - runs in pool workers
    """Pool worker initialiser: on Linux, get SIGKILL when the parent dies, so
    a killed experiment leaves no orphaned workers behind."""
    import signal
    import sys

    if sys.platform.startswith("linux"):
        try:
            import ctypes

            ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass


def _process_pool(workers: int):
    """A process pool whose workers start fresh (``spawn``: nothing of this
    process's threads or locks is inherited) and die with this process."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    return ProcessPoolExecutor(
        max_workers=workers, mp_context=mp.get_context("spawn"), initializer=_die_with_parent
    )


def _is_dask(executor) -> bool:
    return type(executor).__module__.startswith("distributed")


def make_executor(workers: int | None = None, scheduler: str | None = None):
    """The executor :func:`run_experiment` uses, and whether it owns it.

    Parameters
    ----------
    workers : processes of the local pool, or with ``scheduler="local"``
        worker processes of the LocalCluster (default ``os.cpu_count()``;
        0: run in this process, pool only).
    scheduler : ``tcp://HOST:PORT`` of a Dask scheduler, or ``"local"``:
        start a Dask LocalCluster of ``workers`` processes on loopback with
        gapath's Dask settings (:func:`gapath.experiments.dask_config.local_client`;
        closed with the client). Default: the ``GAPATH_SCHEDULER``
        environment variable. A ``tcp://`` address wins over ``workers``.

    Returns
    -------
    ``(executor, description)``.

    Raises
    ------
    ConfigError
        On a negative ``workers`` (or 0 with ``"local"``), a scheduler given
        without the ``distributed`` package, a malformed address, or a
        scheduler that cannot be reached.
    """
    scheduler = scheduler or os.environ.get(SCHEDULER_ENV) or None
    if scheduler:
        scheduler = str(scheduler).strip()
        try:
            from distributed import Client
        except ImportError:
            raise ConfigError(
                f"scheduler {scheduler!r} needs the 'distributed' package (pip install 'dask[distributed]')"
            ) from None
        if scheduler.lower() == LOCAL_SCHEDULER:
            from gapath.experiments.dask_config import local_client

            client = local_client(workers)
            n = len(client.nthreads())
            return client, (
                f"Dask LocalCluster of {n} worker process{'es' if n > 1 else ''} (gapath's Dask settings)"
            )
        from distributed.comm.addressing import parse_address, parse_host_port

        # Checked before a Client exists: a Client whose constructor fails is
        # left behind (not freed at once), and its __del__, run later while
        # another Client starts, can deadlock both (seen with distributed
        # 2026.8 in the test suite).
        try:
            parse_host_port(parse_address(scheduler)[1])
        except ValueError as exc:  # e.g. "missing port number in address"
            raise ConfigError(
                f"scheduler {scheduler!r}: {exc}; expected 'local' or the address "
                "of a Dask scheduler, tcp://HOST:PORT"
            ) from None
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise ConfigError(f"cannot connect to the Dask scheduler {scheduler!r}: {exc}") from None
        return client, f"Dask scheduler {scheduler}"
    workers = (os.cpu_count() or 1) if workers is None else int(workers)
    if workers < 0:
        raise ConfigError(f"workers must be >= 0, got {workers}")
    if workers == 0:
        return InlineExecutor(), "this process"
    return _process_pool(workers), f"local pool of {workers} process{'es' if workers > 1 else ''}"


def _is_inline(executor) -> bool:
    return isinstance(executor, InlineExecutor)


def executor_slots(executor) -> int:
    """How many runs ``executor`` executes at once: the pool's processes, the
    Dask cluster's worker threads (at this moment), 1 in-process; for an
    executor it cannot ask, the number of CPUs."""
    if _is_inline(executor):
        return 1
    if _is_dask(executor):
        try:
            return max(1, sum(executor.nthreads().values()))
        except Exception:  # noqa: BLE001 - no answer from the scheduler: guess
            return os.cpu_count() or 1
    n = getattr(executor, "_max_workers", None)
    return max(1, int(n)) if isinstance(n, int) else (os.cpu_count() or 1)


# -- worker side ------------------------------------------------------------

#: Set (to anything) to leave a worker's malloc settings alone (see
#: :func:`_tune_malloc`).
KEEP_MALLOC_ENV = "GAPATH_KEEP_MALLOC"
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
_MALLOC_TUNED = False


def _tune_malloc() -> bool:
    """Undo, in this worker process, the cost of a fixed glibc trim threshold.

    Dask's nanny starts every worker with ``MALLOC_TRIM_THRESHOLD_=65536``
    (``distributed.nanny.pre-spawn-environ``). Setting it switches off
    glibc's adaptive thresholds: every NumPy array above 128 KiB is then
    ``mmap``-ed and unmapped again, and freed heap above 64 KiB is handed
    back to the kernel at once, so a run of the GA takes a fresh page fault
    for almost every page it allocates (measured on the dense-obstacle
    slice: ~450,000 minor faults and +30-45 % CPU per worker). When that
    variable is set, this sets the thresholds glibc's adaptive rule would
    reach at most (mmap above 32 MiB, trim above 64 MiB of free heap) once
    per process; nothing else changes and results do not depend on it.
    Skipped off glibc, without the variable, and when ``GAPATH_KEEP_MALLOC``
    is set. Returns True when it changed the settings."""
    global _MALLOC_TUNED
    if _MALLOC_TUNED:
        return False
    _MALLOC_TUNED = True
    import sys

    if (
        not sys.platform.startswith("linux")
        or "MALLOC_TRIM_THRESHOLD_" not in os.environ
        or os.environ.get(KEEP_MALLOC_ENV)
    ):
        return False
    try:
        import ctypes

        libc = ctypes.CDLL("libc.so.6")
        ok = libc.mallopt(_M_MMAP_THRESHOLD, 32 << 20) == 1
        return libc.mallopt(_M_TRIM_THRESHOLD, 64 << 20) == 1 and ok
    except (OSError, AttributeError):  # not glibc
        return False


def run_batch(runs: list, tune_malloc: bool = True) -> list:
    """:func:`run_one` for each run of ``runs``, in order: the task a pool or
    Dask worker executes. A run that raises (it should not: :func:`run_one`
    returns failures as results) gives a failed result and the others go
    on; ``tune_malloc``: see :func:`_tune_malloc`."""
    if tune_malloc:
        _tune_malloc()
    out = []
    for run in runs:
        try:
            out.append(run_one(run))
        except Exception as exc:  # noqa: BLE001 - one broken run fails alone
            out.append(_lost_run(run, run_key(run), exc))
    return out


# -- client side ------------------------------------------------------------

#: Default seconds of runs per task on a process pool (a task costs the pool
#: about 1.5 ms of CPU, client and worker, with ~40 KB of results).
BATCH_SECONDS = 0.25
#: Default seconds of runs per task on Dask: a task costs about 15 ms of CPU
#: (scheduler, client, nanny and worker event loops; measured on 2 cores),
#: ~6 % of a 0.25 s task and ~1.5 % of a 1 s one. The guided limit
#: (``remaining / (4 x workers)`` runs) still shrinks tasks towards the end.
DASK_BATCH_SECONDS = 1.0


def _submit(executor, batch: list):
    """Submit one task: ``batch``, a list of ``(key, run)``."""
    runs = [run for _, run in batch]
    if _is_dask(executor):
        # a fresh task key per submission: never a cached result of an earlier one
        key = f"gapath-runs-{batch[0][0][:16]}-{len(batch)}-{uuid.uuid4().hex[:12]}"
        return executor.submit(run_batch, runs, key=key, pure=False)
    return executor.submit(run_batch, runs, not _is_inline(executor))


class _Completed:
    """Finished futures one at a time while more are added: Dask's
    ``as_completed``, ``concurrent.futures.wait`` or, in-process, submission
    order (the inline futures compute when asked)."""

    def __init__(self, executor):
        self.kind = "inline" if _is_inline(executor) else "dask" if _is_dask(executor) else "cf"
        self.waiting, self.ready = [], []
        if self.kind == "dask":
            from distributed import as_completed

            self._ac = as_completed()

    def add(self, fut) -> None:
        if self.kind == "dask":
            self._ac.add(fut)
        else:
            self.waiting.append(fut)

    def next(self):
        if self.kind == "dask":
            return next(self._ac)
        if self.kind == "inline":
            return self.waiting.pop(0)
        if not self.ready:
            from concurrent.futures import FIRST_COMPLETED, wait

            done, _ = wait(self.waiting, return_when=FIRST_COMPLETED)
            self.ready = [f for f in self.waiting if f in done]  # submission order
            self.waiting = [f for f in self.waiting if f not in done]
        return self.ready.pop(0)


class _Batcher:
    """Cuts the pending runs into tasks.

    A task holds as many runs as take about ``target_seconds`` by the mean
    time of the last runs that finished (one run until a result is in), at
    most ``max_batch`` and at most ``remaining / (4 * slots)``, so that tasks
    get shorter towards the end and every worker stays busy to the last run
    (guided self-scheduling; 4, not 1, because run times vary: a batch of
    runs averaging 20 ms may hold one of 800 ms). Long runs thus go one per
    task, as before; runs of a few milliseconds go together, so that a
    task's cost is paid once per batch (Dask: about 10 ms of scheduler,
    client and worker event-loop CPU per task, which on a busy machine
    slows the runs themselves; a pool: the client's wake-up and bookkeeping
    per task)."""

    def __init__(
        self, pending, slots: int, *, target_seconds: float = 0.25, max_batch: int = 32, window: int = 16
    ):
        from collections import deque

        self.queue = deque(pending)
        self.slots = max(1, int(slots))
        self.target, self.max_batch = float(target_seconds), max(1, int(max_batch))
        self.recent = deque(maxlen=window)

    def __bool__(self) -> bool:
        return bool(self.queue)

    def observe(self, result: dict) -> None:
        seconds = (result.get("runtime") or {}).get("wall_seconds")
        if result.get("status") == "ok" and seconds is not None:
            self.recent.append(float(seconds))

    def size(self) -> int:
        if not self.recent:
            return 1
        mean = max(sum(self.recent) / len(self.recent), 1e-6)
        guided = len(self.queue) // (4 * self.slots)
        return max(1, min(int(self.target / mean), guided, self.max_batch))

    def take(self) -> list:
        n = min(self.size(), len(self.queue))
        return [self.queue.popleft() for _ in range(n)]


def _close(executor) -> None:
    if _is_dask(executor):
        executor.close()
    else:
        executor.shutdown(wait=True, cancel_futures=True)


def _lost_run(run: dict, key: str, exc: BaseException) -> dict:
    """The failed result of a run whose worker died or whose future broke."""
    return {
        "key": key,
        "config": config_key(run),
        "run": run,
        "seed": run["seed"],
        "versions": store_versions(),
        "status": "failed",
        "error": f"{type(exc).__name__}: {exc}",
        "runtime": {
            "started": time.time(),
            "host": platform.node(),
            "pid": os.getpid(),
            "traceback": "".join(traceback.format_exception(exc)),
        },
    }


# ---------------------------------------------------------------------------
# the experiment
# ---------------------------------------------------------------------------


@dataclass
class ExperimentRun:
    """What :func:`run_experiment` did.

    Attributes
    ----------
    store : the :class:`gapath.experiments.store.ResultStore`.
    total : runs in the experiment.
    skipped : runs already stored when it started.
    ran : runs executed now; ``failed`` of them failed.
    seconds : wall time.
    executor : a description of where the runs executed.
    """

    store: ResultStore
    total: int
    skipped: int
    ran: int
    failed: int
    seconds: float
    executor: str = ""
    failures: list = field(default_factory=list)

    @property
    def complete(self) -> bool:
        """True when every run of the experiment is stored."""
        return self.skipped + self.ran - self.failed == self.total


def _as_spec(spec) -> ExperimentSpec:
    if isinstance(spec, ExperimentSpec):
        return spec
    if isinstance(spec, dict):
        return ExperimentSpec.from_dict(spec)
    if isinstance(spec, (str, Path)):
        return load_spec(spec)
    raise ConfigError(f"expected an ExperimentSpec, a dict or a spec file, got {type(spec).__name__}")


def run_experiment(
    spec,
    out,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    executor=None,
    progress: bool = True,
    retry_failed: bool = True,
    on_result=None,
    batch_seconds: float | None = None,
) -> ExperimentRun:
    """Run every run of ``spec`` not yet stored in ``out``.

    Parameters
    ----------
    spec : an :class:`ExperimentSpec`, a dict of one, or a YAML / TOML /
        JSON spec file.
    out : the store directory (created; an existing one is resumed).
    workers : local pool size (default: the number of CPUs; 0: in process).
    scheduler : a Dask scheduler address ``tcp://HOST:PORT``, or ``"local"``
        (a LocalCluster of ``workers`` processes with gapath's Dask settings,
        started and closed here); default: the ``GAPATH_SCHEDULER``
        environment variable.
    executor : an executor-like object to use instead (not closed here).
    progress : show a tqdm bar over the runs on stderr.
    retry_failed : run again the runs whose last attempt failed.
    on_result : called with each result dict after it is stored.
    batch_seconds : runs go to the workers in tasks of about this many
        seconds (by the mean time of the last runs; one run per task until
        one has finished, and shorter tasks towards the end); each run of a
        task is stored when its task returns. 0: one run per task. Default:
        :data:`BATCH_SECONDS` (0.25 s) on a process pool,
        :data:`DASK_BATCH_SECONDS` (1 s) on Dask, where a task costs about
        15 ms of CPU against the pool's 1.5 ms. Results do not depend on it.

    Returns
    -------
    :class:`ExperimentRun`.

    Raises
    ------
    ConfigError
        On an invalid spec or executor setting.

    Examples
    --------
    >>> import tempfile
    >>> spec = ExperimentSpec(settings={"pop_size": 20, "n_gen": 2}, seeds=2)
    >>> out = tempfile.mkdtemp()
    >>> run_experiment(spec, out, workers=0, progress=False).ran
    2
    >>> run_experiment(spec, out, workers=0, progress=False).skipped
    2
    """
    from tqdm.auto import tqdm

    spec = _as_spec(spec)
    store = ResultStore(out)
    store.initialise(spec)
    runs = spec.runs()
    keyed = {}
    for run in runs:  # identical runs (e.g. a repeated map) execute once
        keyed.setdefault(run_key(run), run)
    done = store.done_keys()
    failed_before = store.failed_keys() - done
    pending = [(k, r) for k, r in keyed.items() if k not in done and (retry_failed or k not in failed_before)]
    skipped = len(keyed) - len(pending)
    t0 = time.perf_counter()
    ran = failed = 0
    failures = []
    description = "nothing to run"
    if pending:
        owned = executor is None
        if owned:
            executor, description = make_executor(workers, scheduler)
        else:
            description = type(executor).__name__
        bar = tqdm(
            total=len(keyed),
            initial=skipped,
            unit="run",
            disable=not progress,
            desc=spec.to_dict()["name"],
            dynamic_ncols=True,
            mininterval=0.5,
        )
        if batch_seconds is None:
            batch_seconds = DASK_BATCH_SECONDS if _is_dask(executor) else BATCH_SECONDS
        batcher = _Batcher(
            pending,
            executor_slots(executor),
            target_seconds=batch_seconds,
            max_batch=1 if _is_inline(executor) or batch_seconds <= 0 else 32,
        )
        completed = _Completed(executor)
        in_flight = {}  # future -> its batch of (key, run)
        checked = time.monotonic()

        def fill():
            nonlocal checked
            if _is_dask(executor) and time.monotonic() - checked > 5.0:  # workers come and go
                batcher.slots, checked = executor_slots(executor), time.monotonic()
            while batcher and len(in_flight) < 2 * batcher.slots:
                batch = batcher.take()
                fut = _submit(executor, batch)
                in_flight[fut] = batch
                completed.add(fut)

        try:
            fill()
            while in_flight:
                fut = completed.next()
                batch = in_flight.pop(fut)
                try:
                    results = fut.result()
                except Exception as exc:  # a worker died: the runs of its task failed
                    results = [_lost_run(run, key, exc) for key, run in batch]
                for result in results:
                    batcher.observe(result)
                fill()  # keep the workers busy while this batch is stored
                for result in results:
                    store.write(result)
                    ran += 1
                    if result["status"] != "ok":
                        failed += 1
                        failures.append((result["key"], result.get("error")))
                        bar.set_postfix_str(f"failed={failed}", refresh=False)
                    bar.update(1)
                    if on_result is not None:
                        on_result(result)
        except BaseException:
            for fut in in_flight:
                fut.cancel()
            raise
        finally:
            bar.close()
            if owned:
                _close(executor)
    return ExperimentRun(
        store, len(keyed), skipped, ran, failed, time.perf_counter() - t0, description, failures
    )


def describe_run(run: dict) -> str:
    """A one-line label of a run (map, encoding, engine, seed)."""
    return f"{map_label(run['map'])} {run['encoding']} {run['engine']} seed {run['seed']}"
