"""Constraint handling for the path GA beyond a fixed penalty.

Ahmed & Deb add ``penalty * interfering`` to every objective with one fixed
``penalty``. A large one (gapath's default 1000) makes any path through an
obstacle lose to any feasible path: once the first feasible corridor is
found, an unseeded population locks onto it (``docs/results/penalty.md``).
A small one (0.3) lets paths through obstacles survive long enough to be
repaired by variation into better feasible paths, but on dense maps the
population never reaches a feasible path at all.

:class:`AdaptivePenalty` is a penalty that adapts to the share of feasible
individuals in the population, in pymoo's constraint-handling vocabulary
(the problem returns ``G = interfering``; the algorithm ranks on
``F + penalty * CV``). After each survival the penalty is multiplied by
``factor`` when no survivor or fewer than ``target`` of them are feasible,
and divided by it otherwise, within ``[minimum, maximum]``. With the
default ``initial = maximum`` it stays at ``maximum`` while no individual
is feasible, so a run that stops at its first feasible path (Ahmed & Deb's
Table 1) is the same run as with the fixed penalty ``maximum``, bit for bit;
once feasible paths dominate the population the penalty falls until about
``target`` of it is feasible. With a low ``initial`` and ``target = 0`` the
penalty starts low, doubles in every generation without a feasible path and
halves in every other one. No random numbers are drawn.

:class:`gapath.algorithms.FastNSGA2` takes it as ``constraint_handling=``;
:func:`gapath.solver.solve` builds it for ``constraints="adaptive"``.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from gapath.errors import ConfigError

__all__ = ["HANDLINGS", "AdaptivePenalty"]

#: Named adaptive handlings: the :class:`AdaptivePenalty` keywords (besides
#: ``maximum``) of each. ``adaptive``: from the maximum, aiming at 30 %
#: feasible survivors; ``adaptive-ramp``: from 0.3, doubled only in
#: generations without a feasible survivor, halved in the others;
#: ``adaptive-slow``: the same ramp by a factor 1.1 per generation (1000
#: after 85 generations without a feasible path).
HANDLINGS = {
    "adaptive": {},
    "adaptive-ramp": {"initial": 0.3, "target": 0.0},
    "adaptive-slow": {"initial": 0.3, "target": 0.0, "factor": 1.1},
}


@numba.njit(cache=True)
def _penalised(F, violation, penalty):
    """``F + penalty * violation[:, None]``, the same floating-point
    operations as :class:`gapath.problems.GridPathProblem`'s penalty mode."""
    n, m = F.shape
    out = np.empty((n, m))
    for i in range(n):
        p = penalty * violation[i]
        for j in range(m):
            out[i, j] = F[i, j] + p
    return out


def _positive(value, name):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ConfigError(f"AdaptivePenalty: {name} must be a positive number, got {value!r}") from None
    if not math.isfinite(v) or v <= 0:
        raise ConfigError(f"AdaptivePenalty: {name} must be a positive number, got {value!r}")
    return v


class AdaptivePenalty:
    """A penalty per unit of constraint violation that adapts to the share
    of feasible individuals (``CV <= 0``) among the survivors.

    After each survival the penalty is multiplied by ``factor`` when no
    survivor is feasible or fewer than ``target`` of them are, and divided
    by it otherwise, within ``[minimum, maximum]``.

    Parameters
    ----------
    maximum : largest penalty (default 1000, gapath's fixed penalty).
    target : share of feasible survivors aimed at, in [0, 1] (default 0.3);
        0: the penalty grows only while no survivor is feasible.
    factor : multiplier per generation, > 1 (default 2).
    minimum : smallest penalty, in (0, maximum] (default 0.01).
    initial : the penalty of the first survival, in [minimum, maximum]
        (default ``maximum``: the run equals the fixed-penalty run until a
        path is feasible).

    Attributes
    ----------
    value : the current penalty.
    history : the penalty used by each survival so far, in order.

    Raises
    ------
    ConfigError
        On a non-positive ``maximum``, ``factor <= 1``, ``target`` outside
        [0, 1], ``minimum`` outside (0, maximum] or ``initial`` outside
        [minimum, maximum].

    Examples
    --------
    >>> import numpy as np
    >>> h = AdaptivePenalty(maximum=8.0, target=0.5, factor=2.0, minimum=1.0)
    >>> F = np.array([[1.0, 2.0], [3.0, 4.0]])
    >>> h.penalise(F, np.array([0.0, 1.0])).tolist()
    [[1.0, 2.0], [11.0, 12.0]]
    >>> [h.update(s) for s in (0.0, 1.0, 1.0, 1.0, 1.0, 0.2)]
    [8.0, 4.0, 2.0, 1.0, 1.0, 2.0]
    >>> ramp = AdaptivePenalty(maximum=8.0, target=0.0, minimum=1.0, initial=1.0)
    >>> [ramp.update(s) for s in (0.0, 0.0, 0.0, 0.0, 0.01, 0.01)]
    [2.0, 4.0, 8.0, 8.0, 4.0, 2.0]
    """

    def __init__(self, maximum=1000.0, target=0.3, factor=2.0, minimum=0.01, initial=None):
        self.maximum = _positive(maximum, "maximum")
        self.factor = _positive(factor, "factor")
        if self.factor <= 1:
            raise ConfigError(f"AdaptivePenalty: factor must be > 1, got {factor!r}")
        try:
            self.target = float(target)
        except (TypeError, ValueError):
            self.target = math.nan
        if not 0.0 <= self.target <= 1.0:
            raise ConfigError(f"AdaptivePenalty: target must be in [0, 1], got {target!r}")
        self.minimum = _positive(minimum, "minimum")
        if self.minimum > self.maximum:
            raise ConfigError(f"AdaptivePenalty: minimum ({minimum!r}) must not exceed maximum ({maximum!r})")
        self.initial = self.maximum if initial is None else _positive(initial, "initial")
        if not self.minimum <= self.initial <= self.maximum:
            raise ConfigError(
                f"AdaptivePenalty: initial ({initial!r}) must be in [minimum, maximum] = "
                f"[{self.minimum:g}, {self.maximum:g}]"
            )
        self.reset()

    def reset(self) -> None:
        """Back to ``initial`` with an empty history (at the start of a run)."""
        self.value = self.initial
        self.history = []

    def penalise(self, F, violation) -> np.ndarray:
        """The penalised objectives ``F + value * violation`` (each row's
        violation added to each of its objectives); rows with no violation
        keep their objectives exactly.

        Parameters
        ----------
        F : (n, m) objectives.
        violation : (n,) constraint violation (>= 0; here the count of
            interfering cells).

        Returns
        -------
        (n, m) float array.
        """
        F = np.ascontiguousarray(F, dtype=np.float64)
        v = np.ascontiguousarray(violation, dtype=np.float64).reshape(len(F))
        return _penalised(F, v, float(self.value))

    def update(self, feasible_share: float) -> float:
        """Record the current penalty (used by the survival that produced
        ``feasible_share``), then adapt it for the next survival.

        Returns
        -------
        float: the penalty for the next survival.
        """
        self.history.append(self.value)
        share = float(feasible_share)
        if share <= 0.0 or share < self.target:
            self.value = min(self.maximum, self.value * self.factor)
        else:
            self.value = max(self.minimum, self.value / self.factor)
        return self.value

    def settings(self) -> dict:
        """The parameters, JSON-ready."""
        return dict(
            maximum=self.maximum,
            target=self.target,
            factor=self.factor,
            minimum=self.minimum,
            initial=self.initial,
        )

    def __repr__(self) -> str:
        return (
            f"AdaptivePenalty(maximum={self.maximum:g}, target={self.target:g}, "
            f"factor={self.factor:g}, minimum={self.minimum:g}, initial={self.initial:g})"
        )
