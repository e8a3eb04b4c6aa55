"""Sweeps: mobility, singularity and actuation maps across a grid of poses, batched.

:func:`sweep` varies joints (or the end effector's pose coordinates) over a
grid, closes every loop at every point by continuation, and analyses all the
poses together with stacked numpy linear algebra: DOF, pattern, mobility, the
margin of the rank decisions and, for a choice of inputs, the actuation
verdict and conditioning; the :class:`SweepResult` names the singular poses,
where the answer changes, and the seams of full turns.  ``mobility sweep`` is its command line.

Modules, in data-flow order:

``grid``
    the request: coordinates, ranges, units, checked against the mechanism.
``walks``, ``steps``, ``continuation``, ``grid_closure``
    the order each axis is walked in (angles that wrap); one continuation
    step of many poses (the kinematics and Newton's method are
    :mod:`mobility.core.kinematics`', for a stack of poses), with its retries;
    continuation along lines of the grid; the whole grid, with the poses the
    lines missed tried again.
``posed_screws``, ``batch_actuation``, ``batch_transmission``
    each pose's joint twists (their screw systems, counts and margins are
    :mod:`mobility.core.screw_systems`'s, the one engine); the actuation
    verdict and conditioning; the transmission indices, all stacked.
``seams``
    where a walk round a full turn comes back on another pose.
``result``, ``runner``
    :class:`SweepResult`; :func:`sweep` (chunks, threads or dask, progress).
"""

from .grid import DEFAULT_MAX_POSES, POSE_COORDINATES, GridPlan, SweepAxis, parse_vary, plan_grid
from .result import COLUMNS, MarginDip, SingularPose, SweepResult
from .runner import DEFAULT_CHUNK_SIZE, MAX_WORKERS, analyse_joint_variables, sweep

__all__ = [
    "sweep",
    "analyse_joint_variables",
    "SweepResult",
    "SingularPose",
    "MarginDip",
    "SweepAxis",
    "GridPlan",
    "parse_vary",
    "plan_grid",
    "COLUMNS",
    "POSE_COORDINATES",
    "DEFAULT_MAX_POSES",
    "DEFAULT_CHUNK_SIZE",
    "MAX_WORKERS",
]
