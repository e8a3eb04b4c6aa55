"""The answer of a sweep: one row per grid point, and where the answer changes.

:class:`SweepResult` holds, for every grid point, whether the pose was
assembled and what :func:`mobility.analyze` (with inputs, :func:`mobility.check_actuation`)
says there, and names the regular answer, the singular poses, the changes, the
seams and the margin dips, as docs/sweeps.md defines them.

Examples
--------
>>> import mobility
>>> r = mobility.sweep(mobility.load("mechanisms/parallelogram.yaml"), ["O1=0:360:13"])
>>> r.size, r.counts()
(13, {(1, '1T', 1): 11, (2, '1T1R', 2): 2})
>>> [p.values for p in r.singular]
[(120.0,), (300.0,)]
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field, fields
from functools import cached_property
from typing import Any

import numpy as np

from ..actuation import SINGULAR
from ..core.frozen import ReadOnlyArrays, read_only, read_only_cached_property
from ..core.kinematics import kinematics
from ..core.model import Mechanism
from ..core.tolerance import DEFAULT_TOLERANCE, MARGIN_DIP, Tolerance, clean_numbers
from ..errors import RequestError, counted, shown_argument
from .grid import SweepAxis

__all__ = ["GridPoint", "SingularPose", "MarginDip", "SweepResult", "COLUMNS", "TRANSMISSION"]

COLUMNS = ("dof", "pattern", "mobility", "assembled", "residual", "smallest_kept", "largest_dropped", "near_singular", "inexact",
           "verdict", "conditioning", "actuation_margin", "iti", "oti", "lti", "cti")
"""Columns of a sweep's table after the varied coordinates (the actuation ones only when inputs are chosen, the transmission ones then too unless left out)."""

TRANSMISSION = ("iti", "oti", "lti", "cti")
"""The transmission columns (:mod:`mobility.transmission`)."""


@dataclass(frozen=True)
class GridPoint:
    """A point of a sweep's grid.

    Attributes
    ----------
    index : int
        Flat index of the grid point.
    values : tuple of float
        Its coordinate values (user units).
    """

    index: int
    values: tuple[float, ...]

    def to_dict(self, names: tuple[str, ...] = ()) -> dict[str, Any]:
        """JSON form: ``index``, ``values`` (keyed by ``names``, the coordinates, if given), then a subclass's fields in order (tuples as lists)."""
        located = {"index": self.index, "values": dict(zip(names, self.values)) if names else list(self.values)}
        return located | {f.name: _listed(getattr(self, f.name)) for f in fields(self) if f.name not in located}


def _listed(value: Any) -> Any:
    return list(value) if isinstance(value, tuple) else value


@dataclass(frozen=True)
class SingularPose(GridPoint):
    """A grid point where the answer is singular (docs/sweeps.md).

    Attributes
    ----------
    index, values
        As :class:`GridPoint`.
    dof, mobility : int
    pattern : str
    verdict : str
        The actuation verdict (empty when no input is chosen; ``null`` in JSON then).
    reasons : tuple of str
    """

    dof: int
    pattern: str
    mobility: int
    verdict: str
    reasons: tuple[str, ...]

    def to_dict(self, names: tuple[str, ...] = ()) -> dict[str, Any]:
        """JSON form (``names``: the coordinates, to key the values); no verdict is ``null``."""
        return super().to_dict(names) | {"verdict": self.verdict or None}


@dataclass(frozen=True)
class MarginDip(GridPoint):
    """A grid point where a rank margin dips: a singularity may lie next to it, between grid points.

    Attributes
    ----------
    index, values
        As :class:`GridPoint`.
    column : str
        ``"smallest_kept"`` (the analysis) or ``"actuation_margin"`` (the actuation verdict).
    margin : float
    neighbours : tuple of float
        The margins of its neighbours along ``axis``, where the dip is deepest
        (one at an end of the axis: the singularity may lie beyond it).
    axis : str
    """

    column: str
    margin: float
    neighbours: tuple[float, ...]
    axis: str


@dataclass(frozen=True, eq=False)
class SweepResult(ReadOnlyArrays):
    """Every pose of a sweep (arrays of length ``N``, the grid flattened in C order).

    Frozen: its arrays (and :attr:`values`, :attr:`changes`) are read-only, made
    so in place, also after a pickle round trip. It compares by identity.

    Attributes
    ----------
    mechanism : Mechanism
        The mechanism at the file's pose (``q = 0``).
    axes : tuple of SweepAxis
        The varied coordinates, first varying slowest.
    q : ndarray, shape (N, n)
        Joint variables of each pose (:mod:`mobility.core.kinematics`; the best
        attempt where not assembled, zeros where no solve reached it). A driven
        R or C angle may be whole turns from the grid's value (:attr:`SweepAxis.internal`).
    assembled : ndarray of bool
    residual : ndarray of float
        Largest loop-closure residual component (dimensionless; infinite where
        no solve reached the point, shown empty or null).
    dof, mobility : ndarray of int
        -1 where not assembled.
    pattern : ndarray of str
        Empty where not assembled.
    smallest_kept, largest_dropped : ndarray of float
        The margin of the pose's rank decisions (NaN where not assembled).
    near_singular, inexact : ndarray of bool
        The margin's warnings (False where not assembled; empty in CSV, ``null`` in JSON).
    actuated : tuple of str
        The actuated joints (empty: no actuation columns).
    verdict : ndarray of str
        Actuation verdict (empty where not assembled or no input chosen).
    conditioning, actuation_margin : ndarray of float
        Actuation conditioning ``kappa`` and the margin of the verdict's rank
        decision (NaN where not assembled or no input chosen).
    iti, oti, lti, cti : ndarray of float
        The transmission indices of :mod:`mobility.transmission` (NaN where not
        assembled; empty without inputs or when the sweep left them out).
    good_threshold : float
        The good-transmission threshold (``LTI >= good_threshold``; 0.7 as published).
    tolerance : Tolerance
    seams : ndarray of int, shape (k, 2)
        Pairs of grid points round a full turn that no small motion joins (:mod:`mobility.sweeps.seams`).
    """

    mechanism: Mechanism
    axes: tuple[SweepAxis, ...]
    q: np.ndarray
    assembled: np.ndarray
    residual: np.ndarray
    dof: np.ndarray
    pattern: np.ndarray
    mobility: np.ndarray
    smallest_kept: np.ndarray
    largest_dropped: np.ndarray
    near_singular: np.ndarray
    inexact: np.ndarray
    actuated: tuple[str, ...] = ()
    verdict: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=object))
    conditioning: np.ndarray = field(default_factory=lambda: np.zeros(0))
    actuation_margin: np.ndarray = field(default_factory=lambda: np.zeros(0))
    iti: np.ndarray = field(default_factory=lambda: np.zeros(0))
    oti: np.ndarray = field(default_factory=lambda: np.zeros(0))
    lti: np.ndarray = field(default_factory=lambda: np.zeros(0))
    cti: np.ndarray = field(default_factory=lambda: np.zeros(0))
    good_threshold: float = 0.7
    tolerance: Tolerance = DEFAULT_TOLERANCE
    seams: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=int))

    def __post_init__(self) -> None:
        for value in vars(self).values():  # columns of every pose, made by the sweep for this result: read-only in place, not copied
            read_only(value, copy=False)

    def __repr__(self) -> str:
        """One line: the mechanism, the grid, what was assembled and found (the table is in the columns).

        Examples
        --------
        >>> import mobility
        >>> mobility.sweep(mobility.load("mechanisms/parallelogram.yaml"), ["O1=0:360:13"])
        SweepResult('planar parallelogram four-bar', 13 poses over O1, 13 assembled, regular: DOF 1 1T mobility 1, 2 singular)
        """
        regular = self.regular
        found = f"regular: DOF {regular[0]} {regular[1]} mobility {regular[2]}" + (f" {regular[3]}" if regular[3] else "") if regular else "no answer"
        return (f"SweepResult({self.name!r}, {counted(self.size, 'pose', grouped=True)} over {' x '.join(self.names)}, "
                f"{int(self.assembled.sum()):,} assembled, {found}, {len(self.singular)} singular)")

    # -- the grid ----------------------------------------------------------------
    @property
    def name(self) -> str:
        """The mechanism's name."""
        return self.mechanism.name

    @property
    def shape(self) -> tuple[int, ...]:
        """Points per axis."""
        return tuple(a.count for a in self.axes)

    @property
    def size(self) -> int:
        """Number of poses."""
        return int(np.prod(self.shape))

    @property
    def names(self) -> tuple[str, ...]:
        """The varied coordinates."""
        return tuple(a.name for a in self.axes)

    @read_only_cached_property
    def values(self) -> np.ndarray:
        """Coordinate values of every pose, ``(N, axes)``, user units."""
        grids = np.meshgrid(*[a.values for a in self.axes], indexing="ij")
        return np.stack([g.reshape(-1) for g in grids], axis=1)

    def grid(self, column: str) -> np.ndarray:
        """A column reshaped to the grid's shape (e.g. ``r.grid("conditioning")`` for a map)."""
        return np.asarray(self.column(column)).reshape(self.shape)

    def column(self, name: str) -> np.ndarray:
        """A column of the table by name: a coordinate or one of :data:`COLUMNS`."""
        if isinstance(name, str) and name in self.names:
            return self.values[:, self.names.index(name)]
        if isinstance(name, str) and name in self.columns:
            return getattr(self, name)
        raise RequestError(f"no column {shown_argument(name)}; expected one of: {', '.join(self.columns)}")

    @property
    def columns(self) -> tuple[str, ...]:
        """The columns of the table: the coordinates, then :data:`COLUMNS` (actuation ones only with inputs)."""
        own = COLUMNS if self.actuated else COLUMNS[: COLUMNS.index("verdict")]
        if not self.has_transmission:
            own = tuple(c for c in own if c not in TRANSMISSION)
        return self.names + own

    @property
    def has_transmission(self) -> bool:
        """Whether the table has the transmission columns (inputs chosen, indices not left out)."""
        return bool(self.actuated) and self.lti.size == self.size

    def good_transmission(self, threshold: float | None = None) -> float:
        """The good-transmission workspace: the share of the assembled poses with ``LTI >= threshold`` (default :attr:`good_threshold`).

        NaN without transmission columns or assembled poses.  The region is
        ``r.grid("lti") >= threshold``.

        Examples
        --------
        >>> import mobility
        >>> r = mobility.sweep(mobility.load("mechanisms/3prs.yaml"), ["P1=-20:20:3"])
        >>> r.good_transmission(), r.good_transmission(0.99)
        (1.0, 0.0)
        """
        limit = self.good_threshold if threshold is None else float(threshold)
        ok = self.assembled
        if not self.has_transmission or not ok.any():
            return float("nan")
        with np.errstate(invalid="ignore"):
            return float(np.mean(self.lti[ok] >= limit))

    # -- what the sweep found ----------------------------------------------------------
    def classes(self) -> list[tuple[int, str, int, str] | None]:
        """The answer of each pose as one value ``(dof, pattern, mobility, verdict)`` (None where not assembled)."""
        verdict = self.verdict.tolist() if self.actuated else [""] * self.size
        return [(d, p, m, v) if ok else None for d, p, m, v, ok in zip(self.dof.tolist(), self.pattern.tolist(), self.mobility.tolist(), verdict, self.assembled.tolist())]

    def counts(self) -> dict[tuple[int, str, int], int]:
        """Assembled poses per ``(dof, pattern, mobility)``, most common first."""
        found = Counter(zip(self.dof[self.assembled].tolist(), self.pattern[self.assembled].tolist(), self.mobility[self.assembled].tolist()))
        return dict(sorted(found.items(), key=lambda kv: (-kv[1], kv[0])))

    def verdict_counts(self) -> dict[str, int]:
        """Assembled poses per actuation verdict (empty without inputs)."""
        if not self.actuated:
            return {}
        found = Counter(self.verdict[self.assembled].tolist())
        return dict(sorted(found.items(), key=lambda kv: -kv[1]))

    @cached_property
    def regular(self) -> tuple[int, str, int, str] | None:
        """The most common answer ``(dof, pattern, mobility, verdict)`` of the assembled poses (None if there is none)."""
        found = Counter(c for c in self.classes() if c is not None)
        if not found:
            return None
        return sorted(found.items(), key=lambda kv: (-kv[1], kv[0]))[0][0]

    @cached_property
    def singular(self) -> tuple[SingularPose, ...]:
        """The singular poses of the grid, in grid order."""
        regular = self.regular
        if regular is None:
            return ()
        dof0, _, mob0, verdict0 = regular
        out = []
        gains = self.assembled & ((self.dof > dof0) | (self.mobility > mob0))
        dead = self.assembled & (self.dof < dof0) & (self.mobility >= mob0)
        lost = self.assembled & (self.verdict == SINGULAR) & (verdict0 != SINGULAR) if self.actuated else np.zeros(self.size, dtype=bool)
        kind = "a dead point" if kinematics(self.mechanism).loop_count else "a serial singularity"
        for i in np.flatnonzero(gains | dead | lost):
            reasons = []
            if self.dof[i] > dof0:
                reasons.append(f"the end effector gains {counted(self.dof[i] - dof0, 'freedom')}: {self.dof[i]} DOF ({self.pattern[i]})")
            if dead[i]:
                reasons.append(f"the end effector loses {counted(dof0 - self.dof[i], 'freedom')} while the mechanism still moves ({kind}): {self.dof[i]} DOF ({self.pattern[i]})")
            if self.mobility[i] > mob0:
                reasons.append(f"the mechanism gains {counted(self.mobility[i] - mob0, 'freedom')}: mobility {self.mobility[i]}")
            if lost[i]:
                reasons.append(f"the inputs {', '.join(self.actuated)} are actuation-singular")
            verdict = str(self.verdict[i]) if self.actuated else ""
            out.append(SingularPose(int(i), tuple(float(x) for x in self.values[i]), int(self.dof[i]), str(self.pattern[i]), int(self.mobility[i]), verdict, tuple(reasons)))
        return tuple(out)

    def _class_codes(self) -> np.ndarray:
        """Each pose's answer as a small integer (-1 where not assembled), in the grid's shape."""
        codes = np.full(self.size, -1)
        lookup: dict = {}
        for i, c in enumerate(self.classes()):
            if c is not None:
                codes[i] = lookup.setdefault(c, len(lookup))
        return codes.reshape(self.shape)

    @read_only_cached_property
    def changes(self) -> np.ndarray:
        """Neighbouring assembled grid points whose answers differ: rows ``(index a, index b, axis)``, ``a < b``."""
        grid = self._class_codes()
        index = np.arange(self.size).reshape(self.shape)
        rows = []
        for axis in range(len(self.shape)):
            a = np.take(grid, range(self.shape[axis] - 1), axis=axis)
            b = np.take(grid, range(1, self.shape[axis]), axis=axis)
            ia = np.take(index, range(self.shape[axis] - 1), axis=axis)
            ib = np.take(index, range(1, self.shape[axis]), axis=axis)
            differ = (a >= 0) & (b >= 0) & (a != b)
            rows += [(int(x), int(y), axis) for x, y in zip(ia[differ], ib[differ])]
        return np.array(sorted(rows), dtype=int).reshape(-1, 3)

    @cached_property
    def dips(self) -> tuple[MarginDip, ...]:
        """The grid points where a rank margin dips (docs/sweeps.md), in grid order, deepest dip per point and column."""
        codes = self._class_codes()
        index = np.arange(self.size).reshape(self.shape)
        singular = {p.index for p in self.singular}
        found: dict[tuple[int, str], MarginDip] = {}
        columns = ("smallest_kept", "actuation_margin") if self.actuated else ("smallest_kept",)
        for column in columns:
            values = np.where(self.assembled, np.asarray(getattr(self, column), dtype=float), np.nan).reshape(self.shape)
            for axis, name in enumerate(self.names):
                n = self.shape[axis]
                if n < 3:
                    continue
                left, mid, right = (np.take(values, range(k, n - 2 + k), axis=axis) for k in range(3))
                code = [np.take(codes, range(k, n - 2 + k), axis=axis) for k in range(3)]
                at = np.take(index, range(1, n - 1), axis=axis)
                with np.errstate(invalid="ignore"):
                    same = (code[1] >= 0) & (code[0] == code[1]) & (code[2] == code[1]) & np.isfinite(left + mid + right)
                    dip = same & (mid <= left) & (mid <= right) & (mid <= MARGIN_DIP * np.maximum(left, right))
                candidates: list[tuple[int, float, tuple[float, ...]]] = [(i, m, (a, b)) for i, a, b, m in zip(at[dip].tolist(), left[dip].tolist(), right[dip].tolist(), mid[dip].tolist())]
                for end, inner in ((0, 1), (n - 1, n - 2)):  # an end of the axis: falling towards it from its one neighbour
                    e, f = np.take(values, end, axis=axis), np.take(values, inner, axis=axis)
                    with np.errstate(invalid="ignore"):
                        low = (np.take(codes, end, axis=axis) >= 0) & (np.take(codes, end, axis=axis) == np.take(codes, inner, axis=axis)) & (e <= MARGIN_DIP * f)
                    candidates += [(i, m, (b,)) for i, m, b in zip(np.take(index, end, axis=axis)[low].tolist(), e[low].tolist(), f[low].tolist())]
                for i, m, around in candidates:
                    if i in singular:
                        continue
                    old = found.get((i, column))
                    if old is None or m / max(around) < old.margin / max(old.neighbours):
                        found[(i, column)] = MarginDip(i, tuple(float(x) for x in self.values[i]), column, m, around, name)
        return tuple(found[k] for k in sorted(found))

    # -- one pose --------------------------------------------------------------------
    def mechanism_at(self, index: int) -> Mechanism:
        """The pose of grid point ``index`` (flat) rebuilt as a :class:`~mobility.core.model.Mechanism`.

        Raises
        ------
        RequestError
            When the point is not on the grid or was not assembled.
        """
        self._require_index(index, "mechanism_at")
        if not self.assembled[index]:
            raise RequestError(f"grid point {int(index)} ({', '.join(f'{n}={v:g}' for n, v in zip(self.names, self.values[index]))}) was not assembled; its loops do not close", caller="mechanism_at")
        return kinematics(self.mechanism).mechanism_at(self.q[index])

    def _require_index(self, index: Any, what: str) -> None:
        if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not -self.size <= index < self.size:
            raise RequestError(caller=what, expected=f"a grid point index in 0..{self.size - 1}", got=shown_argument(index))

    def row(self, index: int) -> dict[str, Any]:
        """One row of the table as a dict (JSON-ready).

        Raises
        ------
        RequestError
            When ``index`` is not a grid point's (flat) index.
        """
        self._require_index(index, "row")
        out: dict[str, Any] = {n: float(v) for n, v in zip(self.names, self.values[index])}
        ok = bool(self.assembled[index])
        for name in self.columns[len(self.names) :]:
            value, kind = getattr(self, name)[index], _KINDS.get(name)
            out[name] = bool(value) if name == "assembled" else (kind(value) if ok else None) if kind else _number(value)
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON form: the request, the summary (counts, regular answer, singular poses, changes) and the table by column."""
        return {**self.summary_dict(), "columns": {name: self.column_list(name) for name in self.columns}}

    def summary_dict(self) -> dict[str, Any]:
        """:meth:`to_dict` without the table (``columns``): what a writer sends before the columns, one at a time."""
        regular = self.regular
        return {
            "name": self.name, "coordinates": [a.to_dict() for a in self.axes], "shape": list(self.shape), "poses": self.size,
            "assembled": int(self.assembled.sum()), "actuated": list(self.actuated),
            "counts": [{"dof": d, "pattern": p, "mobility": m, "poses": n} for (d, p, m), n in self.counts().items()],
            "verdicts": self.verdict_counts(),
            "regular": None if regular is None else {"dof": regular[0], "pattern": regular[1], "mobility": regular[2], "verdict": regular[3] or None},
            "singular_poses": [p.to_dict(self.names) for p in self.singular],
            "changes": [{"from": int(a), "to": int(b), "axis": self.names[int(k)]} for a, b, k in self.changes],
            "seams": [{"from": int(a), "to": int(b)} for a, b in self.seams], "margin_dips": [d.to_dict(self.names) for d in self.dips],
            **({"transmission": {"good_threshold": self.good_threshold, "good_share": _number(self.good_transmission()),
                                 "lti_min": _number(np.nanmin(self.lti[self.assembled])) if np.isfinite(self.lti[self.assembled]).any() else None,
                                 "cti_min": _number(np.nanmin(self.cti[self.assembled])) if np.isfinite(self.cti[self.assembled]).any() else None}}
               if self.has_transmission else {}),
            "tolerance": {"rank": self.tolerance.rank, "near_singular": self.tolerance.near_singular, "closure": self.tolerance.closure},
        }

    def column_list(self, name: str) -> list:
        """Column ``name`` of :meth:`to_dict`'s table: plain Python values, ``None`` where a pose has no answer (or a number is not finite)."""
        col = self.column(name)
        if name == "assembled":
            return [bool(v) for v in col]
        kind = _KINDS.get(name)
        if kind is not None:
            return [kind(v) if ok else None for v, ok in zip(col, self.assembled)]
        if name in self.names:
            extent = next(a.extent for a in self.axes if a.name == name)
            return [_number(v) for v in clean_numbers(np.asarray(col, dtype=float), extent)]
        return [_number(v) for v in col]


_KINDS = {"dof": int, "mobility": int, "pattern": str, "verdict": str, "near_singular": bool, "inexact": bool}
"""The columns of plain values (None where a pose has no answer); the others are numbers."""


def _number(x: Any) -> float | None:
    """A float for JSON (None for NaN or infinity)."""
    x = float(x)
    return x if np.isfinite(x) else None
