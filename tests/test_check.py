"""`mobility check`: the library passes; mismatches, missing blocks and bad input give the right exit status."""

import dataclasses
import json
import os
import warnings

import pytest
from conftest import MECHANISMS

import mobility
from mobility.testing import check as check_module
from mobility.testing.check import COMPARATORS, check_file, check_mechanism, check_paths, mechanism_files
from mobility.testing.flexure_check import flexure_document
from mobility.cli import main
from mobility.errors import MechanismCheckFailed
from mobility.testing.pytest_plugin import assert_mechanism_passes, mechanism_test_cases, mechanism_tests

pytest_plugins = ["pytester"]

PLANAR = """\
name: planar 3-RRR
ground: base
end_effector: platform
joints:
  - {name: A1, type: R, links: [base, p1], axis: [0, 0, 1], point: [4, 0, 0]}
  - {name: B1, type: R, links: [p1, d1], axis: [0, 0, 1], point: [3, 2, 0]}
  - {name: C1, type: R, links: [d1, platform], axis: [0, 0, 1], point: [1, 0.3, 0]}
  - {name: A2, type: R, links: [base, p2], axis: [0, 0, 1], point: [-2, 3.5, 0]}
  - {name: B2, type: R, links: [p2, d2], axis: [0, 0, 1], point: [-3, 1, 0]}
  - {name: C2, type: R, links: [d2, platform], axis: [0, 0, 1], point: [-0.5, 0.8, 0]}
"""


def run(capsys, *args):
    status = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return status, out, err


@pytest.fixture(scope="module")
def library_report():
    return check_paths([MECHANISMS])


def test_every_library_file_passes(library_report):
    assert len(library_report.results) >= 25
    failing = [f"{r.path}: {r.status}: {r.message}" for r in library_report.results if not r.ok]
    assert failing == []
    assert library_report.exit_status == 0


def test_folders_are_expanded_recursively_and_sorted(tmp_path):
    (tmp_path / "b").mkdir()
    (tmp_path / "a" / "deep").mkdir(parents=True)
    for rel in ("b/z.yaml", "a/deep/y.yml", "a/x.yaml", "a/notes.txt", "a/W.YAML"):
        (tmp_path / rel).write_text(PLANAR)
    shown = [s for s, _, _ in mechanism_files([tmp_path])]
    assert shown == [str(tmp_path / p) for p in ("a/W.YAML", "a/deep/y.yml", "a/x.yaml", "b/z.yaml")]  # the suffix in any case


def test_cli_table_for_the_library(capsys):
    status, out, err = run(capsys, "check", MECHANISMS / "bennett.yaml", MECHANISMS / "3prs.yaml")
    assert status == 0 and err == ""
    lines = out.splitlines()
    assert lines[0].split() == ["file", "G-K", "M", "DOF", "pattern", "expected", "verdict"]
    row = next(line for line in lines if "bennett" in line).split()
    assert row[1:5] == ["-2", "1", "1", "1R"] and "pass" in row
    assert lines[-1] == "2 passed, 0 failed, 0 without expected block, 0 errors"


def test_a_mismatch_fails_with_exit_1(write_yaml, capsys):
    text = (MECHANISMS / "bennett.yaml").read_text().replace("  dof: 1\n", "  dof: 2\n")
    status, out, _ = run(capsys, "check", write_yaml(text, "bennett_wrong.yaml"))
    assert status == 1
    assert "FAIL: dof 1 (expected 2)" in out
    assert "0 passed, 1 failed" in out


def test_each_expected_key_is_compared(write_yaml):
    base = (MECHANISMS / "delta.yaml").read_text()
    for old, new in [
        ("pattern: 3T\n", "pattern: 2T1R\n"),
        ("mobility: 9\n", "mobility: 3\n"),
        ("idle_dof: 6\n", "idle_dof: 0\n"),
        ("gruebler_kutzbach: 9\n", "gruebler_kutzbach: 3\n"),
        ("redundant_constraints: 0\n", "redundant_constraints: 1\n"),
        ("translations: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n", "translations: [[1, 0, 0], [0, 1, 0]]\n"),
    ]:
        assert old in base
        result = check_file(write_yaml(base.replace(old, new)))
        assert result.status == "fail", old
        assert [c.key for c in result.mismatches] == [old.split(":")[0]]


def test_translations_are_compared_as_subspaces(write_yaml):
    def status(translations):
        return check_file(write_yaml(PLANAR + f"expected: {{dof: 3, translations: {translations}}}\n")).status

    assert status("[[1, 1, 0], [1, -1, 0]]") == "pass"  # another basis of the xy-plane
    assert status("[[0, 5, 0], [3, 0, 0]]") == "pass"  # any length, any order
    assert status("[[1, 0, 0], [0, 0, 1]]") == "fail"  # another plane
    assert status("[[1, 0, 0]]") == "fail"  # a line inside the plane is not the plane
    assert status("[]") == "fail"
    zero = check_file(write_yaml(PLANAR + "expected: {translations: [[0, 0, 0]]}\n"))
    assert zero.status == "error" and zero.message.endswith("expected.translations[0]: expected a non-zero direction, got [0, 0, 0]")  # bad input, not a failed check


def test_expected_translations_of_any_finite_size_are_directions(write_yaml):
    text = (MECHANISMS / "3prs.yaml").read_text()
    assert "translations: [[0, 0, 1]]" in text
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the norm of [0, 1e308, 1e308] squared overflowed (a numpy warning, then a wrong direction)
        assert check_file(write_yaml(text.replace("translations: [[0, 0, 1]]", "translations: [[0, -1.7e308, 1.7e308]]"))).message == (
            "translations: found the span of [[0, 0, 1]], expected the span of [[0, -1.7e+308, 1.7e+308]]")
        assert check_file(write_yaml(text.replace("translations: [[0, 0, 1]]", "translations: [[0, 0, 5e-324]]"))).ok
        dependent = check_file(write_yaml(text.replace("translations: [[0, 0, 1]]", "translations: [[0, 0, 1.7e308], [0, 0, 5e-324]]")))
        assert dependent.status == "error" and "expected.translations[1]: linearly dependent" in dependent.message  # not a basis


def test_no_translation_is_written_as_an_empty_list():
    assert check_file(MECHANISMS / "agile_eye.yaml").ok
    eye = mobility.load(MECHANISMS / "agile_eye.yaml")
    wrong = check_mechanism(eye.replace(expected=mobility.Expected(translations=((0.0, 0.0, 1.0),))))
    assert wrong.status == "fail"


def test_a_file_without_expected_block_is_not_a_pass(write_yaml, capsys):
    status, out, _ = run(capsys, "check", write_yaml(PLANAR))
    assert status == 1
    assert "no expected block" in out
    assert check_file(write_yaml(PLANAR)).status == "missing"


def test_bad_input_gives_exit_2_and_its_one_line_error(write_yaml, capsys):
    bad = write_yaml(PLANAR.replace("axis: [0, 0, 1], point: [4, 0, 0]", "axis: [0, 1], point: [4, 0, 0]"), "bad.yaml")
    wrong = write_yaml((MECHANISMS / "bennett.yaml").read_text().replace("  dof: 1\n", "  dof: 2\n"), "wrong.yaml")
    status, out, err = run(capsys, "check", bad, wrong, MECHANISMS / "sarrus.yaml")
    assert status == 2  # bad input wins over the mismatch
    assert f"ERROR: {bad}:5: joints[0].axis: expected a list of 3 numbers, got 2" in out
    assert "FAIL" in out and "1 passed, 1 failed, 0 without expected block, 1 error" in out
    assert err == "" and "Traceback" not in out


@pytest.mark.parametrize("make", [lambda tmp: tmp / "missing.yaml", lambda tmp: tmp])
def test_missing_paths_and_empty_folders_are_bad_input(tmp_path, capsys, make):
    status, out, _ = run(capsys, "check", make(tmp_path))
    assert status == 2
    assert "ERROR" in out


def test_an_internal_error_is_reported_per_file_with_exit_3(monkeypatch):
    def broken(*args, **kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(check_module, "analyze", broken)
    report = check_paths([MECHANISMS / "sarrus.yaml", MECHANISMS / "missing.yaml"])
    assert [r.status for r in report.results] == ["error", "error"]
    assert report.results[0].internal and "RuntimeError: boom" in report.results[0].message
    assert report.exit_status == 3


def test_a_key_without_comparator_is_never_a_silent_pass():
    m = mobility.load(MECHANISMS / "sarrus.yaml")
    result = check_mechanism(m.replace(expected=mobility.Expected(dof=1, extra={"stiffness": 3})))
    assert result.status == "fail"
    assert result.mismatches[0].key == "stiffness" and "no comparator" in result.message
    assert "stiffness" not in COMPARATORS


def test_finite_keys_are_compared(write_yaml):
    text = (MECHANISMS / "bennett.yaml").read_text()
    assert "finite_verdict: full-cycle" in text and check_file(MECHANISMS / "bennett.yaml").ok
    wrong = check_file(write_yaml(text.replace("finite_verdict: full-cycle", "finite_verdict: cannot-move").replace("full_cycle_dof: 1", "full_cycle_dof: 0")))
    assert [c.describe() for c in wrong.mismatches] == ["full_cycle_dof 1 (expected 0)", "finite_verdict full-cycle (expected cannot-move)"]


def test_json_output(write_yaml, capsys):
    wrong = write_yaml((MECHANISMS / "sarrus.yaml").read_text().replace("pattern: 1T\n", "pattern: 1R\n"), "w.yaml")
    status, out, _ = run(capsys, "check", MECHANISMS / "bennett.yaml", wrong, "--json")
    data = json.loads(out)
    assert status == data["exit_status"] == 1
    assert data["summary"] == {"pass": 1, "fail": 1, "missing": 0, "error": 0, "total": 2}
    first, second = data["results"]
    assert (first["status"], first["name"], first["found"]["dof"], first["found"]["gruebler_kutzbach"]) == ("pass", "Bennett 4R linkage", 1, -2)
    assert all(c["ok"] for c in first["comparisons"])
    bad = [c for c in second["comparisons"] if not c["ok"]]
    assert bad == [{"key": "pattern", "expected": "1R", "actual": "1T", "ok": False, "note": ""}]
    assert second["found"]["translations"] == [[0.0, 0.0, 1.0]]


def test_tolerance_option_is_validated(capsys):
    status, _, err = run(capsys, "check", MECHANISMS / "sarrus.yaml", "--tol", "0.5")
    assert status == 2 and "--tol" in err


# --- the same check in a user's pytest suite -------------------------------------------------


def test_mechanism_test_cases_one_per_file(tmp_path):
    (tmp_path / "m").mkdir()
    (tmp_path / "m" / "one.yaml").write_text(PLANAR)
    cases = mechanism_test_cases(tmp_path / "m", tmp_path / "nothing")
    assert [c.values[0] for c in cases] == [str(tmp_path / "m" / "one.yaml"), str(tmp_path / "nothing")]
    with pytest.raises(MechanismCheckFailed, match="no expected block"):
        assert_mechanism_passes(cases[0].values[0])
    with pytest.raises(MechanismCheckFailed, match="no such file or folder"):
        assert_mechanism_passes(cases[1].values[0])
    assert [r.name for r in assert_mechanism_passes(MECHANISMS / "bennett.yaml")] == ["Bennett 4R linkage"]


def _user_project(pytester):
    folder = pytester.mkdir("designs")
    for stem in ("bennett", "sarrus"):
        (folder / f"{stem}.yaml").write_text((MECHANISMS / f"{stem}.yaml").read_text())
    wrong = (MECHANISMS / "rssr.yaml").read_text().replace("  mobility: 2\n", "  mobility: 1\n")
    (folder / "rssr_wrong.yaml").write_text(wrong)
    return folder


def test_one_line_in_a_user_test_module(pytester):
    _user_project(pytester)
    pytester.makepyfile(test_designs="from mobility.testing.pytest_plugin import mechanism_tests\n\ntest_designs = mechanism_tests('designs')\n")
    result = pytester.runpytest_inprocess("-p", "no:cacheprovider", "test_designs.py")
    result.assert_outcomes(passed=2, failed=1)
    result.stdout.fnmatch_lines(["*test_designs?designs/rssr_wrong.yaml?*", "*mobility 2 (expected 1)*"])


def test_plugin_collects_mechanism_files_as_tests(pytester):
    _user_project(pytester)
    pytester.makepyfile(test_other="def test_other():\n    pass\n")
    result = pytester.runpytest_inprocess("-p", "no:cacheprovider", "--mobility-check", "designs", "test_other.py")
    result.assert_outcomes(passed=3, failed=1)
    result.stdout.fnmatch_lines(["*designs/rssr_wrong.yaml::check*"])


def test_plugin_is_inert_unless_configured(pytester):
    _user_project(pytester)
    result = pytester.runpytest_inprocess("-p", "no:cacheprovider", "designs")
    result.assert_outcomes()


def test_mechanism_tests_returns_a_parametrized_test():
    test = mechanism_tests(MECHANISMS / "bennett.yaml", MECHANISMS / "sarrus.yaml")
    marks = [m for m in test.pytestmark if m.name == "parametrize"]
    assert [p.id for p in marks[0].args[1]] == [str(MECHANISMS / "bennett.yaml"), str(MECHANISMS / "sarrus.yaml")]
    test(str(MECHANISMS / "bennett.yaml"))  # passes silently


def test_full_cycle_expectations_are_held_to_the_finite_limit(tmp_path, monkeypatch, capsys):
    # a chain of 6 revolute joints expecting a full-cycle DOF: above a limit of 5 joints the check is an error
    # line, and the other files of the folder are still checked.  Stretched in a line, the planar chain's end
    # link has 2 DOF (1T1R); every bent pose of its one branch has 3 (2T1R), its full-cycle DOF.
    joints = "\n".join(f"  - {{name: R{i}, type: R, links: [l{i}, l{i + 1}], axis: [0, 0, 1], point: [{i}, 0, 0]}}" for i in range(6))
    (tmp_path / "chain.yaml").write_text(f"name: chain\nground: l0\nend_effector: l6\njoints:\n{joints}\nexpected: {{dof: 2, full_cycle_dof: 3}}\n")
    (tmp_path / "slide.yaml").write_text("name: slide\nground: g\nend_effector: s\njoints:\n  - {name: P, type: P, links: [g, s], axis: [1, 0, 0]}\nexpected: {dof: 1}\n")
    monkeypatch.setenv("MOBILITY_MAX_FINITE_JOINTS", "5")
    assert main(["check", str(tmp_path)]) == 2
    out = capsys.readouterr().out
    assert "6 joints are more than the limit of 5 for the full-cycle expectations" in out and "MOBILITY_MAX_FINITE_JOINTS" in out
    assert "slide" in out
    monkeypatch.setenv("MOBILITY_MAX_FINITE_JOINTS", "6")
    assert main(["check", str(tmp_path)]) == 0


# --- hostile names and paths --------------------------------------------------------------------


def test_a_file_name_that_is_not_utf8_is_shown_escaped_in_valid_json_and_table(tmp_path, capsys):
    folder = tmp_path / "sub"
    folder.mkdir()
    (folder / os.fsdecode(b"bad\xff\xfename.yaml")).write_text((MECHANISMS / "four_bar.yaml").read_text())
    (folder / os.fsdecode(b"broken\xff.yaml")).write_text("name: x\n")
    status, out, _ = run(capsys, "check", "--json", folder)
    data = json.loads(out.encode("utf-8").decode("utf-8"))  # was lone surrogates: not UTF-8, so not JSON on the wire
    assert status == 2 and [r["path"] for r in data["results"]] == [str(folder / "bad\\xff\\xfename.yaml"), str(folder / "broken\\xff.yaml")]
    assert data["results"][0]["status"] == "pass"
    assert data["results"][1]["message"].startswith(f"{folder}/broken\\xff.yaml:1: ")
    status, out, _ = run(capsys, "check", folder)
    out.encode("utf-8")  # no surrogate reaches the table either
    assert "sub/bad\\xff\\xfename.yaml" in out and "ERROR: " + str(folder / "broken\\xff.yaml:1:") in out


def test_a_symlink_loop_is_named_as_one_not_as_missing(tmp_path):
    loop, other = tmp_path / "loop.yaml", tmp_path / "other.yaml"
    loop.symlink_to(other.name)
    other.symlink_to(loop.name)
    given = check_paths([loop]).results[0]  # given by name: was "no such file or folder"
    assert given.message == f"{loop}: is a symbolic link loop (too many levels of symbolic links), expected a mechanism file or folder"
    found = check_paths([tmp_path]).results  # found in a folder, both ends of the loop
    assert [r.message for r in found] == [f"{p}: is a symbolic link loop (too many levels of symbolic links), expected a mechanism file" for p in (loop, other)]


# --- other kinds of document ---------------------------------------------------------------------

EXAMPLES = MECHANISMS.parent / "examples"


def test_the_projects_own_examples_pass(capsys):
    status, out, err = run(capsys, "check", "--json", EXAMPLES)
    data = json.loads(out)
    assert (status, err) == (0, "") and data["summary"]["pass"] == data["summary"]["total"] >= 1  # was 1: "without expected block"
    flexure = next(r for r in data["results"] if r["path"].endswith("three_rod.yaml"))
    assert (flexure["kind"], flexure["status"], flexure["name"]) == ("flexure", "pass", "three-rod spherical flexure (actuation example)")
    assert flexure["found"] == {"dof": 3, "pattern": "3R", "constraints": 3, "translations": [], "actuation": "valid"}
    assert [c["key"] for c in flexure["comparisons"]] == ["dof", "pattern", "translations", "actuation"]
    assert all(r["kind"] == "mechanism" for r in json.loads(run(capsys, "check", "--json", MECHANISMS / "bennett.yaml")[1])["results"])


THREE_ROD = (EXAMPLES / "flexure" / "three_rod.yaml").read_text()


def flexure_with(tmp_path, name, expected):
    """The three-rod flexure with another expected block (its last line)."""
    lines = THREE_ROD.rstrip("\n").split("\n")
    assert lines[-1].startswith("expected:")
    path = tmp_path / name
    path.write_text("\n".join(lines[:-1] + [f"expected: {expected}"]) + "\n")
    return path


def test_a_flexure_document_is_read_by_the_flexure_reader(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text(THREE_ROD.replace("material: aluminium}", "material: steel}", 1))
    unknown = flexure_with(tmp_path, "unknown.yaml", "{dof: 3, mobility: 3}")  # a mechanism's key, not a flexure's
    wrong = flexure_with(tmp_path, "wrong.yaml", "{pattern: 4R}")
    status, out, _ = run(capsys, "check", "--json", bad, unknown, wrong)
    first, second, third = json.loads(out)["results"]
    assert status == 2
    assert first["message"].startswith(f"{bad}:39: elements[0].material: unknown material 'steel'")
    assert second["message"] == f"{unknown}:67: expected.mobility: unknown key in the expected block; expected one of: dof, pattern, translations, actuation"
    assert third["message"].startswith(f'{wrong}:67: expected.pattern: expected a pattern such as "3T"')


def test_a_flexure_mismatch_fails_and_says_what_was_found(tmp_path, capsys):
    path = flexure_with(tmp_path, "f.yaml", "{dof: 2, pattern: 3R, translations: [[0, 0, 1]], actuation: redundant}")
    status, out, _ = run(capsys, "check", path)
    assert status == 1
    row = next(line for line in out.splitlines() if line.startswith(str(path)))
    assert row.split()[1:3] == ["3", "3R"]  # the found DOF and pattern in the table
    assert row.endswith("FAIL: dof 3 (expected 2); translations: found the span of [], expected the span of [[0, 0, 1]]; actuation valid (expected redundant)")


def test_a_flexure_actuation_key_needs_marked_actuators(tmp_path):
    unmarked = tmp_path / "unmarked.yaml"
    unmarked.write_text(THREE_ROD.replace(", actuated: true}", "}"))
    result = check_file(unmarked, others=(flexure_document,))
    assert (result.status, result.message) == ("fail", "actuation: no input is marked actuated (actuated: true), so there is no verdict to compare")
    # other actuators marked: the verdict of those (the vertical lines v1..v3 cannot control the rotations about horizontal axes)
    vertical = tmp_path / "vertical.yaml"
    vertical.write_text(THREE_ROD.replace(", actuated: true}", "}").replace("direction: [0, 0, 1]}", "direction: [0, 0, 1], actuated: true}"))
    assert check_file(vertical, others=(flexure_document,)).message == "actuation actuation-singular (expected valid)"


def test_a_flexure_document_is_parsed_once(monkeypatch):
    calls = []
    real = check_module.parse_yaml
    monkeypatch.setattr(check_module, "parse_yaml", lambda *a, **k: calls.append(a[1]) or real(*a, **k))
    result = check_file(EXAMPLES / "flexure" / "three_rod.yaml", others=(flexure_document,))
    assert result.status == "pass" and len(calls) == 1  # was 3: read as a mechanism, then as YAML, then as a flexure


def test_without_the_flexure_check_a_flexure_document_is_a_mechanism_error():
    result = check_file(EXAMPLES / "flexure" / "three_rod.yaml")
    assert result.status == "error" and ":38: elements: a flexure document, not a mechanism: read it with mobility.load_flexure" in result.message


def test_the_pytest_helpers_check_flexure_documents_too(tmp_path):
    (passed,) = assert_mechanism_passes(EXAMPLES / "flexure")
    assert passed.kind == "flexure"
    with pytest.raises(MechanismCheckFailed, match=r"disagrees with its expected block:\n  dof 3 \(expected 4\)"):
        assert_mechanism_passes(flexure_with(tmp_path, "f.yaml", "{dof: 4}"))


# --- the actuation key ---------------------------------------------------------------------------


def test_the_actuation_key_compares_the_verdict_of_the_marked_joints(write_yaml):
    text = (MECHANISMS / "actuation_3rps.yaml").read_text()
    assert "actuation: valid" in text
    assert check_file(write_yaml(text)).ok
    result = check_file(write_yaml(text.replace("actuation: valid", "actuation: redundant")))
    assert result.message == "actuation valid (expected redundant)"
    m = mobility.load(MECHANISMS / "actuation_3rps.yaml")
    two = m.replace(joints=tuple(dataclasses.replace(j, actuated=j.name in ("P1", "P2")) for j in m.joints))
    assert check_mechanism(two).message == "actuation actuation-singular (expected valid)"
    none = text.replace("actuated: true", "actuated: false")
    assert check_file(write_yaml(none)).message == "actuation: no input is marked actuated (actuated: true), so there is no verdict to compare"


def test_the_actuation_key_is_validated_at_its_line(write_yaml, capsys):
    text = (MECHANISMS / "actuation_3rps.yaml").read_text()
    path = write_yaml(text.replace("actuation: valid", "actuation: fine"))
    line = next(k for k, row in enumerate(text.split("\n"), 1) if "actuation: valid" in row)
    status, out, _ = run(capsys, "check", path)
    assert status == 2 and f"{path}:{line}: expected.actuation: expected one of valid, redundant, actuation-singular, got 'fine'" in out


def test_the_file_formats_verdict_words_are_the_actuation_verdicts():
    from mobility.actuation import VERDICTS
    from mobility.io.expected import ACTUATION_VERDICTS

    assert ACTUATION_VERDICTS == VERDICTS


def test_the_library_pins_the_verdict_of_every_file_that_marks_actuated_joints(library_report):
    pinned = {r.path for r in library_report.results if any(c.key == "actuation" for c in r.comparisons)}
    marked = {str(p) for p in MECHANISMS.glob("*.yaml") if any(j.actuated for j in mobility.load(p).joints)}
    assert pinned == marked - {str(MECHANISMS / "3crr.yaml")}  # 3crr: see its expected block
    verdicts = {c.expected for r in library_report.results for c in r.comparisons if c.key == "actuation"}
    assert verdicts == {"valid", "redundant", "actuation-singular"}


@pytest.mark.parametrize("path, expected", [
    (None, r"^check_file: expected a file name \(str or Path\), got NoneType$"),
    (3, r"^check_file: expected a file name \(str or Path\), got int$"),
    (b"four_bar.yaml", r"^check_file: expected a file name \(str or Path\), got bytes$"),
    ("a\x00b.yaml", r"^check_file: expected a file name without a NUL character, got 'a\\x00b\.yaml'$"),
])
def test_check_file_refuses_what_is_not_a_file_name(path, expected):
    with pytest.raises(mobility.errors.RequestError, match=expected):
        check_file(path)


@pytest.mark.parametrize("paths, expected", [
    (None, r"^check_paths: expected a list of file or folder names, got NoneType$"),
    (3, r"^check_paths: expected a list of file or folder names, got int$"),
    (str(MECHANISMS), r"^check_paths: expected a list of file or folder names, got str \(one name is written \[name\]\)$"),
    ([str(MECHANISMS), 3], r"^check_paths: paths\[1\]: expected a file name \(str or Path\), got int$"),
    ([None], r"^check_paths: paths\[0\]: expected a file name \(str or Path\), got NoneType$"),
])
def test_check_paths_refuses_what_is_not_a_list_of_names(paths, expected):
    with pytest.raises(mobility.errors.RequestError, match=expected):
        check_paths(paths)
