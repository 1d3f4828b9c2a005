"""Exceptions raised by gapath.

Every error a user can cause by bad input is a subclass of :class:`ValueError`
so that ``except ValueError`` keeps working, and carries a message that names
the file, line or argument and the offending value.
"""

from __future__ import annotations


class GapathError(Exception):
    """Base class of all gapath errors."""


class MapError(GapathError, ValueError):
    """A map (file, array or generator argument) is malformed.

    The message names the file and line (or the argument) and the value found.
    """


class ConfigError(GapathError, ValueError):
    """An argument or setting is invalid (unknown objective, bad size, ...)."""


class NoPathError(GapathError, ValueError):
    """No feasible path exists between start and goal."""


class LabelBudgetError(GapathError):
    """An exact search stopped at its label budget (``max_labels``,
    ``gapath exact --max-labels``) before its front was complete.

    The message says how far the search got; ``stats`` holds the same figures
    (labels, expansions, solutions so far, seconds). What was found is not a
    Pareto front, so none is returned.
    """

    def __init__(self, message: str, stats: dict | None = None):
        super().__init__(message)
        self.stats = dict(stats or {})
