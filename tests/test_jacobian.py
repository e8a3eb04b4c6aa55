"""Jacobians by differentiating finite screws (Eq. 26), checked against finite differences and the analyzer."""

import json
import math

import numpy as np
import pytest

import mobility
from mobility.cli import main
from mobility.errors import AnalysisError, MechanismError, RequestError
from mobility.jacobians import jacobian, parallel_model, wrench_axis
from mobility.report.jacobian import jacobian_json, jacobian_text
from mobility.core.screws import SWAP, reciprocal_product, same_subspace

from conftest import MECHANISMS

METROM = MECHANISMS / "metrom.yaml"


@pytest.fixture(scope="module")
def metrom():
    return mobility.load(METROM)


@pytest.fixture(scope="module")
def model(metrom):
    return parallel_model(metrom)


def force_line(direction, point):
    d = np.asarray(direction, float)
    return np.concatenate([d, np.cross(point, d)])[:, None]


def test_metrom_at_home(metrom):
    jac = jacobian(metrom)
    result = mobility.analyze(metrom)
    assert jac.dof == result.dof == 5
    assert jac.actuated == ("P0", "P1", "P2", "P3", "P4")
    assert not jac.singular and jac.matrix.shape == (6, 6)
    # the constraint: a force through O along s1 x s2 (s1 = z the SPR leg, s2 = y: -x)
    assert same_subspace(jac.constraint_wrenches.T, force_line([-1, 0, 0], [0, 0, 0]))
    kind, d, p, h = wrench_axis(jac.constraint_wrenches[0])
    assert kind == "force" and np.allclose(np.abs(d), [1, 0, 0]) and np.allclose(p, 0, atol=1e-9)
    # the analyzer's systems, compared as subspaces
    assert same_subspace(jac.constraint_wrenches.T, result.wrenches.T)
    assert same_subspace(jac.platform_twists.T, result.twists.T)
    assert same_subspace(jac.twist_map, result.twists.T)
    # the actuation wrench of a P leg is the force along the leg
    for label, w in zip(jac.actuated[1:], jac.actuation_wrenches[1:]):
        joint = metrom.joint(label)
        assert same_subspace(w[:, None], force_line(joint.axis, metrom.joint("S" + label[1:]).point))
    assert same_subspace(jac.actuation_wrenches[0][:, None], force_line([0, 0, 1], [0, 0, 0]))
    # J maps the twist per unit rate of each input to that unit rate and nothing else
    assert np.allclose(jac.matrix @ jac.twist_map, np.eye(6)[:, :5], atol=1e-9)


def random_pose(model, seed):
    """A pose reached by moving the SPR limb's joints; the other limbs follow by inverse kinematics."""
    rng = np.random.default_rng(seed)
    spr = model.chains[0].limb
    q0 = np.concatenate([rng.uniform(-0.3, 0.3, 3), [rng.uniform(-80, 80)], [rng.uniform(-0.3, 0.3)]])
    q = model.assemble(spr.transform(q0))
    assert np.allclose(q[0], q0, atol=1e-7)
    return q


@pytest.mark.parametrize("seed", [1, 2])
def test_metrom_away_from_home_against_the_analyzer(model, seed):
    q = random_pose(model, seed)
    jac = jacobian(model, q)
    moved = model.mechanism_at(q)
    result = mobility.analyze(moved)
    assert (result.dof, result.pattern) == (jac.dof, "2T3R") == (5, "2T3R")
    assert same_subspace(jac.constraint_wrenches.T, result.wrenches.T)
    assert same_subspace(jac.platform_twists.T, result.twists.T)
    # the constraint is still a force through O, along the moved s1 x s2 (the axis of the SPR limb's R)
    r_axis = model.chains[0].limb.moved(q[0]).joints[-1].axis
    assert same_subspace(jac.constraint_wrenches.T, force_line(r_axis, [0, 0, 0]))
    # and the same Jacobian is found by taking the moved mechanism as a new home
    again = jacobian(moved)
    assert np.allclose(again.matrix, jac.matrix, atol=1e-8 * np.abs(jac.matrix).max())


@pytest.mark.parametrize("seed", [3, 4])
def test_metrom_jacobian_against_finite_differences_of_the_finite_model(model, seed):
    """Move the SPR limb's joints by ±h, re-solve the other limbs, difference the actuated joints."""
    q = random_pose(model, seed)
    jac = jacobian(model, q)
    rng = np.random.default_rng(100 + seed)
    spr = model.chains[0].limb
    delta = rng.normal(size=5)
    h = 1e-5
    plus = model.assemble(spr.transform(q[0] + h * delta), start=q)
    minus = model.assemble(spr.transform(q[0] - h * delta), start=q)
    rates = np.array([(plus[c][p] - minus[c][p]) / (2 * h) for c, p in model.actuated])
    twist = spr.twists(q[0]) @ delta  # Eq. 26 for the SPR limb
    # the twist itself against the matrix finite difference
    tp, tm, t0 = spr.transform(q[0] + h * delta), spr.transform(q[0] - h * delta), spr.transform(q[0])
    x = (tp - tm) / (2 * h) @ np.linalg.inv(t0)
    assert np.allclose(twist, np.concatenate([[x[2, 1], x[0, 2], x[1, 0]], x[:3, 3]]), rtol=1e-6, atol=1e-6)
    predicted = jac.matrix @ twist
    assert np.allclose(predicted[:5], rates, rtol=1e-5, atol=1e-5 * np.abs(rates).max())
    assert abs(predicted[5]) < 1e-9 * np.abs(jac.matrix[5]).max() * np.abs(twist).max()
    # and the forward map gives the twist back from the rates
    assert np.allclose(jac.twist_map @ rates, twist, rtol=1e-4, atol=1e-6 * np.abs(twist).max())


def test_actuation_wrench_products(model):
    q = random_pose(model, 5)
    jac = jacobian(model, q)
    for w, (c, p) in zip(jac.actuation_wrenches, model.actuated):
        t = jac.limb_twists[c]
        assert math.isclose(float(reciprocal_product(w, t[:, p])), 1.0, rel_tol=1e-9)
        others = np.delete(t, p, axis=1)
        assert np.allclose(reciprocal_product(w[:, None], others), 0.0, atol=1e-9 * np.abs(t).max())
    assert np.allclose(jac.matrix[:5], (SWAP @ jac.actuation_wrenches.T).T)


@pytest.mark.parametrize("path", sorted(MECHANISMS.glob("pkm_*.yaml")), ids=lambda p: p.name)
def test_table_1_pkms_jacobian_matches_the_analyzer(path):
    m = mobility.load(path)
    jac = jacobian(m)
    result = mobility.analyze(m)
    assert jac.dof == 5 and not jac.singular
    assert same_subspace(jac.constraint_wrenches.T, result.wrenches.T)
    assert same_subspace(jac.platform_twists.T, result.twists.T)


def test_symmetric_layout_is_an_actuation_singularity():
    from mobility.synthesis import assemble_pkm, named_pattern, synthesize

    res = synthesize(named_pattern("2T3R", directions=((0, 0, 1), (0, 1, 0))), joints=5, verify_samples=0, generic_points=1)
    m = assemble_pkm(res, "SP1Rc", other="SPRR", twist_pattern=(1, 1, 1, 1))
    jac = jacobian(m)
    assert jac.singular and jac.rank == 5 and jac.twist_map is None
    assert mobility.analyze(m).dof == 5  # the platform still has 5 DOF: only the actuation fails


def test_errors(metrom):
    with pytest.raises(MechanismError):
        jacobian(metrom, actuated=["nope"])
    with pytest.raises(MechanismError):
        jacobian(metrom.replace(joints=tuple(j if not j.actuated else j.__class__(j.name, j.type, j.links, j.axis) for j in metrom.joints)))
    tie = mobility.loads(
        """
name: tie
ground: g
end_effector: e
joints:
  - {name: A, type: R, links: [g, a], axis: [0, 0, 1], point: [0, 0, 0], actuated: true}
  - {name: B, type: R, links: [a, e], axis: [0, 0, 1], point: [1, 0, 0]}
  - {name: C, type: R, links: [a, b], axis: [0, 0, 1], point: [0, 1, 0]}
  - {name: D, type: R, links: [b, e], axis: [0, 0, 1], point: [1, 1, 0]}
"""
    )
    with pytest.raises(MechanismError):
        jacobian(tie)
    model = parallel_model(metrom)
    q = list(model.home())
    q[1] = q[1] + 0.1
    with pytest.raises(AnalysisError):
        jacobian(model, q)


def test_reversed_joints_and_multi_dof_inputs():
    """A limb written from the platform side and a U named by freedom: same twists as written forward."""
    fwd = mobility.loads(
        """
name: arm
ground: g
end_effector: e
joints:
  - {name: U, type: U, links: [g, a], point: [0, 0, 0], axes: [[0, 0, 1], [0, 1, 0]]}
  - {name: P, type: P, links: [a, e], axis: [1, 0, 0]}
"""
    )
    rev = mobility.loads(
        """
name: arm reversed
ground: g
end_effector: e
joints:
  - {name: P, type: P, links: [e, a], axis: [-1, 0, 0]}
  - {name: U, type: U, links: [a, g], point: [0, 0, 0], axes: [[0, 1, 0], [0, 0, 1]]}
"""
    )
    a = jacobian(fwd, actuated=["U.0", "U.1", "P"])
    b = jacobian(rev, actuated=["U.0", "U.1", "P"])
    assert a.dof == b.dof == 3
    assert same_subspace(a.platform_twists.T, b.platform_twists.T)
    model = parallel_model(rev, actuated=["P"])
    q = [np.array([0.3, 0.4, -0.2])]  # chain order: P, then U's freedoms reversed
    moved = model.mechanism_at(q)
    assert same_subspace(jacobian(moved, actuated=["P"]).platform_twists.T, mobility.analyze(moved).twists.T)


# -- command line ----------------------------------------------------------------------------


def test_cli_jacobian(capsys):
    assert main(["jacobian", str(METROM)]) == 0
    out = capsys.readouterr().out
    assert "platform DOF: 5" in out and "force   along [1, 0, 0]  through [0, 0, 0]" in out
    assert main(["jacobian", str(METROM), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["dof"] == 5 and len(data["matrix"]) == 6 and data["constraint_axes"][0]["kind"] == "force"
    assert main(["jacobian", str(METROM), "--actuated", "P0,P1,P2,P3"]) == 1  # 4 inputs for 5 DOF: not square
    capsys.readouterr()
    assert main(["jacobian", str(METROM), "--actuated", "P0,Q"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "metrom.yaml" in err and "'Q'" in err


def test_cli_synthesize(capsys, tmp_path):
    assert main(["synthesize", "2T3R", "--joints", "2", "--verify", "1"]) == 0
    out = capsys.readouterr().out
    assert "U " in out and "P1P2" in out
    assert main(["synthesize", "3R", "--json", "--write", str(tmp_path)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [s["name"] for s in data["structures"]] == ["S"]
    assert main(["synthesize", "9T"]) == 2
    assert capsys.readouterr().err.count("\n") == 1


# -- pieces: closure by the policy, wrench axes, the report ---------------------------------


def test_closure_is_decided_by_the_policy(model):
    q = random_pose(model, 6)
    assert model.closure_error(q) <= mobility.DEFAULT_TOLERANCE.closure
    off = [v.copy() for v in q]
    off[1][0] += 1e-9  # one joint of another limb: the limbs no longer meet, by about 1e-9
    assert 1e-10 < model.closure_error(off) < 1e-8
    with pytest.raises(AnalysisError):
        model.mechanism_at(off)
    with pytest.raises(AnalysisError):
        jacobian(model, off)
    loose = mobility.Tolerance(closure=1e-6)
    assert jacobian(model, off, tol=loose).dof == 5
    assert mobility.analyze(model.mechanism_at(off, tol=loose)).dof == 5
    with pytest.raises(RequestError):
        jacobian(model, q[:-1])  # one limb's values missing


def test_wrench_axis_against_the_screw_written_from_its_parts():
    rng = np.random.default_rng(2)
    for _ in range(5):
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        p = rng.normal(size=3) * 100
        p -= (p @ d) * d  # the point nearest the origin
        h = rng.normal()
        w = 3.0 * np.concatenate([d, np.cross(p, d) + h * d])
        kind, dd, pp, hh = wrench_axis(w)
        assert kind == "wrench" and np.allclose(dd, d) and np.allclose(pp, p) and math.isclose(hh, h)
    assert wrench_axis(np.array([0.0, 0, 0, 0, 2, 0]))[:2][0] == "couple"
    assert wrench_axis(np.array([1e-14, 0, 0, 0, 2, 0]))[0] == "couple"  # a force at round-off next to the moment
    assert wrench_axis(np.array([1e-6, 0, 0, 0, 2, 0]))[0] == "force"


def test_jacobian_report_is_what_the_cli_prints(metrom, capsys):
    jac = jacobian(metrom)
    text = jacobian_text(jac, metrom.length_unit)
    assert main(["jacobian", str(METROM)]) == 0
    assert capsys.readouterr().out == text + "\n"
    lines = text.splitlines()
    assert lines[0] == metrom.name and "    C1  force   along [1, 0, 0]  through [0, 0, 0]" in lines
    assert json.loads(jacobian_json(jac)) == jac.to_dict() | {"condition": jac.condition}
    square_not = jacobian(metrom, actuated=["P0", "P1", "P2", "P3"])
    assert "J is singular (rank 5 < 6, 5 rows): the actuated joints do not control the platform at this pose" in jacobian_text(square_not)


@pytest.mark.parametrize("inputs, verdict", [(["P1", "P2", "P3", "P4"], "redundant"), (["P1", "P2", "P3"], "valid"), (["P1", "P2"], "actuation-singular")])
def test_the_4puu_jacobian_agrees_with_the_actuation_verdict_redundant_inputs_included(inputs, verdict):
    m = mobility.load(MECHANISMS / "4puu.yaml")
    jac = jacobian(m, actuated=inputs)
    assert mobility.check_actuation(m, inputs).verdict == verdict  # the screw route, independent of the Jacobian
    assert jac.matrix.shape == (len(inputs) + 3, 6)
    assert jac.singular == (verdict == "actuation-singular")
    assert jac.redundant == (1 if verdict == "redundant" else 0)
    assert (jac.twist_map is not None) == (verdict == "valid")
    assert jac.rank == (5 if verdict == "actuation-singular" else 6)


def _three_hrs(pitch: float) -> mobility.Mechanism:
    """The bundled 3-PRS with its actuated sliders made screws of ``pitch`` (mm/rad) about the guides."""
    text = (MECHANISMS / "3prs.yaml").read_text()
    slider = 'type: P, links: [frame, "slider{i+1}"], axis: [0, 0, 1]'
    assert slider in text
    return mobility.loads(text.replace(slider, f'type: H, pitch: {pitch}, links: [frame, "slider{{i+1}}"], axis: [0, 0, 1], point: [R, 0, 0]'))


@pytest.mark.parametrize("pitch", [1.0, 1e6, 1.5e10])
def test_a_screw_input_of_large_pitch_is_judged_as_the_actuation_check_judges_it(pitch):
    # A large pitch makes the input's row of J short (one radian moves far), so kappa grows with the pitch;
    # at 1.5e10 mm/rad it passes 1/rank.  Whether the inputs control the platform does not depend on that
    # unit: the rank is decided on unit rows, and agrees with the screw route of check_actuation.
    m = _three_hrs(pitch)
    jac = jacobian(m)
    assert mobility.check_actuation(m, ["P1", "P2", "P3"]).verdict == "valid"
    assert not jac.singular and jac.rank == 6 and jac.twist_map is not None
    assert (jac.condition > 1e8) == (pitch > 1e10)


def test_a_pitch_whose_rotation_is_below_resolution_is_refused_at_its_line():
    with pytest.raises(MechanismError, match=r"<string>:34: limbs\[0\]\.joints\[0\]\.pitch: pitch 1e\+19 is 4\.6e\+16 times the spread of the joint points 219 .*beyond 1e\+16"):
        _three_hrs(1e19)
    assert mobility.analyze(_three_hrs(1e12)).pattern == "3R"  # 4.6e9 times the spread: resolved, and analysed
