"""The result store of an experiment: one directory, one file per run.

Layout of a store directory::

    DIR/experiment.json        the normalised spec (gapath.experiments.spec)
    DIR/spec.yaml|.toml|.json  a copy of the spec file, when it came from one
    DIR/versions.json          package versions of the last invocation
    DIR/runs/<key>.json        one finished run (key: spec.run_key, sha256)
    DIR/runs/<key>.failed.json one failed run (retried on the next invocation)
    DIR/summary.csv, ...       written by gapath.experiments.report.report

Every file is written to a temporary name in the same directory and renamed
into place (:func:`gapath.results.atomic_write`), so a process killed at any
moment leaves either the whole result or none: re-running the experiment
skips the finished runs and loses only those that were in flight.
"""

from __future__ import annotations

import functools
import json
import os
from pathlib import Path

from gapath.errors import ConfigError
from gapath.experiments.spec import ExperimentSpec, run_key
from gapath.results import atomic_write, dumps, versions

__all__ = ["ResultStore", "store_versions"]

_OK, _FAILED = ".json", ".failed.json"


def store_versions() -> dict[str, str]:
    """:func:`gapath.results.versions` plus dask and distributed when
    installed (looked up once per process: a lookup costs ~15 ms)."""
    return dict(_versions())


@functools.lru_cache(maxsize=1)
def _versions() -> tuple:
    from importlib import metadata

    out = versions()
    for pkg in ("dask", "distributed"):
        try:
            out[pkg] = metadata.version(pkg)
        except metadata.PackageNotFoundError:
            pass
    return tuple(sorted(out.items()))


def _dumps(obj) -> str:
    return dumps(obj, sort_keys=True, separators=(",", ":")) + "\n"


class ResultStore:
    """An experiment's directory of results.

    Parameters
    ----------
    root : the directory (created by :meth:`initialise`).

    Examples
    --------
    >>> import tempfile
    >>> store = ResultStore(tempfile.mkdtemp())
    >>> store.write({"key": "ab", "status": "ok"})
    >>> store.done_keys()
    {'ab'}
    """

    def __init__(self, root):
        self.root = Path(root)
        self.runs_dir = self.root / "runs"

    # -- the experiment ------------------------------------------------------
    def initialise(self, spec) -> None:
        """Create the directory and save the spec (normalised, and the source
        file when there is one) and the package versions."""
        self.runs_dir.mkdir(parents=True, exist_ok=True)
        atomic_write(self.root / "experiment.json", dumps(spec.to_dict(), indent=1, sort_keys=True) + "\n")
        if spec.source and Path(spec.source).resolve() != (self.root / "experiment.json").resolve():
            src = Path(spec.source)
            try:
                atomic_write(self.root / f"spec{src.suffix.lower()}", src.read_bytes())
            except OSError:
                pass
        atomic_write(self.root / "versions.json", dumps(store_versions(), indent=1, sort_keys=True) + "\n")

    def exists(self) -> bool:
        """True when the directory holds an experiment."""
        return (self.root / "experiment.json").is_file()

    def spec(self):
        """The saved :class:`gapath.experiments.spec.ExperimentSpec`.

        Raises
        ------
        ConfigError
            If the directory holds no experiment.
        """

        path = self.root / "experiment.json"
        try:
            data = json.loads(path.read_text())
        except OSError:
            raise ConfigError(f"{self.root}: not an experiment directory (no experiment.json)") from None
        except json.JSONDecodeError as exc:
            raise ConfigError(f"{path}: invalid JSON ({exc.msg}, line {exc.lineno})") from None
        return ExperimentSpec.from_dict(data, source=path)

    # -- runs ----------------------------------------------------------------
    def path(self, key: str, failed: bool = False) -> Path:
        """The file of run ``key``."""
        return self.runs_dir / f"{key}{_FAILED if failed else _OK}"

    def _names(self) -> list[str]:
        try:
            return os.listdir(self.runs_dir)
        except FileNotFoundError:
            return []

    def done_keys(self) -> set[str]:
        """Keys of the finished runs (one directory listing)."""
        return {
            n[: -len(_OK)]
            for n in self._names()
            if n.endswith(_OK) and not n.endswith(_FAILED) and not n.startswith(".")
        }

    def failed_keys(self) -> set[str]:
        """Keys of the runs whose last attempt failed."""
        return {n[: -len(_FAILED)] for n in self._names() if n.endswith(_FAILED) and not n.startswith(".")}

    def write(self, result: dict) -> None:
        """Store one result of :func:`gapath.experiments.runner.run_one`
        atomically; a success replaces an earlier failure of the same run."""
        key = result["key"]
        ok = result.get("status") == "ok"
        atomic_write(self.path(key, failed=not ok), _dumps(result))
        if ok:
            try:
                os.unlink(self.path(key, failed=True))
            except FileNotFoundError:
                pass

    def read(self, key: str, failed: bool = False) -> dict:
        """The stored result of run ``key``."""
        path = self.path(key, failed)
        try:
            return json.loads(path.read_text())
        except json.JSONDecodeError as exc:
            raise ConfigError(f"{path}: invalid JSON ({exc.msg}, line {exc.lineno})") from None

    def results(self, runs=None) -> list[dict]:
        """The finished results of ``runs`` (default: every run of the saved
        spec), in the spec's run order; unfinished runs are left out."""

        runs = self.spec().runs() if runs is None else runs
        done = self.done_keys()
        return [self.read(k) for k in (run_key(r) for r in runs) if k in done]

    def status(self, runs=None) -> dict:
        """Counts ``total``, ``done``, ``failed`` (last attempt failed),
        ``pending`` (neither) and ``extra`` (stored results that are not runs
        of the spec, e.g. after it shrank)."""

        runs = self.spec().runs() if runs is None else runs
        keys = {run_key(r) for r in runs}
        done, failed = self.done_keys(), self.failed_keys() - self.done_keys()
        n_done, n_failed = len(keys & done), len(keys & failed)
        return dict(
            total=len(keys),
            done=n_done,
            failed=n_failed,
            pending=len(keys) - n_done - n_failed,
            extra=len(done - keys),
        )
