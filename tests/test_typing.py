"""The type hints are true: mypy (the version and stubs pinned in the test extra) finds nothing in the package.

The package ships them (``mobility/py.typed``, PEP 561), so a wrong annotation
misleads every user's type checker: a change that makes one wrong fails here
with mypy's report.
"""

import re
import tomllib
from pathlib import Path

from mypy import api

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "mobility"


def test_mypy_finds_no_error_in_the_package(tmp_path):
    # the project's [tool.mypy] settings; a fresh cache, so nothing left from another run counts
    stdout, stderr, status = api.run(["--config-file", str(ROOT / "pyproject.toml"), "--cache-dir", str(tmp_path / "cache"), str(PACKAGE)])
    report = stdout + stderr
    assert status == 0, f"mypy found errors (run `mypy` in the repository root):\n{report}"
    checked = re.search(r"Success: no issues found in (\d+) source files", stdout)
    assert checked is not None, report
    assert int(checked.group(1)) == len(list(PACKAGE.rglob("*.py")))  # every module was checked, not a part of them


def test_the_type_hints_ship_with_the_package():
    assert (PACKAGE / "py.typed").is_file()
    settings = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "py.typed" in settings["tool"]["setuptools"]["package-data"]["mobility"]
