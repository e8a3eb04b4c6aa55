"""Sweeps: mobility, singularity and actuation maps across a grid of poses, batched.

:func:`sweep` varies joints (or the end effector's pose coordinates) over a
grid, closes every loop at every point by continuation, and analyses all the
poses together (the one engine, :mod:`mobility.core.screw_systems`): DOF,
pattern, mobility, rank margins and, for a choice of inputs, the actuation
verdict, conditioning and transmission indices. The :class:`SweepResult`
names the singular poses, the changes and the seams. ``mobility sweep`` is its
command line; docs/sweeps.md tells the method.

Modules, in data-flow order: ``grid`` (the request), ``walks``, ``steps``,
``continuation``, ``grid_closure`` (closing the loops), ``posed_screws``,
``batch_actuation``, ``batch_transmission`` (the analysis, stacked), ``seams``,
``result``, ``runner`` (chunks, threads or dask, progress).
"""

from .grid import DEFAULT_MAX_POSES, POSE_COORDINATES, GridPlan, SweepAxis, parse_vary, plan_grid
from .result import COLUMNS, MarginDip, SingularPose, SweepResult
from .runner import DEFAULT_CHUNK_SIZE, MAX_WORKERS, analyse_joint_variables, sweep

__all__ = ["sweep", "analyse_joint_variables", "SweepResult", "SingularPose", "MarginDip", "SweepAxis", "GridPlan", "parse_vary", "plan_grid",
           "COLUMNS", "POSE_COORDINATES", "DEFAULT_MAX_POSES", "DEFAULT_CHUNK_SIZE", "MAX_WORKERS"]
