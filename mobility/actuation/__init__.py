"""Actuation spaces: which inputs may drive a mechanism, and how well.

The method is that of Li, Shan, Yu and Ke, "Actuation Spaces Synthesis of
Lower-Mobility Parallel Mechanisms Based on Screw Theory" (Chinese Journal of
Mechanical Engineering, 2021): a choice of inputs is valid when its actuation
wrenches are linearly independent of the constraint wrenches of the end
effector, so that the two together span all six dimensions.

Its modules, and :mod:`mobility.flexure`'s use of ``assessment`` and
``ranking``: docs/actuation.md, "Where the code lives".

Examples: :func:`check_actuation`, :func:`enumerate_actuations`, :func:`locked_dof`.
"""

from .assessment import Assessment, EndEffectorSpaces, InputWrench, assess_inputs, assess_wrenches
from .locking import lock_joints, locked_dof
from .ranking import MAX_COMBINATIONS, combination_type, combinations_count, combine_poses, inputs_per_combination, limit_combinations, rank_combinations
from .results import REDUNDANT, SINGULAR, VALID, VERDICTS, ActuationCheck, ActuationInput, Combination, Enumeration, TypeGroup
from .rigid import ENUMERATION_MODES, check_actuation, check_over_poses, enumerate_actuations
from .rigid_pose import RigidPose

__all__ = ["check_actuation", "check_over_poses", "enumerate_actuations", "ENUMERATION_MODES", "RigidPose", "lock_joints", "locked_dof", "VALID",
           "SINGULAR", "REDUNDANT", "VERDICTS", "ActuationCheck", "ActuationInput", "Combination", "TypeGroup", "Enumeration", "EndEffectorSpaces",
           "InputWrench", "Assessment", "assess_wrenches", "assess_inputs", "MAX_COMBINATIONS", "combination_type", "combinations_count",
           "limit_combinations", "inputs_per_combination", "combine_poses", "rank_combinations"]
