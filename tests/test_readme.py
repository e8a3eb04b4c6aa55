"""The README stays true to the code: its example output, its Quickstart, CI's command."""

import re
from pathlib import Path

from mobility.cli import main

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()


def test_example_report_is_what_the_command_prints(capsys):
    block = README.split("prints:\n\n```\n", 1)[1].split("\n```", 1)[0]
    assert main(["analyze", str(ROOT / "mechanisms" / "3prs_tilted.yaml")]) == 0
    printed = capsys.readouterr().out.rstrip("\n")
    # the margin line holds round-off-level numbers that differ between BLAS builds
    strip = lambda text: [line for line in text.splitlines() if "margin:" not in line]  # noqa: E731
    assert strip(printed) == strip(block)


def test_quickstart_has_two_command_lines_and_ci_runs_the_test_one():
    quickstart = README.split("## Quickstart", 1)[1].split("\n## ", 1)[0]
    commands = re.findall(r"```\n(.+?)\n```", quickstart)
    assert len(commands) == 2
    install_and_analyze, install_and_test = commands
    assert "pip install" in install_and_analyze and "analyze mechanisms/" in install_and_analyze
    assert (ROOT / install_and_analyze.split("analyze ", 1)[1].strip()).exists()
    assert "pip install" in install_and_test and "pytest" in install_and_test
    assert install_and_test in (ROOT / ".ci" / "run").read_text()
