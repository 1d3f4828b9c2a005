"""Plots of fronts and paths (matplotlib).

The module leaves the matplotlib backend alone, so the figures show in a
notebook's inline backend; ``gapath`` commands select Agg (files only).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

#: (label, colour) of the marked paths.
MARKS = {"shortest": "tab:blue", "safest": "tab:green", "knee": "tab:red"}


def marked_paths(front) -> dict[str, int]:
    """Indices of the shortest, the safest (least vulnerable) and the knee
    path of a front (objectives not in the front are left out)."""
    marks = {}
    if len(front) == 0:
        return marks
    for label, name in (("shortest", "length"), ("safest", "vulnerability")):
        if name in front.objectives:
            marks[label] = front.best(name)
    marks["knee"] = front.knee()
    return marks


def plot_front(front, ax=None, reference=None, title=None):
    """Scatter the front's first two objectives (a third one as colour),
    with the marked paths highlighted and an optional reference front.

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
        ax.scatter(R[:, 0], R[:, 1] if R.shape[1] > 1 else np.zeros(len(R)), s=40,
                   facecolors="none", edgecolors="0.6", label="reference")
    if len(F):
        y = F[:, 1] if F.shape[1] > 1 else np.zeros(len(F))
        if F.shape[1] > 2:
            sc = ax.scatter(F[:, 0], y, s=12, c=F[:, 2], cmap="viridis", label="front", zorder=3)
            plt.colorbar(sc, ax=ax, label=names[2])
        else:
            ax.scatter(F[:, 0], y, s=12, c="k", label="front", zorder=3)
        for label, i in marked_paths(front).items():
            ax.scatter([F[i, 0]], [y[i]], s=90, marker="*", color=MARKS[label], label=label, zorder=4)
    ax.set_xlabel(names[0])
    ax.set_ylabel(names[1] if len(names) > 1 else "")
    ax.set_title(title or f"front ({len(F)} paths)")
    if ax.get_legend_handles_labels()[0]:          # an empty front has nothing to label
        ax.legend(fontsize=8)
    return ax


def plot_paths(workspace, front, ax=None, title=None):
    """The map with the shortest, the safest and the knee path of ``front``.

    Returns
    -------
    The matplotlib ``Axes``.
    """
    if ax is None:
        h, w = workspace.shape
        scale = 6.0 / max(h, w)
        _, ax = plt.subplots(figsize=(max(3.0, w * scale) + 1, max(3.0, h * scale) + 0.6))
    ax.imshow(workspace.occ, cmap="Greys", vmin=0, vmax=1.4, interpolation="nearest")
    for label, i in marked_paths(front).items():
        p = np.asarray(front.paths[i])
        ax.plot(p[:, 1], p[:, 0], "-", color=MARKS[label], lw=2, label=label, alpha=0.85)
    (sr, sc), (gr, gc) = workspace.start, workspace.goal
    ax.plot([sc], [sr], "o", color="tab:orange", ms=8, label="start")
    ax.plot([gc], [gr], "s", color="tab:purple", ms=8, label="goal")
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
