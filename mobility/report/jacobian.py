"""Reports of a Jacobian (:class:`~mobility.jacobians.JacobianResult`): text and JSON.

Only formatting: no computation happens here.  :func:`jacobian_text` is what
``mobility jacobian`` prints, :func:`jacobian_json` its ``--json`` object;
:func:`wrench_line` writes one wrench as its kind and axis.

Examples
--------
>>> import numpy as np
>>> wrench_line(np.array([0.0, 0, 2, 0, -2, 0]), 1.0)                # a force along z through (1, 0, 0)
'force   along [0, 0, 1]  through [1, 0, 0]'
>>> wrench_line(np.array([0.0, 0, 0, 0, 0, 5]), 1.0)
'couple  about [0, 0, 1]'
"""

from __future__ import annotations

import json

import numpy as np

from ..jacobians import JacobianResult, wrench_axis
from .text import fmt_number, fmt_vector

__all__ = ["wrench_line", "jacobian_text", "jacobian_json"]


def wrench_line(wrench: np.ndarray, scale: float) -> str:
    """A wrench ``[f; m]`` as ``kind  along ... through ...`` (a couple: ``about ...``), lengths rounded against ``scale``."""
    kind, d, p, h = wrench_axis(wrench)
    if kind == "couple":
        return f"couple  about {fmt_vector(d)}"
    pitch = "" if kind == "force" else f"  pitch {fmt_number(h, scale)}"
    return f"{kind:<6}  along {fmt_vector(d)}  through {fmt_vector(p, scale)}{pitch}"


def jacobian_text(result: JacobianResult, unit: str = "") -> str:
    """The report printed by ``mobility jacobian``: wrenches, the matrix ``J`` and, when regular, ``J^-1``.

    Parameters
    ----------
    result : JacobianResult
    unit : str
        The mechanism's length unit, named in the matrix's heading.
    """
    scale = float(np.max(np.abs(result.matrix))) if result.matrix.size else 1.0
    labels = list(result.actuated) + [f"C{k + 1}" for k in range(result.constraint_wrenches.shape[0])]
    width = max(len(s) for s in labels) if labels else 2
    out = [result.name, f"  platform DOF: {result.dof}   actuated: {', '.join(result.actuated)}"]
    out.append("  constraint wrenches on the platform:")
    out += [f"    {lab:<{width}}  {wrench_line(w, scale)}" for lab, w in zip(labels[len(result.actuated) :], result.constraint_wrenches)] or ["    (none)"]
    out.append("  actuation wrenches (unit reciprocal product with their joint's twist):")
    out += [f"    {lab:<{width}}  {wrench_line(w, scale)}" for lab, w in zip(result.actuated, result.actuation_wrenches)]
    units = f" (lengths in {unit})" if unit else ""
    out.append(f"  Jacobian J: J [w; v] = [actuated rates; 0]{units}")
    head = "".join(f"{c:>12}" for c in ("wx", "wy", "wz", "vx", "vy", "vz"))
    out.append(f"    {'':<{width}}{head}")
    for lab, row in zip(labels, result.matrix):
        out.append(f"    {lab:<{width}}" + "".join(f"{fmt_number(x, scale):>12}" for x in row))
    if result.singular or result.twist_map is None:
        why = "not square" if result.matrix.shape[0] != 6 else f"rank {result.rank} < 6"
        out.append(f"  J is singular ({why}): the actuated joints do not control the platform at this pose")
    else:
        out.append(f"  condition number (normalised coordinates): {fmt_number(result.condition)}")
        out.append("  platform twist [w; v] per unit actuated rate (columns of J^-1):")
        out += [f"    {lab:<{width}}  {fmt_vector(col, scale)}" for lab, col in zip(result.actuated, result.twist_map.T)]
    return "\n".join(out)


def jacobian_json(result: JacobianResult) -> str:
    """The result as one JSON object (``mobility jacobian --json``)."""
    return json.dumps(result.to_dict(), indent=2)
