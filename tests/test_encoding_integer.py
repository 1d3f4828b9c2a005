import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gapath import ConfigError, Workspace
from gapath.encodings import Frame, IntegerEncoding, make_encoding
from gapath.generators import random_monotone_path


def _ws(h, w, start=None, goal=None):
    return Workspace(np.zeros((h, w), bool), start, goal)


grids = st.tuples(st.integers(2, 12), st.integers(2, 12))


@st.composite
def workspace_and_genes(draw):
    h, w = draw(grids)
    cells = [(r, c) for r in range(h) for c in range(w)]
    start = draw(st.sampled_from(cells))
    goal = draw(st.sampled_from([x for x in cells if x != start]))
    ws = _ws(h, w, start, goal)
    enc = IntegerEncoding(Frame.of(ws))
    n = draw(st.integers(1, 6))
    X = np.array(
        draw(
            st.lists(
                st.lists(st.integers(-3 * max(h, w), 3 * max(h, w)), min_size=enc.n_var, max_size=enc.n_var),
                min_size=n,
                max_size=n,
            )
        )
    )
    return ws, enc, X


@settings(max_examples=150, deadline=None)
@given(workspace_and_genes())
def test_any_genome_decodes_to_a_valid_path(case):
    ws, enc, X = case
    from gapath.problems import GridPathProblem

    problem = GridPathProblem(ws)
    for path in problem.decode(X):
        assert ws.is_valid_path(path), path
        assert len({tuple(c) for c in path}) == len(path)  # no repeated cell


@settings(max_examples=100, deadline=None)
@given(workspace_and_genes(), st.integers(0, 2**32 - 1))
def test_edge_fixed_genomes_round_trip(case, seed):
    ws, enc, X = case
    Xf = enc.edge_fix(X, np.random.default_rng(seed))
    assert (Xf >= enc.xl).all() and (Xf <= enc.xu).all()
    entries, exits = enc.decode(Xf)
    assert np.array_equal(enc.encode_profiles(entries, exits), Xf)


def test_seeds_example_path_1():
    # Ahmed & Deb Fig. 2, Path 1 on 8x8: (0, 3, 1, 0, -2, -1, 0); the end
    # column is reached by a diagonal then five cells up.
    ws = _ws(8, 8)
    enc = IntegerEncoding(Frame.of(ws))
    entries, exits = enc.decode(np.array([[0, 3, 1, 0, -2, -1, 0]]))
    assert exits[0].tolist() == [7, 4, 3, 3, 5, 6, 6, 0]
    assert entries[0, -1] == 5  # diagonal step up into the last column


def test_gene_bounds_follow_the_start_row():
    enc = IntegerEncoding(Frame.of(_ws(6, 5)))
    assert enc.n_var == 4
    assert (enc.xl[0], enc.xu[0]) == (0, 5)  # bottom start: only upward moves
    assert (enc.xl[1:] == -5).all() and (enc.xu[1:] == 5).all()
    mid = IntegerEncoding(Frame.of(_ws(6, 5, start=(2, 0))))
    assert (mid.xl[0], mid.xu[0]) == (-3, 2)


def test_encode_decode_round_trip_on_random_monotone_paths():
    rng = np.random.default_rng(0)
    ws = _ws(15, 20)
    from gapath.problems import GridPathProblem

    p = GridPathProblem(ws)
    paths = [random_monotone_path(ws.shape, ws.start, ws.goal, rng, max_step=4) for _ in range(50)]
    X = p.encode(paths)
    for a, b in zip(paths, p.decode(X)):
        assert np.array_equal(a, b)


def test_unrepresentable_paths_are_rejected():
    ws = _ws(4, 3)
    enc = IntegerEncoding(Frame.of(ws))
    # horizontal step followed by an upward move (C-D1): dominated, not coded
    with pytest.raises(ConfigError, match="not representable"):
        enc.encode([[(3, 0), (3, 1), (2, 1), (1, 2), (0, 2)]])
    with pytest.raises(ConfigError, match="column-monotone"):
        enc.encode([[(3, 0), (2, 1), (2, 0), (1, 1), (0, 2)]])
    with pytest.raises(ConfigError, match="start to goal"):
        enc.encode([[(2, 0), (1, 1), (0, 2)]])


@pytest.mark.parametrize("start,goal", [((0, 7), (5, 0)), ((5, 3), (0, 3)), ((1, 2), (4, 2))])
def test_mirrored_and_transposed_frames(start, goal):
    from gapath.problems import GridPathProblem

    ws = _ws(6, 8, start, goal)
    p = GridPathProblem(ws)
    rng = np.random.default_rng(1)
    X = p.encoding.edge_fix(rng.integers(p.xl, p.xu + 1, size=(30, p.n_var)), rng)
    paths = p.decode(X)
    for path in paths:
        assert ws.is_valid_path(path)
    assert np.array_equal(p.encode(paths), X)


def test_edge_fix_draws_rows_with_linear_probability():
    ws = _ws(6, 3)  # start row 5; gene 1 moves from row r
    enc = IntegerEncoding(Frame.of(ws))
    X = np.tile([[2, 9]], (60000, 1))  # row 3, then 9 up: beyond the top edge
    Xf = enc.edge_fix(X, np.random.default_rng(5))
    rows = 3 - Xf[:, 1]
    counts = np.bincount(rows, minlength=6)[:4]  # rows 0..3
    # weight 3 at the edge (row 0), 2, 1, and 0 at the current row 3
    np.testing.assert_allclose(counts / counts.sum(), [3 / 6, 2 / 6, 1 / 6, 0], atol=0.01)


def test_edge_fix_is_reproducible_for_a_seed():
    enc = IntegerEncoding(Frame.of(_ws(10, 10)))
    X = np.random.default_rng(0).integers(-20, 20, size=(40, enc.n_var))
    a = enc.edge_fix(X, np.random.default_rng(3))
    b = enc.edge_fix(X, np.random.default_rng(3))
    assert np.array_equal(a, b)


def test_unknown_encoding():
    with pytest.raises(ConfigError, match="unknown encoding 'gray'"):
        make_encoding("gray", Frame.of(_ws(3, 3)))


@settings(max_examples=60, deadline=None)
@given(workspace_and_genes())
def test_decode_keys_are_the_profiles_side_by_side(case):
    _, enc, X = case
    entries, exits = enc.decode(X)
    K = enc.decode_keys(X)
    assert K.dtype == np.int64 and K.flags.c_contiguous
    assert np.array_equal(K, np.hstack([entries, exits]))
    assert np.array_equal(enc.decode_keys(X.astype(float) + 0.2), K)  # rounded, as decode


@settings(max_examples=60, deadline=None)
@given(workspace_and_genes(), st.integers(0, 2**32 - 1))
def test_edge_fix_of_integer_and_float_genes_agree(case, seed):
    """Integer genes skip the rounding pass; the result is the same."""
    _, enc, X = case
    a = enc.edge_fix(X, np.random.default_rng(seed))
    b = enc.edge_fix(X.astype(float), np.random.default_rng(seed))
    assert a.dtype == np.int64 and np.array_equal(a, b)


@settings(max_examples=40, deadline=None)
@given(workspace_and_genes(), st.integers(0, 2**32 - 1))
def test_edge_fix_drawn_is_edge_fix_with_its_draws(case, seed):
    _, enc, X = case
    a = enc.edge_fix(X, np.random.default_rng(seed))
    b = enc.edge_fix_drawn(X, np.random.default_rng(seed).random(X.shape))
    assert np.array_equal(a, b)
    with pytest.raises(ConfigError, match="one draw per gene"):
        enc.edge_fix_drawn(X, np.zeros((len(X), enc.n_var + 1)))
