"""Rigid transforms: rotations from roll-pitch-yaw or axis-angle, skew matrices, and the exponential map of SE(3).

Conventions (pinned by tests): ``rpy`` gives ``R = Rz(yaw) @ Ry(pitch) @
Rx(roll)`` (fixed axes, as in URDF; radians here, the loader converts
degrees); a transform ``(R, t)`` maps a child frame to its parent,
``x_parent = R @ x_child + t``; twists are ``[w; v]``, angular part first.
"""

from __future__ import annotations

from dataclasses import dataclass

import math
from typing import Sequence

import numpy as np
import numpy.typing as npt

__all__ = ["cross", "skew", "rotation_from_rpy", "rotation_from_axis_angle", "Transform", "twist_matrix", "twist_exp",
           "displacement_log", "rotation_log", "so3_left_jacobian", "bracket", "dexp", "displacement_logs", "rotation_logs",
           "dexps", "Motion", "compose", "rotate", "twist_logs", "rotation_logs_last", "inverse_left_jacobian_times"]


def skew(v: npt.ArrayLike) -> np.ndarray:
    """Return the 3x3 matrix ``[v]x`` with ``skew(v) @ u == np.cross(v, u)`` (of each row of ``v``: ``(k, 3)`` gives ``(k, 3, 3)``).

    Examples
    --------
    >>> bool(np.allclose(skew([1, 2, 3]) @ [4, 5, 6], np.cross([1, 2, 3], [4, 5, 6])))
    True
    """
    v = np.asarray(v, dtype=float)
    out = np.zeros(v.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product of 3-vectors stored along axis 0 (shape ``(3,)`` or ``(3, n)``, broadcast).

    The numbers of ``np.cross(a, b, axis=0)`` without its axis handling (twenty
    times the arithmetic on tiny arrays; ``tests/test_screws.py`` pins them).

    Examples
    --------
    >>> cross(np.array([1.0, 0, 0]), np.array([0.0, 1, 0])).tolist()
    [0.0, 0.0, 1.0]
    """
    return np.array((a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]))


def rotation_from_rpy(rpy: Sequence[float] | np.ndarray) -> np.ndarray:
    """Rotation matrix ``Rz(yaw) @ Ry(pitch) @ Rx(roll)`` from angles in radians.

    Examples
    --------
    >>> R = rotation_from_rpy((0.0, 0.0, np.pi / 2))
    >>> np.round(R @ [1.0, 0.0, 0.0], 12) + 0.0
    array([0., 1., 0.])
    """
    r, p, y = (float(a) for a in rpy)
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def rotation_from_axis_angle(axis: npt.ArrayLike, angle: float) -> np.ndarray:
    """Rotation by ``angle`` (radians) about the unit vector ``axis`` (Rodrigues).

    Examples
    --------
    >>> R = rotation_from_axis_angle(np.array([0.0, 0.0, 1.0]), np.pi / 2)
    >>> np.round(R @ [1.0, 0.0, 0.0], 12) + 0.0
    array([0., 1., 0.])
    """
    k = skew(axis)
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


@dataclass(frozen=True)
class Transform:
    """A rigid transform ``x_parent = rotation @ x_child + translation``.

    Examples
    --------
    >>> Transform(np.eye(3), np.array([1.0, 0, 0])).inverse().apply_point((1, 0, 0)).tolist()
    [0.0, 0.0, 0.0]
    """

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

    def apply_point(self, p: npt.ArrayLike) -> np.ndarray:
        """Map a point from the child frame to the parent frame."""
        return self.rotation @ np.asarray(p, dtype=float) + self.translation

    def apply_vector(self, v: npt.ArrayLike) -> np.ndarray:
        """Map a free vector (a direction) from the child frame to the parent frame."""
        return self.rotation @ np.asarray(v, dtype=float)

    def as_matrix(self) -> np.ndarray:
        """The 4x4 homogeneous matrix."""
        m = np.eye(4)
        m[:3, :3] = self.rotation
        m[:3, 3] = self.translation
        return m


# the exponential map of SE(3), in [w; v] coordinates (angular part first)


def twist_matrix(twist: np.ndarray) -> np.ndarray:
    """The 4x4 matrix ``[[skew(w), v], [0, 0]]`` of a twist ``[w; v]``.

    Examples
    --------
    >>> twist_matrix([0, 0, 1, 1, 0, 0])[:3].tolist()
    [[0.0, -1.0, 0.0, 1.0], [1.0, 0.0, -0.0, 0.0], [-0.0, 0.0, 0.0, 0.0]]
    """
    x = np.asarray(twist, dtype=float)
    out = np.zeros((4, 4))
    out[:3, :3] = skew(x[:3])
    out[:3, 3] = x[3:]
    return out


def twist_exp(twist: np.ndarray) -> np.ndarray:
    """The displacement ``exp(twist)`` as a 4x4 homogeneous matrix.

    Examples
    --------
    >>> g = twist_exp([0, 0, np.pi / 2, 0, 0, 0])   # quarter turn about z through the origin
    >>> np.round(g[:3, :3] @ [1, 0, 0], 12).tolist()
    [0.0, 1.0, 0.0]
    """
    x = np.asarray(twist, dtype=float)
    theta = float(np.linalg.norm(x[:3]))
    a, _, _, _ = _coefficients(theta)
    k = skew(x[:3])
    out = np.eye(4)
    out[:3, :3] = np.eye(3) + float(np.sinc(theta / np.pi)) * k + a * (k @ k)
    out[:3, 3] = so3_left_jacobian(x[:3]) @ x[3:]
    return out


_FACTORIALS = tuple(float(math.factorial(k)) for k in range(20))


def _coefficients(theta: float) -> tuple[float, ...]:
    """:func:`_coefficients_many` of one angle, as floats."""
    return tuple(float(c[0]) for c in _coefficients_many(np.array([theta])))


def so3_left_jacobian(w: np.ndarray) -> np.ndarray:
    """The left Jacobian of SO(3), ``sum_k skew(w)^k / (k+1)! = I + A skew(w) + B skew(w)^2``."""
    a, b, _, _ = _coefficients(float(np.linalg.norm(w)))
    k = skew(w)
    return np.eye(3) + a * k + b * (k @ k)


def rotation_log(rot: np.ndarray) -> np.ndarray:
    """Rotation vector of a rotation matrix (closed form away from a half turn, else scipy).

    Examples
    --------
    >>> rotation_log(rotation_from_axis_angle(np.array([0.0, 0.6, 0.8]), 0.5)).round(12).tolist()
    [0.0, 0.3, 0.4]
    """
    return rotation_logs_last(np.asarray(rot, dtype=float)[..., None])[:, 0]


def displacement_log(g: np.ndarray) -> np.ndarray:
    """The twist ``[w; v]`` with ``exp(twist) = g`` (rotation angle below pi).

    Examples
    --------
    >>> x = np.array([0.1, -0.2, 0.3, 1.0, 2.0, -0.5])
    >>> bool(np.allclose(displacement_log(twist_exp(x)), x))
    True
    """
    return displacement_logs(np.asarray(g, dtype=float)[None])[0]


def bracket(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Lie bracket of twists ``[a, b]`` (the twist of ``A B - B A`` for their matrices).

    Examples
    --------
    >>> bracket([1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0]).tolist()
    [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    return np.concatenate([cross(a[:3], b[:3]), cross(a[:3], b[3:]) - cross(b[:3], a[3:])])


def dexp(x: np.ndarray) -> np.ndarray:
    """``sum_k ad(x)^k / (k+1)!``, so that ``d exp(x) exp(-x) = dexp(x) dx`` (closed form).

    In ``[w; v]`` order it is ``[[J, 0], [Q, J]]`` with ``J`` the left Jacobian
    of SO(3) and ``Q`` the series ``sum_k sum_(i+j=k-1) W^i V W^j / (k+1)!``
    summed in closed form (Barfoot and Furgale, IEEE T-RO 2014, eq. 102).
    """
    return dexps(np.asarray(x, dtype=float)[None])[0]


# the same maps for many twists at once (the loops of a mechanism)


_TERMS = np.arange(8)
_ALTERNATING = np.where(_TERMS % 2 == 0, 1.0, -1.0)
_SERIES_NUMERATORS = np.array([np.ones(8), np.ones(8), np.ones(8), _TERMS + 1.0])[:, None, :]
_SERIES_DENOMINATORS = np.array([[_FACTORIALS[2 * m + k] for m in range(8)] for k in (2, 3, 4, 5)])[:, None, :]


def _coefficients_many(theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(1 - cos t)/t^2, (t - sin t)/t^3, (t^2 + 2 cos t - 2)/(2 t^4), (2 t - 3 sin t + t cos t)/(2 t^5)`` of every angle of ``theta`` (1-D).

    Their Taylor series below ``t = 1`` (no cancellation), the closed forms above.
    """
    theta = np.asarray(theta, dtype=float)
    small = theta < 1.0
    steps = np.empty((len(theta), 8))
    steps[:, 0] = 1.0
    steps[:, 1:] = (theta * theta)[:, None]
    signed = np.cumprod(steps, axis=-1) * _ALTERNATING  # +-t2**m
    a, b, c, d = np.cumsum(signed * _SERIES_NUMERATORS / _SERIES_DENOMINATORS, axis=-1)[..., -1]
    if small.all():
        return a, b, c, d
    t = np.where(small, 1.0, theta)
    s, co = np.sin(t), np.cos(t)
    closed = ((1.0 - co) / t**2, (t - s) / t**3, (t**2 + 2.0 * co - 2.0) / (2.0 * t**4), (2.0 * t - 3.0 * s + t * co) / (2.0 * t**5))
    return tuple(np.where(small, series, form) for series, form in zip((a, b, c, d), closed))


def displacement_logs(g: np.ndarray) -> np.ndarray:
    """:func:`displacement_log` of each displacement of a stack ``g`` (shape (k, 4, 4)), shape (k, 6).

    Examples
    --------
    >>> x = np.array([[0.1, -0.2, 0.3, 1.0, 2.0, -0.5], [0, 0, 1e-9, 1, 0, 0]])
    >>> bool(np.allclose(displacement_logs(np.array([twist_exp(r) for r in x])), x, rtol=1e-14, atol=1e-15))
    True
    """
    g = np.moveaxis(np.asarray(g, dtype=float), 0, -1)
    return twist_logs((g[:3, :3], g[:3, 3])).T


def rotation_logs(rot: np.ndarray) -> np.ndarray:
    """Rotation vectors of a stack of rotation matrices ``(k, 3, 3)`` (closed form, scipy near a half turn).

    Examples
    --------
    >>> w = np.array([[0.1, -0.2, 0.3], [0.0, 0.0, 3.1]])
    >>> g = np.stack([twist_exp(np.concatenate([x, [0, 0, 0]])) for x in w])
    >>> bool(np.allclose(rotation_logs(g[:, :3, :3]), w))
    True
    """
    return rotation_logs_last(np.moveaxis(np.asarray(rot, dtype=float), 0, -1)).T


def dexps(x: np.ndarray) -> np.ndarray:
    """:func:`dexp` of each twist of ``x`` (shape (k, 6)), shape (k, 6, 6).

    Examples
    --------
    >>> x = np.array([[0.1, -0.2, 0.3, 1.0, 2.0, -0.5], [2.0, 0.0, 1.0, 0.0, 1.0, 0.0]])
    >>> bool(np.allclose(dexps(x), np.stack([dexp(t) for t in x])))
    True
    """
    x = np.asarray(x, dtype=float)
    _, b, c, d = coefficients = [u[:, None, None] for u in _coefficients_many(np.sqrt(np.einsum("ij,ij->i", x[:, :3], x[:, :3])))]
    w, v = skew(x[:, :3]), skew(x[:, 3:])
    ww, wv, vw = w @ w, w @ v, v @ w
    wvw = wv @ w
    out = np.zeros((len(x), 6, 6))
    out[:, :3, :3] = out[:, 3:, 3:] = np.eye(3) + coefficients[0] * w + b * ww
    out[:, 3:, :3] = 0.5 * v + b * (wv + vw + wvw) + c * (ww @ v + v @ ww - 3.0 * wvw) + d * (wvw @ w + w @ wvw)
    return out


# many displacements, pose index last (the stacked kinematics)
#
# Products are elementwise, summed in a fixed order, so a pose's bits do not depend on the stack around it
# (``einsum`` and ``matmul`` choose inner loops by size, which made a sweep's poses depend on its chunk size).

Motion = tuple[np.ndarray, np.ndarray]
"""Displacements of many poses, pose index last: rotations ``(3, 3, N)`` and translations ``(3, N)``."""


def stacked_dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a . b`` along the first axis (components first), in a fixed order."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def rotate(rot: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``rot v`` for rotations ``(3, 3, N)`` and vectors ``(3, N)`` (or one vector ``(3,)``), in a fixed order."""
    return rot[:, 0] * v[0] + rot[:, 1] * v[1] + rot[:, 2] * v[2]


def compose(g: np.ndarray | None, h: np.ndarray) -> np.ndarray:
    """``g h`` of stacked displacements held as frames ``[R | t]`` ``(3, 4, ...)`` (``None`` is the identity).

    The translation column is ``R t_h + t_g`` summed in the order of :func:`rotate`.
    """
    if g is None:
        return h
    out = g[:, 0, None] * h[0] + g[:, 1, None] * h[1] + g[:, 2, None] * h[2]
    out[:, 3] += g[:, 3]
    return out


def _series(theta: np.ndarray, coefficients: tuple[float, ...], closed) -> np.ndarray:
    """A function of ``theta`` by its Taylor series in ``theta^2`` below 1, by ``closed(theta)`` above."""
    t2 = theta * theta
    out = np.zeros_like(theta)
    for c in reversed(coefficients):
        out = out * t2 + c
    big = theta >= 1.0
    if np.any(big):
        out[big] = closed(theta[big])
    return out


# 1 - x cot x = sum 2^(2k) |B_2k| x^(2k) / (2k)!  with x = t/2, in powers t^(2k-2)
_BERNOULLI = (1 / 6, 1 / 30, 1 / 42, 1 / 30, 5 / 66, 691 / 2730, 7 / 6, 3617 / 510, 43867 / 798)
_COT_SERIES = tuple(b / _FACTORIALS[2 * k] for k, b in enumerate(_BERNOULLI, start=1))


def rotation_logs_last(rot: np.ndarray) -> np.ndarray:
    """Rotation vectors ``(3, N)`` of rotations ``(3, 3, N)`` (closed form, scipy near a half turn)."""
    axis2 = np.array((rot[2, 1] - rot[1, 2], rot[0, 2] - rot[2, 0], rot[1, 0] - rot[0, 1]))  # 2 sin(t) u
    sine2 = np.sqrt(stacked_dot(axis2, axis2))
    theta = np.arctan2(0.5 * sine2, 0.5 * (rot[0, 0] + rot[1, 1] + rot[2, 2] - 1.0))
    out = axis2 / (2.0 * np.sinc(theta / np.pi))
    near_half_turn = theta > 3.0
    if np.any(near_half_turn):
        from scipy.spatial.transform import Rotation  # near a half turn only; slow to import

        out[:, near_half_turn] = Rotation.from_matrix(np.moveaxis(np.asarray(rot[:, :, near_half_turn], dtype=float), -1, 0)).as_rotvec().T
    return out


def inverse_left_jacobian_times(w: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``J_l(w)^-1 x`` for rotation vectors ``w`` ``(3, N)`` and vectors ``x`` ``(3, N)`` or ``(3, k, N)``.

    ``J_l^-1 = I - W/2 + c W^2`` with ``c = (1 - (t/2) cot(t/2)) / t^2``.
    """
    c = _series(np.sqrt(stacked_dot(w, w)), _COT_SERIES, lambda t: (1.0 - 0.5 * t / np.tan(0.5 * t)) / t**2)
    if x.ndim == 3:
        w = w[:, None, :]
    wx = cross(w, x)
    return x - 0.5 * wx + c * cross(w, wx)


def twist_logs(g: Motion) -> np.ndarray:
    """Twists ``[w; v]`` ``(6, N)`` with ``exp(twist) = g`` of stacked displacements."""
    w = rotation_logs_last(g[0])
    return np.concatenate([w, inverse_left_jacobian_times(w, g[1])])
