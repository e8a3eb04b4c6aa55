"""Read MuJoCo (MJCF) files as MuJoCo compiles them: bodies, joints and loop closures at ``qpos0``.

Rather than re-implement MuJoCo's compiler (defaults, frames, ``<include>``, ``<replicate>``...), MuJoCo (the
``mechanism-mobility[mujoco]`` extra) compiles the file, checked first (:mod:`mobility.io.mjcf_scan`), without what
kinematics ignores; the compiled model is read at ``qpos0`` (``mj_kinematics``).  How joints, equalities and actuators
map: ``docs/robot-files.md``.  MuJoCo's warnings become notes.
"""

from __future__ import annotations

import math
import os
import re
import warnings
from contextlib import contextmanager
from dataclasses import replace
from importlib import import_module
from pathlib import Path
from types import ModuleType
from typing import Any, Iterator

import numpy as np

from ..core.expected import independent_of
from ..core.model import Joint
from ..core.tolerance import DEFAULT_TOLERANCE, characteristic_scale
from ..core.validation import require_vector
from ..errors import MechanismError, MechanismFileError, MissingExtraError, clipped, counted, one_line
from .files import read_capped
from .mjcf_scan import MjcfScan, scan_mjcf
from .precision import mjcf_rounding
from .robot_actuators import BallActuator
from .robot_tree import (Body, Closure, RobotTree, TreeCoupling, TreeJoint, Unsupported, Weld, at_line, rotation_tuple, unique_name,
                         vector_tuple)
from .xml_source import parse_xml

__all__ = ["read_mjcf", "import_mujoco"]

_LINE = re.compile(r"\bline(?: number)?\s*=?\s*(\d+)", re.IGNORECASE)
_ELEMENT = re.compile(r"Element (?:name )?'([^']*)'")
_ELEMENT_LINE = re.compile(r"\s*Element (?:name )?'[^']*'(?:, id -?\d+)?, line (\d+)")
_PARSER_LINE = re.compile(r"Line number=(\d+)")
_PARSER_NOISE = re.compile(r"ErrorID=\d+ \(0x[0-9a-fA-F]+\) |Line number=\d+:? ?|Error=")
_PREFIX = re.compile(r"^(?:XML )?Error:\s*", re.IGNORECASE)
_FINITE = "expected positions and directions whose numbers stay finite (smaller numbers)"


def import_mujoco() -> ModuleType:
    """The ``mujoco`` module, or a :class:`~mobility.errors.MissingExtraError` saying which extra installs it."""
    try:
        return import_module("mujoco")
    except ImportError as exc:
        raise MissingExtraError("reading MJCF files", "mujoco", "mujoco", str(exc)) from None


def read_mjcf(path: str | Path) -> RobotTree:
    """Read an MJCF file into a :class:`~mobility.io.robot_tree.RobotTree` at ``qpos0``.

    Raises
    ------
    MechanismFileError
        When the file is not well-formed UTF-8 XML, has a ``<!DOCTYPE>``, is
        not MJCF, fails a check of :mod:`mobility.io.mjcf_scan`, or MuJoCo
        cannot compile it (naming the file and line MuJoCo gives).
    MissingExtraError
        When the ``mujoco`` package is not installed.
    """
    file = str(path)
    raw = read_capped(path)
    if not file.isascii() and _not_utf8(file):  # bytes no encoding decoded: MuJoCo takes a file name as UTF-8 text only
        raise MechanismFileError("", "the file name (or its folder's) is not UTF-8 text, which MuJoCo cannot open; rename it", file=file)
    doc = parse_xml(raw, file, mujoco=True)  # as MuJoCo's parser reads it: UTF-8, no DTD
    if doc.root.tag != "mujoco":
        raise doc.fail(doc.root, clipped(doc.root.tag), "not an MJCF file; expected the root element <mujoco>")
    folder = os.path.dirname(file) or "."
    scan = scan_mjcf(doc, folder, size=len(raw))  # includes found beside the file, as MuJoCo finds them for a path
    mujoco = import_mujoco()
    read, alias = _reader(mujoco, file, raw, scan)
    said: list[str] = []
    with _warnings_into(mujoco, said):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")  # MuJoCo's compiler warnings become notes
            spec = _mujoco_call(read, file, scan, alias)
            _kinematics_only(mujoco, spec)
            model = _mujoco_call(spec.compile, file, scan, alias)
            _require_kept(scan, model, file)
            data = mujoco.MjData(model)
            mujoco.mj_kinematics(model, data)
        tree = _MjcfTree(mujoco, spec, model, data, file).tree()  # its forward pass (the gaps) may warn too
    said += [str(w.message) for w in caught]
    notes = [f"MuJoCo warns: {clipped(' '.join(text.split()), 200)}" for text in dict.fromkeys(said) if text.strip()]
    rounding = mjcf_rounding([doc.root, *(parse_xml(read_capped(f), f, mujoco=True).root for f in scan.files)])  # the digits of the file's own numbers
    return replace(tree, notes=tree.notes + tuple(notes), files=scan.files, rounding=rounding)


def _reader(mujoco: ModuleType, file: str, raw: bytes, scan: MjcfScan) -> tuple[Any, str | None]:
    """How MuJoCo is to read the file so that it finds its includes beside it, and the name it is given under (``None``: its own).

    MuJoCo picks its XML reader by the extension, case-sensitively: a file not named ``.xml`` is given under an unused
    ``.xml`` name in the same folder, its text in memory (MuJoCo's ``include`` argument).
    """
    if file.endswith(".xml"):
        return (lambda: mujoco.MjSpec.from_file(file)), None
    taken = {os.path.basename(f) for f in scan.files} | {os.path.basename(file)}
    alias, k = f"{file}.xml", 2
    while os.path.basename(alias) in taken or os.path.lexists(alias):
        alias, k = f"{file}.{k}.xml", k + 1
    return (lambda: mujoco.MjSpec.from_file(alias, include={alias: raw})), alias


def _not_utf8(name: str) -> bool:
    """Whether ``name`` holds bytes that were not UTF-8 (Python keeps them as lone surrogates).

    Examples
    --------
    >>> _not_utf8("gelenk_\\u00e4.xml"), _not_utf8(b"lat\\xe4.xml".decode("utf-8", "surrogateescape"))
    (False, True)
    """
    return any("\ud800" <= char <= "\udfff" for char in name)  # surrogates: the only characters UTF-8 cannot encode


@contextmanager
def _warnings_into(mujoco: ModuleType, said: list[str]) -> Iterator[None]:
    """MuJoCo's warnings appended to ``said`` instead of printed (and written to ``MUJOCO_LOG.TXT``)."""
    before = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(lambda message: said.append(str(message)))
    try:
        yield
    finally:
        mujoco.set_mju_user_warning(before)


def _mujoco_call(call: Any, file: str, scan: MjcfScan, alias: str | None = None) -> Any:
    """Run a MuJoCo parse or compile step; its error becomes one line (see :func:`_mujoco_error`), the file named as given."""
    try:
        return call()
    except (ValueError, RuntimeError) as exc:  # MuJoCo's parse and compile errors
        text = str(exc).replace(alias, file) if alias else str(exc)
        raise _mujoco_error(text, file, scan) from None


def _mujoco_error(text: str, file: str, scan: MjcfScan) -> MechanismFileError:
    """MuJoCo's message on one line, with the file and line it names (:func:`_where`).

    Examples
    --------
    >>> str(_mujoco_error("XML Error: invalid keyword: 'hinj'\\nElement 'joint', line 4\\n", "m.xml", MjcfScan()))
    "m.xml:4: joint: MuJoCo cannot compile it: invalid keyword: 'hinj'; expected a model MuJoCo compiles"
    >>> str(_mujoco_error("Error: axis too small in joint\\nElement name '', id 0, line 0", "m.xml", MjcfScan()))
    'm.xml: MuJoCo cannot compile it: axis too small in joint; expected a model MuJoCo compiles'
    """
    flat = " ".join(text.split())
    element = _ELEMENT.search(flat)
    where = _ELEMENT_LINE.search(flat) or _PARSER_LINE.search(flat)
    line = int(where.group(1)) if where else 0
    reason = _ELEMENT_LINE.sub("", _PARSER_NOISE.sub("", flat))
    reason = _PREFIX.sub("", reason).strip(" ;") or "MuJoCo could not read the file"
    key = element.group(1) if element else ""
    at_file, at_line = _where(file, line, key, scan)
    return MechanismFileError(clipped(key), f"MuJoCo cannot compile it: {clipped(reason, 300)}; expected a model MuJoCo compiles",
                              file=at_file, line=at_line)


def _where(file: str, line: int, key: str, scan: MjcfScan) -> tuple[str, int | None]:
    """The file and line an error is about: never line 0 (MuJoCo's line for an element of an included file);
    for an error inside an included file, the line of its ``<include>`` in the file that holds it."""
    if line <= 0:
        return file, None
    if key != "include":
        return file, line
    holders = {f for f, at in scan.includes if at == line}
    if file in holders or not holders:
        return file, line
    return (holders.pop(), line) if len(holders) == 1 else (file, None)


def _require_kept(scan: MjcfScan, model: Any, file: str) -> None:
    """Refuse a model from which MuJoCo dropped an equality, a joint or a body that the file declares (an open loop, a wrong answer).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> _require_kept(MjcfScan(equalities=1, world_joints=3), SimpleNamespace(neq=0, njnt=3), "m.xml")
    Traceback (most recent call last):
    ...
    mobility.errors.MechanismFileError: m.xml: equality: the file declares 1 equality (<connect>, <weld>, ...), MuJoCo kept 0: it drops an equality naming a body or site inside a <replicate>, which it renames (rocker becomes rocker0); expected every equality kept (name the copy, or move the body out of the <replicate>)
    """
    if model.neq < scan.equalities:
        raise MechanismFileError("equality", f"the file declares {scan.equalities} equalit{'y' if scan.equalities == 1 else 'ies'} (<connect>, <weld>, ...), "
                                 f"MuJoCo kept {model.neq}: it drops an equality naming a body or site inside a <replicate>, which it renames "
                                 "(rocker becomes rocker0); expected every equality kept (name the copy, or move the body out of the <replicate>)",
                                 file=file)
    for key, declared, kept in (("joint", scan.world_joints, model.njnt), ("body", scan.world_bodies, model.nbody - 1)):  # body 0: the world
        if kept < declared:
            noun = counted(declared, key) if key == "joint" else f"{declared} {'body' if declared == 1 else 'bodies'}"
            raise MechanismFileError(key, f"the file declares {noun}, MuJoCo kept {kept}; expected every {key} kept", file=file)


_SIZES = ("nkey", "nuserdata", "memory", "njmax", "nconmax", "nstack",
          *(f"nuser_{kind}" for kind in ("body", "jnt", "geom", "site", "cam", "tendon", "actuator", "sensor")))
"""``<size>`` attributes, set back to MuJoCo's defaults (those of a new spec: their types differ between versions)."""


def _kinematics_only(mujoco: ModuleType, spec: Any) -> None:
    """Leave out of ``spec`` what kinematics at ``qpos0`` does not need and MuJoCo would read, allocate or refuse: asset files,
    what could cost minutes or gigabytes (``<size nkey="1000000">``), mass bounds; the list and why: ``docs/robot-files.md``."""
    kinds = mujoco.mjtGeom
    for geom in spec.geoms:
        if geom.type in (kinds.mjGEOM_MESH, kinds.mjGEOM_HFIELD, kinds.mjGEOM_SDF):
            geom.type = kinds.mjGEOM_SPHERE
            geom.meshname = ""
            geom.hfieldname = ""
            geom.size = [0.01, 0.0, 0.0]
    for element in [*spec.meshes, *spec.hfields, *spec.textures, *spec.skins, *spec.sensors]:
        spec.delete(element)
    for material in spec.materials:
        material.textures = ["" for _ in material.textures]
    defaults = mujoco.MjSpec()
    for attribute in _SIZES:
        setattr(spec, attribute, getattr(defaults, attribute))
    for actuator in spec.actuators:
        actuator.delay = actuator.nsample = 0
    compiler = spec.compiler
    compiler.boundmass = compiler.boundmass or 1e-6
    compiler.boundinertia = compiler.boundinertia or 1e-12
    compiler.LRopt.mode = mujoco.mjtLRMode.mjLRMODE_NONE
    compiler.fusestatic = False


def _line(element: Any) -> int | None:
    """The line of a spec element (``None`` when MuJoCo does not know it: it says line 0 for included files)."""
    found = _LINE.search(element.info)
    return int(found.group(1)) if found and int(found.group(1)) > 0 else None


class _MjcfTree:
    """Reads a compiled MuJoCo model (and the spec it came from, for lines) into a RobotTree."""

    def __init__(self, mujoco: ModuleType, spec: Any, model: Any, data: Any, file: str) -> None:
        self.mj, self.spec, self.m, self.d, self.file = mujoco, spec, model, data, file
        kinds = (("body", spec.bodies), ("joint", spec.joints), ("equality", spec.equalities), ("tendon", spec.tendons),
                 ("actuator", spec.actuators))
        self.lines = {kind: {int(e.id): _line(e) for e in elements if e.id >= 0} for kind, elements in kinds}  # by compiled index
        written = [self.name("mjOBJ_BODY", i) for i in range(model.nbody)]
        used = set(filter(None, written))  # an unnamed body's made-up name never takes a real body's
        self.body_names = [name or unique_name(f"body{i}", used) for i, name in enumerate(written)]

    def name(self, kind: str, index: int) -> str:
        return self.mj.mj_id2name(self.m, getattr(self.mj.mjtObj, kind), index) or ""

    def tree(self) -> RobotTree:
        m, mj = self.m, self.mj
        bodies = tuple(self.body(i) for i in range(m.nbody))
        notes: list[str] = []
        unsupported: list[Unsupported] = []
        actuated, balls = self.actuator_inputs(notes, unsupported)
        joints = tuple(self.joint(i, i in actuated, balls.get(i, ())) for i in range(m.njnt))
        if m.nflex:
            unsupported.append(Unsupported("flex", f"{m.nflex} deformable (flex) bodies are not supported; expected rigid bodies and joints",
                                           _line(self.spec.flexes[0]) if self.spec.flexes else None))
        self.gap_lengths: list[float] = []  # how far each connect and weld misses at qpos0 (equality_gaps)
        self.gap_angles: list[float] = []
        closures, welds, more, couplings = self.equalities(notes)
        unsupported += more
        held = {int(o) for k in range(m.neq) if m.eq_active0[k] and int(m.eq_type[k]) == int(mj.mjtEq.mjEQ_TENDON)
                for o in (m.eq_obj1id[k], m.eq_obj2id[k]) if o >= 0}  # tendons an active tendon equality names
        for i in sorted(set(range(m.ntendon)) - held):
            tname = self.name("mjOBJ_TENDON", i) or f"tendon{i}"
            notes.append(f"tendon {clipped(tname)}{at_line(self.lines['tendon'].get(i))} is not imported: a tendon is not a joint (only an equality on it would constrain the mechanism)")
        for i in range(m.nbody):
            if m.body_mocapid[i] >= 0:
                notes.append(f"mocap body {clipped(self.body_names[i])}{at_line(self.lines['body'].get(i))} is moved only by the simulation: treated as fixed")
        name = self.spec.modelname if self.spec.modelname and self.spec.modelname != "MuJoCo Model" else one_line(Path(self.file).stem)  # a file name may hold a line break; a name may not
        return RobotTree(name, self.file, "MJCF", bodies, joints, tuple(closures), tuple(welds), tuple(unsupported), tuple(notes),
                         pose=f"qpos0, as MuJoCo {mj.__version__} compiles it", gaps=tuple(self.gap_lengths), angle_gaps=tuple(self.gap_angles),
                         couplings=tuple(couplings))

    def body(self, i: int) -> Body:
        """Body ``i`` at ``qpos0``: its parent, origin and rotation in the global frame."""
        m, d, line = self.m, self.d, self.lines["body"].get(i)
        key = f"body[{clipped(self.body_names[i])}]"
        origin = self.finite(d.xpos[i], key, line)
        if not np.all(np.isfinite(d.xmat[i])):
            raise MechanismFileError(key, f"MuJoCo computes a rotation that is not finite at qpos0; {_FINITE}", file=self.file, line=line)
        return Body(self.body_names[i], None if i == 0 else self.body_names[m.body_parentid[i]], origin, rotation_tuple(d.xmat[i]), line)

    def finite(self, values: Any, key: str, line: int | None) -> tuple[float, float, float]:
        """A vector MuJoCo computed, refused at the element's line when it is not finite (numbers too large)."""
        try:
            return vector_tuple(values)
        except MechanismError as exc:
            raise MechanismFileError(key, f"MuJoCo computes it at qpos0 as {exc.message.removeprefix('expected finite numbers, got ')}; {_FINITE}",
                                     file=self.file, line=line) from None

    def joint_name(self, i: int) -> str:
        """The name of joint ``i``: its own, or made of its body's (``body_joint``, ``body_joint1`` for the second of a body's joints)."""
        m = self.m
        body = int(m.jnt_bodyid[i])
        index = i - int(m.body_jntadr[body])
        return self.name("mjOBJ_JOINT", i) or (f"{self.body_names[body]}_joint" + (str(index) if m.body_jntnum[body] > 1 else ""))

    def joint(self, i: int, actuated: bool, actuators: tuple[BallActuator, ...] = ()) -> TreeJoint:
        m, d, types = self.m, self.d, self.mj.mjtJoint
        body = int(m.jnt_bodyid[i])
        name = self.joint_name(i)
        kind = {int(types.mjJNT_HINGE): "hinge", int(types.mjJNT_SLIDE): "slide", int(types.mjJNT_BALL): "ball", int(types.mjJNT_FREE): "free"}[int(m.jnt_type[i])]
        line, key = self.lines["joint"].get(i), f"joint[{clipped(name)}]"
        axis = self.finite(d.xaxis[i], key, line) if kind in ("hinge", "slide") else None
        point = self.finite(d.xpos[body] if kind == "free" else d.xanchor[i], key, line)
        return TreeJoint(name, kind, self.body_names[body], point, axis, actuated, line, actuators)

    def equalities(self, notes: list[str]) -> tuple[list[Closure], list[Weld], list[Unsupported], list[TreeCoupling]]:
        m, eq = self.m, self.mj.mjtEq
        couplings: list[TreeCoupling] = []
        closures: list[Closure] = []
        welds: list[Weld] = []
        unsupported: list[Unsupported] = []
        counts: dict[str, int] = {}
        gaps = self.equality_gaps(notes)
        for k in range(m.neq):
            kind = int(m.eq_type[k])
            tag = {int(eq.mjEQ_CONNECT): "connect", int(eq.mjEQ_WELD): "weld", int(eq.mjEQ_JOINT): "joint", int(eq.mjEQ_TENDON): "tendon"}.get(kind, "flex")
            counts[tag] = counts.get(tag, 0) + 1
            name = self.name("mjOBJ_EQUALITY", k) or f"{tag}{counts[tag] - 1}"
            line = self.lines["equality"].get(k)
            if not m.eq_active0[k]:
                notes.append(f"equality {tag} {clipped(name)}{at_line(line)} is inactive at start: left out")
                continue
            if tag in ("joint", "tendon"):
                coupling = self.equality_coupling(k, tag, f"equality/{tag}[{clipped(name)}]", line, notes)
                if isinstance(coupling, Unsupported):
                    unsupported.append(coupling)
                else:
                    couplings.append(coupling)
                continue
            if tag == "flex":
                unsupported.append(Unsupported(f"equality/flex[{clipped(name)}]", "a flex equality is not supported; expected connect or weld", line))
                continue
            b1, b2, anchor = self.equality_bodies(k, f"equality/{tag}[{clipped(name)}]", line)
            if k in gaps:
                held = "a spherical joint at its first point" if tag == "connect" else "the two bodies welded as they are placed"
                notes.append(f"{tag} {clipped(name)}{at_line(line)} does not hold at qpos0 ({gaps[k]}): the file is not assembled there; "
                             f"analysed as {held}")
            if tag == "weld":
                welds.append(Weld(name, (self.body_names[b1], self.body_names[b2]), line))
                continue
            if b1 == b2:
                notes.append(f"connect {clipped(name)}{at_line(line)} joins body {clipped(self.body_names[b1])} to itself: left out")
                continue
            try:
                joint = Joint(name, "S", (self.body_names[b1], self.body_names[b2]), point=anchor)
            except MechanismError as exc:
                raise MechanismFileError(f"equality/connect[{clipped(name)}]", exc.message, file=self.file, line=line) from None
            closures.append(Closure(joint, "connect", line))
        return closures, welds, unsupported, couplings

    def equality_gaps(self, notes: list[str]) -> dict[int, str]:
        """How far each active connect or weld is from holding at qpos0, where it is; a note when the file turns equalities off.

        From the first three constraint rows (``efc_pos``) of ``mj_forward`` and :meth:`weld_angle`: above ``Tolerance.rank``
        of the joints' characteristic length (not ``<statistic extent>``, which a file sets at will) or radians.
        """
        m, mj = self.m, self.mj
        kinds = (int(mj.mjtEq.mjEQ_CONNECT), int(mj.mjtEq.mjEQ_WELD))
        closing = [k for k in range(m.neq) if m.eq_active0[k] and int(m.eq_type[k]) in kinds]
        if not closing:
            return {}
        bits = mj.mjtDisableBit
        flags = int(m.opt.disableflags)
        off = [name for name, bit in (("constraint", bits.mjDSBL_CONSTRAINT), ("equality", bits.mjDSBL_EQUALITY)) if flags & int(bit)]
        if off:
            said = " and ".join(f'<flag {name}="disable"/>' for name in off)
            count = f"{len(closing)} connect/weld equalit{'y' if len(closing) == 1 else 'ies'}"
            notes.append(f"the file turns equalities off (<option>{said}): MuJoCo itself would not enforce its {count}; "
                         "analysed as written all the same")
        quiet = int(bits.mjDSBL_CONTACT) | int(bits.mjDSBL_LIMIT) | int(bits.mjDSBL_FRICTIONLOSS)  # rows the gaps do not need
        m.opt.disableflags = (flags & ~(int(bits.mjDSBL_CONSTRAINT) | int(bits.mjDSBL_EQUALITY))) | quiet
        try:
            data = mj.MjData(m)  # at qpos0; its own copy, so the kinematics read elsewhere stay as they are
            mj.mj_forward(m, data)
        finally:
            m.opt.disableflags = flags
        rows = np.flatnonzero(np.asarray(data.efc_type[: data.nefc]) == int(mj.mjtConstraint.mjCNSTR_EQUALITY))
        ids, residual = np.asarray(data.efc_id)[rows], np.asarray(data.efc_pos)[rows]
        size = max(self.characteristic_length(closing), 1e-300)
        gaps: dict[int, str] = {}
        for k in closing:
            own = residual[ids == k]
            distance = math.hypot(*own[:3]) if len(own) >= 3 else 0.0  # hypot: no overflow for a relpose near the largest float
            angle = self.weld_angle(k) if int(m.eq_type[k]) == kinds[1] else 0.0
            self.gap_lengths.append(distance)
            self.gap_angles.append(angle)
            if distance > DEFAULT_TOLERANCE.rank * size or angle > DEFAULT_TOLERANCE.rank:
                gaps[k] = f"its points are {distance:.3g} apart" + (
                    f" and its frames {angle:.3g} rad ({math.degrees(angle):.3g} degrees) apart" if angle > DEFAULT_TOLERANCE.rank else "")
        return gaps

    def characteristic_length(self, closing: list[int]) -> float:
        """The mechanism's characteristic length at qpos0: of its joints' points and its connects' anchors (as the analysis measures it)."""
        m, d = self.m, self.d
        points = [np.asarray(d.xanchor[j], dtype=float) for j in range(m.njnt)]
        for k in closing:
            if int(m.eq_type[k]) == int(self.mj.mjtEq.mjEQ_CONNECT):
                try:
                    points.append(np.asarray(self.equality_bodies(k, "equality/connect", None)[2], dtype=float))
                except MechanismFileError:
                    continue  # an anchor that is not finite: refused with its name where the connect is read
        finite = [p for p in points if np.all(np.isfinite(p))]
        if not finite:
            return 1.0
        with np.errstate(all="ignore"):
            return float(characteristic_scale(np.array(finite))[1])

    def weld_angle(self, k: int) -> float:
        """The angle (radians, 0 to pi) between a weld's two frames at qpos0, as its constraint compares them.

        Body semantic: the rotation ``q2^-1 (q1 relpose)``; site semantic:
        ``(q2 s2)^-1 (q1 s1)``, ``s`` the sites' quaternions in their bodies.
        """
        m, d, mj = self.m, self.d, self.mj

        def product(a: Any, b: Any) -> np.ndarray:  # MuJoCo's own quaternion product, (w, x, y, z)
            out = np.zeros(4)
            mj.mju_mulQuat(out, np.asarray(a, dtype=float), np.asarray(b, dtype=float))
            return out

        o1, o2 = int(m.eq_obj1id[k]), int(m.eq_obj2id[k])
        if int(m.eq_objtype[k]) == int(mj.mjtObj.mjOBJ_SITE):
            first = product(d.xquat[int(m.site_bodyid[o1])], m.site_quat[o1])
            second = product(d.xquat[int(m.site_bodyid[o2])], m.site_quat[o2])
        else:
            first = product(d.xquat[o1], m.eq_data[k][6:10])
            second = np.asarray(d.xquat[o2], dtype=float)
        conjugate = np.zeros(4)
        mj.mju_negQuat(conjugate, second)
        error = product(conjugate, first)
        with np.errstate(all="ignore"):
            sine = float(np.linalg.norm(error[1:]))
        angle = 2.0 * math.atan2(sine, abs(float(error[0])))
        return angle if math.isfinite(angle) else 0.0

    def equality_bodies(self, k: int, key: str, line: int | None) -> tuple[int, int, tuple[float, float, float]]:
        """The two bodies of a connect or weld, and the anchor in the global frame."""
        m, d = self.m, self.d
        o1, o2 = int(m.eq_obj1id[k]), int(m.eq_obj2id[k])
        if int(m.eq_objtype[k]) == int(self.mj.mjtObj.mjOBJ_SITE):
            return int(m.site_bodyid[o1]), int(m.site_bodyid[o2]), self.finite(d.site_xpos[o1], key, line)
        rotation = np.asarray(d.xmat[o1]).reshape(3, 3)
        with np.errstate(all="ignore"):  # an overflow is refused just below, in one line
            anchor = d.xpos[o1] + rotation @ np.asarray(m.eq_data[k][:3])
        return o1, o2, self.finite(anchor, key, line)

    def actuator_inputs(self, notes: list[str], unsupported: list[Unsupported]) -> tuple[set[int], dict[int, tuple[BallActuator, ...]]]:
        """The hinges and slides actuators drive, and the inputs of each driven ball joint (one actuator, one input; the
        rules: ``docs/robot-files.md``): about ``xmat @ gear[:3]`` in the global frame, the same for ``jointinparent`` at ``qpos0``."""
        m, trn, types = self.m, self.mj.mjtTrn, self.mj.mjtJoint
        out: set[int] = set()
        drivers: dict[int, list[str]] = {}
        balls: dict[int, list[BallActuator]] = {}
        for a in range(m.nu):
            kind = int(m.actuator_trntype[a])
            aname = self.name("mjOBJ_ACTUATOR", a) or f"actuator{a}"
            line = self.lines["actuator"].get(a)
            if kind not in (int(trn.mjTRN_JOINT), int(trn.mjTRN_JOINTINPARENT)):
                what = {int(trn.mjTRN_TENDON): "a tendon", int(trn.mjTRN_SITE): "a site", int(trn.mjTRN_BODY): "a body",
                        int(trn.mjTRN_SLIDERCRANK): "a slider-crank"}.get(kind, "no joint")
                notes.append(f"actuator {clipped(aname)}{at_line(line)} drives {what}, not a joint: no joint is marked actuated for it")
                continue
            joint = int(m.actuator_trnid[a][0])
            jtype, jname, key = int(m.jnt_type[joint]), self.joint_name(joint), f"actuator[{clipped(aname)}]"
            if jtype == int(types.mjJNT_FREE):
                unsupported.append(Unsupported(key, f"an actuator on the free joint {clipped(jname)} is not supported: it is one input along its "
                                               "six-number gear (a force and a torque together), which no joint of the model expresses as one input "
                                               "(an actuated free joint would be six inputs); expected actuators on hinge, slide or ball joints", line))
            elif jtype == int(types.mjJNT_BALL):
                ball = self.ball_actuator(a, aname, joint, kind == int(trn.mjTRN_JOINTINPARENT), line)
                if ball is None:
                    unsupported.append(Unsupported(key, f"its gear on the ball joint {clipped(jname)} has 0 0 0 as its first three numbers, the axis it "
                                                   "turns about: it drives nothing; expected a non-zero axis", line))
                else:
                    balls.setdefault(joint, []).append(ball)
            else:
                out.add(joint)
                drivers.setdefault(joint, []).append(f"{clipped(aname)}{at_line(line)}")
        for joint, names in drivers.items():
            if len(names) > 1:
                notes.append(f"actuators {', '.join(names)} all drive joint {clipped(self.joint_name(joint))}: one input (its one freedom), not {len(names)}")
        return out, {joint: _independent(self.joint_name(joint), inputs, notes) for joint, inputs in balls.items()}

    def ball_actuator(self, a: int, aname: str, joint: int, in_parent: bool, line: int | None) -> BallActuator | None:
        """The input of actuator ``a`` on a ball joint: its axis in the global frame at ``qpos0`` (``None``: a zero axis)."""
        gear = np.asarray(self.m.actuator_gear[a][:3], dtype=float)
        if not np.any(gear):
            return None
        body = int(self.m.jnt_bodyid[joint])
        with np.errstate(all="ignore"):  # an overflow is refused just below, in one line
            axis = np.asarray(self.d.xmat[body], dtype=float).reshape(3, 3) @ gear
        key = f"actuator[{clipped(aname)}]/@gear"
        try:
            unit = require_vector(self.finite(axis, key, line), key, direction=True)
        except MechanismError as exc:  # numbers too small to keep a direction
            raise MechanismFileError(key, exc.message, file=self.file, line=line) from None
        return BallActuator(aname, unit, in_parent, line)

    def equality_coupling(self, k: int, tag: str, key: str, line: int | None, notes: list[str]) -> TreeCoupling | Unsupported:
        """Equality ``k`` on joints or fixed tendons as a coupling of joint rates at ``qpos0``, through the slope ``polycoef[1]``
        (``q1' - c1 q2' = 0``; for tendons, of their lengths ``sum coef_j q_j``; ``docs/robot-files.md``)."""
        m = self.m
        first, second = int(m.eq_obj1id[k]), int(m.eq_obj2id[k])
        poly = [float(x) for x in m.eq_data[k][:5]]
        kind_name = "mjOBJ_JOINT" if tag == "joint" else "mjOBJ_TENDON"
        shown = ", ".join(clipped(self.name(kind_name, o) or str(o)) for o in (first, second) if o >= 0)
        if tag == "joint":
            terms = {first: 1.0}
            if second >= 0 and poly[1] != 0.0:
                terms[second] = terms.get(second, 0.0) - poly[1]
        else:
            terms = {}
            for tendon, sign in ((first, 1.0), (second, -poly[1])):
                if tendon < 0 or sign == 0.0:
                    continue
                start = int(m.tendon_adr[tendon])
                for w in range(start, start + int(m.tendon_num[tendon])):
                    if int(m.wrap_type[w]) != int(self.mj.mjtWrap.mjWRAP_JOINT):
                        return Unsupported(key, f"a coupling of tendons ({shown}) on a spatial tendon is not supported; expected fixed tendons (of joints)", line)
                    joint = int(m.wrap_objid[w])
                    terms[joint] = terms.get(joint, 0.0) + sign * float(m.wrap_prm[w])
        terms = {j: c for j, c in terms.items() if c != 0.0}
        if len(terms) < 2:
            held = ", ".join(clipped(self.joint_name(j)) for j in terms) or shown
            return Unsupported(key, f"an equality of {tag}s ({shown}) that holds {held} still at qpos0 (no second {tag}, or a zero slope) is not supported; "
                               "expected a coupling of two or more joint rates", line)
        if any(x != 0.0 for x in poly[2:]):
            notes.append(f"equality {tag} {clipped(self.name('mjOBJ_EQUALITY', k) or key)}{at_line(line)} is not linear (polycoef {' '.join(f'{x:g}' for x in poly)}): "
                         f"its coupling acts through its slope at qpos0, {poly[1]:g}, and holds at this pose only")
        return TreeCoupling(key, tuple(self.joint_name(j) for j in terms), tuple(terms.values()), line)


def _independent(joint: str, inputs: list[BallActuator], notes: list[str]) -> tuple[BallActuator, ...]:
    """The inputs of a ball joint whose axes are independent of those before them; a note for each other one."""
    kept: list[BallActuator] = []
    for ball in inputs:
        if independent_of([k.axis for k in kept], ball.axis):
            kept.append(ball)
            continue
        others = ", ".join(clipped(k.name) for k in kept)
        notes.append(f"actuator {clipped(ball.name)}{at_line(ball.line)} turns the ball joint {clipped(joint)} about an axis "
                     f"that actuator{'s' if len(kept) > 1 else ''} {others} already drive{'' if len(kept) > 1 else 's'}: it adds no input")
    return tuple(kept)
