"""``mobility convert FILE -o FILE.yaml``: a robot description (MJCF, URDF) as a mechanism file.

Also the options every command that reads a file shares for robot
descriptions (``--ground``, ``--end-effector``, ``--floating``,
``--ignore-unsupported``, ``--close A B``, ``--closures FILE``), and
:func:`load_mechanism`, which reads the file they name and prints the notes
of the reading on stderr, one line each.  The robot readers and the writer
are imported only when a robot file is read or a file written, so that
``mobility analyze FILE.yaml`` does not pay for them.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np
from pathlib import Path
from typing import Any

from ..core.model import Mechanism
from ..errors import MechanismFileError
from ..io.loader import load, loads

__all__ = ["register", "run", "add_robot_options", "robot_options_from", "load_mechanism"]

ORDER = 15


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("convert", help="write a robot description (MJCF, URDF) as a mechanism file (YAML)",
                       description="Read an MJCF or URDF file and write the mechanism it describes in the project's format, "
                                   "to annotate, add an expected block and check with `mobility check`.")
    p.add_argument("file", help="robot description (MJCF .xml, URDF .urdf) or mechanism file")
    p.add_argument("-o", "--output", metavar="FILE.yaml", help="file to write (default: standard output)")
    p.add_argument("--expected", action="store_true", help="also write an expected block (dof, pattern, mobility) from this analysis")
    add_robot_options(p)
    p.set_defaults(run=run)


def add_robot_options(parser: argparse.ArgumentParser) -> None:
    """Add the options of robot description files to a subcommand."""
    g = parser.add_argument_group("robot description files (MJCF, URDF)")
    g.add_argument("--ground", metavar="BODY", help="the fixed body (default: the world or root body)")
    g.add_argument("--end-effector", metavar="BODY", help="the body whose freedom is reported (default: the body farthest from the ground)")
    g.add_argument("--floating", action="store_true", help="keep the 6 freedoms of free/floating joints (default: treat them as fixed)")
    g.add_argument("--ignore-unsupported", action="store_true", help="leave out joint couplings (mimic, joint/tendon equalities) with a note instead of failing")
    g.add_argument("--close", nargs=2, action="append", metavar=("A", "B"), default=[],
                   help="close a loop: bodies A and B, whose origins coincide, are joined by a spherical joint (repeatable)")
    g.add_argument("--closures", metavar="FILE", help="YAML file of closing joints in the project's format (links are body names)")


def robot_options_from(args: argparse.Namespace) -> dict[str, Any]:
    """The robot options given on the command line (those left at their default are omitted)."""
    values = {"ground": args.ground, "end_effector": args.end_effector, "floating": args.floating,
              "ignore_unsupported": args.ignore_unsupported, "close": tuple(tuple(p) for p in args.close), "closures": args.closures}
    return {k: v for k, v in values.items() if v not in (None, False, ())}


def _is_robot_file(path: str) -> bool:
    """Whether ``path`` is a robot description (a YAML suffix is decided without importing the robot readers)."""
    if Path(path).suffix.lower() in (".yaml", ".yml"):
        return False
    from ..io.robot_files import is_robot_file

    return is_robot_file(path)


def _read_robot(path: str, options: dict[str, Any]) -> Any:
    from ..io.robot_files import read_robot  # XML readers (and MuJoCo for MJCF): only for robot files

    return read_robot(path, **options)


def load_mechanism(args: argparse.Namespace) -> Mechanism:
    """The mechanism of ``args.file``; for a robot description, its notes go to stderr."""
    options = robot_options_from(args)
    if not _is_robot_file(args.file):
        return load(args.file, **options)
    robot = _read_robot(args.file, options)
    for note in robot.notes:
        print(f"mobility: note: {note}", file=sys.stderr)
    return robot.mechanism


def run(args: argparse.Namespace) -> int:
    from ..core.analysis import analyze
    from ..io.writer import mechanism_to_yaml

    notes: tuple[str, ...] = ()
    options = robot_options_from(args)
    if _is_robot_file(args.file):
        robot = _read_robot(args.file, options)
        mechanism, notes = robot.mechanism, robot.notes
    else:
        mechanism = load(args.file, **options)
    description = " ".join([mechanism.description] + [f"Note: {n}." for n in notes]).strip()
    expected = None
    if args.expected:
        result = analyze(mechanism)
        expected = {"dof": result.dof, "pattern": result.pattern, "mobility": result.mobility}
    text = mechanism_to_yaml(mechanism, description=description, expected=expected)
    _require_same_geometry(mechanism, text, args.output or "the converted file")
    for note in notes:
        print(f"mobility: note: {note}", file=sys.stderr)
    if args.output:
        try:
            Path(args.output).write_text(text)
        except OSError as exc:
            raise MechanismFileError("--output", f"cannot write the file ({exc.strerror or exc})", file=args.output) from None
        print(f"mobility: wrote {args.output} ({len(mechanism.joints)} joints, {len(mechanism.links)} links)", file=sys.stderr)
    else:
        sys.stdout.write(text)
    return 0


CONVERSION_DRIFT = 1e-9
"""Largest change of a joint's geometry that writing and reading back may make (relative to the
mechanism's characteristic length for points and pitches, absolute for unit directions): the
written numbers keep many more digits than that, so only numbers the writer cannot hold trip it."""


def _require_same_geometry(mechanism: Mechanism, text: str, where: str) -> None:
    """Read ``text`` back and refuse, in one line, a file whose joints are not ``mechanism``'s.

    The writer keeps a fixed number of digits and writes numbers near zero as
    0; a mechanism whose size is far below or above everyday sizes would
    come back as another mechanism, with another answer.  That is refused
    rather than written.

    Raises
    ------
    MechanismFileError
        Naming the first joint and field that would change.
    """
    from ..core.joint_screws import joint_screws

    back = loads(text, file=where)
    length = joint_screws(mechanism).normalisation.length
    for i, (a, b) in enumerate(zip(mechanism.world_joints, back.world_joints)):
        for name, size in (("point", length), ("pitch", length), ("axis", 1.0), ("normal", 1.0), ("axes", 1.0)):
            x, y = getattr(a, name), getattr(b, name)
            if x is None or (name == "point" and a.type == "P"):
                continue
            with np.errstate(over="ignore", invalid="ignore"):
                drift = float(np.max(np.abs(np.subtract(x, y, dtype=float)))) / size if y is not None else np.inf
            if not drift <= CONVERSION_DRIFT:
                raise MechanismFileError(
                    f"joints[{i}].{name}",
                    f"joint {a.name!r} would not be written faithfully (it changes by {drift:.2g} of the mechanism's size "
                    "once written with the writer's digits); the mechanism is too small or too large to convert",
                    file=str(mechanism.source or where),
                )
