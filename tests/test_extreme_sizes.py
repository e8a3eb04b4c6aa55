"""Extreme sizes: a large mechanism or request ends in an answer, or in one line naming the limit and its variable, in bounded time and memory.

Where a new test goes: a test of a *valid* input whose size is extreme -- thousands of joints, many poses
times joints, a name of 200,000 characters, a nesting depth raised by the environment -- or of a limit
(``MOBILITY_MAX_*``) that refuses it before any work, through the library or any command, goes here.  A
refusal is asserted with :func:`guards.refused`, an answer of every command with :func:`guards.run_all`;
whatever may exhaust memory runs in a child process whose address space is capped.  A *file* beyond a
reader limit (copies, nodes, depth as written) goes in ``test_bad_files.py``; extreme *magnitudes* of
numbers in ``test_extreme_numbers.py``; the analysis of large families itself in ``test_large.py``.

The large cases run every command (``analyze``, ``check``, ``actuation``, ``plot``, ``jacobian``,
``sweep``, ``view``, ``convert``, with their options) in a child process whose address space is capped
(``RLIMIT_AS``): a memory blow-up ends there in a ``MemoryError``, reported as a failure, instead of in
the machine's swap.
"""

from __future__ import annotations

import json
import math
import os
import resource
import subprocess
import sys
from pathlib import Path
from typing import Callable

import pytest

import mobility
from mobility.core.model import Joint, Mechanism
from mobility.io.writer import mechanism_to_yaml

from builders import prs_limbs, serial_chain, triangle_ladder, yaml_text
from guards import RUN_BOUND, refused, run_all, run_child, run_cli

ROOT = Path(__file__).resolve().parent.parent
BOUNDED = {"seconds": RUN_BOUND, "warnings_as_errors": RuntimeWarning}
"""How a command runs here: under the time guard, a numpy warning an error (it would reach stderr)."""


# -- 1. every command on a large mechanism, in bounded memory ------------------------------------------------


MEMORY_CAP = 3 << 29
"""Address space of the child process running the large cases (bytes): 1.5 GiB, about three times what
the largest run maps (460 MB, of which the libraries alone are most; 190 MB resident); the plot that
once built every pair of points in every view (24 GB) stops here."""


LARGE: dict[str, Callable[[], Mechanism]] = {
    "ladder of 2,001 joints": lambda: triangle_ladder(1000, actuated=True),  # 2 n + 1 joints, series inside parallel n deep
    "180-joint parallel mechanism": lambda: prs_limbs(60, actuated=True),  # 1T2R
}


def child_main(case: str, folder: str) -> None:
    """In the child process: cap the address space, run every command on the large case, print the outcomes as JSON."""
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_CAP, MEMORY_CAP))
    outcome = run_all(LARGE[case](), Path(folder))
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    print(json.dumps({"outcome": outcome, "peak_bytes": peak}))


@pytest.mark.parametrize("case", sorted(LARGE))
def test_every_command_on_a_large_mechanism_answers_or_refuses_in_bounded_memory(case, tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg", OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    done = subprocess.run([sys.executable, __file__, case, str(tmp_path)], capture_output=True, text=True, timeout=600, env=env, cwd=ROOT)
    assert done.returncode == 0, done.stderr[-2000:]
    report = json.loads(done.stdout.splitlines()[-1])
    outcome = {name: tuple(v) for name, v in report["outcome"].items()}
    failures = {name: why for name, (_, why) in outcome.items() if why}
    assert not failures, failures
    refusing = {name for name, (status, _) in outcome.items() if status == 2}
    # what may refuse, by its own limit: finite motion beyond 50 joints, enumeration beyond 200 (or its
    # count of combinations), moving beyond 300; a ladder has no serial limbs for a Jacobian
    allowed = {"analyze --finite", "actuation --enumerate", "actuation --samples", "sweep", "view --samples"} if "ladder" in case else {"analyze --finite", "actuation --enumerate"}
    assert refusing <= allowed | ({"jacobian"} if "ladder" in case else set()), refusing
    assert report["peak_bytes"] < MEMORY_CAP


# -- 2. a command beyond its limit names the limit and its variable ------------------------------------------


def test_a_command_beyond_its_limit_names_the_limit_and_its_variable(tmp_path, monkeypatch):
    path = tmp_path / "prs.yaml"
    path.write_text(yaml_text(prs_limbs(4, actuated=True)), encoding="utf-8")  # 12 joints
    done = run_cli("analyze", "--finite", path, **BOUNDED)
    assert done.returncode == 0 and "full-cycle" in done.stdout, done.stderr  # within the default limit of 50
    monkeypatch.setenv("MOBILITY_MAX_FINITE_JOINTS", "11")
    err = refused(run_cli("analyze", "--finite", path, **BOUNDED))
    assert f"mobility: {path}: joints: 12 joints are more than the limit of 11 for --finite (set MOBILITY_MAX_FINITE_JOINTS to raise it)" in err
    monkeypatch.setenv("MOBILITY_MAX_FINITE_JOINTS", "12")
    done = run_cli("analyze", "--finite", path, **BOUNDED)
    assert done.returncode == 0 and "full-cycle" in done.stdout, done.stderr
    monkeypatch.setenv("MOBILITY_MAX_MOVING_JOINTS", "11")
    for args in (["sweep", str(path), "--vary", "R0=0:1:2"], ["view", "--samples", "1", str(path), "-o", str(tmp_path / "v.html")], ["actuation", "--samples", "1", str(path)]):
        err = refused(run_cli(*args, **BOUNDED))
        assert "more than the limit of 11" in err and "MOBILITY_MAX_MOVING_JOINTS" in err, (args, err)


def test_an_enumeration_too_large_is_refused_with_its_exact_count_before_any_is_listed(tmp_path, monkeypatch):
    # two candidates (P, R) in each of 70 limbs, 3 DOF: one in each of 3 limbs, C(70, 3) * 2**3 combinations,
    # counted limb by limb (the 54,740 choices of limbs are never listed); once 2**70, one in every limb
    monkeypatch.setenv("MOBILITY_MAX_ENUMERATED_JOINTS", "1000")
    path = tmp_path / "prs.yaml"
    path.write_text(yaml_text(prs_limbs(70, actuated=True)), encoding="utf-8")
    assert f"mobility: {math.comb(70, 3) * 2**3} combinations to try" in refused(run_cli("actuation", "--enumerate", path, **BOUNDED))


def test_a_raised_depth_limit_keeps_the_cost_in_proportion(tmp_path):
    deep = tmp_path / "deep.yaml"
    deep.write_text("name: x\nground: g\nend_effector: c\njoints: " + "[" * 50_000 + "]" * 50_000 + "\n")  # 100 kB
    done = run_child("analyze", deep, env={"MOBILITY_MAX_DEPTH": "1000000"}, unset=("MPLCONFIGDIR",), cwd=ROOT, timeout=30,
                     memory_cap=2 * 1024**3)  # past 90 s at 3 GB before
    assert "nested deeper than the limit of 1000 levels (the most a YAML document may nest whatever MOBILITY_MAX_DEPTH says" in refused(done)


# -- 3. the budget of poses times joints ----------------------------------------------------------------------


@pytest.fixture
def chain_file(tmp_path):
    def write(joints: int):
        path = tmp_path / f"chain{joints}.yaml"
        path.write_text(mechanism_to_yaml(serial_chain(joints)), encoding="utf-8")
        return path
    return write


def test_actuation_samples_beyond_the_budget_are_refused_before_any_work(chain_file, monkeypatch):
    path = chain_file(100)
    assert refused(run_cli("actuation", path, "--samples", "60")) == (
        f"mobility: --samples 60: 60 poses x 100 joints of {path} = 6,000 pose-joints, more than the limit of 5,000 "
        "(ask for fewer poses, or set MOBILITY_MAX_MOVING_WORK to raise it)")
    done = run_cli("actuation", path, "--samples", "50")  # 5,000: within the budget
    assert done.returncode in (0, 1) and "sampled pose 50" in done.stdout, done.stderr
    monkeypatch.setenv("MOBILITY_MAX_MOVING_WORK", "6000")
    done = run_cli("actuation", path, "--samples", "60")
    assert done.returncode in (0, 1) and "sampled pose 60" in done.stdout, done.stderr


def test_view_samples_and_vary_beyond_the_budget_are_refused(chain_file, tmp_path):
    path = chain_file(30)
    page = tmp_path / "v.html"
    err = refused(run_cli("view", path, "--samples", "199", "-o", page))
    assert "--samples 199: 199 poses x 30 joints" in err and "= 5,970 pose-joints, more than the limit of 5,000" in err and "MOBILITY_MAX_MOVING_WORK" in err
    err = refused(run_cli("view", path, "--vary", "J1=0:10:1000", "-o", page))  # a view draws 200 of the 1,000 poses
    assert "--vary (a grid of 1,000 poses, 200 of them drawn): 200 poses x 30 joints" in err and "= 6,000 pose-joints" in err
    assert not page.exists()
    done = run_cli("view", "mechanisms/four_bar.yaml", "--samples", "3", "-o", page)  # moderate: runs
    assert done.returncode == 0 and "4 poses" in done.stdout, done.stderr


# -- 4. long names in pictures -------------------------------------------------------------------------------


LONG = 200_000


MAX_LABEL = 40
"""The characters of a name a picture writes (``MAX_LABEL`` of ``mobility/report/plotting/style.py``)."""


def long_named() -> Mechanism:
    """The four-bar with a link, a joint and the mechanism named by 200,000 characters each."""
    link, joint = "L" * LONG, "J" * LONG
    z = (0.0, 0.0, 1.0)
    return Mechanism("N" * LONG, "ground", "coupler", (
        Joint(joint, "R", ("ground", link), axis=z, point=(0.0, 0.0, 0.0)),
        Joint("B", "R", (link, "coupler"), axis=z, point=(1.0, 2.0, 0.0)),
        Joint("C", "R", ("coupler", "rocker"), axis=z, point=(4.0, 2.5, 0.0)),
        Joint("D", "R", ("rocker", "ground"), axis=z, point=(5.0, 0.0, 0.0)),
    ))


def drawn_texts(fig) -> list[str]:
    from matplotlib.text import Text

    return [t.get_text() for t in fig.findobj(Text)]


def test_a_long_name_is_clipped_in_the_picture_of_the_mechanism():
    from mobility.report.plotting import plot_mechanism, style

    texts = drawn_texts(plot_mechanism(long_named()))
    clipped_joint = "J" * (MAX_LABEL - 3) + "..."
    assert clipped_joint in texts  # the joint's label, cut
    assert max(len(t) for t in texts) < 200
    title = next(t for t in texts if "end effector 1 DOF" in t)
    assert title.startswith("N" * (MAX_LABEL - 3) + "...: end effector 1 DOF (1R), mobility 1")
    assert style.MAX_LABEL == MAX_LABEL


def test_a_long_name_is_clipped_in_the_joint_graph():
    from mobility.report.plotting import plot_graph

    texts = drawn_texts(plot_graph(long_named()))
    assert max(len(t) for t in texts) < 200
    assert "L" * (MAX_LABEL - 3) + "..." in texts  # the link's box
    assert "J" * (MAX_LABEL - 3) + "... (R)" in texts  # the joint's label on the graph
    assert "J" * (MAX_LABEL - 3) + "...\nR" in texts  # the joint's leaf of the tree
    assert any(t.startswith("N" * (MAX_LABEL - 3) + "...: mobility 1") for t in texts)


def test_a_long_name_is_clipped_in_the_picture_of_a_sweep():
    from mobility.report.sweep_plot import plot_sweep

    m = long_named()
    result = mobility.sweep(m, [f"{'J' * LONG}=0:30:4"])
    texts = drawn_texts(plot_sweep(result))
    assert max(len(t) for t in texts) < 200
    assert "J" * (MAX_LABEL - 3) + "... [deg]" in texts  # the swept coordinate on the axis
    assert "N" * (MAX_LABEL - 3) + "..." in texts  # the title
    assert len(result.axes[0].name) == LONG  # the result keeps the name whole


if __name__ == "__main__":  # the child process of the large cases
    child_main(sys.argv[1], sys.argv[2])
