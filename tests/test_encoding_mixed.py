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
from gapath.encodings import Frame, IntegerEncoding, MixedEncoding
from gapath.problems import GridPathProblem

# Ahmed & Deb section 2.2 on 8x8, "(0 1-3 1-1 0-0 0-2 0-1 1-0 1)": the
# trailing bit pairs with the leading integer (gene 0, the start column)
PATH_1 = [1, 1, 1, 0, 0, 0, 1] + [0, 3, 1, 0, 2, 1, 0]
PATH_2 = [1, 1, 1, 1, 0, 0, 1] + [5, 1, 0, 1, 2, 1, 2]  # "(5 1-1 1-0 1-1 0-2 0-1 1-2 1)"


def targets_leave_grid(enc, X):
    """Whether some move of each genome leaves the grid (decode would clamp)."""
    f = enc.frame
    D = enc.moves(X)
    rows = f.start[0] - np.cumsum(D, axis=1)
    return ((rows < 0) | (rows > f.height - 1)).any(axis=1)


@st.composite
def cases(draw):
    ws = draw(workspaces())
    enc = MixedEncoding(Frame.of(ws))
    m = 3 * max(ws.shape)
    return ws, enc, genome_matrix(draw, enc.n_var, st.integers(-m, m))


@settings(max_examples=100, deadline=None)
@given(cases())
def test_any_genome_decodes_to_a_valid_path(case):
    ws, enc, X = case
    problem = GridPathProblem(ws, encoding="mixed")
    for path in problem.decode(X):
        assert_valid_simple(ws, path)
    # the same path as the integer genome of the signed moves
    integer = IntegerEncoding(enc.frame)
    a, b = enc.decode(X), integer.decode(enc.moves(X))
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])


@settings(max_examples=100, deadline=None)
@given(cases(), st.integers(0, 2**32 - 1))
def test_edge_fix_stays_in_bounds_and_removes_clamping(case, seed):
    ws, enc, X = case
    Xf = enc.edge_fix(X, np.random.default_rng(seed))
    assert Xf.dtype == np.int64
    assert (Xf >= enc.xl).all() and (Xf <= enc.xu).all()
    assert not targets_leave_grid(enc, Xf).any()
    assert np.array_equal(enc.edge_fix(Xf, np.random.default_rng(seed + 1)), Xf)
    # redundant only in the bit of a zero move: round trip up to those bits
    entries, exits = enc.decode(Xf)
    Y = enc.encode_profiles(entries, exits)
    m = enc.n_genes
    assert np.array_equal(Y[:, m:], Xf[:, m:])
    moving = Xf[:, m:] > 0
    assert np.array_equal(Y[:, :m][moving], Xf[:, :m][moving])
    again = enc.decode(Y)
    assert np.array_equal(again[0], entries) and np.array_equal(again[1], exits)


def test_paper_examples():
    enc = MixedEncoding(Frame.of(empty_ws(8, 8)))
    integer = IntegerEncoding(enc.frame)
    entries, exits = enc.decode(np.array([PATH_1, PATH_2]))
    assert exits.tolist() == [[7, 4, 3, 3, 5, 6, 6, 0], [2, 1, 1, 0, 2, 3, 1, 0]]
    # the integer encoding's strings of section 2.3 give the same paths
    ie, ix = integer.decode(np.array([[0, 3, 1, 0, -2, -1, 0], [5, 1, 0, 1, -2, -1, 2]]))
    assert np.array_equal(ie, entries) and np.array_equal(ix, exits)
    assert entries[:, -1].tolist() == [5, 0]  # diagonal up into the goal column
    # encode writes bit 1 for a zero move: Path 2 comes back unchanged, Path 1
    # with 1-0 for its 0-0 (the paper uses both)
    path_1 = list(PATH_1)
    path_1[3] = 1
    assert enc.encode_profiles(entries, exits).tolist() == [path_1, PATH_2]


def test_bounds_and_layout():
    enc = MixedEncoding(Frame.of(empty_ws(6, 5, start=(2, 0))))
    assert (enc.n_genes, enc.n_bits, enc.n_var) == (4, 4, 8)
    assert enc.xl.tolist() == [0] * 8 and enc.xu.tolist() == [1] * 4 + [6] * 4
    # start column: bit 0 moves down, bit 1 up
    assert enc.decode([[0, 1, 1, 1, 3, 0, 0, 0]])[1][0].tolist() == [5, 5, 5, 5, 0]
    assert enc.decode([[1, 1, 1, 1, 2, 0, 0, 0]])[1][0].tolist() == [0, 0, 0, 0, 0]
    # y = 0 is horizontal whatever the bit; out-of-range values are clipped
    a = enc.decode([[1, 0, 1, 0, 0, 0, 0, 0]])
    b = enc.decode([[1, 1, 0, 7, 0, 0, -4, 0]])
    assert np.array_equal(a[1], b[1])


def test_encode_decode_round_trip_on_random_monotone_paths():
    ws = empty_ws(15, 20)
    p = GridPathProblem(ws, encoding="mixed")
    paths = frame_paths(ws, np.random.default_rng(0), 50, max_step=4)
    X = p.encode(paths)
    assert X.dtype == np.int64 and (X >= p.xl).all() and (X <= p.xu).all()
    assert same_paths(paths, p.decode(X))


@pytest.mark.parametrize(
    "start,goal", [((0, 7), (5, 0)), ((5, 3), (0, 3)), ((1, 2), (4, 2)), ((2, 0), (3, 7))]
)
def test_mirrored_and_transposed_frames(start, goal):
    ws = empty_ws(6, 8, start, goal)
    p = GridPathProblem(ws, encoding="mixed")
    rng = np.random.default_rng(1)
    paths = frame_paths(ws, rng, 20)
    assert same_paths(paths, p.decode(p.encode(paths)))
    X = p.encoding.edge_fix(rng.integers(p.xl, p.xu + 1, size=(30, p.n_var)), rng)
    for path in p.decode(X):
        assert_valid_simple(ws, path)


def test_edge_fix_draws_rows_with_linear_probability():
    enc = MixedEncoding(Frame.of(empty_ws(6, 3)))  # start row 5
    X = np.tile([[1, 1, 2, 6]], (60000, 1))  # start 2 up (row 3), then 6 up: beyond the top
    Xf = enc.edge_fix(X, np.random.default_rng(5))
    rows = enc.decode(Xf)[1][:, 1]
    counts = np.bincount(rows, minlength=6)[:4]
    np.testing.assert_allclose(counts / counts.sum(), [3 / 6, 2 / 6, 1 / 6, 0], atol=0.01)
    # the start column is fixed too: 1 down from the bottom row stays put
    assert enc.edge_fix([[0, 1, 1, 0]], np.random.default_rng(0)).tolist() == [[0, 1, 0, 0]]


def test_unrepresentable_paths_are_rejected():
    enc = MixedEncoding(Frame.of(empty_ws(4, 3)))
    with pytest.raises(ConfigError, match="not representable in the mixed encoding"):
        enc.encode([[(3, 0), (3, 1), (2, 1), (1, 2), (0, 2)]])
    with pytest.raises(ConfigError, match="mixed genomes need 4 genes"):
        enc.decode(np.zeros((1, 3)))
