"""Plots of fronts and paths (matplotlib).

The module leaves the matplotlib backend alone, so the figures show in a
notebook's inline backend; ``gapath`` commands select Agg (files only).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import matplotlib.pyplot as plt
import numpy as np

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from gapath.front import PathFront
    from gapath.workspace import Workspace

#: (label, colour) of the marked paths.
MARKS = {"shortest": "tab:blue", "safest": "tab:green", "knee": "tab:red"}

#: Units of the objectives in axis labels (``length`` is in the map's units:
#: see :func:`objective_label`).
OBJECTIVE_UNITS = {
    "vulnerability": "obstacle potential, unitless",
    "smoothness": "total turn, rad",
    "turning": "total turn, rad",
    "elevation": "mean normalised elevation, 0-1",
    "solar": "solar cost summed over the steps",
    "risk": "mean risk, unitless",
}


def length_unit(workspace=None) -> str:
    """The unit of lengths on ``workspace``: metres with a world frame (ROS
    maps), cells when a cell is 1, else cell-size units."""
    if workspace is None:
        return "cell-size units"
    if getattr(workspace, "frame", None) is not None:
        return "m"
    return "cells" if workspace.cell_size == 1.0 else f"units of {workspace.cell_size:g} per cell"


def objective_label(name: str, workspace=None) -> str:
    """An axis label with units for objective ``name``.

    Examples
    --------
    >>> objective_label("smoothness")
    'smoothness (total turn, rad)'
    """
    if name in ("length", "clearance"):
        return f"{name} ({length_unit(workspace)})"
    unit = OBJECTIVE_UNITS.get(name)
    return f"{name} ({unit})" if unit else name


def label_map_axes(ax, workspace, scale: float = 1.0, unit: str | None = None) -> None:
    """Axis labels (with units) of a map drawn with cell ``(row, col)`` at
    ``(col * scale, row * scale)``, row 0 at the top.

    A workspace with a world frame (ROS maps) gets ticks in metres in its
    map frame (x along the columns, y up the image); others are labelled in
    cells (``scale == 1``) or, with ``scale = cell_size``, in ``unit``
    (default :func:`length_unit`).
    """
    frame = getattr(workspace, "frame", None)
    if frame is not None and frame.yaw == 0.0:
        from matplotlib.ticker import MaxNLocator

        x0, y0, x1, y1 = frame.extent()
        res, h = frame.resolution, frame.height
        xs = [v for v in MaxNLocator(nbins=6).tick_values(x0, x1) if x0 <= v <= x1]
        ys = [v for v in MaxNLocator(nbins=6).tick_values(y0, y1) if y0 <= v <= y1]
        ax.set_xticks([((v - frame.x) / res - 0.5) * scale for v in xs], [f"{v:g}" for v in xs])
        ax.set_yticks([(h - (v - frame.y) / res - 0.5) * scale for v in ys], [f"{v:g}" for v in ys])
        ax.set_xlabel("x (m, map frame)")
        ax.set_ylabel("y (m, map frame)")
        return
    if unit is None and scale == 1.0:
        ax.set_xlabel("column (cells)")
        ax.set_ylabel("row (cells, 0 at the top)")
    else:
        unit = unit or length_unit(workspace)
        ax.set_xlabel(f"x = column x cell size ({unit})")
        ax.set_ylabel(f"y = row x cell size ({unit}, 0 at the top)")


def plot_front(
    front: PathFront,
    ax: Axes | None = None,
    reference: np.ndarray | None = None,
    title: str | None = None,
    workspace: Workspace | None = None,
) -> Axes:
    """Scatter the front's first two objectives (a third one as colour),
    with the marked paths highlighted and an optional reference front;
    axis labels carry the units (lengths in the units of ``workspace``).

    Returns
    -------
    The matplotlib ``Axes``.
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(5.5, 4.5))
    F = front.F
    names = front.objectives
    if reference is not None and len(reference):
        R = np.asarray(reference)
        ax.scatter(
            R[:, 0],
            R[:, 1] if R.shape[1] > 1 else np.zeros(len(R)),
            s=40,
            facecolors="none",
            edgecolors="0.6",
            label="reference",
        )
    if len(F):
        y = F[:, 1] if F.shape[1] > 1 else np.zeros(len(F))
        if F.shape[1] > 2:
            sc = ax.scatter(F[:, 0], y, s=12, c=F[:, 2], cmap="viridis", label="front", zorder=3)
            plt.colorbar(sc, ax=ax, label=objective_label(names[2], workspace))
        else:
            ax.scatter(F[:, 0], y, s=12, c="k", label="front", zorder=3)
        for label, i in front.marked().items():
            ax.scatter([F[i, 0]], [y[i]], s=90, marker="*", color=MARKS[label], label=label, zorder=4)
    ax.set_xlabel(objective_label(names[0], workspace))
    ax.set_ylabel(objective_label(names[1], workspace) if len(names) > 1 else "(one objective)")
    ax.set_title(title or f"front ({len(F)} paths)")
    if ax.get_legend_handles_labels()[0]:  # an empty front has nothing to label
        ax.legend(fontsize=8)
    return ax


def plot_paths(
    workspace: Workspace, front: PathFront, ax: Axes | None = None, title: str | None = None
) -> Axes:
    """The map with the shortest, the safest and the knee path of ``front``,
    axes in cells, or in metres in the map frame of a ROS map.

    Returns
    -------
    The matplotlib ``Axes``.
    """
    if ax is None:
        h, w = workspace.shape
        scale = 6.0 / max(h, w)
        _, ax = plt.subplots(figsize=(max(3.0, w * scale) + 1, max(3.0, h * scale) + 0.6))
    ax.imshow(workspace.occ, cmap="Greys", vmin=0, vmax=1.4, interpolation="nearest")
    for label, i in front.marked().items():
        p = np.asarray(front.paths[i])
        ax.plot(p[:, 1], p[:, 0], "-", color=MARKS[label], lw=2, label=label, alpha=0.85)
    (sr, sc), (gr, gc) = workspace.start, workspace.goal
    ax.plot([sc], [sr], "o", color="tab:orange", ms=8, label="start")
    ax.plot([gc], [gr], "s", color="tab:purple", ms=8, label="goal")
    label_map_axes(ax, workspace)
    ax.set_title(title or workspace.name)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    return ax


def png_bytes(ax) -> bytes:
    """The figure of ``ax`` as PNG bytes; the figure is closed."""
    import io

    fig = ax.figure
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    return buf.getvalue()
