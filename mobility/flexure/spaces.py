"""Flexure mechanisms: compliance, freedom and constraint spaces, linear actuators.

A flexure mechanism is rigid bodies joined by compliant elements (here:
slender rods, i.e. wire flexures) instead of joints.  Each element has a 6x6
compliance matrix in its own frame; they are combined by adjoint transforms
into the compliance of the end effector relative to the ground; the
eigen-decomposition of that matrix, made dimensionless, separates the
*freedom space* (directions of large compliance) from the *constraint space*
(directions of small compliance) at a stated threshold.  Linear actuators,
force lines on the end effector, are then checked exactly like the actuated
joints of a rigid mechanism (:mod:`mobility.actuation.actuation`): valid when their
wrenches and the constraint wrenches span six dimensions.  This is the flexure
half of Li, Shan, Yu and Ke, "Actuation Spaces Synthesis of Lower-Mobility
Parallel Mechanisms Based on Screw Theory" (Chinese Journal of Mechanical
Engineering, 2021).

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
* **Non-dimensionalisation**: ``Q`` is written in the normalised coordinates
  of the tolerance policy (origin at the centroid ``c`` of the element end
  points, lengths divided by their RMS distance ``L`` from it):
  a wrench ``[f; (m - c x f) / L]`` and a twist ``[w; (v - c x w) / L]``.
  Every entry of ``Q`` is then in 1/N; the eigenvalues divided by the largest
  one (*relative compliances*, between 0 and 1) do not depend on the unit of
  length or of modulus, nor on where the mechanism is placed.
* **Split**: eigenvectors (wrenches, normalised coordinates) whose relative
  compliance is at most the *threshold* span the constraint space; the others,
  through ``SWAP``, span the freedom space (the twists reciprocal to the
  constraint space: eigenvectors are orthogonal).  The default threshold is
  :data:`DEFAULT_THRESHOLD`; the report gives every eigenvalue and warns when
  the threshold is not in a clear gap between two clusters.

Examples
--------
>>> import numpy as np
>>> rod = Rod("w", ("g", "s"), start=(0, 0, 0), axis=(0, 0, 1), length=0.1, radius=0.001,
...           material=Material("steel", 200e9, 0.3))
>>> m = FlexureMechanism("one wire", "g", "s", (rod,))
>>> c = compliance_matrix(m)
>>> bool(np.isclose(c[5, 2], 0.1 / (200e9 * np.pi * 1e-6)))   # axial: l / (E A)
True
>>> spaces = flexure_spaces(m)
>>> spaces.dof, spaces.pattern   # a single wire constrains one force along it
(5, '2T3R')
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from typing import Any, Sequence

import numpy as np

from ..actuation.actuation import (
    MAX_COMBINATIONS,
    ActuationCheck,
    Enumeration,
    _assess,
    _build_check,
    _combine,
    _plain,
    _axis_dict,
    _rank_combinations,
)
from ..core.analysis import screw_system_in_frame
from ..errors import MechanismError
from ..core.joint_screws import Normalisation
from ..core.result import ScrewAxis, pattern_of
from ..core.screws import SWAP, SWAP_ROWS, adjoint, free_vector_subspace
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, characteristic_scale, decide_rank

__all__ = [
    "DEFAULT_THRESHOLD",
    "LENGTH_UNITS",
    "MODULUS_UNITS",
    "Material",
    "Rod",
    "ForceLine",
    "FlexureMechanism",
    "FlexureSpaces",
    "rod_compliance",
    "compliance_matrix",
    "flexure_spaces",
    "check_force_lines",
    "enumerate_force_lines",
    "line_set_type",
    "actuation_tolerance",
]

DEFAULT_THRESHOLD = 1e-2
"""Default relative-compliance threshold between freedom and constraint directions."""

LENGTH_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "in": 0.0254}
"""Length units a flexure document may use, in metres."""

MODULUS_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9, "N/mm^2": 1e6, "N/m^2": 1.0, "psi": 6894.757293168361}
"""Units of Young's modulus a flexure document may use, in pascals."""

Vector = tuple[float, float, float]


def _vec(value: Any, key: str, *, direction: bool = False) -> Vector:
    arr = np.asarray(value, dtype=float).reshape(-1)
    if arr.shape != (3,) or not np.all(np.isfinite(arr)):
        raise MechanismError(key, f"expected 3 finite numbers, got {value!r}")
    if direction:
        n = float(np.linalg.norm(arr))
        if n == 0.0:
            raise MechanismError(key, "expected a non-zero direction, got [0, 0, 0]")
        arr = arr / n
    return (float(arr[0]), float(arr[1]), float(arr[2]))


def _positive(value: Any, key: str) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise MechanismError(key, f"expected a positive number, got {value!r}") from None
    if not math.isfinite(x) or x <= 0.0:
        raise MechanismError(key, f"expected a positive number, got {value!r}")
    return x


@dataclass(frozen=True)
class Material:
    """An isotropic elastic material: Young's modulus ``E`` (pascals) and Poisson's ratio ``nu``."""

    name: str
    E: float
    nu: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "E", _positive(self.E, "E"))
        nu = float(self.nu)
        if not (-1.0 < nu < 0.5):
            raise MechanismError("nu", f"expected Poisson's ratio in (-1, 0.5), got {self.nu!r}")
        object.__setattr__(self, "nu", nu)

    @property
    def G(self) -> float:
        """Shear modulus ``E / (2 (1 + nu))``."""
        return self.E / (2.0 * (1.0 + self.nu))


@dataclass(frozen=True)
class Rod:
    """A slender rod of circular cross-section (a wire flexure) clamped between two bodies.

    Geometry is in the global frame and the document's length unit.

    Parameters
    ----------
    name : str
    bodies : (str, str)
        The rod starts on ``bodies[0]`` and ends on ``bodies[1]``.
    start : 3-vector
        Where it leaves ``bodies[0]``.
    axis : 3-vector
        Its direction (normalised on construction).
    length, radius : float
    material : Material
    """

    name: str
    bodies: tuple[str, str]
    start: Vector
    axis: Vector
    length: float
    radius: float
    material: Material

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise MechanismError("name", f"expected a non-empty string, got {self.name!r}")
        b = tuple(self.bodies) if isinstance(self.bodies, (list, tuple)) else ()
        if len(b) != 2 or not all(isinstance(x, str) and x for x in b):
            raise MechanismError("bodies", f"expected two body names, got {self.bodies!r}")
        if b[0] == b[1]:
            raise MechanismError("bodies", f"an element must join two different bodies, got {b[0]!r} twice")
        object.__setattr__(self, "bodies", b)
        object.__setattr__(self, "start", _vec(self.start, "point"))
        object.__setattr__(self, "axis", _vec(self.axis, "axis", direction=True))
        object.__setattr__(self, "length", _positive(self.length, "length"))
        object.__setattr__(self, "radius", _positive(self.radius, "radius"))
        if self.radius >= self.length:
            raise MechanismError("radius", f"a rod must be slender: radius {self.radius:g} is not smaller than its length {self.length:g}")

    @property
    def end(self) -> np.ndarray:
        """Where it meets ``bodies[1]``."""
        return np.asarray(self.start) + self.length * np.asarray(self.axis)

    def frame(self) -> tuple[np.ndarray, np.ndarray]:
        """Rotation (columns: local x, y, z with z along the rod) and origin (the end) of its frame."""
        z = np.asarray(self.axis)
        helper = np.eye(3)[int(np.argmin(np.abs(z)))]
        x = np.cross(helper, z)
        x /= np.linalg.norm(x)
        return np.column_stack([x, np.cross(z, x), z]), self.end


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
    >>> bool(np.allclose(np.array([[0,0,0,1,0,0],[0,0,0,0,1,0],[0,0,0,0,0,1],
    ...                            [1,0,0,0,0,0],[0,1,0,0,0,0],[0,0,1,0,0,0]]) @ c,
    ...                  (np.array([[0,0,0,1,0,0],[0,0,0,0,1,0],[0,0,0,0,0,1],
    ...                             [1,0,0,0,0,0],[0,1,0,0,0,0],[0,0,1,0,0,0]]) @ c).T))
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


@dataclass(frozen=True)
class ForceLine:
    """A candidate linear actuator: a force on the end effector along a line.

    Parameters
    ----------
    name : str
    point : 3-vector
        A point of the line (global frame, document length unit).
    direction : 3-vector
        Its direction (normalised on construction).
    actuated : bool
        Whether it belongs to the chosen set of inputs.
    """

    name: str
    point: Vector
    direction: Vector
    actuated: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise MechanismError("name", f"expected a non-empty string, got {self.name!r}")
        object.__setattr__(self, "point", _vec(self.point, "point"))
        object.__setattr__(self, "direction", _vec(self.direction, "direction", direction=True))
        if not isinstance(self.actuated, bool):
            raise MechanismError("actuated", f"expected true or false, got {self.actuated!r}")

    def wrench(self) -> np.ndarray:
        """The unit force ``[d; p x d]`` (global frame)."""
        d = np.asarray(self.direction)
        return np.concatenate([d, np.cross(self.point, d)])


@dataclass(frozen=True)
class FlexureMechanism:
    """Rigid bodies joined by flexure elements (a frozen description).

    Parameters
    ----------
    name, ground, end_effector : str
    elements : tuple of Rod
    actuators : tuple of ForceLine
        Candidate linear actuators on the end effector.
    description : str
    length_unit : str
        A key of :data:`LENGTH_UNITS` (default ``"m"``).
    threshold : float or None
        Relative-compliance threshold (``None``: :data:`DEFAULT_THRESHOLD`).
    source : str
        Where it came from, for messages.
    """

    name: str
    ground: str
    end_effector: str
    elements: tuple[Rod, ...]
    actuators: tuple[ForceLine, ...] = ()
    description: str = ""
    length_unit: str = "m"
    threshold: float | None = None
    source: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "elements", tuple(self.elements))
        object.__setattr__(self, "actuators", tuple(self.actuators))
        for key in ("name", "ground", "end_effector"):
            value = getattr(self, key)
            if not isinstance(value, str) or not value:
                raise MechanismError(key, f"expected a non-empty string, got {value!r}")
        if not self.elements:
            raise MechanismError("elements", "expected at least one flexure element")
        if self.length_unit not in LENGTH_UNITS:
            raise MechanismError("units.length", f"unknown length unit {self.length_unit!r}; expected one of: {', '.join(LENGTH_UNITS)}")
        seen: dict[str, int] = {}
        for i, e in enumerate(self.elements):
            if e.name in seen:
                raise MechanismError(f"elements[{i}].name", f"duplicate element name {e.name!r} (first used by elements[{seen[e.name]}])")
            seen[e.name] = i
        names: dict[str, int] = {}
        for i, a in enumerate(self.actuators):
            if a.name in names:
                raise MechanismError(f"actuators[{i}].name", f"duplicate actuator name {a.name!r}")
            names[a.name] = i
        bodies = self.bodies
        if self.ground not in bodies:
            raise MechanismError("ground", f"body {self.ground!r} is not joined by any element")
        if self.end_effector not in bodies:
            raise MechanismError("end_effector", f"body {self.end_effector!r} is not joined by any element")
        if self.ground == self.end_effector:
            raise MechanismError("end_effector", "the end effector must differ from the ground")
        reached = {self.ground}
        changed = True
        while changed:
            changed = False
            for e in self.elements:
                a, b = e.bodies
                if (a in reached) != (b in reached):
                    reached |= {a, b}
                    changed = True
        missing = sorted(set(bodies) - reached)
        if missing:
            raise MechanismError("elements", f"bodies not connected to the ground {self.ground!r}: {', '.join(missing)}")
        if self.threshold is not None and not (0.0 < float(self.threshold) < 1.0):
            raise MechanismError("threshold", f"expected a number between 0 and 1, got {self.threshold!r}")

    @property
    def bodies(self) -> tuple[str, ...]:
        """Body names in order of first appearance."""
        return tuple(dict.fromkeys(b for e in self.elements for b in e.bodies))

    @property
    def metres(self) -> float:
        """Metres per length unit of the document."""
        return LENGTH_UNITS[self.length_unit]

    def normalisation(self) -> Normalisation:
        """Normalised coordinates: centroid and RMS radius of the element end points."""
        pts = np.array([p for e in self.elements for p in (e.start, e.end)], dtype=float)
        centre, length = characteristic_scale(pts, np.array([e.length for e in self.elements]))
        return Normalisation(centre, length)


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
    for e in mechanism.elements:
        rot, end = e.frame()
        ad = adjoint(rot, end * metres)
        local = rod_compliance(e.length * metres, e.radius * metres, e.material.E, e.material.nu)
        c = ad @ local @ np.linalg.inv(ad)
        q = SWAP @ c
        stiff = SWAP @ np.linalg.inv(0.5 * (q + q.T)) @ SWAP  # energy form of C^-1
        ends = [slot.get(b) for b in e.bodies]
        for i, si in enumerate(ends):
            if si is None:
                continue
            for j, sj in enumerate(ends):
                if sj is None:
                    continue
                h[si : si + 6, sj : sj + 6] += stiff if i == j else -stiff
    try:
        inverse = np.linalg.inv(h)
    except np.linalg.LinAlgError:
        raise MechanismError("elements", "the elements do not hold every body (singular stiffness)") from None
    k = slot[mechanism.end_effector]
    block = inverse[k : k + 6, k : k + 6]
    return block @ SWAP


@dataclass(frozen=True, eq=False)
class FlexureSpaces:
    """Freedom and constraint spaces of a flexure mechanism's end effector.

    Attributes
    ----------
    name : str
    eigenvalues : ndarray, shape (6,)
        Relative compliances (eigenvalues of ``Q`` in normalised coordinates
        over the largest), decreasing.
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
        :func:`compliance_matrix` (SI, about the global origin).
    length : float
        The characteristic length ``L`` used (document unit).
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
    warnings: tuple[str, ...] = ()
    _freedom_n: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    _constraint_n: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    _norm: Normalisation = field(default=None, repr=False)  # type: ignore[assignment]

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        s = self.length
        return {
            "name": self.name,
            "kind": "flexure",
            "eigenvalues": _plain(self.eigenvalues),
            "largest_eigenvalue_per_newton": self.largest,
            "threshold": self.threshold,
            "gap": list(self.gap),
            "dof": self.dof,
            "pattern": self.pattern,
            "freedoms": {
                "translations": _plain(self.freedom_translations),
                "rotations": [_axis_dict(a, s) for a in self.freedom_rotations],
                "twists": _plain(self.freedom_twists, s),
            },
            "constraints": {
                "couples": _plain(self.constraint_couples),
                "forces": [_axis_dict(a, s) for a in self.constraint_forces],
                "wrenches": _plain(self.constraint_wrenches, s),
            },
            "compliance_si": self.compliance.tolist(),
            "characteristic_length": self.length,
            "length_unit": self.length_unit,
            "warnings": list(self.warnings),
        }


def _normalised_q(mechanism: FlexureMechanism, c: np.ndarray) -> tuple[np.ndarray, Normalisation]:
    """``Q = SWAP C`` in normalised coordinates (document length unit), symmetrised, from ``C`` (SI)."""
    norm = mechanism.normalisation()
    metres = mechanism.metres
    # C maps SI wrenches to SI twists; n(x) = [x1; (x2 - c x x1) / L] with c, L in metres.
    n = np.eye(6)
    n[3:, :3] = -_skew(norm.centre * metres) / (norm.length * metres)
    n[3:, 3:] /= norm.length * metres
    q = SWAP @ n @ c @ np.linalg.inv(n)
    return 0.5 * (q + q.T), norm


def _skew(v: np.ndarray) -> np.ndarray:
    x, y, z = v
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def flexure_spaces(mechanism: FlexureMechanism, threshold: float | None = None, *, tol: Tolerance = DEFAULT_TOLERANCE) -> FlexureSpaces:
    """Freedom and constraint spaces from the eigen-decomposition of the compliance.

    Parameters
    ----------
    mechanism : FlexureMechanism
    threshold : float, optional
        Relative compliance above which a direction is a freedom (default: the
        document's ``threshold``, else :data:`DEFAULT_THRESHOLD`).
    tol : Tolerance
        Used for the canonical forms of the spaces.

    Returns
    -------
    FlexureSpaces
    """
    if threshold is None:
        threshold = mechanism.threshold if mechanism.threshold is not None else DEFAULT_THRESHOLD
    if not (0.0 < threshold < 1.0):
        raise ValueError(f"threshold must lie between 0 and 1, got {threshold!r}")
    compliance = compliance_matrix(mechanism)
    q, norm = _normalised_q(mechanism, compliance)
    values, vectors = np.linalg.eigh(q)
    order = np.argsort(values)[::-1]
    values, vectors = values[order], vectors[:, order]
    largest = float(values[0])
    rel = values / largest
    free = rel > threshold
    dof = int(np.count_nonzero(free))
    freedom_n = vectors[SWAP_ROWS][:, free]
    constraint_n = vectors[:, ~free]
    reference = _reference(mechanism, norm)
    ft, fr, frows = screw_system_in_frame(freedom_n, norm, reference, ("rotation", "helical"), tol)
    cc, cf, crows = screw_system_in_frame(constraint_n, norm, reference, ("force", "wrench"), tol)
    rot = free_vector_subspace(freedom_n, tol, coefficients=False).rank
    above = float(rel[dof - 1]) if dof else 1.0
    below = float(rel[dof]) if dof < 6 else 0.0
    warnings = []
    if below > 0 and above / max(below, 1e-300) < 10.0:
        warnings.append(
            f"the threshold {threshold:g} does not sit in a clear gap: the relative compliances either side are "
            f"{above:.3g} and {below:.3g} (less than a factor 10 apart); the split into freedoms and constraints is uncertain"
        )
    return FlexureSpaces(
        name=mechanism.name,
        eigenvalues=rel,
        largest=largest,
        threshold=float(threshold),
        dof=dof,
        pattern=pattern_of(dof - rot, rot),
        freedom_translations=ft,
        freedom_rotations=fr,
        freedom_twists=frows,
        constraint_couples=cc,
        constraint_forces=cf,
        constraint_wrenches=crows,
        gap=(above, below),
        compliance=compliance,
        length=norm.length,
        length_unit=mechanism.length_unit,
        warnings=tuple(warnings),
        _freedom_n=freedom_n,
        _constraint_n=constraint_n,
        _norm=norm,
    )


def _select(mechanism: FlexureMechanism, names: Sequence[str] | None) -> list[ForceLine]:
    by_name = {a.name: a for a in mechanism.actuators}
    if names is None:
        return [a for a in mechanism.actuators if a.actuated]
    out = []
    for n in names:
        if n not in by_name:
            raise MechanismError("actuators", f"unknown actuator {n!r}; expected one of: {', '.join(by_name) or '(none)'}")
        out.append(by_name[n])
    return out


def check_force_lines(
    mechanism: FlexureMechanism,
    names: Sequence[str] | None = None,
    *,
    lines: Sequence[ForceLine] = (),
    threshold: float | None = None,
    tol: Tolerance = DEFAULT_TOLERANCE,
) -> ActuationCheck:
    """Check a set of linear actuators (force lines) on a flexure mechanism.

    Parameters
    ----------
    mechanism : FlexureMechanism
    names : sequence of str, optional
        Actuators of the document (default: those marked ``actuated: true``).
    lines : sequence of ForceLine
        Further force lines given in code (global frame, document unit).
    threshold : float, optional
        See :func:`flexure_spaces`.

    Returns
    -------
    ActuationCheck
        ``kind`` ``"flexure"``; the freedom space plays the part of the end
        effector's twist system and the constraint space that of its
        constraint wrenches.
    """
    spaces = flexure_spaces(mechanism, threshold, tol=tol)
    chosen = _select(mechanism, names) + list(lines)
    norm = spaces._norm
    entries = [(a.name, "F", None, _unit(norm.from_world(a.wrench())[:, 0]), "") for a in chosen]
    warnings = list(spaces.warnings)
    if not chosen:
        warnings.append("no actuator is chosen (mark actuators with `actuated: true`, or name them)")
    reference = _reference(mechanism, norm)
    return _build_check(
        mechanism.name,
        "flexure",
        entries,
        [_rate(e[3], norm) for e in entries],
        spaces._freedom_n,
        spaces._constraint_n,
        norm,
        reference,
        actuation_tolerance(spaces, tol),
        warnings,
        mechanism.length_unit,
    )


def actuation_tolerance(spaces: "FlexureSpaces", tol: Tolerance = DEFAULT_TOLERANCE) -> Tolerance:
    """The rank policy of a flexure's actuation check, from the gap between its eigenvalue clusters.

    The freedom and constraint spaces of a real flexure (finite stiffness in
    every direction) are those of an ideal one (infinitely compliant and
    infinitely stiff directions) only up to relative amounts of the order of
    ``eps``, the ratio of the relative compliances either side of the
    threshold (the three-rod flexure's constraint forces meet ``0.6 eps L``
    away from the point where the rod axes meet).  Rank decisions on those
    spaces therefore count relative singular values up to ``eps`` as zero
    (the same for every threshold inside the gap), bounded to
    ``[tol.rank, 0.1]``, and warn below ten times that.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> t = actuation_tolerance(SimpleNamespace(gap=(0.8, 0.0008)))
    >>> round(t.rank, 6), round(t.near_singular, 6)
    (0.001, 0.01)
    """
    above, below = spaces.gap
    eps = below / above if above > 0 else 1.0
    rank = min(max(eps, tol.rank), 0.1)
    return Tolerance(rank=rank, near_singular=min(10.0 * rank, 0.5), inexact=min(tol.inexact, rank))


def _reference(mechanism: FlexureMechanism, norm: Normalisation) -> np.ndarray:
    """Normalised centroid of the points where elements meet the end effector."""
    ee = mechanism.end_effector
    pts = [e.end if e.bodies[1] == ee else np.asarray(e.start) for e in mechanism.elements if ee in e.bodies]
    return norm.point_from_world(np.mean(pts, axis=0))


def _unit(w: np.ndarray) -> np.ndarray:
    return w / np.linalg.norm(w)


def _rate(w: np.ndarray, norm: Normalisation) -> float:
    """``a o $`` of a force line's input: the unit wrench's force part length (input = speed along the line)."""
    return float(np.linalg.norm(w[:3]))


def line_set_type(lines: Sequence[ForceLine], *, tol: Tolerance = DEFAULT_TOLERANCE) -> str:
    """Classify a set of force lines: ``parallel``, ``concurrent``, ``coplanar`` or ``general``.

    Decided by the rank policy in coordinates centred on the lines' points
    and scaled by their spread (so the answer does not depend on units or
    placement).

    Examples
    --------
    >>> z = ForceLine("a", (0, 0, 0), (0, 0, 1))
    >>> line_set_type([z, ForceLine("b", (1, 0, 0), (0, 0, 1))])
    'parallel'
    >>> line_set_type([ForceLine("a", (1, 0, 0), (-1, 0, 1)), ForceLine("b", (0, 1, 0), (0, -1, 1)),
    ...                ForceLine("c", (-1, 0, 0), (1, 0, 1))])
    'concurrent'
    """
    if len(lines) < 2:
        return "single"
    pts = np.array([a.point for a in lines])
    dirs = np.array([a.direction for a in lines])
    centre, length = characteristic_scale(pts)
    p = (pts - centre) / length

    def rank(m: np.ndarray) -> int:
        return decide_rank(np.linalg.svd(m, compute_uv=False), tol).rank

    if rank(dirs.T) == 1:
        return "parallel"
    # Concurrent: one point x with (p_i - x) x d_i = 0 for all i, i.e. [d_i]x x = d_i x p_i (rank test).
    a = np.vstack([_skew(d) for d in dirs])
    b = np.concatenate([np.cross(d, q) for d, q in zip(dirs, p)])
    if rank(a) == rank(np.column_stack([a, b])):
        return "concurrent"
    # Coplanar: a plane n.x = delta holding every point and direction.
    m = np.vstack([np.column_stack([p, -np.ones(len(p))]), np.column_stack([dirs, np.zeros(len(dirs))])])
    if rank(m) < 4:
        return "coplanar"
    return "general"


def enumerate_force_lines(mechanism: FlexureMechanism, k: int | None = None, *, threshold: float | None = None, tol: Tolerance = DEFAULT_TOLERANCE) -> Enumeration:
    """Check every set of ``k`` candidate actuators (default: the DOF of the freedom space).

    Combinations are grouped by :func:`line_set_type` and ranked as in
    :func:`mobility.actuation.actuation.enumerate_actuations`.
    """
    spaces = flexure_spaces(mechanism, threshold, tol=tol)
    k = spaces.dof if k is None else int(k)
    if k < 0:
        raise ValueError("k must be non-negative")
    cands = list(mechanism.actuators)
    if math.comb(len(cands), k) > MAX_COMBINATIONS:
        raise ValueError(f"{math.comb(len(cands), k)} combinations to try (more than {MAX_COMBINATIONS}); choose a smaller k")
    norm = spaces._norm
    atol = actuation_tolerance(spaces, tol)
    wrench = {a.name: _unit(norm.from_world(a.wrench())[:, 0]) for a in cands}
    found = []
    for combo in itertools.combinations(cands, k):
        ws = [wrench[a.name] for a in combo]
        a = _assess(ws, [_rate(w, norm) for w in ws], spaces._freedom_n, spaces._constraint_n, atol)
        found.append(_combine(tuple(x.name for x in combo), line_set_type(combo, tol=atol), [a]))
    ranked, groups = _rank_combinations(found)
    warnings = list(spaces.warnings)
    if not cands:
        warnings.append("the document lists no candidate actuators")
    if k != spaces.dof:
        warnings.append(f"{k} inputs per combination for {spaces.dof} DOF: none can be valid")
    return Enumeration(mechanism.name, "flexure", spaces.dof, spaces.pattern, "any", k, ranked, groups, ("given pose",), tuple(warnings))
