"""Actuation wrenches of the joints of a rigid mechanism at one pose.

Limbs and actuation wrenches as docs/actuation.md, "Definitions", defines them;
the wrench of a freedom and its rate come from :mod:`mobility.actuation.input_wrenches`.

Examples
--------
>>> from mobility.core.model import Joint, Mechanism
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
>>> arm = Mechanism("RR arm", "g", "hand", (R("A", "g", "upper", (0, 0, 0)), R("B", "upper", "hand", (1, 0, 0))))
>>> pose = RigidPose(arm)
>>> len(pose.limbs), pose.spaces.dof
(1, 2)
>>> a = pose.input_wrench(0, 0, "A")   # driving A: a force through B, normal to the arm
>>> f, m = pose.spaces.normalisation.to_world(a.wrench)[:, 0].reshape(2, 3)
>>> [round(float(x), 6) + 0.0 for x in f / f[1]], [round(float(x), 6) + 0.0 for x in m / f[1]], a.note
([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], '')
"""

from __future__ import annotations

from functools import cached_property
from typing import Sequence

import numpy as np

from ..core.joint_screws import JointScrews, joint_screws
from ..core.model import Mechanism
from ..core.screw_systems import Systems, evaluate
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance
from ..core.topology import Node, Parallel, Topology, decompose, joints_of
from .assessment import EndEffectorSpaces, InputWrench
from .input_wrenches import input_wrenches

__all__ = ["RigidPose"]

_NOT_ON_A_PATH = "not on a path between the ground and the end effector"
_DRIVEN_BY_OTHERS = "its motion is produced by the other joints of its limb: it cannot be driven on its own"


class RigidPose:
    """What one pose of a rigid mechanism needs for actuation assessments, computed once.

    Attributes
    ----------
    topology : Topology
    screws : JointScrews
    root : Systems
        The end effector's twist system (normalised; a stack of this one pose).
    limbs : list of (Node, Systems)
        Each limb and its twist system.
    limb_of : dict of int to int
        The limb of each joint on a path between ground and end effector.
    """

    def __init__(self, mechanism: Mechanism, tol: Tolerance = DEFAULT_TOLERANCE) -> None:
        self.mechanism = mechanism
        self.tol = tol
        self.topology: Topology = decompose(mechanism)
        self.screws: JointScrews = joint_screws(mechanism)
        self.root: Systems = _evaluate(self.topology.root, self.screws.twists, self.screws.offsets, tol)
        root = self.topology.root
        if isinstance(root, Parallel):
            self.limbs: list[tuple[Node, Systems]] = list(zip(root.children, self.root.children))
        else:
            self.limbs = [(root, self.root)]
        self.limb_of: dict[int, int] = {j: k for k, (node, _) in enumerate(self.limbs) for j in joints_of(node)}
        self._attachments: dict[int, np.ndarray] = {}
        self._wrenches: dict[tuple[int, int], tuple[np.ndarray | None, float, str, float]] = {}

    @cached_property
    def spaces(self) -> EndEffectorSpaces:
        """The end effector's twist and constraint systems."""
        return EndEffectorSpaces(self.root.basis[0], self.root.wrenches[0], self.screws.normalisation, self.screws.reference)

    def attachment(self, limb: int) -> np.ndarray:
        """Normalised centroid of the points of the limb's joints on the end effector."""
        if limb not in self._attachments:
            node = self.limbs[limb][0]
            ee = self.mechanism.end_effector
            world = self.mechanism.world_joints
            pts = [point for j in joints_of(node) if ee in world[j].links and (point := world[j].point) is not None]
            norm = self.screws.normalisation
            self._attachments[limb] = norm.point_from_world(np.mean(pts, axis=0)) if pts else self.screws.reference
        return self._attachments[limb]

    def wrench(self, joint: int, freedom: int) -> tuple[np.ndarray | None, float, str]:
        """Unit actuation wrench (normalised) of one freedom of a joint, its rate ``a o $``, and a note."""
        wrench, rate, note, _ = self._wrench(joint, freedom)
        return wrench, rate, note

    def transmission(self, joint: int, freedom: int) -> float:
        """``|a o $| / (|a| |$|)`` of one freedom of a joint, in ``[0, 1]``: 0 where its twist puts no power through its actuation wrench (or it has none)."""
        return self._wrench(joint, freedom)[3]

    def _wrench(self, joint: int, freedom: int) -> tuple[np.ndarray | None, float, str, float]:
        key = (joint, freedom)
        if key not in self._wrenches:
            self._wrenches[key] = self._actuation_wrench(joint, freedom)
        return self._wrenches[key]

    def input_wrench(self, joint: int, freedom: int, label: str) -> InputWrench:
        """The :class:`InputWrench` of one freedom of a joint, named ``label``."""
        wrench, rate, note, transmission = self._wrench(joint, freedom)
        return InputWrench(label, self.mechanism.joints[joint].type, self.limb_of.get(joint), wrench, rate, note, transmission)

    def locked_wrenches(self, freedoms: Sequence[tuple[int, int]]) -> np.ndarray | None:
        """The constraint wrenches ``(6, k)`` (orthonormal, normalised) of the limbs where an input has no wrench of its own, all inputs locked.

        Such an input (a 7R arm, joints in line) can still hold its limb, locked
        with the others.  ``freedoms``: the inputs' ``(joint, freedom)``; None when
        every input of every limb has its own wrench (or is on no path).
        """
        lacking = {self.limb_of[j] for j, k in freedoms if j in self.limb_of and self.wrench(j, k)[2] == _DRIVEN_BY_OTHERS}
        if not lacking:
            return None
        held = []
        for limb in sorted(lacking):
            columns = [self.screws.offsets[j] + k for j, k in freedoms if self.limb_of.get(j) == limb]
            locked = self.screws.twists.copy()
            locked[:, columns] = 0.0  # those freedoms locked
            held.append(_evaluate(self.limbs[limb][0], locked, self.screws.offsets, self.tol).wrenches[0])
        return np.concatenate(held, axis=1)

    def _actuation_wrench(self, joint: int, freedom: int) -> tuple[np.ndarray | None, float, str, float]:
        if joint not in self.limb_of:
            return None, 1.0, _NOT_ON_A_PATH, 0.0
        limb = self.limb_of[joint]
        node, value = self.limbs[limb]
        col = self.screws.offsets[joint] + freedom
        w = input_wrenches(node, value, self.screws.twists[None], self.screws.offsets, col, self.attachment(limb)[None], self.tol)
        if not w.has[0]:
            return None, 1.0, _DRIVEN_BY_OTHERS, 0.0
        return w.wrench[0], float(w.rate[0]), "", float(w.transmission[0])


def _evaluate(node: Node, twists: np.ndarray, offsets: tuple[int, ...], tol: Tolerance) -> Systems:
    """The screw systems of ``node`` at this one pose (a stack of one)."""
    return evaluate(node, twists[None], offsets, tol)

