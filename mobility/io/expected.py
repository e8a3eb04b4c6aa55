"""The ``expected`` block of a document: what a regression check compares an analysis with.

Each kind of document allows its own keys (:data:`~mobility.core.expected.EXPECTED_KEYS`,
:data:`FLEXURE_EXPECTED_KEYS`), every value checked where it is read, so that a
misspelt key or a pattern ``"4R"`` is an error at its line, not a check that can never pass.

Examples
--------
>>> from mobility.io.reader import DocumentReader
>>> from mobility.io.yaml_source import parse_yaml
>>> data, positions = parse_yaml("expected: {dof: 3, pattern: 3R, actuation: valid}\\n", "e.yaml")
>>> e = read_expected(DocumentReader("e.yaml", positions), data["expected"], FLEXURE_EXPECTED_KEYS)
>>> e.items()
[('dof', 3), ('pattern', '3R'), ('actuation', 'valid')]
>>> data, positions = parse_yaml("expected: {dof: 3, mobility: 3}\\n", "e.yaml")
>>> read_expected(DocumentReader("e.yaml", positions), data["expected"], FLEXURE_EXPECTED_KEYS)
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: e.yaml:1: expected.mobility: unknown key in the expected block; expected one of: dof, pattern, translations, actuation
"""

from __future__ import annotations

from functools import partial
from typing import Any, Callable

from ..core.expected import Expected, require_expected_basis, require_expected_integer, require_expected_pattern
from ..errors import MechanismError
from .reader import DocumentReader, describe_value, parse_key, shown_value
from .yaml_source import KeyPath, format_key

__all__ = ["ACTUATION_VERDICTS", "FINITE_VERDICTS", "EXPECTED_VALIDATORS", "FLEXURE_EXPECTED_KEYS", "read_expected"]

ACTUATION_VERDICTS = ("valid", "redundant", "actuation-singular")
"""The verdicts of a choice of actuated inputs (:data:`mobility.actuation.VERDICTS`, which the tests compare)."""

FINITE_VERDICTS = ("full-cycle", "instantaneous-only", "cannot-move", "bifurcation")
"""The verdicts of the finite-motion analysis (``mobility analyze --finite``)."""

FLEXURE_EXPECTED_KEYS = ("dof", "pattern", "translations", "actuation")
"""The keys the ``expected`` block of a flexure document may hold (freedom space and actuation)."""


_integer = partial(require_expected_integer, shown=shown_value)  # checked as Expected checks it, the value shown as a file's


def _choice(choices: tuple[str, ...]) -> Callable[[Any, str], str]:
    def validate(value: Any, key: str) -> str:
        if not isinstance(value, str) or value not in choices:
            raise MechanismError(key, f"expected one of {', '.join(choices)}, got {shown_value(value)}")
        return value

    return validate


EXPECTED_VALIDATORS: dict[str, Callable[[Any, str], Any]] = {
    "dof": _integer, "pattern": partial(require_expected_pattern, shown=shown_value), "mobility": _integer, "redundant_constraints": _integer,
    "idle_dof": _integer, "gruebler_kutzbach": partial(_integer, signed=True), "full_cycle_dof": _integer, "full_cycle_mobility": _integer,
    "finite_verdict": _choice(FINITE_VERDICTS), "actuation": _choice(ACTUATION_VERDICTS)}
"""Validators of the ``expected`` keys (``translations`` is read as a list of vectors)."""


def read_expected(reader: DocumentReader, value: Any, keys: tuple[str, ...]) -> Expected:
    """The ``expected`` block ``value`` of a document, each key among ``keys`` and each value checked.

    Raises
    ------
    MechanismFileError
        On an unknown key, a value of the wrong kind, or ``translations`` that
        are not a basis (at that direction's line).
    """
    path: KeyPath = ("expected",)
    data = reader.record(value, path, "the expected block", keys, described="expected results")
    fields: dict[str, Any] = {}
    extra: dict[str, Any] = {}
    for key, raw in data.items():
        kpath = path + (key,)
        if key == "translations":
            if not isinstance(raw, list):
                raise reader.fail(kpath, f"expected a list of 3-vectors, got {describe_value(raw)}")
            try:
                fields[key] = require_expected_basis([reader.vector(v, kpath + (i,)) for i, v in enumerate(raw)], key)
            except MechanismError as exc:
                raise reader.fail(path + parse_key(exc.key), exc.message) from None
            continue
        validator = EXPECTED_VALIDATORS.get(key)
        try:
            parsed = validator(raw, format_key(kpath)) if validator else raw
        except MechanismError as exc:
            raise reader.fail(kpath, exc.message) from None
        if key in Expected.__dataclass_fields__:
            fields[key] = parsed
        else:
            extra[key] = parsed
    return Expected(**fields, extra=extra)
