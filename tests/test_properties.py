"""Property tests: units, frames, names and order of joints change nothing."""

import numpy as np
from builders import normalised, random_mechanism, random_rotation, three_prs, transformed, with_frame_wrapper
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mobility
from mobility.core.model import Joint
from mobility.core.screws import adjoint, same_subspace
from mobility.core.transforms import Transform

SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
seeds = st.integers(min_value=0, max_value=10_000)


def counts(r: mobility.Result) -> tuple:
    return (r.dof, r.pattern, r.mobility, r.redundant_constraints, r.idle_dof, r.gruebler_kutzbach)


@SETTINGS
@given(seeds, st.sampled_from([1000.0, 1e-3, 25.4, 7.0]))
def test_scaling_lengths_changes_nothing(seed, scale):
    m = random_mechanism(seed)
    r0 = mobility.analyze(m)
    m1 = transformed(m, Transform.identity(), scale)
    r1 = mobility.analyze(m1)
    assert counts(r0) == counts(r1)
    assert same_subspace(r0.translations.T, r1.translations.T)
    # in normalised coordinates the two twist systems are the same
    assert same_subspace(normalised(m, r0.twists), normalised(m1, r1.twists))
    assert same_subspace(normalised(m, r0.wrenches), normalised(m1, r1.wrenches))


@SETTINGS
@given(seeds, seeds)
def test_rigid_reframing_changes_nothing(seed, frame_seed):
    m = random_mechanism(seed)
    rng = np.random.default_rng(frame_seed)
    tf = Transform(random_rotation(rng), rng.normal(scale=50.0, size=3))
    r0 = mobility.analyze(m)
    rot6 = np.kron(np.eye(2), tf.rotation)  # normalised coordinates differ by the rotation only
    for moved in (transformed(m, tf), with_frame_wrapper(m, tf)):
        r1 = mobility.analyze(moved)
        assert counts(r0) == counts(r1)
        assert same_subspace(tf.rotation @ r0.translations.T, r1.translations.T)
        assert same_subspace(rot6 @ normalised(m, r0.twists), normalised(moved, r1.twists))
        assert same_subspace(rot6 @ normalised(m, r0.wrenches), normalised(moved, r1.wrenches))
        # the adjoint maps the global-frame systems onto each other
        ad = adjoint(tf.rotation, tf.translation)
        assert same_subspace(normalised(moved, (ad @ r0.twists.T).T), normalised(moved, r1.twists))
        # principal pitches are frame-invariant (the listing order follows the coordinate axes, so compare sorted)
        p0 = sorted(a.pitch for a in r0.rotations)
        p1 = sorted(a.pitch for a in r1.rotations)
        assert np.allclose(p0, p1, atol=1e-6 * (1 + np.abs(p0).max(initial=0)))


@SETTINGS
@given(seeds, st.randoms(use_true_random=False))
def test_renaming_reordering_and_flipping_joints_changes_nothing(seed, rnd):
    m = random_mechanism(seed)
    r0 = mobility.analyze(m)
    joints = list(m.joints)
    rnd.shuffle(joints)
    links = {name: f"link_{i}" for i, name in enumerate(m.links)}
    renamed = []
    for k, j in enumerate(joints):
        a, b = links[j.links[0]], links[j.links[1]]
        flip = rnd.random() < 0.5 and j.type != "U"  # a U joint's axes belong to its two sides
        geometry = {key: getattr(j, key) for key in ("axis", "point", "pitch", "axes", "normal") if getattr(j, key) is not None}
        renamed.append(Joint(f"joint_{k}", j.type, (b, a) if flip else (a, b), **geometry))
    m1 = m.replace(joints=tuple(renamed), ground=links[m.ground], end_effector=links[m.end_effector])
    r1 = mobility.analyze(m1)
    assert counts(r0) == counts(r1)
    assert same_subspace(normalised(m, r0.twists), normalised(m1, r1.twists))


def test_three_prs_in_millimetres_and_moved():
    r0 = mobility.analyze(three_prs())
    tf = Transform(random_rotation(np.random.default_rng(3)), np.array([120.0, -40.0, 900.0]))
    r1 = mobility.analyze(transformed(three_prs(), tf, 1000.0))
    assert counts(r0) == counts(r1) == (3, "1T2R", 3, 0, 0, 3)
    assert same_subspace(tf.rotation @ np.array([[0.0], [0.0], [1.0]]), r1.translations.T)
    # the rotation axes moved with the mechanism: still through the (moved, scaled) S-centre plane
    for a0, a1 in zip(r0.rotations, r1.rotations):
        assert np.allclose(tf.apply_point(a0.point * 1000.0), a1.point, atol=1e-6)
