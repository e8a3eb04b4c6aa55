"""Read URDF files: links and joints at the zero pose.

Each joint's ``<origin>`` places the child frame in the parent's; its ``<axis>`` (default ``1 0 0``) is in the child
frame.  How elements map, which numbers are read (as MuJoCo's URDF compiler reads them) and closing loops:
``docs/robot-files.md``.  The standard library's XML parser suffices (a URDF library would bring meshes and their
dependencies); geometry is not read.

Examples
--------
>>> from mobility.io.robot_tree import build_mechanism
>>> import tempfile, os
>>> text = '''<robot name="arm">
...   <link name="base"/> <link name="upper"/>
...   <joint name="shoulder" type="revolute">
...     <parent link="base"/> <child link="upper"/>
...     <origin xyz="0 0 1" rpy="1.5707963267948966 0 0"/> <axis xyz="0 0 1"/>
...   </joint>
... </robot>'''
>>> with tempfile.NamedTemporaryFile("w", suffix=".urdf", delete=False) as f:
...     _ = f.write(text)
>>> j = build_mechanism(read_urdf(f.name)).mechanism.joints[0]
>>> j.type, [round(x, 12) + 0.0 for x in j.axis], j.point
('R', [0.0, -1.0, 0.0], (0.0, 0.0, 1.0))
>>> os.unlink(f.name)
"""

from __future__ import annotations

import math
import re
import sys
import xml.etree.ElementTree as ET
from collections import deque
from pathlib import Path

import numpy as np

from ..core.transforms import Transform, rotation_from_rpy
from ..errors import clipped, did_you_mean, one_line
from .files import file_name
from .precision import DigitCounter
from .robot_tree import Body, RobotTree, TreeCoupling, TreeJoint, Unsupported, at_line, rotation_tuple, vector_tuple
from .xml_source import XmlDocument, read_xml, require_no_underflow

__all__ = ["read_urdf", "URDF_JOINT_KINDS"]

URDF_JOINT_KINDS = {"revolute": "hinge", "continuous": "hinge", "prismatic": "slide", "planar": "planar", "floating": "free", "fixed": None}
"""URDF joint types and the tree joint kind each becomes (``fixed``: none, the links merge)."""

_JOINT_ELEMENTS = ("parent", "child", "origin", "axis", "limit", "dynamics", "mimic", "calibration", "safety_controller")
"""Elements of a ``<joint>`` that it holds at most once (MuJoCo refuses a repeated one)."""

_NUMBER = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
"""A plain ASCII decimal number, as ``strtod`` reads it in MuJoCo (no ``_``, no digits of other scripts)."""
_XML_SPACE = re.compile(r"[ \t\r\n]+")


def read_urdf(path: str | Path) -> RobotTree:
    """Read a URDF file into a :class:`~mobility.io.robot_tree.RobotTree` at the zero pose.

    Raises
    ------
    MechanismFileError
        On malformed XML, a xacro file, a missing or unknown link, a link with
        two parents, no root or several, bad numbers, or an unknown joint
        type; the message names the line.
    """
    return _UrdfReader(read_xml(file_name(path, "read_urdf"))).tree()


def _xacro_element(root: ET.Element) -> ET.Element | None:
    """The first element of the xacro language (``xacro:`` or any prefix declared for xacro's namespace), if any.

    Examples
    --------
    >>> from mobility.io.xml_source import parse_xml
    >>> tree = parse_xml('<robot xmlns:x="http://www.ros.org/wiki/xacro"><link name="a"/><x:macro name="m"/></robot>').root
    >>> _xacro_element(tree).tag, _xacro_element(parse_xml('<robot><link name="a"/></robot>').root)
    ('x:macro', None)
    """
    prefixes = {"xacro"}
    for el in root.iter():  # the parser keeps prefixes in the tags and declarations as attributes
        prefixes.update(k.partition(":")[2] for k, v in el.attrib.items() if k.startswith("xmlns:") and "xacro" in v.lower())
    return next((el for el in root.iter() if el.tag.partition(":")[0] in prefixes and ":" in el.tag), None)


class _UrdfReader:
    def __init__(self, doc: XmlDocument) -> None:
        self.doc = doc
        self.digits = DigitCounter()  # the numbers that place the joints, as written

    def tree(self) -> RobotTree:
        root = self.doc.root
        macro = _xacro_element(root)
        if macro is not None:
            raise self.doc.fail(macro, macro.tag, "a xacro file; expected a URDF: expand it first (xacro robot.urdf.xacro > robot.urdf)")
        if root.tag != "robot":
            raise self.doc.fail(root, root.tag, "not a URDF file; expected the root element <robot>")
        links = self.links(root)
        joints = self.joints(root, links)
        parent_joint: dict[str, dict] = {}
        for j in joints:
            if j["child"] in parent_joint:
                first = parent_joint[j["child"]]["name"]
                raise self.doc.fail(j["element"], f"joint[{clipped(j['name'])}]/child", f"link {clipped(j['child'])!r} already has the parent joint {clipped(first)!r}; expected a tree (close loops with --close or a closures file)")
            parent_joint[j["child"]] = j
        roots = [name for name in links if name not in parent_joint]
        if len(roots) != 1:
            what = "no root link (the joints form a cycle)" if not roots else f"several root links ({', '.join(clipped(r) for r in roots[:6])})"
            raise self.doc.fail(root, "robot", f"{what}; expected one link that is no joint's child")
        order, poses = self.poses(roots[0], joints)
        unreached = [name for name in links if name not in poses]
        if unreached:
            raise self.doc.fail(links[unreached[0]], f"link[{clipped(unreached[0])}]", "not reached from the root link: the joints form a cycle; expected a tree")
        bodies = tuple(Body(name, parent_joint[name]["parent"] if name in parent_joint else None, vector_tuple(poses[name].translation),
                            rotation_tuple(poses[name].rotation), self.doc.line(links[name])) for name in order)
        tree_joints: list[TreeJoint] = []
        unsupported: list[Unsupported] = []
        notes: list[str] = []
        actuated = self.transmissions(root, {j["name"]: j["type"] for j in joints}, unsupported, notes)
        couplings: list[TreeCoupling] = []
        for j in joints:
            if j["mimic"] is not None:  # q_follower = multiplier q_leader + offset: the rates, q'_f - multiplier q'_l = 0
                mimic = j["element"].find("mimic")
                key = f"joint[{clipped(j['name'])}]/mimic"
                multiplier = self.number(mimic, "multiplier", f"{key}/@multiplier", 1.0)
                self.number(mimic, "offset", f"{key}/@offset", 0.0)  # a position offset: no part in the rates, but a number
                if multiplier == 0.0:
                    raise self.doc.fail(mimic, f"{key}/@multiplier", f"expected a non-zero number: multiplier 0 holds joint {clipped(j['name'])!r} still, which a coupling of two joints does not express")
                couplings.append(TreeCoupling(key, (j["name"], j["mimic"]), (1.0, -multiplier), self.doc.line(mimic)))
            kind = URDF_JOINT_KINDS[j["type"]]
            if kind is None:
                continue
            frame = poses[j["child"]]
            axis = None if kind == "free" else vector_tuple(frame.apply_vector(j["axis"]))
            tree_joints.append(TreeJoint(j["name"], kind, j["child"], vector_tuple(frame.translation), axis, j["name"] in actuated, self.doc.line(j["element"])))
        name = root.get("name") or one_line(Path(self.doc.file).stem)  # a file name may hold a line break; a name may not
        return RobotTree(name, self.doc.file, "URDF", bodies, tuple(tree_joints), unsupported=tuple(unsupported), notes=tuple(notes),
                         rounding=self.digits.rounding(), couplings=tuple(couplings))

    def links(self, root: ET.Element) -> dict[str, ET.Element]:
        links: dict[str, ET.Element] = {}
        for el in root.findall("link"):
            name = el.get("name")
            if not name:
                raise self.doc.fail(el, "link", "missing attribute name; expected <link name=\"...\">")
            if name in links:
                raise self.doc.fail(el, f"link[{clipped(name)}]", f"duplicate link name (first on line {self.doc.line(links[name])})")
            links[name] = el
        if not links:
            raise self.doc.fail(root, "robot", "no <link>; expected links joined by joints")
        return links

    def joints(self, root: ET.Element, links: dict[str, ET.Element]) -> list[dict]:
        """Every ``<joint>``, its name unique, a ``<mimic>`` naming a joint of the robot."""
        joints: list[dict] = []
        first: dict[str, ET.Element] = {}
        for el in root.findall("joint"):
            j = self.joint(el, links)
            if j["name"] in first:
                raise self.doc.fail(el, f"joint[{clipped(j['name'])}]", f"duplicate joint name (first on line {self.doc.line(first[j['name']])})")
            first[j["name"]] = el
            joints.append(j)
        for j in joints:
            if j["mimic"] is not None and j["mimic"] not in first:
                raise self.doc.fail(j["element"].find("mimic"), f"joint[{clipped(j['name'])}]/mimic", f"unknown joint {clipped(j['mimic'])!r}; expected a <joint> of this robot")
        return joints

    def joint(self, el: ET.Element, links: dict[str, ET.Element]) -> dict:
        name = el.get("name")
        if not name:
            raise self.doc.fail(el, "joint", "missing attribute name; expected <joint name=\"...\" type=\"...\">")
        key = f"joint[{clipped(name)}]"
        self.require_once(el, key)
        jtype = el.get("type")
        if jtype is None:
            raise self.doc.fail(el, f"{key}/@type", f"missing attribute type; expected one of {', '.join(URDF_JOINT_KINDS)}")
        if jtype not in URDF_JOINT_KINDS:
            raise self.doc.fail(el, f"{key}/@type", f"unknown joint type {clipped(jtype)!r}; expected one of {', '.join(URDF_JOINT_KINDS)}")
        ends = {}
        for end in ("parent", "child"):
            sub = el.find(end)
            link = sub.get("link") if sub is not None else None
            if not link:
                raise self.doc.fail(sub if sub is not None else el, f"{key}/{end}", f"missing; expected <{end} link=\"...\">")
            if link not in links:
                raise self.doc.fail(sub, f"{key}/{end}", f"unknown link {clipped(link)!r}{did_you_mean(link, links)}; expected a <link> of this robot")
            ends[end] = link
        if ends["parent"] == ends["child"]:
            raise self.doc.fail(el, key, f"parent and child are the same link {clipped(ends['parent'])!r}")
        origin = el.find("origin")
        xyz = self.numbers(origin, "xyz", f"{key}/origin/@xyz", (0.0, 0.0, 0.0))
        rpy = self.numbers(origin, "rpy", f"{key}/origin/@rpy", (0.0, 0.0, 0.0))
        axis = self.numbers(el.find("axis"), "xyz", f"{key}/axis/@xyz", (1.0, 0.0, 0.0))
        for part, attribute, kind in ((origin, "xyz", "length"), (origin, "rpy", "angle"), (el.find("axis"), "xyz", "unit")):
            self.digits.add(part.get(attribute) if part is not None else None, kind)
        if URDF_JOINT_KINDS[jtype] not in (None, "free") and math.hypot(*axis) == 0.0:
            raise self.doc.fail(el.find("axis"), f"{key}/axis/@xyz", "expected a non-zero direction, got 0 0 0")
        if 0.0 < max(abs(a) for a in axis) < sys.float_info.min:  # subnormal: read with fewer digits than a double holds
            axis_element = el.find("axis")
            assert axis_element is not None  # the default axis is not subnormal: these numbers were read from the element
            raise self.doc.fail(axis_element, f"{key}/axis/@xyz", f"numbers below {sys.float_info.min:.3g}, the smallest normal double, do not keep "
                            f"their direction in double precision; expected larger numbers (only the direction counts), got {clipped(axis_element.get('xyz', ''))!r}")
        mimic = el.find("mimic")
        if mimic is not None and not mimic.get("joint"):
            raise self.doc.fail(mimic, f"{key}/mimic", "missing attribute joint; expected <mimic joint=\"...\">")
        return {"name": name, "type": jtype, "element": el, "parent": ends["parent"], "child": ends["child"],
                "origin": Transform(rotation_from_rpy(rpy), np.array(xyz)), "axis": np.array(axis) / (math.hypot(*axis) or 1.0),
                "mimic": mimic.get("joint") if mimic is not None else None}

    def require_once(self, el: ET.Element, key: str) -> None:
        """Refuse a second ``<parent>``, ``<axis>``... in the joint ``el``: its line, and the first one's."""
        first: dict[str, ET.Element] = {}
        for sub in el:
            if sub.tag in _JOINT_ELEMENTS:
                if sub.tag in first:
                    raise self.doc.fail(sub, f"{key}/{sub.tag}", f"a second <{sub.tag}> in the joint (the first on line {self.doc.line(first[sub.tag])}); expected one")
                first[sub.tag] = sub

    def number(self, el: ET.Element, attribute: str, key: str, default: float) -> float:
        """One finite number of an attribute (``default`` when it is absent)."""
        text = el.get(attribute)
        if text is None:
            return default
        word = text.strip(" \t\r\n")
        if not _NUMBER.fullmatch(word) or not math.isfinite(float(word)):
            raise self.doc.fail(el, key, f"expected a number, got {clipped(text)!r}")
        return float(word)

    def numbers(self, el: ET.Element | None, attribute: str, key: str, default: tuple[float, float, float]) -> tuple[float, float, float]:
        if el is None or el.get(attribute) is None:
            return default
        text = el.get(attribute, "")
        words = _XML_SPACE.split(text.strip(" \t\r\n"))
        values = [float(x) for x in words] if all(_NUMBER.fullmatch(x) for x in words) else []
        if len(values) != 3 or not all(math.isfinite(v) for v in values):
            raise self.doc.fail(el, key, f"expected 3 numbers, got {clipped(text)!r}")
        try:
            require_no_underflow(words, values)
        except ValueError as exc:
            raise self.doc.fail(el, key, f"{exc}, got {clipped(text)!r}") from None
        return (values[0], values[1], values[2])

    def poses(self, root_link: str, joints: list[dict]) -> tuple[list[str], dict[str, Transform]]:
        """Links from the root (parents first, file order among siblings) and their frames at the zero pose."""
        children: dict[str, list[dict]] = {}
        for j in joints:
            children.setdefault(j["parent"], []).append(j)
        poses = {root_link: Transform.identity()}
        order = [root_link]
        todo = deque([root_link])
        while todo:
            here = todo.popleft()
            for j in children.get(here, []):
                if j["child"] not in poses:
                    poses[j["child"]] = self.composed(poses[here], j)
                    order.append(j["child"])
                    todo.append(j["child"])
        return order, poses

    def composed(self, parent: Transform, j: dict) -> Transform:
        """The child frame of joint ``j``: ``parent`` composed with its origin, refused at the joint's line if it overflows."""
        with np.errstate(all="ignore"):  # an overflow is refused just below, in one line
            frame = parent.compose(j["origin"])
        if not (np.all(np.isfinite(frame.translation)) and np.all(np.isfinite(frame.rotation))):
            raise self.doc.fail(j["element"].find("origin") if j["element"].find("origin") is not None else j["element"], f"joint[{clipped(j['name'])}]/origin",
                            f"the frame of link {clipped(j['child'])!r}, the origins from the root composed, is not finite; expected origins whose sum stays finite")
        return frame

    def transmissions(self, root: ET.Element, joint_types: dict[str, str], unsupported: list[Unsupported], notes: list[str]) -> set[str]:
        """The joints driven by a ``<transmission>`` (one joint coordinate): a note for a ``fixed`` joint, unsupported on a
        ``planar`` or ``floating`` one (marking it actuated would make each of its freedoms an input)."""
        out: set[str] = set()
        for t in root.findall("transmission"):
            tname = t.get("name", "")
            for j in t.findall("joint"):
                name = j.get("name")
                key = f"transmission[{clipped(tname)}]/joint"
                if not name:
                    raise self.doc.fail(j, key, "missing attribute name; expected <joint name=\"...\">")
                if name not in joint_types:
                    raise self.doc.fail(j, key, f"unknown joint {clipped(name)!r}{did_you_mean(name, joint_types)}; expected a <joint> of this robot")
                jtype = joint_types[name]
                line = self.doc.line(j)
                if jtype == "fixed":
                    notes.append(f"transmission {clipped(tname)}{at_line(line)} drives the fixed joint {clipped(name)}, which cannot move: no input for it")
                elif jtype in ("planar", "floating"):
                    freedoms = "three (two translations and a rotation)" if jtype == "planar" else "six"
                    unsupported.append(Unsupported(key, f"a transmission on the {jtype} joint {clipped(name)} is not supported: a transmission is one input "
                                                   f"along one joint coordinate, and a {jtype} joint has {freedoms}, each of which an actuated joint of the "
                                                   "model would make an input; expected a revolute, continuous or prismatic joint", line))
                else:
                    out.add(name)
        return out

