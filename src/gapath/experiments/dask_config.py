"""gapath's Dask settings for CPU-bound experiments, and a LocalCluster with them.

A Dask worker samples its running task's stack every 10 ms (the statistical
profiler), and the event loops of the scheduler, the nannies and the workers
wake every 20-500 ms to monitor themselves: a default 2-worker
``LocalCluster`` uses 0.12-0.18 CPU cores while idle, which on a 2-core
machine is taken from the runs. :data:`DASK_CONFIG` switches the profiler
off and slows the monitors to 1-2 s (idle: about 0.02 cores); the
dashboard's profile and monitoring plots lose their detail, nothing else
changes, and no result depends on it.

* ``run_experiment(..., scheduler="local")`` (``gapath experiment run
  --scheduler local``, ``GAPATH_SCHEDULER=local``) starts a LocalCluster of
  ``workers`` single-threaded worker processes on loopback with these
  settings (:func:`local_client`), runs on it and closes it.
* For a cluster of your own, point Dask at :data:`DASK_CONFIG_FILE` (the
  same settings as YAML) before starting ``dask scheduler`` and
  ``dask worker``: ``export DASK_CONFIG=.../gapath-dask.yaml``, or copy the
  file into ``~/.config/dask/``.

Measured (``benchmarks/bench_experiments.py``, BENCHMARKS.md): on 320 runs
of the dense-obstacle experiment on 2 cores, a 2-worker LocalCluster took
1.15x the local process pool's time with Dask's defaults and 0.99-1.09x
(medians of three sittings; single rounds 0.85-1.27x) with these settings and
the runner's 1 s Dask tasks.
"""

from __future__ import annotations

import os
from pathlib import Path

from gapath.errors import ConfigError

__all__ = [
    "DASK_CONFIG",
    "DASK_CONFIG_FILE",
    "LOCAL_SCHEDULER",
    "check_dask_config",
    "load_dask_config",
    "local_client",
]

#: gapath's Dask settings (dotted keys of ``distributed/distributed.yaml``),
#: as given to ``dask.config.set``; the same as :data:`DASK_CONFIG_FILE`.
DASK_CONFIG: dict = {
    "distributed.worker.profile.enabled": False,
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "2s",
}

#: :data:`DASK_CONFIG` as a Dask YAML file, for ``DASK_CONFIG=<file>`` or
#: ``~/.config/dask/``.
DASK_CONFIG_FILE = Path(__file__).with_name("gapath-dask.yaml")

#: The ``scheduler`` value that starts a LocalCluster with gapath's settings.
LOCAL_SCHEDULER = "local"


def _flatten(tree: dict, prefix: str = "") -> dict:
    out = {}
    for key, value in tree.items():
        name = f"{prefix}.{key}" if prefix else str(key)
        if isinstance(value, dict):
            out.update(_flatten(value, name))
        else:
            out[name] = value
    return out


def _defaults() -> dict:
    """Dask's and distributed's built-in defaults (not the user's settings)."""
    import dask

    try:
        import distributed  # noqa: F401 - registers distributed.yaml's defaults
    except ImportError:
        raise ConfigError(
            "Dask settings need the 'distributed' package (pip install 'dask[distributed]')"
        ) from None
    return dask.config.merge(*dask.config.defaults)


def check_dask_config(config: dict, source: str = "Dask config") -> dict:
    """Check flat ``{dotted.key: value}`` Dask settings against distributed's
    own defaults: every key must exist there, a boolean setting needs
    ``true``/``false``, a duration (``"1s"``, ``"500ms"``) a positive
    duration, a number a number. Returns ``config``.

    Raises
    ------
    ConfigError
        Naming ``source``, the key and the value, e.g.
        ``gapath-dask.yaml: distributed.admin.tick.interval: expected a
        duration like '1s', got 'often'``.

    Examples
    --------
    >>> check_dask_config(DASK_CONFIG) == DASK_CONFIG
    True
    >>> check_dask_config({"distributed.worker.profile.enabled": "no"})
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: Dask config: distributed.worker.profile.enabled: expected true or false, got 'no'
    """
    import dask
    from dask.utils import parse_timedelta

    defaults = _defaults()
    for key, value in config.items():
        try:
            default = dask.config.get(key, config=defaults)
        except KeyError:
            raise ConfigError(
                f"{source}: {key}: not a Dask setting (no such key in "
                "distributed's distributed.yaml or dask's dask.yaml)"
            ) from None
        if isinstance(default, bool):
            if not isinstance(value, bool):
                raise ConfigError(f"{source}: {key}: expected true or false, got {value!r}")
        elif isinstance(default, str) and _is_duration(default):
            try:
                seconds = parse_timedelta(value)
            except (ValueError, TypeError, KeyError):
                seconds = None
            if isinstance(value, bool) or seconds is None or seconds <= 0:
                raise ConfigError(f"{source}: {key}: expected a duration like '1s', got {value!r}")
        elif isinstance(default, (int, float)):
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ConfigError(f"{source}: {key}: expected a number, got {value!r}")
    return config


def _is_duration(text: str) -> bool:
    from dask.utils import parse_timedelta

    try:
        parse_timedelta(text)
    except (ValueError, TypeError, KeyError):
        return False
    return any(ch.isalpha() for ch in text)


def load_dask_config(path=None) -> dict:
    """The flat, checked settings of a Dask YAML file (default:
    :data:`DASK_CONFIG_FILE`), e.g. ``{"distributed.admin.tick.interval":
    "1s", ...}``, for ``dask.config.set``.

    Raises
    ------
    ConfigError
        On a missing or unreadable file, invalid YAML, or a bad key or value
        (see :func:`check_dask_config`).

    Examples
    --------
    >>> load_dask_config() == DASK_CONFIG
    True
    """
    import yaml

    path = Path(DASK_CONFIG_FILE if path is None else path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read the Dask config ({exc.strerror})") from None
    try:
        tree = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        at = f":{mark.line + 1}" if mark is not None else ""
        raise ConfigError(f"{path}{at}: invalid YAML: {getattr(exc, 'problem', None) or exc}") from None
    if tree is None:
        tree = {}
    if not isinstance(tree, dict):
        raise ConfigError(f"{path}: expected a mapping of Dask settings, got {type(tree).__name__}")
    return check_dask_config(_flatten(tree), str(path))


def local_client(workers: int | None = None, *, config: dict | None = None, timeout: str = "60s"):
    """A ``distributed.Client`` that owns a fresh ``LocalCluster``: ``workers``
    worker processes (default: the number of CPUs) of one thread each,
    behind nannies, on loopback (127.0.0.1, random ports, no dashboard),
    started with ``config`` (default :data:`DASK_CONFIG`) in force, so that
    the scheduler (in this process), the nannies and the workers run with
    it. ``client.close()`` shuts the cluster down.

    Raises
    ------
    ConfigError
        On ``workers < 1``, a bad ``config`` or without ``distributed``.
    """
    workers = (os.cpu_count() or 1) if workers is None else int(workers)
    if workers < 1:
        raise ConfigError(f"scheduler 'local' needs at least 1 worker, got workers={workers}")
    config = check_dask_config(dict(DASK_CONFIG if config is None else config))
    import dask
    from distributed import Client

    with dask.config.set(config):
        # no dashboard; the scheduler's small HTTP server (health, metrics) on a
        # random loopback port rather than on every interface's 8787
        client = Client(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
            timeout=timeout,
            scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
        )
    try:
        client.wait_for_workers(workers, timeout=timeout)
    except BaseException:
        client.close()
        raise
    return client
