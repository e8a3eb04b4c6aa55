"""Type synthesis of limbs for a motion pattern (e.g. the seven 5-DOF limbs of 2T3R PKMs).

:func:`synthesize` enumerates the serial limbs whose finite motion stays in a
:class:`MotionPattern`; :func:`assemble_pkm` builds a parallel mechanism from them.
"""

from .synthesis import MotionPattern, assemble_pkm, named_pattern, synthesize

__all__ = ["synthesize", "named_pattern", "MotionPattern", "assemble_pkm"]
