"""The limits on what a document may ask of the readers and the commands: one place for every bound.

A mechanism file is input from anywhere, so reading it, and then running any
command on it, must end quickly and in bounded memory whatever it holds.
:class:`Limits` gathers every bound: those the readers apply (file size,
nesting depth, nodes after alias expansion, limb copies, joints, frames,
expression length and depth) and the sizes of mechanism that the costlier
commands accept (finite motion, moving the mechanism, enumerating inputs).
Each error that a limit raises is one line naming the file, the key, the limit
and the environment variable that raises it.

The defaults are far above any real mechanism (the largest bundled file has 22
joints, the deepest nests 7 levels) and low enough that every command on a
file at the limits takes a few seconds and a few hundred MB (measured on two
cores: ``analyze``, ``check``, ``actuation``, ``jacobian``, ``convert``,
``plot`` and ``view`` of 5,000 joints take at most 4 s and 230 MB; the
command-specific limits are where their commands reach about 4 s; the
budget of poses times joints, ``max_moving_work``, where they reach 4 to
25 s).  Each limit
can be raised for a run by an environment variable ``MOBILITY_<FIELD>``
(``MOBILITY_MAX_JOINTS=20000``), or for one call by passing
``limits=Limits(...)`` to :func:`mobility.io.loader.load`.

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
        Size of a file (bytes; characters for text given directly).  A file is
        read with this cap, so a file growing as it is read ends in an error,
        not in a full memory (a device, ``/dev/zero``, is refused before it
        is opened).
    max_depth : int
        Nesting depth of the YAML document (a mapping or a list inside
        another counts one level), and of the ``<include>`` elements of an
        MJCF model.
    max_nodes : int
        Number of YAML nodes (keys, values, list items), counted with every
        alias expanded: a chain of aliases that would expand into millions of
        nodes ("billion laughs") stops here, whatever key holds it.
    max_copies : int
        ``copies`` of all the ``limbs`` patterns together.
    max_joints : int
        Joints of the mechanism, ``limbs`` expanded.  The analysis grows
        linearly with them (about 2 s and 90 MB at 10,000); the pictures of
        ``plot`` and the page of ``view`` a little faster.
    max_frames : int
        Frames, the one of each limb copy included.  Chains of ``parent``
        frames are bounded by ``max_depth``.
    max_elements : int
        Elements of an MJCF model, the files it includes and the copies its
        ``<replicate>`` elements make counted, checked before MuJoCo reads
        it: MuJoCo's parser takes time growing with the square of them
        (2.5 s for 10,000 named bodies, 20,000 elements).  The elements that the ``count``
        of ``<replicate>``, ``<flexcomp>`` and ``<composite>`` make are
        bounded by ``max_joints``.  An MJCF model's ``<connect>``, ``<weld>``
        and other equalities count as joints: MuJoCo's constraint rows grow
        with them as with the joints.
    max_asset_values : int
        Points that MuJoCo makes for the height fields and builtin meshes of
        an MJCF model as it reads the file, all together, before anything
        can be left out (a height field's ``nrow`` x ``ncol``, a builtin
        mesh's resolutions multiplied): about 140 bytes each at most, so
        that a 150-byte ``<hfield nrow="20000" ncol="20000">`` or ``<mesh
        builtin="wedge" params="10000 10000 ...">`` (gigabytes) is refused
        before MuJoCo reads it.
    max_expression_length : int
        Characters of one arithmetic expression.
    max_expression_depth : int
        Nesting depth of one expression (operators, calls and parentheses).
    max_finite_joints : int
        Joints of a mechanism that ``analyze --finite`` moves: it re-closes
        every loop by Newton's method with dense matrices, in about as many
        directions as the mechanism has freedoms, so its time grows about
        with the fourth power of the joints.
    max_moving_joints : int
        Joints of a mechanism that ``sweep``, ``--samples`` (``actuation``,
        ``view``) and ``view --vary`` move: every pose is closed with dense
        matrices, whose cost grows with the cube of the joints.
    max_enumerated_joints : int
        Joints of a mechanism whose inputs ``actuation --enumerate``
        searches: each candidate's actuation wrench is found against its
        whole limb, so the time grows with the square of the joints.
    max_moving_work : int
        Poses times joints of the poses that ``--samples`` (``actuation``,
        ``view``) and ``view --vary`` move and analyse one by one (a view
        draws at most 200 of a grid's poses): each pose is closed, analysed
        (and drawn) on its own, in time growing about with the joints.  At
        5,000 (16 poses of a 300-joint chain: ``actuation`` 4 s, ``view`` 7
        s; 227 poses of the 22-joint H4, whose four loops are closed at each:
        ``actuation`` 23 s) every bundled mechanism can be viewed at the 199
        sampled poses a view holds.
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
    mechanism : Mechanism
    limit : str
        The field of :class:`Limits`: ``"max_finite_joints"``,
        ``"max_moving_joints"`` or ``"max_enumerated_joints"``.
    what : str
        What the limit is for, as the user asked it (``"--finite"``).
    file : str
        The file, named in the message.

    Raises
    ------
    MechanismFileError
        ``FILE: joints: N joints are more than the limit of L for WHAT (set MOBILITY_... to raise it)``.
    """
    limits = current_limits()
    bound = getattr(limits, limit)
    count = len(mechanism.joints)
    if count > bound:
        raise MechanismFileError("joints", f"{count} joints are more than the limit of {bound} for {what} ({limits.hint(limit)})", file=file)


def require_work(mechanism: Mechanism, poses: int, what: str, file: str) -> None:
    """Refuse, in one line, a request to move ``mechanism`` into more poses than :attr:`Limits.max_moving_work` allows for its joints.

    Checked before the work starts (after :func:`require_size`): the product
    of the poses asked for and the mechanism's joints is what the time and
    the memory of ``--samples`` and ``view --vary`` grow with.

    Parameters
    ----------
    mechanism : Mechanism
    poses : int
        The poses the request moves and analyses one by one.
    what : str
        The request, as the user wrote it (``"--samples 1000"``).
    file : str
        The file, named in the message.

    Raises
    ------
    RequestError
        ``WHAT: N poses x J joints of FILE = P pose-joints, more than the limit of L (ask for fewer poses, or set MOBILITY_MAX_MOVING_WORK to raise it)``.

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
