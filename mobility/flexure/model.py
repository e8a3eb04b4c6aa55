"""Flexure mechanisms as descriptions: materials, rods, force lines and the mechanism.

Rigid bodies joined by slender rods (wire flexures) instead of joints; frozen,
validated descriptions, geometry in the global frame and the document's length
unit (:data:`LENGTH_UNITS`), moduli in pascals. Bad values raise
:class:`~mobility.errors.MechanismError` naming the key.

Examples
--------
>>> rod = Rod("w", ("g", "s"), start=(0, 0, 0), axis=(0, 0, 2), length=0.1, radius=0.001,
...           material=Material("steel", 200e9, 0.3))
>>> rod.axis, rod.end.tolist()
((0.0, 0.0, 1.0), [0.0, 0.0, 0.1])
>>> m = FlexureMechanism("one wire", "g", "s", (rod,), length_unit="mm")
>>> m.bodies, m.metres
(('g', 's'), 0.001)
>>> Rod("w", ("g", "s"), (0, 0, 0), (0, 0, 1), 0.1, 0.2, Material("steel", 200e9, 0.3))
Traceback (most recent call last):
...
mobility.errors.MechanismError: radius: a rod must be slender: radius 0.2 is not smaller than its length 0.1
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.joint_screws import Normalisation
from ..core.expected import Expected
from ..core.validation import require_ground_and_end_effector, require_instance, require_name, require_vector, require_graph_names, require_unique_names
from ..core.tolerance import characteristic_scale
from ..errors import MechanismError, name_list

__all__ = ["LENGTH_UNITS", "MODULUS_UNITS", "Material", "Rod", "ForceLine", "FlexureMechanism", "require_flexure"]

THINNEST_ROD = 1e-6
"""Smallest radius of a rod over its length: its bending compliance is then 1e12 times its axial one."""

LENGTH_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "in": 0.0254}
"""Length units a flexure document may use, in metres."""

MODULUS_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9, "N/mm^2": 1e6, "N/m^2": 1.0, "psi": 6894.757293168361}
"""Units of Young's modulus a flexure document may use, in pascals."""

Vector = tuple[float, float, float]


def _number(value: Any, key: str, expected: str = "a number") -> float:
    """A finite number, else a :class:`MechanismError` saying what was ``expected``."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise MechanismError(key, f"expected {expected}, got {value!r}") from None
    if not math.isfinite(x):
        raise MechanismError(key, f"expected {expected}, got {value!r}")
    return x


def _positive(value: Any, key: str) -> float:
    """A finite positive number, else a :class:`MechanismError`."""
    x = _number(value, key, "a positive number")
    if x <= 0.0:
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
        nu = _number(self.nu, "nu", "Poisson's ratio in (-1, 0.5)")
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
        require_name(self.name, "name", "a non-empty string")
        b = tuple(self.bodies) if isinstance(self.bodies, (list, tuple)) else ()
        if len(b) != 2 or not all(isinstance(x, str) and x for x in b):
            raise MechanismError("bodies", f"expected two body names, got {self.bodies!r}")
        for k, body in enumerate(b):
            require_name(body, f"bodies[{k}]", "a body name")
        if b[0] == b[1]:
            raise MechanismError("bodies", f"an element must join two different bodies, got {b[0]!r} twice")
        object.__setattr__(self, "bodies", b)
        object.__setattr__(self, "start", require_vector(self.start, "point"))
        object.__setattr__(self, "axis", require_vector(self.axis, "axis", direction=True))
        object.__setattr__(self, "length", _positive(self.length, "length"))
        object.__setattr__(self, "radius", _positive(self.radius, "radius"))
        if not isinstance(self.material, Material):
            raise MechanismError("material", f"expected a Material, got {self.material!r}")
        if self.radius >= self.length:
            raise MechanismError("radius", f"a rod must be slender: radius {self.radius:g} is not smaller than its length {self.length:g}")
        if self.radius < THINNEST_ROD * self.length:
            raise MechanismError("radius", f"radius {self.radius:g} is less than {THINNEST_ROD:g} of the rod's length {self.length:g}: "
                                 "its bending and axial compliances would differ by more than double precision can compare")

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
        require_name(self.name, "name", "a non-empty string")
        object.__setattr__(self, "point", require_vector(self.point, "point"))
        object.__setattr__(self, "direction", require_vector(self.direction, "direction", direction=True))
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
        Relative-compliance threshold (``None``: :data:`mobility.flexure.spaces.DEFAULT_THRESHOLD`).
    expected : Expected or None
        What ``mobility check`` compares the freedom space and the actuation
        verdict with (keys of :data:`mobility.io.expected.FLEXURE_EXPECTED_KEYS`).
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
    expected: Expected | None = None
    source: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "elements", tuple(self.elements))
        object.__setattr__(self, "actuators", tuple(self.actuators))
        require_graph_names(self, "body")
        if not self.elements:
            raise MechanismError("elements", "expected at least one flexure element")
        if self.length_unit not in LENGTH_UNITS:
            raise MechanismError("units.length", f"unknown length unit {self.length_unit!r}; expected one of: {', '.join(LENGTH_UNITS)}")
        require_unique_names(self.elements, "elements", "element")
        require_unique_names(self.actuators, "actuators", "actuator")
        bodies = self.bodies
        require_ground_and_end_effector(self, bodies, "body", "element")
        reached, size = {self.ground}, 0
        while size != len(reached):
            size = len(reached)
            reached |= {b for e in self.elements if reached & set(e.bodies) for b in e.bodies}
        missing = sorted(set(bodies) - reached)
        if missing:
            raise MechanismError("elements", f"bodies not connected to the ground {self.ground!r}: {name_list(missing)}")
        if self.threshold is not None:
            threshold = _number(self.threshold, "threshold", "a number between 0 and 1")
            if not 0.0 < threshold < 1.0:
                raise MechanismError("threshold", f"expected a number between 0 and 1, got {self.threshold!r}")
            object.__setattr__(self, "threshold", threshold)

    @property
    def bodies(self) -> tuple[str, ...]:
        """Body names in order of first appearance."""
        return tuple(dict.fromkeys(b for e in self.elements for b in e.bodies))

    @property
    def metres(self) -> float:
        """Metres per length unit of the document."""
        return LENGTH_UNITS[self.length_unit]

    def end_effector_centre(self) -> np.ndarray:
        """Centroid of the points where elements meet the end effector (global frame)."""
        ee = self.end_effector
        return np.mean([e.end if e.bodies[1] == ee else np.asarray(e.start) for e in self.elements if ee in e.bodies], axis=0)

    def normalisation(self) -> Normalisation:
        """Normalised coordinates: centroid and RMS radius of the element end points."""
        pts = np.array([p for e in self.elements for p in (e.start, e.end)], dtype=float)
        centre, length = characteristic_scale(pts, np.array([e.length for e in self.elements]))
        return Normalisation(centre, length)


def require_flexure(value: object, caller: str) -> FlexureMechanism:
    """``value`` when it is a :class:`FlexureMechanism`, else a :class:`~mobility.errors.RequestError` naming ``caller``.

    Examples
    --------
    >>> require_flexure("three_rod.yaml", "flexure_spaces")
    Traceback (most recent call last):
    mobility.errors.RequestError: flexure_spaces: expected a FlexureMechanism (from mobility.load_flexure or built in code), got str
    """
    return require_instance(value, FlexureMechanism, caller, "mobility.load_flexure")
