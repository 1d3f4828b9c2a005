import json

import numpy as np
import pytest
from pymoo.core.callback import Callback

from gapath import ConfigError
from gapath.generators import random_workspace
from gapath.results import write_result
from gapath.solver import solve


class _Interrupt(Callback):
    def __init__(self, at):
        super().__init__()
        self.at = at

    def notify(self, algorithm):
        if algorithm.n_gen >= self.at:
            raise KeyboardInterrupt


def test_interrupted_run_keeps_its_front(tmp_path):
    ws = random_workspace((12, 12), 20, seed=2)
    r = solve(ws, pop_size=30, n_gen=50, seed=1, callback=_Interrupt(4))
    assert r.interrupted and r.n_gen == 4
    assert len(r.front) >= 1
    write_result(r, tmp_path, plots=False)
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["interrupted"] is True and summary["generations"] == 4
    assert len(json.loads((tmp_path / "paths.json").read_text())) == len(r.front)


def test_unseeded_protocol_and_determinism():
    ws = random_workspace((12, 12), 20, seed=2)
    a = solve(ws, pop_size=30, n_gen=8, seed=3, seed_from="none")
    b = solve(ws, pop_size=30, n_gen=8, seed=3, seed_from="none")
    assert np.array_equal(a.front.F, b.front.F) and np.array_equal(a.front.X, b.front.X)
    assert a.settings["seed_from"] == "none"


@pytest.mark.parametrize(
    "kw,match",
    [
        (dict(pop_size=0), "pop_size"),
        (dict(n_gen=2.5), "n_gen"),
        (dict(seed_from="magic"), "seed source"),
        (dict(tiebreak="turns"), "tiebreak"),
    ],
)
def test_bad_settings(kw, match):
    with pytest.raises(ConfigError, match=match):
        solve(random_workspace((8, 8), 5, seed=0), **{"pop_size": 10, "n_gen": 2, **kw})


def test_engines_give_the_same_front():
    ws = random_workspace((12, 12), 20, seed=2)
    a = solve(ws, pop_size=30, n_gen=8, seed=3, engine="fast")
    b = solve(ws, pop_size=30, n_gen=8, seed=3, engine="pymoo")
    assert a.settings["engine"] == "fast"
    assert np.array_equal(a.front.F, b.front.F) and np.array_equal(a.front.X, b.front.X)
    with pytest.raises(ConfigError, match="unknown engine"):
        solve(ws, pop_size=10, n_gen=2, engine="warp")


@pytest.mark.parametrize("engine", ["fast", "pymoo"])
def test_progress_bar_does_not_change_the_run(engine, capsys):
    ws = random_workspace((12, 12), 20, seed=2)
    quiet = solve(ws, pop_size=30, n_gen=6, seed=5, engine=engine)
    shown = solve(ws, pop_size=30, n_gen=6, seed=5, engine=engine, progress=True)
    assert np.array_equal(quiet.front.X, shown.front.X) and np.array_equal(quiet.front.F, shown.front.F)
    assert shown.n_gen == quiet.n_gen == 6 and shown.n_eval == quiet.n_eval
    bar = capsys.readouterr().err
    assert "6/6" in bar and "feasible=" in bar and "front=" in bar


def test_interrupted_run_with_the_bar_shows_the_last_complete_generation(capsys):
    ws = random_workspace((12, 12), 20, seed=2)
    r = solve(ws, pop_size=30, n_gen=50, seed=1, progress=True, callback=_Interrupt(4))
    assert r.interrupted and r.n_gen == 4 and len(r.front) >= 1
    assert "4/50" in capsys.readouterr().err
