"""The singular value decomposition used by every rank decision.

:func:`numpy.linalg.svd` (LAPACK ``dgesdd``) behind calls that ask for no
more than they use: :func:`left_svd` and :func:`left_svds` never form the
``n x n`` right vectors of a wide ``6 x n`` matrix (cost linear in ``n``).
SciPy's ``dgesvd`` is faster per call (3 µs against 8 µs), but importing
:mod:`scipy.linalg` costs more than a whole ``mobility analyze``
(``benchmarks/bench_start.py``).  No convergence (a NaN or an infinity)
raises :class:`~mobility.errors.AnalysisError`.

Examples
--------
>>> import numpy as np
>>> u, s, vt = svd(np.diag([3.0, 2.0]))
>>> s.tolist()
[3.0, 2.0]
>>> u, s = left_svd(np.ones((2, 5)))
>>> u.shape, s.round(12).tolist()
((2, 2), [3.162277660168, 0.0])
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import AnalysisError
from .tolerance import DEFAULT_TOLERANCE, Tolerance, decide_rank

__all__ = ["svd", "left_svd", "left_svds", "singular_values", "rank"]

_decompose = np.linalg.svd


def _decomposed(m: np.ndarray, **options: Any) -> Any:
    """``numpy.linalg.svd(m, **options)``; an :class:`~mobility.errors.AnalysisError` if it does not converge."""
    try:
        return _decompose(m, **options)
    except np.linalg.LinAlgError:
        raise AnalysisError(f"the singular value decomposition of a {m.shape[-2]}x{m.shape[-1]} matrix did not converge (it holds a NaN or an infinity)") from None


def _as_matrix(m: np.ndarray) -> np.ndarray:
    return m if type(m) is np.ndarray and m.dtype == np.float64 else np.asarray(m, dtype=float)


def svd(m: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Full SVD ``m = u @ diag(s) @ vt`` (``u`` and ``vt`` square), singular values decreasing."""
    m = _as_matrix(m)
    if m.size == 0:
        return np.eye(m.shape[0]), np.zeros(0), np.eye(m.shape[1])
    return _decomposed(m)


def left_svd(m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Left singular vectors ``u`` (square, ``m x m``) and singular values ``s`` (decreasing) of ``m``.

    The columns of ``u`` beyond the rank span the orthogonal complement of
    the column space, which is what a reciprocal system is made of.
    """
    m = _as_matrix(m)
    rows, cols = m.shape
    if m.size == 0:
        return np.eye(rows), np.zeros(0)
    # a tall matrix needs full_matrices for the complement; a wide one gets a square u without it
    u, s, _ = _decomposed(m, full_matrices=cols < rows)
    return u, s


def left_svds(m: np.ndarray, *, full_v: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """:func:`left_svd` of every matrix of a stack ``(N, r, c)``: ``u`` ``(N, r, r)``, ``s`` and, if asked, ``vt`` ``(N, c, c)``.

    A stack is decomposed matrix by matrix by the same LAPACK routine as one
    matrix, so a stack of one gives the numbers of :func:`left_svd`; only the
    call's overhead is shared.  On a large stack of tall or square matrices
    the transposed problem is the cheaper one for LAPACK (10-20 % on 100,000
    matrices of 6 x 5), so it is solved instead; its singular values and
    vectors are the same up to round-off.

    Examples
    --------
    >>> u, s, _ = left_svds(np.stack([np.diag([3.0, 2.0]), np.diag([1.0, 5.0])]))
    >>> s.tolist()
    [[3.0, 2.0], [5.0, 1.0]]
    """
    count, rows, cols = m.shape
    if rows * cols == 0:
        return np.broadcast_to(np.eye(rows), (count, rows, rows)), np.zeros((count, 0)), np.broadcast_to(np.eye(cols), (count, cols, cols))
    try:
        if full_v:
            return _decompose(m)
        if cols <= rows and count >= _TRANSPOSE_FROM:
            _, s, vt = _decompose(np.swapaxes(m, 1, 2))
            return np.swapaxes(vt, 1, 2), s, None
        u, s, _ = _decompose(m, full_matrices=cols < rows)
        return u, s, None
    except np.linalg.LinAlgError:
        raise AnalysisError(f"the singular value decomposition of a stack of {rows}x{cols} matrices did not converge (it holds a NaN or an infinity)") from None


_TRANSPOSE_FROM = 64  # stacks from this size solve the transposed problem of a tall matrix


def singular_values(m: np.ndarray) -> np.ndarray:
    """Singular values of ``m``, decreasing (of each matrix of a stack ``(N, r, c)``, one row each)."""
    m = _as_matrix(m)
    if m.size == 0:
        return np.zeros(m.shape[:-2] + (min(m.shape[-2:]),))
    return _decomposed(m, compute_uv=False)


def rank(m: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> int:
    """The rank of ``m`` as the tolerance policy decides it (:func:`~mobility.core.tolerance.decide_rank`).

    Examples
    --------
    >>> rank(np.array([[1.0, 2.0], [2.0, 4.0 + 1e-12]]))
    1
    """
    return decide_rank(singular_values(m), tol).rank
