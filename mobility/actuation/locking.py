"""The second route to an actuation verdict: lock the inputs, count what is left.

Locking the inputs leaves the end effector with 0 DOF by loop closure exactly
when the actuation and constraint wrenches span six dimensions. It shares
nothing with :mod:`mobility.actuation.assessment` but the model: a check.

Examples
--------
>>> import mobility
>>> m = mobility.load("mechanisms/four_bar.yaml")   # the crank A, the coupler B-C, the rocker D
>>> locked_dof(m, ["A"]), locked_dof(m, [])
(0, 1)
>>> [(j.name, j.links) for j in lock_joints(m, ["B", "C"]).joints]
[('A', ('ground', 'coupler')), ('D', ('coupler', 'ground'))]
"""

from __future__ import annotations

from dataclasses import replace
from typing import Iterable

from ..core.loop_closure import loop_closure
from ..core.model import Coupling, Mechanism, require_mechanism
from ..core.validation import joint_names, require_no_repeats
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, require_tolerance
from ..errors import MechanismError

__all__ = ["lock_joints", "locked_dof"]


def lock_joints(mechanism: Mechanism, names: Iterable[str]) -> Mechanism | None:
    """The mechanism with the named joints made rigid: each removed, its two links merged.

    ``names``: joint names, each once (``["A"]``, not ``"A"``). Joints left
    joining a link to itself are removed too; a coupling left with a single
    joint holds it still (it is locked as well). A merged body keeps the name
    of the ground or the end effector when it holds one.

    Returns
    -------
    Mechanism or None
        ``None`` when the end effector is merged with the ground (it cannot move).

    Raises
    ------
    MechanismError
        When ``names`` is a string, repeats a joint, or names no joint.
    RequestError
        When ``mechanism`` is not a :class:`~mobility.core.model.Mechanism`.
    """
    mechanism = require_mechanism(mechanism, "lock_joints")
    listed = joint_names(names, "actuated")  # a sequence of names (not one string), each given once
    require_no_repeats(listed, "actuated")
    names = set(listed)
    unknown = sorted(names - {j.name for j in mechanism.joints})
    if unknown:
        raise MechanismError("actuated", f"unknown joint {unknown[0]!r}")
    while True:  # a coupling left with one joint holds it still too: lock it and start again
        locked, held = _locked(mechanism, names)
        if not held:
            return locked
        names = names | held


def _locked(mechanism: Mechanism, names: set[str]) -> tuple[Mechanism | None, set[str]]:
    """:func:`lock_joints` once, and the joints that a coupling left with them alone holds still (to lock as well)."""
    parent: dict[str, str] = {}

    def find(x: str) -> str:
        while parent.get(x, x) != x:
            x = parent[x]
        return x

    keep = (mechanism.ground, mechanism.end_effector)
    for j in mechanism.joints:
        if j.name in names:
            a, b = find(j.links[0]), find(j.links[1])
            if a != b:
                if b in keep and a not in keep:
                    a, b = b, a
                if a == mechanism.end_effector and b == mechanism.ground:
                    a, b = b, a
                parent[b] = a
    if find(mechanism.end_effector) == find(mechanism.ground):
        return None, set()
    joints = []
    for j in mechanism.joints:
        if j.name in names:
            continue
        links = (find(j.links[0]), find(j.links[1]))
        if links[0] != links[1]:
            joints.append(j if links == j.links else replace(j, links=links))
    kept = {j.name for j in joints}
    terms = [[(n, x) for n, x in c.terms if n in kept] for c in mechanism.couplings]
    held = {t[0][0] for t in terms if len(t) == 1}
    if held:
        return None, held
    couplings = tuple(Coupling(tuple(n for n, _ in t), tuple(x for _, x in t)) for t in terms if t)
    return mechanism.replace(joints=tuple(joints), expected=None, couplings=couplings), set()


def locked_dof(mechanism: Mechanism, names: Iterable[str], *, tol: Tolerance = DEFAULT_TOLERANCE) -> int:
    """DOF of the end effector with the named joints locked, by loop closure (an independent route).

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> m = Mechanism("RR arm", "g", "hand", (Joint("A", "R", ("g", "arm"), axis=(0, 0, 1), point=(0, 0, 0)),
    ...                                      Joint("B", "R", ("arm", "hand"), axis=(0, 0, 1), point=(1, 0, 0))))
    >>> locked_dof(m, []), locked_dof(m, ["A"]), locked_dof(m, ["A", "B"])
    (2, 1, 0)
    >>> locked_dof(m, "AB")
    Traceback (most recent call last):
    mobility.errors.MechanismError: actuated: expected a sequence of joint names, got the string 'AB' (write ['AB'])
    """
    mechanism = require_mechanism(mechanism, "locked_dof")
    tol = require_tolerance(tol, "locked_dof")
    locked = lock_joints(mechanism, names)
    if locked is None:
        return 0
    return int(loop_closure(locked, tol).end_effector_twists.shape[1])

