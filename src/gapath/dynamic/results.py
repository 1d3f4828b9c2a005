"""What a dynamic run returns: :class:`SimResult`."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(eq=False)
class SimResult:
    """What happened in one run.

    Attributes
    ----------
    success : bool
        The goal was reached without collision.
    reason : str
        ``"goal"``, ``"collision"``, ``"blocked"`` or ``"timeout"``.
    time : float
        Simulated seconds until the end.
    path_length : float
        Distance travelled (world units), backing off included.
    direct_distance : float
        Straight-line start-goal distance.
    global_plan_seconds : float
        Wall-clock time of the first (global) plan.
    replan_seconds : list of float
        Wall-clock time of every later planner call (local replanning).
    global_path : (n, 3) array
        The first plan (empty if there was none).
    trajectory : (T, 5) array
        ``t, x, y, theta, v`` every tick (the start at ``t = 0``).
    events : list of dict
        ``{"t", "kind", ...}``; kinds: ``detect``, ``predict``, ``replan``
        (with ``scope`` local or global and, around moving obstacles,
        ``adopted``: False when the new path was still predicted to
        collide), ``replan-failed``, ``halt``, ``back-off``, ``resume``,
        ``appear``, ``blocked``, ``collision``, ``goal``, ``timeout``.
    paths : list of (t, poses)
        Every accepted plan with the time it was adopted.
    obstacles : (T, M, 2) array or None
        Moving obstacles' positions every tick (NaN while absent).
    """

    success: bool
    reason: str
    time: float
    path_length: float
    direct_distance: float
    global_plan_seconds: float
    replan_seconds: list
    global_path: np.ndarray
    trajectory: np.ndarray
    events: list
    paths: list
    obstacles: np.ndarray | None = None
    planner: str = ""
    seed: int = 0

    @property
    def total_plan_seconds(self) -> float:
        """The paper's T_total = T_global + T_local-replanning."""
        return self.global_plan_seconds + float(sum(self.replan_seconds))

    @property
    def n_replans(self) -> int:
        return len(self.replan_seconds)

    def count(self, kind: str) -> int:
        return sum(1 for e in self.events if e["kind"] == kind)

    @property
    def global_length(self) -> float:
        g = self.global_path
        return float(np.hypot(*np.diff(g[:, :2], axis=0).T).sum()) if len(g) > 1 else 0.0

    def summary(self) -> dict:
        """The scalar figures of the run (JSON-friendly)."""
        return {
            "planner": self.planner,
            "seed": self.seed,
            "success": self.success,
            "reason": self.reason,
            "time_s": round(self.time, 3),
            "path_length": float(self.path_length),
            "global_length": self.global_length,
            "direct_distance": self.direct_distance,
            "global_plan_seconds": self.global_plan_seconds,
            "replan_seconds": float(sum(self.replan_seconds)),
            "total_plan_seconds": self.total_plan_seconds,
            "replans": self.n_replans,
            "halts": self.count("halt"),
            "back_offs": self.count("back-off"),
        }

    def to_json(self) -> dict:
        """Summary, trajectory, events and paths as plain JSON data."""

        def _num(v):
            if isinstance(v, (np.floating, float)):
                return float(v) if math.isfinite(v) else None
            if isinstance(v, np.integer):
                return int(v)
            return v

        return {
            **self.summary(),
            "global_path": np.round(self.global_path, 5).tolist(),
            "trajectory": np.round(self.trajectory, 5).tolist(),
            "events": [{k: _num(v) for k, v in e.items()} for e in self.events],
            "paths": [{"t": round(t, 3), "poses": np.round(p, 5).tolist()} for t, p in self.paths],
            "replan_seconds_each": [float(v) for v in self.replan_seconds],
        }
