"""Reports of a :class:`~mobility.sweeps.SweepResult` printed by ``mobility sweep``: a short text summary, CSV and JSON.

What each holds: docs/sweeps.md, "Output".

Examples
--------
>>> import mobility
>>> r = mobility.sweep(mobility.load("mechanisms/parallelogram.yaml"), ["O1=0:360:5"])
>>> print(sweep_csv(r).splitlines()[0])
O1 [deg],dof,pattern,mobility,assembled,residual,smallest_kept,largest_dropped,near_singular,inexact
>>> sweep_csv(r).splitlines()[2].split(",")[:5]
['90', '1', '1T', '1', 'true']
"""

from __future__ import annotations

import csv
import io
import json
import math
from collections import Counter
from typing import Any, Iterator

import numpy as np

from ..actuation import SINGULAR
from ..core.tolerance import first_least
from ..errors import counted
from ..sweeps import SweepResult
from .text import fmt_number

__all__ = ["sweep_summary", "sweep_csv", "sweep_json", "sweep_csv_pieces", "sweep_json_pieces", "describe_values", "SUMMARY_SINGULAR_LIMIT", "PIECE_ROWS"]

SUMMARY_SINGULAR_LIMIT = 8
"""Singular poses and changes listed in the summary (the CSV and JSON have them all)."""

PIECE_ROWS = 10_000
"""Rows of a table written at a time: a million-pose table is never held whole as text."""


def describe_values(result: SweepResult, values: Any) -> str:
    """``"O1=120 deg, P1=-5 mm"``: coordinate values with their units, with the digits that tell neighbours apart (:func:`axis_digits`)."""
    return ", ".join(f"{a.name}={fmt_number(v, a.extent, digits=axis_digits(a))}{(' ' + a.unit) if a.unit else ''}" for a, v in zip(result.axes, values))


def _step(axis) -> float:
    return axis.stop / (axis.count - 1) - axis.start / (axis.count - 1) if axis.count > 1 else 0.0  # no overflow for ends near the largest float


def axis_digits(axis) -> int:
    """Significant digits that show every value of a sweep axis apart from its neighbours.

    Six, or more when the step is small against the values: ``119.999:120.001:5``
    needs seven (``119.9995``), ``100000:100001:3`` eight.  At most 15.

    Examples
    --------
    >>> from types import SimpleNamespace as A
    >>> axis_digits(A(start=0.0, stop=360.0, count=13)), axis_digits(A(start=119.999, stop=120.001, count=5))
    (6, 8)
    """
    step = abs(_step(axis))
    largest = max(abs(axis.start), abs(axis.stop))
    if step == 0.0 or largest == 0.0 or not math.isfinite(largest / step):
        return 6
    return int(min(15, max(6, math.ceil(math.log10(largest / step)) + 2)))


def _range(axis) -> str:
    unit = f" {axis.unit}" if axis.unit else ""
    scale, digits = axis.extent, axis_digits(axis)
    if axis.count == 1:
        return f"{axis.name} = {fmt_number(axis.start, scale, digits=digits)}{unit}"
    shown = lambda x: fmt_number(x, scale, digits=digits)  # noqa: E731
    return f"{axis.name} from {shown(axis.start)} to {shown(axis.stop)}{unit} ({axis.count} values, step {fmt_number(_step(axis), scale)})"


def sweep_summary(result: SweepResult) -> str:
    """The text summary printed by ``mobility sweep``."""
    kind = "pose coordinate" if all(a.kind == "pose" for a in result.axes) else "coordinate"
    out = [f"{result.name}: sweep of {counted(len(result.axes), kind)}, {counted(result.size, 'pose', grouped=True)}"]
    out += [f"  {_range(a)}" for a in result.axes]
    assembled = int(result.assembled.sum())
    line = f"  assembled: {assembled:,} of {counted(result.size, 'pose', grouped=True)}"
    if assembled:
        line += f" (every loop closed to {result.tolerance.closure:.0e})"  # the bound; each pose's residual, round-off, is in its column
    out.append(line)
    if assembled < result.size:
        out.append(f"  not assembled: {counted(result.size - assembled, 'pose', grouped=True)} (no closed pose reached there; see the 'assembled' column)")
    if not assembled:
        return "\n".join(out)
    out.append("  poses per answer (end-effector DOF, pattern, mobility):")
    doubtful = result.assembled & (result.near_singular | result.inexact)
    doubts = Counter(zip(result.dof[doubtful].tolist(), result.pattern[doubtful].tolist(), result.mobility[doubtful].tolist()))
    for answer, n in result.counts().items():
        dof, pattern, mobility = answer
        line = f"    {n:>9,}  DOF {dof}  {pattern:<6}  mobility {mobility}"
        if doubts[answer]:
            line += f"   ({doubts[answer]:,} of them near-singular or inexact: there the count or the pattern may follow round-off)"
        out.append(line)
    left = result.regular[2] - len(result.axes) if result.regular is not None else 0
    if left > 0:
        assert result.regular is not None  # nothing is left without a regular pose
        out.append(f"  note: {counted(len(result.axes), 'coordinate')} driven for mobility {result.regular[2]}: the other {counted(left, 'freedom')} "
                   f"{'follows' if left == 1 else 'follow'} the solver (the smallest change from the neighbouring pose), so the path across the grid decides {'it' if left == 1 else 'them'}")
    if result.actuated:
        verdicts = ", ".join(f"{v} at {n:,}" for v, n in result.verdict_counts().items())
        out.append(f"  actuation by {', '.join(result.actuated)}: {verdicts}")
        finite = result.assembled & np.isfinite(result.conditioning)
        if finite.any():
            kappa = result.conditioning[finite]
            worst = int(np.flatnonzero(finite)[first_least(kappa)])
            out.append(f"    conditioning kappa: median {fmt_number(float(np.median(kappa)), digits=3)}, "
                       f"smallest {fmt_number(float(kappa.min()), digits=3)} at {describe_values(result, result.values[worst])}")
        controlled = result.assembled & (result.verdict != SINGULAR)  # at a singular pose the margin is that of a lower rank
        margins = np.where(controlled, result.actuation_margin, np.inf)
        if np.isfinite(margins).any():
            lowest = first_least(margins)
            where = "" if controlled.sum() == result.assembled.sum() else " of the poses not actuation-singular"
            near = int((margins < result.tolerance.near_singular).sum())  # as `mobility actuation` warns at one pose
            out.append(f"    actuation margin (distance to an actuation singularity): smallest{where} {float(margins[lowest]):.2e} "
                       f"at {describe_values(result, result.values[lowest])}; near an actuation singularity: {near:,}")
        out += transmission_lines(result)
    margin = result.smallest_kept[result.assembled]
    worst = int(np.flatnonzero(result.assembled)[first_least(margin)])
    near = int(result.near_singular[result.assembled].sum())
    out.append(f"  distance to a singularity (1 far from one, 0 where the count changes): smallest {float(margin.min()):.2e} at {describe_values(result, result.values[worst])}; near-singular poses: {near:,}")
    singular = result.singular
    if singular:
        out.append(f"  singular poses ({len(singular):,}):")
        out += _first(singular, SUMMARY_SINGULAR_LIMIT, lambda p: f"    {describe_values(result, p.values)}: {'; '.join(p.reasons)}", " (see --format csv or json)")
    elif result.assembled.all():
        out.append("  singular poses: none on the grid")
    else:  # the edge of the assembled region is where the loops reach a limit: a singular pose, which Newton closes poorly
        missing = int(result.size - result.assembled.sum())
        out.append(f"  singular poses: none among the assembled poses; the {missing:,} not assembled may hold some "
                   "(where assembly ends the loops reach a limit, itself a singular pose)")
    dips = result.dips
    if dips:
        out.append(f"  margin dips ({len(dips):,}): a singularity with the same answer on both sides may lie next to these poses, between grid points; a finer grid there tells")
        out += _first(dips, SUMMARY_SINGULAR_LIMIT, lambda d: f"    {describe_values(result, d.values)}: "
                      f"{'actuation margin' if d.column == 'actuation_margin' else 'rank margin'} {d.margin:.2e} "
                      f"({'its neighbours' if len(d.neighbours) == 2 else 'an end of the grid; its neighbour'} along {d.axis}: "
                      f"{', '.join(f'{m:.2e}' for m in d.neighbours)})", " (see --format json)")
    changes = result.changes
    classes = result.classes()
    if len(changes):
        out.append(f"  the answer changes between {len(changes):,} pair{'' if len(changes) == 1 else 's'} of neighbouring poses:")
        out += _first(changes, SUMMARY_SINGULAR_LIMIT // 2, lambda c: f"    {describe_values(result, result.values[c[0]])} ({_answer(classes[c[0]])}) -> "
                      f"{describe_values(result, result.values[c[1]])} ({_answer(classes[c[1]])})")
    seams = result.seams
    if len(seams):
        out.append(f"  seams: at {len(seams):,} pair{'' if len(seams) == 1 else 's'} of neighbouring poses a full turn comes back on another pose "
                   "(no small motion joins them: free joints drifted, or another assembly was reached):")
        out += _first(seams, SUMMARY_SINGULAR_LIMIT // 2, lambda s: f"    {describe_values(result, result.values[s[0]])} -> {describe_values(result, result.values[s[1]])}",
                      " (see --format json)")
    return "\n".join(out)


def _first(items: Any, limit: int, line: Any, more: str = "") -> list[str]:
    """``line(item)`` for the first ``limit`` items, then how many more there are."""
    return [line(x) for x in items[:limit]] + ([f"    ... and {len(items) - limit:,} more{more}"] if len(items) > limit else [])


def _answer(c: tuple[int, str, int, str] | None) -> str:
    if c is None:
        return "not assembled"
    dof, pattern, mobility, verdict = c
    return f"DOF {dof} {pattern}, mobility {mobility}" + (f", {verdict}" if verdict else "")


def transmission_lines(result: SweepResult) -> list[str]:
    """The summary of the transmission indices (:mod:`mobility.transmission`): LTI, CTI and the good-transmission workspace."""
    if not result.has_transmission:
        return []
    out = []
    for column, what in (("lti", "local transmission index LTI (distance to an actuation singularity)"),
                         ("cti", "constraint transmission index CTI (distance to a constraint singularity)")):
        values = np.where(result.assembled, np.asarray(getattr(result, column), dtype=float), np.nan)
        if np.isfinite(values).any():
            lowest = first_least(np.where(np.isfinite(values), values, np.inf))
            out.append(f"    {what}: median {float(np.nanmedian(values)):.3f}, smallest {float(values[lowest]):.3f} at {describe_values(result, result.values[lowest])}")
    share = result.good_transmission()
    if np.isfinite(share):
        good = int(round(share * int(result.assembled.sum())))
        out.append(f"    good-transmission workspace (LTI >= {result.good_threshold:g}): {100 * share:.1f}% of the assembled poses ({good:,})")
    return out


ANSWER_COLUMNS = ("dof", "pattern", "mobility", "smallest_kept", "largest_dropped", "near_singular", "inexact", "verdict", "conditioning", "actuation_margin",
                  "iti", "oti", "lti", "cti")
"""Columns that are an answer of the analysis: empty cells where a pose is not assembled."""


def _cell(name: str, value: Any, assembled: bool, scale: float = 1.0, digits: int = 6) -> str:
    if name in ANSWER_COLUMNS and not assembled:
        return ""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        x = float(value)
        if not np.isfinite(x):
            return ""
        return fmt_number(x, scale, digits=digits) if name not in ("residual", "smallest_kept", "largest_dropped", "actuation_margin") else (f"{x:.6g}" if x else "0")
    return str(value)


def sweep_csv(result: SweepResult) -> str:
    """The table as CSV: the varied coordinates (``name [unit]``), then ``dof, pattern, mobility`` and the rest."""
    return "".join(sweep_csv_pieces(result))


def sweep_csv_pieces(result: SweepResult, rows: int | None = None) -> Iterator[str]:
    """:func:`sweep_csv` in pieces of ``rows`` rows (default :data:`PIECE_ROWS`; the header first), for a writer that never holds the whole text."""
    rows = PIECE_ROWS if rows is None else rows
    labels = {a.name: a.label for a in result.axes}
    scales = {a.name: a.extent for a in result.axes}
    digits = {a.name: axis_digits(a) for a in result.axes}
    names = result.columns
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([labels.get(n, n) for n in names])
    columns = [result.column(n) for n in names]
    for start in range(0, result.size, rows):
        for i in range(start, min(start + rows, result.size)):
            ok = bool(result.assembled[i])
            writer.writerow([_cell(n, c[i], ok, scales.get(n, 1.0), digits.get(n, 6)) for n, c in zip(names, columns)])
        yield buffer.getvalue()
        buffer.seek(0)
        buffer.truncate()
    if buffer.tell():
        yield buffer.getvalue()  # the header of an empty table


def sweep_json(result: SweepResult) -> str:
    """:meth:`SweepResult.to_dict` as indented JSON."""
    return "".join(sweep_json_pieces(result))


def sweep_json_pieces(result: SweepResult) -> Iterator[str]:
    """:func:`sweep_json` in pieces: the summary, then one column at a time (a writer never holds the whole table as text).

    Examples
    --------
    >>> import json, mobility
    >>> r = mobility.sweep(mobility.load("mechanisms/parallelogram.yaml"), ["O1=0:360:13"])
    >>> json.loads("".join(sweep_json_pieces(r))) == r.to_dict()
    True
    """
    yield json.dumps(result.summary_dict(), indent=1, ensure_ascii=False)[:-2] + ',\n "columns": {'
    for k, name in enumerate(result.columns):
        values = json.dumps(result.column_list(name), indent=1, ensure_ascii=False).replace("\n", "\n  ")
        yield ("," if k else "") + f"\n  {json.dumps(name)}: {values}"
    yield "\n }\n}"
