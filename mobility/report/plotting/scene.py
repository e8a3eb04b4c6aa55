"""Where the end effector's freedoms and constraints are drawn (no matplotlib).

Free vectors are drawn at the end effector's centre (couples beside it), screws
on their axes. Where a choice is free (the end carrying a rotation mark, a force
arrow's sense, a couple's side), the place farthest from what is drawn is taken.

Examples
--------
>>> import mobility
>>> m = mobility.loads(\'\'\'
... name: slider
... ground: g
... end_effector: s
... joints:
...   - {name: P1, type: P, links: [g, s], axis: [0, 0, 1]}
... \'\'\')
>>> from mobility.report.plotting.sketch import sketch
>>> scene = build_scene(mobility.analyze(m), sketch(m), constraints=True)
>>> len(scene.translations), len(scene.couples), len(scene.forces)
(1, 3, 2)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple, Sequence

import numpy as np

from ...core.frozen import ReadOnlyArrays
from ...core.result import Result, ScrewAxis
from .geometry import perpendiculars, segment_samples
from .sketch import Sketch

__all__ = ["Segment", "AxisGlyph", "ForceGlyph", "Scene", "build_scene", "farthest"]


class Segment(NamedTuple):
    """An arrow from ``start`` to ``end`` (a translation, or a couple's double arrow)."""

    start: np.ndarray
    end: np.ndarray


class AxisGlyph(NamedTuple):
    """A rotation axis: the line, where its mark and label stand, its drawn direction and pitch."""

    start: np.ndarray
    end: np.ndarray
    mark: np.ndarray
    label_at: np.ndarray
    direction: np.ndarray
    pitch: float


class ForceGlyph(NamedTuple):
    """A constraint force (or wrench) line, its arrowhead at ``end``, with its pitch."""

    start: np.ndarray
    end: np.ndarray
    pitch: float


@dataclass(frozen=True, eq=False)
class Scene(ReadOnlyArrays):
    """The glyphs of the end effector's answer, in the global frame and the sketch's drawing units."""

    translations: tuple[Segment, ...]
    rotations: tuple[AxisGlyph, ...]
    forces: tuple[ForceGlyph, ...]
    couples: tuple[Segment, ...]

    def important_points(self) -> list[np.ndarray]:
        """Arrays of the points that must stay apart on the screen: arrow tips, axis ends, marks, labels."""
        out = [s.end[None] for s in self.translations + self.couples]
        out += [np.stack([a.start, a.end, a.mark, a.label_at]) for a in self.rotations]
        out += [np.stack([f.start, f.end]) for f in self.forces]
        return out

    def directions(self) -> np.ndarray:
        """Unit directions of every glyph that must show its length (rows)."""
        dirs = [_unit(s.end - s.start) for s in self.translations + self.couples]
        dirs += [a.direction for a in self.rotations]
        dirs += [_unit(f.end - f.start) for f in self.forces]
        return np.array(dirs).reshape(-1, 3)


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def farthest(options: Sequence[np.ndarray], occupied: list[np.ndarray]) -> int:
    """Index of the option (an array of points) whose nearest occupied point is farthest (ties: the first)."""
    occ = np.concatenate([o.reshape(-1, 3) for o in occupied]) if occupied else np.zeros((0, 3))
    if not len(occ):
        return 0
    gaps = [float(np.min(np.linalg.norm(o.reshape(-1, 3)[:, None, :] - occ[None, :, :], axis=2))) for o in options]
    return int(np.argmax(np.round(gaps, 9)))  # rounding: ties go to the first option


class _Placer:
    """Places glyphs one after the other, each clear of what is already placed."""

    def __init__(self, sk: Sketch) -> None:
        self.size = sk.size
        self.scale = sk.scale
        self.centre = sk.end_effector_centre
        self.points: list[np.ndarray] = [sk.points, self.centre[None]]  # joints, marks, tips and labels
        self.lines: list[np.ndarray] = []  # samples along drawn lines

    def translation(self, t: np.ndarray) -> Segment:
        # either sense, a few lengths: the tip that keeps clear of joints and other tips
        c, size = self.centre, self.size
        tips = [c + s * k * size * t for k in (0.32, 0.25, 0.4) for s in (1.0, -1.0)]
        tip = tips[farthest([x[None] for x in tips], self.points)]
        self.points.append(tip[None])
        self.lines.append(segment_samples(c, tip))
        return Segment(c, tip)

    def rotation(self, a: ScrewAxis) -> AxisGlyph:
        # which end carries the mark and the label, and how long: clear of joints and other labels
        size, half_axis = self.size, 0.5 * self.size
        p = np.asarray(a.point, dtype=float) * self.scale
        d = np.asarray(a.axis, dtype=float)
        options = [(s, k) for k in (1.0, 0.8, 1.25) for s in (1.0, -1.0)]
        marks = [np.stack([p + s * 0.62 * k * half_axis * d, p + s * (k * half_axis + 0.06 * size) * d]) for s, k in options]
        best = farthest(marks, self.points)
        s, k = options[best]
        start, end = p - s * k * half_axis * d, p + s * k * half_axis * d
        self.points.append(marks[best])
        self.lines.append(segment_samples(start, end, 11))
        return AxisGlyph(start, end, marks[best][0], marks[best][1], s * d, a.pitch)

    def force(self, f: ScrewAxis) -> ForceGlyph:
        # shorter than a rotation axis, so both show where they share a line; the arrowhead (and label)
        # at either end, the line a little shorter or longer: clear of marks and joints
        size = self.size
        p = np.asarray(f.point, dtype=float) * self.scale
        d = np.asarray(f.axis, dtype=float)
        options = [(sg, k) for k in (0.28, 0.2, 0.36) for sg in (1.0, -1.0)]
        tips = [np.stack([p + sg * k * size * d, p + sg * (k + 0.06) * size * d]) for sg, k in options]
        sg, k = options[farthest(tips, self.points)]
        start, tip = p - sg * k * size * d, p + sg * k * size * d
        self.points.append(np.stack([tip, tip + 0.06 * size * sg * d]))
        self.lines.append(segment_samples(start, tip))
        return ForceGlyph(start, tip, f.pitch)

    def couple(self, cp: np.ndarray, eyes: np.ndarray | None) -> Segment:
        c, size = self.centre, self.size
        arrow = 0.32 * size
        cp = np.asarray(cp, dtype=float)
        e1, e2 = perpendiculars(cp)
        offsets = [math.cos(k * math.pi / 4) * e1 + math.sin(k * math.pi / 4) * e2 for k in range(8)]
        segs = [segment_samples(c + 0.25 * size * e - 0.5 * arrow * cp, c + 0.25 * size * e + 0.5 * arrow * cp) for e in offsets]
        occupied = np.concatenate([o.reshape(-1, 3) for o in self.points + self.lines])
        clearance = [float(np.min(np.linalg.norm(sg[:, None, :] - occupied[None], axis=2))) / size for sg in segs]
        seen = [1.0 if eyes is None else float(np.min(np.sqrt(np.maximum(0.0, 1.0 - (eyes @ e) ** 2)))) for e in offsets]
        # enough clearance first (beyond 15 % of the scene it no longer matters), then visibility in every view
        k = int(np.argmax([round(4.0 * min(cl, 0.15) + sn, 9) for cl, sn in zip(clearance, seen)]))
        self.points.append(segs[k][[0, -1]])
        self.lines.append(segs[k])
        return Segment(segs[k][0], segs[k][-1])


def build_scene(result: Result, sk: Sketch, constraints: bool, eyes: np.ndarray | None = None) -> Scene:
    """Place the glyphs of ``result``'s freedoms (and, with ``constraints``, its constraint wrenches).

    Given the view directions ``eyes`` (shape (views, 3)), couples stand aside in a direction every view shows.
    """
    placer = _Placer(sk)
    translations = tuple(placer.translation(t) for t in result.translations)
    rotations = tuple(placer.rotation(a) for a in result.rotations)
    forces = tuple(placer.force(f) for f in result.forces) if constraints else ()
    couples = tuple(placer.couple(cp, eyes) for cp in result.couples) if constraints else ()
    return Scene(translations, rotations, forces, couples)
