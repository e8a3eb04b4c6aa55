"""``mobility convert FILE -o FILE.yaml``: a robot description (MJCF, URDF) as a mechanism file.

The file and the options of robot description files (``--ground``,
``--end-effector``, ``--floating``, ``--ignore-unsupported``, ``--close A
B``, ``--closures FILE``) are those every command that reads one mechanism
file shares (:func:`mobility.cli._options.add_mechanism_file`).  The writer
is imported only when a file is written.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np
from pathlib import Path

from ..core.model import Mechanism
from ..errors import MechanismFileError
from ..io.loader import loads
from ._options import add_mechanism_file, read_mechanism

__all__ = ["register", "run"]

ORDER = 15


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("convert", help="write a robot description (MJCF, URDF) as a mechanism file (YAML)",
                       description="Read an MJCF or URDF file and write the mechanism it describes in the project's format, "
                                   "to annotate, add an expected block and check with `mobility check`.")
    add_mechanism_file(p, file_help="robot description (MJCF, URDF) or mechanism file (YAML)")
    p.add_argument("-o", "--output", metavar="FILE.yaml", help="file to write (default: standard output)")
    p.add_argument("--expected", action="store_true", help="also write an expected block (dof, pattern, mobility) from this analysis")
    p.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ..core.analysis import analyze
    from ..io.writer import mechanism_to_yaml

    mechanism, notes = read_mechanism(args)
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
