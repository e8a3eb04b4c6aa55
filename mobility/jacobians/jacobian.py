"""Jacobians of parallel mechanisms by differentiating finite screws (Eq. 26 of Sun et al., 2018).

The method: docs/finite-screws.md, "Jacobian by differentiation".  Any scale
of the file gives the same answer: the Jacobian is computed on the mechanism
scaled exactly by a power of two (:func:`~mobility.core.tolerance.binary_scale`),
then written back in the file's units and the global frame.

Examples
--------
>>> import mobility
>>> m = mobility.loads('''
... name: planar RR arm
... ground: g
... end_effector: hand
... joints:
...   - {name: A, type: R, links: [g, upper], axis: [0, 0, 1], point: [0, 0, 0], actuated: true}
...   - {name: B, type: R, links: [upper, hand], axis: [0, 0, 1], point: [1, 0, 0], actuated: true}
... ''')
>>> jac = jacobian(m)
>>> jac.dof, jac.matrix.shape, jac.singular
(2, (6, 6), False)
>>> (jac.twist_map[:, 1].round(12) + 0.0).tolist()        # unit rate of B: rotation about z through (1, 0, 0)
[0.0, 0.0, 1.0, 0.0, -1.0, 0.0]
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any, Sequence, cast

import numpy as np

from ..core.finite_screws import Limb
from ..core.frozen import ReadOnlyArrays
from ..core.joint_screws import Normalisation
from ..core.model import Mechanism, Vector, require_mechanism
from ..core.screws import SWAP, adjoint, reciprocal_product, reciprocal_system, span_and_reciprocal
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, binary_scale, characteristic_scale, clean_numbers, decide_rank, require_tolerance
from ..errors import AnalysisError, HalfTurnError
from .parallel_model import Chain, ParallelModel, joint_values, parallel_model
from .wrenches import clean_screw, dominant_signs, is_couple, norm, unit_wrench, wrench_axis

__all__ = ["JacobianResult", "jacobian"]


@dataclass(frozen=True, eq=False)
class JacobianResult(ReadOnlyArrays):
    """The Jacobian of a parallel mechanism at one pose (global frame, the mechanism's units; arrays read-only).

    Attributes
    ----------
    name : str
    actuated : tuple of str
        Labels of the actuated freedoms (rows of ``matrix``, in order).
    dof : int
        Platform DOF: 6 minus the rank of the constraint wrenches.
    matrix : ndarray, shape (a + c, 6)
        ``J``: ``J @ $_p = [q'_a; 0]`` for any platform twist ``$_p = [ω; v]``;
        rows are ``(SWAP W)^T`` of the actuation wrenches (scaled to unit
        product with their joint's twist) then of the constraint wrenches.
    actuation_wrenches : ndarray, shape (a, 6)
        Rows ``[f; m]``.
    constraint_wrenches : ndarray, shape (c, 6)
        A basis (rows ``[f; m]``, force parts of unit length) of the platform's constraint system.
    platform_twists : ndarray, shape (dof, 6)
        A basis of the platform's twist system (rows ``[ω; v]``).
    twist_map : ndarray or None, shape (6, a)
        Platform twist per unit actuated rate (first ``a`` columns of ``J^-1``);
        ``None`` when ``J`` is singular or has more rows than 6 (redundant actuation).
    rank : int
        Rank of ``J`` (normalised coordinates), decided on its rows scaled to unit length.
    condition : float
        Condition number of ``J`` in normalised coordinates, rows as they are
        (``inf`` if singular): it depends on the inputs' rate units.
    singular : bool
        ``J`` has rank below 6: the actuated joints do not control the platform
        at this pose. Of rank 6 with more rows, it is regular, with :attr:`redundant` inputs to spare.
    limb_twists : tuple of ndarray
        Per limb, the joint twists ``$_ij`` (6 x n_i), derivatives of its finite screw.
    transform : ndarray, shape (4, 4)
        The platform's displacement from the mechanism's own pose.
    finite_screw : ndarray or None
        Its finite screw ``[w; v]`` (``None`` at a half-turn).
    length : float
        The characteristic length of the pose (RMS distance of the joint points from their centroid).
    """

    name: str
    actuated: tuple[str, ...]
    dof: int
    matrix: np.ndarray
    actuation_wrenches: np.ndarray
    constraint_wrenches: np.ndarray
    platform_twists: np.ndarray
    twist_map: np.ndarray | None
    rank: int
    condition: float
    singular: bool
    limb_twists: tuple[np.ndarray, ...] = field(repr=False)
    transform: np.ndarray = field(repr=False)
    finite_screw: np.ndarray | None = field(repr=False)
    length: float = 1.0

    @property
    def redundant(self) -> int:
        """Inputs beyond those the platform needs (``rows of J - 6`` when ``J`` is regular, else 0)."""
        return 0 if self.singular else self.matrix.shape[0] - 6

    def to_dict(self) -> dict[str, Any]:
        """JSON form: screws with round-off shown as 0 part by part (a moment against a force times the length)."""
        length = self.length

        def screws(rows: np.ndarray | None, moment_first: bool = False) -> Any:
            if rows is None:
                return None
            return [clean_screw(r, length, moment_first) for r in np.asarray(rows, dtype=float).reshape(-1, 6)]

        def axes(rows: np.ndarray) -> list[dict[str, Any]]:
            out = []
            for r in rows:
                kind, d, p, h = wrench_axis(r, length=length)
                out.append({"kind": kind, "axis": clean_numbers(d), "point": clean_numbers(p, max(length, norm(p))), "pitch": h})
            return out

        return {"name": self.name, "actuated": list(self.actuated), "dof": self.dof, "matrix": screws(self.matrix, moment_first=True),
                "actuation_wrenches": screws(self.actuation_wrenches), "actuation_axes": axes(self.actuation_wrenches),
                "constraint_wrenches": screws(self.constraint_wrenches), "constraint_axes": axes(self.constraint_wrenches),
                "platform_twists": screws(self.platform_twists),
                "twist_map": None if self.twist_map is None else np.array(screws(self.twist_map.T)).T.tolist(), "rank": self.rank,
                "condition": self.condition if np.isfinite(self.condition) else None, "singular": self.singular, "redundant": self.redundant,
                "finite_screw": None if self.finite_screw is None else clean_screw(self.finite_screw, length)}


def jacobian(mechanism: Mechanism | ParallelModel, q: Sequence[np.ndarray] | None = None, *, actuated: Sequence[str] | None = None,
             tol: Tolerance = DEFAULT_TOLERANCE) -> JacobianResult:
    """The Jacobian of a parallel mechanism by differentiating its limbs' finite screws.

    Parameters
    ----------
    q : sequence of arrays, optional
        Joint values per limb (an assembled pose, e.g. from
        :meth:`ParallelModel.assemble`); default: the mechanism's own pose.
    actuated : sequence of str, optional
        Actuated joint names (default: those marked ``actuated``); only used
        when ``mechanism`` is a :class:`Mechanism`.

    Raises
    ------
    MechanismError
        Not a set of serial limbs, or no/unknown/repeated actuated joints
        (``actuated`` is a sequence of names: ``["P0"]``, not ``"P0"``).
    RequestError
        ``q`` is not one array of finite joint values per limb.
    AnalysisError
        The limbs do not close at ``q``, or an actuated joint cannot move the platform on its own.

    Examples
    --------
    The METROM-type 5-axis machine, its five sliders driven (five actuation rows and the constraint row):

    >>> import mobility
    >>> j = jacobian(mobility.load("mechanisms/metrom.yaml"))
    >>> j.matrix.shape, j.rank, j.dof, j.singular, j.actuated
    ((6, 6), 6, 5, False, ('P0', 'P1', 'P2', 'P3', 'P4'))
    """
    tol = require_tolerance(tol, "jacobian")
    model = mechanism if isinstance(mechanism, ParallelModel) else parallel_model(require_mechanism(mechanism, "jacobian"), actuated)
    values = model.home() if q is None else joint_values(q, model.chains)
    scale = binary_scale(model.length)  # the same mechanism at a size near 1: every number below is O(1) whatever the file's scale
    unit = _scaled_model(model, scale)
    unit_values = tuple(v * _variable_scales(c, scale) for v, c in zip(values, model.chains))
    if q is not None and unit.closure_error(unit_values) > tol.closure:
        raise AnalysisError("the limbs do not close at this pose (solve it with ParallelModel.assemble)")
    return _in_file_units(_jacobian_near_unit_size(unit, unit_values, tol), model, scale, tol)


def _scaled_model(model: ParallelModel, scale: float) -> ParallelModel:
    """``model`` with every length times ``scale`` (points and pitches; a power of two, so exactly)."""
    chains = []
    for c in model.chains:
        joints = tuple(replace(j, point=cast(Vector, tuple(float(x) * scale for x in j.point)), pitch=j.pitch * scale) for j in c.limb.joints)
        chains.append(Chain(Limb(joints), c.joints, c.freedoms, c.forward))
    return ParallelModel(model.mechanism, tuple(chains), model.actuated, model.labels)


def _variable_scales(chain: Chain, scale: float) -> np.ndarray:
    """Per freedom of a chain, the factor of its variable when lengths are multiplied by ``scale`` (P: ``scale``; angles: 1)."""
    return np.array([scale if j.kind == "P" else 1.0 for j in chain.limb.joints])


def _jacobian_near_unit_size(model: ParallelModel, values: tuple[np.ndarray, ...], tol: Tolerance) -> JacobianResult:
    """:func:`jacobian` of a model whose characteristic length is near 1 (its own units)."""
    moved_points = [j.point for c, v in zip(model.chains, values) for j in c.limb.moved(v).joints if j.kind != "P"]
    centre, length = characteristic_scale(np.array(moved_points, dtype=float).reshape(-1, 3))
    norm = Normalisation(centre, length)
    limb_twists = tuple(c.limb.twists(v) for c, v in zip(model.chains, values))  # Eq. 26: derivatives of S_f
    # Normalised coordinates as in mobility.core.joint_screws: a P joint's unit rate is one characteristic length per unit time.
    limb_n = [norm.from_world(t) * np.array([length if j.kind == "P" else 1.0 for j in c.limb.joints]) for t, c in zip(limb_twists, model.chains)]
    limb_constraints = [reciprocal_system(t, tol) for t in limb_n]
    constraint_span = span_and_reciprocal(np.hstack(limb_constraints), tol)
    # each constraint with its largest normalised component positive: a sign that round-off and scale do not flip
    constraints_n = constraint_span.basis * np.where(dominant_signs(constraint_span.basis) < 0, -1.0, 1.0)
    twists_n = constraint_span.reciprocal  # twists reciprocal to every constraint: the platform's twist system
    rows_n, wrenches_w = [], []
    for label, (c, p) in zip(model.labels, model.actuated):
        t = limb_n[c]
        passive = np.delete(t, p, axis=1)
        recip = reciprocal_system(passive, tol)
        # Orthogonal to the limb's constraints in coordinates centred where the limb meets the platform
        # (for an SPR limb: the force along the leg, not a mix with the constraint force).
        meeting = norm.point_from_world(_meeting_point(model.chains[c], values[c]))
        shift = adjoint(np.eye(3), -meeting)  # screw coordinates about the meeting point: [a; b - meeting x a]
        own = shift @ limb_constraints[c]
        own = np.linalg.qr(own)[0] if own.shape[1] else own
        moved = shift @ recip
        resid = moved - own @ (own.T @ moved) if own.shape[1] else moved
        u, s, _ = np.linalg.svd(resid)
        u = adjoint(np.eye(3), meeting) @ u  # back about the origin
        gain = float(reciprocal_product(u[:, 0], t[:, p])) if s.size and s[0] > tol.rank else 0.0
        if abs(gain) <= tol.rank:
            raise AnalysisError(f"actuated joint {label} cannot move the platform on its own at this pose (its limb's other joints give the same motion)")
        w_n = u[:, 0] / gain
        rows_n.append(SWAP @ w_n)
        w_world = norm.to_world(w_n)[:, 0]
        w_world = w_world / float(reciprocal_product(w_world, limb_twists[c][:, p]))
        wrenches_w.append(w_world)
    rows_n += [SWAP @ w for w in constraints_n.T]
    j_n = np.array(rows_n).reshape(-1, 6)
    sv = np.linalg.svd(j_n, compute_uv=False)
    # Whether the wrenches span is a property of their lines, not of the rate units of the inputs (a screw of
    # large pitch gives a short row): the rank is decided on unit rows, as the actuation check decides it.
    rows = np.linalg.norm(j_n, axis=1)
    rank = decide_rank(np.linalg.svd(j_n / np.where(rows > 0.0, rows, 1.0)[:, None], compute_uv=False), tol).rank
    square = j_n.shape[0] == 6
    singular = rank < 6
    constraints_w = norm.to_world(constraints_n).T
    constraints_w = np.array([unit_wrench(w, tol, length) for w in constraints_w]).reshape(-1, 6)
    act_w = np.array(wrenches_w).reshape(-1, 6)
    matrix = np.vstack([(SWAP @ act_w.T).T, (SWAP @ constraints_w.T).T]) if act_w.size or constraints_w.size else np.zeros((0, 6))
    twist_map = None if singular or not square else np.linalg.solve(matrix, np.eye(6)[:, : len(wrenches_w)])
    twists_w = norm.to_world(twists_n).T
    screw = model.platform(values)
    try:
        fs = screw.vector
    except HalfTurnError:
        fs = None
    condition = float(sv[0] / sv[-1]) if not singular and sv[-1] > 0 else float("inf")
    return JacobianResult(model.mechanism.name, model.labels, 6 - constraints_n.shape[1], matrix, act_w, constraints_w, twists_w.reshape(-1, 6),
                          twist_map, rank, condition, singular, limb_twists, screw.transform(), fs, length)


def _in_file_units(unit: JacobianResult, model: ParallelModel, scale: float, tol: Tolerance) -> JacobianResult:
    """The Jacobian ``unit`` of ``model`` scaled by ``scale``, written in the file's units.

    A twist ``[w; v]`` per unit rate becomes ``[w; v / scale]`` per unit angle,
    ``scale [w; v / scale]`` per unit length; an actuation wrench ``[f; m]``
    becomes ``scale [f; m / scale]`` for an angle input, ``[f; m / scale]`` for
    a length input; a unit-force constraint ``[f; m / scale]``, a couple
    ``[scale f; m]``. The large and small factors never meet.
    """
    twist_factor = np.array([1.0, 1.0, 1.0, 1.0 / scale, 1.0 / scale, 1.0 / scale])
    kinds = [model.chains[c].limb.joints[p].kind for c, p in model.actuated]
    per_rate = np.array([scale if k == "P" else 1.0 for k in kinds])  # scaled rate per file rate

    def wrench_rows(rows: np.ndarray, factors: np.ndarray) -> np.ndarray:
        return rows * twist_factor * (scale / factors)[:, None] if len(rows) else rows.reshape(0, 6)

    actuation = wrench_rows(unit.actuation_wrenches, per_rate)
    couples = np.array([is_couple(w, tol, unit.length) for w in unit.constraint_wrenches], dtype=bool)
    constraints = unit.constraint_wrenches * twist_factor * np.where(couples, scale, 1.0)[:, None] if len(couples) else unit.constraint_wrenches
    matrix = np.vstack([(SWAP @ actuation.T).T, (SWAP @ constraints.T).T]) if actuation.size or constraints.size else np.zeros((0, 6))
    twist_map = None if unit.twist_map is None else unit.twist_map * twist_factor[:, None] * per_rate[None, :]
    limb_twists = tuple(t * twist_factor[:, None] * _variable_scales(c, scale)[None, :] for t, c in zip(unit.limb_twists, model.chains))
    transform = unit.transform.copy()
    transform[:3, 3] /= scale
    screw = None if unit.finite_screw is None else unit.finite_screw * twist_factor
    return JacobianResult(unit.name, unit.actuated, unit.dof, matrix, actuation.reshape(-1, 6), constraints.reshape(-1, 6),
                          (unit.platform_twists * twist_factor).reshape(-1, 6), twist_map, unit.rank, unit.condition, unit.singular,
                          limb_twists, transform, screw, unit.length / scale)


def _meeting_point(chain: Chain, values: np.ndarray) -> np.ndarray:
    """Where the limb meets the platform at the pose: the point of its last joint that has one."""
    moved = chain.limb.moved(values)
    for joint in reversed(moved.joints):
        if joint.kind != "P":
            return np.asarray(joint.point)
    return np.zeros(3)
