"""The screw layer: conventions pinned, span, reciprocal, intersection, adjoint."""

import numpy as np
import pytest
from builders import random_rotation

from mobility.core.screws import (
    SWAP,
    SWAP_ROWS,
    adjoint,
    free_vector_subspace,
    helical_twist,
    intersection,
    prismatic_twist,
    reciprocal_product,
    reciprocal_system,
    revolute_twist,
    same_subspace,
    span_and_reciprocal,
)
from mobility.core.transforms import rotation_from_rpy, skew


def test_twist_convention_angular_part_first():
    # rotation about z through (1, 0, 0): the origin moves with v = p x w = (0, -1, 0)
    assert revolute_twist([0, 0, 1], [1, 0, 0]).tolist() == [0, 0, 1, 0, -1, 0]
    assert prismatic_twist([0, 1, 0]).tolist() == [0, 0, 0, 0, 1, 0]
    assert helical_twist([0, 0, 1], [0, 0, 0], 0.25).tolist() == [0, 0, 1, 0, 0, 0.25]


def test_reciprocal_product_is_power_of_wrench_on_twist():
    rng = np.random.default_rng(0)
    # a force f through point p on a body moving with twist (w, v at origin): power = f . (v + w x p)
    f, p, w, v = rng.normal(size=(4, 3))
    wrench = np.concatenate([f, np.cross(p, f)])
    twist = np.concatenate([w, v])
    assert reciprocal_product(wrench, twist) == pytest.approx(f @ (v + np.cross(w, p)))
    assert reciprocal_product(wrench, twist) == pytest.approx(wrench @ SWAP @ twist)
    assert np.array_equal(SWAP @ twist, twist[SWAP_ROWS])


def test_force_through_axis_is_reciprocal_to_rotation():
    rot = revolute_twist([0, 0, 1], [1, 2, 0])
    force_meeting = np.concatenate([[1.0, 0, 0], np.cross([1, 2, 5], [1.0, 0, 0])])  # line through (1,2,5), meets the axis
    force_skew = np.concatenate([[1.0, 0, 0], np.cross([0, 0, 0], [1.0, 0, 0])])  # line along x through origin: misses it
    assert reciprocal_product(force_meeting, rot) == pytest.approx(0.0)
    assert reciprocal_product(force_skew, rot) != pytest.approx(0.0)


def test_adjoint_same_matrix_for_twists_and_wrenches_keeps_reciprocity():
    rng = np.random.default_rng(1)
    for _ in range(20):
        R = random_rotation(rng)
        t = rng.normal(size=3)
        ad = adjoint(R, t)
        a, b = rng.normal(size=(2, 6))
        assert reciprocal_product(ad @ a, ad @ b) == pytest.approx(reciprocal_product(a, b))
        # a revolute twist moved by the adjoint is the revolute twist of the moved axis
        s = rng.normal(size=3)
        s /= np.linalg.norm(s)
        p = rng.normal(size=3)
        assert np.allclose(ad @ revolute_twist(s, p), revolute_twist(R @ s, R @ p + t))
    assert np.allclose(adjoint(np.eye(3), [1, 2, 3])[3:, :3], skew([1, 2, 3]))


def test_span_and_reciprocal_dimensions_and_orthogonality():
    planar = np.stack([prismatic_twist([1, 0, 0]), prismatic_twist([0, 1, 0]), revolute_twist([0, 0, 1], [3, 4, 0]), revolute_twist([0, 0, 1], [-1, 2, 0])], axis=1)
    sp = span_and_reciprocal(planar)
    assert sp.dim == 3
    assert sp.reciprocal.shape == (6, 3)
    assert np.allclose(sp.basis.T @ sp.basis, np.eye(3))
    assert np.allclose(reciprocal_product(sp.reciprocal[:, :, None], planar[:, None, :]), 0.0)
    # the reciprocal of a planar motion: two couples about x and y, one force along z
    expected = np.stack([[0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 1, 0, 0, 0]], axis=1).astype(float)
    assert same_subspace(sp.reciprocal, expected)


def test_empty_and_full_systems():
    assert span_and_reciprocal(np.zeros((6, 0))).reciprocal.shape == (6, 6)
    assert reciprocal_system(np.eye(6)).shape == (6, 0)


def test_intersection_of_two_cylindrical_pairs_is_their_common_axis():
    c1 = np.stack([revolute_twist([0, 0, 1], [0, 0, 0]), prismatic_twist([0, 0, 1]), prismatic_twist([1, 0, 0])], axis=1)
    c2 = np.stack([revolute_twist([0, 0, 1], [0, 0, 0]), prismatic_twist([0, 0, 1]), prismatic_twist([0, 1, 0])], axis=1)
    common = intersection(c1, c2)
    assert common.shape[1] == 2
    assert same_subspace(common, c1[:, :2])


def test_same_subspace_compares_subspaces_not_bases():
    a = np.array([[1.0, 0], [0, 1], [0, 0]])
    assert same_subspace(a, a @ np.array([[2.0, 1], [1, 1]]))
    assert not same_subspace(a, np.array([[1.0], [0], [0]]))
    assert not same_subspace(a, np.array([[1.0, 0], [0, 0], [0, 1]]))


def test_free_vector_subspace_splits_translations():
    # cylindrical pair about z through (1, 0, 0) plus a translation along x
    sys = np.stack([revolute_twist([0, 0, 1], [1, 0, 0]), prismatic_twist([0, 0, 1]), prismatic_twist([1, 0, 0])], axis=1)
    basis = span_and_reciprocal(sys).basis
    free, coef, decision = free_vector_subspace(basis)
    assert free.shape == (3, 2) and coef.shape == (3, 1) and decision.rank == 1
    assert same_subspace(free, np.array([[0, 1.0], [0, 0], [1, 0]]))
    assert np.allclose((basis @ coef)[:2, 0], 0)  # the remaining screw rotates about z


def test_rpy_convention_is_z_y_x_fixed_axes():
    roll, pitch, yaw = 0.1, 0.2, 0.3
    rx = np.array([[1, 0, 0], [0, np.cos(roll), -np.sin(roll)], [0, np.sin(roll), np.cos(roll)]])
    ry = np.array([[np.cos(pitch), 0, np.sin(pitch)], [0, 1, 0], [-np.sin(pitch), 0, np.cos(pitch)]])
    rz = np.array([[np.cos(yaw), -np.sin(yaw), 0], [np.sin(yaw), np.cos(yaw), 0], [0, 0, 1]])
    assert np.allclose(rotation_from_rpy((roll, pitch, yaw)), rz @ ry @ rx)


def test_cross_equals_numpy_cross():
    from mobility.core.transforms import cross

    rng = np.random.default_rng(7)
    a, b = rng.normal(size=(2, 3, 5))
    assert np.allclose(cross(a, b), np.cross(a, b, axis=0))
    assert np.allclose(cross(a[:, 0], b[:, 0]), np.cross(a[:, 0], b[:, 0]))
    assert np.allclose(cross(a[:, :1], b), np.cross(a[:, :1], b, axis=0))


def test_reciprocal_product_pairs_one_screw_with_every_column():
    rng = np.random.default_rng(0)
    a = rng.normal(size=6)
    for n in (1, 3, 6):
        b = rng.normal(size=(6, n))
        expected = a @ SWAP @ b
        assert np.allclose(reciprocal_product(a, b), expected)
        assert np.allclose(reciprocal_product(b, a), expected)
        assert np.allclose(reciprocal_product(a[:, None], b), expected)
    c, d = rng.normal(size=(2, 6, 4))
    assert np.allclose(reciprocal_product(c, d), np.einsum("ij,ik,kj->j", c, SWAP, d))
