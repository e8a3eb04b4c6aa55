"""The singular value decomposition used by every rank decision.

The matrices of screw theory are tiny (6 x n), where the Python wrapper of
:func:`numpy.linalg.svd` costs more than the factorisation itself; this calls
LAPACK's ``dgesvd`` (QR iteration; for matrices this small it is as fast as
divide and conquer) through :mod:`scipy.linalg.lapack` directly, and tries
``dgesdd`` if it does not converge.

Examples
--------
>>> import numpy as np
>>> u, s, vt = svd(np.diag([3.0, 2.0]))
>>> s.tolist()
[3.0, 2.0]
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lapack

from ..errors import AnalysisError

__all__ = ["svd", "singular_values"]


def svd(m: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Full SVD ``m = u @ diag(s) @ vt`` (``u`` and ``vt`` square), singular values decreasing."""
    if type(m) is not np.ndarray or m.dtype != np.float64:
        m = np.asarray(m, dtype=float)
    if m.size == 0:
        return np.eye(m.shape[0]), np.zeros(0), np.eye(m.shape[1])
    u, s, vt, info = lapack.dgesvd(m)
    if info:
        u, s, vt, info = lapack.dgesdd(m)
        if info:
            raise AnalysisError(f"the singular value decomposition of a {m.shape[0]}x{m.shape[1]} matrix did not converge")
    return u, s, vt


def singular_values(m: np.ndarray) -> np.ndarray:
    """Singular values of ``m``, decreasing."""
    m = np.asarray(m, dtype=float)
    if m.size == 0:
        return np.zeros(0)
    _, s, _, info = lapack.dgesdd(m, compute_uv=0)
    if info != 0:
        return svd(m)[1]
    return s
