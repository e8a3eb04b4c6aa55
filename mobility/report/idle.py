"""What the idle freedoms of a mechanism are, in words: the hint after ``idle DOF`` in the text report.

An idle freedom moves joints and leaves the end effector still: an **S–S rod**
(or S–P–S leg) spinning about its centres' line, a *self-motion* of a serial
chain with more freedoms than DOF, a **chain off the path** moving alone, or
joints inside the loops moving against each other.

Examples
--------
>>> import mobility
>>> idle_hint(mobility.analyze(mobility.load("mechanisms/rssr.yaml")))
'e.g. the spin of an S–S rod about the line through its two centres: 1 such rod here'
"""

from __future__ import annotations

import math
from collections import defaultdict

from ..core.model import Mechanism
from ..core.result import Result
from ..core.tolerance import DEFAULT_TOLERANCE
from ..core.topology import JointNode, Node, Series, joints_of

__all__ = ["spherical_chains", "idle_hint"]


def spherical_chains(mechanism: Mechanism) -> int:
    """The number of chains of links between two spherical joints whose every link carries just those two joints.

    Each (an S–S rod, an S–P–S leg...) spins about its centres' line: one idle
    freedom. The ground and the end effector never belong to one.

    Examples
    --------
    >>> import mobility
    >>> spherical_chains(mobility.load("mechanisms/6sps.yaml")), spherical_chains(mobility.load("mechanisms/3rps.yaml"))
    (6, 0)
    """
    return len(_chain_ends(mechanism))


def _chain_ends(mechanism: Mechanism) -> dict[frozenset[str], tuple[int, int]]:
    """Each chain of :func:`spherical_chains` (its links) with its two spherical joints."""
    joints = mechanism.joints
    at: dict[str, list[int]] = defaultdict(list)
    for i, j in enumerate(joints):
        for link in set(j.links):
            at[link].append(i)
    ends = {mechanism.ground, mechanism.end_effector}
    found: dict[frozenset[str], tuple[int, int]] = {}
    for i, j in enumerate(joints):
        if j.type != "S" or j.links[0] == j.links[1]:
            continue
        for link in j.links:
            came, chain = i, []
            while link not in ends and len(at[link]) == 2 and link not in chain:
                chain.append(link)
                nxt = at[link][0] if at[link][1] == came else at[link][1]
                a, b = joints[nxt].links
                if joints[nxt].type == "S":
                    found.setdefault(frozenset(chain), (i, nxt))
                    break
                came, link = nxt, (b if a == link else a)
    return found


def _serial(node: Node) -> bool:
    """Whether ``node`` is one joint or joints in series (no loop)."""
    return isinstance(node, JointNode) or (isinstance(node, Series) and all(isinstance(c, JointNode) for c in node.children))


def idle_hint(result: Result) -> str:
    """The words after the count of idle freedoms: which motions of this mechanism they are.

    From the tree the result carries (:attr:`~mobility.core.result.Result.node_systems`; without it, no example).

    Examples
    --------
    >>> import mobility
    >>> from mobility.core.model import Joint, Mechanism
    >>> arm = Mechanism("planar 3R arm", "g", "e", tuple(
    ...     Joint(f"J{k}", "R", (("g", "a", "b")[k], ("a", "b", "e")[k]), axis=(0, 0, 1), point=(k, 0, 0)) for k in range(3)))
    >>> idle_hint(mobility.analyze(arm))
    'a self-motion of the serial chain, redundant at this pose: its 3 joint freedoms give the end effector 2 DOF'
    """
    detail = result.detail
    mechanism = getattr(detail, "mechanism", None)
    topology = getattr(detail, "topology", None)
    if mechanism is None or topology is None:
        return "joints move while the end effector stays still"
    ends = _chain_ends(mechanism).values()
    world = mechanism.world_joints
    scale = getattr(detail, "tol", DEFAULT_TOLERANCE).rank * result.length_scale  # the rank policy's "same point", in the file's unit
    pinned = sum(1 for a, b in ends if math.dist(world[a].point, world[b].point) <= scale)  # a link held by two S at one point turns freely
    rods = len(ends) - pinned
    if rods:
        return f"e.g. the spin of an S–S rod about the line through its two centres: {rods} such rod{'s' if rods > 1 else ''} here"
    if pinned:
        return f"a link held by two spherical joints at one point turns freely about it: {pinned} such link{'s' if pinned > 1 else ''} here"
    systems = result.node_systems
    hints = []
    root = systems[topology.root]
    if root.idle:
        if _serial(topology.root):
            hints.append(f"a self-motion of the serial chain, redundant at this pose: its {root.mobility} joint freedoms give the end effector {root.dof} DOF")
        else:
            hints.append("joints inside the loops move against each other")
    moving = [n for n in topology.detached if systems[n].mobility]
    if moving:
        names = [mechanism.joints[k].name for n in moving for k in joints_of(n)]
        shown = ", ".join(names[:4]) + (", ..." if len(names) > 4 else "")
        hints.append(f"a chain off the path from ground to end effector moves alone ({shown})")
    return "; ".join(hints) or "joints move while the end effector stays still"
