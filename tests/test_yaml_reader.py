"""The YAML reader and the expression evaluator, against independent routes: PyYAML for values and lines, Python for arithmetic.

Where a new test goes: a test of how a *valid* document or expression is read -- its values and the line
of every key, compared with PyYAML's loader and its pure-Python composer, or an expression's value
compared with Python's own float arithmetic -- goes here.  An expression or a document that must be
refused goes in the corpus of ``test_bad_files.py``; the loader's building of a mechanism from what is read
in ``test_loader.py``.  (The evaluator raises a plain ``ValueError`` of one line; the loader turns it into
a ``MechanismFileError`` naming the file, line and key.)
"""

from __future__ import annotations

import json
import math

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from mobility.io.expressions import evaluate
from mobility.io.yaml_source import parse_yaml

from conftest import MECHANISMS

TEXTS = {p.name: p.read_text(encoding="utf-8") for p in sorted(MECHANISMS.glob("*.yaml"))}


# -- 1. the YAML reader against PyYAML: the same values, the same lines -----------------------------------


def composer_lines(text: str) -> dict[tuple, int]:
    """Lines of every key path by PyYAML's pure-Python composer (the route the reader used before)."""
    lines: dict[tuple, int] = {}
    stack = [(yaml.compose(text, Loader=yaml.SafeLoader), ())]
    while stack:
        node, path = stack.pop()
        lines.setdefault(path, node.start_mark.line + 1)
        if isinstance(node, yaml.MappingNode):
            for key_node, value_node in node.value:
                lines[path + (key_node.value,)] = key_node.start_mark.line + 1
                stack.append((value_node, path + (key_node.value,)))
        elif isinstance(node, yaml.SequenceNode):
            stack.extend((item, path + (i,)) for i, item in enumerate(node.value))
    return lines


@pytest.mark.parametrize("name", sorted(TEXTS))
def test_bundled_files_read_as_pyyaml_reads_them_with_the_same_lines(name):
    data, positions = parse_yaml(TEXTS[name], name)
    assert data == yaml.load(TEXTS[name], Loader=yaml.SafeLoader)
    assert positions.lines == composer_lines(TEXTS[name])


scalars = st.one_of(
    st.none(), st.booleans(), st.integers(-10**6, 10**6), st.floats(allow_nan=False, allow_infinity=False, width=32),
    st.text(st.characters(codec="utf-8", exclude_categories=("Cs", "Cc")), max_size=8),
    st.sampled_from(["yes", "no", "on", "off", "~", "0x1f", "0o17", "1_000", "1:30", "2001-12-14", ".inf", "-.nan", "1e3", "=", "<<x"]),
)


documents = st.recursive(scalars, lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text("abcxyz_", min_size=1, max_size=4), inner, max_size=4), max_leaves=25)


@settings(max_examples=150, deadline=None, derandomize=True)
@given(documents, st.booleans())
def test_any_plain_document_reads_as_pyyaml_reads_it(doc, flow):
    text = yaml.safe_dump({"root": doc}, default_flow_style=flow, allow_unicode=True)
    data, positions = parse_yaml(text)
    expected = yaml.load(text, Loader=yaml.SafeLoader)
    assert json.dumps(data, sort_keys=True, default=str) == json.dumps(expected, sort_keys=True, default=str)
    assert positions.lines == composer_lines(text)


def test_numbers_read_alike_in_yaml_11_and_12_are_accepted():
    data, _ = parse_yaml("a: [07, 00, -0, 0x1f, 1_000, 12, '010', 1.5]\n")
    assert data["a"] == [7, 0, 0, 31, 1000, 12, "010", 1.5]


def test_aliases_share_values_as_pyyaml_does():
    text = "a: &p [1, 2, 3]\nb: *p\nc: {k: *p, &s name: x}\nd: *s\n"
    data, positions = parse_yaml(text)
    assert data == yaml.safe_load(text)
    assert data["b"] is data["a"] and positions.line(("b", 1)) == 2 and positions.line(("c", "k")) == 3


# -- 2. expressions against Python's arithmetic ---------------------------------------------------------------


leaves = st.one_of(st.integers(-20, 20).map(lambda n: f"{n}.0"), st.sampled_from(["0.5", "2.5", "a", "b", "pi"]))


expressions = st.recursive(
    leaves,
    lambda inner: st.one_of(
        st.tuples(inner, st.sampled_from(["+", "-", "*", "/", "**", "%"]), inner).map(lambda t: f"({t[0]} {t[1]} {t[2]})"),
        inner.map(lambda x: f"-{x}"),
        st.tuples(st.sampled_from(["sqrt", "exp", "log", "sin", "atan"]), inner).map(lambda t: f"{t[0]}({t[1]})"),
    ),
    max_leaves=12,
)


@settings(max_examples=300, deadline=None, derandomize=True)
@given(expressions)
def test_expressions_agree_with_python_or_fail_in_one_line(text):
    names = {"a": 3.0, "b": -1.5}
    scope = {"a": 3.0, "b": -1.5, "pi": math.pi, "sqrt": math.sqrt, "exp": math.exp, "log": math.log, "sin": math.sin, "atan": math.atan}
    try:  # the second route: Python's own float arithmetic on the same text
        expected = eval(text, {"__builtins__": {}}, scope)  # noqa: S307 - numbers, names and calls of the scope only
        python_ok = isinstance(expected, float) and math.isfinite(expected)
    except (ArithmeticError, ValueError, TypeError):
        python_ok = False
    if python_ok:
        try:
            value = evaluate(text, names)
        except ValueError as exc:  # only where Python went through an infinite value, or a zero that is an underflow, and back
            assert "not finite" in str(exc) or "underflows" in str(exc), str(exc)
        else:
            assert value == expected
    else:
        with pytest.raises(ValueError) as info:
            evaluate(text, names)
        assert "\n" not in str(info.value)


def test_functions_of_no_argument_are_evaluated():
    assert evaluate("hypot() + 1", {}) == 1.0 and evaluate("hypot()", {}) == 0.0
    with pytest.raises(ValueError, match="max expected at least 1 argument"):
        evaluate("max()", {})


@pytest.mark.parametrize("text", ["(300e-200)**2", "1e-200 * 1e-200", "1e-300 / 1e10", "exp(-1000)", "-exp(-exp(7.0))"])
def test_an_expression_that_underflows_is_an_error(text):
    with pytest.raises(ValueError, match="underflows: (an exp|a product, quotient or power) of its numbers") as info:
        evaluate(text, {})
    assert ("larger unit" in str(info.value)) == ("exp" not in text)  # a unit cannot lift an exp
    assert evaluate("x - x", {"x": 1e-300}) == 0.0 and evaluate("0 * 5", {}) == 0.0 and evaluate("1e-200 * 2", {}) == 2e-200
