"""Joint twists of a mechanism, in the normalised coordinates of the tolerance policy.

Origin at the mechanism's centre, lengths over its characteristic length
(:mod:`mobility.core.tolerance`); :class:`Normalisation` maps back.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Callable

import numpy as np

from ..errors import MechanismFileError
from .model import Mechanism
from .tolerance import DEFAULT_TOLERANCE, binary_scale, characteristic_scale
from .transforms import cross

__all__ = ["Normalisation", "JointScrews", "joint_screws", "unit_twists", "per_object_cache", "clear_cache"]


@dataclass(frozen=True, eq=False)
class Normalisation:
    """Normalised coordinates: origin at ``centre``, lengths divided by ``length``.

    A screw ``[a; b]`` (twist ``[w; v]`` or wrench ``[f; m]``) in global
    coordinates becomes ``[a; (b - centre x a) / length]``.
    """

    centre: np.ndarray
    length: float

    @cached_property
    def reach(self) -> float:
        """``length`` plus the largest coordinate of ``centre``: how far the mechanism reaches from the origin, in each coordinate."""
        return float(np.abs(self.centre).max()) + self.length

    @cached_property
    def size(self) -> float:
        """A length for rounding output: ``length + |centre|`` (the largest float if that overflows)."""
        scale = binary_scale(self.centre)
        scaled = self.centre * scale
        return min(self.length + float(np.sqrt(scaled @ scaled)) / scale, sys.float_info.max)

    def to_world(self, screws: np.ndarray) -> np.ndarray:
        """Map screws (columns) from normalised to global coordinates."""
        s = np.asarray(screws, dtype=float).reshape(6, -1)
        return np.concatenate([s[:3], self.length * s[3:] + cross(self.centre[:, None], s[:3])])

    def from_world(self, screws: np.ndarray) -> np.ndarray:
        """Map screws (columns) from global to normalised coordinates."""
        s = np.asarray(screws, dtype=float).reshape(6, -1)
        return np.concatenate([s[:3], (s[3:] - cross(self.centre[:, None], s[:3])) / self.length])

    def point_to_world(self, p: np.ndarray) -> np.ndarray:
        """Map a point from normalised to global coordinates."""
        return self.centre + self.length * np.asarray(p, dtype=float)

    def point_from_world(self, p: np.ndarray) -> np.ndarray:
        """Map a point from global to normalised coordinates."""
        return (np.asarray(p, dtype=float) - self.centre) / self.length


@dataclass(frozen=True)
class JointScrews:
    """All joint twists of a mechanism as one matrix.

    ``twists`` (6, n) are unit columns, joint after joint in the order of
    :meth:`~mobility.core.model.Joint.freedoms`, joint ``j``'s
    ``offsets[j]:offsets[j+1]`` (the view ``columns[j]``).  ``reference`` is the
    centroid of the end effector's joint points (the centre if none), through
    whose nearest point canonical axes pass; ``reference_in_world`` the same
    in the global frame and the file's unit.
    """

    twists: np.ndarray
    offsets: tuple[int, ...]
    normalisation: Normalisation
    reference: np.ndarray
    columns: tuple[np.ndarray, ...]
    reference_in_world: np.ndarray

    def of_joint(self, index: int) -> np.ndarray:
        """Twist columns of joint ``index``."""
        return self.columns[index]


_CACHE_ATTRIBUTE = "_mobility_cache"


def per_object_cache(obj: object, key: str, factory: Callable[[], Any]) -> Any:
    """Compute ``factory()`` once per object ``obj`` and key.

    Kept in the object's own ``__dict__`` (as :func:`functools.cached_property`
    does): they live and die with it, one look-up, no hashing of a large description.
    """
    cache = vars(obj).get(_CACHE_ATTRIBUTE)
    if cache is None:
        cache = vars(obj)[_CACHE_ATTRIBUTE] = {}
    if key not in cache:
        cache[key] = factory()
    return cache[key]


def clear_cache(obj: object) -> None:
    """Forget what :func:`per_object_cache` computed for ``obj`` (for benchmarks)."""
    vars(obj).pop(_CACHE_ATTRIBUTE, None)


def joint_screws(mechanism: Mechanism) -> JointScrews:
    """Unit joint twists of ``mechanism`` in normalised coordinates (cached per mechanism).

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> m = Mechanism("slide", "g", "s", (Joint("p", "P", ("g", "s"), axis=(0, 0, 5)),))
    >>> js = joint_screws(m)
    >>> js.twists[:, 0].tolist()
    [0.0, 0.0, 0.0, 0.0, 0.0, 1.0]
    """
    return per_object_cache(mechanism, "joint_screws", lambda: _build(mechanism))


def unit_twists(prismatic: np.ndarray, axes: np.ndarray, offsets: np.ndarray, pitches: np.ndarray, lengths: np.ndarray | float) -> np.ndarray:
    """Unit twists ``[w; v]`` of elementary freedoms at a stack of poses, in normalised coordinates.

    A turn has ``w = axis``, ``v = (offset x axis + h axis) / length``, a slide
    ``w = 0``, ``v = axis``; each column then scaled to unit norm.  ``axes`` and
    ``offsets`` (points less their pose's centre) are (N, 3, f), ``lengths``
    one per pose; the result is (N, 6, f).

    Examples
    --------
    >>> unit_twists(np.array([False]), np.array([[[0.0], [0.0], [1.0]]]), np.array([[[1.0], [0.0], [0.0]]]), np.zeros(1), 1.0)[0, :, 0].round(6).tolist()
    [0.0, 0.0, 0.707107, 0.0, -0.707107, 0.0]
    """
    length = np.reshape(lengths, (-1, 1, 1))
    moment = (cross(offsets.swapaxes(0, 1), axes.swapaxes(0, 1)).swapaxes(0, 1) + pitches * axes) / length
    tw = np.concatenate([np.where(prismatic, 0.0, axes), np.where(prismatic, axes, moment)], axis=1)
    tw /= np.sqrt(np.einsum("nij,nij->nj", tw, tw))[:, None, :]
    return tw


def _refuse_unresolved_links(mechanism: Mechanism, scale: float, length_s: float) -> None:
    """Refuse a link whose joints are written at distinct points that the analysis cannot tell apart.

    Points spanning less than ``inexact`` of the characteristic length (a
    pivot at 1e300, the rest near the origin) would be analysed as one point,
    no margin showing it; points apart by less than ``rank`` of their own size
    are taken as written to coincide.  The default policy's thresholds: the
    twists are tabulated once for every policy.
    """
    table = mechanism.freedom_table
    if len(table.located) < 2:
        return
    ids = table.located_links.T.reshape(-1)
    order = np.argsort(ids, kind="stable")
    ids = ids[order]
    points = np.concatenate([table.located, table.located])[order] * scale
    starts = np.flatnonzero(np.concatenate([[True], ids[1:] != ids[:-1]]))
    low, high = np.minimum.reduceat(points, starts, axis=0), np.maximum.reduceat(points, starts, axis=0)
    extent = (high - low).max(axis=1)
    size = np.maximum(np.abs(low), np.abs(high)).max(axis=1)
    bad = np.flatnonzero((extent > DEFAULT_TOLERANCE.rank * size) & (extent <= DEFAULT_TOLERANCE.inexact * length_s))
    if len(bad) == 0:
        return
    link = int(ids[starts[bad[0]]])
    joints = [int(j) for j, links in zip(table.located_joints, table.located_links) if link in links]
    written = ", ".join(mechanism.joints[j].name for j in joints)
    key, line = mechanism.joint_key(joints[0], "point")
    located = table.located * scale
    farthest = int(np.argmax(np.abs(located - located.mean(axis=0)).max(axis=1)))  # the joint whose point makes the size
    far = mechanism.joints[int(table.located_joints[farthest])].name
    where = ", ".join(f"{x / scale:.3g}" for x in located[farthest])
    raise MechanismFileError(
        key,
        f"the joints of link {mechanism.links[link]!r} ({written}) span {extent[bad[0]] / scale:.3g}, {extent[bad[0]] / length_s:.1e} of the mechanism's size "
        f"{length_s / scale:.3g} (set by joint {far!r} at [{where}]): finer than the analysis can resolve ({DEFAULT_TOLERANCE.inexact:.0e} of it); bring the far joints nearer or split the mechanism, "
        "or, if these joints meet at one point, write the same point for each", file=mechanism.source or "<string>", line=line)


def _build(mechanism: Mechanism) -> JointScrews:
    table = mechanism.freedom_table
    pitches = table.pitches
    centre, length = characteristic_scale(table.located, pitches=pitches[pitches != 0.0])
    if not math.isfinite(length):
        key, line = mechanism.joint_key(int(table.located_joints[np.argmax(np.abs(table.located).max(axis=1))]), "point")  # the farthest
        raise MechanismFileError(
            key,
            f"the joint points are too far apart to compute with: their RMS distance from their centroid exceeds the largest float "
            f"({sys.float_info.max:.3g}); write the mechanism in a larger length unit", file=mechanism.source or "<string>", line=line)
    # every length times the same power of two (exact), so that no product below can overflow
    scale = binary_scale(table.located, pitches)
    centre_s, length_s = centre * scale, length * scale
    _refuse_unresolved_links(mechanism, scale, length_s)
    tw = unit_twists(table.prismatic, table.axes.T[None], (table.points * scale - centre_s).T[None], pitches * scale, length_s)[0]
    tw.setflags(write=False)
    centre.setflags(write=False)  # shared by every later analysis of this mechanism: nobody may write to it
    norm = Normalisation(centre, length)
    ee = table.end_effector_points
    reference = ((ee * scale).sum(axis=0) / len(ee) - centre_s) / length_s if len(ee) else np.zeros(3)
    reference.setflags(write=False)
    offsets = table.offsets
    columns = tuple(tw[:, offsets[j] : offsets[j + 1]] for j in range(len(offsets) - 1))
    with np.errstate(over="ignore"):  # norm.point_to_world, without overflow: the centroid of finite points is
        # finite, so a coordinate past the largest float is one that rounding took there: it is that float
        reference_in_world = np.clip((centre_s + length_s * reference) / scale, -sys.float_info.max, sys.float_info.max)
    reference_in_world.setflags(write=False)
    return JointScrews(tw, offsets, norm, reference, columns, reference_in_world)
