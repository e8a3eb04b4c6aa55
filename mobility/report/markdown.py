"""A Markdown report of a :class:`~mobility.core.result.Result` (``mobility analyze --format md``).

Tables that paste into a paper, a README or an issue: freedoms, constraint
wrenches, the whole-mechanism counts and, for a parallel mechanism, one row per limb.

Examples
--------
>>> import mobility
>>> text = markdown_report(mobility.analyze(mobility.load("mechanisms/slider_crank.yaml")))
>>> print(text.splitlines()[0])
# slider-crank
>>> "| T1 | translation | [1, 0, 0] |" in text, "| Grübler–Kutzbach count | 6(n − 1 − j) + Σf | -2 |" in text
(True, True)
"""

from __future__ import annotations

import re
from typing import Iterable, Sequence

from ..core.validation import require_bool
from ..core.result import Result, ScrewAxis, require_result
from ..errors import RequestError
from .text import fmt_number, fmt_vector, screw_text

__all__ = ["markdown_report", "markdown_table", "md_escape", "md_line", "md_heading", "md_code"]


_LINE_BREAKS = re.compile("\r\n|[\n\r\v\f\x1c\x1d\x1e\x85\u2028\u2029]")
"""Every character that ends a line (``str.splitlines``'s list): text put into one Markdown line may hold none."""


def md_line(text: object) -> str:
    """``text`` on one line (each line break a space): a name holding ``"\\n## "`` cannot start a heading or any block.

    Examples
    --------
    >>> md_line("a\\n## b\\r\\nc")
    'a ## b c'
    """
    return _LINE_BREAKS.sub(" ", str(text))


def md_escape(text: object) -> str:
    """Make ``text`` safe inside a Markdown table cell (pipes escaped, no line breaks).

    Examples
    --------
    >>> md_escape("a|b\\nc")
    'a\\\\|b c'
    """
    return md_line(str(text).replace("\\", "\\\\").replace("|", "\\|"))


def md_heading(text: object) -> str:
    """``text`` as the words of a heading: one line, pipes escaped, and a trailing ``#`` kept (escaped: it would close the heading).

    Examples
    --------
    >>> md_heading("#1 arm #")
    '#1 arm \\\\#'
    """
    escaped = md_escape(text)
    return escaped[:-1] + "\\#" if escaped.endswith("#") else escaped


def md_code(text: str) -> str:
    """``text`` as a Markdown code span on one line, whatever backticks it holds (CommonMark: a fence longer than any run inside).

    Examples
    --------
    >>> md_code("series(A,B)"), md_code("series(D`t,C)")
    ('`series(A,B)`', '``series(D`t,C)``')
    >>> md_code("`x"), md_code("A\\n## B")
    ('`` `x ``', '`A ## B`')
    """
    text = md_line(text)
    fence = "`" * (max((len(run) for run in re.findall("`+", text)), default=0) + 1)  # longer than any run inside
    pad = " " if text.startswith("`") or text.endswith("`") else ""
    return f"{fence}{pad}{text}{pad}{fence}"


def markdown_table(header: Sequence[str], rows: Iterable[Sequence[object]], align: str | None = None) -> str:
    """A GitHub-flavoured Markdown table of ``rows`` of cells (converted with ``str`` and escaped), one per column.

    ``align``: one letter per column, ``l``, ``r`` or ``c`` (default all left); else a :class:`RequestError`.

    Examples
    --------
    >>> print(markdown_table(["a", "b"], [[1, "x|y"]], align="rl"))
    | a | b |
    |--:|:--|
    | 1 | x\\|y |
    """
    header = [md_escape(h) for h in header]
    align = align or "l" * len(header)
    if len(align) != len(header):
        raise RequestError(argument="align", expected=f"one letter per column ({len(header)})", got=len(align))
    rule = {"l": ":--", "r": "--:", "c": ":-:"}
    if not set(align) <= set(rule):
        raise RequestError(argument="align", expected="letters l, r or c", got=repr(align))
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join(rule[a] for a in align) + "|"]
    for row in rows:
        cells = [md_escape(c) for c in row]
        if len(cells) != len(header):
            raise RequestError(argument="rows", expected=f"{len(header)} cells in each row", got=f"a row of {len(cells)}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _pitch(a: ScrewAxis, scale: float) -> str:
    return "0" if a.pitch == 0 else fmt_number(a.pitch, scale)


def _screw_list(axes: Sequence[ScrewAxis], scale: float) -> str:
    return "; ".join(screw_text(a, scale, verb="") for a in axes)


def markdown_report(result: Result, *, limbs: bool = True) -> str:
    """The analysis as Markdown, ending without a newline: a summary, then tables (``limbs``: also the limbs', each in its own frame)."""
    result = require_result(result, "markdown_report")
    require_bool(limbs, caller="markdown_report", argument="limbs", got=type(limbs).__name__)
    s = result.length_scale
    unit = f" ({result.length_unit})" if result.length_unit else ""
    moving = "cannot move (at first order)" if result.dof == 0 else f"has **{result.dof}** DOF, motion pattern **{result.pattern}**"
    out = [f"# {md_heading(result.name)}", "",
           f"The end effector {moving}; the whole mechanism has mobility **{result.mobility}**.", "",
           f"## Freedoms of the end effector ({result.dof})", ""]
    if result.dof:
        rows = [[f"T{i + 1}", "translation", fmt_vector(t), "", ""] for i, t in enumerate(result.translations)]
        rows += [[f"R{i + 1}", a.kind, fmt_vector(a.axis), fmt_vector(a.point, s), _pitch(a, s)] for i, a in enumerate(result.rotations)]
        out += [markdown_table(["", "kind", "direction / axis", f"point on axis{unit}", f"pitch{unit}/rad"], rows), "",
                "Translations: an orthonormal basis of the pure translations. Rotations: principal screws (the end effector's centre "
                f"is at {fmt_vector(result.reference_point, s)}; each axis is given through its point nearest it)."]
    else:
        out.append("None.")
    out += ["", f"## Constraint wrenches on the end effector ({6 - result.dof})", ""]
    k = len(result.couples)
    rows = [[f"C{i + 1}", "couple", fmt_vector(c), "", ""] for i, c in enumerate(result.couples)]
    rows += [[f"W{k + i + 1}", f.kind, fmt_vector(f.axis), fmt_vector(f.point, s), _pitch(f, s)] for i, f in enumerate(result.forces)]
    out.append(markdown_table(["", "kind", "direction / axis", f"point on axis{unit}", f"pitch{unit}"], rows) if rows else "None: the end effector is free.")
    out += ["", "## Whole mechanism", ""]
    counts = [["links (ground included)", "n", result.links], ["joints", "j", result.joints], ["joint freedoms", "Σf", result.joint_freedoms],
              ["independent loops", "j − n + 1", result.loops], ["Grübler–Kutzbach count", "6(n − 1 − j) + Σf", result.gruebler_kutzbach],
              ["mobility (screw theory)", "M", result.mobility], ["redundant constraints", "M − G–K", result.redundant_constraints],
              ["wrenches common to every joint", "", result.common_constraints], ["idle DOF (end effector still)", "M − DOF", result.idle_dof]]
    out.append(markdown_table(["quantity", "formula", "value"], counts, align="llr"))
    if result.gruebler_kutzbach_explanation:
        out += ["", f"Why Grübler–Kutzbach differs: {md_line(result.gruebler_kutzbach_explanation)}"]
    out += ["", f"Structure (series/parallel decomposition): {md_code(result.structure)}"]
    if limbs and result.limbs:
        out += ["", f"## Limbs ({len(result.limbs)}), each in its own frame", ""]
        limb_rows = []
        for i, limb in enumerate(result.limbs):
            free = "; ".join([f"translation {fmt_vector(t)}" for t in limb.translations] + ([_screw_list(limb.rotations, s)] if limb.rotations else []))
            cons = "; ".join([f"couple {fmt_vector(c)}" for c in limb.couples] + ([_screw_list(limb.forces, s)] if limb.forces else []))
            limb_rows.append([i + 1, md_code(limb.structure), limb.frame, limb.dof, limb.idle_dof, free or "none", cons or "none"])
        out.append(markdown_table(["limb", "structure", "frame", "DOF", "idle", "freedoms", "constraint wrenches"], limb_rows, align="rllrrll"))
    out += [
        "",
        f"Distance to a singularity: {result.margin.smallest_kept:.2e} (1 far from one, 0 where the count changes: the smallest kept "
        f"singular value, relative). Departure from the special geometry: {result.margin.largest_dropped:.2e} (0 or round-off when it "
        "is exact: the largest dropped singular value, relative).",
    ]
    if result.precision_summary:
        out += ["", f"Precision: {md_line(result.precision_summary)}."]
    if result.warnings:
        out += ["", *(f"> **Warning:** {md_line(w)}" for w in result.warnings)]
    return "\n".join(out)
