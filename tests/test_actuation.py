"""Actuation spaces of rigid mechanisms (mobility.actuation, mobility actuation).

The 3-RPS case is that of Li, Shan, Yu and Ke, "Actuation Spaces Synthesis of
Lower-Mobility Parallel Mechanisms Based on Screw Theory" (Chin. J. Mech. Eng.,
2021).  Poses are set through the file's parameters (platform height h, tilt
theta about a horizontal axis at azimuth phi); the tests recompute the
platform geometry from the pose independently and check every leg length
against the paper's prismatic range, 120-195 mm.
"""

from __future__ import annotations

import functools
import json
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mobility
from mobility.actuation import (
    MAX_COMBINATIONS,
    REDUNDANT,
    SINGULAR,
    VALID,
    RigidPose,
    assess_wrenches,
    check_actuation,
    check_over_poses,
    combination_type,
    enumerate_actuations,
    lock_joints,
    locked_dof,
)
from mobility.cli import main
from mobility.core.screws import SWAP_ROWS
from mobility.errors import MechanismError, RequestError
from mobility.core.joint_screws import joint_screws
from mobility.core.model import Joint, Mechanism
from mobility.core.screws import reciprocal_product, same_subspace
from mobility.core.transforms import rotation_from_axis_angle
from mobility.report.actuation import actuation_text, enumeration_text
from builders import flat_3rps

ROOT = Path(__file__).resolve().parents[1]
RPS_FILE = ROOT / "mechanisms" / "actuation_3rps.yaml"
RPS_TEXT = RPS_FILE.read_text(encoding="utf-8")
A, B = 92.38, 57.74
STROKE = (120.0, 195.0)


def rps(h: float, phi: float = 0.0, theta: float = 0.0, text: str = RPS_TEXT) -> Mechanism:
    """The 3-RPS file at another pose (its parameters h, phi, theta replaced)."""
    for key, value in (("h", h), ("phi", phi), ("theta", theta)):
        text, n = re.subn(rf"\n  {key}: [^\n]*", f"\n  {key}: {float(value)!r}", text, count=1)
        assert n == 1
    return mobility.loads(text, file=f"3-RPS h={h:g} phi={phi:g} theta={theta:g}")


def platform_points(h: float, phi: float, theta: float) -> np.ndarray:
    """Spherical-joint centres from the pose, by rotating the platform (independent of the file)."""
    ph, th = np.radians(phi), np.radians(theta)
    rot = rotation_from_axis_angle(np.array([-np.sin(ph), np.cos(ph), 0.0]), th)
    centre = np.array([-(B / 2) * (1 - np.cos(th)) * np.cos(2 * ph), (B / 2) * (1 - np.cos(th)) * np.sin(2 * ph), h])
    g = np.radians([0.0, 120.0, 240.0])
    return centre + (rot @ (B * np.stack([np.cos(g), np.sin(g), np.zeros(3)]))).T


def legs(m: Mechanism) -> np.ndarray:
    w = {j.name: j for j in m.world_joints}
    return np.array([np.linalg.norm(np.subtract(w[f"S{i}"].point, w[f"R{i}"].point)) for i in (1, 2, 3)])


def workspace_poses() -> list[Mechanism]:
    """Poses across the prismatic range: the full vertical stroke and tilts up to 5 degrees."""
    h_min = np.sqrt(STROKE[0] ** 2 - (A - B) ** 2) + 0.5
    h_max = np.sqrt(STROKE[1] ** 2 - (A - B) ** 2) - 0.5
    out = [rps(h) for h in np.linspace(h_min, h_max, 5)]
    for h, phi, theta in [(130, 0, 5), (150, 45, 5), (150, 200, 3), (170, 100, 5), (185, 290, 4), (125, 330, 4)]:
        out.append(rps(h, phi, theta))
    return out


POSES = workspace_poses()


# ---------------------------------------------------------------------------
# the mechanism file
# ---------------------------------------------------------------------------


def test_rps_file_matches_its_expected_block_and_marks_the_prismatic_joints():
    m = mobility.load(RPS_FILE)
    r = mobility.analyze(m)
    assert (r.dof, r.pattern, r.mobility) == (m.expected.dof, m.expected.pattern, m.expected.mobility) == (3, "1T2R", 3)
    assert [j.name for j in m.joints if j.actuated] == ["P1", "P2", "P3"]
    assert "Li, Shan, Yu and Ke" in m.description and "92.38" in m.description


@pytest.mark.parametrize("h, phi, theta", [(150, 0, 0), (140, 30, 10), (170, 250, 7), (125, 100, 12)])
def test_closed_form_pose_puts_each_spherical_joint_where_the_rotated_platform_does(h, phi, theta):
    m = rps(h, phi, theta)
    w = {j.name: j for j in m.world_joints}
    points = platform_points(h, phi, theta)
    for i in range(3):
        assert np.allclose(w[f"S{i + 1}"].point, points[i], atol=1e-9)
        leg = points[i] - np.array(w[f"R{i + 1}"].point)
        assert np.allclose(w[f"P{i + 1}"].axis, leg / np.linalg.norm(leg), atol=1e-12)
        assert abs(np.dot(w[f"R{i + 1}"].axis, leg)) < 1e-9  # each leg stays in the plane of its limb


def test_workspace_poses_span_the_paper_stroke():
    lengths = np.concatenate([legs(m) for m in POSES])
    assert lengths.min() >= STROKE[0] and lengths.max() <= STROKE[1]
    assert lengths.min() < STROKE[0] + 1 and lengths.max() > STROKE[1] - 1


# ---------------------------------------------------------------------------
# actuation wrenches
# ---------------------------------------------------------------------------


def _line_distance(point: np.ndarray, line_point: np.ndarray, direction: np.ndarray) -> float:
    return float(np.linalg.norm(np.cross(np.subtract(point, line_point), direction)))


def test_rps_actuation_wrenches_are_the_leg_force_and_the_normal_force_through_the_sphere_centre():
    m = rps(160, 70, 8)
    w = {j.name: j for j in m.world_joints}
    check = check_actuation(m, ["R1", "P2", "R3"])
    for inp in check.inputs:
        i = inp.name[1]
        b = np.array(w[f"S{i}"].point)
        leg = b - np.array(w[f"R{i}"].point)
        leg /= np.linalg.norm(leg)
        assert inp.axis.kind == "force" and inp.axis.pitch == 0.0
        assert _line_distance(b, inp.axis.point, inp.axis.axis) < 1e-9 * 160  # through the S centre
        if inp.kind == "P":
            assert abs(abs(inp.axis.axis @ leg) - 1) < 1e-12  # along the leg
        else:
            assert abs(inp.axis.axis @ leg) < 1e-12  # normal to the leg
            assert abs(inp.axis.axis @ np.array(w[f"R{i}"].axis)) < 1e-12  # in the plane of the limb


def test_actuation_wrench_is_reciprocal_to_the_other_twists_of_its_limb_but_not_to_its_own():
    m = rps(140, 20, 6)
    twists = {j.name: np.stack([_twist(f) for f in j.freedoms()], axis=1) for j in m.world_joints}
    check = check_actuation(m, ["R1", "R2", "R3", "P1", "P2", "P3"])
    def size(w: np.ndarray, t: np.ndarray) -> np.ndarray:  # magnitude of the two terms of w o t
        return np.linalg.norm(w[:3]) * np.linalg.norm(t[3:], axis=0) + np.linalg.norm(w[3:]) * np.linalg.norm(t[:3], axis=0)

    for inp in check.inputs:
        limb = inp.name[1]
        others = np.hstack([twists[n + limb] for n in "RPS" if n + limb != inp.name])
        own = twists[inp.name]
        assert np.all(np.abs(reciprocal_product(inp.wrench[:, None], others)) < 1e-12 * size(inp.wrench, others))
        assert np.all(np.abs(reciprocal_product(inp.wrench[:, None], own)) > 0.1 * size(inp.wrench, own))
    assert check.verdict == REDUNDANT


def _twist(f) -> np.ndarray:
    s = np.asarray(f.axis)
    if f.kind == "P":
        return np.concatenate([np.zeros(3), s])
    return np.concatenate([s, np.cross(f.point, s) + f.pitch * s])


# ---------------------------------------------------------------------------
# the paper's result, and the second route
# ---------------------------------------------------------------------------


def test_rps_all_four_combination_types_are_valid_across_the_prismatic_range():
    found = enumerate_actuations(POSES[0], poses=POSES[1:])
    assert len(found.poses) == len(POSES)
    assert [(g.type, g.valid, g.total) for g in found.groups] == [("3R", 1, 1), ("2R1P", 3, 3), ("1R2P", 3, 3), ("3P", 1, 1)]
    assert all(c.verdict == VALID and c.valid_poses == len(POSES) for c in found.combinations)
    assert all(c.conditioning > 0.02 for c in found.combinations)
    # ranked by the worst-pose conditioning
    kappas = [float(f"{c.conditioning:.12g}") for c in found.combinations]  # ties at round-off fall to the input names
    assert kappas == sorted(kappas, reverse=True)


def test_conditioning_is_the_same_for_3R_and_3P_at_the_symmetric_home_pose():
    # At h, theta = 0 every twist of the platform moves the sphere centres vertically,
    # so both input maps are the same matrix up to one factor per limb type.
    m = rps(150)
    k3r = check_actuation(m, ["R1", "R2", "R3"]).conditioning
    k3p = check_actuation(m, ["P1", "P2", "P3"]).conditioning
    assert k3r == pytest.approx(k3p, rel=1e-9)
    assert check_actuation(m, ["R1", "P2", "P3"]).conditioning < 0.5 * k3p


@pytest.mark.parametrize("pose", [POSES[0], POSES[4], POSES[7]], ids=["stroke-start", "stroke-end", "tilted"])
def test_locking_valid_inputs_immobilises_the_platform_and_only_then(pose):
    found = enumerate_actuations(pose, mode="any")  # any 3 of the 6 one-freedom joints
    assert len(found.combinations) == 20
    if pose is not POSES[7]:
        # At the untilted poses, R and P of one limb fix its sphere centre, about which the
        # other limbs leave a rotation when the third limb has no input.
        assert {c.verdict for c in found.combinations} == {VALID, SINGULAR}
    for c in found.combinations:
        assert (locked_dof(pose, c.inputs) == 0) == (c.verdict == VALID), c.inputs


def test_locking_fewer_inputs_leaves_the_missing_freedoms():
    m = POSES[6]
    assert locked_dof(m, []) == 3
    assert locked_dof(m, ["P1"]) == 2
    assert locked_dof(m, ["R2", "P3"]) == 1
    check = check_actuation(m, ["R2", "P3"])
    assert check.verdict == SINGULAR and check.rank == 5 and check.uncontrolled_twists.shape == (1, 6)


def _det_3r(m: Mechanism) -> float:
    """Determinant of the constraint forces and the R-actuation forces, from the raw geometry."""
    w = {j.name: j for j in m.world_joints}
    cols = []
    for i in (1, 2, 3):
        u = np.array(w[f"R{i}"].axis)
        a, b = np.array(w[f"R{i}"].point), np.array(w[f"S{i}"].point)
        n = np.cross((b - a) / np.linalg.norm(b - a), u)
        cols += [np.concatenate([d, np.cross(b / 100.0, d)]) for d in (u, n)]
    return float(np.linalg.det(np.array(cols).T))


SINGULAR_H, SINGULAR_PHI = 124.8, 174.7


@functools.lru_cache(maxsize=1)
def singular_theta() -> float:
    """Tilt where the 3R choice is actuation-singular at (SINGULAR_H, SINGULAR_PHI), by bisection."""
    lo, hi = 10.0, 20.0
    sign_lo = np.sign(_det_3r(rps(SINGULAR_H, SINGULAR_PHI, lo)))
    assert sign_lo != np.sign(_det_3r(rps(SINGULAR_H, SINGULAR_PHI, hi)))
    for _ in range(55):
        mid = 0.5 * (lo + hi)
        if np.sign(_det_3r(rps(SINGULAR_H, SINGULAR_PHI, mid))) == sign_lo:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def test_3R_has_an_actuation_singularity_inside_the_stroke_when_the_platform_tilts():
    # Not in the paper: tilting about 15 degrees at h = 124.8 mm, with every leg inside
    # 120-195 mm, the three R inputs lose control of one screw motion of the platform.
    h, phi, theta = SINGULAR_H, SINGULAR_PHI, singular_theta()
    m = rps(h, phi, theta)
    assert STROKE[0] < legs(m).min() and legs(m).max() < STROKE[1]
    check = check_actuation(m, ["R1", "R2", "R3"])
    assert check.verdict == SINGULAR and check.rank == 5 and check.conditioning == 0.0
    (lost,) = check.uncontrolled_twists
    norm = joint_screws(m).normalisation
    platform = norm.from_world(mobility.analyze(m).twists.T)
    assert same_subspace(np.hstack([platform, norm.from_world(lost)]), platform)  # a motion the platform has
    wrenches = np.vstack([check.constraint_wrenches] + [i.wrench for i in check.inputs])
    assert np.abs(reciprocal_product(wrenches.T, lost[:, None])).max() < 1e-8 * np.abs(wrenches).max() * np.abs(lost).max()
    assert locked_dof(m, ["R1", "R2", "R3"]) == 1  # the second route agrees
    for nearby in (theta - 1.0, theta + 1.0):
        near = rps(h, phi, nearby)
        assert check_actuation(near, ["R1", "R2", "R3"]).verdict == VALID
        assert locked_dof(near, ["R1", "R2", "R3"]) == 0
    assert check_actuation(m, ["P1", "P2", "P3"]).verdict == VALID


def test_enumeration_reports_the_pose_where_a_combination_fails():
    bad = rps(SINGULAR_H, SINGULAR_PHI, singular_theta())
    found = enumerate_actuations(POSES[0], poses=[POSES[3], bad])
    by_inputs = {c.inputs: c for c in found.combinations}
    r3 = by_inputs[("R1", "R2", "R3")]
    assert r3.verdict == SINGULAR and r3.failures == ((2, SINGULAR),) and r3.valid_poses == 2
    assert found.combinations[-1] is r3
    assert [g for g in found.groups if g.type == "3R"][0].valid == 0


# ---------------------------------------------------------------------------
# other mechanisms and verdicts
# ---------------------------------------------------------------------------


def _slides() -> Mechanism:
    """A carriage on a slide along x, also held by a limb of two slides (x then y)."""
    P = lambda n, a, b, axis: Joint(n, "P", (a, b), axis=axis, point=(0, 0, 0))  # noqa: E731
    return Mechanism(
        "two-limb slide",
        "ground",
        "carriage",
        (
            P("Px1", "ground", "carriage", (1, 0, 0)),
            P("Px2", "ground", "block", (1, 0, 0)),
            P("Py2", "block", "carriage", (0, 1, 0)),
        ),
    )


def test_an_input_whose_wrench_lies_in_the_constraint_space_is_invalid():
    m = _slides()
    check = check_actuation(m, ["Py2"])
    assert check.dof == 1 and check.verdict == SINGULAR
    (inp,) = check.inputs
    assert inp.in_constraint_space and "constraint space" in inp.note
    assert np.allclose(inp.axis.axis, [0, 1, 0])  # a force along y: the first limb already holds it
    assert np.allclose(check.uncontrolled_translations, [[1, 0, 0]]) and not check.uncontrolled_rotations
    assert locked_dof(m, ["Py2"]) == 1
    assert check_actuation(m, ["Px2"]).verdict == VALID and locked_dof(m, ["Px2"]) == 0


def test_a_joint_whose_motion_its_limb_already_has_cannot_be_driven():
    m = _slides()
    m = m.replace(joints=m.joints[:2] + (Joint("Px3", "P", ("block", "carriage"), axis=(1, 0, 0)),))
    check = check_actuation(m, ["Px3"])
    assert check.verdict == SINGULAR and check.inputs[0].wrench is None
    assert "other joints of its limb" in check.inputs[0].note
    assert locked_dof(m, ["Px3"]) == 1


def _four_bar() -> Mechanism:
    R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)  # noqa: E731
    return Mechanism(
        "four-bar",
        "ground",
        "coupler",
        (R("A", "ground", "crank", (0, 0, 0)), R("B", "crank", "coupler", (1, 2, 0)), R("C", "coupler", "rocker", (4, 2.5, 0)), R("D", "rocker", "ground", (5, 0, 0))),
    )


def test_four_bar_every_single_input_is_valid_two_are_redundant():
    m = _four_bar()
    found = enumerate_actuations(m, mode="any")
    assert sorted(c.inputs for c in found.combinations) == [("A",), ("B",), ("C",), ("D",)]
    assert all(c.verdict == VALID and c.conditioning == 1.0 for c in found.combinations)  # one input: G is 1x1
    assert all(locked_dof(m, c.inputs) == 0 for c in found.combinations)
    pair = enumerate_actuations(m, mode="any", k=2)
    assert {c.verdict for c in pair.combinations} == {REDUNDANT} and len(pair.combinations) == 6
    assert "none can be valid" in " ".join(pair.warnings)


def test_four_bar_input_at_a_dead_centre_is_singular():
    # Crank A and coupler in line: the crank's actuation wrench (a force along the coupler)
    # passes through A, so the crank cannot move the coupler.
    R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)  # noqa: E731
    m = Mechanism("four-bar at dead centre", "ground", "coupler", (
        R("A", "ground", "crank", (0, 0, 0)), R("B", "crank", "coupler", (1, 0, 0)),
        R("C", "coupler", "rocker", (3, 0, 0)), R("D", "rocker", "ground", (3, 2, 0))))
    assert check_actuation(m, ["D"]).verdict == SINGULAR  # C, B, A in line: the rocker's force along CB passes through A
    assert locked_dof(m, ["D"]) == 1
    assert check_actuation(m, ["B"]).verdict == VALID and locked_dof(m, ["B"]) == 0


def _movers(check) -> list[str] | None:
    """The inputs a redundant verdict's sentence says move the mechanism without the end effector (None: it says they fight)."""
    found = re.search(r"do not fight: each moves the mechanism on its own, and (.+?) moves? it without moving the end effector", check.explanation)
    return None if found is None else found.group(1).split(", ")


def _independent_by_locking(m: Mechanism, inputs: list[str]) -> bool:
    """Second route: the inputs can be set one by one when locking them takes one freedom of the whole mechanism each."""
    locked = lock_joints(m, inputs)
    assert locked is not None
    return mobility.analyze(m).mobility - mobility.loop_closure(locked).mobility == len(inputs)


def test_a_crank_at_a_dead_centre_drives_the_mechanism_and_is_not_said_to_fight():
    # The slider-crank with the crank and the rod in line: the slider has no instantaneous freedom (0 DOF),
    # the crank still turns; the verdict counts 1 input for 0 DOF, but nothing fights (was "they fight each other").
    R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)  # noqa: E731
    m = Mechanism("slider-crank at its dead centre", "ground", "slider", (
        R("A", "ground", "crank", (0, 0, 0)), R("B", "crank", "rod", (1, 0, 0)),
        R("C", "rod", "slider", (3, 0, 0)), Joint("S", "P", ("slider", "ground"), axis=(1, 0, 0))))
    check = check_actuation(m, ["A"])
    assert (check.verdict, check.dof, mobility.analyze(m).mobility) == (REDUNDANT, 0, 1)
    assert _movers(check) == ["A"] and check.explanation.startswith("1 input for 0 DOF, yet")
    assert _independent_by_locking(m, ["A"]) and locked_dof(m, ["A"]) == check.dof  # locking A leaves the slider as it was
    text = actuation_text(check)
    assert "no end-effector freedom to control: 1 by convention" in text and "one end-effector freedom" not in text
    both = check_actuation(m, ["A", "S"])  # the slider cannot move here: driving it fights the mechanism
    assert both.verdict == REDUNDANT and _movers(both) is None and "fight each other" in both.explanation


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(-2, 2), st.floats(-2, 2)), min_size=4, max_size=5, unique=True), st.data())
def test_inputs_of_a_planar_arm_with_a_self_motion_agree_with_the_locking_route(points, data):
    # A planar arm of 4 or 5 parallel R joints (at most 3 end-effector freedoms), with joints in line at times:
    # a joint whose motion the others produce has no wrench of its own, yet locking it with the others holds the arm
    # (a 7R or an all-driven redundant arm was "actuation-singular, 6 uncontrolled directions").
    pts = [(x, y, 0.0) for x, y in points]
    if min(np.hypot(a[0] - b[0], a[1] - b[1]) for i, a in enumerate(pts) for b in pts[i + 1 :]) < 0.1:
        return  # two joints nearly on one axis: a different mechanism
    links = ["g"] + [f"l{i}" for i in range(1, len(pts))] + ["hand"]
    m = Mechanism("planar arm", "g", "hand", tuple(Joint(f"J{i}", "R", (links[i], links[i + 1]), axis=(0, 0, 1), point=p) for i, p in enumerate(pts)))
    names = [j.name for j in m.joints]
    inputs = data.draw(st.lists(st.sampled_from(names), min_size=1, max_size=len(names), unique=True))
    check = check_actuation(m, inputs)
    dof = mobility.analyze(m).dof
    assert check.dof == dof <= 3
    assert (check.verdict == SINGULAR) == (locked_dof(m, inputs) > 0) == (len(inputs) < len(names))  # one free joint moves the hand
    assert check.uncontrolled_twists.shape[0] == locked_dof(m, inputs)
    if check.verdict == SINGULAR:
        return
    assert check.verdict == (REDUNDANT if len(inputs) > dof else VALID)
    if check.verdict == REDUNDANT:
        movers = _movers(check)
        assert movers is not None  # a serial arm has no loop: every joint rate is set on its own, nothing fights
        for name in inputs:  # an input moves the self-motion exactly when locking it alone leaves the hand its freedoms
            assert (name in movers) == (locked_dof(m, [name]) == dof), (name, movers)


def test_a_7r_arm_driven_at_every_joint_is_held_and_drives_its_self_motion():
    rng = np.random.default_rng(7)
    links = ["g"] + [f"l{i}" for i in range(1, 7)] + ["hand"]
    m = Mechanism("7R arm", "g", "hand", tuple(
        Joint(f"J{i + 1}", "R", (links[i], links[i + 1]), axis=tuple(rng.normal(size=3)), point=tuple(rng.normal(size=3))) for i in range(7)))
    names = [j.name for j in m.joints]
    check = check_actuation(m, names)
    assert (check.dof, check.verdict, check.uncontrolled_twists.shape[0], locked_dof(m, names)) == (6, REDUNDANT, 0, 0)
    assert all(i.axis is None for i in check.inputs)  # none has a wrench of its own: each is produced by the other six
    assert _movers(check) == names  # a generic 7R arm's self-motion turns every joint
    six = check_actuation(m, names[:6])  # J7 left free turns the hand: singular by both routes
    assert six.verdict == SINGULAR and six.uncontrolled_twists.shape[0] == locked_dof(m, names[:6]) == 1
    ranked = enumerate_actuations(m, mode="any", k=7).combinations
    assert [(c.inputs, c.verdict) for c in ranked] == [(tuple(names), REDUNDANT)]  # the enumeration agrees


def test_four_inputs_of_a_planar_four_bar_fight_by_both_routes():
    m = _four_bar()
    check = check_actuation(m, ["A", "D"])
    assert check.verdict == REDUNDANT and _movers(check) is None
    assert check.explanation == "2 inputs for 1 DOF: 1 more than needed (they must be coordinated or they fight each other)"
    assert not _independent_by_locking(m, ["A", "D"])


def test_serial_arm_is_one_limb():
    R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)  # noqa: E731
    arm = Mechanism("planar RR", "g", "hand", (R("A", "g", "upper", (0, 0, 0)), R("B", "upper", "hand", (1, 0, 0))))
    assert check_actuation(arm, ["A", "B"]).verdict == VALID
    one = check_actuation(arm, ["A"])
    assert one.verdict == SINGULAR and len(one.uncontrolled_rotations) == 1
    assert np.allclose(one.uncontrolled_rotations[0].point[:2], [1, 0])  # the hand still turns about B
    assert [i.limb for i in one.inputs] == [0]


def test_each_freedom_of_an_actuated_universal_joint_is_one_input():
    u = Joint("U", "U", ("g", "arm"), point=(0, 0, 0), axes=((0, 0, 1), (0, 1, 0)))
    tip = Joint("P", "P", ("arm", "hand"), axis=(1, 0, 0))
    m = Mechanism("UP arm", "g", "hand", (u, tip))
    check = check_actuation(m, ["U"])
    assert [i.name for i in check.inputs] == ["U.0", "U.1"]
    assert check.verdict == SINGULAR and np.allclose(np.abs(check.uncontrolled_translations), [[1, 0, 0]])
    assert check_actuation(m, ["U", "P"]).verdict == VALID and locked_dof(m, ["U", "P"]) == 0
    assert locked_dof(m, ["U"]) == 1


def test_unknown_joint_is_a_mechanism_error():
    with pytest.raises(MechanismError, match="unknown joint 'Q9'"):
        check_actuation(_four_bar(), ["Q9"])
    with pytest.raises(MechanismError, match="not a pose"):
        check_over_poses(_four_bar(), ["A"], [_slides()])


def test_lock_joints_merges_links_and_drops_joints_left_inside_one_body():
    m = _four_bar()
    locked = lock_joints(m, ["B", "C"])  # crank, coupler and rocker become one body, named after the end effector
    assert [(j.name, j.links) for j in locked.joints] == [("A", ("ground", "coupler")), ("D", ("coupler", "ground"))]
    assert locked_dof(m, ["B", "C"]) == 0 and locked_dof(m, ["C"]) == 0
    assert lock_joints(m, ["A", "B"]) is None  # coupler welded to the ground
    assert locked_dof(m, ["A", "B"]) == 0


def test_combination_type_follows_the_paper():
    assert combination_type("RRR") == "3R"
    assert combination_type("PRR") == "2R1P"
    assert combination_type("PPR") == "1R2P"
    assert combination_type("HPR") == "1R1P1H"


# ---------------------------------------------------------------------------
# the shared algebra: representatives, and what an enumeration refuses
# ---------------------------------------------------------------------------


@functools.lru_cache(maxsize=1)
def _tilted_pose() -> RigidPose:
    return RigidPose(POSES[7])


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(-3.0, 3.0), min_size=3, max_size=3), st.lists(st.floats(0.2, 5.0), min_size=3, max_size=3))
def test_conditioning_does_not_depend_on_the_representative_of_an_actuation_wrench(shifts, scales):
    # An actuation wrench is defined up to its limb's constraint wrenches (reciprocal to every
    # twist of the limb) and a positive factor: G, hence kappa, must not see either.
    pose = _tilted_pose()
    index = {j.name: i for i, j in enumerate(pose.mechanism.joints)}
    spaces = pose.spaces
    base, moved = [], []
    for name, shift, scale in zip(["R1", "P2", "R3"], shifts, scales):
        joint = index[name]
        a, rate, _ = pose.wrench(joint, 0)
        limb_constraints = pose.limbs[pose.limb_of[joint]][1].wrenches[0]  # a stack of this one pose
        other = scale * a + limb_constraints @ np.full(limb_constraints.shape[1], shift)
        twist = pose.screws.twists[:, pose.screws.offsets[joint]]
        if name[0] == "R":
            twist = twist / np.linalg.norm(twist[:3])  # unit angular rate (a P column has unit rate already)
        other_rate = float(other[SWAP_ROWS] @ twist)
        assert other_rate == pytest.approx(scale * rate, rel=1e-9)  # the limb's constraints do no work on its joint
        base.append((a, rate))
        moved.append((other / np.linalg.norm(other), other_rate / np.linalg.norm(other)))
    a = assess_wrenches([w for w, _ in base], [r for _, r in base], spaces.twists, spaces.constraints)
    b = assess_wrenches([w for w, _ in moved], [r for _, r in moved], spaces.twists, spaces.constraints)
    assert a.verdict == b.verdict == VALID
    assert b.conditioning == pytest.approx(a.conditioning, rel=1e-9)
    assert a.conditioning == pytest.approx(check_actuation(POSES[7], ["R1", "P2", "R3"]).conditioning, rel=1e-12)


def _serial_arm(n: int) -> Mechanism:
    """A spatial serial arm of ``n`` revolute joints (6 DOF for n >= 6)."""
    links = ["base"] + [f"l{i}" for i in range(1, n)] + ["hand"]
    axes = [(0, 0, 1), (0, 1, 0), (1, 0, 0)]
    return Mechanism(f"{n}R arm", "base", "hand", tuple(
        Joint(f"J{i}", "R", (links[i], links[i + 1]), axis=axes[i % 3], point=(0.1 * i, 0.05 * i * i, 0.02 * i)) for i in range(n)))


def test_enumeration_refuses_too_many_combinations_and_bad_requests():
    arm = _serial_arm(25)
    with pytest.raises(RequestError, match=r"^177100 combinations to try \(more than 20000\)"):
        enumerate_actuations(arm, mode="any")  # C(25, 6)
    assert MAX_COMBINATIONS == 20000 and isinstance(RequestError("x"), ValueError)
    assert len(enumerate_actuations(arm, mode="any", k=2).combinations) == 300  # C(25, 2) is allowed
    with pytest.raises(RequestError, match="mode must be 'limb' or 'any'"):
        enumerate_actuations(_four_bar(), mode="every")
    with pytest.raises(RequestError, match="k must be non-negative"):
        enumerate_actuations(_four_bar(), mode="any", k=-1)
    with pytest.raises(MechanismError, match="unknown joint 'Q9'"):
        lock_joints(_four_bar(), ["A", "Q9"])


def test_cli_bad_requests_are_one_line_with_status_2(tmp_path, capsys):
    lines = ["name: 25R arm", "ground: l0", "end_effector: l25", "joints:"]
    lines += [f"  - {{name: J{i}, type: R, links: [l{i}, l{i + 1}], axis: {['[0, 0, 1]', '[0, 1, 0]', '[1, 0, 0]'][i % 3]}, point: [{0.1 * i}, {0.05 * i * i}, 0]}}" for i in range(25)]
    arm = tmp_path / "arm.yaml"
    arm.write_text("\n".join(lines) + "\n", encoding="utf-8")
    for argv, message in (
        (["actuation", str(arm), "--enumerate", "--mode", "any"], "mobility: 177100 combinations to try"),
        (["actuation", str(RPS_FILE), "--k", "-1"], "mobility: --k must lie in [0, 6]"),
        (["actuation", str(RPS_FILE), "--pose", str(ROOT / "mechanisms" / "3prs.yaml")], "is not a pose of"),
    ):
        assert main(argv) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and message in err and "Traceback" not in err, argv


# ---------------------------------------------------------------------------
# invariance
# ---------------------------------------------------------------------------


def _moved(m: Mechanism, scale: float, rot: np.ndarray, shift: np.ndarray) -> Mechanism:
    from dataclasses import replace

    out = []
    for j in m.world_joints:
        changes = {}
        if j.axis is not None:
            changes["axis"] = tuple(rot @ j.axis)
        if j.point is not None:
            changes["point"] = tuple(scale * (rot @ j.point) + shift)
        out.append(replace(j, **changes))
    return m.replace(joints=tuple(out), frames=())


def test_verdicts_and_conditioning_do_not_depend_on_unit_or_placement():
    rot = rotation_from_axis_angle(np.array([1.0, 2.0, 3.0]) / np.sqrt(14), 0.7)
    shift = np.array([3000.0, -500.0, 1200.0])
    for m in (POSES[0], POSES[7], POSES[9]):
        moved = _moved(m, 1000.0, rot, shift)
        for combo in (["P1", "P2", "P3"], ["R1", "P2", "R3"], ["R1", "R2"]):
            a, b = check_actuation(m, combo), check_actuation(moved, combo)
            assert a.verdict == b.verdict and a.rank == b.rank
            assert a.conditioning == pytest.approx(b.conditioning, rel=1e-9, abs=1e-12)
            for ia, ib in zip(a.inputs, b.inputs):
                assert np.allclose(rot @ ia.axis.axis, ib.axis.axis, atol=1e-9)
                assert _line_distance(1000.0 * (rot @ ia.axis.point) + shift, ib.axis.point, ib.axis.axis) < 1e-6


# ---------------------------------------------------------------------------
# poses from the user, and from the sampler when it exists
# ---------------------------------------------------------------------------


def test_sampled_poses_keep_the_rps_types_valid_and_agree_with_locking():
    from mobility.core.poses import sample_poses

    m = mobility.load(RPS_FILE)
    sampled = sample_poses(m, 4, seed=3)
    assert len(sampled) == 4
    found = enumerate_actuations(m, samples=4, seed=3)
    assert found.poses == ("given pose",) + tuple(f"sampled pose {i}" for i in range(1, 5))
    assert all(c.verdict == VALID and c.valid_poses == 5 for c in found.combinations)
    for pose in sampled:
        assert np.all((legs(pose) > STROKE[0]) & (legs(pose) < STROKE[1]))
        for c in enumerate_actuations(pose, mode="any").combinations:
            assert (locked_dof(pose, c.inputs) == 0) == (c.verdict == VALID), c.inputs


def test_four_bar_sampled_poses_agree_with_locking():
    from mobility.core.poses import sample_poses

    m = _four_bar()
    for pose in sample_poses(m, 4, step=0.3, seed=0):
        for k in (1, 2):
            for c in enumerate_actuations(pose, mode="any", k=k).combinations:
                assert c.verdict == (VALID if k == 1 else REDUNDANT)
                assert locked_dof(pose, c.inputs) == 0


# ---------------------------------------------------------------------------
# command line
# ---------------------------------------------------------------------------


def test_cli_report_of_the_marked_inputs(capsys):
    assert main(["actuation", str(RPS_FILE)]) == 0
    out = capsys.readouterr().out
    assert "inputs: P1, P2, P3 (3 for 3 DOF)" in out and "verdict: VALID" in out and "kappa" in out
    assert main(["actuation", str(RPS_FILE), "--inputs", "R1,R2"]) == 1
    out = capsys.readouterr().out
    assert "ACTUATION-SINGULAR" in out and "uncontrolled directions" in out


def test_cli_enumerate_with_listed_poses_and_json(tmp_path, capsys):
    pose_file = tmp_path / "tilted.yaml"
    text = RPS_TEXT
    for key, value in (("h", 170), ("phi", 100), ("theta", 5)):
        text = re.sub(rf"\n  {key}: [^\n]*", f"\n  {key}: {value}", text, count=1)
    pose_file.write_text(text, encoding="utf-8")
    assert main(["actuation", str(RPS_FILE), "--enumerate", "--pose", str(pose_file), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["poses"] == ["given pose", str(pose_file)]
    assert {g["type"]: (g["valid"], g["total"]) for g in data["groups"]} == {"3R": (1, 1), "2R1P": (3, 3), "1R2P": (3, 3), "3P": (1, 1)}
    assert main(["actuation", str(RPS_FILE), "--enumerate"]) == 0
    text_out = capsys.readouterr().out
    assert "3R" in text_out and "1R2P" in text_out and "best: P1 P2 P3 (3P)" in text_out


def test_cli_one_choice_at_a_further_pose(tmp_path, capsys):
    pose_file = tmp_path / "tilted.yaml"
    text = RPS_TEXT
    for key, value in (("h", SINGULAR_H), ("phi", SINGULAR_PHI), ("theta", singular_theta())):
        text = re.sub(rf"\n  {key}: [^\n]*", f"\n  {key}: {value!r}", text, count=1)
    pose_file.write_text(text, encoding="utf-8")
    assert main(["actuation", str(RPS_FILE), "--inputs", "R1,R2,R3", "--pose", str(pose_file), "--json"]) == 1
    data = json.loads(capsys.readouterr().out)
    assert data["verdict"] == VALID and [(p["pose"], p["verdict"], p["conditioning"]) for p in data["poses"]] == [(str(pose_file), SINGULAR, 0.0)]
    assert main(["actuation", str(RPS_FILE), "--pose", str(pose_file)]) == 0  # P1 P2 P3 stay valid there
    out = capsys.readouterr().out
    assert "other poses: 1 of 1 valid" in out and f"{pose_file}: valid, kappa" in out


def test_cli_json_of_one_choice(capsys):
    assert main(["actuation", str(RPS_FILE), "--json", "--inputs", "R1,P2,R3"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["verdict"] == "valid" and data["kind"] == "rigid" and data["dof"] == 3
    assert [i["name"] for i in data["inputs"]] == ["R1", "P2", "R3"]
    assert len(data["constraints"]["wrenches"]) == 3


def test_cli_bad_input_is_one_line_with_status_2(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text(RPS_TEXT.replace("actuated: true", "actuated: yes please"), encoding="utf-8")
    assert main(["actuation", str(bad)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "bad.yaml:" in err and "actuated" in err
    assert main(["actuation", str(RPS_FILE), "--inputs", "Z1"]) == 2
    assert "unknown joint 'Z1'" in capsys.readouterr().err
    assert main(["actuation", str(tmp_path / "missing.yaml")]) == 2


def test_the_enumeration_shows_the_margin_that_kappa_does_not_see():
    # 1e-4 mm above the pose where the legs lie in the platform's plane: the three inputs lose their
    # effect together, so kappa stays near 0.447 while the rank margin is about 3e-7
    near = mobility.loads(flat_3rps(1e-4))
    check = mobility.check_actuation(near, ["P1", "P2", "P3"])
    assert check.verdict == "valid" and check.conditioning > 0.4 and check.margin.smallest_kept < 1e-6
    assert any("near an actuation singularity" in w for w in check.warnings)
    found = mobility.enumerate_actuations(near)
    sliders = next(c for c in found.combinations if c.inputs == ("P1", "P2", "P3"))
    assert sliders.conditioning > 0.4 and sliders.margin == pytest.approx(check.margin.smallest_kept, rel=1e-9)
    assert sliders.to_dict()["margin"] == sliders.margin
    header, row = [line for line in enumeration_text(found).splitlines() if "worst margin" in line or "P1 P2 P3" in line][:2]
    assert header.rstrip().endswith("worst margin") and row.split()[-1] == f"{sliders.margin:.2g}"
    assert "actuation margin below measures that" in actuation_text(check)
