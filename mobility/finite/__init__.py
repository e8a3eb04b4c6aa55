"""Finite motion: is a freedom found at one pose full-cycle, or instantaneous only?

:func:`finite_mobility` moves the mechanism along its first-order freedoms,
re-closes every loop and analyses the poses reached.  Modules, in the order
the algorithm uses them:

``parameters``
    the algorithm's parameters, each with why it has its value.
``results``
    the frozen results: :class:`FiniteMobility`, ``Branch``, ``Probe``, ``SecondOrder``.
``orders``
    first and second order at a pose.
``moves``
    probing moves: step along a direction, re-close the loops.
``branches``
    group the poses reached into branches and measure each.
``verdict``
    the verdict and its explanation.
``full_cycle``
    :func:`finite_mobility`, the entry point.

The text report of ``mobility analyze --finite`` is
:func:`mobility.report.finite.finite_report`.
"""

from .full_cycle import finite_mobility
from .parameters import DEFAULT_STEPS
from .results import VERDICTS, Branch, FiniteMobility, Probe, SecondOrder

__all__ = ["finite_mobility", "FiniteMobility", "Branch", "Probe", "SecondOrder", "VERDICTS", "DEFAULT_STEPS"]
