"""The grid workspace: occupancy, start, goal, cell size, corner rule, potential.

Conventions (``SPEC.md``): ``occ[r, c]`` is True for an obstacle; row 0 is the
top row; cells are named ``(row, col)``; the default start is the bottom-left
cell ``(H-1, 0)`` and the default goal the top-right cell ``(0, W-1)``. The
move rules are :mod:`gapath.grid`'s; workspaces made by recipe are in
:mod:`gapath.generators`, from map files in :mod:`gapath.loaders`.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numba
import numpy as np
from numpy.typing import ArrayLike

from gapath.errors import ConfigError, MapError
from gapath.grid import check_cell

#: Variance of the Gaussian potential of one obstacle, in cell units squared.
POTENTIAL_S2 = 0.5
#: Half width of the square window over which the potential is summed.
POTENTIAL_RADIUS = 5


def read_only(array: ArrayLike, dtype: Any = None) -> np.ndarray:
    """``array`` as a C-contiguous, read-only array (a read-only view when it
    is already C-contiguous and of ``dtype``; the caller's array is never
    frozen).

    The map arrays that reach a numba kernel (occupancy, potential, layer
    costs) are read-only everywhere, as a :class:`Workspace`'s own are:
    numba compiles one specialization per set of array flags, so a writable
    copy (a mirrored frame, an unpickled workspace, a layer given by the
    user) would otherwise compile the kernel, and every kernel it calls, a
    second time.

    Examples
    --------
    >>> a = np.zeros((2, 3))
    >>> b = read_only(a[:, ::-1])
    >>> b.flags.writeable, b.flags.c_contiguous, a.flags.writeable
    (False, True, True)
    """
    out = np.ascontiguousarray(array, dtype=dtype)
    if out.flags.writeable:
        out = out.view()
        out.flags.writeable = False
    return out


@numba.njit(cache=True)
def _potential_kernel(occ, s2, radius):
    h, w = occ.shape
    weight = np.empty((2 * radius + 1, 2 * radius + 1))
    for i in range(-radius, radius + 1):
        for j in range(-radius, radius + 1):
            weight[i + radius, j + radius] = np.exp(-(i * i + j * j) / (2.0 * s2))
    pot = np.zeros((h, w))
    for r in range(h):
        for c in range(w):
            acc = 0.0
            for i in range(max(0, r - radius), min(h, r + radius + 1)):
                for j in range(max(0, c - radius), min(w, c + radius + 1)):
                    if occ[i, j]:
                        acc += weight[i - r + radius, j - c + radius]
            pot[r, c] = acc
    return pot


def potential_field(occ: np.ndarray, s2: float = POTENTIAL_S2, radius: int = POTENTIAL_RADIUS) -> np.ndarray:
    """Potential ``P(c) = sum_o exp(-|c - o|^2 / (2 s2))`` of every cell.

    The sum runs over the obstacle cells ``o`` in the square window
    ``|dr| <= radius, |dc| <= radius`` around ``c`` (SPEC: each dropped term is
    below 3e-16 for the default ``radius=5``).

    Parameters
    ----------
    occ : (H, W) bool array, True for obstacles.
    s2 : variance in cell units squared (default 0.5).
    radius : half width of the summation window (default 5).

    Returns
    -------
    (H, W) float64 array.

    Examples
    --------
    >>> occ = np.zeros((3, 3), bool); occ[1, 1] = True
    >>> float(potential_field(occ)[1, 1])
    1.0
    """
    return _potential_kernel(read_only(occ, np.bool_), float(s2), int(radius))


@dataclass(frozen=True)
class MapFrame:
    """Where the cells of a ROS map lie in its world frame (metres).

    map_server's convention: ``origin = (x, y, yaw)`` is the pose of the
    lower-left corner of the map (the corner of the *last* image row's first
    pixel, since image row 0 is the top), ``resolution`` metres per cell; x
    grows along the image columns and y *up* the image (towards row 0),
    rotated by ``yaw`` about the origin.

    Attributes
    ----------
    x, y, yaw : float
        The yaml ``origin``.
    resolution : float
        Metres per cell.
    height, width : int
        Rows and columns of the grid.

    Examples
    --------
    >>> f = MapFrame(-10.0, -10.0, 0.0, 0.05, 384, 384)
    >>> f.to_world([(383, 0), (0, 383)]).round(3).tolist()
    [[-9.975, -9.975], [9.175, 9.175]]
    >>> f.to_cell(0.0, 0.0)
    (183, 200)
    """

    x: float
    y: float
    yaw: float
    resolution: float
    height: int
    width: int

    def to_world(self, cells) -> np.ndarray:
        """World points ``(x, y)`` of cell centres ``(row, col)``, an (n, 2) array."""
        rc = np.asarray(cells, dtype=np.float64).reshape(-1, 2)
        u = (rc[:, 1] + 0.5) * self.resolution
        v = (self.height - rc[:, 0] - 0.5) * self.resolution
        cos, sin = math.cos(self.yaw), math.sin(self.yaw)
        return np.column_stack([self.x + cos * u - sin * v, self.y + sin * u + cos * v])

    def to_cell(self, x: float, y: float, name: str = "point") -> tuple[int, int]:
        """The cell ``(row, col)`` holding the world point ``(x, y)``.

        Raises
        ------
        ConfigError
            If the point is not finite or lies outside the map; the message
            names ``name`` and the map's extent.
        """
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ConfigError(f"{name} must be finite metres X,Y, got {x!r},{y!r}")
        cos, sin = math.cos(self.yaw), math.sin(self.yaw)
        dx, dy = x - self.x, y - self.y
        u, v = cos * dx + sin * dy, -sin * dx + cos * dy
        col, up = math.floor(u / self.resolution), math.floor(v / self.resolution)
        if not (0 <= col < self.width and 0 <= up < self.height):
            (x0, y0), (x1, y1) = self.extent()[:2], self.extent()[2:]
            raise ConfigError(
                f"{name} {x:g},{y:g} is outside the map, which covers x "
                f"{x0:g}..{x1:g} m and y {y0:g}..{y1:g} m"
                + (f" (yaw {math.degrees(self.yaw):.1f} deg)" if self.yaw else "")
            )
        return self.height - 1 - up, col

    def extent(self) -> tuple[float, float, float, float]:
        """``(x_min, y_min, x_max, y_max)`` of the map in the frame (yaw 0:
        the image's borders)."""
        w, h = self.width * self.resolution, self.height * self.resolution
        cos, sin = math.cos(self.yaw), math.sin(self.yaw)
        xs = [self.x + cos * u - sin * v for u, v in ((0, 0), (w, 0), (0, h), (w, h))]
        ys = [self.y + sin * u + cos * v for u, v in ((0, 0), (w, 0), (0, h), (w, h))]
        return min(xs), min(ys), max(xs), max(ys)

    def to_json(self) -> dict:
        """The frame as ``summary.json`` stores it."""
        return {"origin": [self.x, self.y, self.yaw], "resolution": self.resolution, "units": "m"}


#: The least ``cell_size`` a :class:`Workspace` takes. Below about 5e-10 a
#: path's length and that of the same path with a detour of two steps compare
#: equal under SPEC's tolerance (``1e-9`` absolute for values below 1), so
#: the exact searches' smoothest tie-break would link labels into cycles (a
#: segmentation fault on an open 8x9 grid at 7e-10); 1e-6 leaves a factor
#: of 2,000 (docs/CONVENTIONS.md).
MIN_CELL_SIZE = 1e-6


class Workspace:
    """A grid with obstacles, a start and a goal cell.

    Parameters
    ----------
    occ : (H, W) array of bool (or 0/1 integers), True/1 for an obstacle.
    start, goal : ``(row, col)``; default bottom-left ``(H-1, 0)`` and
        top-right ``(0, W-1)``.
    cell_size : length of a cell side (scales path lengths, not potentials),
        at least :data:`MIN_CELL_SIZE`.
    corner_cutting : if False a diagonal move needs both orthogonally
        adjacent cells free (MovingAI convention); default True (SPEC).
    name : a label used in outputs.
    frame : optional :class:`MapFrame`, the map's world frame (ROS maps;
        None when the grid has no world frame).

    Attributes
    ----------
    start, goal : tuple of int
        The start and goal cells ``(row, col)``.
    cell_size : float
        Length of a cell side.
    corner_cutting : bool
        The corner rule (:func:`gapath.grid.can_step`).
    name : str
        The label.
    frame : MapFrame or None
        The world frame.

    Raises
    ------
    MapError
        If ``occ`` is not a non-empty 2-D boolean (or 0/1) array.
    ConfigError
        If start or goal is outside the grid or on an obstacle, if they are
        equal, if ``cell_size`` is not a number >= :data:`MIN_CELL_SIZE`, or
        if ``corner_cutting`` is not a bool (``"no"`` would otherwise read
        as True).

    Examples
    --------
    >>> ws = Workspace(np.zeros((4, 5), bool))
    >>> ws.start, ws.goal
    ((3, 0), (0, 4))
    """

    start: tuple[int, int]
    goal: tuple[int, int]
    cell_size: float
    corner_cutting: bool
    name: str
    frame: MapFrame | None

    def __init__(
        self,
        occ: ArrayLike,
        start: Sequence[int] | None = None,
        goal: Sequence[int] | None = None,
        *,
        cell_size: float = 1.0,
        corner_cutting: bool = True,
        name: str = "workspace",
        frame: MapFrame | None = None,
    ) -> None:
        arr = np.asarray(occ)
        if arr.ndim != 2 or arr.shape[0] == 0 or arr.shape[1] == 0:
            raise MapError(f"occupancy must be a non-empty 2-D array, got shape {arr.shape}")
        if arr.dtype != np.bool_:
            if not (np.issubdtype(arr.dtype, np.integer) or np.issubdtype(arr.dtype, np.floating)):
                raise MapError(f"occupancy must be boolean, got dtype {arr.dtype}")
            bad = ~np.isin(arr, (0, 1))
            if bad.any():
                r, c = np.argwhere(bad)[0]
                raise MapError(
                    f"occupancy must be boolean (or 0/1), got {arr[r, c].item()!r} at (row {r}, col {c})"
                )
            arr = arr.astype(bool)
        occ_c = np.ascontiguousarray(arr, dtype=np.bool_)
        if occ_c.flags.writeable:  # the caller's array: a frozen private copy
            occ_c = occ_c.copy()
            occ_c.setflags(write=False)
        self._occ = occ_c
        h, w = self._occ.shape
        try:
            cs = float(cell_size)
        except (TypeError, ValueError):
            raise ConfigError(f"cell_size must be a positive number, got {cell_size!r}") from None
        if not np.isfinite(cs) or cs <= 0:
            raise ConfigError(f"cell_size must be a positive number, got {cell_size!r}")
        if cs < MIN_CELL_SIZE:
            raise ConfigError(
                f"cell_size must be at least {MIN_CELL_SIZE:g}, got {cell_size!r}: below it, paths a few "
                "steps apart in length compare equal under SPEC's tolerance (1e-9, absolute below 1); "
                "use larger units"
            )
        self.cell_size = cs
        if not isinstance(corner_cutting, (bool, np.bool_)):
            raise ConfigError(f"corner_cutting must be True or False, got {corner_cutting!r}")
        self.corner_cutting = bool(corner_cutting)
        self.name = str(name)
        self.frame = frame
        self.start = check_cell((h - 1, 0) if start is None else start, "start", (h, w))
        self.goal = check_cell((0, w - 1) if goal is None else goal, "goal", (h, w))
        for label, cell in (("start", self.start), ("goal", self.goal)):
            if self._occ[cell]:
                raise ConfigError(f"{label} {cell} is on an obstacle")
        if self.start == self.goal:
            raise ConfigError(f"start and goal are the same cell {self.start}")

    # -- basic properties -------------------------------------------------
    @property
    def occ(self) -> np.ndarray:
        """Read-only (H, W) bool occupancy array."""
        return self._occ

    @property
    def shape(self) -> tuple[int, int]:
        """``(H, W)``: rows and columns of the grid."""
        h, w = self._occ.shape
        return h, w

    @property
    def n_obstacles(self) -> int:
        """Number of obstacle cells."""
        return int(self._occ.sum())

    @cached_property
    def potential(self) -> np.ndarray:
        """Potential field of SPEC (cell units), computed once and cached."""
        pot = potential_field(self._occ)
        pot.setflags(write=False)
        return pot

    def __setstate__(self, state: dict[str, Any]) -> None:
        # copies and unpickled arrays come back writable (a Dask worker's
        # workspace, a deep copy): freeze them again (see read_only)
        self.__dict__.update(state)
        for key in ("_occ", "potential"):
            if key in state:
                self.__dict__[key] = read_only(state[key])

    def replace(self, **changes: Any) -> Workspace:
        """A copy with some of ``occ, start, goal, cell_size, corner_cutting,
        name, frame`` replaced."""
        kw: dict[str, Any] = dict(
            occ=self._occ,
            start=self.start,
            goal=self.goal,
            cell_size=self.cell_size,
            corner_cutting=self.corner_cutting,
            name=self.name,
            frame=self.frame,
        )
        unknown = set(changes) - set(kw)
        if unknown:
            raise ConfigError(f"unknown workspace field(s): {sorted(unknown)}")
        kw.update(changes)
        occ = kw.pop("occ")
        return Workspace(occ, **kw)

    def describe(self) -> dict[str, Any]:
        """The workspace's settings as written to ``summary.json``: ``map``
        (the name), ``shape``, ``start``, ``goal`` (lists), ``cell_size`` and
        ``corner_cutting``; with the occupancy they rebuild the workspace.

        Returns
        -------
        dict
            Plain JSON values.

        Examples
        --------
        >>> ws = Workspace(np.zeros((4, 5), bool), name="open")
        >>> ws.describe()
        {'map': 'open', 'shape': [4, 5], 'start': [3, 0], 'goal': [0, 4], 'cell_size': 1.0, 'corner_cutting': True}
        >>> d = ws.describe()
        >>> Workspace(ws.occ, d["start"], d["goal"], cell_size=d["cell_size"],
        ...           corner_cutting=d["corner_cutting"], name=d["map"]) == ws
        True
        """
        return {
            "map": self.name,
            "shape": list(self.shape),
            "start": list(self.start),
            "goal": list(self.goal),
            "cell_size": self.cell_size,
            "corner_cutting": self.corner_cutting,
        }

    def __repr__(self) -> str:
        h, w = self.shape
        return (
            f"Workspace(name={self.name!r}, shape={h}x{w}, obstacles={self.n_obstacles}, "
            f"start={self.start}, goal={self.goal}, cell_size={self.cell_size}, "
            f"corner_cutting={self.corner_cutting})"
        )

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Workspace):
            return NotImplemented
        return (
            np.array_equal(self._occ, other._occ)
            and self.start == other.start
            and self.goal == other.goal
            and self.cell_size == other.cell_size
            and self.corner_cutting == other.corner_cutting
        )

    __hash__ = None  # type: ignore[assignment]  # mutable arrays: unhashable

    # -- text form ---------------------------------------------------------
    def to_text(self) -> str:
        """The grid as plain text: ``.`` free, ``#`` obstacle, ``S``/``G``."""
        rows = [["#" if v else "." for v in row] for row in self._occ]
        rows[self.start[0]][self.start[1]] = "S"
        rows[self.goal[0]][self.goal[1]] = "G"
        return "\n".join("".join(r) for r in rows) + "\n"

    # -- loading -----------------------------------------------------------
    @classmethod
    def load(
        cls,
        path: str | os.PathLike[str],
        start: Sequence[int] | None = None,
        goal: Sequence[int] | None = None,
        **kwargs: Any,
    ) -> Workspace:
        """Load a map file, the format chosen by extension.

        See :func:`gapath.loaders.load_map` for the formats.
        """
        from gapath.loaders import load_map

        return load_map(path, start=start, goal=goal, **kwargs)

    # -- path checks -------------------------------------------------------
    def is_valid_path(self, path: Iterable[Sequence[int]] | np.ndarray) -> bool:
        """True if ``path`` goes from start to goal in 8-connected steps
        inside the grid (obstacles are not checked: see ``interfering``)."""
        p = np.asarray(path)
        if p.ndim != 2 or p.shape[1] != 2 or len(p) < 2:
            return False
        h, w = self.shape
        if (p[:, 0] < 0).any() or (p[:, 0] >= h).any() or (p[:, 1] < 0).any() or (p[:, 1] >= w).any():
            return False
        if tuple(p[0]) != self.start or tuple(p[-1]) != self.goal:
            return False
        d = np.abs(np.diff(p, axis=0))
        return bool((d.max(axis=1) == 1).all())
