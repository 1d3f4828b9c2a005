"""Experiment specifications: a grid of GA runs, from Python, YAML or TOML.

An experiment is the cartesian product ``maps x encodings x engines x grid
x seeds``; every point of it is one *run*, a plain JSON-serialisable dict
that :func:`gapath.experiments.runner.run_one` executes. Write it as a
Python :class:`ExperimentSpec` (or a dict for :meth:`ExperimentSpec.from_dict`)
or in a YAML / TOML file (:func:`load_spec`)::

    name: dense-small                 # label (not part of any run's identity)
    description: free text            # optional
    maps:                             # list; each entry is one of
      - default                       #   the bundled 32x32 scenario
      - maps/arena.map                #   a map file (relative to the spec file)
      - {file: {path: arena.map, start: [40, 3], goal: [3, 40], corner_cutting: false}}
      - {dense: {n: 32, p0: 0.3, seed: 7}}          # gapath.dense_workspace
      - {dense: {n: [16, 32], p0: 1.0, seed: run}}  # seed "run": the run's seed
      - {random: {shape: [32, 32], obstacles: 173, seed: 2013}}  # random_workspace
    encodings: [integer]              # default [integer]; field or via with paths: free
    engines: [fast]                   # fast | pymoo (default [fast]; former names auto, paper); alias: algorithms
    settings:                         # fixed gapath.solver.solve settings
      objectives: length,vulnerability   # or a list
      pop_size: 200
      n_gen: 500
      seed_from: none                 # weighted (default) | exact | none
      paths: monotone                 # monotone (default) | free (any simple 8-connected path)
      repair: feasible-local          # edge (default) | feasible-local | feasible-reach | ... (fast, monotone)
    grid:                             # axes of the grid: setting -> list of values
      pop_size: [100, 200]
    seeds: {start: 1, count: 100}     # or a list [1, 2, 3], or a count (seeds 1..count)
    costmap:                          # the layers of layer objectives (gapath solve's flags)
      dem: terrain/dem.npy            #   elevation: a DEM (relative to the spec file); default
      dem_method: bilinear            #   fractal terrain (terrain_seed: 1); bilinear | reflect
      risk: [16, 16]                  #   risk: the maximum-risk cell (default: the centre)
      solar_rate: 0.01                #   solar: rotation of the solar vector per step
      layers: {slope: slope.npy}      #   user layers NAME: FILE (objectives slope, slope_max)
    options:
      stop_at_first_feasible: true    # stop a run at its first feasible path
      record_first_feasible: false    # record that generation without stopping
      reference: monotone             # per-run hv ratio / IGD+ vs monotone | free

The same in TOML::

    name = "dense-small"
    maps = ["default", {dense = {n = 32, p0 = 0.3, seed = "run"}}]
    seeds = {start = 1, count = 10}
    [settings]
    pop_size = 200
    seed_from = "none"
    [options]
    stop_at_first_feasible = true

Settings (keys of ``settings`` and ``grid``) are those of
:func:`gapath.solver.solve`: ``objectives``, ``constraints``, ``penalty``,
``pop_size``, ``n_gen``, ``tiebreak`` (``smoothness`` or ``none``),
``sbx_eta``, ``seed_from`` and ``paths`` (``monotone``, Ahmed & Deb's
column-monotone paths, or ``free``; every encoding of the spec must describe
that path set), and ``repair`` (a name of
:data:`gapath.operators.repair.feasible.REPAIRS`: ``edge``, Ahmed & Deb's
edge-fixing alone, or a feasibility-preserving repair such as
``feasible-local``; only with the ``fast`` engine and monotone paths).
Missing ones take solve's defaults (``paths`` is recorded only when given,
and ``repair`` only when it is not ``edge``, so the keys of runs stored
before they existed stay the same), and the
objective mode's defaults (``constraints``, ``sbx_eta``) are resolved, so
every run records every value it ran with.

Costmap layers
    The objectives may be the costmap layer objectives of ``gapath solve``
    (:func:`gapath.costmap.layer_objectives`, kind ``ga``): the means
    ``elevation``, ``risk``, a user layer's name, the worst cells
    ``<layer>_max`` and ``solar``. The ``costmap`` key sets how their layers
    are built, with the settings of ``gapath solve``'s costmap flags
    (``--dem``, ``--dem-method``, ``--terrain-seed``, ``--risk``,
    ``--solar-rate``, ``--layer NAME=FILE``; without the key, their
    defaults), and the runs build them with the same code
    (:func:`gapath.costmap.costmap_from_settings`). A run whose objectives
    name a layer holds the settings of its layers in ``settings.costmap``
    (DEM and layer files, like map files, by name and sha256), so runs
    without layer objectives keep their keys; its result's settings hold
    ``costmap`` as ``summary.json`` does (:func:`gapath.costmap.costmap_record`).
    What ``gapath solve`` refuses is refused when the spec is read: a
    setting whose layer no objective of the spec uses, ``terrain_seed`` with
    ``dem``, ``dem_method`` without ``dem``, a DEM or layer file that is
    missing or bad (the costmap is built on every map), a risk cell off a
    map, ``seed_from: exact`` on monotone paths; and ``options.reference``
    (the exact reference fronts have no layers).

Map generators accept ``start``,
``goal`` and ``corner_cutting`` too. Engines are :func:`gapath.solver.solve`'s
(:data:`ENGINES`): ``fast``, the vectorised :class:`gapath.algorithms.FastNSGA2`,
and ``pymoo``, :func:`gapath.algorithms.paper_nsga2` on stock pymoo. The
former spec names are accepted as aliases (:data:`ENGINE_ALIASES`):
``paper`` means ``pymoo`` and ``auto`` means ``fast``; the saved spec
(``experiment.json``) and the runs hold the engine's name. The engine is
part of a run's identity, although ``fast`` is meant to be bit-identical to
``pymoo``.

Identity of a run
    :func:`run_key` is the sha256 of the run's canonical JSON
    (:func:`canonical_json`: sorted keys, no spaces, shortest float repr), with
    a map file identified by its name and the sha256 of its content rather
    than its path. Runs with equal keys are the same computation; the result
    store (:mod:`gapath.experiments.store`) names each result by its key.
    :func:`config_key` leaves the seed out: runs with the same config key are
    repetitions of one configuration (the rows of a report). The ``pymoo``
    engine enters the key under its former spec name ``paper``
    (:data:`KEY_ENGINE_NAMES`), so the runs stored before the engine names
    became solve's keep their keys.

Errors name the spec file (or ``<spec>``) and the key, e.g.
``exp.yaml: settings.pop_sise: unknown setting``.
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path

from gapath.costmap import (
    DEM_METHODS,
    SETTING_LAYERS,
    CostmapSettings,
    SettingNames,
    check_layer_name,
    costmap_from_settings,
    costmap_layers,
    layer_objectives,
)
from gapath.encodings.free import FREE_ENCODINGS
from gapath.errors import ConfigError, GapathError
from gapath.generators import default_workspace, dense_workspace, random_workspace
from gapath.loaders import load_map
from gapath.objectives import OBJECTIVE_NAMES
from gapath.operators.repair.feasible import REPAIRS
from gapath.solver import objective_mode

__all__ = [
    "ENGINES",
    "ENGINE_ALIASES",
    "KEY_ENGINE_NAMES",
    "SETTINGS",
    "ExperimentSpec",
    "build_costmap_settings",
    "build_workspace",
    "canonical_json",
    "config_key",
    "load_spec",
    "map_label",
    "resolve_engine",
    "run_key",
    "sha256_hex",
]

#: The engines of a spec: :func:`gapath.solver.solve`'s ``engine`` names.
ENGINES = ("fast", "pymoo")

#: The former spec names of the engines, accepted for the spec files and
#: stores written with them: ``paper`` (Ahmed & Deb's NSGA-II on stock
#: pymoo) and ``auto`` (which always chose ``fast``).
ENGINE_ALIASES = {"paper": "pymoo", "auto": "fast"}

#: The name an engine enters :func:`run_key` with: ``pymoo`` is keyed as
#: ``paper``, its name when the first stores were written, so their keys stay.
KEY_ENGINE_NAMES = {"pymoo": "paper"}

#: Settings of :func:`gapath.solver.solve` a spec may set, with solve's defaults.
SETTINGS = dict(
    objectives=("length", "vulnerability"),
    constraints=None,
    penalty=1000.0,
    pop_size=500,
    n_gen=500,
    tiebreak="smoothness",
    sbx_eta=None,
    seed_from="weighted",
)

#: Settings a spec may give that :data:`SETTINGS` does not fill in when they
#: are absent (so that the keys of runs stored before they existed stay the
#: same), with their meaning when absent.
OPTIONAL_SETTINGS = dict(paths="monotone", repair="edge")

#: Per-experiment options and their defaults.
OPTIONS = dict(stop_at_first_feasible=False, record_first_feasible=False, reference=None)

_TOP_KEYS = (
    "name",
    "description",
    "maps",
    "encodings",
    "engines",
    "algorithms",
    "settings",
    "grid",
    "seeds",
    "options",
    "costmap",
)
#: The keys of a spec's ``costmap`` (the costmap flags of ``gapath solve``).
_COSTMAP_KEYS = ("dem", "dem_method", "terrain_seed", "risk", "solar_rate", "layers")
_MAP_KINDS = ("default", "file", "dense", "random")
_MAP_COMMON = ("start", "goal", "corner_cutting")


# ---------------------------------------------------------------------------
# canonical JSON and hashes
# ---------------------------------------------------------------------------


def _plain(obj):
    """``obj`` with tuples as lists and NumPy scalars as Python numbers."""
    if isinstance(obj, dict):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    if hasattr(obj, "item") and not isinstance(obj, (str, bytes)):
        return obj.item()
    return obj


def canonical_json(obj) -> str:
    """The canonical JSON text of ``obj``: sorted keys, no whitespace, ASCII,
    floats in Python's shortest round-trip repr, tuples as lists.

    Raises
    ------
    ValueError
        On NaN or infinite floats (not JSON).

    Examples
    --------
    >>> canonical_json({"b": (1, 2.5), "a": None})
    '{"a":null,"b":[1,2.5]}'
    """
    return json.dumps(_plain(obj), sort_keys=True, separators=(",", ":"), ensure_ascii=True, allow_nan=False)


def sha256_hex(obj) -> str:
    """sha256 (hex) of :func:`canonical_json` of ``obj``."""
    return hashlib.sha256(canonical_json(obj).encode("ascii")).hexdigest()


def _identity(run: dict) -> dict:
    run = copy.deepcopy(run)
    if "engine" in run:
        engine = ENGINE_ALIASES.get(run["engine"], run["engine"])
        run["engine"] = KEY_ENGINE_NAMES.get(engine, engine)
    spec = run.get("map", {})
    if "file" in spec:  # a map file is its name and content, not where it lies
        spec["file"].pop("path", None)
    costmap = (run.get("settings") or {}).get("costmap") or {}
    for entry in [costmap.get("dem"), *(costmap.get("layers") or {}).values()]:
        if isinstance(entry, dict):  # so are the costmap's DEM and layer files
            entry.pop("path", None)
    return run


def run_key(run: dict) -> str:
    """The key of a run: sha256 of its canonical JSON, a map file counted by
    its name and content hash, not its path.

    Examples
    --------
    >>> run_key({"seed": 1}) == run_key({"seed": 1}) != run_key({"seed": 2})
    True
    """
    return sha256_hex(_identity(run))


def config_key(run: dict) -> str:
    """The key of a run's configuration: :func:`run_key` without the seed."""
    ident = _identity(run)
    ident.pop("seed", None)
    return sha256_hex(ident)


# ---------------------------------------------------------------------------
# validation helpers
# ---------------------------------------------------------------------------


class _Where:
    """Formats error messages as ``source: key.path: message``."""

    def __init__(self, source):
        self.source = str(source) if source is not None else "<spec>"

    def error(self, key: str, message: str) -> ConfigError:
        return ConfigError(f"{self.source}: {key}: {message}" if key else f"{self.source}: {message}")


def _int(value, where: _Where, key: str, *, minimum: int | None = None) -> int:
    if (
        isinstance(value, bool)
        or not isinstance(value, (int, float))
        or (isinstance(value, float) and not value.is_integer())
    ):
        raise where.error(key, f"expected an integer, got {value!r}")
    v = int(value)
    if minimum is not None and v < minimum:
        raise where.error(key, f"expected an integer >= {minimum}, got {value!r}")
    return v


def _float(value, where: _Where, key: str, *, lo=None, hi=None) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise where.error(key, f"expected a number, got {value!r}")
    v = float(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise where.error(key, f"expected a number in [{lo}, {hi}], got {value!r}")
    return v


def _cell(value, where: _Where, key: str):
    if value is None:
        return None
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise where.error(key, f"expected [row, col], got {value!r}")
    return [_int(v, where, f"{key}[{i}]", minimum=0) for i, v in enumerate(value)]


def _list(value, where: _Where, key: str) -> list:
    if isinstance(value, (list, tuple)):
        if not value:
            raise where.error(key, "must not be empty")
        return list(value)
    return [value]


def _mapping(value, where: _Where, key: str) -> dict:
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise where.error(key, f"expected a mapping, got {value!r}")
    return value


def _unknown(d: dict, allowed, where: _Where, key: str, what: str) -> None:
    for k in d:
        if k not in allowed:
            prefix = f"{key}.{k}" if key else str(k)
            raise where.error(prefix, f"unknown {what}; expected one of {', '.join(allowed)}")


# ---------------------------------------------------------------------------
# maps
# ---------------------------------------------------------------------------


def _file_sha256(path: Path, where: _Where, key: str) -> str:
    try:
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except OSError as exc:
        raise where.error(key, f"cannot read map file {str(path)!r} ({exc.strerror})") from None


def _normalise_map(value, where: _Where, key: str, base_dir: Path) -> dict:
    """One map entry in canonical form ``{kind: {...}}``."""
    if isinstance(value, str):
        if value == "default":
            return {"default": {}}
        value = {"file": {"path": value}}
    if not isinstance(value, dict) or len(value) != 1:
        raise where.error(
            key,
            f"expected 'default', a file path or one of "
            f"{{{', '.join(_MAP_KINDS[1:])}: {{...}}}}, got {value!r}",
        )
    ((kind, args),) = value.items()
    if kind not in _MAP_KINDS:
        raise where.error(f"{key}.{kind}", f"unknown map kind; expected one of {', '.join(_MAP_KINDS)}")
    k = f"{key}.{kind}"
    args = _mapping(args, where, k)
    out: dict = {}
    if kind == "default":
        _unknown(args, _MAP_COMMON, where, k, "key")
    elif kind == "file":
        _unknown(args, ("path", "name", "sha256") + _MAP_COMMON, where, k, "key")
        if not isinstance(args.get("path"), str):
            raise where.error(f"{k}.path", f"expected a file path, got {args.get('path')!r}")
        path = Path(os.path.expanduser(args["path"]))
        path = (path if path.is_absolute() else base_dir / path).resolve()
        digest = _file_sha256(path, where, f"{k}.path")
        if args.get("sha256") not in (None, digest):
            raise where.error(
                f"{k}.sha256",
                f"map file {str(path)!r} changed: its sha256 is "
                f"{digest[:12]}..., the spec says {str(args['sha256'])[:12]}...",
            )
        out.update(path=str(path), name=path.name, sha256=digest)
    elif kind == "dense":
        _unknown(args, ("n", "p0", "seed") + _MAP_COMMON, where, k, "key")
        if "n" not in args or "p0" not in args:
            raise where.error(k, "needs n (grid side or [rows, cols]) and p0")
        n = args["n"]
        if isinstance(n, (list, tuple)):
            if len(n) != 2:
                raise where.error(f"{k}.n", f"expected a side or [rows, cols], got {n!r}")
            n = [_int(v, where, f"{k}.n[{i}]", minimum=2) for i, v in enumerate(n)]
            n = n[0] if n[0] == n[1] else n
        else:
            n = _int(n, where, f"{k}.n", minimum=2)
        out.update(
            n=n,
            p0=_float(args["p0"], where, f"{k}.p0", lo=0.0, hi=1.0),
            seed=_map_seed(args.get("seed", 0), where, f"{k}.seed"),
        )
    else:  # random
        _unknown(args, ("shape", "obstacles", "seed") + _MAP_COMMON, where, k, "key")
        if "shape" not in args or "obstacles" not in args:
            raise where.error(k, "needs shape ([rows, cols]) and obstacles")
        shape = args["shape"]
        if not isinstance(shape, (list, tuple)) or len(shape) != 2:
            raise where.error(f"{k}.shape", f"expected [rows, cols], got {shape!r}")
        out.update(
            shape=[_int(v, where, f"{k}.shape[{i}]", minimum=2) for i, v in enumerate(shape)],
            obstacles=_int(args["obstacles"], where, f"{k}.obstacles", minimum=0),
            seed=_map_seed(args.get("seed", 0), where, f"{k}.seed"),
        )
    for name in ("start", "goal"):
        if args.get(name) is not None:
            out[name] = _cell(args[name], where, f"{k}.{name}")
    if args.get("corner_cutting") is not None:
        if not isinstance(args["corner_cutting"], bool):
            raise where.error(
                f"{k}.corner_cutting", f"expected true or false, got {args['corner_cutting']!r}"
            )
        out["corner_cutting"] = args["corner_cutting"]
    entry = {kind: out}
    _check_map(entry, where, k)
    return entry


def _check_map(entry: dict, where: _Where, key: str) -> None:
    """Build the map once, so that a start or goal off the grid or on an
    obstacle (or any bad generator argument) fails when the spec is read,
    not in every run. A generator with ``seed: run`` is built with seed 0
    (generators keep the start and goal free whatever the seed)."""

    try:
        build_workspace(entry, seed=0)
    except GapathError as exc:
        raise where.error(key, str(exc)) from None


def _map_seed(value, where: _Where, key: str):
    if value == "run":
        return "run"
    return _int(value, where, key, minimum=0)


def map_label(spec: dict) -> str:
    """A short readable label of a canonical map spec (``seed: run`` is left
    out: it names the configuration, not one map).

    Examples
    --------
    >>> map_label({"dense": {"n": 8, "p0": 0.3, "seed": "run"}})
    'dense-8x8-p0.3'
    """
    ((kind, a),) = spec.items()
    if kind == "default":
        label = "default"
    elif kind == "file":
        label = Path(a["name"]).stem
    elif kind == "dense":
        h, w = (a["n"], a["n"]) if isinstance(a["n"], int) else a["n"]
        label = f"dense-{h}x{w}-p{a['p0']:g}"
    else:
        h, w = a["shape"]
        label = f"random-{h}x{w}-k{a['obstacles']}"
    if kind in ("dense", "random") and a["seed"] != "run":
        label += f"-s{a['seed']}"
    for name in ("start", "goal"):
        if name in a:
            label += f"-{name}{a[name][0]},{a[name][1]}"
    if a.get("corner_cutting") is False:
        label += "-nocc"
    return label


def build_workspace(spec: dict, seed: int | None = None):
    """The :class:`gapath.Workspace` of a canonical map spec; ``seed`` fills a
    generator's ``seed: run``.

    Raises
    ------
    ConfigError
        If a map file changed since the spec was expanded (its sha256
        differs), or on bad generator arguments.
    """

    ((kind, a),) = spec.items()
    start, goal = a.get("start"), a.get("goal")
    cc = a.get("corner_cutting")
    if kind in ("dense", "random"):
        s = a["seed"]
        if s == "run":
            if seed is None:
                raise ConfigError(f"map {map_label(spec)} takes the run's seed, but none was given")
            s = int(seed)
        if kind == "dense":
            ws = dense_workspace(
                a["n"] if isinstance(a["n"], int) else tuple(a["n"]), a["p0"], s, start=start, goal=goal
            )
        else:
            ws = random_workspace(tuple(a["shape"]), a["obstacles"], s, start=start, goal=goal)
        return ws.replace(corner_cutting=cc) if cc is not None else ws
    kw = {} if cc is None else {"corner_cutting": cc}
    if kind == "default":
        ws = default_workspace()
        changes = {k: tuple(v) for k, v in (("start", start), ("goal", goal)) if v is not None}
        return ws.replace(**changes, **kw) if changes or kw else ws

    path = Path(a["path"])
    digest = hashlib.sha256(path.read_bytes()).hexdigest()
    if digest != a["sha256"]:
        raise ConfigError(
            f"map file {path} changed since the experiment was set up "
            f"(sha256 {digest[:12]}..., expected {a['sha256'][:12]}...)"
        )
    return load_map(
        path, start=None if start is None else tuple(start), goal=None if goal is None else tuple(goal), **kw
    )


# ---------------------------------------------------------------------------
# the costmap
# ---------------------------------------------------------------------------


class _CostmapNames(SettingNames):
    """The messages of :func:`gapath.costmap.costmap_from_settings` naming
    the spec's keys: ``source: costmap.dem: reason``."""

    def __init__(self, where: _Where, objectives: str = "settings.objectives"):
        super().__init__(objectives)
        self.where = where

    def key(self, setting: str) -> str:
        return f"costmap.{setting}"

    def usage(self, setting: str) -> str:
        return self.key(setting)

    def error(self, setting, reason, value=None, *, layer=None, sentence=False) -> ConfigError:
        return self.where.error(f"costmap.layers.{layer}" if layer else f"costmap.{setting}", reason)


def _costmap_file(value, where: _Where, key: str, base_dir: Path) -> dict:
    """A DEM or layer file: a path, or (a saved spec) ``{path, name, sha256}``."""
    out = {}
    if isinstance(value, dict):
        _unknown(value, ("path", "name", "sha256"), where, key, "key")
        if value.get("sha256") is not None:
            out["sha256"] = str(value["sha256"])
        value = value.get("path")
    if not isinstance(value, str) or not value:
        raise where.error(key, f"expected a file path, got {value!r}")
    path = Path(os.path.expanduser(value))
    path = (path if path.is_absolute() else base_dir / path).resolve()
    return {"path": str(path), "name": path.name, **out}


def _costmap_files(costmap: dict) -> list[tuple[str, dict]]:
    """``(key, entry)`` of the DEM and layer files of a canonical ``costmap``."""
    files = [("costmap.dem", costmap["dem"])] if "dem" in costmap else []
    return files + [(f"costmap.layers.{n}", e) for n, e in (costmap.get("layers") or {}).items()]


def _normalise_costmap(value, where: _Where, base_dir: Path) -> dict:
    """The spec's ``costmap`` in canonical form: types checked, file paths
    absolute (relative to the spec file), keys not given left out."""
    cm = _mapping(value, where, "costmap")
    _unknown(cm, _COSTMAP_KEYS, where, "costmap", "key")
    out: dict = {}
    if cm.get("dem") is not None:
        out["dem"] = _costmap_file(cm["dem"], where, "costmap.dem", base_dir)
    if cm.get("dem_method") is not None:
        if cm["dem_method"] not in DEM_METHODS:
            raise where.error(
                "costmap.dem_method", f"expected one of {', '.join(DEM_METHODS)}, got {cm['dem_method']!r}"
            )
        out["dem_method"] = cm["dem_method"]
    if cm.get("terrain_seed") is not None:
        out["terrain_seed"] = _int(cm["terrain_seed"], where, "costmap.terrain_seed", minimum=0)
    if cm.get("risk") is not None:
        out["risk"] = _cell(cm["risk"], where, "costmap.risk")
    if cm.get("solar_rate") is not None:
        out["solar_rate"] = _float(cm["solar_rate"], where, "costmap.solar_rate")
    layers = _mapping(cm.get("layers"), where, "costmap.layers")
    if layers:
        out["layers"] = {}
        for name, file in layers.items():
            key = f"costmap.layers.{name}"
            try:
                check_layer_name(str(name), _CostmapNames(where))
            except ConfigError as exc:
                raise where.error(key, str(exc)) from None
            out["layers"][str(name)] = _costmap_file(file, where, key, base_dir)
    return out


def build_costmap_settings(costmap: dict) -> CostmapSettings:
    """The :class:`gapath.costmap.CostmapSettings` of a canonical ``costmap``
    (a run's ``settings.costmap``).

    Raises
    ------
    ConfigError
        If a DEM or layer file changed since the spec was expanded (its
        sha256 differs).

    Examples
    --------
    >>> build_costmap_settings({"risk": [1, 2], "solar_rate": 0.5})
    CostmapSettings(dem=None, dem_method=None, terrain_seed=None, risk=(1, 2), solar_rate=0.5, layers=())
    """

    def path(entry: dict, what: str) -> Path:
        p = Path(entry["path"])
        try:
            digest = hashlib.sha256(p.read_bytes()).hexdigest()
        except OSError:
            return p  # costmap_from_settings says what is wrong with it
        if entry.get("sha256") not in (None, digest):
            raise ConfigError(
                f"{what} file {p} changed since the experiment was set up "
                f"(sha256 {digest[:12]}..., expected {entry['sha256'][:12]}...)"
            )
        return p

    risk = costmap.get("risk")
    return CostmapSettings(
        dem=None if costmap.get("dem") is None else path(costmap["dem"], "DEM"),
        dem_method=costmap.get("dem_method"),
        terrain_seed=costmap.get("terrain_seed"),
        risk=None if risk is None else (int(risk[0]), int(risk[1])),
        solar_rate=costmap.get("solar_rate"),
        layers=tuple((n, path(e, f"layer {n!r}")) for n, e in (costmap.get("layers") or {}).items()),
    )


def _costmap_for(costmap: dict, layers) -> dict:
    """The entries of a canonical ``costmap`` that build ``layers``."""
    out = {k: v for k, v in costmap.items() if k != "layers" and SETTING_LAYERS[k] in layers}
    user = {n: e for n, e in (costmap.get("layers") or {}).items() if n in layers}
    if user:
        out["layers"] = user
    return out


def _check_costmap(costmap: dict, maps, settings, axes, options, where: _Where) -> None:
    """What ``gapath solve`` refuses of its costmap flags, for every
    objectives value of the spec: a ``costmap`` key whose layer no
    objective uses (:func:`gapath.costmap.costmap_layers` over all of
    them), a DEM or layer file that is missing or bad, a risk cell off a map
    (the costmap built on every map); and layer objectives with
    ``seed_from: exact`` on monotone paths or with ``options.reference``
    (the exact fronts have no costmap layers)."""

    names = _CostmapNames(where)
    costmap = copy.deepcopy(costmap)
    for _, entry in _costmap_files(costmap):
        entry.pop("sha256", None)  # checked once the files are known to load
    given = build_costmap_settings(costmap)
    values = axes.get("objectives", [settings.get("objectives", list(SETTINGS["objectives"]))])
    costmap_layers(given, list(dict.fromkeys(n for v in values for n in v)), names=names)
    user = tuple(costmap.get("layers") or {})
    seed_from = axes.get("seed_from", [settings.get("seed_from", SETTINGS["seed_from"])])
    paths = axes.get("paths", [settings.get("paths", OPTIONAL_SETTINGS["paths"])])
    for objectives in values:
        need = layer_objectives(objectives, user)
        if not need:
            continue
        layered = ", ".join(n for n in objectives if n not in OBJECTIVE_NAMES)
        if "exact" in seed_from and "monotone" in paths:
            raise where.error(
                "grid.seed_from" if "seed_from" in axes else "settings.seed_from",
                f"exact seeds from the exact monotone front, which has no costmap layers "
                f"({layered}); expected weighted (the default) or none, or paths: free",
            )
        if options.get("reference"):
            raise where.error(
                "options.reference",
                f"the exact {options['reference']} reference front has no costmap layers "
                f"({layered}); expected no reference with layer objectives",
            )
        for m in maps:
            ws = build_workspace(m, seed=0)
            costmap_from_settings(given.for_layers(need), ws, objectives, names=names)


# ---------------------------------------------------------------------------
# settings and engines
# ---------------------------------------------------------------------------


def _setting(name: str, value, where: _Where, key: str, layers=()):
    """One solve setting, validated and in canonical form (``layers``: the
    user layers of the spec's ``costmap``, objective names too)."""

    if name == "objectives":
        names = value.split(",") if isinstance(value, str) else value
        if not isinstance(names, (list, tuple)) or not all(isinstance(n, str) for n in names):
            raise where.error(key, f"expected objective names, got {value!r}")
        names = [n.strip() for n in names if n.strip()]
        if not names:
            raise where.error(key, "expected at least one objective")
        layer_objectives(names, layers, flag=f"{where.source}: {key}", layer_usage="costmap.layers")
        return names
    if name in ("pop_size", "n_gen"):
        return _int(value, where, key, minimum=2 if name == "pop_size" else 1)
    if name == "penalty":
        return _float(value, where, key, lo=0.0)
    if name == "sbx_eta":
        return None if value is None else _float(value, where, key, lo=0.0)
    choices = {
        "constraints": (None, "penalty", "constraint", "adaptive"),
        "tiebreak": ("smoothness", None),
        "seed_from": ("weighted", "exact", "none"),
        "paths": ("monotone", "free"),
        "repair": tuple(REPAIRS),
    }[name]
    if name == "tiebreak" and value == "none":
        value = None
    if value not in choices:
        raise where.error(key, f"expected one of {', '.join(str(c) for c in choices)}, got {value!r}")
    return value


def _check_paths(encodings, settings, axes, where: _Where) -> None:
    """Every encoding of the spec describes every path set it is run on
    (``paths``: ``monotone`` for integer, binary, mixed and absolute,
    ``free`` for field and via)."""

    path_sets = set(axes.get("paths", [settings.get("paths", OPTIONAL_SETTINGS["paths"])]))
    for i, e in enumerate(encodings):
        needs = "free" if e in FREE_ENCODINGS else "monotone"
        other = path_sets - {needs}
        if other:
            raise where.error(
                f"encodings[{i}]",
                f"encoding {e!r} describes {needs} paths, but the "
                f"spec runs it on {other.pop()} paths (settings."
                f"paths); use field or via for free paths and "
                f"integer, binary, mixed or absolute for monotone",
            )


def _check_repair(engines, settings, axes, where: _Where) -> None:
    """A repair other than ``edge`` runs only with the ``fast`` engine on
    monotone paths (what :func:`gapath.solver.solve` accepts)."""

    repairs = set(axes.get("repair", [settings.get("repair", OPTIONAL_SETTINGS["repair"])])) - {"edge"}
    if not repairs:
        return
    key = "grid.repair" if "repair" in axes else "settings.repair"
    name = sorted(repairs)[0]
    others = [e for e in engines if e != "fast"]
    if others:
        raise where.error(key, f"repair {name!r} needs the fast engine, but the spec runs {others[0]!r}")
    path_sets = set(axes.get("paths", [settings.get("paths", OPTIONAL_SETTINGS["paths"])]))
    if path_sets - {"monotone"}:
        raise where.error(key, f"repair {name!r} needs monotone paths, but the spec runs free paths")


def _complete_settings(settings: dict) -> dict:
    """solve's defaults filled in, the objective mode resolved; ``repair:
    edge`` (the default) left out, so such a run keeps the key of a run
    without the setting."""

    s = {k: (list(v) if isinstance(v, tuple) else v) for k, v in SETTINGS.items()}
    s.update(settings)
    if s.get("repair") == OPTIONAL_SETTINGS["repair"]:
        del s["repair"]
    mode = objective_mode(s["objectives"], s["constraints"], s["sbx_eta"], s["tiebreak"])
    s["constraints"], s["sbx_eta"] = mode["constraints"], float(mode["sbx_eta"])
    return s


def resolve_engine(engine: str) -> str:
    """The engine's name among :data:`ENGINES`: a former name of
    :data:`ENGINE_ALIASES` replaced, other names unchanged.

    Examples
    --------
    >>> resolve_engine("paper"), resolve_engine("auto"), resolve_engine("pymoo")
    ('pymoo', 'fast', 'pymoo')
    """
    return ENGINE_ALIASES.get(engine, engine)


# ---------------------------------------------------------------------------
# the spec
# ---------------------------------------------------------------------------


@dataclass
class ExperimentSpec:
    """A grid of runs (see the module docstring for the schema).

    Parameters
    ----------
    name : label of the experiment.
    maps : map entries: ``"default"``, a file path, or ``{kind: {...}}`` with
        kind ``file``, ``dense`` or ``random``.
    encodings : genome encodings (an axis).
    engines : ``fast`` or ``pymoo`` (an axis; the former names ``auto`` and
        ``paper`` are aliases of :data:`ENGINE_ALIASES`).
    settings : fixed :func:`gapath.solver.solve` settings.
    grid : setting -> list of values (axes; their product is taken).
    seeds : list of seeds, ``{"start": s, "count": k}`` or a count ``k``
        (seeds ``1..k``).
    options : ``stop_at_first_feasible``, ``record_first_feasible``,
        ``reference`` (``None``, ``"monotone"`` or ``"free"``).
    description : free text.
    source : the file the spec came from (for messages and relative paths).
    costmap : the costmap layers of the layer objectives: ``dem``,
        ``dem_method``, ``terrain_seed``, ``risk``, ``solar_rate``,
        ``layers`` (``{name: file}``), as ``gapath solve``'s flags.

    Raises
    ------
    ConfigError
        On any invalid entry; the message names the source and the key.

    Examples
    --------
    >>> spec = ExperimentSpec(maps=["default"], settings={"pop_size": 20, "n_gen": 2}, seeds=2)
    >>> [r["seed"] for r in spec.runs()]
    [1, 2]
    """

    name: str = "experiment"
    maps: list = field(default_factory=lambda: ["default"])
    encodings: list = field(default_factory=lambda: ["integer"])
    engines: list = field(default_factory=lambda: ["fast"])
    settings: dict = field(default_factory=dict)
    grid: dict = field(default_factory=dict)
    seeds: object = 1
    options: dict = field(default_factory=dict)
    description: str = ""
    source: str | None = None
    costmap: dict = field(default_factory=dict)

    def __post_init__(self):
        self._normalised = self._normalise()

    # -- construction --------------------------------------------------------
    @classmethod
    def from_dict(cls, data: dict, source=None) -> ExperimentSpec:
        """A spec from a mapping (the parsed YAML / TOML document).

        Raises
        ------
        ConfigError
            On unknown keys or bad values (names ``source`` and the key).
        """
        where = _Where(source)
        if not isinstance(data, dict):
            raise where.error(
                "", f"the spec must be a mapping of {', '.join(_TOP_KEYS)}, got {type(data).__name__}"
            )
        _unknown(data, _TOP_KEYS, where, "", "key")
        data = dict(data)
        if "algorithms" in data:
            if "engines" in data:
                raise where.error("algorithms", "give engines or algorithms, not both")
            data["engines"] = data.pop("algorithms")
        kwargs = {k: v for k, v in data.items() if v is not None}
        return cls(**kwargs, source=None if source is None else str(source))

    def to_dict(self) -> dict:
        """The normalised spec as a JSON-serialisable dict (what the store
        saves as ``experiment.json``)."""
        return copy.deepcopy(self._normalised)

    # -- normalisation -------------------------------------------------------
    def _normalise(self) -> dict:
        where = _Where(self.source)
        base_dir = Path(self.source).resolve().parent if self.source else Path.cwd()
        if not isinstance(self.name, str) or not self.name:
            raise where.error("name", f"expected a non-empty string, got {self.name!r}")
        maps = [
            _normalise_map(m, where, f"maps[{i}]", base_dir)
            for i, m in enumerate(_list(self.maps, where, "maps"))
        ]
        encodings = []
        for i, e in enumerate(_list(self.encodings, where, "encodings")):
            from gapath.encodings import ENCODINGS
            from gapath.encodings.free import FREE_ENCODINGS

            if e not in ENCODINGS and e not in FREE_ENCODINGS:
                raise where.error(
                    f"encodings[{i}]",
                    f"unknown encoding {e!r}; expected one of {', '.join([*ENCODINGS, *FREE_ENCODINGS])}",
                )
            encodings.append(e)
        engines = []
        for i, e in enumerate(_list(self.engines, where, "engines")):
            e = resolve_engine(e) if isinstance(e, str) else e
            if e not in ENGINES:
                raise where.error(
                    f"engines[{i}]",
                    f"unknown engine {e!r}; expected one of {', '.join(ENGINES)} "
                    f"(or the former names {', '.join(ENGINE_ALIASES)})",
                )
            if e not in engines:
                engines.append(e)
        costmap = _normalise_costmap(self.costmap, where, base_dir)
        user = tuple(costmap.get("layers") or {})
        settings = _mapping(self.settings, where, "settings")
        _unknown(settings, tuple(SETTINGS) + tuple(OPTIONAL_SETTINGS), where, "settings", "setting")
        settings = {k: _setting(k, v, where, f"settings.{k}", user) for k, v in settings.items()}
        if settings.get("repair") == OPTIONAL_SETTINGS["repair"]:  # the default: not recorded
            del settings["repair"]
        grid = _mapping(self.grid, where, "grid")
        _unknown(grid, tuple(SETTINGS) + tuple(OPTIONAL_SETTINGS), where, "grid", "setting")
        axes = {}
        for k, values in grid.items():
            if not isinstance(values, (list, tuple)) or not values:
                raise where.error(f"grid.{k}", f"expected a non-empty list of values, got {values!r}")
            axes[k] = [_setting(k, v, where, f"grid.{k}[{i}]", user) for i, v in enumerate(values)]
        _check_paths(encodings, settings, axes, where)
        _check_repair(engines, settings, axes, where)
        options = _mapping(self.options, where, "options")
        _unknown(options, tuple(OPTIONS), where, "options", "option")
        opts = dict(OPTIONS)
        for k in ("stop_at_first_feasible", "record_first_feasible"):
            if k in options:
                if not isinstance(options[k], bool):
                    raise where.error(f"options.{k}", f"expected true or false, got {options[k]!r}")
                opts[k] = options[k]
        if options.get("reference") not in (None, "monotone", "free"):
            raise where.error("options.reference", f"expected monotone or free, got {options['reference']!r}")
        opts["reference"] = options.get("reference")
        _check_costmap(costmap, maps, settings, axes, opts, where)
        for key, entry in _costmap_files(costmap):  # a file is its name and content (run_key)
            digest = _file_sha256(Path(entry["path"]), where, key)
            if entry.get("sha256") not in (None, digest):
                raise where.error(
                    f"{key}.sha256",
                    f"file {entry['path']!r} changed: its sha256 is {digest[:12]}..., "
                    f"the spec says {entry['sha256'][:12]}...",
                )
            entry["sha256"] = digest
        out = dict(
            name=self.name,
            description=str(self.description or ""),
            maps=maps,
            encodings=encodings,
            engines=engines,
            settings=settings,
            grid=axes,
            seeds=self._seeds(where),
            options=opts,
        )
        if costmap:  # left out without one: the saved specs of before stay the same
            out["costmap"] = costmap
        return out

    def _seeds(self, where: _Where) -> list[int]:
        s = self.seeds
        if isinstance(s, dict):
            _unknown(s, ("start", "count"), where, "seeds", "key")
            start = _int(s.get("start", 1), where, "seeds.start", minimum=0)
            count = _int(s.get("count", 1), where, "seeds.count", minimum=1)
            return list(range(start, start + count))
        if isinstance(s, (list, tuple)):
            if not s:
                raise where.error("seeds", "must not be empty")
            seeds = [_int(v, where, f"seeds[{i}]", minimum=0) for i, v in enumerate(s)]
            if len(set(seeds)) != len(seeds):
                raise where.error("seeds", f"repeated seeds in {seeds}")
            return seeds
        return list(range(1, _int(s, where, "seeds", minimum=1) + 1))

    # -- expansion -----------------------------------------------------------
    def configurations(self) -> list[dict]:
        """The runs of seed ``None``: one per configuration, in grid order."""
        n = self._normalised
        axes = list(n["grid"].items())
        out = []
        for m, enc, eng in itertools.product(n["maps"], n["encodings"], n["engines"]):
            for combo in itertools.product(*[v for _, v in axes]):
                settings = dict(n["settings"])
                settings.update({k: v for (k, _), v in zip(axes, combo)})
                settings = _complete_settings(settings)
                costmap = n.get("costmap") or {}
                need = layer_objectives(settings["objectives"], tuple(costmap.get("layers") or {}))
                if need:  # only runs with layer objectives have a costmap
                    settings["costmap"] = copy.deepcopy(_costmap_for(costmap, need))
                out.append(
                    dict(
                        map=copy.deepcopy(m),
                        encoding=enc,
                        engine=eng,
                        settings=settings,
                        options=dict(n["options"]),
                    )
                )
        return out

    def runs(self) -> list[dict]:
        """Every run: configurations x seeds, in a deterministic order (seed
        innermost). Each run is a JSON-serialisable dict with keys ``map``,
        ``encoding``, ``engine``, ``settings``, ``options`` and ``seed``."""
        return [
            dict(copy.deepcopy(c), seed=s) for c in self.configurations() for s in self._normalised["seeds"]
        ]

    def __len__(self) -> int:
        n = self._normalised
        k = math.prod(len(v) for v in n["grid"].values())
        return len(n["maps"]) * len(n["encodings"]) * len(n["engines"]) * k * len(n["seeds"])


def load_spec(path) -> ExperimentSpec:
    """Read an experiment spec from a ``.yaml`` / ``.yml``, ``.toml`` or
    ``.json`` file.

    Raises
    ------
    ConfigError
        If the file cannot be read or parsed (message with the line), or on
        any invalid entry (message with the key).
    """
    import tomllib

    import yaml

    path = Path(path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read the experiment spec ({exc.strerror})") from None
    except UnicodeDecodeError as exc:
        raise ConfigError(
            f"{path}: not a text file (undecodable byte at offset {exc.start}); "
            f"expected a YAML, TOML or JSON experiment spec"
        ) from None
    suffix = path.suffix.lower()
    if suffix in (".yaml", ".yml"):
        try:
            data = yaml.safe_load(text)
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            at = f", line {mark.line + 1}, column {mark.column + 1}" if mark else ""
            raise ConfigError(f"{path}{at}: invalid YAML: {getattr(exc, 'problem', None) or exc}") from None
    elif suffix == ".toml":
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise ConfigError(f"{path}: invalid TOML: {exc}") from None
    elif suffix == ".json":
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise ConfigError(
                f"{path}, line {exc.lineno}, column {exc.colno}: invalid JSON: {exc.msg}"
            ) from None
    else:
        raise ConfigError(f"{path}: unknown spec format {suffix!r}; expected .yaml, .yml, .toml or .json")
    if data is None:
        raise ConfigError(f"{path}: the experiment spec is empty")
    return ExperimentSpec.from_dict(data, source=path)
