"""Bad command lines: an option, an output path or an environment variable that is wrong ends in one line and exit status 2, before any work.

Where a new test goes: a test of what is given on the command line *besides the content of the input
files* -- an option's value (out of range, not a number, digits other than ASCII, a name given twice), an
output path (the input file itself, a pipe, a link loop, a missing folder), an environment variable
(``MOBILITY_MAX_*``) -- goes here.  It runs the command with :func:`guards.run_cli` (in-process; argparse's
own refusals too) or :func:`guards.run_child` (a child process, when the environment or a hang matters)
and asserts the refusal with :func:`guards.refused`.  A bad input *file* goes in ``test_bad_files.py``; a
request that is valid but beyond a budget (poses times joints, joints for ``--finite``) in
``test_extreme_sizes.py``; the options' normal behaviour in ``test_cli.py``.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

import mobility
from mobility.errors import RequestError
from mobility.io.limits import Limits
from mobility.sweeps import sweep

from guards import raises_one_line, refused, run_child, run_cli

ROOT = Path(__file__).resolve().parent.parent
FOUR_BAR = str(ROOT / "mechanisms" / "four_bar.yaml")
RPS = str(ROOT / "mechanisms" / "actuation_3rps.yaml")


# -- 1. option values: out of range, not a number, other digits, an underscore, a name twice -------------


@pytest.mark.parametrize("args, expected", [
    # out of range
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
    # not a number (argparse's own refusal)
    (["analyze", "--tol", "abc", FOUR_BAR], "argument --tol: invalid float value: 'abc' (see mobility analyze --help)"),
    # digits other than ASCII's
    (["analyze", FOUR_BAR, "--tol", "\u0661e-9"], "argument --tol: invalid float value: '\u0661e-9'"),
    (["analyze", FOUR_BAR, "--tol", "\u20031e-9"], "argument --tol: invalid float value"),  # an em space: float() strips it
    (["actuation", FOUR_BAR, "--samples", "\u0663"], "argument --samples: invalid int value"),
    (["sweep", FOUR_BAR, "--vary", "A=0:1:2", "--max-poses", "\u0661\u0660"], "argument --max-poses: invalid int value"),
    (["plot", FOUR_BAR, "-o", "x.png", "--dpi", "\u0661\u0665\u0660"], "argument --dpi: invalid int value"),
    # an underscore in a number, refused as in files
    (["sweep", FOUR_BAR, "--vary", "A=1_0:20:3"], "mobility: --vary 'A=1_0:20:3': START must be a number, got '1_0'"),
    (["sweep", FOUR_BAR, "--vary", "A=0:20:1_0"], "mobility: --vary 'A=0:20:1_0': COUNT must be an integer, got '1_0'"),
    (["analyze", "--tol", "1_0e-9", FOUR_BAR], "argument --tol: invalid float value: '1_0e-9'"),
    (["sweep", FOUR_BAR, "--vary", "A=0:20:3", "--max-poses", "1_000"], "argument --max-poses: invalid int value: '1_000'"),
])
def test_a_bad_option_value_is_refused_in_one_line(args, expected, tmp_path):
    done = run_cli(*[a.replace("{tmp}", str(tmp_path)) for a in args])
    assert expected in refused(done, usage_error=expected.startswith("argument --"))  # argparse's own refusal, or the command's


def test_a_vary_range_in_other_digits_is_refused():
    assert refused(run_cli("sweep", FOUR_BAR, "--vary", "A=\u0661:2:3")) == "mobility: --vary 'A=\u0661:2:3': START must be a number, got '\u0661'"
    assert refused(run_cli("sweep", FOUR_BAR, "--vary", "A=1:2:\u0663")) == "mobility: --vary 'A=1:2:\u0663': COUNT must be an integer, got '\u0663'"
    raises_one_line(lambda: sweep(mobility.load(FOUR_BAR), {"A": ("0", "\u0662", 3)}), RequestError, "STOP must be a number")


def test_a_pose_coordinate_far_beyond_reach_is_refused_in_one_line():
    # once reported as one unassembled pose; since the sweeps' reach limit (SWEEP_REACH) it is refused before any work
    line = refused(run_cli("sweep", "--vary", "x=1e12:1e12:1", "--json", "--no-progress", FOUR_BAR))
    assert line.startswith("mobility: --vary x=1e+12:1e+12:1: 1e+12 is beyond what a sweep reaches from the file's pose")


@pytest.mark.parametrize("command", [["actuation", RPS, "--inputs", "P1,P1,P1"], ["jacobian", RPS, "--actuated", "P1,P1"], ["sweep", RPS, "--vary", "P1=0:1:2", "--inputs", "P1,P1"]])
def test_an_input_named_twice_is_refused(command):
    assert "'P1' is given twice; name each input once" in refused(run_cli(*command))


# -- 2. outputs: the input file, a pipe, a link loop, a missing folder -----------------------------------


@pytest.mark.parametrize("command", [["sweep", "--vary", "A=0:10:3"], ["convert"]])
def test_an_output_that_is_the_input_file_is_refused_and_the_file_kept(command, tmp_path):
    path = tmp_path / "four_bar.yaml"
    shutil.copy(FOUR_BAR, path)
    before = path.read_bytes()
    args = command[:1] + [str(path)] + command[1:] + ["-o", str(tmp_path / "." / "four_bar.yaml")]
    assert "the same file as" in refused(run_cli(*args)) and path.read_bytes() == before


@pytest.mark.parametrize("command", [["sweep", "--vary", "A=0:10:3", "-o"], ["view", "-o"], ["convert", "-o"], ["plot", "-o"], ["sweep", "--vary", "A=0:10:3", "--plot"]])
def test_an_output_that_is_a_pipe_is_refused_without_waiting_for_a_reader(command, tmp_path):
    fifo = tmp_path / ("out." + {"view": "html", "plot": "png", "convert": "yaml"}.get(command[0], "png" if command[-1] == "--plot" else "csv"))
    os.mkfifo(fifo)
    assert f"{fifo}: is a pipe or socket, expected a file to write" in refused(run_cli(*command[:1], FOUR_BAR, *command[1:], fifo))


@pytest.mark.parametrize("command, suffix", [(["sweep", "--vary", "A=0:10:3", "-o"], ".csv"), (["sweep", "--vary", "A=0:10:3", "--plot"], ".png"),
                                             (["view", "-o"], ".html"), (["plot", "-o"], ".png"), (["convert", "-o"], ".yaml")])
def test_an_output_that_is_a_symlink_loop_is_refused_before_any_work(command, suffix, tmp_path, symlink_loop):
    loop = symlink_loop(tmp_path, "out" + suffix)
    done = run_cli(*command[:1], FOUR_BAR, *command[1:], loop)  # was 3: Path.resolve raised RuntimeError
    option = command[-1]
    assert refused(done) == f"mobility: {option} {loop}: cannot write there: a symbolic link loop (too many levels of symbolic links)"


@pytest.mark.parametrize("command, suffix", [(["sweep", "--vary", "A=0:10:3", "-o"], ".csv"), (["view", "-o"], ".html"), (["plot", "-o"], ".png"), (["convert", "-o"], ".yaml")])
def test_an_output_in_a_missing_folder_is_refused_before_any_work(command, suffix, tmp_path):
    target = tmp_path / "no such folder" / ("out" + suffix)
    done = run_cli(*command[:1], FOUR_BAR, *command[1:], target)
    assert refused(done) == f"mobility: {command[-1]} {target}: cannot write there: the folder {target.parent} does not exist"


# -- 3. the environment: limit variables, a library's log line -------------------------------------------


def test_an_environment_limit_in_other_digits_is_refused():
    raises_one_line(lambda: Limits.from_environment({"MOBILITY_MAX_JOINTS": "\u0661\u0660"}), RequestError,
                    "^MOBILITY_MAX_JOINTS: expected a positive integer, got '\u0661\u0660'$")
    done = run_child("analyze", FOUR_BAR, env={"MOBILITY_MAX_JOINTS": "\u0661\u0660"})
    assert refused(done).startswith("mobility: MOBILITY_MAX_JOINTS: expected a positive integer")
    raises_one_line(lambda: Limits.from_environment({"MOBILITY_MAX_JOINTS": " 20000 "}), RequestError,  # issue 33: digits only, as files
                    "^MOBILITY_MAX_JOINTS: expected a positive integer, got ' 20000 '$")
    assert Limits.from_environment({"MOBILITY_MAX_JOINTS": "20000"}).max_joints == 20000


@pytest.mark.parametrize("value", [" 5000 ", "5000\n", "5_000", "+5000"])
def test_a_limit_variable_is_ascii_digits_only(value, monkeypatch):
    monkeypatch.setenv("MOBILITY_MAX_JOINTS", value)
    assert refused(run_cli("analyze", FOUR_BAR)).startswith("mobility: MOBILITY_MAX_JOINTS: expected a positive integer, got ")


def test_a_librarys_log_line_becomes_a_note(tmp_path):
    done = run_child("plot", FOUR_BAR, "-o", tmp_path / "p.png", env={"HOME": "/proc"}, unset=("MPLCONFIGDIR",), cwd=ROOT, timeout=120,
                     memory_cap=2 * 1024**3)
    assert done.returncode == 0, done.stderr
    lines = done.stderr.splitlines()
    assert lines and all(line.startswith("mobility: note: ") for line in lines), done.stderr
    assert any("Matplotlib created a temporary cache directory" in line for line in lines)
