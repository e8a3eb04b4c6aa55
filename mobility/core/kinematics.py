"""Finite motion of a mechanism: joint variables, forward kinematics and loop closure.

One module, longer than most, because it is one concept that reads better
whole: the joint variables, the link displacements, the loop residuals, their
Jacobians and the Newton closure all stand on one spanning tree and one set of
normalised coordinates, held by one :class:`Kinematics` object.

The screw route (:func:`mobility.analyze`) answers at one pose.  This module
moves the mechanism: it is the finite counterpart of
:mod:`mobility.core.loop_closure`, on the same spanning tree of the joint graph.

* **Joint variables** ``q``: one per elementary freedom
  (:meth:`~mobility.core.model.Joint.freedoms`), in the order of
  :func:`~mobility.core.joint_screws.joint_screws` (joint after joint); ``q = 0`` is
  the given pose.  Rotations are in radians, translations in units of the
  mechanism's characteristic length ``L`` (see :mod:`mobility.core.tolerance`), so
  every number here is dimensionless and does not change when the file is
  scaled or moved rigidly.
* **Finite motion of a joint** (``links[1]`` relative to ``links[0]``): the
  product of exponentials of its freedoms, ``exp(q1 x1) exp(q2 x2) ...``,
  in the order of the freedoms (``U``: the axis on ``links[0]``'s side first;
  ``S``: rotations about x, y, z; ``E``: two translations, then the rotation).
  Twists ``x_i`` are taken at the given pose, in normalised coordinates.
* **Forward kinematics** along a breadth-first spanning tree from the ground:
  the displacement ``g_L`` of each link (a 4x4 homogeneous matrix mapping the
  link's points from the given pose to the moved one, normalised coordinates)
  is the product of the joint motions on its tree path.
* **Loop closure**: each joint off the tree (a *chord*, from ``a`` to ``b``)
  closes one loop, ``g_a E_c(q_c) g_b^-1 = I``.  The residual of the loop is
  the matrix logarithm of that product
  (:func:`~mobility.core.transforms.displacement_log`), a twist ``[w; v]`` (6 numbers; the
  common part of the two tree paths cancels).  Its Jacobian is the
  right-trivialised loop Jacobian (the joint twists at the moved pose, the
  same equations as :mod:`mobility.core.loop_closure`) corrected by the inverse
  of the differential of the exponential, so it is the exact derivative.
* **Re-closure**: Gauss–Newton with minimum-norm steps (least squares) from a
  guess, optionally with extra linear equations ``A q = b`` (used to fix the
  progress along a direction).
* **Moved mechanism**: :meth:`Kinematics.mechanism_at` builds a new
  :class:`~mobility.core.model.Mechanism` at the pose ``q``: each joint's geometry
  is carried by the link it belongs to (a ``U`` joint's first axis by
  ``links[0]``, its second by ``links[1]``; every other field by
  ``links[0]``), written in the global frame.

Examples
--------
>>> import numpy as np
>>> from mobility.core.model import Joint, Mechanism
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
>>> m = Mechanism("four-bar", "g", "c", (R("A", "g", "k", (0, 0, 0)), R("B", "k", "c", (1, 2, 0)),
...                                        R("C", "c", "r", (4, 2.5, 0)), R("D", "r", "g", (5, 0, 0))))
>>> kin = kinematics(m)
>>> kin.variable_count, kin.chords
(4, (2,))
>>> float(np.abs(kin.residual(np.zeros(4))).max())
0.0
>>> guess = 0.05 * kin.tangent_space(np.zeros(4))[:, 0]
>>> closed = kin.close(guess)
>>> closed.converged, closed.residual < 1e-12
(True, True)
>>> moved = kin.mechanism_at(closed.q)
>>> bool(np.isclose(np.linalg.norm(np.subtract(moved.joints[1].point, moved.joints[0].point)), np.sqrt(5)))
True
"""

from __future__ import annotations

from dataclasses import dataclass, field
from dataclasses import replace as _replace
from typing import Sequence

import numpy as np

from ..errors import RequestError
from .joint_screws import Normalisation, joint_screws, per_object_cache
from .model import WORLD, Joint, Mechanism
from .tolerance import DEFAULT_TOLERANCE, NEWTON_RCOND, RankDecision, Tolerance, decide_rank
from .topology import spanning_tree
from .transforms import bracket, cross, displacement_log, displacement_logs, skew

__all__ = [
    "Factor",
    "Closure",
    "Kinematics",
    "kinematics",
]


# ---------------------------------------------------------------------------
# The model
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Factor:
    """One factor ``exp(sign * q[variable] * twist)`` of a product of exponentials."""

    variable: int
    sign: float


@dataclass(frozen=True, eq=False)
class Closure:
    """Outcome of one re-closure (:meth:`Kinematics.close`).

    Attributes
    ----------
    q : ndarray
        Joint variables reached (the best iterate).
    residual : float
        Largest absolute loop residual (and extra-equation error) there,
        dimensionless.
    iterations : int
        Newton steps taken.
    converged : bool
        ``residual <= tol.closure``.
    history : tuple of float
        The residual before each step (for diagnostics).
    """

    q: np.ndarray
    residual: float
    iterations: int
    converged: bool
    history: tuple[float, ...] = ()


@dataclass(frozen=True, eq=False)
class Kinematics:
    """Product-of-exponentials model of a mechanism at its given pose (``q = 0``).

    Build it with :func:`kinematics`.  All twists and displacements are in the
    normalised coordinates of the tolerance policy (origin at the mechanism's
    centre, lengths over ``L``).

    Attributes
    ----------
    mechanism : Mechanism
        The mechanism at ``q = 0``.
    normalisation : Normalisation
        Centre and length ``L`` of the normalised coordinates.
    twists : ndarray, shape (6, n)
        The twist of each freedom at the given pose, unit angular part for a
        rotation (unit linear part for a translation), so ``q`` is an angle
        or a length over ``L``.
    offsets : ndarray, shape (J + 1,)
        Variables of joint ``j`` are ``offsets[j]:offsets[j+1]``.
    kinds : tuple of str
        ``"R"``, ``"P"`` or ``"H"`` for each variable.
    tree : tuple of int
        Indices of the joints of the spanning tree.
    chords : tuple of int
        Indices of the joints closing one loop each, in the order of the
        residual's 6-blocks.
    paths : dict of str to tuple of Factor
        For each link, the product of exponentials from the ground to it
        along the spanning tree.
    loops : tuple of tuple of Factor
        For each chord, the product around its loop (from the links' common
        ancestor, through the chord, and back), whose value is the identity
        when the loop closes.
    """

    mechanism: Mechanism
    normalisation: Normalisation
    twists: np.ndarray
    offsets: np.ndarray
    kinds: tuple[str, ...]
    tree: tuple[int, ...]
    chords: tuple[int, ...]
    paths: dict[str, tuple[Factor, ...]] = field(repr=False)
    loops: tuple[tuple[Factor, ...], ...] = field(repr=False)
    _points: np.ndarray = field(repr=False)
    _axes: np.ndarray = field(repr=False)
    _pitches: np.ndarray = field(repr=False)
    _skews: np.ndarray = field(repr=False)
    _skews2: np.ndarray = field(repr=False)
    _prismatic: np.ndarray = field(repr=False)
    _loop_groups: tuple = field(repr=False)

    @property
    def variable_count(self) -> int:
        """Number of joint variables ``n`` (the sum of the joints' DOF)."""
        return self.twists.shape[1]

    @property
    def loop_count(self) -> int:
        """Number of independent loops (chords)."""
        return len(self.chords)

    def variables_of(self, joint: int | str) -> slice:
        """Slice of ``q`` holding the variables of a joint (index or name)."""
        names = [j.name for j in self.mechanism.joints]
        if isinstance(joint, int) and 0 <= joint < len(names):
            index = joint
        elif joint in names:
            index = names.index(joint)
        else:
            raise RequestError(f"joint: expected a joint name or an index below {len(names)}, got {joint!r}")
        return slice(int(self.offsets[index]), int(self.offsets[index + 1]))

    # -- products of exponentials -------------------------------------------
    def _factor_exps(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``exp(q_i x_i)`` and its inverse for every variable, each of shape ``(n, 4, 4)`` (Rodrigues, vectorised)."""
        q = np.asarray(q, dtype=float)
        sin, one_minus_cos = np.sin(q), 1.0 - np.cos(q)
        rot = np.eye(3) + sin[:, None, None] * self._skews + one_minus_cos[:, None, None] * self._skews2
        rot[self._prismatic] = np.eye(3)
        p = self._points
        shift = p - np.einsum("nij,nj->ni", rot, p) + (self._pitches * q)[:, None] * self._axes
        shift[self._prismatic] = q[self._prismatic, None] * self._axes[self._prismatic]
        exps = np.zeros((len(q), 4, 4))
        exps[:, 3, 3] = 1.0
        exps[:, :3, :3] = rot
        exps[:, :3, 3] = shift
        inverses = exps.copy()
        inverses[:, :3, :3] = rot.transpose(0, 2, 1)
        inverses[:, :3, 3] = -np.einsum("nji,nj->ni", rot, shift)
        return exps, inverses

    @staticmethod
    def _product(factors: tuple[Factor, ...], exps: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
        g = np.eye(4)
        forward, backward = exps
        for f in factors:
            g = g @ (forward[f.variable] if f.sign > 0 else backward[f.variable])
        return g

    def _check(self, q: np.ndarray) -> np.ndarray:
        q = np.asarray(q, dtype=float).reshape(-1)
        if q.shape != (self.variable_count,):
            raise RequestError(f"expected {self.variable_count} joint variables, got {q.size}")
        return q

    def link_displacements(self, q: np.ndarray) -> dict[str, np.ndarray]:
        """Displacement ``g_L`` (4x4, normalised coordinates) of every link at ``q``.

        ``g_L`` maps a point of link ``L`` at the given pose to where it is at
        ``q`` (the ground's is the identity).
        """
        q = self._check(q)
        exps = self._factor_exps(q)
        return {link: self._product(path, exps) for link, path in self.paths.items()}

    def loop_displacements(self, q: np.ndarray) -> list[np.ndarray]:
        """For each chord ``c`` from ``a`` to ``b``: ``g_a E_c(q_c) g_b^-1`` (identity when closed)."""
        q = self._check(q)
        exps = self._factor_exps(q)
        return [self._product(loop, exps) for loop in self.loops]

    def residual(self, q: np.ndarray) -> np.ndarray:
        """Loop-closure residual at ``q``: the logarithm of each loop product, stacked (``6 * loops``)."""
        if not self.loops:
            self._check(q)
            return np.zeros(0)
        return np.concatenate([displacement_log(g) for g in self.loop_displacements(q)])

    def _spatial(self, factors: tuple[Factor, ...], exps: tuple[np.ndarray, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        """Product ``G`` of ``factors`` and its right-trivialised derivative ``(dG G^-1)`` per variable."""
        cols = np.zeros((6, self.variable_count))
        if not factors:
            return np.eye(4), cols
        forward, backward = exps
        before = np.empty((len(factors), 4, 4))
        g = np.eye(4)
        for i, f in enumerate(factors):
            before[i] = g
            g = g @ (forward[f.variable] if f.sign > 0 else backward[f.variable])
        variables = [f.variable for f in factors]  # each variable at most once in a path or loop
        x = self.twists[:, variables].T * np.array([f.sign for f in factors])[:, None]
        rot, shift = before[:, :3, :3], before[:, :3, 3]
        w = np.einsum("mij,mj->mi", rot, x[:, :3])
        v = cross(shift.T, w.T).T + np.einsum("mij,mj->mi", rot, x[:, 3:])
        cols[:, variables] = np.concatenate([w, v], axis=1).T
        return g, cols

    def loop_jacobian(self, q: np.ndarray) -> np.ndarray:
        """Right-trivialised loop Jacobian at ``q``: rows ``(dL L^-1)`` of each loop product ``L``.

        At a closed pose these are the loop-closure equations of
        :mod:`mobility.core.loop_closure` written with the joint twists at the moved
        pose (up to the sign and the column scaling of unit twists).
        """
        q = self._check(q)
        exps = self._factor_exps(q)
        rows = [self._spatial(loop, exps)[1] for loop in self.loops]
        return np.vstack(rows) if rows else np.zeros((0, self.variable_count))

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """Exact derivative of :meth:`residual` at ``q``, shape ``(6 * loops, n)``."""
        return self.linearize(q)[1]

    def linearize(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`residual` and :meth:`jacobian` at ``q``, computed together."""
        q = self._check(q)
        if not self.loops:
            return np.zeros(0), np.zeros((0, self.variable_count))
        forward, backward = self._factor_exps(q)
        table = np.concatenate([forward, backward, np.eye(4)[None]])
        residual = np.empty((self.loop_count, 6))
        rows = np.empty((self.loop_count, 6, self.variable_count))
        for loops, factors, signs in self._loop_groups:
            residual[loops], rows[loops] = self._linearize_loops(table, factors, signs)
        return residual.reshape(-1), rows.reshape(-1, self.variable_count)

    def _linearize_loops(self, table: np.ndarray, factors: np.ndarray, signs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Residuals and exact derivatives of loops of about one length, all at once.

        ``factors[l, i]`` indexes the matrix of loop ``l``'s ``i``-th factor in
        ``table`` (forward exponentials, backward ones, the identity that pads
        a shorter loop), ``signs`` its sign (0 for padding).  The products are
        taken position by position over all the loops, then the logarithms and
        the derivatives of the exponential as stacks.
        """
        n = self.variable_count
        count, length = factors.shape
        matrices = table[factors]  # (loops, length, 4, 4)
        before = np.empty((count, length, 4, 4))
        g = np.broadcast_to(np.eye(4), (count, 4, 4))
        for i in range(length):
            before[:, i] = g
            g = g @ matrices[:, i]
        variables = factors % n
        x = self.twists.T[variables] * signs[..., None]  # a padding factor has sign 0
        turned = before[..., :3, :3] @ x.reshape(count, length, 2, 3).transpose(0, 1, 3, 2)  # R w and R v of each factor's twist
        w = turned[..., 0]
        v = cross(before[..., :3, 3].T, w.T).T + turned[..., 1]
        cols = np.zeros((count, n + 1, 6))
        cols[np.arange(count)[:, None], np.where(signs != 0.0, variables, n)] = np.concatenate([w, v], axis=-1)
        r, derivative = displacement_logs(g, with_dexp=True)
        return r, np.linalg.solve(derivative, cols[:, :n].transpose(0, 2, 1))

    def end_effector_jacobian(self, q: np.ndarray) -> np.ndarray:
        """Twist of the end effector (normalised coordinates, ``[w; v]``) per unit joint rate, at ``q``."""
        q = self._check(q)
        exps = self._factor_exps(q)
        return self._spatial(self.paths[self.mechanism.end_effector], exps)[1]

    # -- first-order and second-order structure ------------------------------
    def rank_decision(self, q: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[RankDecision, np.ndarray]:
        """Rank of the loop Jacobian at ``q`` (unit-norm columns, the tolerance policy) and its null space.

        Returns the decision and an orthonormal basis (``n x mobility``, in
        the metric of ``q``) of the joint rates that close every loop to first
        order.
        """
        jac = self.loop_jacobian(q)
        n = self.variable_count
        if jac.shape[0] == 0:
            return RankDecision(0), np.eye(n)
        norms = np.linalg.norm(self.twists, axis=0)
        _, s, vt = np.linalg.svd(jac / norms, full_matrices=True)
        decision = decide_rank(s, tol)
        null = vt[decision.rank :].T / norms[:, None]  # back to rates of q
        if null.shape[1]:
            null = np.linalg.qr(null)[0]
        return decision, null

    def tangent_space(self, q: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> np.ndarray:
        """Orthonormal basis of the first-order motions at ``q`` (null space of the loop Jacobian)."""
        return self.rank_decision(q, tol)[1]

    def second_order_forms(self, cokernel: np.ndarray) -> np.ndarray:
        """Second derivative of the residual at ``q = 0`` along a direction, projected on ``cokernel``.

        For a direction ``d`` of joint rates, ``r(t d) = t J d + t^2/2 B(d, d) + O(t^3)``
        with ``B(d, d) = sum_{i<j} [a_i, a_j]`` over the factors of each loop
        (``a_i = sign_i d_(var i) x_i``, Baker–Campbell–Hausdorff).  Returns the
        symmetric matrices ``M_k`` with ``w_k . B(d, d) = d @ M_k @ d`` for each
        column ``w_k`` of ``cokernel`` (shape ``(6 * loops, c)``), as an array
        ``(c, n, n)``.  A first-order motion ``d`` extends to second order only
        if every ``d @ M_k @ d`` vanishes (``w_k`` spanning the left null space
        of the Jacobian).
        """
        n = self.variable_count
        cokernel = np.asarray(cokernel, dtype=float).reshape(6 * self.loop_count, -1)
        out = np.zeros((cokernel.shape[1], n, n))
        for index, loop in enumerate(self.loops):
            w = cokernel[6 * index : 6 * index + 6]  # (6, c)
            if not np.any(w):
                continue
            xs = [f.sign * self.twists[:, f.variable] for f in loop]
            for i in range(len(loop)):
                for j in range(i + 1, len(loop)):
                    b = bracket(xs[i], xs[j]) @ w  # (c,)
                    vi, vj = loop[i].variable, loop[j].variable
                    out[:, vi, vj] += 0.5 * b
                    out[:, vj, vi] += 0.5 * b
        return out

    # -- re-closure ------------------------------------------------------------
    def close(
        self,
        q: np.ndarray,
        *,
        constraints: tuple[np.ndarray, np.ndarray] | None = None,
        tol: Tolerance = DEFAULT_TOLERANCE,
        max_iter: int = 40,
        max_move: float | None = None,
    ) -> Closure:
        """Re-close every loop by Gauss–Newton with minimum-norm steps, starting from ``q``.

        Parameters
        ----------
        q : ndarray
            Starting joint variables (e.g. the given pose plus a step).
        constraints : (A, b), optional
            Extra linear equations ``A q = b`` solved together with the loops
            (e.g. the progress along a direction).
        tol : Tolerance
            Closed when every residual component is at most ``tol.closure``
            (dimensionless: radians, lengths over ``L``).
        max_iter : int
            Newton steps at most.
        max_move : float, optional
            Give up when the iterate goes farther than this from the start
            (it would reach another assembly, not the nearby one).

        Returns
        -------
        Closure
            ``converged`` tells whether it closed; never raises for a failure
            to close (the caller decides what that means).
        """
        q = self._check(q).copy()
        closed = tol.closure
        start = q.copy()
        if constraints is None:
            a = np.zeros((0, self.variable_count))
            b = np.zeros(0)
        else:
            a = np.asarray(constraints[0], dtype=float).reshape(-1, self.variable_count)
            b = np.asarray(constraints[1], dtype=float).reshape(-1)
        best_q, best_err = q.copy(), np.inf
        history: list[float] = []
        stalled = 0
        polish = 0
        for iteration in range(max_iter + 1):
            r, jac = self.linearize(q)
            f = np.concatenate([r, a @ q - b])
            err = float(np.max(np.abs(f))) if f.size else 0.0
            history.append(err)
            improved = err < 0.5 * best_err
            if err < best_err:
                stalled = 0 if improved else stalled + 1
                best_q, best_err = q.copy(), err
            else:
                stalled += 1
            if best_err <= closed:
                # closed; polish while Newton still gains (a small residual near a
                # singular pose can leave the pose itself off by residual / sigma_min)
                polish += 1
                if not improved or polish > 3 or err == 0.0:
                    break
            if iteration == max_iter or stalled >= 6:
                break
            step = np.linalg.lstsq(np.vstack([jac, a]), -f, rcond=NEWTON_RCOND)[0]
            if _converging_linearly(history):
                step = 2.0 * step  # at a singular root Newton halves the error each step: the doubled step removes it
            q = q + step
            if not np.all(np.isfinite(q)) or (max_move is not None and np.linalg.norm(q - start) > max_move):
                break
        return Closure(best_q, best_err, len(history) - 1, best_err <= closed, tuple(history))

    # -- the moved mechanism -------------------------------------------------------
    def mechanism_at(self, q: np.ndarray) -> Mechanism:
        """The mechanism at the pose ``q``, joints written in the global frame.

        Each joint's geometry is carried by the link it belongs to (see the
        module docstring); names, types, links and ``actuated`` flags are kept,
        named frames are dropped (they describe the given pose) and so is the
        ``expected`` block (it describes the given pose too).
        """
        g = self.link_displacements(q)
        norm = self.normalisation
        joints = []
        for joint in self.mechanism.world_joints:
            ga, gb = g[joint.links[0]], g[joint.links[1]]

            def point(p: tuple[float, float, float] | None, disp: np.ndarray = ga) -> tuple[float, ...] | None:
                if p is None:
                    return None
                pn = norm.point_from_world(np.asarray(p))
                return tuple(float(x) for x in norm.point_to_world(disp[:3, :3] @ pn + disp[:3, 3]))

            def direction(d: tuple[float, float, float] | None, disp: np.ndarray = ga) -> tuple[float, ...] | None:
                return None if d is None else tuple(float(x) for x in disp[:3, :3] @ np.asarray(d))

            changes: dict = {"frame": WORLD, "point": point(joint.point), "axis": direction(joint.axis), "normal": direction(joint.normal)}
            if joint.axes is not None:
                changes["axes"] = (direction(joint.axes[0], ga), direction(joint.axes[1], gb))
            joints.append(_replace(joint, **changes))
        return self.mechanism.replace(joints=_keep_coincident_points(self.mechanism.world_joints, joints), frames=(), expected=None)


POINT_FIXED_IN_BOTH = frozenset("RUS")
"""Joint types whose point stays fixed in both links (they only turn about it); a C, H, P or E joint moves it along the other."""


def _keep_coincident_points(given: Sequence[Joint], moved: list[Joint]) -> tuple[Joint, ...]:
    """``moved`` with the joints of one link that met at one point in ``given`` meeting there still.

    Each moved point is carried by one of its joint's links, so two joints of
    a link that met at one point (axes that intersect) may come out apart by
    round-off of the mechanism's size; near the origin that is far above the
    round-off of their own tiny coordinates, and the analysis would take them
    for distinct points it cannot resolve.  A rigid link keeps them together:
    each takes the moved point of the first joint of the group.
    """
    first: dict[tuple, int] = {}
    for index, joint in enumerate(given):
        if joint.point is None:
            continue
        # the links the point is fixed in: both for a joint that only turns about it, else the carrier (links[0])
        for link in joint.links if joint.type in POINT_FIXED_IN_BOTH else joint.links[:1]:
            key = (link, tuple(joint.point))
            if key in first:
                source = moved[first[key]].point
                if index != first[key] and moved[index].point != source:
                    moved[index] = _replace(moved[index], point=source)
            else:
                first[key] = index
    return tuple(moved)


LINEAR_RATIO = (0.15, 0.35)
"""Newton's residual shrinking by a ratio in this range at two steps running (about 1/4: the
error halves, the residual is quadratic in it) is the mark of a singular root."""


def _converging_linearly(history: list[float]) -> bool:
    """Whether the last three residuals shrank by about 1/4 at each step (Newton at a singular root)."""
    if len(history) < 3 or history[-3] == 0.0 or history[-2] == 0.0:
        return False
    low, high = LINEAR_RATIO
    return low <= history[-2] / history[-3] <= high and low <= history[-1] / history[-2] <= high


def kinematics(mechanism: Mechanism) -> Kinematics:
    """The product-of-exponentials model of ``mechanism`` at its pose (cached per mechanism).

    Parameters
    ----------
    mechanism : Mechanism

    Returns
    -------
    Kinematics
    """
    return per_object_cache(mechanism, "kinematics", lambda: _build(mechanism))


def _build(mechanism: Mechanism) -> Kinematics:
    norm = joint_screws(mechanism).normalisation
    kinds, axes, points, pitches, offsets = [], [], [], [], [0]
    for joint in mechanism.world_joints:
        for f in joint.freedoms():
            kinds.append(f.kind)
            axes.append(np.asarray(f.axis, dtype=float))
            points.append(norm.point_from_world(np.asarray(f.point, dtype=float)))
            pitches.append(f.pitch / norm.length)
        offsets.append(len(kinds))
    n = len(kinds)
    axes_a = np.array(axes, dtype=float).reshape(n, 3)
    points_a = np.array(points, dtype=float).reshape(n, 3)
    pitch_a = np.array(pitches, dtype=float)
    is_p = np.array([k == "P" for k in kinds], dtype=bool)
    points_a[is_p] = 0.0
    pitch_a[~np.array([k == "H" for k in kinds], dtype=bool)] = 0.0
    w = np.where(is_p[:, None], 0.0, axes_a)
    v = np.where(is_p[:, None], axes_a, np.cross(points_a, axes_a) + pitch_a[:, None] * axes_a)
    twists = np.concatenate([w, v], axis=1).T.copy()
    twists.setflags(write=False)
    skews = np.array([skew(a) for a in axes_a]).reshape(n, 3, 3)

    # the spanning tree from the ground that mobility.core.loop_closure uses
    tree_edges, chords = spanning_tree(mechanism)

    def joint_factors(index: int, forward: bool) -> tuple[Factor, ...]:
        lo, hi = offsets[index], offsets[index + 1]
        if forward:
            return tuple(Factor(v, 1.0) for v in range(lo, hi))
        return tuple(Factor(v, -1.0) for v in reversed(range(lo, hi)))

    paths: dict[str, tuple[Factor, ...]] = {mechanism.ground: ()}
    joint_paths: dict[str, tuple[int, ...]] = {mechanism.ground: ()}
    tree: list[int] = []
    for edge in tree_edges:
        tree.append(edge.joint)
        paths[edge.child] = paths[edge.parent] + joint_factors(edge.joint, edge.forward)
        joint_paths[edge.child] = joint_paths[edge.parent] + (edge.joint,)
    loops = []
    for index in chords:
        a, b = mechanism.joints[index].links
        pa, pb = joint_paths[a], joint_paths[b]
        common = 0
        while common < min(len(pa), len(pb)) and pa[common] == pb[common]:
            common += 1
        skip_a = sum(offsets[j + 1] - offsets[j] for j in pa[:common])
        skip_b = sum(offsets[j + 1] - offsets[j] for j in pb[:common])
        inverse_b = tuple(Factor(f.variable, -f.sign) for f in reversed(paths[b][skip_b:]))
        loops.append(paths[a][skip_a:] + joint_factors(index, True) + inverse_b)
    # the loops as tables of the index of each factor's matrix among [forward (n), backward (n), identity],
    # grouped by length within a factor of two (so padding at most doubles the work)
    by_length: dict[int, list[int]] = {}
    for row, loop in enumerate(loops):
        by_length.setdefault(max(len(loop), 1).bit_length(), []).append(row)
    groups = []
    for rows in by_length.values():
        length = max(len(loops[r]) for r in rows)
        factors = np.full((len(rows), length), 2 * n, dtype=int)
        signs = np.zeros((len(rows), length))
        for k, row in enumerate(rows):
            for i, factor in enumerate(loops[row]):
                factors[k, i] = factor.variable if factor.sign > 0 else n + factor.variable
                signs[k, i] = factor.sign
        groups.append((np.array(rows), factors, signs))
    return Kinematics(
        mechanism=mechanism,
        normalisation=norm,
        twists=twists,
        offsets=np.array(offsets),
        kinds=tuple(kinds),
        tree=tuple(sorted(tree)),
        chords=chords,
        paths=paths,
        loops=tuple(tuple(loop) for loop in loops),
        _points=points_a,
        _axes=axes_a,
        _pitches=pitch_a,
        _skews=skews,
        _skews2=skews @ skews,
        _prismatic=is_p,
        _loop_groups=tuple(groups),
    )
