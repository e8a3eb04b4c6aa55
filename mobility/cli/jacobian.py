"""``mobility jacobian FILE``: the Jacobian of a parallel mechanism, by differentiating finite screws.

The limbs must be serial chains from the ground to the end effector; the
actuated joints are those marked ``actuated: true`` in the file, or those named
with ``--actuated``.  Exit status 0 when the Jacobian is square and regular, 1
when it is singular (or not square), 2 on bad input.
"""

from __future__ import annotations

import argparse
import json

import numpy as np

from ..errors import MechanismError, MechanismFileError
from ..jacobians.jacobian import JacobianResult, jacobian, wrench_axis
from ..io.loader import load
from ..report.text import fmt_number, fmt_vector
from ._options import add_tolerance_option, tolerance_from

ORDER = 45


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "jacobian",
        help="Jacobian of a parallel mechanism (actuation and constraint wrenches) from its finite screws",
        description="Jacobian by differentiating the limbs' finite screws (Sun et al. 2018, Eq. 26): "
        "J $ = [actuated rates; 0] for the platform twist $ = [w; v].",
    )
    p.add_argument("file", help="mechanism file (YAML) whose limbs are serial chains")
    p.add_argument("--actuated", default=None, metavar="A,B,...", help="actuated joints (default: those marked actuated: true); NAME.k picks the k-th freedom of a multi-DOF joint")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    add_tolerance_option(p)
    p.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    mechanism = load(args.file)
    names = None if args.actuated is None else [n.strip() for n in args.actuated.split(",") if n.strip()]
    try:
        result = jacobian(mechanism, actuated=names, tol=tol)
    except MechanismError as exc:
        if isinstance(exc, MechanismFileError):
            raise
        raise MechanismFileError(exc.key, exc.message, file=args.file) from None
    if args.json:
        print(json.dumps(result.to_dict(), indent=2))
    else:
        print(text_report(result, mechanism.length_unit))
    return 1 if result.singular else 0


def _axis_text(w: np.ndarray, scale: float) -> str:
    kind, d, p, h = wrench_axis(w)
    if kind == "couple":
        return f"couple  about {fmt_vector(d)}"
    pitch = "" if kind == "force" else f"  pitch {fmt_number(h, scale)}"
    return f"{kind:<6}  along {fmt_vector(d)}  through {fmt_vector(p, scale)}{pitch}"


def text_report(result: JacobianResult, unit: str = "") -> str:
    """The report printed by ``mobility jacobian``."""
    scale = float(np.max(np.abs(result.matrix))) if result.matrix.size else 1.0
    labels = list(result.actuated) + [f"C{k + 1}" for k in range(result.constraint_wrenches.shape[0])]
    width = max(len(s) for s in labels) if labels else 2
    out = [result.name, f"  platform DOF: {result.dof}   actuated: {', '.join(result.actuated)}"]
    out.append("  constraint wrenches on the platform:")
    out += [f"    {lab:<{width}}  {_axis_text(w, scale)}" for lab, w in zip(labels[len(result.actuated) :], result.constraint_wrenches)] or ["    (none)"]
    out.append("  actuation wrenches (unit reciprocal product with their joint's twist):")
    out += [f"    {lab:<{width}}  {_axis_text(w, scale)}" for lab, w in zip(result.actuated, result.actuation_wrenches)]
    units = f" (lengths in {unit})" if unit else ""
    out.append(f"  Jacobian J: J [w; v] = [actuated rates; 0]{units}")
    head = "".join(f"{c:>12}" for c in ("wx", "wy", "wz", "vx", "vy", "vz"))
    out.append(f"    {'':<{width}}{head}")
    for lab, row in zip(labels, result.matrix):
        out.append(f"    {lab:<{width}}" + "".join(f"{fmt_number(x, scale):>12}" for x in row))
    if result.singular:
        why = "not square" if result.matrix.shape[0] != 6 else f"rank {result.rank} < 6"
        out.append(f"  J is singular ({why}): the actuated joints do not control the platform at this pose")
    else:
        out.append(f"  condition number (normalised coordinates): {fmt_number(result.condition)}")
        out.append("  platform twist [w; v] per unit actuated rate (columns of J^-1):")
        out += [f"    {lab:<{width}}  {fmt_vector(col, scale)}" for lab, col in zip(result.actuated, result.twist_map.T)]
    return "\n".join(out)
