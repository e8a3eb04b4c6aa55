"""``mobility check PATH...``: analyse mechanism files and compare them with their ``expected`` blocks.

Prints one table row per file (file, Grübler–Kutzbach count, mobility, DOF,
pattern, what was expected, verdict) and a summary line, or one JSON object
with ``--json``.  Exit status: 0 when every file passes; 1 when a file
disagrees with its ``expected`` block or has none; 2 when a path or file is
bad input (it appears in the table with its one-line error; bad input wins
over mismatches); 3 on an internal error.
"""

from __future__ import annotations

import argparse
import json

from ..testing.check import CheckReport, CheckResult, check_paths
from ._options import add_tolerance_option, tolerance_from

ORDER = 20

VERDICTS = {"pass": "pass", "fail": "FAIL", "missing": "no expected block", "error": "ERROR"}
"""How each status is shown in the table."""


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "check",
        help="analyse mechanism files and compare them with their expected blocks (exit 1 on a mismatch)",
        description=(
            "Analyse every mechanism file given (folders: every *.yaml/*.yml inside, recursively) and compare "
            "it with its expected block.  Exit status: 0 all pass, 1 a mismatch or a file without expected "
            "block, 2 bad input (a bad file or path; wins over mismatches), 3 internal error."
        ),
    )
    p.add_argument("paths", nargs="+", metavar="PATH", help="mechanism files or folders")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the table")
    add_tolerance_option(p)
    p.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    report = check_paths(args.paths, tol=tol)
    print(json.dumps(report.to_dict(), indent=2, ensure_ascii=False) if args.json else table(report))
    return report.exit_status


def expected_text(r: CheckResult) -> str:
    """The expected block in short: ``'3 1T2R M3 +4'`` (DOF, pattern, mobility, number of other keys)."""
    if not r.comparisons:
        return "-"
    values = {c.key: c.expected for c in r.comparisons}
    parts = [str(values.pop(k)) if k != "mobility" else f"M{values.pop(k)}" for k in ("dof", "pattern", "mobility") if k in values]
    if values:
        parts.append(f"+{len(values)}")
    return " ".join(parts)


def verdict_text(r: CheckResult) -> str:
    """``pass (7 keys)``, ``FAIL: dof 4 (expected 3)``, ``no expected block`` or ``ERROR: file:line: key: ...``."""
    if r.status == "pass":
        return f"pass ({len(r.comparisons)} keys)"
    if r.status == "missing":
        return VERDICTS["missing"]
    return f"{VERDICTS[r.status]}: {r.message}"


def table(report: CheckReport) -> str:
    """The text table of ``mobility check``."""
    header = ("file", "G-K", "M", "DOF", "pattern", "expected", "verdict")
    rows = []
    for r in report.results:
        res = r.result
        found = ("", "", "", "") if res is None else (str(res.gruebler_kutzbach), str(res.mobility), str(res.dof), res.pattern)
        rows.append((r.path, *found, expected_text(r), verdict_text(r)))
    widths = [max(len(h), *(len(row[i]) for row in rows)) if rows else len(h) for i, h in enumerate(header)]
    right = {1, 2, 3}

    def line(cells: tuple[str, ...]) -> str:
        out = [c.rjust(w) if i in right else c.ljust(w) for i, (c, w) in enumerate(zip(cells[:-1], widths))]
        return "  ".join(out + [cells[-1]]).rstrip()

    out = [line(header), line(tuple("-" * w for w in widths))]
    out += [line(row) for row in rows]
    out.append("")
    out.append(report.summary())
    return "\n".join(out)
