"""Couplings of joint rates in a robot description, and the model's couplings they become.

A reader lists each (an MJCF joint or tendon equality, a URDF ``<mimic>``) as a :class:`TreeCoupling` on the tree's
joint names; :func:`model_couplings` turns them into :class:`~mobility.core.model.Coupling` s on the model's.

Examples
--------
>>> from mobility.core.model import Joint
>>> slides = [Joint(n, "P", ("g", n), axis=(0, 1, 0)) for n in ("r", "l")]
>>> model_couplings((TreeCoupling("joint[r]/mimic", ("r", "l"), (1.0, -1.0), 5),), {"r": "slide", "l": "slide"}, {"r": "r", "l": "l"}, "g.urdf", slides)
(Coupling(joints=('r', 'l'), coefficients=(1.0, -1.0)),)
>>> model_couplings((TreeCoupling("joint[r]/mimic", ("r", "b"), (1.0, -1.0), 5),), {"r": "slide", "b": "ball"}, {"r": "r"}, "g.urdf", slides)
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: g.urdf:5: joint[r]/mimic: couples joint 'b', a ball joint, not a hinge or slide; expected hinges and slides that move
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Mapping, Sequence

from ..core.model import Coupling, Joint, require_couplings
from ..errors import MechanismError, MechanismFileError, clipped

__all__ = ["TreeCoupling", "model_couplings"]


@dataclass(frozen=True)
class TreeCoupling:
    """``sum coefficients[j] * rate(joints[j]) = 0`` on hinges and slides of the tree (by name); ``key`` names the element for messages."""

    key: str
    joints: tuple[str, ...]
    coefficients: tuple[float, ...]
    line: int | None = None


def model_couplings(couplings: Iterable[TreeCoupling], kinds: Mapping[str, str], model_name: Mapping[str, str], file: str, joints: Sequence[Joint]) -> tuple[Coupling, ...]:
    """The couplings on the model's ``joints`` (``model_name`` of each hinge and slide the mechanism holds; ``kinds`` of every tree joint).

    Raises
    ------
    MechanismFileError
        At the element's line: a joint that is no hinge or slide, one the
        mechanism does not hold (welded still), a malformed coupling, or one
        of slides and turns together.
    """
    out = []
    listed = tuple(couplings)
    for c in listed:
        for name in c.joints:
            if name not in model_name:
                kind = kinds.get(name)
                why = f"a {kind} joint, not a hinge or slide" if kind not in (None, "hinge", "slide") else "a joint the mechanism does not hold (welded or fixed)"
                raise MechanismFileError(c.key, f"couples joint {clipped(name)!r}, {why}; expected hinges and slides that move", file=file, line=c.line)
        try:
            out.append(Coupling(tuple(model_name[n] for n in c.joints), c.coefficients))
        except MechanismError as exc:
            raise MechanismFileError(c.key, exc.message, file=file, line=c.line) from None
    try:
        return require_couplings(out, joints)
    except MechanismError as exc:  # couplings[k]...: the element that wrote it
        c = listed[int(exc.key[len("couplings["):].split("]", 1)[0])]
        raise MechanismFileError(c.key, exc.message, file=file, line=c.line) from None
