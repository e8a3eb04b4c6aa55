"""Compliance of flexure elements and of a flexure mechanism's end effector.

Conventions
-----------
* A compliance matrix ``C`` maps a wrench ``[f; m]`` (N, N m) to the small
  displacement twist ``[w; v]`` (rad, m) it causes: ``T = C W``.  Twists and
  wrenches change frame by the same adjoint ``Ad``, so ``C`` does by
  ``Ad C Ad^-1``.  ``Q = SWAP C`` is symmetric positive definite (the work
  ``W . SWAP T = W^T Q W``); every eigen-decomposition is of ``Q``.
* **Rod** (circular cross-section, radius ``r``, length ``l``, Young's modulus
  ``E``, Poisson's ratio ``nu``, ``G = E / (2 (1 + nu))``; Euler-Bernoulli
  bending, no shear deformation), clamped on body ``a`` at its start and on
  body ``b`` at its end; in a frame at its end with ``z`` along the rod, the
  end's displacement under a wrench applied there is
  ``v_z = l/(EA) f_z``, ``w_z = l/(GJ) m_z``, and in bending
  ``v_x = l^3/(3EI) f_x + l^2/(2EI) m_y``, ``w_y = l^2/(2EI) f_x + l/(EI) m_y``
  (and the same about ``x`` with the signs of ``f_y``, ``m_x`` turned), with
  ``A = pi r^2``, ``I = pi r^4 / 4``, ``J = pi r^4 / 2``.
* **Network**: the stiffness of every element (``H = SWAP C^-1 SWAP`` in the
  energy form) is assembled over the bodies other than the ground, as in a
  finite-element model; the end effector's compliance is its block of the
  inverse, times ``SWAP``.  Elements in parallel add stiffnesses, elements in
  series add compliances, and any other network (bridges) is handled alike.
* **Non-dimensionalisation** (:func:`normalised_energy_form`): ``Q`` is
  written in the normalised coordinates of the tolerance policy (origin at
  the centroid ``c`` of the element end points, lengths divided by their RMS
  distance ``L`` from it): a wrench ``[f; (m - c x f) / L]`` and a twist
  ``[w; (v - c x w) / L]``.  Every entry of ``Q`` is then in 1/N; its
  eigenvalues over the largest do not depend on the unit of length or of
  modulus, nor on where the mechanism is placed.

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
    """``Q = SWAP C`` in normalised coordinates, symmetrised, and those coordinates (document length unit).

    Parameters
    ----------
    compliance : ndarray, shape (6, 6)
        The mechanism's :func:`compliance_matrix` (SI units).

    Returns
    -------
    q : ndarray, shape (6, 6)
        Symmetric, in 1/N.
    normalisation : Normalisation
        :meth:`FlexureMechanism.normalisation` (document length unit).
    """
    norm = mechanism.normalisation()
    metres = mechanism.metres
    to_normalised = Normalisation(norm.centre * metres, norm.length * metres).from_world(np.eye(6))  # C is in SI units
    q = SWAP @ to_normalised @ compliance @ np.linalg.inv(to_normalised)
    return 0.5 * (q + q.T), norm
