import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from reference import metrics as ref_metrics
from reference import potential as ref_potential

from gapath import ConfigError, Workspace
from gapath.encodings import Frame, IntegerEncoding, expand_profiles
from gapath.objectives import evaluate_path, evaluate_paths, objective_index, pad_paths
from gapath.workspace import potential_field


def test_potential_matches_full_sum():
    rng = np.random.default_rng(3)
    occ = rng.random((14, 17)) < 0.2
    # the 5-cell window drops terms below exp(-36): equal to 1e-12
    np.testing.assert_allclose(potential_field(occ), ref_potential(occ), rtol=0, atol=1e-12)


def test_potential_of_single_obstacle_by_hand():
    occ = np.zeros((5, 5), bool)
    occ[2, 2] = True
    pot = potential_field(occ)
    assert pot[2, 2] == 1.0
    assert pot[2, 3] == pytest.approx(math.exp(-1))
    assert pot[3, 3] == pytest.approx(math.exp(-2))
    assert pot[0, 0] == pytest.approx(math.exp(-8))


def test_workspace_caches_potential():
    ws = Workspace(np.eye(4, dtype=bool)[::-1] & False)
    assert ws.potential is ws.potential


def test_hand_computed_path():
    occ = np.zeros((3, 3), bool)
    occ[1, 2] = True
    ws = Workspace(occ)  # start (2,0), goal (0,2)
    # up, then diagonal up-right, then right: two 45-degree turns
    path = [(2, 0), (1, 0), (0, 1), (0, 2)]
    m = evaluate_path(ws, path)
    assert m["length"] == 2 + math.sqrt(2)
    assert m["smoothness"] == pytest.approx(math.pi / 2)
    expected_vul = math.exp(-5) + math.exp(-4) + math.exp(-2) + math.exp(-1)
    assert m["vulnerability"] == pytest.approx(expected_vul)
    assert m["interfering"] == 0
    # a reversal of heading is a turn of pi
    m2 = evaluate_path(ws, [(2, 0), (2, 1), (2, 0), (1, 0), (0, 1), (0, 2)])
    assert m2["smoothness"] == pytest.approx(math.pi + math.pi / 2 + math.pi / 2)


def test_corner_cutting_counts_as_interfering():
    occ = np.zeros((2, 2), bool)
    occ[0, 0] = True
    path = [(1, 0), (0, 1)]
    assert evaluate_path(Workspace(occ), path)["interfering"] == 0
    assert evaluate_path(Workspace(occ, corner_cutting=False), path)["interfering"] == 1


def test_cell_size_scales_length_only():
    occ = np.zeros((4, 4), bool)
    occ[1, 1] = True
    path = [(3, 0), (2, 1), (1, 2), (0, 3)]
    a = evaluate_path(Workspace(occ), path)
    b = evaluate_path(Workspace(occ, cell_size=0.5), path)
    assert b["length"] == a["length"] * 0.5
    assert b["vulnerability"] == a["vulnerability"]


def _random_walk(rng, h, w, n):
    r, c = int(rng.integers(h)), int(rng.integers(w))
    path = [(r, c)]
    while len(path) < n:
        dr, dc = rng.integers(-1, 2, size=2)
        if (dr or dc) and 0 <= r + dr < h and 0 <= c + dc < w:
            r, c = r + dr, c + dc
            path.append((r, c))
    return path


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 10_000), st.booleans())
def test_kernel_matches_python_reference(seed, corner_cutting):
    rng = np.random.default_rng(seed)
    h, w = rng.integers(3, 9, size=2)
    occ = rng.random((h, w)) < 0.3
    paths = [_random_walk(rng, h, w, int(rng.integers(2, 25))) for _ in range(5)]
    P, L = pad_paths(paths)
    got = evaluate_paths(P, L, occ, potential_field(occ), 1.0, corner_cutting)
    for p, row in zip(paths, got):
        ref = ref_metrics(occ, p, 1.0, corner_cutting)
        np.testing.assert_allclose(row, ref, rtol=1e-12, atol=1e-11)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 10_000))
def test_profile_kernel_is_bit_identical_to_path_kernel(seed):
    rng = np.random.default_rng(seed)
    h, w = rng.integers(3, 12, size=2)
    occ = rng.random((h, w)) < 0.3
    occ[h - 1, 0] = occ[0, w - 1] = False
    ws = Workspace(occ, corner_cutting=bool(rng.integers(2)))
    enc = IntegerEncoding(Frame.of(ws))
    X = rng.integers(-h, h + 1, size=(20, enc.n_var))
    entries, exits = enc.decode(X)
    a = Frame.of(ws).evaluate(entries, exits)
    P, L = expand_profiles(Frame.of(ws), entries, exits)
    b = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
    assert np.array_equal(a, b)


def test_equal_step_counts_give_bit_identical_lengths():
    ws = Workspace(np.zeros((6, 6), bool))
    a = evaluate_path(ws, [(5, 0), (4, 1), (4, 2), (3, 3), (2, 4), (1, 5), (0, 5)])
    b = evaluate_path(ws, [(5, 0), (5, 1), (4, 2), (3, 3), (2, 4), (1, 5), (0, 5)])
    assert a["length"] == b["length"]


def test_objective_names_are_checked():
    assert objective_index("length,vulnerability") == [0, 1]
    with pytest.raises(ConfigError, match="unknown objective 'speed'"):
        objective_index(["length", "speed"])
    with pytest.raises(ConfigError, match="twice"):
        objective_index(["length", "length"])


def test_evaluate_path_rejects_bad_paths():
    ws = Workspace(np.zeros((3, 3), bool))
    with pytest.raises(ConfigError, match="not 8-adjacent"):
        evaluate_path(ws, [(2, 0), (0, 2)])
    with pytest.raises(ConfigError, match="outside the 3x3 grid"):
        evaluate_path(ws, [(2, 0), (3, 0)])
