"""Two independent routes must agree: series/parallel screw systems vs whole-graph loop closure."""

from pathlib import Path

import numpy as np
import pytest
from builders import four_bar, normalised, random_mechanism, six_ups, three_prs

import mobility
from mobility.core.joint_screws import joint_screws
from mobility.core.loop_closure import loop_closure
from mobility.core.screw_systems import evaluate
from mobility.core.screws import same_subspace
from mobility.core.topology import Bridge, decompose

MECHANISMS = sorted((Path(__file__).resolve().parent.parent / "mechanisms").glob("**/*.yaml"))


def agree(m: mobility.Mechanism) -> tuple[int, int]:
    """Assert both routes agree on ``m``; return (dof, mobility)."""
    r = mobility.analyze(m)
    lc = loop_closure(m)
    assert r.mobility == lc.mobility, m.name
    assert r.dof == lc.end_effector_twists.shape[1], m.name
    assert r.redundant_constraints == 6 * lc.loops - lc.rank, m.name
    sp = evaluate(decompose(m).root, joint_screws(m))
    assert same_subspace(sp.basis, lc.end_effector_twists), m.name
    # and the reported twists (global frame, file units) are the loop-closure ones mapped back
    assert same_subspace(normalised(m, r.twists), lc.end_effector_twists), m.name
    return r.dof, r.mobility


def test_hand_built_mechanisms_agree():
    assert agree(three_prs()) == (3, 3)
    assert agree(three_prs(heights=(0.1, 0.4, 0.9))) == (3, 3)
    assert agree(four_bar()) == (1, 1)
    assert agree(six_ups()) == (6, 6)


@pytest.mark.parametrize("path", MECHANISMS, ids=[p.stem for p in MECHANISMS])
def test_bundled_mechanisms_agree(path):
    agree(mobility.load(path))


@pytest.mark.parametrize("seed", range(300))
def test_random_mechanisms_agree(seed):
    agree(random_mechanism(seed))


def test_random_sample_exercises_every_case():
    """The random sample above is not trivial: it covers bridges, idle motions, redundancy and all DOF counts."""
    dofs, bridges, idle, redundant = set(), 0, 0, 0
    for seed in range(300):
        m = random_mechanism(seed)
        r = mobility.analyze(m)
        dofs.add(r.dof)
        bridges += isinstance(decompose(m).root, Bridge)
        idle += r.idle_dof > 0
        redundant += r.redundant_constraints > 0
    assert dofs == set(range(7))
    assert bridges >= 10 and idle >= 10 and redundant >= 30


@pytest.mark.parametrize("seed", range(40))
def test_forced_bridges_agree(seed):
    m = random_mechanism(1000 + seed, bridge=True)
    agree(m)


def test_loop_closure_jacobian_closes_loops():
    m = three_prs()
    lc = loop_closure(m)
    assert lc.loops == 2 and lc.jacobian.shape == (12, 15)
    assert np.allclose(lc.jacobian @ lc.joint_rates, 0, atol=1e-12)
