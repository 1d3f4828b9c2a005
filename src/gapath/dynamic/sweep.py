"""A difficulty sweep of the dynamic study: which planner still reaches the
goal when the obstacles get more numerous and faster and the sensor shorter
and narrower.

The study of :mod:`gapath.studies.dynamic` (NO-MOPP's Tables I-IV) runs
a setting in which every planner, plain grid A* included, succeeds (issue
17). :func:`sweep` varies one factor at a time around a hard *base* setting:

``moving``
    moving obstacles (half of them, rounded up, timed to cross the robot's
    reference path, the rest wandering);
``speed``
    their speed relative to the robot's: speeds are drawn uniformly in
    ``[0.8, 1.2] x speed x robot speed``;
``sensor``
    sensor range (world units);
``fov``
    half-angle of the field of view, degrees (NO-MOPP's +-45, +-90, +-180).

Every run ``i`` of a setting uses *scenario seed* ``seeds[i]`` for the map
(a new maze or warehouse per seed), the dynamic obstacles and the planner's
random numbers, so that all planners meet the same obstacles on the same
map, and a setting is judged over several maps rather than one chosen
instance. Moving obstacles are predicted on straight lines (the default of
:class:`~gapath.dynamic.SimSettings`) unless ``sim`` says otherwise.

:func:`aggregate_sweep` summarises every (scenario, setting, planner): runs,
successes, collisions, blocked, timeouts, halts per run (median, min, max)
and the driven length of the successful runs (median, min, max), also over
the straight-line distance and over the *grid optimum* (8-connected A* on
the static map, no corner cutting) of each run's map. :func:`verdicts` says,
per setting, whether the hybrid A* (NO-MOPP) is ahead of the others where
any planner fails.
"""

from __future__ import annotations

import io
import math
import statistics
import time
from dataclasses import dataclass, field, replace

from gapath.dynamic import Robot, SimSettings, make_planner, simulate
from gapath.dynamic.scenarios import SCENARIOS as MAPS
from gapath.dynamic.scenarios import make_scenario
from gapath.errors import ConfigError
from gapath.planners.astar import astar
from gapath.results import atomic_write, dumps

__all__ = [
    "BASE",
    "LEVELS",
    "SCENARIOS",
    "SEEDS",
    "SWEEP_PLANNERS",
    "Difficulty",
    "SweepResult",
    "aggregate_sweep",
    "blocks",
    "keep_blocks",
    "section",
    "splice_block",
    "one_at_a_time",
    "sweep",
    "sweep_markdown",
    "sweep_png",
    "verdicts",
    "wilson",
    "mcnemar_p",
]

#: Planners of the sweep: NO-MOPP-style hybrid A* with replanning, RRT*,
#: grid A*, D* Lite.
SWEEP_PLANNERS = ("hybrid-astar", "rrt-star", "astar", "dstar-lite")
#: The factors, in table order.
FACTORS = ("moving", "speed", "sensor", "fov")
#: Units of the factors, for tables.
FACTOR_TEXT = {
    "moving": "moving obstacles",
    "speed": "obstacle speed / robot speed",
    "sensor": "sensor range (m)",
    "fov": "field of view (+- deg)",
}


@dataclass(frozen=True)
class Difficulty:
    """One setting of the sweep.

    Parameters
    ----------
    moving : int, default 10
        Moving obstacles: ``ceil(moving / 2)`` crossers, the rest wanderers.
    speed : float, default 1.0
        Obstacle speed relative to the robot's (centre of a +-20 % range).
    sensor : float, default 4.0
        Sensor range, world units.
    fov : float, default 90.0
        Field-of-view half-angle, degrees.
    stationary : int, default 3
        Stationary obstacles appearing on the reference path.

    Raises
    ------
    ConfigError
        On a negative count, a speed or sensor range <= 0 or a field of
        view outside (0, 180].
    """

    moving: int = 10
    speed: float = 1.0
    sensor: float = 4.0
    fov: float = 90.0
    stationary: int = 3

    def __post_init__(self):
        for name in ("moving", "stationary"):
            v = getattr(self, name)
            if not (isinstance(v, int) and v >= 0):
                raise ConfigError(f"{name} must be an integer >= 0, got {v!r}")
        if not (math.isfinite(self.speed) and self.speed > 0):
            raise ConfigError(f"speed (relative to the robot) must be > 0, got {self.speed!r}")
        if not (math.isfinite(self.sensor) and self.sensor > 0):
            raise ConfigError(f"sensor range must be > 0, got {self.sensor!r}")
        if not 0 < self.fov <= 180:
            raise ConfigError(f"fov (half-angle, degrees) must be in (0, 180], got {self.fov!r}")

    def obstacles(self, robot_speed: float) -> dict:
        """Keyword arguments of :func:`gapath.dynamic.scenarios.dynamic_obstacles`."""
        u = self.speed * robot_speed
        return {
            "n_stationary": self.stationary,
            "n_crossers": (self.moving + 1) // 2,
            "n_wanderers": self.moving // 2,
            "robot_speed": robot_speed,
            "sensor_range": self.sensor,
            "speed_range": (0.8 * u, 1.2 * u),
        }

    def as_dict(self) -> dict:
        return {"moving": self.moving, "speed": self.speed, "sensor": self.sensor, "fov": self.fov}


#: The hard base setting of the committed sweep (fixed before any run).
BASE = Difficulty()
#: Its levels per factor (the base's value is one of them).
LEVELS = {
    "moving": (4, 10, 16, 24),
    "speed": (0.5, 1.0, 1.5, 2.0),
    "sensor": (2.5, 4.0, 6.0, 10.0),
    "fov": (45.0, 90.0, 180.0),
}
#: Scenario seeds of the committed sweep.
SEEDS = tuple(range(50))
#: Scenarios of the committed sweep.
SCENARIOS = ("maze", "warehouse")


def wilson(k: int, n: int, z: float = 1.96) -> tuple[float, float]:
    """Wilson score interval of a success share ``k / n`` (95 % by default).

    Examples
    --------
    >>> [round(v, 3) for v in wilson(10, 10)]
    [0.722, 1.0]
    """
    if n <= 0:
        return math.nan, math.nan
    p = k / n
    d = 1 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return max(0.0, c - h), min(1.0, c + h)


def mcnemar_p(b: int, c: int) -> float:
    """Two-sided exact McNemar (sign) test of ``b`` against ``c`` discordant
    pairs: the probability of a split at least this uneven if either
    planner were as likely to be the one that succeeds.

    Examples
    --------
    >>> mcnemar_p(0, 0), round(mcnemar_p(0, 6), 4)
    (1.0, 0.0312)
    """
    n = b + c
    if n == 0:
        return 1.0
    k = min(b, c)
    tail = sum(math.comb(n, i) for i in range(k + 1)) / 2.0**n
    return min(1.0, 2.0 * tail)


def one_at_a_time(base: Difficulty = BASE, levels: dict | None = None) -> list[tuple[str, Difficulty]]:
    """The settings of a one-factor-at-a-time design: ``("base", base)``
    first, then ``(factor, setting)`` for every level that differs from
    the base.

    Examples
    --------
    >>> [(f, d.moving) for f, d in one_at_a_time(levels={"moving": (4, 10)})]
    [('base', 10), ('moving', 4)]
    """
    levels = LEVELS if levels is None else levels
    out = [("base", base)]
    for factor, values in levels.items():
        if factor not in FACTORS:
            raise ConfigError(f"unknown sweep factor {factor!r}; choose from {', '.join(FACTORS)}")
        for v in values:
            v = int(v) if factor == "moving" else float(v)
            if v == getattr(base, factor):
                continue
            out.append((factor, replace(base, **{factor: v})))
    return out


@dataclass(eq=False)
class SweepResult:
    """Runs and aggregates of :func:`sweep`.

    Attributes
    ----------
    rows : list of dict
        One per run: scenario, factor, setting, seed, planner and the run's
        :meth:`~gapath.dynamic.SimResult.summary` with the map's
        ``grid_optimum``.
    table : list of dict
        :func:`aggregate_sweep` of the rows.
    settings : dict
    seconds : float
        Wall-clock time of the sweep.
    """

    rows: list
    table: list
    settings: dict = field(default_factory=dict)
    seconds: float = 0.0

    def jsonl(self) -> str:
        """One JSON line per table row."""
        return "".join(dumps({"benchmark": "dynamic_sweep", **r}) + "\n" for r in self.table)


def _grid_optimum(ws) -> float:

    return float(astar(ws.replace(corner_cutting=False)).length)


def sweep(
    settings=None,
    *,
    scenarios=SCENARIOS,
    planners=SWEEP_PLANNERS,
    seeds=SEEDS,
    robot=None,
    sim=None,
    progress=None,
) -> SweepResult:
    """Simulate every planner on every setting and scenario seed.

    Parameters
    ----------
    settings : list of (str, Difficulty), optional
        Labelled settings; default :func:`one_at_a_time` (``BASE``, ``LEVELS``).
    scenarios : sequence of str, default ("maze", "warehouse")
    planners : sequence of str
        Names for :func:`gapath.dynamic.make_planner`.
    seeds : iterable of int, default 0..49
        Scenario seeds: run ``i`` uses map seed, obstacle seed and planner
        seed ``seeds[i]``.
    robot : Robot, optional
        Car and line of sight; its sensor range and field of view are those
        of each setting.
    sim : SimSettings, optional
    progress : callable, optional
        Called as ``progress(done, total, row)`` after each run.

    Returns
    -------
    SweepResult

    Raises
    ------
    ConfigError
        On no seeds, an unknown planner or scenario, or a bad setting.

    Examples
    --------
    >>> from gapath.dynamic import SimSettings
    >>> one = [("base", Difficulty(moving=1, stationary=0, sensor=6.0, fov=180.0))]
    >>> res = sweep(one, scenarios=("maze",), planners=("astar",), seeds=[0],
    ...             sim=SimSettings(record_world=False))
    >>> [(r["planner"], r["runs"], r["success"] + r["collisions"] + r["blocked"] + r["timeouts"])
    ...  for r in res.table]
    [('astar', 1, 1)]
    """

    settings = one_at_a_time() if settings is None else list(settings)
    seeds = [int(s) for s in seeds]
    if not seeds:
        raise ConfigError("the sweep needs at least one scenario seed")
    for p in planners:
        make_planner(p)  # validates the name
    for scen in scenarios:
        if scen not in MAPS:
            raise ConfigError(f"unknown scenario {scen!r}; choose from {', '.join(MAPS)}")
    for item in settings:
        if not (isinstance(item, tuple) and len(item) == 2 and isinstance(item[1], Difficulty)):
            raise ConfigError(f"settings must be (label, Difficulty) pairs, got {item!r}")
    robot = Robot() if robot is None else robot
    sim = SimSettings(record_world=False) if sim is None else sim
    t0 = time.perf_counter()
    maps = {}
    for scen in scenarios:
        for s in seeds:
            ws = MAPS[scen](s)
            maps[scen, s] = (ws, _grid_optimum(ws))
    # warm-up: load or compile every kernel before the runs
    ws0 = maps[scenarios[0], seeds[0]][0]
    for p in planners:
        sc = make_scenario(ws0, seeds[0], **settings[0][1].obstacles(robot.speed))
        simulate(
            ws0, make_planner(p), robot, sc.stationary, sc.moving, replace(sim, max_time=5.0), sc.start, 0
        )
    rows = []
    total = len(scenarios) * len(settings) * len(seeds) * len(planners)
    for scen in scenarios:
        for label, diff in settings:
            rb = replace(robot, sensor_range=diff.sensor, fov=diff.fov)
            for s in seeds:
                ws, optimum = maps[scen, s]
                sc = make_scenario(ws, s, **diff.obstacles(robot.speed))
                for p in planners:
                    res = simulate(ws, make_planner(p), rb, sc.stationary, sc.moving, sim, sc.start, s)
                    row = {
                        "scenario": scen,
                        "factor": label,
                        **diff.as_dict(),
                        "scenario_seed": s,
                        **res.summary(),
                        "grid_optimum": optimum,
                        "final_speed": float(res.trajectory[-1, 4]) if len(res.trajectory) else 0.0,
                    }
                    rows.append(row)
                    if progress is not None:
                        progress(len(rows), total, row)
    from dataclasses import asdict

    return SweepResult(
        rows=rows,
        table=aggregate_sweep(rows),
        seconds=time.perf_counter() - t0,
        settings={
            "scenarios": list(scenarios),
            "planners": list(planners),
            "seeds": seeds,
            "settings": [(label, d.as_dict()) for label, d in settings],
            "sim": {k: v for k, v in asdict(sim).items() if k != "record_world"},
            "robot_speed": robot.speed,
        },
    )


def _stats(values, digits=3):
    if not values:
        return math.nan, math.nan, math.nan
    return (
        round(float(statistics.median(values)), digits),
        round(float(min(values)), digits),
        round(float(max(values)), digits),
    )


def aggregate_sweep(rows) -> list[dict]:
    """One row per (scenario, setting, planner), in the order first met.

    ``success + collisions + blocked + timeouts == runs``; lengths are over
    the successful runs (NaN when there are none); halts are per run;
    ``collisions_stopped`` counts the collisions in which the robot was
    standing or backing off (the obstacle ran into it).
    """
    keys = []
    groups = {}
    for r in rows:
        k = (r["scenario"], r["factor"], r["moving"], r["speed"], r["sensor"], r["fov"], r["planner"])
        if k not in groups:
            keys.append(k)
            groups[k] = []
        groups[k].append(r)
    out = []
    for k in keys:
        runs = groups[k]
        ok = [r for r in runs if r["success"]]
        length = _stats([r["path_length"] for r in ok])
        over_direct = _stats([r["path_length"] / r["direct_distance"] for r in ok], 4)
        over_opt = _stats([r["path_length"] / r["grid_optimum"] for r in ok], 4)
        halts = _stats([r["halts"] for r in runs], 1)
        out.append(
            {
                "scenario": k[0],
                "factor": k[1],
                "moving": k[2],
                "speed": k[3],
                "sensor": k[4],
                "fov": k[5],
                "planner": k[6],
                "runs": len(runs),
                "success": len(ok),
                "success_pct": round(100.0 * len(ok) / len(runs), 1),
                "success_ci95_pct": [round(100.0 * v, 1) for v in wilson(len(ok), len(runs))],
                "collisions": sum(r["reason"] == "collision" for r in runs),
                "collisions_stopped": sum(
                    r["reason"] == "collision" and r.get("final_speed", 1.0) <= 0.0 for r in runs
                ),
                "blocked": sum(r["reason"] == "blocked" for r in runs),
                "timeouts": sum(r["reason"] == "timeout" for r in runs),
                "halts_median": halts[0],
                "halts_min": halts[1],
                "halts_max": halts[2],
                "length_median": length[0],
                "length_min": length[1],
                "length_max": length[2],
                "length_over_direct_median": over_direct[0],
                "length_over_optimum_median": over_opt[0],
                "length_over_optimum_min": over_opt[1],
                "length_over_optimum_max": over_opt[2],
                "seeds": sorted({r["scenario_seed"] for r in runs}),
            }
        )
    return out


def _setting_key(r):
    return (r["scenario"], r["factor"], r["moving"], r["speed"], r["sensor"], r["fov"])


def verdicts(rows, lead: str = "hybrid-astar") -> list[dict]:
    """Per (scenario, setting) of a sweep's run ``rows``: whether any planner
    failed; ``lead``'s successes against the best other planner's;
    ``ahead`` (at least as many successes as every other planner) and
    ``strictly_ahead`` (more than each); and per other planner the paired
    comparison over the same scenario seeds: ``lead_only`` (seeds where only
    ``lead`` succeeded), ``other_only`` and the exact McNemar ``p``.
    """
    by = {}
    for r in rows:
        by.setdefault(_setting_key(r), {}).setdefault(r["planner"], {})[r["scenario_seed"]] = bool(
            r["success"]
        )
    out = []
    for k, per in by.items():
        if lead not in per:
            continue
        succ = {p: sum(v.values()) for p, v in per.items()}
        any_fail = any(not ok for v in per.values() for ok in v.values())
        pairs = {}
        for p, v in per.items():
            if p == lead:
                continue
            common = set(v) & set(per[lead])
            b = sum(per[lead][s] and not v[s] for s in common)
            c = sum(v[s] and not per[lead][s] for s in common)
            pairs[p] = {"lead_only": b, "other_only": c, "p": round(mcnemar_p(b, c), 4)}
        others = [succ[p] for p in pairs]
        out.append(
            {
                "scenario": k[0],
                "factor": k[1],
                "moving": k[2],
                "speed": k[3],
                "sensor": k[4],
                "fov": k[5],
                "runs": len(per[lead]),
                "any_failure": any_fail,
                "lead": lead,
                "lead_success": succ[lead],
                "best_other": max(others) if others else None,
                "ahead": all(succ[lead] >= v for v in others),
                "strictly_ahead": all(succ[lead] > v for v in others),
                "paired": pairs,
            }
        )
    return out


def _level(r) -> str:
    f = r["factor"]
    if f == "base":
        return "base"
    v = r[f]
    return f"{FACTOR_TEXT[f]} = {v:g}"


def _fmt(v, d=2):
    if isinstance(v, float) and math.isnan(v):
        return "-"
    return f"{v:.{d}f}"


def _range(r, key, d):
    """``median (min-max)`` of ``key``, or ``-`` without values."""
    if isinstance(r[f"{key}_median"], float) and math.isnan(r[f"{key}_median"]):
        return "-"
    return f"{_fmt(r[f'{key}_median'], d)} ({_fmt(r[f'{key}_min'], d)}-{_fmt(r[f'{key}_max'], d)})"


def sweep_markdown(result: SweepResult, labels: dict | None = None, lead: str = "hybrid-astar") -> str:
    """The sweep as markdown (no heading): per scenario, a summary table
    (successes per planner and the paired verdict for ``lead``) and the full
    table (success with its 95 % Wilson interval, failure reasons, halts,
    driven length and length over the grid optimum)."""
    labels = labels or {}
    planners = result.settings.get("planners") or sorted({r["planner"] for r in result.table})
    ver = {_setting_key(v): v for v in verdicts(result.rows, lead)}
    lines = []
    for scen in result.settings.get("scenarios", sorted({r["scenario"] for r in result.table})):
        rows = [r for r in result.table if r["scenario"] == scen]
        if not rows:
            continue
        settings = []
        for r in rows:
            if _setting_key(r) not in settings:
                settings.append(_setting_key(r))
        cell = {(_setting_key(r), r["planner"]): r for r in rows}
        others = [p for p in planners if p != lead]
        lines += [
            f"### {scen}: successes (collisions) out of {rows[0]['runs']} scenario seeds",
            "",
            "| setting | "
            + " | ".join(labels.get(p, p) for p in planners)
            + f" | {labels.get(lead, lead)} ahead? | paired: {labels.get(lead, lead)} only / other only (p) |",
            "|---|" + "---|" * len(planners) + "---|---|",
        ]
        for k in settings:
            first = cell[k, planners[0]]
            v = ver.get(k)
            if v is None:
                verdict, pair = "-", "-"
            else:
                verdict = (
                    "no failures"
                    if not v["any_failure"]
                    else (
                        "**yes, strictly**"
                        if v["strictly_ahead"]
                        else ("yes (tie)" if v["ahead"] else "**no**")
                    )
                )
                pair = "; ".join(
                    f"{labels.get(p, p)} {v['paired'][p]['lead_only']}/{v['paired'][p]['other_only']} "
                    f"({v['paired'][p]['p']:.2g})"
                    for p in others
                    if p in v["paired"]
                )
            lines.append(
                f"| {_level(first)} | "
                + " | ".join(
                    f"{cell[k, p]['success']} ({cell[k, p]['collisions']})" if (k, p) in cell else "-"
                    for p in planners
                )
                + f" | {verdict} | {pair} |"
            )
        lines += [
            "",
            f"<details><summary>{scen}: every planner and setting</summary>",
            "",
            "| setting | planner | success (95 % CI) | coll. (robot stopped) / blocked / timeout | "
            "halts per run, median "
            "(range) | driven length m, median (range) | length / grid optimum, median (range) |",
            "|---|---|---|---|---|---|---|",
        ]
        last = None
        for r in rows:
            level = _level(r)
            lo, hi = r["success_ci95_pct"]
            lines.append(
                f"| {level if level != last else ''} | {labels.get(r['planner'], r['planner'])} | "
                f"{r['success']}/{r['runs']} ({lo:.0f}-{hi:.0f} %) | "
                f"{r['collisions']}"
                + (f" ({r['collisions_stopped']})" if "collisions_stopped" in r else "")
                + f" / {r['blocked']} / {r['timeouts']} | "
                f"{_range(r, 'halts', 1)} | {_range(r, 'length', 2)} | {_range(r, 'length_over_optimum', 3)} |"
            )
            last = level
        lines += ["", "</details>", ""]
    return "\n".join(lines) + "\n"


def sweep_png(result: SweepResult, path, labels: dict | None = None):
    """Success per planner against each factor's levels (the base setting
    included in every panel), one row of panels per scenario."""
    import matplotlib.pyplot as plt

    from gapath.dynamic.plots import PLANNER_COLOURS

    labels = labels or {}
    scens = result.settings.get("scenarios") or sorted({r["scenario"] for r in result.table})
    planners = result.settings.get("planners") or sorted({r["planner"] for r in result.table})
    factors = [f for f in FACTORS if any(r["factor"] == f for r in result.table)]
    fig, axes = plt.subplots(
        len(scens),
        max(len(factors), 1),
        figsize=(2.6 * max(len(factors), 1), 2.4 * len(scens)),
        squeeze=False,
    )
    for i, scen in enumerate(scens):
        for j, f in enumerate(factors):
            ax = axes[i][j]
            for k, p in enumerate(planners):
                pts = sorted(
                    (r[f], 100.0 * r["success"] / r["runs"])
                    for r in result.table
                    if r["scenario"] == scen and r["planner"] == p and r["factor"] in (f, "base")
                )
                if pts:
                    xs, ys = zip(*pts)
                    ax.plot(
                        xs,
                        [y + (k - 1.5) * 0.8 for y in ys],  # a small offset keeps ties visible
                        marker="o",
                        ms=3,
                        lw=1.2,
                        color=PLANNER_COLOURS.get(p),
                        label=labels.get(p, p),
                    )
            ax.set_xlabel(FACTOR_TEXT[f], fontsize=8)
            if j == 0:
                ax.set_ylabel(f"{scen}: success %", fontsize=8)
            ax.set_ylim(-5, 105)
            ax.tick_params(labelsize=7)
            ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=6, loc="lower left")
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=72)
    plt.close(fig)
    atomic_write(path, buf.getvalue())
    return path


# ---------------------------------------------------------------------------
# the sweep's section of docs/results/dynamic.md
# ---------------------------------------------------------------------------

_BEGIN = "<!-- begin {name} ({kind}) -->"
_END = "<!-- end {name} -->"
_KINDS = ("generated", "hand-written")


def splice_block(text: str, name: str, body: str, kind: str = "generated") -> str:
    """``text`` with the block ``name`` (between its begin and end markers)
    replaced by ``body``, or ``body`` appended in a new block. ``kind``
    (``"generated"`` or ``"hand-written"``) is written into the begin marker.

    Examples
    --------
    >>> t = splice_block("# doc\\n", "x", "one\\n")
    >>> splice_block(t, "x", "two\\n").count("two"), splice_block(t, "x", "two\\n").count("one")
    (1, 0)
    """
    if kind not in _KINDS:
        raise ConfigError(f"kind must be one of {_KINDS}, got {kind!r}")
    begin, end = _BEGIN.format(name=name, kind=kind), _END.format(name=name)
    block = f"{begin}\n{body.rstrip()}\n{end}\n"
    i = -1
    for k in _KINDS:
        i = text.find(_BEGIN.format(name=name, kind=k))
        if i >= 0:
            break
    j = text.find(end, i + 1) if i >= 0 else -1
    if i >= 0 and j >= 0:
        return text[:i] + block + text[j + len(end) :].lstrip("\n")
    return text.rstrip("\n") + "\n\n" + block


def blocks(text: str) -> dict[str, tuple[str, str]]:
    """The marked blocks of ``text``: ``{name: (kind, body)}`` in order."""
    import re

    out = {}
    pattern = r"<!-- begin (.+?) \((generated|hand-written)\) -->\n(.*?)<!-- end \1 -->"
    for m in re.finditer(pattern, text, re.S):
        out[m.group(1)] = (m.group(2), m.group(3))
    return out


def keep_blocks(old_text: str, new_text: str) -> str:
    """``new_text`` with every marked block of ``old_text`` that it lacks
    appended (so that regenerating one part of a document keeps the other
    parts' generated sections)."""
    have = blocks(new_text)
    for name, (kind, body) in blocks(old_text).items():
        if name not in have:
            new_text = splice_block(new_text, name, body, kind)
    return new_text


def section(result: SweepResult, command: str, labels: dict | None = None, png: str | None = None) -> str:
    """The sweep's section: protocol, the command that regenerates it, a
    summary of the verdicts, the tables and the plot."""
    st = result.settings
    lead = "hybrid-astar"
    labels = labels or {}
    base = dict(st["settings"])["base"] if st.get("settings") else BASE.as_dict()
    levels = {}
    for label, d in st.get("settings", []):
        if label != "base":
            levels.setdefault(label, []).append(d[label])
    ver = verdicts(result.rows, lead)
    fail = [v for v in ver if v["any_failure"]]
    ahead = [v for v in fail if v["ahead"]]
    strict = [v for v in fail if v["strictly_ahead"]]
    behind = [v for v in fail if not v["ahead"]]
    sig_better = sum(
        1
        for v in fail
        if all(q["p"] < 0.05 and q["lead_only"] > q["other_only"] for q in v["paired"].values())
    )
    sig_worse = sum(
        1
        for v in fail
        if any(q["p"] < 0.05 and q["other_only"] > q["lead_only"] for q in v["paired"].values())
    )
    seeds = st.get("seeds", [])
    lines = [
        "## Difficulty sweep",
        "",
        f"Made by `{command}` (`gapath.dynamic.sweep.sweep`, "
        f"{result.seconds / 60:.1f} min wall on the shared 2-core machine). Protocol, fixed before the "
        "sweep was run:",
        "",
        f"* Scenarios {', '.join(st.get('scenarios', []))}; scenario seeds {seeds[0]}..{seeds[-1]} "
        f"({len(seeds)} per setting): seed *s* is the map seed, the obstacle seed and the planner seed, "
        "so every setting is judged over a new map per seed and every planner meets the same map "
        "and obstacles.",
        f"* Planners: {', '.join(labels.get(p, p) for p in st.get('planners', []))}; the study's "
        "robot, planner settings and simulation settings (above); moving obstacles predicted on "
        "straight lines (the paper's eqs. (7)-(10)); 3 stationary obstacles appearing on the "
        "reference path.",
        f"* One factor at a time around a hard base: {base['moving']} moving obstacles (half timed "
        f"to cross the reference path, half wandering), speed {base['speed']:g} x the robot's "
        f"(uniform in +-20 %), sensor range {base['sensor']:g} m, field of view +-{base['fov']:g} deg. "
        "Levels: "
        + "; ".join(
            f"{FACTOR_TEXT[f]} {', '.join(f'{v:g}' for v in sorted(set(vals) | {base[f]}))}"
            for f, vals in levels.items()
        )
        + ".",
        "* Success = goal reached without collision; failures are collisions, blocked (no path "
        "for 15 s) or timeouts. Halts are halt events per run; lengths are driven distances of "
        "the successful runs, also over the grid optimum of each run's map (8-connected A*, no "
        "corner cutting; any-angle paths can be a few per cent shorter, so ratios just below 1 "
        "are possible). *Ahead* = at least as many successes as each other planner; the paired "
        "columns count the seeds where only NO-MOPP or only the other planner succeeded, with "
        "the exact McNemar p.",
        "",
        f"**Verdict.** Some planner failed in {len(fail)} of {len(ver)} settings. NO-MOPP (hybrid A*) "
        f"is ahead (ties included) in {len(ahead)} of them, strictly ahead of all three others in "
        f"{len(strict)}, and significantly better (p < 0.05) than every other planner in "
        f"{sig_better}; it is behind at least one planner in {len(behind)}"
        + (": " + "; ".join(f"{v['scenario']} {_level(v)}" for v in behind) if behind else "")
        + f". In {sig_worse} setting(s) another planner is significantly better.",
        "",
        sweep_markdown(result, labels, lead),
    ]
    if png:
        lines += [f"![{png}]({png})", ""]
    return "\n".join(lines)
