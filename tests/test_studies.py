"""The paper studies' library entry points (gapath.studies.*.run): callable
without argparse, the same studies as their ``gapath experiment`` commands."""

import pytest

from gapath.errors import ConfigError


def test_every_study_has_a_library_run():
    from gapath.studies import dense, dynamic, encodings, mars

    for study in (dense, dynamic, encodings, mars):
        assert callable(study.run)
        assert "argparse" not in study.run.__code__.co_names


def test_dense_run_writes_the_report_and_counts_failures(tmp_path):
    from gapath.studies import dense

    rep = dense.run(
        tmp_path / "stores",
        grids=(8,),
        p0s=(0.3,),
        runs=2,
        large_runs=0,
        results=tmp_path / "results",
        workers=0,
        progress=False,
    )
    assert rep["failed"] == 0 and set(rep["wall_seconds"]) == {"table1"}
    assert [f.name for f in rep["files"]] == ["dense.md", "dense.csv", "dense.png"]
    assert all(f.parent == tmp_path / "results" and f.is_file() for f in rep["files"])
    (row,) = rep["table1"]
    assert (row["grid"], row["p0"], row["runs"]) == (8, 0.3, 2)
    # resumed: nothing runs again, so no wall time is recorded
    again = dense.run(
        tmp_path / "stores",
        grids=(8,),
        p0s=(0.3,),
        runs=2,
        large_runs=0,
        results=tmp_path / "results",
        workers=0,
        progress=False,
    )
    assert again["wall_seconds"] == {} and again["table1"] == rep["table1"]


def test_mars_run_takes_the_quick_settings_and_checks_the_terrain(monkeypatch):
    from gapath.studies import mars

    study = mars.run(1, quick=True, size=20, terrain="fractal", ga_gen=2)
    assert study.settings["n_workspaces"] == 1 and study.settings["terrain"] == "fractal"
    assert (study.settings["ga_pop"], study.settings["ga_gen"]) == (mars.QUICK["ga_pop"], 2)
    with pytest.raises(ConfigError, match="terrain must be one of auto, mars, fractal"):
        mars.run(1, terrain="moon")
    monkeypatch.setattr(mars, "find_mars_dtm", lambda: None)
    with pytest.raises(ConfigError, match="terrain 'mars': the Mars DTM"):
        mars.run(1, terrain="mars")
