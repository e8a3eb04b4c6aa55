"""Pictures: a mechanism at its pose with its freedoms and constraints, and its joint graph.

:func:`plot_mechanism` draws the mechanism in 3D (links as thin bodies between
their joints, one symbol per joint type, the ground and the end effector
marked) and, on the end effector, the answer of :func:`mobility.analyze`:
arrows for the translations, axis lines with a rotation mark for the
rotations (the pitch written where it is not zero) and, on request, the
constraint wrenches (force lines, couples).  It shows the scene from two
viewpoints chosen by :func:`choose_views` so that no two important points fall
on each other and no freedom is seen end-on.

:func:`plot_graph` draws the joint graph (links as nodes, joints as edges, each
limb in its own colour) beside the series/parallel tree that the analysis
reduces it to, every node of the tree labelled with the dimension of its twist
system, so one can see why the answer is what it is.

matplotlib is optional (``pip install 'mobility[plot]'``): it is imported only
when a picture is drawn, and :class:`PlottingUnavailableError` says how to get
it when it is missing.  Figures are built without :mod:`matplotlib.pyplot`
(no global state); show one in a notebook by leaving it as the cell's value,
or save it with :func:`save_figure`.

Every drawn answer carries a ``gid`` (``"mobility:translation:0"``,
``"mobility:rotation-axis:1"``, ``"mobility:force:0"``, ``"mobility:couple:0"``,
``"mobility:link:<name>"``, ``"mobility:joints:<type>"``, ...), so programs and
tests can read the picture back.

The geometry of the drawing (where each joint is drawn, the size of the
scene) is computed without matplotlib by :func:`sketch`; a prismatic joint (or
a planar joint without a point) has no location in the file, so it is drawn
between the located joints of its two links, or beside the one it has.

Examples
--------
>>> import mobility
>>> from mobility.report.plotting import sketch
>>> m = mobility.loads('''
... name: R-P arm
... ground: g
... end_effector: hand
... joints:
...   - {name: R1, type: R, links: [g, arm], axis: [0, 0, 1], point: [0, 0, 0]}
...   - {name: P1, type: P, links: [arm, hand], axis: [1, 0, 0]}
...   - {name: R2, type: R, links: [hand, tool], axis: [1, 0, 0], point: [2, 0, 0]}
... ''')
>>> s = sketch(m)
>>> s.points[s.names.index("P1")].tolist()   # midway between R1 and R2
[1.0, 0.0, 0.0]
"""

from __future__ import annotations

import itertools
import math
import textwrap
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from ..errors import PlotFormatError, PlottingUnavailableError
from ..core.joint_screws import joint_screws
from ..core.model import Mechanism
from ..core.result import Result
from ..core.screw_systems import SystemValue, evaluate
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance
from ..core.topology import Bridge, JointNode, Node, Parallel, Series, decompose, joints_of

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = [
    "Sketch",
    "sketch",
    "choose_views",
    "plot_mechanism",
    "plot_graph",
    "save_figure",
    "FORMATS",
]

FORMATS = (".png", ".svg", ".pdf")
"""File types :func:`save_figure` writes (by suffix)."""



def _matplotlib() -> Any:
    """Import matplotlib (and the 3D toolkit) or raise :class:`PlottingUnavailableError`."""
    try:
        import matplotlib
        import matplotlib.figure  # noqa: F401
        from mpl_toolkits.mplot3d import Axes3D  # noqa: F401  (registers the 3d projection)
    except ImportError as exc:
        missing = exc.name or ""
        raise PlottingUnavailableError("" if missing.split(".")[0] == "matplotlib" else f"missing module {missing!r}") from None
    return matplotlib


_FIGURE_CLASS: list[type] = []


def _figure_class() -> type:
    """A :class:`matplotlib.figure.Figure` that shows itself in Jupyter (made on first use).

    The figures are built without :mod:`matplotlib.pyplot`, so no backend
    registers a display hook for them; ``_repr_png_`` lets IPython show one
    left as a cell's value whatever the backend.
    """
    if not _FIGURE_CLASS:
        from matplotlib.figure import Figure

        class MobilityFigure(Figure):
            """A figure of :mod:`mobility.report.plotting`; displays itself as PNG in Jupyter."""

            def _repr_png_(self) -> bytes:
                import io

                buf = io.BytesIO()
                self.savefig(buf, format="png", dpi=90, facecolor="white")
                return buf.getvalue()

        _FIGURE_CLASS.append(MobilityFigure)
    return _FIGURE_CLASS[0]


# ---------------------------------------------------------------------------
# geometry of the drawing (no matplotlib)


@dataclass(frozen=True, eq=False)
class Sketch:
    """Where each joint is drawn, and the size of the scene.

    Attributes
    ----------
    names, types : tuple of str
        Joint names and types, in the mechanism's order.
    points : ndarray, shape (J, 3)
        Drawn location of each joint (global frame).
    located : ndarray of bool, shape (J,)
        True where the location comes from the file (``point``); false for a
        placed prismatic or planar joint.
    link_joints : dict
        Link name -> indices of its joints.
    centre : ndarray, shape (3,)
        Centre of the drawn joints.
    size : float
        Extent of the scene (largest side of the joints' bounding box, or the
        mechanism's characteristic length when the joints do not spread).
    end_effector_centre : ndarray, shape (3,)
        Centroid of the located joints of the end effector (where its freedoms
        are drawn); the drawn joints when none is located.
    """

    names: tuple[str, ...]
    types: tuple[str, ...]
    points: np.ndarray
    located: np.ndarray
    link_joints: dict[str, tuple[int, ...]]
    centre: np.ndarray
    size: float
    end_effector_centre: np.ndarray


def sketch(mechanism: Mechanism) -> Sketch:
    """Compute where each joint of ``mechanism`` is drawn.

    A joint without a point (prismatic, or planar without ``point``) is drawn
    midway between the located joints of its two links; when only one of its
    links has located joints, a quarter of the scene away from them along its
    axis, on the side away from the end effector; when neither has, after the
    others are placed, from those.

    Parameters
    ----------
    mechanism : Mechanism

    Returns
    -------
    Sketch
    """
    joints = mechanism.world_joints
    n = len(joints)
    pts = np.zeros((n, 3))
    located = np.array([j.point is not None for j in joints])
    for i, j in enumerate(joints):
        if j.point is not None:
            pts[i] = j.point
    link_joints: dict[str, list[int]] = {}
    for i, j in enumerate(joints):
        for x in j.links:
            link_joints.setdefault(x, []).append(i)
    norm = joint_screws(mechanism).normalisation
    if located.any():
        lp = pts[located]
        size = float(np.max(np.ptp(lp, axis=0)))
        centre = lp.mean(axis=0)
    else:
        size, centre = 0.0, np.zeros(3)
    if size <= 1e-9 * max(norm.length, 1e-300):
        size = 2.0 * norm.length if norm.length > 0 else 1.0
    ee = [i for i in link_joints[mechanism.end_effector] if located[i]]
    ee_centre = pts[ee].mean(axis=0) if ee else centre

    placed = located.copy()

    def anchors(i: int, link: str, usable: np.ndarray) -> np.ndarray | None:
        idx = [k for k in link_joints[link] if k != i and usable[k]]
        return pts[idx].mean(axis=0) if idx else None

    for usable_from_placed in (False, True):
        for i, j in enumerate(joints):
            if placed[i]:
                continue
            usable = placed if usable_from_placed else located
            a = anchors(i, j.links[0], usable)
            b = anchors(i, j.links[1], usable)
            if a is not None and b is not None:
                pts[i] = 0.5 * (a + b)
            elif a is not None or b is not None:
                x = a if a is not None else b
                direction = np.asarray(j.axis if j.axis is not None else (0.0, 0.0, 0.0), dtype=float)
                away = x - ee_centre
                if np.linalg.norm(away) < 1e-9 * size:
                    away = x - centre
                if direction @ away < 0:
                    direction = -direction
                pts[i] = x + 0.25 * size * direction
            elif usable_from_placed:
                pts[i] = centre
            else:
                continue
            placed[i] = True
    if not located.any():
        centre = pts.mean(axis=0)
        ee_centre = pts[link_joints[mechanism.end_effector]].mean(axis=0)
        spread = float(np.max(np.ptp(pts, axis=0)))
        size = spread if spread > 0 else size
    for arr in (pts, located):
        arr.setflags(write=False)
    return Sketch(
        tuple(j.name for j in joints),
        tuple(j.type for j in joints),
        pts,
        located,
        {k: tuple(v) for k, v in link_joints.items()},
        centre,
        size,
        ee_centre,
    )


def _view_axes(elev: Any, azim: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Eye direction and screen x, y of orthographic views (matplotlib's elev/azim, degrees).

    Scalars give 3-vectors; arrays of ``n`` views give arrays of shape (n, 3).
    """
    e, a = np.radians(elev), np.radians(azim)
    eye = np.stack([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)], axis=-1)
    sx = np.stack([-np.sin(a), np.cos(a), np.zeros_like(a)], axis=-1)
    return eye, sx, np.cross(eye, sx)


def _view_scores(elev: np.ndarray, azim: np.ndarray, points: np.ndarray, directions: np.ndarray, size: float) -> np.ndarray:
    """Badness of each view: important points on top of each other, directions seen end-on."""
    eye, sx, sy = _view_axes(elev, azim)
    bad = 0.008 * np.abs(elev - 25.0)  # a mild preference for a usual look
    if len(points) > 1:
        i, j = np.triu_indices(len(points), 1)
        d = points[i] - points[j]
        d3 = np.linalg.norm(d, axis=1)
        keep = d3 > 0.03 * size
        if keep.any():
            d = d[keep]
            d3 = d3[keep, None]
            d2 = np.hypot(d @ sx.T, d @ sy.T)  # (pairs, views)
            bad = bad + np.sum(d2 < 0.04 * size, axis=0)  # points drawn on top of each other
            bad = bad + np.sum(np.exp(-((d2 / (0.08 * size)) ** 2)) * (d2 < 0.5 * d3), axis=0)
            bad = bad + 6.0 * (1.0 - np.mean(d2 / d3, axis=0))  # foreshortening: a flat scene seen edge-on
    if len(directions):
        seen = np.sqrt(np.maximum(0.0, 1.0 - (directions @ eye.T) ** 2))  # (directions, views)
        bad = bad + 4.0 * np.sum(seen < 0.35, axis=0) + np.sum(np.maximum(0.0, 0.6 - seen), axis=0)
    return bad


def choose_views(points: np.ndarray, directions: np.ndarray, size: float, count: int = 2, *, separation: float = 60.0) -> list[tuple[float, float]]:
    """Viewpoints ``(elev, azim)`` in degrees where nothing important overlaps.

    Every candidate view on a grid is scored by the pairs of ``points`` that
    fall within 4 % of ``size`` of each other on the screen (and softly by
    pairs brought close), and by the ``directions`` seen nearly end-on.  The
    best view comes first; each next one is the best at least ``separation``
    degrees away from those chosen.

    Parameters
    ----------
    points : ndarray, shape (n, 3)
    directions : ndarray, shape (k, 3)
        Unit directions that must show their length (arrows, axes).
    size : float
        Extent of the scene.
    count : int
        Number of views.
    separation : float
        Smallest angle between two chosen view directions, degrees.

    Returns
    -------
    list of (elev, azim)

    Examples
    --------
    >>> import numpy as np
    >>> # a vertical axis must not be seen from above
    >>> elev, azim = choose_views(np.zeros((1, 3)), np.array([[0.0, 0, 1]]), 1.0, count=1)[0]
    >>> elev < 60
    True
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    directions = np.asarray(directions, dtype=float).reshape(-1, 3)
    elev, azim = (g.ravel().astype(float) for g in np.meshgrid([10, 20, 30, 40, 55, 70, 85], np.arange(0, 360, 10), indexing="ij"))
    scores = np.round(_view_scores(elev, azim, points, directions, size), 9)
    eyes = _view_axes(elev, azim)[0]
    chosen: list[int] = []
    cos_sep = math.cos(math.radians(separation))
    for k in np.lexsort((azim, elev, scores)):  # best first; ties to the lower view, then smaller azimuth
        if all(eyes[k] @ eyes[c] < cos_sep for c in chosen):
            chosen.append(int(k))
            if len(chosen) == count:
                break
    return [(float(elev[k]), float(azim[k])) for k in chosen]


# ---------------------------------------------------------------------------
# drawing primitives (3D)

JOINT_STYLE = {
    "R": {"marker": "o", "s": 46, "facecolor": "white", "label": "R revolute"},
    "P": {"marker": "s", "s": 46, "facecolor": "#ffe08a", "label": "P prismatic"},
    "H": {"marker": "8", "s": 52, "facecolor": "#c8e6c9", "label": "H helical"},
    "C": {"marker": "D", "s": 40, "facecolor": "#d1c4e9", "label": "C cylindrical"},
    "U": {"marker": "P", "s": 70, "facecolor": "#90caf9", "label": "U universal"},
    "S": {"marker": "o", "s": 70, "facecolor": "#37474f", "label": "S spherical"},
    "E": {"marker": "h", "s": 64, "facecolor": "#ffccbc", "label": "E planar"},
}

COLORS = {
    "ground": "#5d5d5d",
    "end_effector": "#ef6c00",
    "link": "#4f7cac",
    "translation": "#1b8a3a",
    "rotation": "#1565c0",
    "force": "#c62828",
    "couple": "#8e24aa",
}


def _perpendiculars(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    d = d / np.linalg.norm(d)
    e1 = np.cross(d, np.eye(3)[int(np.argmin(np.abs(d)))])
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(d, e1)


def _cone(ax: Any, tip: np.ndarray, direction: np.ndarray, length: float, color: str, gid: str) -> None:
    """A solid arrowhead with its tip at ``tip`` pointing along ``direction``."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    d = direction / np.linalg.norm(direction)
    e1, e2 = _perpendiculars(d)
    base = tip - length * d
    ring = [base + 0.35 * length * (math.cos(t) * e1 + math.sin(t) * e2) for t in np.linspace(0, 2 * math.pi, 9)[:-1]]
    faces = [[tip, ring[k], ring[(k + 1) % len(ring)]] for k in range(len(ring))]
    poly = Poly3DCollection(faces, facecolor=color, edgecolor=color, linewidth=0.3)
    poly.set_gid(gid)
    ax.add_collection3d(poly)


def _arrow(ax: Any, start: np.ndarray, end: np.ndarray, color: str, gid: str, *, head: float, both: bool = False, **kw: Any) -> None:
    """An arrow from ``start`` to ``end``: a shaft (``Line3D`` with ``gid``) and one or two heads."""
    d = end - start
    ax.plot(*np.stack([start, end]).T, color=color, gid=gid, solid_capstyle="butt", **kw)
    _cone(ax, end, d, head, color, gid + ":head")
    if both:
        _cone(ax, end - 1.6 * head * d / np.linalg.norm(d), d, head, color, gid + ":head2")


def _rotation_mark(ax: Any, centre: np.ndarray, axis: np.ndarray, radius: float, color: str, gid: str) -> None:
    """A circular arrow around ``axis`` at ``centre`` (right-hand sense)."""
    e1, e2 = _perpendiculars(axis)
    t = np.linspace(0.0, 1.5 * math.pi, 40)
    arc = centre + radius * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)
    ax.plot(*arc.T, color=color, lw=1.6, gid=gid)
    tangent = -math.sin(t[-1]) * e1 + math.cos(t[-1]) * e2
    _cone(ax, arc[-1] + 0.35 * radius * tangent, tangent, 0.6 * radius, color, gid + ":head")


def _helix(centre: np.ndarray, axis: np.ndarray, radius: float, length: float) -> np.ndarray:
    e1, e2 = _perpendiculars(axis)
    t = np.linspace(0, 4 * math.pi, 60)
    s = np.linspace(-0.5, 0.5, 60) * length
    return centre + radius * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2) + s[:, None] * (axis / np.linalg.norm(axis))


def _unique_points(p: np.ndarray, eps: float) -> np.ndarray:
    out: list[np.ndarray] = []
    for x in p:
        if all(np.linalg.norm(x - y) > eps for y in out):
            out.append(x)
    return np.array(out).reshape(-1, 3)


def _draw_link(ax: Any, name: str, pts: np.ndarray, role: str, size: float) -> None:
    """A link as a thin body: a bar between two joints, a plate over three or more."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    from scipy.spatial import ConvexHull, QhullError

    color = COLORS.get(role, COLORS["link"])
    lw = {"ground": 4.0, "end_effector": 3.0}.get(role, 2.6)
    u = _unique_points(pts, 1e-6 * size)
    gid = f"mobility:link:{name}"
    if len(u) < 2:
        return
    if len(u) == 2:
        ax.plot(*u.T, color=color, lw=lw, gid=gid, solid_capstyle="round")
        return
    c = u.mean(axis=0)
    _, sv, vt = np.linalg.svd(u - c)
    flat = sv[2] <= 0.05 * sv[0] if len(sv) > 2 else True
    if flat and sv[1] > 0.05 * sv[0]:
        uv = (u - c) @ vt[:2].T
        try:
            hull = ConvexHull(uv)
        except QhullError:  # pragma: no cover - collinear after all
            hull = None
        if hull is not None:
            ring = u[hull.vertices]
            poly = Poly3DCollection([ring], facecolor=color, alpha=0.22 if role != "link" else 0.15, edgecolor=color, linewidth=lw * 0.6)
            poly.set_gid(gid)
            ax.add_collection3d(poly)
            inner = [k for k in range(len(u)) if k not in set(hull.vertices)]
            for k in inner:
                ax.plot(*np.stack([c, u[k]]).T, color=color, lw=lw * 0.6, gid=gid + ":spoke")
            return
    if not flat or sv[1] <= 0.05 * sv[0]:
        for k in range(len(u)):  # a star from the centroid: a thin 3D body
            ax.plot(*np.stack([c, u[k]]).T, color=color, lw=lw, gid=gid if k == 0 else gid + ":spoke", solid_capstyle="round")


def _joint_symbols(ax: Any, m: Mechanism, sk: Sketch, labels: bool, view: tuple[float, float]) -> None:
    """One scatter per joint type, small axis segments, names (beside each joint on the screen of ``view``)."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    size = sk.size
    joints = m.world_joints
    for t, style in JOINT_STYLE.items():
        idx = [i for i, jt in enumerate(sk.types) if jt == t]
        if not idx:
            continue
        p = sk.points[idx]
        edge = "white" if t == "S" else "black"
        ax.scatter(*p.T, marker=style["marker"], s=style["s"], facecolors=style["facecolor"], edgecolors=edge, linewidths=1.0, depthshade=False, zorder=5, gid=f"mobility:joints:{t}")
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
            axes_segs.append(_helix(x, np.asarray(j.axis), 0.025 * size, 0.1 * size))
        if j.type == "U":
            axes_segs += [np.stack([x - 0.06 * size * np.asarray(a), x + 0.06 * size * np.asarray(a)]) for a in j.axes]
        if j.type == "E":
            e1, e2 = _perpendiculars(np.asarray(j.normal))
            axes_segs.append(np.array([x + 0.05 * size * (s1 * e1 + s2 * e2) for s1, s2 in ((1, 1), (-1, 1), (-1, -1), (1, -1), (1, 1))]))
    if axes_segs:
        coll = Line3DCollection(axes_segs, colors="black", linewidths=1.1)
        coll.set_gid("mobility:joint-axes")
        ax.add_collection3d(coll)
    if rails:
        coll = Line3DCollection(rails, colors="#b8860b", linewidths=5.0, alpha=0.55, capstyle="butt")
        coll.set_gid("mobility:joint-rails")
        ax.add_collection3d(coll)
    if labels and len(joints) <= 40:
        _, sx, sy = _view_axes(*view)
        off = 0.03 * size * (0.8 * sx + 0.6 * sy)  # up and to the right on the screen, whatever the view
        for i, name in enumerate(sk.names):
            ax.text(*(sk.points[i] + off), name, fontsize=6.5, color="#263238", gid=f"mobility:joint-label:{name}", zorder=1e4)


def _triad(ax: Any, elev: float, azim: float) -> None:
    """The global x, y, z directions as seen in this view, drawn flat in the lower left corner."""
    _, sx, sy = _view_axes(elev, azim)
    origin = np.array([0.07, 0.07])
    for e, lab in zip(np.eye(3), "xyz"):
        tip = origin + 0.07 * np.array([e @ sx, e @ sy])
        ax.annotate("", xy=tuple(tip), xytext=tuple(origin), xycoords="axes fraction",
                    arrowprops={"arrowstyle": "-|>", "color": "#78909c", "lw": 1.0, "shrinkA": 0, "shrinkB": 0}, gid=f"mobility:triad:{lab}")
        if np.hypot(e @ sx, e @ sy) > 0.15:
            label = origin + 0.095 * np.array([e @ sx, e @ sy])
            ax.text2D(label[0], label[1], lab, transform=ax.transAxes, fontsize=7.5, color="#546e7a", ha="center", va="center")


def _segment_samples(start: np.ndarray, end: np.ndarray, n: int = 7) -> np.ndarray:
    return start + np.linspace(0.0, 1.0, n)[:, None] * (end - start)


def _farthest(options: Sequence[np.ndarray], occupied: list[np.ndarray]) -> int:
    """Index of the option (an array of points) whose nearest occupied point is farthest."""
    occ = np.concatenate([o.reshape(-1, 3) for o in occupied]) if occupied else np.zeros((0, 3))
    if not len(occ):
        return 0
    gaps = [float(np.min(np.linalg.norm(o.reshape(-1, 3)[:, None, :] - occ[None, :, :], axis=2))) for o in options]
    return int(np.argmax(np.round(gaps, 9)))  # rounding: ties go to the first option


def _scene(m: Mechanism, r: Result, sk: Sketch, constraints: bool, eyes: np.ndarray | None = None) -> dict[str, Any]:
    """Where the freedoms and constraints of the end effector are drawn (no drawing).

    Free vectors (translations, couples) are drawn at the end effector's
    centre (couples beside it); screws on their axes.  Where a choice is free
    (which end of an axis carries the rotation mark, which way a force arrow
    points, on which side a couple stands), the place farthest from what is
    already drawn is taken, so marks and labels do not fall on each other.
    With ``eyes`` (view directions, once chosen), a couple stands aside in a
    direction every view shows, not one seen end-on.
    """
    size = sk.size
    c = sk.end_effector_centre
    arrow = 0.32 * size
    half_axis = 0.5 * size
    out: dict[str, Any] = {"translations": [], "rotations": [], "forces": [], "couples": []}
    points: list[np.ndarray] = [sk.points, c[None]]  # joints, marks, tips and labels
    lines: list[np.ndarray] = []  # samples along drawn lines
    for t in r.translations:
        # either sense, a few lengths: the tip that keeps clear of joints and other tips
        tips = [c + s * k * size * t for k in (0.32, 0.25, 0.4) for s in (1.0, -1.0)]
        tip = tips[_farthest([x[None] for x in tips], points)]
        out["translations"].append((c, tip))
        points.append(tip[None])
        lines.append(_segment_samples(c, tip))
    for a in r.rotations:
        p = np.asarray(a.point, dtype=float)
        d = np.asarray(a.axis, dtype=float)
        # which end carries the mark and the label, and how long: clear of joints and other labels
        options = [(s, k) for k in (1.0, 0.8, 1.25) for s in (1.0, -1.0)]
        marks = [np.stack([p + s * 0.62 * k * half_axis * d, p + s * (k * half_axis + 0.06 * size) * d]) for s, k in options]
        best = _farthest(marks, points)
        s, k = options[best]
        start, end = p - s * k * half_axis * d, p + s * k * half_axis * d
        out["rotations"].append((start, end, marks[best][0], marks[best][1], s * d, a.pitch))
        points.append(marks[best])
        lines.append(_segment_samples(start, end, 11))
    if constraints:
        for f in r.forces:
            p = np.asarray(f.point, dtype=float)
            d = np.asarray(f.axis, dtype=float)
            # shorter than a rotation axis, so both show where they share a line
            # the arrowhead (and label) at either end, the line a little shorter or longer: clear of marks and joints
            options = [(sg, k) for k in (0.28, 0.2, 0.36) for sg in (1.0, -1.0)]
            tips = [np.stack([p + sg * k * size * d, p + sg * (k + 0.06) * size * d]) for sg, k in options]
            sg, k = options[_farthest(tips, points)]
            start, tip = p - sg * k * size * d, p + sg * k * size * d
            out["forces"].append((start, tip, f.pitch))
            points.append(np.stack([tip, tip + 0.06 * size * sg * d]))
            lines.append(_segment_samples(start, tip))
        for cp in r.couples:
            cp = np.asarray(cp, dtype=float)
            e1, e2 = _perpendiculars(cp)
            offsets = [math.cos(k * math.pi / 4) * e1 + math.sin(k * math.pi / 4) * e2 for k in range(8)]
            segs = [_segment_samples(c + 0.25 * size * e - 0.5 * arrow * cp, c + 0.25 * size * e + 0.5 * arrow * cp) for e in offsets]
            occupied = np.concatenate([o.reshape(-1, 3) for o in points + lines])
            clearance = [float(np.min(np.linalg.norm(sg[:, None, :] - occupied[None], axis=2))) / size for sg in segs]
            seen = [1.0 if eyes is None else float(np.min(np.sqrt(np.maximum(0.0, 1.0 - (eyes @ e) ** 2)))) for e in offsets]
            # enough clearance first (beyond 15 % of the scene it no longer matters), then visibility in every view
            k = int(np.argmax([round(4.0 * min(cl, 0.15) + sn, 9) for cl, sn in zip(clearance, seen)]))
            out["couples"].append((segs[k][0], segs[k][-1]))
            points.append(segs[k][[0, -1]])
            lines.append(segs[k])
    return out


def plot_mechanism(
    mechanism: Mechanism,
    result: Result | None = None,
    *,
    constraints: bool = False,
    views: int | Sequence[tuple[float, float]] = 2,
    labels: bool = True,
    legend: bool = True,
    title: str | None = None,
    figsize: tuple[float, float] | None = None,
    tol: Tolerance = DEFAULT_TOLERANCE,
) -> "Figure":
    """Draw ``mechanism`` at its pose with the end effector's freedoms (and constraints).

    Parameters
    ----------
    mechanism : Mechanism
    result : Result, optional
        Its analysis; computed with ``tol`` when not given.
    constraints : bool
        Also draw the constraint wrenches on the end effector: force lines
        (red, ``W``) and couples (purple double arrows, ``C``), numbered as in
        the text report.
    views : int or sequence of (elev, azim)
        Number of viewpoints chosen by :func:`choose_views`, or the
        viewpoints themselves (degrees).
    labels : bool
        Write joint names (up to 40 joints).
    legend : bool
    title : str, optional
        Default: name, DOF, pattern and mobility.
    figsize : (width, height) in inches, optional
    tol : Tolerance

    Returns
    -------
    matplotlib.figure.Figure
        One 3D axes per view, orthographic.

    Raises
    ------
    PlottingUnavailableError
        When matplotlib is not installed.
    """
    _matplotlib()
    from matplotlib.lines import Line2D

    from ..core.analysis import analyze

    r = result if result is not None else analyze(mechanism, tol=tol)
    sk = sketch(mechanism)
    size = sk.size
    sc = _scene(mechanism, r, sk, constraints)

    important = [sk.points, sk.end_effector_centre[None]]
    directions = []
    for s, e in sc["translations"] + sc["couples"]:
        important.append(e[None])
        directions.append((e - s) / np.linalg.norm(e - s))
    for s, e, mark, label_at, d, _ in sc["rotations"]:
        important.append(np.stack([s, e, mark, label_at]))
        directions.append(d)
    for s, e, _ in sc["forces"]:
        important.append(np.stack([s, e]))
        directions.append((e - s) / np.linalg.norm(e - s))
    important_pts = np.concatenate(important)
    dirs = np.array(directions).reshape(-1, 3)
    if isinstance(views, int):
        link_dirs = []
        for link, idx in sk.link_joints.items():
            u = _unique_points(sk.points[list(idx)], 1e-6 * size)
            if len(u) == 2:
                link_dirs.append((u[1] - u[0]) / np.linalg.norm(u[1] - u[0]))
        # links matter too, but less than the answer: weight by listing freedoms twice
        view_list = choose_views(important_pts, np.concatenate([dirs, dirs, np.array(link_dirs).reshape(-1, 3)]), size, views)
    else:
        view_list = [(float(e), float(a)) for e, a in views]
    if sc["couples"]:  # place the couples again, now that the views are known
        sc = _scene(mechanism, r, sk, constraints, eyes=np.array([_view_axes(e, a)[0] for e, a in view_list]))

    extent_pts = np.concatenate([important_pts, sk.points])
    lo, hi = extent_pts.min(axis=0), extent_pts.max(axis=0)
    mid = 0.5 * (lo + hi)
    half = 0.5 * float(np.max(hi - lo)) * 1.08 + 0.02 * size

    nv = len(view_list)
    fig = _figure_class()(figsize=figsize or (6.2 * nv, 6.6))
    head = 0.045 * size
    for k, (elev, azim) in enumerate(view_list):
        ax = fig.add_subplot(1, nv, k + 1, projection="3d")
        ax.set_proj_type("ortho")
        ax.view_init(elev=elev, azim=azim)
        ax.set_xlim(mid[0] - half, mid[0] + half)
        ax.set_ylim(mid[1] - half, mid[1] + half)
        ax.set_zlim(mid[2] - half, mid[2] + half)
        ax.set_box_aspect((1, 1, 1), zoom=1.25)
        ax.set_axis_off()
        ax.set_title(f"view {k + 1}: elev {elev:g}°, azim {azim:g}°", fontsize=9, color="#455a64")
        _triad(ax, elev, azim)
        for link, idx in sk.link_joints.items():
            role = "ground" if link == mechanism.ground else "end_effector" if link == mechanism.end_effector else "link"
            _draw_link(ax, link, sk.points[list(idx)], role, size)
        _joint_symbols(ax, mechanism, sk, labels, (elev, azim))
        ax.scatter(*sk.end_effector_centre, marker="x", s=30, color=COLORS["end_effector"], depthshade=False, gid="mobility:end-effector-centre")
        for i, (s, e) in enumerate(sc["translations"]):
            _arrow(ax, s, e, COLORS["translation"], f"mobility:translation:{i}", head=head, lw=2.4)
            ax.text(*(e + 0.03 * size * (e - s) / np.linalg.norm(e - s)), f"T{i + 1}", color=COLORS["translation"], fontsize=9, fontweight="bold", zorder=1e4)
        for i, (s, e, mark, label_at, d, pitch) in enumerate(sc["rotations"]):
            ax.plot(*np.stack([s, e]).T, color=COLORS["rotation"], lw=1.8, ls=(0, (8, 3, 2, 3)), gid=f"mobility:rotation-axis:{i}")
            _rotation_mark(ax, mark, r.rotations[i].axis, 0.06 * size, COLORS["rotation"], f"mobility:rotation-mark:{i}")
            text = f"R{i + 1}" if pitch == 0 else f"R{i + 1}\nh = {pitch:.3g}{(' ' + r.length_unit) if r.length_unit else ''}/rad"
            ax.text(*label_at, text, color=COLORS["rotation"], fontsize=9, fontweight="bold", gid=f"mobility:rotation-label:{i}", ha="center", va="center", zorder=1e4)
        k0 = len(r.couples)
        for i, (s, e, pitch) in enumerate(sc["forces"]):
            d = (e - s) / np.linalg.norm(e - s)
            ax.plot(*np.stack([s, e]).T, color=COLORS["force"], lw=2.6, alpha=0.8, gid=f"mobility:force:{i}")
            _cone(ax, e, d, head * 0.8, COLORS["force"], f"mobility:force:{i}:head")
            text = f"W{k0 + i + 1}" if pitch == 0 else f"W{k0 + i + 1}  h = {pitch:.3g}"
            ax.text(*(e + 0.03 * size * d), text, color=COLORS["force"], fontsize=8.5, gid=f"mobility:force-label:{i}", zorder=1e4)
        for i, (s, e) in enumerate(sc["couples"]):
            _arrow(ax, s, e, COLORS["couple"], f"mobility:couple:{i}", head=head * 0.8, both=True, lw=1.8, ls="--")
            ax.text(*(e + 0.03 * size * (e - s) / np.linalg.norm(e - s)), f"C{i + 1}", color=COLORS["couple"], fontsize=8.5, zorder=1e4)

    if legend:
        handles = []
        types_present = [t for t in JOINT_STYLE if t in sk.types]
        for t in types_present:
            st = JOINT_STYLE[t]
            handles.append(Line2D([], [], ls="", marker=st["marker"], markersize=7, markerfacecolor=st["facecolor"], markeredgecolor="white" if t == "S" else "black", label=st["label"]))
        handles.append(Line2D([], [], color=COLORS["ground"], lw=4, label="ground"))
        handles.append(Line2D([], [], color=COLORS["end_effector"], lw=3, label="end effector"))
        if any(x not in (mechanism.ground, mechanism.end_effector) for x in sk.link_joints):
            handles.append(Line2D([], [], color=COLORS["link"], lw=2.6, label="link"))
        if sc["translations"]:
            handles.append(Line2D([], [], color=COLORS["translation"], lw=2.4, marker=">", markevery=[1], label="translation T"))
        if sc["rotations"]:
            handles.append(Line2D([], [], color=COLORS["rotation"], lw=1.8, ls=(0, (8, 3, 2, 3)), label="rotation axis R (h: pitch)"))
        if sc["forces"]:
            handles.append(Line2D([], [], color=COLORS["force"], lw=1.6, label="constraint force W"))
        if sc["couples"]:
            handles.append(Line2D([], [], color=COLORS["couple"], lw=1.8, ls="--", label="constraint couple C"))
        width = fig.get_figwidth()
        fig.legend(handles=handles, loc="lower center", ncol=max(2, min(len(handles), int(width / 1.75))), frameon=False, fontsize=8.5)
    unit = f", lengths in {r.length_unit}" if r.length_unit else ""
    text = title if title is not None else f"{r.name}: end effector {r.dof} DOF ({r.pattern}), mobility {r.mobility}{unit}"
    wrapped = textwrap.fill(text, width=max(40, int(fig.get_figwidth() * 10.5)))
    fig.suptitle(wrapped, fontsize=11)
    top = 0.9 - 0.22 * wrapped.count("\n") / fig.get_figheight()  # room for a title on several lines
    fig.subplots_adjust(left=0.0, right=1.0, top=top, bottom=0.1 if legend else 0.02, wspace=0.0)
    return fig


# ---------------------------------------------------------------------------
# the joint graph and its decomposition

LIMB_COLORS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2", "#bcbd22", "#7f7f7f")


def _node_values(node: Node, value: SystemValue | None, m: Mechanism, screws: Any, tol: Tolerance) -> dict[int, tuple[int, int]]:
    """(dimension, idle) of every node of the tree, keyed by ``id(node)``."""
    out: dict[int, tuple[int, int]] = {}

    def walk(n: Node, v: SystemValue | None) -> None:
        if isinstance(n, JointNode):
            out[id(n)] = (m.joints[n.index].dof, 0)
            return
        if v is None:
            v = evaluate(n, screws, tol)
        out[id(n)] = (v.dim, v.idle)
        if isinstance(n, Parallel):
            for c, cv in zip(n.children, v.children):
                walk(c, cv)
        elif isinstance(n, Series):
            values = iter(v.children)
            for c in n.children:
                walk(c, None if isinstance(c, JointNode) else next(values))
        else:
            values = iter(v.children)
            for _, _, c in n.edges:
                walk(c, None if isinstance(c, JointNode) else next(values))

    walk(node, value)
    return out


def _children(n: Node) -> list[Node]:
    if isinstance(n, JointNode):
        return []
    if isinstance(n, Bridge):
        return [c for _, _, c in n.edges]
    return list(n.children)


def _tree_layout(root: Node) -> tuple[dict[int, tuple[float, float]], list[tuple[int, int]], dict[int, Node]]:
    """Leaves left to right, each parent above the middle of its children."""
    pos: dict[int, tuple[float, float]] = {}
    edges: list[tuple[int, int]] = []
    nodes: dict[int, Node] = {}
    counter = itertools.count()

    def place(n: Node, depth: int) -> float:
        nodes[id(n)] = n
        kids = _children(n)
        if not kids:
            x = float(next(counter))
        else:
            xs = [place(c, depth + 1) for c in kids]
            edges.extend((id(n), id(c)) for c in kids)
            x = 0.5 * (min(xs) + max(xs))
        pos[id(n)] = (x, -float(depth))
        return x

    place(root, 0)
    return pos, edges, nodes


def _branch_colors(m: Mechanism, root: Node, detached: Sequence[Node]) -> dict[int, str]:
    """Colour of each joint: one per branch of the top node (limb), grey when detached."""
    out: dict[int, str] = {}
    branches = _children(root) if isinstance(root, (Parallel, Bridge)) else [root]
    for k, b in enumerate(branches):
        for i in joints_of(b):
            out[i] = LIMB_COLORS[k % len(LIMB_COLORS)]
    for d in detached:
        for i in joints_of(d):
            out[i] = "#9e9e9e"
    return out


def plot_graph(
    mechanism: Mechanism,
    result: Result | None = None,
    *,
    figsize: tuple[float, float] | None = None,
    tol: Tolerance = DEFAULT_TOLERANCE,
) -> "Figure":
    """Draw the joint graph and the series/parallel tree found by :func:`mobility.core.topology.decompose`.

    Left: links as nodes (ground and end effector marked), joints as edges
    labelled ``name (type)``, coloured by branch of the top parallel
    connection (a limb).  Right: the tree, ``∥`` parallel (twist systems
    intersect), ``—`` series (twist systems add), ``⊠`` bridge (solved by loop
    closure), each labelled with the dimension of its twist system (and its
    idle motions); leaves are the joints.

    Parameters
    ----------
    mechanism : Mechanism
    result : Result, optional
        Used for the title; computed when not given.
    figsize : (width, height) in inches, optional
    tol : Tolerance

    Returns
    -------
    matplotlib.figure.Figure
        Two axes: ``fig.axes[0]`` the joint graph, ``fig.axes[1]`` the tree.

    Raises
    ------
    PlottingUnavailableError
        When matplotlib is not installed.
    """
    _matplotlib()
    import networkx as nx
    from matplotlib.lines import Line2D

    from ..core.analysis import analyze

    r = result if result is not None else analyze(mechanism, tol=tol)
    topo = decompose(mechanism)
    screws = joint_screws(mechanism)
    colors = _branch_colors(mechanism, topo.root, topo.detached)

    # --- joint graph: layers by distance from the ground
    g = nx.MultiGraph()
    g.add_nodes_from(mechanism.links)
    for i, j in enumerate(mechanism.joints):
        g.add_edge(*j.links, key=i, name=j.name)
    depth = nx.single_source_shortest_path_length(g, mechanism.ground)
    # within a layer: the mean place of a link's neighbours in the layer below
    # (barycentre ordering), then its branch (limb), so limbs do not cross
    branch_of = {c: k for k, c in enumerate(dict.fromkeys(colors[i] for i in sorted(colors)))}

    def branch(x: str) -> int:
        if x in (mechanism.ground, mechanism.end_effector):
            return 0
        return min(branch_of.get(colors.get(k, ""), 99) for _, _, k in g.edges(x, keys=True))

    layers: dict[int, list[str]] = {}  # lists, not sets: the order within a layer is kept
    place: dict[str, float] = {}
    for d in sorted(set(depth.values())):
        members = [x for x in mechanism.links if depth[x] == d]

        def key(x: str) -> tuple[float, int, int]:
            below = [place[y] for y in g.neighbors(x) if depth[y] == d - 1]
            return (float(np.mean(below)) if below else 0.0, branch(x), mechanism.links.index(x))

        layers[d] = sorted(members, key=key)
        place.update({x: float(k) / max(len(members) - 1, 1) for k, x in enumerate(layers[d])})
    pos = nx.multipartite_layout(g, subset_key=layers, align="horizontal", scale=1.0)
    width_nodes = max(sum(1 for x in depth.values() if x == d) for d in set(depth.values()))
    leaves = len(joints_of(topo.root)) + sum(len(joints_of(d)) for d in topo.detached)
    w = max(10.0, min(26.0, 3.2 + 0.55 * max(leaves, 2 * width_nodes)))
    fig = _figure_class()(figsize=figsize or (w, 6.4))
    ax_g = fig.add_axes((0.01, 0.08, 0.40, 0.82))
    ax_t = fig.add_axes((0.43, 0.08, 0.56, 0.82))
    node_color = ["#bdbdbd" if x == mechanism.ground else "#ffb74d" if x == mechanism.end_effector else "#e3f2fd" for x in g.nodes]
    nodes_art = nx.draw_networkx_nodes(g, pos, ax=ax_g, node_color=node_color, edgecolors="#37474f", node_size=60)
    nodes_art.set_gid("mobility:graph:links")
    for x, fc in zip(g.nodes, node_color):  # each link's name in a box of its role's colour
        nx.draw_networkx_labels(g, pos, labels={x: x}, ax=ax_g, font_size=7, bbox={"boxstyle": "round,pad=0.3", "fc": fc, "ec": "#37474f", "lw": 0.8})
    # multi-edges: one arc radius per joint between the same two links
    seen: dict[frozenset[str], int] = {}
    for u, v, k, data in g.edges(keys=True, data=True):
        n_same = g.number_of_edges(u, v)
        slot = seen.get(frozenset((u, v)), 0)
        seen[frozenset((u, v))] = slot + 1
        colour = colors.get(k, "#37474f")
        gid = f"mobility:graph:joint:{data['name']}"
        if n_same == 1:  # a plain line: much cheaper than an arrow patch
            ax_g.plot(*np.stack([pos[u], pos[v]]).T, color=colour, lw=2.2, gid=gid, zorder=1)
            continue
        # joints between the same two links: arcs of different curvature
        style = f"arc3,rad={0.4 * (slot - (n_same - 1) / 2)}"
        arts = nx.draw_networkx_edges(g, pos, edgelist=[(u, v, k)], ax=ax_g, edge_color=colour, width=2.2, connectionstyle=style, arrows=True, arrowstyle="-", node_size=520)
        for art in arts if isinstance(arts, list) else [arts]:
            art.set_gid(gid)
    label_box = {"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.85}
    for u, v in {frozenset(e[:2]): e[:2] for e in g.edges(keys=True)}.values():
        # joints between the same two links share one label, one line each,
        # near the end in the wider layer, where labels have room
        ks = sorted(g[u][v])
        text = "\n".join(f"{mechanism.joints[k].name} ({mechanism.joints[k].type})" for k in ks)
        t = 0.32 if len(layers[depth[u]]) > len(layers[depth[v]]) else 0.68
        x, y = (1.0 - t) * np.asarray(pos[u]) + t * np.asarray(pos[v])
        ax_g.text(x, y, text, fontsize=6.5, color=colors.get(ks[0], "#37474f"), ha="center", va="center", bbox=label_box, zorder=3)
    ax_g.set_title("joint graph (links = nodes, joints = edges)", fontsize=10)
    ax_g.set_axis_off()
    ax_g.margins(0.12)

    # --- decomposition tree
    values = _node_values(topo.root, None, mechanism, screws, tol)
    roots: list[Node] = [topo.root, *topo.detached]
    tree = nx.DiGraph()
    tpos: dict[int, tuple[float, float]] = {}
    tnodes: dict[int, Node] = {}
    offset = 0.0
    for k, root in enumerate(roots):
        if k:
            values.update(_node_values(root, None, mechanism, screws, tol))
        p, e, nodes = _tree_layout(root)
        xs = [x for x, _ in p.values()]
        for key, (x, y) in p.items():
            tpos[key] = (x - min(xs) + offset, y)
        offset += max(xs) - min(xs) + 2.0
        tree.add_nodes_from(p)
        tree.add_edges_from(e)
        tnodes.update(nodes)
    labels: dict[int, str] = {}
    shapes: dict[str, list[int]] = {"joint": [], "series": [], "parallel": [], "bridge": []}
    for key, n in tnodes.items():
        dim, idle = values[key]
        idle_text = f", idle {idle}" if idle else ""
        if isinstance(n, JointNode):
            labels[key] = f"{n.name}\n{mechanism.joints[n.index].type}"
            shapes["joint"].append(key)
        elif isinstance(n, Series):
            labels[key] = f"— series\ndim {dim}{idle_text}"
            shapes["series"].append(key)
        elif isinstance(n, Parallel):
            labels[key] = f"∥ parallel\ndim {dim}{idle_text}"
            shapes["parallel"].append(key)
        else:
            labels[key] = f"⊠ bridge\ndim {dim}{idle_text}"
            shapes["bridge"].append(key)
    nx.draw_networkx_edges(tree, tpos, ax=ax_t, arrows=False, edge_color="#90a4ae", width=1.2)
    fill = {"series": "#fff3e0", "parallel": "#e8f5e9", "bridge": "#fce4ec", "joint": "white"}
    for kind, keys in shapes.items():
        for key in keys:  # every node a box of its kind's colour, read back by its gid
            n = tnodes[key]
            edge = colors.get(n.index, "#37474f") if isinstance(n, JointNode) else "#546e7a"
            ax_t.text(*tpos[key], labels[key], ha="center", va="center", fontsize=6.5, gid=f"mobility:tree:{kind}",
                      bbox={"boxstyle": "round,pad=0.45", "fc": fill[kind], "ec": edge, "lw": 2.0 if kind == "joint" else 1.0})
    bridge_edges = {}
    for key in shapes["bridge"]:  # a bridge's connections join named links: say which
        for u, v, child in tnodes[key].edges:
            bridge_edges[(key, id(child))] = f"{u}–{v}"
    if bridge_edges:
        nx.draw_networkx_edge_labels(tree, tpos, edge_labels=bridge_edges, ax=ax_t, font_size=6, label_pos=0.7, rotate=False, bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none"})
    root_key = id(topo.root)
    x0, y0 = tpos[root_key]
    ax_t.annotate(f"end effector: {r.dof} DOF ({r.pattern})", (x0, y0), xytext=(0, 26), textcoords="offset points", ha="center", fontsize=9, fontweight="bold", color=COLORS["end_effector"])
    for d in topo.detached:
        x, y = tpos[id(d)]
        ax_t.annotate("detached", (x, y), xytext=(0, 26), textcoords="offset points", ha="center", fontsize=8, color="#757575")
    ax_t.set_title("series/parallel tree (dim: DOF between the node's two end links)", fontsize=10)
    ax_t.set_axis_off()
    ax_t.margins(0.08, 0.18)
    handles = [
        Line2D([], [], ls="", marker="o", markersize=9, markerfacecolor="#bdbdbd", markeredgecolor="#37474f", label="ground"),
        Line2D([], [], ls="", marker="o", markersize=9, markerfacecolor="#ffb74d", markeredgecolor="#37474f", label="end effector"),
    ]
    branches = _children(topo.root) if isinstance(topo.root, (Parallel, Bridge)) else [topo.root]
    if len(branches) > 1:
        handles += [Line2D([], [], color=LIMB_COLORS[k % len(LIMB_COLORS)], lw=2.2, label=f"branch {k + 1}") for k in range(min(len(branches), len(LIMB_COLORS)))]
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), frameon=False, fontsize=8)
    fig.suptitle(f"{r.name}: mobility {r.mobility}, end effector {r.dof} DOF ({r.pattern}), {r.loops} loop(s)", fontsize=11)
    return fig


def save_figure(fig: "Figure", path: str | Path, *, dpi: int = 150) -> Path:
    """Write ``fig`` to ``path`` as PNG, SVG or PDF (by suffix).

    Raises
    ------
    PlotFormatError
        For another suffix.
    """
    p = Path(path)
    if p.suffix.lower() not in FORMATS:
        raise PlotFormatError(f"{p}: cannot write a {p.suffix or 'suffix-less'} file; expected a name ending in {', '.join(FORMATS)}")
    fig.savefig(p, dpi=dpi, facecolor="white")
    return p
