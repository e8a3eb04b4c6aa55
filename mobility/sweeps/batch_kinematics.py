"""The names the stacked screw systems import the kinematics by; :class:`mobility.core.kinematics.Kinematics` takes a stack of poses.

Examples
--------
>>> import numpy as np
>>> import mobility
>>> bk = BatchKinematics(mobility.load("mechanisms/parallelogram.yaml"))
>>> bk.residual(np.zeros((2, bk.variable_count))).shape
(2, 6)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..core.kinematics import Kinematics, kinematics
from ..core.model import Mechanism
from ..core.transforms import Motion

__all__ = ["BatchKinematics", "Motion"]

if TYPE_CHECKING:
    BatchKinematics = Kinematics
else:

    def BatchKinematics(mechanism: Mechanism) -> Kinematics:  # noqa: N802 - the class name its users know
        """The kinematics of ``mechanism`` (:func:`mobility.core.kinematics.kinematics`), for a stack of poses."""
        return kinematics(mechanism)
