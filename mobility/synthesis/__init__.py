"""Type synthesis of limbs for a motion pattern (e.g. the seven 5-DOF limbs of 2T3R PKMs), by finite screws.

Its modules, in data-flow order: docs/finite-screws.md.

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

__all__ = ["synthesize", "generates", "candidate_joints", "named_pattern", "MotionPattern", "PatternFactor", "PATTERNS", "SynthesisResult",
           "SynthesizedLimb", "CandidateJoint", "TABLE_1_2T3R", "assemble_pkm", "pkm_document", "write_pkm_files"]
