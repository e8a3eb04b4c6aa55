"""Human-readable and JSON reports of a :class:`~mobility.core.result.Result`.

Examples
--------
>>> fmt_number(1.23456789e-17), fmt_number(-0.5), fmt_number(1500.0)
('0', '-0.5', '1500')
>>> fmt_vector([0.0, 0.70710678118, -0.70710678118])
'[0, 0.707107, -0.707107]'
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from ..core.result import Result, ScrewAxis, require_result
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, clean_numbers
from ..errors import AnalysisError, counted
from .idle import idle_hint

__all__ = ["fmt_number", "fmt_vector", "screw_text", "margin_lines", "text_report", "json_report"]


def fmt_number(x: float, scale: float = 1.0, digits: int = 6, tol: Tolerance = DEFAULT_TOLERANCE) -> str:
    """A number with ``digits`` significant digits; round-off shown as 0 by the one rule, :func:`~mobility.core.tolerance.clean_numbers`.

    ``scale``: the size round-off is relative to (the mechanism's length for a point or a pitch, 1 for a unit direction).
    """
    text = f"{clean_numbers(float(x), scale, tol):.{digits}g}"
    return "0" if text in ("-0", "0") else text


def fmt_vector(v: Any, scale: float = 1.0) -> str:
    """A vector as ``[a, b, c]``."""
    return "[" + ", ".join(fmt_number(x, scale) for x in np.asarray(v, dtype=float)) + "]"


def screw_text(a: ScrewAxis, scale: float = 1.0, *, verb: str = "about", pitch_unit: str = "") -> str:
    """A screw axis in words: kind, ``verb`` (``"about"``, ``"along"`` or none), direction, a point, and the pitch when it is not zero.

    ``scale``: the mechanism's length (as for :func:`fmt_number`); ``pitch_unit`` is written after the pitch.

    Examples
    --------
    >>> import numpy as np
    >>> from mobility.core.result import ScrewAxis
    >>> screw_text(ScrewAxis(np.array([0, 0, 1.0]), np.array([1.0, 0, 0]), 0.5, "helical"), pitch_unit=" mm/rad")
    'helical about [0, 0, 1] through [1, 0, 0] pitch 0.5 mm/rad'
    >>> screw_text(ScrewAxis(np.array([1.0, 0, 0]), np.zeros(3), 0.0, "force"), verb="")
    'force [1, 0, 0] through [0, 0, 0]'
    """
    head = " ".join(part for part in (a.kind, verb, fmt_vector(a.axis)) if part)
    pitch = "" if a.pitch == 0 else f" pitch {fmt_number(a.pitch, scale)}{pitch_unit}"
    return f"{head} through {fmt_vector(a.point, scale)}{pitch}"


def _axis_line(label: str, a: ScrewAxis, scale: float, unit: str) -> str:
    pitch = "0" if a.pitch == 0 else f"{fmt_number(a.pitch, scale)}{(' ' + unit) if unit else ''}/rad"
    return f"    {label:<3} axis {fmt_vector(a.axis)}  through {fmt_vector(a.point, scale)}  pitch {pitch}  ({a.kind})"


def margin_lines(result: Result) -> list[str]:
    """How far the pose is from a change of the count, and how far the geometry is from the special one the count relies on, in words and numbers.

    Examples
    --------
    >>> import mobility
    >>> first, second = margin_lines(mobility.analyze(mobility.load("mechanisms/four_bar.yaml")))
    >>> print(first)
      distance to a singularity: 3.46e-01   (1 far from one, 0 where the count changes: the smallest kept singular value, relative)
    >>> second.split(":")[0]  # its number is round-off here, which differs between BLAS builds
    '  departure from the special geometry'
    """
    margin = result.margin
    return [
        f"  distance to a singularity: {margin.smallest_kept:.2e}   (1 far from one, 0 where the count changes: the smallest kept singular value, relative)",
        f"  departure from the special geometry: {margin.largest_dropped:.2e}   (0 or round-off when it is exact: the largest dropped singular value, relative)",
    ]


def text_report(result: Result, *, limbs: bool = False) -> str:
    """The report printed by ``mobility analyze`` (``limbs``: also each limb's twists and constraint wrenches in the limb's frame)."""
    result = require_result(result, "text_report")
    s = result.length_scale
    unit = result.length_unit
    out = [result.name, f"  end-effector DOF: {result.dof}   pattern: {result.pattern}"]
    if result.translation_count:
        out.append("  translations (orthonormal basis):")
        out += [f"    T{i + 1}  {fmt_vector(t)}" for i, t in enumerate(result.translations)]
    if result.rotations:
        out.append(f"  rotations (the end effector's centre is at {fmt_vector(result.reference_point, s)}; each axis is shown through its point nearest it):")
        out += [_axis_line(f"R{i + 1}", a, s, unit) for i, a in enumerate(result.rotations)]
    if result.dof == 0:
        out.append("  the end effector cannot move (at first order)")
    out.append(f"  constraint wrenches on the end effector: {6 - result.dof}")
    out += [f"    C{i + 1}  couple about {fmt_vector(c)}" for i, c in enumerate(result.couples)]
    k = len(result.couples)
    for i, f in enumerate(result.forces):
        pitch = "" if f.pitch == 0 else f"  with couple pitch {fmt_number(f.pitch, s)}"
        out.append(f"    W{k + i + 1}  {f.kind} along {fmt_vector(f.axis)} through {fmt_vector(f.point, s)}{pitch}")
    out += ["  whole mechanism:", f"    mobility M = {result.mobility}   (Grübler–Kutzbach count: {result.gruebler_kutzbach})",
            f"    redundant constraints: {result.redundant_constraints}   idle DOF: {result.idle_dof}   "
            f"loops: {result.loops}   links: {result.links}   joints: {result.joints} ({counted(result.joint_freedoms, 'freedom')})"]
    if result.gruebler_kutzbach_explanation:
        out.append("    why G–K differs: " + result.gruebler_kutzbach_explanation)
    if result.idle_dof:
        out.append(f"    idle DOF: {counted(result.idle_dof, 'motion')} of the joints {'leaves' if result.idle_dof == 1 else 'leave'} the end effector still ({idle_hint(result)})")
    out.append(f"  structure: {result.structure}")
    out += margin_lines(result)
    out += [f"  precision: {result.precision_summary}"] if result.precision_summary else []
    out += [f"  warning: {w}" for w in result.warnings]
    if limbs and result.limbs:
        out.append("  limbs (each in its own frame):")
        for i, limb in enumerate(result.limbs):
            out.append(f"    limb {i + 1}: {limb.structure}   frame: {limb.frame}   DOF {limb.dof}   idle {limb.idle_dof}")
            out += [f"      translation {fmt_vector(t)}" for t in limb.translations]
            out += [f"      {screw_text(a, s)}" for a in limb.rotations]
            out += [f"      constraint couple about {fmt_vector(c)}" for c in limb.couples]
            out += [f"      constraint {screw_text(f, s, verb='along')}" for f in limb.forces]
    return "\n".join(out)


def json_report(result: Result) -> str:
    """The result as one JSON object (``mobility analyze --json``): always valid JSON (an :class:`AnalysisError` for a number not finite)."""
    result = require_result(result, "json_report")
    try:
        return json.dumps(result.to_dict(), indent=2, ensure_ascii=False, allow_nan=False)
    except ValueError:
        raise AnalysisError(f"the result of {result.name!r} holds a number that is not finite; it cannot be written as JSON") from None


def with_section(report: str, fmt: str, key: str, value: Any, heading: str, section: str) -> str:
    """A report of ``mobility analyze`` in format ``fmt`` with one more section.

    ``"json"``: ``value`` is added to the object under ``key``; ``"md"``: ``section`` under the heading
    ``heading``, in a code block; any other (``"text"``): ``section`` appended.

    Examples
    --------
    >>> json.loads(with_section('{"dof": 1}', "json", "extra", [1], "Extra", "extra: 1"))
    {'dof': 1, 'extra': [1]}
    >>> with_section("report", "text", "extra", [1], "Extra", "extra: 1").splitlines()
    ['report', 'extra: 1']
    """
    if fmt == "json":
        data = json.loads(report)
        data[key] = value
        return json.dumps(data, indent=2, ensure_ascii=False)
    if fmt == "md":
        return report.rstrip("\n") + f"\n\n## {heading}\n\n```\n" + section + "\n```\n"
    return report + "\n" + section
