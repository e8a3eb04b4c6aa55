"""API inputs, second audit: a wrong argument is a one-line RequestError naming the function and the argument.

Each test failed before its fix (an AttributeError, a TypeError from numpy or
matplotlib, a silent wrong answer, or a call that did not end).
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mobility
from mobility.core.loop_closure import loop_closure
from mobility.core.poses import MAX_STEP, sample_poses, step_value
from mobility.errors import RequestError
from mobility.finite.parameters import MAX_RANDOMS
from mobility.report.markdown import markdown_report
from mobility.report.plotting import plot_graph, plot_mechanism, save_figure
from mobility.report.plotting.backend import DPI_RANGE
from mobility.synthesis import named_pattern

from conftest import MECHANISMS


@pytest.fixture(scope="module")
def four_bar():
    return mobility.load(MECHANISMS / "four_bar.yaml")


@pytest.fixture(scope="module")
def four_bar_result(four_bar):
    return mobility.analyze(four_bar)


@pytest.fixture(scope="module")
def four_bar_sweep(four_bar):
    return mobility.sweep(four_bar, ["A=0:20:3"])


def refused(call, function, argument):
    """Run ``call``: it must raise a RequestError of one line naming ``function`` and ``argument``; return the message."""
    with pytest.raises(RequestError) as info:
        call()
    message = str(info.value)
    assert "\n" not in message and len(message) < 300, message
    assert function in message and argument in message, message
    return message


def _generator():
    yield "3R"


NOT_A_PATTERN = [None, b"3R", 3, 3.5, ["3R"], Path("3R"), "mechanism", "generator"]


def _value(bad, four_bar):
    """The bad value named by ``bad`` (fixtures and generators are made per test)."""
    return {"mechanism": four_bar, "generator": _generator()}.get(bad, bad) if isinstance(bad, str) else bad


# 1. synthesize, named_pattern and poses_view check what they are given


@pytest.mark.parametrize("bad", NOT_A_PATTERN, ids=repr)
def test_synthesize_refuses_what_is_not_a_pattern(bad, four_bar):
    refused(lambda: mobility.synthesize(_value(bad, four_bar)), "synthesize", "pattern")  # was AttributeError: no attribute 'factors'


@pytest.mark.parametrize("bad", NOT_A_PATTERN, ids=repr)
def test_named_pattern_refuses_what_is_not_a_name(bad, four_bar):
    message = refused(lambda: named_pattern(_value(bad, four_bar)), "named_pattern", "name")
    assert "2T3R, 3T, 3R, 2T1R, 3T1R" in message


@pytest.mark.parametrize("bad", [5, "ab", [None, None]], ids=repr)
def test_named_pattern_refuses_directions_that_are_not_directions(bad):
    refused(lambda: named_pattern("2T3R", directions=bad), "named_pattern", "directions")  # 5 was TypeError: not iterable


def test_named_pattern_reads_a_bounded_part_of_endless_directions():
    with pytest.raises(mobility.SynthesisError, match="the 2T3R pattern takes 2 directions, got 16 or more"):
        named_pattern("2T3R", directions=itertools.repeat((1, 0, 0)))


@pytest.mark.parametrize("key, bad", [("joints", 2.5), ("joints", "3"), ("samples", None), ("verify_samples", -1), ("generic_points", True), ("seed", None)], ids=repr)
def test_synthesize_checks_its_counts_and_seed(key, bad):
    refused(lambda: mobility.synthesize("2T1R", **{key: bad}), "synthesize", key)


@pytest.mark.parametrize("bad", [None, 5, Path("poses"), "mechanism"], ids=repr)
def test_poses_view_refuses_what_is_not_a_sequence_of_frames(bad, four_bar):
    refused(lambda: mobility.poses_view(_value(bad, four_bar)), "poses_view", "frames")  # was TypeError: not iterable


def test_poses_view_reads_a_bounded_part_of_endless_frames(four_bar, four_bar_result):
    with pytest.raises(RequestError, match=r"^3 or more poses is more than a view holds \(max_poses=2\)"):
        mobility.poses_view(itertools.repeat((four_bar, four_bar_result)), max_poses=2)


@pytest.mark.parametrize("bad", ["one note", None, [1]], ids=repr)
def test_poses_view_wants_notes_as_a_list_of_strings(bad, four_bar, four_bar_result):
    refused(lambda: mobility.poses_view([(four_bar, four_bar_result)], notes=bad), "poses_view", "notes")  # a string was a note per character


# 2. finite_mobility: seed, steps and randoms


@pytest.mark.parametrize("seed", [b"abc", -1, 3.5, "A", math.nan, [None], None, True], ids=repr)
def test_finite_mobility_wants_a_non_negative_integer_seed(four_bar, seed):
    refused(lambda: mobility.finite_mobility(four_bar, seed=seed), "finite_mobility", "seed")  # None drew fresh randomness


@pytest.mark.parametrize("seed", [None, -1, 2.0])
def test_sample_poses_refuses_the_same_seeds_as_finite_mobility(four_bar, seed):
    with pytest.raises(RequestError, match="seed: expected a non-negative integer"):
        sample_poses(four_bar, 1, seed=seed)


@pytest.mark.parametrize("steps", [b"abc", b"\x01", "abc", [1e300], [2.0], 0.01, [0.01] * 11, itertools.repeat(0.01), [None], np.eye(2)], ids=repr)
def test_finite_mobility_wants_one_to_ten_steps_in_range(four_bar, steps):
    message = refused(lambda: mobility.finite_mobility(four_bar, steps=steps), "finite_mobility", "steps")  # b'abc' was steps 97, 98, 99
    assert "tolerances" not in message and f"each at most {MAX_STEP:g}" in message


def test_finite_mobility_takes_steps_as_any_sequence_of_numbers(four_bar):
    assert mobility.finite_mobility(four_bar, steps=np.array([0.05, 0.001, 0.01])).steps == (0.001, 0.01, 0.05)


@pytest.mark.timeout(60)
@pytest.mark.parametrize("randoms", [10**40, 2**63, MAX_RANDOMS + 1, 10**5000], ids=["1e40", "2**63", "MAX+1", "1e5000"])
def test_finite_mobility_bounds_the_random_directions(four_bar, randoms):
    message = refused(lambda: mobility.finite_mobility(four_bar, randoms=randoms), "finite_mobility", "randoms")  # was a run that did not end
    assert f"at most {MAX_RANDOMS:,}" in message


# 3. sample_poses: a step in range


@pytest.mark.parametrize("step", [1e300, 10**49, 10**400, 2.0], ids=repr)
def test_sample_poses_refuses_a_step_beyond_its_range(four_bar, step):
    message = refused(lambda: sample_poses(four_bar, 2, step=step), "sample_poses", "step")  # was [] with an overflow warning
    assert "(0, 1]" in message


@settings(max_examples=200, deadline=None)
@given(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10, 10**400), st.text(max_size=3), st.binary(max_size=3), st.none(), st.booleans()))
def test_a_step_is_a_real_number_in_range(value):
    number = None if isinstance(value, (bool, str, bytes)) or value is None else value
    expected = number is not None and 0 < number <= MAX_STEP and math.isfinite(number)
    assert (step_value(value) is not None) == expected


# 4. plot_mechanism: figsize, title and flags


@pytest.mark.parametrize("figsize", [5, math.nan, b"abc", ["A", "A"], np.array([1, 2, 3]), (0.1, 5), (100, 5), (5, math.inf)], ids=repr)
def test_plot_mechanism_wants_a_width_and_a_height_in_range(four_bar, four_bar_result, figsize):
    refused(lambda: plot_mechanism(four_bar, four_bar_result, figsize=figsize), "plot_mechanism", "figsize")
    refused(lambda: plot_graph(four_bar, four_bar_result, figsize=figsize), "plot_graph", "figsize")


def test_plot_mechanism_takes_a_numpy_figsize(four_bar, four_bar_result):
    fig = plot_mechanism(four_bar, four_bar_result, figsize=np.array([4, 3]), views=1)  # was: the truth value of an array is ambiguous
    assert fig.get_size_inches().tolist() == [4.0, 3.0]


@pytest.mark.parametrize("title", [5, b"title", ["a"]], ids=repr)
def test_plot_mechanism_wants_a_string_title(four_bar, four_bar_result, title):
    refused(lambda: plot_mechanism(four_bar, four_bar_result, title=title), "plot_mechanism", "title")  # was AttributeError


@pytest.mark.parametrize("figsize", [(4, 1), (6, 6.6)])
def test_a_long_title_is_cut_to_the_room_of_the_figure(four_bar, four_bar_result, figsize):
    fig = plot_mechanism(four_bar, four_bar_result, title="x" * 10000, figsize=figsize, views=1)  # was "bottom cannot be >= top"
    title = fig._suptitle.get_text()
    assert title.endswith("...") and len(title) <= 600 and fig.subplotpars.top > fig.subplotpars.bottom


@pytest.mark.parametrize("key", ["constraints", "labels", "legend"])
def test_plot_mechanism_wants_bool_flags(four_bar, four_bar_result, key):
    refused(lambda: plot_mechanism(four_bar, four_bar_result, **{key: np.array([1, 2])}), "plot_mechanism", key)


# 5. save_figure: path and dpi


@pytest.fixture(scope="module")
def figure():
    from matplotlib.figure import Figure

    return Figure(figsize=(1, 1))


@pytest.mark.parametrize("path", [None, b"x.png", np.array([1])], ids=repr)
def test_save_figure_wants_a_file_name(figure, path):
    refused(lambda: save_figure(figure, path), "save_figure", "path")  # was TypeError


@pytest.mark.parametrize("dpi", [-1, 10**40, b"abc", np.array([100]), 150.5, DPI_RANGE[0] - 1, DPI_RANGE[1] + 1, True], ids=repr)
def test_save_figure_wants_a_dpi_in_the_range_of_the_command_line(figure, dpi, tmp_path):
    message = refused(lambda: save_figure(figure, tmp_path / "x.png", dpi=dpi), "save_figure", "dpi")
    assert "from 20 to 600" in message and not (tmp_path / "x.png").exists()


def test_save_figure_takes_a_numpy_dpi(figure, tmp_path):
    assert save_figure(figure, tmp_path / "x.png", dpi=np.int64(20)).stat().st_size > 0


# 6. sweep_view: max_poses


@pytest.mark.parametrize("max_poses", [None, "x", [], 0, 201, True, 2.0], ids=repr)
def test_sweep_view_wants_max_poses_in_range(four_bar_sweep, max_poses):
    refused(lambda: mobility.sweep_view(four_bar_sweep, max_poses=max_poses), "sweep_view", "max_poses")  # was TypeError: '<=' not supported


def test_sweep_view_takes_a_numpy_max_poses(four_bar_sweep):
    assert len(mobility.sweep_view(four_bar_sweep, max_poses=np.int64(2)).frames) == 2


# 7. a choice is a string, a flag a bool


@pytest.mark.parametrize("bad", [np.array([1, 2]), ["limb"], None], ids=repr)
def test_choices_are_strings(four_bar, four_bar_result, bad):
    refused(lambda: mobility.enumerate_actuations(four_bar, mode=bad), "enumerate_actuations", "mode")  # was: truth value of an array is ambiguous
    refused(lambda: loop_closure(four_bar, method=bad), "loop_closure", "method")


@pytest.mark.parametrize("bad", [np.array([1, 2]), 1, "yes", None], ids=repr)
def test_the_limbs_flag_of_markdown_report_is_a_bool(four_bar_result, bad):
    refused(lambda: markdown_report(four_bar_result, limbs=bad), "markdown_report", "limbs")


def test_numpy_bools_are_flags(four_bar_result):
    assert markdown_report(four_bar_result, limbs=np.False_) == markdown_report(four_bar_result, limbs=False)
