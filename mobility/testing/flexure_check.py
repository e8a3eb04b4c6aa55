"""Regression checks of flexure documents: freedom space and actuation verdict against their ``expected`` blocks.

``dof`` and ``pattern`` are compared with :func:`mobility.flexure.flexure_spaces`,
``translations`` as subspaces, ``actuation`` with the verdict of
:func:`mobility.flexure.check_force_lines` for the actuated actuators.
:func:`flexure_document` is the :data:`~mobility.testing.check.OtherDocument`
``mobility check`` uses, so that a folder may mix mechanisms and flexures.

Examples
--------
>>> import dataclasses
>>> from mobility.flexure import load_flexure
>>> flexure = load_flexure("examples/flexure/three_rod.yaml")
>>> c = check_flexure(flexure)
>>> c.status, c.found["pattern"], [x.key for x in c.comparisons]
('pass', '3R', ['dof', 'pattern', 'translations', 'actuation'])
>>> wrong = dataclasses.replace(flexure, expected=dataclasses.replace(flexure.expected, dof=2))
>>> check_flexure(wrong).message
'dof 3 (expected 2)'
"""

from __future__ import annotations

from typing import Any

from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, clean_numbers
from ..flexure import FlexureMechanism, check_force_lines, flexure_spaces, is_flexure_document, read_flexure
from ..io.yaml_source import Positions
from .check import CheckResult, Comparison, compare_translations, compare_verdict

__all__ = ["check_flexure", "flexure_document"]


def check_flexure(flexure: FlexureMechanism, *, tol: Tolerance = DEFAULT_TOLERANCE, path: str = "") -> CheckResult:
    """Compute a flexure mechanism's spaces and compare them with its ``expected`` block.

    The result's ``found`` holds ``dof``, ``pattern``, ``constraints``, ``translations`` (and ``actuation`` when expected).

    Raises
    ------
    MobilityError
        When the spaces cannot be computed.
    """
    spaces = flexure_spaces(flexure, tol=tol)
    found: dict[str, Any] = {"dof": spaces.dof, "pattern": spaces.pattern, "constraints": 6 - spaces.dof,
                             "translations": clean_numbers(spaces.freedom_translations)}
    expected = flexure.expected
    items = expected.items() if expected is not None else []
    if not items:
        return CheckResult(path, flexure.name, "missing", kind="flexure", found=found)
    comparisons = []
    for key, value in items:
        if key == "translations":
            comparisons.append(compare_translations(spaces.freedom_translations, value, tol))
        elif key == "actuation":
            check = check_force_lines(flexure, tol=tol)
            found["actuation"] = check.verdict
            comparisons.append(compare_verdict(key, check.verdict, value, [i.name for i in check.inputs]))
        else:  # dof, pattern: the reader allows no other key
            comparisons.append(Comparison(key, value, found[key], found[key] == value))
    status = "pass" if all(c.ok for c in comparisons) else "fail"
    return CheckResult(path, flexure.name, status, tuple(comparisons), kind="flexure", found=found)


def flexure_document(path: str, data: Any, positions: Positions, tol: Tolerance) -> CheckResult | None:
    """The check of a parsed flexure document (an :data:`~mobility.testing.check.OtherDocument`), ``None`` for another kind; a bad one raises its one-line error."""
    if not is_flexure_document(data):
        return None
    return check_flexure(read_flexure(data, positions, path), tol=tol, path=path)
