"""The 3D view of a sweep: a slider through its assembled poses (``mechanism_at``), each analysed and labelled by its coordinates.

A sweep larger than a page holds is thinned to evenly spaced poses, keeping every
singular pose, so that the slider passes through each change of pattern (:func:`sweep_notes`).

Examples
--------
>>> import mobility
>>> m = mobility.load("mechanisms/parallelogram.yaml")
>>> s = mobility.sweep(m, vary={"O1": (0, 120, 3)})   # the crank turned 120 deg: folded
>>> v = sweep_view(s)
>>> [f.label for f in v.frames], [f.result.pattern for f in v.frames]
(['O1=0 deg', 'O1=60 deg', 'O1=120 deg'], ['1T', '1T', '1T1R'])
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.analysis import analyze
from ..errors import RequestError
from .views import MAX_POSES, View, ViewFrame, poses_view, require_max_poses

__all__ = ["sweep_view", "sweep_poses", "sweep_notes", "transmission_label"]


def sweep_poses(sweep: Any, max_poses: int = MAX_POSES) -> list[int]:
    """Indices of the grid points a view shows: every assembled one, or evenly spaced ones and every singular one.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> s = SimpleNamespace(size=10, assembled=np.arange(10) != 3, singular=(SimpleNamespace(index=7),))
    >>> sweep_poses(s, 4)
    [0, 5, 7, 9]
    """
    assembled = np.flatnonzero(np.asarray(sweep.assembled, dtype=bool))
    if len(assembled) <= max_poses:
        return assembled.tolist()
    singular = sorted({int(p.index) for p in sweep.singular})[:max_poses]
    spaced = assembled[np.round(np.linspace(0, len(assembled) - 1, max_poses - len(singular))).astype(int)] if max_poses > len(singular) else []
    return sorted(set(singular) | {int(i) for i in spaced})


def sweep_notes(sweep: Any, shown: int) -> list[str]:
    """What a view of ``shown`` of the sweep's poses says of the others: none when every pose is drawn.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> sweep_notes(SimpleNamespace(size=25, assembled=np.arange(25) < 14), 14)
    ["14 of the sweep's 25 poses drawn: 11 not assembled (no closed pose reached there)"]
    >>> sweep_notes(SimpleNamespace(size=1000, assembled=np.arange(1000) != 3), 200)
    ["200 of the sweep's 1,000 poses drawn: 1 not assembled (no closed pose reached there); 799 assembled poses left out (evenly spaced ones drawn, every singular one kept)"]
    """
    size = int(sweep.size)
    assembled = int(np.count_nonzero(sweep.assembled))
    if shown >= size:
        return []
    why = []
    if assembled < size:
        why.append(f"{size - assembled:,} not assembled (no closed pose reached there)")
    if shown < assembled:
        why.append(f"{assembled - shown:,} assembled poses left out (evenly spaced ones drawn, every singular one kept)")
    return [f"{shown:,} of the sweep's {size:,} poses drawn: " + "; ".join(why)]


def transmission_label(sweep: Any, index: int) -> str:
    """What the slider's label adds at a pose of a sweep with transmission indices: its LTI and CTI (``""`` without them).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> transmission_label(SimpleNamespace(has_transmission=True, lti=np.array([0.8123]), cti=np.array([np.nan])), 0)
    ', LTI 0.812'
    """
    if not getattr(sweep, "has_transmission", False):
        return ""
    parts = [f"{name} {float(value):.3f}" for name, value in (("LTI", sweep.lti[index]), ("CTI", sweep.cti[index])) if np.isfinite(value)]
    return "".join(f", {p}" for p in parts)


def sweep_view(sweep: Any, *, max_poses: int = MAX_POSES) -> View:
    """The view of a sweep's poses with a slider (at most ``max_poses`` of them, from 1 to :data:`~mobility.view.views.MAX_POSES`).

    A :class:`RequestError` when ``sweep`` is not a sweep result or none of its poses was assembled.
    """
    from ..report.sweep import describe_values  # here: the sweeps package loads only when a sweep is shown

    if not all(hasattr(sweep, a) for a in ("assembled", "values", "singular", "mechanism_at", "tolerance", "axes")):
        raise RequestError(caller="sweep_view", argument="sweep", expected="a sweep result (mobility.sweep)", got=type(sweep).__name__)
    max_poses = require_max_poses(max_poses, "sweep_view")
    indices = sweep_poses(sweep, max_poses)
    if not indices:
        raise RequestError(f"{sweep.name}: no pose of the sweep was assembled; nothing to show")
    frames = []
    for i in indices:
        mechanism = sweep.mechanism_at(i)
        frames.append(ViewFrame(mechanism, analyze(mechanism, tol=sweep.tolerance), describe_values(sweep, sweep.values[i]) + transmission_label(sweep, i)))
    return poses_view(frames, max_poses=max_poses, notes=sweep_notes(sweep, len(frames)))
