"""The answer of :func:`mobility.finite.finite_mobility` for people: the section printed by ``mobility analyze --finite``.

Examples
--------
>>> from mobility.core.model import Joint, Mechanism
>>> from mobility.finite import finite_mobility
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
>>> m = Mechanism("four-bar", "g", "c", (R("A", "g", "k", (0, 0, 0)), R("B", "k", "c", (1, 2, 0)),
...                                        R("C", "c", "r", (4, 2.5, 0)), R("D", "r", "g", (5, 0, 0))))
>>> print(finite_report(finite_mobility(m)).splitlines()[1])
  verdict: full-cycle
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..errors import counted
from .text import with_section

if TYPE_CHECKING:  # pragma: no cover
    from ..finite.results import FiniteMobility, SecondOrder

__all__ = ["finite_report", "with_finite"]


def finite_report(f: "FiniteMobility") -> str:
    """The text section printed by ``mobility analyze --finite``: verdict, answers, moves, second order, branches, warnings."""
    out = ["finite motion (instantaneous or full-cycle):", f"  verdict: {f.verdict}",
           f"  instantaneous: DOF {f.instantaneous_dof} ({f.instantaneous_pattern}), mobility {f.instantaneous_mobility}"
           f"   (distance to a singularity: {f.margin.smallest_kept:.2e})",
           f"  full-cycle:    DOF {f.full_cycle_dof} ({f.full_cycle_pattern}), mobility {f.full_cycle_mobility}"]
    if f.instantaneous_only_dof or f.instantaneous_only_mobility:
        out.append(f"  instantaneous only: {f.instantaneous_only_dof} end-effector DOF, {counted(f.instantaneous_only_mobility, 'freedom')} of the mechanism")
    if f.probes:
        out.append(f"  moves: {f.moved} of {counted(len(f.probes), 'direction')} re-closed at every step ({', '.join(f'{h:g}' for h in f.steps)}; "
                   f"radians, lengths over the characteristic length)")
    if f.second_order is not None:
        out.append(f"  second order: {counted(f.second_order.cokernel, 'dependent loop equation')}; {_second_order_text(f.second_order)}")
    out += [f"  branch {i + 1}: {b.describe()}" for i, b in enumerate(f.branches)]
    out.append("  " + f.explanation)
    out += [f"  warning: {w}" for w in f.warnings]
    return "\n".join(out)


def _second_order_text(so: "SecondOrder") -> str:
    if so.obstructed:
        return f"obstructed (least violation {so.least_violation:.2e}, relative): no direction survives"
    if so.directions.shape[1]:
        return f"{counted(so.directions.shape[1], 'direction line')} survive{'s' if so.directions.shape[1] == 1 else ''}"
    return "every first-order motion survives"


def with_finite(report: str, fmt: str, finite: "FiniteMobility") -> str:
    """A report of ``mobility analyze`` in format ``fmt`` with the finite-motion answer added (key ``finite``: :func:`~mobility.report.text.with_section`).

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> from mobility.finite import finite_mobility
    >>> f = finite_mobility(Mechanism("slide", "g", "s", (Joint("p", "P", ("g", "s"), axis=(1, 0, 0)),)))
    >>> import json
    >>> json.loads(with_finite('{"dof": 1}', "json", f))["finite"]["verdict"]
    'full-cycle'
    """
    return with_section(report, fmt, "finite", finite.to_dict(), "Finite motion", finite_report(finite))
