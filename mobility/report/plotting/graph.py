"""The picture of a mechanism's joint graph beside the series/parallel tree the analysis reduced it to.

The tree's values are those the analysis found (:attr:`~mobility.core.result.Result.node_systems`):
nothing is evaluated again.
"""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING, Any, Sequence, cast

import numpy as np

from ...core.analysis import analyze
from ...core.model import Mechanism, require_mechanism
from ...core.result import Result, require_same_mechanism
from ...errors import RequestError, counted
from ...core.tolerance import DEFAULT_TOLERANCE, Tolerance, require_tolerance
from ...core.topology import Bridge, JointNode, Node, Parallel, Series, joints_of
from .backend import new_figure, require_figsize, require_matplotlib
from .style import COLORS, LIMB_COLORS, drawn_name

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["plot_graph", "tree_layout", "branch_colors", "LABELLED_JOINTS"]

DETACHED_COLOR = "#9e9e9e"
NODE_FILL = {"joint": "white", "series": "#fff3e0", "parallel": "#e8f5e9", "bridge": "#fce4ec"}

LABELLED_JOINTS = 200
"""Joints up to which every link, joint and tree node is written in a box; a larger graph is drawn
with markers and lines only (one collection per kind: thousands of text boxes take minutes to draw
and cannot be read)."""


def _children(n: Node) -> list[Node]:
    if isinstance(n, JointNode):
        return []
    if isinstance(n, Bridge):
        return [c for _, _, c in n.edges]
    return list(n.children)


def tree_layout(root: Node) -> tuple[dict[int, tuple[float, float]], list[tuple[int, int]], dict[int, Node]]:
    """Positions of a tree's nodes: leaves left to right, each parent above the middle of its children.

    Returns ``id(node) -> (x, y)`` (``y = -depth``), the edges ``(id(parent), id(child))`` and ``id(node) -> node``.

    Examples
    --------
    >>> from mobility.core.topology import JointNode, Series
    >>> root = Series((JointNode(0, "A"), JointNode(1, "B")))
    >>> pos, edges, nodes = tree_layout(root)
    >>> [pos[id(n)] for n in (root, *root.children)]
    [(0.5, -0.0), (0.0, -1.0), (1.0, -1.0)]
    """
    pos: dict[int, tuple[float, float]] = {}
    edges: list[tuple[int, int]] = []
    nodes: dict[int, Node] = {}
    leaves = itertools.count()
    # depth first with an explicit stack (trees of thousands of levels): a node is placed after its children
    stack: list[tuple[Node, int, bool]] = [(root, 0, False)]
    while stack:
        n, depth, children_placed = stack.pop()
        kids = _children(n)
        if not children_placed:
            nodes[id(n)] = n
            if not kids:
                pos[id(n)] = (float(next(leaves)), -float(depth))
                continue
            stack.append((n, depth, True))
            stack.extend((c, depth + 1, False) for c in reversed(kids))
            continue
        xs = [pos[id(c)][0] for c in kids]
        edges.extend((id(n), id(c)) for c in kids)
        pos[id(n)] = (0.5 * (min(xs) + max(xs)), -float(depth))
    return pos, edges, nodes


def branch_colors(root: Node, detached: Sequence[Node]) -> dict[int, str]:
    """Colour of each joint (by index): one per branch of the top node (limb), grey when detached."""
    branches = _children(root) if isinstance(root, (Parallel, Bridge)) else [root]
    out = {i: LIMB_COLORS[k % len(LIMB_COLORS)] for k, b in enumerate(branches) for i in joints_of(b)}
    return out | {i: DETACHED_COLOR for d in detached for i in joints_of(d)}


def plot_graph(mechanism: Mechanism, result: Result | None = None, *, figsize: tuple[float, float] | None = None,
               tol: Tolerance = DEFAULT_TOLERANCE) -> "Figure":
    """Draw the joint graph and the series/parallel tree found by :func:`mobility.core.topology.decompose`.

    Left: links as nodes, joints as edges labelled ``name (type)``, coloured by
    limb. Right: the tree, ``∥`` parallel (twist systems intersect), ``—``
    series (they add), ``⊠`` bridge (loop closure), each labelled with the
    dimension of its twist system (and idle motions). Beyond
    :data:`LABELLED_JOINTS` joints, markers and lines without names.

    ``result``: the analysis at this pose (computed with ``tol`` when not given); ``figsize``: inches,
    each from 1 to 30.  Returns a figure of two axes, ``fig.axes[0]`` the joint graph, ``fig.axes[1]`` the tree.
    Arguments are checked as :func:`~mobility.report.plotting.plot_mechanism` checks them.
    """
    mechanism = require_mechanism(mechanism, "plot_graph")
    tol = require_tolerance(tol, "plot_graph")
    size = require_figsize(figsize, "plot_graph")
    if result is not None:
        _require_result_like(result)
        require_same_mechanism(mechanism, result, "plot_graph")
    require_matplotlib()
    from matplotlib.lines import Line2D

    r = result if result is not None else analyze(mechanism, tol=tol)
    topo = r.topology
    colors = branch_colors(topo.root, topo.detached)
    graph = _JointGraph(mechanism, colors)
    leaves = len(joints_of(topo.root)) + sum(len(joints_of(d)) for d in topo.detached)
    fig = new_figure(size or (max(10.0, min(26.0, 3.2 + 0.55 * max(leaves, 2 * graph.widest_layer))), 6.4))
    labelled = len(mechanism.joints) <= LABELLED_JOINTS
    graph.draw(fig.add_axes((0.01, 0.08, 0.40, 0.82)), labelled)
    _draw_tree(fig.add_axes((0.43, 0.08, 0.56, 0.82)), r, mechanism, colors, labelled)
    handles = [
        Line2D([], [], ls="", marker="o", markersize=9, markerfacecolor="#bdbdbd", markeredgecolor="#37474f", label="ground"),
        Line2D([], [], ls="", marker="o", markersize=9, markerfacecolor="#ffb74d", markeredgecolor="#37474f", label="end effector"),
    ]
    branches = _children(topo.root) if isinstance(topo.root, (Parallel, Bridge)) else [topo.root]
    if len(branches) > 1:
        handles += [Line2D([], [], color=LIMB_COLORS[k % len(LIMB_COLORS)], lw=2.2, label=f"branch {k + 1}") for k in range(min(len(branches), len(LIMB_COLORS)))]
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), frameon=False, fontsize=8)
    unlabelled = "" if labelled else f" (names left out: more than {LABELLED_JOINTS} joints)"
    fig.suptitle(f"{drawn_name(r.name)}: mobility {r.mobility}, end effector {r.dof} DOF ({r.pattern}), {counted(r.loops, 'loop')}{unlabelled}", fontsize=11)
    return fig


_RESULT_FIELDS = ("topology", "node_systems", "name", "mobility", "dof", "pattern", "loops")
"""What :func:`plot_graph` reads of a result."""


def _require_result_like(value: object) -> None:
    """A :class:`RequestError` unless ``value`` is a :class:`Result`, or stands for one (has every field the picture reads).

    Examples
    --------
    >>> _require_result_like(5)
    Traceback (most recent call last):
    mobility.errors.RequestError: plot_graph: result: expected a Result (from mobility.analyze) or None, got int
    """
    if not isinstance(value, Result) and not all(hasattr(value, key) for key in _RESULT_FIELDS):
        raise RequestError(caller="plot_graph", argument="result", expected="a Result (from mobility.analyze) or None", got=type(value).__name__)


class _JointGraph:
    """The joint graph laid out in layers by distance from the ground, and drawn.

    Within a layer: the mean place of a link's neighbours in the layer below
    (barycentre ordering), then its branch (limb), so limbs do not cross.
    """

    def __init__(self, mechanism: Mechanism, colors: dict[int, str]) -> None:
        import networkx as nx

        self.mechanism = mechanism
        self.colors = colors
        g: nx.MultiGraph[str] = nx.MultiGraph()
        g.add_nodes_from(mechanism.links)
        for i, j in enumerate(mechanism.joints):
            g.add_edge(*j.links, key=i, name=j.name)
        self.graph = g
        self.depth = nx.single_source_shortest_path_length(g, mechanism.ground)
        self.layers = self._layers()
        self.pos = nx.multipartite_layout(g, subset_key=self.layers, align="horizontal", scale=1.0)
        self.widest_layer = max(len(members) for members in self.layers.values())

    def _layers(self) -> dict[int, list[str]]:
        m, g, depth, colors = self.mechanism, self.graph, self.depth, self.colors
        branch_of = {c: k for k, c in enumerate(dict.fromkeys(colors[i] for i in sorted(colors)))}

        def branch(x: str) -> int:
            if x in (m.ground, m.end_effector):
                return 0
            return min(branch_of.get(colors.get(k, ""), 99) for _, _, k in g.edges(x, keys=True))

        layers: dict[int, list[str]] = {}  # lists, not sets: the order within a layer is kept
        place: dict[str, float] = {}
        order = {x: k for k, x in enumerate(m.links)}
        by_depth: dict[int, list[str]] = {}
        for x in m.links:
            by_depth.setdefault(depth[x], []).append(x)
        for d in sorted(by_depth):
            members = by_depth[d]

            def key(x: str) -> tuple[float, int, int]:
                below = [place[y] for y in g.neighbors(x) if depth[y] == d - 1]
                return (float(np.mean(below)) if below else 0.0, branch(x), order[x])

            layers[d] = sorted(members, key=key)
            place.update({x: float(k) / max(len(members) - 1, 1) for k, x in enumerate(layers[d])})
        return layers

    def draw(self, ax: Any, labelled: bool = True) -> None:
        """Links as boxed names, joints as lines (arcs between links joined twice), joint labels (without names: markers and lines)."""
        import networkx as nx

        m, g, pos, colors = self.mechanism, self.graph, self.pos, self.colors
        node_color = ["#bdbdbd" if x == m.ground else "#ffb74d" if x == m.end_effector else "#e3f2fd" for x in g.nodes]
        nodes_art = nx.draw_networkx_nodes(g, pos, ax=ax, node_color=node_color, edgecolors="#37474f", node_size=60)
        nodes_art.set_gid("mobility:graph:links")
        if not labelled:
            self._draw_lines(ax)
            return
        for x, fc in zip(g.nodes, node_color):  # each link's name in a box of its role's colour
            nx.draw_networkx_labels(g, pos, labels={x: drawn_name(x)}, ax=ax, font_size=7, bbox={"boxstyle": "round,pad=0.3", "fc": fc, "ec": "#37474f", "lw": 0.8})
        seen: dict[frozenset[str], int] = {}
        for u, v, k, data in g.edges(keys=True, data=True):
            n_same = g.number_of_edges(u, v)
            slot = seen.get(frozenset((u, v)), 0)
            seen[frozenset((u, v))] = slot + 1
            colour = colors.get(k, "#37474f")
            gid = f"mobility:graph:joint:{data['name']}"
            if n_same == 1:  # a plain line: much cheaper than an arrow patch
                ax.plot(*np.stack([pos[u], pos[v]]).T, color=colour, lw=2.2, gid=gid, zorder=1)
                continue
            # joints between the same two links: arcs of different curvature
            style = f"arc3,rad={0.4 * (slot - (n_same - 1) / 2)}"
            arts = nx.draw_networkx_edges(g, pos, edgelist=[(u, v, k)], ax=ax, edge_color=colour, width=2.2, connectionstyle=style, arrows=True, arrowstyle="-", node_size=520)
            for art in arts if isinstance(arts, list) else [arts]:
                art.set_gid(gid)
        label_box = {"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.85}
        for u, v in {frozenset(e[:2]): e[:2] for e in g.edges(keys=True)}.values():
            # joints between the same two links share one label, one line each,
            # near the end in the wider layer, where labels have room
            ks = cast("list[int]", sorted(g[u][v]))  # the edges' keys, joint indices (the stubs type them as nodes)
            text = "\n".join(f"{drawn_name(m.joints[k].name)} ({m.joints[k].type})" for k in ks)
            t = 0.32 if len(self.layers[self.depth[u]]) > len(self.layers[self.depth[v]]) else 0.68
            x, y = (1.0 - t) * np.asarray(pos[u]) + t * np.asarray(pos[v])
            ax.text(x, y, text, fontsize=6.5, color=colors.get(ks[0], "#37474f"), ha="center", va="center", bbox=label_box, zorder=3)
        self._finish(ax)

    def _draw_lines(self, ax: Any) -> None:
        """Every joint as a straight line in its branch's colour, all in one collection."""
        from matplotlib.collections import LineCollection

        m, pos, colors = self.mechanism, self.pos, self.colors
        segments = [np.stack([pos[j.links[0]], pos[j.links[1]]]) for j in m.joints]
        lines = LineCollection(segments, colors=[colors.get(i, "#37474f") for i in range(len(m.joints))], linewidths=1.2, zorder=1)
        lines.set_gid("mobility:graph:joints")
        ax.add_collection(lines)
        self._finish(ax)

    @staticmethod
    def _finish(ax: Any) -> None:
        ax.set_title("joint graph (links = nodes, joints = edges)", fontsize=10)
        ax.set_axis_off()
        ax.margins(0.12)


def _node_label(n: Node, dof: int, idle: int, mechanism: Mechanism) -> tuple[str, str]:
    """The kind of a tree node and its label: the joint's name and type, or the node's kind, dimension and idle count."""
    if isinstance(n, JointNode):
        return "joint", f"{drawn_name(n.name)}\n{mechanism.joints[n.index].type}"
    idle_text = f", idle {idle}" if idle else ""
    kind, mark = ("series", "—") if isinstance(n, Series) else ("parallel", "∥") if isinstance(n, Parallel) else ("bridge", "⊠")
    return kind, f"{mark} {kind}\ndim {dof}{idle_text}"


def _draw_tree(ax: Any, r: Result, mechanism: Mechanism, colors: dict[int, str], labelled: bool = True) -> None:
    """The series/parallel tree (and each detached network's), nodes labelled with what the analysis found there (or markers)."""
    import networkx as nx

    topo, systems = r.topology, r.node_systems
    tree: nx.DiGraph[int] = nx.DiGraph()
    tpos: dict[int, tuple[float, float]] = {}
    tnodes: dict[int, Node] = {}
    offset = 0.0
    for root in (topo.root, *topo.detached):  # side by side
        p, e, nodes = tree_layout(root)
        xs = [x for x, _ in p.values()]
        left, right = min(xs), max(xs)
        tpos.update({key: (x - left + offset, y) for key, (x, y) in p.items()})
        offset += right - left + 2.0
        tree.add_nodes_from(p)
        tree.add_edges_from(e)
        tnodes.update(nodes)
    nx.draw_networkx_edges(tree, tpos, ax=ax, arrows=False, edge_color="#90a4ae", width=1.2)
    if not labelled:
        _tree_markers(ax, tpos, tnodes)
    labels = {key: _node_label(n, *systems[n], mechanism) for key, n in tnodes.items()} if labelled else {}
    for kind in NODE_FILL:  # every node a box of its kind's colour, read back by its gid (drawn kind by kind)
        for key, (node_kind, label) in labels.items():
            if node_kind != kind:
                continue
            n = tnodes[key]
            edge = colors.get(n.index, "#37474f") if isinstance(n, JointNode) else "#546e7a"
            ax.text(*tpos[key], label, ha="center", va="center", fontsize=6.5, gid=f"mobility:tree:{kind}",
                    bbox={"boxstyle": "round,pad=0.45", "fc": NODE_FILL[kind], "ec": edge, "lw": 2.0 if kind == "joint" else 1.0})
    bridge_edges = {(key, id(child)): f"{drawn_name(u)}–{drawn_name(v)}"  # a bridge's connections join named links: say which
                    for key, n in tnodes.items() if labelled and isinstance(n, Bridge) for u, v, child in n.edges}
    if bridge_edges:
        nx.draw_networkx_edge_labels(tree, tpos, edge_labels=bridge_edges, ax=ax, font_size=6, label_pos=0.7, rotate=False, bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none"})
    x0, y0 = tpos[id(topo.root)]
    ax.annotate(f"end effector: {r.dof} DOF ({r.pattern})", (x0, y0), xytext=(0, 26), textcoords="offset points", ha="center", fontsize=9, fontweight="bold", color=COLORS["end_effector"])
    for d in topo.detached:
        x, y = tpos[id(d)]
        ax.annotate("detached", (x, y), xytext=(0, 26), textcoords="offset points", ha="center", fontsize=8, color="#757575")
    ax.set_title("series/parallel tree (dim: DOF between the node's two end links)", fontsize=10)
    ax.set_axis_off()
    ax.margins(0.08, 0.18)


def _tree_markers(ax: Any, tpos: dict[int, tuple[float, float]], tnodes: dict[int, Node]) -> None:
    """Each node of the tree as a marker filled with its kind's colour, one collection per kind (gid ``mobility:tree:<kind>``)."""
    for kind, cls in {"joint": JointNode, "series": Series, "parallel": Parallel, "bridge": Bridge}.items():
        xy = np.array([tpos[key] for key, n in tnodes.items() if type(n) is cls]).reshape(-1, 2)
        if len(xy):
            art = ax.scatter(xy[:, 0], xy[:, 1], s=14, c=NODE_FILL[kind], edgecolors="#546e7a", linewidths=0.6, zorder=3)
            art.set_gid(f"mobility:tree:{kind}")
