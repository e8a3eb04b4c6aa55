"""Actuators of imported robot files: one actuator is one input, as MuJoCo counts it (``model.nu``).

The second route is MuJoCo itself: it compiles the same MJCF file, and its
number of actuators ``nu``, each actuator's joint (``actuator_trnid``) and
its row of the transmission Jacobian (``actuator_moment``: the input rate per
joint rate; for a ball joint, per component of the angular velocity in the
body's frame) give the number of inputs and the axis each one turns about.
The importer must give as many actuated freedoms as ``nu``, each about
MuJoCo's axis; what it cannot express (an actuator on a free joint, a URDF
transmission on a planar or floating joint) is refused in one line, never
counted as several inputs.  A URDF transmission on a fixed joint is reported
in a note.  A number written non-zero that reads as 0 (``1e-400``) is
refused in MJCF and URDF, as the expression evaluator of mechanism files
refuses an underflow.
"""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest

from mobility import analyze
from mobility.actuation import check_actuation
from mobility.cli import main
from mobility.errors import MechanismFileError
from mobility.io.robot_files import read_robot


def write(tmp_path: Path, text: str, name: str) -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def one_line_error(capsys, argv: list[str]) -> str:
    """The one line a command prints on stderr for bad input, checked to exit with status 2."""
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    return err[0]


def inputs(mechanism) -> int:
    """The number of inputs of an imported mechanism: each freedom of an actuated joint is one."""
    return sum(j.dof for j in mechanism.joints if j.actuated)


def mujoco_axes(path: Path) -> tuple[int, list[np.ndarray]]:
    """MuJoCo's ``nu`` and, for each actuator on a ball joint, the axis it turns about in the global frame at ``qpos0``.

    The axis is the actuator's row of MuJoCo's own transmission Jacobian
    (``actuator_moment``) over the ball joint's three degrees of freedom
    (the angular velocity in the body's frame), rotated by the body's frame.
    """
    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    moment = np.zeros((model.nu, model.nv))
    mujoco.mju_sparse2dense(moment, data.actuator_moment, data.moment_rownnz, data.moment_rowadr, data.moment_colind)
    axes = []
    for a in range(model.nu):
        joint = int(model.actuator_trnid[a][0])
        assert model.jnt_type[joint] == mujoco.mjtJoint.mjJNT_BALL
        dof = int(model.jnt_dofadr[joint])
        body = int(model.jnt_bodyid[joint])
        axes.append(data.xmat[body].reshape(3, 3) @ moment[a, dof:dof + 3])
    return model.nu, axes


BALL = """<mujoco model="ball">
  <worldbody>
    <body name="arm" pos="0 0 1" euler="0 0 90">
      <joint name="shoulder" type="ball"/>
      <geom size="0.1"/>
      <body name="hand" pos="1 0 0"><geom size="0.1"/></body>
    </body>
  </worldbody>
  <actuator>
{actuators}
  </actuator>
</mujoco>
"""


@pytest.mark.parametrize("actuator", [
    '<motor name="m" joint="shoulder" gear="1 2 0 0 0 0"/>',
    '<motor name="m" joint="shoulder"/>',
    '<general name="m" joint="shoulder" gear="0 0 3"/>',
    '<general name="m" jointinparent="shoulder" gear="0 1 1"/>',
    '<position name="m" joint="shoulder" kp="10" gear="1 0 1"/>',
    '<velocity name="m" joint="shoulder" kv="1" gear="0 1 0"/>',
])
def test_an_actuator_on_a_ball_joint_is_one_input_about_mujocos_axis(tmp_path, actuator):
    path = write(tmp_path, BALL.format(actuators=actuator), "ball.xml")
    nu, (axis,) = mujoco_axes(path)
    robot = read_robot(path)
    m = robot.mechanism
    assert inputs(m) == nu == 1  # the old importer made the ball joint an actuated S: 3 inputs
    (driven,) = [j for j in m.joints if j.actuated]
    assert (driven.name, driven.type, driven.point) == ("shoulder.m", "R", (0.0, 0.0, 1.0))
    assert np.allclose(driven.axis, axis / np.linalg.norm(axis), atol=1e-12)
    check = check_actuation(m)
    assert check.verdict == "actuation-singular" and check.dof == 3  # one input for the ball's three rotations: not valid
    assert [i.name for i in check.inputs] == ["shoulder.m"]
    assert f"ball joint shoulder (line 4) has 1 input, one per actuator: it is the joints {'R shoulder.m (actuated), U shoulder' if 'inparent' in actuator else 'U shoulder, R shoulder.m (actuated)'} through its centre" in robot.notes
    without = read_robot(write(tmp_path, BALL.format(actuators=""), "plain.xml")).mechanism
    assert [j.type for j in without.joints] == ["S"]
    a, b = analyze(m), analyze(without)
    assert (a.dof, a.mobility) == (b.dof, b.mobility) == (3, 3)
    assert np.linalg.matrix_rank(np.vstack([a.twists, b.twists]), tol=1e-9) == 3  # the chain through the centre moves as the ball does


def test_three_actuators_on_a_ball_joint_are_three_inputs_each_its_own(tmp_path):
    actuators = "\n".join(f'<motor name="m{k}" joint="shoulder" gear="{g}"/>' for k, g in enumerate(["1 0 0", "1 1 0", "0 1 2"]))
    path = write(tmp_path, BALL.format(actuators=actuators), "ball3.xml")
    nu, axes = mujoco_axes(path)
    m = read_robot(path).mechanism
    assert inputs(m) == nu == 3
    driven = [j for j in m.joints if j.actuated]
    assert [j.name for j in driven] == ["shoulder.m0", "shoulder.m1", "shoulder.m2"] and len(m.joints) == 3
    # turning about the joint of input k changes MuJoCo's input k alone: the pairing is diagonal
    pairing = np.array(axes) @ np.array([j.axis for j in driven]).T
    assert np.allclose(pairing - np.diag(np.diag(pairing)), 0.0, atol=1e-12) and np.all(np.abs(np.diag(pairing)) > 0.1)
    assert check_actuation(m).verdict == "valid"


def test_actuators_adding_no_input_are_noted(tmp_path):
    actuators = '<motor name="a" joint="shoulder" gear="1 0 0"/>\n<position name="b" joint="shoulder" gear="2 0 0"/>'
    robot = read_robot(write(tmp_path, BALL.format(actuators=actuators), "same.xml"))
    assert inputs(robot.mechanism) == 1
    assert any("actuator b (line 11) turns the ball joint shoulder about an axis that actuator a already drives: it adds no input" in n for n in robot.notes)
    hinge = BALL.replace('type="ball"', 'type="hinge" axis="0 0 1"').format(actuators=actuators)
    robot = read_robot(write(tmp_path, hinge, "hinge.xml"))
    assert inputs(robot.mechanism) == 1
    assert "actuators a (line 10), b (line 11) all drive joint shoulder: one input (its one freedom), not 2" in robot.notes


def test_a_zero_gear_axis_on_a_ball_joint_is_refused(tmp_path, capsys):
    path = write(tmp_path, BALL.format(actuators='<motor name="m" joint="shoulder" gear="0 0 0 1 0 0"/>'), "zero.xml")
    line = one_line_error(capsys, ["actuation", str(path)])
    assert line.startswith(f"mobility: {path}:10: actuator[m]: ") and "0 0 0" in line and "drives nothing" in line


FREE = """<mujoco model="floating">
  <worldbody>
    <body name="base" pos="0 0 1">
      <joint name="root" type="free"/>
      <geom size="0.1"/>
      <body name="arm"><joint name="elbow" axis="0 0 1"/><geom size="0.1"/></body>
    </body>
  </worldbody>
  <actuator>
    <motor name="thrust" joint="root" gear="0 0 1 0 0 0"/>
    <motor name="drive" joint="elbow"/>
  </actuator>
</mujoco>
"""


@pytest.mark.parametrize("floating", [[], ["--floating"]])
def test_an_actuator_on_a_free_joint_is_refused_not_six_inputs(tmp_path, capsys, floating):
    path = write(tmp_path, FREE, "free.xml")
    assert mujoco.MjModel.from_xml_path(str(path)).nu == 2
    line = one_line_error(capsys, ["actuation", str(path), *floating])
    assert line.startswith(f"mobility: {path}:10: actuator[thrust]: an actuator on the free joint root is not supported: ")
    assert "one input" in line and "six" in line and "--ignore-unsupported" in line
    robot = read_robot(path, floating=bool(floating), ignore_unsupported=True)
    assert inputs(robot.mechanism) == 1 and [j.name for j in robot.mechanism.joints if j.actuated] == ["elbow"]
    assert any(n.startswith("left out actuator[thrust] (line 10): ") for n in robot.notes)


def test_a_ball_actuators_name_is_kept_apart_from_a_connects(tmp_path):
    text = BALL.format(actuators='<motor name="m" joint="shoulder"/>').replace(
        "</worldbody>", '</worldbody>\n  <equality><connect name="shoulder.m" body1="hand" body2="world" anchor="0 0 0"/></equality>')
    m = read_robot(write(tmp_path, text, "named.xml")).mechanism
    assert sorted(j.name for j in m.joints) == ["shoulder", "shoulder.m", "shoulder.m~2"]
    assert [j.name for j in m.joints if j.actuated] == ["shoulder.m"]


URDF = """<robot name="r">
  <link name="base"/> <link name="slider"/> <link name="tip"/>
  <joint name="move" type="{kind}">
    <parent link="base"/> <child link="slider"/> <axis xyz="0 0 1"/>
  </joint>
  <joint name="weld" type="fixed">
    <parent link="slider"/> <child link="tip"/> <origin xyz="1 0 0"/>
  </joint>
  <transmission name="t"><joint name="{driven}"/></transmission>
</robot>
"""


@pytest.mark.parametrize("kind, freedoms", [("planar", "three"), ("floating", "six")])
def test_a_transmission_on_a_planar_or_floating_joint_is_refused(tmp_path, capsys, kind, freedoms):
    path = write(tmp_path, URDF.format(kind=kind, driven="move"), "r.urdf")
    line = one_line_error(capsys, ["actuation", str(path), "--floating"])
    assert line.startswith(f"mobility: {path}:9: transmission[t]/joint: a transmission on the {kind} joint move is not supported: ")
    assert f"has {freedoms}" in line
    robot = read_robot(path, floating=True, ignore_unsupported=True)
    assert inputs(robot.mechanism) == 0


def test_a_transmission_on_a_revolute_joint_is_one_input(tmp_path):
    assert inputs(read_robot(write(tmp_path, URDF.format(kind="revolute", driven="move"), "r.urdf")).mechanism) == 1


def test_a_transmission_on_a_fixed_joint_is_noted(tmp_path):
    robot = read_robot(write(tmp_path, URDF.format(kind="revolute", driven="weld"), "r.urdf"))
    assert inputs(robot.mechanism) == 0
    assert "transmission t (line 9) drives the fixed joint weld, which cannot move: no input for it" in robot.notes


# -- numbers that underflow ------------------------------------------------------------------

UNDER_URDF = """<robot name="r">
  <link name="base"/> <link name="arm"/>
  <joint name="j" type="revolute">
    <parent link="base"/> <child link="arm"/>
    <origin xyz="{xyz}" rpy="{rpy}"/> <axis xyz="{axis}"/>
  </joint>
</robot>
"""


@pytest.mark.parametrize("field, values, key, word", [
    ("xyz", "0 0 1e-400", "joint[j]/origin/@xyz", "1e-400"),
    ("rpy", "-2.5E-999 0 0", "joint[j]/origin/@rpy", "-2.5E-999"),
    ("axis", "1 0 .000001e-320", "joint[j]/axis/@xyz", ".000001e-320"),
])
def test_a_urdf_number_that_underflows_to_zero_is_refused(tmp_path, capsys, field, values, key, word):
    numbers = {"xyz": "0 0 1", "rpy": "0 0 0", "axis": "0 0 1", field: values}
    path = write(tmp_path, UNDER_URDF.format(**numbers), "u.urdf")
    line = one_line_error(capsys, ["analyze", str(path)])
    assert line == (f"mobility: {path}:5: {key}: the number '{word}' underflows: it is below the smallest float (4.94e-324) "
                    f"and would read as {float(word)!r}; expected 0 or a larger number, got '{values}'")


def test_urdf_zeros_and_subnormal_numbers_are_read(tmp_path):
    path = write(tmp_path, UNDER_URDF.format(xyz="0e-400 -0.0E+999 1e-310", rpy="0.000 0 0", axis="0 0 1"), "z.urdf")
    assert read_robot(path).mechanism.joints[0].point == (0.0, 0.0, 1e-310)


UNDER_MJCF = """<mujoco>
  <worldbody>
    <body name="b" {attribute}>
      <joint name="s" type="{kind}"/>
      <geom size="0.1"/>
    </body>
  </worldbody>
  <actuator><motor name="m" joint="s" {gear}/></actuator>
</mujoco>
"""


@pytest.mark.parametrize("attribute, kind, gear, line, key, word", [
    ('pos="0 0 1e-400"', "hinge", "", 3, "body[b]/@pos", "1e-400"),
    ('euler="0 0 -7e-1000"', "hinge", "", 3, "body[b]/@euler", "-7e-1000"),
    ('pos="0 0 1"', "ball", 'gear="1e-400 0 1"', 8, "motor[m]/@gear", "1e-400"),
    ('pos="0x1p-2000 0 1"', "hinge", "", 3, "body[b]/@pos", "0x1p-2000"),
])
def test_an_mjcf_number_that_underflows_to_zero_is_refused(tmp_path, capsys, attribute, kind, gear, line, key, word):
    path = write(tmp_path, UNDER_MJCF.format(attribute=attribute, kind=kind, gear=gear), "u.xml")
    message = one_line_error(capsys, ["analyze", str(path)])
    assert message.startswith(f"mobility: {path}:{line}: {key}: the number '{word}' underflows: it is below the smallest float")
    with pytest.raises(MechanismFileError):
        read_robot(path)


def test_mjcf_zeros_and_subnormal_numbers_are_read(tmp_path):
    path = write(tmp_path, UNDER_MJCF.format(attribute='pos="0e-400 -0x0p-3000 1e-310"', kind="hinge", gear='gear="1 0e-999 0"'), "z.xml")
    if int(mujoco.__version__.split(".")[0]) >= 4:
        assert read_robot(path).mechanism.joints[0].point == (0.0, 0.0, 1e-310)
    else:  # MuJoCo 3.17 (the oldest pyproject.toml allows) refuses a subnormal number itself: one line, MuJoCo's reason
        with pytest.raises(MechanismFileError, match=r"z\.xml:3: body: MuJoCo cannot compile it: number is too large in attribute 'pos'"):
            read_robot(path)
