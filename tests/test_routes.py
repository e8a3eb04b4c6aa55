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
from mobility.core.topology import Bridge, JointNode, Parallel, Series, decompose, joints_of

MECHANISMS = sorted((Path(__file__).resolve().parent.parent / "mechanisms").glob("**/*.yaml"))


def agree(m: mobility.Mechanism) -> tuple[int, int]:
    """Assert both routes agree on ``m``; return (dof, mobility)."""
    r = mobility.analyze(m)
    lc = loop_closure(m)
    assert r.mobility == lc.mobility, m.name
    assert r.dof == lc.end_effector_twists.shape[1], m.name
    assert r.redundant_constraints == 6 * lc.loops + len(m.couplings) - lc.rank, m.name  # one equation per coupling
    s = joint_screws(m)
    sp = evaluate(decompose(m).root, s.twists[None], s.offsets)
    assert same_subspace(sp.basis[0], lc.end_effector_twists), m.name
    # and the reported twists (global frame, file units) are the loop-closure ones mapped back
    assert same_subspace(normalised(m, r.twists), lc.end_effector_twists), m.name
    nodes_agree(m, r)
    return r.dof, r.mobility


def end_links(node, source: str, target: str, m: mobility.Mechanism) -> dict:
    """``{id(node): (node, a, b)}`` for every node below ``node``, whose network joins links ``source`` and ``target``."""
    out = {id(node): (node, source, target)}
    if isinstance(node, Parallel):
        for child in node.children:
            out.update(end_links(child, source, target, m))
    elif isinstance(node, Series):  # children in order; consecutive children share exactly one link
        links = [{x for i in joints_of(c) for x in m.joints[i].links} for c in node.children]
        ends = [source] + [(a & b).pop() for a, b in zip(links, links[1:])] + [target]
        for child, a, b in zip(node.children, ends, ends[1:]):
            out.update(end_links(child, a, b, m))
    elif isinstance(node, Bridge):
        for u, v, child in node.edges:
            out.update(end_links(child, u, v, m))
    return out


def nodes_agree(m: mobility.Mechanism, r) -> None:
    """Each node of the main tree, as reported by the result, against loop closure of its own network.

    The network of a node (its joints, between its two end links) is made a
    mechanism of its own: its end effector's DOF and its mobility must be the
    node's ``dof`` and ``dof + idle``.
    """
    systems = r.node_systems
    assert len(systems) >= len(m.joints)
    for node, a, b in end_links(r.topology.root, m.ground, m.end_effector, m).values():
        found = systems[node]
        if isinstance(node, JointNode):
            assert found == (m.joints[node.index].dof, 0)
            continue
        world = m.world_joints
        inside = {m.joints[i].name for i in joints_of(node)}
        part = mobility.Mechanism("part", a, b, tuple(world[i] for i in joints_of(node)), couplings=tuple(c for c in m.couplings if set(c.joints) <= inside))
        lc = loop_closure(part)
        assert (found.dof, found.mobility) == (lc.end_effector_twists.shape[1], lc.mobility), (m.name, node)
    # the detached networks only add to the mobility
    assert r.mobility == systems[r.topology.root].mobility + sum(systems[d].mobility for d in r.topology.detached)


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
