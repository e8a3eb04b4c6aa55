"""The one tolerance policy of the package (README, "How it works").

Every rank decision goes through :func:`decide_rank` or :func:`decide_ranks`,
on matrices in *normalised coordinates* (:func:`characteristic_scale`), and
keeps its *margin*.  The fixed constants that decide no count (checks of a
description, solver stopping rules, ties of readable forms) stand here too,
each with the reason for its value: every number of the kind in one place.
"""

from __future__ import annotations

import contextlib
import math
import numbers
import sys
from dataclasses import dataclass
from typing import Any, NamedTuple, Sequence

import numpy as np

from ..errors import RequestError, shown_argument

__all__ = ["first_least", "Tolerance", "DEFAULT_TOLERANCE", "require_tolerance", "PRECISION_FACTOR", "PRECISION_CEILING", "file_tolerance",
           "PARALLEL_AXES", "ORTHONORMAL", "SIGN_TIE", "COMPONENT_TIE", "NORM_TIE", "COINCIDENT_POINTS", "MARGIN_DIP", "NEWTON_DAMPING",
           "SOLVER_STOP", "WRITE_DRIFT", "RankDecision", "decide_rank", "binary_scale", "characteristic_scale", "clean_numbers",
           "RankDecisions", "ROW_BY_ROW", "decide_few", "decide_ranks", "characteristic_scales", "SAME_GRID_VALUE", "SEAM_GAP", "SWEEP_REACH"]


@dataclass(frozen=True)
class Tolerance:
    """Every threshold of the package, all relative and dimensionless.

    Each is a real number (stored as a ``float``; a bool or a string is refused).

    Parameters
    ----------
    rank : float
        A singular value counts when ``s > rank * max(s_max, 1)`` (absolute below 1: the columns have unit norm).
    near_singular : float
        A kept singular value below ``near_singular * s_max`` marks the pose as
        near-singular (a warning; the count is still given).
    inexact : float
        A dropped singular value above ``inexact * s_max`` marks the geometry
        as only approximately special (a warning).
    closure : float
        A pose is assembled when every loop closes to this residual
        (rotations in radians, lengths over the characteristic length).
    round_off : float
        Numbers below ``round_off`` times their scale are shown as 0
        (:func:`clean_numbers`).

    Examples
    --------
    >>> Tolerance(rank=np.float32(1e-9)).rank == float(np.float32(1e-9))
    True
    """

    rank: float = 1e-8
    near_singular: float = 1e-5
    inexact: float = 1e-11
    closure: float = 1e-12
    round_off: float = 1e-12

    def __post_init__(self) -> None:
        for name in ("rank", "near_singular", "inexact", "closure", "round_off"):
            value = getattr(self, name)
            number = math.nan
            if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)):
                with contextlib.suppress(OverflowError):  # an integer beyond the floats stays NaN
                    number = float(value)
            if not math.isfinite(number):
                raise RequestError(f"{name} must be a finite number, got {shown_argument(value)}", caller="Tolerance")
            object.__setattr__(self, name, number)
        if not (0.0 < self.inexact <= self.rank < self.near_singular < 1.0):
            raise RequestError("tolerances must satisfy 0 < inexact <= rank < near_singular < 1")
        if not (0.0 < self.closure < 1.0 and 0.0 < self.round_off < 1.0):
            raise RequestError("the closure and round-off tolerances must lie between 0 and 1")


DEFAULT_TOLERANCE = Tolerance()


def require_tolerance(value: object, caller: str) -> Tolerance:
    """``value`` when it is a :class:`Tolerance`, else a :class:`~mobility.errors.RequestError` naming ``caller``.

    Examples
    --------
    >>> require_tolerance(DEFAULT_TOLERANCE, "analyze").rank
    1e-08
    >>> require_tolerance(1e-8, "analyze")
    Traceback (most recent call last):
    mobility.errors.RequestError: analyze: tol must be a Tolerance (e.g. Tolerance(rank=1e-9)), got float
    """
    if not isinstance(value, Tolerance):
        raise RequestError(f"tol must be a Tolerance (e.g. Tolerance(rank=1e-9)), got {type(value).__name__}", caller=caller)
    return value


PRECISION_FACTOR = 100.0
"""How many times a file's own precision the rank threshold is raised to (:func:`file_tolerance`).

A file rounded to precision ``p`` (relative to its size) misses along a loop
of up to some thirty frames by up to about ``100 p``, and so does a direction
the designer's mechanism holds exactly (parallel axes, axes through one
point); at ``100 p`` those are dropped as drawn.  On the six-digit files of the
tests (``tests/data/robots/toddlerbot``, ``tests/data/cad``) the rounding's
directions have singular values of 0.001 to 0.6 ``p``, the mechanism's own 21
to 300 times ``100 p``."""

PRECISION_CEILING = 1e-3
"""The highest rank threshold a file's precision raises the default to.

Past it a pose within a tenth of a percent of a singularity would be called
singular; a file that rough (four digits or fewer) cannot tell a mechanism
from its neighbours anyway.  The report says what precision was found, and
``--tol`` decides otherwise."""


def file_tolerance(precision: float | None) -> Tolerance:
    """The tolerance that decides the ranks of a mechanism when none is given: never finer than its file.

    The default, unless :data:`PRECISION_FACTOR` times ``precision`` (the
    file's, relative to its size: :mod:`mobility.io.precision`) is above its
    rank threshold: then the threshold is raised to it (two significant
    digits, at most :data:`PRECISION_CEILING`) and the near-singular warning
    to ten times that.  A tolerance given explicitly is used as it is.

    Examples
    --------
    >>> file_tolerance(None) is DEFAULT_TOLERANCE, file_tolerance(1e-16) is DEFAULT_TOLERANCE
    (True, True)
    >>> t = file_tolerance(5e-6)
    >>> t.rank, t.near_singular
    (0.0005, 0.005)
    >>> file_tolerance(0.5).rank, file_tolerance(5e-7).rank
    (0.001, 5e-05)
    """
    if precision is None or not PRECISION_FACTOR * precision > DEFAULT_TOLERANCE.rank:
        return DEFAULT_TOLERANCE
    rank = min(float(f"{PRECISION_FACTOR * precision:.2g}"), PRECISION_CEILING)  # two digits: an estimate, shown as one
    return Tolerance(rank=rank, near_singular=max(DEFAULT_TOLERANCE.near_singular, 10.0 * rank))


# Fixed constants (checks of a description, solver safeguards, ties of readable forms): none decides a count.

PARALLEL_AXES = 1e-9
"""The two axes of a U joint are refused as parallel when the sine of their angle is below this (a check of the description, not a rank decision)."""

ORTHONORMAL = 1e-9
"""A frame's rotation must be orthonormal to this (entries of ``R R^T - I``, ``numpy.isclose``'s 1e-5 relative on the diagonal): ten digits pass."""

SIGN_TIE = 1e-9
"""Components of a unit column within this of its largest are a tie for :func:`~mobility.core.screws.span_and_reciprocal`'s
sign rule, broken by the lowest index: a readability choice far above round-off, not a rank decision."""

COMPONENT_TIE = 1e-9
"""Components of a unit vector within this of the largest are a tie, broken by the lowest index: a readability choice far above round-off."""

COINCIDENT_POINTS = 1e-12
"""Joint points whose RMS distance from their centroid is below this fraction of the centroid's distance from the origin coincide (round-off of averaging; :func:`characteristic_scale`)."""

MARGIN_DIP = 0.5
"""A sweep's grid point whose rank margin is at most this fraction of a neighbour's (and no larger than either) is a *margin dip* (:attr:`mobility.sweeps.SweepResult.dips`).

A margin falling linearly to 0 between grid points is at most 1/3 of its
farther neighbour at the nearer point; 0.5 leaves room for curvature."""

NORM_TIE = 1e-12
"""Projections of coordinate axes whose norms are within this of the largest are a tie, broken by the lowest index (:func:`~mobility.core.canonical.readable_basis`)."""

NEWTON_DAMPING = 1e-14
"""Damping of Newton's steps (:func:`mobility.core.kinematics.newton`), relative to the Jacobian's mean squared row.

Far below every kept singular value squared: it only keeps a singular pose's
normal equations solvable; whether loops closed is :attr:`Tolerance.closure`'s."""

VALUE_TIE = 1e-9
"""Values within this fraction of the smallest are a tie for :func:`first_least` (far above the 1e-12 round-off seen at mirror poses)."""

UNIT_ROUND_OFF = 4 * sys.float_info.epsilon
"""A direction whose length is within this of 1 is kept as written, not divided again (which would change its last bit on each write and read)."""

WRITE_DRIFT = 1e-9
"""Largest change of a joint's geometry a write and read-back of its file may make (relative to ``L`` for points and pitches; :func:`mobility.io.writer.require_written_faithfully`)."""

SAME_GRID_VALUE = 1e-9
"""Two values of a sweep's axis that differ by less than this fraction of its step are one value.

Evenly spaced values and angles reduced by whole turns carry round-off
(``-180`` and ``180`` degrees are one state of an R joint;
:mod:`mobility.sweeps.walks`).
"""

SEAM_GAP = 1e-3
"""Two solves of one pose farther apart than this are two poses (a seam of a sweep: :mod:`mobility.sweeps.seams`).

The largest difference of the joints' unit twists, normalised coordinates.
Solves of one assembly agree to round-off (1e-6 at a change point); two
assemblies differ by a tenth and up in the cases found.
"""

SWEEP_REACH = 1000.0
"""Farthest a sweep drives a coordinate from the file's pose: characteristic lengths, or radians for an angle that does not wrap (an H joint's).

Beyond it double precision cannot close the loops to :attr:`Tolerance.closure`
(``D`` lengths put round-off ``D * 1e-16`` in every residual; the 3-PRS
reaches 1,900 lengths, fails at 4,700).  An R or C angle wraps: no
limit (:attr:`mobility.sweeps.SweepAxis.internal`).
"""

NEAR_LARGEST_FLOAT = sys.float_info.max * 2.0**-20
"""A mechanism reaching this far (centre's largest coordinate plus ``L``) has its result's lazy parts computed by :func:`mobility.analyze` itself.

So an axis point beyond the largest float is an error of the analysis, not
of a later read; nearer, ``2**-20`` leaves room for axes a million ``L`` away.
"""

SOLVER_STOP = 1e-15
"""``xtol``, ``ftol`` and ``gtol`` of every least-squares search: iterate until round-off; the policy then judges the fit."""


class RankDecision(NamedTuple):
    """The outcome of one rank decision: the ``rank`` kept, and relative to the largest value the ``smallest_kept`` (1.0 when none) and ``largest_dropped`` (0.0 when none).

    Examples
    --------
    >>> RankDecision(3)
    RankDecision(rank=3, smallest_kept=1.0, largest_dropped=0.0)
    """

    rank: int
    smallest_kept: float = 1.0
    largest_dropped: float = 0.0


def decide_rank(singular_values: np.ndarray | Sequence[float], tol: Tolerance = DEFAULT_TOLERANCE) -> RankDecision:
    """Decide the numerical rank from singular values sorted in decreasing order.

    Examples
    --------
    >>> d = decide_rank(np.array([2.0, 1.0, 1e-15]))
    >>> d.rank, d.smallest_kept, d.largest_dropped
    (2, 0.5, 5e-16)
    """
    return RankDecision(*_decide(singular_values.tolist() if isinstance(singular_values, np.ndarray) else singular_values, tol.rank))


def _decide(s: Sequence[float], rtol: float) -> tuple[int, float, float]:
    """Rank, smallest kept and largest dropped (relative) of singular values in decreasing order: the policy itself."""
    if not s:
        return 0, 1.0, 0.0
    scale = s[0] if s[0] > 1.0 else 1.0
    threshold = rtol * scale
    rank, length = 0, len(s)
    while rank < length and s[rank] > threshold:  # decreasing order
        rank += 1
    return rank, s[rank - 1] / scale if rank else 1.0, s[rank] / scale if rank < length else 0.0


def binary_scale(*values: Any) -> float:
    """A power of two, ``2**-k``, that brings the largest magnitude among ``values`` into ``[0.5, 1)``.

    Scaling by a power of two is exact: the one way of normalising before
    squaring, the same bits as the plain computation where that one does not
    overflow.  1.0 when every value is zero; ``k`` stays within
    ``±BINARY_EXPONENT`` so the scale is a normal float.

    Examples
    --------
    >>> binary_scale([3.0, -5.0]), binary_scale(0.0), binary_scale([1e300]) * 1e300 < 1.0
    (0.125, 1.0, True)
    """
    big = max((float(np.abs(np.asarray(v, dtype=float)).max(initial=0.0)) for v in values), default=0.0)
    if big == 0.0 or not math.isfinite(big):
        return 1.0
    exponent = min(max(math.frexp(big)[1], -BINARY_EXPONENT), BINARY_EXPONENT)
    return math.ldexp(1.0, -exponent)


BINARY_EXPONENT = 1021
"""The largest ``|k|`` of :func:`binary_scale`: ``2**k`` and ``2**-k`` are normal floats."""


def characteristic_scale(points: np.ndarray, lengths: np.ndarray | None = None, pitches: np.ndarray | None = None) -> tuple[np.ndarray, float]:
    """Centre and characteristic length of a mechanism.

    The centre is the centroid of the joint ``points`` (global frame); the
    length their RMS distance ``d`` from it, or when they coincide (to
    :data:`COINCIDENT_POINTS`) the largest of ``lengths`` and ``pitches``
    (absolute values), else 1.0.  A pitch ``h`` above ``d`` raises it to
    ``L = sqrt(d h)``: the screw's turn and the points' offsets are then both
    ``sqrt(d / h)`` of ``L``, resolved up to ``h / d = 1 / rank**2`` (1e16),
    where ``L = d`` would lose the rotation at 1e8.  Both follow the mechanism
    under scaling and rigid motion (so the ranks are invariant), computed on
    :func:`binary_scale`'d points to full precision at any scale.

    Examples
    --------
    >>> c, L = characteristic_scale(np.array([[1.0, 0, 0], [-1.0, 0, 0]]))
    >>> c.tolist(), L
    ([0.0, 0.0, 0.0], 1.0)
    >>> characteristic_scale(np.array([[1e200, 0, 0], [-1e200, 0, 0]]))[1], characteristic_scale(np.array([[1e-250, 0, 0], [0, 0, 0]]))[1]
    (1e+200, 5e-251)
    >>> round(characteristic_scale(np.array([[1.0, 0, 0], [-1.0, 0, 0]]), pitches=np.array([100.0]))[1], 12)
    10.0
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    n = len(pts)
    pitch = _largest(pitches)
    other = max(_largest(lengths), pitch)
    scale = binary_scale(pts, other)
    if n == 0:
        centre, radius = np.zeros(3), 0.0
    else:
        scaled = pts * scale
        centre = scaled.sum(axis=0) / n
        d = scaled - centre
        radius = float(np.sqrt(np.einsum("ij,ij->", d, d) / n))
        centre /= scale
    if radius / scale > COINCIDENT_POINTS * float(np.abs(centre).max(initial=0.0)):
        return centre, float(_balanced(np.array(radius), pitch * scale)) / scale
    return centre, other if other > 0.0 else 1.0


def _largest(lengths: np.ndarray | None) -> float:
    """The largest magnitude of ``lengths``; 0.0 when there is none."""
    return 0.0 if lengths is None or len(lengths) == 0 else float(np.abs(lengths).max())


def _balanced(radius: np.ndarray, pitch: Any) -> np.ndarray:
    """``radius`` raised to ``sqrt(radius * pitch)`` where ``pitch`` is larger: on :func:`binary_scale`'d lengths (the same bits at any power-of-two scale), without overflow."""
    return np.where(pitch > radius, np.sqrt(radius) * np.sqrt(pitch), radius)


def clean_numbers(value: Any, scale: float = 1.0, tol: Tolerance = DEFAULT_TOLERANCE) -> Any:
    """A JSON-ready copy of ``value`` with round-off shown as 0: the one rule for every number shown.

    Arrays, tuples and lists become lists, numpy scalars Python numbers; a
    float below ``tol.round_off * scale`` (``scale``: a length for points, 1
    for directions) becomes ``0.0``, as does ``-0.0``; anything else is kept.

    Examples
    --------
    >>> clean_numbers(np.array([1.0, -1e-17, 2.5]))
    [1.0, 0.0, 2.5]
    >>> clean_numbers((3e-10, [np.float64(-0.0)]), scale=1000.0)
    [0.0, [0.0]]
    """
    if isinstance(value, np.ndarray):
        if value.dtype.kind != "f":
            return value.tolist()
        return (np.where(np.abs(value) < tol.round_off * scale, 0.0, value) + 0.0).tolist()
    if isinstance(value, (list, tuple)):
        return [clean_numbers(v, scale, tol) for v in value]
    if isinstance(value, (float, np.floating)):
        x = float(value)
        return 0.0 if abs(x) < tol.round_off * scale else x
    if isinstance(value, np.generic):
        return value.item()
    return value


def first_least(values: Any) -> int:
    """Index of the first of the smallest values, values within :data:`VALUE_TIE` of the smallest counting as equal.

    Mirror poses tie by round-off that depends on the BLAS kernel: the pose
    named is the first given, never the one the last bits favour.  ``values``
    is not empty; NaN counts as larger than any number.

    Examples
    --------
    >>> first_least([0.3, 0.1 + 1e-12, 0.1, 0.2])
    1
    >>> first_least([2.0, float("nan"), 1.0])
    2
    """
    a = np.asarray(values, dtype=float)
    a = np.where(np.isnan(a), np.inf, a)
    least = float(a.min())
    if not np.isfinite(least):
        return int(np.argmin(a))
    return int(np.flatnonzero(a <= least + VALUE_TIE * abs(least))[0])


# the same policy over many matrices at once (sweeps)


class RankDecisions(NamedTuple):
    """Many rank decisions at once: :class:`RankDecision` with arrays of shape (N,) for fields (see :func:`decide_ranks`)."""

    rank: np.ndarray
    smallest_kept: np.ndarray
    largest_dropped: np.ndarray


ROW_BY_ROW = 8
"""Up to this many rows, :func:`decide_ranks` loops over them in Python (:func:`decide_few`): less overhead than array operations."""


def decide_few(singular_values: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE, counts: int | Sequence[int] | np.ndarray | None = None) -> tuple[tuple[int, ...], tuple[float, ...], tuple[float, ...]]:
    """:func:`decide_ranks` of a few rows, as tuples of Python numbers: ranks, smallest kept, largest dropped.

    For a stack of a few matrices (one pose) building arrays costs more than
    deciding, so callers that only read the numbers take them as they are.

    Examples
    --------
    >>> decide_few(np.array([[2.0, 1.0, 1e-15], [3.0, 0.0, 0.0]]), counts=[3, 1])
    ((2, 1), (0.5, 1.0), (5e-16, 0.0))
    """
    n, k = singular_values.shape
    lengths = [k] * n if counts is None else [counts] * n if isinstance(counts, (int, np.integer)) else counts.tolist() if isinstance(counts, np.ndarray) else counts
    rtol = tol.rank
    decided = [_decide(row[:length], rtol) for row, length in zip(singular_values.tolist(), lengths)]
    return tuple(zip(*decided)) if decided else ((), (), ())  # type: ignore[return-value]  # three tuples of n


def decide_ranks(singular_values: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE, counts: int | Sequence[int] | np.ndarray | None = None) -> RankDecisions:
    """:func:`decide_rank` of every row of ``singular_values``, vectorised, with the same semantics.

    Row ``i`` is ``decide_rank(singular_values[i, :counts[i]], tol)``: each row
    in decreasing order, ``counts`` (an int or one per row, default all) the
    leading values that are its matrix's own (not padding columns).

    Examples
    --------
    >>> d = decide_ranks(np.array([[2.0, 1.0, 1e-15], [3.0, 0.0, 0.0]]), counts=np.array([3, 1]))
    >>> d.rank.tolist(), d.smallest_kept.tolist(), d.largest_dropped.tolist()
    ([2, 1], [0.5, 1.0], [5e-16, 0.0])
    >>> tuple(decide_rank(np.array([2.0, 1.0, 1e-15]))) == (2, 0.5, 5e-16)
    True
    """
    s = np.asarray(singular_values, dtype=float)
    n, k = s.shape
    if n <= ROW_BY_ROW:
        return RankDecisions(*(np.array(x, dtype=t) for x, t in zip(decide_few(s, tol, counts), (int, float, float))))
    present = np.arange(k)[None, :] < (np.full(n, k) if counts is None else np.broadcast_to(np.minimum(counts, k), (n,)))[:, None]
    length = present.sum(axis=1)
    if k == 0:
        return RankDecisions(np.zeros(n, dtype=int), np.ones(n), np.zeros(n))
    scale = np.where(s[:, 0] > 1.0, s[:, 0], 1.0)
    above = (s > (tol.rank * scale)[:, None]) & present
    rank = np.cumprod(above, axis=1).sum(axis=1)  # leading values above the threshold, as the loop counts them
    rows = np.arange(n)
    kept = np.where(rank > 0, s[rows, np.maximum(rank - 1, 0)] / scale, 1.0)
    dropped = np.where(rank < length, s[rows, np.minimum(rank, k - 1)] / scale, 0.0)
    return RankDecisions(rank, kept, dropped)


def characteristic_scales(points: np.ndarray, lengths: np.ndarray | None = None, pitches: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`characteristic_scale` of many poses of one mechanism at once.

    ``points`` has shape (N, n, 3); ``lengths`` and ``pitches`` are the same
    for every pose.  Returns centres (N, 3) and lengths (N,).

    Examples
    --------
    >>> c, L = characteristic_scales(np.array([[[1.0, 0, 0], [-1.0, 0, 0]], [[2.0, 2, 0], [2.0, 2, 0]]]))
    >>> c.tolist(), L.tolist()
    ([[0.0, 0.0, 0.0], [2.0, 2.0, 0.0]], [1.0, 1.0])
    """
    pts = np.asarray(points, dtype=float)
    count, n = pts.shape[0], pts.shape[1]
    pitch = _largest(pitches)
    other = max(_largest(lengths), pitch)
    if n == 0:
        centres = np.zeros((count, 3))
        radius = balanced = np.zeros(count)
    else:
        # each pose scaled by its own power of two, as characteristic_scale does
        big = np.maximum(np.abs(pts).reshape(count, -1).max(axis=1), other)
        exponent = np.clip(np.frexp(np.where(np.isfinite(big) & (big > 0.0), big, 1.0))[1], -BINARY_EXPONENT, BINARY_EXPONENT)
        scale = np.where(big > 0.0, np.ldexp(1.0, -exponent), 1.0)
        scaled = pts * scale[:, None, None]
        centres = scaled.sum(axis=1) / n
        d = scaled - centres[:, None, :]
        with np.errstate(over="ignore"):  # infinite only when the radius exceeds the largest float
            scaled_radius = np.sqrt(np.einsum("kij,kij->k", d, d) / n)
            radius = scaled_radius / scale
            balanced = _balanced(scaled_radius, pitch * scale) / scale
        centres /= scale[:, None]
    fallback = other if other > 0.0 else 1.0
    spread = radius > COINCIDENT_POINTS * (np.abs(centres).max(axis=1) if n else 0.0)
    return centres, np.where(spread, balanced, fallback)
