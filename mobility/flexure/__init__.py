"""Flexure mechanisms: rods with their compliance, freedom and constraint spaces, and linear actuators.

Modules, in the order data flows:

``model``
    the frozen description: :class:`Material`, :class:`Rod`,
    :class:`ForceLine`, :class:`FlexureMechanism`, and the units.
``loader``
    flexure documents (YAML, top-level ``elements``): :func:`load_flexure`.
``compliance``
    :func:`rod_compliance`, :func:`compliance_matrix` of the end effector,
    and its normalised energy form.
``spaces``
    :func:`flexure_spaces`: freedom and constraint spaces from the
    eigenvalues of the compliance, split at a threshold.
``actuators``
    :func:`check_force_lines`, :func:`enumerate_force_lines`: linear
    actuators assessed with the public algebra of :mod:`mobility.actuation`.
"""

from .actuators import actuation_tolerance, check_force_lines, enumerate_force_lines, line_set_type
from .compliance import compliance_matrix, normalised_energy_form, rod_compliance
from .loader import is_flexure_document, load_flexure, loads_flexure, read_flexure
from .model import LENGTH_UNITS, MODULUS_UNITS, FlexureMechanism, ForceLine, Material, Rod
from .spaces import CLEAR_GAP, DEFAULT_THRESHOLD, FlexureSpaces, flexure_spaces

__all__ = [
    "load_flexure",
    "loads_flexure",
    "read_flexure",
    "is_flexure_document",
    "FlexureMechanism",
    "Material",
    "Rod",
    "ForceLine",
    "LENGTH_UNITS",
    "MODULUS_UNITS",
    "rod_compliance",
    "compliance_matrix",
    "normalised_energy_form",
    "flexure_spaces",
    "FlexureSpaces",
    "DEFAULT_THRESHOLD",
    "CLEAR_GAP",
    "check_force_lines",
    "enumerate_force_lines",
    "line_set_type",
    "actuation_tolerance",
]
