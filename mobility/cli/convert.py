"""``mobility convert FILE -o FILE.yaml``: a robot description (MJCF, URDF) as a mechanism file.

Also the options every command that reads a file shares for robot
descriptions (``--ground``, ``--end-effector``, ``--floating``,
``--ignore-unsupported``, ``--close A B``, ``--closures FILE``), and
:func:`load_mechanism`, which reads the file they name and prints the notes
of the reading on stderr, one line each.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..core.analysis import analyze
from ..core.model import Mechanism
from ..errors import MechanismFileError
from ..io.loader import load
from ..io.robot_files import is_robot_file, read_robot
from ..io.writer import mechanism_to_yaml

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


def load_mechanism(args: argparse.Namespace) -> Mechanism:
    """The mechanism of ``args.file``; for a robot description, its notes go to stderr."""
    options = robot_options_from(args)
    if not is_robot_file(args.file):
        return load(args.file, **options)
    robot = read_robot(args.file, **options)
    for note in robot.notes:
        print(f"mobility: note: {note}", file=sys.stderr)
    return robot.mechanism


def run(args: argparse.Namespace) -> int:
    notes: tuple[str, ...] = ()
    options = robot_options_from(args)
    if is_robot_file(args.file):
        robot = read_robot(args.file, **options)
        mechanism, notes = robot.mechanism, robot.notes
    else:
        mechanism = load(args.file, **options)
    description = " ".join([mechanism.description] + [f"Note: {n}." for n in notes]).strip()
    expected = None
    if args.expected:
        result = analyze(mechanism)
        expected = {"dof": result.dof, "pattern": result.pattern, "mobility": result.mobility}
    text = mechanism_to_yaml(mechanism, description=description, expected=expected)
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
