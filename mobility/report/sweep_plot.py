"""Pictures of a sweep: a curve (one coordinate), a map (two) or slices of a 3-D grid.

* **curve**: the end effector's DOF and the mobility along the coordinate
  (steps), and below them the rank margin (smallest kept relative singular
  value, log scale) and, with inputs, the actuation conditioning; singular
  poses are marked by red lines, poses that could not be assembled are shaded;
* **map**: the colour is the actuation conditioning when inputs are chosen,
  else the rank margin (log10); the regions of each answer (DOF, pattern,
  mobility, verdict) are outlined, singular poses marked with red crosses,
  poses not assembled left grey;
* **slices**: the same map at up to :data:`MAX_SLICES` values of the third
  coordinate, the slices holding singular poses first.

matplotlib is optional (``pip install 'mobility[plot]'``); figures are built
without :mod:`matplotlib.pyplot` by the pictures' backend
(:mod:`mobility.report.plotting.backend`), and
:func:`~mobility.report.plotting.save_figure` writes them.  Every drawn
element of an answer carries a ``gid`` (``"mobility:sweep:curve"``, ``"mobility:sweep:map"``,
``"mobility:sweep:regions"``, ``"mobility:sweep:singular"``,
``"mobility:sweep:unassembled"``) so that tests can read a picture back.

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

from ..errors import RequestError
from ..sweeps import SweepResult
from .plotting.backend import new_figure, require_matplotlib

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["plot_sweep", "colour_of", "MAX_SLICES"]

MAX_SLICES = 6
"""Slices drawn of a 3-D grid."""


def colour_of(result: SweepResult) -> tuple[np.ndarray, str]:
    """The quantity a map shows, per pose (NaN where not assembled), and its label."""
    if result.actuated:
        return np.where(result.assembled, result.conditioning, np.nan), f"actuation conditioning κ ({', '.join(result.actuated)})"
    with np.errstate(divide="ignore"):
        margin = np.log10(np.where(result.assembled, result.smallest_kept, np.nan))
    return margin, "rank margin: log10 smallest kept relative singular value"


def _answers(result: SweepResult) -> tuple[np.ndarray, list[str]]:
    """A code per pose for its answer (-1: not assembled) and a label per code."""
    codes = np.full(result.size, -1)
    labels: list[str] = []
    seen: dict = {}
    for i, c in enumerate(result.classes()):
        if c is None:
            continue
        if c not in seen:
            seen[c] = len(seen)
            dof, pattern, mobility, verdict = c
            labels.append(f"DOF {dof} {pattern}, M={mobility}" + (f", {verdict}" if verdict else ""))
        codes[i] = seen[c]
    return codes, labels


def plot_sweep(result: SweepResult, *, title: str | None = None) -> "Figure":
    """A picture of ``result``: a curve, a map or slices (see the module docstring).

    Raises
    ------
    RequestError
        For a sweep of more than three coordinates.
    PlottingUnavailableError
        When matplotlib is not installed.
    """
    k = len(result.axes)
    if k > 3:
        raise RequestError(f"a sweep of {k} coordinates cannot be drawn; plots show 1 (curve), 2 (map) or 3 (slices)")
    require_matplotlib()
    title = result.name if title is None else title
    if k == 1:
        return _curve(result, title)
    if k == 2:
        fig = new_figure((7.5, 6.0), layout="constrained")
        ax = fig.add_subplot()
        mesh = _map(ax, result, np.arange(result.size).reshape(result.shape), None)
        fig.colorbar(mesh, ax=ax, label=colour_of(result)[1])
        ax.set_title(title)
        return fig
    return _slices(result, title)


def _curve(result: SweepResult, title: str) -> "Figure":
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
    top.yaxis.get_major_locator().set_params(integer=True)
    top.set_title(title)
    with np.errstate(divide="ignore"):
        bottom.semilogy(x, np.where(ok, result.smallest_kept, np.nan), color="tab:green", label="rank margin (smallest kept)", gid="mobility:sweep:curve")
    if result.actuated:
        bottom.semilogy(x, np.where(ok & (result.conditioning > 0), result.conditioning, np.nan), color="tab:purple", label="actuation conditioning κ", gid="mobility:sweep:curve")
    bottom.set_xlabel(axis.label)
    bottom.set_ylabel("relative value")
    step = (x[1] - x[0]) if len(x) > 1 else 1.0
    for panel in (top, bottom):
        for i in np.flatnonzero(~ok):
            panel.axvspan(x[i] - step / 2, x[i] + step / 2, color="0.85", lw=0, gid="mobility:sweep:unassembled")
    for p in result.singular:
        top.axvline(p.values[0], color="tab:red", lw=1.0, gid="mobility:sweep:singular")
        bottom.axvline(p.values[0], color="tab:red", lw=1.0)
    if result.singular:
        top.plot([], [], color="tab:red", label="singular pose")
    top.legend(loc="best", fontsize="small")
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
        finite = z[np.isfinite(z)]
        limits = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    cmap = require_matplotlib().colormaps["viridis"].with_extremes(bad="0.8")
    mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(z).T, shading="nearest", cmap=cmap, vmin=limits[0], vmax=limits[1], gid="mobility:sweep:map")
    missing = ~result.assembled[index]
    if missing.any():
        ax.pcolormesh(x, y, np.ma.masked_where(~missing, np.ones(missing.shape)).T, shading="nearest", cmap="Greys", vmin=0, vmax=3, gid="mobility:sweep:unassembled")
    code = codes[index].astype(float)
    present = np.unique(code[code >= 0])
    if present.size > 1 and len(x) > 1 and len(y) > 1:
        ax.contour(x, y, np.ma.masked_less(code, 0).T, levels=np.arange(-0.5, present.max() + 1.0), colors="white", linewidths=1.2).set_gid("mobility:sweep:regions")
    singular = [p.index for p in result.singular]
    where = np.isin(index, singular)
    if where.any():
        i, j = np.nonzero(where)
        ax.scatter(x[i], y[j], marker="x", color="tab:red", s=28, label="singular pose", gid="mobility:sweep:singular", zorder=3)
    if present.size > 1:
        ax.scatter([], [], marker="s", color="none", edgecolor="0.3", label="regions (white outlines): " + "; ".join(labels[c] for c in present.astype(int)))
    ax.set_xlabel(a0.label)
    ax.set_ylabel(a1.label)
    handles, names = ax.get_legend_handles_labels()
    if names:
        ax.legend(handles, names, loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize="x-small", ncol=1, frameon=False)
    return mesh


def _slices(result: SweepResult, title: str) -> "Figure":
    third = result.axes[2]
    grid = np.arange(result.size).reshape(result.shape)
    on_singular = sorted({int(np.unravel_index(p.index, result.shape)[2]) for p in result.singular})
    even = np.linspace(0, third.count - 1, min(third.count, MAX_SLICES)).round().astype(int).tolist()
    chosen = sorted(set(on_singular[: MAX_SLICES // 2] + [i for i in even if i not in on_singular])[:MAX_SLICES]) if on_singular else even
    chosen = sorted(set(chosen))[:MAX_SLICES]
    colour, label = colour_of(result)
    finite = colour[np.isfinite(colour)]
    limits = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    columns = min(3, len(chosen))
    rows = int(np.ceil(len(chosen) / columns))
    fig = new_figure((4.2 * columns, 3.8 * rows + 0.6), layout="constrained")
    axes = np.atleast_1d(fig.subplots(rows, columns, squeeze=False)).ravel()
    mesh = None
    for ax, k in zip(axes, chosen):
        mesh = _map(ax, result, grid[:, :, k], limits)
        unit = f" {third.unit}" if third.unit else ""
        ax.set_title(f"{third.name} = {third.values[k]:g}{unit}", fontsize="medium")
    for ax in axes[len(chosen) :]:
        ax.set_visible(False)
    if mesh is not None:
        fig.colorbar(mesh, ax=axes[: len(chosen)].tolist(), label=label, shrink=0.9)
    fig.suptitle(title)
    return fig
