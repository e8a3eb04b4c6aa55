"""A robot description as a tree of bodies, and the joint graph it makes.

The readers of MJCF and URDF (:mod:`mobility.io.mjcf`, :mod:`mobility.io.urdf`) each produce a :class:`RobotTree`,
which :func:`build_mechanism` turns into a :class:`~mobility.core.model.Mechanism` the same way for both (the rules:
``docs/robot-files.md``); every choice made for the user comes back in :attr:`ImportedRobot.notes`.

Examples
--------
>>> tree = RobotTree("pendulum", "p.urdf", "URDF", bodies=(
...     Body("base", None), Body("arm", "base"), Body("tip", "arm")), joints=(
...     TreeJoint("swing", "hinge", "arm", point=(0, 0, 1), axis=(0, 1, 0)),))
>>> robot = build_mechanism(tree)
>>> m = robot.mechanism
>>> m.ground, m.end_effector, [(j.name, j.type, j.links) for j in m.joints]
('base', 'arm', [('swing', 'R', ('base', 'arm'))])
>>> build_mechanism(tree, RobotOptions(end_effector="tip")).mechanism.end_effector
'tip'
>>> build_mechanism(tree, RobotOptions(ground="bse"))
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: p.urdf: ground: no body named 'bse' (did you mean 'base'?); expected one of: base, arm, tip
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Iterable, Mapping, Sequence, cast

import numpy as np

from ..core.model import Coupling, Joint, Mechanism, require_couplings
from ..core.tolerance import DEFAULT_TOLERANCE, file_tolerance
from ..errors import MechanismError, MechanismFileError, clipped, counted, did_you_mean
from .limits import current_limits
from .precision import Rounding, file_precision
from .robot_actuators import BallActuator, ball_chain, ball_chain_names

__all__ = ["Body", "TreeJoint", "Closure", "Weld", "Unsupported", "TreeCoupling", "RobotTree", "RobotOptions", "ImportedRobot", "build_mechanism",
           "model_couplings", "JOINT_KINDS", "rotation_tuple", "vector_tuple", "at_line", "unique_name", "model_joint_names"]

Vector = tuple[float, float, float]
Rotation = tuple[Vector, Vector, Vector]
IDENTITY: Rotation = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))

JOINT_KINDS = {"hinge": "R", "slide": "P", "ball": "S", "planar": "E", "free": "free"}
"""Joint kinds of a tree, and the joint type each becomes (``free``: 3 P + S, or fixed)."""


@dataclass(frozen=True)
class Body:
    """A rigid body of the description at the reference pose: ``x_world = rotation @ x_body + origin`` (``parent``: ``None`` for the root)."""

    name: str
    parent: str | None
    origin: Vector = (0.0, 0.0, 0.0)
    rotation: Rotation = IDENTITY
    line: int | None = None


@dataclass(frozen=True)
class TreeJoint:
    """A joint moving ``body`` relative to its parent body, geometry in the global frame.

    ``kind``: one of :data:`JOINT_KINDS`; ``axis``: the hinge or slide direction,
    or a planar joint's normal; ``actuators``: a ball joint's inputs, one each.
    """

    name: str
    kind: str
    body: str
    point: Vector
    axis: Vector | None = None
    actuated: bool = False
    line: int | None = None
    actuators: tuple[BallActuator, ...] = ()


@dataclass(frozen=True)
class Closure:
    """A joint closing a loop: its ``links`` are two body names, its geometry in the global frame."""

    joint: Joint
    what: str
    line: int | None = None
    file: str | None = None


@dataclass(frozen=True)
class Weld:
    """Two bodies held rigidly together (MJCF ``<weld>``, ``--close A B --weld``)."""

    name: str
    bodies: tuple[str, str]
    line: int | None = None


@dataclass(frozen=True)
class Unsupported:
    """An element the joint-graph model cannot express: ``key`` names it, ``message`` says why."""

    key: str
    message: str
    line: int | None = None


@dataclass(frozen=True)
class TreeCoupling:
    """``sum coefficients[j] * rate(joints[j]) = 0`` on hinges and slides of the tree (by name); ``key`` names the element for messages."""

    key: str
    joints: tuple[str, ...]
    coefficients: tuple[float, ...]
    line: int | None = None


@dataclass(frozen=True)
class RobotTree:
    """A robot description read from a file: bodies (every parent before its children), joints (in file order), closures, at one ``pose``.

    ``files``: the other files read for it; ``rounding``: the digits of its numbers (:mod:`mobility.io.precision`);
    ``gaps``, ``angle_gaps``: how far each loop closure (``length_unit``) and weld (radians) misses at the pose.
    """

    name: str
    file: str
    format: str
    bodies: tuple[Body, ...]
    joints: tuple[TreeJoint, ...] = ()
    closures: tuple[Closure, ...] = ()
    welds: tuple[Weld, ...] = ()
    unsupported: tuple[Unsupported, ...] = ()
    notes: tuple[str, ...] = ()
    pose: str = "all joint positions zero"
    length_unit: str = "m"
    files: tuple[str, ...] = ()
    couplings: tuple[TreeCoupling, ...] = ()
    rounding: Rounding | None = None
    gaps: tuple[float, ...] = ()
    angle_gaps: tuple[float, ...] = ()

    def body(self, name: str, key: str) -> Body:
        """The body called ``name``; an error naming ``key`` and the close matches otherwise."""
        for b in self.bodies:
            if b.name == name:
                return b
        names = [b.name for b in self.bodies]
        hint = did_you_mean(name, names)
        shown = ", ".join(clipped(n) for n in names[:12]) + (f", ... ({len(names)} bodies)" if len(names) > 12 else "")
        raise MechanismFileError(key, f"no body named {clipped(name)!r}{hint}; expected one of: {shown}", file=self.file)

    def with_closures(self, closures: Iterable[Closure], welds: Iterable[Weld] = (), notes: Iterable[str] = (), files: Iterable[str] = (),
                      gaps: Iterable[float] = ()) -> "RobotTree":
        """The same tree with more closing joints, welds and notes (and the files they were read from, and how far the closures miss)."""
        return replace(self, closures=self.closures + tuple(closures), welds=self.welds + tuple(welds), notes=self.notes + tuple(notes),
                       files=self.files + tuple(files), gaps=self.gaps + tuple(gaps))


@dataclass(frozen=True)
class RobotOptions:
    """How to read a robot description file.

    Parameters
    ----------
    ground, end_effector : str, optional
        Body names (defaults: the root body; the body farthest from the ground).
    floating : bool
        Keep the six freedoms of free / floating joints (default: fixed).
    ignore_unsupported : bool
        Leave out elements the model cannot express (with a note).
    close : tuple of (str, str)
        Pairs of bodies whose origins coincide, joined by a spherical joint there.
    closures : str, optional
        A side file of closing joints (:func:`~mobility.io.robot_files.with_closures_file`).
    """

    ground: str | None = None
    end_effector: str | None = None
    floating: bool = False
    ignore_unsupported: bool = False
    close: tuple[tuple[str, str], ...] = ()
    closures: str | None = None


@dataclass(frozen=True)
class ImportedRobot:
    """A mechanism read from a robot description, the notes of its reading and every file read for it (the description first)."""

    mechanism: Mechanism
    notes: tuple[str, ...] = ()
    format: str = ""
    files: tuple[str, ...] = ()
    closures: tuple[str, ...] = ()
    """The joints that close loops (an MJCF ``connect``, a pair closed with ``--close`` or a closures file)."""


@dataclass
class _Groups:
    """Union-find of bodies into rigid links."""

    parent: dict[str, str] = field(default_factory=dict)

    def find(self, name: str) -> str:
        while self.parent[name] != name:  # path halving
            self.parent[name] = self.parent[self.parent[name]]
            name = self.parent[name]
        return name

    def union(self, a: str, b: str) -> None:
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            self.parent[rb] = ra


def build_mechanism(tree: RobotTree, options: RobotOptions | None = None) -> ImportedRobot:
    """The mechanism of a robot tree (the rules: ``docs/robot-files.md``).

    Raises
    ------
    MechanismFileError
        On an unsupported element (unless ``ignore_unsupported``), an unknown
        ground or end-effector body, or a mechanism with nothing to move.
    """
    options = options or RobotOptions()
    _refuse_blank_names(tree)
    notes = list(tree.notes)
    for item in tree.unsupported:
        if not options.ignore_unsupported:
            raise MechanismFileError(item.key, f"{item.message}; pass --ignore-unsupported (ignore_unsupported=True) to leave it out",
                                     file=tree.file, line=item.line)
        notes.append(f"left out {item.key}{at_line(item.line)}: {item.message}")

    ground_body = tree.body(options.ground, "ground").name if options.ground is not None else tree.bodies[0].name
    ee_body = tree.body(options.end_effector, "end_effector").name if options.end_effector is not None else None
    kept = _free_joints_kept(tree, options, notes)
    groups = _rigid_groups(tree, kept, notes)
    names: dict[str, str] = {}  # each rigid link named after the ground or end-effector body in it, else its body nearest the root
    for body in [n for n in (ground_body, ee_body) if n] + [b.name for b in tree.bodies]:  # parents come first
        names.setdefault(groups.find(body), body)

    def link(body: str) -> str:
        return names[groups.find(body)]

    joints: list[Joint] = []
    model_name: dict[str, str] = {}  # of each hinge and slide of the tree that the mechanism holds
    used: set[str] = set()
    link_names = set(names.values())
    by_body: dict[str, list[TreeJoint]] = {}
    for j in tree.joints:
        if j.kind != "free" or j.body in kept:
            by_body.setdefault(j.body, []).append(j)
    parents = {b.name: b.parent for b in tree.bodies}
    for body, chain in by_body.items():
        start, end = link(cast(str, parents[body])), link(body)  # a joint's body is not the root: it has a parent
        if len(chain) == 1 and start == end:
            notes.append(f"joint {clipped(chain[0].name)}{at_line(chain[0].line)} cannot move: welds hold {clipped(body)} to {clipped(start)}; left out")
            continue
        here = start
        for k, j in enumerate(chain):
            there = end if k == len(chain) - 1 else unique_name(f"{body}/{j.name}", link_names)
            made = _model_joints(tree, j, here, there, used, link_names)
            joints += made
            if j.kind in ("hinge", "slide"):
                model_name[j.name] = made[0].name
            here = there
            if j.kind == "ball" and j.actuators:
                shown = ", ".join(f"{joint.type} {clipped(joint.name)}{' (actuated)' if joint.actuated else ''}" for joint in made)
                notes.append(f"ball joint {clipped(j.name)}{at_line(j.line)} has {counted(len(j.actuators), 'input')}, "
                             f"one per actuator: it is the joints {shown} through its centre")

    closing: list[str] = []
    for c in tree.closures:
        a, b = (link(n) for n in c.joint.links)
        if a == b:
            notes.append(f"{c.what} {clipped(c.joint.name)}{at_line(c.line)} joins two bodies of one rigid link ({clipped(a)}): it constrains nothing; left out")
            continue
        try:
            joints.append(replace(c.joint, name=unique_name(c.joint.name, used), links=(a, b)))
            closing.append(joints[-1].name)
        except MechanismError as exc:
            raise MechanismFileError(clipped(c.joint.name), exc.message, file=c.file or tree.file, line=c.line) from None

    if not joints:
        raise MechanismFileError("", f"no joint can move: every body of {clipped(tree.name)!r} is rigidly attached to {clipped(link(ground_body))} (free joints count as fixed unless --floating)", file=tree.file)
    ground = link(ground_body)
    if ee_body is None:
        end_effector = _farthest_link(tree, joints, ground, link)
        notes.append(f"end effector: {clipped(end_effector)} (the body farthest from the ground {clipped(ground)}; choose another with --end-effector)")
    else:
        end_effector = link(ee_body)
        if end_effector == ground:
            raise MechanismFileError("end_effector", f"body {clipped(ee_body)!r} is rigidly attached to the ground {clipped(ground)!r} (no joint between them); expected a body that can move", file=tree.file)
    for role, named in (("ground", ground_body if options.ground is not None else None), ("end effector", ee_body)):
        members = [b.name for b in tree.bodies if named and b.name != named and groups.find(b.name) == groups.find(named)]
        if members:
            notes.append(f"{role} {clipped(named)} is one rigid link with {', '.join(clipped(n) for n in members[:6])}{' ...' if len(members) > 6 else ''}")
    limits = current_limits()
    if len(joints) > limits.max_joints:
        raise MechanismFileError("joints", f"{len(joints)} joints are more than the limit of {limits.max_joints} ({limits.hint('max_joints')})", file=tree.file)
    description = f"Imported from the {tree.format} file {Path(tree.file).name} at the pose: {tree.pose}."
    precision = file_precision(tree.rounding, tree.gaps, tree.angle_gaps, (j.point for j in joints))
    rank = file_tolerance(precision.value).rank
    if rank > DEFAULT_TOLERANCE.rank:
        notes.append(f"the file is precise to about {precision.value:.1e} of its size ({precision.describe()}): "
                     f"ranks are decided at {rank:.1e}, not finer (--tol decides at another threshold)")
    couplings = model_couplings(tree.couplings, {j.name: j.kind for j in tree.joints}, model_name, tree.file, joints)
    try:
        mechanism = Mechanism(name=tree.name, ground=ground, end_effector=end_effector, joints=tuple(joints),
                              description=description, length_unit=tree.length_unit, source=tree.file, precision=precision.value, couplings=couplings)
    except MechanismError as exc:
        raise MechanismFileError(exc.key, exc.message, file=tree.file) from None
    return ImportedRobot(mechanism, tuple(notes), tree.format, (tree.file,) + tree.files, tuple(closing))


def model_couplings(couplings: Iterable[TreeCoupling], kinds: Mapping[str, str], model_name: Mapping[str, str], file: str, joints: Sequence[Joint]) -> tuple[Coupling, ...]:
    """The model's couplings of the tree's ``couplings`` (each an MJCF joint or tendon equality, a URDF ``<mimic>``) on its ``joints`` (``model_name`` of each hinge and slide the mechanism holds; ``kinds`` of every tree joint).

    Raises
    ------
    MechanismFileError
        At the element's line: a joint that is no hinge or slide, one the
        mechanism does not hold (welded still), a malformed coupling, or one
        of slides and turns together.

    Examples
    --------
    >>> slides = [Joint(n, "P", ("g", n), axis=(0, 1, 0)) for n in ("r", "l")]
    >>> model_couplings((TreeCoupling("joint[r]/mimic", ("r", "l"), (1.0, -1.0), 5),), {"r": "slide", "l": "slide"}, {"r": "r", "l": "l"}, "g.urdf", slides)
    (Coupling(joints=('r', 'l'), coefficients=(1.0, -1.0)),)
    >>> model_couplings((TreeCoupling("joint[r]/mimic", ("r", "b"), (1.0, -1.0), 5),), {"r": "slide", "b": "ball"}, {"r": "r"}, "g.urdf", slides)
    Traceback (most recent call last):
    ...
    mobility.errors.MechanismFileError: g.urdf:5: joint[r]/mimic: couples joint 'b', a ball joint, not a hinge or slide; expected hinges and slides that move
    """
    out = []
    listed = tuple(couplings)
    for c in listed:
        for name in c.joints:
            if name not in model_name:
                kind = kinds.get(name)
                why = f"a {kind} joint, not a hinge or slide" if kind not in (None, "hinge", "slide") else "a joint the mechanism does not hold (welded or fixed)"
                raise MechanismFileError(c.key, f"couples joint {clipped(name)!r}, {why}; expected hinges and slides that move", file=file, line=c.line)
        try:
            out.append(Coupling(tuple(model_name[n] for n in c.joints), c.coefficients))
        except MechanismError as exc:
            raise MechanismFileError(c.key, exc.message, file=file, line=c.line) from None
    try:
        return require_couplings(out, joints)
    except MechanismError as exc:  # couplings[k]...: the element that wrote it
        c = listed[int(exc.key[len("couplings["):].split("]", 1)[0])]
        raise MechanismFileError(c.key, exc.message, file=file, line=c.line) from None


def at_line(line: int | None) -> str:
    """`` (line N)`` after what a note names, or nothing when the line is unknown.

    Examples
    --------
    >>> "joint A" + at_line(9), "joint A" + at_line(None)
    ('joint A (line 9)', 'joint A')
    """
    return f" (line {line})" if line is not None else ""


def unique_name(name: str, used: set[str]) -> str:
    """``name``, or ``name~2``, ``name~3``, ... : the first not in ``used`` (which then holds it).

    Examples
    --------
    >>> used = {"a", "a~2"}
    >>> unique_name("a", used), unique_name("b", used), sorted(used)
    ('a~3', 'b', ['a', 'a~2', 'a~3', 'b'])
    """
    out, k = name, 2
    while out in used:
        out, k = f"{name}~{k}", k + 1
    used.add(out)
    return out


def _free_joints_kept(tree: RobotTree, options: RobotOptions, notes: list[str]) -> set[str]:
    """The bodies whose free joint keeps its six freedoms, with a note for each: all with ``floating``, else those an equality
    ties to a body outside their subtree (fixing it would lock what it is welded to)."""
    free = {j.body: j for j in tree.joints if j.kind == "free"}
    if options.floating or not free:
        return set(free)
    ties = _ties_out_of_subtree(tree, set(free))
    for body, j in free.items():
        if body in ties:
            notes.append(f"free joint {clipped(j.name)}{at_line(j.line)} of body {clipped(body)} keeps its 6 freedoms: {ties[body]}")
        else:
            notes.append(f"free joint {clipped(j.name)}{at_line(j.line)} of body {clipped(body)} treated as fixed (use --floating to keep its 6 freedoms)")
    return set(ties)


def _ties_out_of_subtree(tree: RobotTree, free: set[str]) -> dict[str, str]:
    """For each body of ``free`` that an equality ties to a body outside its subtree, the equality (for a note)."""
    parents = {b.name: b.parent for b in tree.bodies}
    nearest: dict[str, str | None] = {}  # the nearest body of ``free`` at or above each body
    for item in tree.bodies:  # parents come first
        nearest[item.name] = item.name if item.name in free else nearest.get(item.parent) if item.parent else None

    def free_above(name: str) -> list[str]:
        out, here = [], nearest.get(name)
        while here is not None:
            out.append(here)
            above = parents.get(here)
            here = nearest.get(above) if above else None
        return out

    equalities = [(w.bodies, f"weld {clipped(w.name)}{at_line(w.line)}") for w in tree.welds]
    equalities += [(c.joint.links, f"{c.what} {clipped(c.joint.name)}{at_line(c.line)}") for c in tree.closures]
    ties: dict[str, str] = {}
    for (a, b), what in equalities:
        above_a, above_b = free_above(a), free_above(b)
        for body in above_a:
            if body not in above_b:
                ties.setdefault(body, f"{what} ties its subtree to {clipped(b)}, outside it")
        for body in above_b:
            if body not in above_a:
                ties.setdefault(body, f"{what} ties its subtree to {clipped(a)}, outside it")
    return ties


def _rigid_groups(tree: RobotTree, kept: set[str], notes: list[str]) -> _Groups:
    groups = _Groups({b.name: b.name for b in tree.bodies})
    moving = {j.body for j in tree.joints if j.kind != "free" or j.body in kept}
    for b in tree.bodies:
        if b.parent is not None and b.name not in moving:
            groups.union(b.parent, b.name)
    for w in tree.welds:
        if groups.find(w.bodies[0]) != groups.find(w.bodies[1]):
            notes.append(f"weld {clipped(w.name)}{at_line(w.line)} makes {clipped(w.bodies[0])} and {clipped(w.bodies[1])} one rigid link")
        groups.union(*w.bodies)
    return groups


def model_joint_names(j: TreeJoint) -> list[str]:
    """The names the model joints of one tree joint take (before clashes are resolved), in chain order.

    Examples
    --------
    >>> free = TreeJoint("root", "free", "base", (0, 0, 0))
    >>> ball = TreeJoint("s", "ball", "arm", (0, 0, 0), actuators=(BallActuator("m", (0, 0, 1)),))
    >>> model_joint_names(free), model_joint_names(ball)
    (['root.x', 'root.y', 'root.z', 'root'], ['s', 's.m'])
    """
    if j.kind == "free":
        return [f"{j.name}.{axis}" for axis in "xyz"] + [j.name]
    if j.kind == "ball" and j.actuators:
        return ball_chain_names(j.name, j.actuators)
    return [j.name]


def _model_joints(tree: RobotTree, j: TreeJoint, a: str, b: str, used: set[str], link_names: set[str]) -> list[Joint]:
    """The model joints of one tree joint from link ``a`` to link ``b`` (a free joint: P, P, P, S; a driven ball: R and U joints)."""
    try:
        kind = JOINT_KINDS[j.kind]
        if kind == "free":
            out, here = [], a
            for axis, letter in zip(np.eye(3), "xyz"):
                there = unique_name(f"{j.body}/{j.name}.{letter}", link_names)
                out.append(Joint(unique_name(f"{j.name}.{letter}", used), "P", (here, there), axis=tuple(axis), actuated=j.actuated))
                here = there
            out.append(Joint(unique_name(j.name, used), "S", (here, b), point=j.point, actuated=j.actuated))
            return out
        if kind == "S" and j.actuators:  # one input per actuator: a chain through the centre (mobility.io.robot_actuators)
            out, here, chain = [], a, ball_chain(j.name, j.point, j.actuators)
            for k, joint in enumerate(chain):
                there = b if k == len(chain) - 1 else unique_name(f"{j.body}/{joint.name}", link_names)
                out.append(replace(joint, name=unique_name(joint.name, used), links=(here, there)))
                here = there
            return out
        along, normal = (j.axis, None) if kind in ("R", "P") else (None, j.axis if kind == "E" else None)
        return [Joint(unique_name(j.name, used), kind, (a, b), axis=along, normal=normal, point=j.point, actuated=j.actuated)]
    except MechanismError as exc:
        raise MechanismFileError(f"joint[{clipped(j.name)}]", exc.message if not exc.key else f"{exc.key}: {exc.message}", file=tree.file, line=j.line) from None


def _farthest_link(tree: RobotTree, joints: list[Joint], ground: str, link) -> str:
    """The body's link farthest (in joints) from the ground; the last in file order among ties."""
    neighbours: dict[str, set[str]] = {}
    for j in joints:
        neighbours.setdefault(j.links[0], set()).add(j.links[1])
        neighbours.setdefault(j.links[1], set()).add(j.links[0])
    distance = {ground: 0}
    todo = deque([ground])
    while todo:
        here = todo.popleft()
        for n in sorted(neighbours.get(here, ())):
            if n not in distance:
                distance[n] = distance[here] + 1
                todo.append(n)
    best, best_distance = ground, 0
    for b in tree.bodies:
        d = distance.get(link(b.name), -1)
        if d >= best_distance and d > 0:
            best, best_distance = link(b.name), d
    return best


def rotation_tuple(matrix: np.ndarray) -> Rotation:
    """A 3x3 array as nested tuples of floats (for :class:`Body`)."""
    m = np.asarray(matrix, dtype=float).reshape(3, 3)
    return tuple(tuple(float(x) for x in row) for row in m)  # type: ignore[return-value]


def vector_tuple(v: Iterable[float]) -> Vector:
    """A 3-vector as a tuple of floats, checked finite."""
    x, y, z = (float(a) for a in v)
    if not all(math.isfinite(a) for a in (x, y, z)):
        raise MechanismError("", f"expected finite numbers, got {(x, y, z)!r}")
    return (x, y, z)


def _refuse_blank_names(tree: RobotTree) -> None:
    """Refuse a body, joint or closure named by blank characters only, at its line (as the project's format does: it would not read back)."""
    named = [("body", b.name, b.line, tree.file) for b in tree.bodies] + [("joint", j.name, j.line, tree.file) for j in tree.joints]
    named += [(c.what, c.joint.name, c.line, c.file or tree.file) for c in tree.closures]
    for what, name, line, file in named:
        if not name.strip():
            raise MechanismFileError(f"{what}[{name!r}]", "a name of blank characters only; expected a visible name", file=file, line=line)
