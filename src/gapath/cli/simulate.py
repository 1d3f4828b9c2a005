"""``gapath simulate``, and the continuous planners for ``gapath plan``.

``gapath simulate MAP --planner P --obstacles N --seed S --out DIR`` runs one
seeded dynamic-environment simulation (:mod:`gapath.dynamic`) on ``MAP``
(``maze``, ``warehouse`` or any map file gapath reads) and writes
``trajectory.json`` (:meth:`gapath.dynamic.SimResult.to_json`),
``summary.json``, ``run.png`` and, with ``--gif``, ``run.gif``. The exit
status is 0 when the robot reached the goal and 1 for a run that failed to
reach it (its reason is printed, also with ``--quiet``, and stored); no path
between start and goal exits with 1 too, bad input with 2 (README, "Exit
status").

``gapath plan`` (:mod:`gapath.cli.plan`, another module) plans one path
on a map. This module does not register a ``plan`` parser; it offers the
hybrid A* and RRT / RRT* planners to it:

* :func:`add_planner_choices` -- the planner names this module handles
  (and, given a parser, adds their options to it, skipping options the
  parser already has);
* :func:`plan_with` -- turns the parsed arguments into the options of
  :func:`gapath.planners.plan` and plans with one of them, returning a
  :class:`~gapath.planners.PlanOutcome`;
* :func:`write_plan` -- writes ``front.csv``, ``paths.json``,
  ``summary.json`` and ``paths.png`` in the format of ``gapath solve`` (one
  record, with the continuous poses beside the cells).

The planners, the car and their defaults live in the library
(:mod:`gapath.planners.registry`); this module only maps flags to them.
"""

from __future__ import annotations

import contextlib
import math
import re
import time
from pathlib import Path

import numpy as np

from gapath.planners.registry import SIMULATED_PLANNERS, CarSettings, PlanOutcome, planner_names

#: Planner names handled by :func:`plan_with` (the kinematic ones).
PLANNER_CHOICES = planner_names("kinematic")
#: Planners ``gapath simulate`` can drive.
SIMULATE_PLANNERS = SIMULATED_PLANNERS


def _cell_arg(text):
    from gapath.cli._args import cell

    return cell(text)


def _add(parser, *flags, **kwargs) -> None:
    """Add an option unless one of its flags is already there."""
    existing = set()
    for action in parser._actions:  # argparse has no public query
        existing.update(action.option_strings)
    if not existing.intersection(flags):
        parser.add_argument(*flags, **kwargs)


def add_planner_arguments(parser) -> None:
    """The options of the car, hybrid A* and RRT(*) (already present options
    are left alone)."""
    _add(
        parser,
        "--wheelbase",
        type=float,
        default=CarSettings.wheelbase,
        help="car wheelbase, world units (default: %(default)s)",
    )
    _add(
        parser,
        "--max-steer",
        type=float,
        default=CarSettings.max_steer_deg,
        help="maximum steering angle in degrees, below 90 (default: %(default).2f, 0.6 rad)",
    )
    _add(
        parser,
        "--radius",
        type=float,
        default=CarSettings.radius,
        help="robot footprint radius, world units (default: %(default)s)",
    )
    _add(
        parser,
        "--speed",
        type=float,
        default=CarSettings.speed,
        help="robot speed, world units per second (default: %(default)s)",
    )
    _add(
        parser,
        "--heading",
        type=float,
        default=None,
        help="start heading in degrees from +x (east) towards +y (south, down the map); on a "
        "ROS map counter-clockwise from the map frame's +x (ROS yaw); default along "
        "the first steps of the grid shortest path",
    )
    _add(
        parser,
        "--heading-bins",
        type=int,
        default=72,
        help="hybrid A*: heading bins of the discrete states (default: %(default)s)",
    )
    _add(
        parser,
        "--arc-length",
        type=float,
        default=None,
        help="hybrid A*: length of an expansion, above sqrt(2) cells (default: 1.5 cells)",
    )
    _add(
        parser,
        "--heuristic-weight",
        type=float,
        default=1.1,
        help="hybrid A*: weight of the heuristic (default: %(default)s)",
    )
    _add(
        parser,
        "--iterations",
        type=int,
        default=20000,
        help="RRT/RRT*: samples at most (default: %(default)s)",
    )
    _add(
        parser,
        "--step",
        type=float,
        default=None,
        help="RRT/RRT*: tree extension, world units (default: 2 cells)",
    )
    _add(
        parser,
        "--goal-bias",
        type=float,
        default=0.1,
        help="RRT/RRT*: probability of sampling the goal (default: %(default)s)",
    )
    _add(parser, "--seed", type=int, default=1, help="random seed (default: %(default)s)")


def add_planner_choices(parser=None) -> tuple[str, ...]:
    """The planner names :func:`plan_with` handles; with ``parser``, also
    add their options (:func:`add_planner_arguments`)."""
    if parser is not None:
        add_planner_arguments(parser)
    return PLANNER_CHOICES


#: Planner and car parameters by the CLI flag that sets them.
FLAG_NAMES = {
    "max_iter": "--iterations",
    "max_steer_deg": "--max-steer",
    "goal_bias": "--goal-bias",
    "step": "--step",
    "radius": "--radius",
    "wheelbase": "--wheelbase",
    "speed": "--speed",
    "max_steer": "--max-steer",
    "heading_bins": "--heading-bins",
    "arc_length": "--arc-length",
    "heuristic_weight": "--heuristic-weight",
    "sensor_range": "--sensor-range",
    "fov": "--fov",
    "dt": "--dt",
    "max_time": "--max-time",
    "speed_range": "--obstacle-speed",
}


@contextlib.contextmanager
def cli_vocabulary():
    """Re-raise a planner's :class:`~gapath.errors.ConfigError` about one
    of its parameters (``"max_iter must be ..."``) with the flag that sets
    it (``"--iterations must be ..."``)."""
    from gapath.errors import ConfigError

    try:
        yield
    except ConfigError as exc:
        message = str(exc)
        m = re.match(r"(\w+)(?= must| \()", message)
        if m is None or m.group(1) not in FLAG_NAMES:
            raise
        raise ConfigError(FLAG_NAMES[m.group(1)] + message[len(m.group(1)) :]) from None


def planner_heading(workspace, degrees: float) -> float:
    """The planners' heading (radians, from +x towards +y = down the map) of
    a ``--heading`` in degrees: taken as is on grid maps, as a yaw
    (counter-clockwise, y up) in the map frame of a ROS map."""
    theta = math.radians(float(degrees))
    frame = getattr(workspace, "frame", None)
    return theta if frame is None else frame.yaw - theta


#: Car settings (:class:`~gapath.planners.CarSettings`) by argparse ``dest``.
CAR_FLAGS = {"wheelbase": "wheelbase", "max_steer": "max_steer_deg", "speed": "speed", "radius": "radius"}
#: Planner settings by argparse ``dest``, per planner (options of
#: :func:`gapath.planners.plan`).
PLANNER_FLAGS = {
    "hybrid-astar": {
        "heading_bins": "heading_bins",
        "arc_length": "arc_length",
        "heuristic_weight": "heuristic_weight",
    },
    "rrt": {"iterations": "max_iter", "step": "step", "goal_bias": "goal_bias"},
}
PLANNER_FLAGS["rrt-star"] = PLANNER_FLAGS["rrt"]


def car_from_args(args):
    """A :class:`~gapath.planners.hybrid_astar.CarModel` from parsed options
    (missing options take the defaults of :class:`~gapath.planners.CarSettings`)."""
    kwargs = {key: getattr(args, dest) for dest, key in CAR_FLAGS.items() if hasattr(args, dest)}
    with cli_vocabulary():
        return CarSettings(**kwargs).model()


def planner_settings(name: str, args) -> dict:
    """The settings of planner ``name`` given by the parsed options (missing
    options are left to the planner's defaults)."""
    flags = PLANNER_FLAGS.get(name, {})
    return {key: getattr(args, dest) for dest, key in flags.items() if hasattr(args, dest)}


def plan_with(name: str, workspace, args) -> PlanOutcome:
    """Plan from the workspace's start to its goal with ``name``
    (:func:`gapath.planners.plan` with the options in ``args``).

    Parameters
    ----------
    name : {"hybrid-astar", "rrt", "rrt-star"}
    workspace : Workspace
    args : argparse.Namespace
        Options of :func:`add_planner_arguments` (missing ones take their
        defaults).

    Returns
    -------
    PlanOutcome

    Raises
    ------
    ConfigError
        On an unknown planner or bad options (e.g. steering of 90 degrees or
        more, a non-positive wheelbase, a start in collision), naming the
        flag.
    NoPathError
        If no path was found.
    """
    from gapath.errors import ConfigError
    from gapath.planners import plan

    if name not in PLANNER_CHOICES:
        raise ConfigError(f"unknown planner {name!r}; this module plans with {', '.join(PLANNER_CHOICES)}")
    options = dict(planner_settings(name, args), car=car_from_args(args))
    if name == "hybrid-astar" and getattr(args, "heading", None) is not None:
        options["heading"] = planner_heading(workspace, args.heading)
    if name != "hybrid-astar" and hasattr(args, "seed"):
        options["seed"] = args.seed
    with cli_vocabulary():
        return plan(workspace, name, **options)


def write_plan(outcome: PlanOutcome, workspace, out_dir, *, plots: bool = True) -> list[Path]:
    """Write ``front.csv`` (one row: length, turning, clearance),
    ``paths.json``, ``summary.json`` and (with ``plots``) ``paths.png`` into
    ``out_dir``; returns the files."""
    from gapath.results import atomic_write, dumps, versions

    out = Path(out_dir)
    files = [out / "front.csv", out / "paths.json", out / "summary.json"]
    names = list(outcome.objectives)
    atomic_write(
        files[0], ",".join(names) + "\n" + ",".join(repr(float(outcome.objectives[n])) for n in names) + "\n"
    )
    records = outcome.records()
    frame = getattr(workspace, "frame", None)
    if frame is not None:  # also in the map's world frame (ROS maps: metres, y up)
        cs = workspace.cell_size
        p = np.asarray(outcome.poses, dtype=float)
        xy = frame.to_world(p[:, [1, 0]] / cs)
        records[0]["world"] = frame.to_world(outcome.cells).round(6).tolist()
        records[0]["world_poses"] = (
            np.column_stack([xy, np.mod(frame.yaw - p[:, 2] + np.pi, 2 * np.pi) - np.pi]).round(6).tolist()
        )
    atomic_write(files[1], dumps(records, indent=1) + "\n")
    summary = {
        "settings": {
            **workspace.describe(),
            "planner": outcome.planner,
            **{k: v for k, v in outcome.info.items() if k != "seconds"},
        },
        "versions": versions(),
        "wall_time_s": round(outcome.seconds, 6),
        "objectives": {k: float(v) for k, v in outcome.objectives.items()},
    }
    atomic_write(files[2], dumps(summary, indent=1, sort_keys=True) + "\n")
    if plots:
        import matplotlib.pyplot as plt

        from gapath.dynamic.plots import plot_map
        from gapath.plotting import png_bytes

        h, w = workspace.shape
        _, ax = plt.subplots(figsize=(6.0 * w / max(h, w) + 0.4, 6.0 * h / max(h, w) + 0.6))
        plot_map(workspace, ax)
        p = outcome.poses
        ax.plot(p[:, 0], p[:, 1], "-", color="tab:blue", lw=2)
        from gapath.plotting import length_unit

        ax.set_title(
            f"{outcome.planner}: length {outcome.objectives['length']:.2f} "
            f"{length_unit(workspace)}, "
            f"turning {outcome.objectives['turning']:.2f} rad",
            fontsize=9,
        )
        atomic_write(out / "paths.png", png_bytes(ax))
        files.append(out / "paths.png")
    return files


# ---------------------------------------------------------------------------
# gapath simulate
# ---------------------------------------------------------------------------


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "simulate",
        help="simulate a robot among appearing and moving obstacles",
        description="One seeded run of a planner among dynamic obstacles (NO-MOPP's setting): "
        "the robot senses, predicts collisions, replans locally or halts.",
    )
    p.add_argument(
        "map",
        help="'maze', 'warehouse' (generated, seeded by --map-seed) or a map "
        "file (.map, .yaml, .txt, .grid, .npy, .pgm, .png)",
    )
    p.add_argument(
        "--planner", choices=SIMULATE_PLANNERS, default="hybrid-astar", help="planner (default: %(default)s)"
    )
    p.add_argument(
        "--obstacles",
        type=int,
        default=4,
        help="moving obstacles: half timed to cross the robot's path, half wandering (default: %(default)s)",
    )
    p.add_argument(
        "--stationary",
        type=int,
        default=3,
        help="stationary obstacles appearing on the path (default: %(default)s)",
    )
    p.add_argument(
        "--obstacle-speed",
        default="0.3,0.7",
        help="LOW,HIGH speed of moving obstacles (default: %(default)s)",
    )
    p.add_argument("--map-seed", type=int, default=0, help="seed of a generated map (default: 0)")
    p.add_argument("--start", type=_cell_arg, help="start cell ROW,COL (map files; default: the map's)")
    p.add_argument("--goal", type=_cell_arg, help="goal cell ROW,COL")
    p.add_argument(
        "--sensor-range", type=float, default=6.0, help="sensor range, world units (default: %(default)s)"
    )
    p.add_argument(
        "--fov",
        type=float,
        default=180.0,
        help="half-angle of the field of view in degrees: 45, 90 or 180 in the paper (default: %(default)s)",
    )
    p.add_argument(
        "--prediction",
        choices=("straight", "bounce"),
        default="straight",
        help="how moving obstacles are predicted: 'straight' lines at their current velocity "
        "(NO-MOPP's eqs. (7)-(10)) or 'bounce', their own reflecting motion model (default: %(default)s)",
    )
    p.add_argument("--dt", type=float, default=0.1, help="tick, seconds (default: %(default)s)")
    p.add_argument(
        "--max-time",
        type=float,
        default=None,
        help="time limit, seconds (default: 3 x direct distance / speed + 60)",
    )
    add_planner_arguments(p)
    p.add_argument("--out", default="gapath-simulate", help="output directory (default: %(default)s)")
    p.add_argument("--gif", action="store_true", help="also write run.gif")
    p.add_argument("--no-plots", action="store_true", help="skip run.png")
    p.add_argument("--quiet", action="store_true")
    p.set_defaults(func=run)


def _speed_range(text):
    from gapath.errors import ConfigError

    try:
        lo, hi = (float(v) for v in str(text).split(","))
    except ValueError:
        raise ConfigError(f"--obstacle-speed must be LOW,HIGH, got {text!r}") from None
    return lo, hi


def _check_planner_flags(args, workspace, car, planner_kw) -> None:
    """Bad planner flags are bad input (exit 2), not a failed run: the
    simulation would report a planner that cannot start as blocked."""

    if args.planner in ("rrt", "rrt-star"):
        from gapath.planners.rrt import rrt_settings

        with cli_vocabulary():
            rrt_settings(workspace.cell_size, radius=car.radius, **planner_kw)
    elif args.planner == "hybrid-astar":
        from gapath.planners.hybrid_astar import HybridAStar

        with cli_vocabulary():
            HybridAStar(workspace, car, **planner_kw)


def _warm_up_simulation(planner_name, planner_kw, robot, settings) -> float:
    """One short run on an empty 12x12 map with the same planner, robot and
    tick, so that numba compiles (or loads from its cache) the planner's and
    the simulation's kernels before the timed run; returns the seconds."""
    from dataclasses import replace

    from gapath.dynamic import make_planner, simulate
    from gapath.errors import GapathError
    from gapath.workspace import Workspace

    t0 = time.perf_counter()
    try:
        simulate(
            Workspace(np.zeros((12, 12), bool), name="warm-up"),
            make_planner(planner_name, **planner_kw),
            robot,
            settings=replace(settings, max_time=5.0),
            seed=0,
        )
    except GapathError:
        pass  # a bad option is reported by the real run
    return time.perf_counter() - t0


def run(args) -> int:
    from gapath.dynamic import Robot, SimSettings, make_planner, simulate
    from gapath.dynamic.scenarios import make_scenario
    from gapath.errors import EXIT_NO_RESULT, ConfigError, NoPathError
    from gapath.results import atomic_write, dumps, versions

    if args.obstacles < 0 or args.stationary < 0:
        raise ConfigError("--obstacles and --stationary must be >= 0")
    car = car_from_args(args)
    with cli_vocabulary():
        robot = Robot(car=car, sensor_range=args.sensor_range, fov=args.fov)
        settings = SimSettings(
            dt=args.dt, max_time=args.max_time, predict_bounces=args.prediction == "bounce"
        )
    obstacles = dict(
        n_stationary=args.stationary,
        n_crossers=(args.obstacles + 1) // 2,
        n_wanderers=args.obstacles // 2,
        robot_speed=robot.speed,
        sensor_range=robot.sensor_range,
        speed_range=_speed_range(args.obstacle_speed),
    )
    with cli_vocabulary():
        try:
            sc = make_scenario(
                args.map, args.seed, map_seed=args.map_seed, start=args.start, goal=args.goal, **obstacles
            )
        except ConfigError as exc:  # no path between start and goal: exit status 1, not 2
            if isinstance(exc.__context__, NoPathError):
                raise NoPathError(str(exc)) from None
            raise
    planner_kw = planner_settings(args.planner, args)
    _check_planner_flags(args, sc.workspace, robot.car, planner_kw)
    compile_s = _warm_up_simulation(args.planner, planner_kw, robot, settings)
    with cli_vocabulary():
        planner = make_planner(args.planner, **planner_kw)
        start = sc.start
        if args.heading is not None:
            start = (start[0], start[1], planner_heading(sc.workspace, args.heading))
        res = simulate(sc.workspace, planner, robot, sc.stationary, sc.moving, settings, start, args.seed)
    out = Path(args.out)
    data = res.to_json()
    data["stationary"] = [{"cells": o.cells.tolist(), "appear_at": o.appear_at} for o in sc.stationary]
    data["moving"] = [
        {
            "position": o.position.tolist(),
            "velocity": o.velocity.tolist(),
            "radius": o.radius,
            "mode": o.mode,
            "appear_at": o.appear_at,
        }
        for o in sc.moving
    ]
    if res.obstacles is not None:
        data["obstacle_positions"] = np.round(np.nan_to_num(res.obstacles, nan=-1e9), 4).tolist()
    atomic_write(out / "trajectory.json", dumps(data) + "\n")
    c = robot.car
    workspace_settings = sc.workspace.describe()
    del workspace_settings["corner_cutting"]  # the simulation's grid planners never cut corners
    summary = {
        **res.summary(),
        "settings": {
            **workspace_settings,
            "planner": args.planner,
            "seed": args.seed,
            "map_seed": args.map_seed,
            "obstacles": obstacles,
            "robot": {
                "wheelbase": c.wheelbase,
                "max_steer_deg": round(math.degrees(c.max_steer), 6),
                "speed": c.speed,
                "radius": c.radius,
                "sensor_range": robot.sensor_range,
                "fov_deg": robot.fov,
            },
            "dt": settings.dt,
            "prediction": args.prediction,
        },
        "versions": versions(),
        "compile_s": round(compile_s, 4),
    }
    atomic_write(out / "summary.json", dumps(summary, indent=1, sort_keys=True, default=float) + "\n")
    written = ["trajectory.json", "summary.json"]
    if not args.no_plots:
        from gapath.dynamic.plots import plot_run
        from gapath.plotting import png_bytes

        atomic_write(out / "run.png", png_bytes(plot_run(sc.workspace, res, sc.stationary)))
        written.append("run.png")
    if args.gif:
        from gapath.dynamic.plots import animate_run

        animate_run(sc.workspace, res, sc.stationary, out / "run.gif")
        written.append("run.gif")
    if not args.quiet:
        status = "reached the goal" if res.success else f"FAILED ({res.reason})"
        print(
            f"{sc.workspace!r}\n{args.planner}: {status} after {res.time:.1f} s, driven "
            f"{res.path_length:.2f} (direct {res.direct_distance:.2f}); global plan "
            f"{1000 * res.global_plan_seconds:.1f} ms, {res.n_replans} replans "
            f"({1000 * sum(res.replan_seconds):.1f} ms), {res.count('halt')} halts (numba "
            f"warm-up {1000 * compile_s:.0f} ms not counted)\n"
            f"wrote {out}/" + ", ".join(written)
        )
    if not res.success:  # the run happened and failed: exit status 1
        import sys

        print(
            f"gapath: the robot did not reach the goal: {res.reason} (t = {res.time:.1f} s; "
            f"written to {out}/)",
            file=sys.stderr,
        )
        return EXIT_NO_RESULT
    return 0
