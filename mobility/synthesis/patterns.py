"""Motion patterns: sets of finite motions written as triangle products of finite-screw factors.

A *motion pattern* is a set of finite motions ``S_f = F_1 △ F_2 △ ... △ F_k``
(``F_k`` acts first), each factor a subgroup of displacements
(:class:`PatternFactor`); the 2T3R pattern of Sun et al. (2018) and the
others are in docs/finite-screws.md, "Type synthesis".  :data:`PATTERNS`
names the patterns the command line knows; any product of factors can be
built in code.

Examples
--------
>>> import numpy as np
>>> pattern = named_pattern("2T3R")
>>> pattern.dim, [f.kind for f in pattern.factors]
(5, ['rotations', 'translations'])
>>> [label for label, _ in pattern.directions()]              # s1 × s2 is called c
['s1', 's2', 'c']
>>> tilt_then_slide = pattern.transform(np.array([0.0, 0.3, 0.0, 2.0, -1.0]))
>>> pattern.contains(tilt_then_slide)
True
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace
from functools import cached_property
import itertools
from typing import Any, Iterable, Sequence

import numpy as np
from scipy.optimize import least_squares

from ..core.finite_screws import FiniteScrew, ScrewJoint
from ..core.linalg import singular_values
from ..core.tolerance import DEFAULT_TOLERANCE, SOLVER_STOP, Tolerance, characteristic_scale, decide_rank
from ..core.transforms import rotation_from_axis_angle
from ..errors import SynthesisError, counted, shown_argument
from .generic_rank import generic_rank

__all__ = ["Vector", "PatternFactor", "MotionPattern", "PATTERNS", "named_pattern"]

Vector = tuple[float, float, float]

_FACTOR_KINDS = ("rotations", "rotation", "translations")


def _vec(v: Iterable[float], what: str = "point") -> Vector:
    try:
        a = np.asarray(v, dtype=float).reshape(3)
    except (TypeError, ValueError):
        raise SynthesisError(caller=what, expected="3 numbers", got=shown_argument(v)) from None
    if not np.all(np.isfinite(a)):
        raise SynthesisError(caller=what, expected="3 finite numbers", got=a.tolist())
    return (float(a[0]), float(a[1]), float(a[2]))


def _unit(v: Iterable[float], what: str = "direction") -> np.ndarray:
    a = np.array(_vec(v, what))
    biggest = float(np.abs(a).max())
    if biggest == 0.0:
        raise SynthesisError(caller=what, expected="a non-zero finite direction", got=a.tolist())
    a = a / biggest  # first: the norm of (1e308, 1e308, 0) overflows, that of (1e-320, 0, 0) underflows
    return a / float(np.linalg.norm(a))


def _direction_rank(directions: Sequence[Iterable[float]], tol: Tolerance = DEFAULT_TOLERANCE) -> int:
    """Rank of a set of unit directions, by the policy (the largest singular value is at least 1)."""
    return decide_rank(singular_values(np.array(directions, dtype=float).reshape(-1, 3)), tol).rank


@dataclass(frozen=True)
class PatternFactor:
    """One finite-screw factor of a motion pattern: a subgroup of displacements.

    Parameters
    ----------
    kind : {"rotations", "rotation", "translations"}
        ``rotations``: every rotation about ``point`` (``2 tan(θ/2) [s; point × s]``
        for any ``s``, 3 parameters: a rotation vector); ``rotation``: rotations
        about the line through ``point`` along ``directions[0]``; ``translations``:
        ``t [0; u]`` for every ``u`` in the span of ``directions``.
    point : 3-vector
    directions : tuple of 3-vectors

    Raises
    ------
    SynthesisError
        For an unknown kind, a wrong number of directions or dependent ones.

    Examples
    --------
    >>> PatternFactor("translations", directions=((2, 0, 0), (0, 1, 0))).describe()
    'translations along (1, 0, 0), (0, 1, 0)'
    """

    kind: str
    point: Vector = (0.0, 0.0, 0.0)
    directions: tuple[Vector, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in _FACTOR_KINDS:
            raise SynthesisError(argument="factor kind", expected=f"one of {', '.join(_FACTOR_KINDS)}", got=repr(self.kind))
        object.__setattr__(self, "point", _vec(self.point))
        dirs = tuple(_vec(_unit(d)) for d in self.directions)
        object.__setattr__(self, "directions", dirs)
        need = {"rotations": (0, 0), "rotation": (1, 1), "translations": (1, 3)}[self.kind]
        if not need[0] <= len(dirs) <= need[1]:
            takes = {"rotations": "no direction", "rotation": "one direction", "translations": "1 to 3 directions"}[self.kind]
            raise SynthesisError(f"a {self.kind} factor takes {takes}, got {len(dirs)}")
        if dirs and _direction_rank(dirs) < len(dirs):
            raise SynthesisError("the directions of a translations factor must be independent")

    @property
    def dim(self) -> int:
        """Number of parameters (the factor's dimension)."""
        return {"rotations": 3, "rotation": 1, "translations": len(self.directions)}[self.kind]

    def generators(self) -> tuple[ScrewJoint, ...]:
        """One-DOF joints whose chain generates the factor (three R through ``point`` for ``rotations``)."""
        if self.kind == "rotations":
            return tuple(ScrewJoint("R", tuple(e), self.point) for e in np.eye(3))
        if self.kind == "rotation":
            return (ScrewJoint("R", self.directions[0], self.point),)
        return tuple(ScrewJoint("P", d) for d in self.directions)

    def transform(self, x: np.ndarray) -> np.ndarray:
        """4x4 displacement of the factor at parameters ``x`` (shape ``(dim,)``)."""
        out = np.eye(4)
        if self.kind == "translations":
            out[:3, 3] = np.array(self.directions).T @ x
            return out
        if self.kind == "rotations":
            angle = float(np.linalg.norm(x))
            rot = rotation_from_axis_angle(x / angle, angle) if angle > 0 else np.eye(3)
        else:
            rot = rotation_from_axis_angle(np.array(self.directions[0]), float(x[0]))
        out[:3, :3] = rot
        out[:3, 3] = np.asarray(self.point) - rot @ self.point
        return out

    def finite_screw(self, x: np.ndarray) -> FiniteScrew:
        """The factor's finite screw at parameters ``x`` (homogeneous form)."""
        if self.kind == "translations":
            t = np.array(self.directions).T @ x
            n = float(np.linalg.norm(t))
            return FiniteScrew.from_parameters(t / n, (0, 0, 0), 0.0, n) if n > 0 else FiniteScrew.identity()
        if self.kind == "rotations":
            angle = float(np.linalg.norm(x))
            return FiniteScrew.from_parameters(x / angle, self.point, angle) if angle > 0 else FiniteScrew.identity()
        return FiniteScrew.from_parameters(self.directions[0], self.point, float(x[0]))

    def describe(self) -> str:
        """A short text, e.g. ``"rotations about the point (0, 0, 0)"``."""

        def fmt(v: Vector) -> str:
            return "(" + ", ".join(f"{c:g}" for c in v) + ")"

        if self.kind == "rotations":
            return f"rotations about the point {fmt(self.point)}"
        if self.kind == "rotation":
            return f"rotations about the line through {fmt(self.point)} along {fmt(self.directions[0])}"
        return "translations along " + ", ".join(fmt(d) for d in self.directions)


@dataclass(frozen=True)
class MotionPattern:
    """A set of finite motions ``S_f = F_1 △ F_2 △ … △ F_k`` (``F_k`` acts first)."""

    name: str
    factors: tuple[PatternFactor, ...]
    description: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "factors", tuple(self.factors))
        if not self.factors:
            raise SynthesisError("a motion pattern needs at least one factor")

    def translated(self, offset: Iterable[float]) -> "MotionPattern":
        """The same pattern moved by ``offset`` (every point of every factor; directions unchanged).

        Examples
        --------
        >>> named_pattern("3R", point=(1, 2, 3)).translated((-1, -2, -3)).points
        ((0.0, 0.0, 0.0),)
        """
        shift = np.asarray(_vec(offset, "offset"))
        moved = tuple(replace(f, point=_vec(np.asarray(f.point) + shift)) for f in self.factors)
        return MotionPattern(self.name, moved, self.description)

    @property
    def parameter_count(self) -> int:
        """Sum of the factors' dimensions."""
        return sum(f.dim for f in self.factors)

    @cached_property
    def dim(self) -> int:
        """Dimension of the set of motions (generic rank of its generators, the points' centre taken as origin)."""
        centred = self.translated(-np.mean(np.asarray(self.points or [(0.0, 0.0, 0.0)], dtype=float), axis=0))
        return generic_rank(centred.generators(), np.random.default_rng(0), 3, self.length)

    def generators(self) -> tuple[ScrewJoint, ...]:
        """The factors' generators, in product order."""
        return tuple(j for f in self.factors for j in f.generators())

    @property
    def points(self) -> tuple[Vector, ...]:
        """The pattern's points (rotation centres and axis points), each given once."""
        pts: list[Vector] = []
        for f in self.factors:
            if f.kind != "translations" and f.point not in pts:
                pts.append(f.point)
        return tuple(pts)

    @property
    def translation_directions(self) -> tuple[Vector, ...]:
        """Directions of the translation factors."""
        return tuple(d for f in self.factors if f.kind == "translations" for d in f.directions)

    @property
    def length(self) -> float:
        """Characteristic length: RMS distance of the points from their centroid; 1 (unit) for a single point."""
        pts = np.array(self.points or [(0.0, 0.0, 0.0)])
        return characteristic_scale(pts)[1] if len(pts) > 1 else 1.0

    def directions(self) -> tuple[tuple[str, Vector], ...]:
        """The pattern's direction set with labels.

        Translation directions (``s1, s2, ...``), rotation axes (``a1, ...``),
        the cross products of every pair (``c`` for ``s1 × s2``, else ``c1, ...``),
        then the coordinate axes completing a basis; a direction parallel to one
        already in the set (a rank decision) is left out.
        """
        out: list[tuple[str, Vector]] = []

        def add(label: str, d: np.ndarray) -> None:
            d = _unit(d)
            if all(_direction_rank([v, d]) == 2 for _, v in out):
                out.append((label, _vec(d)))

        for i, d in enumerate(self.translation_directions):
            add(f"s{i + 1}", np.array(d))
        rot = [f.directions[0] for f in self.factors if f.kind == "rotation"]
        for i, d in enumerate(rot):
            add(f"a{i + 1}", np.array(d))
        base = [np.array(v) for _, v in out]
        crosses = [np.cross(a, b) for i, a in enumerate(base) for b in base[i + 1 :] if _direction_rank([a, b]) == 2]
        for i, c in enumerate(crosses):
            add("c" if len(crosses) == 1 else f"c{i + 1}", c)
        for label, e in zip("xyz", np.eye(3)):
            if _direction_rank([v for _, v in out] + [e]) > len(out):
                add(label, e)
        return tuple(out)

    def transform(self, x: np.ndarray) -> np.ndarray:
        """4x4 displacement at parameters ``x`` (the factors' parameters, concatenated)."""
        return functools.reduce(np.matmul, (f.transform(x_f) for f, x_f in zip(self.factors, self._split(x))), np.eye(4))

    def _split(self, x: np.ndarray) -> list[np.ndarray]:
        """``x`` cut into the factors' parameters."""
        ends = np.cumsum([f.dim for f in self.factors])
        return [np.asarray(x[e - f.dim : e], dtype=float) for f, e in zip(self.factors, ends)]

    def finite_screw(self, x: np.ndarray) -> FiniteScrew:
        """``F_1(x_1) △ F_2(x_2) △ ...`` (homogeneous form)."""
        return functools.reduce(FiniteScrew.triangle, (f.finite_screw(x_f) for f, x_f in zip(self.factors, self._split(x))), FiniteScrew.identity())

    def fit(self, matrix: np.ndarray, *, starts: int = 6, seed: int = 0, tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[np.ndarray, float]:
        """Parameters of the pattern's motion nearest ``matrix`` and the residual.

        Least squares on the entries of ``[R; p / L]``, from the identity, then
        seeded random starts until the residual is within ``tol.closure``.

        Returns
        -------
        x : ndarray
        residual : float
            Euclidean norm of the residual (0 for a motion of the pattern).
        """
        target = np.asarray(matrix, dtype=float)
        scale = 1.0 / self.length

        def residual(x: np.ndarray) -> np.ndarray:
            t = self.transform(x)
            return np.concatenate([(t[:3, :3] - target[:3, :3]).ravel(), scale * (t[:3, 3] - target[:3, 3])])

        rng = np.random.default_rng(seed)
        best_x, best_r = np.zeros(self.parameter_count), math.inf
        for k in range(max(1, starts)):
            x0 = np.zeros(self.parameter_count) if k == 0 else rng.uniform(-math.pi, math.pi, self.parameter_count)
            sol = least_squares(residual, x0, method="lm", xtol=SOLVER_STOP, ftol=SOLVER_STOP, gtol=SOLVER_STOP)
            r = float(np.linalg.norm(sol.fun))
            if r < best_r:
                best_x, best_r = sol.x, r
            if best_r <= tol.closure:
                break
        return best_x, best_r

    def contains(self, matrix: np.ndarray, *, starts: int = 6, seed: int = 0, tol: Tolerance = DEFAULT_TOLERANCE) -> bool:
        """Whether the displacement ``matrix`` belongs to the pattern: :meth:`fit` to ``tol.closure`` (a loop closure's measure)."""
        return self.fit(matrix, starts=starts, seed=seed, tol=tol)[1] <= tol.closure


def _pattern_2t3r(point: Vector = (0.0, 0.0, 0.0), directions: Sequence[Vector] = ((1, 0, 0), (0, 1, 0))) -> MotionPattern:
    return MotionPattern("2T3R", (PatternFactor("rotations", point), PatternFactor("translations", directions=tuple(directions)[:2])),
                         "two translations in the plane of s1, s2, followed by three rotations about the fixed point O "
                         "(Sun et al. 2018): S_f = 2tan(θ/2)[s; O×s] △ t[0; u], u in span(s1, s2)")


def _pattern_3t(point: Vector = (0.0, 0.0, 0.0), directions: Sequence[Vector] = ((1, 0, 0), (0, 1, 0), (0, 0, 1))) -> MotionPattern:
    return MotionPattern("3T", (PatternFactor("translations", directions=tuple(directions)[:3]),), "spatial translations")


def _pattern_3r(point: Vector = (0.0, 0.0, 0.0), directions: Sequence[Vector] = ()) -> MotionPattern:
    return MotionPattern("3R", (PatternFactor("rotations", point),), "rotations about the fixed point O")


def _pattern_2t1r(point: Vector = (0.0, 0.0, 0.0), directions: Sequence[Vector] = ((1, 0, 0), (0, 1, 0))) -> MotionPattern:
    d = [_unit(v) for v in tuple(directions)[:2]]
    if len(d) < 2:
        raise SynthesisError(f"the 2T1R pattern needs two directions, got {len(d)}")
    return MotionPattern("2T1R", (PatternFactor("translations", directions=tuple(_vec(v) for v in d)),
                                  PatternFactor("rotation", point, (_vec(np.cross(d[0], d[1]), "s1 × s2"),))),
                         "planar motion: rotation about an axis along s1 × s2 through O, followed by translations in the plane of s1, s2")


def _pattern_3t1r(point: Vector = (0.0, 0.0, 0.0), directions: Sequence[Vector] = ((1, 0, 0), (0, 1, 0), (0, 0, 1))) -> MotionPattern:
    d = tuple(directions)[:3]
    if len(d) < 3:
        raise SynthesisError(f"the 3T1R pattern needs three directions, got {len(d)}")
    return MotionPattern("3T1R", (PatternFactor("translations", directions=d), PatternFactor("rotation", point, (_vec(d[2]),))),
                         "Schoenflies motion: rotation about an axis along s3 through O, followed by spatial translations")


PATTERNS = {"2T3R": _pattern_2t3r, "3T": _pattern_3t, "3R": _pattern_3r, "2T1R": _pattern_2t1r, "3T1R": _pattern_3t1r}
"""Named motion patterns: name -> function(point, directions) -> MotionPattern."""

_MOST_DIRECTIONS = 16
"""The directions :func:`named_pattern` reads of an iterable before it says there are too many (an endless generator ends)."""

DIRECTION_COUNTS = {"2T3R": 2, "3T": 3, "3R": 0, "2T1R": 2, "3T1R": 3}
"""The number of directions each named pattern takes (its translation directions; 3T1R's third is also its rotation axis)."""


def named_pattern(name: str, *, point: Iterable[float] = (0.0, 0.0, 0.0), directions: Sequence[Iterable[float]] | None = None) -> MotionPattern:
    """A named motion pattern (see :data:`~mobility.synthesis.patterns.PATTERNS`) at ``point`` with the given directions.

    Raises
    ------
    SynthesisError
        For a name that is not a string, an unknown name or bad geometry.

    Examples
    --------
    >>> named_pattern("3t1r", point=(0, 0, 5)).factors[1].describe()
    'rotations about the line through (0, 0, 5) along (0, 0, 1)'
    >>> named_pattern(None)
    Traceback (most recent call last):
    mobility.errors.SynthesisError: named_pattern: name: expected the name of a motion pattern (2T3R, 3T, 3R, 2T1R, 3T1R), got None
    """
    if not isinstance(name, str):
        raise SynthesisError(caller="named_pattern", argument="name", expected=f"the name of a motion pattern ({', '.join(PATTERNS)})", got=shown_argument(name))
    key = name.strip().upper()
    if key not in PATTERNS:
        raise SynthesisError(f"unknown motion pattern {shown_argument(name)}; expected one of {', '.join(PATTERNS)}")
    kwargs: dict[str, Any] = {"point": _vec(point, "named_pattern: point")}
    if directions is not None:
        wanted = DIRECTION_COUNTS[key]
        try:
            listed = None if isinstance(directions, (str, bytes, bytearray)) else list(itertools.islice(directions, _MOST_DIRECTIONS))
        except TypeError:  # not iterable
            listed = None
        if listed is None:
            raise SynthesisError(caller="named_pattern", argument="directions", expected="a list of directions (3 numbers each)", got=shown_argument(directions))
        given = tuple(_vec(_unit(d, "named_pattern: directions")) for d in listed)
        if len(given) != wanted:
            takes = "no directions" if wanted == 0 else counted(wanted, 'direction')
            raise SynthesisError(f"the {key} pattern takes {takes}, got {len(given) if len(given) < _MOST_DIRECTIONS else f'{_MOST_DIRECTIONS} or more'}")
        if given and _direction_rank(given) < len(given):
            raise SynthesisError(f"the directions of the {key} pattern must be independent, got {[list(d) for d in given]}")
        kwargs["directions"] = given
    return PATTERNS[key](**kwargs)
