"""Actuation spaces of rigid mechanisms: are the chosen input joints a valid actuation?

:func:`check_actuation` gives the actuation wrenches of the joints marked
``actuated`` and the verdict (valid, actuation-singular, redundant);
:func:`enumerate_actuations` lists every valid choice of inputs.
"""

from .actuation import ActuationCheck, Enumeration, check_actuation, enumerate_actuations, locked_dof

__all__ = ["check_actuation", "enumerate_actuations", "locked_dof", "ActuationCheck", "Enumeration"]
