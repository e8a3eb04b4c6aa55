"""``mobility analyze FILE``: the report of one mechanism."""

from __future__ import annotations

import argparse

from ..core.analysis import analyze
from ..errors import RequestError
from ..report.text import json_report, text_report
from ..io.limits import require_size
from ._options import add_mechanism_file, add_tolerance_option, read_with_notes, tolerance_from

ORDER = 10


def _markdown(result, args: argparse.Namespace) -> str:
    from ..report.markdown import markdown_report  # imported when asked for: most runs print text

    return markdown_report(result)


FORMATS = {"text": lambda r, a: text_report(r, limbs=a.limbs), "json": lambda r, a: json_report(r), "md": _markdown}
"""Output formats: name -> function(result, args) -> str (other modules may add)."""


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("analyze", help="DOF, pattern, directions and constraints of a mechanism's end effector")
    add_mechanism_file(p)
    p.add_argument("--json", action="store_true", help="print one JSON object (same as --format json)")
    p.add_argument("--format", choices=sorted(FORMATS), default="text", help="output format (default: text)")
    p.add_argument("--limbs", action="store_true", help="also show each limb's twists and constraints in its own frame")
    add_tolerance_option(p)
    p.add_argument("--finite", action="store_true", help="also move the mechanism: is the freedom full-cycle or instantaneous only?")
    p.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    if args.json and args.format not in ("text", "json"):
        raise RequestError("choose one output format", argument=f"--json and --format {args.format}")
    read = read_with_notes(args)
    mechanism = read.mechanism
    tol = tolerance_from(args, mechanism.precision)
    if args.finite:
        require_size(mechanism, "max_finite_joints", "--finite", args.file)
    result = analyze(mechanism, tol=tol)
    fmt = "json" if args.json else args.format
    text = FORMATS[fmt](result, args)
    if read.closures:  # a robot file's closed loops: which of each closure's rows the rest already imposes
        from ..core.closures import closure_advice
        from ..report.closures import with_closures

        text = with_closures(text, fmt, closure_advice(mechanism, read.closures, tol=tol))
    if args.finite:
        # imported only when asked: the finite analysis pulls in scipy.optimize, slow to import
        from ..finite.full_cycle import finite_mobility
        from ..report.finite import with_finite

        text = with_finite(text, fmt, finite_mobility(mechanism, tol=tol))
    print(text)
    return 0
