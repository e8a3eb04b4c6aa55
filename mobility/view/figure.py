"""The scenes of :mod:`mobility.view.scene` as a plotly figure (a plain dict, JSON-ready).

Each glyph is up to four traces in one legend group; each layer has its own legend whose title
switches the layer.  Every trace carries ``meta = {"layer", "key", "frame"}``; every pose is in the
figure, one visible at a time on a slider.  Built without plotly, which only validates or writes it.

Examples
--------
>>> import mobility
>>> from mobility.view.scene import build_scene
>>> m = mobility.load("mechanisms/four_bar.yaml")
>>> r = mobility.analyze(m)
>>> fig = figure_dict([(build_scene(m, r), r, "")])
>>> sorted({t["meta"]["key"] for t in fig["data"] if t["meta"]["layer"] == "freedoms"})
['R1']
>>> fig["layout"]["legend2"]["title"]["text"]
'<b>freedoms (1)</b>'
"""

from __future__ import annotations

import math
from typing import Any, Sequence

import numpy as np

from ..core.result import Result
from ..errors import RequestError
from .describe import margin_text, plotly_text, pose_title
from .labels import LABEL_FONT, WIDEST, Framing, place_labels
from .scene import Glyph, Scene, viewpoint

__all__ = ["figure_dict", "axis_ticks", "LEGENDS", "ELEMENT_ID"]

LEGENDS = {"mechanism": "legend", "freedoms": "legend2", "constraints": "legend3"}
"""The legend of each layer."""

SCENE_WIDTH = 0.8
"""Share of the figure's width the 3D scene takes; the legends stand at its right."""

ELEMENT_ID = "mobility-view"
"""The id of the element that holds the figure in a page."""

_BACKGROUND, _AXIS, _JOINT_AXES = "#ffffff", "#b0bec5", "#37474f"

FAR_FROM_ORIGIN = 100.0
"""A scene whose middle lies farther from the origin than this many half-widths is drawn about its middle:
its coordinates, written with 7 significant digits, then keep about 7 digits of the scene itself."""


def _coords(points: np.ndarray, offset: np.ndarray) -> dict[str, list[float | None]]:
    """x, y, z lists of ``points - offset`` with 7 significant digits (NaN, a break in a line, as None)."""
    columns = (np.asarray(points, dtype=float).reshape(-1, 3) - offset).T
    return {name: [None if math.isnan(v) else float(f"{v:.7g}") for v in column] for name, column in zip("xyz", columns)}


def axis_ticks(low: float, high: float, drawing: float, count: int = 5, offset: float = 0.0) -> dict[str, list]:
    """Ticks of an axis drawn in drawing units (the file's lengths times ``drawing``, less ``offset``), labelled in the file's units.

    About ``count`` round values (1, 2 or 5 times a power of ten), as
    ``{"tickvals", "ticktext"}``; the step is found from logarithms, so that a
    mechanism at 1e200 or 1e-250 gets ticks without leaving the floats.

    Examples
    --------
    >>> t = axis_ticks(-0.6, 0.6, 2.0**-664)   # drawn near 1: about 4.6e199 in the file
    >>> t["ticktext"]
    ['-4e+199', '-2e+199', '0', '2e+199', '4e+199']
    >>> [round(v, 3) for v in t["tickvals"]]
    [-0.523, -0.261, 0.0, 0.261, 0.523]
    >>> axis_ticks(-300.0, 300.0, 1.0, offset=3e7)["ticktext"]   # drawn about 0, at 3e7 in the file
    ['29999700', '29999800', '29999900', '30000000', '30000100', '30000200', '30000300']
    """
    span = (high - low) / count  # drawing units
    exponent = math.log10(span) - math.log10(drawing)  # log10 of the step in the file's units
    power = math.floor(exponent)
    mantissa = 10.0 ** (exponent - power)
    nice = 1.0 if mantissa < 1.5 else 2.0 if mantissa < 3.5 else 5.0 if mantissa < 7.5 else 10.0
    step_file = nice * 10.0**power
    step = step_file * drawing
    first, last = math.ceil((low + offset) / step), math.floor((high + offset) / step)
    values = [k * step - offset for k in range(first, last + 1)]
    digits = 3 + math.ceil(math.log10(max(abs(first), abs(last), 1)))  # round multiples of the step, told apart
    texts = ["0" if k == 0 else f"{k * step_file:.{digits}g}" for k in range(first, last + 1)]
    return {"tickvals": values, "ticktext": texts}


def _glyph_traces(g: Glyph, frame: int, visible: bool, offset: np.ndarray) -> list[dict[str, Any]]:
    """The traces of one glyph, drawn less ``offset``; the first one carries its legend entry."""
    common = {"legend": LEGENDS[g.layer], "legendgroup": g.key, "name": g.name, "visible": visible, "meta": {"layer": g.layer, "key": g.key, "frame": frame}}
    traces: list[dict[str, Any]] = []
    if len(g.points):  # first, so that a joint's legend entry shows its marker
        outline = "#263238" if g.kind == "joint" else g.color
        traces.append({"type": "scatter3d", "mode": "markers", **_coords(g.points, offset),
                       "marker": {"symbol": g.symbol, "size": 7 if g.kind == "joint" else 5, "color": g.color, "line": {"color": outline, "width": 2}},
                       "hoverinfo": "text", "hovertext": list(g.point_hover)})
    if len(g.path):
        color = _JOINT_AXES if g.kind == "joint" else g.color
        traces.append({"type": "scatter3d", "mode": "lines", **_coords(g.path, offset), "line": {"color": color, "width": g.width},
                       "hoverinfo": "text", "hovertext": g.hover, "connectgaps": False})
    if g.mesh is not None:
        v, f = g.mesh.vertices, g.mesh.faces
        traces.append({"type": "mesh3d", **_coords(v, offset), "i": f[:, 0].tolist(), "j": f[:, 1].tolist(), "k": f[:, 2].tolist(),
                       "color": g.color, "opacity": g.opacity, "flatshading": True, "hoverinfo": "text", "hovertext": g.hover,
                       "lighting": {"ambient": 0.65, "diffuse": 0.6, "specular": 0.1}})
    for k, t in enumerate(traces):
        t.update(common)
        t["showlegend"] = k == 0
    return traces


def _nearest(points: np.ndarray, to: np.ndarray) -> np.ndarray:
    """The row of ``points`` (rows of NaN skipped) nearest ``to``."""
    drawn = points[~np.isnan(points).any(axis=1)]
    return drawn[int(np.argmin(np.linalg.norm(drawn - to, axis=1)))]


def _annotations(scene: Scene, framing: Framing, offset: np.ndarray, width: float) -> list[dict[str, Any]]:
    """The labels of ``scene``'s freedoms and constraints as plotly scene annotations, placed apart (:func:`place_labels`)."""
    labelled = [(g, g.label_at) for g in scene.glyphs if g.label and g.label_at is not None]
    if not labelled:
        return []
    # each label names the end of its glyph (its arrow's tip, its axis's end) nearest where the pictures write it
    anchors = np.array([_nearest(g.path if len(g.path) else at[None], at) for g, at in labelled]) - offset
    lines = [g.path - offset for g in scene.glyphs if g.layer != "mechanism" and len(g.path)]
    links = [g.path - offset for g in scene.glyphs if g.layer == "mechanism" and len(g.path)]
    places = place_labels(framing, anchors, [g.label for g, _ in labelled], lines, links, width)
    out = []
    for (g, _), at, (ax, ay) in zip(labelled, anchors, places):
        x, y, z = (float(f"{v:.7g}") for v in at)
        out.append({"x": x, "y": y, "z": z, "text": plotly_text(g.label), "name": g.key, "showarrow": True, "arrowhead": 0,
                    "arrowwidth": 1.2, "arrowcolor": g.color, "ax": ax, "ay": ay, "xanchor": "center", "yanchor": "middle",
                    "font": {"color": g.color, "size": LABEL_FONT}, "bgcolor": "rgba(255,255,255,0.9)", "bordercolor": g.color,
                    "borderwidth": 1, "borderpad": 2, "hovertext": g.hover, "captureevents": False})
    return out


def _title(result: Result, label: str, frames: int) -> str:
    return f"{plotly_text(pose_title(result, label))}<br><sup>{margin_text(result)}" + ("" if frames == 1 else "  ·  use the slider to walk through the poses") + "</sup>"


def figure_dict(frames: Sequence[tuple[Scene, Result, str]], *, height: int = 720, titled: bool = True) -> dict[str, Any]:
    """The plotly figure of one or several poses.

    ``frames``: each pose's scene, analysis and slider label; ``titled``: whether
    the figure writes its title (a page whose header says it all leaves it out).
    Returns ``{"data": [...], "layout": {...}}``, JSON-serialisable.
    """
    if not frames:
        raise RequestError("a view needs at least one pose")
    lower = np.min([s.lower for s, _, _ in frames], axis=0)
    upper = np.max([s.upper for s, _, _ in frames], axis=0)
    mid, half = 0.5 * (lower + upper), 0.55 * float(np.max(upper - lower))
    # far from the origin for its size, the scene is drawn about its middle (7 digits would not resolve it), ticks in the file's numbers
    offset = mid if float(np.max(np.abs(mid))) > FAR_FROM_ORIGIN * half else np.zeros(3)
    data = [t for k, (scene, _, _) in enumerate(frames) for g in scene.glyphs for t in _glyph_traces(g, k, k == 0, offset)]
    first_scene, first_result, first_label = frames[0]
    unit, drawing = first_result.length_unit, first_scene.scale
    margin = {"l": 10, "r": 10, "t": 70 if titled else 10, "b": 10}
    bottom = 0.16 if len(frames) > 1 else 0.0  # room for the slider
    scene_height = (1.0 - bottom) * (height - margin["t"] - margin["b"])
    drawn = [np.concatenate([g.extent() for g in s.glyphs]) for s, _, _ in frames]
    framing = Framing.about(lower - offset, upper - offset, viewpoint(first_scene), scene_height, np.concatenate(drawn) - offset)
    axis = {
        name: {"range": [float(f"{framing.low[i]:.7g}"), float(f"{framing.high[i]:.7g}")], "title": {"text": f"{name} ({unit})" if unit else name},
               "backgroundcolor": _BACKGROUND, "gridcolor": "#eceff1", "zerolinecolor": _AXIS, "showspikes": False,
               **(axis_ticks(framing.low[i], framing.high[i], drawing, offset=float(offset[i])) if drawing != 1.0 or offset[i] else {})}
        for i, name in enumerate("xyz")
    }
    labels = [_annotations(scene, framing, offset, WIDEST * scene_height) for scene, _, _ in frames]
    layout: dict[str, Any] = {
        "title": {"text": _title(first_result, first_label, len(frames)) if titled else "", "x": 0.01, "xanchor": "left", "font": {"size": 16}},
        "height": height, "margin": margin, "paper_bgcolor": _BACKGROUND, "uirevision": "mobility",
        "scene": {**{f"{n}axis": a for n, a in axis.items()}, "aspectmode": "manual", "aspectratio": dict(zip("xyz", framing.aspect)),
                  "camera": {"eye": dict(zip("xyz", framing.eye)), "up": {"x": 0, "y": 0, "z": 1}, "projection": {"type": "orthographic"}},
                  "annotations": labels[0], "domain": {"x": [0.0, SCENE_WIDTH], "y": [bottom, 1.0]}},
    }
    counts = {"mechanism": "", "freedoms": f" ({first_result.dof})", "constraints": f" ({6 - first_result.dof})"}
    # the legends one under the other at the right of the scene, each as high as its entries
    plot_height = height - margin["t"] - margin["b"]
    top = 1.0
    for layer, name in LEGENDS.items():
        entries = len({g.key for s, _, _ in frames for g in s.layer(layer)})
        layout[name] = {"title": {"text": f"<b>{layer}{counts[layer] if len(frames) == 1 else ''}</b>", "side": "top"}, "orientation": "v",
                        "x": SCENE_WIDTH + 0.01, "xanchor": "left", "y": top, "yanchor": "top", "groupclick": "togglegroup", "titleclick": "toggle",
                        "titledoubleclick": "toggleothers", "bgcolor": "rgba(255,255,255,0.8)"}
        top -= (30 + 29 * entries) / plot_height
    if len(frames) > 1:
        steps = [{"label": plotly_text(label) if label else str(k + 1), "method": "update",
                  "args": [{"visible": [t["meta"]["frame"] == k for t in data]}, {"title.text": _title(result, label, len(frames)), "scene.annotations": labels[k]}]}
                 for k, (_, result, label) in enumerate(frames)]
        # inset so that the labels of the end steps, centred on them, stay on the page
        layout["sliders"] = [{"active": 0, "steps": steps, "x": 0.05, "len": 0.7, "y": 0.1, "yanchor": "top",
                              "currentvalue": {"prefix": "pose: ", "font": {"size": 13}}, "pad": {"t": 0, "b": 0}}]
    return {"data": data, "layout": layout}
