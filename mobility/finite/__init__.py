"""Finite motion: is a freedom found at one pose full-cycle, or instantaneous only?

:func:`finite_mobility` moves the mechanism along its first-order freedoms,
re-closes every loop and analyses the poses reached.
"""

from .full_cycle import FiniteMobility, finite_mobility

__all__ = ["finite_mobility", "FiniteMobility"]
