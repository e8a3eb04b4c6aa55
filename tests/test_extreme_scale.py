"""Numbers at any representable scale: a right answer, or one line and exit status 2, never NaN.

Issue 13: a valid four-bar with every coordinate times 1e200 (or 1e-250)
reported mobility 3 with NaN in its JSON, because the characteristic length
squared its coordinates.  The core now scales by a power of two before
squaring (:func:`mobility.core.tolerance.binary_scale`), so every count is
the same at every scale; geometry finer than the analysis can resolve (a
four-bar with one pivot at 1e300 and the others near the origin) is refused
in one line naming the link; a result whose numbers do not fit in a float is
refused rather than printed.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from builders import four_bar, random_mechanism, three_prs, transformed
from guards import finite_numbers
from hypothesis import given, settings
from hypothesis import strategies as st

import mobility
from mobility.cli import main
from mobility.core.model import Joint, Mechanism
from mobility.core.tolerance import COINCIDENT_POINTS, binary_scale, characteristic_scale, characteristic_scales
from mobility.core.transforms import Transform
from mobility.errors import AnalysisError, MechanismFileError
from mobility.report.text import json_report, text_report

FOUR_BAR = ((0, 0, 0), (1, 2, 0), (4, 2.5, 0), (5, 0, 0))


ROOT = Path(__file__).resolve().parent.parent


def four_bar_text(points) -> str:
    links = (("ground", "crank"), ("crank", "coupler"), ("coupler", "rocker"), ("rocker", "ground"))
    lines = ["name: four-bar", "ground: ground", "end_effector: coupler", "joints:"]
    for name, (a, b), p, act in zip("ABCD", links, points, (True, False, False, False)):
        flag = ", actuated: true" if act else ""
        lines.append(f"  - {{name: {name}, type: R, links: [{a}, {b}], axis: [0, 0, 1], point: [{p[0]!r}, {p[1]!r}, {p[2]!r}]{flag}}}")
    return "\n".join(lines + ["expected: {dof: 1, pattern: 1R, mobility: 1}"]) + "\n"


def run_cli(*args: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), warnings.catch_warnings():
        warnings.simplefilter("error")  # a numpy overflow warning would be an error
        status = main(list(args))
    return status, out.getvalue(), err.getvalue()


def instantaneous_centre(points) -> np.ndarray:
    """Where lines AB and DC meet: the coupler's instantaneous centre, by plane geometry."""
    a, b, c, d = (np.array(p[:2], dtype=float) for p in points)
    t = np.linalg.solve(np.stack([b - a, -(c - d)], axis=1), d - a)
    return a + t[0] * (b - a)


@pytest.mark.parametrize("factor", [1e200, 1e-250, 1e300, 1e-300, 2e307])
def test_a_scaled_four_bar_keeps_its_answer(factor):
    points = [tuple(c * factor for c in p) for p in FOUR_BAR]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = mobility.analyze(four_bar(points))
        data = json.loads(json_report(r))
        text = text_report(r, limbs=True)
    assert (r.dof, r.pattern, r.mobility, r.redundant_constraints) == (1, "1R", 1, 3)
    assert finite_numbers(data) and "nan" not in text and "inf" not in text
    (rotation,) = r.rotations
    centre = instantaneous_centre(FOUR_BAR) * factor
    assert np.allclose(rotation.point[:2], centre, rtol=1e-9, atol=0.0)
    assert not r.warnings and r.margin.smallest_kept == pytest.approx(mobility.analyze(four_bar()).margin.smallest_kept, rel=1e-9)


@pytest.mark.parametrize("factor", [1e200, 1e-250])
def test_a_scaled_four_bar_through_every_command(tmp_path, factor):
    path = tmp_path / "scaled.yaml"
    path.write_text(four_bar_text([tuple(c * factor for c in p) for p in FOUR_BAR]))
    status, out, err = run_cli("analyze", "--json", str(path))
    assert (status, err) == (0, "") and json.loads(out)["mobility"] == 1
    status, out, err = run_cli("analyze", "--finite", str(path))
    assert (status, err) == (0, "") and "full-cycle" in out
    status, out, err = run_cli("check", str(path))
    assert (status, err) == (0, "") and "1 passed" in out
    status, out, err = run_cli("actuation", str(path))
    assert (status, err) == (0, "") and "VALID" in out


@pytest.mark.parametrize("where", range(4))
def test_one_pivot_at_1e300_is_one_line_naming_the_link(tmp_path, where):
    points = list(FOUR_BAR)
    points[where] = (1e300, 0, 0)
    with pytest.raises(MechanismFileError, match=r"joints\[\d\]\.point: the joints of link '\w+' \(\w, \w\) span") as caught:
        mobility.analyze(four_bar(points))
    assert "\n" not in str(caught.value)
    far = "ABCD"[where]  # the joint that makes the size is named with its point, whichever link is refused
    assert f"of the mechanism's size 4.33e+299 (set by joint '{far}' at [1e+300, 0, 0]): finer than" in str(caught.value)
    path = tmp_path / "far.yaml"
    path.write_text(four_bar_text(points))
    for command in (["analyze"], ["analyze", "--json"], ["analyze", "--finite"], ["actuation"]):
        status, out, err = run_cli(*command, str(path))
        assert (status, out) == (2, "") and err.count("\n") == 1, (command, err)
        # the line of the joint named (the joints start on line 5 of the file)
        located = re.match(rf"mobility: {re.escape(str(path))}:(\d+): joints\[(\d)\]\.point: ", err)
        assert located and int(located[1]) == 5 + int(located[2]) and "finer than the analysis can resolve" in err, err
    status, out, _ = run_cli("check", str(path))
    assert status == 2 and "finer than the analysis can resolve" in out


def test_an_unresolved_link_of_a_limb_pattern_names_the_limb_joint_and_its_line(tmp_path):
    # the third copy's sphere at 1e300: the first link refused is leg1, whose joints R1, S1 the pattern writes
    text = (ROOT / "mechanisms" / "3prs.yaml").read_text()
    path = tmp_path / "far_limb.yaml"
    path.write_text(text.replace("point: [r, 0, 0]", 'point: ["r + 1e300*max(i - 1, 0)", 0, 0]'))
    status, out, err = run_cli("analyze", str(path))
    written = next(n for n, line in enumerate(text.splitlines(), 1) if '{name: "R{i+1}"' in line)
    assert (status, out) == (2, "") and err.startswith(f"mobility: {path}:{written}: limbs[0].joints[1].point: the joints of link 'leg1' (R1, S1) span 283"), err


def test_a_joint_too_far_out_to_draw_is_named_with_its_line(tmp_path):
    # a hinge and a slider, the hinge at 1e308: analysed, but beyond any drawing's arithmetic
    path = tmp_path / "lone.yaml"
    path.write_text("name: lone\nground: a\nend_effector: c\njoints:\n"
                    "  - {name: s, type: P, links: [a, b], axis: [1, 0, 0]}\n"
                    "  - {name: j, type: R, links: [b, c], axis: [0, 0, 1], point: [1e308, 0, 0]}\n")
    assert run_cli("analyze", str(path))[0] == 0
    status, out, err = run_cli("plot", str(path), "-o", str(tmp_path / "lone.png"))
    assert (status, out) == (2, "") and err.startswith(f"mobility: {path}:6: joints[1].point (joint j): its point lies 1e+308 from the origin"), err
    assert not (tmp_path / "lone.png").exists()


def test_points_a_round_off_apart_near_the_origin_are_refused_with_the_fix_for_both_readings():
    # Two joints of a link written 3.6e-15 apart near the origin, in a mechanism of size about 70: far
    # above the round-off of their own coordinates, far below what the analysis resolves.  They may be
    # distinct points (a link too narrow to analyse) or one point written with a generator's round-off;
    # the message gives the fix for each.  Written as one point, they analyse.
    joints = lambda x: (
        Joint("J1", "R", ("g", "a"), axis=(0.0, 0.0, 1.0), point=(0.0, 0.0, 0.0)),
        Joint("J2", "R", ("a", "b"), axis=(1.0, 0.0, 0.0), point=(x, 0.0, 0.0)),
        Joint("J3", "R", ("b", "c"), axis=(0.0, 1.0, 0.0), point=(100.0, 0.0, 0.0)),
        Joint("J4", "R", ("c", "g"), axis=(0.0, 0.0, 1.0), point=(100.0, 100.0, 0.0)),
    )
    assert mobility.analyze(Mechanism("m", "g", "b", joints(0.0))).dof >= 0
    with pytest.raises(MechanismFileError, match=r"the joints of link 'a' \(J1, J2\) span 3.55e-15.*bring the far joints nearer or split the mechanism, or, if these joints meet at one point, write the same point for each$"):
        mobility.analyze(Mechanism("m", "g", "b", joints(3.55e-15)))


def test_the_largest_float_as_a_coordinate_is_refused_in_one_line(tmp_path):
    points = list(FOUR_BAR)
    points[3] = (1.7976931348623157e308, -1.7976931348623157e308, 0)
    path = tmp_path / "max.yaml"
    path.write_text(four_bar_text(points))
    status, out, err = run_cli("analyze", "--json", str(path))
    assert (status, out) == (2, "") and err.count("\n") == 1 and err.startswith(f"mobility: {path}:5: joints[0].point: ")


def test_points_too_far_apart_for_a_float_are_refused_in_one_line():
    # the RMS distance from the centroid exceeds the largest float: no length unit can hold the mechanism
    big = 1.7976931348623157e308
    m = four_bar(((big, big, 0), (-big, -big, 0), (big, -big, 0), (-big, big, 0)))
    with pytest.raises(MechanismFileError, match=r"^<string>: joints\[\d\]\.point: the joint points are too far apart"):
        mobility.analyze(m)


def test_a_result_that_would_hold_nan_is_never_written_as_json():
    r = mobility.analyze(four_bar())
    object.__setattr__(r, "margin", r.margin.__class__(float("nan"), 0.0, False, False))
    with pytest.raises(AnalysisError, match="not finite"):
        json_report(r)


def scaled(m: Mechanism, factor: float) -> Mechanism:
    return transformed(m, Transform.identity(), factor)


def counts(r: mobility.Result) -> tuple:
    return r.dof, r.pattern, r.mobility, r.redundant_constraints, r.idle_dof, r.common_constraints


@settings(max_examples=60, deadline=None, derandomize=True)
@given(seed=st.integers(0, 299), exponent=st.integers(-300, 300))
def test_scaling_by_any_power_of_ten_changes_no_count(seed, exponent):
    m = random_mechanism(seed)
    factor = 10.0**exponent
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = mobility.analyze(scaled(m, factor))
        assert finite_numbers(r.to_dict())
    assert counts(r) == counts(mobility.analyze(m))


@settings(max_examples=40, deadline=None, derandomize=True)
@given(exponent=st.integers(-300, 300), heights=st.tuples(*[st.floats(0.1, 0.9)] * 3))
def test_a_three_prs_at_any_scale(exponent, heights):
    r = mobility.analyze(scaled(three_prs(heights=heights), 10.0**exponent))
    assert (r.dof, r.pattern, r.mobility) == (3, "1T2R", 3)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(
    points=st.lists(st.tuples(*[st.floats(-1e3, 1e3, allow_subnormal=False)] * 3), min_size=1, max_size=8),
    power=st.integers(-1000, 1000),
)
def test_the_characteristic_scale_scales_exactly_by_powers_of_two(points, power):
    # a power of two changes no rounding: the centre and length of the scaled points are the scaled ones, bit for bit
    pts = np.array(points)
    centre, length = characteristic_scale(pts)
    scale = math.ldexp(1.0, power)
    if length * scale == 0.0 or not math.isfinite(length * scale) or np.any((pts * scale != 0) & (np.abs(pts * scale) < 2.3e-308)):
        return  # the scaled points leave the normal floats: nothing to compare bit for bit
    centre2, length2 = characteristic_scale(pts * scale)
    spread = np.sqrt(np.mean(np.sum((pts - pts.mean(axis=0)) ** 2, axis=1)))
    if length == 1.0 and spread <= COINCIDENT_POINTS * np.abs(centre).max():  # coincident points: the fallback length 1 does not scale
        assert length2 == 1.0
        return
    assert length2 == length * scale and np.array_equal(centre2, centre * scale)


def test_a_pitch_is_the_characteristic_length_only_of_coincident_points():
    pitch = np.array([2.5])
    third = np.full((3, 3), 0.1)  # the mean of three 0.1s is not 0.1: a spread of round-off, ~1e-17
    assert characteristic_scale(third, pitch)[1] == 2.5 and characteristic_scale(third)[1] == 1.0
    # points a micrometre apart beside another length of 10 m are a mechanism of that size, not of the length's
    # (a helical pitch, given as pitches=, raises the size to their geometric mean: tests/test_spec_conformance.py)
    tiny = np.array([[0.0, 0, 0], [1e-6, 0, 0]])
    assert characteristic_scale(tiny, np.array([1e4]))[1] == pytest.approx(5e-7)
    assert characteristic_scales(tiny[None], np.array([1e4]))[1].tolist() == [characteristic_scale(tiny, np.array([1e4]))[1]]


def test_binary_scale_brings_any_magnitude_near_one():
    for x in (2.2250738585072014e-308, 1e-300, 1.0, 3.0, 1e300, 1.7976931348623157e308):
        s = binary_scale([x, -x / 3])
        assert 0.5 <= x * s < 8.0 and math.frexp(s)[0] == 0.5  # a power of two; below 8 only at the very top of the range
    s = binary_scale([5e-324])  # a subnormal: scaled up as far as a normal power of two goes
    assert s == math.ldexp(1.0, 1021) and 5e-324 * s == math.ldexp(1.0, -53)
