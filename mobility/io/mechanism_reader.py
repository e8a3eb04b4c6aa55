"""The reader of a parsed mechanism document: :class:`MechanismReader`.

It turns the keys of ``docs/file-format.md`` (version 1 and its extensions) into :class:`~mobility.core.model.Mechanism`
fields, each checked once, every error at its file, line and key.

Examples
--------
>>> data, positions = parse_yaml("{name: s, ground: g, end_effector: s, joints: [{name: p, type: P, links: [g, s], axis: [0, 0, 2]}]}")
>>> read_mechanism(data, positions).joints[0].axis
(0.0, 0.0, 1.0)
"""

from __future__ import annotations

import re
import warnings
from collections import Counter
from typing import Any, Callable, Mapping

from ..core.expected import EXPECTED_KEYS
from ..core.model import JOINT_DOF, JOINT_FIELDS, JOINT_TYPES, WORLD, Coupling, Frame, Joint, Mechanism
from ..errors import MechanismError, clipped, did_you_mean, shown_argument
from .expected import read_expected
from .expressions import RESERVED_NAMES
from .limits import Limits, current_limits
from .reader import NAME_RE, DocumentReader, describe_value, parse_key, shown_value
from .yaml_source import KeyPath, Positions, format_key, parse_yaml  # parse_yaml: the examples'

__all__ = ["MechanismReader", "read_mechanism", "is_flexure_document", "TOP_LEVEL_KEYS", "JOINT_KEYS"]

TOP_LEVEL_KEYS = ("name", "description", "ground", "end_effector", "units", "frames", "joints", "expected", "parameters", "limbs", "couplings")
COUPLING_KEYS = ("joints", "coefficients")
JOINT_KEYS = ("name", "type", "links", "frame", "axis", "point", "pitch", "axes", "normal", "actuated")
LIMB_KEYS = ("copies", "index", "frame", "joints")
_TYPE_NAMES = {name: letter for letter, name in JOINT_TYPES.items()}
_SUBST_RE = re.compile(r"\{([^{}]*)\}")
MOST_LINKS_NAMED_ONCE = 64
"""Most links named by one joint only for which a file is searched for a misspelt link name (more: a generated file)."""
_FIELD_WORDS = {"axis": "direction", "point": "point", "pitch": "pitch", "axes": "two directions", "normal": "plane normal"}
_WRITTEN_AS = {"axis": "axis: [x, y, z]", "axes": "axes: [[x, y, z], [x, y, z]]", "normal": "normal: [x, y, z]"}
"""How a joint's direction is written, in the message of a field its type does not take."""


def is_flexure_document(data: Any) -> bool:
    """True when parsed YAML ``data`` is a flexure document (it has ``elements``), which :mod:`mobility.flexure` reads, not this loader.

    Examples
    --------
    >>> is_flexure_document({"name": "three rods", "elements": []}), is_flexure_document({"joints": []})
    (True, False)
    """
    return isinstance(data, dict) and "elements" in data


def read_mechanism(data: Any, positions: Positions, file: str = "<string>", *, limits: Limits | None = None) -> Mechanism:
    """The mechanism of an already parsed document (``data, positions`` from :func:`~mobility.io.yaml_source.parse_yaml`), as ``mobility check`` reads it.

    Examples
    --------
    >>> data, positions = parse_yaml("{name: s, ground: g, end_effector: s, joints: [{name: p, type: P, links: [g, s], axis: [1, 0, 0]}]}")
    >>> read_mechanism(data, positions).joints[0].type
    'P'
    """
    return MechanismReader(file, positions, current_limits(limits)).mechanism(data)


class MechanismReader(DocumentReader):
    """Turns a parsed mechanism document into a Mechanism, translating every error to file:line: key."""

    def mechanism(self, data: Any) -> Mechanism:
        if is_flexure_document(data):
            raise self.fail(("elements",), "a flexure document, not a mechanism: read it with mobility.load_flexure (on the command line: mobility actuation)")
        doc = self.document(data, "a mechanism", TOP_LEVEL_KEYS, ("name", "ground", "end_effector", ("joints", "limbs")))
        name, description = self.name_and_description(doc)
        length_unit = self.units(doc.get("units"))
        self.parameters(doc.get("parameters"))
        frames = self.frames(doc.get("frames"))
        joints, sources = self.joints(doc.get("joints", []), ("joints",), {}, None)
        limb_frames, limb_joints, limb_sources = self.limbs(doc.get("limbs"), len(joints), len(frames))
        frames += limb_frames
        self.require_frame_chains(frames)
        joints += limb_joints
        sources += limb_sources
        if not joints:
            raise self.fail(("joints",), "expected at least one joint")
        expected = read_expected(self, doc["expected"], tuple(EXPECTED_KEYS)) if "expected" in doc else None
        couplings = self.couplings(doc.get("couplings"))
        try:
            mechanism = Mechanism(name=name, ground=self.identifier(doc["ground"], ("ground",), "a link name"),
                                  end_effector=self.identifier(doc["end_effector"], ("end_effector",), "a link name"), joints=tuple(joints),
                                  frames=tuple(frames), description=description, length_unit=length_unit, expected=expected, source=self.file,
                                  written_at={j.name: (format_key(path), self.pos.line(path)) for j, path in zip(joints, sources)}, couplings=couplings)
        except MechanismError as exc:
            raise self.fail(self.source_path(exc.key, sources), exc.message) from None
        for note in dict.fromkeys(self.link_notes(mechanism, sources) + self.angle_notes()):  # a limb's copies: each note once
            warnings.warn(note, UserWarning, stacklevel=2)
        return mechanism

    def link_notes(self, mechanism: Mechanism, sources: list[KeyPath]) -> list[str]:
        """Warnings on link names that look misspelt (``slidr`` beside ``slider``: another mechanism): a link only one joint
        names, close to a link named by more and not of its numbered family (``tip1``, ``tip2``).

        A file with more than :data:`MOST_LINKS_NAMED_ONCE` links named once is generated, and not searched.
        """
        uses = Counter(link for j in mechanism.joints for link in j.links)
        ends = (mechanism.ground, mechanism.end_effector)
        once = [link for link, n in uses.items() if n == 1 and link not in ends]
        if not once or len(once) > MOST_LINKS_NAMED_ONCE:
            return []
        family = {link: re.sub(r"\d+", "#", link) for link in uses}
        held = [link for link, n in uses.items() if n > 1 or link in ends]
        notes = []
        for j, path in zip(mechanism.joints, sources):
            for k, link in enumerate(j.links):
                if uses[link] != 1 or link in ends:
                    continue
                hint = did_you_mean(link, [other for other in held if family[other] != family[link]])
                if hint:
                    notes.append(str(self.fail(path + ("links", k), f"link {clipped(link)!r} is named by this joint only{hint}: "
                                                                     "a misspelt link name makes a link of its own, and another mechanism")))
        return notes

    def couplings(self, value: Any) -> tuple[Coupling, ...]:
        """The ``couplings`` list: each a record of joint names and as many numbers (expressions allowed)."""
        if value is None:
            return ()
        if not isinstance(value, list):
            raise self.fail(("couplings",), f"expected a list of couplings, got {describe_value(value)}")
        out = []
        for k, raw in enumerate(value):
            path: KeyPath = ("couplings", k)
            data = self.record(raw, path, "a coupling", COUPLING_KEYS, COUPLING_KEYS, described="a coupling with joints and coefficients")
            names, numbers = data["joints"], data["coefficients"]
            for key, items in (("joints", names), ("coefficients", numbers)):
                if not isinstance(items, list):
                    raise self.fail(path + (key,), f"expected a list, got {describe_value(items)}")
            joints = tuple(self.identifier(n, path + ("joints", i), "a joint name") for i, n in enumerate(names))
            coefficients = tuple(self.number(x, path + ("coefficients", i), self.names) for i, x in enumerate(numbers))
            try:
                out.append(Coupling(joints, coefficients))
            except MechanismError as exc:
                raise self.fail(path + parse_key(exc.key), exc.message) from None
        return tuple(out)

    def source_path(self, key: str, sources: list[KeyPath]) -> KeyPath:
        """Key path in the file of a model error key such as ``joints[4].name``."""
        path = parse_key(key)
        if len(path) >= 2 and path[0] == "joints" and isinstance(path[1], int) and path[1] < len(sources):
            return sources[path[1]] + path[2:]
        return path

    def joints(self, value: Any, path: KeyPath, names: Mapping[str, float], default_frame: str | None, subst: Callable[[str, KeyPath], str] | None = None) -> tuple[list[Joint], list[KeyPath]]:
        if not isinstance(value, list):
            raise self.fail(path, f"expected a list of joints, got {describe_value(value)}")
        if len(value) > self.limits.max_joints:
            raise self.fail(path, f"{len(value)} joints are more than the limit of {self.limits.max_joints} ({self.limits.hint('max_joints')})")
        out, sources = [], []
        for i, raw in enumerate(value):
            out.append(self.joint(raw, path + (i,), names, default_frame, subst))
            sources.append(path + (i,))
        return out, sources

    def joint(self, raw: Any, path: KeyPath, names: Mapping[str, float], default_frame: str | None, subst: Callable[[str, KeyPath], str] | None) -> Joint:
        data = self.record(raw, path, "a joint", JOINT_KEYS, ("name", "type", "links"), described="a joint with name, type, links and geometry")
        names = names or self.names  # a limb copy's names include the parameters
        text = subst or (lambda s, p: s)
        name = text(self.identifier(data["name"], path + ("name",), "a joint name"), path + ("name",))
        jtype = data["type"]
        if isinstance(jtype, str) and jtype.lower() in _TYPE_NAMES:
            jtype = _TYPE_NAMES[jtype.lower()]
        if not isinstance(jtype, str) or jtype not in JOINT_DOF:
            kinds = f"{', '.join(JOINT_DOF)} (or revolute, prismatic, helical, cylindrical, universal, spherical, planar)"
            if isinstance(jtype, str):
                raise self.fail(path + ("type",), f"unknown joint type {jtype!r}; expected one of {kinds}")
            raise self.fail(path + ("type",), f"expected a joint type, one of {kinds}; got {describe_value(jtype)}")
        links = data["links"]
        if not isinstance(links, list) or len(links) != 2:
            raise self.fail(path + ("links",), f"expected two link names [a, b], got {describe_value(links)}")
        links = tuple(text(self.identifier(x, path + ("links", k), "a link name"), path + ("links", k)) for k, x in enumerate(links))
        self.fields_of_type(data, jtype, path)
        fields: dict[str, Any] = {key: self.vector(data[key], path + (key,), names) for key in ("axis", "point", "normal") if key in data}
        if "pitch" in data:
            fields["pitch"] = self.number(data["pitch"], path + ("pitch",), names)
        if "axes" in data:
            axes = data["axes"]
            if not isinstance(axes, list) or len(axes) != 2:
                raise self.fail(path + ("axes",), f"expected two directions [a1, a2], got {describe_value(axes)}")
            fields["axes"] = tuple(self.vector(a, path + ("axes", k), names) for k, a in enumerate(axes))
        frame = self.identifier(data.get("frame", default_frame or WORLD), path + ("frame",), "a frame name")
        actuated = data.get("actuated", False)
        if not isinstance(actuated, bool):
            raise self.fail(path + ("actuated",), f"expected true or false, got {shown_value(actuated)}")
        try:
            return Joint(name, jtype, links, frame=text(frame, path + ("frame",)), actuated=actuated, **fields)
        except MechanismError as exc:
            raise self.fail(path + parse_key(exc.key), exc.message) from None

    def fields_of_type(self, data: Mapping[str, Any], jtype: str, path: KeyPath) -> None:
        """Refuse a geometry field that joint type ``jtype`` does not take, naming the types it belongs to and what this type takes.

        Checked first, so that ``axes: [0, 0, 1]`` on an R joint is not answered as a malformed pair of directions.

        Examples
        --------
        >>> from mobility.io.yaml_source import Positions
        >>> MechanismReader("j.yaml", Positions({}), None).fields_of_type({"axes": [0, 0, 1]}, "R", ("joints", 0))
        Traceback (most recent call last):
        ...
        mobility.errors.MechanismFileError: j.yaml: joints[0].axes: not a field of a joint of type R (it takes axis, point): axes holds the two directions of a joint of type U; write its direction as axis: [x, y, z]
        """
        need, optional = JOINT_FIELDS[jtype]
        for key in _FIELD_WORDS:
            if key not in data or key in need + optional:
                continue
            owners = [t for t, (n, o) in JOINT_FIELDS.items() if key in n + o]
            takes = ", ".join(need) + (f", and optionally {', '.join(optional)}" if optional else "")  # as the model says it of a joint built in code
            owner = f"holds the {_FIELD_WORDS[key]} of a joint of type {owners[0]}" if len(owners) == 1 else f"is a field of joints of type {', '.join(owners)}"
            direction = next((k for k in _WRITTEN_AS if k in need), None)
            hint = f"; write its {_FIELD_WORDS[direction]} as {_WRITTEN_AS[direction]}" if direction and key in _WRITTEN_AS else ""
            raise self.fail(path + (key,), f"not a field of a joint of type {jtype} (it takes {takes}): {key} {owner}{hint}")

    def limbs(self, value: Any, joints_before: int = 0, frames_before: int = 0) -> tuple[list[Frame], list[Joint], list[KeyPath]]:
        frames: list[Frame] = []
        joints: list[Joint] = []
        sources: list[KeyPath] = []
        if value is None:
            return frames, joints, sources
        if not isinstance(value, list):
            raise self.fail(("limbs",), f"expected a list of limb patterns, got {describe_value(value)}")
        patterns = self.limb_patterns(value, joints_before, frames_before)
        for k, (limb, copies, index) in enumerate(patterns):
            path: KeyPath = ("limbs", k)
            for i in range(copies):
                local = {index: float(i)}
                scope = {**self.names, **local}
                written: dict[str, str] = {}  # each {expression} of this copy, as text

                def subst(s: str, p: KeyPath, scope: dict[str, float] = scope, written: dict[str, str] = written) -> str:
                    if "{" not in s:
                        return s

                    def one(m: re.Match[str]) -> str:
                        text = written.get(m.group(1))
                        if text is None:
                            v = self.number(m.group(1), p, scope)
                            text = written[m.group(1)] = str(int(v)) if v == int(v) else repr(v)
                        return text

                    done = _SUBST_RE.sub(one, s)
                    if "{" in done or "}" in done:  # else every copy would get the same name, refused as a duplicate
                        raise self.fail(p, f"{shown_argument(s)}: an unbalanced brace; write each substituted expression in a pair, as 'P{{i+1}}'")
                    return done

                frame_name = None
                if "frame" in limb:
                    fdata = self.mapping(limb["frame"], path + ("frame",), "a frame")
                    frame_name = subst(self.identifier(fdata.get("name", f"limb{k}_{{{index}}}"), path + ("frame", "name"), "a frame name"), path + ("frame", "name"))
                    parent = fdata.get("parent")
                    fdata = {**fdata, **({"parent": subst(parent, path + ("frame", "parent"))} if isinstance(parent, str) else {})}
                    fdata.pop("name", None)
                    frames.append(self.frame(frame_name, fdata, path + ("frame",), scope))
                js, src = self.joints(limb["joints"], path + ("joints",), scope, frame_name, subst)
                joints += js
                sources += src
        return frames, joints, sources

    def limb_patterns(self, value: list[Any], joints_before: int, frames_before: int) -> list[tuple[Mapping[str, Any], int, str]]:
        """Each limb pattern with its copies and index variable, checked, and the copies, joints and frames they make counted."""
        out = []
        total, all_copies, frames = joints_before, 0, frames_before
        lim = self.limits
        for k, raw in enumerate(value):
            path: KeyPath = ("limbs", k)
            limb = self.record(raw, path, "a limb pattern", LIMB_KEYS, ("joints",), described="a limb pattern with copies and joints")
            copies = limb.get("copies")
            if isinstance(copies, bool) or not isinstance(copies, int) or copies < 1:
                raise self.fail(path + ("copies",), f"expected a positive integer, got {describe_value(copies)}")
            all_copies += copies
            if all_copies > lim.max_copies:
                raise self.fail(path + ("copies",), f"{all_copies} copies of limbs are more than the limit of {lim.max_copies} ({lim.hint('max_copies')})")
            index = limb.get("index", "i")
            if not isinstance(index, str) or not NAME_RE.match(index):
                raise self.fail(path + ("index",), f"expected a variable name, got {shown_value(index)}")
            if index in RESERVED_NAMES:
                raise self.fail(path + ("index",), f"{index!r} is a constant or a function of the expressions; choose another name for the index")
            if index in self.names:
                raise self.fail(path + ("index",), f"{index!r} is already a parameter; choose another name for the index")
            if not isinstance(limb["joints"], list):
                raise self.fail(path + ("joints",), f"expected a list of joints, got {describe_value(limb['joints'])}")
            total += copies * len(limb["joints"])
            if total > lim.max_joints:
                raise self.fail(path + ("copies",), f"the limbs make {total} joints in all, more than the limit of {lim.max_joints} ({lim.hint('max_joints')})")
            frames += copies if "frame" in limb else 0
            if frames > lim.max_frames:
                raise self.fail(path + ("copies",), f"the limbs make {frames} frames in all, more than the limit of {lim.max_frames} ({lim.hint('max_frames')})")
            out.append((limb, copies, index))
        return out
