"""Series/parallel decomposition of joint graphs."""

from builders import random_mechanism, three_prs

from mobility.core.model import Joint, Mechanism
from mobility.core.topology import Bridge, JointNode, Parallel, Series, decompose, describe, joints_of


def R(name, a, b):
    return Joint(name, "R", (a, b), axis=(0, 0, 1), point=(0, 0, 0))


def mech(*joints):
    return Mechanism("m", "g", "e", tuple(joints))


def test_serial_chain_in_order_from_ground():
    t = decompose(mech(R("C", "b", "e"), R("A", "g", "a"), R("B", "a", "b")))
    assert describe(t.root) == "series(A,B,C)"
    assert (t.link_count, t.loop_count, t.detached) == (4, 0, ())


def test_parallel_limbs_and_orientation():
    t = decompose(three_prs())
    assert isinstance(t.root, Parallel)
    assert [describe(c) for c in t.root.children] == ["series(P1,R1,S1)", "series(P2,R2,S2)", "series(P3,R3,S3)"]
    # joints written end effector first are still listed from the ground
    t = decompose(mech(R("A2", "e", "x"), R("A1", "x", "g"), R("B", "g", "e")))
    assert describe(t.root) in ("parallel(series(A1,A2), B)", "parallel(B, series(A1,A2))")


def test_loop_inside_a_limb_nests():
    # slider, then a parallelogram loop (two bars), then a last joint: as the Orthoglide's limbs
    t = decompose(
        mech(
            R("P", "g", "s"),
            R("a1", "s", "bar1"), R("a2", "bar1", "c"),
            R("b1", "s", "bar2"), R("b2", "bar2", "c"),
            R("L", "c", "e"),
        )
    )
    assert describe(t.root) == "series(P,parallel(series(a1,a2), series(b1,b2)),L)"
    assert t.loop_count == 1


def test_several_joints_between_two_links():
    t = decompose(mech(R("A", "g", "e"), R("B", "g", "e"), R("C", "e", "g")))
    assert isinstance(t.root, Parallel) and len(t.root.children) == 3 and t.loop_count == 2


def test_hanging_parts_are_detached_not_in_the_root():
    t = decompose(mech(R("A", "g", "e"), R("X", "e", "x"), R("Y", "x", "y"), R("Z", "y", "e"), R("W", "g", "w")))
    assert describe(t.root) == "A"
    assert sorted(sorted(joints_of(n)) for n in t.detached) == [[1, 2, 3], [4]]


def test_bridge_is_kept_whole():
    # Wheatstone bridge: g-a, g-b, a-e, b-e and the tie a-b
    t = decompose(mech(R("GA", "g", "a"), R("GB", "g", "b"), R("AE", "a", "e"), R("BE", "b", "e"), R("AB", "a", "b")))
    assert isinstance(t.root, Bridge)
    assert t.root.source == "g" and t.root.target == "e" and set(t.root.links) == {"g", "a", "b", "e"}
    assert len(t.root.edges) == 5
    assert describe(t.root).startswith("bridge(")


def test_decomposition_uses_every_joint_once():
    for seed in range(100):
        m = random_mechanism(seed)
        t = decompose(m)
        used = joints_of(t.root) + [i for n in t.detached for i in joints_of(n)]
        assert sorted(used) == list(range(len(m.joints)))
        assert t.loop_count == len(m.joints) - len(m.links) + 1


def test_nodes_are_flat():
    # no series directly inside a series, no parallel directly inside a parallel
    def check(node):
        if isinstance(node, (Series, Parallel)):
            for c in node.children:
                assert type(c) is not type(node)
                check(c)
        elif isinstance(node, Bridge):
            for _, _, c in node.edges:
                check(c)
        else:
            assert isinstance(node, JointNode)

    for seed in range(100):
        check(decompose(random_mechanism(seed)).root)


def test_nodes_compare_hash_pickle_and_print_as_values():
    import pickle

    first = decompose(three_prs()).root
    built = Parallel(tuple(Series(tuple(JointNode(3 * k + i, f"{n}{k + 1}") for i, n in enumerate("PRS"))) for k in range(3)))
    assert first == built and hash(first) == hash(built) and first is not built
    assert built != Parallel(built.children[:2]) and built != Series(built.children)
    assert pickle.loads(pickle.dumps(built)) == built
    assert repr(Series((JointNode(0, "A"),))) == "Series(children=(JointNode(index=0, name='A'),))"
    bridge = Bridge("g", "e", ("g", "e", "a"), (("g", "a", JointNode(0, "A")), ("a", "e", Series((JointNode(1, "B"), JointNode(2, "C"))))))
    assert repr(bridge) == (
        "Bridge(source='g', target='e', links=('g', 'e', 'a'), edges=(('g', 'a', JointNode(index=0, name='A')), "
        "('a', 'e', Series(children=(JointNode(index=1, name='B'), JointNode(index=2, name='C'))))))"
    )
    assert describe(bridge) == "bridge(g-a: A, a-e: series(B,C))"


def test_a_graph_that_reduces_whole_has_nothing_detached_and_hanging_parts_are_found():
    # reducible: the decomposition needs no block search
    t = decompose(mech(R("A", "g", "x"), R("B", "x", "e"), R("C", "g", "e"), R("D", "x", "e")))
    assert describe(t.root) == "parallel(C, series(A,parallel(B, D)))" and t.detached == ()
    # a link hanging off the end effector is a detached block, found by the block search
    t = decompose(mech(R("A", "g", "x"), R("B", "x", "e"), R("C", "g", "e"), R("H", "e", "h")))
    assert describe(t.root) == "parallel(C, series(A,B))" and [joints_of(n) for n in t.detached] == [[3]]
