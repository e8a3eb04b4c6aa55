"""Doctests of the package run in the repository's root, wherever pytest is started.

The examples name bundled files as a user in a checkout would
(``mobility.load("mechanisms/3prs.yaml")``); this makes ``cd tests && pytest``
or ``pytest /path/to/checkout`` run them as ``pytest`` in the root does.
"""

from pathlib import Path

import pytest
from _pytest.doctest import DoctestItem

ROOT = Path(__file__).resolve().parent


@pytest.fixture(autouse=True)
def _doctests_in_the_root(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> None:
    if isinstance(request.node, DoctestItem):
        monkeypatch.chdir(ROOT)
