"""Reports of actuation assessments and flexure spaces, as text and as JSON (``mobility actuation`` and its ``--json``).

Examples
--------
>>> from mobility.actuation import check_actuation
>>> from mobility.core.model import Joint, Mechanism
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
>>> arm = Mechanism("RR arm", "g", "hand", (R("A", "g", "upper", (0, 0, 0)), R("B", "upper", "hand", (1, 0, 0))))
>>> print(actuation_text(check_actuation(arm, ["A"])))
RR arm
  end effector: 2 DOF (1T1R); constraint wrenches: 4
  inputs: A (1 for 2 DOF)
  actuation wrenches (each reciprocal to the other joint twists of its limb):
    A      (R, limb 1)  force along [0, 1, 0] through [1, 0, 0]
  constraint wrenches on the end effector:
    C1  couple about [1, 0, 0]
    C2  couple about [0, 1, 0]
    W3  force along [1, 0, 0] through [1, 0, 0]
    W4  force along [0, 0, 1] through [1, 0, 0]
  verdict: ACTUATION-SINGULAR: actuation and constraint wrenches span only 5 of 6 dimensions: with the inputs locked the end effector can still move along 1 direction (fewer inputs, 1, than DOF, 2)
  uncontrolled directions (the end effector still moves with every input locked):
    rotation about [0, 0, 1] through [1, 0, 0]
  actuation margin: 0.00e+00   (0 at an actuation singularity: the locked inputs do not hold the end effector, or an input does not drive it)
  rank margin: smallest kept relative singular value 1.00e+00
"""

from __future__ import annotations

import json
from typing import Any, Sequence

from ..actuation import SINGULAR, VALID, ActuationCheck, Enumeration
from ..core.result import ScrewAxis
from ..errors import counted
from ..flexure import FlexureSpaces
from .text import fmt_number, fmt_vector, screw_text

__all__ = ["actuation_text", "actuation_json", "enumeration_text", "enumeration_json", "flexure_spaces_text", "flexure_text", "flexure_json"]

PoseChecks = Sequence[tuple[str, ActuationCheck]]
"""Further poses of one choice of inputs: ``(label, check)`` pairs."""


def _line(a: ScrewAxis, scale: float, unit: str) -> str:
    """A wrench's line: ``force along [..] through [..]`` (with its pitch), or a couple."""
    if a.kind == "couple":
        return f"couple about {fmt_vector(a.axis)}"
    return screw_text(a, scale, verb="along", pitch_unit=f" {unit}" if unit else "")


def _motion(a: ScrewAxis, scale: float, unit: str) -> str:
    """A twist's axis: ``rotation about [..] through [..]`` (with its pitch per radian)."""
    return screw_text(a, scale, verb="about", pitch_unit=f" {unit}/rad" if unit else "/rad")


def actuation_text(check: ActuationCheck, poses: PoseChecks = ()) -> str:
    """The report of one choice of inputs and its verdict at further poses (a flexure's name, DOF and wrenches: :func:`flexure_spaces_text`)."""
    s, unit = check.length_scale, check.length_unit
    rigid = check.kind == "rigid"
    out = [check.name, f"  end effector: {check.dof} DOF ({check.pattern}); constraint wrenches: {6 - check.dof}"] if rigid else []
    names = ", ".join(i.name for i in check.inputs) or "(none)"
    out.append(f"  inputs: {names} ({len(check.inputs)} for {check.dof} DOF)")
    if check.inputs:
        out.append("  actuation wrenches" + (" (each reciprocal to the other joint twists of its limb):" if rigid else " (the actuators' force lines):"))
    for i in check.inputs:
        where = f"{i.kind}" + (f", limb {i.limb + 1}" if i.limb is not None else "")
        out.append(f"    {i.name:<6} ({where})  {'none' if i.axis is None else _line(i.axis, s, unit)}")
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
    if check.verdict != SINGULAR:
        if check.dof == 0:
            legend = "no end-effector freedom to control: 1 by convention"
        elif check.dof == 1:
            legend = "one end-effector freedom: 1 by definition; the actuation margin below is the distance to an actuation singularity"
        else:
            legend = "1: isotropic, 0: the inputs' effects lose rank; it stays finite where they all vanish together: the actuation margin below measures that"
        out.append(f"  actuation conditioning kappa = {check.conditioning:.3g}   ({legend})")
    if check.uncontrolled_twists.shape[0]:
        out.append("  uncontrolled directions (the end effector still moves with every input locked):")
        out += [f"    translation along {fmt_vector(t)}" for t in check.uncontrolled_translations]
        out += [f"    {_motion(r, s, unit)}" for r in check.uncontrolled_rotations]
    out.append(f"  actuation margin: {check.actuation_margin:.2e}   (0 at an actuation singularity: the locked inputs do not hold the end effector, or an input does not drive it)")
    out.append(f"  rank margin: smallest kept relative singular value {check.margin.smallest_kept:.2e}")
    out += [f"  warning: {w}" for w in check.warnings]
    if poses:
        out.append(f"  other poses: {sum(c.valid for _, c in poses)} of {len(poses)} valid")
        out += [f"    {label}: {c.verdict}" + (f", kappa {c.conditioning:.3g}" if c.valid else "") for label, c in poses]
    return "\n".join(out)


def actuation_json(check: ActuationCheck, poses: PoseChecks = ()) -> str:
    """:meth:`ActuationCheck.to_dict`, with ``poses`` (label, verdict, conditioning) when there are further poses.

    Examples
    --------
    >>> import json
    >>> from mobility.actuation import check_actuation
    >>> from mobility.core.model import Joint, Mechanism
    >>> arm = Mechanism("R arm", "g", "hand", (Joint("A", "R", ("g", "hand"), axis=(0, 0, 1), point=(0, 0, 0)),))
    >>> check = check_actuation(arm, ["A"])
    >>> data = json.loads(actuation_json(check, [("elsewhere", check)]))
    >>> data["verdict"], data["poses"]
    ('valid', [{'pose': 'elsewhere', 'verdict': 'valid', 'conditioning': 1.0}])
    """
    payload = check.to_dict()
    if poses:
        payload["poses"] = [{"pose": label, "verdict": c.verdict, "conditioning": c.conditioning} for label, c in poses]
    return _dumps(payload)


def enumeration_text(found: Enumeration) -> str:
    """The table of ``--enumerate``: counts per type, then every combination ranked."""
    how = f"any {counted(found.k, 'input')}" if found.mode != "limb" else _limb_choice(found).replace("one joint", "one actuated joint")
    out = [] if found.kind == "flexure" else [found.name]
    out += [f"  {found.dof} DOF ({found.pattern}); {how}: {counted(len(found.combinations), 'combination')}, checked at {counted(len(found.poses), 'pose')}",
            "  type            valid / total"]
    out += [f"  {g.type:<15} {g.valid:>5} / {g.total}" for g in found.groups]
    width = max([len(" ".join(c.inputs)) for c in found.combinations] + [6])
    out.append(f"  {'rank':<5} {'inputs':<{width}}  {'type':<11} {'verdict':<19} {'poses valid':<12} {'worst kappa':<18} worst margin")
    several = len(found.poses) > 1
    for k, c in enumerate(found.combinations):
        worst = f"{c.conditioning:.3g}" + (f" (pose {c.worst_pose})" if several else "")
        singular_everywhere = sum(v == SINGULAR for _, v in c.failures) == c.poses
        margin = "-" if singular_everywhere else f"{c.margin:.2g}" + (f" (pose {c.margin_pose})" if several else "")
        out.append(f"  {k + 1:<5} {' '.join(c.inputs):<{width}}  {c.type:<11} {c.verdict:<19} {c.valid_poses:>3} / {c.poses:<6} {worst:<18} {margin}")
    if len(found.poses) > 1:
        out.append("  poses: " + "; ".join(f"{i}: {p}" for i, p in enumerate(found.poses)))
    out += [f"  warning: {w}" for w in found.warnings]
    if not found.valid:
        hint = f" ({_limb_choice(found)}; mode 'any', --mode any, tries any {found.dof} of the joints)" if found.mode == "limb" and found.kind == "rigid" else ""
        out.append(f"  no combination is valid at every pose{hint}")
    elif found.valid[0].verdict == VALID:
        best = found.valid[0]
        out.append(f"  best: {' '.join(best.inputs)} ({best.type}), worst-pose actuation conditioning {best.conditioning:.3g}")
    return "\n".join(out)


def enumeration_json(found: Enumeration) -> str:
    """:meth:`Enumeration.to_dict` as JSON text."""
    return _dumps(found.to_dict())


def flexure_spaces_text(spaces: FlexureSpaces) -> str:
    """The compliance eigenvalues and the freedom and constraint spaces of a flexure."""
    s, unit = spaces.length, spaces.length_unit
    out = [spaces.name, f"  compliance eigenvalues, relative to the largest ({spaces.largest:.3g} per N in coordinates scaled by L = {fmt_number(spaces.length)} {unit}):",
           "    " + "  ".join(f"{v:.3g}" for v in spaces.eigenvalues),
           f"  threshold {spaces.threshold:g}: {counted(spaces.dof, 'freedom')} above it, {counted(6 - spaces.dof, 'constraint')} at or below "
           f"(nearest eigenvalues {spaces.gap[0]:.3g} and {spaces.gap[1]:.3g})",
           f"  freedom space: {spaces.dof} DOF ({spaces.pattern})"]
    out += [f"    translation along {fmt_vector(t)}" for t in spaces.freedom_translations]
    out += [f"    {_motion(r, s, unit)}" for r in spaces.freedom_rotations]
    out.append(f"  constraint space: {counted(6 - spaces.dof, 'wrench', 'es')}")
    out += [f"    couple about {fmt_vector(c)}" for c in spaces.constraint_couples]
    out += [f"    {_line(f, s, unit)}" for f in spaces.constraint_forces]
    out += [f"  warning: {w}" for w in spaces.warnings]
    return "\n".join(out)


def flexure_text(spaces: FlexureSpaces, answer: ActuationCheck | Enumeration) -> str:
    """A flexure's spaces followed by the assessment of its actuators (one set, or every set)."""
    body = enumeration_text(answer) if isinstance(answer, Enumeration) else actuation_text(answer)
    return flexure_spaces_text(spaces) + "\n" + body


def flexure_json(spaces: FlexureSpaces, answer: ActuationCheck | Enumeration) -> str:
    """``{"spaces": ..., "actuation": ...}``, or ``"enumeration"`` for every set, as JSON text."""
    key = "enumeration" if isinstance(answer, Enumeration) else "actuation"
    return _dumps({"spaces": spaces.to_dict(), key: answer.to_dict()})


def _dumps(payload: dict[str, Any]) -> str:
    return json.dumps(payload, indent=2, ensure_ascii=False)


def _limb_choice(found: Enumeration) -> str:
    """How mode ``"limb"`` chose the inputs of ``found``: one joint per limb, or in each of DOF of the limbs."""
    return f"one joint in each of {found.k} of the {found.limbs} limbs" if found.limbs > found.k else "one joint per limb"
