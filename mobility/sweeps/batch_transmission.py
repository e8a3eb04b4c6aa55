"""The transmission indices of :mod:`mobility.transmission` at many poses, from the sweep's screw systems.

The analysis and the actuation give every screw the indices need; this module
finds the points where the wrenches act (where each limb leaves its input link
and meets the end effector).  :func:`check_transmission` is the same at one pose.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from ..core.kinematics import kinematics
from ..core.model import Mechanism, require_mechanism
from ..core.screw_systems import PoseAnswers, analyse_poses, per_pose
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, require_tolerance
from ..core.topology import Parallel, decompose, joints_of, spanning_tree
from ..errors import RequestError
from ..transmission import GOOD_TRANSMISSION, BatchTransmission, TransmissionCheck, transmission_indices
from .batch_actuation import ActuationInputs, BatchActuation, actuated_inputs, actuation_at_poses
from .posed_screws import PosedScrews, posed_screws

__all__ = ["transmission_at_poses", "transmission_columns", "check_transmission", "require_threshold", "transmission_threshold", "GOOD_TRANSMISSION"]


def _depths(mechanism: Mechanism) -> dict[str, int]:
    """Each link's distance from the ground in joints (the breadth-first spanning tree lists parents first)."""
    depth = {mechanism.ground: 0}
    for edge in spanning_tree(mechanism)[0]:
        depth[edge.child] = depth[edge.parent] + 1
    return depth


def _mean_point(posed: PosedScrews, names: list[str], fallback: np.ndarray) -> np.ndarray:
    """The mean of the named joints' points in normalised coordinates (``fallback`` when none has one)."""
    if not names:
        return fallback
    return posed.normalised(np.mean([posed.points[n] for n in names], axis=0))


def transmission_at_poses(mechanism: Mechanism, posed: PosedScrews, answers: PoseAnswers, actuation: BatchActuation,
                          inputs: ActuationInputs, tol: Tolerance = DEFAULT_TOLERANCE) -> BatchTransmission:
    """The transmission indices of ``inputs`` at every pose of ``posed``, from the ``answers`` and ``actuation`` of the same poses."""
    count = posed.twists.shape[0]
    root = decompose(mechanism).root
    value = answers.root
    limbs = list(zip(root.children, value.children)) if isinstance(root, Parallel) else [(root, value)]
    world = mechanism.world_joints
    ee = mechanism.end_effector
    depth = _depths(mechanism)
    with_point = [j for j in world if j.point is not None]
    attach = []
    for node, _ in limbs:
        on_ee = [world[j].name for j in joints_of(node) if ee in world[j].links and world[j].point is not None]
        attach.append(_mean_point(posed, on_ee, posed.reference))
    limb_of = {j: k for k, (node, _) in enumerate(limbs) for j in joints_of(node)}
    twists, in_points, out_points = [], [], []
    for joint, freedom in inputs.freedoms:
        col = posed.offsets[joint] + freedom
        twists.append(posed.twists[:, :, col])
        out = attach[limb_of[joint]] if joint in limb_of else posed.reference
        a, b = world[joint].links
        distal = b if depth.get(b, 0) >= depth.get(a, 0) else a
        after = [j.name for j in with_point if distal in j.links and j.name != world[joint].name]
        in_points.append(_mean_point(posed, after, out))
        out_points.append(out)
    n = len(inputs.freedoms)
    wrenches = actuation.wrenches if actuation.wrenches is not None else np.zeros((count, n, 6))
    several = len(limbs) > 1  # one limb: no constraint index
    return transmission_indices(wrenches, np.stack(twists, axis=2) if twists else np.zeros((count, 6, 0)),
                                np.stack(in_points, axis=1) if in_points else np.zeros((count, 0, 3)),
                                np.stack(out_points, axis=1) if out_points else np.zeros((count, 0, 3)),
                                value.basis, per_pose(value.dim, count), [limb.wrenches for _, limb in limbs] if several else [],
                                [per_pose(6 - limb.dim, count) for _, limb in limbs] if several else [],
                                np.stack(attach, axis=1) if several else None, singular=actuation.rank < 6, tol=tol)


def check_transmission(mechanism: Mechanism, actuated: Sequence[str] | None = None, *, q: np.ndarray | None = None,
                       threshold: float = GOOD_TRANSMISSION, tol: Tolerance = DEFAULT_TOLERANCE) -> TransmissionCheck:
    """The transmission indices of a mechanism at one pose (see :mod:`mobility.transmission`).

    Parameters
    ----------
    actuated : sequence of str, optional
        The actuated joints (default: those the file marks ``actuated: true``).
    q : array_like, optional
        Joint variables of the pose, as a row of ``SweepResult.q``
        (closing every loop; default: the file's pose).
    threshold : float
        The good-transmission threshold (``LTI >= threshold``), 0.7 as published.

    Raises
    ------
    RequestError
        No input chosen, a threshold outside [0, 1], or ``q`` not a closed
        pose (the wrong count, a number not finite, a loop left open).
    MechanismError
        An actuated name that is not a joint.

    Examples
    --------
    >>> import mobility
    >>> t = check_transmission(mobility.load("mechanisms/3prs.yaml"))
    >>> t.actuated, [round(x, 3) for x in t.iti]
    (('P1', 'P2', 'P3'), [0.943, 0.943, 0.943])
    """
    mechanism = require_mechanism(mechanism, "check_transmission")
    tol = require_tolerance(tol, "check_transmission")
    threshold = require_threshold(threshold, "check_transmission")
    inputs = actuated_inputs(mechanism, actuated)
    if not inputs.freedoms:
        raise RequestError("check_transmission: no input chosen; mark joints `actuated: true` in the file or name them (actuated=[...])")
    bk = kinematics(mechanism)
    stack = np.zeros((1, bk.variable_count)) if q is None else _closed_pose(mechanism, q, bk.variable_count)
    posed = posed_screws(bk, stack)
    answers = analyse_poses(decompose(mechanism), posed.twists, posed.offsets, tol)
    act = actuation_at_poses(mechanism, posed, answers, inputs, tol)
    t = transmission_at_poses(mechanism, posed, answers, act, inputs, tol)
    root = decompose(mechanism).root
    limbs = root.children if isinstance(root, Parallel) else []
    names = [j.name for j in mechanism.world_joints]
    labels = tuple("-".join(names[j] for j in joints_of(node)) for node in limbs) if len(limbs) > 1 else ()
    freedoms = [names[j] if sum(1 for jj, _ in inputs.freedoms if jj == j) == 1 else f"{names[j]}.{k}" for j, k in inputs.freedoms]
    return TransmissionCheck(actuated=tuple(freedoms), iti=tuple(float(x) for x in t.iti[0]), oti=tuple(float(x) for x in t.oti[0]),
                             lti=float(t.lti[0]), limbs=labels, cti_limbs=tuple(float(x) for x in t.cti_limbs[0]) if labels else (),
                             cti=float(t.cti[0]), threshold=threshold)


CLOSED = 1e-6
"""The largest loop-closure residual (dimensionless) of joint variables given to :func:`check_transmission`."""


def _closed_pose(mechanism: Mechanism, q: object, count: int) -> np.ndarray:
    """``q`` as one row of joint variables that close every loop, else a :class:`RequestError`."""
    try:
        row = np.asarray(q, dtype=float).reshape(1, -1)
    except (TypeError, ValueError):
        raise RequestError(f"check_transmission: q: expected {count} joint variables (numbers), got {type(q).__name__}") from None
    if row.shape[1] != count:
        raise RequestError(f"check_transmission: q: expected {count} joint variables, got {row.shape[1]}")
    if not np.all(np.isfinite(row)):
        raise RequestError("check_transmission: q: expected finite joint variables, got NaN or infinity")
    residual = kinematics(mechanism).residual(row[0])
    worst = float(np.max(np.abs(residual))) if residual.size else 0.0
    if worst > CLOSED:
        raise RequestError(f"check_transmission: q: the joint variables do not close the loops (residual {worst:.1e}); "
                           "give a closed pose, such as a row of SweepResult.q")
    return row


def transmission_threshold(transmission: object, good_threshold: object, inputs: bool) -> float | None:
    """The sweep's request checked: its good-transmission threshold when it computes the indices (inputs chosen), else None.

    Raises
    ------
    RequestError
        ``transmission`` not a bool, or ``good_threshold`` not a number in [0, 1].
    """
    if not isinstance(transmission, (bool, np.bool_)):
        raise RequestError(f"sweep: transmission must be True or False, got {transmission!r}")
    threshold = require_threshold(good_threshold, "sweep: good_threshold")
    return threshold if transmission and inputs else None


def require_threshold(value: object, what: str) -> float:
    """``value`` as a good-transmission threshold in [0, 1], else a :class:`RequestError`."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) or not 0.0 <= float(value) <= 1.0:
        raise RequestError(f"{what}: threshold must be a number in [0, 1], got {value!r}")
    return float(value)


def transmission_columns(mechanism: Mechanism, posed: PosedScrews, answers: PoseAnswers, actuation: BatchActuation,
                         inputs: ActuationInputs, tol: Tolerance = DEFAULT_TOLERANCE) -> dict[str, np.ndarray]:
    """The sweep's transmission columns ``iti``, ``oti`` (smallest over the inputs), ``lti``, ``cti`` of these poses."""
    t = transmission_at_poses(mechanism, posed, answers, actuation, inputs, tol)
    return {"iti": t.iti_min, "oti": t.oti_min, "lti": t.lti, "cti": t.cti}
