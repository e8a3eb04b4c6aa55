"""The joint graph and its series/parallel decomposition between ground and end effector.

Links are nodes and joints edges of a multigraph.  :func:`decompose` merges
**series** (an inner link with exactly two joints) and **parallel** (several
connections between two links) until one connection remains; what does not
reduce (a tie link between two limbs) becomes a :class:`Bridge`, solved by
loop closure.  Coupled joints are never merged: they are direct edges of one
bridge holding the whole graph, with one more equation per coupling.  Blocks
on no ground-to-end-effector path are :attr:`Topology.detached`: they add to
the mobility, not to the end effector's freedom.

Structural (no geometry), cached per graph, linear in the joints up to a
logarithm, and without recursion: a ladder of 2,000 loops nests as deep as it
is long.  :mod:`networkx` is imported only for a graph that does not reduce
whole, or a spanning tree.

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

from dataclasses import dataclass, fields
from functools import lru_cache
from typing import Any, Callable, NamedTuple, Union, final

from .model import Mechanism

__all__ = ["JointNode", "Series", "Parallel", "Bridge", "Node", "Topology", "TreeEdge", "decompose", "describe", "joints_of", "spanning_tree"]


@final  # never subclassed: ``type(n) is JointNode`` (the fast test the evaluation uses) is an isinstance test
@dataclass(frozen=True)
class JointNode:
    """A single joint (by index in :attr:`Mechanism.joints`)."""

    index: int
    name: str


class _Composite:
    """Hashing (once, from the children's), equality and ``repr`` of a composite node without recursion (a 2,000-joint ladder)."""

    def _set_hash(self, value: Any) -> None:
        object.__setattr__(self, "_hash", hash(value))

    def __hash__(self) -> int:
        return self._hash  # type: ignore[attr-defined]

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, _Composite):
            return NotImplemented
        return _same_tree(self, other)  # type: ignore[arg-type]

    def __repr__(self) -> str:
        return _written(self, _repr_parts)  # type: ignore[arg-type]

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:  # rebuilt by the constructor, so the hash is this process's
        return type(self), tuple(getattr(self, f.name) for f in fields(self))  # type: ignore[arg-type]


@dataclass(frozen=True, eq=False, repr=False)
class Series(_Composite):
    """Connections in series, in order from the first terminal to the second."""

    children: tuple["Node", ...]

    def __post_init__(self) -> None:
        self._set_hash(("series", self.children))


@dataclass(frozen=True, eq=False, repr=False)
class Parallel(_Composite):
    """Connections in parallel between the same two links."""

    children: tuple["Node", ...]

    def __post_init__(self) -> None:
        self._set_hash(("parallel", self.children))


@dataclass(frozen=True, eq=False, repr=False)
class Bridge(_Composite):
    """A network that is not series-parallel, between ``source`` and ``target``.

    ``edges`` are ``(u, v, node)``, a reduced connection between links ``u`` and
    ``v``; ``couplings`` are ``(slides, ((edge, coefficient), ...))`` on edge
    positions, ``slides`` true for P joints (:mod:`mobility.core.couplings`).
    """

    source: str
    target: str
    links: tuple[str, ...]
    edges: tuple[tuple[str, str, "Node"], ...]
    couplings: tuple[tuple[bool, tuple[tuple[int, float], ...]], ...] = ()

    def __post_init__(self) -> None:
        self._set_hash(("bridge", self.source, self.target, self.links, self.edges, self.couplings))


Node = Union[JointNode, Series, Parallel, Bridge]


def _children(node: Node) -> tuple[Node, ...]:
    if isinstance(node, (Series, Parallel)):
        return node.children
    if isinstance(node, Bridge):
        return tuple(n for _, _, n in node.edges)
    return ()


def _written(node: Node, parts: Callable[[Node], tuple[str, list[str], str] | str]) -> str:
    """The text of a tree, with an explicit stack and one join (no string is copied once per level).

    ``parts(n)`` is a leaf's text, or ``(opening, texts before each child, closing)``.
    """
    out: list[str] = []
    stack: list[Node | str] = [node]
    while stack:
        item = stack.pop()
        if isinstance(item, str):
            out.append(item)
            continue
        p = parts(item)
        if isinstance(p, str):
            out.append(p)
            continue
        opening, before, closing = p
        out.append(opening)
        stack.append(closing)
        for child, text in reversed(list(zip(_children(item), before))):
            stack.append(child)
            stack.append(text)
    return "".join(out)


def _describe_parts(node: Node) -> tuple[str, list[str], str] | str:
    if isinstance(node, JointNode):
        return node.name
    if isinstance(node, Series):
        return "series(", [""] + [","] * (len(node.children) - 1), ")"
    if isinstance(node, Parallel):
        return "parallel(", [""] + [", "] * (len(node.children) - 1), ")"
    return "bridge(", [("" if i == 0 else ", ") + f"{u}-{v}: " for i, (u, v, _) in enumerate(node.edges)], ")"


def _repr_parts(node: Node) -> tuple[str, list[str], str] | str:
    if isinstance(node, JointNode):
        return repr(node)
    if isinstance(node, Bridge):
        one = "," if len(node.edges) == 1 else ""
        before = [("" if i == 0 else "), ") + f"({u!r}, {v!r}, " for i, (u, v, _) in enumerate(node.edges)]
        coupled = f", couplings={node.couplings!r}" if node.couplings else ""
        return f"Bridge(source={node.source!r}, target={node.target!r}, links={node.links!r}, edges=(", before, f"){one}){coupled})"
    one = "," if len(node.children) == 1 else ""
    return f"{type(node).__name__}(children=(", [""] + [", "] * (len(node.children) - 1), f"{one}))"


def _same_tree(a: Node, b: Node) -> bool:
    stack = [(a, b)]
    while stack:
        x, y = stack.pop()
        if x is y:
            continue
        if type(x) is not type(y) or hash(x) != hash(y):
            return False
        if isinstance(x, JointNode):
            if x != y:
                return False
        elif isinstance(x, Bridge):
            assert isinstance(y, Bridge)  # the same type as x (checked above)
            if (x.source, x.target, x.links, x.couplings) != (y.source, y.target, y.links, y.couplings) or [e[:2] for e in x.edges] != [e[:2] for e in y.edges]:
                return False
            stack.extend(zip((n for _, _, n in x.edges), (n for _, _, n in y.edges)))
        else:
            assert isinstance(y, (Series, Parallel))  # the same type as x (checked above)
            if len(x.children) != len(y.children):
                return False
            stack.extend(zip(x.children, y.children))
    return True


@dataclass(frozen=True)
class Topology:
    """The decomposition of a mechanism's joint graph.

    ``root`` is the network between ground and end effector, ``detached`` the
    blocks on no path between them (they count for the mobility only);
    ``link_count`` includes the ground, ``loop_count`` is ``joints - links + 1``,
    ``structure`` :func:`describe` of the root.
    """

    root: Node
    detached: tuple[Node, ...]
    link_count: int
    loop_count: int
    structure: str


@dataclass(frozen=True)
class TreeEdge:
    """A joint of a spanning tree, met going away from the ground.

    ``forward``: written from ``parent`` to ``child``, its twists carry the
    child's motion relative to the parent with a plus sign.
    """

    parent: str
    child: str
    joint: int
    forward: bool


def spanning_tree(mechanism: Mechanism) -> tuple[tuple[TreeEdge, ...], tuple[int, ...]]:
    """A breadth-first spanning tree of the joint graph from the ground, and its chords.

    The tree is in breadth-first order (parents first); the chords are the
    indices of the other joints, in file order, each closing one loop (of
    several joints between two links the first written is in the tree).

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> R = lambda n, a, b: Joint(n, "R", (a, b), axis=(0, 0, 1), point=(0, 0, 0))
    >>> tree, chords = spanning_tree(Mechanism("m", "g", "e", (R("A", "g", "e"), R("B", "e", "g"))))
    >>> [(t.parent, t.child, t.joint, t.forward) for t in tree], chords
    ([('g', 'e', 0, True)], (1,))
    """
    import networkx as nx  # needed only here and for graphs that do not reduce whole: slow to import

    graph: nx.Graph[str] = nx.Graph()
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
    return _written(node, _describe_parts)


def joints_of(node: Node) -> list[int]:
    """Indices of the joints inside a node, in the order :func:`describe` writes them."""
    out = []
    stack = [node]
    while stack:
        n = stack.pop()
        if isinstance(n, JointNode):
            out.append(n.index)
        else:
            stack.extend(reversed(_children(n)))
    return out


def decompose(mechanism: Mechanism) -> Topology:
    """Series/parallel decomposition of ``mechanism``'s joint graph (cached by structure).

    Examples
    --------
    A gear pair: two wheels on the ground, their rates tied, one bridge.

    >>> from mobility.core.model import Joint, Mechanism
    >>> from mobility.core.couplings import Coupling
    >>> R = lambda n, a, b: Joint(n, "R", (a, b), axis=(0, 0, 1), point=(0, 0, 0))
    >>> t = decompose(Mechanism("gears", "g", "b", (R("A", "g", "a"), R("B", "g", "b")), couplings=(Coupling(("A", "B"), (1, 2)),)))
    >>> t.structure, t.root.couplings
    ('bridge(g-a: A, g-b: B)', ((False, ((0, 1.0), (1, 2.0))),))
    """
    signature = tuple((j.name, j.links) for j in mechanism.joints)
    index = {j.name: i for i, j in enumerate(mechanism.joints)} if mechanism.couplings else {}
    coupled = tuple((mechanism.joints[index[c.joints[0]]].type == "P", tuple((index[n], x) for n, x in c.terms)) for c in mechanism.couplings)
    return _decompose(signature, mechanism.ground, mechanism.end_effector, coupled)


Edge = tuple[str, str, Node]


Coupled = tuple[tuple[bool, tuple[tuple[int, float], ...]], ...]
"""Couplings on joint indices: ``(slides, ((joint, coefficient), ...))`` each."""


@lru_cache(maxsize=512)
def _decompose(signature: tuple[tuple[str, tuple[str, str]], ...], ground: str, end_effector: str, coupled: Coupled = ()) -> Topology:
    edges: list[Edge] = [(a, b, JointNode(i, name)) for i, (name, (a, b)) in enumerate(signature)]
    links = {x for a, b, _ in edges for x in (a, b)}
    if coupled:  # the whole graph, coupled joints kept as edges: one bridge
        frozen = {i for _, terms in coupled for i, _ in terms}
        bridge = _reduce(edges, ground, end_effector, frozen)
        assert isinstance(bridge, Bridge)  # two or more coupled joints stay apart
        position = {n.index: k for k, (_, _, n) in enumerate(bridge.edges) if isinstance(n, JointNode) and n.index in frozen}
        couplings = tuple((slides, tuple((position[i], x) for i, x in terms)) for slides, terms in coupled)
        whole = Bridge(bridge.source, bridge.target, bridge.links, bridge.edges, couplings)
        return Topology(whole, (), len(links), len(edges) - len(links) + 1, describe(whole))
    # A graph that reduces whole is one block with the virtual edge ground-end effector
    # (series and parallel steps keep two terminals), so nothing is detached.
    root: Node | None = _reduce(edges, ground, end_effector)
    detached = []
    if isinstance(root, Bridge):
        root = None
        for block_edges, is_main in _blocks(edges, ground, end_effector):
            if is_main:
                root = _reduce(block_edges, ground, end_effector)
            else:
                detached.append(_reduce(block_edges, block_edges[0][0], block_edges[0][1]))
    assert root is not None
    return Topology(root, tuple(detached), len(links), len(edges) - len(links) + 1, describe(root))


def _blocks(edges: list[Edge], s: str, t: str) -> list[tuple[list[Edge], bool]]:
    """Split the edges by biconnected block of the graph plus a virtual edge s-t."""
    import networkx as nx  # only for graphs that do not reduce whole

    g: nx.Graph[str] = nx.Graph()
    g.add_edges_from((a, b) for a, b, _ in edges)
    g.add_edge(s, t)
    block_of: dict[frozenset[str], int] = {}
    main = -1
    for k, block in enumerate(nx.biconnected_component_edges(g)):
        for a, b in block:
            block_of[frozenset((a, b))] = k
            if {a, b} == {s, t}:
                main = k
    grouped: dict[int, list[Edge]] = {}
    for e in edges:
        grouped.setdefault(block_of[frozenset(e[:2])], []).append(e)
    return [(grouped[k], k == main) for k in sorted(grouped)]


# series/parallel reduction


class _Merged(NamedTuple):
    """A connection merged from ``parts`` (``kind`` ``"S"`` or ``"P"``), built into a node at the end.

    ``parts`` are ``(part, flipped)``: a :class:`JointNode` or another
    ``_Merged``, and whether it runs against this connection's direction.
    """

    kind: str
    parts: list[tuple[Any, bool]]


def _spliced(kind: str, item: _Merged, flipped: bool) -> list[tuple[Any, bool]]:
    """The parts of ``item`` with the parts of every nested merge of the same kind spliced in, in order."""
    out = []
    stack = [(item, flipped)]
    while stack:
        part, flip = stack.pop()
        if isinstance(part, _Merged) and part.kind == kind:
            seq = [(p, f != flip) for p, f in part.parts]
            if flip and kind == "S":  # a series run backwards: its parts in reverse order
                seq.reverse()
            stack.extend(reversed(seq))
        else:
            out.append((part, flip))
    return out


def _built(item: Any, flipped: bool) -> Node:
    """The node of a connection: series inside series (parallel inside parallel) spliced, orientation applied."""
    results: list[Node] = []
    stack: list[tuple[Any, bool, int]] = [(item, flipped, -1)]  # count >= 0: build from the last `count` results
    while stack:
        part, flip, count = stack.pop()
        if count >= 0:
            children = tuple(results[len(results) - count :])
            del results[len(results) - count :]
            results.append(Series(children) if part.kind == "S" else Parallel(children))
        elif isinstance(part, _Merged):
            parts = _spliced(part.kind, part, flip)
            stack.append((part, flip, len(parts)))
            stack.extend((p, f, -1) for p, f in reversed(parts))
        else:
            results.append(part)  # a joint reads the same both ways
    return results[0]


def _reduce(edge_list: list[Edge], s: str, t: str, frozen: frozenset[int] | set[int] = frozenset()) -> Node:
    """Series/parallel reduction of a two-terminal multigraph.

    Repeated passes merge every parallel group (in the order of its first
    connection), then every inner link of two connections (in order of first
    appearance); each pass visits only what it merges, so the reduction is
    linear up to the sorting.  Edges at positions ``frozen`` are never merged.
    """
    edges: dict[int, tuple[str, str, Any]] = dict(enumerate(edge_list))
    order: dict[str, int] = {}
    incident: dict[str, set[int]] = {}
    pairs: dict[frozenset[str], dict[int, None]] = {}
    for k, (a, b, _) in edges.items():
        for x in (a, b):
            if x not in order:
                order[x] = len(order)
                incident[x] = set()
            incident[x].add(k)
        if k not in frozen:
            pairs.setdefault(frozenset((a, b)), {})[k] = None
    multiple = {key for key, ks in pairs.items() if len(ks) > 1}
    two = {x for x, ks in incident.items() if len(ks) == 2 and x != s and x != t}
    next_id = len(edges)

    def degree_changed(x: str) -> None:
        if len(incident[x]) == 2 and x != s and x != t:
            two.add(x)
        else:
            two.discard(x)

    def add(a: str, b: str, item: Any) -> None:
        nonlocal next_id
        edges[next_id] = (a, b, item)
        for x in (a, b):
            incident[x].add(next_id)
            degree_changed(x)
        key = frozenset((a, b))
        group = pairs.setdefault(key, {})
        group[next_id] = None
        if len(group) > 1:
            multiple.add(key)
        next_id += 1

    def remove(k: int) -> None:
        a, b, _ = edges.pop(k)
        for x in (a, b):
            incident[x].discard(k)
            degree_changed(x)
        key = frozenset((a, b))
        group = pairs[key]
        del group[k]
        if len(group) < 2:
            multiple.discard(key)

    def other(k: int, x: str) -> str:
        a, b, _ = edges[k]
        return b if a == x else a

    changed = True
    while changed:
        changed = False
        for key in sorted(multiple, key=lambda key: next(iter(pairs[key]))):
            ks = list(pairs[key])
            a = edges[ks[0]][0]
            b = other(ks[0], a)
            parts = [(edges[k][2], edges[k][0] != a) for k in ks]
            for k in ks:
                remove(k)
            add(a, b, _Merged("P", parts))
            changed = True
        for x in sorted(two, key=order.__getitem__):
            k1, k2 = sorted(incident[x])
            a, b = other(k1, x), other(k2, x)
            if a == b or k1 in frozen or k2 in frozen:
                continue  # two connections to one link: merged as parallel first
            # keep the order from the side nearer the source when we can tell
            if b == s or a == t:
                k1, k2, a, b = k2, k1, b, a
            first = (edges[k1][2], edges[k1][0] == x)  # k1 run from a to x
            second = (edges[k2][2], edges[k2][0] != x)  # k2 run from x to b
            remove(k1)
            remove(k2)
            del incident[x]
            two.discard(x)
            add(a, b, _Merged("S", [first, second]))
            changed = True
    if len(edges) == 1:
        ((a, _, item),) = edges.values()
        return _built(item, a != s)
    links = tuple(sorted({x for a, b, _ in edges.values() for x in (a, b)}, key=lambda x: (x != s, x != t, x)))
    return Bridge(s, t, links, tuple((a, b, _built(item, False)) for a, b, item in edges.values()))
