"""Jacobians of parallel mechanisms by differentiating their finite model (the METROM example).

:func:`~mobility.jacobians.parallel_model.parallel_model` turns a mechanism into limbs of finite screws;
:func:`jacobian` gives the actuation and constraint Jacobians at a pose, the same at every scale of the file.
"""

from .jacobian import JacobianResult, jacobian
from .parallel_model import Chain, ParallelModel, parallel_model
from .wrenches import clean_screw, wrench_axis

__all__ = ["jacobian", "parallel_model", "wrench_axis", "clean_screw", "JacobianResult", "ParallelModel", "Chain"]
