"""``mobility check PATH...``: analyse mechanism files and compare them with their ``expected`` blocks.

Prints one table row per file (file, Grübler–Kutzbach count, mobility, DOF,
pattern, what was expected, verdict) and a summary line, or one JSON object
with ``--json``.  Exit status: 0 when every file passes; 1 when a file
disagrees with its ``expected`` block or has none; 2 when a path or file is
bad input (it appears in the table with its one-line error; bad input wins
over mismatches); 3 on an internal error.

A flexure document found among the files (``docs/actuation.md``) is read and
analysed as one (:func:`flexure_document`): its errors are the file's errors;
the flexure format has no ``expected`` block, so a sound one is reported as
having none, like any mechanism file without one.
"""

from __future__ import annotations

import argparse
import json
from typing import Any

from ..core.tolerance import Tolerance
from ..report.check import check_table
from ..testing.check import CheckResult, check_paths
from ._options import add_tolerance_option, tolerance_from

ORDER = 20


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "check",
        help="analyse mechanism files and compare them with their expected blocks (exit 1 on a mismatch)",
        description=(
            "Analyse every mechanism file given (folders: every *.yaml/*.yml inside, recursively) and compare "
            "it with its expected block; a flexure document is read and analysed as one and, having no expected "
            "block, reported as such.  Exit status: 0 all pass, 1 a mismatch or a file without expected "
            "block, 2 bad input (a bad file or path; wins over mismatches), 3 internal error."
        ),
    )
    p.add_argument("paths", nargs="+", metavar="PATH", help="mechanism files or folders")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the table")
    add_tolerance_option(p)
    p.set_defaults(run=run)


def flexure_document(path: str, data: Any, tol: Tolerance) -> CheckResult | None:
    """The check of a flexure document (an :data:`~mobility.testing.check.OtherDocument`), ``None`` for any other ``data``.

    The document is read by the flexure reader and its spaces computed, so a
    bad flexure document is an error naming its file, line and key.  The
    flexure format has no ``expected`` block (an ``expected`` key is refused
    by the reader as unknown): a sound document is ``"missing"``.

    Raises
    ------
    MechanismFileError
        When the flexure document breaks its format.
    """
    from ..flexure import flexure_spaces, is_flexure_document, load_flexure  # only when a file is not a mechanism file

    if not is_flexure_document(data):
        return None
    flexure = load_flexure(path)
    flexure_spaces(flexure, tol=tol)
    return CheckResult(path, flexure.name, "missing", kind="flexure")


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    report = check_paths(args.paths, tol=tol, others=(flexure_document,))
    print(json.dumps(report.to_dict(), indent=2, ensure_ascii=False) if args.json else check_table(report))
    return report.exit_status
