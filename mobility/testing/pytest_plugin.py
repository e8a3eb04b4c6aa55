"""Check mechanism files from a pytest suite.

One test per file by :func:`mobility.testing.check.check_file`, failing when
the file disagrees with its ``expected`` block, has none, or cannot be read:
``test_mechanisms = mechanism_tests("mechanisms/")`` in a test module, or the
plugin (entry point ``pytest11``) with ``--mobility-check mechanisms/``
(docs/library.md, "In your own pytest suite").

Examples
--------
>>> cases = mechanism_test_cases("no/such/folder")
>>> [c.id for c in cases]
['no/such/folder']
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Iterator

import pytest

from .check import CheckResult, OtherDocument, check_file, check_paths, mechanism_files
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance
from ..errors import MechanismCheckFailed

if TYPE_CHECKING:
    from _pytest._code.code import TerminalRepr  # what pytest's own repr_failure returns besides text

__all__ = ["MechanismCheckFailed", "mechanism_test_cases", "mechanism_tests", "assert_mechanism_passes", "failure_text"]


def _document_checks() -> tuple[OtherDocument, ...]:
    """The checks of other kinds of document: flexures (imported when a file is checked, not when pytest starts)."""
    from .flexure_check import flexure_document

    return (flexure_document,)


def failure_text(result: CheckResult) -> str:
    """The lines explaining why ``result`` did not pass (empty when it passed)."""
    if result.ok:
        return ""
    if result.status == "error":
        return result.message if result.message.startswith(result.path) else f"{result.path}: {result.message}"
    head = f"{result.path} ({result.name})"
    if result.status == "fail":
        return "\n".join([f"{head} disagrees with its expected block:"] + [f"  {c.describe()}" for c in result.mismatches])
    return f"{head}: no expected block"


def assert_mechanism_passes(path: str | Path, *, tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[CheckResult, ...]:
    """Check a mechanism file (or every file of a folder) and return the results; raise :class:`MechanismCheckFailed` unless all pass.

    A missing path or a folder without mechanism files fails too.
    """
    report = check_paths([path], tol=tol, others=_document_checks())
    failed = [r for r in report.results if not r.ok]
    if failed:
        raise MechanismCheckFailed("\n".join(failure_text(r) for r in failed))
    return report.results


def mechanism_test_cases(*paths: str | Path) -> list[Any]:
    """``pytest.param`` objects, one per mechanism file found under ``paths`` (a path that gives none: one case that fails, saying why)."""
    cases = []
    for shown, path, _problem in mechanism_files(paths):
        target = path if path is not None else shown
        cases.append(pytest.param(str(target), id=shown.replace("\\", "/")))
    return cases


def mechanism_tests(*paths: str | Path, tol: Tolerance = DEFAULT_TOLERANCE) -> Callable[[str], None]:
    """A parametrized test function checking every mechanism file under ``paths`` (assign it to a ``test_...`` name)."""

    @pytest.mark.parametrize("mechanism_path", mechanism_test_cases(*paths))
    def test_mechanism_file(mechanism_path: str) -> None:
        try:
            assert_mechanism_passes(mechanism_path, tol=tol)
        except MechanismCheckFailed as exc:
            message = str(exc)
        else:
            return
        pytest.fail(message, pytrace=False)

    return test_mechanism_file


# pytest plugin hooks (active only when loaded as a plugin and configured)


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("mobility", "mechanism files checked against their expected blocks")
    group.addoption("--mobility-check", action="append", default=[], metavar="PATH", help="collect the mechanism files under PATH as tests (repeatable)")
    parser.addini("mobility_check", "mechanism files or folders collected as tests", type="paths", default=[])


def _roots(config: pytest.Config) -> list[Path]:
    cached = getattr(config, "_mobility_check_roots", None)
    if cached is None:
        given = [Path(p) for p in config.getoption("mobility_check") or []] + [Path(p) for p in config.getini("mobility_check")]
        cached = [p.resolve() for p in given]
        config._mobility_check_roots = cached  # type: ignore[attr-defined]
    return cached


def pytest_configure(config: pytest.Config) -> None:
    """Add the configured mechanism folders to what pytest collects, unless already covered."""
    roots = _roots(config)
    if not roots:
        return
    args = [Path(str(a).split("::")[0]).resolve() for a in config.args]
    for root in roots:
        if not any(root == a or a in root.parents for a in args):
            config.args.append(str(root))


def pytest_collect_file(file_path: Path, parent: pytest.Collector) -> pytest.Collector | None:
    if file_path.suffix not in (".yaml", ".yml"):
        return None
    roots = _roots(parent.config)
    path = file_path.resolve()
    if any(path == r or r in path.parents for r in roots):
        return MechanismFile.from_parent(parent, path=file_path)
    return None


class MechanismFile(pytest.File):
    """A mechanism file collected by the plugin: one test item."""

    def collect(self) -> Iterator["MechanismItem"]:
        yield MechanismItem.from_parent(self, name="check")


class MechanismItem(pytest.Item):
    """The check of one mechanism file against its ``expected`` block."""

    def runtest(self) -> None:
        result = check_file(self.path, others=_document_checks())
        if not result.ok:
            raise MechanismCheckFailed(failure_text(result))

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException], style: Any = None) -> str | TerminalRepr:
        if isinstance(excinfo.value, MechanismCheckFailed):
            return str(excinfo.value)
        return super().repr_failure(excinfo, style=style)

    def reportinfo(self) -> tuple[Path, int | None, str]:
        return self.path, None, f"mobility check {self.path.name}"
