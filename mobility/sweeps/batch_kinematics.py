"""``BatchKinematics``, the name the stacked screw systems know :class:`mobility.core.kinematics.Kinematics` by.

>>> import numpy as np, mobility
>>> BatchKinematics(mobility.load("mechanisms/parallelogram.yaml")).residual(np.zeros((2, 4))).shape
(2, 6)
"""

from typing import TYPE_CHECKING

from ..core.kinematics import Kinematics, kinematics
from ..core.transforms import Motion

__all__ = ["BatchKinematics", "Motion"]

if TYPE_CHECKING:
    BatchKinematics = Kinematics
else:
    BatchKinematics = kinematics
