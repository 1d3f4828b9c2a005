"""Pictures and animations of dynamic-environment runs (matplotlib; the
backend is the caller's: ``gapath`` commands select Agg).

Colours follow the NO-MOPP paper's figures: static obstacles black,
dynamic stationary obstacles purple, moving obstacles green, the robot an
arrow.
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Circle, Rectangle

#: Colours of the planners in comparison plots.
PLANNER_COLOURS = {
    "hybrid-astar": "tab:blue",
    "rrt": "tab:orange",
    "rrt-star": "tab:red",
    "astar": "tab:green",
    "dstar-lite": "tab:purple",
}


def plot_map(workspace, ax, stationary=(), appeared=None):
    """Draw the workspace on ``ax``: the static obstacles, the stationary
    obstacles (those ``appeared`` when given, a boolean per obstacle), the
    start and the goal, with axes in the map's unit.

    Parameters
    ----------
    workspace : :class:`gapath.workspace.Workspace`
    ax : matplotlib ``Axes``
    stationary : sequence of :class:`gapath.dynamic.StationaryObstacle`
    appeared : sequence of bool, optional
        Which of ``stationary`` to draw (default: all).
    """
    cs = workspace.cell_size
    h, w = workspace.shape
    ax.imshow(
        workspace.occ,
        cmap="Greys",
        vmin=0,
        vmax=1.0,
        interpolation="nearest",
        extent=(-0.5 * cs, (w - 0.5) * cs, (h - 0.5) * cs, -0.5 * cs),
    )
    for k, o in enumerate(stationary):
        if appeared is not None and not appeared[k]:
            continue
        for r, c in o.cells:
            ax.add_patch(Rectangle(((c - 0.5) * cs, (r - 0.5) * cs), cs, cs, color="purple"))
    (sr, sc), (gr, gc) = workspace.start, workspace.goal
    ax.plot([sc * cs], [sr * cs], "o", color="tab:orange", ms=7, zorder=5)
    ax.plot([gc * cs], [gr * cs], "*", color="gold", mec="k", ms=13, zorder=5)
    ax.set_xlim(-0.5 * cs, (w - 0.5) * cs)
    ax.set_ylim((h - 0.5) * cs, -0.5 * cs)
    from gapath.plotting import label_map_axes

    label_map_axes(ax, workspace, scale=cs, unit=_unit(workspace))


def _unit(workspace) -> str:
    """Length unit of a run: the simulation's world units are metres
    (NO-MOPP's speeds in m/s, a cell ``cell_size`` metres wide)."""
    return "m"


def plot_run(workspace, result, stationary=(), ax=None, title=None, moving=True):
    """The map, the global path (dashed), the driven trajectory, the
    appeared stationary obstacles and the moving obstacles' tracks.

    Returns
    -------
    The matplotlib ``Axes``.
    """
    if ax is None:
        h, w = workspace.shape
        _, ax = plt.subplots(figsize=(6.0 * w / max(h, w) + 0.4, 6.0 * h / max(h, w) + 0.4))
    appeared = [
        any(e["kind"] == "appear" and e.get("obstacle") == f"stationary-{k}" for e in result.events)
        for k in range(len(stationary))
    ]
    plot_map(workspace, ax, stationary, appeared)
    g = result.global_path
    if len(g):
        ax.plot(g[:, 0], g[:, 1], "--", color="0.45", lw=1.2, label="global plan")
    tr = result.trajectory
    ax.plot(tr[:, 1], tr[:, 2], "-", color="tab:blue", lw=2, label="driven")
    if moving and result.obstacles is not None and result.obstacles.size:
        for k in range(result.obstacles.shape[1]):
            ob = result.obstacles[:, k]
            ax.plot(ob[:, 0], ob[:, 1], "-", color="tab:green", lw=0.8, alpha=0.6)
    ax.set_title(
        title or f"{result.planner}: {result.reason}, {result.path_length:.1f} {_unit(workspace)}", fontsize=9
    )
    ax.legend(fontsize=7, loc="lower right")
    return ax


def plot_paths(workspace, results: dict, stationary=(), ax=None, title=None):
    """Driven trajectories of several planners on one scenario run
    (``results`` maps planner names to :class:`gapath.dynamic.SimResult`)."""
    if ax is None:
        h, w = workspace.shape
        _, ax = plt.subplots(figsize=(6.0 * w / max(h, w) + 1.8, 6.0 * h / max(h, w) + 0.4))
    plot_map(workspace, ax, stationary)
    for name, res in results.items():
        tr = res.trajectory
        mark = "" if res.success else f" ({res.reason})"
        ax.plot(
            tr[:, 1],
            tr[:, 2],
            "-",
            lw=1.8,
            color=PLANNER_COLOURS.get(name),
            label=f"{name}: {res.path_length:.1f} {_unit(workspace)}{mark}",
        )
    ax.set_title(title or workspace.name, fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    return ax


def animate_run(
    workspace,
    result,
    stationary=(),
    path=None,
    *,
    fps: int = 8,
    every: float = 0.5,
    size: float = 5.0,
    dpi: int = 64,
):
    """Write a GIF of a run: the robot (arrow), its current plan, its trail,
    the appeared stationary obstacles and the moving obstacles.

    Parameters
    ----------
    workspace, result, stationary
        The run.
    path : str or Path
        The GIF file.
    fps : int
        Frames per second of the GIF.
    every : float
        Simulated seconds between frames.
    size, dpi : float, int
        Figure size (inches) and resolution: keep them small for small files.

    Returns
    -------
    int
        Number of frames written.
    """
    from matplotlib.animation import PillowWriter

    tr = result.trajectory
    dt = float(np.median(np.diff(tr[:, 0]))) if len(tr) > 1 else 0.1
    stride = max(1, int(round(every / dt)))
    frames = list(range(0, len(tr), stride))
    if frames[-1] != len(tr) - 1:
        frames.append(len(tr) - 1)
    h, w = workspace.shape
    fig, ax = plt.subplots(figsize=(size * w / max(h, w), size * h / max(h, w) + 0.3), dpi=dpi)
    appear_t = {}
    for e in result.events:
        if e["kind"] == "appear":
            appear_t[int(e["obstacle"].split("-")[1])] = e["t"]
    plan_t = [t for t, _ in result.paths]
    writer = PillowWriter(fps=fps)
    with writer.saving(fig, str(path), dpi):
        for i in frames:
            ax.clear()
            t = tr[i, 0]
            appeared = [k in appear_t and appear_t[k] <= t for k in range(len(stationary))]
            plot_map(workspace, ax, stationary, appeared)
            j = max(0, int(np.searchsorted(plan_t, t, side="right")) - 1)
            if result.paths:
                p = result.paths[j][1]
                ax.plot(p[:, 0], p[:, 1], ":", color="tab:blue", lw=1)
            ax.plot(tr[: i + 1, 1], tr[: i + 1, 2], "-", color="tab:blue", lw=1.5)
            if result.obstacles is not None:
                for k in range(result.obstacles.shape[1]):
                    q = result.obstacles[i, k]
                    if np.all(np.isfinite(q)):
                        ax.add_patch(Circle(q, 0.4 * workspace.cell_size, color="tab:green"))
            x, y, th = tr[i, 1:4]
            ax.arrow(
                x,
                y,
                1.2 * math.cos(th),
                1.2 * math.sin(th),
                width=0.35,
                head_width=1.1,
                head_length=0.8,
                color="tab:red",
                zorder=6,
                length_includes_head=True,
            )
            ax.set_title(f"{result.planner}  t = {t:5.1f} s", fontsize=8)
            fig.tight_layout(pad=0.3)
            writer.grab_frame()
    plt.close(fig)
    return len(frames)
