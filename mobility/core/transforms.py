"""Rigid transforms: rotations from roll-pitch-yaw or axis-angle, skew matrices.

Conventions (stated once, pinned by tests):

* ``rpy = [roll, pitch, yaw]`` gives ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)``
  (fixed axes x, y, z, as in URDF), angles in radians here; the loader
  converts degrees.
* A transform ``(R, t)`` maps coordinates in a child frame to its parent:
  ``x_parent = R @ x_child + t``.

Examples
--------
>>> import numpy as np
>>> R = rotation_from_rpy((0.0, 0.0, np.pi / 2))
>>> np.round(R @ [1.0, 0.0, 0.0], 12) + 0.0
array([0., 1., 0.])
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "cross",
    "skew",
    "rotation_from_rpy",
    "rotation_from_axis_angle",
    "Transform",
]


def skew(v: np.ndarray) -> np.ndarray:
    """Return the 3x3 matrix ``[v]x`` with ``skew(v) @ u == np.cross(v, u)``.

    Examples
    --------
    >>> import numpy as np
    >>> bool(np.allclose(skew([1, 2, 3]) @ [4, 5, 6], np.cross([1, 2, 3], [4, 5, 6])))
    True
    """
    x, y, z = np.asarray(v, dtype=float)
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product of 3-vectors stored along axis 0 (shape ``(3,)`` or ``(3, n)``, broadcast).

    The same numbers as ``np.cross(a, b, axis=0)``, without its axis
    handling, which costs about twenty times the arithmetic on the tiny arrays
    of screw theory (``tests/test_screws.py`` pins the equality).

    Examples
    --------
    >>> import numpy as np
    >>> cross(np.array([1.0, 0, 0]), np.array([0.0, 1, 0])).tolist()
    [0.0, 0.0, 1.0]
    """
    x = a[1] * b[2] - a[2] * b[1]
    y = a[2] * b[0] - a[0] * b[2]
    z = a[0] * b[1] - a[1] * b[0]
    if np.ndim(x) == 0:
        return np.array((x, y, z))
    out = np.empty((3,) + np.shape(x))
    out[0], out[1], out[2] = x, y, z
    return out


def rotation_from_rpy(rpy: tuple[float, float, float] | np.ndarray) -> np.ndarray:
    """Rotation matrix ``Rz(yaw) @ Ry(pitch) @ Rx(roll)`` from angles in radians."""
    r, p, y = (float(a) for a in rpy)
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def rotation_from_axis_angle(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotation by ``angle`` (radians) about the unit vector ``axis`` (Rodrigues).

    Examples
    --------
    >>> import numpy as np
    >>> R = rotation_from_axis_angle(np.array([0.0, 0.0, 1.0]), np.pi / 2)
    >>> np.round(R @ [1.0, 0.0, 0.0], 12) + 0.0
    array([0., 1., 0.])
    """
    k = skew(axis)
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


@dataclass(frozen=True)
class Transform:
    """A rigid transform ``x_parent = rotation @ x_child + translation``."""

    rotation: np.ndarray
    translation: np.ndarray

    @staticmethod
    def identity() -> "Transform":
        """The identity transform."""
        return Transform(np.eye(3), np.zeros(3))

    def compose(self, child: "Transform") -> "Transform":
        """Return ``self @ child`` (apply ``child`` first, then ``self``)."""
        return Transform(self.rotation @ child.rotation, self.rotation @ child.translation + self.translation)

    def inverse(self) -> "Transform":
        """The inverse transform."""
        rt = self.rotation.T
        return Transform(rt, -rt @ self.translation)

    def apply_point(self, p: np.ndarray) -> np.ndarray:
        """Map a point from the child frame to the parent frame."""
        return self.rotation @ np.asarray(p, dtype=float) + self.translation

    def apply_vector(self, v: np.ndarray) -> np.ndarray:
        """Map a free vector (a direction) from the child frame to the parent frame."""
        return self.rotation @ np.asarray(v, dtype=float)

    def as_matrix(self) -> np.ndarray:
        """The 4x4 homogeneous matrix."""
        m = np.eye(4)
        m[:3, :3] = self.rotation
        m[:3, 3] = self.translation
        return m
