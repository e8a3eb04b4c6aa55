"""Type synthesis of limbs by finite screws: which serial chains generate a motion pattern?

:func:`synthesize` enumerates chains of ``R`` and ``P`` joints along the
pattern's directions, in every order, and keeps those whose finite motions
*equal* the pattern: the rank route (:mod:`mobility.synthesis.generic_rank`)
prunes, the sample route (:meth:`~mobility.synthesis.patterns.MotionPattern.contains`)
confirms; docs/finite-screws.md, "Type synthesis", tells both.  Sequences are
grouped into limb types named as in the paper (:mod:`mobility.synthesis.limb_types`).

Examples
--------
>>> from mobility.synthesis.patterns import named_pattern
>>> result = synthesize(named_pattern("2T3R"), joints=2, verify_samples=1)      # the 2-joint chains in 2T3R
>>> sorted(s.name for s in result.structures)         # Rs1: an R along s1 through O
['P1P2', 'P1Rc', 'P1Rs1', 'P1Rs2', 'RcP1', 'RcRc', 'Rs1P1', 'Rs1Rc', 'Rs2P1', 'Rs2Rc', 'U']
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Iterable, Sequence, cast

import numpy as np

from ..core.finite_screws import Limb, ScrewJoint
from ..core.validation import require_instance, require_integer
from ..core.poses import require_seed
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, require_tolerance
from ..errors import AnalysisError, SynthesisError, counted, shown_argument
from .generic_rank import generic_rank, sample_joint_values
from .limb_types import CandidateJoint, SynthesizedLimb, limb_types
from .patterns import MotionPattern, Vector, named_pattern

__all__ = ["SynthesisResult", "candidate_joints", "synthesize", "generates", "MAX_SAMPLES", "MAX_VERIFY_SAMPLES", "MAX_GENERIC_POINTS"]

MAX_SAMPLES = 30
"""Largest ``samples`` of :func:`synthesize` (``mobility synthesize --samples``): random poses per rank decision (3 decide every bundled pattern; 30 take 2T3R about 6 s)."""

MAX_VERIFY_SAMPLES = 10
"""Largest ``verify_samples`` (``--verify``): each verified sample fits every kept limb's motions by the pattern (10 take 2T3R about 20 s)."""

MAX_GENERIC_POINTS = 50
"""Largest ``generic_points``: each adds one candidate R joint per direction, tested once; a chain of ``n`` joints uses at most ``n`` of them."""


@dataclass(frozen=True)
class SynthesisResult:
    """What :func:`synthesize` finds (frozen).

    Attributes
    ----------
    pattern : MotionPattern
    joints : int
        Number of one-DOF joints per limb.
    alphabet, rejected_joints : tuple of CandidateJoint
        The candidate joints that survived the single-joint test; those whose own motion leaves the pattern.
    structures : tuple of SynthesizedLimb
        Limb types found, in order of first discovery.
    sequences, candidates_tested, verified_samples : int
        Joint sequences kept; rank tests made; finite motions fitted by the pattern (the sample route).
    seconds : float
        Wall time of the search and the verification.
    points, directions : dict
        Label -> point (``O``, ``g1``...) and label -> direction (``s1``, ``c``...) used.
    """

    pattern: MotionPattern
    joints: int
    alphabet: tuple[CandidateJoint, ...]
    rejected_joints: tuple[CandidateJoint, ...]
    structures: tuple[SynthesizedLimb, ...]
    sequences: int
    candidates_tested: int
    verified_samples: int
    seconds: float
    points: dict[str, Vector] = field(default_factory=dict)
    directions: dict[str, Vector] = field(default_factory=dict)

    def structure(self, name: str) -> SynthesizedLimb:
        """The limb type called ``name``.

        Raises
        ------
        SynthesisError
            When no limb type of that name was found.
        """
        for s in self.structures:
            if s.name == name:
                return s
        found = ", ".join(s.name for s in self.structures) or "none"
        raise SynthesisError(f"no limb type {name!r} in the synthesis of {self.pattern.name} with {counted(self.joints, 'joint')}; found: {found}")

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {"pattern": self.pattern.name, "description": self.pattern.description, "factors": [f.describe() for f in self.pattern.factors],
                "dim": self.pattern.dim, "joints": self.joints, "points": {k: list(v) for k, v in self.points.items()},
                "directions": {k: list(v) for k, v in self.directions.items()}, "alphabet": [c.label for c in self.alphabet],
                "rejected_joints": [c.label for c in self.rejected_joints], "structures": [s.to_dict() for s in self.structures],
                "sequences": self.sequences, "candidates_tested": self.candidates_tested, "verified_samples": self.verified_samples,
                "seconds": self.seconds}


def candidate_joints(pattern: MotionPattern, generic_points: int, rng: np.random.Generator) -> tuple[list[CandidateJoint], dict[str, Vector], dict[str, Vector]]:
    """R joints along every direction of the set through every point, P joints along every direction.

    The points are the pattern's (``O``, ``O2``...) and ``generic_points``
    random ones (``g1, g2...``) within the pattern's length of their centre.
    Returns the candidates and the label -> point, label -> direction dicts.
    """
    directions = pattern.directions()
    points: list[tuple[str, Vector]] = [("O" if i == 0 else f"O{i + 1}", p) for i, p in enumerate(pattern.points)]
    centre = np.mean([p for _, p in points], axis=0) if points else np.zeros(3)
    length = pattern.length
    for k in range(generic_points):
        g = centre + length * rng.uniform(-1.0, 1.0, 3)
        points.append((f"g{k + 1}", (float(g[0]), float(g[1]), float(g[2]))))
    out = [CandidateJoint(ScrewJoint("R", d, p), dl, pl) for pl, p in points for dl, d in directions]
    out += [CandidateJoint(ScrewJoint("P", d), dl) for dl, d in directions]
    return out, dict(points), dict(directions)


def _count(value: object, key: str, least: int, most: int | None = None, caller: str = "synthesize") -> int:
    """A count of :func:`synthesize`: an integer (not a bool) from ``least`` to ``most``, else a :class:`SynthesisError` naming ``key``.

    Examples
    --------
    >>> _count(np.int64(2), "samples", 1, MAX_SAMPLES)
    2
    >>> _count(2.5, "joints", 1)
    Traceback (most recent call last):
    mobility.errors.SynthesisError: synthesize: joints: expected an integer of at least 1, got 2.5
    >>> _count(10**400, "samples", 1, MAX_SAMPLES)
    Traceback (most recent call last):
    mobility.errors.SynthesisError: synthesize: samples: expected an integer from 1 to 30, got 100000000000000000000000000000000000...
    """
    expected = f"of at least {least}" if most is None else f"from {least} to {most}"
    return require_integer(value, f"an integer {expected}", caller=caller, argument=key, low=least, high=most, error=SynthesisError)


def synthesize(pattern: MotionPattern | str, *, joints: int | None = None, generic_points: int | None = None, samples: int = 3,
               verify_samples: int = 2, seed: int = 0, tol: Tolerance = DEFAULT_TOLERANCE) -> SynthesisResult:
    """Enumerate the limbs of R and P joints whose finite motions are the pattern.

    Parameters
    ----------
    pattern : MotionPattern or str
        A pattern or a name of :data:`~mobility.synthesis.patterns.PATTERNS` (default geometry).
    joints : int, optional
        One-DOF joints per limb (default and most: the pattern's dimension;
        fewer give the parts of limbs).
    generic_points : int, optional
        Generic points for R axes off the pattern's points (default: ``joints``;
        at most :data:`MAX_GENERIC_POINTS`).
    samples : int
        Random poses per generic-rank decision (from 1 to :data:`MAX_SAMPLES`).
    verify_samples : int
        Random finite motions of each kept sequence fitted by the pattern (the
        sample route), at most :data:`MAX_VERIFY_SAMPLES`; 0 skips it.
    seed : int
        Seed of every random choice (generic points, poses, fit starts).
    tol : Tolerance
        Rank policy, and the closure tolerance of the sample route.

    Raises
    ------
    SynthesisError
        A pattern of more than two factors, an unknown name, or a count out of its range.
    RequestError
        A ``pattern`` neither a :class:`MotionPattern` nor a name, or a bad ``seed``.
    AnalysisError
        When the two routes disagree on a chain: a rank decision was too close to call.

    Examples
    --------
    The limbs of three joints generating the planar 2T1R pattern:

    >>> r = synthesize("2T1R", verify_samples=0)
    >>> len(r.structures), [s.name for s in r.structures[:4]]
    (7, ['Ra1Ra1Ra1', 'Ra1Ra1P1', 'Ra1P1Ra1', 'Ra1P1P2'])
    """
    start = time.perf_counter()
    if isinstance(pattern, str):
        pattern = named_pattern(pattern)
    pattern = require_instance(pattern, MotionPattern, "synthesize: pattern", "named_pattern, a name such as '2T3R',")
    samples, verify_samples = _count(samples, "samples", 1, MAX_SAMPLES), _count(verify_samples, "verify_samples", 0, MAX_VERIFY_SAMPLES)
    joints = None if joints is None else _count(joints, "joints", 1)
    generic_points = None if generic_points is None else _count(generic_points, "generic_points", 0, MAX_GENERIC_POINTS)
    rng = np.random.default_rng(require_seed(seed, "synthesize: seed"))
    tol = require_tolerance(tol, "synthesize")
    if len(pattern.factors) > 2:
        raise SynthesisError("synthesize needs a pattern of one or two factors (M = G1 △ G2)")
    # searched with its points' centre at the origin (far from it, twists lose their moments' digits); points moved back at the end
    given = pattern
    centre = np.mean(np.asarray(pattern.points or [(0.0, 0.0, 0.0)], dtype=float), axis=0)
    pattern = pattern.translated(-centre)
    dim = pattern.dim
    n = dim if joints is None else joints
    if n > dim:  # n independent joints move in n dimensions: none lies in a pattern of fewer
        raise SynthesisError(f"joints: a chain of {n} independent one-DOF joints has {n} freedoms, more than the {dim} of {pattern.name}: "
                             f"no such chain lies in it; expected at most {dim} (a limb has {dim})")
    candidates, points, directions = candidate_joints(pattern, n if generic_points is None else generic_points, rng)
    outer_left = pattern.factors[0].generators()
    outer_right = pattern.factors[-1].generators()
    length = pattern.length
    tested = 0

    def inside(chain: tuple[ScrewJoint, ...]) -> bool:
        nonlocal tested
        tested += 1
        return generic_rank(outer_left + chain + outer_right, rng, samples, length, tol) == dim

    def independent(chain: tuple[ScrewJoint, ...]) -> bool:
        return generic_rank(chain, rng, samples, length, tol) == len(chain)

    alphabet = [c for c in candidates if inside((c.joint,))]
    rejected = [c for c in candidates if c not in alphabet]
    found: list[tuple[CandidateJoint, ...]] = []

    def extend(prefix: tuple[CandidateJoint, ...], used_generic: int) -> None:
        if len(prefix) == n:
            found.append(prefix)
            return
        for c in alphabet:
            g = int(c.point[1:]) if c.point.startswith("g") else 0
            if g > used_generic + 1:  # generic points are interchangeable: use them in order
                continue
            chain = tuple(x.joint for x in prefix) + (c.joint,)
            if not independent(chain) or not inside(chain):
                continue
            extend(prefix + (c,), max(used_generic, g))

    extend((), 0)
    if n == dim:
        found = [f for f in found if generic_rank(tuple(x.joint for x in f), rng, samples, length, tol) == dim]
    verified = 0
    for seq in found if verify_samples > 0 else ():
        limb = Limb(tuple(x.joint for x in seq))
        for q in sample_joint_values(limb.joints, rng, verify_samples, length):
            if not pattern.contains(limb.transform(q), seed=seed, tol=tol):
                raise AnalysisError(f"the rank route and the sample route disagree on {' '.join(x.label for x in seq)}: a rank decision was too close to call")
            verified += 1
    plane = tuple(f"s{i + 1}" for i in range(len(pattern.translation_directions)))
    moved_back = {label: cast(Vector, tuple(float(x) for x in np.asarray(p) + centre)) for label, p in points.items()}
    return SynthesisResult(given, n, tuple(alphabet), tuple(rejected), limb_types(found, pattern.name, plane), len(found), tested, verified,
                           time.perf_counter() - start, moved_back, directions)


def generates(pattern: MotionPattern, joints: Sequence[ScrewJoint], *, samples: int = 3, seed: int = 0, tol: Tolerance = DEFAULT_TOLERANCE) -> bool:
    """Whether the chain's set of finite motions equals the pattern (the rank route of docs/finite-screws.md).

    Examples
    --------
    >>> from mobility.synthesis.patterns import named_pattern
    >>> p = named_pattern("2T3R")
    >>> S = [ScrewJoint("R", e) for e in ((1, 0, 0), (0, 1, 0), (0, 0, 1))]          # three R through O
    >>> P1, P2 = ScrewJoint("P", (1, 0, 0)), ScrewJoint("P", (0, 1, 0))
    >>> generates(p, S + [P1, P2]), generates(p, [P1, P2] + S)                      # SP1P2 yes; P1P2S no
    (True, False)
    """
    pattern = require_instance(pattern, MotionPattern, "generates: pattern", "named_pattern")
    if len(pattern.factors) > 2:
        raise SynthesisError("the rank route needs a pattern of one or two factors (M = G1 △ G2)")
    samples = _count(samples, "samples", 1, MAX_SAMPLES, "generates")
    chain = tuple(joints) if not isinstance(joints, (str, bytes)) and isinstance(joints, Iterable) else None
    if chain is None or not all(isinstance(j, ScrewJoint) for j in chain):
        raise SynthesisError(caller="generates", argument="joints", expected="a sequence of ScrewJoint", got=shown_argument(joints))
    rng = np.random.default_rng(require_seed(seed, "generates: seed"))
    tol = require_tolerance(tol, "generates")
    dim = pattern.dim
    outer = generic_rank(pattern.factors[0].generators() + chain + pattern.factors[-1].generators(), rng, samples, pattern.length, tol)
    return outer == dim and generic_rank(chain, rng, samples, pattern.length, tol) == dim
