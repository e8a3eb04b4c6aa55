"""Jacobians of parallel mechanisms by differentiating their finite model (the METROM example).

:func:`parallel_model` turns a mechanism into limbs of finite screws;
:func:`jacobian` gives the actuation and constraint Jacobians at a pose.
"""

from .jacobian import JacobianResult, ParallelModel, jacobian, parallel_model

__all__ = ["jacobian", "parallel_model", "JacobianResult", "ParallelModel"]
