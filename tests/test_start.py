"""A fast start (issue 12): what ``import mobility`` and ``mobility analyze`` import, and what they leave alone.

The time itself is measured by ``benchmarks/bench_start.py`` (never here);
these tests pin the imports that made the difference: scipy (whose import
cost more than a whole analysis), networkx (needed only for graphs that do
not reduce whole, loop closure and finite motion) and the other subcommands'
features.  Each check runs in a fresh interpreter.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def modules_after(code: str) -> set[str]:
    """The modules loaded by a fresh interpreter after running ``code`` (printed as JSON)."""
    script = code + "\nimport json, sys\nprint(json.dumps(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", script], cwd=ROOT, check=True, capture_output=True, text=True).stdout
    return set(json.loads(out.splitlines()[-1]))


def heavy(modules: set[str]) -> set[str]:
    return {m.split(".")[0] for m in modules} & {"scipy", "networkx", "matplotlib", "plotly"}


def test_import_and_analysis_of_a_reducible_mechanism_need_neither_scipy_nor_networkx():
    modules = modules_after("import mobility\nr = mobility.analyze(mobility.load('mechanisms/3prs.yaml'))\nr.to_dict()")
    assert heavy(modules) == set()
    assert "mobility.core.analysis" in modules and "mobility.finite" not in modules


def test_a_graph_that_does_not_reduce_whole_imports_networkx_for_its_blocks():
    code = (
        "from mobility import Joint, Mechanism, analyze\n"
        "R = lambda n, a, b: Joint(n, 'R', (a, b), axis=(0, 0, 1), point=(0, 0, 0))\n"
        "analyze(Mechanism('m', 'g', 'e', (R('A', 'g', 'e'), R('H', 'e', 'h'))))"
    )
    assert heavy(modules_after(code)) == {"networkx"}


def test_the_analyze_command_imports_its_own_module_only():
    modules = modules_after("from mobility.cli import main\nmain(['analyze', 'mechanisms/3prs.yaml'])")
    commands = {m for m in modules if m.startswith("mobility.cli.") and not m.startswith("mobility.cli._")}
    assert commands == {"mobility.cli.analyze"}  # the file options are shared from mobility.cli._options, not another command
    assert heavy(modules) == set()
    assert not any(m.startswith(("mobility.finite", "mobility.synthesis", "mobility.jacobians", "mobility.sweeps", "mobility.view")) for m in modules)


def test_help_and_unknown_commands_still_see_every_command(capsys):
    from mobility.cli import command_names, main

    assert {"analyze", "check", "actuation", "jacobian", "plot", "sweep", "synthesize", "convert", "view"} <= set(command_names())
    with pytest.raises(SystemExit) as stopped:
        main(["no-such-command"])
    assert stopped.value.code == 2
    err = capsys.readouterr().err
    assert "invalid choice: 'no-such-command'" in err and all(name in err for name in ("analyze", "check", "sweep"))
    with pytest.raises(SystemExit) as stopped:
        main(["--debug", "analyze", "--help"])
    assert stopped.value.code == 0
    assert "usage: mobility analyze" in capsys.readouterr().out
