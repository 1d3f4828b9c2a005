"""Bit-flip mutation whose rate decays linearly over the run (Ahmed & Deb, section 2.1)."""

from __future__ import annotations

import math

import numpy as np
from pymoo.core.variable import get
from pymoo.operators.mutation.bitflip import BitflipMutation

from gapath.errors import ConfigError

#: Rate at the final generation, as a share of the initial rate (seeds: 1/5).
FINAL_SHARE = 0.2

#: Named initial rates: ``"bits"`` 1 / number of bits (gapath's default),
#: ``"grid"`` 1 / n for an n-column grid (Ahmed & Deb's 1/n).
RATE_RULES = ("bits", "grid")


def _grid_columns(problem) -> int:
    """The number of columns ``n`` of a path problem's grid (its frame's)."""
    frame = getattr(problem, "frame", None) or getattr(getattr(problem, "encoding", None), "frame", None)
    if frame is None:
        raise ConfigError(
            "DecayingBitflipMutation(prob_var='grid') needs a gapath path problem (one with a "
            f"grid frame), got {type(problem).__name__}"
        )
    return int(frame.n_cols)


def final_generation(termination) -> int | None:
    """The last generation a pymoo termination allows, or None if unknown.

    A :class:`pymoo.termination.max_gen.MaximumGenerationTermination` (what
    ``("n_gen", G)`` becomes) gives ``G``. Terminations that stop when any
    of their criteria does (pymoo's default terminations,
    ``TerminateIfAny``, ``TerminationCollection``) give the smallest
    generation limit among their criteria. Anything else is unknown.

    Examples
    --------
    >>> from pymoo.termination import get_termination
    >>> final_generation(get_termination("n_gen", 50))
    50
    >>> final_generation(get_termination("time", "00:01:00")) is None
    True
    """
    if termination is None:
        return None
    n_max_gen = getattr(termination, "n_max_gen", None)
    if n_max_gen is not None:
        try:
            n_max_gen = float(n_max_gen)
        except (TypeError, ValueError):
            return None
        return int(n_max_gen) if math.isfinite(n_max_gen) and n_max_gen >= 1 else None
    from pymoo.core.termination import TerminateIfAny
    from pymoo.termination.collection import TerminationCollection
    from pymoo.termination.default import DefaultTermination

    if isinstance(termination, (TerminateIfAny, DefaultTermination)):
        parts = termination.criteria
    elif isinstance(termination, TerminationCollection):
        parts = termination.terminations
    else:
        return None
    limits = [g for g in (final_generation(t) for t in parts) if g is not None]
    return min(limits) if limits else None


def decayed_rate(initial: float, n_gen, final_gen) -> float:
    """``initial`` at generation 1 falling linearly to ``initial / 5`` at
    ``final_gen`` (constant ``initial`` when ``final_gen`` is unknown or 1;
    the generation is clipped to ``[1, final_gen]``).

    Examples
    --------
    >>> [round(decayed_rate(0.1, g, 11), 12) for g in (1, 6, 11)]
    [0.1, 0.06, 0.02]
    """
    if final_gen is None or n_gen is None or final_gen <= 1:
        return float(initial)
    progress = (min(max(int(n_gen), 1), final_gen) - 1) / (final_gen - 1)
    return float(initial * (1.0 - (1.0 - FINAL_SHARE) * progress))


class DecayingBitflipMutation(BitflipMutation):
    """Bit-wise mutation whose per-bit probability falls linearly from its
    initial value at generation 1 to one fifth of it at the final
    generation (Ahmed & Deb's binary GA).

    The operator keeps no state: the rate is derived on every call from the
    ``algorithm`` pymoo passes to ``_do`` (``algorithm.n_gen`` and
    ``algorithm.termination``, see :func:`final_generation`). Without an
    algorithm, or when the final generation is unknown, the initial rate is
    used. Genes come back boolean whatever their input dtype (0/1 numbers
    are read as bits; pymoo's own ``BitflipMutation`` would turn 0/1
    integers into -1/-2).

    Parameters
    ----------
    prob_var : initial per-bit probability: a number, ``None`` or
        ``"bits"`` (default: ``1 / n_var``, one flipped bit per genome on
        average at generation 1), or ``"grid"`` (``1 / n`` for a path over
        ``n`` columns, e.g. 1/32 on a 32x32 grid against 1/217 for its 217
        bits: Ahmed & Deb's "mutation rate 1/n, n the size of the grid",
        section 5.2).
    **kwargs : passed to :class:`pymoo.core.mutation.Mutation`.

    Raises
    ------
    ConfigError
        On a ``prob_var`` that is neither a probability in [0, 1] nor one of
        ``"bits"``, ``"grid"``.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from pymoo.termination import get_termination
    >>> m = DecayingBitflipMutation(prob_var=0.05)
    >>> algo = SimpleNamespace(n_gen=100, termination=get_termination("n_gen", 100))
    >>> round(m.rate(None, algo), 12)
    0.01
    """

    def __init__(self, prob_var=None, **kwargs):
        self.rate_rule = None
        if isinstance(prob_var, str):
            if prob_var not in RATE_RULES:
                raise ConfigError(
                    f"DecayingBitflipMutation: prob_var must be a probability or one of "
                    f"{', '.join(RATE_RULES)}, got {prob_var!r}"
                )
            self.rate_rule, prob_var = prob_var, None
        elif np.ndim(prob_var) == 0 and isinstance(prob_var, (int, float)) and not 0.0 <= prob_var <= 1.0:
            raise ConfigError(f"DecayingBitflipMutation: prob_var must be in [0, 1], got {prob_var!r}")
        super().__init__(prob_var=prob_var, **kwargs)

    def initial_rate(self, problem) -> float:
        """The per-bit probability at generation 1.

        Examples
        --------
        >>> from gapath import default_workspace
        >>> from gapath.problems import GridPathProblem
        >>> p = GridPathProblem(default_workspace(), encoding="binary")
        >>> [round(1 / DecayingBitflipMutation(r).initial_rate(p)) for r in ("bits", "grid")]
        [217, 32]
        """
        if self.rate_rule == "grid":
            return 1.0 / _grid_columns(problem)
        if self.prob_var is None:
            return 1.0 / problem.n_var
        return float(get(self.prob_var))

    def rate(self, problem, algorithm=None) -> float:
        """The per-bit probability for the generation ``algorithm`` is in."""
        initial = self.initial_rate(problem)
        if algorithm is None:
            return initial
        return decayed_rate(
            initial,
            getattr(algorithm, "n_gen", None),
            final_generation(getattr(algorithm, "termination", None)),
        )

    def _do(self, problem, X, random_state=None, algorithm=None, **kwargs):
        if random_state is None:
            random_state = np.random.default_rng()
        X = np.asarray(X)
        bits = X if X.dtype == np.bool_ else X > 0.5
        flip = random_state.random(bits.shape) < self.rate(problem, algorithm)
        return bits ^ flip
