"""What the 3D view draws for one pose, as plain data: glyphs in three layers.

Each :class:`Glyph` is one thing a person points at, in the ``mechanism``, ``freedoms`` (``T1..``, ``R1..``) or
``constraints`` (``C1..``, ``W..``, numbered as in the text report) layer (docs/view.md, "How it is built and
tested").  Every glyph size is a fraction of the scene's size, so metres and millimetres look the same.

Examples
--------
>>> import mobility
>>> m = mobility.load("mechanisms/slider_crank.yaml")
>>> s = build_scene(m, mobility.analyze(m))
>>> [g.key for g in s.layer("mechanism")]
['links:ground', 'links:end_effector', 'links:link', 'joints:R', 'joints:P', 'end-effector-centre']
>>> [g.key for g in s.layer("freedoms")], [g.key for g in s.layer("constraints")]
(['T1'], ['C1', 'C2', 'C3', 'W4', 'W5'])
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..core.model import JOINT_TYPES, Mechanism
from ..core.frozen import ReadOnlyArrays
from ..core.result import Result
from ..report.plotting import COLORS, choose_views, sketch
from ..report.plotting.geometry import perpendiculars, segment_samples
from ..report.plotting.glyphs import link_shape
from .describe import couple_text, force_text, joint_text, plotly_text, rotation_text, translation_text
from .geometry import Mesh, arc, cone, fan, helix, pieces

__all__ = ["LAYERS", "JOINT_SYMBOLS", "Glyph", "Scene", "build_scene", "viewpoint"]

LAYERS = ("mechanism", "freedoms", "constraints")
"""The layers of the view, each switchable on its own."""

JOINT_SYMBOLS = {"R": ("circle", "#ffffff"), "P": ("square", "#ffe08a"), "H": ("diamond", "#c8e6c9"), "C": ("diamond-open", "#7e57c2"),
                 "U": ("cross", "#1e88e5"), "S": ("circle", "#37474f"), "E": ("square-open", "#f4511e")}
"""Marker symbol and colour of each joint type (symbols a WebGL 3D scatter can draw)."""

_ARROW, _HALF_AXIS, _HALF_FORCE, _HEAD, _MARK, _COUPLE_OFFSET = 0.36, 0.45, 0.28, 0.05, 0.055, 0.25  # glyph sizes, fractions of the scene's


@dataclass(frozen=True, eq=False)
class Glyph(ReadOnlyArrays):
    """One thing drawn: a link group, a joint type, one freedom or one constraint.

    ``key``: unique in its scene (``"T1"``, ``"W3"``, ``"links:ground"``, ``"joints:R"``...); ``kind``: ``translation``,
    ``rotation``, ``helical``, ``couple``, ``force``, ``wrench``, ``ground``, ``end_effector``, ``link``, ``joint`` or
    ``centre``; ``path``: a polyline (rows of NaN between pieces) ``width`` pixels wide; ``mesh``: solid parts (arrowheads,
    plates) of ``opacity``; ``points``: markers (joints), each with its ``point_hover``; ``direction``: the unit
    direction of a freedom or constraint.
    """

    key: str
    layer: str
    kind: str
    name: str
    color: str
    path: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    width: float = 4.0
    hover: str = ""
    mesh: Mesh | None = None
    opacity: float = 1.0
    points: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    symbol: str = "circle"
    point_hover: tuple[str, ...] = ()
    label: str = ""
    label_at: np.ndarray | None = None
    direction: np.ndarray | None = None

    def extent(self) -> np.ndarray:
        """Every point the glyph occupies, shape (n, 3) (for the bounds of the scene)."""
        parts = [self.path[~np.isnan(self.path).any(axis=1)], self.points]
        if self.mesh is not None:
            parts.append(self.mesh.vertices)
        if self.label_at is not None:
            parts.append(self.label_at[None])
        return np.concatenate([p.reshape(-1, 3) for p in parts])


@dataclass(frozen=True, eq=False)
class Scene(ReadOnlyArrays):
    """The glyphs of one pose (mechanism, then freedoms, then constraints) and the bounds of what is drawn.

    ``centre``: the end effector's (where free vectors are drawn); ``size``: the mechanism's (the unit of every glyph's
    size); ``scale``: :func:`mobility.report.plotting.sketch.drawing_scale`.
    """

    glyphs: tuple[Glyph, ...]
    centre: np.ndarray
    size: float
    lower: np.ndarray
    upper: np.ndarray
    scale: float = 1.0

    def layer(self, name: str) -> tuple[Glyph, ...]:
        """The glyphs of one layer, in drawing order."""
        return tuple(g for g in self.glyphs if g.layer == name)


def build_scene(mechanism: Mechanism, result: Result, drawing: float | None = None) -> Scene:
    """The glyphs of ``mechanism`` at its pose with the freedoms and constraints of ``result``.

    ``drawing``: drawing units per file unit (a power of two, shared by poses
    shown together; default: the pictures' :func:`~mobility.report.plotting.sketch.drawing_scale`).
    The scene has ``result.dof`` glyphs in ``freedoms``, ``6 - result.dof`` in ``constraints``.
    """
    sk = sketch(mechanism, drawing)
    size, c = sk.size, sk.end_effector_centre
    scale, unit = result.length_scale, result.length_unit
    glyphs = _links(mechanism, sk) + _joints(mechanism, sk, scale, unit)
    glyphs.append(Glyph("end-effector-centre", "mechanism", "centre", "end-effector centre", COLORS["end_effector"],
                        points=c[None], symbol="x", point_hover=("end-effector centre",)))
    head = _HEAD * size
    for i, t in enumerate(result.translations):
        tip = c + _ARROW * size * t
        glyphs.append(Glyph(f"T{i + 1}", "freedoms", "translation", f"T{i + 1} translation", COLORS["translation"],
                            path=segment_samples(c, tip - head * t, 9), width=7.0, hover=translation_text(i + 1, t),
                            mesh=cone(tip, t, 2.0 * head, 0.45 * head), label=f"T{i + 1}", label_at=tip + 0.05 * size * t, direction=t))
    for i, a in enumerate(result.rotations):
        glyphs.append(_rotation(i, a, size, scale, unit, sk.scale))
    k = len(result.couples)
    for i, cp in enumerate(result.couples):
        glyphs.append(_couple(i, np.asarray(cp, dtype=float), c, size, k))
    for i, f in enumerate(result.forces):
        glyphs.append(_force(k + i, f, size, scale, unit, sk.scale))
    everything = np.concatenate([g.extent() for g in glyphs])  # the bounds of everything drawn
    return Scene(tuple(glyphs), c, size, everything.min(axis=0), everything.max(axis=0), sk.scale)


def _links(mechanism: Mechanism, sk) -> list[Glyph]:
    """The links, grouped by role (one glyph each for the ground, the end effector and the other links)."""
    roles: dict[str, list[str]] = {"ground": [], "end_effector": [], "link": []}
    for link in sk.link_joints:
        roles["ground" if link == mechanism.ground else "end_effector" if link == mechanism.end_effector else "link"].append(link)
    names = {"ground": "ground", "end_effector": "end effector", "link": "links"}
    widths = {"ground": 9.0, "end_effector": 8.0, "link": 6.0}
    out = []
    for role, members in roles.items():
        lines, meshes = [], []
        for link in members:  # drawn as the pictures draw it (link_shape): a plate, a bar or a star
            kind, ring, segments = link_shape(sk.points[list(sk.link_joints[link])], sk.size)
            if kind == "plate":
                meshes.append(fan(ring))
                lines.append(np.vstack([ring, ring[:1]]))  # its outline
            # a plate's spokes as they are; a bar and a star's segments sampled, so that a hover finds them anywhere
            lines += [s if kind == "plate" else segment_samples(s[0], s[1], 9 if kind == "bar" else 5) for s in segments]
        if not lines:
            continue
        hover = "<br>".join(f"{names[role] if role != 'link' else 'link'} {plotly_text(link)}" for link in members[:12])
        out.append(Glyph(f"links:{role}", "mechanism", role, names[role], COLORS[role], path=pieces(*lines),
                         width=widths[role], hover=hover, mesh=Mesh.merged(*meshes) if meshes else None, opacity=0.25))
    return out


def _joints(mechanism: Mechanism, sk, scale: float, unit: str) -> list[Glyph]:
    """One glyph per joint type: a marker at each joint, short lines along its axes."""
    out = []
    size = sk.size
    joints = mechanism.world_joints
    for jtype, (symbol, color) in JOINT_SYMBOLS.items():
        idx = [i for i, j in enumerate(joints) if j.type == jtype]
        if not idx:
            continue
        axes = []
        for i in idx:
            j, x = joints[i], sk.points[i]
            directions = [j.axis] if j.axis is not None else list(j.axes or ())
            axes += [np.stack([x - 0.07 * size * np.asarray(a), x + 0.07 * size * np.asarray(a)]) for a in directions]
            if j.type == "H":
                axes.append(helix(x, np.asarray(j.axis), 0.025 * size, 0.12 * size))
            if j.type == "E":
                e1, e2 = perpendiculars(np.asarray(j.normal))
                axes.append(np.array([x + 0.05 * size * (s1 * e1 + s2 * e2) for s1, s2 in ((1, 1), (-1, 1), (-1, -1), (1, -1), (1, 1))]))
        hover = tuple(joint_text(joints[i], bool(sk.located[i]), scale, unit) for i in idx)
        out.append(Glyph(f"joints:{jtype}", "mechanism", "joint", f"{jtype} {JOINT_TYPES[jtype]}", color,
                         path=pieces(*axes), width=3.0, hover=f"{jtype} joint axes", points=sk.points[idx],
                         symbol=symbol, point_hover=hover))
    return out


def _rotation(i: int, a, size: float, scale: float, unit: str, drawing: float) -> Glyph:
    """``R<i+1>``: the axis line through its point, a circular arrow near one end (a helix if it has a pitch)."""
    d = np.asarray(a.axis, dtype=float)
    p = np.asarray(a.point, dtype=float) * drawing
    side = 1.0 if i % 2 == 0 else -1.0  # alternate ends, so that two axes through one point keep their labels apart
    start, end = p - side * _HALF_AXIS * size * d, p + side * _HALF_AXIS * size * d
    ring, tangent = arc(p + side * 0.78 * _HALF_AXIS * size * d, d, _MARK * size)
    head = cone(ring[-1] + 0.9 * _HEAD * size * tangent, tangent, 1.6 * _HEAD * size, 0.4 * _HEAD * size)
    parts = [segment_samples(start, end, 15), ring]
    if a.pitch != 0:
        parts.append(helix(p, d, 0.03 * size, 0.22 * size))
    label = f"R{i + 1}" if a.pitch == 0 else f"R{i + 1} h={a.pitch:.3g}"
    return Glyph(f"R{i + 1}", "freedoms", a.kind, f"R{i + 1} {a.kind}", COLORS["rotation"], path=pieces(*parts), width=5.0,
                 hover=rotation_text(i + 1, a, scale, unit), mesh=head, label=label, label_at=end + side * 0.06 * size * d, direction=d)


def _couple(i: int, direction: np.ndarray, centre: np.ndarray, size: float, count: int) -> Glyph:
    """``C<i+1>``: a double-headed arrow beside the centre (couples of one result stand apart)."""
    e1, e2 = perpendiculars(direction)
    angle = 2.0 * math.pi * i / max(count, 1) + math.pi / 6
    mid = centre + _COUPLE_OFFSET * size * (math.cos(angle) * e1 + math.sin(angle) * e2)
    half = 0.5 * _ARROW * size
    head = _HEAD * size
    tip = mid + half * direction
    heads = Mesh.merged(cone(tip, direction, 1.6 * head, 0.4 * head), cone(tip - 1.5 * head * direction, direction, 1.6 * head, 0.4 * head))
    return Glyph(f"C{i + 1}", "constraints", "couple", f"C{i + 1} couple", COLORS["couple"], path=segment_samples(mid - half * direction, tip - head * direction, 9),
                 width=5.0, hover=couple_text(i + 1, direction), mesh=heads, label=f"C{i + 1}", label_at=tip + 0.05 * size * direction, direction=direction)


def _force(n: int, f, size: float, scale: float, unit: str, drawing: float) -> Glyph:
    """``W<n+1>``: the force line through its point with an arrowhead (and a circular arrow for a pitch)."""
    d = np.asarray(f.axis, dtype=float)
    p = np.asarray(f.point, dtype=float) * drawing
    head = _HEAD * size
    start, tip = p - _HALF_FORCE * size * d, p + _HALF_FORCE * size * d
    parts = [segment_samples(start, tip - head * d, 11)]
    meshes = [cone(tip, d, 1.8 * head, 0.45 * head)]
    if f.pitch != 0:
        ring, tangent = arc(p - 0.6 * _HALF_FORCE * size * d, d, 0.8 * _MARK * size)
        parts.append(ring)
        meshes.append(cone(ring[-1] + 0.7 * head * tangent, tangent, 1.3 * head, 0.35 * head))
    label = f"W{n + 1}" if f.pitch == 0 else f"W{n + 1} h={f.pitch:.3g}"
    return Glyph(f"W{n + 1}", "constraints", f.kind, f"W{n + 1} {f.kind}", COLORS["force"], path=pieces(*parts), width=6.0,
                 hover=force_text(n + 1, f, scale, unit), mesh=Mesh.merged(*meshes), label=label, label_at=tip + 0.05 * size * d, direction=d)


def viewpoint(scene: Scene) -> tuple[float, float]:
    """Elevation and azimuth (degrees) from which no freedom or constraint is seen end-on and no labels overlap.

    The pictures' :func:`~mobility.report.plotting.choose_views`, given joints, labels and directions.
    """
    answer = [g for g in scene.glyphs if g.layer != "mechanism"]  # every glyph of the answer is labelled
    important = np.array([scene.centre, *(g.label_at for g in answer)])
    context = np.concatenate([g.points for g in scene.glyphs if g.layer == "mechanism"]).reshape(-1, 3)
    return choose_views(important, np.array([g.direction for g in answer]).reshape(-1, 3), scene.size, count=1, context=context)[0]
