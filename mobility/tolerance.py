"""The one tolerance policy of the package.

Every rank decision in :mod:`mobility` goes through :func:`decide_rank`, on
matrices written in *normalised coordinates*: lengths divided by the
mechanism's characteristic length ``L`` and measured from its centre ``c``
(see :func:`characteristic_scale`).  Screws in those coordinates do not
change when the file is scaled (every length times ``k``, so ``L`` too) or
when the whole mechanism is moved rigidly (``c`` moves with it, and a
rotation of both blocks of a screw leaves singular values unchanged).  A
singular value counts when it exceeds ``rtol`` times the largest one (and
``rtol`` in absolute terms, since every column has unit norm, so the largest
singular value is at least one for a non-empty matrix).

Each decision also records its *margin*: the smallest kept and the largest
dropped singular value relative to the largest.  A small kept value means the
pose is close to a singularity where the rank would drop; a dropped value well
above round-off means the geometry is only nearly special (e.g. coordinates
typed with few digits).  Both are reported, never hidden.

Examples
--------
>>> import numpy as np
>>> d = decide_rank(np.array([2.0, 1.0, 1e-15]))
>>> d.rank, d.smallest_kept, d.largest_dropped
(2, 0.5, 5e-16)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

__all__ = [
    "Tolerance",
    "DEFAULT_TOLERANCE",
    "RankDecision",
    "decide_rank",
    "characteristic_scale",
]


@dataclass(frozen=True)
class Tolerance:
    """Thresholds of the rank decisions, all relative and dimensionless.

    Parameters
    ----------
    rank : float
        A singular value counts when ``s > rank * max(s_max, 1)``.
    near_singular : float
        A kept singular value below ``near_singular * s_max`` marks the pose as
        near-singular (a warning; the count is still given).
    inexact : float
        A dropped singular value above ``inexact * s_max`` marks the geometry
        as only approximately special (a warning).
    """

    rank: float = 1e-8
    near_singular: float = 1e-5
    inexact: float = 1e-11

    def __post_init__(self) -> None:
        if not (0.0 < self.inexact <= self.rank < self.near_singular < 1.0):
            raise ValueError("tolerances must satisfy 0 < inexact <= rank < near_singular < 1")


DEFAULT_TOLERANCE = Tolerance()


class RankDecision(NamedTuple):
    """The outcome of one rank decision.

    Attributes
    ----------
    rank : int
        Number of singular values kept.
    smallest_kept : float
        Smallest kept singular value over the largest one (1.0 when nothing is
        kept, i.e. no risk of losing rank).
    largest_dropped : float
        Largest dropped singular value over the largest one (0.0 when nothing
        is dropped).
    """

    rank: int
    smallest_kept: float = 1.0
    largest_dropped: float = 0.0


def decide_rank(singular_values: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> RankDecision:
    """Decide the numerical rank from singular values sorted in decreasing order.

    Parameters
    ----------
    singular_values : ndarray
        Singular values in decreasing order, as returned by :func:`numpy.linalg.svd`.
    tol : Tolerance
        The policy.

    Returns
    -------
    RankDecision
    """
    s = singular_values.tolist() if isinstance(singular_values, np.ndarray) else list(singular_values)
    if not s:
        return RankDecision(0)
    scale = s[0] if s[0] > 1.0 else 1.0
    threshold = tol.rank * scale
    rank = 0
    while rank < len(s) and s[rank] > threshold:  # decreasing order
        rank += 1
    kept = s[rank - 1] / scale if rank else 1.0
    dropped = s[rank] / scale if rank < len(s) else 0.0
    return RankDecision(rank, kept, dropped)


def characteristic_scale(points: np.ndarray, lengths: np.ndarray | None = None) -> tuple[np.ndarray, float]:
    """Centre and characteristic length of a mechanism.

    The centre is the centroid of the joint points; the length is the RMS
    distance of those points from it, or, when all points coincide, the
    largest other length given (helical pitches); 1.0 when there is none.
    Both follow the mechanism under scaling and rigid motion, which is what
    makes the rank decisions invariant.

    Parameters
    ----------
    points : ndarray, shape (n, 3)
        Joint points in the global frame.
    lengths : ndarray, optional
        Other lengths of the mechanism (absolute values are used).

    Returns
    -------
    centre : ndarray, shape (3,)
    length : float

    Examples
    --------
    >>> import numpy as np
    >>> c, L = characteristic_scale(np.array([[1.0, 0, 0], [-1.0, 0, 0]]))
    >>> c.tolist(), L
    ([0.0, 0.0, 0.0], 1.0)
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    n = len(pts)
    if n == 0:
        centre = np.zeros(3)
        radius = 0.0
    else:
        centre = pts.sum(axis=0) / n
        d = pts - centre
        radius = float(np.sqrt(np.einsum("ij,ij->", d, d) / n))
    other = 0.0 if lengths is None or len(lengths) == 0 else float(np.abs(lengths).max())
    if radius > 0.0 and radius >= 1e-9 * other:
        return centre, radius
    if other > 0.0:
        return centre, other
    return centre, 1.0
