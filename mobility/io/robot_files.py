"""Robot description files (MJCF, URDF): recognise them and read them into a mechanism.

:func:`robot_format` tells a robot description by its extension, else its first element (``<mujoco>``, ``<robot>``);
:func:`read_robot` reads one, adds the loop closures asked for (for URDF and MJCF alike, ``docs/robot-files.md``:
:func:`with_close_pairs`, :func:`with_closures_file`) and builds the mechanism with the notes of the reading.

Examples
--------
>>> import tempfile, os
>>> text = '''<robot name="slider">
...   <link name="rail"/> <link name="carriage"/>
...   <joint name="slide" type="prismatic">
...     <parent link="rail"/> <child link="carriage"/> <axis xyz="0 0 2"/>
...   </joint>
... </robot>'''
>>> with tempfile.NamedTemporaryFile("w", suffix=".urdf", delete=False) as f:
...     _ = f.write(text)
>>> robot_format(f.name)
'urdf'
>>> robot = read_robot(f.name)
>>> m = robot.mechanism
>>> m.ground, m.end_effector, m.joints[0].type, m.joints[0].axis
('rail', 'carriage', 'P', (0.0, 0.0, 1.0))
>>> robot.notes
('end effector: carriage (the body farthest from the ground rail; choose another with --end-effector)',)
>>> os.unlink(f.name)
"""

from __future__ import annotations

from dataclasses import fields, replace
from pathlib import Path
from typing import Any, Iterable, Mapping

import numpy as np

from ..core.model import WORLD, Joint
from ..core.transforms import Transform
from ..core.validation import require_bool
from ..errors import MechanismFileError, RequestError, clipped, counted, did_you_mean
from .files import file_name
from .mechanism_reader import MechanismReader
from .robot_tree import Closure, ImportedRobot, RobotOptions, RobotTree, build_mechanism, model_joint_names, unique_name
from .xml_source import read_xml, root_tag
from .yaml_source import parse_yaml, read_text

__all__ = ["robot_format", "is_robot_file", "read_robot", "require_no_robot_options", "RobotOptions", "ImportedRobot", "ROBOT_SUFFIXES",
           "with_close_pairs", "with_closures_file", "close_pairs", "CLOSURES_KEYS"]

ROBOT_SUFFIXES = {".urdf": "urdf", ".mjcf": "mjcf", ".xml": None}
"""Extensions of robot description files (``.xml``: MJCF or URDF, by its first element)."""

_ROOTS = {"mujoco": "mjcf", "robot": "urdf"}


def robot_format(path: str | Path) -> str | None:
    """``"mjcf"``, ``"urdf"``, or ``None`` for a file that is not a robot description: by extension, else its first element."""
    suffix = Path(file_name(path, "robot_format")).suffix.lower()
    if suffix in (".yaml", ".yml"):
        return None
    if ROBOT_SUFFIXES.get(suffix):
        return ROBOT_SUFFIXES[suffix]
    return _ROOTS.get(root_tag(path) or "")


def is_robot_file(path: str | Path) -> bool:
    """Whether ``path`` is to be read as a robot description: an XML extension or XML content."""
    suffix = Path(file_name(path, "is_robot_file")).suffix.lower()
    return suffix not in (".yaml", ".yml") and (suffix in ROBOT_SUFFIXES or root_tag(path) is not None)


def read_robot(path: str | Path, options: RobotOptions | None = None, **option_values: Any) -> ImportedRobot:
    """Read an MJCF or URDF file into a mechanism, with the notes of the reading.

    ``option_values`` are fields of :class:`~mobility.io.robot_tree.RobotOptions`, overriding ``options``.

    Raises
    ------
    MechanismFileError
        When the file is not MJCF or URDF, or cannot be read (file, line, element).
    MissingExtraError
        For an MJCF file when the ``mujoco`` package is not installed.
    RequestError
        When ``path`` is not a file name, or an option is unknown, of the wrong
        type, or an empty body name.
    """
    file_name(path, "read_robot")
    options = _options(options, option_values)
    fmt = robot_format(path)
    if fmt is None and Path(path).suffix.lower() in (".yaml", ".yml"):
        raise MechanismFileError("", "a mechanism file (YAML), not a robot description; expected MJCF or URDF (read it with mobility.load)", file=str(path))
    if fmt is None:  # no known extension, and a first element not found early (an encoding read only in full)
        doc = read_xml(path)  # a file that cannot be read, or malformed XML, says so here
        fmt = _ROOTS.get(doc.root.tag)
        if fmt is None:
            raise doc.fail(doc.root, doc.root.tag, "not a robot description; expected MJCF (<mujoco>) or URDF (<robot>), or a mechanism file (.yaml)")
    if fmt == "mjcf":
        from .mjcf import read_mjcf  # imports mujoco only when asked

        tree = read_mjcf(path)
    else:
        from .urdf import read_urdf

        tree = read_urdf(path)
    if options.close:
        tree = with_close_pairs(tree, options.close)
    if options.closures is not None:
        tree = with_closures_file(tree, options.closures)
    return build_mechanism(_closures_named_apart(tree), options)


def _closures_named_apart(tree: RobotTree) -> RobotTree:
    """The tree with each closing joint named apart from the joints and the other closing joints (``~2``, ``~3``, ...: MuJoCo
    keeps connects and joints apart, the joint graph cannot), with a note for each renamed.

    Examples
    --------
    >>> from mobility.core.model import Joint
    >>> from mobility.io.robot_tree import Body, Closure, TreeJoint
    >>> tree = RobotTree("r", "r.xml", "MJCF", (Body("world", None), Body("a", "world"), Body("b", "a")),
    ...                  (TreeJoint("A", "hinge", "a", (0, 0, 0), (0, 0, 1)),),
    ...                  (Closure(Joint("A", "S", ("a", "b"), point=(0, 0, 0)), "connect", 9),))
    >>> renamed = _closures_named_apart(tree)
    >>> renamed.closures[0].joint.name, renamed.notes
    ('A~2', ('connect A (line 9) is named like another joint: it is joint A~2 of the mechanism',))
    """
    if not tree.closures:
        return tree
    names = [name for j in tree.joints for name in model_joint_names(j)]
    taken: set[str] = set()
    for name in names:  # in the order the mechanism names them, each clash made ~2, ~3, ...
        unique_name(name, taken)
    taken.update(names)
    closures, notes = [], []
    for c in tree.closures:
        name = unique_name(c.joint.name, taken)
        if name != c.joint.name:
            where = f" ({c.file + ', ' if c.file else ''}line {c.line})" if c.line is not None else ""
            notes.append(f"{c.what} {clipped(c.joint.name)}{where} is named like another joint: it is joint {clipped(name)} of the mechanism")
            c = replace(c, joint=replace(c.joint, name=name))
        closures.append(c)
    return replace(tree, closures=tuple(closures), notes=tree.notes + tuple(notes))


def require_no_robot_options(path: str | Path, option_values: dict[str, Any], spelling: Mapping[str, str] | None = None) -> None:
    """Refuse the robot options given for a mechanism file (YAML), options left at their defaults passing; ``spelling`` names
    them as the caller's user wrote them, in its order (the command line's ``--ground``), else by keyword, sorted.

    Raises
    ------
    RequestError
        Naming the options given (or the first unknown or wrong one).

    Examples
    --------
    >>> require_no_robot_options("arm.yaml", {"ground": None, "close": []})
    >>> require_no_robot_options("arm.yaml", {"ground": "base", "floating": True})
    Traceback (most recent call last):
    ...
    mobility.errors.RequestError: floating, ground: options of robot description files (MJCF, URDF), not of the mechanism file arm.yaml
    """
    options, default = _options(None, option_values), RobotOptions()
    given = sorted(f.name for f in fields(RobotOptions) if getattr(options, f.name) != getattr(default, f.name))
    if given:
        named = [spelling[k] for k in spelling if k in given] if spelling else given
        raise RequestError(f"options of robot description files (MJCF, URDF), not of the mechanism file {path}", argument=", ".join(named))


def _options(options: RobotOptions | None, values: dict[str, Any]) -> RobotOptions:
    """``options`` with ``values`` applied, each field checked: a :class:`RequestError` naming the first wrong one."""
    if options is not None and not isinstance(options, RobotOptions):
        raise RequestError(argument="options", expected="a RobotOptions or None", got=type(options).__name__)
    known = {f.name for f in fields(RobotOptions)}
    unknown = sorted(set(values) - known)
    if unknown:
        raise RequestError(f"unknown option {unknown[0]!r} for a robot description; expected one of: {', '.join(sorted(known))}")
    out = replace(options or RobotOptions(), **values)
    for key in ("ground", "end_effector"):
        name = getattr(out, key)
        if name is not None and not isinstance(name, str):
            raise RequestError(argument=key, expected="a body name (str)", got=type(name).__name__)
        if name == "":  # not the same as leaving it out (the default body)
            raise RequestError("an empty body name; expected the name of a body (or leave the option out for the default)", argument=key)
    flags = {}
    for key in ("floating", "ignore_unsupported"):
        flag = getattr(out, key)
        flags[key] = flag is not None and require_bool(flag, argument=key, got=type(flag).__name__)  # None: the default, False
    closures = None if out.closures is None else file_name(out.closures, "closures")
    if closures == "":
        raise RequestError("an empty file name; expected the name of a closures file (or leave the option out)", argument="closures")
    return replace(out, close=close_pairs(out.close), closures=closures, floating=flags["floating"], ignore_unsupported=flags["ignore_unsupported"])


CLOSURES_KEYS = ("description", "joints")
"""Keys of a closures side file."""


def close_pairs(value: object) -> tuple[tuple[str, str], ...]:
    """``value`` as pairs of body names ``((A, B), ...)`` (``None``: none), else a :class:`~mobility.errors.RequestError`
    naming ``close`` or ``close[k]`` (a bare pair ``("A", "B")`` too).

    Examples
    --------
    >>> close_pairs([["a", "b"]])
    (('a', 'b'),)
    >>> close_pairs(("a", "b"))
    Traceback (most recent call last):
    ...
    mobility.errors.RequestError: close[0]: expected a pair of body names (A, B), got str (one pair is written [(A, B)])
    """
    if value is None:
        return ()
    if not isinstance(value, (list, tuple)):
        raise RequestError(caller="close", expected="a list of pairs of body names [(A, B), ...]", got=type(value).__name__)
    pairs = []
    for k, pair in enumerate(value):
        if isinstance(pair, (list, tuple)) and len(pair) == 2 and all(isinstance(name, str) for name in pair):
            pairs.append((pair[0], pair[1]))
            continue
        if not isinstance(pair, (list, tuple)):
            got = type(pair).__name__
            if len(value) == 2 and all(isinstance(name, str) for name in value):
                got += " (one pair is written [(A, B)])"
        elif len(pair) != 2:
            got = f"{len(pair)} item{'s' if len(pair) != 1 else ''}"
        else:
            got = f"a pair of {type(pair[0]).__name__} and {type(pair[1]).__name__}"
        raise RequestError(argument=f"close[{k}]", expected="a pair of body names (A, B)", got=got)
    return tuple(pairs)


def with_close_pairs(tree: RobotTree, pairs: Iterable[tuple[str, str]]) -> RobotTree:
    """The tree with a spherical joint at the origin of ``A`` for each pair ``(A, B)`` (bodies whose origins coincide).

    Raises
    ------
    MechanismFileError
        When a name is not a body of the tree (key ``close``).
    RequestError
        When ``pairs`` is not a list of pairs of names (:func:`close_pairs`).

    Examples
    --------
    >>> from mobility.io.robot_tree import Body, TreeJoint
    >>> tree = RobotTree("two arms", "t.urdf", "URDF", bodies=(
    ...     Body("base", None), Body("a", "base", origin=(1, 0, 0)), Body("b", "base", origin=(1, 0, 0))))
    >>> closed = with_close_pairs(tree, [("a", "b")])
    >>> [(c.joint.type, c.joint.links, c.joint.point) for c in closed.closures]
    [('S', ('a', 'b'), (1.0, 0.0, 0.0))]
    """
    closures, notes, gaps = [], [], []
    for a, b in close_pairs(pairs):
        first, second = tree.body(a, "close"), tree.body(b, "close")
        if first.name == second.name:
            raise MechanismFileError("close", f"expected two different bodies, got {a!r} twice", file=tree.file)
        gap = float(np.linalg.norm(np.subtract(first.origin, second.origin)))
        gaps.append(gap)
        name = f"close_{a}_{b}"
        closures.append(Closure(Joint(name, "S", (a, b), point=first.origin), "--close"))
        notes.append(f"--close {a} {b}: spherical joint {name} at the origin of {a}; the origin of {b} is {gap:.3g} {tree.length_unit} from it")
    return tree.with_closures(closures, notes=notes, gaps=gaps)


def with_closures_file(tree: RobotTree, path: str | Path) -> RobotTree:
    """The tree with the closing joints of a side file.

    The file holds ``joints`` as in a mechanism file, their ``links`` body names, a ``frame`` naming a body whose
    frame at the pose the geometry is written in (default: global)::

          # closures of four_bar.urdf
          joints:
            - {name: C, type: R, links: [coupler, rocker], axis: [0, 0, 1], point: [3, 0.5, 0], frame: coupler}

    Raises
    ------
    MechanismFileError
        On a malformed file, an unknown body or frame, or bad joint geometry (at its line and key).
    RequestError
        When ``path`` is not a file name.
    """
    file = file_name(path, "closures")
    data, positions = parse_yaml(read_text(path), file)
    reader = MechanismReader(file, positions)
    doc = reader.record(data, (), "a closures file", CLOSURES_KEYS, ("joints",), described="closing joints: a mapping with joints")
    joints, sources = reader.joints(doc["joints"], ("joints",), {}, None)
    if not joints:
        raise reader.fail(("joints",), "expected at least one closing joint (a closures file that closes nothing is a mistake)")
    bodies = {b.name: b for b in tree.bodies}
    closures = []
    for joint, source in zip(joints, sources):
        for k, link in enumerate(joint.links):
            if link not in bodies:
                known = ", ".join(list(bodies)[:12])
                raise reader.fail(source + ("links", k), f"no body named {link!r}{did_you_mean(link, bodies)} in {Path(tree.file).name}; expected one of: {known}")
        if joint.frame != WORLD:
            if joint.frame not in bodies:
                raise reader.fail(source + ("frame",), f"unknown frame {joint.frame!r}; expected {WORLD!r} or a body of {Path(tree.file).name}")
            body = bodies[joint.frame]
            joint = joint.transformed(Transform(np.array(body.rotation), np.array(body.origin)))
        closures.append(Closure(joint, "closing joint", positions.line(source), file))
    return tree.with_closures(closures, notes=[f"{counted(len(closures), 'closing joint')} from {file}"], files=[file])
