"""Bad arguments of the Python API: each is one of the project's errors, of one line, naming the function or key and what was expected.

Where a new test goes: a test that calls a public function, class or method of the package (``mobility.*``)
with a wrong argument (type, range, shape, count, a string where names or an object are due), or checks
that an argument of the right kind in another form (a numpy number, an array, any sequence) is taken, goes
here, in the section of the function's area.  It asserts the refusal with :func:`guards.raises_one_line`
(a :class:`~mobility.errors.RequestError` for an argument of a call, a
:class:`~mobility.errors.MechanismError` for a field of a description: ``Joint``, ``Frame``,
``Mechanism``, ``Expected``).  A bad *file* goes in ``test_bad_files.py`` (or ``test_bad_robot_files.py``),
a bad *option* of the command line in ``test_bad_command_line.py``, a valid but huge or extreme input in
``test_extreme_numbers.py`` or ``test_extreme_sizes.py``.

Each test failed before its fix (an AttributeError, a TypeError from numpy or matplotlib, a silent wrong
answer, or a call that did not end).
"""

from __future__ import annotations

import itertools
import math
import pickle
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mobility
import mobility.errors as errors
from mobility import Expected, Frame, Joint, Tolerance
from mobility.actuation import lock_joints
from mobility.core.finite_screws import FiniteScrew, Limb, ScrewJoint, finite_screw, transform_from_finite_screw, triangle_product
from mobility.core.loop_closure import loop_closure
from mobility.core.model import Mechanism
from mobility.core.poses import MAX_STEP, sample_poses, step_value
from mobility.errors import MechanismError, RequestError, SynthesisError
from mobility.finite.parameters import MAX_RANDOMS
from mobility.io.limits import Limits
from mobility.report.markdown import markdown_report
from mobility.report.plotting import plot_graph, plot_mechanism, save_figure
from mobility.report.plotting.backend import DPI_RANGE
from mobility.synthesis import named_pattern

from conftest import MECHANISMS
from guards import raises_one_line

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.fixture(scope="module")
def four_bar():
    return mobility.load(MECHANISMS / "four_bar.yaml")


@pytest.fixture(scope="module")
def four_bar_result(four_bar):
    return mobility.analyze(four_bar)


@pytest.fixture(scope="module")
def four_bar_sweep(four_bar):
    return mobility.sweep(four_bar, ["A=0:20:3"])


@pytest.fixture(scope="module")
def rps():
    return mobility.load(MECHANISMS / "actuation_3rps.yaml")


@pytest.fixture(scope="module")
def metrom():
    return mobility.load(MECHANISMS / "metrom.yaml")


# -- 1. Joint, Frame and Mechanism: names, numbers, frames ---------------------------------------------


def test_names_given_in_code_follow_the_same_rule():
    z = (0, 0, 1)
    raises_one_line(lambda: Joint("hip\tleft", "R", ("a", "b"), axis=z, point=(0, 0, 0)), MechanismError, r"^name: a tab '\\t' \(U\+0009\) is not allowed in a name$")
    raises_one_line(lambda: Joint("hip", "R", ("a", "b\u2028"), axis=z, point=(0, 0, 0)), MechanismError, r"^links\[1\]: a line separator")
    raises_one_line(lambda: Frame("tool\u202e"), MechanismError, r"^name: a format character .*U\+202E")
    joint = Joint("A", "R", ("ground", "crank"), axis=z, point=(0, 0, 0))
    raises_one_line(lambda: Mechanism("arm", ground="ground", end_effector="crank\u2029", joints=(joint,)), MechanismError, r"^end_effector: a paragraph separator")
    assert Joint("连杆 1", "R", ("ground", "crank"), axis=z, point=(0, 0, 0)).name == "连杆 1"  # any printable text is a name


def test_name_problem_is_none_for_every_printable_name():
    assert [errors.name_problem(n) for n in ("A", "left knee", "Grübler 𝄞", "P,1", "a\u00a0b")] == [None] * 5


def test_a_joint_refuses_other_digits_and_bools_for_numbers():
    z, o = (0, 0, 1), (0, 0, 0)
    raises_one_line(lambda: Joint("H", "H", ("a", "b"), axis=z, point=o, pitch="\u0661"), MechanismError, "^pitch: expected a number, got '\u0661'$")
    raises_one_line(lambda: Joint("H", "H", ("a", "b"), axis=z, point=o, pitch=True), MechanismError, "^pitch: expected a number, got True$")
    for axis in ((True, 0, 0), np.array([True, False, False]), ("\u0661", 0, 0)):
        raises_one_line(lambda: Joint("R", "R", ("a", "b"), axis=axis, point=o), MechanismError, "^axis: expected a list of 3 numbers")
    assert Joint("H", "H", ("a", "b"), axis=z, point=o, pitch="0.5").pitch == 0.5  # ASCII text is still a number
    assert Joint("R", "R", ("a", "b"), axis=(0, 0, np.int64(2)), point=o).axis == (0.0, 0.0, 1.0)


def test_the_apis_text_numbers_follow_the_same_rule():
    import numpy as np

    from mobility import Joint
    from mobility.errors import MechanismError

    z = (0, 0, 1)
    raises_one_line(lambda: Joint("H", "H", ("a", "b"), axis=np.array(["0", "0", "1_0"], dtype=object), point=(0, 0, 0), pitch=1), MechanismError, "no '_'")
    raises_one_line(lambda: Joint("H", "H", ("a", "b"), axis=z, point=(0, 0, 0), pitch="1_0"), MechanismError, "pitch: expected a number")
    assert Joint("H", "H", ("a", "b"), axis=np.array(["0", "0", "2"], dtype=object), point=(0, 0, 0), pitch="1").axis == (0.0, 0.0, 1.0)


def test_joint_and_frame_refuse_wrong_values_with_their_key():
    raises_one_line(lambda: Joint("A", ["R"], ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0)), MechanismError, "^type: unknown joint type")
    raises_one_line(lambda: Joint("A", "H", ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0), pitch=10**400), MechanismError, "^pitch: ")
    raises_one_line(lambda: Frame("f", rotation="abc"), MechanismError, "^rotation: ")
    raises_one_line(lambda: Frame("f", rotation=[[1, 0, 0], [0, 1], [0, 0, 1]]), MechanismError, "^rotation: ")
    raises_one_line(lambda: Frame.from_rpy("f", origin=None), MechanismError, "^origin: expected a list of 3 numbers, got None")
    raises_one_line(lambda: Frame.from_rpy("f", rpy=None), MechanismError, "^rpy: ")


def test_from_rpy_says_it_takes_radians():
    doc = Frame.from_rpy.__doc__
    assert "radians" in doc.split("\n")[0] and "np.radians" in doc
    f = Frame.from_rpy("f", rpy=np.radians([0, 0, 90]))
    assert np.allclose(f.rotation, [[0, -1, 0], [1, 0, 0], [0, 0, 1]])


def test_numpy_numbers_are_accepted_where_numbers_are(tmp_path):
    assert Tolerance(rank=np.float32(1e-9)).rank == pytest.approx(1e-9) and type(Tolerance(rank=np.float32(1e-9)).rank) is float
    raises_one_line(lambda: Tolerance(rank=np.True_), RequestError, "rank")
    u = Joint("U", "U", ("a", "b"), point=(0, 0, 0), axes=np.eye(3)[:2])
    assert u.axes == ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    driven = Joint("A", "R", ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0), actuated=np.bool_(True))
    assert driven.actuated is True and driven == Joint("A", "R", ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0), actuated=True)
    raises_one_line(lambda: Joint("A", "R", ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0), actuated=1), MechanismError, "^actuated: ")
    urdf = Path(__file__).parent / "data" / "robots" / "hand" / "four_bar.urdf"
    assert mobility.load(urdf, floating=np.bool_(False)) == mobility.load(urdf, floating=False)


def test_a_mechanism_checks_its_frames_and_expected_block(four_bar):
    raises_one_line(lambda: four_bar.replace(frames=[{"name": "f"}]), MechanismError, r"^frames\[0\]: expected a Frame, got dict")
    raises_one_line(lambda: four_bar.replace(expected="dof: 1"), MechanismError, "^expected: expected an Expected or None, got str")
    raises_one_line(lambda: four_bar.frame_transform("Z"), RequestError, "no frame named 'Z'.*the frames are world")
    assert four_bar.frame_transform("world").translation.tolist() == [0.0, 0.0, 0.0]


@pytest.mark.parametrize("bad", [5, {"j": 5}, None, {"j": ("k", "x")}, {"j": ("k",)}])
def test_a_mechanism_checks_where_its_joints_were_written(bad):
    # a wrong written_at was accepted, then broke the first error message that used it
    raises_one_line(lambda: mobility.Mechanism("m", "g", "s", (mobility.Joint("j", "P", ("g", "s"), axis=(0, 0, 1)),), written_at=bad), mobility.MechanismError, r"^written_at: expected a mapping of joint names to \(key path, line or None\)$")


# -- 2. Expected, Limits, Tolerance ------------------------------------------------------------------------


@pytest.mark.parametrize("fields, key", [
    (dict(dof="1"), "dof"), (dict(dof=-1), "dof"), (dict(mobility=1.0), "mobility"), (dict(idle_dof=True), "idle_dof"),
    (dict(redundant_constraints=[1]), "redundant_constraints"), (dict(gruebler_kutzbach="-2"), "gruebler_kutzbach"),
    (dict(pattern="4R"), "pattern"), (dict(pattern=1), "pattern"), (dict(translations=[[0, 0]]), r"translations\[0\]"),
    (dict(translations="z"), "translations"), (dict(extra=None), "extra"), (dict(extra={"dof": 1}), r"extra\.dof"),
    (dict(extra={3: "x"}), "extra"),
], ids=lambda v: repr(v) if isinstance(v, dict) else None)
def test_expected_checks_its_fields(fields, key):
    raises_one_line(lambda: Expected(**fields), MechanismError, f"^{key}: ")


def test_expected_keeps_valid_fields_and_copies_extra():
    extra = {"actuation": "valid"}
    e = Expected(dof=np.int64(1), pattern="1R", gruebler_kutzbach=-2, translations=[[0, 0, 1]], extra=extra)
    assert (e.dof, type(e.dof), e.translations, e.gruebler_kutzbach) == (1, int, ((0.0, 0.0, 1.0),), -2)
    extra["actuation"] = "redundant"  # the caller's dict changes afterwards: the Expected does not
    assert e.extra == {"actuation": "valid"} and e.items()[-1] == ("actuation", "valid")
    assert Expected(pattern=0).pattern == "0"  # as a file may write it


def test_a_check_with_a_wrong_expected_is_an_error_not_a_failure(four_bar):
    raises_one_line(lambda: mobility.check_mechanism(four_bar.replace(expected=Expected(dof="1"))), MechanismError, "dof")


def test_mechanisms_and_expected_blocks_are_hashable_and_picklable(four_bar):
    assert four_bar.expected is not None and hash(four_bar) == hash(mobility.load(MECHANISMS / "four_bar.yaml"))
    assert len({four_bar, mobility.load(MECHANISMS / "four_bar.yaml")}) == 1
    e = Expected(dof=1, extra={"stiffness": [1, 2]})  # an unhashable value of an extra key
    assert hash(e) == hash(Expected(dof=1, extra={"stiffness": [1, 2]}))
    assert pickle.loads(pickle.dumps(e)) == e and pickle.loads(pickle.dumps(four_bar)) == four_bar


@pytest.mark.parametrize("field, value, shown", [
    ("max_joints", "5", "'5'"), ("max_file_bytes", -1, "-1"), ("max_depth", 0, "0"), ("max_nodes", True, "True"), ("max_copies", 2.0, "2.0"),
])
def test_limits_refuse_what_is_not_a_positive_integer(field, value, shown):
    error = raises_one_line(lambda: Limits(**{field: value}), RequestError)
    assert str(error) == f"Limits: {field}: expected a positive integer, got {shown}"


def test_limits_take_numpy_integers_as_ints():
    limits = Limits(max_joints=np.int64(7))
    assert limits.max_joints == 7 and type(limits.max_joints) is int


# -- 3. a mechanism where one is due, joint names, joint values ----------------------------------------------


@pytest.mark.parametrize("call", [
    lambda m: mobility.gruebler_kutzbach("x.yaml"),
    lambda m: mobility.parallel_model("x.yaml"),
    lambda m: mobility.check_mechanism("x.yaml"),
    lambda m: mobility.locked_dof("x.yaml", []),
    lambda m: mobility.enumerate_actuations(m, poses=["x.yaml"]),
    lambda m: mobility.flexure_spaces("x.yaml"),
    lambda m: mobility.flexure_spaces(mobility.load_flexure(EXAMPLES / "flexure" / "three_rod.yaml"), "0.1"),
], ids=["gruebler_kutzbach", "parallel_model", "check_mechanism", "locked_dof", "enumerate_actuations-poses", "flexure_spaces", "flexure_spaces-threshold"])
def test_a_file_name_or_a_string_where_an_object_is_due_is_a_request_error(call, four_bar):
    raises_one_line(lambda: call(four_bar), RequestError)


def test_locking_refuses_a_string_of_names_and_repeated_names(four_bar):
    assert mobility.locked_dof(four_bar, ["A"]) == 0 and mobility.locked_dof(four_bar, ("A", "B")) == 0  # sequences still work
    raises_one_line(lambda: mobility.locked_dof(four_bar, "AB"), MechanismError, "got the string 'AB'")  # was 0: A and B locked
    raises_one_line(lambda: lock_joints(four_bar, "AB"), MechanismError, "got the string 'AB'")
    raises_one_line(lambda: mobility.locked_dof(four_bar, ["A", "A"]), MechanismError, "'A' is given twice")


def test_the_jacobian_refuses_a_string_of_actuated_names(metrom):
    assert mobility.jacobian(metrom, actuated=["P0", "P1", "P2", "P3", "P4"]).actuated == ("P0", "P1", "P2", "P3", "P4")
    raises_one_line(lambda: mobility.jacobian(metrom, actuated="P0"), MechanismError, "got the string 'P0'")  # was 'unknown joint P'
    raises_one_line(lambda: mobility.parallel_model(metrom, "P0"), MechanismError, "got the string 'P0'")


def test_the_jacobian_checks_its_joint_values_and_assemble_its_displacement(metrom):
    raises_one_line(lambda: mobility.jacobian(metrom, [["a"]] * 5), RequestError, "^q: expected one array of joint values per limb")
    raises_one_line(lambda: mobility.jacobian(metrom, 3), RequestError, "^q: ")
    model = mobility.parallel_model(metrom)
    raises_one_line(lambda: model.assemble(np.zeros(6)), RequestError, r"4x4 homogeneous transform.*shape \(6,\)")
    raises_one_line(lambda: model.assemble("x"), RequestError, "displacement")
    q = model.assemble(np.eye(4))
    assert mobility.jacobian(model, [list(v) for v in q]).rank == 6


# -- 4. actuation ------------------------------------------------------------------------------------------


def test_enumerate_actuations_refuses_a_k_the_limb_mode_contradicts(rps):
    assert mobility.enumerate_actuations(rps, mode="limb", k=3).k == 3  # the number of limbs: agrees with the mode
    raises_one_line(lambda: mobility.enumerate_actuations(rps, mode="limb", k=2), RequestError, "mode 'limb' takes one input in each limb, 3 here")


@pytest.mark.parametrize("k", [3.9, "3", True, np.float64(3)], ids=repr)
def test_enumerate_actuations_wants_an_integer_k(rps, k):
    raises_one_line(lambda: mobility.enumerate_actuations(rps, mode="any", k=k), RequestError, r"^k must be an integer \(inputs per combination\)")
    raises_one_line(lambda: mobility.enumerate_actuations(rps, mode="any", k=-1), RequestError, "^k must be non-negative")


def test_enumerate_actuations_takes_a_numpy_k(rps):
    assert mobility.enumerate_actuations(rps, mode="any", k=np.int64(3)).k == 3


def test_enumerate_actuations_names_samples_and_passes_its_tolerance_on(rps, monkeypatch):
    raises_one_line(lambda: mobility.enumerate_actuations(rps, samples=2.5), RequestError, r"^samples: expected a number of poses")
    import mobility.actuation.rigid as rigid

    seen = []
    monkeypatch.setattr(rigid, "sample_poses", lambda m, n, **kw: seen.append(kw["tol"]) or [])
    tol = Tolerance(rank=1e-9)
    mobility.enumerate_actuations(rps, samples=1, tol=tol)
    assert seen == [tol]


@pytest.mark.parametrize("bad", [np.array([1, 2]), ["limb"], None], ids=repr)
def test_choices_are_strings(four_bar, four_bar_result, bad):
    raises_one_line(lambda: mobility.enumerate_actuations(four_bar, mode=bad), RequestError, naming=("enumerate_actuations", "mode"), shorter_than=300)  # was: truth value of an array is ambiguous
    raises_one_line(lambda: loop_closure(four_bar, method=bad), RequestError, naming=("loop_closure", "method"), shorter_than=300)


# -- 5. finite mobility and sampled poses: seed, steps, randoms ----------------------------------------------


@pytest.mark.parametrize("randoms", [-5, 2.5, "3", True], ids=repr)
def test_finite_mobility_wants_a_non_negative_integer_of_randoms(four_bar, randoms):
    raises_one_line(lambda: mobility.finite_mobility(four_bar, randoms=randoms), RequestError, "randoms: expected a non-negative integer")


def test_finite_mobility_takes_a_numpy_integer_of_randoms(four_bar):
    assert mobility.finite_mobility(four_bar, randoms=np.int64(2)).verdict == "full-cycle"


@pytest.mark.parametrize("seed", [b"abc", -1, 3.5, "A", math.nan, [None], None, True], ids=repr)
def test_finite_mobility_wants_a_non_negative_integer_seed(four_bar, seed):
    raises_one_line(lambda: mobility.finite_mobility(four_bar, seed=seed), RequestError, naming=("finite_mobility", "seed"), shorter_than=300)  # None drew fresh randomness


@pytest.mark.parametrize("seed", [None, -1, 2.0])
def test_sample_poses_refuses_the_same_seeds_as_finite_mobility(four_bar, seed):
    raises_one_line(lambda: sample_poses(four_bar, 1, seed=seed), RequestError, "seed: expected a non-negative integer")


@pytest.mark.parametrize("steps", [b"abc", b"\x01", "abc", [1e300], [2.0], 0.01, [0.01] * 11, itertools.repeat(0.01), [None], np.eye(2)], ids=repr)
def test_finite_mobility_wants_one_to_ten_steps_in_range(four_bar, steps):
    message = str(raises_one_line(lambda: mobility.finite_mobility(four_bar, steps=steps), RequestError, naming=("finite_mobility", "steps"), shorter_than=300))  # b'abc' was steps 97, 98, 99
    assert "tolerances" not in message and f"each at most {MAX_STEP:g}" in message


def test_finite_mobility_takes_steps_as_any_sequence_of_numbers(four_bar):
    assert mobility.finite_mobility(four_bar, steps=np.array([0.05, 0.001, 0.01])).steps == (0.001, 0.01, 0.05)


@pytest.mark.timeout(60)
@pytest.mark.parametrize("randoms", [10**40, 2**63, MAX_RANDOMS + 1, 10**5000], ids=["1e40", "2**63", "MAX+1", "1e5000"])
def test_finite_mobility_bounds_the_random_directions(four_bar, randoms):
    message = str(raises_one_line(lambda: mobility.finite_mobility(four_bar, randoms=randoms), RequestError, naming=("finite_mobility", "randoms"), shorter_than=300))  # was a run that did not end
    assert f"at most {MAX_RANDOMS:,}" in message


@pytest.mark.parametrize("step", [1e300, 10**49, 10**400, 2.0], ids=repr)
def test_sample_poses_refuses_a_step_beyond_its_range(four_bar, step):
    message = str(raises_one_line(lambda: sample_poses(four_bar, 2, step=step), RequestError, naming=("sample_poses", "step"), shorter_than=300))  # was [] with an overflow warning
    assert "(0, 1]" in message


@settings(max_examples=200, deadline=None)
@given(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10, 10**400), st.text(max_size=3), st.binary(max_size=3), st.none(), st.booleans()))
def test_a_step_is_a_real_number_in_range(value):
    number = None if isinstance(value, (bool, str, bytes)) or value is None else value
    expected = number is not None and 0 < number <= MAX_STEP and math.isfinite(number)
    assert (step_value(value) is not None) == expected


# -- 6. finite screws --------------------------------------------------------------------------------------


@pytest.mark.parametrize("call, message", [
    (lambda: finite_screw([0, 0, 1], "abc", 1.0), "point: expected 3 finite numbers, got 'abc'"),
    (lambda: finite_screw([0, 0, 1], [0, 0], 1.0), "point: expected 3 finite numbers, got 2 numbers"),
    (lambda: finite_screw([0, 0, 1], [0, math.nan, 0], 1.0), "point: expected 3 finite numbers, got [0, nan, 0]"),
    (lambda: finite_screw([0, 0, 1], [0, 0, 0], "x"), "angle: expected a finite number, got 'x'"),
    (lambda: finite_screw([0, 0, 1], [0, 0, 0], math.nan), "angle: expected a finite number, got nan"),
    (lambda: finite_screw([0, 0, 1], [0, 0, 0], [1, 2]), "angle: expected a finite number, got [1, 2]"),
    (lambda: finite_screw([0, 0, 1], [0, 0, 0], 10**400), "angle: expected a finite number, got 1000"),
    (lambda: finite_screw([0, 0, 1], [0, 0, 0], 1.0, "y"), "translation: expected a finite number, got 'y'"),
    (lambda: finite_screw([0, 0, 1], [0, 0, 0], 1.0, math.inf), "translation: expected a finite number, got inf"),
    (lambda: triangle_product("abcdef", np.zeros(6)), "screws[0]: expected a 6-vector [w; v] of finite numbers, got 'abcdef'"),
    (lambda: triangle_product(np.zeros(6), np.zeros(5)), "screws[1]: expected a 6-vector [w; v] of finite numbers, got shape (5,)"),
    (lambda: triangle_product(np.zeros(6), [[1, 2], [3]]), "screws[1]: expected a 6-vector [w; v] of finite numbers, got [[1, 2], [3]]"),
    (lambda: triangle_product(object()), "screws[0]: expected a 6-vector [w; v] of finite numbers, got <object object"),
    (lambda: transform_from_finite_screw("x"), "screw: expected a 6-vector [w; v] of finite numbers, got 'x'"),
    (lambda: FiniteScrew("abcdefgh"), "homogeneous: expected 8 finite numbers"),
    (lambda: FiniteScrew(np.zeros(3)), "homogeneous: expected 8 finite numbers, a dual quaternion (q, q0) with q non-zero, got shape (3,)"),
    (lambda: FiniteScrew(None), "homogeneous: expected 8 finite numbers, a dual quaternion (q, q0) with q non-zero, got None"),
    (lambda: FiniteScrew.from_vector("x"), "screw: expected a 6-vector [w; v] of finite numbers, got 'x'"),
    (lambda: FiniteScrew.from_transform("x"), "matrix: expected a 4x4 matrix of finite numbers, got 'x'"),
    (lambda: FiniteScrew.identity().triangle(5), "other: expected a FiniteScrew, got int"),
    (lambda: Limb((ScrewJoint("R", (0, 0, 1)),)).transform("a"), "q: expected 1 finite joint values, got 'a'"),
    (lambda: Limb((ScrewJoint("R", (0, 0, 1)),)).transform([math.nan]), "q: expected 1 finite joint values, got [nan]"),
])
def test_a_bad_finite_screw_argument_is_a_request_error_naming_it(call, message):
    raises_one_line(call, RequestError, naming=(message,))


def test_a_nan_screw_is_refused_not_composed_into_nan():
    raises_one_line(lambda: triangle_product(np.full(6, np.nan), np.zeros(6)), RequestError, r"^screws\[0\]: expected a 6-vector")  # was NaN, silently
    raises_one_line(lambda: triangle_product([1e200] * 6, [1e200] * 6), RequestError, "overflows double precision")  # was a HalfTurnError: the screws are no half-turn
    good = triangle_product([0.2, 0.0, -0.6, 0.3, 1.0, 0.0], [0.1, 0.4, 0.0, 0.0, 0.0, 2.0])
    assert np.all(np.isfinite(good)) and abs(good[2] - (-0.6 + 0.0 + 0.5 * 0.2 * 0.4) / (1 - 0.25 * 0.02)) < 1e-12


def test_a_bad_screw_joint_is_a_mechanism_error_naming_the_key():
    pitch = raises_one_line(lambda: ScrewJoint("H", (0, 0, 1), pitch="x"), MechanismError)
    assert pitch.key == "pitch" and "expected a finite number" in str(pitch)
    point = raises_one_line(lambda: ScrewJoint("R", (0, 0, 1), point=(0, math.nan, 0)), MechanismError)
    assert point.key == "point"
    assert ScrewJoint("H", (0, 0, 2), pitch=0.5).pitch == 0.5


# -- 7. sweeps ---------------------------------------------------------------------------------------------


def test_a_sweep_takes_numpy_integers_and_refuses_floats_and_bools(four_bar):
    vary = ["A=0:20:3"]
    plain = mobility.sweep(four_bar, vary, workers=2, chunk_size=2, max_poses=10)
    numpy = mobility.sweep(four_bar, vary, workers=np.int64(2), chunk_size=np.int32(2), max_poses=np.int64(10))
    assert np.array_equal(plain.dof, numpy.dof)
    for key, bad in (("workers", 2.0), ("workers", True), ("chunk_size", np.float64(2)), ("max_poses", np.True_)):
        raises_one_line(lambda: mobility.sweep(four_bar, vary, **{key: bad}), RequestError, f"{key} must be a positive integer")


@pytest.mark.parametrize("max_poses", [None, "x", [], 0, 201, True, 2.0], ids=repr)
def test_sweep_view_wants_max_poses_in_range(four_bar_sweep, max_poses):
    raises_one_line(lambda: mobility.sweep_view(four_bar_sweep, max_poses=max_poses), RequestError, naming=("sweep_view", "max_poses"), shorter_than=300)  # was TypeError: '<=' not supported


def test_sweep_view_takes_a_numpy_max_poses(four_bar_sweep):
    assert len(mobility.sweep_view(four_bar_sweep, max_poses=np.int64(2)).frames) == 2


@pytest.mark.parametrize("arguments, words", [
    (("four_bar", np.zeros((1, 4))), ("analyse_joint_variables", "expected a Mechanism", "got str")),  # was TypeError: vars()
    ((None, "abc"), ("q: expected finite real joint variables of shape (N, 4)", "got 'abc'")),  # was ValueError from numpy
    ((None, np.zeros(4)), ("q:", "got shape (4,)")),  # was ValueError: all input arrays must have the same shape
    ((None, np.zeros((0, 4))), ("q:", "got shape (0, 4)")),  # was an empty dict
    ((None, np.full((1, 4), np.nan)), ("q:", "got a NaN or an infinity")),  # was AnalysisError: the SVD did not converge
])
def test_analyse_joint_variables_checks_its_arguments_at_the_entry(four_bar, arguments, words):
    from mobility.sweeps import analyse_joint_variables

    mechanism, q = arguments
    raises_one_line(lambda: analyse_joint_variables(four_bar if mechanism is None else mechanism, q), RequestError, naming=words, shorter_than=300)


@pytest.mark.parametrize("options, words", [({"tol": 3}, ("analyse_joint_variables", "tol", "got int")),  # was AttributeError: no 'rank'
                                            ({"transmission": "yes"}, ("transmission: expected True or False, got 'yes'",))])  # was taken as True
def test_analyse_joint_variables_checks_its_options(four_bar, options, words):
    from mobility.sweeps import analyse_joint_variables

    raises_one_line(lambda: analyse_joint_variables(four_bar, np.zeros((2, 4)), **options), RequestError, naming=words, shorter_than=300)
    assert analyse_joint_variables(four_bar, np.zeros((2, 4)).tolist())["dof"].tolist() == [1, 1]  # a nested list of numbers is taken


# -- 8. synthesis ------------------------------------------------------------------------------------------


def _generator():
    yield "3R"


NOT_A_PATTERN = [None, b"3R", 3, 3.5, ["3R"], Path("3R"), "mechanism", "generator"]


def _value(bad, four_bar):
    """The bad value named by ``bad`` (fixtures and generators are made per test)."""
    return {"mechanism": four_bar, "generator": _generator()}.get(bad, bad) if isinstance(bad, str) else bad


@pytest.mark.parametrize("bad", NOT_A_PATTERN, ids=repr)
def test_synthesize_refuses_what_is_not_a_pattern(bad, four_bar):
    raises_one_line(lambda: mobility.synthesize(_value(bad, four_bar)), RequestError, naming=("synthesize", "pattern"), shorter_than=300)  # was AttributeError: no attribute 'factors'


@pytest.mark.parametrize("bad", NOT_A_PATTERN, ids=repr)
def test_named_pattern_refuses_what_is_not_a_name(bad, four_bar):
    message = str(raises_one_line(lambda: named_pattern(_value(bad, four_bar)), RequestError, naming=("named_pattern", "name"), shorter_than=300))
    assert "2T3R, 3T, 3R, 2T1R, 3T1R" in message


@pytest.mark.parametrize("bad", [5, "ab", [None, None]], ids=repr)
def test_named_pattern_refuses_directions_that_are_not_directions(bad):
    raises_one_line(lambda: named_pattern("2T3R", directions=bad), RequestError, naming=("named_pattern", "directions"), shorter_than=300)  # 5 was TypeError: not iterable


def test_named_pattern_reads_a_bounded_part_of_endless_directions():
    raises_one_line(lambda: named_pattern("2T3R", directions=itertools.repeat((1, 0, 0))), mobility.SynthesisError, "the 2T3R pattern takes 2 directions, got 16 or more")


@pytest.mark.parametrize("key, bad", [("joints", 2.5), ("joints", "3"), ("samples", None), ("verify_samples", -1), ("generic_points", True), ("seed", None)], ids=repr)
def test_synthesize_checks_its_counts_and_seed(key, bad):
    raises_one_line(lambda: mobility.synthesize("2T1R", **{key: bad}), RequestError, naming=("synthesize", key), shorter_than=300)


@pytest.mark.parametrize("options, message", [
    ({"samples": 10**400}, "synthesize: samples: expected an integer from 1 to 30, got 1000"),
    ({"samples": 31}, "synthesize: samples: expected an integer from 1 to 30, got 31"),
    ({"verify_samples": 10**400}, "synthesize: verify_samples: expected an integer from 0 to 10, got 1000"),
    ({"generic_points": 51}, "synthesize: generic_points: expected an integer from 0 to 50, got 51"),
])
def test_synthesize_bounds_its_counts_before_the_search(options, message):
    from mobility.synthesis import synthesize

    raises_one_line(lambda: synthesize("3R", **options), SynthesisError, naming=(message,))


@pytest.fixture(scope="module")
def three_r():
    from mobility.synthesis import synthesize

    return synthesize("3R", verify_samples=0)


@pytest.mark.parametrize("options, message", [
    ({"twist_pattern": ()}, "assemble_pkm: twist_pattern: expected a non-empty sequence of finite numbers"),
    ({"twist_pattern": (1.0, "a")}, "assemble_pkm: twist_pattern: expected a non-empty sequence of finite numbers"),
    ({"copies": 0}, "assemble_pkm: copies: expected an integer from 1 to 1665 (3 joints of the limb and 3 per copy within the limit of 5000 joints"),
    ({"copies": 10_000}, "set MOBILITY_MAX_JOINTS to raise it), got 10000"),
    ({"copies": 2.0}, "assemble_pkm: copies: expected an integer from 1 to"),
    ({"twist_deg": math.nan}, "assemble_pkm: twist_deg: expected a finite number of degrees, got nan"),
    ({"height": 0.0}, "assemble_pkm: height: expected a finite positive length, got 0.0"),
    ({"base_radius": "600"}, "assemble_pkm: base_radius: expected a finite positive length, got '600'"),
])
def test_assemble_pkm_checks_its_arguments_at_the_entry(three_r, options, message):
    from mobility.synthesis import assemble_pkm

    raises_one_line(lambda: assemble_pkm(three_r, "S", **options), RequestError, naming=(message,))


@pytest.mark.parametrize("arguments, words", [
    (("3R", "out"), ("write_pkm_files: result: expected a SynthesisResult", "got str")),  # was AttributeError: no 'joints'
    ((None, 3), ("write_pkm_files: folder: expected a folder name", "got int")),  # was TypeError from pathlib
])
def test_write_pkm_files_checks_its_arguments_at_the_entry(three_r, arguments, words):
    from mobility.synthesis import write_pkm_files

    result, folder = arguments
    raises_one_line(lambda: write_pkm_files(three_r if result is None else result, folder), RequestError, naming=words, shorter_than=300)


def test_assemble_pkm_copies_follow_the_joint_limit(three_r, monkeypatch):
    from mobility.synthesis import assemble_pkm

    monkeypatch.setenv("MOBILITY_MAX_JOINTS", "21")  # 3 one-DOF joints of the limb at most, 3 per UPS copy: 6 copies
    assert len(assemble_pkm(three_r, "S", copies=6).joints) == 1 + 18  # the limb S is one joint
    raises_one_line(lambda: assemble_pkm(three_r, "S", copies=7), RequestError, r"copies: expected an integer from 1 to 6 .*MOBILITY_MAX_JOINTS.*got 7$")
    assert len(assemble_pkm(three_r, "S", copies=2, twist_pattern=np.array([1.0, 0.5])).joints) == 1 + 6


# -- 9. pictures, views and reports ------------------------------------------------------------------------


@pytest.mark.parametrize("bad", [None, 5, Path("poses"), "mechanism"], ids=repr)
def test_poses_view_refuses_what_is_not_a_sequence_of_frames(bad, four_bar):
    raises_one_line(lambda: mobility.poses_view(_value(bad, four_bar)), RequestError, naming=("poses_view", "frames"), shorter_than=300)  # was TypeError: not iterable


def test_poses_view_reads_a_bounded_part_of_endless_frames(four_bar, four_bar_result):
    raises_one_line(lambda: mobility.poses_view(itertools.repeat((four_bar, four_bar_result)), max_poses=2), RequestError, r"^3 or more poses is more than a view holds \(max_poses=2\)")


@pytest.mark.parametrize("bad", ["one note", None, [1]], ids=repr)
def test_poses_view_wants_notes_as_a_list_of_strings(bad, four_bar, four_bar_result):
    raises_one_line(lambda: mobility.poses_view([(four_bar, four_bar_result)], notes=bad), RequestError, naming=("poses_view", "notes"), shorter_than=300)  # a string was a note per character


@pytest.mark.parametrize("figsize", [5, math.nan, b"abc", ["A", "A"], np.array([1, 2, 3]), (0.1, 5), (100, 5), (5, math.inf)], ids=repr)
def test_plot_mechanism_wants_a_width_and_a_height_in_range(four_bar, four_bar_result, figsize):
    raises_one_line(lambda: plot_mechanism(four_bar, four_bar_result, figsize=figsize), RequestError, naming=("plot_mechanism", "figsize"), shorter_than=300)
    raises_one_line(lambda: plot_graph(four_bar, four_bar_result, figsize=figsize), RequestError, naming=("plot_graph", "figsize"), shorter_than=300)


def test_plot_mechanism_takes_a_numpy_figsize(four_bar, four_bar_result):
    fig = plot_mechanism(four_bar, four_bar_result, figsize=np.array([4, 3]), views=1)  # was: the truth value of an array is ambiguous
    assert fig.get_size_inches().tolist() == [4.0, 3.0]


@pytest.mark.parametrize("title", [5, b"title", ["a"]], ids=repr)
def test_plot_mechanism_wants_a_string_title(four_bar, four_bar_result, title):
    raises_one_line(lambda: plot_mechanism(four_bar, four_bar_result, title=title), RequestError, naming=("plot_mechanism", "title"), shorter_than=300)  # was AttributeError


@pytest.mark.parametrize("figsize", [(4, 1), (6, 6.6)])
def test_a_long_title_is_cut_to_the_room_of_the_figure(four_bar, four_bar_result, figsize):
    fig = plot_mechanism(four_bar, four_bar_result, title="x" * 10000, figsize=figsize, views=1)  # was "bottom cannot be >= top"
    title = fig._suptitle.get_text()
    assert title.endswith("...") and len(title) <= 600 and fig.subplotpars.top > fig.subplotpars.bottom


@pytest.mark.parametrize("key", ["constraints", "labels", "legend"])
def test_plot_mechanism_wants_bool_flags(four_bar, four_bar_result, key):
    raises_one_line(lambda: plot_mechanism(four_bar, four_bar_result, **{key: np.array([1, 2])}), RequestError, naming=("plot_mechanism", key), shorter_than=300)


def test_plot_graph_with_a_result_that_is_not_one_names_it(four_bar):
    from mobility.report.plotting import plot_graph

    raises_one_line(lambda: plot_graph(four_bar, result=5), RequestError, r"^plot_graph: result: expected a Result \(from mobility.analyze\) or None, got int$")


@pytest.fixture(scope="module")
def figure():
    from matplotlib.figure import Figure

    return Figure(figsize=(1, 1))


@pytest.mark.parametrize("path", [None, b"x.png", np.array([1])], ids=repr)
def test_save_figure_wants_a_file_name(figure, path):
    raises_one_line(lambda: save_figure(figure, path), RequestError, naming=("save_figure", "path"), shorter_than=300)  # was TypeError


@pytest.mark.parametrize("dpi", [-1, 10**40, b"abc", np.array([100]), 150.5, DPI_RANGE[0] - 1, DPI_RANGE[1] + 1, True], ids=repr)
def test_save_figure_wants_a_dpi_in_the_range_of_the_command_line(figure, dpi, tmp_path):
    message = str(raises_one_line(lambda: save_figure(figure, tmp_path / "x.png", dpi=dpi), RequestError, naming=("save_figure", "dpi"), shorter_than=300))
    assert "from 20 to 600" in message and not (tmp_path / "x.png").exists()


def test_save_figure_takes_a_numpy_dpi(figure, tmp_path):
    assert save_figure(figure, tmp_path / "x.png", dpi=np.int64(20)).stat().st_size > 0


@pytest.mark.parametrize("bad", [np.array([1, 2]), 1, "yes", None], ids=repr)
def test_the_limbs_flag_of_markdown_report_is_a_bool(four_bar_result, bad):
    raises_one_line(lambda: markdown_report(four_bar_result, limbs=bad), RequestError, naming=("markdown_report", "limbs"), shorter_than=300)


def test_numpy_bools_are_flags(four_bar_result):
    assert markdown_report(four_bar_result, limbs=np.False_) == markdown_report(four_bar_result, limbs=False)
