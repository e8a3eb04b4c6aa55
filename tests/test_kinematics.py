"""Finite kinematics (mobility.core.kinematics, on the exponential map of mobility.core.transforms): forward kinematics, loop closure, re-closure.

Each piece is checked by a second route: scipy's matrix exponential for the
closed forms, finite differences for the Jacobians, the loop-closure route of
mobility.core.loop_closure for the equations at the given pose, and the rigid
invariants of every link (not the residual) for the closure of moved poses.
"""

from __future__ import annotations

import numpy as np
import pytest
from builders import six_ups, transformed
from scipy.linalg import expm
from test_finite import bennett, folded_parallelogram, puu4, rigidity_gap, tsai_3upu

from mobility.core.kinematics import kinematics
from mobility.core.poses import sample_poses
from mobility.core.loop_closure import loop_closure
from mobility.core.model import Joint, Mechanism
from mobility.core.tolerance import DEFAULT_TOLERANCE, Tolerance
from mobility.errors import RequestError
from mobility.core.transforms import Transform, bracket, dexp, displacement_log, rotation_from_axis_angle, twist_exp, twist_matrix


def mixed_joints() -> Mechanism:
    """Two limbs with every joint type (R P H C U S E) between a base and a platform, plus a tie link."""
    j = [
        Joint("C1", "C", ("base", "a1"), axis=(0, 0, 1), point=(1, 0, 0)),
        Joint("U1", "U", ("a1", "a2"), point=(1, 0, 1), axes=((1, 0, 0), (0, 1, 0))),
        Joint("S1", "S", ("a2", "platform"), point=(0.8, 0.1, 2)),
        Joint("H2", "H", ("base", "b1"), axis=(0, 0, 1), point=(-1, 0, 0), pitch=0.2),
        Joint("P2", "P", ("b1", "b2"), axis=(0.1, 0.2, 1)),
        Joint("E2", "E", ("b2", "b3"), normal=(0.2, 0.1, 1), point=(-1, 0, 1.2)),
        Joint("S2", "S", ("b3", "platform"), point=(-0.9, 0.1, 2)),
        Joint("R3", "R", ("base", "c1"), axis=(0, 1, 0), point=(0, -1, 0)),
        Joint("S3", "S", ("c1", "platform"), point=(0, -0.9, 2.1)),
    ]
    return Mechanism("mixed", "base", "platform", tuple(j))


MECHANISMS = {
    "bennett": bennett,
    "parallelogram": folded_parallelogram,
    "3-UPU": tsai_3upu,
    "4-PUU": puu4,
    "6-UPS": six_ups,
    "mixed": mixed_joints,
}


# ---------------------------------------------------------------------------
# closed forms of SE(3)
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("angle", [0.0, 1e-9, 1e-4, 0.3, 0.999, 1.001, 2.0, 3.05])
def test_exp_log_and_dexp_agree_with_scipy(angle):
    rng = np.random.default_rng(int(angle * 1000))
    w = rng.normal(size=3)
    x = np.concatenate([angle * w / np.linalg.norm(w), rng.normal(size=3)])
    assert np.allclose(twist_exp(x), expm(twist_matrix(x)), atol=1e-13)
    assert np.allclose(displacement_log(twist_exp(x)), x, atol=1e-12)
    block = np.zeros((12, 12))
    ad = np.zeros((6, 6))
    ad[:3, :3] = ad[3:, 3:] = twist_matrix(np.concatenate([x[:3], [0, 0, 0]]))[:3, :3]
    ad[3:, :3] = twist_matrix(np.concatenate([x[3:], [0, 0, 0]]))[:3, :3]
    block[:6, :6] = ad
    block[:6, 6:] = np.eye(6)
    assert np.allclose(dexp(x), expm(block)[:6, 6:], atol=1e-13)


def test_bracket_is_the_matrix_commutator():
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=6), rng.normal(size=6)
    comm = twist_matrix(a) @ twist_matrix(b) - twist_matrix(b) @ twist_matrix(a)
    assert np.allclose(twist_matrix(bracket(a, b)), comm, atol=1e-14)


# ---------------------------------------------------------------------------
# forward kinematics and the loop equations
# ---------------------------------------------------------------------------


def test_forward_kinematics_of_a_tree_joint_is_its_screw_motion():
    m = mixed_joints()
    kin = kinematics(m)
    q = np.zeros(kin.variable_count)
    cyl = kin.variables_of("C1")
    q[cyl] = (0.4, 0.3)  # turn 0.4 rad about the C axis and slide 0.3 L along it
    g = kin.link_displacements(q)["a1"]
    norm = kin.normalisation
    p = norm.point_from_world(np.array([2.0, 1.0, 0.5]))  # any point of link a1
    centre = norm.point_from_world(np.array([1.0, 0.0, 0.0]))
    rot = rotation_from_axis_angle(np.array([0.0, 0.0, 1.0]), 0.4)
    expected = centre + rot @ (p - centre) + np.array([0, 0, 0.3])
    assert np.allclose(g[:3, :3] @ p + g[:3, 3], expected, atol=1e-14)
    helical = kin.variables_of("H2")
    q[helical] = 1.0
    g = kin.link_displacements(q)["b1"]
    assert np.isclose(g[2, 3], 0.2 / norm.length, atol=1e-14)  # pitch 0.2 per radian, in units of L


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_jacobian_matches_finite_differences_of_the_residual(name):
    kin = kinematics(MECHANISMS[name]())
    rng = np.random.default_rng(1)
    n = kin.variable_count
    q = 0.2 * rng.normal(size=n)
    jac = kin.jacobian(q)
    h = 1e-6
    fd = np.column_stack([(kin.residual(q + h * e) - kin.residual(q - h * e)) / (2 * h) for e in np.eye(n)])
    assert jac.shape == (6 * kin.loop_count, n)
    assert np.abs(jac - fd).max() < 1e-8 * max(1.0, np.abs(jac).max())
    # the end effector's twist map against finite differences of its displacement
    ee = kin.mechanism.end_effector
    g0 = kin.link_displacements(q)[ee]
    fd_ee = np.column_stack([displacement_log(kin.link_displacements(q + h * e)[ee] @ np.linalg.inv(g0)) / h for e in np.eye(n)])
    assert np.abs(kin.end_effector_jacobian(q) - fd_ee).max() < 1e-5


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_loop_equations_at_the_pose_are_those_of_the_loop_closure_route(name):
    m = MECHANISMS[name]()
    kin = kinematics(m)
    zero = np.zeros(kin.variable_count)
    assert np.abs(kin.residual(zero)).max() == 0.0
    lc = loop_closure(m)
    # same spanning tree and chords; unit-twist columns there, unit-angle variables here; opposite sign
    norms = np.linalg.norm(kin.twists, axis=0)
    assert np.allclose(kin.jacobian(zero), -lc.jacobian * norms, atol=1e-12)
    decision, null = kin.rank_decision(zero)
    assert null.shape[1] == lc.mobility
    assert np.abs(kin.jacobian(zero) @ null).max() < 1e-12


def test_second_order_forms_match_the_residual_along_a_line():
    kin = kinematics(tsai_3upu())
    n = kin.variable_count
    d = np.random.default_rng(5).normal(size=n)
    t = 1e-3
    second = (kin.residual(t * d) + kin.residual(-t * d)) / (2 * t * t)  # = B(d, d) / 2 + O(t^2)
    forms = kin.second_order_forms(np.eye(6 * kin.loop_count))
    assert np.allclose(np.einsum("i,cij,j->c", d, forms, d) / 2.0, second, atol=1e-5)


# ---------------------------------------------------------------------------
# re-closure and moved poses
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["bennett", "3-UPU", "6-UPS", "mixed"])
def test_newton_recloses_quadratically_and_the_moved_pose_is_rigid(name):
    m = MECHANISMS[name]()
    kin = kinematics(m)
    rng = np.random.default_rng(2)
    tangent = kin.tangent_space(np.zeros(kin.variable_count))
    guess = 0.05 * tangent @ rng.normal(size=tangent.shape[1]) + 1e-3 * rng.normal(size=kin.variable_count)
    closure = kin.close(guess)
    assert closure.converged and closure.residual < 1e-14
    assert closure.iterations <= 8
    history = np.array(closure.history)
    big = history[history > 1e-10]
    assert len(big) >= 2 and big[-1] < big[-2] ** 1.5 * 10  # superlinear
    moved = kin.mechanism_at(closure.q)
    assert rigidity_gap(m, moved) < 1e-12
    # the unclosed guess is not rigid: the invariants do see an open loop
    assert rigidity_gap(m, kin.mechanism_at(guess)) > 1e-6
    # names, links and flags are kept; geometry is in the global frame
    assert [(j.name, j.type, j.links, j.actuated) for j in moved.joints] == [(j.name, j.type, j.links, j.actuated) for j in m.joints]
    assert all(j.frame == "world" for j in moved.joints) and moved.expected is None


def test_close_reports_failure_instead_of_raising():
    kin = kinematics(folded_parallelogram())
    # turning the crank while the other three joints are held: impossible
    closure = kin.close(np.array([0.1, 0, 0, 0]), constraints=(np.eye(4), np.array([0.1, 0, 0, 0])))
    assert not closure.converged and closure.residual > 1e-3
    assert closure.iterations < 40  # it gives up when Newton stops gaining


def test_close_each_takes_each_pose_the_steps_it_takes_alone():
    # one Newton on a stack of starts, each with its own linear equation, threshold and largest move
    kin = kinematics(MECHANISMS["6-UPS"]())
    n = kin.variable_count
    rng = np.random.default_rng(4)
    tangent = kin.tangent_space(np.zeros(n))
    directions = tangent @ rng.normal(size=(tangent.shape[1], 5))
    directions = (directions / np.linalg.norm(directions, axis=0)).T
    directions[4] = np.eye(n)[0]  # along one joint alone: it does not close (the loops hold it) within the small move
    steps = np.array([1e-3, 1e-2, 5e-2, 2e-2, 1e-2])
    closure, moves = np.array([1e-12, 1e-14, 1e-13, 1e-30, 1e-12]), np.array([1.0, 1.0, 1.0, 1.0, 1e-3])
    starts = steps[:, None] * directions + 1e-4 * rng.normal(size=(5, n))
    together = kin.close_each(starts, constraints=(directions[:, None, :], steps[:, None]), closure=closure, max_move=moves)
    assert len(together) == 5
    for k, c in enumerate(together):
        alone = kin.close(starts[k], constraints=(directions[k][None, :], steps[k:k + 1]), tol=Tolerance(closure=closure[k]), max_move=moves[k])
        assert (c.converged, c.iterations) == (alone.converged, alone.iterations)
        assert np.abs(c.q - alone.q).max() < 1e-12 and abs(c.residual - alone.residual) < 1e-15
        assert len(c.history) == c.iterations + 1
    assert [c.converged for c in together] == [True, True, True, False, False]  # 1e-30: beyond floating point
    assert abs(float(directions[2] @ together[2].q) - 5e-2) < 1e-14  # the pose's own linear equation holds


def test_closure_threshold_is_the_policy_s():
    kin = kinematics(MECHANISMS["bennett"]())
    guess = 0.05 * kin.tangent_space(np.zeros(kin.variable_count))[:, 0]
    strict = kin.close(guess)
    assert strict.converged and strict.residual <= DEFAULT_TOLERANCE.closure
    # "closed" means below the policy's closure threshold, whatever it is
    verdicts = {}
    for closure in (1e-4, 1e-12, 1e-17, 1e-30):
        c = kin.close(guess, tol=Tolerance(closure=closure))
        assert c.converged == (c.residual <= closure)
        verdicts[closure] = c.converged
    assert verdicts[1e-4] and verdicts[1e-12] and not verdicts[1e-30]  # floating point never reaches 1e-30


def test_bad_arguments_are_request_errors():
    kin = kinematics(MECHANISMS["bennett"]())
    with pytest.raises(RequestError, match="expected 4 joint variables, got 3"):
        kin.residual(np.zeros(3))
    with pytest.raises(RequestError, match="joint: expected a joint name"):
        kin.variables_of("no such joint")
    assert kin.variables_of(kin.mechanism.joints[2].name) == kin.variables_of(2) == slice(2, 3)
    with pytest.raises(RequestError, match="count"):
        sample_poses(kin.mechanism, -1)
    with pytest.raises(RequestError, match="step"):
        sample_poses(kin.mechanism, 2, step=0.0)


def _rigid_motion(seed=4):
    rng = np.random.default_rng(seed)
    axis = rng.normal(size=3)
    return Transform(rotation_from_axis_angle(axis / np.linalg.norm(axis), 1.3), rng.normal(size=3) * 20)


@pytest.mark.parametrize("name", ["bennett", "3-UPU", "4-PUU", "mixed"])
def test_kinematics_is_invariant_to_scale_and_rigid_motion(name):
    m = MECHANISMS[name]()
    tf = _rigid_motion()
    kin = kinematics(m)
    q = 0.1 * np.random.default_rng(3).normal(size=kin.variable_count)
    cases = [(transformed(m, Transform.identity(), 1000.0), 1000.0, np.eye(3))]
    if name != "mixed":
        # S joints turn about the global x, y, z and E joints slide along in-plane axes chosen from
        # the global frame: their variables mean other motions after a rotation, so only the scaling
        # is compared for them (finite_mobility does not depend on that choice; see test_finite)
        cases.append((transformed(m, tf), 1.0, tf.rotation))
    for other, scale, rot in cases:
        k2 = kinematics(other)
        r1, r2 = kin.residual(q), k2.residual(q)
        # normalised coordinates follow the mechanism: the residual only turns with the frame
        assert np.allclose(r2.reshape(-1, 2, 3), np.einsum("ij,lsj->lsi", rot, r1.reshape(-1, 2, 3)), atol=1e-12)
        j1, j2 = kin.jacobian(q), k2.jacobian(q)
        assert np.allclose(j1.T @ j1, j2.T @ j2, atol=1e-10)
        # the moved mechanism is the moved copy of the moved mechanism
        a = kin.mechanism_at(q)
        b = k2.mechanism_at(q)
        for ja, jb in zip(a.world_joints, b.world_joints):
            if ja.point is not None:
                expected = scale * np.asarray(ja.point) if scale != 1.0 else tf.apply_point(ja.point)
                assert np.allclose(jb.point, expected, atol=1e-9 * scale)


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_one_pose_is_a_stack_of_one(name):
    # Kinematics takes one pose (n,) or a stack (N, n): a pose's numbers are the same bits alone or in a stack
    kin = kinematics(MECHANISMS[name]())
    q = 0.3 * np.random.default_rng(7).normal(size=(5, kin.variable_count))
    for method in ("residual", "jacobian", "loop_jacobian", "end_effector_jacobian"):
        stacked = getattr(kin, method)(q)
        assert stacked.shape[0] == 5
        for i, x in enumerate(q):
            assert np.array_equal(stacked[i], getattr(kin, method)(x)), method
    links = kin.link_displacements(q)
    for i, x in enumerate(q):
        assert all(np.array_equal(links[link][i], g) for link, g in kin.link_displacements(x).items())
    with pytest.raises(RequestError, match=rf"expected joint variables of shape \(N, {kin.variable_count}\)"):
        kin.residual(np.zeros((2, kin.variable_count + 1)))
