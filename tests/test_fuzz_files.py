"""Fuzzing the files: any generated or mutated document ends in a result with finite numbers, or in one line and exit 2, within a time bound.

Where a new test goes: a test that draws input *files* at random (hypothesis strategies: mutations of the
bundled files, generated mechanisms, extreme numbers put in them, flexure documents) and runs them through
the library and the command line goes here; each example runs under :func:`guards.time_bound` and must end
in a result whose numbers pass :func:`guards.finite_numbers`, or in one ``MobilityError`` of one line (exit
2, one line ``mobility: ...``).  A bad input found by these tests becomes a case of the corpus of
``test_bad_files.py`` (a refusal) or a test of ``test_extreme_numbers.py`` (an answer).

The mutations: type changes, deletions, duplications, deep nesting, aliases, alias bombs, control bytes,
cuts, a value swapped for a list or a mapping.
"""

from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mobility
from mobility.errors import MobilityError
from mobility.flexure import check_force_lines, flexure_spaces, loads_flexure

from conftest import MECHANISMS
from guards import finite_numbers, refused, run_cli, time_bound

TEXTS = {p.name: p.read_text(encoding="utf-8") for p in sorted(MECHANISMS.glob("*.yaml"))}
FLEXURE_TEXTS = {p.name: p.read_text(encoding="utf-8") for p in sorted((MECHANISMS.parent / "examples" / "flexure").glob("*.yaml"))}


# -- 1. mutations of the bundled files, and generated mechanisms --------------------------------------------


ODD_VALUES = [
    None, True, False, "", " ", "x", "1/0", "(-8)**(1/3)", "(-1)**0.5", "9e999", "exp(1000)", "nan", "inf", ".nan",
    10**400, -1, 0, 2**63, -(2**63), 1.5, [], {}, [[]], [None, None, None], {"a": None}, "pi", "R", "S", "world", "g",
    "__import__('os')", "{i+1}", "P{i", "sqrt(-1)", "a" * 300, "+".join(["1"] * 200), [0, 0, 0], [1, 2], [1, 2, 3, 4],
    ["x", "y", "z"], {"name": "A"}, "\u00e9\u4e2d", "0x10", "1e400",
]


def key_paths(data: Any) -> list[tuple]:
    """Every path of a parsed document (iteratively)."""
    out, stack = [], [((), data)]
    while stack:
        path, value = stack.pop()
        out.append(path)
        if isinstance(value, dict):
            stack.extend((path + (k,), v) for k, v in value.items())
        elif isinstance(value, list):
            stack.extend((path + (i,), v) for i, v in enumerate(value))
    return out


def parent_and_key(doc: Any, path: tuple) -> tuple[Any, Any]:
    parent = doc
    for part in path[:-1]:
        parent = parent[part]
    return parent, path[-1]


@st.composite
def mutated_files(draw: st.DrawFn, texts: dict[str, str] = TEXTS) -> str:
    name = draw(st.sampled_from(sorted(texts)))
    text = texts[name]
    kind = draw(st.sampled_from(["replace", "delete", "duplicate", "nest", "alias", "bomb", "control", "cut", "swap"]))
    if kind in ("control", "cut"):
        at = draw(st.integers(0, len(text)))
        if kind == "cut":
            return text[:at]
        char = draw(st.sampled_from([chr(c) for c in (*range(0, 9), 11, 12, *range(14, 32), 127, 0xFFFE)]))
        return text[:at] + char + text[at:]
    doc = yaml.safe_load(text)
    paths = [p for p in key_paths(doc) if p]
    path = draw(st.sampled_from(paths))
    parent, key = parent_and_key(doc, path)
    if kind == "replace":
        parent[key] = copy.deepcopy(draw(st.sampled_from(ODD_VALUES)))
    elif kind == "delete":
        del parent[key]
    elif kind == "duplicate":
        if isinstance(parent, list):
            parent.insert(key, copy.deepcopy(parent[key]))
        elif len(path) == 1:  # the same top-level key twice
            return yaml.safe_dump(doc, sort_keys=False) + yaml.safe_dump({key: parent[key]})
        else:
            parent[f"{key}2"] = copy.deepcopy(parent[key])
    elif kind == "nest":
        value = parent[key]
        for _ in range(draw(st.integers(1, 200))):
            value = [value]
        parent[key] = value
    elif kind == "alias":  # another node's value, shared: the dump writes an anchor and an alias
        other = draw(st.sampled_from(paths))
        other_parent, other_key = parent_and_key(doc, other)
        if other[: len(path)] != path and path[: len(other)] != other:
            parent[key] = other_parent[other_key]
    elif kind == "bomb":
        bomb: Any = ["lol"] * 10
        for _ in range(draw(st.integers(1, 9))):
            bomb = [bomb] * 10
        parent[key] = bomb
    elif kind == "swap" and isinstance(parent, dict):
        parent[key] = {"list": [parent[key]], "mapping": {"x": parent[key]}}[draw(st.sampled_from(["list", "mapping"]))]
    return yaml.safe_dump(doc, sort_keys=False, allow_unicode=True)


@st.composite
def generated_mechanisms(draw: st.DrawFn) -> str:
    links = ["g", "e"] + [f"l{i}" for i in range(draw(st.integers(0, 4)))]
    coordinate = st.one_of(st.integers(-3, 3), st.sampled_from([0.5, -1.25, 2.5]))
    vector = st.lists(coordinate, min_size=3, max_size=3)
    joints = []
    for k in range(draw(st.integers(1, 7))):
        kind = draw(st.sampled_from("RPHCUSE"))
        joint: dict[str, Any] = {"name": f"J{k}", "type": kind, "links": draw(st.lists(st.sampled_from(links), min_size=2, max_size=2, unique=True))}
        if kind in "RPHC":
            joint["axis"] = draw(vector)
        if kind in "RHCUS":
            joint["point"] = draw(vector)
        if kind == "H":
            joint["pitch"] = draw(coordinate)
        if kind == "U":
            joint["axes"] = [draw(vector), draw(vector)]
        if kind == "E":
            joint["normal"] = draw(vector)
        joints.append(joint)
    return yaml.safe_dump({"name": "fuzz", "ground": "g", "end_effector": "e", "joints": joints}, sort_keys=False)


@pytest.fixture(scope="module")
def fuzz_file(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("fuzz") / "fuzz.yaml"


def ends_in_result_or_one_error(text: str, path: Path) -> None:
    """Load and analyse ``text`` in-process, by the library and by the command line, each under a time bound."""
    with time_bound(20):
        try:
            result = mobility.analyze(mobility.loads(text, file="fuzz.yaml"))
        except MobilityError as exc:
            assert "\n" not in str(exc), str(exc)
            library_ok = False
        else:
            assert finite_numbers(result.to_dict()), result.to_dict()
            library_ok = True
        path.write_bytes(text.encode("utf-8", "surrogatepass"))
        done = run_cli("analyze", "--json", path)
    assert done.returncode == (0 if library_ok else 2), (done.returncode, done.stderr)
    if done.returncode == 2:
        refused(done)
    else:
        assert finite_numbers(json.loads(done.stdout))


FUZZ = settings(max_examples=120, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


@FUZZ
@given(mutated_files())
def test_fuzz_mutated_bundled_files_end_in_result_or_one_error(fuzz_file, text):
    ends_in_result_or_one_error(text, fuzz_file)


@FUZZ
@given(generated_mechanisms())
def test_fuzz_generated_mechanisms_end_in_result_or_one_error(fuzz_file, text):
    ends_in_result_or_one_error(text, fuzz_file)


# -- 2. extreme numbers put in the bundled files ---------------------------------------------------------------


def scaled_document(doc: Any, factor: float) -> Any:
    """The numbers of a document times ``factor``, directions, angles and counts kept (expressions untouched)."""
    if isinstance(doc, dict):
        keep = ("expected", "copies", "units", "axis", "axes", "normal", "rpy", "angle")
        return {k: v if k in keep else scaled_document(v, factor) for k, v in doc.items()}
    if isinstance(doc, list):
        return [scaled_document(v, factor) for v in doc]
    if isinstance(doc, (int, float)) and not isinstance(doc, bool):
        return doc * factor
    return doc


@st.composite
def extreme_files(draw: st.DrawFn, texts: dict[str, str] = TEXTS) -> str:
    doc = yaml.safe_load(texts[draw(st.sampled_from(sorted(texts)))])
    if draw(st.booleans()):
        doc = scaled_document(doc, draw(st.sampled_from([1e-300, 1e-200, 1e-100, 1e100, 1e200, 1e300])))
    else:
        paths = [p for p in key_paths(doc) if p and isinstance(parent_and_key(doc, p)[0][p[-1]], (int, float))]
        if paths:
            parent, key = parent_and_key(doc, draw(st.sampled_from(paths)))
            parent[key] = draw(st.sampled_from([1.7976931348623157e308, -1.7976931348623157e308, 5e-324, 2.2250738585072014e-308, 1e155]))
    return yaml.safe_dump(doc, sort_keys=False)


@FUZZ
@given(extreme_files())
def test_fuzz_extreme_numbers_end_in_result_or_one_error(fuzz_file, text):
    ends_in_result_or_one_error(text, fuzz_file)


# -- 3. flexure documents: the same mutations and extreme numbers ----------------------------------------------


def flexure_ends_in_result_or_one_error(text: str, path: Path) -> None:
    """Read a flexure document in-process (spaces and actuation), then ``mobility actuation`` and ``mobility check`` on it."""
    with time_bound(20):
        try:
            flexure = loads_flexure(text, file="fuzz.yaml")
            spaces, check = flexure_spaces(flexure), check_force_lines(flexure)
        except MobilityError as exc:
            assert "\n" not in str(exc), str(exc)
            library_ok = False
        else:
            assert finite_numbers(spaces.to_dict()) and finite_numbers(check.to_dict())
            library_ok = True
        path.write_bytes(text.encode("utf-8", "surrogatepass"))
        done = run_cli("actuation", "--json", path)
        checked = run_cli("check", "--json", path)
    if library_ok:
        assert done.returncode in (0, 1) and finite_numbers(json.loads(done.stdout)), (done.returncode, done.stderr)
        assert checked.returncode in (0, 1), checked.stderr  # pass, or a mismatch of a mutated expected block
    else:
        refused(done)
        assert checked.returncode == 2


@FUZZ
@given(st.one_of(mutated_files(FLEXURE_TEXTS), extreme_files(FLEXURE_TEXTS)))
def test_fuzz_flexure_documents_end_in_result_or_one_error(fuzz_file, text):
    flexure_ends_in_result_or_one_error(text, fuzz_file)
