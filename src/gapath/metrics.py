"""Front quality indicators and front bookkeeping (SPEC "Duplicates and ties",
"Reference (exact) fronts").

Fronts are ``(k, m)`` arrays of objective vectors (all minimised); anything
with an ``F`` attribute (an :class:`gapath.planners.exact.ExactFront`, a pymoo
``Result`` or ``Population`` is not one: pass ``res.F``) is accepted too.

Normalisation
    Indicators that compare a front with a reference front map every
    objective ``f`` to ``(f - ideal) / (nadir - ideal)``, ``ideal`` and
    ``nadir`` being the reference front's componentwise minimum and maximum.
    An axis on which the reference front is degenerate (``nadir`` equal to
    ``ideal`` within the tolerance, e.g. a one-point reference front) gets a
    unit range: ``f - ideal``. The hypervolume reference point is 1.1 in every
    normalised objective; points not strictly better than it contribute
    nothing.

Tolerance
    Two values ``a, b`` are equal when ``|a - b| <= tol * max(1, |a|, |b|)``,
    ``tol = 1e-9`` by default (:func:`close`).
"""

from __future__ import annotations

import numpy as np

from gapath.errors import ConfigError

__all__ = [
    "TOL",
    "REF_POINT",
    "close",
    "normalisation_bounds",
    "hypervolume",
    "hv_ratio",
    "igd_plus",
    "coverage",
    "nondominated",
    "dedupe",
]

#: SPEC tolerance for equal objective values.
TOL = 1e-9
#: Hypervolume reference point in every normalised objective.
REF_POINT = 1.1


def _as_F(front, name: str = "front", m: int | None = None) -> np.ndarray:
    F = getattr(front, "F", front)
    F = np.asarray(F, dtype=float)
    if F.size == 0:
        return np.zeros((0, m if m is not None else (F.shape[-1] if F.ndim == 2 else 0)))
    if F.ndim == 1:
        F = F[None, :]
    if F.ndim != 2:
        raise ConfigError(f"{name} must be a (k, m) array of objective vectors, got shape {F.shape}")
    if m is not None and F.shape[1] != m:
        raise ConfigError(f"{name} has {F.shape[1]} objectives, expected {m}")
    return F


def close(a, b, tol: float = TOL):
    """Elementwise SPEC equality ``|a - b| <= tol * max(1, |a|, |b|)``.

    Examples
    --------
    >>> bool(close(1.0, 1.0 + 1e-12)), bool(close(1.0, 1.001))
    (True, False)
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    return np.abs(a - b) <= tol * np.maximum(1.0, np.maximum(np.abs(a), np.abs(b)))


def normalisation_bounds(reference, tol: float = TOL) -> tuple[np.ndarray, np.ndarray]:
    """Ideal and nadir points of a reference front, as used for normalising.

    Parameters
    ----------
    reference : (k, m) array_like, k >= 1.
    tol : tolerance below which an axis counts as degenerate.

    Returns
    -------
    ideal, nadir : (m,) float arrays. On a degenerate axis (``nadir`` equal to
    ``ideal`` within ``tol``) ``nadir = ideal + 1`` (a unit range).

    Raises
    ------
    ConfigError
        If the reference front is empty.

    Examples
    --------
    >>> ideal, nadir = normalisation_bounds([[1.0, 5.0], [3.0, 5.0]])
    >>> ideal.tolist(), nadir.tolist()
    ([1.0, 5.0], [3.0, 6.0])
    """
    R = _as_F(reference, "reference")
    if len(R) == 0:
        raise ConfigError("the reference front is empty")
    ideal, nadir = R.min(axis=0), R.max(axis=0)
    nadir = np.where(close(ideal, nadir, tol), ideal + 1.0, nadir)
    return ideal, nadir


def hypervolume(front, ideal, nadir) -> float:
    """Hypervolume of a front after normalising by ``ideal`` and ``nadir``.

    Objectives are mapped to ``(f - ideal) / (nadir - ideal)`` (a unit range
    where ``nadir == ideal``) and the hypervolume is measured against the
    reference point 1.1 with pymoo's ``HV`` indicator (moocore).

    Parameters
    ----------
    front : (k, m) array_like or object with an ``F`` attribute.
    ideal, nadir : (m,) array_like.

    Returns
    -------
    float, 0.0 for an empty front.

    Examples
    --------
    >>> round(hypervolume([[0.0, 1.0], [1.0, 0.0]], [0, 0], [1, 1]), 4)
    0.21
    """
    from pymoo.indicators.hv import HV

    ideal = np.asarray(ideal, float).ravel()
    nadir = np.asarray(nadir, float).ravel()
    m = len(ideal)
    if nadir.shape != ideal.shape:
        raise ConfigError(f"ideal and nadir differ in length ({m} and {len(nadir)})")
    nadir = np.where(nadir == ideal, ideal + 1.0, nadir)
    if (nadir < ideal).any():
        raise ConfigError(f"nadir {nadir.tolist()} is below ideal {ideal.tolist()} on some axis")
    F = _as_F(front, "front", m)
    if len(F) == 0:
        return 0.0
    # norm_ref_point=False: the reference point is given in normalised units
    # (with the default True pymoo would normalise 1.1 a second time).
    hv = HV(ref_point=np.full(m, REF_POINT), ideal=ideal, nadir=nadir, zero_to_one=True, norm_ref_point=False)
    return float(hv(F))


def hv_ratio(front, reference) -> float:
    """``HV(front) / HV(reference)`` with SPEC's normalisation.

    Both fronts are normalised by the reference front's ideal and nadir
    points (see :func:`normalisation_bounds`; a degenerate axis gets a unit
    range) and measured against the reference point 1.1.

    Parameters
    ----------
    front : (k, m) array_like or object with an ``F`` attribute.
    reference : (r, m) array_like, r >= 1 (the exact front).

    Returns
    -------
    float: 1.0 for the reference front itself, 0.0 for an empty front or a
    front whose points all lie beyond the reference point. It can exceed 1.0
    when ``front`` is better than ``reference``.

    Raises
    ------
    ConfigError
        If the reference front is empty or the dimensions differ.

    Examples
    --------
    >>> ref = [[0.0, 1.0], [1.0, 0.0]]
    >>> hv_ratio(ref, ref)
    1.0
    >>> round(hv_ratio([[1.0, 1.0]], ref), 4)
    0.0476
    """
    ideal, nadir = normalisation_bounds(reference)
    return hypervolume(front, ideal, nadir) / hypervolume(reference, ideal, nadir)


def igd_plus(front, reference) -> float:
    """IGD+ of a front with respect to a reference front (pymoo's ``IGDPlus``),
    on the same normalisation as :func:`hv_ratio`.

    Returns
    -------
    float: 0.0 when every reference point is weakly dominated by the front,
    ``inf`` for an empty front.

    Raises
    ------
    ConfigError
        If the reference front is empty or the dimensions differ.

    Examples
    --------
    >>> igd_plus([[0.0, 1.0], [1.0, 0.0]], [[0.0, 1.0], [1.0, 0.0]])
    0.0
    """
    from pymoo.indicators.igd_plus import IGDPlus

    R = _as_F(reference, "reference")
    ideal, nadir = normalisation_bounds(R)
    F = _as_F(front, "front", R.shape[1])
    if len(F) == 0:
        return float("inf")
    return float(IGDPlus(R, zero_to_one=True, ideal=ideal, nadir=nadir)(F))


def coverage(front, reference, tol: float = TOL) -> float:
    """Share of reference points matched by a front point within the tolerance.

    A reference point ``r`` is matched when some front point ``f`` has
    ``close(f_i, r_i, tol)`` in every objective.

    Returns
    -------
    float in [0, 1].

    Raises
    ------
    ConfigError
        If the reference front is empty or the dimensions differ.

    Examples
    --------
    >>> coverage([[1.0, 2.0]], [[1.0, 2.0 + 1e-12], [2.0, 1.0]])
    0.5
    """
    R = _as_F(reference, "reference")
    if len(R) == 0:
        raise ConfigError("the reference front is empty")
    F = _as_F(front, "front", R.shape[1])
    if len(F) == 0:
        return 0.0
    matched = np.zeros(len(R), bool)
    chunk = max(1, 2_000_000 // max(1, F.size))
    for s in range(0, len(R), chunk):
        eq = close(R[s : s + chunk, None, :], F[None, :, :], tol).all(axis=2)
        matched[s : s + chunk] = eq.any(axis=1)
    return float(matched.mean())


def nondominated(F, tol: float = 0.0) -> np.ndarray:
    """Indices (ascending) of the non-dominated rows of ``F`` (minimisation).

    Parameters
    ----------
    F : (k, m) array_like.
    tol : with ``tol == 0`` (default) exact Pareto dominance, computed by
        pymoo's ``NonDominatedSorting`` (moocore). With ``tol > 0`` dominance
        up to the tolerance: ``a`` dominates ``b`` when every ``a_i`` is
        smaller than or ``close`` to ``b_i`` and some ``a_i`` is smaller and
        not ``close`` (this is the dominance :func:`gapath.planners.exact.monotone_front`
        uses).

    Returns
    -------
    (j,) int array. Equal (or, with ``tol``, tolerance-equal) rows do not
    dominate each other: all of them are returned; see :func:`dedupe`.

    Examples
    --------
    >>> nondominated([[1, 2], [2, 1], [2, 2], [1, 2]]).tolist()
    [0, 1, 3]
    >>> nondominated([[1, 2], [1.5, 2 - 1e-12]], tol=1e-9).tolist()
    [0]
    """
    F = _as_F(F, "F")
    if len(F) == 0:
        return np.zeros(0, np.int64)
    if tol == 0:
        from pymoo.util.nds.non_dominated_sorting import NonDominatedSorting

        idx = NonDominatedSorting().do(F, only_non_dominated_front=True)
        return np.sort(np.asarray(idx, dtype=np.int64))
    dominated = np.zeros(len(F), bool)
    chunk = max(1, 2_000_000 // max(1, F.size))
    for s in range(0, len(F), chunk):
        B = F[s : s + chunk, None, :]  # candidates to be dominated
        A = F[None, :, :]  # potential dominators
        eq = close(A, B, tol)
        not_worse = ((A <= B) | eq).all(axis=2)
        better = ((A < B) & ~eq).any(axis=2)
        dominated[s : s + chunk] = (not_worse & better).any(axis=1)
    return np.flatnonzero(~dominated)


def dedupe(F, tol: float = TOL, prefer=None) -> np.ndarray:
    """Indices (ascending) keeping one row per tolerance-equal objective vector.

    Rows are visited in increasing order of ``prefer`` (then of index); a row
    is kept unless it is ``close`` in every objective to a row kept before.

    Parameters
    ----------
    F : (k, m) array_like.
    tol : SPEC tolerance (default 1e-9); 0 keeps one row per exactly equal
        vector.
    prefer : (k,) array_like, optional. Among equal rows the one with the
        smallest value is kept (e.g. smoothness); default: the first row.

    Returns
    -------
    (j,) int array.

    Examples
    --------
    >>> dedupe([[1.0, 2.0], [1.0, 2.0 + 1e-12], [3.0, 0.0]], prefer=[5, 1, 0]).tolist()
    [1, 2]
    """
    F = _as_F(F, "F")
    if len(F) == 0:
        return np.zeros(0, np.int64)
    if prefer is None:
        order = np.arange(len(F))
    else:
        prefer = np.asarray(prefer, float).ravel()
        if len(prefer) != len(F):
            raise ConfigError(f"prefer has {len(prefer)} values for {len(F)} rows")
        order = np.argsort(prefer, kind="stable")
    kept: list[int] = []
    for i in order:
        if kept and close(F[kept], F[i], tol).all(axis=1).any():
            continue
        kept.append(int(i))
    return np.sort(np.asarray(kept, dtype=np.int64))
