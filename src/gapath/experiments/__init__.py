"""Experiments: seeded multi-run aggregation (more to come: runner, store)."""

from gapath.experiments.multirun import MultiRunResult, merge_fronts, multirun

__all__ = ["MultiRunResult", "merge_fronts", "multirun"]
