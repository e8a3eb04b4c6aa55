"""The README and docs stay true to the code: the example output, the Quickstart, CI's command, the format page."""

import math
import re
from pathlib import Path

import pytest

import mobility

from mobility.cli import main

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()


def test_example_report_is_what_the_command_prints(capsys):
    block = README.split("prints:\n\n```\n", 1)[1].split("\n```", 1)[0]
    assert main(["analyze", str(ROOT / "mechanisms" / "3prs_tilted.yaml")]) == 0
    printed = capsys.readouterr().out.rstrip("\n")
    # the departure from the special geometry is a round-off-level number that differs between BLAS builds: its words compared, not its number
    strip = lambda text: [re.sub(r"(special geometry: )\S+", r"\1<round-off>", line) for line in text.splitlines()]  # noqa: E731
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


def test_the_file_format_page_fragments_load_when_completed():
    text = (ROOT / "docs" / "file-format.md").read_text(encoding="utf-8")
    parameters, limbs = re.findall(r"```yaml\n(.*?)```", text, re.S)[:2]
    m = mobility.loads("name: doc\nground: g\nend_effector: l1\n" + parameters)
    assert m.world_joints[0].axis == pytest.approx((0.0, -math.sin(math.radians(60)), math.cos(math.radians(60))))
    m = mobility.loads("name: doc\nground: base\nend_effector: leg1\n" + limbs)  # the block defines its parameter h itself
    assert [j.name for j in m.world_joints] == ["P1", "R1", "P2", "R2", "P3", "R3"]
    # the third limb's frame is turned by 240 degrees about z: its R axis [0, 1, 0] becomes [-sin 240, cos 240, 0]
    assert m.world_joints[5].axis == pytest.approx((-math.sin(math.radians(240)), math.cos(math.radians(240)), 0.0))


def _console_blocks():
    """Every ```console block of the README and docs/ that runs one ``mobility`` command: (where, arguments, shown lines)."""
    for page in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        text = page.read_text(encoding="utf-8")
        for found in re.finditer(r"```console\n\$ mobility (.*?)\n(.*?)```", text, re.S):
            where = f"{page.name}:{text[: found.start()].count(chr(10)) + 2}"
            yield pytest.param(found.group(1).split(), found.group(2).rstrip("\n").split("\n"), id=where)


def _shows(shown: list[str], printed: list[str]) -> bool:
    """Whether ``printed`` is ``shown`` where each ``...`` line stands for any lines (none included)."""
    runs, run = [], []
    for line in shown:
        if line.strip() == "...":
            runs.append(run)
            run = []
        else:
            run.append(line)
    runs.append(run)
    if len(runs) == 1:
        return printed == shown
    at = 0
    for k, run in enumerate(runs):
        if k == 0:
            if printed[: len(run)] != run:
                return False
            at = len(run)
        elif k == len(runs) - 1:
            return not run or (len(printed) - len(run) >= at and printed[len(printed) - len(run) :] == run)
        else:
            for start in range(at, len(printed) - len(run) + 1):
                if printed[start : start + len(run)] == run:
                    at = start + len(run)
                    break
            else:
                return False
    return True


@pytest.mark.parametrize("arguments, shown", list(_console_blocks()))
def test_each_console_example_in_the_docs_is_what_the_command_prints(arguments, shown, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    assert main(arguments) == 0
    printed = capsys.readouterr().out.rstrip("\n").split("\n")
    assert _shows(shown, printed), "\n".join(printed)


def test_an_elided_example_still_has_to_match_around_its_gaps():
    printed = ["a", "b", "c", "d"]
    assert _shows(["a", "...", "d"], printed) and _shows(["...", "c", "..."], printed) and _shows(["a", "b", "c", "d"], printed)
    assert not _shows(["a", "...", "c"], printed)  # the end must match when the block does not end in "..."
    assert not _shows(["b", "..."], printed) and not _shows(["a", "...", "d", "..."] + ["e"], printed)
    assert not _shows(["a", "c", "d"], printed)


def _documents_with_expected_blocks() -> list[tuple[str, str]]:
    """Every YAML block of README.md and docs/*.md that is a whole document (a name, a ground) with an expected block."""
    found = []
    for page in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        for k, block in enumerate(re.findall(r"```yaml\n(.*?)```", page.read_text(encoding="utf-8"), re.S)):
            if re.search(r"^name:", block, re.M) and re.search(r"^ground:", block, re.M) and re.search(r"^expected:", block, re.M):
                found.append((f"{page.name}#{k}", block))
    return found


@pytest.mark.parametrize("where, block", _documents_with_expected_blocks(), ids=[w for w, _ in _documents_with_expected_blocks()])
def test_a_document_shown_with_its_expected_block_passes_check(where, block, tmp_path):
    from mobility.testing.check import check_file
    from mobility.testing.flexure_check import flexure_document

    path = tmp_path / "shown.yaml"
    path.write_text(block.replace("description: ...", "description: shown in the docs"), encoding="utf-8")
    result = check_file(path, others=(flexure_document,))  # as mobility check reads it
    assert result.status == "pass", (where, result.message)
