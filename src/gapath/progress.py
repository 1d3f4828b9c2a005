"""The progress bar (kept for compatibility: it lives in :mod:`gapath.callbacks`)."""

from gapath.callbacks import Callbacks, ProgressBar, population_arrays, population_status

__all__ = ["Callbacks", "ProgressBar", "population_arrays", "population_status"]
