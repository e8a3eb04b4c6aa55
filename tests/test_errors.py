"""Errors: every class of ``mobility.errors`` is a MobilityError, and the command line turns each into one line and status 2."""

from __future__ import annotations

import concurrent.futures
import copy
import inspect
import pickle
import sys

import pytest

import mobility
import mobility.cli.analyze
import mobility.errors as errors
from mobility.cli import build_parser, main
from mobility.core.tolerance import Tolerance
from mobility.errors import MechanismFileError, MobilityError, PlotFormatError, RequestError, SynthesisError

from conftest import MECHANISMS

ERROR_CLASSES = [obj for obj in vars(errors).values() if inspect.isclass(obj) and issubclass(obj, BaseException) and obj.__module__ == errors.__name__]

# One instance of each class, as the package raises it (a new class needs a line here).
SAMPLES = {
    errors.MobilityError: errors.MobilityError("something went wrong"),
    errors.MechanismError: errors.MechanismError("joints[1].axis", "expected a non-zero direction"),
    errors.MechanismFileError: errors.MechanismFileError("joints[1].axis", "expected a non-zero direction", file="m.yaml", line=7),
    errors.MechanismCheckFailed: errors.MechanismCheckFailed("m.yaml: dof: expected 3, found 2"),
    errors.RequestError: errors.RequestError("--tol must lie in [1e-11, 1e-05), got 2"),
    errors.SynthesisError: errors.SynthesisError("unknown motion pattern '9X'"),
    errors.PlotFormatError: errors.PlotFormatError("x.gif: cannot tell the picture type"),
    errors.AnalysisError: errors.AnalysisError("the decomposition did not converge"),
    errors.HalfTurnError: errors.HalfTurnError("a half-turn has no finite quasi-vector"),
    errors.MissingExtraError: errors.MissingExtraError("the 3D view", "plotly", "view"),
    errors.PlottingUnavailableError: errors.PlottingUnavailableError(),
}


def test_every_error_class_is_a_mobility_error():
    names = {c.__name__ for c in ERROR_CLASSES}
    assert {"MobilityError", "MechanismFileError", "RequestError", "MissingExtraError"} <= names  # the scan sees the classes
    assert [c.__name__ for c in ERROR_CLASSES if not issubclass(c, MobilityError)] == []
    # the classes, and the helpers of a message: names, a close name, one line, a value cut short, an argument quoted, a control character found,
    # and the name the package is installed by (install hints)
    helpers = {"name_list", "did_you_mean", "one_line", "clipped", "shown_argument", "control_character_problem", "name_problem", "counted",
               "TERMINAL_CONTROL", "DISTRIBUTION"}
    assert set(errors.__all__) == names | helpers


def test_every_error_class_has_a_sample():
    assert set(SAMPLES) == set(ERROR_CLASSES)
    assert all(type(e) is c for c, e in SAMPLES.items())


@pytest.mark.parametrize("cls", ERROR_CLASSES, ids=lambda c: c.__name__)
def test_the_command_line_prints_each_error_on_one_line_with_status_2(cls, monkeypatch, capsys):
    error = SAMPLES[cls]

    def run(args):
        raise error

    monkeypatch.setattr(mobility.cli.analyze, "run", run)
    assert main(["analyze", str(MECHANISMS / "four_bar.yaml")]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err == f"mobility: {error}\n"


def test_a_missing_extra_says_what_to_install(monkeypatch, capsys, tmp_path):
    monkeypatch.setitem(sys.modules, "plotly.io", None)  # importing it now fails as if plotly were absent
    assert main(["view", str(MECHANISMS / "four_bar.yaml"), "-o", str(tmp_path / "v.html")]) == 2
    assert capsys.readouterr().err == "mobility: the 3D view needs plotly, which is not installed: pip install 'mechanism-mobility[view]'\n"
    assert not (tmp_path / "v.html").exists()


BAD_REQUESTS = [
    (["analyze", str(MECHANISMS / "four_bar.yaml"), "--tol", "2"], RequestError, "--tol must lie in [1e-11, 1e-05), got 2"),
    (["synthesize", "9X"], SynthesisError, "unknown motion pattern '9X'"),
    (["synthesize", "3T", "--point", "1,2"], SynthesisError, "--point: expected three comma-separated numbers, got '1,2'"),
    (["analyze", "no-such-file.yaml"], MechanismFileError, "no-such-file.yaml: no such file"),
    (["plot", str(MECHANISMS / "four_bar.yaml"), "-o", "four_bar.gif"], PlotFormatError, "four_bar.gif: cannot tell the picture type"),
]


@pytest.mark.parametrize("argv, cls, message", BAD_REQUESTS, ids=[f"{a[0]}-{c.__name__}" for a, c, _ in BAD_REQUESTS])
def test_bad_requests_raise_their_class_and_end_in_one_line(argv, cls, message, capsys):
    args = build_parser().parse_args(argv)
    with pytest.raises(cls) as raised:  # the route the command line takes raises exactly this kind
        args.run(args)
    assert str(raised.value).startswith(message)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err == f"mobility: {raised.value}\n"


def test_a_bad_file_names_file_line_and_key(write_yaml, capsys):
    path = write_yaml("name: x\nground: g\nend_effector: e\njoints:\n  - {name: A, type: R, links: [g, e], axis: [0, 0, 0], point: [0, 0, 0]}\n")
    assert main(["analyze", str(path)]) == 2
    assert capsys.readouterr().err == f"mobility: {path}:5: joints[0].axis: expected a non-zero direction, got [0, 0, 0]\n"


@pytest.mark.parametrize("fields", [{"rank": 2.0}, {"rank": 0.0}, {"near_singular": 1e-9}, {"inexact": 1e-6}])
def test_a_tolerance_out_of_order_is_a_request_error(fields):
    with pytest.raises(RequestError, match="0 < inexact <= rank < near_singular < 1"):
        Tolerance(**fields)


def test_name_lists_in_messages_stay_short():
    assert errors.name_list(["A", "B"]) == "A, B"
    assert errors.name_list((f"J{i}" for i in range(5000))) == "J0, J1, J2, J3, J4, J5, J6, J7, J8, J9, J10, J11, ... (5000 in all)"
    assert errors.name_list([], empty="nothing") == "nothing"



def test_a_missing_extra_says_what_to_install_without_repeating_the_import_error():
    plain = errors.MissingExtraError("reading MJCF files", "mujoco", "mujoco", "No module named 'mujoco'")
    assert str(plain) == "reading MJCF files needs mujoco, which is not installed: pip install 'mechanism-mobility[mujoco]'"
    dask = errors.MissingExtraError("running a sweep on a dask cluster", "dask[distributed]", "dask", "No module named 'dask.distributed'")
    assert str(dask) == "running a sweep on a dask cluster needs dask[distributed], which is not installed: pip install 'mechanism-mobility[dask]'"
    # another module failing inside the package is worth saying
    broken = errors.MissingExtraError("the 3D view", "plotly", "view", "No module named 'narwhals'")
    assert str(broken).endswith("which is not installed (No module named 'narwhals'): pip install 'mechanism-mobility[view]'")


@pytest.mark.parametrize("call, message", [
    (lambda m: mobility.analyze("four_bar.yaml"), "analyze: expected a Mechanism (from mobility.load or built in code), got str"),
    (lambda m: mobility.analyze(m, tol=1e-9), "analyze: tol must be a Tolerance (e.g. Tolerance(rank=1e-9)), got float"),
    (lambda m: mobility.loop_closure({"joints": []}), "loop_closure: expected a Mechanism (from mobility.load or built in code), got dict"),
    (lambda m: mobility.finite_mobility(None), "finite_mobility: expected a Mechanism (from mobility.load or built in code), got NoneType"),
    (lambda m: mobility.check_actuation([m]), "check_actuation: expected a Mechanism (from mobility.load or built in code), got list"),
    (lambda m: mobility.enumerate_actuations(m, tol="loose"), "enumerate_actuations: tol must be a Tolerance (e.g. Tolerance(rank=1e-9)), got str"),
    (lambda m: mobility.jacobian("m"), "jacobian: expected a Mechanism (from mobility.load or built in code), got str"),
    (lambda m: mobility.load(3), "load: expected a file name (str or Path), got int"),
    (lambda m: mobility.loads(b"name: x"), "loads: expected the text of a mechanism file (str), got bytes"),
    (lambda m: mobility.Tolerance(rank="1e-8"), "Tolerance: rank must be a finite number, got '1e-8'"),
    (lambda m: mobility.Tolerance(closure=float("inf")), "Tolerance: closure must be a finite number, got inf"),
])
def test_a_public_function_given_the_wrong_kind_of_argument_says_so_in_one_error(call, message):
    m = mobility.load(MECHANISMS / "four_bar.yaml")
    with pytest.raises(errors.RequestError) as caught:
        call(m)
    assert str(caught.value) == message


def _api_misuse():
    import mobility
    from mobility.core.model import Mechanism
    from mobility.core.poses import sample_poses
    from mobility.report.markdown import markdown_report
    from mobility.report.plotting import save_figure
    from mobility.report.text import json_report, text_report

    bar = mobility.load(MECHANISMS / "four_bar.yaml")
    return [
        (lambda: Mechanism("x", "g", "b", None), "joints: expected a sequence of Joints, got NoneType"),  # was a TypeError
        (lambda: Mechanism("x", "g", "b", "AB"), "joints: expected a sequence of Joints, got str"),
        (lambda: Mechanism("x", "g", "b", bar.joints, frames=3), "frames: expected a sequence of Frames, got int"),
        (lambda: sample_poses(bar, "x"), "count: expected a number of poses in [0, 100,000], got 'x'"),
        (lambda: sample_poses(bar, 10**9), "count: expected a number of poses in [0, 100,000], got 1000000000"),  # was a walk of a billion poses
        (lambda: sample_poses(bar, 2, step="a"), "step: expected a positive joint-space distance, got 'a'"),
        (lambda: sample_poses(bar, 2, step=float("inf")), "step: expected a positive joint-space distance, got inf"),
        (lambda: sample_poses(bar, 2, seed="a"), "seed: expected a non-negative integer, got 'a'"),
        (lambda: text_report(None), "text_report: expected a Result (from mobility.analyze), got NoneType"),  # was an AttributeError
        (lambda: json_report(bar), "json_report: expected a Result (from mobility.analyze), got Mechanism"),
        (lambda: markdown_report(3), "markdown_report: expected a Result (from mobility.analyze), got int"),
        (lambda: save_figure(None, "x.png"), "save_figure: expected a matplotlib Figure, got NoneType"),
    ]


def test_a_wrong_argument_to_the_api_is_one_of_the_project_s_errors():
    from mobility.errors import MobilityError

    for call, message in _api_misuse():
        with pytest.raises(MobilityError) as info:
            call()
        assert str(info.value) == message


def test_no_reader_takes_a_number_for_a_file_descriptor_of_the_caller(tmp_path):
    import os

    from mobility.flexure.loader import load_flexure, loads_flexure
    from mobility.io.files import read_capped
    from mobility.io.yaml_source import parse_yaml, read_text

    fd = os.open(MECHANISMS / "four_bar.yaml", os.O_RDONLY)
    try:
        for call, message in [
            (lambda: load_flexure(fd), "load_flexure: expected a file name (str or Path), got int"),  # read the descriptor and closed it
            (lambda: load_flexure(True), "load_flexure: expected a file name (str or Path), got bool"),  # True is descriptor 1: stdout
            (lambda: read_text(fd), "read: expected a file name (str or Path), got int"),
            (lambda: read_capped(None), "read: expected a file name (str or Path), got NoneType"),
            (lambda: read_capped(str(tmp_path / "a\x00b.yaml")), "read: expected a file name without a NUL character"),
            (lambda: loads_flexure(3), "loads_flexure: expected the text of a flexure document (str), got int"),
            (lambda: parse_yaml(3), "parse_yaml: expected the text of a document (str), got int"),
        ]:
            with pytest.raises(RequestError) as info:
                call()
            assert str(info.value).startswith(message)
        assert os.fstat(fd) and os.fstat(1)  # the caller's descriptors are still open
    finally:
        os.close(fd)


# -- every error pickles and copies: it crosses a process pool ------------------------------------------------


@pytest.mark.parametrize("error", [*SAMPLES.values(), errors.PlottingUnavailableError("broken")], ids=lambda e: type(e).__name__ + ("-detail" if str(e).endswith("broken") else ""))
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


def test_every_error_class_is_exported_at_the_top_level():
    for cls in ERROR_CLASSES:
        assert getattr(mobility, cls.__name__) is cls and cls.__name__ in mobility.__all__
    assert set(mobility.__all__) <= set(dir(mobility))


def test_a_request_error_carries_its_fields_and_writes_its_message_from_them():
    import copy
    import pickle

    m = mobility.load(MECHANISMS / "four_bar.yaml")
    with pytest.raises(RequestError) as caught:
        mobility.analyze("four_bar.yaml")
    err = caught.value
    assert (err.caller, err.argument, err.expected, err.got) == ("analyze", "", "a Mechanism (from mobility.load or built in code)", "str")
    with pytest.raises(RequestError) as caught:
        mobility.plot_mechanism(m, labels=1)
    assert (caught.value.caller, caught.value.argument, caught.value.got) == ("plot_mechanism", "labels", "1")
    built = RequestError("give fewer", caller="sweep_view", argument="max_poses", expected="an integer from 1 to 200", got=0)
    assert str(built) == "sweep_view: max_poses: expected an integer from 1 to 200, got 0; give fewer"  # a count of 0 is shown, not dropped
    for copied in (pickle.loads(pickle.dumps(built)), copy.copy(built)):
        assert (str(copied), copied.argument, copied.got, copied.problem) == (str(built), "max_poses", "0", "give fewer")
    assert str(RequestError("--tol must lie in [1e-11, 1e-05), got 2")) == "--tol must lie in [1e-11, 1e-05), got 2"  # a message written whole


def test_robot_options_for_a_yaml_file_are_refused_in_one_place_named_as_the_caller_wrote_them():
    from mobility.io.loader import read_file

    path = str(MECHANISMS / "four_bar.yaml")
    with pytest.raises(RequestError) as caught:
        mobility.load(path, floating=True, ground="base")
    assert str(caught.value) == f"floating, ground: options of robot description files (MJCF, URDF), not of the mechanism file {path}"
    with pytest.raises(RequestError) as caught:
        read_file(path, spelling={"ground": "--ground", "floating": "--floating"}, floating=True, ground="base")
    assert caught.value.argument == "--ground, --floating"  # the command line's order and spelling
    read = read_file(path)
    assert read.files == (path,) and read.notes == () and read.mechanism == mobility.load(path)
