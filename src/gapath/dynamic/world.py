"""The world of a dynamic run: stationary obstacles that appear, moving obstacles, the robot and the run's settings."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from gapath.errors import ConfigError
from gapath.planners.hybrid_astar import CarModel


@dataclass
class StationaryObstacle:
    """Cells ``(row, col)`` that become obstacles at time ``appear_at`` (s)."""

    cells: np.ndarray
    appear_at: float = 0.0

    def __post_init__(self):
        self.cells = np.asarray(self.cells, dtype=np.int64).reshape(-1, 2)
        if len(self.cells) == 0:
            raise ConfigError("a stationary obstacle needs at least one cell")
        if not (math.isfinite(self.appear_at) and self.appear_at >= 0):
            raise ConfigError(f"appear_at must be >= 0, got {self.appear_at!r}")


MOVING_MODES = ("bounce", "pass")
#: Prediction models of moving obstacles (``SimSettings.predict_bounces``
#: False / True); the first is the default.
PREDICTION_MODELS = ("straight", "bounce")


@dataclass
class MovingObstacle:
    """A disc moving at constant velocity (world units).

    Parameters
    ----------
    position : (x, y)
    velocity : (vx, vy), units per second
    radius : float, default 0.4
    mode : {"bounce", "pass"}
        Reflect off the map edges and obstacles, or pass through everything
        and disappear once outside the map.
    appear_at : float, default 0
        Time it enters the world.
    """

    position: tuple
    velocity: tuple
    radius: float = 0.4
    mode: str = "bounce"
    appear_at: float = 0.0

    def __post_init__(self):
        self.position = np.asarray(self.position, dtype=float).reshape(2).copy()
        self.velocity = np.asarray(self.velocity, dtype=float).reshape(2).copy()
        if not (np.all(np.isfinite(self.position)) and np.all(np.isfinite(self.velocity))):
            raise ConfigError("moving obstacle position and velocity must be finite")
        if not (math.isfinite(self.radius) and self.radius > 0):
            raise ConfigError(f"moving obstacle radius must be > 0, got {self.radius!r}")
        if self.mode not in MOVING_MODES:
            raise ConfigError(f"mode must be one of {MOVING_MODES}, got {self.mode!r}")

    @classmethod
    def from_heading(cls, position, speed: float, heading: float, **kwargs) -> MovingObstacle:
        """An obstacle moving at ``speed`` along ``heading`` (radians)."""
        return cls(position, (speed * math.cos(heading), speed * math.sin(heading)), **kwargs)

    @property
    def speed(self) -> float:
        return float(np.hypot(*self.velocity))

    @property
    def heading(self) -> float:
        return float(math.atan2(self.velocity[1], self.velocity[0]))


@dataclass(frozen=True)
class Robot:
    """The robot: a car with a sensor.

    Parameters
    ----------
    car : CarModel
        Wheelbase, steering, ``speed`` (m/s) and footprint ``radius``.
    sensor_range : float, default 6.0
        World units (>= 0).
    fov : float, default 180
        Half-angle of the field of view in degrees, ``0 < fov <= 180``
        (the paper's +-45, +-90 and +-180).
    line_of_sight : bool, default True
        Static walls hide what is behind them.

    Raises
    ------
    ConfigError
        On a negative sensor range or a field of view outside (0, 180].
    """

    car: CarModel = field(default_factory=CarModel)
    sensor_range: float = 6.0
    fov: float = 180.0
    line_of_sight: bool = True

    def __post_init__(self):
        if not isinstance(self.car, CarModel):
            raise ConfigError(f"car must be a CarModel, got {type(self.car).__name__}")
        try:
            rng = float(self.sensor_range)
            fov = float(self.fov)
        except (TypeError, ValueError):
            raise ConfigError("sensor_range and fov must be numbers") from None
        if not math.isfinite(rng) or rng < 0:
            raise ConfigError(f"sensor_range must be a finite number >= 0, got {self.sensor_range!r}")
        if not (0 < fov <= 180):
            raise ConfigError(f"fov (half-angle, degrees) must be in (0, 180], got {self.fov!r}")
        object.__setattr__(self, "sensor_range", rng)
        object.__setattr__(self, "fov", fov)

    @property
    def speed(self) -> float:
        return self.car.speed

    @property
    def radius(self) -> float:
        return self.car.radius


@dataclass(frozen=True)
class SimSettings:
    """Settings of :class:`Simulation` (seconds and world units).

    Attributes
    ----------
    dt : float, default 0.1
        Tick length.
    max_time : float or None
        Time limit; default ``3 * direct distance / speed + 60``.
    horizon : float, default 6.0
        Collision prediction horizon.
    safety_margin : float, default 0.15
        Added to the sum of the radii for predictions.
    replan_distance : float, default 2.0
        The paper's threshold: replan around a moving obstacle when it is at
        least this far (gap between the discs), otherwise halt.
    halt_time : float, default 1.5
        Halt (do not replan) when the predicted collision is nearer in time.
    sweep_time : float, default 4.0
        Prediction span of a moving obstacle's sweep blocked for replanning.
    replan_cooldown : float, default 1.0
        Least time between two replans for moving obstacles.
    rejoin_margin : float, default 3.0
        Local replans rejoin the path this far beyond the blocked part.
    detour_limit : float, default 4.0
        A replan around a *moving* obstacle is taken only if it is at most
        this much longer than the rest of the current path (otherwise the
        robot keeps its path and waits for the obstacle to pass).
    trail_length : float, default 5.0
        How far back along its driven trajectory the robot may back off.
    memory : float, default 1.0
        A moving obstacle out of view is still predicted for this long.
    goal_tolerance : float, default 0.5
    blocked_patience : float, default 15.0
        Give up (reason "blocked") after this long without any path.
    retry_interval : float, default 1.0
        While blocked, replan this often.
    appear_clearance : float, default 1.0
        A stationary obstacle appears only this far from the robot's disc, a
        moving one only three times as far (gap between the discs).
    predict_bounces : bool, default False
        False (the default, NO-MOPP's eqs. (7)-(10), :func:`path_contact`):
        a tracked moving obstacle is predicted on a straight line at its
        current velocity. True: with the obstacles' own motion model
        (constant velocity reflected off the known map, solved piecewise, to
        within the chord of one tick) -- an oracle the paper does not have,
        kept as an option (``gapath simulate --prediction bounce``).
    record_world : bool, default True
        Record the moving obstacles' positions every tick (for animations).
    """

    dt: float = 0.1
    max_time: float | None = None
    horizon: float = 6.0
    safety_margin: float = 0.15
    replan_distance: float = 2.0
    halt_time: float = 1.5
    sweep_time: float = 4.0
    replan_cooldown: float = 1.0
    rejoin_margin: float = 3.0
    detour_limit: float = 4.0
    trail_length: float = 5.0
    memory: float = 1.0
    goal_tolerance: float = 0.5
    blocked_patience: float = 15.0
    retry_interval: float = 1.0
    appear_clearance: float = 1.0
    predict_bounces: bool = False
    record_world: bool = True

    def __post_init__(self):
        for name in ("dt", "horizon", "goal_tolerance", "retry_interval"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ConfigError(f"{name} must be > 0, got {v!r}")
        for name in (
            "safety_margin",
            "replan_distance",
            "halt_time",
            "sweep_time",
            "replan_cooldown",
            "rejoin_margin",
            "detour_limit",
            "trail_length",
            "memory",
            "blocked_patience",
            "appear_clearance",
        ):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise ConfigError(f"{name} must be >= 0, got {v!r}")
        if self.max_time is not None and not (self.max_time > 0):
            raise ConfigError(f"max_time must be > 0, got {self.max_time!r}")
