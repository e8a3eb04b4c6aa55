"""The Markdown report: its tables read back give the analysis (and the independent loop-closure route)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from builders import THREE_RPS_YAML
from scipy.linalg import subspace_angles

import mobility
from mobility.cli import main
from mobility.core.joint_screws import joint_screws
from mobility.core.loop_closure import loop_closure
from mobility.errors import RequestError
from mobility.report.markdown import markdown_report, markdown_table, md_escape

MECHANISMS = sorted((Path(__file__).resolve().parent.parent / "mechanisms").glob("*.yaml"))

RPS = THREE_RPS_YAML.replace("name: 3-RPS\n", "name: 3-RPS | test\n", 1)

SCREW = """
name: nut
ground: g
end_effector: nut
joints:
  - {name: H1, type: H, links: [g, nut], axis: [0, 0, 1], point: [1, 2, 0], pitch: 0.25}
"""


def split_row(line: str) -> list[str]:
    """Cells of a Markdown table row (escaped pipes kept inside cells)."""
    cells = re.split(r"(?<!\\)\|", line.strip())[1:-1]
    return [c.strip().replace("\\|", "|") for c in cells]


def tables(text: str) -> dict[str, list[dict[str, str]]]:
    """Every table of the report, keyed by the heading above it."""
    out: dict[str, list[dict[str, str]]] = {}
    heading = ""
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("#"):
            heading = line.lstrip("# ").split(" (")[0]
        if line.startswith("|") and i + 1 < len(lines) and re.fullmatch(r"\|(:?-+:?\|)+", lines[i + 1]):
            header = split_row(line)
            rows = []
            i += 2
            while i < len(lines) and lines[i].startswith("|"):
                cells = split_row(lines[i])
                assert len(cells) == len(header), lines[i]
                rows.append(dict(zip(header, cells)))
                i += 1
            out[heading] = rows
            continue
        i += 1
    return out


def vec(text: str) -> np.ndarray:
    return np.array([float(x) for x in text.strip("[]").split(",")])


def screw_rows(rows: list[dict[str, str]], point_key: str, pitch_key: str) -> np.ndarray:
    """Screws [a; b] from table rows: free vectors (no point) or lines with a pitch."""
    out = []
    for r in rows:
        d = vec(r["direction / axis"])
        if not r[point_key]:
            out.append(np.concatenate([np.zeros(3), d]))
        else:
            p, h = vec(r[point_key]), float(r[pitch_key])
            out.append(np.concatenate([d, np.cross(p, d) + h * d]))
    return np.array(out).reshape(-1, 6)


def load(text_or_path):
    return mobility.load(text_or_path) if isinstance(text_or_path, Path) else mobility.loads(text_or_path)


CASES = [pytest.param(p, id=p.stem) for p in MECHANISMS] + [pytest.param(RPS, id="3rps"), pytest.param(SCREW, id="helical")]


@pytest.mark.parametrize("source", CASES)
def test_tables_read_back_give_the_analysis(source):
    m = load(source)
    r = mobility.analyze(m)
    text = markdown_report(r)
    t = tables(text)
    unit = f" ({r.length_unit})" if r.length_unit else ""
    free = t.get("Freedoms of the end effector", [])
    cons = t.get("Constraint wrenches on the end effector", [])
    assert len(free) == r.dof
    assert len(cons) == 6 - r.dof
    assert sum(row["kind"] == "translation" for row in free) == r.translation_count
    assert sum(row["kind"] == "couple" for row in cons) == len(r.couples)
    norm = joint_screws(m).normalisation
    closure = loop_closure(m)  # the independent route
    if r.dof:
        printed = norm.from_world(screw_rows(free, f"point on axis{unit}", f"pitch{unit}/rad").T)
        # second route: the end-effector twists of the loop-closure Jacobian
        assert np.max(subspace_angles(printed, closure.end_effector_twists)) < 1e-4
    if r.dof < 6:
        printed_w = norm.from_world(screw_rows(cons, f"point on axis{unit}", f"pitch{unit}").T)
        # reciprocal to every end-effector twist (swap the halves for the reciprocal product)
        lc = closure.end_effector_twists
        swapped = np.vstack([printed_w[3:], printed_w[:3]])
        assert np.max(np.abs(swapped.T @ lc)) < 1e-4 if lc.size else True
        assert np.linalg.matrix_rank(printed_w, tol=1e-4) == 6 - r.dof
    whole = {row["quantity"]: int(row["value"]) for row in t["Whole mechanism"]}
    assert whole["links (ground included)"] == len(m.links)
    assert whole["joints"] == len(m.joints)
    assert whole["joint freedoms"] == sum(j.dof for j in m.joints)
    assert whole["Grübler–Kutzbach count"] == 6 * (len(m.links) - 1 - len(m.joints)) + sum(j.dof for j in m.joints) - len(m.couplings)  # one per coupling
    assert whole["mobility (screw theory)"] == closure.mobility
    assert whole["redundant constraints"] == whole["mobility (screw theory)"] - whole["Grübler–Kutzbach count"]
    assert whole["idle DOF (end effector still)"] == whole["mobility (screw theory)"] - r.dof
    assert f"`{r.structure}`" in text


def test_3rps_constraint_forces_and_limbs():
    r = mobility.analyze(mobility.loads(RPS))
    assert r.pattern == "1T2R"
    t = tables(markdown_report(r))
    cons = t["Constraint wrenches on the end effector"]
    # three coplanar forces (one per limb, through S_i along the base R axis) span
    # one couple about the normal of their plane and two forces in that plane
    assert [row["kind"] for row in cons] == ["couple", "force", "force"]
    assert np.allclose(np.abs(vec(cons[0]["direction / axis"])), [0, 0, 1], atol=1e-6)
    for row in cons[1:]:
        assert abs(vec(row["direction / axis"])[2]) < 1e-6
        assert vec(row["point on axis (mm)"])[2] == pytest.approx(150, rel=1e-6)
    # the limb table: one row per limb, each limb a 5-DOF chain with one constraint force
    limbs = t["Limbs"]
    assert [int(row["limb"]) for row in limbs] == [1, 2, 3]
    assert all(int(row["DOF"]) == 5 and row["constraint wrenches"].count("force") == 1 for row in limbs)


def test_pitch_is_printed_for_a_helical_freedom():
    r = mobility.analyze(mobility.loads(SCREW))
    free = tables(markdown_report(r))["Freedoms of the end effector"]
    assert len(free) == 1 and free[0]["kind"] == "helical"
    assert float(free[0]["pitch/rad"]) == pytest.approx(0.25, rel=1e-5)
    assert np.allclose(np.cross(vec(free[0]["point on axis"]) - [1, 2, 0], [0, 0, 1]), 0, atol=1e-5)


def test_name_with_pipe_is_escaped_and_heading_kept():
    text = markdown_report(mobility.analyze(mobility.loads(RPS)))
    assert text.splitlines()[0] == "# 3-RPS \\| test"
    assert md_escape("a|b") == "a\\|b"
    with pytest.raises(RequestError, match="expected 3 cells in each row, got a row of 2"):
        markdown_table(["a", "b", "c"], [[1, 2]])
    with pytest.raises(RequestError, match="one letter per column"):
        markdown_table(["a", "b"], [], align="l")
    with pytest.raises(RequestError, match="letters l, r or c"):
        markdown_table(["a", "b"], [], align="lx")


def test_cli_format_md_and_json(tmp_path, capsys):
    path = tmp_path / "rps.yaml"
    path.write_text(RPS)
    assert main(["analyze", str(path), "--format", "md"]) == 0
    out = capsys.readouterr().out
    assert out.rstrip("\n") == markdown_report(mobility.analyze(mobility.load(path)))
    assert main(["analyze", str(path), "--format", "json"]) == 0
    as_format = capsys.readouterr().out
    assert main(["analyze", str(path), "--json"]) == 0
    assert capsys.readouterr().out == as_format


def test_a_joint_name_with_backticks_stays_inside_its_code_span():
    # names with backticks ended the code span early: the rest of the structure was read as Markdown
    text = THREE_RPS_YAML.replace('name: "R{i+1}"', 'name: "R`{i+1}"').replace('name: "P{i+1}"', 'name: "P``{i+1}"')
    assert "R`{i+1}" in text and "P``{i+1}" in text
    report = markdown_report(mobility.analyze(mobility.loads(text)))
    structure = next(line for line in report.splitlines() if line.startswith("Structure"))
    fence, code = re.fullmatch(r"Structure \(series/parallel decomposition\): (`+)(.*)\1", structure).groups()
    assert len(fence) == 3 and "R`1" in code and "P``1" in code  # a fence longer than any run inside
    limb_cells = [line.split(" | ")[1] for line in report.splitlines() if line.startswith("| 1 |")]
    assert limb_cells and limb_cells[0].startswith("```") and "R`1" in limb_cells[0]
