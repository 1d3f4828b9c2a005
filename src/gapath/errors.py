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
