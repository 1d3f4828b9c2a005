"""Experiments: seeded multi-run aggregation, and grids of runs that scale out.

The infrastructure of the paper studies (:mod:`gapath.studies`):

* :func:`multirun`, :func:`merge_fronts` -- several seeds of one setting.
* :class:`ExperimentSpec`, :func:`load_spec` (:mod:`gapath.experiments.spec`)
  -- a grid of runs in Python, YAML or TOML.
* :func:`run_experiment`, :func:`run_one` (:mod:`gapath.experiments.runner`)
  -- runs on a local process pool or a Dask cluster, into a resumable
  :class:`ResultStore` (:mod:`gapath.experiments.store`).
* :func:`gapath.experiments.report.report` -- tables and plots.

The runner, store and report names are imported on first use, so that
``import gapath.experiments`` stays light.
"""

from gapath.experiments.multirun import MultiRunResult, merge_fronts, multirun

_LAZY = {
    "ExperimentSpec": "gapath.experiments.spec",
    "load_spec": "gapath.experiments.spec",
    "run_key": "gapath.experiments.spec",
    "ExperimentRun": "gapath.experiments.runner",
    "run_experiment": "gapath.experiments.runner",
    "run_one": "gapath.experiments.runner",
    "ResultStore": "gapath.experiments.store",
}

__all__ = ["MultiRunResult", "merge_fronts", "multirun", *_LAZY]


def __getattr__(name):
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'gapath.experiments' has no attribute {name!r}")
