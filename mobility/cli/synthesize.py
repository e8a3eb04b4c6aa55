"""``mobility synthesize PATTERN``: limbs of R and P joints whose finite motions are a motion pattern.

Type synthesis by finite screws (Sun et al. 2018, :mod:`mobility.synthesis`); ``--write DIR`` also writes PKMs of them.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from ..errors import RequestError, SynthesisError, counted
from ..report.synthesis import synthesis_json, synthesis_text, written_files_text
from ..synthesis import PATTERNS, named_pattern, synthesize, write_pkm_files
from ..synthesis.enumeration import MAX_SAMPLES, MAX_VERIFY_SAMPLES
from ._options import integer_option, number_option, require_option_for

ORDER = 50
EXIT_STATUS = "0 a limb type is found, 1 none is, 2 bad input (one line on standard error)"


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("synthesize",
                       help="type synthesis: limbs of R and P joints whose finite motions are a motion pattern",
                       description="Enumerate limbs of R and P joints whose set of finite motions equals PATTERN "
                       "(finite screws, Sun et al. 2018).  Patterns: " + ", ".join(PATTERNS) + ".")
    p.add_argument("pattern", help="motion pattern: " + ", ".join(PATTERNS))
    p.add_argument("--joints", type=integer_option, default=None, help="one-DOF joints per limb (default: the pattern's dimension)")
    p.add_argument("--point", default="0,0,0", metavar="X,Y,Z", help="the pattern's point O, in mm like the files --write writes (default: %(default)s)")
    p.add_argument("--directions", default=None, metavar="X,Y,Z;X,Y,Z", help="the pattern's translation directions, ';'-separated (default: the coordinate axes)")
    p.add_argument("--samples", type=integer_option, default=3, help="random poses per rank decision, at most 30 (default: %(default)d)")
    p.add_argument("--verify", type=integer_option, default=2, help="finite motions of each kept limb fitted by the pattern, at most 10 (default: %(default)d; 0 skips)")
    p.add_argument("--seed", type=integer_option, default=0, help="seed of every random choice (default: %(default)d)")
    p.add_argument("--write", default=None, metavar="DIR", help="assemble a PKM of each limb type with four 6-DOF limbs and write mechanism files there")
    p.add_argument("--other", choices=("UPS", "SPRR"), default="UPS", help="the 6-DOF limbs of --write (default: %(default)s)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=run)


def _vector(text: str, what: str) -> tuple[float, float, float]:
    try:
        parts = [number_option(x) for x in text.split(",")]
    except ValueError:
        parts = []
    if len(parts) != 3:
        raise SynthesisError(caller=what, expected="three comma-separated numbers", got=repr(text))
    return (parts[0], parts[1], parts[2])


def _require_folder_to_write(folder: str) -> None:
    """A folder that is there, or can be made in one that is (a file, or a missing parent, is refused)."""
    if not folder.strip():
        raise RequestError(argument=f"--write {folder!r}", expected="a folder name")
    where = Path(os.path.abspath(folder))
    if where.exists() and not where.is_dir():
        raise RequestError("is a file, expected a folder to write mechanism files in", argument=f"--write {folder}")
    if not where.exists() and not where.parent.is_dir():
        raise RequestError(f"cannot write there: the folder {where.parent} does not exist", argument=f"--write {folder}")


def run(args: argparse.Namespace) -> int:
    if args.samples < 1 or args.verify < 0:
        raise RequestError(f"--samples must be at least 1 and --verify not negative, got {args.samples} and {args.verify}")
    if args.samples > MAX_SAMPLES or args.verify > MAX_VERIFY_SAMPLES or args.seed < 0 or (args.joints is not None and not 1 <= args.joints <= 8):
        raise RequestError(f"--samples must be at most {MAX_SAMPLES}, --verify at most {MAX_VERIFY_SAMPLES}, --seed not negative and --joints in [1, 8]; "
                           f"got {args.samples}, {args.verify}, {args.seed} and {args.joints}")
    require_option_for(args, "other", "--other", "--write", args.write is not None, "it chooses the 6-DOF limbs of the PKMs --write assembles")
    directions = None if args.directions is None else [_vector(d, "--directions") for d in args.directions.split(";")]
    pattern = named_pattern(args.pattern, point=_vector(args.point, "--point"), directions=directions)
    if args.write is not None:  # before the search: a folder that cannot take the files is refused now
        _require_folder_to_write(args.write)
        if args.joints is not None and args.joints != pattern.dim:
            raise RequestError(f"--write assembles PKMs from limbs of {counted(pattern.dim, 'joint')} (the dimension of {pattern.name}); --joints {args.joints} gives parts of limbs")
    result = synthesize(pattern, joints=args.joints, samples=args.samples, verify_samples=args.verify, seed=args.seed)
    try:
        written, skipped = write_pkm_files(result, args.write, other=args.other) if args.write else ((), ())
    except RequestError as exc:
        raise RequestError(f"--write {exc}") from None
    if args.json:
        print(synthesis_json(result, written, skipped))
    else:
        print(synthesis_text(result))
        if args.write:
            print(written_files_text(args.write, written, skipped))
    return 0 if result.structures else 1
