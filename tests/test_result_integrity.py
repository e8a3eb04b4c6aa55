"""Results stay what they were computed as: read-only arrays, pickling at any time, drawn only with their own mechanism.

Every result (:class:`~mobility.core.result.Result`, the sweep's, the finite
analysis's, the actuation verdict's, and what they hold) keeps its arrays
read-only, also those computed on first access and those restored by a
pickle round trip (what dask does) or a deep copy; it pickles and deep-copies
whatever has been read of it; and a view or a picture refuses a result
computed for another mechanism than the one drawn.
"""

from __future__ import annotations

import copy
import inspect
import pickle
from functools import cached_property
from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import mobility  # noqa: E402
from mobility.actuation import check_actuation  # noqa: E402
from mobility.core.frozen import ReadOnlyArrays, read_only  # noqa: E402
from mobility.core.result import ScrewAxis  # noqa: E402
from mobility.errors import RequestError  # noqa: E402
from mobility.finite import finite_mobility  # noqa: E402
from mobility.report.plotting import plot_graph, plot_mechanism  # noqa: E402
from mobility.report.text import text_report  # noqa: E402
from mobility.view import mechanism_view, poses_view  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"


def _load(name: str) -> mobility.Mechanism:
    return mobility.load(MECHANISMS / name)


def _read_everything(obj: object) -> None:
    """Read every property and cached property of ``obj`` (what a report, a picture or a user may read)."""
    for cls in type(obj).__mro__:
        for name, attr in vars(cls).items():
            if isinstance(attr, (property, cached_property)) and not name.startswith("__"):
                getattr(obj, name)


def _walk(obj: object, path: str, members):
    """Every ndarray reachable from ``obj`` through tuples, lists, dicts and what ``members(obj)`` gives (``(name, value)`` pairs), with its path."""
    if isinstance(obj, np.ndarray):
        yield path, obj
    elif isinstance(obj, (tuple, list)):
        for i, x in enumerate(obj):
            yield from _walk(x, f"{path}[{i}]", members)
    elif isinstance(obj, dict):
        for k, x in obj.items():
            yield from _walk(x, f"{path}[{k!r}]", members)
    else:
        for name, value in members(obj):
            yield from _walk(value, f"{path}.{name}", members)


def _result_members(obj: object):
    """The attributes of a ReadOnlyArrays result, every property read first; nothing of another object."""
    if not isinstance(obj, ReadOnlyArrays):
        return ()
    _read_everything(obj)
    return list(vars(obj).items())


def _arrays(obj: object, path: str = "result"):
    """Every ndarray reachable from ``obj`` through results, tuples and mappings, each with its path; reads everything first."""
    return _walk(obj, path, _result_members)


def _writable(obj: object) -> list[str]:
    """The paths of the arrays reachable from ``obj`` that something could write into (the array or an array it views)."""
    out = []
    for path, a in _arrays(obj):
        base = a
        while isinstance(base, np.ndarray):
            if base.flags.writeable:
                out.append(path)
                break
            base = base.base
    return out


@pytest.fixture(scope="module")
def results():
    """One of each result, every lazy part read."""
    head = _load("3prs_tilted.yaml")
    rps = _load("actuation_3rps.yaml")
    out = {
        "Result": mobility.analyze(head),
        "ActuationCheck": check_actuation(rps, [j.name for j in rps.joints if j.actuated]),
        "SweepResult": mobility.sweep(_load("parallelogram.yaml"), ["O1=0:360:13"]),
        "FiniteMobility": finite_mobility(_load("3upu_singular.yaml")),
    }
    for r in out.values():
        list(_arrays(r))
    return out


# -- 1. arrays are read-only ---------------------------------------------------


def test_the_axes_of_a_result_are_read_only_and_its_json_keeps_its_numbers():
    r = mobility.analyze(_load("3prs.yaml"))
    before = r.to_dict()
    for array in (r.rotations[0].axis, r.rotations[0].point, r.twists, r.wrenches, r.translations, r.couples, r.reference_point,
                  r.limbs[0].rotations[0].axis, r.limbs[0].forces[0].point, r.limbs[0].twists):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 99.0
    assert r.to_dict() == before
    assert _writable(r) == []


@pytest.mark.parametrize("kind", ["Result", "ActuationCheck", "SweepResult", "FiniteMobility"])
def test_no_array_reachable_from_a_result_can_be_written(results, kind):
    r = results[kind]
    assert _writable(r) == []
    assert len(list(_arrays(r))) > 3


def test_the_arrays_named_in_the_audit_are_read_only(results):
    check, sweep, finite = results["ActuationCheck"], results["SweepResult"], results["FiniteMobility"]
    for array in (check.constraint_forces[0].axis, check.inputs[0].wrench, check.inputs[0].axis.point, check.constraint_wrenches,
                  sweep.values, finite.probes[0].direction, finite.branches[0].tangent):
        with pytest.raises(ValueError, match="read-only"):
            array.flat[0] = 42.0
    with pytest.raises(ValueError, match="read-only"):
        sweep.changes[0] = (0, 1, 0)


def test_a_sweeps_values_feed_its_rows_and_singular_poses_unchanged():
    sweep = mobility.sweep(_load("parallelogram.yaml"), ["O1=0:360:13"])
    with pytest.raises(ValueError, match="read-only"):
        sweep.values[4, 0] = 1e9
    assert sweep.row(4)["O1"] == 120.0 and sweep.column("O1")[4] == 120.0
    assert [p.values for p in sweep.singular] == [(120.0,), (300.0,)]


def test_an_axis_copies_a_writable_array_it_is_given_and_leaves_the_callers_alone():
    mine = np.array([0.0, 0.0, 1.0])
    a = ScrewAxis(mine, np.zeros(3), 0.0, "rotation")
    mine[2] = 5.0
    assert mine.flags.writeable and a.axis.tolist() == [0.0, 0.0, 1.0] and not a.axis.flags.writeable
    frozen = read_only(np.ones(2))
    assert ScrewAxis(frozen, frozen, 0.0, "rotation").axis is frozen  # nothing can write into it: kept, not copied
    view = np.zeros(4)[:3]
    view.setflags(write=False)  # read-only, but its base is not: copied
    assert ScrewAxis(view, view, 0.0, "rotation").point.base is None


# -- 2. and 3. pickles and deep copies -------------------------------------------


@pytest.mark.parametrize("kind", ["Result", "ActuationCheck", "SweepResult", "FiniteMobility"])
@pytest.mark.parametrize("restore", [lambda r: pickle.loads(pickle.dumps(r)), copy.deepcopy, copy.copy], ids=["pickle", "deepcopy", "copy"])
def test_a_result_read_in_full_pickles_and_copies_with_read_only_arrays(results, kind, restore):
    r = results[kind]
    again = restore(r)
    assert again.to_dict() == r.to_dict()
    assert _writable(again) == []


def test_an_unpickled_result_keeps_its_json_when_written_to():
    r = mobility.analyze(_load("3prs.yaml"))
    r.twists, r.limbs  # computed before the round trip
    r2 = pickle.loads(pickle.dumps(r))
    for array in (r2.twists, r2.reference_point, r2.rotations[0].axis, r2.limbs[0].wrenches):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 42.0
    assert r2.to_dict() == r.to_dict()


def test_a_result_pickles_after_its_node_systems_are_read_by_the_report_and_the_graph():
    m = _load("rssr.yaml")  # an idle freedom: the report reads the node systems to name it
    r = mobility.analyze(m)
    assert "idle" in text_report(r)
    plot_graph(m, r)
    r.node_systems
    again = pickle.loads(pickle.dumps(r))
    deep = copy.deepcopy(r)
    for other in (again, deep):
        assert sorted(other.node_systems.values()) == sorted(r.node_systems.values())
        assert other.node_systems[other.topology.root] == r.node_systems[r.topology.root]
        with pytest.raises(TypeError):
            other.node_systems[other.topology.root] = None  # still read-only


# -- 4. a view or a picture of one mechanism with another's result --------------------


@pytest.fixture(scope="module")
def four_bar_and_other():
    four_bar = _load("four_bar.yaml")
    moved = mobility.sample_poses(four_bar, 1, step=0.2, seed=1)[0]
    return four_bar, mobility.analyze(_load("3prs.yaml")), moved


def test_views_and_pictures_refuse_the_result_of_another_mechanism(four_bar_and_other):
    four_bar, other, _ = four_bar_and_other
    for draw in (lambda: mechanism_view(four_bar, other), lambda: poses_view([(four_bar, other, "x")]),
                 lambda: plot_mechanism(four_bar, other), lambda: plot_graph(four_bar, other)):
        with pytest.raises(RequestError, match=r"the result is of another mechanism \('3-PRS parallel head .*\) than 'planar four-bar'"):
            draw()


def test_views_and_pictures_refuse_the_result_of_another_pose(four_bar_and_other):
    four_bar, _, moved = four_bar_and_other
    with pytest.raises(RequestError, match=r"^frame 0: the result is of another mechanism than 'planar four-bar' \(of the same name, with other joints, pose or fields\)"):
        poses_view([(four_bar, mobility.analyze(moved), "x")])
    with pytest.raises(RequestError, match="of the same name"):
        plot_mechanism(moved, mobility.analyze(four_bar))


def test_views_and_pictures_take_the_result_of_an_equal_mechanism(four_bar_and_other):
    four_bar, _, moved = four_bar_and_other
    again = _load("four_bar.yaml")
    assert again is not four_bar and again == four_bar
    assert mechanism_view(four_bar, mobility.analyze(again)).answer.startswith("end effector 1 DOF")
    assert len(poses_view([(four_bar, mobility.analyze(again), "a"), (moved, mobility.analyze(moved), "b")]).frames) == 2
    plot_mechanism(four_bar, mobility.analyze(again), views=1)
    plot_graph(four_bar, mobility.analyze(again))


def test_the_number_of_views_is_an_integer_in_range():
    m = _load("four_bar.yaml")
    r = mobility.analyze(m)
    assert len(plot_mechanism(m, r, views=np.int64(1)).axes) == 1
    assert len(plot_mechanism(m, r, views=[(30, 40), (np.float64(10), 200)]).axes) == 2
    for bad in (0, -1, 4, 100, np.int64(0), True, [], "ab", [(1,)], [(np.nan, 0)], 2.0):
        with pytest.raises(RequestError, match=r"^plot_mechanism: views: expected a number of views from 1 to 3, or a list of \(elev, azim\) pairs in degrees, got "):
            plot_mechanism(m, r, views=bad)


def test_a_view_is_written_only_to_a_file_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    view = mechanism_view(_load("four_bar.yaml"))
    for bad in (b"x.html", 3, None):
        with pytest.raises(RequestError, match=rf"^write_html: expected a file name \(str or Path\), got {type(bad).__name__}$"):
            view.write_html(bad)
    with pytest.raises(RequestError, match="NUL"):
        view.write_html("a\x00b.html")
    assert list(tmp_path.iterdir()) == []
    assert "<html" in view.write_html("x.html").read_text(encoding="utf-8").lower()


def test_every_result_class_of_the_audit_holds_read_only_arrays():
    from mobility.actuation.results import ActuationCheck, ActuationInput
    from mobility.core.result import LimbSystem, Result
    from mobility.finite.results import Branch, FiniteMobility, Probe, SecondOrder
    from mobility.report.plotting.scene import Scene as PictureScene
    from mobility.report.plotting.sketch import Sketch
    from mobility.sweeps.result import SweepResult
    from mobility.view.geometry import Mesh
    from mobility.view.scene import Glyph, Scene

    for cls in (ScrewAxis, LimbSystem, Result, ActuationInput, ActuationCheck, Probe, Branch, SecondOrder, FiniteMobility,
                SweepResult, Mesh, Glyph, Scene, PictureScene, Sketch):
        assert issubclass(cls, ReadOnlyArrays), cls
        assert inspect.getattr_static(cls, "__setstate__") is ReadOnlyArrays.__setstate__, cls


def test_check_results_pickle_and_compare_as_the_library_page_says():
    from mobility.testing.check import check_file, check_paths

    report = check_paths([str(MECHANISMS / "four_bar.yaml"), str(MECHANISMS / "rssr.yaml")])
    for r in report.results:
        list(_arrays(r.result))
    again = pickle.loads(pickle.dumps(report))
    assert again.to_dict() == report.to_dict() and _writable(again.results[1].result) == []
    a, b = (check_file(str(MECHANISMS / "four_bar.yaml")) for _ in range(2))
    assert a != b and a.result != b.result  # by identity
    assert a.comparisons == b.comparisons and a.result.margin == b.result.margin and a.result.mechanism == b.result.mechanism  # by value


def test_what_a_mechanism_computes_of_itself_is_read_only_and_not_pickled():
    # the joint twists' centre and reference are shared by every later analysis of the mechanism:
    # a write through r.detail.screws would have changed them all
    m = mobility.load(ROOT / "mechanisms" / "3prs.yaml")
    before = mobility.analyze(m).to_dict()
    from mobility.core.joint_screws import joint_screws

    screws = joint_screws(m)
    for array in (screws.normalisation.centre, screws.reference, screws.reference_in_world, *screws.columns):
        with pytest.raises(ValueError, match="read-only"):
            array[...] = 0
    assert type(screws.offsets) is tuple and all(type(o) is int for o in screws.offsets)  # immutable by its kind
    again = pickle.loads(pickle.dumps(m))
    assert again == m and "_mobility_cache" not in vars(again) and "freedom_table" not in vars(again)
    assert not again.freedom_table.axes.flags.writeable  # recomputed read-only, not unpickled writable
    assert mobility.analyze(again).to_dict() == before


# -- 5. the loop-closure route, the Jacobian, flexure spaces and the actuation assessment -----------------


def _new_results():
    """One of each result class that derives from ReadOnlyArrays since the machinery moved to core/frozen, from a real computation."""
    from mobility.actuation import RigidPose
    from mobility.actuation.assessment import assess_wrenches

    rps = _load("actuation_3rps.yaml")
    pose = RigidPose(rps)
    inputs = [pose.input_wrench(i, 0, j.name) for i, j in enumerate(rps.joints) if j.actuated]
    three_rod = mobility.load_flexure(ROOT / "examples" / "flexure" / "three_rod.yaml")
    return {
        "LoopClosure": mobility.loop_closure(_load("3prs.yaml")),
        "LoopClosure-chords": mobility.loop_closure(_load("3prs.yaml"), method="chords"),
        "JacobianResult": mobility.jacobian(_load("metrom.yaml")),
        "FlexureSpaces": mobility.flexure_spaces(three_rod),
        "EndEffectorSpaces": pose.spaces,
        "InputWrench": inputs[0],
        # two of the three legs driven: actuation-singular, one uncontrolled direction
        "Assessment": assess_wrenches([i.wrench for i in inputs[:2]], [i.rate for i in inputs[:2]], pose.spaces.twists, pose.spaces.constraints),
    }


NEW_KINDS = ["LoopClosure", "LoopClosure-chords", "JacobianResult", "FlexureSpaces", "EndEffectorSpaces", "InputWrench", "Assessment"]

_NAMED_ARRAYS = {
    "LoopClosure": lambda r: (r.end_effector_twists, r.end_effector_map, r.joint_rates, r.world_twists, r.jacobian),
    "JacobianResult": lambda r: (r.matrix, r.actuation_wrenches, r.constraint_wrenches, r.platform_twists, r.twist_map, *r.limb_twists,
                                 r.transform, r.finite_screw),
    "FlexureSpaces": lambda r: (r.eigenvalues, r.freedom_translations, r.freedom_twists, r.constraint_couples, r.constraint_wrenches,
                                r.compliance, r.freedom_rotations[0].point, r.constraint_forces[0].axis,
                                r.normalised.twists, r.normalised.constraints, r.normalised.reference),
    "EndEffectorSpaces": lambda r: (r.twists, r.constraints, r.reference),
    "InputWrench": lambda r: (r.wrench,),
    "Assessment": lambda r: (r.uncontrolled,),
}


def _named_arrays(kind: str, r: object) -> tuple[np.ndarray, ...]:
    """The arrays a user reads of a result of ``kind``, computed ones included."""
    return _NAMED_ARRAYS[kind.split("-")[0]](r)


def _coordinates(r: object) -> tuple[np.ndarray, ...]:
    """The arrays of the plain objects a result keeps to write its answers out (joint screws, a normalisation)."""
    if isinstance(r, mobility.LoopClosure):
        s = r.screws
        assert type(s.offsets) is tuple  # immutable by its kind
        return (s.twists, s.reference, *s.columns, s.reference_in_world, s.normalisation.centre)
    spaces = getattr(r, "normalised", r)
    return (spaces.normalisation.centre,) if hasattr(spaces, "normalisation") else ()


def _cannot_be_written(arrays) -> None:
    for array in arrays:
        assert isinstance(array, np.ndarray)
        with pytest.raises(ValueError, match="read-only"):
            array[...] = 0.0


@pytest.fixture(scope="module")
def new_results():
    return _new_results()


@pytest.mark.parametrize("kind", NEW_KINDS)
def test_no_array_of_a_loop_closure_jacobian_flexure_space_or_assessment_can_be_written(new_results, kind):
    r = new_results[kind]
    _cannot_be_written(_named_arrays(kind, r))
    _cannot_be_written(_coordinates(r))
    assert _writable(r) == []
    assert len(list(_arrays(r))) >= len(_named_arrays(kind, r))


@pytest.mark.parametrize("kind", NEW_KINDS)
@pytest.mark.parametrize("restore", [lambda r: pickle.loads(pickle.dumps(r)), copy.deepcopy, copy.copy], ids=["pickle", "deepcopy", "copy"])
def test_a_loop_closure_jacobian_flexure_space_or_assessment_pickles_and_copies_with_read_only_arrays(new_results, kind, restore):
    r = new_results[kind]
    list(_arrays(r))  # every lazy part computed before the round trip
    again = restore(r)
    assert all(np.array_equal(a, b) for a, b in zip(_named_arrays(kind, again), _named_arrays(kind, r), strict=True))
    _cannot_be_written(_named_arrays(kind, again))
    _cannot_be_written(_coordinates(again))
    assert _writable(again) == []
    restored = _coordinates(again)  # new arrays (or, for a shallow copy, the very ones): nothing can write into them
    assert [a.flags.writeable or (isinstance(a.base, np.ndarray) and a.base.flags.writeable) for a in restored] == [False] * len(restored)
    if hasattr(r, "to_dict"):
        assert again.to_dict() == r.to_dict()


def test_a_flexure_spaces_normalisation_is_its_own_read_only_copy():
    three_rod = mobility.load_flexure(ROOT / "examples" / "flexure" / "three_rod.yaml")
    spaces = mobility.flexure_spaces(three_rod)
    mine = three_rod.normalisation()
    assert np.array_equal(spaces.normalised.normalisation.centre, mine.centre) and spaces.normalised.normalisation.length == mine.length
    from mobility.actuation.assessment import EndEffectorSpaces

    given = EndEffectorSpaces(np.eye(6)[:, [3]], np.eye(6)[:, 1:], mine, np.zeros(3))
    mine.centre[0] = 5.0  # the caller's coordinates stay the caller's
    assert given.normalisation.centre[0] != 5.0 and not given.normalisation.centre.flags.writeable and mine.centre.flags.writeable
    assert EndEffectorSpaces(given.twists, given.constraints, given.normalisation, given.reference).normalisation is given.normalisation


def test_the_loop_closure_jacobian_flexure_and_assessment_classes_hold_read_only_arrays():
    from mobility.actuation.assessment import Assessment, EndEffectorSpaces, InputWrench
    from mobility.core.loop_closure import LoopClosure
    from mobility.flexure.spaces import FlexureSpaces
    from mobility.jacobians.jacobian import JacobianResult

    for cls in (LoopClosure, JacobianResult, FlexureSpaces, EndEffectorSpaces, InputWrench, Assessment):
        assert issubclass(cls, ReadOnlyArrays), cls
    for cls in (JacobianResult, FlexureSpaces, InputWrench, Assessment):
        assert inspect.getattr_static(cls, "__setstate__") is ReadOnlyArrays.__setstate__, cls


def _plain_members(obj: object):
    """The fields of a dataclass that is not a ReadOnlyArrays result; nothing of another object."""
    import dataclasses

    if dataclasses.is_dataclass(obj) and not isinstance(obj, (type, ReadOnlyArrays)):
        return [(f.name, getattr(obj, f.name)) for f in dataclasses.fields(obj)]
    return ()


def _arrays_outside_results(obj: object, path: str = "result"):
    """The paths of the ndarrays reachable from ``obj`` through tuples, lists, dicts and dataclasses that are not ReadOnlyArrays results."""
    return [p for p, _ in _walk(obj, path, _plain_members)]


def test_the_results_that_are_not_read_only_arrays_hold_no_array():
    # enumerations (rigid and flexure), synthesis and check results: numbers, names and tuples only, or ReadOnlyArrays results
    from mobility.flexure.actuators import enumerate_force_lines
    from mobility.testing.check import check_paths
    from mobility.testing.flexure_check import flexure_document

    three_rod = mobility.load_flexure(ROOT / "examples" / "flexure" / "three_rod.yaml")
    rps = _load("actuation_3rps.yaml")
    found = {
        "enumerate_actuations": mobility.enumerate_actuations(rps),
        "enumerate_force_lines": enumerate_force_lines(three_rod),
        "synthesize": mobility.synthesize(mobility.named_pattern("2T3R"), joints=3, verify_samples=1),
        "check_paths": check_paths([str(MECHANISMS / "four_bar.yaml"), str(ROOT / "examples" / "flexure" / "three_rod.yaml")], others=[flexure_document]),
    }
    for name, r in found.items():
        assert list(_arrays_outside_results(r)) == [], name
    assert found["check_paths"].results[1].kind == "flexure" and found["check_paths"].results[1].found is not None


def test_the_result_of_the_same_file_read_by_another_path_is_the_result_of_this_mechanism():
    # `source` differs (a relative and an absolute path, or a copy): the mechanism is the same, the view must take its result
    here = mobility.load(ROOT / "mechanisms" / "four_bar.yaml")
    there = mobility.loads((ROOT / "mechanisms" / "four_bar.yaml").read_text(encoding="utf-8"))
    assert here.source != there.source
    view = mobility.mechanism_view(here, mobility.analyze(there))
    assert view.frames[0].result.pattern == "1R"
    with pytest.raises(mobility.RequestError, match="of another mechanism"):
        mobility.mechanism_view(here, mobility.analyze(mobility.load(ROOT / "mechanisms" / "3prs.yaml")))
