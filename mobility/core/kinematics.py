"""Finite motion of a mechanism, for one pose or a stack of many: forward kinematics, loop closure, Newton.

One module, longer than most, because it is one concept that reads better
whole: the joint variables, the link displacements, the loop residuals, their
Jacobians and the Newton closure all stand on one spanning tree and one set of
normalised coordinates, held by one :class:`Kinematics` object.  Every method
takes one pose ``q`` ``(n,)`` or a stack ``(N, n)`` (as SciPy's ``Rotation``):
one pose is a stack of one, and nothing loops over poses.  It is the finite
counterpart of :mod:`mobility.core.loop_closure`, on the same spanning tree.

* **Joint variables** ``q``: one per elementary freedom
  (:meth:`~mobility.core.model.Joint.freedoms`), joint after joint; ``q = 0``
  is the given pose.  Radians, and lengths over the mechanism's
  characteristic length ``L`` (:mod:`mobility.core.tolerance`): dimensionless,
  unchanged when the file is scaled or moved rigidly.
* **A joint's motion** (``links[1]`` relative to ``links[0]``):
  ``exp(q1 x1) exp(q2 x2) ...`` in the order of its freedoms (``U``: the axis
  on ``links[0]``'s side first; ``S``: about x, y, z; ``E``: two translations,
  then the rotation), twists ``x_i`` at the given pose, normalised coordinates.
* **Forward kinematics**: a link's displacement ``g_L`` is the product of the
  joint motions on its path of a breadth-first spanning tree from the ground.
  Stacks are held pose index last (:data:`~mobility.core.transforms.Motion`)
  and multiplied in a fixed order, so each pose's numbers are the same bits
  whatever the stack around it.
* **Loop closure**: each joint off the tree (a *chord*, from ``a`` to ``b``)
  closes one loop, ``g_a E_c(q_c) g_b^-1 = I``; its residual is the logarithm
  of that product (a twist, 6 numbers).  Its right-trivialised Jacobian is
  exact at a closed pose; :meth:`Kinematics.jacobian` corrects it by the
  inverse differential of the exponential, exact everywhere.
* **Re-closure**: :func:`newton`, on every pose of a stack at once;
  **moved mechanism**: :meth:`Kinematics.mechanism_at`.

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
>>> kin.residual(np.stack([np.zeros(4), closed.q])).shape   # a stack of poses
(2, 6)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from dataclasses import replace as _replace
from typing import Sequence

import numpy as np

from ..errors import RequestError
from .joint_screws import Normalisation, joint_screws, per_object_cache
from .model import WORLD, Joint, Mechanism
from .tolerance import DEFAULT_TOLERANCE, NEWTON_DAMPING, RankDecision, Tolerance, decide_rank
from .topology import spanning_tree
from .transforms import Motion, bracket, compose, cross, dexps, inverse_left_jacobian_times, rotate, rotation_logs_last, skew, twist_logs

__all__ = [
    "Factor",
    "Closure",
    "Closures",
    "Equations",
    "Evaluation",
    "Kinematics",
    "kinematics",
    "newton",
    "polish",
    "min_norm_steps",
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
    reference : ndarray, shape (3,)
        The end effector's reference point (normalised coordinates of the
        given pose) whose displacement the pose coordinates of
        :meth:`evaluate` measure.
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
    reference: np.ndarray = field(repr=False)
    _steps: tuple[tuple[str, str, tuple[Factor, ...]], ...] = field(repr=False)
    _axes: np.ndarray = field(repr=False)
    _pitches: np.ndarray = field(repr=False)
    _prismatic: np.ndarray = field(repr=False)
    _k: np.ndarray = field(repr=False)  # skew(axis), skew(axis)^2, skew(axis) p and skew(axis)^2 p of each variable (p: the axis's point nearest the origin)
    _k2: np.ndarray = field(repr=False)
    _kp: np.ndarray = field(repr=False)
    _k2p: np.ndarray = field(repr=False)
    _loop_groups: tuple["_Chains", ...] = field(repr=False)  # loops of about one length together
    _loop_alone: tuple["_Chains", ...] = field(repr=False)  # each loop alone
    _end_effector: "_Chains" = field(repr=False)  # the end effector's path

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

    # -- products of exponentials, pose index last ----------------------------------
    def _stack(self, q: np.ndarray) -> tuple[np.ndarray, bool]:
        """``q`` as a stack ``(N, n)`` (``numpy.longdouble`` kept, else float64) and whether it was one pose."""
        q = np.asarray(q)
        q = q if q.dtype == np.longdouble else np.asarray(q, dtype=float)
        n = self.variable_count
        if q.ndim == 2:
            if q.shape[1] != n:
                raise RequestError(f"expected joint variables of shape (N, {n}), got {q.shape}")
            return q, False
        if q.size != n:
            raise RequestError(f"expected {n} joint variables, got {q.size}")
        return q.reshape(1, n), True

    @staticmethod
    def _chain(chains: "_Chains", exps: "_Exponentials") -> tuple[np.ndarray, list[np.ndarray | None]]:
        """Products of ``G`` chains of factors of one length as frames ``[R | t]``, their poses side by side
        (``(3, 4, G N)``), and the partial products before each position (``None``: the identity)."""
        g: np.ndarray | None = None
        before: list[np.ndarray | None] = []
        for factors in chains.steps:
            before.append(g)
            g = compose(g, exps.gather(factors))
        return (_identity(exps.count * chains.size) if g is None else g), before

    def _columns(self, chains: "_Chains", before: list[np.ndarray | None], rows: np.ndarray | None, count: int) -> np.ndarray:
        """Right-trivialised derivatives ``(6, n, G, len(rows))`` of chains' products from their partial products.

        The positions are taken all at once for a small stack (fewer array
        operations), one at a time for a large one (no copies of the partial
        products); each pose's numbers are the same either way.
        """
        n, size, x = self.variable_count, chains.size, chains.twists
        cols = np.zeros((6, n + 1, size, count))  # a padding factor's column is the last, dropped
        if not before:
            return cols[:, :n]
        which = np.arange(size)
        cols[:, chains.variables[0], which] = x[:, 0, :, None]  # the identity before the first factor
        block = len(before) if size * count <= GROUPED_POSES else 1
        for start in range(1, len(before), block):
            part = before[start : start + block]
            frames = (part[0][:, :, None] if len(part) == 1 else np.stack(part, axis=2)).reshape(3, 4, len(part), size, -1)  # type: ignore[index, arg-type]
            if rows is not None:
                frames = frames[..., rows]
            turns = x[:, start : start + len(part), :, None]
            rot = frames[:, :3]
            w = rotate(rot, turns[:3])
            variables = chains.variables[start : start + len(part)]
            cols[:3, variables, which] = w
            cols[3:, variables, which] = cross(frames[:, 3], w) + rotate(rot, turns[3:])
        return cols[:, :n]

    def link_motions(self, q: np.ndarray) -> dict[str, Motion]:
        """Displacement of every link, stacked pose index last: rotation ``(3, 3, N)`` and translation ``(3, N)``."""
        q, _ = self._stack(q)
        exps = _Exponentials(self, q.T)
        frames = {self.mechanism.ground: _identity(exps.count)}
        for parent, child, step in self._steps:
            g = frames[parent]
            for f in step:
                g = compose(g, exps.factor(f.variable, f.sign))
            frames[child] = g
        return {link: (g[:, :3], g[:, 3]) for link, g in frames.items()}

    def link_displacements(self, q: np.ndarray) -> dict[str, np.ndarray]:
        """Displacement ``g_L`` (4x4, normalised coordinates; ``(N, 4, 4)`` for a stack) of every link at ``q``.

        ``g_L`` maps a point of link ``L`` at the given pose to where it is at
        ``q`` (the ground's is the identity).
        """
        _, single = self._stack(q)
        out = {}
        for link, (rot, shift) in self.link_motions(q).items():
            g = np.zeros((rot.shape[-1], 4, 4))
            g[:, :3, :3] = np.moveaxis(rot, -1, 0)
            g[:, :3, 3] = shift.T
            g[:, 3, 3] = 1.0
            out[link] = g[0] if single else g
        return out

    # -- loops and the end effector ----------------------------------------------------
    def evaluate(self, q: np.ndarray, components: np.ndarray | None = None) -> "Evaluation":
        """The loop residuals (and pose coordinates ``components``) of a stack now, their Jacobian later and only for the poses that need it."""
        return Evaluation(self, self._stack(q)[0], components)

    def residual(self, q: np.ndarray) -> np.ndarray:
        """Loop-closure residual at ``q``: the logarithm of each loop product, stacked (``6 * loops``; ``(N, 6 * loops)`` for a stack)."""
        stack, single = self._stack(q)
        values = self.evaluate(stack).values.T
        return values[0] if single else values

    def loop_jacobian(self, q: np.ndarray) -> np.ndarray:
        """Right-trivialised loop Jacobian at ``q``: rows ``(dL L^-1)`` of each loop product ``L`` (``(6 * loops, n)``).

        At a closed pose these are the loop-closure equations of
        :mod:`mobility.core.loop_closure` written with the joint twists at the moved
        pose (up to the sign and the column scaling of unit twists).
        """
        stack, single = self._stack(q)
        jac = np.moveaxis(self.evaluate(stack).jacobian(), -1, 0)
        return jac[0] if single else jac

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """Exact derivative of :meth:`residual` at ``q``, shape ``(6 * loops, n)`` (``(N, 6 * loops, n)`` for a stack)."""
        stack, single = self._stack(q)
        exact = Equations(exact=True).jacobians(self.evaluate(stack))
        return exact[0] if single else exact

    def end_effector_jacobian(self, q: np.ndarray) -> np.ndarray:
        """Twist of the end effector (normalised coordinates, ``[w; v]``) per unit joint rate, at ``q`` (``(6, n)``)."""
        stack, single = self._stack(q)
        exps = _Exponentials(self, stack.T)
        chains = self._end_effector
        cols = np.moveaxis(self._columns(chains, self._chain(chains, exps)[1], None, exps.count)[:, :, 0], -1, 0)
        return cols[0] if single else cols

    # -- first-order and second-order structure ------------------------------
    def rank_decision(self, q: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[RankDecision, np.ndarray]:
        """Rank of the loop Jacobian at one pose ``q`` (unit-norm columns, the tolerance policy) and its null space.

        Returns the decision and an orthonormal basis (``n x mobility``, in
        the metric of ``q``) of the joint rates that close every loop to first
        order.
        """
        return self.rank_decisions(self._stack(q)[0][:1], tol)[0]

    def rank_decisions(self, q: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[tuple[RankDecision, np.ndarray], ...]:
        """:meth:`rank_decision` at each pose of a stack ``q`` ``(N, n)`` (one Jacobian and one SVD call for the stack)."""
        stack = self._stack(q)[0]
        n = self.variable_count
        if self.loop_count == 0:
            return tuple((RankDecision(0), np.eye(n)) for _ in stack)
        # + 0.0: a signed zero (the sign of a product's round-off) is a plain zero, whose null space LAPACK completes
        # the same way whatever the file's scale (-0.0 and 0.0 steer its reflections apart)
        jac = np.moveaxis(self.evaluate(stack).jacobian(), -1, 0) + 0.0
        norms = np.linalg.norm(self.twists, axis=0)
        _, s, vt = np.linalg.svd(jac / norms, full_matrices=True)
        out = []
        for sk, vk in zip(s, vt):
            decision = decide_rank(sk, tol)
            null = vk[decision.rank :].T / norms[:, None]  # back to rates of q
            out.append((decision, np.linalg.qr(null)[0] if null.shape[1] else null))
        return tuple(out)

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
        """Re-close every loop of one pose by :func:`newton` (a stack of one), starting from ``q``.

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
            to close (the caller decides what that means).  Unlike a sweep's
            solves, it keeps stepping while Newton still gains after closing, down
            to the round-off of the residual (a small residual near a singular
            pose can leave the pose itself off by residual / sigma_min).
        """
        q = self._stack(q)[0][0]
        if constraints is not None:
            constraints = (np.asarray(constraints[0], dtype=float).reshape(1, -1, self.variable_count), np.asarray(constraints[1], dtype=float).reshape(1, -1))
        return self.close_each(q[None], constraints=constraints, closure=np.array([tol.closure]), max_iter=max_iter,
                               max_move=np.inf if max_move is None else max_move)[0]

    def close_each(
        self,
        q: np.ndarray,
        *,
        closure: np.ndarray,
        constraints: tuple[np.ndarray, np.ndarray] | None = None,
        max_iter: int = 40,
        max_move: np.ndarray | float = np.inf,
    ) -> tuple[Closure, ...]:
        """:meth:`close` of each pose of a stack ``q`` ``(N, n)``, every pose with its own equations and thresholds, solved at once.

        ``constraints`` are ``A`` ``(N, k, n)`` and ``b`` ``(N, k)``, one
        system per pose; ``closure`` ``(N,)`` is each pose's closure threshold
        (``tol.closure`` of :meth:`close`); ``max_move`` a float or ``(N,)``.
        Each pose takes the Newton steps it would take alone: one Newton on
        the stack costs about what one on a single pose does, so moves along
        many directions and steps cost little more than one.
        """
        stack = self._stack(q)[0]
        count = len(stack)
        limit = np.broadcast_to(np.asarray(closure, dtype=float), (count,))
        if constraints is None:
            equations, goals = Equations(exact=True), np.zeros((count, 0))
        else:
            equations, goals = Equations(linear=np.asarray(constraints[0], dtype=float), exact=True), np.asarray(constraints[1], dtype=float)
        out = newton(self, stack, goals, equations, max_move=max_move, max_iter=max_iter, polished=ROUND_OFF / limit, accelerate=True,
                     patience=CLOSE_STALLED, closure=limit)
        closures = []
        for k in range(count):
            history = tuple(float(e) for e in out.history[k] if not np.isnan(e))
            closures.append(Closure(out.q[k], float(out.residual[k]), len(history) - 1, bool(out.converged[k]), history))
        return tuple(closures)

    # -- the moved mechanism -------------------------------------------------------
    def mechanism_at(self, q: np.ndarray) -> Mechanism:
        """The mechanism at the pose ``q``, joints written in the global frame.

        Each joint's geometry is carried by the link it belongs to (a ``U``
        joint's first axis by ``links[0]``, its second by ``links[1]``; every
        other field by ``links[0]``); names, types, links and ``actuated`` flags
        are kept, named frames and the ``expected`` block (both describe the
        given pose) dropped.
        """
        g = self.link_displacements(q)
        norm = self.normalisation
        joints = []
        for joint in self.mechanism.world_joints:
            ga, gb = g[joint.links[0]], g[joint.links[1]]

            def point(p: tuple[float, float, float] | None, disp: np.ndarray = ga) -> tuple[float, ...] | None:
                if p is None or np.array_equal(disp, _EYE4):  # a link that did not move (the ground) keeps its points exactly
                    return None if p is None else tuple(float(x) for x in p)
                pn = norm.point_from_world(np.asarray(p))
                return tuple(float(x) for x in norm.point_to_world(disp[:3, :3] @ pn + disp[:3, 3]))

            def direction(d: tuple[float, float, float] | None, disp: np.ndarray = ga) -> tuple[float, ...] | None:
                return None if d is None else tuple(float(x) for x in disp[:3, :3] @ np.asarray(d))

            changes: dict = {"frame": WORLD, "point": point(joint.point), "axis": direction(joint.axis), "normal": direction(joint.normal)}
            if joint.axes is not None:
                changes["axes"] = (direction(joint.axes[0], ga), direction(joint.axes[1], gb))
            joints.append(_replace(joint, **changes))
        return self.mechanism.replace(joints=_keep_coincident_points(self.mechanism.world_joints, joints), frames=(), expected=None)


_EYE4 = np.eye(4)

POINT_FIXED_IN_BOTH = frozenset("RUS")
"""Joint types whose point stays fixed in both links (they only turn about it); a C, H, P or E joint moves it along the other."""


def _keep_coincident_points(given: Sequence[Joint], moved: list[Joint]) -> tuple[Joint, ...]:
    """``moved`` with the joints of one link that met at one point in ``given`` meeting there still (the first one's point).

    Carried by different links, they could come apart by the round-off of the mechanism's size, far above that of
    coordinates near the origin: the analysis would take them for distinct points it cannot resolve.
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


def _identity(count: int) -> np.ndarray:
    """``count`` identity displacements as frames ``[I | 0]`` ``(3, 4, count)``."""
    return np.broadcast_to(np.eye(3, 4)[..., None], (3, 4, count))


@dataclass(frozen=True, eq=False)
class _Chains:
    """``G`` products of factors (loops, or the end effector's path), padded to one length by the identity.

    ``steps[i][g]``: chain ``g``'s ``i``-th factor (``None`` for padding);
    ``variables[i, g]`` its variable (``n`` for padding); ``twists[:, i, g]``
    its signed twist (zero for padding).
    """

    loops: tuple[int, ...]
    steps: tuple[tuple[Factor | None, ...], ...]
    variables: np.ndarray
    twists: np.ndarray
    size: int  # G


class _Exponentials:
    """``exp(q_i x_i)`` of every variable of a stack (Rodrigues), its inverse computed when first asked."""

    def __init__(self, kin: Kinematics, q: np.ndarray) -> None:  # q: (n, N)
        self.count = q.shape[1]
        sin, one_minus_cos = np.sin(q), 1.0 - np.cos(q)
        frames = np.empty((len(q), 3, 4, self.count), dtype=np.result_type(q.dtype, np.float64))
        rot, shift = frames[:, :, :3], frames[:, :, 3]
        # written in place term by term (the same sums, in the same order; numpy is slower with a fresh array as out)
        np.multiply(kin._k, sin[:, None, None, :], out=rot)
        rot += kin._k2 * one_minus_cos[:, None, None, :]
        # about the line through p: shift = (I - R) p + h q a, and (I - R) p = -(sin K p + (1 - cos) K^2 p)
        np.multiply(kin._kp, sin[:, None, :], out=shift)
        shift += kin._k2p * one_minus_cos[:, None, :]
        np.negative(shift, out=shift)
        shift += (kin._pitches[:, None] * q)[:, None, :] * kin._axes[:, :, None]
        rot += np.eye(3)[None, :, :, None]
        prismatic = kin._prismatic
        rot[prismatic] = np.eye(3)[:, :, None]
        shift[prismatic] = q[prismatic][:, None, :] * kin._axes[prismatic][:, :, None]
        self.frames = frames  # the forward exponentials as frames [R | t], (n, 3, 4, N)
        self._inverse: dict[int, np.ndarray] = {}

    def factor(self, variable: int, sign: float) -> np.ndarray:
        if sign > 0:
            return self.frames[variable]
        if variable not in self._inverse:
            g = self.frames[variable]
            inverse = np.empty_like(g)
            inverse[:, :3] = np.swapaxes(g[:, :3], 0, 1)
            inverse[:, 3] = -rotate(inverse[:, :3], g[:, 3])
            self._inverse[variable] = inverse
        return self._inverse[variable]

    def gather(self, factors: Sequence[Factor | None]) -> np.ndarray:
        """The exponentials of ``G`` factors (``None``: the identity), side by side: ``(3, 4, G N)``."""
        if len(factors) == 1 and factors[0] is not None:
            return self.factor(factors[0].variable, factors[0].sign)
        parts = [_identity(self.count) if f is None else self.factor(f.variable, f.sign) for f in factors]
        return np.stack(parts, axis=2).reshape(3, 4, -1)


class Evaluation:
    """The loop residuals (and pose coordinates) of a stack of poses, with what their Jacobian needs kept.

    Attributes
    ----------
    values : ndarray, shape (m, N)
        The residual of each loop (6 numbers), then the pose coordinates asked
        for (0..5 for x, y, z, rx, ry, rz: the displacement of the
        :attr:`Kinematics.reference` point and the rotation vector, normalised
        coordinates).  Their Jacobian, per unit joint rate, right-trivialised
        for the loops (exact at a closed pose), comes from :meth:`jacobian`.
    """

    def __init__(self, kin: Kinematics, q: np.ndarray, components: np.ndarray | None) -> None:
        self._kin = kin
        exps = _Exponentials(kin, q.T)
        self._count = count = exps.count
        blocks: list[np.ndarray] = [np.zeros((6, count))] * kin.loop_count
        # loops of about one length side by side while the stack is small (fewer, larger array operations), else each alone
        plan = kin._loop_groups if count <= GROUPED_POSES else kin._loop_alone
        self._chains: list[tuple[_Chains, list[np.ndarray | None], tuple[np.ndarray, np.ndarray] | None]] = []  # the end effector's with its pose (p, r)
        for chains in plan:
            g, before = kin._chain(chains, exps)
            logs = twist_logs((g[:, :3], g[:, 3])).reshape(6, chains.size, count)
            for k, loop in enumerate(chains.loops):
                blocks[loop] = logs[:, k]
            self._chains.append((chains, before, None))
        self._components = None if components is None or not len(components) else np.asarray(components)
        if self._components is not None:
            g, before = kin._chain(kin._end_effector, exps)
            rot, shift = g[:, :3], g[:, 3]
            p = rotate(rot, kin.reference) + shift
            r = rotation_logs_last(rot)
            blocks.append(np.concatenate([p - kin.reference[:, None], r])[self._components])
            self._chains.append((kin._end_effector, before, (p, r)))
        self.values = np.concatenate(blocks) if blocks else np.zeros((0, count))

    def jacobian(self, rows: np.ndarray | None = None) -> np.ndarray:
        """The Jacobian ``(m, n, len(rows))`` of the chosen poses (all by default)."""
        kin = self._kin
        count = self._count if rows is None else len(rows)
        blocks: list[np.ndarray] = [np.zeros(0)] * kin.loop_count
        for chains, before, pose in self._chains:
            cols = kin._columns(chains, before, rows, count)
            if pose is None:
                for k, loop in enumerate(chains.loops):
                    blocks[loop] = cols[:, :, k]
                continue
            cols = cols[:, :, 0]
            p, r = pose if rows is None else (pose[0][:, rows], pose[1][:, rows])
            omega = cols[:3]
            dp = cols[3:] + cross(omega, p[:, None, :])  # point velocity v + w x p
            dr = inverse_left_jacobian_times(r, omega)
            blocks.append(np.concatenate([dp, dr])[self._components])
        if not blocks:
            return np.zeros((0, kin.variable_count, count))
        return np.concatenate(blocks)


GROUPED_POSES = 256
"""Stacks of at most this many poses evaluate loops of about one length side by side (:class:`Evaluation`); larger ones each loop alone."""


# ---------------------------------------------------------------------------
# Newton's method, on a stack of poses
# ---------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Equations:
    """What a Newton solve closes besides the loops, and the variables it moves.

    Attributes
    ----------
    free : ndarray of bool, shape (n,), optional
        The variables solved for (default: all); the others keep their
        starting values.
    components : ndarray of int
        Pose coordinates of the end effector fixed (0..5: x, y, z, rx, ry, rz,
        see :class:`Evaluation`), their values the first columns of the goals.
    linear : ndarray, shape (k, n) or (N, k, n), optional
        Extra linear equations ``A q = b``, ``b`` the last ``k`` columns of
        the goals: one ``A`` for every pose, or one per pose of the stack
        (moves along different directions solved at once).
    exact : bool
        The loops' Jacobian is their exact derivative (the right-trivialised
        one corrected by the inverse differential of the exponential at each
        loop's residual), not the right-trivialised one (exact at a closed
        pose, and cheaper).
    """

    free: np.ndarray | None = None
    components: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    linear: np.ndarray | None = None
    exact: bool = False

    def mask(self, n: int) -> np.ndarray:
        """The free variables as a mask of ``n``."""
        return np.ones(n, dtype=bool) if self.free is None else self.free

    def take(self, rows: np.ndarray) -> "Equations":
        """The equations of the poses ``rows`` of the stack (the same unless each pose has its own linear equations)."""
        return self if self.linear is None or self.linear.ndim == 2 else Equations(self.free, self.components, self.linear[rows], self.exact)

    def values(self, kin: Kinematics, q: np.ndarray, goals: np.ndarray) -> tuple[np.ndarray, Evaluation]:
        """Every equation's residual ``(m, N)`` at the poses ``q`` ``(N, n)`` and their ``goals``, and the evaluation that gives their Jacobian."""
        evaluation = kin.evaluate(q, self.components)
        values = evaluation.values
        fixed = len(self.components)
        if fixed:
            values[values.shape[0] - fixed :] -= goals[:, :fixed].T
        if self.linear is not None:
            lhs = self.linear @ q.T if self.linear.ndim == 2 else np.sum(self.linear * q[:, None, :], axis=2).T  # each pose's A q
            values = np.concatenate([values, lhs - goals[:, fixed:].T])
        return values, evaluation

    def jacobians(self, evaluation: Evaluation, rows: np.ndarray | None = None) -> np.ndarray:
        """The Jacobians of :meth:`values` (all poses, or ``rows``) over the free variables, stacked ``(N, m, free)``."""
        kin = evaluation._kin
        free = self.mask(kin.variable_count)
        jac = np.moveaxis(evaluation.jacobian(rows)[:, free], -1, 0)
        if self.exact and kin.loop_count:
            count, loops, width = len(jac), kin.loop_count, jac.shape[2]
            r = evaluation.values[: 6 * loops] if rows is None else evaluation.values[: 6 * loops, rows]
            derivative = dexps(np.asarray(r, dtype=float).T.reshape(-1, 6))  # (N L, 6, 6)
            jac[:, : 6 * loops] = np.linalg.solve(derivative, jac[:, : 6 * loops].reshape(-1, 6, width)).reshape(count, 6 * loops, width)
        if self.linear is not None:
            linear = self.linear[..., free]
            if linear.ndim == 2:
                linear = np.broadcast_to(linear, (len(jac),) + linear.shape)
            elif rows is not None:
                linear = linear[rows]
            jac = np.concatenate([jac, linear], axis=1)
        return np.ascontiguousarray(jac)


@dataclass(frozen=True, eq=False)
class Closures:
    """Outcome of :func:`newton` on a stack of poses.

    Attributes
    ----------
    q : ndarray, shape (N, n)
        The best iterate of each pose.
    residual : ndarray, shape (N,)
        Its largest residual component.
    converged : ndarray of bool, shape (N,)
        ``residual <= tol.closure``.
    history : ndarray, shape (N, steps + 1)
        The largest residual component before each step (NaN once a pose stopped).
    """

    q: np.ndarray
    residual: np.ndarray
    converged: np.ndarray
    history: np.ndarray


MAX_ITERATIONS = 12
"""Newton steps at most for one solve of a sweep."""

POLISHED = 0.1
"""A pose whose residual is below this fraction of ``Tolerance.closure`` needs no further step (a sweep's solves)."""

STALLED = 4
"""A pose of a sweep stops after this many steps in a row that did not halve its best residual."""

CLOSE_STALLED = 6
"""Steps in a row that do not halve the best residual before :meth:`Kinematics.close` gives up:
Newton from a start off every branch of a singular pose can lose ground for a few steps first."""

ROUND_OFF = float(np.finfo(float).eps)
"""A residual below this (the round-off of numbers of about one) has nothing left to gain (:meth:`Kinematics.close`)."""

LINEAR_RATIO = (0.15, 0.35)
"""Newton's residual shrinking by a ratio in this range at two steps running (about 1/4: the
error halves, the residual is quadratic in it) is the mark of a singular root."""


def newton(
    kin: Kinematics,
    start: np.ndarray,
    goals: np.ndarray,
    equations: Equations = Equations(),
    *,
    tol: Tolerance = DEFAULT_TOLERANCE,
    max_move: np.ndarray | float = np.inf,
    max_iter: int = MAX_ITERATIONS,
    polished: np.ndarray | float = POLISHED,
    accelerate: bool = False,
    patience: int = STALLED,
    closure: np.ndarray | None = None,
) -> Closures:
    """Close every loop of a stack of poses by Gauss–Newton with damped minimum-norm steps.

    The step ``J^T (J J^T + mu I)^-1 r`` (:func:`min_norm_steps`), ``mu`` far
    below every kept singular value, is the minimum-norm step even where
    ``J`` is rank-deficient (a change point, a planar loop's dependent rows)
    and lies in ``J``'s row space: round-off never drifts a pose along the
    motions the equations leave free.  A pose is done when its residual is
    below ``polished * tol.closure``, or closed and no longer halving, or
    after ``patience`` steps that did not halve it.

    Parameters
    ----------
    start : ndarray, shape (N, n)
        Starting joint variables (the variables not free keep them).
    goals : ndarray, shape (N, c + k)
        Values of the fixed pose coordinates, then right-hand sides of the
        linear equations (:class:`Equations`).
    tol : Tolerance
        ``tol.closure`` is the largest residual component of a closed pose.
    max_move : float or ndarray (N,)
        A solve that wanders farther than this from its start has failed (it
        would reach another assembly, not the nearby one).
    polished : float or ndarray (N,)
    accelerate : bool
        Double the step of a pose whose residual shrank by a ratio in
        :data:`LINEAR_RATIO` at the last two steps (Newton at a singular
        root): it removes the leading error term, the same poses in half the
        steps.
    patience : int
        Steps in a row that do not halve a pose's best residual before it stops.
    closure : ndarray (N,), optional
        The largest residual component of each closed pose, when the poses
        have their own (default ``tol.closure`` for every pose).
    """
    q0 = np.array(start, dtype=float)
    count = len(q0)
    q = q0.copy()
    best_q, best = q.copy(), np.full(count, np.inf)
    stalled = np.zeros(count, dtype=int)
    active = np.arange(count)
    max_move = np.broadcast_to(np.asarray(max_move, dtype=float), (count,))
    # the thresholds of "closed" and of "nothing left to gain": one for every pose, or each pose its own
    per_pose = closure is not None or np.ndim(polished) > 0
    closed = np.broadcast_to(np.asarray(tol.closure if closure is None else closure, dtype=float), (count if per_pose else 1,))
    enough = np.asarray(polished, dtype=float) * closed  # no step has anything left to gain below this
    own_rows = equations.linear is not None and equations.linear.ndim == 3
    free = equations.mask(kin.variable_count)
    movable = bool(free.any())
    history: list[np.ndarray] = []
    # A solve that diverges (a target far beyond the mechanism's size, or a pose with no assembly near it)
    # overflows: its iterates turn non-finite and are dropped (err = inf, the move refused), so numpy's
    # warnings would only repeat what the result says (not closed).
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        for iteration in range(max_iter + 1):
            if active.size == 0:
                break
            these = equations.take(active) if own_rows else equations
            r, evaluation = these.values(kin, q[active], goals[active])
            err = np.abs(r).max(axis=0) if r.shape[0] else np.zeros(active.size)
            err = np.where(np.isfinite(err), err, np.inf)
            history.append(np.full(count, np.nan))
            history[-1][active] = err
            better = err < best[active]
            halved = err < 0.5 * best[active]
            stalled[active] = np.where(halved, 0, stalled[active] + 1)
            best_q[active[better]] = q[active[better]]
            best[active[better]] = err[better]
            b, st = best[active], stalled[active]
            # done: near round-off, or closed and no longer gaining (a last step polishes a pose near a singularity)
            low, high = (enough[active], closed[active]) if per_pose else (enough[0], closed[0])
            done = (b <= low) | ((b <= high) & (st > 0))
            keep = np.flatnonzero(~done & (st < patience) & (iteration < max_iter) & movable & (r.shape[0] > 0))
            if keep.size == 0:
                break
            jac = these.jacobians(evaluation, keep)
            active, r = active[keep], r[:, keep]
            step = min_norm_steps(jac, r)  # in J's row space (the primal (J^T J + mu I)^-1 J^T r would drift by 1/mu)
            if accelerate and len(history) >= 3:
                before, last, now = (h[active] for h in history[-3:])
                low, high = LINEAR_RATIO
                # at a singular root Newton halves the error each step (the residual shrinks by about 1/4): the doubled step removes it
                step[(low <= last / before) & (last / before <= high) & (low <= now / last) & (now / last <= high)] *= 2.0
            moved = q[active].copy()
            moved[:, free] += step
            finite = np.all(np.isfinite(moved), axis=1) & (np.linalg.norm(moved - q0[active], axis=1) <= max_move[active])
            q[active[finite]] = moved[finite]
            active = active[finite]
    return Closures(best_q, best, best <= closed, np.array(history).T)


def min_norm_steps(j: np.ndarray, r: np.ndarray) -> np.ndarray:
    """The damped minimum-norm Newton steps ``-J^T (J J^T + mu I)^-1 r`` of stacked systems ``j`` ``(N, m, free)``, ``r`` ``(m, N)``."""
    equations = j.shape[1]
    gram = j @ j.swapaxes(1, 2)
    diagonal = gram.reshape(len(gram), -1)[:, :: equations + 1]
    diagonal += (NEWTON_DAMPING * diagonal.sum(axis=1) / equations + 1e-300)[:, None]
    return -(j.swapaxes(1, 2) @ np.linalg.solve(gram, np.ascontiguousarray(r.T)[:, :, None]))[:, :, 0]


POLISH_STEPS = 2
"""Newton steps of :func:`polish` (each from a residual in extended precision)."""

_EXTENDED = np.finfo(np.longdouble).eps < np.finfo(float).eps
"""Whether this platform's ``numpy.longdouble`` holds more digits than float64 (x86: 64-bit mantissa)."""


def polish(kin: Kinematics, q: np.ndarray, goals: np.ndarray, equations: Equations = Equations()) -> np.ndarray:
    """Closed poses ``q`` ``(N, n)`` (and their :func:`newton` ``goals``) refined by Newton steps whose residual is in extended precision.

    Near a singularity, with a smallest singular value ``s`` of the closure Jacobian, the round-off of a float64
    residual (1e-16) leaves the variables uncertain by ``1e-16 / s``, which the pose's screw systems amplify again by
    ``1 / s``: a parallelogram 0.01 degree from its change point (``s`` about 2e-4) shows its coupler tilted by 1e-12
    rad and a pure translation with a rotational part of 1e-8.  Residuals in ``numpy.longdouble`` (x86: three more
    digits) take that below the float64 rounding of the variables; the steps are solved in float64, one that does not
    lower the extended residual is not taken, and where ``longdouble`` is float64 nothing changes.  Returns float64
    poses, the variables not free unchanged.
    """
    free = equations.mask(kin.variable_count)
    if not _EXTENDED or len(q) == 0 or not free.any():
        return q
    exact, wanted = np.asarray(q, dtype=np.longdouble), np.asarray(goals, dtype=np.longdouble)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        r, evaluation = equations.values(kin, exact, wanted)
        if r.shape[0] == 0:
            return q
        err = np.abs(r).max(axis=0)
        for _ in range(POLISH_STEPS):
            j = equations.jacobians(evaluation).astype(float)  # the step in float64: the residual is what needs the digits
            trial = exact.copy()
            trial[:, free] += min_norm_steps(j, np.asarray(r, dtype=float))
            r_trial, evaluation = equations.values(kin, trial, wanted)
            err_trial = np.abs(r_trial).max(axis=0)
            better = np.isfinite(err_trial) & (err_trial < err)
            if not better.any():
                break
            exact[better], err[better] = trial[better], err_trial[better]
            r, evaluation = (r_trial, evaluation) if better.all() else equations.values(kin, exact, wanted)
    return exact.astype(float)


def kinematics(mechanism: Mechanism) -> Kinematics:
    """The product-of-exponentials model of ``mechanism`` at its pose (cached per mechanism)."""
    return per_object_cache(mechanism, "kinematics", lambda: _build(mechanism))


def _build(mechanism: Mechanism) -> Kinematics:
    screws = joint_screws(mechanism)
    norm, norm_reference = screws.normalisation, screws.reference
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
    # the model of the exponentials, from the twists: the axis, its point nearest the origin, the pitch
    w, v = twists[:3].T, twists[3:].T
    unit = np.where(is_p[:, None], v, w)
    nearest = np.where(is_p[:, None], 0.0, np.cross(w, v))
    k = skew(unit).reshape(-1, 3, 3)

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
    rows = np.vstack([twists.T, np.zeros((1, 6))])  # a padding factor's twist is zero

    def chains(indices: tuple[int, ...], members: list[tuple[Factor, ...]]) -> _Chains:
        length = max([len(c) for c in members] + [0])
        padded = [tuple(c) + (None,) * (length - len(c)) for c in members]
        variables = np.array([[n if f is None else f.variable for f in step] for step in zip(*padded)], dtype=int).reshape(length, len(members))
        signs = np.array([[0.0 if f is None else f.sign for f in step] for step in zip(*padded)]).reshape(length, len(members))
        return _Chains(indices, tuple(zip(*padded)), variables, (signs[..., None] * rows[variables]).transpose(2, 0, 1), len(members))

    # loops grouped by length within a factor of two (so padding at most doubles the work)
    by_length: dict[int, list[int]] = {}
    for row, loop in enumerate(loops):
        by_length.setdefault(max(len(loop), 1).bit_length(), []).append(row)
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
        reference=norm_reference,
        _steps=tuple((e.parent, e.child, paths[e.child][len(paths[e.parent]) :]) for e in tree_edges),
        _axes=unit,
        _pitches=np.where(np.array(kinds) == "H", np.einsum("ij,ij->i", w, v), 0.0),
        _prismatic=is_p,
        _k=k[..., None],
        _k2=(k @ k)[..., None],
        _kp=np.einsum("vij,vj->vi", k, nearest)[:, :, None],
        _k2p=np.einsum("vij,vj->vi", k @ k, nearest)[:, :, None],
        _loop_groups=tuple(chains(tuple(rows_), [loops[r] for r in rows_]) for rows_ in by_length.values()),
        _loop_alone=tuple(chains((row,), [loop]) for row, loop in enumerate(loops)),
        _end_effector=chains((), [paths[mechanism.end_effector]]),
    )
