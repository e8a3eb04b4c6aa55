"""Advice on closures (:func:`mobility.core.closures.closure_advice`) for people: what ``mobility analyze`` adds for a robot file with loops.

Examples
--------
>>> from mobility.core.model import Joint, Mechanism
>>> from mobility.core.closures import closure_advice
>>> z = (0, 0, 1)
>>> m = Mechanism("four-bar", "ground", "coupler", (
...     Joint("A", "R", ("ground", "crank"), axis=z, point=(0, 0, 0)),
...     Joint("B", "R", ("crank", "coupler"), axis=z, point=(1, 2, 0)),
...     Joint("D", "R", ("ground", "rocker"), axis=z, point=(5, 0, 0)),
...     Joint("C", "S", ("coupler", "rocker"), point=(4, 2.5, 0))))
>>> for line in closures_report(closure_advice(m, ["C"])).splitlines()[:3]:
...     print(line)
closures (how many constraint rows of each closing joint the rest of the mechanism does not already impose):
  C: 3 rows, 2 independent, 1 redundant
    redundant: force along [0, 0, 1] through [4, 2.5, 0]
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Sequence

from ..errors import counted
from .text import fmt_number, fmt_vector, with_section

if TYPE_CHECKING:  # pragma: no cover
    from ..core.closures import ClosureAdvice

__all__ = ["closures_report", "with_closures"]


def closures_report(advice: Sequence["ClosureAdvice"]) -> str:
    """The text section: each closing joint's rows, how many are independent, and the redundant directions."""
    out = ["closures (how many constraint rows of each closing joint the rest of the mechanism does not already impose):"]
    for a in advice:
        line = f"  {a.joint}: {counted(a.rows, 'row')}, {a.independent} independent"
        if a.redundant:
            line += f", {a.redundant} redundant"
        out.append(line)
        out += [f"    redundant: couple about {fmt_vector(c)}" for c in a.couples]
        for f in a.forces:
            pitch = "" if f.pitch == 0 else f" with couple pitch {fmt_number(f.pitch, a.length_scale)}"
            out.append(f"    redundant: {f.kind} along {fmt_vector(f.axis)} through {fmt_vector(f.point, a.length_scale)}{pitch}")
    if any(a.redundant for a in advice):
        out.append("  a closure with redundant rows over-constrains a simulator's loop (a singular constraint Jacobian): "
                   "a closure of fewer rows, or one that leaves the redundant directions free, holds the same mechanism")
    return "\n".join(out)


def with_closures(report: str, fmt: str, advice: Sequence["ClosureAdvice"]) -> str:
    """A report of ``mobility analyze`` in format ``fmt`` with the advice on closures added (key ``closures``: :func:`~mobility.report.text.with_section`; nothing without closures)."""
    if not advice:
        return report
    return with_section(report, fmt, "closures", [a.to_dict() for a in advice], "Closures", closures_report(advice))
