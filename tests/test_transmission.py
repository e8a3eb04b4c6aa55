"""Motion/force transmission indices (mobility.transmission): closed forms of the literature, invariance, zeros at singular poses, sweep and CLI."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import mobility
from mobility.cli import main
from mobility.errors import RequestError
from mobility.sweeps.batch_transmission import check_transmission
from mobility.transmission import GOOD_TRANSMISSION, power_coefficient

MECH = "mechanisms"


def load(name: str) -> mobility.Mechanism:
    return mobility.load(f"{MECH}/{name}.yaml")


def test_power_coefficient_is_the_cosine_of_the_pressure_angle():
    # a force through P at angle a to the velocity of P (rotation about z through the origin, P on x)
    p = np.array([2.0, 0, 0])
    rz = np.array([0, 0, 1.0, 0, 0, 0])
    for a in (0.0, 0.3, 1.0, math.pi / 2):
        d = np.array([math.sin(a), math.cos(a), 0.0])
        f = np.concatenate([d, np.cross(p, d)])
        assert float(power_coefficient(f, rz, p)) == pytest.approx(abs(math.cos(a)), abs=1e-12)


def test_prs_input_index_is_the_cosine_of_the_leg_angle_to_the_guide():
    # Wang et al. (2010): a prismatic input's ITI is |cos| of the angle between the slide and the force (the leg); 3prs.yaml: zs / L
    t = check_transmission(load("3prs"))
    zs = math.sqrt(300**2 - (200 - 100) ** 2)
    assert t.iti == pytest.approx((zs / 300,) * 3, abs=1e-9)
    assert t.lti == pytest.approx(min(t.iti + t.oti), abs=1e-12)


def test_five_bar_input_index_is_the_sine_of_the_crank_coupler_angle():
    # Liu, Wang, Pritschow (2006) / Wang et al. (2010): lambda = |sin| of the angle between the crank A2B2 and the coupler B2P
    t = check_transmission(load("planar_5r"))
    a2, b2, p = np.array([200.0, 0]), np.array([260.0, 140]), np.array([110.0, 300])
    u, v = b2 - a2, p - b2
    sine = abs(u[0] * v[1] - u[1] * v[0]) / (np.linalg.norm(u) * np.linalg.norm(v))
    assert t.iti[1] == pytest.approx(sine, abs=1e-9)


def test_puu_input_index_and_redundant_actuation_takes_the_best_inputs():
    t = check_transmission(load("4puu"))
    dx = math.sqrt(300**2 - (150 - 60) ** 2 - 250**2)
    chosen = [i for i in t.iti if not math.isnan(i)]
    assert len(chosen) == 3  # 4 inputs, 3 DOF: the best three
    assert chosen == pytest.approx([dx / 300] * 3, abs=1e-9)


def test_constraint_singularity_of_the_4puu_gives_exactly_zero_and_a_small_index_beside_it():
    t = check_transmission(load("4puu_singular"))
    assert t.cti == 0.0 and t.lti == 0.0
    assert all(c == 0.0 or math.isnan(c) for c in t.cti_limbs)
    r = mobility.sweep(load("4puu_singular"), ["P1=-2:2:5"])
    singular = [p.index for p in r.singular]
    assert singular == [2] and r.cti[2] == 0.0 and r.lti[2] == 0.0
    assert np.all((r.cti[[0, 1, 3, 4]] > 0) & (r.cti[[0, 1, 3, 4]] < 1e-5))  # 1 mm from it: close to a constraint singularity
    regular = mobility.sweep(load("4puu"), ["P1=-20:20:5"])  # overconstrained and redundantly actuated: the best square choice
    assert np.all(regular.cti > 0.8) and np.all(regular.lti > 0.4)
    assert check_transmission(load("3prs")).cti > 0.9


def test_indices_fall_to_exactly_zero_at_the_singular_poses_of_the_sweep():
    r = mobility.sweep(load("parallelogram"), ["O1=0:360:13"], actuated=["O1"])
    singular = [p.index for p in r.singular]
    assert singular and all(r.lti[i] == 0.0 for i in singular)
    others = np.setdiff1d(np.arange(r.size), singular)
    assert np.all(r.lti[others] > 0.5)


def _five_bar_with_a_straight_limb() -> mobility.Mechanism:
    """planar_5r.yaml's link lengths with crank A2B2 and distal link B2P in line (P at full reach of limb 2), B1 from the circles."""
    a2 = np.array([200.0, 0.0])
    crank1, crank2 = math.hypot(-50, 150), math.hypot(60, 140)
    distal1, distal2 = math.hypot(160, 150), math.hypot(-150, 160)
    u = np.array([math.cos(math.radians(110)), math.sin(math.radians(110))])
    b2, p = a2 + crank2 * u, a2 + (crank2 + distal2) * u
    d = float(np.linalg.norm(p))
    along = (crank1**2 - distal1**2 + d**2) / (2 * d)
    e = p / d
    b1 = along * e + math.sqrt(crank1**2 - along**2) * np.array([-e[1], e[0]])
    at = lambda v: f"[{float(v[0])!r}, {float(v[1])!r}, 0]"  # noqa: E731
    return mobility.loads("name: five-bar, limb 2 straight\nground: ground\nend_effector: distal1\njoints:\n"
                          "  - {name: A1, type: R, links: [ground, proximal1], axis: [0, 0, 1], point: [0, 0, 0], actuated: true}\n"
                          f"  - {{name: B1, type: R, links: [proximal1, distal1], axis: [0, 0, 1], point: {at(b1)}}}\n"
                          f"  - {{name: P, type: R, links: [distal1, distal2], axis: [0, 0, 1], point: {at(p)}}}\n"
                          f"  - {{name: B2, type: R, links: [distal2, proximal2], axis: [0, 0, 1], point: {at(b2)}}}\n"
                          "  - {name: A2, type: R, links: [proximal2, ground], axis: [0, 0, 1], point: [200, 0, 0], actuated: true}\n")


def test_five_bar_input_singularity_where_crank_elbow_and_tool_point_fall_in_line_gives_lti_zero():
    # The end effector loses a freedom there (2 inputs, 1 DOF): the best choice of inputs would leave A2 out and
    # report LTI 1; A2's limb is at a serial singularity (ITI = sin of the crank-coupler angle = 0), so LTI is 0.
    m = _five_bar_with_a_straight_limb()
    t = check_transmission(m)
    assert mobility.analyze(m).dof == 1 and t.iti[1] == 0.0 and t.lti == 0.0 and not t.good
    r = mobility.sweep(m, ["A1=-10:10:3", "B2=-20:20:5"])
    singular = [p.index for p in r.singular]
    assert singular == [2, 7, 12] and all("loses 1 freedom" in p.reasons[0] for p in r.singular)  # B2 = 0: limb 2 straight
    assert all(r.lti[i] == 0.0 and r.iti[i] == 0.0 for i in singular)
    others = np.setdiff1d(np.arange(r.size), singular)
    elbow = np.radians(r.values[others, 1])
    assert np.allclose(r.lti[others], np.abs(np.sin(elbow)), atol=1e-9)  # beside it: ITI of A2 = |sin| of the elbow angle


def _moved(m: mobility.Mechanism, scale: float, rotation: np.ndarray, shift: np.ndarray) -> mobility.Mechanism:
    """The whole file scaled and moved rigidly (world geometry, no frames)."""
    joints = []
    for j in m.world_joints:
        changes = {}
        if j.point is not None:
            changes["point"] = tuple(rotation @ (scale * np.asarray(j.point)) + shift)
        for key in ("axis", "normal"):
            if getattr(j, key) is not None:
                changes[key] = tuple(rotation @ np.asarray(getattr(j, key)))
        if j.axes is not None:
            changes["axes"] = tuple(tuple(rotation @ np.asarray(a)) for a in j.axes)
        joints.append(dataclasses.replace(j, **changes))
    return mobility.Mechanism(m.name, ground=m.ground, end_effector=m.end_effector, joints=tuple(joints))


def _rotation(a: float, b: float, c: float) -> np.ndarray:
    ca, sa, cb, sb, cc, sc = math.cos(a), math.sin(a), math.cos(b), math.sin(b), math.cos(c), math.sin(c)
    rz = np.array([[ca, -sa, 0], [sa, ca, 0], [0, 0, 1]])
    ry = np.array([[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]])
    rx = np.array([[1, 0, 0], [0, cc, -sc], [0, sc, cc]])
    return rz @ ry @ rx


angles = st.floats(-math.pi, math.pi, allow_nan=False)


@settings(max_examples=12, deadline=None)
@given(scale=st.floats(1e-3, 1e3), a=angles, b=angles, c=angles, shift=st.tuples(*[st.floats(-1e3, 1e3)] * 3),
       name=st.sampled_from(["3prs_tilted", "actuation_3rps", "planar_5r", "4puu", "crank_rocker_goessner"]))
def test_indices_are_invariant_to_units_and_frames(scale, a, b, c, shift, name):
    m = load(name)
    base = check_transmission(m)
    moved = check_transmission(_moved(m, scale, _rotation(a, b, c), np.asarray(shift)))
    pairs = [(base.lti, moved.lti), (base.cti, moved.cti)]
    if not any(math.isnan(x) for x in base.iti + base.cti_limbs):  # a redundant system's best choice may tie (a symmetric pose): only its least index is defined then
        pairs += [*zip(base.iti, moved.iti), *zip(base.oti, moved.oti), *zip(base.cti_limbs, moved.cti_limbs)]
    for x, y in pairs:
        assert (math.isnan(x) and math.isnan(y)) or x == pytest.approx(y, abs=1e-7)


@settings(max_examples=8, deadline=None)
@given(scale=st.floats(1e-3, 1e3), a=angles, b=angles, c=angles, shift=st.tuples(*[st.floats(-1e3, 1e3)] * 3))
def test_the_input_singularity_stays_exactly_zero_in_any_unit_and_frame(scale, a, b, c, shift):
    moved = check_transmission(_moved(_five_bar_with_a_straight_limb(), scale, _rotation(a, b, c), np.asarray(shift)))
    assert moved.lti == 0.0 and moved.iti[1] == 0.0 and moved.iti[0] == pytest.approx(1.0, abs=1e-7)


def test_sweep_columns_threshold_and_leaving_them_out():
    m = load("3prs")
    r = mobility.sweep(m, ["P1=-60:60:7"], good_threshold=0.9)
    assert {"iti", "oti", "lti", "cti"} <= set(r.columns)
    assert np.all((r.lti >= 0) & (r.lti <= 1))
    assert r.good_transmission() == pytest.approx(float(np.mean(r.lti >= 0.9)))
    assert r.good_transmission(0.0) == 1.0 and r.good_threshold == 0.9
    assert "transmission" in r.summary_dict() and r.row(0)["lti"] == pytest.approx(float(r.lti[0]))
    bare = mobility.sweep(m, ["P1=-60:60:7"], transmission=False)
    assert "lti" not in bare.columns and np.isnan(bare.good_transmission())
    assert np.array_equal(bare.conditioning, r.conditioning)
    with pytest.raises(RequestError, match="good_threshold"):
        mobility.sweep(m, ["P1=-60:60:7"], good_threshold=1.5)
    with pytest.raises(RequestError, match="transmission must be True or False"):
        mobility.sweep(m, ["P1=-60:60:7"], transmission="no")
    with pytest.raises(RequestError, match="good_threshold"):  # also without inputs: a bad request is refused, not ignored
        mobility.sweep(load("parallelogram"), ["O1=0:10:2"], good_threshold=float("nan"))


def test_check_transmission_refuses_bad_requests():
    with pytest.raises(RequestError, match="no input"):
        check_transmission(load("parallelogram"))
    with pytest.raises(RequestError, match="threshold"):
        check_transmission(load("3prs"), threshold=-0.1)
    with pytest.raises(RequestError, match="joint variables"):
        check_transmission(load("3prs"), q=[0.0, 1.0])
    assert check_transmission(load("3prs"), threshold=GOOD_TRANSMISSION).good


def test_cli_sweep_reports_the_good_transmission_workspace(capsys):
    assert main(["sweep", f"{MECH}/3prs.yaml", "--vary", "P1=-20:20:3", "--good-transmission", "0.8"]) == 0
    out = capsys.readouterr().out
    assert "good-transmission workspace (LTI >= 0.8): 100.0% of the assembled poses (3)" in out
    assert "local transmission index LTI" in out
    assert main(["sweep", f"{MECH}/3prs.yaml", "--vary", "P1=-20:20:3", "--no-transmission"]) == 0
    assert "good-transmission" not in capsys.readouterr().out
    assert main(["sweep", f"{MECH}/3prs.yaml", "--vary", "P1=-20:20:3", "--good-transmission", "2"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--good-transmission must be a number in [0, 1]" in err


def test_five_bar_output_index_is_the_sine_of_the_distal_links_angle_and_vanishes_where_the_sweep_finds_singular_poses():
    # Liu et al.: eta = |sin psi|, psi the angle between the distal links; planar_5r.yaml has them at 90 deg, so psi = 90 deg - P
    r = mobility.sweep(load("planar_5r"), ["A1=-10:30:9", "P=40:100:13"])
    ok = r.assembled
    assert ok.sum() > 50
    assert np.allclose(r.oti[ok], np.abs(np.cos(np.radians(r.values[ok, 1]))), atol=1e-9)
    singular = [p.index for p in r.singular]
    assert singular and all(r.lti[i] == 0.0 and r.oti[i] == 0.0 for i in singular)
    share = r.good_transmission()
    assert share == pytest.approx(float(np.mean(np.abs(np.cos(np.radians(r.values[ok, 1]))) >= 0.7)))


def test_maps_outline_the_good_transmission_workspace():
    from mobility.report.sweep_plot import plot_sweep

    r = mobility.sweep(load("planar_5r"), ["A1=-10:30:9", "P=30:60:7"])
    fig = plot_sweep(r)
    outlines = [a for ax in fig.axes for a in ax.get_children() if a.get_gid() == "mobility:sweep:good-transmission"]
    assert len(outlines) == 1
    line = mobility.sweep(load("planar_5r"), ["P=0:90:10"])
    curve = plot_sweep(line)
    lti = next(x for x in curve.axes[1].get_lines() if x.get_label().startswith("local transmission index"))
    y = np.asarray(lti.get_ydata(), dtype=float)
    assert np.isnan(y[-1]) and line.lti[-1] == 0.0  # the singular pose: 0, off the log scale
    assert np.allclose(y[:-1], line.lti[:-1]) and np.all(line.lti[:-1] > 0)


def test_the_views_slider_labels_each_pose_with_its_indices():
    from mobility.view import sweep_view

    r = mobility.sweep(load("3prs"), ["P1=-20:20:3"])
    labels = [f.label for f in sweep_view(r).frames]
    assert labels == [f"P1={v:g} mm, LTI {r.lti[i]:.3f}, CTI {r.cti[i]:.3f}" for i, v in enumerate((-20, 0, 20))]
    bare = mobility.sweep(load("3prs"), ["P1=-20:20:3"], transmission=False)
    assert [f.label for f in sweep_view(bare).frames] == ["P1=-20 mm", "P1=0 mm", "P1=20 mm"]


@pytest.mark.parametrize("q, message", [
    ([math.nan] * 15, "finite"),
    ("abc", "numbers"),
    ([5.0] + [0.0] * 14, "do not close the loops"),
])
def test_check_transmission_takes_only_a_closed_pose(q, message):
    with pytest.raises(RequestError, match=message):
        check_transmission(load("3prs"), q=q)
    r = mobility.sweep(load("3prs"), ["P1=-20:20:3"])
    assert check_transmission(load("3prs"), q=r.q[0]).lti == pytest.approx(float(r.lti[0]), abs=1e-12)


def test_analyse_joint_variables_gives_the_indices_unless_told_not_to():
    from mobility.sweeps import analyse_joint_variables

    r = mobility.sweep(load("3prs"), ["P1=-20:20:3"])
    columns = analyse_joint_variables(load("3prs"), np.asarray(r.q))
    assert np.allclose(columns["lti"], r.lti) and np.allclose(columns["cti"], r.cti)
    assert "lti" not in analyse_joint_variables(load("3prs"), np.asarray(r.q), transmission=False)
