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
import re
import shutil
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.linalg import subspace_angles

import mobility
from mobility.errors import MechanismFileError, MissingExtraError
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


def same_subspace(a: np.ndarray, b: np.ndarray) -> float:
    """Largest principal angle between the row spaces of a and b (0 when they are the same)."""
    if a.shape[0] == 0 or b.shape[0] == 0:
        assert a.shape[0] == b.shape[0] == 0 or np.allclose(a, 0) and np.allclose(b, 0)
        return 0.0
    ua = np.linalg.svd(a.T, full_matrices=False)[0][:, : np.linalg.matrix_rank(a)]
    ub = np.linalg.svd(b.T, full_matrices=False)[0][:, : np.linalg.matrix_rank(b)]
    assert ua.shape[1] == ub.shape[1]
    return float(np.max(subspace_angles(ua, ub)))


def assert_agrees_with_mujoco(robot_or_mechanism, model, data, *, kinds=(CONNECT, WELD), floating=False) -> MujocoRoute:
    m = getattr(robot_or_mechanism, "mechanism", robot_or_mechanism)
    result = mobility.analyze(m)
    route = MujocoRoute(model, data, m.end_effector, kinds=kinds, floating=floating)
    assert route.dropped < 1e-12 and route.kept > 1e-6, (route.kept, route.dropped)  # a clear rank gap
    assert result.mobility == route.mobility
    assert result.dof == route.dof
    assert same_subspace(result.twists, route.twists) < 1e-8
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
    assert same_subspace(imported.twists, written.twists) < 1e-9


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


def test_published_gripper_joint_coupling_is_reported_not_ignored(tmp_path):
    path = fixed_gripper(tmp_path)
    with pytest.raises(MechanismFileError) as err:
        read_robot(path)
    assert str(err.value) == (
        f"{path}:132: equality/joint[joint0]: a coupling of joints (left_driver_joint, right_driver_joint) is not supported; "
        "expected connect or weld; pass --ignore-unsupported (ignore_unsupported=True) to leave it out")


def test_published_gripper_two_four_bars_closed_by_connect(tmp_path):
    path = fixed_gripper(tmp_path)
    robot = read_robot(path, ignore_unsupported=True)
    m = robot.mechanism
    assert sorted(j.name for j in m.joints if j.type == "S") == ["connect0", "connect1"]
    assert not any(j.actuated for j in m.joints)  # the actuator drives a tendon
    notes = " | ".join(robot.notes)
    assert "left out equality/joint[joint0] (line 132)" in notes
    assert "tendon split (line 123)" in notes and "actuator fingers_actuator (line 136) drives a tendon" in notes
    r = mobility.analyze(m)
    assert (r.mobility, r.dof, r.pattern) == (2, 1, "1T")  # each finger is a parallelogram: it translates
    model, data = mujoco_compile(path)
    route = assert_agrees_with_mujoco(robot, model, data)
    assert route.mobility == 2
    # with the coupling MuJoCo finds one fewer freedom: why it may not be dropped silently
    assert MujocoRoute(model, data, m.end_effector, kinds=(CONNECT, WELD, JOINT_EQ)).mobility == 1


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
    inactive = text.replace('anchor="3 0.5 0"/>', 'anchor="3 0.5 0" active="false"/>')
    robot = read_robot(_write(inactive))
    assert any("equality connect C (line" in n and "inactive" in n for n in robot.notes)
    assert mobility.analyze(robot.mechanism).mobility == 3


def test_tendon_equality_is_unsupported_and_a_tendon_alone_is_a_note():
    text = (HAND / "four_bar.xml").read_text().replace(
        "<equality>", '<tendon><fixed name="sum"><joint joint="A" coef="1"/><joint joint="D" coef="1"/></fixed></tendon>\n  <equality>')
    robot = read_robot(_write(text))
    assert any(n.startswith("tendon sum (line") for n in robot.notes)
    coupled = text.replace("</equality>", '<tendon tendon1="sum"/></equality>')
    with pytest.raises(MechanismFileError, match=r":\d+: equality/tendon\[tendon0\]: a coupling of tendons \(sum\) is not supported"):
        read_robot(_write(coupled))


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
    ("<mujoco><include file='absent.xml'/></mujoco>", r"MuJoCo cannot compile it: .*absent\.xml"),
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
    with pytest.raises(MechanismFileError, match=r": flex: 1 deformable \(flex\) bodies are not supported; expected rigid bodies and joints; pass --ignore-unsupported"):
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
    assert str(err.value).endswith("pip install 'mobility[mujoco]'")


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
