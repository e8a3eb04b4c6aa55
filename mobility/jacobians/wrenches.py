"""Reading the wrenches of a Jacobian at any scale: norms, couples, axes, round-off.

A wrench ``[f; m]`` of a mechanism of characteristic length ``L`` is compared
part with part in normalised terms, ``[f; m / L]``: its force is round-off
next to its moment when ``|f| L`` is (a couple), and each part's round-off is
shown as 0 against the whole.  Norms are taken on numbers scaled by a power
of two (:func:`~mobility.core.tolerance.binary_scale`), so nothing overflows
or underflows at 1e200 or 1e-250.

Examples
--------
>>> is_couple(np.array([1e-14, 0, 0, 0, 2, 0]), DEFAULT_TOLERANCE), is_couple(np.array([1e-6, 0, 0, 0, 2, 0]), DEFAULT_TOLERANCE)
(True, False)
>>> float(norm(np.array([3e200, 4e200])) / 1e200), float(norm(np.array([3e-200, 4e-200])) / 1e-200)   # no overflow, no underflow
(5.0, 5.0)
"""

from __future__ import annotations

import numpy as np

from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, binary_scale, clean_numbers
from ..core.transforms import cross

__all__ = ["norm", "is_couple", "wrench_axis", "clean_screw", "dominant_signs", "unit_wrench"]


def norm(v: np.ndarray) -> float:
    """Euclidean norm without overflow or underflow (computed on the entries scaled by a power of two)."""
    scale = binary_scale(v)
    return float(np.linalg.norm(np.asarray(v, dtype=float) * scale)) / scale


def is_couple(wrench: np.ndarray, tol: Tolerance, length: float = 1.0) -> bool:
    """Whether the force part of ``[f; m]`` is round-off next to its moment over ``length``: a pure couple.

    Like with like (the moment over ``length``): the same at every scale of the file.
    """
    w = np.asarray(wrench, dtype=float)
    scale = binary_scale(w[:3], w[3:] / length)
    return norm(w[:3] * scale) <= tol.round_off * norm(w[3:] / length * scale)


def wrench_axis(wrench: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE, length: float = 1.0) -> tuple[str, np.ndarray, np.ndarray, float]:
    """Kind, unit direction, point nearest the origin and pitch of a wrench ``[f; m]``.

    The direction keeps the sign of the force. A force part at round-off next
    to the moment over ``length`` (the characteristic length) makes a couple; a
    pitch at round-off next to the larger of ``length`` and the axis's distance
    a pure force. Nothing is squared before it is scaled.

    Examples
    --------
    >>> kind, d, p, h = wrench_axis([0.0, 0, 2, 0, -2, 0])      # a force along z through (1, 0, 0)
    >>> kind, d.tolist(), p.tolist(), h
    ('force', [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], 0.0)
    >>> wrench_axis([0.0, 0, 0, 0, 0, -3])[:2]                    # a couple about -z
    ('couple', array([ 0.,  0., -1.]))
    >>> wrench_axis([0.0, 0, 2e-200, 0, -2e-200 * 1e250, 0], length=1e250)[2].tolist()   # the same force, scaled
    [1e+250, 0.0, 0.0]
    """
    w = np.asarray(wrench, dtype=float)
    f, m = w[:3], w[3:]
    if is_couple(w, tol, length):
        return "couple", m / norm(m), np.zeros(3), 0.0
    nf = norm(f)
    d = f / nf
    moment = m / nf  # the moment per unit force: a length, finite whenever the axis is representable
    pitch = float(d @ moment)
    point = cross(d, moment)
    pitch = 0.0 if abs(pitch) <= tol.round_off * max(length, norm(point)) else pitch
    return ("force" if pitch == 0.0 else "wrench"), d, point + 0.0, pitch


def clean_screw(screw: np.ndarray, length: float, moment_first: bool = False) -> list[float]:
    """A screw ``[a; b]`` (``b`` a moment or a velocity: ``a`` times a length) as a list, round-off shown as 0.

    Each part against the whole screw's size ``max(|a|, |b| / length)`` (``b``
    times ``length``): a file scaled by any factor shows the same zeros.
    ``moment_first``: written ``[b; a]`` (a row of the Jacobian, ``(SWAP W)^T``).

    Examples
    --------
    >>> clean_screw(np.array([0.0, 0, 1e200, 1e-120, 0, 0]), 1e-200)   # a force 1e200 and its moment 1e-120 at length 1e-200
    [0.0, 0.0, 1e+200, 0.0, 0.0, 0.0]
    >>> clean_screw(np.array([0.0, 0, 1e-200, 1e-5, 0, 0]), 1e200)     # a lever of 1e195 at length 1e200: kept
    [0.0, 0.0, 1e-200, 1e-05, 0.0, 0.0]
    """
    s = np.asarray(screw, dtype=float).reshape(6)
    a, b = (s[3:], s[:3]) if moment_first else (s[:3], s[3:])
    size = max(norm(a), norm(b) / length)
    a_clean, b_clean = clean_numbers(a, size), clean_numbers(b, size * length)
    return b_clean + a_clean if moment_first else a_clean + b_clean


def dominant_signs(columns: np.ndarray) -> np.ndarray:
    """The sign of each column's entry of largest magnitude."""
    if not columns.shape[1]:
        return np.ones(0)
    return np.sign(columns[np.argmax(np.abs(columns), axis=0), np.arange(columns.shape[1])])


def unit_wrench(w: np.ndarray, tol: Tolerance, length: float) -> np.ndarray:
    """A wrench scaled to a unit force part (a couple to a unit moment)."""
    return w / norm(w[3:] if is_couple(w, tol, length) else w[:3])
