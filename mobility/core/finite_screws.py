"""Finite screws: rigid displacements in the quasi-vector form of Huang, Dai and Sun.

Finite screws ``S_f = 2 tan(θ/2) [s; r × s] + t [0; s]`` (angular part first,
like :mod:`mobility.core.screws`), the triangle product, limbs (Eq. 7) and
half-turns; the conventions are stated once in docs/finite-screws.md and pinned
by ``tests/test_finite_screws.py``.  Each displacement is also kept as its unit
dual quaternion (:class:`FiniteScrew`), whose product never divides; only
reading ``S_f`` off a half-turn raises :class:`~mobility.errors.HalfTurnError`
(``cos(θ/2)`` within :data:`QUATERNION_ROUND_OFF`, a fact of the arithmetic).

References
----------
T. Sun, S. Yang, T. Huang, J. S. Dai, "A finite and instantaneous screw based
approach for topology design and kinematic analysis of 5-axis parallel kinematic
machines", Chinese Journal of Mechanical Engineering 31:44 (2018).
J. S. Dai, "An historical review of the theoretical development of rigid body
displacements from Rodrigues parameters to the finite twist", Mechanism and
Machine Theory 41 (2006) 41-52.

Examples
--------
>>> import numpy as np
>>> quarter = finite_screw([0, 0, 1], [1, 0, 0], np.pi / 2)        # 90° about a z-line through (1, 0, 0)
>>> np.round(quarter, 12) + 0.0
array([ 0.,  0.,  2.,  0., -2.,  0.])
>>> slide = finite_screw([1, 0, 0], [0, 0, 0], 0.0, translation=3.0)
>>> both = triangle_product(quarter, slide)                         # slide first, then the rotation
>>> bool(np.allclose(transform_from_finite_screw(both),
...                  transform_from_finite_screw(quarter) @ transform_from_finite_screw(slide)))
True
>>> FiniteScrew.from_parameters([0, 0, 1], [0, 0, 0], np.pi).is_half_turn
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import reduce
from itertools import accumulate
from typing import Iterable

import numpy as np
import numpy.typing as npt
from scipy.spatial.transform import Rotation

from ..errors import HalfTurnError, MechanismError, RequestError, shown_argument
from .tolerance import DEFAULT_TOLERANCE, Tolerance, binary_scale
from .transforms import cross, skew

__all__ = ["finite_screw", "finite_screw_from_transform", "transform_from_finite_screw", "triangle_product",
           "twist_from_finite_screw_rate", "FiniteScrew", "ScrewJoint", "Limb", "QUATERNION_ROUND_OFF"]

QUATERNION_ROUND_OFF = 64 * np.finfo(float).eps
"""A component of a unit quaternion at or below this (64 units in the last place) is round-off: ``cos(θ/2)``
that small is a half-turn, ``sin(θ/2)`` no rotation (what double precision delivers, not a tolerance policy)."""


def _unit_or_none(v: Iterable[float]) -> np.ndarray | None:
    """``v`` scaled to unit length; ``None`` when it is not three finite numbers or is zero."""
    try:
        a = np.asarray(v, dtype=float).reshape(3)
    except (TypeError, ValueError, OverflowError):
        return None
    if not np.all(np.isfinite(a)) or not np.any(a):
        return None
    a = a * binary_scale(a)  # before squaring: any finite direction has a unit vector
    return a / float(np.linalg.norm(a))


def _shown(v: object) -> str:
    """A value as the error messages show it (a list for arrays), clipped to one line."""
    if isinstance(v, np.ndarray) and v.size <= 16:
        return shown_argument(v.tolist())
    if isinstance(v, np.ndarray):
        return f"an array of shape {v.shape}"
    return shown_argument(v)


def _numbers(value: object, count: int, what: str, expected: str = "") -> np.ndarray:
    """``value`` as ``count`` finite floats (shape ``(count,)``), else a :class:`~mobility.errors.RequestError` naming ``what``."""
    expected = expected or f"{count} finite numbers"
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise RequestError(caller=what, expected=expected, got=_shown(value)) from None
    if a.shape != (count,):
        got = _shown(value) if a.ndim == 0 else f"shape {a.shape}" if isinstance(value, np.ndarray) or a.ndim != 1 else f"{a.size} numbers"
        raise RequestError(caller=what, expected=expected, got=got)
    if not np.all(np.isfinite(a)):
        raise RequestError(caller=what, expected=expected, got=_shown(value))
    return a


def _number(value: object, what: str) -> float:
    """``value`` as a finite float (a real number, not a string or a bool), else a :class:`~mobility.errors.RequestError` naming ``what``."""
    if not isinstance(value, (bool, np.bool_, str, bytes, list, tuple, np.ndarray)) or (isinstance(value, np.ndarray) and value.ndim == 0):
        try:
            number = float(value)  # type: ignore[arg-type]
        except (TypeError, ValueError, OverflowError):
            number = math.nan
        if math.isfinite(number):
            return number
    raise RequestError(caller=what, expected="a finite number", got=_shown(value))


def _screw(s: npt.ArrayLike, what: str = "screw") -> np.ndarray:
    return _numbers(s, 6, what, "a 6-vector [w; v] of finite numbers")


def finite_screw(axis: Iterable[float], point: Iterable[float], angle: float, translation: float = 0.0) -> np.ndarray:
    """The finite screw ``2 tan(θ/2) [s; r × s] + t [0; s]`` of a screw displacement.

    ``axis`` ``s`` (normalised here), ``point`` ``r`` on it, ``angle`` ``θ`` in
    radians (right-hand rule about ``s``), ``translation`` ``t`` along ``s``.
    Returns ``[w; v]``; :class:`~mobility.errors.HalfTurnError` when ``θ`` is an
    odd multiple of ``π``.

    Examples
    --------
    >>> finite_screw([0, 0, 2], [0, 0, 0], 0.0, 1.5).tolist()
    [0.0, 0.0, 0.0, 0.0, 0.0, 1.5]
    """
    return FiniteScrew.from_parameters(axis, point, angle, translation).vector


def transform_from_finite_screw(screw: npt.ArrayLike) -> np.ndarray:
    """The 4x4 homogeneous matrix of the displacement with finite screw ``[w; v]``.

    This is the Cayley map of SE(3): ``R = (I - [w]/2)^-1 (I + [w]/2)`` and
    ``p = (I - [w]/2)^-1 v``, defined for every finite quasi-vector.

    Examples
    --------
    >>> T = transform_from_finite_screw([0, 0, 2, 0, 0, 0])          # 2 tan(45°) about z
    >>> np.round(T[:3, :3] @ [1, 0, 0], 12) + 0.0
    array([0., 1., 0.])
    """
    s = _screw(screw)
    w, v = s[:3], s[3:]
    half = 0.5 * skew(w)
    inv = np.linalg.inv(np.eye(3) - half)
    out = np.eye(4)
    out[:3, :3] = inv @ (np.eye(3) + half)
    out[:3, 3] = inv @ v
    return out


def finite_screw_from_transform(matrix: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> np.ndarray:
    """The finite screw of the displacement given as a 4x4 homogeneous matrix.

    ``tol`` says how far from a rigid displacement the matrix may be
    (:meth:`FiniteScrew.from_transform`); a half-turn raises
    :class:`~mobility.errors.HalfTurnError`.

    Examples
    --------
    >>> S = np.array([0.1, -0.4, 0.3, 1.0, 2.0, -0.5])
    >>> bool(np.allclose(finite_screw_from_transform(transform_from_finite_screw(S)), S))
    True
    """
    return FiniteScrew.from_transform(matrix, tol).vector


def triangle_product(*screws: npt.ArrayLike) -> np.ndarray:
    """The screw triangle product ``S_1 △ S_2 △ … △ S_k`` of finite screws (``S_k`` acts first).

    ``S_a △ S_b`` is ``b`` then ``a`` (fixed frame, matrix ``T_a @ T_b``; the formula, and the
    paper's opposite order, in docs/finite-screws.md).  A half-turn partial product raises
    :class:`~mobility.errors.HalfTurnError` (compose :class:`FiniteScrew` objects instead, which never divide).

    Examples
    --------
    >>> S = np.array([0.2, 0.0, -0.6, 0.3, 1.0, 0.0])
    >>> bool(np.allclose(triangle_product(S, -S), 0.0))                  # -S is the inverse
    True
    """
    if not screws:
        return np.zeros(6)
    return reduce(_triangle2, [_screw(s, f"screws[{i}]") for i, s in enumerate(screws)])


def _triangle2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    wa, va, wb, vb = a[:3], a[3:], b[:3], b[3:]
    with np.errstate(over="ignore", invalid="ignore"):
        d = 1.0 - 0.25 * float(wa @ wb)
        # scal q of the product, relative to the unit dual quaternions: d / sqrt((1 + |wa|²/4)(1 + |wb|²/4))
        scale = float(np.sqrt((1.0 + 0.25 * wa @ wa) * (1.0 + 0.25 * wb @ wb)))
        w = wa + wb + 0.5 * cross(wa, wb)
        v = va + vb + 0.5 * (cross(wa, vb) + cross(va, wb)) - 0.25 * float(wa @ va) * wb - 0.25 * float(wb @ vb) * wa
        out = np.concatenate([w, v]) / d if d != 0.0 else np.full(6, np.inf)
    if not (np.isfinite(d) and np.isfinite(scale) and np.all(np.isfinite(w)) and np.all(np.isfinite(v))):
        raise RequestError("the triangle product of these finite screws overflows double precision (expected screws of moderate size)", caller="screws")
    if abs(d) <= QUATERNION_ROUND_OFF * scale or not np.all(np.isfinite(out)):
        raise HalfTurnError("the triangle product is a half-turn (1 - wa·wb/4 = 0): it has no finite quasi-vector; use FiniteScrew")
    return out


def twist_from_finite_screw_rate(screw: npt.ArrayLike, rate: npt.ArrayLike) -> np.ndarray:
    """The instantaneous twist ``[ω; v]`` of a motion whose finite screw is ``S`` with derivative ``dS``.

    The twist is ``d/dΔ [S(τ+Δ) △ (-S(τ))]`` at ``Δ = 0`` (spatial twist,
    fixed frame).  With ``S = [w; v]``, ``dS = [dw; dv]`` and ``k = 1 + w·w/4``::

        ω = (dw + ½ w × dw) / k
        v = (dv + ½ (v × dw + w × dv) + ¼ (v·dw + w·dv) w - ¼ (w·v) dw) / k

    At ``S = 0`` this is ``[ω; v] = dS`` (Eq. 5 of Sun et al.).

    Examples
    --------
    >>> rate = np.array([0.0, 0.0, 1.0, 0.0, -1.0, 0.0])                # d/dθ of 2tan(θ/2)[z; (1,0,0) × z] at 0
    >>> twist_from_finite_screw_rate(np.zeros(6), rate).tolist()
    [0.0, 0.0, 1.0, 0.0, -1.0, 0.0]
    """
    s = _screw(screw)
    ds = _screw(rate, "rate")
    w, v, dw, dv = s[:3], s[3:], ds[:3], ds[3:]
    k = 1.0 + 0.25 * float(w @ w)
    omega = dw + 0.5 * cross(w, dw)
    vel = dv + 0.5 * (cross(v, dw) + cross(w, dv)) + 0.25 * float(v @ dw + w @ dv) * w - 0.25 * float(w @ v) * dw
    return np.concatenate([omega, vel]) / k


# -- homogeneous form (unit dual quaternions) ---------------------------------


def _qmul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Quaternion product, scalar first."""
    a0, a1, a2, a3 = a
    b0, b1, b2, b3 = b
    return np.array([a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3, a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
                     a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1, a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0])


def _dqmul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Dual-quaternion product of 8-vectors ``(q, q0)``."""
    return np.concatenate([_qmul(a[:4], b[:4]), _qmul(a[:4], b[4:]) + _qmul(a[4:], b[:4])])


def _conj(q: np.ndarray) -> np.ndarray:
    return np.concatenate([q[:1], -q[1:]])


def _canonical(h: np.ndarray) -> np.ndarray:
    """Unit dual quaternion with the sign fixed (``h`` and ``-h`` are the same displacement)."""
    h = h / np.linalg.norm(h[:4])
    key = h[0] if abs(h[0]) > QUATERNION_ROUND_OFF else h[1:4][np.argmax(np.abs(h[1:4]))]
    return -h if key < 0 else h


@dataclass(frozen=True, eq=False)
class FiniteScrew:
    """A rigid displacement in homogeneous finite-screw form (exact for half-turns).

    Holds the unit dual quaternion ``(q, q0)`` (scalar parts first, sign
    fixed); the finite screw is ``2 [vec q; vec q0] / scal q``.

    Examples
    --------
    >>> half = FiniteScrew.from_parameters([0, 0, 1], [1, 0, 0], np.pi)    # half-turn about a z-line
    >>> twice = half.triangle(half)                                        # a full turn: the identity
    >>> bool(np.allclose(twice.vector, 0.0))
    True
    >>> half.vector
    Traceback (most recent call last):
    ...
    mobility.errors.HalfTurnError: half-turn: 2 tan(θ/2) is infinite, the displacement has no finite quasi-vector
    """

    homogeneous: np.ndarray = field(repr=False)

    def __post_init__(self) -> None:
        h = _numbers(self.homogeneous, 8, "homogeneous", "8 finite numbers, a dual quaternion (q, q0) with q non-zero")
        if not np.any(h[:4]):
            raise RequestError("homogeneous: a finite screw needs a non-zero finite rotation quaternion q, got q = 0")
        h = _canonical(h)
        h.setflags(write=False)
        object.__setattr__(self, "homogeneous", h)

    # -- construction -----------------------------------------------------
    @staticmethod
    def identity() -> "FiniteScrew":
        """The identity displacement (``S_f = 0``)."""
        return FiniteScrew(np.array([1.0, 0, 0, 0, 0, 0, 0, 0]))

    @staticmethod
    def from_vector(screw: npt.ArrayLike) -> "FiniteScrew":
        """From a quasi-vector ``[w; v]`` (any finite 6-vector is a displacement)."""
        s = _screw(screw)
        w, v = s[:3], s[3:]
        with np.errstate(over="ignore", invalid="ignore"):
            h = np.concatenate([[1.0], 0.5 * w, [-0.25 * float(w @ v)], 0.5 * v])
        if not np.all(np.isfinite(h)):
            raise RequestError(caller="screw", expected="a 6-vector [w; v] whose product w·v is a finite number", got=_shown(s))
        return FiniteScrew(h)

    @staticmethod
    def from_parameters(axis: Iterable[float], point: Iterable[float], angle: float, translation: float = 0.0) -> "FiniteScrew":
        """Rotation ``angle`` about the line through ``point`` along ``axis``, translation ``translation`` along it."""
        s = _unit_or_none(axis)
        if s is None:
            raise RequestError(caller="axis", expected="a non-zero finite direction of 3 numbers", got=_shown(axis))
        r = _numbers(point, 3, "point")
        theta = _number(angle, "angle")
        c, sn = np.cos(0.5 * theta), np.sin(0.5 * theta)
        t = _number(translation, "translation")
        q = np.concatenate([[c], sn * s])
        q0 = np.concatenate([[-0.5 * t * sn], 0.5 * t * c * s + sn * cross(r, s)])
        return FiniteScrew(np.concatenate([q, q0]))

    @staticmethod
    def from_transform(matrix: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> "FiniteScrew":
        """From a 4x4 homogeneous matrix of a rigid displacement.

        It is one when ``R Rᵀ`` and the last row differ from the identity and
        ``[0, 0, 0, 1]`` by at most ``tol.rank`` per entry and ``det R > 0``;
        else :class:`~mobility.errors.RequestError`.
        """
        try:
            m = np.asarray(matrix, dtype=float)
        except (TypeError, ValueError, OverflowError):
            m = np.empty(0)
        if m.shape != (4, 4) or not np.all(np.isfinite(m)):
            raise RequestError(argument="matrix", expected="a 4x4 matrix of finite numbers", got=_shown(matrix))
        rot = m[:3, :3]
        off = max(float(np.max(np.abs(rot @ rot.T - np.eye(3)))), float(np.max(np.abs(m[3] - [0.0, 0.0, 0.0, 1.0]))))
        if off > tol.rank or np.linalg.det(rot) < 0:
            raise RequestError("expected a rigid displacement (rotation block orthonormal, det +1, last row [0, 0, 0, 1])")
        x, y, z, w = Rotation.from_matrix(rot).as_quat()
        q = np.array([w, x, y, z])
        q0 = 0.5 * _qmul(np.concatenate([[0.0], m[:3, 3]]), q)
        return FiniteScrew(np.concatenate([q, q0]))

    # -- reading ------------------------------------------------------------
    @property
    def is_half_turn(self) -> bool:
        """True when ``cos(θ/2)`` is within round-off of zero."""
        return bool(abs(self.homogeneous[0]) <= QUATERNION_ROUND_OFF)

    @property
    def vector(self) -> np.ndarray:
        """The quasi-vector ``[w; v] = 2 tan(θ/2) [s; r × s] + t [0; s]`` (:class:`~mobility.errors.HalfTurnError` at a half-turn)."""
        h = self.homogeneous
        if self.is_half_turn:
            raise HalfTurnError("half-turn: 2 tan(θ/2) is infinite, the displacement has no finite quasi-vector")
        return 2.0 * np.concatenate([h[1:4], h[5:8]]) / h[0]

    @property
    def direction(self) -> np.ndarray:
        """``2 [vec q; vec q0]``: the quasi-vector times ``cos(θ/2)``, finite everywhere (at a half-turn its line ``2 [s; r × s]``)."""
        h = self.homogeneous
        return 2.0 * np.concatenate([h[1:4], h[5:8]])

    def transform(self) -> np.ndarray:
        """The 4x4 homogeneous matrix."""
        h = self.homogeneous
        q, q0 = h[:4], h[4:]
        out = np.eye(4)
        out[:3, :3] = Rotation.from_quat([q[1], q[2], q[3], q[0]]).as_matrix()
        out[:3, 3] = 2.0 * _qmul(q0, _conj(q))[1:]
        return out

    def parameters(self) -> tuple[np.ndarray, np.ndarray, float, float]:
        """Screw parameters ``(axis, point, angle, translation)``, ``angle`` in ``[0, π]``.

        ``point`` is the point of the axis nearest the origin.  A pure
        translation has ``angle = 0``, its direction as ``axis`` and the origin
        as ``point``; the identity has axis ``[0, 0, 1]`` and zero translation.
        """
        h = self.homogeneous
        q, q0 = h[:4], h[4:]
        sn = float(np.linalg.norm(q[1:]))
        angle = 2.0 * float(np.arctan2(sn, q[0]))
        if sn <= QUATERNION_ROUND_OFF:
            p = 2.0 * _qmul(q0, _conj(q))[1:]
            t = float(np.linalg.norm(p))
            axis = p / t if t > 0 else np.array([0.0, 0.0, 1.0])
            return axis, np.zeros(3), 0.0, t
        s = q[1:] / sn
        c = float(q[0])
        t = -2.0 * float(q0[0]) / sn
        moment = (q0[1:] - 0.5 * t * c * s) / sn
        return s, cross(s, moment), angle, t

    # -- algebra ------------------------------------------------------------
    def triangle(self, other: "FiniteScrew") -> "FiniteScrew":
        """``self △ other``: ``other`` first, then ``self`` (matrix ``T_self @ T_other``)."""
        if not isinstance(other, FiniteScrew):
            raise RequestError(caller="other", expected="a FiniteScrew", got=type(other).__name__)
        return FiniteScrew(_dqmul(self.homogeneous, other.homogeneous))

    def inverse(self) -> "FiniteScrew":
        """The inverse displacement (``-S_f`` in quasi-vector form)."""
        h = self.homogeneous
        return FiniteScrew(np.concatenate([_conj(h[:4]), _conj(h[4:])]))

    def isclose(self, other: "FiniteScrew", *, length: float = 1.0, tol: Tolerance = DEFAULT_TOLERANCE) -> bool:
        """Whether two finite screws are the same displacement (dual quaternions equal up to sign).

        Equal when no entry differs by more than ``tol.rank``, the dual parts
        (lengths) divided by ``length``.

        Examples
        --------
        >>> a = FiniteScrew.from_parameters([0, 0, 1], [1, 0, 0], 0.5)
        >>> b = FiniteScrew.from_transform(a.transform())
        >>> a.isclose(b), a.isclose(FiniteScrew.from_parameters([0, 0, 1], [1, 1e-6, 0], 0.5))
        (True, False)
        """
        scale = np.concatenate([np.ones(4), np.full(4, 1.0 / length)])
        a, b = self.homogeneous * scale, other.homogeneous * scale
        return bool(min(np.max(np.abs(a - b)), np.max(np.abs(a + b))) <= tol.rank)


# -- joints and limbs ------------------------------------------------------------


_KINDS = ("R", "P", "H")


@dataclass(frozen=True)
class ScrewJoint:
    """A one-DOF joint of a serial chain, in the chain's initial configuration (fixed frame).

    ``kind`` is ``"R"`` (value: angle), ``"P"`` (value: length along ``axis``)
    or ``"H"`` (value: angle; translation ``pitch * angle``, pitch in length per
    radian); ``axis`` is normalised, ``point`` ignored for ``P``; ``label``
    names it in reports.

    Examples
    --------
    >>> ScrewJoint("H", (0, 0, 2), pitch=0.1).twist().tolist()
    [0.0, 0.0, 1.0, 0.0, 0.0, 0.1]
    """

    kind: str
    axis: tuple[float, float, float]
    point: tuple[float, float, float] = (0.0, 0.0, 0.0)
    pitch: float = 0.0
    label: str = ""

    def __post_init__(self) -> None:
        if self.kind not in _KINDS:
            raise MechanismError("kind", f"expected one of {', '.join(_KINDS)}, got {self.kind!r}")
        axis = _unit_or_none(self.axis)
        if axis is None:
            raise MechanismError("axis", f"expected a non-zero finite direction of 3 numbers, got {_shown(self.axis)}")
        object.__setattr__(self, "axis", tuple(float(x) for x in axis))
        try:
            pt = np.asarray(self.point, dtype=float).reshape(3)
        except (TypeError, ValueError, OverflowError):
            raise MechanismError("point", f"expected 3 numbers, got {_shown(self.point)}") from None
        if self.kind == "P":
            pt = np.zeros(3)
        elif not np.all(np.isfinite(pt)):
            raise MechanismError("point", f"expected 3 finite numbers, got {_shown(self.point)}")
        object.__setattr__(self, "point", tuple(float(x) for x in pt))
        pitch = 0.0
        if self.kind == "H":
            try:
                pitch = _number(self.pitch, "pitch")
            except RequestError as err:
                raise MechanismError("pitch", str(err).removeprefix("pitch: ")) from None
        object.__setattr__(self, "pitch", pitch)

    def finite_screw(self, value: float) -> FiniteScrew:
        """Finite screw of the joint displaced by ``value`` (homogeneous form)."""
        value = _number(value, "value")
        if self.kind == "P":
            return FiniteScrew.from_parameters(self.axis, self.point, 0.0, value)
        return FiniteScrew.from_parameters(self.axis, self.point, value, self.pitch * value)

    def twist(self) -> np.ndarray:
        """Unit twist ``[s; r × s + h s]`` (``[0; s]`` for ``P``) in the initial configuration."""
        s = np.asarray(self.axis)
        if self.kind == "P":
            return np.concatenate([np.zeros(3), s])
        return np.concatenate([s, cross(np.asarray(self.point), s) + self.pitch * s])

    def moved(self, matrix: np.ndarray) -> "ScrewJoint":
        """The same joint carried by the rigid displacement ``matrix`` (4x4)."""
        m = np.asarray(matrix, dtype=float)
        return ScrewJoint(self.kind, tuple(m[:3, :3] @ self.axis), tuple(m[:3, :3] @ self.point + m[:3, 3]), self.pitch, self.label)


def _pure(twist: np.ndarray) -> np.ndarray:
    """The pure dual quaternion ``(0, w) + ε (0, v)`` of a twist ``[w; v]``."""
    return np.concatenate([[0.0], twist[:3], [0.0], twist[3:]])


@dataclass(frozen=True)
class Limb:
    """A serial chain of one-DOF joints, base first, in its initial configuration.

    Its finite screw is Eq. 7 (:meth:`finite_screw`), every axis at home: the
    joint at the end effector acts first, before any other joint has moved it.
    Its twists are that finite screw's derivatives (:meth:`twists`).

    Examples
    --------
    >>> arm = Limb((ScrewJoint("R", (0, 0, 1)), ScrewJoint("P", (1, 0, 0))))   # R about z, then a slide along x
    >>> T = arm.transform([np.pi / 2, 2.0])
    >>> np.round(T[:3, 3], 12) + 0.0                                       # the slide turned with the R
    array([0., 2., 0.])
    """

    joints: tuple[ScrewJoint, ...]

    def __post_init__(self) -> None:
        object.__setattr__(self, "joints", tuple(self.joints))
        if not all(isinstance(j, ScrewJoint) for j in self.joints):
            raise MechanismError("joints", "a limb is a sequence of ScrewJoint")

    def __len__(self) -> int:
        return len(self.joints)

    def _values(self, q: npt.ArrayLike | None) -> np.ndarray:
        if q is None:
            return np.zeros(len(self.joints))
        try:
            values = np.asarray(q, dtype=float).reshape(-1)
        except (TypeError, ValueError, OverflowError):
            raise RequestError(argument="q", expected=f"{len(self.joints)} finite joint values", got=_shown(q)) from None
        if values.shape != (len(self.joints),):
            raise RequestError(argument="q", expected=f"{len(self.joints)} joint values", got=values.size)
        if not np.all(np.isfinite(values)):
            raise RequestError(argument="q", expected=f"{len(self.joints)} finite joint values", got=_shown(q))
        return values

    def factors(self, q: npt.ArrayLike | None = None) -> list[FiniteScrew]:
        """The joints' finite screws ``S_j(q_j)``, base first."""
        return [j.finite_screw(x) for j, x in zip(self.joints, self._values(q))]

    def finite_screw(self, q: npt.ArrayLike | None = None) -> FiniteScrew:
        """``S_1(q1) △ S_2(q2) △ ... △ S_n(qn)`` (Eq. 7), homogeneous form."""
        return reduce(FiniteScrew.triangle, self.factors(q), FiniteScrew.identity())

    def transform(self, q: npt.ArrayLike | None = None) -> np.ndarray:
        """4x4 displacement of the chain's end."""
        return self.finite_screw(q).transform()

    def _raw_rates(self, q: npt.ArrayLike | None) -> tuple[np.ndarray, np.ndarray]:
        """``H = H_1 ... H_n`` and its partial derivatives (8 x n), by the product rule with ``dH_j/dq_j = ½ ξ_j H_j`` (sign not fixed)."""
        factors = [f.homogeneous for f in self.factors(q)]
        one = np.array([1.0, 0, 0, 0, 0, 0, 0, 0])
        left = list(accumulate(factors, _dqmul, initial=one))  # left[j] = H_1 ... H_j
        right = list(accumulate(reversed(factors), lambda acc, f: _dqmul(f, acc), initial=one))[::-1]  # right[j] = H_j ... H_n (0-based)
        rates = np.empty((8, len(factors)))
        for j, (joint, f) in enumerate(zip(self.joints, factors)):
            rates[:, j] = _dqmul(_dqmul(left[j], 0.5 * _dqmul(_pure(joint.twist()), f)), right[j + 1])
        return left[-1], rates

    def finite_screw_rates(self, q: npt.ArrayLike | None = None) -> np.ndarray:
        """Partial derivatives ``∂S_f/∂q_j`` of the quasi-vector (6 x n); :class:`~mobility.errors.HalfTurnError` at a half-turn."""
        return _quasi_vector_rates(*self._raw_rates(q))[1]

    def twists(self, q: npt.ArrayLike | None = None) -> np.ndarray:
        """Joint twists at pose ``q`` (6 x n), as the derivative of the limb's finite screw.

        Column ``j`` is :func:`twist_from_finite_screw_rate` ``(S_f, ∂S_f/∂q_j)``
        (Eqs. 5 and 26); at a half-turn, ``2 vec(dH H*)``.
        """
        h, dh = self._raw_rates(q)
        n = dh.shape[1]
        if abs(h[0]) <= QUATERNION_ROUND_OFF * np.linalg.norm(h[:4]):
            hc = np.concatenate([_conj(h[:4]), _conj(h[4:])]) / float(h[:4] @ h[:4])
            prods = [_dqmul(dh[:, j], hc) for j in range(n)]
            return np.stack([2.0 * np.concatenate([p[1:4], p[5:8]]) for p in prods], axis=1).reshape(6, n)
        s, d = _quasi_vector_rates(h, dh)
        return np.stack([twist_from_finite_screw_rate(s, d[:, j]) for j in range(n)], axis=1).reshape(6, n)

    def moved(self, q: npt.ArrayLike) -> "Limb":
        """The same chain with pose ``q`` taken as its new initial configuration (axes carried along)."""
        out = []
        acc = np.eye(4)
        for joint, x in zip(self.joints, self._values(q)):
            out.append(joint.moved(acc))
            acc = acc @ joint.finite_screw(x).transform()
        return Limb(tuple(out))


def _quasi_vector_rates(h: np.ndarray, dh: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Quasi-vector ``2 [vec q; vec q0] / scal q`` of a dual quaternion and its derivatives (quotient rule)."""
    if abs(h[0]) <= QUATERNION_ROUND_OFF * np.linalg.norm(h[:4]):
        raise HalfTurnError("the chain's displacement is a half-turn: its quasi-vector and derivatives are infinite")
    vec = 2.0 * np.concatenate([h[1:4], h[5:8]])
    dvec = 2.0 * np.concatenate([dh[1:4], dh[5:8]])
    return vec / h[0], dvec / h[0] - np.outer(vec, dh[0]) / h[0] ** 2
