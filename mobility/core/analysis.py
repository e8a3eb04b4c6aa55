"""The analysis: mechanism in, :class:`~mobility.core.result.Result` out.

Model -> topology (cached per graph) -> joint twists in normalised
coordinates (cached per mechanism) -> screw systems of the tree -> canonical
forms -> result in the global frame (example: :func:`analyze`).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import AnalysisError

from .canonical import canonical_form
from .joint_screws import JointScrews, Normalisation, joint_screws, per_object_cache
from .model import WORLD, Mechanism, require_mechanism
from .result import LimbSystem, Margin, NodeSystem, Result, ScrewAxis, pattern_of
from .screw_systems import PoseAnswers, analyse_poses, at_pose, subtree_values
from .screws import free_vector_subspace, span_and_reciprocal
from .tolerance import NEAR_LARGEST_FLOAT, Tolerance, decide_rank, file_tolerance, require_tolerance
from .transforms import cross
from .topology import JointNode, Node, Parallel, Topology, decompose, describe, joints_of

__all__ = ["analyze", "gruebler_kutzbach", "screw_system_in_frame"]


def gruebler_kutzbach(mechanism: Mechanism) -> int:
    """The Grübler–Kutzbach count ``6 (n - 1 - j) + sum f`` of the whole mechanism, less one per coupling of joints.

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> gruebler_kutzbach(Mechanism("slide", "g", "s", (Joint("p", "P", ("g", "s"), axis=(1, 0, 0)),)))
    1
    """
    return _gruebler_kutzbach(require_mechanism(mechanism, "gruebler_kutzbach"))


def _gruebler_kutzbach(mechanism: Mechanism) -> int:
    return 6 * (len(mechanism.links) - 1 - len(mechanism.joints)) + mechanism.freedom_count - len(mechanism.couplings)


def analyze(mechanism: Mechanism, *, tol: Tolerance | None = None) -> Result:
    """Analyse the mobility of ``mechanism`` at its pose.

    Parameters
    ----------
    mechanism : Mechanism
        From :func:`mobility.load` or built in code.
    tol : Tolerance, optional
        Used as given; by default never finer than the file's precision
        (:func:`~mobility.core.tolerance.file_tolerance`).

    Returns
    -------
    Result
        Frozen; screws in the global frame and the mechanism's length unit
        (directions, limb systems and common constraints computed on first access).

    Examples
    --------
    The planar four-bar: one rotation of the coupler, though Grübler–Kutzbach
    (spatial) counts -2:

    >>> import mobility
    >>> r = analyze(mobility.load("mechanisms/four_bar.yaml"))
    >>> r.dof, r.pattern, r.mobility, r.gruebler_kutzbach, r.redundant_constraints
    (1, '1R', 1, -2, 3)
    """
    mechanism = require_mechanism(mechanism, "analyze")
    tol = file_tolerance(mechanism.precision) if tol is None else require_tolerance(tol, "analyze")
    topology = per_object_cache(mechanism, "topology", lambda: decompose(mechanism))
    screws = joint_screws(mechanism)
    answers = analyse_poses(topology, screws.twists[None], screws.offsets, tol)
    gk = _gruebler_kutzbach(mechanism)
    kept, dropped = answers.smallest_kept.item(), answers.largest_dropped.item()
    dof, rotations = at_pose(answers.root.dim), int(answers.rotations[0])
    mobility = at_pose(answers.root.mobility) + sum(at_pose(v.mobility) for v in answers.detached)
    margin = Margin(kept, dropped, kept < tol.near_singular, dropped > tol.inexact)
    warnings = []
    if margin.near_singular:
        warnings.append(
            f"near-singular pose: a direction counted as independent (a freedom, or a constraint of a rigid part) has relative singular value {margin.smallest_kept:.2e} "
            f"(below {tol.near_singular:.0e}); a small change of pose may change the count"
        )
    if margin.inexact:
        cause = "check that the special geometry is exact"
        if margin.near_singular:  # the screw systems are reciprocals of ill-conditioned ones: round-off grows by about 1/margin
            cause += f", or, this pose being near-singular, it may be round-off amplified about {1.0 / margin.smallest_kept:.0e} times"
        warnings.append(
            f"inexact geometry: a direction counted as blocked has relative singular value {margin.largest_dropped:.2e} "
            f"(above round-off, below the rank threshold {tol.rank:.0e}); {cause}"
        )
    norm = screws.normalisation
    result = Result(
        name=mechanism.name, dof=dof, pattern=pattern_of(dof - rotations, rotations), mobility=mobility, gruebler_kutzbach=gk,
        redundant_constraints=mobility - gk, idle_dof=mobility - dof, loops=topology.loop_count, links=topology.link_count,
        joints=len(mechanism.joints), joint_freedoms=mechanism.freedom_count, structure=topology.structure, margin=margin,
        warnings=tuple(warnings), length_unit=mechanism.length_unit, length_scale=norm.size, reference_point=screws.reference_in_world,
        detail=_Detail(mechanism, topology, screws, answers, tol))
    if norm.reach > NEAR_LARGEST_FLOAT:
        result.to_dict()  # its axes may lie past the largest float: said here, not when a lazy part is first read
    return result


class _Detail:
    """The lazily computed parts of a result: canonical forms, limbs, common constraints, the tree's systems.

    It keeps the screw systems the analysis found, so nothing is evaluated twice.
    """

    def __init__(self, mechanism: Mechanism, topology: Topology, screws: JointScrews, answers: PoseAnswers, tol: Tolerance) -> None:
        self.mechanism = mechanism
        self.topology = topology
        self.screws = screws
        self.answers = answers
        self.tol = tol

    def node_systems(self) -> dict[Node, NodeSystem]:
        """DOF and idle count of every node of the tree, read from the values the analysis computed."""
        out: dict[Node, NodeSystem] = {}
        for top, value in zip((self.topology.root, *self.topology.detached), (self.answers.root, *self.answers.detached)):
            for node, v in subtree_values(top, value):
                if v is None:  # a joint inside a series or a bridge: its twists are independent
                    assert isinstance(node, JointNode)
                    out[node] = NodeSystem(self.mechanism.joints[node.index].dof, 0)
                else:
                    out[node] = NodeSystem(at_pose(v.dim), at_pose(v.idle))
        return out

    def twist_form(self) -> tuple[np.ndarray, tuple[ScrewAxis, ...], np.ndarray]:
        return screw_system_in_frame(self.answers.root.basis[0], self.screws.normalisation, self.screws.reference, ("rotation", "helical"), self.tol)

    def wrench_form(self) -> tuple[np.ndarray, tuple[ScrewAxis, ...], np.ndarray]:
        return screw_system_in_frame(self.answers.root.wrenches[0], self.screws.normalisation, self.screws.reference, ("force", "wrench"), self.tol)

    def common_constraints(self) -> int:
        return 6 - span_and_reciprocal(self.screws.twists, self.tol).dim

    def common_motion(self) -> str:
        """What three wrenches common to every joint say of the joints: ``"translation"``, ``"planar"``, ``"spherical"`` or ``""``.

        Three couples: translation; a force along ``n`` and the couples normal
        to it: planar; three forces through one point: spherical.  Decided on
        the orthonormal common wrenches by the rank policy.
        """
        common = span_and_reciprocal(self.screws.twists, self.tol).reciprocal
        if common.shape[1] != 3:
            return ""
        forces, moments = common[:3], common[3:]
        s = np.linalg.svd(forces, compute_uv=False)
        rank = decide_rank(np.concatenate([[1.0], s]), self.tol).rank - 1  # the basis is orthonormal: an absolute threshold
        if rank == 0:
            return "translation"
        if rank == 1:
            u = np.linalg.svd(forces)[0][:, 0]  # the force's direction
            couples = free_vector_subspace(common, self.tol)[0]  # (3, 2): the couples' axes
            return "planar" if couples.shape[1] == 2 and decide_rank(np.array([1.0, float(np.linalg.norm(couples.T @ u))]), self.tol).rank == 1 else ""
        if rank == 3:
            skew = moments @ np.linalg.inv(forces)  # p x . when every wrench is a force through p
            return "spherical" if decide_rank(np.array([1.0, float(np.linalg.norm(skew + skew.T))]), self.tol).rank == 1 else ""
        return ""

    def limbs(self) -> tuple[LimbSystem, ...]:
        """Each branch of a top-level parallel connection, in its own frame.

        A frame's normalised coordinates differ from the global ones by ``diag(R.T, R.T)`` only.
        """
        if not isinstance(self.topology.root, Parallel):
            return ()
        norm, tol = self.screws.normalisation, self.tol
        out = []
        for node, value in zip(self.topology.root.children, self.answers.root.children):  # a parallel node keeps every child's value
            frames = {self.mechanism.joints[i].frame for i in joints_of(node)}
            frame = frames.pop() if len(frames) == 1 else WORLD
            tf = self.mechanism.frame_transform(frame)
            rt = tf.rotation.T
            local = Normalisation(rt @ (norm.centre - tf.translation), norm.length)
            rot6 = np.kron(np.eye(2), rt)
            reference = rt @ self.screws.reference
            translations, rotations, twists = screw_system_in_frame(rot6 @ value.basis[0], local, reference, ("rotation", "helical"), tol)
            couples, forces, wrenches = screw_system_in_frame(rot6 @ value.wrenches[0], local, reference, ("force", "wrench"), tol)
            out.append(LimbSystem(describe(node), frame, at_pose(value.dim), at_pose(value.idle), translations, rotations, twists, couples, forces, wrenches))
        return tuple(out)


def screw_system_in_frame(basis: np.ndarray, norm: Normalisation, reference: np.ndarray, kinds: tuple[str, str], tol: Tolerance) -> tuple[np.ndarray, tuple[ScrewAxis, ...], np.ndarray]:
    """Canonical form of a normalised screw system, written in the coordinates of ``norm``.

    ``basis`` (6, d) is orthonormal and ``reference`` in normalised
    coordinates; ``norm`` maps them to the frame and unit wanted; ``kinds``
    names a screw without and with pitch (``("rotation", "helical")``).
    Returns the free vectors (k, 3), the axes, and the rows (d, 6) of a basis:
    free vectors, then the axes' unit screws.

    Examples
    --------
    >>> from mobility.core.joint_screws import Normalisation
    >>> free, axes, rows = screw_system_in_frame(np.eye(6)[:, 3:], Normalisation(np.zeros(3), 2.0), np.zeros(3), ("rotation", "helical"), Tolerance())
    >>> free.tolist(), axes, rows.shape
    ([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], (), (3, 6))
    """
    form = canonical_form(basis, reference, tol)
    free = form.free.T.copy().reshape(-1, 3)
    with np.errstate(over="ignore", invalid="ignore"):  # checked below: a number too large for a float is refused, never shown
        axes = tuple(
            ScrewAxis(p.axis, norm.point_to_world(p.point), 0.0 if abs(p.pitch) <= tol.rank else p.pitch * norm.length, kinds[abs(p.pitch) > tol.rank])
            for p in form.screws
        )
        rows = [np.concatenate([np.zeros(3), f]) for f in free]
        rows += [np.concatenate([a.axis, cross(a.point, a.axis) + a.pitch * a.axis]) for a in axes]
        basis_rows = np.array(rows, dtype=float).reshape(-1, 6)
    if not np.all(np.isfinite(basis_rows)) or not all(np.all(np.isfinite(a.point)) and math.isfinite(a.pitch) for a in axes):
        raise AnalysisError(
            f"the {kinds[0]} axes lie beyond the largest float in the mechanism's unit (characteristic length {norm.length:.3g}): "
            "write the mechanism in a larger length unit"
        )
    for arr in (free, basis_rows):
        arr.setflags(write=False)
    return free, axes, basis_rows
