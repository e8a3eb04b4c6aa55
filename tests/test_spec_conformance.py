"""Files that follow the contract (docs/spec-v1.md) load and give its results; what it leaves open is refused in one line.

Findings of a spec audit: a helical joint in a tiny mechanism was refused
(and the advice "write it as a P joint" changed its answer); a zero or
dependent expected translation basis was a failed check instead of bad
input; the contract's pattern of a mechanism that cannot move was refused;
and docs/file-format.md said more than the code did.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import yaml
from builders import ONE_WIRE_FLEXURE
from conftest import ROOT

import mobility
from mobility.cli import main
from mobility.core.expected import EXPECTED_PATTERN, Expected, require_expected_pattern
from mobility.core.screws import pattern_of
from mobility.core.tolerance import characteristic_scale, characteristic_scales
from mobility.errors import MechanismError, MechanismFileError, RequestError
from mobility.flexure import loads_flexure
from mobility.testing.check import check_file, compare_translations

FORMAT_PAGE = ROOT / "docs" / "file-format.md"

SCALES = (1e-9, 1.0, 1e6)


def _tiny_chain(scale: float, pitch: float = 1.0) -> str:
    """R about z at the origin, then an H about x 1e-9 above it (pitch ``pitch``), then a P along x; every length times ``scale``."""
    return f"""\
name: tiny screw
ground: g
end_effector: e
joints:
  - {{name: A, type: R, links: [g, a], axis: [0, 0, 1], point: [0, 0, 0]}}
  - {{name: B, type: H, links: [a, b], axis: [1, 0, 0], point: [0, 0, {1e-9 * scale!r}], pitch: {pitch * scale!r}}}
  - {{name: C, type: P, links: [b, e], axis: [1, 0, 0]}}
"""


def _exact_counts(axes_points_pitches: list[tuple[tuple[float, ...], tuple[float, ...] | None, float | None]]) -> tuple[int, int]:
    """(dof, translations) of a serial chain from its twists in exact-enough arithmetic (lengths of order one)."""
    twists = []
    for axis, point, pitch in axes_points_pitches:
        s = np.array(axis, dtype=float)
        if point is None:
            twists.append(np.concatenate([np.zeros(3), s]))
        else:
            twists.append(np.concatenate([s, np.cross(point, s) + (pitch or 0.0) * s]))
    t = np.array(twists).T
    dof = np.linalg.matrix_rank(t)
    return dof, dof - np.linalg.matrix_rank(t[:3])


ONE_WIRE = ONE_WIRE_FLEXURE
"""A flexure document of one wire, to which a test adds its ``expected`` block."""


@pytest.mark.parametrize("scale", SCALES)
def test_a_tiny_mechanism_with_a_helical_joint_loads_and_counts_alike_at_every_scale(scale):
    # the H joint's pitch is 2e9 times the spread of the joint points: it was refused ("write it as a P joint"),
    # and as a P joint beside the slider C it would lose its rotation (2 DOF, 1T1R) instead of 3 DOF, 1T2R
    result = mobility.analyze(mobility.loads(_tiny_chain(scale)))
    # the same chain with the offset left out (lengths of order one): the screw's rotation about x stays a rotation
    assert _exact_counts([((0, 0, 1), (0, 0, 0), 0.0), ((1, 0, 0), (0, 0, 0), 1.0), ((1, 0, 0), None, None)]) == (3, 1)
    assert (result.dof, result.pattern, result.mobility) == (3, "1T2R", 3)
    assert np.allclose(np.abs(result.translations), [[1, 0, 0]])
    assert not result.margin.near_singular  # resolved with room to spare, not at the edge of the rank policy


@pytest.mark.parametrize("scale", SCALES)
def test_a_two_joint_chain_with_a_screw_is_two_rotations_at_every_scale(scale):
    text = _tiny_chain(scale).replace("  - {name: C, type: P, links: [b, e], axis: [1, 0, 0]}\n", "").replace("end_effector: e", "end_effector: b")
    result = mobility.analyze(mobility.loads(text))
    assert (result.dof, result.pattern) == (2, "2R")  # a P joint in its place would make it 1T1R
    assert sorted(r.kind for r in result.rotations) == ["helical", "rotation"]
    helical = next(r for r in result.rotations if r.kind == "helical")
    assert helical.pitch == pytest.approx(scale)


@pytest.mark.parametrize("scale", SCALES)
def test_a_pitch_beyond_what_any_scale_resolves_is_refused_alike_at_every_scale_with_true_advice(scale):
    with pytest.raises(MechanismFileError) as info:
        mobility.loads(_tiny_chain(scale, pitch=1e8), file="m.yaml")  # 2e17 times the spread of the points
    err = info.value
    assert (err.line, err.key) == (6, "joints[1].pitch")
    assert re.search(r"is 2\.0e\+17 times the spread of the joint points .*beyond 1e\+16", err.message), err.message
    assert "P joint" not in err.message  # a P joint would change the answer
    assert "write the points that are meant to coincide as one point" in err.message


def test_points_written_as_one_let_a_huge_pitch_be_the_size():
    # the advice of the refusal, followed: the H joint's point on the R joint's, and any pitch is resolved
    text = _tiny_chain(1.0, pitch=1e8).replace("[0, 0, 1e-09]", "[0, 0, 0]")
    result = mobility.analyze(mobility.loads(text))
    assert (result.dof, result.pattern) == (3, "1T2R")


def test_a_pitch_raises_the_characteristic_length_to_the_geometric_mean_whatever_the_scale():
    points = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 2.0]])  # RMS distance 1 from their centroid
    assert characteristic_scale(points, pitches=np.array([1e6]))[1] == pytest.approx(1e3)
    assert characteristic_scale(points, pitches=np.array([0.5]))[1] == 1.0  # a pitch below the spread changes nothing
    assert characteristic_scale(points, np.array([1e6]))[1] == 1.0  # other lengths only stand in for coincident points
    for power in (-60, -3, 7, 90):
        k = math.ldexp(1.0, power)  # an exact scale: the same bits, scaled
        assert characteristic_scale(points * k, pitches=np.array([1e6 * k]))[1] == characteristic_scale(points, pitches=np.array([1e6]))[1] * k
    many = np.stack([points, points * 3.0])
    assert characteristic_scales(many, pitches=np.array([1e6]))[1].tolist() == [
        characteristic_scale(points, pitches=np.array([1e6]))[1], characteristic_scale(points * 3.0, pitches=np.array([1e6]))[1]]


def _slide_with(expected: str) -> str:
    return f"""\
name: slide
ground: g
end_effector: s
joints:
  - {{name: p, type: P, links: [g, s], axis: [1, 0, 0]}}
expected:
  dof: 1
{expected}"""


@pytest.mark.parametrize(
    "block, where",
    [
        ("  translations: [[0, 0, 0]]\n", ":8: expected.translations[0]: expected a non-zero direction, got [0, 0, 0]"),
        ("  translations:\n    - [1, 0, 0]\n    - [2, 0, 0]\n", ":10: expected.translations[1]: linearly dependent on the directions before it"),
        ("  translations: [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]]\n", ":8: expected.translations[3]: linearly dependent"),
        ("  translations: [[1, 0, 0], [1, 1e-12, 0]]\n", ":8: expected.translations[1]: linearly dependent"),  # round-off apart
    ],
)
def test_an_expected_translation_basis_that_is_not_a_basis_is_bad_input_naming_file_line_and_key(block, where, write_yaml, capsys):
    path = write_yaml(_slide_with(block))
    assert main(["check", str(path)]) == 2  # bad input, not a failed check (1)
    out = capsys.readouterr().out
    assert f"ERROR: {path}{where}" in out and "FAIL" not in out
    assert main(["analyze", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"mobility: {path}{where}")


def test_an_expected_translation_basis_is_checked_in_code_and_in_flexure_documents_too():
    with pytest.raises(MechanismError, match=r"^translations\[1\]: linearly dependent"):
        Expected(translations=((0, 0, 1), (0, 0, 2)))
    with pytest.raises(MechanismError, match=r"^translations\[0\]: expected a non-zero direction"):
        Expected(translations=((0, 0, 0),))
    assert Expected(translations=()).translations == ()  # no translation
    with pytest.raises(RequestError, match=r"^compare_translations: expected\[1\]: linearly dependent"):
        compare_translations(np.eye(3)[:1], [[1, 0, 0], [3, 0, 0]], mobility.Tolerance())
    flexure = ONE_WIRE + "expected: {translations: [[0, 0, 1], [0, 0, -1]]}\n"
    with pytest.raises(MechanismFileError, match=r"^w\.yaml:9: expected\.translations\[1\]: linearly dependent"):
        loads_flexure(flexure, file="w.yaml")


NOT_MOVING = """\
name: locked
ground: g
end_effector: s
joints:
  - {name: A, type: R, links: [g, s], axis: [1, 0, 0], point: [0, 0, 0]}
  - {name: B, type: R, links: [g, s], axis: [0, 1, 0], point: [0, 0, 0]}
"""


@pytest.mark.parametrize("written", ['""', "''", '"0"', "0"])
def test_the_pattern_of_a_mechanism_that_cannot_move_is_accepted_as_analyze_and_the_contract_write_it(written, write_yaml):
    assert mobility.analyze(mobility.loads(NOT_MOVING)).pattern == "0"
    result = check_file(write_yaml(NOT_MOVING + f"expected: {{dof: 0, pattern: {written}, mobility: 0}}\n"))
    assert result.status == "pass", result.message


def test_an_empty_pattern_is_compared_not_waved_through(write_yaml):
    text = _slide_with('  pattern: ""\n')
    result = check_file(write_yaml(text))
    assert result.status == "fail" and result.message == "pattern 1T (expected 0)"


def test_expected_pattern_accepts_every_pattern_analyze_can_report():
    reported = {pattern_of(t, r) for t in range(4) for r in range(4)}
    assert "0" in reported and "3T3R" in reported
    for pattern in reported:
        assert require_expected_pattern(pattern, "pattern") == pattern and EXPECTED_PATTERN.fullmatch(pattern)
    assert require_expected_pattern("", "pattern") == "0"
    with pytest.raises(MechanismError, match=r'also written ""'):
        require_expected_pattern("0T", "pattern")


def _format_page_blocks() -> list[str]:
    return re.findall(r"```yaml\n(.*?)```", FORMAT_PAGE.read_text(encoding="utf-8"), re.S)


def _completed(block: str) -> str:
    """``block`` with only the required top-level keys it lacks: a name, the first joint's first link as the ground, its second as end effector."""
    data = yaml.safe_load(block)
    joints = data.get("joints") or data["limbs"][0]["joints"]
    ground, end = joints[0]["links"]
    end = re.sub(r"\{[^}]*\}", "1", end)  # a limb's "{i+1}": its first copy
    head = "".join(f"{key}: {value}\n" for key, value in (("name", "doc"), ("ground", ground), ("end_effector", end)) if key not in data)
    return head + block


def test_every_yaml_example_of_the_format_page_loads_as_written():
    blocks = _format_page_blocks()
    assert len(blocks) >= 2 and any("limbs:" in b for b in blocks)
    for block in blocks:
        mechanism = mobility.loads(_completed(block))
        assert mechanism.joints, block
    limbs = mobility.loads(_completed(next(b for b in blocks if "limbs:" in b)))
    assert limbs.world_joints[1].point[2] == pytest.approx(0.5)  # h, defined by the example itself


def test_the_format_page_says_exactly_where_expressions_are_allowed():
    page = FORMAT_PAGE.read_text(encoding="utf-8")
    assert "Any number of the file" not in page  # the count of copies and the expected integers take none
    head = "name: e\nground: g\nend_effector: s\nparameters: {a: 2}\n"
    joint = "  - {name: p, type: P, links: [g, s], axis: [1, 0, 0]}\n"
    m = mobility.loads(head + "joints:\n" + joint + "expected: {translations: [[a, 0, 0]]}\n")
    assert m.expected is not None and m.expected.translations == ((2.0, 0.0, 0.0),)
    assert "components of\n`expected.translations`" in page
    with pytest.raises(MechanismFileError, match=r"expected\.dof: expected a non-negative integer"):
        mobility.loads(head + "joints:\n" + joint + "expected: {dof: 'a - 1'}\n")
    with pytest.raises(MechanismFileError, match=r"limbs\[0\]\.copies: expected a positive integer"):
        mobility.loads(head + "limbs:\n  - copies: 'a'\n    joints:\n  " + joint.replace("{name: p", "{name: 'p{i}'"))


@pytest.mark.parametrize(
    "text, where",
    [
        ("name: x\nground: g\nend_effector: e\n", "m.yaml:1: joints: missing required key (or limbs)"),
        ("name: x\nground: g\njoints: [{name: p, type: P, links: [g, s], axis: [1, 0, 0]}]\n", "m.yaml:1: end_effector: missing required key"),
        ("name: x\nground: g\nend_effector: s\njoints:\n  - {name: p, links: [g, s]}\n", "m.yaml:5: joints[0].type: missing required key of a joint"),
        ("name: x\nground: g\nend_effector: s\nlimbs:\n  - {copies: 2}\n", "m.yaml:5: limbs[0].joints: missing required key of a limb pattern"),
    ],
)
def test_a_missing_required_key_is_named_by_its_key_path(text, where):
    with pytest.raises(MechanismFileError) as info:
        mobility.loads(text, file="m.yaml")
    assert str(info.value) == where
    assert info.value.key == where.split(": ")[1]


def test_a_p_joint_takes_a_point_and_the_message_and_the_page_say_so():
    text = "name: x\nground: g\nend_effector: s\njoints:\n  - {name: p, type: P, links: [g, s], axis: [1, 0, 0], %s}\n"
    assert mobility.loads(text % "point: [0, 3, 0]").joints[0].point == (0.0, 3.0, 0.0)
    with pytest.raises(MechanismFileError, match=r"joints\[0\]\.normal: not a field of a joint of type P \(it takes axis, and optionally point\)"):
        mobility.loads(text % "normal: [0, 0, 1]")
    assert "(for `P`: `axis`, and optionally `point`)" in FORMAT_PAGE.read_text(encoding="utf-8")


def test_a_flexure_document_may_expect_no_motion_as_the_contract_writes_it():
    text = ONE_WIRE + 'expected: {pattern: ""}\n'
    doc = loads_flexure(text, file="w.yaml")
    assert doc.expected is not None and doc.expected.pattern == "0"
