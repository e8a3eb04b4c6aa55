"""Regression checks: analyse mechanisms and compare with their ``expected`` blocks.

:func:`check_file` compares every key of a file's ``expected`` block with the
analysis by the comparator of :data:`COMPARATORS` (docs/library.md; a key no
comparator knows is a mismatch, never a pass); :func:`check_paths` gathers the
files and folders of ``mobility check`` in a :class:`CheckReport`.

Examples
--------
>>> import mobility
>>> m = mobility.loads('''
... name: slide
... ground: g
... end_effector: s
... joints: [{name: p, type: P, links: [g, s], axis: [1, 0, 0]}]
... expected: {dof: 1, pattern: 1T, translations: [[2, 0, 0]], mobility: 1}
... ''')
>>> c = check_mechanism(m)
>>> c.status, [x.key for x in c.comparisons]
('pass', ['dof', 'pattern', 'translations', 'mobility'])
>>> check_mechanism(m.replace(expected=mobility.Expected(dof=2))).mismatches[0].describe()
'dof 1 (expected 2)'
"""

from __future__ import annotations

import dataclasses
import errno
import os
import stat
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any, Callable, Iterable, Sequence

import numpy as np

from ..core.analysis import analyze
from ..errors import MechanismError, MobilityError, RequestError, counted
from ..io.files import file_name, os_reason, printable_name
from ..io.limits import current_limits, require_size
from ..io.loader import load
from ..io.mechanism_reader import read_mechanism
from ..io.yaml_source import Positions, parse_yaml, read_text
from ..core.expected import require_expected_basis
from ..core.model import Mechanism, require_mechanism
from ..core.result import Result
from ..core.screws import same_subspace
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, binary_scale, clean_numbers, require_tolerance

__all__ = ["Comparison", "CheckResult", "CheckReport", "COMPARATORS", "STATUSES", "OtherDocument", "check_mechanism", "check_file", "check_paths",
           "mechanism_files", "compare_translations", "compare_verdict"]

STATUSES = ("pass", "fail", "missing", "error")
"""The statuses of a checked file, in the order the summary lists them."""

MECHANISM_SUFFIXES = (".yaml", ".yml")


@dataclass(frozen=True)
class Comparison:
    """One key of an ``expected`` block compared with what the analysis found.

    ``expected`` is the file's value (translations as 3-lists), ``actual`` what
    was found in the same form (``None``: nothing), ``note`` why a comparison
    failed when the values alone do not say it.
    """

    key: str
    expected: Any
    actual: Any
    ok: bool
    note: str = ""

    def describe(self) -> str:
        """``key actual (expected value)``, e.g. ``'dof 4 (expected 3)'``."""
        if self.note:
            return f"{self.key}: {self.note}"
        return f"{self.key} {_short(self.actual)} (expected {_short(self.expected)})"

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {"key": self.key, "expected": clean_numbers(self.expected), "actual": clean_numbers(self.actual), "ok": self.ok, "note": self.note}


@dataclass(frozen=True, eq=False)
class CheckResult:
    """The check of one mechanism (usually one file).

    ``path``: the file as given (empty for a mechanism built in code); ``status``:
    one of :data:`STATUSES`; ``comparisons``: one per ``expected`` key, in order;
    ``internal``: the error is a defect of :mod:`mobility`, not bad input (exit
    status 3, not 2); ``kind``: ``"mechanism"`` or another document's
    (``"flexure"``, whose ``found`` replaces ``result``).
    """

    path: str
    name: str
    status: str
    comparisons: tuple[Comparison, ...] = ()
    result: Result | None = None
    error: str = ""
    internal: bool = False
    kind: str = "mechanism"
    found: dict[str, Any] | None = None

    def found_values(self) -> dict[str, Any] | None:
        """``found``, or for a mechanism the numbers of its ``result`` (``None`` on error)."""
        r = self.result
        if self.found is not None or r is None:
            return self.found
        return {key: getattr(r, key) for key in ("dof", "pattern", "mobility", "gruebler_kutzbach", "redundant_constraints", "idle_dof")} | {
            "translations": clean_numbers(r.translations)}

    @property
    def ok(self) -> bool:
        """True when the file passed."""
        return self.status == "pass"

    @property
    def mismatches(self) -> tuple[Comparison, ...]:
        """The comparisons that failed."""
        return tuple(c for c in self.comparisons if not c.ok)

    @property
    def message(self) -> str:
        """One line saying why the file did not pass (empty when it passed)."""
        if self.status == "fail":
            return "; ".join(c.describe() for c in self.mismatches)
        if self.status == "missing":
            return "no expected block"
        if self.status == "error":
            return self.error
        return ""

    def to_dict(self) -> dict[str, Any]:
        """JSON form (one entry of ``mobility check --json``)."""
        return {"path": self.path, "name": self.name, "kind": self.kind, "status": self.status, "message": self.message,
                "found": self.found_values(), "comparisons": [c.to_dict() for c in self.comparisons]}


@dataclass(frozen=True, eq=False)
class CheckReport:
    """The checks of several files, with the exit status of ``mobility check``.

    ``results`` are in the order the files were given (folders expanded, sorted).
    """

    results: tuple[CheckResult, ...]

    def count(self, status: str) -> int:
        """Number of files with ``status``."""
        return sum(r.status == status for r in self.results)

    @property
    def ok(self) -> bool:
        """True when every file passed (and there was at least one)."""
        return bool(self.results) and all(r.ok for r in self.results)

    @property
    def exit_status(self) -> int:
        """3 if a check met an internal error, else 2 if any input was bad, else 1
        if any file failed or had no ``expected`` block, else 0."""
        if any(r.status == "error" and r.internal for r in self.results):
            return 3
        if any(r.status == "error" for r in self.results):
            return 2
        return 0 if self.ok else 1

    def summary(self) -> str:
        """``'40 passed, 1 failed, 0 without expected block, 0 errors'``."""
        return f"{self.count('pass')} passed, {self.count('fail')} failed, {self.count('missing')} without expected block, {counted(self.count('error'), 'error')}"

    def to_dict(self) -> dict[str, Any]:
        """JSON form of ``mobility check --json``."""
        return {"results": [r.to_dict() for r in self.results], "summary": {s: self.count(s) for s in STATUSES} | {"total": len(self.results)},
                "exit_status": self.exit_status}


class _Subject:
    """A mechanism with its analyses computed on demand (the finite one is costly)."""

    def __init__(self, mechanism: Mechanism, tol: Tolerance) -> None:
        self.mechanism = mechanism
        self.tol = tol

    @cached_property
    def result(self) -> Result:
        return analyze(self.mechanism, tol=self.tol)

    @cached_property
    def finite(self) -> dict[str, Any]:
        from ..finite.full_cycle import finite_mobility  # imported on demand: it pulls in scipy.optimize

        require_size(self.mechanism, "max_finite_joints", "the full-cycle expectations", self.mechanism.source or "<mechanism>")
        return finite_mobility(self.mechanism, tol=self.tol).expected_values()


Comparator = Callable[[_Subject, Any], Comparison]
"""``comparator(subject, expected_value) -> Comparison``."""


def _equal(key: str, finite: bool = False) -> Comparator:
    """Equality with the screw analysis's ``key``, or (``finite``) the full-cycle analysis's."""

    def compare(subject: _Subject, expected: Any) -> Comparison:
        actual = subject.finite[key] if finite else getattr(subject.result, key)
        return Comparison(key, expected, actual, actual == expected)

    return compare


def compare_translations(found: np.ndarray, expected: Any, tol: Tolerance) -> Comparison:
    """An expected translation basis (rows) compared with the ``found`` one as subspaces.

    Raises
    ------
    RequestError
        When ``expected`` is not a basis (a zero row, or a dependent one): an input error, not a failed check.

    Examples
    --------
    >>> compare_translations(np.array([[0.0, 0.0, 1.0]]), [[0, 0, 5]], DEFAULT_TOLERANCE).ok
    True
    >>> compare_translations(np.zeros((0, 3)), [[1, 0, 0]], DEFAULT_TOLERANCE).describe()
    'translations: found the span of [], expected the span of [[1, 0, 0]]'
    >>> compare_translations(np.zeros((0, 3)), [[0, 0, 0]], DEFAULT_TOLERANCE)
    Traceback (most recent call last):
    mobility.errors.RequestError: compare_translations: expected[0]: expected a non-zero direction, got [0, 0, 0]
    """
    rows = np.asarray(expected, dtype=float).reshape(-1, 3)
    try:
        require_expected_basis([(float(x), float(y), float(z)) for x, y, z in rows.tolist()], "expected")
    except MechanismError as exc:
        raise RequestError(exc.message, caller="compare_translations", argument=exc.key) from None
    actual = clean_numbers(found)
    scaled = rows * np.array([binary_scale(row) for row in rows]).reshape(-1, 1)  # before squaring: any finite vector has a direction
    unit = scaled / np.linalg.norm(scaled, axis=1)[:, None]
    if len(unit) == 0 or len(found) == 0:
        ok = len(found) == 0 and len(unit) == 0
    else:
        ok = same_subspace(unit.T, found.T, tol)
    note = "" if ok else f"found the span of {_short(actual)}, expected the span of {_short(rows.tolist())}"
    return Comparison("translations", rows.tolist(), actual, ok, note)


def compare_verdict(key: str, found: Any, expected: Any, inputs: Sequence[str]) -> Comparison:
    """An expected actuation verdict compared with the one ``found`` for ``inputs`` (none marked: a mismatch that says so).

    Examples
    --------
    >>> compare_verdict("actuation", "valid", "valid", ["P1", "P2"]).ok
    True
    >>> compare_verdict("actuation", "actuation-singular", "valid", []).describe()
    'actuation: no input is marked actuated (actuated: true), so there is no verdict to compare'
    """
    if not inputs:
        return Comparison(key, expected, None, False, "no input is marked actuated (actuated: true), so there is no verdict to compare")
    return Comparison(key, expected, found, found == expected)


def _actuation(subject: _Subject, expected: Any) -> Comparison:
    from ..actuation import check_actuation  # imported on demand: most files expect no actuation verdict

    check = check_actuation(subject.mechanism, tol=subject.tol)
    return compare_verdict("actuation", check.verdict, expected, [i.name for i in check.inputs])


COMPARATORS: dict[str, Comparator] = {
    **{key: _equal(key) for key in ("dof", "pattern")}, "translations": lambda subject, expected: compare_translations(subject.result.translations, expected, subject.tol),
    **{key: _equal(key) for key in ("mobility", "redundant_constraints", "idle_dof", "gruebler_kutzbach")},
    **{key: _equal(key, finite=True) for key in ("full_cycle_dof", "full_cycle_mobility", "finite_verdict")}, "actuation": _actuation}
"""How each ``expected`` key is compared (other modules may register more)."""


def check_mechanism(mechanism: Mechanism, *, tol: Tolerance = DEFAULT_TOLERANCE, path: str = "") -> CheckResult:
    """Analyse ``mechanism`` and compare it with its ``expected`` block.

    ``tol`` is the rank policy of the analysis and of the subspace comparisons;
    ``path`` where the mechanism came from.  No ``expected`` block: status
    ``"missing"`` (still analysed).

    Raises
    ------
    RequestError
        When ``mechanism`` is not a Mechanism or ``tol`` not a Tolerance.
    MobilityError
        When the analysis fails (:func:`check_file` makes it an ``"error"`` result).

    Examples
    --------
    >>> import mobility
    >>> check_mechanism(mobility.load("mechanisms/four_bar.yaml")).status
    'pass'
    """
    mechanism = require_mechanism(mechanism, "check_mechanism")
    tol = require_tolerance(tol, "check_mechanism")
    subject = _Subject(mechanism, tol)
    expected = mechanism.expected
    items = expected.items() if expected is not None else []
    if not items:
        return CheckResult(path, mechanism.name, "missing", (), subject.result)
    comparisons = [COMPARATORS[key](subject, value) if key in COMPARATORS else Comparison(key, value, None, False, "no comparator knows this key")
                   for key, value in items]
    status = "pass" if all(c.ok for c in comparisons) else "fail"
    return CheckResult(path, mechanism.name, status, tuple(comparisons), subject.result)


OtherDocument = Callable[[str, Any, Positions, Tolerance], "CheckResult | None"]
"""``check(path, data, positions, tol)``: the check of a parsed YAML document (:func:`~mobility.io.yaml_source.parse_yaml`)
that is not a mechanism file, or ``None`` when ``data`` is not of its kind; a bad document raises its
:class:`~mobility.errors.MobilityError` (:func:`mobility.testing.flexure_check.flexure_document`, for flexures)."""


def check_file(path: str | Path, *, tol: Tolerance = DEFAULT_TOLERANCE, others: Sequence[OtherDocument] = ()) -> CheckResult:
    """Load, analyse and check one mechanism file; never raises on a bad file.

    A YAML file is parsed once and offered to each of ``others`` in turn before it is
    read as a mechanism.  A file that cannot be read or analysed gives status ``"error"``.

    Raises
    ------
    RequestError
        When ``path`` is not a file name (then no result can name it).

    Examples
    --------
    >>> check_file("no/such/file.yaml").message
    'no/such/file.yaml: no such file'
    """
    file_name(path, "check_file")
    name = printable_name(path)
    try:
        if Path(path).suffix.lower() not in MECHANISM_SUFFIXES:
            return check_mechanism(load(path), tol=tol, path=name)
        limits = current_limits()
        data, positions = parse_yaml(read_text(path, limits), str(path), limits)
        for other in others:
            found = other(str(path), data, positions, tol)
            if found is not None:
                return dataclasses.replace(found, path=name, name=printable_name(found.name))
        return check_mechanism(read_mechanism(data, positions, str(path), limits=limits), tol=tol, path=name)
    except MobilityError as exc:
        return CheckResult(name, "", "error", error=printable_name(str(exc)))
    except Exception as exc:  # a defect of the package: report it, keep checking the other files
        return CheckResult(name, "", "error", error=printable_name(f"internal error ({type(exc).__name__}: {exc})"), internal=True)


def _require_mode(raw: str | Path) -> int:
    """The file type bits of ``raw``, else a :class:`RequestError` saying why it cannot be looked up."""
    try:
        return os.stat(raw).st_mode
    except FileNotFoundError:
        raise RequestError("no such file or folder") from None
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise RequestError(f"is {os_reason(exc)}, expected a mechanism file or folder") from None
        raise RequestError(f"cannot look it up: {os_reason(exc)}") from None
    except ValueError as exc:  # a NUL in a name given from Python
        raise RequestError(f"cannot look it up: {exc}") from None


def mechanism_files(paths: Iterable[str | Path]) -> list[tuple[str, Path | None, str]]:
    """Expand ``paths`` into ``(shown, path, problem)``: the name to report, as text, and the file (``None`` when ``problem`` says why nothing can be checked there).

    Folders give every ``*.yaml``/``*.yml`` file inside, recursively, sorted.
    """
    out: list[tuple[str, Path | None, str]] = []
    for raw in paths:
        p = Path(raw)
        shown = printable_name(raw)
        try:
            mode = _require_mode(raw)
        except RequestError as exc:
            out.append((shown, None, f"{shown}: {exc}"))
            continue
        if stat.S_ISDIR(mode):
            found = sorted(f for f in p.rglob("*") if f.suffix.lower() in MECHANISM_SUFFIXES and not f.is_dir())  # a pipe among them is reported on its row, not skipped
            if not found:
                out.append((shown, None, f"{shown}: no *.yaml mechanism file in this folder"))
            out.extend((printable_name(f), f, "") for f in found)
        else:
            out.append((shown, p, ""))
    return out


def check_paths(paths: Sequence[str | Path], *, tol: Tolerance = DEFAULT_TOLERANCE, others: Sequence[OtherDocument] = ()) -> CheckReport:
    """Check every mechanism file given or found in the folders given (``others``: as for :func:`check_file`).

    Raises
    ------
    RequestError
        When ``paths`` is not a list (or tuple) of file names (a bare name is not read as its characters).

    Examples
    --------
    >>> report = check_paths(["no/such/folder"])
    >>> report.exit_status, report.results[0].message
    (2, 'no/such/folder: no such file or folder')
    >>> check_paths("mechanisms")
    Traceback (most recent call last):
    ...
    mobility.errors.RequestError: check_paths: expected a list of file or folder names, got str (one name is written [name])
    """
    if not isinstance(paths, (list, tuple)):
        one = " (one name is written [name])" if isinstance(paths, (str, os.PathLike)) else ""
        raise RequestError(caller="check_paths", expected="a list of file or folder names", got=f"{type(paths).__name__}{one}")
    for k, path in enumerate(paths):
        file_name(path, f"check_paths: paths[{k}]")
    results = []
    for shown, path, problem in mechanism_files(paths):
        if path is None:
            results.append(CheckResult(shown, "", "error", error=problem))
        else:
            results.append(check_file(path, tol=tol, others=others))
    return CheckReport(tuple(results))


def _short(value: Any) -> str:
    """A compact text form: vectors with 6 significant digits, round-off shown as 0 (:func:`~mobility.core.tolerance.clean_numbers`)."""
    value = clean_numbers(value)
    if isinstance(value, list):
        return "[" + ", ".join(_short(v) for v in value) + "]"
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)
