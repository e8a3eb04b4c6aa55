"""Jacobians of parallel mechanisms by differentiating their finite model (the METROM example).

:func:`parallel_model` turns a mechanism into limbs of finite screws
(:class:`ParallelModel`, with inverse kinematics and moved poses);
:func:`jacobian` gives the actuation and constraint Jacobians at a pose
(:class:`JacobianResult`); :func:`wrench_axis` reads one wrench as its axis.
:mod:`mobility.report.jacobian` formats the result for people.
"""

from .jacobian import Chain, JacobianResult, ParallelModel, jacobian, parallel_model, wrench_axis

__all__ = ["jacobian", "parallel_model", "wrench_axis", "JacobianResult", "ParallelModel", "Chain"]
