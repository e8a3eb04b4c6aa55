"""The mechanism model: links, joints and frames, as a frozen description.

Joints are the edges of the joint graph, links its nodes; joint geometry may
be written in any named frame (:meth:`Mechanism.world_joints` gives it in
``world``).  Each class checks itself on construction and raises
:class:`~mobility.errors.MechanismError` with the key path of the problem.

One module, longer than most, because the rules of the file format read best
beside the fields they check.

Example: :class:`Mechanism`.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field, fields, replace
from functools import cached_property
from types import MappingProxyType
from typing import Any, Iterable, Mapping, Sequence, cast

import numpy as np

from ..errors import MechanismError, RequestError, did_you_mean, name_list, shown_argument
from .couplings import Coupling, require_couplings
from .expected import Expected
from .frozen import read_only
from .tolerance import DEFAULT_TOLERANCE, ORTHONORMAL, PARALLEL_AXES, characteristic_scale
from .transforms import Transform, rotation_from_rpy
from .validation import (Vector, _listed, _not_bool, number_from_text, require_graph_names, require_ground_and_end_effector,
                         require_instance, require_integer, require_name, require_real, require_unique_names, require_vector)

__all__ = ["Coupling", "JOINT_TYPES", "JOINT_DOF", "JOINT_FIELDS", "Freedom", "FreedomTable", "Joint", "Frame", "Mechanism",
           "require_mechanism", "joint_freedoms", "WORLD"]

_FAR = sys.float_info.max / 1e8
"""Coordinates below this cannot overflow when a few are added (the bound of :meth:`Mechanism._frames_cannot_overflow`)."""

WORLD = "world"
"""Name of the global frame."""

JOINT_DOF: Mapping[str, int] = MappingProxyType({"R": 1, "P": 1, "H": 1, "C": 2, "U": 2, "S": 3, "E": 3})
"""Degrees of freedom of each joint type."""

JOINT_TYPES: Mapping[str, str] = MappingProxyType(
    {"R": "revolute", "P": "prismatic", "H": "helical", "C": "cylindrical", "U": "universal", "S": "spherical", "E": "planar"})
"""Joint type letters and their names."""

_IDENTITY = np.eye(3)
_ORTHONORMAL_LIMIT = ORTHONORMAL + 1e-5 * _IDENTITY  # |R R^T - I| entry by entry, as numpy.allclose(R R^T, I, atol=ORTHONORMAL)

JOINT_FIELDS: Mapping[str, tuple[tuple[str, ...], tuple[str, ...]]] = MappingProxyType({
    "R": (("axis", "point"), ()), "P": (("axis",), ("point",)), "H": (("axis", "point", "pitch"), ()), "C": (("axis", "point"), ()),
    "U": (("point", "axes"), ()), "S": (("point",), ()), "E": (("normal",), ("point",))})
"""Geometry fields each joint type takes: those it requires, and those it may also carry."""


@dataclass(frozen=True)
class Freedom:
    """One elementary freedom of a joint: ``"R"`` about the line through ``point`` along ``axis``, ``"P"`` along ``axis``, or ``"H"`` (``pitch`` length per radian).

    Examples
    --------
    >>> Freedom("P", (1.0, 0.0, 0.0)).point
    (0.0, 0.0, 0.0)
    """

    kind: str
    axis: Vector
    point: Vector = (0.0, 0.0, 0.0)
    pitch: float = 0.0


@dataclass(frozen=True)
class Joint:
    """A joint: an edge of the joint graph between two links.

    Parameters
    ----------
    type : str
        One of ``R P H C U S E`` (:data:`JOINT_TYPES`).
    links : tuple of two str
        Its motion is that of ``links[1]`` relative to ``links[0]``.
    axis, point, pitch, axes, normal
        Geometry as the type requires (the file format), written in ``frame``;
        directions are normalised.
    actuated : bool
        Whether the joint is driven (the actuation analysis).

    Examples
    --------
    >>> j = Joint("A", "R", ("ground", "crank"), axis=(0, 0, 2), point=(1, 0, 0))
    >>> j.axis, j.dof
    ((0.0, 0.0, 1.0), 1)
    >>> Joint("A", "R", ("ground", "crank"), axis=(0, 0, 1))
    Traceback (most recent call last):
    mobility.errors.MechanismError: point: missing; a joint of type R needs axis, point
    """

    name: str
    type: str
    links: tuple[str, str]
    axis: Vector | None = None
    point: Vector | None = None
    pitch: float | None = None
    axes: tuple[Vector, Vector] | None = None
    normal: Vector | None = None
    frame: str = WORLD
    actuated: bool = False

    def __post_init__(self) -> None:
        require_name(self.name, "name", "a non-empty string")
        if not isinstance(self.type, str) or self.type not in JOINT_DOF:
            raise MechanismError("type", f"unknown joint type {shown_argument(self.type)}; expected one of {', '.join(JOINT_DOF)}")
        links = tuple(self.links) if isinstance(self.links, (list, tuple)) else None
        if links is None or len(links) != 2 or not all(isinstance(x, str) and x for x in links):
            raise MechanismError("links", f"expected two link names, got {self.links!r}")
        for k, link in enumerate(links):
            require_name(link, f"links[{k}]", "a link name")
        if links[0] == links[1]:
            raise MechanismError("links", f"a joint must join two different links, got {links[0]!r} twice")
        object.__setattr__(self, "links", links)
        need, optional = JOINT_FIELDS[self.type]
        for key in ("axis", "point", "pitch", "axes", "normal"):
            value = getattr(self, key)
            if key in need and value is None:
                raise MechanismError(key, f"missing; a joint of type {self.type} needs {', '.join(need)}")
            if key not in need + optional and value is not None:
                takes = ", ".join(need) + (f", and optionally {', '.join(optional)}" if optional else "")
                raise MechanismError(key, f"not a field of a joint of type {self.type} (it takes {takes})")
        for key in ("axis", "normal", "point"):
            if getattr(self, key) is not None:
                object.__setattr__(self, key, require_vector(getattr(self, key), key, direction=key != "point"))
        if self.pitch is not None:
            try:
                pitch = number_from_text(self.pitch) if isinstance(self.pitch, str) else float(_not_bool(self.pitch))
            except OverflowError:
                raise MechanismError("pitch", "expected a finite number, got an integer too large for a float") from None
            except (TypeError, ValueError):
                raise MechanismError("pitch", f"expected a number, got {shown_argument(self.pitch)}") from None
            if not math.isfinite(pitch):
                raise MechanismError("pitch", f"expected a finite number, got {self.pitch!r}")
            object.__setattr__(self, "pitch", pitch)
        if self.axes is not None:
            axes = list(self.axes) if isinstance(self.axes, (list, tuple, np.ndarray)) else None
            if axes is None or len(axes) != 2:
                raise MechanismError("axes", "expected two directions [a1, a2]")
            a1 = require_vector(axes[0], "axes[0]", direction=True)
            a2 = require_vector(axes[1], "axes[1]", direction=True)
            sine = float(np.linalg.norm(np.cross(a1, a2)))
            if sine < PARALLEL_AXES:
                raise MechanismError("axes", "the two axes of a U joint must not be parallel")
            object.__setattr__(self, "axes", (a1, a2))
        require_name(self.frame, "frame", "a frame name")
        if not isinstance(self.actuated, (bool, np.bool_)):
            raise MechanismError("actuated", f"expected true or false, got {shown_argument(self.actuated)}")
        object.__setattr__(self, "actuated", bool(self.actuated))

    @property
    def dof(self) -> int:
        """Degrees of freedom of the joint."""
        return JOINT_DOF[self.type]

    def freedoms(self) -> tuple[Freedom, ...]:
        """The joint's elementary freedoms, in its own frame.

        Examples
        --------
        >>> [f.kind for f in Joint("c", "C", ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0)).freedoms()]
        ['R', 'P']
        """
        t = self.type
        # Each branch reads only the fields its type requires, which __post_init__ checked are set (JOINT_FIELDS).
        axis, point, pitch, axes = cast(Vector, self.axis), cast(Vector, self.point), cast(float, self.pitch), cast("tuple[Vector, Vector]", self.axes)
        if t == "R":
            return (Freedom("R", axis, point),)
        if t == "P":
            return (Freedom("P", axis),)
        if t == "H":
            return (Freedom("H", axis, point, pitch),)
        if t == "C":
            return (Freedom("R", axis, point), Freedom("P", axis))
        if t == "U":
            return (Freedom("R", axes[0], point), Freedom("R", axes[1], point))
        if t == "S":
            return tuple(Freedom("R", e, point) for e in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)))
        # E: two translations in the plane, one rotation about the normal.
        normal = cast(Vector, self.normal)
        n = np.asarray(normal)
        u1 = np.cross(n, np.eye(3)[int(np.argmin(np.abs(n)))])
        u1 /= np.linalg.norm(u1)
        u2 = np.cross(n, u1)
        p = self.point if self.point is not None else (0.0, 0.0, 0.0)
        return (Freedom("P", tuple(u1)), Freedom("P", tuple(u2)), Freedom("R", normal, p))

    def transformed(self, tf: Transform, frame: str = WORLD) -> "Joint":
        """The same joint with its geometry mapped by ``tf`` and written in ``frame``."""
        changes: dict[str, Any] = {"frame": frame}
        floats = lambda v: tuple(float(x) for x in v)  # noqa: E731
        with np.errstate(over="ignore", invalid="ignore"):  # a point beyond the largest float is refused by the Joint itself
            for key in ("axis", "normal"):
                if getattr(self, key) is not None:
                    changes[key] = floats(tf.apply_vector(getattr(self, key)))
            if self.point is not None:
                changes["point"] = floats(tf.apply_point(self.point))
            if self.axes is not None:
                changes["axes"] = tuple(floats(tf.apply_vector(a)) for a in self.axes)
        return replace(self, **changes)


@dataclass(frozen=True)
class Frame:
    """A named frame: ``x_parent = rotation @ x_frame + origin``.

    Examples
    --------
    >>> Frame("tool", origin=(0, 0, 1)).transform.apply_point((1, 0, 0)).tolist()
    [1.0, 0.0, 1.0]
    """

    name: str
    origin: Vector = (0.0, 0.0, 0.0)
    rotation: tuple[Vector, Vector, Vector] = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    parent: str = WORLD

    def __post_init__(self) -> None:
        require_name(self.name, "name", "a frame name")
        object.__setattr__(self, "origin", require_vector(self.origin, "origin"))
        try:
            rot = np.asarray(self.rotation, dtype=float)
        except (TypeError, ValueError, OverflowError):  # text, a ragged nesting, an integer beyond the floats
            rot = None
        if rot is None or rot.shape != (3, 3) or not np.isfinite(rot).all():
            raise MechanismError("rotation", "expected a 3x3 matrix of finite numbers")
        if (np.abs(rot @ rot.T - _IDENTITY) > _ORTHONORMAL_LIMIT).any() or np.linalg.det(rot) < 0:
            raise MechanismError("rotation", "expected a proper rotation matrix")
        object.__setattr__(self, "rotation", tuple(map(tuple, rot.tolist())))
        require_name(self.parent, "parent", "a frame name")

    @staticmethod
    def from_rpy(name: str, origin: Iterable[float] = (0, 0, 0), rpy: Iterable[float] = (0, 0, 0), parent: str = WORLD) -> "Frame":
        """A frame from roll-pitch-yaw angles **in radians** (``R = Rz(y) Ry(p) Rx(r)``).

        Unlike a mechanism file (degrees unless ``units.angle`` says otherwise),
        this takes **radians** (:func:`numpy.radians`).  ``origin`` is in the
        parent; a bad ``origin`` or ``rpy`` raises :class:`~mobility.errors.MechanismError`.

        Examples
        --------
        A yaw of 90 degrees, given in radians:

        >>> f = Frame.from_rpy("leg", (1, 0, 0), np.radians([0, 0, 90]))
        >>> [round(float(x), 12) + 0.0 for x in f.transform.apply_point((1, 0, 0))]
        [1.0, 1.0, 0.0]
        """
        rpy = require_vector(_listed(rpy), "rpy")
        rotation = cast("tuple[Vector, Vector, Vector]", tuple(map(tuple, rotation_from_rpy(rpy))))  # a 3x3 matrix
        return Frame(name, require_vector(_listed(origin), "origin"), rotation, parent)

    @property
    def transform(self) -> Transform:
        """The transform from this frame to its parent."""
        return Transform(np.array(self.rotation), np.array(self.origin))


@dataclass(frozen=True, eq=False)
class FreedomTable:
    """The elementary freedoms of every joint, in the global frame, as arrays.

    Row ``k`` is one :class:`Freedom` (``prismatic``, ``axes``, ``points``,
    ``pitches``); joint ``j`` owns rows ``offsets[j]:offsets[j + 1]``.
    ``located`` holds the points of the joints that have one (all but P and
    point-less E), ``located_joints`` their joint indices and ``located_links``
    their two links (indices in :attr:`Mechanism.links`);
    ``end_effector_points`` those on the end effector.

    Examples
    --------
    >>> m = Mechanism("m", "g", "b", (Joint("c", "C", ("g", "b"), axis=(0, 0, 1), point=(0, 0, 0)),))
    >>> m.freedom_table.prismatic.tolist(), m.freedom_table.offsets
    ([False, True], (0, 2))
    """

    prismatic: np.ndarray
    axes: np.ndarray
    points: np.ndarray
    pitches: np.ndarray
    offsets: tuple[int, ...]
    located: np.ndarray
    end_effector_points: np.ndarray
    located_joints: np.ndarray
    located_links: np.ndarray


@dataclass(frozen=True)
class Mechanism:
    """A mechanism: a joint graph with geometry at one pose.

    Parameters
    ----------
    name, ground, end_effector : str
        The ground is fixed; the end effector's freedom is reported.
    joints : tuple of Joint
        At least one.
    description, length_unit : str
        The unit is a label only (results do not depend on it).
    source : str
        Where it came from (a file path), for messages.
    written_at : mapping of str to (str, int or None)
        By joint name, the key path (``limbs[0].joints[2]``) and 1-based line
        the file wrote it at, for messages (empty when built in code).
    couplings : tuple of Coupling
        Linear relations between joint rates (:mod:`mobility.core.couplings`).
    precision : float or None
        How precise the file's geometry is relative to its size
        (:mod:`mobility.io.precision`; ``None``: exact); ranks are never decided
        finer (:func:`~mobility.core.tolerance.file_tolerance`).
        ``written_at`` and ``precision`` are not part of the value.

    Examples
    --------
    A slider-crank, built in code (the same as a file's ``joints`` list):

    >>> x, z = (1, 0, 0), (0, 0, 1)
    >>> m = Mechanism("slider-crank", ground="ground", end_effector="slider", joints=(
    ...     Joint("A", "R", ("ground", "crank"), axis=z, point=(0, 0, 0)),
    ...     Joint("B", "R", ("crank", "rod"), axis=z, point=(1, 1, 0)),
    ...     Joint("C", "R", ("rod", "slider"), axis=z, point=(3, 0, 0)),
    ...     Joint("D", "P", ("slider", "ground"), axis=x)))
    >>> sorted(m.links), m.freedom_count
    (['crank', 'ground', 'rod', 'slider'], 4)
    """

    name: str
    ground: str
    end_effector: str
    joints: tuple[Joint, ...]
    frames: tuple[Frame, ...] = ()
    description: str = ""
    length_unit: str = ""
    expected: Expected | None = None
    source: str = ""
    written_at: Mapping[str, tuple[str, int | None]] = field(default_factory=dict, compare=False, repr=False)
    couplings: tuple[Coupling, ...] = ()
    precision: float | None = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        if self.precision is not None:
            try:
                p = require_real(self.precision, "")
                if p < 0.0:
                    raise RequestError()
            except RequestError:
                raise MechanismError("precision", f"expected a finite number >= 0 or None, got {self.precision!r}") from None
            object.__setattr__(self, "precision", p)
        for key, kind in (("joints", Joint), ("frames", Frame)):
            value = getattr(self, key)
            if isinstance(value, (str, bytes, dict)) or not isinstance(value, Iterable):
                raise MechanismError(key, f"expected a sequence of {kind.__name__}s, got {type(value).__name__}")
            object.__setattr__(self, key, tuple(value))
            for i, item in enumerate(getattr(self, key)):
                if not isinstance(item, kind):
                    raise MechanismError(f"{key}[{i}]", f"expected a {kind.__name__}, got {type(item).__name__}")
        require_graph_names(self, "link")
        if not self.joints:
            raise MechanismError("joints", "expected at least one joint")
        require_unique_names(self.joints, "joints", "joint")
        if self.expected is not None and not isinstance(self.expected, Expected):
            raise MechanismError("expected", f"expected an Expected or None, got {type(self.expected).__name__}")
        try:
            if not isinstance(self.written_at, Mapping) or not all(
                isinstance(k, str) and isinstance(v, tuple) and len(v) == 2 and isinstance(v[0], str) for k, v in self.written_at.items()
            ):
                raise RequestError()
            for _, line in self.written_at.values():
                if line is not None:
                    require_integer(line, "")
        except RequestError:
            raise MechanismError("written_at", "expected a mapping of joint names to (key path, line or None)") from None
        frame_index: dict[str, int] = {}
        for i, f in enumerate(self.frames):
            if f.name == WORLD:
                raise MechanismError(f"frames.{f.name}", f"the name {WORLD!r} is reserved for the global frame")
            if f.name in frame_index:
                raise MechanismError(f"frames.{f.name}", "duplicate frame name")
            frame_index[f.name] = i
        for f in self.frames:
            if f.parent != WORLD and f.parent not in frame_index:
                raise MechanismError(f"frames.{f.name}.parent", f"unknown frame {f.parent!r}; expected {WORLD!r} or one of: {name_list(frame_index)}")
        for f in self.frames:  # cycles among parents
            chain = [f.name]
            cur = f
            while cur.parent != WORLD:
                if cur.parent in chain:
                    raise MechanismError(f"frames.{f.name}.parent", "cycle among frame parents: " + " -> ".join(chain + [cur.parent]))
                chain.append(cur.parent)
                cur = self.frames[frame_index[cur.parent]]
        for i, j in enumerate(self.joints):
            if j.frame != WORLD and j.frame not in frame_index:
                raise MechanismError(f"joints[{i}].frame", f"unknown frame {j.frame!r}; expected {WORLD!r} or one of: {name_list(frame_index)}")
        links = self.links
        require_ground_and_end_effector(self, links, "link", "joint")
        unreached = self._links_not_connected_to_ground()
        if self.end_effector in unreached:
            raise MechanismError("end_effector", f"link {self.end_effector!r} is not connected to the ground {self.ground!r} through joints")
        if unreached:
            raise MechanismError("joints", f"links not connected to the ground {self.ground!r}: {name_list(sorted(unreached))}")
        if self.frames and not self._frames_cannot_overflow():
            self.world_joints  # noqa: B018 - every joint's geometry must stay finite in the global frame
        if any(j.type == "H" for j in self.joints):
            self._require_resolved_pitches()
        object.__setattr__(self, "couplings", require_couplings(self.couplings, self.joints))

    def _require_resolved_pitches(self) -> None:
        """Refuse a helical pitch ``h`` so much larger than the joint points' spread ``d`` that no scale resolves both.

        The length is then ``L = sqrt(d h)`` (:func:`~mobility.core.tolerance.characteristic_scale`), and the screw's
        turn and the points' offsets are both ``sqrt(d / h)`` of it: below ``Tolerance.rank`` (``h / d`` above 1e16) round-off.
        """
        table = self.freedom_table
        pitches = np.abs(table.pitches)
        largest = float(pitches.max())
        length = characteristic_scale(table.located, pitches=pitches[pitches != 0.0])[1]
        if largest * DEFAULT_TOLERANCE.rank <= length:
            return
        spread = characteristic_scale(table.located)[1]  # the points do not coincide, or the length would be the pitch
        index = int(np.searchsorted(table.offsets, int(np.argmax(pitches)), side="right")) - 1
        raise MechanismError(
            f"joints[{index}].pitch",
            f"pitch {largest:.6g} is {largest / spread:.1e} times the spread of the joint points {spread:.3g} (their RMS distance from their centroid): "
            f"beyond {DEFAULT_TOLERANCE.rank**-2:.0e} no scale resolves both the screw's rotation and the points' offsets; "
            "write the points that are meant to coincide as one point, or bring the pitch and the spread within that ratio")

    def _frames_cannot_overflow(self) -> bool:
        """Whether no joint can leave the floats in the global frame: the cheap bound (origins and points add; rotations keep lengths)."""
        origin = max(max(abs(x) for x in f.origin) for f in self.frames)
        point = max((max(abs(x) for x in j.point) for j in self.joints if j.point is not None), default=0.0)
        return 2.0 * (origin * (len(self.frames) + 1) + point) < _FAR

    def _links_not_connected_to_ground(self) -> set[str]:
        neighbours: dict[str, set[str]] = {}
        for j in self.joints:
            a, b = j.links
            neighbours.setdefault(a, set()).add(b)
            neighbours.setdefault(b, set()).add(a)
        seen = {self.ground}
        todo = [self.ground]
        while todo:
            new = neighbours[todo.pop()] - seen
            seen |= new
            todo.extend(new)
        return set(neighbours) - seen

    @cached_property
    def links(self) -> tuple[str, ...]:
        """Link names, in order of first appearance."""
        return tuple(dict.fromkeys(name for j in self.joints for name in j.links))

    @cached_property
    def freedom_count(self) -> int:
        """Sum of the joints' DOF."""
        return sum(j.dof for j in self.joints)

    def joint(self, name: str) -> Joint:
        """The joint called ``name`` (:class:`~mobility.errors.RequestError` when none is).

        Examples
        --------
        >>> Mechanism("s", "g", "b", (Joint("p", "P", ("g", "b"), axis=(0, 0, 1)),)).joint("p").type
        'P'
        """
        for j in self.joints:
            if j.name == name:
                return j
        raise RequestError(f"no joint named {name!r}; the joints are {name_list(j.name for j in self.joints)}")

    def frame_transform(self, name: str) -> Transform:
        """Transform from frame ``name`` to the global frame (:class:`~mobility.errors.RequestError` when none is).

        Examples
        --------
        >>> import mobility
        >>> mobility.load("mechanisms/3prs.yaml").frame_transform("world").translation.tolist()
        [0.0, 0.0, 0.0]
        """
        transforms = self._frame_transforms
        if not isinstance(name, str) or name not in transforms:
            raise RequestError(f"no frame named {shown_argument(name)}{did_you_mean(name, transforms)}; the frames are {name_list(transforms)}", caller="frame_transform")
        return transforms[name]

    @cached_property
    def _frame_transforms(self) -> dict[str, Transform]:
        by_name = {f.name: f for f in self.frames}
        out: dict[str, Transform] = {WORLD: Transform.identity()}
        for f in self.frames:  # each chain of parents walked once, without recursion (a chain may be long)
            chain = []
            name = f.name
            while name not in out:
                chain.append(name)
                name = by_name[name].parent
            for name in reversed(chain):
                frame = by_name[name]
                with np.errstate(over="ignore", invalid="ignore"):
                    tf = out[frame.parent].compose(frame.transform)
                if not (np.all(np.isfinite(tf.translation)) and np.all(np.isfinite(tf.rotation))):
                    raise MechanismError(f"frames.{name}.origin", "its origin in the global frame is not finite: the origins of its chain of frames add up beyond the largest float")
                out[name] = tf
        return out

    @cached_property
    def world_joints(self) -> tuple[Joint, ...]:
        """The joints with their geometry in the global frame (``frame`` ``"world"``; :attr:`joints` keeps the original)."""
        transforms = self._frame_transforms  # a frame whose origin is not finite is named as such, before any joint
        out = []
        for i, j in enumerate(self.joints):
            if j.frame == WORLD:
                out.append(j)
                continue
            try:
                out.append(j.transformed(transforms[j.frame]))
            except MechanismError as exc:
                raise MechanismError(f"joints[{i}].{exc.key}", f"{exc.message} once written in the global frame (from frame {j.frame!r})") from None
        return tuple(out)

    @cached_property
    def freedom_table(self) -> FreedomTable:
        """Every joint's elementary freedoms in the global frame, as arrays (computed once)."""
        prismatic, axes, points, pitches, offsets = [], [], [], [], [0]
        for j in self.world_joints:
            for f in j.freedoms():
                prismatic.append(f.kind == "P")
                axes.append(f.axis)
                points.append(f.point)
                pitches.append(f.pitch)
            offsets.append(len(axes))
        link_index = {name: i for i, name in enumerate(self.links)}
        located, located_joints, located_links = [], [], []
        for index, j in enumerate(self.world_joints):
            if j.point is not None:
                located.append(j.point)
                located_joints.append(index)
                located_links.append((link_index[j.links[0]], link_index[j.links[1]]))
        ee = [j.point for j in self.world_joints if j.point is not None and self.end_effector in j.links]
        p, ax, pt, h, loc, eep, lj, ll = read_only((
            np.array(prismatic), np.array(axes, dtype=float), np.array(points, dtype=float), np.array(pitches, dtype=float),
            np.array(located, dtype=float).reshape(-1, 3), np.array(ee, dtype=float).reshape(-1, 3),
            np.array(located_joints, dtype=int), np.array(located_links, dtype=int).reshape(-1, 2)), copy=False)
        return FreedomTable(p, ax, pt, h, tuple(offsets), loc, eep, lj, ll)

    def __getstate__(self) -> dict[str, Any]:
        """The fields only: what a mechanism computed of itself (its freedom table, joint twists...) is computed again after unpickling, read-only."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def joint_key(self, index: int, key: str = "") -> tuple[str, int | None]:
        """The key path of joint ``index`` (with ``key`` below it, such as ``"point"``) as its file wrote it, and its line.

        Otherwise (built in code) its place in :attr:`joints`, without a line.

        Examples
        --------
        >>> import mobility
        >>> mobility.load("mechanisms/3prs.yaml").joint_key(4, "point")
        ('limbs[0].joints[1].point', 35)
        >>> Mechanism("slide", "g", "s", (Joint("p", "P", ("g", "s"), axis=(0, 0, 1)),)).joint_key(0, "axis")
        ('joints[0].axis', None)
        """
        written, line = self.written_at.get(self.joints[index].name, (f"joints[{index}]", None))
        return (f"{written}.{key}" if key else written), line

    def replace(self, **changes: Any) -> "Mechanism":
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)


def require_mechanism(value: object, caller: str) -> Mechanism:
    """``value`` when it is a :class:`Mechanism`, else a :class:`~mobility.errors.RequestError` naming ``caller``.

    Examples
    --------
    >>> require_mechanism("four_bar.yaml", "analyze")
    Traceback (most recent call last):
    mobility.errors.RequestError: analyze: expected a Mechanism (from mobility.load or built in code), got str
    """
    return require_instance(value, Mechanism, caller, "mobility.load")


def joint_freedoms(mechanism: "Mechanism", names: Sequence[str], key: str = "actuated") -> list[tuple[int, int, str]]:
    """``(joint index, freedom, label)`` of every input named: a joint gives each of its freedoms, ``NAME.k`` its freedom ``k``.

    Freedoms are numbered from 0, as reports label them (``S1.0`` to ``S1.2``);
    a one-freedom joint's label is its name.  An unknown name, a ``k`` out of
    range or a freedom named twice raises :class:`~mobility.errors.MechanismError`
    under ``key``.

    Examples
    --------
    >>> m = Mechanism("m", "g", "b", (Joint("S", "S", ("g", "a"), point=(0, 0, 0)), Joint("P", "P", ("a", "b"), axis=(1, 0, 0))))
    >>> [label for _, _, label in joint_freedoms(m, ["S", "P"])], joint_freedoms(m, ["S.2"])
    (['S.0', 'S.1', 'S.2', 'P'], [(0, 2, 'S.2')])
    >>> joint_freedoms(m, ["S.3"])
    Traceback (most recent call last):
    mobility.errors.MechanismError: actuated: 'S.3': joint 'S' has freedoms S.0 to S.2
    """
    index = {j.name: i for i, j in enumerate(mechanism.joints)}
    out: list[tuple[int, int, str]] = []
    seen: dict[tuple[int, int], str] = {}
    for name in names:
        if name in index:
            j = index[name]
            dof = mechanism.joints[j].dof
            chosen = [(j, k, name if dof == 1 else f"{name}.{k}") for k in range(dof)]
        else:
            base, dot, sub = name.rpartition(".")
            if not dot or base not in index:
                raise MechanismError(key, f"unknown joint {name!r}; expected one of: {name_list(index)} (JOINT.k names freedom k, from 0, of a multi-freedom joint)")
            j = index[base]
            dof = mechanism.joints[j].dof
            if dof == 1:
                raise MechanismError(key, f"{name!r}: joint {base!r} has one freedom; name it {base!r}")
            if not (sub.isascii() and sub.isdigit() and int(sub) < dof):
                raise MechanismError(key, f"{name!r}: joint {base!r} has freedoms {base}.0 to {base}.{dof - 1}")
            chosen = [(j, int(sub), f"{base}.{int(sub)}")]
        for j, k, label in chosen:
            if (j, k) in seen:
                raise MechanismError(key, f"{name!r} names freedom {label!r} again (given by {seen[(j, k)]!r}); name each input once")
            seen[(j, k)] = name
        out += chosen
    return out
