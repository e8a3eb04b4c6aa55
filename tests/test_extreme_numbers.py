"""Extreme numbers: a valid mechanism at any representable scale has its right answer, or one line and exit status 2, never NaN.

Where a new test goes: a test of a *valid* input whose numbers are extreme -- lengths times 1e200 or
1e-250, a point at the largest float, points a round-off apart, a result that would not fit in a float --
through the library or any command, goes here; so does a check of the answers at scale by a second
route (the Jacobian, the picture and the 3D view of a scaled mechanism are those at scale 1, scaled).
A refusal is asserted with :func:`guards.raises_one_line` or :func:`guards.refused`, an answer with
:func:`guards.finite_numbers`; every command at once with :func:`guards.run_all`.  A number a *file*
cannot hold as written (``1e400``, ``exp(1000)``) goes in ``test_bad_files.py``; a large *count* (joints,
poses, characters) in ``test_extreme_sizes.py``; files of extreme numbers made at random in
``test_fuzz_files.py``.

Issue 13: a valid four-bar with every coordinate times 1e200 (or 1e-250)
reported mobility 3 with NaN in its JSON, because the characteristic length
squared its coordinates.  The core now scales by a power of two before
squaring (:func:`mobility.core.tolerance.binary_scale`), so every count is
the same at every scale; geometry finer than the analysis can resolve (a
four-bar with one pivot at 1e300 and the others near the origin) is refused
in one line naming the link; a result whose numbers do not fit in a float is
refused rather than printed.  Every command (``analyze``, ``check``,
``actuation``, ``plot``, ``jacobian``, ``sweep``, ``view``, ``convert``, with
their options) is run at extreme scales under a time guard: a bound on a
hang, not a speed assertion (speed is measured by ``benchmarks/``).
"""

from __future__ import annotations

import dataclasses
import json
import math
import re
import warnings
from pathlib import Path
from typing import Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mobility
from mobility.core.model import Joint, Mechanism
from mobility.core.tolerance import COINCIDENT_POINTS, binary_scale, characteristic_scale, characteristic_scales
from mobility.errors import AnalysisError, MechanismFileError, MobilityError
from mobility.flexure import check_force_lines, loads_flexure
from mobility.report.text import json_report, text_report

from builders import four_bar, random_mechanism, scaled, three_prs, yaml_text
from guards import RUN_BOUND, finite_numbers, raises_one_line, refused, run_all, run_cli

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"
FLEXURE_TEXTS = {p.name: p.read_text(encoding="utf-8") for p in sorted((ROOT / "examples" / "flexure").glob("*.yaml"))}
THREE_PRS = mobility.load(MECHANISMS / "3prs.yaml")
PLANAR_3RRR = mobility.load(MECHANISMS / "planar_3rrr.yaml")


def run_strict(*args: str):
    """``mobility ARGS`` in-process with every warning an error (a numpy overflow warning would be one)."""
    return run_cli(*args, warnings_as_errors=Warning)


# -- 1. a four-bar at any scale: the same answer, and one pivot far out refused naming its link ------------


FOUR_BAR = ((0, 0, 0), (1, 2, 0), (4, 2.5, 0), (5, 0, 0))


def four_bar_text(points) -> str:
    links = (("ground", "crank"), ("crank", "coupler"), ("coupler", "rocker"), ("rocker", "ground"))
    lines = ["name: four-bar", "ground: ground", "end_effector: coupler", "joints:"]
    for name, (a, b), p, act in zip("ABCD", links, points, (True, False, False, False)):
        flag = ", actuated: true" if act else ""
        lines.append(f"  - {{name: {name}, type: R, links: [{a}, {b}], axis: [0, 0, 1], point: [{p[0]!r}, {p[1]!r}, {p[2]!r}]{flag}}}")
    return "\n".join(lines + ["expected: {dof: 1, pattern: 1R, mobility: 1}"]) + "\n"


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
    for args, answer in ((["analyze", "--json"], None), (["analyze", "--finite"], "full-cycle"), (["check"], "1 passed"), (["actuation"], "VALID")):
        done = run_strict(*args, path)
        assert (done.returncode, done.stderr) == (0, ""), (args, done.stderr)
        assert answer in done.stdout if answer else json.loads(done.stdout)["mobility"] == 1


@pytest.mark.parametrize("where", range(4))
def test_one_pivot_at_1e300_is_one_line_naming_the_link(tmp_path, where):
    points = list(FOUR_BAR)
    points[where] = (1e300, 0, 0)
    caught = raises_one_line(lambda: mobility.analyze(four_bar(points)), MechanismFileError, r"joints\[\d\]\.point: the joints of link '\w+' \(\w, \w\) span")
    far = "ABCD"[where]  # the joint that makes the size is named with its point, whichever link is refused
    assert f"of the mechanism's size 4.33e+299 (set by joint '{far}' at [1e+300, 0, 0]): finer than" in str(caught)
    path = tmp_path / "far.yaml"
    path.write_text(four_bar_text(points))
    for command in (["analyze"], ["analyze", "--json"], ["analyze", "--finite"], ["actuation"]):
        err = refused(run_strict(*command, path))
        # the line of the joint named (the joints start on line 5 of the file)
        located = re.match(rf"mobility: {re.escape(str(path))}:(\d+): joints\[(\d)\]\.point: ", err)
        assert located and int(located[1]) == 5 + int(located[2]) and "finer than the analysis can resolve" in err, err
    done = run_strict("check", path)
    assert done.returncode == 2 and "finer than the analysis can resolve" in done.stdout


def test_an_unresolved_link_of_a_limb_pattern_names_the_limb_joint_and_its_line(tmp_path):
    # the third copy's sphere at 1e300: the first link refused is leg1, whose joints R1, S1 the pattern writes
    text = (ROOT / "mechanisms" / "3prs.yaml").read_text()
    path = tmp_path / "far_limb.yaml"
    path.write_text(text.replace("point: [r, 0, 0]", 'point: ["r + 1e300*max(i - 1, 0)", 0, 0]'))
    err = refused(run_strict("analyze", path))
    written = next(n for n, line in enumerate(text.splitlines(), 1) if '{name: "R{i+1}"' in line)
    assert err.startswith(f"mobility: {path}:{written}: limbs[0].joints[1].point: the joints of link 'leg1' (R1, S1) span 283"), err


def test_a_joint_too_far_out_to_draw_is_named_with_its_line(tmp_path):
    # a hinge and a slider, the hinge at 1e308: analysed, but beyond any drawing's arithmetic
    path = tmp_path / "lone.yaml"
    path.write_text("name: lone\nground: a\nend_effector: c\njoints:\n"
                    "  - {name: s, type: P, links: [a, b], axis: [1, 0, 0]}\n"
                    "  - {name: j, type: R, links: [b, c], axis: [0, 0, 1], point: [1e308, 0, 0]}\n")
    assert run_strict("analyze", path).returncode == 0
    err = refused(run_strict("plot", path, "-o", tmp_path / "lone.png"))
    assert err.startswith(f"mobility: {path}:6: joints[1].point (joint j): its point lies 1e+308 from the origin"), err
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
    raises_one_line(lambda: mobility.analyze(Mechanism("m", "g", "b", joints(3.55e-15))), MechanismFileError,
                    r"the joints of link 'a' \(J1, J2\) span 3.55e-15.*bring the far joints nearer or split the mechanism, or, if these joints meet at one point, write the same point for each$")


# -- 2. the largest float ------------------------------------------------------------------------------------


def test_the_largest_float_as_a_coordinate_is_refused_in_one_line(tmp_path):
    points = list(FOUR_BAR)
    points[3] = (1.7976931348623157e308, -1.7976931348623157e308, 0)
    path = tmp_path / "max.yaml"
    path.write_text(four_bar_text(points))
    assert refused(run_strict("analyze", "--json", path)).startswith(f"mobility: {path}:5: joints[0].point: ")


def test_points_too_far_apart_for_a_float_are_refused_in_one_line():
    # the RMS distance from the centroid exceeds the largest float: no length unit can hold the mechanism
    big = 1.7976931348623157e308
    m = four_bar(((big, big, 0), (-big, -big, 0), (big, -big, 0), (-big, big, 0)))
    raises_one_line(lambda: mobility.analyze(m), MechanismFileError, r"^<string>: joints\[\d\]\.point: the joint points are too far apart")


def test_a_result_that_would_hold_nan_is_never_written_as_json():
    r = mobility.analyze(four_bar())
    object.__setattr__(r, "margin", r.margin.__class__(float("nan"), 0.0, False, False))
    raises_one_line(lambda: json_report(r), AnalysisError, "not finite")


AT_THE_LARGEST_FLOAT = """\
name: 3-PRS with its S centres at the largest float
ground: frame
end_effector: platform
limbs:
- copies: 3
  frame: {name: "leg{i+1}", rpy: [0, 0, "120*i"]}
  joints:
  - {name: "P{i+1}", type: P, links: [frame, "slider{i+1}"], axis: [0, 0, 1]}
  - {name: "R{i+1}", type: R, links: ["slider{i+1}", "leg{i+1}"], axis: [0, 1, 0], point: [200, 0, 283]}
  - {name: "S{i+1}", type: S, links: ["leg{i+1}", platform], point: [100, 0, Z]}
"""


FAR_4R = """\
name: spatial 4R with a frame at the largest float
ground: ground
end_effector: coupler
frames:
  F1: {origin: [64.27876096865394, 76.60444431189781, 1.7976931348623157e308], rpy: [40, 0, 50]}
  F2: {origin: [-41.04241719908025, 112.76311449430901, 0], rpy: [70, 0, 110], parent: F1}
  F3: {origin: [64.27876096865394, -76.60444431189781, 0], rpy: [40, 0, -50], parent: F2}
joints:
  - {name: J1, type: R, links: [ground, link1], axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J2, type: R, links: [link1, coupler], frame: F1, axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J3, type: R, links: [coupler, link3], frame: F2, axis: [0, 0, 1], point: [0, 0, 0]}
  - {name: J4, type: R, links: [link3, ground], frame: F3, axis: [0, 0, 1], point: [0, 0, 0]}
"""


@pytest.mark.parametrize("text", [AT_THE_LARGEST_FLOAT.replace("Z", "1.7976931348623157e308"), FAR_4R], ids=["3-PRS", "4R"])
def test_points_at_the_largest_float_are_an_error_of_analyze_itself(text):
    # The points are representable floats, but the screw axes lie past the largest one: analyze says so
    # (it used to return, with a reference point of inf and an overflow warning, and the error came when a
    # lazy part of the result was first read: found by the fuzz test run with 20 times its examples).
    m = mobility.loads(text)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        raises_one_line(lambda: mobility.analyze(m), MobilityError, "axes lie beyond the largest float")


def test_an_actuation_wrench_past_the_largest_float_is_refused_by_name():
    text = AT_THE_LARGEST_FLOAT.replace("Z", "1.7976931348623157e308").replace("axis: [0, 0, 1]}", "axis: [0, 0, 1], actuated: true}")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        raises_one_line(lambda: mobility.check_actuation(mobility.loads(text)), MobilityError, "the actuation wrench of 'P1' lies beyond the largest float")


def test_a_force_line_at_the_largest_float_acts_as_a_couple():
    # found by the flexure fuzz test: the actuator t3 moved to y = 1.8e308 in its leg's frame.  Its unit
    # wrench is a couple about the line's normal to the platform (the limit of a force ever farther away),
    # the verdict stands, and the conditioning is 0, its limit (that input's row outgrows every other).
    text = FLEXURE_TEXTS["three_rod.yaml"].replace("{name: t3, frame: leg3, point: [rho, 0, h]", "{name: t3, frame: leg3, point: [rho, 1.7976931348623157e308, h]")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check = check_force_lines(loads_flexure(text))
    t3 = check.inputs[2]
    assert (check.verdict, check.conditioning, t3.axis.kind) == ("valid", 0.0, "couple")
    assert t3.axis.axis == pytest.approx([0, 0, -1], abs=1e-12) and finite_numbers(check.to_dict())


# -- 3. any mechanism at any power of ten: no count changes ------------------------------------------------


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


# -- 4. every command at an extreme scale -------------------------------------------------------------------


def far_pivot() -> Mechanism:
    """A four-bar with one pivot at 1e300 and the others near the origin: finer than any analysis resolves."""
    m = mobility.load(MECHANISMS / "four_bar.yaml")
    joints = list(m.world_joints)
    joints[3] = dataclasses.replace(joints[3], point=(1e300, 0.0, 0.0))
    return m.replace(joints=tuple(joints), frames=())


def lone_far_pivot() -> Mechanism:
    """One hinge at 1e308 on every axis: a valid mechanism (1R) that no picture can hold (a drawing squares coordinates)."""
    return Mechanism("lone pivot", "a", "b", (Joint("j", "R", ("a", "b"), axis=(0.0, 0.0, 1.0), point=(1e308, 1e308, 1e308), actuated=True),))


EXTREME: dict[str, Callable[[], Mechanism]] = {
    "3prs x 1e200": lambda: scaled(THREE_PRS, 1e200),
    "3prs x 1e-250": lambda: scaled(THREE_PRS, 1e-250),
    "planar 3-RRR x 1e-250": lambda: scaled(PLANAR_3RRR, 1e-250),
    "pivot at 1e300": far_pivot,
    "lone pivot at 1e308": lone_far_pivot,
}


@pytest.mark.parametrize("case", sorted(EXTREME))
def test_every_command_at_an_extreme_scale_answers_or_refuses_in_one_line(case, tmp_path):
    outcome = run_all(EXTREME[case](), tmp_path)
    failures = {name: why for name, (_, why) in outcome.items() if why}
    assert not failures, failures
    refusing = {name for name, (status, _) in outcome.items() if status == 2}
    if case == "pivot at 1e300":  # geometry finer than any analysis resolves: everything that analyses refuses it
        assert set(outcome) - refusing <= {"convert"}
    elif case == "lone pivot at 1e308":  # analysed; drawn nowhere (too far out for a drawing's arithmetic)
        assert refusing == {"plot", "view", "view --samples"}, refusing
    else:  # a valid mechanism at any scale: every command answers (convert: when its file can hold the numbers)
        assert refusing <= ({"convert"} if "1e-250" in case else set()), refusing


# -- 5. the answers at scale, by a second route: Jacobian, picture, view -------------------------------------


def jacobian_parts(m: Mechanism) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[str]]:
    from mobility.jacobians import jacobian

    j = jacobian(m)
    kinds = [m.joint(label.split(".")[0]).type for label in j.actuated]
    # the constraint rows in normalised terms, [f; m / L], each over its largest entry (nothing squared)
    normalised = j.constraint_wrenches / np.array([1, 1, 1, j.length, j.length, j.length])
    normalised /= np.abs(normalised).max(axis=1)[:, None]
    return j.actuation_wrenches, normalised, j.twist_map, kinds


def unscaled_wrenches(rows: np.ndarray, factor: float, per_length: list[bool]) -> np.ndarray:
    """Wrench rows of a mechanism scaled by ``factor`` brought back to scale 1 (moments over ``factor``; a wrench per unit angle times it)."""
    out = rows.copy()
    out[:, 3:] /= factor
    return out * np.where(per_length, 1.0, factor)[:, None]


@settings(max_examples=25, deadline=None, derandomize=True)
@given(exponent=st.integers(-300, 300), name=st.sampled_from(["3prs", "planar_3rrr", "6ups", "tricept"]))
def test_the_jacobian_of_a_scaled_mechanism_is_the_jacobian_scaled(exponent, name):
    from mobility.core.screws import same_subspace

    m = mobility.load(MECHANISMS / f"{name}.yaml")
    factor = 10.0**exponent
    act, con, twists, kinds = jacobian_parts(m)
    act_k, con_k, twists_k, _ = jacobian_parts(scaled(m, factor))
    per_length = [k == "P" for k in kinds]
    # actuation wrenches and the twists per unit input rate are unique: equal after unscaling
    assert np.allclose(unscaled_wrenches(act_k, factor, per_length), act, rtol=1e-8, atol=1e-9 * np.abs(act).max())
    back = twists_k.copy()
    back[3:] /= factor  # velocities are lengths per time
    back *= np.where(per_length, factor, 1.0)[None, :]  # per unit length of a slider's rate
    assert np.allclose(back, twists, rtol=1e-8, atol=1e-9 * np.abs(twists).max())
    # the constraint wrenches are a basis of a subspace: the same subspace (in normalised terms, scale-free)
    assert same_subspace(con_k.T, con.T)


@pytest.mark.parametrize("factor", [1e200, 1e-250])
def test_the_jacobian_command_prints_the_same_digits_scaled(tmp_path, factor):
    from mobility.core.joint_screws import joint_screws

    texts = {}
    for k in (1.0, factor):
        path = tmp_path / f"m{k}.yaml"
        path.write_text(yaml_text(scaled(PLANAR_3RRR, k)), encoding="utf-8")
        done = run_cli("jacobian", "--json", path, seconds=RUN_BOUND, warnings_as_errors=RuntimeWarning)
        assert done.returncode == 0 and done.stderr == "", done.stderr
        texts[k] = json.loads(done.stdout)
    one, big = texts[1.0], texts[factor]
    assert one["condition"] == pytest.approx(big["condition"], rel=1e-9) and one["rank"] == big["rank"] == 6
    # the actuation rows of J: revolute inputs, so [m; f] becomes [m; f / k]
    for row, row_k in zip(one["matrix"][:3], big["matrix"][:3]):
        assert np.allclose(np.array(row_k) * [1, 1, 1, factor, factor, factor], row, rtol=1e-8, atol=1e-9)
    # each actuation axis passes through the same point, scaled
    for axis, axis_k in zip(one["actuation_axes"], big["actuation_axes"]):
        assert axis["kind"] == axis_k["kind"] == "force"
        assert np.allclose(np.array(axis_k["point"]) / factor, axis["point"], rtol=1e-8, atol=1e-9 * joint_screws(PLANAR_3RRR).normalisation.length)


@pytest.mark.parametrize("factor", [1e200, 1e-250, 2e307 / 40.0])
def test_the_picture_of_a_scaled_mechanism_is_the_same_picture(factor):
    import matplotlib

    matplotlib.use("Agg")
    from mobility.report.plotting import plot_mechanism, sketch

    def rotation_axes(m: Mechanism) -> tuple[dict[str, np.ndarray], float]:
        fig = plot_mechanism(m, constraints=True, views=[(30, 40)])
        lines = {line.get_gid(): np.column_stack(line.get_data_3d()) for line in fig.axes[0].get_lines() if (line.get_gid() or "").startswith(("mobility:rotation-axis", "mobility:force:"))}
        return lines, sketch(m).scale

    plain, one = rotation_axes(THREE_PRS)
    big, scale = rotation_axes(scaled(THREE_PRS, factor))
    assert one == 1.0 and 0.1 < sketch(scaled(THREE_PRS, factor)).size < 10.0  # the plain one in its file's numbers, the scaled one near 1
    assert plain.keys() == big.keys() and len(plain) >= 4
    for gid, line in plain.items():  # the same lines, in drawing units: the file's times the drawing scale
        assert np.allclose(big[gid] / (factor * scale), line, rtol=1e-8, atol=1e-9), gid


def test_the_view_of_a_scaled_mechanism_labels_its_axes_in_the_file_units():
    from mobility.view import mechanism_view

    plain = mechanism_view(THREE_PRS).figure_dict
    view = mechanism_view(scaled(THREE_PRS, 1e-250))
    big, per_drawn = view.figure_dict, 1.0 / view.scenes[0].scale  # file units per drawing unit
    assert "tickvals" not in plain["layout"]["scene"]["xaxis"]  # an everyday size: plotly's own ticks
    for name in ("xaxis", "yaxis", "zaxis"):
        axis = big["layout"]["scene"][name]
        lo, hi = axis["range"]
        assert all(lo <= v <= hi for v in axis["tickvals"]) and len(axis["tickvals"]) >= 3
        drawn, shown = np.array(axis["tickvals"]), np.array([float(t) for t in axis["ticktext"]])
        ratio = shown[shown != 0] / drawn[shown != 0]  # one factor from drawing units to the file's
        assert np.allclose(ratio, per_drawn, rtol=1e-6)  # each tick's text is the file's value where it is drawn
    traces = [t for t in big["data"] if t["meta"]["key"] == "R1" and "x" in t]
    plain_traces = [t for t in plain["data"] if t["meta"]["key"] == "R1" and "x" in t]
    assert np.allclose(np.array(traces[0]["x"], dtype=float) * per_drawn / 1e-250, np.array(plain_traces[0]["x"], dtype=float), rtol=1e-5, atol=1e-6, equal_nan=True)  # None: a break in the line


@pytest.mark.parametrize("factor, offset", [(1.0, 3e7), (1e-6, 1000.0)])
def test_the_view_of_a_mechanism_far_from_the_origin_is_drawn_about_its_middle(factor, offset):
    # With absolute coordinates written to 7 digits, a 3-PRS a millionth of its size, moved 1000 mm away,
    # was drawn with two distinct x values (and at 3e7 mm its axis lines were 1 % of its size off)
    from mobility.view import mechanism_view

    def moved(m: Mechanism) -> Mechanism:
        return m.replace(joints=tuple(dataclasses.replace(j, point=(j.point[0] + offset, j.point[1], j.point[2])) if j.point is not None else j
                                      for j in m.world_joints), frames=())

    near, far = scaled(THREE_PRS, factor), moved(scaled(THREE_PRS, factor))
    plain, view = mechanism_view(near).figure_dict, mechanism_view(far).figure_dict
    per_drawn = 1.0 / mechanism_view(far).scenes[0].scale  # file units per drawing unit (the same near and far)
    lo, hi = plain["layout"]["scene"]["xaxis"]["range"]
    middle, width = 0.5 * (lo + hi), hi - lo  # the near scene's middle: where the far one's is drawn from
    compared = 0
    for mine, theirs in zip(view["data"], plain["data"]):  # the same glyphs, drawn the same about the scene's middle
        assert mine["meta"] == theirs["meta"]
        if "x" in mine and mine["meta"]["key"] in ("R1", "W2", "T1"):
            x, x0 = np.array(mine["x"], dtype=float) + middle, np.array(theirs["x"], dtype=float)
            assert np.allclose(x, x0, rtol=0, atol=1e-6 * width, equal_nan=True), mine["meta"]
            compared += 1
    assert compared >= 3
    axis = view["layout"]["scene"]["xaxis"]
    shown = np.array([float(t) for t in axis["ticktext"]])
    assert len(set(axis["ticktext"])) == len(shown) >= 3  # ticks told apart
    file_x = (np.array(axis["tickvals"]) + middle) * per_drawn + offset  # the file's x where each tick is drawn
    assert np.allclose(shown, file_x, rtol=1e-12, atol=1e-9 * width * per_drawn)
