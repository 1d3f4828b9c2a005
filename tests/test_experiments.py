"""Experiment runner, spec files, result store, Dask equality, SIGKILL resume,
reports and the ``gapath experiment`` CLI."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from experiment_cases import small_spec, stored

from gapath import ConfigError
from gapath.cli import main
from gapath.experiments import merge_fronts
from gapath.experiments import runner as runner_mod
from gapath.experiments.report import report
from gapath.experiments.runner import FirstFeasible, front_from_dict, run_experiment, run_one
from gapath.experiments.spec import ExperimentSpec, canonical_json, config_key, load_spec, run_key
from gapath.experiments.store import ResultStore

YAML_SPEC = """\
name: small
maps:
  - default
  - {dense: {n: 8, p0: 0.4, seed: run}}
engines: [paper]
settings:
  objectives: length,vulnerability
  n_gen: 4
  seed_from: none
grid:
  pop_size: [12, 16]
seeds: {start: 1, count: 2}
options:
  record_first_feasible: true
"""

TOML_SPEC = """\
name = "small"
maps = ["default", {dense = {n = 8, p0 = 0.4, seed = "run"}}]
engines = ["paper"]
seeds = {start = 1, count = 2}

[settings]
objectives = ["length", "vulnerability"]
n_gen = 4
seed_from = "none"

[grid]
pop_size = [12, 16]

[options]
record_first_feasible = true
"""


def aggregate_files(out) -> dict:
    """Every file of the report that must not depend on how runs executed."""
    out = Path(out)
    files = [out / "summary.csv", out / "summary.md", *sorted((out / "fronts").glob("*.csv"))]
    return {f.relative_to(out).as_posix(): f.read_bytes() for f in files}


# ---------------------------------------------------------------------------
# specs
# ---------------------------------------------------------------------------


def test_yaml_and_toml_specs_expand_to_the_same_runs(tmp_path):
    (tmp_path / "e.yaml").write_text(YAML_SPEC)
    (tmp_path / "e.toml").write_text(TOML_SPEC)
    a, b = load_spec(tmp_path / "e.yaml"), load_spec(tmp_path / "e.toml")
    assert len(a) == len(a.runs()) == 2 * 2 * 2
    assert [run_key(r) for r in a.runs()] == [run_key(r) for r in b.runs()]
    r = a.runs()[0]
    assert r["settings"]["pop_size"] == 12 and r["settings"]["constraints"] == "penalty"
    assert r["settings"]["sbx_eta"] == 10.0 and r["settings"]["penalty"] == 1000.0
    assert [x["seed"] for x in a.runs()[:2]] == [1, 2]
    # the normalised spec round-trips
    c = ExperimentSpec.from_dict(json.loads(json.dumps(a.to_dict())))
    assert [run_key(x) for x in c.runs()] == [run_key(x) for x in a.runs()]


@pytest.mark.parametrize(
    "text, suffix, match",
    [
        (
            "maps: [default]\nsettings: {pop_sise: 3}\n",
            ".yaml",
            r"e\.yaml: settings\.pop_sise: unknown setting",
        ),
        (
            "maps: [{dense: {n: 8, p0: 1.5}}]\n",
            ".yaml",
            r"e\.yaml: maps\[0\]\.dense\.p0: expected a number in \[0\.0, 1\.0\]",
        ),
        ("maps: [{maze: {n: 8}}]\n", ".yaml", r"maps\[0\]\.maze: unknown map kind"),
        ("maps: [nothere.map]\n", ".yaml", r"maps\[0\]\.file\.path: cannot read map file"),
        ("grid: {pop_size: 20}\n", ".yaml", r"grid\.pop_size: expected a non-empty list"),
        ("grid: {n_gen: [5, x]}\n", ".yaml", r"grid\.n_gen\[1\]: expected an integer"),
        (
            "settings: {objectives: [length, speed]}\n",
            ".yaml",
            r"settings\.objectives: unknown objective 'speed'",
        ),
        ("engines: [turbo]\n", ".yaml", r"engines\[0\]: unknown engine 'turbo'"),
        ("seeds: {start: 1, cnt: 3}\n", ".yaml", r"seeds\.cnt: unknown key"),
        (
            "options: {stop_at_first_feasible: yes please}\n",
            ".yaml",
            r"options\.stop_at_first_feasible: expected true or false",
        ),
        ("runs: 3\n", ".yaml", r"e\.yaml: runs: unknown key"),
        ("maps: [default\nseeds: 2\n", ".yaml", r"e\.yaml, line \d+, column \d+: invalid YAML"),
        ('maps = ["default"\nseeds = 2\n', ".toml", r"e\.toml: invalid TOML: .*line"),
        (
            '[settings]\npop_size = "big"\n',
            ".toml",
            r"e\.toml: settings\.pop_size: expected an integer, got 'big'",
        ),
        ("", ".yaml", r"e\.yaml: the experiment spec is empty"),
        ("a = 1", ".ini", r"unknown spec format"),
        (
            "maps: [{default: {start: [31, 40]}}]\n",
            ".yaml",
            r"e\.yaml: maps\[0\]\.default: start \(31, 40\) is outside the 32x32 grid",
        ),
        (
            "maps: [{default: {goal: [0, 0]}}]\n",
            ".yaml",
            r"maps\[0\]\.default: goal \(0, 0\) is on an obstacle",
        ),
        (
            "maps: [{random: {shape: [8, 8], obstacles: 5, seed: run, goal: [0, 8]}}]\n",
            ".yaml",
            r"maps\[0\]\.random: goal \(0, 8\) is outside the 8x8 grid",
        ),
        (
            "maps: [{dense: {n: 8, p0: 0.2, start: [3, 3], goal: [3, 3]}}]\n",
            ".yaml",
            r"maps\[0\]\.dense: start and goal share a column",
        ),
    ],
)
def test_spec_errors_name_the_file_and_the_key(tmp_path, text, suffix, match):
    path = tmp_path / f"e{suffix}"
    path.write_text(text)
    with pytest.raises(ConfigError, match=match):
        load_spec(path)


def test_map_file_start_and_goal_checked_when_the_spec_is_read(tmp_path):
    (tmp_path / "m.txt").write_text("....\n.#..\n....\n")
    for entry, match in [
        ("{file: {path: m.txt, start: [1, 1]}}", r"maps\[0\]\.file: .*start \(1, 1\) is on an obstacle"),
        ("{file: {path: m.txt, goal: [3, 0]}}", r"maps\[0\]\.file: .*goal \(3, 0\) is outside the 3x4 grid"),
    ]:
        (tmp_path / "e.yaml").write_text(f"maps: [{entry}]\n")
        with pytest.raises(ConfigError, match=match):
            load_spec(tmp_path / "e.yaml")
    (tmp_path / "e.yaml").write_text("maps: [{file: {path: m.txt, start: [2, 0], goal: [0, 3]}}]\n")
    assert len(load_spec(tmp_path / "e.yaml").runs()) == 1


def test_binary_spec_file_is_named(tmp_path):
    path = tmp_path / "e.yaml"
    path.write_bytes(bytes(range(128, 256)))
    with pytest.raises(ConfigError, match=r"e\.yaml: not a text file"):
        load_spec(path)


def test_map_files_relative_to_the_spec_and_identified_by_content(tmp_path):
    from gapath.generators import random_workspace
    from gapath.loaders import save_movingai

    ws = random_workspace((10, 12), 20, seed=3)
    for d in ("a", "b"):
        (tmp_path / d).mkdir()
        save_movingai(ws, tmp_path / d / "m.map")
        (tmp_path / d / "e.yaml").write_text("maps: [m.map, {file: {path: m.map, corner_cutting: false}}]\n")
    a, b = load_spec(tmp_path / "a" / "e.yaml"), load_spec(tmp_path / "b" / "e.yaml")
    ra, rb = a.runs(), b.runs()
    assert ra[0]["map"]["file"]["path"] == str((tmp_path / "a" / "m.map").resolve())
    assert run_key(ra[0]) == run_key(rb[0]) and run_key(ra[0]) != run_key(ra[1])
    # a changed file is noticed when a run builds its map
    (tmp_path / "a" / "m.map").write_text((tmp_path / "a" / "m.map").read_text().replace(".", "@", 3))
    assert run_one(ra[0])["error"].startswith("ConfigError: map file")


def test_run_keys_are_stable_canonical_hashes():
    spec = ExperimentSpec(
        maps=[{"dense": {"n": 8, "p0": 0.3, "seed": "run"}}],
        engines=["paper"],
        settings={"pop_size": 20, "n_gen": 5, "seed_from": "none"},
        seeds=[3],
    )
    run = spec.runs()[0]
    # pinned: a change here silently invalidates every stored result
    assert canonical_json(run) == (
        '{"encoding":"integer","engine":"pymoo","map":{"dense":{"n":8,"p0":0.3,"seed":"run"}},'
        '"options":{"record_first_feasible":false,"reference":null,"stop_at_first_feasible":false},'
        '"seed":3,"settings":{"constraints":"penalty","n_gen":5,"objectives":["length",'
        '"vulnerability"],"penalty":1000.0,"pop_size":20,"sbx_eta":10.0,"seed_from":"none",'
        '"tiebreak":"smoothness"}}'
    )
    assert run_key(run) == "5052aae65717b722049b90a7e70c417a02f05d2b35d1c1ccd7ed27ffadce0347"
    # key order, tuples, string vs list objectives, [n, n] vs n do not matter
    shuffled = json.loads(json.dumps(run))
    shuffled["settings"] = dict(reversed(list(shuffled["settings"].items())))
    assert run_key(shuffled) == run_key(run)
    other = ExperimentSpec(
        maps=[{"dense": {"seed": "run", "p0": 0.3, "n": [8, 8]}}],
        engines=("paper",),
        settings={
            "seed_from": "none",
            "n_gen": 5.0,
            "pop_size": 20,
            "objectives": ["length", "vulnerability"],
        },
        seeds=[3],
    )
    assert run_key(other.runs()[0]) == run_key(run)
    assert config_key(run) == config_key(dict(run, seed=4)) and run_key(dict(run, seed=4)) != run_key(run)


# ---------------------------------------------------------------------------
# one run
# ---------------------------------------------------------------------------


def test_first_feasible_stops_the_run_and_records_the_generation():
    from gapath.generators import dense_workspace
    from gapath.solver import solve

    ws = dense_workspace(16, 0.3, seed=3)
    stop, watch = FirstFeasible(stop=True), FirstFeasible(stop=False)
    r = solve(ws, pop_size=40, n_gen=60, seed=1, seed_from="none", callback=stop)
    full = solve(ws, pop_size=40, n_gen=30, seed=1, seed_from="none", callback=watch)
    assert 1 < stop.generation == r.n_gen < 30 and len(r.front) >= 1
    assert watch.generation == stop.generation and full.n_gen == 30
    res = run_one(
        table_run := ExperimentSpec(
            maps=[{"dense": {"n": 16, "p0": 0.3, "seed": 3}}],
            engines=["paper"],
            settings={"pop_size": 40, "n_gen": 60, "seed_from": "none"},
            seeds=[1],
            options={"stop_at_first_feasible": True},
        ).runs()[0]
    )
    assert res["status"] == "ok" and res["n_gen"] == stop.generation
    ind = res["indicators"]
    assert ind["first_feasible_gen"] == stop.generation and ind["feasible"]
    assert ind["min_length"] == pytest.approx(r.front.metrics[:, 0].min())
    assert ind["n_obstacles"] == ws.n_obstacles and res["seed"] == 1
    assert res["key"] == run_key(table_run) and res["versions"]["gapath"]
    f = front_from_dict(json.loads(json.dumps(res["front"])))
    assert np.array_equal(f.F, r.front.F) and all(
        np.array_equal(a, b) for a, b in zip(f.paths, r.front.paths)
    )


# ---------------------------------------------------------------------------
# the store
# ---------------------------------------------------------------------------


def test_store_writes_atomically_and_reruns_skip_finished_runs(tmp_path, monkeypatch):
    spec = small_spec()
    out = tmp_path / "exp"
    first = run_experiment(spec, out, workers=0, progress=False)
    assert (first.ran, first.skipped, first.failed, first.complete) == (8, 0, 0, True)
    store = ResultStore(out)
    assert len(store.done_keys()) == 8 and not [p for p in (out / "runs").iterdir() if p.name.startswith(".")]
    assert json.loads((out / "experiment.json").read_text())["name"] == "tiny"
    assert "pymoo" in json.loads((out / "versions.json").read_text())
    calls = []
    monkeypatch.setattr(runner_mod, "run_one", lambda run: calls.append(run))
    again = run_experiment(spec, out, workers=0, progress=False)
    assert (again.ran, again.skipped, calls) == (0, 8, [])
    # more seeds: only the new runs execute
    monkeypatch.undo()
    more = run_experiment(small_spec(seeds=3), out, workers=0, progress=False)
    assert (more.ran, more.skipped) == (4, 8)
    # an interrupted write leaves neither a partial file nor a temporary one
    result = store.read(sorted(store.done_keys())[0])
    result["key"] = "f" * 64

    def boom(src, dst):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", boom)
    with pytest.raises(OSError):
        store.write(result)
    monkeypatch.undo()
    assert "f" * 64 not in store.done_keys()
    assert not [p for p in (out / "runs").iterdir() if p.name.startswith(".")]


def test_failed_runs_are_recorded_and_retried(tmp_path, monkeypatch):
    spec = small_spec(maps=["default"])
    real = runner_mod.run_one

    def flaky(run):
        if run["seed"] == 2:
            raise RuntimeError("worker lost")  # as if the process died
        return real(run)

    monkeypatch.setattr(runner_mod, "run_one", flaky)
    r = run_experiment(spec, tmp_path, workers=0, progress=False)
    assert (r.ran, r.failed, r.complete) == (4, 2, False)
    st = ResultStore(tmp_path).status()
    assert (st["done"], st["failed"], st["pending"]) == (2, 2, 0)
    bad = ResultStore(tmp_path).read(next(iter(ResultStore(tmp_path).failed_keys())), failed=True)
    assert bad["status"] == "failed" and "worker lost" in bad["error"]
    monkeypatch.undo()
    assert run_experiment(spec, tmp_path, workers=0, progress=False, retry_failed=False).ran == 0
    r = run_experiment(spec, tmp_path, workers=0, progress=False)
    assert (r.ran, r.failed, r.complete) == (2, 0, True)
    assert ResultStore(tmp_path).failed_keys() == set()


# ---------------------------------------------------------------------------
# executors: the local pool and a Dask cluster give the same results
# ---------------------------------------------------------------------------


def test_local_pool_and_dask_cluster_store_identical_results(tmp_path, monkeypatch):
    distributed = pytest.importorskip("distributed")
    spec = small_spec()
    run_experiment(spec, tmp_path / "inline", workers=0, progress=False)
    run_experiment(spec, tmp_path / "pool", workers=2, progress=False)
    run_experiment(small_spec(seeds=3), tmp_path / "inline3", workers=0, progress=False)
    with distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=False,
        protocol="tcp",
        host="127.0.0.1",
        dashboard_address=None,
    ) as cluster:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        r = run_experiment(spec, tmp_path / "dask", scheduler=cluster.scheduler_address, progress=False)
        assert r.executor.startswith("Dask scheduler") and r.ran == 8
        # GAPATH_SCHEDULER selects the cluster too
        monkeypatch.setenv("GAPATH_SCHEDULER", cluster.scheduler_address)
        r = run_experiment(small_spec(seeds=3), tmp_path / "dask", progress=False)
        assert r.executor.startswith("Dask scheduler") and (r.ran, r.skipped) == (4, 8)
        # runs batched into fewer Dask tasks: the same results
        r = run_experiment(small_spec(seeds=3), tmp_path / "dask-batched", progress=False, batch_seconds=60)
        assert r.ran == 12 and r.complete
    assert stored(tmp_path / "dask-batched") == stored(tmp_path / "inline3") == stored(tmp_path / "dask")
    reference = stored(tmp_path / "inline")
    assert len(reference) == 8
    assert stored(tmp_path / "pool") == reference
    dask = stored(tmp_path / "dask")
    assert {k: dask[k] for k in reference} == reference
    for d in ("inline", "pool"):
        report(tmp_path / d, plots=False)
    assert aggregate_files(tmp_path / "pool") == aggregate_files(tmp_path / "inline")


class _RecordingPool:
    """A spawn process pool that records the number of runs of each task."""

    def __init__(self, workers=2):
        self.pool = runner_mod._process_pool(workers)
        self._max_workers = workers
        self.sizes = []

    def submit(self, fn, runs, *args):
        self.sizes.append(len(runs))
        return self.pool.submit(fn, runs, *args)

    def shutdown(self, **kw):
        self.pool.shutdown(**kw)


def test_batched_tasks_store_the_same_results_as_single_runs(tmp_path):
    spec = small_spec(seeds=8)  # 32 runs of a few ms each
    run_experiment(spec, tmp_path / "inline", workers=0, progress=False)
    reference = stored(tmp_path / "inline")
    assert len(reference) == 32
    pool = _RecordingPool(2)
    try:
        r = run_experiment(spec, tmp_path / "batched", executor=pool, progress=False, batch_seconds=60)
        assert (r.ran, r.failed, r.complete) == (32, 0, True)
        batched = list(pool.sizes)
        r = run_experiment(spec, tmp_path / "single", executor=pool, progress=False, batch_seconds=0)
        assert r.ran == 32
    finally:
        pool.shutdown()
    # one run per task until a run's time is known (2 tasks per worker in flight),
    # then batches, shorter towards the end, the last ones single
    assert sum(batched) == 32 and batched[:4] == [1, 1, 1, 1] and max(batched) > 1
    assert batched[-1] == 1 and batched == sorted(batched[:4]) + sorted(batched[4:], reverse=True)
    assert pool.sizes[len(batched) :] == [1] * 32
    assert stored(tmp_path / "batched") == reference == stored(tmp_path / "single")
    report(tmp_path / "inline", plots=False)
    report(tmp_path / "batched", plots=False)
    assert aggregate_files(tmp_path / "batched") == aggregate_files(tmp_path / "inline")


def test_batch_sizes_follow_run_times_and_shrink_towards_the_end():
    b = runner_mod._Batcher([(str(i), {}) for i in range(100)], slots=1, target_seconds=0.25, max_batch=32)
    assert b.size() == 1  # nothing known yet
    for _ in range(4):
        b.observe({"status": "ok", "runtime": {"wall_seconds": 0.01}})
    assert b.size() == 25  # 0.25 s of 10 ms runs
    b.observe({"status": "failed", "runtime": {"wall_seconds": 0.0}})  # failures do not count
    assert b.size() == 25
    assert [len(b.take()) for _ in range(3)] == [25, 18, 14]  # at most remaining / (4 * slots)
    while len(b.queue) > 7:
        b.take()
    assert b.size() == 1 and len(b.take()) == 1
    two = runner_mod._Batcher([(str(i), {}) for i in range(100)], slots=2, target_seconds=0.25)
    two.observe({"status": "ok", "runtime": {"wall_seconds": 0.001}})
    assert two.size() == 12  # 100 / (4 * 2), under the target's 250 and max_batch's 32
    slow = runner_mod._Batcher([(str(i), {}) for i in range(100)], slots=2)
    slow.observe({"status": "ok", "runtime": {"wall_seconds": 2.0}})
    assert slow.size() == 1  # long runs: one per task


def test_a_lost_task_fails_each_of_its_runs_and_the_others_are_stored(tmp_path):
    from concurrent.futures import Future
    from concurrent.futures.process import BrokenProcessPool

    class DiesOnSeed2:
        _max_workers = 1

        def __init__(self):
            self.sizes = []

        def submit(self, fn, runs, *args):
            self.sizes.append(len(runs))
            fut = Future()
            if any(r["seed"] == 2 for r in runs):
                fut.set_exception(BrokenProcessPool("a worker died"))
            else:
                fut.set_result(fn(runs, *args))
            return fut

    spec = small_spec(maps=["default"], seeds=6)  # 12 runs
    ex = DiesOnSeed2()
    r = run_experiment(spec, tmp_path, executor=ex, progress=False, batch_seconds=60)
    st = ResultStore(tmp_path)
    lost = {k for k in st.failed_keys()}
    assert r.ran == 12 and r.failed == len(lost) == 12 - len(st.done_keys())
    assert max(ex.sizes) > 1 and r.failed >= 2  # the two seed-2 runs at least
    for k in lost:
        bad = st.read(k, failed=True)
        assert "BrokenProcessPool: a worker died" in bad["error"] and bad["key"] == k
    assert all(st.read(k)["run"]["seed"] != 2 for k in st.done_keys())
    r = run_experiment(spec, tmp_path, workers=0, progress=False)
    assert (r.ran, r.failed, r.complete) == (len(lost), 0, True)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc malloc")
def test_malloc_thresholds_are_restored_under_a_dask_nanny_environment():
    code = """
import resource, numpy as np
from gapath.experiments import runner
tuned = runner._tune_malloc()
again = runner._tune_malloc()
f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(300):
    a = np.ones(200_000)  # 1.6 MB, allocated and freed
    del a
print(tuned, again, resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0)
"""

    def faults(**env):
        e = {k: v for k, v in os.environ.items() if k not in ("MALLOC_TRIM_THRESHOLD_", "GAPATH_KEEP_MALLOC")}
        out = subprocess.run(
            [sys.executable, "-c", code], env={**e, **env}, capture_output=True, text=True, check=True
        ).stdout.split()
        return out[0] == "True", out[1] == "True", int(out[2])

    nanny = {"MALLOC_TRIM_THRESHOLD_": "65536"}  # what Dask's nanny sets
    untouched = faults(**nanny, GAPATH_KEEP_MALLOC="1")
    tuned = faults(**nanny)
    plain = faults()
    assert untouched[:2] == (False, False) and tuned[:2] == (True, False) and plain[:2] == (False, False)
    # a page fault per page of every array under the nanny's setting; none once tuned
    assert untouched[2] > 300 * 300 and tuned[2] < 5000 and plain[2] < 5000


# ---------------------------------------------------------------------------
# SIGKILL and resume
# ---------------------------------------------------------------------------

KILL_SPEC = """\
name: killme
maps: [default]
engines: [paper]
settings: {pop_size: 30, n_gen: 15, seed_from: none}
seeds: 10
"""


def test_sigkill_loses_only_runs_in_flight_and_resume_matches(tmp_path):
    spec_path = tmp_path / "kill.yaml"
    spec_path.write_text(KILL_SPEC)
    out = tmp_path / "killed"
    cmd = [
        sys.executable,
        "-m",
        "gapath.cli",
        "experiment",
        "run",
        str(spec_path),
        "--out",
        str(out),
        "--workers",
        "1",
        "--quiet",
    ]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, start_new_session=True)
    try:
        deadline = time.monotonic() + 120
        while len(ResultStore(out).done_keys()) < 2:
            assert proc.poll() is None, proc.stderr.read().decode()
            assert time.monotonic() < deadline, "no run finished in 120 s"
            time.sleep(0.02)
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(timeout=30)
        n_killed = len(ResultStore(out).done_keys())
        assert 2 <= n_killed < 10
        # the pool's worker dies with its parent (PR_SET_PDEATHSIG)
        deadline = time.monotonic() + 20
        while _group_alive(proc.pid) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not _group_alive(proc.pid)
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.stderr.close()
    # no half-written result; resume runs exactly the missing ones
    for p in (out / "runs").iterdir():
        if not p.name.startswith("."):
            json.loads(p.read_text())
    r = run_experiment(load_spec(spec_path), out, workers=0, progress=False)
    assert (r.skipped, r.ran, r.complete) == (n_killed, 10 - n_killed, True)
    run_experiment(load_spec(spec_path), tmp_path / "whole", workers=0, progress=False)
    assert stored(out) == stored(tmp_path / "whole")
    report(out, plots=False)
    report(tmp_path / "whole", plots=False)
    assert aggregate_files(out) == aggregate_files(tmp_path / "whole")


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    # zombies of the killed leader count as gone
    out = subprocess.run(["ps", "-o", "stat=", "-g", str(pgid)], capture_output=True, text=True).stdout
    return any(s and not s.startswith("Z") for s in out.split())


# ---------------------------------------------------------------------------
# reports
# ---------------------------------------------------------------------------


def test_report_tables_and_merged_fronts(tmp_path):
    spec = small_spec()
    run_experiment(spec, tmp_path, workers=0, progress=False)
    rep = report(tmp_path)
    assert [r["map"] for r in rep.rows] == ["default", "default", "dense-8x8-p0.4", "dense-8x8-p0.4"]
    assert [r["pop_size"] for r in rep.rows] == ["12", "16", "12", "16"]
    results = ResultStore(tmp_path).results()
    for row, conf in zip(rep.rows, spec.configurations()):
        runs = [r for r in results if r["config"] == config_key(conf)]
        assert row["done"] == row["runs"] == 2 and row["failed"] == 0
        feasible = [r for r in runs if r["indicators"]["feasible"]]
        assert row["success_pct"] == 100.0 * len(feasible) / 2
        sizes = [r["indicators"]["front_size"] for r in runs]
        assert row["front_size_median"] == float(np.median(sizes))
        assert row["front_size_q1"] == float(np.percentile(sizes, 25))
        if conf["map"].get("default") is not None:
            merged = merge_fronts([front_from_dict(r["front"]) for r in runs])
            assert np.array_equal(rep.fronts[row["config"]].F, merged.F)
            assert row["merged_front_size"] == len(merged)
        else:
            assert row["merged_front_size"] is None  # a new map per seed: nothing to merge
    header = rep.csv.splitlines()[0].split(",")
    assert header[:5] == ["config", "map", "encoding", "engine", "pop_size"]
    assert {
        "success_pct",
        "n_gen_median",
        "n_gen_q1",
        "n_gen_q3",
        "first_feasible_gen_median",
        "min_length_mean",
    } <= set(header)
    assert "| config | map | encoding | engine | pop_size |" in rep.markdown
    for name in ("summary.csv", "summary.md", "timing.csv", "indicators.png"):
        assert (tmp_path / name).is_file()
    assert (tmp_path / "summary.csv").read_text() == rep.csv


# ---------------------------------------------------------------------------
# CLI
# ---------------------------------------------------------------------------


def test_cli_run_status_report(tmp_path, capsys):
    spec = tmp_path / "e.toml"
    spec.write_text(TOML_SPEC)
    out = tmp_path / "store"
    assert (
        main(["experiment", "run", str(spec), "--out", str(out), "--workers", "0", "--quiet", "--no-plots"])
        == 0
    )
    assert (out / "summary.md").is_file() and (out / "spec.toml").read_text() == TOML_SPEC
    capsys.readouterr()
    assert main(["experiment", "status", str(out)]) == 0
    assert "small: 8/8 done, 0 failed, 0 pending" in capsys.readouterr().out
    assert main(["experiment", "report", str(out), "--no-plots"]) == 0
    assert "| config | map |" in capsys.readouterr().out
    # resuming from the store directory itself
    assert main(["experiment", "run", str(out), "--workers", "0", "--quiet", "--no-report"]) == 0
    bad = tmp_path / "bad.yaml"
    bad.write_text("settings: {pop_size: -3}\n")
    assert main(["experiment", "run", str(bad), "--out", str(tmp_path / "x"), "--quiet"]) == 2
    assert "bad.yaml: settings.pop_size: expected an integer >= 2" in capsys.readouterr().err
    assert main(["experiment", "status", str(tmp_path / "nothing")]) == 2
    assert "not an experiment directory" in capsys.readouterr().err


def test_experiment_group_is_extensible(monkeypatch, tmp_path, capsys):
    import types

    from gapath.cli import experiment

    mod = types.ModuleType("gapath_test_hello")

    def register_experiment(sub):
        p = sub.add_parser("hello")
        p.set_defaults(func=lambda args: print("hello from a plug-in") or 0)

    mod.register_experiment = register_experiment
    monkeypatch.setitem(sys.modules, "gapath_test_hello", mod)
    monkeypatch.setattr(
        experiment, "EXPERIMENT_MODULES", [*experiment.EXPERIMENT_MODULES, "gapath_test_hello"]
    )
    assert main(["experiment", "hello"]) == 0
    assert "hello from a plug-in" in capsys.readouterr().out


def test_dense_quick(tmp_path):
    from gapath.studies import dense

    assert main(["experiment", "dense", "--quick", "--out", str(tmp_path), "--workers", "0", "--quiet"]) == 0
    md = (tmp_path / "dense.md").read_text()
    assert "| 8x8 | 0.3 |" in md and "| 16x16 | 0.7 |" in md and "| 64x64 | 0.2 |" in md
    assert (tmp_path / "dense.png").stat().st_size > 1000
    rows = (tmp_path / "dense.csv").read_text().splitlines()
    assert rows[0].startswith("part,map_seed,grid,p0,runs") and len(rows) == 1 + 4 + 1
    spec = ResultStore(tmp_path / "table1-map1").spec().to_dict()
    assert spec["settings"]["seed_from"] == "none" and spec["options"]["stop_at_first_feasible"]
    assert spec["maps"][0] == {"dense": {"n": 8, "p0": 0.3, "seed": 1}}
    assert ResultStore(tmp_path / "large-map1").spec().to_dict()["maps"][0]["dense"]["seed"] == 1
    full = dense.table1_spec()
    assert len(full) == 3000 and full.runs()[0]["settings"]["pop_size"] == 200
    assert full.runs()[0]["settings"]["n_gen"] == 500
    assert dense.paper_row(32, 0.5)["success_pct"] == 36
    assert dense.p0_for_obstacles(64, 791, samples=300) == pytest.approx(dense.LARGE[64], abs=0.003)


def test_engines_auto_is_saved_resolved_and_fast_matches_paper():
    from gapath.experiments.spec import ENGINES, resolve_engine
    from gapath.solver import ENGINES as SOLVE_ENGINES

    assert set(ENGINES) == set(SOLVE_ENGINES)  # one vocabulary: solve's
    auto = ExperimentSpec(engines=["auto"]).to_dict()["engines"]
    assert auto == [resolve_engine("auto")] == ["fast"]
    assert ExperimentSpec(engines=["paper"]).to_dict()["engines"] == ["pymoo"]
    assert ExperimentSpec(engines=["pymoo", "paper"]).to_dict()["engines"] == ["pymoo"]
    spec = ExperimentSpec(
        maps=[{"dense": {"n": 16, "p0": 0.5, "seed": "run"}}],
        engines=["paper", "fast"],
        settings={"pop_size": 30, "n_gen": 20, "seed_from": "none"},
        seeds=2,
        options={"stop_at_first_feasible": True},
    )
    paper, fast = [run_one(r) for r in spec.runs()[:2]], [run_one(r) for r in spec.runs()[2:]]
    for p, f in zip(paper, fast):
        assert p["status"] == f["status"] == "ok" and p["key"] != f["key"]
        assert (p["settings"]["engine"], f["settings"]["engine"]) == ("pymoo", "fast")
        assert p["front"] == f["front"] and p["indicators"] == f["indicators"] and p["n_gen"] == f["n_gen"]


def test_spec_paths_setting_runs_free_paths_and_keeps_old_keys(tmp_path):
    """``settings.paths: free`` runs the GA over free paths (a map without a
    column-monotone path is solved); a spec without ``paths`` keeps the run
    keys it had; an encoding of the other path set is refused when read."""
    from gapath.errors import ConfigError
    from gapath.experiments.runner import run_one
    from gapath.experiments.spec import ExperimentSpec, run_key

    base = dict(
        name="p",
        maps=[{"file": {"path": str(tmp_path / "back.txt"), "start": [0, 0], "goal": [0, 4]}}],
        settings={"pop_size": 8, "n_gen": 2},
        seeds=[1],
    )
    (tmp_path / "back.txt").write_text("...#.\n##.#.\n...#.\n.###.\n.....\n")  # steps back a column
    plain = ExperimentSpec.from_dict(base).runs()[0]
    assert "paths" not in plain["settings"]
    assert run_key(plain) == run_key(ExperimentSpec.from_dict(dict(base)).runs()[0])
    free = ExperimentSpec.from_dict(
        {**base, "encodings": ["field"], "settings": {**base["settings"], "paths": "free"}}
    ).runs()[0]
    assert free["settings"]["paths"] == "free" and run_key(free) != run_key(plain)
    res = run_one(free)
    assert res["status"] == "ok", res
    assert res["indicators"]["feasible"] and res["indicators"]["front_size"] >= 1
    mono = run_one(plain)  # no column-monotone path on this map
    assert mono["status"] == "ok" and not mono["indicators"]["feasible"]
    with pytest.raises(ConfigError, match="describes monotone paths"):
        ExperimentSpec.from_dict({**base, "settings": {**base["settings"], "paths": "free"}})
    with pytest.raises(ConfigError, match="expected one of monotone, free"):
        ExperimentSpec.from_dict({**base, "settings": {**base["settings"], "paths": "any"}})


def test_spec_repair_setting_reaches_solve_and_keeps_old_keys():
    """``settings.repair`` runs solve with that repair; ``edge`` (the
    default) is not recorded, so such runs keep the keys of a spec without
    the setting; a repair the engine or the path set cannot run is refused
    when read."""
    from gapath import dense_workspace
    from gapath.errors import ConfigError
    from gapath.experiments.runner import run_one
    from gapath.experiments.spec import ExperimentSpec, canonical_json, run_key

    base = dict(
        name="r",
        maps=[{"dense": {"n": 32, "p0": 0.6, "seed": 1}}],
        settings={"pop_size": 200, "n_gen": 1, "seed_from": "none"},
        seeds=[2],
    )
    plain = ExperimentSpec.from_dict(base)
    edge = ExperimentSpec.from_dict({**base, "settings": {**base["settings"], "repair": "edge"}})
    assert "repair" not in canonical_json(plain.runs()[0])
    assert canonical_json(edge.runs()[0]) == canonical_json(plain.runs()[0])
    assert edge.to_dict() == plain.to_dict()
    fixed = ExperimentSpec.from_dict({**base, "settings": {**base["settings"], "repair": "feasible-local"}})
    (run,) = fixed.runs()
    assert run["settings"]["repair"] == "feasible-local" and run_key(run) != run_key(plain.runs()[0])
    # one generation (the initial population) on a dense map: only the repaired run is feasible
    got, without = run_one(run), run_one(plain.runs()[0])
    assert got["status"] == without["status"] == "ok"
    assert got["settings"]["repair"] == "feasible-local" and "repair" not in without["settings"]
    assert got["indicators"]["feasible"] and not without["indicators"]["feasible"]
    occ = dense_workspace(32, 0.6, 1).occ
    assert all(not occ[tuple(np.asarray(p).T)].any() for p in got["front"]["paths"])
    grid = ExperimentSpec.from_dict({**base, "grid": {"repair": ["edge", "feasible-local"]}})
    assert [r["settings"].get("repair") for r in grid.runs()] == [None, "feasible-local"]
    assert canonical_json(grid.runs()[0]) == canonical_json(plain.runs()[0])
    for extra, match in (
        ({"engines": ["pymoo"]}, "settings.repair: repair 'feasible-local' needs the fast engine"),
        (
            {"encodings": ["field"], "settings": {**fixed.settings, "paths": "free"}},
            "needs monotone paths",
        ),
        ({"settings": {**base["settings"], "repair": "best"}}, "expected one of edge, feasible-local"),
    ):
        with pytest.raises(ConfigError, match=match):
            ExperimentSpec.from_dict({**base, "settings": fixed.settings, **extra})
