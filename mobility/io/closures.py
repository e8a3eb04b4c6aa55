"""Loop closures a robot description cannot express: ``--close A B`` pairs and a side file.

For URDF and MJCF alike (``docs/robot-files.md``): ``--close A B`` joins two bodies whose origins coincide by a
spherical joint at ``A``'s origin; a side file holds ``joints`` as in a mechanism file, their ``links`` body names,
a ``frame`` naming a body whose frame at the pose the geometry is written in (default: global)::

      # closures of four_bar.urdf
      joints:
        - {name: C, type: R, links: [coupler, rocker], axis: [0, 0, 1], point: [3, 0.5, 0], frame: coupler}

Examples
--------
>>> from mobility.io.robot_tree import Body, RobotTree, TreeJoint
>>> tree = RobotTree("two arms", "t.urdf", "URDF", bodies=(
...     Body("base", None), Body("a", "base", origin=(1, 0, 0)), Body("b", "base", origin=(1, 0, 0))))
>>> closed = with_close_pairs(tree, [("a", "b")])
>>> [(c.joint.type, c.joint.links, c.joint.point) for c in closed.closures]
[('S', ('a', 'b'), (1.0, 0.0, 0.0))]
"""

from __future__ import annotations

from pathlib import Path
from typing import Iterable

import numpy as np

from ..core.model import WORLD, Joint
from ..core.transforms import Transform
from ..errors import MechanismFileError, RequestError, counted, did_you_mean
from .files import file_name
from .mechanism_reader import MechanismReader
from .robot_tree import Closure, RobotTree
from .yaml_source import parse_yaml, read_text

__all__ = ["with_close_pairs", "with_closures_file", "close_pairs", "CLOSURES_KEYS"]

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
    """The tree with a spherical joint at the origin of ``A`` for each pair ``(A, B)``.

    Raises
    ------
    MechanismFileError
        When a name is not a body of the tree (key ``close``).
    RequestError
        When ``pairs`` is not a list of pairs of names (:func:`close_pairs`).
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
    """The tree with the closing joints of a side file (see the module docstring).

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
