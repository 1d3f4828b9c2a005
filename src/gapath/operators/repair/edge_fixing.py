"""Ahmed & Deb's edge-fixing, written back into the genes as a pymoo repair."""

from __future__ import annotations

import zlib

import numpy as np
from pymoo.core.repair import Repair

from gapath.errors import ConfigError


class EdgeFixingRepair(Repair):
    """Bring paths that would leave the grid back inside, in the genes.

    A move that would cross the top or bottom edge is replaced by a row drawn
    with linear probability, highest at the violated edge and zero at the
    current row (Ahmed & Deb, section 2.1), and the fixed genes are written
    back, so the population holds what it is evaluated on. Genes are also
    rounded and clipped to the bounds.

    Randomness comes from the ``random_state`` pymoo passes when the GA
    calls the repair (initialisation and offspring), so runs are reproducible
    for a seed. Called without one (by hand, or attached to an operator),
    the generator is seeded from the genes themselves: still deterministic.

    The problem must expose an ``encoding`` with an ``edge_fix(X, rng)``
    method (every :class:`gapath.problems.GridPathProblem` does).

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import default_workspace
    >>> from gapath.problems import GridPathProblem
    >>> p = GridPathProblem(default_workspace())
    >>> X = EdgeFixingRepair()._do(p, np.full((1, p.n_var), 31))
    >>> bool((X >= p.xl).all() and (X <= p.xu).all())
    True
    """

    def _do(self, problem, X, random_state=None, **kwargs):
        encoding = getattr(problem, "encoding", None)
        if encoding is None or not hasattr(encoding, "edge_fix"):
            raise ConfigError(f"EdgeFixingRepair needs a gapath path problem, got {type(problem).__name__}")
        X = np.asarray(X)
        if len(X) == 0:
            return X
        if random_state is None:
            random_state = np.random.default_rng(zlib.crc32(np.ascontiguousarray(X).tobytes()))
        return encoding.edge_fix(X, random_state)
