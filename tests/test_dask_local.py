"""gapath's Dask settings (gapath.experiments.dask_config) and the executor
``scheduler="local"`` / ``--scheduler local`` / ``GAPATH_SCHEDULER=local``:
a LocalCluster started with them stores the same results as the pool."""

from pathlib import Path

import pytest
from experiment_cases import small_spec, stored

from gapath import ConfigError
from gapath.cli import main
from gapath.experiments import dask_config
from gapath.experiments.dask_config import (
    DASK_CONFIG,
    DASK_CONFIG_FILE,
    check_dask_config,
    load_dask_config,
    local_client,
)
from gapath.experiments.runner import make_executor, run_experiment

distributed = pytest.importorskip("distributed")


# ---------------------------------------------------------------------------
# the settings and their YAML file
# ---------------------------------------------------------------------------


def test_shipped_yaml_file_holds_the_settings_and_loads_into_dask(tmp_path):
    import dask

    assert DASK_CONFIG_FILE.is_file() and DASK_CONFIG_FILE.suffix == ".yaml"
    assert load_dask_config() == DASK_CONFIG == load_dask_config(DASK_CONFIG_FILE)
    assert DASK_CONFIG["distributed.worker.profile.enabled"] is False
    for key in (
        "distributed.admin.tick.interval",
        "distributed.admin.system-monitor.interval",
        "distributed.worker.memory.monitor-interval",
    ):
        assert key in DASK_CONFIG
    # what DASK_CONFIG=<file> does in `dask scheduler` / `dask worker`: Dask's own loader
    collected = dask.config.merge(*dask.config.collect_yaml([str(DASK_CONFIG_FILE)]))
    for key, value in DASK_CONFIG.items():
        assert dask.config.get(key, config=collected) == value
    # a copy elsewhere loads the same
    copy = tmp_path / "mine.yaml"
    copy.write_text(DASK_CONFIG_FILE.read_text())
    assert load_dask_config(copy) == DASK_CONFIG


@pytest.mark.parametrize(
    "text, message",
    [
        (
            "distributed:\n  worker:\n    profile:\n      enabled: sometimes\n",
            "distributed.worker.profile.enabled: expected true or false, got 'sometimes'",
        ),
        (
            "distributed:\n  admin:\n    tick:\n      interval: often\n",
            "distributed.admin.tick.interval: expected a duration like '1s', got 'often'",
        ),
        (
            "distributed:\n  admin:\n    tick:\n      interval: -1s\n",
            "distributed.admin.tick.interval: expected a duration like '1s', got '-1s'",
        ),
        (
            "distributed:\n  admin:\n    tick:\n      intervall: 1s\n",
            "distributed.admin.tick.intervall: not a Dask setting",
        ),
        (
            "distributed:\n  scheduler:\n    worker-saturation: lots\n",
            "distributed.scheduler.worker-saturation: expected a number, got 'lots'",
        ),
        ("distributed:\n  admin: [1, 2\n", "invalid YAML"),
        ("- just\n- a list\n", "expected a mapping of Dask settings"),
    ],
)
def test_bad_dask_config_files_give_errors_naming_file_and_key(tmp_path, text, message):
    f = tmp_path / "bad.yaml"
    f.write_text(text)
    with pytest.raises(ConfigError, match="bad.yaml") as err:
        load_dask_config(f)
    assert message in str(err.value)
    with pytest.raises(ConfigError, match="cannot read"):
        load_dask_config(tmp_path / "missing.yaml")


def test_check_dask_config_accepts_good_values_and_local_client_checks_its_arguments():
    good = {
        "distributed.scheduler.work-stealing": False,
        "distributed.admin.tick.interval": "500ms",
        "distributed.scheduler.worker-saturation": 1.0,
    }
    assert check_dask_config(good) == good
    with pytest.raises(ConfigError, match="at least 1 worker"):
        local_client(0)
    with pytest.raises(ConfigError, match="at least 1 worker"):
        make_executor(0, "local")
    with pytest.raises(ConfigError, match="expected true or false"):
        local_client(1, config={"distributed.worker.profile.enabled": "off"})
    # a malformed scheduler value is named, with what is expected
    with pytest.raises(ConfigError, match="expected 'local' or the address of a Dask scheduler"):
        make_executor(2, "lcoal")


# ---------------------------------------------------------------------------
# --scheduler local
# ---------------------------------------------------------------------------


def _monitors(server) -> dict:
    """What a Dask server (scheduler, nanny or worker) runs with."""
    pcs = server.periodic_callbacks
    return {
        "tick_s": server._tick_interval,
        "monitor_ms": pcs["monitor"].callback_time,
        "profiler": "profile" in pcs,
        "memory_monitor_ms": pcs["memory_monitor"].callback_time if "memory_monitor" in pcs else None,
    }


def test_local_client_runs_workers_and_scheduler_with_gapaths_settings():
    import dask

    def worker_settings(dask_worker):
        import dask

        return {k: dask.config.get(k) for k in DASK_CONFIG}, _monitors(dask_worker)

    client = local_client(1)
    try:
        cluster = client.cluster
        assert client.scheduler.address.startswith("tcp://127.0.0.1:")
        assert sum(client.nthreads().values()) == 1
        # the worker process: gapath's settings in force, no profiler, 1 s monitors
        ((config, worker),) = client.run(worker_settings).values()
        assert config == DASK_CONFIG
        assert worker == {"tick_s": 1.0, "monitor_ms": 2000, "profiler": False, "memory_monitor_ms": 1000}
        # the scheduler and the nanny (in this process) were built with them
        assert _monitors(cluster.scheduler) == {
            "tick_s": 1.0,
            "monitor_ms": 2000,
            "profiler": False,
            "memory_monitor_ms": None,
        }
        (nanny,) = cluster.workers.values()
        assert _monitors(nanny)["tick_s"] == 1.0 and _monitors(nanny)["memory_monitor_ms"] == 1000
        # the scheduler's HTTP routes (health, metrics; no Bokeh dashboard) on loopback only
        http = cluster.scheduler.http_server
        assert {sock.getsockname()[0] for sock in http._sockets.values()} == {"127.0.0.1"}
        assert not any("bokeh" in str(r) for r in cluster.scheduler.http_application.default_router.rules)
    finally:
        client.close()
    assert cluster.status.name == "closed"  # the client owned its cluster
    # this process's global Dask config is left as it was
    assert dask.config.get("distributed.worker.profile.enabled") is True


def test_scheduler_local_stores_the_same_results_as_the_pool(tmp_path, monkeypatch):
    monkeypatch.delenv("GAPATH_SCHEDULER", raising=False)
    spec = small_spec()
    run_experiment(small_spec(seeds=3), tmp_path / "inline", workers=0, progress=False)
    run_experiment(spec, tmp_path / "pool", workers=2, progress=False)
    r = run_experiment(spec, tmp_path / "local", workers=2, scheduler="local", progress=False)
    assert r.executor == "Dask LocalCluster of 2 worker processes (gapath's Dask settings)"
    assert (r.ran, r.failed, r.complete) == (8, 0, True)
    # GAPATH_SCHEDULER=local through the CLI, resuming the same store with one more seed
    monkeypatch.setenv("GAPATH_SCHEDULER", "local")
    spec_file = tmp_path / "e.yaml"
    spec_file.write_text(
        "name: tiny\nmaps: [default, {dense: {n: 8, p0: 0.4, seed: run}}]\nengines: [paper]\n"
        "settings: {pop_size: 12, n_gen: 4, seed_from: none}\ngrid: {pop_size: [12, 16]}\n"
        "seeds: 3\noptions: {record_first_feasible: true}\n"
    )
    assert (
        main(
            [
                "experiment",
                "run",
                str(spec_file),
                "--out",
                str(tmp_path / "local"),
                "--workers",
                "1",
                "--quiet",
                "--no-report",
            ]
        )
        == 0
    )
    pool, local, inline = stored(tmp_path / "pool"), stored(tmp_path / "local"), stored(tmp_path / "inline")
    assert len(pool) == 8 and len(local) == len(inline) == 12
    assert {k: local[k] for k in pool} == pool
    assert local == inline


def test_cli_help_names_the_local_scheduler(capsys):
    with pytest.raises(SystemExit):
        main(["experiment", "run", "--help"])
    assert "local" in capsys.readouterr().out
    assert Path(dask_config.__file__).with_name("gapath-dask.yaml") == DASK_CONFIG_FILE


def test_a_malformed_address_leaves_no_half_built_client():
    # a Client that fails in its constructor is left behind, and its __del__,
    # run later while another Client starts, can deadlock both (distributed
    # 2026.8): the address is checked before any Client is built
    import gc

    gc.collect()
    before = sum(isinstance(o, distributed.Client) for o in gc.get_objects())
    with pytest.raises(ConfigError, match="missing port number"):
        make_executor(2, "lcoal")
    assert sum(isinstance(o, distributed.Client) for o in gc.get_objects()) == before
