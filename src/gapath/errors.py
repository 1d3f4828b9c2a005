"""Exceptions raised by gapath, and the exit statuses of the ``gapath`` CLI.

Every error a user can cause by bad input is a subclass of :class:`ValueError`
so that ``except ValueError`` keeps working, and carries a message that names
the file, line or argument and the offending value.

The CLI maps them to its exit statuses (README, "Exit status"):
:class:`NoPathError` to :data:`EXIT_NO_RESULT` (the search ran and found
nothing feasible), every other :class:`GapathError` to
:data:`EXIT_BAD_INPUT`.
"""

from __future__ import annotations

import math

#: A result was found (and written).
EXIT_OK = 0
#: The search ran but found nothing feasible (no path; a simulated robot that
#: did not reach its goal; an experiment with failed runs). The reason is printed.
EXIT_NO_RESULT = 1
#: Bad input: an argument, a file or a value (one message naming it).
EXIT_BAD_INPUT = 2
#: An internal error (a bug in gapath): one message, no traceback unless
#: ``GAPATH_TRACEBACK=1`` is set.
EXIT_INTERNAL = 3
#: Interrupted (Ctrl-C); the partial results are written.
EXIT_INTERRUPTED = 130


class GapathError(Exception):
    """Base class of all gapath errors."""


class MapError(GapathError, ValueError):
    """A map (file, array or generator argument) is malformed.

    The message names the file and line (or the argument) and the value found.
    """


class ConfigError(GapathError, ValueError):
    """An argument or setting is invalid (unknown objective, bad size, ...)."""


class NoPathError(GapathError, ValueError):
    """No feasible path exists between start and goal, or the search found none.

    Parameters
    ----------
    message : str
        The reason (which path set, which cells).
    hint : str, optional
        What to do about it ("try --mode free"); the CLI prints it after the
        reason.

    Examples
    --------
    >>> e = NoPathError("no path joins (0, 0) and (0, 4)", hint="check --start and --goal")
    >>> str(e), e.hint
    ('no path joins (0, 0) and (0, 4)', 'check --start and --goal')
    """

    def __init__(self, message: str = "", hint: str | None = None):
        super().__init__(message)
        self.hint = hint


class LabelBudgetError(GapathError):
    """An exact search stopped at its label budget (``max_labels``,
    ``gapath exact --max-labels``) before its front was complete.

    The message says how far the search got; ``stats`` holds the same figures
    (labels, expansions, solutions so far, seconds). What was found is not a
    Pareto front, so none is returned (a work budget that returns the
    solutions found so far is ``free_front(..., max_expansions=)``).
    """

    def __init__(self, message: str, stats: dict | None = None):
        super().__init__(message)
        self.stats = dict(stats or {})


def positive_int(value: object, name: str) -> int:
    """``value`` as an ``int`` if it is a whole number >= 1 (``3``,
    ``3.0``, ``"3"``), else a :class:`ConfigError` naming ``name``: the one
    positive-integer check of gapath's settings.

    Parameters
    ----------
    value : object
        The setting as given.
    name : str
        The setting's name, or the flag that sets it, for the message.

    Returns
    -------
    int

    Raises
    ------
    ConfigError
        ``"{name} must be a positive integer, got {value!r}"``.

    Examples
    --------
    >>> positive_int(3.0, "runs")
    3
    >>> positive_int(0, "runs")
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: runs must be a positive integer, got 0
    """
    try:
        v = int(value)  # type: ignore[call-overload]
        if v != float(value):  # type: ignore[arg-type]
            raise ValueError
    except (TypeError, ValueError, OverflowError):
        raise ConfigError(f"{name} must be a positive integer, got {value!r}") from None
    if v <= 0:
        raise ConfigError(f"{name} must be a positive integer, got {value!r}")
    return v


def non_negative(value: object, name: str, *, finite: bool = True, what: str = "") -> float:
    """``value`` as a ``float`` if it is a number >= 0 (finite unless
    ``finite=False``; NaN never), else a :class:`ConfigError` naming
    ``name``: the one non-negative-number check of gapath's settings.

    Parameters
    ----------
    value : object
        The setting as given.
    name : str
        The setting's name, or the flag that sets it, for the message.
    finite : bool, optional
        Refuse infinity too (default).
    what : str, optional
        Added to the message after "number >= 0", e.g. " (an epsilon)".

    Returns
    -------
    float

    Raises
    ------
    ConfigError
        ``"{name} must be a [finite ]number >= 0{what}, got {value!r}"``.

    Examples
    --------
    >>> non_negative("0.5", "epsilon")
    0.5
    >>> non_negative(-1, "epsilon")
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: epsilon must be a finite number >= 0, got -1
    """
    try:
        v = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError, OverflowError):
        v = math.nan
    if not (v >= 0 and (not finite or math.isfinite(v))):
        kind = "a finite number" if finite else "a number"
        raise ConfigError(f"{name} must be {kind} >= 0{what}, got {value!r}")
    return v
