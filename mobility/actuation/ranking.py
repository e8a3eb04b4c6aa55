"""Combinations of inputs: their type, their verdict over several poses, and their ranking.

A combination is valid only when valid at every pose; its conditioning is the
worst over the poses. Counted per type (``3R``, ``2R1P``, ... as Li, Shan, Yu
and Ke write them, or the geometry of a set of force lines).

Examples
--------
>>> from mobility.core.tolerance import RankDecision
>>> from mobility.actuation.assessment import Assessment
>>> from mobility.actuation.results import SINGULAR, VALID
>>> pose = lambda verdict, kappa: Assessment(verdict, RankDecision(6), None, kappa, ())
>>> c = combine_poses(("R1", "P2"), "1R1P", [pose(VALID, 0.4), pose(SINGULAR, 0.0), pose(VALID, 0.2)])
>>> c.verdict, c.valid_poses, c.conditioning, c.worst_pose, c.failures
('actuation-singular', 2, 0.0, 1, ((1, 'actuation-singular'),))
>>> ranked, groups = rank_combinations([c, combine_poses(("P1", "P2"), "2P", [pose(VALID, 0.3)])])
>>> [r.inputs for r in ranked], [(g.type, g.valid, g.total) for g in groups]
([('P1', 'P2'), ('R1', 'P2')], [('1R1P', 0, 1), ('2P', 1, 1)])
"""

from __future__ import annotations

import re
from math import comb
from typing import Iterable, Sequence

import numpy as np

from ..core.validation import require_integer
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, first_least
from ..errors import RequestError, shown_argument
from .assessment import Assessment
from .results import SINGULAR, VALID, VERDICTS, Combination, TypeGroup

__all__ = ["MAX_COMBINATIONS", "combination_type", "combine_poses", "rank_combinations", "combinations_count", "limit_combinations", "inputs_per_combination"]

MAX_COMBINATIONS = 20000
"""Largest number of input combinations an enumeration will try."""

_TYPE_ORDER = "RPHCUSEF"


def combination_type(kinds: Iterable[str]) -> str:
    """The type of a combination of inputs, as the paper writes it: counts of each joint type.

    Examples
    --------
    >>> combination_type("RPR"), combination_type(["P", "P", "P"]), combination_type("PRP")
    ('2R1P', '3P', '1R2P')
    """
    kinds = list(kinds)
    order = sorted(set(kinds), key=lambda k: (_TYPE_ORDER.find(k) if k in _TYPE_ORDER else len(_TYPE_ORDER), k))
    return "".join(f"{kinds.count(k)}{k}" for k in order) or "0"


def _type_key(t: str) -> tuple:
    """Sort key putting 3R, 2R1P, 1R2P, 3P in the paper's order."""
    counts = dict.fromkeys(_TYPE_ORDER, 0)
    for number, kind in re.findall(r"(\d+)(\D)", t):
        counts[kind] = counts.get(kind, 0) + int(number)
    return tuple(-counts[k] for k in _TYPE_ORDER) + (t,)


def combine_poses(inputs: tuple[str, ...], type: str, per_pose: Sequence[Assessment]) -> Combination:
    """One combination's verdict over its assessments at several poses (pose 0 first)."""
    verdicts, conditioning = [a.verdict for a in per_pose], [a.conditioning for a in per_pose]
    failures = tuple((i, v) for i, v in enumerate(verdicts) if v != VALID)
    margins = [a.actuation_margin if a.verdict != SINGULAR else np.inf for a in per_pose]
    k, m = first_least(conditioning), first_least(margins)
    return Combination(inputs, type, max(verdicts, key=VERDICTS.index), len(per_pose) - len(failures), len(per_pose), float(conditioning[k]), k,
                       failures, float(min(margins[m], 1.0)), m)


def rank_combinations(found: Sequence[Combination]) -> tuple[tuple[Combination, ...], tuple[TypeGroup, ...]]:
    """The combinations ranked (best first), and the valid and total counts of each type.

    Conditioning numbers equal to round-off (the policy's ``round_off``) tie,
    broken by the input names: the order does not hang on LAPACK's last bit.
    """
    ranked = sorted(found, key=lambda c: (VERDICTS.index(c.verdict), -_to_round_off(c.conditioning), c.inputs))
    groups: dict[str, list[int]] = {}
    for c in found:
        g = groups.setdefault(c.type, [0, 0])
        g[0] += c.verdict == VALID
        g[1] += 1
    return tuple(ranked), tuple(TypeGroup(t, v, n) for t, (v, n) in sorted(groups.items(), key=lambda kv: _type_key(kv[0])))


def _to_round_off(x: float, tol: Tolerance = DEFAULT_TOLERANCE) -> float:
    """``x`` with the digits below the round-off rule dropped."""
    digits = max(1, round(-np.log10(tol.round_off)))
    return float(f"{x:.{digits}g}")


def combinations_count(candidates: int, k: int, advice: str) -> int:
    """How many sets of ``k`` of ``candidates`` inputs there are, refusing more than :data:`MAX_COMBINATIONS`.

    Raises
    ------
    RequestError
        When ``k`` is negative, or there are too many (``advice`` says what to do).

    Examples
    --------
    >>> combinations_count(6, 3, ""), combinations_count(2, 3, "")
    (20, 0)
    >>> combinations_count(60, 4, "choose a smaller k")
    Traceback (most recent call last):
    ...
    mobility.errors.RequestError: 487635 combinations to try (more than 20000); choose a smaller k
    """
    if k < 0:
        raise RequestError("k must be non-negative")
    count = comb(candidates, k) if k <= candidates else 0
    return limit_combinations(count, advice)


def inputs_per_combination(k: object, default: int) -> int:
    """``k``, the inputs per combination of an enumeration, checked: ``default`` for None, else a non-negative integer.

    A bool, a float (``3.9``) or a string (``"3"``) is refused, not rounded or read.

    Raises
    ------
    RequestError
        When ``k`` is not a non-negative integer.

    Examples
    --------
    >>> inputs_per_combination(None, 3), inputs_per_combination(np.int64(2), 3)
    (3, 2)
    >>> inputs_per_combination(3.9, 3)
    Traceback (most recent call last):
    mobility.errors.RequestError: k must be an integer (inputs per combination), got 3.9
    """
    if k is None:
        return default
    try:
        number = require_integer(k, "")
    except RequestError:
        raise RequestError(f"k must be an integer (inputs per combination), got {shown_argument(k)}") from None
    if number < 0:
        raise RequestError(f"k must be non-negative (inputs per combination), got {number}")
    return number


def limit_combinations(count: int, advice: str) -> int:
    """``count``, unless it exceeds :data:`MAX_COMBINATIONS` (then a :class:`~mobility.errors.RequestError`)."""
    if count > MAX_COMBINATIONS:
        raise RequestError(f"{count} combinations to try (more than {MAX_COMBINATIONS}); {advice}")
    return count
