"""Coupled joints (gear pairs, mimic joints, joint equalities, fixed tendons): in the model, both routes, the files.

The second route for every answer is the loop-closure route (one more row per
coupling), and for robot files MuJoCo's own constraint Jacobian with its
equalities active.
"""

from __future__ import annotations

import numpy as np
import pytest

import mobility
from mobility import Coupling, Joint, Mechanism
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
