"""Bad files: whatever a file given to the library or to any command holds, it ends in one line naming file:line:key, exit status 2.

Where a new test goes: a test of an input *file* (a mechanism or flexure YAML document, a closures or
poses file, any file a command reads) that is the wrong kind of file (a device, a pipe, a link loop, a
folder), too large, not UTF-8, badly named, or whose YAML content is malformed or hostile (an alias bomb,
deep nesting, a control character, a number that is not finite, a name that is not a name) goes here.
It asserts the refusal with :func:`guards.raises_one_line` (a
:class:`~mobility.errors.MechanismFileError` whose ``file``, ``line`` and ``key`` it checks) through the
library, and with :func:`guards.refused` through the command line.  A bad element of a robot file (MJCF,
URDF) goes in ``test_bad_robot_files.py``; a file generated or mutated at random in ``test_fuzz_files.py``;
how the reader reads *valid* YAML in ``test_yaml_reader.py``; a valid file of extreme numbers or size in
``test_extreme_numbers.py`` or ``test_extreme_sizes.py``.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path
from typing import Any

import pytest

import mobility
from mobility.errors import MechanismFileError, RequestError, one_line
from mobility.io.files import read_capped
from mobility.io.limits import Limits
from mobility.io.yaml_source import parse_yaml, read_text
from mobility.testing.check import check_paths

from conftest import MECHANISMS
from guards import raises_one_line, refused, run_child, run_cli, time_bound

ROOT = Path(__file__).resolve().parent.parent
HAND = ROOT / "tests" / "data" / "robots" / "hand"
EXAMPLES = ROOT / "examples"
BAR = str(MECHANISMS / "four_bar.yaml")
BAR_TEXT = (MECHANISMS / "four_bar.yaml").read_text(encoding="utf-8")
DEVICE = "is a device (a terminal, /dev/zero...), not a regular file; expected a mechanism file"
PIPE = "is a pipe or socket, expected a mechanism file"

HEAD = "name: t\nground: g\nend_effector: e\n"
ONE_JOINT = "joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1]}\n"


# -- 1. what a file is: a device, a pipe, a link loop, its size, its name, its encoding -------------------


BLOCKING_DEVICES = [d for d in ("/dev/kmsg",) if os.access(d, os.R_OK)]  # reading waits for the kernel's next message
DEVICES = ["/dev/null", "/dev/zero"] + BLOCKING_DEVICES


@pytest.mark.parametrize("device", DEVICES)
def test_a_device_given_as_the_file_is_refused_in_one_line(device):
    done = run_child("analyze", device)  # /dev/kmsg waited for ever; /dev/null read as an empty file, /dev/zero up to 4 MB
    assert refused(done) == f"mobility: {device}: {DEVICE}"


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
        done = run_child(*command)
        assert done.returncode == 2, command
        assert expected in done.stdout + done.stderr, (command, done.stdout, done.stderr)


def test_a_terminal_is_refused_rather_than_read_until_someone_types():
    leader, follower = os.openpty()
    try:
        terminal = os.ttyname(follower)
        with time_bound(10):
            raises_one_line(lambda: mobility.load(terminal), MechanismFileError, f"^{terminal}: is a device \\(a terminal, /dev/zero...\\), not a regular file; expected a mechanism file$")
            done = run_cli("analyze", terminal)
        assert refused(done) == f"mobility: {terminal}: is a device (a terminal, /dev/zero...), not a regular file; expected a mechanism file"
    finally:
        os.close(leader)
        os.close(follower)


def test_dev_zero_and_big_files_stop_at_the_size_limit(tmp_path, write_yaml):
    with time_bound(10):
        raises_one_line(lambda: mobility.load("/dev/zero"), MechanismFileError, "^/dev/zero: is a device .*not a regular file; expected a mechanism file$")  # refused before it is opened (a device may never end, or wait for ever)
        (tmp_path / "huge.yaml").write_bytes(b"#" * (4194304 + 1))
        raises_one_line(lambda: mobility.load(tmp_path / "huge.yaml"), MechanismFileError, "larger than the limit of 4194304 bytes")
        path = write_yaml(HEAD + ONE_JOINT + "description: " + "x" * 500 + "\n")
        assert mobility.load(path).description == "x" * 500
        raises_one_line(lambda: mobility.load(path, limits=Limits(max_file_bytes=300)), MechanismFileError, "larger than the limit of 300 bytes")
        raises_one_line(lambda: mobility.loads(path.read_text(), limits=Limits(max_file_bytes=300)), MechanismFileError, "larger than the limit of 300")


def test_a_fifo_is_refused_wherever_a_file_is_read(tmp_path):
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    urdf = str(HAND / "four_bar.urdf")
    for command in (("analyze", str(fifo)), ("actuation", BAR, "--pose", str(fifo)), ("analyze", urdf, "--closures", str(fifo)),
                    ("sweep", str(fifo), "--vary", "A=0:1:2")):
        assert refused(run_child(*command)) == f"mobility: {fifo}: {PIPE}", command
    done = run_child("check", str(tmp_path))  # a folder whose only mechanism file is a FIFO: its row says so
    assert done.returncode == 2 and f"ERROR: {fifo}: {PIPE}" in done.stdout


def test_a_pipe_is_refused_without_waiting_for_a_writer(tmp_path):
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    done = run_cli("analyze", fifo)  # opening it would wait for ever
    assert refused(done) == f"mobility: {fifo}: is a pipe or socket, expected a mechanism file"


def test_a_pipe_put_in_place_of_a_file_after_its_stat_is_refused_without_waiting(tmp_path, monkeypatch):
    fifo = tmp_path / "swapped.yaml"
    os.mkfifo(fifo)
    regular = tmp_path / "regular.yaml"
    regular.write_text(BAR_TEXT)
    real_stat, looks_regular = os.stat, os.stat(regular)
    # the race: the path was a regular file when looked at, a FIFO when opened (opening a FIFO waits for a writer)
    monkeypatch.setattr(os, "stat", lambda path, *a, **k: looks_regular if os.fspath(path) == str(fifo) else real_stat(path, *a, **k))
    with time_bound(10):
        error = raises_one_line(lambda: read_capped(fifo), MechanismFileError)
    assert str(error) == f"{fifo}: {PIPE}"


@pytest.mark.parametrize("command", [["view", "-o", "{tmp}/v.html"], ["convert"], ["plot", "-o", "{tmp}/p.png"], ["analyze"],
                                     ["sweep", "--vary", "A=0:10:3"]])
def test_an_input_that_is_a_symlink_loop_is_named_as_one(command, tmp_path, symlink_loop):
    loop = symlink_loop(tmp_path, "in.yaml")
    done = run_cli(*command[:1], loop, *[a.replace("{tmp}", str(tmp_path)) for a in command[1:]])
    assert refused(done) == f"mobility: {loop}: is a symbolic link loop (too many levels of symbolic links), expected a mechanism file"
    assert not any(p.name in ("v.html", "p.png") for p in tmp_path.iterdir())


def test_check_reports_a_pipe_in_a_folder_and_prints_paths_as_text(tmp_path):
    odd = tmp_path / "a\x1b[31mred.yaml"
    shutil.copy(BAR, odd)
    os.mkfifo(tmp_path / "pipe.yaml")
    done = run_cli("check", tmp_path)
    out = done.stdout
    assert done.returncode == 2
    assert "\x1b" not in out and "a\\x1b[31mred.yaml" in out and "pass (3 keys)" in out
    assert "pipe.yaml: is a pipe or socket, expected a mechanism file" in out and "1 passed, 0 failed, 0 without expected block, 1 error" in out


def test_a_file_name_with_an_escape_sequence_is_printed_as_text(tmp_path):
    line = refused(run_cli("analyze", tmp_path / "x\x1b[31m\u202e.yaml"))
    assert "x\\x1b[31m\\u202e.yaml: no such file" in line and "\x1b" not in line and "\u202e" not in line


def test_a_message_escapes_line_separators_and_format_characters_of_a_path():
    path = "/no/such/x\u2028y\u2029z\u200e\u202e.yaml"
    assert refused(run_cli("analyze", path)) == "mobility: /no/such/x\\u2028y\\u2029z\\u200e\\u202e.yaml: no such file"
    assert one_line("a\ufeffb\u2066c") == "a\\ufeffb\\u2066c"


def test_text_that_is_not_utf8_names_its_line(tmp_path):
    path = tmp_path / "latin1.yaml"
    path.write_bytes((HEAD + "description: caf\xe9\n").encode("latin-1"))
    error = raises_one_line(lambda: read_text(path), MechanismFileError)
    assert error.line == 4 and "not UTF-8" in error.message


# -- 2. the content of a YAML file: a corpus of malformed, extreme and hostile documents -------------------


def joint_axis(z: str) -> str:
    return HEAD + f'joints:\n  - {{name: A, type: P, links: [g, e], axis: [0, 1, "{z}"]}}\n'


def laughs(levels: int, under: str) -> str:
    """An alias bomb: ``levels`` lists of ten aliases to the level below, the last under key ``under``."""
    lines = ["l0: &l0 [x, x, x, x, x, x, x, x, x, x]"]
    lines += [f"l{k}: &l{k} [" + ", ".join([f"*l{k - 1}"] * 10) + "]" for k in range(1, levels)]
    return "\n".join(lines) + f"\n{under}: *l{levels - 1}\n"


# (text, line, key, words of the message); None: not checked.
CORPUS = {
    "complex cube root": (joint_axis("(-8)**(1/3)"), 5, "joints[0].axis[2]", "complex"),
    "complex square root": (joint_axis("(-1)**0.5"), 5, "joints[0].axis[2]", "complex"),
    "2,000-term sum": (joint_axis("+".join(["1"] * 2000)), 5, "joints[0].axis[2]", "longer than the limit of 1000"),
    "400-term sum (deep tree)": (joint_axis("+".join(["1"] * 400)), 5, "joints[0].axis[2]", "nested deeper than the limit"),
    "deep parentheses": (joint_axis("(" * 250 + "1" + ")" * 250), 5, "joints[0].axis[2]", "too many nested parentheses"),
    "deeply nested calls": (joint_axis("sqrt(" * 150 + "1" + ")" * 150), 5, "joints[0].axis[2]", "nested deeper than the limit of 100 levels (set MOBILITY_MAX_EXPRESSION_DEPTH to raise it)"),
    "overflowing expression": (joint_axis("exp(1000)"), 5, "joints[0].axis[2]", "too large for a float"),
    "overflowing power": (joint_axis("10.0**400"), 5, "joints[0].axis[2]", "too large for a float"),
    "modulo zero": (joint_axis("2 % 0"), 5, "joints[0].axis[2]", "division by zero"),
    "infinite literal": (joint_axis("1/9e999"), 5, "joints[0].axis[2]", "not finite"),
    "YAML infinity": (HEAD + "joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 1, .inf]}\n", 5, "joints[0].axis[2]", "finite"),
    "400-digit integer": (HEAD + "joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 1, " + "9" * 400 + "]}\n", 5, "joints[0].axis[2]", "integer of 400 digits"),
    "5,000-digit integer": (HEAD + "joints:\n  - {name: A, type: P, links: [g, e], axis: [0, 1, " + "9" * 5000 + "]}\n", 5, "joints[0].axis[2]", "as an integer"),
    "list nested 3,000 deep": (HEAD + ONE_JOINT + "x: " + "[" * 3000 + "]" * 3000 + "\n", 6, "x[0][0]...", "nested deeper than the limit of 64"),
    "mapping nested 10,000 deep": (HEAD + ONE_JOINT + "x: " + "{a: " * 10000 + "1" + "}" * 10000 + "\n", 6, "x.a.a...", "nested deeper than the limit of 64"),
    "recursive alias": (HEAD + "joints: &j [*j]\n", 4, "joints[0]", "recursive alias *j"),
    "undefined alias": (HEAD + "joints: [*j]\n", 4, "joints[0]", "undefined alias *j"),
    "NUL byte": (HEAD + ONE_JOINT + "description: a\x00b\n", 6, "", "control character '\\x00'"),
    "BEL byte": (HEAD + "description: a\x07b\n" + ONE_JOINT, 4, "", "control character '\\x07'"),
    "type as a list": (HEAD + "joints:\n  - {name: A, type: [R], links: [g, e], axis: [0, 0, 1]}\n", 5, "joints[0].type", "expected a joint type, one of R, P, H, C, U, S, E (or revolute, prismatic, helical, cylindrical, universal, spherical, planar); got a list of 1 item"),
    "20,000 copies": (HEAD + "limbs: [{copies: 20000, joints: [{name: 'P{i}', type: P, links: [g, e], axis: [0, 0, 1]}]}]\n", 4, "limbs[0].copies", "limit of 5000"),
    "100,000,000 copies": (HEAD + ONE_JOINT + "limbs: [{copies: 100000000, joints: []}]\n", 6, "limbs[0].copies", "limit of 5000"),
    "many limbs of many copies": (HEAD + ONE_JOINT + "limbs:\n" + "  - {copies: 3000, joints: []}\n" * 2, 8, "limbs[1].copies", "6000 copies of limbs"),
    "limbs making too many joints": (HEAD + "limbs: [{copies: 3000, joints: [{name: 'P{i}', type: P, links: [g, 'l{i}'], axis: [0, 0, 1]}, {name: 'Q{i}', type: P, links: ['l{i}', e], axis: [0, 1, 0]}]}]\n", 4, "limbs[0].copies", "6000 joints"),
    "billion laughs, unknown key": (HEAD + ONE_JOINT + laughs(9, "lol"), 11, None, "limit of 200000 YAML nodes"),
    "billion laughs, known key": (HEAD + laughs(9, "joints"), 9, None, "limit of 200000 YAML nodes"),
    "unknown tag": (HEAD + "joints:\n  - {name: A, type: P, links: [g, e], axis: !vec [0, 0, 1]}\n", 5, "joints[0].axis", "unsupported YAML tag '!vec'"),
    "python tag": (HEAD + ONE_JOINT + "x: !!python/object/apply:os.system [echo]\n", 6, "x", "unsupported YAML tag"),
    "link named true": (HEAD + "joints:\n  - {name: A, type: P, links: [g, true], axis: [0, 0, 1]}\n", 5, "joints[0].links[1]", "expected a link name (a string), got true"),
    "joint named 1.5": (HEAD + "joints:\n  - {name: 1.5, type: P, links: [g, e], axis: [0, 0, 1]}\n", 5, "joints[0].name", "a joint name (a string)"),
    "index shadows pi": (HEAD + "limbs: [{copies: 2, index: pi, joints: [{name: 'P{pi}', type: P, links: [g, e], axis: [0, 0, 1]}]}]\n", 4, "limbs[0].index", "'pi' is a constant"),
    "index shadows a parameter": (HEAD + "parameters: {k: 2}\nlimbs: [{copies: 2, index: k, joints: [{name: 'P{k}', type: P, links: [g, e], axis: [0, 0, 1]}]}]\n", 5, "limbs[0].index", "already a parameter"),
    "parameter named sin": (HEAD + ONE_JOINT + "parameters: {sin: 2}\n", 6, "parameters.sin", "not pi, tau, e or a function name"),
    "octal in YAML 1.1": (HEAD + "joints:\n  - {name: A, type: R, links: [g, e], axis: [0, 0, 1], point: [010, 0, 0]}\n", 5, "joints[0].point[0]", "reads as octal 8 in YAML 1.1 but as 10"),
    "base 60 in YAML 1.1": (HEAD + "joints:\n  - {name: A, type: R, links: [g, e], axis: [0, 0, 1], point: [1:30, 0, 0]}\n", 5, "joints[0].point[0]", "base-60"),
    "escaped ESC in a name": (HEAD + 'joints:\n  - {name: "A\\e[31m", type: P, links: [g, e], axis: [0, 0, 1]}\n', 5, "joints[0].name", "control character '\\x1b'"),
    "escaped C1 in a key": (HEAD + ONE_JOINT + '"x\\x9b": 1\n', 6, "", "control character '\\x9b'"),
    "bidirectional override": (HEAD + "joints:\n  - {name: A\u202eB, type: P, links: [g, e], axis: [0, 0, 1]}\n", 5, None, "control character '\\u202e'"),
    "parameter named pi with a line break": (HEAD + 'parameters: {"pi\\n": 3}\n' + ONE_JOINT, 4, None, "not pi, tau, e or a function name"),
    "limb index e with a line break": (HEAD + "limbs: [{copies: 2, index: \"e\\n\", joints: [{name: 'P{e}', type: P, links: [g, e], axis: [0, 0, 1]}]}]\n", 4, "limbs[0].index", "expected"),
    "fullwidth letter in an expression": (HEAD + "parameters: {a: 1}\njoints:\n  - {name: A, type: R, links: [g, e], axis: [0, 0, 1], point: ['\uff41+0', 0, 0]}\n", 6, "joints[0].point[0]", "expressions are written in ASCII"),
    "a point beyond the largest float once in the global frame": (HEAD + "frames:\n  F: {origin: [1.0e308, 0, 0]}\njoints:\n  - {name: A, type: R, links: [g, e], axis: [0, 0, 1], point: [1.0e308, 0, 0], frame: F}\n", 7, "joints[0].point", "once written in the global frame (from frame 'F')"),
    "frame origins adding up beyond the largest float": (HEAD + "frames:\n  F: {origin: [1.0e308, 0, 0], parent: G}\n  G: {origin: [1.0e308, 0, 0]}\njoints:\n  - {name: A, type: R, links: [g, e], axis: [0, 0, 1], point: [0, 0, 0], frame: F}\n", 5, "frames.F.origin", "its origin in the global frame is not finite"),
    "merge key": (HEAD + "joints:\n  - &b {name: A, type: P, links: [g, e], axis: [0, 0, 1]}\n  - {<<: *b, name: B}\n", 6, "joints[1].<<", "merge keys"),
    "second document": (HEAD + ONE_JOINT + "---\nname: u\n", 6, "", "found a second one"),
    "collection as a key": (HEAD + ONE_JOINT + "? [a, b]\n: 1\n", 6, "", "mapping keys must be plain names"),
    "impossible date": (HEAD + ONE_JOINT + "description: 2001-13-45\n", 6, "description", "as a date"),
    "frames chained 100 deep": (HEAD + "frames:\n" + "".join(f"  f{i}: {{parent: f{i + 1}}}\n" for i in range(99)) + "  f99: {}\njoints:\n  - {name: A, type: P, links: [g, e], axis: [0, 0, 1], frame: f0}\n", 5, "frames.f0.parent", "limit of 64 parents"),
}


@pytest.mark.parametrize("case", sorted(CORPUS))
def test_hostile_input_is_one_line_naming_file_line_and_key(write_yaml, case):
    text, line, key, words = CORPUS[case]
    path = write_yaml(text)
    with time_bound(10):
        err = raises_one_line(lambda: mobility.load(path), MechanismFileError, shorter_than=400)
    assert err.file == str(path) and err.line == line, str(err)
    if key is not None:
        assert err.key == key, str(err)
    assert words in err.message, str(err)


COMMANDS = [["analyze"], ["analyze", "--json"], ["check"], ["jacobian"], ["actuation"], ["plot", "-o", "picture.png"],
            ["sweep", "--vary", "A=0:1:2"], ["view", "-o", "page.html"], ["convert"]]


@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: c[0])
@pytest.mark.parametrize("case", ["400-digit integer", "billion laughs, unknown key", "NUL byte", "recursive alias", "20,000 copies", "type as a list"])
def test_hostile_input_exits_2_with_one_line_from_every_command(tmp_path, write_yaml, command, case):
    text, line, _, words = CORPUS[case]
    path = write_yaml(text)
    args = [str(tmp_path / a) if a.endswith((".png", ".html")) else a for a in command]
    with time_bound(10):
        done = run_cli(*args, path)
    if command == ["check"]:  # check reports a bad file in its table, on stdout
        assert done.returncode == 2 and not done.stderr, (done.returncode, done.stdout, done.stderr)
        shown = done.stdout
    else:
        shown = refused(done)
    assert f"{path}:{line}:" in shown and words in shown


def test_check_over_a_folder_reports_each_bad_file_on_its_line_and_goes_on(tmp_path, write_yaml):
    write_yaml(CORPUS["billion laughs, known key"][0], "a_bomb.yaml")
    write_yaml(CORPUS["mapping nested 10,000 deep"][0], "b_deep.yaml")
    write_yaml(BAR_TEXT, "c_good.yaml")
    write_yaml(CORPUS["NUL byte"][0], "d_nul.yaml")
    with time_bound(20):
        report = check_paths([tmp_path])
        done = run_cli("check", tmp_path)
    assert [Path(r.path).name for r in report.results] == ["a_bomb.yaml", "b_deep.yaml", "c_good.yaml", "d_nul.yaml"]
    assert [r.status for r in report.results] == ["error", "error", "pass", "error"]
    assert all(not r.internal for r in report.results)
    assert done.returncode == 2 == report.exit_status
    rows = [row for row in done.stdout.splitlines() if ".yaml" in row]
    assert len(rows) == 4 and "pass" in rows[2] and all("ERROR" in rows[i] for i in (0, 1, 3))


def test_loading_a_flexure_document_as_a_mechanism_names_load_flexure():
    error = raises_one_line(lambda: mobility.load(EXAMPLES / "flexure" / "three_rod.yaml"), MechanismFileError, "a flexure document")
    assert "mobility.load_flexure" in str(error) and "mobility actuation" in str(error) and error.key == "elements"
    assert mobility.load_flexure(EXAMPLES / "flexure" / "three_rod.yaml").elements


# -- 3. names: no control, format or line-break character; messages escape them -----------------------


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
        error = raises_one_line(lambda: mobility.loads(text, file="m.yaml"), MechanismFileError)
        assert (error.key, error.message) == (key, f"{described} is not allowed in {what}")
        assert error.line == (1 if key == "name" else 12)


def test_a_frame_name_holding_a_line_break_is_refused():
    text = BAR_TEXT + 'frames:\n  "tool\\nframe": {origin: [0, 0, 1]}\n'
    raises_one_line(lambda: mobility.loads(text, file="m.yaml"), MechanismFileError, r"^m\.yaml:\d+: frames\.tool\\nframe: a line break '\\n' \(U\+000A\) is not allowed in a frame name$")


# -- 4. numbers: a YAML number that underflows to 0 or overflows to infinity is refused, as in an expression -------


@pytest.mark.parametrize("written, message", [
    ("1.0e-400", "the number '1.0e-400' underflows: it is below the smallest float (4.94e-324) and would read as 0.0"),
    ("-2.5e-999", "the number '-2.5e-999' underflows: it is below the smallest float (4.94e-324) and would read as -0.0"),
    ("1.0e+400", "the number '1.0e+400' is too large for a float (it would read as inf)"),
    ('"2 * 1e-400"', "expression '2 * 1e-400': the number '1e-400' underflows: it is below the smallest float (4.94e-324) and would read as 0.0"),
])
def test_a_number_that_reads_as_zero_or_infinity_is_refused(written, message):
    text = BAR_TEXT.replace("point: [1, 2, 0]", f"point: [{written}, 2, 0]")
    assert text != BAR_TEXT
    error = raises_one_line(lambda: mobility.loads(text, file="m.yaml"), MechanismFileError)
    assert (error.line, error.key, error.message) == (12, "joints[1].point[0]", message)


def test_a_zero_written_small_and_a_subnormal_number_are_read():
    for written, value in (("0.0e-400", 0.0), ("5e-324", 5e-324), ("1.0e-300", 1e-300)):
        m = mobility.loads(BAR_TEXT.replace("point: [0, 0, 0]", f"point: [{written}, 0, 0]"))
        assert m.joints[0].point == (value, 0.0, 0.0)


# -- 5. the reader's limits, raised by the environment and by argument -----------------------------------


def test_limits_are_raised_by_the_environment_and_by_argument(write_yaml, monkeypatch):
    text = HEAD + "limbs: [{copies: 3, joints: [{name: 'P{i}', type: P, links: [g, 'l{i}'], axis: [0, 0, 1]}, {name: 'Q{i}', type: P, links: ['l{i}', e], axis: [0, 1, 0]}]}]\n"
    assert len(mobility.loads(text).joints) == 6
    raises_one_line(lambda: mobility.loads(text, limits=Limits(max_joints=5)), MechanismFileError, "6 joints in all, more than the limit of 5 .set MOBILITY_MAX_JOINTS")
    monkeypatch.setenv("MOBILITY_MAX_COPIES", "2")
    raises_one_line(lambda: mobility.loads(text), MechanismFileError, "3 copies of limbs are more than the limit of 2")
    monkeypatch.setenv("MOBILITY_MAX_COPIES", "3")
    assert len(mobility.loads(text).joints) == 6
    monkeypatch.setenv("MOBILITY_MAX_DEPTH", "none")
    raises_one_line(lambda: mobility.loads(text), RequestError, "MOBILITY_MAX_DEPTH: expected a positive integer")
    assert "MOBILITY_MAX_DEPTH" in refused(run_cli("analyze", write_yaml(text)))


def expanded_nodes(value: Any) -> int:
    """Nodes of a document with every alias expanded: collections, keys and scalars (walked on the values)."""
    count, stack = 0, [value]
    while stack:
        item = stack.pop()
        count += 1
        if isinstance(item, dict):
            count += len(item)
            stack.extend(item.values())
        elif isinstance(item, list):
            stack.extend(item)
    return count


@pytest.mark.parametrize("levels", [1, 2, 3, 4])
def test_alias_expansion_is_counted_node_by_node(levels):
    text = laughs(levels, "top")
    data, _ = parse_yaml(text)
    total = expanded_nodes(data)
    assert total > 2 * 10**levels  # the last level and the top key each reach 10**levels scalars
    assert parse_yaml(text, limits=Limits(max_nodes=total))[0] == data
    raises_one_line(lambda: parse_yaml(text, limits=Limits(max_nodes=total - 1)), MechanismFileError, f"more than the limit of {total - 1} YAML nodes")
