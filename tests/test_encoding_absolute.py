import numpy as np
import pytest
from encoding_cases import (
    assert_valid_simple,
    empty_ws,
    frame_paths,
    genome_matrix,
    same_paths,
    workspaces,
)
from hypothesis import given, settings
from hypothesis import strategies as st

from gapath import ConfigError
from gapath.encodings import AbsoluteEncoding, Frame, IntegerEncoding
from gapath.problems import GridPathProblem


@st.composite
def cases(draw):
    ws = draw(workspaces())
    enc = AbsoluteEncoding(Frame.of(ws))
    m = 3 * max(ws.shape)
    return ws, enc, genome_matrix(draw, enc.n_var, st.integers(-m, m))


@settings(max_examples=100, deadline=None)
@given(cases())
def test_any_genome_decodes_to_a_valid_path(case):
    ws, enc, X = case
    problem = GridPathProblem(ws, encoding="absolute")
    for path in problem.decode(X):
        assert_valid_simple(ws, path)
    # the exits are the (clipped) genes, the goal row last
    exits = enc.decode(X)[1]
    assert np.array_equal(exits[:, :-1], np.clip(X, 0, enc.frame.height - 1))
    assert (exits[:, -1] == enc.frame.goal[0]).all()


@settings(max_examples=100, deadline=None)
@given(cases(), st.integers(0, 2**32 - 1))
def test_edge_fixed_genomes_round_trip(case, seed):
    ws, enc, X = case
    Xf = enc.edge_fix(X, np.random.default_rng(seed))
    assert Xf.dtype == np.int64
    assert (Xf >= enc.xl).all() and (Xf <= enc.xu).all()
    assert np.array_equal(enc.encode_profiles(*enc.decode(Xf)), Xf)  # non-redundant


def test_paper_examples():
    # Fig. 2 paths as exit rows per column (section 2.4), same paths as the
    # integer strings of section 2.3
    enc = AbsoluteEncoding(Frame.of(empty_ws(8, 8)))
    integer = IntegerEncoding(enc.frame)
    A = np.array([[7, 4, 3, 3, 5, 6, 6], [2, 1, 1, 0, 2, 3, 1]])
    entries, exits = enc.decode(A)
    ie, ix = integer.decode(np.array([[0, 3, 1, 0, -2, -1, 0], [5, 1, 0, 1, -2, -1, 2]]))
    assert np.array_equal(entries, ie) and np.array_equal(exits, ix)
    assert exits[:, -1].tolist() == [0, 0] and entries[:, -1].tolist() == [5, 0]
    assert np.array_equal(enc.encode_profiles(entries, exits), A)


def test_bounds():
    enc = AbsoluteEncoding(Frame.of(empty_ws(6, 5, start=(2, 0))))
    assert enc.n_var == 4 and enc.xl.tolist() == [0] * 4 and enc.xu.tolist() == [5] * 4
    assert enc.edge_fix([[-3, 2.6, 9, 4]]).tolist() == [[0, 3, 5, 4]]


def test_encode_decode_round_trip_on_random_monotone_paths():
    ws = empty_ws(15, 20)
    p = GridPathProblem(ws, encoding="absolute")
    paths = frame_paths(ws, np.random.default_rng(0), 50, max_step=4)
    X = p.encode(paths)
    assert same_paths(paths, p.decode(X))
    assert np.array_equal(p.encode(p.decode(X)), X)


@pytest.mark.parametrize(
    "start,goal", [((0, 7), (5, 0)), ((5, 3), (0, 3)), ((1, 2), (4, 2)), ((2, 0), (3, 7))]
)
def test_mirrored_and_transposed_frames(start, goal):
    ws = empty_ws(6, 8, start, goal)
    p = GridPathProblem(ws, encoding="absolute")
    rng = np.random.default_rng(1)
    X = rng.integers(p.xl, p.xu + 1, size=(30, p.n_var))
    paths = p.decode(X)
    for path in paths:
        assert_valid_simple(ws, path)
    assert np.array_equal(p.encode(paths), X)
    paths = frame_paths(ws, rng, 20)
    assert same_paths(paths, p.decode(p.encode(paths)))


def test_unrepresentable_paths_are_rejected():
    enc = AbsoluteEncoding(Frame.of(empty_ws(4, 3)))
    with pytest.raises(ConfigError, match="not representable in the absolute encoding"):
        enc.encode([[(3, 0), (3, 1), (2, 1), (1, 2), (0, 2)]])
    with pytest.raises(ConfigError, match="absolute genomes need 2 genes"):
        enc.decode(np.zeros((1, 3)))
