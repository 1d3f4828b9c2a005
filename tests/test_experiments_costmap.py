"""The ``costmap:`` key of experiment specs: layer objectives in an
experiment run on the costmap that ``gapath solve``'s flags build (one
builder, :func:`gapath.costmap.costmap_from_settings`), the runs record it in
their settings, and every bad entry is one message naming the spec file and
the key, with exit status 2."""

import numpy as np
import pytest
from experiment_cases import stored
from test_cli_costmap import SMALL

from gapath.cli import main
from gapath.costmap import CostmapSettings, costmap_from_settings
from gapath.errors import EXIT_BAD_INPUT
from gapath.experiments.runner import front_from_dict
from gapath.experiments.spec import ExperimentSpec, load_spec, run_key
from gapath.loaders import load_text
from gapath.solver import solve

OBJECTIVES = ["length", "vulnerability", "elevation_max"]
SPEC = """\
name: layers
maps: [small.txt]
settings:
  objectives: [length, vulnerability, elevation_max]
  pop_size: 16
  n_gen: 4
costmap:
  dem: data/dem.npy
  dem_method: reflect
seeds: [1, 2]
"""


@pytest.fixture
def files(tmp_path):
    (tmp_path / "small.txt").write_text("\n".join(SMALL) + "\n")
    (tmp_path / "data").mkdir()
    rng = np.random.default_rng(5)
    np.save(tmp_path / "data" / "dem.npy", rng.random((6, 7)))
    np.save(tmp_path / "sand.npy", rng.random((8, 10)))
    np.save(tmp_path / "small.npy", rng.random((3, 3)))
    return tmp_path


def test_spec_costmap_runs_end_to_end_like_solve(files, capsys):
    spec = files / "e.yaml"
    spec.write_text(SPEC)
    out = files / "store"
    assert (
        main(["experiment", "run", str(spec), "--out", str(out), "--workers", "0", "--quiet", "--no-plots"])
        == 0
    )
    results = stored(out)
    assert len(results) == 2
    ws = load_text(files / "small.txt")
    settings = CostmapSettings(dem=files / "data" / "dem.npy", dem_method="reflect")
    cm = costmap_from_settings(settings, ws, OBJECTIVES)
    for r in results.values():
        assert r["status"] == "ok", r
        rec = r["settings"]["costmap"]
        assert rec["layers"] == ["elevation"] and rec["elevation"]["method"] == "reflect"
        assert rec["elevation"]["file"] == str((files / "data" / "dem.npy").resolve())
        assert r["run"]["settings"]["costmap"]["dem"]["name"] == "dem.npy"
        direct = solve(ws, objectives=OBJECTIVES, pop_size=16, n_gen=4, seed=r["seed"], costmap=cm)
        got = front_from_dict(r["front"])
        assert got.objectives == tuple(OBJECTIVES)
        assert len(got) > 0
        np.testing.assert_array_equal(got.F, direct.front.F)


def test_costmap_key_changes_the_run_key_by_content_not_path(files, tmp_path):
    (files / "e.yaml").write_text(SPEC)
    other = tmp_path / "elsewhere"
    other.mkdir()
    (other / "data").mkdir()
    (other / "small.txt").write_text((files / "small.txt").read_text())
    (other / "data" / "dem.npy").write_bytes((files / "data" / "dem.npy").read_bytes())
    (other / "e.yaml").write_text(SPEC)
    a, b = load_spec(files / "e.yaml").runs(), load_spec(other / "e.yaml").runs()
    assert run_key(a[0]) == run_key(b[0])
    plain = ExperimentSpec(maps=[str(files / "small.txt")], settings={"pop_size": 16}, seeds=[1])
    assert "costmap" not in plain.runs()[0]["settings"] and "costmap" not in plain.to_dict()
    # the saved spec (experiment.json) reads back to the same runs
    spec = load_spec(files / "e.yaml")
    assert ExperimentSpec.from_dict(spec.to_dict()).runs() == spec.runs()


def test_grid_of_objectives_gives_a_costmap_only_to_the_runs_that_use_it(files):
    spec = ExperimentSpec.from_dict(
        {
            "maps": ["small.txt"],
            "grid": {"objectives": [["length", "vulnerability"], ["length", "risk"]]},
            "costmap": {"risk": [2, 3]},
        },
        source=files / "e.yaml",
    )
    a, b = spec.runs()
    assert "costmap" not in a["settings"] and b["settings"]["costmap"] == {"risk": [2, 3]}


BAD = [
    ("costmap: {dems: data/dem.npy}", "e.yaml: costmap.dems: unknown key; expected one of dem, dem_method"),
    ("costmap: [dem.npy]", "e.yaml: costmap: expected a mapping, got ['dem.npy']"),
    ("costmap: {dem: 3}", "e.yaml: costmap.dem: expected a file path, got 3"),
    ("costmap: {terrain_seed: x}", "e.yaml: costmap.terrain_seed: expected an integer, got 'x'"),
    (
        "costmap: {dem: data/dem.npy, dem_method: cubic}",
        "e.yaml: costmap.dem_method: expected one of bilinear, reflect, got 'cubic'",
    ),
    ("costmap: {risk: 3}", "e.yaml: costmap.risk: expected [row, col], got 3"),
    ("costmap: {solar_rate: .inf}", "e.yaml: costmap.solar_rate: expected a number, got inf"),
    ("costmap: {layers: [sand.npy]}", "e.yaml: costmap.layers: expected a mapping, got ['sand.npy']"),
    ("costmap: {dem: missing.npy}", "e.yaml: costmap.dem: DEM file '{d}/missing.npy' does not exist"),
    (
        "costmap: {dem: data/dem.npy}\nsettings: {objectives: [length, vulnerability]}",
        "e.yaml: costmap.dem: sets the elevation layer, which no objective uses: add elevation (or elevation_max) to settings.objectives",
    ),
    (
        "costmap: {layers: {sand: sand.npy}}\nsettings: {objectives: [length, elevation]}",
        "e.yaml: costmap.layers.sand: sets the user layer 'sand', which no objective uses",
    ),
    (
        "costmap: {dem: data/dem.npy, terrain_seed: 2}",
        "e.yaml: costmap.terrain_seed: seeds the fractal terrain, which costmap.dem {d}/data/dem.npy replaces",
    ),
    ("costmap: {dem_method: reflect}", "e.yaml: costmap.dem_method: applies to a costmap.dem"),
    (
        "costmap: {layers: {risk: sand.npy}}",
        "e.yaml: costmap.layers.risk: layer name 'risk' is built in (costmap.risk sets it)",
    ),
    (
        "costmap: {layers: {sand: small.npy}}\nsettings: {objectives: [length, sand]}",
        "e.yaml: costmap.layers.sand: layer 'sand' must have the grid's shape (8, 10), got shape (3, 3)",
    ),
    (
        "costmap: {risk: [99, 3]}\nsettings: {objectives: [length, risk]}",
        "e.yaml: costmap.risk: risk cell (99, 3) is outside the 8x10 grid",
    ),
    (
        "costmap: {layers: {sand: sand.npy}}\nsettings: {objectives: [length, mud]}",
        "e.yaml: settings.objectives: unknown objective 'mud'; expected some of",
    ),
    (
        "settings: {objectives: [length, risk], seed_from: exact}",
        "e.yaml: settings.seed_from: exact seeds from the exact monotone front, which has no costmap layers (risk)",
    ),
]


@pytest.mark.parametrize(
    "entry,message", BAD, ids=[m.split(":")[1].strip() + f"-{i}" for i, (_, m) in enumerate(BAD)]
)
def test_bad_costmap_key_is_one_message_and_exit_2(entry, message, files, capsys):
    base = "maps: [small.txt]\nseeds: [1]\n"
    if "objectives" not in entry:
        base += "settings: {objectives: [length, elevation]}\n"
    spec = files / "e.yaml"
    spec.write_text(base + entry + "\n")
    code = main(["experiment", "run", str(spec), "--out", str(files / "o"), "--workers", "0", "--quiet"])
    err = capsys.readouterr().err
    assert code == EXIT_BAD_INPUT, err
    assert message.replace("{d}", str(files.resolve())) in err, err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
