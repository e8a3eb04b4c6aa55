"""The suite's own rules, checked: a test that skips fails (nothing may skip in CI)."""

import shutil
import subprocess
import sys
from pathlib import Path


def test_a_skipping_test_fails_with_its_reason(tmp_path):
    shutil.copy(Path(__file__).with_name("conftest.py"), tmp_path / "conftest.py")
    (tmp_path / "test_skips.py").write_text(
        "import pytest\n"
        "def test_skips():\n    pytest.skip('no browser')\n"
        "@pytest.mark.skipif(True, reason='marked')\n"
        "def test_marked():\n    pass\n"
        "def test_passes():\n    pass\n"
    )
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "no:randomly", "--rootdir", str(tmp_path), str(tmp_path)],
                          capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert done.returncode == 1, done.stdout
    assert "this suite allows no skip; the test skipped: Skipped: no browser" in done.stdout
    assert "1 failed, 1 passed, 1 error" in done.stdout
