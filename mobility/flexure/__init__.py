"""Flexure mechanisms: rods with their compliance, freedom and actuation spaces.

A flexure document (``elements`` of type ``rod`` between bodies) is read by
:func:`load_flexure`; :func:`flexure_spaces` gives the freedom and constraint
spaces from the compliance matrix; :func:`check_force_lines` checks actuators.
"""

from .loader import load_flexure, loads_flexure
from .spaces import FlexureMechanism, check_force_lines, flexure_spaces

__all__ = ["load_flexure", "loads_flexure", "flexure_spaces", "check_force_lines", "FlexureMechanism"]
