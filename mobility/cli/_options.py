"""Options shared by several subcommands: each ``add_*`` function registers them, its partner reads them back checked."""

from __future__ import annotations

import argparse

from ..core.model import Mechanism
from ..core.tolerance import Tolerance
from ..errors import RequestError

__all__ = ["add_tolerance_option", "tolerance_from", "add_pose_sampler_options", "sampled_poses"]


def add_tolerance_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--tol``, the relative rank threshold of the tolerance policy."""
    parser.add_argument("--tol", type=float, default=Tolerance().rank, help="relative rank threshold (default: %(default)g)")


def tolerance_from(args: argparse.Namespace) -> Tolerance:
    """The :class:`~mobility.core.tolerance.Tolerance` asked for by ``--tol``.

    Raises
    ------
    RequestError
        When the value lies outside ``[inexact, near_singular)`` of the policy.
    """
    base = Tolerance()
    if not (base.inexact <= args.tol < base.near_singular):
        raise RequestError(f"--tol must lie in [{base.inexact:g}, {base.near_singular:g}), got {args.tol:g}")
    return Tolerance(rank=args.tol)


def add_pose_sampler_options(parser: argparse.ArgumentParser, *, samples_help: str, step: float, samples_group: argparse._ActionsContainer | None = None) -> None:
    """Add ``--samples N``, ``--step`` and ``--seed``: further poses reached by moving the mechanism.

    Parameters
    ----------
    parser : argparse.ArgumentParser
    samples_help : str
        What the subcommand does with the poses.
    step : float
        The default ``--step`` of :func:`~mobility.core.poses.sample_poses`.
    samples_group : optional
        A group of ``parser`` (e.g. mutually exclusive) that ``--samples`` joins.
    """
    (samples_group or parser).add_argument("--samples", type=int, default=0, metavar="N", help=samples_help + " (default: %(default)s)")
    parser.add_argument("--step", type=float, default=step, help="step of the pose sampler (default: %(default)g)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the pose sampler (default: %(default)d)")


def sampled_poses(args: argparse.Namespace, mechanism: Mechanism) -> list[Mechanism]:
    """The poses asked for by ``--samples``, ``--step`` and ``--seed`` (none for ``--samples 0``).

    Raises
    ------
    RequestError
        For a negative ``--samples`` or a ``--step`` that is not positive.
    """
    if args.samples < 0 or args.step <= 0:
        raise RequestError("--samples must not be negative and --step must be positive")
    if not args.samples:
        return []
    from ..core.poses import sample_poses  # the finite kinematics: imported only by the commands that move

    return sample_poses(mechanism, args.samples, step=args.step, seed=args.seed)
