"""Read flexure documents (YAML) into :class:`~mobility.flexure.model.FlexureMechanism` objects.

A flexure document (the format is in ``docs/actuation.md``) has the top-level
key ``elements`` (:func:`is_flexure_document`). It shares ``parameters``,
``frames`` and the angle unit with mechanism files, and gives bad input the
same one-line ``file:line: key: what was expected`` errors; its ``expected``
block holds keys of :data:`~mobility.io.expected.FLEXURE_EXPECTED_KEYS`.

Examples
--------
>>> text = '''
... name: one wire
... units: {length: mm, modulus: GPa}
... ground: base
... end_effector: stage
... materials: {steel: {E: 200, nu: 0.3}}
... elements:
...   - {name: w1, type: rod, bodies: [base, stage], axis: [0, 0, 1], length: 100, radius: 1, material: steel}
... '''
>>> m = loads_flexure(text)
>>> m.elements[0].material.E, m.length_unit
(200000000000.0, 'mm')
>>> loads_flexure(text.replace("radius: 1,", "radius: -1,"), file="wire.yaml")
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: wire.yaml:8: elements[0].radius: expected a positive number, got -1.0
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from ..errors import MechanismError, RequestError, name_list
from .model import LENGTH_UNITS, MODULUS_UNITS, FlexureMechanism, ForceLine, Material, Rod
from .compliance import compliance_matrix
from ..io.reader import DocumentReader, describe_value, parse_key, shown_value
from ..core.model import WORLD, Frame
from ..core.transforms import Transform
from ..io.expected import FLEXURE_EXPECTED_KEYS, read_expected
from ..io.files import file_name
from ..io.mechanism_reader import is_flexure_document
from ..io.yaml_source import KeyPath, Positions, parse_yaml, read_text

__all__ = ["load_flexure", "loads_flexure", "read_flexure", "is_flexure_document", "FLEXURE_KEYS", "ELEMENT_KEYS", "ACTUATOR_KEYS", "ELEMENT_TYPES"]

FLEXURE_KEYS = ("name", "description", "units", "parameters", "frames", "ground", "end_effector", "materials", "elements", "actuators", "threshold", "expected")
ELEMENT_KEYS = ("name", "type", "bodies", "frame", "point", "axis", "length", "radius", "material")
ACTUATOR_KEYS = ("name", "frame", "point", "direction", "actuated")
MATERIAL_KEYS = ("E", "nu")
ELEMENT_TYPES = ("rod",)
"""Flexure element types: ``rod`` (a slender rod of circular section, a wire flexure)."""


def load_flexure(path: str | Path) -> FlexureMechanism:
    """Load a flexure document.

    Raises
    ------
    MechanismFileError
        When the file cannot be read or breaks the format.
    """
    name = file_name(path, "load_flexure")  # never a descriptor of the caller's (an int)
    return loads_flexure(read_text(name), file=name)


def loads_flexure(text: str, file: str = "<string>") -> FlexureMechanism:
    """Load a flexure document from YAML text (see :func:`load_flexure`)."""
    if not isinstance(text, str):
        raise RequestError(caller="loads_flexure", expected="the text of a flexure document (str)", got=type(text).__name__)
    data, positions = parse_yaml(text, file)
    return read_flexure(data, positions, file)


def read_flexure(data: Any, positions: Positions, file: str = "<string>") -> FlexureMechanism:
    """The flexure mechanism of an already parsed document (``data, positions`` from :func:`~mobility.io.yaml_source.parse_yaml`)."""
    return _FlexureReader(file, positions).flexure_mechanism(data)


class _FlexureReader(DocumentReader):
    """The mechanism reader's helpers (numbers, vectors, frames, errors) for flexure documents."""

    def flexure_mechanism(self, data: Any) -> FlexureMechanism:
        doc = self.document(data, "a flexure document", FLEXURE_KEYS, ("name", "ground", "end_effector", "elements"))
        name, description = self.name_and_description(doc)
        length_unit, modulus = self.flexure_units(doc.get("units"))
        self.parameters(doc.get("parameters"))
        transforms = self.resolve_frames(self.frames(doc.get("frames")))
        materials = self.materials(doc.get("materials"), modulus)
        elements = self.elements(doc["elements"], transforms, materials, modulus)
        actuators = self.actuators(doc.get("actuators"), transforms)
        threshold = None
        if "threshold" in doc:
            threshold = self.number(doc["threshold"], ("threshold",))
            if not (0.0 < threshold < 1.0):
                raise self.fail(("threshold",), f"expected a relative compliance between 0 and 1, got {threshold!r}")
        expected = read_expected(self, doc["expected"], FLEXURE_EXPECTED_KEYS) if "expected" in doc else None
        ground = self.identifier(doc["ground"], ("ground",), "a body name")
        end_effector = self.identifier(doc["end_effector"], ("end_effector",), "a body name")
        try:
            mechanism = FlexureMechanism(name=name, ground=ground, end_effector=end_effector, elements=tuple(elements), actuators=tuple(actuators),
                                         description=description, length_unit=length_unit, threshold=threshold, expected=expected, source=self.file)
            compliance_matrix(mechanism)  # sizes or moduli beyond double precision: named here, with their line
            return mechanism
        except MechanismError as exc:
            raise self.fail(parse_key(exc.key), exc.message) from None

    def flexure_units(self, value: Any) -> tuple[str, float]:
        if value is None:
            return "m", 1.0
        units = self.mapping(value, ("units",), "units")
        self.require_known_keys(units, ("angle", "length", "modulus"), ("units",), "units")
        self.units({k: v for k, v in units.items() if k == "angle"})
        length = units.get("length", "m")
        if not isinstance(length, str) or length not in LENGTH_UNITS:
            raise self.fail(("units", "length"), f"expected one of {', '.join(LENGTH_UNITS)} (a flexure's compliance needs a real unit), got {shown_value(length)}")
        modulus = units.get("modulus", "Pa")
        if not isinstance(modulus, str) or modulus not in MODULUS_UNITS:
            raise self.fail(("units", "modulus"), f"expected one of {', '.join(MODULUS_UNITS)}, got {shown_value(modulus)}")
        return length, MODULUS_UNITS[modulus]

    def resolve_frames(self, frames: list[Frame]) -> dict[str, Transform]:
        by_name = {f.name: f for f in frames}
        out: dict[str, Transform] = {WORLD: Transform.identity()}

        def resolve(name: str, chain: tuple[str, ...]) -> Transform:
            if name in out:
                return out[name]
            if name in chain:
                raise self.fail(("frames", chain[0], "parent"), "cycle among frame parents: " + " -> ".join(chain + (name,)))
            f = by_name[name]
            if f.parent != WORLD and f.parent not in by_name:
                raise self.fail(("frames", name, "parent"), f"unknown frame {f.parent!r}; expected {WORLD!r} or one of: {name_list(by_name)}")
            out[name] = resolve(f.parent, chain + (name,)).compose(f.transform)
            return out[name]

        for f in frames:
            resolve(f.name, ())
        return out

    def frame_of(self, data: Mapping[str, Any], path: KeyPath, transforms: Mapping[str, Transform]) -> Transform:
        frame = data.get("frame", WORLD)
        if not isinstance(frame, str) or frame not in transforms:
            raise self.fail(path + ("frame",), f"unknown frame {shown_value(frame)}; expected {WORLD!r} or one of: {', '.join(k for k in transforms if k != WORLD) or '(none)'}")
        return transforms[frame]

    def material(self, raw: Any, path: KeyPath, modulus: float) -> Material:
        data = self.record(raw, path, "a material", MATERIAL_KEYS, MATERIAL_KEYS, described="a material with E and nu")
        e = self.number(data["E"], path + ("E",))
        nu = self.number(data["nu"], path + ("nu",))
        if math.isfinite(e) and not math.isfinite(e * modulus):  # finite as written, past the largest float once in pascals
            raise self.fail(path + ("E",), f"{e:g} (units.modulus) is {e:g} x {modulus:g} Pa, beyond the largest float ({sys.float_info.max:.3g} Pa); "
                                           "expected a Young's modulus that a float holds in pascals")
        try:
            return Material(str(path[-1]), e * modulus, nu)
        except MechanismError as exc:
            raise self.fail(path + (exc.key,), exc.message) from None

    def materials(self, value: Any, modulus: float) -> dict[str, Material]:
        if value is None:
            return {}
        data = self.mapping(value, ("materials",), "material names to {E, nu}")
        return {str(k): self.material(v, ("materials", k), modulus) for k, v in data.items()}

    def elements(self, value: Any, transforms: Mapping[str, Transform], materials: Mapping[str, Material], modulus: float) -> list[Rod]:
        if not isinstance(value, list) or not value:
            raise self.fail(("elements",), f"expected a non-empty list of flexure elements, got {describe_value(value)}")
        out = []
        for i, raw in enumerate(value):
            path: KeyPath = ("elements", i)
            required = ("name", "type", "bodies", "length", "radius", "material")
            data = self.record(raw, path, "a flexure element", ELEMENT_KEYS, required, described="a flexure element with name, type, bodies and geometry")
            if data["type"] not in ELEMENT_TYPES:
                raise self.fail(path + ("type",), f"unknown flexure element type {shown_value(data['type'])}; expected one of: {', '.join(ELEMENT_TYPES)}")
            bodies = data["bodies"]
            if not isinstance(bodies, list) or len(bodies) != 2:
                raise self.fail(path + ("bodies",), f"expected two body names [a, b], got {describe_value(bodies)}")
            bodies = [self.identifier(b, path + ("bodies", k), "a body name") for k, b in enumerate(bodies)]
            tf = self.frame_of(data, path, transforms)
            point = self.vector(data["point"], path + ("point",)) if "point" in data else (0.0, 0.0, 0.0)
            axis = self.vector(data["axis"], path + ("axis",)) if "axis" in data else (0.0, 0.0, 1.0)
            if not np.any(axis):
                raise self.fail(path + ("axis",), "expected a non-zero direction, got [0, 0, 0]")
            mat = data["material"]
            if isinstance(mat, str):
                if mat not in materials:
                    raise self.fail(path + ("material",), f"unknown material {mat!r}; expected one of: {', '.join(materials) or '(none: add a materials section)'} or an inline {{E, nu}}")
                material = materials[mat]
            else:
                material = self.material(mat, path + ("material",), modulus)
            name = self.identifier(data["name"], path + ("name",), "an element name")
            length, radius = self.number(data["length"], path + ("length",)), self.number(data["radius"], path + ("radius",))
            try:
                out.append(Rod(name, (bodies[0], bodies[1]), tuple(tf.apply_point(point)), tuple(tf.apply_vector(axis)), length, radius, material))
            except MechanismError as exc:
                raise self.fail(path + parse_key(exc.key), exc.message) from None
        return out

    def actuators(self, value: Any, transforms: Mapping[str, Transform]) -> list[ForceLine]:
        if value is None:
            return []
        if not isinstance(value, list):
            raise self.fail(("actuators",), f"expected a list of force lines, got {describe_value(value)}")
        out = []
        for i, raw in enumerate(value):
            path: KeyPath = ("actuators", i)
            data = self.record(raw, path, "a linear actuator", ACTUATOR_KEYS, ("name", "point", "direction"), described="a force line with name, point and direction")
            tf = self.frame_of(data, path, transforms)
            point = self.vector(data["point"], path + ("point",))
            direction = self.vector(data["direction"], path + ("direction",))
            if not np.any(direction):
                raise self.fail(path + ("direction",), "expected a non-zero direction, got [0, 0, 0]")
            actuated = data.get("actuated", False)
            if not isinstance(actuated, bool):
                raise self.fail(path + ("actuated",), f"expected true or false, got {shown_value(actuated)}")
            name = self.identifier(data["name"], path + ("name",), "an actuator name")
            try:
                out.append(ForceLine(name, tuple(tf.apply_point(point)), tuple(tf.apply_vector(direction)), actuated))
            except MechanismError as exc:
                raise self.fail(path + parse_key(exc.key), exc.message) from None
        return out
