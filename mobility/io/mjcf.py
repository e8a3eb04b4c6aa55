"""Read MuJoCo (MJCF) files as MuJoCo compiles them: bodies, joints and loop closures at ``qpos0``.

MJCF has defaults and classes, frames, ``ref`` positions, ``xyaxes``,
``zaxis`` and Euler sequences, ``<include>``, ``<replicate>`` and attached
models: rather than re-implement its compiler, this module asks MuJoCo (the
``mujoco`` package, the ``mobility[mujoco]`` extra) to compile the file, then
reads the compiled model at the pose ``qpos0`` (``mj_kinematics``): each
joint's anchor and axis in the global frame, each body's parent.

* joints ``hinge``, ``slide``, ``ball``, ``free`` become R, P, S and a free
  joint (fixed unless ``--floating``; see :mod:`mobility.io.robot_tree`);
* an ``<equality><connect>`` is a spherical joint between its two bodies at
  its anchor (written on ``body1``, or ``site1``); a ``<weld>`` makes its two
  bodies one rigid link; an equality inactive at start is left out (a note);
* a joint driven by an actuator (joint transmission) is marked actuated;
  actuators driving tendons, sites or bodies mark nothing (a note);
* joint and tendon equalities and deformable (flex) bodies are not supported:
  each is an error of one line naming its line, unless ``ignore_unsupported``;
  tendons are not joints: they are listed in a note.

Geometry is not needed: meshes, height fields, textures and skins are removed
before compiling (a mesh geom becomes a small sphere), so a file whose mesh
files are absent imports.  Every error is one line naming the file, the line
(from MuJoCo where it knows it) and the element.
"""

from __future__ import annotations

import re
import warnings
from dataclasses import replace
from importlib import import_module
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

from ..core.model import Joint
from ..errors import MechanismError, MechanismFileError, MissingExtraError
from .robot_tree import Body, Closure, RobotTree, TreeJoint, Unsupported, Weld, rotation_tuple, vector_tuple
from .files import read_capped
from .xml_source import read_xml

__all__ = ["read_mjcf", "import_mujoco"]

_LINE = re.compile(r"\bline(?: number)?\s*=?\s*(\d+)", re.IGNORECASE)
_ELEMENT = re.compile(r"Element (?:name )?'([^']*)'")


def import_mujoco() -> ModuleType:
    """The ``mujoco`` module, or an error saying which extra installs it.

    Raises
    ------
    MissingExtraError
        When the ``mujoco`` package cannot be imported.
    """
    try:
        return import_module("mujoco")
    except ImportError as exc:
        raise MissingExtraError("reading MJCF files", "mujoco", "mujoco", str(exc)) from None


def read_mjcf(path: str | Path) -> RobotTree:
    """Read an MJCF file into a :class:`~mobility.io.robot_tree.RobotTree` at ``qpos0``.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    RobotTree

    Raises
    ------
    MechanismFileError
        When the file is not well-formed XML, not MJCF, or MuJoCo cannot
        compile it (the message names the line MuJoCo gives).
    MissingExtraError
        When the ``mujoco`` package is not installed.
    """
    file = str(path)
    doc = read_xml(path)
    if doc.root.tag != "mujoco":
        raise doc.fail(doc.root, doc.root.tag, "not an MJCF file; expected the root element <mujoco>")
    mujoco = import_mujoco()
    if Path(file).suffix.lower() == ".xml":
        spec = _mujoco_call(lambda: mujoco.MjSpec.from_file(file), file)
    else:  # MuJoCo picks its reader by extension: give it the text (includes then resolve from the working directory)
        spec = _mujoco_call(lambda: mujoco.MjSpec.from_string(read_capped(file).decode("utf-8", errors="replace")), file)
    _without_asset_files(mujoco, spec)
    with warnings.catch_warnings(record=True) as caught:  # MuJoCo's compiler warnings become notes
        warnings.simplefilter("always")
        model = _mujoco_call(spec.compile, file)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    tree = _MjcfTree(mujoco, spec, model, data, file).tree()
    said = [f"MuJoCo warns: {str(w.message).splitlines()[0]}" for w in caught if str(w.message).strip()]
    return replace(tree, notes=tree.notes + tuple(said))


def _mujoco_call(call: Any, file: str) -> Any:
    """Run a MuJoCo parse or compile step; its error becomes one line with the line it names."""
    try:
        return call()
    except (ValueError, RuntimeError) as exc:  # MuJoCo's parse and compile errors
        text = str(exc).strip()
        first = text.splitlines()[0] if text else "MuJoCo could not read the file"
        first = re.sub(r"^(XML )?(parse )?Error( \d+)?:?\s*", "", first, flags=re.IGNORECASE).strip() or first
        line = _LINE.search(text)
        element = _ELEMENT.search(text)
        raise MechanismFileError(element.group(1) if element else "", f"MuJoCo cannot compile it: {first}; expected a model MuJoCo compiles",
                                 file=file, line=int(line.group(1)) if line else None) from None


def _without_asset_files(mujoco: ModuleType, spec: Any) -> None:
    """Remove what needs files on disk (meshes, height fields, textures, skins): kinematics needs none of it."""
    kinds = mujoco.mjtGeom
    for geom in spec.geoms:
        if geom.type in (kinds.mjGEOM_MESH, kinds.mjGEOM_HFIELD, kinds.mjGEOM_SDF):
            geom.type = kinds.mjGEOM_SPHERE
            geom.meshname = ""
            geom.hfieldname = ""
            geom.size = [0.01, 0.0, 0.0]
    for collection in (spec.meshes, spec.hfields, spec.textures, spec.skins):
        for element in list(collection):
            if hasattr(spec, "delete"):  # newer MuJoCo; in older ones each element deletes itself
                spec.delete(element)
            else:
                element.delete()
    for material in spec.materials:
        material.textures = ["" for _ in material.textures]


def _line(element: Any) -> int | None:
    found = _LINE.search(getattr(element, "info", "") or "")
    return int(found.group(1)) if found else None


class _MjcfTree:
    """Reads a compiled MuJoCo model (and the spec it came from, for lines) into a RobotTree."""

    def __init__(self, mujoco: ModuleType, spec: Any, model: Any, data: Any, file: str) -> None:
        self.mj, self.spec, self.m, self.d, self.file = mujoco, spec, model, data, file
        self.lines = {kind: self.element_lines(obj, elements, in_order) for kind, obj, elements, in_order in (
            ("body", "mjOBJ_BODY", spec.bodies, False), ("joint", "mjOBJ_JOINT", spec.joints, False),
            ("equality", "mjOBJ_EQUALITY", spec.equalities, True), ("tendon", "mjOBJ_TENDON", spec.tendons, True),
            ("actuator", "mjOBJ_ACTUATOR", spec.actuators, True))}
        self.body_names = [self.name("mjOBJ_BODY", i) or f"body{i}" for i in range(model.nbody)]

    def element_lines(self, kind: str, elements: Any, in_order: bool) -> dict[int, int | None]:
        """Line of each element of the spec, by its index in the compiled model.

        Older MuJoCo gives spec elements no ``id``: they are then found by name,
        or, for the kinds MuJoCo compiles in file order (``in_order``), by position.
        """
        out: dict[int, int | None] = {}
        for position, element in enumerate(elements):
            index = getattr(element, "id", None)
            if index is None or index < 0:
                index = position if in_order else self.mj.mj_name2id(self.m, getattr(self.mj.mjtObj, kind), element.name) if element.name else -1
            if index >= 0:
                out[int(index)] = _line(element)
        return out

    def name(self, kind: str, index: int) -> str:
        return self.mj.mj_id2name(self.m, getattr(self.mj.mjtObj, kind), index) or ""

    def tree(self) -> RobotTree:
        m, d, mj = self.m, self.d, self.mj
        bodies = tuple(
            Body(self.body_names[i], None if i == 0 else self.body_names[m.body_parentid[i]],
                 vector_tuple(d.xpos[i]), rotation_tuple(d.xmat[i]), self.lines["body"].get(i))
            for i in range(m.nbody))
        notes: list[str] = []
        actuated = self.actuated_joints(notes)
        joints = tuple(self.joint(i, i in actuated) for i in range(m.njnt))
        unsupported: list[Unsupported] = []
        if m.nflex:
            flexes = list(getattr(self.spec, "flexes", []))
            unsupported.append(Unsupported("flex", f"{m.nflex} deformable (flex) bodies are not supported; expected rigid bodies and joints",
                                           _line(flexes[0]) if flexes else None))
        closures, welds, more = self.equalities(notes)
        unsupported += more
        for i in range(m.ntendon):
            tname = self.name("mjOBJ_TENDON", i) or f"tendon{i}"
            notes.append(f"tendon {tname}{_at(self.lines['tendon'].get(i))} is not imported: a tendon is not a joint (only an equality on it would constrain the mechanism)")
        for i in range(m.nbody):
            if m.body_mocapid[i] >= 0:
                notes.append(f"mocap body {self.body_names[i]}{_at(self.lines['body'].get(i))} is moved only by the simulation: treated as fixed")
        name = self.spec.modelname if self.spec.modelname and self.spec.modelname != "MuJoCo Model" else Path(self.file).stem
        version = getattr(mj, "__version__", "")
        return RobotTree(name, self.file, "MJCF", bodies, joints, tuple(closures), tuple(welds), tuple(unsupported), tuple(notes),
                         pose=f"qpos0, as MuJoCo {version} compiles it".replace("  ", " "))

    def joint(self, i: int, actuated: bool) -> TreeJoint:
        m, d, types = self.m, self.d, self.mj.mjtJoint
        body = int(m.jnt_bodyid[i])
        index = i - int(m.body_jntadr[body])
        name = self.name("mjOBJ_JOINT", i) or (f"{self.body_names[body]}_joint" + (str(index) if m.body_jntnum[body] > 1 else ""))
        kind = {int(types.mjJNT_HINGE): "hinge", int(types.mjJNT_SLIDE): "slide", int(types.mjJNT_BALL): "ball", int(types.mjJNT_FREE): "free"}[int(m.jnt_type[i])]
        axis = vector_tuple(d.xaxis[i]) if kind in ("hinge", "slide") else None
        point = vector_tuple(d.xpos[body]) if kind == "free" else vector_tuple(d.xanchor[i])
        return TreeJoint(name, kind, self.body_names[body], point, axis, actuated, self.lines["joint"].get(i))

    def actuated_joints(self, notes: list[str]) -> set[int]:
        m, trn = self.m, self.mj.mjtTrn
        out: set[int] = set()
        for a in range(m.nu):
            kind = int(m.actuator_trntype[a])
            if kind in (int(trn.mjTRN_JOINT), int(trn.mjTRN_JOINTINPARENT)):
                out.add(int(m.actuator_trnid[a][0]))
                continue
            aname = self.name("mjOBJ_ACTUATOR", a) or f"actuator{a}"
            what = {int(trn.mjTRN_TENDON): "a tendon", int(trn.mjTRN_SITE): "a site", int(trn.mjTRN_BODY): "a body", int(trn.mjTRN_SLIDERCRANK): "a slider-crank"}.get(kind, "no joint")
            notes.append(f"actuator {aname}{_at(self.lines['actuator'].get(a))} drives {what}, not a joint: no joint is marked actuated for it")
        return out

    def equalities(self, notes: list[str]) -> tuple[list[Closure], list[Weld], list[Unsupported]]:
        m, eq = self.m, self.mj.mjtEq
        closures: list[Closure] = []
        welds: list[Weld] = []
        unsupported: list[Unsupported] = []
        counts: dict[str, int] = {}
        for k in range(m.neq):
            kind = int(m.eq_type[k])
            tag = {int(eq.mjEQ_CONNECT): "connect", int(eq.mjEQ_WELD): "weld", int(eq.mjEQ_JOINT): "joint", int(eq.mjEQ_TENDON): "tendon"}.get(kind, "flex")
            counts[tag] = counts.get(tag, 0) + 1
            name = self.name("mjOBJ_EQUALITY", k) or f"{tag}{counts[tag] - 1}"
            line = self.lines["equality"].get(k)
            if not m.eq_active0[k]:
                notes.append(f"equality {tag} {name}{_at(line)} is inactive at start: left out")
                continue
            if tag in ("joint", "tendon"):
                kind_name = "mjOBJ_JOINT" if tag == "joint" else "mjOBJ_TENDON"
                objects = [self.name(kind_name, int(o)) or str(int(o)) for o in (m.eq_obj1id[k], m.eq_obj2id[k]) if o >= 0]
                unsupported.append(Unsupported(f"equality/{tag}[{name}]", f"a coupling of {tag}s ({', '.join(objects)}) is not supported; expected connect or weld", line))
                continue
            if tag == "flex":
                unsupported.append(Unsupported(f"equality/flex[{name}]", "a flex equality is not supported; expected connect or weld", line))
                continue
            b1, b2, anchor = self.equality_bodies(k)
            if tag == "weld":
                welds.append(Weld(name, (self.body_names[b1], self.body_names[b2]), line))
                continue
            if b1 == b2:
                notes.append(f"connect {name}{_at(line)} joins body {self.body_names[b1]} to itself: left out")
                continue
            try:
                joint = Joint(name, "S", (self.body_names[b1], self.body_names[b2]), point=anchor)
            except MechanismError as exc:
                raise MechanismFileError(f"equality/connect[{name}]", exc.message, file=self.file, line=line) from None
            closures.append(Closure(joint, "connect", line))
        return closures, welds, unsupported

    def equality_bodies(self, k: int) -> tuple[int, int, tuple[float, float, float]]:
        """The two bodies of a connect or weld, and the anchor in the global frame."""
        m, d = self.m, self.d
        o1, o2 = int(m.eq_obj1id[k]), int(m.eq_obj2id[k])
        if int(m.eq_objtype[k]) == int(self.mj.mjtObj.mjOBJ_SITE):
            return int(m.site_bodyid[o1]), int(m.site_bodyid[o2]), vector_tuple(d.site_xpos[o1])
        rotation = np.asarray(d.xmat[o1]).reshape(3, 3)
        return o1, o2, vector_tuple(d.xpos[o1] + rotation @ np.asarray(m.eq_data[k][:3]))


def _at(line: int | None) -> str:
    return f" (line {line})" if line is not None else ""
