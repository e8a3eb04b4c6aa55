"""Pictures of a sweep: a curve (one coordinate), a map (two) or slices of a 3-D grid.

What each picture draws: docs/sweeps.md, "Output" (``--plot``).  Every drawn answer
carries a ``gid`` (``"mobility:sweep:curve"``, ``...:map``, ``...:regions``, ``...:singular``,
``...:unassembled``, ``...:good-transmission``).

Examples
--------
>>> import mobility
>>> r = mobility.sweep(mobility.load("mechanisms/parallelogram.yaml"), ["O1=0:360:37"])
>>> fig = plot_sweep(r)
>>> len([a for a in fig.axes[0].get_children() if a.get_gid() == "mobility:sweep:singular"])
2
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..core.tolerance import SAME_GRID_VALUE
from ..errors import RequestError, clipped, counted
from ..sweeps import SweepAxis, SweepResult
from ..sweeps.grid import whole_turns
from .plotting.backend import new_figure, require_matplotlib
from .plotting.style import MAX_TITLE, drawn_name
from .text import fmt_number

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["plot_sweep", "require_drawable", "colour_of", "choose_slices", "MAX_SLICES"]

MAX_SLICES = 6
"""Slices drawn of a 3-D grid."""


def colour_of(result: SweepResult) -> tuple[np.ndarray, str]:
    """The quantity a map shows, per pose (NaN where not assembled), and its label.

    With inputs, the actuation conditioning κ; else the rank margin, a pose that
    gains a freedom (whose margin is another rank's) shown at the map's smallest.
    """
    if result.actuated:
        return np.where(result.assembled, result.conditioning, np.nan), f"actuation conditioning κ ({', '.join(result.actuated)})"
    with np.errstate(divide="ignore"):
        margin = np.log10(np.where(result.assembled, result.smallest_kept, np.nan))
    gained = _gains(result)
    regular = margin[~gained & np.isfinite(margin)]
    if gained.any() and regular.size:
        margin[gained] = regular.min()
    return margin, "rank margin: log10 smallest kept relative singular value"


def _gains(result: SweepResult) -> np.ndarray:
    """Poses that gain a freedom over the regular answer (their rank margin belongs to another rank)."""
    out = np.zeros(result.size, dtype=bool)
    if result.regular is not None:
        dof0, _, mob0, _ = result.regular
        out = result.assembled & ((result.dof > dof0) | (result.mobility > mob0))
    return out


def _colour_limits(result: SweepResult, colour: np.ndarray) -> tuple[float, float]:
    """The ends of the colour scale: κ from 0 (an actuation singularity is always the darkest), the margin over its range."""
    finite = colour[np.isfinite(colour)]
    if not finite.size:
        return (0.0, 1.0)
    low, high = 0.0 if result.actuated else float(finite.min()), float(finite.max())
    return (low, high if high > low else low + 1.0)


def _answers(result: SweepResult) -> tuple[np.ndarray, list[str]]:
    """A code per pose for its answer (-1: not assembled) and a label per code."""
    codes = np.full(result.size, -1)
    seen: dict = {}  # each answer -> its code, in the order of first appearance
    for i, c in enumerate(result.classes()):
        if c is not None:
            codes[i] = seen.setdefault(c, len(seen))
    return codes, [f"DOF {dof} {pattern}, M={mobility}" + (f", {verdict}" if verdict else "")
                   for dof, pattern, mobility, verdict in seen]


def require_drawable(coordinates: int, what: str = "") -> None:
    """Refuse a picture of ``coordinates`` varied coordinates that cannot be drawn, before the sweep is computed.

    A :class:`RequestError` for more than three (``what`` put in front of the message), a
    :class:`~mobility.errors.PlottingUnavailableError` when matplotlib is not installed.

    Examples
    --------
    >>> require_drawable(4, "--plot out.png: ")
    Traceback (most recent call last):
    ...
    mobility.errors.RequestError: --plot out.png: a sweep of 4 coordinates cannot be drawn; plots show 1 (curve), 2 (map) or 3 (slices)
    """
    if coordinates > 3:
        raise RequestError(f"{what}a sweep of {counted(coordinates, 'coordinate')} cannot be drawn; plots show 1 (curve), 2 (map) or 3 (slices)")
    require_matplotlib()


def plot_sweep(result: SweepResult, *, title: str | None = None) -> "Figure":
    """A picture of ``result``: a curve, a map or slices (docs/sweeps.md, "Output"), refused as :func:`require_drawable` does.

    The default title is the mechanism's name; names are cut to
    :data:`~mobility.report.plotting.style.MAX_LABEL` characters (``title``, a str, to
    :data:`~mobility.report.plotting.style.MAX_TITLE`).
    """
    if title is not None and not isinstance(title, str):
        raise RequestError(caller="plot_sweep", argument="title", expected="a str or None", got=type(title).__name__)
    k = len(result.axes)
    require_drawable(k)
    title = drawn_name(result.name) if title is None else clipped(title, MAX_TITLE)
    if k == 1:
        fig = _curve(result, title)
    elif k == 2:
        fig = new_figure((7.5, 6.0), layout="constrained")
        ax = fig.add_subplot()
        mesh = _map(ax, result, np.arange(result.size).reshape(result.shape), None)
        fig.colorbar(mesh, ax=ax, label=colour_of(result)[1])
        ax.set_title(title)
    else:
        fig = _slices(result, title)
    if not result.assembled.any():
        fig.text(0.5, 0.5, "no pose of the grid could be assembled", ha="center", va="center", fontsize="large",
                 bbox={"facecolor": "white", "edgecolor": "0.5"}, gid="mobility:sweep:nothing")
    return fig


def _axis_label(axis: SweepAxis) -> str:
    """``"O1 [deg]"``, the name cut to :data:`~mobility.report.plotting.style.MAX_LABEL` characters (a name may be megabytes long)."""
    return f"{drawn_name(axis.name)} [{axis.unit}]" if axis.unit else drawn_name(axis.name)


UNASSEMBLED = "0.85"
"""The grey of poses not assembled (curves: shaded spans; maps: cells)."""


def _unassembled_patch(label: str = "not assembled (grey)") -> Any:
    """A legend entry for the grey of poses not assembled."""
    from matplotlib.patches import Patch

    return Patch(facecolor=UNASSEMBLED, edgecolor="0.6", label=label)


def _curve(result: SweepResult, title: str) -> "Figure":
    from matplotlib.ticker import MaxNLocator

    axis = result.axes[0]
    x = axis.values
    fig = new_figure((8.0, 6.0), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    ok = result.assembled
    dof = np.where(ok, result.dof, np.nan).astype(float)
    mob = np.where(ok, result.mobility, np.nan).astype(float)
    top.step(x, dof, where="mid", color="tab:blue", label="end-effector DOF", gid="mobility:sweep:curve")
    top.step(x, mob, where="mid", color="tab:orange", linestyle="--", label="mobility", gid="mobility:sweep:curve")
    top.set_ylabel("freedoms")
    top.yaxis.set_major_locator(MaxNLocator(integer=True))  # freedoms are whole numbers, also when the curve is flat
    counts = np.concatenate([result.dof[ok], result.mobility[ok]])
    low, high = (int(counts.min()), int(counts.max())) if counts.size else (0, 1)
    top.set_ylim(max(low - 1, 0) - 0.25, high + 1.25)
    top.set_title(title)
    with np.errstate(divide="ignore"):
        # broken at a pose that gains a freedom: its margin is that of another rank (the red line marks it)
        bottom.semilogy(x, np.where(ok & ~_gains(result), result.smallest_kept, np.nan), color="tab:green", label="rank margin (smallest kept)", gid="mobility:sweep:curve")
    if result.actuated:
        bottom.semilogy(x, np.where(ok & (result.conditioning > 0), result.conditioning, np.nan), color="tab:purple", label="actuation conditioning κ", gid="mobility:sweep:curve")
    if result.has_transmission:
        bottom.semilogy(x, np.where(ok & (result.lti > 0), result.lti, np.nan), color="tab:brown", label=f"local transmission index LTI (good >= {result.good_threshold:g})", gid="mobility:sweep:curve")
    shown = np.concatenate([np.asarray(line.get_ydata(), dtype=float) for line in bottom.get_lines()] or [np.zeros(0)])
    shown = shown[np.isfinite(shown) & (shown > 0)]
    if shown.size:  # at least a factor of 4: a flat curve would leave the log scale a range of 1e-16 (no ticks, a tilted line)
        bottom.set_ylim(shown.min() / 2.0, min(shown.max() * 2.0, 10.0))
    bottom.set_xlabel(_axis_label(axis))
    bottom.set_ylabel("relative value")
    step = (x[1] - x[0]) if len(x) > 1 else 1.0
    for panel in (top, bottom):
        for i in np.flatnonzero(~ok):
            panel.axvspan(x[i] - step / 2, x[i] + step / 2, color=UNASSEMBLED, lw=0, gid="mobility:sweep:unassembled")
    for p in result.singular:
        top.axvline(p.values[0], color="tab:red", lw=1.0, gid="mobility:sweep:singular")
        bottom.axvline(p.values[0], color="tab:red", lw=1.0)
    if result.singular:
        top.plot([], [], color="tab:red", label="singular pose")
    handles, _ = top.get_legend_handles_labels()
    if not ok.all():
        handles.append(_unassembled_patch("not assembled (grey spans)"))
    top.legend(handles=handles, loc="best", fontsize="small")
    bottom.legend(loc="best", fontsize="small")
    return fig


def _map(ax: Any, result: SweepResult, index: np.ndarray, limits: tuple[float, float] | None) -> Any:
    """One 2-D map of the poses ``index`` (a 2-D array of flat indices; rows: first coordinate)."""
    a0, a1 = result.axes[0], result.axes[1]
    x, y = a0.values, a1.values
    colour, _ = colour_of(result)
    codes, labels = _answers(result)
    z = colour[index]
    if limits is None:
        limits = _colour_limits(result, z)
    matplotlib = require_matplotlib()
    cmap = matplotlib.colormaps["viridis"].with_extremes(bad=UNASSEMBLED)
    mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(z).T, shading="nearest", cmap=cmap, vmin=limits[0], vmax=limits[1], gid="mobility:sweep:map")
    missing = ~result.assembled[index]
    if missing.any():
        grey = matplotlib.colors.ListedColormap([UNASSEMBLED])
        ax.pcolormesh(x, y, np.ma.masked_where(~missing, np.ones(missing.shape)).T, shading="nearest", cmap=grey, vmin=0, vmax=1, gid="mobility:sweep:unassembled")
    code = codes[index].astype(float)
    present = np.unique(code[code >= 0])
    if present.size > 1 and len(x) > 1 and len(y) > 1:
        ax.contour(x, y, np.ma.masked_less(code, 0).T, levels=np.arange(-0.5, present.max() + 1.0), colors="white", linewidths=1.2).set_gid("mobility:sweep:regions")
    if result.has_transmission and len(x) > 1 and len(y) > 1:
        good = np.where(result.assembled[index], np.nan_to_num(np.asarray(result.lti, dtype=float)[index], nan=0.0), 0.0)
        if (good >= result.good_threshold).any() and (good < result.good_threshold).any():
            ax.contour(x, y, good.T, levels=[result.good_threshold], colors="black", linestyles="dashed", linewidths=1.2).set_gid("mobility:sweep:good-transmission")
            ax.plot([], [], color="black", linestyle="dashed", label=f"good transmission: LTI >= {result.good_threshold:g} (dashed outline)")
    singular = [p.index for p in result.singular]
    where = np.isin(index, singular)
    if where.any():
        i, j = np.nonzero(where)
        ax.scatter(x[i], y[j], marker="x", color="tab:red", s=28, label="singular pose", gid="mobility:sweep:singular", zorder=3)
    if present.size > 1:
        ax.scatter([], [], marker="s", color="none", edgecolor="0.3", label="regions (white outlines): " + "; ".join(labels[c] for c in present.astype(int)))
    ax.set_xlabel(_axis_label(a0))
    ax.set_ylabel(_axis_label(a1))
    handles, _ = ax.get_legend_handles_labels()
    if missing.any():
        handles.append(_unassembled_patch())
    if handles:
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize="x-small", ncol=1, frameon=False)
    return mesh


def _at_file_pose(axis: SweepAxis) -> int | None:
    """The index of the axis's value at the file's pose (displacement 0, or whole turns of an angle that wraps), if it has one."""
    k = axis.anchor
    value = axis.values[k]
    return k if abs(value - float(whole_turns(value, axis.period))) <= SAME_GRID_VALUE * axis.step else None


def _spread(candidates: list[int], chosen: list[int], count: int, size: int) -> list[int]:
    """``count`` of ``candidates`` (indices ``0 .. size - 1``) nearest evenly spaced places, the places nearest those ``chosen`` already left out."""
    places = np.linspace(0, size - 1, count + len(chosen)).tolist() if count > 0 else []
    for i in chosen:
        if places:
            places.remove(min(places, key=lambda x: abs(x - i)))
    picked: list[int] = []
    left = list(candidates)
    for place in places:
        if not left:
            break
        best = min(left, key=lambda i: (abs(i - place), i))
        picked.append(best)
        left.remove(best)
    return picked


def choose_slices(result: SweepResult, most: int = MAX_SLICES) -> tuple[tuple[int, ...], str]:
    """The indices of the values of the third coordinate drawn as slices (increasing), and a note saying which (for the title).

    Preferred, in turn: the file's pose, the values holding singular poses,
    then values spread over the range.

    Examples
    --------
    >>> import mobility
    >>> r = mobility.sweep(mobility.load("mechanisms/3prs.yaml"), ["P1=0:1:2", "P2=0:1:2", "P3=-3:3:7"])
    >>> choose_slices(r)
    ((0, 1, 2, 3, 5, 6), "6 of 7 values of P3: the file's pose; then values spread over the range")
    """
    third = result.axes[2]
    count = third.count
    if count <= most:
        return tuple(range(count)), f"all {count} values of {drawn_name(third.name)}"
    home = _at_file_pose(third)
    chosen = [] if home is None else [home]
    holding = sorted({int(np.unravel_index(p.index, result.shape)[2]) for p in result.singular})
    left = [i for i in holding if i not in chosen]
    room = most - len(chosen)
    singular = [left[int(k)] for k in np.linspace(0, len(left) - 1, room).round()] if len(left) > room else left
    chosen += singular
    chosen += _spread([i for i in range(count) if i not in chosen], chosen, most - len(chosen), count)
    parts = ["the file's pose"] if home is not None else []
    if holding:
        shown = sum(1 for i in holding if i in chosen)
        plural = "s" if len(holding) != 1 else ""
        parts.append(f"the {len(holding)} value{plural} holding singular poses" if shown == len(holding) else f"{shown} of the {len(holding)} values holding singular poses")
    if len(chosen) > len(singular) + (home is not None):
        parts.append("then values spread over the range" if parts else "values spread over the range")
    return tuple(sorted(chosen)), f"{len(chosen)} of {count} values of {drawn_name(third.name)}: " + "; ".join(parts)


def _slices(result: SweepResult, title: str) -> "Figure":
    third = result.axes[2]
    grid = np.arange(result.size).reshape(result.shape)
    chosen, note = choose_slices(result)
    home = _at_file_pose(third)
    on_slice = np.bincount([int(np.unravel_index(p.index, result.shape)[2]) for p in result.singular], minlength=third.count)
    colour, label = colour_of(result)
    limits = _colour_limits(result, colour)
    columns = min(3, len(chosen))
    rows = int(np.ceil(len(chosen) / columns))
    fig = new_figure((4.2 * columns, 3.8 * rows + 0.8), layout="constrained")
    axes = np.atleast_1d(fig.subplots(rows, columns, squeeze=False)).ravel()
    mesh = None
    unit = f" {third.unit}" if third.unit else ""
    for ax, k in zip(axes, chosen):
        mesh = _map(ax, result, grid[:, :, k], limits)
        marks = (["file's pose"] if k == home else []) + ([f"{on_slice[k]} singular"] if on_slice[k] else [])
        ax.set_title(f"{drawn_name(third.name)} = {fmt_number(float(third.values[k]), third.extent)}{unit}" + (f" ({', '.join(marks)})" if marks else ""), fontsize="medium")
    for ax in axes[len(chosen) :]:
        ax.set_visible(False)
    if mesh is not None:
        fig.colorbar(mesh, ax=axes[: len(chosen)].tolist(), label=label, shrink=0.9)
    fig.suptitle(f"{title}\nslices: {note}")
    return fig
