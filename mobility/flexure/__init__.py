"""Flexure mechanisms: rods with their compliance, freedom and constraint spaces, and linear actuators.

Modules, in data-flow order: ``model`` (the frozen description and units),
``loader`` (flexure documents, top-level ``elements``), ``compliance`` (of the
rods and the end effector), ``spaces`` (freedom and constraint spaces from the
compliance's eigenvalues, split at a threshold), ``actuators`` (linear
actuators assessed with the algebra of :mod:`mobility.actuation`).
"""

from .actuators import actuation_tolerance, check_force_lines, enumerate_force_lines, line_set_type
from .compliance import compliance_matrix, normalised_energy_form, rod_compliance
from .loader import is_flexure_document, load_flexure, loads_flexure, read_flexure
from .model import LENGTH_UNITS, MODULUS_UNITS, FlexureMechanism, ForceLine, Material, Rod
from .spaces import CLEAR_GAP, DEFAULT_THRESHOLD, FlexureSpaces, flexure_spaces

__all__ = ["load_flexure", "loads_flexure", "read_flexure", "is_flexure_document", "FlexureMechanism", "Material", "Rod", "ForceLine",
           "LENGTH_UNITS", "MODULUS_UNITS", "rod_compliance", "compliance_matrix", "normalised_energy_form", "flexure_spaces", "FlexureSpaces",
           "DEFAULT_THRESHOLD", "CLEAR_GAP", "check_force_lines", "enumerate_force_lines", "line_set_type", "actuation_tolerance"]
