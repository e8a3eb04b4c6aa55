"""A parallel mechanism as serial limbs of finite screws, for its Jacobian.

One :class:`Chain` per limb (its one-DOF freedoms as finite-screw joints,
:class:`mobility.core.finite_screws.Limb`), the inverse kinematics, and the
actuated freedoms; :mod:`mobility.jacobians.jacobian` differentiates it.

Examples
--------
>>> import mobility
>>> model = parallel_model(mobility.load("mechanisms/metrom.yaml"))
>>> len(model.chains), model.labels
(5, ('P0', 'P1', 'P2', 'P3', 'P4'))
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterable, Sequence

import numpy as np
from scipy.optimize import least_squares

from ..core.finite_screws import FiniteScrew, Limb, ScrewJoint
from ..core.model import Joint, Mechanism, joint_freedoms, require_mechanism
from ..core.validation import joint_names, require_no_repeats
from ..core.tolerance import DEFAULT_TOLERANCE, SOLVER_STOP, Tolerance, characteristic_scale
from ..core.transforms import cross, skew
from ..errors import AnalysisError, MechanismError, RequestError, counted

__all__ = ["Chain", "ParallelModel", "parallel_model", "joint_values"]


@dataclass(frozen=True)
class Chain:
    """One limb as a serial chain of one-DOF freedoms, from the ground to the platform.

    Attributes
    ----------
    limb : Limb
        The freedoms at the mechanism's pose, global frame. A joint met from its
        ``links[1]`` side has its freedoms reversed, axes too: every chain variable is the joint's own.
    joints : tuple of int
        Index in :attr:`Mechanism.joints` of each freedom's joint.
    freedoms : tuple of int
        Index of each freedom within its joint.
    forward : tuple of bool
        Whether each freedom's joint is met from its ``links[0]`` side.
    """

    limb: Limb
    joints: tuple[int, ...]
    freedoms: tuple[int, ...]
    forward: tuple[bool, ...]


@dataclass(frozen=True)
class ParallelModel:
    """A mechanism as parallel serial chains, with its actuated freedoms.

    Attributes
    ----------
    mechanism : Mechanism
    chains : tuple of Chain
    actuated : tuple of (int, int)
        ``(chain, position in the chain)`` of each actuated freedom.
    labels : tuple of str
        Name of each actuated freedom (``name.k`` for freedom ``k`` of a multi-DOF joint).
    """

    mechanism: Mechanism
    chains: tuple[Chain, ...]
    actuated: tuple[tuple[int, int], ...]
    labels: tuple[str, ...]

    def home(self) -> tuple[np.ndarray, ...]:
        """Joint values of the mechanism's own pose (all zero)."""
        return tuple(np.zeros(len(c.limb)) for c in self.chains)

    def platform(self, q: Sequence[np.ndarray] | None = None) -> FiniteScrew:
        """The platform's finite screw at ``q`` (from the first chain)."""
        values = self.home() if q is None else q
        return self.chains[0].limb.finite_screw(values[0])

    def closure_error(self, q: Sequence[np.ndarray]) -> float:
        """Largest difference between the chains' platform displacements (entries of ``[R; p / L]``; closed: at most ``Tolerance.closure``)."""
        length = self.length
        mats = [c.limb.transform(v) for c, v in zip(self.chains, q)]
        return max(max(float(np.max(np.abs(m[:3, :3] - mats[0][:3, :3]))), float(np.max(np.abs(m[:3, 3] - mats[0][:3, 3]))) / length) for m in mats)

    @property
    def length(self) -> float:
        """Characteristic length of the mechanism (RMS distance of the joint points from their centroid)."""
        pts = [j.point for c in self.chains for j in c.limb.joints if j.kind != "P"]
        return characteristic_scale(np.array(pts, dtype=float).reshape(-1, 3))[1]

    def assemble(self, displacement: np.ndarray, start: Sequence[np.ndarray] | None = None, *, tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[np.ndarray, ...]:
        """Joint values of every chain putting the platform at ``displacement`` (4x4): inverse kinematics.

        Each chain by :func:`scipy.optimize.least_squares` on ``[R; p / L]`` from
        ``start`` (default: home), to half of ``tol.closure``, so any two chains agree to ``tol.closure``.

        Raises
        ------
        RequestError
            When ``displacement`` is not a 4x4 matrix of finite numbers, or
            ``start`` not one array of joint values per limb.
        AnalysisError
            When a chain cannot reach the displacement.

        Examples
        --------
        >>> import mobility
        >>> model = parallel_model(mobility.load("mechanisms/metrom.yaml"))
        >>> [len(q) for q in model.assemble(np.eye(4))] == [len(c.limb) for c in model.chains]
        True
        >>> model.assemble(np.zeros(6))
        Traceback (most recent call last):
        mobility.errors.RequestError: assemble: displacement must be a 4x4 homogeneous transform of finite numbers, got an array of shape (6,)
        """
        target = _finite_array(displacement, "assemble: displacement", "a 4x4 homogeneous transform of finite numbers")
        if target.shape != (4, 4):
            raise RequestError(f"displacement must be a 4x4 homogeneous transform of finite numbers, got an array of shape {target.shape}", caller="assemble")
        starts = None if start is None else joint_values(start, self.chains, "start")
        length = self.length
        out = []
        for k, chain in enumerate(self.chains):
            limb = chain.limb
            x0 = np.zeros(len(limb)) if starts is None else starts[k]

            def residual(x: np.ndarray, limb: Limb = limb) -> np.ndarray:
                t = limb.transform(x)
                return np.concatenate([(t[:3, :3] - target[:3, :3]).ravel(), (t[:3, 3] - target[:3, 3]) / length])

            def jac(x: np.ndarray, limb: Limb = limb) -> np.ndarray:
                t, tw = limb.transform(x), limb.twists(x)
                return np.array([np.concatenate([(skew(w) @ t[:3, :3]).ravel(), (cross(w, t[:3, 3]) + v) / length]) for w, v in zip(tw[:3].T, tw[3:].T)]).T

            sol = least_squares(residual, x0, jac=jac, method="lm", x_scale="jac", xtol=SOLVER_STOP, ftol=SOLVER_STOP, gtol=SOLVER_STOP)
            if float(np.max(np.abs(sol.fun))) > 0.5 * tol.closure:
                raise AnalysisError(f"limb {k + 1} cannot reach the platform displacement (residual {np.linalg.norm(sol.fun):.2e})")
            out.append(sol.x)
        return tuple(out)

    def mechanism_at(self, q: Sequence[np.ndarray], *, tol: Tolerance = DEFAULT_TOLERANCE) -> Mechanism:
        """The mechanism with its joints moved to pose ``q`` (a new home), global frame.

        Raises
        ------
        AnalysisError
            When the chains do not close at ``q`` (to ``tol.closure``).
        """
        if self.closure_error(q) > tol.closure:
            raise AnalysisError("the limbs do not close at this pose (solve it with ParallelModel.assemble)")
        world = self.mechanism.world_joints
        moved: dict[int, Joint] = {}
        for chain, values in zip(self.chains, q):
            acc = np.eye(4)
            pos = 0
            while pos < len(chain.joints):
                index = chain.joints[pos]
                span = [p for p in range(pos, len(chain.joints)) if chain.joints[p] == index]
                joint = world[index]
                moved[index] = _moved_joint(joint, acc, chain, span, values)
                for p in span:
                    acc = acc @ chain.limb.joints[p].finite_screw(values[p]).transform()
                pos = span[-1] + 1
        joints = tuple(moved.get(i, j) for i, j in enumerate(world))
        return self.mechanism.replace(joints=joints, frames=())


def _finite_array(value: Any, key: str, what: str) -> np.ndarray:
    """``value`` as an array of finite floats, else a :class:`RequestError` saying it must be ``what``."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise RequestError(f"{key} must be {what}, got {type(value).__name__}") from None
    if not np.isfinite(array).all():
        raise RequestError(f"{key} must be {what}, got a value that is not finite")
    return array


def joint_values(q: Any, chains: Sequence[Chain], key: str = "q") -> tuple[np.ndarray, ...]:
    """``q`` as one array of finite joint values per chain, as many as the chain's freedoms; else a :class:`RequestError`.

    Examples
    --------
    >>> import mobility
    >>> chains = parallel_model(mobility.load("mechanisms/metrom.yaml")).chains
    >>> [len(v) for v in joint_values([[0.0] * len(c.limb) for c in chains], chains)] == [len(c.limb) for c in chains]
    True
    >>> joint_values([["a"]] * 5, chains)
    Traceback (most recent call last):
    mobility.errors.RequestError: q: expected one array of joint values per limb, as many as the limb's freedoms (numbers), got list
    """
    expected = "one array of joint values per limb, as many as the limb's freedoms"
    if isinstance(q, (str, bytes)) or not isinstance(q, Iterable):
        raise RequestError(argument=key, expected=expected, got=type(q).__name__)
    values = []
    for v in q:
        try:
            array = np.asarray(v, dtype=float)
        except (TypeError, ValueError, OverflowError):
            raise RequestError(argument=key, expected=f"{expected} (numbers)", got=type(v).__name__) from None
        if array.ndim != 1 or not np.isfinite(array).all():
            raise RequestError(argument=key, expected=f"{expected} (finite numbers in a flat list)")
        values.append(array)
    if len(values) != len(chains) or any(len(v) != len(c.limb) for v, c in zip(values, chains)):
        raise RequestError(argument=key, expected=expected)
    return tuple(values)


def _moved_joint(joint: Joint, acc: np.ndarray, chain: Chain, span: Sequence[int], values: np.ndarray) -> Joint:
    """A joint carried by the displacement ``acc`` of the link it is mounted on (U: second axis by the first too)."""
    rot, pos = acc[:3, :3], acc[:3, 3]
    fields: dict[str, Any] = {}
    if joint.axis is not None:
        fields["axis"] = tuple(rot @ joint.axis)
    if joint.point is not None:
        fields["point"] = tuple(rot @ joint.point + pos)
    if joint.normal is not None:
        fields["normal"] = tuple(rot @ joint.normal)
    if joint.axes is not None:
        first = chain.limb.joints[span[0]].finite_screw(values[span[0]]).transform()[:3, :3]
        a1, a2 = (np.asarray(a) for a in joint.axes)
        if chain.forward[span[0]]:
            fields["axes"] = (tuple(rot @ a1), tuple(rot @ first @ a2))
        else:
            fields["axes"] = (tuple(rot @ first @ a1), tuple(rot @ a2))
    return Joint(joint.name, joint.type, joint.links, frame="world", actuated=joint.actuated, pitch=joint.pitch, **fields)


def parallel_model(mechanism: Mechanism, actuated: Sequence[str] | None = None) -> ParallelModel:
    """Split a mechanism into serial chains from the ground to the end effector.

    Parameters
    ----------
    mechanism : Mechanism
        Every link but the ground and the end effector has exactly two joints.
    actuated : sequence of str, optional
        Names of the actuated joints (``name.k``: freedom ``k`` of a multi-DOF
        joint); default: those marked ``actuated``.

    Raises
    ------
    MechanismError
        Not a set of serial limbs, or an actuated name unknown, missing or repeated.
    RequestError
        When ``mechanism`` is not a :class:`~mobility.core.model.Mechanism`.
    """
    mechanism = require_mechanism(mechanism, "parallel_model")
    world = mechanism.world_joints
    incident: dict[str, list[int]] = {}
    for i, j in enumerate(world):
        for link in j.links:
            incident.setdefault(link, []).append(i)
    for link, js in incident.items():
        if link not in (mechanism.ground, mechanism.end_effector) and len(js) != 2:
            listed = ", ".join(world[i].name for i in js)
            raise MechanismError("joints", f"link {link!r} has {counted(len(js), 'joint')} ({listed}); the Jacobian needs limbs that are serial chains from {mechanism.ground!r} to {mechanism.end_effector!r}")
    chains = []
    for first in incident[mechanism.ground]:
        link, index = mechanism.ground, first
        screw_joints: list[ScrewJoint] = []
        jidx: list[int] = []
        fidx: list[int] = []
        fwd: list[bool] = []
        while True:  # every other link has two joints (checked above): the walk cannot come back to one
            joint = world[index]
            forward = joint.links[0] == link
            freedoms = list(enumerate(joint.freedoms()))
            if not forward:
                freedoms.reverse()
            for k, f in freedoms:
                axis = np.asarray(f.axis) if forward else -np.asarray(f.axis)
                screw_joints.append(ScrewJoint(f.kind, tuple(axis), f.point, f.pitch, f"{joint.name}.{k}" if joint.dof > 1 else joint.name))
                jidx.append(index)
                fidx.append(k)
                fwd.append(forward)
            link = joint.links[1] if forward else joint.links[0]
            if link == mechanism.end_effector:
                break
            if link == mechanism.ground:
                raise MechanismError("joints", f"joint {joint.name!r} closes a loop back to the ground without reaching {mechanism.end_effector!r}")
            index = next(i for i in incident[link] if i != index)
        chains.append(Chain(Limb(tuple(screw_joints)), tuple(jidx), tuple(fidx), tuple(fwd)))
    if not chains:
        raise MechanismError("joints", f"no joint on the ground {mechanism.ground!r}")
    names = [j.name for j in mechanism.joints if j.actuated] if actuated is None else joint_names(actuated, "actuated")
    if not names:
        raise MechanismError("joints", "no actuated joint: mark joints with 'actuated: true' or name them (--actuated A,B,...)")
    act: list[tuple[int, int]] = []
    labels: list[str] = []
    require_no_repeats(names, "actuated")
    for index, k, label in joint_freedoms(mechanism, names):  # NAME.k: freedom k (from 0) of a multi-freedom joint, as every report labels it
        where = [(c, p) for c, chain in enumerate(chains) for p, (ji, fi) in enumerate(zip(chain.joints, chain.freedoms)) if ji == index and fi == k]
        if not where:
            raise MechanismError("actuated", f"joint {mechanism.joints[index].name!r} is on no limb from {mechanism.ground!r} to {mechanism.end_effector!r}")
        act.append(where[0])
        labels.append(label)
    return ParallelModel(mechanism, tuple(chains), tuple(act), tuple(labels))
