"""The limits on what a document may ask of the readers and the commands: one place for every bound.

A mechanism file is input from anywhere, so reading it and running any command on it must end quickly and in bounded
memory.  Each error a limit raises is one line naming the file, the key, the limit and the environment variable
``MOBILITY_<FIELD>`` that raises it for a run (``limits=Limits(...)`` to :func:`mobility.io.loader.load` for one call).
The defaults, and what the commands cost at them: ``docs/file-format.md`` (Limits).

Examples
--------
>>> Limits().max_joints
5000
>>> Limits.from_environment({"MOBILITY_MAX_JOINTS": "20000"}).max_joints
20000
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

from ..core.model import Mechanism
from ..core.validation import integer_from_text, require_integer
from ..errors import MechanismFileError, RequestError, shown_argument

__all__ = ["Limits", "DEFAULT_LIMITS", "current_limits", "require_size", "require_work"]


@dataclass(frozen=True)
class Limits:
    """Every bound the document readers apply.

    Parameters
    ----------
    max_file_bytes : int
        Size of a file (bytes; characters for text given directly), read with this cap.
    max_depth : int
        Nesting depth of the YAML document, and of an MJCF model's ``<include>`` elements.
    max_nodes : int
        YAML nodes counted with every alias expanded ("billion laughs" stop here).
    max_copies : int
        ``copies`` of all the ``limbs`` patterns together.
    max_joints : int
        Joints, ``limbs`` expanded, MJCF copies and equalities counted (the analysis: 2 s, 90 MB at 10,000).
    max_frames : int
        Frames, the one of each limb copy included.
    max_elements : int
        Elements of an MJCF model and its includes and copies (MuJoCo's parser: 2.5 s at 20,000).
    max_asset_values : int
        Points MuJoCo makes for an MJCF model's height fields and builtin meshes as it reads it.
    max_expression_length, max_expression_depth : int
        Characters, and nesting depth, of one arithmetic expression.
    max_finite_joints : int
        Joints ``analyze --finite`` moves (its time grows about with their fourth power).
    max_moving_joints : int
        Joints ``sweep``, ``--samples`` and ``view --vary`` move (cube of the joints).
    max_enumerated_joints : int
        Joints whose inputs ``actuation --enumerate`` searches (square of the joints).
    max_moving_work : int
        Poses times joints that ``--samples`` and ``view --vary`` move and analyse one by one
        (at 5,000 every bundled mechanism can be viewed at the 199 sampled poses a view holds).
    """

    max_file_bytes: int = 4 * 1024 * 1024
    max_depth: int = 64
    max_nodes: int = 200_000
    max_copies: int = 5000
    max_joints: int = 5000
    max_frames: int = 5000
    max_elements: int = 20_000
    max_asset_values: int = 1_000_000
    max_expression_length: int = 1000
    max_expression_depth: int = 100
    max_finite_joints: int = 50
    max_moving_joints: int = 300
    max_enumerated_joints: int = 200
    max_moving_work: int = 5_000

    def __post_init__(self) -> None:
        """Every field a positive integer (``int`` or a numpy integer; not a bool, a float or a string), else a :class:`~mobility.errors.RequestError`.

        Examples
        --------
        >>> Limits(max_file_bytes=-1)
        Traceback (most recent call last):
        ...
        mobility.errors.RequestError: Limits: max_file_bytes: expected a positive integer, got -1
        """
        for f in fields(self):
            object.__setattr__(self, f.name, require_integer(getattr(self, f.name), "a positive integer", caller="Limits", argument=f.name, low=1))

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
            try:  # ASCII digits only: int() alone reads "١٠" as 10, "1_0" as 10, " 5000 " as 5000
                value = integer_from_text(raw) if raw.isdigit() else 0
            except ValueError:
                value = 0
            if value < 1:
                raise RequestError(argument=cls.variable(f.name), expected="a positive integer", got=shown_argument(raw))
            changed[f.name] = value
        return cls(**changed) if changed else DEFAULT_LIMITS


DEFAULT_LIMITS = Limits()
"""The limits when no environment variable changes them."""


def current_limits(limits: Limits | None = None) -> Limits:
    """``limits`` if given, else the defaults with the environment applied."""
    return limits if limits is not None else Limits.from_environment()


def require_size(mechanism: Mechanism, limit: str, what: str, file: str) -> None:
    """Refuse, in one line, a mechanism with more joints than the command-specific ``limit`` of :class:`Limits`.

    Parameters
    ----------
    limit : str
        The field of :class:`Limits` (``"max_finite_joints"``).
    what : str
        What the limit is for, as the user asked it (``"--finite"``).
    """
    limits = current_limits()
    bound = getattr(limits, limit)
    count = len(mechanism.joints)
    if count > bound:
        raise MechanismFileError("joints", f"{count} joints are more than the limit of {bound} for {what} ({limits.hint(limit)})", file=file)


def require_work(mechanism: Mechanism, poses: int, what: str, file: str) -> None:
    """Refuse, in one line, a request to move ``mechanism`` into more poses than :attr:`Limits.max_moving_work` allows for its joints.

    Checked before the work starts (after :func:`require_size`); ``what`` is
    the request as the user wrote it (``"--samples 1000"``).

    Examples
    --------
    >>> from mobility.core.model import Joint
    >>> chain = Mechanism("chain", "L0", "L300", tuple(Joint(f"J{i}", "R", (f"L{i}", f"L{i + 1}"), axis=(0, 0, 1), point=(i, 0, 0)) for i in range(300)))
    >>> require_work(chain, 16, "--samples 16", "chain.yaml")
    >>> require_work(chain, 1000, "--samples 1000", "chain.yaml")
    Traceback (most recent call last):
    mobility.errors.RequestError: --samples 1000: 1,000 poses x 300 joints of chain.yaml = 300,000 pose-joints, more than the limit of 5,000 (ask for fewer poses, or set MOBILITY_MAX_MOVING_WORK to raise it)
    """
    limits = current_limits()
    joints = len(mechanism.joints)
    work = poses * joints
    if work > limits.max_moving_work:
        raise RequestError(f"{what}: {poses:,} poses x {joints:,} joints of {file} = {work:,} pose-joints, more than the limit of "
                           f"{limits.max_moving_work:,} (ask for fewer poses, or {limits.hint('max_moving_work')})")
