"""The picture of a mechanism at its pose with its end effector's freedoms and constraints (:func:`plot_mechanism`).

Every drawn answer carries a ``gid`` (``"mobility:translation:0"``,
``"mobility:rotation-axis:1"``, ``"mobility:force:0"``, ``"mobility:couple:0"``,
...), so programs and tests can read the picture back.
"""

from __future__ import annotations

import math
import textwrap
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from ...core.analysis import analyze
from ...core.model import Mechanism, require_mechanism
from ...core.validation import require_bool, require_integer
from ...core.result import Result, require_result_of
from ...errors import RequestError, clipped
from ...core.tolerance import DEFAULT_TOLERANCE, Tolerance, require_tolerance
from .backend import new_figure, require_figsize, require_matplotlib
from .geometry import SAME_POINT, unique_points
from .glyphs import arrow, cone, draw_joints, draw_links, rotation_mark, triad
from .scene import Scene, build_scene
from .sketch import Sketch, sketch
from .style import COLORS, JOINT_STYLE, MAX_TITLE, drawn_name
from .views import MAX_VIEWS, choose_views, thinned, view_axes

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["plot_mechanism", "MAX_TITLE"]


def plot_mechanism(mechanism: Mechanism, result: Result | None = None, *, constraints: bool = False, views: int | Sequence[tuple[float, float]] = 2,
                   labels: bool = True, legend: bool = True, title: str | None = None, figsize: tuple[float, float] | None = None,
                   tol: Tolerance = DEFAULT_TOLERANCE) -> "Figure":
    """Draw ``mechanism`` at its pose with the end effector's freedoms (and constraints).

    Parameters
    ----------
    result : Result, optional
        Its analysis at this pose; computed with ``tol`` when not given.
    constraints : bool
        Also draw the constraint wrenches: force lines (red, ``W``) and couples
        (purple double arrows, ``C``), numbered as in the text report.
    views : int or sequence of (elev, azim)
        Number of viewpoints chosen by :func:`~mobility.report.plotting.views.choose_views`,
        up to :data:`~mobility.report.plotting.views.MAX_VIEWS`, or the viewpoints themselves (degrees).
    labels : bool
        Write joint names (up to 40 joints).
    title : str, optional
        Default: name, DOF, pattern and mobility. Wrapped to the figure's width;
        cut (``...``) beyond :data:`MAX_TITLE` characters or the lines it has room for.
    figsize : (width, height) in inches, optional
        Each from 1 to 30 (:data:`~mobility.report.plotting.backend.FIGSIZE_RANGE`).

    Returns
    -------
    matplotlib.figure.Figure
        One orthographic 3D axes per view.

    Raises
    ------
    PlottingUnavailableError
        When matplotlib is not installed.
    RequestError
        When an argument is out of its range (each named), or ``result`` is not a :class:`Result` of ``mechanism``.
    """
    mechanism = require_mechanism(mechanism, "plot_mechanism")
    tol = require_tolerance(tol, "plot_mechanism")
    count, given = _views_asked(views)
    for key, flag in (("constraints", constraints), ("labels", labels), ("legend", legend)):
        require_bool(flag, caller="plot_mechanism", argument=key)
    if title is not None and not isinstance(title, str):
        raise RequestError(caller="plot_mechanism", argument="title", expected="a str or None", got=type(title).__name__)
    size = require_figsize(figsize, "plot_mechanism")
    r = require_result_of(mechanism, result, "plot_mechanism") if result is not None else None
    require_matplotlib()
    r = r if r is not None else analyze(mechanism, tol=tol)
    sk = sketch(mechanism)
    scene = build_scene(r, sk, bool(constraints))
    answer = np.concatenate([sk.end_effector_centre[None], *scene.important_points()])
    view_list = given if count is None else _chosen_views(sk, answer, scene.directions(), count)
    if scene.couples:  # place the couples again, now that the views are known
        scene = build_scene(r, sk, bool(constraints), eyes=np.array([view_axes(e, a)[0] for e, a in view_list]))
    extent = np.concatenate([sk.points, answer])
    fig = new_figure(size or (6.2 * len(view_list), 6.6))
    for k, view in enumerate(view_list):
        _draw_view(_view_axes3d(fig, k, view_list, extent, sk.size), mechanism, r, sk, scene, bool(labels), view)
    if legend:
        _legend(fig, mechanism, sk, scene)
    unit = f", lengths in {r.length_unit}" if r.length_unit else ""
    _title(fig, title if title is not None else f"{drawn_name(r.name)}: end effector {r.dof} DOF ({r.pattern}), mobility {r.mobility}{unit}", bool(legend))
    return fig


def _views_asked(views: Any) -> tuple[int | None, list[tuple[float, float]]]:
    """``(count, [])`` for a number of views to choose, ``(None, viewpoints)`` for the viewpoints given; else a :class:`RequestError`.

    Examples
    --------
    >>> import numpy as np
    >>> _views_asked(np.int64(2)), _views_asked([(30, 40)])
    ((2, []), (None, [(30.0, 40.0)]))
    >>> _views_asked(0)
    Traceback (most recent call last):
    mobility.errors.RequestError: plot_mechanism: views: expected a number of views from 1 to 3, or a list of (elev, azim) pairs in degrees, got 0
    """
    expected = f"a number of views from 1 to {MAX_VIEWS}, or a list of (elev, azim) pairs in degrees"
    try:
        return require_integer(views, expected, caller="plot_mechanism", argument="views", low=1, high=MAX_VIEWS), []
    except RequestError:
        try:
            given = [] if isinstance(views, (str, bytes, bool, np.bool_)) else [(float(e), float(a)) for e, a in views]
        except (TypeError, ValueError):  # not iterable, not pairs, not numbers
            given = []
        if given and all(math.isfinite(e) and math.isfinite(a) for e, a in given):
            return None, given
        raise


def _chosen_views(sk: Sketch, answer: np.ndarray, directions: np.ndarray, count: int) -> list[tuple[float, float]]:
    """Views where the answer shows best; the joints and links matter too, but less (the freedoms are listed twice)."""
    dirs = []
    for idx in sk.link_joints.values():
        u = unique_points(sk.points[list(idx)], SAME_POINT * sk.size)
        if len(u) == 2:
            dirs.append((u[1] - u[0]) / np.linalg.norm(u[1] - u[0]))
    link_dirs = thinned(np.array(dirs).reshape(-1, 3))
    return choose_views(answer, np.concatenate([directions, directions, link_dirs]), sk.size, count, context=sk.points)


def _view_axes3d(fig: "Figure", k: int, view_list: list[tuple[float, float]], extent: np.ndarray, size: float) -> Any:
    """The ``k``-th of the orthographic 3D axes, one per view, each framing the whole scene as a cube."""
    lo, hi = extent.min(axis=0), extent.max(axis=0)
    mid = 0.5 * (lo + hi)
    half = 0.5 * float(np.max(hi - lo)) * 1.08 + 0.02 * size
    elev, azim = view_list[k]
    ax = fig.add_subplot(1, len(view_list), k + 1, projection="3d")
    ax.set_proj_type("ortho")
    ax.view_init(elev=elev, azim=azim)
    for set_limits, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid):
        set_limits(m - half, m + half)
    ax.set_box_aspect((1, 1, 1), zoom=1.25)
    ax.set_axis_off()
    ax.set_title(f"view {k + 1}: elev {elev:g}°, azim {azim:g}°", fontsize=9, color="#455a64")
    return ax


def _draw_view(ax: Any, mechanism: Mechanism, r: Result, sk: Sketch, scene: Scene, labels: bool, view: tuple[float, float]) -> None:
    """The mechanism and the glyphs of its answer in one view."""
    size = sk.size
    head = 0.045 * size
    triad(ax, *view)
    draw_links(ax, mechanism, sk)
    draw_joints(ax, mechanism, sk, labels, view)
    ax.scatter(*sk.end_effector_centre, marker="x", s=30, color=COLORS["end_effector"], depthshade=False, gid="mobility:end-effector-centre")
    for i, (s, e) in enumerate(scene.translations):
        arrow(ax, s, e, COLORS["translation"], f"mobility:translation:{i}", head=head, lw=2.4)
        ax.text(*(e + 0.03 * size * (e - s) / np.linalg.norm(e - s)), f"T{i + 1}", color=COLORS["translation"], fontsize=9, fontweight="bold", zorder=1e4)
    unit = f" {r.length_unit}" if r.length_unit else ""
    for i, g in enumerate(scene.rotations):
        ax.plot(*np.stack([g.start, g.end]).T, color=COLORS["rotation"], lw=1.8, ls=(0, (8, 3, 2, 3)), gid=f"mobility:rotation-axis:{i}")
        rotation_mark(ax, g.mark, r.rotations[i].axis, 0.06 * size, COLORS["rotation"], f"mobility:rotation-mark:{i}")
        text = f"R{i + 1}" if g.pitch == 0 else f"R{i + 1}\nh = {g.pitch:.3g}{unit}/rad"
        ax.text(*g.label_at, text, color=COLORS["rotation"], fontsize=9, fontweight="bold", gid=f"mobility:rotation-label:{i}", ha="center", va="center", zorder=1e4)
    k0 = len(r.couples)
    for i, force in enumerate(scene.forces):
        d = (force.end - force.start) / np.linalg.norm(force.end - force.start)
        ax.plot(*np.stack([force.start, force.end]).T, color=COLORS["force"], lw=2.6, alpha=0.8, gid=f"mobility:force:{i}")
        cone(ax, force.end, d, head * 0.8, COLORS["force"], f"mobility:force:{i}:head")
        text = f"W{k0 + i + 1}" if force.pitch == 0 else f"W{k0 + i + 1}  h = {force.pitch:.3g}"
        ax.text(*(force.end + 0.03 * size * d), text, color=COLORS["force"], fontsize=8.5, gid=f"mobility:force-label:{i}", zorder=1e4)
    for i, (s, e) in enumerate(scene.couples):
        arrow(ax, s, e, COLORS["couple"], f"mobility:couple:{i}", head=head * 0.8, both=True, lw=1.8, ls="--")
        ax.text(*(e + 0.03 * size * (e - s) / np.linalg.norm(e - s)), f"C{i + 1}", color=COLORS["couple"], fontsize=8.5, zorder=1e4)


def _legend(fig: "Figure", mechanism: Mechanism, sk: Sketch, scene: Scene) -> None:
    """One entry per joint type present, the link roles, and each kind of glyph drawn."""
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], ls="", marker=st["marker"], markersize=7, markerfacecolor=st["facecolor"], markeredgecolor="white" if t == "S" else "black",
                      label=st["label"]) for t, st in JOINT_STYLE.items() if t in sk.types]
    handles += [Line2D([], [], color=COLORS["ground"], lw=4, label="ground"), Line2D([], [], color=COLORS["end_effector"], lw=3, label="end effector")]
    if any(x not in (mechanism.ground, mechanism.end_effector) for x in sk.link_joints):
        handles.append(Line2D([], [], color=COLORS["link"], lw=2.6, label="link"))
    if scene.translations:
        handles.append(Line2D([], [], color=COLORS["translation"], lw=2.4, marker=">", markevery=[1], label="translation T"))
    if scene.rotations:
        handles.append(Line2D([], [], color=COLORS["rotation"], lw=1.8, ls=(0, (8, 3, 2, 3)), label="rotation axis R (h: pitch)"))
    if scene.forces:
        handles.append(Line2D([], [], color=COLORS["force"], lw=1.6, label="constraint force W"))
    if scene.couples:
        handles.append(Line2D([], [], color=COLORS["couple"], lw=1.8, ls="--", label="constraint couple C"))
    fig.legend(handles=handles, loc="lower center", ncol=max(2, min(len(handles), int(fig.get_figwidth() / 1.75))), frameon=False, fontsize=8.5)


def _title(fig: "Figure", text: str, legend: bool) -> None:
    """The title, wrapped to the figure's width and cut to the lines that leave half the height to the views, with room kept for it and the legend."""
    width = max(40, int(fig.get_figwidth() * 10.5))
    most = 1 + int(0.4 * fig.get_figheight() / 0.22)  # lines whose room (0.22 inch each) keeps the top at 0.5 or above
    lines = textwrap.wrap(clipped(text, MAX_TITLE), width=width) or [""]
    if len(lines) > most:
        lines = lines[:most]
        lines[-1] = clipped(lines[-1] + " ...", width)
    wrapped = "\n".join(lines)
    fig.suptitle(wrapped, fontsize=11)
    top = 0.9 - 0.22 * wrapped.count("\n") / fig.get_figheight()  # room for a title on several lines
    fig.subplots_adjust(left=0.0, right=1.0, top=top, bottom=0.1 if legend else 0.02, wspace=0.0)
