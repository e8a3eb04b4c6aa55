"""Jacobians of parallel mechanisms by differentiating their finite model (the METROM example).

:func:`~mobility.jacobians.parallel_model.parallel_model` turns a mechanism into limbs of finite screws
(:class:`ParallelModel`, with inverse kinematics and moved poses);
:func:`jacobian` gives the actuation and constraint Jacobians at a pose
(:class:`JacobianResult`), the same at every scale of the file;
:mod:`~mobility.jacobians.wrenches` reads one wrench as its axis
(:func:`wrench_axis`) and shows a screw's round-off as 0 part by part
(:func:`clean_screw`).  :mod:`mobility.report.jacobian` formats the result for people.
"""

from .jacobian import JacobianResult, jacobian
from .parallel_model import Chain, ParallelModel, parallel_model
from .wrenches import clean_screw, wrench_axis

__all__ = ["jacobian", "parallel_model", "wrench_axis", "clean_screw", "JacobianResult", "ParallelModel", "Chain"]
