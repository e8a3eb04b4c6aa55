"""The regression check a mechanism may carry: :class:`Expected`, and the rules of its keys.

A file's ``expected`` block says what an analysis must find
(:mod:`mobility.testing.check` compares); the file reader applies these rules
(:mod:`mobility.io.expected`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from ..errors import MechanismError, RequestError, shown_argument
from .tolerance import decide_rank
from .validation import Vector, _listed, require_integer, require_vector

__all__ = ["Expected", "EXPECTED_KEYS", "EXPECTED_PATTERN", "require_expected_integer", "require_expected_pattern",
           "require_expected_basis", "independent_of"]


EXPECTED_KEYS: dict[str, str] = {
    "dof": "end-effector DOF (integer >= 0)",
    "pattern": 'motion pattern such as "1T2R"',
    "translations": "basis of the translation subspace (list of 3-vectors)",
    "mobility": "DOF of the whole mechanism (integer >= 0)",
    "redundant_constraints": "number of redundant constraints (integer >= 0)",
    "idle_dof": "number of idle DOF (integer >= 0)",
    "gruebler_kutzbach": "Grübler-Kutzbach count (integer)",
    "full_cycle_dof": "end-effector DOF along the finite motion from this pose (integer >= 0; mobility analyze --finite)",
    "full_cycle_mobility": "DOF of the whole mechanism along the finite motion (integer >= 0; mobility analyze --finite)",
    "finite_verdict": "full-cycle, instantaneous-only, cannot-move or bifurcation (mobility analyze --finite)",
    "actuation": "verdict of the joints marked actuated: valid, redundant or actuation-singular (mobility actuation)",
}
"""Keys an ``expected`` block may hold, with what each means."""


EXPECTED_PATTERN = re.compile(r"0|([1-3]T)?([1-3]R)?")
"""An expected motion pattern: ``nT``, ``mR``, ``nTmR`` with ``n, m`` at most 3, or ``0`` (matched whole).

The contract's ``{nT}T{nR}R`` with zero parts dropped writes no motion as
``""``, read as ``"0"`` (:func:`require_expected_pattern`).
"""


def require_expected_integer(value: Any, key: str, *, signed: bool = False, shown: Callable[[Any], str] | None = None) -> int:
    """An expected count: an integer (Python or numpy, not a bool), non-negative unless ``signed``; else a :class:`MechanismError` naming ``key``.

    Examples
    --------
    >>> require_expected_integer(np.int64(3), "dof")
    3
    >>> require_expected_integer("1", "dof")
    Traceback (most recent call last):
    mobility.errors.MechanismError: dof: expected a non-negative integer, got '1'
    """
    try:
        return require_integer(value, "", low=None if signed else 0)
    except RequestError:
        raise MechanismError(key, f"expected {'an integer' if signed else 'a non-negative integer'}, got {(shown or shown_argument)(value)}") from None


def require_expected_pattern(value: Any, key: str, *, shown: Callable[[Any], str] | None = None) -> str:
    """An expected motion pattern (:data:`EXPECTED_PATTERN`; the integer ``0`` and the contract's ``""`` are ``"0"``), else a :class:`MechanismError` naming ``key``.

    Examples
    --------
    >>> require_expected_pattern("1T2R", "pattern"), require_expected_pattern(0, "pattern"), require_expected_pattern("", "pattern")
    ('1T2R', '0', '0')
    >>> require_expected_pattern("4R", "pattern")
    Traceback (most recent call last):
    mobility.errors.MechanismError: pattern: expected a pattern such as "3T", "1T2R", "3R" or "0" (no motion; also written ""), at most 3T and 3R, got '4R'
    """
    if (type(value) is int and value == 0) or (isinstance(value, str) and value == ""):
        return "0"
    if not isinstance(value, str) or not EXPECTED_PATTERN.fullmatch(value):
        raise MechanismError(key, f'expected a pattern such as "3T", "1T2R", "3R" or "0" (no motion; also written ""), at most 3T and 3R, got {(shown or shown_argument)(value)}')
    return value


def require_expected_basis(vectors: Sequence[Vector], key: str) -> tuple[Vector, ...]:
    """``vectors`` as a tuple when they are a basis of directions (an expected ``translations``), else a :class:`MechanismError` naming ``key[i]``, the first bad one.

    Each must be non-zero and independent of those before it by the one rank
    policy (round-off differences are dependent); an empty list is a basis.

    Examples
    --------
    >>> require_expected_basis([(0.0, 0.0, 1.0), (1.0, 0.0, 0.0)], "translations")
    ((0.0, 0.0, 1.0), (1.0, 0.0, 0.0))
    >>> require_expected_basis([(0.0, 0.0, 1.0), (0.0, 0.0, 2.0)], "translations")
    Traceback (most recent call last):
    mobility.errors.MechanismError: translations[1]: linearly dependent on the directions before it; expected a basis (independent directions)
    >>> require_expected_basis([(0.0, 0.0, 0.0)], "translations")
    Traceback (most recent call last):
    mobility.errors.MechanismError: translations[0]: expected a non-zero direction, got [0, 0, 0]
    """
    units: list[Vector] = []
    for i, v in enumerate(vectors):
        unit = require_vector(v, f"{key}[{i}]", direction=True)
        if not independent_of(units, unit):
            raise MechanismError(f"{key}[{i}]", "linearly dependent on the directions before it; expected a basis (independent directions)")
        units.append(unit)
    return tuple(vectors)


def independent_of(directions: Sequence[Vector], direction: Vector) -> bool:
    """Whether the unit ``direction`` is independent of the independent unit ``directions``, by the one rank policy.

    Examples
    --------
    >>> independent_of([], (0.0, 0.0, 1.0)), independent_of([(0.0, 0.0, 1.0)], (0.0, 0.0, -1.0))
    (True, False)
    """
    if not directions:  # one non-zero direction is a basis
        return True
    return decide_rank(np.linalg.svd(np.array([*directions, direction]), compute_uv=False)).rank > len(directions)


_EXPECTED_COUNTS = ("dof", "mobility", "redundant_constraints", "idle_dof")


@dataclass(frozen=True)
class Expected:
    """What a regression check compares an analysis against (all optional).

    Each field is checked as the same key of a file's ``expected`` block
    (:data:`EXPECTED_KEYS`), a bad one raising :class:`~mobility.errors.MechanismError`
    under its key; ``extra`` holds further keys (compared by
    :data:`mobility.testing.check.COMPARATORS`), copied.  Hashable and picklable.

    Examples
    --------
    >>> e = Expected(dof=1, pattern="1R", extra={"actuation": "valid"})
    >>> e.items()
    [('dof', 1), ('pattern', '1R'), ('actuation', 'valid')]
    >>> hash(e) == hash(Expected(dof=1, pattern="1R", extra={"actuation": "valid"}))
    True
    >>> Expected(dof="1")
    Traceback (most recent call last):
    mobility.errors.MechanismError: dof: expected a non-negative integer, got '1'
    """

    dof: int | None = None
    pattern: str | None = None
    translations: tuple[Vector, ...] | None = None
    mobility: int | None = None
    redundant_constraints: int | None = None
    idle_dof: int | None = None
    gruebler_kutzbach: int | None = None
    extra: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for key in _EXPECTED_COUNTS + ("gruebler_kutzbach",):
            value = getattr(self, key)
            if value is not None:
                object.__setattr__(self, key, require_expected_integer(value, key, signed=key == "gruebler_kutzbach"))
        if self.pattern is not None:
            object.__setattr__(self, "pattern", require_expected_pattern(self.pattern, "pattern"))
        if self.translations is not None:
            rows = _listed(self.translations)
            if not isinstance(rows, tuple):
                raise MechanismError("translations", f"expected a list of 3-vectors, got {shown_argument(self.translations)}")
            translations = tuple(require_vector(_listed(v), f"translations[{i}]") for i, v in enumerate(rows))
            object.__setattr__(self, "translations", require_expected_basis(translations, "translations"))
        if not isinstance(self.extra, Mapping):
            raise MechanismError("extra", f"expected a mapping of further expected keys, got {type(self.extra).__name__}")
        extra = dict(self.extra)  # a copy: the caller's mapping may change afterwards
        for key in extra:
            if not isinstance(key, str) or not key:
                raise MechanismError("extra", f"expected keys that are names (non-empty strings), got {shown_argument(key)}")
            if key in self.__dataclass_fields__:
                raise MechanismError(f"extra.{key}", f"{key!r} is a field of Expected: give it as Expected({key}=...)")
        object.__setattr__(self, "extra", extra)

    def __hash__(self) -> int:
        # extra's values may be unhashable (lists); equal Expecteds have equal keys, which is all a hash needs
        return hash((self.dof, self.pattern, self.translations, self.mobility, self.redundant_constraints,
                     self.idle_dof, self.gruebler_kutzbach, frozenset(self.extra)))

    def items(self) -> list[tuple[str, Any]]:
        """The expectations that are set, as ``(key, value)`` pairs."""
        out = [(k, getattr(self, k)) for k in EXPECTED_KEYS if hasattr(self, k) and getattr(self, k) is not None]
        out.extend((k, v) for k, v in self.extra.items() if v is not None)
        return out
