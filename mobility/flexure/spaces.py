"""Freedom and constraint spaces of a flexure mechanism, from the eigen-decomposition of its compliance.

Eigenvectors (wrenches) of the normalised compliance whose *relative
compliance* is at most the threshold span the constraint space, the others the
freedom space (docs/actuation.md, "Non-dimensionalisation and split").

Examples
--------
>>> from mobility.flexure.model import FlexureMechanism, Material, Rod
>>> rod = Rod("w", ("g", "s"), start=(0, 0, 0), axis=(0, 0, 1), length=0.1, radius=0.001,
...           material=Material("steel", 200e9, 0.3))
>>> spaces = flexure_spaces(FlexureMechanism("one wire", "g", "s", (rod,)))
>>> spaces.dof, spaces.pattern   # a single wire constrains one force along it
(5, '2T3R')
>>> [(f.kind, f.axis.tolist()) for f in spaces.constraint_forces]
[('force', [0.0, 0.0, 1.0])]
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..actuation import EndEffectorSpaces
from ..core.analysis import screw_system_in_frame
from ..core.frozen import ReadOnlyArrays
from ..core.result import ScrewAxis
from ..core.screws import SWAP_ROWS, motion_pattern
from ..core.validation import require_real
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, clean_numbers, require_tolerance
from ..errors import RequestError, shown_argument
from .compliance import compliance_matrix, normalised_energy_form
from .model import FlexureMechanism, require_flexure

__all__ = ["DEFAULT_THRESHOLD", "CLEAR_GAP", "FlexureSpaces", "flexure_spaces"]

DEFAULT_THRESHOLD = 1e-2
"""Default relative-compliance threshold between freedom and constraint directions."""

CLEAR_GAP = 10.0
"""The relative compliances either side of the threshold must differ by this factor, or a warning says so."""


@dataclass(frozen=True, eq=False)
class FlexureSpaces(ReadOnlyArrays):
    """Freedom and constraint spaces of a flexure mechanism's end effector.

    Its arrays (those of ``normalised`` too) are read-only, also after a pickle round trip.

    Attributes
    ----------
    name : str
    eigenvalues : ndarray, shape (6,)
        Relative compliances, decreasing.
    largest : float
        The largest eigenvalue of ``Q`` in normalised coordinates (1/N).
    threshold : float
        Relative compliances above it are freedoms.
    dof : int
        Dimension of the freedom space.
    pattern : str
        ``{nT}T{nR}R`` of the freedom space.
    freedom_translations : ndarray, shape (k, 3)
    freedom_rotations : tuple of ScrewAxis
    freedom_twists : ndarray, shape (dof, 6)
        Basis (rows ``[w; v]``), global frame, document length unit.
    constraint_couples : ndarray, shape (k, 3)
    constraint_forces : tuple of ScrewAxis
    constraint_wrenches : ndarray, shape (6 - dof, 6)
        Basis (rows ``[f; m]``).
    gap : (float, float)
        The relative compliances either side of the threshold (0 or 1 at an end).
    compliance : ndarray, shape (6, 6)
        :func:`~mobility.flexure.compliance.compliance_matrix` (SI, about the global origin).
    length : float
        The characteristic length ``L`` used (document unit).
    length_unit : str
    normalised : EndEffectorSpaces
        The two spaces, orthonormal, normalised, with the reference point (the
        centroid of the elements' ends on the end effector): what actuators are assessed against.
    warnings : tuple of str
    """

    name: str
    eigenvalues: np.ndarray
    largest: float
    threshold: float
    dof: int
    pattern: str
    freedom_translations: np.ndarray
    freedom_rotations: tuple[ScrewAxis, ...]
    freedom_twists: np.ndarray
    constraint_couples: np.ndarray
    constraint_forces: tuple[ScrewAxis, ...]
    constraint_wrenches: np.ndarray
    gap: tuple[float, float]
    compliance: np.ndarray
    length: float
    length_unit: str
    normalised: EndEffectorSpaces = field(repr=False)
    warnings: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        s = self.length
        return {"name": self.name, "kind": "flexure", "eigenvalues": clean_numbers(self.eigenvalues), "largest_eigenvalue_per_newton": self.largest,
                "threshold": self.threshold, "gap": list(self.gap), "dof": self.dof, "pattern": self.pattern,
                "freedoms": {"translations": clean_numbers(self.freedom_translations), "rotations": [a.to_dict(s) for a in self.freedom_rotations],
                             "twists": clean_numbers(self.freedom_twists, s)},
                "constraints": {"couples": clean_numbers(self.constraint_couples), "forces": [a.to_dict(s) for a in self.constraint_forces],
                                "wrenches": clean_numbers(self.constraint_wrenches, s)},
                "compliance_si": self.compliance.tolist(), "characteristic_length": self.length, "length_unit": self.length_unit,
                "warnings": list(self.warnings)}


def flexure_spaces(mechanism: FlexureMechanism, threshold: float | None = None, *, tol: Tolerance = DEFAULT_TOLERANCE) -> FlexureSpaces:
    """Freedom and constraint spaces from the eigen-decomposition of the compliance.

    Parameters
    ----------
    threshold : float, optional
        Relative compliance above which a direction is a freedom (default: the
        document's ``threshold``, else :data:`DEFAULT_THRESHOLD`).
    tol : Tolerance
        Used for the canonical forms of the spaces.

    Raises
    ------
    RequestError
        When ``mechanism`` is not a :class:`FlexureMechanism`, or ``threshold`` not a number between 0 and 1.
    """
    mechanism = require_flexure(mechanism, "flexure_spaces")
    tol = require_tolerance(tol, "flexure_spaces")
    if threshold is None:
        threshold = mechanism.threshold if mechanism.threshold is not None else DEFAULT_THRESHOLD
    else:
        try:
            require_real(threshold, "")
        except RequestError:
            raise RequestError(f"threshold must be a number between 0 and 1, got {shown_argument(threshold)}") from None
    if not (0.0 < threshold < 1.0):
        raise RequestError(f"threshold must lie between 0 and 1, got {threshold!r}")
    compliance = compliance_matrix(mechanism)
    q, norm = normalised_energy_form(mechanism, compliance)
    values, vectors = np.linalg.eigh(q)
    order = np.argsort(values)[::-1]
    values, vectors = values[order], vectors[:, order]
    largest = float(values[0])
    relative = values / largest
    free = relative > threshold
    dof = int(np.count_nonzero(free))
    normalised = EndEffectorSpaces(vectors[SWAP_ROWS][:, free], vectors[:, ~free], norm, norm.point_from_world(mechanism.end_effector_centre()))
    translations, rotations, twist_rows = screw_system_in_frame(normalised.twists, norm, normalised.reference, ("rotation", "helical"), tol)
    couples, forces, wrench_rows = screw_system_in_frame(normalised.constraints, norm, normalised.reference, ("force", "wrench"), tol)
    above = float(relative[dof - 1]) if dof else 1.0
    below = float(relative[dof]) if dof < 6 else 0.0
    warnings = []
    if below > 0 and above < CLEAR_GAP * below:
        warnings.append(f"the threshold {threshold:g} does not sit in a clear gap: the relative compliances either side are "
                        f"{above:.3g} and {below:.3g} (less than a factor {CLEAR_GAP:g} apart); the split into freedoms and constraints is uncertain")
    return FlexureSpaces(mechanism.name, relative, largest, float(threshold), dof, motion_pattern(normalised.twists, tol), translations, rotations,
                         twist_rows, couples, forces, wrench_rows, (above, below), compliance, norm.length, mechanism.length_unit, normalised, tuple(warnings))
