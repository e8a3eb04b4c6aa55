"""``mobility analyze FILE``: the report of one mechanism."""

from __future__ import annotations

import argparse
import json

from ..core.analysis import analyze
from ..io.loader import load
from ..report.text import json_report, text_report
from ..report.markdown import markdown_report
from ._options import add_tolerance_option, tolerance_from

ORDER = 10

FORMATS = {
    "text": lambda r, a: text_report(r, limbs=a.limbs),
    "json": lambda r, a: json_report(r),
    "md": lambda r, a: markdown_report(r),
}
"""Output formats: name -> function(result, args) -> str (other modules may add)."""


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("analyze", help="DOF, pattern, directions and constraints of a mechanism's end effector")
    p.add_argument("file", help="mechanism file (YAML)")
    p.add_argument("--json", action="store_true", help="print one JSON object (same as --format json)")
    p.add_argument("--format", choices=sorted(FORMATS), default="text", help="output format (default: text)")
    p.add_argument("--limbs", action="store_true", help="also show each limb's twists and constraints in its own frame")
    add_tolerance_option(p)
    p.add_argument("--finite", action="store_true", help="also move the mechanism: is the freedom full-cycle or instantaneous only?")
    p.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    mechanism = load(args.file)
    result = analyze(mechanism, tol=tol)
    fmt = "json" if args.json else args.format
    text = FORMATS[fmt](result, args)
    if args.finite:
        from ..finite.full_cycle import finite_mobility  # scipy.optimize is slow to import: only when asked

        text = _with_finite(text, fmt, finite_mobility(mechanism, tol=tol))
    print(text)
    return 0


def _with_finite(text: str, fmt: str, finite) -> str:
    """Add the finite-motion answer to a report: a ``finite`` key in JSON, a section otherwise."""
    if fmt == "json":
        data = json.loads(text)
        data["finite"] = finite.to_dict()
        return json.dumps(data, indent=2, ensure_ascii=False)
    from ..finite.full_cycle import finite_report

    section = finite_report(finite)
    if fmt == "md":
        return text.rstrip("\n") + "\n\n## Finite motion\n\n```\n" + section + "\n```\n"
    return text + "\n" + section
