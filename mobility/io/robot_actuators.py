"""Actuators of robot description files: one actuator is one input.

An actuator on a ball joint drives one rotation, the angular velocity's component along its gear's axis (a
:class:`BallActuator`).  The model actuates a joint as a whole, so a driven ball joint becomes a chain through its
centre (:func:`ball_chain`) with the ball's three rotations at the reference pose: same mobility and twists.

Examples
--------
>>> chain = ball_chain("shoulder", (0, 0, 1), (BallActuator("motor", (0, 1, 0)),))
>>> [(j.name, j.type, j.actuated) for j in chain]
[('shoulder', 'U', False), ('shoulder.motor', 'R', True)]
>>> chain[1].axis, chain[0].axes
((0.0, 1.0, 0.0), ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)))
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable

import numpy as np

from ..core.model import Joint

__all__ = ["BallActuator", "ball_chain", "ball_chain_axes", "ball_chain_names"]

Vector = tuple[float, float, float]


@dataclass(frozen=True)
class BallActuator:
    """One input of a ball joint: a rotation about ``axis`` (global frame, at the reference pose), as one actuator drives it;
    ``in_parent``: written in the parent body's frame (MuJoCo's ``jointinparent``), else in the child's."""

    name: str
    axis: Vector
    in_parent: bool = False
    line: int | None = None


def ball_chain_axes(axes: Iterable[Iterable[float]]) -> list[Vector]:
    """The rotation axes of a ball joint as a chain of joints through its centre, the first ``len(axes)`` driven one each by the given inputs.

    The axes ``e`` returned are the dual basis of ``axes`` (``axes[i] . e[j]``
    zero for ``i != j``, each ``e[j]`` of length 1), completed by directions
    normal to every input's axis: turning about ``e[j]`` changes input ``j``
    alone.  The axes given must be independent, finite and non-zero.

    Examples
    --------
    >>> ball_chain_axes([(0, 0, 2)])
    [(0.0, 0.0, 1.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)]
    >>> [[round(x, 6) + 0.0 for x in e] for e in ball_chain_axes([(1, 0, 0), (1, 1, 0)])]
    [[0.707107, -0.707107, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    """
    given = np.array([[float(x) for x in a] for a in axes], dtype=float).reshape(-1, 3)
    given /= np.linalg.norm(given, axis=1, keepdims=True)
    count = len(given)
    _, _, vt = np.linalg.svd(given, full_matrices=True)
    rows = np.vstack([given, vt[count:]])  # the inputs' axes, then an orthonormal basis of the directions normal to them
    dual = np.linalg.inv(rows)  # rows @ dual = I: column j is axis e[j]
    out: list[Vector] = []
    for k, column in enumerate(dual.T):
        unit = column / np.linalg.norm(column)
        if k >= count and unit[int(np.argmax(np.abs(unit)))] < 0:  # an axis normal to the inputs: either sense, the largest number positive
            unit = -unit
        out.append((float(unit[0]) + 0.0, float(unit[1]) + 0.0, float(unit[2]) + 0.0))
    return out


def _chain_order(count: int, actuators: tuple[BallActuator, ...]) -> list[int]:
    """Indices of the chain's joints (``k < count``: actuator ``k``'s R; ``count``: the rest), from the parent to the child.

    Axes written in the parent's frame come first, in the child's last: each moves with the body it is written in.
    """
    rest = [count] if count < 3 else []
    return [k for k, a in enumerate(actuators) if a.in_parent] + rest + [k for k, a in enumerate(actuators) if not a.in_parent]


def ball_chain_names(name: str, actuators: tuple[BallActuator, ...]) -> list[str]:
    """The names of :func:`ball_chain`'s joints, in chain order (before clashes with other names are resolved).

    Examples
    --------
    >>> ball_chain_names("s", (BallActuator("a", (1, 0, 0), in_parent=True), BallActuator("b", (0, 1, 0))))
    ['s.a', 's', 's.b']
    """
    count = len(actuators)
    return [f"{name}.{actuators[k].name}" if k < count else name for k in _chain_order(count, actuators)]


def ball_chain(name: str, point: Vector, actuators: tuple[BallActuator, ...]) -> list[Joint]:
    """A ball joint driven by ``actuators`` as a chain of joints through ``point``, in chain order: the actuated R joint
    ``name.a`` of each actuator ``a``, the U or R joint ``name`` for the rest; ``links`` are placeholders for the caller to set.
    """
    axes = ball_chain_axes([a.axis for a in actuators])
    count = len(actuators)
    rest = axes[count:]
    ends = ("parent", "child")
    out = []
    for k, joint_name in zip(_chain_order(count, actuators), ball_chain_names(name, actuators)):
        if k < count:
            out.append(Joint(joint_name, "R", ends, axis=axes[k], point=point, actuated=True))
        elif len(rest) == 2:
            out.append(Joint(joint_name, "U", ends, axes=(rest[0], rest[1]), point=point))
        else:
            out.append(Joint(joint_name, "R", ends, axis=rest[0], point=point))
    return out
