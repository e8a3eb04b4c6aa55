"""Motion/force and constraint transmission indices on stacks of poses.

Every index is a **power coefficient** of a unit wrench ``w = [f; m]`` and a
twist ``t = [omega; v]`` at the point ``P`` where the wrench acts,
``tau_P(w, t) = |w o t| / (|f| |v_P| + |m_P| |omega|)``: ``ITI`` of each
input's actuation wrench on its input twist, ``OTI`` on the end effector's
twist with every other input locked, ``LTI = min(ITI, OTI)``, ``CTI`` of each
limb's constraint wrench on the twist gained without it.  Definitions, the
choice of normalisation, redundancy (the best non-redundant choice, at most
:data:`MAX_CHOICES`) and the checks against textbook closed forms:
docs/sweeps.md, "Transmission indices".

Sources
-------
J. Wang, C. Wu, X.-J. Liu, "Performance evaluation of parallel manipulators:
motion/force transmissibility and its index", Mech. Mach. Theory 45 (2010)
1462-1476; X.-J. Liu, C. Wu, J. Wang, "A new approach for singularity
analysis and closeness measurement to singularities of parallel manipulators",
ASME J. Mechanisms Robotics 4 (2012) 041001; C. Chen, J. Angeles, "Generalized
transmission index and transmission quality for spatial linkages", Mech. Mach.
Theory 42 (2007) 1225-1237; Y. Takeda, H. Funabashi, "Motion transmissibility
of in-parallel actuated manipulators", JSME Int. J. C 38 (1995) 749-755;
J. Brinker, B. Corves, Y. Takeda, "Kinematic performance evaluation of
high-speed Delta parallel robots based on motion/force transmission indices",
Mech. Mach. Theory 125 (2018) 111-125.

Examples
--------
A force along x through the origin, the point moving along x then along y:

>>> import numpy as np
>>> force = np.array([1.0, 0, 0, 0, 0, 0])
>>> float(power_coefficient(force, np.array([0, 0, 0, 1.0, 0, 0]), np.zeros(3)))
1.0
>>> float(power_coefficient(force, np.array([0, 0, 0, 0, 1.0, 0]), np.zeros(3)))
0.0
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations
from math import comb
from typing import Sequence

import numpy as np

from ..core.screws import SWAP_ROWS
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, decide_ranks
from ..errors import AnalysisError

__all__ = ["GOOD_TRANSMISSION", "BatchTransmission", "TransmissionCheck", "power_coefficient", "transmission_indices"]

GOOD_TRANSMISSION = 0.7
"""The published threshold of good transmission: ``LTI >= 0.7`` (Wang et al., 2010, after Tao's transmission angles of 40 to 140 deg).

``cos 45.57 deg = 0.7``: a pressure angle of at most 45.57 deg, a transmission angle between 44.43 and 135.57 deg."""

_TINY = 1e-12
"""Below this (relative to the screws' unit size) a denominator is no power at all: the index is 0."""


def power_coefficient(wrench: np.ndarray, twist: np.ndarray, point: np.ndarray) -> np.ndarray:
    """``|w o t| / (|f| |v_P| + |m_P| |omega|)`` of wrenches ``[f; m]`` and twists ``[omega; v]`` (last axis 6) at points ``P`` (last axis 3).

    Moments and velocities are about the origin of the coordinates, as
    :mod:`mobility.core.screws` writes them.  Broadcasts over the leading
    axes; 0 where the denominator vanishes (no power can pass).

    Examples
    --------
    A rotation about z through the origin moves the point (1, 0, 0) along y;
    a force along the diagonal of x and y through that point has a pressure
    angle of 45 degrees:

    >>> import numpy as np
    >>> rz = np.array([0, 0, 1.0, 0, 0, 0])
    >>> p = np.array([1.0, 0, 0])
    >>> f = np.concatenate([[1, 1, 0] / np.sqrt(2), np.cross(p, [1, 1, 0] / np.sqrt(2))])
    >>> round(float(power_coefficient(f, rz, p)), 6)
    0.707107
    """
    w = np.asarray(wrench, dtype=float)
    t = np.asarray(twist, dtype=float)
    p = np.asarray(point, dtype=float)
    f, m = w[..., :3], w[..., 3:]
    omega, v = t[..., :3], t[..., 3:]
    v_p = v + np.cross(omega, p)
    m_p = m - np.cross(p, f)
    power = np.abs(np.einsum("...i,...i->...", f, v_p) + np.einsum("...i,...i->...", m_p, omega))
    most = np.linalg.norm(f, axis=-1) * np.linalg.norm(v_p, axis=-1) + np.linalg.norm(m_p, axis=-1) * np.linalg.norm(omega, axis=-1)
    size = (np.linalg.norm(w, axis=-1) + np.linalg.norm(m_p, axis=-1)) * (np.linalg.norm(t, axis=-1) + np.linalg.norm(v_p, axis=-1))
    ok = most > _TINY * size
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(ok, np.minimum(power / np.where(ok, most, 1.0), 1.0), 0.0)


@dataclass(frozen=True, eq=False)
class BatchTransmission:
    """The transmission indices of ``N`` poses (see the module docstring).

    Attributes
    ----------
    iti, oti : ndarray, shape (N, n)
        Input and output transmission index of each input (NaN for an input
        left out of the best non-redundant choice, or where the end effector
        has no freedom; at an input singularity with more inputs than
        freedoms every input's ITI is given, the singular one's 0).
    lti : ndarray, shape (N,)
        Local transmission index ``min(ITI, OTI)``: the distance to an
        actuation singularity (0 there).
    cti_limbs : ndarray, shape (N, L)
        Constraint transmission index of each limb (NaN: the limb imposes no
        constraint, is redundant, or is left out of the best choice).
    cti : ndarray, shape (N,)
        ``min`` over the limbs: the distance to a constraint singularity (0 there).
    """

    iti: np.ndarray
    oti: np.ndarray
    lti: np.ndarray
    cti_limbs: np.ndarray
    cti: np.ndarray

    @property
    def iti_min(self) -> np.ndarray:
        """The smallest input transmission index of each pose."""
        return _nanmin(self.iti)

    @property
    def oti_min(self) -> np.ndarray:
        """The smallest output transmission index of each pose."""
        return _nanmin(self.oti)


@dataclass(frozen=True)
class TransmissionCheck:
    """The transmission indices of one pose (:func:`mobility.check_transmission`).

    Attributes
    ----------
    actuated : tuple of str
        The inputs (one per freedom: ``NAME`` or ``NAME.k``).
    iti, oti : tuple of float
        Input and output transmission index of each input.
    lti : float
        Local transmission index (distance to an actuation singularity).
    limbs : tuple of str
        Each limb, named by its joints.
    cti_limbs : tuple of float
        Constraint transmission index of each limb (NaN: no index, see
        :class:`BatchTransmission`).
    cti : float
        Distance to a constraint singularity (NaN: no limb has an index).
    threshold : float
        The good-transmission threshold the pose was judged against.
    """

    actuated: tuple[str, ...]
    iti: tuple[float, ...]
    oti: tuple[float, ...]
    lti: float
    limbs: tuple[str, ...]
    cti_limbs: tuple[float, ...]
    cti: float
    threshold: float = GOOD_TRANSMISSION

    @property
    def good(self) -> bool:
        """Whether the pose transmits well: ``LTI >= threshold``."""
        return bool(self.lti >= self.threshold)

    def __str__(self) -> str:
        """A few lines for a terminal."""
        inputs = ", ".join(f"{n} {i:.3f}/{o:.3f}" for n, i, o in zip(self.actuated, self.iti, self.oti))
        limbs = ", ".join(f"{n} {c:.3f}" for n, c in zip(self.limbs, self.cti_limbs))
        verdict = "good" if self.good else "poor"
        return (f"LTI {self.lti:.3f} ({verdict} transmission, threshold {self.threshold:g})\n"
                f"ITI/OTI per input: {inputs}\nCTI {self.cti:.3f}" + (f" (per limb: {limbs})" if limbs else ""))


def _nanmin(a: np.ndarray) -> np.ndarray:
    """Row minimum ignoring NaN (NaN where a row has no number)."""
    if a.shape[1] == 0:
        return np.full(a.shape[0], np.nan)
    filled = np.where(np.isnan(a), np.inf, a)
    low = filled.min(axis=1)
    return np.where(np.isinf(low), np.nan, low)


def _svd(m: np.ndarray, full: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    try:
        return np.linalg.svd(m, full_matrices=full)
    except np.linalg.LinAlgError:
        raise AnalysisError(f"the singular value decomposition of a stack of {m.shape[1]}x{m.shape[2]} matrices did not converge") from None


def _output_twists(g: np.ndarray, basis: np.ndarray) -> np.ndarray:
    """Column ``i``: the twist of ``basis`` on which every row of ``g`` but the ``i``-th vanishes, ``(M, 6, d)``.

    The columns of ``basis @ adj(g)`` (``g`` square, ``(M, d, d)``), from one
    SVD: ``adj(g)`` is ``V diag(prod_{j != i} s_j) U^T`` up to sign, defined
    (and rank one, on the null vector) also where ``g`` is singular.
    """
    u, s, vt = _svd(g)
    d = s.shape[1]
    top = np.where(s[:, :1] > 0, s[:, :1], 1.0)
    r = s / top
    p = np.stack([np.prod(np.delete(r, i, axis=1), axis=1) for i in range(d)], axis=1)
    adj = np.swapaxes(vt, 1, 2) @ (p[:, :, None] * np.swapaxes(u, 1, 2))
    return basis @ adj


def _at_point(screws: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Screws ``(N, 6, k)`` written about points ``(N, 3)``: a wrench's moment there (``m - P x f``), or a twist's velocity (``v + omega x P``)."""
    out = screws.copy()
    out[:, 3:] -= np.cross(points[:, :, None], screws[:, :3], axis=1)
    return out


def _orthonormal(screws: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """An orthonormal basis of the first ``counts`` columns of each stack member (the other columns zero)."""
    if screws.shape[2] == 1:
        size = np.linalg.norm(screws[:, :, 0], axis=1)
        return screws / np.where(size > 0, size, 1.0)[:, None, None] * (counts > 0)[:, None, None]
    q, _ = np.linalg.qr(screws)
    return q * (np.arange(q.shape[2]) < counts[:, None])[:, None, :]


def _pair_index(wrenches: np.ndarray, own: np.ndarray, twists: np.ndarray, released: np.ndarray, point: np.ndarray) -> np.ndarray:
    """How well a limb's constraint system resists the twists released without it: the least power coefficient over their principal pairs.

    Both systems are written about the limb's point ``point`` and paired by
    the singular vectors of their power matrix (the pairs do not depend on the
    bases; one wrench and one twist: the pair itself).
    """
    if twists.shape[2] == 0 or wrenches.shape[2] == 0:  # nothing released (or no constraint) at any pose
        return np.zeros(wrenches.shape[0])
    qc = _orthonormal(_at_point(wrenches, point), own)
    qr = _orthonormal(_at_point(twists, point), released)
    zero = np.zeros(3)
    if qc.shape[2] == 1 and qr.shape[2] == 1:
        return power_coefficient(qc[:, :, 0], qr[:, :, 0], zero)
    u, _, vt = _svd(np.swapaxes(qc, 1, 2) @ qr[:, SWAP_ROWS, :])
    pairs = min(qc.shape[2], qr.shape[2])
    c = qc @ u[:, :, :pairs]
    t = qr @ np.swapaxes(vt, 1, 2)[:, :, :pairs]
    values = power_coefficient(np.swapaxes(c, 1, 2), np.swapaxes(t, 1, 2), zero)  # (N, pairs)
    valid = np.arange(pairs)[None, :] < np.minimum(own, released)[:, None]
    return np.where(valid, values, np.inf).min(axis=1)


def _limb_index(wrenches: Sequence[np.ndarray], counts: Sequence[np.ndarray], points: np.ndarray, actuation: np.ndarray,
                present: np.ndarray, degenerate: np.ndarray, tol: Tolerance) -> np.ndarray:
    """The constraint transmission index of every limb at every pose, ``(N, L)``.

    Without redundancy (six wrenches in all, every one present: a 3-PRS) the
    released twists are columns of the adjugate of the square power matrix,
    one SVD for every limb; otherwise one SVD per limb, with the analysis's
    rank decision.
    """
    count = actuation.shape[0]
    limbs = len(wrenches)
    out = np.full((count, limbs), np.nan)
    if limbs == 0:
        return out
    a_cols = np.swapaxes(actuation, 1, 2)  # (N, 6, n)
    n_present = present.sum(axis=1)
    widths = [w.shape[2] for w in wrenches]
    square = a_cols.shape[2] + sum(widths) == 6 and bool(present.all()) and all(bool(np.all(c == k)) for c, k in zip(counts, widths))
    if square:
        power = np.swapaxes(np.concatenate([a_cols, *wrenches], axis=2)[:, SWAP_ROWS, :], 1, 2)  # row l: the power of wrench l on a twist
        adj = _output_twists(power, np.broadcast_to(np.eye(6), (count, 6, 6)))
        edges = np.cumsum([a_cols.shape[2], *widths])
    for j in range(limbs):
        own = counts[j]
        if not np.any(own > 0):
            continue
        if square:
            released_twists = adj[:, :, edges[j] : edges[j + 1]]
            released = own.copy()
        else:
            others = np.concatenate([a_cols] + [w for k, w in enumerate(wrenches) if k != j], axis=2)
            other_counts = n_present + sum((c for k, c in enumerate(counts) if k != j), np.zeros(count, dtype=int))
            if others.shape[2]:
                u, s, _ = _svd(others, full=True)
                rank = decide_ranks(s, tol, np.minimum(other_counts, s.shape[1])).rank
            else:
                u, rank = np.broadcast_to(np.eye(6), (count, 6, 6)), np.zeros(count, dtype=int)
            released = 6 - rank
            low = int(rank.min())
            released_twists = u[:, SWAP_ROWS, low:] * (np.arange(low, 6)[None, :] >= rank[:, None])[:, None, :]  # reciprocal to every other wrench
            order = np.argsort(np.arange(low, 6)[None, :] < rank[:, None], axis=1, kind="stable")  # each pose's columns first
            released_twists = np.take_along_axis(released_twists, order[:, None, :], axis=2)
        value = _pair_index(wrenches[j], own, released_twists, released, points[:, j])
        value = np.where(released > own, 0.0, value)
        value = np.where(degenerate & (released >= 1), 0.0, value)
        out[:, j] = np.where((own > 0) & (released >= 1), value, np.nan)
    return out


MAX_CHOICES = 64
"""The most choices (of inputs and of limbs) :func:`transmission_indices` tries in a redundant wrench system;
with more, the indices that need a choice are not computed (NaN): their count grows combinatorially."""

MAX_LIMBS_CHOSEN = 12
"""The most limbs whose subsets :func:`transmission_indices` searches for a square choice (``2**12`` subsets)."""


def _best_choice_index(wrenches: Sequence[np.ndarray], counts: Sequence[np.ndarray], points: np.ndarray, actuation: np.ndarray,
                       present: np.ndarray, degenerate: np.ndarray, dim: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The constraint indices ``(N, L)`` of the best non-redundant choice of inputs and limbs, and the poses where one was made.

    Every choice of ``DOF`` inputs and of whole limbs with ``6 - DOF``
    constraint wrenches in all (a square system) is tried; the one whose
    least index is largest wins (NaN for a limb left out).
    """
    count, n = actuation.shape[0], actuation.shape[1]
    limbs = len(wrenches)
    out = np.full((count, limbs), np.nan)
    done = np.zeros(count, dtype=bool)
    widths = [w.shape[2] for w in wrenches]
    full = present.all(axis=1) & np.all([c == k for c, k in zip(counts, widths)], axis=0) if limbs else np.zeros(count, dtype=bool)
    for d in np.unique(dim[full]).tolist():
        need = 6 - d
        if d == 0 or n < d or (n == d and sum(widths) == need):
            continue
        if comb(n, d) > MAX_CHOICES or limbs > MAX_LIMBS_CHOSEN:  # too many choices to try: no index (NaN)
            continue
        groups = [s for k in range(1, limbs + 1) for s in combinations(range(limbs), k) if sum(widths[j] for j in s) == need]
        inputs = list(combinations(range(n), d))
        if not groups or len(groups) * len(inputs) > MAX_CHOICES:
            continue
        rows = np.flatnonzero(full & (dim == d))
        a_cols = np.swapaxes(actuation[rows], 1, 2)
        best = np.full(rows.size, -1.0)
        values = np.full((rows.size, limbs), np.nan)
        for chosen in inputs:
            for group in groups:
                stack = np.concatenate([a_cols[:, :, list(chosen)]] + [wrenches[j][rows] for j in group], axis=2)
                adj = _output_twists(np.swapaxes(stack[:, SWAP_ROWS, :], 1, 2), np.broadcast_to(np.eye(6), (rows.size, 6, 6)))
                edges = np.cumsum([d, *(widths[j] for j in group)])
                kappa = np.full((rows.size, limbs), np.nan)
                for k, j in enumerate(group):
                    own = np.full(rows.size, widths[j])
                    kappa[:, j] = _pair_index(wrenches[j][rows], own, adj[:, :, edges[k] : edges[k + 1]], own, points[rows, j])
                score = np.nanmin(kappa, axis=1)
                better = score > best
                best = np.where(better, score, best)
                values[better] = kappa[better]
        values = np.where(degenerate[rows][:, None] & ~np.isnan(values), 0.0, values)
        out[rows] = values
        done[rows] = True
    return out, done


def transmission_indices(actuation: np.ndarray, input_twists: np.ndarray, input_points: np.ndarray, output_points: np.ndarray,
                         basis: np.ndarray, dim: np.ndarray, limb_wrenches: Sequence[np.ndarray] = (),
                         limb_counts: Sequence[np.ndarray] = (), limb_points: np.ndarray | None = None,
                         singular: np.ndarray | None = None, tol: Tolerance = DEFAULT_TOLERANCE) -> BatchTransmission:
    """The transmission indices of ``N`` poses, from the screw systems of the analysis.

    Every screw is in one set of coordinates per pose (the sweep's normalised
    ones: :attr:`mobility.sweeps.posed_screws.PosedScrews.normalised`), the
    points too.

    Parameters
    ----------
    actuation : ndarray, shape (N, n, 6)
        The unit actuation wrench of each input (zeros where it has none).
    input_twists : ndarray, shape (N, 6, n)
        The unit twist of each actuated freedom.
    input_points : ndarray, shape (N, n, 3)
        Where each actuation wrench acts on its input link.
    output_points : ndarray, shape (N, n, 3)
        Where each actuation wrench acts on the end effector.
    basis : ndarray, shape (N, 6, k)
        The end effector's twist system (columns beyond ``dim`` zero).
    dim : ndarray of int, shape (N,)
    limb_wrenches : sequence of ndarray, shape (N, 6, k_j)
        The constraint wrenches of each limb (columns beyond ``limb_counts`` zero).
    limb_counts : sequence of ndarray of int, shape (N,)
    limb_points : ndarray, shape (N, L, 3)
        Where each limb meets the end effector.
    singular : ndarray of bool, shape (N,), optional
        The poses where the rank decision of the actuation verdict finds the
        actuation and constraint wrenches together of rank below 6 (the
        wrench system degenerate): their output and constraint indices are 0
        exactly.

    Examples
    --------
    One prismatic input pushing a slider along its own axis: every index is 1.

    >>> import numpy as np
    >>> x = np.array([0, 0, 0, 1.0, 0, 0])
    >>> r = transmission_indices(np.array([[[1.0, 0, 0, 0, 0, 0]]]), x.reshape(1, 6, 1), np.zeros((1, 1, 3)),
    ...                          np.zeros((1, 1, 3)), x.reshape(1, 6, 1), np.array([1]))
    >>> r.iti.tolist(), r.oti.tolist(), r.lti.tolist()
    ([[1.0]], [[1.0]], [1.0])
    """
    count, n = actuation.shape[0], actuation.shape[1]
    present = np.any(actuation != 0.0, axis=2)
    iti = power_coefficient(actuation, np.swapaxes(input_twists, 1, 2), input_points) if n else np.zeros((count, 0))
    oti = np.full((count, n), np.nan)
    lti = np.full(count, np.nan)
    dim = np.asarray(dim)
    for d in np.unique(dim).tolist() if n else []:
        rows = np.flatnonzero(dim == d)
        if d == 0 or n < d:  # the inputs move no output (a dead centre: the output locked for an instant), or a freedom moves unactuated
            oti[rows] = 0.0
            lti[rows] = 0.0
            continue
        if comb(n, d) > MAX_CHOICES:  # too many choices of inputs to try: OTI and LTI not computed (NaN)
            continue
        t = basis[rows][:, :, :d]
        a = actuation[rows]
        g = a[:, :, SWAP_ROWS] @ t
        best = np.full(rows.size, -1.0)
        for subset in combinations(range(n), d):
            s = list(subset)
            twists = _output_twists(g[:, s], t)
            o = power_coefficient(a[:, s], np.swapaxes(twists, 1, 2), output_points[rows][:, s])
            score = np.minimum(o.min(axis=1), iti[rows][:, s].min(axis=1))
            better = score > best
            best = np.where(better, score, best)
            keep = np.full((better.sum(), n), np.nan)
            keep[:, s] = o[better]
            oti[rows[better]] = keep
        lti[rows] = best
    # An input with no wrench of its own moves no output (its limb at a serial singularity: ITI = 0).  With no more
    # inputs than freedoms the minimum already gives 0; with more, the best choice would leave it out, yet the
    # inputs outnumber the freedoms there because the end effector lost the freedom that input drove: an input
    # singularity, LTI 0 (a five-bar whose crank, elbow and tool point fall in line).
    stalled = (n > dim) & ~present.all(axis=1) if n else np.zeros(count, dtype=bool)
    lti = np.where(stalled, 0.0, lti)
    if n:
        chosen = ~np.isnan(oti)
        iti = np.where(chosen | np.isnan(lti)[:, None] | stalled[:, None], iti, np.nan)
    degenerate = np.zeros(count, dtype=bool) if singular is None else np.asarray(singular, dtype=bool)
    oti = np.where(degenerate[:, None] & ~np.isnan(oti), 0.0, oti)
    lti = np.where(degenerate & ~np.isnan(lti), 0.0, lti)
    points = np.zeros((count, len(limb_wrenches), 3)) if limb_points is None else limb_points
    counts = [np.asarray(c) for c in limb_counts]
    cti_limbs = _limb_index(list(limb_wrenches), counts, points, actuation, present, degenerate, tol)
    chosen, done = _best_choice_index(list(limb_wrenches), counts, points, actuation, present, degenerate, dim)
    cti_limbs = np.where(done[:, None], chosen, cti_limbs)
    return BatchTransmission(iti, oti, lti, cti_limbs, _nanmin(cti_limbs))
