"""The verdict: what the branches found say about the instantaneous answer, in one word and one paragraph.

* ``full-cycle``: one branch with every instantaneous freedom (also a pose
  with no instantaneous freedom: nothing to follow); when the end effector's
  pattern differs at nearby poses, the explanation says so (a pattern
  singularity at this pose);
* ``instantaneous-only``: one branch, of lower dimension or end-effector DOF;
* ``cannot-move``: no direction moves;
* ``bifurcation``: two or more branches meet (a change point).

Each verdict comes with an explanation holding the numbers behind it.
"""

from __future__ import annotations

from typing import Any

from ..core.result import Result
from ..core.tolerance import Tolerance
from ..errors import counted
from .results import Branch, FiniteMobility, Probe, SecondOrder

__all__ = ["no_motion", "judge"]


def _given_pose(instant: Result, steps: tuple[float, ...]) -> dict[str, Any]:
    """The fields every verdict shares: the instantaneous answer at the given pose."""
    return dict(name=instant.name, instantaneous_dof=instant.dof, instantaneous_pattern=instant.pattern,
                instantaneous_mobility=instant.mobility, margin=instant.margin, steps=steps)


def _steps_text(steps: tuple[float, ...]) -> str:
    return ", ".join(f"{h:g}" for h in steps)


def no_motion(instant: Result, steps: tuple[float, ...], warnings: list[str]) -> FiniteMobility:
    """The verdict at a pose without first-order motion: nothing to follow, full-cycle with DOF 0."""
    text = ("The pose has no first-order motion (mobility 0), so there is nothing to follow: "
            "the DOF 0 found by the screw route holds for finite motion too (a structure).")
    return FiniteMobility(verdict="full-cycle", explanation=text, full_cycle_dof=0, full_cycle_pattern="0", full_cycle_mobility=0,
                          branches=(), probes=(), second_order=None, warnings=tuple(warnings), **_given_pose(instant, steps))


def judge(instant: Result, k: int, branches: list[Branch], probes: tuple[Probe, ...], second: SecondOrder | None,
          steps: tuple[float, ...], warnings: list[str], tol: Tolerance) -> FiniteMobility:
    """The verdict from the branches found by the moves.

    ``instant`` is the screw route at the given pose, ``k`` the first-order
    mobility of the loop-closure route.  Branches of dimension 0 are dropped,
    the others sorted by dimension then DOF, largest first; ``warnings`` is copied, not extended.
    """
    warnings = list(warnings)
    branches = sorted((b for b in branches if b.dimension > 0), key=lambda b: (-b.dimension, -b.dof))
    if not branches:
        text = _cannot_move_text(instant, k, probes, second, steps, tol)
        return FiniteMobility(verdict="cannot-move", explanation=text, full_cycle_dof=0, full_cycle_pattern="0", full_cycle_mobility=0,
                              branches=(), probes=probes, second_order=second, warnings=tuple(warnings), **_given_pose(instant, steps))
    top = branches[0]
    full_dof = max(b.dof for b in branches)
    patterns = list(dict.fromkeys(b.pattern for b in branches if b.dof == full_dof))
    verdict, text = _verdict_text(instant, k, branches, probes, second, steps)
    if verdict != "bifurcation" and len(patterns) > 1:
        warnings.append("branches of equal DOF with different patterns")
    return FiniteMobility(verdict=verdict, explanation=text, full_cycle_dof=full_dof, full_cycle_pattern=" | ".join(patterns),
                          full_cycle_mobility=top.dimension, branches=tuple(branches), probes=probes, second_order=second,
                          warnings=tuple(warnings), **_given_pose(instant, steps))


def _cannot_move_text(instant: Result, k: int, probes: tuple[Probe, ...], second: SecondOrder | None, steps: tuple[float, ...], tol: Tolerance) -> str:
    smallest = min((p.residuals[0] for p in probes), default=float("nan"))
    if second is not None and second.obstructed:
        order2 = (f" The second-order test agrees: no first-order motion keeps the {counted(second.cokernel, 'dependent loop equation')} "
                  f"closed to second order (least violation {second.least_violation:.2e} relative).")
    elif second is not None:
        order2 = " Some directions pass the second-order test, yet no move along them closes: the obstruction is of higher order."
    else:
        order2 = ""
    return (f"The screw route finds {counted(k, 'first-order motion')} (end-effector DOF {instant.dof}), but none is a finite motion: "
            f"in {counted(len(probes), 'direction')}, Newton does not re-close the loops at every step {_steps_text(steps)} "
            f"(smallest residual left at step {steps[0]:g}: {smallest:.2e}; closed means below {tol.closure:.0e}).{order2} "
            "The pose cannot move at all.")


def _verdict_text(instant: Result, k: int, branches: list[Branch], probes: tuple[Probe, ...], second: SecondOrder | None, steps: tuple[float, ...]) -> tuple[str, str]:
    """The verdict when some branch moves, and its explanation."""
    top = branches[0]
    moved = sum(p.moved for p in probes)
    worst = max((p.residuals[-1] for p in probes if p.moved), default=0.0)
    summary = "; ".join(f"branch {i + 1}: {b.describe()}" for i, b in enumerate(branches))
    numbers = f"{moved} of {counted(len(probes), 'direction')} moved at steps {_steps_text(steps)} (loops re-closed to {worst:.1e} or better)"
    if len(branches) > 1:
        return "bifurcation", (f"{len(branches)} branches of finite motion meet at this pose (a bifurcation, or change point): {summary}. "
                               f"The {counted(k, 'first-order motion')} of the screw route {'is' if k == 1 else 'are'} the union of their "
                               f"tangents; {numbers}. No single motion has all {counted(k, 'freedom')}: each branch has at most {top.dimension}.")
    if top.dimension == k and top.dof == instant.dof and top.pattern == instant.pattern:
        return "full-cycle", f"Every first-order motion is a finite one: {numbers}; {summary}. The instantaneous answer holds for finite motion."
    if top.dimension == k and top.dof == instant.dof:
        return "full-cycle", (f"Every first-order motion is a finite one ({numbers}; {summary}): the DOF {instant.dof} and the mobility {k} hold "
                              f"for finite motion, but not the pattern: {top.pattern} at nearby poses, {instant.pattern} at this one, which is "
                              "special for the kind of the end effector's freedoms (a pattern singularity), not for their number.")
    if top.dimension == k and top.dof > instant.dof:
        return "full-cycle", (f"Every first-order motion is a finite one ({numbers}; {summary}), and the end effector has more DOF at nearby "
                              f"poses ({top.dof}) than at this one ({instant.dof}): the pose is singular for the end effector, not for the mechanism.")
    text = (f"The finite motion has {top.dimension} of the {counted(k, 'first-order freedom')} and end-effector DOF {top.dof} "
            f"({top.pattern}) instead of {instant.dof} ({instant.pattern}): {numbers}; {summary}.")
    if second is not None and second.directions.shape[1]:
        text += f" Second order: {counted(second.directions.shape[1], 'direction line')} pass{'es' if second.directions.shape[1] == 1 else ''}."
    return "instantaneous-only", text
