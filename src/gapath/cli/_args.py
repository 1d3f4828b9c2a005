"""The map arguments of the ``gapath`` commands, in one place.

``gapath solve``, ``gapath exact`` and ``gapath plan`` take the same way of
naming a map, its start and goal and its corner rule
(:func:`add_map_arguments`), read by :func:`load_workspace`:

``MAP``
    A map file (``.map``, ``.yaml``, ``.txt``, ``.grid``, ``.npy``, ``.pgm``,
    ``.png``) or ``default`` (the bundled 32x32 scenario). Optional with
    ``--scen``.
``--start ROW,COL`` / ``--goal ROW,COL``
    Cells; row 0 is the top row of the file or image.
``--start-xy X,Y`` / ``--goal-xy X,Y``
    Metres in the map frame of a ROS map (origin and resolution from its
    yaml; y grows *up* the image, rows grow down it).
``--scen FILE:INDEX``
    Start and goal from scenario ``INDEX`` of a MovingAI ``.scen`` file,
    counted from 0 in file order (the scenario on line ``INDEX + 2``). The map
    is ``MAP`` when given, otherwise the line's map name (its basename)
    looked up next to the ``.scen`` file. The corner rule is MovingAI's (no
    corner cutting) and the scenario's optimal length is reported beside the
    result.
``--corner-cutting`` / ``--no-corner-cutting``
    Override the rule of the map's source: by default a MovingAI ``.map``, a
    ROS map and an occupancy image forbid corner cutting, text grids,
    ``.npy`` files and the bundled scenario allow it
    (:data:`gapath.loaders.CORNER_RULES`).

The costmap flags (Lavin's cost layers and user layers) are shared the same
way by ``gapath solve``, ``gapath exact`` and ``gapath plan``
(:func:`add_costmap_arguments`, read by :func:`costmap_from_args`). The
objectives name the layers; a flag sets how a layer is built:

``--dem FILE`` / ``--dem-method bilinear|reflect`` / ``--terrain-seed N``
    The ``elevation`` layer: a DEM raster (``.npy``/``.npz``) resampled to
    the grid, or seeded fractal terrain (seed 1 by default); normalised to
    [0, 1].
``--risk ROW,COL``
    The ``risk`` layer's maximum-risk cell (default: the grid's centre; an
    obstacle cell is allowed, a hazard may sit in one).
``--solar-rate RAD``
    The ``solar`` layer's rotation of the solar vector per step (0.01).
``--layer NAME=FILE``
    A user layer: a ``.npy``/``.npz`` array of the grid's shape, finite and
    non-negative, used as given (repeat the flag for several).

Which objective names a command takes (:func:`layer_objectives`): the GA
(``solve``) the means ``elevation``, ``risk``, ``NAME``, the worst cells
``<layer>_max`` and ``solar``; the exact search (``exact --mode free``) the
sums ``<layer>_sum`` and ``solar``; the planners (``plan --layers``) the
layers themselves. A flag whose layer no objective uses is an error.
"""

from __future__ import annotations

import argparse
import json
import math
import re
from dataclasses import dataclass
from pathlib import Path

from gapath.errors import ConfigError
from gapath.workspace import Workspace

#: The tolerance a length must meet to match a MovingAI optimum (the
#: ``.scen`` files print 6 significant digits or 8 decimals).
SCEN_RTOL = 1e-5


def cell(text: str) -> tuple[int, int]:
    """``"ROW,COL"`` as a cell (an argparse ``type``).

    Examples
    --------
    >>> cell("3,14")
    (3, 14)
    """
    try:
        r, c = (int(v) for v in str(text).split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected ROW,COL (two integers), got {text!r}") from None
    return r, c


def point(text: str) -> tuple[float, float]:
    """``"X,Y"`` as a point in metres (an argparse ``type``).

    Examples
    --------
    >>> point("-2.5,0.5")
    (-2.5, 0.5)
    """
    try:
        x, y = (float(v) for v in str(text).split(","))
    except ValueError:
        x = y = math.nan
    if not (math.isfinite(x) and math.isfinite(y)):
        raise argparse.ArgumentTypeError(f"expected X,Y (two numbers, metres), got {text!r}")
    return x, y


def scen_ref(text: str) -> tuple[Path, int]:
    """``"FILE:INDEX"`` as a (path, index) pair (an argparse ``type``).

    Examples
    --------
    >>> scen_ref("maps/arena.map.scen:7")
    (PosixPath('maps/arena.map.scen'), 7)
    """
    name, sep, index = str(text).rpartition(":")
    if not sep or not name or not index.isdigit():
        raise argparse.ArgumentTypeError(
            f"expected FILE:INDEX (a .scen file and a scenario index from 0), got {text!r}"
        )
    return Path(name), int(index)


def add_corner_arguments(parser) -> None:
    """``--corner-cutting`` / ``--no-corner-cutting`` (default: the map's rule)."""
    cc = parser.add_mutually_exclusive_group()
    cc.add_argument(
        "--corner-cutting",
        dest="corner_cutting",
        action="store_true",
        default=None,
        help="allow diagonal moves past blocked corners (default for text grids, "
        ".npy and the bundled scenario)",
    )
    cc.add_argument(
        "--no-corner-cutting",
        dest="corner_cutting",
        action="store_false",
        help="a diagonal move needs both orthogonal neighbours free (MovingAI's "
        "rule; default for MovingAI .map, ROS maps and images)",
    )


#: What argparse takes for a negative number: also "X,Y" pairs such as
#: "-2,-0.5", so that ``--start-xy -2,-0.5`` works without ``=``.
_NEGATIVE = re.compile(r"^-\d+$|^-\d*\.\d+$|^-?\d*\.?\d+(e-?\d+)?,-?\d*\.?\d+(e-?\d+)?$")


def add_map_arguments(parser, *, what: str = "map") -> None:
    """``MAP``, ``--start``/``--goal``, ``--start-xy``/``--goal-xy``,
    ``--scen`` and the corner rule (see the module docstring)."""
    if hasattr(parser, "_negative_number_matcher"):  # argparse has no public hook
        parser._negative_number_matcher = _NEGATIVE
    parser.add_argument(
        "map",
        nargs="?",
        default=None,
        metavar="MAP",
        help=f"{what} file (.map, .yaml, .txt, .grid, .npy, .pgm, .png) or "
        "'default' for the bundled 32x32 scenario; optional with --scen",
    )
    parser.add_argument(
        "--start",
        type=cell,
        metavar="ROW,COL",
        help="start cell, row 0 at the top (default: bottom-left; a text grid's S)",
    )
    parser.add_argument(
        "--goal", type=cell, metavar="ROW,COL", help="goal cell (default: top-right; a text grid's G)"
    )
    parser.add_argument(
        "--start-xy",
        type=point,
        metavar="X,Y",
        help="start in metres in the map frame of a ROS map (origin and "
        "resolution from its yaml; y grows up the image)",
    )
    parser.add_argument(
        "--goal-xy", type=point, metavar="X,Y", help="goal in metres in the map frame of a ROS map"
    )
    parser.add_argument(
        "--scen",
        type=scen_ref,
        metavar="FILE:INDEX",
        help="start and goal of scenario INDEX (from 0) of a MovingAI .scen file, "
        "with MovingAI's corner rule; the map is MAP or, without MAP, the "
        "scenario's map next to the .scen file; its optimal length is "
        "reported beside the result",
    )
    add_corner_arguments(parser)


def matches_optimum(length, optimal) -> bool:
    """True if ``length`` matches a MovingAI optimum:
    ``abs(length - optimal) <= 1e-5 * max(1, optimal)``.

    Examples
    --------
    >>> matches_optimum(1003.2004, 1003.2), matches_optimum(10.1, 10.0)
    (True, False)
    """
    if length is None or not math.isfinite(length):
        return False
    return abs(length - optimal) <= SCEN_RTOL * max(1.0, optimal)


@dataclass(eq=False)
class MapChoice:
    """A workspace with how its corner rule and start/goal were chosen.

    Attributes
    ----------
    workspace : Workspace
    corner_source : str
        Why the corner rule is what it is (``"the rule of a MovingAI .map"``,
        ``"--corner-cutting"``, ...).
    scenario : Scenario or None
        The ``--scen`` line; ``scen_file``, ``scen_index`` name it.
    """

    workspace: Workspace
    corner_source: str
    scenario: object = None
    scen_file: Path | None = None
    scen_index: int | None = None

    def corner_line(self) -> str:
        """The report line of the corner rule."""
        if self.workspace.corner_cutting:
            return f"corner cutting: allowed ({self.corner_source}; --no-corner-cutting forbids it)"
        return (
            f"corner cutting: not allowed, a diagonal move needs both orthogonal "
            f"neighbours free ({self.corner_source}; --corner-cutting allows it)"
        )

    def settings(self) -> dict:
        """Entries for ``summary.json``'s settings: the corner rule, where it
        comes from, and the world frame (ROS maps)."""
        ws = self.workspace
        out = {"corner_cutting": ws.corner_cutting, "corner_rule": self.corner_source}
        frame = getattr(ws, "frame", None)
        if frame is not None:
            out["frame"] = frame.to_json()
            out["start_xy"], out["goal_xy"] = (
                [round(float(v), 6) for v in p] for p in frame.to_world([ws.start, ws.goal])
            )
        return out

    def scenario_record(self, length) -> dict | None:
        """``summary.json``'s ``scenario`` entry: the line, its optimum, the
        length found and whether they match; None without ``--scen``."""
        sc = self.scenario
        if sc is None:
            return None
        found = None if length is None else float(length)
        return {
            "file": str(self.scen_file),
            "index": self.scen_index,
            "line": sc.line,
            "map": sc.map,
            "start": list(sc.start),
            "goal": list(sc.goal),
            "optimal": sc.optimal,
            "length": found,
            "matches": None if found is None else matches_optimum(found, sc.optimal),
            "rule": "no corner cutting",
            "tolerance": "abs(length - optimal) <= 1e-5 * max(1, optimal)",
        }

    def scenario_line(self, length, what: str = "length") -> str | None:
        """The report line comparing ``length`` with the scenario's optimum."""
        sc = self.scenario
        if sc is None:
            return None
        head = (
            f"scenario {self.scen_file}:{self.scen_index} (line {sc.line}): MovingAI optimum {sc.optimal:.8g}"
        )
        if length is None:
            return head + f"; no {what} to compare"
        verdict = (
            "matches" if matches_optimum(length, sc.optimal) else f"differs by {length - sc.optimal:+.6g}"
        )
        note = "" if not self.workspace.corner_cutting else " (the optimum assumes no corner cutting)"
        return head + f", {what} {length:.8g}: {verdict}{note}"


def _scenario(args):
    from gapath.loaders import load_scenarios

    path, index = args.scen
    scens = load_scenarios(path)
    if not scens:
        raise ConfigError(f"--scen {path}:{index}: the file holds no scenario")
    if index >= len(scens):
        raise ConfigError(
            f"--scen {path}:{index}: the file holds {len(scens)} scenarios, "
            f"expected an index 0..{len(scens) - 1}"
        )
    return scens[index]


def _xy_cells(args, map_arg):
    """``--start-xy`` / ``--goal-xy`` as cells (None where not given)."""
    from gapath.loaders import map_frame

    wanted = [
        (flag, xy)
        for flag, xy in (("--start-xy", args.start_xy), ("--goal-xy", args.goal_xy))
        if xy is not None
    ]
    if not wanted:
        return None, None
    frame = None if map_arg == "default" else map_frame(map_arg)
    if frame is None:
        raise ConfigError(
            f"{wanted[0][0]} needs a map with a world frame (a ROS map_server "
            f".yaml); {map_arg} has none: give --{wanted[0][0][2:-3]} ROW,COL"
        )
    cells = {flag: frame.to_cell(*xy, name=f"{flag} (metres in the map frame)") for flag, xy in wanted}
    return cells.get("--start-xy"), cells.get("--goal-xy")


def load_workspace(args) -> MapChoice:
    """The workspace the map arguments of ``args`` name.

    Raises
    ------
    ConfigError
        On missing or conflicting arguments (no MAP and no ``--scen``,
        ``--start`` with ``--start-xy`` or ``--scen``, metres on a map
        without a world frame, a point outside the map, a scenario index out
        of range or a map whose size differs from the scenario's).
    MapError
        On a bad map or scenario file.
    """
    from gapath.generators import default_workspace
    from gapath.loaders import corner_rule, load_map

    map_arg = args.map
    start, goal = args.start, args.goal
    scen = getattr(args, "scen", None)
    for flag, cell_value, xy in (
        ("start", start, getattr(args, "start_xy", None)),
        ("goal", goal, getattr(args, "goal_xy", None)),
    ):
        if cell_value is not None and xy is not None:
            raise ConfigError(f"--{flag} and --{flag}-xy both give the {flag}; keep one")
        if scen is not None and (cell_value is not None or xy is not None):
            raise ConfigError(
                f"--scen gives the start and the goal; drop --{flag}"
                + ("" if cell_value is not None else "-xy")
            )
    scenario = None
    if scen is not None:
        scenario = _scenario(args)
        if map_arg is None:
            map_arg = str(scenario.resolve_map())
        start, goal = scenario.start, scenario.goal
    elif map_arg is None:
        raise ConfigError("a MAP is needed (a map file or 'default'), or --scen FILE:INDEX")
    if getattr(args, "start_xy", None) is not None or getattr(args, "goal_xy", None) is not None:
        sxy, gxy = _xy_cells(args, map_arg)
        start = sxy if sxy is not None else start
        goal = gxy if gxy is not None else goal
    cc = args.corner_cutting
    if cc is not None:
        source = "--corner-cutting" if cc else "--no-corner-cutting"
    elif scenario is not None:
        cc, source = False, "MovingAI's rule, which the .scen optima assume"
    elif map_arg == "default":
        source = "the rule of the bundled scenario (SPEC)"
    else:
        source = corner_rule(map_arg)[1]
    if map_arg == "default":
        ws = default_workspace()
        changes = {k: v for k, v in (("start", start), ("goal", goal)) if v is not None}
        if cc is not None:
            changes["corner_cutting"] = cc
        ws = ws.replace(**changes) if changes else ws
    else:
        ws = load_map(map_arg, start=start, goal=goal, **({} if cc is None else {"corner_cutting": cc}))
    if scenario is not None and ws.shape != (scenario.height, scenario.width):
        raise ConfigError(
            f"--scen {args.scen[0]}:{args.scen[1]} is for a {scenario.width}x"
            f"{scenario.height} map ({scenario.map}, width x height), but "
            f"{map_arg} is {ws.shape[1]}x{ws.shape[0]}"
        )
    return MapChoice(ws, source, scenario, *(args.scen if scen is not None else (None, None)))


def shortest_in_csv(path) -> float | None:
    """The smallest ``length`` of a ``front.csv`` (None without a length
    column or rows)."""
    import csv

    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError:
        return None
    if not rows or "length" not in rows[0] or len(rows) < 2:
        return None
    j = rows[0].index("length")
    return min(float(r[j]) for r in rows[1:])


def update_summary(out_dir, entries: dict, settings: dict | None = None) -> None:
    """Add ``entries`` (and ``settings`` entries) to ``out_dir/summary.json``,
    if the command wrote one."""
    from gapath.results import atomic_write, dumps

    path = Path(out_dir) / "summary.json"
    try:
        summary = json.loads(path.read_text())
    except (OSError, ValueError):
        return
    summary.update({k: v for k, v in entries.items() if v is not None})
    if settings:
        summary.setdefault("settings", {}).update(settings)
    atomic_write(path, dumps(summary, indent=1, sort_keys=True) + "\n")


# ---------------------------------------------------------------------------
# the costmap flags
# ---------------------------------------------------------------------------


def layer_objectives(objectives, user_layers=(), *, kind: str = "ga", flag: str = "--objectives") -> tuple:
    """The costmap layers that objective names need
    (:func:`gapath.costmap.layer_objectives`, with messages naming ``flag``
    and ``--layer NAME=FILE``).

    Examples
    --------
    >>> layer_objectives(["length", "risk_max", "solar"])
    ('solar', 'risk')
    """
    from gapath.costmap import layer_objectives as check

    return check(objectives, user_layers, kind=kind, flag=flag)


def layer_file(text: str) -> tuple[str, Path]:
    """``"NAME=FILE"`` as a user layer's (name, path) (an argparse ``type``).

    The name is checked by :func:`gapath.costmap.check_layer_name`: it
    starts with a letter (then letters, digits, ``_``, ``-``), is not a
    built-in name and does not end in ``_max`` or ``_sum``.

    Examples
    --------
    >>> layer_file("slope=maps/slope.npy")
    ('slope', PosixPath('maps/slope.npy'))
    >>> layer_file("risk=r.npy")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: layer name 'risk' is built in (--risk ROW,COL sets it); choose another name for a user layer
    """
    name, sep, file = str(text).partition("=")
    name = name.strip()
    if not sep or not name or not file:
        raise argparse.ArgumentTypeError(
            f"expected NAME=FILE (a layer name and a .npy/.npz file), got {text!r}"
        )
    from gapath.costmap import check_layer_name

    try:
        check_layer_name(name)
    except ConfigError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return name, Path(file)


def add_costmap_arguments(parser) -> None:
    """``--dem``, ``--dem-method``, ``--terrain-seed``, ``--risk``,
    ``--solar-rate`` and ``--layer NAME=FILE`` (see the module docstring).

    Every default is ``None`` in the parsed namespace (so that a flag given
    without its layer can be told apart); :data:`COSTMAP_DEFAULTS` gives the
    values used.

    Examples
    --------
    >>> p = argparse.ArgumentParser()
    >>> add_costmap_arguments(p)
    >>> a = p.parse_args(["--risk", "3,4", "--layer", "slope=s.npy"])
    >>> a.risk, a.layer, a.terrain_seed
    ((3, 4), [('slope', PosixPath('s.npy'))], None)
    """
    g = parser.add_argument_group(
        "costmap layers",
        "the layers that the objectives name (elevation, risk, solar, a --layer NAME; "
        "NAME_max: the worst cell, for the GA; NAME_sum: the sum, for gapath exact); "
        "each flag sets how its layer is built, and is refused when no objective uses it",
    )
    g.add_argument(
        "--dem",
        metavar="FILE",
        help="elevation layer: raster (.npy or .npz) resampled to the grid; default: seeded fractal terrain",
    )
    g.add_argument(
        "--dem-method",
        choices=("bilinear", "reflect"),
        default=None,
        help="bilinear: stretch the DEM over the grid; reflect: one pixel per cell, "
        "tiled with reflection (default: bilinear)",
    )
    g.add_argument(
        "--terrain-seed",
        type=int,
        default=None,
        metavar="N",
        help="seed of the fractal terrain when no --dem is given (default: 1)",
    )
    g.add_argument(
        "--risk",
        type=cell,
        metavar="ROW,COL",
        help="risk layer: the maximum-risk cell (default: the centre of the grid)",
    )
    g.add_argument(
        "--solar-rate",
        type=float,
        default=None,
        metavar="RAD",
        help="solar layer: rotation of the solar vector per path step, radians (default: 0.01)",
    )
    g.add_argument(
        "--layer",
        type=layer_file,
        action="append",
        metavar="NAME=FILE",
        help="a user layer NAME from a .npy/.npz array of the grid's shape (finite, >= 0, "
        "used as given), for the objective NAME (NAME_max, NAME_sum); repeat for several",
    )


def settings_from_args(args):
    """The :class:`gapath.costmap.CostmapSettings` of the parsed costmap
    flags (missing ones count as not given).

    Returns
    -------
    CostmapSettings

    Examples
    --------
    >>> settings_from_args(argparse.Namespace(risk=(1, 2))).risk
    (1, 2)
    """
    from gapath.costmap import CostmapSettings

    dem = getattr(args, "dem", None)
    return CostmapSettings(
        dem=None if dem is None else Path(dem),
        dem_method=getattr(args, "dem_method", None),
        terrain_seed=getattr(args, "terrain_seed", None),
        risk=getattr(args, "risk", None),
        solar_rate=getattr(args, "solar_rate", None),
        layers=tuple(getattr(args, "layer", None) or ()),
    )


def costmap_from_args(args, workspace, objectives, *, kind: str = "ga", flag: str = "--objectives"):
    """The costmap the parsed costmap flags (:func:`add_costmap_arguments`)
    build for ``objectives`` on ``workspace``, or None when no objective is
    a layer: :func:`gapath.costmap.costmap_from_settings` of
    :func:`settings_from_args`, with messages naming the flags.

    Parameters
    ----------
    args : argparse.Namespace
        With the costmap flags (missing ones count as not given).
    workspace : Workspace
    objectives : sequence of str
        The objective names (see :func:`layer_objectives` for ``kind``).
    kind : {"ga", "exact", "plan"}
    flag : str
        The flag of the objective names, for messages.

    Returns
    -------
    Costmap or None
        Holding every layer the objectives need, and only those.

    Raises
    ------
    ConfigError
        One message naming the flag and value (see
        :func:`gapath.costmap.costmap_from_settings`).

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> ws = Workspace(np.zeros((5, 6), bool))
    >>> args = argparse.Namespace(risk=(1, 2), solar_rate=0.5)
    >>> cm = costmap_from_args(args, ws, ["length", "risk_max", "solar"])
    >>> cm.risk_cells, cm.solar_rate, cm.names
    ([(1, 2)], 0.5, ('distance', 'heuristic', 'solar', 'risk'))
    >>> costmap_from_args(argparse.Namespace(), ws, ["length", "vulnerability"]) is None
    True
    >>> costmap_from_args(args, ws, ["length", "solar"])
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: --risk sets the risk layer, which no objective uses: add risk (or risk_max) to --objectives
    """
    from gapath.costmap import SettingNames, costmap_from_settings

    return costmap_from_settings(
        settings_from_args(args), workspace, objectives, kind=kind, names=SettingNames(flag)
    )


def costmap_settings(args, costmap, objectives, *, kind: str = "ga") -> dict | None:
    """``summary.json``'s ``settings.costmap``
    (:func:`gapath.costmap.costmap_record` of the flags); None without a
    costmap.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> ws = Workspace(np.zeros((5, 6), bool))
    >>> args = argparse.Namespace(terrain_seed=3)
    >>> cm = costmap_from_args(args, ws, ["length", "elevation"])
    >>> s = costmap_settings(args, cm, ["length", "elevation"])
    >>> s["layers"], s["elevation"]
    (['elevation'], {'source': 'fractal terrain', 'terrain_seed': 3, 'hurst': 0.8})
    """
    from gapath.costmap import costmap_record

    return costmap_record(settings_from_args(args), costmap, objectives, kind=kind)
