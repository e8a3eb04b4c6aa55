"""The inputs of a compiled MuJoCo model's actuators: one actuator, one input.

An actuator with a joint transmission drives a hinge's or slide's rate
(several on one joint: one input, a note), or a ball joint's rotation about
``xmat @ gear[:3]`` in the global frame (``jointinparent`` is the same at
``qpos0``): a :class:`~mobility.io.robot_actuators.BallActuator`; one whose
axis earlier ones span adds no input (a note), one of axis ``0 0 0`` is
unsupported, as is one on a free joint (a six-number gear).  Actuators on
tendons, sites or bodies drive no joint (a note).
"""

from __future__ import annotations

from typing import Any, Protocol

import numpy as np

from ..core.expected import independent_of
from ..core.validation import require_vector
from ..errors import MechanismError, MechanismFileError, clipped
from .robot_actuators import BallActuator
from .robot_tree import Unsupported, at_line

__all__ = ["actuator_inputs"]


class CompiledModel(Protocol):
    """What is read of a compiled model: MuJoCo, the model and its data at ``qpos0``, names and lines."""

    mj: Any
    m: Any
    d: Any
    file: str
    lines: dict[str, dict[int, int | None]]

    def name(self, kind: str, index: int) -> str: ...

    def joint_name(self, i: int) -> str: ...

    def finite(self, values: Any, key: str, line: int | None) -> tuple[float, float, float]: ...


def actuator_inputs(model: CompiledModel, notes: list[str], unsupported: list[Unsupported]) -> tuple[set[int], dict[int, tuple[BallActuator, ...]]]:
    """The hinges and slides actuators drive, and the inputs of each driven ball joint (see the module docstring)."""
    m, trn, types = model.m, model.mj.mjtTrn, model.mj.mjtJoint
    out: set[int] = set()
    drivers: dict[int, list[str]] = {}
    balls: dict[int, list[BallActuator]] = {}
    for a in range(m.nu):
        kind = int(m.actuator_trntype[a])
        aname = model.name("mjOBJ_ACTUATOR", a) or f"actuator{a}"
        line = model.lines["actuator"].get(a)
        if kind not in (int(trn.mjTRN_JOINT), int(trn.mjTRN_JOINTINPARENT)):
            what = {int(trn.mjTRN_TENDON): "a tendon", int(trn.mjTRN_SITE): "a site", int(trn.mjTRN_BODY): "a body",
                    int(trn.mjTRN_SLIDERCRANK): "a slider-crank"}.get(kind, "no joint")
            notes.append(f"actuator {clipped(aname)}{at_line(line)} drives {what}, not a joint: no joint is marked actuated for it")
            continue
        joint = int(m.actuator_trnid[a][0])
        jtype, jname, key = int(m.jnt_type[joint]), model.joint_name(joint), f"actuator[{clipped(aname)}]"
        if jtype == int(types.mjJNT_FREE):
            unsupported.append(Unsupported(key, f"an actuator on the free joint {clipped(jname)} is not supported: it is one input along its "
                                           "six-number gear (a force and a torque together), which no joint of the model expresses as one input "
                                           "(an actuated free joint would be six inputs); expected actuators on hinge, slide or ball joints", line))
        elif jtype == int(types.mjJNT_BALL):
            ball = _ball_actuator(model, a, aname, joint, kind == int(trn.mjTRN_JOINTINPARENT), line)
            if ball is None:
                unsupported.append(Unsupported(key, f"its gear on the ball joint {clipped(jname)} has 0 0 0 as its first three numbers, the axis it "
                                               "turns about: it drives nothing; expected a non-zero axis", line))
            else:
                balls.setdefault(joint, []).append(ball)
        else:
            out.add(joint)
            drivers.setdefault(joint, []).append(f"{clipped(aname)}{at_line(line)}")
    for joint, names in drivers.items():
        if len(names) > 1:
            notes.append(f"actuators {', '.join(names)} all drive joint {clipped(model.joint_name(joint))}: one input (its one freedom), not {len(names)}")
    return out, {joint: _independent(model.joint_name(joint), inputs, notes) for joint, inputs in balls.items()}


def _ball_actuator(model: CompiledModel, a: int, aname: str, joint: int, in_parent: bool, line: int | None) -> BallActuator | None:
    """The input of actuator ``a`` on a ball joint: its axis in the global frame at ``qpos0`` (``None``: a zero axis)."""
    gear = np.asarray(model.m.actuator_gear[a][:3], dtype=float)
    if not np.any(gear):
        return None
    body = int(model.m.jnt_bodyid[joint])
    with np.errstate(all="ignore"):  # an overflow is refused just below, in one line
        axis = np.asarray(model.d.xmat[body], dtype=float).reshape(3, 3) @ gear
    key = f"actuator[{clipped(aname)}]/@gear"
    try:
        unit = require_vector(model.finite(axis, key, line), key, direction=True)
    except MechanismError as exc:  # numbers too small to keep a direction
        raise MechanismFileError(key, exc.message, file=model.file, line=line) from None
    return BallActuator(aname, unit, in_parent, line)


def _independent(joint: str, inputs: list[BallActuator], notes: list[str]) -> tuple[BallActuator, ...]:
    """The inputs of a ball joint whose axes are independent of those before them; a note for each other one."""
    kept: list[BallActuator] = []
    for ball in inputs:
        if independent_of([k.axis for k in kept], ball.axis):
            kept.append(ball)
            continue
        others = ", ".join(clipped(k.name) for k in kept)
        notes.append(f"actuator {clipped(ball.name)}{at_line(ball.line)} turns the ball joint {clipped(joint)} about an axis "
                     f"that actuator{'s' if len(kept) > 1 else ''} {others} already drive{'' if len(kept) > 1 else 's'}: it adds no input")
    return tuple(kept)

