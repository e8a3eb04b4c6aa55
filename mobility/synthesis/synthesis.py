"""Type synthesis of limbs by finite screws: which serial chains generate a motion pattern?

A *motion pattern* is a set of finite motions written as a triangle product of
finite-screw factors (:class:`Factor`), e.g. the 2T3R pattern of Sun et al.
(2018): two translations in the plane of ``s1, s2`` followed by three rotations
about a fixed point ``O``,

    ``S_f = 2 tan(θ/2) [s; O × s]  △  t [0; u],   u ∈ span(s1, s2)``

(the translations act first; see :mod:`mobility.core.finite_screws` for the order).

:func:`synthesize` enumerates serial chains of ``R`` and ``P`` joints whose
directions come from the pattern's direction set (its translation directions
and their cross products), whose ``R`` axes pass through the pattern's points
or through generic points, in every order (so every permutation and every
replacement the paper uses, such as an ``S`` by three ``R`` through ``O``, a
``U`` by two, or a translation by a rotation about a parallel axis, is among
the candidates; none is written in).  It keeps the chains whose set of finite
motions *equals* the pattern: every motion of the chain lies in the pattern,
and the chain's motion has the pattern's dimension.  Two routes decide it:

1. **rank route (prunes the search).**  For a pattern ``M = G1 △ G2`` made of
   two subgroups (one factor: ``G1 = G2``), a chain ``L`` (which contains the
   identity) lies in ``M`` exactly when ``G1 △ L △ G2`` has the dimension of
   ``M``: that set contains ``M`` (take ``L`` at its identity) and lies in
   ``G1 M G2 = M`` when ``L ⊂ M``; conversely equal dimension makes the two
   irreducible images coincide.  Dimensions are generic ranks of the twists
   (derivatives of the chain's finite screw) at random seeded joint values,
   decided by :func:`mobility.core.tolerance.decide_rank`.  Every prefix of a valid
   chain is valid too (set the later joints to zero), which prunes the search.
2. **sample route (confirms every chain kept).**  Random finite motions of the
   chain (angles in ``(-π, π)``, slides across the pattern's size) are fitted
   by the pattern's finite screw with :func:`scipy.optimize.least_squares`;
   each must fit to round-off.

Joint groups are named as in the paper: a run of three ``R`` through one point
is an ``S``, of two a ``U``; an ``R`` whose axis is parallel to ``s1 × s2`` is
``Rc``; ``P`` joints in the plane of the pattern's translations are numbered
``P1, P2`` in order of appearance.

Examples
--------
>>> pattern = named_pattern("2T3R")
>>> pattern.dim, [f.kind for f in pattern.factors]
(5, ['rotations', 'translations'])
>>> result = synthesize(pattern, joints=2, verify_samples=1)      # the 2-joint chains in 2T3R
>>> sorted(s.name for s in result.structures)         # Rs1: an R along s1 through O
['P1P2', 'P1Rc', 'P1Rs1', 'P1Rs2', 'RcP1', 'RcRc', 'Rs1P1', 'Rs1Rc', 'Rs2P1', 'Rs2Rc', 'U']
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Iterable, Sequence

import numpy as np
from scipy.optimize import least_squares

from ..errors import SynthesisError
from ..core.finite_screws import FiniteScrew, Limb, ScrewJoint
from ..core.model import Joint, Mechanism
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, characteristic_scale, decide_rank
from ..core.transforms import rotation_from_axis_angle
from ..io.writer import mechanism_to_yaml

__all__ = [
    "Factor",
    "MotionPattern",
    "PATTERNS",
    "named_pattern",
    "CandidateJoint",
    "LimbStructure",
    "SynthesisResult",
    "synthesize",
    "generates",
    "TABLE_1_2T3R",
    "assemble_pkm",
    "pkm_document",
]

TABLE_1_2T3R = ("SP1P2", "UP1P2Rc", "UP1RcP2", "SP1Rc", "SRcRc", "UP1RcRc", "SRcP1")
"""The seven 5-DOF limbs of Table 1 of Sun et al. (2018) for 2T3R PKMs (for comparison only)."""

Vector = tuple[float, float, float]


def _unit(v: Iterable[float]) -> np.ndarray:
    a = np.asarray(v, dtype=float).reshape(3)
    n = float(np.linalg.norm(a))
    if n == 0.0 or not math.isfinite(n):
        raise SynthesisError(f"expected a non-zero finite direction, got {a.tolist()}")
    return a / n


def _vec(v: Iterable[float]) -> Vector:
    a = np.asarray(v, dtype=float).reshape(3)
    return (float(a[0]), float(a[1]), float(a[2]))


_FACTOR_KINDS = ("rotations", "rotation", "translations")


@dataclass(frozen=True)
class Factor:
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
    """

    kind: str
    point: Vector = (0.0, 0.0, 0.0)
    directions: tuple[Vector, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in _FACTOR_KINDS:
            raise SynthesisError(f"factor kind: expected one of {', '.join(_FACTOR_KINDS)}, got {self.kind!r}")
        object.__setattr__(self, "point", _vec(self.point))
        dirs = tuple(_vec(_unit(d)) for d in self.directions)
        object.__setattr__(self, "directions", dirs)
        need = {"rotations": (0, 0), "rotation": (1, 1), "translations": (1, 3)}[self.kind]
        if not need[0] <= len(dirs) <= need[1]:
            raise SynthesisError(f"a {self.kind} factor takes {need[0]}..{need[1]} directions, got {len(dirs)}")
        if dirs and np.linalg.matrix_rank(np.array(dirs), tol=1e-9) < len(dirs):
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
        """A short text, e.g. ``"rotations about (0, 0, 0)"``."""
        fmt = lambda v: "(" + ", ".join(f"{c:g}" for c in v) + ")"  # noqa: E731
        if self.kind == "rotations":
            return f"rotations about the point {fmt(self.point)}"
        if self.kind == "rotation":
            return f"rotations about the line through {fmt(self.point)} along {fmt(self.directions[0])}"
        return "translations along " + ", ".join(fmt(d) for d in self.directions)


@dataclass(frozen=True)
class MotionPattern:
    """A set of finite motions ``S_f = F_1 △ F_2 △ ... △ F_k`` (``F_k`` acts first).

    Parameters
    ----------
    name : str
    factors : tuple of Factor
    description : str
    """

    name: str
    factors: tuple[Factor, ...]
    description: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "factors", tuple(self.factors))
        if not self.factors:
            raise SynthesisError("a motion pattern needs at least one factor")

    @property
    def parameter_count(self) -> int:
        """Sum of the factors' dimensions."""
        return sum(f.dim for f in self.factors)

    @cached_property
    def dim(self) -> int:
        """Dimension of the set of motions (generic rank of its generators)."""
        return _generic_rank(self.generators(), np.random.default_rng(0), 3, self.length)

    def generators(self) -> tuple[ScrewJoint, ...]:
        """The factors' generators, in product order."""
        return tuple(j for f in self.factors for j in f.generators())

    @property
    def points(self) -> tuple[Vector, ...]:
        """The pattern's points (rotation centres and axis points), without repeats."""
        pts: list[Vector] = []
        for f in self.factors:
            if f.kind != "translations" and not any(np.allclose(f.point, p) for p in pts):
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

        The translation directions (``s1, s2, ...``) and the directions of
        rotation factors (``a1, ...``), then the normalised cross products of
        every pair (``c`` for ``s1 × s2``, else ``c1, c2, ...``), then, if they
        do not span space, the coordinate axes that complete them.
        """
        out: list[tuple[str, Vector]] = []

        def add(label: str, d: np.ndarray) -> None:
            d = _unit(d)
            if not any(abs(abs(float(d @ np.array(v))) - 1.0) < 1e-9 for _, v in out):
                out.append((label, _vec(d)))

        for i, d in enumerate(self.translation_directions):
            add(f"s{i + 1}", np.array(d))
        rot = [f.directions[0] for f in self.factors if f.kind == "rotation"]
        for i, d in enumerate(rot):
            add(f"a{i + 1}", np.array(d))
        base = [np.array(v) for _, v in out]
        crosses = [np.cross(a, b) for i, a in enumerate(base) for b in base[i + 1 :] if np.linalg.norm(np.cross(a, b)) > 1e-9]
        for i, c in enumerate(crosses):
            add("c" if len(crosses) == 1 else f"c{i + 1}", c)
        for label, e in zip("xyz", np.eye(3)):
            if np.linalg.matrix_rank(np.array([v for _, v in out] + [e]), tol=1e-9) > len(out):
                add(label, e)
        return tuple(out)

    def transform(self, x: np.ndarray) -> np.ndarray:
        """4x4 displacement at parameters ``x`` (the factors' parameters, concatenated)."""
        out = np.eye(4)
        k = 0
        for f in self.factors:
            out = out @ f.transform(np.asarray(x[k : k + f.dim], dtype=float))
            k += f.dim
        return out

    def finite_screw(self, x: np.ndarray) -> FiniteScrew:
        """``F_1(x_1) △ F_2(x_2) △ ...`` (homogeneous form)."""
        out = FiniteScrew.identity()
        k = 0
        for f in self.factors:
            out = out.triangle(f.finite_screw(np.asarray(x[k : k + f.dim], dtype=float)))
            k += f.dim
        return out

    def fit(self, matrix: np.ndarray, *, starts: int = 6, seed: int = 0) -> tuple[np.ndarray, float]:
        """Parameters of the pattern's motion nearest ``matrix`` and the residual.

        Least squares (:func:`scipy.optimize.least_squares`) on the entries of
        ``[R; p / L]``, from the identity and then random seeded starts until
        the residual is at round-off.

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
            sol = least_squares(residual, x0, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15)
            r = float(np.linalg.norm(sol.fun))
            if r < best_r:
                best_x, best_r = sol.x, r
            if best_r < _FIT_TOLERANCE:
                break
        return best_x, best_r

    def contains(self, matrix: np.ndarray, *, starts: int = 6, seed: int = 0) -> bool:
        """Whether the displacement ``matrix`` belongs to the pattern (a fit to round-off)."""
        return self.fit(matrix, starts=starts, seed=seed)[1] < _FIT_TOLERANCE


_FIT_TOLERANCE = 1e-9
"""A sampled motion belongs to a pattern when the least-squares residual (entries of [R; p/L]) is below this."""


def _pattern_2t3r(point: Vector = (0.0, 0.0, 0.0), directions: Sequence[Vector] = ((1, 0, 0), (0, 1, 0))) -> MotionPattern:
    return MotionPattern(
        "2T3R",
        (Factor("rotations", point), Factor("translations", directions=tuple(directions)[:2])),
        "two translations in the plane of s1, s2, followed by three rotations about the fixed point O "
        "(Sun et al. 2018): S_f = 2tan(θ/2)[s; O×s] △ t[0; u], u in span(s1, s2)",
    )


def _pattern_3t(point: Vector = (0.0, 0.0, 0.0), directions: Sequence[Vector] = ((1, 0, 0), (0, 1, 0), (0, 0, 1))) -> MotionPattern:
    return MotionPattern("3T", (Factor("translations", directions=tuple(directions)[:3]),), "spatial translations")


def _pattern_3r(point: Vector = (0.0, 0.0, 0.0), directions: Sequence[Vector] = ()) -> MotionPattern:
    return MotionPattern("3R", (Factor("rotations", point),), "rotations about the fixed point O")


def _pattern_2t1r(point: Vector = (0.0, 0.0, 0.0), directions: Sequence[Vector] = ((1, 0, 0), (0, 1, 0))) -> MotionPattern:
    d = [_unit(v) for v in tuple(directions)[:2]]
    return MotionPattern(
        "2T1R",
        (Factor("translations", directions=tuple(_vec(v) for v in d)), Factor("rotation", point, (_vec(np.cross(d[0], d[1])),))),
        "planar motion: rotation about an axis along s1 × s2 through O, followed by translations in the plane of s1, s2",
    )


def _pattern_3t1r(point: Vector = (0.0, 0.0, 0.0), directions: Sequence[Vector] = ((1, 0, 0), (0, 1, 0), (0, 0, 1))) -> MotionPattern:
    d = tuple(directions)[:3]
    return MotionPattern(
        "3T1R",
        (Factor("translations", directions=d), Factor("rotation", point, (_vec(d[2]),))),
        "Schoenflies motion: rotation about an axis along s3 through O, followed by spatial translations",
    )


PATTERNS = {"2T3R": _pattern_2t3r, "3T": _pattern_3t, "3R": _pattern_3r, "2T1R": _pattern_2t1r, "3T1R": _pattern_3t1r}
"""Named motion patterns: name -> function(point, directions) -> MotionPattern."""


def named_pattern(name: str, *, point: Iterable[float] = (0.0, 0.0, 0.0), directions: Sequence[Iterable[float]] | None = None) -> MotionPattern:
    """A named motion pattern (see :data:`PATTERNS`) at ``point`` with the given directions.

    Raises
    ------
    SynthesisError
        For an unknown name or bad geometry.
    """
    key = name.strip().upper()
    if key not in PATTERNS:
        raise SynthesisError(f"unknown motion pattern {name!r}; expected one of {', '.join(PATTERNS)}")
    kwargs: dict[str, Any] = {"point": _vec(point)}
    if directions is not None:
        kwargs["directions"] = tuple(_vec(_unit(d)) for d in directions)
    return PATTERNS[key](**kwargs)


# -- generic ranks ----------------------------------------------------------------


def _twists_batch(joints: Sequence[ScrewJoint], q: np.ndarray) -> np.ndarray:
    """Spatial twists of a chain at many poses at once: shape (samples, 6, n).

    Column ``j`` is the twist of joint ``j`` carried by the joints before it,
    ``Ad(T_1 ... T_{j-1}) ξ_j``; this equals the derivative of the chain's
    finite screw mapped by Eq. 5 (:meth:`Limb.twists`, pinned by a test), only
    computed for many samples together.
    """
    samples, n = q.shape
    rot = np.broadcast_to(np.eye(3), (samples, 3, 3)).copy()
    pos = np.zeros((samples, 3))
    out = np.empty((samples, 6, n))
    for j, joint in enumerate(joints):
        s = np.asarray(joint.axis)
        w = rot @ s
        if joint.kind == "P":
            out[:, :3, j] = 0.0
            out[:, 3:, j] = w
            pos = pos + w * q[:, j : j + 1]
            continue
        r = np.einsum("kij,j->ki", rot, np.asarray(joint.point)) + pos  # the axis point, carried
        out[:, :3, j] = w
        out[:, 3:, j] = np.cross(r, w) + joint.pitch * w
        # T <- T @ exp(q ξ): rotation about the carried axis through r (plus pitch slide)
        k = np.zeros((samples, 3, 3))
        k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -s[2], s[1], -s[0]
        k[:, 1, 0], k[:, 2, 0], k[:, 2, 1] = s[2], -s[1], s[0]
        th = q[:, j][:, None, None]
        local = np.eye(3) + np.sin(th) * k + (1.0 - np.cos(th)) * (k @ k)
        p_local = np.asarray(joint.point) - local @ np.asarray(joint.point) + joint.pitch * q[:, j][:, None] * s
        pos = pos + np.einsum("kij,kj->ki", rot, p_local)
        rot = rot @ local
    return out


def _sample_values(joints: Sequence[ScrewJoint], rng: np.random.Generator, samples: int, length: float) -> np.ndarray:
    q = rng.uniform(-math.pi, math.pi, (samples, len(joints)))
    for j, joint in enumerate(joints):
        if joint.kind == "P":
            q[:, j] = rng.uniform(-length, length, samples)
    return q


def _generic_rank(joints: Sequence[ScrewJoint], rng: np.random.Generator, samples: int, length: float, tol: Tolerance = DEFAULT_TOLERANCE) -> int:
    """Largest rank of the chain's twists over random poses (normalised coordinates, unit columns)."""
    if not joints:
        return 0
    tw = _twists_batch(joints, _sample_values(joints, rng, samples, length))
    tw[:, 3:, :] /= length
    tw /= np.linalg.norm(tw, axis=1, keepdims=True)
    sv = np.linalg.svd(tw, compute_uv=False)
    return max(decide_rank(s, tol).rank for s in sv)


# -- enumeration --------------------------------------------------------------------


@dataclass(frozen=True)
class CandidateJoint:
    """A one-DOF joint of the enumeration, with the labels of its direction and point."""

    joint: ScrewJoint
    direction: str
    point: str = ""

    @property
    def label(self) -> str:
        """e.g. ``R[c@g1]`` or ``P[s1]``."""
        return f"{self.joint.kind}[{self.direction}{'@' + self.point if self.point else ''}]"


@dataclass(frozen=True)
class LimbStructure:
    """A limb type found by :func:`synthesize`: a name and every joint sequence realising it.

    Attributes
    ----------
    name : str
        Paper-style name, e.g. ``"UP1RcP2"``.
    groups : tuple of str
        The joint groups in order (``S``, ``U``, ``Rc``, ``P1``...).
    realizations : tuple of tuple of CandidateJoint
        The joint sequences found (directions and points from the pattern).
    conditions : tuple of str
        One line per group: the directions and points it was found with.
    in_table_1 : bool
        Whether the name is among the seven of Table 1 of Sun et al. (2018)
        (meaningful for the 2T3R pattern only; for comparison, not used to decide).
    """

    name: str
    groups: tuple[str, ...]
    realizations: tuple[tuple[CandidateJoint, ...], ...]
    conditions: tuple[str, ...]
    in_table_1: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {
            "name": self.name,
            "groups": list(self.groups),
            "conditions": list(self.conditions),
            "in_table_1": self.in_table_1,
            "realizations": [[c.label for c in r] for r in self.realizations],
        }


@dataclass(frozen=True)
class SynthesisResult:
    """What :func:`synthesize` finds (frozen).

    Attributes
    ----------
    pattern : MotionPattern
    joints : int
        Number of one-DOF joints per limb.
    alphabet : tuple of CandidateJoint
        The candidate joints that survived the single-joint test.
    rejected_joints : tuple of CandidateJoint
        Candidates whose own motion already leaves the pattern.
    structures : tuple of LimbStructure
        Limb types found, in order of first discovery.
    sequences : int
        Joint sequences kept.
    candidates_tested : int
        Rank tests made during the search.
    verified_samples : int
        Finite motions fitted by the pattern (sample route), all to round-off.
    seconds : float
        Wall time of the search and the verification.
    points : dict
        Label -> point used (``O``, ``g1``...).
    directions : dict
        Label -> direction used (``s1``, ``s2``, ``c``...).
    """

    pattern: MotionPattern
    joints: int
    alphabet: tuple[CandidateJoint, ...]
    rejected_joints: tuple[CandidateJoint, ...]
    structures: tuple[LimbStructure, ...]
    sequences: int
    candidates_tested: int
    verified_samples: int
    seconds: float
    points: dict[str, Vector] = field(default_factory=dict)
    directions: dict[str, Vector] = field(default_factory=dict)

    def structure(self, name: str) -> LimbStructure:
        """The structure called ``name``."""
        for s in self.structures:
            if s.name == name:
                return s
        raise KeyError(name)

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {
            "pattern": self.pattern.name,
            "description": self.pattern.description,
            "factors": [f.describe() for f in self.pattern.factors],
            "dim": self.pattern.dim,
            "joints": self.joints,
            "points": {k: list(v) for k, v in self.points.items()},
            "directions": {k: list(v) for k, v in self.directions.items()},
            "alphabet": [c.label for c in self.alphabet],
            "rejected_joints": [c.label for c in self.rejected_joints],
            "structures": [s.to_dict() for s in self.structures],
            "sequences": self.sequences,
            "candidates_tested": self.candidates_tested,
            "verified_samples": self.verified_samples,
            "seconds": self.seconds,
        }


def _candidate_joints(pattern: MotionPattern, generic_points: int, rng: np.random.Generator) -> tuple[list[CandidateJoint], dict[str, Vector], dict[str, Vector]]:
    """R joints along every direction of the set through every point, P joints along every direction."""
    directions = pattern.directions()
    points: list[tuple[str, Vector]] = []
    for i, p in enumerate(pattern.points):
        points.append(("O" if i == 0 else f"O{i + 1}", p))
    centre = np.mean([p for _, p in points], axis=0) if points else np.zeros(3)
    length = pattern.length
    for k in range(generic_points):
        points.append((f"g{k + 1}", _vec(centre + length * rng.uniform(-1.0, 1.0, 3))))
    out = [CandidateJoint(ScrewJoint("R", d, p), dl, pl) for pl, p in points for dl, d in directions]
    out += [CandidateJoint(ScrewJoint("P", d), dl) for dl, d in directions]
    return out, dict(points), dict(directions)


def synthesize(
    pattern: MotionPattern | str,
    *,
    joints: int | None = None,
    generic_points: int | None = None,
    samples: int = 3,
    verify_samples: int = 2,
    seed: int = 0,
    tol: Tolerance = DEFAULT_TOLERANCE,
) -> SynthesisResult:
    """Enumerate the limbs of R and P joints whose finite motions are the pattern.

    Parameters
    ----------
    pattern : MotionPattern or str
        A pattern or a name of :data:`PATTERNS` (default geometry).
    joints : int, optional
        One-DOF joints per limb (default: the pattern's dimension).
    generic_points : int, optional
        Generic points for R axes off the pattern's points (default: ``joints``).
    samples : int
        Random poses per generic-rank decision.
    verify_samples : int
        Random finite motions of each kept joint sequence fitted by the pattern
        (the sample route); 0 skips it.
    seed : int
        Seed of every random choice (generic points, poses, fit starts).
    tol : Tolerance
        Rank policy.

    Returns
    -------
    SynthesisResult

    Raises
    ------
    SynthesisError
        For a pattern with more than two factors (the rank route needs
        ``M = G1 △ G2``) or a joint count below 1.
    """
    start = time.perf_counter()
    if isinstance(pattern, str):
        pattern = named_pattern(pattern)
    if len(pattern.factors) > 2:
        raise SynthesisError("synthesize needs a pattern of one or two factors (M = G1 △ G2)")
    dim = pattern.dim
    n = dim if joints is None else int(joints)
    if n < 1:
        raise SynthesisError(f"joints: expected at least 1, got {n}")
    rng = np.random.default_rng(seed)
    candidates, points, directions = _candidate_joints(pattern, n if generic_points is None else generic_points, rng)
    outer_left = pattern.factors[0].generators()
    outer_right = pattern.factors[-1].generators()
    length = pattern.length
    tested = 0

    def inside(chain: tuple[ScrewJoint, ...]) -> bool:
        nonlocal tested
        tested += 1
        return _generic_rank(outer_left + chain + outer_right, rng, samples, length, tol) == dim

    def independent(chain: tuple[ScrewJoint, ...]) -> bool:
        return _generic_rank(chain, rng, samples, length, tol) == len(chain)

    alphabet = [c for c in candidates if inside((c.joint,))]
    rejected = [c for c in candidates if c not in alphabet]
    found: list[tuple[CandidateJoint, ...]] = []

    def generic_index(label: str) -> int:
        return int(label[1:]) if label.startswith("g") else 0

    def extend(prefix: tuple[CandidateJoint, ...], used_generic: int) -> None:
        if len(prefix) == n:
            found.append(prefix)
            return
        for c in alphabet:
            g = generic_index(c.point)
            if g > used_generic + 1:  # generic points are interchangeable: use them in order
                continue
            chain = tuple(x.joint for x in prefix) + (c.joint,)
            if not independent(chain) or not inside(chain):
                continue
            extend(prefix + (c,), max(used_generic, g))

    extend((), 0)
    if n == dim:
        found = [f for f in found if _generic_rank(tuple(x.joint for x in f), rng, samples, length, tol) == dim]
    verified = 0
    if verify_samples > 0:
        for seq in found:
            limb = Limb(tuple(x.joint for x in seq))
            for q in _sample_values(limb.joints, rng, verify_samples, length):
                matrix = limb.transform(q)
                if not pattern.contains(matrix, seed=seed):
                    raise AssertionError(f"rank route and sample route disagree on {' '.join(x.label for x in seq)}")  # pragma: no cover
                verified += 1
    structures = _structures(found, pattern, directions)
    return SynthesisResult(
        pattern,
        n,
        tuple(alphabet),
        tuple(rejected),
        structures,
        len(found),
        tested,
        verified,
        time.perf_counter() - start,
        points,
        directions,
    )


def generates(pattern: MotionPattern, joints: Sequence[ScrewJoint], *, samples: int = 3, seed: int = 0, tol: Tolerance = DEFAULT_TOLERANCE) -> bool:
    """Whether the chain's set of finite motions equals the pattern (rank route).

    True when every motion of the chain lies in the pattern (``G1 △ L △ G2``
    has the pattern's dimension) and the chain's motion has that dimension.

    Examples
    --------
    >>> p = named_pattern("2T3R")
    >>> S = [ScrewJoint("R", e) for e in ((1, 0, 0), (0, 1, 0), (0, 0, 1))]          # three R through O
    >>> P1, P2 = ScrewJoint("P", (1, 0, 0)), ScrewJoint("P", (0, 1, 0))
    >>> generates(p, S + [P1, P2]), generates(p, [P1, P2] + S)                      # SP1P2 yes; P1P2S no
    (True, False)
    """
    if len(pattern.factors) > 2:
        raise SynthesisError("the rank route needs a pattern of one or two factors (M = G1 △ G2)")
    chain = tuple(joints)
    rng = np.random.default_rng(seed)
    dim = pattern.dim
    outer = _generic_rank(pattern.factors[0].generators() + chain + pattern.factors[-1].generators(), rng, samples, pattern.length, tol)
    return outer == dim and _generic_rank(chain, rng, samples, pattern.length, tol) == dim


def _groups(seq: Sequence[CandidateJoint], plane: tuple[str, ...]) -> list[tuple[str, list[CandidateJoint]]]:
    """Split a joint sequence into named groups: runs of R through one point (S, U), Rc, P1, P2..."""
    out: list[tuple[str, list[CandidateJoint]]] = []
    i = 0
    p_count = 0
    while i < len(seq):
        c = seq[i]
        if c.joint.kind == "R":
            j = i
            while j + 1 < len(seq) and seq[j + 1].joint.kind == "R" and seq[j + 1].point == c.point:
                j += 1
            run = list(seq[i : j + 1])
            while run:
                take = run[:3]
                run = run[3:]
                if len(take) == 3:
                    out.append(("S", take))
                elif len(take) == 2:
                    out.append(("U", take))
                else:
                    out.append(("Rc" if take[0].direction == "c" else f"R{take[0].direction}", take))
            i = j + 1
        else:
            if c.direction in plane:
                p_count += 1
                out.append((f"P{p_count}", [c]))
            else:
                out.append((f"P{c.direction}", [c]))
            i += 1
    return out


def _structures(found: list[tuple[CandidateJoint, ...]], pattern: MotionPattern, directions: dict[str, Vector]) -> tuple[LimbStructure, ...]:
    plane = tuple(f"s{i + 1}" for i in range(len(pattern.translation_directions)))
    by_name: dict[str, list[tuple[tuple[str, ...], tuple[CandidateJoint, ...], list[list[CandidateJoint]]]]] = {}
    for seq in found:
        groups = _groups(seq, plane)
        name = "".join(g for g, _ in groups)
        by_name.setdefault(name, []).append((tuple(g for g, _ in groups), seq, [m for _, m in groups]))
    out = []
    for name, entries in by_name.items():
        names = entries[0][0]
        conditions = []
        for k, g in enumerate(names):
            members = [e[2][k] for e in entries]
            pts = sorted({c.point for m in members for c in m if c.point})
            where = f" through {' or '.join(pts)}" if pts else ""
            if g == "S":
                conditions.append(f"S: three R{where}")
            elif g == "U":
                axes = sorted({"(" + ", ".join(c.direction for c in m) + ")" for m in members})
                conditions.append(f"U: two R{where}, axes {' or '.join(axes)}")
            else:
                dirs = sorted({m[0].direction for m in members})
                what = "along" if g.startswith("P") else "axis along"
                conditions.append(f"{g}: {what} {' or '.join(dirs)}{where}")
        out.append(LimbStructure(name, names, tuple(e[1] for e in entries), tuple(conditions), pattern.name == "2T3R" and name in TABLE_1_2T3R))
    return tuple(out)


# -- assembly of PKMs ------------------------------------------------------------------


def _freedom_twist(f: Any, origin: np.ndarray, length: float) -> np.ndarray:
    """Unit twist of a model freedom in coordinates centred at ``origin``, lengths over ``length``."""
    s = np.asarray(f.axis)
    if f.kind == "P":
        return np.concatenate([np.zeros(3), s])
    return np.concatenate([s, np.cross((np.asarray(f.point) - origin) / length, s)])


def _mechanism_joints(seq: Sequence[CandidateJoint], groups: Sequence[tuple[str, list[CandidateJoint]]], points: dict[str, np.ndarray], prefix: str, base: str, end: str) -> list[Joint]:
    """Mechanism joints of a limb from its groups (S and U become one joint each)."""
    out = []
    links = [base] + [f"{prefix}{k + 1}" for k in range(len(groups) - 1)] + [end]
    for k, (g, members) in enumerate(groups):
        a, b = links[k], links[k + 1]
        first = members[0]
        name = f"{prefix}_{g}" if sum(1 for h, _ in groups if h == g) == 1 else f"{prefix}_{g}{k + 1}"
        if g == "S":
            out.append(Joint(name, "S", (a, b), point=tuple(points[first.point])))
        elif g == "U":
            out.append(Joint(name, "U", (a, b), point=tuple(points[first.point]), axes=(members[0].joint.axis, members[1].joint.axis)))
        elif first.joint.kind == "P":
            out.append(Joint(name, "P", (a, b), axis=first.joint.axis))
        else:
            out.append(Joint(name, "R", (a, b), axis=first.joint.axis, point=tuple(points[first.point])))
    return out


def assemble_pkm(
    result: SynthesisResult,
    structure: str,
    *,
    other: str = "UPS",
    copies: int = 4,
    base_radius: float = 600.0,
    platform_radius: float = 400.0,
    height: float = 900.0,
    twist_deg: float = 60.0,
    twist_pattern: Sequence[float] = (1.0, 0.0, 1.0, 2.0),
    name: str | None = None,
) -> Mechanism:
    """A PKM of one synthesized limb and ``copies`` 6-DOF limbs, as a :class:`Mechanism`.

    The first realisation of ``structure`` (a name in ``result``) is used as
    found, with the pattern's point ``O`` where the pattern put it (the base
    centre, for a machine) and its generic points (``g1, g2, ...``) moved onto
    the line through ``O`` along ``s1``, at distances ``height``, ``height/2``,
    ``height/4``...  (for a machine, synthesize with ``s1`` vertical, e.g.
    ``directions=((0, 0, 1), (0, 1, 0))``).  The 6-DOF limbs are ``UPS`` (U on
    the base with a vertical and a tangential axis, S on the platform) or
    ``SPRR`` (S on the base, then two R on the platform, the first horizontal
    and normal to the leg, the second vertical: each R normal to the axis
    before it, so the limb reaches every orientation), attached at ``base_radius`` in the plane through ``O``
    normal to z and, turned by ``twist_deg``, at ``platform_radius`` and
    ``height``.  Every 6-DOF limb's P is actuated, and so is the first P of
    the synthesized limb (its last R if it has none; none if it has neither).

    Raises
    ------
    SynthesisError
        For an unknown ``other`` limb.
    KeyError
        When ``structure`` is not in ``result``.
    """
    if other not in ("UPS", "SPRR"):
        raise SynthesisError(f"other: expected UPS or SPRR, got {other!r}")
    found = result.structure(structure)
    plane = tuple(k for k in result.directions if k.startswith("s"))
    s1 = np.array(result.directions.get("s1", (0.0, 0.0, 1.0)))
    s2 = np.array(result.directions.get("s2", np.cross(s1, [1.0, 0.0, 0.0]) if abs(s1[0]) < 0.9 else np.cross(s1, [0.0, 1.0, 0.0])))
    s2 = s2 - (s2 @ s1) * s1
    s2 /= np.linalg.norm(s2)
    origin = np.array(result.points.get("O", (0.0, 0.0, 0.0)))
    joints: list[Joint] = []
    for offset in (0.0, 0.25):  # first g on the line through O along s1, then every g off it
        points: dict[str, np.ndarray] = {k: np.array(v) for k, v in result.points.items()}
        for label in points:
            if label.startswith("g"):  # off one line through O, so that two Rc do not lose rank at home
                k = int(label[1:]) - 1
                points[label] = origin + height / 2**k * s1 + (offset if k == 0 else (-1) ** k / 4) * height * s2
        for seq in found.realizations:
            joints = _mechanism_joints(seq, _groups(seq, plane), points, "L0", "base", "platform")
            twists = np.array([_freedom_twist(f, origin, height) for j in joints for f in j.freedoms()]).T
            if decide_rank(np.linalg.svd(twists, compute_uv=False)).rank == twists.shape[1]:
                break
        else:
            continue
        break
    else:
        raise SynthesisError(f"every realisation of {structure} is singular at its home pose (all joint values zero) with these points")
    acted = next((j for j in joints if j.type == "P"), None) or next((j for j in reversed(joints) if j.type == "R"), None)
    joints = [Joint(j.name, j.type, j.links, j.axis, j.point, j.pitch, j.axes, j.normal, j.frame, j is acted) for j in joints]
    for i in range(copies):
        phi = math.radians(45.0 + 360.0 * i / copies)
        psi = phi + math.radians(twist_deg) * twist_pattern[i % len(twist_pattern)]
        a = origin + np.array([base_radius * math.cos(phi), base_radius * math.sin(phi), 0.0])
        b = origin + np.array([platform_radius * math.cos(psi), platform_radius * math.sin(psi), height])
        tangent_a = np.array([-math.sin(phi), math.cos(phi), 0.0])
        across = np.cross(b - a, [0.0, 0.0, 1.0])
        across /= np.linalg.norm(across)
        up = np.array([0.0, 0.0, 1.0])
        k = i + 1
        if other == "UPS":
            joints += [
                Joint(f"U{k}", "U", ("base", f"L{k}a"), point=tuple(a), axes=(tuple(up), tuple(tangent_a))),
                Joint(f"P{k}", "P", (f"L{k}a", f"L{k}b"), axis=tuple(b - a), actuated=True),
                Joint(f"S{k}", "S", (f"L{k}b", "platform"), point=tuple(b)),
            ]
        else:
            joints += [
                Joint(f"S{k}", "S", ("base", f"L{k}a"), point=tuple(a)),
                Joint(f"P{k}", "P", (f"L{k}a", f"L{k}b"), axis=tuple(b - a), actuated=True),
                Joint(f"R{k}a", "R", (f"L{k}b", f"L{k}c"), axis=tuple(across), point=tuple(b)),
                Joint(f"R{k}b", "R", (f"L{k}c", "platform"), axis=tuple(up), point=tuple(b)),
            ]
    return Mechanism(name or f"{found.name}-{copies}({other})", "base", "platform", tuple(joints))


def pkm_document(result: SynthesisResult, structure: str, *, other: str = "UPS", **geometry: Any) -> tuple[Mechanism, str]:
    """A PKM assembled by :func:`assemble_pkm`, analysed, and its mechanism file text.

    The ``expected`` block comes from the synthesis (DOF and pattern of the
    pattern, mobility the Grübler-Kutzbach count), and :func:`mobility.analyze`
    must agree before the text is returned.

    Raises
    ------
    SynthesisError
        When the limb cannot be assembled at its home pose, or the analyzer
        disagrees with the expected values.

    Returns
    -------
    mechanism : Mechanism
    text : str
    """
    from ..core.analysis import analyze, gruebler_kutzbach  # a producer of models may call the analysis; nothing below imports this module

    mechanism = assemble_pkm(result, structure, other=other, **geometry)
    found = result.structure(structure)
    # Expected from the synthesis, not from the analyzer: the limb's finite motions are the pattern, and the
    # 6-DOF limbs add no constraint, so the platform moves in the pattern; with no redundant constraint the
    # mobility is the Grübler-Kutzbach count.
    pattern_text = result.pattern.name
    expected = {"dof": result.pattern.dim, "pattern": pattern_text, "mobility": gruebler_kutzbach(mechanism)}
    r = analyze(mechanism)
    if (r.dof, r.pattern, r.mobility) != (expected["dof"], expected["pattern"], expected["mobility"]):
        raise SynthesisError(f"{structure}: the analyzer finds {r.dof} DOF {r.pattern}, mobility {r.mobility} for the assembled PKM, not {expected}")
    table = " It is one of the seven 5-DOF limbs of Table 1 of that paper." if found.in_table_1 else " It is not in Table 1 of that paper; the enumeration found it."
    description = (
        f"A {expected['dof']}-DOF parallel mechanism of one {found.name} limb and {mechanism.name.split('-', 1)[1]} limbs, "
        f"assembled by mobility.assemble_pkm from the type synthesis of the {result.pattern.name} pattern "
        f"({result.pattern.description}) after T. Sun, S. Yang, T. Huang, J. S. Dai, 'A Finite and Instantaneous Screw "
        f"Based Approach for Topology Design and Kinematic Analysis of 5-Axis Parallel Kinematic Machines', Chinese "
        f"Journal of Mechanical Engineering 31:44 (2018).{table} Conditions of the limb: {'; '.join(found.conditions)}. "
        f"Dimensions are illustrative (mm). Expected: the limb's finite motions are the {pattern_text} pattern and the "
        f"6-DOF limbs add no constraint, so the platform has {expected['dof']} DOF, {pattern_text}; the mobility is the "
        f"Grübler-Kutzbach count (no redundant constraint)."
    )
    return mechanism, mechanism_to_yaml(mechanism, description=description, expected=expected)
