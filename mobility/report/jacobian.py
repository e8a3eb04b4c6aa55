"""Reports of a Jacobian (:class:`~mobility.jacobians.JacobianResult`): text and JSON.

Round-off is shown as 0 relative to what a number is part of (:func:`~mobility.jacobians.wrenches.clean_screw`),
so a file scaled by any factor prints the same digits, scaled.

Examples
--------
>>> import numpy as np
>>> wrench_line(np.array([0.0, 0, 2, 0, -2, 0]), 1.0)                # a force along z through (1, 0, 0)
'force   along [0, 0, 1]  through [1, 0, 0]'
>>> wrench_line(np.array([0.0, 0, 0, 0, 0, 5]), 1.0)
'couple  about [0, 0, 1]'
>>> wrench_line(np.array([0.0, 0, 2e-200, 0, -2, 0]), 1e200)          # the same force, the file scaled by 1e200
'force   along [0, 0, 1]  through [1e+200, 0, 0]'
"""

from __future__ import annotations

import json

import numpy as np

from ..jacobians import JacobianResult, clean_screw, wrench_axis
from ..errors import counted
from .text import fmt_number, fmt_vector

__all__ = ["wrench_line", "jacobian_text", "jacobian_json"]


def wrench_line(wrench: np.ndarray, length: float) -> str:
    """A wrench ``[f; m]`` as ``kind  along ... through ...`` (a couple: ``about ...``), against the characteristic ``length``."""
    kind, d, p, h = wrench_axis(wrench, length=length)
    if kind == "couple":
        return f"couple  about {fmt_vector(d)}"
    size = max(length, float(np.max(np.abs(p))))
    pitch = "" if kind == "force" else f"  pitch {fmt_number(h, size)}"
    return f"{kind:<6}  along {fmt_vector(d)}  through {fmt_vector(p, size)}{pitch}"


def _shown(x: float) -> str:
    """A number already cleaned of round-off, with 6 significant digits."""
    return "0" if x == 0.0 else f"{x:.6g}"


def jacobian_text(result: JacobianResult, unit: str = "") -> str:
    """The report printed by ``mobility jacobian``: wrenches, the matrix ``J`` (``unit``: named in its heading) and, when regular, ``J^-1``."""
    length = result.length
    labels = list(result.actuated) + [f"C{k + 1}" for k in range(result.constraint_wrenches.shape[0])]
    width = max(len(s) for s in labels) if labels else 2
    out = [result.name, f"  platform DOF: {result.dof}   actuated: {', '.join(result.actuated)}"]
    out.append("  constraint wrenches on the platform:")
    out += [f"    {lab:<{width}}  {wrench_line(w, length)}" for lab, w in zip(labels[len(result.actuated) :], result.constraint_wrenches)] or ["    (none)"]
    out.append("  actuation wrenches (unit reciprocal product with their joint's twist):")
    out += [f"    {lab:<{width}}  {wrench_line(w, length)}" for lab, w in zip(result.actuated, result.actuation_wrenches)]
    out.append(f"  Jacobian J: J [w; v] = [actuated rates; 0]{f' (lengths in {unit})' if unit else ''}")
    cells = [[_shown(x) for x in clean_screw(row, length, moment_first=True)] for row in result.matrix]
    column = max([12] + [len(c) + 2 for row in cells for c in row])
    out.append(f"    {'':<{width}}" + "".join(f"{c:>{column}}" for c in ("wx", "wy", "wz", "vx", "vy", "vz")))
    for lab, row in zip(labels, cells):
        out.append(f"    {lab:<{width}}" + "".join(f"{c:>{column}}" for c in row))
    rows = result.matrix.shape[0]
    if result.singular:
        why = f"rank {result.rank} < 6" + (f", {counted(rows, 'row')}" if rows != 6 else "")
        out.append(f"  J is singular ({why}): the actuated joints do not control the platform at this pose")
    elif result.twist_map is None:  # regular with more rows than 6: redundant actuation
        out.append(f"  condition number (normalised coordinates): {fmt_number(result.condition)}")
        out.append(f"  J has rank 6 with {counted(rows, 'row')}: the platform is controlled, redundantly ({result.redundant} input"
                   f"{'s' if result.redundant > 1 else ''} more than needed); the actuated rates must agree, J [w; v] = [rates; 0]")
    else:
        out.append(f"  condition number (normalised coordinates): {fmt_number(result.condition)}")
        out.append("  platform twist [w; v] per unit actuated rate (columns of J^-1):")
        out += [f"    {lab:<{width}}  [" + ", ".join(_shown(x) for x in clean_screw(col, length)) + "]" for lab, col in zip(result.actuated, result.twist_map.T)]
    return "\n".join(out)


def jacobian_json(result: JacobianResult) -> str:
    """The result as one JSON object (``mobility jacobian --json``)."""
    return json.dumps(result.to_dict(), indent=2)
