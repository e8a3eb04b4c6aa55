"""Robot description files (MJCF, URDF): recognise them and read them into a mechanism.

:func:`robot_format` tells a robot description by its extension, else its
first element (``<mujoco>``, ``<robot>``); :func:`read_robot` reads one, adds
the loop closures asked for and builds the mechanism with the notes of the reading.

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
from typing import Any, Mapping

from ..core.validation import require_bool
from ..errors import MechanismFileError, RequestError, clipped
from .closures import close_pairs, with_close_pairs, with_closures_file
from .files import file_name
from .robot_tree import ImportedRobot, RobotOptions, RobotTree, build_mechanism, model_joint_names, unique_name
from .xml_source import read_xml, root_tag

__all__ = ["robot_format", "is_robot_file", "read_robot", "require_no_robot_options", "RobotOptions", "ImportedRobot", "ROBOT_SUFFIXES"]

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
