"""URDF import (standard-library parser), cross-checked by MuJoCo's own URDF compiler.

The second route: MuJoCo compiles the same URDF (visuals and collisions
removed, a placeholder inertia on each link, static bodies kept), and its
joint axes and anchors at ``qpos0``, its body Jacobians and -- for a loop
closed in the side file or by ``--close`` -- a ``connect`` equality added
through ``MjSpec`` give the same joints, mobility and twist system.
Published model: the Puma 560 URDF of rtb-data 2.0.0 (MIT), kept unchanged
under ``tests/data/robots/rtb_data``.
"""

from __future__ import annotations

import math
import os
import re
import warnings
import xml.etree.ElementTree as ET
from pathlib import Path

import mujoco
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mobility
from mobility.errors import MechanismFileError, RequestError
from mobility.io.robot_files import RobotOptions, read_robot
from test_mjcf import MujocoRoute, assert_agrees_with_mujoco, compiled_at_qpos0, same_subspace

DATA = Path(__file__).parent / "data" / "robots"
HAND = DATA / "hand"
PUMA = DATA / "rtb_data" / "puma560_robot.urdf"


def mujoco_from_urdf(text: str, connect: tuple[str, str, tuple[float, float, float]] | None = None):
    """MuJoCo's model and data at qpos0 of a URDF, optionally with a connect (body1, body2, anchor in body1)."""
    root = ET.fromstring(text)
    for link in root.iter("link"):
        for tag in ("visual", "collision", "inertial"):
            for el in link.findall(tag):
                link.remove(el)
        inertial = ET.SubElement(link, "inertial")
        ET.SubElement(inertial, "mass", value="1")
        ET.SubElement(inertial, "inertia", ixx="1", iyy="1", izz="1", ixy="0", ixz="0", iyz="0")
    ET.SubElement(ET.SubElement(root, "mujoco"), "compiler", fusestatic="false")
    spec = mujoco.MjSpec.from_string(ET.tostring(root, encoding="unicode"))
    if connect:
        eq = spec.add_equality()
        eq.type, eq.objtype, eq.name1, eq.name2 = mujoco.mjtEq.mjEQ_CONNECT, mujoco.mjtObj.mjOBJ_BODY, connect[0], connect[1]
        eq.data[:3] = connect[2]
    return compiled_at_qpos0(spec)


def joint_geometry(model, data) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    return {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j): (data.xaxis[j].copy(), data.xanchor[j].copy()) for j in range(model.njnt)}


def write(tmp_path: Path, text: str, name: str = "robot.urdf") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


# -- the published serial arm -----------------------------------------------------------------

def test_puma560_joints_are_those_mujoco_compiles():
    robot = read_robot(PUMA)
    m = robot.mechanism
    assert (m.ground, m.end_effector) == ("link1", "link7")
    model, data = mujoco_from_urdf(PUMA.read_text())
    theirs = joint_geometry(model, data)
    assert [j.name for j in m.joints] == list(theirs) == ["j1", "j2", "j3", "j4", "j5", "j6"]
    for j in m.joints:
        axis, anchor = theirs[j.name]
        assert np.allclose(j.axis, axis, atol=1e-12) and np.allclose(j.point, anchor, atol=1e-12), j.name
    r = mobility.analyze(m)
    assert (r.mobility, r.dof) == (6, 5)  # at the zero pose the wrist is singular: j4 and j6 are coaxial
    route = assert_agrees_with_mujoco(robot, model, data)
    assert route.dof == 5
    assert abs(float(np.dot(m.joint("j4").axis, m.joint("j6").axis))) == pytest.approx(1.0)


# A coordinate of a physical file: zero or at least 10 µm in a 2 m robot.  MuJoCo decides with absolute
# tolerances, mobility relative to the mechanism's size (scale-invariant): two parallel axes 1e-116 apart in a
# robot whose every length is of that size are distinct for mobility, coaxial for MuJoCo.
COORDINATE = st.one_of(st.just(0.0), st.floats(1e-5, 2), st.floats(-2, -1e-5))
# Likewise angles: two axes turned 1e-8 rad apart sit at mobility's rank tolerance (Tolerance.rank, 1e-8), where it
# warns of inexact geometry and may count them parallel; MuJoCo's route has its own threshold.
ANGLE = st.one_of(st.just(0.0), st.floats(1e-5, math.pi), st.floats(-math.pi, -1e-5))


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["revolute", "continuous", "prismatic"]),
                          st.tuples(*[COORDINATE] * 3), st.tuples(*[ANGLE] * 3),
                          st.tuples(*[st.floats(-1, 1, allow_subnormal=False)] * 3).filter(lambda a: math.hypot(*a) > 0.1)),
                min_size=1, max_size=4))
def test_origins_rpy_and_axes_agree_with_mujoco(chain):
    LIMIT = '<limit lower="-1" upper="1" effort="1" velocity="1"/>'
    links = "".join(f'<link name="l{i}"/>' for i in range(len(chain) + 1))
    joints = "".join(
        f'<joint name="j{i}" type="{kind}"><parent link="l{i}"/><child link="l{i + 1}"/>'
        f'<origin xyz="{" ".join(map(repr, xyz))}" rpy="{" ".join(map(repr, rpy))}"/><axis xyz="{" ".join(map(repr, axis))}"/>'
        f'{LIMIT if kind != "continuous" else ""}</joint>'
        for i, (kind, xyz, rpy, axis) in enumerate(chain))
    text = f'<robot name="chain">{links}{joints}</robot>'
    path = Path(_tmp()) / "chain.urdf"
    path.write_text(text)
    robot = read_robot(path)
    model, data = mujoco_from_urdf(text)
    theirs = joint_geometry(model, data)
    for j in robot.mechanism.joints:
        axis, anchor = theirs[j.name]
        assert np.allclose(j.axis, axis, atol=1e-9)
        if j.type == "R":
            assert np.allclose(j.point, anchor, atol=1e-9)
    assert_agrees_with_mujoco(robot, model, data)


# -- loops: closing frames and a side file ----------------------------------------------------

def test_four_bar_closed_by_closing_frames():
    robot = read_robot(HAND / "four_bar.urdf", close=[("coupler_tip", "rocker_tip")], end_effector="coupler")
    m = robot.mechanism
    assert [(j.name, j.type, j.links) for j in m.joints] == [
        ("A", "R", ("ground", "crank")), ("B", "R", ("crank", "coupler")), ("D", "R", ("ground", "rocker")),
        ("close_coupler_tip_rocker_tip", "S", ("coupler", "rocker"))]
    assert m.joint("close_coupler_tip_rocker_tip").point == pytest.approx((4, 2.5, 0))
    assert m.joint("A").actuated and not m.joint("D").actuated  # named in a <transmission>
    assert any("the origin of rocker_tip is" in n for n in robot.notes)
    r = mobility.analyze(m)
    assert (r.dof, r.pattern, r.mobility) == (1, "1R", 1)
    same_loop_in_mjcf = mobility.analyze(mobility.load(HAND / "four_bar.xml"))
    assert same_subspace(r.twists, same_loop_in_mjcf.twists, r.dof) < 1e-9
    model, data = mujoco_from_urdf((HAND / "four_bar.urdf").read_text(), connect=("coupler", "rocker", (3, 0.5, 0)))
    assert_agrees_with_mujoco(robot, model, data)


def test_four_bar_closed_by_a_side_file():
    robot = read_robot(HAND / "four_bar.urdf", closures=str(HAND / "four_bar_closures.yaml"), end_effector="coupler")
    c = robot.mechanism.joint("C")
    assert (c.type, c.links) == ("R", ("coupler", "rocker"))
    assert c.point == pytest.approx((4, 2.5, 0)) and c.axis == pytest.approx((0, 0, 1))
    r = mobility.analyze(robot.mechanism)
    assert (r.dof, r.pattern, r.mobility, r.gruebler_kutzbach) == (1, "1R", 1, -2)
    model, data = mujoco_from_urdf((HAND / "four_bar.urdf").read_text(), connect=("coupler", "rocker", (3, 0.5, 0)))
    assert MujocoRoute(model, data, "coupler").mobility == r.mobility


def test_open_tree_without_its_closure():
    r = mobility.analyze(mobility.load(HAND / "four_bar.urdf"))
    assert r.mobility == 3  # three independent joints: the loop is not closed


# -- joint types ------------------------------------------------------------------------------

PLANAR_AND_FLOATING = """<robot name="table">
  <link name="table"/> <link name="puck"/> <link name="drone"/>
  <joint name="slide" type="planar"><parent link="table"/><child link="puck"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/></joint>
  <joint name="fly" type="floating"><parent link="table"/><child link="drone"/><origin xyz="2 0 3"/></joint>
</robot>"""


def test_planar_and_floating_joints(tmp_path):
    path = write(tmp_path, PLANAR_AND_FLOATING)
    robot = read_robot(path, end_effector="puck")
    assert [(j.name, j.type) for j in robot.mechanism.joints] == [("slide", "E")]
    assert robot.mechanism.joint("slide").normal == (0.0, 0.0, 1.0)
    assert "free joint fly (line 4) of body drone treated as fixed (use --floating to keep its 6 freedoms)" in robot.notes
    assert mobility.analyze(robot.mechanism).pattern == "2T1R"
    floating = read_robot(path, end_effector="drone", floating=True).mechanism
    assert [j.type for j in floating.joints] == ["E", "P", "P", "P", "S"]
    assert floating.joint("fly").point == (2.0, 0.0, 3.0)
    r = mobility.analyze(floating)
    assert (r.dof, r.pattern, r.mobility) == (6, "3T3R", 9)


MIMIC = """<robot name="gripper">
  <link name="palm"/> <link name="left"/> <link name="right"/>
  <joint name="l" type="prismatic"><parent link="palm"/><child link="left"/><axis xyz="0 1 0"/></joint>
  <joint name="r" type="prismatic"><parent link="palm"/><child link="right"/><axis xyz="0 -1 0"/>
    <mimic joint="l" multiplier="1"/>
  </joint>
</robot>"""


def test_mimic_is_a_coupling_of_the_two_rates(tmp_path):
    path = write(tmp_path, MIMIC)
    m = read_robot(path).mechanism
    assert m.couplings[0].terms == (("r", 1.0), ("l", -1.0))
    assert mobility.analyze(m).mobility == 1 == mobility.loop_closure(m).mobility  # the two fingers move as one
    assert mobility.analyze(read_robot(write(tmp_path, MIMIC.replace('\n    <mimic joint="l" multiplier="1"/>', ""))).mechanism).mobility == 2
    for bad, words in (('multiplier="0"', ":5: joint[r]/mimic/@multiplier: expected a non-zero number"), ('multiplier="x"', ":5: joint[r]/mimic/@multiplier: expected a number, got 'x'")):
        with pytest.raises(MechanismFileError) as err:
            read_robot(write(tmp_path, MIMIC.replace('multiplier="1"', bad)))
        assert str(err.value).startswith(f"{path}{words}")


# -- bad input --------------------------------------------------------------------------------

J = '<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>'


@pytest.mark.parametrize("text, expected", [
    ('<robot name="r">\n<link name="a">\n</robot>', r":3: malformed XML: mismatched tag"),
    ('<robot name="r" xmlns:xacro="x">\n<xacro:property name="l" value="1"/>\n</robot>', r":2: xacro:property: a xacro file; expected a URDF: expand it first"),
    # xacro's namespace under another prefix: its macros were dropped and the rest analysed (exit 0, links missing)
    ('<robot name="r" xmlns:x="http://www.ros.org/wiki/xacro">\n<link name="a"/><link name="b"/>\n' + J
     + '\n<x:macro name="leg" params="p"><link name="${p}c"/></x:macro>\n<x:leg p="l"/>\n</robot>', r":4: x:macro: a xacro file; expected a URDF: expand it first"),
    ('<sdf version="1.6"/>', r":1: sdf: not a URDF file; expected the root element <robot>"),
    ('<robot name="r">\n<link name="a"/>\n<joint name="j" type="revolute">\n<parent link="a"/><child link="c"/></joint>\n</robot>',
     r":4: joint\[j\]/child: unknown link 'c'; expected a <link> of this robot"),
    ('<robot name="r">\n<link name="base"/><link name="crank"/>\n<joint name="j" type="revolute">\n<parent link="base"/><child link="crnk"/></joint>\n</robot>',
     r":4: joint\[j\]/child: unknown link 'crnk' \(did you mean 'crank'\?\); expected a <link> of this robot"),
    ('<robot name="r">\n<link name="a"/><link name="b"/>\n' + J + '\n<joint name="k" type="fixed"><parent link="a"/><child link="b"/></joint>\n</robot>',
     r":4: joint\[k\]/child: link 'b' already has the parent joint 'j'; expected a tree"),
    ('<robot name="r">\n<link name="a"/><link name="b"/>\n' + J + '\n<joint name="k" type="fixed"><parent link="b"/><child link="a"/></joint>\n</robot>',
     r":1: robot: no root link \(the joints form a cycle\)"),
    ('<robot name="r">\n<link name="a"/><link name="b"/><link name="c"/>\n' + J + '\n</robot>', r":1: robot: several root links \(a, c\)"),
    ('<robot name="r">\n<link name="a"/><link name="b"/>\n' + J.replace('<axis', '<origin xyz="1 2"/><axis') + '\n</robot>',
     r":3: joint\[j\]/origin/@xyz: expected 3 numbers, got '1 2'"),
    ('<robot name="r">\n<link name="a"/><link name="b"/>\n' + J.replace('type="revolute"', 'type="hinge"') + '\n</robot>',
     r":3: joint\[j\]/@type: unknown joint type 'hinge'; expected one of revolute, continuous, prismatic, planar, floating, fixed"),
    ('<robot name="r">\n<link name="a"/><link name="b"/>\n' + J.replace('0 0 1', '0 0 0') + '\n</robot>',
     r":3: joint\[j\]/axis/@xyz: expected a non-zero direction"),
    ('<robot name="r">\n<link name="a"/>\n<link name="a"/>\n</robot>', r":3: link\[a\]: duplicate link name \(first on line 2\)"),
    ('<robot name="r">\n<link name="a"/><link name="b"/>\n' + J + '\n<transmission name="t">\n<joint name="q"/>\n</transmission>\n</robot>',
     r":5: transmission\[t\]/joint: unknown joint 'q'"),
    ('<robot name="r">\n<link name="a"/>\n</robot>', r": no joint can move"),
    ('<robot name="r">\n<link name="a&#x9b;31m"/>\n</robot>', r":2: link\.name: control character '\\x9b' \(code 155\) is not allowed"),
    ('<robot name="r&#x202e;">\n<link name="a"/>\n</robot>', r":1: robot\.name: control character '\\u202e'"),
    ('<robot name="r">\n<link name="a"/><link name="b"/><link name="c"/>\n' + J + '\n' + J.replace('link="a"', 'link="b"').replace('link="b"/><axis', 'link="c"/><axis') + '\n</robot>',
     r":4: joint\[j\]: duplicate joint name \(first on line 3\)"),
    ('<robot name="r">\n<link name="a"/><link name="b"/>\n' + J.replace('<axis', '\n<mimic joint="nosuch"/><axis') + '\n</robot>',
     r":4: joint\[j\]/mimic: unknown joint 'nosuch'; expected a <joint> of this robot"),
])
def test_bad_urdf_is_one_line(tmp_path, text, expected):
    with pytest.raises(MechanismFileError) as err:
        read_robot(write(tmp_path, text))
    assert "\n" not in str(err.value)
    assert re.search(expected, str(err.value)), str(err.value)


@pytest.mark.parametrize("side, expected", [
    ("joints:\n  - {name: C, type: S, links: [coupler, rockr], point: [0, 0, 0]}\n", r"closures\.yaml:2: joints\[0\]\.links\[1\]: no body named 'rockr' \(did you mean 'rocker'\?\) in four_bar\.urdf"),
    ("joints:\n  - {name: C, type: S, links: [coupler, rocker], point: [0, 0, 0], frame: tip}\n", r"closures\.yaml:2: joints\[0\]\.frame: unknown frame 'tip'; expected 'world' or a body of four_bar\.urdf"),
    ("joint:\n  - {name: C}\n", r"closures\.yaml:1: joint: unknown key in a closures file \(did you mean 'joints'\?\)"),
    ("description: nothing\n", r"closures\.yaml:1: joints: missing required key"),
    ("joints:\n  - {name: C, type: R, links: [coupler, rocker], point: [0, 0, 0]}\n", r"closures\.yaml:2: joints\[0\]\.axis: missing"),
    ("joints: []\n", r"closures\.yaml:1: joints: expected at least one closing joint"),  # was read as closing nothing
])
def test_bad_side_file_is_one_line(tmp_path, side, expected):
    path = write(tmp_path, side, "closures.yaml")
    with pytest.raises(MechanismFileError) as err:
        read_robot(HAND / "four_bar.urdf", closures=str(path))
    assert re.search(expected, str(err.value)), str(err.value)


def test_an_xml_file_of_another_kind_is_one_line(tmp_path):
    with pytest.raises(MechanismFileError) as err:
        read_robot(write(tmp_path, '<?xml version="1.0"?>\n<sdf version="1.6"/>', "world.xml"))
    assert str(err.value).endswith("world.xml:2: sdf: not a robot description; expected MJCF (<mujoco>) or URDF (<robot>), or a mechanism file (.yaml)")


def test_bad_close_pairs_and_options():
    with pytest.raises(MechanismFileError, match=r"four_bar\.urdf: close: no body named 'couplr_tip' \(did you mean 'coupler_tip'\?\); expected one of: ground, "):
        read_robot(HAND / "four_bar.urdf", close=[("couplr_tip", "rocker_tip")])
    with pytest.raises(MechanismFileError, match="close: expected two different bodies, got 'crank' twice"):
        read_robot(HAND / "four_bar.urdf", close=[("crank", "crank")])
    with pytest.raises(RequestError, match="unknown option 'grund'"):
        read_robot(HAND / "four_bar.urdf", grund="ground")
    with pytest.raises(RequestError, match="ground: options of robot description files"):
        mobility.load(Path(__file__).parent.parent / "mechanisms" / "four_bar.yaml", ground="ground")


_DIRS: list = []


def _tmp() -> str:
    import tempfile

    if not _DIRS:
        _DIRS.append(tempfile.TemporaryDirectory())
    return _DIRS[0].name


@pytest.fixture(scope="module", autouse=True)
def _cleanup():
    yield
    for d in _DIRS:
        d.cleanup()


# -- bounds: a robot file is read within the same limits as a mechanism file ----------------------

def test_a_robot_file_is_read_within_the_size_limit(tmp_path, capsys):
    huge = tmp_path / "huge"  # /dev/zero is refused before it is read (a device, not a regular file)
    huge.write_bytes(b"<robot name='r'>" + b" " * (4 * 1024 * 1024))
    link = tmp_path / "zero.urdf"
    link.symlink_to(huge)
    from mobility.cli import main

    assert main(["analyze", str(link)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "larger than the limit" in err[0] and "MOBILITY_MAX_FILE_BYTES" in err[0]


def test_a_robot_file_is_held_to_the_joint_limit(tmp_path, monkeypatch):
    monkeypatch.setenv("MOBILITY_MAX_JOINTS", "20")
    n = 21
    links = "".join(f'<link name="l{i}"/>' for i in range(n + 1))
    joints = "".join(f'<joint name="j{i}" type="continuous"><parent link="l{i}"/><child link="l{i + 1}"/>'
                     f'<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/></joint>' for i in range(n))
    path = tmp_path / "chain.urdf"
    path.write_text(f'<robot name="chain">{links}{joints}</robot>')
    with pytest.raises(MechanismFileError, match=r"21 joints are more than the limit of 20 .*MOBILITY_MAX_JOINTS"):
        mobility.load(path)
    monkeypatch.setenv("MOBILITY_MAX_JOINTS", "21")
    assert len(mobility.load(path).joints) == 21


def test_origins_whose_sum_overflows_are_refused_at_the_joint_without_a_warning(tmp_path):
    links = "".join(f'<link name="l{i}"/>' for i in range(4))
    joints = "".join(f'\n<joint name="j{i}" type="revolute"><parent link="l{i}"/><child link="l{i + 1}"/>'
                     f'<origin xyz="1e308 0 0"/><axis xyz="0 0 1"/></joint>' for i in range(3))
    path = write(tmp_path, f'<robot name="far">{links}{joints}\n</robot>')
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a numpy RuntimeWarning would be printed on the terminal
        with pytest.raises(MechanismFileError) as err:
            read_robot(path)
    assert str(err.value) == (f"{path}:3: joint[j1]/origin: the frame of link 'l2', the origins from the root composed, "
                              "is not finite; expected origins whose sum stays finite")


def test_huge_values_are_quoted_short(tmp_path):
    for text in ('<robot name="r"><link name="a"/><link name="b"/>' + J.replace('type="revolute"', 'type="' + "A" * 3_000_000 + '"') + '</robot>',
                 '<robot name="r"><link name="a"/><link name="b"/>' + J.replace('link="a"', 'link="' + "Z" * 3_000_000 + '"') + '</robot>'):
        path = write(tmp_path, text)
        with pytest.raises(MechanismFileError) as err:
            read_robot(path)
        assert len(str(err.value)) - len(str(path)) < 200 and "..." in str(err.value)


# -- numbers and encodings: what is written is what is read ---------------------------------------------

def test_an_axis_too_small_to_keep_its_direction_is_refused(tmp_path):
    text = '<robot name="r">\n<link name="a"/><link name="b"/>\n' + J.replace('0 0 1', '{}') + '\n</robot>'
    with pytest.raises(MechanismFileError) as err:  # subnormal: 7e-324 reads as 5e-324, the direction (5, 7, 0) as (1, 1, 0)
        read_robot(write(tmp_path, text.format("5e-324 7e-324 0")))
    assert str(err.value).endswith(":3: joint[j]/axis/@xyz: numbers below 2.23e-308, the smallest normal double, do not keep their direction "
                                   "in double precision; expected larger numbers (only the direction counts), got '5e-324 7e-324 0'")
    for small, large in (("1e-300 1e-300 0", "1 1 0"), ("1e300 1e300 0", "1 1 0"), ("1e308 1e308 1e308", "1 1 1")):  # normalized without overflow or underflow
        got, want = (read_robot(write(tmp_path, text.format(v))).mechanism.joints[0].axis for v in (small, large))
        assert np.allclose(got, want, rtol=0, atol=1e-15), small


def test_a_utf16_urdf_named_xml_is_read(tmp_path):
    text = '<?xml version="1.0" encoding="UTF-16"?>\n<robot name="r">\n<link name="a"/><link name="b"/>\n' + J + '\n</robot>'
    path = tmp_path / "robot.xml"
    path.write_bytes(text.encode("utf-16"))  # with a byte order mark: Python's XML parser reads it
    robot = read_robot(path)
    assert robot.format == "URDF" and [j.name for j in robot.mechanism.joints] == ["j"]


def test_a_dtd_is_read_since_this_reader_alone_reads_urdf(tmp_path):
    text = '<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY base "a">]>\n<robot name="r">\n<link name="&base;"/><link name="b"/>\n' + J + '\n</robot>'
    assert read_robot(write(tmp_path, text)).mechanism.ground == "a"


@pytest.mark.parametrize("option", ["ground", "end_effector"])
def test_an_empty_body_name_is_refused(option):
    with pytest.raises(RequestError, match=rf"^{option}: an empty body name; expected the name of a body"):
        read_robot(HAND / "four_bar.urdf", **{option: ""})


# -- numbers and elements as MuJoCo's URDF compiler reads them ------------------------------------

ROBOT = '<robot name="r">\n<link name="a"/><link name="b"/>\n{joint}\n</robot>'


@pytest.mark.parametrize("xyz", ["\u0661 \u0662 \u0663", "\uff11 \uff10 \uff10", "1_0 0 0", "1\u00a00 0", "1\u20030 0", "0,0,1", "nan 0 1", "inf 0 1", "0x1 0 0", "1e 0 0"])
def test_a_number_that_is_not_a_plain_decimal_is_refused(tmp_path, xyz):
    text = ROBOT.format(joint=J.replace("0 0 1", xyz))
    with pytest.raises(MechanismFileError) as err:
        read_robot(write(tmp_path, text))
    assert str(err.value).endswith(f":3: joint[j]/axis/@xyz: expected 3 numbers, got {xyz!r}")


@pytest.mark.parametrize("xyz, axis", [("1. 0 0", (1, 0, 0)), (".5 0 0", (1, 0, 0)), ("+1 -0 1e0", (math.sqrt(0.5), 0, math.sqrt(0.5))),
                                       ("0\t0\n1", (0, 0, 1)), ("  0 1E+2 0 ", (0, 1, 0)), ("0 0 2.5e-3", (0, 0, 1))])
def test_plain_decimals_in_every_form_mujoco_reads_are_read(tmp_path, xyz, axis):
    j = read_robot(write(tmp_path, ROBOT.format(joint=J.replace("0 0 1", xyz)))).mechanism.joints[0]
    assert np.allclose(j.axis, axis)


@pytest.mark.parametrize("element", ['<parent link="a"/>', '<child link="b"/>', '<axis xyz="1 0 0"/>', '<origin xyz="0 0 1"/>', '<limit lower="-1" upper="1"/>',
                                     '<mimic joint="j"/>', '<dynamics damping="1"/>'])
def test_an_element_repeated_in_a_joint_is_refused_naming_both_lines(tmp_path, element):
    tag = element[1:].split()[0]
    first = 3 if f"<{tag} " in J else 4  # line 3 holds J and its elements
    joint = J.replace("</joint>", ("\n" + element) * (1 if first == 3 else 2) + "</joint>")
    with pytest.raises(MechanismFileError) as err:
        read_robot(write(tmp_path, ROBOT.format(joint=joint)))
    assert str(err.value).endswith(f":{first + 1}: joint[j]/{tag}: a second <{tag}> in the joint (the first on line {first}); expected one")


def test_a_transmission_joint_without_a_name_says_so(tmp_path):
    text = ROBOT.format(joint=J + '\n<transmission name="t">\n<joint/>\n</transmission>')
    with pytest.raises(MechanismFileError) as err:
        read_robot(write(tmp_path, text))
    assert str(err.value).endswith(':5: transmission[t]/joint: missing attribute name; expected <joint name="...">')


# -- arguments of read_robot and load: a wrong type is a RequestError naming it ----------------------

@pytest.mark.parametrize("options, expected", [
    ({"ground": 3}, r"^ground: expected a body name \(str\), got int$"),
    ({"end_effector": 3}, r"^end_effector: expected a body name \(str\), got int$"),
    ({"ground": ["crank"]}, r"^ground: expected a body name \(str\), got list$"),
    ({"end_effector": b"coupler"}, r"^end_effector: expected a body name \(str\), got bytes$"),
    ({"floating": "yes"}, r"^floating: expected True or False, got str$"),
    ({"ignore_unsupported": 2}, r"^ignore_unsupported: expected True or False, got int$"),
    ({"close": "ab"}, r"^close: expected a list of pairs of body names \[\(A, B\), \.\.\.\], got str$"),
    ({"close": 5}, r"^close: expected a list of pairs of body names \[\(A, B\), \.\.\.\], got int$"),
    ({"close": {"coupler_tip": "rocker_tip"}}, r"^close: expected a list of pairs of body names \[\(A, B\), \.\.\.\], got dict$"),
    ({"close": [("coupler_tip",)]}, r"^close\[0\]: expected a pair of body names \(A, B\), got 1 item$"),
    ({"close": [("coupler_tip", "rocker_tip", "x")]}, r"^close\[0\]: expected a pair of body names \(A, B\), got 3 items$"),
    ({"close": [None]}, r"^close\[0\]: expected a pair of body names \(A, B\), got NoneType$"),
    ({"close": [(1, 2)]}, r"^close\[0\]: expected a pair of body names \(A, B\), got a pair of int and int$"),
    ({"close": [("coupler_tip", "rocker_tip"), "ab"]}, r"^close\[1\]: expected a pair of body names \(A, B\), got str$"),
    ({"close": ("coupler_tip", "rocker_tip")}, r"^close\[0\]: expected a pair of body names \(A, B\), got str \(one pair is written \[\(A, B\)\]\)$"),
    ({"closures": 3}, r"^closures: expected a file name \(str or Path\), got int$"),
    ({"closures": True}, r"^closures: expected a file name \(str or Path\), got bool$"),
    ({"closures": {"joints": []}}, r"^closures: expected a file name \(str or Path\), got dict$"),
    ({"closures": b"four_bar_closures.yaml"}, r"^closures: expected a file name \(str or Path\), got bytes$"),
    ({"closures": "a\x00b.yaml"}, r"^closures: expected a file name without a NUL character, got 'a\\x00b\.yaml'$"),
    ({"options": 3}, r"^options: expected a RobotOptions or None, got int$"),
    ({"options": {"ground": "crank"}}, r"^options: expected a RobotOptions or None, got dict$"),
    ({"options": RobotOptions(ground=3)}, r"^ground: expected a body name \(str\), got int$"),
    ({"options": RobotOptions(close=(("a",),))}, r"^close\[0\]: expected a pair of body names \(A, B\), got 1 item$"),
])
@pytest.mark.parametrize("file", ["four_bar.urdf", "four_bar.xml"])
def test_a_robot_option_of_the_wrong_type_is_refused_naming_it(options, expected, file):
    with pytest.raises(RequestError, match=expected):
        read_robot(HAND / file, **options)
    if "options" not in options:
        with pytest.raises(RequestError, match=expected):
            mobility.load(HAND / file, **options)


@pytest.mark.parametrize("path", [None, 3, True, b"four_bar.urdf"])
def test_read_robot_refuses_what_is_not_a_file_name(path):
    with pytest.raises(RequestError, match=rf"^read_robot: expected a file name \(str or Path\), got {type(path).__name__}$"):
        read_robot(path)


def test_a_close_pair_may_be_a_list_and_the_closures_a_path():
    closed = read_robot(HAND / "four_bar.urdf", close=[["coupler_tip", "rocker_tip"]]).mechanism
    assert [j.type for j in closed.joints][-1] == "S"
    sided = read_robot(HAND / "four_bar.urdf", closures=HAND / "four_bar_closures.yaml", end_effector="coupler").mechanism
    assert [j.name for j in sided.joints] == ["A", "B", "D", "C"]


def test_a_file_descriptor_is_never_read_nor_closed(tmp_path):
    """closures=fd once read the caller's descriptor and closed it (closures=True closed standard output)."""
    fd = os.open(HAND / "four_bar_closures.yaml", os.O_RDONLY)
    try:
        for value in (fd, True, 1, 0):
            with pytest.raises(RequestError, match=r"^closures: expected a file name"):
                mobility.load(HAND / "four_bar.urdf", closures=value)
        os.fstat(fd)  # still open
        os.fstat(1)
    finally:
        os.close(fd)


def test_a_mechanism_file_given_to_read_robot_is_named_as_one():
    path = Path(__file__).parent.parent / "mechanisms" / "four_bar.yaml"
    with pytest.raises(MechanismFileError, match=r"four_bar\.yaml: a mechanism file \(YAML\), not a robot description; expected MJCF or URDF \(read it with mobility\.load\)$"):
        read_robot(path)
