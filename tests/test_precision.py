"""A file's own precision: ranks are never decided finer than the numbers of the file (issue 31).

Files of ``tests/data/cad`` are mechanisms of the library written as a CAD
exporter writes them, every number with six significant digits (see the
README there).  Each answer is checked against MuJoCo's own constraint
Jacobian (``efc_J``) of the same file: by default at the threshold the file's
precision chose, strictly (``tol``, ``--tol``) at 1e-9.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest

import mobility
from mobility.core.model import Mechanism
from mobility.core.tolerance import DEFAULT_TOLERANCE, Tolerance, file_tolerance
from mobility.errors import MechanismError
from mobility.io.precision import DigitCounter

from test_mjcf import HAND, mujoco_compile

CAD = Path(__file__).parent / "data" / "cad"
TODDLERBOT = Path(__file__).parent / "data" / "robots" / "toddlerbot" / "toddlerbot_fixed.xml"
STRICT = Tolerance(rank=1e-9)

# file: (the designer's mobility, the mobility its rounded numbers give at 1e-9)
ROUNDED = {
    "rounded_spherical_3rrr.xml": (3, 0),  # a 3-RRR spherical PM: rigid when decided finer than its digits
    "rounded_four_bar.xml": (1, 0),  # a four-bar whose four hinges are 1e-6 off parallel: jammed at 1e-9
}


def mujoco_mobility(path: Path, threshold: float) -> int:
    """``nv`` less the rank of MuJoCo's equality rows of ``efc_J`` at qpos0, singular values counted above ``threshold`` times the largest.

    Every equality is on: joint equalities are couplings of the mechanism too.
    """
    model, data = mujoco_compile(path)
    rows = [i for i in range(data.nefc) if data.efc_type[i] == mujoco.mjtConstraint.mjCNSTR_EQUALITY]
    jac = np.asarray(data.efc_J[: data.nefc * model.nv]).reshape(data.nefc, model.nv)[rows]
    s = np.linalg.svd(jac, compute_uv=False)
    return model.nv - int(np.sum(s > threshold * s[0]))


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "mobility", *args], capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("name", sorted(ROUNDED))
def test_a_file_rounded_to_six_digits_gives_the_designers_mechanism_by_default_and_the_rounded_one_when_asked(name):
    designed, rounded = ROUNDED[name]
    m = mobility.load(CAD / name)
    assert m.precision is not None and 1e-6 <= m.precision <= 1e-4  # six digits, relative to the size
    default, strict = mobility.analyze(m), mobility.analyze(m, tol=STRICT)
    assert default.rank_threshold == file_tolerance(m.precision).rank > DEFAULT_TOLERANCE.rank
    assert (default.mobility, strict.mobility) == (designed, rounded)
    assert default.mobility == mujoco_mobility(CAD / name, default.rank_threshold)  # MuJoCo agrees at the threshold above the file's precision
    assert strict.mobility == mujoco_mobility(CAD / name, 1e-9)  # and at 1e-9
    assert default.margin.largest_dropped < m.precision and default.margin.smallest_kept > 20 * default.rank_threshold


def test_a_published_biped_exported_by_onshape_to_robot_is_decided_at_its_own_precision():
    # ToddlerBot: six significant digits; knee and neck four-bars closed by welds, nine gear pairs coupled by joint
    # equalities.  At 1e-9 one of its linkages is held by its rounding (a singular value of 1e-8, relative); at its
    # precision it moves, as MuJoCo's Jacobian (every equality on) says
    robot = mobility.read_robot(TODDLERBOT)
    m = robot.mechanism
    assert len(m.couplings) == 9
    assert m.precision == 1e-05  # a quaternion's six digits: half a unit of the sixth digit, twice
    assert any(n.startswith("the file is precise to about 1.0e-05 of its size (numbers written with 6 significant digits)") for n in robot.notes)
    default, strict = mobility.analyze(m), mobility.analyze(m, tol=STRICT)
    assert (default.mobility, strict.mobility) == (32, 31)  # (41, 40) without the couplings
    assert default.mobility == mujoco_mobility(TODDLERBOT, default.rank_threshold)
    assert strict.mobility == mujoco_mobility(TODDLERBOT, 1e-9)
    assert default.margin.largest_dropped < m.precision and default.margin.smallest_kept > 20 * default.rank_threshold


def test_the_exact_mechanism_the_file_rounds_gives_the_same_answer_as_the_default():
    exact = mobility.analyze(mobility.load("mechanisms/spherical_3rrr.yaml"))
    rounded = mobility.analyze(mobility.load(CAD / "rounded_spherical_3rrr.xml"))
    assert (rounded.mobility, rounded.dof, rounded.pattern) == (exact.mobility, exact.dof, exact.pattern)
    assert exact.precision is None and exact.rank_threshold == DEFAULT_TOLERANCE.rank and exact.precision_summary == ""


def test_exact_robot_files_keep_the_default_threshold_and_their_reports():
    for path in (HAND / "four_bar.xml", HAND / "3rps.xml", HAND / "four_bar.urdf"):
        m = mobility.load(path, **({"closures": str(HAND / "four_bar_closures.yaml")} if path.suffix == ".urdf" else {}))
        assert file_tolerance(m.precision) is DEFAULT_TOLERANCE
        r = mobility.analyze(m)
        assert r.rank_threshold == DEFAULT_TOLERANCE.rank and r.precision_summary == "" and "precision" not in r.to_dict()
    text = run("analyze", str(HAND / "four_bar.xml"))
    assert text.returncode == 0 and "precision" not in text.stdout and "precise" not in text.stderr


def test_the_report_says_what_precision_was_found_and_which_threshold_decided():
    path = str(CAD / "rounded_four_bar.xml")
    text = run("analyze", path)
    assert text.returncode == 0, text.stderr
    assert "  precision: the file is precise to 1.0e-05 of its size: ranks decided at 1.0e-03 (100 x its precision) instead of 1e-08" in text.stdout
    assert "mobility M = 1" in text.stdout
    assert "mobility: note: the file is precise to about 1.0e-05 of its size (numbers written with 6 significant digits)" in text.stderr
    data = json.loads(run("analyze", "--json", path).stdout)
    assert data["mobility"] == 1 and data["precision"] == {"value": 1e-05, "rank_threshold": 0.001, "raised": True}
    markdown = run("analyze", "--format", "md", path).stdout
    assert "Precision: the file is precise to 1.0e-05 of its size" in markdown
    strict = run("analyze", "--tol", "1e-9", "--json", path)
    data = json.loads(strict.stdout)
    assert data["mobility"] == 0 and data["precision"] == {"value": 1e-05, "rank_threshold": 1e-09, "raised": False}
    assert "ranks decided at 1.0e-09 as asked (its precision would give 1.0e-03)" in run("analyze", "--tol", "1e-9", path).stdout


def test_digits_tell_a_rounded_file_from_one_written_by_hand_or_in_full():
    cad = DigitCounter()
    cad.add("-0.0926361 0.0115732 0.0764594", "length")
    cad.add("2.35619 -2.01031e-14 1.5708", "angle")  # 1.5708 is 1.57080: %g drops the zero
    r = cad.rounding()
    assert (r.digits, r.length, r.angle) == (6, 5e-08, 5e-06)
    quaternion = DigitCounter()
    quaternion.add("0.707107 0 0.707107 0", "quat")
    assert quaternion.rounding().angle == 1e-06  # a quaternion turns by twice its error
    hand = DigitCounter()
    hand.add("0 0.25 1.5 120.5", "length")
    hand.add("0 0 1", "unit")
    assert hand.rounding() is None
    full = DigitCounter()
    full.add("0.30000000000000004 1.5707963267948966", "length")
    assert full.rounding().digits == 17 and file_tolerance(full.rounding().length) is DEFAULT_TOLERANCE


def test_a_mechanism_refuses_a_precision_that_is_not_a_number_at_least_zero():
    m = mobility.load("mechanisms/four_bar.yaml")
    for bad in (-1e-6, float("nan"), "1e-6", True):
        with pytest.raises(MechanismError, match="precision"):
            Mechanism(m.name, m.ground, m.end_effector, m.joints, precision=bad)
    assert m.replace(precision=1e-6) == m and m.replace(precision=1e-6).precision == 1e-6  # not part of its value


def test_a_precision_given_in_code_raises_the_threshold_up_to_its_ceiling_and_tol_still_decides():
    m = mobility.load("mechanisms/four_bar.yaml").replace(precision=1e-4)  # coarser than 1e-3 / 100: the ceiling decides
    r = mobility.analyze(m)
    assert r.rank_threshold == 1e-3 and r.mobility == 1
    assert r.precision_summary.startswith("the file is precise to 1.0e-04 of its size: ranks decided at 1.0e-03 (its ceiling) instead of 1e-08")
    asked = mobility.analyze(m, tol=DEFAULT_TOLERANCE)
    assert asked.rank_threshold == 1e-8 and "as asked (its precision would give 1.0e-03)" in asked.precision_summary
    fine = m.replace(precision=1e-11)  # 100 x 1e-11 is below the default: nothing changes, nothing is said
    assert mobility.analyze(fine).rank_threshold == 1e-8 and mobility.analyze(fine).precision_summary == ""


def test_a_urdf_written_with_seven_digits_is_read_as_such_and_its_open_chain_keeps_its_answer():
    m = mobility.load(Path(__file__).parent / "data" / "robots" / "rtb_data" / "puma560_robot.urdf")
    assert m.precision == 5e-07  # rpy written with seven digits (1.570796): half a unit of the seventh
    default, strict = mobility.analyze(m), mobility.analyze(m, tol=STRICT)
    assert default.rank_threshold == 5e-05 and (default.dof, default.mobility) == (strict.dof, strict.mobility) == (5, 6)
