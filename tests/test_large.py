"""Large mechanisms: any size that fits in memory analyses, and the two routes still agree.

A ladder of triangles nests series inside parallel as deep as it is long, a
long chain makes one series of thousands of joints, a parallel mechanism of
hundreds of limbs one parallel node of hundreds of children.  None of them
may meet a recursion limit, and the counts must be those of the independent
loop-closure route (:mod:`mobility.core.loop_closure`), which beyond its size
limit closes the loops chord by chord; that route is checked against its own
one-SVD form here too.  Speed is measured by ``benchmarks/bench_large.py``,
never here.
"""

from __future__ import annotations

import json
import sys

import numpy as np
import pytest
from builders import prs_limbs, random_mechanism, serial_chain, triangle_ladder

import mobility
from mobility.cli import main
from mobility.core.joint_screws import joint_screws
from mobility.core.loop_closure import WHOLE_SVD_SIZE, loop_closure
from mobility.core.model import Joint, Mechanism
from mobility.core.screw_systems import evaluate
from mobility.core.screws import same_subspace
from mobility.core.topology import Parallel, Series, decompose, describe, joints_of

Z = (0.0, 0.0, 1.0)


def four_bar_ladder(cells: int) -> Mechanism:
    """The ladder with each rung made of two bars (``B{i}``, ``m{i}``, ``C{i}``): a chain of parallelogram four-bars, mobility 1.

    Parallelograms pass the motion on unchanged: every link ``l{i}`` turns as
    fast as the first, so the end effector's freedom is as clear after 2,000
    cells as after one (with other four-bars the ratio of the speeds is a
    product of 2,000 factors, below any rank threshold).  The cranks ``v``
    alternate so that no two joints of a link coincide.
    """
    joints = [Joint(f"A{i}", "R", ("g", f"l{i}"), axis=Z, point=(float(i), 0.0, 0.0)) for i in range(cells + 1)]
    for i in range(cells):
        v = (0.2, 1.0) if i % 2 == 0 else (-0.3, 0.8)
        joints.append(Joint(f"B{i}", "R", (f"l{i}", f"m{i}"), axis=Z, point=(i + v[0], v[1], 0.0)))
        joints.append(Joint(f"C{i}", "R", (f"m{i}", f"l{i + 1}"), axis=Z, point=(i + 1 + v[0], v[1], 0.0)))
    return Mechanism(f"ladder of {cells} four-bars", "g", f"l{cells}", tuple(joints))


def agree(m: Mechanism) -> mobility.Result:
    """Assert the series/parallel route and the loop-closure route agree on ``m``; return the result."""
    r = mobility.analyze(m)
    lc = loop_closure(m)
    assert (r.mobility, r.dof) == (lc.mobility, lc.end_effector_twists.shape[1])
    assert r.redundant_constraints == 6 * lc.loops - lc.rank
    s = joint_screws(m)
    assert same_subspace(evaluate(decompose(m).root, s.twists[None], s.offsets).basis[0], lc.end_effector_twists)
    return r


@pytest.mark.parametrize("triangles", [200, 2000])
def test_rigid_ladders_analyse_and_agree_with_loop_closure(triangles):
    r = agree(triangle_ladder(triangles))
    assert (r.dof, r.mobility, r.loops, r.gruebler_kutzbach) == (0, 0, triangles, 1 - 4 * triangles)
    # 3 equations of each planar loop repeat, and the rigid triangles repeat one more each but the first
    assert r.redundant_constraints == 4 * triangles - 1 and r.common_constraints == 3
    n = triangles
    assert r.structure.count("parallel(") == n and r.structure.startswith(f"parallel(A{n}, series(parallel(A{n - 1}, series(")
    assert r.structure.endswith(f",B{n - 2})),B{n - 1}))")


@pytest.mark.parametrize("cells", [200, 2000])
def test_a_ladder_of_four_bars_moves_with_one_freedom(cells):
    r = agree(four_bar_ladder(cells))
    assert (r.dof, r.pattern, r.mobility, r.loops) == (1, "1R", 1, cells)
    assert r.redundant_constraints == 3 * cells  # planar: 3 equations of each loop repeat
    (rotation,) = r.rotations  # the last link turns about its ground pivot
    assert np.allclose(np.abs(rotation.axis), Z) and np.allclose(rotation.point[:2], (cells, 0.0), atol=1e-9)


def test_a_long_chain_is_one_series_with_idle_freedoms():
    m = serial_chain(2000)
    r = agree(m)
    assert (r.dof, r.pattern, r.mobility, r.idle_dof, r.loops) == (6, "3T3R", 2000, 1994, 0)
    root = r.topology.root
    assert isinstance(root, Series) and len(root.children) == 2000
    assert r.node_systems[root] == (6, 1994)


def test_hundreds_of_limbs_make_one_parallel_node():
    m = prs_limbs(667)
    r = agree(m)
    assert (r.dof, r.pattern, r.mobility, r.loops) == (3, "1T2R", 3, 666)
    assert isinstance(r.topology.root, Parallel) and len(r.topology.root.children) == 667
    assert r.redundant_constraints == 6 * 666 - (5 * 667 - 3)
    assert np.allclose(np.abs(r.translations), [[0, 0, 1]])


def test_deep_trees_describe_compare_hash_and_print_without_recursion():
    m = triangle_ladder(3000)
    limit = sys.getrecursionlimit()
    root = decompose(m).root
    # built again from the same graph (the decomposition is cached: clear it to get new objects)
    from mobility.core import topology

    topology._decompose.cache_clear()
    again = decompose(m).root
    assert again is not root and again == root and hash(again) == hash(root)
    assert describe(root).count("series(") == 3000
    assert sorted(joints_of(root)) == list(range(len(m.joints)))
    assert repr(root).startswith("Parallel(children=(JointNode(index=3000, name='A3000'), Series(children=(")
    assert sys.getrecursionlimit() == limit  # nothing raised it


def test_deep_trees_differ_where_they_differ():
    a = decompose(triangle_ladder(1500)).root
    renamed = triangle_ladder(1500).joints[:-1] + (Joint("X", "R", ("l1499", "l1500"), axis=Z, point=(0.0, 1.0, 0.0)),)
    b = decompose(Mechanism("m", "g", "l1500", renamed)).root
    assert b != a and describe(b) == describe(a).replace("B1499", "X")


@pytest.mark.parametrize("seed", range(60))
def test_closing_the_loops_chord_by_chord_agrees_with_one_svd(seed):
    m = random_mechanism(seed)
    whole, chords = loop_closure(m, method="svd"), loop_closure(m, method="chords")
    assert (whole.rank, whole.mobility) == (chords.rank, chords.mobility)
    assert same_subspace(whole.end_effector_twists, chords.end_effector_twists)
    assert same_subspace(whole.joint_rates, chords.joint_rates)
    assert np.allclose(chords.jacobian @ chords.joint_rates, 0.0, atol=1e-10)
    assert np.allclose(chords.joint_rates.T @ chords.joint_rates, np.eye(chords.mobility), atol=1e-10)


def test_the_size_limit_of_one_svd_is_where_the_routes_switch():
    small, large = four_bar_ladder(WHOLE_SVD_SIZE // 6 - 1), four_bar_ladder(WHOLE_SVD_SIZE // 6 + 10)
    for m in (small, large):
        auto, whole, chords = loop_closure(m), loop_closure(m, method="svd"), loop_closure(m, method="chords")
        assert auto.mobility == whole.mobility == chords.mobility
        assert same_subspace(auto.joint_rates, whole.joint_rates)
    with pytest.raises(mobility.errors.RequestError, match="method"):
        loop_closure(small, method="qr")


def ladder_text(triangles: int) -> str:
    lines = [f"name: ladder of {triangles}", "ground: g", f"end_effector: l{triangles}", "joints:"]
    lines += [f"  - {{name: A{i}, type: R, links: [g, l{i}], axis: [0, 0, 1], point: [{i}, 0, 0]}}" for i in range(triangles + 1)]
    lines += [f"  - {{name: B{i}, type: R, links: [l{i}, l{i + 1}], axis: [0, 0, 1], point: [{i + 0.5}, 1, 0]}}" for i in range(triangles)]
    return "\n".join(lines + ["expected: {dof: 0, mobility: 0}"]) + "\n"


def test_the_command_line_reports_a_ladder_of_two_thousand_loops(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("MOBILITY_MAX_JOINTS", "10000")  # the loader's default limit is lower
    path = tmp_path / "ladder.yaml"
    path.write_text(ladder_text(2000))
    assert main(["analyze", "--json", str(path)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert (data["dof"], data["mobility"], data["loops"], data["joints"]) == (0, 0, 2000, 4001)
    assert main(["analyze", "--limbs", str(path)]) == 0
    assert "structure: parallel(A2000, series(parallel(A1999, " in capsys.readouterr().out
    assert main(["check", str(path)]) == 0
