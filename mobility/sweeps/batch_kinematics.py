"""Forward kinematics and loop closure of many poses at once.

The batched counterpart of :mod:`mobility.core.kinematics`, on the same model
and the same variables: one variable per elementary freedom, ``q = 0`` the
file's pose, twists in the normalised coordinates of the file's pose, the
displacement of each link the product of the exponentials of the joints on
its path in the breadth-first spanning tree from the ground, and one loop per
chord, ``rest_a  E_c  rest_b^-1`` (the common part of the two tree paths left
out), whose residual is the logarithm of that product.  Every function takes
``q`` of shape ``(N, n)`` and works on all ``N`` poses with stacked numpy
operations; nothing loops over poses.

The Jacobians are the right-trivialised ones (``dL L^-1`` per unit rate, the
joint twists moved to the current pose), exact at a closed pose; Newton from
a near pose converges on them quadratically for every practical purpose.

Examples
--------
>>> import numpy as np
>>> import mobility
>>> m = mobility.load("mechanisms/parallelogram.yaml")
>>> bk = BatchKinematics(m)
>>> q = np.zeros((2, bk.variable_count)); q[1] = [0.1, -0.1, 0.1, -0.1]   # the parallelogram moves so
>>> float(np.abs(bk.residual(q)).max()) < 1e-15
True
>>> bool(np.allclose(bk.residual(q)[1], mobility.core.kinematics.kinematics(m).residual(q[1])))
True
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial.transform import Rotation

from ..core.kinematics import Kinematics, kinematics
from ..core.model import Mechanism
from ..core.topology import spanning_tree
from ..core.transforms import skew
from ..errors import RequestError

__all__ = ["BatchKinematics", "Evaluation", "Motion", "rotation_logs", "displacement_logs", "left_jacobians"]

Factors = tuple[tuple[int, float], ...]
"""A product of exponentials: ``(variable, sign)`` for each factor, in order."""


Motion = tuple[np.ndarray, np.ndarray]
"""Displacements of many poses, pose index last: rotations ``(3, 3, N)`` and translations ``(3, N)``."""


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


def _a(theta: np.ndarray) -> np.ndarray:
    """``(1 - cos t) / t^2``."""
    return _series(theta, tuple((-1) ** m / math.factorial(2 * m + 2) for m in range(9)), lambda t: (1.0 - np.cos(t)) / t**2)


def _b(theta: np.ndarray) -> np.ndarray:
    """``(t - sin t) / t^3``."""
    return _series(theta, tuple((-1) ** m / math.factorial(2 * m + 3) for m in range(9)), lambda t: (t - np.sin(t)) / t**3)


def _c(theta: np.ndarray) -> np.ndarray:
    """``(1 - (t/2) cot(t/2)) / t^2``, so that the inverse left Jacobian is ``I - W/2 + c W^2``."""
    # 1 - x cot x = sum 2^(2k) |B_2k| x^(2k) / (2k)!  with x = t/2
    bernoulli = (1 / 6, 1 / 30, 1 / 42, 1 / 30, 5 / 66, 691 / 2730, 7 / 6, 3617 / 510, 43867 / 798)
    coefficients = tuple(b / math.factorial(2 * k) for k, b in enumerate(bernoulli, start=1))  # in t^(2k-2)
    return _series(theta, coefficients, lambda t: (1.0 - 0.5 * t / np.tan(0.5 * t)) / t**2)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product along the first axis (components first)."""
    return np.array((a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]))


def _compose(g: Motion | None, h: Motion) -> Motion:
    """``g h`` (``None`` is the identity)."""
    if g is None:
        return h
    rot, shift = g
    turned = rot[:, 0, None] * h[0][0] + rot[:, 1, None] * h[0][1] + rot[:, 2, None] * h[0][2]
    return turned, _rotate(rot, h[1]) + shift


def _rotate(rot: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``rot v`` for rotations ``(3, 3, N)`` and vectors ``(3, N)`` (or one vector ``(3,)``).

    Written as elementwise products summed in a fixed order, as every product
    of this module, so that each pose's numbers are the same bits whatever
    the batch around it: ``einsum`` picks its inner loop (and fused
    multiply-adds) by the arrays' sizes, which made a pose's round-off, and
    through a Newton solve that cannot close the pose it stops at, depend on
    how many poses were solved with it (the chunk size of a sweep).
    """
    return rot[:, 0] * v[0] + rot[:, 1] * v[1] + rot[:, 2] * v[2]


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a . b`` along the first axis (components first), in a fixed order (see :func:`_rotate`)."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _soa_rotation_logs(rot: np.ndarray) -> np.ndarray:
    """Rotation vectors ``(3, N)`` of rotations ``(3, 3, N)`` (closed form, scipy near a half turn)."""
    axis2 = np.array((rot[2, 1] - rot[1, 2], rot[0, 2] - rot[2, 0], rot[1, 0] - rot[0, 1]))  # 2 sin(t) u
    sine2 = np.sqrt(_dot(axis2, axis2))
    theta = np.arctan2(0.5 * sine2, 0.5 * (rot[0, 0] + rot[1, 1] + rot[2, 2] - 1.0))
    out = axis2 / (2.0 * np.sinc(theta / np.pi))
    near_half_turn = theta > 3.0
    if np.any(near_half_turn):
        out[:, near_half_turn] = Rotation.from_matrix(np.moveaxis(rot[:, :, near_half_turn], -1, 0)).as_rotvec().T
    return out


def _inverse_left_jacobian_times(w: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``J_l(w)^-1 x`` for rotation vectors ``w`` ``(3, N)`` and vectors ``x`` ``(3, N)`` or ``(3, k, N)``."""
    c = _c(np.sqrt(_dot(w, w)))
    if x.ndim == 3:
        wb = w[:, None, :]
        wx = _cross(wb, x)
        return x - 0.5 * wx + c * _cross(wb, wx)
    wx = _cross(w, x)
    return x - 0.5 * wx + c * _cross(w, wx)


def _soa_logs(g: Motion) -> np.ndarray:
    """Twists ``[w; v]`` ``(6, N)`` with ``exp(twist) = g``."""
    w = _soa_rotation_logs(g[0])
    return np.concatenate([w, _inverse_left_jacobian_times(w, g[1])])


def left_jacobians(rotvec: np.ndarray) -> np.ndarray:
    """The left Jacobian of SO(3), ``I + A skew(w) + B skew(w)^2``, of each row of ``rotvec`` (shape ``(N, 3, 3)``)."""
    w = np.asarray(rotvec, dtype=float).reshape(-1, 3)
    theta = np.linalg.norm(w, axis=1)
    k = np.array([skew(x) for x in w]).reshape(-1, 3, 3)
    return np.eye(3) + _a(theta)[:, None, None] * k + _b(theta)[:, None, None] * (k @ k)


def rotation_logs(rot: np.ndarray) -> np.ndarray:
    """Rotation vectors of a stack of rotation matrices ``(N, 3, 3)`` (closed form, scipy near a half turn).

    Examples
    --------
    >>> import numpy as np
    >>> from scipy.spatial.transform import Rotation
    >>> w = np.array([[0.1, -0.2, 0.3], [0.0, 0.0, 3.1]])
    >>> bool(np.allclose(rotation_logs(Rotation.from_rotvec(w).as_matrix()), w))
    True
    """
    return _soa_rotation_logs(np.moveaxis(np.asarray(rot, dtype=float), 0, -1)).T


def displacement_logs(g: np.ndarray) -> np.ndarray:
    """Twists ``[w; v]`` with ``exp(twist) = g`` for a stack of displacements ``(N, 4, 4)`` (shape ``(N, 6)``).

    Examples
    --------
    >>> import numpy as np
    >>> from mobility.core.transforms import twist_exp
    >>> x = np.array([[0.1, -0.2, 0.3, 1.0, 2.0, -0.5], [0, 0, 1e-9, 1, 0, 0]])
    >>> bool(np.allclose(displacement_logs(np.array([twist_exp(r) for r in x])), x, rtol=1e-14, atol=1e-15))
    True
    """
    g = np.moveaxis(np.asarray(g, dtype=float), 0, -1)
    return _soa_logs((g[:3, :3], g[:3, 3])).T


def _floats(q: np.ndarray) -> np.ndarray:
    """``q`` as floats: ``numpy.longdouble`` kept (the extended-precision residuals of a polishing step), else float64."""
    q = np.asarray(q)
    return q if q.dtype == np.longdouble else np.asarray(q, dtype=float)


class BatchKinematics:
    """The product-of-exponentials model of one mechanism, evaluated on many poses at once.

    Parameters
    ----------
    mechanism : Mechanism
    reference : ndarray, shape (3,), optional
        The end effector's reference point, normalised coordinates of the file's
        pose (for the pose coordinates of :meth:`evaluate`).

    Attributes
    ----------
    mechanism : Mechanism
    model : Kinematics
        The single-pose model (:func:`mobility.core.kinematics.kinematics`),
        whose variables, twists and spanning tree are used here.
    variable_count, loop_count : int
    """

    def __init__(self, mechanism: Mechanism, reference: np.ndarray | None = None) -> None:
        model: Kinematics = kinematics(mechanism)
        self.mechanism = mechanism
        self.model = model
        tw = np.asarray(model.twists, dtype=float)  # (6, n): unit angular part (R, H) or unit linear part (P)
        kinds = np.array(model.kinds)
        self.prismatic = kinds == "P"
        w, v = tw[:3].T, tw[3:].T
        self.axes = np.where(self.prismatic[:, None], v, w)
        self.points = np.where(self.prismatic[:, None], 0.0, np.cross(w, v))  # the point of each line nearest the origin
        self.pitches = np.where(kinds == "H", np.einsum("ij,ij->i", w, v), 0.0)
        self.twists = tw.T.copy()
        k = np.array([skew(a) for a in self.axes]).reshape(-1, 3, 3)
        self._k = k[..., None]
        self._k2 = (k @ k)[..., None]
        self._kp = np.einsum("vij,vj->vi", k, self.points)[:, :, None]
        self._k2p = np.einsum("vij,vj->vi", k @ k, self.points)[:, :, None]
        self.variable_count = tw.shape[1]
        self.reference = np.zeros(3) if reference is None else np.asarray(reference, dtype=float)
        # the spanning tree and loops of the single-pose model, as (variable, sign) pairs
        paths = {link: tuple((f.variable, f.sign) for f in path) for link, path in model.paths.items()}
        loops = [tuple((f.variable, f.sign) for f in loop) for loop in model.loops]
        tree, _ = spanning_tree(mechanism)
        steps = [(e.parent, e.child, paths[e.child][len(paths[e.parent]):]) for e in tree]
        self._steps = tuple(steps)
        self._loops = tuple(loops)
        self._end_effector = paths[mechanism.end_effector]
        self.loop_count = len(loops)

    # -- exponentials and products (pose index last) -------------------------------
    def _exponentials(self, q: np.ndarray) -> "_Exponentials":
        return _Exponentials(self, _floats(q).T)

    def _chain(self, factors: Factors, exps: "_Exponentials") -> tuple[Motion, list[Motion | None]]:
        """Product of ``factors`` and the partial product before each factor (``None``: the identity)."""
        g: Motion | None = None
        before: list[Motion | None] = []
        for variable, sign in factors:
            before.append(g)
            g = _compose(g, exps.factor(variable, sign))
        if g is None:
            g = (np.broadcast_to(np.eye(3)[..., None], (3, 3, exps.count)), np.zeros((3, exps.count)))
        return g, before

    def _columns(self, factors: Factors, before: list[Motion | None], rows: np.ndarray | None, count: int) -> np.ndarray:
        """Right-trivialised derivative ``(6, n, len(rows))`` of a product from its partial products."""
        cols = np.zeros((6, self.variable_count, count))
        for (variable, sign), g in zip(factors, before):
            x = sign * self.twists[variable]
            if g is None:
                cols[:, variable] = x[:, None]
                continue
            rot, shift = (g[0], g[1]) if rows is None else (g[0][:, :, rows], g[1][:, rows])
            w = _rotate(rot, x[:3])
            cols[:3, variable] = w
            cols[3:, variable] = _cross(shift, w) + _rotate(rot, x[3:])
        return cols

    def _product(self, factors: Factors, exps: "_Exponentials") -> Motion:
        g: Motion | None = None
        for variable, sign in factors:
            g = _compose(g, exps.factor(variable, sign))
        if g is None:
            return np.broadcast_to(np.eye(3)[..., None], (3, 3, exps.count)), np.zeros((3, exps.count))
        return g

    def _check(self, q: np.ndarray) -> np.ndarray:
        q = _floats(q)
        if q.ndim != 2 or q.shape[1] != self.variable_count:
            raise RequestError(f"expected joint variables of shape (N, {self.variable_count}), got {q.shape}")
        return q

    def link_motions(self, q: np.ndarray) -> dict[str, Motion]:
        """Displacement of every link: rotation ``(3, 3, N)`` and translation ``(3, N)``, normalised coordinates of the file's pose."""
        exps = self._exponentials(self._check(q))
        count = exps.count
        out: dict[str, Motion] = {self.mechanism.ground: (np.broadcast_to(np.eye(3)[..., None], (3, 3, count)), np.zeros((3, count)))}
        for parent, child, step in self._steps:
            g = out[parent]
            for variable, sign in step:
                g = _compose(g, exps.factor(variable, sign))
            out[child] = g
        return out

    def link_displacements(self, q: np.ndarray) -> dict[str, np.ndarray]:
        """Displacement ``g_L`` (``(N, 4, 4)``) of every link, as :meth:`Kinematics.link_displacements` gives one."""
        out = {}
        for link, (rot, shift) in self.link_motions(q).items():
            g = np.zeros((rot.shape[-1], 4, 4))
            g[:, :3, :3] = np.moveaxis(rot, -1, 0)
            g[:, :3, 3] = shift.T
            g[:, 3, 3] = 1.0
            out[link] = g
        return out

    # -- loops and the end effector ---------------------------------------------------
    def residual(self, q: np.ndarray) -> np.ndarray:
        """Loop-closure residual of every pose, ``(N, 6 * loops)`` (as :meth:`Kinematics.residual`)."""
        q = self._check(q)
        if not self._loops:
            return np.zeros((len(q), 0))
        exps = self._exponentials(q)
        return np.concatenate([_soa_logs(self._product(loop, exps)) for loop in self._loops]).T

    def evaluate(self, q: np.ndarray, components: np.ndarray | None = None) -> "Evaluation":
        """The loop residuals (and pose coordinates ``components``) now, their Jacobian later and only for the poses that need it."""
        return Evaluation(self, self._check(q), components)

class _Exponentials:
    """``exp(q_i x_i)`` of every variable (Rodrigues), its inverse computed when first asked."""

    def __init__(self, bk: BatchKinematics, q: np.ndarray) -> None:  # q: (n, N)
        self.count = q.shape[1]
        sin, one_minus_cos = np.sin(q), 1.0 - np.cos(q)
        rot = bk._k * sin[:, None, None, :] + bk._k2 * one_minus_cos[:, None, None, :]
        # about the line through p: shift = (I - R) p + h q a, and (I - R) p = -(sin K p + (1 - cos) K^2 p)
        shift = -(bk._kp * sin[:, None, :] + bk._k2p * one_minus_cos[:, None, :]) + (bk.pitches[:, None] * q)[:, None, :] * bk.axes[:, :, None]
        rot += np.eye(3)[None, :, :, None]
        rot[bk.prismatic] = np.eye(3)[:, :, None]
        shift[bk.prismatic] = q[bk.prismatic][:, None, :] * bk.axes[bk.prismatic][:, :, None]
        self.rot, self.shift = rot, shift
        self._inverse: dict[int, Motion] = {}

    def factor(self, variable: int, sign: float) -> Motion:
        if sign > 0:
            return self.rot[variable], self.shift[variable]
        if variable not in self._inverse:
            rt = np.swapaxes(self.rot[variable], 0, 1)
            self._inverse[variable] = (rt, -_rotate(rt, self.shift[variable]))
        return self._inverse[variable]


class Evaluation:
    """The loop residuals (and pose coordinates) of many poses, with what their Jacobian needs kept.

    Attributes
    ----------
    values : ndarray, shape (m, N)
        The residual of each loop (6 numbers), then the pose coordinates asked
        for (0..5 for x, y, z, rx, ry, rz: the displacement of the reference
        point and the rotation vector, normalised coordinates).  Their
        Jacobian, per unit joint rate, right-trivialised for the loops (exact
        at a closed pose), comes from :meth:`jacobian`.
    """

    def __init__(self, bk: BatchKinematics, q: np.ndarray, components: np.ndarray | None) -> None:
        self._bk = bk
        exps = bk._exponentials(q)
        self._count = exps.count
        values = []
        self._chains: list[tuple[Factors, list[Motion | None], Motion | None]] = []  # the end effector's with its pose (p, r)
        for loop in bk._loops:
            g, before = bk._chain(loop, exps)
            values.append(_soa_logs(g))
            self._chains.append((loop, before, None))
        self._components = None if components is None or not len(components) else np.asarray(components)
        if self._components is not None:
            (rot, shift), before = bk._chain(bk._end_effector, exps)
            p = _rotate(rot, bk.reference) + shift
            r = _soa_rotation_logs(rot)
            values.append(np.concatenate([p - bk.reference[:, None], r])[self._components])
            self._chains.append((bk._end_effector, before, (p, r)))
        self.values = np.concatenate(values) if values else np.zeros((0, self._count))

    def jacobian(self, rows: np.ndarray | None = None) -> np.ndarray:
        """The Jacobian ``(m, n, len(rows))`` of the chosen poses (all by default)."""
        bk = self._bk
        count = self._count if rows is None else len(rows)
        blocks = []
        for factors, before, pose in self._chains:
            cols = bk._columns(factors, before, rows, count)
            if pose is None:
                blocks.append(cols)
                continue
            p, r = pose if rows is None else (pose[0][:, rows], pose[1][:, rows])
            omega = cols[:3]
            dp = cols[3:] + _cross(omega, p[:, None, :])  # point velocity v + w x p
            dr = _inverse_left_jacobian_times(r, omega)
            blocks.append(np.concatenate([dp, dr])[self._components])
        if not blocks:
            return np.zeros((0, bk.variable_count, count))
        return np.concatenate(blocks)
