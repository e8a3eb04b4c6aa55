"""The API reference (docs/api, built by .ci/docs with warnings as errors) covers the public API and hides nothing of ours.

The build itself is CI's (about half a minute of Sphinx); these checks are what it cannot see: a name
added to ``mobility.__all__`` but not to the public page, and an ignore pattern that would silence a
broken reference to the package's own names.
"""

import re
import runpy
from pathlib import Path

import mobility

ROOT = Path(__file__).resolve().parents[1]
API = ROOT / "docs" / "api"


def listed_names(page: Path) -> list[str]:
    """The entries of the autosummary tables of ``page``."""
    names: list[str] = []
    for block in re.findall(r"^\.\. autosummary::\n((?:\n|   .*\n)+)", page.read_text(encoding="utf-8"), re.M):
        names += [line.strip() for line in block.splitlines() if line.strip() and not line.strip().startswith(":")]
    return names


def test_the_public_page_lists_every_name_of_mobility_all_once():
    names = [n for n in listed_names(API / "public.rst") if not n.startswith("mobility.")]
    assert sorted(names) == sorted(mobility.__all__)
    assert len(names) == len(set(names))


def test_the_public_page_lists_the_modules_a_user_imports():
    modules = {n for n in listed_names(API / "public.rst") if n.startswith("mobility.")}
    assert {"mobility.errors", "mobility.testing.pytest_plugin", "mobility.core.tolerance", "mobility.sweeps",
            "mobility.actuation", "mobility.finite", "mobility.flexure", "mobility.synthesis", "mobility.jacobians",
            "mobility.view", "mobility.report"} <= modules


def test_no_ignored_reference_is_one_of_the_package():
    conf = runpy.run_path(str(API / "conf.py"))
    assert conf["nitpicky"] is True
    ours = ["mobility", "mobility.analyze", "mobility.core.result.Result", "mobility.errors.RequestError", "Result", "Tolerance.closure"]
    for _, target in conf["nitpick_ignore_regex"]:
        assert not [name for name in ours if re.fullmatch(target, name)], target
    assert "numpy.ndarray" in [name for _, target in conf["nitpick_ignore_regex"] for name in ["numpy.ndarray"] if re.fullmatch(target, name)]


def test_ci_builds_with_warnings_as_errors_and_every_reference_checked():
    script = (ROOT / ".ci" / "docs").read_text(encoding="utf-8")
    build = next(line for line in script.splitlines() if "-m sphinx" in line)
    assert {"-W", "-n", "-E"} <= set(build.split()), build
    assert "docs/api" in build.split()
