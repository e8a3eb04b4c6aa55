"""Finite screws: the quasi-vector, the triangle product, half-turns, Eq. 5 and limbs (Eq. 7).

Every check compares with an independent route: 4x4 matrix products, the
exponential of the twist matrix (scipy.linalg.expm) and finite differences.
"""

import math

import numpy as np
import pytest

from mobility.errors import HalfTurnError, MechanismError, RequestError
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.linalg import expm

from mobility.core.finite_screws import (
    FiniteScrew,
    Limb,
    ScrewJoint,
    finite_screw,
    finite_screw_from_transform,
    transform_from_finite_screw,
    triangle_product,
    twist_from_finite_screw_rate,
)
from mobility.core.screws import prismatic_twist, revolute_twist
from mobility.core.tolerance import Tolerance
from mobility.core.transforms import rotation_from_axis_angle, skew

FAST = settings(max_examples=40, deadline=None)

coord = st.floats(-3.0, 3.0, allow_nan=False)
vec3 = st.tuples(coord, coord, coord).map(np.array)
direction = vec3.filter(lambda v: np.linalg.norm(v) > 0.1)
angle = st.floats(-3.0, 3.0, allow_nan=False)  # |θ| < π: a finite quasi-vector
slide = st.floats(-2.0, 2.0, allow_nan=False)


def matrix_of(axis, point, theta, t=0.0):
    """Screw displacement as a matrix, by Rodrigues (independent of the finite-screw code)."""
    s = np.asarray(axis, float) / np.linalg.norm(axis)
    rot = rotation_from_axis_angle(s, theta)
    out = np.eye(4)
    out[:3, :3] = rot
    out[:3, 3] = (np.eye(3) - rot) @ np.asarray(point, float) + t * s
    return out


def twist_of(matrix_rate, matrix):
    """Spatial twist [w; v] from dT/dt and T."""
    x = matrix_rate @ np.linalg.inv(matrix)
    return np.concatenate([[x[2, 1], x[0, 2], x[1, 0]], x[:3, 3]])


def hat(twist):
    m = np.zeros((4, 4))
    m[:3, :3] = skew(twist[:3])
    m[:3, 3] = twist[3:]
    return m


# -- the quasi-vector and its matrix ---------------------------------------------------


@FAST
@given(direction, vec3, angle, slide)
def test_finite_screw_is_the_papers_formula_and_its_matrix_the_displacement(axis, point, theta, t):
    s = axis / np.linalg.norm(axis)
    expected = 2 * math.tan(theta / 2) * np.concatenate([s, np.cross(point, s)]) + t * np.concatenate([np.zeros(3), s])
    got = finite_screw(axis, point, theta, t)
    assert np.allclose(got, expected, atol=1e-9 * (1 + np.abs(expected).max()))
    assert np.allclose(transform_from_finite_screw(got), matrix_of(axis, point, theta, t), atol=1e-9)
    assert np.allclose(FiniteScrew.from_parameters(axis, point, theta, t).transform(), matrix_of(axis, point, theta, t), atol=1e-9)


@FAST
@given(direction, vec3, angle, slide)
def test_transform_round_trip_and_screw_parameters(axis, point, theta, t):
    m = matrix_of(axis, point, theta, t)
    s = finite_screw_from_transform(m)
    assert np.allclose(transform_from_finite_screw(s), m, atol=1e-9)
    a, p, th, tt = FiniteScrew.from_transform(m).parameters()
    assert np.allclose(matrix_of(a, p, th, tt), m, atol=1e-8)
    assert 0.0 <= th <= math.pi + 1e-12
    assert abs(float(np.asarray(p) @ a)) < 1e-8 * (1 + np.linalg.norm(point) + abs(t))  # nearest the origin


# -- the triangle product -----------------------------------------------------------------


@FAST
@given(direction, vec3, angle, slide, direction, vec3, angle, slide)
def test_triangle_product_is_b_then_a_as_the_matrix_product(a1, p1, th1, t1, a2, p2, th2, t2):
    ta, tb = matrix_of(a1, p1, th1, t1), matrix_of(a2, p2, th2, t2)
    sa, sb = finite_screw(a1, p1, th1, t1), finite_screw(a2, p2, th2, t2)
    both = FiniteScrew.from_transform(ta @ tb)
    if both.is_half_turn or abs(both.homogeneous[0]) < 1e-3:  # the product is (nearly) a half-turn: no usable quasi-vector
        return
    got = triangle_product(sa, sb)
    assert np.allclose(transform_from_finite_screw(got), ta @ tb, atol=1e-7)
    assert np.allclose(got, finite_screw_from_transform(ta @ tb), rtol=1e-7, atol=1e-7)
    # the homogeneous form composes the same way
    assert FiniteScrew.from_vector(sa).triangle(FiniteScrew.from_vector(sb)).isclose(both, tol=Tolerance(rank=1e-9))


@FAST
@given(direction, vec3, angle, slide, direction, vec3, angle, slide)
def test_the_papers_eq_3_written_a_then_b_is_our_product_in_the_other_order(a1, p1, th1, t1, a2, p2, th2, t2):
    """Paper 000, Eq. 3, coded as printed: (Sa + Sb + ½ Sb × Sa - tan(θa/2) tan(θb/2) (tb [0; sa] + ta [0; sb])) / (1 - tan tan sa·sb)."""
    sa_, sb_ = np.asarray(a1) / np.linalg.norm(a1), np.asarray(a2) / np.linalg.norm(a2)
    ka, kb = math.tan(th1 / 2), math.tan(th2 / 2)
    denominator = 1.0 - ka * kb * float(sa_ @ sb_)
    if abs(denominator) < 1e-3:  # (nearly) a half-turn: no usable quasi-vector
        return
    sa, sb = finite_screw(a1, p1, th1, t1), finite_screw(a2, p2, th2, t2)
    lie = np.concatenate([np.cross(sb[:3], sa[:3]), np.cross(sb[:3], sa[3:]) + np.cross(sb[3:], sa[:3])])  # Sb × Sa
    paper = (sa + sb + 0.5 * lie - ka * kb * (t2 * np.concatenate([np.zeros(3), sa_]) + t1 * np.concatenate([np.zeros(3), sb_]))) / denominator
    assert np.allclose(triangle_product(sb, sa), paper, rtol=1e-7, atol=1e-7 * (1 + np.abs(paper).max()))


@FAST
@given(direction, vec3, angle, slide)
def test_inverse_is_the_negative(axis, point, theta, t):
    s = finite_screw(axis, point, theta, t)
    assert np.allclose(triangle_product(s, -s), 0.0, atol=1e-9 * (1 + np.abs(s).max() ** 2))
    assert np.allclose(FiniteScrew.from_vector(s).inverse().transform(), np.linalg.inv(matrix_of(axis, point, theta, t)), atol=1e-8)


@FAST
@given(vec3, vec3, vec3)
def test_pure_translations_add(u, v, w):
    su, sv, sw = (np.concatenate([np.zeros(3), x]) for x in (u, v, w))
    got = triangle_product(su, sv, sw)
    assert np.allclose(got, su + sv + sw)
    assert np.allclose(transform_from_finite_screw(got)[:3, 3], u + v + w)


def test_order_convention_is_pinned():
    """A quarter turn about z then a slide along x, versus the other order."""
    turn = finite_screw([0, 0, 1], [0, 0, 0], math.pi / 2)
    move = finite_screw([1, 0, 0], [0, 0, 0], 0.0, 1.0)
    # move first, then turn: the point ends up on +y
    assert np.allclose(transform_from_finite_screw(triangle_product(turn, move)) @ [0, 0, 0, 1], [0, 1, 0, 1])
    # turn first, then move: the point ends up on +x
    assert np.allclose(transform_from_finite_screw(triangle_product(move, turn)) @ [0, 0, 0, 1], [1, 0, 0, 1])


# -- half-turns ---------------------------------------------------------------------------


@FAST
@given(direction, vec3, slide, direction, vec3, angle, slide)
def test_half_turns_compose_exactly_in_homogeneous_form(a1, p1, t1, a2, p2, th2, t2):
    half = FiniteScrew.from_parameters(a1, p1, math.pi, t1)
    other = FiniteScrew.from_parameters(a2, p2, th2, t2)
    assert half.is_half_turn
    assert np.allclose(half.transform(), matrix_of(a1, p1, math.pi, t1), atol=1e-9)
    assert np.allclose(half.triangle(other).transform(), matrix_of(a1, p1, math.pi, t1) @ matrix_of(a2, p2, th2, t2), atol=1e-8)
    assert np.allclose(other.triangle(half).transform(), matrix_of(a2, p2, th2, t2) @ matrix_of(a1, p1, math.pi, t1), atol=1e-8)
    with pytest.raises(HalfTurnError):
        half.vector
    # the finite direction is the half-turn's line 2 [s; r x s], whatever the slide (t cos(θ/2) = 0)
    s = a1 / np.linalg.norm(a1)
    line = 2 * np.concatenate([s, np.cross(p1, s)])
    assert np.allclose(half.direction, line, atol=1e-9) or np.allclose(half.direction, -line, atol=1e-9)


def test_half_turn_line_and_parameters():
    half = FiniteScrew.from_parameters([0, 0, 2], [1, 2, 5], math.pi, 0.75)
    assert np.allclose(np.abs(half.direction), 2 * np.abs(np.concatenate([[0, 0, 1], np.cross([1, 2, 5], [0, 0, 1])])))
    a, p, th, t = half.parameters()
    assert math.isclose(th, math.pi) and np.allclose(np.abs(a), [0, 0, 1])
    assert np.allclose(p, [1, 2, 0]) and math.isclose(abs(t), 0.75)


def test_two_quarter_turns_make_a_half_turn():
    quarter = finite_screw([0, 0, 1], [1, 0, 0], math.pi / 2)
    with pytest.raises(HalfTurnError):
        triangle_product(quarter, quarter)  # 1 - w.w/4 = 0
    q = FiniteScrew.from_vector(quarter)
    assert np.allclose(q.triangle(q).transform(), matrix_of([0, 0, 1], [1, 0, 0], math.pi), atol=1e-12)
    # and a third quarter turn brings the quasi-vector back (θ = 3π/2 ≡ -π/2)
    assert np.allclose(q.triangle(q).triangle(q).vector, finite_screw([0, 0, 1], [1, 0, 0], -math.pi / 2))


def test_half_turn_matrix_has_no_quasi_vector():
    with pytest.raises(HalfTurnError):
        finite_screw_from_transform(matrix_of([1, 1, 0], [0, 0, 3], math.pi, 0.2))
    with pytest.raises(HalfTurnError):
        finite_screw([0, 1, 0], [0, 0, 0], -math.pi)


# -- Eq. 5: the derivative at the identity is the twist ---------------------------------


@FAST
@given(direction, vec3, st.floats(-2, 2), st.floats(-2, 2))
def test_derivative_at_identity_is_the_instantaneous_twist(axis, point, rate, slide_rate):
    h = 1e-6
    d = (finite_screw(axis, point, rate * h, slide_rate * h) - finite_screw(axis, point, -rate * h, -slide_rate * h)) / (2 * h)
    s = axis / np.linalg.norm(axis)
    twist = rate * revolute_twist(s, point) + slide_rate * prismatic_twist(s)  # the project's instantaneous convention
    assert np.allclose(d, twist, atol=1e-6 * (1 + np.abs(twist).max()))
    assert np.allclose(twist_from_finite_screw_rate(np.zeros(6), d), d)


@FAST
@given(direction, vec3, angle, slide, vec3, vec3)
def test_derivative_mapping_anywhere_gives_the_spatial_twist(axis, point, theta, t, dw, dv):
    s = finite_screw(axis, point, theta, t)
    ds = np.concatenate([dw, dv])
    h = 1e-6 / (1 + np.abs(s).max())
    rate = (transform_from_finite_screw(s + h * ds) - transform_from_finite_screw(s - h * ds)) / (2 * h)
    expected = twist_of(rate, transform_from_finite_screw(s))
    assert np.allclose(twist_from_finite_screw_rate(s, ds), expected, atol=1e-5 * (1 + np.abs(expected).max()))


# -- limbs (Eq. 7) ------------------------------------------------------------------------


def random_limb(rng, kinds="RPRHRP"):
    return Limb(tuple(ScrewJoint(k, rng.normal(size=3), rng.normal(size=3), pitch=0.3) for k in kinds))


def product_of_exponentials(limb, q):
    out = np.eye(4)
    for joint, x in zip(limb.joints, q):
        out = out @ expm(hat(joint.twist()) * x)
    return out


@pytest.mark.parametrize("seed", range(5))
def test_limb_finite_screw_is_the_product_of_exponentials_base_first(seed):
    rng = np.random.default_rng(seed)
    limb = random_limb(rng)
    q = rng.uniform(-3, 3, len(limb))
    assert np.allclose(limb.transform(q), product_of_exponentials(limb, q), atol=1e-9)
    # and the quasi-vector is the triangle product of the joints' quasi-vectors, base joint on the left
    assert np.allclose(limb.finite_screw(q).vector, triangle_product(*[f.vector for f in limb.factors(q)]), rtol=1e-9, atol=1e-9)
    reversed_order = triangle_product(*[f.vector for f in reversed(limb.factors(q))])
    assert not np.allclose(limb.finite_screw(q).vector, reversed_order, atol=1e-3)


@pytest.mark.parametrize("seed", range(5))
def test_limb_twists_are_derivatives_of_its_finite_screw(seed):
    rng = np.random.default_rng(10 + seed)
    limb = random_limb(rng)
    q = rng.uniform(-3, 3, len(limb))
    twists = limb.twists(q)
    rates = limb.finite_screw_rates(q)
    s = limb.finite_screw(q).vector
    h = 1e-6
    for j in range(len(limb)):
        e = np.zeros(len(limb))
        e[j] = h
        fd_rate = (limb.finite_screw(q + e).vector - limb.finite_screw(q - e).vector) / (2 * h)
        assert np.allclose(rates[:, j], fd_rate, rtol=1e-5, atol=1e-5 * (1 + np.abs(fd_rate).max()))
        fd_twist = twist_of((limb.transform(q + e) - limb.transform(q - e)) / (2 * h), limb.transform(q))
        assert np.allclose(twists[:, j], fd_twist, atol=1e-6 * (1 + np.abs(fd_twist).max()))
        assert np.allclose(twists[:, j], twist_from_finite_screw_rate(s, rates[:, j]), atol=1e-9)


def test_limb_twists_at_a_half_turn():
    limb = Limb((ScrewJoint("P", (1, 0, 0)), ScrewJoint("R", (0, 0, 1), (1, 2, 0)), ScrewJoint("R", (0, 1, 0), (0, 0, 1))))
    q = np.array([0.5, math.pi, 0.0])
    assert limb.finite_screw(q).is_half_turn
    with pytest.raises(HalfTurnError):
        limb.finite_screw_rates(q)
    t = limb.twists(q)
    assert np.allclose(t[:, 1], revolute_twist([0, 0, 1], [1.5, 2, 0]))  # the R carried by the slide
    moved_axis = rotation_from_axis_angle(np.array([0.0, 0, 1]), math.pi) @ [0, 1, 0]
    moved_point = matrix_of([0, 0, 1], [1.5, 2, 0], math.pi) @ [0.5, 0, 1, 1]
    assert np.allclose(t[:, 2], revolute_twist(moved_axis, moved_point[:3]))


def test_moved_limb_has_the_twists_of_the_pose_at_its_home():
    rng = np.random.default_rng(3)
    limb = random_limb(rng, "RRPRR")
    q = rng.uniform(-2, 2, len(limb))
    assert np.allclose(limb.moved(q).twists(), limb.twists(q), atol=1e-9)


# -- bad arguments and descriptions, thresholds from the policy -----------------------------


def test_bad_arguments_raise_request_errors_and_bad_joints_mechanism_errors():
    with pytest.raises(RequestError):
        finite_screw([0, 0, 0], [0, 0, 0], 1.0)  # no direction
    with pytest.raises(RequestError):
        triangle_product([1.0, 2.0, 3.0])  # not a 6-vector
    with pytest.raises(RequestError):
        transform_from_finite_screw(np.zeros(5))
    with pytest.raises(RequestError):
        FiniteScrew(np.zeros(8))
    with pytest.raises(RequestError):
        FiniteScrew.from_transform(np.diag([1.0, 1.0, -1.0, 1.0]))  # a reflection
    with pytest.raises(RequestError):
        Limb((ScrewJoint("R", (0, 0, 1)),)).transform([0.1, 0.2])  # two values for one joint
    with pytest.raises(MechanismError) as bad_kind:
        ScrewJoint("X", (0, 0, 1))
    assert bad_kind.value.key == "kind"
    with pytest.raises(MechanismError) as bad_axis:
        ScrewJoint("R", (0, 0))
    assert bad_axis.value.key == "axis"
    with pytest.raises(MechanismError):
        Limb(("R",))


def test_a_matrix_is_a_rotation_to_the_rank_tolerance():
    m = matrix_of([1, 2, 3], [0.5, 0, 1], 0.7)
    nearly = m.copy()
    nearly[0, 0] += 1e-12  # round-off: read as the displacement
    assert FiniteScrew.from_transform(nearly).isclose(FiniteScrew.from_transform(m))
    sloppy = m.copy()
    sloppy[0, 0] += 1e-6  # not a rotation by the default policy, one by a looser one
    with pytest.raises(RequestError):
        FiniteScrew.from_transform(sloppy)
    loose = Tolerance(rank=5e-6, near_singular=1e-4)
    assert FiniteScrew.from_transform(sloppy, loose).isclose(FiniteScrew.from_transform(m), tol=loose)


def test_isclose_compares_lengths_over_a_length():
    a = FiniteScrew.from_parameters([0, 0, 1], [1000.0, 0, 0], 0.5)
    b = FiniteScrew.from_parameters([0, 0, 1], [1000.0 + 1e-7, 0, 0], 0.5)  # 1e-7 mm off, on a 1000 mm part
    assert not a.isclose(b)  # in the unit of the numbers: 2.5e-8 apart
    assert a.isclose(b, length=1000.0)
    assert a.isclose(FiniteScrew(-a.homogeneous))  # the sign of a dual quaternion is no displacement


def test_an_axis_of_any_finite_size_is_a_direction():
    # the squared norm of (1e308, 1e308, 0) overflowed: the axis was taken for a zero vector and refused
    assert np.allclose(finite_screw((1e308, 1e308, 0), (0, 0, 0), 0.5), finite_screw((1, 1, 0), (0, 0, 0), 0.5), atol=1e-15)
    assert np.allclose(finite_screw((5e-324, 0, 0), (0, 0, 0), 0.5), finite_screw((1, 0, 0), (0, 0, 0), 0.5), atol=1e-15)
