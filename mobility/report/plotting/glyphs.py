"""Drawing primitives of the 3D pictures (matplotlib): arrows, rotation marks, links, joint symbols, the axes triad.

Every artist carries a ``gid`` (``"mobility:joints:<type>"``, ``"<gid>:head"`` for an arrowhead...).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ...core.model import Mechanism
from .geometry import SAME_POINT, arc, helix, perpendiculars, plate_ring, unique_points
from .sketch import Sketch
from .style import COLORS, JOINT_STYLE, drawn_name
from .views import view_axes

__all__ = ["cone", "arrow", "rotation_mark", "link_shape", "draw_link", "draw_links", "joint_scale", "draw_joints", "triad", "LINK_WIDTHS", "LINK_ARTISTS", "ROOMY_JOINTS"]
LINK_WIDTHS = {"ground": 4.0, "end_effector": 3.0, "link": 2.6}
"""Line width of a link by its role (points)."""

ROOMY_JOINTS = 100
"""Joints drawn at full symbol size at most (:func:`joint_scale`)."""

LINK_ARTISTS = 200
"""Links drawn one artist each at most; more are drawn one collection per role (:func:`draw_links`)."""


def cone(ax: Any, tip: np.ndarray, direction: np.ndarray, length: float, color: str, gid: str) -> None:
    """A solid arrowhead with its tip at ``tip`` pointing along ``direction``."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    d = direction / np.linalg.norm(direction)
    e1, e2 = perpendiculars(d)
    base = tip - length * d
    ring = [base + 0.35 * length * (math.cos(t) * e1 + math.sin(t) * e2) for t in np.linspace(0, 2 * math.pi, 9)[:-1]]
    faces = [[tip, ring[k], ring[(k + 1) % len(ring)]] for k in range(len(ring))]
    poly = Poly3DCollection(faces, facecolor=color, edgecolor=color, linewidth=0.3)
    poly.set_gid(gid)
    ax.add_collection3d(poly)


def arrow(ax: Any, start: np.ndarray, end: np.ndarray, color: str, gid: str, *, head: float, both: bool = False, **kw: Any) -> None:
    """An arrow from ``start`` to ``end``: a shaft (``Line3D`` with ``gid``) and one or two heads."""
    d = end - start
    ax.plot(*np.stack([start, end]).T, color=color, gid=gid, solid_capstyle="butt", **kw)
    cone(ax, end, d, head, color, gid + ":head")
    if both:
        cone(ax, end - 1.6 * head * d / np.linalg.norm(d), d, head, color, gid + ":head2")


def rotation_mark(ax: Any, centre: np.ndarray, axis: np.ndarray, radius: float, color: str, gid: str) -> None:
    """A circular arrow around ``axis`` at ``centre`` (right-hand sense)."""
    points, tangent = arc(centre, axis, radius, samples=40)
    ax.plot(*points.T, color=color, lw=1.6, gid=gid)
    cone(ax, points[-1] + 0.35 * radius * tangent, tangent, 0.6 * radius, color, gid + ":head")


def link_shape(pts: np.ndarray, size: float) -> tuple[str, np.ndarray, list[np.ndarray]]:
    """How a link over the joint places ``pts`` is drawn: ``(kind, ring, segments)``.

    ``kind`` is ``"none"`` (fewer than two distinct places), ``"bar"`` (two),
    ``"plate"`` (three or more, nearly coplanar and not collinear: ``ring`` is
    the convex outline, ``segments`` the spokes to the joints inside it) or
    ``"star"`` (segments from the centroid to every place: a thin 3D body).
    """
    u = unique_points(pts, SAME_POINT * size)
    if len(u) < 2:
        return "none", np.zeros((0, 3)), []
    if len(u) == 2:
        return "bar", np.zeros((0, 3)), [u]
    c = u.mean(axis=0)
    ring = plate_ring(u)
    if ring is not None:
        return "plate", u[ring], [np.stack([c, u[k]]) for k in range(len(u)) if k not in ring]
    return "star", np.zeros((0, 3)), [np.stack([c, x]) for x in u]


def draw_link(ax: Any, name: str, pts: np.ndarray, role: str, size: float) -> None:
    """A link as a thin body: a bar between two joints, a plate over three or more."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    color = COLORS.get(role, COLORS["link"])
    lw = LINK_WIDTHS.get(role, LINK_WIDTHS["link"])
    gid = f"mobility:link:{name}"
    kind, ring, segments = link_shape(pts, size)
    if kind == "bar":
        ax.plot(*segments[0].T, color=color, lw=lw, gid=gid, solid_capstyle="round")
    elif kind == "plate":
        poly = Poly3DCollection([ring], facecolor=color, alpha=0.22 if role != "link" else 0.15, edgecolor=color, linewidth=lw * 0.6)
        poly.set_gid(gid)
        ax.add_collection3d(poly)
        for seg in segments:
            ax.plot(*seg.T, color=color, lw=lw * 0.6, gid=gid + ":spoke")
    elif kind == "star":
        for k, seg in enumerate(segments):
            ax.plot(*seg.T, color=color, lw=lw, gid=gid if k == 0 else gid + ":spoke", solid_capstyle="round")


def draw_links(ax: Any, mechanism: Mechanism, sk: Sketch) -> None:
    """Every link by :func:`draw_link`; beyond :data:`LINK_ARTISTS` links (a millisecond per artist and view), one collection per role.

    Their gids: ``mobility:links:<role>`` and ``mobility:links:<role>:plates``.
    """
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    def role_of(link: str) -> str:
        return "ground" if link == mechanism.ground else "end_effector" if link == mechanism.end_effector else "link"

    if len(sk.link_joints) <= LINK_ARTISTS:
        for link, idx in sk.link_joints.items():
            draw_link(ax, link, sk.points[list(idx)], role_of(link), sk.size)
        return
    lines: dict[str, list[np.ndarray]] = {}
    plates: dict[str, list[np.ndarray]] = {}
    for link, idx in sk.link_joints.items():
        kind, ring, segments = link_shape(sk.points[list(idx)], sk.size)
        lines.setdefault(role_of(link), []).extend(segments)
        if kind == "plate":
            plates.setdefault(role_of(link), []).append(ring)
    for role, rings in plates.items():
        color = COLORS.get(role, COLORS["link"])
        poly = Poly3DCollection(rings, facecolor=color, alpha=0.22 if role != "link" else 0.15, edgecolor=color, linewidth=LINK_WIDTHS[role] * 0.6)
        poly.set_gid(f"mobility:links:{role}:plates")
        ax.add_collection3d(poly)
    for role, segments in lines.items():
        if not segments:
            continue
        coll = Line3DCollection(segments, colors=COLORS.get(role, COLORS["link"]), linewidths=LINK_WIDTHS[role], capstyle="round")
        coll.set_gid(f"mobility:links:{role}")
        ax.add_collection3d(coll)


def joint_scale(count: int) -> float:
    """The factor on the size of joint symbols among ``count`` joints: 1 up to :data:`ROOMY_JOINTS`, then ``sqrt(ROOMY_JOINTS / count)``.

    Examples
    --------
    >>> joint_scale(9), joint_scale(400)
    (1.0, 0.5)
    """
    return min(1.0, math.sqrt(ROOMY_JOINTS / max(count, 1)))


def draw_joints(ax: Any, m: Mechanism, sk: Sketch, labels: bool, view: tuple[float, float]) -> None:
    """One scatter per joint type (smaller beyond :data:`ROOMY_JOINTS` joints), axis segments, names beside the joints as ``view`` shows them."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    joints = m.world_joints
    crowd = joint_scale(len(joints))
    size = sk.size * crowd  # the axis segments: shorter among many joints
    for t, style in JOINT_STYLE.items():
        idx = [i for i, jt in enumerate(sk.types) if jt == t]
        if not idx:
            continue
        p = sk.points[idx]
        edge = "white" if t == "S" else "black"
        ax.scatter(*p.T, marker=style["marker"], s=style["s"] * crowd, facecolors=style["facecolor"], edgecolors=edge, linewidths=crowd, depthshade=False, zorder=5, gid=f"mobility:joints:{t}")
    # the small axis segments of every joint in two collections (thin axes, thick rails): one artist each
    axes_segs: list[np.ndarray] = []
    rails: list[np.ndarray] = []
    for i, j in enumerate(joints):
        x = sk.points[i]
        if j.type in ("R", "H", "C"):
            a = np.asarray(j.axis)
            axes_segs.append(np.stack([x - 0.06 * size * a, x + 0.06 * size * a]))
        if j.type in ("P", "C"):
            a = np.asarray(j.axis)
            rails.append(np.stack([x - 0.07 * size * a, x + 0.07 * size * a]))
        if j.type == "H":
            axes_segs.append(helix(x, np.asarray(j.axis), 0.025 * size, 0.1 * size))
        if j.type == "U":
            assert j.axes is not None  # a U joint has its two axes
            axes_segs += [np.stack([x - 0.06 * size * np.asarray(a), x + 0.06 * size * np.asarray(a)]) for a in j.axes]
        if j.type == "E":
            e1, e2 = perpendiculars(np.asarray(j.normal))
            axes_segs.append(np.array([x + 0.05 * size * (s1 * e1 + s2 * e2) for s1, s2 in ((1, 1), (-1, 1), (-1, -1), (1, -1), (1, 1))]))
    if axes_segs:
        coll = Line3DCollection(axes_segs, colors="black", linewidths=1.1 * crowd)
        coll.set_gid("mobility:joint-axes")
        ax.add_collection3d(coll)
    if rails:
        coll = Line3DCollection(rails, colors="#b8860b", linewidths=5.0 * crowd, alpha=0.55, capstyle="butt")
        coll.set_gid("mobility:joint-rails")
        ax.add_collection3d(coll)
    if labels and len(joints) <= 40:
        _, sx, sy = view_axes(*view)
        off = 0.03 * size * (0.8 * sx + 0.6 * sy)  # up and to the right on the screen, whatever the view
        for i, name in enumerate(sk.names):
            ax.text(*(sk.points[i] + off), drawn_name(name), fontsize=6.5, color="#263238", gid=f"mobility:joint-label:{name}", zorder=1e4)


def triad(ax: Any, elev: float, azim: float) -> None:
    """The global x, y, z directions as seen in this view, drawn flat in the lower left corner."""
    _, sx, sy = view_axes(elev, azim)
    origin = np.array([0.07, 0.07])
    for e, lab in zip(np.eye(3), "xyz"):
        tip = origin + 0.07 * np.array([e @ sx, e @ sy])
        ax.annotate("", xy=tuple(tip), xytext=tuple(origin), xycoords="axes fraction",
                    arrowprops={"arrowstyle": "-|>", "color": "#78909c", "lw": 1.0, "shrinkA": 0, "shrinkB": 0}, gid=f"mobility:triad:{lab}")
        if np.hypot(e @ sx, e @ sy) > 0.15:
            label = origin + 0.095 * np.array([e @ sx, e @ sy])
            ax.text2D(label[0], label[1], lab, transform=ax.transAxes, fontsize=7.5, color="#546e7a", ha="center", va="center")
