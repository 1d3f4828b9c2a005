"""Tests of gapath.loaders: real benchmark maps, round trips, and every error."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from data_files import TESTS_DATA, data_path
from PIL import Image

from gapath.errors import ConfigError, MapError
from gapath.generators import default_workspace, random_workspace
from gapath.loaders import (
    Scenario,
    from_array,
    load_image,
    load_map,
    load_movingai,
    load_npy,
    load_occupancy,
    load_ros,
    load_scenarios,
    load_text,
    save_movingai,
)
from gapath.workspace import Workspace


@pytest.fixture(scope="module")
def data() -> Path:
    """``tests/data``: the small real maps (always in the repository). The
    large ones (512x512, Berlin, Willow) are optional: ``data_path(name)``
    finds them in ../shared/data or $GAPATH_SHARED_DATA, or skips."""
    return TESTS_DATA


def write(tmp_path: Path, name: str, content: str | bytes) -> Path:
    path = tmp_path / name
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, newline="")
    return path


def assert_error(exc_info, *fragments):
    message = str(exc_info.value)
    for fragment in fragments:
        assert str(fragment) in message, f"{fragment!r} not in {message!r}"


# ---------------------------------------------------------------------------
# real data (counts from tests/data/README.md and ../shared/data/README.md)
# ---------------------------------------------------------------------------

#: map -> (rows, cols), free cells ('.'), blocked cells ('@' + 'T')
MAPS = {
    "mapf/Berlin_1_256.map": ((256, 256), 47540, 17996),
    "mapf/den312d.map": ((81, 65), 2445, 255 + 2565),
    "mapf/empty-32-32.map": ((32, 32), 1024, 0),
    "mapf/maze-32-32-2.map": ((32, 32), 666, 358),
    "mapf/random-32-32-10.map": ((32, 32), 922, 102),
    "mapf/random-32-32-20.map": ((32, 32), 819, 204 + 1),
    "mapf/random-64-64-10.map": ((64, 64), 3687, 409),
    "mapf/room-32-32-4.map": ((32, 32), 682, 342),
    "grid/8room_000.map": ((512, 512), 206642, 54913 + 589),
    "grid/Berlin_0_256.map": ((256, 256), 48147, 17389),
    "grid/arena.map": ((49, 49), 2054, 347),
    "grid/den312d.map": ((81, 65), 2445, 255 + 2565),
    "grid/maze512-1-0.map": ((512, 512), 131071, 131073),
    "grid/random512-10-0.map": ((512, 512), 235900, 26214 + 30),
    "grid/random512-40-0.map": ((512, 512), 104950, 104857 + 52337),
}

#: scenario file -> number of scenarios
SCENARIOS = {
    "mapf/empty-32-32-random-1.scen": 512,
    "mapf/random-32-32-10-random-1.scen": 461,
    "mapf/random-32-32-20-random-1.scen": 409,
    "mapf/maze-32-32-2-random-1.scen": 333,
    "mapf/room-32-32-4-random-1.scen": 341,
    "mapf/random-64-64-10-random-1.scen": 1000,
    "mapf/den312d-random-1.scen": 1000,
    "mapf/Berlin_1_256-random-1.scen": 1000,
    "grid/arena.map.scen": 160,
    "grid/den312d.map.scen": 320,
    "grid/Berlin_0_256.map.scen": 930,
    "grid/random512-10-0.map.scen": 1670,
    "grid/random512-40-0.map.scen": 3060,
    "grid/8room_000.map.scen": 2140,
    "grid/maze512-1-0.map.scen": 12120,
}

#: yaml -> (rows, cols) = (pgm height, pgm width), resolution
ROS_MAPS = {
    "turtlebot3_world/map.yaml": ((384, 384), 0.05),
    "nav2_depot/depot.yaml": ((307, 604), 0.05),
    "lse_arena/lse_arena.yaml": ((60, 80), 0.05),
    "willow_full/willow-full.yaml": ((526, 584), 0.1),
}


def test_bundled_data_is_byte_identical(data):
    """tests/data holds unmodified upstream files (SHA256SUMS, README there)."""
    import hashlib

    lines = (data / "SHA256SUMS").read_text().splitlines()
    listed = {name: digest for digest, name in (line.split("  ", 1) for line in lines)}
    on_disk = {p.relative_to(data).as_posix() for p in data.rglob("*") if p.is_file()}
    assert on_disk - set(listed) == {"README.md", "SHA256SUMS", ".gitattributes"}
    for name, digest in listed.items():
        assert hashlib.sha256((data / name).read_bytes()).hexdigest() == digest, name


def free_corners(occ: np.ndarray) -> tuple[tuple[int, int], tuple[int, int]]:
    """The last and the first free cell in row-major order (start, goal)."""
    free = np.argwhere(~occ)
    return tuple(map(int, free[-1])), tuple(map(int, free[0]))


@pytest.mark.parametrize("name", MAPS)
def test_movingai_maps_cell_counts(data, name):
    shape, n_free, n_blocked = MAPS[name]
    occ = load_occupancy(data_path(f"movingai/{name}"))
    assert occ.shape == shape
    assert int((~occ).sum()) == n_free
    assert int(occ.sum()) == n_blocked


@pytest.mark.parametrize("name", MAPS)
def test_movingai_maps_load_as_workspaces(data, name):
    path = data_path(f"movingai/{name}")
    start, goal = free_corners(load_occupancy(path))
    ws = load_movingai(path, start, goal, corner_cutting=False)
    assert ws.shape == MAPS[name][0]
    assert (ws.start, ws.goal) == (start, goal)
    assert ws.corner_cutting is False
    assert ws.cell_size == 1.0
    assert ws.name == path.stem


def test_berlin_0_has_crlf_and_loads(data):
    path = data_path("movingai/grid/Berlin_0_256.map")
    assert b"\r\n" in path.read_bytes()
    assert load_occupancy(path).shape == (256, 256)


def test_random_32_32_20_tree_is_blocked(data):
    path = data / "movingai/mapf/random-32-32-20.map"
    rows = path.read_text().splitlines()[4:]
    (r,), (c,) = np.nonzero(np.array([list(row) for row in rows]) == "T")
    assert load_occupancy(path)[r, c]


@pytest.mark.parametrize("name", SCENARIOS)
def test_scenario_files(data, name):
    scen_path = data_path(f"movingai/{name}")
    scenarios = load_scenarios(scen_path)
    assert len(scenarios) == SCENARIOS[name]
    assert all(isinstance(s, Scenario) for s in scenarios)
    assert len({s.map for s in scenarios}) == 1
    first = scenarios[0]
    assert "/" not in first.map and first.map.endswith(".map")
    map_path = first.resolve_map()
    assert map_path.parent == scen_path.parent
    occ = load_occupancy(map_path)
    assert all((s.height, s.width) == occ.shape for s in scenarios)
    starts = np.array([s.start for s in scenarios])
    goals = np.array([s.goal for s in scenarios])
    for cells in (starts, goals):
        assert (cells >= 0).all() and (cells < occ.shape).all()
        assert not occ[cells[:, 0], cells[:, 1]].any()
    assert all(s.bucket == math.floor(s.optimal / 4) for s in scenarios)
    assert first.line == 2 and first.source == scen_path


def test_scenario_fields_swap_x_y(data):
    first = load_scenarios(data / "movingai/grid/arena.map.scen")[0]
    # "0\tmaps/dao/arena.map\t49\t49\t1\t11\t1\t12\t1"
    assert first == Scenario(0, "arena.map", 49, 49, (11, 1), (12, 1), 1.0)
    ws = load_movingai(first.resolve_map(), first.start, first.goal, corner_cutting=False)
    assert ws.start == (11, 1)


@pytest.mark.parametrize("name", ROS_MAPS)
def test_ros_maps(data, name):
    shape, resolution = ROS_MAPS[name]
    path = data_path(f"ros/{name}")
    occ = load_occupancy(path)
    assert occ.shape == shape
    start, goal = free_corners(occ)
    ws = load_ros(path, start, goal)
    assert ws.shape == shape
    assert ws.cell_size == resolution
    assert np.array_equal(ws.occ, occ)
    assert load_map(path, start, goal) == ws
    assert load_ros(path, start, goal, cell_size=2.0).cell_size == 2.0


def test_turtlebot3_occupied_pixels_in_both_unknown_modes(data):
    path = data / "ros/turtlebot3_world/map.yaml"
    assert int(load_occupancy(path, unknown="free").sum()) == 870  # value 0
    assert int(load_occupancy(path, unknown="blocked").sum()) == 870 + 138683  # + value 205
    start, goal = free_corners(load_occupancy(path))
    assert load_ros(path, start, goal, unknown="free").n_obstacles == 870


def test_depot_205_is_free_under_its_free_thresh(data):
    path = data / "ros/nav2_depot/depot.yaml"
    for unknown in ("blocked", "free"):
        assert int(load_occupancy(path, unknown=unknown).sum()) == 5947


def test_lse_arena_gimp_comment_and_no_unknown(data):
    yaml_path = data / "ros/lse_arena/lse_arena.yaml"
    assert b"# CREATOR: GIMP" in (data / "ros/lse_arena/lse_arena.pgm").read_bytes()
    assert int(load_occupancy(yaml_path).sum()) == 345
    assert int(load_occupancy(yaml_path, unknown="free").sum()) == 345


def test_willow_grey_levels(data):
    values = np.asarray(Image.open(data_path("ros/willow_full/willow-full.pgm")))
    # p = (255 - v) / 255 > 0.65  <=>  v <= 89;  p < 0.196  <=>  v >= 206
    path = data_path("ros/willow_full/willow-full.yaml")
    assert int(load_occupancy(path, unknown="free").sum()) == int((values <= 89).sum())
    assert int((~load_occupancy(path)).sum()) == int((values >= 206).sum())


def test_image_alone_uses_ros_defaults(data):
    pgm = data / "ros/turtlebot3_world/map.pgm"
    occ = load_occupancy(data / "ros/turtlebot3_world/map.yaml")
    assert np.array_equal(load_occupancy(pgm), occ)
    start, goal = free_corners(occ)
    ws = load_map(pgm, start, goal)
    assert ws.cell_size == 1.0 and ws.name == "map"
    lse = load_occupancy(data / "ros/lse_arena/lse_arena.pgm")
    assert lse.shape == (60, 80) and int(lse.sum()) == 345


def test_ros_default_start_on_unknown_names_the_file(data):
    path = data / "ros/turtlebot3_world/map.yaml"
    with pytest.raises(ConfigError) as exc_info:
        load_map(path)
    assert_error(exc_info, str(path), "start (383, 0)", "obstacle", "start=")


def test_default_workspace():
    ws = default_workspace()
    assert ws.shape == (32, 32)
    assert ws.n_obstacles == 173
    assert (ws.start, ws.goal) == ((31, 0), (0, 31))
    assert ws.corner_cutting is True


# ---------------------------------------------------------------------------
# round trips and small synthetic maps
# ---------------------------------------------------------------------------


@pytest.fixture
def ws() -> Workspace:
    return random_workspace((7, 9), 20, seed=3)


def test_save_movingai_round_trip(tmp_path, ws):
    path = tmp_path / "ws.map"
    save_movingai(ws, path)
    text = path.read_text()
    assert text.startswith("type octile\nheight 7\nwidth 9\nmap\n")
    assert text.count("@") == 20 and "\r" not in text
    again = load_movingai(path, ws.start, ws.goal)
    assert again.corner_cutting is False  # MovingAI's rule, whatever was saved
    assert again == ws.replace(corner_cutting=False)
    assert load_movingai(path, ws.start, ws.goal, corner_cutting=True) == ws
    save_movingai(ws.occ.astype(int), tmp_path / "array.map")
    assert (tmp_path / "array.map").read_text() == text


def test_save_movingai_round_trip_real_map(tmp_path, data):
    source = data / "movingai/mapf/random-32-32-20.map"  # has a 'T'
    ws = load_map(source, (0, 0), (31, 31))
    save_movingai(ws, tmp_path / "copy.map")
    assert load_map(tmp_path / "copy.map", (0, 0), (31, 31)) == ws


def test_save_movingai_unwritable(tmp_path, ws):
    with pytest.raises(MapError) as exc_info:
        save_movingai(ws, tmp_path / "no" / "such" / "dir.map")
    assert_error(exc_info, "dir.map", "cannot write")


def test_movingai_accepts_all_symbols_and_crlf(tmp_path):
    path = write(tmp_path, "sym.map", "type octile\r\nheight 2\r\nwidth 4\r\nmap\r\n.GS@\r\nOTW.\r\n")
    ws = load_movingai(path, (1, 3), (0, 0))
    assert ws.occ.tolist() == [[False, False, False, True], [True, True, True, False]]


def test_text_round_trip(tmp_path, ws):
    path = write(tmp_path, "ws.txt", ws.to_text())
    assert load_text(path) == ws
    assert load_map(path) == ws
    assert load_map(write(tmp_path, "ws.grid", ws.to_text())) == ws


def test_text_marks_symbols_crlf_and_trailing_line(tmp_path):
    path = write(tmp_path, "g.txt", "..G\r\n#@.\r\nS..\r\n\r\n")
    ws = load_text(path)
    assert ws.occ.tolist() == [[False, False, False], [True, True, False], [False, False, False]]
    assert (ws.start, ws.goal) == ((2, 0), (0, 2))
    assert load_text(path, start=(1, 2)).start == (1, 2)  # explicit wins
    plain = write(tmp_path, "p.txt", "...\n.#.\n...\n")
    assert (load_text(plain).start, load_text(plain).goal) == ((2, 0), (0, 2))


@pytest.mark.parametrize(
    "array",
    [
        np.array([[0, 1, 0], [0, 0, 0]], dtype=bool),
        np.array([[0, 1, 0], [0, 0, 0]], dtype=np.int8),
        np.array([[0, 1, 0], [0, 0, 0]], dtype=np.uint64),
        np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 0.0]]),
    ],
)
def test_npy_round_trip(tmp_path, array):
    path = tmp_path / "grid.npy"
    np.save(path, array)
    ws = load_npy(path)
    assert ws.occ.tolist() == [[False, True, False], [False, False, False]]
    assert load_map(path, corner_cutting=False, cell_size=0.5, name="g") == ws.replace(
        corner_cutting=False, cell_size=0.5
    )
    assert from_array(array) == ws


def test_image_orientation_negate_and_png(tmp_path):
    pixels = np.full((3, 4), 254, np.uint8)
    pixels[0, 0] = 0  # top-left black: occupied, grid row 0
    pixels[2, 3] = 205  # unknown
    Image.fromarray(pixels).save(tmp_path / "m.png")
    occ = load_occupancy(tmp_path / "m.png")
    assert occ[0, 0] and occ[2, 3] and occ.sum() == 2
    assert load_occupancy(tmp_path / "m.png", unknown="free").sum() == 1
    write(
        tmp_path,
        "m.yaml",
        "image: m.png\nresolution: 0.5\norigin: [0, 0, 0]\n"
        "negate: 1\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    )
    negated = load_occupancy(tmp_path / "m.yaml")
    assert not negated[0, 0] and negated[2, 3] and negated.sum() == 11  # white is occupied


def test_ros_scale_mode_transparent_pixels_are_unknown(tmp_path):
    rgba = np.zeros((2, 2, 4), np.uint8)
    rgba[..., :3] = 255
    rgba[..., 3] = 255
    rgba[0, 1, 3] = 0  # transparent white
    Image.fromarray(rgba, "RGBA").save(tmp_path / "s.png")
    body = (
        "image: s.png\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    write(tmp_path, "t.yaml", body + "mode: trinary\n")
    write(tmp_path, "s.yaml", body + "mode: scale\n")
    assert load_occupancy(tmp_path / "t.yaml").sum() == 0
    assert load_occupancy(tmp_path / "s.yaml").tolist() == [[False, True], [False, False]]
    assert load_occupancy(tmp_path / "s.yaml", unknown="free").sum() == 0


def test_absolute_image_path(tmp_path):
    Image.fromarray(np.full((2, 3), 254, np.uint8)).save(tmp_path / "a.pgm")
    sub = tmp_path / "sub"
    sub.mkdir()
    write(
        sub,
        "a.yaml",
        f"image: {tmp_path / 'a.pgm'}\nresolution: 0.25\norigin: [1, 2, 0]\n"
        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    )
    ws = load_ros(sub / "a.yaml")
    assert ws.shape == (2, 3) and ws.cell_size == 0.25


def test_workspace_load_goes_through_load_map(tmp_path, ws):
    path = write(tmp_path, "w.txt", ws.to_text())
    assert Workspace.load(path) == ws


# ---------------------------------------------------------------------------
# errors: dispatch and arguments
# ---------------------------------------------------------------------------


def test_unknown_extension(tmp_path):
    path = write(tmp_path, "grid.csv", "0,1\n")
    with pytest.raises(MapError) as exc_info:
        load_map(path)
    assert_error(exc_info, "grid.csv", "'.csv'", ".map", ".yaml", ".txt", ".npy", ".png")


def test_scen_passed_to_load_map_gives_a_hint(tmp_path):
    with pytest.raises(MapError) as exc_info:
        load_map(write(tmp_path, "a.scen", "version 1\n"))
    assert_error(exc_info, "load_scenarios")


@pytest.mark.parametrize("name", ["gone.map", "gone.yaml", "gone.txt", "gone.npy", "gone.png"])
def test_missing_file(tmp_path, name):
    with pytest.raises(MapError) as exc_info:
        load_map(tmp_path / name)
    assert_error(exc_info, name, "not found")


def test_missing_scenario_file(tmp_path):
    with pytest.raises(MapError) as exc_info:
        load_scenarios(tmp_path / "gone.scen")
    assert_error(exc_info, "gone.scen", "not found")


def test_directory_instead_of_file(tmp_path):
    (tmp_path / "dir.map").mkdir()
    with pytest.raises(MapError) as exc_info:
        load_map(tmp_path / "dir.map")
    assert_error(exc_info, "dir.map", "directory")


def test_bad_unknown_policy(tmp_path):
    path = write(tmp_path, "u.txt", "..\n..\n")
    with pytest.raises(ConfigError) as exc_info:
        load_map(path, unknown="maybe")
    assert_error(exc_info, "'maybe'", "'blocked'", "'free'")
    with pytest.raises(ConfigError):
        load_occupancy(path, unknown=None)


def test_workspace_errors_name_the_file(tmp_path):
    path = write(tmp_path, "corner.map", "type octile\nheight 2\nwidth 2\nmap\n..\n@.\n")
    with pytest.raises(ConfigError) as exc_info:
        load_movingai(path)
    assert_error(exc_info, "corner.map", "start (1, 0)", "obstacle")
    with pytest.raises(ConfigError) as exc_info:
        load_movingai(path, (0, 0), (5, 5))
    assert_error(exc_info, "corner.map", "goal (5, 5)", "outside")
    with pytest.raises(ConfigError) as exc_info:
        load_movingai(path, (0, 0), (1, 1), cell_size=-1)
    assert_error(exc_info, "corner.map", "cell_size")


# ---------------------------------------------------------------------------
# errors: MovingAI .map
# ---------------------------------------------------------------------------

GOOD_MAP = "type octile\nheight 3\nwidth 3\nmap\n...\n.@.\n...\n"


@pytest.mark.parametrize(
    "content, fragments",
    [
        ("", ["line 1", "'type <value>'", "end of the file"]),
        ("height 3\nwidth 3\nmap\n...\n", ["line 1", "'type <value>'", "'height 3'"]),
        ("type hex\nheight 3\nwidth 3\nmap\n...\n", ["line 1", "'hex'", "'octile'"]),
        (
            "type octile\nheight three\nwidth 3\nmap\n...\n",
            ["line 2", "height", "'three'", "positive integer"],
        ),
        ("type octile\nheight 0\nwidth 3\nmap\n", ["line 2", "'0'"]),
        ("type octile\nheight 3\nwidth -3\nmap\n", ["line 3", "width", "'-3'"]),
        ("type octile\nheight 3\nwidth 2.5\nmap\n", ["line 3", "'2.5'"]),
        ("type octile\nheight 3\nmap\n...\n", ["line 3", "'width <value>'", "'map'"]),
        ("type octile\nheight 3\nwidth 3\n...\n...\n...\n", ["line 4", "'map'", "'...'"]),
        ("type octile\nheight 3\nwidth 3\n", ["line 4", "'map'", "end of the file"]),
        ("type octile\nheight 3\nwidth 3\nmap\n...\n...\n", ["line 7", "found 2 rows", "expected 3"]),
        ("type octile\nheight 3\nwidth 3\nmap\n", ["line 5", "found 0 rows"]),
        (GOOD_MAP + "...\n", ["line 8", "found 4 rows", "expected 3"]),
        ("type octile\nheight 3\nwidth 3\nmap\n...\n....\n...\n", ["line 6", "4 characters", "expected 3"]),
        ("type octile\nheight 3\nwidth 3\nmap\n...\n\n...\n", ["line 6", "0 characters"]),
        ("type octile\nheight 3\nwidth 3\nmap\n...\n.x.\n...\n", ["line 6, column 2", "'x'", "'@'"]),
        ("type octile\nheight 3\nwidth 3\nmap\n...\n...\n..#\n", ["line 7, column 3", "'#'"]),
    ],
)
def test_movingai_errors(tmp_path, content, fragments):
    path = write(tmp_path, "bad.map", content)
    with pytest.raises(MapError) as exc_info:
        load_movingai(path)
    assert_error(exc_info, "bad.map", *fragments)


def test_movingai_trailing_blank_lines_and_bom_are_fine(tmp_path):
    path = write(tmp_path, "ok.map", "\ufeff" + GOOD_MAP + "\n\n")
    assert load_movingai(path).n_obstacles == 1


def test_binary_file(tmp_path):
    path = write(tmp_path, "bin.map", b"type octile\nheight 1\n\xff\xfe\x00")
    with pytest.raises(MapError) as exc_info:
        load_movingai(path)
    assert_error(exc_info, "bin.map", "line 3", "0xff", "UTF-8")


# ---------------------------------------------------------------------------
# errors: .scen
# ---------------------------------------------------------------------------

SCEN_LINE = "0\tt.map\t3\t2\t0\t1\t2\t0\t2.82842712"


def test_scenario_parsing(tmp_path):
    path = write(tmp_path, "t.scen", f"version 1\r\n{SCEN_LINE}\r\n\r\n1 sub/dir/t.map 3 2 2 0 0 1 2.8\n")
    first, second = load_scenarios(path)
    assert first == Scenario(0, "t.map", 3, 2, (1, 0), (0, 2), 2.82842712)
    assert second.map == "t.map" and second.line == 4 and second.start == (0, 2)
    with pytest.raises(MapError) as exc_info:
        first.resolve_map()
    assert_error(exc_info, "t.scen", "line 2", "'t.map'", "not found")
    write(tmp_path, "t.map", "type octile\nheight 2\nwidth 3\nmap\n...\n...\n")
    assert first.resolve_map() == tmp_path / "t.map"
    assert Scenario(0, "t.map", 3, 2, (1, 0), (0, 2), 1.0).resolve_map(tmp_path).is_file()


@pytest.mark.parametrize(
    "content, fragments",
    [
        ("", ["line 1", "'version 1'", "empty file"]),
        (SCEN_LINE + "\n", ["line 1", "'version 1'"]),
        ("version 2\n", ["line 1", "'version 2'"]),
        ("version 1\n0\tt.map\t3\t2\t0\t1\t2\t0\n", ["line 2", "9 tab-separated", "found 8"]),
        (
            "version 1\n" + SCEN_LINE + "\n" + SCEN_LINE.replace("\t0\t1\t", "\tzero\t1\t", 1) + "\n",
            ["line 3", "column 5 (start x)", "'zero'"],
        ),
        (
            "version 1\n" + SCEN_LINE.replace("\t3\t2\t", "\t0\t2\t") + "\n",
            ["line 2", "column 3 (map width)", "'0'"],
        ),
        ("version 1\n0\tt.map\t3\t2\t0\t1\t2\t-1\t2.8\n", ["line 2", "column 8 (goal y)", "'-1'"]),
        ("version 1\n0\tt.map\t3\t2\t3\t1\t2\t0\t2.8\n", ["line 2", "start (x=3, y=1)", "3x2"]),
        ("version 1\n0\tt.map\t3\t2\t0\t1\t2\t2\t2.8\n", ["line 2", "goal (x=2, y=2)"]),
        ("version 1\n0\tt.map\t3\t2\t0\t1\t2\t0\tfar\n", ["line 2", "column 9", "'far'"]),
        ("version 1\n0\tt.map\t3\t2\t0\t1\t2\t0\tnan\n", ["line 2", "column 9", "'nan'"]),
        ("version 1\n0\tdir/\t3\t2\t0\t1\t2\t0\t2.8\n", ["line 2", "column 2 (map)", "'dir/'"]),
    ],
)
def test_scenario_errors(tmp_path, content, fragments):
    path = write(tmp_path, "bad.scen", content)
    with pytest.raises(MapError) as exc_info:
        load_scenarios(path)
    assert_error(exc_info, "bad.scen", *fragments)


# ---------------------------------------------------------------------------
# errors: ROS yaml + image
# ---------------------------------------------------------------------------

ROS_KEYS = {
    "image": "m.pgm",
    "resolution": 0.05,
    "origin": "[0.0, 0.0, 0.0]",
    "negate": 0,
    "occupied_thresh": 0.65,
    "free_thresh": 0.196,
}


def ros_yaml(tmp_path, **changes) -> Path:
    Image.fromarray(np.full((4, 5), 254, np.uint8)).save(tmp_path / "m.pgm")
    keys = {**ROS_KEYS, **changes}
    body = "".join(f"{k}: {v}\n" for k, v in keys.items() if v is not None)
    return write(tmp_path, "m.yaml", body)


def test_ros_yaml_good(tmp_path):
    ws = load_ros(ros_yaml(tmp_path))
    assert ws.shape == (4, 5) and ws.cell_size == 0.05 and ws.n_obstacles == 0


@pytest.mark.parametrize("key", list(ROS_KEYS))
def test_ros_missing_key(tmp_path, key):
    with pytest.raises(MapError) as exc_info:
        load_ros(ros_yaml(tmp_path, **{key: None}))
    assert_error(exc_info, "m.yaml", f"missing key '{key}'")


@pytest.mark.parametrize(
    "changes, fragments",
    [
        ({"resolution": 0}, ["'resolution'", "metres per cell", "got 0"]),
        ({"resolution": "1.0e-9"}, ["'resolution'", "at least 1e-06", "got 1e-09"]),
        ({"resolution": "fine"}, ["'resolution'", "'fine'"]),
        ({"resolution": "true"}, ["'resolution'", "True"]),
        ({"occupied_thresh": 1.5}, ["'occupied_thresh'", "[0, 1]", "1.5"]),
        ({"free_thresh": "low"}, ["'free_thresh'", "'low'"]),
        ({"free_thresh": 0.7}, ["'free_thresh'", "0.7", "above occupied_thresh 0.65"]),
        ({"negate": 2}, ["'negate'", "0 or 1", "got 2"]),
        ({"origin": "[0, 0]"}, ["'origin'", "[x, y, yaw]", "[0, 0]"]),
        ({"image": '""'}, ["'image'", "''"]),
        ({"image": "nothere.pgm"}, ["key 'image'", "nothere.pgm", "not found"]),
        ({"mode": "raw"}, ["'mode'", "'raw'", "not supported"]),
        ({"mode": "fancy"}, ["'mode'", "'fancy'", "'trinary' or 'scale'"]),
    ],
)
def test_ros_bad_values(tmp_path, changes, fragments):
    with pytest.raises(MapError) as exc_info:
        load_ros(ros_yaml(tmp_path, **changes))
    assert_error(exc_info, "m.yaml", *fragments)


@pytest.mark.parametrize(
    "content, fragments",
    [
        ("image: [unclosed\n", ["invalid YAML", "line"]),
        ("- just\n- a list\n", ["expected a mapping", "['just', 'a list']"]),
        ("", ["expected a mapping", "None"]),
    ],
)
def test_ros_bad_yaml(tmp_path, content, fragments):
    with pytest.raises(MapError) as exc_info:
        load_ros(write(tmp_path, "m.yaml", content))
    assert_error(exc_info, "m.yaml", *fragments)


def test_ros_image_not_an_image(tmp_path):
    path = ros_yaml(tmp_path)
    (tmp_path / "m.pgm").write_bytes(b"P5\n4 5\n255\n\x00\x01")  # truncated pixel data
    with pytest.raises(MapError) as exc_info:
        load_ros(path)
    assert_error(exc_info, "m.yaml", "key 'image'", "m.pgm", "cannot read the image")
    garbage = write(tmp_path, "junk.png", b"this is not a png")
    with pytest.raises(MapError) as exc_info:
        load_map(garbage)
    assert_error(exc_info, "junk.png", "cannot read the image")


def test_16_bit_image_is_rejected(tmp_path):
    Image.fromarray(np.full((2, 2), 40000, np.uint16)).save(tmp_path / "deep.png")
    with pytest.raises(MapError) as exc_info:
        load_image(tmp_path / "deep.png")
    assert_error(exc_info, "deep.png", "mode", "8-bit")


# ---------------------------------------------------------------------------
# errors: text, npy, arrays
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "content, fragments",
    [
        ("", ["empty map"]),
        ("\n\n", ["empty map"]),
        ("...\n..\n...\n", ["line 2", "2 characters", "expected 3"]),
        ("\n...\n", ["line 1", "0 characters"]),
        ("...\n.o.\n", ["line 2, column 2", "'o'", "'#'"]),
        ("S..\n..S\n", ["line 2, column 3", "second 'S'", "row 0, col 0"]),
        ("G.G\n...\n", ["line 1, column 3", "second 'G'"]),
    ],
)
def test_text_errors(tmp_path, content, fragments):
    path = write(tmp_path, "bad.txt", content)
    with pytest.raises(MapError) as exc_info:
        load_text(path)
    assert_error(exc_info, "bad.txt", *fragments)


@pytest.mark.parametrize(
    "array, fragments",
    [
        (np.zeros((2, 2, 2), bool), ["2-D", "(2, 2, 2)"]),
        (np.zeros((0, 3), bool), ["non-empty", "(0, 3)"]),
        (np.array([[0, 2], [0, 0]]), ["value 2", "(row 0, col 1)"]),
        (np.array([[0.0, 0.0], [0.5, 0.0]]), ["value 0.5", "(row 1, col 0)"]),
        (np.array([[0.0, np.nan]]), ["value nan", "(row 0, col 1)"]),
        (np.array([["a", "b"]]), ["dtype <U1"]),
    ],
)
def test_npy_errors(tmp_path, array, fragments):
    path = tmp_path / "bad.npy"
    np.save(path, array)
    with pytest.raises(MapError) as exc_info:
        load_npy(path)
    assert_error(exc_info, "bad.npy", *fragments)
    with pytest.raises(MapError) as exc_info:
        from_array(array)
    assert_error(exc_info, "array", *fragments)


def test_npy_pickled_garbage_and_npz(tmp_path):
    np.save(tmp_path / "obj.npy", np.array([[None, 1]], dtype=object), allow_pickle=True)
    with pytest.raises(MapError) as exc_info:
        load_npy(tmp_path / "obj.npy")
    assert_error(exc_info, "obj.npy", "not a readable .npy")
    with pytest.raises(MapError) as exc_info:
        load_npy(write(tmp_path, "junk.npy", b"not numpy at all"))
    assert_error(exc_info, "junk.npy", "not a readable .npy")
    with pytest.raises(MapError) as exc_info:
        load_npy(write(tmp_path, "empty.npy", b""))
    assert_error(exc_info, "empty.npy", "not a readable .npy")
    with open(tmp_path / "arch.npy", "wb") as f:
        np.savez(f, a=np.zeros((2, 2), bool))
    with pytest.raises(MapError) as exc_info:
        load_npy(tmp_path / "arch.npy")
    assert_error(exc_info, "arch.npy", ".npz")


def test_from_array_lists_and_errors():
    ws = from_array([[0, 0], [1, 0]], start=(1, 1), goal=(0, 0), cell_size=2.0)
    assert ws.n_obstacles == 1 and ws.cell_size == 2.0 and ws.name == "array"
    with pytest.raises(MapError) as exc_info:
        from_array([1, 0, 1])
    assert_error(exc_info, "array", "2-D", "(3,)")
    with pytest.raises(ConfigError) as exc_info:
        from_array([[0, 0], [1, 0]])
    assert_error(exc_info, "array", "start (1, 0)", "obstacle")


# ---------------------------------------------------------------------------
# the corner rule of each source, and the world frame of ROS maps
# ---------------------------------------------------------------------------


def test_corner_rule_follows_the_source(tmp_path, data):
    from gapath.loaders import CORNER_RULES, corner_rule

    grid = np.zeros((3, 4), bool)
    np.save(tmp_path / "g.npy", grid)
    save_movingai(grid, tmp_path / "g.map")
    write(tmp_path, "g.txt", "....\n....\n....\n")
    Image.fromarray(np.full((3, 4), 254, np.uint8)).save(tmp_path / "g.png")
    write(
        tmp_path,
        "g.yaml",
        "image: g.png\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n",
    )
    expected = {"g.map": False, "g.yaml": False, "g.png": False, "g.txt": True, "g.npy": True}
    for name, rule in expected.items():
        path = tmp_path / name
        assert load_map(path).corner_cutting is rule, name
        assert corner_rule(name)[0] is rule
        for override in (True, False):
            assert load_map(path, corner_cutting=override).corner_cutting is override
    assert load_movingai(tmp_path / "g.map").corner_cutting is False
    assert load_ros(tmp_path / "g.yaml").corner_cutting is False
    assert load_image(tmp_path / "g.png").corner_cutting is False
    assert load_text(tmp_path / "g.txt").corner_cutting is True
    assert load_npy(tmp_path / "g.npy").corner_cutting is True
    assert from_array(grid).corner_cutting is True
    assert default_workspace().corner_cutting is True  # stored as a .map, SPEC's rule
    assert CORNER_RULES["movingai"] is False and CORNER_RULES["text"] is True
    real = data / "movingai/mapf/random-32-32-20.map"
    start, goal = free_corners(load_occupancy(real))
    assert load_map(real, start, goal).corner_cutting is False
    with pytest.raises(MapError, match="unknown map extension"):
        corner_rule("g.bmp")


def test_ros_maps_have_a_world_frame_others_do_not(tmp_path, data):
    from gapath.loaders import map_frame

    path = data / "ros/turtlebot3_world/map.yaml"
    frame = map_frame(path)
    assert (frame.x, frame.y, frame.yaw, frame.resolution) == (-10.0, -10.0, 0.0, 0.05)
    assert (frame.height, frame.width) == (384, 384)
    start, goal = free_corners(load_occupancy(path))
    ws = load_ros(path, start, goal)
    assert ws.frame == frame and ws.replace(name="x").frame == frame
    assert ws.frame.extent() == pytest.approx((-10.0, -10.0, 9.2, 9.2))
    # the world origin (0, 0) is 10 m right of and 10 m above the lower-left corner
    assert frame.to_cell(0.0, 0.0) == (383 - 200, 200)
    with pytest.raises(ConfigError, match="outside the map"):
        frame.to_cell(-10.01, 0.0)
    assert map_frame(data / "movingai/grid/arena.map") is None
    assert load_map(data / "ros/turtlebot3_world/map.pgm", start, goal).frame is None
    assert default_workspace().frame is None
