"""The command line: reports, JSON, exit statuses, one-line errors."""

import json
import subprocess
import sys
import textwrap

import pytest

from mobility.cli import main

FOUR_BAR = """\
name: planar four-bar
ground: ground
end_effector: coupler
joints:
  - {name: A, type: R, links: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, links: [crank, coupler],  axis: [0, 0, 1], point: [1, 2, 0]}
  - {name: C, type: R, links: [coupler, rocker], axis: [0, 0, 1], point: [4, 2.5, 0]}
  - {name: D, type: R, links: [rocker, ground],  axis: [0, 0, 1], point: [5, 0, 0]}
expected: {dof: 1, pattern: 1R, mobility: 1}
"""

THREE_PRS = """\
name: 3-PRS
ground: base
end_effector: platform
parameters: {rb: 1.0, rp: 0.5, h: 0.5, l: 1.0}
limbs:
  - copies: 3
    frame: {name: "leg{i+1}", rpy: [0, 0, "120*i"]}
    joints:
      - {name: "P{i+1}", type: P, links: [base, "s{i+1}"], axis: [0, 0, 1]}
      - {name: "R{i+1}", type: R, links: ["s{i+1}", "l{i+1}"], axis: [0, 1, 0], point: [rb, 0, h]}
      - {name: "S{i+1}", type: S, links: ["l{i+1}", platform], point: [rp, 0, "h + sqrt(l**2 - (rb-rp)**2)"]}
"""


def run(capsys, *args):
    status = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return status, out, err


def test_text_report(write_yaml, capsys):
    status, out, err = run(capsys, "analyze", write_yaml(FOUR_BAR))
    assert status == 0 and err == ""
    assert "end-effector DOF: 1   pattern: 1R" in out
    assert "mobility M = 1   (Grübler–Kutzbach count: -2)" in out
    assert "why G–K differs" in out
    assert "structure: parallel(series(A,B), series(D,C))" in out


def test_json_has_the_spec_keys(write_yaml, capsys):
    status, out, _ = run(capsys, "analyze", write_yaml(THREE_PRS), "--json")
    data = json.loads(out)
    assert status == 0
    for key in ("name", "dof", "pattern", "translations", "rotations", "twists", "wrenches", "mobility", "gruebler_kutzbach", "redundant_constraints", "idle_dof"):
        assert key in data
    assert (data["dof"], data["pattern"], data["translations"]) == (3, "1T2R", [[0.0, 0.0, 1.0]])
    assert len(data["twists"]) == 3 and len(data["wrenches"]) == 3
    assert run(capsys, "analyze", write_yaml(THREE_PRS), "--format", "json")[1] == out


def test_limbs_in_their_own_frames(write_yaml, capsys):
    status, out, _ = run(capsys, "analyze", write_yaml(THREE_PRS), "--limbs")
    assert status == 0
    # each limb's constraint is a force along its R axis (y of the limb frame) through its S centre
    assert out.count("constraint force along [0, 1, 0] through [0.5, 0, 1.36603]") == 3
    assert "frame: leg2" in out


@pytest.mark.parametrize(
    "text, expected",
    [
        (FOUR_BAR.replace("[0, 0, 1], point: [1, 2, 0]", "[0, 0, 0], point: [1, 2, 0]"), ":6: joints[1].axis: expected a non-zero direction"),
        (FOUR_BAR.replace("type: R, links: [crank, coupler]", "type: X, links: [crank, coupler]"), ":6: joints[1].type: unknown joint type 'X'"),
        (FOUR_BAR.replace("end_effector: coupler", "end_effector: nowhere"), ":3: end_effector: link 'nowhere' is not joined by any joint"),
        (FOUR_BAR + "  - [oops\n", ":"),
    ],
)
def test_bad_input_is_one_line_with_status_2(write_yaml, capsys, text, expected):
    path = write_yaml(text)
    status, out, err = run(capsys, "analyze", path)
    assert status == 2 and out == ""
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith(f"mobility: {path}") and expected in err


def test_missing_file_and_bad_options(capsys, tmp_path):
    status, _, err = run(capsys, "analyze", tmp_path / "none.yaml")
    assert status == 2 and "no such file" in err
    with pytest.raises(SystemExit) as info:
        main(["analyze"])
    assert info.value.code == 2
    status, _, err = run(capsys, "analyze", tmp_path / "none.yaml", "--tol", "0.5")
    assert status == 2 and "--tol" in err


def test_console_script_runs_as_a_process(write_yaml):
    path = write_yaml(textwrap.dedent(FOUR_BAR))
    done = subprocess.run([sys.executable, "-m", "mobility", "analyze", str(path), "--json"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["dof"] == 1
    done = subprocess.run([sys.executable, "-m", "mobility", "analyze", str(path) + ".missing"], capture_output=True, text=True)
    assert done.returncode == 2 and "Traceback" not in done.stderr
