"""MJCF import, cross-checked by MuJoCo itself.

Every imported mechanism is compared with a second route that does not use
mobility's importer: MuJoCo compiles the same file, and at ``qpos0`` the null
space of its equality-constraint Jacobian (``data.efc_J``, the rows of the
connect and weld constraints) gives the mobility, and the body Jacobian of
the end effector (``mj_jacBody``) mapped through that null space gives the
end effector's twist system.  Published models: the xArm7 arm and the xArm7
gripper (two four-bar fingers closed by ``<connect>``) from robosuite 1.5.2
(MIT), kept unchanged under ``tests/data/robots/robosuite``.
"""

from __future__ import annotations

import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.linalg import subspace_angles

import mobility
from mobility.errors import MechanismFileError, MissingExtraError, RequestError
from mobility.io.robot_files import read_robot, robot_format

DATA = Path(__file__).parent / "data" / "robots"
HAND = DATA / "hand"
ROBOSUITE = DATA / "robosuite"
MECHANISMS = Path(__file__).parent.parent / "mechanisms"
CONNECT, WELD, JOINT_EQ = (int(mujoco.mjtEq.mjEQ_CONNECT), int(mujoco.mjtEq.mjEQ_WELD), int(mujoco.mjtEq.mjEQ_JOINT))


# -- the second route: MuJoCo's own Jacobians ------------------------------------------------

def mujoco_compile(path_or_text: Path | str):
    """MuJoCo's model and data at qpos0 (mesh geoms made spheres: the mesh files are absent)."""
    spec = mujoco.MjSpec.from_file(str(path_or_text)) if isinstance(path_or_text, Path) else mujoco.MjSpec.from_string(path_or_text)
    for geom in spec.geoms:
        if geom.type == mujoco.mjtGeom.mjGEOM_MESH:
            geom.type, geom.meshname, geom.size = mujoco.mjtGeom.mjGEOM_SPHERE, "", [0.02, 0, 0]
    for mesh in list(spec.meshes):
        spec.delete(mesh) if hasattr(spec, "delete") else mesh.delete()
    return compiled_at_qpos0(spec)


def compiled_at_qpos0(spec):
    """The model of ``spec`` without contacts, with dense Jacobians, and its data after a forward pass at qpos0."""
    model = spec.compile()
    model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONTACT)
    model.opt.jacobian = int(mujoco.mjtJacobian.mjJAC_DENSE)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return model, data


class MujocoRoute:
    """Mobility and end-effector twists from MuJoCo's constraint and body Jacobians at qpos0."""

    def __init__(self, model, data, end_effector: str, *, kinds=(CONNECT, WELD), floating: bool = False):
        free = {int(model.jnt_dofadr[j]) + k for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE for k in range(6)}
        cols = [i for i in range(model.nv) if floating or i not in free]
        rows = [i for i in range(data.nefc) if data.efc_type[i] == mujoco.mjtConstraint.mjCNSTR_EQUALITY and model.eq_type[data.efc_id[i]] in kinds]
        jac = np.asarray(data.efc_J[: data.nefc * model.nv]).reshape(data.nefc, model.nv)[np.ix_(rows, cols)]
        _, s, vt = np.linalg.svd(jac) if rows else (None, np.zeros(0), np.zeros((0, len(cols))))
        rank = int(np.sum(s > 1e-9 * s[0])) if s.size else 0
        self.kept = float(s[rank - 1] / s[0]) if rank else 1.0
        self.dropped = float(s[rank] / s[0]) if rank < s.size else 0.0
        null = vt[rank:].T if rows else np.eye(len(cols))
        self.mobility = null.shape[1]
        body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, end_effector)
        jacp, jacr = np.zeros((3, model.nv)), np.zeros((3, model.nv))
        mujoco.mj_jacBody(model, data, jacp, jacr, body)
        origin_velocity = jacp + np.cross(data.xpos[body], jacr.T).T  # v(origin) = v(p) - w x p
        self.twists = (np.vstack([jacr, origin_velocity])[:, cols] @ null).T  # rows [w; v]
        s_ee = np.linalg.svd(self.twists, compute_uv=False) if self.twists.size else np.zeros(0)
        self.dof = int(np.sum(s_ee > 1e-9 * s_ee[0])) if s_ee.size and s_ee[0] > 0 else 0


def same_subspace(a: np.ndarray, b: np.ndarray, rank: int) -> float:
    """Largest principal angle between the ``rank``-dimensional row spaces of a and b (0 when they are the same).

    ``rank`` is the dimension both routes decided, each at its own threshold:
    the rows carry round-off (MuJoCo's null space about 1e-15 of its largest
    singular value, and how much depends on the BLAS kernel the CPU selects),
    so a rank read again here at machine precision would decide finer than the
    data and could count that round-off as a direction.
    """
    if rank == 0:
        return 0.0
    ua = np.linalg.svd(a.T, full_matrices=False)[0][:, :rank]
    ub = np.linalg.svd(b.T, full_matrices=False)[0][:, :rank]
    return float(np.max(subspace_angles(ua, ub)))


def assert_agrees_with_mujoco(robot_or_mechanism, model, data, *, kinds=(CONNECT, WELD), floating=False) -> MujocoRoute:
    m = getattr(robot_or_mechanism, "mechanism", robot_or_mechanism)
    result = mobility.analyze(m)
    route = MujocoRoute(model, data, m.end_effector, kinds=kinds, floating=floating)
    assert route.dropped < 1e-12 and route.kept > 1e-6, (route.kept, route.dropped)  # a clear rank gap
    assert result.mobility == route.mobility
    assert result.dof == route.dof
    assert same_subspace(result.twists, route.twists, route.dof) < 1e-8
    return route


def fixed_gripper(tmp_path: Path) -> Path:
    """The robosuite gripper with the one attribute MuJoCo 4 rejects removed (``group`` on a ``<default>``)."""
    text = (ROBOSUITE / "xarm7_gripper.xml").read_text()
    fixed, count = re.subn(r'(<default class="xarm7_hand") group="1">', r"\1>", text)
    assert count == 1
    path = tmp_path / "xarm7_gripper.xml"
    path.write_text(fixed)
    return path


# -- hand files ------------------------------------------------------------------------------

def test_four_bar_closed_by_one_connect():
    robot = read_robot(HAND / "four_bar.xml")
    m = robot.mechanism
    assert (m.ground, m.end_effector) == ("world", "coupler")
    assert [(j.name, j.type, j.links) for j in m.joints] == [
        ("A", "R", ("world", "crank")), ("B", "R", ("crank", "coupler")), ("D", "R", ("world", "rocker")), ("C", "S", ("coupler", "rocker"))]
    assert m.joint("C").point == pytest.approx((4.0, 2.5, 0.0))
    assert m.joint("A").actuated and not m.joint("B").actuated
    r = mobility.analyze(m)
    assert (r.dof, r.pattern, r.mobility) == (1, "1R", 1)
    # the coupler turns about its instantaneous centre: where the crank line AB meets the rocker line DC
    a, b, c, d = np.array([0, 0.0]), np.array([1, 2.0]), np.array([4, 2.5]), np.array([5, 0.0])
    t = np.linalg.solve(np.column_stack([b - a, -(c - d)]), d - a)
    centre = a + t[0] * (b - a)
    axis = r.rotations[0]
    assert abs(abs(axis.axis[2]) - 1) < 1e-12 and np.allclose(axis.point[:2], centre, atol=1e-9)
    assert_agrees_with_mujoco(robot, *mujoco_compile(HAND / "four_bar.xml"))


def test_four_bar_agrees_with_the_bundled_yaml_four_bar():
    imported = mobility.analyze(mobility.load(HAND / "four_bar.xml"))
    written = mobility.analyze(mobility.load(MECHANISMS / "four_bar.yaml"))
    assert (imported.dof, imported.pattern, imported.mobility) == (written.dof, written.pattern, written.mobility)
    assert same_subspace(imported.twists, written.twists, written.dof) < 1e-9


def test_parallelogram_euler_xyaxes_and_classes_match_the_bundled_yaml():
    robot = read_robot(HAND / "parallelogram.xml")
    r = mobility.analyze(robot.mechanism)
    written = mobility.analyze(mobility.load(MECHANISMS / "parallelogram.yaml"))  # the same, in mm
    assert (r.dof, r.pattern, r.mobility) == (written.dof, written.pattern, written.mobility) == (1, "1T", 1)
    phi = math.radians(60)
    assert abs(abs(float(r.translations[0] @ [-math.sin(phi), math.cos(phi), 0])) - 1) < 1e-12
    assert robot.mechanism.joint("A2").point == pytest.approx((0.1 + 0.06 * math.cos(phi), 0.06 * math.sin(phi), 0), abs=1e-15)
    assert_agrees_with_mujoco(robot, *mujoco_compile(HAND / "parallelogram.xml"))


def test_3rps_matches_the_bundled_yaml_and_mujoco():
    robot = read_robot(HAND / "3rps.xml", end_effector="platform")
    m = robot.mechanism
    assert sorted(j.name for j in m.joints if j.actuated) == ["P1", "P2", "P3"]
    assert {j.name: j.type for j in m.joints if j.name.startswith("S")} == {"S1": "S", "S2": "S", "S3": "S"}
    r = mobility.analyze(m)
    written = mobility.analyze(mobility.load(MECHANISMS / "3rps.yaml"))
    for key in ("dof", "pattern", "mobility", "gruebler_kutzbach", "redundant_constraints", "idle_dof"):
        assert getattr(r, key) == getattr(written, key), key
    assert np.allclose(np.abs(r.translations), [[0, 0, 1]], atol=1e-12)
    route = assert_agrees_with_mujoco(robot, *mujoco_compile(HAND / "3rps.xml"))
    assert route.mobility == 3


def test_a_reference_position_does_not_move_the_pose():
    text = (HAND / "four_bar.xml").read_text().replace('<joint name="B"/>', '<joint name="B" ref="40"/>')
    model, data = mujoco_compile(text)
    assert model.qpos0[1] == pytest.approx(math.radians(40))  # degrees, the default unit
    path = _write(text)
    assert mobility.load(path).joint("B").point == pytest.approx((1.0, 2.0, 0.0))


def test_frames_and_childclass_are_compiled_by_mujoco():
    # the whole four-bar inside a <frame> turned and moved: the same answers, axes turned with it
    text = (HAND / "four_bar.xml").read_text()
    body = text[text.index("<worldbody>") + len("<worldbody>"): text.index("</worldbody>")]
    turned = text.replace(body, f'<frame pos="1 -2 3" euler="30 -20 50">{body}</frame>')
    path = _write(turned)
    robot = read_robot(path)
    r = mobility.analyze(robot.mechanism)
    assert (r.dof, r.pattern, r.mobility) == (1, "1R", 1)
    assert abs(np.linalg.norm(r.rotations[0].axis) - 1) < 1e-12 and abs(r.rotations[0].axis[2]) < 1 - 1e-3
    assert_agrees_with_mujoco(robot, *mujoco_compile(turned))


@settings(max_examples=20, deadline=None)
@given(st.tuples(*[st.floats(-5, 5, allow_subnormal=False)] * 3), st.tuples(*[st.floats(-180, 180, allow_subnormal=False)] * 3))
def test_moving_the_file_rigidly_changes_no_count(offset, euler):
    text = (HAND / "3rps.xml").read_text()
    body = text[text.index("<worldbody>") + len("<worldbody>"): text.index("</worldbody>")]
    moved = text.replace(body, '<frame pos="{} {} {}" euler="{} {} {}">{}</frame>'.format(*offset, *euler, body))
    robot = read_robot(_write(moved), end_effector="platform")
    r = mobility.analyze(robot.mechanism)
    assert (r.dof, r.pattern, r.mobility) == (3, "1T2R", 3)
    assert_agrees_with_mujoco(robot, *mujoco_compile(moved))


# -- published models ------------------------------------------------------------------------

def test_published_serial_arm_xarm7_with_absent_meshes():
    path = ROBOSUITE / "xarm7_robot.xml"
    assert not (ROBOSUITE / "meshes").exists()  # geometry is not needed
    robot = read_robot(path)
    m = robot.mechanism
    assert [j.name for j in m.joints] == [f"joint{i}" for i in range(1, 8)]
    assert all(j.actuated and j.type == "R" for j in m.joints)
    assert (m.ground, m.end_effector) == ("world", "link7")
    r = mobility.analyze(m)
    assert (r.mobility, r.gruebler_kutzbach, r.redundant_constraints) == (7, 7, 0)
    model, data = mujoco_compile(path)
    route = assert_agrees_with_mujoco(robot, model, data)
    assert route.dof == r.dof == 5  # straight up at qpos0: joints 1, 3 and 5, 7 are coaxial
    hand = read_robot(path, end_effector="right_hand").mechanism
    assert hand.end_effector == "right_hand" and mobility.analyze(hand).dof == 5


def test_published_gripper_as_shipped_fails_in_one_line():
    # robosuite writes group="1" on a <default>; MuJoCo 4 rejects it: one line naming the line
    with pytest.raises(MechanismFileError) as err:
        read_robot(ROBOSUITE / "xarm7_gripper.xml")
    message = str(err.value)
    assert "\n" not in message and message.startswith(f"{ROBOSUITE / 'xarm7_gripper.xml'}:20: ")
    assert "group" in message


def test_published_gripper_joint_coupling_is_read_as_a_coupling_of_the_two_drivers(tmp_path):
    path = fixed_gripper(tmp_path)
    m = read_robot(path).mechanism
    (coupling,) = m.couplings
    assert coupling.terms == (("left_driver_joint", 1.0), ("right_driver_joint", -1.0))  # polycoef "0 1 0 0 0"
    model, data = mujoco_compile(path)
    route = assert_agrees_with_mujoco(m, model, data, kinds=(CONNECT, WELD, JOINT_EQ))  # MuJoCo with the coupling on
    assert route.mobility == 1 == mobility.loop_closure(m).mobility


def test_published_gripper_two_four_bars_closed_by_connect(tmp_path):
    path = fixed_gripper(tmp_path)
    text = path.read_text().replace('<joint joint1="left_driver_joint"', '<joint active="false" joint1="left_driver_joint"')
    path.write_text(text)
    robot = read_robot(path)
    m = robot.mechanism
    assert sorted(j.name for j in m.joints if j.type == "S") == ["connect0", "connect1"]
    assert not any(j.actuated for j in m.joints)  # the actuator drives a tendon
    notes = " | ".join(robot.notes)
    assert "equality joint joint0 (line 132) is inactive at start: left out" in notes
    assert "tendon split (line 123)" in notes and "actuator fingers_actuator (line 136) drives a tendon" in notes
    r = mobility.analyze(m)
    assert (r.mobility, r.dof, r.pattern) == (2, 1, "1T")  # each finger is a parallelogram: it translates
    model, data = mujoco_compile(path)
    route = assert_agrees_with_mujoco(robot, model, data)
    assert route.mobility == 2


# -- welds, free joints, several joints in a body, sites, inactive equalities ---------------

def test_weld_merges_bodies_and_locks_the_joint_between_them():
    text = (HAND / "four_bar.xml").read_text().replace("</equality>", '<weld name="hold" body1="rocker"/></equality>')
    robot = read_robot(_write(text))
    notes = " | ".join(robot.notes)
    assert "weld hold" in notes and "joint D" in notes and "cannot move" in notes
    assert "D" not in [j.name for j in robot.mechanism.joints]
    r = mobility.analyze(robot.mechanism)
    assert (r.mobility, r.dof) == (0, 0)
    assert_agrees_with_mujoco(robot, *mujoco_compile(text))



def test_a_free_joint_held_by_a_weld_is_left_out_with_a_note_even_when_floating():
    text = """
<mujoco model="welded box">
  <worldbody>
    <body name="arm"><joint name="hinge" type="hinge" axis="0 0 1"/><geom type="capsule" fromto="0 0 0 1 0 0" size="0.05"/></body>
    <body name="box" pos="2 0 0"><freejoint name="float"/><geom type="box" size="0.1 0.1 0.1"/></body>
  </worldbody>
  <equality><weld name="hold" body1="box" body2="world"/></equality>
</mujoco>"""
    robot = read_robot(_write(text), floating=True, end_effector="arm")
    assert "joint float cannot move: welds hold box to world; left out" in robot.notes
    assert [j.name for j in robot.mechanism.joints] == ["hinge"]
    route = assert_agrees_with_mujoco(robot, *mujoco_compile(text), floating=True)
    assert route.mobility == 1

FREE_PENDULUM = """
<mujoco model="free pendulum">
  <worldbody>
    <body name="base" pos="0 0 1">
      <freejoint name="root"/>
      <geom size="0.1"/>
      <body name="arm" pos="0.5 0 0">
        <joint name="swing" axis="0 1 0" pos="-0.5 0 0"/>
        <geom size="0.05"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def test_free_joint_is_fixed_unless_floating():
    path = _write(FREE_PENDULUM)
    fixed = read_robot(path)
    assert [j.name for j in fixed.mechanism.joints] == ["swing"]
    assert any("free joint root of body base treated as fixed" in n for n in fixed.notes)
    model, data = mujoco_compile(FREE_PENDULUM)
    assert_agrees_with_mujoco(fixed, model, data)
    floating = read_robot(path, floating=True)
    m = floating.mechanism
    assert [(j.name, j.type) for j in m.joints] == [("root.x", "P"), ("root.y", "P"), ("root.z", "P"), ("root", "S"), ("swing", "R")]
    assert m.joint("root").point == pytest.approx((0, 0, 1))
    r = mobility.analyze(m)
    assert (r.mobility, r.dof) == (7, 6)
    assert_agrees_with_mujoco(floating, model, data, floating=True)


def test_several_joints_in_one_body_hang_by_a_chain():
    text = """
    <mujoco><worldbody><body name="head" pos="0 0 2">
      <joint name="pan" axis="0 0 1"/><joint name="tilt" axis="0 1 0" pos="0 0 -0.5"/>
      <geom size="0.1"/>
    </body></worldbody></mujoco>"""
    robot = read_robot(_write(text))
    m = robot.mechanism
    assert [(j.name, j.links) for j in m.joints] == [("pan", ("world", "head/pan")), ("tilt", ("head/pan", "head"))]
    assert m.joint("tilt").point == pytest.approx((0, 0, 1.5))
    assert mobility.analyze(m).pattern == "2R"
    assert_agrees_with_mujoco(robot, *mujoco_compile(text))


def test_connect_between_sites_and_inactive_equalities():
    text = (HAND / "four_bar.xml").read_text()
    text = text.replace('<body name="rocker" pos="5 0 0">', '<body name="rocker" pos="5 0 0"><site name="c_on_rocker" pos="-1 2.5 0"/>')
    text = text.replace('<joint name="B"/>', '<joint name="B"/><site name="c_on_coupler" pos="3 0.5 0"/>')
    by_sites = text.replace('<connect name="C" body1="coupler" body2="rocker" anchor="3 0.5 0"/>', '<connect name="C" site1="c_on_coupler" site2="c_on_rocker"/>')
    robot = read_robot(_write(by_sites))
    assert robot.mechanism.joint("C").point == pytest.approx((4, 2.5, 0))
    assert mobility.analyze(robot.mechanism).pattern == "1R"
    assert_agrees_with_mujoco(robot, *mujoco_compile(by_sites))
    assert not any("does not hold at qpos0" in n for n in robot.notes)  # the sites meet: nothing to say
    apart = by_sites.replace('<site name="c_on_rocker" pos="-1 2.5 0"/>', '<site name="c_on_rocker" pos="-1 2.1 0"/>')
    robot = read_robot(_write(apart))  # 0.4 apart at qpos0, as MuJoCo's own constraint residual says
    assert any(n.startswith("connect C (line") and "does not hold at qpos0 (its points are 0.4 apart)" in n for n in robot.notes)
    welded = text.replace('<connect name="C" body1="coupler" body2="rocker" anchor="3 0.5 0"/>', '<weld name="W" body1="coupler" body2="rocker"/>')
    assert not any("does not hold" in n for n in read_robot(_write(welded)).notes)  # relpose taken from qpos0: holds
    shifted = welded.replace('body2="rocker"/>', 'body2="rocker" relpose="0.3 0 0 1 0 0 0"/>')
    assert any(n.startswith("weld W (line") and "does not hold at qpos0" in n for n in read_robot(_write(shifted)).notes)
    inactive = text.replace('anchor="3 0.5 0"/>', 'anchor="3 0.5 0" active="false"/>')
    robot = read_robot(_write(inactive))
    assert any("equality connect C (line" in n and "inactive" in n for n in robot.notes)
    assert mobility.analyze(robot.mechanism).mobility == 3


def test_tendon_equality_is_a_coupling_and_a_tendon_alone_is_a_note():
    text = (HAND / "four_bar.xml").read_text().replace(
        "<equality>", '<tendon><fixed name="sum"><joint joint="A" coef="1"/><joint joint="D" coef="1"/></fixed></tendon>\n  <equality>')
    robot = read_robot(_write(text))
    assert any(n.startswith("tendon sum (line") for n in robot.notes)
    coupled = text.replace("</equality>", '<tendon tendon1="sum"/></equality>')
    robot = read_robot(_write(coupled))
    assert robot.mechanism.couplings[0].terms == (("A", 1.0), ("D", 1.0)) and not any(n.startswith("tendon sum") for n in robot.notes)
    assert_agrees_with_mujoco(robot, *mujoco_compile(coupled), kinds=(CONNECT, WELD, int(mujoco.mjtEq.mjEQ_TENDON)))


# -- choosing ground and end effector --------------------------------------------------------

def test_ground_and_end_effector_by_name():
    m = read_robot(HAND / "four_bar.xml", ground="rocker", end_effector="crank").mechanism
    assert (m.ground, m.end_effector) == ("rocker", "crank")
    assert mobility.analyze(m).mobility == 1


@pytest.mark.parametrize("options, expected", [
    ({"ground": "rockr"}, "four_bar.xml: ground: no body named 'rockr' (did you mean 'rocker'?); expected one of: world, crank, coupler, rocker"),
    ({"end_effector": "tip"}, "four_bar.xml: end_effector: no body named 'tip'; expected one of: world, crank, coupler, rocker"),
    ({"ground": "crank", "end_effector": "crank"}, "four_bar.xml: end_effector: body 'crank' is rigidly attached to the ground 'crank' (no joint between them); expected a body that can move"),
])
def test_unknown_or_impossible_bodies_are_one_line(options, expected):
    with pytest.raises(MechanismFileError) as err:
        read_robot(HAND / "four_bar.xml", **options)
    assert str(err.value).endswith(expected)


# -- bad input -------------------------------------------------------------------------------

@pytest.mark.parametrize("text, expected", [
    ("<mujoco>\n<worldbody>\n<body name='a'>\n</worldbdy>\n</mujoco>\n", r":4: malformed XML: mismatched tag \(column 3\)"),
    ("<mujoco>\n<worldbody>\n<body>\n<joint class='nope'/>\n<geom size='1'/></body>\n</worldbody>\n</mujoco>\n",
     r":4: joint: MuJoCo cannot compile it: unknown default class name 'nope'; expected a model MuJoCo compiles"),
    ("<mujoco>\n<worldbody>\n<body>\n<joint type='hinj'/>\n<geom size='1'/></body>\n</worldbody>\n</mujoco>\n", r":4: joint: MuJoCo cannot compile it: invalid keyword: 'hinj'"),
    ("<mujoco><worldbody><body><geom size='1'/></body></worldbody></mujoco>", r": no joint can move: every body of .* is rigidly attached to world"),
    ("<mujoco><include file='absent.xml'/></mujoco>", r"\.xml:1: include: 'absent\.xml': no such file \(looked in '.*'\); expected a file to include"),
])
def test_bad_mjcf_is_one_line(text, expected):
    with pytest.raises(MechanismFileError) as err:
        read_robot(_write(text))
    assert "\n" not in str(err.value)
    assert re.search(expected, str(err.value)), str(err.value)


def test_deformable_bodies_are_unsupported():
    text = """<mujoco><worldbody>
      <body name="arm" pos="0 0 1"><joint name="j" axis="0 1 0"/><geom size="0.1"/></body>
      <flexcomp name="cloth" type="grid" count="3 3 1" spacing="0.1 0.1 0.1" pos="0 0 2" dim="2"/>
    </worldbody></mujoco>"""
    with pytest.raises(MechanismFileError, match=r"\.xml:3: flexcomp\[cloth\]: a deformable body, not supported \(not even left out: .*\); expected rigid bodies and joints"):
        read_robot(_write(text))


def test_an_entity_bomb_is_refused_quickly():
    entities = '<!ENTITY a "aaaaaaaaaa">' + "".join(f'<!ENTITY {n} "{("&" + p + ";") * 10}">' for p, n in zip("abcdefgh", "bcdefghi"))
    with pytest.raises(MechanismFileError, match=r":1: malformed XML: limit on input amplification factor"):
        read_robot(_write(f'<?xml version="1.0"?><!DOCTYPE m [{entities}]><mujoco model="&i;"/>'))


def test_without_mujoco_the_message_says_what_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "mujoco", None)  # import mujoco now raises ImportError
    with pytest.raises(MissingExtraError) as err:
        read_robot(HAND / "four_bar.xml")
    assert str(err.value).startswith("reading MJCF files needs mujoco, which is not installed")
    assert str(err.value).endswith("pip install 'mechanism-mobility[mujoco]'")


def test_format_by_extension_or_content(tmp_path):
    plain = tmp_path / "model.txt"
    shutil.copy(HAND / "four_bar.xml", plain)
    assert robot_format(plain) == "mjcf" and robot_format(HAND / "four_bar.urdf") == "urdf"
    assert robot_format(MECHANISMS / "four_bar.yaml") is None
    assert mobility.load(plain).joint("C").type == "S"


_FILES: list[Path] = []


def _write(text: str) -> Path:
    """A temporary MJCF file (kept until the session ends: hypothesis calls this many times)."""
    import tempfile

    handle = tempfile.NamedTemporaryFile("w", suffix=".xml", delete=False)
    with handle:
        handle.write(text)
    _FILES.append(Path(handle.name))
    return Path(handle.name)


@pytest.fixture(scope="module", autouse=True)
def _remove_written_files():
    yield
    for path in _FILES:
        path.unlink(missing_ok=True)


# -- free bodies held by the mechanism --------------------------------------------------------

ARM_AND_TOOL = """<mujoco model="arm and tool">
  <worldbody>
    <body name="l1"><joint name="j1" type="hinge" axis="0 0 1"/><geom size=".1"/>
      <body name="l2" pos="1 0 0"><joint name="j2" type="hinge" axis="0 0 1"/><geom size=".1"/></body>
    </body>
    <body name="tool" pos="2 0 0"><freejoint name="tool_free"/><geom size=".1"/></body>
  </worldbody>
  <equality>{}</equality>
</mujoco>"""


@pytest.mark.parametrize("equality, mobility_, dof", [
    ('<weld name="grip" body1="tool" body2="l2"/>', 2, 2),
    ('<connect name="pin" body1="tool" body2="l2" anchor="0 0 0"/>', 5, 4),  # a ball at the tool: M = 2 + 6 - 3; l2's 2 + 3 turns - 1 shared
])
def test_a_free_body_tied_to_a_moving_body_keeps_its_freedoms(equality, mobility_, dof):
    text = ARM_AND_TOOL.format(equality)
    robot = read_robot(_write(text), end_effector="tool")
    notes = " | ".join(robot.notes)
    assert "free joint tool_free of body tool keeps its 6 freedoms: " in notes and "(line 8) ties its subtree to l2, outside it" in notes
    r = mobility.analyze(robot.mechanism)
    assert (r.mobility, r.dof) == (mobility_, dof)
    # MuJoCo keeps every freedom of the free joint: its null space is the second route
    route = assert_agrees_with_mujoco(robot, *mujoco_compile(text), floating=True)
    assert route.mobility == mobility_
    # the same as --floating, which keeps the freedoms of every free joint
    assert mobility.analyze(read_robot(_write(text), end_effector="tool", floating=True).mechanism).mobility == mobility_


def test_a_free_body_tied_only_inside_its_own_subtree_is_still_fixed():
    text = FREE_PENDULUM.replace("</worldbody>", "</worldbody><equality><connect name='own' body1='arm' body2='base' anchor='0 0 1'/></equality>")
    robot = read_robot(_write(text))
    assert any("free joint root of body base treated as fixed" in n for n in robot.notes)
    assert mobility.analyze(robot.mechanism).mobility == 0  # the connect holds the arm to its own (fixed) base


# -- names MuJoCo leaves empty, masses it would refuse --------------------------------------------

UNNAMED_NEXT_TO_BODY1 = """<mujoco model="unnamed">
  <worldbody>
    <body pos="0 -1 0"><joint type="slide" axis="1 0 0"/><geom size="0.1"/></body>
    <body name="body1" pos="0 1 0"><joint name="h" type="hinge" axis="0 0 1"/><geom size="0.1"/>
      <body name="tip" pos="0.5 0 0"><geom size="0.1"/></body>
    </body>
  </worldbody>
  <equality><connect body1="tip" anchor="0 0 0"/></equality>
</mujoco>"""


def test_an_unnamed_body_never_takes_the_name_of_a_named_one():
    # body 1 has no name; the made-up "body1" would merge it with the real body1 (the slider would then
    # carry the hinge, and the connect would lock both: mobility 0 instead of 1)
    robot = read_robot(_write(UNNAMED_NEXT_TO_BODY1))
    m = robot.mechanism
    assert {j.name: j.links for j in m.joints}["h"] == ("world", "body1")
    assert {j.name: j.links for j in m.joints}["body1~2_joint"] == ("world", "body1~2")
    route = assert_agrees_with_mujoco(robot, *mujoco_compile(UNNAMED_NEXT_TO_BODY1))
    assert route.mobility == 1 and mobility.analyze(m).idle_dof == 1  # the slider moves alone; the hinge is held


MASSLESS = """<mujoco model="massless">
  <worldbody>
    <body name="a"><joint name="h" type="hinge" axis="0 0 1"/>
      <body name="b" pos="1 0 0"><joint name="s" type="slide" axis="1 0 0"/></body>
    </body>
  </worldbody>
</mujoco>"""


def test_bodies_without_mass_import_because_kinematics_needs_none():
    with pytest.raises(ValueError, match="mass and inertia"):
        mujoco.MjSpec.from_string(MASSLESS).compile()  # MuJoCo alone refuses the file
    r = mobility.analyze(read_robot(_write(MASSLESS)).mechanism)
    assert (r.mobility, r.dof, r.pattern) == (2, 2, "1T1R")
    # with masses given, MuJoCo compiles it: the same answer by its own Jacobians
    with_mass = MASSLESS.replace('axis="0 0 1"/>', 'axis="0 0 1"/><geom size="0.1"/>').replace('axis="1 0 0"/>', 'axis="1 0 0"/><geom size="0.1"/>')
    assert_agrees_with_mujoco(read_robot(_write(with_mass)), *mujoco_compile(with_mass))


def test_a_weld_pose_near_the_largest_float_is_a_note_without_a_numpy_warning():
    text = """<mujoco><worldbody>
<body name="a"><joint name="j" type="hinge" axis="0 0 1"/><geom size=".1"/>
<body name="b" pos="1 0 0"><joint name="k" axis="0 0 1"/><geom size=".1"/></body></body>
</worldbody><equality><weld body1="a" body2="b" relpose="1e300 0 0 1 0 0 0"/></equality></mujoco>"""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)  # the gap's norm overflowed: a warning on stderr
        robot = read_robot(_write(text))
    assert any("does not hold at qpos0 (its points are 1e+300 apart)" in n for n in robot.notes), robot.notes
    assert mobility.analyze(robot.mechanism).mobility == 1  # b welded to a as placed: the hinge j alone


# -- files MuJoCo would open: pipes, includes ----------------------------------------------------

def _cli(*args: str, cwd: Path, timeout: float = 30) -> subprocess.CompletedProcess:
    """The command line in a child process, so that a wait for ever fails the test instead of stopping the suite."""
    root = Path(__file__).resolve().parent.parent
    env = dict(os.environ, PYTHONPATH=str(root))
    return subprocess.run([sys.executable, "-m", "mobility", *args], capture_output=True, text=True, cwd=cwd, timeout=timeout, env=env)


def test_a_named_pipe_is_refused_without_waiting_even_when_included(tmp_path):
    os.mkfifo(tmp_path / "p.xml")
    done = _cli("analyze", "p.xml", cwd=tmp_path)
    assert (done.returncode, done.stderr) == (2, "mobility: p.xml: is a pipe or socket, expected a mechanism file\n")
    (tmp_path / "model.xml").write_text('<mujoco>\n<worldbody>\n<include file="p.xml"/>\n</worldbody>\n</mujoco>\n')
    done = _cli("analyze", "model.xml", cwd=tmp_path)
    assert (done.returncode, done.stderr) == (2, "mobility: model.xml:3: include: 'p.xml': a pipe or socket; expected a file to include\n")


def _include(tmp_path: Path, target: str, name: str = "model.xml") -> Path:
    path = tmp_path / name
    path.write_text(f'<mujoco>\n<worldbody>\n<body name="a"><joint/><geom size=".1"/></body>\n<include file="{target}"/>\n</worldbody>\n</mujoco>\n')
    return path


def test_an_include_is_checked_before_mujoco_opens_it(tmp_path):
    big = tmp_path / "big.xml"
    with open(big, "wb") as handle:
        handle.truncate(700 * 1024 * 1024)  # sparse: 700 MB that take no room
    (tmp_path / "folder").mkdir()
    cases = {
        "big.xml": r"model\.xml:4: include: 'big\.xml': has 734003200 bytes: with the \d+ bytes read before it, more than the limit of 4194304 bytes .*MOBILITY_MAX_FILE_BYTES",
        "folder": r"model\.xml:4: include: 'folder': a directory; expected a file to include",
        "/dev/zero": r"model\.xml:4: include: '/dev/zero': not a regular file",
        "missing.xml": r"model\.xml:4: include: 'missing\.xml': no such file \(looked in '.*'\); expected a file to include",
        "model.xml": r"model\.xml:4: include: 'model\.xml': included already \(the model file itself\)",
    }
    for target, expected in cases.items():
        with pytest.raises(MechanismFileError) as err:
            read_robot(_include(tmp_path, target))
        assert re.search(expected, str(err.value)), str(err.value)


def test_included_files_are_found_as_mujoco_finds_them_and_named_in_errors(tmp_path):
    # MuJoCo looks in the model's folder first, then in the folder of the file that includes
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "arm.xml").write_text('<mujoco>\n<body name="arm"><joint/><geom size=".1"/>\n<include file="hand.xml"/></body>\n</mujoco>\n')
    (tmp_path / "sub" / "hand.xml").write_text('<mujoco>\n<body name="hand">\n<joint axis="0 nan 1"/><geom size=".1"/></body>\n</mujoco>\n')
    path = _include(tmp_path, "sub/arm.xml")
    with pytest.raises(MechanismFileError) as err:
        read_robot(path)
    assert str(err.value) == f"{tmp_path / 'sub' / 'hand.xml'}:3: joint/@axis: expected finite numbers, got '0 nan 1'"
    (tmp_path / "hand.xml").write_text('<mujoco><body name="top_hand"><joint/><geom size=".1"/></body></mujoco>')  # the model's folder wins
    m = read_robot(path).mechanism
    assert "top_hand" in {link for j in m.joints for link in j.links}
    model, _ = mujoco_compile(path)
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "top_hand") > 0
    # an error MuJoCo finds in an included file: its name and line are unknown to MuJoCo (it says line 0)
    (tmp_path / "hand.xml").write_text('<mujoco>\n<body name="top_hand">\n<joint axis="0 0 0"/><geom size=".1"/></body>\n</mujoco>\n')
    with pytest.raises(MechanismFileError) as err:
        read_robot(path)
    assert str(err.value) == f"{path}: MuJoCo cannot compile it: axis too small in joint; expected a model MuJoCo compiles"


# -- expansion bounded before MuJoCo expands ----------------------------------------------------

@pytest.mark.parametrize("body, expected", [
    ('<replicate count="100" offset="1 0 0">\n<body><joint/><geom size=".1"/></body></replicate>',
     r":4: joint: 100 joints \(count of <replicate> 100\) are more than the limit of 50 \(set MOBILITY_MAX_JOINTS to raise it\)"),
    ('<replicate count="3" offset="1 0 0">\n<replicate count="200" offset="0 1 0">\n<replicate count="200" offset="0 0 1">\n<body><joint/></body></replicate></replicate></replicate>',
     r":6: joint: 120000 joints \(count of <replicate> 3 x 200 x 200\) are more than the limit of 50"),
    ('<replicate count="20" offset="1 0 0">\n<body><geom size=".1"/><geom size=".2"/><site/></body></replicate>',
     r":3: replicate: 80 elements made by the count of <replicate>, <flexcomp> and <composite> \(count of <replicate> 20\) are more than the limit of 50 \(set MOBILITY_MAX_JOINTS"),
    ('<flexcomp name="cloth" type="grid" count="30 30 1" spacing=".1 .1 .1" dim="2"/>',
     r":3: flexcomp\[cloth\]: a deformable body, not supported"),  # refused before its points are made
    ('<composite type="cable" count="1000 1 1"><joint kind="main"/></composite>', r":3: composite: 1000 elements made by the count"),
])
def test_copies_are_counted_before_mujoco_makes_them(monkeypatch, body, expected):
    monkeypatch.setenv("MOBILITY_MAX_JOINTS", "50")
    with pytest.raises(MechanismFileError) as err:
        read_robot(_write(f"<mujoco>\n<worldbody>\n{body}\n</worldbody>\n</mujoco>\n"))
    assert re.search(expected, str(err.value)), str(err.value)


def test_an_included_file_is_counted_with_every_copy_and_limits_can_be_raised(tmp_path, monkeypatch):
    (tmp_path / "leg.xml").write_text('<mujoco><body><joint/><geom size=".1"/></body></mujoco>')
    path = tmp_path / "legs.xml"
    path.write_text('<mujoco>\n<worldbody>\n<replicate count="20" offset="1 0 0">\n<include file="leg.xml"/>\n</replicate>\n</worldbody>\n</mujoco>\n')
    monkeypatch.setenv("MOBILITY_MAX_JOINTS", "79")  # 20 copies of <include>, <body>, <joint>, <geom>
    with pytest.raises(MechanismFileError, match=r"legs\.xml:3: replicate: 80 elements made by the count .* limit of 79"):
        read_robot(path)
    monkeypatch.setenv("MOBILITY_MAX_JOINTS", "80")
    assert len(read_robot(path).mechanism.joints) == 20
    monkeypatch.setenv("MOBILITY_MAX_ELEMENTS", "80")
    with pytest.raises(MechanismFileError, match=r"leg\.xml:1: geom: 82 elements \(included files and copies counted; count of <replicate> 20\) are more than the limit of 80 \(set MOBILITY_MAX_ELEMENTS"):
        read_robot(path)


def test_a_huge_replicate_is_refused_at_once(tmp_path):
    (tmp_path / "many.xml").write_text('<mujoco><worldbody><replicate count="1000000" offset="0.01 0 0">'
                                       '<body name="b"><joint/><geom size=".01"/></body></replicate></worldbody></mujoco>')
    done = _cli("analyze", "many.xml", cwd=tmp_path)
    assert done.returncode == 2 and done.stderr.count("\n") == 1
    assert "many.xml:1: joint: 1000000 joints (count of <replicate> 1000000) are more than the limit of 5000" in done.stderr


# -- numbers, MuJoCo's warnings and messages -----------------------------------------------------

@pytest.mark.parametrize("attributes, expected", [
    ('pos="nan 0 0"', ":4: body[b]/@pos: expected finite numbers, got 'nan 0 0'"),
    ('euler="1e400 0 0"', ":4: body[b]/@euler: expected finite numbers, got '1e400 0 0'"),
    ('><joint name="k" axis="inf 0 1"/', ":4: joint[k]/@axis: expected finite numbers, got 'inf 0 1'"),
])
def test_a_number_that_is_not_finite_is_refused_at_its_line(attributes, expected):
    text = f'<mujoco>\n<worldbody>\n<body name="a"><joint/><geom size=".1"/>\n<body name="b" {attributes}><joint/><geom size=".1"/></body></body>\n</worldbody>\n</mujoco>'
    with pytest.raises(MechanismFileError) as err:
        read_robot(_write(text))
    assert str(err.value).endswith(expected)


def test_mujoco_warnings_become_notes_and_never_reach_the_terminal(tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)  # MuJoCo would also write MUJOCO_LOG.TXT here
    text = (HAND / "four_bar.xml").read_text().replace('<joint name="B"/>', '<joint name="B" damping="nan" range="-inf inf"/>')
    robot = read_robot(_write(text))
    assert "MuJoCo warns: XML contains a 'NaN'. Please check it carefully." in robot.notes
    assert mobility.analyze(robot.mechanism).mobility == 1
    assert capfd.readouterr().err == "" and not (tmp_path / "MUJOCO_LOG.TXT").exists()


def test_mujoco_messages_keep_their_reason_and_never_say_line_0(tmp_path):
    deep = "<mujoco>\n<worldbody>\n" + "<body>\n" * 600 + "<geom size='1'/>" + "</body>" * 600 + "\n</worldbody>\n</mujoco>\n"
    with pytest.raises(MechanismFileError) as err:
        read_robot(_write(deep))
    message = str(err.value)
    assert "Element nesting is too deep" in message and "\n" not in message
    assert re.search(r"\.xml:\d+: MuJoCo cannot compile it: XML parse error 18: ", message) and ":0:" not in message
    (tmp_path / "deep.xml").write_text(deep)
    including = tmp_path / "model.xml"
    including.write_text('<mujoco>\n<worldbody>\n<include file="deep.xml"/>\n</worldbody>\n</mujoco>\n')
    with pytest.raises(MechanismFileError) as err:
        read_robot(including)
    assert str(err.value).startswith(f"{including}:3: include: MuJoCo cannot compile it: Include error: ")
    assert "Element nesting is too deep" in str(err.value)


def test_a_file_whose_first_element_comes_late_is_still_mjcf(tmp_path):
    text = (HAND / "four_bar.xml").read_text()
    commented = tmp_path / "commented.xml"
    commented.write_text("<!-- " + "x" * 70_000 + " -->\n" + text)
    long_root = tmp_path / "long_root.xml"
    long_root.write_text(re.sub(r'<mujoco model="[^"]*"', '<mujoco model="' + "y" * 2_000_000 + '"', text, count=1))
    for path in (commented, long_root):
        assert robot_format(path) == "mjcf"
        assert mobility.analyze(mobility.load(path)).pattern == "1R"


def test_a_huge_value_is_quoted_short(tmp_path):
    path = tmp_path / "long.xml"
    path.write_text('<mujoco><worldbody><body><joint type="' + "A" * 3_000_000 + '"/><geom size="1"/></body></worldbody></mujoco>')
    with pytest.raises(MechanismFileError) as err:
        read_robot(path)
    assert len(str(err.value)) - len(str(path)) < 400 and "AAA..." in str(err.value)


# -- directions MuJoCo would silently replace ------------------------------------------------------

DIRECTION_MODEL = ('<mujoco>\n<worldbody>\n<body name="p"><joint axis="1 0 0"/><geom size=".1"/>\n'
                   '<body name="b" {body}><joint name="j" {joint}/><geom size=".1"/><site name="s" type="capsule" size=".1" {site}/></body></body>\n'
                   '<body name="d" pos="1 0 0"><joint axis="0 1 0"/><geom size=".1"/></body>\n</worldbody>\n{equality}\n</mujoco>\n')
_PLACES = {"axis": ("joint", "joint[j]", 4), "fromto": ("site", "site[s]", 4), "relpose": ("equality", "weld", 7)}


def _direction_model(attribute: str, text: str) -> str:
    element, _, _ = _PLACES.get(attribute, ("body", "body[b]", 4))
    parts = {"body": "", "joint": 'axis="0 0 1"', "site": "", "equality": ""}
    parts[element] = (f'<equality><weld body1="b" body2="d" relpose="{text}"/></equality>' if element == "equality" else f'{attribute}="{text}"')
    return DIRECTION_MODEL.format(**parts)


def _as_written(attribute: str, text: str) -> str:
    """The same direction with numbers near 1 (scaled by the largest, then normalized without overflow): what the file means."""
    numbers = [float.fromhex(t) if t.lower().lstrip("+-").startswith("0x") else float(t) for t in text.split()]

    def unit(vector: list[float]) -> list[float]:
        scaled = [x / max(abs(y) for y in vector) for x in vector]
        return [x / math.hypot(*scaled) for x in scaled]

    if attribute == "fromto":  # the segment's direction, from the origin (in halves: the difference of huge numbers may overflow)
        return " ".join(repr(x) for x in [0.0, 0.0, 0.0] + unit([b / 2 - a / 2 for a, b in zip(numbers[:3], numbers[3:])]))
    head, direction, tail = {"axisangle": ([], numbers[:3], numbers[3:]), "relpose": (numbers[:3], numbers[3:], [])}.get(attribute, ([], numbers, []))
    return " ".join(repr(x) for x in head + unit(direction) + tail)


def _mujoco_state(text: str) -> np.ndarray:
    """What MuJoCo computes at qpos0 that a direction changes: body b's frame, joint j's axis, site s's frame, the weld's residual."""
    model = mujoco.MjModel.from_xml_string(text)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return np.concatenate([data.xmat[2], data.xaxis[1], data.site_xmat[0], data.efc_pos[: data.nefc]])


@pytest.mark.parametrize("attribute, text, refused", [
    ("quat", "1e200 1e200 0 0", True),          # the squares overflow: MuJoCo divides by an infinite norm, uses no rotation
    ("quat", "1e153 1e153 0 0", False),         # below the overflow: normalized as written
    ("quat", "0x1p520 0x1p520 0 0", True),      # hexadecimal numbers, which MuJoCo reads too
    ("quat", "1e-170 1e-170 0 0", True),        # the squares underflow: MuJoCo leaves it unnormalized
    ("quat", "1e-8 1e-8 0 0", True),            # sum of squares 2e-16 < mjEPS
    ("quat", "1e-7 1e-7 0 0", False),           # 2e-14: normalized
    ("quat", "1e200 0 0 0", False),             # MuJoCo's zero quaternion is no rotation, as written
    ("axisangle", "1e200 1e200 0 90", True),
    ("axisangle", "1e200 1e200 0 0", False),    # a turn by nothing, whatever the axis
    ("zaxis", "1e200 1e200 0", True),
    ("zaxis", "0 0 -1e200", False),             # MuJoCo's signed zero keeps -z
    ("axis", "1e154 1e154 0", True),            # a zero joint axis
    ("axis", "1e153 1e153 0", False),
    ("fromto", "0 0 0 1e200 1e200 0", True),
    ("fromto", "0 0 0 0 0 1e200", False),
    ("relpose", "1 0 0 1e200 1e200 0 0", True),  # a weld with a zero quaternion
    ("relpose", "1 0 0 1e-8 1e-8 0 0", True),
    ("relpose", "1 0 0 1e-8 0 0 0", False),     # MuJoCo makes it the identity, as written
])
def test_a_direction_is_refused_exactly_when_mujoco_would_use_another(tmp_path, monkeypatch, attribute, text, refused):
    monkeypatch.chdir(tmp_path)  # a MuJoCo warning writes MUJOCO_LOG.TXT in the working directory
    model = _direction_model(attribute, text)
    differs = not np.allclose(_mujoco_state(model), _mujoco_state(_direction_model(attribute, _as_written(attribute, text))), atol=1e-9)
    assert differs == refused, "MuJoCo's behaviour is not the one this case documents"
    if not refused:
        read_robot(_write(model))
        return
    _, key, line = _PLACES.get(attribute, ("body", "body[b]", 4))
    with pytest.raises(MechanismFileError) as err:
        read_robot(_write(model))
    assert re.search(rf"\.xml:{line}: {re.escape(key)}/@{attribute}: the sum of its squares.* MuJoCo would .*silently use .*; expected "
                     rf"(smaller|larger) numbers \(only the direction counts\), got '{re.escape(text)}'$", str(err.value)), str(err.value)


def test_the_audited_quaternions_are_refused_in_one_line(tmp_path):
    chain = ('<mujoco model="t"><worldbody><body name="b0" quat="{q}" pos="0 0 0.1"><joint name="j0" type="hinge" axis="0 0 1"/><geom size="0.1"/>'
             '<body name="b1" quat="{q}" pos="0 0 0.1"><joint name="j1" type="hinge" axis="0 0 1"/><geom size="0.1"/></body></body></worldbody></mujoco>')
    for name, q in (("t_q.xml", "1e200 1e200 0 0"), ("t_q2.xml", "1e-170 1e-170 0 0")):
        (tmp_path / name).write_text(chain.format(q=q))
        done = _cli("analyze", name, cwd=tmp_path)
        assert done.returncode == 2 and done.stdout == "" and done.stderr.count("\n") == 1
        assert done.stderr.startswith(f"mobility: {name}:1: body[b0]/@quat: the sum of its squares")
    (tmp_path / "t_11.xml").write_text(chain.format(q="1 1 0 0"))
    assert mobility.analyze(mobility.load(tmp_path / "t_11.xml")).dof == 2  # the same chain, written with small numbers


# -- what MuJoCo reads is what was checked ---------------------------------------------------------

SMALL = '<mujoco><body name="small"><joint/><geom size=".1"/></body></mujoco>'


def test_a_dtd_is_refused_since_mujoco_would_open_the_entity_as_written(tmp_path):
    (tmp_path / "small.xml").write_text(SMALL)
    os.mkfifo(tmp_path / "&f;")  # the file MuJoCo opens: its parser skips the DTD and reads '&f;' as written
    (tmp_path / "model.xml").write_text('<?xml version="1.0"?>\n<!DOCTYPE m [<!ENTITY f "small.xml">]>\n'
                                        '<mujoco>\n<worldbody><include file="&f;"/></worldbody>\n</mujoco>\n')
    done = _cli("analyze", "model.xml", cwd=tmp_path)
    assert (done.returncode, done.stdout) == (2, "")
    assert done.stderr == ("mobility: model.xml:2: <!DOCTYPE>: a document type declaration, which MuJoCo skips (it reads '&name;' as written, "
                           "not the entity); expected MJCF without <!DOCTYPE>\n")
    # in an included file too, named with its own line
    (tmp_path / "part.xml").write_text('<!DOCTYPE m>\n<mujoco><body name="p"><joint/><geom size=".1"/></body></mujoco>')
    with pytest.raises(MechanismFileError, match=r"part\.xml:1: <!DOCTYPE>: a document type declaration"):
        read_robot(_include(tmp_path, "part.xml"))


def test_a_tab_in_an_include_name_is_refused_since_mujoco_would_open_it_with_the_tab(tmp_path):
    (tmp_path / "a b.xml").write_text(SMALL)  # what an XML parser reads: the tab becomes a space
    os.mkfifo(tmp_path / "a\tb.xml")  # what MuJoCo opens
    (tmp_path / "model.xml").write_text('<mujoco>\n<worldbody>\n<include file="a\tb.xml"/>\n</worldbody>\n</mujoco>\n')
    done = _cli("analyze", "model.xml", cwd=tmp_path)
    assert (done.returncode, done.stderr) == (2, "mobility: model.xml:3: include/@file: 'a\\tb.xml': a tab or a line break, which MuJoCo keeps "
                                                 "in the name it opens while XML reads a space; expected a file name without tabs or line breaks\n")
    (tmp_path / "model.xml").write_text('<mujoco>\n<worldbody>\n<include file="a b.xml"/>\n</worldbody>\n</mujoco>\n')  # a space is a space
    assert read_robot(tmp_path / "model.xml").mechanism.end_effector == "small"


@pytest.mark.parametrize("encoding, name, expected", [
    ("utf-16", "model.xml", ":1: not UTF-8 text (it starts with a UTF-16 byte order mark); expected a UTF-8 file, the only encoding MuJoCo reads"),
    ("utf-16", "model.mjcf", ":1: not UTF-8 text (it starts with a UTF-16 byte order mark); expected a UTF-8 file, the only encoding MuJoCo reads"),
    ("latin-1", "model.xml", ":3: not UTF-8 text (byte 0xe9 is not valid UTF-8 there); expected a UTF-8 file, the only encoding MuJoCo reads"),
])
def test_an_mjcf_file_mujoco_cannot_read_as_utf8_is_one_clear_line(tmp_path, capsys, encoding, name, expected):
    declaration = '<?xml version="1.0" encoding="ISO-8859-1"?>\n' if encoding == "latin-1" else ""
    text = declaration + '<mujoco>\n<worldbody><body name="caf\u00e9"><joint/><geom size=".1"/></body></worldbody>\n</mujoco>\n'
    path = tmp_path / name
    path.write_bytes(text.encode(encoding))
    if encoding == "utf-16" and name.endswith(".xml"):
        with pytest.raises((ValueError, RuntimeError)):
            mujoco.MjModel.from_xml_path(str(path))  # MuJoCo reads UTF-8 only (Latin-1 bytes would make names that are not text)
    from mobility.cli import main

    assert main(["analyze", str(path)]) == 2
    assert capsys.readouterr().err == f"mobility: {path}{expected}\n"


@pytest.mark.parametrize("option", ["ground", "end_effector"])
def test_an_empty_body_name_is_refused_not_taken_as_the_default(option):
    with pytest.raises(RequestError, match=rf"^{option}: an empty body name; expected the name of a body"):
        read_robot(HAND / "four_bar.xml", **{option: ""})
    with pytest.raises(RequestError, match=rf"^{option}: an empty body name"):
        mobility.load(HAND / "four_bar.xml", **{option: ""})


def test_the_files_read_are_listed(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "arm.xml").write_text('<mujoco><body name="arm"><joint/><geom size=".1"/></body></mujoco>')
    path = _include(tmp_path, "sub/arm.xml")
    files = read_robot(path).files
    assert [os.path.realpath(f) for f in files] == [str(path.resolve()), str((tmp_path / "sub" / "arm.xml").resolve())]


def test_a_file_name_that_is_not_utf8_is_one_line_not_an_internal_error(tmp_path):
    # MuJoCo takes a file name as UTF-8 text: a name of Latin-1 bytes reached it as a TypeError (exit 3)
    folder = os.fsencode(tmp_path) + b"/d\xe4"
    os.mkdir(folder)
    for name in (os.fsencode(tmp_path) + b"/lat\xe4.xml", folder + b"/m.xml"):
        shutil.copy(HAND / "four_bar.xml", name)
        path = os.fsdecode(name)
        with pytest.raises(MechanismFileError, match=r"the file name \(or its folder's\) is not UTF-8 text, which MuJoCo cannot open; rename it$"):
            mobility.load(path)
        done = subprocess.run([sys.executable, "-m", "mobility", "analyze", path], capture_output=True)
        assert done.returncode == 2 and done.stdout == b"" and done.stderr.count(b"\n") == 1 and b"is not UTF-8 text" in done.stderr
