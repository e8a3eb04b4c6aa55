import os
import sys
from pathlib import Path

import pytest
from hypothesis import settings

# The property tests draw the same examples on every run (a run that passes here passes in CI); set
# HYPOTHESIS_PROFILE=explore to let them search new examples.
settings.register_profile("repeatable", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repeatable"))

sys.path.insert(0, os.path.dirname(__file__))

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"


@pytest.fixture
def write_yaml(tmp_path):
    """Write YAML text to a file and return its path."""

    def write(text: str, name: str = "m.yaml") -> Path:
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path

    return write


@pytest.fixture
def symlink_loop():
    """Make ``folder/name`` -> ``folder/other-name`` -> ``folder/name``: looking it up never ends (ELOOP); return the path."""

    def make(folder: Path, name: str) -> Path:
        path, other = folder / name, folder / ("other-" + name)
        path.symlink_to(other.name)
        other.symlink_to(path.name)
        return path

    return make


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """A test that skips fails: in CI nothing may skip, so a missing tool or extra is a failure that says so."""
    outcome = yield
    report = outcome.get_result()
    if report.skipped and not hasattr(report, "wasxfail"):
        reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else str(report.longrepr)
        report.outcome = "failed"
        report.longrepr = f"this suite allows no skip; the test skipped: {reason}"
