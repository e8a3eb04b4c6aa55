"""Advice on closures: how many constraint rows of each closing joint are independent, and along which screws the others are redundant.

The second route is MuJoCo's own constraint Jacobian of the same file: the rows
of one equality, projected off the row space of the other equalities' rows,
have as their rank the number of that closure's independent rows.
"""

from __future__ import annotations

import json
import subprocess
import sys

import mujoco
import numpy as np
import pytest

import mobility
from mobility.core.closures import closure_advice
from mobility.core.transforms import Transform, rotation_from_rpy
from mobility.errors import RequestError
from mobility.io.robot_files import read_robot

from builders import transformed  # noqa: E402  (tests/ is on the path)
from test_mjcf import HAND, compiled_at_qpos0, fixed_gripper, mujoco_compile


def mujoco_independent_rows(model, data) -> list[int]:
    """For each active equality of the model, the rank of its rows of ``efc_J`` off the row space of the others' rows."""
    equality = [i for i in range(data.nefc) if data.efc_type[i] == mujoco.mjtConstraint.mjCNSTR_EQUALITY]
    jac = np.asarray(data.efc_J[: data.nefc * model.nv]).reshape(data.nefc, model.nv)
    ranks = []
    for eq in range(model.neq):
        own = jac[[i for i in equality if data.efc_id[i] == eq]]
        if not len(own):  # an equality not active at this pose
            continue
        others = jac[[i for i in equality if data.efc_id[i] != eq]]
        if len(others):
            _, s, vt = np.linalg.svd(others)
            span = vt[: int(np.sum(s > 1e-9 * s[0]))]
            own = own - (own @ span.T) @ span
        s = np.linalg.svd(own, compute_uv=False)
        ranks.append(int(np.sum(s > 1e-9 * max(1.0, float(np.abs(jac).max())))))
    return ranks


def test_a_planar_four_bar_closed_by_a_point_constraint_has_one_redundant_row_along_the_plane_normal():
    robot = read_robot(HAND / "four_bar.xml")
    assert robot.closures == ("C",)
    (c,) = closure_advice(robot.mechanism, robot.closures)
    assert (c.rows, c.independent, c.redundant) == (3, 2, 1)
    assert c.couples.shape == (0, 3) and len(c.forces) == 1
    force = c.forces[0]
    assert force.kind == "force" and np.allclose(np.abs(force.axis), [0, 0, 1], atol=1e-12)
    assert np.allclose(force.point[:2], robot.mechanism.joint("C").point[:2], atol=1e-12)  # its line passes through the anchor
    assert mujoco_independent_rows(*mujoco_compile(HAND / "four_bar.xml")) == [c.independent]


def test_each_finger_of_the_published_gripper_has_one_redundant_row_along_its_hinges(tmp_path):
    path = fixed_gripper(tmp_path)
    robot = read_robot(path, ignore_unsupported=True)
    assert sorted(robot.closures) == ["connect0", "connect1"]
    advice = closure_advice(robot.mechanism, robot.closures)
    assert [(a.rows, a.independent) for a in advice] == [(3, 2), (3, 2)]
    for a in advice:  # each finger's loop is planar, its hinges along x: the redundant row is the force along x
        (force,) = a.forces
        assert np.allclose(np.abs(force.axis), [1, 0, 0], atol=1e-9)
    model, data = mujoco_compile(path)
    connects = [e for e in range(model.neq) if model.eq_type[e] == mujoco.mjtEq.mjEQ_CONNECT]
    model.eq_active0[[e for e in range(model.neq) if e not in connects]] = 0  # the joint coupling is left out, as in the mechanism
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert mujoco_independent_rows(model, data) == [a.independent for a in advice]


def test_a_spatial_closure_has_every_row_independent():
    robot = read_robot(HAND / "3rps.xml")
    advice = closure_advice(robot.mechanism, robot.closures)
    assert len(advice) == 2 and all((a.rows, a.independent, a.redundant) == (3, 3, 0) for a in advice)
    assert all(a.wrenches.shape == (0, 6) for a in advice)
    assert mujoco_independent_rows(*mujoco_compile(HAND / "3rps.xml")) == [3, 3]


def test_a_revolute_closure_of_the_planar_four_bar_repeats_the_three_planar_constraints():
    # an R joint closing the loop has 5 rows; the planar rest already holds the force along z and the couples about x
    # and y, which are G-K's three redundant constraints of the planar four-bar
    m = mobility.load("mechanisms/four_bar.yaml")
    (c,) = closure_advice(m, ["C"])
    assert (c.rows, c.independent, c.redundant) == (5, 2, 3)
    assert c.redundant == mobility.analyze(m).redundant_constraints
    assert np.allclose(np.abs(c.couples), [[1, 0, 0], [0, 1, 0]], atol=1e-12) and c.forces[0].kind == "force"


@pytest.mark.parametrize("scale", [1e-6, 1.0, 1e6])
def test_the_advice_does_not_depend_on_the_unit_or_the_frame(scale):
    m = mobility.load("mechanisms/four_bar.yaml")
    rotation = rotation_from_rpy((0.3, -0.2, 1.1))
    moved = transformed(m, Transform(rotation, np.array([5.0, -2.0, 7.0])), scale)
    (a,), (b,) = closure_advice(m, ["C"]), closure_advice(moved, ["C"])
    assert (a.rows, a.independent, len(a.forces), len(a.couples)) == (b.rows, b.independent, len(b.forces), len(b.couples))
    assert np.allclose(np.abs(b.forces[0].axis), np.abs(rotation @ a.forces[0].axis), atol=1e-9)  # the redundant force moved with it
    through = rotation @ (np.asarray(a.forces[0].point) * scale) + np.array([5.0, -2.0, 7.0])
    offset = np.asarray(b.forces[0].point) - through
    assert np.linalg.norm(np.cross(offset, b.forces[0].axis)) < 1e-9 * (10.0 * scale + 10.0)  # on the moved line


def test_a_joint_on_no_loop_has_every_row_independent_and_a_bad_request_is_refused():
    m = mobility.load("mechanisms/scara.yaml")
    advice = closure_advice(m, [m.joints[0].name])
    assert advice[0].redundant == 0 and advice[0].independent == advice[0].rows
    with pytest.raises(RequestError, match="is not a joint of"):
        closure_advice(m, ["nowhere"])
    with pytest.raises(RequestError, match="joints must be a list of joint names"):
        closure_advice(m, m.joints[0].name)


def test_analyze_reports_the_closures_of_a_robot_file_in_text_and_json():
    run = lambda *a: subprocess.run([sys.executable, "-m", "mobility", "analyze", *a], capture_output=True, text=True, timeout=120)  # noqa: E731
    text = run(str(HAND / "four_bar.xml"))
    assert text.returncode == 0
    assert "  C: 3 rows, 2 independent, 1 redundant\n    redundant: force along [0, 0, 1] through [4, 2.5, 0]" in text.stdout
    data = json.loads(run("--json", str(HAND / "four_bar.xml")).stdout)
    assert data["closures"] == [{"joint": "C", "rows": 3, "independent": 2, "redundant": 1, "redundant_couples": [],
                                 "redundant_forces": [{"axis": [0.0, 0.0, 1.0], "point": [4.0, 2.5, 0.0], "pitch": 0.0, "kind": "force"}]}]
    plain = run("mechanisms/four_bar.yaml")
    assert plain.returncode == 0 and "closures" not in plain.stdout  # a mechanism file names no closure


def test_the_view_of_a_robot_file_shows_the_advice_on_its_closures(tmp_path):
    run = lambda *a: subprocess.run([sys.executable, "-m", "mobility", "view", *a], capture_output=True, text=True, timeout=120)  # noqa: E731
    page = tmp_path / "four_bar.html"
    assert run(str(HAND / "four_bar.xml"), "-o", str(page)).returncode == 0
    html = page.read_text(encoding="utf-8")
    assert "C: 3 rows, 2 independent, 1 redundant" in html and "redundant: force along [0, 0, 1] through [4, 2.5, 0]" in html
    plain = tmp_path / "plain.html"
    assert run("mechanisms/four_bar.yaml", "-o", str(plain)).returncode == 0
    assert "independent, " not in plain.read_text(encoding="utf-8")  # a mechanism file names no closure
