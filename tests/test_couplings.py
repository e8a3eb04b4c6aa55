"""Coupled joints (gear pairs, mimic joints, joint equalities, fixed tendons): in the model, both routes, the files.

The second route for every answer is the loop-closure route (one more row per
coupling), and for robot files MuJoCo's own constraint Jacobian with its
equalities active.
"""

from __future__ import annotations

import re

import mujoco
import numpy as np
import pytest
from conftest import MECHANISMS
from test_mjcf import CONNECT, JOINT_EQ, WELD, MujocoRoute, assert_agrees_with_mujoco, mujoco_compile

import mobility
from mobility import Coupling, Joint, Mechanism
from mobility.cli import main
from mobility.io.robot_files import read_robot
from mobility.io.writer import mechanism_to_yaml
from mobility.core.screws import same_subspace
from mobility.core.topology import Bridge, decompose
from mobility.errors import MechanismError

Z = (0.0, 0.0, 1.0)


def R(name, a, b, point, axis=Z):
    return Joint(name, "R", (a, b), axis=axis, point=point)


def gear_pair(ratio: float = 2.0, coupled: bool = True) -> Mechanism:
    """Two wheels on the ground, ``q'_A + ratio q'_B = 0``."""
    couplings = (Coupling(("A", "B"), (1.0, ratio)),) if coupled else ()
    return Mechanism("gears", "ground", "b", (R("A", "ground", "a", (0, 0, 0)), R("B", "ground", "b", (3, 0.5, 0))), couplings=couplings)


def four_bar(couplings=()) -> Mechanism:
    return Mechanism("four-bar", "g", "c", (R("A", "g", "k", (0, 0, 0)), R("B", "k", "c", (1, 2, 0)), R("C", "c", "r", (4, 2.5, 0)), R("D", "r", "g", (5, 0, 0))), couplings=couplings)


def both_routes(m: Mechanism):
    r, lc, chords = mobility.analyze(m), mobility.loop_closure(m), mobility.loop_closure(m, method="chords")
    assert r.mobility == lc.mobility == chords.mobility
    assert r.dof == lc.end_effector_twists.shape[1]
    if r.dof:
        assert same_subspace(lc.world_twists.T, r.twists.T)
    return r, lc


# -- the model --------------------------------------------------------------------------------

@pytest.mark.parametrize("couplings, key, words", [
    ((Coupling(("A", "E"), (1, 2)),), "couplings[0].joints[1]", "unknown joint 'E'"),
    ((Coupling(("A", "B"), (1, 2)), Coupling(("C", "S"), (1, 1))), "couplings[1].joints[1]", "of type S"),
    (("A",), "couplings[0]", "expected a Coupling"),
])
def test_a_coupling_on_joints_the_mechanism_cannot_couple_is_refused_with_its_key(couplings, key, words):
    joints = four_bar().joints + (Joint("S", "S", ("c", "x"), point=(0, 0, 0)),)
    with pytest.raises(MechanismError) as err:
        Mechanism("m", "g", "c", joints, couplings=couplings)
    assert err.value.key == key and words in err.value.message


@pytest.mark.parametrize("joints, coefficients, key", [
    (("A", "A"), (1, 2), "joints[1]"),
    (("A", "B"), (1, 0), "coefficients[1]"),
    (("A",), (1,), "joints"),
    (("A", "B"), (1,), "coefficients"),
    (("A", "B"), (1, float("nan")), "coefficients[1]"),
])
def test_a_malformed_coupling_is_refused(joints, coefficients, key):
    with pytest.raises(MechanismError) as err:
        Coupling(joints, coefficients)
    assert err.value.key == key


def test_a_slide_and_a_turn_are_not_coupled():
    joints = (R("A", "g", "a", (0, 0, 0)), Joint("P", "P", ("g", "b"), axis=(1, 0, 0)))
    with pytest.raises(MechanismError, match="slides only or turns only"):
        Mechanism("rack", "g", "b", joints, couplings=(Coupling(("A", "P"), (1, 1)),))


# -- both routes ------------------------------------------------------------------------------

def test_a_gear_pair_moves_with_one_freedom_and_without_its_coupling_with_two():
    free, _ = both_routes(gear_pair(coupled=False))
    geared, lc = both_routes(gear_pair())
    assert (free.mobility, free.dof) == (2, 1)
    assert (geared.mobility, geared.dof, geared.idle_dof) == (1, 1, 0)
    assert isinstance(decompose(gear_pair()).root, Bridge)
    assert lc.jacobian.shape == (1, 2)  # no loop: the coupling's row only


def test_the_coordinates_of_unit_twists_are_the_joint_rates_times_their_twists_norms():
    """The loop-closure route's solution, turned back into natural rates from the joints alone, keeps the coupling."""
    m = gear_pair(ratio=3.0)
    lc = mobility.loop_closure(m)
    norm = lc.screws.normalisation
    (x,) = lc.joint_rates.T  # coordinates on the unit columns
    rates = []
    for joint, xj in zip(m.joints, x):  # |T| of a turn [w; (p - c) x w / L], |w| = 1
        v = np.cross(np.subtract(joint.point, norm.centre), joint.axis) / norm.length
        rates.append(xj / np.sqrt(1.0 + v @ v))
    assert abs(rates[0] + 3.0 * rates[1]) < 1e-12 * max(map(abs, rates))
    assert abs(rates[0]) > 0.1  # a solution that moves


def test_a_screw_driven_by_a_motor_keeps_its_coupling_in_natural_rates():
    """An H joint's unit column is its twist per radian [w; (p - c) x w / L + h w / L] scaled by its norm, as an R joint's."""
    joints = (R("M", "g", "motor", (0, 0, 0)), Joint("S", "H", ("g", "nut"), axis=(1, 0, 0), point=(2, 1, 0), pitch=0.5))
    m = Mechanism("lead screw", "g", "nut", joints, couplings=(Coupling(("M", "S"), (2.0, -1.0)),))
    r, lc = both_routes(m)
    assert (r.mobility, r.dof) == (1, 1)
    norm = lc.screws.normalisation
    (x,) = lc.joint_rates.T
    rates = []
    for joint, xj in zip(m.joints, x):
        v = (np.cross(np.subtract(joint.point, norm.centre), joint.axis) + (joint.pitch or 0.0) * np.asarray(joint.axis)) / norm.length
        rates.append(xj / np.sqrt(1.0 + v @ v))
    assert abs(2.0 * rates[0] - rates[1]) < 1e-12 * max(map(abs, rates)) and abs(rates[0]) > 0.1


def test_a_coupling_that_a_loop_already_obeys_is_redundant_and_one_it_does_not_locks_the_loop():
    plain, _ = both_routes(four_bar())
    assert plain.mobility == 1
    # the four-bar's own velocity ratio between A and C, at this pose, from the loop-closure route
    lc = mobility.loop_closure(four_bar())
    x = lc.joint_rates[:, 0]
    scale = np.linalg.norm(lc.screws.twists[:3], axis=0)  # |u[:3]| = 1 / |T| for a turn
    qa, qc = x[0] * scale[0], x[2] * scale[2]
    obeyed, lc_obeyed = both_routes(four_bar((Coupling(("A", "C"), (qc, -qa)),)))
    assert obeyed.mobility == 1 and obeyed.dof == 1
    assert lc_obeyed.rank == 3  # the coupling's row lies in the loop's
    locked, _ = both_routes(four_bar((Coupling(("A", "C"), (qc, qa)),)))
    assert (locked.mobility, locked.dof) == (0, 0)
    assert (obeyed.gruebler_kutzbach, obeyed.redundant_constraints) == (-3, 4)  # the loop's 6 equations and the coupling's 1: rank 3
    assert "6 independent constraints and the coupling of joints 1 (7 in all); the loop-closure equations have rank 3" in obeyed.gruebler_kutzbach_explanation


def test_a_coupling_between_a_detached_chain_and_the_end_effector_drives_it():
    """A wheel that is not on the way to the end effector, geared to the end effector's own: one freedom in all."""
    joints = four_bar().joints + (R("W", "g", "wheel", (9, 0, 0)),)
    apart, _ = both_routes(Mechanism("m", "g", "c", joints))
    assert apart.mobility == 2
    geared, _ = both_routes(Mechanism("m", "g", "c", joints, couplings=(Coupling(("W", "A"), (1.0, -4.0)),)))
    assert (geared.mobility, geared.dof) == (1, 1)


def test_slides_coupled_like_the_fingers_of_a_parallel_gripper():
    joints = (Joint("L", "P", ("palm", "left"), axis=(1, 0, 0)), Joint("Rt", "P", ("palm", "right"), axis=(-1, 0, 0)),
              Joint("F", "R", ("palm", "g"), axis=Z, point=(0, 0, 0)))
    m = Mechanism("gripper", "g", "left", joints, couplings=(Coupling(("L", "Rt"), (1.0, -1.0)),))
    r, _ = both_routes(m)
    assert (r.mobility, r.dof) == (2, 2)
    assert both_routes(Mechanism("gripper", "g", "left", joints))[0].mobility == 3


# -- the YAML format ---------------------------------------------------------------------------

GEARS = """name: gears
ground: frame
end_effector: b
parameters: {ratio: 2}
joints:
  - {name: A, type: R, links: [frame, a], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: B, type: R, links: [frame, b], axis: [0, 0, 1], point: [3, 0, 0]}
couplings:
  - {joints: [A, B], coefficients: [1, ratio]}
"""


def test_a_file_writes_couplings_with_expressions_and_convert_writes_them_back(tmp_path):
    m = mobility.loads(GEARS)
    assert m.couplings == (Coupling(("A", "B"), (1.0, 2.0)),)
    assert mobility.analyze(m).mobility == 1
    text = mechanism_to_yaml(m)
    assert "couplings:\n  - {joints: [A, B], coefficients: [1, 2]}\n" in text
    assert mobility.loads(text).couplings == m.couplings
    source = tmp_path / "gears.yaml"
    source.write_text(GEARS)
    assert main(["convert", str(source), "-o", str(tmp_path / "out.yaml")]) == 0
    assert mobility.load(tmp_path / "out.yaml").couplings == m.couplings


@pytest.mark.parametrize("old, new, message", [
    ("joints: [A, B]", "joints: [A, C]", "gears.yaml:9: couplings[0].joints[1]: unknown joint 'C'; expected one of: A, B"),
    ("joints: [A, B]", "joints: [A, A]", "gears.yaml:9: couplings[0].joints[1]: joint 'A' is already in this coupling"),
    ("coefficients: [1, ratio]", "coefficients: [0, ratio]", "gears.yaml:9: couplings[0].coefficients[0]: expected a non-zero number"),
    ("coefficients: [1, ratio]", "coefficients: [1]", "gears.yaml:9: couplings[0].coefficients: expected one number per joint (2), got 1"),
    ("coefficients: [1, ratio]", "coefficients: [1, radio]", "gears.yaml:9: couplings[0].coefficients[1]: "),
    ("{joints: [A, B], coefficients: [1, ratio]}", "{joints: [A, B]}", "gears.yaml:9: couplings[0].coefficients: missing"),
    ("type: R, links: [frame, b]", "type: S, links: [frame, b]", "gears.yaml:9: couplings[0].joints[1]: joint 'B' is of type S"),
])
def test_a_bad_coupling_in_a_file_is_one_line_naming_file_line_and_key(tmp_path, capsys, old, new, message):
    path = tmp_path / "gears.yaml"
    text = GEARS.replace(old, new)
    if "type: S" in new:
        text = text.replace("axis: [0, 0, 1], point: [3, 0, 0]", "point: [3, 0, 0]")
    path.write_text(text)
    assert main(["analyze", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and err.startswith("mobility: ") and f"{tmp_path}/{message}" in err, err


# -- robot files and MuJoCo's constraint Jacobian ----------------------------------------------

TENDON_EQ = int(mujoco.mjtEq.mjEQ_TENDON)
EVERY_EQUALITY = (CONNECT, WELD, JOINT_EQ, TENDON_EQ)


def finger(side: str, sign: float) -> tuple[str, str]:
    """One finger of a Robotiq-like gripper (driver, coupler, spring link, follower: a planar five-bar closed by a connect), and its connect."""
    x = lambda v: f"{sign * v:g}"  # noqa: E731
    geom = '<geom size="0.004"/>'
    body = f"""
      <body name="{side}_driver" pos="{x(0.03)} 0 0"><joint name="{side}_driver_joint" axis="0 1 0"/>{geom}
        <body name="{side}_coupler" pos="{x(0.01)} 0 0.05"><joint name="{side}_coupler_joint" axis="0 1 0"/>{geom}</body>
      </body>
      <body name="{side}_spring_link" pos="{x(0.015)} 0 0.01"><joint name="{side}_spring_joint" axis="0 1 0"/>{geom}
        <body name="{side}_follower" pos="{x(0.01)} 0 0.05"><joint name="{side}_follower_joint" axis="0 1 0"/>{geom}</body>
      </body>"""
    connect = f'<connect name="{side}_loop" body1="{side}_coupler" body2="{side}_follower" anchor="{x(-0.005)} 0 0.04"/>'
    return body, connect


def robotiq_like(coupled: bool = True) -> str:
    (left, c1), (right, c2) = finger("left", 1.0), finger("right", -1.0)
    active = "" if coupled else ' active="false"'
    return f"""<mujoco model="robotiq-like">
  <worldbody><body name="base">{left}{right}
  </body></worldbody>
  <equality>{c1}{c2}
    <joint name="drivers" joint1="right_driver_joint" joint2="left_driver_joint" polycoef="0 1 0 0 0"{active}/>
  </equality>
</mujoco>"""


def write(tmp_path, name: str, text: str):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_a_robotiq_like_gripper_has_mobility_four_without_its_driver_coupling_and_three_with_it_as_mujoco_says(tmp_path):
    free = read_robot(write(tmp_path, "free.xml", robotiq_like(coupled=False)))
    coupled = read_robot(write(tmp_path, "coupled.xml", robotiq_like()))
    assert free.mechanism.couplings == () and len(coupled.mechanism.couplings) == 1
    assert mobility.analyze(free.mechanism).mobility == 4 == mobility.loop_closure(free.mechanism).mobility
    assert mobility.analyze(coupled.mechanism).mobility == 3 == mobility.loop_closure(coupled.mechanism).mobility
    assert assert_agrees_with_mujoco(free, *mujoco_compile(robotiq_like(coupled=False))).mobility == 4
    assert assert_agrees_with_mujoco(coupled, *mujoco_compile(robotiq_like()), kinds=EVERY_EQUALITY).mobility == 3


def test_a_nonlinear_joint_equality_acts_through_its_slope_at_qpos0_and_the_report_says_so(tmp_path, capsys):
    text = robotiq_like().replace('polycoef="0 1 0 0 0"', 'polycoef="0 -2 0.5 0 0"')
    robot = read_robot(write(tmp_path, "gripper.xml", text))
    assert robot.mechanism.couplings[0].terms == (("right_driver_joint", 1.0), ("left_driver_joint", 2.0))
    assert any("is not linear" in n and "slope at qpos0, -2" in n for n in robot.notes)
    assert_agrees_with_mujoco(robot, *mujoco_compile(text), kinds=EVERY_EQUALITY)
    assert main(["analyze", str(tmp_path / "gripper.xml")]) == 0
    notes = [line for line in capsys.readouterr().err.splitlines() if "is not linear" in line]
    assert len(notes) == 1 and notes[0].startswith("mobility: note: equality joint drivers (line ")


def test_an_equality_that_holds_one_joint_still_or_mixes_a_slide_and_a_hinge_is_refused_at_its_line(tmp_path):
    held = robotiq_like().replace(' joint2="left_driver_joint" polycoef="0 1 0 0 0"', "")
    with pytest.raises(mobility.MechanismFileError, match=r"held\.xml:\d+: equality/joint\[drivers\]: an equality of joints \(right_driver_joint\) that holds right_driver_joint still"):
        read_robot(write(tmp_path, "held.xml", held))
    assert len(read_robot(tmp_path / "held.xml", ignore_unsupported=True).mechanism.couplings) == 0
    mixed = robotiq_like().replace('<joint name="left_driver_joint" axis="0 1 0"/>', '<joint name="left_driver_joint" type="slide" axis="0 1 0"/>')
    with pytest.raises(mobility.MechanismFileError, match=r"mixed\.xml:\d+: equality/joint\[drivers\]: joint 'left_driver_joint' is a slide \(P\) and joint 'right_driver_joint' is not"):
        read_robot(write(tmp_path, "mixed.xml", mixed))


def mjcf_of_tree(m: Mechanism) -> str:
    """An MJCF of a tree of R joints (bodies at the origin, unrotated, so every joint is written in world coordinates), its couplings as fixed tendons held by equalities."""
    children: dict[str, list[Joint]] = {}
    for j in m.joints:
        children.setdefault(j.links[0], []).append(j)

    def bodies(link: str) -> str:
        return "".join(f'<body name="{j.links[1]}"><joint name="{j.name}" pos="{" ".join(map(str, j.point))}" axis="{" ".join(map(str, j.axis))}"/>'
                       f'<geom size="1"/>{bodies(j.links[1])}</body>' for j in children.get(link, []))

    tendons = "".join(f'<fixed name="t{k}">' + "".join(f'<joint joint="{n}" coef="{c}"/>' for n, c in c_.terms) + "</fixed>" for k, c_ in enumerate(m.couplings))
    equalities = "".join(f'<tendon tendon1="t{k}"/>' for k in range(len(m.couplings)))
    return f'<mujoco model="{m.name}"><worldbody><body name="{m.ground}">{bodies(m.ground)}</body></worldbody>' \
           f"<tendon>{tendons}</tendon><equality>{equalities}</equality></mujoco>"


@pytest.mark.parametrize("stem", ["gear_pair", "bevel_differential", "coupled_finger"])
def test_the_bundled_coupled_mechanisms_agree_with_mujoco_with_their_couplings_as_tendon_equalities(tmp_path, stem):
    m = mobility.load(MECHANISMS / f"{stem}.yaml")
    r, _ = both_routes(m)
    text = mjcf_of_tree(m)
    robot = read_robot(write(tmp_path, f"{stem}.xml", text), end_effector=m.end_effector)
    assert len(robot.mechanism.couplings) == len(m.couplings)
    route = assert_agrees_with_mujoco(robot, *mujoco_compile(text), kinds=EVERY_EQUALITY)
    assert (route.mobility, route.dof) == (r.mobility, r.dof)
    uncoupled = MujocoRoute(*mujoco_compile(text), m.end_effector, kinds=(CONNECT, WELD))
    assert uncoupled.mobility == r.mobility + len(m.couplings)  # each coupling takes one freedom here


@pytest.mark.parametrize("seed", range(60))
def test_random_mechanisms_with_couplings_agree_between_the_routes(seed):
    """Random mechanisms (series, parallel, bridges, idle motions) with one or two couplings of their one-freedom joints."""
    from builders import random_mechanism
    from test_routes import agree

    for k in range(seed * 100, seed * 100 + 100):  # the first random mechanism from here with two turns or two slides
        m = random_mechanism(k, bridge=seed % 3 == 0)
        turns = [j.name for j in m.joints if j.type in ("R", "H")]
        slides = [j.name for j in m.joints if j.type == "P"]
        if len(turns) >= 2 or len(slides) >= 2:
            break
    rng = np.random.default_rng(seed)
    couplings = []
    for names in (turns, slides):
        if len(names) >= 2:
            picked = rng.choice(names, size=min(len(names), int(rng.integers(2, 4))), replace=False)
            couplings.append(Coupling(tuple(str(n) for n in picked), tuple(float(x) for x in rng.choice([-3, -1, 0.5, 1, 2], size=len(picked)))))
    assert couplings, "every random mechanism has two turns or two slides"
    coupled = Mechanism(m.name, m.ground, m.end_effector, m.joints, m.frames, couplings=tuple(couplings))
    agree(coupled)
    free = mobility.analyze(m).mobility
    assert free - len(couplings) <= mobility.analyze(coupled).mobility <= free  # each coupling takes at most one freedom


def test_full_cycle_mobility_refuses_coupled_joints_rather_than_let_them_turn_apart(capsys):
    with pytest.raises(mobility.RequestError, match=r"finite_mobility: 'gears' couples joints \(A/B\)"):
        mobility.finite_mobility(gear_pair())
    assert main(["analyze", str(MECHANISMS / "gear_pair.yaml"), "--finite"]) == 2
    assert capsys.readouterr().err.startswith("mobility: finite_mobility: 'spur gear pair' couples joints (A/B)")


def test_locking_a_coupled_joint_holds_the_joints_its_coupling_leaves_alone():
    from mobility.actuation import lock_joints, locked_dof

    finger = mobility.load(MECHANISMS / "coupled_finger.yaml")
    locked = lock_joints(finger, ["PIP"])
    assert [j.name for j in locked.joints] == ["MCP"] and locked.couplings == ()  # DIP follows PIP: held too
    assert (locked_dof(finger, ["PIP"]), locked_dof(finger, ["MCP", "PIP"])) == (1, 0)
    differential = mobility.load(MECHANISMS / "bevel_differential.yaml")
    one_axle = lock_joints(differential, ["L"])
    assert [c.joints for c in one_axle.couplings] == [("C", "S"), ("Rt", "C", "S")]
    assert (locked_dof(differential, ["L"]), locked_dof(differential, ["L", "Rt"])) == (1, 0)
    # the actuation verdicts of the screw route agree with locking: two inputs drive the finger, PIP and DIP together do not
    text = (MECHANISMS / "coupled_finger.yaml").read_text()
    marked = lambda *names: mobility.loads(re.sub(r"(\{name: (%s),.*?)\}" % "|".join(names), r"\1, actuated: true}", text).split("expected:")[0])  # noqa: E731
    assert mobility.check_actuation(marked("MCP", "PIP")).verdict == "valid"
    assert mobility.check_actuation(marked("PIP", "DIP")).verdict == "actuation-singular"


def test_coupling_rates_are_mujocos_where_the_joints_stand_at_different_distances_from_the_centre(tmp_path):
    """A bent finger: the coupled joints' unit columns have different norms, so a coefficient taken on the unit coordinates would turn the fingertip's twist system; MuJoCo's rows are on the natural rates."""
    joints = (R("MCP", "palm", "proximal", (0, 0, 0)), R("PIP", "proximal", "middle", (45, 10, 0)), R("DIP", "middle", "distal", (70, 30, 0)))
    m = Mechanism("bent finger", "palm", "distal", joints, couplings=(Coupling(("DIP", "PIP"), (3.0, -2.0)),))
    r, lc = both_routes(m)
    assert (r.mobility, r.dof) == (2, 2)
    text = mjcf_of_tree(m)
    route = assert_agrees_with_mujoco(read_robot(write(tmp_path, "finger.xml", text), end_effector="distal"), *mujoco_compile(text), kinds=EVERY_EQUALITY)
    model, data = mujoco_compile(text)
    jac = np.asarray(data.efc_J[: data.nefc * model.nv]).reshape(data.nefc, model.nv)
    scale = np.linalg.norm(lc.screws.twists[:3], axis=0)  # |u[:3]| = 1 / |T|: unit coordinates to radians
    natural = lc.joint_rates * scale[:, None]
    assert np.abs(jac @ natural).max() < 1e-12 * np.abs(natural).max()  # our rates close MuJoCo's rows
    assert route.mobility == natural.shape[1] == 2


def test_what_moves_a_coupled_mechanism_to_other_poses_is_refused_in_one_line(capsys):
    # the position solver closes loops, not couplings: a sweep or sampled poses would let coupled joints turn apart
    m = mobility.load("mechanisms/gear_pair.yaml")
    with pytest.raises(mobility.RequestError, match=r"^sweep: 'spur gear pair' couples joints \(A/B\), which the poses of a sweep do not follow yet"):
        mobility.sweep(m, ["A=0:1:3"])
    with pytest.raises(mobility.RequestError, match=r"^sample_poses: 'spur gear pair' couples joints \(A/B\)"):
        mobility.sample_poses(m, 2)
    from mobility.cli import main

    assert main(["sweep", "mechanisms/gear_pair.yaml", "--vary", "A=0:1:3"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mobility: sweep: 'spur gear pair' couples joints (A/B)") and len(err.strip().splitlines()) == 1
