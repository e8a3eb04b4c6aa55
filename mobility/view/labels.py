"""Where the view looks from, how far it zooms, and where each label sits, computed as the browser will draw it.

In plotly's orthographic projection each axis's range maps onto its ``aspectratio`` (scene units),
the camera looks along ``-eye`` and the scene is 2 scene units high, whatever the window's width.
So :class:`Framing` knows where every point lands in pixels, and :func:`place_labels` puts each
label beside its point, covering no other label, as few drawn lines as can be, inside the box's outline.

Examples
--------
>>> import numpy as np
>>> f = Framing.about(np.array([-1.0, -1, -1]), np.array([1.0, 1, 1]), (0.0, 0.0), 500.0)
>>> [round(float(x), 3) for x in f.pixels(np.array([[0.0, 1, 1]]))[0]]   # +y is right, +z is up on the screen
[202.83, -202.83]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Framing", "place_labels", "label_size", "FILL", "WIDEST", "LABEL_FONT"]

FILL = 0.86
"""Share of the scene's height (and of its width) that the box of everything drawn fills at first sight."""

WIDEST = 1.2
"""The narrowest window the first zoom is made for: this many times as wide as high (a page beside its table, a notebook)."""

LABEL_FONT = 13
"""Font size of the labels, pixels."""

_CHAR = 0.62 * LABEL_FONT  # the width of an average character of a sans-serif font, pixels (digits, capitals and '=' are about this)
_PAD = 2 + 1  # the box's padding and border, pixels


def label_size(text: str) -> tuple[float, float]:
    """Width and height (pixels) of a label's box as the browser draws it, a little generous."""
    return _CHAR * len(text) + 2 * _PAD + 4, 1.3 * LABEL_FONT + 2 * _PAD + 2


@dataclass(frozen=True)
class Framing:
    """The first view of a scene: what the axes span, the zoom, the camera, and where points land in pixels.

    ``low``, ``high``: each axis's range (drawing units); ``aspect``: plotly's
    ``aspectratio``; ``right``, ``up``: the screen's directions in the scene;
    ``eye``: the camera's (scene units); ``height``: the scene's, pixels.
    """

    low: tuple[float, float, float]
    high: tuple[float, float, float]
    aspect: tuple[float, float, float]
    right: tuple[float, float, float]
    up: tuple[float, float, float]
    eye: tuple[float, float, float]
    height: float

    @staticmethod
    def about(lower: np.ndarray, upper: np.ndarray, elev_azim: tuple[float, float], height: float, drawn: np.ndarray | None = None) -> "Framing":
        """The framing of everything between ``lower`` and ``upper`` seen from ``elev_azim`` (degrees) in a scene ``height`` pixels high.

        With ``drawn`` (points, shape (n, 3)), they rather than their box's corners fill :data:`FILL`, the box staying in view.
        """
        lower, upper = np.asarray(lower, dtype=float), np.asarray(upper, dtype=float)
        extent = upper - lower
        biggest = float(np.max(extent)) or 1.0
        half = np.maximum(0.5 * extent + 0.03 * biggest, 0.08 * biggest)  # a flat mechanism keeps some depth
        mid = 0.5 * (lower + upper)
        elev, azim = (math.radians(x) for x in elev_azim)
        toward = np.array([math.cos(elev) * math.cos(azim), math.cos(elev) * math.sin(azim), math.sin(elev)])
        right = np.cross(-toward, [0.0, 0.0, 1.0])
        right = right / np.linalg.norm(right) if np.linalg.norm(right) > 1e-9 else np.array([0.0, 1.0, 0.0])
        up = np.cross(right, -toward)
        corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
        across, tall = float(np.max(np.abs(corners @ right))), float(np.max(np.abs(corners @ up)))
        # scene units per drawing unit: the tallest (or widest) part of the box fills FILL of the scene
        zoom = min(FILL / tall, FILL * WIDEST / across)
        if drawn is not None and len(drawn):
            seen = np.asarray(drawn, dtype=float).reshape(-1, 3) - mid
            seen = seen[~np.isnan(seen).any(axis=1)]
            x, y = seen @ right, seen @ up  # about the box's middle, which is the scene's centre
            zoom = min(FILL / max(float(np.max(np.abs(y))), 1e-300), FILL * WIDEST / max(float(np.max(np.abs(x))), 1e-300), 0.9 / tall, 0.9 * WIDEST / across)  # the box, and its ticks, in view
        aspect = tuple(float(f"{2.0 * h * zoom:.6g}") for h in half)
        eye = tuple(round(float(x), 4) for x in 2.0 * toward)
        return Framing(tuple(float(x) for x in mid - half), tuple(float(x) for x in mid + half), aspect,  # type: ignore[arg-type]
                       tuple(float(x) for x in right), tuple(float(x) for x in up), eye, float(height))  # type: ignore[arg-type]

    @property
    def zoom(self) -> float:
        """Scene units per drawing unit."""
        return self.aspect[0] / (self.high[0] - self.low[0])

    def pixels(self, points: np.ndarray) -> np.ndarray:
        """Where ``points`` (drawing units, shape (n, 3)) land: pixels right of and below the scene's centre."""
        mid = 0.5 * (np.array(self.low) + np.array(self.high))
        scene = (np.asarray(points, dtype=float).reshape(-1, 3) - mid) * self.zoom
        return np.stack([scene @ np.array(self.right), -(scene @ np.array(self.up))], axis=1) * (0.5 * self.height)

    def outline(self) -> np.ndarray:
        """The corners of the axes' box, in pixels from the centre (the tick labels are drawn outside their hull)."""
        corners = np.array([[x, y, z] for x in (self.low[0], self.high[0]) for y in (self.low[1], self.high[1]) for z in (self.low[2], self.high[2])])
        return self.pixels(corners)


def _ink(paths: list[np.ndarray], step: float = 3.0) -> np.ndarray:
    """Points every ``step`` pixels (or closer) along polylines (pixels; rows of NaN break a line), all segments at once."""
    starts, ends = [np.zeros((0, 2))], [np.zeros((0, 2))]
    for p in paths:
        a, b = p[:-1], p[1:]
        keep = ~(np.isnan(a).any(axis=1) | np.isnan(b).any(axis=1))
        starts.append(a[keep])
        ends.append(b[keep])
    a, b = np.concatenate(starts), np.concatenate(ends)
    if not len(a):
        return np.zeros((0, 2))
    pieces = np.maximum(np.ceil(np.hypot(*(b - a).T) / step), 1).astype(int)  # samples per segment, less one
    which = np.repeat(np.arange(len(a)), pieces + 1)
    first = np.concatenate([[0], np.cumsum(pieces + 1)[:-1]])
    t = (np.arange(len(which)) - first[which]) / pieces[which]
    return a[which] + t[:, None] * (b - a)[which]


class _InkGrid:
    """Ink counted on a grid of pixels, with its running sums: the ink inside any box in four look-ups."""

    def __init__(self, points: np.ndarray, half_w: float, half_h: float, cell: float = 4.0) -> None:
        self.cell, self.x0, self.y0 = cell, -half_w - 200.0, -half_h - 200.0
        nx, ny = int((2 * half_w + 400) / cell) + 1, int((2 * half_h + 400) / cell) + 1
        counts, _, _ = np.histogram2d(points[:, 0], points[:, 1], bins=(nx, ny),
                                      range=((self.x0, self.x0 + nx * cell), (self.y0, self.y0 + ny * cell)))
        self.sums = np.zeros((nx + 1, ny + 1))
        self.sums[1:, 1:] = counts.cumsum(axis=0).cumsum(axis=1)

    def inside(self, x_lo: np.ndarray, x_hi: np.ndarray, y_lo: np.ndarray, y_hi: np.ndarray) -> np.ndarray:
        """The ink in each box (cells whose corner lies in it)."""
        nx, ny = self.sums.shape[0] - 1, self.sums.shape[1] - 1
        i0 = np.clip(np.ceil((x_lo - self.x0) / self.cell), 0, nx).astype(int)
        i1 = np.clip(np.floor((x_hi - self.x0) / self.cell) + 1, 0, nx).astype(int)
        j0 = np.clip(np.ceil((y_lo - self.y0) / self.cell), 0, ny).astype(int)
        j1 = np.clip(np.floor((y_hi - self.y0) / self.cell) + 1, 0, ny).astype(int)
        s = self.sums
        return s[i1, j1] - s[i0, j1] - s[i1, j0] + s[i0, j0]


def place_labels(framing: Framing, anchors: np.ndarray, texts: list[str], lines: list[np.ndarray], links: list[np.ndarray],
                 width: float) -> list[tuple[float, float]]:
    """Where each label's box centre goes, in pixels from its anchor (plotly's ``ax``, ``ay``), so that labels do not collide.

    ``anchors``: the point each label names (drawing units); ``texts``: the labels, earlier ones getting the
    better places; ``lines``, ``links``: polylines drawn (rows of NaN between pieces), the freedoms and
    constraints, and the mechanism's (covering these costs more); ``width``: the narrowest scene's width
    (pixels), which labels stay inside.  Returns offsets (right, down) in pixels.

    Examples
    --------
    >>> import numpy as np
    >>> f = Framing.about(np.array([-1.0, -1, -1]), np.array([1.0, 1, 1]), (20.0, 30.0), 600.0)
    >>> a = np.zeros((2, 3))   # two labels at one point
    >>> (x1, y1), (x2, y2) = place_labels(f, a, ["R1", "R2"], [], [], 870.0)
    >>> abs(x1 - x2) > 20 or abs(y1 - y2) > 20   # side by side, not on each other
    True
    """
    from scipy.spatial import ConvexHull

    at = framing.pixels(anchors)
    edges = ConvexHull(framing.outline()).equations  # rows (normal, offset): normal . p + offset is minus the depth of p inside
    half_w, half_h = 0.5 * width, 0.5 * framing.height
    drawn = _InkGrid(_ink([framing.pixels(p) for p in lines]), half_w, half_h)
    bars = _InkGrid(_ink([framing.pixels(p) for p in links]), half_w, half_h)
    placed = np.zeros((0, 4))  # boxes: centre x, y, half width, half height
    out = []
    # the places tried about an anchor: 18 directions, 5 gaps between the anchor and the box (nearer first, at equal cost)
    gap_grid, angles = np.meshgrid([10.0, 24.0, 42.0, 66.0, 95.0], np.radians(np.arange(0, 360, 20)), indexing="ij")
    gaps, d = gap_grid.ravel(), np.stack([np.cos(angles.ravel()), np.sin(angles.ravel())], axis=1)
    signs = np.array([[sx, sy] for sx in (-1, 1) for sy in (-1, 1)], dtype=float)
    for (x0, y0), text in zip(at, texts):
        w, h = label_size(text)
        with np.errstate(divide="ignore"):
            reach = np.minimum(0.5 * w / np.abs(d[:, 0]), 0.5 * h / np.abs(d[:, 1]))  # from the box's centre to its edge along d
        centres = np.array([x0, y0]) + (gaps + reach)[:, None] * d
        corners = centres[:, None, :] + signs[None] * [0.5 * w, 0.5 * h]  # (candidates, 4, 2)
        away = np.array([x0, y0]) / (np.hypot(x0, y0) or 1.0)  # from the centre outwards
        cost = 0.02 * gaps - 0.5 * (d @ away)
        # outside the box's outline (where the tick labels are) or the scene: never, unless nothing else is left
        inside = np.all(corners.reshape(-1, 2) @ edges[:, :2].T + edges[:, 2] <= -4.0, axis=1)  # by 4 pixels at least
        cost += 400.0 * np.count_nonzero(~inside.reshape(-1, 4), axis=1)
        cost += 400.0 * np.count_nonzero((np.abs(corners[..., 0]) > half_w - 4) | (np.abs(corners[..., 1]) > half_h - 4), axis=1)
        if len(placed):  # touching or overlapping a placed label: at least 4 pixels apart
            ox = np.minimum(centres[:, None, 0] + 0.5 * w, placed[:, 0] + placed[:, 2]) - np.maximum(centres[:, None, 0] - 0.5 * w, placed[:, 0] - placed[:, 2])
            oy = np.minimum(centres[:, None, 1] + 0.5 * h, placed[:, 1] + placed[:, 3]) - np.maximum(centres[:, None, 1] - 0.5 * h, placed[:, 1] - placed[:, 3])
            near = (ox > -4) & (oy > -4)
            cost += np.sum(near * (1000.0 + 10.0 * np.maximum(ox + 4, 0) * np.maximum(oy + 4, 0)), axis=1)
        for grid, weight in ((drawn, 1.0), (bars, 2.0)):  # the drawn lines under the box, the links' twice
            cost += weight * grid.inside(centres[:, 0] - 0.5 * w - 2, centres[:, 0] + 0.5 * w + 2, centres[:, 1] - 0.5 * h - 2, centres[:, 1] + 0.5 * h + 2)
        best = centres[int(np.argmin(cost))] - [x0, y0]  # the first of the cheapest
        placed = np.vstack([placed, [x0 + best[0], y0 + best[1], 0.5 * w, 0.5 * h]])
        out.append((round(float(best[0]), 1), round(float(best[1]), 1)))
    return out
