"""Options and files that once got past the exit-2 contract: each ends in one line and exit 2, quickly."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from mobility.cli import main

ROOT = Path(__file__).resolve().parent.parent
FOUR_BAR = str(ROOT / "mechanisms" / "four_bar.yaml")
RPS = str(ROOT / "mechanisms" / "actuation_3rps.yaml")


@pytest.mark.parametrize("args, expected", [
    (["actuation", "--samples", "2", "--step=inf", RPS], "--step must lie in (0, 1]"),
    (["view", "--samples", "2", "--seed=-1", RPS, "-o", "{tmp}/v.html"], "--seed must not be negative"),
    (["actuation", "--samples", "1000000", RPS], "--samples must lie in [0, 1000]"),
    (["actuation", "--enumerate", "--mode", "any", "--k", "99999999999999999999", RPS], "--k must lie in [0, 6]"),
    (["plot", "--dpi", "5000", FOUR_BAR, "-o", "{tmp}/p.png"], "--dpi must lie in [20, 600], got 5000"),
    (["plot", "--dpi", "0", FOUR_BAR, "-o", "{tmp}/p.png"], "--dpi must lie in [20, 600], got 0"),
    (["sweep", "--vary", "A=0:10:99999999999999999999", FOUR_BAR], "99,999,999,999,999,999,999 values, more than --max-poses"),
    (["synthesize", "3T", "--joints", "100000"], "--joints in [1, 8]"),
    (["synthesize", "2T3R", "--verify", "11"], "--verify at most 10"),
    (["synthesize", "2T3R", "--samples", "31"], "--samples must be at most 30"),
    (["synthesize", "3T", "--directions", "1,0,0"], "the 3T pattern takes 3 directions, got 1"),
    (["synthesize", "3T", "--seed=-1"], "--seed not negative"),
    (["analyze", "--tol", "abc", FOUR_BAR], "argument --tol: invalid float value: 'abc' (see mobility analyze --help)"),
])
def test_an_out_of_range_option_is_refused_in_one_line(args, expected, tmp_path, capsys):
    status = main([a.replace("{tmp}", str(tmp_path)) for a in args]) if args[1:2] != ["--tol"] else None
    if status is None:  # argparse's own refusal exits
        with pytest.raises(SystemExit) as stop:
            main(args)
        status = stop.value.code
    out, err = capsys.readouterr()
    assert status == 2 and out == "" and err.count("\n") == 1 and expected in err, err


@pytest.mark.parametrize("command", [["sweep", "--vary", "A=0:10:3"], ["convert"]])
def test_an_output_that_is_the_input_file_is_refused_and_the_file_kept(command, tmp_path, capsys):
    path = tmp_path / "four_bar.yaml"
    shutil.copy(FOUR_BAR, path)
    before = path.read_bytes()
    args = command[:1] + [str(path)] + command[1:] + ["-o", str(tmp_path / "." / "four_bar.yaml")]
    assert main(args) == 2
    assert "the same file as" in capsys.readouterr().err and path.read_bytes() == before


def test_a_pipe_is_refused_without_waiting_for_a_writer(tmp_path, capsys):
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    assert main(["analyze", str(fifo)]) == 2  # opening it would wait for ever
    assert capsys.readouterr().err == f"mobility: {fifo}: is a pipe or socket, expected a mechanism file\n"


@pytest.mark.parametrize("command", [["sweep", "--vary", "A=0:10:3", "-o"], ["view", "-o"], ["convert", "-o"], ["plot", "-o"], ["sweep", "--vary", "A=0:10:3", "--plot"]])
def test_an_output_that_is_a_pipe_is_refused_without_waiting_for_a_reader(command, tmp_path, capsys):
    fifo = tmp_path / ("out." + {"view": "html", "plot": "png", "convert": "yaml"}.get(command[0], "png" if command[-1] == "--plot" else "csv"))
    os.mkfifo(fifo)
    assert main(command[:1] + [FOUR_BAR] + command[1:] + [str(fifo)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{fifo}: is a pipe or socket, expected a file to write" in err


@pytest.mark.parametrize("command", [["actuation", RPS, "--inputs", "P1,P1,P1"], ["jacobian", RPS, "--actuated", "P1,P1"], ["sweep", RPS, "--vary", "P1=0:1:2", "--inputs", "P1,P1"]])
def test_an_input_named_twice_is_refused(command, capsys):
    assert main(command) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "'P1' is given twice; name each input once" in err


def test_check_reports_a_pipe_in_a_folder_and_prints_paths_as_text(tmp_path, capsys):
    odd = tmp_path / "a\x1b[31mred.yaml"
    shutil.copy(FOUR_BAR, odd)
    os.mkfifo(tmp_path / "pipe.yaml")
    assert main(["check", str(tmp_path)]) == 2
    out = capsys.readouterr().out
    assert "\x1b" not in out and "a\\x1b[31mred.yaml" in out and "pass (3 keys)" in out
    assert "pipe.yaml: is a pipe or socket, expected a mechanism file" in out and "1 passed, 0 failed, 0 without expected block, 1 error" in out


def test_a_pose_coordinate_far_beyond_reach_is_refused_in_one_line(capsys):
    # once reported as one unassembled pose; since the sweeps' reach limit (SWEEP_REACH) it is refused before any work
    assert main(["sweep", "--vary", "x=1e12:1e12:1", "--json", "--no-progress", FOUR_BAR]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1
    assert err.startswith("mobility: --vary x=1e+12:1e+12:1: 1e+12 is beyond what a sweep reaches from the file's pose")


def test_an_xml_file_in_an_unknown_encoding_is_one_line(tmp_path, capsys):
    path = tmp_path / "robot.urdf"
    path.write_text('<?xml version="1.0" encoding="klingon"?>\n<robot name="r"><link name="a"/></robot>\n')
    assert main(["analyze", str(path)]) == 2
    assert capsys.readouterr().err == f"mobility: {path}:1: unreadable XML (unknown encoding: klingon); expected UTF-8 or another known encoding\n"


def _symlink_loop(folder: Path, name: str) -> Path:
    """``folder/name`` -> ``folder/other`` -> ``folder/name``: looking it up never ends (ELOOP)."""
    path, other = folder / name, folder / ("other-" + name)
    path.symlink_to(other.name)
    other.symlink_to(path.name)
    return path


@pytest.mark.parametrize("command, suffix", [(["sweep", "--vary", "A=0:10:3", "-o"], ".csv"), (["sweep", "--vary", "A=0:10:3", "--plot"], ".png"),
                                             (["view", "-o"], ".html"), (["plot", "-o"], ".png"), (["convert", "-o"], ".yaml")])
def test_an_output_that_is_a_symlink_loop_is_refused_before_any_work(command, suffix, tmp_path, capsys):
    loop = _symlink_loop(tmp_path, "out" + suffix)
    assert main(command[:1] + [FOUR_BAR] + command[1:] + [str(loop)]) == 2  # was 3: Path.resolve raised RuntimeError
    out, err = capsys.readouterr()
    option = command[-1]
    assert out == "" and err == f"mobility: {option} {loop}: cannot write there: a symbolic link loop (too many levels of symbolic links)\n"


@pytest.mark.parametrize("command", [["view", "-o", "{tmp}/v.html"], ["convert"], ["plot", "-o", "{tmp}/p.png"], ["analyze"],
                                     ["sweep", "--vary", "A=0:10:3"]])
def test_an_input_that_is_a_symlink_loop_is_named_as_one(command, tmp_path, capsys):
    loop = _symlink_loop(tmp_path, "in.yaml")
    assert main(command[:1] + [str(loop)] + [a.replace("{tmp}", str(tmp_path)) for a in command[1:]]) == 2
    assert capsys.readouterr().err == f"mobility: {loop}: is a symbolic link loop (too many levels of symbolic links), expected a mechanism file\n"
    assert not any(p.name in ("v.html", "p.png") for p in tmp_path.iterdir())


@pytest.mark.parametrize("command, suffix", [(["sweep", "--vary", "A=0:10:3", "-o"], ".csv"), (["view", "-o"], ".html"), (["plot", "-o"], ".png"), (["convert", "-o"], ".yaml")])
def test_an_output_in_a_missing_folder_is_refused_before_any_work(command, suffix, tmp_path, capsys):
    target = tmp_path / "no such folder" / ("out" + suffix)
    assert main(command[:1] + [FOUR_BAR] + command[1:] + [str(target)]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err == f"mobility: {command[-1]} {target}: cannot write there: the folder {target.parent} does not exist\n"


# -- issue 33: one number rule for options, environment and the API; limits whose cost stays in proportion --------

@pytest.mark.parametrize("args, expected", [
    (["sweep", FOUR_BAR, "--vary", "A=1_0:20:3"], "mobility: --vary 'A=1_0:20:3': START must be a number, got '1_0'"),
    (["sweep", FOUR_BAR, "--vary", "A=0:20:1_0"], "mobility: --vary 'A=0:20:1_0': COUNT must be an integer, got '1_0'"),
    (["analyze", "--tol", "1_0e-9", FOUR_BAR], "argument --tol: invalid float value: '1_0e-9'"),
    (["sweep", FOUR_BAR, "--vary", "A=0:20:3", "--max-poses", "1_000"], "argument --max-poses: invalid int value: '1_000'"),
])
def test_a_number_with_an_underscore_is_refused_as_in_files(args, expected, capsys):
    try:
        status = main(args)
    except SystemExit as stop:  # argparse's own refusal
        status = stop.code
    out, err = capsys.readouterr()
    assert status == 2 and out == "" and err.count("\n") == 1 and expected in err, err


@pytest.mark.parametrize("value", [" 5000 ", "5000\n", "5_000", "+5000"])
def test_a_limit_variable_is_ascii_digits_only(value, monkeypatch, capsys):
    monkeypatch.setenv("MOBILITY_MAX_JOINTS", value)
    assert main(["analyze", FOUR_BAR]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and err.startswith("mobility: MOBILITY_MAX_JOINTS: expected a positive integer, got "), err


def test_the_apis_text_numbers_follow_the_same_rule():
    import numpy as np

    from mobility import Joint
    from mobility.errors import MechanismError

    z = (0, 0, 1)
    with pytest.raises(MechanismError, match="no '_'"):
        Joint("H", "H", ("a", "b"), axis=np.array(["0", "0", "1_0"], dtype=object), point=(0, 0, 0), pitch=1)
    with pytest.raises(MechanismError, match="pitch: expected a number"):
        Joint("H", "H", ("a", "b"), axis=z, point=(0, 0, 0), pitch="1_0")
    assert Joint("H", "H", ("a", "b"), axis=np.array(["0", "0", "2"], dtype=object), point=(0, 0, 0), pitch="1").axis == (0.0, 0.0, 1.0)


def _child(*args: str, env: dict[str, str], seconds: float = 30) -> subprocess.CompletedProcess:
    """The command line in a child whose address space is capped at 2 GiB, under a time bound."""
    import resource

    def cap() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (2 * 1024**3, 2 * 1024**3))

    environ = {k: v for k, v in os.environ.items() if k != "MPLCONFIGDIR"}
    environ.update(PYTHONPATH=str(ROOT), **env)
    return subprocess.run([sys.executable, "-m", "mobility", *args], capture_output=True, text=True, cwd=ROOT, timeout=seconds,
                          env=environ, preexec_fn=cap)


def test_a_raised_depth_limit_keeps_the_cost_in_proportion(tmp_path):
    deep = tmp_path / "deep.yaml"
    deep.write_text("name: x\nground: g\nend_effector: c\njoints: " + "[" * 50_000 + "]" * 50_000 + "\n")  # 100 kB
    done = _child("analyze", str(deep), env={"MOBILITY_MAX_DEPTH": "1000000"})  # past 90 s at 3 GB before
    assert (done.returncode, done.stdout) == (2, "") and done.stderr.count("\n") == 1, done.stderr
    assert "nested deeper than the limit of 1000 levels (the most a YAML document may nest whatever MOBILITY_MAX_DEPTH says" in done.stderr


def test_a_librarys_log_line_becomes_a_note(tmp_path):
    done = _child("plot", FOUR_BAR, "-o", str(tmp_path / "p.png"), env={"HOME": "/proc"}, seconds=120)
    assert done.returncode == 0, done.stderr
    lines = done.stderr.splitlines()
    assert lines and all(line.startswith("mobility: note: ") for line in lines), done.stderr
    assert any("Matplotlib created a temporary cache directory" in line for line in lines)
