"""API inputs: every wrong argument is a one-line MobilityError, numpy numbers are numbers, errors cross processes.

The findings of an audit of the Python API (each test failed before its fix).
"""

from __future__ import annotations

import concurrent.futures
import copy
import inspect
import pickle
from pathlib import Path

import numpy as np
import pytest

import mobility
import mobility.errors as errors
from mobility import Expected, Frame, Joint, Tolerance
from mobility.actuation import lock_joints
from mobility.errors import MechanismError, MechanismFileError, MobilityError, RequestError

from conftest import MECHANISMS

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
ERROR_CLASSES = [obj for obj in vars(errors).values() if inspect.isclass(obj) and issubclass(obj, BaseException) and obj.__module__ == errors.__name__]


@pytest.fixture(scope="module")
def four_bar():
    return mobility.load(MECHANISMS / "four_bar.yaml")


@pytest.fixture(scope="module")
def rps():
    return mobility.load(MECHANISMS / "actuation_3rps.yaml")


@pytest.fixture(scope="module")
def metrom():
    return mobility.load(MECHANISMS / "metrom.yaml")


def one_line_error(call, cls=MobilityError, match=None):
    """Run ``call``: it must raise a ``cls`` (a MobilityError) whose message is one line, and return it."""
    with pytest.raises(cls, match=match) as info:
        call()
    assert isinstance(info.value, MobilityError) and "\n" not in str(info.value)
    return info.value


# 1. joint names are a sequence of names, each once


def test_locking_refuses_a_string_of_names_and_repeated_names(four_bar):
    assert mobility.locked_dof(four_bar, ["A"]) == 0 and mobility.locked_dof(four_bar, ("A", "B")) == 0  # sequences still work
    one_line_error(lambda: mobility.locked_dof(four_bar, "AB"), MechanismError, "got the string 'AB'")  # was 0: A and B locked
    one_line_error(lambda: lock_joints(four_bar, "AB"), MechanismError, "got the string 'AB'")
    one_line_error(lambda: mobility.locked_dof(four_bar, ["A", "A"]), MechanismError, "'A' is given twice")


def test_the_jacobian_refuses_a_string_of_actuated_names(metrom):
    assert mobility.jacobian(metrom, actuated=["P0", "P1", "P2", "P3", "P4"]).actuated == ("P0", "P1", "P2", "P3", "P4")
    one_line_error(lambda: mobility.jacobian(metrom, actuated="P0"), MechanismError, "got the string 'P0'")  # was 'unknown joint P'
    one_line_error(lambda: mobility.parallel_model(metrom, "P0"), MechanismError, "got the string 'P0'")


# 2. enumerate_actuations and finite_mobility check their numbers


def test_enumerate_actuations_refuses_a_k_the_limb_mode_contradicts(rps):
    assert mobility.enumerate_actuations(rps, mode="limb", k=3).k == 3  # the number of limbs: agrees with the mode
    one_line_error(lambda: mobility.enumerate_actuations(rps, mode="limb", k=2), RequestError, "mode 'limb' takes one input in each limb, 3 here")


@pytest.mark.parametrize("k", [3.9, "3", True, np.float64(3)], ids=repr)
def test_enumerate_actuations_wants_an_integer_k(rps, k):
    one_line_error(lambda: mobility.enumerate_actuations(rps, mode="any", k=k), RequestError, r"^k must be an integer \(inputs per combination\)")
    one_line_error(lambda: mobility.enumerate_actuations(rps, mode="any", k=-1), RequestError, "^k must be non-negative")


def test_enumerate_actuations_takes_a_numpy_k(rps):
    assert mobility.enumerate_actuations(rps, mode="any", k=np.int64(3)).k == 3


def test_enumerate_actuations_names_samples_and_passes_its_tolerance_on(rps, monkeypatch):
    one_line_error(lambda: mobility.enumerate_actuations(rps, samples=2.5), RequestError, r"^samples: expected a number of poses")
    import mobility.actuation.rigid as rigid

    seen = []
    monkeypatch.setattr(rigid, "sample_poses", lambda m, n, **kw: seen.append(kw["tol"]) or [])
    tol = Tolerance(rank=1e-9)
    mobility.enumerate_actuations(rps, samples=1, tol=tol)
    assert seen == [tol]


@pytest.mark.parametrize("randoms", [-5, 2.5, "3", True], ids=repr)
def test_finite_mobility_wants_a_non_negative_integer_of_randoms(four_bar, randoms):
    one_line_error(lambda: mobility.finite_mobility(four_bar, randoms=randoms), RequestError, "randoms: expected a non-negative integer")


def test_finite_mobility_takes_a_numpy_integer_of_randoms(four_bar):
    assert mobility.finite_mobility(four_bar, randoms=np.int64(2)).verdict == "full-cycle"


# 3. Expected checks its fields, copies its extra keys, and hashes


@pytest.mark.parametrize("fields, key", [
    (dict(dof="1"), "dof"), (dict(dof=-1), "dof"), (dict(mobility=1.0), "mobility"), (dict(idle_dof=True), "idle_dof"),
    (dict(redundant_constraints=[1]), "redundant_constraints"), (dict(gruebler_kutzbach="-2"), "gruebler_kutzbach"),
    (dict(pattern="4R"), "pattern"), (dict(pattern=1), "pattern"), (dict(translations=[[0, 0]]), r"translations\[0\]"),
    (dict(translations="z"), "translations"), (dict(extra=None), "extra"), (dict(extra={"dof": 1}), r"extra\.dof"),
    (dict(extra={3: "x"}), "extra"),
], ids=lambda v: repr(v) if isinstance(v, dict) else None)
def test_expected_checks_its_fields(fields, key):
    one_line_error(lambda: Expected(**fields), MechanismError, f"^{key}: ")


def test_expected_keeps_valid_fields_and_copies_extra():
    extra = {"actuation": "valid"}
    e = Expected(dof=np.int64(1), pattern="1R", gruebler_kutzbach=-2, translations=[[0, 0, 1]], extra=extra)
    assert (e.dof, type(e.dof), e.translations, e.gruebler_kutzbach) == (1, int, ((0.0, 0.0, 1.0),), -2)
    extra["actuation"] = "redundant"  # the caller's dict changes afterwards: the Expected does not
    assert e.extra == {"actuation": "valid"} and e.items()[-1] == ("actuation", "valid")
    assert Expected(pattern=0).pattern == "0"  # as a file may write it


def test_a_check_with_a_wrong_expected_is_an_error_not_a_failure(four_bar):
    one_line_error(lambda: mobility.check_mechanism(four_bar.replace(expected=Expected(dof="1"))), MechanismError, "dof")


def test_mechanisms_and_expected_blocks_are_hashable_and_picklable(four_bar):
    assert four_bar.expected is not None and hash(four_bar) == hash(mobility.load(MECHANISMS / "four_bar.yaml"))
    assert len({four_bar, mobility.load(MECHANISMS / "four_bar.yaml")}) == 1
    e = Expected(dof=1, extra={"stiffness": [1, 2]})  # an unhashable value of an extra key
    assert hash(e) == hash(Expected(dof=1, extra={"stiffness": [1, 2]}))
    assert pickle.loads(pickle.dumps(e)) == e and pickle.loads(pickle.dumps(four_bar)) == four_bar


# 4. every error pickles and copies: it crosses a process pool


SAMPLES = [
    errors.MobilityError("something went wrong"),
    errors.MechanismError("joints[1].axis", "expected a non-zero direction"),
    errors.MechanismFileError("joints[1].axis", "expected a non-zero direction", file="m.yaml", line=7),
    errors.MechanismCheckFailed("m.yaml: dof: expected 3, found 2"),
    errors.RequestError("--tol must lie in [1e-11, 1e-05), got 2"),
    errors.SynthesisError("unknown motion pattern '9X'"),
    errors.PlotFormatError("x.gif: cannot tell the picture type"),
    errors.AnalysisError("the decomposition did not converge"),
    errors.HalfTurnError("a half-turn has no finite quasi-vector"),
    errors.MissingExtraError("the 3D view", "plotly", "view"),
    errors.PlottingUnavailableError("broken"),
]


def test_the_samples_cover_every_error_class():
    assert {type(e) for e in SAMPLES} == set(ERROR_CLASSES)


@pytest.mark.parametrize("error", SAMPLES, ids=lambda e: type(e).__name__)
@pytest.mark.parametrize("how", ["pickle", "copy", "deepcopy"])
def test_every_error_pickles_and_copies_with_its_message_and_attributes(error, how):
    again = {"pickle": lambda e: pickle.loads(pickle.dumps(e)), "copy": copy.copy, "deepcopy": copy.deepcopy}[how](error)
    assert type(again) is type(error) and again is not error
    assert str(again) == str(error) and again.args == error.args and vars(again) == vars(error)


def test_a_bad_document_in_a_worker_process_reaches_the_caller():
    with concurrent.futures.ProcessPoolExecutor(1) as pool:
        future = pool.submit(mobility.loads, "name: x\nground: g\n", "bad.yaml")
        error = future.exception(timeout=120)
        assert pool.submit(len, "ok").result(timeout=120) == 2  # the pool survived
    assert type(error) is MechanismFileError and error.file == "bad.yaml" and str(error).startswith("bad.yaml")


# 5. the error classes at the top level


def test_every_error_class_is_exported_at_the_top_level():
    for cls in ERROR_CLASSES:
        assert getattr(mobility, cls.__name__) is cls and cls.__name__ in mobility.__all__
    assert set(mobility.__all__) <= set(dir(mobility))


# 6. wrong arguments are MobilityErrors, never raw exceptions


def test_joint_and_frame_refuse_wrong_values_with_their_key():
    one_line_error(lambda: Joint("A", ["R"], ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0)), MechanismError, "^type: unknown joint type")
    one_line_error(lambda: Joint("A", "H", ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0), pitch=10**400), MechanismError, "^pitch: ")
    one_line_error(lambda: Frame("f", rotation="abc"), MechanismError, "^rotation: ")
    one_line_error(lambda: Frame("f", rotation=[[1, 0, 0], [0, 1], [0, 0, 1]]), MechanismError, "^rotation: ")
    one_line_error(lambda: Frame.from_rpy("f", origin=None), MechanismError, "^origin: expected a list of 3 numbers, got None")
    one_line_error(lambda: Frame.from_rpy("f", rpy=None), MechanismError, "^rpy: ")


def test_a_mechanism_checks_its_frames_and_expected_block(four_bar):
    one_line_error(lambda: four_bar.replace(frames=[{"name": "f"}]), MechanismError, r"^frames\[0\]: expected a Frame, got dict")
    one_line_error(lambda: four_bar.replace(expected="dof: 1"), MechanismError, "^expected: expected an Expected or None, got str")
    one_line_error(lambda: four_bar.frame_transform("Z"), RequestError, "no frame named 'Z'.*the frames are world")
    assert four_bar.frame_transform("world").translation.tolist() == [0.0, 0.0, 0.0]


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
    one_line_error(lambda: call(four_bar), RequestError)


def test_the_jacobian_checks_its_joint_values_and_assemble_its_displacement(metrom):
    one_line_error(lambda: mobility.jacobian(metrom, [["a"]] * 5), RequestError, "^q: expected one array of joint values per limb")
    one_line_error(lambda: mobility.jacobian(metrom, 3), RequestError, "^q: ")
    model = mobility.parallel_model(metrom)
    one_line_error(lambda: model.assemble(np.zeros(6)), RequestError, r"4x4 homogeneous transform.*shape \(6,\)")
    one_line_error(lambda: model.assemble("x"), RequestError, "displacement")
    q = model.assemble(np.eye(4))
    assert mobility.jacobian(model, [list(v) for v in q]).rank == 6


# 7. numpy scalars and arrays are numbers


def test_numpy_numbers_are_accepted_where_numbers_are(tmp_path):
    assert Tolerance(rank=np.float32(1e-9)).rank == pytest.approx(1e-9) and type(Tolerance(rank=np.float32(1e-9)).rank) is float
    one_line_error(lambda: Tolerance(rank=np.True_), RequestError, "rank")
    u = Joint("U", "U", ("a", "b"), point=(0, 0, 0), axes=np.eye(3)[:2])
    assert u.axes == ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    driven = Joint("A", "R", ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0), actuated=np.bool_(True))
    assert driven.actuated is True and driven == Joint("A", "R", ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0), actuated=True)
    one_line_error(lambda: Joint("A", "R", ("a", "b"), axis=(0, 0, 1), point=(0, 0, 0), actuated=1), MechanismError, "^actuated: ")
    urdf = Path(__file__).parent / "data" / "robots" / "hand" / "four_bar.urdf"
    assert mobility.load(urdf, floating=np.bool_(False)) == mobility.load(urdf, floating=False)


def test_a_sweep_takes_numpy_integers_and_refuses_floats_and_bools(four_bar):
    vary = ["A=0:20:3"]
    plain = mobility.sweep(four_bar, vary, workers=2, chunk_size=2, max_poses=10)
    numpy = mobility.sweep(four_bar, vary, workers=np.int64(2), chunk_size=np.int32(2), max_poses=np.int64(10))
    assert np.array_equal(plain.dof, numpy.dof)
    for key, bad in (("workers", 2.0), ("workers", True), ("chunk_size", np.float64(2)), ("max_poses", np.True_)):
        one_line_error(lambda: mobility.sweep(four_bar, vary, **{key: bad}), RequestError, f"{key} must be a positive integer")


# 8. Frame.from_rpy takes radians, and says so


def test_from_rpy_says_it_takes_radians():
    doc = Frame.from_rpy.__doc__
    assert "radians" in doc.split("\n")[0] and "np.radians" in doc
    f = Frame.from_rpy("f", rpy=np.radians([0, 0, 90]))
    assert np.allclose(f.rotation, [[0, -1, 0], [1, 0, 0], [0, 0, 1]])


# 9. a flexure document given to the mechanism loader says what to use


def test_loading_a_flexure_document_as_a_mechanism_names_load_flexure():
    error = one_line_error(lambda: mobility.load(EXAMPLES / "flexure" / "three_rod.yaml"), MechanismFileError, "a flexure document")
    assert "mobility.load_flexure" in str(error) and "mobility actuation" in str(error) and error.key == "elements"
    assert mobility.load_flexure(EXAMPLES / "flexure" / "three_rod.yaml").elements


@pytest.mark.parametrize("bad", [5, {"j": 5}, None, {"j": ("k", "x")}, {"j": ("k",)}])
def test_a_mechanism_checks_where_its_joints_were_written(bad):
    # a wrong written_at was accepted, then broke the first error message that used it
    with pytest.raises(mobility.MechanismError, match=r"^written_at: expected a mapping of joint names to \(key path, line or None\)$"):
        mobility.Mechanism("m", "g", "s", (mobility.Joint("j", "P", ("g", "s"), axis=(0, 0, 1)),), written_at=bad)
