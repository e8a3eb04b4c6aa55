"""The limits on what a document may ask of the readers: one place for every bound.

A mechanism file is input from anywhere, so reading it must end quickly and in
bounded memory whatever it holds.  :class:`Limits` gathers every bound the
readers apply (file size, nesting depth, nodes after alias expansion, limb
copies, joints, expression length and depth); each error that a limit raises
is one line naming the file, the line, the key, the limit and the environment
variable that raises it.

The defaults are far above any real mechanism (the largest bundled file has 22
joints, the deepest nests 7 levels) and low enough that reading, and then
analysing, a file at the limits takes a few seconds and a few hundred MB.
Each limit can be raised for a run by an environment variable
``MOBILITY_<FIELD>`` (``MOBILITY_MAX_JOINTS=5000``), or for one call by
passing ``limits=Limits(...)`` to :func:`mobility.io.loader.load`.

Examples
--------
>>> Limits().max_joints
1000
>>> Limits.from_environment({"MOBILITY_MAX_JOINTS": "5000"}).max_joints
5000
>>> Limits().hint("max_joints")
'set MOBILITY_MAX_JOINTS to raise it'
>>> Limits.from_environment({"MOBILITY_MAX_DEPTH": "deep"})
Traceback (most recent call last):
...
mobility.errors.RequestError: MOBILITY_MAX_DEPTH: expected a positive integer, got 'deep'
"""

from __future__ import annotations

import os
from dataclasses import dataclass, fields
from typing import Mapping

from ..errors import RequestError

__all__ = ["Limits", "DEFAULT_LIMITS", "current_limits"]


@dataclass(frozen=True)
class Limits:
    """Every bound the document readers apply.

    Parameters
    ----------
    max_file_bytes : int
        Size of a file (bytes; characters for text given directly).  A file is
        read with this cap, so ``/dev/zero`` ends in an error, not in a full
        memory.
    max_depth : int
        Nesting depth of the YAML document (a mapping or a list inside
        another counts one level).
    max_nodes : int
        Number of YAML nodes (keys, values, list items), counted with every
        alias expanded: a chain of aliases that would expand into millions of
        nodes ("billion laughs") stops here, whatever key holds it.
    max_copies : int
        ``copies`` of all the ``limbs`` patterns together.
    max_joints : int
        Joints of the mechanism, ``limbs`` expanded (the analysis needs time
        and memory growing faster than linearly with them).
    max_frames : int
        Frames, the one of each limb copy included.  Chains of ``parent``
        frames are bounded by ``max_depth``.
    max_expression_length : int
        Characters of one arithmetic expression.
    max_expression_depth : int
        Nesting depth of one expression (operators, calls and parentheses).
    """

    max_file_bytes: int = 4 * 1024 * 1024
    max_depth: int = 64
    max_nodes: int = 200_000
    max_copies: int = 1000
    max_joints: int = 1000
    max_frames: int = 1000
    max_expression_length: int = 1000
    max_expression_depth: int = 100

    @staticmethod
    def variable(name: str) -> str:
        """The environment variable of the field ``name`` (``MOBILITY_MAX_JOINTS``)."""
        return f"MOBILITY_{name.upper()}"

    def hint(self, name: str) -> str:
        """How to raise the limit ``name``, for an error message."""
        return f"set {self.variable(name)} to raise it"

    @classmethod
    def from_environment(cls, environ: Mapping[str, str] | None = None) -> "Limits":
        """The defaults, with each ``MOBILITY_<FIELD>`` variable of ``environ`` applied.

        Raises
        ------
        RequestError
            When a variable is not a positive integer.
        """
        env = os.environ if environ is None else environ
        changed: dict[str, int] = {}
        for f in fields(cls):
            raw = env.get(cls.variable(f.name))
            if raw is None:
                continue
            try:
                value = int(raw.strip())
            except ValueError:
                value = 0
            if value < 1:
                raise RequestError(f"{cls.variable(f.name)}: expected a positive integer, got {raw!r}")
            changed[f.name] = value
        return cls(**changed) if changed else DEFAULT_LIMITS


DEFAULT_LIMITS = Limits()
"""The limits when no environment variable changes them."""


def current_limits(limits: Limits | None = None) -> Limits:
    """``limits`` if given, else the defaults with the environment applied."""
    return limits if limits is not None else Limits.from_environment()
