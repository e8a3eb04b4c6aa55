"""The analyzer on mechanisms whose answers are known by hand."""

import numpy as np
import pytest
from builders import four_bar, six_ups, three_prs

import mobility
from mobility.core.model import Joint, Mechanism
from mobility.core.screws import same_subspace
from mobility.core.topology import JointNode
from mobility.errors import RequestError

Z = (0, 0, 1)


def mech(*joints, ground="g", ee="e"):
    return Mechanism("m", ground, ee, tuple(joints))


def test_three_prs_symmetric_pose():
    r = mobility.analyze(three_prs())
    assert (r.dof, r.pattern, r.mobility, r.gruebler_kutzbach) == (3, "1T2R", 3, 3)
    assert np.allclose(r.translations, [[0, 0, 1]])
    plane_z = 0.5 + np.sqrt(1 - 0.25)  # height of the S centres
    assert len(r.rotations) == 2
    for rot in r.rotations:
        assert rot.kind == "rotation" and rot.pitch == 0.0
        assert abs(rot.axis[2]) < 1e-12  # horizontal axes ...
        assert rot.point[2] == pytest.approx(plane_z)  # ... in the plane of the S centres
    assert same_subspace(np.array([a.axis for a in r.rotations]).T, np.eye(3)[:, :2])
    # constraints: a couple about z and two horizontal forces in the plane of the S centres
    assert np.allclose(r.couples, [[0, 0, 1]])
    assert all(f.kind == "force" and f.point[2] == pytest.approx(plane_z) for f in r.forces)
    assert r.structure == "parallel(series(P1,R1,S1), series(P2,R2,S2), series(P3,R3,S3))"
    assert not r.warnings


def test_three_prs_away_from_symmetry_couples_rotation_and_translation():
    sym = mobility.analyze(three_prs())
    r = mobility.analyze(three_prs(heights=(0.3, 0.5, 0.8)))
    assert (r.dof, r.pattern) == (3, "1T2R")
    assert np.allclose(r.translations, [[0, 0, 1]])
    # parasitic motion: the reference point (the S-centre centroid) moves when the platform rotates,
    # shown as an axis not through it or a non-zero pitch; at the symmetric pose neither happens
    ref_sym = np.mean([j.point for j in three_prs().joints if j.type == "S"], axis=0)
    assert all(np.allclose(a.point, ref_sym) for a in sym.rotations)
    ref = np.mean([j.point for j in three_prs(heights=(0.3, 0.5, 0.8)).joints if j.type == "S"], axis=0)
    offsets = [np.linalg.norm(a.point - ref) for a in r.rotations]
    assert max(offsets) > 1e-3 or any(a.kind == "helical" for a in r.rotations)
    assert any(a.kind == "helical" for a in r.rotations)


def test_four_bar_rotates_about_instantaneous_centre():
    r = mobility.analyze(four_bar())
    assert (r.dof, r.pattern, r.mobility, r.gruebler_kutzbach, r.redundant_constraints) == (1, "1R", 1, -2, 3)
    # instantaneous centre: intersection of lines AB and DC
    a, b, c, d = (np.array(p[:2], float) for p in ((0, 0), (1, 2), (4, 2.5), (5, 0)))
    t = np.linalg.solve(np.stack([b - a, -(c - d)], axis=1), d - a)
    centre = a + t[0] * (b - a)
    (rot,) = r.rotations
    assert np.allclose(rot.axis, Z) and np.allclose(rot.point[:2], centre)
    assert r.common_constraints == 3
    assert "3 wrenches reciprocal to every joint twist" in r.gruebler_kutzbach_explanation


def test_parallelogram_coupler_translates():
    r = mobility.analyze(four_bar(points=((0, 0, 0), (1, 2, 0), (4, 2, 0), (3, 0, 0))))
    assert (r.dof, r.pattern) == (1, "1T")
    direction = np.array([-2.0, 1.0, 0]) / np.sqrt(5)  # perpendicular to the crank (1, 2)
    assert np.allclose(r.translations[0], direction) or np.allclose(r.translations[0], -direction)


def test_stewart_six_ups_has_six_dof():
    r = mobility.analyze(six_ups())
    assert (r.dof, r.pattern, r.mobility, r.gruebler_kutzbach, r.idle_dof) == (6, "3T3R", 6, 6, 0)
    assert r.wrenches.shape == (0, 6)


def test_idle_spin_of_an_s_s_rod_is_counted():
    # platform held by a P along z and an S-S rod: the rod's spin about its own axis is idle
    r = mobility.analyze(
        mech(
            Joint("P", "P", ("g", "e"), axis=Z),
            Joint("S1", "S", ("g", "rod"), point=(1, 0, 0)),
            Joint("S2", "S", ("rod", "e"), point=(1, 0, 1)),
        )
    )
    assert r.idle_dof == 1
    assert (r.dof, r.mobility) == (0, 1)  # the rod blocks the slider along its own line: 0 DOF
    r2 = mobility.analyze(
        mech(
            Joint("P", "P", ("g", "e"), axis=Z),
            Joint("S1", "S", ("g", "rod"), point=(1, 0, 0)),
            Joint("S2", "S", ("rod", "e"), point=(2, 0, 0)),
        )
    )
    assert (r2.dof, r2.pattern, r2.mobility, r2.idle_dof) == (1, "1T", 2, 1)


def test_helical_and_cylindrical_pairs():
    r = mobility.analyze(mech(Joint("H", "H", ("g", "e"), axis=Z, point=(1, 0, 0), pitch=0.25)))
    (a,) = r.rotations
    assert (r.dof, r.pattern, a.kind) == (1, "1R", "helical")
    assert a.pitch == pytest.approx(0.25) and np.allclose(a.point, (1, 0, 0))
    r = mobility.analyze(mech(Joint("C", "C", ("g", "e"), axis=Z, point=(1, 0, 0))))
    assert (r.dof, r.pattern) == (2, "1T1R")
    assert np.allclose(r.translations, [Z]) and r.rotations[0].pitch == 0.0
    # two H joints on one axis with different pitches in series = C
    r = mobility.analyze(
        mech(
            Joint("H1", "H", ("g", "m"), axis=Z, point=(0, 0, 0), pitch=0.1),
            Joint("H2", "H", ("m", "e"), axis=Z, point=(0, 0, 0), pitch=0.3),
        )
    )
    assert (r.dof, r.pattern, r.idle_dof) == (2, "1T1R", 0)


def test_planar_pair_and_universal_joint():
    r = mobility.analyze(mech(Joint("E", "E", ("g", "e"), normal=Z, point=(0, 0, 2))))
    assert (r.dof, r.pattern) == (3, "2T1R")
    assert same_subspace(r.translations.T, np.eye(3)[:, :2])
    r = mobility.analyze(mech(Joint("U", "U", ("g", "e"), point=(1, 2, 3), axes=((1, 0, 0), (0, 1, 0)))))
    assert (r.dof, r.pattern) == (2, "2R")
    assert all(np.allclose(a.point, (1, 2, 3)) for a in r.rotations)


def test_two_joints_between_the_same_links_form_a_loop():
    # an R and a P about/along the same axis, both between g and e: they block each other
    r = mobility.analyze(mech(Joint("R", "R", ("g", "e"), axis=Z, point=(0, 0, 0)), Joint("P", "P", ("g", "e"), axis=Z)))
    assert (r.dof, r.mobility, r.loops) == (0, 0, 1)
    assert r.structure == "parallel(R, P)"
    # two coaxial R joints: the common rotation survives
    r = mobility.analyze(mech(Joint("R1", "R", ("g", "e"), axis=Z, point=(1, 1, 0)), Joint("R2", "R", ("g", "e"), axis=Z, point=(1, 1, 5))))
    assert (r.dof, r.pattern, r.mobility, r.redundant_constraints) == (1, "1R", 1, 5)


def test_links_hanging_off_do_not_change_the_end_effector():
    base = mech(Joint("R1", "R", ("g", "a"), axis=Z, point=(0, 0, 0)), Joint("R2", "R", ("a", "e"), axis=Z, point=(1, 0, 0)))
    hanging = base.replace(
        joints=base.joints
        + (
            Joint("X1", "S", ("a", "x"), point=(0, 1, 0)),
            Joint("X2", "R", ("x", "y"), axis=(1, 0, 0), point=(0, 2, 0)),
            Joint("X3", "R", ("y", "a"), axis=(0, 1, 0), point=(1, 3, 0.5)),
        )
    )
    r0, r1 = mobility.analyze(base), mobility.analyze(hanging)
    assert (r0.dof, r0.pattern) == (r1.dof, r1.pattern) == (2, "1T1R")
    assert same_subspace(r0.twists.T, r1.twists.T)
    # the hanging loop S-R-R (generic) has 5 freedoms and one loop of rank 5: mobility 0, adding nothing
    assert r1.mobility == r0.mobility == 2
    # with the last axis through the S centre the loop turns about it: one more DOF, idle for the end effector
    turning = hanging.replace(joints=hanging.joints[:-1] + (Joint("X3", "R", ("y", "a"), axis=(0, 1, 0), point=(0, 3, 0)),))
    r2 = mobility.analyze(turning)
    assert (r2.dof, r2.mobility, r2.idle_dof) == (2, 3, 1)


def test_bridge_tie_link_between_two_limbs_is_solved():
    # two planar RRR limbs joined by a tie link: not series-parallel
    def R(n, a, b, p):
        return Joint(n, "R", (a, b), axis=Z, point=p)

    m = mech(
        R("A1", "g", "a1", (0, 0, 0)), R("A2", "a1", "a2", (1, 1, 0)), R("A3", "a2", "e", (2, 2, 0)),
        R("B1", "g", "b1", (4, 0, 0)), R("B2", "b1", "b2", (3.5, 1, 0)), R("B3", "b2", "e", (2.5, 2.2, 0)),
        R("T1", "a1", "t", (0.5, 0.5, 0)), R("T2", "t", "b1", (3.7, 0.6, 0)),
    )
    r = mobility.analyze(m)
    assert r.structure.startswith("bridge(")
    # planar Gruebler (valid here: generic planar geometry): 3 (7 links - 1) - 2 x 8 joints = 2
    assert (r.links, r.joints, r.mobility) == (7, 8, 2)
    # two planar rotations about different centres: one rotation and one translation
    assert (r.dof, r.pattern, r.idle_dof) == (2, "1T1R", 0)


def test_end_effector_twists_and_wrenches_are_reciprocal():
    for m in (three_prs(), three_prs(heights=(0.2, 0.6, 0.9)), four_bar(), six_ups()):
        r = mobility.analyze(m)
        assert r.twists.shape == (r.dof, 6) and r.wrenches.shape == (6 - r.dof, 6)
        power = r.wrenches[:, :3] @ r.twists[:, 3:].T + r.wrenches[:, 3:] @ r.twists[:, :3].T
        assert np.allclose(power, 0, atol=1e-9)


def test_result_is_frozen_and_serialisable():
    r = mobility.analyze(three_prs())
    with pytest.raises(AttributeError):
        r.dof = 4
    with pytest.raises(ValueError):
        r.translations[0, 0] = 1.0
    d = r.to_dict()
    for key in ("name", "dof", "pattern", "translations", "rotations", "twists", "wrenches", "mobility", "gruebler_kutzbach", "redundant_constraints", "idle_dof"):
        assert key in d
    assert d["rotations"][0].keys() >= {"axis", "point", "pitch"}


def test_near_singular_pose_is_reported_with_its_margin():
    # a four-bar whose coupler is almost aligned with the crank: close to the stretched (singular) pose
    eps = 1e-7
    r = mobility.analyze(four_bar(points=((0, 0, 0), (1, 0, 0), (3, eps, 0), (6, 0, 0))))
    assert r.margin.near_singular
    assert r.margin.smallest_kept < 1e-5
    assert any("near-singular" in w for w in r.warnings)


def test_inexact_geometry_is_reported():
    # a parallelogram typed with a tiny error: the count is still given, with a warning
    r = mobility.analyze(four_bar(points=((0, 0, 0), (1, 2, 0), (4, 2, 0), (3, 1e-10, 0))))
    assert r.margin.inexact and any("inexact geometry" in w for w in r.warnings)


def test_limb_frames_match_the_adjoint_route():
    """Joints written in a limb frame: twists built in the frame and moved by the adjoint
    (the seed method's route) equal the twists of the joints mapped to the world frame."""
    from mobility.core.joint_screws import joint_screws
    from mobility.core.screws import adjoint

    m = mobility.loads(
        """
name: frames
ground: g
end_effector: e
frames:
  base: {origin: [10, -3, 2], rpy: [10, 20, 30]}
  leg: {origin: [1, 2, 3], rpy: [0, 45, 120], parent: base}
joints:
  - {name: A, type: R, links: [g, a], axis: [0, 1, 0], point: [1, 0, 0.5], frame: leg}
  - {name: B, type: H, links: [a, b], axis: [1, 1, 0], point: [0, 2, 0], pitch: 0.3, frame: leg}
  - {name: C, type: U, links: [b, c], point: [0, 0, 1], axes: [[1, 0, 0], [0, 0, 1]], frame: base}
  - {name: D, type: P, links: [c, e], axis: [0, 0, 1], frame: leg}
"""
    )
    js = joint_screws(m)
    world_twists = js.normalisation.to_world(js.twists)
    col = 0
    for j in m.joints:
        tf = m.frame_transform(j.frame)
        ad = adjoint(tf.rotation, tf.translation)
        for f in j.freedoms():  # in the joint's own frame
            if f.kind == "P":
                t = np.concatenate([np.zeros(3), f.axis])
            else:
                t = np.concatenate([f.axis, np.cross(f.point, f.axis) + f.pitch * np.asarray(f.axis)])
            moved = ad @ t
            scale = np.linalg.norm(moved[:3]) or np.linalg.norm(moved[3:])
            got = world_twists[:, col]
            assert np.allclose(moved / scale, got / (np.linalg.norm(got[:3]) or np.linalg.norm(got[3:]))), j.name
            col += 1
    assert col == js.twists.shape[1]


def test_node_systems_give_every_node_of_the_tree_read_only():
    m = three_prs()
    r = mobility.analyze(m)
    systems = r.node_systems
    root = r.topology.root
    assert r.topology.structure == r.structure and not r.topology.detached
    assert systems[root] == (r.dof, r.idle_dof) and systems[root].mobility == r.mobility
    # each limb (a child of the top parallel connection) as the limb systems report it in its own frame
    assert [systems[c] for c in root.children] == [(limb.dof, limb.idle_dof) for limb in r.limbs] == [(5, 0)] * 3
    assert sum(isinstance(n, JointNode) for n in systems) == len(m.joints) and len(systems) == len(m.joints) + 4
    with pytest.raises(TypeError):
        systems[root] = (0, 0)


def test_detached_networks_have_their_systems_too():
    z = (0, 0, 1)
    m = Mechanism("arm with a four-bar hanging off the base", "g", "e", (
        Joint("A", "R", ("g", "e"), axis=z, point=(0, 0, 0)),
        Joint("B", "R", ("g", "x"), axis=z, point=(0, 0, 1)),
        Joint("C", "R", ("x", "y"), axis=z, point=(1, 2, 1)),
        Joint("D", "R", ("y", "w"), axis=z, point=(4, 2.5, 1)),
        Joint("E", "R", ("w", "g"), axis=z, point=(5, 0, 1)),
    ))
    r = mobility.analyze(m)
    (detached,) = r.topology.detached
    assert r.node_systems[detached] == (1, 0) and r.node_systems[r.topology.root] == (1, 0)
    assert r.mobility == 2


def test_an_unknown_joint_name_is_a_request_error():
    m = four_bar()
    assert m.joint(m.joints[1].name) is m.joints[1]
    with pytest.raises(RequestError, match="no joint named 'Z'; the joints are"):
        m.joint("Z")


def test_result_knows_the_mechanism_it_analysed():
    m = four_bar()
    r = mobility.analyze(m)
    assert r.mechanism is m and r.mechanism.joints[r.topology.root.children[0].children[0].index].name == "A"
