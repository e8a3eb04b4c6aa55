"""Options shared by several subcommands."""

from __future__ import annotations

import argparse

from ..core.tolerance import Tolerance
from ..errors import RequestError

__all__ = ["add_tolerance_option", "tolerance_from"]


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
