"""``mobility check PATH...``: analyse mechanism files and compare them with their ``expected`` blocks.

A flexure document among the files is checked as one; ``--library`` checks the library bundled with the package.
"""

from __future__ import annotations

import argparse
import json

from .. import library
from ..errors import RequestError
from ..report.check import check_table
from ..testing.check import check_paths
from ..testing.flexure_check import flexure_document
from ._options import add_tolerance_option, tolerance_from

ORDER = 20
EXIT_STATUS = ("0 every file passes, 1 a file disagrees with its expected block or has none, "
               "2 a path or file is bad input (in the table, on its line; it wins over disagreements)")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("check",
                       help="analyse mechanism files and compare them with their expected blocks (exit 1 on a mismatch)",
                       description="Analyse every mechanism file given (folders: every *.yaml/*.yml inside, recursively) and compare "
                       "it with its expected block (a flexure document is checked as one).")
    p.add_argument("paths", nargs="*", metavar="PATH", help="mechanism files or folders")
    p.add_argument("--library", action="store_true",
                   help="check the library bundled with the package (its classic mechanisms and flexure examples), before any PATH")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the table")
    add_tolerance_option(p)
    p.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    if not args.paths and not args.library:
        raise RequestError("give a mechanism file or folder (PATH), or --library for the bundled library", caller="check")
    paths = [*(library.folders() if args.library else ()), *args.paths]
    report = check_paths(paths, tol=tol, others=(flexure_document,))
    print(json.dumps(report.to_dict(), indent=2, ensure_ascii=False) if args.json else check_table(report))
    return report.exit_status
