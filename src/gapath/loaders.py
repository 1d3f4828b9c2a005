"""Read grid maps from files and arrays into :class:`~gapath.workspace.Workspace`.

Formats (``load_map`` picks one by the file extension):

===================  ==========================================================
``.map``             MovingAI benchmark map (:func:`load_movingai`)
``.yaml`` ``.yml``   ROS map_server description + image (:func:`load_ros`)
``.pgm`` ``.png``    occupancy image alone, ROS defaults (:func:`load_image`)
``.txt`` ``.grid``   plain text grid (:func:`load_text`)
``.npy``             NumPy boolean (or 0/1) array (:func:`load_npy`)
===================  ==========================================================

MovingAI scenario files (``.scen``) are read by :func:`load_scenarios`, and
:func:`from_array` wraps an in-memory array. :func:`load_occupancy` returns the
bare obstacle array of any map file, which helps to choose a start and a goal
before building the workspace.

Choices shared by every loader
------------------------------
* Row 0 is the top row of the file or image (SPEC), ``occ[r, c]`` is True for
  an obstacle, cells are ``(row, col)``; MovingAI's ``(x, y)`` is ``(col, row)``.
* ``start`` and ``goal`` default as in :class:`Workspace` (bottom-left,
  top-right); a text grid may mark them with ``S`` and ``G`` instead.
* ``corner_cutting=None`` (every loader's default) means the rule of the
  map's source (SPEC, :data:`CORNER_RULES`): a MovingAI ``.map``, a ROS
  map_server map and an occupancy image follow ``corner_cutting=False`` (a
  diagonal move needs both orthogonal neighbours free: the optimal lengths of
  MovingAI ``.scen`` files assume it, and a robot cannot pass between two
  diagonal obstacles); text grids, ``.npy`` files and arrays keep
  ``corner_cutting=True`` (Ahmed & Deb's grids). True or False overrides.
* A ROS map keeps its world frame (:class:`MapFrame`, ``workspace.frame``:
  origin and resolution from the yaml); other formats have none
  (``workspace.frame is None``).
* ``cell_size`` defaults to 1.0, except for ROS maps, where it is the yaml
  ``resolution`` (metres per cell). An explicit ``cell_size`` always wins.
* ``unknown`` says what to do with the unknown cells of an occupancy image:
  ``"blocked"`` (default: a planner must not drive through unexplored space)
  or ``"free"``. It is accepted by every loader so that all of them share one
  signature, and has no effect on formats without unknown cells.
* Every error a user can cause is a :class:`~gapath.errors.MapError` (bad file
  or array) or :class:`~gapath.errors.ConfigError` (bad argument, or a start /
  goal that does not fit the map) whose message names the file, the line and
  column where it applies, the value found and what was expected.
"""

from __future__ import annotations

import io
import math
import re
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import yaml
from PIL import Image

from gapath.errors import ConfigError, MapError
from gapath.workspace import MIN_CELL_SIZE, MapFrame, Workspace

__all__ = [
    "CORNER_RULES",
    "MapFrame",
    "Scenario",
    "corner_rule",
    "from_array",
    "load_image",
    "load_map",
    "load_movingai",
    "load_npy",
    "load_occupancy",
    "load_ros",
    "load_scenarios",
    "load_text",
    "map_frame",
    "save_movingai",
]

#: Policies for the unknown cells of occupancy images.
UNKNOWN_POLICIES = ("blocked", "free")

#: map_server defaults, used for an image loaded without a yaml file.
ROS_DEFAULTS = dict(negate=False, occupied_thresh=0.65, free_thresh=0.196)

#: The corner rule of each map source when ``corner_cutting`` is not given
#: (SPEC): ``False`` = a diagonal move needs both orthogonal neighbours free.
CORNER_RULES = {
    "movingai": False,  # MovingAI's rule: its .scen optima assume it
    "ros": False,  # a robot cannot pass between two diagonal obstacles
    "image": False,  # an occupancy image is a robot map (map_server defaults)
    "text": True,  # SPEC's default (Ahmed & Deb's grids)
    "npy": True,
    "array": True,
}

_SOURCE_LABELS = {
    "movingai": "MovingAI .map",
    "ros": "ROS map_server map",
    "image": "occupancy image",
    "text": "text grid",
    "npy": ".npy array",
    "array": "array",
}


def corner_rule(source: str) -> tuple[bool, str]:
    """The default corner rule of a map source and a phrase naming it.

    Parameters
    ----------
    source : str
        A key of :data:`CORNER_RULES`, or a map file name (its extension
        decides, as in :func:`load_map`).

    Returns
    -------
    (bool, str)
        ``corner_cutting`` and e.g. ``"the rule of a MovingAI .map"``.

    Raises
    ------
    MapError
        On an unknown extension.

    Examples
    --------
    >>> corner_rule("arena.map")
    (False, 'the rule of a MovingAI .map')
    >>> corner_rule("grid.txt")[0]
    True
    """
    key = source if source in CORNER_RULES else _SOURCES[_reader_for(Path(source))]
    return CORNER_RULES[key], f"the rule of a {_SOURCE_LABELS[key]}"


# ---------------------------------------------------------------------------
# errors and file access
# ---------------------------------------------------------------------------


def _map_error(source, message: str, line: int | None = None, column: int | None = None) -> MapError:
    """A MapError reading ``<source>[, line L][, column C]: <message>``."""
    where = str(source)
    if line is not None:
        where += f", line {line}"
    if column is not None:
        where += f", column {column}"
    return MapError(f"{where}: {message}")


def _read_bytes(path: Path) -> bytes:
    try:
        return path.read_bytes()
    except FileNotFoundError:
        raise _map_error(path, "file not found") from None
    except IsADirectoryError:
        raise _map_error(path, "is a directory, expected a map file") from None
    except OSError as exc:
        raise _map_error(path, f"cannot read the file ({exc.strerror or exc})") from None


def _text_lines(path: Path) -> list[str]:
    """The lines of a UTF-8 text file, trailing whitespace (``\\r`` of CRLF
    files included) removed, trailing empty lines dropped."""
    data = _read_bytes(path)
    try:
        text = data.decode("utf-8").removeprefix("\ufeff")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise _map_error(
            path, f"byte 0x{data[exc.start]:02x} is not UTF-8 text (is this a binary file?)", line
        ) from None
    lines = [line.rstrip() for line in text.split("\n")]
    while lines and not lines[-1]:
        lines.pop()
    return lines


def _parse_int(text: str, source, line: int, what: str, minimum: int) -> int:
    if not re.fullmatch(r"[+-]?[0-9]+", text) or int(text) < minimum:
        kind = "a positive" if minimum == 1 else "a non-negative"
        raise _map_error(source, f"{what}: expected {kind} integer, got {text!r}", line)
    return int(text)


# ---------------------------------------------------------------------------
# the parsed grid and the workspace built from it
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class _Grid:
    """What a map file holds before it becomes a Workspace."""

    blocked: np.ndarray
    unknown: np.ndarray | None = None  # cells neither free nor blocked (images)
    cell_size: float | None = None  # from the file (ROS resolution)
    start: tuple[int, int] | None = None  # marked in the file (text S)
    goal: tuple[int, int] | None = None  # marked in the file (text G)
    corner_cutting: bool = True  # the source's rule (CORNER_RULES)
    frame: MapFrame | None = None  # world frame (ROS maps)

    def occupancy(self, policy: str) -> np.ndarray:
        """Obstacles, unknown cells included when ``policy`` is "blocked"."""
        if self.unknown is None or policy == "free":
            return self.blocked
        return self.blocked | self.unknown


def _check_unknown(unknown) -> None:
    if unknown not in UNKNOWN_POLICIES:
        raise ConfigError(f"unknown must be 'blocked' or 'free', got {unknown!r}")


def _workspace(occ, source, start, goal, *, corner_cutting, cell_size, name, frame=None) -> Workspace:
    """Build the Workspace, naming ``source`` in its errors."""
    try:
        return Workspace(
            occ, start, goal, cell_size=cell_size, corner_cutting=corner_cutting, name=name, frame=frame
        )
    except (ConfigError, MapError) as exc:
        message = str(exc)
        defaulted = [
            label
            for label, cell in (("start", start), ("goal", goal))
            if cell is None and message.startswith(f"{label} (")
        ]
        if defaulted and "obstacle" in message:
            message += (
                f" (the default {defaulted[0]}, the {'bottom-left' if defaulted[0] == 'start' else 'top-right'} "
                f"cell; choose a free cell with --{defaulted[0]} ROW,COL, or "
                f"{defaulted[0]}=(row, col) in Python)"
            )
        raise type(exc)(f"{source}: {message}") from None


def _load(reader, path, start, goal, *, corner_cutting, cell_size, unknown, name) -> Workspace:
    """Read ``path`` with ``reader`` and build the workspace; the body of
    every file loader."""
    _check_unknown(unknown)
    path = Path(path)
    grid = reader(path)
    return _workspace(
        grid.occupancy(unknown),
        path,
        grid.start if start is None else start,
        grid.goal if goal is None else goal,
        corner_cutting=grid.corner_cutting if corner_cutting is None else corner_cutting,
        cell_size=cell_size if cell_size is not None else (grid.cell_size or 1.0),
        name=path.stem if name is None else name,
        frame=grid.frame,
    )


# ---------------------------------------------------------------------------
# character grids (MovingAI and text)
# ---------------------------------------------------------------------------

_FREE, _BLOCKED, _START, _GOAL, _BAD = range(5)
_MOVINGAI_LEGEND = {
    ".": _FREE,
    "G": _FREE,
    "S": _FREE,
    "@": _BLOCKED,
    "O": _BLOCKED,
    "T": _BLOCKED,
    "W": _BLOCKED,
}
_TEXT_LEGEND = {".": _FREE, "#": _BLOCKED, "@": _BLOCKED, "S": _START, "G": _GOAL}


def _check_row_lengths(rows: list[str], source, first_line: int, width: int, expected: str) -> None:
    for i, row in enumerate(rows):
        if len(row) != width or not row:
            raise _map_error(
                source, f"row has {len(row)} characters, expected {width} ({expected})", first_line + i
            )


def _classify(rows: list[str], source, first_line: int, legend: dict) -> np.ndarray:
    """Code of every character of equal-length ``rows`` (as an (H, W) array)."""
    chars = np.frombuffer("".join(rows).encode("utf-32-le"), dtype="<u4")
    lut = np.full(128, _BAD, np.uint8)
    for char, code in legend.items():
        lut[ord(char)] = code
    codes = np.where(chars < 128, lut[np.minimum(chars, 127)], _BAD)
    codes = codes.reshape(len(rows), len(rows[0]))
    bad = np.argwhere(codes == _BAD)
    if len(bad):
        r, c = bad[0]
        allowed = ", ".join(repr(ch) for ch in legend)
        raise _map_error(
            source, f"unknown character {rows[r][c]!r}, expected one of {allowed}", first_line + r, c + 1
        )
    return codes


def _mark(codes: np.ndarray, code: int, char: str, source, first_line: int):
    """The single cell marked ``char`` in a text grid, or None."""
    cells = np.argwhere(codes == code)
    if len(cells) > 1:
        r, c = cells[1]
        raise _map_error(
            source,
            f"second {char!r} mark (the first is at row {cells[0][0]}, "
            f"col {cells[0][1]}); expected at most one",
            first_line + r,
            c + 1,
        )
    return (int(cells[0][0]), int(cells[0][1])) if len(cells) else None


# ---------------------------------------------------------------------------
# MovingAI .map
# ---------------------------------------------------------------------------


def _header_value(lines: list[str], index: int, key: str, source) -> str:
    found = lines[index] if index < len(lines) else None
    parts = found.split() if found is not None else []
    if len(parts) != 2 or parts[0].lower() != key:
        got = "the end of the file" if found is None else repr(found)
        raise _map_error(source, f"expected header line '{key} <value>', got {got}", index + 1)
    return parts[1]


def _read_movingai(path: Path) -> _Grid:
    lines = _text_lines(path)
    kind = _header_value(lines, 0, "type", path)
    if kind != "octile":
        raise _map_error(path, f"map type {kind!r} is not supported, expected 'octile'", 1)
    height = _parse_int(_header_value(lines, 1, "height", path), path, 2, "height", 1)
    width = _parse_int(_header_value(lines, 2, "width", path), path, 3, "width", 1)
    if len(lines) < 4 or lines[3].strip() != "map":
        got = repr(lines[3]) if len(lines) > 3 else "the end of the file"
        raise _map_error(path, f"expected header line 'map', got {got}", 4)
    rows = lines[4:]
    _check_row_lengths(rows[:height], path, 5, width, "width on line 3")
    if len(rows) != height:
        where = 5 + min(len(rows), height)
        raise _map_error(path, f"found {len(rows)} rows, expected {height} (height on line 2)", where)
    codes = _classify(rows, path, 5, _MOVINGAI_LEGEND)
    return _Grid(blocked=codes == _BLOCKED, corner_cutting=CORNER_RULES["movingai"])


def load_movingai(
    path, start=None, goal=None, *, corner_cutting=None, cell_size=None, unknown="blocked", name=None
) -> Workspace:
    """Load a MovingAI benchmark ``.map`` file.

    The file has the header lines ``type octile``, ``height H``, ``width W``,
    ``map``, then ``H`` rows of exactly ``W`` characters: ``.`` ``G`` ``S``
    are free, ``@`` ``O`` ``T`` ``W`` blocked. CRLF line ends are accepted.

    Parameters
    ----------
    path : str or path-like
    start, goal : (row, col), optional
        Default bottom-left and top-right, as in :class:`Workspace`.
    corner_cutting : bool, optional
        Default False, MovingAI's rule (a diagonal move needs both orthogonal
        neighbours free), which the optimal lengths of ``.scen`` files
        assume; True allows diagonal moves past blocked corners.
    cell_size : float, optional
        Default 1.0.
    unknown : {"blocked", "free"}
        Accepted for a uniform signature; a ``.map`` has no unknown cells.
    name : str, optional
        Default: the file name without extension.

    Returns
    -------
    Workspace

    Raises
    ------
    MapError
        If the file is missing or malformed (garbled header, non-positive
        size, wrong number of rows, ragged row, unknown character); the
        message names the file, the 1-based line (and column) and the value.
    ConfigError
        If start or goal is off the grid or on an obstacle.

    Examples
    --------
    >>> ws = load_movingai("empty-32-32.map")                 # doctest: +SKIP
    >>> ws.shape, ws.n_obstacles                              # doctest: +SKIP
    ((32, 32), 0)
    """
    return _load(
        _read_movingai,
        path,
        start,
        goal,
        corner_cutting=corner_cutting,
        cell_size=cell_size,
        unknown=unknown,
        name=name,
    )


def save_movingai(workspace, path) -> None:
    """Write a workspace (or a 2-D boolean array) as a MovingAI ``.map`` file.

    Obstacles are written ``@``, free cells ``.``, with LF line ends. The
    format has no start, goal or cell size, so those are not saved.

    Parameters
    ----------
    workspace : Workspace or (H, W) bool / 0-1 array
    path : str or path-like

    Raises
    ------
    MapError
        If the array is not a 2-D boolean (0/1) grid or the file cannot be
        written.

    Examples
    --------
    >>> save_movingai(Workspace(np.zeros((2, 3), bool)), "tiny.map")  # doctest: +SKIP
    >>> print(open("tiny.map").read(), end="")                         # doctest: +SKIP
    type octile
    height 2
    width 3
    map
    ...
    ...
    """
    path = Path(path)
    occ = workspace.occ if isinstance(workspace, Workspace) else _check_array(workspace, "array")
    h, w = occ.shape
    rows = ["".join("@" if v else "." for v in row) for row in occ]
    text = "\n".join(["type octile", f"height {h}", f"width {w}", "map", *rows]) + "\n"
    try:
        path.write_text(text, encoding="ascii", newline="\n")
    except OSError as exc:
        raise _map_error(path, f"cannot write the file ({exc.strerror or exc})") from None


# ---------------------------------------------------------------------------
# MovingAI .scen
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Scenario:
    """One line of a MovingAI ``.scen`` file.

    Attributes
    ----------
    bucket : int
        ``floor(optimal / 4)`` in the benchmark files.
    map : str
        Basename of the map file (directories of older files stripped).
    width, height : int
        Map size stated by the scenario.
    start, goal : (row, col)
        MovingAI ``(x, y)`` swapped into SPEC order ``(y, x)``.
    optimal : float
        Shortest 8-connected length **without corner cutting** (the default
        rule of a MovingAI ``.map``, so load the map without
        ``corner_cutting`` to compare).
    source : Path
        The ``.scen`` file; ``line`` its 1-based line number.
    """

    bucket: int
    map: str
    width: int
    height: int
    start: tuple[int, int]
    goal: tuple[int, int]
    optimal: float
    source: Path | None = field(default=None, compare=False, repr=False)
    line: int | None = field(default=None, compare=False, repr=False)

    def resolve_map(self, folder=None) -> Path:
        """Path of the map file: ``map`` looked up in ``folder`` (default: the
        folder of the ``.scen`` file).

        Raises
        ------
        MapError
            If no such file exists; names the scenario file and line.

        Examples
        --------
        >>> sc = load_scenarios("arena.map.scen")[0]                   # doctest: +SKIP
        >>> ws = load_movingai(sc.resolve_map(), sc.start, sc.goal)  # doctest: +SKIP
        """
        if folder is None:
            folder = Path(self.source).parent if self.source is not None else Path(".")
        candidate = Path(folder) / self.map
        if not candidate.is_file():
            raise _map_error(self.source or "scenario", f"map {self.map!r} not found in {folder}", self.line)
        return candidate


_SCEN_COLUMNS = (
    "bucket",
    "map",
    "map width",
    "map height",
    "start x",
    "start y",
    "goal x",
    "goal y",
    "optimal length",
)


def _parse_scenario(text: str, source: Path, line: int) -> Scenario:
    fields = text.split("\t")
    if len(fields) != len(_SCEN_COLUMNS):
        fields = text.split()  # tolerate space-separated copies
    if len(fields) != len(_SCEN_COLUMNS):
        raise _map_error(
            source,
            f"expected 9 tab-separated columns ({', '.join(_SCEN_COLUMNS)}), found {len(fields)} in {text!r}",
            line,
        )
    fields = [f.strip() for f in fields]

    def integer(i, minimum=0):
        return _parse_int(fields[i], source, line, f"column {i + 1} ({_SCEN_COLUMNS[i]})", minimum)

    bucket, width, height = integer(0), integer(2, 1), integer(3, 1)
    map_name = re.split(r"[\\/]", fields[1])[-1]
    if not map_name:
        raise _map_error(source, f"column 2 (map): expected a map file name, got {fields[1]!r}", line)
    start, goal = (integer(5), integer(4)), (integer(7), integer(6))
    for label, (r, c) in (("start", start), ("goal", goal)):
        if r >= height or c >= width:
            raise _map_error(source, f"{label} (x={c}, y={r}) is outside the {width}x{height} map", line)
    try:
        optimal = float(fields[8])
    except ValueError:
        optimal = math.nan
    if not (math.isfinite(optimal) and optimal >= 0):
        raise _map_error(
            source, f"column 9 (optimal length): expected a non-negative number, got {fields[8]!r}", line
        )
    return Scenario(bucket, map_name, width, height, start, goal, optimal, source, line)


def load_scenarios(path) -> list[Scenario]:
    """Read a MovingAI ``.scen`` scenario file.

    The first line is ``version 1``; every further non-empty line has 9
    tab-separated columns: bucket, map, map width, map height, start x,
    start y, goal x, goal y, optimal length.

    Parameters
    ----------
    path : str or path-like

    Returns
    -------
    list of Scenario
        In file order; ``start``/``goal`` are ``(row, col) = (y, x)``.

    Raises
    ------
    MapError
        If the file is missing, lacks the version line, or a line is
        malformed (wrong column count, bad number, start/goal outside the
        stated size); the message names the file, line and value.

    Examples
    --------
    >>> scens = load_scenarios("empty-32-32-random-1.scen")   # doctest: +SKIP
    >>> len(scens), scens[0].map                              # doctest: +SKIP
    (512, 'empty-32-32.map')
    """
    path = Path(path)
    lines = _text_lines(path)
    header = lines[0].split() if lines else []
    if len(header) != 2 or header[0] != "version" or header[1] not in ("1", "1.0"):
        got = repr(lines[0]) if lines else "an empty file"
        raise _map_error(path, f"expected the header line 'version 1', got {got}", 1)
    return [
        _parse_scenario(text, path, number) for number, text in enumerate(lines[1:], start=2) if text.strip()
    ]


# ---------------------------------------------------------------------------
# plain text and NumPy
# ---------------------------------------------------------------------------


def _read_text(path: Path) -> _Grid:
    rows = _text_lines(path)
    if not rows:
        raise _map_error(path, "empty map, expected rows of '.' (free) and '#' or '@' (blocked)")
    _check_row_lengths(rows, path, 1, len(rows[0]), "the length of line 1")
    codes = _classify(rows, path, 1, _TEXT_LEGEND)
    return _Grid(
        blocked=codes == _BLOCKED,
        corner_cutting=CORNER_RULES["text"],
        start=_mark(codes, _START, "S", path, 1),
        goal=_mark(codes, _GOAL, "G", path, 1),
    )


def load_text(
    path, start=None, goal=None, *, corner_cutting=None, cell_size=None, unknown="blocked", name=None
) -> Workspace:
    """Load a plain text grid.

    One line per row: ``.`` free, ``#`` or ``@`` blocked, optionally one
    ``S`` (start) and one ``G`` (goal) on free cells. The marks are used
    when ``start``/``goal`` are not given. CRLF and trailing empty lines are
    accepted. :meth:`Workspace.to_text` writes this format.

    Parameters
    ----------
    path : str or path-like
    start, goal : (row, col), optional
        Default: the ``S``/``G`` marks, else bottom-left / top-right.
    corner_cutting : bool, optional
        Default True (SPEC's default for text grids); False for MovingAI's
        rule.
    cell_size, unknown, name
        As in :func:`load_movingai`.

    Returns
    -------
    Workspace

    Raises
    ------
    MapError
        On an empty map, ragged rows, an unknown character or a repeated
        mark (message: file, line, column, value).
    ConfigError
        If start or goal is off the grid or on an obstacle.

    Examples
    --------
    >>> Path("tiny.txt").write_text("..G\\n.#.\\nS..\\n")        # doctest: +SKIP
    >>> load_text("tiny.txt").n_obstacles                       # doctest: +SKIP
    1
    """
    return _load(
        _read_text,
        path,
        start,
        goal,
        corner_cutting=corner_cutting,
        cell_size=cell_size,
        unknown=unknown,
        name=name,
    )


def _check_array(array, source) -> np.ndarray:
    """``array`` as an (H, W) bool array, or MapError naming ``source``."""
    arr = np.asarray(array)
    if arr.ndim != 2 or arr.size == 0:
        raise _map_error(source, f"expected a non-empty 2-D array, got shape {arr.shape}")
    if arr.dtype == np.bool_:
        return arr
    if not (np.issubdtype(arr.dtype, np.integer) or np.issubdtype(arr.dtype, np.floating)):
        raise _map_error(source, f"expected a boolean or 0/1 array, got dtype {arr.dtype}")
    bad = np.argwhere((arr != 0) & (arr != 1))  # NaN included
    if len(bad):
        r, c = bad[0]
        raise _map_error(
            source, f"value {arr[r, c].item()!r} at (row {r}, col {c}); expected a boolean or 0/1 array"
        )
    return arr.astype(bool)


def _read_npy(path: Path) -> _Grid:
    try:
        with io.BytesIO(_read_bytes(path)) as buffer:
            array = np.load(buffer, allow_pickle=False)
    except (ValueError, OSError, EOFError) as exc:
        raise _map_error(path, f"not a readable .npy array ({exc})") from None
    if not isinstance(array, np.ndarray):
        raise _map_error(path, "is an .npz archive, expected a single .npy array")
    return _Grid(blocked=_check_array(array, path), corner_cutting=CORNER_RULES["npy"])


def load_npy(
    path, start=None, goal=None, *, corner_cutting=None, cell_size=None, unknown="blocked", name=None
) -> Workspace:
    """Load a NumPy ``.npy`` occupancy array (True/1 = obstacle).

    Read with ``allow_pickle=False``. The array must be 2-D, boolean or
    integer/float holding only 0 and 1.

    Parameters
    ----------
    path : str or path-like
    corner_cutting : bool, optional
        Default True (SPEC's default for arrays); False for MovingAI's rule.
    start, goal, cell_size, unknown, name
        As in :func:`load_movingai`.

    Returns
    -------
    Workspace

    Raises
    ------
    MapError
        If the file is missing or not an ``.npy`` array, or the array has the
        wrong shape, dtype, or a value other than 0/1 (named with its cell).
    ConfigError
        If start or goal is off the grid or on an obstacle.

    Examples
    --------
    >>> np.save("grid.npy", np.zeros((4, 4), bool))   # doctest: +SKIP
    >>> load_npy("grid.npy").shape                    # doctest: +SKIP
    (4, 4)
    """
    return _load(
        _read_npy,
        path,
        start,
        goal,
        corner_cutting=corner_cutting,
        cell_size=cell_size,
        unknown=unknown,
        name=name,
    )


def from_array(
    array, start=None, goal=None, *, corner_cutting=None, cell_size=1.0, name="array"
) -> Workspace:
    """A workspace from an (H, W) array, True/1 for obstacles.

    Like :class:`Workspace`, with the array checked first so that the error
    names the first bad value.

    Parameters
    ----------
    array : (H, W) array-like of bool, or of integers / floats 0 and 1
    corner_cutting : bool, optional
        Default True (SPEC's default for arrays).
    start, goal, cell_size, name
        As in :class:`Workspace`.

    Returns
    -------
    Workspace

    Raises
    ------
    MapError
        If the array is not 2-D, empty, of another dtype, or holds a value
        other than 0/1 (the message gives the value and its cell).
    ConfigError
        If start or goal is off the grid or on an obstacle.

    Examples
    --------
    >>> from_array([[0, 0], [1, 0]], start=(1, 1), goal=(0, 0)).n_obstacles
    1
    """
    if corner_cutting is None:
        corner_cutting = CORNER_RULES["array"]
    return _workspace(
        _check_array(array, "array"),
        "array",
        start,
        goal,
        corner_cutting=corner_cutting,
        cell_size=cell_size,
        name=name,
    )


# ---------------------------------------------------------------------------
# occupancy images and ROS map_server
# ---------------------------------------------------------------------------

_IMAGE_MODES = ("1", "L", "LA", "P", "PA", "RGB", "RGBA")


def _read_image(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """8-bit grey levels (ITU-R 601 luma, as ``Image.convert("L")``) and
    alpha (255 where the image has no alpha channel) of an image file."""
    data = _read_bytes(path)
    try:
        with Image.open(io.BytesIO(data)) as img:
            img.load()
            mode = img.mode
            la = img.convert("LA") if mode in _IMAGE_MODES else None
    except (OSError, ValueError, SyntaxError, Image.DecompressionBombError) as exc:
        raise _map_error(path, f"cannot read the image ({exc})") from None
    if la is None:
        raise _map_error(
            path,
            f"image mode {mode!r} is not supported, expected an 8-bit grey or colour image (PGM P5 / PNG)",
        )
    pixels = np.asarray(la)
    return pixels[..., 0], pixels[..., 1]


def _threshold(
    grey: np.ndarray,
    alpha: np.ndarray,
    *,
    negate: bool,
    occupied_thresh: float,
    free_thresh: float,
    mode: str = "trinary",
) -> _Grid:
    """map_server's rule: occupancy ``p = (255 - v) / 255`` (``v / 255`` when
    negated) is occupied above ``occupied_thresh``, free below
    ``free_thresh``, unknown otherwise. In ``scale`` mode non-opaque pixels
    are unknown as well; the graded costs ROS gives the pixels between the
    thresholds cannot be kept in a binary grid, so those stay unknown."""
    value = grey.astype(np.float64)
    p = value / 255.0 if negate else (255.0 - value) / 255.0
    blocked = p > occupied_thresh
    unknown = ~blocked & ~(p < free_thresh)
    if mode == "scale":
        transparent = alpha < 255
        blocked &= ~transparent
        unknown |= transparent
    return _Grid(blocked=blocked, unknown=unknown)


def _read_plain_image(path: Path) -> _Grid:
    grey, alpha = _read_image(path)
    grid = _threshold(
        grey,
        alpha,
        negate=bool(ROS_DEFAULTS["negate"]),
        occupied_thresh=float(ROS_DEFAULTS["occupied_thresh"]),
        free_thresh=float(ROS_DEFAULTS["free_thresh"]),
    )
    return replace(grid, corner_cutting=CORNER_RULES["image"])


def load_image(
    path, start=None, goal=None, *, corner_cutting=None, cell_size=None, unknown="blocked", name=None
) -> Workspace:
    """Load an occupancy image (``.pgm``, ``.png``) with map_server defaults.

    Same thresholding as :func:`load_ros` with ``negate: 0``,
    ``occupied_thresh: 0.65``, ``free_thresh: 0.196``, trinary mode and a
    resolution of 1 (``cell_size`` 1.0): black is occupied, white free, the
    ROS grey 205 unknown.

    Parameters
    ----------
    path : str or path-like
    corner_cutting : bool, optional
        Default False, as a ROS map (a robot cannot pass between two
        diagonal obstacles).
    start, goal, cell_size, name
        As in :func:`load_movingai`.
    unknown : {"blocked", "free"}, default "blocked"
        What the unknown (grey) pixels become.

    Returns
    -------
    Workspace

    Raises
    ------
    MapError
        If the file is missing or not a readable 8-bit image.
    ConfigError
        On a bad ``unknown``; if start or goal is off the grid or on an
        obstacle (on a mostly unknown map pass them explicitly).

    Examples
    --------
    >>> load_image("map.pgm", start=(200, 160), goal=(170, 220)).shape  # doctest: +SKIP
    (384, 384)
    """
    return _load(
        _read_plain_image,
        path,
        start,
        goal,
        corner_cutting=corner_cutting,
        cell_size=cell_size,
        unknown=unknown,
        name=name,
    )


def _yaml_mapping(path: Path) -> dict:
    try:
        meta = yaml.safe_load(_read_bytes(path))
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        problem = getattr(exc, "problem", None) or exc
        raise _map_error(
            path, f"invalid YAML ({problem})", mark.line + 1 if mark is not None else None
        ) from None
    if not isinstance(meta, dict):
        raise _map_error(
            path,
            "expected a mapping with the map_server keys image, resolution, "
            f"origin, negate, occupied_thresh, free_thresh; got {meta!r}",
        )
    return meta


def _yaml_value(meta: dict, key: str, path: Path, expected: str, valid):
    """``meta[key]`` if ``valid(value)``, else MapError naming file and key."""
    if key not in meta:
        raise _map_error(path, f"missing key {key!r} ({expected})")
    value = meta[key]
    if not valid(value):
        raise _map_error(path, f"key {key!r}: expected {expected}, got {value!r}")
    return value


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _read_ros(path: Path) -> _Grid:
    meta = _yaml_mapping(path)
    mode = meta.get("mode", "trinary")
    if mode == "raw":
        raise _map_error(
            path,
            "key 'mode': 'raw' stores occupancy values, not grey levels, and "
            "is not supported; use 'trinary' or 'scale'",
        )
    if mode not in ("trinary", "scale"):
        raise _map_error(path, f"key 'mode': expected 'trinary' or 'scale', got {mode!r}")
    image = _yaml_value(
        meta, "image", path, "the image file name", lambda v: isinstance(v, str) and v.strip()
    )
    resolution = _yaml_value(
        meta,
        "resolution",
        path,
        f"a number of metres per cell, at least {MIN_CELL_SIZE:g} (gapath's least cell size)",
        lambda v: _is_number(v) and v >= MIN_CELL_SIZE,
    )
    origin = _yaml_value(
        meta,
        "origin",
        path,
        "[x, y, yaw]",
        lambda v: isinstance(v, list) and len(v) == 3 and all(map(_is_number, v)),
    )
    negate = _yaml_value(meta, "negate", path, "0 or 1", lambda v: v in (0, 1))
    thresholds = {
        key: _yaml_value(meta, key, path, "a number in [0, 1]", lambda v: _is_number(v) and 0 <= v <= 1)
        for key in ("occupied_thresh", "free_thresh")
    }
    if thresholds["free_thresh"] > thresholds["occupied_thresh"]:
        raise _map_error(
            path,
            f"key 'free_thresh': {thresholds['free_thresh']!r} is above "
            f"occupied_thresh {thresholds['occupied_thresh']!r}",
        )
    try:
        grey, alpha = _read_image(path.parent / image.strip())
    except MapError as exc:
        raise _map_error(path, f"key 'image': {exc}") from None
    grid = _threshold(grey, alpha, negate=bool(negate), mode=mode, **thresholds)
    h, w = grey.shape
    x, y, yaw = (float(v) for v in origin)
    frame = MapFrame(x, y, yaw, float(resolution), int(h), int(w))
    return replace(grid, cell_size=float(resolution), corner_cutting=CORNER_RULES["ros"], frame=frame)


def load_ros(
    yaml_path, start=None, goal=None, *, corner_cutting=None, cell_size=None, unknown="blocked", name=None
) -> Workspace:
    """Load a ROS map_server map (``.yaml`` description + image).

    Required keys, as map_server reads them: ``image`` (relative to the yaml
    file, or absolute), ``resolution`` (metres per pixel, becomes
    ``cell_size``), ``origin`` (with the resolution, the workspace's
    :class:`MapFrame`, ``workspace.frame``), ``negate``, ``occupied_thresh``, ``free_thresh``; optional
    ``mode`` ``trinary`` (default) or ``scale``. A pixel of grey level ``v``
    has occupancy ``p = (255 - v) / 255`` (``v / 255`` with ``negate: 1``):
    occupied if ``p > occupied_thresh``, free if ``p < free_thresh``,
    unknown otherwise. In ``scale`` mode, non-opaque pixels are unknown and
    the graded pixels between the thresholds are treated as unknown too.
    ``raw`` mode is rejected. Image row 0 (the top) is grid row 0.

    Parameters
    ----------
    yaml_path : str or path-like
    start, goal : (row, col), optional
        Default bottom-left / top-right; on a mostly unknown map these are
        usually blocked, so pass them explicitly
        (:meth:`MapFrame.to_cell` turns metres into cells).
    corner_cutting : bool, optional
        Default False: a robot cannot pass between two diagonal obstacles.
    cell_size : float, optional
        Default: the yaml ``resolution`` (the frame keeps the resolution).
    unknown : {"blocked", "free"}, default "blocked"
        What unknown cells become; blocked keeps a planner out of unexplored
        space.
    name : str, optional
        Default: the yaml file name without extension.

    Returns
    -------
    Workspace

    Raises
    ------
    MapError
        If the yaml is missing, invalid, lacks a key or has a bad value (the
        message names the file and key), or the image cannot be read.
    ConfigError
        On a bad ``unknown``; if start or goal is off the grid or on an
        obstacle.

    Examples
    --------
    >>> ws = load_ros("lse_arena.yaml", start=(50, 10), goal=(10, 70))  # doctest: +SKIP
    >>> ws.shape, ws.cell_size, ws.corner_cutting                       # doctest: +SKIP
    ((60, 80), 0.05, False)
    >>> ws.frame.to_world([ws.start]).round(3).tolist()                # doctest: +SKIP
    [[0.525, 0.475]]
    """
    return _load(
        _read_ros,
        yaml_path,
        start,
        goal,
        corner_cutting=corner_cutting,
        cell_size=cell_size,
        unknown=unknown,
        name=name,
    )


# ---------------------------------------------------------------------------
# dispatch
# ---------------------------------------------------------------------------

_READERS = {
    ".map": _read_movingai,
    ".yaml": _read_ros,
    ".yml": _read_ros,
    ".pgm": _read_plain_image,
    ".png": _read_plain_image,
    ".txt": _read_text,
    ".grid": _read_text,
    ".npy": _read_npy,
}


_SOURCES = {
    _read_movingai: "movingai",
    _read_ros: "ros",
    _read_plain_image: "image",
    _read_text: "text",
    _read_npy: "npy",
}


def _reader_for(path: Path):
    reader = _READERS.get(path.suffix.lower())
    if reader is None:
        hint = "; scenario files are read with load_scenarios" if path.suffix.lower() == ".scen" else ""
        raise _map_error(
            path, f"unknown map extension {path.suffix!r}, expected one of {', '.join(_READERS)}{hint}"
        )
    return reader


def load_map(
    path, start=None, goal=None, *, corner_cutting=None, cell_size=None, unknown="blocked", name=None
) -> Workspace:
    """Load a map file, the format chosen by its extension.

    ``.map`` MovingAI (:func:`load_movingai`), ``.yaml``/``.yml`` ROS
    map_server (:func:`load_ros`), ``.pgm``/``.png`` image with map_server
    defaults (:func:`load_image`), ``.txt``/``.grid`` plain text
    (:func:`load_text`), ``.npy`` NumPy array (:func:`load_npy`).

    Parameters
    ----------
    path : str or path-like
    start, goal : (row, col), optional
        Default bottom-left / top-right (text grids: their ``S``/``G``).
    corner_cutting : bool, optional
        Default: the rule of the map's source (:data:`CORNER_RULES`): False
        for MovingAI ``.map``, ROS ``.yaml`` and images, True for text grids
        and ``.npy``. True or False overrides it.
    cell_size : float, optional
        Default 1.0; for ROS maps the yaml ``resolution``.
    unknown : {"blocked", "free"}, default "blocked"
        What the unknown cells of occupancy images become.
    name : str, optional
        Default: the file name without extension.

    Returns
    -------
    Workspace

    Raises
    ------
    MapError
        On an unknown extension, a missing file or a malformed map; the
        message names the file (and line, key or value).
    ConfigError
        On a bad argument, or a start/goal off the grid or on an obstacle;
        the message names the file.

    Examples
    --------
    >>> ws = load_map("random-32-32-20.map", (31, 31), (0, 0))  # doctest: +SKIP
    >>> ws.shape, ws.corner_cutting                              # doctest: +SKIP
    ((32, 32), False)
    """
    path = Path(path)
    return _load(
        _reader_for(path),
        path,
        start,
        goal,
        corner_cutting=corner_cutting,
        cell_size=cell_size,
        unknown=unknown,
        name=name,
    )


def load_occupancy(path, *, unknown="blocked") -> np.ndarray:
    """The (H, W) obstacle array of a map file, without building a workspace.

    Useful to pick a start and a goal on a map whose corners are blocked.

    Parameters
    ----------
    path : str or path-like
        Any format :func:`load_map` reads.
    unknown : {"blocked", "free"}, default "blocked"

    Returns
    -------
    (H, W) bool array, True for obstacles.

    Raises
    ------
    MapError, ConfigError
        As :func:`load_map`.

    Examples
    --------
    >>> occ = load_occupancy("den312d.map")   # doctest: +SKIP
    >>> occ.shape                             # doctest: +SKIP
    (81, 65)
    """
    _check_unknown(unknown)
    path = Path(path)
    return _reader_for(path)(path).occupancy(unknown)


def map_frame(path) -> MapFrame | None:
    """The world frame of a map file: a :class:`MapFrame` for a ROS
    ``.yaml``, None for the other formats (they have no world frame).

    Raises
    ------
    MapError, ConfigError
        As :func:`load_map`.

    Examples
    --------
    >>> map_frame("lse_arena.yaml").resolution     # doctest: +SKIP
    0.05
    >>> map_frame("arena.map") is None             # doctest: +SKIP
    True
    """
    path = Path(path)
    reader = _reader_for(path)
    return reader(path).frame if reader is _read_ros else None
