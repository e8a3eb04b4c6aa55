"""Compliance of flexure elements and of a flexure mechanism's end effector.

A compliance matrix ``C`` maps a wrench ``[f; m]`` (N, N m) to the small
displacement twist ``[w; v]`` (rad, m) it causes, ``T = C W``; ``Q = SWAP C``
is symmetric positive definite (the work ``W^T Q W``) and every
eigen-decomposition is of ``Q``.  Rods are Euler-Bernoulli beams (no shear
deformation); the elements' stiffnesses are assembled over the bodies other
than the ground, as in a finite-element model, so any network works.  The
formulas and the normalised coordinates: docs/actuation.md, "Compliance" and
"Non-dimensionalisation and split".

Examples
--------
>>> import numpy as np
>>> from mobility.flexure.model import FlexureMechanism, Material, Rod
>>> rod = Rod("w", ("g", "s"), start=(0, 0, 0), axis=(0, 0, 1), length=0.1, radius=0.001,
...           material=Material("steel", 200e9, 0.3))
>>> c = compliance_matrix(FlexureMechanism("one wire", "g", "s", (rod,)))
>>> bool(np.isclose(c[5, 2], 0.1 / (200e9 * np.pi * 1e-6)))   # axial: l / (E A)
True
"""

from __future__ import annotations

import math

import numpy as np

from ..core.joint_screws import Normalisation
from ..core.screws import SWAP, adjoint
from ..errors import MechanismError
from .model import FlexureMechanism

__all__ = ["rod_compliance", "compliance_matrix", "normalised_energy_form"]


def rod_compliance(length: float, radius: float, E: float, nu: float) -> np.ndarray:
    """Compliance of a clamped rod's end, in a frame at that end with ``z`` along the rod.

    Units are those of the arguments (e.g. metres and pascals give rad/N m,
    m/N...).  Twist ``[w; v]`` = ``C @ [f; m]``.

    Examples
    --------
    >>> import numpy as np
    >>> c = rod_compliance(2.0, 0.1, 1.0, 0.25)
    >>> I = np.pi * 0.1**4 / 4
    >>> bool(np.isclose(c[3, 0], 2.0**3 / (3 * I)))      # v_x from f_x
    True
    >>> from mobility.core.screws import SWAP
    >>> bool(np.allclose(SWAP @ c, (SWAP @ c).T))      # the energy form is symmetric
    True
    """
    area = math.pi * radius**2
    inertia = math.pi * radius**4 / 4.0
    polar = 2.0 * inertia
    shear = E / (2.0 * (1.0 + nu))
    bend = length / (E * inertia)
    couple = length**2 / (2.0 * E * inertia)
    deflect = length**3 / (3.0 * E * inertia)
    c = np.zeros((6, 6))
    # rows w (0-2), v (3-5); columns f (0-2), m (3-5)
    c[0, 3] = bend
    c[0, 1] = -couple
    c[1, 4] = bend
    c[1, 0] = couple
    c[2, 5] = length / (shear * polar)
    c[3, 0] = deflect
    c[3, 4] = couple
    c[4, 1] = deflect
    c[4, 3] = -couple
    c[5, 2] = length / (E * area)
    return c


def compliance_matrix(mechanism: FlexureMechanism) -> np.ndarray:
    """Compliance of the end effector relative to the ground, global frame, SI units.

    ``[w; v] = C @ [f; m]`` with the twist and wrench about the global origin;
    rad, m, N and N m.

    Raises
    ------
    MechanismError
        When the assembled stiffness is singular (a body held by nothing).
    """
    metres = mechanism.metres
    movable = [b for b in mechanism.bodies if b != mechanism.ground]
    slot = {b: 6 * i for i, b in enumerate(movable)}
    h = np.zeros((6 * len(movable), 6 * len(movable)))
    for index, e in enumerate(mechanism.elements):
        rot, end = e.frame()
        ad = adjoint(rot, end * metres)
        try:
            with np.errstate(all="raise"):
                local = rod_compliance(e.length * metres, e.radius * metres, e.material.E, e.material.nu)
                c = ad @ local @ np.linalg.inv(ad)
                q = SWAP @ c
                stiff = SWAP @ np.linalg.inv(0.5 * (q + q.T)) @ SWAP  # energy form of C^-1
        except (ArithmeticError, FloatingPointError, np.linalg.LinAlgError):
            stiff = None
        if stiff is None or not np.all(np.isfinite(stiff)):
            raise MechanismError(f"elements[{index}]", f"the compliance of {e.name!r} (length {e.length:g}, radius {e.radius:g}, E {e.material.E:g}) "
                                 "is beyond the range of double precision in SI units; expected sizes and moduli a physical flexure can have")
        ends = [slot[b] for b in e.bodies if b in slot]  # the ground's end holds nothing to solve for
        for si in ends:
            for sj in ends:
                h[si : si + 6, sj : sj + 6] += stiff if si == sj else -stiff
    try:
        inverse = np.linalg.inv(h)
    except np.linalg.LinAlgError:
        raise MechanismError("elements", "the elements do not hold every body (singular stiffness)") from None
    k = slot[mechanism.end_effector]
    return inverse[k : k + 6, k : k + 6] @ SWAP


def normalised_energy_form(mechanism: FlexureMechanism, compliance: np.ndarray) -> tuple[np.ndarray, Normalisation]:
    """``Q = SWAP C`` (1/N) of the :func:`compliance_matrix` ``compliance`` in normalised coordinates, symmetrised.

    Returns ``Q`` and those coordinates, :meth:`FlexureMechanism.normalisation` (document length unit).
    """
    norm = mechanism.normalisation()
    metres = mechanism.metres
    to_normalised = Normalisation(norm.centre * metres, norm.length * metres).from_world(np.eye(6))  # C is in SI units
    q = SWAP @ to_normalised @ compliance @ np.linalg.inv(to_normalised)
    return 0.5 * (q + q.T), norm
