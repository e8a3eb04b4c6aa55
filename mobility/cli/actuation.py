"""``mobility actuation FILE``: which joints (or linear actuators) may drive a mechanism.

For a mechanism file: the actuation wrench of every joint marked
``actuated: true``, the constraint wrenches and the verdict (valid,
actuation-singular with the uncontrolled directions, or redundant), with the
actuation conditioning.  ``--enumerate`` checks every combination of inputs
(one joint per limb, or ``--mode any --k K``) at the given pose and at further
poses (``--pose FILE``, ``--samples N``), grouped by type and ranked.

For a flexure document (top-level ``elements``): the compliance eigenvalues,
the freedom and constraint spaces, and the same verdict for the linear
actuators marked ``actuated: true`` (``--enumerate``: every set of ``k``
candidate actuators).

Exit status: 0 when the chosen inputs are valid (with ``--enumerate``: when at
least one combination is valid), 1 otherwise, 2 on bad input.
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

from ..actuation.actuation import VALID, ActuationCheck, Enumeration, check_actuation, check_over_poses, enumerate_actuations
from ..errors import MechanismFileError
from ..flexure.spaces import FlexureSpaces, check_force_lines, enumerate_force_lines, flexure_spaces
from ..flexure.loader import is_flexure_document, loads_flexure
from ..io.loader import load, loads
from ..report.text import fmt_number, fmt_vector
from ..core.result import ScrewAxis
from ..core.tolerance import Tolerance
from ..io.yaml_source import parse_yaml, read_text
from ._options import add_tolerance_option, tolerance_from

ORDER = 30


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "actuation",
        help="which joints (or linear actuators) may drive the mechanism: actuation wrenches and verdicts",
        description="Actuation spaces (Li, Shan, Yu, Ke 2021): a choice of inputs is valid when its actuation wrenches "
        "and the constraint wrenches together span six dimensions.",
    )
    p.add_argument("file", help="mechanism file or flexure document (YAML)")
    p.add_argument("--enumerate", action="store_true", help="check every combination of inputs, grouped by type and ranked")
    p.add_argument("--mode", choices=("limb", "any"), default="limb", help="enumeration: one joint per limb (default) or any K joints")
    p.add_argument("--k", type=int, default=None, help="inputs per combination with --mode any (default: the DOF)")
    p.add_argument("--inputs", default=None, help="comma-separated joint (or actuator) names to check instead of those marked actuated")
    p.add_argument("--pose", action="append", default=[], metavar="FILE", help="another pose of the same mechanism (repeatable)")
    p.add_argument("--samples", type=int, default=0, help="also check N poses reached by moving the mechanism (needs mobility.finite.full_cycle)")
    p.add_argument("--step", type=float, default=0.1, help="step passed to the pose sampler (default: %(default)g)")
    p.add_argument("--seed", type=int, default=0, help="seed of the pose sampler (default: %(default)d)")
    p.add_argument("--threshold", type=float, default=None, help="flexure: relative compliance above which a direction is free (default: the file's, else 0.01)")
    add_tolerance_option(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    if args.threshold is not None and not (0.0 < args.threshold < 1.0):
        print("mobility actuation: error: --threshold must lie between 0 and 1", file=sys.stderr)
        return 2
    if args.samples < 0 or (args.k is not None and args.k < 0):
        print("mobility actuation: error: --samples and --k must not be negative", file=sys.stderr)
        return 2
    tol = tol
    text = read_text(args.file)
    data, _ = parse_yaml(text, args.file)
    names = [n.strip() for n in args.inputs.split(",") if n.strip()] if args.inputs is not None else None
    if is_flexure_document(data):
        if args.pose or args.samples:
            print("mobility actuation: error: --pose and --samples apply to rigid mechanisms only (a flexure is analysed at its one pose)", file=sys.stderr)
            return 2
        return _run_flexure(args, loads_flexure(text, file=args.file), names, tol)
    mechanism = loads(text, file=args.file)
    if args.enumerate:
        poses = [load(p) for p in args.pose]
        try:
            found = enumerate_actuations(mechanism, mode=args.mode, k=args.k, poses=poses, samples=args.samples, step=args.step, seed=args.seed, tol=tol)
        except ValueError as exc:
            if isinstance(exc, MechanismFileError):
                raise
            print(f"mobility actuation: error: {exc}", file=sys.stderr)
            return 2
        _emit(args, found.to_dict(), lambda: enumeration_text(found))
        return 0 if found.valid else 1
    check = check_actuation(mechanism, names, tol=tol)
    extra = check_over_poses(mechanism, names, [load(p) for p in args.pose], tol=tol) if args.pose else ()
    if args.samples:
        from ..core.kinematics import sample_poses

        sampled = sample_poses(mechanism, args.samples, step=args.step, seed=args.seed)
        extra = tuple(extra) + check_over_poses(mechanism, names, sampled, tol=tol)
    labels = list(args.pose) + [f"sampled pose {i + 1}" for i in range(len(extra) - len(args.pose))]
    payload = check.to_dict()
    if extra:
        payload["poses"] = [{"pose": label, "verdict": c.verdict, "conditioning": c.conditioning} for label, c in zip(labels, extra)]
    _emit(args, payload, lambda: check_text(check, list(zip(labels, extra))))
    return 0 if check.valid and all(c.valid for c in extra) else 1


def _run_flexure(args: argparse.Namespace, mechanism: Any, names: list[str] | None, tol: Tolerance) -> int:
    spaces = flexure_spaces(mechanism, args.threshold, tol=tol)
    if args.enumerate:
        found = enumerate_force_lines(mechanism, args.k, threshold=args.threshold, tol=tol)
        payload = {"spaces": spaces.to_dict(), "enumeration": found.to_dict()}
        _emit(args, payload, lambda: spaces_text(spaces) + "\n" + enumeration_text(found))
        return 0 if found.valid else 1
    check = check_force_lines(mechanism, names, threshold=args.threshold, tol=tol)
    payload = {"spaces": spaces.to_dict(), "actuation": check.to_dict()}
    _emit(args, payload, lambda: spaces_text(spaces) + "\n" + check_text(check, []))
    return 0 if check.valid else 1


def _emit(args: argparse.Namespace, payload: dict[str, Any], text: Any) -> None:
    print(json.dumps(payload, indent=2, ensure_ascii=False) if args.json else text())


# ---------------------------------------------------------------------------
# text reports (formatting only)
# ---------------------------------------------------------------------------


def _line(a: ScrewAxis, scale: float, unit: str) -> str:
    if a.kind == "couple":
        return f"couple about {fmt_vector(a.axis)}"
    text = f"{a.kind} along {fmt_vector(a.axis)} through {fmt_vector(a.point, scale)}"
    if a.pitch:
        text += f" pitch {fmt_number(a.pitch, scale)}{(' ' + unit) if unit else ''}"
    return text


def _motion(a: ScrewAxis, scale: float, unit: str) -> str:
    text = f"{a.kind} about {fmt_vector(a.axis)} through {fmt_vector(a.point, scale)}"
    if a.pitch:
        text += f" pitch {fmt_number(a.pitch, scale)}{(' ' + unit) if unit else ''}/rad"
    return text


def check_text(check: ActuationCheck, poses: list[tuple[str, ActuationCheck]]) -> str:
    """The report of one choice of inputs (and its verdict at further poses)."""
    s, unit = check.length_scale, check.length_unit
    rigid = check.kind == "rigid"
    out = [check.name, f"  end effector: {check.dof} DOF ({check.pattern}); constraint wrenches: {6 - check.dof}"] if rigid else []
    names = ", ".join(i.name for i in check.inputs) or "(none)"
    out.append(f"  inputs: {names} ({len(check.inputs)} for {check.dof} DOF)")
    if check.inputs:
        out.append("  actuation wrenches" + (" (each reciprocal to the other joint twists of its limb):" if rigid else " (the actuators' force lines):"))
    for i in check.inputs:
        where = f"{i.kind}" + (f", limb {i.limb + 1}" if i.limb is not None else "")
        body = "none" if i.axis is None else _line(i.axis, s, unit)
        out.append(f"    {i.name:<6} ({where})  {body}")
        if i.note:
            out.append(f"           {i.note}")
    if rigid:
        out.append("  constraint wrenches on the end effector:")
        out += [f"    C{k + 1}  couple about {fmt_vector(c)}" for k, c in enumerate(check.constraint_couples)]
        n = len(check.constraint_couples)
        out += [f"    W{n + k + 1}  {_line(f, s, unit)}" for k, f in enumerate(check.constraint_forces)]
        if check.dof == 6:
            out.append("    (none)")
    out.append(f"  verdict: {check.verdict.upper()}: {check.explanation}")
    if check.verdict != "actuation-singular":
        out.append(f"  actuation conditioning kappa = {check.conditioning:.3g}   (1: isotropic, 0: actuation singularity)")
    if check.uncontrolled_twists.shape[0]:
        out.append("  uncontrolled directions (the end effector still moves with every input locked):")
        out += [f"    translation along {fmt_vector(t)}" for t in check.uncontrolled_translations]
        out += [f"    {_motion(r, s, unit)}" for r in check.uncontrolled_rotations]
    out.append(f"  rank margin: smallest kept relative singular value {check.margin.smallest_kept:.2e}")
    out += [f"  warning: {w}" for w in check.warnings]
    if poses:
        bad = sum(not c.valid for _, c in poses)
        out.append(f"  other poses: {len(poses) - bad} of {len(poses)} valid")
        out += [f"    {label}: {c.verdict}" + (f", kappa {c.conditioning:.3g}" if c.valid else "") for label, c in poses]
    return "\n".join(out)


def spaces_text(spaces: FlexureSpaces) -> str:
    """The freedom and constraint spaces of a flexure."""
    s, unit = spaces.length, spaces.length_unit
    out = [spaces.name]
    out.append(f"  compliance eigenvalues, relative to the largest ({spaces.largest:.3g} per N in coordinates scaled by L = {fmt_number(spaces.length)} {unit}):")
    out.append("    " + "  ".join(f"{v:.3g}" for v in spaces.eigenvalues))
    out.append(
        f"  threshold {spaces.threshold:g}: {spaces.dof} freedom(s) above it, {6 - spaces.dof} constraint(s) at or below "
        f"(nearest eigenvalues {spaces.gap[0]:.3g} and {spaces.gap[1]:.3g})"
    )
    out.append(f"  freedom space: {spaces.dof} DOF ({spaces.pattern})")
    out += [f"    translation along {fmt_vector(t)}" for t in spaces.freedom_translations]
    out += [f"    {_motion(r, s, unit)}" for r in spaces.freedom_rotations]
    out.append(f"  constraint space: {6 - spaces.dof} wrench(es)")
    out += [f"    couple about {fmt_vector(c)}" for c in spaces.constraint_couples]
    out += [f"    {_line(f, s, unit)}" for f in spaces.constraint_forces]
    out += [f"  warning: {w}" for w in spaces.warnings]
    return "\n".join(out)


def enumeration_text(found: Enumeration) -> str:
    """The table of ``--enumerate``."""
    how = "one actuated joint per limb" if found.mode == "limb" else f"any {found.k} input(s)"
    out = [] if found.kind == "flexure" else [found.name]
    out.append(
        f"  {found.dof} DOF ({found.pattern}); {how}: {len(found.combinations)} combination(s), "
        f"checked at {len(found.poses)} pose(s)"
    )
    out.append("  type            valid / total")
    out += [f"  {g.type:<15} {g.valid:>5} / {g.total}" for g in found.groups]
    width = max([len(" ".join(c.inputs)) for c in found.combinations] + [6])
    out.append(f"  {'rank':<5} {'inputs':<{width}}  {'type':<11} {'verdict':<19} {'poses valid':<12} worst kappa")
    for k, c in enumerate(found.combinations):
        worst = f"{c.conditioning:.3g}" + (f" (pose {c.worst_pose})" if len(found.poses) > 1 else "")
        out.append(f"  {k + 1:<5} {' '.join(c.inputs):<{width}}  {c.type:<11} {c.verdict:<19} {c.valid_poses:>3} / {c.poses:<6} {worst}")
    if len(found.poses) > 1:
        out.append("  poses: " + "; ".join(f"{i}: {p}" for i, p in enumerate(found.poses)))
    out += [f"  warning: {w}" for w in found.warnings]
    if not found.valid:
        out.append("  no combination is valid at every pose")
    elif found.valid[0].verdict == VALID:
        best = found.valid[0]
        out.append(f"  best: {' '.join(best.inputs)} ({best.type}), worst-pose actuation conditioning {best.conditioning:.3g}")
    return "\n".join(out)
