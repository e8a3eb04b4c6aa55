"""Options shared by several subcommands."""

from __future__ import annotations

import argparse

from ..errors import MobilityError
from ..tolerance import Tolerance

__all__ = ["UsageError", "add_tolerance_option", "tolerance_from"]


class UsageError(MobilityError, ValueError):
    """A command-line option has a value out of its range (exit status 2)."""


def add_tolerance_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--tol``, the relative rank threshold of the tolerance policy."""
    parser.add_argument("--tol", type=float, default=Tolerance().rank, help="relative rank threshold (default: %(default)g)")


def tolerance_from(args: argparse.Namespace) -> Tolerance:
    """The :class:`~mobility.tolerance.Tolerance` asked for by ``--tol``.

    Raises
    ------
    UsageError
        When the value lies outside ``[inexact, near_singular)`` of the policy.
    """
    base = Tolerance()
    if not (base.inexact <= args.tol < base.near_singular):
        raise UsageError(f"--tol must lie in [{base.inexact:g}, {base.near_singular:g}), got {args.tol:g}")
    return Tolerance(rank=args.tol)
