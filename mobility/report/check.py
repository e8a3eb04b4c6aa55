"""The table of ``mobility check`` (:func:`mobility.testing.check.check_paths` computes it): one row per file, then a summary line.

Examples
--------
>>> from mobility.testing.check import check_paths
>>> print(check_table(check_paths(["no/such.yaml"])))
file          G-K  M  DOF  pattern  expected  verdict
------------  ---  -  ---  -------  --------  -------------------------------------------
no/such.yaml                        -         ERROR: no/such.yaml: no such file or folder
<BLANKLINE>
0 passed, 0 failed, 0 without expected block, 1 error
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..errors import one_line

if TYPE_CHECKING:  # pragma: no cover
    from ..testing.check import CheckReport, CheckResult

__all__ = ["STATUS_WORDS", "expected_text", "verdict_text", "check_table"]

STATUS_WORDS = {"pass": "pass", "fail": "FAIL", "missing": "no expected block", "error": "ERROR"}
"""How each status of a checked file is shown in the table."""

HEADER = ("file", "G-K", "M", "DOF", "pattern", "expected", "verdict")
RIGHT_ALIGNED = {1, 2, 3}  # the counts


def expected_text(r: "CheckResult") -> str:
    """The expected block in short: ``'3 1T2R M3 +4'`` (DOF, pattern, mobility, number of other keys)."""
    if not r.comparisons:
        return "-"
    values = {c.key: c.expected for c in r.comparisons}
    parts = [str(values.pop(k)) if k != "mobility" else f"M{values.pop(k)}" for k in ("dof", "pattern", "mobility") if k in values]
    if values:
        parts.append(f"+{len(values)}")
    return " ".join(parts)


def verdict_text(r: "CheckResult") -> str:
    """``pass (7 keys)``, ``FAIL: dof 4 (expected 3)``, ``no expected block`` or ``ERROR: file:line: key: ...``."""
    if r.status == "pass":
        return f"pass ({len(r.comparisons)} keys)"
    return STATUS_WORDS["missing"] if r.status == "missing" else f"{STATUS_WORDS[r.status]}: {r.message}"


def check_table(report: "CheckReport") -> str:
    """The text table of ``mobility check``: file, G-K, M, DOF, pattern, expected, verdict; then the summary."""
    rows = []
    for r in report.results:
        res, f = r.result, r.found or {}
        found = [str(getattr(res, k) if res is not None else f.get(k, ""))
                 for k in ("gruebler_kutzbach", "mobility", "dof", "pattern")]
        rows.append(tuple(one_line(c) for c in (r.path, *found, expected_text(r), verdict_text(r))))  # a path as typed may hold an escape
    widths = [max(len(h), *(len(row[i]) for row in rows)) if rows else len(h) for i, h in enumerate(HEADER)]

    def line(cells: tuple[str, ...]) -> str:
        out = [c.rjust(w) if i in RIGHT_ALIGNED else c.ljust(w) for i, (c, w) in enumerate(zip(cells[:-1], widths))]
        return "  ".join(out + [cells[-1]]).rstrip()

    out = [line(HEADER), line(tuple("-" * w for w in widths))]
    out += [line(row) for row in rows]
    out += ["", report.summary()]
    return "\n".join(out)
