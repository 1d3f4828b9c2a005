"""The binary encoding's initial bit-flip rate: 1 / number of bits (gapath's
default) or 1 / n for an n-column grid (Ahmed & Deb's "1/n")."""

import numpy as np
import pytest

from gapath import Workspace, default_workspace
from gapath.errors import ConfigError
from gapath.operators.defaults import default_operators
from gapath.operators.mutation.decaying_bitflip import DecayingBitflipMutation
from gapath.problems import GridPathProblem
from gapath.solver import solve


@pytest.mark.parametrize("shape", [(32, 32), (12, 20), (20, 9)])
def test_named_rates(shape):
    p = GridPathProblem(Workspace(np.zeros(shape, bool)), encoding="binary")
    assert DecayingBitflipMutation().initial_rate(p) == 1.0 / p.n_var
    assert DecayingBitflipMutation("bits").initial_rate(p) == 1.0 / p.n_var
    assert DecayingBitflipMutation("grid").initial_rate(p) == 1.0 / p.frame.n_cols
    assert DecayingBitflipMutation(0.25).initial_rate(p) == 0.25


def test_grid_rate_flips_about_n_var_over_n_bits_per_genome():
    p = GridPathProblem(default_workspace(), encoding="binary")  # 217 bits, 32 columns
    X = np.zeros((4000, p.n_var), bool)
    flips = {
        r: DecayingBitflipMutation(r)._do(p, X, random_state=np.random.default_rng(3)).sum(axis=1).mean()
        for r in ("bits", "grid")
    }
    assert abs(flips["bits"] - 1.0) < 0.1
    assert abs(flips["grid"] - p.n_var / 32) < 0.3


@pytest.mark.parametrize("bad", ["paper", "1/n", -0.1, 1.5])
def test_bad_rates_raise(bad):
    with pytest.raises(ConfigError, match="prob_var"):
        DecayingBitflipMutation(bad)


def test_named_rate_is_for_the_binary_encoding_only():
    assert default_operators("binary", pm_prob_var="grid")["mutation"].rate_rule == "grid"
    with pytest.raises(ConfigError, match="binary encoding"):
        default_operators("integer", pm_prob_var="grid")


def test_solve_passes_the_rate_and_records_it():
    ws = default_workspace()
    runs = {
        r: solve(ws, encoding="binary", pop_size=20, n_gen=3, seed=2, seed_from="none", pm_prob_var=r)
        for r in ("bits", "grid")
    }
    for r, res in runs.items():
        assert res.settings["pm_prob_var"] == r
        m = res.pymoo_result.algorithm.mutation
        assert m.initial_rate(res.problem) == (1 / 217 if r == "bits" else 1 / 32)
    default = solve(ws, encoding="binary", pop_size=20, n_gen=3, seed=2, seed_from="none")
    assert "pm_prob_var" not in default.settings
    assert np.array_equal(default.front.F, runs["bits"].front.F)  # "bits" is the default
    assert not np.array_equal(
        runs["grid"].pymoo_result.algorithm.arrays.X, runs["bits"].pymoo_result.algorithm.arrays.X
    )
