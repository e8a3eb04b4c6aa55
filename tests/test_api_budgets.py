"""Arguments of the Python API checked at the entry, names clipped in pictures, and the budget of poses times joints.

* finite screws (``finite_screw``, ``triangle_product``, ``FiniteScrew``),
  ``plot_graph``, ``assemble_pkm`` and ``synthesize``: a bad argument is a
  :class:`~mobility.errors.RequestError` (or :class:`SynthesisError`) of one
  line naming it and what was expected, never a bare numpy or Python error, a
  silent NaN or a search that does not end;
* a name of 200,000 characters is written in a picture cut to
  ``MAX_LABEL`` characters (matplotlib lays out every glyph of a text: drawn
  whole, such a name took a minute);
* ``--samples`` (``actuation``, ``view``) and ``view --vary`` refuse, before
  any work, more poses times joints than ``MOBILITY_MAX_MOVING_WORK``; a
  moderate request runs, and raising the variable lets a larger one run.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import mobility
from builders import four_bar, serial_chain
from mobility.cli import main
from mobility.core.finite_screws import FiniteScrew, Limb, ScrewJoint, finite_screw, transform_from_finite_screw, triangle_product
from mobility.core.model import Joint, Mechanism
from mobility.errors import MechanismError, RequestError, SynthesisError
from mobility.io.writer import mechanism_to_yaml

LONG = 200_000
MAX_LABEL = 40
"""The characters of a name a picture writes (``MAX_LABEL`` of ``mobility/report/plotting/style.py``)."""


# -- finite screws ----------------------------------------------------------------------------------


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
    with pytest.raises(RequestError) as caught:
        call()
    assert message in str(caught.value) and "\n" not in str(caught.value)


def test_a_nan_screw_is_refused_not_composed_into_nan():
    with pytest.raises(RequestError, match=r"^screws\[0\]: expected a 6-vector"):
        triangle_product(np.full(6, np.nan), np.zeros(6))  # was NaN, silently
    with pytest.raises(RequestError, match="overflows double precision"):
        triangle_product([1e200] * 6, [1e200] * 6)  # was a HalfTurnError: the screws are no half-turn
    good = triangle_product([0.2, 0.0, -0.6, 0.3, 1.0, 0.0], [0.1, 0.4, 0.0, 0.0, 0.0, 2.0])
    assert np.all(np.isfinite(good)) and abs(good[2] - (-0.6 + 0.0 + 0.5 * 0.2 * 0.4) / (1 - 0.25 * 0.02)) < 1e-12


def test_a_bad_screw_joint_is_a_mechanism_error_naming_the_key():
    with pytest.raises(MechanismError) as pitch:
        ScrewJoint("H", (0, 0, 1), pitch="x")
    assert pitch.value.key == "pitch" and "expected a finite number" in str(pitch.value)
    with pytest.raises(MechanismError) as point:
        ScrewJoint("R", (0, 0, 1), point=(0, math.nan, 0))
    assert point.value.key == "point"
    assert ScrewJoint("H", (0, 0, 2), pitch=0.5).pitch == 0.5


# -- plot_graph, assemble_pkm, synthesize ----------------------------------------------------------------


def test_plot_graph_with_a_result_that_is_not_one_names_it():
    from mobility.report.plotting import plot_graph

    with pytest.raises(RequestError, match=r"^plot_graph: result: expected a Result \(from mobility.analyze\) or None, got int$"):
        plot_graph(four_bar(), result=5)


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

    with pytest.raises(RequestError) as caught:
        assemble_pkm(three_r, "S", **options)
    assert message in str(caught.value)


def test_assemble_pkm_copies_follow_the_joint_limit(three_r, monkeypatch):
    from mobility.synthesis import assemble_pkm

    monkeypatch.setenv("MOBILITY_MAX_JOINTS", "21")  # 3 one-DOF joints of the limb at most, 3 per UPS copy: 6 copies
    assert len(assemble_pkm(three_r, "S", copies=6).joints) == 1 + 18  # the limb S is one joint
    with pytest.raises(RequestError, match=r"copies: expected an integer from 1 to 6 .*MOBILITY_MAX_JOINTS.*got 7$"):
        assemble_pkm(three_r, "S", copies=7)
    assert len(assemble_pkm(three_r, "S", copies=2, twist_pattern=np.array([1.0, 0.5])).joints) == 1 + 6


@pytest.mark.parametrize("options, message", [
    ({"samples": 10**400}, "synthesize: samples: expected an integer from 1 to 30, got 1000"),
    ({"samples": 31}, "synthesize: samples: expected an integer from 1 to 30, got 31"),
    ({"verify_samples": 10**400}, "synthesize: verify_samples: expected an integer from 0 to 10, got 1000"),
    ({"generic_points": 51}, "synthesize: generic_points: expected an integer from 0 to 50, got 51"),
])
def test_synthesize_bounds_its_counts_before_the_search(options, message):
    from mobility.synthesis import synthesize

    with pytest.raises(SynthesisError) as caught:
        synthesize("3R", **options)
    assert message in str(caught.value)


# -- long names in pictures -------------------------------------------------------------------------------


def long_named() -> Mechanism:
    """The four-bar with a link, a joint and the mechanism named by 200,000 characters each."""
    link, joint = "L" * LONG, "J" * LONG
    z = (0.0, 0.0, 1.0)
    return Mechanism("N" * LONG, "ground", "coupler", (
        Joint(joint, "R", ("ground", link), axis=z, point=(0.0, 0.0, 0.0)),
        Joint("B", "R", (link, "coupler"), axis=z, point=(1.0, 2.0, 0.0)),
        Joint("C", "R", ("coupler", "rocker"), axis=z, point=(4.0, 2.5, 0.0)),
        Joint("D", "R", ("rocker", "ground"), axis=z, point=(5.0, 0.0, 0.0)),
    ))


def drawn_texts(fig) -> list[str]:
    from matplotlib.text import Text

    return [t.get_text() for t in fig.findobj(Text)]


def test_a_long_name_is_clipped_in_the_picture_of_the_mechanism():
    from mobility.report.plotting import plot_mechanism, style

    texts = drawn_texts(plot_mechanism(long_named()))
    clipped_joint = "J" * (MAX_LABEL - 3) + "..."
    assert clipped_joint in texts  # the joint's label, cut
    assert max(len(t) for t in texts) < 200
    title = next(t for t in texts if "end effector 1 DOF" in t)
    assert title.startswith("N" * (MAX_LABEL - 3) + "...: end effector 1 DOF (1R), mobility 1")
    assert style.MAX_LABEL == MAX_LABEL


def test_a_long_name_is_clipped_in_the_joint_graph():
    from mobility.report.plotting import plot_graph

    texts = drawn_texts(plot_graph(long_named()))
    assert max(len(t) for t in texts) < 200
    assert "L" * (MAX_LABEL - 3) + "..." in texts  # the link's box
    assert "J" * (MAX_LABEL - 3) + "... (R)" in texts  # the joint's label on the graph
    assert "J" * (MAX_LABEL - 3) + "...\nR" in texts  # the joint's leaf of the tree
    assert any(t.startswith("N" * (MAX_LABEL - 3) + "...: mobility 1") for t in texts)


def test_a_long_name_is_clipped_in_the_picture_of_a_sweep():
    from mobility.report.sweep_plot import plot_sweep

    m = long_named()
    result = mobility.sweep(m, [f"{'J' * LONG}=0:30:4"])
    texts = drawn_texts(plot_sweep(result))
    assert max(len(t) for t in texts) < 200
    assert "J" * (MAX_LABEL - 3) + "... [deg]" in texts  # the swept coordinate on the axis
    assert "N" * (MAX_LABEL - 3) + "..." in texts  # the title
    assert len(result.axes[0].name) == LONG  # the result keeps the name whole


# -- the budget of poses times joints -------------------------------------------------------------------------


def run(capsys, *args) -> tuple[int, str, str]:
    status = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return status, out, err


@pytest.fixture
def chain_file(tmp_path):
    def write(joints: int):
        path = tmp_path / f"chain{joints}.yaml"
        path.write_text(mechanism_to_yaml(serial_chain(joints)), encoding="utf-8")
        return path
    return write


def test_actuation_samples_beyond_the_budget_are_refused_before_any_work(capsys, chain_file, monkeypatch):
    path = chain_file(100)
    status, out, err = run(capsys, "actuation", path, "--samples", "60")
    assert (status, out) == (2, "") and err.count("\n") == 1
    assert err == (f"mobility: --samples 60: 60 poses x 100 joints of {path} = 6,000 pose-joints, more than the limit of 5,000 "
                   "(ask for fewer poses, or set MOBILITY_MAX_MOVING_WORK to raise it)\n")
    status, out, err = run(capsys, "actuation", path, "--samples", "50")  # 5,000: within the budget
    assert status in (0, 1) and "sampled pose 50" in out, err
    monkeypatch.setenv("MOBILITY_MAX_MOVING_WORK", "6000")
    status, out, err = run(capsys, "actuation", path, "--samples", "60")
    assert status in (0, 1) and "sampled pose 60" in out, err


def test_view_samples_and_vary_beyond_the_budget_are_refused(capsys, chain_file, tmp_path):
    path = chain_file(30)
    page = tmp_path / "v.html"
    status, out, err = run(capsys, "view", path, "--samples", "199", "-o", page)
    assert (status, out) == (2, "") and err.count("\n") == 1
    assert "--samples 199: 199 poses x 30 joints" in err and "= 5,970 pose-joints, more than the limit of 5,000" in err and "MOBILITY_MAX_MOVING_WORK" in err
    status, out, err = run(capsys, "view", path, "--vary", "J1=0:10:1000", "-o", page)  # a view draws 200 of the 1,000 poses
    assert (status, out) == (2, "") and err.count("\n") == 1
    assert "--vary (a grid of 1,000 poses, 200 of them drawn): 200 poses x 30 joints" in err and "= 6,000 pose-joints" in err
    assert not page.exists()
    status, out, err = run(capsys, "view", "mechanisms/four_bar.yaml", "--samples", "3", "-o", page)  # moderate: runs
    assert status == 0 and "4 poses" in out, err
