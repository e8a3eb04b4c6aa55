"""Bad robot files (MJCF, URDF): what would make MuJoCo wait, allocate without bound, or answer wrong is refused in one line or read right.

Where a new test goes: a test of an element, attribute or name of a robot file (MJCF or URDF, and the
closures file read with it) that is refused at its file:line, or that MuJoCo or the URDF reader would
read wrong and the importer reads right (with a note), goes here.  It asserts a refusal with
:func:`guards.raises_one_line` through :func:`mobility.io.robot_files.read_robot`, or with
:func:`guards.refused` through the command line, in a child process (:func:`guards.run_child`) wherever
the old behaviour could hang or exhaust memory: then the test fails instead of stopping the suite.  What
holds for every file whatever its format (a device, a pipe, a size) goes in ``test_bad_files.py``; how a
valid robot file is read, in ``test_mjcf.py`` and ``test_urdf.py``.

Found by an audit of the importer: a ``<flexcomp file>`` naming a pipe,
``<size nkey="1000000">``, a 150-byte height field of gigabytes, thousands of
``<connect>`` under a memory limit, equalities turned off by ``<option>``, a
weld's angle given as ``sin(angle/2)``, an upper-case ``.XML``, a body fused
away by ``fusestatic``, a closing joint renamed without a word.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import mujoco
import pytest

import mobility
from mobility.errors import MechanismFileError
from mobility.io.robot_files import read_robot

from guards import PACKAGE_ROOT, raises_one_line, refused, run_child, run_cli

ROOT = Path(__file__).resolve().parent.parent
HAND = ROOT / "tests" / "data" / "robots" / "hand"
HISTORY = hasattr(mujoco.MjSpec().add_actuator(), "nsample")  # actuators' history buffers: newer MuJoCo only
BUILTIN_MESHES = hasattr(mujoco, "mjtMeshBuiltin")  # <mesh builtin>: newer MuJoCo only
ARM = '<body name="arm"><joint name="j" axis="0 0 1"/><geom size=".1"/></body>'
MEMORY_CAP = 2 * 1024**3
"""The address space of a child that reads a hostile file: the old code grew past it (2.4 GB for 1000 x 1000 empty replicates)."""

FOUR_BAR = """<mujoco model="four">
  {option}
  <worldbody>
    <body name="crank"><joint name="A" axis="0 0 1"/><geom size=".1"/>
      <body name="coupler" pos="1 2 0"><joint name="B" axis="0 0 1"/><geom size=".1"/><site name="s1" pos="3 0.5 0"/></body>
    </body>
    <body name="rocker" pos="5 0 0"><joint name="D" axis="0 0 1"/><geom size=".1"/><site name="s2" pos="-1 {rocker_y} 0"/></body>
  </worldbody>
  <equality><connect name="C" site1="s1" site2="s2"/></equality>
</mujoco>
"""


def _model(tmp_path: Path, text: str, name: str = "model.xml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


# -- 0. names and encodings of URDF and MJCF files -------------------------------------------------------


def test_a_robot_name_holding_a_character_reference_to_a_line_break_is_refused(tmp_path):
    for source, written, reference, key, message in (
        ("four_bar.urdf", '<link name="coupler"', '<link name="coupler&#13;"', "link.name", "a line break '\\r' (U+000D) is not allowed in a name"),
        ("four_bar.xml", '<joint name="B"/>', '<joint name="B&#x2028;"/>', "joint.name", "a line separator '\\u2028' (U+2028) is not allowed in a name"),
    ):
        text = (HAND / source).read_text(encoding="utf-8")
        assert written in text
        path = tmp_path / source
        path.write_text(text.replace(written, reference, 1), encoding="utf-8")
        error = raises_one_line(lambda: mobility.load(path), MechanismFileError)
        assert (error.key, error.message) == (key, message)


def test_a_robot_named_after_a_file_name_holding_a_line_break_is_named_on_one_line(tmp_path):
    # a robot without a name attribute is named after its file; a file name may hold a line break, a name may not
    for source, suffix, unnamed in ((HAND / "four_bar.urdf", ".urdf", re.compile(r'<robot name="[^"]*"')),
                                    (HAND / "four_bar.xml", ".xml", re.compile(r'<mujoco model="[^"]*"'))):
        text = source.read_text(encoding="utf-8")
        text = unnamed.sub(unnamed.pattern.split(" ")[0], text, count=1)
        path = tmp_path / f"two\nlines\u2028{suffix}"
        path.write_text(text, encoding="utf-8")
        name = mobility.load(path).name
        assert name == "two\\nlines\\u2028", (source, name)


def test_an_xml_file_in_an_unknown_encoding_is_one_line(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text('<?xml version="1.0" encoding="klingon"?>\n<robot name="r"><link name="a"/></robot>\n')
    assert refused(run_cli("analyze", path)) == f"mobility: {path}:1: unreadable XML (unknown encoding: klingon); expected UTF-8 or another known encoding"


# -- 1. files MuJoCo would read: a flexcomp's mesh file, and the asset files never opened ----------------------

def test_a_flexcomp_reading_a_pipe_is_refused_at_its_line_without_waiting(tmp_path):
    os.mkfifo(tmp_path / "cloth.obj")
    _model(tmp_path, f'<mujoco>\n<worldbody>\n{ARM}\n<flexcomp name="f" type="mesh" file="cloth.obj" dim="2"/>\n</worldbody>\n</mujoco>\n')
    done = run_child("analyze", "model.xml", cwd=tmp_path, timeout=20)
    assert "mobility: model.xml:4: flexcomp[f]: a deformable body, not supported" in refused(done)


def test_a_flexcomp_is_refused_even_when_unsupported_elements_are_left_out(tmp_path):
    # before: left out with a note, yet its 9 points stayed as 27 slide joints (mobility 28, a cloth vertex as end effector)
    path = _model(tmp_path, f'<mujoco>\n<worldbody>\n{ARM}\n<flexcomp name="g" type="grid" count="3 3 1" spacing=".1 .1 .1" dim="2" pos="0 0 2"/>\n'
                            '</worldbody>\n</mujoco>\n')
    raises_one_line(lambda: read_robot(path, ignore_unsupported=True), MechanismFileError, r"model\.xml:4: flexcomp\[g\]: a deformable body, not supported \(not even left out")


def test_a_flex_on_rigid_bodies_is_still_left_out_with_a_note(tmp_path):
    text = f"""<mujoco><worldbody>{ARM}
      <body name="p1" pos="0 0 2"><geom size=".01"/></body><body name="p2" pos="1 0 2"><geom size=".01"/></body>
    </worldbody><deformable><flex name="rod" dim="1" body="p1 p2" vertex="0 0 0 0 0 0" element="0 1"/></deformable></mujoco>"""
    robot = read_robot(_model(tmp_path, text), ignore_unsupported=True)
    assert any(n.startswith("left out flex (line 3): 1 deformable (flex) bodies are not supported") for n in robot.notes), robot.notes
    assert mobility.analyze(robot.mechanism).mobility == 1


def test_mesh_texture_height_field_and_skin_files_are_never_opened(tmp_path):
    for name in ("arm.obj", "wood.png", "ground.png", "hand.skn"):
        os.mkfifo(tmp_path / name)  # opening any of them would wait for ever
    _model(tmp_path, """<mujoco><asset><mesh name="m" file="arm.obj"/><texture name="t" type="2d" file="wood.png"/>
      <hfield name="h" file="ground.png" size="1 1 1 1"/></asset><deformable><skin name="s" file="hand.skn"/></deformable>
      <worldbody><body name="arm"><joint name="j" axis="0 0 1"/><geom type="mesh" mesh="m"/></body></worldbody></mujoco>""")
    done = run_child("analyze", "model.xml", cwd=tmp_path, timeout=20)
    assert done.returncode == 0, done.stderr
    assert "pattern: 1R" in done.stdout


# -- 2. sizes MuJoCo allocates or computes for simulation only ---------------------------------------------------

_PEAK = """
import sys
import mobility
from mobility.io.robot_files import read_robot
robot = read_robot(sys.argv[1])
peak = [line.split()[1] for line in open("/proc/self/status") if line.startswith("VmHWM:")]  # this process's own peak (kB)
print(mobility.analyze(robot.mechanism).mobility, int(peak[0]) // 1024)
"""
"""Reads a file in a child process; prints the mobility and the child's peak memory in MB (``VmHWM``: ``ru_maxrss``
would count the memory of the test process it was forked from)."""


@pytest.mark.parametrize("inside, outside", [
    ('<size nkey="1000000"/>', ""),                 # a million keyframes: minutes
    ('<size nuser_jnt="100000000"/>', ""),          # 800 MB of numbers for each joint
    ('<size nuser_body="100000000"/>', ""),
    ('<size nuserdata="100000000" memory="100G"/>', ""),
    ('<size njmax="100000000" nconmax="100000000" nstack="100000000"/>', ""),
    *([("", '<actuator><motor joint="j" nsample="16000000" delay="1"/><motor joint="j" nsample="16000000" delay="1"/></actuator>')]
      if HISTORY else []),
    ("", '<sensor><user dim="100000000" objtype="joint" objname="j" needstage="pos" datatype="real"/></sensor>'),
    ('<compiler><lengthrange mode="all" useexisting="false" inttotal="100000" timestep="0.0001" interval="100000"/></compiler>',
     '<actuator><motor joint="j"/></actuator>'),   # MuJoCo simulates each actuator for 1e9 steps
])
def test_what_only_simulation_needs_is_left_out_in_seconds_and_little_memory(tmp_path, inside, outside):
    path = _model(tmp_path, f"<mujoco>{inside}<worldbody>{ARM}</worldbody>{outside}</mujoco>")
    done = subprocess.run([sys.executable, "-c", _PEAK, str(path)], capture_output=True, text=True, timeout=20,
                          env=dict(os.environ, PYTHONPATH=PACKAGE_ROOT), cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    mobility_, peak_mb = map(int, done.stdout.split())
    assert mobility_ == 1 and peak_mb < 300, done.stdout


def test_keyframes_written_in_the_file_are_kept(tmp_path):
    path = _model(tmp_path, f'<mujoco><size nkey="5"/><worldbody>{ARM}</worldbody><keyframe><key name="k" qpos="0.5"/></keyframe></mujoco>')
    assert mobility.analyze(read_robot(path).mechanism).mobility == 1


def test_a_height_field_larger_than_the_asset_limit_is_refused_before_mujoco_allocates_it(tmp_path, monkeypatch):
    text = f'<mujoco>\n<asset>\n<hfield name="h" nrow="2000" ncol="1000" size="1 1 1 1"/>\n</asset>\n<worldbody>{ARM}</worldbody>\n</mujoco>'
    path = _model(tmp_path, text)
    err = raises_one_line(lambda: read_robot(path), MechanismFileError)
    assert str(err) == (f"{path}:3: hfield[h]: nrow x ncol = 2000 x 1000: 2000000 points, which MuJoCo allocates as it reads the file; "
                        "expected at most the limit of 1000000 (set MOBILITY_MAX_ASSET_VALUES to raise it)")
    monkeypatch.setenv("MOBILITY_MAX_ASSET_VALUES", "2000000")
    assert mobility.analyze(read_robot(path).mechanism).mobility == 1


def test_the_audited_height_field_is_one_line_at_once(tmp_path):
    _model(tmp_path, f'<mujoco><asset><hfield name="h" nrow="20000" ncol="20000" size="1 1 1 1"/></asset><worldbody>{ARM}</worldbody></mujoco>')
    assert "model.xml:1: hfield[h]: nrow x ncol = 20000 x 20000: 400000000 points" in refused(run_child("analyze", "model.xml", cwd=tmp_path, timeout=20))


def test_builtin_meshes_count_with_the_height_fields(tmp_path, monkeypatch):
    monkeypatch.setenv("MOBILITY_MAX_ASSET_VALUES", "1000")
    meshes = '<mesh name="a" builtin="plate" params="20 20"/>\n<mesh name="b" builtin="supersphere" params="30 1 1"/>\n'
    path = _model(tmp_path, f"<mujoco>\n<asset>\n{meshes}</asset>\n<worldbody>{ARM}</worldbody>\n</mujoco>")
    err = raises_one_line(lambda: read_robot(path), MechanismFileError)
    assert str(err).endswith(":4: mesh[b]: builtin supersphere, resolution 30 squared (params): 900 points; 1300 with the height fields "
                             "and builtin meshes before it, which MuJoCo allocates as it reads the file; expected at most the limit of 1000 "
                             "(set MOBILITY_MAX_ASSET_VALUES to raise it)")
    monkeypatch.setenv("MOBILITY_MAX_ASSET_VALUES", "1300")
    if BUILTIN_MESHES:  # an older MuJoCo refuses the attribute itself
        assert mobility.analyze(read_robot(path).mechanism).mobility == 1


@pytest.mark.parametrize("count", ["-1", "2 -3"])
def test_a_negative_replicate_count_is_refused_at_its_line(tmp_path, count):
    # MuJoCo makes no copy of it and says nothing: before, "no joint can move" or a mechanism without the copies
    path = _model(tmp_path, f'<mujoco>\n<worldbody>\n<body name="b"><joint/><geom size=".1"/></body>\n<replicate count="{count}" offset="1 0 0">\n'
                            f'<body><joint/><geom size=".1"/></body>\n</replicate>\n</worldbody>\n</mujoco>\n')
    err = raises_one_line(lambda: read_robot(path), MechanismFileError)
    assert str(err) == f"{path}:4: replicate/@count: expected a count of 0 or more, got {count!r}"


# -- 3. equalities count as joints ------------------------------------------------------------------------------

def _chain_with_equalities(tmp_path: Path, joints: int, equality: str, count: int) -> Path:
    bodies = "".join(f'<body name="b{k}" pos="{k} 0 0"><joint name="j{k}" axis="0 0 1"/><geom size=".1"/></body>' for k in range(joints))
    equalities = "\n".join(equality.format(k=k % (joints - 1)) for k in range(count))  # bodies b0 ... b(n-2), each to the last
    return _model(tmp_path, f"<mujoco>\n<worldbody>{bodies}</worldbody>\n<equality>\n{equalities}\n</equality>\n</mujoco>\n")


@pytest.mark.parametrize("equality, line", [
    ('<connect body1="b{k}" body2="world" anchor="0 0 0"/>', 10),  # the 7th: 4 joints and 7 equalities
    ('<weld body1="b{k}" body2="b3"/>', 10),  # a weld makes no joint, but six constraint rows in MuJoCo
])
def test_equalities_count_toward_the_joint_limit_before_mujoco_reads_them(tmp_path, monkeypatch, equality, line):
    monkeypatch.setenv("MOBILITY_MAX_JOINTS", "10")
    path = _chain_with_equalities(tmp_path, 4, equality, 7)
    err = raises_one_line(lambda: read_robot(path), MechanismFileError)
    tag = equality[1:].split()[0]
    assert str(err) == (f"{path}:{line}: {tag}: 11 joints and equalities (7 of them <connect>, <weld> or other equalities, each counted "
                        "as a joint) are more than the limit of 10 (set MOBILITY_MAX_JOINTS to raise it)")
    monkeypatch.setenv("MOBILITY_MAX_JOINTS", "11")
    assert read_robot(path).mechanism.joints


# -- 4. the gap of a connect: whatever the options and the statistic say ------------------------------------------

@pytest.mark.parametrize("flag", ["equality", "constraint"])
def test_equalities_turned_off_still_have_their_gap_noted_and_the_switch_said(tmp_path, flag):
    text = FOUR_BAR.format(option=f'<option><flag {flag}="disable"/></option>', rocker_y="3.5")  # the sites 1 apart
    notes = read_robot(_model(tmp_path, text)).notes
    assert f'the file turns equalities off (<option><flag {flag}="disable"/>): MuJoCo itself would not enforce its 1 connect/weld equality; ' \
           "analysed as written all the same" in notes
    assert any(n.startswith("connect C (line 9) does not hold at qpos0 (its points are 1 apart)") for n in notes), notes


def test_the_gap_is_measured_against_the_mechanism_not_mujocos_statistic(tmp_path):
    text = FOUR_BAR.format(option='<statistic extent="1e10"/>', rocker_y="3.5")
    notes = read_robot(_model(tmp_path, text)).notes
    assert any(n.startswith("connect C (line 9) does not hold at qpos0 (its points are 1 apart)") for n in notes), notes
    assembled = FOUR_BAR.format(option='<statistic extent="1e-10"/>', rocker_y="2.5")  # the sites meet: nothing to say, whatever the extent
    assert not any("does not hold" in n for n in read_robot(_model(tmp_path, assembled)).notes)


# -- 5. a weld's angle in radians ---------------------------------------------------------------------------------

WELD_OF_SITES = """<mujoco><worldbody>
  <body name="a"><joint name="j" axis="0 0 1"/><geom size=".1"/><site name="sa" pos="1 0 0"/></body>
  <body name="b" pos="2 0 0"><joint name="k" axis="0 0 1"/><geom size=".1"/><site name="sb" pos="-1 0 0" euler="0 0 {degrees}"/></body>
</worldbody><equality><weld name="w" {extra}/></equality></mujoco>"""


@pytest.mark.parametrize("degrees, extra, shown", [
    (90, 'site1="sa" site2="sb"', "1.57 rad (90 degrees)"),        # was "0.707 rad": sin(45 degrees)
    (180, 'site1="sa" site2="sb"', "3.14 rad (180 degrees)"),
    (10, 'site1="sa" site2="sb" torquescale="3"', "0.175 rad (10 degrees)"),  # MuJoCo's residual is scaled by torquescale
])
def test_a_weld_gap_is_its_true_angle(tmp_path, degrees, extra, shown):
    notes = read_robot(_model(tmp_path, WELD_OF_SITES.format(degrees=degrees, extra=extra))).notes
    assert any(f"does not hold at qpos0 (its points are 0 apart and its frames {shown} apart)" in n for n in notes), notes


def test_a_weld_by_relpose_has_its_angle_too(tmp_path):
    text = WELD_OF_SITES.format(degrees=0, extra='body1="b" body2="a" relpose="-2 0 0 0.7071067811865476 0 0 0.7071067811865476"')
    notes = read_robot(_model(tmp_path, text)).notes
    assert any("(its points are 0 apart and its frames 1.57 rad (90 degrees) apart)" in n for n in notes), notes


# -- 6. an upper-case .XML, and includes found beside any file ---------------------------------------------------

@pytest.mark.parametrize("name", ["FOUR.XML", "four.Xml", "four.mjcf", "four"])
def test_any_name_is_read_with_its_includes_found_beside_it(tmp_path, monkeypatch, name):
    (tmp_path / "models" / "parts").mkdir(parents=True)
    (tmp_path / "models" / "parts" / "hand.xml").write_text('<mujoco><body name="hand" pos="1 0 0"><joint name="h" axis="0 0 1"/>'
                                                            '<geom size=".1"/></body></mujoco>')
    path = tmp_path / "models" / name
    path.write_text(f'<mujoco model="m"><worldbody>{ARM[:-7]}<include file="parts/hand.xml"/></body></worldbody></mujoco>')
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")  # includes are not looked for in the working directory
    robot = read_robot(path)
    assert [j.name for j in robot.mechanism.joints] == ["j", "h"]
    assert [os.path.realpath(f) for f in robot.files] == [os.path.realpath(path), os.path.realpath(tmp_path / "models" / "parts" / "hand.xml")]


def test_an_upper_case_name_is_checked_like_any_other(tmp_path):
    os.mkfifo(tmp_path / "part.xml")
    _model(tmp_path, "<mujoco>\n<worldbody>\n<include file='part.xml'/>\n</worldbody>\n</mujoco>\n", "ARM.XML")
    assert "mobility: ARM.XML:3: include: 'part.xml': a pipe or socket" in refused(run_child("analyze", "ARM.XML", cwd=tmp_path, timeout=20))


# -- 7. fusestatic keeps every body the file names ----------------------------------------------------------------

def test_a_body_fusestatic_would_fuse_away_can_be_the_end_effector(tmp_path):
    text = """<mujoco><compiler fusestatic="true"/><worldbody><body name="base"><geom size=".1"/>
      <body name="l1" pos="0 0 1"><joint name="j1" axis="0 0 1"/><geom size=".1"/><body name="tool" pos="1 0 0"><geom size=".1"/></body></body>
    </body></worldbody></mujoco>"""
    robot = read_robot(_model(tmp_path, text), end_effector="tool")
    assert robot.mechanism.end_effector == "tool"
    assert "end effector tool is one rigid link with l1" in robot.notes
    assert mobility.analyze(robot.mechanism).pattern == "1R"


# -- 8. a closing joint named like a joint: renamed, and said so -------------------------------------------------

def test_a_connect_named_like_a_joint_is_renamed_with_a_note(tmp_path):
    text = FOUR_BAR.format(option="", rocker_y="2.5").replace('<connect name="C"', '<connect name="A"')
    robot = read_robot(_model(tmp_path, text))
    assert "connect A (line 9) is named like another joint: it is joint A~2 of the mechanism" in robot.notes
    assert [j.name for j in robot.mechanism.joints] == ["A", "B", "D", "A~2"]


def test_a_close_pair_named_like_a_joint_is_renamed_with_a_note(tmp_path):
    text = f'<mujoco><worldbody>{ARM[:-7]}<body name="tip" pos="1 0 0"><joint name="close_arm_tip" type="slide"/><geom size=".1"/>' \
           '</body></body></worldbody></mujoco>'
    robot = read_robot(_model(tmp_path, text), close=[("arm", "tip"), ("arm", "tip")])
    notes = [n for n in robot.notes if "is named like another joint" in n]
    assert notes == ["--close close_arm_tip is named like another joint: it is joint close_arm_tip~2 of the mechanism",
                     "--close close_arm_tip is named like another joint: it is joint close_arm_tip~3 of the mechanism"]
    assert [j.name for j in robot.mechanism.joints] == ["j", "close_arm_tip", "close_arm_tip~2", "close_arm_tip~3"]


def test_a_closures_file_joint_named_like_a_joint_is_renamed_with_a_note(tmp_path):
    closures = tmp_path / "closures.yaml"
    closures.write_text(textwrap.dedent("""\
        joints:
          - {name: B, type: R, links: [coupler, rocker], axis: [0, 0, 1], point: [4, 2.5, 0]}
        """))
    text = FOUR_BAR.format(option="", rocker_y="2.5").replace('<equality><connect name="C" site1="s1" site2="s2"/></equality>', "")
    robot = read_robot(_model(tmp_path, text), closures=closures)
    assert f"closing joint B ({closures}, line 2) is named like another joint: it is joint B~2 of the mechanism" in robot.notes
    assert mobility.analyze(robot.mechanism).mobility == 1


# -- 9. MuJoCo's own rules: where a sub-model's files are read, and every element that multiplies others (issue 33) --

def _sub_model(tmp_path: Path) -> Path:
    """A model attaching a sub-model (``sub/inner.xml``) that includes ``part.xml``; MuJoCo reads it from ``sub/``."""
    sub = tmp_path / "sub"
    sub.mkdir()
    (sub / "inner.xml").write_text('<mujoco model="inner"><worldbody><body name="b"><joint name="j" axis="0 0 1"/><geom size=".1"/>'
                                   '<include file="part.xml"/></body></worldbody></mujoco>')
    (tmp_path / "part.xml").write_text('<mujoco><geom size=".2"/></mujoco>')  # a harmless file of the same name beside the top model
    return _model(tmp_path, '<mujoco model="top"><asset><model name="m" file="sub/inner.xml"/></asset><worldbody><body name="base">'
                            '<joint name="r" axis="0 0 1"/><geom size=".1"/><attach model="m" body="b" prefix="a"/></body></worldbody></mujoco>')


def test_a_file_a_sub_model_includes_is_checked_in_the_sub_models_folder(tmp_path):
    top = _sub_model(tmp_path)
    (tmp_path / "sub" / "part.xml").write_text('<mujoco><geom size=".2"/></mujoco>')
    done = run_child("analyze", str(top), cwd=tmp_path, timeout=30, memory_cap=MEMORY_CAP)
    assert done.returncode == 0 and "mobility M = 2" in done.stdout, done.stderr  # read right where it is harmless
    (tmp_path / "sub" / "part.xml").unlink()
    os.mkfifo(tmp_path / "sub" / "part.xml")  # MuJoCo opens this one: it would wait for ever
    assert "include: 'part.xml': a pipe or socket; expected a file to include" in refused(run_child("analyze", str(top), cwd=tmp_path, timeout=30, memory_cap=MEMORY_CAP))
    (tmp_path / "sub" / "part.xml").unlink()
    (tmp_path / "sub" / "part.xml").write_text("<mujoco><!--" + "x" * (6 * 1024 * 1024) + "--></mujoco>")
    assert "more than the limit of 4194304 bytes" in refused(run_child("analyze", str(top), cwd=tmp_path, timeout=30, memory_cap=MEMORY_CAP))


@pytest.mark.parametrize("inside", ["", "<!-- nothing but a comment -->", "<replicate count=\"1000\"/>", "<replicate count=\"1000\"></replicate>"])
def test_an_empty_replicate_is_counted_before_mujoco_makes_its_copies(tmp_path, inside):
    count = "100000" if "replicate" not in inside else "1000"  # nested: 1000 x 1000 copies of nothing
    text = f'<mujoco><worldbody>{ARM}\n<replicate count="{count}">{inside}</replicate></worldbody></mujoco>'
    done = run_child("analyze", str(_model(tmp_path, text)), cwd=tmp_path, timeout=20, memory_cap=MEMORY_CAP)
    assert "elements made by the count of <replicate>" in refused(done)
    assert "are more than the limit of 5000 (set MOBILITY_MAX_JOINTS to raise it)" in done.stderr


@pytest.mark.parametrize("model_first", [True, False], ids=["model before the attaches", "model after them"])
def test_the_copies_attach_makes_are_counted_before_mujoco_reads_anything(tmp_path, model_first):
    sub = tmp_path / "sub"
    sub.mkdir()
    chain = "".join(f'<body name="l{i}" pos="{i} 0 0"><joint name="j{i}" axis="0 0 1"/><geom size=".1"/></body>' for i in range(1000))  # 1,000 joints
    (sub / "chain.xml").write_text(f'<mujoco model="chain"><worldbody><body name="root">{chain}</body></worldbody></mujoco>')
    attaches = "".join(f'<body name="b{k}"><attach model="c" body="root" prefix="p{k}"/></body>' for k in range(8))
    asset, world = '<asset><model name="c" file="sub/chain.xml"/></asset>', f"<worldbody>{attaches}</worldbody>"
    top = _model(tmp_path, f"<mujoco>{asset + world if model_first else world + asset}</mujoco>")
    done = run_child("analyze", str(top), cwd=tmp_path, timeout=15, memory_cap=MEMORY_CAP)  # 24.6 s before: MuJoCo compiled every copy, then the joint limit refused it
    assert "attach: " in refused(done)
    assert "are more than the limit of 5000" in done.stderr


def test_a_connect_mujoco_drops_is_an_error_not_a_wrong_answer(tmp_path):
    text = FOUR_BAR.format(option="", rocker_y="2.5").replace('<body name="rocker"', '<replicate count="1"><body name="rocker"')
    text = text.replace('<site name="s2" pos="-1 2.5 0"/></body>', '<site name="s2" pos="-1 2.5 0"/></body></replicate>')
    assert "</replicate>" in text
    done = run_child("analyze", str(_model(tmp_path, text)), cwd=tmp_path, timeout=30, memory_cap=MEMORY_CAP)  # mobility 3, DOF 2 before, without a word
    assert "equality: the file declares 1 equality (<connect>, <weld>, ...), MuJoCo kept 0" in refused(done)
    done = run_child("analyze", str(_model(tmp_path, FOUR_BAR.format(option="", rocker_y="2.5"))), cwd=tmp_path, timeout=30, memory_cap=MEMORY_CAP)
    assert done.returncode == 0 and "mobility M = 1" in done.stdout, done.stderr


def test_attach_copies_of_a_model_that_replicates_are_counted_with_its_copies(tmp_path):
    sub = tmp_path / "sub"
    sub.mkdir()
    (sub / "rep.xml").write_text('<mujoco model="rep"><worldbody><body name="root"><replicate count="1000" offset="1 0 0">'
                                 '<body name="l"><joint name="j" axis="0 0 1"/><geom size=".1"/></body></replicate></body></worldbody></mujoco>')
    attaches = "".join(f'<body name="b{k}"><attach model="r" body="root" prefix="p{k}"/></body>' for k in range(8))
    top = _model(tmp_path, f'<mujoco><asset><model name="r" file="sub/rep.xml"/></asset><worldbody>{attaches}</worldbody></mujoco>')
    assert "attach: " in refused(run_child("analyze", str(top), cwd=tmp_path, timeout=15, memory_cap=MEMORY_CAP))
