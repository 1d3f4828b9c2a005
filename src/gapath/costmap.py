"""Layered costmaps (Lavin, "A Pareto optimal D* search algorithm", section III-A).

A :class:`Costmap` holds named ``(H, W)`` float layers over a
:class:`~gapath.workspace.Workspace`. The paper's five layers are

``distance``
    The occupancy grid as a cost: traversing a free cell costs one unit per
    unit length, an obstacle costs ``inf`` (it is not traversable). Built
    from the workspace; it is the only layer that may hold ``inf``.
``heuristic``
    Octile distance from every cell to the goal, times ``cell_size`` (the
    8-connected shortest length on an empty grid): the paper's ``h(n)``.
``elevation``
    Terrain height normalised to ``[0, 1]`` (paper: "the elevations were
    normalized [0:1] for each sample"), from a DEM array
    (:meth:`Costmap.set_elevation`, :func:`elevation_from_dem`) or a seeded
    fractal terrain (:func:`fractal_terrain`).
``solar``
    Dynamic: the cost of a step depends on its direction and on its index
    along the path, see :meth:`Costmap.solar_cost`. It has no ``(H, W)``
    array; :meth:`Costmap.layer` refuses it and :meth:`Costmap.solar_table`
    gives the costs of the 8 moves per step index.
``risk``
    Proximity to one (or more) risk cells: ``1 / max(d^2, cap^2)`` with
    ``d`` the Euclidean distance in cell units (paper eq. 7: inverse square
    distance), capped at ``1 / cap^2`` near the risk cell so that it stays
    finite there (``cap = 1`` by default: 1 at the risk cell and at its four
    orthogonal neighbours). Several risk cells add up.

Any other name is a *user layer*: a non-negative finite ``(H, W)`` array
added with :meth:`Costmap.add_layer`.

Path objectives (paper eqs. 4-7)
    For a path ``p_0 .. p_m`` (``n = m + 1`` waypoints, start and goal
    included) and steps ``k = 0 .. m - 1`` (``p_k -> p_{k+1}``):

    * ``length`` (F1) = sum of step lengths (SPEC: from the integer step
      counts, times ``cell_size``);
    * ``elevation`` (F2) = ``sum_i e(p_i) / n``, the mean over the waypoints;
    * ``solar`` (F3) = ``sum_k sigma_k``, a sum over the steps (eq. 6 has no
      ``1/n``), with ``sigma_k`` defined in :meth:`Costmap.solar_cost`;
    * ``risk`` (F4) = ``sum_i r(p_i) / n``, the mean over the waypoints;
    * a user layer ``L`` = ``sum_i L(p_i) / n``, like elevation and risk;
    * ``<layer>_max`` (``risk_max``, ``elevation_max``, a user layer's name +
      ``_max``) = ``max_i L(p_i)``, the worst cell of the path, start and
      goal included (worst-case risk; not in the paper). Like the mean, a
      maximum is not a sum over the steps: the GA problems take it, the
      graph-search planners (cost sums) do not. A layer whose own name ends
      in ``_max`` keeps that name for itself (the real layer wins).

Errors
    Unknown layer names, layers of the wrong shape, NaN, infinite or negative
    values raise :class:`gapath.errors.ConfigError` naming the layer and the
    offending value (with its cell) or shape.
"""

from __future__ import annotations

import hashlib
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numba
import numpy as np

from gapath.errors import ConfigError
from gapath.grid import DC, DR, SQRT2, check_cell, check_path, path_length

if TYPE_CHECKING:
    from gapath.workspace import Workspace

__all__ = [
    "Costmap",
    "BUILTIN_LAYERS",
    "PLAN_LAYERS",
    "build_costmap",
    "CELL_MEAN",
    "CELL_MAX",
    "elevation_from_dem",
    "fractal_terrain",
    "load_dem",
    "risk_layer",
    "solar_step_cost",
    "evaluate_layer_profiles",
    "COSTMAP_DEFAULTS",
    "CostmapSettings",
    "SettingNames",
    "check_layer_name",
    "costmap_from_settings",
    "costmap_layers",
    "costmap_record",
    "layer_objectives",
]

#: The paper's layer names (section III-A), in its order.
BUILTIN_LAYERS = ("distance", "heuristic", "elevation", "solar", "risk")
#: Lavin's cost layers a planning costmap may use as objectives besides the
#: length (:func:`build_costmap`, ``gapath plan --layers``).
PLAN_LAYERS = ("elevation", "solar", "risk")
#: Layers that are computed, never set by hand.
_DERIVED = ("distance", "heuristic", "solar")
#: Names that cannot be used for user layers.
_RESERVED = _DERIVED + ("length", "vulnerability", "smoothness", "interfering")

#: Aggregation codes of the layer objectives (numba kernels): the mean of a
#: cell layer over the path's cells, the solar cost summed over the steps,
#: the maximum of a cell layer over the path's cells.
CELL_MEAN, STEP_SUM, CELL_MAX = 0, 1, 2
#: Suffix of the worst-case (maximum over the path's cells) objectives.
MAX_SUFFIX = "_max"


# ---------------------------------------------------------------------------
# validation
# ---------------------------------------------------------------------------


def _check_layer(name: str, values, shape, *, allow_negative: bool = False) -> np.ndarray:
    """``values`` as a C-contiguous float64 array of ``shape``.

    Raises
    ------
    ConfigError
        Naming the layer, if ``values`` is not numeric, has another shape, or
        holds NaN, infinite or (unless ``allow_negative``) negative values.
    """
    try:
        arr = np.asarray(values)
    except Exception:  # pragma: no cover - exotic objects
        raise ConfigError(f"layer {name!r} must be an array, got {type(values).__name__}") from None
    if arr.dtype == np.bool_ or not (
        np.issubdtype(arr.dtype, np.integer) or np.issubdtype(arr.dtype, np.floating)
    ):
        raise ConfigError(f"layer {name!r} must be a numeric array, got dtype {arr.dtype}")
    if shape is not None and arr.shape != tuple(shape):
        raise ConfigError(f"layer {name!r} must have the grid's shape {tuple(shape)}, got shape {arr.shape}")
    if shape is None and (arr.ndim != 2 or arr.size == 0):
        raise ConfigError(f"layer {name!r} must be a non-empty 2-D array, got shape {arr.shape}")
    arr = np.ascontiguousarray(arr, dtype=np.float64)
    bad = np.isnan(arr)
    if bad.any():
        r, c = np.argwhere(bad)[0]
        raise ConfigError(f"layer {name!r} holds NaN at (row {r}, col {c})")
    bad = ~np.isfinite(arr)
    if bad.any():
        r, c = np.argwhere(bad)[0]
        raise ConfigError(
            f"layer {name!r} holds {float(arr[r, c])!r} at (row {r}, col {c}); costs must be "
            f"finite (mark impassable cells as obstacles instead)"
        )
    if not allow_negative:
        neg = arr < 0
        if neg.any():
            r, c = np.argwhere(neg)[0]
            raise ConfigError(
                f"layer {name!r} holds the negative value {float(arr[r, c])!r} at "
                f"(row {r}, col {c}); costs must be >= 0"
            )
    return arr


def _normalise(arr: np.ndarray) -> np.ndarray:
    """Min-max normalisation to [0, 1] (a flat array gives zeros)."""
    lo, hi = float(arr.min()), float(arr.max())
    if hi > lo:
        return (arr - lo) / (hi - lo)
    return np.zeros_like(arr)


# ---------------------------------------------------------------------------
# terrain sources
# ---------------------------------------------------------------------------


def _dem_error(p: Path, exc: BaseException, what: str = "DEM file") -> ConfigError:
    if isinstance(exc, FileNotFoundError):
        return ConfigError(f"{what} {str(p)!r} does not exist")
    if isinstance(exc, OSError):
        return ConfigError(f"{what} {str(p)!r} cannot be read ({exc.strerror or exc})")
    if str(exc) == "object array":
        return ConfigError(
            f"{what} {str(p)!r} holds Python objects (pickled), which gapath "
            f"does not load; save a numeric array with numpy.save"
        )
    kind = "a NumPy .npy array" if p.suffix == ".npy" else "a NumPy .npz archive of arrays"
    return ConfigError(f"{what} {str(p)!r} is not {kind} (not that format, or truncated)")


def check_dem_file(path, *, what: str = "DEM file") -> Path:
    """Check that ``path`` names a readable ``.npy`` array (or ``.npz``
    archive) of numbers, reading only its header.

    ``what`` names the file in messages (``"DEM file"``; ``"layer file"``
    for a user layer).

    Raises
    ------
    ConfigError
        Naming the file: another extension, a missing or unreadable file, or
        content that is not a NumPy array of numbers.

    Examples
    --------
    >>> check_dem_file("missing.npy")
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: DEM file 'missing.npy' does not exist
    """
    import zipfile

    p = Path(path)
    if p.suffix not in (".npy", ".npz"):
        raise ConfigError(f"{what} {str(p)!r} must be .npy or .npz, got {p.suffix!r}")
    try:
        if p.suffix == ".npz":
            with zipfile.ZipFile(p) as z:
                if not any(n.endswith(".npy") for n in z.namelist()):
                    raise ValueError("no arrays")
            return p
        with open(p, "rb") as f:
            version = np.lib.format.read_magic(f)
            read = (
                np.lib.format.read_array_header_1_0
                if version == (1, 0)
                else np.lib.format.read_array_header_2_0
            )
            _, _, dtype = read(f)
    except (OSError, ValueError, EOFError, zipfile.BadZipFile) as exc:
        raise _dem_error(p, exc, what) from None
    if dtype.hasobject:
        raise _dem_error(p, ValueError("object array"), what)
    return p


def load_dem(path, *, what: str = "DEM file", member: str = "elevation") -> np.ndarray:
    """An elevation raster from a ``.npy`` file or a ``.npz`` archive (its
    ``member`` array, by default ``elevation``, else its first array).
    ``what`` names the file in messages (see :func:`check_dem_file`).

    Raises
    ------
    ConfigError
        If the file has another extension, is missing or unreadable, or
        holds no 2-D numeric array (pickled objects are never loaded).
    """
    import zipfile

    p = check_dem_file(path, what=what)
    try:
        if p.suffix == ".npy":
            arr = np.load(p, allow_pickle=False)
        else:
            with np.load(p, allow_pickle=False) as z:
                key = member if member in z.files else z.files[0]
                arr = z[key]
    except (OSError, ValueError, EOFError, zipfile.BadZipFile, IndexError) as exc:
        raise _dem_error(p, exc, what) from None
    label = f"dem {p.name}" if what == "DEM file" else p.name
    return _check_layer(label, arr, None, allow_negative=True)


def elevation_from_dem(
    dem, shape, *, method: str = "bilinear", offset=(0, 0), normalise: bool = True
) -> np.ndarray:
    """An ``(H, W)`` elevation layer from a DEM raster.

    Parameters
    ----------
    dem : 2-D array of heights (any units, any finite values) or a path to a
        ``.npy``/``.npz`` file (see :func:`load_dem`).
    shape : ``(H, W)`` of the grid.
    method : {"bilinear", "reflect"}
        ``"bilinear"``: the whole DEM is stretched over the grid; the centre of
        cell ``(r, c)`` samples the DEM at ``((r + 0.5) * Hd / H - 0.5,
        (c + 0.5) * Wd / W - 0.5)`` (pixel-centre alignment, clamped at the
        border) by bilinear interpolation. ``"reflect"``: one DEM pixel per
        cell, no interpolation; the DEM is tiled with reflection (mirrored
        copies, ``numpy.pad(mode="symmetric")``, period ``2 Hd x 2 Wd``) and
        the window of ``shape`` starting at ``offset`` is cut out, so any
        window size and offset is valid and the terrain stays continuous
        across tile borders.
    offset : ``(row, col)`` of the window's top-left pixel (``"reflect"``
        only; taken modulo the period).
    normalise : scale to [0, 1] (min-max over the window), as the paper does.

    Returns
    -------
    (H, W) float64 array.

    Raises
    ------
    ConfigError
        On an unknown method, a bad shape, or a DEM with NaN/inf values.

    Examples
    --------
    >>> dem = np.arange(6.0).reshape(2, 3)
    >>> elevation_from_dem(dem, (2, 5), method="reflect", normalise=False)
    array([[0., 1., 2., 2., 1.],
           [3., 4., 5., 5., 4.]])
    """
    if isinstance(dem, (str, Path)):
        dem = load_dem(dem)
    dem = _check_layer("dem", dem, None, allow_negative=True)
    try:
        h, w = (int(v) for v in shape)
    except (TypeError, ValueError):
        raise ConfigError(f"shape must be (rows, cols), got {shape!r}") from None
    if h <= 0 or w <= 0:
        raise ConfigError(f"shape must be positive, got {shape!r}")
    hd, wd = dem.shape
    if method == "bilinear":
        if tuple(offset) != (0, 0):
            raise ConfigError("offset applies to method='reflect' only")
        y = np.clip((np.arange(h) + 0.5) * hd / h - 0.5, 0, hd - 1)
        x = np.clip((np.arange(w) + 0.5) * wd / w - 0.5, 0, wd - 1)
        y0 = np.minimum(np.floor(y).astype(np.int64), max(hd - 2, 0))
        x0 = np.minimum(np.floor(x).astype(np.int64), max(wd - 2, 0))
        y1 = np.minimum(y0 + 1, hd - 1)
        x1 = np.minimum(x0 + 1, wd - 1)
        fy = (y - y0)[:, None]
        fx = (x - x0)[None, :]
        out = (
            (1 - fy) * (1 - fx) * dem[np.ix_(y0, x0)]
            + (1 - fy) * fx * dem[np.ix_(y0, x1)]
            + fy * (1 - fx) * dem[np.ix_(y1, x0)]
            + fy * fx * dem[np.ix_(y1, x1)]
        )
    elif method == "reflect":
        r0, c0 = (int(v) for v in offset)
        r0 %= 2 * hd
        c0 %= 2 * wd
        # indices into the mirrored tiling: period 2n, pixel i -> i or 2n-1-i
        ri = (r0 + np.arange(h)) % (2 * hd)
        ci = (c0 + np.arange(w)) % (2 * wd)
        ri = np.where(ri < hd, ri, 2 * hd - 1 - ri)
        ci = np.where(ci < wd, ci, 2 * wd - 1 - ci)
        out = dem[np.ix_(ri, ci)]
    else:
        raise ConfigError(f"unknown DEM method {method!r}; expected 'bilinear' or 'reflect'")
    out = np.ascontiguousarray(out, dtype=np.float64)
    return _normalise(out) if normalise else out


def fractal_terrain(shape, seed: int = 0, *, hurst: float = 0.8) -> np.ndarray:
    """Seeded fractal terrain by spectral synthesis, normalised to [0, 1].

    White Gaussian noise is filtered in the Fourier domain by the amplitude
    ``|f|^-(hurst + 1)`` (power spectrum ``|f|^-(2 hurst + 2)``, a fractional
    Brownian surface with Hurst exponent ``hurst``; the mean is removed),
    transformed back and min-max normalised. Larger ``hurst`` gives smoother
    terrain. The same ``(shape, seed, hurst)`` gives the same array.

    Raises
    ------
    ConfigError
        If the shape is not positive or ``hurst`` is outside (0, 1].

    Examples
    --------
    >>> t = fractal_terrain((8, 6), seed=1)
    >>> t.shape, float(t.min()), float(t.max())
    ((8, 6), 0.0, 1.0)
    """
    try:
        h, w = (int(v) for v in shape)
    except (TypeError, ValueError):
        raise ConfigError(f"shape must be (rows, cols), got {shape!r}") from None
    if h <= 0 or w <= 0:
        raise ConfigError(f"shape must be positive, got {shape!r}")
    if not (0.0 < float(hurst) <= 1.0):
        raise ConfigError(f"hurst must be in (0, 1], got {hurst!r}")
    rng = np.random.default_rng(seed)
    noise = rng.standard_normal((h, w))
    fy = np.fft.fftfreq(h)[:, None]
    fx = np.fft.rfftfreq(w)[None, :]
    f = np.sqrt(fy * fy + fx * fx)
    f[0, 0] = 1.0
    amp = f ** -(float(hurst) + 1.0)
    amp[0, 0] = 0.0
    out = np.fft.irfft2(np.fft.rfft2(noise) * amp, s=(h, w))
    return _normalise(out)


def risk_layer(shape, cells, *, cap: float = 1.0) -> np.ndarray:
    """Risk proximity ``sum_i 1 / max(d_i^2, cap^2)`` (paper eq. 7, capped).

    ``d_i`` is the Euclidean distance, in cell units, from a cell to risk cell
    ``i``. Without the cap the risk cell itself would be infinite.

    Raises
    ------
    ConfigError
        If a cell is outside the grid or ``cap`` is not positive.

    Examples
    --------
    >>> risk_layer((3, 3), [(1, 1)]).round(3).tolist()
    [[0.5, 1.0, 0.5], [1.0, 1.0, 1.0], [0.5, 1.0, 0.5]]
    """
    h, w = shape
    try:
        cap = float(cap)
    except (TypeError, ValueError):
        raise ConfigError(f"risk cap must be a positive number, got {cap!r}") from None
    if not np.isfinite(cap) or cap <= 0:
        raise ConfigError(f"risk cap must be a positive number, got {cap!r}")
    arr = np.asarray(cells)
    if arr.ndim == 1:
        cells = [cells]
    rr, cc = np.mgrid[0:h, 0:w]
    out = np.zeros((h, w))
    for cell in cells:
        r, c = check_cell(cell, "risk cell", shape)
        d2 = (rr - r) ** 2 + (cc - c) ** 2
        out += 1.0 / np.maximum(d2, cap * cap)
    return out


# ---------------------------------------------------------------------------
# the solar cost
# ---------------------------------------------------------------------------


def solar_step_cost(dr, dc, step, *, rate: float, angle0: float = 0.0):
    """Solar deviation of a step (see :meth:`Costmap.solar_cost`); vectorised."""
    dr = np.asarray(dr, dtype=np.float64)
    dc = np.asarray(dc, dtype=np.float64)
    norm = np.hypot(dr, dc)
    theta = float(angle0) + float(rate) * np.asarray(step, dtype=np.float64)
    # step direction (x = east = +col, y = north = -row) . sun vector
    dot = (dc * np.cos(theta) - dr * np.sin(theta)) / norm
    return 0.5 * (1.0 + dot)


# ---------------------------------------------------------------------------
# the costmap
# ---------------------------------------------------------------------------


class Costmap:
    """Named cost layers over a workspace (paper section III-A).

    Parameters
    ----------
    workspace : Workspace
        The grid, start, goal and cell size.
    elevation : (H, W) array, optional
        Elevation layer; normalised to [0, 1] (see :meth:`set_elevation`).
    risk : (row, col) or list of cells, optional
        Risk cell(s) (see :meth:`set_risk`).
    risk_cap : float, default 1.0
        Distance (cells) below which the risk stops growing.
    solar_rate : float, default 0.01
        Rotation of the solar vector per path step, radians, counter-clockwise
        (paper section II: 0.01 rad per step; its Mars study, section IV, uses
        1 rad per step).
    solar_angle0 : float, default 0.0
        Angle of the solar vector at the first step (0: ``[1, 0]``, east).
    layers : dict, optional
        User layers ``{name: (H, W) array}`` (see :meth:`add_layer`).

    Raises
    ------
    ConfigError
        On a layer of the wrong shape, with NaN/inf/negative values, a
        reserved or unknown name, or a bad solar setting.

    Examples
    --------
    >>> from gapath import Workspace
    >>> ws = Workspace(np.zeros((3, 4), bool))
    >>> cm = Costmap(ws, elevation=np.arange(12.0).reshape(3, 4), risk=(1, 1))
    >>> cm.names
    ('distance', 'heuristic', 'elevation', 'solar', 'risk')
    >>> float(cm.layer("elevation")[2, 3])
    1.0
    >>> cm.objective_names
    ('length', 'elevation', 'solar', 'risk')
    """

    def __init__(
        self,
        workspace,
        *,
        elevation=None,
        risk=None,
        risk_cap: float = 1.0,
        solar_rate: float = 0.01,
        solar_angle0: float = 0.0,
        layers=None,
    ):
        self.workspace = workspace
        self._layers: dict[str, np.ndarray] = {}
        self.risk_cells: list[tuple[int, int]] = []
        self.risk_cap = float(risk_cap)
        for label, v in (("solar_rate", solar_rate), ("solar_angle0", solar_angle0)):
            try:
                ok = np.isfinite(float(v))
            except (TypeError, ValueError):
                ok = False
            if not ok:
                raise ConfigError(f"{label} must be a finite number (radians), got {v!r}")
        self.solar_rate = float(solar_rate)
        self.solar_angle0 = float(solar_angle0)
        if elevation is not None:
            self.set_elevation(elevation)
        if risk is not None:
            self.set_risk(risk, cap=risk_cap)
        for name, values in (layers or {}).items():
            self.add_layer(name, values)

    # -- shape and names ---------------------------------------------------
    @property
    def shape(self) -> tuple[int, int]:
        return self.workspace.shape

    @property
    def names(self) -> tuple[str, ...]:
        """Available layers: the built-in ones that are set (paper order),
        then the user layers in the order they were added."""
        builtin = tuple(n for n in BUILTIN_LAYERS if n in _DERIVED or n in self._layers)
        return builtin + tuple(n for n in self._layers if n not in BUILTIN_LAYERS)

    @property
    def objective_names(self) -> tuple[str, ...]:
        """Names usable as path objectives: ``length`` (F1, from the distance
        and heuristic layers), then every other layer except ``heuristic``."""
        return ("length",) + tuple(n for n in self.names if n not in ("distance", "heuristic"))

    @property
    def max_objective_names(self) -> tuple[str, ...]:
        """The worst-case objectives ``<layer>_max`` (the maximum of a cell
        layer over the path's cells), one per cell layer, except where a
        layer already has that name.

        Examples
        --------
        >>> from gapath import Workspace
        >>> Costmap(Workspace(np.zeros((3, 3), bool)), risk=(1, 1)).max_objective_names
        ('risk_max',)
        """
        cell = [n for n in self.names if n not in _DERIVED]
        return tuple(n + MAX_SUFFIX for n in cell if n + MAX_SUFFIX not in self._layers)

    def base_layer(self, name: str) -> str:
        """The cell layer an objective reads: ``name`` itself, or for a
        worst-case objective ``<layer>_max`` its ``<layer>``.

        Raises
        ------
        ConfigError
            If ``name`` is not a layer objective of this costmap (``length``
            and ``solar`` read no cell layer).
        """
        self.check_objectives([name], maxima=True)
        if name in ("length", "solar"):
            raise ConfigError(f"objective {name!r} reads no cell layer")
        if name in self._layers:
            return name
        return name[: -len(MAX_SUFFIX)]

    def aggregation(self, name: str) -> int:
        """How objective ``name`` sums up along a path: :data:`STEP_SUM`
        (``solar``), :data:`CELL_MEAN` (cell layers) or :data:`CELL_MAX`
        (``<layer>_max``).

        Raises
        ------
        ConfigError
            If ``name`` is not a layer objective of this costmap.

        Examples
        --------
        >>> from gapath import Workspace
        >>> cm = Costmap(Workspace(np.zeros((3, 3), bool)), risk=(1, 1))
        >>> [cm.aggregation(n) == a for n, a in (("risk", CELL_MEAN), ("risk_max", CELL_MAX))]
        [True, True]
        """
        self.check_objectives([name], maxima=True)
        if name == "length":
            raise ConfigError("'length' is not a layer objective (it is the path length)")
        if name == "solar":
            return STEP_SUM
        return CELL_MEAN if name in self._layers else CELL_MAX

    def check_objectives(self, objectives, *, maxima: bool = False) -> tuple[str, ...]:
        """``objectives`` (sequence or comma-separated string) as a tuple of
        names, each one a path objective of this costmap.

        Parameters
        ----------
        objectives : sequence of str or str
        maxima : also accept the worst-case objectives
            (:attr:`max_objective_names`; the GA problems take them, the
            graph-search planners, which minimise cost sums, do not).

        Raises
        ------
        ConfigError
            If a name is unknown, not set (e.g. ``elevation`` before
            :meth:`set_elevation`), repeated, or the list is empty.
        """
        if isinstance(objectives, str):
            objectives = [o.strip() for o in objectives.split(",") if o.strip()]
        names = tuple(objectives)
        if not names:
            raise ConfigError("at least one objective is needed")
        allowed = self.objective_names + (self.max_objective_names if maxima else ())
        for n in names:
            if not isinstance(n, str):
                raise ConfigError(f"objective names must be strings, got {n!r}")
            if n not in allowed:
                if not maxima and n in self.max_objective_names:
                    raise ConfigError(
                        f"objective {n!r} (the worst cell of the path) is not a sum along the "
                        f"path; graph-search planners minimise sums (the GA problems take it)"
                    )
                raise ConfigError(self._unknown(n, objective=True))
        for n in names:
            if names.count(n) > 1:
                raise ConfigError(f"objective {n!r} is given twice")
        return names

    def _unknown(self, name, objective=False) -> str:
        if name in BUILTIN_LAYERS and name not in self.names:
            how = {"elevation": "set_elevation(...)", "risk": "set_risk(...)"}[name]
            return f"layer {name!r} is not set on this costmap; call {how} first"
        if objective and name == "heuristic":
            return "'heuristic' is the goal-distance estimate, not a path objective"
        kind = "objective" if objective else "layer"
        avail = self.objective_names if objective else self.names
        return f"unknown {kind} {name!r}; available: {', '.join(avail)}"

    # -- setting layers ----------------------------------------------------
    def set_elevation(self, values, *, method: str = "bilinear", offset=(0, 0)) -> None:
        """Set the elevation layer, normalised to [0, 1].

        ``values`` of the grid's shape is used as is (then normalised);
        another shape (or a ``.npy``/``.npz`` path) is a DEM resampled by
        :func:`elevation_from_dem` with ``method`` (``"bilinear"`` stretches
        the whole DEM, ``"reflect"`` tiles it with reflection and cuts the
        window at ``offset``).
        """
        if isinstance(values, (str, Path)):
            values = load_dem(values)
        arr = _check_layer("elevation", values, None, allow_negative=True)
        if arr.shape == self.shape and method == "bilinear" and tuple(offset) == (0, 0):
            self._layers["elevation"] = _normalise(arr)
        else:
            self._layers["elevation"] = elevation_from_dem(arr, self.shape, method=method, offset=offset)

    def set_risk(self, cells, *, cap: float | None = None) -> None:
        """Set the risk layer from one ``(row, col)`` or several risk cells
        (see :func:`risk_layer`)."""
        cap = self.risk_cap if cap is None else cap
        arr = np.asarray(cells)
        cell_list = [tuple(cells)] if arr.ndim == 1 else [tuple(c) for c in cells]
        self._layers["risk"] = risk_layer(self.shape, cell_list, cap=cap)
        self.risk_cells = [check_cell(c, "risk cell", self.shape) for c in cell_list]
        self.risk_cap = float(cap)

    def add_layer(self, name: str, values) -> None:
        """Add (or replace) a user layer: a non-negative finite ``(H, W)``
        array. ``elevation`` and ``risk`` may be given this way too (then
        used as given, not normalised).

        Raises
        ------
        ConfigError
            On a reserved name (``distance``, ``heuristic``, ``solar``, the
            SPEC objective names) or a bad array.
        """
        if not isinstance(name, str) or not name or "," in name:
            raise ConfigError(f"layer names must be non-empty strings without commas, got {name!r}")
        if name in _RESERVED:
            raise ConfigError(f"layer name {name!r} is reserved (computed by gapath); choose another name")
        self._layers[name] = _check_layer(name, values, self.shape)

    # -- reading layers ----------------------------------------------------
    def layer(self, name: str) -> np.ndarray:
        """The ``(H, W)`` array of a layer (a read-only view or a new array).

        Raises
        ------
        ConfigError
            If the layer is unknown or not set, or is ``solar`` (dynamic: use
            :meth:`solar_cost` or :meth:`solar_table`).
        """
        if name == "distance":
            out = np.where(self.workspace.occ, np.inf, 1.0)
        elif name == "heuristic":
            h, w = self.shape
            gr, gc = self.workspace.goal
            dr = np.abs(np.arange(h) - gr)[:, None]
            dc = np.abs(np.arange(w) - gc)[None, :]
            out = (np.maximum(dr, dc) + (SQRT2 - 1.0) * np.minimum(dr, dc)) * self.workspace.cell_size
        elif name == "solar":
            raise ConfigError(
                "layer 'solar' is dynamic (it depends on the step direction and "
                "index); use Costmap.solar_cost or Costmap.solar_table"
            )
        elif name in self._layers:
            out = self._layers[name].view()
        else:
            raise ConfigError(self._unknown(name))
        out.setflags(write=False)
        return out

    def solar_cost(self, dr, dc, step):
        """Solar deviation ``sigma`` of a step ``(dr, dc)`` taken as step number
        ``step`` (0 for the first step of the path); vectorised.

        The solar vector starts at ``[cos a0, sin a0]`` (``[1, 0]``: east) and
        turns counter-clockwise by ``solar_rate`` per step:
        ``s_k = [cos(a0 + k w), sin(a0 + k w)]`` in ``(x, y)`` = (east, north)
        coordinates (north is towards row 0). With ``r_k`` the unit step
        direction, the paper minimises the dot product ``r_k . s_k`` (eq. 6);
        a search needs non-negative costs, so the cost is that dot product
        mapped from ``[-1, 1]`` to ``[0, 1]``::

            sigma_k = (1 + r_k . s_k) / 2 = (1 - cos(phi_k)) / 2

        where ``phi_k`` is the angle between the rover's rear (``-r_k``) and
        ``s_k``: 0 when the rear solar panel faces the solar vector, 1 when
        the rover heads straight along it. The paper's ``r . s`` is
        ``2 sigma - 1`` per step.

        Examples
        --------
        >>> from gapath import Workspace
        >>> cm = Costmap(Workspace(np.zeros((2, 2), bool)), solar_rate=np.pi / 2)
        >>> [float(cm.solar_cost(0, 1, 0)), float(cm.solar_cost(0, -1, 0)), float(cm.solar_cost(-1, 0, 1))]
        [1.0, 0.0, 1.0]
        """
        return solar_step_cost(dr, dc, step, rate=self.solar_rate, angle0=self.solar_angle0)

    def solar_table(self, n_steps: int) -> np.ndarray:
        """``(n_steps, 8)`` solar costs of the 8 moves (order E, NE, N, NW, W,
        SW, S, SE of :mod:`gapath.grid`) at step indices
        ``0 .. n_steps - 1``."""
        k = np.arange(int(n_steps))[:, None]
        return np.ascontiguousarray(self.solar_cost(DR[None, :], DC[None, :], k))

    # -- path objectives ---------------------------------------------------
    def evaluate_path(self, path, objectives=None) -> dict[str, float]:
        """Objectives (module docstring: F1..F4 and user layers) of one path.

        Parameters
        ----------
        path : (m, 2) cells, consecutive cells 8-adjacent.
        objectives : names (default: :attr:`objective_names`).

        Returns
        -------
        dict name -> value.

        Raises
        ------
        ConfigError
            On unknown objectives or a malformed path.
        """
        names = self.objective_names if objectives is None else self.check_objectives(objectives, maxima=True)
        p = check_path(path, self.workspace.shape)
        d = np.diff(p, axis=0)
        out = {}
        for n in names:
            if n == "length":
                out[n] = path_length(p, self.workspace.cell_size)
            elif n == "solar":
                out[n] = float(np.sum(self.solar_cost(d[:, 0], d[:, 1], np.arange(len(d)))))
            elif n in self._layers:
                out[n] = float(np.mean(self._layers[n][p[:, 0], p[:, 1]]))
            else:  # <layer>_max
                out[n] = float(np.max(self._layers[self.base_layer(n)][p[:, 0], p[:, 1]]))
        return out

    def with_workspace(self, workspace) -> Costmap:
        """A copy over another workspace of the same shape (e.g. with other
        obstacles, start or goal); the layers are shared.

        Raises
        ------
        ConfigError
            If the grid shapes differ.
        """
        if tuple(workspace.shape) != tuple(self.shape):
            raise ConfigError(f"workspace shape {workspace.shape} differs from the costmap's {self.shape}")
        out = object.__new__(Costmap)
        out.__dict__.update(self.__dict__)
        out.workspace = workspace
        out._layers = dict(self._layers)
        out.risk_cells = list(self.risk_cells)
        return out

    def profile_evaluator(self, frame, objectives) -> LayerProfileEvaluator:
        """A callable ``(entries, exits) -> (N, k)`` giving the layer
        objectives ``objectives`` of column profiles of ``frame`` (see
        :func:`evaluate_layer_profiles`)."""
        return LayerProfileEvaluator(self, frame, objectives)

    def __repr__(self) -> str:
        h, w = self.shape
        return (
            f"Costmap({self.workspace.name!r}, {h}x{w}, layers={list(self.names)}, "
            f"solar_rate={self.solar_rate:g}, risk_cells={self.risk_cells})"
        )


# ---------------------------------------------------------------------------
# layer objectives of padded paths
# ---------------------------------------------------------------------------


@numba.njit(cache=True)
def evaluate_layer_paths(paths, lengths, layers, agg, solar_angle0, solar_rate):
    """Layer objectives of padded paths (the free encodings' kernel).

    Parameters
    ----------
    paths : (N, L, 2) int array of cells; rows past ``lengths[i]`` are ignored.
    lengths : (N,) int array, the number of cells of each path.
    layers : (k, H, W) float array, the cell layers (unused for ``solar``).
    agg : (k,) int array: :data:`CELL_MEAN`, the mean of layer ``j`` over the
        path's cells, :data:`CELL_MAX`, its maximum over the path's cells,
        or :data:`STEP_SUM`, the solar cost summed over the steps
        (:meth:`Costmap.solar_cost`).
    solar_angle0, solar_rate : the costmap's solar settings.

    Returns
    -------
    (N, k) float64 array.
    """
    n = paths.shape[0]
    k = agg.shape[0]
    out = np.zeros((n, k))
    for i in range(n):
        m = lengths[i]
        for j in range(k):
            acc = 0.0
            if agg[j] == CELL_MEAN:
                for q in range(m):
                    acc += layers[j, paths[i, q, 0], paths[i, q, 1]]
                out[i, j] = acc / m
            elif agg[j] == CELL_MAX:
                acc = layers[j, paths[i, 0, 0], paths[i, 0, 1]]
                for q in range(1, m):
                    v = layers[j, paths[i, q, 0], paths[i, q, 1]]
                    if v > acc:
                        acc = v
                out[i, j] = acc
            else:
                for q in range(1, m):
                    dr = paths[i, q, 0] - paths[i, q - 1, 0]
                    dc = paths[i, q, 1] - paths[i, q - 1, 1]
                    norm = math.sqrt(dr * dr + dc * dc)
                    th = solar_angle0 + solar_rate * (q - 1)
                    acc += 0.5 * (1.0 + (dc * math.cos(th) - dr * math.sin(th)) / norm)
                out[i, j] = acc
    return out


# ---------------------------------------------------------------------------
# layer objectives of column profiles (the GA's kernel)
# ---------------------------------------------------------------------------


@numba.njit(cache=True)
def evaluate_layer_profiles(entries, exits, col0, layers, agg, flip, transpose, solar_angle0, solar_rate):
    """Layer objectives of column-monotone paths given as column profiles.

    Cells are visited in path order exactly as
    :func:`gapath.objectives.evaluate_profiles` visits them: in column ``k``
    (frame column ``col0 + k``) the vertical run ``entries[i, k] ..
    exits[i, k]``; consecutive columns are joined by one horizontal or
    diagonal step.

    Parameters
    ----------
    entries, exits : (N, n_cols) int arrays (frame rows).
    col0 : frame column of the start.
    layers : (k, Hf, Wf) float array, the cell layers in frame orientation
        (unused rows for ``solar``).
    agg : (k,) int array, :data:`CELL_MEAN` (mean of the layer over the
        path's cells, start and goal included), :data:`CELL_MAX` (its
        maximum over the path's cells) or :data:`STEP_SUM` (the
        solar cost summed over the steps, with their true indices
        ``0, 1, ...`` and their directions mapped back to the workspace).
    flip, transpose : the frame's maps (:class:`gapath.monotone.Frame`);
        a frame step ``(dr, dc)`` is the workspace step ``(dr, -dc)`` after
        a flip, then ``(dc, dr)`` after a transpose.
    solar_angle0, solar_rate : the costmap's solar settings.

    Returns
    -------
    (N, k) float64 array.
    """
    n, n_cols = entries.shape
    n_obj = agg.shape[0]
    out = np.zeros((n, n_obj))
    acc = np.zeros(n_obj)
    for i in range(n):
        acc[:] = 0.0
        for j in range(n_obj):
            if agg[j] == CELL_MAX:
                acc[j] = -np.inf
        n_cells = 0
        step = 0
        for k in range(n_cols):
            c = col0 + k
            a = entries[i, k]
            b = exits[i, k]
            if k > 0:  # the step into column k
                dr = a - exits[i, k - 1]
                dc = 1
                # frame step -> workspace step (undo the flip, then the transpose)
                wdr = dr
                wdc = -dc if flip else dc
                if transpose:
                    wdr, wdc = wdc, wdr
                norm = math.sqrt(wdr * wdr + wdc * wdc)
                th = solar_angle0 + solar_rate * step
                sig = 0.5 * (1.0 + (wdc * math.cos(th) - wdr * math.sin(th)) / norm)
                for j in range(n_obj):
                    if agg[j] == STEP_SUM:
                        acc[j] += sig
                step += 1
            s = 1 if b >= a else -1
            r = a
            while True:
                n_cells += 1
                for j in range(n_obj):
                    if agg[j] == CELL_MEAN:
                        acc[j] += layers[j, r, c]
                    elif agg[j] == CELL_MAX and layers[j, r, c] > acc[j]:
                        acc[j] = layers[j, r, c]
                if r == b:
                    break
                # a vertical step inside the column
                wdr = s
                wdc = 0
                if transpose:
                    wdr, wdc = wdc, wdr
                th = solar_angle0 + solar_rate * step
                sig = 0.5 * (1.0 + (wdc * math.cos(th) - wdr * math.sin(th)))
                for j in range(n_obj):
                    if agg[j] == STEP_SUM:
                        acc[j] += sig
                step += 1
                r += s
        for j in range(n_obj):
            out[i, j] = acc[j] / n_cells if agg[j] == CELL_MEAN else acc[j]
    return out


class LayerProfileEvaluator:
    """Layer objectives of a frame's column profiles (see
    :meth:`Costmap.profile_evaluator`): the layers are put in frame
    orientation once, then every call runs :func:`evaluate_layer_profiles`.

    Raises
    ------
    ConfigError
        If a name is not a layer objective of the costmap (``length`` is not:
        the frame's own evaluation computes it), or the costmap's grid differs
        from the frame's workspace.
    """

    def __init__(self, costmap: Costmap, frame, objectives):
        names = costmap.check_objectives(objectives, maxima=True)
        if "length" in names:
            raise ConfigError(
                "'length' is computed by the frame's objective kernel, not as a layer objective"
            )
        if tuple(costmap.shape) != tuple(frame.workspace.shape):
            raise ConfigError(
                f"the costmap's grid {costmap.shape} differs from the workspace's {frame.workspace.shape}"
            )
        self.objectives = names
        self.costmap = costmap
        self.frame = frame
        fh, fw = frame.occ.shape
        stack = np.zeros((len(names), fh, fw))
        for j, name in enumerate(names):
            if name != "solar":
                arr = costmap.layer(costmap.base_layer(name))
                if frame.transpose:
                    arr = arr.T
                if frame.flip:
                    arr = arr[:, ::-1]
                stack[j] = arr
        self._layers = np.ascontiguousarray(stack)
        self._agg = np.array([costmap.aggregation(n) for n in names], np.int64)

    def __call__(self, entries, exits) -> np.ndarray:
        return evaluate_layer_profiles(
            np.asarray(entries, np.int64),
            np.asarray(exits, np.int64),
            self.frame.col0,
            self._layers,
            self._agg,
            bool(self.frame.flip),
            bool(self.frame.transpose),
            self.costmap.solar_angle0,
            self.costmap.solar_rate,
        )


def build_costmap(
    workspace: Workspace,
    layers: Sequence[str] = (),
    *,
    dem: str | Path | None = None,
    dem_method: str = "bilinear",
    terrain_seed: int = 1,
    risk: tuple[int, int] | None = None,
    solar_rate: float = 0.01,
    user_layers: dict | None = None,
) -> Costmap:
    """The costmap a planner uses for ``layers`` (``gapath plan --layers``,
    and the costmap flags of ``gapath solve`` and ``gapath exact``).

    Parameters
    ----------
    workspace : Workspace
        The grid.
    layers : sequence of str
        Some of :data:`PLAN_LAYERS`: ``elevation`` (from ``dem``, or seeded
        fractal terrain), ``solar`` (always present, see ``solar_rate``),
        ``risk`` (one cell of maximum risk).
    dem : path, optional
        Elevation raster (``.npy`` or ``.npz``) resampled to the grid with
        ``dem_method`` (see :meth:`Costmap.set_elevation`); default
        :func:`fractal_terrain` seeded by ``terrain_seed``.
    dem_method : {"bilinear", "reflect"}, default "bilinear"
    terrain_seed : int, default 1
    risk : (row, col), optional
        The maximum-risk cell; default the centre of the grid.
    solar_rate : float, default 0.01
        Rotation of the solar vector per path step, radians.
    user_layers : dict, optional
        User layers ``{name: (H, W) array}`` (:meth:`Costmap.add_layer`:
        finite, non-negative, the grid's shape, used as given); their names
        may then appear in ``layers``. Every one is added, named in
        ``layers`` or not.

    Returns
    -------
    Costmap

    Raises
    ------
    ConfigError
        On an unknown layer or a bad DEM, risk cell or solar rate.

    Examples
    --------
    >>> from gapath import Workspace
    >>> cm = build_costmap(Workspace(np.zeros((5, 6), bool)), ["risk"])
    >>> cm.risk_cells
    [(2, 3)]
    >>> build_costmap(Workspace(np.zeros((5, 6), bool)), ["slope"])
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: unknown layer 'slope'; expected some of elevation, solar, risk
    """
    known = PLAN_LAYERS + tuple(n for n in (user_layers or {}) if n not in PLAN_LAYERS)
    for name in layers:
        if name not in known:
            raise ConfigError(f"unknown layer {name!r}; expected some of {', '.join(known)}")
    cm = Costmap(workspace, solar_rate=solar_rate, layers=user_layers)
    if "elevation" in layers:
        if dem is not None:
            cm.set_elevation(Path(dem), method=dem_method)
        else:
            cm.set_elevation(fractal_terrain(workspace.shape, seed=terrain_seed))
    if "risk" in layers:
        h, w = workspace.shape
        cm.set_risk((h // 2, w // 2) if risk is None else risk)
    return cm


# ---------------------------------------------------------------------------
# the costmap settings: gapath solve / exact / plan and experiment specs
# ---------------------------------------------------------------------------

#: Objectives that need no costmap.
BASE_OBJECTIVES = ("length", "vulnerability", "smoothness")
#: The built-in cell layers of the costmap settings (a DEM or fractal
#: terrain, a risk cell); ``solar`` is the step layer.
CELL_LAYERS = ("elevation", "risk")
#: Suffix of the summed objectives of the exact search (``risk_sum``).
SUM_SUFFIX = "_sum"
#: The values of the costmap settings when not given (``None``).
COSTMAP_DEFAULTS: dict[str, str | int | float] = {
    "dem_method": "bilinear",
    "terrain_seed": 1,
    "solar_rate": 0.01,
}
#: How a DEM is resampled to the grid (:meth:`Costmap.set_elevation`).
DEM_METHODS = ("bilinear", "reflect")
#: What each kind of search takes as objective names (:func:`layer_objectives`):
#: the GA (``gapath solve``, experiments), the exact search, the planners.
KINDS = ("ga", "exact", "plan")
#: The layer each built-in costmap setting builds (``layers`` builds user layers).
SETTING_LAYERS = {
    "dem": "elevation",
    "dem_method": "elevation",
    "terrain_seed": "elevation",
    "risk": "risk",
    "solar_rate": "solar",
}
#: How each form of layer objective sums up along a path (``settings.costmap``).
AGGREGATIONS = {
    "mean": "mean of the layer over the path's cells, start and goal included",
    "max": "largest value of the layer over the path's cells, start and goal included",
    "sum": "the layer summed over the path's cells, start and goal included",
    "solar": "solar deviation summed over the path's steps",
    "plan": "the planner's search minimises the layer summed along the path; the reported value is the mean over the path's cells",
}

_LAYER_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_-]*$")


@dataclass(frozen=True)
class CostmapSettings:
    """How a costmap's layers are built: the ``gapath solve`` / ``exact`` /
    ``plan`` flags ``--dem``, ``--dem-method``, ``--terrain-seed``,
    ``--risk``, ``--solar-rate``, ``--layer NAME=FILE`` and the ``costmap:``
    key of an experiment spec. ``None`` means not given (the value of
    :data:`COSTMAP_DEFAULTS`, and no layer that needs it).

    Parameters
    ----------
    dem : path, optional
        The ``elevation`` layer's raster (``.npy``/``.npz``); default: seeded
        fractal terrain.
    dem_method : {"bilinear", "reflect"}, optional
    terrain_seed : int, optional
        The fractal terrain's seed (without ``dem``).
    risk : (row, col), optional
        The ``risk`` layer's maximum-risk cell (default: the grid's centre).
    solar_rate : float, optional
        The ``solar`` layer's rotation of the solar vector per step.
    layers : tuple of (name, path)
        User layers, in order.

    Examples
    --------
    >>> CostmapSettings(risk=(1, 2), solar_rate=0.5).for_layers(["risk"])
    CostmapSettings(dem=None, dem_method=None, terrain_seed=None, risk=(1, 2), solar_rate=None, layers=())
    """

    dem: Path | None = None
    dem_method: str | None = None
    terrain_seed: int | None = None
    risk: tuple[int, int] | None = None
    solar_rate: float | None = None
    layers: tuple[tuple[str, Path], ...] = ()

    def for_layers(self, layers: Sequence[str]) -> CostmapSettings:
        """These settings without those of the layers not in ``layers``."""
        keep = {k: getattr(self, k) if v in layers else None for k, v in SETTING_LAYERS.items()}
        return CostmapSettings(**keep, layers=tuple((n, p) for n, p in self.layers if n in layers))


class SettingNames:
    """How the messages of :func:`costmap_from_settings` name the costmap
    settings: as the CLI's flags (this class), or as other keys (a subclass
    overrides :meth:`key`, :meth:`usage` and :meth:`error`).

    Parameters
    ----------
    objectives : str
        What sets the objective names, in hints (``--objectives``,
        ``--layers``).

    Examples
    --------
    >>> names = SettingNames()
    >>> str(names.error("risk", "risk cell (99, 3) is outside the 32x32 grid", "99,3"))
    '--risk 99,3: risk cell (99, 3) is outside the 32x32 grid'
    """

    #: The flag of each setting.
    FLAGS = {
        "dem": "--dem",
        "dem_method": "--dem-method",
        "terrain_seed": "--terrain-seed",
        "risk": "--risk",
        "solar_rate": "--solar-rate",
        "layers": "--layer",
    }
    #: How a setting is given, with its value (``--dem FILE``).
    USAGE = {"dem": "--dem FILE", "risk": "--risk ROW,COL", "layers": "--layer NAME=FILE"}

    def __init__(self, objectives: str = "--objectives"):
        self.objectives = objectives

    def key(self, setting: str) -> str:
        """The name of ``setting`` (a key of :data:`SETTING_LAYERS` or ``layers``)."""
        return self.FLAGS[setting]

    def usage(self, setting: str) -> str:
        """How ``setting`` is given, in hints."""
        return self.USAGE.get(setting, self.key(setting))

    def error(
        self,
        setting: str,
        reason: str,
        value: object = None,
        *,
        layer: str | None = None,
        sentence: bool = False,
    ) -> ConfigError:
        """The error of ``setting`` (a user layer: ``layers`` and ``layer``).

        Parameters
        ----------
        setting : str
        reason : str
            What is wrong and what is expected.
        value : object, optional
            The value as given, shown after the flag.
        layer : str, optional
            The user layer's name.
        sentence : bool
            ``reason`` goes on from the flag (``--dem sets ...``) rather
            than after a colon.

        Returns
        -------
        ConfigError
        """
        head = self.key(setting) + ("" if value is None else f" {value}")
        return ConfigError(f"{head} {reason}" if sentence else f"{head}: {reason}")


def check_layer_name(name: str, names: SettingNames | None = None) -> str:
    """``name`` if it may name a user layer, else a :class:`ConfigError`
    saying why.

    The name starts with a letter (then letters, digits, ``_``, ``-``), is
    not a built-in name (the SPEC objectives, ``distance``, ``heuristic``,
    ``solar``, ``elevation``, ``risk``, ``interfering``) and does not end
    in ``_max`` or ``_sum`` (those suffixes name a layer's worst-cell and
    summed objectives).

    Parameters
    ----------
    name : str
    names : SettingNames, optional
        How the built-in layers' settings are named (the CLI's flags).

    Returns
    -------
    str

    Raises
    ------
    ConfigError
        The reason alone (the caller names the flag or key).

    Examples
    --------
    >>> check_layer_name("slope")
    'slope'
    >>> check_layer_name("risk")
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: layer name 'risk' is built in (--risk ROW,COL sets it); choose another name for a user layer
    """
    names = SettingNames() if names is None else names
    if name in CELL_LAYERS:
        how = f"{names.usage('dem')} or the fractal terrain" if name == "elevation" else names.usage("risk")
        raise ConfigError(
            f"layer name {name!r} is built in ({how} sets it); choose another name for a user layer"
        )
    if name in BASE_OBJECTIVES + ("interfering", "distance", "heuristic", "solar"):
        raise ConfigError(f"layer name {name!r} is reserved (computed by gapath); choose another name")
    if not _LAYER_NAME.match(name):
        raise ConfigError(
            f"layer name {name!r} must start with a letter and hold only letters, digits, '_' and '-'"
        )
    if name.endswith((MAX_SUFFIX, SUM_SUFFIX)):
        raise ConfigError(
            f"layer name {name!r} must not end in {MAX_SUFFIX} or {SUM_SUFFIX} (those suffixes name a "
            f"layer's worst-cell and summed objectives)"
        )
    return name


def _base(name: str, cell_layers) -> tuple[str | None, str]:
    """The cell layer an objective name reads and its form: ``("risk",
    "mean")`` for ``risk``, ``("risk", "max")``, ``("risk", "sum")``;
    ``(None, "")`` for other names."""
    if name in cell_layers:
        return name, "mean"
    for suffix, form in ((MAX_SUFFIX, "max"), (SUM_SUFFIX, "sum")):
        if name.endswith(suffix) and name[: -len(suffix)] in cell_layers:
            return name[: -len(suffix)], form
    return None, ""


def layer_objectives(
    objectives: Sequence[str],
    user_layers: Sequence[str] = (),
    *,
    kind: str = "ga",
    flag: str = "--objectives",
    layer_usage: str = "--layer NAME=FILE",
) -> tuple[str, ...]:
    """The costmap layers that objective names need, checked for the
    kind of search.

    Parameters
    ----------
    objectives : sequence of str
        The objective names (``gapath plan``: the ``--layers`` names).
    user_layers : sequence of str
        The user layers' names.
    kind : {"ga", "exact", "plan"}
        ``"ga"`` (``gapath solve``, experiments): ``solar``, the means
        ``elevation``, ``risk``, a user layer's name, and the worst cells
        ``<layer>_max``; ``"exact"``: ``solar`` and the sums ``<layer>_sum``
        (a mean or a worst cell is no sum along the path: refused with the
        reason); ``"plan"``: the layers themselves (the planners minimise
        sums).
    flag : str
        What messages start with (the flag or key of the names).
    layer_usage : str
        How a user layer is given, in the hint of an unknown name.

    Returns
    -------
    tuple of str
        The layers needed, in the order elevation, solar, risk, user layers.

    Raises
    ------
    ConfigError
        On an unknown or repeated name, or one the kind of search cannot
        minimise, naming ``flag``, the value and what is expected.

    Examples
    --------
    >>> layer_objectives(["length", "risk_max", "solar"])
    ('solar', 'risk')
    >>> layer_objectives(["length", "slope_sum"], ["slope"], kind="exact")
    ('slope',)
    >>> layer_objectives(["length", "risk"], kind="exact")
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: --objectives: 'risk' is the MEAN of layer 'risk' over the path's cells (the GA's objective); a mean is not additive along a path, so no exact label-setting front exists for it: use risk_sum (the layer summed over the path's cells)
    """
    if kind not in KINDS:
        raise ConfigError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    names = list(objectives)
    user = tuple(user_layers)
    cells = CELL_LAYERS + user
    if kind == "ga":
        allowed = list(BASE_OBJECTIVES) + ["elevation", "solar", "risk", *user]
        allowed += [n + MAX_SUFFIX for n in cells]
    elif kind == "exact":
        allowed = list(BASE_OBJECTIVES) + ["solar"] + [n + SUM_SUFFIX for n in cells]
    else:
        allowed = ["elevation", "solar", "risk", *user]
    need = set()
    for n in names:
        if names.count(n) > 1:
            what = "layer" if kind == "plan" else "objective"
            raise ConfigError(f"{flag}: {what} {n!r} is given twice")
        layer, form = _base(n, cells)
        if n == "solar":
            need.add("solar")
            continue
        if n in BASE_OBJECTIVES and kind != "plan":
            continue
        if kind == "exact" and n == "interfering":
            continue  # the exact search's own message (a constraint, not an objective)
        if layer is not None and (form, kind) in (
            ("mean", "ga"),
            ("max", "ga"),
            ("sum", "exact"),
            ("mean", "plan"),
        ):
            need.add(layer)
            continue
        if layer is not None and form == "max":
            if kind == "exact":
                why = "the exact search minimises sums, so it has no front for it"
            else:
                why = "the graph-search planners minimise sums"
            raise ConfigError(
                f"{flag}: {n!r} is the worst cell of the path, not a sum along it; {why} "
                f"(the GA takes it: gapath solve --objectives length,{n})"
            )
        if layer is not None and form == "mean" and kind == "exact":
            raise ConfigError(
                f"{flag}: {n!r} is the MEAN of layer {layer!r} over the path's cells (the GA's "
                f"objective); a mean is not additive along a path, so no exact label-setting front "
                f"exists for it: use {layer + SUM_SUFFIX} (the layer summed over the path's cells)"
            )
        if layer is not None and form == "sum":
            where = (
                "the planners minimise layer sums already: name the layer"
                if kind == "plan"
                else (f"the GA takes the mean {layer!r} or the worst cell {layer + MAX_SUFFIX!r}")
            )
            raise ConfigError(
                f"{flag}: {n!r} (layer {layer!r} summed over the path's cells) is an objective of "
                f"gapath exact --mode free; {where}"
            )
        if kind == "plan":
            raise ConfigError(f"{flag}: unknown layer {n!r}; expected some of {', '.join(allowed)}")
        hint = "" if user else f"; a user layer is given with {layer_usage}"
        raise ConfigError(f"{flag}: unknown objective {n!r}; expected some of {', '.join(allowed)}{hint}")
    order = ("elevation", "solar", "risk") + user
    return tuple(n for n in order if n in need)


def _add_hint(kind: str, objectives: Sequence[str], layer: str, flag: str) -> str:
    """What to add so that ``layer`` is used: the ``--layers`` or
    ``--objectives`` value (``flag``)."""
    if kind == "plan":
        return f"add {flag} {','.join([*objectives, layer])}"
    if layer == "solar":
        return f"add solar to {flag}"
    if kind == "exact":
        return f"add {layer + SUM_SUFFIX} to {flag}"
    return f"add {layer} (or {layer + MAX_SUFFIX}) to {flag}"


def costmap_layers(
    settings: CostmapSettings,
    objectives: Sequence[str],
    *,
    kind: str = "ga",
    names: SettingNames | None = None,
) -> tuple[str, ...]:
    """The layers ``objectives`` need, with ``settings`` checked against
    them (no file is read, no grid is needed).

    Parameters
    ----------
    settings : CostmapSettings
    objectives : sequence of str
        The objective names (see :func:`layer_objectives` for ``kind``).
    kind : {"ga", "exact", "plan"}
    names : SettingNames, optional
        How messages name the settings (default: the CLI's flags, the
        objective names ``--objectives``).

    Returns
    -------
    tuple of str
        As :func:`layer_objectives`.

    Raises
    ------
    ConfigError
        An objective the search cannot take, a user layer given twice, a
        setting whose layer no objective uses, ``terrain_seed`` with
        ``dem``, ``dem_method`` without ``dem``.

    Examples
    --------
    >>> costmap_layers(CostmapSettings(risk=(1, 2)), ["length", "solar"])
    Traceback (most recent call last):
    ...
    gapath.errors.ConfigError: --risk sets the risk layer, which no objective uses: add risk (or risk_max) to --objectives
    """
    names = SettingNames() if names is None else names
    user = [n for n, _ in settings.layers]
    for n in user:
        if user.count(n) > 1:
            raise names.error("layers", f"layer {n!r} is given twice", layer=n)
    need = layer_objectives(
        objectives, user, kind=kind, flag=names.objectives, layer_usage=names.usage("layers")
    )
    unused = "is not planned on" if kind == "plan" else "no objective uses"
    for setting in ("dem", "terrain_seed", "risk", "solar_rate"):
        layer = SETTING_LAYERS[setting]
        if getattr(settings, setting) is not None and layer not in need:
            hint = _add_hint(kind, objectives, layer, names.objectives)
            raise names.error(setting, f"sets the {layer} layer, which {unused}: {hint}", sentence=True)
    for n, path in settings.layers:
        if n not in need:
            hint = _add_hint(kind, objectives, n, names.objectives)
            raise names.error(
                "layers",
                f"sets the user layer {n!r}, which {unused}: {hint}",
                f"{n}={path}",
                layer=n,
                sentence=True,
            )
    if settings.terrain_seed is not None and settings.dem is not None:
        raise names.error(
            "terrain_seed",
            f"seeds the fractal terrain, which {names.key('dem')} {settings.dem} replaces; keep one of them",
            settings.terrain_seed,
            sentence=True,
        )
    if settings.dem_method is not None and settings.dem is None:
        raise names.error(
            "dem_method",
            f"applies to a {names.usage('dem')} (the fractal terrain has the grid's shape)",
            settings.dem_method,
            sentence=True,
        )
    return need


def costmap_from_settings(
    settings: CostmapSettings,
    workspace: Workspace,
    objectives: Sequence[str],
    *,
    kind: str = "ga",
    names: SettingNames | None = None,
) -> Costmap | None:
    """The costmap ``settings`` build for ``objectives`` on ``workspace``, or
    None when no objective is a layer: the one builder of ``gapath solve``,
    ``exact``, ``plan`` and the experiment specs' ``costmap:`` key.

    Parameters
    ----------
    settings : CostmapSettings
    workspace : Workspace
    objectives : sequence of str
        The objective names (see :func:`layer_objectives` for ``kind``).
    kind : {"ga", "exact", "plan"}
    names : SettingNames, optional
        How messages name the settings (default: the CLI's flags).

    Returns
    -------
    Costmap or None
        Holding every layer the objectives need, and only those.

    Raises
    ------
    ConfigError
        One message naming the setting and value: what
        :func:`costmap_layers` refuses, a DEM or layer file that is missing,
        unreadable, not numeric, holds NaN or inf (a user layer: also
        negative values or another shape than the grid's), a risk cell
        outside the grid, a non-finite solar rate.

    Examples
    --------
    >>> from gapath import Workspace
    >>> ws = Workspace(np.zeros((5, 6), bool))
    >>> cm = costmap_from_settings(CostmapSettings(risk=(1, 2)), ws, ["length", "risk_max"])
    >>> cm.risk_cells, cm.names
    ([(1, 2)], ('distance', 'heuristic', 'solar', 'risk'))
    """
    names = SettingNames() if names is None else names
    need = costmap_layers(settings, objectives, kind=kind, names=names)
    if not need:
        return None
    rate = COSTMAP_DEFAULTS["solar_rate"] if settings.solar_rate is None else settings.solar_rate
    try:
        cm = Costmap(workspace, solar_rate=float(rate))
    except ConfigError as exc:
        raise names.error("solar_rate", str(exc), repr(rate)) from None
    if "elevation" in need:
        if settings.dem is not None:
            method = settings.dem_method or str(COSTMAP_DEFAULTS["dem_method"])
            try:
                cm.set_elevation(Path(settings.dem), method=method)
            except ConfigError as exc:
                raise names.error("dem", str(exc)) from None
        else:
            seed = (
                COSTMAP_DEFAULTS["terrain_seed"] if settings.terrain_seed is None else settings.terrain_seed
            )
            cm.set_elevation(fractal_terrain(workspace.shape, seed=int(seed)))
    if "risk" in need:
        h, w = workspace.shape
        cell = (h // 2, w // 2) if settings.risk is None else settings.risk
        try:
            cm.set_risk(cell)
        except ConfigError as exc:
            raise names.error("risk", str(exc), f"{cell[0]},{cell[1]}") from None
    for n, path in settings.layers:
        try:
            cm.add_layer(n, load_dem(path, what="layer file", member=n))
        except ConfigError as exc:
            raise names.error("layers", str(exc), f"{n}={path}", layer=n) from None
    return cm


def _sha256(path) -> str | None:
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return None


def costmap_record(
    settings: CostmapSettings, costmap: Costmap | None, objectives: Sequence[str], *, kind: str = "ga"
) -> dict | None:
    """``settings.costmap`` of a result: every setting needed to build the
    same costmap again (layers, their sources, DEM and layer files with
    their SHA-256, risk cells, solar rate) and what each layer objective
    measures; None without a costmap.

    Examples
    --------
    >>> from gapath import Workspace
    >>> ws = Workspace(np.zeros((5, 6), bool))
    >>> s = CostmapSettings(terrain_seed=3)
    >>> rec = costmap_record(s, costmap_from_settings(s, ws, ["length", "elevation"]), ["length", "elevation"])
    >>> rec["layers"], rec["elevation"]
    (['elevation'], {'source': 'fractal terrain', 'terrain_seed': 3, 'hurst': 0.8})
    """
    if costmap is None:
        return None
    user = dict(settings.layers)
    layers = [n for n in costmap.names if n not in ("distance", "heuristic", "solar") or n in objectives]
    out: dict = {"layers": layers}
    if "elevation" in layers:
        if settings.dem is not None:
            out["elevation"] = {
                "source": "dem",
                "file": str(settings.dem),
                "sha256": _sha256(settings.dem),
                "method": settings.dem_method or COSTMAP_DEFAULTS["dem_method"],
                "normalised": "min-max to [0, 1]",
            }
        else:
            seed = settings.terrain_seed
            out["elevation"] = {
                "source": "fractal terrain",
                "terrain_seed": COSTMAP_DEFAULTS["terrain_seed"] if seed is None else seed,
                "hurst": 0.8,
            }
    if "risk" in layers:
        out["risk"] = {"cells": [list(c) for c in costmap.risk_cells], "cap": costmap.risk_cap}
    if "solar" in layers:
        out["solar"] = {"rate": costmap.solar_rate, "angle0": costmap.solar_angle0}
    if user:
        out["user_layers"] = {n: {"file": str(p), "sha256": _sha256(p)} for n, p in user.items()}
    agg = {}
    for n in objectives:
        layer, form = _base(n, CELL_LAYERS + tuple(user))
        if n == "solar":
            agg[n] = AGGREGATIONS["solar"]
        elif layer is not None:
            agg[n] = AGGREGATIONS["plan" if kind == "plan" else form]
    out["objectives"] = agg
    return out
