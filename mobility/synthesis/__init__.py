"""Type synthesis of limbs for a motion pattern (e.g. the seven 5-DOF limbs of 2T3R PKMs), by finite screws.

One module per step, in the order the data flows:

``patterns``
    motion patterns as triangle products of finite-screw factors
    (:class:`PatternFactor`, :class:`MotionPattern`, :func:`named_pattern`).
``generic_rank``
    the dimension of a chain's set of finite motions (generic rank of its twists).
``limb_types``
    joints labelled by the pattern's directions and points, and the limb
    types named from them as in the paper (:class:`SynthesizedLimb`).
``enumeration``
    :func:`synthesize`: every chain of R and P joints whose finite motions
    are the pattern (:class:`SynthesisResult`); :func:`generates` for one chain.
``assembly``
    :func:`assemble_pkm`: a parallel mechanism of a synthesized limb and
    6-DOF limbs; :func:`pkm_document` and :func:`write_pkm_files`: its
    mechanism file, checked by the analysis.

Examples
--------
>>> from mobility.synthesis import named_pattern, synthesize
>>> sorted(s.name for s in synthesize(named_pattern("3R"), verify_samples=1).structures)
['S']
"""

from .assembly import assemble_pkm, pkm_document, write_pkm_files
from .enumeration import SynthesisResult, candidate_joints, generates, synthesize
from .limb_types import TABLE_1_2T3R, CandidateJoint, SynthesizedLimb
from .patterns import PATTERNS, MotionPattern, PatternFactor, named_pattern

__all__ = [
    "synthesize",
    "generates",
    "candidate_joints",
    "named_pattern",
    "MotionPattern",
    "PatternFactor",
    "PATTERNS",
    "SynthesisResult",
    "SynthesizedLimb",
    "CandidateJoint",
    "TABLE_1_2T3R",
    "assemble_pkm",
    "pkm_document",
    "write_pkm_files",
]
