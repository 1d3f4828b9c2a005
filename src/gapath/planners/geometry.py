"""Continuous geometry on the occupancy grid: the public home of the
numba kernels of :mod:`gapath.planners._geometry`.

Used by the hybrid A* (:mod:`gapath.planners.hybrid_astar`), RRT
(:mod:`gapath.planners.rrt`), the dynamic simulation (:mod:`gapath.dynamic`)
and its scenarios (:mod:`gapath.dynamic.scenarios`); import them from here,
not from the private module.

Frame (cell units)
    A point is ``(x, y)`` with ``x`` the column axis and ``y`` the row axis:
    the centre of cell ``(row, col)`` is ``(x, y) = (col, row)``. A heading
    ``theta`` is measured from the ``+x`` axis (east) towards ``+y`` (south,
    down the image). The kernels work in cell units; the planners' public
    functions scale by ``cell_size``.

Collision model
    The robot is a closed disc of radius ``r`` (``r = 0`` is a point): it
    collides when it meets an obstacle cell (a closed square) or leaves the
    map ``[-1/2, W - 1/2] x [-1/2, H - 1/2]``. A path is checked at samples
    at most ``ds`` apart with the radius :func:`sweep_radius` ``(r, ds)``, so
    the disc swept along the whole path is collision-free, not only the
    samples.

Kernels
    ``disc_free``, ``segment_free``, ``first_blocked``, ``center_blocked``
    (collision checks); ``point_clearance``, ``path_clearance``;
    ``arc_point``, ``sample_arcs``, ``arcs_free`` (arcs of constant
    curvature); ``dubins``, ``turn_to_point`` (shortest car curves);
    ``grid_dijkstra`` (8-connected distances to a cell); ``mod2pi``,
    ``angle_diff`` (angles). Each takes plain floats and numpy arrays.

Examples
--------
>>> import numpy as np
>>> occ = np.zeros((5, 5), dtype=bool)
>>> occ[2, 2] = True
>>> bool(disc_free(occ, 0.0, 0.0, 0.4)), bool(disc_free(occ, 2.0, 1.0, 0.6))
(True, False)
>>> bool(segment_free(occ, 0.0, 0.0, 4.0, 0.0, 0.3, 0.25))
True
"""

from gapath.planners._geometry import (
    angle_diff,
    arc_point,
    arcs_free,
    center_blocked,
    disc_free,
    dubins,
    first_blocked,
    grid_dijkstra,
    mod2pi,
    path_clearance,
    point_clearance,
    sample_arcs,
    segment_free,
    sweep_radius,
    turn_to_point,
)

__all__ = [
    "angle_diff",
    "arc_point",
    "arcs_free",
    "center_blocked",
    "disc_free",
    "dubins",
    "first_blocked",
    "grid_dijkstra",
    "mod2pi",
    "path_clearance",
    "point_clearance",
    "sample_arcs",
    "segment_free",
    "sweep_radius",
    "turn_to_point",
]
