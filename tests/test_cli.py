"""The command line: reports, JSON, exit statuses, one-line errors."""

import csv
import errno
import inspect
import io
import json
import os
import re
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

import mobility
from mobility.cli import build_parser, main
from mobility.cli._options import robot_options_from

ROOT = Path(__file__).resolve().parent.parent
HAND = ROOT / "tests" / "data" / "robots" / "hand"

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


# ---------------------------------------------------------------------------
# one mechanism file, read the same way by every command: YAML, MJCF, URDF and the robot options

ONE_FILE_COMMANDS = ["analyze", "actuation", "view", "sweep", "plot", "jacobian", "convert"]


@pytest.mark.parametrize("command", ONE_FILE_COMMANDS)
def test_every_command_reading_one_file_takes_yaml_mjcf_urdf_and_the_robot_options(command, capsys):
    with pytest.raises(SystemExit) as stop:
        main([command, "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert stop.value.code == 0
    file_help = re.search(r"positional arguments: file (.*?) options:", text).group(1)
    assert "YAML" in file_help and "MJCF, URDF" in file_help, file_help
    for option in ("--ground", "--end-effector", "--floating", "--ignore-unsupported", "--close", "--closures"):
        assert option in text, (command, option)
    args = build_parser([command]).parse_args([command, "f.xml", "--ground", "g", "--end-effector", "e", "--floating", "--close", "a", "b",
                              "--closures", "c.yaml", *(["-o", "x.html"] if command in ("view", "plot") else []),
                              *(["--vary", "A=0:1:2"] if command == "sweep" else [])])
    assert robot_options_from(args) == {"ground": "g", "end_effector": "e", "floating": True, "close": (("a", "b"),), "closures": "c.yaml"}


def test_actuation_reads_an_mjcf_file_whose_actuators_mark_the_inputs(capsys):
    status, out, err = run(capsys, "actuation", HAND / "3rps.xml", "--json")
    data = json.loads(out)
    assert status == 0
    assert [i["name"] for i in data["inputs"]] == ["P1", "P2", "P3"]  # the three <motor joint=...>: nothing marked by hand
    assert data["verdict"] == "valid" and data["dof"] == 3
    assert err == "mobility: note: end effector: platform (the body farthest from the ground world; choose another with --end-effector)\n"
    status, out, err = run(capsys, "actuation", HAND / "3rps.xml", "--end-effector", "platform", "--inputs", "P1,P2")
    assert status == 1 and "inputs: P1, P2 (2 for 3 DOF)" in out and err == ""


def test_actuation_poses_are_read_as_the_file_is(capsys):
    # the same robot file given again as a further pose is read with the same options: piston1 as the end effector
    # (1 DOF, so three inputs are redundant there too), not the platform the file's default would give (valid)
    pose = HAND / "3rps.xml"
    status, out, err = run(capsys, "actuation", HAND / "3rps.xml", "--end-effector", "piston1", "--pose", pose)
    assert status == 1 and err == ""
    assert "verdict: REDUNDANT" in out and out.endswith(f"  other poses: 0 of 1 valid\n    {pose}: redundant\n")


def test_view_reads_a_robot_file_with_its_options(tmp_path, capsys):
    page = tmp_path / "v.html"
    status, out, err = run(capsys, "view", HAND / "parallelogram.xml", "-o", page)
    assert status == 0 and "end effector 1 DOF (1T)" in out and "end effector: coupler" in err
    status, out, err = run(capsys, "view", HAND / "parallelogram.xml", "-o", page, "--end-effector", "crank1")
    assert status == 0 and out == f"wrote {page}: parallelogram, end effector 1 DOF (1R), mobility 1\n" and err == ""
    assert "end effector 1 DOF, pattern 1R; mobility 1" in page.read_text()


def test_sweep_reads_a_robot_file_with_its_options(capsys):
    status, out, err = run(capsys, "sweep", HAND / "parallelogram.xml", "--vary", "O1=0:120:3", "--format", "csv")
    assert status == 0 and [line.split(",")[2] for line in out.splitlines()[1:]] == ["1T", "1T", "1T1R"]  # the coupler folds at 120 deg
    assert err.startswith("mobility: note: end effector: coupler")
    status, out, err = run(capsys, "sweep", HAND / "parallelogram.xml", "--vary", "O1=0:120:3", "--format", "csv",
                           "--ground", "world", "--end-effector", "crank1")
    assert status == 0 and err == ""
    assert [line.split(",")[1:4] for line in out.splitlines()[1:]] == [["1", "1R", "1"], ["1", "1R", "1"], ["1", "1R", "2"]]


def test_plot_and_jacobian_read_a_robot_file(tmp_path, capsys):
    status, out, err = run(capsys, "plot", HAND / "3rps.xml", "-o", tmp_path / "p.png", "--end-effector", "platform")
    assert status == 0 and out.endswith("3-RPS, end effector 3 DOF (1T2R)\n") and err == ""
    status, out, err = run(capsys, "jacobian", HAND / "3rps.xml", "--end-effector", "platform", "--json")
    assert status == 0 and json.loads(out)["actuated"] == ["P1", "P2", "P3"]


@pytest.mark.parametrize("command, extra", [
    ("view", ["-o", "v.html"]), ("sweep", ["--vary", "A=0:10:2"]), ("actuation", []), ("plot", ["-o", "p.png"]), ("jacobian", []),
])
def test_robot_options_on_a_yaml_file_are_one_line_and_exit_2(write_yaml, capsys, command, extra):
    path = write_yaml(FOUR_BAR)
    status, out, err = run(capsys, command, path, *extra, "--ground", "crank", "--end-effector", "rocker")
    assert status == 2 and out == ""
    assert err == f"mobility: --ground, --end-effector: options of robot description files (MJCF, URDF), not of the mechanism file {path}\n"


def test_a_robot_option_on_a_flexure_document_is_refused(capsys):
    path = sorted((ROOT / "examples" / "flexure").glob("*.yaml"))[0]
    status, out, err = run(capsys, "actuation", path, "--floating")
    assert status == 2 and out == "" and err.count("\n") == 1
    assert "mobility: --floating: options of robot description files (MJCF, URDF), not of the flexure document" in err


def test_pose_sampler_step_has_one_default():
    from mobility.actuation import enumerate_actuations
    from mobility.core.poses import DEFAULT_STEP, sample_poses

    view = build_parser(["view"]).parse_args(["view", "f.yaml", "-o", "v.html"])
    actuation = build_parser(["actuation"]).parse_args(["actuation", "f.yaml"])
    assert view.step == actuation.step == DEFAULT_STEP == 0.1
    assert inspect.signature(sample_poses).parameters["step"].default == DEFAULT_STEP
    assert inspect.signature(enumerate_actuations).parameters["step"].default == DEFAULT_STEP


# ---------------------------------------------------------------------------
# the idle freedoms: the hint fits the mechanism


def _idle_line(out: str) -> str:
    return next(line for line in out.splitlines() if re.search(r" of the joints (leave|leaves) the end effector still", line))


@pytest.mark.parametrize("name, rods", [("rssr.yaml", 1), ("6sps.yaml", 6), ("delta.yaml", 6), ("h4.yaml", 8)])
def test_idle_freedoms_of_s_s_rods_are_their_spins(capsys, name, rods):
    from mobility.report.idle import spherical_chains

    m = mobility.load(ROOT / "mechanisms" / name)
    assert spherical_chains(m) == mobility.analyze(m).idle_dof == rods  # each rod (or S–P–S leg) spins: one idle freedom each
    status, out, _ = run(capsys, "analyze", ROOT / "mechanisms" / name)
    assert status == 0
    assert f"idle DOF: {rods} motion{'s' if rods > 1 else ''} of the joints leave{'' if rods > 1 else 's'} the end effector still" in _idle_line(out)
    assert _idle_line(out).endswith(f"(e.g. the spin of an S–S rod about the line through its two centres: {rods} such rod{'s' if rods > 1 else ''} here)")


def test_idle_freedoms_of_a_serial_arm_are_its_self_motion(capsys):
    status, out, _ = run(capsys, "analyze", ROOT / "tests" / "data" / "robots" / "robosuite" / "xarm7_robot.xml")
    assert status == 0 and "S–S" not in out
    assert _idle_line(out) == ("    idle DOF: 2 motions of the joints leave the end effector still "
                               "(a self-motion of the serial chain, redundant at this pose: its 7 joint freedoms give the end effector 5 DOF)")
    status, out, _ = run(capsys, "analyze", ROOT / "tests" / "data" / "robots" / "rtb_data" / "puma560_robot.urdf")
    assert status == 0 and "S–S" not in out and _idle_line(out).endswith("its 6 joint freedoms give the end effector 5 DOF)")


def test_idle_freedoms_off_the_path_and_inside_loops():
    from mobility import Joint, Mechanism
    from mobility.report.idle import idle_hint

    x, z = (1, 0, 0), (0, 0, 1)
    hanging = Mechanism("hanging", "g", "e", (
        Joint("A", "R", ("g", "a"), axis=z, point=(0, 0, 0)), Joint("B", "R", ("a", "e"), axis=z, point=(0, 0, 0)),
        Joint("H", "R", ("e", "h"), axis=z, point=(1, 0, 0))))
    r = mobility.analyze(hanging)
    assert r.idle_dof == 2
    assert idle_hint(r) == ("a self-motion of the serial chain, redundant at this pose: its 2 joint freedoms give the end effector 1 DOF; "
                            "a chain off the path from ground to end effector moves alone (H)")
    loop = Mechanism("sliders", "g", "e", (
        Joint("P1", "P", ("g", "a"), axis=x), Joint("P2", "P", ("a", "e"), axis=x), Joint("P3", "P", ("g", "e"), axis=x)))
    r = mobility.analyze(loop)
    assert (r.idle_dof, r.loops) == (1, 1) and idle_hint(r) == "joints inside the loops move against each other"


@pytest.mark.parametrize("scale", [1.0, 1e-6, 1e6])
def test_a_link_between_two_spherical_joints_at_one_point_is_not_called_a_rod(scale):
    # Two S joints at one centre: the link between them turns freely about that point (3 idle freedoms), and
    # there is no line through two centres to spin about (the hint said so); at distinct centres it is a rod.
    from mobility import Joint, Mechanism
    from mobility.report.idle import idle_hint

    def chain(second):
        return Mechanism("two S", "g", "b", (Joint("S1", "S", ("g", "a"), point=(scale, scale, scale)), Joint("S2", "S", ("a", "b"), point=second)))

    r = mobility.analyze(chain((scale, scale, scale * (1 + 1e-14))))
    assert r.idle_dof == 3 and idle_hint(r) == "a link held by two spherical joints at one point turns freely about it: 1 such link here"
    rod = mobility.analyze(chain((scale, scale, 3 * scale)))
    assert rod.idle_dof == 1 and idle_hint(rod) == "e.g. the spin of an S–S rod about the line through its two centres: 1 such rod here"


@pytest.mark.parametrize("args, message", [
    (["plot", "--graph", "--constraints", "mechanisms/four_bar.yaml", "-o", "{tmp}/g.png"], "mobility: --constraints draws on the mechanism, not on the --graph picture"),
    (["plot", "mechanisms/four_bar.yaml", "-o", "{tmp}/no/such/dir/p.png"], "mobility: -o {tmp}/no/such/dir/p.png: cannot write there: the folder {tmp}/no/such/dir does not exist"),
    (["synthesize", "2T1R", "--samples", "0"], "mobility: --samples must be at least 1 and --verify not negative, got 0 and 2"),
    (["synthesize", "2T1R", "--verify", "-1"], "mobility: --samples must be at least 1 and --verify not negative, got 3 and -1"),
])
def test_plot_and_synthesize_refuse_a_bad_request_in_the_one_line_form(args, message, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(Path(__file__).resolve().parent.parent)
    status = main([a.replace("{tmp}", str(tmp_path)) for a in args])
    out, err = capsys.readouterr()
    assert (status, out, err) == (2, "", message.replace("{tmp}", str(tmp_path)) + "\n")


# ---------------------------------------------------------------------------
# standard output that cannot be written, or whose reader has gone


MOBILITY = [sys.executable, "-m", "mobility"]
BAR = str(ROOT / "mechanisms" / "four_bar.yaml")
STDOUT_COMMANDS = {
    "analyze": ["analyze", BAR],  # a few lines: they fail only when flushed at the end
    "sweep": ["sweep", BAR, "--vary", "A=0:10:3000", "--format", "csv", "--no-progress"],  # 3000 rows: they fail while written
    "convert": ["convert", str(HAND / "four_bar.xml"), "--end-effector", "coupler"],
    "check": ["check", BAR],
    "view": ["view", BAR, "-o", "{tmp}/v.html"],
    "help": ["--help"],
}


@pytest.mark.parametrize("command", STDOUT_COMMANDS.values(), ids=STDOUT_COMMANDS.keys())
def test_a_full_standard_output_is_one_line_and_exit_2(command, tmp_path):
    with open("/dev/full", "w") as full:
        done = subprocess.run(MOBILITY + [a.replace("{tmp}", str(tmp_path)) for a in command], stdout=full, stderr=subprocess.PIPE, text=True)
    # was exit 3 "internal error (OSError ...)"; the flush at interpreter exit must not add a second message (exit 120)
    assert (done.returncode, done.stderr) == (2, "mobility: standard output: cannot write it (No space left on device)\n")


@pytest.mark.parametrize("command", [STDOUT_COMMANDS["analyze"], STDOUT_COMMANDS["sweep"], STDOUT_COMMANDS["help"]], ids=["analyze", "sweep", "help"])
def test_a_reader_that_has_gone_ends_the_command_quietly(command):
    child = subprocess.Popen(MOBILITY + command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    child.stdout.close()  # `| head -0`: nobody reads, every write meets a broken pipe
    err = child.stderr.read()
    assert (child.wait(), err) == (0, "")


def test_a_closed_standard_output_is_one_line_and_exit_2():
    done = subprocess.run(["sh", "-c", 'exec "$@" >&-', "sh", *MOBILITY, "analyze", BAR], capture_output=True, text=True)
    assert (done.returncode, done.stderr) == (2, "mobility: standard output: cannot write it (it is closed)\n")  # was 3 (or a silent 0)


def test_a_failed_write_in_process_is_bad_input_not_an_internal_error(monkeypatch, capsys):
    class Full(io.StringIO):
        def write(self, text):
            raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(sys, "stdout", Full())
    assert main(["analyze", BAR]) == 2
    assert capsys.readouterr().err == "mobility: standard output: cannot write it (No space left on device)\n"


# ---------------------------------------------------------------------------
# robot options given an empty name


@pytest.mark.parametrize("option, what", [("--ground", "a body name"), ("--end-effector", "a body name"), ("--closures", "a file name")])
@pytest.mark.parametrize("command", ["analyze", "convert"])
def test_an_empty_robot_option_is_refused_not_read_as_left_out(command, option, what, capsys):
    status, out, err = run(capsys, command, HAND / "3rps.xml", f"{option}=")  # was the default body (file), silently
    assert (status, out, err) == (2, "", f"mobility: {option}: expected {what}, got an empty one\n")


def test_an_output_named_with_undecodable_bytes_is_reported_on_a_strict_utf8_stdout(tmp_path):
    import os

    name = os.fsdecode(b"bad\xff.csv")
    run = subprocess.run(
        [sys.executable, "-m", "mobility", "sweep", str(ROOT / "mechanisms" / "four_bar.yaml"), "--vary", "A=0:10:3", "--format", "csv", "-o", name],
        capture_output=True, cwd=tmp_path, env=dict(os.environ, PYTHONIOENCODING="utf-8"), timeout=120,
    )
    assert run.returncode == 0, run.stderr
    assert run.stdout.decode("utf-8") == "wrote bad\\xff.csv: 3 poses of planar four-bar (csv)\n"
    assert (tmp_path / name).read_text().startswith("A [deg],dof")


@pytest.mark.parametrize("option, values", [("--closures", ("a.yaml", "b.yaml")), ("--ground", ("world", "crank")), ("--end-effector", ("coupler", "rocker"))])
def test_a_robot_option_given_twice_is_refused_not_overridden(option, values, capsys):
    with pytest.raises(SystemExit) as info:  # argparse's exit, status 2
        main(["analyze", str(HAND / "four_bar.urdf"), option, values[0], option, values[1]])
    out, err = capsys.readouterr()  # the last used to win, the first never read
    assert (info.value.code, out) == (2, "") and err == f"mobility analyze: error: {option} given twice; expected it once (see mobility analyze --help)\n"


def test_joint_names_holding_commas_are_named_in_a_comma_separated_option(tmp_path, capsys):
    # "P,1" is one joint: --actuated P,1,P,2,P,3 names three, not six (and a plain split would find none of them)
    path = tmp_path / "commas.yaml"
    path.write_text((ROOT / "mechanisms" / "3prs.yaml").read_text().replace('name: "P{i+1}"', 'name: "P,{i+1}"'))
    assert main(["jacobian", str(path), "--actuated", "P,1,P,2,P,3", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["actuated"] == ["P,1", "P,2", "P,3"]
    assert main(["actuation", str(path), "--inputs", "P,1, P,2,P,3", "--json"]) == 0
    assert [i["name"] for i in json.loads(capsys.readouterr().out)["inputs"]] == ["P,1", "P,2", "P,3"]
    assert main(["sweep", str(path), "--vary", "P,1=0:1:2", "--inputs", "P,1,P,2,P,3", "--format", "csv"]) == 0
    header, first = list(csv.reader(io.StringIO(capsys.readouterr().out)))[:2]
    assert header[0] == "P,1 [mm]" and dict(zip(header, first))["verdict"] == "valid"
    assert main(["actuation", str(path), "--inputs", "P,4"]) == 2
    assert "unknown joint 'P'" in capsys.readouterr().err  # no joint is called P,4: its parts are names


def test_output_dash_is_standard_output_for_the_commands_that_print_text(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)  # a file named '-' would land here
    four_bar = str(ROOT / "mechanisms" / "four_bar.yaml")
    assert main(["sweep", four_bar, "--vary", "A=0:10:2", "--format", "csv", "-o", "-"]) == 0
    assert capsys.readouterr().out.splitlines()[0].startswith("A [deg],dof,pattern,mobility")
    assert main(["convert", four_bar, "-o", "-"]) == 0
    assert mobility.loads(capsys.readouterr().out).joints == mobility.load(four_bar).joints
    for command in (["plot", four_bar, "-o", "-"], ["view", four_bar, "-o", "-"]):  # a picture or a page is a file
        assert main(command) == 2
        assert capsys.readouterr().err.startswith("mobility: -: ")
    assert list(tmp_path.iterdir()) == []


def _mobility(*args: str, **popen: object) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "mobility", *args], cwd=ROOT, text=True, **popen)


WRONG_EXPECTATION = "name: wrong\nground: g\nend_effector: c\njoints:\n" + "".join(
    f"  - {{name: {n}, type: R, links: [{a}, {b}], axis: [0, 0, 1], point: [{x}, {y}, 0]}}\n"
    for n, a, b, x, y in (("A", "g", "k", 0, 0), ("B", "k", "c", 1, 2), ("C", "c", "r", 4, 2.5), ("D", "r", "g", 5, 0))
) + "expected: {dof: 2}\n"


def test_a_reader_gone_away_keeps_the_commands_own_exit_status(tmp_path):
    # `mobility check designs/ | head` under `set -o pipefail` must still fail when a check fails
    path = tmp_path / "wrong.yaml"
    path.write_text(WRONG_EXPECTATION)
    child = _mobility("check", str(path), stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    child.stdout.close()  # the reader leaves before the first line
    assert child.wait(timeout=60) == 1
    assert child.stderr.read() == ""


def test_ctrl_c_is_one_line_and_status_130(tmp_path):
    # as from a terminal: SIGINT delivered, whatever this suite inherited (a script's background job starts with it ignored,
    # and a program keeps an ignored SIGINT ignored: this test then waited a minute for nothing)
    terminal = lambda: signal.signal(signal.SIGINT, signal.SIG_DFL)  # noqa: E731
    child = _mobility("sweep", "mechanisms/3prs.yaml", "--vary", "P1=-30:30:200", "--vary", "P2=-30:30:200", "--vary", "P3=-30:30:100",
                      "--max-poses", "10000000", "--no-progress", stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=terminal)
    time.sleep(3.0)  # started and sweeping (4 million poses take minutes)
    child.send_signal(signal.SIGINT)
    assert child.wait(timeout=60) == 130
    assert child.stderr.read() == "mobility: interrupted\n" and child.stdout.read() == ""


def test_a_terminal_that_cannot_show_a_character_gets_an_escape_not_an_error():
    env = dict(os.environ, PYTHONIOENCODING="ascii")
    child = _mobility("analyze", "mechanisms/four_bar.yaml", stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    out, err = child.communicate(timeout=60)
    assert (child.returncode, err) == (0, "") and "Gr\\u00fcbler\\u2013Kutzbach count: -2" in out
    for command in (["analyze", "--json", "mechanisms/four_bar.yaml"], ["sweep", "--json", "mechanisms/four_bar.yaml", "--vary", "A=0:1:2"],
                    ["check", "--json", "mechanisms/four_bar.yaml"], ["actuation", "--json", "mechanisms/actuation_3rps.yaml"]):
        child = _mobility(*command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
        out, err = child.communicate(timeout=60)
        assert (child.returncode, err) == (0, "") and out.isascii(), command
        read = json.loads(out)  # a backslash escape such as \xfc was not JSON: the sweep's JSON did not parse
        if command[0] == "analyze":
            assert "Grübler–Kutzbach" in read["gruebler_kutzbach_explanation"]  # the escapes read back as the text


def test_with_standard_error_closed_messages_never_enter_the_output(tmp_path):
    close_stderr = lambda: os.close(2)  # noqa: E731 - the child starts without standard error (`2>&-`)
    child = _mobility("convert", str(HAND / "four_bar.xml"), stdout=subprocess.PIPE, preexec_fn=close_stderr)
    out, _ = child.communicate(timeout=120)
    assert child.returncode == 0 and out.startswith("name: four-bar closed by connect") and "mobility:" not in out
    child = _mobility("analyze", str(tmp_path / "missing.yaml"), stdout=subprocess.PIPE, preexec_fn=close_stderr)
    assert child.communicate(timeout=60)[0] == "" and child.returncode == 2


def test_an_option_of_names_given_none_and_an_output_ending_in_a_slash_are_refused(tmp_path, capsys):
    prs = str(ROOT / "mechanisms" / "3prs.yaml")
    for command, option in ((["actuation", prs, "--inputs", ""], "--inputs"), (["sweep", prs, "--vary", "P1=0:1:2", "--inputs", " , "], "--inputs"),
                            (["jacobian", prs, "--actuated", ""], "--actuated")):
        assert main(command) == 2  # the sweep used to drop the file's actuated joints silently, the actuation to check no input
        assert capsys.readouterr().err.startswith(f"mobility: {option} ")
    for command in (["convert", prs, "-o", f"{tmp_path}/new/"], ["sweep", prs, "--vary", "P1=0:1:2", "-o", f"{tmp_path}/new/"]):
        assert main(command) == 2
        assert "expected a file name, not a folder (it ends with /)" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_a_sweep_written_to_a_csv_or_json_name_is_written_in_that_format(tmp_path, capsys):
    four_bar = str(ROOT / "mechanisms" / "four_bar.yaml")
    for name in ("map.csv", "map.JSON", "map.txt"):
        assert main(["sweep", four_bar, "--vary", "A=0:10:3", "-o", str(tmp_path / name)]) == 0
    assert (tmp_path / "map.csv").read_text().startswith("A [deg],dof,pattern,mobility")
    assert json.loads((tmp_path / "map.JSON").read_text())["poses"] == 3
    assert (tmp_path / "map.txt").read_text().startswith("planar four-bar: sweep of 1 coordinate, 3 poses")
    assert main(["sweep", four_bar, "--vary", "A=0:10:3", "--format", "text", "-o", str(tmp_path / "summary.csv")]) == 0  # --format decides
    assert (tmp_path / "summary.csv").read_text().startswith("planar four-bar: sweep")


@pytest.mark.parametrize("command, status", [("analyze", "0 success, 2 bad input"), ("check", "1 a file disagrees with its expected block"),
                                             ("actuation", "1 otherwise"), ("jacobian", "1 it is singular"), ("synthesize", "1 none is")])
def test_every_commands_help_lists_its_exit_statuses(command, status, capsys):
    with pytest.raises(SystemExit):
        main([command, "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert "Exit status: 0" in help_text and status in help_text and help_text.endswith("3 an internal error; 130 interrupted; 143 terminated.")


def test_actuation_options_that_would_be_ignored_are_refused(capsys):
    rps = str(ROOT / "mechanisms" / "actuation_3rps.yaml")
    for command, said in ((["--k", "2"], "--mode and --k choose the combinations of --enumerate"), (["--mode", "any"], "--mode and --k choose"),
                          (["--enumerate", "--inputs", "P1,P2,P3"], "--inputs checks one choice and --enumerate every combination"),
                          (["--threshold", "0.1"], "--threshold applies to flexure documents")):
        assert main(["actuation", rps, *command]) == 2  # they were silently ignored
        assert capsys.readouterr().err.startswith(f"mobility: {said}")


def test_json_with_another_format_is_refused_before_any_work(capsys):
    four_bar = str(ROOT / "mechanisms" / "four_bar.yaml")
    for command in (["analyze", four_bar, "--json", "--format", "md"], ["sweep", four_bar, "--vary", "A=0:1:2", "--json", "--format", "csv"]):
        assert main(command) == 2  # --json won silently
        assert capsys.readouterr() == ("", f"mobility: --json and --format {command[-1]}: choose one output format\n")


def test_debug_may_follow_the_command_as_the_internal_error_message_suggests(monkeypatch, capsys):
    import mobility.cli.analyze as analyze_command

    def broken(args):
        raise ZeroDivisionError("a planted bug")

    monkeypatch.setattr(analyze_command, "run", broken)
    four_bar = str(ROOT / "mechanisms" / "four_bar.yaml")
    assert main(["analyze", four_bar]) == 3
    assert "rerun with --debug" in capsys.readouterr().err
    for argv in (["analyze", four_bar, "--debug"], ["--debug", "analyze", four_bar]):
        assert main(argv) == 3
        assert "Traceback (most recent call last)" in capsys.readouterr().err


def test_characters_the_pictures_font_lacks_are_one_note_not_a_page_of_warnings(tmp_path, capsys):
    path = tmp_path / "uni.yaml"
    path.write_text((ROOT / "mechanisms" / "four_bar.yaml").read_text(encoding="utf-8").replace("name: A,", "name: 连杆,"), encoding="utf-8")
    assert main(["plot", str(path), "-o", str(tmp_path / "uni.png")]) == 0
    out, err = capsys.readouterr()
    assert out.startswith("wrote ") and (tmp_path / "uni.png").stat().st_size > 0
    assert err == "mobility: note: the picture's font has no glyph for 2 characters of the names (连杆): drawn as boxes\n"


def test_convert_to_standard_output_writes_utf8_yaml_that_reads_back_whatever_the_terminal(tmp_path):
    # escaped for an ASCII terminal, a folded description read back as the escapes' text, and a character beyond
    # the BMP as an invalid YAML escape
    text = (ROOT / "mechanisms" / "four_bar.yaml").read_text(encoding="utf-8").replace("name: planar four-bar", "name: Grübler 𝄞")
    source = tmp_path / "uni.yaml"
    source.write_text(text, encoding="utf-8")
    env = dict(os.environ, PYTHONIOENCODING="ascii")
    child = _mobility("convert", str(source), "-o", "-", stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    out, err = child.communicate(timeout=60)
    assert (child.returncode, err) == (0, "")
    back = tmp_path / "back.yaml"
    back.write_bytes(out.encode("utf-8", "surrogateescape") if isinstance(out, str) else out)
    again = mobility.load(back)
    assert again.name == "Grübler 𝄞" and "Grübler–Kutzbach" in again.description


def test_comma_names_are_found_in_time_linear_in_the_option():
    from mobility.cli._options import names_from

    long_name = ",".join(["x"] * 301)
    started = time.perf_counter()
    found = names_from("x," * 65000, [long_name, "y"])  # took 32 s when every span was tried at every part
    assert time.perf_counter() - started < 5.0
    assert found[:215] == [long_name] * 215 and found[215:] == ["x"] * 285


def test_synthesize_write_refuses_an_empty_folder_name(capsys):
    assert main(["synthesize", "3T", "--write", ""]) == 2
    assert capsys.readouterr().err == "mobility: --write '': expected a folder name\n"


def test_counts_of_one_are_written_in_the_singular():
    from mobility import Joint, Mechanism
    from mobility.report.text import text_report

    slider = Mechanism("one slider", "g", "s", (Joint("P", "P", ("g", "s"), axis=(1, 0, 0)),))
    assert "joints: 1 (1 freedom)" in text_report(mobility.analyze(slider))  # was "(1 freedoms)"
    said = mobility.analyze(mobility.load(ROOT / "mechanisms" / "4puu.yaml")).gruebler_kutzbach_explanation  # one redundant constraint from its geometry
    assert said.endswith(" 1 comes from the special geometry of the loops (parallel or intersecting axes, repeated constraints of parallel limbs).")
