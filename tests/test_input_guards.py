"""Input guards: only regular files are read, names hold no control or format character, numbers are written in ASCII, limits are checked.

Each test names the audit finding it guards: a device or a FIFO given as a
file hung the command; a name holding a line break, a tab or a line
separator was printed raw; ``float`` read Arabic-Indic digits and bools as
numbers; ``Limits`` took any value; a YAML number that underflows was read as 0.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import mobility
from mobility.cli import main
from mobility.core.model import Frame, Joint, Mechanism
import mobility.errors as errors
from mobility.errors import MechanismError, MechanismFileError, RequestError, one_line
from mobility.io.files import read_capped
from mobility.io.limits import Limits
from mobility.sweeps import sweep

from conftest import MECHANISMS
from guards import time_bound

ROOT = Path(__file__).resolve().parent.parent
HAND = ROOT / "tests" / "data" / "robots" / "hand"
BAR = str(MECHANISMS / "four_bar.yaml")
BAR_TEXT = (MECHANISMS / "four_bar.yaml").read_text(encoding="utf-8")
DEVICE = "is a device (a terminal, /dev/zero...), not a regular file; expected a mechanism file"
PIPE = "is a pipe or socket, expected a mechanism file"


def run_cli(*args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    """``mobility ARGS`` in a child process, with the package under test, ended after 60 s (a hang fails, not waits)."""
    package_root = str(Path(mobility.__file__).resolve().parent.parent)
    environ = {**os.environ, "PYTHONPATH": package_root, **(env or {})}
    return subprocess.run([sys.executable, "-m", "mobility", *args], capture_output=True, text=True, timeout=60, env=environ, stdin=subprocess.DEVNULL)


# -- 1. only a regular file is read: a FIFO or a device is refused before it is opened ------------------

BLOCKING_DEVICES = [d for d in ("/dev/kmsg",) if os.access(d, os.R_OK)]  # reading waits for the kernel's next message
DEVICES = ["/dev/null", "/dev/zero"] + BLOCKING_DEVICES


@pytest.mark.parametrize("device", DEVICES)
def test_a_device_given_as_the_file_is_refused_in_one_line(device):
    done = run_cli("analyze", device)  # /dev/kmsg waited for ever; /dev/null read as an empty file, /dev/zero up to 4 MB
    assert (done.returncode, done.stderr) == (2, f"mobility: {device}: {DEVICE}\n")


@pytest.mark.parametrize("device", DEVICES)
def test_every_file_a_command_reads_refuses_a_device(device):
    urdf = str(HAND / "four_bar.urdf")
    commands = {
        ("check", device): f"{device}: {DEVICE}",
        ("actuation", BAR, "--pose", device): f"mobility: {device}: {DEVICE}",
        ("analyze", urdf, "--closures", device): f"mobility: {device}: {DEVICE}",
        ("convert", device): f"mobility: {device}: {DEVICE}",
    }
    for command, expected in commands.items():
        done = run_cli(*command)
        assert done.returncode == 2, command
        assert expected in done.stdout + done.stderr, (command, done.stdout, done.stderr)


def test_a_fifo_is_refused_wherever_a_file_is_read(tmp_path):
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    urdf = str(HAND / "four_bar.urdf")
    for command in (("analyze", str(fifo)), ("actuation", BAR, "--pose", str(fifo)), ("analyze", urdf, "--closures", str(fifo)),
                    ("sweep", str(fifo), "--vary", "A=0:1:2")):
        done = run_cli(*command)
        assert (done.returncode, done.stderr) == (2, f"mobility: {fifo}: {PIPE}\n"), command
    done = run_cli("check", str(tmp_path))  # a folder whose only mechanism file is a FIFO: its row says so
    assert done.returncode == 2 and f"ERROR: {fifo}: {PIPE}" in done.stdout


def test_a_pipe_put_in_place_of_a_file_after_its_stat_is_refused_without_waiting(tmp_path, monkeypatch):
    fifo = tmp_path / "swapped.yaml"
    os.mkfifo(fifo)
    regular = tmp_path / "regular.yaml"
    regular.write_text(BAR_TEXT)
    real_stat, looks_regular = os.stat, os.stat(regular)
    # the race: the path was a regular file when looked at, a FIFO when opened (opening a FIFO waits for a writer)
    monkeypatch.setattr(os, "stat", lambda path, *a, **k: looks_regular if os.fspath(path) == str(fifo) else real_stat(path, *a, **k))
    with time_bound(10):
        with pytest.raises(MechanismFileError) as info:
            read_capped(fifo)
    assert str(info.value) == f"{fifo}: {PIPE}"


# -- 2. names: no control, format or line-break character; messages escape them -----------------------

BAD_NAMES = {  # as written in a double-quoted YAML string -> the character, its name in the message
    "\\t": ("\t", "a tab '\\t' (U+0009)"),
    "\\r": ("\r", "a line break '\\r' (U+000D)"),
    "\\n": ("\n", "a line break '\\n' (U+000A)"),
    "\\N": ("\x85", "a line break '\\x85' (U+0085)"),
    "\\L": ("\u2028", "a line separator '\\u2028' (U+2028)"),
    "\\P": ("\u2029", "a paragraph separator '\\u2029' (U+2029)"),
    "\\u200e": ("\u200e", "a format character (invisible, or reordering the text) '\\u200e' (U+200E)"),
    "\\u200b": ("\u200b", "a format character (invisible, or reordering the text) '\\u200b' (U+200B)"),
}


@pytest.mark.parametrize("escape", BAD_NAMES, ids=[repr(c) for c, _ in BAD_NAMES.values()])
def test_a_yaml_name_holding_a_control_or_format_character_is_refused_at_its_key(escape):
    _, described = BAD_NAMES[escape]
    joint = BAR_TEXT.replace("{name: B,", f'{{name: "B{escape}x",')
    link = BAR_TEXT.replace("links: [crank, coupler]", f'links: [crank, "coupler{escape}"]')
    title = BAR_TEXT.replace("name: planar four-bar", f'name: "planar{escape}four-bar"')
    assert joint != BAR_TEXT and link != BAR_TEXT and title != BAR_TEXT
    for text, key, what in ((joint, "joints[1].name", "a joint name"), (link, "joints[1].links[1]", "a link name"), (title, "name", "the name of the mechanism")):
        with pytest.raises(MechanismFileError) as info:
            mobility.loads(text, file="m.yaml")
        assert (info.value.key, info.value.message) == (key, f"{described} is not allowed in {what}")
        assert info.value.line == (1 if key == "name" else 12)


def test_a_frame_name_holding_a_line_break_is_refused():
    text = BAR_TEXT + 'frames:\n  "tool\\nframe": {origin: [0, 0, 1]}\n'
    with pytest.raises(MechanismFileError, match=r"^m\.yaml:\d+: frames\.tool\\nframe: a line break '\\n' \(U\+000A\) is not allowed in a frame name$"):
        mobility.loads(text, file="m.yaml")


def test_a_robot_name_holding_a_character_reference_to_a_line_break_is_refused(tmp_path):
    for source, written, reference, key, message in (
        ("four_bar.urdf", '<link name="coupler"', '<link name="coupler&#13;"', "link.name", "a line break '\\r' (U+000D) is not allowed in a name"),
        ("four_bar.xml", '<joint name="B"/>', '<joint name="B&#x2028;"/>', "joint.name", "a line separator '\\u2028' (U+2028) is not allowed in a name"),
    ):
        text = (HAND / source).read_text(encoding="utf-8")
        assert written in text
        path = tmp_path / source
        path.write_text(text.replace(written, reference, 1), encoding="utf-8")
        with pytest.raises(MechanismFileError) as info:
            mobility.load(path)
        assert (info.value.key, info.value.message) == (key, message)


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


def test_names_given_in_code_follow_the_same_rule():
    z = (0, 0, 1)
    with pytest.raises(MechanismError, match=r"^name: a tab '\\t' \(U\+0009\) is not allowed in a name$"):
        Joint("hip\tleft", "R", ("a", "b"), axis=z, point=(0, 0, 0))
    with pytest.raises(MechanismError, match=r"^links\[1\]: a line separator"):
        Joint("hip", "R", ("a", "b\u2028"), axis=z, point=(0, 0, 0))
    with pytest.raises(MechanismError, match=r"^name: a format character .*U\+202E"):
        Frame("tool\u202e")
    joint = Joint("A", "R", ("ground", "crank"), axis=z, point=(0, 0, 0))
    with pytest.raises(MechanismError, match=r"^end_effector: a paragraph separator"):
        Mechanism("arm", ground="ground", end_effector="crank\u2029", joints=(joint,))
    assert Joint("连杆 1", "R", ("ground", "crank"), axis=z, point=(0, 0, 0)).name == "连杆 1"  # any printable text is a name


def test_name_problem_is_none_for_every_printable_name():
    assert [errors.name_problem(n) for n in ("A", "left knee", "Grübler 𝄞", "P,1", "a\u00a0b")] == [None] * 5


def test_a_message_escapes_line_separators_and_format_characters_of_a_path(capsys):
    path = "/no/such/x\u2028y\u2029z\u200e\u202e.yaml"
    assert main(["analyze", path]) == 2
    err = capsys.readouterr().err
    assert err == "mobility: /no/such/x\\u2028y\\u2029z\\u200e\\u202e.yaml: no such file\n"
    assert one_line("a\ufeffb\u2066c") == "a\\ufeffb\\u2066c"


# -- 3. numbers: ASCII digits only, and no bool for a number --------------------------------------------

@pytest.mark.parametrize("args, expected", [
    (("--tol", "\u0661e-9"), "argument --tol: invalid float value: '\u0661e-9'"),
    (("--tol", "\u20031e-9"), "argument --tol: invalid float value"),  # an em space: float() strips it
])
def test_an_option_number_in_other_digits_is_refused(args, expected, capsys):
    with pytest.raises(SystemExit) as info:
        main(["analyze", BAR, *args])
    assert info.value.code == 2 and expected in capsys.readouterr().err


def test_integer_options_refuse_other_digits(capsys):
    for argv in (["actuation", BAR, "--samples", "\u0663"], ["sweep", BAR, "--vary", "A=0:1:2", "--max-poses", "\u0661\u0660"],
                 ["plot", BAR, "-o", "x.png", "--dpi", "\u0661\u0665\u0660"]):
        with pytest.raises(SystemExit) as info:
            main(argv)
        assert info.value.code == 2 and "invalid int value" in capsys.readouterr().err, argv


def test_a_vary_range_in_other_digits_is_refused(capsys):
    assert main(["sweep", BAR, "--vary", "A=\u0661:2:3"]) == 2
    assert capsys.readouterr().err == "mobility: --vary 'A=\u0661:2:3': START must be a number, got '\u0661'\n"
    assert main(["sweep", BAR, "--vary", "A=1:2:\u0663"]) == 2
    assert capsys.readouterr().err == "mobility: --vary 'A=1:2:\u0663': COUNT must be an integer, got '\u0663'\n"
    with pytest.raises(RequestError, match="STOP must be a number"):
        sweep(mobility.load(BAR), {"A": ("0", "\u0662", 3)})


def test_an_environment_limit_in_other_digits_is_refused():
    with pytest.raises(RequestError, match="^MOBILITY_MAX_JOINTS: expected a positive integer, got '\u0661\u0660'$"):
        Limits.from_environment({"MOBILITY_MAX_JOINTS": "\u0661\u0660"})
    done = run_cli("analyze", BAR, env={"MOBILITY_MAX_JOINTS": "\u0661\u0660"})
    assert done.returncode == 2 and done.stderr.startswith("mobility: MOBILITY_MAX_JOINTS: expected a positive integer")
    with pytest.raises(RequestError, match="^MOBILITY_MAX_JOINTS: expected a positive integer, got ' 20000 '$"):  # issue 33: digits only, as files
        Limits.from_environment({"MOBILITY_MAX_JOINTS": " 20000 "})
    assert Limits.from_environment({"MOBILITY_MAX_JOINTS": "20000"}).max_joints == 20000


def test_a_joint_refuses_other_digits_and_bools_for_numbers():
    z, o = (0, 0, 1), (0, 0, 0)
    with pytest.raises(MechanismError, match="^pitch: expected a number, got '\u0661'$"):
        Joint("H", "H", ("a", "b"), axis=z, point=o, pitch="\u0661")
    with pytest.raises(MechanismError, match="^pitch: expected a number, got True$"):
        Joint("H", "H", ("a", "b"), axis=z, point=o, pitch=True)
    for axis in ((True, 0, 0), np.array([True, False, False]), ("\u0661", 0, 0)):
        with pytest.raises(MechanismError, match="^axis: expected a list of 3 numbers"):
            Joint("R", "R", ("a", "b"), axis=axis, point=o)
    assert Joint("H", "H", ("a", "b"), axis=z, point=o, pitch="0.5").pitch == 0.5  # ASCII text is still a number
    assert Joint("R", "R", ("a", "b"), axis=(0, 0, np.int64(2)), point=o).axis == (0.0, 0.0, 1.0)


# -- 4. Limits checks its fields -------------------------------------------------------------------------

@pytest.mark.parametrize("field, value, shown", [
    ("max_joints", "5", "'5'"), ("max_file_bytes", -1, "-1"), ("max_depth", 0, "0"), ("max_nodes", True, "True"), ("max_copies", 2.0, "2.0"),
])
def test_limits_refuse_what_is_not_a_positive_integer(field, value, shown):
    with pytest.raises(RequestError) as info:
        Limits(**{field: value})
    assert str(info.value) == f"Limits: {field}: expected a positive integer, got {shown}"


def test_limits_take_numpy_integers_as_ints():
    limits = Limits(max_joints=np.int64(7))
    assert limits.max_joints == 7 and type(limits.max_joints) is int


# -- 5. a YAML number that underflows to 0 or overflows to infinity is refused, as in an expression -------

@pytest.mark.parametrize("written, message", [
    ("1.0e-400", "the number '1.0e-400' underflows: it is below the smallest float (4.94e-324) and would read as 0.0"),
    ("-2.5e-999", "the number '-2.5e-999' underflows: it is below the smallest float (4.94e-324) and would read as -0.0"),
    ("1.0e+400", "the number '1.0e+400' is too large for a float (it would read as inf)"),
    ('"2 * 1e-400"', "expression '2 * 1e-400': the number '1e-400' underflows: it is below the smallest float (4.94e-324) and would read as 0.0"),
])
def test_a_number_that_reads_as_zero_or_infinity_is_refused(written, message):
    text = BAR_TEXT.replace("point: [1, 2, 0]", f"point: [{written}, 2, 0]")
    assert text != BAR_TEXT
    with pytest.raises(MechanismFileError) as info:
        mobility.loads(text, file="m.yaml")
    assert (info.value.line, info.value.key, info.value.message) == (12, "joints[1].point[0]", message)


def test_a_zero_written_small_and_a_subnormal_number_are_read():
    for written, value in (("0.0e-400", 0.0), ("5e-324", 5e-324), ("1.0e-300", 1e-300)):
        m = mobility.loads(BAR_TEXT.replace("point: [0, 0, 0]", f"point: [{written}, 0, 0]"))
        assert m.joints[0].point == (value, 0.0, 0.0)
