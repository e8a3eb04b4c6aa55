"""Finite motion: is a freedom found at one pose full-cycle, or instantaneous only?

:func:`finite_mobility` moves the mechanism along its first-order freedoms,
re-closes every loop and analyses the poses reached.  Modules, in the order
the algorithm uses them (docs/finite.md, "Where the code is"): ``parameters``,
``results``, ``orders`` (first and second order), ``moves``, ``branches``,
``verdict`` and ``full_cycle`` (:func:`finite_mobility`, the entry point).

The text report of ``mobility analyze --finite`` is
:func:`mobility.report.finite.finite_report`.
"""

from .full_cycle import finite_mobility
from .parameters import DEFAULT_STEPS
from .results import VERDICTS, Branch, FiniteMobility, Probe, SecondOrder

__all__ = ["finite_mobility", "FiniteMobility", "Branch", "Probe", "SecondOrder", "VERDICTS", "DEFAULT_STEPS"]
