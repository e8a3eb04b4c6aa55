"""The joint graph and its series/parallel decomposition between ground and end effector.

Links are nodes and joints are edges of a multigraph (two joints between the
same links are a loop).  :func:`decompose` reduces the two-terminal network
between the ground and the end effector by

* **series**: a link with exactly two joints, neither terminal, merges them;
* **parallel**: several connections between the same two links merge;

until one connection remains.  What does not reduce further (every inner link
has three or more connections, e.g. a tie link between two limbs) becomes a
:class:`Bridge`, solved later by loop closure; it is never refused.

Parts of the graph on no ground-to-end-effector path (blocks of the graph
that the virtual edge ground–end-effector does not join) cannot change the
end effector's freedom; they are kept as :attr:`Topology.detached` because
they still add to the mobility of the whole mechanism.

The decomposition is structural (no geometry) and cached per graph, so a
sweep over poses of one mechanism pays for it once.

Examples
--------
>>> from mobility.core.model import Joint, Mechanism
>>> R = lambda n, a, b: Joint(n, "R", (a, b), axis=(0, 0, 1), point=(0, 0, 0))
>>> m = Mechanism("two limbs", "g", "ee", (R("A1", "g", "x"), R("A2", "x", "ee"),
...                                         R("B1", "g", "y"), R("B2", "y", "ee")))
>>> describe(decompose(m).root)
'parallel(series(A1,A2), series(B1,B2))'
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass
from functools import lru_cache
from typing import Union

import networkx as nx

from .model import Mechanism

__all__ = ["JointNode", "Series", "Parallel", "Bridge", "Node", "Topology", "TreeEdge", "decompose", "describe", "joints_of", "spanning_tree"]


@dataclass(frozen=True)
class JointNode:
    """A single joint (by index in :attr:`Mechanism.joints`)."""

    index: int
    name: str


@dataclass(frozen=True)
class Series:
    """Connections in series, in order from the first terminal to the second."""

    children: tuple["Node", ...]


@dataclass(frozen=True)
class Parallel:
    """Connections in parallel between the same two links."""

    children: tuple["Node", ...]


@dataclass(frozen=True)
class Bridge:
    """A network that is not series-parallel, between ``source`` and ``target``.

    ``edges`` are ``(u, v, node)``: a connection (itself reduced) between
    links ``u`` and ``v``.
    """

    source: str
    target: str
    links: tuple[str, ...]
    edges: tuple[tuple[str, str, "Node"], ...]


Node = Union[JointNode, Series, Parallel, Bridge]


@dataclass(frozen=True)
class Topology:
    """The decomposition of a mechanism's joint graph.

    Attributes
    ----------
    root : Node
        The network between ground and end effector.
    detached : tuple of Node
        Networks (blocks) on no ground-to-end-effector path; they count for
        the mobility only.
    link_count : int
        Number of links, ground included.
    loop_count : int
        Number of independent loops, ``joints - links + 1``.
    structure : str
        :func:`describe` of the root.
    """

    root: Node
    detached: tuple[Node, ...]
    link_count: int
    loop_count: int
    structure: str


@dataclass(frozen=True)
class TreeEdge:
    """A joint of a spanning tree, met going away from the ground.

    ``forward`` is true when the joint is written from ``parent`` to ``child``
    (``links == (parent, child)``), so its twists carry the child's motion
    relative to the parent with a plus sign.
    """

    parent: str
    child: str
    joint: int
    forward: bool


def spanning_tree(mechanism: Mechanism) -> tuple[tuple[TreeEdge, ...], tuple[int, ...]]:
    """A breadth-first spanning tree of the joint graph from the ground, and its chords.

    Several joints between the same two links are a loop: the first one
    written is in the tree, the others are chords.

    Returns
    -------
    tree : tuple of TreeEdge
        In breadth-first order (a parent always comes before its children).
    chords : tuple of int
        Indices of the joints off the tree, in file order; each closes one
        independent loop.

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> R = lambda n, a, b: Joint(n, "R", (a, b), axis=(0, 0, 1), point=(0, 0, 0))
    >>> tree, chords = spanning_tree(Mechanism("m", "g", "e", (R("A", "g", "e"), R("B", "e", "g"))))
    >>> [(t.parent, t.child, t.joint, t.forward) for t in tree], chords
    ([('g', 'e', 0, True)], (1,))
    """
    graph = nx.Graph()
    for index, joint in enumerate(mechanism.joints):
        a, b = joint.links
        if graph.has_edge(a, b):
            graph[a][b]["joints"].append(index)
        else:
            graph.add_edge(a, b, joints=[index])
    tree = []
    for parent, child in nx.bfs_edges(graph, mechanism.ground):
        index = graph[parent][child]["joints"][0]
        tree.append(TreeEdge(parent, child, index, mechanism.joints[index].links == (parent, child)))
    in_tree = {t.joint for t in tree}
    return tuple(tree), tuple(i for i in range(len(mechanism.joints)) if i not in in_tree)


def describe(node: Node) -> str:
    """Write a node as ``parallel(series(P1,R1,S1), ...)``."""
    if isinstance(node, JointNode):
        return node.name
    if isinstance(node, Series):
        return "series(" + ",".join(describe(c) for c in node.children) + ")"
    if isinstance(node, Parallel):
        return "parallel(" + ", ".join(describe(c) for c in node.children) + ")"
    inner = ", ".join(f"{u}-{v}: {describe(n)}" for u, v, n in node.edges)
    return f"bridge({inner})"


def joints_of(node: Node) -> list[int]:
    """Indices of the joints inside a node."""
    if isinstance(node, JointNode):
        return [node.index]
    children = [n for _, _, n in node.edges] if isinstance(node, Bridge) else node.children
    return [i for c in children for i in joints_of(c)]


def _reversed(node: Node) -> Node:
    if isinstance(node, Series):
        return Series(tuple(_reversed(c) for c in reversed(node.children)))
    if isinstance(node, Parallel):
        return Parallel(tuple(_reversed(c) for c in node.children))
    if isinstance(node, Bridge):
        return Bridge(node.target, node.source, node.links, node.edges)
    return node


def decompose(mechanism: Mechanism) -> Topology:
    """Series/parallel decomposition of ``mechanism``'s joint graph (cached by structure)."""
    signature = tuple((j.name, j.links) for j in mechanism.joints)
    return _decompose(signature, mechanism.ground, mechanism.end_effector)


@lru_cache(maxsize=512)
def _decompose(signature: tuple[tuple[str, tuple[str, str]], ...], ground: str, end_effector: str) -> Topology:
    edges = [(a, b, JointNode(i, name)) for i, (name, (a, b)) in enumerate(signature)]
    links = {x for a, b, _ in edges for x in (a, b)}
    blocks = _blocks(edges, ground, end_effector)
    root = None
    detached = []
    for block_edges, is_main in blocks:
        if is_main:
            root = _reduce(block_edges, ground, end_effector)
        else:
            a, b = block_edges[0][0], block_edges[0][1]
            detached.append(_reduce(block_edges, a, b))
    assert root is not None
    return Topology(root, tuple(detached), len(links), len(edges) - len(links) + 1, describe(root))


def _blocks(edges: list[tuple[str, str, JointNode]], s: str, t: str) -> list[tuple[list[tuple[str, str, JointNode]], bool]]:
    """Split the edges by biconnected block of the graph plus a virtual edge s-t."""
    g = nx.Graph()
    g.add_edges_from((a, b) for a, b, _ in edges)
    g.add_edge(s, t)
    block_of: dict[frozenset[str], int] = {}
    main = -1
    for k, block in enumerate(nx.biconnected_component_edges(g)):
        for a, b in block:
            block_of[frozenset((a, b))] = k
            if {a, b} == {s, t}:
                main = k
    grouped: dict[int, list[tuple[str, str, JointNode]]] = defaultdict(list)
    for e in edges:
        grouped[block_of[frozenset(e[:2])]].append(e)
    return [(grouped[k], k == main) for k in sorted(grouped)]


def _reduce(edge_list: list[tuple[str, str, Node]], s: str, t: str) -> Node:
    """Series/parallel reduction of a two-terminal multigraph."""
    edges: dict[int, tuple[str, str, Node]] = dict(enumerate(edge_list))
    incident: dict[str, set[int]] = defaultdict(set)
    for k, (a, b, _) in edges.items():
        incident[a].add(k)
        incident[b].add(k)
    next_id = len(edges)

    def oriented(k: int, start: str) -> Node:
        a, _, n = edges[k]
        return n if a == start else _reversed(n)

    def other(k: int, x: str) -> str:
        a, b, _ = edges[k]
        return b if a == x else a

    def add(a: str, b: str, node: Node) -> None:
        nonlocal next_id
        edges[next_id] = (a, b, node)
        incident[a].add(next_id)
        incident[b].add(next_id)
        next_id += 1

    def remove(k: int) -> None:
        a, b, _ = edges.pop(k)
        incident[a].discard(k)
        incident[b].discard(k)

    changed = True
    while changed:
        changed = False
        pairs: dict[frozenset[str], list[int]] = defaultdict(list)
        for k, (a, b, _) in edges.items():
            pairs[frozenset((a, b))].append(k)
        for ks in pairs.values():
            if len(ks) > 1:
                a = edges[ks[0]][0]
                b = other(ks[0], a)
                children: list[Node] = []
                for k in ks:
                    n = oriented(k, a)
                    children.extend(n.children if isinstance(n, Parallel) else (n,))
                    remove(k)
                add(a, b, Parallel(tuple(children)))
                changed = True
        for x in list(incident):
            if x in (s, t) or len(incident[x]) != 2:
                continue
            k1, k2 = sorted(incident[x])
            a, b = other(k1, x), other(k2, x)
            if a == b:
                continue  # two connections to one link: merged as parallel first
            # keep the order from the side nearer the source when we can tell
            if b == s or a == t:
                k1, k2, a, b = k2, k1, b, a
            parts: list[Node] = []
            for n in (_reversed(oriented(k1, x)), oriented(k2, x)):
                parts.extend(n.children if isinstance(n, Series) else (n,))
            remove(k1)
            remove(k2)
            del incident[x]
            add(a, b, Series(tuple(parts)))
            changed = True
    if len(edges) == 1:
        (k,) = edges
        return oriented(k, s)
    links = tuple(sorted({x for a, b, _ in edges.values() for x in (a, b)}, key=lambda x: (x != s, x != t, x)))
    return Bridge(s, t, links, tuple((a, b, n) for a, b, n in edges.values()))
