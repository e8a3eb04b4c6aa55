"""``mobility convert FILE -o FILE.yaml``: a robot description (MJCF, URDF) as a mechanism file, never written over a file it reads."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..errors import MechanismFileError, RequestError, counted, one_line
from ..outputs import atomic_output
from ._options import add_mechanism_file, read_mechanism, require_new_output

ORDER = 15


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("convert", help="write a robot description (MJCF, URDF) as a mechanism file (YAML)",
                       description="Read an MJCF or URDF file and write the mechanism it describes in the project's format, "
                                   "to annotate, add an expected block and check with `mobility check`.")
    add_mechanism_file(p, file_help="robot description (MJCF, URDF) or mechanism file (YAML)")
    p.add_argument("-o", "--output", metavar="FILE.yaml", help="file to write (default, or '-': standard output)")
    p.add_argument("--expected", action="store_true", help="also write an expected block from this analysis (dof, pattern, mobility; "
                                                                   "the actuation verdict when joints are actuated)")
    p.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ..core.analysis import analyze
    from ..io.robot_files import ROBOT_SUFFIXES
    from ..io.writer import mechanism_to_yaml, require_written_faithfully

    if args.output == "-":  # the usual name of standard output
        args.output = None
    if args.output is not None and (not args.output or Path(args.output).suffix.lower() in ROBOT_SUFFIXES):
        raise RequestError(argument=f"-o {args.output!r}", expected="a name for the YAML file (such as model.yaml), not empty nor with a robot "
                           f"description's extension ({', '.join(sorted(ROBOT_SUFFIXES))}), which would be read back as XML")
    require_new_output(args.output, "-o", args.file, args.closures)
    mechanism, notes, files, _ = read_mechanism(args)
    require_new_output(args.output, "-o", *files)  # nor a file the model includes
    description = " ".join([mechanism.description] + [f"Note: {n}." for n in notes]).strip()
    expected = None
    if args.expected:
        result = analyze(mechanism)
        expected = {"dof": result.dof, "pattern": result.pattern, "mobility": result.mobility}
        if any(j.actuated for j in mechanism.joints):  # an MJCF actuator's joint
            from ..actuation import check_actuation

            expected["actuation"] = check_actuation(mechanism).verdict
    text = mechanism_to_yaml(mechanism, description=description, expected=expected)
    require_written_faithfully(mechanism, text, args.output or "the converted file")
    for note in notes:
        print(f"mobility: note: {one_line(note)}", file=sys.stderr)
    if args.output:
        try:
            with atomic_output(args.output) as handle:  # the previous file intact until the new one is whole
                handle.write(text)
        except OSError as exc:
            raise MechanismFileError("--output", f"cannot write the file ({exc.strerror or exc})", file=args.output) from None
        print(one_line(f"mobility: wrote {args.output} ({counted(len(mechanism.joints), 'joint')}, {counted(len(mechanism.links), 'link')})"), file=sys.stderr)
    else:
        _write_utf8(text)
    return 0


def _write_utf8(text: str) -> None:
    """Write a YAML document to standard output in UTF-8, whatever the terminal's encoding (escaped, a folded description would not read back)."""
    buffer = getattr(sys.stdout, "buffer", None)
    encoding = (getattr(sys.stdout, "encoding", None) or "").lower().replace("-", "").replace("_", "")
    if buffer is None or encoding == "utf8" or text.isascii():
        sys.stdout.write(text)
        return
    sys.stdout.flush()
    buffer.write(text.encode("utf-8"))
    buffer.flush()
