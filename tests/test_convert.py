"""``mobility convert`` and the robot-file options of ``mobility analyze``: the command line end to end."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

import mobility
from mobility.cli import main
from mobility.io.robot_files import read_robot
from mobility.io.writer import mechanism_to_yaml

DATA = Path(__file__).parent / "data" / "robots"
HAND = DATA / "hand"


def run(capsys, *args):
    status = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return status, out, err


def same_joints(a: mobility.Mechanism, b: mobility.Mechanism) -> None:
    assert (a.ground, a.end_effector) == (b.ground, b.end_effector)
    assert len(a.joints) == len(b.joints)
    for x, y in zip(a.world_joints, b.world_joints):
        assert (x.name, x.type, x.links, x.actuated) == (y.name, y.type, y.links, y.actuated)
        for key in ("axis", "point", "normal"):
            u, v = getattr(x, key), getattr(y, key)
            assert (u is None) == (v is None) or x.type == "P", key  # a P joint's point is not written
            if u is not None and v is not None:
                assert np.allclose(u, v, atol=1e-11), (x.name, key)


@pytest.mark.parametrize("source, options", [
    (HAND / "3rps.xml", ["--end-effector", "platform"]),
    (HAND / "four_bar.urdf", ["--closures", HAND / "four_bar_closures.yaml", "--end-effector", "coupler"]),
    (DATA / "rtb_data" / "puma560_robot.urdf", []),
])
def test_convert_writes_a_file_that_loads_to_the_same_mechanism(tmp_path, capsys, source, options):
    out_file = tmp_path / "converted.yaml"
    status, out, err = run(capsys, "convert", source, "-o", out_file, *options)
    assert status == 0 and out == ""
    assert err.splitlines()[-1].startswith(f"mobility: wrote {out_file} (")
    converted = mobility.load(out_file)
    keyword = {"--end-effector": "end_effector", "--closures": "closures"}
    given = {keyword[k]: str(v) for k, v in zip(options[::2], options[1::2])}
    same_joints(converted, read_robot(source, **given).mechanism)
    a, b = mobility.analyze(converted), mobility.analyze(mobility.load(source, **given))
    assert (a.dof, a.pattern, a.mobility) == (b.dof, b.pattern, b.mobility)
    assert converted.length_unit == "m" and "Imported from the" in converted.description


def test_convert_with_expected_passes_mobility_check(tmp_path, capsys):
    out_file = tmp_path / "four_bar.yaml"
    status, _, err = run(capsys, "convert", HAND / "four_bar.xml", "-o", out_file, "--expected")
    assert status == 0 and "mobility: note: end effector: coupler" in err
    text = out_file.read_text()
    assert "expected: {dof: 1, pattern: 1R, mobility: 1, actuation: valid}" in text  # one motor for one DOF
    assert "actuated: true" in text  # the motor on A
    status, out, _ = run(capsys, "check", out_file)
    assert status == 0 and "pass (4 keys)" in out
    urdf = (HAND / "four_bar.urdf").read_text()
    no_motor = tmp_path / "no_motor.urdf"
    no_motor.write_text(urdf[:urdf.index("  <transmission")] + urdf[urdf.index("</transmission>") + len("</transmission>\n"):])
    unactuated = tmp_path / "no_motor.yaml"
    run(capsys, "convert", no_motor, "--close", "coupler_tip", "rocker_tip", "--end-effector", "coupler", "-o", unactuated, "--expected")
    assert "expected: {dof: 1, pattern: 1R, mobility: 1}\n" in unactuated.read_text()  # no joint actuated: no verdict to pin


def test_convert_prints_to_stdout_and_notes_to_stderr(capsys):
    status, out, err = run(capsys, "convert", HAND / "four_bar.urdf", "--close", "coupler_tip", "rocker_tip", "--end-effector", "coupler")
    assert status == 0
    assert out.startswith("name: four-bar\n") and "{name: close_coupler_tip_rocker_tip, type: S, links: [coupler, rocker], point: [4, 2.5, 0]}" in out
    assert all(line.startswith("mobility: note: ") for line in err.splitlines())


def test_analyze_a_robot_file_with_options(capsys):
    status, out, err = run(capsys, "analyze", HAND / "3rps.xml", "--end-effector", "platform", "--json")
    data = json.loads(out)
    assert status == 0 and (data["dof"], data["pattern"], data["mobility"]) == (3, "1T2R", 3)
    assert err == ""  # the end effector was named: nothing to note
    status, out, err = run(capsys, "analyze", HAND / "four_bar.xml")
    assert status == 0 and "pattern: 1R" in out and err.startswith("mobility: note: end effector: coupler")


@pytest.mark.parametrize("args, message", [
    (["analyze", HAND / "four_bar.xml", "--ground", "rockr"], "four_bar.xml: ground: no body named 'rockr' (did you mean 'rocker'?)"),
    (["convert", HAND / "four_bar.urdf", "--close", "crank", "tip"], "four_bar.urdf: close: no body named 'tip'"),
    (["analyze", Path(__file__).parent.parent / "mechanisms" / "four_bar.yaml", "--floating"], "--floating: options of robot description files (MJCF, URDF)"),
    (["convert", DATA / "robosuite" / "xarm7_gripper.xml"], "xarm7_gripper.xml:20: default: MuJoCo cannot compile it"),
])
def test_bad_input_is_one_line_and_exit_2(capsys, args, message):
    status, out, err = run(capsys, *args)
    assert status == 2 and out == ""
    assert len(err.splitlines()) == 1 and message in err and err.startswith("mobility: ")


def test_unwritable_output_is_one_line(tmp_path, capsys):
    missing = tmp_path / "no" / "such" / "dir.yaml"  # refused before the file is read
    status, _, err = run(capsys, "convert", HAND / "four_bar.xml", "-o", missing)
    assert status == 2 and err == f"mobility: -o {missing}: cannot write there: the folder {missing.parent} does not exist\n"
    full = tmp_path / "full.yaml"
    full.symlink_to("/dev/full")
    status, _, err = run(capsys, "convert", HAND / "four_bar.xml", "-o", full)  # the write itself fails: after the note on the end effector
    assert status == 2 and err.splitlines()[-1] == f"mobility: {full}: --output: cannot write the file (No space left on device)" and len(err.splitlines()) == 2


def test_convert_never_writes_over_a_file_the_model_includes(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    part = '<mujoco><body name="p"><joint/><geom size=".1"/></body></mujoco>'
    (tmp_path / "part.xml").write_text(part)
    (tmp_path / "model.xml").write_text('<mujoco model="t"><worldbody><include file="part.xml"/></worldbody></mujoco>')
    (tmp_path / "alias.xml").symlink_to("part.xml")
    (tmp_path / "alias.yaml").symlink_to("part.xml")
    for output in ("alias.yaml", tmp_path / "alias.yaml"):
        status, out, err = run(capsys, "convert", "model.xml", "-o", output)
        assert (status, out) == (2, "") and err == f"mobility: -o {output}: the same file as ./part.xml, which would be overwritten\n"
        assert (tmp_path / "part.xml").read_text() == part
    status, _, err = run(capsys, "convert", "model.xml", "-o", "model.yaml")
    assert status == 0 and mobility.load(tmp_path / "model.yaml").end_effector == "p"


@pytest.mark.parametrize("output", ["", "c.xml", "c.URDF", "c.mjcf"])
def test_convert_writes_only_a_file_that_reads_back_as_yaml(tmp_path, capsys, monkeypatch, output):
    monkeypatch.chdir(tmp_path)
    status, out, err = run(capsys, "convert", HAND / "four_bar.xml", "-o", output)  # '' was standard output; .xml was YAML read as XML
    assert (status, out) == (2, "") and err.startswith(f"mobility: -o {output!r}: expected a name for the YAML file (such as model.yaml), not empty nor with a robot description's extension (")
    assert list(tmp_path.iterdir()) == []
    status, _, _ = run(capsys, "convert", HAND / "four_bar.xml", "-o", "c.txt")  # another name reads back as YAML
    assert status == 0 and mobility.load(tmp_path / "c.txt").end_effector == "coupler"


def test_the_files_read_for_a_robot_file_are_each_named_once():
    from mobility.io.loader import read_file

    read = read_file(HAND / "four_bar.urdf", closures=HAND / "four_bar_closures.yaml", end_effector="coupler")
    assert read.files == (str(HAND / "four_bar.urdf"), str(HAND / "four_bar_closures.yaml"))


@pytest.mark.parametrize("command, output", [("sweep", "c.yaml"), ("view", "c.html"), ("plot", "c.png"), ("convert", "c.yaml")])
def test_no_command_writes_over_the_closures_file_it_read(tmp_path, capsys, monkeypatch, command, output):
    monkeypatch.chdir(tmp_path)
    closures = (HAND / "four_bar_closures.yaml").read_text()
    (tmp_path / output).write_text(closures)
    extra = {"sweep": ["--vary", "A=0:1:2", "--no-progress"], "view": [], "plot": ["--dpi", "30"], "convert": []}[command]
    status, _, err = run(capsys, command, HAND / "four_bar.urdf", "--closures", output, "-o", output, *extra)
    assert status == 2 and err.splitlines()[-1] == f"mobility: -o {output}: the same file as {output}, which would be overwritten"
    assert (tmp_path / output).read_text() == closures


@pytest.mark.parametrize("command, extra", [("sweep", ["--vary", "p_joint=0:1:2", "--no-progress"]), ("view", []), ("plot", ["--dpi", "30"])])
def test_no_command_writes_over_a_file_the_model_includes(tmp_path, capsys, monkeypatch, command, extra):
    monkeypatch.chdir(tmp_path)
    part = '<mujoco><body name="p"><joint/><geom size=".1"/></body></mujoco>'
    output = {"sweep": "part.csv", "view": "part.html", "plot": "part.png"}[command]
    (tmp_path / output).write_text(part)
    (tmp_path / "model.xml").write_text(f'<mujoco model="t"><worldbody><include file="{output}"/></worldbody></mujoco>')
    status, _, err = run(capsys, command, "model.xml", "-o", output, *extra)
    assert status == 2 and err.splitlines()[-1] == f"mobility: -o {output}: the same file as ./{output}, which would be overwritten"
    assert (tmp_path / output).read_text() == part


@pytest.mark.parametrize("suffix, text, line, key", [
    (".urdf", '<robot name="r">\n<link name="a"/><link name="b"/>\n<joint name=" " type="revolute"><parent link="a"/><child link="b"/>'
     '<axis xyz="0 0 1"/></joint>\n</robot>\n', 3, "joint[' ']"),
    (".xml", '<mujoco>\n<worldbody>\n<body name="&#10;">\n<joint name="j" type="hinge"/>\n<geom size="0.1"/>\n</body>\n</worldbody>\n</mujoco>\n',
     3, "body['\\n']"),
])
def test_a_blank_name_in_a_robot_file_is_refused_at_its_line_by_every_command(capsys, tmp_path, suffix, text, line, key):
    # analyze accepted it (a joint printed as nothing), convert refused it blaming the YAML it was writing
    path = tmp_path / f"blank{suffix}"
    path.write_text(text, encoding="utf-8")
    for command in (["analyze"], ["convert", "-o", str(tmp_path / "out.yaml")], ["convert"]):
        status, out, err = run(capsys, *command, str(path))
        assert (status, out) == (2, "") and not (tmp_path / "out.yaml").exists(), (command, err)
        assert err == f"mobility: {path}:{line}: {key}: a name of blank characters only; expected a visible name\n", (command, err)


def test_convert_writes_no_digits_of_round_off(capsys):
    # the parallelogram's joint points are sums of body positions: 0.1 - 0.07 was written 0.030000000000000013
    status, out, _ = run(capsys, "convert", HAND / "parallelogram.xml")
    assert status == 0 and "point: [0.03, " in out
    numbers = re.findall(r"-?\d+\.\d+(?:e-?\d+)?", out)
    assert numbers and not [x for x in numbers if re.search(r"(?:0{6,}|9{6,})\d{1,3}$", x.split("e")[0])]  # no 0.15000000000000002
    joints = lambda text: [line for line in text.splitlines() if line.startswith("  - {")]  # noqa: E731
    assert joints(mechanism_to_yaml(mobility.loads(out))) == joints(out)  # idempotent: written again as the same text
