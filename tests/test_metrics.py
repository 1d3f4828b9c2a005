"""Front indicators and bookkeeping (gapath.metrics)."""

from __future__ import annotations

import numpy as np
import pytest

from gapath import ConfigError, Workspace
from gapath.metrics import (
    close,
    coverage,
    dedupe,
    hv_ratio,
    hypervolume,
    igd_plus,
    nondominated,
    normalisation_bounds,
)

REF = np.array([[1.0, 10.0], [2.0, 5.0], [3.0, 2.0], [5.0, 1.0]])


# ---------------------------------------------------------------------------
# hypervolume
# ---------------------------------------------------------------------------


def test_hv_ratio_of_reference_is_one():
    assert hv_ratio(REF, REF) == 1.0
    R3 = np.array([[0.0, 1.0, 2.0], [1.0, 0.0, 2.0], [2.0, 2.0, 0.0]])
    assert hv_ratio(R3, R3) == 1.0


def test_hypervolume_normalises_as_spec_says():
    # normalised: (0, 1), (0.25, 4/9), (0.5, 1/9), (1, 0); reference point 1.1
    z = np.array([[0.0, 1.0], [0.25, 4 / 9], [0.5, 1 / 9], [1.0, 0.0]])
    z = z[np.argsort(z[:, 0])]
    widths = np.diff(np.append(z[:, 0], 1.1))
    expected = float(np.sum(widths * (1.1 - z[:, 1])))
    ideal, nadir = normalisation_bounds(REF)
    assert ideal.tolist() == [1.0, 1.0] and nadir.tolist() == [5.0, 10.0]
    assert hypervolume(REF, ideal, nadir) == pytest.approx(expected, rel=1e-12)


def test_hv_ratio_of_dominated_subset_is_below_one():
    for subset in (REF[:2], REF[[0, 3]], REF[1:3]):
        assert 0.0 < hv_ratio(subset, REF) < 1.0
    worse = REF + 0.5
    assert 0.0 < hv_ratio(worse, REF) < 1.0
    assert hv_ratio(REF[:3], REF) < hv_ratio(REF, REF)


def test_hv_ratio_can_exceed_one_for_a_better_front():
    assert hv_ratio(REF - 0.5, REF) > 1.0


def test_points_beyond_reference_point_count_zero():
    ideal, nadir = REF.min(axis=0), REF.max(axis=0)
    beyond = nadir + 1.2 * (nadir - ideal)  # > 1.1 normalised on both axes
    assert hv_ratio([beyond], REF) == 0.0
    assert hv_ratio([[ideal[0], beyond[1]]], REF) == 0.0  # beyond on one axis only
    # penalised GA points (f + 1000 * interfering) are beyond as well
    assert hv_ratio(REF + 1000.0, REF) == 0.0
    # adding such points changes nothing
    assert hv_ratio(np.vstack([REF[:2], REF + 1000.0]), REF) == hv_ratio(REF[:2], REF)


def test_empty_front():
    assert hv_ratio(np.zeros((0, 2)), REF) == 0.0
    assert hv_ratio([], REF) == 0.0
    assert igd_plus([], REF) == float("inf")
    assert coverage([], REF) == 0.0
    with pytest.raises(ConfigError):
        hv_ratio(REF, np.zeros((0, 2)))


def test_one_point_reference_uses_unit_range():
    ref = np.array([[3.0, 4.0]])
    ideal, nadir = normalisation_bounds(ref)
    assert ideal.tolist() == [3.0, 4.0] and nadir.tolist() == [4.0, 5.0]
    assert hv_ratio(ref, ref) == 1.0
    # 0.5 worse on each axis: (1.1 - 0.5)^2 / 1.1^2
    assert hv_ratio([[3.5, 4.5]], ref) == pytest.approx(0.6**2 / 1.1**2, rel=1e-12)
    # a degenerate axis in a larger front (all lengths equal)
    ref2 = np.array([[2.0, 1.0], [2.0, 3.0]])
    ideal, nadir = normalisation_bounds(ref2)
    assert nadir.tolist() == [3.0, 3.0]
    assert hv_ratio(ref2, ref2) == 1.0


def test_hv_ratio_accepts_objects_with_F():
    class Front:
        F = REF[:2]

    assert hv_ratio(Front(), REF) == hv_ratio(REF[:2], REF)


def test_dimension_mismatch():
    with pytest.raises(ConfigError):
        hv_ratio(np.zeros((2, 3)), REF)


# ---------------------------------------------------------------------------
# IGD+, coverage
# ---------------------------------------------------------------------------


def test_igd_plus():
    assert igd_plus(REF, REF) == 0.0
    assert igd_plus(REF - 1.0, REF) == 0.0  # a dominating front
    assert igd_plus(REF[:2], REF) > 0.0
    assert igd_plus(REF + 0.5, REF) > igd_plus(REF + 0.1, REF)


def test_coverage():
    assert coverage(REF, REF) == 1.0
    assert coverage(REF[:2], REF) == 0.5
    # tolerance-equal points match
    assert coverage(REF * (1 + 1e-12), REF) == 1.0
    assert coverage(REF * (1 + 1e-6), REF) == 0.0
    assert coverage(REF * (1 + 1e-6), REF, tol=1e-5) == 1.0
    # dominating points do not "match"
    assert coverage(REF - 1.0, REF) == 0.0
    # matching is per point: extra front points do not matter
    assert coverage(np.vstack([REF[1:2], REF + 3]), REF) == 0.25


def test_close():
    assert close(1e6, 1e6 + 1e-4)  # relative
    assert not close(1e6, 1e6 + 1e-2)
    assert close(0.0, 1e-10)  # absolute below 1
    assert not close(0.0, 1e-8)


# ---------------------------------------------------------------------------
# nondominated, dedupe
# ---------------------------------------------------------------------------


def test_nondominated_exact():
    F = np.array([[1, 5], [2, 2], [3, 3], [5, 1], [2, 2], [1, 6], [6, 6]], float)
    assert nondominated(F).tolist() == [0, 1, 3, 4]
    assert nondominated(np.zeros((0, 2))).tolist() == []
    assert nondominated([[1.0, 2.0]]).tolist() == [0]
    F3 = np.array([[1, 2, 3], [2, 1, 3], [1, 2, 4], [3, 3, 0]], float)
    assert nondominated(F3).tolist() == [0, 1, 3]


def test_nondominated_with_tolerance():
    F = np.array(
        [
            [1.0, 2.0],
            [1.5, 2.0 - 1e-12],  # better in vulnerability only by rounding-level noise
            [1.0, 2.0 + 1e-12],  # tolerance-equal to row 0
            [2.0, 1.0],
        ]
    )
    assert nondominated(F).tolist() == [0, 1, 3]
    assert nondominated(F, tol=1e-9).tolist() == [0, 2, 3]


def test_dedupe():
    F = np.array(
        [
            [1.0, 2.0],
            [3.0, 1.0],
            [1.0, 2.0 + 1e-12],
            [1.0, 2.0],
            [3.0 + 1e-11, 1.0],
            [2.0, 2.0],
        ]
    )
    assert dedupe(F).tolist() == [0, 1, 5]
    assert dedupe(F, prefer=[3, 2, 1, 0, 2, 9]).tolist() == [1, 3, 5]
    assert dedupe(F, prefer=[3, 5, 1, 0, 2, 9]).tolist() == [3, 4, 5]
    assert dedupe(F, tol=0.0).tolist() == [0, 1, 2, 4, 5]
    assert dedupe(np.zeros((0, 3))).tolist() == []
    with pytest.raises(ConfigError):
        dedupe(F, prefer=[1, 2])


def test_exact_front_against_itself():
    from gapath.planners.exact import monotone_front

    occ = np.zeros((8, 8), bool)
    occ[2:5, 3] = occ[5, 5] = occ[1, 6] = True
    front = monotone_front(Workspace(occ), ("length", "vulnerability"))
    assert hv_ratio(front, front.F) == 1.0
    assert coverage(front, front.F) == 1.0
    assert nondominated(front.F, tol=1e-9).tolist() == list(range(len(front)))
    assert dedupe(front.F).tolist() == list(range(len(front)))
