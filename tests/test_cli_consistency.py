"""The command line says what it does: names it prints are accepted back, options it would not read are refused,
its defaults fit the mechanism, its margins measure what they are said to, its texts are grammatical and its
Markdown stays the document it claims to be."""

from __future__ import annotations

import ast
import csv
import io
import json
import math
import re
import tokenize
from pathlib import Path

import numpy as np
import pytest

import mobility
from mobility import errors
from mobility.actuation import check_actuation, enumerate_actuations, locked_dof
from mobility.cli import main
from mobility.core.loop_closure import loop_closure
from mobility.report.markdown import markdown_report
from mobility.sweeps import sweep

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"
RPS = str(MECHANISMS / "actuation_3rps.yaml")
FOUR_BAR = str(MECHANISMS / "four_bar.yaml")
HAND = ROOT / "tests" / "data" / "robots" / "hand"


def run(capsys, *args):
    status = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return status, out, err


# --- 1. freedom names: what the tool prints, it accepts; every command numbers freedoms from 0 -----------------


def test_the_freedom_names_actuation_prints_are_accepted_back(capsys):
    status, out, _ = run(capsys, "actuation", RPS, "--inputs", "S1")
    printed = next(line for line in out.splitlines() if line.startswith("  inputs:")).split(":", 1)[1].split("(")[0]
    assert [n.strip() for n in printed.split(",")] == ["S1.0", "S1.1", "S1.2"]
    # each printed name, given back, is that freedom alone (was: "unknown joint 'S1.0'")
    status, out, err = run(capsys, "actuation", RPS, "--inputs", "S1.0,S1.1,P2")
    assert status == 0 and err == ""
    assert "  inputs: S1.0, S1.1, P2 (3 for 3 DOF)" in out
    both = check_actuation(mobility.load(RPS), ["S1.0", "S1.1", "P2"])
    assert both.verdict == "valid" and [i.name for i in both.inputs] == ["S1.0", "S1.1", "P2"]
    # the second route: locking those freedoms alone (the spherical joint's first two) leaves the same inputs' wrenches
    whole = check_actuation(mobility.load(RPS), ["S1", "P2"])
    assert np.allclose(whole.inputs[0].wrench, both.inputs[0].wrench) and np.allclose(whole.inputs[1].wrench, both.inputs[1].wrench)
    # the sweep takes the same names
    status, out, err = run(capsys, "sweep", RPS, "--inputs", "S1.0,S1.1,P2", "--vary", "P1=0:1:2", "--format", "csv", "--no-progress")
    assert status == 0 and [row["verdict"] for row in csv.DictReader(io.StringIO(out))] == ["valid", "valid"]


@pytest.mark.parametrize(
    "inputs, message",
    [
        ("S1.3", "mobility: actuated: 'S1.3': joint 'S1' has freedoms S1.0 to S1.2\n"),
        ("P1.0", "mobility: actuated: 'P1.0': joint 'P1' has one freedom; name it 'P1'\n"),
        ("S1,S1.2", "mobility: actuated: 'S1.2' names freedom 'S1.2' again (given by 'S1'); name each input once\n"),
    ],
)
def test_a_freedom_name_out_of_range_or_given_twice_is_one_line(capsys, inputs, message):
    status, out, err = run(capsys, "actuation", RPS, "--inputs", inputs)
    assert status == 2 and out == "" and err == message


ARM = """\
name: arm
ground: g
end_effector: e
joints:
  - {name: U, type: U, links: [g, a], point: [0, 0, 0], axes: [[0, 0, 1], [0, 1, 0]]}
  - {name: P, type: P, links: [a, e], axis: [1, 0, 0]}
"""


def test_jacobian_numbers_freedoms_from_0_as_actuation_does(tmp_path, capsys):
    arm = tmp_path / "arm.yaml"
    arm.write_text(ARM, encoding="utf-8")
    labels = [i.name for i in check_actuation(mobility.loads(ARM), ["U", "P"]).inputs]
    assert labels == ["U.0", "U.1", "P"]
    status, out, _ = run(capsys, "jacobian", arm, "--actuated", ",".join(labels), "--json")
    assert status == 0 and json.loads(out)["actuated"] == labels  # was: U.0 refused ("freedoms 1..2")
    status, out, _ = run(capsys, "jacobian", arm, "--actuated", "U", "--json")
    assert json.loads(out)["actuated"] == ["U.0", "U.1"]  # the whole joint: the same labels (were U.1, U.2)
    status, _, err = run(capsys, "jacobian", arm, "--actuated", "U.2,P")
    assert status == 2 and err == f"mobility: {arm}: actuated: 'U.2': joint 'U' has freedoms U.0 to U.1\n"


# --- 2. options that would be left unread are refused ----------------------------------------------------------


@pytest.mark.parametrize(
    "args, message",
    [
        (["view", FOUR_BAR, "-o", "{tmp}/v.html", "--max-poses", "5"], "--max-poses needs --vary"),
        (["view", FOUR_BAR, "-o", "{tmp}/v.html", "--step", "0.1"], "--step needs --samples"),  # the default value, typed
        (["view", FOUR_BAR, "-o", "{tmp}/v.html", "--seed", "3"], "--seed needs --samples"),
        (["synthesize", "3T", "--other", "SPRR"], "--other needs --write"),
        (["actuation", RPS, "--step", "0.2"], "--step needs --samples"),
        (["actuation", RPS, "--enumerate", "--seed", "4"], "--seed needs --samples"),
        (["actuation", str(ROOT / "examples" / "flexure" / "three_rod.yaml"), "--enumerate", "--mode", "limb"], "--mode chooses how a rigid mechanism's joints"),
        (["plot", FOUR_BAR, "-o", "{tmp}/g.png", "--graph", "--views", "1"], "--views draws on the mechanism, not on the --graph picture"),
        (["plot", FOUR_BAR, "-o", "{tmp}/g.png", "--graph", "--no-labels"], "--no-labels draws on the mechanism, not on the --graph picture"),
        (["sweep", FOUR_BAR, "--vary", "A=0:1:2", "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "--workers sets the threads of this process"),
    ],
)
def test_an_option_its_command_would_not_read_is_refused_in_one_line(tmp_path, capsys, args, message):
    status, out, err = run(capsys, *[a.replace("{tmp}", str(tmp_path)) for a in args])
    assert status == 2 and out == ""
    assert err.startswith(f"mobility: {message}") and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []  # refused before any work


def test_the_same_options_with_what_they_need_are_read(tmp_path, capsys):
    status, out, _ = run(capsys, "actuation", RPS, "--samples", "2", "--step", "0.2", "--seed", "4")
    assert status == 0 and "other poses: 2 of 2 valid" in out


# --- 3. the default enumeration of a single loop -----------------------------------------------------------------


def test_limb_mode_drives_a_single_loop_with_one_joint_as_mode_any_does(capsys):
    status, out, _ = run(capsys, "actuation", FOUR_BAR, "--enumerate")
    assert status == 0  # was 1: every pair of joints "redundant", no combination valid
    assert "one actuated joint in each of 1 of the 2 limbs: 4 combinations" in out
    status, out, _ = run(capsys, "actuation", FOUR_BAR, "--enumerate", "--json")
    found = json.loads(out)
    assert (found["mode"], found["k"], found["limbs"]) == ("limb", 1, 2)
    limb = {tuple(c["inputs"]): c["verdict"] for c in found["combinations"]}
    assert limb == {(name,): "valid" for name in "ABCD"}
    m = mobility.load(FOUR_BAR)
    anywhere = {c.inputs: c.verdict for c in enumerate_actuations(m, mode="any").combinations}
    assert anywhere == limb  # the two modes agree on a single loop
    assert all(locked_dof(m, list(inputs)) == 0 for inputs in limb)  # the second route: each joint locked holds the loop


def test_limb_mode_drives_dof_of_the_limbs_when_several_loops_have_more_limbs_than_dof(capsys):
    # the Tricept: three UPS legs and a passive central UP leg, 3 DOF; one input in each of the four legs was
    # "redundant" (nothing valid); the machine is driven by its three UPS legs
    tricept = ROOT / "mechanisms" / "tricept.yaml"
    status, out, _ = run(capsys, "actuation", tricept, "--enumerate")
    assert status == 0 and "one actuated joint in each of 3 of the 4 limbs: 4 combinations, checked at 1 pose" in out
    m = mobility.load(tricept)
    found = enumerate_actuations(m)
    assert (found.k, found.limbs) == (3, 4)
    assert found.combinations[0].inputs == ("P1", "P2", "P3") and found.combinations[0].verdict == "valid"
    limb = {c.inputs: c.verdict for c in found.combinations}
    assert len(limb) == 4 and set(limb.values()) == {"valid"}
    anywhere = {c.inputs: c.verdict for c in enumerate_actuations(m, mode="any").combinations}
    assert all(anywhere[inputs] == verdict for inputs, verdict in limb.items())  # the same verdict in mode any
    assert all(locked_dof(m, list(inputs)) == 0 for inputs in limb)  # the second route: the three locked hold the platform


def test_limb_mode_finding_nothing_points_to_mode_any(tmp_path, capsys):
    arm = tmp_path / "rr.yaml"  # one limb, two DOF: one joint per limb is too few
    arm.write_text("name: RR arm\nground: g\nend_effector: hand\njoints:\n"
                   "  - {name: A, type: R, links: [g, upper], axis: [0, 0, 1], point: [0, 0, 0]}\n"
                   "  - {name: B, type: R, links: [upper, hand], axis: [0, 0, 1], point: [1, 0, 0]}\n", encoding="utf-8")
    status, out, _ = run(capsys, "actuation", arm, "--enumerate")
    assert status == 1 and "no combination is valid at every pose (one joint per limb; mode 'any', --mode any, tries any 2 of the joints)" in out
    assert run(capsys, "actuation", arm, "--enumerate", "--mode", "any")[0] == 0


# --- 4. the actuation margin is 0 at an actuation singularity ----------------------------------------------------


def crank_rocker(crank_deg: float, end_effector: str = "rocker", scale: float = 1.0, shift=(0.0, 0.0)) -> mobility.Mechanism:
    """Crank 1 at A = (0, 0), coupler 4, rocker 3 at D = (4, 0): a crank-rocker, the crank actuated; toggle at atan2(3, 4)."""
    t = math.radians(crank_deg)
    b = np.array([math.cos(t), math.sin(t)])
    d = np.array([4.0, 0.0])
    dist = float(np.linalg.norm(d - b))
    along = (16 - 9 + dist**2) / (2 * dist)
    u = (d - b) / dist
    c = b + along * u + math.sqrt(max(16 - along**2, 0.0)) * np.array([-u[1], u[0]])
    p = lambda q: f"[{float(q[0] * scale + shift[0])!r}, {float(q[1] * scale + shift[1])!r}, 0]"  # noqa: E731
    return mobility.loads(f"""
name: crank-rocker
ground: ground
end_effector: {end_effector}
joints:
  - {{name: A, type: R, links: [ground, crank], axis: [0, 0, 1], point: {p((0, 0))}, actuated: true}}
  - {{name: B, type: R, links: [crank, coupler], axis: [0, 0, 1], point: {p(b)}}}
  - {{name: C, type: R, links: [coupler, rocker], axis: [0, 0, 1], point: {p(c)}}}
  - {{name: D, type: R, links: [rocker, ground], axis: [0, 0, 1], point: {p(d)}}}
""")


TOGGLE = math.degrees(math.atan2(3, 4))  # crank and coupler in line: the rocker at the end of its swing


def rocker_angle(crank_deg: float) -> float:
    m = crank_rocker(crank_deg)
    c, d = (np.array(j.point) for j in m.world_joints[2:])
    return math.atan2(c[1] - d[1], c[0] - d[0])


def test_the_actuation_margin_vanishes_at_a_crank_rockers_toggle(capsys):
    at = check_actuation(crank_rocker(TOGGLE))
    regular = check_actuation(crank_rocker(TOGGLE + 90))
    assert at.actuation_margin < 1e-6 * regular.actuation_margin  # was 0.707 at the toggle (the rank margin)
    assert regular.verdict == "valid" and regular.actuation_margin > 0.1
    assert at.margin.smallest_kept > 0.5  # the rank margin does not see it: the locked crank holds the rocker
    # the second route: by loop closure the rocker stands still while the crank turns at the toggle
    rates = loop_closure(crank_rocker(TOGGLE)).joint_rates[:, 0]
    assert abs(rates[3]) < 1e-12 * abs(rates[0]) and abs(rates[0]) > 0.1
    # the third: near the toggle the margin is proportional to the velocity ratio by finite differences
    ratio = [abs(rocker_angle(TOGGLE + x + 1e-6) - rocker_angle(TOGGLE + x - 1e-6)) / 2e-6 for x in (0.5, 1.0, 2.0)]
    margin = [check_actuation(crank_rocker(TOGGLE + x)).actuation_margin for x in (0.5, 1.0, 2.0)]
    per_ratio = [m / r for m, r in zip(margin, ratio)]
    assert max(per_ratio) < 1.02 * min(per_ratio)
    # scale-invariant: the same linkage a thousand times larger, elsewhere
    moved = check_actuation(crank_rocker(TOGGLE + 30, scale=1e3, shift=(5e3, -2e3)))
    assert moved.actuation_margin == pytest.approx(check_actuation(crank_rocker(TOGGLE + 30)).actuation_margin, rel=1e-9)
    # driving the coupler instead, the toggle is no singularity: the crank turns the coupler about C
    assert check_actuation(crank_rocker(TOGGLE, "coupler")).actuation_margin > 0.1
    # the report says so
    assert "actuation margin: 0.00e+00" in __import__("mobility.report.actuation", fromlist=["x"]).actuation_text(at)


def test_the_sweeps_actuation_margin_column_vanishes_at_the_toggle(tmp_path, capsys):
    path = tmp_path / "toggle.yaml"
    m = crank_rocker(TOGGLE)
    from mobility.io.writer import mechanism_to_yaml

    path.write_text(mechanism_to_yaml(m), encoding="utf-8")
    status, out, _ = run(capsys, "sweep", path, "--vary", "A=-10:10:5", "--format", "csv", "--no-progress")
    rows = {float(r["A [deg]"]): float(r["actuation_margin"]) for r in csv.DictReader(io.StringIO(out))}
    assert status == 0 and rows[0.0] < 1e-6 and min(rows[-10.0], rows[10.0]) > 0.04  # was 0.707 at the toggle
    r = sweep(m, ["A=-10:10:5"])
    for i in range(r.size):  # the one-pose check on each pose rebuilt
        assert r.actuation_margin[i] == pytest.approx(check_actuation(r.mechanism_at(i), tol=r.tolerance).actuation_margin, rel=1e-6, abs=1e-12)


# --- 5. counts in words -----------------------------------------------------------------------------------------


def test_explanations_count_in_the_singular_and_the_plural():
    said = mobility.analyze(mobility.load(FOUR_BAR)).gruebler_kutzbach_explanation
    assert "the 1 independent loop imposes 6 independent constraints" in said
    assert "3 constraints are redundant" in said and "from 3 wrenches reciprocal" in said and "the loop loses 3 equations" in said
    verdict = check_actuation(mobility.load(FOUR_BAR), ["A"]).explanation
    assert verdict.startswith("the 1 actuation wrench and the 5 constraint wrenches span")
    for text in (said, verdict, check_actuation(mobility.load(RPS), ["P1", "P2"]).explanation):
        assert "(s)" not in text and "(es)" not in text


def test_no_message_or_report_counts_with_a_parenthesised_plural():
    # "1 freedom(s)", "3 wrench(es)": every count in a message or a report is written through errors.counted
    found = []
    for path in sorted((ROOT / "mobility").rglob("*.py")):
        for token in tokenize.generate_tokens(io.StringIO(path.read_text(encoding="utf-8")).readline):
            if token.type == tokenize.STRING and not token.string.lstrip("rbfuRBFU").startswith(('"""', "'''")) and re.search(r"[a-z]\((?:e)?s\)", re.sub(r"\{[^{}]*\}", "", token.string)):  # not in {expressions}
                found.append(f"{path.relative_to(ROOT)}:{token.start[0]}: {token.string}")
    assert found == []
    assert errors.counted(1, "wrench", "es") == "1 wrench" and errors.counted(3, "wrench", "es") == "3 wrenches"


def _counted_nouns(trees: dict[Path, ast.Module]) -> set[str]:
    """The nouns the package counts (the last word of every ``counted(n, "noun")``), in the singular."""
    return {n.args[1].value.split()[-1] for tree in trees.values() for n in ast.walk(tree)
            if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id == "counted" and len(n.args) >= 2
            and isinstance(n.args[1], ast.Constant) and isinstance(n.args[1].value, str)}


_PLURAL_VERBS = ("are", "were", "have", "follow", "leave", "remain", "span", "survive", "stay", "move", "lie", "meet", "pass", "make", "give")
"""Verbs in the plural form: after a count written through counted (which may be 1), the verb must follow the count too."""


_NEVER_ONE = {
    ("mobility/view/describe.py", "len(results)"): "the poses of a view of several poses (one pose is described above it)",
    ("mobility/view/sweep.py", "size"): "a sweep of more poses than are drawn",
}
"""Counts formatted by hand that the code around them keeps above 1."""


def _formatted_count_problems(trees: dict[Path, ast.Module]) -> list[str]:
    """Counts formatted by hand before a plural noun (``f"{n} poses"``: "1 poses"), and counts through counted followed by a plural verb ("1 freedom follow")."""
    nouns = _counted_nouns(trees)
    plurals = {w + "s" for w in nouns} | {w + "es" for w in nouns}
    found = []
    for path, tree in trees.items():
        for node in ast.walk(tree):
            if not isinstance(node, ast.JoinedStr):
                continue
            parts = node.values
            whole = "".join(p.value if isinstance(p, ast.Constant) else "{}" for p in parts)
            for k, part in enumerate(parts):
                if not isinstance(part, ast.FormattedValue) or k + 1 == len(parts) or not isinstance(parts[k + 1], ast.Constant):
                    continue
                after = "".join(p.value if isinstance(p, ast.Constant) else "{}" for p in parts[k + 1:])
                is_counted = isinstance(part.value, ast.Call) and isinstance(part.value.func, ast.Name) and part.value.func.id == "counted"
                where = f"{path.relative_to(ROOT)}:{part.lineno}: {{{ast.unparse(part.value)}}}{after[:40]}"
                word = re.match(r" ([a-z]+)\b", after)
                if not is_counted and word and word.group(1) in plurals and "than the limit" not in whole and "more than" not in whole and (  # a count above a limit is never 1
                        (str(path.relative_to(ROOT)), ast.unparse(part.value)) not in _NEVER_ONE):
                    found.append(where)
                clause = re.split(r"[,;:(){]", after, maxsplit=1)[0]
                before = "".join(p.value if isinstance(p, ast.Constant) else "{}" for p in parts[:k])
                verb = re.search(rf"\b({'|'.join(_PLURAL_VERBS)})\b", clause)
                if is_counted and verb and not before.endswith("and the ") and not after[verb.end():].startswith("{"):  # "pass{es}": agreed
                    found.append(where)
    return found


def test_no_count_formatted_by_hand_before_a_plural_and_no_plural_verb_after_a_count():
    # "not assembled: 1 poses", "the other 1 freedom follow": counts built by formatting, which a scan of constants cannot see
    trees = {path: ast.parse(path.read_text(encoding="utf-8")) for path in sorted((ROOT / "mobility").rglob("*.py"))}
    assert {"pose", "freedom", "motion"} <= _counted_nouns(trees)
    assert _formatted_count_problems(trees) == []
    planted = {ROOT / "mobility" / "planted.py": ast.parse('f"not assembled: {n:,} poses"; f"the other {counted(k, \'freedom\')} follow the solver"; '
                                                            'f"{counted(k, \'motion\')} of the joints leave"; f"{counted(k, \'line\')} pass{s}"; '
                                                            'f"{count} joints are more than the limit"')}
    assert [p.split(": ", 1)[1] for p in _formatted_count_problems({**trees, **planted}) if "planted" in p] == [
        "{n} poses", "{counted(k, 'freedom')} follow the solver", "{counted(k, 'motion')} of the joints leave"]


def test_reports_with_counts_of_one_agree_in_the_singular():
    from mobility.report.sweep import sweep_summary
    from mobility.report.text import text_report

    # one idle motion: a slider beside a four-bar, off the path to the end effector
    idle = mobility.loads(Path(FOUR_BAR).read_text(encoding="utf-8").replace("expected:", "  - {name: X, type: P, links: [ground, probe], axis: [1, 0, 0]}\nexpected:"))
    said = text_report(mobility.analyze(idle))
    assert "idle DOF: 1 motion of the joints leaves the end effector still" in said
    # one pose that cannot close (the parallelogram's O2 held while O1 turns)
    one = sweep_summary(sweep(mobility.load(MECHANISMS / "parallelogram.yaml"), ["O1=10:10:1", "O2=0:0:1"]))
    assert "assembled: 0 of 1 pose" in one and "not assembled: 1 pose (" in one and "sweep of 2 coordinates, 1 pose" in one
    # one freedom left to the solver: two of the three prismatic joints of the 3-UPU driven
    left = sweep_summary(sweep(mobility.load(MECHANISMS / "3upu_singular.yaml"), ["P1=-30:30:3", "P2=-30:30:3"]))
    assert "the other 1 freedom follows the solver (the smallest change from the neighbouring pose), so the path across the grid decides it" in left


def test_reports_say_the_centre_and_the_margins_in_a_designers_words():
    from mobility.report.text import text_report

    r = mobility.analyze(mobility.load(MECHANISMS / "3prs_tilted.yaml"))
    centre = "[0.292623, -0.608285, 0]"
    kept, dropped = f"{r.margin.smallest_kept:.2e}", f"{r.margin.largest_dropped:.2e}"
    for text in (text_report(r), markdown_report(r)):
        assert f"the end effector's centre is at {centre}; each axis is" in text  # a centre, not a point of the axis
        assert f"centre {centre}" not in text
        assert re.search(rf"[Dd]istance to a singularity: {kept}\s+\(1 far from one, 0 where the count changes", text)
        assert re.search(rf"[Dd]eparture from the special geometry: {dropped}\s+\(0 or round-off when it is exact", text)
        assert "margin: smallest kept" not in text and "Rank margin" not in text


# --- 6. Markdown: names cannot inject blocks ---------------------------------------------------------------------


INJECTED = """\
name: "arm | left #"
ground: ground
end_effector: coupler
joints:
  - {name: "#A|1", type: R, links: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: "B", type: R, links: [crank, coupler],  axis: [0, 0, 1], point: [1, 2, 0]}
  - {name: "C", type: R, links: [coupler, "rock|er"], axis: [0, 0, 1], point: [4, 2.5, 0]}
  - {name: "D", type: R, links: ["rock|er", ground],  axis: [0, 0, 1], point: [5, 0, 0]}
"""


def test_names_in_markdown_start_no_heading_and_break_no_table(tmp_path, capsys):
    path = tmp_path / "inject.yaml"
    path.write_text(INJECTED, encoding="utf-8")
    status, out, _ = run(capsys, "analyze", path, "--format", "md")
    assert status == 0
    headings = [line for line in out.splitlines() if line.startswith("#")]
    assert headings == ["# arm \\| left \\#", "## Freedoms of the end effector (1)", "## Constraint wrenches on the end effector (5)",
                        "## Whole mechanism", "## Limbs (2), each in its own frame"]  # the name's last '#' kept (was read as the heading's closing)
    structure = next(line for line in out.splitlines() if line.startswith("Structure"))
    assert structure.endswith("`parallel(series(#A|1,B), series(D,C))`")
    for table in [block for block in out.split("\n\n") if block.startswith("|")]:
        cells = {line.replace("\\|", "").count("|") for line in table.splitlines()}
        assert len(cells) == 1  # every row as many cells as the header
    assert markdown_report(mobility.analyze(mobility.loads(INJECTED))) == out.rstrip("\n")
    from mobility.report.markdown import md_code, md_heading, md_line

    # text given to one Markdown line keeps to it, whatever reaches it (a name from the model holds no line break;
    # a warning or a hand-made result might): no "## " can start a heading of its own
    assert md_code("A\n## B") == "`A ## B`" and md_line("x\r\n# y\u2028z") == "x # y z" and md_heading("a\n## b #") == "a ## b \\#"


# --- 7. messages say the actual problem --------------------------------------------------------------------------


def test_a_yaml_pose_of_a_robot_read_with_close_is_named_as_the_problem(capsys):
    status, out, err = run(capsys, "actuation", HAND / "four_bar.urdf", "--close", "coupler_tip", "rocker_tip", "--end-effector", "coupler",
                           "--pose", FOUR_BAR)
    last = err.strip().splitlines()[-1]
    assert status == 2 and out == ""
    assert last.startswith(f"mobility: --pose {FOUR_BAR}: a mechanism file (YAML), while FILE ")  # was: "--close: options of robot description files ..."
    assert "read with --close, --end-effector" in last


def test_an_unbalanced_brace_in_a_limb_name_is_said(tmp_path, capsys):
    text = (MECHANISMS / "actuation_3rps.yaml").read_text(encoding="utf-8").replace('name: "P{i+1}"', 'name: "P{i"')
    path = tmp_path / "brace.yaml"
    path.write_text(text, encoding="utf-8")
    status, _, err = run(capsys, "analyze", path)
    line = text[: text.index('name: "P{i"')].count("\n") + 1
    assert status == 2  # was: "duplicate joint name 'P{i' (first used by joints[1])"
    assert err == f"mobility: {path}:{line}: limbs[0].joints[1].name: 'P{{i': an unbalanced brace; write each substituted expression in a pair, as 'P{{i+1}}'\n"


def test_a_youngs_modulus_past_the_largest_float_in_pascals_is_said(tmp_path, capsys):
    text = (ROOT / "examples" / "flexure" / "three_rod.yaml").read_text(encoding="utf-8")
    assert "E: 70," in text
    path = tmp_path / "stiff.yaml"
    path.write_text(text.replace("E: 70,", "E: 1e300,"), encoding="utf-8")
    status, _, err = run(capsys, "actuation", path)
    assert status == 2 and "got inf" not in err  # was: "expected a positive number, got inf"
    assert "materials.aluminium.E: 1e+300 (units.modulus) is 1e+300 x 1e+09 Pa, beyond the largest float" in err and err.count("\n") == 1


def par4_like(limbs: int = 4) -> mobility.Mechanism:
    """A Par4-like robot: each limb an actuated R, a planar parallelogram of four R joints, and a U to the plate."""
    lines = ["name: Par4-like", "ground: base", "end_effector: plate", "joints:"]
    for i in range(limbs):
        c, s = math.cos(2 * math.pi * i / limbs), math.sin(2 * math.pi * i / limbs)
        at = lambda x, y, z: f"[{x * c - y * s!r}, {x * s + y * c!r}, {float(z)!r}]"  # noqa: E731
        tangent, radial = f"[{-s!r}, {c!r}, 0]", f"[{c!r}, {s!r}, 0]"
        lines += [
            f"  - {{name: A{i}, type: R, links: [base, arm{i}], axis: {tangent}, point: {at(200, 0, 0)}, actuated: true}}",
            f"  - {{name: B{i}a, type: R, links: [arm{i}, rod{i}a], axis: {radial}, point: {at(450, -30, 0)}}}",
            f"  - {{name: B{i}b, type: R, links: [arm{i}, rod{i}b], axis: {radial}, point: {at(450, 30, 0)}}}",
            f"  - {{name: C{i}a, type: R, links: [rod{i}a, bar{i}], axis: {radial}, point: {at(450, -30, -500)}}}",
            f"  - {{name: C{i}b, type: R, links: [rod{i}b, bar{i}], axis: {radial}, point: {at(450, 30, -500)}}}",
            f"  - {{name: D{i}, type: U, links: [bar{i}, plate], point: {at(450, 0, -500)}, axes: [{tangent}, {radial}]}}",
        ]
    return mobility.loads("\n".join(lines) + "\n")


def test_the_redundancy_of_planar_loops_inside_limbs_is_attributed_to_them():
    r = mobility.analyze(par4_like())
    said = r.gruebler_kutzbach_explanation
    assert (r.redundant_constraints, r.loops, r.common_constraints) == (16, 7, 1)
    # each parallelogram, one end held, moves with 1 freedom where Grübler–Kutzbach counts 6(4 - 1 - 4) + 4 = -2: 3 redundant,
    # one of them the couple common to every joint; was: 9 put down to "the special geometry of the loops" with no loop named
    assert "7 of them come from 1 wrench reciprocal to every joint twist: each loop loses 1 equation." in said
    assert "8 more come from 4 sub-networks of loops inside the limbs" in said and "parallel(series(B0a,C0a), series(B0b,C0b))" in said
    assert "(2 each, beyond those common to every joint)" in said
    assert said.endswith("1 comes from the special geometry of the other loops (parallel or intersecting axes, repeated constraints of parallel limbs).")
    # the second route: a parallelogram alone (its bar the end effector) has those 3 redundant constraints
    alone = mobility.loads(
        "name: parallelogram\nground: arm\nend_effector: bar\njoints:\n"
        "  - {name: Ba, type: R, links: [arm, a], axis: [1, 0, 0], point: [450, -30, 0]}\n"
        "  - {name: Bb, type: R, links: [arm, b], axis: [1, 0, 0], point: [450, 30, 0]}\n"
        "  - {name: Ca, type: R, links: [a, bar], axis: [1, 0, 0], point: [450, -30, -500]}\n"
        "  - {name: Cb, type: R, links: [b, bar], axis: [1, 0, 0], point: [450, 30, -500]}\n"
    )
    assert mobility.analyze(alone).redundant_constraints == 3
