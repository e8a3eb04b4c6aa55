"""Linear actuators on a flexure: force lines assessed like the actuated joints of a rigid mechanism.

A set of force lines is valid when their wrenches and the constraint space span
six dimensions (:mod:`mobility.actuation.assessment`, the freedom space as the
end effector's twists); an input's rate is the speed of its point along its
line. The flexure half of Li, Shan, Yu and Ke, "Actuation Spaces Synthesis of
Lower-Mobility Parallel Mechanisms Based on Screw Theory" (Chinese Journal of
Mechanical Engineering, 2021).

Examples
--------
>>> from mobility.flexure.model import FlexureMechanism, ForceLine, Material, Rod
>>> steel = Material("steel", 200e9, 0.3)
>>> rods = tuple(Rod(f"w{i}", ("g", "s"), (x, y, 0), (0, 0, 1), 0.1, 0.001, steel)
...              for i, (x, y) in enumerate([(0, 0), (0.05, 0), (0, 0.05)]))
>>> m = FlexureMechanism("three wires", "g", "s", rods)   # three parallel wires: 2T1R
>>> push = [ForceLine("x", (0, 0, 0.1), (1, 0, 0)), ForceLine("y", (0, 0, 0.1), (0, 1, 0)),
...         ForceLine("t", (0.05, 0, 0.1), (0, 1, 0))]
>>> check = check_force_lines(m, [], lines=push)
>>> check.pattern, check.verdict
('2T1R', 'valid')
>>> check_force_lines(m, [], lines=push[:2]).verdict   # no input turns the stage
'actuation-singular'
"""

from __future__ import annotations

import itertools
from typing import Sequence

import numpy as np

from ..actuation import (ActuationCheck, Enumeration, InputWrench, assess_inputs, assess_wrenches, combinations_count, combine_poses,
                         inputs_per_combination, rank_combinations)
from ..core.joint_screws import Normalisation
from ..core.linalg import rank
from ..core.validation import require_no_repeats
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, binary_scale, characteristic_scale
from ..core.transforms import skew
from ..errors import MechanismError, counted, name_list
from .model import FlexureMechanism, ForceLine
from .spaces import FlexureSpaces, flexure_spaces

__all__ = ["check_force_lines", "enumerate_force_lines", "line_set_type", "actuation_tolerance"]


def check_force_lines(mechanism: FlexureMechanism, names: Sequence[str] | None = None, *, lines: Sequence[ForceLine] = (),
                      threshold: float | None = None, tol: Tolerance = DEFAULT_TOLERANCE) -> ActuationCheck:
    """Assess a set of linear actuators (force lines) on a flexure mechanism.

    Parameters
    ----------
    names : sequence of str, optional
        Actuators of the document (default: those marked ``actuated: true``).
    lines : sequence of ForceLine
        Further force lines given in code (global frame, document unit).
    threshold : float, optional
        See :func:`~mobility.flexure.spaces.flexure_spaces`.

    Returns
    -------
    ActuationCheck
        ``kind`` ``"flexure"``: the freedom and constraint spaces stand for the end effector's twists and constraint wrenches.

    Raises
    ------
    MechanismError
        When a name is not an actuator of the document.
    """
    spaces = flexure_spaces(mechanism, threshold, tol=tol)
    chosen = _select(mechanism, names) + list(lines)
    norm = spaces.normalised.normalisation
    inputs = [_input_wrench(a, norm) for a in chosen]
    warnings = list(spaces.warnings)
    if not chosen:
        warnings.append("no actuator is chosen (mark actuators with `actuated: true`, or name them)")
    return assess_inputs(mechanism.name, "flexure", inputs, spaces.normalised, actuation_tolerance(spaces, tol), warnings=warnings,
                         length_unit=mechanism.length_unit)


def enumerate_force_lines(mechanism: FlexureMechanism, k: int | None = None, *, threshold: float | None = None, tol: Tolerance = DEFAULT_TOLERANCE) -> Enumeration:
    """Assess every set of ``k`` candidate actuators (default: the DOF of the freedom space).

    Combinations are grouped by :func:`line_set_type` and ranked as in
    :func:`mobility.actuation.enumerate_actuations`.

    Raises
    ------
    RequestError
        When ``k`` is not a non-negative integer or there are too many combinations to try.
    """
    spaces = flexure_spaces(mechanism, threshold, tol=tol)
    k = inputs_per_combination(k, spaces.dof)
    candidates = list(mechanism.actuators)
    combinations_count(len(candidates), k, "choose a smaller k")
    norm = spaces.normalised.normalisation
    atol = actuation_tolerance(spaces, tol)
    wrench = {a.name: _input_wrench(a, norm) for a in candidates}
    twists, constraints = spaces.normalised.twists, spaces.normalised.constraints
    found = []
    for combo in itertools.combinations(candidates, k):
        inputs = [wrench[a.name] for a in combo]
        assessment = assess_wrenches([i.wrench for i in inputs], [i.rate for i in inputs], twists, constraints, atol)
        found.append(combine_poses(tuple(a.name for a in combo), line_set_type(combo, tol=atol), [assessment]))
    ranked, groups = rank_combinations(found)
    warnings = list(spaces.warnings)
    if not candidates:
        warnings.append("the document lists no candidate actuators")
    if k != spaces.dof:
        warnings.append(f"{counted(k, 'input')} per combination for {spaces.dof} DOF: none can be valid")
    return Enumeration(mechanism.name, "flexure", spaces.dof, spaces.pattern, "any", k, ranked, groups, ("given pose",), tuple(warnings))


def actuation_tolerance(spaces: FlexureSpaces, tol: Tolerance = DEFAULT_TOLERANCE) -> Tolerance:
    """The rank policy of a flexure's actuation assessment, from the gap between its eigenvalue clusters.

    A real flexure's spaces are an ideal one's only up to ``eps``, the ratio of
    the relative compliances either side of the threshold (the three-rod
    flexure's constraint forces meet ``0.6 eps L`` from where the rod axes
    meet): relative singular values up to ``eps`` count as zero (bounded to
    ``[tol.rank, 0.1]``), and warn below ten times that.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> t = actuation_tolerance(SimpleNamespace(gap=(0.8, 0.0008)))
    >>> round(t.rank, 6), round(t.near_singular, 6)
    (0.001, 0.01)
    """
    above, below = spaces.gap
    eps = below / above if above > 0 else 1.0
    threshold = min(max(eps, tol.rank), 0.1)
    return Tolerance(rank=threshold, near_singular=min(10.0 * threshold, 0.5), inexact=min(tol.inexact, threshold))


def line_set_type(lines: Sequence[ForceLine], *, tol: Tolerance = DEFAULT_TOLERANCE) -> str:
    """Classify a set of force lines: ``parallel``, ``concurrent``, ``coplanar`` or ``general``.

    Decided by the rank policy in coordinates centred on the lines' points and
    scaled by their spread (independent of units and placement); one line is ``single``.

    Examples
    --------
    >>> z = ForceLine("a", (0, 0, 0), (0, 0, 1))
    >>> line_set_type([z, ForceLine("b", (1, 0, 0), (0, 0, 1))])
    'parallel'
    >>> line_set_type([ForceLine("a", (1, 0, 0), (-1, 0, 1)), ForceLine("b", (0, 1, 0), (0, -1, 1)),
    ...                ForceLine("c", (-1, 0, 0), (1, 0, 1))])
    'concurrent'
    """
    if len(lines) < 2:
        return "single"
    pts = np.array([a.point for a in lines])
    dirs = np.array([a.direction for a in lines])
    centre, length = characteristic_scale(pts)
    p = (pts - centre) / length

    if rank(dirs.T, tol) == 1:
        return "parallel"
    # Concurrent: one point x with (p_i - x) x d_i = 0 for all i, i.e. [d_i]x x = d_i x p_i (rank test).
    a = np.vstack([skew(d) for d in dirs])
    b = np.concatenate([np.cross(d, q) for d, q in zip(dirs, p)])
    if rank(a, tol) == rank(np.column_stack([a, b]), tol):
        return "concurrent"
    # Coplanar: a plane n.x = delta holding every point and direction.
    m = np.vstack([np.column_stack([p, -np.ones(len(p))]), np.column_stack([dirs, np.zeros(len(dirs))])])
    if rank(m, tol) < 4:
        return "coplanar"
    return "general"


def _select(mechanism: FlexureMechanism, names: Sequence[str] | None) -> list[ForceLine]:
    """The named actuators of the document (default: those marked actuated)."""
    by_name = {a.name: a for a in mechanism.actuators}
    if names is None:
        return [a for a in mechanism.actuators if a.actuated]
    out = []
    require_no_repeats(names, "actuators")
    for n in names:
        if n not in by_name:
            raise MechanismError("actuators", f"unknown actuator {n!r}; expected one of: {name_list(by_name)}")
        out.append(by_name[n])
    return out


def _input_wrench(line: ForceLine, norm: Normalisation) -> InputWrench:
    """A force line as an input: its unit wrench (normalised) and its rate, the length of its force part (the point's speed)."""
    with np.errstate(over="ignore", invalid="ignore"):  # a line past the largest float: refused by the assessment, by name
        w = norm.from_world(line.wrench())[:, 0]
        w = w * binary_scale(w)  # before squaring: a line however far has a unit wrench
        w = w / np.linalg.norm(w)
    return InputWrench(line.name, "F", None, w, float(np.linalg.norm(w[:3])))
